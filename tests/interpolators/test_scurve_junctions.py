"""S-curve on coarse chords of a curve: chords whose turn times length exceeds DENSITY times the tolerance.

A circle of radius 1 mm written as 0.15 mm chords (4 decimals) turns by 0.15 rad per chord: turn times length is
2.25 times the tolerance of 0.01 mm, so the chords were blended one junction at a time. Under the S-curve each
blend is a clothoid pair within half of its chord, whose jerk holds the speed far below the curve's (2.35 times
the G2 arc's time at F1200). Under the S-curve they now merge into one curve while the sagitta of the curve
through their points fits the tolerance (:data:`interpolators.dense.CURVE_DENSITY`). Asserted: cycle times
against the same path as G2 arcs and against the path length at the feed, the distance from the chords, the axis
limits (finite differences and analytic columns), the blocks; the trapezoid's runs and the G61 stops unchanged.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

from interpolators import DEFAULT_LIMITS, interpolate, parse_program
from interpolators.dense import CURVE_DENSITY, DENSITY, merge_dense_runs
from tests.interpolators.setpoint_checks import check_limits
from toolpaths.geometry import Line

TOL = 0.01  # G64 without P: the default tolerance [mm]
RADIUS, CHORD, TURNS, PITCH = 1.0, 0.15, 5, 0.12


def _points(lead: float = 0.0) -> np.ndarray:
    """The helix' points (4 decimals), down PITCH per turn from Z1; with ``lead`` > 0 the start of a line of that
    length [mm] entering it along its tangent first."""
    n_turn = round(2 * math.pi * RADIUS / CHORD)
    a = -2 * np.pi * np.arange(TURNS * n_turn + 1) / n_turn
    pts = np.round(np.c_[RADIUS * np.cos(a), RADIUS * np.sin(a), 1.0 + PITCH * a / (2 * np.pi)], 4)
    return np.vstack([[RADIUS, lead, 1.0], pts]) if lead > 0 else pts


def _chords(pts: np.ndarray, feed: float, mode: str = "G64") -> str:
    body = "\n".join(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f}" for x, y, z in pts[1:])
    return f"G21 G90 G17 {mode}\nG0 X{pts[0, 0]:.4f} Y{pts[0, 1]:.4f} Z{pts[0, 2]:.4f}\nF{feed:g}\n{body}\nM2\n"


def _arcs(feed: float, lead: float = 0.0) -> str:
    entry = f"G0 X{RADIUS} Y{lead} Z1\nF{feed:g}\n" + (f"G1 X{RADIUS} Y0\n" if lead > 0 else "")
    return (f"G21 G90 G17 G64\n{entry}G2 X{RADIUS} Y0 I{-RADIUS} J0 Z{1.0 - TURNS * PITCH:.4f} P{TURNS}\nM2\n")


def _xyz(sp) -> np.ndarray:
    return sp.position[:, [sp.axis_index(a) for a in "xyz"]]


def _distance_to_chords(sp, program, pts: np.ndarray, step: float = 2e-4) -> float:
    """Worst distance [mm] of the setpoints of the feed moves from the polygon ``pts`` (points ``step`` apart)."""
    dense = np.vstack([a + np.linspace(0.0, 1.0, max(2, math.ceil(np.linalg.norm(b - a) / step)))[:, None] * (b - a)
                       for a, b in zip(pts[:-1], pts[1:])])
    feed = np.array([b.kind == "line" for b in program.blocks])[sp.block]
    return float(cKDTree(dense).query(_xyz(sp)[feed])[0].max()) - step / 2


def _length(pts: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


def test_coarse_chords_lie_between_the_two_density_bounds():
    """The chords are coarser than DENSITY allows and within CURVE_DENSITY: the trapezoid keeps its per-junction
    blends (nothing merges), the S-curve merges the whole helix into one curve."""
    pts = _points()
    d = np.diff(pts, axis=0)
    u = d / np.linalg.norm(d, axis=1)[:, None]
    density = np.arccos(np.clip(np.einsum("ij,ij->i", u[:-1], u[1:]), -1, 1)) * np.linalg.norm(d, axis=1)[1:] / TOL
    assert DENSITY < density.min() and density.max() < CURVE_DENSITY
    segs = [Line(pts[k], pts[k + 1]) for k in range(len(pts) - 1)]
    n = len(segs)
    args = (segs, list(range(n)), [20.0] * n, [False] * n, [TOL] * n)
    assert merge_dense_runs(*args)[2] == {}
    runs = merge_dense_runs(*args, curvature_continuous=True)[2]
    assert len({id(r) for r in runs.values()}) == 1


# (feed [mm/min], largest S-curve time over the arcs' S-curve time): measured 1.007 and 1.144 (2.348 and 2.749
# before the chords merged); at F3000 the fitted curve's curvature varies (|dk/ds|) where the arc's does not.
@pytest.mark.parametrize(("feed", "ratio"), [(1200.0, 1.03), (3000.0, 1.2)])
def test_coarse_chords_run_like_the_arc_under_the_scurve(feed, ratio):
    pts = _points()
    program = parse_program(_chords(pts, feed))
    sp = interpolate(program, profile="scurve")
    sp_arc = interpolate(parse_program(_arcs(feed)), profile="scurve")
    assert _length(pts) / (feed / 60.0) < sp.duration <= ratio * sp_arc.duration
    assert _distance_to_chords(sp, program, pts) <= TOL
    check_limits(sp, program, DEFAULT_LIMITS, jerk=True, feed=True)
    chords = [i for i, b in enumerate(program.blocks) if b.kind == "line"]
    assert len(chords) == len(pts) - 1 and set(chords) <= set(sp.block.tolist())
    assert np.all(np.diff(sp.block) >= 0)
    assert np.array_equal(_xyz(sp)[-1], pts[-1])


def test_tangent_line_into_coarse_chords_runs_like_line_and_arc():
    """A 5 mm line entering the chords along their tangent (a line/curve junction with a curvature step) runs as
    the line into the G2 arcs does (measured 0.993; 2.112 before the chords merged)."""
    pts = _points(lead=5.0)
    program = parse_program(_chords(pts, 1200.0))
    sp = interpolate(program, profile="scurve")
    sp_arc = interpolate(parse_program(_arcs(1200.0, lead=5.0)), profile="scurve")
    assert sp.duration <= 1.03 * sp_arc.duration
    assert _distance_to_chords(sp, program, pts) <= TOL
    check_limits(sp, program, DEFAULT_LIMITS, jerk=True, feed=True)


def test_coarse_chords_under_g61_stop_at_every_chord():
    """Under G61 nothing merges: each chord starts and ends at rest, on its programmed end point."""
    pts = _points()[:12]
    program = parse_program(_chords(pts, 1200.0, mode="G61"))
    sp = interpolate(program, profile="scurve")
    xyz = _xyz(sp)
    for k in range(1, len(pts)):
        at = np.flatnonzero(np.all(xyz == pts[k], axis=1))
        assert len(at) and np.all(sp.velocity[at] == 0.0), k
    check_limits(sp, program, DEFAULT_LIMITS, jerk=True, feed=True)
