"""SL cycles of Heidenhain conversational programs: contours given as label subprograms.

Sources: HEIDENHAIN TNC 426/430 user's manual, "SL cycles" (cycle 14 CONTOUR GEOMETRY, cycle 20
CONTOUR DATA, cycles 21-24, cycle 25 CONTOUR TRAIN); iTNC 530 / TNC 640 user's manuals for cycle
programming, the same cycles.

========================= ==================================================================
``CYCL DEF 14.0 CONTOUR`` 14.1 ``CONTOUR LABEL 1 /2 /3``: the labels whose subprograms are the
                          contours (one label: the pocket; several: each a pocket or an island
                          by its direction and RL/RR, superimposed), DEF-active
                          (:func:`contour_labels`, :func:`superimposed_region`); or ``CONTOUR DEF
                          P1 = LBL 1 I2 = LBL 2``, each label's role written
                          (:mod:`interpolators.heidenhain_contour_def`)
``CYCL DEF 20``           CONTOUR DATA Q1 depth, Q2 path overlap, Q3 side allowance, Q4 floor
                          allowance, Q5 surface, Q6 set-up clearance, Q7 clearance height, Q8
                          inside rounding radius, Q9 sense of rotation (:func:`contour_data`)
``CYCL DEF 25``           CONTOUR TRAIN, called: the first label of cycle 14 followed at the depths
                          (:func:`contour_train_cycle`; the moves: :func:`interpolators.heidenhain_sl.contour_train`)
``CYCL DEF 22``           ROUGH-OUT, called, with cycle 20's data: one pocket by the rings of
                          :func:`pocket_rings`; pockets with islands by the offset rings of the
                          region (:func:`clearing_rings`, :mod:`toolpaths.pockets`: within 1 um);
                          Q8 rounds the inside corners of both (:func:`rounded_ring`,
                          :func:`rounded_region_ring`); Q18 rest machining after a coarse tool
                          (:func:`rest_pieces`, Q8 not applied)
``CYCL DEF 21, 23, 24``   PILOT DRILLING where 22 will plunge, FLOOR FINISHING (22 in one infeed
                          to Q1), SIDE FINISHING (the rings R + Q14 at each infeed)
                          (:func:`pilot_drilling_cycle`, :func:`floor_finishing_cycle`,
                          :func:`side_finishing_cycle`)
========================= ==================================================================
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from interpolators._words import Where
from interpolators.compensation import CompensationError, compensate
from interpolators.corners import PathGeometryError, end_tangent, round_elements
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Arc, Line, piece_of
from toolpaths.pockets import TOLERANCE, Edge, Region, offset_rings, region, segment_clear

__all__ = ["CONTOUR_CYCLES", "ROUGHING_CYCLES", "ContourTrain", "RoughOut", "SideFinish", "PilotDrill",
           "floor_finishing_cycle", "side_finishing_cycle", "pilot_drilling_cycle", "contour_labels", "contour_data",
           "contour_train_cycle", "rough_out_cycle", "train_levels", "reversed_path", "path_at_level",
           "closed_pocket", "pocket_rings", "contour_edges", "superimposed_region", "clearing_rings",
           "rest_pieces", "rounded_ring", "rounded_region_ring"]

#: The SL cycles read here: 14 and 20 are DEF-active, 25 is called.
CONTOUR_CYCLES: tuple[int, ...] = (14, 20, 25)
#: The SL cycles that machine the region of cycle 14's contours (with cycle 20's data), called.
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


@dataclasses.dataclass(frozen=True, kw_only=True)
class RoughOut:
    """Cycle 22 ROUGH-OUT with the CONTOUR DATA of cycle 20, in mm, mm/s.

    Attributes
    ----------
    depth : float
        Q1, the milling depth from the surface [mm]; its sign is the working direction.
    overlap : float
        Q2, the path overlap factor: the rings are Q2 x the tool radius apart [-].
    side_allowance, floor_allowance : float
        Q3, Q4: the finishing allowances on the wall and on the floor [mm].
    surface : float
        Q5, the workpiece surface coordinate [mm, program] (absolute).
    setup : float
        Q6, the set-up clearance above the surface [mm].
    clearance : float
        Q7, the clearance height [mm, program] (absolute).
    ccw : bool
        Q9 = +1: the rings run counter-clockwise, -1 clockwise.
    plunge : float
        Q10, the plunging depth per infeed [mm] (> 0).
    plunge_feed, feed : float
        Q11 plunging feed and Q12 roughing feed [mm/s].
    retract_feed : float or None
        Q208, the feed up to the set-up clearance after each infeed [mm/s]; ``None``: rapid.
    number : int
        The cycle this roughing runs for: 22, or 23 (floor finishing), 21 (pilot drilling's plunge points).
    coarse_tool : int
        Q18, the coarse roughing tool before this one (rest machining); 0: none.
    rounding : float
        Q8, the rounding radius of the tool-centre path's inside corners [mm] (0: sharp; :func:`rounded_ring`).
    """

    depth: float
    overlap: float
    side_allowance: float
    floor_allowance: float
    surface: float
    setup: float
    clearance: float
    ccw: bool
    plunge: float
    plunge_feed: float
    feed: float
    retract_feed: float | None
    number: int = 22
    coarse_tool: int = 0
    rounding: float = 0.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class SideFinish:
    """Cycle 24 SIDE FINISHING with the CONTOUR DATA of cycle 20, in mm, mm/s.

    Attributes
    ----------
    depth : float
        Q1 of cycle 20, the depth from the surface [mm]; its sign is the working direction.
    surface, clearance : float
        Q5 and Q7 of cycle 20 [mm, program] (absolute).
    setup : float
        Q6 of cycle 20 [mm].
    ccw : bool
        Q9 of cycle 24 = +1: climb milling (the material on the tool's right), -1 up-cut.
    plunge : float
        Q10, the plunging depth per infeed [mm] (> 0).
    plunge_feed, feed : float
        Q11 plunging feed and Q12 milling feed [mm/s].
    allowance : float
        Q14, the allowance left on the walls after finishing [mm].
    """

    depth: float
    surface: float
    clearance: float
    setup: float
    ccw: bool
    plunge: float
    plunge_feed: float
    feed: float
    allowance: float


@dataclasses.dataclass(frozen=True, kw_only=True)
class PilotDrill:
    """Cycle 21 PILOT DRILLING with the CONTOUR DATA of cycle 20, in mm, mm/s.

    Attributes
    ----------
    rough_out : RoughOut
        Cycle 22 as the rough-out tool Q13 will run it (its Q10..Q12 those of cycle 21): where it plunges is
        where cycle 21 drills.
    tool : int
        Q13, the number of the rough-out tool (its radius from TOOL DEF or the tool table).
    plunge, feed : float
        Q10 plunging depth [mm] (> 0) and Q11 feed rate for plunging [mm/s].
    """

    rough_out: RoughOut
    tool: int
    plunge: float
    feed: float


def _with_data(number: int, data: dict[int, float] | None, where: Where, column: int) -> dict[int, float]:
    if data is None:
        where.fail(f"cycle {number} without CONTOUR DATA (CYCL DEF 20)", column=column, text=where.text,
                   expected=f"CYCL DEF 20 CONTOUR DATA before cycle {number}")
    return data


def floor_finishing_cycle(q: dict[int, float], data: dict[int, float] | None, *, feed_scale: float,
                          scale: float, where: Where, column: int) -> RoughOut:
    """Cycle 23 FLOOR FINISHING (TNC 426/430 user's manual, "FLOOR FINISHING (Cycle 23)": the tool clears the
    floor allowance Q4 left by cycle 22 at the depth Q1, parallel to the contour as 22 roughs; Q11 feed rate for
    plunging, Q12 feed rate for roughing) as a cycle 22 in one infeed to Q1 with no floor allowance."""
    data = _with_data(23, data, where, column)
    if not q.get(11, 0) > 0 or not q.get(12, 0) > 0:
        where.fail("cycle 23: the feeds Q11 and Q12 must be given and > 0", column=column, text=where.text,
                   expected="FLOOR FINISHING Q11 > 0, Q12 > 0")
    rough = rough_out_cycle({10: data[1], 11: q[11], 12: q[12]}, data, feed_scale=feed_scale, scale=scale,
                            where=where, column=column)
    return dataclasses.replace(rough, floor_allowance=0.0, plunge=abs(rough.depth), number=23)


def side_finishing_cycle(q: dict[int, float], data: dict[int, float] | None, *, feed_scale: float,
                         scale: float, where: Where, column: int) -> SideFinish:
    """Cycle 24 SIDE FINISHING (TNC 426/430 user's manual, "SIDE FINISHING (Cycle 24)": Q9 direction of rotation
    (+1 climb, -1 up-cut milling for pocket and island), Q10 plunging depth, Q11 feed rate for plunging, Q12
    feed rate for milling, Q14 finishing allowance for side, what stays on the walls after it) to the depth Q1
    of cycle 20."""
    data = _with_data(24, data, where, column)
    missing = [f"Q{k}" for k in (9, 10, 11, 12, 14) if k not in q]
    if missing:
        where.fail(f"cycle 24 lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="SIDE FINISHING Q9 Q10 Q11 Q12 Q14")
    if data[1] == 0 or q[10] == 0 or not q[11] > 0 or not q[12] > 0:
        where.fail("cycle 24: Q1 (cycle 20) and Q10 must be != 0, the feeds Q11, Q12 > 0", column=column,
                   text=where.text, expected="Q1 != 0, Q10 != 0, Q11 > 0, Q12 > 0")
    if abs(data[1]) / abs(q[10]) > 10_000:
        where.fail("cycle 24: more than 10000 infeeds", column=column, text=where.text,
                   expected="a larger plunging depth Q10")
    return SideFinish(depth=data[1] * scale, surface=data[5] * scale, clearance=data[7] * scale,
                      setup=abs(data[6]) * scale, ccw=q[9] >= 0, plunge=abs(q[10]) * scale,
                      plunge_feed=q[11] * feed_scale, feed=q[12] * feed_scale, allowance=q[14] * scale)


def pilot_drilling_cycle(q: dict[int, float], data: dict[int, float] | None, *, feed_scale: float,
                         scale: float, where: Where, column: int) -> PilotDrill:
    """Cycle 21 PILOT DRILLING (TNC 426/430 user's manual, "PILOT DRILLING (Cycle 21)": the TNC drills where the
    rough-out tool Q13 will plunge, pecking as cycle 1 does; Q10 plunging depth, Q11 feed rate for plunging,
    Q13 rough-out tool number; the depth from cycle 20's Q1 less the floor allowance Q4)."""
    data = _with_data(21, data, where, column)
    missing = [f"Q{k}" for k in (10, 11, 13) if k not in q]
    if missing:
        where.fail(f"cycle 21 lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="PILOT DRILLING Q10 Q11 Q13")
    rough = rough_out_cycle({10: q[10], 11: q[11], 12: q[11]}, data, feed_scale=feed_scale, scale=scale,
                            where=where, column=column)
    return PilotDrill(rough_out=dataclasses.replace(rough, number=21), tool=int(q[13]),
                      plunge=abs(q[10]) * scale, feed=q[11] * feed_scale)


def rough_out_cycle(q: dict[int, float], data: dict[int, float] | None, *, feed_scale: float, scale: float,
                    where: Where, column: int) -> RoughOut:
    """Cycle 22 ROUGH-OUT from its Q parameters and cycle 20's (TNC 426/430 user's manual, "ROUGH-OUT (Cycle
    22)": Q10 plunging depth, Q11 feed rate for plunging, Q12 feed rate for roughing, Q18 coarse roughing
    tool (0: none), Q19 feed rate for reciprocation; the iTNC 530's Q208 feed rate for retraction (0: Q12,
    MAX: rapid), Q401 feed rate factor, Q404 fine roughing strategy). Q18 != 0: rest machining after that
    coarse roughing tool (:func:`rest_pieces`); Q19, Q401, Q404 move nothing here."""
    if data is None:
        where.fail("cycle 22 without CONTOUR DATA (CYCL DEF 20)", column=column, text=where.text,
                   expected="CYCL DEF 20 CONTOUR DATA before cycle 22")
    missing = [f"Q{k}" for k in (10, 11, 12) if k not in q]
    if missing:
        where.fail(f"cycle 22 lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="ROUGH-OUT Q10 Q11 Q12")
    if data[1] == 0 or q[10] == 0 or not q[11] > 0 or not q[12] > 0 or not 0 < data[2] < 2:
        where.fail("cycle 22: Q1 and Q10 must be != 0, the feeds Q11, Q12 > 0 and the overlap Q2 in (0, 2)",
                   column=column, text=where.text, expected="Q1 != 0, Q10 != 0, Q11 > 0, Q12 > 0, 0 < Q2 < 2")
    if abs(data[1]) / abs(q[10]) > 10_000:
        where.fail("cycle 22: more than 10000 infeeds", column=column, text=where.text,
                   expected="a larger plunging depth Q10")
    back = q.get(208, math.inf)
    return RoughOut(depth=data[1] * scale, overlap=data[2], side_allowance=data[3] * scale,
                    floor_allowance=abs(data[4]) * scale, surface=data[5] * scale, setup=abs(data[6]) * scale,
                    clearance=data[7] * scale, ccw=data[9] >= 0, plunge=abs(q[10]) * scale,
                    plunge_feed=q[11] * feed_scale, feed=q[12] * feed_scale,
                    retract_feed=None if math.isinf(back) else (back or q[12]) * feed_scale,
                    coarse_tool=int(q.get(18, 0.0)), rounding=abs(data[8]) * scale)


def _samples(path: list[Block], plane: int, per: int = 24) -> np.ndarray:
    """Points along the path's segments in the plane, shape (n, 2) [mm]."""
    p, q = PLANE_AXES[plane]
    pts = [np.asarray(b.segment.point_at(np.linspace(0.0, b.segment.length, per)))[:, [p, q]] for b in path]
    return np.concatenate(pts)


def _signed_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _inside(points: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    """Ray casting: which ``points`` lie inside the closed ``polygon`` (both (n, 2))."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    ax, ay = polygon[:, 0][None, :], polygon[:, 1][None, :]
    bx, by = np.roll(polygon[:, 0], -1)[None, :], np.roll(polygon[:, 1], -1)[None, :]
    crosses = (ay > y) != (by > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = ax + (y - ay) * (bx - ax) / (by - ay)
    return np.count_nonzero(crosses & (x < xs), axis=1) % 2 == 1


def _distance(points: np.ndarray, path: list[Block], plane: int) -> np.ndarray:
    """Smallest distance of each point (n, 2) from the path's lines and arcs in the plane [mm]."""
    p, q = PLANE_AXES[plane]
    best = np.full(len(points), np.inf)
    for b in path:
        seg = b.segment
        if isinstance(seg, Arc):
            c = np.array([seg.center[p], seg.center[q]])
            v = points - c
            ang = np.arctan2(v[:, 1], v[:, 0])
            rel = (ang - seg.start_angle) * (1.0 if seg.sweep > 0 else -1.0) % (2 * math.pi)
            on = rel <= abs(seg.sweep) + 1e-12
            ends = np.array([[seg.start[p], seg.start[q]], [seg.end[p], seg.end[q]]])
            d_end = np.min(np.linalg.norm(points[:, None, :] - ends[None, :, :], axis=2), axis=1)
            d = np.where(on, np.abs(np.linalg.norm(v, axis=1) - seg.radius), d_end)
        else:
            a, e = np.array([seg.start[p], seg.start[q]]), np.array([seg.end[p], seg.end[q]])
            u = e - a
            t = np.clip((points - a) @ u / (u @ u), 0.0, 1.0) if u @ u > 0 else np.zeros(len(points))
            d = np.linalg.norm(points - (a + t[:, None] * u), axis=1)
        best = np.minimum(best, d)
    return best


def _split(b: Block) -> tuple[Block, Block]:
    """A line or arc block cut at its middle into two blocks of the same kind."""
    middle = np.asarray(b.segment.point_at(b.segment.length / 2.0), dtype=float)
    halves = []
    for start, end in ((np.array(b.start, dtype=float), middle), (middle, np.array(b.target, dtype=float))):
        halves.append(dataclasses.replace(b, start=start, target=end, segment=piece_of(b.segment, start, end)))
    return halves[0], halves[1]


def closed_pocket(path: list[Block], *, ccw: bool, plane: int) -> tuple[list[Block], np.ndarray] | None:
    """The closed contour ``path`` turned to run ``ccw`` (counter-clockwise seen from the plane normal) and
    started at the middle of its first element (so that its offsets close smoothly), with a polygon of its
    points (n, 2) [mm]; ``None`` when it is not closed or encloses no area."""
    p, q = PLANE_AXES[plane]
    if np.hypot(*(np.asarray(path[-1].target) - np.asarray(path[0].start))[[p, q]]) > 1e-6:
        return None
    polygon = _samples(path, plane)
    area = _signed_area(polygon)
    if abs(area) <= 1e-9:
        return None
    if (area > 0) != ccw:
        path = reversed_path(path)
    head, tail = _split(path[0])
    return [tail, *path[1:], head], _samples(path, plane)


def pocket_rings(loop: list[Block], polygon: np.ndarray, *, radii: list[float], plane: int,
                 ccw: bool) -> list[list[Block]]:
    """The tool-centre rings of the closed ``loop`` (from :func:`closed_pocket`) offset inward by each of
    ``radii`` [mm, ascending] with :func:`interpolators.compensation.compensate` (the TNC rule: the first
    point square to the first element), while a ring exists: its points inside the pocket and at least its
    radius from the contour, its end at its start, and the straight step from its start out to the previous
    ring's start inside and at least the previous radius from the contour. The first ring that fails ends
    the list."""
    p, q = PLANE_AXES[plane]
    first = loop[0]
    tangent = np.asarray(first.segment.tangent_at(0.0), dtype=float)
    rings: list[list[Block]] = []
    for r in radii:
        lead_in = np.asarray(first.start, dtype=float) - tangent * 2.0 * (r + 1.0)
        entry = dataclasses.replace(first, kind="line", start=lead_in, target=np.array(first.start, dtype=float),
                                    segment=Line(lead_in, first.start))
        try:
            ring = compensate([entry, *loop], side="left" if ccw else "right", radius=r, plane=plane,
                              entry="perpendicular", open_end=True)[1:]
        except CompensationError:
            break
        if rings:  # the step out to the previous ring (the straight line between their starts) is checked too
            step = Line(ring[0].start, rings[-1][0].start)
            ring = [dataclasses.replace(ring[0], kind="line", start=step.start, target=step.end, segment=step),
                    *ring]
        pts = _samples(ring, plane)
        closes = np.hypot(*(np.asarray(ring[-1].target) - np.asarray(ring[int(bool(rings))].start))[[p, q]]) <= 1e-6
        reach = r - (radii[len(rings)] - radii[len(rings) - 1] if rings else 0.0)
        if not closes or not np.all(_inside(pts, polygon)) or np.min(_distance(pts, loop, plane)) < reach - 1e-6:
            break
        rings.append(ring[int(bool(rings)):])
    return rings


def rounded_ring(ring: list[Block], radius: float, *, plane: int, ccw: bool) -> list[Block]:
    """The closed tool-centre ``ring`` with its inside corners rounded by ``radius`` [mm]: cycle 20's Q8 (TNC
    426/430 user's manual, "CONTOUR DATA (Cycle 20)": "Inside corner radius Q8: inside "corner" rounding radius;
    entered value is referenced to the tool midpoint path"; iTNC 530 cycle manual: "used to calculate smoother
    traverse motions between the contour elements. Q8 is not a radius that is inserted as a separate contour
    element between programmed elements").

    Inside corners are where the ring turns in its own sense (left for ``ccw``): the corners of the pocket that
    the tool cannot reach (its other corners are already arcs of the offset). Each is rounded as ``RND`` rounds
    (:func:`interpolators.corners.round_elements`), the arc on the block before the corner; our reading where
    the manual is silent: a corner the radius does not fit stays sharp, and the ring's start (within its first
    element, square to the contour) is no corner."""
    out = [ring[0]]
    for b in ring[1:]:
        prev = out[-1]
        p, q = PLANE_AXES[plane]
        if not np.hypot(*(np.asarray(prev.target) - np.asarray(prev.start))[[p, q]]) > 1e-12:
            out.append(b)  # after an element of no length in the plane (a plunge on the ring): no corner to round
            continue
        t1 = end_tangent(prev.segment, plane)
        t2 = np.asarray(b.segment.tangent_at(0.0), dtype=float).reshape(3)[[p, q]]
        cross = float(t1[0] * t2[1] - t1[1] * t2[0])
        if abs(cross) <= 1e-9 * float(np.hypot(*t2)) or (cross > 0) != ccw:
            out.append(b)
            continue
        try:
            head, arc, tail = round_elements(prev.segment, b.segment, radius, plane=plane, word="Q8")
        except PathGeometryError:
            out.append(b)
            continue
        out[-1] = dataclasses.replace(prev, start=np.array(head.start, dtype=float),
                                      target=np.array(head.end, dtype=float), segment=head)
        out += [dataclasses.replace(prev, kind="arc", start=np.array(arc.start, dtype=float),
                                    target=np.array(arc.end, dtype=float), segment=arc),
                dataclasses.replace(b, start=np.array(tail.start, dtype=float), target=np.array(tail.end, dtype=float),
                                    segment=tail)]
    return out


def _feature(area: Region, p: np.ndarray) -> tuple[np.ndarray, float, float]:
    """The part of ``area``'s boundary nearest to the point ``p`` as a circle: its centre, radius and sign (the
    distance to it ``sign * (|x - centre| - radius)``), a line as ``radius`` inf with ``centre`` its point nearest
    ``p`` and ``sign`` 0 (its distance then ``(x - centre) . n``, ``n`` the unit normal toward ``p``); an edge's
    end the region wraps round is a circle of radius 0."""
    best: tuple[float, tuple[np.ndarray, float, float]] | None = None
    for e in area.boundary:
        u = e.fraction(p)
        if e.centre is None:
            w = e.end - e.start
            u = min(max(float((p - e.start) @ w / (w @ w)), 0.0), 1.0)
            near = e.start + u * w
            cand = (near, math.inf, 0.0) if 0.0 < u < 1.0 else (near, 0.0, 1.0)
        elif 0.0 < u < 1.0:
            r = float(np.hypot(*(p - e.centre)))
            cand = (e.centre, e.radius, 1.0 if r >= e.radius else -1.0)
        else:
            cand = (min((e.start, e.end), key=lambda q: float(np.hypot(*(p - q)))), 0.0, 1.0)
        dist = _feature_distance(cand, p)[0]
        if best is None or abs(dist) < best[0]:
            best = (abs(dist), cand)
    return best[1]


def _feature_distance(f: tuple[np.ndarray, float, float], x: np.ndarray, normal: np.ndarray | None = None
                      ) -> tuple[float, np.ndarray]:
    """The distance of ``x`` to the feature ``f`` of :func:`_feature` and its gradient (a line: along
    ``normal``, else toward ``x`` from the line's point)."""
    centre, radius, sign = f
    if math.isinf(radius):
        n = normal if normal is not None else (x - centre) / (float(np.hypot(*(x - centre))) or 1.0)
        return float((x - centre) @ n), n
    v = x - centre
    r = float(np.hypot(*v)) or 1e-300
    return sign * (r - radius), sign * v / r


def rounded_region_ring(ring: np.ndarray, area: Region, radius: float, *,
                        tolerance: float = TOLERANCE) -> np.ndarray:
    """The closed ring (n, 2) of :func:`clearing_rings` with its inside corners rounded by ``radius`` [mm]: cycle
    20's Q8 for pockets with islands, as :func:`rounded_ring` rounds one pocket's ring.

    The ring lies on a level ``r`` of the distance to the region's boundary; its corners are where the offsets of
    two boundary parts meet, found where the distance's gradient turns by more than 0.01 rad across a vertex (a
    ring bends smoothly elsewhere); they turn toward the larger distances. The rounding arc is the circle of
    ``radius`` tangent to both offsets: its centre lies at ``r + radius`` from both parts (a line, an arc or an
    edge's end the region wraps round; solved by Newton steps from the bisector), the arc from its point nearest
    the one part's offset to the other's, sampled in chords of at most ``tolerance`` sagitta (inside the circle:
    never nearer the boundary than ``r``), joined to the ring where the ring passes within ``tolerance`` of those
    points. Our reading where the manual is silent, as for one pocket: a corner stays sharp where the circle
    would come nearer than ``r + radius`` to another part of the boundary, where its arc would reach past the
    next corner, and at the ring's start (no corner)."""
    pts = np.asarray(ring, dtype=float)
    out: list[np.ndarray] = []
    cur, last = 0, (0, pts[0])  # the next vertex to copy; the segment and point the last arc ended at
    for i, corner in sorted(_corners(pts, area).items()):
        if i < cur:
            continue
        fillet = _fillet(pts, i, corner, area, radius, tolerance, last)
        if fillet is None:
            continue
        ka, arc, kb = fillet
        out += [*pts[cur:ka + 1], *arc]
        cur, last = kb + 1, (kb, arc[-1])
    out += list(pts[cur:])
    keep = [0] + [k for k in range(1, len(out)) if np.hypot(*(out[k] - out[k - 1])) > 1e-12]
    return np.array([out[k] for k in keep])


def _off_corner(ring: np.ndarray, area: Region) -> np.ndarray:
    """The ring (n, 2), its last vertex joined to its first, closed and started at the middle of the chord
    farthest along it from its corners (:func:`_corners`), where no rounding reaches."""
    corners = [i - 1 for i in _corners(np.concatenate([ring[-1:], ring, ring[:1]]), area)]
    closed = np.concatenate([ring, ring[:1]])
    if not corners:
        return closed
    along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    total, at = along[-1], along[corners]
    mids = (along[:-1] + along[1:]) / 2.0
    gap = np.abs(mids[:, None] - at[None, :]) % total
    k = int(np.argmax(np.min(np.minimum(gap, total - gap), axis=1)))
    mid = (closed[k] + closed[k + 1]) / 2.0
    return np.concatenate([[mid], closed[k + 1:-1], closed[:k + 1], [mid]])


def _corners(pts: np.ndarray, area: Region) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """The inside corners among the inner vertices of the polyline ``pts`` (n, 2), by index: two points of it just
    before and after the vertex (2, 2) and the distance's gradients there (2, 2). A corner: the gradient turns
    there by more than 0.01 rad, the polyline toward the larger distances."""
    a, v, b = pts[:-2], pts[1:-1], pts[2:]
    lin, lout = np.hypot(*(v - a).T), np.hypot(*(b - v).T)
    ok = (lin > 0) & (lout > 0)
    din = (v - a) / np.where(ok, lin, 1.0)[:, None]
    dout = (b - v) / np.where(ok, lout, 1.0)[:, None]
    delta = np.minimum(1e-5, np.minimum(lin, lout) / 4)[:, None]
    probes = np.stack([v - delta * din, v + delta * dout], axis=1)
    g = area.distance(probes.reshape(-1, 2))[1].reshape(-1, 2, 2)
    g1, g2 = g[:, 0], g[:, 1]
    phi = np.arctan2(g1[:, 0] * g2[:, 1] - g1[:, 1] * g2[:, 0], np.einsum("ij,ij->i", g1, g2))
    turn = din[:, 0] * dout[:, 1] - din[:, 1] * dout[:, 0]
    toward = din[:, 0] * g1[:, 1] - din[:, 1] * g1[:, 0]
    found = np.flatnonzero(ok & (np.abs(phi) > 1e-2) & (turn * toward > 0))
    return {int(k) + 1: (probes[k], g[k]) for k in found}


def _on_ring(pts: np.ndarray, point: np.ndarray, i: int, step: int, stop: int, reach: float,
             tolerance: float) -> int | None:
    """The segment ``k`` (``pts[k]`` to ``pts[k + 1]``) nearest ``point`` among those from vertex ``i`` toward
    ``stop`` within the length ``reach`` along the ring; None when it is farther than ``tolerance``."""
    best, k, walked = (math.inf, None), (i - 1 if step < 0 else i), 0.0
    while (k >= stop) if step < 0 else (k < stop):
        a, b = pts[k], pts[k + 1]
        w = b - a
        u = min(max(float((point - a) @ w / (w @ w)), 0.0), 1.0) if w @ w > 0 else 0.0
        dist = float(np.hypot(*(a + u * w - point)))
        if dist < best[0]:
            best = (dist, k)
        walked += float(np.hypot(*w))
        if walked > reach:
            break
        k += step
    return best[1] if best[0] <= tolerance else None


def _fillet(pts: np.ndarray, i: int, corner: tuple[np.ndarray, np.ndarray], area: Region, radius: float,
            tolerance: float, last: tuple[int, np.ndarray]) -> tuple[int, list[np.ndarray], int] | None:
    """The rounding of the corner ``i`` of the ring ``pts`` (:func:`rounded_region_ring`; ``corner`` as
    :func:`_corners` gives it): the segment the arc starts on, the arc's points (its ends included) and the
    segment it ends on; None when it stays sharp (its arc would start before ``last``, the segment and point
    where the ring goes on)."""
    v = pts[i]
    probes, (g1, g2) = corner
    phi = math.atan2(float(g1[0] * g2[1] - g1[1] * g2[0]), float(g1 @ g2))
    f1, f2 = _feature(area, probes[0]), _feature(area, probes[1])
    target = float(area.distance(v[None, :])[0][0]) + radius
    centre = v + (g1 + g2) / float(np.hypot(*(g1 + g2))) * radius / math.cos(abs(phi) / 2.0)
    for _ in range(30):  # Newton: at target from both parts
        (d1, n1), (d2, n2) = _feature_distance(f1, centre, g1), _feature_distance(f2, centre, g2)
        jac = np.array([n1, n2])
        if abs(np.linalg.det(jac)) < 1e-12:
            return None
        centre = centre - np.linalg.solve(jac, np.array([d1 - target, d2 - target]))
        if max(abs(d1 - target), abs(d2 - target)) < 1e-12:
            break
    (_, n1), (_, n2) = _feature_distance(f1, centre, g1), _feature_distance(f2, centre, g2)
    pa, pb = centre - radius * n1, centre - radius * n2
    if float(area.distance(centre[None, :])[0][0]) < target - tolerance:
        return None
    reach = 3.0 * max(float(np.hypot(*(pa - v))), float(np.hypot(*(pb - v)))) + tolerance
    ka = _on_ring(pts, pa, i, -1, last[0], reach, 2.0 * tolerance)
    kb = _on_ring(pts, pb, i, 1, len(pts) - 1, reach, 2.0 * tolerance)
    w = pts[last[0] + 1] - pts[last[0]]
    if ka is None or kb is None or (ka == last[0] and float((pa - last[1]) @ w) < 0):
        return None
    a0 = math.atan2(pa[1] - centre[1], pa[0] - centre[0])
    sweep = math.atan2(float(n1[0] * n2[1] - n1[1] * n2[0]), float(n1 @ n2))
    step = 2.0 * math.acos(1.0 - tolerance / radius) if tolerance < radius else math.pi
    k = max(1, math.ceil(abs(sweep) / step))
    arc = [pa] + [centre + radius * np.array([math.cos(a0 + sweep * j / k), math.sin(a0 + sweep * j / k)])
                  for j in range(1, k)] + [pb]
    return ka, arc, kb


def contour_edges(path: list[Block], plane: int) -> list[Edge]:
    """The lines and arcs of a contour's blocks as :class:`toolpaths.pockets.Edge` in the ``plane`` [mm]."""
    p, q = PLANE_AXES[plane]
    edges = []
    for b in path:
        seg = b.segment
        start, end = np.array([seg.start[p], seg.start[q]]), np.array([seg.end[p], seg.end[q]])
        if isinstance(seg, Arc):
            edges.append(Edge(start=start, end=end, centre=np.array([seg.center[p], seg.center[q]]),
                              radius=float(seg.radius), a0=float(seg.start_angle), sweep=float(seg.sweep)))
        elif np.linalg.norm(end - start) > 0:
            edges.append(Edge(start=start, end=end))
    return edges


def superimposed_region(contours: list[tuple[list[Block], str]], *, plane: int, where: Where,
                        column: int, roles: tuple[str, ...] = ()) -> Region:
    """The region cycle 14's contours enclose: each closed contour (its blocks after the starting point, and its
    ``RL``/``RR``/``R0``) is a pocket or an island by the TNC's rule (TNC 426/430 user's manual, "SL Cycles":
    the TNC recognizes a pocket when the tool path lies inside the contour, e.g. clockwise with RR, and an island
    when it lies outside, e.g. clockwise with RL); the first contour written with R0 is a pocket. Overlapping
    pockets and islands combine: the union of the pockets less the union of the islands ("Overlapping
    contours"). ``roles`` (``CONTOUR DEF``'s ``"P"`` / ``"I"``, one per contour,
    :mod:`interpolators.heidenhain_contour_def`): each contour's role as written, its direction and RL/RR
    not asked."""
    if roles:
        return _region_of_roles(contours, roles, plane=plane, where=where, column=column)
    pockets, islands = [], []
    for k, (path, side) in enumerate(contours):
        polygon = _samples(path, plane)
        closed = np.hypot(*(polygon[-1] - polygon[0])) <= 1e-6
        area = _signed_area(polygon)
        if not closed or abs(area) <= 1e-9:
            where.fail(f"SL cycle: contour {k + 1} of cycle 14 is not closed or encloses no area", column=column,
                       text=where.text, expected="closed contours (each its last point its first)")
        if side == "R0" and k > 0:
            where.fail(f"SL cycle: contour {k + 1} of cycle 14 has no RL/RR to tell a pocket from an island",
                       column=column, text=where.text, expected="RL or RR in each contour after the first")
        pocket = len(contours) == 1 or side == "R0" or (side == "RL") == (area > 0)
        (pockets if pocket else islands).append(contour_edges(path, plane))
    if not pockets:
        where.fail("SL cycle: cycle 14's contours are all islands", column=column, text=where.text,
                   expected="at least one pocket (a contour the tool runs inside of with its RL/RR)")
    return region(pockets, islands)


def _region_of_roles(contours: list[tuple[list[Block], str]], roles: tuple[str, ...], *, plane: int, where: Where,
                     column: int) -> Region:
    """:func:`superimposed_region` of contours whose roles ``"P"`` / ``"I"`` are written (``CONTOUR DEF``; at least
    one ``"P"``: the SL cycles check it first)."""
    pockets, islands = [], []
    for k, ((path, _), role) in enumerate(zip(contours, roles, strict=True)):
        polygon = _samples(path, plane)
        if np.hypot(*(polygon[-1] - polygon[0])) > 1e-6 or abs(_signed_area(polygon)) <= 1e-9:
            kind = "a pocket" if role == "P" else "an island"
            where.fail(f"SL cycle: subcontour {k + 1} of CONTOUR DEF ({kind}) is not closed or encloses no area",
                       column=column, text=where.text, expected="closed contours (each its last point its first)")
        (pockets if role == "P" else islands).append(contour_edges(path, plane))
    return region(pockets, islands)


def clearing_rings(area: Region, *, first: float, step: float, ccw: bool, start: np.ndarray,
                   tolerance: float = TOLERANCE, rounding: float = 0.0) -> list[tuple[np.ndarray, bool]]:
    """The rings that clear ``area`` [mm]: its offsets ``first``, ``first + step``, .. (``step`` infinite: the
    offset ``first`` alone) from the boundary
    (:func:`toolpaths.pockets.offset_rings`, within ``tolerance``), run from the innermost level outward, at each
    level the nearest ring next, each closed (n, 2) from its vertex nearest to where the tool is (``start``
    first), with ``True`` when the straight move to it from the previous ring's end keeps ``first`` from the
    boundary (else the tool leaves the material to reach it). ``ccw``: the material on the tool's right (Q9 =
    +1, climb milling with M3: counter-clockwise in a pocket, clockwise round an island). ``rounding`` > 0: each
    ring's inside corners rounded by it (cycle 20's Q8, :func:`rounded_region_ring`), before its start is
    chosen."""
    lo, hi = area.bounds()
    half = float(np.min(hi - lo)) / 2
    levels = [first + k * step for k in range(min(100_000, int(half / step) + 2))] if math.isfinite(step) else [first]
    levels = [lv for lv in levels if lv <= half + step]
    grid = max(min(step, first) / 3, tolerance * 10)
    per_level = offset_rings(area, levels, step=grid, tolerance=tolerance, left_higher=ccw)
    out: list[tuple[np.ndarray, bool]] = []
    here = np.asarray(start, dtype=float)
    for rings in reversed(per_level):
        todo = list(rings)
        while todo:
            k = int(np.argmin([np.min(np.linalg.norm(r - here, axis=1)) for r in todo]))
            ring = todo.pop(k)
            i = int(np.argmin(np.linalg.norm(ring - here, axis=1)))
            if rounding > 0:
                ring = rounded_region_ring(_off_corner(ring, area), area, rounding, tolerance=tolerance)[:-1]
                i = int(np.argmin(np.linalg.norm(ring - here, axis=1)))
            ring = np.concatenate([ring[i:], ring[:i + 1]])
            linked = bool(out) and segment_clear(area, here, ring[0], first, tolerance=tolerance)
            out.append((ring, linked))
            here = ring[-1]
    return out


def _to_polylines(point: np.ndarray, lines: list[np.ndarray]) -> np.ndarray:
    """The distance of each point (n, 2) to the closed polylines ``lines`` [mm]."""
    best = np.full(len(point), np.inf)
    for ring in lines:
        a, b = ring, np.roll(ring, -1, axis=0)
        u = b - a
        uu = np.maximum(np.einsum("kd,kd->k", u, u), 1e-300)
        for k in range(0, len(point), 2000):
            x = point[k:k + 2000]
            t = np.clip(np.einsum("nkd,kd->nk", x[:, None, :] - a[None], u) / uu, 0.0, 1.0)
            d = np.linalg.norm(x[:, None, :] - (a[None] + t[..., None] * u[None]), axis=2).min(axis=1)
            best[k:k + 2000] = np.minimum(best[k:k + 2000], d)
    return best


def _resampled(line: np.ndarray, spacing: float) -> np.ndarray:
    """The polyline (n, 2) with points added along its chords, at most ``spacing`` [mm] apart."""
    out = [line[:1]]
    for a, b in zip(line[:-1], line[1:]):
        n = max(1, math.ceil(float(np.linalg.norm(b - a)) / spacing))
        out.append(a + np.linspace(0.0, 1.0, n + 1)[1:, None] * (b - a))
    return np.concatenate(out)


def rest_pieces(area: Region, rings: list[tuple[np.ndarray, bool]], *, coarse: float, radius: float,
                allowance: float) -> list[tuple[np.ndarray, bool]]:
    """Rest machining (cycle 22 with Q18): the parts of the fine tool's ``rings`` (of :func:`clearing_rings`, tool
    ``radius`` [mm]) that can reach material the coarse tool (radius ``coarse`` [mm]) left. The coarse tool's
    centre reached ``C = {d >= coarse + allowance}`` and cut what lies within ``coarse`` of it; a point of a
    fine ring is kept when its distance to ``C`` exceeds ``coarse - radius`` (a bound: the fine tool's edge can
    then lie farther than ``coarse`` from ``C``; the rings resampled R/2 apart), with one point more at each end of
    a kept run. Each piece is
    returned open, with ``True`` when the straight move to it from the previous piece's end keeps ``radius +
    allowance`` from the contours. The manual (TNC 426/430, cycle 22 Q18: "the TNC machines only the areas the
    coarse roughing tool could not") leaves the path to the control; this is our reading."""
    (border,) = offset_rings(area, [coarse + allowance], step=max(coarse / 3, TOLERANCE * 10))
    first = radius + allowance
    out: list[tuple[np.ndarray, bool]] = []
    here = None
    for closed, _ in rings:
        ring = _resampled(closed, radius / 2)
        dist = _to_polylines(ring, border)
        inside_c = area.distance(ring)[0] >= coarse + allowance
        useful = (np.where(inside_c, 0.0, dist) > coarse - radius + TOLERANCE)
        if not np.any(useful):
            continue
        keep = useful | np.roll(useful, 1) | np.roll(useful, -1)
        keep[0] = keep[-1] = keep[0] or keep[-1]  # the ring is closed: its first vertex is its last
        if np.all(keep):
            pieces = [ring]
        else:
            shift = int(np.argmin(keep[:-1]))  # start at a dropped vertex so that runs do not wrap
            k = np.concatenate([keep[shift:-1], keep[:shift + 1]])
            v = np.concatenate([ring[shift:-1], ring[:shift + 1]])
            edges = np.flatnonzero(np.diff(k.astype(int)))
            pieces = [v[s + 1:e + 1] for s, e in zip(edges[::2], edges[1::2])]
        for piece in pieces:
            if len(piece) < 2:
                continue
            linked = here is not None and segment_clear(area, here, piece[0], first)
            out.append((piece, linked))
            here = piece[-1]
    return out
