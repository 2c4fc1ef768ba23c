"""Panasonic FP data logging and trace CSV files (FPWIN Pro7, FP7, FP0H, FP-XH): their records as a table of positions.

The layout (FP0H user manual, 1.3.3 "File Format (For Trace Function)"; FPWIN Pro7 help, "CSV format" of data
logging): optional comment lines, then a line ``Date,Time,Obtaining interval,1,2,...`` (the channels numbered), then
header rows whose first three cells are blank, each enabled or left out in the tool: the data names (a register or
variable, ``DT100``), an arbitrary comment (``Command position``), ``MOMENT`` (the value at the sample), the data
format (``Signed 32-bit``, ``INT``) and the unit (``um``); then one row per record: date, time of day to the second,
the interval since the record before in counts, and the values. A trace's stop trigger is a record of its own,
``STOP TRG`` in the place of the values, with the interval since the record before it.

The count of an interval is 10 us in the FP0H manual and 10 ms in FPWIN Pro7's help, so it is never assumed: the
rows are read with the sampling period given (``--sample-time S``), the period of the interval most records have;
the time of each row is then the sum of the intervals before it, scaled by that period (the trigger's own interval
counted, our reading: the records after it are counted from it). The names and the comment of a channel make its
name (its number where the file names it by none: ``--columns x_ref=1,x=2``), its unit row its unit; the rows go to
:mod:`vcnc.traces.delimited` as any table's, on the file's own lines and in its own columns (the time in the place
of the intervals). A data logging CSV has no intervals (``Date,Time,1,2``, the channels numbered; records stamped to
the second): its records are periodic, one every ``--sample-time S``.
"""

from __future__ import annotations

import re
from collections import Counter
from typing import NamedTuple

from vcnc.core.errors import CaptureError
from vcnc.traces.columns import is_unit_row

__all__ = ["FpTrace", "fp_trace", "fp_table"]

#: The first three names of the header line, in English and in Japanese (FPWIN Pro7 help in both languages).
_KEYS = (("date", "time", "obtaining interval"), ("\u65e5\u4ed8", "\u6642\u523b", "\u53d6\u5f97\u9593\u9694"))
#: The cell a stop trigger's record holds in the place of the values.
_TRIGGER = re.compile(r"^\s*(?:STOP\s*TRG|\u505c\u6b62\u30c8\u30ea\u30ac)\s*$", re.IGNORECASE)
#: A row of the values' kinds (``MOMENT``; KW Watcher's "momentary or difference value").
_KINDS = frozenset({"moment", "momentary", "difference", "diff"})
#: A row of data formats (``Signed 32-bit``, IEC types, KW Watcher's ``S16``/``US32``/``FLT``).
_FORMAT = re.compile(r"^(?:(?:un)?signed\s*\d+\s*-?\s*bits?|u?s\d+|hex\d+|flt|bits?|char\d*|u?[sd]?int|l?real|"
                     r"[dl]?word|bool|float|double)$", re.IGNORECASE)


class FpTrace(NamedTuple):
    """Where the parts of an FP trace or logging CSV are (0-based line indices)."""

    delimiter: str
    header: int  #: the ``Date,Time,Obtaining interval`` (or ``Date,Time``) line
    first_row: int  #: the first record
    channels: int  #: the number of channels
    interval: bool  #: whether the records state their obtaining interval (a trace; logging's are periodic)


def _cells(line: str, delimiter: str) -> list[str]:
    return [c.strip().strip('"').strip() for c in line.split(delimiter)]


def fp_trace(lines: list[str]) -> FpTrace | None:
    """The layout of an FP trace or logging CSV's lines (module docstring), or None for another file: a header line
    ``Date,Time,Obtaining interval`` over channels, or ``Date,Time`` over channels numbered ``1,2,..`` (logging)."""
    for i, line in enumerate(lines[:200]):
        for delimiter in (",", ";", "\t"):
            cells = _cells(line, delimiter)
            cells = cells[:-1] if len(cells) > 1 and not cells[-1] else cells
            keys = tuple(c.lower() for c in cells[:3])
            logging = keys[:2] in {k[:2] for k in _KEYS} and cells[2:] == [str(n) for n in range(1, len(cells) - 1)]
            if (keys in _KEYS and len(cells) > 3) or (logging and len(cells) > 2):
                first = next((k for k in range(i + 1, len(lines)) if _cells(lines[k], delimiter)[0]), len(lines))
                return FpTrace(delimiter, i, first, len(cells) - 3 + logging, not logging)
    return None


def _header_rows(lines: list[str], fp: FpTrace) -> tuple[list[str], list[str] | None]:
    """The channels' names (a channel's text rows joined: its data name and comment; its number where it has none)
    and units, or None."""
    texts: list[list[str]] = []
    units = None
    skip = 2 + fp.interval
    for line in lines[fp.header + 1:fp.first_row]:
        cells = (_cells(line, fp.delimiter)[skip:] + [""] * fp.channels)[:fp.channels]
        words = [c for c in cells if c]
        if not words:
            continue
        if is_unit_row(cells):
            units = cells
        elif not all(c.lower() in _KINDS or _FORMAT.match(c) for c in words):
            texts.append(cells)
    names = [" ".join(row[k] for row in texts if row[k]) or f"{k + 1}" for k in range(fp.channels)]
    return names, units


def _records(lines: list[str], fp: FpTrace, src: str) -> tuple[dict[int, tuple[int, list[str]]], int]:
    """Each record's line -> (its time in counts of the interval, its values), and the interval most records have
    (1 for logging, one count per record); a stop trigger's record left out, its interval counted."""
    skip = 2 + fp.interval
    rows: dict[int, tuple[int, list[str]]] = {}
    total = 0
    intervals: Counter[int] = Counter()
    for k in range(fp.first_row, len(lines)):
        cells = _cells(lines[k], fp.delimiter)
        if len(cells) <= skip or not lines[k].strip():
            continue
        try:
            count = int(cells[2]) if fp.interval else 1
        except ValueError:
            raise CaptureError("the obtaining interval of a Panasonic FP trace record is no whole number of counts",
                               file=src, line=k + 1, column=3, text=cells[2][:40]) from None
        total += count if rows else 0
        if _TRIGGER.match(cells[skip]):
            continue
        if rows:
            intervals[count] += 1
        rows[k] = (total, cells[skip:skip + fp.channels])
    return rows, intervals.most_common(1)[0][0] if intervals else 0


def fp_table(text: str, src: str, fp: FpTrace, sample_time: float | None) -> str:
    """The FP trace or logging CSV ``text`` as a table on its own lines and in its own columns: ``Time [s]`` in the
    place of the obtaining interval (blank date and time of day), the channels under their names (and units), the
    other lines blank (module docstring).

    Raises
    ------
    CaptureError
        Without ``sample_time`` (naming the interval most records have), or an interval that is no whole number.
    """
    lines = text.splitlines()
    names, units = _header_rows(lines, fp)
    rows, step = _records(lines, fp, src)
    if len(rows) < 2:
        raise CaptureError(f"a Panasonic FP trace or data logging CSV (channels {names}) with {len(rows)} record(s) "
                           "below its header; expected a record of date, time and values per line", file=src,
                           line=fp.header + 1)
    if sample_time is None or step <= 0:
        what = (f"data logging/trace CSV (Date, Time, Obtaining interval; channels {names}): its records are {step} "
                "counts apart, and the count is 10 us in the FP0H manual and 10 ms in FPWIN Pro7's help, never "
                "assumed" if fp.interval else
                f"data logging CSV (Date, Time; channels {names}): its records are stamped to the second")
        interval = f" ({step} counts)" if fp.interval else ""
        raise CaptureError(f"a Panasonic FP {what}", file=src, line=fp.header + 1,
                           expected=f"--sample-time S, the sampling interval set for the "
                           f"{'trace' if fp.interval else 'logging'}{interval}")
    out = [""] * len(lines)
    named = [f"{n} [{u}]" if units and u else n for n, u in zip(names, units or [""] * len(names))]
    out[fp.first_row - 1] = "\t".join(["Date", "Clock", "Time [s]"][:2 + fp.interval] + named)
    for k, (count, values) in rows.items():
        out[k] = "\t".join(["nan", "nan", repr(count * sample_time / step)][:2 + fp.interval] + values)
    return "\n".join(out)
