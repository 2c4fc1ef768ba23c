"""Fanuc and Haas corner rounding and chamfering: ``,R`` and ``,C`` between two moves.

A move block with ``,R r`` is followed by a tangent arc of radius ``r`` into the next move, one with
``,C c`` by a chamfer that cuts ``c`` from the corner (the "virtual corner", the programmed end
point) along each move. The arc or chamfer is programmed geometry: its own block, with the line,
number and feed of the block that carries the word, the two moves trimmed to its ends. The
geometry is :mod:`interpolators.corners` (shared with the Heidenhain reader's RND and CHF); it is
built on the blocks in machine coordinates, after work offsets, G91, G68 rotation and G51 scaling
(which scales the value as it scales an arc's R), and before cutter compensation offsets the run
(G41/G42 then offset the rounded contour, as the control does).

Sources:

- Fanuc Series 0i-MF / 30i-B operator's manual (milling), "Optional chamfering and corner R":
  ``,C`` and ``,R`` at the end of a block of linear (G01) or circular (G02, G03) interpolation insert a
  chamfer or a corner R between it and the next block of linear or circular interpolation in the
  same plane; ``,C`` is the distance from the virtual corner to the chamfer's start and end. The
  alarms (Fanuc 0i alarm list): PS0050 "CHF/CNR NOT ALLOWED IN THRD BLK" (a threading block),
  PS0051 "MISSING MOVE AFTER CNR/CHF" ("Improper movement or the move distance was specified in the
  block next to the chamfering or corner R block"), PS0052 "CODE IS NOT G01 AFTER CHF/CNR" (the next
  block is not a G01, G02 or G03 move), PS0055 "MISSING MOVE VALUE IN CHF/CNR" ("the move distance is
  less than chamfer or corner R amount").
- NCT 2000M operator's manual (a Fanuc-compatible control), 16.1 "Programming Chamfer and Corner
  Round": ",C and ,R" only "between the coordinates of the selected plane (G17, G18, G19)", only
  "between blocks G1, G2 or G3", both in one block an error; on an arc ``,C`` is "the length of the
  chord drawn from intersection".
- Haas mill operator's manual, "G01 Corner Rounding and Chamfering": ``G01 X.. Y.. ,C..`` /
  ``,R..`` between two G01 linear interpolation blocks in the selected plane; ``,C`` the distance
  from the intersection at which the chamfer starts and ends, ``,R`` the radius of the arc tangent to
  both lines. Under the ``haas`` dialect both moves must be G01.

Secondary descriptions that agree: https://cnclearning.com/?p=1015, "Automatic chamfering" (Fanuc,
Haas, Mitsubishi: ",C Value: The linear distance from the corner to the start of the chamfer"; ",R":
the radius of the arc "tangent to both intersecting lines"), and the Fanuc 0i alarm list for
PS0050-PS0055.

LinuxCNC and grbl know no such words (a ``,`` is an error there). The corner runs at the feed of the
block with the word, the move after it at its own (vcnc's reading: none of the sources gives the
corner another feed); under G93 inverse time, where that block's feed is its time, the words are
refused. Bare ``R``/``C`` on a G01 (the lathe form of Fanuc "Chamfering and corner R", T series) are
not read on a mill: ``R`` on G01 stays an error and ``C`` is the rotary axis.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.corners import PathGeometryError, chamfer_elements, round_elements
from interpolators.iso_words import Word
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Arc, Line

if TYPE_CHECKING:
    from interpolators.iso import State

__all__ = ["CORNER_LETTERS", "CORNER_DIALECTS", "PendingCorner", "corner_word", "start_corner", "finish_corner",
           "corner_not_followed", "corner_after_block"]

#: The lexer's letters of the two words (``,R`` rounding, ``,C`` chamfer).
CORNER_LETTERS: tuple[str, ...] = (",R", ",C")
#: Dialects that read them, with the motion codes (round(10 * G)) that may carry them and follow them.
CORNER_DIALECTS: dict[str, tuple[int, ...]] = {"fanuc": (10, 20, 30), "haas": (10,)}

_NAMES = {",R": "corner rounding", ",C": "chamfering"}
_PLANES = {2: "G17", 1: "G18", 0: "G19"}


@dataclasses.dataclass(frozen=True, kw_only=True)
class PendingCorner:
    """A ``,R`` / ``,C`` waiting for the next move.

    Attributes
    ----------
    word : Word
        The word as read (``,R`` or ``,C``, its value in program units).
    size : float
        Radius or chamfer distance [mm] (program units and G51 scaling applied).
    index : int
        Index of the block that carries the word in the reader's block list.
    where : Where
        Its line, for the messages.
    plane : int
        The plane (tool-axis index, :data:`toolpaths.geometry.PLANE_AXES`) it was programmed in.
    """

    word: Word
    size: float
    index: int
    where: Where
    plane: int


def _label(word: Word) -> str:
    return f"{word.text!r} {_NAMES[word.letter]}"


def _allowed(dialect: str) -> str:
    return "G01" if CORNER_DIALECTS[dialect] == (10,) else "G01, G02 or G03"


def corner_word(seen: dict[str, Word], dialect: str, where: Where) -> tuple[dict[str, Word], Word | None]:
    """The block's ``,R`` or ``,C`` taken out of its words: ``(other words, the corner word or None)``.
    Outside the Fanuc and Haas dialects, both in one block, or a value <= 0: an error."""
    found = [seen[k] for k in CORNER_LETTERS if k in seen]
    if not found:
        return seen, None
    w = found[0]
    if dialect not in CORNER_DIALECTS:
        where.fail(f"{_label(w)} between two moves (Fanuc/Haas ',R' / ',C'): not in the {dialect} dialect",
                   column=w.column, text=w.text, expected="the rounding arc or chamfer written as its own move "
                   "(or --dialect fanuc / haas)")
    if len(found) > 1:
        where.fail("',C' chamfering and ',R' corner rounding in one block", column=found[1].column,
                   text=found[1].text, expected="either ,C or ,R")
    if not w.value > 0:
        where.fail(f"{_label(w)}: the value must be > 0", column=w.column, text=w.text,
                   expected=f"{w.letter}<distance> > 0")
    return {k: v for k, v in seen.items() if k not in CORNER_LETTERS}, w


def start_corner(word: Word, block: Block, *, index: int, dialect: str, motion: int, plane: int, size: float,
                 inverse_time: bool, where: Where) -> PendingCorner:
    """Check the block that carries ``word`` and remember the corner for the next move."""
    if motion not in CORNER_DIALECTS[dialect]:
        code = "G00 rapid" if motion == 0 else f"G{motion // 10:02d}"
        where.fail(f"{_label(word)} on a {code} block ({dialect}: only on {_allowed(dialect)})",
                   column=word.column, text=word.text, expected=f"{word.letter} on a {_allowed(dialect)} move")
    if inverse_time:
        where.fail(f"{_label(word)} under G93 inverse time (the block's F is its time): not supported",
                   column=word.column, text=word.text, expected="G94 feed per minute")
    if block.extra_target is not None:
        where.fail(f"{_label(word)} on a move with A, B, C, U, V or W words: not supported", column=word.column,
                   text=word.text, expected="a move of the plane's axes")
    return PendingCorner(word=word, size=size, index=index, where=where, plane=plane)


def corner_not_followed(corner: PendingCorner, where: Where | None, what: str) -> None:
    """The block after a ``,R`` / ``,C`` is not the move it needs (Fanuc PS0051 / PS0052): an error at
    that block (``where``; None: the program ended)."""
    w = corner.word
    text = (f"{_label(w)} (line {corner.where.line}) is not followed by a move: {what} "
            "(Fanuc PS0051 missing move after CNR/CHF, PS0052)")
    if where is None:
        corner.where.fail(text, column=w.column, text=w.text, expected="the next block a move in the plane")
    where.fail(text, column=1, text=where.text, expected=f"a G01/G02/G03 move in the plane right after line "
               f"{corner.where.line}")


def _in_plane(seg: Line | Arc, plane: int) -> bool:
    """True when ``seg`` moves in the plane and not along its normal."""
    p, q = PLANE_AXES[plane]
    d = np.asarray(seg.end, float) - np.asarray(seg.start, float)
    if isinstance(seg, Arc):
        return abs(seg.helix) <= 1e-9 and abs(seg.sweep) <= 2.0 * math.pi + 1e-12
    return abs(d[plane]) <= 1e-9 and float(np.hypot(d[p], d[q])) > 1e-9


def finish_corner(corner: PendingCorner, blocks: list[Block], block: Block, *, dialect: str, plane: int,
                  where: Where) -> Block:
    """Insert the rounding arc or chamfer between ``blocks[-1]`` (the block with the word) and
    ``block`` (the next move, not yet appended): ``blocks[-1]`` is trimmed and the corner block
    appended; returns ``block`` trimmed."""
    w = corner.word
    first = blocks[-1]
    if block.kind == "rapid" or block.kind == "arc" and dialect == "haas":
        corner_not_followed(corner, where, f"a {'G00 rapid' if block.kind == 'rapid' else 'G02/G03 arc'} "
                                           f"({dialect}: only {_allowed(dialect)})")
    if plane != corner.plane:
        corner_not_followed(corner, where, f"the plane changed from {_PLANES[corner.plane]} to {_PLANES[plane]}")
    if block.extra_target is not None:
        corner_not_followed(corner, where, "a move with A, B, C, U, V or W words")
    for seg, which in ((first.segment, f"line {corner.where.line}"), (block.segment, "this block")):
        if not _in_plane(seg, plane):
            corner_not_followed(corner, where, f"{which} moves along the plane's normal axis or not in the "
                                f"{_PLANES[plane]} plane (a helix, a move of the third axis)")
    try:
        if w.letter == ",R":
            head, middle, tail = round_elements(first.segment, block.segment, corner.size, plane=plane, word=",R")
        else:
            head, middle, tail = chamfer_elements(first.segment, block.segment, corner.size, plane=plane,
                                                  word=",C")
    except PathGeometryError as exc:
        corner.where.fail(f"{_label(w)}: {exc.message} (Fanuc PS0055)", column=w.column, text=w.text,
                          expected=exc.expected)
    blocks[-1] = dataclasses.replace(first, target=np.array(head.end, float), segment=head)
    kind = "arc" if isinstance(middle, Arc) else "line"
    blocks.append(dataclasses.replace(first, kind=kind, start=np.array(middle.start, float),
                                      target=np.array(middle.end, float), segment=middle))
    return dataclasses.replace(block, start=np.array(tail.start, float), segment=tail)


def corner_after_block(st: State, words: list[Word], count: int, blocks: list[Block], where: Where) -> None:
    """After each block: a ``,R`` / ``,C`` its block did not take (not a move of G01-G03) or a pending
    corner the block did not take (no move, or other blocks made) is an error."""
    if st.corner_word is not None:
        w, st.corner_word = st.corner_word, None
        where.fail(f"{w.text!r} {'corner rounding' if w.letter == ',R' else 'chamfering'} on a block without a "
                   "G01/G02/G03 move", column=w.column, text=w.text, expected="the word on a move block")
    if st.corner is None:
        return
    if st.corner_fresh:
        st.corner_fresh = False
        if len(blocks) == st.corner.index + 1:
            return
        corner_not_followed(st.corner, where, "its own block made more than one move")
    if len(blocks) > count:
        corner_not_followed(st.corner, where, f"this block makes a {blocks[-1].kind} that is not a G01/G02/G03 "
                            "move")
    if any(w.letter != "N" for w in words):
        corner_not_followed(st.corner, where, "this block has no move")
