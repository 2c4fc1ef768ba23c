"""SL cycles of Heidenhain conversational programs: contours given as label subprograms.

Sources: HEIDENHAIN TNC 426/430 user's manual, "SL cycles" (cycle 14 CONTOUR GEOMETRY, cycle 20
CONTOUR DATA, cycles 21-24, cycle 25 CONTOUR TRAIN); iTNC 530 / TNC 640 user's manuals for cycle
programming, the same cycles.

========================= ==================================================================
``CYCL DEF 14.0 CONTOUR`` 14.1 ``CONTOUR LABEL 1 /2 /3``: the labels whose subprograms are the
                          contours (the first the pocket, the others pockets or islands by their
                          RL/RR), DEF-active (:func:`contour_labels`)
``CYCL DEF 20``           CONTOUR DATA Q1 depth, Q2 path overlap, Q3 side allowance, Q4 floor
                          allowance, Q5 surface, Q6 set-up clearance, Q7 clearance height, Q8
                          inside rounding radius, Q9 sense of rotation (:func:`contour_data`)
``CYCL DEF 25``           CONTOUR TRAIN, called: the first label of cycle 14 followed at the depths
                          (:func:`contour_train_cycle`; the moves are the reader's ``_contour_train``)
``CYCL DEF 21 .. 24``     pilot drilling, rough-out, floor and side finishing: an error naming the cycle
========================= ==================================================================
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from interpolators._words import Where
from interpolators.program import Block
from toolpaths.geometry import Arc, Line

__all__ = ["CONTOUR_CYCLES", "ROUGHING_CYCLES", "ContourTrain", "contour_labels", "contour_data",
           "contour_train_cycle", "train_levels", "reversed_path", "path_at_level"]

#: The SL cycles read here: 14 and 20 are DEF-active, 25 is called.
CONTOUR_CYCLES: tuple[int, ...] = (14, 20, 25)
#: The SL cycles that clear a pocket (offsetting with islands): refused with their names.
ROUGHING_CYCLES = {21: "PILOT DRILLING", 22: "ROUGH-OUT", 23: "FLOOR FINISHING", 24: "SIDE FINISHING"}

_LABELS_RE = re.compile(r"\s*(?:CONTOUR|KONTUR)?\s*(?:LABEL|LBL)\s*((?:\d+\s*/?\s*)+)$", re.I)


@dataclasses.dataclass(frozen=True, kw_only=True)
class ContourTrain:
    """Cycle 25 CONTOUR TRAIN as defined, in mm, mm/s.

    Attributes
    ----------
    depth : float
        Q1, the milling depth from the surface [mm]; its sign is the working direction.
    allowance : float
        Q3, the finishing allowance for the side [mm]: the tool runs this much farther from the contour.
    surface : float
        Q5, the workpiece surface coordinate [mm, program] (absolute).
    clearance : float
        Q7, the clearance height [mm, program] (absolute): where the tool moves in the plane.
    plunge : float
        Q10, the plunging depth per infeed [mm] (> 0).
    plunge_feed, feed : float
        Q11 plunging feed and Q12 milling feed [mm/s].
    climb : int
        Q15: +1 climb milling, -1 up-cut milling (with M3), 0 both alternately, one per infeed.
    """

    depth: float
    allowance: float
    surface: float
    clearance: float
    plunge: float
    plunge_feed: float
    feed: float
    climb: int


def contour_labels(rest: str, where: Where, column: int) -> tuple[str, ...]:
    """The label numbers of ``CYCL DEF 14.1 CONTOUR LABEL 1 /2`` (``rest`` after ``14.1``; the German
    dialog writes ``KONTURLABEL1 /2``). TNC 426/430 user's manual, "CONTOUR GEOMETRY (Cycle 14)": "all
    subprograms that are superimposed to define the contour are listed"; up to 12 labels."""
    lm = _LABELS_RE.match(rest)
    labels = tuple(re.findall(r"\d+", lm.group(1))) if lm else ()
    if not labels or len(labels) > 12 or "0" in labels:
        where.fail("malformed cycle 14.1: the contour's label numbers", column=column, text=rest.strip(),
                   expected="CYCL DEF 14.1 CONTOUR LABEL n /m .. (1 to 12 labels, none 0)")
    return labels


def contour_data(q: dict[int, float], where: Where, column: int) -> dict[int, float]:
    """Cycle 20 CONTOUR DATA (TNC 426/430 user's manual, "CONTOUR DATA (Cycle 20)"): Q1 milling depth
    (its sign the working direction), Q2 path overlap factor, Q3 finishing allowance for the side, Q4 for
    the floor, Q5 surface coordinate (absolute), Q6 set-up clearance, Q7 clearance height (absolute), Q8
    inside corner radius, Q9 direction of rotation (-1 clockwise, +1 counter-clockwise for pockets). It
    moves nothing; the pocket cycles 21-24 use it."""
    missing = [f"Q{k}" for k in (1, 2, 3, 4, 5, 6, 7, 8, 9) if k not in q]
    if missing:
        where.fail(f"cycle 20 lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="CONTOUR DATA Q1 .. Q9")
    return dict(q)


def contour_train_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                        column: int) -> ContourTrain:
    """Cycle 25 CONTOUR TRAIN from its Q parameters (TNC 426/430 user's manual, "CONTOUR TRAIN (Cycle 25)":
    "In conjunction with Cycle 14 CONTOUR GEOMETRY, this cycle facilitates the machining of open
    contours"; Q1 milling depth, Q3 finishing allowance for side, Q5 workpiece surface coordinate, Q7
    clearance height, Q10 plunging depth, Q11 feed rate for plunging, Q12 feed rate for milling, Q15 climb
    (+1), up-cut (-1) or both alternately in several infeeds (0); cycle 20 is not needed)."""
    missing = [f"Q{k}" for k in (1, 3, 5, 7, 10, 11, 12, 15) if k not in q]
    if missing:
        where.fail(f"cycle 25 lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="CONTOUR TRAIN Q1 Q3 Q5 Q7 Q10 Q11 Q12 Q15")
    if q[1] == 0 or q[10] == 0 or not q[11] > 0 or not q[12] > 0:
        where.fail("cycle 25: the depth Q1 and the plunging depth Q10 must be != 0, the feeds Q11 and Q12 > 0",
                   column=column, text=where.text, expected="Q1 != 0, Q10 != 0, Q11 > 0, Q12 > 0")
    if q[15] not in (-1.0, 0.0, 1.0):
        where.fail(f"cycle 25: Q15={q[15]:g} is not a milling direction", column=column, text=where.text,
                   expected="Q15=+1 (climb), -1 (up-cut) or 0 (alternately)")
    if abs(q[1]) / abs(q[10]) > 10_000:
        where.fail("cycle 25: more than 10000 infeeds", column=column, text=where.text,
                   expected="a larger plunging depth Q10")
    return ContourTrain(depth=q[1] * scale, allowance=q[3] * scale, surface=q[5] * scale, clearance=q[7] * scale,
                        plunge=abs(q[10]) * scale, plunge_feed=q[11] * feed_scale, feed=q[12] * feed_scale,
                        climb=int(q[15]))


def train_levels(surface: float, depth: float, plunge: float) -> list[float]:
    """The infeed levels [mm] from ``surface`` by ``plunge`` toward ``surface + depth``, the last one there."""
    d = -1.0 if depth < 0 else 1.0
    n = max(1, math.ceil(abs(depth) / plunge - 1e-9))
    return [surface + d * min(plunge * (i + 1), abs(depth)) for i in range(n)]


def _segment_at(b: Block, start: np.ndarray, end: np.ndarray, *, reverse: bool = False) -> Line | Arc:
    seg = b.segment
    if isinstance(seg, Arc):
        centre = np.array(seg.center, dtype=float)
        centre[seg.plane] = start[seg.plane]
        turns = max(0, math.ceil(abs(seg.sweep) / (2 * math.pi) - 1e-9) - 1)
        return Arc(start, end, centre, ccw=seg.ccw != reverse, plane=seg.plane, turns=turns)
    return Line(start, end)


def path_at_level(path: list[Block], axis: int, level: float) -> list[Block]:
    """The blocks of a flat tool-centre path moved along the tool ``axis`` to ``level`` [mm, machine]."""
    out = []
    for b in path:
        start, end = np.array(b.start, dtype=float), np.array(b.target, dtype=float)
        start[axis] = end[axis] = level
        out.append(dataclasses.replace(b, start=start, target=end, segment=_segment_at(b, start, end)))
    return out


def reversed_path(path: list[Block]) -> list[Block]:
    """The path run backwards: each block from its end to its start (arcs turning the other way), each
    keeping its line, number and text."""
    out = []
    for b in reversed(path):
        start, end = np.array(b.target, dtype=float), np.array(b.start, dtype=float)
        out.append(dataclasses.replace(b, start=start, target=end, segment=_segment_at(b, start, end, reverse=True)))
    return out
