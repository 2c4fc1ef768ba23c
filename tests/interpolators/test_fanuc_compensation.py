"""Fanuc/Haas cutter compensation C at corners (``--dialect fanuc`` / ``haas``; :mod:`interpolators.compensation`
with ``corner="fanuc"``).

Every end point is worked out by hand from the Fanuc 0i-MF/0i-MD operator's manual, cutter compensation C,
"Tool movement in offset mode": at an outside corner turned by at most 90 degrees the tool goes to the
intersection of the offset paths; at a sharper one it goes on ``r`` along the first element's tangent,
straight to ``r`` before the second element along its tangent, and on; inside corners end at the
intersection. The start-up is type A (perpendicular to the next block at its start), the cancel type A
(perpendicular to the last block at its end). Tool radius 2 mm, G54 at the origin. Each program is also
checked against the independent reference (:func:`tests.interpolators.reference_iso.fanuc_corner`).
"""

from __future__ import annotations

import dataclasses
import math

import pytest

import interpolators.iso_compensation as iso_compensation
from interpolators import parse_program
from interpolators.compensation import compensate
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.core.errors import InputError
from vcnc.errors import GCodeError

BASE = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, home=(0.0, 0.0, 100.0),
                      tools={1: Tool(number=1, radius=2.0, length=0.0)})
CONTROLS = [dataclasses.replace(BASE, dialect=DIALECTS[name]) for name in ("fanuc", "haas")]
S5 = math.sqrt(5.0)


def rows(text: str, context: MachineContext) -> list[tuple]:
    """(line, kind, x, y) of each ``--blocks`` row after the first rapid, checked against the reference."""
    header, table = blocks_table(parse_program(text, context=context))
    match = match_blocks(iso_reference(text, context), [r + [0.0] * 6 for r in table])
    assert match.mismatch is None, match.mismatch
    assert match.exact + match.within == len(table)
    return [(r[1], r[2], r[3], r[4]) for r in table[1:]]


def check(got: list[tuple], want: list[tuple]) -> None:
    assert [g[:2] for g in got] == [w[:2] for w in want]
    for g, w in zip(got, want):
        assert g[2:] == pytest.approx(w[2:], abs=1e-9), g


# clockwise square (0,0) (0,20) (20,20) (20,0): G41 has the tool outside, G42 inside
SQUARE = "G21 G90 G17 G54\nG0 X-10. Y0 Z0\n{side} D1 G1 X0 Y0 F100.\nY20.\nX20.\nY0\nX0\nG40 X-10. Y-10.\nM30\n"


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_square_outside_corners_go_to_the_intersection(context):
    # alpha = 90: the offset lines x = -2, y = 22, x = 22, y = -2 meet at (-2, 22), (22, 22), (22, -2);
    # no corner arc (LinuxCNC's), one row per block
    check(rows(SQUARE.format(side="G41"), context),
          [(3, "feed", -2, 0), (4, "feed", -2, 22), (5, "feed", 22, 22), (6, "feed", 22, -2), (7, "feed", 0, -2),
           (8, "feed", -10, -10)])


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_square_inside_corners_go_to_the_intersection(context):
    check(rows(SQUARE.format(side="G42"), context),
          [(3, "feed", 2, 0), (4, "feed", 2, 18), (5, "feed", 18, 18), (6, "feed", 18, 2), (7, "feed", 0, 2),
           (8, "feed", -10, -10)])


def test_linuxcnc_keeps_its_corner_arcs():
    out = rows(SQUARE.format(side="G41"), dataclasses.replace(BASE, dialect=DIALECTS["linuxcnc"]))
    assert [k for _, k, _, _ in out].count("arc_cw") == 3
    # the arc about (0, 20) ends above the corner
    assert out[2][:2] == (5, "arc_cw") and out[2][2:] == pytest.approx((0, 22), abs=1e-9)


# triangle (0,0) (20,40) (40,0), clockwise: corner angles 53.13 degrees at (20,40), 63.43 at (40,0)
TRIANGLE = "G21 G90 G17 G54\nG0 X-10. Y0 Z0\n{side} D1 G1 X0 Y0 F100.\nX20. Y40.\nX40. Y0\nX0\nG40 X-10. Y-10.\nM30\n"


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_triangle_acute_outside_corners_add_straight_pieces(context):
    # u1 = (1, 2)/sqrt5, n1 = (-2, 1)/sqrt5 (left); u2 = (1, -2)/sqrt5, n2 = (2, 1)/sqrt5; u3 = (-1, 0), n3 = (0, -1)
    # at (20, 40): P + 2 n1 + 2 u1 = (20 - 2/sqrt5, 40 + 6/sqrt5), then P + 2 n2 - 2 u2 = (20 + 2/sqrt5, 40 + 6/sqrt5)
    # at (40, 0): P + 2 n2 + 2 u2 = (40 + 6/sqrt5, -2/sqrt5), then P + 2 n3 - 2 u3 = (42, -2)
    check(rows(TRIANGLE.format(side="G41"), context),
          [(3, "feed", -4 / S5, 2 / S5), (4, "feed", 20 - 2 / S5, 40 + 6 / S5), (5, "feed", 20 + 2 / S5, 40 + 6 / S5),
           (5, "feed", 40 + 6 / S5, -2 / S5), (6, "feed", 42, -2), (6, "feed", 0, -2), (7, "feed", -10, -10)])


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_triangle_inside_corners_meet(context):
    # inside, the vertex moves r / sin(half angle) along the bisector: at (20, 40) sin(26.57) = 1/sqrt5, 2 sqrt5
    # down; at (40, 0) the offsets y = 2 and 2x + y = 80 - 2 sqrt5 meet at x = 39 - sqrt5
    check(rows(TRIANGLE.format(side="G42"), context),
          [(3, "feed", 4 / S5, -2 / S5), (4, "feed", 20, 40 - 2 * S5), (5, "feed", 39 - S5, 2), (6, "feed", 0, 2),
           (7, "feed", -10, -10)])


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_line_arc_and_arc_line_at_right_angles_meet_on_the_offset_circle(context):
    # the line +X turns left into a clockwise half circle about (30, 0) (R10) and out of it into +X: outside
    # corners of 90 degrees for G42. Offsets y = -2 and the circle of radius 8 about (30, 0) meet at
    # x = 30 -/+ sqrt(64 - 4): the line grows, the arc sweeps more than its 180 degrees (no gouge)
    text = ("G21 G90 G17 G54\nG0 X-10. Y-10. Z0\nG42 D1 G1 X0 Y0 F100.\nX20.\nG2 X40. Y0 I10. J0\nG1 X60.\n"
            "G40 X70. Y-10.\nM30\n")
    check(rows(text, context), [(3, "feed", 0, -2), (4, "feed", 30 - math.sqrt(60), -2),
                                (5, "arc_cw", 30 + math.sqrt(60), -2), (6, "feed", 60, -2), (7, "feed", 70, -10)])


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_acute_line_arc_and_arc_line_corners(context):
    # +X line into a counter-clockwise arc about (25, -5) (R 5 sqrt2, 270 degrees) that starts heading
    # t2 = (-1, -1)/sqrt2 and ends heading (-1, 1)/sqrt2 into a +X line: 135 degree right turns, outside for G41.
    # Line -> arc: the line on to (20, 2) + 2 (1, 0) = (22, 2); to P + 2 n2 - 2 t2 = (20, 0) + (s, -s) + (s, s)
    # (s = sqrt2) = (20 + 2s, 0); to the arc's offset start (20 + s, -s) on radius 5s - 2. Arc -> line: the
    # arc ends at (30 - s, -s), on 2 t1 to (30 - 2s, 0), to (30, 2) - 2 (1, 0) = (28, 2), on along y = 2
    s = math.sqrt(2.0)
    text = ("G21 G90 G17 G54\nG0 X-10. Y-10. Z0\nG41 D1 G1 X0 Y0 F100.\nX20.\nG3 X30. Y0 I5. J-5.\nG1 X50.\n"
            "G40 X60. Y-10.\nM30\n")
    check(rows(text, context), [(3, "feed", 0, 2), (4, "feed", 22, 2), (5, "feed", 20 + 2 * s, 0),
                                (5, "feed", 20 + s, -s), (5, "arc_ccw", 30 - s, -s), (6, "feed", 30 - 2 * s, 0),
                                (6, "feed", 28, 2), (6, "feed", 50, 2), (7, "feed", 60, -10)])


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_a_small_outside_turn_meets_too(context):
    # 0.4 mm down over 20 mm: a right turn of theta = atan(0.02), below LinuxCNC's 0.05 rad corner arc limit;
    # Fanuc still goes to the intersection, r tan(theta / 2) past the corner on y = 2
    text = "G21 G90 G17 G54\nG0 X-10. Y0 Z0\nG41 D1 G1 X0 Y0 F100.\nX20.\nX40. Y-0.4\nG40 X50. Y-10.\nM30\n"
    out = rows(text, context)
    assert out[1][2:] == pytest.approx((20 + 2 * math.tan(math.atan(0.02) / 2), 2), abs=1e-9)
    assert [r[0] for r in out] == [3, 4, 5, 6]


def test_compensate_names_the_corner_rules():
    with pytest.raises(InputError, match=r"corner rule must be one of \('linuxcnc', 'fanuc'\), got 'yasnac'"):
        compensate([], side="left", radius=1.0, plane=2, corner="yasnac")


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_offsets_that_do_not_meet_take_the_acute_rule(context):
    # our reading: a right-angle turn into a clockwise arc of R3 about (23, 0) with the tool (G42) inside it:
    # the offset line y = -2 misses the offset circle (radius 1), so the vectors are joined as at an acute
    # corner: the line on to (22, -2) (= P + 2 n2 - 2 t2 too: no piece), up to the arc's offset start (22, 0);
    # out of the arc at (24, 0) the same way down to (24, -2)
    text = ("G21 G90 G17 G54\nG0 X-10. Y-10. Z0\nG42 D1 G1 X0 Y0 F100.\nX20.\nG2 X26. Y0 I3. J0\nG1 X40.\n"
            "G40 X50. Y-10.\nM30\n")
    check(rows(text, context), [(3, "feed", 0, -2), (4, "feed", 22, -2), (5, "feed", 22, 0), (5, "arc_cw", 24, 0),
                                (6, "feed", 24, -2), (6, "feed", 40, -2), (7, "feed", 50, -10)])


def test_rapid_pieces_at_an_acute_corner_stay_rapids():
    # the triangle's second side as a G0: the straight pieces before it are traverses, as the G0 itself
    text = TRIANGLE.format(side="G41").replace("X40. Y0\n", "G0 X40. Y0\nG1 ")
    out = rows(text, CONTROLS[0])
    assert [(r[0], r[1]) for r in out[1:5]] == [(4, "feed"), (5, "rapid"), (5, "rapid"), (6, "feed")]
    assert out[3][2:] == pytest.approx((40 + 6 / S5, -2 / S5), abs=1e-9)


def test_the_reference_tells_linuxcnc_corners_from_fanuc_ones(monkeypatch):
    # the reference predicts Fanuc's corner points, not only one radius from the element: the same program
    # with LinuxCNC's corner arcs under --dialect fanuc is caught at the first outside corner (line 4)
    original = iso_compensation.compensate
    monkeypatch.setattr(iso_compensation, "compensate", lambda *a, **k: original(*a, **{**k, "corner": "linuxcnc"}))
    text = SQUARE.format(side="G41")
    context = CONTROLS[0]
    _, table = blocks_table(parse_program(text, context=context))
    match = match_blocks(iso_reference(text, context), [r + [0.0] * 6 for r in table])
    assert match.mismatch.startswith("end point differs: expected #2 line 4")
    assert "Fanuc corner [-2.0, 22.0, 0.0]" in match.mismatch


@pytest.mark.parametrize("context", CONTROLS, ids=["fanuc", "haas"])
def test_g39_asks_for_the_corner_arc_at_one_corner(context):
    # G39 between Y20 and X20: line 4 ends at its perpendicular vector (-2, 20), an arc of radius 2 about the
    # corner (0, 20) to the next block's vector (0, 22) (carried by that block, as corner arcs are); the other
    # corners stay intersections
    text = SQUARE.format(side="G41").replace("Y20.\n", "Y20.\nG39\n")
    out = rows(text, context)
    check(out, [(3, "feed", -2, 0), (4, "feed", -2, 20), (6, "arc_cw", 0, 22), (6, "feed", 22, 22),
                (7, "feed", 22, -2), (8, "feed", 0, -2), (9, "feed", -10, -10)])
    _, table = blocks_table(parse_program(text, context=context))
    assert table[3][6:8] == pytest.approx([0, 20], abs=1e-9)


@pytest.mark.parametrize("block, message", [
    ("G39\nG41 D1 G1 X0 Y0 F100.\n", r"3:1: G39 corner circular interpolation outside offset mode"),
    ("G41 D1 G1 X0 Y0 F100.\nG39 I5.\n", r"4:5: word I on G39: a corner vector given by X Y or I J K is not "
                                          r"supported.*G39 alone"),
])
def test_g39_errors(block, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90 G17 G54\nG0 X-10. Y0 Z0\n{block}Y20.\nX20.\nG40 X30. Y30.\nM30\n",
                      context=CONTROLS[0])


def test_g39_is_not_linuxcnc():
    with pytest.raises(GCodeError, match=r"G39 corner circular interpolation \(Fanuc/Haas; --dialect fanuc or haas\)"):
        parse_program("G21 G90 G17\nG0 X-10. Y0 Z0\nG41 D1 G1 X0 Y0 F100.\nY20.\nG39\nX20.\nM30\n",
                      context=dataclasses.replace(BASE, dialect=DIALECTS["linuxcnc"]))
