"""Heidenhain programs of a thirteenth wild set (hyperMILL 2025 for a DMC 105V, a machine warm-up generator, a
CAM program manager's INCH programs, programs written in the forms of Fusion's and NX's TNC 640 posts): an FK
line along a tangent of the arc before it (one solution, not several), FUNCTION DWELL in the reference. Each a
hand-written program, checked against the independent reference where it runs."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()


def checked(body: str, context: MachineContext = ZERO):
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", context)


def program(body: str):
    return parse_heidenhain("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", context=ZERO)


def ends(prog, line: int) -> list[tuple[str, list[float]]]:
    return [(b.kind, np.round(b.target, 4).tolist()) for b in prog.blocks if b.line == line]


def arc_end(prog, line: int) -> list[float]:
    """The end of the one counter-clockwise arc of a line."""
    (block,) = [b for b in prog.blocks if b.line == line]
    assert block.kind == "arc" and block.segment.ccw
    return block.target.tolist()


def test_fk_line_along_a_tangent_of_the_arc_before_it_is_one_solution():
    # the FL's line X=0 touches the FCT's circle (centre 10/60, radius 10) at 0/60: a double root, which Newton's
    # method meets only to about 1e-5 mm from every start; vcnc counted 6 solutions there and asked for FSELECT
    prog = program("TOOL CALL 1 Z S4000\nL X+20 Y+70 R0 FMAX\nL Z-5 R0 F500\nL X+10 Y+70 F300\n"
                   "FCT DR+ R10\nFL X+0 Y+0 AN-90")
    assert arc_end(prog, 6) == pytest.approx([0.0, 60.0, -5.0], abs=1e-4)
    assert ends(prog, 7) == [("line", [0.0, 0.0, -5.0])]


def test_fk_tangent_line_with_a_second_real_solution_still_needs_fselect():
    # the line Y=70 (AN+180, 10 from 0/60) touches the circle about 90/60 at 90/70 (a quarter turn) and, turned
    # the other way round it, at 90/50 (three quarters): two solutions, not the four the double root made
    body = ("TOOL CALL 1 Z S4000\nL X+100 Y+50 R0 FMAX\nL Z-5 R0 F500\nL X+100 Y+60 F300\n"
            "FCT DR+ R10\nFL X+10 AN+180 PDX+0 PDY+60 D10")
    with pytest.raises(GCodeError, match="2 solutions"):
        program(body)
    prog = program(body + "\nFSELECT 1")
    assert arc_end(prog, 6) == pytest.approx([90.0, 70.0, -5.0], abs=1e-4)
    assert ends(prog, 7) == [("line", [10.0, 70.0, -5.0])]


def test_function_dwell_with_a_q_parameter_is_a_dwell_in_the_reference_too():
    # the warm-up generator's 'FUNCTION DWELL TIME+Q23' in a loop (TNC 640 user's manual, "Defining a dwell time:
    # FUNCTION DWELL"); the reference passed FUNCTION DWELL over silently, so it could not see the dwell rows
    prog = checked("Q23 = 2\nQ90 = 1\nTOOL CALL 1 Z S500\nL X+10 R0 FMAX M3\nLBL 2\nFUNCTION DWELL TIME+Q23\n"
                   "Q90 = Q90 + 1\nFN 12: IF +Q90 LT +4 GOTO LBL 2\nL X+20 R0 FMAX")
    dwells = [b for b in prog.blocks if b.kind == "dwell"]
    assert len(dwells) == 3 and all(b.dwell == pytest.approx(2.0) for b in dwells)
    assert ends(prog, 10) == [("rapid", [20.0, 0.0, 0.0])]


DRILL = ("TOOL CALL 1 Z S3000\nL Z+50 R0 FMAX M3\n"
         "CYCL DEF 200 DRILLING ~\n Q200=2 ;SET-UP CLEARANCE ~\n Q201=-5 ;DEPTH ~\n Q206=150 ;FEED ~\n"
         " Q202=5 ;PLUNGING DEPTH ~\n Q210=0 ;DWELL TOP ~\n Q203=+0 ;SURFACE ~\n Q204=20 ;2ND SET-UP ~\n"
         " Q211=0 ;DWELL BOTTOM\n")


def holes(prog) -> list[list[float]]:
    """The bottoms of the drilled holes, in order."""
    return [np.round(b.target, 4).tolist() for b in prog.blocks if b.kind == "line"]


def test_pattern_def_row_is_num_positions_d_apart_along_rot():
    # TNC 640 cycle programming manual, "PATTERN DEF", "Defining a single row": from the starting point X/Y,
    # D apart, NUM positions, the row turned ROT about its start; vcnc refused every form but POS
    prog = checked(DRILL + "PATTERN DEF ~\n ROW1 (X+10 Y+20 D+10 NUM3 ROT+90 Z+0)\nCYCL CALL PAT FMAX")
    assert holes(prog) == [[10.0, 20.0, -5.0], [10.0, 30.0, -5.0], [10.0, 40.0, -5.0]]


def test_pattern_def_circ_shares_the_full_turn_from_start():
    # "Defining a full circle": NUM positions on the circle of diameter D about X/Y, the first at START
    prog = checked(DRILL + "PATTERN DEF ~\n CIRC1 (X+50 Y+50 D40 START+90 NUM4 Z-2)\nCYCL CALL PAT FMAX")
    assert holes(prog) == [[50.0, 70.0, -7.0], [30.0, 50.0, -7.0], [50.0, 30.0, -7.0], [70.0, 50.0, -7.0]]


def test_pattern_def_pitchcirc_steps_by_step_or_to_end_after_a_pos():
    # "Defining a pitch circle": STEP apart (negative: clockwise), or the end angle END; forms run in the order
    # written, a POS first
    prog = checked(DRILL + "PATTERN DEF ~\n POS1 (X+0 Y+0 Z+0) ~\n PITCHCIRC1 (X+0 Y+0 D20 START+0 STEP-90 NUM3 Z+0)"
                   "\nCYCL CALL PAT FMAX")
    assert holes(prog) == [[0.0, 0.0, -5.0], [10.0, 0.0, -5.0], [0.0, -10.0, -5.0], [-10.0, 0.0, -5.0]]
    prog = checked(DRILL + "PATTERN DEF ~\n PITCHCIRC1 (X+0 Y+0 D20 START+0 END+180 NUM3 Z+0)\nCYCL CALL PAT FMAX")
    assert holes(prog) == [[10.0, 0.0, -5.0], [0.0, 10.0, -5.0], [-10.0, 0.0, -5.0]]


@pytest.mark.parametrize(("form", "message"), [
    ("SQUARE1 (X+0 Y+0 D+8)", "pattern 'SQUARE1' is not supported"),  # PAT1 and FRAME1 run: test_heidenhain_sl35
    ("ROW1 (X+0 Y+0 NUM5 Z+0)", "PATTERN DEF ROW without D"),
    ("CIRC1 (X+0 Y+0 D20 NUM0 Z+0)", "PATTERN DEF CIRC with NUM0"),
    ("PITCHCIRC1 (X+0 Y+0 D20 START+0 NUM3)", "PATTERN DEF PITCHCIRC without STEP or END"),
    ("ROW1 (X+0 Y+0 D5 NUM2 AN+30)", "word 'AN\\+30' in PATTERN DEF ROW"),
])
def test_pattern_def_forms_not_run_say_which(form, message):
    with pytest.raises(GCodeError, match=message):
        program(DRILL + "PATTERN DEF ~\n " + form + "\nCYCL CALL PAT FMAX")


POCKET = ("TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+10 Y+20 Z+15 R0 FMAX\nCYCL DEF {n} X ~\n Q215=0 ~\n"
          " Q218=30 ~\n Q219={w} ~\n Q220=2 ~\n Q368=0 ~\n Q224={a} ~\n Q374={a} ~\n Q367={pos} ~\n Q207=500 ~\n"
          " Q351=+1 ~\n Q201=-2 ~\n Q202=2 ~\n Q369=0 ~\n Q206=150 ~\n Q338=0 ~\n Q200=2 ~\n Q203=+0 ~\n Q204=20 ~\n"
          " Q370=1 ~\n Q366=0 ~\n Q385=400 ~\n Q424=36 ~\n Q425=22\nCYCL CALL")


def centre_move(prog) -> list[float]:
    """Where the cycle's first plane move goes (over the shape's centre)."""
    first = [b for b in prog.blocks if b.line > 3 and b.kind == "rapid" and b.target[2] == b.start[2]]
    return np.round(first[0].target, 6).tolist()


@pytest.mark.parametrize(("number", "width", "angle", "position", "centre"), [
    (251, 16, 0, 1, [25.0, 28.0, 15.0]),  # the tool at the lower left corner: the centre half the sides up right
    (251, 16, 90, 3, [18.0, 5.0, 15.0]),  # the upper right corner, the pocket turned 90 deg about the tool
    (256, 16, 0, 2, [-5.0, 28.0, 15.0]),  # the stud's lower right corner
    (253, 10, 0, 1, [25.0, 20.0, 15.0]),  # the slot's left end: the centre half the length on
    (253, 10, 0, 3, [0.0, 20.0, 15.0]),  # the centre of its right circle: (30 - 10) / 2 back
])
def test_q367_places_the_pocket_slot_or_stud_beside_the_tool(number, width, angle, position, centre):
    # TNC 640 cycle programming manual, Q367 "Position of pocket / stud / slot": the tool's position at the call
    # is a corner or an end of the shape, not its centre; vcnc refused every Q367 but 0
    prog = checked(POCKET.format(n=number, w=width, a=angle, pos=position))
    assert centre_move(prog) == pytest.approx(centre, abs=1e-6)
    if number == 251:  # the pocket's straight cuts lie symmetric about its centre
        cut = np.array([b.target[:2] for b in prog.blocks if b.kind == "line" and b.line > 3])
        assert (cut.min(axis=0) + cut.max(axis=0)) / 2 == pytest.approx(centre[:2], abs=1e-6)


def test_q367_of_cycle_254_stays_an_error():
    body = POCKET.format(n=254, w=10, a=0, pos=1).replace("CYCL DEF 254 X ~\n", "CYCL DEF 254 X ~\n Q375=60 ~\n"
                                                          " Q216=+0 ~\n Q217=+0 ~\n Q376=+0 ~\n Q248=+90 ~\n")
    with pytest.raises(GCodeError, match="cycle 254: Q367=1"):
        program(body)


def test_contour_formula_file_is_named_when_refused():
    # the TNC 640 SL cycles' contour formula file (SEL CONTOUR, DECLARE CONTOUR, QC1 = ..) is refused naming the
    # function and the simple contour formula vcnc runs instead (CONTOUR DEF itself runs since session 35:
    # test_heidenhain_sl35)
    with pytest.raises(GCodeError, match="SEL CONTOUR .* CONTOUR DEF P1 = LBL 1"):
        program('SEL CONTOUR "MODEL"\nM30')
