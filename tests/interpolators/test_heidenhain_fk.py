"""Heidenhain FK free contour programming (``FPOL``, ``FL``, ``FLT``, ``FC``, ``FCT``, ``FSELECT``): hand-written
programs with the end points worked out by hand (the working in each test, from the data as the iTNC 530 user's
manual, section 6.6 "Path Contours - FK Free Contour Programming", defines them), each also checked against the
independent reference (``reference_heidenhain``, which solves the FK data numerically)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators import reference_heidenhain_fk
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n1 L X+0 Y+0 Z-5 R0 F500\n"
CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})
S3 = math.sqrt(3.0)


def run(body: str, *, reference: bool = True):
    text = HEAD + body + "\n99 END PGM T MM\n"
    return checked_program(text, CTX, check=reference)


def ends(prog) -> list[list[float]]:
    """The XY end points of the blocks after the first (the move to the start at X+0 Y+0)."""
    return [np.round(b.target[:2], 6).tolist() for b in prog.blocks[1:]]


def centre(block) -> list[float]:
    return np.round(block.segment.center[:2], 6).tolist()


def test_end_points_and_tangency():
    # FL to (20, 0); FLT keeps +X up to X 30; FCT to (40, 10) leaves (30, 0) along +X, so its centre is on
    # X 30 and as far from both ends: (30, 10), radius 10, counter-clockwise; FLT LEN 10 then goes on along +Y
    prog = run("2 FL X+20 Y+0\n3 FLT X+30\n4 FCT X+40 Y+10\n5 FLT LEN 10")
    assert ends(prog) == [[20, 0], [30, 0], [40, 10], [40, 20]]
    arc = prog.blocks[3]
    assert arc.kind == "arc" and centre(arc) == [30, 10] and arc.segment.ccw


def test_length_and_angle():
    # LEN 10 at AN+30: (10 cos 30, 10 sin 30); IAN+60 turns from 30 to 90 degrees: 5 up
    prog = run("2 FL LEN 10 AN+30\n3 FL LEN 5 IAN+60")
    assert ends(prog) == [[round(5 * S3, 6), 5], [round(5 * S3, 6), 10]]


def test_centre_and_radius():
    # centre (10, 0), R10 through the start (0, 0); DR- (clockwise) from 180 to 90 degrees ends at (10, 10); then
    # about CCPR 10 / CCPA 0 from FPOL (10, 10), i.e. (20, 10), radius 10 from (10, 10), DR+ through CCA 90:
    # from 180 to 270 degrees, ending at (20, 0)
    prog = run("2 FC CCX+10 CCY+0 R10 DR- X+10 Y+10\n3 FPOL X+10 Y+10\n4 FC CCPR+10 CCPA+0 DR+ CCA+90")
    assert ends(prog) == [[10, 10], [20, 0]]
    assert centre(prog.blocks[1]) == [10, 0] and not prog.blocks[1].segment.ccw
    assert centre(prog.blocks[2]) == [20, 10] and prog.blocks[2].segment.ccw


def test_polar_end_points_about_fpol():
    # FPOL (10, 10): PR 10 at PA 90 is (10, 20); from there IPR+5 IPA-90 is radius 15 at 0 degrees: (25, 10)
    prog = run("2 FPOL X+10 Y+10\n3 FL PR+10 PA+90\n4 FL IPR+5 IPA-90")
    assert ends(prog) == [[10, 20], [25, 10]]


def test_relative_data():
    # 5 ends at (10, 5), 6 at (20, 5); 7 is IX+5 IY+10 from block 5's end: (15, 15); 8 turns IAN+90 from block 6's
    # direction (+X): +Y, LEN 10: (15, 25); 9 is IPR+10 from block 5's polar radius about FPOL (0, 0),
    # |(10, 5)| = sqrt(125), at PA 0: (sqrt(125) + 10, 0)
    prog = run("2 FPOL X+0 Y+0\n5 FL X+10 Y+5\n6 FL X+20 Y+5\n7 FL IX+5 IY+10 RX 5 RY 5\n8 FL LEN 10 IAN+90 RAN 6\n"
               "9 FL IPR+10 PA+0 RPR 5")
    assert ends(prog) == [[10, 5], [20, 5], [15, 15], [15, 25], [round(math.sqrt(125) + 10, 6), 0]]


def test_fselect_picks_among_the_solutions():
    # a line of LEN 5 parallel to block 2 (+X) runs either way: +X (first, 0 degrees) or -X (second)
    first = run("2 FL X+10 Y+0\n3 FL IAN+90 LEN 5\n4 FL LEN 5 PAR 2\n5 FSELECT 1")
    back = run("2 FL X+10 Y+0\n3 FL IAN+90 LEN 5\n4 FL LEN 5 PAR 2\n5 FSELECT 2")
    assert ends(first)[-1] == [15, 5] and ends(back)[-1] == [5, 5]
    # from (0, 0) to (10, 0) with R10 DR+: centres (5, +-5 sqrt 3); about (5, 5 sqrt 3) the arc turns 60 degrees
    # (the shorter, first solution), about (5, -5 sqrt 3) 300 degrees (the second)
    short = run("2 FC X+10 Y+0 R10 DR+\n3 FSELECT 1")
    long = run("2 FC X+10 Y+0 R10 DR+\n3 FSELECT 2")
    assert centre(short.blocks[1]) == [5, round(5 * S3, 6)] and centre(long.blocks[1]) == [5, -round(5 * S3, 6)]
    assert short.blocks[1].segment.length == pytest.approx(10 * math.pi / 3)


def test_closed_contour():
    # CLSD+ marks (0, 0), the start of the first element; CLSD- ends the last one there
    prog = run("2 FL X+20 Y+0 CLSD+\n3 FL AN+90 LEN 10\n4 FL AN+180 LEN 20\n5 FL CLSD-")
    assert ends(prog) == [[20, 0], [20, 10], [0, 10], [0, 0]]


def test_relative_data_naming_an_element_of_the_open_stretch():
    # block 2 (along +X) stays open through 3 (10 up) and 4, whose X is 20 on from block 2's open end (RX 2), until
    # the line down to (50, 0) fixes them all: block 2 ends at X 50 - 20 = 30
    prog = run("2 FL AN+0\n3 FL LEN 10 AN+90\n4 FL IX+20 RX 2 Y+10\n5 FL X+50 Y+0 AN-90")
    assert ends(prog) == [[30, 0], [30, 10], [50, 10], [50, 0]]


def test_closed_contour_starting_with_an_open_element():
    # the first element (bare CLSD: the start of the closed contour, (0, 0)) has no length until the next line
    # through (20, 10) along +Y meets it at (20, 0); the second bare CLSD ends the contour back at (0, 0)
    prog = run("2 FL AN+0 CLSD\n3 FL X+20 Y+10 AN+90\n4 FL X+0 Y+10\n5 FL CLSD")
    assert ends(prog) == [[20, 0], [20, 10], [0, 10], [0, 0]]


def test_open_line_resolved_by_the_next_element():
    # FL AN+0 has no length; the next line through (30, 10) at 45 degrees meets Y 0 at X 20
    prog = run("2 FL AN+0\n3 FL X+30 Y+10 AN+45")
    assert ends(prog) == [[20, 0], [30, 10]]
    # the next FCT R5 DR+ turns CCA 90 from the line: its centre 5 above the line's end (t, 0), its end (t + 5, 5);
    # X+30 puts t at 25
    prog = run("2 FL AN+0\n3 FCT X+30 DR+ R5 CCA+90")
    assert ends(prog) == [[25, 0], [30, 5]] and centre(prog.blocks[2]) == [25, 5]


def test_open_line_rounded_by_an_fct_and_ended_by_the_next_line():
    # FL AN+0 (no length), FCT R5 DR+ (radius and sense only), FLT to (30, 20) at AN+90: the arc turns +X into +Y,
    # a quarter circle; the last line is X 30, so the arc ends at (30, 5), its centre (25, 5), the first line at
    # (25, 0)
    prog = run("2 FL AN+0\n3 FCT DR+ R5\n4 FLT X+30 Y+20 AN+90")
    assert ends(prog) == [[25, 0], [30, 5], [30, 20]] and centre(prog.blocks[2]) == [25, 5]
    # clockwise from AN+0 to AN-45 with R10: the centre (t, -10) 10 below the line's end (t, 0), the arc's end the
    # centre + 10 (sin 45, cos 45); the line from there at -45 degrees reaches (40, -20) after u along each axis:
    # t + 5 sqrt 2 + u = 40 and -10 + 5 sqrt 2 - u = -20, so u = 10 + 5 sqrt 2 and t = 30 - 10 sqrt 2
    prog = run("2 FL AN+0\n3 FCT DR- R10\n4 FLT X+40 Y-20 AN-45")
    t = 30 - 10 * math.sqrt(2)
    assert ends(prog) == [[round(t, 6), 0], [round(t + 5 * math.sqrt(2), 6), round(-10 + 5 * math.sqrt(2), 6)],
                          [40, -20]]


def test_tangents_between_known_circles_close_the_contour():
    # the FK form of a contour around two circles (as the manuals' FK examples run one): circles of R10 about
    # (0, 0) and (40, 0), both clockwise, from (-10, 0) (CLSD+); each FLT without data is the tangent leaving one
    # circle and reaching the next in their senses: over the top (0, 10) to (40, 10), round B to its bottom
    # (40, -10), back to (0, -10), and round A to the start (CLSD-)
    prog = run("2 L X-10 Y+0\n3 FC DR- R10 CLSD+ CCX+0 CCY+0\n4 FLT\n5 FCT DR- R10 CCX+40 CCY+0\n6 FLT\n"
               "7 FCT DR- R10 CLSD- CCX+0 CCY+0")
    assert ends(prog)[1:] == [[0, 10], [40, 10], [40, -10], [0, -10], [-10, 0]]
    assert [centre(b) for b in prog.blocks[2::2]] == [[0, 0], [40, 0], [0, 0]]
    # clockwise R10 about (0, 0), then counter-clockwise R5 about (40, 0): the crossing tangent; its normal n
    # from each centre makes (c2 - c1) . n = k1 r1 - k2 r2 = -10 - 5 (k = -1 clockwise), so n = (-15/40,
    # -sqrt(1 - (15/40)^2)) (the other root has the line running backwards); T1 = c1 - 10 n, T2 = c2 + 5 n
    prog = run("2 L X+0 Y+10\n3 FC DR- R10 CCX+0 CCY+0\n4 FLT\n5 FCT DR+ R5 CCX+40 CCY+0 X+45 Y+0")
    n = np.array([-15 / 40, -math.sqrt(1 - (15 / 40) ** 2)])
    assert ends(prog)[1:] == [np.round(-10 * n, 6).tolist(), np.round([40, 0] + 5 * n, 6).tolist(), [45, 0]]


def test_tangents_between_circles_with_approach_and_rl():
    # the closed contour of the test above run with APPR CT and RL by a tool of radius 2: left of the clockwise
    # circles is outside, so the tool runs them on radius 12: from (-12, 0) over (0, 12) to (40, 12), round to
    # (40, -12), back to (0, -12) and round to (-12, 0); the R0 line leaves to (-30, 0)
    text = ("0 BEGIN PGM T MM\n1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n3 L X-30 Y+0 Z-5 R0 F500\n"
            "4 APPR CT X-10 Y+0 CCA90 R+5 RL F250\n5 FC DR- R10 CLSD+ CCX+0 CCY+0\n6 FLT\n7 FCT DR- R10 CCX+40 CCY+0\n"
            "8 FLT\n9 FCT DR- R10 CLSD- CCX+0 CCY+0\n10 L X-30 Y+0 R0 F1000\n11 END PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    assert [np.round(b.target[:2], 6).tolist() for b in prog.blocks[3:]] == [
        [0, 12], [40, 12], [40, -12], [0, -12], [-12, 0], [-30, 0]]
    assert [round(b.segment.radius, 9) for b in prog.blocks[3:8:2]] == [12, 12, 12]
    match = match_blocks(heidenhain_reference(text, CTX), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch


def test_open_arc_resolved_by_the_next_element():
    # the circle about (10, 0) through (0, 0), clockwise; the tangents from (10, 20) touch it 60 degrees either side
    # of +Y (cos = 10 / 20): at 30 and 150 degrees; clockwise from 180 degrees the arc reaches 150 first, where it
    # runs toward (10, 20): (10 - 5 sqrt 3, 5)
    prog = run("2 FC CCX+10 CCY+0 DR-\n3 FLT X+10 Y+20")
    assert ends(prog) == [[round(10 - 5 * S3, 6), 5], [10, 20]]
    # a tangent along +X touches the clockwise circle at its top (10, 10); LEN 5 on from there
    prog = run("2 FC CCX+10 CCY+0 DR-\n3 FLT AN+0 LEN 5")
    assert ends(prog) == [[10, 10], [15, 10]]


def test_radius_compensation_and_feed():
    # the contour of test_end_points_and_tangency under RL with a tool of radius 2: the tool runs 2 to the left,
    # (20, 2), (30, 2), inside the counter-clockwise arc about (30, 10) on radius 8 to (38, 10), up to (38, 20);
    # the R0 block leaves to its end point (60, 20). The feed is the FK block's
    text = HEAD + ("TOOL DEF 1 L+0 R+2\nTOOL CALL 1 Z S1000\n2 FL X+20 Y+0 RL F300\n3 FLT X+30\n4 FCT X+40 Y+10\n"
                   "5 FLT LEN 10\n6 FL X+60 Y+20 R0\n99 END PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    assert ends(prog) == [[20, 2], [30, 2], [38, 10], [38, 20], [60, 20]]
    assert prog.blocks[1].feed * 60 == pytest.approx(300) and prog.blocks[3].segment.radius == pytest.approx(8)
    match = match_blocks(heidenhain_reference(text, CTX), blocks_table(prog)[1])  # compensated ends: to R
    assert match.mismatch is None, match.mismatch


def test_open_line_ended_by_a_coordinate_and_the_next_line():
    # FL X+10 leaves the line's direction and length open (its end somewhere on X 10); the next line through (20, 10)
    # at 45 degrees meets X 10 at (10, 0), so both are fixed together
    prog = run("2 FL X+10\n3 FL X+20 Y+10 AN+45")
    assert ends(prog) == [[10, 0], [20, 10]]


@pytest.mark.parametrize(("choice", "angle"), [(1, 60), (2, 120), (3, 240), (4, 300)])
def test_auxiliary_point_at_a_distance_from_a_line(choice, angle):
    # a line of LEN 10 from (0, 0) whose extension passes 5 from the point (0, 10): |u x (0, 10)| = 10 |cos a| = 5,
    # a = 60, 120, 240 or 300 degrees; of equal lengths they are numbered by direction
    prog = run(f"2 FL LEN 10 PDX+0 PDY+10 D5\n3 FSELECT {choice}")
    assert ends(prog) == [np.round(10 * np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))]),
                                   6).tolist()]


@pytest.mark.parametrize("choice", [1, 2])
def test_auxiliary_point_at_a_distance_from_an_arc(choice):
    # a counter-clockwise R10 arc through CCA 90 from (0, 0) whose circle passes 5 from (0, 20): its centre
    # C = 10 (-sin a, cos a) for the entry direction a, |P - C|^2 = 500 - 400 cos a is 15^2 (5^2 has no angle), so
    # cos a = 0.6875; the two arcs are of equal length, numbered by entry direction (+a first); the end is C plus
    # (S - C) turned 90 degrees
    a = math.acos(0.6875) * (1 if choice == 1 else -1)
    c = 10 * np.array([-math.sin(a), math.cos(a)])
    end = c + np.array([c[1], -c[0]])  # -C turned +90 degrees: (x, y) -> (-y, x) of (-cx, -cy)
    prog = run(f"2 FC DR+ R10 CCA+90 PDX+0 PDY+20 D5\n3 FSELECT {choice}")
    assert ends(prog) == [np.round(end, 6).tolist()] and centre(prog.blocks[1]) == np.round(c, 6).tolist()


def test_arc_fixed_by_the_auxiliary_point_of_the_next_line():
    # the manual's form (FC DR- R10 P1X.. P1Y.. then FLT AN.. PDX.. PDY.. D..): the clockwise R10 arc from (0, 0)
    # through P1 (10, -10) has its centre at (10, 0) or (0, -10) (10 from both points); the FLT leaves it along +X
    # (AN+0), at its top C + (0, 10), 5 from (30, 15) only for C = (10, 0): the arc ends at (10, 10), the line 20
    # on at (30, 10)
    prog = run("2 FC DR- R10 P1X+10 P1Y-10\n3 FLT AN+0 PDX+30 PDY+15 D5 LEN 20")
    assert ends(prog) == [[10, 10], [30, 10]] and centre(prog.blocks[1]) == [10, 0]


@pytest.mark.parametrize("choice", [1, 2])
def test_chain_of_tangential_arcs_fixed_together(choice):
    # an arc about (0, 0) (R10, DR+, from (10, 0)), a tangent arc of R10 DR- only, and a tangent arc DR+ R10 about
    # (30, 0) to (40, 0): arcs of opposite senses touch from outside, so the middle centre is 20 from both known
    # ones, (15, +-5 sqrt 7), and each touching point the midpoint of two centres. The first arc reaches the upper
    # touching point after 41.4 degrees, the lower after 318.6: FSELECT 1 is the upper chain
    sign = 1 if choice == 1 else -1
    prog = run(f"2 L X+10 Y+0\n3 FC DR+ R10 CCX+0 CCY+0\n4 FCT DR- R10\n5 FCT DR+ R10 CCX+30 CCY+0 X+40 Y+0\n"
               f"6 FSELECT {choice}")
    h = 2.5 * math.sqrt(7) * sign
    assert ends(prog)[1:] == [[7.5, round(h, 6)], [22.5, round(h, 6)], [40, 0]]
    assert [centre(b) for b in prog.blocks[2:]] == [[0, 0], [15, round(2 * h, 6)], [30, 0]]


def test_manual_fk_example_with_auxiliary_points():
    # the TNC 370 user's manual's "Example 2 for exercise in FK free contour programming" (section 5.6, p. 5-49):
    # a lever of a circle R30 about FPOL (30, 30) and a circle R20 55 from it at 60 degrees (CCPR/CCPA), joined by
    # the two lines at AN+60 / AN-120 passing 10 from (30, 30) (PDX PDY D). Its FSELECT numbers are the TNC's (not
    # documented); here the ones that draw the lever in our numbering. With u along 60 degrees and n its left normal,
    # the lines are (30, 30) +- 10 n + s u: the left one meets the big circle at s = sqrt(30^2 - 10^2) and the small
    # one (about c2) at s = -sqrt(20^2 - 10^2) from c2 + 10 n; the right one leaves the small circle at c2 - 10 n +
    # sqrt(300) u and meets the big circle at (30, 30) - 10 n + sqrt(800) u; the last arc closes at (0, 30)
    prog = run("2 L X+0 Y+30\n3 FPOL X+30 Y+30\n4 FC DR- R30 CCX+30 CCY+30\n5 FL AN+60 PDX+30 PDY+30 D10\n"
               "6 FSELECT 1\n7 FC DR- R20 CCPR+55 CCPA+60\n8 FSELECT 1\n9 FL AN-120 PDX+30 PDY+30 D10\n"
               "10 FSELECT 2\n11 FC X+0 Y+30 DR- CCX+30 CCY+30\n12 FSELECT 1")
    c1, u = np.array([30.0, 30.0]), np.array([0.5, math.sqrt(3) / 2])
    n, c2 = np.array([-u[1], u[0]]), c1 + 55 * u
    points = [c1 + 10 * n + math.sqrt(800) * u, c2 + 10 * n - math.sqrt(300) * u, c2 - 10 * n + math.sqrt(300) * u,
              c1 - 10 * n + math.sqrt(800) * u, [0, 30]]
    assert ends(prog)[1:] == [np.round(p, 6).tolist() for p in points]
    assert [centre(b) for b in prog.blocks[2::2]] == [[30, 30], np.round(c2, 6).tolist(), [30, 30]]


def test_manual_fk_example_of_lines():
    # the TNC 370 user's manual's "Example 1 for exercise in FK free contour programming" (section 5.6, p. 5-48), its
    # FSELECT numbers the manual's: LEN 64.5 through P1 (15, 35) from (0, 0), up (FSELECT 1); then PR 67 about FPOL
    # (50, 20) at AN+21 (the line's parameter t from |E - FPOL| = 67, the root ahead); IX+15; LEN 40 parallel to the
    # first line, back down (FSELECT 2); to (75, 20); CLSD- back to (0, 0)
    prog = run("2 FPOL X+50 Y+20\n3 FL LEN 64.5 CLSD+ P1X+15 P1Y+35\n4 FSELECT 1\n5 FL PR+67 AN+21\n"
               "6 FL IX+15 IY+0\n7 FL LEN 40 PAR 3\n8 FSELECT 2\n9 FL X+75 Y+20\n10 FL CLSD-")
    u1 = np.array([15.0, 35.0]) / math.hypot(15, 35)
    e1, d = 64.5 * u1, np.array([math.cos(math.radians(21)), math.sin(math.radians(21))])
    q = e1 - [50, 20]
    t = -q @ d + math.sqrt((q @ d) ** 2 - q @ q + 67 ** 2)
    e2 = e1 + t * d
    e3 = e2 + [15, 0]
    assert ends(prog) == [np.round(p, 6).tolist() for p in (e1, e2, e3, e3 - 40 * u1, [75, 20], [0, 0])]


@pytest.mark.parametrize(("body", "message"), [
    ("2 FL AN+30\n3 L X+5", "FL: its length is not determined (the TNC's 'not yet resolved' element)"),
    ("2 FL AN+30", "expected LEN, or a coordinate of its end point"),
    ("2 FC CCX+10 CCY+0 DR-\n3 L X+5", "FC: its circle or its end is not determined"),
    ("2 FL X+10 Y+0\n3 FSELECT 2", "FSELECT without an FK element of several solutions"),
    ("2 FC X+10 Y+0 R10 DR+\n3 FL X+0", "FC: the FK element of line 3 has 2 solutions and no FSELECT picks one"),
    ("2 L X+10 Y+0\n3 FC DR+ R10 CCX+0 CCY+0\n4 FCT DR- R10\n5 FCT DR+ R10 CCX+30 CCY+0\n6 L X+0",
     "FCT: the FK elements of lines 4-5 (resolved together) have 2 solutions (fixed by the FCT of line 6)"),
    ("2 L X+10 Y+0\n3 FC DR+ R10 CCX+0 CCY+0\n4 FCT DR- R10\n5 FCT DR+ R10 CCX+30 CCY+0\n6 FSELECT 3",
     "FSELECT 3: the FK elements of lines 4-5 (resolved together) have 2 solutions"),
    ("2 FC X+10 Y+10 DR+", "FC: its circle or its end is not determined"),
    ("2 FC X+10 Y+0 R10 DR+\n3 FSELECT 3", "FSELECT 3: the FK element of line 3 has 2 solutions"),
    ("2 FL X+10", "FL: its end point is not determined"),
    ("2 FL LEN 10", "FL: its direction is not determined"),
    ("2 FL PR+10 PA+0", "PR+10 without an FK pole"),
    ("2 FL IX+5 RX 7", "RX 7: block 7 is not an FK element run before"),
    ("2 FL X+10 Y+0 AN+90", "FL: no element fits its data"),
    ("2 FL AN+10 PDX+5 D2", "D2: an auxiliary point at a distance needs PDX, PDY and D"),
    ("2 FL LEN 10 PDX+0 PDY+3 D5", "FL: no element fits its data"),  # no line through (0, 0) is 5 from (0, 3)
    ("2 FL CLSD-", "CLSD- without a CLSD+"),
    ("2 FC CCX+10 CCY+0 X+20 Y+0", "FC without a direction of rotation"),
    # not enough data: the first open element named, with the blocks after it that did not fix it
    ("2 FL AN+0\n3 FL X+30 Y+10", "FL: its length is not determined, not even with the FK blocks of lines 4-4"),
    ("2 FL AN+0\n3 FCT DR+ R5\n4 FLT X+30 Y+20", "not even with the FK blocks of lines 4-5 after it"),
    ("2 FL AN+0\n3 FCT DR+ R5\n4 L X+5", "FL: its length is not determined, not even with the FK blocks"),
    ("2 FC CCX+10 CCY+0 DR-\n3 FLT\n4 L X+5", "FC: its circle or its end is not determined, not even with"),
    # contradictory data: the block whose data made the open elements determined, and where they began
    ("2 FL AN+0\n3 FL X+30 Y-10 AN+45", "FL: no element fits the data of the open FK elements from line 3 on"),
    # IX from the open line's unknown end and AN leave where it ends open (and contradict Y); an FL (not FLT) after
    # the arc leaves its sweep open
    ("2 FL AN+0\n3 FL IX+10 Y+5 AN+45", "FL: its length is not determined, not even with the FK blocks"),
    ("2 FL AN+0\n3 FCT DR+ R5\n4 FL X+30 Y+20 AN+90", "not even with the FK blocks of lines 4-5 after it"),
    ("2 FC CCX+10 CCY+0 DR-\n3 FLT\n4 FCT DR+ R5 CCX+10 CCY+0", "FCT: no element fits the data of the open FK"),
    ("2 FL X+5 Z+3", "word 'Z+3' names the tool axis, not an axis of the working plane"),
    ("2 FL X+5 W+3", "unknown word 'W+3' in an FK block"),
    ("2 FPOL X+1 PA+3", "word 'PA+3' not allowed in FPOL"),
    ("2 FL X+5 Y+5 DR+", "word 'DR+' not allowed in FL"),
    ("TOOL CALL 1 X\n2 FL X+5 Y+5", "word 'X+5' names the tool axis"),
    ("TOOL CALL 1 X\n2 FL Y+5 Z+5 X+1", "expected FK data in the working plane YZ of the TOOL CALL axis"),
])
def test_errors_name_the_element_and_the_data_needed(body, message):
    with pytest.raises(GCodeError) as exc:
        run(body, reference=False)
    assert message in str(exc.value)


@pytest.mark.parametrize(("axis", "first", "second"), [("Y", 2, 0), ("X", 1, 2)])
def test_fk_in_the_working_plane_of_another_tool_axis(axis, first, second):
    # FK data name the axes of the working plane of the TOOL CALL axis (our reading): ZX with tool axis Y (first
    # axis Z, as X in XY), YZ with tool axis X (first Y). The contour of test_end_points_and_tangency written in
    # those letters resolves to its points (20, 0), (30, 0), the arc about (30, 10) to (40, 10), (40, 20) in (first,
    # second); the tool axis stays at 0. Reader only: the reference runs tool axis Z; in XY it checks the same data.
    a, b = "XYZ"[first], "XYZ"[second]
    text = (f"0 BEGIN PGM T MM\n1 TOOL CALL 1 {axis} S1000\n2 L X+0 Y+0 Z+0 R0 F500\n3 FL {a}+20 {b}+0\n"
            f"4 FLT {a}+30\n5 FCT {a}+40 {b}+10\n6 FLT LEN 10\n7 END PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    assert [np.round(blk.target[[first, second]], 6).tolist() for blk in prog.blocks[1:]] == [
        [20, 0], [30, 0], [40, 10], [40, 20]]
    assert all(blk.target["XYZ".index(axis)] == 0 for blk in prog.blocks)
    arc = prog.blocks[3]
    assert arc.kind == "arc" and np.round(arc.segment.center[[first, second]], 6).tolist() == [30, 10]


def test_flt_needs_a_preceding_element():
    with pytest.raises(GCodeError, match="FLT without a preceding contour element"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 FLT X+5 Y+0 F100\n2 END PGM T MM\n", source="t.h", context=CTX)


@pytest.mark.parametrize(("cycle", "turn"), [
    ("CYCL DEF 10.0 ROTATION\n3 CYCL DEF 10.1 ROT+90", lambda x, y: [-y, x]),
    ("CYCL DEF 8.0 MIRROR IMAGE\n3 CYCL DEF 8.1 Y", lambda x, y: [x, -y]),
])
def test_fk_contour_under_a_rotation_or_mirror(cycle, turn):
    # the contour of test_end_points_and_tangency resolved in program coordinates, then turned 90 degrees about
    # the datum (machine = (-y, x)) or mirrored in Y (the arc then turns clockwise); FLT takes the program-frame
    # tangent of the element before it
    prog = run(f"2 {cycle}\n4 FL X+20 Y+0\n5 FLT X+30\n6 FCT X+40 Y+10\n7 FLT LEN 10")
    assert ends(prog) == [turn(20, 0), turn(30, 0), turn(40, 10), turn(40, 20)]


def test_inch_program_and_q_parameters():
    # in an INCH program the FK data are inches: FL to X 1 (25.4 mm), FLT LEN Q1 = 1 on along +X (50.8 mm); the
    # arc FCT R Q2 = 0.5 DR+ through CCA 90 ends 0.5 in on and 0.5 in up: (63.5, 12.7) mm
    text = ("0 BEGIN PGM T INCH\n1 L X+0 Y+0 Z+0 R0 F20\n2 Q1 = 1\n3 Q2 = 0.5\n4 FL X+1 Y+0\n5 FLT LEN Q1\n"
            "6 FCT R+Q2 DR+ CCA+90\n7 END PGM T INCH\n")
    prog = checked_program(text, CTX)
    assert ends(prog) == [[25.4, 0], [50.8, 0], [63.5, 12.7]]


def test_fk_contour_in_an_sl_contour_train():
    # cycle 25 CONTOUR TRAIN on the contour LBL 1 written in FK: (0, 0) along +X, an FCT R10 DR+ rounding into +Y, up
    # to (50, 30): the contour (40, 0), arc about (40, 10) to (50, 10), (50, 30); RL with the tool radius 3 runs it
    # 3 inside: (40, 3), the arc on radius 7 to (47, 10), (47, 30), at Z-5 then Z-10 (tool length 10: machine Z 5
    # and 0). Reader only: the reference's SL cycles read their contour labels as L/C blocks.
    ctx = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L Z+100 R0 FMAX\n3 CYCL DEF 14.0 CONTOUR\n"
            "4 CYCL DEF 14.1 CONTOUR LABEL 1\n5 CYCL DEF 25 CONTOUR TRAIN Q1=-10 Q3=+0 Q5=+0 Q7=+50 Q10=+5 Q11=100 "
            "Q12=350 Q15=+1\n6 L X-10 Y-10 R0 FMAX\n7 CYCL CALL\n8 L X-10 Y-10 Z+100 R0 FMAX M30\n9 LBL 1\n"
            "10 L X+0 Y+0 RL\n11 FL AN+0\n12 FCT DR+ R10\n13 FLT X+50 Y+30 AN+90\n14 LBL 0\nEND PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h", context=ctx)
    cut = [np.round(b.target, 6).tolist() for b in prog.blocks if b.kind != "rapid" and b.feed * 60 > 300]
    assert cut == [[x, y, z] for z in (5, 0) for x, y in ((40, 3), (47, 10), (47, 30))]


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_reference_decisions_stand_a_rounding_difference(monkeypatch, seed):
    # every starting point and residual vector the reference's solver (MINPACK's leastsq) sees off by 1e-13
    # relative and 1e-16 absolute (as a BLAS thread count or memory alignment may make them; a line along +X then
    # leaves at -1e-10 degrees, which must still number it first): the same solutions, numbered alike
    rng = np.random.default_rng(seed)

    def noisy(a):
        a = np.asarray(a, float)
        return a * (1.0 + 1e-13 * rng.standard_normal(a.shape)) + 1e-16 * rng.standard_normal(a.shape)

    solver = reference_heidenhain_fk.leastsq
    monkeypatch.setattr(reference_heidenhain_fk, "leastsq",
                        lambda fun, x0, *a, **k: solver(lambda z: noisy(fun(z)), noisy(x0), *a, **k))
    first = run("2 FL X+10 Y+0\n3 FL IAN+90 LEN 5\n4 FL LEN 5 PAR 2\n5 FSELECT 1")
    back = run("2 FL X+10 Y+0\n3 FL IAN+90 LEN 5\n4 FL LEN 5 PAR 2\n5 FSELECT 2")
    assert ends(first) == [[10, 0], [10, 5], [15, 5]] and ends(back) == [[10, 0], [10, 5], [5, 5]]
