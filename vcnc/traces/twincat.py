"""Beckhoff TwinCAT 3 Scope View CSV export ("Export to csv", TE130x Scope View, TC3ScopeExportTool).

Layout, as documented by Beckhoff (infosys, TE1300 "Export to csv") and as written by TwinCAT 3
Scope 3.4 with each exporter setting (the eleven export files in the test data of the open-source
reader ``CagtayFabry/pytcs``: default, decimal comma, EOF line, five separators, channels sorted
or not, double time stamps excluded or not):

- **Header block**: ``Name<d>scope``, ``File<d>path``, ``Starttime of export<d>ticks<d>date<d>time``,
  ``Endtime of export...``, blank lines; absent when the exporter's header setting leaves it out
  (then the channel ``Name`` row comes first).
- **Channel rows**, one per property (``Name``, ``SymbolComment``, ``Data-Type``,
  ``SampleTime[ms]``, ..., ``SymbolName``, ``Unit``, ``ScaleFactor``...; some exports write only
  ``Name``). Each row repeats its key at the start of every *acquisition group*: the key's column is
  the group's time column and the channels follow it up to the next key. With "exclude double
  time stamps" the channels of one sample time share a group; otherwise every channel has its own.
- **Data rows**: each group's time [ms from the start, or 100 ns FILETIME ticks with "full time
  stamp"] and its channels. A group with fewer samples leaves its cells blank (a space) or the row
  ends early. An optional last line ``EOF``.
- **Units**: a channel's ``Unit`` row (``mm``, ``µm``, ``°``...; ``(None)``) scales its
  positions unless ``--unit`` is given.
- **Scaling**: the ``ScaleFactor`` / ``Offset`` and ``Unit ScaleFactor`` / ``Unit Offset`` rows
  record the channel's scaling, which Scope applies to the exported values only when "Scale values
  before export" is set (Beckhoff infosys, TE13xx "Export to csv"); the file does not say which, and
  the pytcs test exports hold both (the default export unscaled, its simple export scaled). The
  values are read as they stand, and a used channel whose scaling is not 1 and 0 is named in
  ``meta["scaling"]`` (found by tracewild, session 16).
- **Separator** tab (default), ``;``, ``,``, ``:`` or space, the character after the first
  ``Name``; **decimal mark** ``.`` or ``,`` (with any separator but ``,``). With space, a name or unit
  holding a space is written as several words (pytcs' ``Seperator_1`` export: ``test space``,
  ``V (Voltage)``): they are rejoined group by group against a row of one-word cells (``Data-Type``...),
  units at their parenthesis, and a group whose names cannot be told apart is an error (tracewild10).

Channels are found by ``Name`` (or ``SymbolName``). Without ``--columns``, NC axis channels
``...SetPos`` / ``...ActPos`` (``NcToPlc.SetPos`` / ``NcToPlc.ActPos``, Beckhoff infosys
``NCTOPLC_AXIS_REF``) pair up per axis, named by the axis letter their names carry (``Axis_Y.NcToPlc.SetPos``: y;
tracewild6), else x, y, z... in their order. The commanded and measured channels are taken on the time
stamps they share (a slower group gives the grid); a time stamp a group repeats holds one sample.

**Lag.** An axis traced with its set position and its lag instead of its actual position
(``...PosDiff``, "Position difference (lag distance)" in ``NCTOPLC_AXIS_REF``; "Lag distance" /
"Schleppabstand" in the axis' online view), or mapped as ``x_lag=NAME``, is read with the actual
position = set position - lag: Beckhoff defines the position lag value as "current set position -
actual position" (infosys, TF50x0 TwinCAT 3 NC PTP, "Monitoring", Position Lag Monitoring), and the
sign is checked on the data (:mod:`vcnc.traces.lag`). With both an ``ActPos`` and a ``PosDiff`` of the
axis, ``ActPos`` is used: it is the measurement, the lag the control's difference of it from the set
position, and it needs no convention.
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES
from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError
from vcnc.traces.columns import (
    LAG_SUFFIX,
    TIME_UNITS,
    assumed_unit,
    axis_of,
    check_units,
    mapped_axes,
    mapping_meta,
    on_uniform_grid,
    parse_number,
    position_scale,
    read_text,
    unit_named,
    unit_stated,
    with_following_errors,
)
from vcnc.traces.names import channels_from_names, mapping_note

__all__ = ["read_twincat", "looks_like_twincat", "scope_project_reason"]

_FIRST = re.compile(r'^"?Name"?([\t;,: ])')
#: The root element of a TwinCAT 3 Scope project (``.tcscopex``: ``<ScopeProject
#: AssemblyName="TwinCAT.Measurement.Scope.API.Model">``, anderssandstrom/tc_target_drive's DataLog/Phasing.tcscopex).
SCOPE_PROJECT = "ScopeProject"
_FILETIME_TICK_S = 1e-7
_NAMES = {"\t": "tab", ";": "semicolon", ",": "comma", ":": "colon", " ": "space"}
#: How an NC axis' lag is signed, and where Beckhoff says so.
LAG_CONVENTION = ("set position - actual position (Beckhoff infosys, TF50x0 TwinCAT 3 NC PTP, 'Monitoring': "
                  "position lag value = current set position - actual position)")
#: Ends of NC axis channel names (lower case): the set position, the actual position and the lag
#: (``NcToPlc.SetPos`` / ``ActPos`` / ``PosDiff``, "Position difference (lag distance)", Beckhoff
#: infosys ``NCTOPLC_AXIS_REF``; the online view's "Set Position" / "Actual Position" / "Lag
#: Distance", German "Sollposition" / "Istposition" / "Schleppabstand").
_SET_ENDS = ("setpos", "set position", "sollposition")
_ACT_ENDS = ("actpos", "actual position", "istposition")
_LAG_ENDS = ("posdiff", "lag distance", "schleppabstand")


@dataclasses.dataclass(frozen=True)
class _Channel:
    """A channel: its names and its value and time columns (0-based)."""

    name: str
    symbol: str
    column: int
    time_column: int
    unit: str | None  # the unit of the channel's "Unit" row as a LENGTH_UNITS key, if it is a length
    scaling: str = ""  # its scale rows that are not the identity ("ScaleFactor -1, Offset 1"), if any


def looks_like_twincat(text: str) -> bool:
    """True for a TwinCAT Scope CSV export: ``Name<separator>`` first, then ``File`` or
    ``Starttime of export``, or a ``SampleTime[ms]`` row."""
    lines = text.lstrip("\ufeff").splitlines()[:6]
    m = _FIRST.match(lines[0]) if lines else None
    if m is None:
        return False
    keys = [ln.strip().lstrip('"') for ln in lines[1:5]]
    return (any(k.startswith(("File", "Starttime of export")) for k in keys) or "SampleTime[ms]" in text[:20000]
            or _cells(lines[0], m.group(1)).count("Name") >= 2)


def read_twincat(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                 time_unit: str | None = None, unit: str | None = None,
                 axes: Sequence[str] | None = None, resample: bool = False) -> Capture:
    """Read a TwinCAT Scope CSV export (module docstring) into a capture.

    Parameters
    ----------
    path : path-like
        The export.
    columns : mapping, optional
        ``{"x_ref": NAME, "x": NAME, ...}``: the commanded and measured channel of each axis
        (``Name`` or ``SymbolName``), or ``x_lag`` for a following error; default the ``SetPos`` /
        ``ActPos`` (or ``PosDiff``) channels.
    time_unit : {"ms", "s", "us"}, optional
        Unit of the time columns (default ms, as Scope writes; FILETIME ticks are detected).
    unit : {"mm", "um", "nm", "m", "in", "deg"} or a count size ("0.1um"), optional
        Unit of the positions, or the size of one count of positions logged in increments
        (:func:`vcnc.traces.columns.length_unit`) (default mm).
    axes : sequence of str, optional
        Names of the axes of the ``SetPos`` channels, in their order.
    resample : bool
        Interpolate time stamps that are not uniform onto the median step (else an error).

    Raises
    ------
    CaptureError
        Naming the file and line: no channel rows, an unknown or ambiguous channel (listing the
        channels found), a cell that is not a number, time going backwards, dropped samples.
    """
    src = str(Path(path))
    check_units(time_unit, unit, src)
    lines = read_text(path, src).lstrip("\ufeff").splitlines()
    m = _FIRST.match(lines[0]) if lines else None
    if m is None:
        raise CaptureError("expected 'Name<separator><scope name>' on the first line (TwinCAT Scope CSV export)",
                           file=src, line=1)
    d = m.group(1)
    channels, data_start, names_line = _channel_rows(lines, d, src)
    found = [c.name for c in channels]
    mapping, note = (({k: v for k, v in columns.items() if k != "t"}, "") if columns
                     else _nc_pairs(channels, axes, src, names_line))
    ax = mapped_axes(mapping, src)
    rows, row_lines = _rows(lines, data_start, d, max(c.column for c in channels) + 1, src)
    used = {key: _find(name, channels, found, src, names_line) for key, name in mapping.items()}
    comma = d != ","
    times = {c.time_column: _values(rows, c.time_column, comma, src, row_lines) for c in used.values()}
    per_s, base = _time_scale(times, rows, time_unit, src, row_lines)
    series = {key: _series(c, times[c.time_column], rows, row_lines, per_s, base, comma, src)
              for key, c in used.items()}
    first = series[f"{ax[0]}_ref"]
    common = first[0]
    for tk, _, _ in series.values():
        common = np.intersect1d(common, tk)
    if common.size < 2:
        raise CaptureError(f"channels {list(mapping.values())} share fewer than two time stamps", file=src)

    def on(key: str) -> np.ndarray:
        tk, v, _ = series[key]
        return v[np.searchsorted(tk, common)]

    units = {key: unit or c.unit for key, c in used.items()}

    def scaled(key: str) -> np.ndarray:
        return on(key) * position_scale([axis_of(key)], units[key], src)

    t, (ref, second), how = on_uniform_grid(np.round(common - common[0], 9),
                                            [np.column_stack([scaled(f"{a}_ref") for a in ax]),
                                             np.column_stack([scaled(a if a in mapping else a + LAG_SUFFIX)
                                                              for a in ax])], src,
                                            [first[2][k] for k in np.searchsorted(first[0], common)],
                                            resample=resample)
    meas, lag = with_following_errors(ax, mapping, ref, second, float(t[1] - t[0]), src, line=names_line,
                                      expected=LAG_CONVENTION)
    meta = {"format": "TwinCAT Scope CSV", "separator": _NAMES[d],
            "time_unit": "100 ns ticks" if per_s == _FILETIME_TICK_S else (time_unit or "ms"),
            "unit": ",".join(sorted({u or assumed_unit(k) for k, u in units.items()})), **mapping_meta(ax, mapping),
            **lag, **how}
    if note:
        meta["columns"] = note
    if unit is None:
        meta.update(unit_stated(units, "stated in the Unit row"))
    scaling = [f"{c.name} ({c.scaling})" for c in used.values() if c.scaling]
    if scaling:
        meta["scaling"] = (f"{'; '.join(scaling)}: applied by Scope only with 'Scale values before export', "
                           "read as exported")
    return Capture(t=t, axes=tuple(ax), reference=ref, measured=meas, meta=meta, source=src)


def _cells(line: str, d: str) -> list[str]:
    return [c.strip().strip('"') for c in line.split(d)]


def _is_data(line: str, d: str) -> bool:
    """True for a row of numbers (blank cells allowed, at least one number)."""
    cells = [c for c in line.split(d) if c.strip()]
    try:
        for c in cells:
            parse_number(c, d != ",")
    except ValueError:
        return False
    return bool(cells)


def _channel_rows(lines: list[str], d: str, src: str) -> tuple[list[_Channel], int, int]:
    """The channels of the ``Name`` row (and ``SymbolName`` row), the index of the first data row
    and the file line of the ``Name`` row."""
    first = 1 if len(lines) > 1 and _cells(lines[1], d)[0] in ("File", "Starttime of export") else 0
    if first == 0 and len(_cells(lines[0], d)) <= 2 and not (len(lines) > 1 and _is_data(lines[1], d)):
        first = 1  # "Name<d>scope name": the export header, not a channel row
    start = next((i for i in range(first, len(lines)) if _cells(lines[i], d)[0] == "Name"), None)
    if start is None:
        raise CaptureError("no channel 'Name' row after the export header (TwinCAT Scope CSV export)", file=src)
    rows: dict[str, list[str]] = {}
    data_start = None
    for i in range(start, len(lines)):
        if not lines[i].strip():
            continue
        if _is_data(lines[i], d):
            data_start = i
            break
        cells = _cells(lines[i], d)
        rows.setdefault(cells[0], cells)
    if data_start is None:
        raise CaptureError("no rows of numbers after the channel rows", file=src, line=len(lines))
    if d == " ":
        _rejoin_words(rows, src, start + 1)
    names, symbols, units = rows["Name"], rows.get("SymbolName"), rows.get("Unit")
    channels, time_column = [], 0
    for j, name in enumerate(names):
        if name == "Name":
            time_column = j
        elif name:
            symbol = symbols[j] if symbols and j < len(symbols) else name
            unit = units[j].split()[0] if units and j < len(units) and units[j].split() else ""
            channels.append(_Channel(name=name, symbol=symbol, column=j, time_column=time_column,
                                     unit=unit_named(unit, "length"), scaling=_scaling(rows, j, d != ",")))
    if not channels:
        raise CaptureError("the channel 'Name' row names no channel", file=src, line=start + 1)
    return channels, data_start, start + 1


#: Channel rows whose cells hold no space: the layout of the groups, in a space-separated export.
_ONE_WORD_ROWS = ("Data-Type", "SampleTime[ms]", "VariableSize", "SymbolBased", "IndexGroup", "IndexOffset", "NetID",
                  "Port", "Offset", "ScaleFactor", "BitMask")


def _rejoin_words(rows: dict[str, list[str]], src: str, line: int) -> None:
    """Rejoin the ``Name``, ``SymbolName`` and ``Unit`` cells a space-separated export split at their spaces (a
    channel ``test space``, a unit ``V (Voltage)``: the pytcs export with separator space), group by group against
    a row whose cells hold no space. Every later name and unit stood one column off: a channel was read with its
    neighbour's values (tracewild10). A group whose words cannot be told apart is an error naming it."""
    ref = next((rows[k] for k in _ONE_WORD_ROWS if k in rows), None)
    if ref is None:
        return
    starts = [j for j, c in enumerate(ref) if c == ref[0]]
    sizes = [b - a - 1 for a, b in zip(starts, [*starts[1:], len(ref)])]
    for key in ("Name", "SymbolName", "Unit"):
        cells = rows.get(key)
        if cells is None or len(cells) == len(ref):
            continue
        marks = [j for j, c in enumerate(cells) if c == key]
        groups = [cells[a + 1:b] for a, b in zip(marks, [*marks[1:], len(cells)])]
        if len(groups) != len(sizes):
            raise CaptureError(f"the {key!r} row has {len(groups)} groups of channels, the {ref[0]!r} row "
                               f"{len(sizes)} (a space-separated export)", file=src, line=line)
        out: list[str] = []
        for size, words, column in zip(sizes, groups, starts):
            joined = (words if len(words) == size else [" ".join(words)] if size == 1
                      else _units(words) if key == "Unit" else words)
            if len(joined) != size:
                raise CaptureError(
                    f"a space-separated export splits {key} cells at their spaces, and the {size} channels of "
                    f"the group at column {column + 1} read as {len(words)} words {words[:8]}: which words form "
                    "one name cannot be told; export with another separator (tab, the default)", file=src,
                    line=line)
            out += [key, *joined]
        rows[key] = out


def _units(words: list[str]) -> list[str]:
    """``Unit`` words rejoined: a word opening with ``(`` after a symbol (``V (Voltage)``), or within an open
    parenthesis, belongs to the unit before it."""
    out: list[str] = []
    for w in words:
        if out and (out[-1].count("(") > out[-1].count(")") or (w.startswith("(") and "(" not in out[-1])):
            out[-1] += " " + w
        else:
            out.append(w)
    return out


_SCALE_ROWS = {"ScaleFactor": 1.0, "Offset": 0.0, "Unit ScaleFactor": 1.0, "Unit Offset": 0.0}


def _scaling(rows: dict[str, list[str]], j: int, comma: bool) -> str:
    """The scale rows of column ``j`` whose value is not the identity, as ``"ScaleFactor -1, Offset 1"``."""
    out = []
    for key, identity in _SCALE_ROWS.items():
        cells = rows.get(key, [])
        cell = cells[j] if j < len(cells) else ""
        try:
            value = parse_number(cell, comma)
        except ValueError:
            continue
        if value == value and value != identity:
            out.append(f"{key} {cell}")
    return ", ".join(out)


def _rows(lines: list[str], start: int, d: str, width: int, src: str) -> tuple[list[list[str]], list[int]]:
    """The data rows as cells (a row may end early), and the file line of each."""
    rows, row_lines = [], []
    for i in range(start, len(lines)):
        s = lines[i].strip()
        if not s or s.upper() == "EOF":
            continue
        cells = lines[i].split(d)
        while cells and not cells[-1].strip():
            cells.pop()
        if len(cells) > width:
            raise CaptureError(f"{len(cells)} fields, but the channel rows have {width}", file=src, line=i + 1)
        rows.append(cells)
        row_lines.append(i + 1)
    return rows, row_lines


def _values(rows: list[list[str]], j: int, comma: bool, src: str, row_lines: list[int]) -> np.ndarray:
    """Column ``j`` as numbers, NaN where blank or missing."""
    out = np.full(len(rows), np.nan)
    for k, r in enumerate(rows):
        if j < len(r):
            try:
                out[k] = parse_number(r[j], comma)
            except ValueError:
                raise CaptureError("not a number", file=src, line=row_lines[k], column=j + 1,
                                   text=r[j].strip()) from None
    return out


def _time_scale(times: dict[int, np.ndarray], rows: list[list[str]], time_unit: str | None, src: str,
                row_lines: list[int]) -> tuple[float, int]:
    """Seconds per time unit, and the tick count subtracted from FILETIME stamps (0 for ms)."""
    finite = [t[np.isfinite(t)] for t in times.values()]
    if any(f.size == 0 for f in finite):
        raise CaptureError("a channel used has no time stamps", file=src)
    if max(float(np.max(np.abs(f))) for f in finite) <= 1e15:
        return TIME_UNITS[time_unit or "ms"], 0
    firsts = [_tick(rows, int(np.flatnonzero(np.isfinite(t))[0]), j, src, row_lines) for j, t in times.items()]
    return _FILETIME_TICK_S, min(firsts)


def _tick(rows: list[list[str]], k: int, j: int, src: str, row_lines: list[int]) -> int:
    """The FILETIME stamp in row ``k``, column ``j`` [100 ns ticks], exact."""
    cell = rows[k][j].strip()
    if not cell.isdigit():
        raise CaptureError("expected a FILETIME stamp (a whole number of 100 ns ticks) like the others of the "
                           "export", file=src, line=row_lines[k], column=j + 1, text=cell)
    return int(cell)


def _series(c: _Channel, t_raw: np.ndarray, rows: list[list[str]], row_lines: list[int], per_s: float, base: int,
            comma: bool, src: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(time [s], value, file line)`` of a channel's samples, a repeated time stamp once."""
    v = _values(rows, c.column, comma, src, row_lines)
    keep = np.flatnonzero(np.isfinite(v) & np.isfinite(t_raw))
    if base:
        t = np.array([(_tick(rows, k, c.time_column, src, row_lines) - base) * per_s for k in keep])
    else:
        t = t_raw[keep] * per_s
    t = np.round(t, 9)
    lines = np.asarray(row_lines)[keep]
    if t.size:
        first = np.r_[True, t[1:] != t[:-1]]
        t, v_kept, lines = t[first], v[keep][first], lines[first]
    else:
        v_kept = v[keep]
    back = np.flatnonzero(np.diff(t) < 0)
    if back.size:
        k = int(back[0]) + 1
        raise CaptureError(f"time of channel {c.name!r} goes backwards ({t[k]:.9g} s after {t[k - 1]:.9g} s)",
                           file=src, line=int(lines[k]), column=c.time_column + 1)
    if t.size < 2:
        raise CaptureError(f"channel {c.name!r} has fewer than two samples", file=src)
    return t, v_kept, lines


def _find(name: str, channels: list[_Channel], found: list[str], src: str, line: int) -> _Channel:
    hits = [c for c in channels if c.name == name] or [c for c in channels if c.symbol == name]
    if not hits:
        raise CaptureError(f"channel {name!r} not found; channels found: {found}", file=src, line=line)
    if len(hits) > 1:
        raise CaptureError(f"{len(hits)} channels are named {name!r} (SymbolName {[h.symbol for h in hits]}); "
                           "give a SymbolName that is unique, or rename the channels in Scope", file=src, line=line)
    return hits[0]


def _axis_letters(prefixes: list[str]) -> list[str] | None:
    """The axis letters the NC axes' names carry (``Axis_Y.NcToPlc.`` -> y, ``MAIN.Z.NcToPlc.`` -> z): each prefix's
    one word (between separators) that is an axis letter alone, all different; None otherwise (``MAIN.Axis1.``: then
    x, y, z... in order). A letter with a number (``MAIN.A1``, often "Achse 1", axis 1 in German projects; ``X1``, one
    of two X drives) names no axis (review29). Our reading: an axis a machine names Y is axis y to its user
    (``vcnc identify --axis y``)."""
    letters = []
    for prefix in prefixes:
        words = {w for w in re.split(r"[^a-z0-9]+", prefix.lower()) if w in AXIS_NAMES}
        if len(words) != 1:
            return None
        letters.append(words.pop())
    return letters if len(set(letters)) == len(letters) else None


def _nc_pairs(channels: list[_Channel], axes: Sequence[str] | None, src: str,
              line: int) -> tuple[dict[str, str], str]:
    """The NC axis channels of each axis (module docstring), named ``axes`` (default the axis letters their names
    carry, :func:`_axis_letters`, else x, y, z... in the order of their set positions): a set position with the
    actual position of the same prefix (``Axis1.NcToPlc.SetPos`` / ``Axis1.NcToPlc.ActPos``), else with its lag
    (``...PosDiff``): the actual position is a measurement, the lag the control's difference of the two. Without NC
    axis channels, PLC variables whose names leave no doubt (``MAIN.fSollPos`` / ``MAIN.fIstPos``,
    :func:`vcnc.traces.names.columns_from_names`; tracewild2), with the note for ``meta["columns"]``."""
    def split(name: str, ends: tuple[str, ...]) -> str | None:
        low = name.lower().rstrip()
        return next((low[: -len(e)] for e in ends if low.endswith(e)), None)

    actual = {split(c.name, _ACT_ENDS): c.name for c in reversed(channels) if split(c.name, _ACT_ENDS) is not None}
    lag = {split(c.name, _LAG_ENDS): c.name for c in reversed(channels) if split(c.name, _LAG_ENDS) is not None}
    pairs, prefixes = [], []
    for c in channels:
        prefix = split(c.name, _SET_ENDS)
        if prefix in actual:
            pairs.append((c.name, "", actual[prefix]))
        elif prefix in lag:
            pairs.append((c.name, LAG_SUFFIX, lag[prefix]))
        if prefix in actual or prefix in lag:
            prefixes.append(str(prefix))
    if not pairs:
        named, why = channels_from_names([c.name for c in channels], "channel")
        if named is not None:
            return named, mapping_note("channel", named)
        raise CaptureError("which channels are the commanded and measured positions? give --columns "
                           f"x_ref=NAME,x=NAME (or x{LAG_SUFFIX}=NAME for a following error); channels found: "
                           f"{[c.name for c in channels]} (not read from the names: {why})", file=src, line=line)
    names = list(axes) if axes else _axis_letters(prefixes) or list(AXIS_NAMES[: len(pairs)])
    if len(names) != len(pairs):
        raise CaptureError(f"{len(names)} axis name(s) for the {len(pairs)} NC axis set positions "
                           f"{[ref for ref, _, _ in pairs]}", file=src, line=line)
    out: dict[str, str] = {}
    for a, (ref, suffix, other) in zip(names, pairs):
        out[f"{a}_ref"], out[a + suffix] = ref, other
    return out, ""


def scope_project_reason(root: str) -> str | None:
    """Why a TwinCAT 3 Scope project is not read, for the XML root element ``root``, else None: the project configures
    the scope's charts and channels; a recording is exported to CSV from TwinCAT Scope ("Export to csv", TE13xx Scope
    View; TC3ScopeExportTool), which :func:`read_twincat` reads (our reading of the layout: no sample values in it)."""
    if root.rpartition(":")[2] != SCOPE_PROJECT:
        return None
    return ("a TwinCAT Scope project (root <ScopeProject>): the scope's configuration, its charts and channels; vcnc "
            "reads a recording exported to CSV (TwinCAT Scope: Export to csv, or TC3ScopeExportTool)")
