"""S-curve G64 blends of the kinks at line/arc, arc/line, arc/arc and line/merged-curve junctions.

Under the S-curve such a kink used to be passed at about 0.1 J Ts^2 / turn (a stop); it is now replaced by a
curvature-continuous quintic within the path tolerance (:func:`interpolators.lookahead.blend_corners`). Each
program is checked for its cycle time (against the same program under the trapezoid and under G61), the speed
at the kink, every axis limit, the distance of the samples from the programmed path and the blocks of the
samples.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators import interpolate, parse_program
from interpolators.lookahead import blend_corners
from tests.interpolators.setpoint_checks import check_limits
from tests.interpolators.test_interpolate import LIMITS
from toolpaths.geometry import Arc, Line, SplineCurve

TOLERANCE = 0.01


def _line_arc_line(turn: float, *, mode: str = "G64 P0.01", feed: float = 1200.0) -> str:
    """A 5 mm line into a full G3 circle of radius 1 mm at (1, 0), then a 5 mm line; both lines meet the
    circle (tangent +Y at (1, 0)) with a kink of ``turn`` rad."""
    dx, dy = math.sin(turn), math.cos(turn)
    return (f"G21 G90 G17 {mode}\nG0 X{1 - 5 * dx:.6f} Y{-5 * dy:.6f}\nF{feed:.0f}\nG1 X1 Y0\n"
            f"G3 X1 Y0 I-1 J0\nG1 X{1 + 5 * dx:.6f} Y{5 * dy:.6f}\nM30\n")


def _arc_arc(*, mode: str = "G64 P0.05") -> str:
    """A G2 half circle of radius 5 into a G3 arc of radius 4 whose start tangent is turned 0.4 rad from it."""
    # the G2 arrives at (10, 0) along -Y; the G3 leaves along -Y turned 0.4 rad towards +X, its centre on the left
    c = (4.0 * math.cos(0.4), 4.0 * math.sin(0.4))  # centre of the second arc from (10, 0)
    end = math.pi + 0.4 + 1.5
    return (f"G21 G90 G17 {mode}\nG0 X0 Y0\nF600\nG2 X10 Y0 I5 J0\n"
            f"G3 X{10 + c[0] + 4 * math.cos(end):.6f} Y{c[1] + 4 * math.sin(end):.6f} "
            f"I{c[0]:.6f} J{c[1]:.6f}\nM30\n")


def _line_into_chords(*, kink: float = 0.2, radius: float = 10.0, n: int = 300, feed: float = 900.0,
                      tolerance: float = 0.1) -> str:
    """A line along X into a quarter circle of ``n`` 4-decimal chords turned ``kink`` rad against the line (merged
    into one curve under G64), then a line with the same kink out of it."""
    pts = []
    for k in range(n + 1):
        a = kink + 0.5 * math.pi * k / n
        pts.append((round(radius * math.sin(a) - radius * math.sin(kink), 4),
                    round(radius * math.cos(kink) - radius * math.cos(a), 4)))
    end = 0.5 * math.pi + 2 * kink
    last = (pts[-1][0] + 10 * math.cos(end), pts[-1][1] + 10 * math.sin(end))
    body = "\n".join(f"G1 X{x:.4f} Y{y:.4f}" for x, y in [*pts, last])
    return f"G21 G90 G17 G64 P{tolerance}\nG0 X-10 Y0\nF{feed:.0f}\n{body}\nM30\n"


def _distance_from_program(sp, prog) -> np.ndarray:
    """Distance [mm] of each sample from the nearest programmed line or arc of the program (XY)."""
    pts = sp.position[:, :2]
    best = np.full(len(pts), np.inf)
    for b in prog.blocks:
        seg = b.segment
        if isinstance(seg, Line) and seg.length > 0:
            a, d = seg.start[:2], seg.end[:2] - seg.start[:2]
            t = np.clip((pts - a) @ d / (d @ d), 0.0, 1.0)
            best = np.minimum(best, np.linalg.norm(pts - a - t[:, None] * d, axis=1))
        elif isinstance(seg, Arc):
            on = seg.point_at(np.linspace(0.0, seg.length, 4001))[:, :2]
            for chunk in np.array_split(np.arange(len(pts)), max(1, len(pts) // 500)):
                dist = np.linalg.norm(pts[chunk, None, :] - on[None, :, :], axis=2).min(axis=1)
                best[chunk] = np.minimum(best[chunk], dist)
    return best


def _speed_near(sp, point: tuple[float, float], radius: float = 0.02) -> float:
    """Lowest XY path speed [mm/s] of the samples within ``radius`` mm of ``point``."""
    near = np.linalg.norm(sp.position[:, :2] - np.asarray(point), axis=1) <= radius
    assert near.any()
    return float(np.linalg.norm(sp.velocity[near][:, :2], axis=1).min())


def test_blend_corners_replaces_a_line_arc_kink_by_a_g2_curve():
    line = Line([0.0, -5.0, 0.0], [1.0, 0.0, 0.0])
    arc = Arc([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], ccw=True)
    segs, blocks = blend_corners([line, arc], [3, 4], [TOLERANCE], curvature_continuous=True)
    assert [type(s) for s in segs] == [Line, SplineCurve, Arc]
    assert blocks == [3, 3, 4]  # the blend belongs to the incoming block
    cut, blend, rest = segs
    assert np.array_equal(cut.end, blend.start) and np.array_equal(blend.end, rest.start)
    assert np.allclose(blend.tangent_at(0.0), line.direction, atol=1e-9)
    assert np.allclose(blend.curvature_at(0.0), 0.0, atol=1e-6)
    assert np.allclose(blend.tangent_at(blend.length), rest.tangent_at(0.0), atol=1e-9)
    assert np.allclose(blend.curvature_at(blend.length), rest.curvature_at(0.0), atol=1e-6)
    assert rest.radius == pytest.approx(1.0) and rest.center.tolist() == [0.0, 0.0, 0.0]
    # the trapezoid keeps the kink (line/line corners only)
    segs, blocks = blend_corners([line, arc], [3, 4], [TOLERANCE], curvature_continuous=False)
    assert segs[0] is line and segs[1] is arc and blocks == [3, 4]


@pytest.mark.parametrize(("turn", "tolerance", "feed", "ratio"), [(0.1, 0.01, 1200.0, 1.2), (0.3, 0.05, 600.0, 1.06)])
def test_line_arc_kinks_pass_at_speed_within_the_tolerance(turn, tolerance, feed, ratio):
    """S-curve / trapezoid time: 1.277 and 1.090 with the kinks as stops, now 1.161 and 1.041."""
    prog = parse_program(_line_arc_line(turn, mode=f"G64 P{tolerance}", feed=feed))
    sp = interpolate(prog, profile="scurve", limits=LIMITS)
    exact = interpolate(parse_program(_line_arc_line(turn, mode="G61", feed=feed)), profile="scurve", limits=LIMITS)
    trap = interpolate(prog, profile="trapezoid", limits=LIMITS)
    check_limits(sp, prog, LIMITS, jerk=True, feed=True)
    assert _distance_from_program(sp, prog).max() <= tolerance * (1 + 1e-6)
    # the kinks are passed at speed, not stopped at; the block order is kept
    assert _speed_near(sp, (1.0, 0.0), radius=tolerance + 0.01) > 2.0
    assert _speed_near(exact, (1.0, 0.0)) < 0.1
    assert np.all(np.diff(sp.block) >= 0)
    assert sp.duration < exact.duration - 0.05
    assert sp.duration < ratio * trap.duration


def test_trapezoid_and_g61_keep_the_line_arc_kink():
    for text, profile in ((_line_arc_line(0.3), "trapezoid"), (_line_arc_line(0.3, mode="G61"), "scurve")):
        prog = parse_program(text)
        sp = interpolate(prog, profile=profile, limits=LIMITS)
        k = next(i for i, b in enumerate(prog.blocks) if isinstance(b.segment, Arc))
        pts = sp.position[sp.block == k][:, :2]
        assert len(pts) > 100
        assert np.abs(np.hypot(pts[:, 0], pts[:, 1]) - 1.0).max() <= 1e-9  # every sample of the arc on its circle
        assert _speed_near(sp, (1.0, 0.0)) < 0.1  # the kink is a stop


def test_arc_arc_kink_passes_at_speed():
    """S-curve / trapezoid time: 1.034 with the kink as a stop, now 1.013."""
    prog = parse_program(_arc_arc())
    sp = interpolate(prog, profile="scurve", limits=LIMITS)
    exact = interpolate(parse_program(_arc_arc(mode="G61")), profile="scurve", limits=LIMITS)
    check_limits(sp, prog, LIMITS, jerk=True, feed=True)
    assert _distance_from_program(sp, prog).max() <= 0.05 * (1 + 1e-6)
    assert _speed_near(sp, (10.0, 0.0), radius=0.06) > 2.0
    assert _speed_near(exact, (10.0, 0.0)) < 0.1
    assert sp.duration < exact.duration - 0.02
    assert sp.duration < 1.02 * interpolate(prog, profile="trapezoid", limits=LIMITS).duration


def test_line_into_merged_chords_with_a_kink():
    """S-curve / trapezoid time: 1.064 with the kinks as stops, 1.038 with the kink blends in the (1 - FIT_SHARE)
    of the tolerance the fit left them, now 1.027: they take what the fit's own deviation leaves (0.1 mm less
    about 0.002 mm here), passing the kinks at 15.0 mm/s instead of 13.0."""
    prog = parse_program(_line_into_chords())
    sp = interpolate(prog, profile="scurve", limits=LIMITS)
    check_limits(sp, prog, LIMITS, jerk=True, feed=True)
    # the merged curve keeps within its fit's deviation, the kink blends beside it within the rest
    assert _distance_from_program(sp, prog).max() <= 0.1 * (1 + 1e-6)
    first, last = prog.blocks[3].segment, prog.blocks[-2].segment
    assert _speed_near(sp, tuple(first.end[:2]), 0.1) > 14.0  # the blend passes within P = 0.1 of the kink
    assert _speed_near(sp, tuple(last.start[:2]), 0.1) > 14.0
    assert sp.duration < 1.035 * interpolate(prog, profile="trapezoid", limits=LIMITS).duration
    assert np.all(np.diff(sp.block) >= 0)


def test_a_kink_into_merged_chords_that_end_the_program():
    """A line, then a 0.3 rad kink into ten 0.04 mm chords of a 2 mm radius (merged into a curve of one piece)
    that end the chain: the blend trims that piece, which is then the chain's last segment; its samples carry
    the run's chords (the lead's review: it raised IndexError looking for a segment after it)."""
    chords, x, y, ang = [], 0.0, 0.0, 0.3
    for _ in range(10):
        ang += 0.04 / 2.0
        x, y = x + 0.04 * math.cos(ang), y + 0.04 * math.sin(ang)
        chords.append(f"G1 X{x:.4f} Y{y:.4f}")
    prog = parse_program("G21 G90 G17 G64 P0.1\nG0 X-5 Y0\nF600\nG1 X0 Y0\n" + "\n".join(chords) + "\nM30\n")
    sp = interpolate(prog, profile="scurve", limits=LIMITS)
    check_limits(sp, prog, LIMITS, jerk=True, feed=True)
    assert _distance_from_program(sp, prog).max() <= 0.1 * (1 + 1e-6)
    assert np.all(np.diff(sp.block) >= 0) and sp.block[-1] == len(prog.blocks) - 1
    assert sp.position[-1, :2] == pytest.approx([round(x, 4), round(y, 4)], abs=1e-9)


@pytest.mark.parametrize("stretch", [1.0, 1.3])
def test_hermite_quintic_matches_both_ends_and_trims(stretch):
    t_in, k_in = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.5, 0.0])
    t_out, k_out = np.array([0.0, 1.0, 0.0]), np.array([-0.25, 0.0, 0.0])
    curve = SplineCurve.hermite([0.0, 0.0, 0.0], t_in, k_in, [2.0, 2.0, 0.0], t_out, k_out, stretch=stretch)
    assert curve.start.tolist() == [0.0, 0.0, 0.0] and curve.end.tolist() == [2.0, 2.0, 0.0]
    assert np.allclose(curve.tangent_at(0.0), t_in, atol=1e-12)
    assert np.allclose(curve.curvature_at(0.0), k_in, atol=1e-9)
    assert np.allclose(curve.tangent_at(curve.length), t_out, atol=1e-12)
    assert np.allclose(curve.curvature_at(curve.length), k_out, atol=1e-9)
    part = curve.trimmed(0.5, curve.length - 0.25)
    assert part.length == pytest.approx(curve.length - 0.75, abs=1e-6)  # the arc-length table inverted to 1e-6
    assert np.allclose(part.start, curve.point_at(0.5), atol=1e-12)
    assert np.allclose(part.tangent_at(0.0), curve.tangent_at(0.5), atol=1e-9)
    assert part.end.tolist() == curve.point_at(curve.length - 0.25).tolist()
