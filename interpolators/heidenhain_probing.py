"""Touch probe cycles of Heidenhain programs (``TCH PROBE 4xx``), run on the nominal workpiece.

A virtual CNC has no workpiece to touch; as CAM simulators do, vcnc runs the cycles on the workpiece the
cycle's data describe: every touch point lies where the nominal centre, diameter, side length or coordinate
puts the surface, so the measured values are the nominal ones, the deviations are 0, and the datum a cycle
sets is the one the nominal workpiece gives. The probe's moves become ordinary blocks (cycle time, path).

Sources: HEIDENHAIN TNC 320 user's manual "Cycle programming" (340 55x-04), chapter "Touch Probe Cycles:
Automatic Datum Setting": DATUM SLOT CENTER / RIDGE CENTER (cycles 408, 409), DATUM FROM INSIDE / OUTSIDE OF
RECTANGLE (410, 411), 15.6 DATUM FROM INSIDE OF CIRCLE (412), 15.7 DATUM FROM OUTSIDE OF CIRCLE (413), DATUM
IN TOUCH PROBE AXIS (417), DATUM IN ONE AXIS (419), and "Executing touch probe cycles"; iTNC 530 cycle
programming manual, 15.6 (cycle 412: the parameters Q261, Q320, Q260, Q301, Q305, Q331, Q332, Q303, and
"If you enter Q305=0, the TNC automatically sets the display so that the new datum is at the center").

Cycle runs (measured = nominal):

* positioning logic ("Executing touch probe cycles"): below the clearance height Q260 the probe first rises
  to it, then moves in the working plane to the first starting point; above it, it moves in the plane at its
  height; then it goes down to the starting point's height. These moves run at the FMAX column's feed;
* each touch: from its starting point, the set-up clearance (Q320 + SET_UP) before the surface, the probe
  moves at the probing feed F until the stylus tip (its radius: :attr:`TouchProbe.tip_radius`) touches the
  surface, and returns to the starting point; after the last touch the probe rises to Q260;
* 417: touch point 1 (Q263, Q264) probed down the touch probe axis to Q294. Result: Q160 = Q294. The datum:
  Q294 becomes Q333;
* 412 / 413: Q423 (4, or 3) touch points at the angles Q325 + k Q247 about the centre (Q321, Q322) on the
  circle of diameter Q262, at the measuring height Q261, probed radially outward (412, a hole) or inward (413,
  a stud). Between points: at the measuring height (Q301=0) or up to Q260, across and down again (Q301=1), on
  a straight line (Q365=0) or an arc about the centre (Q365=1, also when the definition has no Q365), as
  programmed: Q365 is the "Type of traverse? Line=0/arc=1" of the pattern cycle 220 (TNC 640 cycle manual
  34059x-01), and the cycles without it move "in a circular arc either at measuring height or at clearance
  height to the next starting point" (TNC 320 cycle manual 340 55x-04, cycle 422 "Cycle run" 3; iTNC 530 cycle
  manual 340 49x-06, cycle 405); a line at the measuring height between two points of 413 may cross the stud:
  vcnc has no workpiece to collide with. Results: Q151, Q152 = the centre, Q153 = the diameter. The datum: the
  centre becomes (Q331, Q332);
* 410 / 411: four touch points on the sides of the rectangle of side lengths Q323 (along the reference axis)
  and Q324 (the minor axis) about the centre (Q321, Q322), at the measuring height Q261, probed outward (410,
  a pocket) or inward (411, a stud), in the order of the manual's figure numbers as we read them: 1 on the
  side at the reference axis' minus end, 2 on the minor axis' minus side, 3 the reference axis' plus side, 4
  the minor axis' plus side (our reading: no page found states the order; gigacook/tnc426-simulator, a TNC
  simulator, takes the same). Between points: paraxially at the measuring height (Q301=0: along the one axis
  to the corner beside the rectangle, then the other) or straight at Q260 (Q301=1). Results: Q151, Q152 =
  the centre, Q154, Q155 = the side lengths. The datum: as 412;
* 408 / 409: two touch points on the walls of the slot (408, probed outward) or ridge (409, inward) of width
  Q311 about the centre (Q321, Q322), across the measuring axis Q272 (1: the reference axis, 2: the minor
  axis), the minus side first (our reading). 408 moves between them as Q301 says; 409 always at Q260 (it has
  no Q301: it must pass over the ridge). Results: Q166 = the width, Q157 = the centre line. The datum: the
  centre line becomes Q405 in the measuring axis;
* 419: one touch at (Q263, Q264) at the measuring height Q261 in the measuring axis Q272 (1, 2, or 3: the
  touch probe axis, where the touch point is Q261 itself: our reading) in the direction Q267 (+1 or -1). The
  datum: the touched coordinate becomes Q333 in that axis;
* a hole, pocket or slot too small for the starting points (half width - tip - clearance < 0): every touch
  from the centre, without clearance-height moves between them (iTNC 530 manual, cycles 410, 412 notes); a
  tip wider than the hole is an error. Q381=1 (408 - 413) also probes the touch probe axis at (Q382, Q383)
  down to Q384 as 417 does, which becomes Q333;
* 400 BASIC ROTATION: two touches as 419's at (Q263, Q264) and (Q265, Q266), between them straight at the
  measuring height (Q301=0) or over Q260 (Q301=1). The nominal workpiece lies as the program expects: the
  misalignment measured is the reference angle Q307 and the basic rotation set is 0 (our reading; noted), so
  the following blocks are unchanged and the preset row Q305 keeps its datum.

Automatic workpiece inspection (TNC 320 cycle manual, chapter "Touch Probe Cycles: Automatic Workpiece
Inspection", 16.1 "Measurement results in Q parameters", "Classification of results" and the cycles' result
tables): the measuring cycles set no datum; their results are the nominal values, the deviations Q161 - Q166
are 0, and Q180 = 1 (within tolerance; Q181 rework, Q182 scrap only where the nominal itself breaks a limit the
cycle gives: a hole or pocket too large or a stud too small is scrap, the other way rework, our reading; a limit
0 is not monitored). The measuring log (Q281) is not written: noted.

* 420 MEASURE ANGLE: touches as 400's; Q150 = the angle of the line through the two points from the reference
  axis [deg] (0 when Q272=3: both touch at Q261);
* 421 / 422 MEASURE HOLE / CIRCLE OUTSIDE: as 412 / 413 on the centre Q273, Q274; Q151 - Q153, Q161 - Q163;
* 423 / 424 MEASURE RECTANGLE INSIDE / OUTSIDE: as 410 / 411 on the centre Q273, Q274 and the sides Q282,
  Q283; Q151, Q152, Q154, Q155, Q161, Q162, Q164, Q165;
* 426 MEASURE RIDGE WIDTH: touch point 1 (Q263, Q264) probed in the minus direction of the measuring axis Q272
  ("the first probing is always in the negative direction"), point 2 (Q265, Q266) in the plus direction, over
  Q260 between them; Q156 = their distance, Q157 = their middle, Q166 = Q156 - Q311;
* 427 MEASURE COORDINATE: one touch as 419's; Q160 = the coordinate (the manual: a stud's dimension);
* 431 MEASURE PLANE: three touches down the touch probe axis as 417's; Q173 - Q175 = the heights; a plane
  level with the working plane: the angles Q158, Q159, Q170 - Q172 are 0; a tilted one is an error (its
  spatial angles are not modelled).

Our reading, where the manuals leave details open: the move back after a touch goes to the starting point at
the FMAX column's feed; the datum is set as :class:`ProbeRun` ``datum`` says (the reader applies it: Q305=0
the active preset, Q305=n with Q303=1 row n of the preset table, with Q303=0 row n of the datum table, which
``CYCL DEF 7.1 #n`` selects; Q303=-1 noted); a touch point farther from its starting point than the DIST
column is an error (the TNC reports it unreachable).

Not modelled (an error naming the cycle, and for some why): the other probe cycles (0, 1, 401-405, 414-416,
418, 425, 430, 444, 45x, 46x, 14xx, ...), and the tool touch probe cycles (TT: 30-33, 480-484: the tool
setter's position is not known).
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from interpolators._words import Where
from interpolators.context import TouchProbe
from toolpaths.geometry import PLANE_AXES

__all__ = ["PROBE_RE", "ProbeMove", "ProbeRun", "PROBE_CYCLES", "probe_run", "refuse_probe"]

#: ``TCH PROBE 417 DATUM IN TS AXIS Q263=..``: the cycle number, its sub-number (old ``TCH PROBE 0.1``), the rest.
PROBE_RE = re.compile(r"TCH\s*PROBE\s*(\d+)(?:\.(\d+))?(?![\d.])\s*(.*)$", re.I | re.S)

#: Cycles run here.
PROBE_CYCLES: tuple[int, ...] = (400, 408, 409, 410, 411, 412, 413, 417, 419, 420, 421, 422, 423, 424, 426, 427,
                                 431)

#: Tool measurement with the tool touch probe TT (TNC 320 / TNC 640 touch probe cycles manual, "Touch probe
#: cycles: automatic tool measurement").
_TOOL_CYCLES = (30, 31, 32, 33, 480, 481, 482, 483, 484)

_CIRCLE = (321, 322, 262, 325, 247, 261, 320, 260)
_RECTANGLE = (321, 322, 323, 324, 261, 320, 260)
_SLOT = (321, 322, 311, 272, 261, 320, 260)
_ONE_AXIS = (263, 264, 261, 320, 260, 272, 267)
_TWO_POINTS = (263, 264, 265, 266, 272, 267, 261, 320, 260)
#: The Q parameters a definition must give (TNC 320 cycle manual, the cycles' parameter lists); the others take
#: the defaults of :data:`_DEFAULTS`.
_REQUIRED = {417: (263, 264, 294, 320, 260), 412: _CIRCLE, 413: _CIRCLE, 410: _RECTANGLE, 411: _RECTANGLE,
             408: _SLOT, 409: _SLOT, 419: _ONE_AXIS, 427: _ONE_AXIS, 400: _TWO_POINTS, 420: _TWO_POINTS,
             421: (273, 274, 262, 325, 247, 261, 320, 260), 422: (273, 274, 262, 325, 247, 261, 320, 260),
             423: (273, 274, 282, 283, 261, 320, 260), 424: (273, 274, 282, 283, 261, 320, 260),
             426: (263, 264, 265, 266, 272, 261, 320, 260, 311),
             431: (263, 264, 294, 265, 266, 295, 296, 297, 298, 320, 260)}
#: The measuring cycles that probe as a datum cycle does, and their parameters' numbers in that cycle's.
_INSPECTION = {421: 412, 422: 413, 423: 410, 424: 411}
_RENAMED = {273: 321, 274: 322, 282: 323, 283: 324}
#: Defaults of optional parameters (our reading: the TNC's dialog values): Q301=1 clearance height between
#: points, Q305=0 the active datum, Q303=1 the preset table, Q423=4 points, Q365=1 arcs (see above); the limits
#: of the measuring cycles 0 (not monitored: TNC 320 cycle manual 16.1, "Tolerance monitoring").
_DEFAULTS = {301: 1.0, 305: 0.0, 331: 0.0, 332: 0.0, 303: 1.0, 333: 0.0, 381: 0.0, 423: 4.0, 365: 1.0, 405: 0.0,
             **dict.fromkeys((275, 276, 277, 278, 284, 285, 286, 287, 288, 289), 0.0)}


@dataclasses.dataclass(frozen=True)
class ProbeMove:
    """One move of the probe in program coordinates [mm]: a line to ``target``, or (``centre`` set) an arc
    about ``centre`` through ``sweep`` [deg, positive counter-clockwise] in the working plane; ``feed``
    [mm/min]."""

    target: np.ndarray
    feed: float
    centre: np.ndarray | None = None
    sweep: float = 0.0


@dataclasses.dataclass(frozen=True)
class ProbeRun:
    """What a probe cycle does: its ``moves``, the ``results`` (Q number -> value [program units]), and the
    datum: the program point ``datum_from`` [mm] (NaN in axes the cycle does not set) gets the program
    coordinates ``datum_to`` [mm], stored as ``q305`` (0: the active datum) in the table ``q303`` names; ``notes``
    for the reader to add."""

    moves: list[ProbeMove]
    results: dict[int, float]
    datum_from: np.ndarray
    datum_to: np.ndarray
    q305: int
    q303: int
    notes: tuple[str, ...] = ()


class _Path:
    """The moves of a run, from the probe's program position (its tool point) [mm]."""

    def __init__(self, here: np.ndarray, plane: int, probe: TouchProbe) -> None:
        self.pos = np.array(here, dtype=float)
        self.plane = plane
        self.probe = probe
        self.moves: list[ProbeMove] = []

    def line(self, target: np.ndarray, feed: float) -> None:
        target = np.array(target, dtype=float)
        if np.any(np.abs(target - self.pos) > 1e-12):
            self.moves.append(ProbeMove(target, feed))
            self.pos = target

    def axis(self, level: float) -> None:
        """Along the touch probe axis to ``level`` at FMAX."""
        target = self.pos.copy()
        target[self.plane] = level
        self.line(target, self.probe.fmax)

    def arc(self, centre: np.ndarray, target: np.ndarray, sweep: float) -> None:
        self.moves.append(ProbeMove(np.array(target, dtype=float), self.probe.fmax, np.array(centre), sweep))
        self.pos = np.array(target, dtype=float)

    def pre_position(self, start: np.ndarray, clearance: float) -> None:
        """The positioning logic to ``start`` (TNC 320 cycle manual, "Executing touch probe cycles")."""
        if self.pos[self.plane] < clearance:
            self.axis(clearance)
        across = start.copy()
        across[self.plane] = self.pos[self.plane]
        self.line(across, self.probe.fmax)
        self.axis(start[self.plane])

    def touch(self, start: np.ndarray, touch: np.ndarray, where: Where, what: str) -> None:
        """Probe from ``start`` to ``touch`` at the probing feed and back at FMAX."""
        if float(np.linalg.norm(touch - start)) > self.probe.dist + 1e-9:
            where.fail(f"{what}: the touch point is {float(np.linalg.norm(touch - start)):g} mm from its starting "
                       f"point, beyond the touch probe table's DIST {self.probe.dist:g} mm", column=1,
                       text=where.text, expected="a set-up clearance Q320 + SET_UP within the probing path DIST")
        self.line(touch, self.probe.feed)
        self.line(start, self.probe.fmax)


#: Why some workpiece probe cycles are not run.
_WHY = {**dict.fromkeys((401, 418, 430), "the holes' diameters are not in its data, so the nominal workpiece gives no "
                                    "touch points"),
        **dict.fromkeys((402, 403, 405), "it turns a rotary axis or table to align the workpiece"),
        404: "it sets a basic rotation (a turned coordinate system)",
        425: "its data give the starting point, not where the walls lie",
        **dict.fromkeys((414, 415), "no manual page found for where it touches")}


def refuse_probe(number: int, where: Where, column: int) -> None:
    """The error of a probe cycle vcnc does not run."""
    if number in _TOOL_CYCLES:
        where.fail(f"TCH PROBE {number} (tool measurement with the tool touch probe TT) is not modelled: the tool "
                   "setter's position is not known", column=column, text=where.text,
                   expected=f"TCH PROBE {', '.join(map(str, PROBE_CYCLES))} (workpiece probing)")
    why = f": {_WHY[number]}" if number in _WHY else ""
    where.fail(f"TCH PROBE {number} is not modelled{why} (vcnc runs the touch probe cycles "
               f"{', '.join(map(str, PROBE_CYCLES))} on the nominal workpiece)", column=column, text=where.text,
               expected=f"TCH PROBE {', '.join(map(str, PROBE_CYCLES))}")


def probe_run(number: int, q: dict[int, float], *, here: np.ndarray, plane: int, tip_radius: float,
              scale: float, probe: TouchProbe, where: Where, column: int) -> ProbeRun:
    """The run of touch probe cycle ``number`` with its parameters ``q`` [program units] from the probe's
    program position ``here`` [mm] (its tool point), the touch probe axis ``plane`` (the tool axis, 0 1 2),
    the stylus tip's radius ``tip_radius`` [mm], ``scale`` mm per program unit."""
    _require(number, q, _REQUIRED[number], "in the cycle definition", where, column)
    q = {**_DEFAULTS, **q}
    out = _Outcome(_Path(here, plane, probe), scale, tip_radius, where, column, number)
    if number == 417:
        out.results[160] = q[294]
        _axis_touch(out.path, (q[263], q[264], q[294]), q, scale, where, number)
        out.datum(plane, q[294], q[333])
    elif number in (419, 427):
        axis, nominal = out.axis_touches(q, [(q[263], q[264])])
        if number == 419:
            out.datum(axis, nominal, q[333])
        else:
            out.results[160] = nominal
            out.status([(nominal, q[288], q[289])], inside=False)
    elif number in (400, 420):
        _edge(out, q)
    elif number == 426:
        _ridge(out, q)
    elif number == 431:
        _plane(out, q)
    else:
        _shape_cycle(out, q)
    out.path.axis(q[260] * scale)
    if q.get(281, 0) != 0:
        out.notes.append(f"TCH PROBE {number}: the measuring log (Q281={q[281]:g}) is not written")
    return ProbeRun(out.path.moves, out.results, out.datum_from, out.datum_to, _whole(q, 305, where, column),
                    _whole(q, 303, where, column), tuple(out.notes))


class _Outcome:
    """What a run builds up: the probe's path, the results, the datum, notes."""

    def __init__(self, path: _Path, scale: float, tip: float, where: Where, column: int, number: int) -> None:
        self.path, self.scale, self.tip, self.where, self.column, self.number = path, scale, tip, where, column, number
        self.results: dict[int, float] = {}
        self.datum_from, self.datum_to = np.full(3, np.nan), np.full(3, np.nan)
        self.notes: list[str] = []

    def datum(self, axis: int, nominal: float, new: float) -> None:
        """The probed coordinate ``nominal`` of ``axis`` (0 1 2) becomes ``new`` [program units]."""
        self.datum_from[axis], self.datum_to[axis] = nominal * self.scale, new * self.scale

    def fail(self, message: str, expected: str) -> None:
        self.where.fail(f"TCH PROBE {self.number}: {message}", column=self.column, text=self.where.text,
                        expected=expected)

    def status(self, checks: list[tuple[float, float, float]], *, inside: bool) -> None:
        """Q180 - Q182 (TNC 320 cycle manual 16.1 "Classification of results") from (value, maximum, minimum)
        [program units] each (a limit 0: not monitored): a hole too large or a stud too small is scrap, the other
        way rework (our reading); measured = nominal, so only limits the nominal itself breaks count."""
        scrap = any((hi and value > hi and inside) or (lo and value < lo and not inside) for value, hi, lo in checks)
        rework = not scrap and any((hi and value > hi) or (lo and value < lo) for value, hi, lo in checks)
        self.results.update({180: float(not (scrap or rework)), 181: float(rework), 182: float(scrap)})
        if scrap or rework:
            self.notes.append(f"TCH PROBE {self.number}: the nominal workpiece is outside the cycle's limits "
                              f"({'scrap' if scrap else 'rework'})")

    def axis_touches(self, q: dict[int, float], points: list[tuple[float, float]],
                     signs: tuple[float, ...] | None = None) -> tuple[int, float]:
        """Touches at ``points`` (reference axis, minor axis) [program units] at the measuring height Q261 along
        the measuring axis Q272 (1, 2, 3: the touch probe axis, where the touch point is Q261: our reading) in the
        direction Q267 (or ``signs``, one per point, moving over Q260 between them), moving between them at Q260
        (Q301=1) or straight at the measuring height; the axis (0 1 2) and the nominal coordinate of the last
        touch [program units]."""
        if q[272] not in (1, 2, 3) or (signs is None and q[267] not in (1, -1)):
            self.fail(f"measuring axis Q272={q[272]:g}, traverse direction Q267={q.get(267, 0):g}",
                      "Q272 = 1, 2 or 3 and Q267 = +1 or -1")
        path, scale = self.path, self.scale
        k = int(q[272]) - 1
        axis = (*PLANE_AXES[path.plane], path.plane)[k]
        nominal = 0.0
        for n, (u, v) in enumerate(points):
            offset = np.zeros(3)
            offset[axis] = q[267] if signs is None else signs[n]
            nominal = (u, v, q[261])[k]
            touch = _point(path.plane, u * scale, v * scale, q[261] * scale)
            touch -= offset * (self.tip if k < 2 else 0.0)  # in the plane the tip's centre stops a radius short
            start = touch - offset * (q[320] * scale + path.probe.set_up)
            if n == 0:
                path.pre_position(start, q[260] * scale)
            elif q[301] == 1 or signs is not None:
                path.axis(q[260] * scale)
                path.line(_point(path.plane, *(start[list(PLANE_AXES[path.plane])]), q[260] * scale), path.probe.fmax)
                path.axis(start[path.plane])
            else:
                path.line(start, path.probe.fmax)
            path.touch(start, touch, self.where, f"TCH PROBE {self.number} touch point {n + 1}")
        return axis, nominal


def _ridge(out: _Outcome, q: dict[int, float]) -> None:
    """426 MEASURE RIDGE WIDTH: touch point 1 (Q263, Q264) probed in the minus direction of the measuring axis
    Q272, point 2 (Q265, Q266) in the plus direction ("the first probing is always in the negative direction"),
    over Q260 between them. Q156 = the distance of the two touch points along the axis, Q157 = their middle,
    Q166 = Q156 - the nominal length Q311 (0 when the points lie Q311 apart, as on the nominal ridge)."""
    if q[272] not in (1, 2):
        out.fail(f"measuring axis Q272={q[272]:g}", "Q272 = 1 or 2")
    out.axis_touches(q, [(q[263], q[264]), (q[265], q[266])], signs=(-1.0, 1.0))
    first, second = (q[263], q[265]) if q[272] == 1 else (q[264], q[266])
    width = first - second
    out.results.update({156: width, 157: (first + second) / 2.0, 166: width - q[311]})
    out.status([(width, q[288], q[289])], inside=False)


def _edge(out: _Outcome, q: dict[int, float]) -> None:
    """400 BASIC ROTATION, 420 MEASURE ANGLE: two touches along the measuring axis at (Q263, Q264) and (Q265,
    Q266). 420: Q150 = the angle of the line through them from the reference axis [deg] (0 in the touch probe
    axis, where both touch Q261). 400: the nominal workpiece lies as the program expects, so the misalignment
    measured is the preset rotation angle Q307 and the basic rotation the cycle sets is 0 (our reading): noted."""
    out.axis_touches(q, [(q[263], q[264]), (q[265], q[266])])
    if out.number == 420:
        flat = q[272] == 3
        out.results[150] = 0.0 if flat else math.degrees(math.atan2(q[266] - q[264], q[265] - q[263]))
    else:
        out.notes.append("TCH PROBE 400: basic rotation 0 (the nominal workpiece is not misaligned)")


def _plane(out: _Outcome, q: dict[int, float]) -> None:
    """431 MEASURE PLANE: three touches down the touch probe axis as 417's; Q173 - Q175 = the probed heights.
    A plane the three nominal points tilt: its angles Q158, Q159, Q170 - Q172 are not modelled (an error);
    a level one: all 0."""
    points = [(q[263], q[264], q[294]), (q[265], q[266], q[295]), (q[296], q[297], q[298])]
    if len({p[2] for p in points}) > 1:
        out.fail("a tilted plane (its spatial angles Q170 - Q172) is not modelled",
                 "Q294 = Q295 = Q298 (a plane square to the touch probe axis)")
    for point in points:
        _axis_touch(out.path, point, q, out.scale, out.where, out.number)
    out.results.update({158: 0.0, 159: 0.0, 170: 0.0, 171: 0.0, 172: 0.0, 173: q[294], 174: q[295], 175: q[298]})


def _shape_cycle(out: _Outcome, q: dict[int, float]) -> None:
    """The cycles probing a circle, rectangle, slot or ridge: 408 - 413 set the datum (and Q381=1 the probe
    axis's), 421 - 424 measure (their centre Q273/Q274 and sides Q282/Q283 as 410 - 413's Q321/Q322, Q323/Q324):
    the deviations Q161 - Q165 are 0 and Q180 - Q182 the status."""
    number, plane = out.number, out.path.plane
    datum_cycle = _INSPECTION.get(number, number)
    shape = _Shape(out.path, datum_cycle, {_RENAMED.get(n, n): v for n, v in q.items()}, out.scale, out.tip,
                   out.where)
    out.results.update(shape.run())
    if number in _INSPECTION:
        out.results.update(dict.fromkeys((161, 162, 163) if datum_cycle > 411 else (161, 162, 164, 165), 0.0))
        if number in (421, 422):
            limits = [(q[262], *((q[275], q[276]) if number == 421 else (q[277], q[278])))]
        else:
            limits = [(q[282], q[284], q[285]), (q[283], q[286], q[287])]
        out.status(limits, inside=number in (421, 423))
        return
    for i, nominal, new in shape.datum():
        out.datum(PLANE_AXES[plane][i], nominal, new)
    if q[381] == 1:
        _require(number, q, (382, 383, 384), "with Q381=1 (the touch point in the touch probe axis)", out.where,
                 out.column)
        _axis_touch(out.path, (q[382], q[383], q[384]), q, out.scale, out.where, number)
        out.datum(plane, q[384], q[333])


def _require(number: int, q: dict[int, float], needed: tuple[int, ...], what: str, where: Where,
             column: int) -> None:
    missing = [n for n in needed if n not in q]
    if missing:
        where.fail(f"TCH PROBE {number} lacks {', '.join(f'Q{n}' for n in missing)}", column=column,
                   text=where.text, expected=f"Q{' Q'.join(map(str, needed))} {what}")


def _whole(q: dict[int, float], n: int, where: Where, column: int) -> int:
    if q[n] != int(q[n]) or (n == 305 and q[n] < 0):
        where.fail(f"Q{n}={q[n]:g} is not a whole number{' >= 0' if n == 305 else ''}", column=column,
                   text=where.text, expected=f"Q{n} = a row number" if n == 305 else "Q303 = -1, 0 or 1")
    return int(q[n])


def _point(plane: int, u: float, v: float, w: float) -> np.ndarray:
    """The point of reference-axis, minor-axis and touch-probe-axis coordinates ``u``, ``v``, ``w`` [mm]."""
    a, b = PLANE_AXES[plane]
    p = np.zeros(3)
    p[[a, b, plane]] = u, v, w
    return p


def _axis_touch(path: _Path, point: tuple[float, float, float], q: dict[int, float], scale: float, where: Where,
                number: int) -> None:
    """Probing down the touch probe axis to ``point`` (reference axis, minor axis, probe axis) [program units]:
    cycle 417's run, and the probe-axis touch of Q381=1."""
    touch = _point(path.plane, *(np.array(point) * scale))
    start = touch.copy()
    start[path.plane] += q[320] * scale + path.probe.set_up
    path.pre_position(start, q[260] * scale)
    path.touch(start, touch, where, f"TCH PROBE {number}")


class _Shape:
    """The touch points of the cycles probing a circle (412, 413), rectangle (410, 411) or slot / ridge (408,
    409) in the working plane at the measuring height Q261, and their results."""

    def __init__(self, path: _Path, number: int, q: dict[int, float], scale: float, tip: float,
                 where: Where) -> None:
        self.path, self.number, self.q, self.scale, self.where = path, number, q, scale, where
        self.inside = number in (408, 410, 412)
        self.centre = _point(path.plane, q[321] * scale, q[322] * scale, q[261] * scale)
        self.gap = q[320] * scale + path.probe.set_up
        self.tip = tip

    def run(self) -> dict[int, float]:
        q = self.q
        if self.number in (412, 413):
            points = self._circle_points()
            results = {151: q[321], 152: q[322], 153: q[262]}
        elif self.number in (410, 411):
            points = self._rectangle_points()
            results = {151: q[321], 152: q[322], 154: q[323], 155: q[324]}
        else:
            points = self._slot_points()
            results = {166: q[311], 157: q[320 + int(q[272])]}
        self._probe(points)
        return results

    def datum(self) -> list[tuple[int, float, float]]:
        """(plane axis 0 / 1, nominal coordinate, new coordinate) [program units] of the datum set."""
        q = self.q
        if self.number in (408, 409):
            k = int(q[272]) - 1
            return [(k, q[321 + k], q[405])]
        return [(0, q[321], q[331]), (1, q[322], q[332])]

    def _fail(self, message: str, expected: str) -> None:
        self.where.fail(f"TCH PROBE {self.number}: {message}", column=1, text=self.where.text, expected=expected)

    def _radii(self, half: float) -> tuple[float, float]:
        """The distances from the centre [mm] of the tip's centre at the touch and of the starting point, across
        a wall ``half`` [mm] from it; a starting point past the centre: 0 (probed from the centre)."""
        side = -1.0 if self.inside else 1.0
        touch = half + side * self.tip
        if touch <= 0:
            self._fail(f"the stylus tip (radius {self.tip:g} mm) does not fit the hole (diameter or width "
                       f"{2 * half:g} mm)", "a nominal size above the tip's diameter")
        return touch, max(touch + side * self.gap, 0.0)

    def _circle_points(self) -> list[tuple[np.ndarray, np.ndarray]]:
        q = self.q
        count = int(q[423])
        if count not in (3, 4) or q[423] != count:
            self._fail(f"Q423={q[423]:g} measuring points", "Q423 = 3 or 4")
        if q[262] <= 0 or q[247] == 0:
            self._fail(f"nominal diameter Q262={q[262]:g}, stepping angle Q247={q[247]:g}",
                       "Q262 > 0 and Q247 != 0")
        touch, start = self._radii(q[262] * self.scale / 2.0)
        units = [_point(self.path.plane, math.cos(t), math.sin(t), 0.0)
                 for t in np.radians(q[325] + np.arange(count) * q[247])]
        return [(self.centre + start * u, self.centre + touch * u) for u in units]

    def _rectangle_points(self) -> list[tuple[np.ndarray, np.ndarray]]:
        q = self.q
        if q[323] <= 0 or q[324] <= 0:
            self._fail(f"side lengths Q323={q[323]:g}, Q324={q[324]:g}", "Q323 > 0 and Q324 > 0")
        (tu, su), (tv, sv) = (self._radii(q[n] * self.scale / 2.0) for n in (323, 324))
        if su == 0.0 or sv == 0.0:  # a pocket too small for the starting points: all from the centre
            su = sv = 0.0
        plane = self.path.plane
        return [(self.centre + _point(plane, du * su, dv * sv, 0.0), self.centre + _point(plane, du * tu, dv * tv, 0))
                for du, dv in ((-1, 0), (0, -1), (1, 0), (0, 1))]

    def _slot_points(self) -> list[tuple[np.ndarray, np.ndarray]]:
        q = self.q
        if q[272] not in (1, 2) or q[311] <= 0:
            self._fail(f"measuring axis Q272={q[272]:g}, width Q311={q[311]:g}", "Q272 = 1 or 2 and Q311 > 0")
        touch, start = self._radii(q[311] * self.scale / 2.0)
        unit = _point(self.path.plane, *((1.0, 0.0) if q[272] == 1 else (0.0, 1.0)), 0.0)
        return [(self.centre + side * start * unit, self.centre + side * touch * unit) for side in (-1.0, 1.0)]

    def _probe(self, points: list[tuple[np.ndarray, np.ndarray]]) -> None:
        """Probe ``points`` [(starting point, touch point)] in turn; between them at Q260 or at the measuring
        height as the cycle says; from the centre (a small hole) without moves between them."""
        path, q = self.path, self.q
        clearance = q[260] * self.scale
        from_centre = bool(np.allclose(points[0][0], self.centre))
        high = not from_centre and (q[301] == 1 or self.number == 409)
        for k, (start, touch) in enumerate(points):
            if k == 0:
                path.pre_position(start, clearance)
            elif high:
                path.axis(clearance)
                self._across(start, clearance)
                path.axis(start[path.plane])
            elif not from_centre:
                self._across(start, start[path.plane])
            path.touch(start, touch, self.where, f"TCH PROBE {self.number} touch point {k + 1}")

    def _across(self, start: np.ndarray, level: float) -> None:
        """To the next starting point at ``level`` [mm]: 412 / 413 on an arc about the centre (Q365=1) or a line;
        410 / 411 at the measuring height paraxially (round the corner), else straight."""
        path, q = self.path, self.q
        target = start.copy()
        target[path.plane] = level
        if self.number in (412, 413) and q[365] != 0:
            pole = self.centre.copy()
            pole[path.plane] = level
            path.arc(pole, target, q[247])
            return
        if self.number in (410, 411) and level == start[path.plane]:
            path.line(path.pos + target - self.centre, path.probe.fmax)  # the corner beside the rectangle
        path.line(target, path.probe.fmax)
