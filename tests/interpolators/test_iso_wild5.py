"""ISO programs of the fifth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


@pytest.mark.parametrize("name", ["linuxcnc", "grbl", "fanuc", "haas"])
@pytest.mark.parametrize("m", [3, 4])
def test_snapmaker_spindle_power_word_is_named(name, m):
    # Snapmaker Luban writes "M3 P100" (Snapmaker gcode_reference.md: "M3 [P] | 50< percentage <=100"); none
    # of these controls reads P with M3, and the message says what the P meant there
    with pytest.raises(GCodeError, match=rf":2:4: M{m} P: spindle power in percent \(Snapmaker 2.0 firmware\).*"
                                         rf"\(got 'P100'\); expected M{m} S<rpm>"):
        parse_program(f"G21 G90\nM{m} P100\nG0 X1\n", context=_in_dialect(name))


def test_a_p_word_without_a_spindle_code_keeps_its_message():
    with pytest.raises(GCodeError, match=r"word P needs G04 \(dwell\)"):
        parse_program("G21 G90\nG0 X1 P100\n", context=_in_dialect("linuxcnc"))


def test_an_arc_off_its_circle_says_when_absolute_centres_fit():
    # a proLIGHT 1000 post writes I J as the centre's coordinates; read as offsets (G91.1, LinuxCNC's power-on
    # mode) the end is off the circle. From (10, 0) to (0, 10): I1 J1 as offsets is the centre (11, 1), radii
    # 1.41 and 14.2 mm; as coordinates (G90.1) the centre (1, 1), radius 9.06 mm at both ends
    with pytest.raises(GCodeError, match=r":3:11: arc end point is not on the circle: start radius 1.41421 mm, end "
                                         r"radius 14.2127 mm .*; I/J/K as absolute centre coordinates \(LinuxCNC "
                                         r"G90.1\) would fit \(got 'I1'\)"):
        parse_program("G21 G90 F100\nG0 X10 Y0\nG2 X0 Y10 I1 J1\n", context=_in_dialect("linuxcnc"))
    prog = parse_program("G21 G90 G90.1 F100\nG0 X10 Y0\nG2 X0 Y10 I1 J1\n", context=_in_dialect("linuxcnc"))
    assert prog.blocks[-1].target.tolist() == [100, 60, 100]  # G54 (100, 50, -20), Z still at home (100)
    # the other way round: G90.1 in force, I-9 J1 fits as offsets from the start
    with pytest.raises(GCodeError, match=r"; I/J/K as offsets from the start \(G91.1\) would fit \(got 'I-9'\)"):
        parse_program("G21 G90 G90.1 F100\nG0 X10 Y0\nG2 X0 Y10 I-9 J1\n", context=_in_dialect("linuxcnc"))


def test_an_arc_off_its_circle_either_way_gets_no_hint():
    # the Shapeoko calibration file's arc from (20, -21) to (21, -20) with I20 J21: off the circle both ways
    with pytest.raises(GCodeError, match=r"end radius 27.5862 mm \(difference 1.41 mm > tolerance 0.029 mm\) "
                                         r"\(got 'I20'\)"):
        parse_program("G21 G90 F100\nG0 X20 Y-21\nG3 X21 Y-20 I20 J21\n", context=_in_dialect("grbl"))


def test_a_user_m_code_runs_when_its_program_is_in_the_user_m_path(tmp_path):
    """LinuxCNC m-code.adoc "M100 to M199": the executable M101 of the user M path runs with P and Q as its
    arguments and the program waits for it; it moves nothing of the path. A shop's M101 ("enable Z-axis",
    a halcmd script) in mfiles/ beside the program: from X1 on to X2 in G54 (100, 50, -20), Z at home."""
    (tmp_path / "mfiles").mkdir()
    (tmp_path / "mfiles" / "M101").write_text("#!/bin/sh\nexit 0\n")
    text = "G21 G90\nG0 X1\nM101 P2 Q3\nG0 X2\nM2\n"
    ctx = dataclasses.replace(CTX, dialect=dataclasses.replace(DIALECTS["linuxcnc"], user_m_path=("mfiles",)))
    prog = parse_program(text, source=str(tmp_path / "part.ngc"), context=ctx)
    assert [b.target.tolist() for b in prog.blocks] == [[101, 0, 100], [102, 0, 100]]
    assert "user M code M101 (an external program of the user M path: no motion)" in prog.notes
    # no such file there (M102), or no user M path at all: the code is refused, naming the file
    with pytest.raises(GCodeError, match=r":3:1: user M code 'M102' .*: M102 not found \(folders: its own folder, "
                                         r"mfiles\)"):
        parse_program(text.replace("M101", "M102"), source=str(tmp_path / "part.ngc"), context=ctx)
    with pytest.raises(GCodeError, match=r"M101 not found \(folders: its own folder\).*expected M codes below 100, "
                                         r"or the file M101 in a folder of the machine's \[program\] user_m_path"):
        parse_program(text, source=str(tmp_path / "part.ngc"), context=_in_dialect("linuxcnc"))


def test_no_centre_mode_hint_for_a_zero_radius_or_a_lone_centre_word():
    # the Stepcraft post's "too small" hole: I0 on a full circle is a zero radius, not an off-circle end; and
    # I alone cannot be an absolute centre (G90.1 needs both I and J)
    with pytest.raises(GCodeError, match=r"arc radius is zero: the centre is the start point \(got 'I0'\)"):
        parse_program("G21 G90 F100\nG0 X10 Y5\nG3 X10 Y5 I0\n", context=_in_dialect("linuxcnc"))
    with pytest.raises(GCodeError, match=r"tolerance 0.0282843 mm\) \(got 'I-3'\)"):
        parse_program("G21 G90 F100\nG0 X10 Y0\nG3 X0 Y10 I-3\n", context=_in_dialect("linuxcnc"))


@pytest.mark.parametrize("line", ["G03 F360", "G3", "G2"])
def test_linuxcnc_refuses_an_arc_code_without_its_centre_words(line):
    # a Stepcraft post writes "G03 F360" and the end point with I on the next line; LinuxCNC's convert_arc
    # refuses the first ("R i j k words all missing for arc", rs274 2.9: also without axis words)
    code = line.split()[0]
    with pytest.raises(GCodeError, match=rf":3:1: {code} arc without R, I, J or K \(LinuxCNC: 'R i j k words all "
                                         rf"missing for arc'.*; expected {code} with I/J/K or R"):
        parse_program(f"G21 G90 F100\nG0 X0 Y0\n{line}\nX1 Y0 I0.5\n", context=_in_dialect("linuxcnc"))


def test_grbl_refuses_an_arc_code_without_axis_words():
    # gnea/grbl grbl/gcode.c: a G2/G3 word sets axis_command = AXIS_COMMAND_MOTION_MODE, and the arc checks fail
    # "[No axis words]" (error 26) on a block without axis words; only G0/G1 alone just set the mode. (This test
    # said the opposite until wild21, which read the source: a UCCNC file of Eagle's stepcraft.ulp writes "G03 F360".)
    with pytest.raises(GCodeError, match=r":3:1: G03 arc without axis words: grbl refuses it \(error 26"):
        parse_program("G21 G90 F100\nG0 X0 Y0\nG03 F360\nX1 Y0 I0.5\n", context=_in_dialect("grbl"))


def test_an_unbracketed_assignment_is_read_as_macro_b_with_a_note_under_linuxcnc():
    # an Inkscape gcodetools file with "#<test> = #<test> + 2": rs274 says "Bad character '+' used", as LinuxCNC
    # reads a parameter setting's value as one real value (overview.adoc "Parameter Setting"); Fanuc macro B
    # takes "#1=#1+2" (B-64304EN "Arithmetic and logic operation"). vcnc reads it so under every dialect, and
    # the linuxcnc one says LinuxCNC refuses it: X is 3 + 2 = 5 in G54 (100, 50, -20), Y and Z at home (0, 100)
    text = "G21 G90\n#1 = 3\n#1 = #1 + 2 G0 X1\nG0 X#1\nM2\n"
    for name in ("linuxcnc", "fanuc"):
        assert parse_program(text, context=_in_dialect(name)).blocks[-1].target.tolist() == [105, 0, 100]
    note = ("parameter assignment with an operation outside [ ], read as Fanuc macro B does (LinuxCNC refuses it: "
            "\"Bad character used\")")
    assert note in parse_program(text, context=_in_dialect("linuxcnc")).notes
    assert not parse_program(text.replace("#1 + 2", "[#1 + 2]"), context=_in_dialect("linuxcnc")).notes


def test_a_g04_x_dwell_is_noted_under_linuxcnc():
    # a hand-written "G04 X3." (Fanuc: X is the time in s); LinuxCNC's G4 takes P only (g-code.adoc "G4 Dwell"),
    # rs274 says "Dwell time missing with g4": read as 3 s, with a note under the linuxcnc dialect only
    text = "G21 G90\nG0 X1\nG04 X3.\nG0 X2\nM2\n"
    note = "G04 X<s> dwell read as Fanuc does (LinuxCNC refuses it: \"Dwell time missing with g4\")"
    prog = parse_program(text, context=_in_dialect("linuxcnc"))
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == [3.0] and note in prog.notes
    assert note not in parse_program(text, context=_in_dialect("fanuc")).notes


@pytest.mark.parametrize(("name", "tap_dwell"), [("linuxcnc", [1.5]), ("fanuc", [])])
def test_a_tapping_cycle_without_p_takes_linuxcnc_s_last_dwell_but_not_fanuc_s(name, tap_dwell):
    """rs274 runs "G82 .. P1.5 / G80 / G84 .. (no P)" with DWELL(1.5) at the tap's bottom too: LinuxCNC keeps the
    dwell P across series (interp_cycles.cc: G74/G84 read settings->cycle_p); Fanuc clears the hole machining
    data at G80 (B-64304EN "Canned cycle for drilling"), so a CNCagent program's G84 there does not dwell."""
    text = "G21 G90 G0 X0 Y0 Z10\nS300 M3\nG82 X5 Y5 Z-1 R2 P1.5 F50\nG80\nG84 X10 Y10 Z-4 R2 F450\nG80\nM30\n"
    prog = checked_iso(text, _in_dialect(name))
    assert [b.dwell for b in prog.blocks if b.kind == "dwell" and b.line == 5] == tap_dwell


def test_a_grbl_file_runs_on_past_a_second_percent_line():
    # a Fusion 360 MPCNC post wraps its custom start code in "%( *** START end ***)": grbl reads no '%' and
    # CNCjs, which evaluates '%' lines itself, streams the rest of the file: X1 then X2 in G54 (100, 50, -20)
    text = "%\nG21 G90\nG0 X1\n%( *** START end ***)\nG0 X2\n%\n"
    prog = checked_iso(text, _in_dialect("grbl"))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 0, 100], [102, 0, 100]]
