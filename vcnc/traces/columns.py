"""What the text trace readers share: decoding, numbers, the column mapping, units and timing.

- **Text.** :func:`vcnc.core.text.decode_text`: a BOM picks UTF-8 or UTF-16 (Windows tools write
  both); without one the text is UTF-8, else Windows-1252 (TNCscope and TwinCAT on a German
  Windows). A file with NUL bytes and neither a UTF-16 BOM nor UTF-16's pattern is binary and refused.
- **Numbers.** Decimal numbers only (``1``, ``-2.5``, ``1e-3``): ``nan``, ``inf``, ``1_000`` and
  values that overflow a float are refused, naming the line and the column.
- **Timing.** A capture's time must increase with a uniform step: :func:`check_timing` tells
  dropped samples (a step that is a multiple of the usual one) from jitter and names the line.
  On request (``resample``, ``--resample``) :func:`on_uniform_grid` interpolates linearly onto
  the median step instead, and says so in the capture's ``meta``.
"""

from __future__ import annotations

import datetime
import io
import math
import re
import zipfile
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES, ROTARY_AXES
from vcnc.core.capture import UNIT_GIVEN, check_sampling
from vcnc.core.errors import CaptureError
from vcnc.core.text import ZIP_SIGNATURE, BinaryDataError, decode_text
from vcnc.traces.diadem import header_naming
from vcnc.traces.lag import subtract_following_error

__all__ = ["TIME_UNITS", "LENGTH_UNITS", "read_text", "parse_number", "parse_columns", "check_units",
           "mapped_axes", "position_scale", "mapping_meta", "check_timing", "on_uniform_grid", "MAX_SAMPLES",
           "unit_in_name", "unit_named", "length_unit", "parse_time_stamp", "is_unit_row", "LAG_SUFFIX", "axis_of",
           "IPOC", "with_following_errors", "COUNT_UNITS", "ANGLE_UNITS", "REACH", "within_reach"]

#: Seconds per time unit.
TIME_UNITS: dict[str, float] = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
#: Millimetres (or degrees, for the units of :data:`ANGLE_UNITS`) per position unit.
LENGTH_UNITS: dict[str, float] = {"mm": 1.0, "um": 1e-3, "nm": 1e-6, "m": 1000.0, "in": 25.4, "deg": 1.0,
                                  "rad": math.degrees(1.0), "rev": 360.0}
#: Units of rotary positions (axes a, b, c): degrees, radians and turns (revolutions). Drives and their tools
#: log a motor's position in turns (ODrive firmware 0.5 CHANGELOG: "input_pos, input_vel, pos_estimate_linear ... are
#: now in units of [turns]"; ``odrive-interface.yaml``: ``unit: turn``) or radians (SimpleFOC, "Units in the
#: library": positions in radians; ROS joint states, REP 103).
ANGLE_UNITS = frozenset({"deg", "rad", "rev"})

#: Most samples a resampled capture may have (a stray time stamp must not allocate without bound).
MAX_SAMPLES = 100_000_000

#: Unit names as headers and channel rows write them, to vcnc's unit names.
_TIME_NAMES = {"s": "s", "sec": "s", "ms": "ms", "msec": "ms", "us": "us", "µs": "us", "ns": "ns"}
_LENGTH_NAMES = {"mm": "mm", "um": "um", "µm": "um", "nm": "nm", "m": "m", "in": "in", "inch": "in", "deg": "deg",
                 "°": "deg", "rad": "rad", "rev": "rev", "revs": "rev", "turn": "rev", "turns": "rev",
                 "revolution": "rev", "revolutions": "rev"}
#: Unit symbols of positions logged in increments whose size the symbol does not say (lower case): encoder
#: increments and counts, pulses (Mitsubishi's droop pulses, Panasonic's command pulses), Delta's PUU ("pulse of
#: user unit", ASDA-A2 manual section 6.2) and the LU of SINAMICS EPOS ("length unit", the neutral unit its
#: position setpoints and actual values are traced in), Yaskawa's "reference unit" (the unit of position
#: references after the electronic gear), a "user unit", B&R ACOPOS' ``Units`` (the axis' user units, its encoder
#: scaling setting how many make a motor revolution: B&R's ``acp10par.h`` gives ``PCTRL_S_SET`` "Set position
#: [Units]", ``PCTRL_S_ACT`` "Actual position [Units]", ``PCTRL_LAG_ERROR`` "Lag error [Units]") and maxon's ``qc``
#: (quadcounts: four per encoder line, the position unit of EPOS Studio's data recorder, our reading of its exports'
#: units row). Their size is given with ``--unit`` (``0.1um``).
COUNT_UNITS = frozenset({"inc", "incr", "increment", "increments", "count", "counts", "cnt", "cnts", "pulse",
                         "pulses", "pls", "puu", "lu", "reference unit", "reference units", "user unit", "user units",
                         "units", "qc"})
#: A position unit given as the size of one count (``0.1um``, ``0.0001in``, ``0.001deg``): drives and
#: controls that log positions in increments of their measuring system (Mitsubishi's sampling output in
#: units A-E = 10 um ... 0.001 um, encoder counts of a drive's scope).
_COUNT_UNIT = re.compile(r"\s*((?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([^\d\s.][^\s]*)\s*")
_UNIT = re.compile(r"[\[(]\s*([^\[\]()]+?)\s*[\])]\s*$")
#: A unit after the name without brackets: ``Zeit in ms``, ``Zeit/ms`` (DIN 1313's quantity/unit), ``time_ms``,
#: ``rel_time_s`` (loggers written in code); "in" after "/" is inch (DIN 1313's quantity/unit: ``ActPos/in``), never
#: after "_" (an input).
_SUFFIX_UNIT = re.compile(r"(?:\s+in\s+|\s*/\s*|_)([^\s/_\d\[\]()][^\s/_\[\]()]*)\s*$", re.IGNORECASE)
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")

#: Suffix of a mapping's following-error column (``x_lag``): commanded - actual position, the
#: measured position being formed as ``x_ref - x_lag`` (:mod:`vcnc.traces.lag`).
LAG_SUFFIX = "_lag"


def read_text(path: str | Path, src: str) -> str:
    """The text of a trace file (module docstring); CaptureError for a binary file, naming the DIAdem header beside
    it when one names the file as its channels' data (:func:`vcnc.traces.diadem.header_naming`)."""
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise CaptureError(f"cannot read the file ({exc.strerror})", file=src) from None
    try:
        return decode(raw, src)
    except CaptureError:
        header = header_naming(Path(path)) if not raw.startswith(ZIP_SIGNATURE) else None
        if header is None:
            raise
        raise CaptureError(f"the binary data of the DIAdem header {header.name!r} beside it, which names its channels "
                           "(KUKA.Trace writes a .dat beside each .r64)", file=src,
                           expected=f"the header: vcnc convert {header.name!r}") from None


def decode(raw: bytes, src: str) -> str:
    """``raw`` as text (:func:`vcnc.core.text.decode_text`); CaptureError for binary data, naming a ZIP archive's
    members (:func:`_archive_reason`)."""
    reason = _archive_reason(raw)
    if reason is not None:
        raise CaptureError(reason, file=src, expected="a text trace export")
    try:
        return decode_text(raw)
    except BinaryDataError as exc:
        raise CaptureError(str(exc), file=src, line=exc.line, column=exc.column,
                           expected="a text trace export") from None


def _archive_reason(raw: bytes) -> str | None:
    """What a ZIP archive holds, for ``raw`` that starts with a ZIP local file header, else None: NumPy's ``savez``
    writes arrays as ``NAME.npy`` members (a recording saved from Python, as anderssandstrom/ecmc_autotune's
    ``veltest_*.npz`` of t, cmd, vel, pos, torque), which vcnc reads once saved as delimited text; an Excel workbook
    (``xl/workbook.xml``, ECMA-376) is saved as CSV."""
    if not raw.startswith(ZIP_SIGNATURE):
        return None
    try:
        with zipfile.ZipFile(io.BytesIO(raw)) as z:
            names = z.namelist()
    except (zipfile.BadZipFile, OSError):
        return "a damaged ZIP archive"
    if names and all(n.endswith(".npy") for n in names):
        arrays = [n[:-4] for n in names]
        return (f"a NumPy archive (.npz) of the arrays {arrays}: save the time, commanded and measured position as "
                "delimited text with their names in a header line (numpy.savetxt(..., delimiter=',', header=...,"
                " comments='')), which vcnc reads")
    if "xl/workbook.xml" in names:  # Office Open XML (ECMA-376): a workbook's part
        return "an Excel workbook (.xlsx): save the sheet that holds the trace as CSV, which vcnc reads"
    return f"a ZIP archive of {names[:8]}: give vcnc the trace export inside it"


def parse_number(cell: str, decimal_comma: bool = False) -> float:
    """A cell as a finite number; NaN when empty; ValueError when not a decimal number."""
    s = cell.strip()
    if not s:
        return math.nan
    if decimal_comma:
        s = s.replace(",", ".")
    if not _NUMBER.fullmatch(s):
        raise ValueError(s)
    v = float(s)
    if not math.isfinite(v):
        raise ValueError(s)
    return v


#: KUKA.RobotSensorInterface's interpolation-cycle time stamp, a column of milliseconds (names.py's docstring).
IPOC = "ipoc"


def unit_in_name(name: str, kind: str) -> str | None:
    """The unit a column name ends with, ``[ms]`` or ``(µm)`` (or, without brackets, ``Zeit in ms``,
    ``Zeit/ms``, ``time_ms``): a key of :data:`TIME_UNITS`
    (``kind="time"``) or :data:`LENGTH_UNITS` (``kind="length"``), or for a length the size of one count
    as :func:`length_unit` reads it (``motor_pos [0.1 deg]`` -> ``"0.1deg"``, Mitsubishi's ``B(1μm)``), else None.
    KUKA RSI's ``IPOC`` (:data:`IPOC`) is a time in ms."""
    if kind == "time" and name.strip().lower() == IPOC:
        return "ms"
    m = _UNIT.search(name)
    if not m:
        suffix = _SUFFIX_UNIT.search(name)
        if suffix and not (suffix.group(1).lower() == "in" and suffix.group(0).strip()[0] == "_"):
            return unit_named(suffix.group(1), kind)
        return None
    named = unit_named(m.group(1), kind)
    if named is None and kind == "length" and length_unit(m.group(1)) is not None:
        return m.group(1).replace(" ", "").replace("\u03bc", "\u00b5")
    return named


def unit_named(text: str, kind: str) -> str | None:
    """A unit symbol (``ms``, ``µm``, ``°``...) as a key of :data:`TIME_UNITS` (``kind="time"``)
    or :data:`LENGTH_UNITS` (``kind="length"``), else None."""
    names = _TIME_NAMES if kind == "time" else _LENGTH_NAMES
    return names.get(text.strip().lower().replace("μ", "µ"))


_DATE_TIME = re.compile(r"(\d{4})[-/.](\d{1,2})[-/.](\d{1,2})[ T](\d{1,2}):(\d{2}):(\d{2})(?:[.,](\d{1,9}))?Z?")
_DE_DATE_TIME = re.compile(r"(\d{1,2})\.(\d{1,2})\.(\d{4}) (\d{1,2}):(\d{2}):(\d{2})(?:[.,](\d{1,9}))?")
_TIME_OF_DAY = re.compile(r"(\d{1,2}):(\d{2}):(\d{2})(?:[.,](\d{1,9}))?")


def parse_time_stamp(cell: str) -> float:
    """A logger's time stamp as seconds: ``2024-05-02 15:56:24.376`` (``T``, ``/`` and a trailing
    ``Z`` accepted) or ``02.05.2024 15:56:24,376`` as seconds since 1970 (time zone ignored: only
    differences are used), ``15:56:24.376`` as seconds since midnight. ValueError otherwise."""
    s = cell.strip()
    m = _DATE_TIME.fullmatch(s)
    if m:
        y, mo, d, h, mi, sec, frac = m.groups()
    else:
        m = _DE_DATE_TIME.fullmatch(s)
        if m:
            d, mo, y, h, mi, sec, frac = m.groups()
        else:
            m = _TIME_OF_DAY.fullmatch(s)
            if not m:
                raise ValueError(s)
            h, mi, sec, frac = m.groups()
            y = mo = d = None
    day = 0.0
    if y is not None:
        try:
            day = (datetime.date(int(y), int(mo), int(d)) - datetime.date(1970, 1, 1)).days * 86400.0
        except ValueError:
            raise ValueError(s) from None
    if int(h) > 23 or int(mi) > 59 or int(sec) > 60:
        raise ValueError(s)
    return day + int(h) * 3600 + int(mi) * 60 + int(sec) + (float("0." + frac) if frac else 0.0)


#: Further unit symbols a units row holds (velocities, currents, ...), lower case.
_OTHER_UNITS = {"v", "a", "ma", "nm", "n", "rpm", "1/min", "mm/min", "m/min", "mm/s", "m/s", "mm/s^2", "m/s^2",
                "deg/s", "\u00b0/s", "rad", "rad/s", "%", "-", "hz", "bar", "\u00b0c", "r/min", "min-1", "min^-1",
                "rev/min", "1/s", "inc/s", "n\u00b7m", "kw", "w"} | COUNT_UNITS


def is_unit_row(cells: Sequence[str]) -> bool:
    """True for a row of unit symbols (``s;mm;mm``, ``[ms],[\u00b5m]``) under a header of names."""
    tokens = [c.strip().strip("[]()").strip().lower().replace("\u03bc", "\u00b5") for c in cells if c.strip()]
    return bool(tokens) and all(t in _TIME_NAMES or t in _LENGTH_NAMES or t in _OTHER_UNITS for t in tokens)


def parse_columns(text: str) -> dict[str, str]:
    """``"t=Time,x_ref=PosCmd,x=PosAct"`` as a mapping capture column -> source column
    (``x_lag=Lag``: a following error in the place of ``x``, :func:`mapped_axes`).

    Raises
    ------
    CaptureError
        A part without ``=``, or a capture column that is not ``t``, ``<axis>_ref``, ``<axis>``
        or ``<axis>_lag``.
    """
    out: dict[str, str] = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        key, eq, value = part.partition("=")
        key, value = key.strip(), value.strip()
        if not eq or not value or not (key == "t" or axis_of(key) in AXIS_NAMES):
            raise CaptureError(f"--columns part {part!r}: expected 't=NAME', '<axis>_ref=NAME', '<axis>=NAME' or "
                               f"'<axis>{LAG_SUFFIX}=NAME' (a following error) (axes {' '.join(AXIS_NAMES)})")
        out[key] = value
    return out


def axis_of(key: str) -> str:
    """The axis of a capture column: ``x`` of ``x_ref``, ``x_lag`` and ``x``."""
    for suffix in ("_ref", LAG_SUFFIX):
        if key.endswith(suffix):
            return key[: -len(suffix)]
    return key


def length_unit(unit: str) -> tuple[str, float] | None:
    """A position unit as (its base unit, a key of :data:`LENGTH_UNITS`; millimetres or degrees per unit):
    a unit name (``um``, ``µm``, ``inch``) or the size of one count (``0.1um``, ``5e-4mm``); None for
    anything else (a count size that is not finite and > 0 included)."""
    base = unit_named(unit, "length")
    if base is not None:
        return base, LENGTH_UNITS[base]
    m = _COUNT_UNIT.fullmatch(unit)
    base = unit_named(m.group(2), "length") if m else None
    if base is None:
        return None
    size = float(m.group(1))
    return (base, size * LENGTH_UNITS[base]) if math.isfinite(size) and size > 0 else None


def check_units(time_unit: str | None, unit: str | None, src: str) -> None:
    """CaptureError unless the time unit is one of :data:`TIME_UNITS` and the position unit one of
    :data:`LENGTH_UNITS` or the size of one count (:func:`length_unit`)."""
    if time_unit is not None and time_unit not in TIME_UNITS:
        raise CaptureError(f"time unit {time_unit!r}: expected one of {', '.join(TIME_UNITS)}", file=src)
    if unit is not None and length_unit(unit) is None:
        raise _unknown_length_unit(unit, src)


def _unknown_length_unit(unit: str, src: str) -> CaptureError:
    return CaptureError(f"position unit {unit!r}: expected one of {', '.join(LENGTH_UNITS)}, or the size of one count "
                        "of positions logged in increments (e.g. 0.1um, 0.0001in, 0.001deg)", file=src)


def mapped_axes(columns: Mapping[str, str], src: str) -> list[str]:
    """The axes of a column mapping, each with its ``<axis>_ref`` and either ``<axis>`` (the
    measured position) or ``<axis>_lag`` (the following error, commanded - actual), in the order
    the mapping names those."""
    axes = list(dict.fromkeys(axis_of(k) for k in columns if not k.endswith("_ref") and axis_of(k) in AXIS_NAMES))
    both = [a for a in axes if a in columns and a + LAG_SUFFIX in columns]
    if both:
        raise CaptureError(f"--columns gives both {both[0]}= (the measured position) and {both[0]}{LAG_SUFFIX}= (the "
                           "following error) for one axis: give one", file=src)
    missing = [a for a in axes if f"{a}_ref" not in columns] + [k[:-4] for k in columns
                                                                if k.endswith("_ref") and k[:-4] not in axes]
    if not axes or missing:
        raise CaptureError(f"--columns needs '<axis>_ref=...' and '<axis>=...' (or '<axis>{LAG_SUFFIX}=...', the "
                           f"following error) for each axis (incomplete: {sorted(set(missing)) or 'no axis given'})",
                           file=src)
    return axes


def assumed_unit(key: str) -> str:
    """The unit a position column ``key`` (``x_ref``, ``a``, ...) is read in when neither the file nor the
    options state one: deg on a rotary axis, else mm (:func:`position_scale`'s scale 1)."""
    return "deg" if axis_of(key) in ROTARY_AXES else "mm"


def position_scale(axes: Sequence[str], unit: str | None, src: str) -> float:
    """Millimetres (degrees) per unit of the positions of ``axes`` (a unit of :func:`length_unit`);
    the units of :data:`ANGLE_UNITS` only for rotary axes. A linear axis logged in turns, radians or degrees of its
    motor takes the travel of one turn (radian, degree) as its unit (``--unit 5mm``: a screw of 5 mm lead), our
    reading of what the file cannot say."""
    u = unit or "mm"
    found = length_unit(u)
    if found is None:
        raise _unknown_length_unit(u, src)
    base, scale = found
    linear = [a for a in axes if a not in ROTARY_AXES]
    if base in ANGLE_UNITS and linear:
        lead = {"rev": "; a linear axis logged in turns of its motor takes the travel of one turn as its unit "
                       "(--unit 5mm for a screw of 5 mm lead)",
                "rad": "; a linear axis logged in radians of its motor takes the travel of one radian as its unit "
                       "(the lead over 2 pi: --unit 0.7958mm for a screw of 5 mm lead)",
                "deg": "; a linear axis logged in degrees of its motor takes the travel of one degree as its unit "
                       "(the lead over 360: --unit 0.013889mm for a screw of 5 mm lead)"}.get(base, "")
        raise CaptureError(f"unit {u!r} is for rotary axes (a, b, c: --columns a_ref=..,a=..); axes {linear} are "
                           f"linear{lead}", file=src)
    if base not in ANGLE_UNITS and len(linear) < len(axes) and unit is not None:
        raise CaptureError(f"unit {u!r} given for rotary axes {[a for a in axes if a in ROTARY_AXES]}; "
                           "rotary positions are in deg, rad or rev", file=src)
    return scale


def unit_stated(units: Mapping[str, str | None], how: str) -> dict[str, str]:
    """``{UNIT_GIVEN: ...}`` (:data:`vcnc.core.capture.UNIT_GIVEN`) when every position column of ``units``
    (capture column -> unit, None where assumed; ``t`` aside) has its unit stated, ``how`` saying where (``"stated
    in the header"``); else ``{}``. The one rule every reader's stated units go through."""
    positions = {k: u for k, u in units.items() if k != "t"}
    if not positions or any(u is None for u in positions.values()):
        return {}
    return {UNIT_GIVEN: f"{how}: " + ", ".join(f"{k} in {u}" for k, u in positions.items())}


def mapping_meta(axes: Sequence[str], columns: Mapping[str, str]) -> dict[str, str]:
    """``commanded`` and ``measured`` entries of a capture's ``meta``: which channel is which (a
    measured position formed from a following error as ``x:COMMANDED - LAG``)."""
    def measured(a: str) -> str:
        return columns[a] if a in columns else f"{columns[a + '_ref']} - {columns[a + LAG_SUFFIX]}"

    return {"commanded": ",".join(f"{a}:{columns[a + '_ref']}" for a in axes),
            "measured": ",".join(f"{a}:{measured(a)}" for a in axes)}


def with_following_errors(axes: Sequence[str], columns: Mapping[str, str], reference: np.ndarray,
                          second: np.ndarray, sample_time: float, src: str, *, expected: str,
                          line: int | Mapping[str, int] | None = None) -> tuple[np.ndarray, dict[str, str]]:
    """The measured positions (samples x axes) of a mapping whose ``second`` column of each axis is
    its measured position (``<axis>``) or its following error (``<axis>_lag``): the latter
    subtracted from the commanded position after its sign is checked (:mod:`vcnc.traces.lag`,
    ``expected`` the convention and its source, ``line`` the file line its messages name, or one per
    axis); and the ``meta["following_error"]`` entry, if any."""
    measured = np.array(second, dtype=float, copy=True)
    found = []
    for j, a in enumerate(axes):
        if a in columns:
            continue
        channel = columns[a + LAG_SUFFIX]
        at = line.get(a) if isinstance(line, Mapping) else line
        measured[:, j], how = subtract_following_error(reference[:, j], second[:, j], sample_time, channel=channel,
                                                       src=src, line=at, expected=expected)
        found.append(f"{a}:{channel} ({how})")
    if not found:
        return measured, {}
    return measured, {"following_error": f"{'; '.join(found)}; measured = commanded - following error, "
                                         f"the following error read as {expected}"}


def check_timing(t: np.ndarray, src: str, row_lines: Sequence[int] | None = None) -> None:
    """CaptureError unless ``t`` [s] increases with a uniform step, saying whether samples were
    dropped (a step that is a whole multiple of the usual one) or the time stamps jitter."""
    if t.size < 2:
        raise CaptureError(f"only {t.size} sample(s); a capture needs at least 2", file=src)
    try:
        check_sampling(t, src, list(row_lines) if row_lines is not None else None)
    except CaptureError as exc:
        dt = np.diff(t)
        ts = float(np.median(dt))
        if not ts > 0:
            raise
        ratio = dt / ts
        gaps = np.flatnonzero((ratio > 1.5) & (np.abs(ratio - np.round(ratio)) < 0.01))
        if gaps.size:
            k = int(gaps[0])
            lost = int(np.sum(np.round(ratio[gaps]) - 1))
            raise CaptureError(f"{lost} sample(s) missing in {gaps.size} gap(s), the first {float(dt[k]):.9g} s "
                               f"long after t = {float(t[k]):.9g} s; the sample time is {ts:.9g} s. "
                               "vcnc needs uniform sampling: trace without drop-outs, cut the capture, or give "
                               "--resample (resample=True) to interpolate across the gaps",
                               file=src, line=row_lines[k + 1] if row_lines is not None else None) from None
        jitter = float(np.max(np.abs(dt - ts)))
        raise CaptureError(f"{exc.message}; the time stamps jitter by up to {jitter:.3g} s ({jitter / ts:.1%} of the "
                           "step): vcnc needs the control's own sampled time, not a logging PC's clock; --resample "
                           "(resample=True) interpolates onto the median step",
                           file=src, line=exc.line, column=exc.column) from None


def on_uniform_grid(t: np.ndarray, values: Sequence[np.ndarray], src: str, row_lines: Sequence[int] | None = None,
                    *, resample: bool = False) -> tuple[np.ndarray, list[np.ndarray], dict[str, str]]:
    """Time [s] from 0 and ``values`` (arrays of N rows) on a uniform grid, and what was done.

    Uniform time stamps are kept as they are. Otherwise :func:`check_timing` raises, or with
    ``resample`` every array is interpolated linearly onto the median step from 0 to the last
    time stamp (``meta["resampled"]`` records it): for loggers whose PC clock jitters, or a
    trace with a few dropped samples.
    """
    t = t - t[0]
    try:
        check_timing(t, src, row_lines)
        return t, list(values), {}
    except CaptureError:
        if not resample or np.any(np.diff(t) <= 0):
            raise
    dt = np.diff(t)
    ts = float(f"{float(np.median(dt)):.6g}")
    n = int(np.floor(t[-1] / ts + 1e-9)) + 1
    if n > MAX_SAMPLES:
        raise CaptureError(f"resampling {t[-1]:.6g} s at {ts:.6g} s would make more than {MAX_SAMPLES} samples",
                           file=src)
    grid = np.round(np.arange(n) * ts, 12)
    out = [np.column_stack([np.interp(grid, t, v[:, j]) for j in range(v.shape[1])]) for v in values]
    how = (f"linear, onto a {ts:.6g} s step from {t.size} samples with steps of {float(dt.min()):.6g} to "
           f"{float(dt.max()):.6g} s")
    return grid, out, {"resampled": how}


#: Largest magnitude of a position [mm, deg] or time [s] a trace may hold: far beyond any machine's travel or
#: recording, and far below where the squares and sums of the lag and identification overflow (1e154).
REACH = 1e15


def within_reach(values: np.ndarray, what: str, unit: str, src: str | None, row_lines: Sequence[int] | None = None
                 ) -> None:
    """CaptureError naming the first row (its file line, from ``row_lines``; else the sample) whose value (after
    its unit's scaling) is not finite or beyond :data:`REACH`: a number no trace of a machine holds (a corrupted
    cell, or a unit far off)."""
    bad = np.flatnonzero(~(np.abs(values) <= REACH))
    if bad.size:
        k = int(bad[0])
        where = "in this row" if row_lines is not None else f"at sample {k}"
        raise CaptureError(f"{what} is {values[k]:.6g} {unit} {where}, beyond any machine's travel or recording "
                           f"({REACH:g}): a corrupted number, or a unit far off", file=src,
                           line=None if row_lines is None else row_lines[k])
