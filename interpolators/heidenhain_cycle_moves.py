"""The moves of Heidenhain conversational machining cycles when they are called: drilling, boring, tapping, bore
and thread milling, circular and rectangular pockets and studs, slots, the multipass-milling surfaces (230-233)
and the pattern cycles 220/221, from the definitions of :mod:`interpolators.heidenhain_cycles` and
:mod:`interpolators.heidenhain_surfaces`, on the machine state :class:`interpolators.heidenhain.Machine`.
The sources of each cycle's moves are in its function's docstring.
"""
from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.heidenhain_contours import ContourTrain, PilotDrill, RoughOut, SideFinish
from interpolators.heidenhain_cycles import (
    THREAD_CYCLES,
    AxisMove,
    DrillCycle,
    PatternCycle,
    back_boring_moves,
    hole_moves,
    scaled_cycle,
    to_second_clearance,
)
from interpolators.heidenhain_paths import helical_arc
from interpolators.heidenhain_surfaces import RuledSurface, SurfaceCycle, ruled_surface_moves, surface_moves
from interpolators.heidenhain_targets import program_target
from interpolators.heidenhain_words import SourceBlock
from toolpaths.geometry import PLANE_AXES, Arc, Line

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine

__all__ = ["run_surface", "run_hole", "at_level", "pattern_cycle_run", "active_cycle", "surface_level", "axis_move"]


def run_surface(m: Machine, c: SurfaceCycle | RuledSurface, where: Where, blk: SourceBlock) -> None:
    """Cycle 230, 231, 232 or 233 (:func:`interpolators.heidenhain_surfaces.surface_moves`, ``ruled_surface_moves``):
    its moves, given in program coordinates of the working plane's axes and the tool axis, through the active
    transformations."""
    axis = m.plane
    p, q = PLANE_AXES[axis]
    if c.number in (232, 233) and not m.tool_radius > 0:
        where.fail(f"cycle {c.number} FACE MILLING without a tool radius (the stepover is Q370 x the radius); "
                   f"{m.no_radius()}", column=blk.column, text=blk.code,
                   expected="TOOL CALL of a tool with a radius > 0 before the call: a TOOL DEF n L.. R.. or the "
                            "machine context's tool table ([program.tools.N] radius)")
    try:
        moves = ruled_surface_moves(c, radius=m.tool_radius) if isinstance(c, RuledSurface) else \
            surface_moves(c, radius=m.tool_radius, position=tuple(float(m.to_program(m.pos)[i]) for i in (p, q, axis)))
    except ValueError as exc:
        where.fail(f"cycle {c.number}: {exc}", column=blk.column, text=blk.code, expected="a larger Q370 or tool")
    for mv in moves:
        target, _ = program_target(m, {"XYZ"[i]: v for i, v in zip((p, q, axis), mv.point) if v is not None}, m.pos)
        if np.allclose(target, m.pos, rtol=0.0, atol=1e-12):
            continue
        kind = "rapid" if math.isinf(mv.feed) else "line"
        m.emit(kind, target, Line(m.pos, target), mv.feed, where, blk.number)
    m.used.update(range(3))


def run_hole(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """The moves of cycle ``c`` at the current position in the plane (210, 212-215: about their centre Q216, Q217,
    reached at the clearance height first), ``surface`` [mm, machine]."""
    axis = m.plane
    if m.tool_radius < 0 and (c.number == 208 or c.number in THREAD_CYCLES or c.shape >= 251):
        # a cycle milling about the tool's radius with R + DR below zero: its rings would step inward for ever
        where.fail(f"cycle {c.number} with a negative tool radius {m.tool_radius:g} mm (the tool's radius R plus DR "
                   "of its TOOL CALL) is not modelled", column=blk.column, text=blk.code,
                   expected="R + DR >= 0: the tool in the machine context's tool table or a TOOL DEF n L.. R..")
    if c.number == 208:
        _bore_milling(m, c, surface, where, blk)
        return
    if c.number in THREAD_CYCLES:
        _thread_milling(m, c, surface, where, blk)
        return
    if c.place is not None:
        _to_centre(m, c, surface, where, blk)
    if c.centre_offset != (0.0, 0.0):
        _beside_tool(m, c, surface, where, blk)
    if c.shape in (251, 252, 253):
        _circular_pocket(m, c, surface, where, blk)
        return
    if c.shape == 254:  # Q377 slots, Q378 apart on the pitch circle, one after the other
        if not m.transform.identity:
            where.fail("cycle 254 under a coordinate transformation (cycles 8, 10, 11, 26) is not supported",
                       column=blk.column, text=blk.code, expected="CIRCULAR SLOT without mirror, rotation or scaling")
        for k in range(c.repeats):
            _circular_pocket(m, dataclasses.replace(c, angle=c.angle + k * c.slot[4]), surface, where, blk)
        return
    if c.shape in (256, 257):
        _rectangular_stud(m, c, surface, where, blk)
        if c.place is not None:  # 213, 215: the end position is over the centre
            _to_centre(m, c, surface, where, blk)
        return
    centre = m.pos.copy()
    p, q = PLANE_AXES[axis]
    moves = back_boring_moves(c, surface=surface) if c.number == 204 else hole_moves(c, start=m.pos[axis],
                                                                                       surface=surface)
    for mv in moves:
        if mv.kind == "dwell":
            m.emit("dwell", m.pos, None, 0.0, where, blk.number, dwell=mv.dwell)
        elif mv.kind == "plane":
            target, _ = program_target(m, {"I" + "XYZ"[p]: mv.offset[0], "I" + "XYZ"[q]: mv.offset[1]}, centre)
            target[axis] = m.pos[axis]
            m.emit("rapid", target, Line(m.pos, target), math.inf, where, blk.number)
        else:
            axis_move(m, mv.kind, mv.level, mv.feed, where, blk)
    m.used.add(axis)


def _to_centre(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """Cycles 210, 212-215: at FMAX along the tool axis to the set-up clearance, or the 2nd one when higher, then
    over the centre Q216, Q217 (TNC 370 user's manual p. 8-20, cycle 213: "The TNC moves the tool in the Z axis
    to the setup clearance, or - if this has been specified - to the 2nd setup clearance and subsequently to the
    center")."""
    p, q = PLANE_AXES[m.plane]
    d = -1.0 if c.depth < 0 else 1.0
    axis_move(m, "rapid", surface - d * max(c.setup, c.second_setup), math.inf, where, blk)
    target, _ = program_target(m, {"XYZ"[p]: c.place[0], "XYZ"[q]: c.place[1]}, m.pos)
    if not np.array_equal(target, m.pos):
        m.emit("rapid", target, Line(m.pos, target), math.inf, where, blk.number)


def _beside_tool(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """Cycles 251, 253, 256 with Q367 = 1..4 (``c.centre_offset``, heidenhain_cycles' ``beside_tool_offset``): the
    tool goes at FMAX over the pocket's, slot's or stud's centre, from where the cycle runs as with Q367 = 0; below
    the set-up clearance it first rises to it (our reading: the manual's cycle run starts over the centre and
    names no path there; the plane move stays clear of the part above the set-up clearance)."""
    p, q = PLANE_AXES[m.plane]
    d = -1.0 if c.depth < 0 else 1.0
    clear = surface - d * c.setup
    if d * (m.pos[m.plane] - clear) > 0:
        axis_move(m, "rapid", clear, math.inf, where, blk)
    target, _ = program_target(m, {"I" + "XYZ"[p]: c.centre_offset[0], "I" + "XYZ"[q]: c.centre_offset[1]}, m.pos)
    if not np.array_equal(target, m.pos):
        m.emit("rapid", target, Line(m.pos, target), math.inf, where, blk.number)


def _bore_milling(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """Cycle 208 BORE MILLING at the current position (TNC 320 user's manual for cycle programming,
    "BORE MILLING (Cycle 208)", cycle run: to the set-up clearance at FMAX, to the circumference,
    a helix at the feed Q206 to the depth, a full circle there, back to the centre, out at FMAX to
    the set-up clearance and the 2nd one). The helix runs on the diameter Q335 less the tool
    diameter, from the set-up clearance down by Q334 per turn; it starts on the reference axis
    side, reached on a straight line at the feed (the TNC rounds that approach: our reading).
    A tool as wide as the hole drills straight down ("bores directly to the entered depth").
    """
    axis = m.plane
    p, q = PLANE_AXES[axis]
    d = -1.0 if c.depth < 0 else 1.0
    top, bottom = surface - d * c.setup, surface + c.depth
    r = c.bore_diameter / 2.0 - m.tool_radius
    if r < -1e-9:
        where.fail(f"cycle 208: the tool (radius {m.tool_radius:g} mm) is wider than the hole "
                   f"({c.bore_diameter:g} mm)", column=blk.column, text=blk.code,
                   expected="a tool radius of at most Q335 / 2")
    axis_move(m, "rapid", top, math.inf, where, blk)
    centre = m.pos.copy()
    m.used.add(axis)
    if r <= 1e-9:
        axis_move(m, "line", bottom, c.feed, where, blk)
    else:
        k = m.lengths(where)
        start, _ = program_target(m, {"I" + "XYZ"[p]: r / k}, centre)
        m.emit("line", start, Line(m.pos, start), c.feed, where, blk.number)
        turns = abs(bottom - top) / c.helix_pitch
        sweep = m.transform.sweep(360.0 * turns * (1.0 if c.climb else -1.0), axis)
        for turn in (sweep, math.copysign(360.0, sweep)):  # the helix, then a full circle at the depth
            seg = helical_arc(m.pos, centre, turn, plane=axis, axis_end=bottom)
            m.emit("arc", np.array(seg.end), seg, c.feed, where, blk.number)
        back = centre.copy()
        back[axis] = bottom
        m.emit("line", back, Line(m.pos, back), c.feed, where, blk.number)
        m.used.update((p, q))
    _out_of_hole(m, c, surface, where, blk)


def _thread_milling(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """The thread-milling cycles 262-267 at the current position (TNC 426/430 user's manual, "Cycles for
    drilling, tapping and thread milling"; TNC 320 user's manual 340 55x-03), in the manuals' order: FMAX to
    the set-up clearance; 264: drill the hole (as cycle 205); 263: the countersinking; the countersinking at
    the front (265 with Q360 = 1: after the thread); the thread: at the pre-positioning feed Q253 to the
    starting plane, a tangential approach, the helix, a tangential departure back to the starting point in
    the plane; FMAX out to the set-up clearance and the 2nd set-up clearance.

    The manuals leave the paths' sizes to the control; our reading, kept inside the thread (267: outside the
    stud): the helix runs on the diameter Q335 less the tool diameter (267: plus) at the feed Q207,
    counter-clockwise for climb milling inside (Q351 = +1, M3; clockwise round a stud), and upward when that
    follows the thread (a right-hand thread climb-milled inside, or up-cut outside), else downward. Q355 = 0
    (and 263, 264) turns once, over one pitch ending (upward: starting) at the thread depth; Q355 = 1 runs
    between the depth and the surface; Q355 > 1 (:func:`_thread_passes`) turns once as Q355 = 0 at the depth and
    again at every Q355 pitches above it while still below the surface, each with its approach and departure,
    at Q253 along the axis between them; 265 runs one helix from the surface down to the depth, clockwise for
    a right-hand thread. Inside, the approach and the departure are half circles at the helix's end levels
    between the centre and the helix, in the helix's sense (so they join it tangentially). 267 starts on the
    reference axis one pitch outside the helix (the manual: "determined by the thread radius, tool radius and
    pitch"), and the half circles run against the helix's sense between that distance and the helix.
    """
    axis = m.plane
    p, q = PLANE_AXES[axis]
    d = -1.0 if c.depth < 0 else 1.0
    top = surface - d * c.setup
    r = c.bore_diameter / 2.0 + (m.tool_radius if c.outside else -m.tool_radius)
    if r <= 1e-9:
        where.fail(f"cycle {c.number}: the tool (radius {m.tool_radius:g} mm) is not narrower than the thread "
                   f"({c.bore_diameter:g} mm)", column=blk.column, text=blk.code,
                   expected="a tool radius below Q335 / 2")
    axis_move(m, "rapid", top, math.inf, where, blk)
    centre = m.pos.copy()
    sense = m.transform.sweep(1.0 if c.climb != c.outside else -1.0, axis)
    if c.number == 264:
        drill = dataclasses.replace(c, number=205, depth=c.sink_depth, feed=c.drill_feed, second_setup=0.0)
        for mv in hole_moves(drill, start=m.pos[axis], surface=surface):
            axis_move(m, mv.kind, mv.level, mv.feed, where, blk)
    if c.number == 263 and c.sink_depth:
        level = surface + c.sink_depth
        if not c.sink_side:
            axis_move(m, "line", level - d * c.setup, c.approach_feed, where, blk)
        axis_move(m, "line", level, c.sink_feed if not c.sink_side else c.approach_feed, where, blk)
        _circle_out_and_back(m, centre, r, sense, c.sink_feed, where, blk)
    if c.front_depth and not c.front_after:
        axis_move(m, "line", surface + c.front_depth, c.sink_feed if c.number == 265 else c.approach_feed, where,
                   blk)
        _circle_out_and_back(m, centre, c.front_offset, sense, c.sink_feed, where, blk)
    _thread_helix(m, c, centre, surface, r, sense, where, blk)
    if c.front_depth and c.front_after:
        axis_move(m, "line", surface + c.front_depth, c.approach_feed, where, blk)
        _circle_out_and_back(m, centre, c.front_offset, sense, c.sink_feed, where, blk)
    m.used.update((p, q, axis))
    _out_of_hole(m, c, surface, where, blk)


def _thread_helix(m: Machine, c: DrillCycle, centre: np.ndarray, surface: float, r: float, sense: float,
                  where: Where, blk: SourceBlock) -> None:
    """The thread of :func:`_thread_milling`: to the starting plane at Q253, the approach, the helix of radius
    ``r`` [mm] about ``centre`` turning by ``sense`` (+1 counter-clockwise), the departure."""
    axis = m.plane
    k = m.lengths(where)
    ref = "I" + "XYZ"[PLANE_AXES[axis][0]]
    out = r + c.helix_pitch if c.outside else 0.0  # 267: the starting point's distance from the centre
    if c.outside:
        start, _ = program_target(m, {ref: out / k}, centre)
        start[axis] = m.pos[axis]
        m.emit("rapid", start, Line(m.pos, start), math.inf, where, blk.number)
    turn = -sense if c.outside else sense  # the half circles: against the helix outside
    for start_level, end_level in _thread_passes(c, surface):
        axis_move(m, "line", start_level, c.approach_feed, where, blk)
        here = m.pos.copy()
        on, _ = program_target(m, {ref: r / k}, centre)
        on[axis] = start_level
        seg = helical_arc(m.pos, (here + on) / 2.0, math.copysign(180.0, turn), plane=axis, axis_end=start_level)
        m.emit("arc", np.array(seg.end), seg, c.feed, where, blk.number)
        turns = abs(end_level - start_level) / c.helix_pitch
        seg = helical_arc(m.pos, at_level(centre, axis, start_level), math.copysign(360.0 * turns, sense),
                          plane=axis, axis_end=end_level)
        m.emit("arc", np.array(seg.end), seg, c.feed, where, blk.number)
        back = at_level(centre, axis, end_level)
        if c.outside:  # out along the radius the helix ended on, to the starting point's distance
            back = back + (m.pos - back) * (out / r)
        seg = helical_arc(m.pos, (m.pos + back) / 2.0, math.copysign(180.0, turn), plane=axis, axis_end=end_level)
        m.emit("arc", back, seg, c.feed, where, blk.number)


def _thread_passes(c: DrillCycle, surface: float) -> list[tuple[float, float]]:
    """The (starting, end) levels [mm] of the helices of :func:`_thread_helix`, in the order they run. Upward
    (a right-hand thread climb-milled inside, ...) a helix starts at the thread depth, downward it ends there.
    Q355 > 1 (TNC 426/430 user's manual p. 251: "several helical paths with approach and departure; between
    them, the TNC offsets the tool by Q355, multiplied by the pitch"; our reading of where they lie, which the
    manual leaves open): one turn as Q355 = 0, and one more at every Q355 pitches above it while the turn still
    reaches below the surface, each one pitch long; upward from the deepest, downward from the highest."""
    d = -1.0 if c.depth < 0 else 1.0
    bottom = surface + c.depth
    upward = (c.right_hand == c.climb) != c.outside
    if c.continuous:
        return [(bottom, surface) if upward else (surface, bottom)]
    step = c.threads_per_step * c.helix_pitch
    depths = [abs(c.depth)]  # the deep end of each turn, measured from the surface
    while step > 0 and depths[-1] - step > 1e-9:
        depths.append(depths[-1] - step)
    levels = [(surface + d * u, surface + d * (u - c.helix_pitch)) for u in depths]  # (deep end, far end)
    return levels if upward else [(far, deep) for deep, far in reversed(levels)]


def _plunge(m: Machine, c: DrillCycle, centre: np.ndarray, level: float, room: float, sense: float, where: Where,
            blk: SourceBlock) -> None:
    """The roughing infeed of cycles 251-253 from over the ``centre`` down to ``level`` [mm] at the plunging
    feed Q206, by Q366 (TNC 640 user's manual for cycle programming, cycles 251-253, Q366 "Plunging
    strategy": 0 vertical; 1 helical; 2 reciprocating, 251/253 only). The control sets the helix and the
    reciprocating path from the plunging angle ANGLE of its tool table, which vcnc's tool table does not
    hold; our reading, kept inside the pocket: the helix turns once, in the milling sense, on the tool
    radius (at most ``room`` [mm], the roughing radius left for the tool centre) about the centre, out from
    and back to the centre along the reference axis; the reciprocating plunge runs along the pocket's
    (turned) reference axis from the centre out to the room on that side, to the room on the other side
    halfway down and back to the first end at the level, then to the centre. Without room: vertical."""
    axis = m.plane
    if c.plunge_type == 0:
        axis_move(m, "line", level, c.approach_feed, where, blk)
        return
    p, q = PLANE_AXES[axis]
    here = at_level(centre, axis, m.pos[axis])
    k = m.lengths(where)
    if c.plunge_type == 1:
        reach, ways = min(m.tool_radius or room, room), ((1.0, level),)
    else:
        reach = (c.sides[0] / 2.0 - c.side_allowance - m.tool_radius) if c.shape in (251, 253) else room
        ways = ((-1.0, (m.pos[axis] + level) / 2.0), (1.0, level))
    if reach <= 1e-9:
        axis_move(m, "line", level, c.approach_feed, where, blk)
        return
    cos, sin = (math.cos(math.radians(c.angle)), math.sin(math.radians(c.angle))) if c.plunge_type == 2 else (1, 0)

    def at(u: float, z: float) -> np.ndarray:
        pt, _ = program_target(m, {"I" + "XYZ"[p]: u * cos / k, "I" + "XYZ"[q]: u * sin / k}, here)
        pt[axis] = z
        return pt

    out = at(reach, m.pos[axis])
    m.emit("line", out, Line(m.pos, out), c.approach_feed, where, blk.number)
    if c.plunge_type == 1:
        seg = helical_arc(m.pos, here, math.copysign(360.0, sense), plane=axis, axis_end=level)
        m.emit("arc", np.array(seg.end), seg, c.approach_feed, where, blk.number)
    else:
        for side, z in ways:
            end = at(side * reach, z)
            m.emit("line", end, Line(m.pos, end), c.approach_feed, where, blk.number)
    back = at_level(centre, axis, level)
    m.emit("line", back, Line(m.pos, back), c.approach_feed, where, blk.number)


def _slot_point(m: Machine, c: DrillCycle, angle: float, radius: float) -> np.ndarray:
    """Machine point at ``radius`` [mm] and ``angle`` [deg] about cycle 254's pitch-circle centre, at the tool's
    tool-axis position."""
    p, q = PLANE_AXES[m.plane]
    a = math.radians(angle)
    pt, _ = program_target(m, {"XYZ"[p]: c.slot[0] + radius * math.cos(a), "XYZ"[q]: c.slot[1] + radius * math.sin(a)},
                            m.pos)
    pt[m.plane] = m.pos[m.plane]
    return pt


def _slot_ring(m: Machine, c: DrillCycle, h: float, sense: float, feed: float, where: Where,
               blk: SourceBlock) -> None:
    """Once round cycle 254's slot at ``h`` [mm] from its centre line (the tool centre's path), from the outer
    side of its first end: a line out along the radius there, then counter-clockwise (``sense`` > 0) the outer
    arc, the half circle round the far end, the inner arc back and the half circle round the first end;
    clockwise the same path reversed."""
    axis, a0, rp, sweep = m.plane, c.angle, c.slot[2], c.slot[3]
    start = _slot_point(m, c, a0, rp + h)
    m.emit("line", start, Line(m.pos, start), feed, where, blk.number)
    centre, first, last = (_slot_point(m, c, a0, 0.0), _slot_point(m, c, a0, rp), _slot_point(m, c, a0 + sweep, rp))
    legs = [(centre, sweep), (last, 180.0), (centre, -sweep), (first, 180.0)]
    if sense < 0:
        legs = [(first, -180.0), (centre, sweep), (last, -180.0), (centre, -sweep)]
    for pole, turn in legs:
        seg = helical_arc(m.pos, pole, turn, plane=axis, axis_end=m.pos[axis])
        m.emit("arc", np.array(seg.end), seg, feed, where, blk.number)


def _circle_out_and_back(m: Machine, centre: np.ndarray, radius: float, sense: float, feed: float, where: Where,
                         blk: SourceBlock) -> None:
    """At the tool's level: a half circle from ``centre`` out to ``radius`` [mm] on the reference axis, a full
    circle, a half circle back to the centre, turning by ``sense``, at ``feed`` [mm/s] (the countersinking of
    cycles 263-265; nothing for a radius 0)."""
    if radius <= 1e-12:
        return
    axis = m.plane
    here = at_level(centre, axis, m.pos[axis])
    on, _ = program_target(m, {"I" + "XYZ"[PLANE_AXES[axis][0]]: radius / m.lengths(where)}, here)
    for pole, sweep, end in (((here + on) / 2.0, 180.0, on), (here, 360.0, on), ((on + here) / 2.0, 180.0, here)):
        seg = helical_arc(m.pos, pole, math.copysign(sweep, sense), plane=axis, axis_end=m.pos[axis])
        m.emit("arc", np.array(end), seg, feed, where, blk.number)


def _circular_pocket(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """Cycle 252 CIRCULAR POCKET about the current position (TNC 640 user's manual for cycle programming,
    "CIRCULAR POCKET (Cycle 252)", cycle run: FMAX to the set-up clearance, plunge in the centre to each
    plunging depth, rough out from the inside, leaving the allowances Q368/Q369, then up by the set-up
    clearance and at FMAX back to the centre; then finish the wall (in infeeds of Q338) approached
    tangentially, then the floor from the inside out; FMAX to the set-up clearance and the 2nd one).

    The manual leaves the roughing path to the control; our reading, kept inside the pocket: at each
    depth (plunged vertically at Q206) full circles about the centre, Q370 x the tool radius apart, out to
    the pocket radius less the allowance and the tool radius, each reached by a straight step outward
    along the reference axis, at the milling feed Q207, counter-clockwise for climb milling (Q351 = +1).
    The wall is finished at Q385 by a half circle out from the centre, a full circle and a half circle back
    (as cycle 262); the floor by the roughing's circles at the depth out to the wall. Q215 = 0 finishes
    only what has an allowance; Q215 = 2 finishes wall and floor (the old 212/214: the wall only).
    """
    axis = m.plane
    d = -1.0 if c.depth < 0 else 1.0
    top, bottom = surface - d * c.setup, surface + c.depth
    wall = c.bore_diameter / 2.0 - m.tool_radius
    rough = wall - c.side_allowance
    if rough <= 1e-9:
        what = {5: ("radius 5.4", "5.4 RADIUS"), 4: ("sides 4.4, 4.5", "half the shorter side")}.get(
            c.number, ("allowance Q368", "Q223 / 2 less Q368"))
        where.fail(f"cycle {c.number}: the tool (radius {m.tool_radius:g} mm) and the {what[0]} fill the pocket "
                   f"({c.bore_diameter:g} mm)", column=blk.column, text=blk.code,
                   expected=f"a tool radius below {what[1]}")
    step = c.stepover * m.tool_radius or wall
    sense = m.transform.sweep(1.0 if c.climb else -1.0, axis)
    if c.shape == 254:  # at FMAX over the slot's first end (the pitch circle at the starting angle), then down
        first = _slot_point(m, c, c.angle, c.slot[2])
        m.emit("rapid", first, Line(m.pos, first), math.inf, where, blk.number)
    axis_move(m, "rapid", top, math.inf, where, blk)
    centre = m.pos.copy()

    def rings(allowance: float, feed: float) -> None:
        if c.shape in (251, 253):
            _rect_rings(m, c, centre, allowance, step, feed, where, blk)
        elif c.shape == 254:
            h = 0.0
            while h < wall - allowance - 1e-9:
                h = min(h + step, wall - allowance)
                _slot_ring(m, c, h, sense, feed, where, blk)
        else:
            _pocket_rings(m, centre, wall - allowance, step, sense, feed, where, blk)
    if c.operation in (0, 1):
        for level in _depths(surface, bottom - d * c.floor_allowance, c.plunge, d):
            _plunge(m, c, centre, level, rough, sense, where, blk)
            rings(c.side_allowance, c.feed)
            _back_to_centre(m, centre, level - d * c.setup, where, blk)
    if c.operation == 2 or (c.operation == 0 and (c.side_allowance > 0 or c.wall_only)):
        for level in _depths(surface, bottom, c.finish_infeed or abs(c.depth), d):
            axis_move(m, "line", level, c.approach_feed, where, blk)
            if c.shape in (251, 253):
                _rect_wall(m, c, centre, sense, where, blk)
                continue
            if c.shape == 254:
                _slot_ring(m, c, wall, sense, c.finish_feed, where, blk)
                back = at_level(centre, axis, level)
                m.emit("line", back, Line(m.pos, back), c.finish_feed, where, blk.number)
                continue
            k = m.lengths(where)
            start, _ = program_target(m, {"I" + "XYZ"[PLANE_AXES[axis][0]]: wall / k}, m.pos)
            here = m.pos.copy()
            for pole, sweep in (((here + start) / 2.0, 180.0), (here, 360.0), (None, 180.0)):
                pole = (m.pos + here) / 2.0 if pole is None else pole
                seg = helical_arc(m.pos, pole, math.copysign(sweep, sense), plane=axis, axis_end=level)
                m.emit("arc", np.array(seg.end), seg, c.finish_feed, where, blk.number)
    if (c.operation == 2 and not c.wall_only) or (c.operation == 0 and c.floor_allowance > 0):
        axis_move(m, "line", bottom, c.approach_feed, where, blk)
        rings(0.0, c.finish_feed)
        _back_to_centre(m, centre, bottom - d * c.setup, where, blk)
    m.used.update(range(3))
    _out_of_hole(m, c, surface, where, blk)


def _rect_rings(m: Machine, c: DrillCycle, centre: np.ndarray, allowance: float, step: float, feed: float,
                where: Where, blk: SourceBlock) -> None:
    """Cycle 251's roughing (or floor finishing) at the tool's level: rounded rectangles about ``centre``, the
    outer one the pocket less ``allowance`` and the tool radius, the inner ones offset inward by equal steps of
    at most ``step`` [mm]; each entered from the centre side along the pocket's reference axis."""
    half = (c.sides[0] / 2.0 - allowance - m.tool_radius, c.sides[1] / 2.0 - allowance - m.tool_radius)
    if min(half) <= 1e-9:
        where.fail(f"cycle {c.number}: the tool (radius {m.tool_radius:g} mm) and the allowance Q368 fill the pocket",
                   column=blk.column, text=blk.code, expected="a tool radius plus Q368 below Q218 / 2 and Q219 / 2")
    n = max(1, math.ceil(min(half) / step - 1e-9))
    inset = min(half) / n
    corner = max(c.corner - allowance - m.tool_radius, 0.0)
    for j in range(n - 1, -1, -1):
        off = j * inset
        _rect_path(m, c, centre, (half[0] - off, half[1] - off), max(corner - off, 0.0), feed, where, blk)


def _rect_wall(m: Machine, c: DrillCycle, centre: np.ndarray, sense: float, where: Where, blk: SourceBlock) -> None:
    """Cycle 251's wall finishing at the tool's level: out from the centre, round the pocket less the tool
    radius, back to the centre."""
    half = (c.sides[0] / 2.0 - m.tool_radius, c.sides[1] / 2.0 - m.tool_radius)
    _rect_path(m, c, centre, half, max(c.corner - m.tool_radius, 0.0), c.finish_feed, where, blk)
    back = centre.copy()
    back[m.plane] = m.pos[m.plane]
    m.emit("line", back, Line(m.pos, back), c.finish_feed, where, blk.number)


def _rect_path(m: Machine, c: DrillCycle, centre: np.ndarray, half: tuple[float, float], corner: float,
               feed: float, where: Where, blk: SourceBlock, *, ccw: bool | None = None) -> None:
    """From the tool's position a line to the middle of the rectangle's side on the reference axis, then
    once round the rectangle of half sides ``half`` [mm] with corners rounded by ``corner`` [mm] about
    ``centre`` turned by the cycle's angle, counter-clockwise for climb milling (or as ``ccw`` says), at
    ``feed`` [mm/s]."""
    axis = m.plane
    p, q = PLANE_AXES[axis]
    k = m.lengths(where)
    a, b = half
    corner = min(corner, a, b)
    s = 1.0 if (c.climb if ccw is None else ccw) else -1.0  # clockwise: mirrored across the reference axis
    cos, sin = math.cos(math.radians(c.angle)), math.sin(math.radians(c.angle))
    level = centre.copy()
    level[axis] = m.pos[axis]

    def at(u: float, v: float) -> np.ndarray:
        v *= s
        pt, _ = program_target(m, {"I" + "XYZ"[p]: (u * cos - v * sin) / k, "I" + "XYZ"[q]: (u * sin + v * cos) / k},
                                level)
        return pt

    def line(u: float, v: float) -> None:
        pt = at(u, v)
        if np.linalg.norm(pt - m.pos) > 1e-12:
            m.emit("line", pt, Line(m.pos, pt), feed, where, blk.number)

    line(a, 0.0)
    r = corner
    for (u0, v0), (cu, cv) in (((a, b - r), (a - r, b - r)), ((-a + r, b), (-a + r, b - r)),
                               ((-a, -b + r), (-a + r, -b + r)), ((a - r, -b), (a - r, -b + r))):
        line(u0, v0)
        if corner > 1e-12:
            seg = helical_arc(m.pos, at(cu, cv), m.transform.sweep(90.0 * s, axis), plane=axis, axis_end=m.pos[axis])
            m.emit("arc", np.array(seg.end), seg, feed, where, blk.number)
    line(a, 0.0)


def _rectangular_stud(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """Cycle 256 RECTANGULAR STUD about the current position (TNC 640 user's manual for cycle programming
    34059x-01, "RECTANGULAR STUD (Cycle 256)", cycle run: from the stud's centre along +X to the starting
    position 2 mm right of the blank Q424; FMAX to the set-up clearance, at Q206 to the plunging depth; a
    half circle tangentially onto the contour, one revolution; stepovers until the finished size; a half
    circle tangentially off back to the starting position; the next plunging depth; FMAX out).

    Our reading where the manual leaves it open: the revolutions run the rounded rectangle (Q218 x Q219,
    corners Q220, turned by Q224) grown by Q368 and the tool radius, and at equal stepovers of at most Q370
    x the tool radius from the blank Q424 x Q425, clockwise for climb milling (Q351 = +1, M3), each reached
    by a straight stepover along the reference axis; the half circles run the other way. The tool stops at
    the depth less Q369. Q215 = 0/2 with an allowance: one more revolution at the finished size (Q385) at
    each depth of Q338, as roughing; Q215 = 2 runs that finishing alone (Q215: 0 roughing and finishing,
    1 roughing only, 2 finishing only). The tool ends over the starting position. The starting position lies the
    cycle's ``lead`` beyond the blank (256/257: the manual's 2 mm; 213/215: :func:`finishing_cycle`).
    """
    axis = m.plane
    d = -1.0 if c.depth < 0 else 1.0
    top, bottom = surface - d * c.setup, surface + c.depth
    grow = c.side_allowance + m.tool_radius
    final = (c.sides[0] / 2.0 + grow, c.sides[1] / 2.0 + grow)
    blank = (c.blank[0] / 2.0 + m.tool_radius, c.blank[1] / 2.0 + m.tool_radius)
    span = max(blank[0] - final[0], blank[1] - final[1], 0.0)
    n = max(1, math.ceil(span / (c.stepover * m.tool_radius or span or 1.0) - 1e-9))
    cw = c.climb
    k = m.lengths(where)
    cos, sin = math.cos(math.radians(c.angle)), math.sin(math.radians(c.angle))
    centre = m.pos.copy()
    plane = PLANE_AXES[axis]

    def at(u: float) -> np.ndarray:
        pt, _ = program_target(m, {"I" + "XYZ"[plane[0]]: u * cos / k, "I" + "XYZ"[plane[1]]: u * sin / k}, centre)
        pt[axis] = m.pos[axis]
        return pt

    start_u = c.blank[0] / 2.0 + c.lead + m.tool_radius
    first = at(start_u)
    m.emit("rapid", first, Line(m.pos, first), math.inf, where, blk.number)
    axis_move(m, "rapid", top, math.inf, where, blk)
    half = m.transform.sweep(180.0 if cw else -180.0, axis)  # the half circles: against the revolutions
    passes = [(j * span / n, c.feed) for j in range(n - 1, -1, -1)]
    levels = [(z, passes) for z in _depths(surface, bottom - d * c.floor_allowance, c.plunge, d)
              if c.operation in (0, 1)]  # Q215 = 2: finishing only
    if c.operation == 2 or (c.operation == 0 and c.side_allowance > 0):
        levels += [(z, [(-c.side_allowance, c.finish_feed)]) for z in _depths(surface, bottom,
                                                                                c.finish_infeed or abs(c.depth), d)]
    def half_circle(u: float, level: float, feed: float) -> None:
        """The half circle to ``at(u)``; none where the tool is there (213 with Q221 = 0, 215 with Q222 = Q223:
        no lead, the tool plunges on the contour: our reading)."""
        if np.hypot(*(at(u) - m.pos)[list(plane)]) > 1e-9:
            seg = helical_arc(m.pos, (m.pos + at(u)) / 2.0, half, plane=axis, axis_end=level)
            m.emit("arc", np.array(seg.end), seg, feed, where, blk.number)

    for level, rounds in levels:
        axis_move(m, "line", level, c.approach_feed, where, blk)
        for i, (off, feed) in enumerate(rounds):
            a = final[0] + off
            if i == 0:
                half_circle(a, level, feed)
            _rect_path(m, c, at_level(centre, axis, level), (a, final[1] + off), max(c.corner + grow + off, 0.0),
                       feed, where, blk, ccw=not cw)
        half_circle(start_u, level, rounds[-1][1])
    m.used.update(range(3))
    _out_of_hole(m, c, surface, where, blk)


def _out_of_hole(m: Machine, c: DrillCycle, surface: float, where: Where, blk: SourceBlock) -> None:
    """The end of a cycle's run at a hole: at FMAX along the tool axis to the set-up clearance above ``surface``
    [mm, machine], then to the 2nd set-up clearance when it is higher (:func:`interpolators.heidenhain_cycles.
    to_second_clearance`)."""
    d = -1.0 if c.depth < 0 else 1.0
    for mv in (AxisMove("rapid", surface - d * c.setup), *to_second_clearance(c, surface=surface)):
        axis_move(m, mv.kind, mv.level, mv.feed, where, blk)


def at_level(point: np.ndarray, axis: int, level: float) -> np.ndarray:
    """``point`` with its ``axis`` coordinate ``level``."""
    out = point.copy()
    out[axis] = level
    return out


def _depths(surface: float, bottom: float, step: float, d: float) -> list[float]:
    """The levels from ``surface`` in steps of ``step`` toward ``bottom`` (the last one ``bottom``) [mm]."""
    n = max(1, math.ceil(abs(bottom - surface) / step - 1e-9))
    return [surface + d * min(step * (i + 1), abs(bottom - surface)) for i in range(n)]


def _pocket_rings(m: Machine, centre: np.ndarray, radius: float, step: float, sense: float, feed: float,
                  where: Where, blk: SourceBlock) -> None:
    """Full circles about ``centre`` (at the tool's level), ``step`` apart out to ``radius`` [mm], each reached
    by a straight step outward along the program's reference axis at ``feed`` [mm/s]."""
    axis = m.plane
    pole = centre.copy()
    pole[axis] = m.pos[axis]
    k = m.lengths(where)
    r = 0.0
    while r < radius - 1e-9:
        r = min(r + step, radius)
        out, _ = program_target(m, {"I" + "XYZ"[PLANE_AXES[axis][0]]: r / k}, pole)
        m.emit("line", out, Line(m.pos, out), feed, where, blk.number)
        seg = helical_arc(m.pos, pole, math.copysign(360.0, sense), plane=axis, axis_end=m.pos[axis])
        m.emit("arc", np.array(seg.end), seg, feed, where, blk.number)


def _back_to_centre(m: Machine, centre: np.ndarray, level: float, where: Where, blk: SourceBlock) -> None:
    """At FMAX up to ``level`` [mm], then over the pocket's ``centre``."""
    axis_move(m, "rapid", level, math.inf, where, blk)
    target = centre.copy()
    target[m.plane] = level
    if not np.array_equal(target, m.pos):
        m.emit("rapid", target, Line(m.pos, target), math.inf, where, blk.number)


def pattern_cycle_run(pat: PatternCycle, m: Machine, where: Where, blk: SourceBlock) -> None:
    """Cycle 220/221 runs the last machining cycle at each of its positions (TNC 320 cycle manual,
    cycle 220 "Cycle run": at rapid to the 2nd set-up clearance, to the first position in the
    plane, the machining cycle from the set-up clearance; to the next positions at the set-up
    clearance, or at the 2nd with Q301 = 1; the pattern's Q200, Q203, Q204 replace the
    machining cycle's). After the last position the tool is at the 2nd set-up clearance. Cycle 220 with
    Q365 = 1 moves from one position to the next on the pitch circle (TNC 640 cycle programming manual
    34059x-01, cycle 220 "Cycle run" 3: "on a straight line or circular arc"), at rapid traverse as the
    straight moves (our reading: the manual names the rapid for the first position only).

    The old cycles 1 PECKING, 2 TAPPING and 17 RIGID TAPPING (:data:`PATTERN_OLD_CYCLES`; an iTNC 530 shop
    program taps with cycle 2 on cycle 220's positions) start where the tool stands, their surface their own
    set-up clearance below it (TNC 426/430 user's manual, cycles 1 and 2: "Set-up clearance: distance between
    tool tip (at starting position) and workpiece surface"): the pattern takes the tool at rapid to its set-up
    clearance Q200 above its surface Q203 and runs the cycle from there, which is the same surface when
    Q200 equals the cycle's set-up clearance (another value is an error: which surface would count, no
    manual page found says); after the cycle, back at that start, the tool rises at rapid to the 2nd set-up
    clearance before the next position with Q301 = 1 and after the last one (our reading)."""
    _check_pattern_cycle(pat, m, where, blk)
    old = m.cycle.surface is None
    base = dataclasses.replace(m.cycle, setup=pat.setup, surface=pat.surface, second_setup=pat.second_setup)
    scaled = base if m.transform.identity else scaled_cycle(base, m.transform.axis_factor(m.plane))
    axis, p, q = m.plane, *PLANE_AXES[m.plane]
    d = -1.0 if scaled.depth < 0 else 1.0
    surface = surface_level(m, scaled.surface, 0.0)
    clear = surface - d * max(scaled.setup, scaled.second_setup)
    axis_move(m, "rapid", clear, math.inf, where, blk)
    for k, (u, v) in enumerate(pat.points):
        target, _ = program_target(m, {"XYZ"[p]: u, "XYZ"[q]: v}, m.pos)
        target[axis] = m.pos[axis]
        if k and pat.centre is not None:
            _pitch_circle_move(m, pat, target, where, blk)
        elif not np.array_equal(target, m.pos):
            m.emit("rapid", target, Line(m.pos, target), math.inf, where, blk.number)
        high = pat.high or k == len(pat.points) - 1
        if old:
            axis_move(m, "rapid", surface - d * scaled.setup, math.inf, where, blk)
            run_hole(m, dataclasses.replace(scaled, second_setup=0.0), surface, where, blk)
            if high:
                axis_move(m, "rapid", clear, math.inf, where, blk)
        else:
            run_hole(m, scaled if high else dataclasses.replace(scaled, second_setup=0.0), surface, where, blk)


#: The old cycles a pattern cycle 220/221 runs (:func:`pattern_cycle_run`).
PATTERN_OLD_CYCLES: tuple[int, ...] = (1, 2, 17)


def _check_pattern_cycle(pat: PatternCycle, m: Machine, where: Where, blk: SourceBlock) -> None:
    """An error unless the defined cycle is one a pattern runs: a drilling or milling cycle of the 200 series
    (not the SL and surface cycles), or an old cycle of :data:`PATTERN_OLD_CYCLES` whose set-up clearance is
    the pattern's Q200."""
    number = getattr(m.cycle, "number", None)  # SL cycles 21/24/25 carry none
    if m.cycle is None or isinstance(m.cycle, (ContourTrain, RoughOut, SideFinish, PilotDrill, SurfaceCycle,
                                               RuledSurface)) or (m.cycle.surface is None
                                                                  and number not in PATTERN_OLD_CYCLES):
        # which of the other cycles a pattern runs, and from where, no manual page found says (the
        # TNC 320 cycle manual gives the pattern's run for the 200 series, whose Q200/Q203/Q204 it replaces)
        what = ("without a machining cycle" if m.cycle is None else f"with cycle {number}" if number
                else "with an SL cycle")
        where.fail(f"cycle {pat.number} {what}: a pattern runs the machining cycles of the 200 series and the old "
                   f"cycles {', '.join(map(str, PATTERN_OLD_CYCLES))} here", column=blk.column, text=blk.code,
                   expected="CYCL DEF 200..240 or CYCL DEF 1, 2, 17 before the pattern cycle")
    if m.cycle.surface is None and abs(m.cycle.setup - pat.setup) > 1e-9:
        where.fail(f"cycle {pat.number} with cycle {number}: the pattern's set-up clearance Q200 "
                   f"({pat.setup / m.scale:g}) differs from the cycle's ({m.cycle.setup / m.scale:g}) (the old cycle "
                   "counts its depth from its own set-up clearance below the tool; which surface then counts, no "
                   "manual page found says)", column=blk.column, text=blk.code,
                   expected=f"Q200 = {m.cycle.setup / m.scale:g}, the set-up clearance of cycle {number}")


def _pitch_circle_move(m: Machine, pat: PatternCycle, target: np.ndarray, where: Where, blk: SourceBlock) -> None:
    """Cycle 220 Q365 = 1: from the tool's position along the pitch circle by ``pat.step`` to ``target``
    (the next position, at the tool's height), at rapid traverse (see :func:`pattern_cycle_run`)."""
    axis, p, q = m.plane, *PLANE_AXES[m.plane]
    m.lengths(where, blk, what="cycle 220 Q365=1 (arcs on the pitch circle)")
    centre, _ = program_target(m, {"XYZ"[p]: pat.centre[0], "XYZ"[q]: pat.centre[1]}, m.pos)
    centre[axis] = m.pos[axis]
    if not np.array_equal(target, m.pos):
        seg = Arc(m.pos, target, centre, ccw=m.transform.sweep(pat.step, axis) > 0, plane=axis)
        m.emit("arc", target, seg, math.inf, where, blk.number)


def active_cycle(m: Machine) -> DrillCycle:
    """The defined machining cycle with its tool-axis lengths scaled by cycles 11/26 ("the scaling
    factor also affects the dimensions in cycles")."""
    if m.transform.identity:
        return m.cycle
    return scaled_cycle(m.cycle, m.transform.axis_factor(m.plane))


def surface_level(m: Machine, surface: float, shift: float) -> float:
    """Machine tool-axis coordinate [mm] of a cycle's surface (Q203) [mm] plus an extra ``shift``
    (a pattern position's or CYCL CALL POS's tool-axis coordinate) [mm]."""
    if m.transform.identity:
        return m.origin()[m.plane] + surface + shift
    return m.axis_level(surface + shift)


def axis_move(m: Machine, kind: str, level: float, feed: float, where: Where, blk: SourceBlock) -> None:
    if level != m.pos[m.plane]:
        target = m.pos.copy()
        target[m.plane] = level
        m.emit(kind, target, Line(m.pos, target), feed, where, blk.number)
