"""The TNC fuzzer of session 40: the reference checks what the reader (and the TNC) checks.

The seeded generator (:mod:`tests.interpolators.tnc_generator`) drew, in seeds 1100000-1101499 (session 39), 60
programs the reader refused and the independent reference (:mod:`tests.interpolators.reference_heidenhain`) ran:
RL/RR contours whose inside corners the tool cannot reach and RND roundings between an arc and a line too short
for them. The reference now refuses them from the manuals' rules (iTNC 530 user's manual 60642x-04, "Radius
compensation: Machining corners": the tool centre runs to the intersection of the tool centre paths at an inside
corner, "The permissible tool radius, therefore, is limited by the geometry of the programmed contour"; TNC 426/430
manual, "Rounding corners RND": "The rounding arc is tangential to the preceding and following contour elements").
Each program is hand-written after the seed that showed it.
"""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_iso import ReferenceError
from vcnc.errors import GCodeError

CTX = MachineContext()


def _program(tool_radius: float, body: str) -> str:
    lines = [f"TOOL DEF 1 L+0 R+{tool_radius}", "TOOL CALL 1 Z S2000 F500", "L X-20 Y-20 Z+10 R0 FMAX",
             "L Z-2 R0 F200", *body.splitlines(), "L Z+50 R0 FMAX M30"]
    return "0 BEGIN PGM G40 MM\n" + "".join(f"{k + 1} {b}\n" for k, b in enumerate(lines)) + \
        f"{len(lines) + 1} END PGM G40 MM\n"


def _both_refuse(text: str, reader_match: str, reference_match: str) -> None:
    with pytest.raises(GCodeError, match=reader_match):
        parse_heidenhain(text, source="t.h", context=CTX)
    with pytest.raises(ReferenceError, match=reference_match):
        heidenhain_reference(text, CTX)


# -- inside corners the compensated tool cannot reach (seeds 1100058 'CHF 1' beside a tool of radius 2.5, 1100025
#    a CR after a short line) ------------------------------------------------------------------------------------

def test_a_chamfer_between_two_inside_corners_shorter_than_the_tool_needs_is_refused():
    # a square pocket wall run RL counter-clockwise inside: every corner an inside one; CHF 1 at 90 degrees is a
    # chamfer line of 1.41 mm with two inside corners of 45 degrees, which take 2 x 2.5 tan(22.5) = 2.07 mm of it
    body = "L X+0 Y+0 RL\nL X+40\nCHF 1\nL Y+40\nL X+0\nL Y+0\nL X-20 Y-20 R0"
    _both_refuse(_program(2.5, body), "cannot be reached by the tool without gouging",
                 "shorter than the inside corners at its ends take")
    prog = checked_program(_program(0.5, body), CTX, exact=False)  # radius 0.5: 0.41 mm of it
    assert len(prog.blocks) > 6


def test_an_element_shorter_than_the_next_inside_corner_takes_is_refused():
    # a line of 1 mm between two inside corners of 90 degrees: a tool of radius 2 takes 2 mm of it at each end
    body = "L X+0 Y+0 RL\nL X+40\nL Y+1\nL X+0\nL Y+0\nL X-20 Y-20 R0"
    _both_refuse(_program(2, body), "gouging", "radius compensation: ")
    checked_program(_program(0.4, body), CTX, exact=False)


def test_an_arc_curving_toward_the_tool_tighter_than_the_tool_is_refused():
    # RL round the outside of nothing: the half circle of radius 2 turns left, toward the tool on the left of the
    # path; a tool of radius 3 cannot follow it inside
    body = "L X+0 Y+0 RL\nL X+20\nCC X+20 Y+2\nC X+20 Y+4 DR+\nL X+0\nL X-20 Y-20 R0"
    with pytest.raises(ReferenceError, match="curving toward the tool"):
        heidenhain_reference(_program(3, body), CTX)
    with pytest.raises(GCodeError):
        parse_heidenhain(_program(3, body), source="t.h", context=CTX)
    checked_program(_program(1, body), CTX, exact=False)


# -- RND between an arc and a line too short for it (seed 1100085: 'C .. DR+', 'RND R3', a line) -------------------

def test_a_rounding_whose_touch_point_falls_beyond_the_line_is_refused():
    # an arc of radius 10 about (10, 10) from (0, 10) to (10, 20), then a line of 1 mm straight down: RND R3 would
    # touch the line 3 mm below the corner
    body = "L X+0 Y+0 R0\nL Y+10\nCC X+10 Y+10\nC X+10 Y+20 DR-\nRND R3\nL Y+19\nL X+30"
    _both_refuse(_program(1, body), "does not fit between the elements", "RND radius does not fit")
    checked_program(_program(1, body.replace("L Y+19", "L Y+12")), CTX, exact=False)  # 8 mm of line: it fits


# -- cycle 22's Q8 on a ring with an element of no length in the plane (seed 1102051: the 40 x 35 pocket of a
#    CYCL DEF 14 label, tool radius 1, Q8 = 1). The innermost ring of the rectangle has a side of length 0; the
#    rounding asked that side for its direction and the program stopped with an error naming no block --------------

def test_rough_out_rounds_a_ring_with_a_side_of_no_length():
    body = ("CYCL DEF 14.0 CONTOUR\nCYCL DEF 14.1 CONTOUR LABEL 3\n"
            "CYCL DEF 20 CONTOUR DATA Q1=-5 Q2=+1 Q3=+0 Q4=+0.5 Q5=+1 Q6=+2 Q7=+50 Q8=+1 Q9=+1\n"
            "CYCL DEF 22 ROUGH-OUT Q10=+2 Q11=+100 Q12=+350 Q18=+0 Q19=+0\nCYCL CALL\nL Z+50 R0 FMAX M30\n"
            "LBL 3\nL X+0 Y+35 RL\nL X+40 Y+35\nL X+40 Y+0\nL X+0 Y+0\nL X+0 Y+35\nLBL 0")
    text = "0 BEGIN PGM Q8 MM\n" + "".join(f"{k + 1} {b}\n" for k, b in enumerate(
        ["TOOL DEF 1 L+0 R+1", "TOOL CALL 1 Z S1000", "L Z+50 R0 FMAX", *body.splitlines()])) + "99 END PGM Q8 MM\n"
    prog = parse_heidenhain(text, source="t.h", context=CTX)  # PathGeometryError: '.. has no direction ..'
    cut = [b for b in prog.blocks if b.line > 8 and b.target[2] < 1]
    assert cut and all(1 - 1e-9 <= b.target[0] <= 39 + 1e-9 and 1 - 1e-9 <= b.target[1] <= 34 + 1e-9 for b in cut)


# -- the last element before R0, shorter than the inside corner at its start takes (seed 1100217: 'L IX+6.4653
#    IY-7.0337' after a line, a turn of 153 degrees under RR, tool radius 3, then 'L Z+20 R0'). The reader ran it
#    as LinuxCNC does (only a line whose end moved is checked: the tool ran backwards from the corner's intersection
#    to the element's end, into the line before); the TNC's tool radius is limited by the contour (iTNC 530 manual,
#    "Radius compensation: Machining corners") ------------------------------------------------------------------

def test_the_last_element_shorter_than_its_inside_corner_takes_is_refused():
    # RL along +X, then back left by 153.4 degrees on a line of 8.94 mm: a tool of radius 3 needs 3 tan(76.7) =
    # 12.7 mm of it, a tool of radius 1 4.2 mm
    body = "L X+0 Y+0 RL\nL X+20 Y+0\nL X+12 Y+4\nL Z+20 R0 FMAX"
    _both_refuse(_program(3, body), "Straight feed in concave corner cannot be reached",
                 "the next element is shorter than the inside corner takes")
    checked_program(_program(1, body), CTX, exact=False)


# -- cycle 22 in a triangle whose innermost ring is smaller than its start leg (seed 1102049: a triangle of
#    inradius 12.3 mm, tool radius 2, rings 2 mm apart). The reference asked the legs from the middle of the first
#    edge to be as far from the walls as the ring, stopped at the ring 10 and left the middle uncut; the reader
#    runs the ring 12. The reference now asks the legs to keep the wall allowance R + Q3 only ---------------------

def test_rough_out_of_a_triangle_clears_its_middle():
    lines = ["TOOL DEF 1 L+0 R+2", "TOOL CALL 1 Z S3000 F400", "L Z+50 R0 FMAX", "CONTOUR DEF P1 = LBL 1",
             "CYCL DEF 20 CONTOUR DATA Q1=-4 Q2=+1 Q3=+0 Q4=+0 Q5=+1 Q6=+2 Q7=+50 Q8=+0 Q9=-1",
             "CYCL DEF 22 ROUGH-OUT Q10=+5 Q11=+100 Q12=+350 Q18=+0 Q19=+0", "CYCL CALL", "L Z+50 R0 FMAX M30",
             "LBL 1", "L X+15 Y+40 RL", "L X+40 Y+0", "L X+0 Y+0", "L X+15 Y+40", "LBL 0"]
    text = "0 BEGIN PGM TRI MM\n" + "".join(f"{k + 1} {b}\n" for k, b in enumerate(lines)) + "15 END PGM TRI MM\n"
    prog = checked_program(text, CTX)  # mismatch: the reference's last ring was the one at 10 mm
    sides = [((15, 40), (40, 0)), ((40, 0), (0, 0)), ((0, 0), (15, 40))]

    def wall(x: float, y: float) -> float:
        return min(abs((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / ((bx - ax) ** 2 + (by - ay) ** 2) ** 0.5
                   for (ax, ay), (bx, by) in sides)

    cut = [b for b in prog.blocks if b.target[2] < 0]
    assert max(wall(*b.target[:2]) for b in cut) > 12 - 1e-6  # the inradius is 12.3: the tool reaches the middle


# -- an element trimmed at its start by an inside corner and at its end by an RND (seed 1102204: 'L IX-10.743
#    IY+16.5485', 'L X+9.3682 Y+41.1753', 'RND R3' under RL, tool radius 2.5). The reference checked the corner
#    against the whole line, before the RND took its end --------------------------------------------------------

def test_an_element_the_corner_and_the_rounding_after_it_consume_is_refused():
    # the line of 8.94 mm back up-left: the inside corner at its start takes 1 x tan(76.7) = 4.24 mm of it with a
    # tool of radius 1, the outside RND R8 at its end 8 tan(31.7) = 4.94 mm, RND R3 1.85 mm
    body = "L X+0 Y+0 RL\nL X+20 Y+0\nL X+12 Y+4\nRND R8\nL X+12 Y+20\nL X+0 Y+30 R0"
    _both_refuse(_program(1, body), "Straight feed in concave corner cannot be reached",
                 "shorter than the inside corner and the RND/CHF at its ends take")
    checked_program(_program(1, body.replace("RND R8", "RND R3")), CTX, exact=False)
