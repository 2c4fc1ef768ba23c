"""Forms of HEIDENHAIN's own example programs (the user's manuals' Q parameter examples, HEIDENHAIN's published NC
solutions and HIT training solutions) that the reader refused or ran otherwise, each as a few hand-written blocks
with its end points worked out by hand and checked against the independent reference (``reference_heidenhain``).
The examples themselves ran through ``/tmp/tncman10/run.py`` (kept out of the repository)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool, read_tool_table
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError, InputError

ZERO = MachineContext()


def checked(body: str, *, exact: bool = True):
    """The program read, and its blocks matched against the reference (``exact=False``: compensated rows within
    the tool radius)."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO, exact=exact)


def test_polar_arc_without_an_angle_is_a_full_circle():
    # HEIDENHAIN's NC solution 11101 mills a bore as a helix 'CP IPA+9000 Z-30 DR+' and then its floor with
    # 'CP DR+': no PA, so the end angle stays the current one (as an LP without PA keeps it) and the end is the
    # start: one whole turn. Pole (50, 50), start (60, 50): the floor circle ends at (60, 50) after 360 deg
    prog = checked("1 L X+60 Y+50 Z+0 R0 F500\n2 CC X+50 Y+50\n3 CP IPA+720 Z-4 DR+\n4 CP DR+\n5 L X+50 Y+50")
    helix, floor = prog.blocks[1], prog.blocks[2]
    assert np.allclose(helix.target, [60, 50, -4]) and np.allclose(floor.target, [60, 50, -4])
    assert floor.segment.ccw and math.isclose(floor.segment.sweep, 2 * math.pi)
    cw = checked("1 L X+60 Y+50 Z+0 R0 F500\n2 CC X+50 Y+50\n3 CP DR-")
    assert not cw.blocks[-1].segment.ccw and math.isclose(cw.blocks[-1].segment.sweep, -2 * math.pi)


def test_polar_full_circle_under_radius_compensation():
    # the NC solution's form: 'LP PR+5 PA+0 RL' switches RL on at the bore's radius, the helix and the floor circle
    # follow; tool radius 2 (TOOL DEF): RL on a counter-clockwise circle of radius 5 puts the centre at radius 3
    prog = checked("1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n3 L X+0 Y+0 Z+0 R0 F300\n4 CC X+0 Y+0\n"
                   "5 LP PR+5 PA+0 RL\n6 CP IPA+360 Z-2 DR+\n7 CP DR+\n8 L X+0 Y+0 R0", exact=False)
    arcs = [b for b in prog.blocks if b.kind != "line"]
    assert len(arcs) == 2 and all(np.isclose(b.segment.radius, 3.0) for b in arcs)
    assert np.allclose(arcs[-1].target, [3, 0, -2])


def test_polar_arc_without_angle_or_direction_is_an_error():
    with pytest.raises(GCodeError, match=r"CP arc without direction .*expected DR\+ or DR-"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L X+10 Y+0 Z+0 R0 F100\n2 CC X+0 Y+0\n3 CP\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


# the TNC 640 user's manual's Q parameter example "Sphere" turns the part with cycle 10 ROTATION between its arcs
# and moves on each in the Z/X plane: 'CC Z+0 X+Q108' (Q108: the tool radius) and 'LP PR+Q6 PA+Q24'. With the
# rotation ROT+90 the program's X is the machine's Y: about the pole (Z 0, X 0) at radius 10 and PA+30 (from +Z
# toward +X) the program point is X 5, Z 8.660, so the machine point is (0, 5, 8.660)
SPHERE = ("1 L X+0 Y+0 Z+20 R0 FMAX\n2 CYCL DEF 10.0 ROTATION\n3 CYCL DEF 10.1 ROT+90\n4 FN 0: Q108 = +0\n"
          "5 FN 1: Q26 = +10 + +Q108\n6 CC Z+0 X+Q108\n7 LP PR+Q26 PA+30 R0 F300\n8 LP IPA-30\n")


def test_polar_line_about_a_pole_in_zx_under_a_rotation():
    prog = checked(SPHERE)
    assert np.allclose(prog.blocks[-2].target, [0, 5, 10 * math.cos(math.radians(30))])
    # IPA-30 from there: PA 0, on +Z above the pole
    assert np.allclose(prog.blocks[-1].target, [0, 0, 10])


def test_arc_about_a_pole_in_zx_under_a_rotation_stays_an_error():
    # an arc in a plane turned out of the machine's axes is not modelled; the CC itself is read
    with pytest.raises(GCodeError, match=r"CP about a CC outside the working plane under a coordinate "
                                         r"transformation .*expected R0 and no cycle 8/10/11/26 for CP"):
        checked(SPHERE + "9 CP IPA+90 DR+")


# the TNC 640 cycle manual's NC blocks of cycle 205 write 'Q379=7.5 ;STARTING POINT' and 'Q253=750 ;F
# PRE-POSITIONING': at Q253 from the set-up clearance above the surface to the set-up clearance above the deepened
# starting point, the infeeds from there. Surface 0, Q200 2, Q379 7.5, Q202 5, depth -20: FMAX to 2, at F750 to
# -5.5, infeeds to -12.5, -17.5, -20 with the re-entries Q258 0.5 above the last depth
PECK = ("1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+100 R0 FMAX\n3 CYCL DEF 205 UNIVERSAL PECKING ~\n Q200=2 ~\n Q201=-20 ~\n"
        " Q206=150 ~\n Q202=5 ~\n Q203=+0 ~\n Q204=50 ~\n Q212=0 ~\n Q205=0 ~\n Q258=0.5 ~\n Q259=0.5 ~\n Q257=0 ~\n"
        " Q256=0.2 ~\n Q211=0 ~\n Q379={start} ~\n Q253={feed}\n4 L X+10 Y+10 R0 FMAX M99")


def test_universal_pecking_from_a_deepened_starting_point():
    prog = checked(PECK.format(start="7.5", feed="750"))
    moves = [(b.kind, round(float(b.target[2]), 6), round(b.feed * 60, 6)) for b in prog.blocks[2:]]
    assert moves == [("rapid", 2, math.inf), ("line", -5.5, 750), ("line", -12.5, 150), ("rapid", 2, math.inf),
                     ("rapid", -12, math.inf), ("line", -17.5, 150), ("rapid", 2, math.inf), ("rapid", -17, math.inf),
                     ("line", -20, 150), ("rapid", 2, math.inf), ("rapid", 50, math.inf)]
    fast = checked(PECK.format(start="7.5", feed="MAX"))  # Q253 FMAX: rapid down to the deepened start
    assert [b.kind for b in fast.blocks[3:5]] == ["rapid", "line"] and fast.blocks[3].target[2] == -5.5


@pytest.mark.parametrize("start, feed, words", [
    ("20", "750", r"cycle 205: the deepened starting point Q379 must lie within the depth Q201"),
    ("7.5", "0", r"cycle 205: a deepened starting point Q379 needs the pre-positioning feed Q253 > 0"),
])
def test_universal_pecking_deepened_start_errors(start, feed, words):
    with pytest.raises(GCodeError, match=words):
        checked(PECK.format(start=start, feed=feed))


# T-ANGLE, the tool table's point angle (iTNC 530 technical manual 9.5.4, ID50 NR32): cycle 240 with Q343=1
# centres to the diameter Q344, cycles 200/203/205 with Q395=1 measure the depth to the full diameter. Tool 1: a
# 90 deg centre drill, length 0; tool 2: a 118 deg drill of radius 3
TANGLE = MachineContext(tools={1: Tool(number=1, radius=5.0, point_angle=90.0),
                               2: Tool(number=2, radius=3.0, point_angle=118.0), 3: Tool(number=3, radius=3.0)})
CENTER = ("1 TOOL CALL {t} Z S3000\n2 L X+0 Y+0 Z+100 R0 FMAX\n3 CYCL DEF 240 CENTERING ~\n Q200=2 ~\n Q343=1 ~\n"
          " Q201=+0 ~\n Q344=-9 ~\n Q206=250 ~\n Q211=0 ~\n Q203=+20 ~\n Q204=100\n4 L X+30 Y+20 R0 FMAX M99")
DRILL = ("1 TOOL CALL {t} Z S3000\n2 L X+0 Y+0 Z+100 R0 FMAX\n3 CYCL DEF 200 DRILLING ~\n Q200=2 ~\n Q201=-15 ~\n"
         " Q206=250 ~\n Q202=20 ~\n Q210=0 ~\n Q203=+0 ~\n Q204=50 ~\n Q211=0 ~\n Q395={ref}\n"
         "4 L X+10 Y+10 R0 FMAX M99")


def tanged(body: str):
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", TANGLE)


def test_centering_to_a_diameter_takes_the_point_angle():
    # diameter 9 with a 90 deg point: 4.5 deep, from the surface 20 to 15.5
    prog = tanged(CENTER.format(t=1))
    assert min(float(b.target[2]) for b in prog.blocks) == pytest.approx(15.5)


def test_depth_to_the_full_diameter_takes_the_point_angle():
    # Q395=1: the cylindrical part at -15, the tip 3 / tan(59 deg) = 1.8026 mm deeper
    tip = -15 - 3 / math.tan(math.radians(59))
    assert min(float(b.target[2]) for b in tanged(DRILL.format(t=2, ref=1)).blocks) == pytest.approx(tip)
    assert min(float(b.target[2]) for b in tanged(DRILL.format(t=2, ref=0)).blocks) == pytest.approx(-15)


def test_the_point_angle_is_the_called_tools_at_the_call():
    # the cycle is defined with the 118 deg drill, a 90 deg tool of radius 5 is called before the call: its cone
    prog = tanged(DRILL.format(t=2, ref=1) + "\n5 TOOL CALL 1 Z S3000\n6 L X+40 Y+10 R0 FMAX M99")
    assert float(prog.blocks[-3].target[2]) == pytest.approx(-20)  # -15 - 5 / tan(45 deg)


@pytest.mark.parametrize("body, words", [
    (CENTER.format(t=3), r"cycle 240: Q343=1 \(centering to the diameter Q344\) needs the tool's point angle, and "
                         r"the called tool has none .*expected a point angle in the tool table \(T-ANGLE"),
    (DRILL.format(t=3, ref=1), r"cycle 200: Q395=1 \(depth to the full diameter\) needs the tool's point angle"),
])
def test_no_point_angle_is_an_error_naming_the_column(body, words):
    with pytest.raises(GCodeError, match=words):
        tanged(body)


def test_tool_tables_carry_the_point_angle(tmp_path):
    path = tmp_path / "tool.t"
    path.write_text("BEGIN TOOL     .T     MM\nT    NAME             L           R           T-ANGLE\n"
                    "2    DRILL_D6         +120        +3          +118\n3    MILL             +80         +5\n[END]\n")
    tools = read_tool_table(str(path))
    assert tools[2].point_angle == 118.0 and tools[3].point_angle == 0.0
    with pytest.raises(InputError, match=r"tool 4: point angle must lie in \[0, 180\]"):
        Tool(number=4, point_angle=181.0)


# the manuals' SL example "Overlapping contours" writes its islands one side short of their first point (the square
# 'L X+27 Y+50 RL' / 'L Y+58' / 'L X+43' / 'L Y+42' / 'L X+27'): the SL cycles close such a contour with a line back
# to its first point, so the program runs as the one that writes the closing line
SL = ("1 TOOL DEF 1 L+0 R+3\n2 TOOL CALL 1 Z S2000\n3 L X+0 Y+0 Z+50 R0 FMAX\n4 CYCL DEF 14.0 CONTOUR\n"
      "5 CYCL DEF 14.1 CONTOUR LABEL1/2\n6 CYCL DEF 20 CONTOUR DATA ~\n Q1=-10 ~\n Q2=1 ~\n Q3=+0 ~\n Q4=+0 ~\n"
      " Q5=+0 ~\n Q6=2 ~\n Q7=+50 ~\n Q8=0 ~\n Q9=-1\n7 CYCL DEF 22 ROUGH-OUT ~\n Q10=10 ~\n Q11=100 ~\n Q12=350 ~\n"
      " Q18=0 ~\n Q19=150\n8 CYCL CALL M3\n9 L Z+50 R0 FMAX M2\n10 LBL 1\n11 CC X+35 Y+50\n12 L X+10 Y+50 RR\n"
      "13 C X+10 DR-\n14 LBL 0\n15 LBL 2\n16 L X+27 Y+50 RL\n17 L Y+58\n18 L X+43\n19 L Y+42\n20 L X+27\n{close}"
      "21 LBL 0")


def test_an_sl_island_one_side_short_is_closed():
    short = checked(SL.format(close=""), exact=False)
    closed = checked(SL.format(close="20 L Y+50\n"), exact=False)
    assert len(short.blocks) == len(closed.blocks) > 50
    assert all(np.allclose(a.target, b.target) for a, b in zip(short.blocks, closed.blocks, strict=True))
    # the island's square 27..43 x 42..58 stays uncut: no feed move at the depth ends inside it
    floor = [b for b in short.blocks if b.kind != "rapid" and b.target[2] == -10]
    assert len(floor) > 20
    assert not [b for b in floor if 27 < b.target[0] < 43 and 42 < b.target[1] < 58]
