"""Readings settled by the post processors of hobby and router CAM (session 36, fcpost36): FreeCAD's Path/CAM posts
(FreeCAD/FreeCAD src/Mod/CAM/Path/Post/scripts/), Vectric's ``.pp`` templates, and the controls they write for. Each
snippet is written for these tests in the output style of the post it names (repository, path); the control's
manual gives the reading."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])

#: A Vectric VCarve post for LinuxCNC's QtPlasmaC ("THS vCarve Post", a .pp template, FIRST_PLUNGE_MOVE "M3 $0 S1"):
#: the torch is spindle 0, selected with LinuxCNC's $ word; M52 adaptive feed, M65 outputs, M68 analog output.
THS_PLASMA = ("%\n(THS vCarve Post)\nG20\nG90 G40\nG17 G91.1\nG64 P0.01 Q0.012\nM52 P1.\nM65 P2.\n"
              "M68 E3 Q0.\n\nG54\nF40\n(----- Toolpath Profile 1 -----)\nG0 X1.0000 Y1.0000\nM3 $0 S1\n"
              "G1 X2.0000 Y1.0000\nG2 X2.5000 Y1.5000 I0.0000 J0.5000\nM5\n\nG0 X0 Y0\nM65 P2.\n"
              "M68 E3 Q0.\nM5 $-1\nM30\n%\n")


def test_the_spindle_selection_word_of_linuxcnc():
    # LinuxCNC M-code reference "M3, M4, M5": "M3 $0 S1000"; $-1 all spindles. rs274 -g runs THS_PLASMA (its moves
    # match vcnc's: benchmarks/linuxcnc_diff.py). Before: "unknown word '$0' (a grbl setting ...)"
    prog = checked_iso(THS_PLASMA, LINUXCNC)  # the reference reads $ since iso37
    assert prog.blocks[-1].target.tolist() == pytest.approx([0.0, 0.0, 0.0])
    assert prog.blocks[-2].target.tolist() == pytest.approx([2.5 * 25.4, 1.5 * 25.4, 0.0])
    assert any(n.startswith("$ spindle selection (one spindle: $0)") for n in prog.notes)
    for block in ("M3 $0.9 S1", "M3 $ -1 S1", "M3 $[-1] S1", "S100 $0", "M19 $0 R0"):  # rs274 runs each
        checked_iso(f"G21\n{block}\nG0 X1\nM2\n", LINUXCNC)


@pytest.mark.parametrize("block, message", [
    ("M3 $1 S100", r"2:4: spindle \$1: vcnc's machine has one spindle"),  # rs274: "Invalid spindle ($) number"
    ("M5 $-2", r"2:4: spindle \$-2"),
    ("G0 X1 $0", r"2:7: \$ \(spindle selection\) word with no S, M3"),  # rs274: "... word with no M3, ... to use it"
    ("G97 $0", r"2:5: \$ \(spindle selection\) word with no S"),
    ("M5 $0 $-1", r"2:7: word \$ appears twice"),  # rs274: "Multiple spindle choice ($) words on one line"
])
def test_a_spindle_selection_linuxcnc_refuses(block, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21\n{block}\nG0 X1\nM2\n", context=LINUXCNC)


@pytest.mark.parametrize("dialect", ["fanuc", "grbl"])
def test_other_dialects_name_the_linuxcnc_spindle_word(dialect):
    with pytest.raises(GCodeError, match=r"2:4: unknown word '\$0'.*on LinuxCNC '\$' selects the spindle"):
        parse_program("G21\nM3 $0 S1\nG0 X1\nM2\n", context=MachineContext(dialect=DIALECTS[dialect]))


@pytest.mark.parametrize("line, column, text, code", [
    ("M117 Cutting Toolpath 1", 6, "Cutting", "M117 <text>: Marlin's LCD message"),
    ("M118 E1 Hello", 9, "Hello", "M118 <text>: Marlin's serial print"),
])
def test_a_marlin_message_line_is_named(line, column, text, code):
    # Vectric's Marlin gCode post (an MPCNC router's: "Added status messages (M117)") writes "M117 <text>"
    # (marlinfw.org/docs/gcode/M117.html "M117 [string]"); no dialect of vcnc reads Marlin. Before: "malformed
    # number for word C ('Cutting': a statement of another control's language, such as KinetiC-NC's PRINT?)"
    prog = f"; Vectric gCode for Marlin\n{line}\nG90\nG21\nG0 X10.000 Y10.000\nM30\n"
    with pytest.raises(GCodeError, match=rf":2:{column}: malformed number for word {text[0]} \({code}, whose text "
                                         r"is no G-code.*--dialect grbl\)"):
        parse_program(prog, context=MachineContext(dialect=DIALECTS["grbl"]))


#: FreeCAD's UC-CNC post (FreeCAD/FreeCAD src/Mod/CAM/Path/Post/scripts/uccnc_post.py: ``"%" + PROG_NAME``, then
#: the "(uccnc_post with default settings)" comment and its preamble with comments after each code)
UCCNC = ("%prog1\n(uccnc_post with default settings)\n(Units: 'mm' and 'mm/min')\n(preamble: begin)\n"
         "G17 (Default: XY-plane)\nG54 (Default: First coordinate system)\nG90 (Default: Absolute distance mode "
         "selection)\n(preamble: done)\nG0 X10.000 Y10.000\nG1 Z-1.000 F100.000\nM05 (stop spindle)\n"
         "M30 (Stop program and rewind code)\n")


def test_a_program_name_after_the_first_percent_names_its_reading():
    # rs274 refuses "%prog1" ("Bad character '%' used"); a Fanuc control skips the tape's leader. Before, the error
    # named only CNCjs's macro lines
    with pytest.raises(GCodeError, match=r":1:1: '%' must stand alone on its line \(a program name after the '%', "
                                         r"as FreeCAD's UC-CNC post writes '%prog1': --dialect fanuc"):
        parse_program(UCCNC, context=LINUXCNC)
    prog = parse_program(UCCNC, context=MachineContext(dialect=DIALECTS["fanuc"]))
    assert prog.blocks[-1].target.tolist() == pytest.approx([10.0, 10.0, -1.0])


#: FreeCAD's RepRapFirmware post (FreeCAD/FreeCAD src/Mod/CAM/Path/Post/scripts/rrf_post.py): a spindle wait after M3
#: written "G4 S3" ("RRF: P for milliseconds, S for seconds, change P to S"), the tool change left as "  T1".
RRF = ("(Exported by FreeCAD)\n(Post Processor: rrf_post.py, version: 2022-02-11)\n(Begin preamble)\n"
       "(Default Configuration)\nG90\nG21\nG17\n(Begin toolchange)\n  T1\nM3 S10000\nG4 S3\nG0 X30.000 Y30.000\nM5\n")


@pytest.mark.parametrize("dialect, message", [
    ("grbl", r"G4 dwell without P: grbl takes the dwell time from P only"),
    ("linuxcnc", r"G04 needs exactly one of P or X"),
    ("fanuc", r"G04 needs exactly one of P or X"),
])
def test_a_firmware_dwell_in_seconds_is_named(dialect, message):
    # Duet G-code reference "G4: Dwell": "Snnn Time to wait, in seconds"; an ISO control's S is the spindle speed.
    # Before, the error did not say what G4 S is
    with pytest.raises(GCodeError, match=rf":11:1: {message}.*\(G4 S<seconds> is the dwell of RepRapFirmware and "
                                         r"Marlin"):
        parse_program(RRF, context=MachineContext(dialect=DIALECTS[dialect]))


def test_a_bare_g53_is_refused_as_linuxcnc_refuses_it():
    # FreeCAD's Job offers the fixture "G53" (Path/Main: MachineState.WCSLIST "G53", "G54", ..), which its fixture
    # operation writes as a code alone; centroid_post.py's preamble "G53 G00 G17" has its G0. rs274 -g: "Must use g0
    # or g1 with g53" for "G53" and "G90 G53" after a G0 move, and runs "G53 G0" and "G53 X5". Before, vcnc ran a
    # bare G53 on the modal G0 silently
    for block in ("G53", "G90 G53", "G53 G49 M5"):
        with pytest.raises(GCodeError, match=r":3:\d+: G53 without G0/G1 or axis words in its block: LinuxCNC "
                                             r"refuses it \(\"Must use G0 or G1 with G53\"\)"):
            parse_program(f"G21\nG0 X1\n{block}\nG0 X2\nM2\n", context=LINUXCNC)
    for block in ("G53 G0", "G53 G00 G17", "G53 X5"):
        parse_program(f"G21\nG0 X1\n{block}\nG0 X2\nM2\n", context=LINUXCNC)
    for dialect in ("fanuc", "grbl"):  # grbl gcode.c checks the modal motion; Fanuc's G53 without axes moves nothing
        prog = parse_program("G21\nG0 X1\nG53\nG0 X2\nM2\n", context=MachineContext(dialect=DIALECTS[dialect]))
        assert [b.target[0] for b in prog.blocks] == pytest.approx([1.0, 2.0])


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc"])
def test_a_freecad_fixture_beyond_g59_3_is_named(dialect):
    # FreeCAD's Job lists the fixtures G54 .. G59.9 (Path/Main MachineState.WCSLIST) and its fixture operation writes
    # the code chosen; rs274: "Unknown g code used" for G59.4. Before, the error did not say where it came from
    with pytest.raises(GCodeError, match=r":2:1: unknown G code 'G59.4' \(a fixture FreeCAD's Job offers: LinuxCNC "
                                         r"has G54-G59.3, Fanuc G54.1 P1-P300 beyond G59\)"):
        parse_program("G21\nG59.4\nG0 X2\nM2\n", context=MachineContext(dialect=DIALECTS[dialect]))
