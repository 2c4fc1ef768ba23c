"""The multipass-milling cycles of Heidenhain conversational programs: surfaces milled in lines.

These cycles are placed by absolute coordinates in their definition (a starting point Q225, Q226, Q227), not
at the tool's position, so their moves are worked out here as points in program coordinates; the reader
carries them through the active transformations (:func:`surface_moves`).

========================= ==================================================================
``CYCL DEF 232``          FACE MILLING, strategies Q389 = 0, 1, 2 (:func:`face_milling_cycle`)
``CYCL DEF 230``          MULTIPASS MILLING, Q240 lines meandering at one height (:func:`multipass_cycle`)
``CYCL DEF 231``          RULED SURFACE between four points, Q240 lines (:func:`ruled_surface_cycle`)
``CYCL DEF 233``          FACE MILLING of the TNC 640: the surface from the tool's position, Q350 direction,
                          Q389 = 0 .. 3, Q215 roughing / finishing (:func:`face_milling_233`); its side walls
                          (limits Q347-Q349) and the helical strategy Q389 = 4 are errors
========================= ==================================================================
"""

from __future__ import annotations

import dataclasses
import math

from interpolators._words import Where

__all__ = ["MAX_LINES", "SURFACE_CYCLES", "SurfaceCycle", "RuledSurface", "SurfaceMove", "face_milling_cycle",
           "face_milling_233", "multipass_cycle", "ruled_surface_cycle", "ruled_surface_moves", "surface_cycle",
           "surface_moves"]

#: The multipass-milling cycles this module runs.
SURFACE_CYCLES: tuple[int, ...] = (230, 231, 232, 233)

#: Most lines of one level of cycle 232 (a guard against a tiny tool radius or stepover factor).
MAX_LINES = 100_000

_REQUIRED = {
    232: (389, 225, 226, 227, 386, 218, 219, 202, 207, 200, 357, 204),
    230: (225, 226, 227, 218, 219, 240, 206, 207, 209, 200),
    231: (225, 226, 227, 228, 229, 230, 231, 232, 233, 234, 235, 236, 240, 207),
    233: (389, 350, 218, 219, 227, 386, 202, 207, 200, 204),
}


@dataclasses.dataclass(frozen=True, kw_only=True)
class SurfaceCycle:
    """A multipass-milling cycle as defined, in mm, mm/s [program coordinates].

    Attributes
    ----------
    number : int
        232 or 233 FACE MILLING, or 230 MULTIPASS MILLING.
    strategy : int
        232: Q389, 0 meander with the stepover outside the surface, 1 meander with the stepover within it,
        2 line by line, back over the surface at the set-up clearance (230: 0, a meander); 233: Q389, 0 and 1
        meander, 2 and 3 line by line, the lines' end points beyond the far edge by the tool radius plus Q357
        (0, 2) or by Q357 (1, 3).
    start : tuple of float
        Q225, Q226, Q227: the starting point in the reference, minor and tool axes [mm] (233: the tool's position
        in the plane when the cycle is called, and Q227).
    sides : tuple of float
        Q218, Q219: the surface's side lengths along the reference and minor axes, their signs the direction
        of the first milling path and of the first stepover [mm].
    direction : int
        233: Q350, the axis the lines run along, 1 the reference axis, 2 the minor axis (others: 1).
    operation : int
        233: Q215, 0 roughing and finishing, 1 roughing only, 2 finishing only (others: 0).
    end_level : float
        232: Q386, the tool-axis coordinate the surface is milled down to [mm] (230: Q227, one height).
    plunge : float
        232: Q202, the largest infeed [mm]; the infeeds are equal.
    allowance : float
        232: Q369, the floor allowance, milled in the last infeed at ``finish_feed`` [mm].
    stepover : float
        232: Q370, the largest stepover as a factor of the tool radius [-].
    lines : int
        230: Q240, the number of lines (0: from ``stepover``).
    feed, finish_feed, approach_feed, step_feed, return_feed : float
        Q207 milling, Q385 finishing (232, 233), the infeed to each level (232: Q253 pre-positioning, 233: Q207,
        230: Q206 plunging), the stepover feed (232: Q253, with Q389 = 1 Q207; 233: Q253; 230: Q209) and the
        move back to the next line's start of the line-by-line strategies (232: Q253; 233: ``inf``, rapid)
        [mm/s].
    setup, side_clearance, second_setup : float
        Q200 set-up clearance above ``start``'s tool-axis coordinate, Q357 clearance to the side (232), Q204
        2nd set-up clearance above it (230: Q200) [mm].
    """

    number: int
    strategy: int
    start: tuple[float, float, float]
    sides: tuple[float, float]
    end_level: float
    plunge: float = 0.0
    allowance: float = 0.0
    stepover: float = 1.0
    lines: int = 0
    feed: float
    finish_feed: float
    approach_feed: float
    step_feed: float
    return_feed: float = 0.0
    setup: float
    side_clearance: float = 0.0
    second_setup: float
    direction: int = 1
    operation: int = 0


@dataclasses.dataclass(frozen=True)
class SurfaceMove:
    """One move of a multipass-milling cycle.

    Attributes
    ----------
    kind : {"rapid", "line"}
    point : tuple of float
        The end point in the reference, minor and tool axes [mm, program]; ``None`` in a coordinate keeps the
        tool's (the positioning moves of one axis group).
    feed : float
        [mm/s]; ``inf`` for rapids.
    """

    kind: str
    point: tuple[float | None, float | None, float | None]
    feed: float = math.inf


def _required(number: int, q: dict[int, float], where: Where, column: int) -> None:
    missing = [f"Q{k}" for k in _REQUIRED[number] if k not in q]
    if missing:
        where.fail(f"cycle {number} lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="the cycle's Q parameters: " + " ".join(f"Q{k}" for k in _REQUIRED[number]))


@dataclasses.dataclass(frozen=True, kw_only=True)
class RuledSurface:
    """Cycle 231 RULED SURFACE as defined, in mm, mm/s [program coordinates].

    Attributes
    ----------
    number : int
        231.
    corners : tuple of tuple of float
        Points 1 (Q225-Q227), 2 (Q228-Q230), 3 (Q231-Q233) and 4 (Q234-Q236) in the reference, minor and tool
        axes [mm]: the lines run from the edge 1-4 to the edge 2-3.
    lines : int
        Q240, the number of cuts.
    feed : float
        Q207, the milling feed [mm/s] (the first line at half of it).
    """

    number: int = 231
    corners: tuple[tuple[float, float, float], ...]
    lines: int
    feed: float


def ruled_surface_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                        column: int) -> RuledSurface:
    """Cycle 231 RULED SURFACE from its Q parameters (TNC 410/426/430 ISO programming user's manual, "Cycles for
    multipass milling", RULED SURFACE, p. 292, https://azmanual.top/manuals/798543/heidenhain-tnc-410-iso-
    programming.html?page=318): Q225-Q227 the starting point 1, Q228-Q230 the 2nd point, Q231-Q233 the 3rd,
    Q234-Q236 the 4th, each absolute; Q240 "Number of passes to be made between points 1 and 4, 2 and 3"; Q207
    the milling feed ("The TNC performs the first step at half the programmed feed rate"). The moves are
    :func:`ruled_surface_moves`."""
    _required(231, q, where, column)
    lines = int(q[240])
    if lines < 1 or lines != q[240] or lines > MAX_LINES or not q[207] > 0:
        where.fail(f"cycle 231: Q240={q[240]:g} cuts, Q207={q[207]:g}", column=column, text=where.text,
                   expected=f"a whole number of cuts Q240 1 .. {MAX_LINES}, a feed Q207 > 0")
    corners = tuple(tuple(q[k] * scale for k in (first, first + 1, first + 2)) for first in (225, 228, 231, 234))
    return RuledSurface(corners=corners, lines=lines, feed=q[207] * feed_scale)


def ruled_surface_moves(c: RuledSurface, *, radius: float) -> list[SurfaceMove]:
    """The moves of cycle 231 for a tool of ``radius`` [mm] (the cycle run of the TNC 426/430 user's manual,
    "RULED SURFACE (Cycle 231)", whose pages were not among the texts found: our reading of it): at FMAX in a
    3-D line to point 1; the lines from the edge 1-4 to the edge 2-3, the j-th from 1 + j (4 - 1) / (Q240 - 1) to
    2 + j (3 - 2) / (Q240 - 1) (one line, 1 to 2, with Q240 = 1), the first at Q207 / 2, the others at Q207;
    after each line at FMAX up by the tool diameter, back over the line's start, down to it, at Q207 in all three
    axes to the next line's start; at the end at FMAX to the tool diameter above the highest of the four points."""
    p1, p2, p3, p4 = (tuple(map(float, pt)) for pt in c.corners)
    n = c.lines - 1

    def along(a: tuple, b: tuple, j: int) -> tuple[float, float, float]:
        f = j / n if n else 0.0
        return tuple(a[i] + (b[i] - a[i]) * f for i in range(3))

    lift = 2.0 * radius
    out = [SurfaceMove("rapid", p1)]
    for j in range(c.lines):
        start, end = along(p1, p4, j), along(p2, p3, j)
        if j:
            out.append(SurfaceMove("line", start, c.feed))
        out.append(SurfaceMove("line", end, c.feed / 2.0 if j == 0 else c.feed))
        if j < n:
            out += [SurfaceMove("rapid", (None, None, end[2] + lift)), SurfaceMove("rapid", (*start[:2], None)),
                    SurfaceMove("rapid", (None, None, start[2]))]
    out.append(SurfaceMove("rapid", (None, None, max(pt[2] for pt in c.corners) + lift)))
    return out


def surface_cycle(number: int, q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                  column: int) -> SurfaceCycle | RuledSurface:
    """Cycle 230, 231, 232 or 233 from its Q parameters."""
    for k, v in q.items():
        if math.isinf(v) and not (number in (232, 233) and k == 253):
            where.fail(f"cycle {number}: Q{k}=MAX is not a value here", column=column, text=where.text,
                       expected=f"Q{k}=<number>")
    if number == 230:
        return multipass_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if number == 231:
        return ruled_surface_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if number == 233:
        return face_milling_233(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    return face_milling_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)


def face_milling_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                       column: int) -> SurfaceCycle:
    """Cycle 232 FACE MILLING from its Q parameters (TNC 640 user's manual for cycle programming 34059x-01,
    "FACE MILLING (Cycle 232)", p. 235-238; TNC 320 user's manual 340 551-02, "Cycles for multipass milling",
    p. 298): Q389 strategy (0, 1, 2), Q225/Q226/Q227 the starting point, Q386 the end point in the tool axis,
    Q218/Q219 the side lengths (signed), Q202 the largest plunging depth, Q369 the floor allowance (the last
    infeed), Q370 the largest stepover factor (default 1), Q207 milling, Q385 finishing (default Q207), Q253
    pre-positioning feed (default Q207, ``MAX``: rapid), Q200 set-up clearance, Q357 clearance to the side, Q204
    2nd set-up clearance. The moves are :func:`surface_moves`. A starting point below
    the end point in the tool axis is an error (our reading: the TNC faces downward only)."""
    _required(232, q, where, column)
    strategy = int(q[389])
    if strategy not in (0, 1, 2) or q[389] != strategy:
        where.fail(f"cycle 232: Q389={q[389]:g} is not a strategy", column=column, text=where.text,
                   expected="Q389=0, 1 or 2")
    _levels_checked(232, q, where, column)
    feed = q[207] * feed_scale
    approach = (q.get(253, 0.0) or q[207]) * feed_scale
    return SurfaceCycle(
        number=232, strategy=strategy, start=(q[225] * scale, q[226] * scale, q[227] * scale),
        sides=(q[218] * scale, q[219] * scale), end_level=q[386] * scale, plunge=abs(q[202]) * scale,
        allowance=abs(q.get(369, 0.0)) * scale, stepover=q.get(370, 1.0), feed=feed,
        finish_feed=(q.get(385, 0.0) or q[207]) * feed_scale, approach_feed=approach,
        step_feed=feed if strategy == 1 else approach, return_feed=approach, setup=abs(q[200]) * scale,
        side_clearance=abs(q[357]) * scale, second_setup=abs(q[204]) * scale)


def _levels_checked(number: int, q: dict[int, float], where: Where, column: int) -> None:
    """The checks of the tool-axis values 232 and 233 share: Q227 above Q386 by at least the allowance Q369, the
    milling feed Q207, the stepover factor Q370 and (with infeeds to make) the plunging depth Q202 > 0, at most
    10000 infeeds."""
    depth = q[227] - q[386] - abs(q.get(369, 0.0))
    if q[227] <= q[386] or depth < 0:
        where.fail(f"cycle {number}: the starting point Q227 must lie above the end point Q386 by at least the "
                   "allowance Q369", column=column, text=where.text, expected="Q227 > Q386 + Q369")
    if not q[207] > 0 or not q.get(370, 1.0) > 0 or (depth > 0 and not q[202] > 0):
        where.fail(f"cycle {number}: the milling feed Q207, the stepover factor Q370 and the plunging depth Q202 "
                   "must be > 0", column=column, text=where.text, expected="Q207 > 0, Q370 > 0, Q202 > 0")
    if depth / max(abs(q[202]), 1e-12) > 10_000:
        where.fail(f"cycle {number}: {depth:g} in plunges of {q[202]:g} are more than 10000 infeeds", column=column,
                   text=where.text, expected="a larger plunging depth Q202")


def face_milling_233(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                     column: int) -> SurfaceCycle:
    """Cycle 233 FACE MILLING from its Q parameters (TNC7 basic user's manual 81762x-19, "Cycle 233 FACE
    MILLING", https://content.heidenhain.de/doku/tnc_guide/pdf_files/TNC7_basic/81762x-19/html5/
    TNC7basic_EN_81762x-19.tncdoc; the same cycle as the TNC 640's): Q215 machining operation (0 roughing and
    finishing, 1 only roughing, 2 only finishing), Q389 strategy (0 meander, stepover outside the surface; 1
    meander, stepover at its edge; 2 line by line with overtravel, 3 without, the stepover when retracting at
    rapid traverse; 4 helical, an error here), Q350 milling direction (1 the lines along the reference axis, 2
    along the minor axis), Q218/Q219 the side lengths along the reference and minor axes from the starting
    point (signed), Q227 the starting point and Q386 the end point in the tool axis, Q369 the floor allowance,
    Q202 the largest plunging depth, Q370 the largest stepover factor, Q207 milling, Q385 finishing, Q253
    pre-positioning feed (``MAX``: rapid), Q357 clearance to the side, Q200 set-up clearance, Q204 2nd set-up
    clearance; the limits Q347, Q348, Q349 (side walls) must be 0, the side-wall parameters Q220, Q368 and Q338
    then have nothing to act on. The starting point in the plane is the tool's position when the cycle is
    called (our reading: the cycle has no Q225/Q226, and the manual measures the side lengths "from the
    starting point"); a Q367 (a surface position relative to the tool) is an error: the manual found describes
    no such parameter for this cycle. The moves are :func:`surface_moves`."""
    _required(233, q, where, column)
    limits = [f"Q{k}={q[k]:g}" for k in (347, 348, 349) if q.get(k, 0.0)]
    if limits:
        where.fail(f"cycle 233: the side walls {', '.join(limits)} are not supported", column=column,
                   text=where.text, expected="Q347=0 Q348=0 Q349=0 (no limits)")
    if 367 in q:
        where.fail(f"cycle 233: the surface position Q367={q[367]:g} is not supported", column=column,
                   text=where.text, expected="no Q367 (the surface's corner at the tool's position)")
    strategy, direction, operation = int(q[389]), int(q[350]), int(q.get(215, 0.0))
    if strategy not in (0, 1, 2, 3) or q[389] != strategy:
        where.fail(f"cycle 233: Q389={q[389]:g} is not a strategy vcnc runs", column=column, text=where.text,
                   expected="Q389=0, 1, 2 or 3 (4, helical, is not supported)")
    if direction not in (1, 2) or q[350] != direction:
        where.fail(f"cycle 233: Q350={q[350]:g} is not a milling direction", column=column, text=where.text,
                   expected="Q350=1 (the reference axis) or 2 (the minor axis)")
    if operation not in (0, 1, 2) or q.get(215, 0.0) != operation:
        where.fail(f"cycle 233: Q215={q[215]:g} is not a machining operation", column=column, text=where.text,
                   expected="Q215=0 (roughing and finishing), 1 (roughing) or 2 (finishing)")
    _levels_checked(233, q, where, column)
    feed = q[207] * feed_scale
    return SurfaceCycle(
        number=233, strategy=strategy, start=(0.0, 0.0, q[227] * scale), sides=(q[218] * scale, q[219] * scale),
        end_level=q[386] * scale, plunge=abs(q[202]) * scale, allowance=abs(q.get(369, 0.0)) * scale,
        stepover=q.get(370, 1.0), feed=feed, finish_feed=(q.get(385, 0.0) or q[207]) * feed_scale,
        approach_feed=feed, step_feed=(q.get(253, 0.0) or q[207]) * feed_scale, return_feed=math.inf,
        setup=abs(q[200]) * scale, side_clearance=abs(q.get(357, 0.0)) * scale, second_setup=abs(q[204]) * scale,
        direction=direction, operation=operation)


def multipass_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                    column: int) -> SurfaceCycle:
    """Cycle 230 MULTIPASS MILLING from its Q parameters (TNC 426/430 user's manual, "Cycles for multipass
    milling", MULTIPASS MILLING (Cycle 230); its pages were not among the texts found, so the parameters and the
    cycle run here are our reading of that manual's cycle as its dialog names them): Q225/Q226/Q227 the starting
    point, Q218/Q219 the side lengths, Q240 the number of cuts, Q206 the feed for plunging, Q207 milling, Q209
    the stepover feed, Q200 the set-up clearance. The moves are :func:`surface_moves`."""
    _required(230, q, where, column)
    lines = int(q[240])
    if lines < 1 or lines != q[240] or lines > 10_000:
        where.fail(f"cycle 230: Q240={q[240]:g} cuts", column=column, text=where.text,
                   expected="a whole number of cuts 1 .. 10000")
    if not (q[206] > 0 and q[207] > 0 and q[209] > 0):
        where.fail("cycle 230: the feeds Q206, Q207 and Q209 must be > 0", column=column, text=where.text,
                   expected="Q206 > 0, Q207 > 0, Q209 > 0 [mm/min]")
    return SurfaceCycle(
        number=230, strategy=0, start=(q[225] * scale, q[226] * scale, q[227] * scale),
        sides=(q[218] * scale, q[219] * scale), end_level=q[227] * scale, lines=lines, feed=q[207] * feed_scale,
        finish_feed=q[207] * feed_scale, approach_feed=q[206] * feed_scale, step_feed=q[209] * feed_scale,
        setup=abs(q[200]) * scale, second_setup=abs(q[200]) * scale)


def _levels(c: SurfaceCycle) -> list[tuple[float, bool]]:
    """232's and 233's infeed levels [mm, tool axis] from Q227 to Q386, each with whether it is the finishing one:
    equal infeeds of at most Q202 down to Q386 + Q369, then Q386 when Q369 > 0 (233: Q215 = 1 without that last
    level, Q215 = 2 that level alone, at the finishing feed also when Q369 = 0)."""
    top, rough = c.start[2], c.end_level + c.allowance
    if c.number == 230:
        return [(top, False)]
    if c.operation == 2:
        return [(c.end_level, True)]
    n = max(1, math.ceil((top - rough) / c.plunge - 1e-9)) if top > rough else 0
    out = [(top - (top - rough) * (i + 1) / n, False) for i in range(n)]
    return out + [(c.end_level, True)] if c.allowance > 0 and c.operation == 0 else out


def _rows(c: SurfaceCycle, v0: float, width: float, radius: float) -> list[float]:
    """The lines' coordinates across them [mm]: from ``v0`` to ``v0 + width`` in equal stepovers (232, 233: of at
    most Q370 x the tool radius; 230: Q240 lines)."""
    n = c.lines - 1 if c.number == 230 else math.ceil(abs(width) / (c.stepover * radius) - 1e-9) if radius else 0
    if n <= 0:
        return [v0]
    return [v0 + width * j / n for j in range(n + 1)]


def _ends(c: SurfaceCycle, u0: float, length: float, radius: float) -> tuple[float, float, float]:
    """The coordinates along the lines [mm] of the approach point, of the lines' near ends and of their far ends,
    for the surface from ``u0`` to ``u0 + length``."""
    s = -1.0 if length < 0 else 1.0
    if c.number == 230:
        return u0 - s * radius, u0 - s * radius, u0 + length + s * radius
    outside = radius + c.side_clearance
    approach = u0 - s * outside
    if c.number == 233:
        beyond = outside if c.strategy in (0, 2) else c.side_clearance
        return approach, (u0 - s * beyond if c.strategy in (0, 1) else approach), u0 + length + s * beyond
    if c.strategy == 1:
        return approach, u0 + s * radius, u0 + length - s * radius
    return approach, approach, u0 + length + s * outside


def surface_moves(c: SurfaceCycle, *, radius: float, position: tuple[float, float, float]) -> list[SurfaceMove]:
    """The moves of cycle 232 or 233 FACE MILLING or 230 MULTIPASS MILLING for a tool of ``radius`` [mm] at
    ``position`` [mm, program: reference, minor and tool axes] (TNC 640 user's manual for cycle programming
    34059x-01, p. 235-236, cycle 232's "Cycle run"; TNC 320 user's manual 340 551-02 p. 298 for the parameters;
    cycle 233: TNC7 basic user's manual 81762x-19, "Cycle 233 FACE MILLING", :func:`face_milling_233`; cycle 230:
    our reading of the TNC 426/430 user's manual's "MULTIPASS MILLING (Cycle 230)", :func:`multipass_cycle`):

    * positioning logic: above the 2nd set-up clearance (Q227 + Q204) the tool goes at FMAX first in the plane
      to the starting point, then down to the set-up clearance Q227 + Q200; below it first up to the 2nd
      set-up clearance; then at Q253 (233: at the milling feed Q207, "the tool then moves in the spindle axis at
      the feed rate for milling Q207 to the first plunging depth"; 230: Q206) to the first infeed level;
    * the starting point lies off the surface's edge by the tool radius plus Q357 (230: the tool radius);
      the lines run along the reference axis (233 with Q350 = 2: along the minor axis, Q219 their length and
      Q218 the width across them) in the direction of Q218's sign, at Q226 and then in equal
      stepovers of at most Q370 x the tool radius to Q226 + Q219 (our reading: the first and the last line's
      tool centre on the surface's edges, which the manual's "calculated from the programmed width, the tool
      radius and the maximum path overlap factor" leaves open; an R2 of the tool table is not held by vcnc's
      tool table); 230: Q240 lines from Q226 to Q226 + Q219; 233: from the tool's position;
    * Q389 = 0: meander, each line out to the tool radius plus Q357 beyond the far edge, the stepover there
      at Q253; Q389 = 1: meander within the surface, the lines from the tool radius inside the near edge to
      the tool radius inside the far edge ("the end point lies within the surface"; the first line starts at
      the starting point), the stepover at the milling feed Q207 (Q253's description: "If you are moving the
      tool transversely to the material (Q389=1), the TNC moves the tool at the feed rate for milling");
      after the last line the tool plunges there (at Q253, our reading) to the next level and mills the
      surface back in the reverse order; Q389 = 2: each line from the near side at the milling feed, then at
      FMAX (our reading) up to the set-up clearance above the level, at Q253 to the start of the next line,
      down to the level at Q253 (our reading); after the last line up and at Q253 back over the starting
      point, down to the next level;
    * 233: Q389 = 0 meanders out to the tool radius plus Q357 beyond the far edge, Q389 = 1 to Q357 beyond it
      ("If Q389=0, the end point lies outside of the surface, with Q389=1, it lies at the edge of the surface.
      The control calculates end point 2 from the side length and the set-up clearance to the side"; our
      reading: the lines back end as far beyond the near edge), the stepovers at Q253 ("shifts the tool
      laterally to the starting point of the next line at the pre-positioning feed rate"); Q389 = 2 and 3 the
      same ends line by line, "stepover when retracting at rapid traverse": up to the set-up clearance above the
      level, over to the next line's start at FMAX and down at Q207 (our reading);
    * equal infeeds of at most Q202 from Q227 to Q386 + Q369, then the last one, Q369, at Q385 (233: Q215 = 1
      without it, Q215 = 2 only it);
    * finally at FMAX to the 2nd set-up clearance (230: to the set-up clearance);
    * 230 (TNC 426/430 manual's cycle run): at FMAX in the plane to the starting point, which is the tool radius
      before Q225 (our reading of "offsets the tool by the tool radius"), at FMAX to the set-up clearance above
      Q227, at Q206 down to Q227, the lines (at Q207) meandering out to the tool radius beyond the far edge,
      the stepovers at Q209 (our reading: Q219 / (Q240 - 1) apart, the first and the last line on the edges).

    A ``ValueError`` when cycle 232's or 233's lines would be more than :data:`MAX_LINES`.
    """
    u0, v0 = (position[0], position[1]) if c.number == 233 else c.start[:2]
    length, width = c.sides
    swap = c.direction == 2
    if swap:
        u0, v0, length, width = v0, u0, width, length
    top = c.start[2]
    clear = top + c.second_setup
    approach, near, far = _ends(c, u0, length, radius)
    rows = _rows(c, v0, width, radius)
    if c.number != 230 and len(rows) > MAX_LINES:
        raise ValueError(f"{len(rows)} lines of stepovers of {c.stepover * radius:g} mm are more than {MAX_LINES}")
    out: list[SurfaceMove] = []
    if position[2] <= clear and c.number != 230:
        out.append(SurfaceMove("rapid", (None, None, clear)))
    out += [SurfaceMove("rapid", (approach, rows[0], None)), SurfaceMove("rapid", (None, None, top + c.setup))]
    at = (approach, rows[0])
    forward = True  # the lines in the order of Q219's sign
    levels = _levels(c)
    line_by_line = c.strategy >= 2
    for k, (z, finishing) in enumerate(levels):
        feed = c.finish_feed if finishing else c.feed
        out.append(SurfaceMove("line", (*at, z), c.approach_feed))
        order = rows if forward else rows[::-1]
        for j, v in enumerate(order):
            if line_by_line:
                if j:
                    out += [SurfaceMove("rapid", (None, None, z + c.setup)),
                            SurfaceMove("line", (approach, v, z + c.setup), c.return_feed),
                            SurfaceMove("line", (approach, v, z), c.approach_feed)]
                out.append(SurfaceMove("line", (far, v, z), feed))
                continue
            if j:
                out.append(SurfaceMove("line", (at[0], v, z), c.step_feed))
            target = far if at[0] != far else near
            out.append(SurfaceMove("line", (target, v, z), feed))
            at = (target, v)
        if line_by_line and k < len(levels) - 1:
            out += [SurfaceMove("rapid", (None, None, z + c.setup)),
                    SurfaceMove("line", (approach, rows[0], z + c.setup), c.return_feed)]
            at = (approach, rows[0])
        elif not line_by_line:
            forward = not forward
    out.append(SurfaceMove("rapid", (None, None, clear)))
    if swap:
        return [SurfaceMove(mv.kind, (mv.point[1], mv.point[0], mv.point[2]), mv.feed) for mv in out]
    return out
