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

from vcnc.core.errors import InputError

__all__ = ["atomic_path", "atomic_dir", "check_output", "check_distinct_outputs", "write_rows"]

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
    with _cannot_write(final, "file"):
        final.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{final.name}.", suffix=".part", dir=final.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    os.chmod(tmp_path, 0o666 & ~_umask())  # mkstemp makes 0600; output files get the usual mode
    try:
        yield tmp_path
        with _cannot_write(final, "file"):
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
    with _cannot_write(final, "folder"):
        final.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{final.name}.", suffix=".part", dir=final.parent))
    os.chmod(tmp, 0o777 & ~_umask())
    try:
        yield tmp
        with _cannot_write(final, "folder"):
            final.mkdir(parents=True, exist_ok=True)
        for item in tmp.iterdir():
            target = final / item.name
            if target.is_dir() and not target.is_symlink():
                shutil.rmtree(target)
            os.replace(item, target)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


@contextlib.contextmanager
def _cannot_write(final: Path, kind: str) -> Iterator[None]:
    """An :class:`OSError` making or renaming an output as an :class:`InputError` naming it (exit 2, one line):
    the place asked for cannot hold it (a file where a folder is needed or the reverse, no permission)."""
    try:
        yield
    except OSError as exc:
        raise InputError(f"cannot write the {kind} here: {exc.strerror or exc}", file=str(final),
                         expected=f"a {kind} name in a writable folder") from None


def check_output(name: str | os.PathLike[str] | None, *, option: str, what: str, folder: bool = False,
                 inputs: Sequence[str | os.PathLike[str] | None] = ()) -> None:
    """:class:`InputError` before any work when the output ``name`` of ``option`` cannot be written there.

    ``what`` says what it holds (``"the capture file (CSV)"``). Refused: a folder where a file is asked for
    (or a file where ``folder`` asks for a folder); a path under an existing file (``part.nc/out.csv``); a
    folder without write permission; a file that is one of the command's ``inputs`` (``vcnc interpolate
    part.nc -o part.nc`` would replace the program by its setpoints). Missing folders are made later, when the
    output is written (:func:`atomic_path`). Without this a long run would reach its end and fail on the rename.
    """
    if not name:
        return
    path = Path(name)
    if folder and path.exists() and not path.is_dir():
        raise InputError(f"{option} {name}: a file of that name exists; expected a folder for {what} "
                         "(made if absent)")
    if not folder and path.is_dir():
        raise InputError(f"{option} {name}: a folder of that name exists; expected a file name for {what}")
    parent = path.absolute().parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise InputError(f"{option} {name}: {parent} is a file, not a folder; expected a path for {what} "
                         "in a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option} {name}: the folder {parent} is not writable; expected a writable place "
                         f"for {what}")
    for source in inputs:
        if source and not folder and path.is_file() and Path(source).is_file() and path.samefile(source):
            raise InputError(f"{option} {name}: it is the input {source} itself, which {what} would replace; "
                             "expected another file name")


def check_distinct_outputs(outputs: Sequence[tuple[str, str | os.PathLike[str] | None]]) -> None:
    """:class:`InputError` before any work when two outputs of one command, ``(option, name)`` each, name the same
    file (``-o run.csv --json run.csv``): the one written last would replace the other, the run end with exit 0
    and one result lost."""
    seen: dict[str, tuple[str, str | os.PathLike[str]]] = {}
    for option, name in outputs:
        if not name:
            continue
        key = os.path.realpath(name)
        if key in seen:
            first, first_name = seen[key]
            raise InputError(f"{option} {name}: the same file as {first} {first_name}, which it would replace",
                             expected=f"another file name for {option}")
        seen[key] = (option, name)


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
