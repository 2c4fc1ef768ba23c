"""What a file beside a trace says of its sampling: a LinuxCNC INI's servo period, for ``halsampler`` output.

``halsampler`` writes one line per sample and no time (halsampler(1)); the sampler component runs in the thread it
is added to (``addf sampler.0 servo-thread`` in the HAL file), whose period the machine's INI states:
``[EMCMOT] SERVO_PERIOD`` in nanoseconds (LinuxCNC docs, "INI Configuration", section [EMCMOT]). A trace without a
time column whose directory holds an INI stating one servo period gets that period named in its error, as the
``--sample-time`` to give if the sampler ran in the servo thread. It is not read on its own: which thread the sampler
ran in, and whether the INI is the one the machine ran with, the files do not say (our reading: a wrong sampling
period would be worse than a question).
"""

from __future__ import annotations

import re
from pathlib import Path

__all__ = ["servo_period_hint"]

_SECTION = re.compile(r"^\s*\[\s*([^\]]+?)\s*\]")
_SERVO_PERIOD = re.compile(r"^\s*SERVO_PERIOD\s*=\s*(\d+(?:\.\d*)?)\s*(?:[#;].*)?$")
#: More INI files than a configuration directory holds: not looked through.
_MAX_FILES = 20


def _servo_periods(ini: Path) -> list[tuple[float, int]]:
    """``(period [s], line)`` of each ``SERVO_PERIOD`` in the ``[EMCMOT]`` section of an INI file."""
    try:
        lines = ini.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return []
    found, section = [], ""
    for i, line in enumerate(lines):
        head = _SECTION.match(line)
        if head:
            section = head.group(1).upper()
            continue
        m = _SERVO_PERIOD.match(line)
        if m and section == "EMCMOT" and float(m.group(1)) > 0:
            found.append((float(m.group(1)) * 1e-9, i + 1))
    return found


def servo_period_hint(src: str) -> str:
    """``"; ..."`` naming the servo period the INI files beside ``src`` state (module docstring), or ``""`` when
    none states one or they disagree."""
    inis = sorted(Path(src).parent.glob("*.ini"))[:_MAX_FILES + 1]
    if not inis or len(inis) > _MAX_FILES:
        return ""
    stated = [(ini, period, line) for ini in inis for period, line in _servo_periods(ini)]
    if not stated or len({period for _, period, _ in stated}) > 1:
        return ""
    ini, period, line = stated[0]
    return (f"; {ini.name} beside it states [EMCMOT] SERVO_PERIOD (line {line}): if the sampler ran in the servo "
            f"thread, give --sample-time {period:.9g}")
