"""ISO programs of the fourteenth wild round (issue 18, set /tmp/isowild14): CAMotics' examples, a LinuxCNC plasma
table's and a LinuxCNC knee mill's shop programs (o<name> subroutines beside them, user M codes), Fanuc-style test
programs of a G-code plotter, a mould shop's Fanuc macro B subprograms, ncEFI's templates, UGS's and gSender's
test files, qtpyvcp's samples. What their controls refuse is refused naming what the text is."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from vcnc.errors import GCodeError

PLACEHOLDER = r"a template's placeholder '\({}\)' where the number goes: a generator fills it in, so the file is a " \
              r"template, not a program"


@pytest.mark.parametrize(("line", "column", "letter", "name"), [
    ("G00 Z(GCODE_OP_SAFEZ)", 5, "Z", "GCODE_OP_SAFEZ"),  # ncEFI's ncPRG_end.nc
    ("F(GCODE_OP_BFEED)      (base feed rate, set in code)", 1, "F", "GCODE_OP_BFEED"),  # its ncPRG_start.nc
    ("G1 X10 Y ( SAFE_Y )", 8, "Y", "SAFE_Y")])
@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl", "fanuc", "haas"])
def test_a_template_placeholder_is_named(line, column, letter, name, dialect):
    with pytest.raises(GCodeError, match=f":2:{column}: malformed number for word {letter} "
                                         f"\\({PLACEHOLDER.format(name)}\\)"):
        parse_program(f"G21 G90\n{line}\nM2\n", context=MachineContext().with_dialect(dialect))


def test_a_comment_of_prose_after_a_bare_axis_letter_is_no_placeholder():
    # lowercase prose, or one word without '_': still the 3D printer's axis flag
    for line in ("G1 X (move)", "G1 X (SAFE)"):
        with pytest.raises(GCodeError, match=r":2:4: malformed number for word X \(an axis letter without its "
                                             r"number, as 3D printer firmware such as Marlin takes axis flags\)"):
            parse_program(f"G21 G90\n{line}\nM2\n", context=MachineContext())
