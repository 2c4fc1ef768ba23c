"""Delimited text traces: logger CSVs, and the dispatch to the TwinCAT Scope CSV
(:mod:`vcnc.traces.twincat`), halscope log (:mod:`vcnc.traces.halscope`) and EPICS camonitor log
(:mod:`vcnc.traces.camonitor`) readers.

**Generic delimited text.** The delimiter (tab, ``;`` or ``,``) and a decimal comma are detected
from the data; lines before the header (the line of column names just above the numeric rows)
are skipped. Which column is what is given by a mapping such as ``t=Time,x_ref=PosCmd,x=PosAct``
(header names, or 1-based column numbers for a file without a header; ``x_lag=Lag`` in the place of
``x=`` for a following error, commanded - actual, :mod:`vcnc.traces.lag`); time in s, ms or us and
positions in mm, um, m, in or deg (rotary axes a, b, c only) are converted to s and mm / deg;
without ``time_unit`` / ``unit`` a unit the header names (``Zeit [ms]``, ``Ist (µm)``) is used.
A time column of time stamps (``2024-05-02 15:56:24.376``, ``02.05.2024 15:56:24,376``,
``15:56:24.376``) is read as seconds.
A row of units under the names (``Zeit;Soll;Ist`` then ``ms;µm;µm``) gives the units the
same way. Cells may be in double quotes (``"0,5"``, ``"Soll"``). Rows with an empty cell in a used column
are skipped (loggers that write change-only rows). The
time must increase with a uniform step (:func:`vcnc.traces.columns.check_timing` names dropped
samples and jitter).

**Columns separated by spaces** (tracewild, session 16), as LinuxCNC's ``halsampler`` writes them
(man page halsampler(1), http://linuxcnc.org/docs/2.9/html/man/man1/halsampler.1.html;
``src/hal/components/sampler_usr.c``: one line per sample, each value
``%f`` followed by a space, no header and no time column; with ``-t`` the sample number first;
a line ``overrun`` where the FIFO was full and samples were lost), and as other loggers and
MATLAB's ``save -ascii`` do. A file without a time column is read with ``sample_time`` [s]
(``--sample-time``); with it, a mapped ``t`` column counts samples (``halsampler -t``), so that the
timing check names the samples an ``overrun`` lost. Without a sample-number column an ``overrun``
line is an error naming it: how many samples were lost is not known.

**Drive tools' layouts** (tracewild2, session 24). A sampling period stated above the table
(:mod:`vcnc.traces.preamble`: ``Sampling time: 0.5 ms``, SINAMICS' ``Trace cycle``) times a column of
sample numbers (``Sample #``, ``No.``) or a file without a time column, and gives a time column without a
unit its unit when its step is that period; positions in increments (``[inc]``, ``(counts)``, ``[pulse]``,
``(PUU)``, ``[LU]``, in the names or a units row; :func:`vcnc.traces.names.counted`) are read only with the
size of one count, given (``--unit 0.1um``) or stated (``Resolution: 0.1 um``), else an error asking for it
(counts are never read as millimetres); the table is the last block of rows, lines after it (Rexroth MTX's
``[Statistics]``) a trailer; a column of text in the rows (a machining step's name) is read around and an
error naming its cell only when mapped; a delimiter ending every row but not the names is no extra column;
time stamps rounded to the digits printed (MATLAB's five) are the uniform step they round (each within half
a unit of its last digit, our reading).

**Recorders' layouts** (tracewild3, session 25). Header rows labelled in their first cell, a cell wider than the
rows (Hioki's ``"SIGNAL","TIME","CH1"`` and ``"VERT_UNITS","S","V"`` above a ``"DATA"`` line; Panasonic's "Data name"
and "Unit" rows) give the names and units (:func:`_keyed_rows`); a header that spreads each channel over ``CHn``,
``Axis n``, description cells (dls-pmac-control's Power PMAC gather save) is joined per channel; a file of one row of
numbers (a saved row vector) and a header of time and other quantities only (speeds, currents: no position at all)
are refused as such, naming what was found.

**tracewild4** (session 26). A blank name over a time unit in the units row is the time column (maxon EPOS Studio's
data recorder export); positions of a linear axis in a motor's turns, radians or degrees are scaled by the lead (over a
gear ratio) stated above the table (:func:`vcnc.traces.preamble.stated_turn_travel`); a file of one hexadecimal number
per line is named as a hexadecimal dump (Mitsubishi's CNC sampling output form 1).

**tracewild5** (session 27). A cell ``NaN`` before a column's first number or after its last is a missing value, as
an empty cell (the ODrive GUI's export fills a channel not yet received with it), and one between its numbers a lost
value, an error when the column is used; a headerless file without a sampling period names the servo period a
LinuxCNC INI beside it states (:mod:`vcnc.traces.companion`); a linear axis logged in degrees of its motor is scaled
by a stated lead as turns and radians are.

**tracewild6** (session 29). A table written as a MATLAB matrix literal (``[`` before the first row, ``;`` after each,
``]`` after the last: ECP Executive's "Export Raw Data") is read without its brackets (:func:`_matrix_literal`); names
that hold single spaces and are set apart by runs of spaces (``Commanded Pos   Encoder 1 Pos``) are the header of rows
separated by spaces when they number the columns (:func:`_spaced_names`); a PI GCS array (:mod:`vcnc.traces.gcsarray`)
is read under its tables' names, a row every ``SAMPLE_TIME``, in the unit given.

**tracewild8** (session 32). A drive's parameter list (a line per object: index, subindex, value) is refused as such
(:func:`_check_parameter_list`), as is an EPICS IOC's log with ecmc's axis diagnostics
(:func:`_check_ecmc_diagnostics`). A column taken as sample numbers must step by 1 (:func:`_check_sample_numbers`):
CoDeSys V2.3's trace names its first column ``Cycle`` whether it counts task cycles or, with a frequency scan, holds ms.

**traces38** (session 38). A ``rostopic echo -p`` table (:mod:`vcnc.traces.rostopic`) has its time in nanoseconds
(kept to the microsecond from the first row: nanoseconds since 1970 read as a float hold 256 ns) and its positions in
SI units, m or rad, asked for and never assumed; a commanded and a measured position counted in increments of
different names (Yaskawa's reference units beside encoder pulses) are named in the question for their size
(:func:`_unlike_counts`); a text cell of numbers set apart by another delimiter makes its line no row (a row split at
its decimal commas, :data:`_JOINED_NUMBERS`); a header with neither a time column nor a pair names the missing pair
first.
"""

from __future__ import annotations

import csv
import math
import os
import re
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import NamedTuple

import numpy as np

from vcnc.core.axes import ROTARY_AXES
from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError
from vcnc.traces.camonitor import looks_like_camonitor, read_camonitor
from vcnc.traces.columns import (
    COUNT_UNITS,
    LAG_SUFFIX,
    LENGTH_UNITS,
    TIME_UNITS,
    assumed_unit,
    axis_of,
    check_timing,
    check_units,
    is_unit_row,
    length_unit,
    mapped_axes,
    mapping_meta,
    on_uniform_grid,
    parse_columns,
    parse_number,
    parse_time_stamp,
    position_scale,
    read_text,
    unit_in_name,
    unit_named,
    unit_stated,
    with_following_errors,
    within_reach,
)
from vcnc.traces.companion import servo_period_hint
from vcnc.traces.diadem import looks_like_diadem, read_diadem_channels
from vcnc.traces.fptrace import FpTrace, fp_table, fp_trace
from vcnc.traces.gcsarray import GcsArrayHeader, gcs_array_header
from vcnc.traces.halscope import looks_like_halscope, read_halscope
from vcnc.traces.indraworks import looks_like_oscilloscope, read_oscilloscope_signals
from vcnc.traces.names import (
    columns_from_names,
    counted,
    is_sample_number,
    mapping_note,
    no_positions,
    rsi_orientation_note,
)
from vcnc.traces.preamble import stated_count_size, stated_period, stated_turn_travel
from vcnc.traces.rostopic import TIME_UNIT as ROSTOPIC_TIME_UNIT
from vcnc.traces.rostopic import is_rostopic_table
from vcnc.traces.rostopic import unit_options as rostopic_unit_options
from vcnc.traces.rostopic import unit_question as rostopic_unit_question
from vcnc.traces.twincat import looks_like_twincat, read_twincat

__all__ = ["read_delimited", "parse_columns", "looks_like_halscope", "looks_like_twincat", "looks_like_camonitor",
           "TIME_UNITS", "LENGTH_UNITS"]

#: " ": runs of spaces (halsampler), tried last; "|": a pipe, as database and report tools separate columns
#: (tracefuzz; our reading, a delimiter no number holds)
_DELIMITERS = ("\t", ";", ",", "|", " ")
_NAMES = {",": "comma", ";": "semicolon", "\t": "tab", "|": "pipe", " ": "spaces"}
_OVERRUN = "overrun"  # halsampler's line where its FIFO was full and samples were lost


def read_delimited(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                   time_unit: str | None = None, unit: str | None = None,
                   axes: Sequence[str] | None = None, resample: bool = False,
                   sample_time: float | None = None) -> Capture:
    """Read a delimited text trace (module docstring) into a capture.

    Parameters
    ----------
    path : path-like
        The trace.
    columns : mapping, optional
        Capture column -> source column (``{"t": "Time", "x_ref": "PosCmd", "x": "PosAct"}``);
        required except for halscope logs with joint position pins and TwinCAT exports with
        ``SetPos`` / ``ActPos`` channels.
    time_unit : {"s", "ms", "us", "ns"}, optional
        Unit of the time column (default s; TwinCAT: ms).
    unit : {"mm", "um", "nm", "m", "in", "deg"} or a count size ("0.1um"), optional
        Unit of the positions, or the size of one count of positions logged in increments
        (:func:`vcnc.traces.columns.length_unit`) (default mm; "deg" only for rotary axes).
    axes : sequence of str, optional
        Names for the joints of a halscope log (joint order) or the pairs of a TwinCAT export.
    resample : bool
        Interpolate time stamps that are not uniform onto the median step (else an error).
    sample_time : float, optional
        Generic delimited text: the sampling period [s] of a file without a time column, or whose
        ``t`` column counts samples (``halsampler -t``).

    Raises
    ------
    CaptureError
        Naming the file, the line and the columns found: no numeric rows, an unknown column in
        ``columns``, no commanded/measured pair, time going backwards or not uniform, a halsampler
        ``overrun`` without sample numbers.
    """
    src = str(Path(path))
    check_units(time_unit, unit, src)
    text = read_text(path, src)
    kind = ("camonitor" if looks_like_camonitor(text[:4000]) else "halscope" if looks_like_halscope(text[:2000])
            else "twincat" if looks_like_twincat(text[:20000]) else None)
    if sample_time is not None and kind is not None:
        raise CaptureError("--sample-time applies to delimited text without a time column, not to a halscope log, "
                           "a TwinCAT export or a camonitor log (they record their own)", file=src)
    if kind == "camonitor":
        if time_unit is not None:
            raise CaptureError("--time-unit applies to delimited text, not to a camonitor log (time stamps)", file=src)
        return read_camonitor(path, columns=columns, unit=unit, resample=resample)
    if kind == "halscope":
        return read_halscope(path, columns=columns, unit=unit, axes=axes)
    if kind == "twincat":
        return read_twincat(path, columns=columns, time_unit=time_unit, unit=unit, axes=axes, resample=resample)
    gcs = gcs_array_header(text[:40000].lstrip("\ufeff"))
    if gcs is not None:
        return _gcs_array(text.lstrip("\ufeff"), src, gcs, columns=columns, time_unit=time_unit, unit=unit,
                          resample=resample, sample_time=sample_time)
    if looks_like_oscilloscope(text[:4000]):
        return _indraworks(text, src, columns=columns, time_unit=time_unit, unit=unit, resample=resample)
    if looks_like_diadem(text[:40000]):
        return _diadem(text, Path(path), src, columns=columns, time_unit=time_unit, unit=unit, resample=resample,
                       sample_time=sample_time)
    fp = fp_trace(text.lstrip("\ufeff").splitlines())
    if fp is not None:
        return _panasonic_fp(text.lstrip("\ufeff"), src, fp, columns=columns, time_unit=time_unit, unit=unit,
                             resample=resample, sample_time=sample_time)
    return _generic(_matrix_literal(text.lstrip("\ufeff")), src, columns=columns, time_unit=time_unit, unit=unit,
                    resample=resample, sample_time=sample_time)


def _diadem(text: str, path: Path, src: str, *, columns: Mapping[str, str] | None, time_unit: str | None,
            unit: str | None, resample: bool, sample_time: float | None) -> Capture:
    """A DIAdem DAT header (:mod:`vcnc.traces.diadem`): its channels, read from the files beside it, as a table under
    their names and units (``Zeit [s]``, ``Sollposition [deg]``), mapped as any table's; a mapping may name a channel
    without its unit (``t=Zeit``), as the recorder shows it."""
    channels = read_diadem_channels(text, path, src)
    if columns:  # a channel named as DIAdem and KUKA.Trace show it, without its unit
        full = dict(zip(channels.plain, channels.names))
        columns = {k: v if v in channels.names else full.get(v, v) for k, v in columns.items()}
    table = ["\t".join(channels.names)]
    table += ["\t".join(repr(float(v)) for v in row) for row in channels.values.tolist()]
    try:
        capture = _generic("\n".join(table), src, columns=columns, time_unit=time_unit, unit=unit, resample=resample,
                           sample_time=sample_time)
    except CaptureError as exc:  # the table's lines are not the file's: name the channel headers' line instead
        raise CaptureError(exc.message, file=src, line=channels.header_line, expected=exc.expected) from None
    capture.meta["format"] = f"DIAdem DAT header with {', '.join(channels.files) or 'implicit channels'}"
    return capture


def _panasonic_fp(text: str, src: str, fp: FpTrace, *, columns: Mapping[str, str] | None, time_unit: str | None,
                  unit: str | None, resample: bool, sample_time: float | None) -> Capture:
    """A Panasonic FP trace or data logging CSV (:mod:`vcnc.traces.fptrace`): its records as a table under their
    channels' names, a trace's time the sum of its obtaining intervals and a logging's rows periodic, at the sampling
    interval given."""
    if time_unit is not None:
        raise CaptureError("--time-unit applies to a time column; a Panasonic FP trace or logging CSV has none "
                           "(--sample-time S gives its sampling interval)", file=src, line=fp.header + 1)
    capture = _generic(fp_table(text, src, fp, sample_time), src, columns=columns, time_unit=None, unit=unit,
                       resample=resample, sample_time=None if fp.interval else sample_time)
    capture.meta["format"] = f"Panasonic FP {'trace' if fp.interval else 'data logging'} CSV"
    if fp.interval:
        capture.meta["time_unit"] = f"obtaining intervals, {sample_time:.9g} s given for the commonest"
    return capture


def _indraworks(text: str, src: str, *, columns: Mapping[str, str] | None, time_unit: str | None, unit: str | None,
                resample: bool) -> Capture:
    """An IndraWorks oscilloscope XML export (:mod:`vcnc.traces.indraworks`): its signals as a table under their
    names, mapped as any table's."""
    signals = read_oscilloscope_signals(text, src)
    if time_unit is None and unit_in_name(signals.names[0], "time") is None:  # never assumed: ms or s (our reading)
        raise CaptureError(f"the IndraWorks oscilloscope export (signals {signals.names[1:]}) states no unit of its "
                           "time stamps (XValue)", file=src, expected="--time-unit s, ms or us (the oscilloscope's "
                           "time axis)")
    table = ["\t".join(signals.names)]
    table += ["\t".join(repr(float(v)) for v in row) for row in signals.values.tolist()]
    try:
        capture = _generic("\n".join(table), src, columns=columns, time_unit=time_unit, unit=unit, resample=resample,
                           sample_time=None)
    except CaptureError as exc:  # the table's lines are not the file's
        raise CaptureError(exc.message, file=src, expected=exc.expected) from None
    capture.meta["format"] = "Rexroth IndraWorks oscilloscope XML"
    return capture


def _gcs_array(text: str, src: str, gcs: GcsArrayHeader, *, columns: Mapping[str, str] | None,
               time_unit: str | None, unit: str | None, resample: bool, sample_time: float | None) -> Capture:
    """A PI GCS array (:mod:`vcnc.traces.gcsarray`): its rows under its tables' names, a row every ``SAMPLE_TIME``
    seconds (or ``sample_time`` given), positions in the unit given: the file states none."""
    if time_unit is not None:
        raise CaptureError("--time-unit applies to a time column; a PI GCS array has none (SAMPLE_TIME times its "
                           "rows)", file=src)
    period = sample_time if sample_time is not None else gcs.sample_time
    if period is None:
        raise CaptureError("the PI GCS array does not state its SAMPLE_TIME as a number of seconds", file=src,
                           line=gcs.sample_line or gcs.end_line, expected="--sample-time S, the recording period")
    lines = text.splitlines()
    lines[gcs.end_line - 1] = "\t".join(gcs.names)  # the tables' names over their rows
    named, why = (columns, "") if columns else columns_from_names(gcs.names, period_known=True)
    if named is None:
        raise CaptureError("which tables of the PI GCS array are the commanded and measured positions? give --columns "
                           f"x_ref=NAME,x=NAME (SAMPLE_TIME times its rows); tables: {gcs.names} (not read from the "
                           f"names: {why})", file=src, line=gcs.end_line)
    if unit is None:
        raise CaptureError(f"the PI GCS array (data recorder tables {gcs.names}; read as "
                           f"{', '.join(f'{k}={v}' for k, v in named.items())}) does not state the axis' unit: a PI "
                           "axis records in its physical unit, the controller's PUN? answer (mm on most motorised "
                           "stages, um on piezo stages, deg on rotation stages)", file=src, line=gcs.end_line,
                           expected="--unit mm, um or deg (the axis' unit)")
    capture = _generic("\n".join(lines), src, columns=columns, time_unit=None, unit=unit, resample=resample,
                       sample_time=period)
    capture.meta["format"] = "PI GCS array (data recorder)"
    capture.meta["sampling"] = (f"{period:.9g} s, stated in line {gcs.sample_line} (SAMPLE_TIME)" if sample_time is None
                                else f"{period:.9g} s, given")
    return capture


def _split(line: str, delimiter: str) -> list[str]:
    """The cells of a line; a cell in double quotes may hold the delimiter (``"1,5"``)."""
    line = line.rstrip("\r\n")
    if delimiter == " ":
        return line.split()
    if '"' not in line:
        return line.split(delimiter)
    try:
        return next(csv.reader([line], delimiter=delimiter, quotechar='"', strict=True))
    except (csv.Error, StopIteration):
        return line.split(delimiter)


def _value(cell: str, comma: bool) -> float:
    """A cell as a number, or a time stamp as seconds (:func:`parse_time_stamp`); ValueError."""
    try:
        return parse_number(cell, comma or "," in cell)  # a comma inside a quoted cell is a decimal comma
    except ValueError:
        if ":" not in cell:
            raise
        return parse_time_stamp(cell)


def _numbers(cells: list[str], comma: bool) -> list[float] | None:
    """The cells as numbers (NaN for empty ones), or None when one is not a number."""
    try:
        return [_value(c, comma) for c in cells]
    except ValueError:
        return None


#: Cells that hold no value, as numpy, pandas and MATLAB write a missing number.
_NAN_WORDS = frozenset({"nan", "-nan", "+nan"})


#: A cell of numbers set apart by another delimiter (``0  13.322  13.322  0`` between the decimal commas of a row
#: separated by spaces, split at its commas): no text, a sign of the wrong delimiter.
_JOINED_NUMBERS = re.compile(r"[+-]?[\d.,]*\d(?:\s*[\s|;\t]\s*[+-]?[\d.,]*\d)+")


def _row(cells: list[str], comma: bool) -> tuple[list[float], list[int], list[int]] | None:
    """A row of the table: its cells as numbers (NaN for empty, ``NaN`` and text cells), the places of its text
    cells and of its ``NaN`` cells; None for a line that is no row (no number, text cells as many as the numbers: a
    header, or a text cell that is numbers set apart by another delimiter, :data:`_JOINED_NUMBERS`: trace_fuzz seeds
    44000332 and 44000455 were read split at their decimal commas). A ``NaN`` cell is a missing value, not text
    (:func:`_nan_cells`)."""
    vals, text, missing = [], [], []
    for i, c in enumerate(cells):
        try:
            vals.append(_value(c, comma))
        except ValueError:
            if _JOINED_NUMBERS.fullmatch(c.strip()):
                return None
            vals.append(float("nan"))
            (missing if c.strip().lower() in _NAN_WORDS else text).append(i)
    n = sum(v == v for v in vals)
    return (vals, text, missing) if n and (not text or (n >= 2 and len(text) < n)) else None


def _nan_cells(data: np.ndarray, found: dict[int, list[tuple[int, int, str]]],
               text_cells: dict[int, tuple[int, str]]) -> None:
    """The ``NaN`` cells of each column (``found``: column -> (row, file line, cell)) that lie between two of its
    numbers, added to ``text_cells`` as a value lost in the middle of a recording (an error when the column is used);
    those before its first number or after its last are a channel not yet, or no longer, recorded, as the ODrive
    GUI's export writes it, and their rows are skipped like rows with an empty cell (our reading)."""
    for c, cells in found.items():
        numbers = np.flatnonzero(~np.isnan(data[:, c]))
        inside = [(line, cell) for row, line, cell in cells if numbers.size and numbers[0] < row < numbers[-1]]
        if inside and c not in text_cells:
            text_cells[c] = inside[0]


def _numeric_block(lines: list[str], delimiter: str) -> tuple[int, int, int, bool, int]:
    """``(first, last, width, decimal_comma, text cells)`` of the last block of rows in ``lines`` (first = -1
    when there are none); lines after it that are no rows are a trailer (module docstring). With a tab or
    ``;`` delimiter a comma in a number is a decimal comma."""
    comma = delimiter != ","
    first, last, width, texts = -1, -1, 0, 0
    for i in range(len(lines) - 1, -1, -1):
        s = lines[i].strip()
        if not s:  # blank lines between the rows of numbers are skipped, as in _table
            continue
        if (s.upper() == "EOF" and first < 0) or s.lower() == _OVERRUN:
            continue
        cells = _split(lines[i], delimiter)
        row = _row(cells, comma) if len(cells) >= 2 and (not width or len(cells) == width) else None
        if row is None:
            if first < 0:
                continue  # a trailer line below the rows
            break
        first, width, texts = i, len(cells), texts + len(row[1])
        last = i if last < 0 else last
    return first, last, width, comma, texts


class _Table(NamedTuple):
    """The table of a delimited trace."""

    header: list[str] | None  #: the names above the rows, or None
    units_row: list[str] | None  #: a row of units under the names, or None
    data: np.ndarray  #: rows x columns, NaN for empty and text cells
    row_lines: list[int]  #: the file line of each row
    delimiter: str
    overruns: list[int]  #: file lines of halsampler's overrun marks
    text: dict[int, tuple[int, str]]  #: column -> (file line, cell) of its first text cell
    lines: list[str]  #: the file's lines
    header_line: int | None = None  #: the 1-based line of the names (above a row of units), when found above the rows


def _aligned_blanks(lines: list[str]) -> list[str]:
    """``lines`` with ``nan`` written into the blank cells of a table whose columns are aligned by spaces.

    A recorder printing fixed-width columns leaves a channel's cell blank before its first sample or after its last
    (trace_fuzz's ``spaces`` + ``ends:empty`` layout): split at runs of spaces that row has fewer cells, and the block
    of rows ended there (seed 35100 case 105730: 'only one row of numbers' among 400 rows). Where every full row of
    numbers ends (or starts) each cell at the same places, a shorter row's cells are put in the columns they end (start)
    at, and its blank cells read as missing values, as a ``NaN`` cell (:func:`_nan_cells`). Lines with a tab, ``;`` or
    ``|`` and rows whose cells do not fall on the columns are left alone (tracewild10). Each column is aligned at an
    edge of its own: ``%-6d`` sample numbers start at one place, ``%9.3f`` positions end at one (tracewild37, seeds
    41000762 and 41000969)."""
    words = [line.split() if not any(c in line for c in "\t;|") else [] for line in lines]
    counts = [len(w) if w and w[0][0] in "+-.0123456789" else 0 for w in words]  # rows, roughly
    width = max(counts, default=0)
    # one number is a row only beside a full row: a row of two columns, one blank (trace_fuzz seed 43000558)
    counts = [c if c != 1 or any(0 <= j < len(counts) and counts[j] == width for j in (i - 1, i + 1)) else 0
              for i, c in enumerate(counts)]
    if width < 2 or all(c in (0, width) for c in counts):
        return lines  # every row as wide as the widest: nothing blank (the common case, one split a line)

    def cells_at(i: int) -> list[tuple[int, int]] | None:
        spans = [m.span() for m in re.finditer(r"\S+", lines[i])]
        return spans if _numbers([lines[i][a:b] for a, b in spans], True) is not None else None

    rows = [(i, sp) for i, c in enumerate(counts) if c and (sp := cells_at(i)) is not None]
    width = max((len(sp) for _, sp in rows), default=0)
    full = [sp for _, sp in rows if len(sp) == width]
    if len(full) < 2 or len(full) == len(rows):
        return lines
    edges = [next((e for e in (1, 0) if len({sp[k][e] for sp in full}) == 1), None) for k in range(width)]
    if None in edges:
        return lines
    places = [full[0][k][e] for k, e in enumerate(edges)]
    out = list(lines)
    for i, sp in rows:
        at = [[k for k, e in enumerate(edges) if p[e] == places[k]] for p in sp]
        ks = [k[0] for k in at if len(k) == 1]
        if len(sp) < width and len(ks) == len(sp) and ks == sorted(set(ks)):
            cells = dict(zip(ks, (lines[i][a:b] for a, b in sp)))
            out[i] = " ".join(cells.get(k, "nan") for k in range(width))
    return out


def _table(text: str, src: str) -> _Table:
    """The header, units and rows of the last block of rows in ``text`` (module docstring)."""
    lines = _aligned_blanks(text.splitlines())
    blocks = [(d, *_numeric_block(lines, d)) for d in _DELIMITERS]
    # the delimiter that makes the longest block of rows (then the one with fewest text cells, then the widest)
    delimiter, first, last, width, comma, _ = max(blocks, key=lambda b: (b[1] >= 0 and b[3] >= 2, b[2] - b[1],
                                                                           -b[5], b[3]))
    if first < 0 or width < 2:
        k = next((i for i, line in enumerate(lines) if line.strip()), None)  # what the file holds instead
        first_text = lines[k].strip() if k is not None else ""
        raise CaptureError("no rows of numbers separated by tab, ';', ',', '|' or spaces" + (
            _hex_dump(lines) or _grouped_hint(lines)), file=src,
                           line=k + 1 if k is not None else None, text=first_text[:80] if k is not None else None)
    rows, row_lines, overruns, text_cells = [], [], [], {}
    nan_cells: dict[int, list[tuple[int, int, str]]] = {}
    for i in range(first, last + 1):
        if lines[i].strip().lower() == _OVERRUN:
            overruns.append(i + 1)
        if not lines[i].strip() or lines[i].strip().upper() in ("EOF", _OVERRUN.upper()):
            continue
        cells = _split(lines[i], delimiter)
        vals, where, missing = _row(cells, comma) or ([float("nan")] * width, [], [])
        for k in where:
            text_cells.setdefault(k, (i + 1, cells[k].strip()))
        for k in missing:
            nan_cells.setdefault(k, []).append((len(rows), i + 1, cells[k].strip()))
        rows.append(vals)
        row_lines.append(i + 1)
    data = np.array(rows, dtype=float)
    _nan_cells(data, nan_cells, text_cells)
    # a delimiter ending every row ('0;1;2;') but not the names, or the names but not the rows
    trailing = bool(np.isnan(data[:, -1]).all()) and width - 1 not in text_cells

    def names_at(j: int | None) -> list[str] | None:
        cells = _header_cells(lines[j], delimiter) if j is not None else []
        if delimiter == " " and j is not None and len(cells) != width:
            spaced = _spaced_names(lines[j])
            cells = spaced if len(spaced) == width else cells
        cells = _channel_groups(cells, width - trailing) or cells
        if len(cells) == width + 1 and not cells[-1]:
            cells = cells[:-1]
        if len(cells) == width - 1 and trailing:
            cells = [*cells, ""]
        return cells if len(cells) == width else None

    def above(j: int | None) -> int | None:
        return next((k for k in range(j - 1, -1, -1) if lines[k].strip()), None) if j is not None else None

    header = units_row = None
    j = above(first)
    for k in (j, above(j)):  # a row whose cells are grouped by thousands ends the rows: no names (tracewild37)
        if k is not None and (hint := _grouped_hint([lines[k]])):
            raise CaptureError("the line above the rows of numbers is no header" + hint, file=src, line=k + 1)
    if j is not None:
        header = names_at(j)
        if header is not None and is_unit_row(header):  # names above a row of units
            units_row = header
            j = above(j)
            header = names_at(j)
        if header is not None and len(set(header)) < len(header):
            header = _grouped_names(names_at(above(j)), header)
    header_line = j + 1 if header is not None and j is not None else None
    if header is None:
        header, units_row = _keyed_rows(lines[:first], delimiter, width, units_row)
    return _Table(_time_named(header, units_row), units_row, data, row_lines, delimiter, overruns, text_cells, lines,
                  header_line)


#: A MATLAB matrix literal's opening bracket before the first row's numbers, and what ends a row: ``;``, or ``]``
#: (``];``) after the last.
_MATRIX_OPEN = re.compile(r"^\s*\[\s*(?=[-+.\d])")
_MATRIX_END = re.compile(r"\]\s*;?\s*$")
_MATRIX_ROW_END = re.compile(r"\s*(?:\]\s*;?|;)\s*$")


def _matrix_literal(text: str) -> str:
    """The rows of a table written as a MATLAB matrix literal (``[0 0.000 1000 0;`` ... ``676 5.985 0 7]``: rows
    separated by ``;`` between brackets, MATLAB documentation "Creating, Concatenating, and Expanding Matrices") without
    its brackets and semicolons, so that they read as rows of numbers; ECP Executive's "Export Raw Data" (Educational
    Control Products' servo plants, Model 210/220/205) writes its table so under a line of names (our reading of its
    exports). Only one line may open the matrix, a later one must close it, and every line between must be a row of
    numbers (a line opening with ``[2024-05-01 ...]`` or ``[-]`` above a header ``Ist [um]`` is no matrix: its
    brackets stay); any other text is returned as it is."""
    lines = text.splitlines()
    opens = [i for i, line in enumerate(lines) if _MATRIX_OPEN.match(line)]
    if len(opens) != 1:
        return text
    end = next((i for i in range(opens[0], len(lines)) if _MATRIX_END.search(lines[i])), None)
    if end is None:
        return text
    rows = [_MATRIX_ROW_END.sub("", _MATRIX_OPEN.sub("", lines[i])) for i in range(opens[0], end + 1)]
    if not all(_number_cells(row) for row in rows):
        return text
    lines[opens[0]:end + 1] = rows
    return "\n".join(lines)


def _number_cells(row: str) -> bool:
    """Whether a matrix row holds only numbers, separated by spaces or commas as MATLAB's are (or nothing)."""
    try:
        [parse_number(c) for c in re.split(r"[\s,]+", row.strip()) if c]
    except ValueError:
        return False
    return True


def _spaced_names(line: str) -> list[str]:
    """The names of a header line whose names hold single spaces and are set apart by runs of spaces (ECP
    Executive's ``Sample   Time     Commanded Pos   Encoder 1 Pos``), for rows of numbers separated by spaces."""
    stripped = line.strip()
    stripped = stripped[1:].strip() if stripped[:1] in ("#", "%") else stripped
    return [c for c in re.split(r"\s{2,}|\t", stripped) if c]


_HEX = re.compile(r"[0-9A-Fa-f]{4,16}")


def _hex_dump(lines: list[str]) -> str:
    """What a file of one hexadecimal number per line is: Mitsubishi's CNC sampling output with "#6 OUTPUT FORM" 1
    writes each channel's sample as 8 hexadecimal digits on a line of its own ("Data Output Format", M700/M800 and C70
    instruction manuals, "Sampling"), which no column layout can read; its decimal output (form 0) is a table. Our
    reading, so that a word of hex letters (``Added``, ``DEADBEEF``) is no dump: the first lines (up to 8) are all
    such numbers of one width, and one of them holds a digit and one a letter."""
    first = [s for s in (line.strip() for line in lines[:200]) if s][:8]
    if (len(first) < 2 or not all(_HEX.fullmatch(s) and len(s) == len(first[0]) for s in first)
            or not any(c.isdigit() for s in first for c in s) or all(s.isdigit() for s in first)):
        return ""
    return (f": lines of one hexadecimal number each ({first[0]}) are a hexadecimal dump (Mitsubishi's CNC sampling "
            "with output form 1 writes one channel's sample per line); save the sampling in decimal (output form 0), "
            "a row per sample")


#: A number with both marks, digits grouped by thousands before the decimal mark: ``4,263.66``, ``-1.234.567,5``;
#: or a whole number with two marks or more of one kind, which no decimal mark reads (``20,296,998``, tracewild37).
_GROUPED_DECIMAL = re.compile(r"[+-]?[1-9]\d{0,2}(?:,\d{3})+\.\d+|[+-]?[1-9]\d{0,2}(?:\.\d{3})+,\d+"
                              r"|[+-]?[1-9]\d{0,2}(?:,\d{3}){2,}|[+-]?[1-9]\d{0,2}(?:\.\d{3}){2,}")


def _grouped_hint(lines: list[str]) -> str:
    """Why cells such as ``4,263.66`` are no numbers: digits grouped by thousands, which a spreadsheet's number
    format writes and no trace tool seen does (TwinCAT Scope's export settings choose a separator and a decimal mark,
    no grouping; TNCscope, SINUMERIK, halscope write plain numbers). vcnc reads no grouping (a ``1,234`` without a
    decimal part would read as 1.234 with a decimal comma): the hint names the first such cell; else ``""``."""
    for i, line in enumerate(lines[:200]):
        cell = next((c for c in re.split(r'[\s;|"]+', line) if _GROUPED_DECIMAL.fullmatch(c)), None)
        if cell is not None:
            where = f" (line {i + 1})" if len(lines) > 1 else ""
            return (f": {cell!r}{where} writes its digits grouped by thousands (a spreadsheet's number format); vcnc "
                    "reads no digit grouping: save the numbers without thousands separators")
    return ""


def _time_named(header: list[str] | None, units_row: list[str] | None) -> list[str] | None:
    """The header with its one blank name over a time unit named ``time``: maxon EPOS Studio's data recorder
    export leaves the time column's name blank and writes ``ms`` under it (``;Velocity actual value averaged``
    over ``ms;rpm;%``; our reading of its exports)."""
    if header is None or units_row is None or "time" in header:
        return header
    blank = [i for i, (h, u) in enumerate(zip(header, units_row))
             if not h.strip() and unit_named(u.strip("[]() "), "time") is not None]
    return [("time" if i == blank[0] else h) for i, h in enumerate(header)] if len(blank) == 1 else header


#: First cells of the header rows of recorders that label each row (Hioki memory recorders' text files: ``"SIGNAL",
#: "TIME", "ACH1"`` and ``"VERT_UNITS", "S", "V"``, instruction manual 8841/8807, "Text File Internal Format";
#: Panasonic's data logging CSV: "Data name", "Unit" rows, FPWIN Pro7 help "CSV format").
_NAME_KEYS = frozenset({"signal", "signals", "name", "names", "data name", "channel", "channels", "label", "labels"})
_UNIT_KEYS = frozenset({"vert_units", "vertunits", "unit", "units"})


def _keyed_rows(above: list[str], delimiter: str, width: int,
                units_row: list[str] | None) -> tuple[list[str] | None, list[str] | None]:
    """The names and units of a table from labelled rows above it (``"SIGNAL","TIME","ACH1"`` over rows of two
    numbers: the label is a cell more than the rows have), the nearest of each; (None, ``units_row``) without a
    labelled row of names."""
    names = None
    for line in reversed(above):
        cells = _header_cells(line, delimiter)
        cells = cells[:-1] if cells and not cells[-1] else cells
        key = cells[0].strip().strip('"').lower() if cells else ""
        if len(cells) != width + 1:
            continue
        if key in _NAME_KEYS and names is None:
            names = [c.strip().strip('"') for c in cells[1:]]
        elif key in _UNIT_KEYS and units_row is None:
            units_row = [c.strip().strip('"') for c in cells[1:]]
    return (names, units_row) if names is not None else (None, units_row)


_CHANNEL = re.compile(r"CH\d+", re.IGNORECASE)


def _channel_groups(cells: list[str], width: int) -> list[str] | None:
    """A header that spreads each channel's name over several cells, ``point,CH0, Axis 1, Motor present desired
    position, CH1, ...`` above rows of one value per channel, as dls-pmac-control's Power PMAC gather export writes it
    (``ppmacgather.py``: ``f"CH{i}, Axis {axisNo}, {desc}, "`` per channel): the names joined per channel
    (``CH0 Axis 1 Motor present desired position``), the first cell kept; None for any other header."""
    cells = cells[:-1] if cells and not cells[-1] else cells
    n = width - 1
    if n < 1 or len(cells) <= width or (len(cells) - 1) % n:
        return None
    size = (len(cells) - 1) // n
    groups = [cells[1 + k * size:1 + (k + 1) * size] for k in range(n)]
    if not all(_CHANNEL.fullmatch(g[0]) for g in groups):
        return None
    return [cells[0], *(" ".join(g) for g in groups)]


def _grouped_names(groups: list[str] | None, names: list[str]) -> list[str]:
    """Names that repeat under a row of group names (``X;;Y;`` over ``Soll;Ist;Soll;Ist``, a spreadsheet's
    merged cells) joined with their group (``X Soll``), empty groups filled from the left; the names as
    they are without such a row, or when joining leaves them repeated."""
    if groups is None or is_unit_row(groups):
        return names
    filled = []
    for g in groups:
        filled.append(g or (filled[-1] if filled else ""))
    joined = [f"{g} {n}".strip() for g, n in zip(filled, names)]
    return joined if len(set(joined)) == len(joined) else names


def _header_cells(line: str, delimiter: str) -> list[str]:
    """The cells of a line above the numbers, also behind a comment mark (``# time x_cmd x_fb``: gnuplot,
    numpy.savetxt; ``% ...``: MATLAB)."""
    stripped = line.lstrip()
    return [c.strip() for c in _split(stripped[1:] if stripped[:1] in ("#", "%") else line, delimiter)]


def _column(name: str | int, header: list[str] | None, width: int, src: str, line: int) -> int:
    """Index of a source column named ``name`` (a header name, or a 1-based number, also as an int)."""
    name = str(name)
    if header is not None and name in header:
        return header.index(name)
    if name.isdigit() and 1 <= int(name) <= width:
        return int(name) - 1
    found = header if header is not None else "(no header line: give 1-based column numbers)"
    raise CaptureError(f"column {name!r} not found; columns found: {found}", file=src, line=line)


#: A line of a drive's object dictionary: index in hexadecimal, subindex, value (``0x6065,  0, 4294967295``).
_OBJECT_ENTRY = re.compile(r"\s*0x[0-9A-Fa-f]{4}\s*[,;\t ]\s*\d{1,3}\s*[,;\t ]")


def _check_parameter_list(text: str, src: str) -> None:
    """An error for a drive's parameter list, one object a line (index, subindex, value), as SOMANET drives' OBLAC
    configuration export writes it (``META,FORMAT,2``, then ``0x2001,  0, 3693``; CiA 301's object indices): values of
    settings, not samples over time (our reading of saikasener/altinay's LiftMotor.csv, beside its recordings); and
    Rexroth IndraWorks' parameter save, whose first line is ``SERCOS-ASCII`` (anderssandstrom/tc_target_drive's
    indradrive/params.par: a block per S-/P- parameter, ``|`` between blocks)."""
    all_lines = text.splitlines()
    lines = [ln for ln in all_lines if ln.strip() and not ln.lstrip().startswith("#")]
    if lines and lines[0].strip().lstrip("\ufeff") == "SERCOS-ASCII":
        raise CaptureError("a drive's parameter file, not a recording: 'SERCOS-ASCII' in line 1 begins Rexroth "
                           "IndraWorks' parameter save (S-/P- parameters, each with its name, attributes, unit and "
                           "value); vcnc identifies a drive from a trace of its commanded and measured position (the "
                           "drive tool's oscilloscope export)", file=src, line=1)
    entries = [n for n, ln in enumerate(all_lines, 1) if _OBJECT_ENTRY.match(ln)]
    if len(entries) >= 10 and 2 * len(entries) >= len(lines):
        first = all_lines[entries[0] - 1].strip()
        raise CaptureError(f"a drive's parameter list, not a recording: {len(entries)} lines of object index, "
                           f"subindex and value (line {entries[0]}: {first!r}) are settings, no samples over time; "
                           "vcnc identifies a drive from a trace of its commanded and measured position (the drive "
                           "tool's recorder or scope export)", file=src, line=entries[0])


#: The header ecmc prints above its axis diagnostics in an IOC's console log (``2023/01/23 16:08:46.963 ecmc::  Ax
#: PosSet     PosAct     PosErr ...``, ecmccfg's examples/test/subst_hw_axes/readme.md).
_ECMC_DIAGNOSTICS = re.compile(r"ecmc::\s+Ax\s+PosSet\s+PosAct\s+PosErr\b")


def _check_ecmc_diagnostics(text: str, src: str) -> None:
    """An error for an EPICS IOC's console log with ecmc's axis diagnostics (a line per axis now and then among the
    IOC's messages, each after a time stamp and ``ecmc::``): no table of samples; the axis' ``PosSet``/``PosAct``
    records logged with camonitor are (:mod:`vcnc.traces.camonitor`). Our reading of ecmccfg's logs (tracewild8)."""
    m = _ECMC_DIAGNOSTICS.search(text)
    if m is None:
        return
    line = text.count("\n", 0, m.start()) + 1
    rows = sum(1 for ln in text.splitlines() if re.search(r"ecmc::\s+\d+\s+-?\d", ln))
    raise CaptureError(f"an EPICS IOC's console log with ecmc's axis diagnostics ({rows} lines 'ecmc:: Ax PosSet "
                       "PosAct PosErr ...' among its messages), no table of samples: log the axis' PosSet and PosAct "
                       "records with camonitor, which vcnc reads", file=src, line=line)


def _check_no_recording(text: str, src: str) -> None:
    """Errors for text that is no recording: a drive's parameters, an IOC's log with ecmc's diagnostics."""
    _check_parameter_list(text, src)
    _check_ecmc_diagnostics(text, src)


def _check_rows(data: np.ndarray, lines: list[str], row_lines: list[int], src: str) -> None:
    """An error for a table of one row: MATLAB's and numpy's savetxt write a vector as one row; among more than 20
    lines of text it is a program's printout or log with one line of numbers in it (tracewild8)."""
    if data.shape[0] >= 2:
        return
    _check_ragged_rows(lines, row_lines[0], src)
    grouped = _grouped_hint(lines)  # rows whose cells are grouped by thousands are no rows (trace_fuzz 42000917)
    text_lines = sum(1 for ln in lines if ln.strip()) - 1
    if text_lines > 20 and not grouped:
        raise CaptureError(f"only one row of numbers ({data.shape[1]} values) among {text_lines} lines of text: no "
                           "table of samples (a program's printed output or a log?); a trace has a row per sample and "
                           "a column per channel", file=src, line=row_lines[0])
    raise CaptureError(f"only one row of numbers ({data.shape[1]} values)" + (grouped or (
        ": a trace has a row per sample and a column per channel"
        + (" (a saved row vector? transpose it)" if data.shape[1] > 3 else ""))), file=src, line=row_lines[0])


def _check_ragged_rows(lines: list[str], line: int, src: str, *, fewest: int = 2) -> None:
    """An error for a row of numbers (of ``fewest`` cells or more) above the rows from ``line`` that holds another
    number of cells: a table separated by spaces whose blank cells are not aligned on its columns
    (:func:`_aligned_blanks` places only those that are), read as one row (trace_fuzz seeds 41000762 and 41000969 were
    named a printout with one row among text), or whose rows from ``line`` were read without the names above the
    short one (seed 43000558: 'no header line')."""
    above = next((k for k in range(line - 2, -1, -1) if lines[k].strip()), None)
    if above is None:
        return
    cells = lines[above].split()
    width = len(lines[line - 1].split())
    if len(cells) >= fewest and len(cells) != width and _numbers(cells, True) is not None:
        raise CaptureError(f"rows of numbers with {len(cells)} and {width} cells (lines {above + 1} and {line}): a "
                           "cell left blank in columns separated by spaces that are not aligned cannot be placed; "
                           "expected the same number of cells in every row (write the missing value as nan, or "
                           "separate the columns with ';' or tab)", file=src, line=above + 1)


def _named_columns(table: _Table, hline: int | None, known: bool, src: str) -> dict[str, str]:
    """The mapping read from a table's names (:func:`vcnc.traces.names.columns_from_names`; ``known``: the sampling
    period is stated or given), else the error saying why: no position among the names, rows of another width above
    the rows (a blank cell that cannot be placed), or the question asking for ``--columns``."""
    header, data = table.header, table.data
    columns, why = (columns_from_names(header, period_known=known) if header is not None
                    else (None, "the file has no header line"))
    if columns is not None:
        return columns
    if header is not None and not known and why.startswith("no column is named as time"):
        paired, no_pair = columns_from_names(header, period_known=True)
        if paired is None:  # the positions are missing too: say so first (a VESC log names its encoder alone)
            why = f"{no_pair}; and {why}"
    if header is not None and no_positions(header):
        raise CaptureError(f"no position in the file: its columns {header} are time, sample numbers or other "
                           "quantities (speeds, currents, voltages, torques... by their names or units); vcnc "
                           "identifies a drive from a trace of its commanded and its measured position",
                           file=src, line=hline)
    if header is None:
        _check_ragged_rows(table.lines, table.row_lines[0], src, fewest=1)
    raise CaptureError("which columns are time, commanded and measured position? give --columns "
                       f"t=NAME,x_ref=NAME,x=NAME; columns found: {header or f'{data.shape[1]} unnamed'} "
                       f"(not read from the names: {why})" + _sample_step_hint(header, data)
                       + (servo_period_hint(src) if header is None and not known else ""), file=src, line=hline)


def _generic(text: str, src: str, *, columns: Mapping[str, str] | None, time_unit: str | None,
             unit: str | None, resample: bool, sample_time: float | None) -> Capture:
    _check_no_recording(text, src)
    table = _table(text, src)
    header, units_row, data, row_lines, delimiter, overruns = table[:6]
    lines = table.lines
    _check_rows(data, lines, row_lines, src)
    above = lines[:row_lines[0] - 1]
    hline = table.header_line or len(above) or None  # the names' line; None without a header above the first row
    period = stated_period(above) if sample_time is None and time_unit is None else None
    guessed = not columns
    if not columns:
        columns = _named_columns(table, hline, period is not None or sample_time is not None, src)
    axes = mapped_axes(columns, src)
    idx = {k: _column(v, header, data.shape[1], src, hline) for k, v in columns.items()}
    for k, c in idx.items():
        if c in table.text:  # a column of text ('Starting', 'Layer 1 Up') is only an error when used
            line, cell = table.text[c]
            raise CaptureError(f"not a number in column {c + 1} ({columns[k]!r}, used as {k})"
                               + _grouped_hint([cell]), file=src, line=line, column=c + 1, text=cell)
    stated: dict[str, str] = {}
    if period is not None and ("t" not in idx or (header is not None and is_sample_number(header[idx["t"]]))):
        sample_time = float(period.value)
        stated["sampling"] = f"{sample_time:.9g} s, stated in line {period.line} ({period.text!r})"
    _check_time_options(columns, time_unit, sample_time, overruns, src)
    used = data[:, list(idx.values())]
    keep = ~np.isnan(used).any(axis=1)
    if keep.sum() < 2:
        raise CaptureError(f"fewer than two rows with all of {list(columns.values())}", file=src)
    d = data[keep]
    lines_kept = [n for n, k in zip(row_lines, keep) if k]
    units = _header_units(header, units_row, idx, time_unit, unit)
    if is_rostopic_table(header):
        _rostopic_units(units, columns, src, hline)
    _check_digit_grouping(d, idx, columns, lambda: [_split(lines[n - 1], delimiter) for n in lines_kept], lines_kept,
                          src, in_counts=_in_counts(header, units_row, idx, above, unit, units))
    stated.update(_count_sizes(units, header, units_row, idx, above, columns, src, hline))
    if unit is not None and (gear := _unlike_counts(_counted_columns(header, units_row, idx))):
        stated["count_units"] = f"unit {unit} given for both{gear}"
    stated.update(_turn_travel(units, above))
    if unit is None:
        stated.update(unit_stated({k: u for k, u in units.items() if k in idx}, "stated in the file"))
    stamped = "t" in idx and ":" in _split(lines[lines_kept[0] - 1], delimiter)[idx["t"]]
    if units["t"] is None and period is not None and sample_time is None and not stamped:
        units["t"] = _unit_of_step(d[:, idx["t"]], float(period.value))
        if units["t"] is not None:
            stated["time_unit_from_period"] = (f"{units['t']}: the step of {columns['t']!r} is the sampling period "
                                               f"stated in line {period.line} ({period.text!r})")
    time_stated = units["t"] is not None
    units["t"] = units["t"] or "s"
    if stamped:
        units["t"] = "s"  # time stamps are read as seconds, whatever the unit given
    if sample_time is None:
        t = d[:, idx["t"]] * TIME_UNITS[units["t"]]
    else:  # a column of sample numbers, or none: the row's place
        if "t" in idx:
            _check_sample_numbers(d[:, idx["t"]], columns["t"], src, hline)
        t = np.round((d[:, idx["t"]] if "t" in idx else np.flatnonzero(keep)) * sample_time, 12)
    if stamped or (units["t"] == "ns" and np.abs(d[:, idx["t"]]).max() > 2.0 ** 53):
        # seconds since 1970 hold 0.24 us, and nanoseconds since 1970 (ROS) were read to 256 ns: to the microsecond
        # from the first stamp
        with np.errstate(over="ignore", invalid="ignore"):
            t = np.round(t - t[0], 6)
    within_reach(t, f"time {columns.get('t', 'row number')!r}", "s", src, lines_kept)
    _increasing(t, src, lines_kept)
    if sample_time is None and not stamped:
        t, rounded = _rounded_stamps(t, lambda: [_split(lines[n - 1], delimiter)[idx["t"]] for n in lines_kept],
                                     TIME_UNITS[units["t"]], src)
        stated.update(rounded)
    time_known = time_stated or stamped or sample_time is not None
    _check_guessed_time(t, columns, time_known, src, hline, guessed=guessed)

    def scaled(k: str) -> np.ndarray:
        with np.errstate(over="ignore"):
            values = d[:, idx[k]] * position_scale([axis_of(k)], units[k], src)
        within_reach(values, f"{columns[k]!r} ({units[k] or assumed_unit(k)})", assumed_unit(k), src, lines_kept)
        return values

    t, (ref, second), how = on_uniform_grid(t, [np.column_stack([scaled(f"{a}_ref") for a in axes]),
                                               np.column_stack([scaled(a if a in idx else a + LAG_SUFFIX)
                                                                for a in axes])], src, lines_kept, resample=resample)
    meas, lag = with_following_errors(axes, columns, ref, second, float(t[1] - t[0]), src, line=hline,
                                      expected="commanded - actual (vcnc's contract for a <axis>_lag column)")
    shown = sorted({units[k] or assumed_unit(k) for k in idx if k != "t"})
    time_meta = ("time stamps" if stamped else units["t"] if sample_time is None else
                 f"sample numbers x {sample_time:.9g} s" if "t" in idx else f"rows every {sample_time:.9g} s")
    meta = {"format": f"delimited text ({_NAMES[delimiter]})", "time_unit": time_meta,
            "unit": ",".join(shown), **mapping_meta(axes, columns), **lag, **how, **stated}
    if guessed:
        meta["columns"] = _guessed_note(columns, units, time_known) + rsi_orientation_note(header or [])
    return Capture(t=t, axes=tuple(axes), reference=ref, measured=meas, meta=meta, source=src)


#: A number with its digits grouped by thousands (``1,234``, ``-12.345.678``), which a decimal point or comma at
#: the same place would also read.
_GROUPED = re.compile(r"[+-]?[1-9]\d{0,2}(?:([.,])\d{3})(?:\1\d{3})*")


def _check_digit_grouping(d: np.ndarray, idx: Mapping[str, int], columns: Mapping[str, str],
                          cells: Callable[[], list[list[str]]], row_lines: Sequence[int], src: str, *,
                          in_counts: Mapping[str, str]) -> None:
    """An error for a position column whose numbers look grouped by thousands: every cell with a point or comma
    is ``1,234`` / ``1.234`` (three digits after each), beside whole numbers below 1000 (``523``) written
    without one, in a file whose other columns write the other decimal mark (``1.234`` beside ``0,5``), or in a
    column of counts (``[inc]``, or any position under a stated count size, ``Resolution: 0.5 um``: a count is a whole
    number, :func:`_in_counts`). A
    spreadsheet's digit grouping writes such a column of counts (``"1,234"`` with the delimiter ``,``, ``1.234`` in
    a German export); read as decimals it is a thousand times too small, and a column of decimals with three places
    always has the mark (tracefuzz; our reading). The cells are only read when the numbers are whole in
    thousandths (also when all are whole: ``"100,000"`` nm beside ``"0"``, tracewild37)."""
    with np.errstate(over="ignore", invalid="ignore"):  # a number beyond reach is the reach check's error
        suspect = [k for k in idx if k != "t" and _whole(d[:, idx[k]] * 1000) and (d[:, idx[k]] != 0).any()]
    if not suspect:
        return
    rows = cells()
    for k in suspect:
        col = [r[idx[k]].strip().strip('"') for r in rows]
        marked = [j for j, c in enumerate(col) if "." in c or "," in c]
        whole = [c for c in col if c and "." not in c and "," not in c]
        if not marked or not all(_GROUPED.fullmatch(col[j]) for j in marked):
            continue
        j = marked[0]
        mark = "," if "," in col[j] else "."
        other = "." if mark == "," else ","
        beside = next((c.strip().strip('"') for r in rows for i, c in enumerate(r) if i != idx[k] and other in c), None)
        if whole or beside is not None or k in in_counts:
            like = (f"whole numbers like {whole[0]!r}" if whole else f"{beside!r} in another column" if beside
                    else in_counts[k])
            raise CaptureError(f"{k}={columns[k]!r}: {col[j]!r} beside {like} reads as digits "
                               "grouped by thousands as well as a decimal; vcnc reads no digit grouping",
                               file=src, line=row_lines[j], text=col[j],
                               expected="numbers without thousands separators (the export's number format)")


def _whole(values: np.ndarray) -> bool:
    """True when every value is a whole number (to rounding)."""
    return bool(np.all(np.abs(values - np.round(values)) < 1e-6))


def _rounded_stamps(t: np.ndarray, stamps: Callable[[], list[str]], scale: float,
                    src: str) -> tuple[np.ndarray, dict[str, str]]:
    """Time [s] on a uniform step when its stamps are one rounded to the digits printed (``0.0063694``,
    ``0.012739``: MATLAB's five significant digits; the steps then differ by more than the timing check
    allows) and the ``meta["time_rounded"]`` note; else ``t`` as it is. Our reading: a uniform step fitted by
    least squares weighted by the printed resolution, every stamp within the rounding of its last digit
    (twice it, for the fit)."""
    try:
        check_timing(t - t[0], src)
        return t, {}
    except CaptureError:
        pass
    cells = stamps()  # the printed stamps, read only when the timing check fails
    k = np.arange(t.size)
    half = np.array([_half_digit(c) for c in cells]) * scale
    step, start = np.polyfit(k, t, 1, w=1.0 / half)  # the stamps printed with more digits weigh more
    grid = start + k * step
    if not step > 0 or not np.all(np.abs(t - grid) <= 2 * half):
        return t, {}
    return grid, {"time_rounded": f"time stamps printed to {_digits(cells)} digits, read as a uniform step of "
                                  f"{step:.9g} s (they are within the rounding of their last digit)"}


def _half_digit(cell: str) -> float:
    """Half a unit of the last digit of a printed number (``0.012739`` -> 5e-7; ``1.27e-2`` -> 5e-5)."""
    mantissa, _, exponent = cell.strip().lower().replace(",", ".").partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 0.5 * 10.0 ** (int(exponent or 0) - decimals)


def _digits(cells: list[str]) -> int:
    """The most significant digits printed in the cells (for the note)."""
    return max(len(c.strip().lower().partition("e")[0].replace(".", "").replace(",", "").lstrip("-+0")) for c in cells)


def _unit_of_step(t: np.ndarray, period: float) -> str | None:
    """The time unit (of :data:`TIME_UNITS`) in which the median step of a time column is the stated sampling
    ``period`` [s] (to 0.1 %), or None."""
    step = float(np.median(np.diff(t))) if t.size > 1 else 0.0
    return next((u for u, scale in TIME_UNITS.items() if abs(step * scale - period) <= 1e-3 * period), None)


def _count_sizes(units: dict[str, str | None], header: list[str] | None, units_row: list[str] | None,
                 idx: Mapping[str, int], above: list[str], columns: Mapping[str, str], src: str,
                 line: int) -> dict[str, str]:
    """Positions logged in counts (:func:`vcnc.traces.names.counted`, or a count unit in the units row) without
    a unit given: scaled by the size of one count the preamble states (:mod:`vcnc.traces.preamble`), set in
    ``units``, and the ``meta["count_size"]`` note; without one an error asking for ``--unit``. A stated count
    size above positions that name no unit at all is an error too: counts or mm, the file does not say which
    (tracefuzz; our reading: a drive tool stating its resolution logs counts, a column without a unit may be either,
    and a wrong guess is a factor of thousands)."""
    marked = _counted_columns(header, units_row, idx)
    counts = {k: c for k, c in marked.items() if units[k] is None}
    plain = [k for k in idx if k != "t" and units[k] is None and k not in marked]
    size = stated_count_size(above) if counts or plain else None
    if plain and size is not None:
        raise CaptureError(f"line {size.line} states the size of one count ({size.text!r}), and "
                           f"{', '.join(f'{k}={columns[k]!r}' for k in plain)} state no unit: counts or mm?",
                           file=src, line=line, expected=f"--unit {size.value} (counts) or --unit mm")
    if not counts:
        return {}
    if size is None:
        k, c = next(iter(counts.items()))
        raise CaptureError(f"{k}={columns[k]!r} is logged in increments ({c!r}) and the file does not state their "
                           "size" + _unlike_counts(counts),
                           file=src, line=line, expected="--unit with the size of one count (e.g. --unit 0.1um, "
                                                         "0.0001in, 0.001deg)")
    for k in counts:
        units[k] = str(size.value)
    return {"count_size": f"{size.value} per count for {', '.join(counts)}, stated in line {size.line} "
                          f"({size.text!r})"}


def _unlike_counts(counts: Mapping[str, str]) -> str:
    """The note for an axis whose commanded and measured positions may count increments of different sizes, else
    ``""``: counts of different names (Yaskawa's "Input Reference Pulse Counter" in reference units beside its
    "Feedback Pulse Counter" in encoder pulses), or pulses on both sides (Panasonic MINAS' command pulse counter and
    Mitsubishi's cumulative command pulses count the controller's pulses before the drive's electronic gear, their
    feedback pulses the encoder's): one ``--unit`` sizes both, right only with a gear of 1:1."""
    def name(c: str) -> str:
        return c.lower().rstrip("s")

    for k, c in counts.items():
        other = next((k2 for k2 in (k[:-4], k[:-4] + LAG_SUFFIX) if k.endswith("_ref") and k2 in counts), None)
        if other is not None and (name(counts[other]) != name(c) or name(c) in _PULSES):
            return (f"; {k} counts {c!r} and {other} {counts[other]!r}: --unit gives one size to both, right only "
                    "where one of each is as long (an electronic gear between the command's and the encoder's "
                    "pulses makes them differ)")
    return ""


#: Count units of a drive's pulse counters (:func:`_unlike_counts`).
_PULSES = frozenset({"pulse", "pl"})


def _in_counts(header: list[str] | None, units_row: list[str] | None, idx: Mapping[str, int],
               above: list[str], unit: str | None, units: Mapping[str, str | None]) -> dict[str, str]:
    """The position columns whose values are counts, each with what says so (for a message): a count unit in its name
    or units row (:func:`_counted_columns`), or, for every position, a count size the preamble states (``Resolution:
    0.5 um``: the file logs counts, whatever ``--unit`` says; a count is a whole number, so ``19.725`` in every cell
    there is 19725 grouped by thousands, never 19.725 counts). A plain unit given (``--unit mm``, not a count size
    such as ``0.5um``) says the positions are no counts, and so does a column's own plain unit without one given
    (``X Soll [mm]``: the resolution is the encoder's, the column mm). ``units``: each column's unit as
    :func:`_header_units` reads it."""
    marked = {k: f"a count unit ({c!r})" for k, c in _counted_columns(header, units_row, idx).items()}
    size = stated_count_size(above)
    if size is not None and (unit is None or unit_named(unit, "length") is None):
        said = f"counts (line {size.line} states {size.text!r})"
        marked.update({k: said for k in idx if k != "t" and k not in marked and units[k] not in LENGTH_UNITS})
    return marked


def _counted_columns(header: list[str] | None, units_row: list[str] | None, idx: Mapping[str, int]) -> dict[str, str]:
    """The position columns logged in counts, by their names (:func:`vcnc.traces.names.counted`) or a count unit in
    the units row, each with its count unit."""
    out = {}
    for k in idx:
        cell = units_row[idx[k]].strip("[]() ").lower() if units_row is not None else ""
        c = (counted(header[idx[k]]) if header is not None else None) or (cell if cell in COUNT_UNITS else None)
        if k != "t" and c is not None:
            out[k] = c
    return out


#: Motor angle units per turn, for a linear axis logged in its motor's angle (:func:`_turn_travel`).
_PER_TURN = {"rev": 1.0, "rad": 2 * math.pi, "deg": 360.0}


def _turn_travel(units: dict[str, str | None], above: list[str]) -> dict[str, str]:
    """Positions of a linear axis in turns, radians or degrees of its motor (``[turns]``, ``[deg]``) scaled by the
    travel of one turn the lines above the table state (a screw's lead, over a gear ratio:
    :func:`vcnc.traces.preamble.stated_turn_travel`), set in ``units``, and the ``meta["turn_travel"]`` note; without
    a lead nothing (the unit's error asks for it)."""
    turning = [k for k, u in units.items() if k != "t" and axis_of(k) not in ROTARY_AXES and u is not None
               and (length_unit(u) or ("", 0.0))[0] in _PER_TURN]
    travel = stated_turn_travel(above) if turning else None
    if travel is None:
        return {}
    mm, said = travel
    for k in turning:
        per_unit = mm / _PER_TURN[length_unit(str(units[k]))[0]]
        units[k] = f"{per_unit:.12g}mm"
    return {"turn_travel": f"{mm:.9g} mm per motor turn for {', '.join(turning)} ({said})"}


def _check_time_options(columns: Mapping[str, str], time_unit: str | None, sample_time: float | None,
                        overruns: list[int], src: str) -> None:
    """A time column or a sampling period, not a time unit with a period; an ``overrun`` only with
    sample numbers (module docstring)."""
    if sample_time is not None and not sample_time > 0:
        raise CaptureError(f"--sample-time must be > 0 s, not {sample_time!r}", file=src)
    if "t" not in columns and sample_time is None:
        raise CaptureError("--columns needs t=NAME (the time column), or --sample-time S for a file without one "
                           "(halsampler)" + servo_period_hint(src), file=src)
    if sample_time is not None and time_unit is not None:
        raise CaptureError("--time-unit and --sample-time: with --sample-time the t column counts samples; give one",
                           file=src)
    if overruns and "t" not in columns:
        raise CaptureError("'overrun': halsampler lost samples here (its FIFO was full) and, without a column of "
                           "sample numbers (halsampler -t), how many is not known", file=src, line=overruns[0])


def _header_units(header: list[str] | None, units_row: list[str] | None, idx: Mapping[str, int],
                  time_unit: str | None, unit: str | None) -> dict[str, str | None]:
    """The unit of each mapped column: as given, else as its header name ends (``Time [ms]``,
    ``PosAct (µm)``) or the row of units under the names says, else s for time and mm (None)
    for positions."""
    def named(k: str, kind: str) -> str | None:
        by_name = unit_in_name(header[idx[k]], kind) if header is not None else None
        return by_name or (unit_named(units_row[idx[k]].strip("[]() "), kind) if units_row is not None else None)

    out: dict[str, str | None] = {"t": time_unit or (named("t", "time") if "t" in idx else None)}
    for k in idx:
        if k != "t":
            out[k] = unit or named(k, "length")
    return out


def _rostopic_units(units: dict[str, str | None], columns: Mapping[str, str], src: str, line: int | None) -> None:
    """A ``rostopic echo -p`` table's units (:mod:`vcnc.traces.rostopic`): its time columns count nanoseconds, and
    positions without a unit given are an error asking for m or rad (never assumed mm)."""
    if "t" in units and units["t"] is None:
        units["t"] = ROSTOPIC_TIME_UNIT
    if any(units[k] is None for k in units if k != "t"):
        raise CaptureError(rostopic_unit_question(columns), file=src, line=line,
                           expected=rostopic_unit_options(columns))


def _guessed_note(columns: Mapping[str, str], units: Mapping[str, str | None], time_known: bool) -> str:
    """The capture's ``meta["columns"]`` of a mapping read from the header names: the mapping, and the units
    assumed because the file does not state them (s, mm; deg on a rotary axis)."""
    assumed = ([f"t in {units['t']}"] if not time_known else []) + [
        f"{k} in {assumed_unit(k)}" for k in columns if k != "t" and units[k] is None]
    return (mapping_note("header", columns)
            + (f"; not stated in the file, assumed {', '.join(assumed)}" if assumed else "")
            + " (--columns, --time-unit, --unit set them)")


def _check_sample_numbers(numbers: np.ndarray, name: str, src: str, line: int | None) -> None:
    """A column taken as sample numbers (with a sampling period) counts samples: its median step is 1 (halsampler
    -t; a lost sample leaves a larger step here and there). One that steps by another number holds something else:
    CoDeSys V2.3 writes the time in ms in its ``Cycle`` column when the trace has a frequency scan (names.py), and a
    sampling period times those would stretch the time by the step (our reading: refuse rather than guess)."""
    step = _sample_step(numbers)
    if step != 1.0:
        raise CaptureError(f"the column {name!r}, taken as sample numbers with the sampling period, steps by "
                           f"{step:.6g}, not 1: it holds no sample numbers (a time in ms, as CoDeSys' 'Cycle' with a "
                           "frequency scan?)", file=src, line=line,
                           expected=f"--columns t={name} with --time-unit ms|us|s and no --sample-time")


def _sample_step(numbers: np.ndarray) -> float:
    """The median step of a column of sample numbers, its blank cells left out (1.0 for fewer than two)."""
    return float(np.nanmedian(np.diff(numbers))) if numbers.size > 1 else 1.0


def _sample_step_hint(header: list[str] | None, data: np.ndarray) -> str:
    """A note for the question of a header whose one column of sample numbers does not step by 1 (CoDeSys' ``Cycle``
    holding ms, :func:`_check_sample_numbers`): it is no count of samples but likely a time; else ``""``."""
    samples = [j for j, h in enumerate(header or []) if is_sample_number(h)]
    if len(samples) != 1:
        return ""
    step = _sample_step(data[:, samples[0]])
    if step == 1.0 or not math.isfinite(step):
        return ""
    name = (header or [])[samples[0]]
    return (f"; {name!r} steps by {step:.6g}, not 1: a time rather than sample numbers? give --columns t={name},... "
            "with --time-unit ms|us|s")


def _check_guessed_time(t: np.ndarray, columns: Mapping[str, str], stated: bool, src: str, line: int | None, *,
                        guessed: bool) -> None:
    """A time column whose unit neither the file nor ``--time-unit`` states is taken in seconds, unless its
    step is 0.1 or more: no drive trace is sampled that slowly (servo loops close every 0.05-10 ms; a
    logging PC every few ms), so such a column counts ms, samples or something else (our reading). This holds for a
    column read from its name (``guessed``) and for one mapped by ``--columns``, which says which column holds the
    time, not its unit (a drive logger's headerless rows with ``--columns t=1,..``: ms stamps stepping by 10 were
    read as a 10 s sampling, a 1001-sample record of 2.8 hours, realtrace11). No time column: nothing to check."""
    if "t" not in columns:
        return
    step = float(np.median(np.diff(t)))
    if not stated and step >= 0.1:
        how = "read from its name" if guessed else "mapped by --columns"
        raise CaptureError(f"the time column {columns['t']!r} ({how}) steps by {step:.6g} and the file does not "
                           "state its unit: seconds would be a sampling far too slow for a drive trace", file=src,
                           line=line, expected="--time-unit ms|us|s, or --sample-time S when it counts samples")


def _increasing(t: np.ndarray, src: str, row_lines: list[int]) -> None:
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        raise CaptureError(f"time does not increase: {t[k]:.9g} s after {t[k - 1]:.9g} s", file=src, line=row_lines[k])
