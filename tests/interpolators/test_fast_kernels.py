"""The compiled and batched forms of the interpolator's inner loops against their scalar forms, bit for bit.

Each kernel replaced a Python loop or a per-object evaluation (interpolation of dense CAM programs); the
setpoints must not change by one bit, so each is checked here against the form it replaced on hand-made inputs:
the look-ahead's reach (the Python form of ``scurve_reach`` it replaced, written out here, and ``trapezoid_reach``)
and its backward/forward passes, the B-spline
design matrix (scipy's), the fit's chord distance (its numpy form, written out here), and the pieces of a fitted
curve built and evaluated at once (``SplineCurve`` one piece at a time).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import BSpline

from interpolators.dense import chord_distance, cubic_basis, fit_run
from interpolators.lookahead import junction_speeds
from interpolators.profiles import reach_many, reach_passes, scurve_reach, trapezoid_reach
from toolpaths.geometry import SplineCurve


def _scurve_reach_python(v: float, length: float, a_max: float, j_max: float) -> float:
    """``profiles.scurve_reach`` as it was in Python before the compiled kernel replaced it."""
    if length <= 0:
        return v
    A, J = a_max, j_max
    dv_lim = A * A / J
    p, q = 2.0 * v, -length * math.sqrt(J)
    disc = (q / 2.0) ** 2 + (p / 3.0) ** 3
    sd = math.sqrt(disc)
    x = math.copysign(abs(-q / 2.0 + sd) ** (1.0 / 3.0), -q / 2.0 + sd) + math.copysign(
        abs(-q / 2.0 - sd) ** (1.0 / 3.0), -q / 2.0 - sd
    )
    for _ in range(2):
        x -= (x * x * x + p * x + q) / (3.0 * x * x + p)
    dv = x * x
    if dv > dv_lim:
        b = 2.0 * v * J + A * A
        c = 2.0 * v * A * A - 2.0 * length * A * J
        dv = (-b + math.sqrt(b * b - 4.0 * J * c)) / (2.0 * J)
    return v + max(dv, 0.0)


def _bits(a) -> np.ndarray:
    return np.asarray(a, dtype=float).view(np.int64)


def _reach_inputs() -> tuple[np.ndarray, ...]:
    """Start speeds, lengths, accelerations, jerks over the ranges a machine sees (a grid, rest starts included)."""
    v = np.array([0.0, 1e-9, 0.3, 5.0, 41.7, 200.0, 833.3])
    length = np.array([1e-9, 1e-6, 1e-3, 0.05, 0.7, 12.0, 400.0])
    a = np.array([50.0, 1000.0, 12000.0])
    j = np.array([1e3, 5e4, 2e6])
    grid = np.meshgrid(v, length, a, j, indexing="ij")
    return tuple(g.ravel() for g in grid)


@pytest.mark.parametrize("jerk_limited", [True, False])
def test_reach_many_is_the_scalar_reach(jerk_limited):
    v, length, a, j = _reach_inputs()
    got = reach_many(v, length, a, j, jerk_limited=jerk_limited)
    if jerk_limited:
        ref = [_scurve_reach_python(*x) for x in zip(v.tolist(), length.tolist(), a.tolist(), j.tolist())]
        assert np.array_equal(_bits([scurve_reach(*x) for x in zip(v, length, a, j)]), _bits(ref))
    else:
        ref = [trapezoid_reach(*x) for x in zip(v.tolist(), length.tolist(), a.tolist())]
    assert np.array_equal(_bits(got), _bits(ref))
    assert np.all(got >= v)  # a reach never loses speed


def test_scurve_reach_covers_the_length():
    # the reached speed's change dv, with zero end accelerations, takes T = dv/A + A/J (dv >= A^2/J) or
    # 2 sqrt(dv/J) and covers (v0 + v1) T / 2: that distance is the length given
    for v, length, a, j in zip(*_reach_inputs()):
        dv = scurve_reach(v, length, a, j) - v
        if dv < 1e-6 * v:
            continue  # a change within v's last digits: the difference does not resolve T
        T = dv / a + a / j if dv >= a * a / j else 2.0 * math.sqrt(dv / j)
        assert (2.0 * v + dv) * T / 2.0 == pytest.approx(length, rel=1e-9)


def test_scurve_reach_of_zero_length_is_the_start_speed():
    assert reach_many(np.array([3.5]), np.array([0.0]), np.array([100.0]), np.array([1e4]), jerk_limited=True)[0] == 3.5


def _passes_by_loop(v, length, a, j, jerk_limited):
    """The look-ahead's passes as the Python loops they were."""
    vl = list(v)
    reach = (lambda s, L, a_, j_: _scurve_reach_python(s, L, a_, j_)) if jerk_limited else (
        lambda s, L, a_, j_: trapezoid_reach(s, L, a_))
    n = len(length)
    for k in range(n - 1, 0, -1):
        vl[k] = min(vl[k], reach(vl[k + 1], length[k], a[k], j[k]))
    for k in range(1, n):
        vl[k] = min(vl[k], reach(vl[k - 1], length[k - 1], a[k - 1], j[k - 1]))
    return vl


@pytest.mark.parametrize("jerk_limited", [True, False])
def test_reach_passes_are_the_loops(jerk_limited):
    # a chain of short and long segments with junction limits of all sizes (a CAM contour's mix)
    length = np.array([0.02, 0.02, 5.0, 0.3, 0.004, 0.004, 0.004, 12.0, 0.8, 0.05])
    a = np.array([800.0, 800.0, 1200.0, 1200.0, 300.0, 300.0, 300.0, 1200.0, 900.0, 900.0])
    j = 20.0 * a
    v = np.array([0.0, 150.0, 150.0, 3.0, 90.0, 400.0, 400.0, 60.0, 250.0, 20.0, 0.0])
    got = reach_passes(v, length, a, j, jerk_limited=jerk_limited)
    ref = _passes_by_loop(v.tolist(), length.tolist(), a.tolist(), j.tolist(), jerk_limited)
    assert np.array_equal(_bits(got), _bits(ref))
    assert got[0] == 0.0 and got[-1] == 0.0
    # every segment can change between its end speeds within its length
    reach_fwd = reach_many(got[:-1], length, a, j, jerk_limited=jerk_limited)
    reach_bwd = reach_many(got[1:], length, a, j, jerk_limited=jerk_limited)
    assert np.all(got[1:] <= reach_fwd) and np.all(got[:-1] <= reach_bwd)


def test_junction_speeds_keeps_the_rounding_margin():
    length = np.array([1.0, 0.5, 2.0])
    v = junction_speeds(length, np.full(3, 100.0), np.full(3, 1000.0), np.full(3, 1e5), np.array([80.0, 200.0]),
                        jerk_limited=True)
    ref = np.asarray(_passes_by_loop([0.0, 80.0, 100.0, 0.0], (length * (1.0 - 1e-9)).tolist(), [1000.0] * 3,
                                     [1e5] * 3, True)) * (1.0 - 1e-9)
    assert np.array_equal(_bits(v), _bits(ref))


def _knots(u: np.ndarray, every: int) -> np.ndarray:
    inner = u[every:-1:every]
    return np.concatenate([[u[0]] * 4, inner, [u[-1]] * 4])


def _cam_points(n: int, radius: float) -> np.ndarray:
    """Points of an arc with a slow rise, rounded to 4 decimals as CAM output is."""
    s = np.linspace(0.0, 0.03 * n, n + 1) + 0.01 * np.sin(np.arange(n + 1))
    return np.stack([radius * np.cos(s / radius), radius * np.sin(s / radius), 0.002 * s], axis=1).round(4)


@pytest.mark.parametrize("n, every", [(8, 4), (40, 5), (301, 7), (1000, 33)])
def test_cubic_basis_is_scipys_design_matrix(n, every):
    pts = _cam_points(n, 6.0)
    u = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    knots = _knots(u, every)
    # the fit's points, points between them (in order and not), the knots themselves and both ends
    x = np.concatenate([u, 0.5 * (u[1:] + u[:-1]), knots[::-1], [u[-1], 0.0]])
    first, values = cubic_basis(x, knots)
    B = BSpline.design_matrix(x, knots, 3)
    assert np.array_equal(first, B.indices[::4])
    assert np.array_equal(_bits(values), _bits(B.data.reshape(-1, 4)))
    assert np.allclose(values.sum(axis=1), 1.0)  # a partition of unity


def _chord_distance_numpy(points, u, curve, u_eval):
    """The fit's check as the numpy expression it was."""
    n = len(points) - 1
    j = np.clip(np.searchsorted(u, u_eval, side="right") - 1, 0, n - 1)
    best = np.full(len(u_eval), np.inf)
    for dj in (-1, 0, 1):
        k = np.clip(j + dj, 0, n - 1)
        a, ab = points[k], points[k + 1] - points[k]
        t = np.clip(np.einsum("ij,ij->i", curve - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        best = np.minimum(best, np.linalg.norm(curve - a - t[:, None] * ab, axis=1))
    return float(best.max())


def test_chord_distance_is_the_numpy_form():
    pts = _cam_points(200, 4.0)
    u = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    u_eval = np.linspace(0.0, u[-1], 1601)
    # a curve off the chords by up to 3 um in all three coordinates
    wobble = 0.003 * np.stack([np.sin(7 * u_eval), np.cos(5 * u_eval), np.sin(3 * u_eval)], axis=1)
    curve = np.stack([np.interp(u_eval, u, pts[:, i]) for i in range(3)], axis=1) + wobble
    got = chord_distance(pts, u, curve, u_eval)
    assert got == _chord_distance_numpy(pts, u, curve, u_eval)
    assert 0.0 < got <= 0.003 * np.sqrt(3.0)
    on_chords = np.stack([np.interp(u_eval, u, pts[:, i]) for i in range(3)], axis=1)
    assert chord_distance(pts, u, on_chords, u_eval) < 1e-12


def _fitted_pieces():
    pts = _cam_points(1200, 5.0)  # 36 mm: about nine knot intervals
    spl = fit_run(pts, 0.01)
    assert spl is not None
    knots = np.unique(spl.t)
    assert len(knots) >= 5
    return spl, np.concatenate([knots[:-1:2], knots[-1:]]), pts


def test_pieces_built_at_once_are_the_pieces_one_by_one():
    spl, brk, pts = _fitted_pieces()
    batch = SplineCurve.pieces(spl, brk, start=pts[0], end=pts[-1])
    assert len(batch) == len(brk) - 1
    for i, p in enumerate(batch):
        one = SplineCurve(spl, brk[i], brk[i + 1], start=pts[0] if i == 0 else None,
                          end=pts[-1] if i == len(brk) - 2 else None)
        assert p.length == one.length
        assert np.array_equal(p.start, one.start) and np.array_equal(p.end, one.end)
        k, dk, t_abs = p.bounds()
        k1, dk1, t_abs1 = one.bounds()
        assert (k, dk) == (k1, dk1) and np.array_equal(t_abs, t_abs1)
        s = np.linspace(-0.1, one.length + 0.1, 57)
        assert np.array_equal(_bits(p.parameter_at(s)), _bits(one.parameter_at(s)))
    assert all(np.array_equal(a.end, b.start) for a, b in zip(batch[:-1], batch[1:]))  # the pieces meet exactly


def test_pieces_evaluated_at_once_are_each_piece_evaluated():
    spl, brk, pts = _fitted_pieces()
    pieces = SplineCurve.pieces(spl, brk, start=pts[0], end=pts[-1])
    # rows in any order, several per piece, at both ends and beyond them (clipped)
    piece = np.array([2, 0, 1, 1, 0, 2, len(pieces) - 1, 0, len(pieces) - 1, 1])
    frac = np.array([0.5, 0.0, 1.0, 0.25, 1.2, -0.1, 1.0, 0.999, 0.0, 0.61])
    s = frac * np.array([pieces[k].length for k in piece])
    u = SplineCurve.parameters(pieces, piece, s)
    pos, tan, curv = SplineCurve.evaluate_pieces(pieces, piece, s)
    for r, (k, s_r) in enumerate(zip(piece.tolist(), s.tolist())):
        p = pieces[k]
        s_c = min(max(s_r, 0.0), p.length)
        assert u[r] == p.parameter_at(s_r)
        assert np.array_equal(pos[r], p.point_at(np.array([s_c]))[0])
        assert np.array_equal(tan[r], p.tangent_at(np.array([s_c]))[0])
        assert np.array_equal(curv[r], p.curvature_at(np.array([s_c]))[0])
    assert np.array_equal(pos[1], pts[0]) and np.array_equal(pos[6], pts[-1])  # the programmed ends exactly
    points_only = SplineCurve.evaluate_pieces(pieces, piece, s, frame=False)
    assert np.array_equal(points_only[0], pos) and points_only[1] is None
