"""Look-ahead across blocks that move rotary (A B C) and secondary linear (U V W) axes under G64.

Two consecutive feed moves that both move X/Y/Z and an axis beyond them are passed at speed when
every axis' velocity step at their junction fits in one sample within the share of its limits
that the chain keeps in reserve: the rule ``lookahead.py`` and ``kinematics.junction_speed_limit``
apply to the X, Y, Z tangent of unblended junctions, applied per axis to the rates ``dr_i/ds``.
Such junctions are not blended in X, Y, Z: the axes follow the programmed segments, exactly or across a ramp
of a rate step within 0.9 of the tolerance (``interpolate._ramped_extra``). Runs of dense short
lines are merged, X, Y, Z into one curve and the other axes into one spline along it, within the
tolerance (``tests/interpolators/test_rotary_chains.py``). Every limit holds, checked here by finite
differences of the sampled positions.
"""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import interpolate, parse_program
from interpolators.context import INTERPOLATION_CONTEXT
from interpolators.limits import AxisLimits
from tests.interpolators.setpoint_checks import check_limits
from tests.interpolators.test_secondary_axes import LIMITS

CTX = INTERPOLATION_CONTEXT


def _wrap(mode: str, n: int = 200, step: float = 0.5) -> str:
    """A cylinder wrap: X at ``step`` mm per block, A and W changing their rates gently, then a
    reversal back to the start."""
    lines = [f"G21 G90 {mode} G0 X0 A0 W0", "G1 F1200"]
    lines += [f"X{step * i:.4f} A{20 * np.sin(i / 40):.4f} W{2 * np.sin(i / 30):.4f}" for i in range(1, n + 1)]
    lines.append("G1 X0 A0 W0")
    return "\n".join(lines) + "\n"


def _at_rest(sp, blocks: range) -> int:
    """Samples at rest (every axis) inside the given blocks."""
    still = np.all(np.abs(sp.velocity) < 1e-9, axis=1)
    return int(np.sum(still & (sp.block >= blocks.start) & (sp.block < blocks.stop)))


def _on_segments(sp, prog, tolerance: float = 0.0) -> None:
    """Every sample lies on its block's programmed segment: the axes in proportion to X, within ``tolerance``
    (deg on A, mm on W; 0: exactly, up to rounding)."""
    x, a, w = (sp.position[:, sp.axes.index(k)] for k in ("x", "a", "w"))
    for k in np.unique(sp.block):
        b = prog.blocks[k]
        if b.length == 0:
            continue
        rows = sp.block == k
        share = (x[rows] - b.start[0]) / (b.target[0] - b.start[0])
        assert np.all((share > -1e-9) & (share < 1 + 1e-9)), k
        for col, i in ((a, 0), (w, 5)):
            want = b.extra_start[i] + share * (b.extra_target[i] - b.extra_start[i])
            assert np.all(np.abs(col[rows] - want) <= tolerance + 1e-9), k


@pytest.mark.parametrize("profile, sample_time", [("trapezoid", 1e-3), ("trapezoid", 4e-3), ("scurve", 4e-3)])
def test_g64_passes_gentle_junctions_at_speed_within_every_limit(profile, sample_time):
    g61 = parse_program(_wrap("G61"), context=CTX)
    g64 = parse_program(_wrap("G64 P0.01"), context=CTX)
    sp61 = interpolate(g61, profile=profile, sample_time=sample_time)
    sp64 = interpolate(g64, profile=profile, sample_time=sample_time)
    assert sp61.axes == sp64.axes == ("x", "a", "w")
    wrap = range(2, 200)
    assert _at_rest(sp61, wrap) >= 198  # exact stop: every block ends at rest
    assert _at_rest(sp64, wrap) == 0  # continuous path: no stop inside the wrap
    assert sp64.duration < 0.9 * sp61.duration
    # the reversal at the end is still a stop, and the program ends where it is programmed
    assert np.allclose(sp64.position[-1], 0.0)
    check_limits(sp64, g64, LIMITS, jerk=profile == "scurve")
    _on_segments(sp64, g64, tolerance=0.01)  # G64 P0.01: the axes within 0.01 deg and 0.01 mm (fit_axes)


def test_scurve_rate_steps_of_collinear_blocks_ride_on_ramps():
    """At 1 ms the S-curve's jerk share (``v |dr_i| <= share J_i Ts^2``) leaves the gentle A rate steps of blocks of
    6 mm (longer than ``UNBLENDED_MAX_LENGTH``: not merged) too small a speed to be worth passing unblended; A and W
    follow a quintic ramp of the path across each junction instead, within 0.9 P of their programmed motion
    (``interpolate._ramped_extra``), and the wrap runs at its feed: 120.08 s for 2400 mm at F1200 (before the ramps
    this test asserted more than 60 samples at rest: 73 of them, 126.415 s). The 0.5 mm blocks of ``_wrap`` merge
    and pass without a stop (before the axes were merged with X, Y, Z this test asserted stops on those too)."""
    prog = parse_program(_wrap("G64 P0.01", step=6.0), context=CTX)
    sp = interpolate(prog, profile="scurve", sample_time=1e-3)
    assert _at_rest(sp, range(2, 200)) == 0
    assert sp.duration == pytest.approx(2400.0 / 20.0, abs=0.1)
    check_limits(sp, prog, LIMITS, jerk=True)
    _on_segments(sp, prog, tolerance=0.9 * 0.01)
    dense = parse_program(_wrap("G64 P0.01"), context=CTX)
    sp = interpolate(dense, profile="scurve", sample_time=1e-3)
    assert _at_rest(sp, range(2, 200)) == 0
    check_limits(sp, dense, LIMITS, jerk=True)


def test_a_low_rotary_acceleration_lowers_the_junction_speed():
    prog = parse_program(_wrap("G64 P0.01"), context=CTX)
    slow_a = {**LIMITS, "a": AxisLimits(velocity=180.0, acceleration=200.0, jerk=4000.0, rapid=360.0)}
    fast = interpolate(prog)
    slow = interpolate(prog, limits=slow_a)
    assert slow.duration > fast.duration
    # the check with the lowered limit
    for i, axis in enumerate(slow.axes):
        lim = slow_a[axis]
        acc = np.diff(slow.position[:, i], 2) / slow.sample_time**2
        assert np.all(np.abs(acc) <= lim.acceleration * (1 + 1e-6) + 1e-6), axis


def test_reversals_rapids_and_xyz_only_neighbours_stay_stops():
    text = ("G21 G90 G64 P0.01 G1 X10 A10 F1200\n"
            "X20 A0\n"  # A reverses: its rate step is far too large
            "X30\n"  # X only: a chain of its own
            "X40 A10\n"
            "G0 X50 A20\n")  # a rapid: a chain of its own
    prog = parse_program(text, context=CTX)
    sp = interpolate(prog)
    still = np.all(np.abs(sp.velocity) < 1e-9, axis=1)
    for k in range(4):  # each block ends at rest
        assert still[np.flatnonzero(sp.block == k)[-1] + 1], k
    check_limits(sp, prog, LIMITS)


def test_straight_xyz_with_a_constant_rate_is_one_profile():
    """Blocks on one line with the same A rate per mm: no step at all, the chain needs no reserve
    and runs like one block."""
    split = parse_program("G21 G90 G64 G1 X10 A20 F3000\nX20 A40\nX30 A60\n", context=CTX)
    whole = parse_program("G21 G90 G64 G1 X30 A60 F3000\n", context=CTX)
    a, b = interpolate(split), interpolate(whole)
    assert a.duration == pytest.approx(b.duration, abs=2e-3)
    assert np.allclose(a.position[-1], b.position[-1])
    check_limits(a, split, LIMITS)


@pytest.mark.parametrize("seed", range(12))
def test_random_nine_axis_programs_hold_every_limit(seed):
    """Random G64 programs moving all nine axes (fixed seeds): every axis within its limits by finite
    differences, both profiles, two sample times; many junctions passed at speed."""
    rng = np.random.default_rng(seed)
    lines = [f"G21 G90 G64 P{rng.choice([0.001, 0.01, 0.1])} G1 F{rng.choice([600, 3000, 12000])}"]
    p = np.zeros(9)
    for _ in range(30):
        p = p + np.r_[1.0, rng.normal(0, 0.01, 2), rng.normal(0.5, 0.01, 3), rng.normal(0.2, 0.005, 3)]
        if rng.random() < 0.2:  # now and then a rough step of a few axes, or a rapid
            p = p + rng.normal(0, 1, 9) * (rng.random(9) < 0.3)
        code = "G0" if rng.random() < 0.1 else "G1"
        lines.append(code + " " + " ".join(f"{a}{v:.4f}" for a, v in zip("XYZABCUVW", p)))
    prog = parse_program("\n".join(lines) + "\n", context=CTX)
    passed = 0
    for profile, sample_time in (("trapezoid", 1e-3), ("trapezoid", 4e-3), ("scurve", 1e-3), ("scurve", 4e-3)):
        sp = interpolate(prog, profile=profile, sample_time=sample_time)
        assert sp.axes == ("x", "y", "z", "a", "b", "c", "u", "v", "w")
        assert np.allclose(sp.position[-1], [*prog.blocks[-1].target, *prog.blocks[-1].extra_target])
        check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
        still = np.all(np.abs(sp.velocity) < 1e-9, axis=1)
        ends = [np.flatnonzero(sp.block == k)[-1] + 1 for k in range(len(prog.blocks) - 1)]
        passed += int(np.sum(~still[ends]))
    assert passed > 0
