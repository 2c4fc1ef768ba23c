"""Exact primitives: end points bit-exact, samples on the geometry, plane conventions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toolpaths import Arc, Line, PackedSegments, Path
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


def test_path_records_blocks():
    segs = (Line([0, 0, 0], [1, 0, 0]), Line([1, 0, 0], [1, 1, 0]))
    path = Path(segments=segs, blocks=(0, 2), axes=("x", "y"))
    assert len(path) == 2 and path.length == pytest.approx(2.0)
    with pytest.raises(InputError):
        Path(segments=segs, blocks=(0,))
