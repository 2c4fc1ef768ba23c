"""Plausibility of a machine file's numbers: warnings, not errors, where a value is legal but no real machine tool
has it, most often a unit slip (a feed in mm/min under a key in mm/s, a lead in m, a servo period in ms).

:func:`plausibility_warnings` judges the keys of a machine file as read (:func:`vcnc.engine.machine_file
.parse_machine_text` has checked their types and signs); each warning names the file, the key's line, the key, its
value and unit, and why it is implausible. The bounds are wide on purpose: they flag values one or more orders of
magnitude outside what machine tools have, never a fast or a slow but real machine.

Where the bounds come from (orders of magnitude, not a catalogue):

- feed and rapid speeds: the fastest linear-motor machining centres traverse at 120-180 m/min (2-3 m/s); a
  heavy gantry still moves a few m/min, so a top speed under 1 mm/s (0.06 m/min) is a slip too; rotary tables turn
  up to a few thousand rpm (direct-drive turn-mill tables);
- accelerations: linear motors reach 2-5 g, ball screws 0.3-1.5 g; above 10 g or below 1 mm/s^2 is no axis;
- ball-screw leads: 1-50 mm per turn (THK and HIWIN catalogues; miniature screws from 0.5 mm);
- servo periods: 31.25 us to a few ms (Fanuc, Heidenhain, Siemens; LinuxCNC's default SERVO_PERIOD 1 ms); 20 ms and
  more is a PLC task's cycle, not a position loop's;
- reflected inertias and moving masses: 1e-6-1 kg m^2 on the motor shaft, 0.1 kg to tens of tonnes;
- measurement: noise, count size or backlash of 0.1 mm or more is no position loop a machine tool is run with.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping
from typing import Any

from vcnc.core.axes import ROTARY_AXES

__all__ = ["plausibility_warnings"]

#: (table path under [axes.<a>], key) -> (linear bounds, rotary bounds, unit of a linear and of a rotary axis,
#: reason); a bound None is not checked; rotary bounds None: the key is not checked on a rotary axis
_AXIS_BOUNDS: dict[tuple[str, str], tuple[tuple[float | None, float | None], tuple[float | None, float | None] | None,
                                          str, str, str]] = {
    ("limits", "velocity"): ((1.0, 3000.0), (0.1, 40000.0), "mm/s", "deg/s",
                             "machine tools feed at up to 2-3 m/s (180 m/min) and rotary tables turn up to a few "
                             "thousand rpm"),
    ("limits", "rapid"): ((1.0, 3000.0), (0.1, 40000.0), "mm/s", "deg/s",
                          "machine tools traverse at up to 2-3 m/s (180 m/min)"),
    ("limits", "acceleration"): ((1.0, 100000.0), (0.1, 1.0e6), "mm/s^2", "deg/s^2",
                                 "linear motors accelerate at up to 2-5 g, ball screws at 0.3-1.5 g "
                                 "(1 g = 9810 mm/s^2)"),
    ("drive", "lead"): ((0.5, 500.0), None, "mm/rev", "deg/rev", "ball screws have leads of 1-50 mm per turn"),
    ("drive", "inertia"): ((1.0e-6, 1.0), (1.0e-6, 10.0), "kg m^2", "kg m^2",
                           "the inertia reflected on a feed drive's motor shaft is 1e-6 to 1 kg m^2"),
    ("drive", "mass"): ((0.1, 50000.0), (0.1, 50000.0), "kg", "kg", "a moving table or gantry weighs 0.1 kg to tens of "
                                                                    "tonnes"),
    ("noise", "std"): ((None, 0.1), (None, 0.1), "mm", "deg", "position measurement noise is micrometres at most"),
    ("encoder", "resolution"): ((None, 0.1), (None, 0.1), "mm", "deg",
                                "encoders and linear scales count in steps of micrometres or finer"),
    ("backlash", "width"): ((None, 0.1), (None, 0.5), "mm", "deg",
                            "backlash beyond 0.1 mm is a worn-out axis no machine tool is run with"),
}

#: (table, key) -> the reason on a rotary axis, where :data:`_AXIS_BOUNDS`' reason speaks of a linear axis' units
_ROTARY_REASONS: dict[tuple[str, str], str] = {
    ("limits", "velocity"): "rotary tables turn at up to a few thousand rpm (direct-drive turn-mill tables)",
    ("limits", "acceleration"): "even a heavy rotary table accelerates faster than 0.1 deg/s^2",
    ("noise", "std"): "angle encoders resolve arc-seconds (1 arc-second = 0.00028 deg)",
    ("encoder", "resolution"): "angle encoders count in steps of arc-seconds or finer (1 arc-second = 0.00028 deg)",
    ("backlash", "width"): "the lost motion of a worm or gear stage of a rotary table is arc-minutes "
                           "(1 arc-minute = 0.017 deg)",
}

#: sample_time [s]: its plausible range and why
_SAMPLE_TIME = (1.0e-5, 0.02, "position loops close every 31.25 us to a few ms (20 ms and more is a PLC task's cycle)")


def _slip(value: float, unit: str, key: str) -> str:
    """A likely unit slip behind an implausible value, in words ("" when none is likely)."""
    if key in ("velocity", "rapid") and unit == "mm/s":
        if value > 3000.0:
            return f"; in mm/min? {value:g} mm/min is {value / 60.0:g} mm/s"
        return f"; in m/s or m/min? {value:g} m/min is {value * 1000.0 / 60.0:g} mm/s"
    if key == "acceleration" and unit == "mm/s^2" and value < 1.0:
        return f"; in m/s^2? {value:g} m/s^2 is {value * 1000.0:g} mm/s^2"
    if key == "lead" and value < 0.5:
        return f"; in m or cm? {value:g} m is {value * 1000.0:g} mm"
    if unit == "mm" and value >= 0.1:
        return f"; in um? {value:g} um is {value / 1000.0:g} mm"
    return ""


def _outside(value: Any, bounds: tuple[float | None, float | None]) -> bool:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return False  # the reader's own checks judge it
    lo, hi = bounds
    return (lo is not None and value < lo) or (hi is not None and value > hi)


def _axis_warnings(axis: str, tab: Mapping[str, Any], at: Callable[..., str]) -> Iterator[str]:
    rotary = axis in ROTARY_AXES
    for (table, key), (lin, rot, lin_unit, rot_unit, reason) in _AXIS_BOUNDS.items():
        sub = tab.get(table)
        bounds = rot if rotary else lin
        if not isinstance(sub, Mapping) or key not in sub or bounds is None or not _outside(sub[key], bounds):
            continue
        value, unit = float(sub[key]), rot_unit if rotary else lin_unit
        reason = _ROTARY_REASONS.get((table, key), reason) if rotary else reason
        lo, hi = bounds
        side = f"above {hi:g}" if hi is not None and value > hi else f"below {lo:g}"
        yield (f"{at('axes', axis, table, key)}: axes.{axis}.{table}.{key} = {value:g} [{unit}] is {side} {unit}, "
               f"implausible for a real machine: {reason}{_slip(value, unit, key)}")


def plausibility_warnings(data: Mapping[str, Any], *, file: str, line: Callable[..., int | None]) -> list[str]:
    """Warnings on the values of a machine file ``data`` (its TOML tables, already checked as legal) that no
    real machine tool has; each names ``file``, the key's line (``line(*path)``), key, value, unit and the reason.

    Parameters
    ----------
    data : mapping
        The machine file's TOML tables.
    file : str
        The file's name as the user gave it.
    line : callable
        ``line(*path)`` -> the line of a key (:meth:`vcnc.engine.machine_file.LineIndex.line`).

    Returns
    -------
    list of str
        One sentence per implausible value, ``FILE:LINE: KEY = VALUE [UNIT] is ...``; empty for a plausible file.
    """

    def at(*path: str) -> str:
        n = line(*path)
        return f"{file}:{n}" if n is not None else file

    out = []
    ts = data.get("sample_time")
    lo, hi, reason = _SAMPLE_TIME
    if _outside(ts, (lo, hi)):
        side = f"above {hi:g}" if ts > hi else f"below {lo:g}"
        out.append(f"{at('sample_time')}: sample_time = {ts:g} [s] is {side} s, implausible for a servo period: "
                   f"{reason}")
    axes = data.get("axes")
    for a, tab in (axes.items() if isinstance(axes, Mapping) else ()):
        if isinstance(tab, Mapping):
            out.extend(_axis_warnings(a, tab, at))
    return out
