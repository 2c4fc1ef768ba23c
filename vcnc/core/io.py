"""File output: atomic (nothing half-written is left behind on failure), and numeric tables as text."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TextIO

import numpy as np

__all__ = ["atomic_path", "atomic_dir", "write_rows"]

#: Rows formatted per call of :func:`write_rows`: large enough that the per-call cost vanishes, small enough
#: that the text of one chunk stays a few MB.
ROWS_PER_CHUNK = 2000

#: Rows per call of the compiled formatter (:mod:`vcnc.core.numtext`): its buffer takes 27 bytes per number.
COMPILED_ROWS_PER_CHUNK = 5000


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it into place.

    On any exception the temporary file is removed and ``path`` is left untouched.
    """
    final = Path(path)
    final.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{final.name}.", suffix=".part", dir=final.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    os.chmod(tmp_path, 0o666 & ~_umask())  # mkstemp makes 0600; output files get the usual mode
    try:
        yield tmp_path
        os.replace(tmp_path, final)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


@contextlib.contextmanager
def atomic_dir(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary directory; on success its files are moved into ``path``.

    Files already in ``path`` that the job did not write are kept. On failure nothing in
    ``path`` changes.
    """
    final = Path(path)
    final.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{final.name}.", suffix=".part", dir=final.parent))
    os.chmod(tmp, 0o777 & ~_umask())
    try:
        yield tmp
        final.mkdir(parents=True, exist_ok=True)
        for item in tmp.iterdir():
            target = final / item.name
            if target.is_dir() and not target.is_symlink():
                shutil.rmtree(target)
            os.replace(item, target)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_rows(out: TextIO, data: np.ndarray | Sequence[np.ndarray], fmt: Sequence[str], *,
               delimiter: str = ",") -> None:
    """Write the rows of the 2-D ``data`` to ``out``, one ``%``-format per column, joined by ``delimiter``.

    ``data`` may also be 2-D blocks of columns side by side (the same number of rows): their table is then
    gathered a chunk of rows at a time, never whole (a long capture's is hundreds of MB).

    The same text as ``np.savetxt(out, table, fmt=fmt, delimiter=delimiter)`` (which formats every row with
    ``%`` in turn), byte for byte. Columns of ``%.<P>g`` (P <= 15) and ``%d`` with a one-character delimiter
    are formatted by compiled code (:mod:`vcnc.core.numtext`, 3-4x faster on a capture's numbers than the
    following); other formats by one ``%`` on the row format repeated over a chunk of rows, so that no per-row
    Python work remains (``benchmarks/interpolation.py`` and ``benchmarks/simulate_program.py`` measure them)."""
    blocks = [data] if isinstance(data, np.ndarray) else [np.asarray(b) for b in data]
    n_rows = len(blocks[0]) if blocks else 0
    if (not blocks or any(b.ndim != 2 or len(b) != n_rows for b in blocks)
            or sum(b.shape[1] for b in blocks) != len(fmt)):
        raise ValueError(f"data of shape(s) {[b.shape for b in blocks]} for {len(fmt)} column formats")

    def table(start: int, stop: int) -> np.ndarray:
        return blocks[0][start:stop] if len(blocks) == 1 else np.hstack([b[start:stop] for b in blocks])

    from vcnc.core.numtext import column_codes, format_chunks

    codes = column_codes(fmt) if len(delimiter) == 1 else None
    if codes is not None:
        for text in format_chunks(table, n_rows, codes, fmt, delimiter, COMPILED_ROWS_PER_CHUNK):
            out.write(text)
        return
    row = delimiter.join(fmt) + "\n"
    for start in range(0, n_rows, ROWS_PER_CHUNK):
        chunk = table(start, start + ROWS_PER_CHUNK)
        out.write((row * len(chunk)) % tuple(chunk.ravel().tolist()))
