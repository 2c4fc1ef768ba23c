"""The calls of the last machining cycle of Heidenhain conversational programs: ``M99`` / ``CYCL CALL`` (and the
program of cycle 12 PGM CALL), ``CYCL CALL PAT`` at the points of ``PATTERN DEF``, ``CYCL CALL POS``; each runs
the cycle's moves (:mod:`interpolators.heidenhain_cycle_moves`, the SL cycles' :mod:`interpolators.heidenhain_sl`)
on the machine state :class:`interpolators.heidenhain.Machine`.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.heidenhain_contours import ROUGHING_CYCLES, ContourTrain, PilotDrill, RoughOut, SideFinish
from interpolators.heidenhain_cycle_moves import active_cycle, axis_move, run_hole, run_surface, surface_level
from interpolators.heidenhain_cycles import LEGACY_CYCLES, MACHINING_CYCLES
from interpolators.heidenhain_sl import contour_train, pilot_drill, rough_out, side_finish
from interpolators.heidenhain_surfaces import RuledSurface, SurfaceCycle
from interpolators.heidenhain_targets import plane_coords, program_target
from interpolators.heidenhain_words import SourceBlock, Word
from toolpaths.geometry import PLANE_AXES, Line

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine

__all__ = ["positioning_feed", "pattern_call", "position_call", "cycle_call"]


def positioning_feed(words: list[Word], m: Machine, where: Where) -> float:
    """The feed [mm/s] of ``CYCL CALL PAT F..`` between the pattern's points: F, or rapid for F MAX and
    without F (inf)."""
    for w in words:
        if w.key == "F":
            if not w.value > 0:
                where.fail("feed F must be > 0", column=w.column, text=w.text, expected="F > 0 [mm/min] or F MAX")
            return w.value * m.feed_scale
    return math.inf


def pattern_call(m: Machine, where: Where, blk: SourceBlock, feed: float = math.inf) -> None:
    """``CYCL CALL PAT [F..|F MAX]``: the cycle at every position of the last ``PATTERN DEF``, the tool
    positioned between them at the block's feed (F MAX or none: rapid). The TNC 640 user's manual (cycle
    programming, "Calling a cycle with CYCL CALL PAT") offers the feed in the block's dialog; no manual
    page found says which moves it covers: our reading, the moves from hole to hole (up to the clearance
    height, across in the plane), not those of the cycle."""
    if m.pattern is None:
        where.fail("CYCL CALL PAT without a PATTERN DEF", column=blk.column, text=blk.code,
                   expected="PATTERN DEF POS1 (...) before CYCL CALL PAT")
    p, q = PLANE_AXES[m.plane]
    point = m.pos.copy()
    for pos in m.pattern:
        values = {k: v * m.scale for k, v in pos.items() if k[-1] in ("XYZ"[p], "XYZ"[q])}
        point, _ = program_target(m, values, point)
        axis = "XYZ"[m.plane]
        if "I" + axis in pos:
            where.fail("incremental surface in a pattern position", column=blk.column, text=blk.code,
                       expected=f"{axis} (absolute) in PATTERN DEF")
        cycle_call(m, where, blk, hole=point.copy(), surface_shift=pos.get(axis, 0.0) * m.scale, feed=feed)


def _program_cycle_elsewhere(where: Where, blk: SourceBlock) -> None:
    """Cycle 12 PGM CALL called at a pattern's points or by CYCL CALL POS: an error (no manual found says
    where the called program starts from there)."""
    where.fail("cycle 12 PGM CALL by a pattern or CYCL CALL POS is not supported", column=blk.column,
               text=blk.code, expected="M99 or CYCL CALL after CYCL DEF 12")


def position_call(words: list[Word], m: Machine, where: Where, blk: SourceBlock) -> None:
    """``CYCL CALL POS X.. Y.. Z.. F..``: move to the position, then run the cycle there.

    TNC 640 user's manual (cycle programming, "Calling a cycle with CYCL CALL POS"): all three
    coordinates are programmed; the tool-axis coordinate is the starting position and an
    additional datum shift of the cycle's surface; the TNC moves without radius compensation, at
    the feed of the block (F MAX: rapid), first in the working plane and then in the tool axis
    when the tool is above the surface (Q203), else first in the tool axis to the clearance
    height, then in the plane, then in the tool axis.
    """
    if m.cycle_program is not None:
        _program_cycle_elsewhere(where, blk)
    m.refresh_cycle(where, blk.column)
    if m.cycle is None:
        _no_cycle(m, where, blk, "CYCL CALL POS")
    _no_contour_train(m, where, blk)
    seen = {w.key: w for w in words}
    for a in "XYZ":
        if a not in seen and "I" + a not in seen:
            where.fail(f"CYCL CALL POS without {a}", column=blk.column, text=blk.code,
                       expected="CYCL CALL POS X.. Y.. Z.. (all three coordinates)")
    if "F" in seen and not seen["F"].value > 0:
        where.fail("feed F must be > 0", column=seen["F"].column, text=seen["F"].text, expected="F > 0 [mm/min]")
    feed = seen["F"].value * m.feed_scale if "F" in seen else (math.inf if "FMAX" in seen else m.feed)
    if feed is None:
        where.fail("CYCL CALL POS without a feed", column=blk.column, text=blk.code, expected="F or F MAX")
    target, _ = plane_coords(seen, m, where, m9x=None)
    axis, c = m.plane, active_cycle(m)
    shift = target[axis] - m.origin()[axis] if m.transform.identity else m.to_program(target)[axis]
    d = -1.0 if c.depth < 0 else 1.0
    surface = m.pos[axis] + d * c.setup if c.surface is None else surface_level(m, c.surface, shift)
    kind = "rapid" if math.isinf(feed) else "line"
    in_plane = target.copy()
    if d * (m.pos[axis] - surface) < 0:  # above the surface: plane first, then the tool axis
        in_plane[axis] = m.pos[axis]
    else:  # at or below it: up to the clearance height first
        axis_move(m, kind, surface - d * max(c.setup, c.second_setup), feed, where, blk)
        in_plane[axis] = m.pos[axis]
    if not np.array_equal(in_plane, m.pos):
        m.emit(kind, in_plane, Line(m.pos, in_plane), feed, where, blk.number)
    axis_move(m, kind, target[axis], feed, where, blk)
    m.used.update(range(3))
    cycle_call(m, where, blk, surface_shift=shift)


def cycle_call(m: Machine, where: Where, blk: SourceBlock, *, hole: np.ndarray | None = None,
                surface_shift: float = 0.0, feed: float = math.inf) -> None:
    """Run the last machining cycle at the current position, or at ``hole`` (CYCL CALL PAT:
    reached at ``feed`` [mm/s] (inf: rapid) at the clearance height, the 2nd set-up clearance). After ``CYCL DEF 12 PGM
    CALL`` the cycle is that program (TNC 640 manual, cycle 12 PGM CALL: "the program is called
    like a cycle"), run as ``CALL PGM``, where the tool is."""
    if m.cycle_program is not None:
        if hole is not None or surface_shift:
            _program_cycle_elsewhere(where, blk)
        m.runner.run_program(*m.cycle_program, where)
        return
    m.refresh_cycle(where, blk.column)
    if m.cycle is None:
        _no_cycle(m, where, blk, "M99 / CYCL CALL")
    if isinstance(m.cycle, (ContourTrain, RoughOut, SideFinish, PilotDrill, SurfaceCycle, RuledSurface)):
        if hole is not None or surface_shift:
            _no_contour_train(m, where, blk)
        if isinstance(m.cycle, (SurfaceCycle, RuledSurface)):
            run_surface(m, m.cycle, where, blk)
        elif isinstance(m.cycle, RoughOut):
            rough_out(m, m.cycle, where, blk)
        elif isinstance(m.cycle, SideFinish):
            side_finish(m, m.cycle, where, blk)
        elif isinstance(m.cycle, PilotDrill):
            pilot_drill(m, m.cycle, where, blk)
        else:
            contour_train(m, m.cycle, where, blk)
        return
    c = active_cycle(m)
    axis = m.plane
    d = -1.0 if c.depth < 0 else 1.0
    if c.surface is None:
        surface = m.pos[axis] + d * c.setup
    else:
        surface = surface_level(m, c.surface, surface_shift)
    if hole is not None:
        clear = surface - d * max(c.setup, c.second_setup) if c.surface is not None else m.pos[axis]
        kind = "rapid" if math.isinf(feed) else "line"
        if d * (m.pos[axis] - clear) > 0:  # below the clearance height
            axis_move(m, kind, clear, feed, where, blk)
        target = np.array(hole, dtype=float)
        target[axis] = m.pos[axis]
        if not np.array_equal(target, m.pos):
            m.emit(kind, target, Line(m.pos, target), feed, where, blk.number)
    run_hole(m, c, surface, where, blk)


def _no_contour_train(m: Machine, where: Where, blk: SourceBlock) -> None:
    """An error when the cycle to run at positions (CYCL CALL POS / PAT) is an SL cycle (22, 25) or a
    multipass-milling cycle (230-232: placed by their own points; 233: the tool-axis coordinate of a position
    would shift Q227, which no manual found describes)."""
    if isinstance(m.cycle, (SurfaceCycle, RuledSurface)):
        where.fail(f"cycle {m.cycle.number} at positions (CYCL CALL POS / PAT) is not supported", column=blk.column,
                   text=blk.code, expected="CYCL CALL or M99 (233: at the surface's corner; the others: their own "
                                           "points Q225.. place them)")
    if isinstance(m.cycle, (ContourTrain, RoughOut, SideFinish, PilotDrill)):
        number = {ContourTrain: 25, SideFinish: 24, PilotDrill: 21}.get(type(m.cycle)) or m.cycle.number
        name = f"{number} {ROUGHING_CYCLES.get(number, 'CONTOUR TRAIN')}"
        where.fail(f"cycle {name} at positions (CYCL CALL POS / PAT) is not supported", column=blk.column,
                   text=blk.code, expected="CYCL CALL or M99 after the SL cycle (the contour gives the positions)")


def _no_cycle(m: Machine, where: Where, blk: SourceBlock, call: str) -> None:
    """The error of a cycle call without a machining cycle, naming an old cycle whose definition stopped short."""
    n = m.incomplete_cycle
    if n is not None:
        last = LEGACY_CYCLES[n]
        where.fail(f"cycle call after an incomplete CYCL DEF {n} (its lines {n}.1 .. {n}.{last} not all given)",
                   column=blk.column, text=blk.code, expected=f"CYCL DEF {n}.0 .. {n}.{last} before {call}")
    where.fail("cycle call without a machining cycle", column=blk.column, text=blk.code,
               expected=f"a CYCL DEF {', '.join(map(str, MACHINING_CYCLES))} before {call}")
