"""The axes beyond X, Y, Z through a blended corner: a quintic in the path's arc length.

A G64 chain that moves A-C or U-W beside X, Y, Z has its line/line corners blended as any other
(:func:`interpolators.lookahead.blend_corners`: a tangent arc, or under the S-curve a clothoid pair, within
the path tolerance ``P`` of the corner). Along each programmed line these axes move in proportion to the path
(RS274/NGC 3, Sec. 2.1.2.5), so at the corner their rate per mm of path steps with the line's. Across the blend
they follow the quintic Hermite polynomial of the blend's arc length that matches their values and rates at
its ends (those of the shortened lines there) with zero second derivative, so their velocity is continuous
and, at the S-curve's zero path acceleration, their acceleration too; the XYZ blend keeps the curvature, the
quintic the second derivative, continuous. It must stay within ``FIT_SHARE * P`` of their programmed motion
in each axis' unit (deg on A-C, mm on U-W, as :func:`interpolators.dense.fit_axes` reads ``P`` for them;
our reading of LinuxCNC, which blends every axis of such segments under the one G64 ``P`` with its parabolic
blends, ``tcRotaryMotionCheck`` in ``src/emc/tp/tp.c``). That motion is measured along the blend as the
merged runs' is along their curve: the polyline through the blend's end values and the corner's programmed
value at the blend's middle (the symmetric arc and clothoid pair pass nearest the corner there).

A blend whose axes leave that tolerance is made again with ``P`` scaled down by the excess
(:func:`excess`: the deviation grows in proportion to the blend's size, as the XYZ one does), then dropped.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators.dense import FIT_SHARE

if TYPE_CHECKING:
    from scipy.interpolate import BSpline

__all__ = ["hermite_axes", "excess"]

#: Points along a blend at which its axes' deviation from their programmed motion is measured.
_CHECK_POINTS = 33


def hermite_axes(length: float, start: np.ndarray, end: np.ndarray, rate_start: np.ndarray,
                 rate_end: np.ndarray) -> BSpline:
    """The quintic ``r(s)``, ``0 <= s <= length`` [mm], with ``r(0) = start``, ``r(length) = end``, ``r'`` the
    rates (per mm of path) and ``r'' = 0`` at both ends, as a :class:`scipy.interpolate.BSpline` of degree 5
    (its Bezier form). Equal rates ``(end - start) / length`` give the straight line exactly; an axis with equal
    ends and zero rates has all its coefficients at its value (the planner's test of an axis kept still)."""
    from scipy.interpolate import BSpline

    a0, a1 = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    m0 = np.asarray(rate_start, dtype=float) * (length / 5.0)
    m1 = np.asarray(rate_end, dtype=float) * (length / 5.0)
    c = np.array([a0, a0 + m0, a0 + 2.0 * m0, a1 - 2.0 * m1, a1 - m1, a1])
    still = (a0 == a1) & (m0 == 0) & (m1 == 0)
    c[:, still] = a0[still]
    return BSpline(np.r_[[0.0] * 6, [length] * 6], c, 5)


def excess(spl: BSpline, length: float, corner: np.ndarray, tolerance: float) -> float:
    """How far the axes ``spl`` (:func:`hermite_axes` over a blend of ``length`` [mm]) leave their programmed
    motion, as a multiple of ``FIT_SHARE * tolerance`` (at most 1: within it): that motion is the polyline
    through the blend's end values and ``corner`` (the programmed values at the corner) at its middle."""
    s = np.linspace(0.0, length, _CHECK_POINTS)
    ends = spl(np.array([0.0, length]))
    polyline = np.column_stack([np.interp(s, [0.0, 0.5 * length, length], [e0, c, e1])
                                for e0, c, e1 in zip(ends[0], corner, ends[1])])
    dev = float(np.max(np.abs(spl(s) - polyline)))
    return dev / (FIT_SHARE * tolerance) if tolerance > 0 else np.inf
