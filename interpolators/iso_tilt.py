"""Fanuc G68.2 tilted working plane and G53.1 tool axis direction control on a tilting table.

``G68.2 X Y Z I J K`` defines a feature coordinate system whose origin is X Y Z (in the workpiece
coordinate system) and whose axes are turned by the Euler angles I (about Z), J (about the turned X)
and K (about the new Z) [deg]; ``G53.1`` then turns the rotary axes so that the tool is square to that
plane (the linear axes stay), and ``G69`` cancels it. Sources: FANUC Series 30i/300i/300is-MODEL A
Descriptions B-63942EN/02, 5.44 "Tilted working plane command" (cncmanuals.com): "A feature coordinate
system is defined on a workpiece coordinate system", "G68.2 X x0 Y y0 Z z0 Iα Jβ Kγ ; Feature coordinate
system setting ... X, Y, Z : Feature coordinate system origin; I, J, K : Euler's angle for determining the
orientation of the feature coordinate system"; FANUC Series 30i/31i additional manual B-79976E,
"Specifying tilted working plane based on the tool axis direction" (G68.3): "When G68.3 is specified in a
block, the coordinate system for programming is changed to a feature coordinate system. All commands after
the block are regarded as commands in the feature coordinate system until G69 is specified"; cnc.wiki,
"G68.2 Tilted Working Plane": "Rotary axes must be manually aligned via G53.1 or automatic cycles; all tool
and cutter radius compensations must be strictly canceled before activation". The Euler order Z-X'-Z'' of
I J K is not in a manual found here (it is the one the CAM posts write). A program may position the rotary
axes itself (``G0 B.. C..``) instead of G53.1; vcnc runs the plane's coordinates at the positions G53.1
would take (not checked). The plane lives in the rotation of :class:`interpolators.iso_transforms.Frame`,
so that G69 cancels it as it cancels G68. The geometry is :mod:`interpolators.tilted`'s, as the Heidenhain
reader's PLANE.

The P forms (Mazak VORTEX i-series manual, serial 294060, 2013, easymanua.ls):

* ``G68.2 P0 X Y Z I J K`` is the Euler form above: Supplement 5-53, "B. Inclined-plane machining",
  "G68.2 P0 Xx Yy Zz I J K (Setting with Eulerian angles)".
* ``G68.2 P1 Q X Y Z I J K``, roll, pitch and yaw: 4-25, "G68.2P1 Setting with roll, pitch, and yaw
  angles": "x, y, z: Coordinates of the origin of feature coordinate system. To be specified with its
  absolute values in the currently active workpiece coordinate system", "q: Order of rotations", "I: Angle
  of rotation around the X-axis [Roll angle]", J around the Y-axis [Pitch angle], K around the Z-axis [Yaw
  angle], "(Setting range: -360° to 360°.)", "The designation of I, J, or K can be omitted when the argument
  is zero (0: no rotation around the axis concerned)". The sense of the turn is our reading: the one the same
  manual gives its G68 (Supplement 5-53, "A positive value of angle refers to the left turn when seen from
  the positive side of the rotational axis"), right-handed as the Euler angles. What the page leaves to its
  figure, not readable as text, is how Q's digits name the axes and whether the second and third turns are
  about the workpiece's fixed axes or the turned ones; the public implementations disagree (LinuxCNC's
  xyzacb-trsrn sim remap composes Q123 as Rx(I) Ry(J) Rz(K), turned axes; the LinuxCNC multiaxis pull request
  4374 tests Ry(J) Rx(I), fixed axes). With a single non-zero angle neither matters (one turn about X, Y or
  Z), and vcnc runs it (Q, when given, one of the orders 123 ... 321, our reading of the three axes' digits);
  two or more non-zero angles are refused, as is a P1 plane with an angle beyond +-360 deg.

Not read here: ``P2`` three points, ``P3`` two vectors, ``P4`` projection angles (no manual text found on
which point or vector gives the origin, X and the +Z side: refused by name; the one public implementation, the
LinuxCNC tilted-work-plane sim remap, configs/sim/axis/vismach/5axis/table-rotary_spindle-rotary-nutating
python/remap.py, builds P2 over four blocks Q0-Q3 but contradicts itself: its comment makes point 1 the origin,
its code takes Q0's X Y Z; its P3 takes X from the I J K of Q0 less the origin; it has no P4), G68.3/G68.4, and
a work offset or G92 changed under G68.2 (not modelled: the plane's zero then moves by the change, along the machine's
axes).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping

import numpy as np

from interpolators.context import MachineContext
from interpolators.iso_transforms import Rotation
from interpolators.tilted import TiltError, euler, spatial, tilted_frame

__all__ = ["TiltedRotation", "TiltError", "g68_2_plane", "g68_2_rotation", "PLANE_WORDS"]

#: The words each read G68.2 form takes, by P (none: P0).
PLANE_WORDS = {0: "XYZIJKP", 1: "XYZIJKPQ"}
#: The forms refused by name, by P.
_UNREAD = {2: "three points", 3: "two vectors", 4: "projection angles"}
#: Q of G68.2 P1: the orders of the three turns (our reading: the digits 1, 2, 3 name X, Y, Z).
_ORDERS = (123, 132, 213, 231, 312, 321)


@dataclasses.dataclass(frozen=True, kw_only=True)
class TiltedRotation(Rotation):
    """The G68.2 plane on the tilting table: ``untransformed = Rz(angle) p + shift`` (a turn about the
    machine's Z, the tilted tool axis, then a shift).

    Attributes
    ----------
    shift : tuple of float
        Where the plane's zero lies from the work zero once the table is tilted [mm, machine axes].
    positions : dict of str to float
        The rotary axes' positions the plane needs, by axis name (``"b"``) [deg]: where G53.1 turns them.
    """

    shift: tuple[float, float, float] = (0.0, 0.0, 0.0)
    positions: dict[str, float] = dataclasses.field(default_factory=dict)

    def forward(self, point: np.ndarray) -> np.ndarray:
        """Untransformed program coordinates [mm] of a point of the tilted plane."""
        return self._turn(point, self.angle) + np.asarray(self.shift)

    def inverse(self, point: np.ndarray) -> np.ndarray:
        """Tilted-plane coordinates [mm] of a point in untransformed program coordinates."""
        return self._turn(np.asarray(point, dtype=float) - np.asarray(self.shift), -self.angle)


def g68_2_rotation(words: dict[str, float], *, context: MachineContext, work_zero: np.ndarray, extra: np.ndarray,
                   scale: float, turns: Mapping[str, Callable[[float], float]] | None = None) -> TiltedRotation:
    """The plane a ``G68.2 [P0|P1 Q] X Y Z I J K`` block defines.

    Parameters
    ----------
    words : dict
        The block's words (X, Y, Z [program units]; I, J, K [deg]; P, Q).
    context : MachineContext
        Its ``kinematics`` (a tilting table) solves the rotary axes (the solution nearest ``extra``).
    work_zero : ndarray (3,)
        The work zero with every rotary axis at 0 [mm, machine]: work offset plus G92 offset.
    extra : ndarray (6,)
        Positions of a, b, c [deg] (and u, v, w) now.
    scale : float
        mm per program unit.
    turns : mapping of str to callable, optional
        For each rotary axis that wraps at 360 deg, the turn [deg] G53.1 makes it take to a machine angle (the
        solutions are weighed by it, and such an axis' position is the angle it shows, in [0, 360):
        :meth:`interpolators.tilted.Kinematics.choose`).

    Raises
    ------
    TiltError
        No kinematics, a head-tilting machine, a form :func:`g68_2_plane` refuses, or a plane the rotary axes
        cannot reach.

    Notes
    -----
    Of the solutions, the one FANUC's G53.1 takes (FANUC Series 16i/18i-MB operator's manual, "Angle of rotation
    axis": "When tool axis direction control (G53.1) has been performed, more than two pairs of 'computed angles' of
    the rotation axes usually exist"; the output angles are the pair whose master (first rotation) axis' moving
    angle is smallest, then the slave's, then the master angle nearest 0 deg, a multiple of 360 deg, then the
    slave's): :meth:`interpolators.tilted.Kinematics.choose` ``order="master"``, each axis at the turn of 360 deg of
    its angle nearest its position within its limits (``nearest``). The master axis is the outer, tilting one (our
    reading of "first rotation axis" on a table-rotation machine). Before session 38 the sum of both axes' travels
    decided, each angle in (-180, 180] first (A5 C-170 to a plane of A+-30 C+-90: A-30 C-90, where FANUC's master
    rule gives A+30 C-270).
    """
    plane = g68_2_plane(words)
    kin = context.kinematics
    if kin is None:
        raise TiltError("G68.2 tilted working plane needs the machine's kinematics",
                        "a machine with [program.kinematics] (vcnc machines --show: the rotary axes that tilt the "
                        "part)")
    kin.require_table()
    angles = kin.choose(plane, kin.solution_at(extra), nearest=True, turns=turns, order="master")
    origin = np.array([words.get(a, 0.0) * scale for a in "XYZ"])
    theta, datum = tilted_frame(kin, plane, angles, np.asarray(work_zero, dtype=float) + origin)
    shift = datum - np.asarray(work_zero, dtype=float)
    if not all(math.isfinite(v) for v in shift):
        raise TiltError("G68.2: the plane's zero is not a finite point", "finite X, Y, Z")
    return TiltedRotation(plane=2, centre=(0.0, 0.0, 0.0), angle=theta, shift=tuple(float(v) for v in shift),
                          positions=kin.positions(angles))


def g68_2_plane(words: dict[str, float]) -> np.ndarray:
    """Working-plane rotation (columns: the feature coordinate system's X, Y, Z in the workpiece
    coordinates) of a G68.2 block's words: P0 or no P, the Euler angles I J K (:func:`interpolators.tilted.euler`);
    P1, one roll (I, about X), pitch (J, about Y) or yaw (K, about Z) angle [deg] (:func:`interpolators.tilted.spatial`
    with the other two 0; the module's docstring says why only one).

    Raises
    ------
    TiltError
        A P form not read (P2-P4 named), a P1 Q that is no order of X, Y, Z, a P1 angle beyond +-360 deg, or
        more than one non-zero P1 angle; ``letter`` names the word at fault.
    """
    p = words.get("P", 0.0)
    angles = [words.get(a, 0.0) for a in "IJK"]
    if p == 0:
        return euler(*angles)
    if p in _UNREAD:
        raise TiltError(f"G68.2 P{p:g} ({_UNREAD[int(p)]}): not supported (no manual text found on which of its "
                        "points or vectors give the origin, the X axis and the +Z side)",
                        "G68.2 X Y Z I J K (Euler angles) or G68.2 P1 with one roll, pitch or yaw angle", "P")
    if p != 1:
        raise TiltError(f"G68.2 P{p:g}: no such definition of the tilted working plane",
                        "P0 (Euler angles) or P1 (roll, pitch, yaw)", "P")
    if "Q" in words and words["Q"] not in _ORDERS:
        raise TiltError(f"G68.2 P1 Q{words['Q']:g}: not an order of rotation about X, Y and Z",
                        "Q123, Q132, Q213, Q231, Q312 or Q321", "Q")
    for letter, angle in zip("IJK", angles, strict=True):
        if abs(angle) > 360.0:
            raise TiltError(f"G68.2 P1 {letter}{angle:g}: beyond the setting range", "an angle from -360 to 360 deg",
                            letter)
    turned = [letter for letter, angle in zip("IJK", angles, strict=True) if angle != 0.0]
    if len(turned) > 1:
        raise TiltError(f"G68.2 P1 with {', '.join(turned)} non-zero: not supported (the manuals read here "
                        "leave to a figure whether the later turns are about the fixed or the turned axes)",
                        "one non-zero roll (I), pitch (J) or yaw (K) angle, or G68.2 X Y Z I J K (Euler angles)",
                        turned[1])
    return spatial(*angles)
