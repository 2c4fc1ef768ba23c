"""Dense CAM code on tight curves: helical entries of short chords on small radii (S-curve).

A helix of 50 um chords on a radius of 0.24 mm turns by 0.21 rad per chord, above DENSE_MAX_TURN: its
chords were blended one junction at a time, which the jerk limit holds to about half the feed. Under
the S-curve such chords now merge into one curve (:func:`interpolators.dense.curve_junctions`). Asserted:
cycle times against the same helix programmed as one G2 with P, the setpoints' distance from the
chords, the axis limits (finite differences), the blocks; the trapezoid's runs are unchanged.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators import DEFAULT_LIMITS, interpolate, parse_program
from interpolators.dense import DENSE_MAX_TURN, curve_junctions, merge_dense_runs
from tests.interpolators.setpoint_checks import distance_to_path, xyz
from toolpaths.geometry import Line

#: Relative margin of the finite-difference limit checks (as in test_dense_code.py).
LIMIT_MARGIN = 1e-6
TOL = 0.01  # G64 without P: the default tolerance [mm]


def _helix_points(radius: float, chord: float, turns: int, pitch: float, decimals: int) -> np.ndarray:
    """Points of a helix (down in Z by ``pitch`` per turn) ``chord`` [mm] apart, rounded as CAM writes them."""
    n_turn = round(2 * math.pi * radius / chord)
    a = 2 * np.pi * np.arange(turns * n_turn + 1) / n_turn
    z = 1.0 - pitch * a / (2 * np.pi)
    return np.round(np.c_[radius * np.cos(a), radius * np.sin(a), z], decimals)


def _chords_program(pts: np.ndarray, decimals: int) -> str:
    f = f"{{:.{decimals}f}}"
    lines = ["G21 G90 G17 G64", f"G0 X{f.format(pts[0, 0])} Y{f.format(pts[0, 1])} Z1", "G1 F400"]
    lines += [f"G1 X{f.format(x)} Y{f.format(y)} Z{f.format(z)}" for x, y, z in pts[1:]]
    return "\n".join(lines) + "\nM2\n"


def _arc_program(radius: float, turns: int, pitch: float) -> str:
    return (f"G21 G90 G17 G64\nG0 X{radius} Y0 Z1\nG2 X{radius} Y0 I{-radius} J0 Z{1.0 - turns * pitch:.4f} "
            f"P{turns} F400\nM2\n")




def _worst_ratios(sp) -> tuple[float, float, float]:
    """Largest |v|, |a|, |j| of any axis (finite differences) over its limit."""
    Ts = sp.sample_time
    worst = [0.0, 0.0, 0.0]
    for i, ax in enumerate(sp.axes):
        lim = DEFAULT_LIMITS[ax]
        v = np.diff(sp.position[:, i]) / Ts
        a = np.diff(v) / Ts
        j = np.diff(a) / Ts
        for k, (x, m) in enumerate(((v, lim.velocity), (a, lim.acceleration), (j, lim.jerk))):
            worst[k] = max(worst[k], float(np.abs(x).max()) / m)
    return worst[0], worst[1], worst[2]


# (radius, chord, decimals, turns, largest time ratio against the arc): the FreeCAD helical entry (3 decimals;
# measured 1.019, 1.899 before the tight-curve rule), a 0.1 mm radius with 30 um chords (1.240, was 2.251) and
# a 40 um radius with 10 um chords (4 decimals; 1.273, was 2.295). On the two smallest radii the fitted cubic,
# its knots at least 4 chords (1.2 rad) apart, bends up to 17 % tighter than the circle and its curvature varies
# (|dk/ds| about 0.6 / r^2), which bounds the speed below the arc's.
HELICES = [(0.24, 0.05, 3, 6, 1.05), (0.1, 0.03, 4, 6, 1.3), (0.04, 0.01, 4, 6, 1.3)]


@pytest.mark.parametrize(("radius", "chord", "decimals", "turns", "ratio"), HELICES)
def test_small_radius_helix_runs_like_the_arc_under_the_scurve(radius, chord, decimals, turns, ratio):
    pitch = 0.1
    pts = _helix_points(radius, chord, turns, pitch, decimals)
    assert np.median(np.abs(np.diff(np.arctan2(pts[:, 1], pts[:, 0])))) > DENSE_MAX_TURN  # tighter than the cap
    program = parse_program(_chords_program(pts, decimals))
    sp = interpolate(program, profile="scurve")
    sp_arc = interpolate(parse_program(_arc_program(radius, turns, pitch)), profile="scurve")
    assert sp.duration <= ratio * sp_arc.duration
    assert distance_to_path(sp) <= TOL
    assert max(_worst_ratios(sp)) <= 1.0 + LIMIT_MARGIN
    # each sample carries the block of a chord near it, in program order, every chord has samples, and the helix
    # ends on its last point
    assert np.all(np.diff(sp.block) >= 0)
    chords = [i for i, b in enumerate(program.blocks) if b.kind == "line" and b.segment.length > 0]
    assert len(chords) == len(pts) - 1 and set(chords) <= set(sp.block.tolist())
    on = np.isin(sp.block, chords)
    start = np.array([program.blocks[b].start for b in sp.block[on]])
    ab = np.array([program.blocks[b].target for b in sp.block[on]]) - start
    t = np.clip(np.einsum("ij,ij->i", xyz(sp)[on] - start, ab) / np.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
    assert np.linalg.norm(xyz(sp)[on] - start - t[:, None] * ab, axis=1).max() <= TOL
    assert np.allclose(xyz(sp)[-1], pts[-1], atol=1e-12)


def test_small_radius_helix_trapezoid_is_unchanged():
    """Under the trapezoid the tight chords stay per-junction arc blends (of about the helix' radius): as fast as
    the arc, so nothing merges and the setpoints are those of the per-junction planning."""
    pts = _helix_points(0.24, 0.05, 6, 0.1, 3)
    segs = [Line(pts[k], pts[k + 1]) for k in range(len(pts) - 1)]
    n = len(segs)
    args = (segs, list(range(n)), [400 / 60] * n, [False] * n, [TOL] * n)
    assert merge_dense_runs(*args)[2] == {}
    runs = merge_dense_runs(*args, curvature_continuous=True)[2]
    assert len({id(r) for r in runs.values()}) == 1  # the whole helix is one curve
    sp = interpolate(parse_program(_chords_program(pts, 3)), profile="trapezoid")
    sp_arc = interpolate(parse_program(_arc_program(0.24, 6, 0.1)), profile="trapezoid")
    assert sp.duration <= 1.02 * sp_arc.duration  # measured 0.996: the blends cut inside the chords
    assert distance_to_path(sp) <= TOL
    assert max(_worst_ratios(sp)[:2]) <= 1.0 + LIMIT_MARGIN


def test_curve_junctions_keep_isolated_corners():
    """A junction sharper than DENSE_MAX_TURN stays inside a run only on a tight curve (its neighbours turn
    alike: both neighbours together turn at least CURVE_TURN_SHARE of it) and only under the S-curve; an isolated
    corner, one sharper than DENSE_MAX_CURVE_TURN and one next to an arc (NaN) end the run."""
    turns = np.array([0.01, 0.01, 0.3, 0.01, 0.21, 0.25, 0.19, 0.23, 0.6, 0.6, 0.6, 0.2, np.nan, 0.3, 0.3])
    want_trapezoid = turns <= DENSE_MAX_TURN
    assert np.array_equal(curve_junctions(turns, curvature_continuous=False), want_trapezoid)
    got = curve_junctions(turns, curvature_continuous=True)
    # 0.3 between 0.01s: a corner (0.02 < 0.15); 0.21 after a 0.01, before 0.25: the curve's first junction
    # (0.26 >= 0.105); 0.6: sharper than DENSE_MAX_CURVE_TURN; 0.3 next to an arc or at the chain's end
    assert got.tolist() == [True, True, False, True, True, True, True, True, False, False, False, True, False,
                            False, False]


def test_corner_between_tight_chords_stays_a_corner():
    """Two dense runs of 20 um chords meeting at a 0.35 rad corner: merged on each side, the corner honoured
    (the samples pass within the tolerance of it) under the S-curve as under the trapezoid."""
    s = np.arange(0, 101) * 0.02
    first = np.c_[s, 0.002 * s**2, np.zeros_like(s)]
    d = np.array([math.cos(0.35), math.sin(0.35), 0.0])
    second = first[-1] + s[1:, None] * d
    pts = np.round(np.vstack([first, second]), 4)
    segs = [Line(pts[k], pts[k + 1]) for k in range(len(pts) - 1)]
    n = len(segs)
    runs = merge_dense_runs(segs, list(range(n)), [5.0] * n, [False] * n, [TOL] * n, curvature_continuous=True)[2]
    assert sorted(r.blocks[0] for r in {id(r): r for r in runs.values()}.values()) == [0, 100]
