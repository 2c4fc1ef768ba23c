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
blends, ``tcRotaryMotionCheck`` in ``src/emc/tp/tp.c``). Under G20 ``P`` is inches, converted to mm as LinuxCNC
converts it (``SET_MOTION_CONTROL_MODE`` in ``src/emc/task/emccanon.cc``: ``FROM_PROG_LEN(tolerance)``), and that
number of mm is the tolerance in deg on A-C (our reading: LinuxCNC bounds only the XYZ blend with it,
``tpComputeBlendVelocity`` in ``tp.c`` takes the angle between the XYZ directions, and LinuxCNC's G-code reference
gives G64 no angular tolerance; HEIDENHAIN's cycle 32 TA is one, not read here): ``G20 G64 P0.002`` is 0.0508 mm
on X-Z and U-W, 0.0508 deg on A-C. That motion is taken where the programmed path is nearest the blend's X, Y, Z
(:func:`corner_positions`): at each of its check points the programmed value at the nearest point of the incoming
or the outgoing line, so that a sample's axes are within the tolerance of the motion programmed at the point of
the part nearest it, the measure of ``tests/interpolators/test_rotary_chains.py`` (``_axis_deviation``). Our
reading: the axes move in proportion to the path on each block (RS274/NGC 3, Sec. 2.1.2.5), so a position on the
part has one programmed value of each axis. Measured along the blend's arc length instead (the polyline with the
corner at the blend's middle, still the measure where X, Y, Z keep their path: the ramps below), an axis turning
fast per mm (7 deg/mm at a 30 deg corner) was up to 2 P from the value at the nearest point (review31, a G20
C-axis chain at P0.00787).

A blend whose axes leave that tolerance is made again with ``P`` scaled down by the excess
(:func:`excess`: the deviation grows in proportion to the blend's size, as the XYZ one does), then dropped. The
derivatives bound the blend's speed (:func:`hermite_bounds`) where the planner judges whether a blend pays.

Where the X, Y, Z path goes on unchanged through a junction (a line into an arc, or a corner left unblended) but
these axes' rate per mm steps (an axis starting or stopping where a rotary word appears on some blocks only, or a
line and an arc moving it at different rates), the same quintic carries the step over a ramp of the programmed path
centred on the junction (:func:`ramp_half_length`): the X, Y, Z path is the programmed one, so the polyline of
:func:`excess` is exactly the axes' programmed motion there.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators.dense import FIT_SHARE
from interpolators.kinematics import CURVE_BOUND_MARGIN

if TYPE_CHECKING:
    from scipy.interpolate import BSpline

__all__ = ["CHECK_SHARES", "hermite_axes", "hermite_bounds", "excess", "corner_positions", "ramp_half_length"]

#: Points along a blend at which its axes' deviation from their programmed motion and their derivatives are taken.
_CHECK_POINTS = 33
#: The shares of a blend's length at those points (:func:`excess`'s ``along``).
CHECK_SHARES = np.linspace(0.0, 1.0, _CHECK_POINTS)
#: Power series coefficients (in the share u of the blend) of the quintic Hermite basis with zero second
#: derivatives at both ends: the end step ``H1`` (``H0 = 1 - H1``), the start rate ``H2`` and the end rate ``H3``.
_BASIS = np.array([[0, 0, 0, 10, -15, 6], [0, 1, 0, -6, 8, -3], [0, 0, 0, -4, 7, -3]], dtype=float)
#: Power series to Bernstein coefficients of degree 5: ``b_i = sum_k C(i, k) / C(5, k) a_k`` for ``k <= i``.
_TO_BERNSTEIN = np.array([[math.comb(i, k) / math.comb(5, k) if k <= i else 0.0 for k in range(6)] for i in range(6)])


def hermite_axes(length: np.ndarray, start: np.ndarray, end: np.ndarray, rate_start: np.ndarray,
                 rate_end: np.ndarray) -> tuple[BSpline, np.ndarray]:
    """The quintics ``r(s)`` of m blends (``length`` (m,) [mm], the others (m, k)), each over ``0 <= s <= length``
    with ``r(0) = start``, ``r(length) = end``, ``r'`` the rates (per mm of path) and ``r'' = 0`` at both ends,
    as one :class:`scipy.interpolate.BSpline` of degree 5 (one spline evaluated at once for all the blends of a
    chain) and the parameter of each blend's start in it. Blend ``j`` is the polynomial of the knot interval
    ``[S_j, S_j + 2 length_j]`` (knots of multiplicity 6: no continuity between blends), so that its end ``S_j +
    length_j`` lies inside it. Equal rates ``(end - start) / length`` give the straight line; an axis with equal
    ends and zero rates in a blend has that blend's coefficients at its value, so all of them where it keeps one
    value in every blend (the planner's test of an axis kept still)."""
    from scipy.interpolate import BSpline

    length = np.asarray(length, dtype=float)
    a0, a1, m0, m1 = _arrays(start, end, rate_start, rate_end)
    # power series in w = (s - S_j) / (2 length): the basis' in u = 2 w, times 2^k
    power = ((a1 - a0)[:, None, :] * _BASIS[0][None, :, None]
             + (length[:, None] * m0)[:, None, :] * _BASIS[1][None, :, None]
             + (length[:, None] * m1)[:, None, :] * _BASIS[2][None, :, None]) * (2.0 ** np.arange(6))[None, :, None]
    power[:, 0] += a0
    c = np.einsum("ik,jkl->jil", _TO_BERNSTEIN, power)  # (m, 6, k): Bernstein coefficients of each interval
    # an axis still across a blend: exactly its value there (its own in each blend: the chain's lines between two
    # blends may move it, and the first blend's value on all of them put U 1500 mm back to 0 in a G64 P0.05 chain
    # whose unblended middle line moved it; setpoint fuzzer rotary_cam seed 40599)
    still = (a0 == a1) & (m0 == 0) & (m1 == 0)
    c = np.where(still[:, None, :], a0[:, None, :], c)
    offsets = np.concatenate([[0.0], np.cumsum(2.0 * length)])
    return BSpline(np.repeat(offsets, 6), c.reshape(-1, c.shape[2]), 5), offsets[:-1]


def _derivatives(length: np.ndarray, start: np.ndarray, end: np.ndarray, rate_start: np.ndarray,
                 rate_end: np.ndarray, nu: int, u: np.ndarray) -> np.ndarray:
    """``d^nu r / ds^nu`` of :func:`hermite_axes` (``nu = 0``: ``r - start``) of m blends of ``length`` (m,), the
    others (m, k), at the shares ``u`` of their length: shape (m, len(u), k)."""
    p = _BASIS
    for _ in range(nu):
        p = p[:, 1:] * np.arange(1, p.shape[1])
    h = np.stack([np.polynomial.polynomial.polyval(u, row) for row in p])[:, None, :, None]
    L = length[:, None, None]
    return ((end - start)[:, None, :] * h[0] + L * rate_start[:, None, :] * h[1]
            + L * rate_end[:, None, :] * h[2]) / L**nu


def _arrays(*args) -> tuple[np.ndarray, ...]:
    return tuple(np.asarray(x, dtype=float) for x in args)


def hermite_bounds(length: np.ndarray, start: np.ndarray, end: np.ndarray, rate_start: np.ndarray,
                   rate_end: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Largest first, second and third derivatives along the path (absolute, shape (m, k)) of the quintics of
    :func:`hermite_axes` of m blends at once (``length`` (m,), the others (m, k)), at :data:`_CHECK_POINTS` points
    each, by ``CURVE_BOUND_MARGIN`` as the merged runs' splines (for
    :func:`interpolators.kinematics.extra_curve_bounds`); an axis at rest has exactly 0."""
    u = CHECK_SHARES
    args = _arrays(length, start, end, rate_start, rate_end)
    d1, d2, d3 = (np.abs(_derivatives(*args, nu, u)).max(axis=1) * CURVE_BOUND_MARGIN for nu in (1, 2, 3))
    return d1, d2, d3


def excess(length: np.ndarray, start: np.ndarray, end: np.ndarray, rate_start: np.ndarray, rate_end: np.ndarray,
           corner: np.ndarray, tolerance: np.ndarray, *, along: np.ndarray | None = None) -> np.ndarray:
    """How far the axes of m blends (:func:`hermite_axes`, arrays as :func:`hermite_bounds`) leave their programmed
    motion, as a multiple of ``FIT_SHARE * tolerance`` (at most 1: within it; shape (m,)). That motion is the
    programmed value at ``along`` (m, len(CHECK_SHARES)): the signed path distance from the corner of the point of
    the programmed path nearest each check point (:func:`corner_positions`), ``corner + rate_start * t`` before the
    corner and ``corner + rate_end * t`` after it (``corner``: the programmed values there); without ``along`` the
    polyline through the blend's end values and ``corner`` at its middle, along its arc length (a ramp: X, Y, Z on
    the programmed path, the same motion)."""
    u = CHECK_SHARES
    length, start, end, rate_start, rate_end, corner, tolerance = _arrays(length, start, end, rate_start, rate_end,
                                                                          corner, tolerance)
    r = _derivatives(length, start, end, rate_start, rate_end, 0, u)
    if along is None:
        w = np.minimum(2.0 * u, 1.0)[None, :, None]
        v = np.maximum(2.0 * u - 1.0, 0.0)[None, :, None]
        programmed = (corner - start)[:, None, :] * w + (end - corner)[:, None, :] * v
    else:
        t = np.asarray(along, dtype=float)[:, :, None]
        programmed = (corner - start)[:, None, :] + np.where(t < 0, rate_start[:, None, :] * t,
                                                             rate_end[:, None, :] * t)
    dev = np.abs(r - programmed).max(axis=(1, 2))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(tolerance > 0, dev / (FIT_SHARE * tolerance), np.inf)


def corner_positions(points: np.ndarray, corner: np.ndarray, before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """Where points near m corners (``points`` (m, c, 3)) lie along their programmed path: the signed path distance
    from the corner (``corner`` (m, 3)) of the nearest point of the incoming line (unit direction ``before`` (m, 3),
    towards the corner: ``t <= 0``) or of the outgoing one (``after``: ``t >= 0``), whichever is nearer; shape
    (m, c)."""
    rel = np.asarray(points, dtype=float) - np.asarray(corner, dtype=float)[:, None, :]
    before, after = np.asarray(before, dtype=float), np.asarray(after, dtype=float)
    t_in = np.minimum(np.einsum("mck,mk->mc", rel, before), 0.0)
    t_out = np.maximum(np.einsum("mck,mk->mc", rel, after), 0.0)
    d_in = np.linalg.norm(rel - t_in[..., None] * before[:, None, :], axis=2)
    d_out = np.linalg.norm(rel - t_out[..., None] * after[:, None, :], axis=2)
    return np.where(d_in <= d_out, t_in, t_out)


def ramp_half_length(step: np.ndarray, tolerance: np.ndarray) -> np.ndarray:
    """Half the length [mm of path] of the longest ramp that carries the rate steps ``step`` (m, k) [per mm of
    path] of m junctions within ``FIT_SHARE * tolerance`` (m,) of their programmed motion: the quintic of
    :func:`hermite_axes` over ``L`` centred on the corner (rates ``m0``, ``m1``) leaves the polyline by ``3 L |m1 -
    m0| / 32`` at its middle, its largest distance (``r' - m0 = (m1 - m0) (3 u^2 - 2 u^3)``); the longer the ramp,
    the lower its second and third derivatives (``1.5 |dm| / L``, ``6 |dm| / L^2``) and so the faster it is
    passed. Infinite where no axis steps."""
    step = np.abs(np.asarray(step, dtype=float)).max(axis=1)
    with np.errstate(divide="ignore"):
        return np.where(step > 0, 16.0 * FIT_SHARE * np.asarray(tolerance, dtype=float) / (3.0 * step), np.inf)
