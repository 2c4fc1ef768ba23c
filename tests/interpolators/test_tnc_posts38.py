"""Heidenhain forms other CAM systems and shop floors write that vcnc refused or ran otherwise than a TNC (session
38). Each program is hand-written in the style of its source (a post, a real program, a manual's example) and
checked against the independent reference (``reference_heidenhain``), its values worked out by hand where they
say more."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})


def checked(body: str, context: MachineContext = CTX):
    """The reader's program of ``body`` in a BEGIN/END PGM frame, every block checked against the reference."""
    text = "0 BEGIN PGM 1001 MM\n" + body + "END PGM 1001 MM\n"
    prog = parse_heidenhain(text, source="t.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    assert match.exact + match.within == len(prog.blocks)
    return prog


# -- Q-parameter formulas (iTNC 530 user's manual 60642x-04, 9.8 "Entering formulas directly") -------------------

def test_modulo_in_a_formula_is_the_division_remainder():
    # the manual's example "Q12 = 400 % 360 Result: Q12 = 40", as a shop's angle reduction; % binds as * and /
    # (2 * 250 % 360 = 500 % 360 = 140). Refused before as 'malformed formula'.
    prog = checked("1 TOOL CALL 1 Z S2000 F300\n2 L X+0 Y+0 Z+10 R0 FMAX\n3 Q12 = 400 % 360\n"
                   "4 Q13 = 2 * 250 % 360\n5 L X+Q12 Y+Q13\n")
    assert prog.blocks[-1].target == pytest.approx([40.0, 140.0, 20.0])


def test_modulo_by_zero_is_an_error_naming_it():
    with pytest.raises(GCodeError, match="modulo by zero"):
        parse_heidenhain("0 BEGIN PGM 1 MM\n1 Q2 = 0\n2 Q1 = 7 % Q2\n3 END PGM 1 MM\n", source="t.h", context=CTX)


def test_sgn_of_zero_is_one():
    # the manual: "Check algebraic sign of a number, Q12 = SGN Q50: If result for Q12 = 1, then Q50 >= 0; If result
    # for Q12 = -1, then Q50 < 0" (TNC 320, TNC 620 alike). A shop's direction switch 'Q7 = SGN Q6' on a zero
    # distance: +1, the line to X+10 (read 0 before, the line to X+0).
    prog = checked("1 TOOL CALL 1 Z S2000 F300\n2 L X+5 Y+0 Z+10 R0 FMAX\n3 Q6 = 0\n4 Q7 = SGN Q6\n"
                   "5 Q8 = SGN -0.001\n6 Q9 = 10 * Q7\n7 L X+Q9 Y+Q8\n")
    assert prog.blocks[-1].target == pytest.approx([10.0, -1.0, 20.0])
