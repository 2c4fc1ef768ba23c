"""Dense CAM code moving rotary (A B C) or secondary linear (U V W) axes beside X, Y, Z under G64.

A run of dense short lines is merged into one smooth curve in X, Y, Z (:mod:`interpolators.dense`) and the
other axes into one spline along its arc length (:func:`interpolators.dense.fit_axes`), each within the path
tolerance ``P`` (deg on A-C, mm on U-W); the path bounds keep every axis within its limits
(:func:`interpolators.kinematics.extra_curve_bounds`). So such a run takes the time its axis limits require:
the time of the same run without those axes where they are slow, else about the time their velocity limit
asks for. Checked by finite differences of the samples (every limit), the distance of X, Y, Z from the
programmed chords and of each other axis from its programmed value at the same point of the chord.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from benchmarks.dense_code import rotary_programs
from interpolators import interpolate, parse_program
from interpolators.axis_blends import corner_positions, excess, hermite_axes, hermite_bounds, ramp_half_length
from interpolators.context import INTERPOLATION_CONTEXT
from interpolators.dense import fit_axes
from interpolators.kinematics import CURVE_BOUND_MARGIN
from tests.interpolators.setpoint_checks import check_limits, distance_to_path
from tests.interpolators.test_secondary_axes import LIMITS

CTX = INTERPOLATION_CONTEXT
PROFILES = ("trapezoid", "scurve")


def _program(lines: list[str]) -> object:
    return parse_program("\n".join([*lines, "M2"]) + "\n", context=CTX)


def _lines(shape: str, rotary: bool) -> list[str]:
    """The lines of :func:`benchmarks.dense_code.rotary_programs` ``shape`` (``helix``: 400 chords of a two-lap R10
    helix at F2000, A 0 -> 90 deg; ``swarf``: 500 chords of an ellipse rising and falling in Z, A tilting and C
    turning once; ``reversal``: 400 chords of 0.2 mm along a gentle S, A swinging +-30 deg; ``coarse``: the helix in
    60 chords of 2.1 mm, too coarse to merge, under G64 P0.05), without its M2."""
    return rotary_programs(shape, rotary).splitlines()[:-1]


def _axis_deviation(sp, prog, axis: str) -> float:
    """Worst distance of ``axis`` (a-c [deg], u-w [mm]) from its programmed value at the point of the chord
    nearest the sample's X, Y, Z (of its block or the blocks beside it)."""
    j = "abcuvw".index(axis)
    xyz = np.zeros((len(sp), 3))
    for i, ax in enumerate(sp.axes):
        if ax in "xyz":
            xyz[:, "xyz".index(ax)] = sp.position[:, i]
    col = sp.position[:, sp.axes.index(axis)]
    best = np.full(len(sp), np.inf)
    for off in (-1, 0, 1):
        k = np.clip(sp.block + off, 0, len(prog.blocks) - 1)
        s = np.array([prog.blocks[i].start for i in k])
        d = np.array([prog.blocks[i].target for i in k]) - s
        r0 = np.array([prog.blocks[i].extra_start[j] for i in k])
        r1 = np.array([prog.blocks[i].extra_target[j] for i in k])
        n2 = np.einsum("ij,ij->i", d, d)
        share = np.clip(np.einsum("ij,ij->i", xyz - s, d) / np.where(n2 > 0, n2, 1.0), 0.0, 1.0)
        best = np.minimum(best, np.abs(col - (r0 + share * (r1 - r0))))
    return float(best.max())


def _end(prog, axes: tuple[str, ...]) -> list[float]:
    """The programmed end point of the last block, on ``axes``."""
    last = prog.blocks[-1]
    full = dict(zip("xyzabcuvw", [*last.target, *last.extra_target]))
    return [full[a] for a in axes]


def _inner_stops(sp, prog) -> int:
    """Samples at rest (every axis) between the first and the last feed block."""
    feed = [k for k, b in enumerate(prog.blocks) if b.kind == "line"]
    still = np.all(np.abs(sp.velocity) < 1e-9, axis=1)
    return int(np.sum(still & (sp.block > feed[0]) & (sp.block < feed[-1])))


@pytest.mark.parametrize("profile", PROFILES)
@pytest.mark.parametrize("shape, axes", [("helix", "a"), ("swarf", "ac"), ("reversal", "a")])
def test_slow_rotary_motion_costs_no_time(shape, axes, profile):
    """Where the rotary axes stay far from their limits (A at most 24 deg/s on the helix, A and C about
    180 deg/s at most on the swarf and the reversal) the run takes about the time of the same run without
    them: before the axes were merged with X, Y, Z the helix took 7.75 s (trapezoid) and 23.8 s (S-curve)
    against 3.93 s and 4.01 s without A."""
    plain, rotary = _program(_lines(shape, False)), _program(_lines(shape, True))
    sp0 = interpolate(plain, profile=profile)
    sp = interpolate(rotary, profile=profile)
    assert sp.duration <= 1.06 * sp0.duration
    assert _inner_stops(sp, rotary) == 0
    check_limits(sp, rotary, LIMITS, jerk=profile == "scurve")
    assert distance_to_path(sp) <= 0.01
    for axis in axes:
        assert _axis_deviation(sp, rotary, axis) <= 0.01, axis
    assert np.allclose(sp.position[-1], _end(rotary, sp.axes), rtol=0, atol=1e-12)


def _wrap() -> tuple[list[str], float]:
    """A groove wrapped on a cylinder of radius 20 mm: 600 chords of 0.1 mm in X, A turning by
    ``40 sin(x / 6) / 20`` rad (up to 19 deg per mm: the A velocity limit, 180 deg/s, binds); and the time its
    velocity limits require, each chord at ``min(F, V_A / |dA/dx|)``."""
    out = ["G21 G90 G64 P0.01 G0 X0 A0", "G1 F1500"]
    a = [0.0]
    for i in range(1, 601):
        a.append(round(math.degrees(2 * math.sin(0.1 * i / 6)), 4))
        out.append(f"X{0.1 * i:.4f} A{a[-1]:.4f}")
    rate = np.abs(np.diff(a)) / 0.1
    return out, float(np.sum(0.1 / np.minimum(25.0, LIMITS["a"].velocity / np.maximum(rate, 1e-12))))


@pytest.mark.parametrize("profile", PROFILES)
def test_cylinder_wrap_runs_at_the_rotary_axis_limits(profile):
    """The wrap takes at least the time A's velocity limit requires and at most 30 % more (A's acceleration:
    its rate changes by up to 3.2 deg/mm^2 of X; before: 23.3 s trapezoid, 59.8 s S-curve, 5.2 and 13 times)."""
    lines, least = _wrap()
    prog = _program(lines)
    sp = interpolate(prog, profile=profile)
    assert least <= sp.duration <= 1.3 * least
    assert _inner_stops(sp, prog) == 0
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
    assert _axis_deviation(sp, prog, "a") <= 0.01
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


@pytest.mark.parametrize("profile", PROFILES)
def test_axes_that_fit_no_spline_follow_the_chords(profile):
    """A zigzag of +-0.5 deg per 0.2 mm chord cannot lie within 0.01 deg of a smooth curve: the run is not
    merged, each sample lies on its block's chord, and the zigzag's reversals stay stops."""
    lines = ["G21 G90 G64 P0.01 G0 X0 A0", "G1 F1200"]
    lines += [f"X{0.2 * i:.4f} A{0.5 * (i % 2):.4f}" for i in range(1, 41)]
    prog = _program(lines)
    sp = interpolate(prog, profile=profile)
    assert "programmed_path" not in sp.meta  # nothing merged
    assert _axis_deviation(sp, prog, "a") <= 1e-9
    assert _inner_stops(sp, prog) >= 38  # a stop in each block between the first and the last
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")


@pytest.mark.parametrize("profile", PROFILES)
def test_run_into_a_long_line_keeps_every_limit(profile):
    """A merged run whose axis spline bends (A and W curving along it) ending in a long line with constant
    rates: the junction is passed within every limit, the S-curve's acceleration step of A and W included
    (``v^2 |d2r|`` within the jerk share of one sample)."""
    lines = ["G21 G90 G64 P0.01 G0 X0 Y0 A0 W0", "G1 F3000"]
    lines += [f"X{0.25 * i:.4f} Y{2 * math.sin(0.25 * i / 4):.4f} A{0.05 * (0.25 * i) ** 2:.4f} "
              f"W{0.002 * (0.25 * i) ** 2:.4f}" for i in range(1, 81)]
    lines.append(f"X60 Y{2 * math.sin(5.0):.4f} A{5.0 + 40.0:.4f} W{0.2 + 0.4:.4f}")
    prog = _program(lines)
    sp = interpolate(prog, profile=profile)
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
    assert distance_to_path(sp) <= 0.01
    assert _axis_deviation(sp, prog, "a") <= 0.01
    assert _axis_deviation(sp, prog, "w") <= 0.01
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


def test_fit_axes_keeps_a_constant_rate_and_refuses_a_zigzag():
    """The axis spline of a run: a constant rate stays that rate (an axis that does not move has all its
    coefficients at its value and no rate: the samples keep it exactly); a zigzag of +-0.5 deg per point
    fits no spline within 0.01 deg."""
    s = np.linspace(0.0, 10.0, 41)
    values = np.column_stack([3.0 * s, np.full(len(s), 7.0)])
    spl = fit_axes(s, values, 0.01)
    assert spl is not None
    assert np.allclose(spl(s), values, rtol=0, atol=1e-9)
    assert np.allclose(spl(s, 1)[:, 0], 3.0, rtol=0, atol=1e-9)
    assert np.all(spl.c[:, 1] == 7.0)
    assert np.allclose(spl(s, 1)[:, 1], 0.0, rtol=0, atol=1e-12)
    assert np.array_equal(spl(s[[0, -1]]), values[[0, -1]])  # through the end values exactly
    zigzag = np.column_stack([0.5 * (np.arange(41) % 2)])
    assert fit_axes(s, zigzag, 0.01) is None


def test_an_axis_the_run_keeps_still_stays_exact():
    """B programmed at 12.5 deg on every chord of a run that moves A: every sample of the run holds 12.5
    exactly."""
    lines = ["G21 G90 G64 P0.01 G0 X10 Y0 Z0 A0 B12.5", "G1 F2000"]
    lines += [f"X{10 * math.cos(t):.4f} Y{10 * math.sin(t):.4f} A{30 * t:.4f} B12.5"
              for t in np.linspace(0, math.pi, 101)[1:]]
    prog = _program(lines)
    sp = interpolate(prog, profile="scurve")
    assert "programmed_path" in sp.meta  # merged
    assert np.all(sp.position[sp.block >= 1, sp.axes.index("b")] == 12.5)
    check_limits(sp, prog, LIMITS, jerk=True)


@pytest.mark.parametrize("profile", PROFILES)
def test_chords_longer_than_dense_code_merge_when_the_axes_move(profile):
    """120 chords of 1.05 mm (longer than ``DENSE_MAX_LENGTH``) of the two-lap helix under G64 P0.02: without A
    their corners are blended one by one; with A nothing blends them, so they merge into one curve whenever it
    fits the tolerance (``UNBLENDED_MAX_LENGTH``) and run in about the time without A (before: 5.78 s trapezoid,
    10.75 s S-curve against 3.93 s and 4.02 s)."""
    def helix(with_a: bool) -> list[str]:
        out = ["G21 G90 G64 P0.02 G0 X10 Y0 Z0 A0", "G1 F2000"]
        for i in range(1, 121):
            t = 4 * math.pi * i / 120
            out.append(f"X{10 * math.cos(t):.4f} Y{10 * math.sin(t):.4f} Z{-0.5 * i / 120:.4f}"
                       + (f" A{90 * i / 120:.4f}" if with_a else ""))
        return out

    plain, rotary = _program(helix(False)), _program(helix(True))
    sp0, sp = interpolate(plain, profile=profile), interpolate(rotary, profile=profile)
    assert sp.duration <= 1.01 * sp0.duration
    assert _inner_stops(sp, rotary) == 0
    check_limits(sp, rotary, LIMITS, jerk=profile == "scurve")
    assert distance_to_path(sp) <= 0.02
    assert _axis_deviation(sp, rotary, "a") <= 0.02


@pytest.mark.parametrize("profile", PROFILES)
def test_a_run_that_fits_no_spline_leaves_the_other_runs_merged(profile):
    """The two-lap helix with A, then past a sharp corner ten chords whose A zigzags by 0.5 deg: the zigzag's
    run keeps its chords (each sample on its block's chord, a stop at each reversal) while the helix stays
    merged and takes about the time it takes when a straight line follows it instead (before, one run fitting no
    spline left the whole chain unmerged: 8.09 s trapezoid, 24.6 s S-curve against 4.27 s and 4.78 s)."""
    def program(zigzag: bool):
        tail = [f"X{10 + 0.2 * i:.4f} Y0 Z-0.5 A{90 + (0.5 * (i % 2) if zigzag else 0):.4f}" for i in range(1, 11)]
        return _program([*_lines("helix", True), *tail])

    line, zig = program(False), program(True)
    sp0, sp = interpolate(line, profile=profile), interpolate(zig, profile=profile)
    assert "programmed_path" in sp.meta  # the helix merged
    helix = (sp.block >= 2) & (sp.block <= 401)
    assert np.sum(helix) <= 1.02 * np.sum((sp0.block >= 2) & (sp0.block <= 401))  # about the time on the helix
    assert _inner_stops(sp, zig) - _inner_stops(sp0, line) == 8  # the zigzag's inner reversals
    tail = sp.block >= 402
    a = sp.position[:, sp.axes.index("a")]
    assert _axis_deviation(sp, zig, "a") <= 0.01
    for k in np.flatnonzero(tail):
        b = zig.blocks[sp.block[k]]
        share = (sp.position[k, 0] - b.start[0]) / (b.target[0] - b.start[0])
        assert a[k] == pytest.approx(b.extra_start[0] + share * (b.extra_delta[0]), abs=1e-9)
    check_limits(sp, zig, LIMITS, jerk=profile == "scurve")
    assert distance_to_path(sp) <= 0.01
    assert np.allclose(sp.position[-1], _end(zig, sp.axes), rtol=0, atol=1e-12)


@pytest.mark.parametrize("profile", PROFILES)
def test_inverse_time_chords_merge_at_the_slowest_feed_of_each_piece(profile):
    """The helix with A under G93, every chord F6366.2 (1/F min each: 3.77 s in all): rounding the words to
    4 decimals leaves the chords' feeds (length over time) up to 0.3 % apart, which used to end a run at every
    chord (7.75 s trapezoid, 23.8 s S-curve). They merge: the run takes about the programmed time, at most
    1 % more (each piece at the slowest feed of its chords), never above a block's feed."""
    lines = ["G21 G90 G64 P0.01 G0 X10 Y0 Z0 A0", "G93 G1"]
    for i in range(1, 401):
        t = 4 * math.pi * i / 400
        lines.append(f"X{10 * math.cos(t):.4f} Y{10 * math.sin(t):.4f} Z{-0.5 * i / 400:.4f} A{90 * i / 400:.4f}"
                     " F6366.2")
    prog = _program([*lines, "G94"])
    feeds = [b.feed for b in prog.blocks if b.kind == "line"]
    assert 1.0 < max(feeds) / min(feeds) < 1.005
    sp = interpolate(prog, profile=profile)
    assert "programmed_path" in sp.meta
    programmed = 400 * 60.0 / 6366.2
    on_helix = np.sum(sp.block >= 2) * sp.sample_time
    assert programmed <= on_helix <= 1.03 * programmed
    assert _inner_stops(sp, prog) == 0
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    assert distance_to_path(sp) <= 0.01
    assert _axis_deviation(sp, prog, "a") <= 0.01


@pytest.mark.parametrize("profile", PROFILES)
def test_coarse_chords_with_a_blend_their_corners_across_every_axis(profile):
    """The coarse helix's corners are blended as without A (a tangent arc, S-curve a clothoid pair, within P of the
    corner) and A follows a quintic across each blend, its rate continuous: the run takes the time it takes
    without A (before, each corner at the one-sample rule: 4.854 s trapezoid, 7.087 s S-curve against 3.913 s and
    3.993 s), A within P of its programmed motion, every limit held."""
    plain, rotary = _program(_lines("coarse", False)), _program(_lines("coarse", True))  # 60 chords of 2.1 mm, P0.05
    sp0, sp = interpolate(plain, profile=profile), interpolate(rotary, profile=profile)
    assert sp.duration == pytest.approx(sp0.duration, abs=2 * sp.sample_time)
    assert "programmed_path" in sp.meta
    assert _inner_stops(sp, rotary) == 0
    check_limits(sp, rotary, LIMITS, jerk=profile == "scurve")
    assert 0.02 <= distance_to_path(sp) <= 0.05  # the corners are cut, within P
    assert _axis_deviation(sp, rotary, "a") <= 0.05
    assert np.all(np.diff(sp.block) >= 0)
    assert np.allclose(sp.position[-1], _end(rotary, sp.axes), rtol=0, atol=1e-12)


def _polygon(step: float | None) -> list[str]:
    """Two laps of a 24-gon of radius 20 mm (sides of 5.2 mm turning 15 deg) at F2000 under G64 P0.05, A up ``step``
    deg on one side and back on the next (its rate reverses at each corner); no A with ``step`` None."""
    out = ["G21 G90 G64 P0.05 G0 X20 Y0 A0", "G1 F2000"]
    for i in range(1, 49):
        t = 2 * math.pi * i / 24
        out.append(f"X{20 * math.cos(t):.4f} Y{20 * math.sin(t):.4f}"
                   + ("" if step is None else f" A{step * (i % 2):.4f}"))
    return out


@pytest.mark.parametrize("profile", PROFILES)
def test_a_rate_reversal_shrinks_the_corner_blends_to_keep_a_within_p(profile):
    """A reversing at 0.19 deg/mm at each corner: across a blend sized for X/Y alone (1.5 mm) A would leave its
    programmed motion by 1.2 (S-curve 1.8) times 0.9 P, so the blends are made within P scaled down by that: A
    within P, no stop (before: a stop at every corner, 8.47 s trapezoid, 10.15 s S-curve). The trapezoid takes the
    time without A (7.72 s); the S-curve's shorter clothoid pairs bend A faster, within its jerk limit."""
    plain, rotary = _program(_polygon(None)), _program(_polygon(1.0))
    sp0, sp = interpolate(plain, profile=profile), interpolate(rotary, profile=profile)
    assert _inner_stops(sp, rotary) == 0
    assert sp.duration <= (1.002 if profile == "trapezoid" else 1.3) * sp0.duration
    check_limits(sp, rotary, LIMITS, jerk=profile == "scurve")
    assert distance_to_path(sp) <= 0.05
    assert 0.03 <= _axis_deviation(sp, rotary, "a") <= 0.05


@pytest.mark.parametrize("profile", PROFILES)
def test_corners_whose_blend_is_slower_than_a_stop_stay_stops(profile):
    """A reversing by 3 deg per side (0.58 deg/mm): the blends that keep A within P are so short that bending A
    across them is slower than stopping (A's acceleration and jerk on the blend, judged with the X/Y bound): every
    corner stays a stop and each sample on its block's chord."""
    prog = _program(_polygon(3.0))
    sp = interpolate(prog, profile=profile)
    assert "programmed_path" not in sp.meta
    assert _inner_stops(sp, prog) >= 46
    assert _axis_deviation(sp, prog, "a") <= 1e-9
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")


def test_hermite_axes_matches_values_rates_and_no_curvature_at_its_ends():
    """The quintics across two blends (2 mm and 0.5 mm) in one spline: each blend's end values and rates as given
    at its offset and its offset plus its length, second derivative 0 at both ends; equal rates ``(end - start) /
    length`` give the straight line; an axis at rest in both keeps all its coefficients at its value."""
    length = np.array([2.0, 0.5])
    start, end = np.array([[10.0, 5.0, 1.0], [3.0, 5.0, 0.0]]), np.array([[12.0, 5.0, 2.0], [4.0, 5.0, 1.0]])
    rate_start, rate_end = np.array([[0.5, 0.0, 0.5], [1.0, 0.0, 2.0]]), np.array([[1.5, 0.0, 0.5], [3.0, 0.0, 2.0]])
    spl, offset = hermite_axes(length, start, end, rate_start, rate_end)
    for j in range(2):
        ends = offset[j] + np.array([0.0, length[j]])
        assert np.allclose(spl(ends), [start[j], end[j]], rtol=0, atol=1e-12)
        assert np.allclose(spl(ends, 1), [rate_start[j], rate_end[j]], rtol=0, atol=1e-12)
        assert np.allclose(spl(ends, 2), 0.0, rtol=0, atol=1e-12)
        s = np.linspace(0.0, length[j], 9)
        assert np.allclose(spl(offset[j] + s)[:, 2], start[j, 2] + rate_start[j, 2] * s, rtol=0, atol=1e-12)
    assert np.all(spl.c[:, 1] == 5.0)
    args = (length[:1], start[:1], end[:1], rate_start[:1], rate_end[:1])
    fine = np.linspace(0.0, 2.0, 2001)
    for nu, d in zip((1, 2, 3), hermite_bounds(*args)):  # the largest derivatives, by CURVE_BOUND_MARGIN
        assert d[0] == pytest.approx(np.abs(spl(fine, nu)).max(axis=0) * CURVE_BOUND_MARGIN, rel=1e-3, abs=1e-12)
        assert d[0, 1] == 0.0 and (nu == 1 or d[0, 2] == 0.0)
    # A's programmed motion: 10 -> 11 (the corner, at the middle) -> 12; the quintic leaves it by 0.31 deg
    dev = np.abs(spl(fine)[:, 0] - np.interp(fine, [0.0, 1.0, 2.0], [10.0, 11.0, 12.0])).max()
    assert excess(*args, np.array([[11.0, 5.0, 1.5]]), np.array([0.1]))[0] == pytest.approx(dev / 0.09, rel=1e-2)
    assert dev == pytest.approx(0.3125, abs=1e-4)


@pytest.mark.parametrize("profile", PROFILES)
def test_inverse_time_chords_of_changing_feeds_blend_at_each_blocks_speed(profile):
    """A 5-axis CAM program under G93 writes a new F on every block (1/F minutes each): 40 chords of 2 mm on a
    radius of 20 mm with C following the tangent, F 600 +-30 %. Their feeds differ far beyond
    ``UNBLENDED_FEED_SPREAD``, so they do not merge; their corners are blended across X, Y and C, each block's
    speed (its length over its time) a bound of its own, as LinuxCNC's interpreter turns each G93 F into the
    block's feed (``inverse_time_rate_straight``, src/emc/rs274ngc/interp_inverse.cc) and its planner blends them.
    The chords take their programmed time (4.136 s) plus the speed changes between blocks, never a block faster
    than programmed (before: a stop at 8 corners, 5.324 s trapezoid; 38 stops, 7.400 s S-curve)."""
    lines, programmed = ["G21 G90 G64 P0.02 G0 X20 Y0 Z0 C0", "G93 G1"], 0.0
    for i in range(1, 41):
        feed = 600 * (1 + 0.3 * math.sin(i))
        lines.append(f"X{20 * math.cos(0.1 * i):.4f} Y{20 * math.sin(0.1 * i):.4f} C{math.degrees(0.1 * i):.4f} "
                     f"F{feed:.4f}")
        programmed += 60.0 / float(f"{feed:.4f}")
    prog = _program([*lines, "G94"])
    sp = interpolate(prog, profile=profile)
    on_chords = np.sum(sp.block >= 1) * sp.sample_time
    assert programmed <= on_chords <= (1.02 if profile == "trapezoid" else 1.06) * programmed
    assert _inner_stops(sp, prog) == 0
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    assert distance_to_path(sp) <= 0.02
    assert _axis_deviation(sp, prog, "c") <= 0.02
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


@pytest.mark.parametrize("profile", PROFILES)
def test_inch_p_is_converted_to_mm_and_read_as_deg_on_a(profile):
    """``G20 G64 P0.002``: 0.0508 mm on X, Y and, read in deg, on A (our reading, :mod:`interpolators.axis_blends`).
    The 24-gon with A reversing at each corner, in inches: A's blends use that tolerance (0.9 x 0.0508 deg at most,
    and well above 0.002 deg), X, Y within 0.0508 mm, no stop."""
    lines = ["G20 G90 G64 P0.002 G0 X0.7874 Y0 A0", "G1 F80"]
    for i in range(1, 49):
        t = 2 * math.pi * i / 24
        lines.append(f"X{0.7874 * math.cos(t):.5f} Y{0.7874 * math.sin(t):.5f} A{i % 2:.4f}")
    prog = _program(lines)
    assert prog.blocks[-1].tolerance == pytest.approx(0.0508)
    sp = interpolate(prog, profile=profile)
    assert _inner_stops(sp, prog) == 0
    assert distance_to_path(sp) <= 0.0508
    assert 0.02 <= _axis_deviation(sp, prog, "a") <= 0.9 * 0.0508 + 1e-9
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")


@pytest.mark.parametrize("profile", PROFILES)
def test_an_axis_at_rest_at_another_value_in_each_blend_keeps_each_value(profile):
    """C at rest across the first blended corner (at 0) and the last (at 10), moved between them by a line whose
    corners are reversals (never blended): each blend keeps C at its own value. Before, C counted as still in the
    chain's one spline and took the first blend's value in both: a 10 deg jump in one sample at the last blend."""
    prog = _program(["G21 G90 G64 P0.05 G0 X0 Y0 Z0 A0 C0", "G1 F3000 X10 Y0 A1 C0", "X20 Y5 A2 C0",
                     "X10 Y5 A3 C10", "X20 Y5 A4 C10", "X30 Y0 A5 C10", "X40 Y5 A6 C10"])
    sp = interpolate(prog, profile=profile)
    assert "programmed_path" in sp.meta  # the two corners blended
    c = sp.position[:, sp.axes.index("c")]
    assert np.all(c[sp.block <= 2] == 0.0) and np.all(c[sp.block >= 4] == pytest.approx(10.0, abs=1e-12))
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
    assert _axis_deviation(sp, prog, "c") <= 1e-9
    assert distance_to_path(sp) <= 0.05


def test_hermite_axes_keeps_an_axis_at_rest_at_a_value_of_each_blend():
    """An axis at rest in two blends at 0 and at 10: each blend's polynomial at its own value (not the first's)."""
    zero = np.zeros((2, 1))
    spl, offset = hermite_axes(np.array([1.0, 1.0]), np.array([[0.0], [10.0]]), np.array([[0.0], [10.0]]), zero, zero)
    assert spl(offset[1] + np.array([0.0, 0.5, 1.0]))[:, 0] == pytest.approx([10.0] * 3, abs=1e-12)
    assert spl(offset[0] + 0.5)[0] == 0.0


@pytest.mark.parametrize("profile", PROFILES)
def test_an_axis_still_in_each_blend_keeps_its_own_value_in_each(profile):
    # two corner blends in one chain (B turning at each), U still across both but moved 0 -> 1500 mm by the line
    # between them, whose corners are not blended: the chain's one blend spline took the first blend's U (0) for
    # both, so U jumped 1500 -> 0 -> 1500 mm through the second blend (found: setpoint fuzzer rotary_cam seed 40599,
    # the same program in inches)
    prog = _program(["G21 G90 G64 P0.05", "G1 X0 Y0 Z5 B27 F100", "G1 X-0.4 Y-0.45 B29", "G1 X-11 Y10 U1500",
                     "G1 X-14 Y9 B-5", "G1 X-16 Y9.4 B-16"])
    sp = interpolate(prog, profile=profile)
    u, b = sp.position[:, sp.axes.index("u")], sp.position[:, sp.axes.index("b")]
    assert np.abs(u[sp.block <= 1]).max() == 0.0
    np.testing.assert_allclose(u[sp.block >= 3], 1500.0, rtol=0, atol=1e-9)
    # B passes its corner value -5 deg within P (read as deg) in the blend
    assert np.abs(b[sp.block >= 3] + 5.0).min() <= 0.05
    assert np.abs(np.diff(u)).max() <= 1500.0 / 100  # no step: U moves 1500 mm over one line at F100-ish rates
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


def _programmed_a(prog, block: int, xyz: np.ndarray) -> float:
    """A programmed at the point of block ``block``'s line or XY arc nearest ``xyz``: in proportion to the path along
    the block (RS274/NGC 3, Sec. 2.1.2.5)."""
    b = prog.blocks[block]
    seg = b.segment
    if hasattr(seg, "sweep"):
        c = np.asarray(seg.center, dtype=float)
        turned = math.atan2(xyz[1] - c[1], xyz[0] - c[0]) - seg.start_angle
        share = (turned * math.copysign(1.0, seg.sweep)) % (2 * math.pi) / abs(seg.sweep)
        share = share if share <= 1.0 else (0.0 if share > 0.5 + 0.5 * 2 * math.pi / abs(seg.sweep) else 1.0)
    else:
        s, d = np.asarray(seg.start, dtype=float), np.asarray(seg.end, dtype=float) - np.asarray(seg.start, dtype=float)
        share = float(np.clip(np.dot(xyz - s, d) / np.dot(d, d), 0.0, 1.0))
    return b.extra_start[0] + share * b.extra_delta[0]


def _a_off_path(sp, prog) -> float:
    """Worst distance of A from its programmed value at the nearest point of the sample's block or the blocks
    beside it (lines and XY arcs), over the samples of feed blocks (a rapid's A is not proportional to its path)."""
    a = sp.position[:, sp.axes.index("a")]
    xyz = np.zeros((len(sp), 3))  # X, Y, Z (a program may move two of them only)
    for i, ax in enumerate(sp.axes):
        if ax in "xyz":
            xyz[:, "xyz".index(ax)] = sp.position[:, i]
    worst = 0.0
    for i in (i for i in range(len(sp)) if prog.blocks[sp.block[i]].kind != "rapid"):
        near = [k for k in (sp.block[i] - 1, sp.block[i], sp.block[i] + 1)
                if 0 <= k < len(prog.blocks) and prog.blocks[k].kind != "rapid" and prog.blocks[k].segment is not None]
        worst = max(worst, min(abs(a[i] - _programmed_a(prog, k, xyz[i])) for k in near))
    return worst


def _rounded_square(a_on_lines: bool) -> list[str]:
    """A 30 x 40 mm rectangle with R10 corners (lines tangent to the arcs) at F3000 under G64 P0.05, A turning 5 deg
    per block on every block (``a_on_lines``) or 10 deg per arc and still on the lines: at every junction the path
    is tangent and A's rate per mm steps (0.25 to 0.32 deg/mm, or 0 to 0.64)."""
    moves = [("G1 X20 Y0", 1), ("G3 X30 Y10 I0 J10", 2), ("G1 X30 Y30", 3), ("G3 X20 Y40 I-10 J0", 4),
             ("G1 X0 Y40", 5), ("G3 X-10 Y30 I0 J-10", 6), ("G1 X-10 Y10", 7), ("G3 X0 Y0 I10 J0", 8)]
    out = ["G21 G90 G64 P0.05 G0 X0 Y0 Z0 A0", "F3000"]
    for text, k in moves:
        arc = k % 2 == 0
        out.append(f"{text} A{5 * k}" if a_on_lines else (f"{text} A{5 * k}" if arc else text))
    return out


@pytest.mark.parametrize("profile", PROFILES)
@pytest.mark.parametrize("a_on_lines", [True, False])
def test_a_rate_step_at_a_tangent_line_arc_junction_is_ramped(profile, a_on_lines):
    """Lines tangent to arcs, A's rate stepping at each junction: A follows a quintic ramp of the path across each
    junction (within 0.9 P of its programmed motion) instead of the one-sample rule, a stop at every junction
    before (A on every block: 3.060 s trapezoid, 3.400 s S-curve; A on the arcs only: 3.060 s, 3.400 s). Without A
    the contour takes 2.882 s (trapezoid, its junctions passed at the arcs' bound) and 2.924 s (S-curve). A starting
    and stopping on the arcs (0.64 deg/mm) under the S-curve: the ramp within P (0.7 mm) bends A within its jerk
    limit only below 14 mm/s, slower than a stop, and the junctions stay stops, at the time they took before.
    A on every block under the S-curve: since session 33 each junction's curvature step is blended within P as
    without A (:func:`interpolators.lookahead.blend_corners`' kink blends), A on the blend's quintic: the time
    without A (3.129 s with the ramps, 1.07 x, X, Y, Z then on the programmed lines and arcs)."""
    plain = _program([ln.split(" A")[0] for ln in _rounded_square(True)])
    prog = _program(_rounded_square(a_on_lines))
    sp0, sp = interpolate(plain, profile=profile), interpolate(prog, profile=profile)
    stops = profile == "scurve" and not a_on_lines
    blended = profile == "scurve" and a_on_lines
    bound = {("trapezoid", True): 1.001, ("trapezoid", False): 1.04, ("scurve", True): 1.0 + 1e-9,
             ("scurve", False): 1.17}[profile, a_on_lines]
    assert sp.duration <= bound * sp0.duration
    assert (_inner_stops(sp, prog) > 0) == stops
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
    # X, Y, Z on the programmed path where the ramps move A only, within P where the kinks are blended
    assert 0.005 <= distance_to_path(sp) <= 0.05 if blended else distance_to_path(sp) <= 1e-6
    assert (0.0 if stops else 0.005) <= _a_off_path(sp, prog) <= 0.9 * 0.05 + 1e-6
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


def _zigzag(a_every: int | None, p: float = 0.05) -> list[str]:
    """Ten lines of 10 mm zigzagging 1 mm in Y at F3000 under G64 ``p``, A turning 5 deg on every ``a_every``-th line
    (still on the others: 4-axis CAM output with a rotary word on some blocks only); no A with None."""
    out = [f"G21 G90 G64 P{p} G0 X0 Y0 Z0 A0", "G1 F3000"]
    for i in range(1, 11):
        a = "" if a_every is None else f" A{5 * (i // a_every)}"
        out.append(f"X{10 * i} Y{i % 2}{a}")
    return out


@pytest.mark.parametrize("profile", PROFILES)
def test_a_word_on_some_blocks_only_keeps_one_chain(profile):
    """A moving on every other line of a zigzag: the lines that keep A still join the chain (before, a stop wherever
    A started or stopped: 2.260 s trapezoid, 2.650 s S-curve, against 2.034 s and 2.072 s without A; now 2.093 s).
    The trapezoid blends every corner across all axes (A's rate stepping from 0 to 0.5 deg/mm within the blend) and
    takes nearly the time without A. Under the S-curve a blend that keeps A within P of its corner is 0.9 mm long:
    bending A by 0.5 deg/mm over it within A's jerk limit passes at 14 mm/s, slower than a stop (measured: 1.403 s
    against 1.325 s on five lines), so those corners stay stops, at the time they took before."""
    plain, prog = _program(_zigzag(None)), _program(_zigzag(2))
    sp0, sp = interpolate(plain, profile=profile), interpolate(prog, profile=profile)
    if profile == "trapezoid":
        assert _inner_stops(sp, prog) == 0
        assert sp.duration <= 1.03 * sp0.duration
        assert 0.01 <= _axis_deviation(sp, prog, "a") <= 0.05
    else:
        assert sp.duration <= 1.3 * sp0.duration
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
    assert distance_to_path(sp) <= 0.05
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


def test_a_wider_tolerance_ramps_a_start_on_a_straight_line_under_the_s_curve():
    """Collinear lines, A starting and stopping on every other one (0.5 deg/mm) under G64 P0.5: the ramps within
    0.9 P are long enough to pass at speed under the S-curve too: no stop, the time without A (1.664 s; before, a
    stop at each start and stop of A, 2.112 s)."""
    lines = ["G21 G90 G64 P0.5 G0 X0 Y0 Z0 A0", "G1 F3000"]
    lines += [f"X{10 * i}" + (f" A{5 * ((i + 1) // 2)}" if i % 2 else "") for i in range(1, 9)]
    prog, plain = _program(lines), _program([ln.split(" A")[0] for ln in lines])
    sp0, sp = interpolate(plain, profile="scurve"), interpolate(prog, profile="scurve")
    assert _inner_stops(sp, prog) == 0
    assert sp.duration <= 1.005 * sp0.duration
    check_limits(sp, prog, LIMITS, jerk=True)
    assert distance_to_path(sp) <= 1e-9
    assert 0.05 <= _axis_deviation(sp, prog, "a") <= 0.45 + 1e-6


def test_ramp_half_length_keeps_the_quintic_within_the_share_of_p():
    """The ramp of :func:`interpolators.axis_blends.ramp_half_length` centred on a corner of the axes' polyline
    leaves it by exactly FIT_SHARE * P at its middle (ratio 1 of :func:`excess`); a step on one axis of two sizes
    it, infinite without a step."""
    step = np.array([[0.5, 0.1], [0.0, 0.0]])
    half = ramp_half_length(step, np.array([0.05, 0.05]))
    assert half[0] == pytest.approx(16 * 0.9 * 0.05 / (3 * 0.5))
    assert half[1] == math.inf
    corner, m0 = np.array([[2.0, 1.0]]), np.array([[0.0, 0.2]])
    m1 = m0 + step[:1]
    h = half[:1]
    ratio = excess(2 * h, corner - m0 * h[:, None], corner + m1 * h[:, None], m0, m1, corner, np.array([0.05]))
    assert ratio[0] == pytest.approx(1.0, rel=1e-9)


@pytest.mark.parametrize("profile", PROFILES)
def test_a_fast_axis_across_a_blend_stays_within_p_of_the_nearest_programmed_point(profile):
    """C turning about 7 deg/mm on 10 mm sides of a 12-gon (30 deg corners) under G20 G64 P0.00787 (0.2 mm, read as
    0.2 deg on C): the blends' C is checked against its programmed value at the nearest point of the chords (the
    measure of ``_axis_deviation``), no longer along the blend's arc length with the corner at its middle, which
    let C reach 0.426 deg (trapezoid) and 0.400 deg (S-curve), 2 P, from it (review31's seed 120). The blends that
    keep it within 0.9 P are a little smaller: 2.748 -> 2.754 s, 2.871 -> 2.933 s."""
    prog = _program(["G20 G90 G64 P0.00787 G0 X0 Y-0.7874 Z0 C0", "G1 F39.37", "X0.3937 Y-0.6819 C-75",
                     "X0.6819 Y-0.3937 C-145", "X0.7874 Y0 C-210", "X0.6819 Y0.3937 C-210"])
    sp = interpolate(prog, profile=profile)
    assert "programmed_path" in sp.meta and _inner_stops(sp, prog) == 0
    assert 0.1 <= _axis_deviation(sp, prog, "c") <= 0.9 * 0.2 + 1e-3
    assert distance_to_path(sp) <= 0.2
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve")
    assert sp.duration <= (2.76 if profile == "trapezoid" else 2.94)


def test_corner_positions_takes_the_nearer_line():
    """Points near a right-angle corner at the origin (in along +X, out along +Y): a point inside the corner nearer
    the incoming line lies before the corner by its X, one nearer the outgoing line after it by its Y."""
    t = corner_positions(np.array([[[-0.5, 0.1, 0.0], [-0.1, 0.5, 0.0], [0.0, 0.0, 0.0]]]), np.zeros((1, 3)),
                         np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, 1.0, 0.0]]))
    assert np.allclose(t, [[-0.5, 0.5, 0.0]], rtol=0, atol=1e-15)


def test_a_staircase_along_a_dense_run_keeps_its_still_stretches_merged():
    """The dense helix with A up 2.25 deg on every tenth chord only (``rotary_programs('staircase')``, S-curve): the
    chords keeping A still join the chain, each stretch between A's starts and stops merged apart; merged as one
    run, A's staircase fits no spline within P and the run kept its 400 chords (13.045 s with the join alone, no
    split), against 10.747 s with each A chord its own chain. A's 7 deg/mm steps within P0.01 deg pass near a
    stop either way (about 2.6 mm/s at A's jerk limit)."""
    prog = parse_program(rotary_programs("staircase", True), context=CTX)
    sp = interpolate(prog, profile="scurve")
    assert sp.duration <= 10.75
    check_limits(sp, prog, LIMITS, jerk=True)
    assert distance_to_path(sp) <= 0.01
    assert _axis_deviation(sp, prog, "a") <= 0.01
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


def _serpentine(a_rate: float | None) -> list[str]:
    """Two periods of a serpentine of tangent lines (10 mm) and quarter arcs (R5, G2/G3 alternating in pairs) at
    F2000 under G64 P0.02, A turning ``a_rate`` deg per mm of path on every block (None: without A), as a 4-axis
    wrap with arcs: every junction is tangent with a curvature step of 0.2/mm, A's rate continuous."""
    quarter = math.pi * 5 / 2
    out, a = ["G21 G90 G64 P0.02 G0 X0 Y0 Z10 A0", "G1 F2000"], 0.0
    for k in range(2):
        o = 40 * k
        for text, length in ((f"G1 X{o + 10}", 10.0), (f"G3 X{o + 15} Y5 I0 J5", quarter), ("G1 Y15", 10.0),
                             (f"G2 X{o + 20} Y20 I5 J0", quarter), (f"G1 X{o + 30}", 10.0),
                             (f"G2 X{o + 35} Y15 I0 J-5", quarter), ("G1 Y5", 10.0),
                             (f"G3 X{o + 40} Y0 I5 J0", quarter)):
            a += 0.0 if a_rate is None else a_rate * length
            out.append(text if a_rate is None else f"{text} A{a:.4f}")
    return out


@pytest.mark.parametrize("Ts", [1e-3, 2.5e-4])
def test_tangent_line_arc_junctions_with_a_moving_are_blended_as_without_a(Ts):
    """A serpentine of tangent lines and arcs with A on every block at one rate per mm (S-curve): each junction's
    curvature step is blended within P as in the same contour without A (a kink blend, A on its quintic), so it
    takes that contour's time, 4.528 s (before session 33 such chains kept their curvature steps: 4.863 s at 1 ms,
    5.114 s at 0.25 ms, where the one-sample rule made every junction a stop). Every limit kept, X, Y, Z within P,
    A within 0.9 P of its programmed value at the nearest point of the path."""
    prog, plain = _program(_serpentine(0.7)), _program(_serpentine(None))
    sp = interpolate(prog, profile="scurve", sample_time=Ts)
    sp0 = interpolate(plain, profile="scurve", sample_time=Ts)
    assert sp.duration <= sp0.duration * (1.0 + 1e-9) + Ts
    assert "programmed_path" in sp.meta and _inner_stops(sp, prog) == 0
    check_limits(sp, prog, LIMITS, jerk=True)
    assert 0.001 <= distance_to_path(sp) <= 0.02
    assert _a_off_path(sp, prog) <= 0.9 * 0.02 + 1e-6
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


@pytest.mark.parametrize("Ts", [1e-3, 2.5e-4])
def test_contour_after_one_move_with_a_keeps_its_kink_blends(Ts):
    """The rounded rectangle of :func:`_rounded_square` (A still on it) after one feed move ``G1 Z-1 A5`` (S-curve):
    the move joins the chain (:func:`interpolators.interpolate._joins_extra`), and the contour's tangent line/arc
    junctions, A still on both sides, are blended as without it: the two take the contour's time and the move's own
    at most (before session 33 the contour kept its curvature steps: 6.380 s at 1 ms, 6.669 s at 0.25 ms, against
    5.945 s now)."""
    contour = [ln.split(" A")[0] for ln in _rounded_square(True)][1:]
    head = ["G21 G90 G64 P0.05 G0 X0 Y0 Z0 A0", "F3000"]
    prog = _program([*head, "G1 Z-1 A5", *contour])
    alone = interpolate(_program([*head, "G1 Z-1", *contour]), profile="scurve", sample_time=Ts)
    move = interpolate(_program([*head, "G1 Z-1 A5"]), profile="scurve", sample_time=Ts)
    sp = interpolate(prog, profile="scurve", sample_time=Ts)
    assert sp.duration <= alone.duration + move.duration
    assert sp.duration <= 5.95
    still = np.all(np.abs(sp.velocity) < 1e-9, axis=1)  # at rest in the contour (its first corner, A stopping, is)
    assert not np.any(still & (sp.block > 3) & (sp.block < len(prog.blocks) - 1))
    check_limits(sp, prog, LIMITS, jerk=True)
    assert 0.005 <= distance_to_path(sp) <= 0.05
    assert np.all(sp.position[sp.block > 2, sp.axes.index("a")] == 5.0)
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


@pytest.mark.parametrize("turn", [0.0, 0.1])
def test_kinks_beside_a_small_full_circle_with_a_are_blended_along_the_arc(turn):
    """``benchmarks.arc_kinks``' line, full circle of R1 and line (kinks of ``turn`` rad, F1200 P0.01) with A at 0.5
    deg/mm on every block, S-curve: A's programmed value beside a blend is read at the nearest point of the circle
    (by its angle; at the nearest point of its tangent line, 0.78 mm instead of 0.89 mm along it, the 0.1 rad kink's
    blend read 6.3 times 0.9 P off and was dropped: 1.078 s against 1.003 s without A). Within 2 % of the time
    without A, A within 0.9 P of its programmed value, every limit kept."""
    from benchmarks.arc_kinks import line_arc_line, with_a

    text = line_arc_line(turn, 1200.0, 0.01)
    prog = parse_program(with_a(text, 0.5), context=CTX)
    sp = interpolate(prog, profile="scurve")
    sp0 = interpolate(parse_program(with_a(text, None), context=CTX), profile="scurve")
    assert sp.duration <= 1.02 * sp0.duration
    assert "programmed_path" in sp.meta and _inner_stops(sp, prog) == 0
    check_limits(sp, prog, LIMITS, jerk=True)
    assert distance_to_path(sp) <= 0.01
    assert _a_off_path(sp, prog) <= 0.9 * 0.01 + 1e-6
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)


def _a_start_after_an_approach() -> list[str]:
    """A rapid approach, a line along -Y, then a G3 half circle of R5 tangent to it turning A 20 deg (1.27 deg/mm),
    then a line along +Y tangent to the arc's end with A still, at F1200 under G64 P0.5 (0.45 deg on A)."""
    return ["G21 G90 G17 G64 P0.5", "G0 X10 Y10 Z0 A0", "F1200", "G1 Y0", "G3 X20 Y0 I5 J0 A20", "G1 Y10"]


def _speed_at(sp, point: tuple[float, float]) -> float:
    """The X/Y path speed of the sample nearest ``point`` [mm/s]."""
    near = int(np.argmin(np.linalg.norm(sp.position[:, :2] - np.asarray(point), axis=1)))
    return float(np.linalg.norm(sp.velocity[near, :2]))


@pytest.mark.parametrize("Ts", [1e-3, 2.5e-4])
def test_a_starting_on_an_arc_after_an_approach_passes_at_speed(Ts):
    """S-curve. Where A starts (line/arc at X10 Y0): the line after the rapid belonged to the rapid's chain, and a
    chain with a rapid took no feed move of A: a stop, 0 mm/s; now the feed moves after the rapid start the chain of
    A (:func:`interpolators.interpolate._feeds_after_rapid`) and the junction passes at the rule of its curvature and
    rate steps, 15.5 mm/s at 1 ms, 7.9 mm/s at 0.25 ms (20 mm/s without A; the kink blend that would carry both
    leaves A beyond 0.9 P), as the junction where A stops (arc/line at X20 Y0) did before. 2.069 / 2.097 s ->
    2.029 / 2.084 s (2.009 s without A)."""
    prog = _program(_a_start_after_an_approach())
    sp = interpolate(prog, profile="scurve", sample_time=Ts)
    assert _speed_at(sp, (10.0, 0.0)) >= 7.5
    assert _speed_at(sp, (10.0, 0.0)) == pytest.approx(_speed_at(sp, (20.0, 0.0)), rel=0.02)
    assert sp.duration <= {1e-3: 2.03, 2.5e-4: 2.085}[Ts]
    check_limits(sp, prog, LIMITS, jerk=True)
    assert distance_to_path(sp) <= 0.5
    assert _a_off_path(sp, prog) <= 0.9 * 0.5 + 1e-6
    assert np.allclose(sp.position[-1], _end(prog, sp.axes), rtol=0, atol=1e-12)
