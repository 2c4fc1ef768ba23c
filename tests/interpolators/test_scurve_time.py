"""S-curve cycle times of CAM chords against what the axis limits allow (program cycle time, never wall-clock).

Both programs are modelled on FreeCAD profile paths (corpus program 0274): tight fillets (radius 0.1-0.2 mm)
written as chords of 10-30 um with rounded end points (the generators of ``benchmarks/dense_code.py``, which times
the same cases). Each test checks the cycle time against a reference
planned in the same run, the axis limits on the setpoints and the path within the G64 tolerance of the chords.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmarks.dense_code import alternating_circle, fillet_square
from interpolators import DEFAULT_LIMITS, interpolate, parse_program
from interpolators.kinematics import CURVE_BOUND_MARGIN, JERK_SPEED_SHARE, AxisLimitArrays, curve_limits
from tests.interpolators.setpoint_checks import check_limits, distance_to_path
from toolpaths.geometry import SplineCurve

TOL = 0.01  # G64 P0.01 [mm]


def _plan(text: str, profile: str):
    prog = parse_program(text)
    sp = interpolate(prog, profile=profile)
    check_limits(sp, prog, {a: DEFAULT_LIMITS[a] for a in sp.axes}, jerk=profile == "scurve", feed=True)
    return sp


def test_fillet_chords_slow_down_at_the_fillet_only():
    """The fillets (radius 0.1 mm, 10 chords of 16 um, jerk-bound speed about 6 mm/s against F600 = 10 mm/s) lie
    inside 0.5 mm pieces of the merged curve with straight chords; cut where the speed bound changes
    (``dense._bound_breaks``), only the fillet runs slow: 1.675 s, 1.16 times the trapezoid (4.26 s, 2.94 times,
    when the whole piece took the fillet's bound)."""
    text = fillet_square(0.1, 10)
    scurve, trapezoid = _plan(text, "scurve"), _plan(text, "trapezoid")
    length = 4 * (2.75 + 0.25 + 0.5 * math.pi * 0.1)  # about: the chords' length [mm]
    assert scurve.meta["duration"] > length / 10.0
    assert scurve.meta["duration"] <= 1.3 * trapezoid.meta["duration"]
    assert distance_to_path(scurve) <= TOL


def test_tight_circle_of_alternating_turns_merges():
    """Chords turning 0.1 and 0.22 rad in turn (above DENSE_MAX_TURN every other junction): their neighbours
    together turn more than half as much, so the circle is one merged curve (``dense.curve_junctions``) and runs
    within 1.25 times the time of the same two laps as G3 arcs of the mean radius (0.494 s against 0.424 s; 1.07 s,
    2.5 times, with each 0.22 rad junction a corner blended by a clothoid pair). The fitted cubic's curvature
    varies along the noisy chords, which bounds its speed below the arc's."""
    text, arcs = alternating_circle((0.1, 0.22))
    scurve = _plan(text, "scurve")
    assert scurve.meta["duration"] <= 1.25 * _plan(arcs, "scurve").meta["duration"]
    assert scurve.meta["duration"] <= 0.55
    assert distance_to_path(scurve) <= TOL


def test_curve_bounds_keep_the_jerk_vector_norm_within_the_limit():
    """On a curve piece (a quintic turning from +X to +Y through curvature 0 to 0.4 1/mm and back) the jerk vector
    at speed ``v``, acceleration ``a`` and path jerk ``j`` is ``(j - k^2 v^3) t + (3 k v a + k' v^3) n``: its two
    parts are orthogonal, so the speed bound takes the norm ``v^3 |(k^2, k')| = JERK_SPEED_SHARE J`` (the sum
    ``k^2 + k'`` before) and the path jerk what keeps ``(|j| + k^2 v^3)^2 + (3 k v a + k' v^3)^2 = J^2``, both
    exactly at the bounds; the speed is higher than the sum allowed."""
    curve = SplineCurve.hermite(np.zeros(3), np.array([1.0, 0, 0]), np.zeros(3), np.array([3.0, 3.0, 0]),
                                np.array([0, 1.0, 0]), np.zeros(3))
    limits = AxisLimitArrays(dict(DEFAULT_LIMITS), {0, 1})
    v, a, j = curve_limits([curve], np.array([1e3]), limits, jerk_limited=True)
    kappa, dkappa, _ = curve.bounds()
    kappa, dkappa = kappa * CURVE_BOUND_MARGIN, dkappa * CURVE_BOUND_MARGIN
    J = DEFAULT_LIMITS["x"].jerk
    assert kappa > 0.1 and dkappa > 0.1 * kappa * kappa
    assert v[0] ** 3 * math.hypot(kappa * kappa, dkappa) == pytest.approx(JERK_SPEED_SHARE * J, rel=1e-9)
    assert v[0] > (JERK_SPEED_SHARE * J / (kappa * kappa + dkappa)) ** (1.0 / 3.0)
    normal = 3.0 * kappa * v[0] * a[0] + dkappa * v[0] ** 3
    assert math.hypot(j[0] + kappa * kappa * v[0] ** 3, normal) == pytest.approx(J, rel=1e-9)


@pytest.mark.parametrize("turn", [0.05, 0.5, 1.5])
def test_curve_bounds_at_the_higher_jerk_share_leave_path_jerk(turn):
    """At jerk_share 0.6 (interpolate._faster_jerk_share's second plan) a curve whose bound is set by dk/ds (a
    short quintic turning ``turn`` rad, from and back to curvature 0) or by k^2 still keeps a path jerk of at least
    0.26 J (``sqrt(1 - (0.3 + 0.6 sin(phi))^2) - 0.6 cos(phi)``, phi the angle of ``(k^2, dk/ds)``; measured phi 89,
    80 and 47 deg: 0.43, 0.35 and 0.265 J, the last next to the least, 0.2646 J at 48.6 deg), and its speed bound
    is (0.6 / 0.3)^(1/3) times the one at JERK_SPEED_SHARE."""
    end = np.array([math.cos(turn), math.sin(turn), 0.0])
    curve = SplineCurve.hermite(np.zeros(3), np.array([1.0, 0, 0]), np.zeros(3), 2.0 * np.array([1.0, 0, 0])
                                + 0.5 * end, end, np.zeros(3))
    limits = AxisLimitArrays(dict(DEFAULT_LIMITS), {0, 1})
    J = DEFAULT_LIMITS["x"].jerk
    v3, _, _ = curve_limits([curve], np.array([1e4]), limits, jerk_limited=True)
    v6, a6, j6 = curve_limits([curve], np.array([1e4]), limits, jerk_limited=True, jerk_share=0.6)
    assert j6[0] >= 0.26 * J and a6[0] > 0
    assert v6[0] == pytest.approx(v3[0] * 2.0 ** (1.0 / 3.0), rel=1e-9)


@pytest.mark.parametrize("text, seconds, forced", [
    # a full circle R2 from rest at F3000: its speed changes on the curve; at 0.6 of J for v^3 k^2 the
    # acceleration ramps would take longer than the higher cruise gains (0.619 s): the 0.3 plan is kept
    ("G21 G90 G17 G61\nG0 X2 Y0\nF3000\nG3 X2 Y0 I-2 J0\nM30\n", 0.592, 0.619),
    # a quarter arc R0.5 from rest at F6000: likewise (0.234 s at 0.6)
    ("G21 G90 G17 G61\nG0 X0.5 Y0\nF6000\nG3 X0 Y0.5 I-0.5 J0\nM30\n", 0.214, 0.234),
    # a helix R1 of three turns at F2400: cruising on the curve, the 0.6 plan (0.980 s at 0.3)
    ("G21 G90 G17 G61\nG0 X1 Y0 Z0\nF2400\nG3 X1 Y0 Z-3 I-1 J0 P3\nM30\n", 0.896, 0.896),
    # line, G2 R1 half circle, line under G64 P0.01 at F3000: the lines change the speed (0.635 s at 0.3)
    ("G21 G90 G17 G64 P0.01\nG0 X0 Y-5\nF3000\nG1 X0 Y0\nG2 X2 Y0 R1\nG1 X2 Y-5\nM30\n", 0.601, 0.601),
])
def test_curve_jerk_share_follows_need(text, seconds, forced):
    """Under the S-curve each chain is planned with its curves' speed at JERK_SPEED_SHARE (0.3) and at 0.6 of the
    jerk limit for ``v^3 |(k^2, dk/ds)|`` (interpolate._faster_jerk_share), and keeps the faster: cruising on a
    curve needs the jerk for ``v^3 k^2`` only, changing speed on it for ``3 k v a`` and the path jerk too. Cycle
    times measured, ``forced`` the time with 0.6 on every chain; every axis limit held on the setpoints."""
    sp = _plan(text, "scurve")
    assert sp.meta["duration"] == pytest.approx(seconds, abs=1.5e-3)
    assert sp.meta["duration"] <= forced + 1e-9
