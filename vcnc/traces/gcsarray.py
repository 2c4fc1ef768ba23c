"""PI (Physik Instrumente) GCS array files: a PI controller's data recorder, saved by PIMikroMove or PIPython.

Layout, as PI documents it (PIPython documentation, ``pitools.savegcsarray`` / ``readgcsarray``: "a PI specific file
format to store datasets, such as values recorded with the data recorder (e.g. actual and target position of an
axis) ... understood by all PI programs (such as e.g. PIMikroMove)"; the answer to ``DRR?``, controller manuals such
as MS249E C-863.12 "DRR? (Get Recorded Data Values)", "GCS array format", SM146E):

- header lines ``# KEY = value``: ``TYPE``, ``SEPARATOR`` (the data's separator as an ASCII code: 9 tab, 32 space),
  ``DIM`` (the number of tables: columns), ``SAMPLE_TIME`` (seconds between two recorded points: PIPython's
  timescale is ``SAMPLE_TIME * i``), ``NDATA``, and ``NAME0`` ... ``NAME<DIM-1>``, each table's name (its record
  option: "Commanded position of axis", "Actual position of axis", "Position error of axis", C-863 manual, DRC;
  the documentation's example: "Real Position", "Target Position"); ``# REM`` lines and a ``[GCS_ARRAY...]`` line
  may come first;
- ``# END_HEADER``, then one line per recorded point, a value per table, no time column.

:func:`gcs_array_header` reads the header; the delimited reader (:mod:`vcnc.traces.delimited`) reads the rows under
the names, timed by ``SAMPLE_TIME``. The file does not state the axis' unit: a PI axis is in its physical unit, the
controller's ``PUN?`` answer (mm on most motorised stages, µm on piezo stages, deg on rotation stages), so the reader
asks for ``--unit`` instead of assuming one (our reading: a wrong unit is worse than a question).
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

__all__ = ["GcsArrayHeader", "gcs_array_header"]

_KEY = re.compile(r"^\s*#\s*([A-Z_]+[0-9]*)\s*=\s*(.*?)\s*$")
_END = re.compile(r"^\s*#\s*END_HEADER\s*$")
_NAME = re.compile(r"NAME(\d+)")


class GcsArrayHeader(NamedTuple):
    """What a GCS array's header states."""

    names: list[str]  #: the tables' names, NAME0 first
    sample_time: float | None  #: seconds between two points, or None when not stated as a positive number
    sample_line: int | None  #: the 1-based line of ``SAMPLE_TIME``
    end_line: int  #: the 1-based line of ``# END_HEADER``
    separator: str  #: the data's separator (tab or space)


def gcs_array_header(text: str) -> GcsArrayHeader | None:
    """The header of a PI GCS array file (module docstring), or None when ``text`` is not one: it needs a
    ``# END_HEADER`` line after ``# DIM = n`` and ``# NAME0 ... NAME<n-1>`` lines."""
    keys: dict[str, tuple[str, int]] = {}
    for i, line in enumerate(text.splitlines()[:400]):
        if _END.match(line):
            return _header(keys, i + 1)
        m = _KEY.match(line)
        if m:
            keys.setdefault(m.group(1), (m.group(2), i + 1))
    return None


def _header(keys: dict[str, tuple[str, int]], end_line: int) -> GcsArrayHeader | None:
    try:
        dim = int(keys["DIM"][0])
    except (KeyError, ValueError):
        return None
    names = [keys.get(f"NAME{k}", ("", 0))[0] for k in range(dim)]
    if dim < 1 or not all(names) or any(int(m.group(1)) >= dim for m in map(_NAME.fullmatch, keys) if m):
        return None
    sample, line = keys.get("SAMPLE_TIME", ("", None))
    try:
        period: float | None = float(sample)
    except ValueError:
        period = None
    if period is not None and not (math.isfinite(period) and period > 0):
        period = None
    separator = " " if keys.get("SEPARATOR", ("9", 0))[0].strip() == "32" else "\t"
    return GcsArrayHeader(names, period, line, end_line, separator)
