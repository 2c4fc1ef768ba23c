"""Review of session 28: defects found in the day's reader changes, each with a hand-written program."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from tests.interpolators.test_heidenhain_wild12 import DRILL
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")
GRBL = MachineContext().with_dialect("grbl")


@pytest.mark.parametrize("numbered", ["", "N20 "])
def test_a_while_without_brackets_but_with_its_do_names_the_brackets(numbered):
    # 'WHILE #1<3 DO1' (a DDCS macro) ends in its DO: it lacks the brackets Fanuc macro B writes ('WHILE
    # [<conditional expression>] DO m', FANUC 0i-MF operator's manual, custom macro, "Iteration"); the message
    # said "WHILE without DO m at the end of its block", and named no DDCS after a block number
    with pytest.raises(GCodeError, match=r":2:\d+: WHILE condition without its brackets \(as the DDCS controllers "
                                         r"write 'WHILE #18<#3 DO2': Fanuc macro B brackets it\)"):
        parse_program(f"#1=0\n{numbered}WHILE #1<3 DO1\n#1=#1+1\nEND1\nM30\n", context=FANUC)


def test_a_while_without_brackets_and_without_do_names_both():
    with pytest.raises(GCodeError, match=r":2:1: WHILE without DO m at the end of its block \(a condition without "
                                         r"brackets, as the DDCS controllers write"):
        parse_program("#1=0\nWHILE #1<3\n#1=#1+1\nEND1\nM30\n", context=HAAS)


@pytest.mark.parametrize("context", [GRBL, FANUC])
def test_a_grbl_command_inside_a_block_is_named_without_sending_to_the_grbl_dialect(context):
    # grbl reads '$H' only as a line of its own (grbl protocol.c: a line whose first character is '$' goes to
    # system_execute_line, any other to the G-code parser; grbl wiki "Grbl v1.1 Commands", "$H"); inside a block
    # the grbl dialect refuses it too, so "read the program with --dialect grbl" was wrong advice there
    with pytest.raises(GCodeError, match=r":2:7: unknown word '\$H' \(a grbl setting or system command, .* which grbl "
                                         r"reads only on a line of its own, not inside a block\)") as err:
        parse_program("G21 G90\nG0 X1 $H\nM30\n", context=context)
    assert "--dialect grbl" not in str(err.value)


def test_a_grbl_command_on_its_own_line_still_sends_to_the_grbl_dialect():
    with pytest.raises(GCodeError, match=r":2:3: unknown word '\$H' .*: read the program with --dialect grbl\)"):
        parse_program("G21 G90\n  $H\nG0 X1\nM30\n", context=LINUXCNC)
    assert parse_program("G21 G90\n  $H\nG0 X1\nM30\n", context=GRBL).blocks[-1].target[0] == 1.0


@pytest.mark.parametrize("context", [GRBL, LINUXCNC])
def test_a_cncjs_expression_in_a_word_names_cncjs(context):
    # CNCjs User Guide, "Macro": the sender replaces '[xmin]' in 'G0 X[xmin]' before grbl reads the line. The
    # word-start form named CNCjs with this very example, the example itself only "a template's placeholder"
    with pytest.raises(GCodeError, match=r":2:6: malformed value: 'xmin' is neither .*an expression the CNCjs sender "
                                         r"evaluates before grbl reads the line, as a CNCjs macro writes "
                                         r"'G0 X\[xmin\]'\?\)"):
        parse_program("G21\nG0 X[xmin]\nM30\n", context=context)


def test_a_name_later_in_an_expression_keeps_the_placeholder_hint():
    with pytest.raises(GCodeError, match=r"'xmin' is neither a number, a parameter nor a function \(text left in "
                                         r"brackets, such as a template's placeholder\?\)"):
        parse_program("G21\nG0 X[1+xmin]\nM30\n", context=LINUXCNC)


def _circular_pocket(set_up: str, depth: str, peck: str) -> list[tuple[str, list[float]]]:
    # read, and matched against the independent reference (tests/interpolators/reference_heidenhain.py)
    prog = checked_program("0 BEGIN PGM T MM\nTOOL CALL 1 Z S1000\nL X+50 Y+50 Z+10 R0 FMAX\n"
                           f"CYCL DEF 5.0 CIRCULAR POCKET\nCYCL DEF 5.1 {set_up}\nCYCL DEF 5.2 {depth}\n"
                           f"CYCL DEF 5.3 {peck} F100\nCYCL DEF 5.4 RADIUS 10\nCYCL DEF 5.5 F200 DR+\nCYCL CALL\n"
                           "END PGM T MM\n", MachineContext())
    return [(b.kind, np.round(b.target, 9).tolist()) for b in prog.blocks]


@pytest.mark.parametrize(("written", "plain"), [(("SET UP.5", "DEPTH -4", "PECKG 2"), ("SET UP 0.5", "DEPTH -4",
                                                                                         "PECKG 2")),
                                                (("SET UP 2", "DEPTH-2", "PECKG.5"), ("SET UP 2", "DEPTH -2",
                                                                                       "PECKG 0.5"))])
def test_an_english_pocket_item_with_its_decimal_point_after_the_name(written, plain):
    # 'CYCL DEF 5.1 SET UP.5': the English name of the TNC's dialog has no dot of its own, so the dot is the
    # number's, as tnc12 made 'DWELL.5' 0.5 s in the value lines (heidenhain_cycles._ENGLISH_ITEMS, our reading);
    # the pocket lines' own reader took 'SET UP.' for the name and 5 for the set-up clearance, and so did the
    # reference
    assert _circular_pocket(*written) == _circular_pocket(*plain)



@pytest.mark.parametrize("block", ["CYCL CALL MB 10", "CYCL CALL MB MAX", "M3 MB 10"])
def test_mb_without_m140_in_a_cycle_call_or_a_block_of_m_functions_is_refused(block):
    # MB is M140's retraction path (TNC 640 user's manual, "Retraction in the tool axis: M140": "M140 MB MAX");
    # 'L X+10 FMAX MB 10' was refused ("MB without M140"), the same MB in a CYCL CALL or beside other M functions
    # dropped silently: the retract the program wrote did not happen
    with pytest.raises(GCodeError, match=r"t\.h:13:\d+: MB without M140 \(got 'MB ?(10|MAX)'\); expected M140 MB MAX"):
        parse_heidenhain("0 BEGIN PGM T MM\nTOOL CALL 1 Z S1000\nL Z+15 R0 FMAX\n" + DRILL + f"{block}\nEND PGM T MM\n",
                         source="t.h", context=MachineContext())
