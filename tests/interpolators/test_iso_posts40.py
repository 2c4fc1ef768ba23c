"""Constructs of CAM posts and CAM output not read before, read as their controls read them (session 40, posts40).

Each program is hand-written in the output style of the post or program named in its test; the posts were read,
not run."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError


@pytest.mark.parametrize("dialect", ["grbl", "linuxcnc", "fanuc"])
@pytest.mark.parametrize("move", ["G1 X20. Y10. E1.5 F600", "G2 X20 Y0 I10 J0 E0.53 F1200", "X30.5 E3.25"])
def test_an_extruder_e_on_a_move_is_named(dialect, move):
    # A slicer's output (Cura, PrusaSlicer with arc fitting) fed to a CNC router: Marlin's G0-G1 "E<pos> An
    # absolute or relative coordinate on the E (extruder) axis". Before: 'outside M66-M68 (digital/analog I/O)'
    # alone, which names LinuxCNC's I/O codes, not what the word is
    text = f"G21 G90\nG0 X0 Y0 Z1\n{move}\nM2\n"
    with pytest.raises(GCodeError, match=r":3:\d+: word 'E[\d.]+' outside M66-M68 .*\(E on a move: the extruder "
                                         r"axis of 3D printer G-code"):
        parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    # an E without a move keeps its message (no extruder hint)
    with pytest.raises(GCodeError, match=r"outside M66-M68 \(digital/analog I/O\); expected") as err:
        parse_program("G21 G90\nG0 X0 Y0 Z1\nE1.5\nM2\n", context=MachineContext(dialect=DIALECTS[dialect]))
    assert "extruder" not in str(err.value)


@pytest.mark.parametrize("dialect", ["grbl", "linuxcnc"])
@pytest.mark.parametrize(("code", "title"), [("M400", "M400 finish moves"), ("M300 S440 P200", "M300 play tone"),
                                             ("M280 P0 S90", "M280 servo position")])
def test_marlin_codes_above_m199_are_named(dialect, code, title):
    # Fusion's Snapmaker 2.0 post (nunorvoliveira/snapmaker-2.0, SM2.0 (NrvO).cps onClose: M400, M5, G4 S) and
    # MPCNC posts write Marlin's M400 "Finish Moves"; pen plotters M280 "Servo Position". Before: 'machine- or
    # firmware-specific M code' without the firmware's name
    text = f"G21 G90\nG0 X0 Y0 Z1\nG1 X10 F600\n{code}\nM2\n"
    with pytest.raises(GCodeError, match=rf":4:1: .*'{code.split()[0]}' \(above M199: defined by a machine "
                                         rf"configuration\) \(Marlin's {title}: a 3D printer firmware's code"):
        parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    # a code of no firmware vcnc knows stays as it was
    with pytest.raises(GCodeError, match=r"'M428' \(above M199: defined by a machine configuration\): not "):
        parse_program(text.replace(code, "M428"), context=MachineContext(dialect=DIALECTS[dialect]))


@pytest.mark.parametrize("line", ["  Rapid X=10 Y=20 Z=5", "Line X=20.5", "  LoadWcs name=\"1\""])
def test_a_datron_simpl_program_is_named(line):
    # Autodesk's "datron next.cps" (DATRON next control, extension "simpl"): writeBlock("Rapid" + " X=" ..),
    # "Line X=..", wcs format 'LoadWcs name="#"'. Before: "a statement of another control's language, such as
    # KinetiC-NC's PRINT?"
    with pytest.raises(GCodeError, match=r":1:\d+: malformed number for word [RL] \(DATRON SimPL, the language of "
                                         r"the DATRON next control"):
        parse_program(f"{line}\nLine Y=3\n", context=MachineContext(dialect=DIALECTS["fanuc"]))


def test_haas_m109_interactive_input_is_named_not_a_printer_code():
    # Haas mill operator's manual "M109 Interactive User Input": the program waits for the operator's key and
    # stores it in the macro variable P (M109 P501). Before: named as "Marlin's M109 wait for hotend temperature"
    # under --dialect haas
    text = "G21 G90\nG0 X0 Y0 Z1\nM109 P501\nIF [#501 EQ 89] GOTO 10\nG1 X10 F600\nN10 M30\n"
    with pytest.raises(GCodeError, match=r":3:1: M109 interactive user input \(Haas: the program waits for the "
                                         r"operator's key, stored in the macro variable P\): not supported") as err:
        parse_program(text, context=MachineContext(dialect=DIALECTS["haas"]))
    assert "Marlin" not in str(err.value)
    # under fanuc, M109 stays a machine tool builder's code (and Marlin's hotend wait, named as before)
    with pytest.raises(GCodeError, match=r"machine-specific M code 'M109' .*Marlin's M109"):
        parse_program(text, context=MachineContext(dialect=DIALECTS["fanuc"]))


@pytest.mark.parametrize("code", ["M84", "M82", "M10"])
def test_grbl_notes_the_m_codes_below_100_it_refuses(code):
    # Marlin router output (MPCNC posts: M84 at the end, M82 before the moves) read with --dialect grbl: grbl 1.1
    # gcode.c's 'M' switch takes M0-M2, M30, M3-M5, M7-M9, M56, grblHAL's core also M6, M48-M53, M60-M68, M70-M73,
    # M98, M99; any other is "[Unsupported M command]", error 20. Before: 'M84 (no motion)', as if grbl ran it
    # (LinuxCNC's such codes were already noted as refused)
    prog = parse_program(f"G21 G90\nG0 X0 Y0 Z1\nG1 X10 F600\n{code}\nM2\n",
                         context=MachineContext(dialect=DIALECTS["grbl"]))
    assert (f"{code} (no motion; grbl refuses it: error 20, '[Unsupported M command]', as grblHAL does without a "
            "plugin that claims it)") in prog.notes
    # M56 (parking override) is grbl's own: noted as before
    prog = parse_program("G21 G90\nG0 X0 Y0 Z1\nM56\nM2\n", context=MachineContext(dialect=DIALECTS["grbl"]))
    assert "M56 (no motion)" in prog.notes


#: The end of a drilling operation and of the program as Fusion's Mach4 / generic posts write it (G80, then G28
#: G91 Z0. and G28 G91 X0. Y0.), and the axis-word codes that follow G80 elsewhere.
AFTER_G80 = "G21 G90 G17\nG0 X0 Y0 Z5\nG98 G81 X1 Y1 Z-1 R1 F100\nG80\n{}\nG90\nM2\n"


@pytest.mark.parametrize("block", ["G28 G91 Z0.", "G30 G91 Z0", "G92 X0 Y0", "G43.1 Z2", "G10 L20 P1 X0"])
def test_codes_that_use_the_axis_words_after_g80_are_not_noted_as_refused(block):
    # interp_internal.cc check_g_codes lets G10/G28/G30/G52/G92 take the axis words and G43.1 reads its Z: rs274
    # runs "G80" then "G28 G91 Z0." (benchmarks/linuxcnc_diff.py: match). Before: noted "axis words after G80 run
    # as rapid .. (LinuxCNC refuses them ..)" at the end of every Fusion program with a drilling operation
    prog = parse_program(AFTER_G80.format(block), context=MachineContext(dialect=DIALECTS["linuxcnc"]))
    assert not any("after G80" in note for note in prog.notes)


@pytest.mark.parametrize("block", ["Z5.", "G53 Z0"])
def test_bare_axis_words_after_g80_stay_noted(block):
    # rs274: "Cannot use axis values without a g code that uses them" (G53 only modifies a G0/G1)
    prog = parse_program(AFTER_G80.format(block), context=MachineContext(dialect=DIALECTS["linuxcnc"]))
    assert ("axis words after G80 run as rapid, the motion before the cycle (LinuxCNC refuses them: G80 leaves no "
            "motion mode)") in prog.notes
