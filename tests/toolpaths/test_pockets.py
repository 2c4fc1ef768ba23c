"""Regions of pockets less islands: the exact distance to their boundary and the offset rings within TOLERANCE.

Expectations are worked out by hand from the geometry (squares and circles)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toolpaths.pockets import TOLERANCE, Edge, offset_rings, region, segment_clear


def square(x0: float, y0: float, x1: float, y1: float) -> list[Edge]:
    pts = [np.array(p, float) for p in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
    return [Edge(start=a, end=b) for a, b in zip(pts, pts[1:] + pts[:1])]


def circle(cx: float, cy: float, r: float) -> list[Edge]:
    c = np.array([cx, cy])
    return [Edge(start=c + [r, 0.0], end=c + [r, 0.0], centre=c, radius=r, a0=0.0, sweep=2 * math.pi)]


def test_distance_is_signed_to_the_walls_and_the_islands():
    area = region([square(0, 0, 100, 100)], [square(40, 40, 60, 60), circle(80, 20, 5)])
    d, grad = area.distance(np.array([[20.0, 50.0], [50.0, 50.0], [80.0, 20.0], [80.0, 30.0], [-3.0, 50.0]]))
    # 20 from the left wall and from the square island; -10 inside the island (its centre); -5 at the circle's
    # centre; 5 above the circle; -3 outside the pocket
    assert d == pytest.approx([20.0, -10.0, -5.0, 5.0, -3.0])
    assert grad[3] == pytest.approx([0.0, 1.0])  # away from the circle, into the region


def test_overlapping_pockets_combine_and_their_inner_edges_are_no_walls():
    area = region([square(0, 0, 10, 10), square(5, 5, 15, 15)], [])
    # inside both: the nearest wall is a corner of the union, (10, 5) or (5, 10), not the edge x = 10 (2.5 away,
    # inside the other pocket)
    d, _ = area.distance(np.array([[7.5, 7.5], [12.0, 2.0]]))
    assert d[0] == pytest.approx(math.hypot(2.5, 2.5))
    assert d[1] == pytest.approx(-2.0)  # outside both: 2 from the first square's right edge
    assert len(area.boundary) == 8  # two L-shaped halves: 4 + 4 pieces


def test_offset_ring_of_a_circle_lies_within_the_tolerance_and_turns_as_asked():
    area = region([circle(0, 0, 20)], [])
    for left in (True, False):
        (rings,) = offset_rings(area, [5.0], step=1.0, left_higher=left)
        assert len(rings) == 1
        ring = rings[0]
        nxt = np.roll(ring, -1, axis=0)
        pts = (ring[:, None, :] + np.linspace(0, 1, 21)[None, :, None] * (nxt - ring)[:, None, :]).reshape(-1, 2)
        radius = np.linalg.norm(pts, axis=1)
        assert radius.max() <= 15.0 + 1e-9 and radius.min() >= 15.0 - TOLERANCE  # 5 to 5 + 1 um from the wall
        area2 = 0.5 * np.sum(ring[:, 0] * nxt[:, 1] - nxt[:, 0] * ring[:, 1])
        assert (area2 > 0) == left  # inside on the left: counter-clockwise in a pocket


def test_rings_of_a_pocket_round_an_island_keep_apart_until_they_meet():
    area = region([square(0, 0, 100, 100)], [square(40, 40, 60, 60)])
    small, wide = offset_rings(area, [5.0, 25.0], step=1.0)
    # at 5 mm: the wall's ring and the island's (clockwise round it); at 25: none (the gap is 40 wide)
    assert len(small) == 2 and wide == []
    island = min(small, key=lambda r: np.ptp(r[:, 0]))
    assert np.ptp(island[:, 0]) == pytest.approx(30.0 + TOLERANCE, abs=2e-3)  # 20 + 2 x 5, rounded corners
    nxt = np.roll(island, -1, axis=0)
    assert 0.5 * np.sum(island[:, 0] * nxt[:, 1] - nxt[:, 0] * island[:, 1]) < 0


def test_segment_clear_proves_a_link_or_refuses_one_that_crosses_an_island():
    area = region([square(0, 0, 100, 100)], [square(40, 40, 60, 60)])
    assert segment_clear(area, np.array([10.0, 10.0]), np.array([90.0, 10.0]), 5.0)
    assert not segment_clear(area, np.array([10.0, 50.0]), np.array([90.0, 50.0]), 5.0)
    assert not segment_clear(area, np.array([10.0, 10.0]), np.array([90.0, 90.0]), 5.0)


def test_a_triangular_pocket_has_a_triangular_ring_with_its_corners_exact():
    pts = [np.array(p, float) for p in ((0, 0), (40, 0), (0, 30))]
    area = region([[Edge(start=a, end=b) for a, b in zip(pts, pts[1:] + pts[:1])]], [])
    (rings,) = offset_rings(area, [2.0], step=0.5)
    assert len(rings) == 1 and len(rings[0]) == 3
    # the inner corner at the right angle: (2, 2) plus half the tolerance each way
    assert np.min(np.linalg.norm(rings[0] - (2.0 + TOLERANCE / 2), axis=1)) < 1e-9


def _box_distance(pts: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    """The signed distance of points (n, 2) to a rectangle's sides, by hand (> 0 outside it)."""
    q = np.abs(pts - [(x0 + x1) / 2, (y0 + y1) / 2]) - [(x1 - x0) / 2, (y1 - y0) / 2]
    return np.linalg.norm(np.maximum(q, 0.0), axis=1) + np.minimum(np.maximum(q[:, 0], q[:, 1]), 0.0)


def _chord_points(ring: np.ndarray) -> np.ndarray:
    nxt = np.roll(ring, -1, axis=0)
    return (ring[:, None, :] + np.linspace(0, 1, 21)[None, :, None] * (nxt - ring)[:, None, :]).reshape(-1, 2)


def _box_region_distance(pts: np.ndarray, pocket: tuple, islands: list[tuple]) -> np.ndarray:
    return np.min([-_box_distance(pts, *pocket), *(_box_distance(pts, *i) for i in islands)], axis=0)


def test_a_finger_of_the_level_set_narrower_than_the_grid_is_traced_from_the_offset_curves():
    """A channel 12.016 mm wide between an island and the wall, closed at its far end (the island 6.646 from the
    top wall), for the ring at 6.002 (a 5.502 tool with Q3 = 0.5): the level set runs up it and back 11 um apart
    (the slfuzz pocket of issue 19 that no grid of the whole pocket could separate)."""
    pocket, islands = (0.0, 0.0, 77.056, 68.546), [(53.677, 49.81, 65.04, 61.9), (19.338, 59.631, 22.003, 65.941)]
    area = region([square(*pocket)], [square(*i)[::-1] for i in islands])
    (rings,) = offset_rings(area, [6.002], step=1.209)
    assert len(rings) == 1
    d = _box_region_distance(_chord_points(rings[0]), pocket, islands)
    assert d.min() >= 6.002 - 1e-9 and d.max() <= 6.002 + TOLERANCE + 1e-9
    # up the channel to its end, 6.0025 below the top wall, on both sides of its middle x = 71.048
    # (the chords within the band cannot cut across it: its middle is 6.008 from both sides)
    for corner in ((77.056 - 6.0025, 68.546 - 6.0025), (65.04 + 6.0025, 61.9)):
        assert np.min(np.linalg.norm(rings[0] - corner, axis=1)) < 1e-6


def test_a_ring_thinner_than_the_grid_under_an_island_is_traced():
    """The ring at 25.2926 of a pocket whose island lies 50.599 above its bottom wall: under the island the ring's
    two sides run 13 um apart (2 x (25.2995 - 25.2931)), thinner than the grid's cells; past the island's corners
    they part (slfuzz, issue 19)."""
    pocket, islands = (0.0, 0.0, 91.975, 80.0), [(25.954, 50.599, 53.534, 65.26)]
    area = region([square(*pocket)], [square(*i)[::-1] for i in islands])
    (rings,) = offset_rings(area, [25.2926], step=0.76)
    assert len(rings) == 1
    d = _box_region_distance(_chord_points(rings[0]), pocket, islands)
    assert d.min() >= 25.2926 - 1e-9 and d.max() <= 25.2926 + TOLERANCE + 1e-9
    for corner in ((25.954, 50.599 - 25.2931), (53.534, 50.599 - 25.2931)):  # the island's side, straight
        assert np.min(np.linalg.norm(rings[0] - corner, axis=1)) < 1e-9
    wall = rings[0][np.abs(rings[0][:, 1] - 25.2931) < 1e-9]  # the wall's side, straight under the whole island
    assert wall[:, 0].min() < 25.954 and wall[:, 0].max() > 53.534


@pytest.mark.parametrize(("gap", "split"), [(5.99, True), (6.01, False)])
def test_a_channel_narrower_than_the_ring_splits_it_and_one_just_wider_keeps_it_whole(gap, split):
    """A 100 x 40 pocket with an island leaving ``gap`` above and below it, the ring at 3 (6.001 across with
    the tolerance): in two rings, left and right of the island, when the gaps are narrower; else one ring round
    the island and one inside the walls."""
    pocket, islands = (0.0, 0.0, 100.0, 40.0), [(40.0, gap, 60.0, 40.0 - gap)]
    area = region([square(*pocket)], [square(*i)[::-1] for i in islands])
    (rings,) = offset_rings(area, [3.0], step=1.0)
    assert len(rings) == 2
    for ring in rings:
        d = _box_region_distance(_chord_points(ring), pocket, islands)
        assert d.min() >= 3.0 - TOLERANCE and d.max() <= 3.0 + TOLERANCE + 1e-9
    spans = sorted((ring[:, 0].min(), ring[:, 0].max()) for ring in rings)
    if split:
        assert spans[0][1] < 40.0 and spans[1][0] > 60.0
    else:
        assert spans[0][0] < 40.0 < 60.0 < spans[0][1] and spans[1][0] < 40.0 < 60.0 < spans[1][1]


def test_a_point_level_with_where_a_circle_island_starts_is_counted_once():
    """The ray from a point level with the circle's start crosses the circle there once, though sin(-2 pi) puts
    the circle's recomputed end 3e-15 above its start: the pocket keeps its left wall (at y = 20, the circle's
    start's level) and the ring round the island passes 3 from the walls above and below it."""
    c, r = np.array([50.0, 20.0]), 14.0
    island = [Edge(start=c + [r, 0.0], end=c + [r, 0.0], centre=c, radius=r, a0=0.0, sweep=-2 * math.pi)]
    area = region([square(0, 0, 100, 40)], [island])
    assert list(area.contains(np.array([[1e-6, 20.0], [-1e-6, 20.0]]))) == [True, False]
    assert len(area.boundary) == 5
    (rings,) = offset_rings(area, [3.0], step=1.0)
    assert len(rings) == 2  # the gaps above and below the island (6) narrower than the rings need (6.001)
    for ring in rings:
        p = _chord_points(ring)
        d = np.minimum(-_box_distance(p, 0, 0, 100, 40), np.linalg.norm(p - c, axis=1) - r)
        assert d.min() >= 3.0 - TOLERANCE and d.max() <= 3.0 + TOLERANCE + 1e-9


def rounded_box(x0: float, y0: float, x1: float, y1: float, r: float, *, ccw: bool = True) -> list[Edge]:
    """A rectangle with corners rounded to ``r``, counter-clockwise from (x1 - r, y0) (or clockwise)."""
    centres = [(x1 - r, y0 + r), (x1 - r, y1 - r), (x0 + r, y1 - r), (x0 + r, y0 + r)]
    edges = []
    for k, (cx, cy) in enumerate(centres):
        a = -math.pi / 2 + k * math.pi / 2
        c = np.array([cx, cy])
        arc = Edge(start=c + r * np.array([math.cos(a), math.sin(a)]),
                   end=c + r * np.array([math.cos(a + math.pi / 2), math.sin(a + math.pi / 2)]), centre=c, radius=r,
                   a0=a, sweep=math.pi / 2)
        nxt = np.array(centres[(k + 1) % 4]) + r * np.array([math.cos(a + math.pi / 2), math.sin(a + math.pi / 2)])
        edges += [arc, Edge(start=arc.end, end=nxt)]
    if ccw:
        return edges
    return [Edge(start=e.end, end=e.start) if e.centre is None else
            Edge(start=e.end, end=e.start, centre=e.centre, radius=e.radius, a0=e.a0 + e.sweep, sweep=-e.sweep)
            for e in edges[::-1]]


def test_a_ring_past_a_circle_island_cut_by_the_wall_keeps_within_the_band_at_every_chord():
    """regfuzz seed 5 (issue 19): a rounded pocket, a circle island across its top wall and a slot island across
    it; merging the exact ring's points as a grid's would (a point dropped where a wall's offset meets an arc)
    left a chord 1.0055 um above the band and the ring did not settle."""
    w, h, r = 90.96367450835884, 31.922044492951276, 9.458225732947032
    c, rc = np.array([18.694751197918567, 29.05828926525136]), 3.035189865765036
    start = c + rc * np.array([math.cos(-1.506983679984217), math.sin(-1.506983679984217)])
    circle_island = [Edge(start=start, end=start, centre=c, radius=rc, a0=-1.506983679984217, sweep=-2 * math.pi)]
    slot = rounded_box(38.31446728425997, 3.82676989718427, 45.24633488067771, 32.632868974905485,
                       0.22953240777983228, ccw=False)
    area = region([rounded_box(0.0, 0.0, w, h, r)], [circle_island, slot])
    level = 7.123381523086605
    (rings,) = offset_rings(area, [level], step=level / 3)
    assert len(rings) == 2  # left and right of the slot (7.1 from the top wall, 7.1 from the slot's foot)
    for ring in rings:
        p = _chord_points(ring)
        d = np.min([np.abs(np.linalg.norm(p - c, axis=1) - rc), _rounded_box_distance(p, 0.0, 0.0, w, h, r),
                    _rounded_box_distance(p, 38.31446728425997, 3.82676989718427, 45.24633488067771,
                                          32.632868974905485, 0.22953240777983228)], axis=0)
        assert d.min() >= level - 1e-9 and d.max() <= level + TOLERANCE + 1e-9


def _rounded_box_distance(pts: np.ndarray, x0: float, y0: float, x1: float, y1: float, r: float) -> np.ndarray:
    """The unsigned distance of points to a rectangle with corners rounded to ``r``, by hand."""
    q = np.abs(pts - [(x0 + x1) / 2, (y0 + y1) / 2]) - [(x1 - x0) / 2 - r, (y1 - y0) / 2 - r]
    return np.abs(np.linalg.norm(np.maximum(q, 0.0), axis=1) + np.minimum(np.maximum(q[:, 0], q[:, 1]), 0.0) - r)
