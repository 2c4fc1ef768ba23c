"""Dense CAM code under G64 (issue #18 item 8): runs of short lines merged into smooth curves.

Properties of the output, not timings: the chord circle's motion time against the single arc's,
the setpoints' distance from the programmed chords, the finite-difference axis velocity,
acceleration and (S-curve) jerk against the axis limits, the block of each sample, determinism.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators import DEFAULT_LIMITS, interpolate, parse_program
from interpolators.dense import DENSE_MAX_LENGTH, fit_run, merge_dense_runs
from interpolators.interpolate import CURVE_PATH_ERROR
from tests.interpolators.setpoint_checks import distance_to_path
from toolpaths.geometry import Line
from vcnc.contour import contour_error

#: Relative margin on the finite-difference limit checks: the profiles meet the limits exactly
#: (time-optimal), and differences of positions of ~10 mm carry rounding errors of ~1e-15 mm,
#: i.e. 1e-6 mm/s^3 in the third difference at 1 ms: far below this margin.
LIMIT_MARGIN = 1e-6
TOL = 0.01  # G64 P [mm]


def _program(points: np.ndarray, feed: float, *, lead: str = "") -> str:
    """G64 program: a feed move to the first point, then lines through the points (4 decimals)."""
    lines = [f"G21 G90 G17 G64 P{TOL}", lead + f"G1 X{points[0, 0]:.4f} Y{points[0, 1]:.4f} Z{points[0, 2]:.4f} "
             f"F{feed * 60:.1f}"]
    lines += [f"X{x:.4f} Y{y:.4f} Z{z:.4f}" for x, y, z in points[1:]]
    return "\n".join(lines) + "\n"


def _chord_circle(n: int) -> tuple[np.ndarray, float]:
    """A circle of n chords of 8 um (points rounded to 4 decimals) and its radius [mm]."""
    r = n * 0.008 / (2 * math.pi)
    a = 2 * np.pi * np.arange(n + 1) / n
    return np.round(np.c_[r * np.cos(a), r * np.sin(a), np.zeros(n + 1)], 4), r



def _assert_limits(sp, jerk: bool) -> None:
    Ts = sp.sample_time
    for i, ax in enumerate(sp.axes):
        lim = DEFAULT_LIMITS[ax]
        v = np.diff(sp.position[:, i]) / Ts
        a = np.diff(v) / Ts
        assert np.abs(v).max() <= lim.velocity * (1 + LIMIT_MARGIN), ax
        assert np.abs(a).max() <= lim.acceleration * (1 + LIMIT_MARGIN), ax
        if jerk:
            assert np.abs(np.diff(a) / Ts).max() <= lim.jerk * (1 + LIMIT_MARGIN), ax


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_chord_circle_runs_like_the_arc(profile):
    pts, r = _chord_circle(10_000)
    pts[0] = (round(r, 4), 0.0, 0.0)
    arc = (f"G21 G90 G17 G64 P{TOL}\nG1 X{r:.4f} Y0 Z0 F12000\nG3 X{r:.4f} Y0 I{-r:.4f} J0\n")
    sp_arc = interpolate(parse_program(arc), profile=profile)
    program = parse_program(_program(pts, 200.0))
    sp = interpolate(program, profile=profile)
    assert sp.duration <= 1.25 * sp_arc.duration
    assert distance_to_path(sp) <= TOL
    _assert_limits(sp, jerk=profile == "scurve")
    # each sample belongs to a block near it: the chord of its block lies within the tolerance
    blk = sp.block
    assert np.all(np.diff(blk) >= 0)
    on_circle = blk >= 2  # block 0: G21..., block 1: the lead-in; chords from block 2
    p = sp.position[on_circle][:, :2]
    starts = np.array([program.blocks[b].start[:2] for b in blk[on_circle]])
    ends = np.array([program.blocks[b].target[:2] for b in blk[on_circle]])
    ab = ends - starts
    t = np.clip(((p - starts) * ab).sum(1) / (ab * ab).sum(1), 0, 1)
    assert np.hypot(*(p - starts - t[:, None] * ab).T).max() <= TOL
    # deterministic
    again = interpolate(program, profile=profile)
    assert np.array_equal(again.position, sp.position) and np.array_equal(again.block, sp.block)


def _mixed_points(seed: int) -> np.ndarray:
    """3-D dense run (helix-like, varying chord lengths 5-60 um), then a second dense run after a
    sharp corner (90 deg), as a CAM system writes them."""
    rng = np.random.default_rng(seed)
    ds = rng.uniform(0.005, 0.06, 1500)
    s = np.concatenate([[0.0], np.cumsum(ds)])
    phi = s / 8.0
    run1 = np.c_[8 * np.cos(phi), 8 * np.sin(phi), 0.05 * s]
    corner = run1[-1]
    u = rng.uniform(0.01, 0.04, 800)
    s2 = np.cumsum(u)
    tang = np.array([-math.sin(phi[-1]), math.cos(phi[-1]), 0.0])
    side = np.cross(tang, [0.0, 0.0, 1.0])  # 90 deg to the right of the helix tangent
    run2 = corner + s2[:, None] * side + (s2**2 / 40.0)[:, None] * tang
    return np.round(np.vstack([run1, run2]), 4)


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_mixed_dense_code_within_tolerance_and_limits(profile):
    pts = _mixed_points(1)
    corner = pts[1500]
    text = _program(pts, 150.0)
    # a long line and an arc after the dense runs
    end = pts[-1]
    text += f"G1 X{end[0] + 5:.4f}\nG2 X{end[0] + 15:.4f} Y{end[1]:.4f} I5 J0\n"
    program = parse_program(text)
    sp = interpolate(program, profile=profile)
    assert distance_to_path(sp) <= TOL
    _assert_limits(sp, jerk=profile == "scurve")
    # the sharp corner between the two dense runs is honoured
    xyz = sp.position[:, [sp.axes.index(a) for a in "xyz"]]
    assert np.linalg.norm(xyz - corner, axis=1).min() <= TOL
    assert np.all(np.diff(sp.block) >= 0)
    # faster than the same program in exact stop (where nothing merges)
    sp_g61 = interpolate(parse_program(text.replace("G64", "G61")), profile=profile)
    assert sp.duration < 0.5 * sp_g61.duration


def test_runs_are_found_and_split_at_sharp_corners():
    pts = _mixed_points(2)
    segs = [Line(pts[k], pts[k + 1]) for k in range(len(pts) - 1)]
    n = len(segs)
    out, first, runs = merge_dense_runs(segs, list(range(n)), [100.0] * n, [False] * n, [TOL] * n)
    merged = {id(r): r for r in runs.values()}
    assert len(merged) == 2  # one curve per run, split at the corner
    corner_block = [r.blocks[0] for r in merged.values()]
    assert sorted(corner_block) == [0, 1500]
    # nothing is merged without a tolerance, for rapids or for long lines
    for kw in ({"tolerances": [0.0] * n}, {"rapid": [True] * n}):
        args = {"feeds": [100.0] * n, "rapid": [False] * n, "tolerances": [TOL] * n} | kw
        assert merge_dense_runs(segs, list(range(n)), **args)[2] == {}
    long = [Line((0, 0, 0), (DENSE_MAX_LENGTH * 1.5, 0.01, 0))] * 20
    assert merge_dense_runs(long, list(range(20)), [100.0] * 20, [False] * 20, [TOL] * 20)[2] == {}


def _random_dense_program(seed: int) -> str:
    """Smooth random 3-D curves written as dense chords (5-80 um, 4 decimals), joined by sharp
    corners, with a raster of 0.5 mm steps and 90 deg turns (dense but not smooth) between them."""
    rng = np.random.default_rng(seed)
    pts = [np.zeros(3)]
    for _ in range(3):
        s = np.concatenate([[0.0], np.cumsum(rng.uniform(0.005, 0.08, 600))])
        w = rng.uniform(0.05, 0.4, 3)
        amp = rng.uniform(2.0, 10.0, 3) * np.array([1.0, 1.0, 0.2])
        ph = rng.uniform(0, 2 * np.pi, 3)
        curve = amp * (np.sin(w * s[:, None] + ph) - np.sin(ph))
        pts.extend(pts[-1] + curve[1:])
        for k in range(12):  # raster: 0.5 mm steps turning 90 degrees
            pts.append(pts[-1] + (np.array([0.5, 0, 0]) if k % 2 == 0 else np.array([0, 0.5, 0])))
    p = np.round(np.array(pts), 4)
    return _program(p, 120.0)


@pytest.mark.parametrize("seed", [3, 4, 5])
@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_random_dense_curves(seed, profile):
    program = parse_program(_random_dense_program(seed))
    sp = interpolate(program, profile=profile)
    assert distance_to_path(sp) <= TOL
    _assert_limits(sp, jerk=profile == "scurve")
    assert np.all(np.diff(sp.block) >= 0)
    assert np.array_equal(sp.position[-1], program.end_position[[("xyz").index(a) for a in sp.axes]])
    # the path the setpoints report is the one they follow: an ideal machine has no contour error
    ideal = contour_error(sp.path, sp.position, sp.axes, reference=sp.position, sample_time=sp.sample_time)
    assert np.abs(ideal.error).max() <= CURVE_PATH_ERROR * (1 + 1e-6)


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_dense_arc_between_tangent_lines_runs_like_the_arc(profile):
    """A quarter circle of 2,000 chords joining two lines tangentially runs as the G3 arc does
    (the curve's end tangents are the lines' directions, so the junctions stay tangent)."""
    a = np.linspace(-np.pi / 2, 0.0, 2001)
    pts = np.round(np.c_[20 + 10 * np.cos(a), 10 + 10 * np.sin(a)], 4)
    head = f"G21 G90 G17 G64 P{TOL}\nG1 X0 Y0 F9000\nX20 Y0\n"
    dense = head + "\n".join(f"X{x:.4f} Y{y:.4f}" for x, y in pts[1:]) + "\nX30 Y30\n"
    arc = head + "G3 X30 Y10 I0 J10\nG1 X30 Y30\n"
    sp = interpolate(parse_program(dense), profile=profile)
    sp_arc = interpolate(parse_program(arc), profile=profile)
    assert sp.duration <= 1.02 * sp_arc.duration  # measured 1.006 (trapezoid), 1.011 (S-curve)
    assert distance_to_path(sp) <= TOL
    _assert_limits(sp, jerk=profile == "scurve")


@pytest.mark.parametrize("tangents", [(False, False), (True, False), (True, True)])
def test_fit_matches_dense_constrained_least_squares(tangents):
    """fit_run's banded normal equations give the coefficients of an independent dense least-squares solve
    (np.linalg.lstsq on the full design matrix): end points fixed, end tangents imposed as a length along the
    given direction, the other coefficients free."""
    from scipy.interpolate import BSpline

    a = np.linspace(0.0, 1.2, 301)
    pts = np.round(np.c_[30.0 * np.cos(a), 30.0 * np.sin(a), 0.5 * a], 4)
    t0 = np.array([0.0, 1.0, 0.5 / 30.0]) / math.hypot(1.0, 0.5 / 30.0) if tangents[0] else None
    t1 = (np.array([-math.sin(1.2), math.cos(1.2), 0.5 / 30.0]) / math.hypot(1.0, 0.5 / 30.0)
          if tangents[1] else None)
    spl = fit_run(pts, TOL, tangents=(t0, t1))
    assert spl is not None
    u = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    B = BSpline.design_matrix(u, spl.t, 3).toarray()
    m = B.shape[1]
    fixed = {0: pts[0], m - 1: pts[-1]}
    dirs = []
    if t0 is not None:
        fixed[1] = pts[0]
        dirs.append((1, t0))
    if t1 is not None:
        fixed[m - 2] = pts[-1]
        dirs.append((m - 2, -t1))
    free = [j for j in range(m) if j not in fixed]
    rhs = pts - sum(np.outer(B[:, j], p) for j, p in fixed.items())
    # unknowns: x, y, z of the free coefficients, then one length per tangent
    A = np.zeros((3 * len(pts), 3 * len(free) + len(dirs)))
    for d in range(3):
        A[d * len(pts):(d + 1) * len(pts), d * len(free):(d + 1) * len(free)] = B[:, free]
        for i, (j, direction) in enumerate(dirs):
            A[d * len(pts):(d + 1) * len(pts), 3 * len(free) + i] = B[:, j] * direction[d]
    x = np.linalg.lstsq(A, rhs.T.reshape(-1), rcond=None)[0]
    c = np.zeros((m, 3))
    for j, p in fixed.items():
        c[j] = p
    c[free] = x[:3 * len(free)].reshape(3, len(free)).T
    for i, (j, direction) in enumerate(dirs):
        c[j] = c[j] + x[3 * len(free) + i] * direction
    np.testing.assert_allclose(spl.c, c, rtol=0, atol=1e-9)
