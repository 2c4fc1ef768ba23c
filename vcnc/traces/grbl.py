"""Grbl's real-time status reports, which are no trace: named as such.

A sender polls Grbl with ``?`` and logs each answer, a status report in chevrons: Grbl v1.1
``<Run|MPos:12.000,0.000,-1.000|FS:600,0>``, fields set apart by ``|``; Grbl v0.9 ``<Run,MPos:...,WPos:...>`` by
commas (grbl/grbl ``doc/markdown/interface.md``, "Real-time Status Reports": a report is sent within about 5-20 ms of
the ``?``, and ``report.md``: ``MPos:`` or ``WPos:`` in each, ``WPos = MPos - WCO``). Such a log holds one position
per axis at the sender's polling rate (a GUI polls a few times a second), with no commanded position beside it:
Grbl drives stepper motors open loop, its position is the step count it issued. vcnc names the log and the fields it
holds instead of reading it (a trace of a commanded and a measured position at the servo rate is what identification
needs; our reading: a wrong reading of such data as a trace would be worse than a question).
"""

from __future__ import annotations

import re

__all__ = ["looks_like_status_log", "status_reason"]

#: A status report: the machine state, then its fields (Grbl v1.1 ``|``, v0.9 ``,``).
_REPORT = re.compile(r"<(Idle|Run|Hold(?::\d)?|Jog|Alarm|Door(?::\d)?|Check|Home|Sleep|Queue)([|,][^<>]*)>")
#: The field names of a report (``MPos``, ``WPos``, ``FS``, ``Bf``...).
_FIELD = re.compile(r"[|,]([A-Za-z]+):")


def looks_like_status_log(text: str) -> bool:
    """True when at least 2 of the first non-blank lines (up to 200), and a third of them, hold a status report
    (module docstring), a sender's ``ok`` and G-code lines among them."""
    lines = [s for s in (line.strip() for line in text.splitlines()[:400]) if s][:200]
    n = sum(bool(_REPORT.search(s)) for s in lines)
    return n >= 2 and 3 * n >= len(lines)


def status_reason(text: str) -> str:
    """Why a log of status reports is not read: the reports and the fields they hold (module docstring)."""
    reports = [m for line in text.splitlines() for m in _REPORT.finditer(line)]
    fields = dict.fromkeys(f for m in reports for f in _FIELD.findall(m.group(2)))
    return (f"a log of Grbl's real-time status reports ({len(reports)} reports such as {reports[0].group(0)[:60]!r}, "
            f"fields {list(fields)}): a position polled by the sender at its rate, with no commanded position beside "
            "it (Grbl drives its steppers open loop), not a trace sampled at the servo rate. vcnc identifies a drive "
            "from its control's or drive's own trace of a commanded and a measured position")
