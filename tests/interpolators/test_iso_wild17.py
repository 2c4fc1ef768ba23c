"""ISO programs of the seventeenth wild round (set /tmp/isowild17): controls outside the Fanuc/Haas/LinuxCNC mainstream,
Centroid CNC12 (Intercon, MillWrite and SFP posts, Acorn router macros), Tormach PathPilot subroutines, PlanetCNC TNG
scripts, Okuma OSP user tasks and a Mach4 subroutine. The snippets are written for these tests after those programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")

# an Intercon (Centroid CNC12) post: "G4 P3.00 ; pause for dwell" after the tool change, a drilling cycle with P
INTERCON = ("G20 G90 G17 G40 G80\nT1 M6\nM3 S1200\nG4 P3.00 ; pause for dwell\nG0 X1. Y1. Z0.1\n"
            "G82 X1. Y1. Z-0.2 R0.1 P0.5 F10.\nG80\nM30\n")
POINT_NOTE = ("dwell P with a decimal point read in milliseconds, as {} reads P (where P is seconds, as on LinuxCNC "
              "and grbl: --dialect linuxcnc, it dwells 1000 times longer)")


def test_a_dwell_p_with_a_decimal_point_read_in_milliseconds_is_noted():
    prog = checked_iso(INTERCON, FANUC)
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == pytest.approx([0.003, 0.0005])
    assert POINT_NOTE.format("fanuc") + " x2" in prog.notes  # the G4 and the G82


@pytest.mark.parametrize("context", [LINUXCNC, HAAS])
def test_the_same_dwells_read_in_seconds_where_p_is_seconds(context):
    # Haas: a P with a decimal point is seconds (Haas mill operator's manual, G04: "G04 P10. is a dwell of 10 s")
    prog = checked_iso(INTERCON, context)
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == pytest.approx([3.0, 0.5])
    assert not any("decimal point read in milliseconds" in n for n in prog.notes)


@pytest.mark.parametrize("dwell", ["G04 P500", "G04 X0.5", "#1 = 2.5\nG04 P#1"])
def test_a_dwell_p_without_a_literal_decimal_point_is_not_noted(dwell):
    prog = checked_iso(f"G21 G90\n{dwell}\nM30\n", FANUC)
    assert len([b for b in prog.blocks if b.kind == "dwell"]) == 1
    assert not any("decimal point read in milliseconds" in n for n in prog.notes)


@pytest.mark.parametrize(("text", "column", "what"), [
    # an Acorn router's defines file and a CNC12 M-code macro
    ("; Centroid defines\nDEFINE <ACTIVE_TOOL> #4120\nM30\n", "2:2", r"DEFINE <name> #n, a statement of Centroid "
                                                                  r"CNC12's macro language"),
    ("IF #4201 || #4202 THEN GOTO 1000\nN1000\nM30\n", "1:2", r"IF #n THEN \.\.\., a statement of Centroid CNC12's "
                                                             r"macro language"),
    # an Okuma OSP user task
    ("VFST=#81H\nM02\n", "1:2", r"V<name>=, a variable of Okuma OSP's user task language"),
])
@pytest.mark.parametrize("context", [FANUC, LINUXCNC])
def test_statements_of_centroid_and_okuma_macros_are_named(text, column, what, context):
    with pytest.raises(GCodeError, match=rf":{column}: malformed value: '\w+' is neither a number, a parameter nor "
                                         rf"a function \({what}; vcnc reads ISO G-code with Fanuc macro B or "
                                         r"LinuxCNC O-codes\)"):
        parse_program(text, context=context)


def test_a_name_left_in_brackets_keeps_the_placeholder_hint():
    with pytest.raises(GCodeError, match=r"'PX' is neither a number, a parameter nor a function \(text left in "
                                         r"brackets, such as a template's placeholder, or an expression the "
                                         r"CNCjs sender evaluates"):
        parse_program("G21\nG1 X[PX] F100\nM30\n", context=FANUC)


@pytest.mark.parametrize("line", ['G65 "\\cncm\\defines.cnc"', 'G65 "c:\\cncm\\tool_set.cnc" ; an Acorn router macro'])
def test_a_quoted_text_of_a_centroid_macro_is_named(line):
    with pytest.raises(GCodeError, match=r":2:\d+: unknown word '\"[^']*' \(a quoted text, as Centroid CNC12 macros "
                                         r"write a prompt, M225 #100 \"text\", or a macro file, G65 \"file\"; vcnc "
                                         r"reads ISO G-code with Fanuc macro B or LinuxCNC O-codes\)"):
        parse_program(f"G20 G90\n{line}\nM30\n", context=FANUC)


@pytest.mark.parametrize("context", [FANUC, LINUXCNC])
def test_an_okuma_subprogram_call_is_named(context):
    # an Okuma OSP user task (SET-MASTER-XY.MIN): a call of the OSP subprogram OO30 with its named arguments
    with pytest.raises(GCodeError, match=r":1:1: malformed number for word C \('CALL O<name>': Okuma OSP's subprogram "
                                         r"call; vcnc reads ISO G-code, not OSP programs\)"):
        parse_program("CALL OO30 PAXI=3\nM2\n", context=context)
