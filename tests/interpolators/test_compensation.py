"""Cutter radius compensation: LinuxCNC's entry, corner and exit rules with exact expected tool-centre points.

Every expected point below is worked out by hand from the rules in :mod:`interpolators.compensation`
(offset by the tool radius, arcs about the programmed point at outside corners, intersections at
inside corners).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.compensation import CompensationError, compensate
from interpolators.program import Block
from toolpaths.geometry import Arc, Line


def _p(v: list[float]) -> np.ndarray:
    return np.array(list(v) + [0.0] * (3 - len(v)), dtype=float)


def _line(a: list[float], b: list[float], line: int, *, kind: str = "line", feed: float = 10.0) -> Block:
    a3, b3 = _p(a), _p(b)
    return Block(line=line, text=f"N{line}", kind=kind, start=a3, target=b3, feed=feed, segment=Line(a3, b3))


def _arc(a: list[float], b: list[float], c: list[float], line: int, *, ccw: bool, plane: int = 2) -> Block:
    a3, b3 = _p(a), _p(b)
    return Block(line=line, text=f"N{line}", kind="arc", start=a3, target=b3, feed=10.0,
                 segment=Arc(a3, b3, _p(c), ccw=ccw, plane=plane))


def _polyline(points: list[list[float]]) -> list[Block]:
    return [_line(points[k], points[k + 1], k + 1) for k in range(len(points) - 1)]


def _check(out: list[Block], expected: list[tuple]) -> None:
    """``expected``: (line, kind, start, target, arc centre or None, ccw or None) per output block."""
    assert len(out) == len(expected)
    for b, (line, kind, start, target, centre, ccw) in zip(out, expected):
        assert (b.line, b.kind) == (line, kind)
        np.testing.assert_allclose(b.start, _p(start), atol=1e-12)
        np.testing.assert_allclose(b.target, _p(target), atol=1e-12)
        np.testing.assert_array_equal(b.segment.start, b.start)
        np.testing.assert_array_equal(b.segment.end, b.target)
        if centre is None:
            assert isinstance(b.segment, Line)
        else:
            assert isinstance(b.segment, Arc)
            np.testing.assert_allclose(b.segment.center, _p(centre), atol=1e-12)
            assert b.segment.ccw is ccw
    for prev, nxt in zip(out[:-1], out[1:]):  # the tool path is continuous
        np.testing.assert_allclose(prev.target, nxt.start, atol=1e-12)


def test_outline_outside_corners_get_arcs_and_entry_meets_first_side():
    # G41 r=2 around the outside of the square 0..20 travelling clockwise, entry from (-10,-10).
    out = compensate(_polyline([[-10, -10], [0, 0], [0, 20], [20, 20], [20, 0], [0, 0], [-10, -10]]),
                     side="left", radius=2.0, plane=2)
    # entry ends at (0,0) + 2 * (-1, 1)/sqrt(2) (convert_straight_comp1); the inside corner with x = -2 is taken on
    # the entry's parallel offset y = x + 2 sqrt(2)
    y_in = -2.0 + 2.0 * math.sqrt(2.0)
    _check(out, [
        (1, "line", [-10, -10], [-2, y_in], None, None),
        (2, "line", [-2, y_in], [-2, 20], None, None),
        (3, "arc", [-2, 20], [0, 22], [0, 20], False),
        (3, "line", [0, 22], [20, 22], None, None),
        (4, "arc", [20, 22], [22, 20], [20, 20], False),
        (4, "line", [22, 20], [22, 0], None, None),
        (5, "arc", [22, 0], [20, -2], [20, 0], False),
        (5, "line", [20, -2], [0, -2], None, None),
        (6, "line", [0, -2], [-10, -10], None, None),  # exit: straight to the programmed point
    ])
    assert out[2].text == "N3" and out[2].feed == 10.0


def test_pocket_inside_corners_are_intersections():
    # G41 r=2 inside the square 0..20 travelling counter-clockwise, entry from the centre.
    out = compensate(_polyline([[10, 10], [0, 0], [20, 0], [20, 20], [0, 20], [0, 0], [10, 10]]),
                     side="left", radius=2.0, plane=2)
    x_in = 2.0 + 2.0 * math.sqrt(2.0)  # y = 2 on the entry's parallel offset y = x - 2 sqrt(2)
    _check(out, [
        (1, "line", [10, 10], [x_in, 2], None, None),
        (2, "line", [x_in, 2], [18, 2], None, None),
        (3, "line", [18, 2], [18, 18], None, None),
        (4, "line", [18, 18], [2, 18], None, None),
        (5, "line", [2, 18], [2, 0], None, None),  # the last element ends perpendicular (LinuxCNC)
        (6, "line", [2, 0], [10, 10], None, None),
    ])


def test_right_side_mirrors_left():
    # the same clockwise outline with G42 puts the tool inside: the entry turns away from the tool (arc about
    # the programmed point), the corners of the square are intersections
    out = compensate(_polyline([[-10, -10], [0, 0], [0, 20], [20, 20], [20, 0], [0, 0], [-10, -10]]),
                     side="right", radius=2.0, plane=2)
    e = [math.sqrt(2.0), -math.sqrt(2.0)]  # (0,0) + 2 * (1,-1)/sqrt(2)
    _check(out, [
        (1, "line", [-10, -10], e, None, None),
        (2, "arc", e, [2, 0], [0, 0], True),
        (2, "line", [2, 0], [2, 18], None, None),
        (3, "line", [2, 18], [18, 18], None, None),
        (4, "line", [18, 18], [18, 2], None, None),
        (5, "line", [18, 2], [0, 2], None, None),
        (6, "line", [0, 2], [-10, -10], None, None),
    ])


@pytest.mark.parametrize(("side", "r_arc", "x_side"), [("right", 12.0, 22.0), ("left", 8.0, 18.0)])
def test_line_arc_line_tangent_junctions(side, r_arc, x_side):
    # line along +x, counter-clockwise quarter arc about (10,10), line along +y: tangent, so no corner blocks
    d = 2.0 if side == "right" else -2.0
    blocks = [_line([-10, 0], [0, 0], 1),
              _line([0, 0], [10, 0], 2), _arc([10, 0], [20, 10], [10, 10], 3, ccw=True),
              _line([20, 10], [20, 20], 4), _line([20, 20], [20, 30], 5)]
    out = compensate(blocks, side=side, radius=2.0, plane=2)
    y_side = -d
    _check(out, [
        (1, "line", [-10, 0], [0, y_side], None, None),
        (2, "line", [0, y_side], [10, y_side], None, None),
        (3, "arc", [10, y_side], [x_side, 10], [10, 10], True),
        (4, "line", [x_side, 10], [x_side, 20], None, None),
        (5, "line", [x_side, 20], [20, 30], None, None),
    ])
    assert out[2].segment.radius == pytest.approx(r_arc, abs=1e-12)


def _two_arcs() -> list[Block]:
    # counter-clockwise arc about (0,0) ending at (0,10) heading -x, then counter-clockwise arc about
    # (-10,10) leaving (0,10) heading +y: a 90 degree right turn at (0,10)
    return [_line([10, -20], [10, 0], 1), _arc([10, 0], [0, 10], [0, 0], 2, ccw=True),
            _arc([0, 10], [-10, 20], [-10, 10], 3, ccw=True), _line([-10, 20], [-10, 40], 4)]


def test_arc_arc_outside_corner_left():
    out = compensate(_two_arcs(), side="left", radius=2.0, plane=2)
    _check(out, [
        (1, "line", [10, -20], [8, 0], None, None),
        (2, "arc", [8, 0], [0, 8], [0, 0], True),
        (3, "arc", [0, 8], [-2, 10], [0, 10], False),  # corner arc about the programmed corner
        (3, "arc", [-2, 10], [-10, 18], [-10, 10], True),
        (4, "line", [-10, 18], [-10, 40], None, None),
    ])


def test_arc_arc_inside_corner_right():
    out = compensate(_two_arcs(), side="right", radius=2.0, plane=2)
    # circles of radius 12 about (0,0) and (-10,10) meet at (-5,5) + sqrt(94) (1,1)/sqrt(2)
    x = [-5.0 + math.sqrt(47.0), 5.0 + math.sqrt(47.0)]
    _check(out, [
        (1, "line", [10, -20], [12, 0], None, None),
        (2, "arc", [12, 0], x, [0, 0], True),
        (3, "arc", x, [-10, 22], [-10, 10], True),
        (4, "line", [-10, 22], [-10, 40], None, None),
    ])


def test_perpendicular_entry_reaches_first_element_offset():
    out = compensate(_polyline([[10, 10], [0, 0], [20, 0], [20, 20], [30, 30]]), side="left", radius=2.0, plane=2,
                     entry="perpendicular")
    _check(out, [
        (1, "line", [10, 10], [0, 2], None, None),
        (2, "line", [0, 2], [18, 2], None, None),
        (3, "line", [18, 2], [18, 20], None, None),
        (4, "line", [18, 20], [30, 30], None, None),
    ])


def test_tool_axis_moves_and_dwells_follow_the_tool():
    a, b, c = _p([0, 0, 5]), _p([0, 0, -1]), _p([10, 0, -1])
    plunge = Block(line=3, kind="line", start=a, target=b, feed=5.0, segment=Line(a, b))
    dwell = Block(line=4, kind="dwell", start=b, target=b, feed=0.0, dwell=0.5)
    blocks = [_line([-10, 0, 5], [0, 0, 5], 1), plunge, dwell,
              Block(line=5, kind="line", start=b, target=c, feed=10.0, segment=Line(b, c)),
              _line([10, 0, -1], [10, 10, -1], 6)]
    out = compensate(blocks, side="right", radius=1.0, plane=2)
    assert [(b.line, b.kind) for b in out] == [(1, "line"), (3, "line"), (4, "dwell"), (5, "line"), (6, "line")]
    expected = [([-10, 0, 5], [0, -1, 5]), ([0, -1, 5], [0, -1, -1]), ([0, -1, -1], [0, -1, -1]),
                ([0, -1, -1], [10, -1, -1]), ([10, -1, -1], [10, 10, -1])]
    for b, (start, target) in zip(out, expected):
        np.testing.assert_allclose(b.start, start, atol=1e-12)
        np.testing.assert_allclose(b.target, target, atol=1e-12)
    assert out[2].segment is None and out[2].dwell == 0.5


def test_zx_plane():
    # G18: in-plane axes (z, x), tool axis y; left of travel along +z is +x
    blocks = [_line([0, 5, -10], [0, 5, 0], 1), _line([0, 5, 0], [0, 5, 10], 2), _line([0, 5, 10], [10, 5, 10], 3)]
    out = compensate(blocks, side="left", radius=2.0, plane=1)
    _check(out, [
        (1, "line", [0, 5, -10], [2, 5, 0], None, None),
        (2, "line", [2, 5, 0], [2, 5, 10], None, None),
        (3, "line", [2, 5, 10], [10, 5, 10], None, None),
    ])


def test_zero_radius_is_identity():
    blocks = _two_arcs()
    out = compensate(blocks, side="left", radius=0.0, plane=2)
    assert len(out) == len(blocks) and all(o is b for o, b in zip(out, blocks))


def test_gouge_in_a_slot_narrower_than_the_tool():
    # the 1 mm step cannot be followed by a tool of radius 2: its offset would run backwards
    blocks = _polyline([[-10, 0], [0, 0], [10, 0], [10, 1], [0, 1], [-10, 1]])
    gouge = "Straight feed in concave corner cannot be reached by the tool without gouging"
    with pytest.raises(CompensationError, match=gouge) as err:
        compensate(blocks, side="left", radius=2.0, plane=2)
    assert err.value.index == 2
    assert isinstance(err.value, ValueError)


def test_tool_larger_than_inside_arc():
    blocks = [_line([1, -10], [1, 0], 1), _arc([1, 0], [0, 1], [0, 0], 2, ccw=True), _line([0, 1], [-10, 1], 3)]
    with pytest.raises(CompensationError, match="not less than arc radius") as err:
        compensate(blocks, side="left", radius=2.0, plane=2)
    assert err.value.index == 1
    compensate(blocks, side="right", radius=2.0, plane=2)  # outside the arc it is fine


def test_entry_errors():
    with pytest.raises(CompensationError, match="entry move .* not greater than the tool radius") as err:
        compensate(_polyline([[1, 0], [0, 0], [0, 10]]), side="left", radius=2.0, plane=2)
    assert err.value.index == 0
    with pytest.raises(CompensationError, match="entry move must be a straight line"):  # the TNC's rule
        compensate([_arc([10, 0], [0, 10], [0, 0], 1, ccw=True), _line([0, 10], [-10, 10], 2)],
                   side="left", radius=2.0, plane=2, entry="perpendicular")
    with pytest.raises(CompensationError, match="entry arc is not greater than the tool radius"):
        compensate([_arc([1, 0], [0, 1], [0, 0], 1, ccw=True), _line([0, 1], [-10, 1], 2)],
                   side="left", radius=2.0, plane=2)
    with pytest.raises(CompensationError, match="exit move must be a straight line"):
        compensate([_line([10, -10], [10, 0], 1), _line([10, 0], [10, 5], 2),
                    _arc([10, 5], [0, 15], [0, 5], 3, ccw=True)], side="left", radius=2.0, plane=2)


def test_arc_entry_ends_one_radius_along_the_radius_about_a_new_centre():
    """LinuxCNC convert_arc_comp1 (tests/ccomp/mill-zchanges): a G3 entry from (10, 0) to (0, 10) about
    (0, 0) with the tool 2 mm to the left (inside) ends at (0, 10) moved 2 towards the centre, (0, 8),
    about the centre on the line from there through (0, 0) as far from (10, 0) as from (0, 8):
    (0, y) with 10**2 + y**2 = (8 - y)**2, y = -2.25 (radius 10.25). The next line (0, 10) -> (-10, 10)
    then starts tangentially at its offset (0, 8)."""
    blocks = [_arc([10, 0], [0, 10], [0, 0], 1, ccw=True), _line([0, 10], [-10, 10], 2),
              _line([-10, 10], [-10, 20], 3)]
    out = compensate(blocks, side="left", radius=2.0, plane=2)
    _check(out, [
        (1, "arc", [10, 0], [0, 8], [0, -2.25], True),
        (2, "line", [0, 8], [-10, 8], None, None),
        (3, "line", [-10, 8], [-10, 20], None, None),
    ])


def test_a_rapid_reversal_goes_round_by_a_traverse():
    # the reversal into the rapid (block 3) is an outside corner of a half turn (beta = pi, no arc before it):
    # LinuxCNC's convert_straight_comp2 has no arc traverse and goes round it by a STRAIGHT_TRAVERSE from the
    # tool (10, 1) to the programmed corner plus the radius on the new side (10, -1); block 4 is the exit move
    blocks = [_line([-10, 0], [0, 0], 1, feed=7.0), _line([0, 0], [10, 0], 2, kind="rapid", feed=math.inf),
              _line([10, 0], [0, 0], 3, kind="rapid", feed=math.inf), _line([0, 0], [0, -10], 4)]
    out = compensate(blocks, side="left", radius=1.0, plane=2)
    _check(out, [
        (1, "line", [-10, 0], [0, 1], None, None),
        (2, "rapid", [0, 1], [10, 1], None, None),
        (3, "rapid", [10, 1], [10, -1], None, None),
        (3, "rapid", [10, -1], [0, -1], None, None),
        (4, "line", [0, -1], [0, -10], None, None),
    ])
    assert out[2].feed == math.inf


def test_full_circle_outside_and_z_only_exit_keeps_the_offset():
    # right of a counter-clockwise full circle of radius 10 (outside): radius 12; a Z-only last block
    # (Heidenhain "L Z+50 R0") moves at the offset position
    a, b = _p([10, 0, -1]), _p([10, 0, 50])
    blocks = [_line([10, -20, -1], [10, 0, -1], 1), _arc([10, 0, -1], [10, 0, -1], [0, 0, -1], 2, ccw=True),
              Block(line=3, kind="rapid", start=a, target=b, feed=math.inf, segment=Line(a, b))]
    out = compensate(blocks, side="right", radius=2.0, plane=2)
    _check(out, [
        (1, "line", [10, -20, -1], [12, 0, -1], None, None),
        (2, "arc", [12, 0, -1], [12, 0, -1], [0, 0, -1], True),
        (3, "rapid", [12, 0, -1], [12, 0, 50], None, None),
    ])
    assert out[1].segment.sweep == pytest.approx(2 * math.pi) and out[1].segment.radius == pytest.approx(12.0)


def test_small_convex_turn_joins_lines_without_a_corner_arc():
    # a right turn of atan(0.02) = 0.02 rad < CONVEX_TOLERANCE (0.05 rad) with the tool on the left
    out = compensate(_polyline([[-10, 0], [0, 0], [10, 0], [20, -0.2], [30, -10]]), side="left", radius=2.0, plane=2)
    n = np.array([0.2, 10.0]) / math.hypot(0.2, 10.0)
    end3 = [20.0 + 2.0 * n[0], -0.2 + 2.0 * n[1]]
    _check(out, [
        (1, "line", [-10, 0], [0, 2], None, None),
        (2, "line", [0, 2], [10, 2], None, None),
        (3, "line", [10, 2], end3, None, None),
        (4, "line", end3, [30, -10], None, None),
    ])


def test_arcs_that_cannot_meet_inside_name_the_corner():
    # a lens (circles of radius 1 about (-0.5,0) and (0.5,0)) run counter-clockwise with the tool inside: the
    # offset circles of radius 1 - 0.6 = 0.4 are 1 mm apart and never meet at the lens tip
    h = math.sqrt(0.75)
    blocks = [_line([0, -3], [0, -h], 1), _arc([0, -h], [0, h], [-0.5, 0], 2, ccw=True),
              _arc([0, h], [0, -h], [0.5, 0], 3, ccw=True), _line([0, -h], [0, -3], 4)]
    with pytest.raises(CompensationError, match="Arc to arc motion makes a corner the compensated tool can't fit") as e:
        compensate(blocks, side="left", radius=0.6, plane=2)
    assert e.value.index == 2
    compensate(blocks, side="left", radius=0.4, plane=2)  # a smaller tool fits


def test_small_convex_turn_into_an_arc_is_bridged_by_a_line():
    # a clockwise arc of radius 10 leaving (10,0) 0.02 rad to the right of the incoming line, tool on the left
    # (outside the arc, radius 12): no corner arc of 0.02 rad, a straight bridge from (10,2) to the arc's start
    c = np.array([10.0 - 10.0 * math.sin(0.02), -10.0 * math.cos(0.02)])
    u0 = (np.array([10.0, 0.0]) - c) / 10.0
    u1 = np.array([math.cos(math.atan2(u0[1], u0[0]) - 0.5), math.sin(math.atan2(u0[1], u0[0]) - 0.5)])
    end = c + 10.0 * u1
    blocks = [_line([-10, 0], [0, 0], 1), _line([0, 0], [10, 0], 2),
              _arc([10, 0], end.tolist(), c.tolist(), 3, ccw=False), _line(end.tolist(), [30, -30], 4)]
    out = compensate(blocks, side="left", radius=2.0, plane=2)
    s3, e3 = (c + 12.0 * u0).tolist(), (c + 12.0 * u1).tolist()
    _check(out, [
        (1, "line", [-10, 0], [0, 2], None, None),
        (2, "line", [0, 2], [10, 2], None, None),
        (3, "line", [10, 2], s3, None, None),
        (3, "arc", s3, e3, c.tolist(), False),
        (4, "line", e3, [30, -30], None, None),
    ])
    assert out[2].length == pytest.approx(2.0 * 0.02, rel=1e-3)  # chord of the 0.02 rad turn at radius 2


def test_helix_of_three_turns_keeps_its_turns():
    # G3 P3 down 3 mm inside a circle of radius 10 with a tool of radius 2: radius 8, 3 turns, same pitch
    a, b = _p([10, 0, 0]), _p([10, 0, -3])
    helix = Block(line=2, kind="arc", start=a, target=b, feed=10.0,
                  segment=Arc(a, b, _p([0, 0, 0]), ccw=True, plane=2, turns=2))
    out = compensate([_line([10, -10], [10, 0], 1), helix, _line([10, 0, -3], [0, 0, -3], 3)],
                     side="left", radius=2.0, plane=2)
    arc = out[1].segment
    np.testing.assert_allclose([arc.start, arc.end], [[8, 0, 0], [8, 0, -3]], atol=1e-12)
    assert arc.sweep == pytest.approx(6.0 * math.pi) and arc.radius == pytest.approx(8.0) and arc.helix == -3.0


def test_negative_tool_radius_swaps_the_side_as_linuxcnc():
    """LinuxCNC convert_cutter_compensation_on: a negative radius (G41.1 D-1, or a negative tool-table
    diameter) switches G41 to G42 with the radius' magnitude (tests/interp/crazy-paths, inside-corners)."""
    from interpolators import parse_program
    from interpolators.context import MachineContext, Tool

    text = "G21 G90 F100\nG0 X0 Y0\n{} G1 X10\nG1 X20\nG40 G1 X30\n"
    swapped = parse_program(text.format("G41.1 D-2"), context=MachineContext())
    right = parse_program(text.format("G42.1 D2"), context=MachineContext())
    assert [b.target.tolist() for b in swapped.blocks] == [b.target.tolist() for b in right.blocks]
    assert swapped.blocks[1].target[1] == pytest.approx(-1.0)  # G42: the tool 1 mm right of +X
    table = MachineContext(tools={4: Tool(number=4, radius=-1.0)})
    from_table = parse_program(text.format("T4 M6 G41 D4"), context=table)
    assert [b.target.tolist() for b in from_table.blocks] == [b.target.tolist() for b in right.blocks]


def test_reversal_from_an_arc_onto_a_line_whose_offsets_cross_is_an_inside_corner():
    """LinuxCNC tests/interp/inside-corners: a G3 half circle ending downwards, then a line straight up
    (a reversal). With G42 the arc's offset (radius 1 + 0.5) and the line's (X -1.5) cross at
    (-1.5, sqrt(2)): both end there, as at any inside corner, with no corner arc."""
    from interpolators import parse_program
    from interpolators.context import MachineContext

    prog = parse_program("G21 G90 F100\nG0 X-5 Y0\nG42.1 D1 G1 X0 Y0\nG3 X-2 Y0 I-1 J0\nG1 Y3\nG40 G1 X-5 Y5\n",
                         context=MachineContext())
    ends = [(b.kind, b.line, np.round(b.target, 9).tolist()) for b in prog.blocks]
    assert ends[3:5] == [("arc", 4, [-1.5, round(math.sqrt(2.0), 9), 0.0]), ("line", 5, [-1.5, 3.0, 0.0])]


def test_inside_corner_line_into_arc_meets_the_offset_circle():
    """LinuxCNC convert_arc_comp2, concave line->arc: the line +X along Y=0 meets a G3 arc of radius 5
    about (-3, 4), whose tangent at (0, 0) is (0.8, 0.6) (a left turn of 36.87 degrees: concave with the
    tool on the left, inside the arc). The entry's parallel offset Y = 1 meets the offset circle of radius
    5 - 1 = 4 at X = -3 + sqrt(4**2 - 3**2) = -3 + sqrt(7), the intersection nearer the corner; the arc
    ends 1 mm inside its end (2, 4) at (1, 4); the exit runs to the programmed point."""
    blocks = [_line([-10, 0], [0, 0], 1), _arc([0, 0], [2, 4], [-3, 4], 2, ccw=True), _line([2, 4], [2, 10], 3)]
    out = compensate(blocks, side="left", radius=1.0, plane=2)
    x = [-3.0 + math.sqrt(7.0), 1.0]
    _check(out, [
        (1, "line", [-10, 0], x, None, None),
        (2, "arc", x, [1, 4], [-3, 4], True),
        (3, "line", [1, 4], [2, 10], None, None),
    ])


def test_near_reversal_into_an_arc_the_tool_is_outside_of_is_an_inside_corner():
    """LinuxCNC convert_arc_comp2's "m"/"h" rule (tests/interp/crazy-paths, line 106): a turn within
    TOLERANCE_CONCAVE_CORNER (0.05 rad) of a half turn into an arc the tool is outside of is concave. The
    line +X ends at (0, 0); a G2 arc of radius 5 about (-5 sin e, 5 cos e), e = 0.03, leaves it heading
    0.03 rad short of -X; tool left, outside the arc (offset radius 6). The line's offset Y = 1 meets that
    circle at X = -5 sin e - sqrt(6**2 - (5 cos e - 1)**2) (LinuxCNC's angle_from_center = theta + pi +
    asin(l)): both end there, with no corner arc round the outside."""
    e = 0.03
    c = [-5.0 * math.sin(e), 5.0 * math.cos(e)]
    end = [c[0] - 5.0, c[1]]
    blocks = [_line([-10, 0], [0, 0], 1), _arc([0, 0], end, c, 2, ccw=False), _line(end, [end[0], 10], 3)]
    out = compensate(blocks, side="left", radius=1.0, plane=2)
    x = [c[0] - math.sqrt(36.0 - (c[1] - 1.0) ** 2), 1.0]
    _check(out, [
        (1, "line", [-10, 0], x, None, None),
        (2, "arc", x, [c[0] - 6.0, c[1]], c, False),
        (3, "line", [c[0] - 6.0, c[1]], [end[0], 10], None, None),
    ])


def test_arc_arc_inside_corner_meets_on_the_programmed_centres():
    """LinuxCNC convert_arc_comp2, concave arc->arc (tests/interp/inside-corners, lines 16-17): the two
    offset circles are about the programmed centres start + I/J, of the end point's radius -/+ the tool
    radius (G41.1 D0.15: 0.075 in; the G3 with the tool inside, the G2 outside). 4-decimal words put the
    G2's end 0.00009 in off its circle; vcnc's arc moves its centre onto the chord's bisector, but the corner
    is where LinuxCNC's circles meet, nearer the corner (1.2281, 1.3456): its expected ARC_FEED end is
    (1.2235, 1.0250) in."""
    from interpolators import parse_program
    from interpolators.context import MachineContext

    prog = parse_program("G20 G17 G90 F8\nG0 X0 Y0\nG41.1 D0.15 G1 X0.6767 Y0.2334\nG1 X0.3359 Y0.4419\n"
                         "G3 X1.2281 Y1.3456 I0.2921 J0.6039\nG2 X0.1253 Y0.9881 I-0.6093 J0\nG40 G1 X0 Y0\n",
                         context=MachineContext())
    c1, c2 = np.array([0.3359 + 0.2921, 0.4419 + 0.6039]), np.array([1.2281 - 0.6093, 1.3456])
    r1 = math.hypot(*(np.array([1.2281, 1.3456]) - c1)) - 0.075
    r2 = math.hypot(*(np.array([0.1253, 0.9881]) - c2)) + 0.075
    d = math.hypot(*(c2 - c1))
    a = (d * d + r1 * r1 - r2 * r2) / (2.0 * d)
    u = (c2 - c1) / d
    cands = [c1 + a * u + k * math.sqrt(r1 * r1 - a * a) * np.array([-u[1], u[0]]) for k in (1.0, -1.0)]
    want = min(cands, key=lambda p: math.hypot(*(p - [1.2281, 1.3456])))
    ends = [b.target[:2] / 25.4 for b in prog.blocks if b.line == 5]
    # the end lies on vcnc's arc, whose centre moved 7e-6 in onto the bisector: 2e-6 in from LinuxCNC's point, where
    # intersecting the circles about the moved centres would be 1.9e-4 in off
    np.testing.assert_allclose(ends[-1], want, atol=1e-5)
    np.testing.assert_allclose(want, [1.2235, 1.0250], atol=5e-5)  # LinuxCNC's, printed to 4 decimals


def test_a_slot_narrower_than_the_tool_still_gouges_as_in_linuxcnc():
    """LinuxCNC tests/interp/bad/ccomp-gouging.ngc: a 0.1 in step back under a 0.25 in tool; rs274 stops
    with "Straight feed in concave corner cannot be reached by the tool without gouging"."""
    from interpolators import parse_program
    from interpolators.context import MachineContext
    from vcnc.errors import GCodeError

    with pytest.raises(GCodeError, match="Straight feed in concave corner cannot be reached by the tool"):
        parse_program("G20\ng0x0y0z0\ng41.1d.25\ng1x1f1\ng1x2\ng1y.1\ng1x1\ng40\ng1x2\n", context=MachineContext())


def test_program_end_without_an_exit_move_compensates_the_last_arc():
    """LinuxCNC tests/ccomp/mill-line-arc-entry: G40 with no motion after it, then M2: the last G2 is an
    ordinary compensated move (rs274's expected ARC_FEED(2.0, 3.5, 2.0, 2.0, -1): the tool 0.5 in outside
    the programmed circle of radius 1 about (2, 2) at its end (2, 3))."""
    from interpolators import parse_program
    from interpolators.context import MachineContext

    prog = parse_program("G20 F60\nG0 X1 Y5\nG41.1 D1 G1 Y4\nG3 X2 Y3 I1\nG2 X3 Y2 J-1\nG1 Y-1\nG2 X2 Y-2 I-1\n"
                         "G1 X-2\nG2 X-2.6 Y-0.2 J1\nG1 X1.4 Y2.8\nG2 X2 Y3 I.6 J-.8\nG40\nM2\n",
                         context=MachineContext())
    last = prog.blocks[-1]
    assert last.kind == "arc" and last.line == 11
    np.testing.assert_allclose(last.target[:2] / 25.4, [2.0, 3.5], atol=1e-9)
    np.testing.assert_allclose(last.segment.center[:2] / 25.4, [2.0, 2.0], atol=1e-9)


def test_arc_trimmed_past_its_start_gouges_as_in_linuxcnc():
    """LinuxCNC move_endpoint_and_flush: an arc whose trimmed sweep exceeds the programmed one by more than
    0.0254 rad (mm program) gouges. A G3 of radius 5 about (0, 5) sweeps 0.2 rad from (0, 0); the line after
    it turns up (+Y, concave with the tool on the left). Its offset X = 5 sin(0.2) - 1 = -0.0067 meets the
    arc's offset circle (radius 4) at -90.1 degrees, before the arc's offset start (0, 1) at -90: the arc
    would have to run 2 pi - 0.0017 rad."""
    end = [5.0 * math.sin(0.2), 5.0 - 5.0 * math.cos(0.2)]
    blocks = [_line([-10, 0], [0, 0], 1), _arc([0, 0], end, [0, 5], 2, ccw=True), _line(end, [end[0], 10], 3),
              _line([end[0], 10], [end[0] - 10, 10], 4)]
    with pytest.raises(CompensationError, match="Arc move in concave corner cannot be reached by the tool") as e:
        compensate(blocks, side="left", radius=1.0, plane=2)
    assert e.value.index == 1
    compensate(blocks, side="left", radius=0.1, plane=2)  # a tool that fits: X = 0.893 meets the arc within it
