"""Heidenhain programs of the fourteenth wild set (HEIDENHAIN demonstration programs, hyperMILL DMU output,
shop programs): cycle 220's arcs between positions (Q365 = 1), the bound of a pattern's positions and the
tool-table message of the cycles that need a radius, each as a hand-written program with end points worked out
by hand and checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.heidenhain_cycles import MAX_PATTERN_POSITIONS
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=0.0, radius=2.0)})

DRILL = ("3 CYCL DEF 200 DRILLING ~\n Q200=2 ;SET-UP CLEARANCE ~\n Q201=-5 ;DEPTH ~\n Q206=150 ;FEED ~\n"
         " Q202=5 ;PLUNGING DEPTH ~\n Q210=0 ;DWELL TOP ~\n Q203=+0 ;SURFACE ~\n Q204=10 ;2ND SET-UP ~\n"
         " Q211=0 ;DWELL DEPTH\n")


def polar(q247: str = "+0", q241: str = "4", q365: str = "1", before: str = "") -> str:
    return ("1 TOOL CALL 1 Z S1000\n2 L Z+50 R0 FMAX\n" + before + DRILL +
            "4 CYCL DEF 220 POLAR PATTERN ~\n Q216=+50 ;CENTER 1ST ~\n Q217=+50 ;CENTER 2ND ~\n Q244=80 ;DIAMETER ~\n"
            f" Q245=+0 ;START ~\n Q246=+360 ;STOP ~\n Q247={q247} ;STEP ~\n Q241={q241} ;REPETITIONS ~\n"
            " Q200=2 ;SET-UP ~\n Q203=+0 ;SURFACE ~\n Q204=10 ;2ND SET-UP ~\n Q301=0 ;MOVE TO CLEARANCE ~\n"
            f" Q365={q365} ;TYPE OF TRAVERSE\n5 L Z+50 R0 FMAX\n")


def run(body: str, context: MachineContext = CTX):
    return checked_program("0 BEGIN PGM T MM\n" + body + "6 END PGM T MM\n", context)


def between(prog):
    """The moves from one hole to the next: at the set-up clearance Z+2, in the plane."""
    return [b for b in prog.blocks if b.start[2] == b.target[2] == 2.0 and not np.allclose(b.start, b.target)]


def test_cycle_220_with_q365_1_moves_between_the_holes_on_the_pitch_circle():
    # TNC 640 cycle manual 34059x-01, cycle 220: "Q365 Type of traverse? Line=0/arc=1", 1 "on the pitch circle"
    prog = run(polar())
    moves = between(prog)
    assert [m.kind for m in moves] == ["arc"] * 3
    assert [np.round(m.target, 9).tolist() for m in moves] == [[50.0, 90.0, 2.0], [10.0, 50.0, 2.0], [50.0, 10.0, 2.0]]
    assert all(m.segment.ccw and np.allclose(m.segment.center[:2], (50.0, 50.0)) for m in moves)
    assert all(m.feed == np.inf for m in moves)  # at rapid traverse, as the straight moves
    assert not any("Q365" in n for n in prog.notes)


def test_cycle_220_q365_1_with_a_negative_step_turns_clockwise():
    prog = run(polar(q247="-90", q241="3"))
    moves = between(prog)
    assert [m.kind for m in moves] == ["arc", "arc"]
    assert [np.round(m.target, 9).tolist() for m in moves] == [[50.0, 10.0, 2.0], [10.0, 50.0, 2.0]]
    assert not any(m.segment.ccw for m in moves)


def test_cycle_220_q365_1_under_a_mirror_turns_the_other_way():
    prog = run(polar(before="2 CYCL DEF 8.0 MIRROR IMAGE\n2 CYCL DEF 8.1 X\n"))
    moves = between(prog)
    assert [np.round(m.target, 9).tolist() for m in moves] == [[-50.0, 90.0, 2.0], [-10.0, 50.0, 2.0],
                                                               [-50.0, 10.0, 2.0]]
    assert not any(m.segment.ccw for m in moves)


def test_cycle_220_q365_0_moves_straight():
    moves = between(run(polar(q365="0")))
    assert [m.kind for m in moves] == ["rapid"] * 3
    assert np.round(moves[-1].target, 9).tolist() == [50.0, 10.0, 2.0]


def test_cycle_220_q365_1_under_axis_specific_scaling_is_an_error_naming_it():
    with pytest.raises(GCodeError, match=r"Q365=1 .*axis-specific scaling"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + polar(before="2 CYCL DEF 26.0 AXIS-SPECIFIC SCALING\n"
                                                              "2 CYCL DEF 26.1 X1.5 Y1\n") + "6 END PGM T MM\n",
                         source="t.h", context=CTX)


@pytest.mark.parametrize(("pattern", "message"), [
    ("PATTERN DEF ~\n ROW1 (X+0 Y+0 D+1 NUM100000 ROT+0 Z+0)", r"NUM100000.*NUM a whole number from 1 to 99999"),
    ("PATTERN DEF ~\n ROW1 (X+0 Y+0 D+1 NUM60000 Z+0) ~\n ROW2 (X+0 Y+5 D+1 NUM60000 Z+0)",
     r"PATTERN DEF with 120000 positions.*at most 99999 positions in all"),
])
def test_a_pattern_def_of_more_positions_than_the_manuals_range_is_an_error(pattern, message):
    # a mistyped NUM would make hours of moves: cycle 220's Q241 "Input range 1 to 99999" (TNC 320 cycle manual)
    assert MAX_PATTERN_POSITIONS == 99_999
    text = "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n" + DRILL + "4 " + pattern + "\n5 CYCL CALL PAT\n6 END PGM T MM\n"
    with pytest.raises(GCodeError, match=message):
        parse_heidenhain(text, source="t.h", context=CTX)


def test_a_pattern_cycle_of_more_positions_than_the_manuals_range_is_an_error():
    with pytest.raises(GCodeError, match=r"cycle 220: Q241=100000 positions.*Q241 from 1 to 99999"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + polar(q241="100000") + "6 END PGM T MM\n", source="t.h", context=CTX)
    grid = ("4 CYCL DEF 221 CARTESIAN PATTERN ~\n Q225=+0 ;START 1ST ~\n Q226=+0 ;START 2ND ~\n"
            " Q237=+1 ;SPACING 1ST ~\n Q238=+1 ;SPACING 2ND ~\n Q242=1000 ;COLUMNS ~\n Q243=1000 ;LINES ~\n"
            " Q224=+0 ;ANGLE ~\n"
            " Q200=2 ;SET-UP ~\n Q203=+0 ;SURFACE ~\n Q204=10 ;2ND SET-UP ~\n Q301=0 ;MOVE TO CLEARANCE\n")
    with pytest.raises(GCodeError, match=r"cycle 221: Q242 x Q243 = 1000 x 1000 positions.*at most 99999"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n" + DRILL + grid + "6 END PGM T MM\n",
                         source="t.h", context=CTX)


def test_a_pattern_def_within_the_range_runs_every_position():
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L Z+50 R0 FMAX\n" + DRILL +
            "4 PATTERN DEF ~\n ROW1 (X+0 Y+0 D+10 NUM3 ROT+0 Z+0)\n5 CYCL CALL PAT\n6 END PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    bottoms = [np.round(b.target, 9).tolist() for b in prog.blocks if b.target[2] == -5.0]
    assert bottoms == [[0.0, 0.0, -5.0], [10.0, 0.0, -5.0], [20.0, 0.0, -5.0]]


def test_rough_out_without_a_tool_radius_names_the_tool_and_the_tool_table():
    # as HEIDENHAIN's demonstration program SLII001 calls TOOL CALL 20 of the machine's tool table
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 20 Z S1000\n2 L Z+100 R0 FMAX\n3 CYCL DEF 14.0 CONTOUR\n"
            "4 CYCL DEF 14.1 CONTOUR LABEL1\n5 CYCL DEF 20 CONTOUR DATA ~\n Q1=-15 ~\n Q2=+1 ~\n Q3=+1 ~\n Q4=+0.2 ~\n"
            " Q5=+0 ~\n Q6=+2 ~\n Q7=+50 ~\n Q8=+0.1 ~\n Q9=+1\n6 CYCL DEF 22 ROUGH-OUT ~\n Q10=-2 ~\n Q11=+150 ~\n"
            " Q12=+500 ~\n Q18=+0 ~\n Q19=+250\n7 CYCL CALL\n8 L Z+100 R0 FMAX M30\n9 LBL 1\n10 L X+10 Y+10 RL\n"
            "11 L X+90\n12 L Y+90\n13 L X+10\n14 L Y+10\n15 LBL 0\n16 END PGM T MM\n")
    with pytest.raises(GCodeError, match=r"t\.h:\d+:\d+: cycle 22 needs a tool radius > 0 .*tool 20 has none.*"
                                         r"\[program\.tools\.N\] radius"):
        parse_heidenhain(text, source="t.h", context=CTX)


def test_m114_is_an_error_naming_it():
    # a Python 5-axis generator's form (M114 before the L X Y Z B C lines, M115 after): iTNC 530 user's manual,
    # "Automatic compensation of machine geometry when working with tilted axes: M114"; ignored, every point
    # after it would be off by the compensation the TNC adds
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S9000 F1200\n2 L X+0 Y-30 R0 FMAX\n3 M114\n"
            "4 L X+10 Y-28 Z-2 R0\n5 M115\n6 END PGM T MM\n")
    with pytest.raises(GCodeError, match=r"t\.h:4:3: M114 \(automatic compensation .*tilted axes\) is not modelled"
                                         r".*expected M128 or FUNCTION TCPM"):
        parse_heidenhain(text, source="t.h", context=CTX)


def test_sysread_of_the_traverse_range_says_the_machine_context_holds_no_travel():
    # the same generator starts with FN 18: SYSREAD Q30 = ID230 NR3 IDX3 and L ZQ30 R0 FMAX M91
    text = "0 BEGIN PGM T MM\n1 FN 18: SYSREAD Q30 = ID230 NR3 IDX3\n2 L ZQ30 R0 FMAX M91\n3 END PGM T MM\n"
    with pytest.raises(GCodeError, match=r"t\.h:2:\d+: FN 18 SYSREAD ID230 NR3 reads the machine's traverse range "
                                         r"\(its software limit switches\), which the machine context does not hold"):
        parse_heidenhain(text, source="t.h", context=CTX)


def test_fn_9_with_another_comparison_names_the_fn_of_that_comparison():
    # a programming guide's "FN 9: IF +Q10 GT +114 GOTO LBL 11": FN 9 jumps on EQU only, GT is FN 11 (TNC 640
    # user's manual, "If-then decisions with Q parameters": FN 9 EQU, FN 10 NE, FN 11 GT, FN 12 LT)
    text = "0 BEGIN PGM T MM\n1 Q10 = +120\n2 FN 9: IF +Q10 GT +114 GOTO LBL 11\n3 LBL 11\n4 END PGM T MM\n"
    with pytest.raises(GCodeError, match=r"t\.h:3:\d+: malformed FN 9 condition .*expected FN 9: IF a EQU b GOTO "
                                         r"LBL n \(GT is FN 11\)"):
        parse_heidenhain(text, source="t.h", context=CTX)


@pytest.mark.parametrize(("block", "where"), [
    # a CAM cycle definition over lines: the value on its fourth line, 'Q206=ZZ' at column 8 there
    ("1 CYCL DEF 200 DRILLING ~\n  Q200=2 ;SET-UP ~\n  Q201=-5 ;DEPTH ~\n  Q206=ZZ ;FEED\n",
     r"t\.h:5:8: malformed number"),
    # without '~', as a TNC simulator's test program writes it
    ("1 CYCL DEF 200 DRILLING\n  Q200=2\n  Q201=-5\n  Q206=ZZ\n", r"t\.h:5:8: malformed number"),
    # a PATTERN DEF's form on its second line
    ("1 PATTERN DEF ~\n  PAT1 (X+25 Y+33 DX+8 Z+0)\n", r"t\.h:3:9: PATTERN DEF PAT without DY, NUMX, NUMY"),
    ("1 PATTERN DEF ~\n  ROW1 (X+10 Y+20 D+15 NUM5 Z+0) ~\n  ROW2 (X+10 Y+60 D+15 NUM100000 Z+0)\n",
     r"t\.h:4:9: PATTERN DEF ROW with NUM100000"),
])
def test_an_error_in_a_block_over_several_lines_names_the_line_and_column_of_the_word(block, where):
    with pytest.raises(GCodeError, match=where):
        parse_heidenhain("0 BEGIN PGM T MM\n" + block + "2 END PGM T MM\n", source="t.h", context=CTX)
