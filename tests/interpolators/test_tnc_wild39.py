"""Heidenhain forms met in real TNC programs from public repositories (session 39) where the reader and the
independent reference (``reference_heidenhain``) disagreed: one ran a form the other refused, or ran it otherwise.
Each program is hand-written in the style of the program that showed it."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_iso import ReferenceError
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})


# -- a keyword written against its number (CNCSimulator's TNC examples: 'TOOL DEF1 L+30,000'; a hand-written
#    'CALL PGM100'); the TNC's editor writes a space, our reading takes the number or name as it would be read
#    with one, as the reader already took TOOL DEF1 ------------------------------------------------------------

def test_call_pgm_with_the_name_against_pgm_runs_the_program(tmp_path):
    (tmp_path / "100.h").write_text("0 BEGIN PGM 100 MM\n1 L X+10 Y+20 R0 FMAX\n2 END PGM 100 MM\n")
    main = tmp_path / "MAIN.h"
    text = "0 BEGIN PGM MAIN MM\n1 TOOL CALL 1 Z S1000\n2 L Z+50 R0 FMAX\n3 CALL PGM100\n4 L X+0 R0 FMAX\n" \
           "5 END PGM MAIN MM\n"
    main.write_text(text)
    prog = parse_heidenhain(text, source=str(main), context=CTX)  # refused before: 'malformed CALL PGM'
    ref = heidenhain_reference(text, CTX, resolve=lambda name: (tmp_path / f"{name}.h").read_text())
    match = match_blocks(ref, reader_rows(*blocks_table(prog)))
    assert match.mismatch is None and match.exact == len(prog.blocks) == 3
    # the called program's point, then back in the caller: tool length 10 along Z
    assert prog.blocks[1].target == pytest.approx([10.0, 20.0, 60.0])
    assert prog.blocks[2].target == pytest.approx([0.0, 20.0, 60.0])


def test_sel_pgm_with_the_name_against_pgm_selects_it(tmp_path):
    (tmp_path / "7.h").write_text("0 BEGIN PGM 7 MM\n1 L X+5 R0 FMAX\n2 END PGM 7 MM\n")
    main = tmp_path / "MAIN.h"
    text = "0 BEGIN PGM MAIN MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+50 R0 FMAX\n3 SEL PGM7\n" \
           "4 CALL SELECTED PGM\n5 END PGM MAIN MM\n"
    main.write_text(text)
    prog = parse_heidenhain(text, source=str(main), context=CTX)
    assert np.allclose(prog.blocks[-1].target, [5.0, 0.0, 60.0])


def test_tool_def_with_the_number_against_def_is_checked_by_the_reference():
    # the reference refused 'TOOL DEF1 ..' ('tool block'); the reader ran it as TOOL DEF 1
    prog = checked_program("0 BEGIN PGM P MM\n1 TOOL DEF1 L+30 R+5\n2 TOOL CALL 1 Z S1000\n3 L Z+50 R0 FMAX\n"
                           "4 L X+10 Y+10 R0 FMAX\n5 END PGM P MM\n", MachineContext())
    assert prog.blocks[-1].target == pytest.approx([10.0, 10.0, 80.0])


# -- cycle 241's infeeds Q202 (the newer versions' pecking with Q212/Q205): the reader refuses it, naming it; the
#    reference ran one infeed to the depth, as if Q202 were not there --------------------------------------------

CYCLE_241 = """0 BEGIN PGM P MM
1 TOOL CALL 1 Z S1000
2 L X+20 Y+20 Z+50 R0 FMAX
3 CYCL DEF 241 SINGLE-LIP D.H.DRLNG ~
  Q200=+2 ;SET-UP CLEARANCE ~
  Q201=-30 ;DEPTH ~
  Q206=+150 ;FEED RATE FOR PLNGNG ~
  Q211=+0 ;DWELL TIME AT DEPTH ~
  Q203=+0 ;SURFACE COORDINATE ~
  Q204=+50 ;2ND SET-UP CLEARANCE ~
  Q379=+5 ;STARTING POINT ~
  Q253=+750 ;F PRE-POSITIONING ~
  Q208=+1000 ;RETRACTION FEED RATE ~
  Q426=+3 ;DIR. OF SPINDLE ROT. ~
  Q427=+25 ;ROT.SPEED INFEED/OUT ~
  Q428=+500 ;ROT. SPEED DRILLING ~
  Q429=+8 ;COOLANT ON ~
  Q430=+9 ;COOLANT OFF ~
  Q435=+0 ;DWELL DEPTH ~
  Q401=+100 ;FEED RATE FACTOR ~
  Q202={q202} ;MAX. PLUNGING DEPTH ~
  Q212=+2 ;DECREMENT ~
  Q205=+3 ;MIN. PLUNGING DEPTH
4 CYCL CALL
5 END PGM P MM
"""


def test_cycle_241_with_shorter_infeeds_is_refused_by_both():
    text = CYCLE_241.format(q202="+10")
    with pytest.raises(GCodeError, match="cycle 241: infeeds Q202"):
        parse_heidenhain(text, source="t.h", context=CTX)
    with pytest.raises(ReferenceError, match="241"):
        heidenhain_reference(text, CTX)


def test_cycle_241_with_an_infeed_of_the_whole_depth_runs_in_one():
    prog = checked_program(CYCLE_241.format(q202="+30"), CTX)
    depths = [b.target[2] for b in prog.blocks if b.kind == "line"]
    assert min(depths) == pytest.approx(-30.0 + 10.0)  # the depth, plus the tool length 10


# -- CONTOUR DEF: a depth written without its '=' ('DP-5'): the reader refuses the word, naming the forms it reads;
#    the reference skipped it and machined the pocket to cycle 20's depth ----------------------------------------

def rough_out(contour: str, retract: str = " Q208=+1000 ;RETRACTION FEED RATE\n") -> str:
    """A square pocket 80 x 80 roughed out by cycle 22 in two infeeds of 5 to Q1 = -10 (tool R3, L10)."""
    return ("0 BEGIN PGM P MM\n1 TOOL CALL 1 Z S1000\n2 L Z+50 R0 FMAX\n" + contour
            + "4 CYCL DEF 20 CONTOUR DATA ~\n Q1=-10 ;MILLING DEPTH ~\n Q2=+1 ;TOOL PATH OVERLAP ~\n"
            " Q3=+0 ;ALLOWANCE FOR SIDE ~\n Q4=+0 ;ALLOWANCE FOR FLOOR ~\n Q5=+0 ;SURFACE COORDINATE ~\n"
            " Q6=+2 ;SET-UP CLEARANCE ~\n Q7=+50 ;CLEARANCE HEIGHT ~\n Q8=+0 ;ROUNDING RADIUS ~\n"
            " Q9=+1 ;ROTATIONAL DIRECTION\n5 CYCL DEF 22 ROUGH-OUT ~\n Q10=-5 ;PLUNGING DEPTH ~\n"
            " Q11=+100 ;FEED RATE FOR PLNGNG ~\n Q12=+500 ;FEED RATE F. ROUGHNG ~\n Q18=+0 ;COARSE ROUGHING TOOL ~\n"
            " Q19=+100 ;FEED RATE FOR RECIP." + (" ~\n" + retract if retract else "\n")
            + "6 CYCL CALL\n7 L Z+50 R0 FMAX M30\n8 LBL 1\n9 L X+10 Y+10 RL\n10 L X+90\n11 L Y+90\n"
            "12 L X+10\n13 L Y+10\n14 LBL 0\n15 END PGM P MM\n")


def test_contour_def_word_not_read_is_refused_by_both():
    text = rough_out("3 CONTOUR DEF P1 = LBL 1 DP-5\n")
    with pytest.raises(GCodeError, match="DP-5"):
        parse_heidenhain(text, source="t.h", context=CTX)
    with pytest.raises(ReferenceError, match="CONTOUR DEF word"):
        heidenhain_reference(text, CTX)
    # with the depth written as the TNC writes it, 0: both run it (cycle 20's Q1)
    prog = checked_program(rough_out("3 CONTOUR DEF P1 = LBL 1 DP1 = +0\n"), CTX, exact=False)
    assert min(b.target[2] for b in prog.blocks) == pytest.approx(-10.0 + 10.0)


# -- cycle 22's retraction feed Q208 (iTNC 530: "feed rate for retraction", 0: Q12): the reader retracted at it
#    after each infeed, the reference at FMAX whatever Q208 said ---------------------------------------------------

@pytest.mark.parametrize(("retract", "kind"), [(" Q208=+1000 ;RETRACTION FEED RATE\n", "line"),
                                               (" Q208=+0 ;RETRACTION FEED RATE\n", "line"),
                                               (" Q208=MAX ;RETRACTION FEED RATE\n", "rapid"), ("", "rapid")])
def test_rough_out_retracts_between_infeeds_at_q208(retract, kind):
    prog = checked_program(rough_out("3 CYCL DEF 14.0 CONTOUR GEOMETRY\n3 CYCL DEF 14.1 CONTOUR LABEL1\n",
                                     retract), CTX, exact=False)
    ups = [b for a, b in zip(prog.blocks, prog.blocks[1:])
           if b.target[2] == pytest.approx(12.0) and a.target[2] == pytest.approx(5.0)]  # Z-5 up to Q6 = 2
    assert [b.kind for b in ups] == [kind]
