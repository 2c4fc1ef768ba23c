"""LinuxCNC's G5 cubic and G5.1 quadratic splines in the XY plane, as chains of chords.

LinuxCNC G-code reference, "G5 Cubic Spline" and "G5.1 Quadratic Spline": one B-spline segment
from the current point P0 to the end point, with the control points ``P0 + (I, J)`` (and, for
G5, ``end + (P, Q)``): a Bezier curve. A control runs it as its own path elements (LinuxCNC as
arcs); vcnc runs it as straight chords whose distance from the curve is at most
:data:`SPLINE_TOLERANCE`, each an ordinary feed block, so that the interpolator sees exact
geometry within a micrometre.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["SPLINE_TOLERANCE", "MAX_CHORDS", "bezier_chords"]

#: Largest distance [mm] between a spline and its chords.
SPLINE_TOLERANCE: float = 0.001

#: Most chords of one spline block (a guard against absurd control points).
MAX_CHORDS: int = 100_000


def bezier_chords(control: list[np.ndarray], *, tolerance: float = SPLINE_TOLERANCE) -> list[np.ndarray]:
    """End points of the chords of the Bezier curve of ``control`` (3 or 4 points [mm], the curve
    from ``control[0]`` to ``control[-1]``), the first point left out.

    The parameter is split evenly into n intervals with ``M / (8 n^2) <= tolerance``, where M
    bounds the curve's second derivative: the chord error of an interval of length h is at most
    ``M h^2 / 8``.
    """
    pts = [np.asarray(c, dtype=float) for c in control]
    if len(pts) == 3:
        second = 2.0 * float(np.linalg.norm(pts[0] - 2 * pts[1] + pts[2]))
    else:
        second = 6.0 * max(float(np.linalg.norm(pts[0] - 2 * pts[1] + pts[2])),
                           float(np.linalg.norm(pts[1] - 2 * pts[2] + pts[3])))
    n = min(MAX_CHORDS, max(1, math.ceil(math.sqrt(second / (8.0 * tolerance)))))
    t = np.linspace(0.0, 1.0, n + 1)[1:, None]
    if len(pts) == 3:
        curve = (1 - t) ** 2 * pts[0] + 2 * (1 - t) * t * pts[1] + t**2 * pts[2]
    else:
        curve = ((1 - t) ** 3 * pts[0] + 3 * (1 - t) ** 2 * t * pts[1] + 3 * (1 - t) * t**2 * pts[2]
                 + t**3 * pts[3])
    curve[-1] = pts[-1]  # the programmed end point exactly
    return list(curve)
