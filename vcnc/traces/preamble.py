"""What the lines above a delimited trace's table state: its sampling period and the size of one count.

Drive and logger tools write a few lines of settings before the column names: TwinCAT Scope
``SampleTime[ms] 1``, Panasonic's trace "obtaining interval", tuning tools' ``Sampling time: 0.5 ms`` or
``Sampling cycle = 250 us``, German ones ``Abtastzeit: 1 ms``; and with positions in increments
``Resolution: 0.1 um`` or ``Encoder resolution = 10000 inc/mm``. A file whose table has no time column,
or counts samples (``Sample #``), is timed by the period so stated, and positions logged in counts are
scaled by the stated size of one count, each named in the capture's ``meta``.

Our reading, no standard: a line whose words before the value are a sampling word (``sampling``,
``sample``, ``trace``, ``recording``; German ``Abtast-``, ``Aufzeichnungs-``) with ``time``/``period``/
``interval``/``cycle``/``clock``/``rate`` (``-zeit``, ``-takt``...: ``Abtastzeit``; SINAMICS' trace states its
"Trace cycle" in ms, a multiple of the device cycle, CPU 317T Technology Functions manual, section 8), then a
number with a time unit (``s``, ``ms``, ``us``, ``µs``) or a rate (``Hz``, ``kHz``),
the unit also in brackets after the key (``Sample time [ms]: 0.5``). A resolution line is ``resolution``,
``Auflösung`` or ``count size`` / ``increment size``, then a length per count (``0.1 um``, ``0.0001 mm/inc``)
or counts per length (``10000 inc/mm``). A value without a unit, or two lines that disagree, state nothing.

vcnc addition (tracewild4): a screw's lead (``Screw lead: 5 mm``, ``Lead = 0.2 in/rev``, German ``Spindelsteigung``,
a length or a length per turn) and a gear ratio (``Gear ratio: 3``, ``3:1``, ``Übersetzung``: motor turns per screw
turn) state the travel of one motor turn, which scales a linear axis' positions logged in turns, radians or degrees
(:func:`stated_turn_travel`).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from vcnc.traces.columns import ANGLE_UNITS, COUNT_UNITS, LENGTH_UNITS, TIME_UNITS, unit_named

__all__ = ["Stated", "stated_period", "stated_count_size", "stated_turn_travel"]

_NUM = r"([+-]?(?:\d+[.,]?\d*|[.,]\d+)(?:[eE][+-]?\d+)?)"
_KEY_UNIT = r"(?:\s*[\[(]\s*([^\[\]()]+?)\s*[\])])?"
_SEP = r"\s*[:=;,\t]?\s*"
_PERIOD = re.compile(r"^\s*[#%;]?\s*(?:(?:sampl(?:e|ing)|trace|record(?:ing)?)[\s_-]*(?:time|period|interval|cycle|"
                     r"clock|rate)|(?:abtast|aufzeichnungs)[\s_-]*(?:zeit|rate|intervall|periode|zyklus|takt)|"
                     r"trace[\s_-]*takt)" + _KEY_UNIT + _SEP + _NUM + _SEP + r"([^\s\d;,]*)\s*[;,\t]*\s*$",
                     re.IGNORECASE)
_RESOLUTION = re.compile(r"^\s*[#%;]?\s*(?:(?:encoder|position|measuring system|geber)?[\s_-]*(?:resolution|aufl"
                         r"\u00f6sung)|(?:count|increment)[\s_-]*size)" + _KEY_UNIT + _SEP + _NUM +
                         _SEP + r"([^\s;,]*)\s*[;,\t]*\s*$", re.IGNORECASE)
_LEAD = re.compile(r"^\s*[#%;]?\s*(?:(?:ball[\s_-]*)?screw[\s_-]*(?:lead|pitch)|lead|(?:spindel|gewinde)?steigung)"
                   + _KEY_UNIT + _SEP + _NUM + _SEP + r"([^\s;,]*)\s*[;,\t]*\s*$", re.IGNORECASE)
_GEAR = re.compile(r"^\s*[#%;]?\s*(?:(?:gear(?:box)?|transmission|reduction)[\s_-]*ratio|(?:getriebe)?"
                   r"\u00fcbersetzung)" + _SEP + _NUM + r"(?:\s*:\s*" + _NUM + r")?\s*[;,\t]*\s*$", re.IGNORECASE)
#: Units after a lead's value: a length, or a length per turn.
_PER_TURN = ("", "rev", "turn", "u", "r", "rot", "revolution")
_RATES = {"hz": 1.0, "khz": 1e3}
#: Units a stated resolution may be in: lengths and degrees; counts per turn or radian of a motor state nothing of
#: the axis' travel (a linear axis needs its lead), our reading.
_SIZES = frozenset(LENGTH_UNITS) - ANGLE_UNITS | {"deg"}


@dataclass(frozen=True, kw_only=True)
class Stated:
    """A value the preamble states: ``value`` (a period [s], or a count size as ``--unit`` takes it,
    ``"0.0001mm"``), the 1-based file ``line`` and its ``text``."""

    value: float | str
    line: int
    text: str


def _number(text: str) -> float:
    return float(text.replace(",", "."))


def _period(m: re.Match[str]) -> float | None:
    """Seconds of a matched sampling line, or None when its unit is not a time or a rate."""
    unit = (m.group(3) or m.group(1) or "").strip().lower().replace("\u03bc", "\u00b5")
    value = _number(m.group(2))
    if not value > 0:
        return None
    if unit in _RATES:
        return 1.0 / (value * _RATES[unit])
    name = unit_named(unit, "time")
    return value * TIME_UNITS[name] if name is not None else None


def _count_size(m: re.Match[str]) -> str | None:
    """A matched resolution line as a ``--unit`` count size (``"0.0001mm"``), or None."""
    unit = (m.group(3) or m.group(1) or "").strip().lower().replace("\u03bc", "\u00b5")
    value = _number(m.group(2))
    top, _, bottom = unit.partition("/")
    if not value > 0:
        return None
    if bottom and top in COUNT_UNITS:  # counts per length: 10000 inc/mm
        base = unit_named(bottom, "length")
        return f"{LENGTH_UNITS[base] / value:.12g}{'deg' if base == 'deg' else 'mm'}" if base in _SIZES else None
    if bottom and bottom not in COUNT_UNITS:
        return None
    base = unit_named(top, "length")
    return f"{value:.12g}{base}" if base in _SIZES else None


def _stated(lines: Sequence[str], pattern: re.Pattern[str],
            read: Callable[[re.Match[str]], float | str | None]) -> Stated | None:
    found = []
    for i, line in enumerate(lines):
        m = pattern.match(line.replace('"', ""))  # '"Sampling Time","125.0us"': quoted cells
        value = read(m) if m else None
        if value is not None:
            found.append(Stated(value=value, line=i + 1, text=line.strip()))
    if not found or any(f.value != found[0].value for f in found):
        return None
    return found[0]


def stated_period(lines: Sequence[str]) -> Stated | None:
    """The sampling period [s] the lines above a table state (module docstring), or None."""
    return _stated(lines, _PERIOD, _period)


def _lead(m: re.Match[str]) -> float | None:
    """Millimetres per turn of a matched lead line (``Screw lead: 5 mm``, ``Spindelsteigung [mm/U] 10``), or None."""
    top, _, per = (m.group(3) or m.group(1) or "").strip().lower().replace("\u03bc", "\u00b5").partition("/")
    base = unit_named(top, "length")
    value = _number(m.group(2))
    if base is None or base in ANGLE_UNITS or per not in _PER_TURN or not value > 0:
        return None
    return value * LENGTH_UNITS[base]


def _gear(m: re.Match[str]) -> float | None:
    """Motor turns per screw turn of a matched gear ratio line (``Gear ratio: 3``, ``3:1``), or None."""
    a, b = _number(m.group(1)), _number(m.group(2)) if m.group(2) else 1.0
    return a / b if a > 0 and b > 0 else None


def stated_turn_travel(lines: Sequence[str]) -> tuple[float, str] | None:
    """The travel [mm] of one motor turn and what states it, from a screw's lead above a table (``Screw lead: 5 mm``,
    ``Spindelsteigung: 10 mm/U``) divided by a gear ratio when one is stated too (motor turns per screw turn:
    ``Gear ratio: 3``, ``3:1``); None without a lead. Our reading of loggers that record a motor's turns: the turns
    are the motor's, the ratio the gear's i = n_motor / n_screw (DIN 868); a ratio below 1 (a step-up gear, rare
    on a feed drive, or the ratio written the other way round) is kept and named as such in the note."""
    lead = _stated(lines, _LEAD, _lead)
    if lead is None:
        return None
    gear = _stated(lines, _GEAR, _gear)
    if gear is None and any(_GEAR.match(line.replace('"', "")) for line in lines):
        return None  # a gear ratio stated unreadably (3:0) or twice differently: the lead alone would be a guess
    ratio = float(gear.value) if gear is not None else 1.0
    said = f"lead stated in line {lead.line} ({lead.text!r})" + (
        f", gear ratio in line {gear.line} ({gear.text!r})" if gear is not None else "") + (
        "; a ratio below 1 (the motor slower than the screw) is read as motor turns per screw turn all the same: if "
        "the file means screw turns per motor turn, give --unit with the travel of one turn" if ratio < 1 else "")
    return float(lead.value) / ratio, said


def stated_count_size(lines: Sequence[str]) -> Stated | None:
    """The size of one position count the lines above a table state, as ``--unit`` takes it, or None."""
    return _stated(lines, _RESOLUTION, _count_size)
