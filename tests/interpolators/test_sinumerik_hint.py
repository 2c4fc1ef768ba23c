"""A SINUMERIK program given to the ISO reader: its error says it looks like one and names the first construct of
SINUMERIK's own language (``interpolators.iso_flow.sinumerik_construct``), instead of leaving the user with a
message about the first word ISO G-code reads otherwise (Siemens, SINUMERIK 840D "Manual, 5-axis machining", 7.1
"Overview of higher-order functions"; the SINUMERIK programming manuals' "Fundamentals")."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from interpolators.iso_flow import sinumerik_construct
from vcnc.errors import GCodeError

HINT = "this looks like a Siemens SINUMERIK program, whose own language vcnc does not read"


@pytest.mark.parametrize(("line", "what"), [
    ('N20 T="FRAESER_10" D1', 'T="..." (a tool called by its name)'),
    ("N30 G1 X=AC(10) Y=IC(5) F200", "X=AC(..)/IC(..)"),
    ("G2 X20 Y0 CR=10 F100", "CR=/AR=/AP=/RP=/TURN="),
    ("R11=384.553", "R1=.. (an R parameter set)"),
    ("G0 X=R1 Y0", "X=R1 (an axis word from an R parameter)"),
    ("N60 CYCLE81(10,0,2,-5,)", "a cycle call NAME(..)"),
    ('MSG("roughing")', 'MSG("..") (a message)'),
    ("DEF REAL DEPTH=5", "DEF (a variable definition)"),
    ("IF R1>5 GOTOF END_PART", "a SINUMERIK keyword"),
    ("N40 G642 SOFT", "a SINUMERIK keyword"),
    ("N50 TRANS X10 Y5", "TRANS/ROT/SCALE/MIRROR (a programmable frame)"),
])
def test_the_first_sinumerik_construct_is_named_with_the_error(line, what):
    text = f"; SINUMERIK 840D\nN10 G17 G90 G54\n{line}\nN90 G0 Z50\nN100 M30\n"
    with pytest.raises(GCodeError) as err:
        parse_program(text, source="part.mpf")
    message = str(err.value)
    assert HINT in message
    assert f"line 3 {line!r}: {what}" in message
    assert message.startswith("part.mpf:")  # the ISO reader's own location and message come first


def test_the_hint_comes_from_the_first_such_line_even_after_the_error():
    # the ISO reader stops at G71 (line 2), the tool call by name follows on line 3
    with pytest.raises(GCodeError, match=r"part\.mpf:2:9: G71 .*SINUMERIK.*line 3 'T=\"DRILL\"'"):
        parse_program('; part\nG17 G90 G71\nT="DRILL"\nG0 X0 Y0\nM30\n', source="part.mpf")


@pytest.mark.parametrize(("text", "dialect"), [
    # LinuxCNC active comments and ISO comments naming Siemens words are comments
    ("G21 G90 (MSG, CYCLE81 next) (TRANS X1)\nG1 X1\nM2\n", "linuxcnc"),
    # Fadal's macro R parameters are written #R1=..
    ("G21 G90\n#R1=R2+1\nG1 X1\nM2\n", "fadal"),
    # a named LinuxCNC parameter that starts with R
    ("G21 G90\n#<R1>=5\nG1 X1\nM2\n", "linuxcnc"),
])
def test_iso_programs_that_fail_get_no_sinumerik_hint(text, dialect):
    assert sinumerik_construct(text) is None
    with pytest.raises(GCodeError) as err:  # G1 without a feed: an error, without the hint
        parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    assert "SINUMERIK" not in str(err.value)


def test_an_iso_program_that_runs_is_not_touched():
    prog = parse_program("G21 G90 (CYCLE81(1,2) in a comment)\nG1 X10 F100\nM30\n")
    assert prog.blocks[-1].target.tolist() == [10.0, 0.0, 0.0]
