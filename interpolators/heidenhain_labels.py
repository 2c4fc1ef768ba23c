"""Labels, subprograms and program-section repeats of Heidenhain conversational programs.

Semantics (HEIDENHAIN iTNC 530 / TNC 640 conversational user's manuals, "Subprograms and
program section repeats"; iTNC 530 Pilot p. 41):

* ``LBL n`` (1..999) or ``LBL "NAME"`` marks a place; ``LBL 0`` ends a subprogram and may only
  mark that end.
* ``CALL LBL n`` calls a subprogram: the control runs from ``LBL n`` to the next ``LBL 0`` and
  then resumes after the call. Subprograms are written after ``M2``/``M30``; one placed before
  them also runs in the normal flow (its ``LBL 0`` is then passed over).
* ``CALL LBL n REP k`` after ``LBL n`` is a program-section repeat: the section between the
  label and the call runs once more than ``k`` (k repeats), then the program goes on after
  the call. The TNC shows the remaining count as ``REP k/k``; both forms are read. A
  ``REP k`` call of a label *after* the call (a subprogram) runs the subprogram ``k + 1``
  times (our reading: the repeat count applies to the call).
* ``FN 9`` .. ``FN 12`` ``IF ... GOTO LBL n`` jump to a label (see
  :mod:`interpolators.heidenhain_params`).

Calls nest up to :data:`MAX_NESTING` levels (TNC 640: 19), and a run executing more than
:data:`MAX_EXECUTED` blocks (an endless jump loop) is stopped with an error.
"""

from __future__ import annotations

import dataclasses
import re
from typing import TYPE_CHECKING

from interpolators._words import Where

if TYPE_CHECKING:  # the words module reads Q parameters, whose FN jumps name labels
    from interpolators.heidenhain_words import SourceBlock

__all__ = ["LABEL_RE", "CALL_RE", "MAX_NESTING", "MAX_EXECUTED", "LabelTable", "Frame", "label_key"]

#: ``LBL 5``, ``LBL5``, ``LBL "NAME"``, ``LBL NAME``.
LABEL_RE = re.compile(r"LBL\s*(?:\"([^\"]+)\"|'([^']+)'|(\d+)|([A-Z_]\w*))\s*$", re.I)
#: ``CALL LBL 1``, ``CALL LBL 1 REP 25/25``, ``CALL LBL "NAME" REP 2``, ``CALL LBL 1 REPQ13`` (the count in a Q
#: parameter, as HEIDENHAIN's demonstration program 7025 writes it).
CALL_RE = re.compile(r"CALL\s+LBL\s*(?:\"([^\"]+)\"|'([^']+)'|(\d+)|([A-Z_]\w*))"
                     r"(?:\s+(REP)(?:\s*(\d+|Q[LR]?\d+)(?:\s*/\s*\d+)?)?)?\s*$", re.I)

#: Deepest nesting of subprogram calls (TNC 640 user's manual: 19 levels).
MAX_NESTING: int = 19
#: Most blocks one program run may execute before it is judged endless (about 5 s of reading).
MAX_EXECUTED: int = 500_000


def label_key(match: re.Match) -> str:
    """Label of a :data:`LABEL_RE` or :data:`CALL_RE` match: ``"5"`` or ``"NAME"`` (upper case)."""
    for g in match.groups()[:4]:
        if g is not None:
            return str(int(g)) if g.isdigit() else g.upper()
    raise AssertionError("a label pattern matched without a label")  # pragma: no cover


@dataclasses.dataclass
class Frame:
    """An active subprogram call: where to return and how many more runs are due."""

    return_to: int
    label: str
    runs_left: int


class LabelTable:
    """Index of the labels of a program (block index of each ``LBL``)."""

    def __init__(self, blocks: list[SourceBlock], source: str | None) -> None:
        self.where_of: dict[str, int] = {}
        for i, blk in enumerate(blocks):
            m = LABEL_RE.match(blk.code)
            if m is None:
                continue
            key = label_key(m)
            if key in self.where_of and key != "0":
                blk.where(source).fail(f"label {key} is defined twice (first at block {self.where_of[key] + 1})",
                                       column=blk.column, text=blk.code, expected="each label once")
            self.where_of.setdefault(key, i)

    def find(self, key: str, where: Where, *, column: int, text: str) -> int:
        """Block index of label ``key``; an error naming it when the program has none."""
        if key == "0":
            where.fail("LBL 0 cannot be called (it ends a subprogram)", column=column, text=text,
                       expected="a label 1..999 or a name")
        if key not in self.where_of:
            where.fail(f"label {key} is not defined", column=column, text=text, expected=f"a block LBL {key}")
        return self.where_of[key]
