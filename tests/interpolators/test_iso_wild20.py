"""Readings settled by the wild20 set of public programs (LinuxCNC's tests/interp, Bantam Tools' firmware tests)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError


@pytest.mark.parametrize(("width", "end", "noted"), [(252, "\n", False), (253, "\n", True), (252, "\r\n", True),
                                                     (253, "", False), (254, "", True)])
def test_linuxcnc_line_length_limit_is_noted(width, end, noted):
    # linuxcnc.h LINELEN 255; interp_read.cc read_text refuses a line whose fgets buffer is full, 254 bytes with its
    # line end ("Command too long": rs274 refuses 253 characters + LF and 252 + CR LF, runs 252 + LF); vcnc reads
    # it and notes it under the linuxcnc dialect only
    line = "G0 X10 Y10 Z10 (" + "x" * (width - 17) + ")"
    assert len(line) == width
    text = "G21 G90\n" + line + end if end == "" else "G21 G90\n" + line + end + "M2\n"
    for name in ("linuxcnc", "fanuc"):
        prog = parse_program(text, context=MachineContext(dialect=DIALECTS[name]))
        assert [b.target.tolist() for b in prog.blocks] == [[10.0, 10.0, 10.0]]
        long = [n for n in prog.notes if "Command too long" in n]
        assert long == ([f"line 2 is {width + len(end)} bytes long with its line end (LinuxCNC refuses it: "
                         "\"Command too long\", it takes at most 253 bytes, line end included)"]
                        if noted and name == "linuxcnc" else [])


def test_a_bare_cr_file_gets_one_command_too_long_note():
    # a bare-CR file is one line to rs274: its own note says so, the line-length note is not added twice
    prog = parse_program("G21 G90\r" + "G0 X1 (" + "x" * 300 + ")\rM2\r", context=MachineContext())
    assert [n for n in prog.notes if "Command too long" in n] == [n for n in prog.notes if "bare CR" in n]


def test_g10_l20_under_a_g10_rotation_sets_the_offset_in_the_unrotated_system():
    # LinuxCNC tests/interp/g10/g10-l20-while-active: the current and the wanted point are in the rotated system,
    # both turned by R before the offset is their difference (interp_convert.cc convert_setup); checked against
    # the reference, which takes the same rule
    text = ("G21 G54\nG10 L2 P1 X0 Y0 Z0 R90\nG53 G0 X0 Y0 Z0\nG10 L20 P1 X-10\nG1 X0 F100\nY5\n"
            "G10 L20 P1 X3 Y4\nG1 X0 Y0\nM2\n")
    prog = checked_iso(text, MachineContext(dialect=DIALECTS["linuxcnc"]))
    # X-10 at machine 0: offset rot90((0, 0) - (-10, 0)) = (0, 10); X0 is machine (0, 10), Y5 turns to (-5, 10);
    # X3 Y4 at program (0, 5): offset (0, 10) + rot90((0, 5) - (3, 4)) = (-1, 7), so X0 Y0 is machine (-1, 7)
    assert [np.round(b.target, 9).tolist() for b in prog.blocks][1:] == [
        [0.0, 10.0, 0.0], [-5.0, 10.0, 0.0], [-1.0, 7.0, 0.0]]


@pytest.mark.parametrize("name", ["fanuc", "linuxcnc", "grbl"])
def test_a_wincnc_bracket_comment_is_named(name):
    # Vectric's CAMaster post (WinCNC) writes comments in [ ]; no dialect of vcnc reads them
    text = "[TOOLPATH NAME: Drill 1]\nG90\nG0 X1 Y1\nM30\n"
    with pytest.raises(GCodeError, match=r":1:1: '\[TOOLPATH NAME: Drill 1\]': text in square brackets at the "
                                         r"start of a block, a comment as WinCNC \(CAMaster routers\) writes them"):
        parse_program(text, context=MachineContext(dialect=DIALECTS[name]))
    # a bracket without prose keeps the placeholder message
    with pytest.raises(GCodeError, match=r":1:1: '\[xmin\]' in brackets where a word should start"):
        parse_program("[xmin]\nM30\n", context=MachineContext(dialect=DIALECTS[name]))
