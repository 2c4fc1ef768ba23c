"""Heidenhain programs as they are found in the wild (hyperMILL's DMU posts, Fusion 360's TNC post, shop
programs): the forms the reader refused before, each as a hand-written program with end points worked
out by hand and checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})
ROTARY = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, extra_axes=("a", "c"))


def run(body: str, context: MachineContext = CTX, *, head: str = "0 BEGIN PGM T MM\n"):
    text = head + body + "\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    assert match.exact == len(prog.blocks)
    return prog


def ends(prog):
    return [np.round(b.target, 9).tolist() for b in prog.blocks]


def test_a_comment_wrapped_over_lines_ending_in_tilde_stays_a_comment():
    # as a shop's face-milling program saves a long comment; the cycle's parameter lines still continue the block
    prog = run("1 ;This program is free software: you can redistribute it and/or modify it~\n"
               " under the terms of the GNU General Public License, either version 3 of the~\n"
               " License, or any later version.\n"
               "2 Q1 = 4 ;a short one~\n still comment\n"
               "3 CYCL DEF 200 DRILLING ~\n  Q200=+2 ;SET-UP CLEARANCE~\n  Q201=-Q1 ;DEPTH ~\n  Q206=+100 ;FEED~\n"
               "  Q202=+4 ~\n  Q210=+0 ~\n  Q203=+0 ~\n  Q204=+5 ~\n  Q211=+0\n"
               "4 L X+5 Y+0 Z+10 R0 FMAX M99")
    assert ends(prog) == [[5, 0, 10], [5, 0, 2], [5, 0, -4], [5, 0, 2], [5, 0, 5]]


def test_the_feed_of_tool_call_is_the_feed_of_the_following_moves():
    # "TOOL CALL 22 Z S6000 F2000" and then "L Z+Q22" without F (a shop program): the feed is 2000 mm/min
    prog = run("TOOL CALL 1 Z S6000 F2000\nL X+0 Y+0 Z+5 R0 FMAX\nL Z-3\nL X+20 F500\nTOOL CALL 1 Z F800\nL Y+10")
    assert [b.kind for b in prog.blocks] == ["rapid", "line", "line", "line"]
    assert [round(b.feed * 60, 9) for b in prog.blocks[1:]] == [2000, 500, 800]
    assert ends(prog) == [[0, 0, 15], [0, 0, 7], [20, 0, 7], [20, 10, 7]]


def test_preassigned_tool_parameters_q108_q114_after_tool_call():
    # TNC 640 "Preassigned Q parameters": Q108 the active radius (table + DR), Q114 the active length (+ DL)
    prog = run("TOOL CALL 1 Z S1000 DR+0.5 DL-1\nL X+Q108 Y+Q114 Z+Q109 R0 FMAX\nQ2 = Q108 * 2\nL X+Q2 FMAX")
    assert ends(prog) == [[3.5, 9, 2 + 9], [7, 9, 11]]
    inch = run("TOOL CALL 1 Z\nL X+Q108 Y+Q113 FMAX", head="0 BEGIN PGM T INCH\n")
    assert ends(inch)[0][:2] == pytest.approx([3.0, 25.4])


def test_cycle_392_atc_of_dmg_machines_moves_nothing():
    prog = run("CYCL DEF 392 ATC~\n   Q240=0 ;TUNING MODE~\n   Q241=1 ;WEIGHT MODE\nL X+1 Y+2 Z+3 R0 FMAX\n"
               "L X+Q241 FMAX")
    assert ends(prog) == [[1, 2, 3], [1, 2, 3]]
    assert any(n.startswith("CYCL DEF 392: ATC") for n in prog.notes)


def test_rotary_axes_in_l_blocks_on_a_machine_that_has_them():
    # hyperMILL's 3+2 posts: "L A0 R0 FMAX", "L A+Q120 C+Q122 R0 FMAX M126", "L A0 C0 R0 FMAX"
    prog = run("L X+10 Y+0 Z+50 R0 FMAX\nL A+90 C+45 R0 FMAX\nL X+20 IC-15 F100\nL A0 C0 R0 FMAX", ROTARY)
    assert ends(prog) == [[10, 0, 50], [10, 0, 50], [20, 0, 50], [20, 0, 50]]
    assert [b.extra_target[[0, 2]].tolist() for b in prog.blocks] == [[0, 0], [90, 45], [90, 30], [0, 0]]
    assert prog.blocks[2].kind == "line" and prog.blocks[1].kind == "rapid"


def test_rotary_words_on_a_three_axis_machine():
    prog = run("L X+1 Y+0 Z+0 R0 FMAX\nL A0 C0 R0 FMAX\nL X+2 FMAX")
    assert ends(prog) == [[1, 0, 0], [2, 0, 0]]
    assert any("no A axis" in n for n in prog.notes)
    with pytest.raises(GCodeError, match="axis 'A' is not an axis of this machine"):
        parse_heidenhain("L X+1 Y+0 Z+0 R0 FMAX\nL A+30 FMAX\n", context=CTX)


def test_a_program_name_with_blanks():
    prog = run("L X+1 Y+0 Z+0 R0 FMAX", head="0 BEGIN PGM CHANFRO EXT RETO MM\n")
    assert prog.name == "CHANFRO EXT RETO"


def test_circles_about_a_cc_that_names_the_tool_axis_run_in_that_plane():
    # Fusion 360's ramp-in: "CC Y-31.6 Z-1.6" / "CP IPA+90 DR+": the YZ plane (reference axis Y, DR+ from Y to Z);
    # from (0, -2, 0) about (0, 0, 0) a quarter turn down to (0, 0, -2), then on along +Y
    prog = run("L X+0 Y-2 Z+0 R0 FMAX\nCC Y+0 Z+0\nCP IPA+90 DR+ F300\nL Y+5\n"
               # the ZX plane (reference axis Z, DR+ from Z to X): from (0, 5, -2) about (0, 5, -4) to (2, 5, -4)
               "CC X+0 Z-4\nCP IPA+90 DR+\n"
               # C to an end point in ZX, clockwise: back over the top to (-2, 5, -4)
               "C X-2 Z-4 DR-\n"
               # a CC in the working plane again: the arc is in XY, from (-2, 5) a quarter turn to (0, 3)
               "CC X+0 Y+5\nCP IPA+90 DR+")
    assert ends(prog) == [[0, -2, 0], [0, 0, -2], [0, 5, -2], [2, 5, -4], [-2, 5, -4], [0, 3, -4]]
    arcs = [b.segment for b in prog.blocks if b.kind == "arc"]
    assert [a.plane for a in arcs] == [0, 1, 1, 2]
    assert [a.ccw for a in arcs] == [True, True, False, True]
    assert np.allclose(arcs[0].center, [0, 0, 0]) and np.allclose(arcs[2].center, [0, 5, -4])
    assert math.isclose(arcs[2].length, math.pi * 2)
    assert np.allclose(arcs[2].point_at(math.pi), [0, 5, -2])  # over the top: Z+ side of the centre


def test_a_circle_outside_the_working_plane_under_radius_compensation_is_an_error():
    with pytest.raises(GCodeError, match="not in the working plane"):
        parse_heidenhain("TOOL CALL 1 Z\nL X+0 Y+0 Z+0 RL F100\nCC X+0 Z-4\n", context=CTX)


def test_ln_lines_with_3d_compensation_move_by_the_delta_radius_along_the_normal():
    # iTNC 530 manual: "the TNC displaces the tool in the direction of the surface-normal vectors by the sum of
    # the delta values"; CAM posts (NX, hyperMILL, Fusion 360 with 3-D compensation) write LN blocks
    prog = run("TOOL CALL 1 Z S1000 DR-0.5\nL X+0 Y+0 Z+10 R0 FMAX\n"
               "LN X+10 Y+0 Z+0 NX+0 NY+0 NZ+1 F500\nLN X+20 Y+5 Z-1 NX+3 NY+0 NZ+4 TX+0 TY+0 TZ+1\n"
               "TOOL CALL 1 Z\nLN X+30 Y+5 Z-1 NX+1 NY+1 NZ+1 FMAX")
    assert np.allclose(ends(prog), [[0, 0, 20], [10, 0, 9.5], [20 - 0.3, 5, 9 - 0.4], [30, 5, 9]])  # tool length 10
    assert [b.kind for b in prog.blocks] == ["rapid", "line", "line", "rapid"]
    assert any("TX/TY/TZ" in n for n in prog.notes)
    with pytest.raises(GCodeError, match="LN without a surface-normal vector"):
        parse_heidenhain("L X+0 Y+0 Z+0 R0 F100\nLN X+1 Y+0 Z+0 NX+0 NY+0\n", context=CTX)


def test_decimal_commas_as_tncs_set_to_the_comma_save_programs():
    """``X+50,022``, ``T0,01`` and ``Q2 = 1,5 * 2`` (HEIDENHAIN's demonstration programs 668/700/7025, the
    Czech shop program Krivka): the comma between two digits is the decimal point."""
    prog = run("1 TOOL CALL 1 Z S900\n2 CYCL DEF 32.0 TOLERANCE\n3 CYCL DEF 32.1 T0,01\n"
               "4 L X+50,022 Y-1,5 Z+5 R0 FMAX\n5 Q2 = 1,5 * 2\n6 L IX+Q2 Z-0,25 F300\n"
               "7 FN 1: Q3 = +0,5 + +Q2\n8 L Y+Q3 F1000,000\n")
    assert ends(prog) == [[50.022, -1.5, 15.0], [53.022, -1.5, 9.75], [53.022, 3.5, 9.75]]
    assert prog.blocks[1].feed == pytest.approx(300 / 60)
    assert prog.blocks[2].feed == pytest.approx(1000 / 60)


def test_a_polar_line_about_a_pole_that_names_the_tool_axis_runs_in_that_plane():
    """HEIDENHAIN's demonstration program 7025: ``CC Z.. X..`` then ``LP PR.. PA-90`` and ``CP IPA..``: the
    polar line and arc run in ZX, the angle counted from +Z toward +X."""
    prog = run("1 TOOL CALL 1 Z S900\n2 L X+75 Y+50 Z+20 R0 FMAX\n3 CC Z+0 X+75\n4 LP PR+20 PA-90 R0 F300\n"
               "5 CP IPA+90 DR+\n6 LP IPR-10 IPA+45\n7 CC X+0 Y+0\n8 LP PR+10 PA+90 Z+5 FMAX\n")
    s = 10 * math.sqrt(0.5)
    assert ends(prog)[:3] == [[75.0, 50.0, 30.0], [55.0, 50.0, 10.0], [75.0, 50.0, 30.0]]
    assert ends(prog)[3] == pytest.approx([75.0 + s, 50.0, 10.0 + s])
    assert ends(prog)[4] == pytest.approx([0.0, 10.0, 15.0])


def test_a_polar_line_in_another_plane_under_a_rotation_runs_and_an_arc_there_is_an_error():
    # the polar point about the pole (Z 0, X 0) in program coordinates, then turned by ROT+30 as any program
    # point: PA+90 from +Z is X 5 in the program, (5 cos 30, 5 sin 30) on the machine, Z 0 + the tool length 10
    # (the TNC 640 manual's Q parameter example "Sphere" moves so; test_heidenhain_manual_examples2 has its form)
    prog = run("1 TOOL CALL 1 Z\n2 L X+0 Y+0 Z+0 R0 F100\n3 CC Z+0 X+0\n4 CYCL DEF 10.0 ROTATION\n"
               "5 CYCL DEF 10.1 ROT+30\n6 LP PR+5 PA+90")
    assert ends(prog)[-1] == pytest.approx([5 * math.cos(math.radians(30)), 2.5, 10.0])
    with pytest.raises(GCodeError, match="CP about a CC outside the working plane under a coordinate transformation"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z\n2 L X+0 Y+0 Z+0 R0 F100\n3 CC Z+0 X+0\n"
                         "4 CYCL DEF 10.0 ROTATION\n5 CYCL DEF 10.1 ROT+30\n6 LP PR+5 PA+0\n7 CP IPA+90 DR+\n"
                         "8 END PGM T MM\n", source="t.h", context=CTX)


def test_a_section_repeat_counted_by_a_q_parameter():
    """``CALL LBL 1 REPQ13`` (HEIDENHAIN's demonstration program 7025): the count is the Q parameter's value."""
    prog = run("1 TOOL CALL 1 Z\n2 L X+0 Y+0 Z+0 R0 F100\n3 Q5 = 2\n4 LBL 1\n5 L IX+1\n6 CALL LBL 1 REPQ5\n")
    assert ends(prog) == [[0.0, 0.0, 10.0], [1.0, 0.0, 10.0], [2.0, 0.0, 10.0], [3.0, 0.0, 10.0]]
    with pytest.raises(GCodeError, match="REP Q5 = 1.5 is not a whole number"):
        run("1 Q5 = 1.5\n2 LBL 1\n3 CALL LBL 1 REP Q5\n")


def test_tool_call_by_a_q_parameter_and_sysread_of_the_tool_data():
    """``TOOL CALL Q11 Z`` and ``FN 18: SYSREAD Q10 = ID50 NR2 IDXQ11`` (the German shop program "Gleichlaufnut"),
    ``ID20 NR1`` (the tool-check macros of a DMU 60 eVo): the tool number, the table's L and R (TOOL DEF first)."""
    prog = run("1 Q11 = 1\n2 TOOL DEF 2 L+20 R+4\n3 TOOL CALL Q11 Z S5000 F500\n"
               "4 FN 18: SYSREAD Q10 = ID50 NR2 IDXQ11\n5 FN 18: SYSREAD Q12 = ID50 NR1 IDX2\n"
               "6 FN 18: SYSREAD Q13 = ID20 NR1\n7 L X+Q10 Y+Q12 Z+Q13\n")
    assert ends(prog) == [[3.0, 20.0, 11.0]]  # R of tool 1 = 3, L of tool 2 = 20, tool 1 active (length 10)
    with pytest.raises(GCodeError, match="tool number Q11 = 2.5 is not a whole number"):
        run("1 Q11 = 2.5\n2 TOOL CALL Q11 Z\n")
    unknown = run("1 FN 18: SYSREAD Q10 = ID50 NR1 IDX7\n2 L X+0 Y+0 Z+Q10 FMAX\n")  # as TOOL CALL: 0, noted
    assert ends(unknown) == [[0.0, 0.0, 0.0]] and any("tool 7 is not in the tool table" in n for n in unknown.notes)
    with pytest.raises(GCodeError, match="FN 18 SYSREAD 'SYSREAD Q1 = ID50 NR36 IDX1' is not supported"):
        run("1 FN 18: SYSREAD Q1 = ID50 NR36 IDX1\n")


def test_inch_arcs_whose_four_decimal_end_points_miss_the_circle_by_their_rounding():
    """A CAM post's inch program (dominiczino/Heidenhain-Program-Manager, FrameOp1.H): start, end and centre each
    rounded to the 4 places of the TNC's input format miss the circle by up to 2 * sqrt(2) * 0.0001 in = 0.0072 mm."""
    inch = "0 BEGIN PGM T INCH\n"
    # from (1, 0) about (0, 0): start radius 1 in, end radius 1.0002 in (0.00508 mm off): runs, ends where written
    prog = run("1 L X+1 Y+0 Z+0 R0 F10\n2 CC X+0 Y+0\n3 C X+0 Y+1.0002 DR+", head=inch)
    assert np.allclose(prog.blocks[-1].target, [0.0, 1.0002 * 25.4, 0.0])
    assert prog.blocks[-1].kind == "arc"
    with pytest.raises(GCodeError, match="not on the circle"):  # 0.0003 in = 0.00762 mm > 0.00718 mm
        parse_heidenhain(inch + "1 L X+1 Y+0 Z+0 R0 F10\n2 CC X+0 Y+0\n3 C X+0 Y+1.0003 DR+\n", context=CTX)
    with pytest.raises(GCodeError, match="not on the circle"):  # the same 0.00508 mm in a mm program: 0.002 mm
        parse_heidenhain("1 L X+25.4 Y+0 Z+0 R0 F100\n2 CC X+0 Y+0\n3 C X+0 Y+25.40508 DR+\n", context=CTX)


def test_r_f_and_m_without_a_value_are_fields_left_empty():
    """As HEIDENHAIN's demonstration programs 668 and 700 (older TNCs) were saved: ``L X+32,000 Y+0,000 R F5000 M13``,
    ``L X+12,500 R F M``, ``CYCL CALL M``: no compensation change, the modal feed, no M function."""
    prog = run("1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+2 R0 FMAX\n3 L X+32,000 Y+0,000 Z+2,000 R F500 M13\n"
               "4 L X+12,500 R F M\n5 L Y+6,5 R F M\n6 L Z+50 R F3000 M")
    assert ends(prog) == [[0, 0, 12], [32, 0, 12], [12.5, 0, 12], [12.5, 6.5, 12], [12.5, 6.5, 60]]
    assert [round(b.feed * 60, 9) for b in prog.blocks[1:]] == [500, 500, 500, 3000]
    assert any(n.startswith("R, F or M without a value") for n in prog.notes)


def test_a_label_call_with_the_rep_count_left_empty_calls_the_section_once():
    """700.klartext: ``LBL 1 .. LBL 0``, a mirror image, then ``CALL LBL 1 REP``: the section once more."""
    prog = run("1 TOOL CALL 1 Z\n2 L X+0 Y+0 Z+0 R0 F100\n3 LBL 1\n4 L IX+1\n5 LBL 0\n6 CALL LBL 1 REP\n7 L IY+1\n")
    assert ends(prog) == [[0, 0, 10], [1, 0, 10], [2, 0, 10], [2, 1, 10]]
    assert any(n.startswith("CALL LBL n REP without a count") for n in prog.notes)


def test_tnc_text_without_begin_pgm_and_block_numbers_is_read_as_conversational():
    """An engraving generator's output (viktor-olah/CNC-Engraving-Heidenhain-.NETCORE): only L, CC and C blocks."""
    from interpolators import detect_dialect, parse_program

    text = "TOOL CALL 1 Z S1000 F600\nL X1.376 Y1.202 FMAX\nL Z-0.2 FAUTO\nCC X2.5 Y1.202\nC X3.624 DR+\n"
    assert detect_dialect(text) == "heidenhain"
    assert detect_dialect("L X1.376 Y1.202 FMAX\nL Z-0.2 FAUTO\n") == "heidenhain"
    assert detect_dialect("CC X2.5 Y1.75\nC X3.624 DR+\n") == "heidenhain"
    for iso in ("G1 X1 Y2\nL2\n", "C5 X1\n", "M3 S1000\nG0 X0\n", "(CC X2)\nG0 X1\n"):
        assert detect_dialect(iso) == "iso"
    prog = parse_program(text, context=CTX)
    # from (1.376, 1.202) about (2.5, 1.202): a half circle counter-clockwise to (3.624, 1.202), at Z -0.2 + 10
    assert ends(prog)[-1] == [3.624, 1.202, 9.8]
    assert round(prog.blocks[-1].feed * 60, 9) == 600
    match = match_blocks(heidenhain_reference(text, CTX), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None and match.exact == len(prog.blocks)


def test_sysread_of_r2_dl_dr_of_a_tool_reads_zero_with_a_note():
    """``FN 18: SYSREAD Q1603 = ID50 NR3 IDXQ1 ; R2`` .. ``NR5 ; DR`` (a shop's tool-copy macro, Stugo/Heidenhain):
    the machine context's tool table holds no R2, DL, DR: 0, noted; NR1 (L) still the table's length."""
    prog = run("1 Q1 = 1\n2 FN 18: SYSREAD Q3 = ID50 NR3 IDXQ1\n3 FN 18: SYSREAD Q4 = ID50 NR4 IDX1\n"
               "4 FN 18: SYSREAD Q5 = ID50 NR5 IDX1\n5 FN 18: SYSREAD Q6 = ID50 NR1 IDX1\n"
               "6 L X+Q3 Y+Q4 Z+Q5 R0 FMAX\n7 L X+Q6 FMAX\n")
    assert ends(prog) == [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]
    assert sum(n.startswith("FN 18 SYSREAD ID50 NR") for n in prog.notes) == 3


def test_syswrite_of_a_tools_length_and_radius_and_of_data_vcnc_does_not_hold():
    """``FN 17: SYSWRITE ID50 NR1 IDXQ8 = +0 ; L`` .. (a shop's tool-table reset macro; TNC 426/430 technical
    manual 7.3.3: ID50 NR1 length L, NR2 radius R of the tool IDX): the data TOOL CALL and FN 18 take from then on;
    DL/DR written 0 agree with vcnc's table; a name (text), PLC or datum-table data: noted, not written."""
    prog = run("1 Q8 = 1\n2 FN 17: SYSWRITE ID50 NR1 IDXQ8 = +25.5\n3 FN 17: SYSWRITE ID50 NR2 IDX1 = +Q8 + 1\n"
               "4 FN 17: SYSWRITE ID50 NR4 IDXQ8 = +0\n5 FN 17: SYSWRITE ID50 NR0 IDXQ8 = \"\"\n"
               "6 FN 17: SYSWRITE ID503 NR99 IDX1 = +0\n7 FN 18: SYSREAD Q2 = ID50 NR2 IDX1\n"
               "8 TOOL CALL 1 Z S1000\n9 L X+Q2 Y+0 Z+0 R0 FMAX\n10 FN 17: SYSWRITE ID50 NR1 IDX1 = +5\n"
               "11 L Z+1 FMAX\n12 TOOL CALL 1 Z\n13 L Z+1 FMAX\n")
    # table length 10 became 25.5, radius 3 became 2; the active tool's length changes at its next TOOL CALL
    assert ends(prog) == [[2.0, 0.0, 25.5], [2.0, 0.0, 26.5], [2.0, 0.0, 6.0]]
    assert sum(n.startswith("FN 17 SYSWRITE") for n in prog.notes) == 2
    with pytest.raises(GCodeError, match="FN 17 SYSWRITE ID50 NR4 IDX1 = 0.1: writing the tool's length oversize DL"):
        run("1 FN 17: SYSWRITE ID50 NR4 IDX1 = +0.1\n")
    with pytest.raises(GCodeError, match="writing the active tool .* is not supported"):
        run("1 FN 17: SYSWRITE ID20 NR1 = +3\n")
    with pytest.raises(GCodeError, match="FN 17 SYSWRITE ID50 NR1: no tool number"):
        run("1 FN 17: SYSWRITE ID50 NR1 = +3\n")
    with pytest.raises(GCodeError, match="malformed FN 17 SYSWRITE"):
        run("1 FN 17: SYSWRITE ID50 NR1 IDX1\n")
