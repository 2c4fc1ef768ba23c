"""Contour evaluator: invariants on exact geometry (issue 6).

Sources: the steady radial error of a circle tracked by two identical axes, R (1 - |G(j omega)|)
with omega = F / R, is the classical result the thesis' circular tests rely on (Sec. 3.4.1,
Figs. 3.6 and 3.14).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.signal

import interpolators
import toolpaths
from toolpaths.geometry import Arc, Line, Path
from vcnc.contour import contour_error, contour_metrics, path_features
from vcnc.errors import InputError

#: A program no test was written against: lines, G02/G03 in G17, G18, G19, helices in G17, G64.
MIXED = """G21 G90 G17 G64
G00 X0 Y0 Z0
G01 X10 Y0 F3000
G03 X20 Y10 I0 J10
G02 X30 Y20 Z-2 I10 J0
G01 X30 Y-5 Z-2
G18 G02 X40 Z-2 I5 K0
G19 G03 Y-5 Z3 J0 K2.5
G17 G02 X30 Y-5 I-5 J0 Z1
G01 X0 Y0 Z0
M30
"""

HEIDENHAIN = """BEGIN PGM SHAPE MM
L X+0 Y+0 R0 FMAX
L X+15 Y+0 F6000
CC X+15 Y+10
C X+25 Y+10 DR+
L X+25 Y+30
CC X+15 Y+30
C X+5 Y+30 DR+
L X+0 Y+0
END PGM SHAPE MM
"""


def _setpoints(text: str, **kw):
    return interpolators.interpolate(interpolators.parse_program(text), sample_time=1e-3, **kw)


def _lag(pos: np.ndarray, n: int) -> np.ndarray:
    out = np.empty_like(pos)
    out[n:] = pos[:-n]
    out[:n] = pos[0]
    return out


def _brute(path: Path, positions: np.ndarray, axes, step: float = 0.005) -> np.ndarray:
    """Brute force: distance to every chord of the path sampled every ``step`` mm (exact within
    the chord sagitta, step^2 / (8 R) = 1.25e-6 mm for R = 2.5 mm)."""
    idx = [toolpaths.AXIS_LETTERS.index(a) for a in axes]
    pts = path.points(step=step)[:, idx]
    a, d = pts[:-1], np.diff(pts, axis=0)
    dd = np.maximum((d * d).sum(axis=1), 1e-300)
    out = np.empty(len(positions))
    for k0 in range(0, len(positions), 32):
        p = positions[k0 : k0 + 32, None, :]
        u = np.clip(((p - a) * d).sum(axis=2) / dd, 0.0, 1.0)
        r = p - (a + u[..., None] * d)
        out[k0 : k0 + 32] = np.sqrt((r * r).sum(axis=2).min(axis=1))
    return out


@pytest.mark.parametrize("text", [MIXED, HEIDENHAIN, toolpaths.circle(20.0, 12000), toolpaths.diamond(28.28, 12000)])
def test_ideal_machine_gives_zero_error_on_every_primitive(text):
    sp = _setpoints(text)
    for ref in (sp.position, None):  # windowed and global search
        ce = contour_error(sp.path, sp.position, sp.axes, reference=ref, t=sp.t)
        assert np.max(np.abs(ce.error)) < 1e-9
    kinds = {type(s).__name__ for s in sp.path}
    assert kinds <= {"Line", "Arc"}


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_straight_line_along_one_axis_has_zero_error_whatever_the_lag(axis):
    sp = _setpoints(f"G90 G00 X0 Y0 Z0\nG01 {axis.upper()}25 F9000\nG01 {axis.upper()}-5\nM30\n")
    for lag in (1, 20, 150):
        ce = contour_error(sp.path, _lag(sp.position, lag), sp.axes, reference=sp.position)
        assert np.max(np.abs(ce.error)) < 1e-12
        m = ce.metrics()
        assert m["max_um"] < 1e-9
        assert m["tracking"][axis]["max_um"] > 0


def test_lag_along_a_diagonal_line_is_no_contour_error():
    sp = _setpoints("G90 G00 X0 Y0 Z0\nG01 X30 Y-20 Z7 F9000\nM30\n")
    ce = contour_error(sp.path, _lag(sp.position, 40), sp.axes, reference=sp.position)
    assert np.max(np.abs(ce.error)) < 1e-12


@pytest.mark.parametrize(
    ("num", "den", "sign"),
    [
        ([1.0], [0.02, 1.0], -1),  # first-order lag, tau 20 ms: |G| < 1, inside
        ([(2 * math.pi * 8) ** 2], [1.0, 2 * 0.2 * 2 * math.pi * 8, (2 * math.pi * 8) ** 2], +1),  # |G| > 1, outside
    ],
)
def test_circle_radial_error_matches_transfer_function(num, den, sign):
    R, F, Ts = 20.0, 200.0, 1e-3
    omega = F / R
    turns = 6
    arc = Arc([R, 0, 0], [R, 0, 0], [0, 0, 0], ccw=True, turns=turns - 1)
    path = Path(segments=(arc,), blocks=(0,), axes=("x", "y"))
    k = np.arange(int(turns * 2 * math.pi / omega / Ts))
    ref = np.column_stack([R * np.cos(omega * k * Ts), R * np.sin(omega * k * Ts)])
    bd, ad, _ = scipy.signal.cont2discrete((num, den), Ts, method="zoh")
    act = np.column_stack([scipy.signal.lfilter(bd.ravel(), ad, ref[:, i]) for i in range(2)])
    ce = contour_error(path, act, ("x", "y"), reference=ref, sample_time=Ts)
    steady = ce.error[len(k) // 2 :]
    _, g = scipy.signal.freqs(num, den, worN=[omega])
    expected = R * (1.0 - abs(g[0]))
    assert np.sign(steady.mean()) == sign
    # the evaluator's steady radial error (signed: + outside) equals -R (1 - |G|) within 1 %
    assert np.ptp(steady) < 0.01 * abs(expected)
    assert abs(-steady.mean() - expected) <= 0.01 * abs(expected)


def test_sign_convention():
    ccw = Path(segments=(Arc([10, 0, 0], [10, 0, 0], [0, 0, 0], ccw=True),), blocks=(0,), axes=("x", "y"))
    cw = Path(segments=(Arc([10, 0, 0], [10, 0, 0], [0, 0, 0], ccw=False),), blocks=(0,), axes=("x", "y"))
    line = Path(segments=(Line([0, 0, 0], [10, 0, 0]),), blocks=(0,), axes=("x", "y"))
    outside = np.array([[0.0, 10.5]])
    assert contour_error(ccw, outside, ("x", "y")).error[0] == pytest.approx(0.5)
    assert contour_error(cw, outside, ("x", "y")).error[0] == pytest.approx(-0.5)
    assert contour_error(line, np.array([[5.0, 0.25]]), ("x", "y")).error[0] == pytest.approx(-0.25)  # left
    assert contour_error(line, np.array([[5.0, -0.25]]), ("x", "y")).error[0] == pytest.approx(0.25)  # right


def test_helix_distance_is_exact():
    helix = Arc([10, 0, 0], [10, 0, 12], [0, 0, 0], ccw=True, turns=2)  # 3 turns, rise 4 mm per turn
    path = Path(segments=(helix,), blocks=(0,), axes=("x", "y", "z"))
    s = np.linspace(0.0, helix.length, 2001)
    on = helix.point_at(s)
    ce = contour_error(path, on, ("x", "y", "z"), reference=on)
    assert np.max(np.abs(ce.error)) < 1e-9
    assert not ce.signed
    np.testing.assert_allclose(ce.arc_length, s, atol=1e-7)
    # radial displacement is perpendicular to the helix tangent: distance = displacement
    radial = np.column_stack([on[:, 0], on[:, 1], np.zeros(len(s))]) / 10.0
    off = on + 0.03 * radial
    ce = contour_error(path, off[10:-10], ("x", "y", "z"), reference=on[10:-10])
    np.testing.assert_allclose(ce.error, 0.03, rtol=1e-7)


def test_steep_helix_point_outside_the_sweep_angle_finds_the_foot_along_the_axis():
    # a quarter turn of radius 1 mm rising 50 mm (a G18/G19 helix of a tool-path program is as steep):
    # the points' in-plane angle lies before the sweep's start, yet the nearest point is mid-helix
    helix = Arc([1, 0, 0], [0, 1, 50], [0, 0, 0], ccw=True)
    path = Path(segments=(helix,), blocks=(0,), axes=("x", "y", "z"))
    pts = np.array([[math.cos(-0.05), math.sin(-0.05), z] for z in (10.0, 25.0, 40.0)])
    dense = helix.point_at(np.linspace(0.0, helix.length, 200_001))
    brute = np.min(np.linalg.norm(dense[None, :, :] - pts[:, None, :], axis=2), axis=1)
    ce = contour_error(path, pts, ("x", "y", "z"))
    np.testing.assert_allclose(ce.error, brute, atol=1e-6)
    assert np.all(ce.error < 1.5)  # the start point, 10-40 mm away, was taken before


def test_matches_brute_force_on_perturbed_programs():
    rng = np.random.default_rng(5)
    # open variants (the brute force would rightly see the start of a closed path near its end)
    programs = (MIXED.replace("G01 X0 Y0 Z0", "G01 X0 Y-10 Z0"), HEIDENHAIN.replace("L X+0 Y+0\n", "L X+0 Y+40\n"))
    for text in programs:
        sp = _setpoints(text)
        act = _lag(sp.position, 3) + rng.normal(0.0, 0.01, sp.position.shape)
        ce = contour_error(sp.path, act, sp.axes, reference=sp.position)
        np.testing.assert_allclose(np.abs(ce.error), _brute(sp.path, act, sp.axes), atol=2e-6)
        # the reported nearest point is on the reported segment at the reported arc length
        cum = np.concatenate([[0.0], np.cumsum([g.length for g in sp.path])])
        idx = [toolpaths.AXIS_LETTERS.index(a) for a in sp.axes]
        for k in range(0, len(act), 97):
            seg = sp.path[int(ce.segment[k])]
            foot = seg.point_at(ce.arc_length[k] - cum[ce.segment[k]])[idx]
            assert np.linalg.norm(act[k] - foot) == pytest.approx(abs(ce.error[k]), abs=1e-9)
        glob = contour_error(sp.path, act, sp.axes)
        np.testing.assert_allclose(glob.error, ce.error, atol=1e-9)


def test_circle_run_twice_is_located_in_order():
    text = "G90 G17\nG00 X10 Y0\nG03 X10 Y0 I-10 J0 F6000\nG03 X10 Y0 I-10 J0\nM30\n"
    sp = _setpoints(text)
    act = _lag(sp.position, 5) * 0.999
    ce = contour_error(sp.path, act, sp.axes, reference=sp.position)
    assert np.all(np.diff(ce.commanded_segment) >= 0)
    assert set(ce.commanded_segment.tolist()) == {0, 1, 2}
    assert np.all(np.diff(ce.commanded_arc_length) >= -1e-9)
    np.testing.assert_allclose(ce.arc_length[-1], sp.path.length, atol=0.5)


def _first_order(pos: np.ndarray, tau: float = 0.02, Ts: float = 1e-3) -> np.ndarray:
    a = math.exp(-Ts / tau)
    return np.column_stack([scipy.signal.lfilter([1 - a], [1, -a], pos[:, i] - pos[0, i]) + pos[0, i]
                            for i in range(pos.shape[1])])


def test_features_and_metrics_of_the_diamond():
    sp = _setpoints(toolpaths.diamond(20.0, 6000))
    feats = path_features(sp.path)
    assert len(feats["corners"]) == 4  # the rapid's end is a corner too, then 3 diamond vertices
    circ = path_features(_setpoints(toolpaths.circle(10.0, 6000)).path)
    np.testing.assert_allclose(np.diff(circ["quadrants"]), 10.0 * math.pi / 2)
    m = contour_error(sp.path, _first_order(sp.position), sp.axes, reference=sp.position).metrics()
    assert m["max_um"] > 1.0
    assert m["corner_max_um"] == pytest.approx(m["max_um"])  # a linear lag errs only at corners
    assert set(m["tracking"]) == {"x", "y"}
    # a G64 blend arc (a second segment of its block, as the look-ahead makes it) is a corner,
    # not a quadrant change, even where it crosses 90 degrees
    blend = Arc([9.0, 0, 0], [10.0, 1.0, 0], [9.0, 1.0, 0], ccw=True)
    path = Path(segments=(Line([0, 0, 0], [9.0, 0, 0]), blend, Line([10.0, 1.0, 0], [10.0, 10.0, 0])),
                blocks=(0, 0, 1), axes=("x", "y"))
    feats = path_features(path)
    np.testing.assert_allclose(feats["corners"], [9.0 + blend.length / 2])
    assert len(feats["quadrants"]) == 0


def test_feature_windows_of_a_zigzag_match_the_definition():
    # 59 corners: each corner's max is the largest error of the samples within FEATURE_WINDOW_MM of it
    from vcnc.contour import FEATURE_WINDOW_MM

    text = "G90 G00 X0 Y0\n" + "".join(f"G01 X{20 * (i % 2)} Y{2 * i} F6000\n" for i in range(1, 61)) + "M30\n"
    sp = _setpoints(text)
    ce = contour_error(sp.path, _first_order(sp.position), sp.axes, reference=sp.position)
    m = ce.metrics()
    corners = path_features(sp.path)["corners"]
    expected = [np.max(np.abs(ce.error[np.abs(ce.arc_length - s0) <= FEATURE_WINDOW_MM])) * 1e3 for s0 in corners]
    assert len(m["corners"]) == len(corners) == 59
    np.testing.assert_allclose([c["max_um"] for c in m["corners"]], expected, rtol=1e-12)
    np.testing.assert_allclose(m["corners"][5]["position_mm"][:2], [0.0, 12.0], atol=1e-9)  # end of move 6


def test_clothoid_blend_distance():
    from toolpaths.geometry import ClothoidPair

    corner = np.array([10.0, 0.0, 0.0])
    u_in, u_out = np.array([1.0, 0.0, 0.0]), np.array([0.6, 0.8, 0.0])
    blend = ClothoidPair.for_corner(corner, u_in, u_out, tolerance=0.2, max_leg=5.0)
    far = corner + 10.0 * u_out
    path = Path(segments=(Line([0, 0, 0], blend.start), blend, Line(blend.end, far)), blocks=(0, 0, 1),
                axes=("x", "y"))
    assert len(path_features(path)["corners"]) == 1
    s = np.linspace(0.0, path.length, 3001)
    cum = np.concatenate([[0.0], np.cumsum([g.length for g in path])])
    k = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, 2)
    on = np.array([path[int(i)].point_at(si - cum[i]) for i, si in zip(k, s)])[:, :2]
    ce = contour_error(path, on, ("x", "y"), reference=on)
    assert np.max(np.abs(ce.error)) < 1e-9
    act = on + np.random.default_rng(2).normal(0.0, 0.02, on.shape)
    ce = contour_error(path, act, ("x", "y"), reference=on)
    np.testing.assert_allclose(np.abs(ce.error), _brute(path, act, ("x", "y"), step=0.002), atol=2e-6)


def test_contour_metrics_of_a_capture():
    from vcnc.capture import Capture

    sp = _setpoints(toolpaths.circle(10.0, 6000))
    act = _lag(sp.position, 10)
    cap = Capture(t=sp.t, axes=sp.axes, reference=sp.position, measured=act, path=sp.path)
    m = contour_metrics(cap)
    assert set(m) == {"max_um", "rms_um"} and m["max_um"] > 0
    one = _setpoints("G90 G00 X0 Y0\nG01 X10 F6000\nM30\n")
    cap1 = Capture(t=one.t, axes=one.axes, reference=one.position, measured=_lag(one.position, 3), path=one.path)
    assert contour_metrics(cap1) is None


def test_bad_input_is_named():
    sp = _setpoints(toolpaths.circle(10.0, 6000))
    with pytest.raises(InputError, match="column"):
        contour_error(sp.path, sp.position, ("x",))
    with pytest.raises(InputError, match="not finite at sample 3"):
        bad = sp.position.copy()
        bad[3, 0] = np.nan
        contour_error(sp.path, bad, sp.axes)
    with pytest.raises(InputError, match="does not belong"):
        contour_error(sp.path, sp.position, sp.axes, reference=sp.position + 1.0)
    with pytest.raises(InputError, match="arc"):
        contour_error(sp.path, sp.position[:, :1], ("x",))


def _exact_distance(seg, p: np.ndarray) -> float:
    """Distance [mm] from ``p`` (x, y, z) to a Line or a planar Arc, in closed form (no search, no pruning)."""
    if isinstance(seg, Line):
        d = seg.end - seg.start
        u = min(max(float((p - seg.start) @ d / (d @ d)), 0.0), 1.0)
        return float(np.linalg.norm(p - (seg.start + u * d)))
    i, j = seg.plane_axes
    a, b = p[i] - seg.center[i], p[j] - seg.center[j]
    off = p[seg.plane] - seg.start[seg.plane]
    turn = (math.atan2(b, a) - seg.start_angle) % (2 * math.pi)
    if seg.sweep < 0:
        turn = (2 * math.pi - turn) % (2 * math.pi)
    if turn <= abs(seg.sweep):
        return math.hypot(math.hypot(a, b) - seg.radius, off)
    return min(float(np.linalg.norm(p - seg.start)), float(np.linalg.norm(p - seg.end)))


#: G61 (exact stop: lines and arcs only) programs no other test uses: corners of every angle, arcs of
#: less and more than half a turn in G17 and G18, a full circle, and a square and a circle run twice.
EXACT_PATHS = [
    "G21 G90 G17 G61\nG00 X0 Y0 Z0\nG01 X10 Y0 F3000\nX10 Y10\nX3 Y2\nX12 Y-4\nX-5 Y-4 Z1\nM30\n",
    "G21 G90 G17 G61\nG00 X0 Y0 Z0\nG03 X10 Y0 I5 J0 F3000\nG02 X10 Y8 I0 J4\nG03 X10 Y-2 I0 J-5\n"
    "G18 G02 X20 Z0 I5 K0\nG17 G03 X20 Y-2 I-3 J0\nM30\n",
    "G21 G90 G17 G61\nG00 X0 Y0 Z0\nG01 X8 Y0 F4000\nX8 Y8\nX0 Y8\nX0 Y0\nX8 Y0\nX8 Y8\nX0 Y8\nX0 Y0\n"
    "G03 X0 Y0 I4 J4\nG03 X0 Y0 I4 J4\nM30\n",
]


@pytest.mark.parametrize("text", EXACT_PATHS)
def test_distance_is_the_brute_force_minimum_over_every_segment(text):
    # the windowed, pruned search (with the command) and the global one (without) against the closed-form
    # distance to every segment of the path, to rounding: lagging, noisy and far-off (2 mm) positions
    sp = _setpoints(text)
    rng = np.random.default_rng(11)
    act = _lag(sp.position, 4) + rng.normal(0.0, 0.02, sp.position.shape)
    act[::50] += rng.normal(0.0, 2.0, act[::50].shape)
    want = np.array([min(_exact_distance(seg, p) for seg in sp.path) for p in act])
    windowed = contour_error(sp.path, act, sp.axes, reference=sp.position, window_s=(5.0, 5.0))
    glob = contour_error(sp.path, act, sp.axes)
    np.testing.assert_allclose(np.abs(windowed.error), want, rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.abs(glob.error), want, rtol=0, atol=1e-12)
    # and the nearest segment reported is one at that distance
    for k in range(0, len(act), 7):
        assert _exact_distance(sp.path[int(windowed.segment[k])], act[k]) == pytest.approx(want[k], abs=1e-12)
