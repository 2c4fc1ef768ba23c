"""Tilted working plane (3+2 machining) on a machine whose table tilts: geometry shared by the readers.

A control that tilts the working plane (Heidenhain ``PLANE``/cycle 19, Fanuc ``G68.2``) turns the
part with the machine's rotary axes so that the tilted plane's tool axis becomes the spindle axis
(machine Z), then runs the program's X, Y, Z in that plane. This module holds what every reader
needs for it:

* :class:`RotaryAxis`, :class:`Kinematics`: the machine (two rotary axes among a, b, c, which one
  carries the other, their pivots and limits; or one tilting axis), part of
  :class:`interpolators.context.MachineContext`;
* the working-plane rotation ``R`` (columns: the tilted X, Y, Z axes in the untilted workpiece
  coordinates) of each definition: :func:`spatial` (PLANE SPATIAL, cycle 19), :func:`projected`,
  :func:`euler` (the Z-X'-Z'' angles Fanuc's G68.2 I J K use too), :func:`vector`, :func:`points`,
  :func:`relative`, and :meth:`Kinematics.axial` (PLANE AXIAL);
* :meth:`Kinematics.solutions` / :meth:`Kinematics.choose`: the rotary-axis angles that make the
  tilted tool axis the spindle axis (both solutions, SEQ/SYM, the limits);
* :meth:`Kinematics.place` and :func:`tilted_frame`: machine coordinates of the part, and the map
  ``machine = Rz(theta) p + datum`` of program coordinates ``p`` in the tilted plane.

Conventions. Angles are in degrees. A rotary axis' angle is the turn of the tool relative to the part,
right-handed about the axis' direction (ISO 841 / DIN 66217: "the positive direction of a rotary
axis A, B, C is that which advances a right-handed screw in +X, +Y, +Z"; a table axis turns the part
the other way, ISO 841's primed axes A', B', C'). With this convention the tilt angles of the HEIDENHAIN
manuals come out for table machines: iTNC 530 user's manual (DIN/ISO, 2010), "The PLANE Function",
example of a machine with tilting table A and rotary table C: ``PLANE SPATIAL SPA+0 SPB+45 SPC+0``
positions A+45 C+90 or A-45 C-90. The part sits on the inner axis, which the outer one carries.

Why the tilted plane stays parallel to the machine's XY plane. At the angles of a solution the
part's rotation into the machine, ``M``, maps the tilted tool axis ``R e_z`` onto the spindle axis:
``M R e_z = e_z``. ``M R`` is then a rotation that keeps ``e_z``, a rotation ``Rz(theta)`` about the
machine's Z. A program point ``p`` of the tilted plane is the part point ``d + R p`` (``d``: the
datum), whose machine position is ``place(d) + M R p = place(d) + Rz(theta) p``: the tilted X and Y
run in the machine's XY plane (turned by ``theta``) and the tilted Z along the machine's Z. Arcs of the
tilted XY plane stay arcs of the machine's XY plane (``tests/interpolators/test_tilted.py`` checks it).

Head-tilting machines turn the tool, not the part; their tilted plane is not parallel to a plane
of the machine, which vcnc's principal-plane arcs cannot follow: :meth:`Kinematics.require_table`
names it as unsupported.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from interpolators.rotary_wrap import within_turn
from vcnc.core.errors import InputError

__all__ = ["RotaryAxis", "Kinematics", "TiltError", "spatial", "projected", "euler", "vector", "points",
           "relative", "rotation_about", "tilted_frame", "Solution"]

_UNIT = {"X": (1.0, 0.0, 0.0), "Y": (0.0, 1.0, 0.0), "Z": (0.0, 0.0, 1.0)}
_DEFAULT_AXIS = {"a": "X", "b": "Y", "c": "Z"}
#: Angles closer than this are the same position [deg]; vectors closer than this are parallel [-].
ANGLE_TOLERANCE = 1e-6
_PARALLEL = 1e-9


class TiltError(ValueError):
    """A tilt the machine cannot take; the reader adds the file, line and column (of the word ``letter``
    when given, else of the block's code)."""

    def __init__(self, message: str, expected: str, letter: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.expected = expected
        self.letter = letter


def rotation_about(direction: Sequence[float], angle_deg: float) -> np.ndarray:
    """Right-handed rotation matrix about the unit vector ``direction`` by ``angle_deg`` [deg]."""
    u = np.asarray(direction, dtype=float)
    u = u / np.linalg.norm(u)
    a = math.radians(angle_deg)
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    return np.eye(3) + math.sin(a) * k + (1.0 - math.cos(a)) * (k @ k)


def _rx(a: float) -> np.ndarray:
    return rotation_about(_UNIT["X"], a)


def _ry(a: float) -> np.ndarray:
    return rotation_about(_UNIT["Y"], a)


def _rz(a: float) -> np.ndarray:
    return rotation_about(_UNIT["Z"], a)


def spatial(spa: float, spb: float, spc: float) -> np.ndarray:
    """Working-plane rotation of ``PLANE SPATIAL SPA SPB SPC`` [deg] (and of cycle 19 with spatial angles).

    iTNC 530 user's manual 340 422, 9.2 "Defining the Machining Plane with Space Angles: PLANE
    SPATIAL", p. 460: "Spatial angles define a machining plane through up to three rotations around
    the fixed machine coordinate system. The sequence of rotations is firmly specified: first around
    the A axis, then B, and then C (the function corresponds to Cycle 19, if the entries in Cycle 19
    are set to space angles)". Rotations about fixed axes in the order A, B, C compose as
    ``Rz(SPC) Ry(SPB) Rx(SPA)``.
    """
    return _rz(spc) @ _ry(spb) @ _rx(spa)


def euler(precession: float, nutation: float, rotation: float) -> np.ndarray:
    """Working-plane rotation of ``PLANE EULER EULPR EULNU EULROT`` [deg]: about Z by the precession, about
    the turned X by the nutation, about the new Z by the rotation (iTNC 530 user's manual, "Defining the
    Machining Plane with Euler Angles: PLANE EULER"; the Z-X'-Z'' angles of Fanuc's G68.2 I J K too):
    ``Rz(EULPR) Rx(EULNU) Rz(EULROT)``."""
    return _rz(precession) @ _rx(nutation) @ _rz(rotation)


def _frame(x_axis: np.ndarray, z_axis: np.ndarray) -> np.ndarray:
    """Rotation with tilted Z along ``z_axis`` and tilted X along ``x_axis`` made square to it."""
    z = z_axis / np.linalg.norm(z_axis)
    x = x_axis - (x_axis @ z) * z
    nx = np.linalg.norm(x)
    if nx < _PARALLEL:
        raise TiltError("the X direction of the plane is parallel to its normal",
                        "a base vector (or points P1, P2) not along the plane's normal")
    x = x / nx
    return np.column_stack([x, np.cross(z, x), z])


def projected(propr: float, promin: float, rot: float) -> np.ndarray:
    """Working-plane rotation of ``PLANE PROJECTED PROPR PROMIN ROT`` [deg].

    iTNC 530 user's manual, "Defining the Machining Plane with Projection Angles: PLANE PROJECTED":
    the plane is given by the angles its traces make in the ZX plane (PROPR, about Y, from X) and in the
    YZ plane (PROMIN, about X, from Y), then turned about its own tool axis by ROT. Our reading: the
    tilted X lies along the ZX trace before ROT.
    """
    a = _ry(propr) @ np.array(_UNIT["X"])
    b = _rx(promin) @ np.array(_UNIT["Y"])
    return _frame(a, np.cross(a, b)) @ _rz(rot)


def vector(base: Sequence[float], normal: Sequence[float]) -> np.ndarray:
    """Working-plane rotation of ``PLANE VECTOR BX BY BZ NX NY NZ``: tilted Z along the normal, tilted X
    along the base vector made square to it (iTNC 530 user's manual, "Defining the Machining Plane with
    Two Vectors: PLANE VECTOR": the TNC normalizes the vectors and computes from them)."""
    n = np.asarray(normal, dtype=float)
    if np.linalg.norm(n) < _PARALLEL:
        raise TiltError("PLANE VECTOR with a zero normal vector", "NX, NY, NZ not all 0")
    return _frame(np.asarray(base, dtype=float), n)


def points(p1: Sequence[float], p2: Sequence[float], p3: Sequence[float]) -> np.ndarray:
    """Working-plane rotation of ``PLANE POINTS`` through three points [mm]: tilted X from P1 to P2, P3 on
    the side of the tilted +Y (iTNC 530 user's manual, "Defining the Machining Plane via Three Points:
    PLANE POINTS": "The connection from Point 1 to Point 2 determines the direction of the tilted main
    axis", the third point the inclination)."""
    a, b, c = (np.asarray(p, dtype=float) for p in (p1, p2, p3))
    n = np.cross(b - a, c - a)
    if np.linalg.norm(n) < _PARALLEL * max(1.0, float(np.linalg.norm(b - a) * np.linalg.norm(c - a))):
        raise TiltError("PLANE POINTS through three points on a line", "three points that span a plane")
    return _frame(b - a, n)


def relative(active: np.ndarray, axis: str, angle: float) -> np.ndarray:
    """``PLANE RELATIV SPA|SPB|SPC``: the active plane turned by ``angle`` [deg] about its own (tilted)
    axis X, Y or Z (iTNC 530 user's manual, "Incremental Tilting: PLANE RELATIVE": "the angle always
    acts in relation to the active input coordinate system")."""
    return np.asarray(active, dtype=float) @ rotation_about(_UNIT[axis.upper()], angle)


@dataclasses.dataclass(frozen=True, kw_only=True)
class RotaryAxis:
    """One rotary axis of a tilting table.

    Attributes
    ----------
    name : {"a", "b", "c"}
        The axis (its words A, B, C and its column of the blocks).
    direction : str
        The machine axis it turns about: ``"X"``, ``"Y"``, ``"Z"``, or ``"-X"`` ... when a positive
        angle turns the tool the other way round relative to the part; default: X for a, Y for b, Z for c.
    pivot : tuple of float
        A point of its axis of rotation [mm, machine coordinates with every rotary axis at 0].
    limits : tuple of float
        Lowest and highest angle [deg].
    """

    name: str
    direction: str = ""
    pivot: tuple[float, float, float] = (0.0, 0.0, 0.0)
    limits: tuple[float, float] = (-360.0, 360.0)

    def __post_init__(self) -> None:
        if self.name not in _DEFAULT_AXIS:
            raise InputError(f"kinematics: rotary axis name must be 'a', 'b' or 'c', got {self.name!r}")
        d = (self.direction or _DEFAULT_AXIS[self.name]).upper()
        if d.lstrip("+-") not in _UNIT or d.count("-") + d.count("+") > 1:
            raise InputError(f"kinematics: axis {self.name} direction must be X, Y, Z, -X, -Y or -Z, "
                             f"got {self.direction!r}")
        object.__setattr__(self, "direction", d.lstrip("+"))
        pivot = tuple(float(v) for v in self.pivot)
        if len(pivot) != 3 or not all(math.isfinite(v) for v in pivot):
            raise InputError(f"kinematics: axis {self.name} pivot must be three finite numbers [mm], "
                             f"got {self.pivot!r}")
        object.__setattr__(self, "pivot", pivot)
        lo, hi = (float(v) for v in self.limits)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise InputError(f"kinematics: axis {self.name} limits must be two finite angles low < high [deg], "
                             f"got {self.limits!r}")
        object.__setattr__(self, "limits", (lo, hi))

    @property
    def unit(self) -> np.ndarray:
        """Unit vector of :attr:`direction` [-]."""
        return _unit_of(self.direction)

    def turn_part(self, angle: float) -> np.ndarray:
        """Rotation of the part in the machine at ``angle`` [deg]: the opposite of the tool's turn (read-only)."""
        return _part_turn(self.direction, angle)

    def within(self, angle: float, near: float | None = None) -> float | None:
        """``angle`` [deg] or a turn of 360 deg from it inside :attr:`limits` (the one in (-180, 180]
        first; with ``near`` [deg], the one nearest it), else None."""
        if near is not None:  # the turns within the limits, the one nearest ``near`` (also from beyond them)
            first = math.ceil((self.limits[0] - ANGLE_TOLERANCE - angle) / 360.0)
            last = math.floor((self.limits[1] + ANGLE_TOLERANCE - angle) / 360.0)
            k = min(max(round((near - angle) / 360.0), first), last)
            fits = [angle + 360.0 * (k + j) for j in (0, -1, 1) if first <= k + j <= last]
            if fits:
                return min(fits, key=lambda c: abs(c - near))
        a = math.remainder(angle, 360.0)
        a = 180.0 if a == -180.0 else a
        for cand in (a, a + 360.0, a - 360.0):
            if self.limits[0] - ANGLE_TOLERANCE <= cand <= self.limits[1] + ANGLE_TOLERANCE:
                return cand
        return None


def _unit_of(direction: str) -> np.ndarray:
    """Unit vector of an axis direction ``"X"``, ``"-Y"``, ... [-]."""
    sign = -1.0 if direction.startswith("-") else 1.0
    return sign * np.array(_UNIT[direction.lstrip("-")])


@functools.lru_cache(maxsize=256)
def _part_turn(direction: str, angle: float) -> np.ndarray:
    """:meth:`RotaryAxis.turn_part` of an axis along ``direction``, kept: a program on positioned rotary axes
    (M128, a tilted plane) turns the part by the same few angles at every block. Read-only, as it is shared."""
    turn = rotation_about(_unit_of(direction), -angle)
    turn.setflags(write=False)
    return turn


@dataclasses.dataclass(frozen=True)
class Solution:
    """Angles of the two rotary axes [deg], outer (the carrying axis) first."""

    outer: float
    inner: float


@dataclasses.dataclass(frozen=True, kw_only=True)
class Kinematics:
    """The rotary axes of a 5-axis (or 4-axis) machine, for the tilted working plane.

    Attributes
    ----------
    kind : {"table", "head"}
        ``"table"``: both rotary axes turn the part (trunnion table); ``"head"``: they turn the tool
        (not supported for a tilted plane: :meth:`require_table`).
    axes : tuple of RotaryAxis
        The two rotary axes: the outer one (nearer the machine's base) first, then the one it carries,
        which carries the part; or one, tilting, axis (a 4-axis machine: its inner angle is always 0).
    """

    kind: str = "table"
    axes: tuple[RotaryAxis, ...]

    def __post_init__(self) -> None:
        if self.kind not in ("table", "head"):
            raise InputError(f"kinematics: kind must be 'table' or 'head', got {self.kind!r}")
        if len(self.axes) not in (1, 2) or not all(isinstance(a, RotaryAxis) for a in self.axes):
            raise InputError("kinematics: axes must be two rotary axes (the outer one first) or one")
        outer, inner = self.axes[0], self.axes[-1]
        if abs(float(outer.unit[2])) > _PARALLEL:
            raise InputError(f"kinematics: the outer axis {outer.name} turns about the spindle axis Z; it cannot "
                             "tilt the part (the outer axis must turn about X or Y)")
        if len(self.axes) == 1:
            return
        if outer.name == inner.name:
            raise InputError(f"kinematics: the two rotary axes are both {outer.name!r}")
        if abs(float(outer.unit @ inner.unit)) > _PARALLEL:
            raise InputError(f"kinematics: axes {outer.name} ({outer.direction}) and {inner.name} "
                             f"({inner.direction}) must turn about perpendicular machine axes")

    @property
    def names(self) -> tuple[str, ...]:
        """The axis names, outer first."""
        return tuple(a.name for a in self.axes)

    def positions(self, angles: Solution) -> dict[str, float]:
        """The axes' positions [deg] by name (the inner angle only when there is an inner axis)."""
        return dict(zip(self.names, (angles.outer, angles.inner)[:len(self.axes)], strict=True))

    def solution_at(self, extra: Sequence[float]) -> Solution:
        """The axes' present positions as a :class:`Solution` (inner 0 without an inner axis), read from
        ``extra``: the positions of a, b, c [deg] first (the extra-axis columns of a block)."""
        at = [float(extra["abc".index(name)]) for name in self.names]
        return Solution(outer=at[0], inner=at[-1] if len(at) == 2 else 0.0)

    def _turns(self, angles: Solution):
        return zip(self.axes, (angles.outer, angles.inner)[:len(self.axes)], strict=True)

    def require_table(self) -> None:
        """Raise :class:`TiltError` unless both rotary axes turn the part."""
        if self.kind != "table":
            raise TiltError("a tilted working plane on a machine whose head tilts is not supported (its arcs are "
                            "not in a principal plane of the machine)",
                            "kinematics kind = 'table' (a tilting table)")

    def rotation(self, angles: Solution) -> np.ndarray:
        """Rotation of the part into the machine at ``angles`` [deg]: ``M`` of the module's notes."""
        m = np.eye(3)
        for axis, angle in self._turns(angles):
            m = m @ axis.turn_part(angle)
        return m

    def place(self, point: Sequence[float], angles: Solution) -> np.ndarray:
        """Machine position [mm] at ``angles`` of the part point that is at ``point`` [mm, machine] with
        every rotary axis at 0: turned about the inner axis' pivot, then about the outer's."""
        q = np.asarray(point, dtype=float)
        for axis, angle in reversed(list(self._turns(angles))):
            q = np.asarray(axis.pivot) + axis.turn_part(angle) @ (q - np.asarray(axis.pivot))
        return q

    def unplace(self, position: Sequence[float], angles: Solution) -> np.ndarray:
        """The inverse of :meth:`place`: where the part point at machine ``position`` [mm] at ``angles`` [deg]
        is with every rotary axis at 0 [mm]."""
        q = np.asarray(position, dtype=float)
        for axis, angle in self._turns(angles):
            q = np.asarray(axis.pivot) + axis.turn_part(angle).T @ (q - np.asarray(axis.pivot))
        return q

    def axial(self, angles: Solution) -> np.ndarray:
        """Working-plane rotation of ``PLANE AXIAL`` (the axes' angles given): the plane whose tool axis
        the axes at ``angles`` make the spindle axis, its X turned with it (``M^T``)."""
        return self.rotation(angles).T

    def solutions(self, plane: np.ndarray) -> list[Solution]:
        """Angles [deg] that make the tool axis ``plane @ e_z`` of the rotation ``plane`` the spindle axis.

        Two solutions in general (the outer axis' angle of opposite signs, the inner's 180 deg apart),
        one when the tilted tool axis lies in the plane of both axes, none when the axes cannot reach it;
        angles in (-180, 180]. When the tilted tool axis is the inner axis' own, any inner angle does:
        the inner angle is NaN (:meth:`choose` keeps the axis where it is; the plane's turn about the tool
        axis is then a turn of the coordinates, iTNC 530's COORD ROT; TNC7 user's manual 81762x-17, "free rotary
        axis": "the rotary axis has no effect on the tool angle of inclination because the rotary axis and the tool
        axis are parallel in the tilting situation"). The manual states no tolerance: parallel here is within
        1e-9 rad, and so is one solution (a tool axis 5e-5 deg off the inner axis has two, each with its own inner
        angle; before session 38 it was one, with an inner angle of 0). Limits are not applied here. A single
        axis reaches only the tool axes square to it: one solution (inner angle 0), or none.
        """
        outer, inner = self.axes[0], self.axes[-1]
        uo, ui = outer.unit, inner.unit
        n = np.asarray(plane, dtype=float)[:, 2]
        ez = np.array(_UNIT["Z"])
        if len(self.axes) == 1:
            if abs(float(uo @ n) - float(uo @ ez)) > 1e-9:
                return []
            return [Solution(outer=_wrap(_angle_between(ez, n, uo)), inner=0.0)]
        # v = the tool axis after the outer turn: uo.v = uo.ez, ui.v = ui.n (Paden-Kahan subproblem 2)
        # rest = 1 - alpha^2 - beta^2 from the tool axis' part square to the inner axis (|side|^2 = 1 - beta^2 without
        # the cancellation of 1 - beta^2 near the pole, where beta^2 = 1 - 1e-13 kept only 3 digits of rest)
        alpha, beta = float(uo @ ez), float(ui @ n)
        side = n - beta * ui
        rest = float(side @ side) - alpha * alpha
        if rest < -1e-9:
            return []
        # one solution when g is below the same _PARALLEL that makes the tool axis the inner axis' own (then the
        # inner angle is free): with alpha = 0, g = |side|, so the two thresholds agree (a tilt of 5e-5 deg is two
        # solutions of an inner angle, not one of a free angle)
        g = math.sqrt(max(rest, 0.0))
        gammas = (0.0,) if g < _PARALLEL else (g, -g)
        out = []
        for g in gammas:
            v = alpha * uo + beta * ui + g * np.cross(uo, ui)
            to = _angle_between(ez, v, uo)
            ti = math.nan if np.linalg.norm(side) < _PARALLEL else _angle_between(v, n, ui)
            out.append(Solution(outer=_wrap(to), inner=_wrap(ti)))
        return out

    def choose(self, plane: np.ndarray, current: Solution, *, sequence: int = 0, table_rot: bool = False,
               nearest: bool = False, turns: Mapping[str, Callable[[float], float]] | None = None,
               order: str = "sum") -> Solution:
        """The solution the control takes: within the limits, the outer (master) axis' angle of the sign
        ``sequence`` (+1 SEQ+/SYM+, -1 SEQ-/SYM-), else (0) the one nearest ``current`` [deg] (the sum of
        both axes' travel; sums equal within :data:`ANGLE_TOLERANCE` tie, and a tie goes to the positive master
        angle). When the tilted tool axis is the
        inner axis' own, the inner axis stays (COORD ROT) or, with ``table_rot``, turns so that the tilted X
        runs along the machine's X (iTNC 530 user's manual, "Selecting the type of transformation": "TABLE
        ROT specifies that the PLANE function should position the rotary table to the defined tilting
        angle").

        iTNC 530 user's manual (DIN/ISO, 2010), "Selection of alternate tilting possibilities": SEQ+
        positions the master axis so that it assumes a positive angle, SEQ- a negative one; without SEQ
        the TNC selects the solution closest to the current position (TNC7 user's manual 81762x-17, "Tilting
        solution": "Two possible solutions: Based on the current position of the rotary axes, choose the
        possible solution with the shortest path"); its example (tilting table A,
        rotary table C, PLANE SPATIAL SPB+45: A+45 C+90 from A+0 C+0, A-45 C-90 from A+0 C-105, an error
        for SEQ+ with -90 < A < +10) is what this returns. The master axis is here the outer axis, the
        one that tilts; SYM (TNC 640: the side of the master axis' symmetry point, at 0) is read as SEQ.
        With ``nearest`` each axis takes the turn of 360 deg of its angle nearest its ``current`` one (a tool
        direction under TCP: :func:`interpolators.tcp.tool_vector_extra`), else the one in (-180, 180] first.

        An axis named in ``turns`` wraps at 360 deg (:mod:`interpolators.rotary_wrap`): its angle is stated as the
        axis shows it, in [0, 360) (what the caller then turns it to, as an absolute word by the machine's rule),
        ``turns[name](angle)`` is the turn [deg] the axis makes to reach it from where it is, and its travel is
        that turn's size, not the distance of two unwrapped angles (C shown at 280, a plane needing B+30 C+90 or
        B-30 C-90: C270 is 10 deg away under the shorter-way rule, C90 190 deg). Its limits hold modulo 360 deg
        (some turn of the angle within them), and SEQ judges its angle in (-180, 180].

        ``order="master"`` ranks them as FANUC's tool axis direction control (G53.1) does (FANUC Series 16i/18i-MB
        operator's manual, "Angle of rotation axis", output judgement conditions of a table or tool rotation type
        machine): the smallest "master axis (first rotation axis) moving angle", then the slave's, then the master angle
        nearer 0 deg ("multiple of 360 degrees"), then the slave's; travels equal within :data:`ANGLE_TOLERANCE`
        (a tie left goes to the positive master angle, as above).
        FANUC counts every turn of 360 deg of a "computed angle" as a candidate: the caller asks for ``nearest`` too.

        Raises
        ------
        TiltError
            No solution within the limits (with the sign asked for).
        """
        if order not in ("sum", "master"):
            raise ValueError(f"order must be 'sum' or 'master', got {order!r}")
        turns = turns or {}
        now = (current.outer, current.inner)
        near = now if nearest else (None, None)
        found = []  # (travel, -master angle, solution)
        for s in self.solutions(plane):
            angles = [s.outer]
            if len(self.axes) == 2:
                free = self._square_inner(plane, s.outer) if table_rot else current.inner
                angles.append(free if math.isnan(s.inner) else s.inner)
            placed = [_place(axis, a, n, c, turns.get(axis.name))
                      for axis, a, n, c in zip(self.axes, angles, near, now, strict=False)]
            if any(p is None for p in placed):
                continue
            master = s.outer if self.axes[0].name in turns else placed[0][0]
            if sequence and master * sequence < -ANGLE_TOLERANCE:
                continue
            solution = Solution(outer=placed[0][0], inner=placed[1][0] if len(placed) == 2 else 0.0)
            if order == "sum":
                found.append((sum(p[1] for p in placed), -master, solution))
            else:
                found.append((*(round(p[1] / ANGLE_TOLERANCE) for p in placed),
                              *(round(abs(math.remainder(p[0], 360.0)) / ANGLE_TOLERANCE) for p in placed), -master,
                              solution))
        if not found:
            outer = self.axes[0]
            sign = {1: " with a positive", -1: " with a negative"}.get(sequence, "")
            limits = ", ".join(f"{a.name.upper()} {a.limits[0]:g}..{a.limits[1]:g}" for a in self.axes)
            raise TiltError(f"the rotary axes {', '.join(n.upper() for n in self.names)} cannot tilt the part to "
                            f"this plane{sign} {outer.name.upper()} within their limits {limits} deg",
                            "a working plane the machine's rotary axes reach")
        if order == "sum":  # travels equal within ANGLE_TOLERANCE tie (99.99999999999999 against 100 deg)
            least = min(f[0] for f in found)
            found = [(0, *f[1:]) for f in found if f[0] <= least + ANGLE_TOLERANCE]
        return min(found, key=lambda f: f[:-1])[-1]

    def _square_inner(self, plane: np.ndarray, outer: float) -> float:
        """The inner angle [deg] that turns the tilted X onto the machine's X, the tool axis being the inner's."""
        def theta(inner: float) -> float:
            turn = self.rotation(Solution(outer=outer, inner=inner)) @ plane
            return math.degrees(math.atan2(turn[1, 0], turn[0, 0]))

        t0 = theta(0.0)
        return min((t0, -t0), key=lambda a: abs(math.remainder(theta(a), 360.0)))


def _wrap(angle: float) -> float:
    if math.isnan(angle):
        return angle
    a = math.remainder(angle, 360.0)
    a = 0.0 if abs(a) < 1e-12 else a
    return 180.0 if abs(a + 180.0) < 1e-12 else a


def _angle_between(a: np.ndarray, b: np.ndarray, axis: np.ndarray) -> float:
    """Angle [deg] of the right-handed turn about ``axis`` that takes ``a`` to ``b`` (their parts square to it)."""
    pa = a - (a @ axis) * axis
    pb = b - (b @ axis) * axis
    return math.degrees(math.atan2(float(axis @ np.cross(pa, pb)), float(pa @ pb)))


def _place(axis: RotaryAxis, angle: float, near: float | None, now: float,
           turn: Callable[[float], float] | None) -> tuple[float, float] | None:
    """The angle [deg] ``axis`` takes for the solution's ``angle`` and its travel [deg] from ``now``, or None when its
    limits forbid it: :meth:`RotaryAxis.within` (nearest ``near`` when given), or on a wrapping axis (``turn``, the
    turn it makes to an angle it shows) the angle reduced to [0, 360) and the size of that turn
    (:meth:`Kinematics.choose`)."""
    if turn is not None:
        if axis.within(angle) is None:
            return None
        shown = within_turn(angle)
        return shown, abs(turn(shown))
    placed = axis.within(angle, near)
    return None if placed is None else (placed, abs(placed - now))


def tilted_frame(kinematics: Kinematics, plane: np.ndarray, angles: Solution,
                 datum: Sequence[float]) -> tuple[float, np.ndarray]:
    """The map of the tilted plane's program coordinates to the machine at ``angles``.

    Parameters
    ----------
    kinematics : Kinematics
    plane : ndarray (3, 3)
        Working-plane rotation (columns: tilted X, Y, Z in the untilted workpiece coordinates).
    angles : Solution
        Positions of the rotary axes [deg], a solution for ``plane``.
    datum : sequence of float
        The tilted plane's zero with every rotary axis at 0 [mm, machine]: the preset plus the datum
        shift active when the plane was tilted.

    Returns
    -------
    theta : float
        The turn of the tilted X about the machine's Z [deg]: ``machine = Rz(theta) p + origin``.
    origin : ndarray (3,)
        Machine position of the tilted zero at ``angles`` [mm] (without tool length).

    Raises
    ------
    TiltError
        ``angles`` do not bring the tilted tool axis onto the spindle axis.
    """
    turn = kinematics.rotation(angles) @ np.asarray(plane, dtype=float)
    if abs(turn[2, 2] - 1.0) > 1e-9:
        raise TiltError("the rotary axes' positions do not make the tilted tool axis the spindle axis",
                        "the rotary axes at the plane's angles")
    theta = math.degrees(math.atan2(turn[1, 0], turn[0, 0]))
    return theta, kinematics.place(datum, angles)
