"""Results of a sweep on disk: an append-only journal while running, one table at the end.

While a sweep runs, every finished point is appended as one JSON line to the journal
``<output>.partial.jsonl`` beside the output (flushed at once, so it survives the sweep's
process being killed; a torn last line is ignored on reading). At the end - also after an
interruption or an error - the previous output, the journal and the new rows are merged, one row
per point id, into ``results.parquet`` or ``results.csv`` (written atomically), and only then is
the journal removed. Resuming reads both files, so no finished point is computed twice or lost.
"""

from __future__ import annotations

import csv
import json
import logging
import os
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import pyarrow as pa

from vcnc.core.errors import InputError
from vcnc.core.io import atomic_path
from vcnc.core.jsonsafe import plain

__all__ = ["ResultStore", "COLUMNS", "FORMATS", "read_results", "rows_to_table"]

log = logging.getLogger(__name__)

FORMATS: tuple[str, ...] = (".parquet", ".csv")

#: result columns and their types, in file order; point functions may add further columns
COLUMNS: dict[str, pa.DataType] = {
    "id": pa.string(),
    "status": pa.string(),
    "error": pa.string(),
    "machine": pa.string(),
    "toolpath": pa.string(),
    "feed": pa.float64(),
    "gain": pa.float64(),
    "noise": pa.float64(),
    "effect": pa.string(),
    "magnitude": pa.float64(),
    "seed": pa.int64(),
    "axis": pa.string(),
    "profile": pa.string(),
    "samples": pa.int64(),
    "tracking_max_um": pa.float64(),
    "tracking_rms_um": pa.float64(),
    "contour_max_um": pa.float64(),
    "contour_rms_um": pa.float64(),
    "ident_fit_rms_um": pa.float64(),
    "ident_pole_error_pct": pa.float64(),
    "ident_param_error_pct": pa.float64(),
    "diag_effects": pa.string(),
    "diag_hit": pa.bool_(),
    "t_simulate_s": pa.float64(),
    "t_identify_s": pa.float64(),
    "t_point_s": pa.float64(),
    "worker": pa.string(),
}

#: seconds between fsyncs of the journal (each line is flushed at once regardless)
_FSYNC_PERIOD_S = 2.0


def rows_to_table(rows: Iterable[Mapping[str, Any]]) -> pa.Table:
    """A pyarrow Table of result rows: :data:`COLUMNS` typed, further columns inferred."""
    rows = list(rows)
    names = list(COLUMNS)
    for r in rows:
        for k in r:
            if k not in COLUMNS and k not in names:
                names.append(k)
    arrays = []
    for name in names:
        values = [plain(r.get(name)) for r in rows]
        if name in COLUMNS:
            arrays.append(pa.array(values, type=COLUMNS[name]))
            continue
        try:
            arrays.append(pa.array(values))
        except (pa.ArrowInvalid, pa.ArrowTypeError):
            arrays.append(pa.array([None if v is None else str(v) for v in values], type=pa.string()))
    return pa.Table.from_arrays(arrays, names=names)


def read_results(path: str | os.PathLike[str]) -> pa.Table:
    """Read a results file (``.parquet`` or ``.csv``) into a pyarrow Table."""
    rows = _read_table_rows(Path(path))
    return rows_to_table(rows)


def _check_format(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise InputError(
            f"results file must end in {' or '.join(FORMATS)}", file=str(path), text=path.suffix or path.name
        )
    return suffix


def _read_table_rows(path: Path) -> list[dict[str, Any]]:
    suffix = _check_format(path)
    try:
        if suffix == ".parquet":
            import pyarrow.parquet as pq

            table = pq.read_table(path)
            rows = table.to_pylist()
        else:
            rows = _read_csv_rows(path)
    except (OSError, pa.ArrowException, csv.Error, UnicodeDecodeError, ValueError) as exc:
        raise InputError(
            f"cannot read the existing results ({exc}); it is not overwritten - move it away or choose another "
            f"output", file=str(path)
        ) from None
    if rows and "id" not in rows[0]:
        raise InputError("existing file is not a sweep result (no 'id' column); it is not overwritten",
                         file=str(path))
    return rows


def _read_csv_rows(path: Path) -> list[dict[str, Any]]:
    import pyarrow.csv as pcsv

    with open(path, newline="") as fh:
        header = next(csv.reader(fh), None)
    if not header:
        return []
    types = {k: t for k, t in COLUMNS.items() if k in header}
    table = pcsv.read_csv(
        path,
        convert_options=pcsv.ConvertOptions(
            column_types=types, strings_can_be_null=True, true_values=["true", "True"],
            false_values=["false", "False"],
        ),
    )
    return table.to_pylist()


class ResultStore:
    """Results of one sweep: what is already done, the journal, and the final table.

    Parameters
    ----------
    output : path
        ``*.parquet`` or ``*.csv``.
    """

    def __init__(self, output: str | os.PathLike[str]) -> None:
        self.output = Path(output)
        self.format = _check_format(self.output)
        self.journal = self.output.with_name(self.output.name + ".partial.jsonl")
        self._fh: Any = None
        self._last_sync = 0.0

    # ------------------------------------------------------------------ reading
    def load(self) -> dict[str, dict[str, Any]]:
        """Rows already finished: the output file's, then the journal's (later rows win)."""
        done: dict[str, dict[str, Any]] = {}
        if self.output.exists():
            for r in _read_table_rows(self.output):
                done[str(r["id"])] = r
        if self.journal.exists():
            for r in self._read_journal():
                done[str(r["id"])] = r
        return done

    def _read_journal(self) -> list[dict[str, Any]]:
        rows = []
        with open(self.journal, encoding="utf-8", errors="replace") as fh:
            for n, line in enumerate(fh, start=1):
                if not line.strip():
                    continue
                try:
                    r = json.loads(line)
                except json.JSONDecodeError:
                    # a line torn by a crash; its point is simply computed again
                    log.warning("%s:%d: incomplete line ignored", self.journal, n)
                    continue
                if isinstance(r, dict) and "id" in r:
                    rows.append(r)
        return rows

    # ------------------------------------------------------------------ writing
    def open(self) -> None:
        """Open the journal for appending (a torn last line is closed off first)."""
        self.output.parent.mkdir(parents=True, exist_ok=True)
        needs_newline = False
        if self.journal.exists() and self.journal.stat().st_size:
            with open(self.journal, "rb") as fh:
                fh.seek(-1, os.SEEK_END)
                needs_newline = fh.read(1) != b"\n"
        self._fh = open(self.journal, "a", encoding="utf-8")
        if needs_newline:
            self._fh.write("\n")
            self._fh.flush()

    def append(self, row: Mapping[str, Any]) -> None:
        """Append one finished point to the journal (flushed at once)."""
        if self._fh is None:
            self.open()
        self._fh.write(json.dumps({k: plain(v) for k, v in row.items()}, default=str) + "\n")
        self._fh.flush()
        now = time.monotonic()
        if now - self._last_sync > _FSYNC_PERIOD_S:
            os.fsync(self._fh.fileno())
            self._last_sync = now

    def close(self) -> None:
        """Close the journal (synced to disk)."""
        if self._fh is not None:
            self._fh.flush()
            os.fsync(self._fh.fileno())
            self._fh.close()
            self._fh = None

    def consolidate(self) -> pa.Table:
        """Merge output and journal into the output (atomic), then remove the journal.

        Returns the table written. If writing fails, both files stay as they were.
        """
        self.close()
        rows = list(self.load().values())
        table = rows_to_table(rows)
        with atomic_path(self.output) as tmp:
            if self.format == ".parquet":
                import pyarrow.parquet as pq

                pq.write_table(table, tmp)
            else:
                _write_csv(table, tmp)
        if self.journal.exists():
            self.journal.unlink()
        return table


def _write_csv(table: pa.Table, path: Path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(table.column_names)
        for r in table.to_pylist():
            w.writerow(["" if v is None else ("true" if v is True else "false" if v is False else repr(v)
                                              if isinstance(v, float) else v) for v in r.values()])
