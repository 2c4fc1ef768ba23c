"""Readings settled by the shopiso40 set of public shop programs (/tmp/shopiso40/progs, sources.tsv: Fusion 360
and Mastercam output for Fanuc and Haas mills, a Fanuc bolt-circle macro (z64/cncbook), grbl, TinyG and FluidNC
senders' and firmwares' sample files, hobby CAM output). The snippets are written for these tests after those
programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import INTERPOLATION_CONTEXT
from vcnc.errors import GCodeError

FANUC = INTERPOLATION_CONTEXT.with_dialect("fanuc")


def test_a_cycle_level_error_speaks_the_programs_units():
    """z64/cncbook's bolt-circle macro taps to 'Z#5' with #5 = .500 (J = tap depth, its sign lost) under G20: the
    levels are named as the program writes them, in inch, not as 12.7 mm, a number the program never holds."""
    text = "%\nO1\nG20 G90 G0 X1 Y0 Z1\nG98 G84 Z.5 R.1 F10\nM30\n%\n"
    with pytest.raises(GCodeError, match=r":4:9: G84 tapping cycle: hole bottom Z 0\.5 in lies above the R plane "
                                         r"0\.1 in \(got 'Z\.5'\)"):
        parse_program(text, context=FANUC)
    with pytest.raises(GCodeError, match=r"hole bottom Z 5 mm lies above the R plane 1 mm"):
        parse_program(text.replace("G20", "G21").replace("Z.5 R.1", "Z5 R1"), context=FANUC)


def test_a_back_boring_level_error_speaks_the_programs_units():
    """The G87 back-boring levels likewise: an inch program's R.2 above its Z-.5 is named in inch (it read
    'R 5.08 below Z -12.7 below the initial level 25.4 mm')."""
    text = "%\nO1\nG20 G90 G0 X1 Y0 Z1\nG98 G87 Z-.5 R.2 Q.01 F5\nM30\n%\n"
    with pytest.raises(GCodeError, match=r":4:14: G87 back boring cycle: back boring needs R 0\.2 below Z -0\.5 below "
                                         r"the initial level 1 in \(got 'R\.2'\)"):
        parse_program(text, context=FANUC)
