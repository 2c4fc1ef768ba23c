"""Heidenhain programs of a fifth wild set (the worked examples of the TNC 426/430 user's manual, Fusion 360,
hyperMILL and shop programs): what the reader refused though the control runs it, each as a hand-written
program with end points worked out by hand and checked against the independent reference."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

ZERO = MachineContext()


def checked(body: str):
    """The program read, and its blocks matched against the reference (compensated rows within the radius)."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO, exact=False)


def test_an_appr_lct_arc_smaller_than_the_tool_is_the_tool_path():
    # the manual's own examples approach with R5 and a tool of R10 ("the radius then suffices to completely
    # define the tool path"). Tool R4, first element from PA (10, 0) along +Y, RL: the tool centre reaches
    # (6, 0) on a counter-clockwise arc of radius 2 about (4, 0); the line from PS (4, -20) touches that circle
    # at the angle -acos(2/20) + 90 deg = -5.739 deg: PH = (4 + 2 cos, 2 sin)
    prog = checked("1 TOOL DEF 1 L+0 R+4\n2 TOOL CALL 1 Z S1000\n3 L X+4 Y-20 Z-2 R0 F500\n"
                   "4 APPR LCT X+10 Y+0 R2 RL F200\n5 L X+10 Y+30\n6 L X+40 R0")
    phi = math.radians(-90.0) + math.acos(2.0 / 20.0)
    line, arc, first = prog.blocks[1:4]
    assert np.allclose(line.target[:2], [4 + 2 * math.cos(phi), 2 * math.sin(phi)])
    assert arc.kind == "arc" and arc.segment.ccw and np.allclose(arc.segment.center[:2], [4, 0])
    assert np.allclose(arc.target[:2], [6, 0]) and np.allclose(first.target[:2], [6, 30])
    # the same arc opened by the tool's radius: before, an error ("tool radius 4 mm not less than arc radius 2")


def test_a_dep_block_without_r0_cancels_the_compensation():
    # TNC 410 manual: "The TNC automatically cancels the radius compensation in a DEP block": DEP LCT to
    # PN (40, 40) without R0 ends on PN itself, as DEP LCT .. R0 does, and the next block leaves from there
    body = ("1 TOOL DEF 1 L+0 R+4\n2 TOOL CALL 1 Z S1000\n3 L X+4 Y-20 Z-2 R0 F500\n"
            "4 APPR LCT X+10 Y+0 R2 RL F200\n5 L X+10 Y+30\n6 DEP LCT X+40 Y+40 R3{r0}\n7 L Z+50 FMAX")
    without, with_r0 = checked(body.format(r0="")), checked(body.format(r0=" R0"))
    assert [b.target.tolist() for b in without.blocks] == [b.target.tolist() for b in with_r0.blocks]
    assert np.allclose(without.blocks[-2].target, [40, 40, -2]) and np.allclose(without.blocks[-1].target,
                                                                                [40, 40, 50])


def test_an_arc_turning_away_from_the_tool_needs_a_radius_beyond_it():
    # APPR CT with RL and R- turns clockwise, away from the tool: its tool path of radius 3 lies outside a
    # contour arc of radius 3 - 4 < 0, which no contour arc has (our reading: no manual page for this case)
    with pytest.raises(GCodeError, match=r"APPR CT R-3 turns away from the tool's side and is not larger than "
                                         r"the tool radius 4 mm"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 TOOL DEF 1 L+0 R+4\n2 TOOL CALL 1 Z S1000\n3 L X+4 Y-20 Z-2 R0 F500\n"
                         "4 APPR CT X+10 Y+0 CCA90 R-3 RL F200\n5 L X+10 Y+30\nEND PGM T MM\n", context=ZERO)


def test_the_manuals_formula_functions_agree_with_the_reference():
    # TNC 426/430 manual 10.9 "Q1 = 5 * 3 + 2 * 10" = 35, "SQ 10 - 3^3" = 73; FN 5 SQRT, FN 8 LEN (3, 4) = 5,
    # FN 13 ANG (1, 1) = 45: both readers put them in the same X/Y words
    prog = checked("1 Q1 = 5 * 3 + 2 * 10\n2 Q2 = SQ 10 - 3^3\n3 FN 5: Q3 = SQRT +16\n4 FN 8: Q4 = +3 LEN +4\n"
                   "5 FN 13: Q5 = +1 ANG +1\n6 FN 6: Q6 = SIN +30\n7 FN 7: Q7 = COS +60\n"
                   "8 L X+Q1 Y+Q2 Z+Q3 R0 FMAX\n9 L X+Q4 Y+Q5 R0 FMAX\n10 L X+Q6 Y+Q7 R0 FMAX")
    assert np.allclose([b.target for b in prog.blocks], [[35, 73, 4], [5, 45, 4], [0.5, 0.5, 4]])


def test_rnd_chf_cr_and_ct_agree_with_the_reference():
    # as the manual's "circular movements" example: RND R5 at the left turn (20, 0): 5 tan 45 = 5 from the corner
    # on each line, centre (15, 5); CHF 4 at (20, 20): 4 back on each line; CR R+10 DR+ from (0, 20) to
    # (-10, 10): the quarter about (0, 10); CT on to (0, 0): the same circle, since it leaves along -Y
    prog = checked("1 L X+0 Y+0 Z-1 R0 F100\n2 L X+20 Y+0\n3 RND R5\n4 L X+20 Y+20\n5 CHF 4\n6 L X+0 Y+20\n"
                   "7 CR X-10 Y+10 R+10 DR+\n8 CT X+0 Y+0")
    assert np.allclose([b.target[:2] for b in prog.blocks], [[0, 0], [15, 0], [20, 5], [20, 16], [16, 20], [0, 20],
                                                             [-10, 10], [0, 0]], atol=1e-12)
    rnd, cr, ct = prog.blocks[2], prog.blocks[6], prog.blocks[7]
    assert rnd.segment.ccw and np.allclose(rnd.segment.center[:2], [15, 5])
    assert cr.segment.ccw and np.allclose(cr.segment.center[:2], [0, 10])
    assert ct.segment.ccw and np.allclose(ct.segment.center[:2], [0, 10])


def test_a_tool_def_without_length_or_radius_keeps_the_table_tool():
    # a Fusion-style "TOOL DEF 1 ; pre-load": tool pre-selection, the table's length stays (here 20)
    ctx = MachineContext(tools={1: Tool(number=1, length=20.0)})
    text = "0 BEGIN PGM T MM\n1 TOOL DEF 1 ; pre-load\n2 TOOL CALL 1 Z S1000\n3 L X+0 Y+0 Z+5 R0 FMAX\nEND PGM T MM\n"
    prog = parse_heidenhain(text, context=ctx)
    assert prog.blocks[-1].target.tolist() == [0.0, 0.0, 25.0]
    assert match_blocks(heidenhain_reference(text, ctx), blocks_table(prog)[1]).mismatch is None


def test_a_repeat_count_display_after_a_q_parameter_is_refused_naming_the_form():
    # an APT post wrote "CALL LBL 1 REP Q3/Q3" and its author changed it to "REP 10/10" the same day: the
    # "/k" display of the repeats left follows a number; "REP Q3" alone runs
    body = "1 Q3 = 2\n2 L X+0 Y+0 Z+0 R0 F100\n3 LBL 1\n4 L IX+1\n5 CALL LBL 1 REP {rep}"
    assert checked(body.format(rep="Q3")).blocks[-1].target.tolist() == [3.0, 0.0, 0.0]
    assert checked(body.format(rep="2/2")).blocks[-1].target.tolist() == [3.0, 0.0, 0.0]
    with pytest.raises(GCodeError, match=r"t\.h:6:.*malformed label call.*count display '/k' only after a number"):
        checked(body.format(rep="Q3/Q3"))


def test_fn13_angle_lies_between_0_and_360_degrees():
    # TNC 370 user's manual 7.3: FN13 ANGLE "(0 < angle < 360)": the vector (0, -1) is at 270 degrees, not -90
    prog = checked("1 FN 13: Q1 = +0 ANG -1\n2 FN 13: Q2 = -1 ANG -1\n3 L X+Q1 Y+Q2 Z+0 R0 FMAX")
    assert np.allclose(prog.blocks[-1].target, [270.0, 225.0, 0.0])


@pytest.mark.parametrize("between", ["", "7 TOOL CALL 1 Z DL+0\n"])
def test_an_r0_block_with_only_the_tool_axis_ends_at_the_programmed_point(between):
    # TNC manuals: the block that cancels compensation "positions the tool perpendicular to the programmed
    # ... end position", R0 "moves to the programmed coordinates": after an RL contour ending at (20, 20),
    # tool R5, L Z+50 R0 retracts to (20, 20, 50), not straight up from the offset point (15, 20); a TOOL CALL
    # between does not cancel compensation (only R0, DEP and PGM MGT do, TNC 620 manual)
    prog = checked("1 TOOL DEF 1 L+0 R+5\n2 TOOL CALL 1 Z S1000\n3 L X+0 Y+0 Z+10 R0 FMAX\n"
                   "4 L X+20 Y+0 RL F500\n5 L X+20 Y+20\n" + between + "8 L Z+50 R0 FMAX\n9 L X+40")
    contour_end, retract, after = prog.blocks[-3:]
    assert np.allclose(contour_end.target, [15, 20, 10])
    assert np.allclose(retract.target, [20, 20, 50]) and np.allclose(after.target, [40, 20, 50])
