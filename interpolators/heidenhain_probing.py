"""Touch probe cycles of Heidenhain programs (``TCH PROBE 4xx``), run on the nominal workpiece.

A virtual CNC has no workpiece to touch; as CAM simulators do, vcnc runs the cycles on the workpiece the
cycle's data describe: every touch point lies where the nominal centre, diameter or coordinate puts the
surface, so the measured values are the nominal ones, the deviations are 0, and the datum a cycle sets is
the one the nominal workpiece gives. The probe's moves become ordinary blocks (cycle time, path).

Sources: HEIDENHAIN TNC 320 user's manual "Cycle programming" (340 55x-04), chapter "Touch Probe Cycles:
Automatic Datum Setting": 15.6 DATUM FROM INSIDE OF CIRCLE (cycle 412), 15.7 DATUM FROM OUTSIDE OF CIRCLE
(cycle 413), DATUM IN TOUCH PROBE AXIS (cycle 417), and "Executing touch probe cycles"; iTNC 530 cycle
programming manual, 15.6 (cycle 412: the parameters Q261, Q320, Q260, Q301, Q305, Q331, Q332, Q303, and
"If you enter Q305=0, the TNC automatically sets the display so that the new datum is at the center").

Cycle runs (measured = nominal):

* positioning logic ("Executing touch probe cycles"): below the clearance height Q260 the probe first rises
  to it, then moves in the working plane to the first starting point; above it, it moves in the plane at its
  height; then it goes down to the starting point's height. These moves run at the FMAX column's feed;
* 417: the starting point is touch point 1 (Q263, Q264) the set-up clearance (Q320 + SET_UP) above Q294;
  the probe moves down its own axis at the probing feed F until its tip touches Q294, returns to the
  starting point, and rises to Q260. Result: Q160 = Q294. The datum: Q294 becomes Q333;
* 412 / 413: Q423 (4, or 3) touch points at the angles Q325 + k Q247 about the centre (Q321, Q322) on the
  circle of diameter Q262, at the measuring height Q261. Each starting point lies the set-up clearance inside
  (412) or outside (413) the point where the stylus tip (its radius: :attr:`TouchProbe.tip_radius`) touches
  the circle; the probe probes radially at F and returns to the starting point. Between points: at the
  measuring height (Q301=0) or up to Q260, across and down again (Q301=1), on an arc about the centre
  (Q365=0) or a straight line (Q365=1), as programmed (a line at the measuring height between two points of
  413 may cross the stud: vcnc has no workpiece to collide with). At the end the probe rises to Q260.
  Results: Q151, Q152 = the centre, Q153 = the diameter. The datum: the centre becomes (Q331, Q332). 412 in
  a hole too small for the starting points (radius - tip - clearance < 0): every touch from the centre,
  without clearance-height moves between them (iTNC 530 manual, cycle 412 note); a tip wider than the hole
  is an error. Q381=1 also probes the touch probe axis at (Q382, Q383) down to Q384 as 417 does, which
  becomes Q333.

Our reading, where the manuals leave details open: the move back after a touch goes to the starting point at
the FMAX column's feed; the datum is set as :class:`ProbeRun` ``datum`` says (the reader applies it: Q305=0
the active preset, Q305=n with Q303=1 row n of the preset table, with Q303=0 row n of the datum table, which
vcnc does not model: noted); a touch point farther from its starting point than the DIST column is an error
(the TNC reports it unreachable).

Not modelled (an error naming the cycle): the other probe cycles (0, 1, 400-405, 408-411, 414-416, 418-431,
444, 45x, 46x, 14xx, ...), and the tool touch probe cycles (TT: 30-33, 480-484: the tool setter's position is
not known).
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
PROBE_CYCLES: tuple[int, ...] = (412, 413, 417)

#: Tool measurement with the tool touch probe TT (TNC 320 / TNC 640 touch probe cycles manual, "Touch probe
#: cycles: automatic tool measurement").
_TOOL_CYCLES = (30, 31, 32, 33, 480, 481, 482, 483, 484)

#: The Q parameters a definition must give (TNC 320 cycle manual, the cycles' parameter lists); the others take
#: the defaults of :data:`_DEFAULTS`.
_REQUIRED = {417: (263, 264, 294, 320, 260), 412: (321, 322, 262, 325, 247, 261, 320, 260),
             413: (321, 322, 262, 325, 247, 261, 320, 260)}
#: Defaults of optional parameters (our reading: the TNC's dialog values): Q301=1 clearance height between
#: points, Q305=0 the active datum, Q303=1 the preset table, Q423=4 points, Q365=1 straight lines.
_DEFAULTS = {301: 1.0, 305: 0.0, 331: 0.0, 332: 0.0, 303: 1.0, 333: 0.0, 381: 0.0, 423: 4.0, 365: 1.0}


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
    coordinates ``datum_to`` [mm], stored as ``q305`` (0: the active datum) in the table ``q303`` names."""

    moves: list[ProbeMove]
    results: dict[int, float]
    datum_from: np.ndarray
    datum_to: np.ndarray
    q305: int
    q303: int


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


def refuse_probe(number: int, where: Where, column: int) -> None:
    """The error of a probe cycle vcnc does not run."""
    if number in _TOOL_CYCLES:
        where.fail(f"TCH PROBE {number} (tool measurement with the tool touch probe TT) is not modelled: the tool "
                   "setter's position is not known", column=column, text=where.text,
                   expected=f"TCH PROBE {', '.join(map(str, PROBE_CYCLES))} (workpiece probing)")
    where.fail(f"TCH PROBE {number} is not modelled (vcnc runs the touch probe cycles "
               f"{', '.join(map(str, PROBE_CYCLES))} on the nominal workpiece)", column=column, text=where.text,
               expected=f"TCH PROBE {', '.join(map(str, PROBE_CYCLES))}")


def probe_run(number: int, q: dict[int, float], *, here: np.ndarray, plane: int, tip_radius: float,
              scale: float, probe: TouchProbe, where: Where, column: int) -> ProbeRun:
    """The run of touch probe cycle ``number`` with its parameters ``q`` [program units] from the probe's
    program position ``here`` [mm] (its tool point), the touch probe axis ``plane`` (the tool axis, 0 1 2),
    the stylus tip's radius ``tip_radius`` [mm], ``scale`` mm per program unit."""
    missing = [n for n in _REQUIRED[number] if n not in q]
    if missing:
        where.fail(f"TCH PROBE {number} lacks {', '.join(f'Q{n}' for n in missing)}", column=column,
                   text=where.text, expected=f"Q{' Q'.join(map(str, _REQUIRED[number]))} in the cycle definition")
    q = {**_DEFAULTS, **q}
    path = _Path(here, plane, probe)
    clearance = q[260] * scale
    datum_from, datum_to = np.full(3, np.nan), np.full(3, np.nan)
    if number == 417:
        results = {160: q[294]}
        _axis_touch(path, (q[263], q[264], q[294]), q[320], scale, clearance, where, number)
        datum_from[plane], datum_to[plane] = q[294] * scale, q[333] * scale
    else:
        results = {151: q[321], 152: q[322], 153: q[262]}
        _circle(path, number, q, scale, tip_radius, clearance, where)
        a, b = PLANE_AXES[plane]
        datum_from[[a, b]] = q[321] * scale, q[322] * scale
        datum_to[[a, b]] = q[331] * scale, q[332] * scale
        if q[381] == 1:
            for n in (382, 383, 384):
                if n not in q:
                    where.fail(f"TCH PROBE {number} with Q381=1 lacks Q{n}", column=column, text=where.text,
                               expected="Q382, Q383, Q384: the touch point in the touch probe axis")
            _axis_touch(path, (q[382], q[383], q[384]), q[320], scale, clearance, where, number)
            datum_from[plane], datum_to[plane] = q[384] * scale, q[333] * scale
    path.axis(clearance)
    return ProbeRun(path.moves, results, datum_from, datum_to, _whole(q, 305, where, column),
                    _whole(q, 303, where, column))


def _whole(q: dict[int, float], n: int, where: Where, column: int) -> int:
    if q[n] != int(q[n]) or (n == 305 and q[n] < 0):
        where.fail(f"Q{n}={q[n]:g} is not a whole number{' >= 0' if n == 305 else ''}", column=column,
                   text=where.text, expected=f"Q{n} = a row number" if n == 305 else "Q303 = -1, 0 or 1")
    return int(q[n])


def _axis_touch(path: _Path, point: tuple[float, float, float], q320: float, scale: float, clearance: float,
                where: Where, number: int) -> None:
    """Probing down the touch probe axis to ``point`` (reference axis, minor axis, probe axis) [program units]:
    cycle 417's run, and the probe-axis touch of Q381=1."""
    a, b = PLANE_AXES[path.plane]
    touch = np.zeros(3)
    touch[[a, b, path.plane]] = np.array(point) * scale
    start = touch.copy()
    start[path.plane] += q320 * scale + path.probe.set_up
    path.pre_position(start, clearance)
    path.touch(start, touch, where, f"TCH PROBE {number}")


def _circle(path: _Path, number: int, q: dict[int, float], scale: float, tip: float, clearance: float,
            where: Where) -> None:
    """The touch points of cycles 412 (inside: probing outward) and 413 (outside: inward)."""
    count = int(q[423])
    if count not in (3, 4) or q[423] != count:
        where.fail(f"TCH PROBE {number}: Q423={q[423]:g} measuring points", column=1, text=where.text,
                   expected="Q423 = 3 or 4")
    if q[262] <= 0 or q[247] == 0:
        where.fail(f"TCH PROBE {number}: nominal diameter Q262={q[262]:g}, stepping angle Q247={q[247]:g}",
                   column=1, text=where.text, expected="Q262 > 0 and Q247 != 0")
    a, b = PLANE_AXES[path.plane]
    centre = np.zeros(3)
    centre[[a, b]] = q[321] * scale, q[322] * scale
    centre[path.plane] = q[261] * scale
    radius, gap = q[262] * scale / 2.0, q[320] * scale + path.probe.set_up
    side = -1.0 if number == 412 else 1.0
    touch_r = radius + side * tip
    if touch_r <= 0:
        where.fail(f"TCH PROBE 412: the stylus tip (radius {tip:g} mm) does not fit the hole of diameter "
                   f"{2 * radius:g} mm", column=1, text=where.text, expected="a nominal diameter Q262 above the tip's")
    start_r = max(touch_r + side * gap, 0.0)
    from_centre = start_r == 0.0  # 412 in a small hole: every touch from the centre
    between_high = q[301] == 1 and not from_centre
    for k in range(count):
        angle = math.radians(q[325] + k * q[247])
        u = np.zeros(3)
        u[[a, b]] = math.cos(angle), math.sin(angle)
        start, touch = centre + start_r * u, centre + touch_r * u
        if k == 0:
            path.pre_position(start, clearance)
        elif between_high:
            path.axis(clearance)
            _across(path, centre, start, q, clearance)
            path.axis(start[path.plane])
        elif not from_centre:
            _across(path, centre, start, q, start[path.plane])
        path.touch(start, touch, where, f"TCH PROBE {number} touch point {k + 1}")


def _across(path: _Path, centre: np.ndarray, start: np.ndarray, q: dict[int, float], level: float) -> None:
    """To the next starting point at ``level`` [mm]: an arc about the centre (Q365=0) or a line (Q365=1)."""
    target = start.copy()
    target[path.plane] = level
    if q[365] == 0:
        pole = centre.copy()
        pole[path.plane] = level
        path.arc(pole, target, q[247])
    else:
        path.line(target, path.probe.fmax)
