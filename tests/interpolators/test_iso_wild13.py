"""ISO programs of the thirteenth wild round (issue 18, set /tmp/isowild12): hobby routers' and lasers' generators
(GrblGru, jscut, GCodeKit4, Fusion personal posts, a Python panel engraver, drl2gcode, pcb-gcode), student Haas
programs, a CATIA Haas VF6 post, a MillMaster Pro file. What their controls refuse is refused naming what the
text is and how that control says it."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

SLASH = r"'//' comment line \(Syntec/DDCS macro and MillMaster Pro style\)"


@pytest.mark.parametrize("line", ['// Tool is a 3/4" (or whatever you decide', "  // see note)", "//O0000 RAIL-HOLE"])
def test_a_slash_comment_line_is_named_before_its_parentheses(line):
    # a MillMaster Pro file's header: prose after '//', an unclosed '(' in it; before, "unclosed comment"
    with pytest.raises(GCodeError, match=f":2:{line.index('//') + 2}: {SLASH}.*expected a \\( \\) or ; comment"):
        parse_program(f"G70\n{line}\nG0 X1\n", context=MachineContext().with_dialect("fanuc"))


def test_a_block_delete_line_still_runs():
    prog = checked_iso("G21 G90\n/G0 X1 (skip) Y2\nM30\n", MachineContext())
    assert [b.target.tolist() for b in prog.blocks] == [[1.0, 2.0, 0.0]]
