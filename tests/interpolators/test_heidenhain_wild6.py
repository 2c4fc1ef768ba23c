"""Heidenhain programs of a sixth wild set (hyperMILL, an NX post, shop and training programs, files of a
CNC simulator): what the reader refused or named wrongly, each as a hand-written program checked against
the independent reference where it runs."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()


def checked(body: str):
    """The program read, and its blocks matched against the reference."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO)


DRILL = ("1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n3 L X+10 Y+20 Z+50 R0 FMAX\n"
         "4 CYCL DEF 200 {name}\n    Q200=2 ;SET-UP CLEARANCE ~\n    Q201=-10 ;DEPTH ~\n    Q206=150 ;FEED ~\n"
         "    Q202=10 ;PLUNGING DEPTH ~\n    Q210=0 ;DWELL TOP ~\n    Q203=+0 ;SURFACE ~\n"
         "    Q204=50 ;2ND SET-UP CLEARANCE ~\n    Q211=0 ;DWELL BOTTOM\n5 CYCL CALL")


def plunges(prog) -> list[float]:
    return [b.target[2] for b in prog.blocks]


def test_a_tilde_before_a_comment_continues_the_cycle_definition():
    # a shop's iTNC 530 training program: 'CYCL DEF 200 BOHREN ~  ;anbohren' (the TNC itself saves the '~'
    # after the comment); before, "unexpected 'BOHREN' in a cycle definition". The hole (TNC 640 cycle
    # manual, cycle 200): from Z+50 at FMAX to the set-up clearance Z+2, one infeed Q202 = Q201 to Z-10 at
    # Q206, at FMAX back to the set-up clearance and on to the 2nd set-up clearance Z+50
    prog = checked(DRILL.format(name="BOHREN ~  ;;------ anbohren"))
    assert np.allclose(plunges(prog), [50, 2, -10, 2, 50])
    assert all(np.allclose(b.target[:2], [10, 20]) for b in prog.blocks)


@pytest.mark.parametrize("name", ["DRILLING ~", "BOHREN ~", "TAPPING W/ CHIP BRKG ~", "VRTÁNÍ ~",
                                  "SINGLE-LIP D.H.DRLNG ~", "FÚRÁS 2 ~", "~"])
def test_the_cycle_name_is_any_text_in_the_dialog_language(name):
    # the TNC saves the cycle's name in the language of its dialogs (English, German, Czech, Hungarian ..);
    # digits and accented letters included. Same moves as above whatever the name
    assert np.allclose(plunges(checked(DRILL.format(name=name))), [50, 2, -10, 2, 50])


def test_an_assignment_without_its_value_is_still_an_error():
    with pytest.raises(GCodeError, match=r"cycle parameter Q201 without '=' \(got 'Q201 -5'\); expected Q201=value"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 CYCL DEF 200 DRILLING Q200=2 Q201 -5\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


@pytest.mark.parametrize(("line", "message"), [
    ('($Message("Load the machine settings") )', r"t.h:1:1: '\(\$Message\(...\)\)' is a command of the CNC "
                                                 r"Simulator program: not a TNC block"),
    ("( Einrichtblatt", r"t.h:1:1: a '\(...\)' comment is ISO \(DIN 66025\) syntax: not a TNC block"),
])
def test_lines_of_other_languages_before_the_program_are_named(line, message):
    # a CNC simulator's "Heidenhain" examples start with its own $Message command; a DNC export with a
    # parenthesised setup sheet. A TNC refuses both; the error says what the line is
    with pytest.raises(GCodeError, match=message):
        parse_heidenhain(line + "\nBEGIN PGM T MM\nL X+10 R0 FMAX\nEND PGM T MM\n", source="t.h", context=ZERO)


def test_an_iso_block_number_is_named():
    with pytest.raises(GCodeError, match=r"t.h:2:1: the block number 'N1' is ISO \(DIN 66025\) syntax"):
        parse_heidenhain("BEGIN PGM T MM\nN1 L X+10 R0 FMAX\nEND PGM T MM\n", source="t.h", context=ZERO)


def test_a_pattern_after_an_old_cycle_names_that_cycle():
    # a shop's program runs cycle 220 after an old cycle: which run a pattern gives the old pockets, no manual
    # page found says; the error names the cycle (it said "without a machining cycle" though one was defined).
    # (The shop's own form, cycle 220 after the old tapping cycle 2, runs since session 39: test_tnc_old39.)
    body = ("1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n3 L X+0 Y+0 Z+2 R0 FMAX\n"
            "4 CYCL DEF 5.0 KREISTASCHE\n5 CYCL DEF 5.1 ABST 1\n6 CYCL DEF 5.2 TIEFE -5\n"
            "7 CYCL DEF 5.3 ZUSTLG 5 F100\n8 CYCL DEF 5.4 RADIUS 8\n9 CYCL DEF 5.5 F200 DR-\n"
            "10 CYCL DEF 220 MUSTER KREIS Q216=+60 Q217=+45 Q244=+48 Q245=+0 Q246=+180 Q247=+180 Q241=+2 "
            "Q200=+1 Q203=+0 Q204=+1 Q301=+1 Q365=+0")
    with pytest.raises(GCodeError, match=r"t.h:11:4: cycle 220 with cycle 5: a pattern runs the machining cycles "
                                         r"of the 200 series and the old cycles 1, 2, 17 here"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", source="t.h", context=ZERO)
