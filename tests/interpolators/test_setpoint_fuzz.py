"""Setpoints of random programs (``benchmarks/setpoint_fuzz.py``: the readers' generators and CAM-like dense code,
both profiles, random limits and sample times) checked for their invariants, and the failures the fuzzer found,
each as a small hand-written program."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.setpoint_fuzz import cam_program, check_setpoints, junction_tolerances, rotary_cam_program, run_case
from interpolators import AxisLimits, interpolate, parse_program
from interpolators.context import INTERPOLATION_CONTEXT
from interpolators.limits import DEFAULT_LIMITS, DEFAULT_ROTARY_LIMITS
from tests.interpolators.setpoint_checks import check_limits, xyz
from toolpaths.geometry import SplineCurve

#: Seeds run per source: CAM-like code is quick; of the readers' generators, one program each that runs in seconds
#: (``python -m benchmarks.setpoint_fuzz`` runs them at volume).
SEEDS = {"cam": range(6), "tnc_cam": range(8), "rotary_cam": range(6), "linuxcnc": (2,), "fanuc": (0,)}
#: The context of the cases of a rapid passed at speed into a feed move: grbl's (Dialect.rapid_feed_stop; LinuxCNC,
#: Fanuc and Haas stop there).
GRBL = INTERPOLATION_CONTEXT.with_dialect("grbl")


@pytest.mark.parametrize("source", SEEDS)
def test_random_programs_keep_every_setpoint_invariant(source):
    # limits (jerk under the S-curve), feed, path deviation within the block's tolerance, every block end passed
    # within it (on a sample at a stop), the program's end reached, dwells held, finite values, no jumps,
    # Setpoints.block never decreasing; each program under the trapezoid and the S-curve
    outcomes = [(seed, *case) for seed in SEEDS[source] for case in run_case(source, seed)]
    assert [(seed, fails) for seed, outcome, _, _, fails in outcomes if outcome != "ok"] == []
    assert len(outcomes) == 2 * len(SEEDS[source])


def test_cam_programs_are_seeded_and_dense():
    assert cam_program(3) == cam_program(3)
    assert cam_program(3) != cam_program(4)
    assert "CYCL DEF 32.0 TOLERANCE" in "".join(cam_program(s, tnc=True) for s in range(4))


def test_rotary_cam_programs_write_inches_inverse_time_and_alternating_arcs():
    # seed 0: G20 with G64 P in inches, A-C words beside X/Y/Z, G93 sections with an F on every block, then G94 F
    text = rotary_cam_program(0)
    lines = text.splitlines()
    assert lines[0] == "G20 G17 G90 G40 G94"
    g93 = lines.index("G93")
    inverse = lines[g93 + 1:lines.index("G94", g93)]
    assert len(inverse) >= 4 and all(" F" in line for line in inverse)
    assert len({line.split(" F")[1] for line in inverse}) == len(inverse)
    assert any(w in text for w in (" A", " B", " C"))
    prog = parse_program(text, context=INTERPOLATION_CONTEXT)
    assert prog.blocks[-1].target[0] == pytest.approx(float(lines[-2].split("X")[1].split()[0]) * 25.4, abs=1e-9)
    # seed 4 (G21): arcs turning alternately, one after the other, then a staircase's and a chain's tangent arcs
    arcs = [line[:2] for line in rotary_cam_program(4).splitlines() if line[:3] in ("G2 ", "G3 ")]
    assert (len(arcs), sum(a != b for a, b in zip(arcs, arcs[1:]))) == (27, 15)


def test_rotary_cam_staircases_write_an_axis_on_some_blocks_and_on_arcs():
    # seed 0: W indexed alone between lines and arcs, B on an arc; seed 5: axes moving on 22 arcs (a staircase's
    # 12, A on the first, and a tangent chain's)
    lines = rotary_cam_program(0).splitlines()
    assert "G1 W1.0542" in lines
    assert "G2 X0.048094 Y0.252169 B61.2066 I-0.032130 J-0.137175" in lines
    arcs = [line for line in rotary_cam_program(5).splitlines()
            if line[:3] in ("G2 ", "G3 ") and any(f" {a}" in line for a in "ABCUVW")]
    assert len(arcs) == 22
    assert arcs[0] == "G3 X0.594458 Y0.648734 A-9.4203 I-0.031729 J0.005943"


def test_axis_check_names_a_rotary_axis_beyond_its_programmed_values():
    # A runs 0 -> 10 deg on the first line, then holds 10 deg: a sample of A at 10.03 deg on the last line is
    # 0.03 deg beyond the values of the blocks around it, more than P0.01 (read as deg on A)
    prog = parse_program("G21 G64 P0.01\nG0 X0 Y0 A0\nG1 X10 A10 F600\nG1 X20\nG1 X30\nG1 X40\nG1 X50\nM2\n",
                         context=INTERPOLATION_CONTEXT)
    limits = {a: AxisLimits(velocity=100.0, acceleration=1000.0, jerk=1e5) for a in "xya"}
    sp = interpolate(prog, limits=limits, sample_time=0.002)
    assert check_setpoints(prog, sp, limits, "trapezoid") == []
    k = int(np.argmax(sp.block == 5)) + 10
    sp.position[k, sp.axes.index("a")] += 0.03
    fails = [f for f in check_setpoints(prog, sp, limits, "trapezoid") if not f.startswith(("limits", "jump"))]
    assert len(fails) == 2
    assert fails[0].startswith("axis: a at sample")
    assert "(block 5, line 7) 10.03, 0.03 beyond its programmed values 10 .. 10, tolerance 0.01" in fails[0]
    # and 0.03 deg from A programmed at the nearest point of the line (A still there: no slack)
    assert fails[1] == (f"axis_path: a at sample {k} (block 5, line 7) 0.03 beyond its value at the nearest point "
                        "of the path and the slack of its rate, tolerance 0.01")


def test_axis_path_check_measures_at_the_nearest_point_of_the_path():
    # A 0 -> 10 deg along X0 -> X10 (1 deg/mm), then still: a sample of the first line with A 0.05 deg behind is
    # within the A range of its blocks (the axis check passes it) but 0.05 deg from A at its X, above P0.01
    prog = parse_program("G21 G64 P0.01\nG0 X0 Y0 A0\nG1 X10 A10 F600\nG1 X20\nM2\n", context=INTERPOLATION_CONTEXT)
    limits = {a: AxisLimits(velocity=100.0, acceleration=1000.0, jerk=1e5) for a in "xya"}
    sp = interpolate(prog, limits=limits, sample_time=0.002)
    assert check_setpoints(prog, sp, limits, "trapezoid") == []
    k = int(np.argmax(sp.block == 1)) + 200
    assert sp.position[k, sp.axes.index("x")] == pytest.approx(sp.position[k, sp.axes.index("a")], abs=1e-9)
    sp.position[k, sp.axes.index("a")] -= 0.05
    fails = [f for f in check_setpoints(prog, sp, limits, "trapezoid") if not f.startswith(("limits", "jump"))]
    assert len(fails) == 1 and fails[0].startswith(f"axis_path: a at sample {k} (block 1, line 3) 0.0")
    assert fails[0].endswith("tolerance 0.01")


def test_axis_path_check_reads_a_full_circle_at_both_of_its_ends():
    # setpoint fuzzer seed 43461 (rotary_cam), shrunk: B alone to 18.9 deg, then a full circle of radius 0.105 mm
    # taking B to 18.8, then an arc. The circle's start and end are one point, B 18.9 at one and 18.8 at the other:
    # the check read B at whichever of the two its nearest-point search found and named 0.0566 deg beyond P0.01
    # where B ran as programmed (each half of the circle is now searched for its own nearest point)
    text = ("G21 G17 G90 G94 G64\nG0 X-0.0936 Y1.489 Z5 B0\nG1 B18.9 F12000\n"
            "G2 X-0.0936 Y1.489 B18.8 I-0.0734 J0.0759\nG3 X2.116206 Y-6.87574 B105.6 I3.445609 J-3.564\nM2\n")
    prog = parse_program(text, context=INTERPOLATION_CONTEXT)
    limits = {"x": AxisLimits(velocity=6500.0, acceleration=1000.0, jerk=2.3e6),
              "y": AxisLimits(velocity=7700.0, acceleration=5e4, jerk=1.6e7),
              "z": AxisLimits(velocity=2900.0, acceleration=1e4, jerk=1e5),
              "b": AxisLimits(velocity=100.0, acceleration=800.0, jerk=4.5e5)}
    assert [b.kind for b in prog.blocks] == ["rapid", "line", "arc", "arc"]
    for profile in ("trapezoid", "scurve"):
        sp = interpolate(prog, limits=limits, sample_time=0.000629, profile=profile)
        on_circle = sp.position[sp.block == 2, sp.axes.index("b")]
        assert on_circle[0] == pytest.approx(18.9, abs=1e-9)
        assert on_circle[-1] == pytest.approx(18.8, abs=1e-4)
        assert check_setpoints(prog, sp, limits, profile) == []


def test_spline_points_by_arc_length_have_unit_speed_and_the_curvature_as_second_derivative():
    # a cubic B-spline whose parameter speed |C'| runs 1 -> 3: the points at arc length s, differentiated twice,
    # are the curvature vector and once the unit tangent, across the arc-length table's nodes too; u(s) was a
    # cubic Hermite matching du/ds only, and d2u/ds2 stepped at each node: 2.2e-3 /mm off the curvature and
    # 1.6e-4 off unit speed here, on merged curves a jerk spike (setpoint fuzzer cam seed 40037: Y 6.6 % over its
    # jerk limit by finite differences at Ts = 0.28 ms) and a speed excess (tnc_cam seed 1: Y 7e-5 over)
    from scipy.interpolate import BSpline

    knots = np.r_[[0.0] * 4, 1.0, 2.0, [3.0] * 4]
    controls = np.array([[0, 0, 0], [1, 0.5, 0], [2, 2, 0], [4, 3, 0], [7, 3, 0], [10, 2, 0]], dtype=float)
    curve = SplineCurve(BSpline(knots, controls, 3), 0.0, 3.0)
    assert curve.length == pytest.approx(11.0603833, abs=1e-7)
    h = 1e-3
    s = np.arange(h, curve.length - h, h / 7)
    p, ahead, behind = curve.point_at(s), curve.point_at(s + h), curve.point_at(s - h)
    second = (ahead - 2 * p + behind) / h**2
    assert np.linalg.norm(second - curve.curvature_at(s), axis=1).max() < 1e-4
    assert np.linalg.norm((ahead - behind) / (2 * h) - curve.tangent_at(s), axis=1).max() < 1e-6


def test_a_rapid_minutes_into_a_program_keeps_its_jerk_by_finite_differences():
    # a 1700 mm rapid after a 200 s dwell, S-curve, Ts = 0.35 ms: the samples' third differences are the jerk of the
    # acceleration column within 0.02 mm/s^3 (4e-7 of it); the time into each phase was taken from the program's
    # start, whose rounding at 200 s moved the samples by up to 1e-10 mm: 1.33 mm/s^3 off (found: tnc seed 31017,
    # 1e-4 over the jerk limit)
    limits = {a: AxisLimits(velocity=1000.0, acceleration=5000.0, jerk=50000.0, rapid=1000.0) for a in "xyz"}
    prog = parse_program("G21\nG0 X0 Y0 Z0\nG4 P200\nG0 X1700\nM2\n")
    Ts = 0.00035
    sp = interpolate(prog, limits=limits, sample_time=Ts, profile="scurve")
    assert len(sp) == 577145
    fd = np.diff(sp.position[:, 0], 3) / Ts**3
    column = np.diff(sp.acceleration[:, 0]) / Ts
    phase = (np.abs(column[:-2]) > 45000) & (np.abs(column[1:-1]) > 45000) & (np.abs(column[2:]) > 45000)
    phase &= np.sign(column[:-2]) == np.sign(column[2:])
    assert phase.sum() == 1132
    assert np.abs(fd - column[1:-1])[phase].max() < 0.02
    assert np.abs(fd).max() <= 50000.0
    assert sp.position[-1, 0] == 1700.0


def test_phases_minutes_into_a_program_start_where_the_phase_before_ends():
    # B rapids 0 <-> 90 deg at 360 deg/s (default rotary limits, jerk 36000 deg/s^3), S-curve, Ts = 0.25 ms, after a
    # dwell of 0.3 s or 250.3 s (both whole samples): the motion after the dwell is the same to the bit, and within
    # every limit by finite differences. Each phase's start was a sum of the durations from the program's start,
    # rounded by an ulp of that time: after 250 s a phase started 3e-14 s off the end of the one before and B's jerk
    # by finite differences read 1.0000095 x its limit, 0.3 deg/s^3 beyond check_limits' allowance (found: corpus
    # program 0284 at 534 s, 36002.4 for 36000 deg/s^3; setpoint fuzzer rotary_cam seed 43378, C 1.000018 x)
    moves = "".join(f"G0 B{90 if i % 2 == 0 else 0}\nG1 X{i % 2 * 5} F600\n" for i in range(8))
    runs = []
    for dwell in (0.3, 250.3):
        prog = parse_program(f"G21 G90 G94\nG0 B0\nG4 P{dwell}\n{moves}M2\n", context=INTERPOLATION_CONTEXT)
        sp = interpolate(prog, sample_time=0.00025, profile="scurve")
        check_limits(sp, prog, DEFAULT_LIMITS | DEFAULT_ROTARY_LIMITS, jerk=True)
        runs.append(sp.position[round((dwell + 0.1) / 0.00025):])
    assert len(runs[0]) == len(runs[1]) > 30000
    assert np.array_equal(runs[0], runs[1])


def test_scurve_kink_blend_keeps_the_slower_feed_of_the_block_after_it():
    # a 20 mm/s arc into a 1 mm/s line under G64: the kink blend's second half carries the line's block, and was
    # planned at the arc's feed, so the line's samples ran at 20 mm/s (found: linuxcnc_fuzz seed 104, G93 feeds)
    prog = parse_program("G21 G64\nG0 X0 Y0\nG2 X10 Y0 R5 F1200\nG1 X12 Y-20 F60\nM2\n")
    sp = interpolate(prog, profile="scurve")
    speed = np.linalg.norm(sp.velocity, axis=1)
    assert speed[sp.block == 2].max() <= 1.0 + 1e-9
    assert speed[sp.block == 1].max() == pytest.approx(20.0, rel=1e-3)
    np.testing.assert_allclose(sp.position[-1], [12.0, -20.0], atol=1e-12)


def test_scurve_kink_blend_passes_the_corner_within_the_tolerance():
    # a plunge into a helix under G64 (0.01 mm): the kink blend stayed within 0.01 mm of both pieces but passed
    # the corner X5 Y5 Z0 0.0131 mm away (found: fanuc_generator seed 102 under random limits); now the corner is
    # within the tolerance (here the smaller blend does not pay and the corner is a stop)
    limits = {"x": AxisLimits(velocity=27.4, acceleration=260.0, jerk=120618.0, rapid=62.0),
              "y": AxisLimits(velocity=74.1, acceleration=170.0, jerk=34463.0, rapid=174.0),
              "z": AxisLimits(velocity=403.3, acceleration=2228.0, jerk=16174.0, rapid=932.0)}
    prog = parse_program("G21 G64\nG0 X5 Y5 Z2\nG1 Z0 F100\nG3 X5 Y5 Z-0.5 I10 J0\nM2\n")
    sp = interpolate(prog, limits=limits, sample_time=0.0024, profile="scurve")
    assert check_setpoints(prog, sp, limits, "scurve") == []
    assert np.linalg.norm(xyz(sp) - [5.0, 5.0, 0.0], axis=1).min() <= 0.01
    np.testing.assert_allclose(sp.position[-1], [5.0, 5.0, -0.5], atol=1e-12)


def test_limit_check_allows_the_rapid_rate_on_a_step_across_a_rapid_end():
    # a rapid down Z at up to 30 mm/s into a feed move at the 20 mm/s velocity limit (grbl: passed at speed): the
    # position step that straddles the junction runs partly on the rapid, above 20 mm/s on average; the check took
    # the feed block's limit for it (found: fanuc_generator seeds 127 and 138, when the planner blended that junction
    # under every dialect; LinuxCNC and Fanuc stop there since session 35, Dialect.rapid_feed_stop)
    limits = {"x": AxisLimits(velocity=20.0, acceleration=500.0, rapid=30.0),
              "y": AxisLimits(velocity=20.0, acceleration=500.0, rapid=30.0),
              "z": AxisLimits(velocity=20.0, acceleration=500.0, rapid=30.0)}
    prog = parse_program("G21 G64\nG0 X0 Y0 Z0\nG0 Z-10\nG1 Z-20 F6000\nM2\n", context=GRBL)
    sp = interpolate(prog, limits=limits, sample_time=0.0025)
    z = sp.position[:, 2]
    first_feed = int(np.argmax(sp.block == 2))
    assert abs(z[first_feed] - z[first_feed - 1]) / 0.0025 > 20.0
    assert check_setpoints(prog, sp, limits, "trapezoid") == []


def _rapid_into_dense_chords() -> str:
    """A rapid under G64 P0.5 to X10 Y0 Z5, then under P0.01 a run of 41 chords (20 um, then 0.1 mm) of a curve
    turning from +X to +Y: merged into a smooth curve of several pieces."""
    lines = ["G21 G90 G64 P0.5", "G0 X10 Y0 Z5", "G64 P0.01", "G1 X10.02 Y0.01 F3000"]
    for k in range(1, 41):
        t = k * 0.05
        lines.append(f"G1 X{10.02 + 8 * np.sin(t / 2):.4f} Y{0.01 + 8 * (1 - np.cos(t / 2)) + 0.5 * t:.4f}")
    return "\n".join([*lines, "M2"]) + "\n"


def test_a_rapid_into_a_merged_run_is_blended_within_the_run_s_smaller_tolerance():
    # the pieces of a merged run after its first took the tolerance of the item before the run (here the rapid's
    # P0.5: _merged read the run's last block as the one before the next piece's first, shared by the pieces),
    # so the S-curve's kink blend of the rapid into the curve passed X10 Y0 Z5 0.185 mm away under P0.01 (found:
    # setpoint_fuzz cam seed 42205, 0.078 mm); the corner is within min(0.5, 0.01), LinuxCNC's
    # tcFindBlendTolerance (src/emc/tp/tc.c); under grbl, which blends that junction
    prog = parse_program(_rapid_into_dense_chords(), context=GRBL)
    limits = {a: AxisLimits(velocity=100.0, acceleration=1000.0, jerk=1e5, rapid=200.0) for a in "xyz"}
    for profile in ("trapezoid", "scurve"):
        sp = interpolate(prog, limits=limits, sample_time=0.001, profile=profile)
        assert check_setpoints(prog, sp, limits, profile) == []
        assert np.linalg.norm(xyz(sp) - [10.0, 0.0, 5.0], axis=1).min() <= 0.01
        np.testing.assert_allclose(xyz(sp)[-1], prog.blocks[-1].target, atol=1e-12)


def test_deviation_check_takes_the_smaller_tolerance_of_a_junction():
    # the same plan with the corner cut by 0.05 mm on the first chord's samples: within the rapid's P0.5, but the
    # junction's tolerance is min(0.5, 0.01) (junction_tolerances); the check allowed the larger before
    prog = parse_program(_rapid_into_dense_chords(), context=GRBL)
    limits = {a: AxisLimits(velocity=100.0, acceleration=1000.0, jerk=1e5, rapid=200.0) for a in "xyz"}
    sp = interpolate(prog, limits=limits, sample_time=0.001, profile="trapezoid")
    np.testing.assert_allclose(junction_tolerances(prog)[[0, 1, -1]], [0.01, 0.01, 0.0])
    k = int(np.argmax(sp.block == 1))
    sp.position[k, 2] -= 0.05
    fails = [f for f in check_setpoints(prog, sp, limits, "trapezoid") if f.startswith("deviation")]
    assert len(fails) == 1 and f"sample {k} (block 1, line 4)" in fails[0] and "tolerance 0.01" in fails[0]


def test_limit_check_allows_the_rounding_of_positions_far_from_zero():
    # X at -245.76 mm runs at its 1353.6 mm/s^3 jerk limit (Ts = 0.3126 ms): the third differences of the sampled
    # positions round by up to 8 eps x 245.76 / Ts^3 = 0.014 mm/s^3, above the check's 1e-6 x limit + 1e-3 (found:
    # fanuc_generator seed 42082 under the setpoint fuzzer, 1.0000027 x the limit); a real 0.1 % excess still fails
    from types import SimpleNamespace

    from tests.interpolators.setpoint_checks import check_limits

    Ts, jerk = 0.0003125822677638682, 1353.6
    prog = parse_program("G21 G90 G1 X-245.76 F6000\nG1 X-245.8\nM2\n", context=INTERPOLATION_CONTEXT)
    limits = {a: AxisLimits(velocity=132.0, acceleration=476.0, jerk=jerk) for a in "xyz"}
    t = np.arange(400) * Ts
    for scale, ok in ((1.0, True), (1.001, False)):
        x = -245.76 - scale * jerk * t**3 / 6
        sp = SimpleNamespace(sample_time=Ts, axes=("x",), position=x[:, None], block=np.ones(400, dtype=int),
                             velocity=(-scale * jerk * t**2 / 2)[:, None], acceleration=(-scale * jerk * t)[:, None])
        fd = np.abs(np.diff(x, 3)) / Ts**3
        if ok:
            assert fd.max() > jerk * (1 + 1e-6) + 1e-3  # the rounding alone
            check_limits(sp, prog, limits, jerk=True)
        else:
            with pytest.raises(AssertionError):
                check_limits(sp, prog, limits, jerk=True)


def test_axis_path_check_takes_the_move_after_a_zero_length_block():
    # a G1 repeating the point between a line moving W and one starting B (4.8 deg/mm) under G64 P0.05: the blend's
    # first half carries line 3 with B up to 0.163 deg, its value on line 5 at the nearest point (the corner cut
    # 0.034 mm short along it); the check took the zero-length block for the one after (found: rotary_cam seed 42091)
    prog = parse_program("G21 G64 P0.05\nG0 X0 Y0 B0\nG1 X1.3 Y3.2 W1 F100\nG1 X1.3 Y3.2\nG1 X3.9 Y1.9 B14\nM2\n",
                         context=INTERPOLATION_CONTEXT)
    limits = {a: AxisLimits(velocity=100.0, acceleration=1000.0, jerk=1e5) for a in "xybw"}
    sp = interpolate(prog, limits=limits, sample_time=0.0005)
    assert sp.position[sp.block == 1, sp.axes.index("b")].max() == pytest.approx(0.163, abs=5e-4)
    assert check_setpoints(prog, sp, limits, "trapezoid") == []


def test_a_fitted_axis_still_but_for_rounding_keeps_a_positive_jerk_bound():
    # B steps along lines and an arc, C and A start on the last line: a fitted piece of the chain carries B with
    # derivatives of its spline's rounding (|r_1| 1.03e-15 /mm, just above the 1e-15 taken as moving; |r_2| 4.3e-16
    # below); r_2 stayed in the jerk term at the acceleration its own term did not bound, the path jerk bound came
    # out at -7.8e21 mm/s^3 and ruckig found no S-curve profile (found: rotary_cam seed 42267, shrunk)
    prog = parse_program("G21 G17 G90 G40 G94\nG1 X-0.4286 Y0.903504 Z5.000 F12000\nG1 X-6.744 Y1.011 Z5.000 B28.6438\n"
                         "G1 X-6.5421 Y1.1285 Z5.0000\nG3 X-6.557361 Y1.269500 B30.6523 I-0.039045 J0.067100\n"
                         "G1 X-13.0583 Y3.3615 Z5.000\nG1 X-8.0846 Y10.9205 Z9.809380 B26.0610 C28.3496 A31.4030\nM2\n",
                         context=INTERPOLATION_CONTEXT)
    table = {"x": (1463, 1447, 65579), "y": (91.3, 13843, 467490), "z": (976, 76579, 1279465),
             "a": (205, 33384, 768069), "b": (552, 89033, 13482551), "c": (17.7, 191466, 49414)}
    limits = {k: AxisLimits(velocity=v, acceleration=a, jerk=j) for k, (v, a, j) in table.items()}
    sp = interpolate(prog, limits=limits, sample_time=0.00027, profile="scurve")
    np.testing.assert_allclose(sp.position[-1], [-8.0846, 10.9205, 9.80938, 31.403, 26.061, 28.3496], atol=1e-9)
    assert check_setpoints(prog, sp, limits, "scurve") == []


def test_extra_curve_bounds_take_a_derivative_below_the_threshold_as_zero():
    from interpolators.kinematics import extra_curve_bounds

    d1, d2, d3 = (np.zeros((1, 6)) for _ in range(3))
    d1[0, 1], d2[0, 1], d3[0, 1] = 1.03e-15, 4.3e-16, 4.6e-16  # B: a spline's rounding
    limits = {"b": AxisLimits(velocity=552.0, acceleration=89033.0, jerk=13482551.0)}
    v, a, j = extra_curve_bounds(d1, d2, d3, np.array([200.0]), limits, share=np.ones(1), jerk_limited=True)
    assert v[0] == 200.0
    assert a[0] == pytest.approx(89033.0 / 1.03e-15) and j[0] == pytest.approx(13482551.0 / 1.03e-15)


def test_tnc_programs_run_on_the_machine_they_were_written_for():
    """The ``tnc`` source takes tnc_generator's context of the seed: on its five-axis seeds the B/C table, without
    which the reader refuses every PLANE SPATIAL/... ("not supported without the machine's kinematics") and the
    program goes untested (``setpoint_fuzz --sources tnc --seed 48000``: 1 of 10 refused). Seed 3 tilts the plane."""
    from benchmarks.setpoint_fuzz import program_of
    from tests.interpolators.tnc_generator import five_axis

    text, machine = program_of("tnc", 3)
    assert five_axis(3) and "PLANE SPATIAL" in text
    assert machine.kinematics is not None and machine.extra_axes == ("b", "c")
    assert any(b.segment is not None for b in parse_program(text, source="tnc-3", context=machine).blocks)
