"""Programmable coordinate rotation of Fanuc and Haas mills: G68 / G69.

Haas mill operator's manual, "G68 Rotation (Group 16)": ``G17 G68 X.. Y.. R..`` rotates all the
X, Y, Z, I, J and K values of the following blocks about the centre X Y (the two axes of the
selected plane: X Z under G18, Y Z under G19; an axis not given: the current position) by R
degrees, counter-clockwise positive; the values of the G68 block itself are not rotated. R omitted:
the default angle (Haas Setting 72, Fanuc parameter No. 5410), 0 here. Under G91, R is added to the
active angle only with Haas Setting 73 / Fanuc parameter RIN (No. 5400#0) on; both are off by
default, so R is absolute (Fanuc 0i-MF operator's manual, "Coordinate system rotation (G68, G69)").
G69 cancels it. Arcs rotate with their centre; the G68 centre is in the program coordinates of the
active work offset, never incremental.

A program point ``p`` of the rotated system lies at ``centre + R(angle) (p - centre)`` in the
unrotated program coordinates; the reader adds its offsets after that
(:meth:`interpolators.iso._State.to_machine`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from toolpaths.geometry import PLANE_AXES

__all__ = ["Rotation", "g68_rotation"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Rotation:
    """An active G68 rotation.

    Attributes
    ----------
    plane : int
        Plane of rotation: 2 (G17, XY), 1 (G18, ZX) or 0 (G19, YZ).
    centre : tuple of float
        Centre of rotation (x, y, z) [mm, program coordinates]; only the plane's two axes matter.
    angle : float
        Angle [deg], counter-clockwise positive seen from the plane's normal.
    """

    plane: int
    centre: tuple[float, float, float]
    angle: float

    def _turn(self, point: np.ndarray, angle: float) -> np.ndarray:
        out = np.array(point, dtype=float)
        p, q = PLANE_AXES[self.plane]
        c = np.asarray(self.centre, dtype=float)
        a = math.radians(angle)
        cos, sin = math.cos(a), math.sin(a)
        dp, dq = out[p] - c[p], out[q] - c[q]
        out[p], out[q] = c[p] + cos * dp - sin * dq, c[q] + sin * dp + cos * dq
        return out

    def forward(self, point: np.ndarray) -> np.ndarray:
        """Unrotated program coordinates [mm] of a point of the rotated system."""
        return self._turn(point, self.angle)

    def inverse(self, point: np.ndarray) -> np.ndarray:
        """Rotated-system coordinates [mm] of a point in unrotated program coordinates."""
        return self._turn(point, -self.angle)


def g68_rotation(words: dict[str, float], *, plane: int, current: np.ndarray, scale: float) -> Rotation:
    """The rotation a ``G68`` block sets.

    Parameters
    ----------
    words : dict
        The block's words as written (the plane's two axis letters for the centre, ``R`` the angle).
    plane : int
        Active plane (2 G17, 1 G18, 0 G19), after the block's own plane code.
    current : ndarray (3,)
        Current position [mm, unrotated program coordinates]: the centre's default.
    scale : float
        mm per program unit.
    """
    centre = np.array(current, dtype=float)
    for i in PLANE_AXES[plane]:
        letter = "XYZ"[i]
        if letter in words:
            centre[i] = words[letter] * scale
    return Rotation(plane=plane, centre=tuple(float(v) for v in centre), angle=float(words.get("R", 0.0)))
