"""The moves of the SL cycles of Heidenhain conversational programs when they are called: 21 PILOT DRILLING, 22
ROUGH-OUT (and 23 FLOOR FINISHING), 24 SIDE FINISHING and 25 CONTOUR TRAIN, on the machine state
:class:`interpolators.heidenhain.Machine`. The contour subprograms (cycle 14's labels) run on a flow of their
own and are taken out of the program's blocks; their geometry (pockets, islands, rings, levels) is
:mod:`interpolators.heidenhain_contours`'.
"""
from __future__ import annotations

import dataclasses
import functools
import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.heidenhain_compensation import finish_compensation
from interpolators.heidenhain_contours import (
    ContourTrain,
    PilotDrill,
    RoughOut,
    SideFinish,
    clearing_rings,
    closed_pocket,
    path_at_level,
    pocket_rings,
    rest_pieces,
    reversed_path,
    rounded_ring,
    superimposed_region,
    train_levels,
)
from interpolators.heidenhain_cycle_moves import at_level, axis_move, run_hole
from interpolators.heidenhain_cycles import pecking_cycle
from interpolators.heidenhain_labels import Frame
from interpolators.heidenhain_words import SourceBlock
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Line
from toolpaths.pockets import Region

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine

__all__ = ["rough_out", "side_finish", "pilot_drill", "contour_train"]


def _trace_contour(m: Machine, label: str, radius: float, start: np.ndarray, feed: float, where: Where,
                   blk: SourceBlock) -> tuple[list[Block], str]:
    """The blocks of the contour subprogram ``LBL label`` run from ``start`` [mm, machine] with the tool
    radius ``radius`` [mm] and the feed ``feed`` [mm/s] where it gives none (its RL/RR compensation
    applied, the last element kept as a contour element),
    taken out of the program's blocks, and the compensation it used (``RL``, ``RR`` or ``R0``). The
    machine's position, feed and tool radius are as before."""
    runner = m.runner
    saved = (m.pos.copy(), m.tool_radius, m.feed, m.ccw, m.last_axes, m.pole_record, m.last_rapid)
    first = len(m.blocks)
    m.pos, m.tool_radius, m.feed = np.array(start, dtype=float), radius, feed
    sub = runner.fork()
    target = sub.labels.find(label, where, column=blk.column, text=blk.code)
    sub.stack.append(Frame(return_to=len(runner.blocks), label=label, runs_left=1))
    sub.pc = target + 1
    sub.steps()
    runner.executed += sub.executed
    if sub.stack:
        where.fail(f"cycle 25: the contour LBL {label} ends without LBL 0", column=blk.column, text=blk.code,
                   expected=f"LBL {label} .. LBL 0 (the contour subprogram)")
    if m.pending is not None or m.approach is not None:
        where.fail(f"cycle 25: the contour LBL {label} ends with a RND/CHF or APPR waiting for an element",
                   column=blk.column, text=blk.code, expected="a contour element after RND, CHF and APPR")
    side = m.comp_side if m.comp != "R0" else "R0"
    if m.comp != "R0":
        finish_compensation(m, open_end=True)
    path = m.blocks[first:]
    del m.blocks[first:]
    m.pos, m.tool_radius, m.feed, m.ccw, m.last_axes, m.pole_record, m.last_rapid = saved
    for b in path:
        if b.segment is None or b.start[m.plane] != b.target[m.plane]:
            Where(m.source, b.line, b.text).fail(
                f"cycle 25: the contour LBL {label} moves along the tool axis or dwells", column=1, text=b.text,
                expected="contour elements in the working plane (cycle 25 sets the depth)")
    if len(path) < 2:
        where.fail(f"cycle 25: the contour LBL {label} has no element after its starting point", column=blk.column,
                   text=blk.code, expected="a starting point and at least one contour element")
    return path, side


def _sl_contour(m: Machine, label: str, feed: float, where: Where, blk: SourceBlock) -> tuple[list[Block], str]:
    """The contour ``LBL label`` of cycle 14 as the SL cycles 21-24 take it (:func:`_trace_contour` with the tool
    radius 0), closed by a straight line from its last point back to its first where it ends elsewhere. Our
    reading of the manuals' own example "Overlapping contours" (TNC 426/430 and iTNC 530 user's manuals, SL
    cycles): its square island ``L X+27 Y+50 RL`` / ``L Y+58`` / ``L X+43`` / ``L Y+42`` / ``L X+27`` and its
    triangle ``L X+65 Y+42 RL`` / ``L X+57`` / ``L X+65 Y+58`` / ``L X+73 Y+42`` each end one side short of their
    first point. Cycle 25 runs its contour open. A note names the contour closed so: a contour that ends away by a
    mistake in the program shows there too."""
    path, side = _trace_contour(m, label, 0.0, m.pos, feed, where, blk)
    p, q = PLANE_AXES[m.plane]
    first, last = np.asarray(path[0].target, dtype=float), path[-1]
    here = np.array(last.target, dtype=float)
    if np.hypot(*(first - here)[[p, q]]) > 1e-6:
        end = here.copy()
        end[[p, q]] = first[[p, q]]
        path.append(dataclasses.replace(last, kind="line", start=here, target=end, segment=Line(here, end)))
        m.note(f"SL contour LBL {label} (cycle 14) ends away from its first point: closed by a line back to it")
    return path, side


def _sl_checks(m: Machine, number: int, where: Where, blk: SourceBlock) -> str:
    """The contour label of an SL cycle call, after the checks all of them share."""
    if not m.contour:
        where.fail(f"cycle {number} without a contour (CYCL DEF 14 or CONTOUR DEF)", column=blk.column,
                   text=blk.code, expected="CYCL DEF 14.0 CONTOUR / 14.1 CONTOUR LABEL n, or CONTOUR DEF P1 = LBL n, "
                                           "before the cycle call")
    if m.contour_roles and "P" not in m.contour_roles:
        where.fail(f"cycle {number}: CONTOUR DEF names islands only", column=blk.column, text=blk.code,
                   expected="at least one pocket Pn = LBL m in CONTOUR DEF")
    if not m.transform.identity or m.comp != "R0":
        where.fail(f"cycle {number} under a coordinate transformation (cycles 8, 10, 11, 26) or with RL/RR active "
                   "is not supported", column=blk.column, text=blk.code,
                   expected="R0 and no mirror, rotation or scaling")
    return m.contour[0]


def rough_out(m: Machine, c: RoughOut, where: Where, blk: SourceBlock) -> None:
    """Cycle 22 ROUGH-OUT of a pocket with no islands (TNC 426/430 user's manual, "ROUGH-OUT (Cycle 22)": "the
    tool mills the contour from the inside outward", at each plunging depth, leaving the allowances Q3 and
    Q4; then to the clearance height). The manual leaves the path to the control; our reading, kept inside
    the pocket: rings parallel to the contour (:func:`interpolators.heidenhain_contours.pocket_rings`), the
    outermost R + Q3 from it, each next one Q2 x R farther in, as long as one fits, run from the innermost
    out in the sense Q9, joined square to the contour at the middle of its first element; per depth: at
    FMAX to Q7 (first), over the innermost ring's start, to Q6 above Q5, at Q11 down, the rings at Q12, up
    at Q208 to Q6. The contour's own RL/RR is ignored, as the SL cycles do; Q8 rounds the rings' inside corners
    (:func:`interpolators.heidenhain_contours.rounded_ring`). Several labels in cycle 14 (pockets and islands):
    :func:`_rough_out_region` (Q8 there by :func:`interpolators.heidenhain_contours.rounded_region_ring`; not
    applied to rest machining, noted).
    Cycle 23 FLOOR FINISHING runs as this in one infeed to Q1 (:func:`interpolators.heidenhain_contours.
    floor_finishing_cycle`; the manual's tangential vertical approach arc is a straight plunge at Q11 here)."""
    _sl_checks(m, c.number, where, blk)
    if m.tool_radius <= 0:
        where.fail(f"cycle {c.number} needs a tool radius > 0 (the rings are Q2 x R apart); {m.no_radius()}",
                   column=blk.column, text=blk.code,
                   expected="a TOOL CALL of a tool with a radius: a TOOL DEF n L.. R.. or the machine context's tool "
                            "table ([program.tools.N] radius)")
    if len(m.contour) > 1 or c.coarse_tool:
        if c.rounding and c.coarse_tool:
            m.note("cycle 20 Q8 (rounding radius of the path's inside corners) not applied to rest machining (Q18): "
                   "the corners are sharp")
        _rough_out_region(m, c, where, blk)
        return
    axis = m.plane
    rings = _pocket_rings_of(m, c, m.tool_radius, where, blk)
    if c.rounding:
        rings = [rounded_ring(ring, c.rounding, plane=axis, ccw=c.ccw) for ring in rings]
    d, bottom, surface, clear, above = _rough_out_heights(m, c, c.number, where, blk)
    m.used.update((*PLANE_AXES[axis], axis))
    axis_move(m, "rapid", clear, math.inf, where, blk)
    for level in train_levels(surface, d * bottom, c.plunge):
        over = at_level(rings[0][0].start, axis, m.pos[axis])
        if not np.array_equal(over, m.pos):
            m.emit("rapid", over, Line(m.pos, over), math.inf, where, blk.number)
        axis_move(m, "rapid", above, math.inf, where, blk)
        axis_move(m, "line", level, c.plunge_feed, where, blk)
        for ring in rings:
            begin = at_level(ring[0].start, axis, level)
            if not np.array_equal(begin, m.pos):
                m.emit("line", begin, Line(m.pos, begin), c.feed, where, blk.number)
            for b in path_at_level(ring, axis, level):
                m.blocks.append(dataclasses.replace(b, kind="arc" if b.kind == "arc" else "line", feed=c.feed,
                                                    start=m.pos.copy()))
                m.pos = np.array(b.target, dtype=float)
        axis_move(m, "rapid" if c.retract_feed is None else "line", above,
                   math.inf if c.retract_feed is None else c.retract_feed, where, blk)
    axis_move(m, "rapid", clear, math.inf, where, blk)


def _rough_out_heights(m: Machine, c: RoughOut, number: int, where: Where,
                       blk: SourceBlock) -> tuple[float, float, float, float, float]:
    """The tool-axis frame of cycle ``number`` from cycle 20's data: the working direction (+-1, the sign of Q1),
    the depth less the floor allowance Q4 (> 0, else an error), the surface Q5, the clearance height Q7 and the
    set-up height Q6 above Q5 [mm, machine]."""
    bottom = abs(c.depth) - c.floor_allowance
    if bottom <= 0:
        where.fail(f"cycle {number}: the floor allowance Q4 is not smaller than the depth Q1", column=blk.column,
                   text=blk.code, expected="|Q4| < |Q1|")
    d = -1.0 if c.depth < 0 else 1.0
    surface = m.origin()[m.plane] + c.surface
    return d, bottom, surface, m.origin()[m.plane] + c.clearance, surface - d * c.setup


def _pocket_rings_of(m: Machine, c: RoughOut, radius: float, where: Where, blk: SourceBlock) -> list[list[Block]]:
    """The rings of cycle 22 in the one pocket of cycle 14 for a tool of ``radius`` [mm], the innermost first
    (:func:`interpolators.heidenhain_contours.pocket_rings`)."""
    label = m.contour[0]
    path, _ = _sl_contour(m, label, c.feed, where, blk)
    pocket = closed_pocket(path[1:], ccw=c.ccw, plane=m.plane)
    if pocket is None:
        where.fail(f"cycle {c.number}: the contour LBL {label} is not closed or encloses no area",
                   column=blk.column, text=blk.code, expected="a closed pocket contour (its last point its first)")
    loop, polygon = pocket
    first = radius + c.side_allowance
    span = float(np.max(np.ptp(polygon, axis=0)))
    step = c.overlap * radius
    radii = [first + k * step for k in range(min(10_000, int(span / step) + 2))]
    rings = pocket_rings(loop, polygon, radii=radii, plane=m.plane, ccw=c.ccw)[::-1]
    if not rings:
        where.fail(f"cycle {c.number}: the tool (radius {radius:g} mm) plus the allowance Q3 does not fit the "
                   f"pocket LBL {label}", column=blk.column, text=blk.code, expected="a pocket wider than the tool")
    return rings


def _sl_region(m: Machine, feed: float, where: Where, blk: SourceBlock) -> Region:
    """The region of cycle 14's contours (:func:`interpolators.heidenhain_contours.superimposed_region`)."""
    contours = [_sl_contour(m, label, feed, where, blk) for label in m.contour]
    return superimposed_region([(path[1:], side) for path, side in contours], plane=m.plane, where=where,
                               column=blk.column, roles=m.contour_roles)


def _region_rings(m: Machine, area: Region, *, first: float, step: float, ccw: bool, number: int, where: Where,
                  blk: SourceBlock, rounding: float = 0.0) -> list[tuple[np.ndarray, bool]]:
    """:func:`interpolators.heidenhain_contours.clearing_rings` with the errors named (``rounding``: cycle 20's
    Q8, 22's rings only)."""
    try:  # from the lower left (the same rings whatever the tool's position: cycle 21 drills where 22 plunges)
        rings = clearing_rings(area, first=first, step=step, ccw=ccw, start=area.bounds()[0], rounding=rounding)
    except ValueError as exc:
        where.fail(f"cycle {number}: {exc}", column=blk.column, text=blk.code,
                   expected="contours whose offsets the tool can follow")
    if not rings:
        where.fail(f"cycle {number}: the tool (radius {m.tool_radius:g} mm) plus the allowance fits nowhere in the "
                   "contours of cycle 14", column=blk.column, text=blk.code, expected="a pocket wider than the tool")
    return rings


def _plane_point(m: Machine, xy: np.ndarray, level: float) -> np.ndarray:
    """The machine point (plane coordinates ``xy``, tool axis at ``level``), the other axes where they are."""
    p, q = PLANE_AXES[m.plane]
    out = m.pos.copy()
    out[p], out[q], out[m.plane] = xy[0], xy[1], level
    return out


def side_finish(m: Machine, c: SideFinish, where: Where, blk: SourceBlock) -> None:
    """Cycle 24 SIDE FINISHING (:func:`interpolators.heidenhain_contours.side_finishing_cycle`) of every wall of
    the region of cycle 14 (pocket walls and islands): the manual has the tool approach each partial contour on a
    tangential arc and finish it at each infeed; our reading: each ring R + Q14 from the contours (the whole
    boundary's offset, within 1 um), the nearest next, from Q7 at FMAX over its start, to Q6 above Q5, then per
    infeed Q10 to the depth Q1: down at Q11, the ring at Q12 in the sense Q9; up to Q7 between rings."""
    _sl_checks(m, 24, where, blk)
    radius = m.tool_radius + c.allowance
    if not radius > 0:
        where.fail("cycle 24: the tool radius plus Q14 is not > 0", column=blk.column, text=blk.code,
                   expected="a tool with a radius")
    area = _sl_region(m, c.feed, where, blk)
    rings = _region_rings(m, area, first=radius, step=math.inf, ccw=c.ccw, number=24, where=where, blk=blk)
    axis, d = m.plane, -1.0 if c.depth < 0 else 1.0
    surface = m.origin()[axis] + c.surface
    clear, above = m.origin()[axis] + c.clearance, surface - d * c.setup
    m.used.update((*PLANE_AXES[axis], axis))
    for ring, _ in rings:
        axis_move(m, "rapid", clear, math.inf, where, blk)
        over = _plane_point(m, ring[0], clear)
        if not np.array_equal(over, m.pos):
            m.emit("rapid", over, Line(m.pos, over), math.inf, where, blk.number)
        axis_move(m, "rapid", above, math.inf, where, blk)
        for level in train_levels(surface, c.depth, c.plunge):
            axis_move(m, "line", level, c.plunge_feed, where, blk)
            for xy in ring[1:]:
                target = _plane_point(m, xy, level)
                m.emit("line", target, Line(m.pos, target), c.feed, where, blk.number)
    axis_move(m, "rapid", clear, math.inf, where, blk)


def pilot_drill(m: Machine, c: PilotDrill, where: Where, blk: SourceBlock) -> None:
    """Cycle 21 PILOT DRILLING (:func:`interpolators.heidenhain_contours.pilot_drilling_cycle`): a hole, pecked as
    cycle 1 PECKING does (Q10 infeeds at Q11, out to the set-up clearance Q6 between them), at each point where
    cycle 22 plunges with the rough-out tool Q13 (its radius from TOOL DEF or the tool table; the same rings as
    22 computes), down to Q1 less the floor allowance Q4; from Q7 at FMAX over each point; Q7 at the end."""
    _sl_checks(m, 21, where, blk)
    data = m.tool_data(c.tool)
    if data is None or not data[1] > 0:
        where.fail(f"cycle 21: the rough-out tool Q13 = {c.tool} has no radius", column=blk.column, text=blk.code,
                   expected="Q13 a tool of TOOL DEF or the tool table with a radius > 0")
    r, rough = data[1], c.rough_out
    axis = m.plane
    p, q = PLANE_AXES[axis]
    if len(m.contour) == 1:
        points = [np.array(_pocket_rings_of(m, rough, r, where, blk)[0][0].start, dtype=float)[[p, q]]]
    else:
        area = _sl_region(m, c.feed, where, blk)
        rings = _region_rings(m, area, first=r + rough.side_allowance, step=rough.overlap * r, ccw=rough.ccw,
                              number=21, where=where, blk=blk)
        points = [ring[0] for k, (ring, linked) in enumerate(rings) if k == 0 or not linked]
    d, bottom, surface, clear, above = _rough_out_heights(m, rough, 21, where, blk)
    drill = pecking_cycle({1: rough.setup, 2: d * bottom, 3: c.plunge, 4: 0.0, 5: c.feed}, feed_scale=1.0,
                          scale=1.0, where=where, column=blk.column)
    m.used.update((p, q, axis))
    for point in points:
        axis_move(m, "rapid", clear, math.inf, where, blk)
        over = _plane_point(m, point, clear)
        if not np.array_equal(over, m.pos):
            m.emit("rapid", over, Line(m.pos, over), math.inf, where, blk.number)
        axis_move(m, "rapid", above, math.inf, where, blk)
        run_hole(m, drill, surface, where, blk)
    axis_move(m, "rapid", clear, math.inf, where, blk)


def _rough_out_region(m: Machine, c: RoughOut, where: Where, blk: SourceBlock) -> None:
    """Cycle 22 ROUGH-OUT of the superimposed contours of cycle 14 (pockets less islands,
    :func:`interpolators.heidenhain_contours.superimposed_region`; TNC 426/430 user's manual, "ROUGH-OUT (Cycle
    22)": the tool mills the contour from the inside outward, the islands cleared with an approach toward the
    pocket contour, leaving Q3 and Q4). Our reading of the path the manual leaves to the control: the offsets of
    the whole boundary (pocket walls and islands alike) R + Q3, R + Q3 + Q2 R, .. (each ring within
    :data:`toolpaths.pockets.TOLERANCE` = 1 um, never nearer the contours than its offset), run from the
    innermost level outward in the sense Q9, joined by straight feed moves where they keep R + Q3 from every
    contour, else by a retraction to Q7 and a new plunge (separate regions); cycle 20's Q8 rounds the rings'
    inside corners (:func:`interpolators.heidenhain_contours.rounded_region_ring`; not after a coarse tool Q18).
    Per depth as for one pocket."""
    axis = m.plane
    area = _sl_region(m, c.feed, where, blk)
    rings = _region_rings(m, area, first=m.tool_radius + c.side_allowance, step=c.overlap * m.tool_radius,
                          ccw=c.ccw, number=c.number, where=where, blk=blk,
                          rounding=0.0 if c.coarse_tool else c.rounding)
    if c.coarse_tool:
        # the tool of the TOOL CALL before the cycle call rests-machines what Q18's tool left
        fine = f"{m.tool_called or 'the tool called'} ({m.tool_radius:g} mm), the rest-machining tool"
        coarse = m.tool_data(c.coarse_tool)
        if coarse is None or not coarse[1] > m.tool_radius:
            where.fail(f"cycle 22: the coarse roughing tool Q18 = {c.coarse_tool} has no radius larger than that of "
                       f"{fine}", column=blk.column, text=blk.code,
                       expected="Q18 a tool of TOOL DEF or the tool table, larger than the rest-machining tool")
        rings = rest_pieces(area, rings, coarse=coarse[1], radius=m.tool_radius, allowance=c.side_allowance)
        if not rings:
            m.note(f"cycle 22: the coarse roughing tool Q18 = {c.coarse_tool} left nothing that {fine}, reaches")
            return
    d, bottom, surface, clear, above = _rough_out_heights(m, c, c.number, where, blk)
    m.used.update((*PLANE_AXES[axis], axis))
    point = functools.partial(_plane_point, m)
    axis_move(m, "rapid", clear, math.inf, where, blk)
    for level in train_levels(surface, d * bottom, c.plunge):
        for k, (ring, linked) in enumerate(rings):
            if k == 0 or not linked:
                if k:
                    axis_move(m, "rapid", clear, math.inf, where, blk)
                over = point(ring[0], m.pos[axis])
                if not np.array_equal(over, m.pos):
                    m.emit("rapid", over, Line(m.pos, over), math.inf, where, blk.number)
                axis_move(m, "rapid", above, math.inf, where, blk)
                axis_move(m, "line", level, c.plunge_feed, where, blk)
            for xy in ring[0 if linked else 1:]:
                target = point(xy, level)
                if not np.array_equal(target, m.pos):
                    m.emit("line", target, Line(m.pos, target), c.feed, where, blk.number)
        axis_move(m, "rapid" if c.retract_feed is None else "line", above,
                   math.inf if c.retract_feed is None else c.retract_feed, where, blk)
    axis_move(m, "rapid", clear, math.inf, where, blk)


def contour_train(m: Machine, c: ContourTrain, where: Where, blk: SourceBlock) -> None:
    """Cycle 25 CONTOUR TRAIN (:func:`interpolators.heidenhain_contours.contour_train_cycle`) along the first
    label of cycle 14. The manual gives the parameters, not the moves; our reading: at FMAX to the clearance
    height Q7, in the plane to the contour's compensated starting point (its first point moved the tool
    radius plus Q3 off the first element, to the side of the RL/RR of the subprogram, as the TNC starts a
    compensated contour), at Q11 down to the first infeed level (Q10 below the surface Q5), the contour at
    Q12 with the tool radius plus Q3 (its last element offset as the others), at FMAX up to Q7, and so on
    to the depth Q1; the tool ends at Q7 over the contour's end. Q15 = +1 (climb milling with M3: the tool
    left of its path) runs an RR contour backwards, Q15 = -1 an RL contour; Q15 = 0 runs the contour as
    programmed, then backwards at the next depth from where it ended (plunging there at Q11), and so on. An
    R0 contour runs as programmed (the tool centre on it, Q3 not applied)."""
    label = _sl_checks(m, 25, where, blk)
    axis = m.plane
    radius = m.tool_radius + c.allowance
    if radius < 0:
        where.fail(f"cycle 25: the allowance Q3 ({c.allowance:g} mm) is below minus the tool radius",
                   column=blk.column, text=blk.code, expected="Q3 >= -R")
    programmed, _ = _trace_contour(m, label, 0.0, m.pos, c.feed, where, blk)
    first, tangent = np.array(programmed[0].target), np.array(programmed[1].segment.tangent_at(0.0), dtype=float)
    tangent[axis] = 0.0
    lead = first - tangent / (np.linalg.norm(tangent) or 1.0) * 2.0 * (radius + 1.0)
    traced, side = _trace_contour(m, label, radius, lead, c.feed, where, blk)
    contour = traced[1:]
    surface = m.origin()[axis] + c.surface
    clear = m.origin()[axis] + c.clearance
    p, q = PLANE_AXES[axis]
    m.used.update((p, q, axis))
    for k, level in enumerate(train_levels(surface, c.depth, c.plunge)):
        backwards = k % 2 == 1 if c.climb == 0 else side != "R0" and (c.climb > 0) != (side == "RL")
        run = path_at_level(reversed_path(contour) if backwards else contour, axis, level)
        if k == 0 or c.climb != 0:
            axis_move(m, "rapid", clear, math.inf, where, blk)
            over = at_level(run[0].start, axis, clear)
            if not np.array_equal(over, m.pos):
                m.emit("rapid", over, Line(m.pos, over), math.inf, where, blk.number)
        axis_move(m, "line", level, c.plunge_feed, where, blk)
        for b in run:
            m.blocks.append(dataclasses.replace(b, kind="arc" if b.kind == "arc" else "line", feed=c.feed,
                                                start=m.pos.copy()))
            m.pos = np.array(b.target, dtype=float)
    axis_move(m, "rapid", clear, math.inf, where, blk)
    m.last_rapid = True
