"""A Fanuc/Haas lathe program with one of G50 S / G96 beside the lathe's four-digit T word (newuser34): read as a
mill's before, its feed per revolution (G99 F0.2) taken as 0.2 mm/min, a seven-hour program refused for its length
instead of for what it is."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")

# written for this test after a Fanuc lathe's face-and-turn: T0101 (tool 1, offset 1), G96 alone, F in mm/rev (G99)
FACE_AND_TURN = ("%\nO1000\nG21 G40 G99\nT0101\nG96 S180 M03\nG00 X52. Z2.\nG01 Z0. F0.2\nX-1.6\nG00 Z2.\nM30\n%\n")
# and a Haas lathe's start with the spindle limit G50 S alone, the tool call after it
LIMIT_THEN_TOOL = "%\nO1001\nG21 G18\nG50 S2500\nT0202\nG97 S1200 M03\nG00 X40. Z2.\nG01 Z-20. F0.15\nM30\n%\n"


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g96_beside_a_lathe_tool_call_is_a_lathe_program(context):
    with pytest.raises(GCodeError, match=r":5:1: a lathe program: G96 \(constant surface speed\) here and a T word "
                                         r"of four digits \(T0101: a lathe's tool and offset number\) at line 4"):
        parse_program(FACE_AND_TURN, context=context)


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g50_s_before_a_lathe_tool_call_is_a_lathe_program(context):
    with pytest.raises(GCodeError, match=r":5:1: a lathe program: a T word of four digits .* here and G50 S \(the "
                                         r"lathe's maximum spindle speed\) at line 4 .*expected a milling program"):
        parse_program(LIMIT_THEN_TOOL, context=context)


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_a_mill_programs_tool_calls_stay_a_mills(context):
    # two lathe-looking T words are one kind of mark: not a lathe program by themselves; nor is T1 with G96
    prog = checked_iso("G21 G90 G17\nT0101 M6\nG0 X10. Y10.\nT0202 M6\nG1 X20. F500.\nM30\n", context)
    assert [b.target.tolist() for b in prog.blocks][-1] == [20.0, 10.0, 0.0]
    prog = checked_iso("G21 G90 G17\nT1 M6\nG96 S100 M3\nG0 X10. Y10.\nG1 X20. F500.\nM30\n", context)
    assert [b.target.tolist() for b in prog.blocks][-1] == [20.0, 10.0, 0.0]
