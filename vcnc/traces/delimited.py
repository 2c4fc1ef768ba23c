"""Delimited text traces: logger CSVs, Beckhoff TwinCAT Scope CSV exports, LinuxCNC halscope logs.

- **Generic delimited text.** The delimiter (tab, ``;`` or ``,``) and a decimal comma are detected
  from the data; lines before the header (the line of column names just above the numeric rows)
  are skipped. Which column is what is given by a mapping such as ``t=Time,x_ref=PosCmd,x=PosAct``
  (header names, or 1-based column numbers for a file without a header); time in s, ms or us and
  positions in mm, um, m, in or deg (rotary axes a, b, c only) are converted to s and mm / deg.
  Rows with an empty cell in a used column are skipped (loggers that write change-only rows).
- **TwinCAT Scope CSV export** (Beckhoff TE13xx Scope View, "Export to csv"): a header block
  (``Name``, ``File``, ``Starttime of export``...), then one row per channel property with a
  ``key<TAB>value`` pair per channel (``Name``, ``SampleTime[ms]``, ``Unit``...), then the data
  with a time column [ms from the first data point, or 100 ns file-time ticks with "Full
  Timestamp"] before each channel's value column. Channels are named by their ``Name``; the
  commanded and measured channels are paired on their common time stamps. Format as documented
  by Beckhoff (infosys "Export to csv") and exported by TwinCAT 3 Scope 3.4 (the test files of
  the open-source reader ``CagtayFabry/pytcs``).
- **LinuxCNC halscope log** ("Save log"): ``Sampling period is <n> ns``, then one line per sample
  of ``<label> <value>`` pairs (``write_log_file`` in LinuxCNC's ``src/hal/utils/scope_files.c``).
  Without a mapping, ``joint.N.motor-pos-cmd`` / ``joint.N.motor-pos-fb`` pins (or ``axis.N``, or
  ``pos-cmd`` / ``pos-fb``) pair up per joint, joints in order named x, y, z... .
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES, ROTARY_AXES
from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError

__all__ = ["read_delimited", "parse_columns", "looks_like_halscope", "looks_like_twincat", "TIME_UNITS",
           "LENGTH_UNITS"]

#: Seconds per time unit.
TIME_UNITS: dict[str, float] = {"s": 1.0, "ms": 1e-3, "us": 1e-6}
#: Millimetres (or degrees, for "deg") per position unit.
LENGTH_UNITS: dict[str, float] = {"mm": 1.0, "um": 1e-3, "m": 1000.0, "in": 25.4, "deg": 1.0}

_HALSCOPE = re.compile(r"^\s*Sampling period is\s+(\d+)\s*ns", re.I)
_DELIMITERS = ("\t", ";", ",")
_FILETIME_TICK_S = 1e-7


def parse_columns(text: str) -> dict[str, str]:
    """``"t=Time,x_ref=PosCmd,x=PosAct"`` as a mapping capture column -> source column.

    Raises
    ------
    CaptureError
        A part without ``=``, or a capture column that is not ``t``, ``<axis>_ref`` or ``<axis>``.
    """
    out: dict[str, str] = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        key, eq, value = part.partition("=")
        key, value = key.strip(), value.strip()
        base = key[:-4] if key.endswith("_ref") else key
        if not eq or not value or not (key == "t" or base in AXIS_NAMES):
            raise CaptureError(f"--columns part {part!r}: expected 't=NAME', '<axis>_ref=NAME' or '<axis>=NAME' "
                               f"(axes {' '.join(AXIS_NAMES)})")
        out[key] = value
    return out


def looks_like_halscope(head: str) -> bool:
    """True when the first line is halscope's ``Sampling period is ... ns``."""
    return bool(_HALSCOPE.match(head.lstrip("\ufeff").splitlines()[0] if head.strip() else ""))


def looks_like_twincat(head: str) -> bool:
    """True for a TwinCAT Scope CSV export (``Name`` first, a ``SampleTime[ms]`` row)."""
    first = head.lstrip("\ufeff").split("\n", 1)[0]
    return first.startswith("Name") and "SampleTime[ms]" in head


def read_delimited(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                   time_unit: str | None = None, unit: str | None = None,
                   axes: Sequence[str] | None = None) -> Capture:
    """Read a delimited text trace (module docstring) into a capture.

    Parameters
    ----------
    path : path-like
        The trace.
    columns : mapping, optional
        Capture column -> source column (``{"t": "Time", "x_ref": "PosCmd", "x": "PosAct"}``);
        required except for halscope logs with joint position pins.
    time_unit : {"s", "ms", "us"}, optional
        Unit of the time column (default s; TwinCAT: ms).
    unit : {"mm", "um", "m", "in", "deg"}, optional
        Unit of the positions (default mm; "deg" only for rotary axes).
    axes : sequence of str, optional
        Names for the joints of a halscope log, in joint order.

    Raises
    ------
    CaptureError
        Naming the file, the line and the columns found: no numeric rows, an unknown column in
        ``columns``, no commanded/measured pair, time going backwards or not uniform.
    """
    src = str(Path(path))
    raw = Path(path).read_bytes()
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    _check_units(time_unit, unit, src)
    if looks_like_halscope(text[:200]):
        return _halscope(text, src, columns=columns, unit=unit, axes=axes)
    if looks_like_twincat(text[:20000]):
        return _twincat(text, src, columns=columns, time_unit=time_unit or "ms", unit=unit)
    return _generic(text, src, columns=columns, time_unit=time_unit or "s", unit=unit)


def _check_units(time_unit: str | None, unit: str | None, src: str) -> None:
    if time_unit is not None and time_unit not in TIME_UNITS:
        raise CaptureError(f"time unit {time_unit!r}: expected one of {', '.join(TIME_UNITS)}", file=src)
    if unit is not None and unit not in LENGTH_UNITS:
        raise CaptureError(f"position unit {unit!r}: expected one of {', '.join(LENGTH_UNITS)}", file=src)


def _number(cell: str, decimal_comma: bool) -> float:
    """A cell as a number; NaN when empty; ValueError when not a number."""
    s = cell.strip()
    if not s:
        return math.nan
    return float(s.replace(",", ".") if decimal_comma else s)


def _split(line: str, delimiter: str) -> list[str]:
    return line.rstrip("\r\n").split(delimiter)


def _numeric_block(lines: list[str], delimiter: str) -> tuple[int, int, bool]:
    """``(first, width, decimal_comma)`` of the numeric rows at the end of ``lines`` (first = -1
    when there are none). With a tab or ``;`` delimiter a comma in a number is a decimal comma."""
    comma = delimiter != ","
    first, width = -1, 0
    for i in range(len(lines) - 1, -1, -1):
        s = lines[i].strip()
        if not s:
            if first >= 0:
                break
            continue
        if s.upper() == "EOF" and first < 0:
            continue
        cells = _split(lines[i], delimiter)
        if len(cells) < 2 or (width and len(cells) != width):
            break
        try:
            vals = [_number(c, comma) for c in cells]
        except ValueError:
            break
        if all(math.isnan(v) for v in vals):
            break
        first, width = i, len(cells)
    return first, width, comma


def _table(text: str, src: str) -> tuple[list[str] | None, np.ndarray, list[int], str]:
    """``(header names or None, data (rows x columns, NaN for empty), file line of each row,
    delimiter)`` of a delimited file."""
    lines = text.splitlines()
    blocks = [(d, *_numeric_block(lines, d)) for d in _DELIMITERS]
    # the delimiter that makes the longest block of numeric rows (then the widest)
    delimiter, first, width, comma = max(blocks, key=lambda b: (b[1] >= 0 and b[2] >= 2, -b[1], b[2]))
    if first < 0 or width < 2:
        raise CaptureError("no rows of numbers separated by tab, ';' or ','", file=src)
    header = None
    for j in range(first - 1, -1, -1):
        if lines[j].strip():
            cells = [c.strip() for c in _split(lines[j], delimiter)]
            header = cells if len(cells) == width else None
            break
    rows, row_lines = [], []
    for i in range(first, len(lines)):
        if not lines[i].strip() or lines[i].strip().upper() == "EOF":
            continue
        rows.append([_number(c, comma) for c in _split(lines[i], delimiter)])
        row_lines.append(i + 1)
    return header, np.array(rows, dtype=float), row_lines, delimiter


def _column(name: str, header: list[str] | None, width: int, src: str, line: int) -> int:
    """Index of a source column named ``name`` (a header name, or a 1-based number)."""
    if header is not None and name in header:
        return header.index(name)
    if name.isdigit() and 1 <= int(name) <= width:
        return int(name) - 1
    found = header if header is not None else "(no header line: give 1-based column numbers)"
    raise CaptureError(f"column {name!r} not found; columns found: {found}", file=src, line=line)


def _axes_of(columns: Mapping[str, str], src: str) -> list[str]:
    axes = [k for k in columns if k in AXIS_NAMES]
    missing = [a for a in axes if f"{a}_ref" not in columns] + [k[:-4] for k in columns
                                                                if k.endswith("_ref") and k[:-4] not in columns]
    if not axes or missing:
        raise CaptureError(f"--columns needs '<axis>_ref=...' and '<axis>=...' for each axis (incomplete: "
                           f"{sorted(set(missing)) or 'no axis given'})", file=src)
    return axes


def _scale(axes: list[str], unit: str | None, src: str) -> float:
    u = unit or "mm"
    linear = [a for a in axes if a not in ROTARY_AXES]
    if u == "deg" and linear:
        raise CaptureError(f"unit 'deg' is for rotary axes (a, b, c); axes {linear} are linear", file=src)
    if u != "deg" and len(linear) < len(axes) and unit is not None:
        raise CaptureError(f"unit {u!r} given for rotary axes {[a for a in axes if a in ROTARY_AXES]}; "
                           "rotary positions are in deg", file=src)
    return LENGTH_UNITS[u]


def _generic(text: str, src: str, *, columns: Mapping[str, str] | None, time_unit: str,
             unit: str | None) -> Capture:
    header, data, row_lines, delimiter = _table(text, src)
    hline = row_lines[0] - 1
    if not columns:
        raise CaptureError("which columns are time, commanded and measured position? give --columns "
                           f"t=NAME,x_ref=NAME,x=NAME; columns found: {header or f'{data.shape[1]} unnamed'}",
                           file=src, line=hline)
    if "t" not in columns:
        raise CaptureError("--columns needs t=NAME (the time column)", file=src)
    axes = _axes_of(columns, src)
    idx = {k: _column(v, header, data.shape[1], src, hline) for k, v in columns.items()}
    used = data[:, list(idx.values())]
    keep = ~np.isnan(used).any(axis=1)
    if keep.sum() < 2:
        raise CaptureError(f"fewer than two rows with all of {list(columns.values())}", file=src)
    d = data[keep]
    lines_kept = [n for n, k in zip(row_lines, keep) if k]
    t = d[:, idx["t"]] * TIME_UNITS[time_unit]
    _increasing(t, src, lines_kept)
    s = _scale(axes, unit, src)
    names = {",": "comma", ";": "semicolon", "\t": "tab"}
    meta = {"format": f"delimited text ({names[delimiter]})", "time_unit": time_unit, "unit": unit or "mm",
            "commanded": ",".join(f"{a}:{columns[a + '_ref']}" for a in axes),
            "measured": ",".join(f"{a}:{columns[a]}" for a in axes)}
    return Capture(t=t - t[0], axes=tuple(axes), reference=d[:, [idx[f"{a}_ref"] for a in axes]] * s,
                   measured=d[:, [idx[a] for a in axes]] * s, meta=meta, source=src)


def _increasing(t: np.ndarray, src: str, row_lines: list[int]) -> None:
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        raise CaptureError(f"time does not increase: {t[k]!r} s after {t[k - 1]!r} s", file=src, line=row_lines[k])


def _twincat(text: str, src: str, *, columns: Mapping[str, str] | None, time_unit: str,
             unit: str | None) -> Capture:
    _, data, row_lines, delimiter = _table(text, src)
    hline = row_lines[0] - 1
    lines = text.splitlines()
    # the channel row "Name<d>channel<d>Name<d>channel..." (the first line names the scope itself)
    names_row = next((i for i in range(1, hline) if lines[i].startswith("Name" + delimiter)), None)
    header = [c.strip() for c in _split(lines[names_row], delimiter)] if names_row is not None else None
    if header is None or len(header) != data.shape[1]:
        raise CaptureError("TwinCAT Scope export without a channel 'Name' row matching the data columns "
                           "(export with one time column per channel)", file=src, line=hline)
    channels = {header[j + 1]: j + 1 for j in range(0, len(header) - 1, 2) if header[j] == "Name"}
    if not columns:
        raise CaptureError("which channels are the commanded and measured positions? give --columns "
                           f"x_ref=NAME,x=NAME; channels found: {list(channels)}", file=src, line=hline)
    axes = _axes_of(columns, src)
    ticks = np.nanmax(np.abs(data[:, ::2])) > 1e15  # "Full Timestamp": file time in 100 ns ticks
    per_s = _FILETIME_TICK_S if ticks else TIME_UNITS[time_unit]
    series = {}
    for key, name in columns.items():
        if key == "t":
            continue
        if name not in channels:
            raise CaptureError(f"channel {name!r} not found; channels found: {list(channels)}", file=src,
                               line=hline)
        j = channels[name]
        ok = ~np.isnan(data[:, j]) & ~np.isnan(data[:, j - 1])
        series[key] = (np.round(data[ok, j - 1] * per_s, 9), data[ok, j])
    common = series[f"{axes[0]}_ref"][0]
    for tk, _ in series.values():
        common = np.intersect1d(common, tk)
    if common.size < 2:
        raise CaptureError(f"channels {list(columns.values())} share fewer than two time stamps", file=src)

    def on(key: str) -> np.ndarray:
        tk, v = series[key]
        return v[np.searchsorted(tk, common)]

    s = _scale(axes, unit, src)
    meta = {"format": "TwinCAT Scope CSV", "time_unit": "100 ns ticks" if ticks else time_unit,
            "unit": unit or "mm", "commanded": ",".join(f"{a}:{columns[a + '_ref']}" for a in axes),
            "measured": ",".join(f"{a}:{columns[a]}" for a in axes)}
    return Capture(t=np.round(common - common[0], 9), axes=tuple(axes),
                   reference=np.column_stack([on(f"{a}_ref") for a in axes]) * s,
                   measured=np.column_stack([on(a) for a in axes]) * s, meta=meta, source=src)


def _halscope(text: str, src: str, *, columns: Mapping[str, str] | None, unit: str | None,
              axes: Sequence[str] | None) -> Capture:
    lines = text.splitlines()
    period = int(_HALSCOPE.match(lines[0].lstrip("\ufeff")).group(1)) * 1e-9
    labels: list[str] | None = None
    rows, row_lines = [], []
    for i, line in enumerate(lines[1:], start=2):
        parts = line.split()
        if not parts:
            continue
        if len(parts) % 2:
            raise CaptureError("expected '<label> <value>' pairs", file=src, line=i, text=line.strip())
        names, values = parts[::2], parts[1::2]
        if labels is None:
            labels = names
        elif names != labels:
            if len(names) < len(labels) and i == len(lines):  # halscope may write a last partial sample
                break
            raise CaptureError(f"labels {names} differ from the first sample's {labels}", file=src, line=i)
        try:
            rows.append([float(v) for v in values])
        except ValueError:
            raise CaptureError(f"non-numeric value; channels: {labels}", file=src, line=i) from None
        row_lines.append(i)
    if labels is None or len(rows) < 2:
        raise CaptureError("fewer than two samples after 'Sampling period is ... ns'", file=src)
    mapping = dict(columns) if columns else _halscope_pairs(labels, axes, src)
    mapping.pop("t", None)
    ax = _axes_of(mapping, src)
    missing = [v for v in mapping.values() if v not in labels]
    if missing:
        raise CaptureError(f"channel(s) {missing} not found; channels found: {labels}", file=src, line=row_lines[0])
    data = np.array(rows)
    s = _scale(ax, unit, src)
    meta = {"format": "halscope log", "sample_time_s": f"{period:.9g}", "unit": unit or "mm",
            "commanded": ",".join(f"{a}:{mapping[a + '_ref']}" for a in ax),
            "measured": ",".join(f"{a}:{mapping[a]}" for a in ax)}
    return Capture(t=np.round(np.arange(len(rows)) * period, 12), axes=tuple(ax),
                   reference=data[:, [labels.index(mapping[f"{a}_ref"]) for a in ax]] * s,
                   measured=data[:, [labels.index(mapping[a]) for a in ax]] * s, meta=meta, source=src)


_PIN = re.compile(r"^(?:joint|axis)\.(\d+)\.(?:motor-)?pos-(cmd|fb)$")


def _halscope_pairs(labels: list[str], axes: Sequence[str] | None, src: str) -> dict[str, str]:
    """Commanded/feedback pins of each joint, joints in order named ``axes`` (default x, y, z...)."""
    pins: dict[int, dict[str, str]] = {}
    for name in labels:
        m = _PIN.match(name)
        if m:
            pins.setdefault(int(m.group(1)), {}).setdefault(m.group(2), name)
    joints = sorted(j for j, p in pins.items() if {"cmd", "fb"} <= p.keys())
    if not joints:
        raise CaptureError("no joint.N.motor-pos-cmd / joint.N.motor-pos-fb pair; give --columns "
                           f"x_ref=LABEL,x=LABEL; channels found: {labels}", file=src)
    names = list(axes) if axes else list(AXIS_NAMES[: len(joints)])
    if len(names) != len(joints):
        raise CaptureError(f"{len(names)} axis name(s) for joints {joints}", file=src)
    out: dict[str, str] = {}
    for a, j in zip(names, joints):
        out[f"{a}_ref"], out[a] = pins[j]["cmd"], pins[j]["fb"]
    return out
