"""The multipass-milling cycles of Heidenhain conversational programs: surfaces milled in lines.

These cycles are placed by absolute coordinates in their definition (a starting point Q225, Q226, Q227), not
at the tool's position, so their moves are worked out here as points in program coordinates; the reader
carries them through the active transformations (:func:`surface_moves`).

========================= ==================================================================
``CYCL DEF 232``          FACE MILLING, strategies Q389 = 0, 1, 2 (:func:`face_milling_cycle`)
``CYCL DEF 230``          MULTIPASS MILLING, Q240 lines meandering at one height (:func:`multipass_cycle`)
``CYCL DEF 231``          RULED SURFACE between four points, Q240 lines (:func:`ruled_surface_cycle`)
``CYCL DEF 233``          FACE MILLING of the TNC 640 (side walls, Q350 direction, limits Q347-Q349): an error
========================= ==================================================================
"""

from __future__ import annotations

import dataclasses
import math

from interpolators._words import Where

__all__ = ["MAX_LINES", "SURFACE_CYCLES", "SurfaceCycle", "RuledSurface", "SurfaceMove", "face_milling_cycle",
           "multipass_cycle", "ruled_surface_cycle", "ruled_surface_moves", "surface_cycle", "surface_moves"]

#: The multipass-milling cycles this module runs (233 is refused by :func:`surface_cycle`).
SURFACE_CYCLES: tuple[int, ...] = (230, 231, 232, 233)

#: Most lines of one level of cycle 232 (a guard against a tiny tool radius or stepover factor).
MAX_LINES = 100_000

_REQUIRED = {
    232: (389, 225, 226, 227, 386, 218, 219, 202, 207, 200, 357, 204),
    230: (225, 226, 227, 218, 219, 240, 206, 207, 209, 200),
    231: (225, 226, 227, 228, 229, 230, 231, 232, 233, 234, 235, 236, 240, 207),
}


@dataclasses.dataclass(frozen=True, kw_only=True)
class SurfaceCycle:
    """A multipass-milling cycle as defined, in mm, mm/s [program coordinates].

    Attributes
    ----------
    number : int
        232 FACE MILLING or 230 MULTIPASS MILLING.
    strategy : int
        232: Q389, 0 meander with the stepover outside the surface, 1 meander with the stepover within it,
        2 line by line, back over the surface at the set-up clearance (230: 0, a meander).
    start : tuple of float
        Q225, Q226, Q227: the starting point in the reference, minor and tool axes [mm].
    sides : tuple of float
        Q218, Q219: the surface's side lengths along the reference and minor axes, their signs the direction
        of the first milling path and of the first stepover [mm].
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
    feed, finish_feed, approach_feed, step_feed : float
        Q207 milling, Q385 finishing (232), Q253 pre-positioning (232) or Q206 plunging (230), and the stepover
        feed (232: Q253, with Q389 = 1 Q207; 230: Q209) [mm/s].
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
    setup: float
    side_clearance: float = 0.0
    second_setup: float


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
    """Cycle 230, 231 or 232 from its Q parameters; 233 is an error (TNC 640 user's manual for cycle programming
    9/2015, "FACE MILLING (Cycle 233)", p. 175: its side walls Q347-Q349, the milling direction Q350 and the
    helical strategy Q389 = 4 are not modelled)."""
    if number == 233:
        where.fail("cycle 233 FACE MILLING (the TNC 640's, with limits Q347-Q349 and direction Q350) is not "
                   "supported", column=column, text=where.text,
                   expected="CYCL DEF 232 FACE MILLING (Q389 0, 1, 2) or the surface programmed with L blocks")
    for k, v in q.items():
        if math.isinf(v) and not (number == 232 and k == 253):
            where.fail(f"cycle {number}: Q{k}=MAX is not a value here", column=column, text=where.text,
                       expected=f"Q{k}=<number>")
    if number == 230:
        return multipass_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if number == 231:
        return ruled_surface_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
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
    depth = q[227] - q[386] - abs(q.get(369, 0.0))
    if q[227] <= q[386] or depth < 0:
        where.fail("cycle 232: the starting point Q227 must lie above the end point Q386 by at least the allowance "
                   "Q369", column=column, text=where.text, expected="Q227 > Q386 + Q369")
    if not q[207] > 0 or not q.get(370, 1.0) > 0 or (depth > 0 and not q[202] > 0):
        where.fail("cycle 232: the milling feed Q207, the stepover factor Q370 and the plunging depth Q202 must be "
                   "> 0", column=column, text=where.text, expected="Q207 > 0, Q370 > 0, Q202 > 0")
    if depth / max(abs(q[202]), 1e-12) > 10_000:
        where.fail(f"cycle 232: {depth:g} in plunges of {q[202]:g} are more than 10000 infeeds", column=column,
                   text=where.text, expected="a larger plunging depth Q202")
    feed = q[207] * feed_scale
    approach = (q.get(253, 0.0) or q[207]) * feed_scale
    return SurfaceCycle(
        number=232, strategy=strategy, start=(q[225] * scale, q[226] * scale, q[227] * scale),
        sides=(q[218] * scale, q[219] * scale), end_level=q[386] * scale, plunge=abs(q[202]) * scale,
        allowance=abs(q.get(369, 0.0)) * scale, stepover=q.get(370, 1.0), feed=feed,
        finish_feed=(q.get(385, 0.0) or q[207]) * feed_scale, approach_feed=approach,
        step_feed=feed if strategy == 1 else approach, setup=abs(q[200]) * scale,
        side_clearance=abs(q[357]) * scale, second_setup=abs(q[204]) * scale)


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
    """232's infeed levels [mm, tool axis] from Q227 to Q386, each with whether it is the finishing one: equal
    infeeds of at most Q202 down to Q386 + Q369, then Q386 when Q369 > 0."""
    top, rough = c.start[2], c.end_level + c.allowance
    if c.number == 230:
        return [(top, False)]
    n = max(1, math.ceil((top - rough) / c.plunge - 1e-9)) if top > rough else 0
    out = [(top - (top - rough) * (i + 1) / n, False) for i in range(n)]
    return out + [(c.end_level, True)] if c.allowance > 0 else out


def _rows(c: SurfaceCycle, radius: float) -> list[float]:
    """The lines' minor-axis coordinates [mm]: from Q226 to Q226 + Q219 in equal stepovers (232: of at most
    Q370 x the tool radius; 230: Q240 lines)."""
    v0, width = c.start[1], c.sides[1]
    n = c.lines - 1 if c.number == 230 else math.ceil(abs(width) / (c.stepover * radius) - 1e-9) if radius else 0
    if n <= 0:
        return [v0]
    return [v0 + width * j / n for j in range(n + 1)]


def _ends(c: SurfaceCycle, radius: float) -> tuple[float, float, float]:
    """The reference-axis coordinates [mm] of the approach point, of the lines' near ends and of their far ends."""
    u0, length = c.start[0], c.sides[0]
    s = -1.0 if length < 0 else 1.0
    if c.number == 230:
        return u0 - s * radius, u0 - s * radius, u0 + length + s * radius
    outside = radius + c.side_clearance
    approach = u0 - s * outside
    if c.strategy == 1:
        return approach, u0 + s * radius, u0 + length - s * radius
    return approach, approach, u0 + length + s * outside


def surface_moves(c: SurfaceCycle, *, radius: float, level: float) -> list[SurfaceMove]:
    """The moves of cycle 232 FACE MILLING or 230 MULTIPASS MILLING for a tool of ``radius`` [mm] whose tool-axis
    coordinate is ``level`` [mm, program] (TNC 640 user's manual for cycle programming 34059x-01, p. 235-236,
    cycle 232's "Cycle run"; TNC 320 user's manual 340 551-02 p. 298 for the parameters; cycle 230: our reading
    of the TNC 426/430 user's manual's "MULTIPASS MILLING (Cycle 230)", :func:`multipass_cycle`):

    * positioning logic: above the 2nd set-up clearance (Q227 + Q204) the tool goes at FMAX first in the plane
      to the starting point, then down to the set-up clearance Q227 + Q200; below it first up to the 2nd
      set-up clearance; then at Q253 (230: Q206) to the first infeed level;
    * the starting point lies off the surface's edge by the tool radius plus Q357 (230: the tool radius);
      the lines run along the reference axis in the direction of Q218's sign, at Q226 and then in equal
      stepovers of at most Q370 x the tool radius to Q226 + Q219 (our reading: the first and the last line's
      tool centre on the surface's edges, which the manual's "calculated from the programmed width, the tool
      radius and the maximum path overlap factor" leaves open; an R2 of the tool table is not held by vcnc's
      tool table); 230: Q240 lines from Q226 to Q226 + Q219;
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
    * equal infeeds of at most Q202 from Q227 to Q386 + Q369, then the last one, Q369, at Q385;
    * finally at FMAX to the 2nd set-up clearance (230: to the set-up clearance);
    * 230 (TNC 426/430 manual's cycle run): at FMAX in the plane to the starting point, which is the tool radius
      before Q225 (our reading of "offsets the tool by the tool radius"), at FMAX to the set-up clearance above
      Q227, at Q206 down to Q227, the lines (at Q207) meandering out to the tool radius beyond the far edge,
      the stepovers at Q209 (our reading: Q219 / (Q240 - 1) apart, the first and the last line on the edges).

    A ``ValueError`` when cycle 232's lines would be more than :data:`MAX_LINES`.
    """
    top = c.start[2]
    clear = top + c.second_setup
    approach, near, far = _ends(c, radius)
    rows = _rows(c, radius)
    if c.number == 232 and len(rows) > MAX_LINES:
        raise ValueError(f"{len(rows)} lines of stepovers of {c.stepover * radius:g} mm are more than {MAX_LINES}")
    out: list[SurfaceMove] = []
    if level <= clear and c.number == 232:
        out.append(SurfaceMove("rapid", (None, None, clear)))
    out += [SurfaceMove("rapid", (approach, rows[0], None)), SurfaceMove("rapid", (None, None, top + c.setup))]
    at = (approach, rows[0])
    forward = True  # the lines in the order of Q219's sign
    levels = _levels(c)
    for k, (z, finishing) in enumerate(levels):
        feed = c.finish_feed if finishing else c.feed
        out.append(SurfaceMove("line", (*at, z), c.approach_feed))
        order = rows if forward else rows[::-1]
        for j, v in enumerate(order):
            if c.strategy == 2:
                if j:
                    out += [SurfaceMove("rapid", (None, None, z + c.setup)),
                            SurfaceMove("line", (approach, v, z + c.setup), c.approach_feed),
                            SurfaceMove("line", (approach, v, z), c.approach_feed)]
                out.append(SurfaceMove("line", (far, v, z), feed))
                continue
            if j:
                out.append(SurfaceMove("line", (at[0], v, z), c.step_feed))
            target = far if at[0] != far else near
            out.append(SurfaceMove("line", (target, v, z), feed))
            at = (target, v)
        if c.strategy == 2 and k < len(levels) - 1:
            out += [SurfaceMove("rapid", (None, None, z + c.setup)),
                    SurfaceMove("line", (approach, rows[0], z + c.setup), c.approach_feed)]
            at = (approach, rows[0])
        elif c.strategy != 2:
            forward = not forward
    out.append(SurfaceMove("rapid", (None, None, clear)))
    return out
