"""Program calls of Heidenhain conversational programs: which file ``CALL PGM`` runs.

Semantics (HEIDENHAIN TNC 640 / TNC 620 conversational user's manuals, "Subprograms and program
section repeats: Calling any program as a subprogram"; iTNC 530 user's manual, same section):

* ``CALL PGM name`` runs another program as a subprogram and then resumes after the call;
  ``SEL PGM name`` selects a program that ``CALL SELECTED PGM`` runs.
* "If the program you want to call is located in the same directory as the program you are
  calling it from, then you only need to enter the program name"; a relative path is taken from
  the calling program's directory. The file type ``.H`` may be left out.
* "The called program must not contain the miscellaneous functions M2 or M30" and must not call
  the calling program (an endless loop); its ``END PGM`` returns to the caller.
* "Q parameters effectively have a global effect with a PGM CALL", and coordinate
  transformations defined in the called program stay in effect for the calling one; each
  program keeps the unit of its own ``BEGIN PGM`` line (MM or INCH).

A path on a control drive (``TNC:\\ZW35\\HERE\\PGM1.H``) names a directory of that control; vcnc
looks for its file name in the calling program's directory, which stands in for it (noted). ISO
programs (``.I``) are not run from conversational ones (an error naming the file).
"""

from __future__ import annotations

import re
from pathlib import Path

from interpolators._words import Where

__all__ = ["CALL_PGM_RE", "SEL_PGM_RE", "find_program"]

#: ``CALL PGM name``, ``CALL PGM "path name.h"``, ``CALL SELECTED PGM``; group 1 the name. A name written right
#: after PGM (``CALL PGM100``, as hand-written programs have it; the TNC's editor puts a space) is the name, as
#: ``TOOL DEF1`` is tool 1: our reading (tncwild39).
CALL_PGM_RE = re.compile(r"CALL\s+(?:SELECTED\s+PGM|PGM\s*(\"[^\"]+\"|'[^']+'|[^\s\"']\S*))\s*$", re.I)
#: ``SEL PGM name`` (``SEL PGM100`` likewise).
SEL_PGM_RE = re.compile(r"SEL\s+PGM\s*(\"[^\"]+\"|'[^']+'|[^\s\"']\S*)\s*$", re.I)

_DRIVE_RE = re.compile(r"^[A-Z]{2,}:[\\/]", re.I)


def find_program(name: str, caller: str | None, where: Where, *, column: int) -> tuple[Path, bool]:
    """The file a ``CALL PGM`` names, and whether it was found by a control drive path's file name.

    Parameters
    ----------
    name : str
        The name as written (quotes allowed, ``\\`` or ``/`` separators, ``.H`` optional).
    caller : str or None
        File of the calling program (its directory is searched); None: an error.
    where : Where
        The calling block, for errors.
    column : int
        1-based column of the name.

    Raises
    ------
    vcnc.GCodeError
        No calling file, an ISO program, or no such file (naming the places searched).
    """
    raw = name.strip().strip("\"'")
    if caller is None:
        where.fail(f"CALL PGM {raw}: the calling program was not read from a file", column=column, text=raw,
                   expected="a program loaded from a file (the called program is searched in its directory)")
    on_drive = _DRIVE_RE.match(raw) is not None
    rel = raw.replace("\\", "/")
    if on_drive:
        rel = rel.rsplit("/", 1)[-1]
    if Path(rel).suffix.upper() == ".I":
        where.fail(f"CALL PGM {raw}: an ISO program (.I) called from a conversational one is not supported",
                   column=column, text=raw, expected="a conversational program (.H)")
    folder = Path(caller).parent
    tries = [rel] if Path(rel).suffix else [rel + ".h", rel + ".H", rel]
    for cand in tries:
        found = _find_ignoring_case(folder, cand)
        if found is not None:
            return found, on_drive
    where.fail(f"CALL PGM {raw}: no program {tries[0]!r} in {str(folder)!r}", column=column, text=raw,
               expected="the called program in the calling program's directory (or a path relative to it)")
    raise AssertionError("unreachable")  # pragma: no cover


def _find_ignoring_case(folder: Path, rel: str) -> Path | None:
    """``folder / rel``, its last part matched without regard to case (the TNC's file names are not
    case sensitive)."""
    path = folder / rel
    if path.is_file():
        return path
    parent = path.parent
    if parent.is_dir():
        for entry in parent.iterdir():
            if entry.name.lower() == path.name.lower() and entry.is_file():
                return entry
    return None
