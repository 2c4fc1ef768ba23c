"""Heidenhain conversational reader: hand-written programs per function (issue #19) with exact
expected end points, and the real programs of the corpus checked against a simple reference."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from interpolators import interpolate, load_program, parse_program
from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n"


def run(body: str, **kw):
    return parse_heidenhain(HEAD + body + "\nEND PGM T MM\n", source="t.h", **kw)


def ends(prog):
    return [b.target.tolist() for b in prog.blocks]


def test_comments_structure_and_stops():
    prog = run("; a comment\n1 BLK FORM 0.1 Z X+0 Y+0 Z-10\n* - Contour 1\n2 TOOL DEF 3 L+0 R+0\n"
               "3 TOOL CALL 3 Z S3000\n4 STOP\n5 M0\n6 M1\n7 M3 M8 M12\n8 L X+5 Y+2 R0 FMAX ;rapid\n9 M30")
    assert ends(prog) == [[5.0, 2.0, 0.0]]
    assert prog.blocks[0].kind == "rapid" and prog.name == "T"
    assert prog.notes == ("STOP: program stop (no motion)", "M0: program stop (no motion)",
                          "M1: program stop (no motion)", "M12 ignored (no motion)")


def test_tool_length_from_table_tool_def_and_dl():
    ctx = MachineContext(tools={5: Tool(number=5, length=100.0, radius=0.0)})
    prog = run("TOOL CALL 5 Z\nL Z+10 FMAX\nTOOL CALL 5 Z DL-0.5\nL Z+10 FMAX\nTOOL DEF 5 L+20 R+0\n"
               "TOOL CALL 5 Z\nL Z+10 FMAX", context=ctx)
    assert [b.target[2] for b in prog.blocks] == [110.0, 109.5, 30.0]


def test_m91_m92_m140_and_datum_shift():
    ctx = MachineContext(tools={1: Tool(number=1, length=50.0)}, home=(0, 0, 400),
                         work_offsets={"G54": (100, 0, 0)})
    prog = run("TOOL CALL 1 Z\nL X+0 Y+0 Z+5 FMAX\nL Z-10 FMAX M91\nL X+1 FMAX M92\n"
               "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+10\nCYCL DEF 7.2 Y+5\nL X+0 Y+0 FMAX\n"
               "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 IX+1\nL X+0 FMAX\nL M140 MB MAX\nL M140 MB+20", context=ctx)
    assert ends(prog) == [[100, 0, 55], [100, 0, -10], [1, 0, -10], [110, 5, -10], [111, 5, -10],
                          [111, 5, 400], [111, 5, 420]]


def test_m140_in_a_block_of_m_functions_retracts_as_in_a_line():
    # "7475 M140 MB MAX" alone, as a CAM post writes it between operations (TNC 640 user's manual, "Retraction in the
    # tool axis: M140", effective at the end of its block): up to the limit (home z 400 here), then MB 20 above it
    from tests.interpolators.reference_heidenhain import heidenhain_reference
    from tests.interpolators.reference_match import match_blocks, reader_rows
    from vcnc.commands.interpolate import blocks_table

    ctx = MachineContext(tools={1: Tool(number=1, length=0.0)}, home=(0, 0, 400))
    text = ("0 BEGIN PGM R MM\n1 TOOL CALL 1 Z\n2 L X+0 Y+0 Z-5 R0 FMAX\n3 M5 M140 MB MAX M9\n4 L X+10 FMAX\n"
            "5 M140 MB+20\n6 M140\n7 END PGM R MM\n")
    prog = parse_heidenhain(text, context=ctx)
    assert ends(prog) == [[0, 0, -5], [0, 0, 400], [10, 0, 400], [10, 0, 420]]
    assert [b.line for b in prog.blocks] == [3, 4, 5, 6]
    assert "M140 without MB: no retraction" in prog.notes
    text = text.replace("5 M140 MB+20\n", "")  # the reference reads MB MAX only
    assert match_blocks(heidenhain_reference(text, ctx), reader_rows(*blocks_table(parse_heidenhain(text, context=ctx)))
                        ).mismatch is None


def test_a_rotary_axis_alone_moves_in_degrees_per_minute_also_in_an_inch_program():
    # iTNC 530 user's manual 60642x-03, 12.5 "Miscellaneous functions for rotary axes", M116 "Standard behavior": "in
    # degrees/min (in mm programs and also in inch programs)"; with X moving, F is the path's (1/10 inch/min in INCH)
    ctx = MachineContext(extra_axes=("c",))
    for unit, path_feed in (("MM", 100 / 60), ("INCH", 100 * 2.54 / 60)):
        prog = parse_heidenhain(f"0 BEGIN PGM R {unit}\n1 TOOL CALL 1 Z\n2 L X+0 Y+0 Z+1 R0 FMAX\n3 L C+90 F3600\n"
                                f"4 L X+1 C+100 F100\n5 END PGM R {unit}\n", context=ctx)
        rotary, line = prog.blocks[1], prog.blocks[2]
        assert rotary.extra_target[2] == 90.0 and rotary.feed == pytest.approx(60.0)  # 3600 deg/min
        assert line.feed == pytest.approx(path_feed)


def test_q_parameter_arithmetic_fn0_to_fn13():
    prog = run("FN 0: Q1 = +6\nFN 1: Q2 = +Q1 + +4\nFN 2: Q3 = +Q2 - -2\nFN 3: Q4 = +Q3 * -Q1\nFN 4: Q5 = +Q4 DIV +8\n"
               "FN 5: Q6 = SQRT +Q4 * -1\nFN 8: Q7 = +3 LEN +4\nFN 13: Q8 = +0 ANG +2\nFN 6: Q9 = SIN +30\n"
               "L X+Q2 Y-Q5 Z+Q7 F100\nL X+Q8 Y+Q3 Z+Q9\nL X+(Q6*Q6) Y+0 Z+0")
    # Q2 = 10, Q3 = 12, Q4 = -72, Q5 = -9, Q7 = 5, Q8 = 90, Q9 = 0.5
    assert ends(prog)[:2] == [[10, 9, 5], [90, 12, pytest.approx(0.5)]]
    assert prog.blocks[2].target[0] == pytest.approx(72.0)  # Q6 = SQRT(-72 * -1), squared


def test_parameters_written_without_spaces_as_hypermill_posts_write_them():
    # hyperMILL's TNC post: "FN 0:Q2=105 ; Z FEED RATE", "CYCL DEF9 .0", and formulas "Q3=Q2+1" without blanks
    text = (HEAD + "FN 0:Q2=105 ; Z FEED RATE\nQ3=Q2+1\nL X+0 Y+0 Z+50 R0 F MAX\nCYCL DEF9 .0 VARAKOZASI IDO\n"
            "CYCL DEF9.1 V.IDO5\nL X+Q3 Y+0 Z+0 FQ2\nEND PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h")
    assert [b.kind for b in prog.blocks] == ["rapid", "dwell", "line"]
    assert prog.blocks[1].dwell == 5.0
    assert ends(prog)[2] == [106, 0, 0] and prog.blocks[2].feed * 60 == pytest.approx(105)
    match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch


def test_skippable_blocks_run_with_block_skip_off_and_are_noted():
    # "/" before the block number (hyperMILL: "/81 M30") or after it (the TNC's own form)
    text = HEAD + "L X+0 Y+0 Z+50 R0 FMAX\n3 /L X+10 F100\n/4 L X+20\n5 L X+30\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h")
    assert [e[0] for e in ends(prog)] == [0, 10, 20, 30]
    assert any("block skip" in n for n in prog.notes)
    match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch


def test_f_auto_is_the_feed_of_the_tool_call():
    text = (HEAD + "TOOL CALL 1 Z S1000 F300\nL X+0 Y+0 Z+50 R0 FMAX\nL Z+2 FAUTO\nL X+10 F100\nL X+20 F AUTO\n"
            "L X+30\nEND PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h")
    assert [round(b.feed * 60, 9) for b in prog.blocks[1:]] == [300, 100, 300, 300]
    match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    with pytest.raises(GCodeError, match="F AUTO without a feed in the TOOL CALL"):
        run("TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+2 R0 F AUTO")


def test_fu_feed_per_revolution_indexed_tools_and_fz_refused():
    # FU 0.1 mm/rev at S1000: 100 mm/min; TOOL CALL 12.1 (index 1 of tool 12) takes tool 12's data
    ctx = MachineContext(tools={12: Tool(number=12, length=40.0, radius=0.0)})
    text = HEAD + "TOOL CALL 12.1 Z S1000\nL X+0 Y+0 Z+50 R0 FMAX\nL X+10 FU0.1\nL X+20\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h", context=ctx)
    assert [round(b.feed * 60, 9) for b in prog.blocks[1:]] == [100, 100]
    assert ends(prog)[0] == [0, 0, 90] and any("indexed tool 12.1" in n for n in prog.notes)
    match = match_blocks(heidenhain_reference(text, ctx), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    with pytest.raises(GCodeError, match="FZ .feed per tooth. needs the tool's number of teeth"):
        run("TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+2 R0 FZ0.05")


def test_formulas_precedence_and_functions():
    prog = run("Q1 = 2 + 3 * 4 ^ 2\nQ2 = (2 + 3) * 4\nQ3 = INT Q2 / 3\nQ4 = SQ 3 + SQRT(16) + ABS -2\n"
               "Q5 = FRAC 2.75 + SGN -4 + NEG 1 + COS(60) + ATAN(1) + LOG(100) + LN(EXP(1)) + PI\n"
               "QL6 = Q1 - Q2\nL X+Q1 Y+Q2 Z+Q3 F100\nL X+Q4 Y+Q5 Z+QL6")
    b = prog.blocks
    assert b[0].target.tolist() == [50.0, 20.0, pytest.approx(6.0 + 2 / 3)]
    assert b[1].target.tolist() == pytest.approx([15.0, 0.75 - 1 - 1 + 0.5 + 45 + 2 + 1 + math.pi, 30.0])


def test_a_formula_run_in_a_loop_reads_the_parameters_each_time_and_fails_as_written():
    """A formula is parsed once and then only computed (the loop of the Czech shop program Krivka): each pass
    reads the current Q values; a division by zero on a later pass and a malformed formula fail as before."""
    prog = run("Q1 = 0\nLBL 1\nQ1 = Q1 + 1\nQ2 = Q1 * Q1 - 2 ^ Q1 / (Q1 + 1)\nL X+Q2 Y+Q1 Z+0 F100\n"
               "FN 12: IF +Q1 LT +4 GOTO LBL 1")
    assert [b.target[0] for b in prog.blocks] == pytest.approx([q * q - 2 ** q / (q + 1) for q in (1, 2, 3, 4)])
    with pytest.raises(GCodeError, match=r"bad formula '10 / \(Q1 - 2\)': division by zero"):
        run("Q1 = 0\nLBL 1\nQ1 = Q1 + 1\nQ2 = 10 / (Q1 - 2)\nFN 12: IF +Q1 LT +4 GOTO LBL 1")
    for _ in range(2):  # the second time from the cache of formulas: the same message
        with pytest.raises(GCodeError, match=r"bad formula '\(Q1 \+ 2': missing '\)'"):
            run("Q2 = (Q1 + 2")
        with pytest.raises(GCodeError, match=r"unknown function 'FOO'"):
            run("Q2 = FOO 3")


def test_q_parameters_in_feeds_and_inch_programs():
    prog = run("FN 0: Q58 = +1200\nL X+1 FQ58\nL X-Q58 F(Q58/2)")
    assert [b.feed for b in prog.blocks] == [20.0, 10.0] and prog.blocks[1].target[0] == -1200
    inch = parse_heidenhain("0 BEGIN PGM I INCH\n1 L X+1 F10\n2 CC X+0 Y+0\n3 C X+0 Y+1 DR+\n4 END PGM I INCH\n")
    assert inch.blocks[0].target[0] == pytest.approx(25.4) and inch.blocks[0].feed == pytest.approx(10 * 2.54 / 60)
    assert inch.blocks[1].target.tolist() == pytest.approx([0, 25.4, 0])


def test_conditional_jumps_count_a_loop():
    prog = run("Q1 = 0\nLBL 1\nQ1 = Q1 + 1\nL X+Q1 F100\nFN 12: IF +Q1 LT +4 GOTO LBL 1\n"
               "FN 9: IF +Q1 EQU +4 GOTO LBL \"DONE\"\nL X+99\nLBL \"DONE\"\nL Y+1")
    assert [b.target[0] for b in prog.blocks] == [1, 2, 3, 4, 4]
    assert prog.blocks[-1].target[1] == 1


def test_endless_jump_is_an_error():
    with pytest.raises(GCodeError, match="does not end: more than 1000 blocks"):
        run("LBL 1\nL IX+1 F100\nFN 9: IF +0 EQU +0 GOTO LBL 1", max_executed=1000)


def test_section_repeat_and_subprograms_after_m30():
    prog = run("L X+0 Y+0 F100\nLBL 1\nL IX+1\nCALL LBL 1 REP 2/2\nCALL LBL 5\nCALL LBL \"SQ\" REP 1\nL Y+9\nM30\n"
               "LBL 5\nL IY+10\nCALL LBL \"SQ\"\nLBL 0\nLBL \"SQ\"\nL IX+100\nLBL 0")
    x = [b.target[0] for b in prog.blocks]
    y = [b.target[1] for b in prog.blocks]
    # section LBL 1 runs 3 times; LBL 5 calls SQ once; SQ called with REP 1 runs twice
    assert x == [0, 1, 2, 3, 3, 103, 203, 303, 303]
    assert y == [0, 0, 0, 0, 10, 10, 10, 10, 9]


def test_polar_lines_and_helix():
    prog = run("CC X+10 Y+0\nL X+20 Y+0 Z+0 F100\nLP PR+10 PA+90\nLP IPA+90\nCP IPA+450 IZ-5 DR+\nCP PA+0 DR-")
    b = prog.blocks
    assert b[1].target.tolist() == pytest.approx([10, 10, 0])
    assert b[2].target.tolist() == pytest.approx([0, 0, 0])
    helix = b[3].segment
    assert helix.sweep == pytest.approx(math.radians(450)) and helix.helix == pytest.approx(-5)
    assert b[3].target.tolist() == pytest.approx([10, -10, -5])
    # from -90 degrees clockwise to PA 0: three quarters of a turn
    assert b[4].segment.sweep == pytest.approx(-1.5 * math.pi) and b[4].target.tolist() == pytest.approx([20, 0, -5])


def test_whole_turns_helix_and_c_full_circle():
    prog = run("CC X+0 Y+0\nL X+5 Y+0 Z+0 F100\nCP IPA+720 Z-2 DR+\nC DR-")
    assert prog.blocks[1].segment.sweep == pytest.approx(4 * math.pi)
    assert prog.blocks[1].target.tolist() == pytest.approx([5, 0, -2])
    assert prog.blocks[2].segment.sweep == pytest.approx(-2 * math.pi)


def test_ct_tangential_arc():
    prog = run("L X+0 Y+0 F100\nL X+10\nCT X+20 Y+10")
    arc = prog.blocks[2].segment
    assert arc.center.tolist() == pytest.approx([10, 10, 0]) and arc.sweep == pytest.approx(math.pi / 2)
    assert prog.blocks[2].target.tolist() == [20, 10, 0]


def test_rnd_and_chf_between_lines():
    prog = run("L X+0 Y+0 F100\nL X+10\nRND R2 F50\nL Y+10\nCHF 3\nL X+0")
    b = prog.blocks
    assert [x.kind for x in b] == ["line", "line", "arc", "line", "line", "line"]
    assert b[1].target.tolist() == pytest.approx([8, 0, 0]) and b[2].target.tolist() == pytest.approx([10, 2, 0])
    assert b[2].segment.radius == pytest.approx(2) and b[2].feed == pytest.approx(50 / 60)
    assert b[3].target.tolist() == pytest.approx([10, 7, 0]) and b[4].target.tolist() == pytest.approx([7, 10, 0])
    assert b[5].target.tolist() == [0, 10, 0] and b[5].feed == pytest.approx(100 / 60)



def _tangent_to(seg, point, centre, r):
    """The rounding circle (centre, r) touches ``seg`` at ``point``: on both, normal to seg there."""
    assert np.hypot(*(point[:2] - centre[:2])) == pytest.approx(r, abs=1e-9)
    if hasattr(seg, "center"):  # an arc: the two centres and the point are collinear
        a, b = point[:2] - seg.center[:2], centre[:2] - seg.center[:2]
        assert abs(a[0] * b[1] - a[1] * b[0]) == pytest.approx(0, abs=1e-9)
    else:
        d = (seg.end - seg.start)[:2]
        assert float(d @ (centre[:2] - point[:2])) == pytest.approx(0, abs=1e-9)


def test_rnd_next_to_arcs():
    """TNC 620 manual, "Rounding corners RND": tangential to the preceding and the following
    element, lines or arcs; here a line into an arc and an arc into a line."""
    prog = run("L X+0 Y+0 F100\nL X+10\nRND R2\nCC X+20 Y+0\nC X+30 Y+0 DR+\nRND R1\nL X+40 Y+10")
    b = prog.blocks
    assert [x.kind for x in b] == ["line", "line", "arc", "arc", "arc", "line"]
    fillet, big, second = b[2].segment, b[3].segment, b[4].segment
    assert fillet.radius == pytest.approx(2) and not fillet.ccw  # the corner turns right
    _tangent_to(b[1].segment, b[1].target, fillet.center, 2)
    _tangent_to(big, big.start, fillet.center, 2)
    assert np.hypot(*(fillet.center[:2] - np.array([20, 0]))) == pytest.approx(12)  # outside the arc: R + r
    assert second.radius == pytest.approx(1) and not second.ccw  # north, then north-east: a right turn
    _tangent_to(big, big.end, second.center, 1)
    _tangent_to(b[5].segment, b[5].start, second.center, 1)
    assert b[5].target.tolist() == [40, 10, 0] and big.center.tolist() == [20, 0, 0]
    with pytest.raises(GCodeError, match="CHF before an arc: a chamfer joins two straight lines"):
        run("L X+0 Y+0 F100\nL X+10\nCHF 1\nCC X+20 Y+0\nC X+30 Y+0 DR+")
    with pytest.raises(GCodeError, match="meet tangentially"):
        run("L X+0 Y+0 F100\nL X+10\nRND R1\nCC X+10 Y+10\nC X+20 Y+10 DR+")

def test_appr_lt_and_dep_lt():
    # TNC 640 manual p. 213: PS -> PH (last feed), then the depth, then PH -> PA tangential to the
    # first contour element, PH at LEN before PA; DEP LT: LEN along the last element's tangent
    prog = run("L X+40 Y+10 Z+0 R0 F300\nAPPR LT X+20 Y+20 Z-10 LEN15 RR F100\nL X+35 Y+35\nDEP LT LEN5 R0")
    h = 15 / math.sqrt(2)
    d = 5 / math.sqrt(2)
    expected = [[40, 10, 0], [20 - h, 20 - h, 0], [20 - h, 20 - h, -10], [20, 20, -10], [35, 35, -10],
                [35 + d, 35 + d, -10]]
    assert np.allclose(ends(prog), expected, rtol=0, atol=1e-12)
    assert [b.feed * 60 for b in prog.blocks[1:]] == pytest.approx([300, 100, 100, 100, 100])
    with pytest.raises(GCodeError, match="DEP PLT is not supported"):
        run("L X+0 F100\nL X+1\nDEP PLT LEN2")
    with pytest.raises(GCodeError, match="APPR LN without radius compensation"):
        run("L X+0 F100\nAPPR LN X+1 Y+1 LEN2 R0\nL X+5")


def test_appr_ln_ct_and_dep_ln_ct():
    # TNC7 manual "APPR LN": PH at LEN from PA, perpendicular to the first element, on the tool's side
    # (RR: right of the direction +X, so below); "APPR CT": RR with R+ turns clockwise, the arc ending
    # tangentially at PA; CCA 90 from PH; DEP LN / DEP CT the same from the last contour point
    prog = run(PROGRAM_LN_CT)
    assert np.allclose(ends(prog)[1:5], [[0, -10, 5], [0, -10, -1], [0, 0, -1], [10, 0, -1]], atol=1e-12)
    assert np.allclose(ends(prog)[5], [10, -4, -1])  # DEP LN: 4 on the right of +X
    b = prog.blocks
    # APPR CT: clockwise arc of radius 5 centred at (0, -5): 90 degrees back from PA = (0, 0) is (-5, -5)
    assert np.allclose(ends(prog)[7:10], [[-5, -5, 5], [-5, -5, -1], [0, 0, -1]], atol=1e-12)
    assert b[9].kind == "arc" and not b[9].segment.ccw and np.allclose(b[9].segment.center[:2], [0, -5])
    # DEP CT with RR and R-: counter-clockwise, centre (10, 2), half a turn to (10, 4)
    assert b[11].segment.ccw and np.allclose(ends(prog)[11], [10, 4, -1]) and np.allclose(
        b[11].segment.center[:2], [10, 2])
    with_radius = "\n".join(ln for ln in PROGRAM_LN_CT.split("\n") if not ln.startswith("DEP CT")) + "\nDEP LN LEN1 R0"
    for tool, body in (("R+0", PROGRAM_LN_CT), ("R+1", with_radius)):
        text = HEAD + f"TOOL DEF 1 L+0 {tool}\nTOOL CALL 1 Z\n" + body + "\nEND PGM T MM\n"
        prog = parse_heidenhain(text, source="t.h")
        match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(prog)[1])
        assert match.mismatch is None, match.mismatch  # against the reference, also with a tool radius
    polar = run("CC X+0 Y+0\nL X-20 Y-20 Z+5 R0 F300\nAPPR PLN PR+10 PA+90 Z-1 LEN5 RR F100\nL X+0 Y+20")
    assert np.allclose(ends(polar)[1:4], [[5, 10, 5], [5, 10, -1], [0, 10, -1]], atol=1e-12)  # PA (0, 10)


def test_dep_ct_under_radius_compensation_runs_the_offset_arc():
    # DEP CT .. R0 with RR and a tool of radius 1: R is the radius of the tool's path (iTNC 530 manual, APPR
    # LCT: "the radius then suffices to completely define the tool path"); R-2 turns counter-clockwise, away
    # from the tool (right of the travel +X): the tool centre leaves (10, -1) on radius 2 about (10, 1) to
    # (10, 3) (the contour arc: radius 3 about the same centre); the next R0 block leaves from there
    body = ("TOOL DEF 1 L+0 R+1\nTOOL CALL 1 Z\nL X-20 Y-20 Z+5 R0 F300\nAPPR LN X+0 Y+0 Z-1 LEN10 RR F100\n"
            "L X+10 Y+0\nDEP CT CCA180 R-2 R0\nL Z+50 FMAX")
    prog = run(body)
    arc = prog.blocks[-2]
    assert arc.kind == "arc" and arc.segment.ccw and np.allclose(arc.segment.center[:2], [10, 1])
    assert np.allclose(arc.start[:2], [10, -1]) and np.allclose(arc.target, [10, 3, -1])
    assert np.allclose(prog.blocks[-1].target, [10, 3, 50])
    # RL with R+2 on the same contour: the arc turns left, to the tool's side: from (10, 1) on radius 2
    # about (10, 3) to (10, 5)
    left = run(body.replace("RR", "RL").replace("R-2", "R+2"))
    arc = left.blocks[-2]
    assert arc.segment.ccw and np.allclose(arc.start[:2], [10, 1]) and np.allclose(arc.target[:2], [10, 5])
    assert np.allclose(arc.segment.center[:2], [10, 3])
    for text in (body, body.replace("RR", "RL").replace("R-2", "R+2")):
        text = HEAD + text + "\nEND PGM T MM\n"
        match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(parse_heidenhain(text))[1])
        assert match.mismatch is None, match.mismatch


def test_appr_lct_and_dep_lct():
    # TNC7 manual "APPR LCT": a line from PS touching the arc of radius R that ends tangentially at PA
    # (RL: counter-clockwise, centre (0, 5)); "DEP LCT": the arc leaving PE, then the line to PN touching it
    prog = run("L X-5 Y+20 Z+5 R0 F300\nAPPR LCT X+0 Y+0 Z-1 R5 RL F100\nL X+10 Y+0\nDEP LCT X+15 Y+20 Z+5 R5 R0")
    assert np.allclose(ends(prog), [[-5, 20, 5], [-5, 5, 5], [-5, 5, -1], [0, 0, -1], [10, 0, -1], [15, 5, -1],
                                    [15, 20, -1], [15, 20, 5]], atol=1e-9)
    assert prog.blocks[3].segment.ccw and prog.blocks[5].segment.ccw
    text = (HEAD + "L X-5 Y+20 Z+5 R0 F300\nAPPR LCT X+0 Y+0 Z-1 R5 RL F100\nL X+10 Y+0\nDEP LCT X+15 Y+20 R5 R0\n"
            "END PGM T MM\n")
    match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(parse_heidenhain(text))[1])
    assert match.mismatch is None, match.mismatch


PROGRAM_LN_CT = ("L X-20 Y-20 Z+5 R0 F300\nAPPR LN X+0 Y+0 Z-1 LEN10 RR F100\nL X+10 Y+0\nDEP LN LEN4 R0\n"
                 "L X-20 Y-20 Z+5 FMAX\nAPPR CT X+0 Y+0 Z-1 CCA90 R+5 RR F100\nL X+10 Y+0\nDEP CT CCA180 R-2 R0")


def test_radius_compensation_words():
    prog = run("TOOL CALL 0 Z\nL X+0 Y+0 RL F100\nL X+10 R0")  # tool radius 0: the contour is the path
    assert ends(prog) == [[0, 0, 0], [10, 0, 0]]
    # a 20 mm square, tool radius 2: RL runs inside (intersections at the corners), RR outside
    # (an arc at each corner); the entry ends perpendicular to the first contour element (TNC)
    ctx = MachineContext(tools={2: Tool(number=2, radius=2.0)})
    square = "TOOL CALL 2 Z\nL X-10 Y-5 Z+0 R0 FMAX\nL X+0 Y+0 {} F100\nL X+20\nL Y+20\nL X+0\nL Y+0\nL X-10 Y-5 R0"
    left = run(square.format("RL"), context=ctx)
    assert np.allclose(ends(left), [[-10, -5, 0], [0, 2, 0], [18, 2, 0], [18, 18, 0], [2, 18, 0], [2, 0, 0],
                                    [-10, -5, 0]], atol=1e-12)
    right = run(square.format("RR"), context=ctx)
    assert [b.kind for b in right.blocks].count("arc") == 3
    assert np.allclose(ends(right)[1:3], [[0, -2, 0], [20, -2, 0]], atol=1e-12)
    assert np.allclose(right.blocks[3].segment.center, [20, 0, 0]) and right.blocks[3].segment.radius == 2.0
    with pytest.raises(GCodeError, match="RR while RL is active"):
        run("L X+0 Y+0 RL F100\nL X+5 RR", context=ctx)
    with pytest.raises(GCodeError, match="radius compensation RL"):  # an arc smaller than the tool, inside
        run("TOOL CALL 2 Z\nL X+0 Y+0 R0 F100\nL X+10 RL\nCC X+11 Y+0\nC X+12 Y+0 DR+\nL X+20 R0", context=ctx)


def test_dwell_and_tolerance_cycles():
    prog = run("L X+1 F100\nCYCL DEF 9.0 DWELL TIME\nCYCL DEF 9.1 DWELL 1.5\nCYCL DEF 32.0 TOLERANCE\n"
               "CYCL DEF 32.1 T0.05\nL X+2\nCYCL DEF 32.1\nL X+3")
    b = prog.blocks
    assert b[1].kind == "dwell" and b[1].dwell == 1.5
    assert (b[0].exact_stop, b[2].exact_stop, b[2].tolerance, b[3].tolerance) == (True, False, 0.05, None)


def test_cycle_definitions_take_q_parameters():
    # the Q parameters of a definition are set in the program's store, as the TNC does
    prog = run("Q9 = 4\nCYCL DEF 200 DRILLING ~\n Q200=+2 ;SET-UP CLEARANCE ~\n Q201=-Q9 ;DEPTH ~\n"
               " Q206=+100 ~\n Q202=+2 ~\n Q210=+0 ~\n Q203=+0 ~\n Q204=+5 ~\n Q211=+0\nL X+Q201 Y+Q200 F100")
    assert ends(prog) == [[-4, 2, 0]]


def axis_moves(prog, first=0):
    """(kind, z [mm], feed [mm/min] or dwell [s]) of the blocks from ``first`` on."""
    return [(b.kind, round(float(b.target[2]), 9), b.dwell if b.kind == "dwell" else
             (math.inf if b.kind == "rapid" else round(b.feed * 60, 9))) for b in prog.blocks[first:]]


def test_cycle_200_pecks_dwells_and_second_clearance():
    prog = run("L X+10 Y+20 Z+50 R0 FMAX\nCYCL DEF 200 DRILLING Q200=+2 Q201=-10 Q206=+120 Q202=+4 Q210=+0.5 "
               "Q203=+0 Q204=+20 Q211=+1\nL FMAX M99")
    inf = math.inf
    assert axis_moves(prog, 1) == [
        ("rapid", 2, inf), ("line", -4, 120), ("rapid", 2, inf), ("dwell", 2, 0.5), ("rapid", -2, inf),
        ("line", -8, 120), ("rapid", 2, inf), ("dwell", 2, 0.5), ("rapid", -6, inf), ("line", -10, 120),
        ("dwell", -10, 1.0), ("rapid", 2, inf), ("rapid", 20, inf)]
    assert all(b.target[:2].tolist() == [10, 20] for b in prog.blocks)


def test_cycle_1_pecking_from_the_starting_point():
    # DIST 25 from Z+25: surface at 0; advanced stop distance 0.6 mm (depth <= 30 mm)
    prog = run("L X+0 Y+0 Z+25 R0 FMAX\nCYCL DEF 1.0 PECKING\nCYCL DEF 1.1 DIST25\nCYCL DEF 1.2 DEPTH-10\n"
               "CYCL DEF 1.3 PLNGNG4\nCYCL DEF 1.4 DWELL0\nCYCL DEF 1.5 F600\nCYCL CALL")
    inf = math.inf
    assert axis_moves(prog, 1) == [
        ("line", -4, 600), ("rapid", 25, inf), ("rapid", -3.4, inf), ("line", -8, 600), ("rapid", 25, inf),
        ("rapid", -7.4, inf), ("line", -10, 600), ("rapid", 25, inf)]


def test_cycle_203_decrement_and_chip_breaking():
    prog = run("L X+0 Y+0 Z+2 R0 FMAX\nCYCL DEF 203 UNIVERSAL DRILLING Q200=+2 Q201=-9 Q206=+60 Q202=+3 Q210=+0 "
               "Q203=+0 Q204=+2 Q212=+1 Q213=+1 Q205=+1 Q211=+0 Q208=+0 Q256=+0.5\nL M99")
    r = math.inf
    assert axis_moves(prog, 1) == [
        ("line", -3, 60), ("line", -2.5, 60), ("line", -5, 60), ("line", 2, 60), ("rapid", -3, r), ("line", -6, 60),
        ("line", -5.5, 60), ("line", -7, 60), ("line", 2, 60), ("rapid", -5, r), ("line", -8, 60),
        ("line", -7.5, 60), ("line", -9, 60), ("line", 2, 60)]


def test_cycle_205_advanced_stop_and_pattern_call():
    prog = run("L X+0 Y+0 Z+50 R0 FMAX\nPATTERN DEF ~\nPOS1 (X+10 Y+0 Z+0) ~\nPOS2 (IX+5 Y+5 Z-1)\n"
               "CYCL DEF 205 UNIVERSAL PECKING Q200=+2 Q201=-6 Q206=+60 Q202=+3 Q203=+0 Q204=+10 Q212=+0 "
               "Q205=+0 Q258=+0.5 Q259=+0.5 Q257=+0 Q256=+0.2 Q211=+0\nCYCL CALL PAT FMAX")
    inf = math.inf
    assert ends(prog)[1] == [10, 0, 50] and ends(prog)[9] == [15, 5, 10]  # in the plane at the clearance
    assert axis_moves(prog, 2)[:7] == [("rapid", 2, inf), ("line", -3, 60), ("rapid", 2, inf),
                                       ("rapid", -2.5, inf), ("line", -6, 60), ("rapid", 2, inf), ("rapid", 10, inf)]
    assert axis_moves(prog, 10) == [("rapid", 1, inf), ("line", -4, 60), ("rapid", 1, inf), ("rapid", -3.5, inf),
                                   ("line", -7, 60), ("rapid", 1, inf), ("rapid", 9, inf)]



def test_cycle_205_advanced_stop_goes_from_q258_to_q259_and_q379_beyond_the_depth_is_refused():
    # 4 pecks of 2 to Z-8: re-entries above -2, -4, -6 by 0.2, 0.6, 1.0 (Q258 0.2 to Q259 1.0 in equal steps)
    text = (HEAD + "L X+0 Y+0 Z+50 R0 FMAX\nCYCL DEF 205 Q200=+2 Q201=-8 Q206=+60 Q202=+2 Q203=+0 Q204=+10 Q212=+0 "
            "Q205=+0 Q258=+0.2 Q259=+1 Q257=+0 Q256=+0.2 Q211=+0 Q379=+0 Q253=750\nCYCL CALL\nEND PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h")
    rapids = [round(b.target[2], 6) for b in prog.blocks[1:] if b.kind == "rapid"]
    assert rapids == [2, 2, -1.8, 2, -3.4, 2, -5.0, 2, 10]
    match = match_blocks(heidenhain_reference(text, MachineContext()), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    # a deepened starting point runs (test_heidenhain_manual_examples2); one at or below the depth is an error
    with pytest.raises(GCodeError, match="Q379 must lie within the depth Q201"):
        run("CYCL DEF 205 Q200=+2 Q201=-8 Q206=+60 Q202=+2 Q203=+0 Q204=+10 Q379=+8 Q253=750\nCYCL CALL")


def test_cycl_call_pos_moves_then_runs_the_cycle_with_z_as_a_datum_shift():
    """TNC 640 user's manual, "Calling a cycle with CYCL CALL POS": above the surface the tool goes
    first in the plane, then in the tool axis; the tool-axis coordinate shifts the surface Q203."""
    prog = run("L X+0 Y+0 Z+100 R0 FMAX\nCYCL DEF 200 DRILLING Q200=+2 Q201=-5 Q206=+150 Q202=+5 Q210=+0 "
               "Q203=+0 Q204=+50 Q211=+0\nCYCL CALL POS X+10 Y+10 Z+0 FMAX\nCYCL CALL POS X+20 Y+10 Z-2 F500")
    inf = math.inf
    assert ends(prog)[1:3] == [[10, 10, 100], [10, 10, 0]]
    assert axis_moves(prog, 3)[:4] == [("rapid", 2, inf), ("line", -5, 150), ("rapid", 2, inf), ("rapid", 50, inf)]
    second = [b for b in prog.blocks if b.line == 5]
    assert [b.target.tolist() for b in second[:2]] == [[20, 10, 50], [20, 10, -2]]  # the plane, then Z, at F500
    assert second[0].feed == pytest.approx(500 / 60) and second[1].feed == pytest.approx(500 / 60)
    assert [b.target[2] for b in second[2:]] == [0, -7, 0, 48]  # surface -2: clearance 0, depth -7, 2nd 48

BAD = [
    ("CYCL DEF 18.0 THREAD CUTTING", "cycle 18 THREAD CUTTING (spindle-synchronised"),
    ("FN 26: TABOPEN TNC:\\TABLE.TAB", "FN 26 is not supported"),
    ("L X+1 F100\nAPPR LT X+0 Y+0 LEN5 RL", "without a following contour element"),
    ("L X+1 F100\nAPPR LCT X+0 Y+0 R5 R0\nL X+5", "APPR LCT without radius compensation"),
    ("CALL LBL 7", "label 7 is not defined"),
    ("Q1 = 0\nQ2 = 5 / Q1", "division by zero"),
    ("FN 4: Q2 = +5 DIV +0", "division by zero"),
    ("Q1 = SQRT(-1)", "SQRT of -1"),
    ("L X+1 F100\nRND R20\nL Y+1", "does not fit"),
    ("L X+1 F100\nCT X+2 Y+0", "on the tangent"),
    ("M99", "without a machining cycle"),
    ("L B+10 F100", "axis 'B'"),
    ("FN 14: ERROR = 1000", "FN 14"),
    ("CYCL CALL PAT F100", "without a PATTERN DEF"),
    ("PATTERN DEF SQUARE1 (X+0 Y+0 D+5)", "pattern 'SQUARE1' is not supported"),
    ("L X+nan F100", "not a number"),
    ("L X+1.2.3 F100", "malformed number"),
    ("L X+0 Y+0 FMAX\nFL X+10 Y+0", "FL feed move without a feed"),
    ("L X+0 Y+0 F100\nFL AN+30", "FL: its length is not determined"),
    ("CYCL DEF 200 DRILLING Q200=+2 Q201=-5 Q206=+100 Q202=+5 Q203=+0 Q204=+20\nCYCL CALL POS X+1 Y+1 FMAX",
     "CYCL CALL POS without Z"),
]


@pytest.mark.parametrize("body, words", BAD)
def test_errors_name_the_function(body, words):
    with pytest.raises(GCodeError) as info:
        run(body)
    assert words in str(info.value)
    assert info.value.file == "t.h" and info.value.line >= 2 and info.value.column >= 1


def test_detection_of_real_file_headers():
    text = "0  BEGIN PGM spot-drill MM \n1 L X+1 R0 FMAX\n2 END PGM spot-drill MM\n"
    assert parse_program(text).dialect == "heidenhain"
    assert parse_program("; header\n* - part\n1 CYCL DEF 7.0 DATUM SHIFT\n2 L X+1 FMAX\n").dialect == "heidenhain"


# --- the corpus -------------------------------------------------------------------------------

#: Accepted programs up to this many blocks are also interpolated here (0219 and 0220, 4071 and
#: 5760 blocks, take 11-14 s each on the 2-core CI machine; the corpus runner interpolates them).
INTERPOLATED_BLOCKS = 1000
CORPUS = Path(__file__).resolve().parents[3] / "shared" / "data" / "gcode-corpus"
_LIT = r"[+-]?\s*\d*\.?\d+"


def _reference_ends(path: Path):
    """Independent reference from a straight reading of the text: the machine coordinates that an
    ``L`` or ``C`` line with literal absolute coordinates must reach, and the pole (last literal
    ``CC``) of each ``CP`` line (datum shifts with literal values and TOOL DEF lengths tracked;
    everything after a shift by a Q parameter is left out)."""
    shift = [0.0, 0.0, 0.0]
    lengths: dict[int, float] = {}
    length = 0.0
    known = True
    out: dict[int, list[tuple[int, float]]] = {}
    poles: dict[int, list[tuple[int, float]]] = {}
    pole = None
    for lineno, raw in enumerate(path.read_bytes().decode("latin-1").split("\n"), start=1):
        code = re.sub(r"^\s*\d+\s*", "", raw.split(";")[0]).strip()
        if m := re.match(rf"CYCLE? DEF 7\.([123])\s+(I?)[XYZ]\s*({_LIT})\s*$", code):
            i = int(m.group(1)) - 1
            shift[i] = (shift[i] if m.group(2) else 0.0) + float(m.group(3).replace(" ", ""))
        elif re.match(r"CYCLE? DEF 7\.[123]", code):
            known = False
        elif m := re.match(rf"TOOL DEF (\d+) L({_LIT})", code):
            lengths[int(m.group(1))] = float(m.group(2))
        elif m := re.match(r"TOOL CALL (\d+)", code):
            length = lengths.get(int(m.group(1)), 0.0)
        elif known and re.match(r"(L|C|CC) ", code) and not re.search(r"Q|\bI[XYZ]|M9[12]|M140", code):
            axes = re.findall(rf"\b([XYZ])({_LIT})", code)
            values = [("XYZ".index(a), float(v.replace(" ", "")) + shift["XYZ".index(a)]
                       + (length if a == "Z" else 0.0)) for a, v in axes]
            if code.startswith("CC "):
                pole = values
            elif axes:
                out[lineno] = values
        elif known and code.startswith("CP ") and pole is not None:
            poles[lineno] = pole
    return out, poles


@pytest.mark.skipif(not CORPUS.is_dir(), reason=f"corpus not found at {CORPUS} (shared data absent)")
def test_corpus_programs_run_and_end_where_the_text_says():
    files = sorted(CORPUS.glob("*.h"))
    assert len(files) == 47
    ran, failed = [], {}
    total_checked = 0
    for f in files:
        try:
            prog = load_program(f)
        except GCodeError as exc:
            assert exc.line is not None and exc.expected, str(exc)
            failed[f.name] = str(exc)
            continue
        ran.append(f.name)
        ref, poles = _reference_ends(f)
        pos = np.zeros(3)
        checked = 0
        for b in prog.blocks:
            assert np.array_equal(b.start, pos), (f.name, b.line)
            pos = b.target
            if b.kind != "dwell" and b.line in ref and b.text.split(";")[0].strip().split()[-1] != "M99":
                for axis, value in ref[b.line]:
                    assert b.target[axis] == pytest.approx(value, abs=1e-9), (f.name, b.line, b.text)
                checked += 1
            if b.line in poles:  # a CP arc ends on its circle about the pole
                c = dict(poles[b.line])
                r0 = math.hypot(b.start[0] - c[0], b.start[1] - c[1])
                assert math.hypot(b.target[0] - c[0], b.target[1] - c[1]) == pytest.approx(r0, abs=1e-9)
                checked += 1
        total_checked += checked
        if len(prog.blocks) > 0 and prog.blocks[0].kind != "dwell":
            assert checked > 0 or not ref, f.name
        if 0 < len(prog.blocks) <= INTERPOLATED_BLOCKS:
            setpoints = interpolate(prog)
            last = [prog.blocks[-1].target["xyz".index(a)] for a in setpoints.axes]
            assert np.allclose(setpoints.position[-1], last, atol=1e-6), f.name
    print(f"{len(ran)} of {len(files)} Heidenhain programs run, {total_checked} block ends checked; "
          f"rejected: {failed}")
    assert len(ran) >= 41 and total_checked > 20000
