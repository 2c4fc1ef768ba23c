"""Interpolation invariants: exact geometry, limits on every axis, analytic and ruckig times."""

from __future__ import annotations

import math

import numpy as np
import pytest

import toolpaths as tp
from interpolators import DEFAULT_LIMITS, AxisLimits, interpolate, parse_program
from interpolators.profiles import ruckig_duration, trapezoid_duration
from tests.interpolators.setpoint_checks import check_limits
from toolpaths import Arc
from vcnc.errors import GCodeError, InputError

REL = 1e-6
LIMITS = {
    "x": AxisLimits(velocity=200.0, acceleration=2000.0, jerk=40_000.0, rapid=400.0),
    "y": AxisLimits(velocity=150.0, acceleration=1500.0, jerk=30_000.0, rapid=300.0),
    "z": AxisLimits(velocity=100.0, acceleration=1000.0, jerk=20_000.0, rapid=200.0),
}


def _random_program(seed: int, n: int = 30, *, g64: bool = False) -> str:
    """Lines, R arcs (<= and > 180 deg), IJK arcs, helices and other planes, random feeds."""
    rng = np.random.default_rng(seed)
    out = ["G21 G90 G17" + (" G64 P0.02" if g64 else " G61")]  # the default path mode is G64
    pos = np.zeros(3)
    for _ in range(n):
        kind = rng.integers(0, 4)
        f = rng.uniform(600, 15000)
        tgt = np.round(pos + rng.uniform(-8, 8, 3) * [1, 1, 0.3], 3)
        if kind <= 1:
            out.append(f"G01 X{tgt[0]:.3f} Y{tgt[1]:.3f} Z{tgt[2]:.3f} F{f:.0f}")
        elif kind == 2:
            chord = np.hypot(*(tgt[:2] - pos[:2]))
            r = chord / 2 * rng.uniform(1.01, 3) * rng.choice([-1, 1])
            out.append(f"G0{rng.integers(2, 4)} X{tgt[0]:.3f} Y{tgt[1]:.3f} R{r:.4f} F{f:.0f}")
            tgt[2] = pos[2]
        else:
            plane, (p, q) = [(17, (0, 1)), (18, (2, 0)), (19, (1, 2))][rng.integers(0, 3)]
            off = rng.uniform(-3, 3, 2)
            out.append(f"G{plane} G0{rng.integers(2, 4)} {'IJK'[p]}{off[0]:.3f} {'IJK'[q]}{off[1]:.3f} "
                       f"{'XYZ'[3 - p - q]}{pos[3 - p - q] + rng.uniform(-1, 1):.3f} F{f:.0f}")
            out.append("G17")
            tgt = None
        if tgt is not None:
            pos = tgt
        else:
            pos = None  # recomputed below from the parsed program
            prog = parse_program("\n".join(out) + "\n")
            pos = prog.blocks[-1].target.copy()
    return "\n".join(out) + "\nM30\n"


def _check_exact_geometry(sp, prog):
    full = np.zeros((len(sp), 3))
    cols = [("x", "y", "z").index(a) for a in sp.axes]
    full[:, cols] = sp.position
    for b_idx in np.unique(sp.block):
        b = prog.blocks[b_idx]
        m = sp.block == b_idx
        pts = full[m]
        seg = b.segment
        if seg is None:
            assert np.abs(pts - b.start).max() == 0
            continue
        other = [k for k in range(3) if k not in cols]
        pts[:, other] = np.asarray(seg.start)[other]  # axes not reported stay at their start
        if isinstance(seg, Arc):
            p, q = seg.plane_axes
            r = np.hypot(pts[:, p] - seg.center[p], pts[:, q] - seg.center[q])
            assert np.abs(r - seg.radius).max() <= 1e-9 * seg.radius
            # helix coordinate follows the angle
            ang = np.unwrap(np.arctan2(pts[:, q] - seg.center[q], pts[:, p] - seg.center[p]))
            frac = (ang - seg.start_angle) / seg.sweep
            frac -= np.round(frac[0])  # same turn as the start
            assert np.abs(pts[:, seg.plane] - (seg.start[seg.plane] + seg.helix * frac)).max() <= 1e-9 * max(
                1.0, seg.radius)
        else:
            d = pts - seg.start
            along = d @ seg.direction
            assert along.min() >= -1e-9 and along.max() <= seg.length + 1e-9
            assert np.abs(d - np.outer(along, seg.direction)).max() <= 1e-9
    # every block end point is a sample, exactly
    for k, b in enumerate(prog.blocks):
        if b.segment is None or b.segment.length == 0:
            continue
        idx = np.flatnonzero(sp.block == k)
        nxt = idx[-1] + 1 if idx[-1] + 1 < len(sp) else idx[-1]
        assert np.abs(full[nxt, cols] - b.target[cols]).max() <= 1e-9


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
@pytest.mark.parametrize("seed", [1, 2])
def test_random_programs_exact_stop(profile, seed):
    prog = parse_program(_random_program(seed))
    sp = interpolate(prog, limits=LIMITS, profile=profile)
    assert sp.axes == ("x", "y", "z")
    assert sp.meta["profile"] == profile and len(sp.path) >= len(prog.blocks) - 1
    _check_exact_geometry(sp, prog)
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    assert np.array_equal(sp.position[-1], prog.end_position)
    assert np.all(np.diff(sp.block) >= 0)


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_random_programs_continuous_path(profile):
    prog = parse_program(_random_program(5, g64=True))
    sp = interpolate(prog, limits=LIMITS, profile=profile)
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    assert np.array_equal(sp.position[-1], prog.end_position)
    stop = interpolate(parse_program(_random_program(5)), limits=LIMITS, profile=profile)
    assert sp.duration <= stop.duration + sp.sample_time  # never slower than stopping at every block


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_g64_polygon_blends_within_tolerance(profile):
    text = "G64 P0.05 G01 X20 F9000\nY20\nX0 Y20\nX0 Y0\nX20 Y0\nX20 Y10\nG61 X20 Y12\n"
    prog = parse_program(text)
    sp = interpolate(prog, limits=LIMITS, profile=profile)
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    # every sample within the tolerance of the programmed polyline
    pts = sp.position
    corners = np.array([[0, 0], [20, 0], [20, 20], [0, 20], [0, 0], [20, 0], [20, 10], [20, 12]], float)
    d = np.full(len(pts), np.inf)
    for a, b in zip(corners[:-1], corners[1:]):
        u = (b - a) / np.linalg.norm(b - a)
        t = np.clip((pts - a) @ u, 0, np.linalg.norm(b - a))
        d = np.minimum(d, np.linalg.norm(pts - a - np.outer(t, u), axis=1))
    assert d.max() <= 0.05 + 1e-9
    stop = interpolate(parse_program(text.replace("G64 P0.05", "G61")), limits=LIMITS, profile=profile)
    assert sp.duration <= stop.duration + sp.sample_time


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_g64_polyline_circle_within_limits(profile):
    # a 72-gon of radius 20 mm (5 degree corners) at 150 mm/s: corners are blended and passed at speed
    ang = np.linspace(0, 2 * np.pi, 73)
    pts = np.c_[20 * np.cos(ang), 20 * np.sin(ang)]
    body = "\n".join(f"X{x:.4f} Y{y:.4f}" for x, y in pts[1:])
    text = f"G00 X20 Y0\nG64 P0.01 G01 X{pts[1, 0]:.4f} Y{pts[1, 1]:.4f} F9000\n{body}\n"
    prog = parse_program(text)
    sp = interpolate(prog, limits=LIMITS, profile=profile)
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    stop = interpolate(parse_program(text.replace("G64 P0.01", "G61")), limits=LIMITS, profile=profile)
    if profile == "trapezoid":  # blended corners passed at speed
        assert sp.duration < 0.6 * stop.duration
        assert "programmed_path" in sp.meta
    else:  # arc blends have curvature steps the jerk limit allows only at low speed: no gain yet
        assert sp.duration <= stop.duration + sp.sample_time
    r = np.hypot(sp.position[:, 0], sp.position[:, 1])
    on = sp.block >= 1
    assert r[on].max() <= 20 + 1e-4 and r[on].min() >= 20 * np.cos(np.pi / 72) - 0.01 - 1e-9


def test_trapezoid_single_move_takes_analytic_time():
    Ts = 1e-3
    for length, feed in ((10.0, 6000.0), (1.0, 12000.0), (0.003, 15000.0), (57.3, 600.0)):
        prog = parse_program(f"G01 X{length} F{feed}\n")
        sp = interpolate(prog, profile="trapezoid", sample_time=Ts)
        V, A = feed / 60.0, DEFAULT_LIMITS["x"].acceleration
        T = float(trapezoid_duration(np.array([length]), np.array([V]), np.array([A]))[0])
        assert T - 1e-9 <= sp.duration < T + Ts
        assert sp.position[-1, 0] == length
        assert np.abs(sp.velocity[:, 0]).max() <= V * (1 + REL)


def test_scurve_single_move_agrees_with_ruckig():
    lim = DEFAULT_LIMITS["x"]
    for length, feed in ((10.0, 6000.0), (1.0, 12000.0), (0.003, 15000.0)):
        prog = parse_program(f"G01 X{length} F{feed}\n")
        sp = interpolate(prog, profile="scurve")
        T = ruckig_duration(length, 0.0, 0.0, feed / 60.0, lim.acceleration, lim.jerk)
        assert T - 1e-9 <= sp.duration < T + sp.sample_time


def test_arc_feed_capped_by_centripetal_acceleration():
    # R = 1 mm at 200 mm/s would need 40000 mm/s^2: the feed is lowered to respect 2000 mm/s^2
    prog = parse_program("G01 X1 F12000\nG03 I-1\n")
    for profile in ("trapezoid", "scurve"):
        sp = interpolate(prog, profile=profile)
        check_limits(sp, prog, DEFAULT_LIMITS, jerk=profile == "scurve", feed=True)
        on_arc = sp.block == 1
        speed = np.linalg.norm(sp.velocity[on_arc], axis=1)
        assert speed.max() <= math.sqrt(2000.0 * 1.0) + 1e-9


def test_rapid_is_straight_at_rapid_rate():
    prog = parse_program("G00 X100 Y50\n")
    sp = interpolate(prog, limits=LIMITS)
    check_limits(sp, prog, LIMITS, jerk=False, feed=True)
    assert np.abs(np.cross(np.c_[sp.position, np.zeros(len(sp))], [100, 50, 0])).max() < 1e-9
    assert np.abs(sp.velocity[:, 0]).max() == pytest.approx(LIMITS["x"].rapid_rate, rel=1e-3)


def test_dwell_and_sample_time():
    prog = parse_program("G01 X1 F600\nG04 P0.0125\nG01 X0\n")  # LinuxCNC: P in seconds
    sp = interpolate(prog, sample_time=0.5e-3)
    dwell = sp.block == 1
    assert dwell.sum() == 25 and np.all(sp.position[dwell, 0] == 1.0) and np.all(sp.velocity[dwell] == 0)
    assert np.allclose(np.diff(sp.t), 0.5e-3)


def test_thesis_programs_interpolate():
    for text in (tp.random_moves(40, seed=3), tp.heidenhain_identification("slow", n=30),
                 tp.heidenhain_identification("fast", n=20)):
        prog = parse_program(text)
        for profile in ("trapezoid", "scurve"):
            sp = interpolate(prog, profile=profile)
            check_limits(sp, prog, DEFAULT_LIMITS, jerk=profile == "scurve", feed=True)
            _check_exact_geometry(sp, prog)


def test_bad_arguments():
    prog = parse_program("G01 X1 F600\n")
    with pytest.raises(InputError):
        interpolate(prog, profile="quintic")
    with pytest.raises(InputError):
        interpolate(prog, sample_time=0.0)
    with pytest.raises(InputError, match="no limits for axis 'x'"):
        interpolate(prog, limits={"y": LIMITS["y"]})
    with pytest.raises(InputError, match="finite jerk"):
        interpolate(prog, limits={"x": AxisLimits(velocity=1, acceleration=1)}, profile="scurve")
    with pytest.raises(GCodeError, match="max_samples"):
        interpolate(parse_program("G01 X1000 F1\n"), max_samples=10_000)


@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_setpoints_sampled_in_chunks_are_the_same(profile, monkeypatch):
    """The samples are evaluated SAMPLE_CHUNK at a time (memory): chunks of 997 samples, which cut phases, blends,
    a dense-line curve, a dwell and a rotary move anywhere, give exactly the setpoints of one chunk."""
    import importlib

    from interpolators.context import MachineContext

    module = importlib.import_module("interpolators.interpolate")
    chords = "\n".join(f"G1 X{20 + 5 * math.cos(i / 40):.4f} Y{5 * math.sin(i / 40):.4f}" for i in range(1, 250))
    prog = parse_program("G21 G90 G64 P0.01\nG1 X10 F1200\nG1 Y5\nG2 X15 Y0 I0 J-5\nG1 X25\n" + chords +
                         "\nG4 P0.05\nG1 A30 F3600\nG0 X0 Y0\nM30\n",
                         context=MachineContext(extra_axes=("a",)))
    monkeypatch.setattr(module, "SAMPLE_CHUNK", 1 << 40)
    whole = interpolate(prog, profile=profile)
    monkeypatch.setattr(module, "SAMPLE_CHUNK", 997)
    chunked = interpolate(prog, profile=profile)
    assert len(whole.t) > 4 * 997
    for name in ("t", "position", "velocity", "acceleration", "block"):
        assert np.array_equal(getattr(whole, name), getattr(chunked, name)), name
    assert chunked.axes == ("x", "y", "a") and chunked.position[-1].tolist() == [0.0, 0.0, 30.0]
