"""Exact primitives: end points bit-exact, samples on the geometry, plane conventions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toolpaths import Arc, Line, PackedSegments, Path
from toolpaths.geometry import PLANE_AXES, ClothoidPair, SplineCurve
from vcnc.errors import InputError


def test_line_end_points_exact_and_tangent():
    ln = Line([0.1, 0.2, 0.3], [1.7, -2.9, 0.3])
    s = np.linspace(0, ln.length, 101)
    p = ln.point_at(s)
    assert np.array_equal(p[0], ln.start) and np.array_equal(p[-1], ln.end)
    d = np.cross(p - ln.start, ln.direction)
    assert np.abs(d).max() < 1e-12
    assert np.allclose(np.linalg.norm(ln.tangent_at(s), axis=1), 1.0)


@pytest.mark.parametrize("plane", [0, 1, 2])
@pytest.mark.parametrize("ccw", [True, False])
def test_arc_samples_on_circle_and_direction(plane, ccw):
    p, q = {2: (0, 1), 1: (2, 0), 0: (1, 2)}[plane]
    c = np.array([1.0, -2.0, 0.5])
    r = 3.0
    start = c.copy()
    start[p] += r
    end = c.copy()
    end[q] += r  # a quarter turn counter-clockwise, or three quarters clockwise
    end[plane] += 2.0  # helix
    arc = Arc(start, end, c, ccw=ccw, plane=plane)
    assert arc.sweep == pytest.approx(math.pi / 2 if ccw else -3 * math.pi / 2)
    assert arc.helix == pytest.approx(2.0)
    s = np.linspace(0, arc.length, 257)
    pts = arc.point_at(s)
    assert np.array_equal(pts[0], arc.start) and np.array_equal(pts[-1], arc.end)
    rad = np.hypot(pts[:, p] - c[p], pts[:, q] - c[q])
    assert np.abs(rad - r).max() < 1e-12 * r
    # helix rises linearly with arc length
    assert np.allclose(pts[:, plane] - start[plane], 2.0 * s / arc.length, atol=1e-12)
    # tangent is the derivative of the point
    h = 1e-6
    num = (arc.point_at(s[1:-1] + h) - arc.point_at(s[1:-1] - h)) / (2 * h)
    assert np.abs(num - arc.tangent_at(s[1:-1])).max() < 1e-6
    assert np.allclose(np.linalg.norm(arc.tangent_at(s), axis=1), 1.0)


def test_full_circle_and_bad_arcs():
    arc = Arc([5, 0, 0], [5, 0, 0], [0, 0, 0], ccw=False)
    assert arc.sweep == pytest.approx(-2 * math.pi)
    assert arc.length == pytest.approx(10 * math.pi)
    with pytest.raises(InputError):
        Arc([5, 0, 0], [0, 6, 0], [0, 0, 0], ccw=True)
    with pytest.raises(InputError):
        Arc([0, 0, 0], [0, 0, 0], [0, 0, 0], ccw=True)


def test_packed_matches_primitives():
    rng = np.random.default_rng(3)
    segs = [
        Line([0, 0, 0], [3, 4, 0]),
        Arc([3, 4, 0], [3, 4, 0], [1, 4, 0], ccw=True),
        Arc([0, 1, 1], [1, 0, 2], [0, 0, 1], ccw=False, plane=0),
        np.array([1.0, 2.0, 3.0]),
    ]
    packed = PackedSegments.from_segments(segs)
    for i, seg in enumerate(segs[:3]):
        s = np.concatenate([[0.0], rng.uniform(0, seg.length, 50), [seg.length]])
        v = rng.uniform(0, 10, len(s))
        a = rng.uniform(-5, 5, len(s))
        pos, vel, acc = packed.evaluate(np.full(len(s), i), s, v, a)
        assert np.array_equal(pos[0], seg.start) and np.array_equal(pos[-1], seg.end)
        assert np.allclose(pos, seg.point_at(s), atol=1e-12)
        assert np.allclose(vel, seg.tangent_at(s) * v[:, None], atol=1e-12)
        assert np.allclose(acc, seg.tangent_at(s) * a[:, None] + seg.curvature_at(s) * (v * v)[:, None], atol=1e-12)
    pos, _, _ = packed.evaluate(np.array([3]), np.array([0.0]))
    assert np.array_equal(pos[0], segs[3])
    # mixed kinds in any order, without acceleration; arc lengths beyond the ends are clipped to them
    seg = rng.integers(0, 4, 40)
    s = rng.uniform(-1.0, 12.0, 40)
    pos, vel, acc = packed.evaluate(seg, s, np.ones(40))
    assert acc is None
    for i, (k, s_k) in enumerate(zip(seg, s)):
        if k == 3:
            assert np.array_equal(pos[i], segs[3]) and not vel[i].any()
            continue
        s_k = min(max(s_k, 0.0), segs[k].length)
        assert np.allclose(pos[i], segs[k].point_at(s_k), atol=1e-12)
        assert np.allclose(vel[i], segs[k].tangent_at(s_k), atol=1e-12)


def test_path_records_blocks():
    segs = (Line([0, 0, 0], [1, 0, 0]), Line([1, 0, 0], [1, 1, 0]))
    path = Path(segments=segs, blocks=(0, 2), axes=("x", "y"))
    assert len(path) == 2 and path.length == pytest.approx(2.0)
    with pytest.raises(InputError):
        Path(segments=segs, blocks=(0,))


def _same_attributes(built, reference, names) -> None:
    for name in names:
        np.testing.assert_allclose(getattr(built, name), getattr(reference, name), rtol=1e-13, atol=1e-13,
                                   err_msg=name)


def test_bulk_constructors_match_the_constructors_row_by_row():
    """Line/Arc/ClothoidPair.from_arrays build what the constructors build per row, None where they raise."""
    rng = np.random.default_rng(3)
    start, end = rng.normal(size=(20, 3)) * 50, rng.normal(size=(20, 3)) * 50
    for built, a, b in zip(Line.from_arrays(start, end), start, end):
        _same_attributes(built, Line(a, b), ("start", "end", "length", "direction"))
    # arcs in the three planes, both senses, one with its end off the circle (the constructor raises)
    center = rng.normal(size=(6, 3)) * 10
    plane = np.array([0, 1, 2, 0, 1, 2])
    ccw = np.array([True, False, True, False, True, False])
    ang0, ang1 = rng.uniform(0, 2 * np.pi, 6), rng.uniform(0, 2 * np.pi, 6)
    a_start, a_end = center.copy(), center.copy()
    for i, k in enumerate(plane):
        p, q = PLANE_AXES[int(k)]
        a_start[i, [p, q]] += 7.0 * np.array([np.cos(ang0[i]), np.sin(ang0[i])])
        a_end[i, [p, q]] += 7.0 * np.array([np.cos(ang1[i]), np.sin(ang1[i])])
        a_end[i, k] += 3.0  # a helix
    a_end[4] += 0.5 * (a_end[4] - center[4])  # off the circle
    built = Arc.from_arrays(a_start, a_end, center, ccw=ccw, plane=plane)
    for i, arc in enumerate(built):
        if i == 4:
            assert arc is None
            with pytest.raises(InputError):
                Arc(a_start[i], a_end[i], center[i], ccw=bool(ccw[i]), plane=int(plane[i]))
            continue
        ref = Arc(a_start[i], a_end[i], center[i], ccw=bool(ccw[i]), plane=int(plane[i]))
        _same_attributes(arc, ref, ("start", "end", "center", "radius", "start_angle", "sweep", "helix", "length"))
        assert (arc.plane, arc.plane_axes, arc.ccw) == (ref.plane, ref.plane_axes, ref.ccw)
        s = np.linspace(0.0, ref.length, 9)
        np.testing.assert_allclose(arc.point_at(s), ref.point_at(s), atol=1e-12)
    # clothoid pairs: random corners, one with unequal legs (the constructor raises)
    corner = rng.normal(size=(5, 3))
    u_in, u_out = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    u_in /= np.linalg.norm(u_in, axis=1)[:, None]
    u_out /= np.linalg.norm(u_out, axis=1)[:, None]
    c_start, c_end = corner - 0.3 * u_in, corner + 0.3 * u_out
    c_end[2] = corner[2] + 0.5 * u_out[2]
    for i, blend in enumerate(ClothoidPair.from_arrays(c_start, corner, c_end)):
        if i == 2:
            assert blend is None
            continue
        ref = ClothoidPair(c_start[i], corner[i], c_end[i])
        _same_attributes(blend, ref, ("start", "corner", "end", "length", "half_length", "deflection", "sharpness",
                                      "peak_curvature", "deviation", "u_in", "u_out", "w_in", "w_out", "normal"))


def test_spline_curve_bounds_hold_between_the_table_nodes():
    # a quintic whose tangent turns through +X between two of its four table nodes: the largest |t_x| of the nodes
    # was 0.967, and a merged CAM curve planned from it ran X 0.46 % over its velocity limit (setpoint fuzzer,
    # tnc_cam seed 239); the bound now adds the curvature times half the node spacing
    t_in, t_out = np.array([1.0, -0.9, 0.0]), np.array([1.0, 1.0, 0.0])
    curve = SplineCurve.hermite(np.zeros(3), t_in / np.linalg.norm(t_in), np.zeros(3), np.array([1.0, 0.2, 0.0]),
                                t_out / np.linalg.norm(t_out), np.zeros(3), subdivisions=4)
    t = np.abs(curve.tangent_at(np.linspace(0.0, curve.length, 20001)))
    kappa, _, t_abs = curve.bounds()
    assert t[:, 0].max() == pytest.approx(1.0, abs=1e-9)
    assert np.all(t_abs >= t.max(axis=0) - 1e-12)
    assert t_abs[0] == 1.0 and t_abs[2] == 0.0
    assert kappa > 0
