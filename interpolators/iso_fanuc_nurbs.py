"""Fanuc ``G06.2`` NURBS interpolation (``--dialect fanuc``).

The control points, weights and knots of a rational B-spline, one block each, then the tool follows the curve.
Sources: FANUC Series 15i/150i-MA operator's manual (programming), "NURBS interpolation (G06.2)"
(http://www.cncmanuals.com/fanuc/fanuc-series-15i-150i-ma-programming-operators-manual.html/143 to /144 and
/158): the format ``G06.2 [P_] K_ IP_ [R_] [F_] ; K_ IP_ [R_] ; ... K_ ; K_ ;`` with "P_ : Rank of NURBS curve,
IP_ : Control point, R_ : Weight, K_ : Knot, F_ : Feedrate"; "G06.2 is a modal G code of group 01. So, the NURBS
interpolation mode ends when a G code of group 01 other than G06.2 (e.g. G00, G01, G02, G03) is specified"; "The
rank setting, if any, must be specified in the same block as the first control point. If the rank setting is
omitted, a rank of four (degree of three) is assumed ... The valid data range for P is 2 to 4"; "When the weight
setting is omitted, a weight of 1.0 is assumed"; "The number of specified knots must equal the number of control
points plus the rank value. In the blocks specifying the first to last control points, each control point and a
knot are specified in the same block. After these blocks, as many blocks (including only a knot) as the rank
value are specified. P/S alarm No. 1002 is issued for blocks in which knot is not specified"; "The NURBS curve
programmed for NURBS interpolation must start from the first control point and end at the last control point.
The first k knots (where k is the rank) must have the same values as the last k knots (multiple knots)" (alarm
1007; our reading: the first k knots equal one another, and the last k); "Knots of the same value that continue
in excess of the rank value cannot be specified" (alarm 1008); "If a control point command is omitted in the
first block, the current position where NURBS interpolation is started is the first control point"; "If a knot
command is omitted in the first block, the same value as specified in the second block is assumed"; the curve
``P(t) = sum N_i,k(t) w_i P_i / sum N_i,k(t) w_i`` (de Boor-Cox), ``x_0 <= t <= x_m``. The Mitsubishi M700V
programming manual 6.15 "NURBS Interpolation" describes the same format ("Designate the same coordinate value for
the 1st block control point as that designated right before NURBS interpolation"; knots "the same or greater value
than the previous block"). Siemens NX Post Builder's Fanuc 30i post writes it (Unigraphics/PostBuilder
``fanuc_30i.def``, block templates ``nurbs``: ``G06.2 X Y Z K F P<rank>``, and ``knots``: ``K``).

vcnc runs the curve (:func:`interpolators.iso_nurbs.nurbs_chords` with the program's knots) as chords within
:data:`interpolators.iso_splines.SPLINE_TOLERANCE` of it, at the modal feed, on the line of the last knot block.
Refused, each an error naming it: a first control point away from the current position, a missing or decreasing
knot, knots not clamped as above, fewer control points than the rank, a rank outside 2-4, a weight <= 0,
another motion code before the last knot block (or the program's end), and G06.2 under G91 (our reading does not
say from where an incremental control point counts), under cutter compensation, tool centre point control, a G68
rotation, G51 scaling or mirror image, and with A-W axis words.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.iso_nurbs import chord_blocks, nurbs_chords
from interpolators.program import Block

if TYPE_CHECKING:
    from interpolators.iso import State

__all__ = ["NurbsCurve", "g062_block", "unfinished_g062"]

#: How far [mm] the first control point may be from the current position (our choice: 1 um, as
#: :data:`interpolators.iso_reference.REFERENCE_TOLERANCE`).
START_TOLERANCE = 1e-3
_EXPECTED = "G06.2 [P2..4] K X Y Z [R] [F] ; K X Y Z [R] ; ... then <rank> blocks K alone (Fanuc)"


@dataclasses.dataclass
class NurbsCurve:
    """A G06.2 curve being read: its control points [mm, machine], weights, knots and rank."""

    rank: int
    line: int
    points: list[np.ndarray] = dataclasses.field(default_factory=list)
    weights: list[float] = dataclasses.field(default_factory=list)
    knots: list[float | None] = dataclasses.field(default_factory=list)
    knot_only: int = 0


def g062_block(seen, gcodes, target: np.ndarray, st: State, blocks: list[Block], used: set[int], where: Where,
               number, move_feed, notes) -> None:
    """One block under G06.2 (``target``: its end as an ordinary move reads it, machine coordinates): a control
    point with its knot, or a knot alone; the last knot block runs the curve (``move_feed(st, segment)``: the
    chords' feed) and adds its note to ``notes``."""
    w = gcodes["motion"][1] if "motion" in gcodes else next(iter(seen.values()))
    _refuse(seen, st, where, w)
    moves = [a for a in "XYZ" if a in seen]
    if st.g062 is None:
        rank = seen["P"].value if "P" in seen else 4
        if rank not in (2, 3, 4):
            where.fail(f"G06.2 NURBS rank P{rank:g}: the rank is 2, 3 or 4", column=seen["P"].column,
                       text=seen["P"].text, expected=_EXPECTED)
        st.g062 = NurbsCurve(rank=int(rank), line=where.line)
        first = np.array(target if moves else st.pos, dtype=float)
        if float(np.linalg.norm(first - st.pos)) > START_TOLERANCE:
            bad = seen[moves[0]]
            where.fail("G06.2 NURBS: the first control point is not the current position (the curve starts at it)",
                       column=bad.column, text=bad.text, expected="the first block's X Y Z at the point the tool "
                       "stands on, or none")
        _add_point(seen, first, st, where, w)
        return
    curve = st.g062
    if "P" in seen:
        where.fail("G06.2 NURBS: the rank P goes in the first block only", column=seen["P"].column,
                   text=seen["P"].text, expected=_EXPECTED)
    if "K" not in seen:
        where.fail("G06.2 NURBS: a block without its knot K (Fanuc alarm 1002)", column=w.column, text=w.text,
                   expected=_EXPECTED)
    if moves and not curve.knot_only:
        point = np.array(curve.points[-1], dtype=float)
        for a in moves:  # an axis the block leaves out keeps the last control point's coordinate
            point["XYZ".index(a)] = target["XYZ".index(a)]
        _add_point(seen, point, st, where, w)
        return
    if moves or "R" in seen:
        bad = seen[moves[0] if moves else "R"]
        where.fail("G06.2 NURBS: a control point after the knot-only blocks began", column=bad.column,
                   text=bad.text, expected=_EXPECTED)
    curve.knots.append(seen["K"].value)
    curve.knot_only += 1
    if curve.knot_only == curve.rank:
        _run(curve, st, blocks, used, where, number, move_feed, w)
        notes.add("G06.2 NURBS run as chords within 1 um of the curve")


def _refuse(seen, st: State, where: Where, w) -> None:
    """The settings and words G06.2 does not run under here: an error naming the first."""
    extra = next((seen[k] for k in "ABCUVWIJQ" if k in seen), None)
    why = ("under G91 (incremental control points): not supported" if st.incremental else
           "under cutter compensation: not supported" if st.comp_side is not None else
           "under tool centre point control: not supported" if st.tcp else
           "under a G68 rotation, G51 scaling, mirror image or G10 R rotation: not supported"
           if st.frame is not None or st.rotation else
           f"with word {extra.letter}: not supported (control points take X Y Z, R, K, P and F)"
           if extra is not None else None)
    if why is not None:
        bad = extra if extra is not None and why.startswith("with") else w
        where.fail(f"G06.2 NURBS {why}", column=bad.column, text=bad.text, expected=_EXPECTED)


def _add_point(seen, point: np.ndarray, st: State, where: Where, w) -> None:
    weight = seen["R"].value if "R" in seen else 1.0
    if weight <= 0:
        where.fail(f"G06.2 NURBS weight R{weight:g}: a weight is > 0", column=seen["R"].column, text=seen["R"].text,
                   expected=_EXPECTED)
    st.g062.points.append(point)
    st.g062.weights.append(float(weight))
    st.g062.knots.append(seen["K"].value if "K" in seen else None)
    if "K" not in seen and len(st.g062.points) > 1:
        where.fail("G06.2 NURBS: a block without its knot K (Fanuc alarm 1002)", column=w.column, text=w.text,
                   expected=_EXPECTED)


def _run(curve: NurbsCurve, st: State, blocks: list[Block], used: set[int], where: Where, number, move_feed,
         w) -> None:
    """The last knot block: check the knots and run the curve as chords."""
    st.g062 = None
    k, points = curve.rank, np.array(curve.points)
    knots = list(curve.knots)
    if knots[0] is None:  # the first block's knot omitted: the second block's (15i-MA)
        knots[0] = knots[1]
    knots = np.array(knots, dtype=float)
    why = (f"{len(points)} control points, fewer than the rank {k}" if len(points) < k else
           "a knot smaller than the one before it" if np.any(np.diff(knots) < 0) else
           f"the first {k} knots are not equal, nor the last {k} (Fanuc alarm 1007: the curve starts at the "
           "first control point and ends at the last)" if np.ptp(knots[:k]) > 0 or np.ptp(knots[-k:]) > 0 else
           f"more than {k} equal knots (Fanuc alarm 1008)" if _longest_run(knots) > k else None)
    if why is not None:
        where.fail(f"G06.2 NURBS of line {curve.line}: {why}", column=w.column, text=w.text, expected=_EXPECTED)
    used.update((0, 1, 2))
    chord_blocks(nurbs_chords(points, np.array(curve.weights), k, knots=knots), st, blocks, where, number, move_feed)


def _longest_run(knots: np.ndarray) -> int:
    """The most knots of one value in a row."""
    longest = run = 1
    for a, b in zip(knots[:-1], knots[1:]):
        run = run + 1 if a == b else 1
        longest = max(longest, run)
    return longest


def unfinished_g062(st: State, where: Where) -> None:
    """Fail where a G06.2 curve has not had its last knot block: another motion code came, or the program ended
    (``where``: that place)."""
    if st.g062 is not None:
        left = st.g062.rank - st.g062.knot_only
        where.fail(f"G06.2 NURBS of line {st.g062.line}: {left} knot-only block(s) K missing before the curve's end",
                   column=1, text=where.text or "", expected=_EXPECTED)
