"""Fanuc G68.2 tilted working plane and G53.1 tool axis direction control on a tilting table.

``G68.2 X Y Z I J K`` defines a feature coordinate system whose origin is X Y Z (in the workpiece
coordinate system) and whose axes are turned by the Euler angles I (about Z), J (about the turned X)
and K (about the new Z) [deg]; ``G53.1`` then turns the rotary axes so that the tool is square to that
plane (the linear axes stay), and ``G69`` cancels it. Sources: FANUC Series 30i/31i additional manual
B-79976E, "Specifying tilted working plane based on the tool axis direction" (G68.3, cncmanuals.com):
"When G68.3 is specified in a block, the coordinate system for programming is changed to a feature
coordinate system. All commands after the block are regarded as commands in the feature coordinate
system until G69 is specified"; cnc.wiki, "G68.2 Tilted Working Plane": "Rotary axes must be manually
aligned via G53.1 or automatic cycles; all tool and cutter radius compensations must be strictly
canceled before activation". The Euler order Z-X'-Z'' of I J K is not in a manual found here (it is
the one the CAM posts write). A program may position the rotary axes itself (``G0 B.. C..``) instead
of G53.1; vcnc runs the plane's coordinates at the positions G53.1 would take (not checked). The plane
lives in the rotation of :class:`interpolators.iso_transforms.Frame`, so that G69 cancels it as it
cancels G68. The geometry is :mod:`interpolators.tilted`'s, as the Heidenhain reader's PLANE.

Not read here: the other definitions of G68.2 (``P1`` .. ``P4``: roll-pitch-yaw, three points, two
vectors, projection angles), G68.3/G68.4, and a work offset or G92 changed under G68.2 (not modelled:
the plane's zero then moves by the change, along the machine's axes).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from interpolators.context import MachineContext
from interpolators.iso_transforms import Rotation
from interpolators.tilted import TiltError, euler, tilted_frame

__all__ = ["TiltedRotation", "TiltError", "g68_2_rotation"]


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
                   scale: float) -> TiltedRotation:
    """The plane a ``G68.2 X Y Z I J K`` block defines.

    Parameters
    ----------
    words : dict
        The block's words (X, Y, Z [program units]; I, J, K [deg]).
    context : MachineContext
        Its ``kinematics`` (a tilting table) solves the rotary axes (the solution nearest ``extra``).
    work_zero : ndarray (3,)
        The work zero with every rotary axis at 0 [mm, machine]: work offset plus G92 offset.
    extra : ndarray (6,)
        Positions of a, b, c [deg] (and u, v, w) now.
    scale : float
        mm per program unit.

    Raises
    ------
    TiltError
        No kinematics, a head-tilting machine, or a plane the rotary axes cannot reach.
    """
    kin = context.kinematics
    if kin is None:
        raise TiltError("G68.2 tilted working plane needs the machine's kinematics",
                        "a machine with [program.kinematics] (vcnc machines --show: the rotary axes that tilt the "
                        "part)")
    kin.require_table()
    plane = euler(words.get("I", 0.0), words.get("J", 0.0), words.get("K", 0.0))
    angles = kin.choose(plane, kin.solution_at(extra))
    origin = np.array([words.get(a, 0.0) * scale for a in "XYZ"])
    theta, datum = tilted_frame(kin, plane, angles, np.asarray(work_zero, dtype=float) + origin)
    shift = datum - np.asarray(work_zero, dtype=float)
    if not all(math.isfinite(v) for v in shift):
        raise TiltError("G68.2: the plane's zero is not a finite point", "finite X, Y, Z")
    return TiltedRotation(plane=2, centre=(0.0, 0.0, 0.0), angle=theta, shift=tuple(float(v) for v in shift),
                          positions=kin.positions(angles))
