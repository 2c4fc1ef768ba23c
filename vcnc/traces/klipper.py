"""Klipper's ``klippy.log``, which holds no trace: named as such.

Klipper's host process logs, among its messages, a statistics line every second while it prints (``Stats
1234.5: gcodein=0 mcu: mcu_awake=0.003 ... print_time=12.345 buffer_time=1.2 print_stall=0 extruder: target=0
temp=25.0 pwm=0.000``: ``klippy/extras/statistics.py``, ``"Stats %.1f: %s"``), the micro-controllers' timing, buffer
and heater figures, no axis position; and its steppers run open loop, so there is no measured position to record
beside the commanded one (its ``motan`` data logger records the step queues, i.e. the commands). vcnc names the log
instead of reading it (our reading of the log, as :mod:`vcnc.traces.grbl` names a Grbl sender's log).
"""

from __future__ import annotations

import re

__all__ = ["looks_like_klippy_log", "klippy_reason"]

#: A statistics line: ``Stats`` and the reactor's time, then ``key=value`` fields and section names.
_STATS = re.compile(r"^Stats \d+(?:\.\d+)?: (?:\S+=\S+|\S+:)(?: +(?:\S+=\S+|\S+:))*\s*$")


def looks_like_klippy_log(text: str) -> bool:
    """True when at least 2 of the first 400 lines are Klipper statistics lines (module docstring)."""
    return sum(bool(_STATS.match(line.strip())) for line in text.splitlines()[:400]) >= 2


def klippy_reason(text: str) -> str:
    """Why a ``klippy.log`` is not read: its statistics lines and the figures they hold (module docstring)."""
    stats = [line.strip() for line in text.splitlines() if _STATS.match(line.strip())]
    keys = list(dict.fromkeys(k for line in stats for k in re.findall(r"(\w+)=", line)))
    return (f"Klipper's klippy.log ({len(stats)} statistics lines such as {stats[0][:60]!r}, figures {keys[:8]}"
            f"{' ...' if len(keys) > 8 else ''}): the micro-controllers' timing and heaters, no axis positions, and "
            "Klipper drives its steppers open loop (no measured position). vcnc identifies a drive from its "
            "control's or drive's own trace of a commanded and a measured position")
