"""ISO programs of the eighth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas", "grbl"])
@pytest.mark.parametrize("unit", ["G71", "G70"])
def test_a_heidenhain_din_iso_program_is_named(name, unit):
    # a TNC program in its ISO mode (TNC 320 ISO Programming User's Manual, 3.2: first block '%', the program
    # name and the unit; blank form G30/G31; last block N99999999 and the first block again): not Fanuc's '%'
    # tape leader, not a grbl sender's '%' macro line, and not the conversational language vcnc reads
    text = (f"%PLATTE {unit} *\nN10 G30 G17 X+0 Y+0 Z-40 *\nN20 G31 G90 X+100 Y+100 Z+0 *\n"
            f"N30 G00 G40 G90 Z+50 *\nN99999999 %PLATTE {unit} *\n")
    with pytest.raises(GCodeError, match=rf":1:1: Heidenhain DIN/ISO program header '%PLATTE {unit} \*' .*not "
                                         r"supported; vcnc reads Heidenhain conversational and ISO G-code of "
                                         r"Fanuc/Haas/LinuxCNC/grbl"):
        parse_program(text, context=_in_dialect(name))


@pytest.mark.parametrize("name", ["fanuc", "grbl"])
def test_a_percent_line_that_is_no_tnc_header_keeps_its_meaning(name):
    # Fanuc skips the rest of the first '%' line (tape leader), grbl blanks a sender's '%' macro line: a
    # comment-like text after '%' is no TNC program name and unit
    prog = parse_program("% wait\nG21 G90 G54 G0 X1 Y2 Z3\nM30\n", context=_in_dialect(name))
    assert prog.blocks[-1].target.tolist() == [101.0, 52.0, -17.0]


@pytest.mark.parametrize("name", ["fanuc", "linuxcnc"])
def test_a_fanuc_all_folder_backup_is_named(name):
    # a Robodrill memory punched out whole: '&F=<folder>' lines head each folder of programs (Renishaw probe
    # macros O9810 ... among them); the file stores many programs and is no program to run
    text = "%\n&F=//CNC_MEM/\n&F=/USER/PATH1/\nO0001(PART)\nG90 G0 X0 Y0\nM30\n%\n"
    with pytest.raises(GCodeError, match=r":2:1: Fanuc folder line '&F=//CNC_MEM/': this file is a backup of the "
                                         r"control's program folders"):
        parse_program(text, context=_in_dialect(name))


@pytest.mark.parametrize(("name", "noted"), [("linuxcnc", True), ("fanuc", False), ("grbl", False)])
def test_bare_cr_line_ends_are_read_as_lines_and_noted_for_linuxcnc(name, noted):
    # a Fusion program saved with classic Mac line ends (CR alone, no LF): vcnc reads each CR as a line end;
    # rs274 reads lines up to LF only and refuses the file as one overlong line ("Command too long")
    prog = parse_program("G21 G90 G54\rG0 X1 Y2\rG1 Z-1 F100\rM2\r", context=_in_dialect(name))
    assert [b.target.tolist() for b in prog.blocks] == [[101.0, 52.0, 100.0], [101.0, 52.0, -21.0]]
    assert any("bare CR" in n and "Command too long" in n for n in prog.notes) == noted
