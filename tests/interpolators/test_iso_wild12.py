"""ISO programs of the twelfth wild round (issue 18): post-processor fixtures and parser test files (pygcode's
Vectric/Mach3 files, CNCjs toolpath fixtures, FreeCAD's post tests). What their controls refuse is refused
naming the feature as that control knows it; programs written for one control are not read past what it runs."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

CTX = MachineContext(tools={7: Tool(number=7, length=0.0, radius=1.5)})


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


# A Mach3 wizard's profile: the cutter's radius written as the D word ("G41 D1.5" for a 3 mm tool).
RADIUS_AS_D = "G21 G90 G17\nM6 T7\nG0 X0 Y-5 Z5\nG1 Z-1 F100\nG41 D{d} X5 Y-5\nG1 Y5\nX-5\nG40 G1 X-5 Y-10\nM30\n"


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas"])
def test_a_fractional_compensation_number_is_refused(name):
    # LinuxCNC interp_convert.cc convert_cutter_compensation_on: "G41 requires D word to be a whole number"
    with pytest.raises(GCodeError, match=r":5:5: G41 D1\.5: the offset number D must be a whole number .*"
                                         r"expected G41 D<n>, n a tool or offset number"):
        parse_program(RADIUS_AS_D.format(d="1.5"), context=_in_dialect(name))


def test_a_whole_compensation_number_takes_the_radius_from_the_tool_table():
    prog = checked_iso(RADIUS_AS_D.format(d="7"), _in_dialect("linuxcnc"))
    # the square's corner (5, 5) run on the left: 1.5 mm (tool 7's radius) inside, at (3.5, 3.5)
    assert [b.target.tolist() for b in prog.blocks if b.kind == "line"] == [
        [0.0, -5.0, -1.0], [3.5, -3.5, -1.0], [3.5, 3.5, -1.0], [-5.0, 3.5, -1.0], [-5.0, -10.0, -1.0]]
    assert "G41/G42 cutter radius compensation" in prog.notes


# A CNCjs toolpath fixture: a thread mill's helix entered under G42, incremental.
HELIX_G42 = "G21 G91\nG1 Z-0.6 F100\nG1 G42 D8 X0.5 Y-2 F10\nG3 X2 Y2 Z0.4 R2\nG40 G1 X-0.5\nM30\n"


def test_grbl_refuses_cutter_compensation_naming_it():
    # gnea/grbl gcode.c: G40 only ("cutter radius compensation is always disabled"); G41/G42 are error 20
    with pytest.raises(GCodeError, match=r":3:4: G42 cutter radius compensation: grbl has none .*error 20"):
        parse_program(HELIX_G42, context=_in_dialect("grbl"))
    assert parse_program(HELIX_G42, context=_in_dialect("linuxcnc")).blocks  # LinuxCNC runs it


def test_grbl_dwell_time_comes_from_p_only():
    # gnea/grbl gcode.c: "[P word missing]" (error 28); the other dialects read G4 X in seconds
    with pytest.raises(GCodeError, match=r":2:1: G4 dwell without P: grbl takes the dwell time from P only"):
        parse_program("G21\nG4 X2\nM30\n", context=_in_dialect("grbl"))
    dwell = [b for b in parse_program("G21\nG4 P2\nM30\n", context=_in_dialect("grbl")).blocks if b.kind == "dwell"]
    assert [b.dwell for b in dwell] == [2.0]  # grbl's P is in seconds


def test_grbl_runs_a_canned_cycle_as_grblhal_does_and_says_grbl_1_1_would_not():
    text = "G21 G90 G17 F120\nG0 X0 Y0 Z5\nG81 X10 Y10 Z-2 R1\nX20\nG80\nG0 Z5\nM30\n"
    grbl = checked_iso(text, _in_dialect("grbl"))
    # grblHAL gcode.h: "CCRetractMode_Previous = 0, // G98 (Default: Must be zero)": back to Z5 after each hole
    assert [b.target.tolist() for b in grbl.blocks][1:10] == [
        [10.0, 10.0, 5.0], [10.0, 10.0, 1.0], [10.0, 10.0, -2.0], [10.0, 10.0, 5.0],
        [20.0, 10.0, 5.0], [20.0, 10.0, 1.0], [20.0, 10.0, -2.0], [20.0, 10.0, 5.0], [20.0, 10.0, 5.0]]
    linuxcnc = parse_program(text.replace("G17", "G17 G98"), context=_in_dialect("linuxcnc"))
    assert [b.target.tolist() for b in grbl.blocks] == [b.target.tolist() for b in linuxcnc.blocks]
    assert "G81 canned cycle run as grblHAL runs it (grbl 1.1 refuses it: error 20)" in grbl.notes


@pytest.mark.parametrize(("name", "what"), [
    ("linuxcnc", r"user M code 'M110' \(M100-M199 runs the executable file M110 of the user M path"),
    ("fanuc", r"machine-specific M code 'M110' \(M100-M199 on a Fanuc control: a function of the machine tool "
              r"builder"),
    ("haas", r"machine-specific M code 'M110' \(M100-M199 on a Haas control"),
    ("grbl", r"M code 'M110' unknown to grbl")])
def test_a_high_m_code_is_named_as_its_control_knows_it(name, what):
    # a Doosan lathe post's header "G0 G18 G20 G40 G54 G80 G99 M110"
    with pytest.raises(GCodeError, match=f":1:5: {what}.*M110 not found"):
        parse_program("G21 M110\nG0 X1\nM30\n", context=_in_dialect(name))


def test_a_bare_g71_says_it_is_a_unit_code_elsewhere():
    # a Mach3 header "G71 G91.1": LinuxCNC 2.9 reads G71 as its lathe roughing cycle and refuses it
    with pytest.raises(GCodeError, match=r"G71 lathe roughing cycle: not supported \(a unit code on Siemens, Fagor "
                                         r"and Heidenhain ISO controls: mm input; write G21"):
        parse_program("G71 G91.1\nG0 X1\n", context=_in_dialect("linuxcnc"))
    with pytest.raises(GCodeError, match=r"G71 lathe roughing cycle: not supported \(got 'G71'\)"):
        parse_program("G21\nG71 P10 Q20 U0.5 W0.1 D2\n", context=_in_dialect("linuxcnc"))


SIEMENS = r"a Siemens SINUMERIK {}; vcnc reads ISO G-code, not SINUMERIK programs"


@pytest.mark.parametrize(("line", "what"), [
    ("TRANS X100 Y2", "'TRANS': " + SIEMENS.format("statement")),  # a programmable frame (Fundamentals 2.12)
    ("DEF REAL R0=0", "'DEF': " + SIEMENS.format("statement")),
    ("CYCLE81(10,0,2,-5)", "'CYCLE81': " + SIEMENS.format("statement")),
    ("G1 X=R0", "'X=': " + SIEMENS.format("address with '='")),
    ("G2 X10 Y0 CR=5 F100", "'CR=': " + SIEMENS.format("address with '='")),
    ("PRINT 5", r"'PRINT': a statement of another control's language, such as KinetiC-NC's PRINT\?")])
def test_a_siemens_statement_is_named_as_siemens(line, what):
    # an NC interpreter's SINUMERIK examples (.mpf): vcnc reads ISO G-code only, and says whose language it is
    with pytest.raises(GCodeError, match=f":2:[0-9]+: malformed number for word [A-Z] \\({what}\\)"):
        parse_program(f"G21 G90 G0 X0 Y0\n{line}\nM30\n", context=_in_dialect("fanuc"))


@pytest.mark.parametrize(("code", "name"), [("G43 H7 Z10", "G43 tool length offset"),
                                            ("G95 G1 X1 F0.1 S1000 M3", "G95 feed per revolution")])
def test_grbl_runs_grblhal_codes_and_says_grbl_1_1_would_not(code, name):
    # grbl 1.1 gcode.c: G43.1 only, no G95 (error 20); grblHAL gcode.h: ToolLengthOffset_Enable, FeedMode_UnitsPerRev
    prog = parse_program(f"G21 G90 F100\nM6 T7\n{code}\nM30\n", context=_in_dialect("grbl"))
    assert f"{name} run as grblHAL runs it (grbl 1.1 refuses it: error 20)" in prog.notes


@pytest.mark.parametrize(("text", "what"), [
    ("N1 G21\nN2 T0*57\n", r":2:6: unknown word '\*57' \(a RepRap/Marlin line checksum"),  # a parser's fixture
    ("\x01G17 G21\nG0 X1\n", r":1:1: unknown word '\\x01G17' \(control character 0x01")])
def test_a_checksum_or_a_control_character_is_named(text, what):
    with pytest.raises(GCodeError, match=what):
        parse_program(text, context=_in_dialect("grbl"))


def test_a_tool_vector_on_a_move_is_named_as_a_5_axis_post_s():
    # a 5-axis CAM output: every point carries the tool-axis vector as I J K
    with pytest.raises(GCodeError, match=r":2:22: word I is only allowed on arcs .*a 5-axis post's tool-axis "
                                         r"vector I J K\?"):
        parse_program("G21 G90\nG1 X-4.6 Y-43.6 Z137 I-0.11 J-0.81 K-0.57 F71\n", context=_in_dialect("fanuc"))
    with pytest.raises(GCodeError, match=r"a G02/G03 meant\?"):
        parse_program("G21 G90\nG1 X10 Y0 I5 J0 F71\n", context=_in_dialect("fanuc"))
