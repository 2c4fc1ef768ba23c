"""Cutter radius compensation (ISO G41/G42/G40, Heidenhain RL/RR/R0) of lines and arcs in the active plane.

The tool centre is moved by the tool radius ``r`` to the left (G41, RL) or right (G42, RR) of the
programmed contour, seen in the direction of travel with the plane normal pointing at the viewer.
The rules are LinuxCNC's (G-code reference, "G41, G42 Cutter Compensation" and "Cutter
Compensation" chapter, https://linuxcnc.org/docs/html/gcode/tool-compensation.html; source
``src/emc/rs274ngc/interp_convert.cc``, ``convert_straight_comp1`` / ``convert_straight_comp2`` /
``convert_arc_comp2``), except at outside corners under ``corner="fanuc"`` (Fanuc's, below):

* **Entry move** (the first move with motion in the plane after G41/G42): a straight line from
  the uncompensated position to the programmed end point moved by ``r`` perpendicular to the
  entry move itself (``convert_straight_comp1``: ``alpha = atan2(py - cy, px - cx) +/- pi/2``).
  It must be longer than ``r`` ("Length of cutter compensation entry move is not greater than the
  tool radius"). With ``entry="perpendicular"`` the entry ends at the first contour point moved by
  ``r`` perpendicular to the first contour element, as the TNC approaches a contour with RL/RR
  (TNC 640 user's manual, "Tool radius compensation": "the tool is positioned perpendicular to
  the first contour element at the starting point"), as Fanuc's type A start-up does (cutter
  compensation C: the vector perpendicular to the next block at its start point; no length rule).
* **Corners** are classified as LinuxCNC does (``convert_straight_comp2`` into a line,
  ``convert_arc_comp2`` into an arc): ``beta`` is the turn away from the tool side, from the
  direction of the programmed corner to the tool to the new element's programmed tangent. A turn
  of more than ``small`` (``compensate``'s ``convex_tolerance``: by default :data:`CONVEX_TOLERANCE`,
  LinuxCNC's TOLERANCE_CONCAVE_CORNER; the TNC reader's a turn no larger than rounding) and at most
  ``pi + small`` is an **outside corner**: with ``corner="linuxcnc"`` an arc of radius ``r`` about
  the programmed corner point joins the two offset elements (into a G0, which has no arc traverse, a
  straight rapid instead); it carries the ``line``/``text`` and the feed of the block it leads into
  (of the last feed move before it when that block is a rapid). A smaller turn has no corner: a line
  starts where the tool is, an arc (which LinuxCNC starts there as a slight spiral) is reached by a
  short bridging line; LinuxCNC's gouge check measures that arc's sweep from where the tool was.
* **Inside corners** (``beta < -small`` or ``beta > pi + small``, and the near reversals of the
  "h" and "m" shapes: ``beta`` within ``small`` of ``pi`` onto a line after an arc, or into an arc,
  the tool is outside of): both offset elements end where they meet, by LinuxCNC's formulas (after
  the entry move with the entry's parallel offset): line-line the intersection, line-arc and arc-line
  the point ``asin``/``acos`` pick, arc-arc the intersection of the circles about the programmed
  centres (start + I/J/K; the end point's radius -/+ ``r``). Where they cannot meet,
  :class:`CompensationError` carries LinuxCNC's message ("Arc move in concave corner cannot be
  reached by the tool without gouging", "Arc to straight motion makes a corner the compensated tool
  can't fit in without gouging", "Arc to arc motion makes a corner ..."). A trimmed element gouges
  as ``move_endpoint_and_flush`` (``interp_queue.cc``) finds: a line whose end was moved and that now runs
  against its programmed direction ("Straight feed in concave corner cannot be reached by the tool without
  gouging"; a line whose start alone moved past its end runs backwards, as rs274 runs it; under
  ``corner="fanuc"`` every reversed line is refused), an arc whose sweep grew by more than 0.0254 rad (mm
  programs) or 0.001 rad (inch). Trimmed ends move in the plane only: each block's tool-axis move runs from its
  programmed start to its programmed end over its compensated element, as LinuxCNC's queue moves ends.
* **Fanuc/Haas outside corners** (``corner="fanuc"``, the ISO reader under ``--dialect fanuc|haas``): no
  corner arc. Fanuc's cutter compensation C (Fanuc 0i-MF / 0i-MD operator's manual, B-64604EN /
  B-64304EN, "Cutter compensation C", "Tool movement in offset mode"; the Series 15i-MA manual 14.4.3
  and the 16/18-MC manual 15.4 draw the same cases) names the corner by its angle ``alpha`` on the
  workpiece side, ``alpha = 180 deg - beta`` at an outside corner:

  - ``180 > alpha >= 90`` ("going around the outside of a corner at an obtuse angle"), line-line,
    line-arc, arc-line and arc-arc alike: both elements end at the intersection of their offset paths
    (an offset line, an offset circle about the arc's centre), of two the one nearest the corner. A
    line grows, an arc may sweep more than programmed: that is no gouge.
  - ``alpha < 90`` ("at an acute angle"): two vectors of length ``r``, perpendicular to each element at
    the corner, each lengthened by ``r`` along its element's tangent: the tool goes on ``r`` along the
    first element's end tangent (a line is lengthened; after an arc a straight piece), straight to the
    point ``r`` before the second element's start along its tangent, and on (a line starts there;
    before an arc a straight piece to its offset start). The straight pieces carry the next block's
    line and feed, as the corner arcs do.
  - Our reading where the manual's figures say nothing: a turn of at most 90 degrees whose offsets do
    not meet (an arc too small for the line to reach) takes the acute rule; a turn of at most
    ``small`` without a meeting point (parallel lines, an arc tangent to the line) keeps LinuxCNC's
    handling below; a turn within ``small`` of 180 degrees next to an arc is classified as LinuxCNC
    does (the "h" and "m" shapes are inside corners).

  Inside corners are the intersection under both rules (Fanuc, "going around the inside of a corner
  (alpha >= 180)"), found by LinuxCNC's formulas. Haas mills offer FANUC or YASNAC by Setting 58
  "Cutter Compensation" (Haas mill operator's manual, settings list): vcnc models FANUC (our reading:
  the factory setting; YASNAC's rules are not in the sources at hand). The TNC (RL/RR, the Heidenhain
  reader) keeps the corner arc: "the TNC moves the tool around outside corners on a transitional arc"
  (TNC 640 user's manual, "Radius compensation: Machining corners"). Fanuc's G39 (corner circular
  interpolation, ``rounded``) asks for that arc at one corner: "the tool moves along the arc from the
  point of the old vector toward that of the new vector" (Series 16/18-MC operator's manual, "Corner
  offset circular interpolation (G39)"); at an inside corner it changes nothing (our reading).
* **Arcs** keep their centre; their radius grows or shrinks by ``r``. A tool radius not smaller
  than an arc on the inside raises "Tool radius not less than arc radius with cutter radius
  comp".
* **Exit move** (the first move after G40/R0): a straight line from the compensated position to
  the programmed end point, without a corner. A program that ends with compensation on, or with G40
  and no motion after it, has none: its last move is compensated as the others (``open_end``).

Moves along the tool axis only and dwells stay where the tool is (shifted in the plane with it).
An arc entry move (LinuxCNC's ``convert_arc_comp1``) ends at its programmed end moved by ``r``
along the radius, about a new centre on the line from there through the programmed centre, as far
from the start as from that end; the TNC's perpendicular entry must be a line. The exit move must be
a line, as in LinuxCNC ("The move just after exiting cutter compensation mode must be straight").
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Collection, Mapping, Sequence

import numpy as np

from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Arc, Line
from vcnc.core.errors import InputError

__all__ = ["CompensationError", "compensate", "SIDES", "ENTRY_RULES", "CORNER_RULES", "CONVEX_TOLERANCE"]

#: Compensation sides: G41/RL is "left", G42/RR is "right".
SIDES: tuple[str, str] = ("left", "right")

#: Entry rules: LinuxCNC's (perpendicular to the entry move) or the TNC's (perpendicular to the first contour element).
ENTRY_RULES: tuple[str, str] = ("linuxcnc", "perpendicular")

#: Outside-corner rules: LinuxCNC's (and the TNC's) arc about the corner, or Fanuc's intersection and vectors.
CORNER_RULES: tuple[str, str] = ("linuxcnc", "fanuc")

#: Convex corners of at most this turn [rad] join a line without a corner arc (LinuxCNC TOLERANCE_CONCAVE_CORNER).
CONVEX_TOLERANCE = 0.05

#: Points closer than this are the same point [mm].
_EPS = 1e-9


class CompensationError(InputError):
    """A compensated run the tool cannot follow (gouge, arc smaller than the tool, bad entry or exit).

    Parameters
    ----------
    message : str
        What is wrong, in LinuxCNC's words where LinuxCNC has them.
    index : int
        Index into the ``blocks`` given to :func:`compensate` of the block at fault.
    """

    def __init__(self, message: str, index: int) -> None:
        super().__init__(message)
        self.index = int(index)


@dataclasses.dataclass(kw_only=True)
class _Offset:
    """One offset element in plane coordinates: a line ``a -> b`` or an arc about ``c``."""

    index: int
    kind: str  # "line" or "arc"
    a: np.ndarray  # (2,) start in the plane [mm]
    b: np.ndarray  # (2,) end in the plane [mm]
    za: float  # tool-axis coordinate at the start [mm]
    zb: float  # tool-axis coordinate at the end [mm]
    c: np.ndarray | None = None  # arc centre (2,) [mm]
    radius: float = 0.0  # arc radius [mm]
    turns: int = 0  # extra full turns of the arc (G2/G3 P > 1)
    ccw: bool = True
    a0: np.ndarray | None = None  # untrimmed start, for the gouge check
    b0: np.ndarray | None = None  # untrimmed end
    pc: np.ndarray | None = None  # programmed arc centre (2,) [mm], LinuxCNC's for the inside corners
    pr: float = 0.0  # offset radius about ``pc`` at the programmed end [mm]
    grown: float = 0.0  # sweep [rad] an arc gained at Fanuc outside corners (no gouge)
    # LinuxCNC's start of an arc after a turn of at most ``small``: where the tool is (convert_arc_comp2,
    # "convex, one arc needed": set_endpoint(cx, cy)), its sweep checked from there (see _check_gouges)
    spiral_from: np.ndarray | None = None

    def tangent(self, point: np.ndarray) -> np.ndarray:
        """Unit tangent at ``point`` (a point of the element)."""
        if self.kind == "line":
            d = self.b0 - self.a0
            return d / math.hypot(*d)
        u = (point - self.c) / self.radius
        return np.array([-u[1], u[0]]) if self.ccw else np.array([u[1], -u[0]])

    def param(self, point: np.ndarray) -> float:
        """Position of ``point`` along the untrimmed element [mm of line, rad of arc] from its start."""
        if self.kind == "line":
            d = self.b0 - self.a0
            return float((point - self.a0) @ d / math.hypot(*d))
        ang0 = math.atan2(*(self.a0 - self.c)[::-1])
        ang = math.atan2(*(point - self.c)[::-1])
        return ((ang - ang0) if self.ccw else (ang0 - ang)) % (2.0 * math.pi)

    def extent(self) -> float:
        """Length [mm] of the untrimmed line, or sweep [rad] of the untrimmed arc."""
        if self.kind == "line":
            return math.hypot(*(self.b0 - self.a0))
        s = self.param(self.b0)
        return s if s > _EPS else 2.0 * math.pi


def _left(t: np.ndarray) -> np.ndarray:
    return np.array([-t[1], t[0]])


def _cross(u: np.ndarray, v: np.ndarray) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def _intersections(e1: _Offset, e2: _Offset) -> list[np.ndarray]:
    """Intersections of the full line or circle of ``e1`` with that of ``e2`` (plane coordinates)."""
    if e1.kind == "line" and e2.kind == "line":
        d, e = e1.b0 - e1.a0, e2.b0 - e2.a0
        den = _cross(d, e)
        if abs(den) <= _EPS * math.hypot(*d) * math.hypot(*e):
            return []
        t = _cross(e2.a0 - e1.a0, e) / den
        return [e1.a0 + t * d]
    if e1.kind == "arc" and e2.kind == "line":
        e1, e2 = e2, e1
    if e1.kind == "line":  # line e1, circle e2
        d = e1.b0 - e1.a0
        d = d / math.hypot(*d)
        w = e1.a0 - e2.c
        b = float(w @ d)
        disc = b * b - (float(w @ w) - e2.radius**2)
        if disc < 0.0:
            return []
        h = math.sqrt(disc)
        return [e1.a0 + (-b - h) * d, e1.a0 + (-b + h) * d]
    dv = e2.c - e1.c
    dist = math.hypot(*dv)
    if dist <= _EPS or dist > e1.radius + e2.radius or dist < abs(e1.radius - e2.radius):
        return []
    x = (dist**2 + e1.radius**2 - e2.radius**2) / (2.0 * dist)
    h = math.sqrt(max(e1.radius**2 - x * x, 0.0))
    base = e1.c + x * dv / dist
    n = _left(dv / dist)
    return [base + h * n, base - h * n]


def _run_parts(blocks: Sequence[Block], movers: list[int], *, closed: bool,
               open_end: bool) -> tuple[int, int | None, list[int]]:
    """The entry move, the exit move (None: the run has none) and the contour between of one compensated run
    (:func:`compensate`'s ``closed`` and ``open_end``); an exit move that is an arc is refused."""
    first = movers[0]
    last = movers[-1] if len(movers) > 1 and movers[-1] == len(blocks) - 1 and not open_end else None
    end = len(blocks) - 1
    if closed and last is None and end > first and blocks[end].segment is not None and blocks[end].kind != "arc":
        last = end
    if last is not None and blocks[last].kind == "arc":  # LinuxCNC: "... must be straight, not an arc"
        raise CompensationError("cutter compensation exit move must be a straight line, not an arc", last)
    return first, last, [i for i in movers[1:] if i != last]


def compensate(
    blocks: Sequence[Block], *, side: str, radius: float, plane: int, entry: str = "linuxcnc", closed: bool = False,
    centers: Mapping[int, np.ndarray] | None = None, inch: bool = False, open_end: bool = False,
    corner: str = "linuxcnc", rounded: Collection[int] = (), convex_tolerance: float = CONVEX_TOLERANCE,
    every_line: bool | None = None,
) -> list[Block]:
    """Tool-centre path of one compensated run.

    Parameters
    ----------
    blocks : sequence of Block
        One compensated run, programmed contour: from the entry move (the first motion after
        G41/G42, or the block with RL/RR) up to and including the exit move (the first motion
        after G40 / the block with R0, or the run's last block when the program ends, unless
        ``open_end``). Blocks
        before the first block with motion in the plane pass unchanged; the exit move (and the
        entry move with ``entry="perpendicular"``) must be a line or rapid. A run whose only
        motion in the plane is its entry move ends with the tool offset.
    side : {"left", "right"}
        Tool left (G41, RL) or right (G42, RR) of the contour in the direction of travel.
    radius : float
        Tool radius [mm] (>= 0; 0 returns the blocks unchanged).
    plane : int
        Normal-axis index of the compensation plane: 2 XY (G17), 1 ZX (G18), 0 YZ (G19).
    entry : {"linuxcnc", "perpendicular"}
        Where the entry move ends: the programmed point moved perpendicular to the entry move
        (LinuxCNC) or perpendicular to the first contour element (Heidenhain TNC; Fanuc/Haas type A).
    closed : bool
        The run's last block is the exit move after G40 even when it has no motion in the plane (a
        ``G0 Z..`` retract): it runs from the tool position to its programmed point, as LinuxCNC
        takes the programmed position for the current one when compensation goes off
        (``convert_cutter_compensation_off``: ``current_x = program_x``).
    centers : mapping of int to ndarray, shape (3,), optional
        Programmed centres [mm] of centre-format arcs by index into ``blocks`` (start plus I/J/K, before
        :func:`interpolators.arcs.arc_from_center` moves the centre onto the chord's bisector). LinuxCNC
        meets inside corners on circles about these, of the end point's radius plus or minus the tool
        radius; without one an arc's own centre is taken.
    inch : bool
        The program is in inch: an arc trimmed at an inside corner may sweep 0.001 rad more than
        programmed, 0.0254 rad in a mm program (``move_endpoint_and_flush``).
    open_end : bool
        The run has no exit move: the program ends with G41/G42 on, or with G40 and no motion after it.
        Its last block is compensated as the others, as LinuxCNC's interpreter flushes the queued moves
        as they are at the program end (tests/ccomp/mill-line-arc-entry).
    corner : {"linuxcnc", "fanuc"}
        Outside corners: an arc about the programmed corner (LinuxCNC, the TNC) or Fanuc's cutter
        compensation C (Fanuc/Haas): the intersection of the offset paths, at an acute corner the two
        vectors joined by straight lines (see the module notes).
    rounded : collection of int
        Fanuc's G39 (corner circular interpolation): indices into ``blocks`` before which it came; the
        outside corner before the next motion in the plane gets the arc about the corner, as under
        ``corner="linuxcnc"``.
    convex_tolerance : float
        The turn [rad] up to which a corner has neither a corner arc nor an intersection (``small`` in the
        module notes): LinuxCNC's TOLERANCE_CONCAVE_CORNER (:data:`CONVEX_TOLERANCE`, the ISO readers), or a
        dialect's own (the TNC's transition arc at every outside corner:
        :data:`interpolators.heidenhain_compensation.TANGENT_TOLERANCE`). Must be > 0 and < pi / 2.
    every_line : bool, optional
        Refuse every line an inside corner turned against its programmed direction, also one whose start alone
        moved past its end (Fanuc's interference check; the TNC, whose tool centre starts each element at the
        tool centre paths' intersection, the permissible tool radius "limited by the geometry of the programmed
        contour": iTNC 530 user's manual 60642x-04, "Radius compensation: Machining corners"). None: LinuxCNC's
        rule (only a line whose end moved) under ``corner="linuxcnc"``, every line under ``"fanuc"``.

    Returns
    -------
    list of Block
        The run with corrected ``start``/``target``/``segment`` in order, plus one arc block at
        each outside corner (carrying the ``line``, ``number``, ``text``, feed and path mode of the
        block it leads into).

    Raises
    ------
    CompensationError
        For a gouge, an inside arc not larger than the tool, an entry move not longer than the
        tool radius, an arc exit move (or entry move under the TNC rule); ``index`` names the block.
    """
    _check_arguments(side, entry, plane, radius, corner, convex_tolerance)
    blocks = list(blocks)
    if radius == 0.0:
        return blocks
    p, q = PLANE_AXES[plane]
    s = 1.0 if side == "left" else -1.0
    movers = [i for i, b in enumerate(blocks) if _moves_in_plane(b, plane)]
    if not movers:
        return blocks
    first, last, contour = _run_parts(blocks, movers, closed=closed, open_end=open_end)
    if entry == "perpendicular" and blocks[first].kind == "arc":
        raise CompensationError("cutter compensation entry move must be a straight line, not an arc", first)
    offsets = _offset_elements(blocks, contour, s=s, radius=radius, plane=plane, centers=centers or {})
    if blocks[first].kind == "arc":
        ent = _entry_arc(blocks[first], first, s=s, radius=radius, plane=plane, centers=centers or {})
    else:
        ent = _entry_element(blocks[first], first, offsets, entry=entry, s=s, radius=radius, plane=plane)
    chain = [ent, *offsets]
    corners = _join_corners(chain, blocks, s=s, radius=radius, plane=plane, rule=corner, rounded=rounded,
                            small=convex_tolerance)
    ends_only = corner == "linuxcnc" if every_line is None else not every_line
    _check_gouges(chain, ent, blocks, radius, inch=inch, ends_only=ends_only)
    return _assemble(blocks, chain, corners, first=first, last=last, side=side, plane=plane)


def _moves_in_plane(block: Block, plane: int) -> bool:
    """The block moves the tool in the compensation plane: an arc, or a line longer than ``_EPS`` there."""
    return block.segment is not None and (
        block.kind == "arc" or math.hypot(*(_flat(block.target, plane) - _flat(block.start, plane))) > _EPS)


def _flat(v: np.ndarray, plane: int) -> np.ndarray:
    """The in-plane coordinates (p, q) of a 3-D point."""
    p, q = PLANE_AXES[plane]
    return np.array([v[p], v[q]], dtype=float)


def _check_arguments(side: str, entry: str, plane: int, radius: float, corner: str, convex_tolerance: float) -> None:
    if corner not in CORNER_RULES:
        raise InputError(f"compensation corner rule must be one of {CORNER_RULES}, got {corner!r}")
    if not 0.0 < convex_tolerance < math.pi / 2.0:
        raise InputError(f"compensation convex_tolerance must be > 0 and < pi/2 rad, got {convex_tolerance!r}")
    if side not in SIDES:
        raise InputError(f"compensation side must be one of {SIDES}, got {side!r}")
    if entry not in ENTRY_RULES:
        raise InputError(f"compensation entry must be one of {ENTRY_RULES}, got {entry!r}")
    if plane not in PLANE_AXES:
        raise InputError(f"compensation plane must be the normal axis index 0, 1 or 2, got {plane!r}")
    if not (radius >= 0.0 and math.isfinite(radius)):
        raise InputError(f"tool radius must be finite and >= 0 mm, got {radius!r}")


def _offset_elements(blocks: list[Block], contour: list[int], *, s: float, radius: float, plane: int,
                     centers: Mapping[int, np.ndarray]) -> list[_Offset]:
    """The contour's lines and arcs moved by the tool radius to the tool's side (``s`` +1 left)."""
    offsets: list[_Offset] = []
    for i in contour:
        b = blocks[i]
        a2, b2 = _flat(b.start, plane), _flat(b.target, plane)
        if b.kind == "arc":
            arc = b.segment
            c = _flat(arc.center, plane)
            new_r = arc.radius - s * radius * (1.0 if arc.ccw else -1.0)
            if new_r <= _EPS * max(arc.radius, 1.0):
                raise CompensationError(
                    f"tool radius {radius:g} mm not less than arc radius {arc.radius:g} mm with cutter radius comp", i)
            ua, ub = (a2 - c) / arc.radius, (b2 - c) / arc.radius
            el = _Offset(index=i, kind="arc", a=c + new_r * ua, b=c + new_r * ub, za=float(b.start[plane]),
                         zb=float(b.target[plane]), c=c, radius=new_r, ccw=arc.ccw,
                         turns=max(math.ceil(abs(arc.sweep) / (2.0 * math.pi) - 1e-9) - 1, 0))
            el.pc = _flat(centers[i], plane) if i in centers else c
            el.pr = math.hypot(*(b2 - el.pc)) - s * radius * (1.0 if arc.ccw else -1.0)
        else:
            d = b2 - a2
            n = s * radius * _left(d / math.hypot(*d))
            el = _Offset(index=i, kind="line", a=a2 + n, b=b2 + n, za=float(b.start[plane]), zb=float(b.target[plane]))
        el.a0, el.b0 = el.a.copy(), el.b.copy()
        offsets.append(el)

    return offsets


def _entry_element(eb: Block, first: int, offsets: list[_Offset], *, entry: str, s: float, radius: float,
                   plane: int) -> _Offset:
    """The entry move, ending at the tool position of the entry rule."""
    # entry move
    e_start, e_prog = _flat(eb.start, plane), _flat(eb.target, plane)
    dist = math.hypot(*(e_prog - e_start))
    if entry == "perpendicular" and offsets:
        e_end = offsets[0].a.copy()
    else:
        if dist <= radius:
            raise CompensationError(
                f"length of cutter compensation entry move ({dist:g} mm) is not greater than the tool radius "
                f"({radius:g} mm)", first)
        e_end = e_prog + s * radius * _left((e_prog - e_start) / dist)
    ent = _Offset(index=first, kind="line", a=e_start, b=e_end, za=float(eb.start[plane]), zb=float(eb.target[plane]))
    # an inside corner after the entry is cut on the entry's parallel offset, as convert_*_comp2 take the
    # direction of the last cut from the programmed point to the tool; the entry still starts where the tool is
    ent.a0, ent.b0 = (e_start + (e_end - e_prog) if entry == "linuxcnc" else e_start.copy()), e_end.copy()
    return ent


def _entry_arc(eb: Block, first: int, *, s: float, radius: float, plane: int,
               centers: Mapping[int, np.ndarray]) -> _Offset:
    """An arc entry move, as LinuxCNC's ``convert_arc_comp1``: from the uncompensated position to the
    programmed end moved by ``r`` along the radius (towards the centre with the tool inside), about a
    new centre on the line from that end through the programmed centre, as far from both ends."""
    arc = eb.segment
    cur, end = _flat(eb.start, plane), _flat(eb.target, plane)
    pc = _flat(centers[first], plane) if first in centers else _flat(arc.center, plane)
    if math.hypot(*(end - cur)) <= radius:
        raise CompensationError(f"Radius of cutter compensation entry arc is not greater than the tool radius "
                                f"({radius:g} mm)", first)
    inside = (s > 0.0) == arc.ccw
    if inside and math.hypot(*(pc - cur)) <= radius:
        raise CompensationError(f"Tool radius {radius:g} mm not less than arc radius with cutter radius comp", first)
    away = (end - pc) / math.hypot(*(end - pc))
    new_end = end + radius * (-away if inside else away)
    ab = _angle(pc - new_end)
    cos_a = math.cos(_angle(cur - new_end) - ab)
    if abs(cos_a) < 1e-6:  # TOLERANCE_EQUAL
        raise CompensationError(f"Tool radius {radius:g} mm not less than arc radius with cutter radius comp", first)
    c = new_end + math.hypot(*(cur - new_end)) / 2.0 / cos_a * np.array([math.cos(ab), math.sin(ab)])
    r_new = math.hypot(*(new_end - c))
    el = _Offset(index=first, kind="arc", a=cur, b=new_end, za=float(eb.start[plane]), zb=float(eb.target[plane]),
                 c=c, radius=r_new, ccw=arc.ccw, turns=max(math.ceil(abs(arc.sweep) / (2.0 * math.pi) - 1e-9) - 1, 0),
                 a0=cur.copy(), b0=new_end.copy(), pc=c, pr=r_new)
    return el


def _join_corners(chain: list[_Offset], blocks: list[Block], *, s: float, radius: float, plane: int,
                  rule: str, rounded: Collection[int], small: float) -> dict[int, list[tuple]]:
    """Trim the elements at inside corners and return the outside corners' arcs (or straight pieces): index
    of the following block -> [(centre or None, from, to), ...]. LinuxCNC's ``convert_straight_comp2`` /
    ``convert_arc_comp2`` decide the corner (:func:`_corner_kind`) and :func:`_concave_point` where the
    elements meet inside; under ``rule="fanuc"`` :func:`_fanuc_corner` turns outside corners, except where
    G39 came (``rounded``)."""
    corners: dict[int, list[tuple]] = {}
    for el_a, el_b in zip(chain[:-1], chain[1:]):
        if math.hypot(*(el_a.b - el_b.a)) <= 1e-7:
            el_b.a = el_a.b.copy()
            if el_b.kind == "arc":
                el_a.spiral_from = None  # flushed unchecked (dequeue_canons)
            continue
        corner = _flat(blocks[el_a.index].target, plane)
        kind, theta, beta = _corner_kind(el_a, el_b, corner, s, small)
        if kind != "concave" and el_b.kind == "arc":
            # convert_arc_comp2 flushes the queued move unchecked at an outside corner (dequeue_canons); into a
            # line, at an inside corner, at G40 and at the program end move_endpoint_and_flush checks it
            el_a.spiral_from = None
        if kind == "concave":
            x = _concave_point(el_a, el_b, corner, theta, beta, s=s, radius=radius)
            el_a.b, el_b.a = x.copy(), x.copy()
            continue
        g39 = any(el_a.index < k <= el_b.index for k in rounded)
        fanuc = rule == "fanuc" and not g39
        pieces = _fanuc_corner(el_a, el_b, corner, beta, radius=radius, small=small) if fanuc else None
        if pieces is not None:
            if pieces:
                corners[el_b.index] = pieces
        elif kind == "arc":
            rapid = el_b.kind == "line" and blocks[el_b.index].kind == "rapid"  # G0: a traverse, no arc
            corners[el_b.index] = [(None if rapid else corner, el_a.b.copy(), el_b.a.copy())]
        elif el_b.kind == "line":  # LinuxCNC's "convex, one arc needed": the line starts where the tool is
            el_b.a, el_b.a0 = el_a.b.copy(), el_a.b.copy()
        else:  # LinuxCNC starts the arc where the tool is (a spiral); vcnc bridges the gap by a line
            corners[el_b.index] = [(None, el_a.b.copy(), el_b.a.copy())]
            if rule == "linuxcnc":
                el_b.spiral_from = el_a.b.copy()
    return corners


def _fanuc_corner(el_a: _Offset, el_b: _Offset, corner: np.ndarray, beta: float, *,
                  radius: float, small: float) -> list[tuple] | None:
    """An outside corner under Fanuc's cutter compensation C ("Tool movement in offset mode"): for a turn
    ``beta`` of at most 90 degrees (the corner's angle ``alpha = 180 - beta`` on the workpiece side at least
    90) both elements end at the intersection of their offsets, the one nearest the corner; for a sharper
    turn the tool goes on ``r`` along the first element's end tangent, straight to ``r`` before the second
    element's start along its tangent, and on (a line is lengthened, an arc keeps its end and a straight
    piece is added). Returns the pieces to insert before ``el_b`` ([] for none), or None for a turn of at
    most ``small`` (:data:`CONVEX_TOLERANCE`) whose offsets do not meet (parallel lines, a tangent arc), left to the
    LinuxCNC rule."""
    if beta <= math.pi / 2.0:
        cands = _intersections(el_a, el_b)
        if cands:
            x = min(cands, key=lambda c: math.hypot(*(c - corner)))
            for el, old in ((el_a, el_a.b), (el_b, el_b.a)):
                if el.kind == "arc":
                    el.grown += abs((_angle(x - el.c) - _angle(old - el.c) + math.pi) % (2.0 * math.pi) - math.pi)
            el_a.b, el_b.a = x.copy(), x.copy()
            return []
        if beta <= small:
            return None
    p1 = el_a.b + radius * el_a.tangent(el_a.b)
    p2 = el_b.a - radius * el_b.tangent(el_b.a)
    pieces = []
    if el_a.kind == "line":
        el_a.b = p1
    else:
        pieces.append((None, el_a.b.copy(), p1))
    pieces.append((None, p1, p2))
    if el_b.kind == "line":
        el_b.a = p2
    else:
        pieces.append((None, p2, el_b.a.copy()))
    return [piece for piece in pieces if math.hypot(*(piece[2] - piece[1])) > _EPS]


def _angle(v: np.ndarray) -> float:
    return math.atan2(float(v[1]), float(v[0]))


def _tool_inside(el: _Offset, s: float) -> bool:
    """LinuxCNC's TOOL_INSIDE_ARC: tool left of a counter-clockwise arc or right of a clockwise one."""
    return (s > 0.0) == el.ccw


def _corner_kind(el_a: _Offset, el_b: _Offset, corner: np.ndarray, s: float,
                 small: float) -> tuple[str, float, float]:
    """The corner between two elements as LinuxCNC classifies it: ("concave" | "arc" | "straight", theta,
    beta) [rad].

    ``theta`` is the direction from the programmed corner to the tool at the end of ``el_a``; ``beta`` the
    turn, positive away from the tool. Into a line (``convert_straight_comp2``) the corner is concave
    when ``beta < -small`` or ``beta > pi + small``, or ``beta > pi - small`` after an arc the tool is
    outside of (the "h" shape); into an arc (``convert_arc_comp2``, ``beta`` normalised to
    [-pi/2, 3 pi/2]) when ``beta < -small``, ``beta > pi + small`` or ``|beta - pi| < small`` with the
    tool outside the new arc (the "m" shape). Otherwise a turn over ``small`` (the run's
    ``convex_tolerance``) gets a corner arc, a smaller one none ("straight").
    """
    theta = _angle(el_a.b0 - corner)
    left = s > 0.0
    if el_b.kind == "line":
        alpha = _angle(el_b.b0 - el_b.a0)
        if left:
            th = theta + 2.0 * math.pi if theta < alpha else theta
            beta = th - alpha - math.pi / 2.0
        else:
            al = alpha + 2.0 * math.pi if alpha < theta else alpha
            beta = al - theta - math.pi / 2.0
        concave = beta < -small or beta > math.pi + small or (
            beta > math.pi - small and el_a.kind == "arc" and not _tool_inside(el_a, s))
    else:
        th = theta - math.pi / 2.0 if left else theta + math.pi / 2.0
        delta = _angle(el_b.c - corner)
        alpha = delta - math.pi / 2.0 if el_b.ccw else delta + math.pi / 2.0
        beta = th - alpha if left else alpha - th
        beta = beta - 2.0 * math.pi if beta > 1.5 * math.pi else beta + 2.0 * math.pi if beta < -math.pi / 2 else beta
        concave = beta < -small or beta > math.pi + small or (
            abs(beta - math.pi) < small and not _tool_inside(el_b, s))
    return ("concave" if concave else "arc" if beta > small else "straight"), theta, beta


def _concave_point(el_a: _Offset, el_b: _Offset, corner: np.ndarray, theta: float, beta: float, *, s: float,
                   radius: float) -> np.ndarray:
    """Where both elements end at an inside corner, by LinuxCNC's formulas (``convert_straight_comp2``:
    line-line and arc-line; ``convert_arc_comp2``: line-arc and arc-arc); CompensationError with its
    messages where the tool cannot reach the corner."""
    fail = f"without gouging (tool radius {radius:g} mm)"
    if el_b.kind == "line" and el_a.kind == "line":
        # back from the tool's offset end along the programmed direction of el_a by r / tan(half the corner),
        # the meeting of the offset lines; where el_a starts at the tool after a corner of at most small (a line
        # a little off its programmed direction) on the programmed offset line, not on the line the tool runs
        d, normal = el_a.b0 - el_a.a0, el_a.b0 - corner
        cands = _intersections(el_a, el_b)
        if cands and abs(float(d @ normal)) <= 1e-12 * math.hypot(*d) * math.hypot(*normal):
            return cands[0]  # el_a runs on its programmed offset line: the meeting, exact on axis-parallel lines
        half = (beta + math.pi) / 2.0
        if abs(math.sin(half)) <= _EPS:
            raise CompensationError(f"Zero degree inside corner is invalid for cutter compensation {fail}",
                                    el_b.index)
        back = theta + (math.pi / 2.0 if s > 0.0 else -math.pi / 2.0)
        return el_a.b0 + radius * math.cos(half) / math.sin(half) * np.array([math.cos(back), math.sin(back)])
    if el_b.kind == "line":  # arc -> line
        oldrad = el_a.radius
        th = _angle(el_b.b0 - el_b.a0) + (math.pi / 2.0 if el_a.ccw else -math.pi / 2.0)
        inside = _tool_inside(el_a, s)
        d = (oldrad + radius if inside else oldrad - radius) * math.cos(th - _angle(el_a.c - corner))
        ratio = (d - radius if inside else d + radius) / oldrad
        if abs(ratio) > 1.0:
            raise CompensationError(f"Arc to straight motion makes a corner the compensated tool can't fit in {fail}",
                                    el_b.index)
        sign = -1.0 if inside == el_a.ccw else 1.0
        ang = sign * math.acos(ratio) + th + math.pi
        return el_a.c + oldrad * np.array([math.cos(ang), math.sin(ang)])
    inside = _tool_inside(el_b, s)
    if el_a.kind == "line":  # line -> arc
        new_r = el_b.radius
        th = theta - math.pi / 2.0 if s > 0.0 else theta + math.pi / 2.0
        arc_r = new_r + radius if inside else new_r - radius
        toward = arc_r * math.sin(beta - math.pi / 2.0) + (radius if inside else -radius)
        ratio = toward / new_r
        if abs(ratio) > 1.0:
            raise CompensationError(f"Arc move in concave corner cannot be reached by the tool {fail}", el_b.index)
        if inside:
            ang = th + math.asin(ratio) if el_b.ccw else th - math.asin(ratio)
        else:
            ang = th + math.pi - math.asin(ratio) if el_b.ccw else th + math.pi + math.asin(ratio)
        return el_b.c + new_r * np.array([math.cos(ang), math.sin(ang)])
    # arc -> arc, on the circles about the programmed centres: where two offset circles meet at a small angle,
    # moving a centre by the rounding of a 4-decimal program moves the corner by several um (tests/interp/
    # inside-corners, line 17)
    new_r = el_b.pr
    oldrad = math.hypot(*(el_a.b0 - el_a.pc))
    cc = math.hypot(*(el_b.pc - el_a.pc))
    if cc <= _EPS:
        raise CompensationError("Arc to arc motion is invalid because the arcs have the same center", el_b.index)
    ratio = (oldrad**2 + cc**2 - new_r**2) / (2.0 * oldrad * cc)
    if abs(ratio) > 1.0:
        raise CompensationError(f"Arc to arc motion makes a corner the compensated tool can't fit in {fail}",
                                el_b.index)
    pullback = math.acos(ratio)
    sign = 1.0 if _tool_inside(el_a, s) == el_b.ccw else -1.0
    ang = _angle(el_b.pc - el_a.pc) + sign * pullback
    return el_a.pc + oldrad * np.array([math.cos(ang), math.sin(ang)])


def _sweep(el: _Offset, a: np.ndarray, b: np.ndarray) -> float:
    """Sweep [rad] of the arc element from ``a`` to ``b`` in its direction, with its extra turns (LinuxCNC's
    ``find_turn``: equal angles are a full turn)."""
    a0, a1 = _angle(a - el.c), _angle(b - el.c)
    sweep = ((a1 - a0) if el.ccw else (a0 - a1)) % (2.0 * math.pi)
    return (sweep if sweep > 1e-12 else 2.0 * math.pi) + 2.0 * math.pi * el.turns


def _check_gouges(chain: list[_Offset], ent: _Offset, blocks: list[Block], radius: float, *, inch: bool,
                  ends_only: bool = False) -> None:
    """CompensationError where a trimmed element gouges, by ``move_endpoint_and_flush`` (interp_queue.cc):
    a line that now runs against its programmed direction (the entry: against its offset direction), or
    an arc whose sweep grew by more than 0.0254 (mm programs) or 0.001 (inch programs) [rad] over the
    programmed sweep and what Fanuc's outside corners added. An arc LinuxCNC starts where the tool is (after a
    turn of at most ``small``: ``spiral_from``) sweeps from there, so that a start a little behind its offset
    start grows it (rs274 refuses an inch program's arcs of 1.2 deg turn so: tests/interpolators/
    test_compensation_spiral.py).

    ``ends_only`` (LinuxCNC's rule): a line is checked only when its end was moved. LinuxCNC checks a queued
    line when an inside corner moves its end point (the direction from its start to the new end against the
    direction it was queued with); a line whose start alone an inside corner moved back past its end is
    flushed as it is, a short move backwards (rs274 runs lagun-linuxcnc's spw_pew.ngc so: an entry, then a line
    shorter than the corner's retreat, then a tangent arc). Fanuc's interference check (the compensated path
    against the programmed one, more than 90 deg apart) looks at every trimmed line: ``ends_only`` False."""
    grow = 0.001 if inch else 0.0254
    for el in chain:
        if el.kind == "line":
            if ends_only and el is not ent and float(np.abs(el.b - el.b0).max()) <= 1e-12:
                continue
            ref = (el.a0 - el.a) if el is ent else (el.b0 - el.a0)
            if float((el.b - el.a) @ ref) >= 0.0:
                continue
            what = "Straight traverse" if blocks[el.index].kind == "rapid" else "Straight feed"
        else:
            sweep = _sweep(el, el.a if el.spiral_from is None else el.spiral_from, el.b)
            programmed = _sweep(el, el.a0, el.b0) if el is ent else abs(blocks[el.index].segment.sweep)
            if sweep <= programmed + el.grown + grow:
                continue
            what = "Arc move"
        raise CompensationError(f"{what} in concave corner cannot be reached by the tool without gouging "
                                f"(tool radius {radius:g} mm)", el.index)


def _assemble(blocks: list[Block], chain: list[_Offset], corners: dict[int, list[tuple]], *, first: int,
              last: int | None, side: str, plane: int) -> list[Block]:
    """The compensated blocks: the run's blocks on the tool-centre path, corner arcs inserted."""
    p, q = PLANE_AXES[plane]

    def point3(template: np.ndarray, xy: np.ndarray, z: float) -> np.ndarray:
        v = np.array(template, dtype=float)
        v[p], v[q] = xy
        v[plane] = z
        return v

    by_index = {el.index: el for el in chain}
    out: list[Block] = []
    tool = None  # tool position in the plane once the entry move has been made
    for i, b in enumerate(blocks):
        if i < first:
            out.append(b)
            continue
        if i == last:
            start = point3(b.start, tool, float(b.start[plane]))
            out.append(dataclasses.replace(b, start=start, segment=Line(start, b.target)))
            continue
        el = by_index.get(i)
        if el is None:  # tool-axis move or dwell: stays where the tool is
            st, tg = point3(b.start, tool, float(b.start[plane])), point3(b.target, tool, float(b.target[plane]))
            seg = None if b.segment is None else Line(st, tg)
            out.append(dataclasses.replace(b, start=st, target=tg, segment=seg))
            continue
        z0 = float(b.start[plane])
        for centre, frm, to in corners.get(i, ()):
            cs, ce = point3(b.start, frm, z0), point3(b.start, to, z0)
            if centre is None:
                seg, kind = Line(cs, ce), ("rapid" if b.kind == "rapid" else "line")
            else:
                seg, kind = Arc(cs, ce, point3(b.start, centre, z0), ccw=(side == "right"), plane=plane), "arc"
            feeds = [f for f in (b.feed, *(o.feed for o in reversed(out))) if 0.0 < f < math.inf]
            if kind == "rapid":
                feeds = [math.inf]
            if not feeds:
                raise CompensationError("outside corner between rapid moves: no feed for the corner arc", i)
            feed = feeds[0]
            out.append(dataclasses.replace(b, kind=kind, start=cs, target=ce, segment=seg, feed=feed, dwell=0.0))
        # a trimmed end keeps its block's tool-axis coordinate: LinuxCNC moves a queued move's end in the plane
        # only (interp_queue.cc move_endpoint_and_flush sets x, y of the XY plane), and the next move starts
        # there; so the tool-axis move of each block runs over its compensated element, start to end
        za, zb = el.za, el.zb
        st, tg = point3(b.start, el.a, za), point3(b.target, el.b, zb)
        if el.kind == "arc":  # intersections onto the circle to rounding, as Arc requires
            st = point3(b.start, el.c + el.radius * (el.a - el.c) / math.hypot(*(el.a - el.c)), za)
            tg = point3(b.target, el.c + el.radius * (el.b - el.c) / math.hypot(*(el.b - el.c)), zb)
            seg = Arc(st, tg, point3(b.start, el.c, za), ccw=el.ccw, plane=plane, turns=el.turns)
        else:
            seg = Line(st, tg)
        out.append(dataclasses.replace(b, start=st, target=tg, segment=seg))
        tool = el.b.copy()
    return out
