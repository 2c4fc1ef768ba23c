"""Review of session 28: defects found in the day's reader changes, each with a hand-written program."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
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
