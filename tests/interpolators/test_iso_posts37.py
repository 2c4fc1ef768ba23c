"""Constructs the posts of SheetCAM, CamBam, Siemens NX Post Builder and Mastercam write, read as their controls read
them (session 37, posts37).

Each program is hand-written in the output style of the post named in its test (formats, modal suppression and
block order as the post prints them); the posts were read, not run."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])

#: SheetCAM's Mach3 floating-head plasma posts (``OnPenDown``): ``G28.1 Z3.00`` (Mach3: to Z3, then reference
#: Z onto the floating head's switch), ``G92 Z0.0``, ``G00 Z<pierce height>``, ``M03``, ``G04 P<delay>``.
SHEETCAM_FLOATING_HEAD = ("(Filename: part.tap)\n(Post processor: Mach3 plasma floating head.scpost)\n"
                          "G21 (Units: Metric)\nG40 G90\nF1\n(Part: part)\nG00 Z10.0000\nX20.0000 Y10.0000\n"
                          "G28.1 Z3.00\nG92 Z0.0\nG00 Z3.0000\nM03\nG04 P0.5\nG01 Z1.5000 F1500.0\n"
                          "G03 X20.0000 Y10.0000 I-10.0000 J0.0000\nM05\nG00 Z10.0000\nG00 X0.0000 Y0.0000\nM05 M30\n")


def test_linuxcnc_axis_words_of_g28_1_move_by_the_modal_motion():
    # LinuxCNC rs274ngc interp_check.cc enhance_block: of the group 0 codes only G10, G28, G30, G52 and G92 use axis
    # words ("mode_zero_covets_axes"); "if there is an axis value in the block and no g-code to use it ... set
    # motion_to_be to be the last motion saved". rs274 (benchmarks/linuxcnc_diff.py) runs "G28.1 Z3.00" as: store
    # the position, then G0 to Z3. Before: vcnc dropped the Z word; the G92 Z0 then zeroed Z at 10, not 3, and the
    # pierce ran 7 mm high (Z 13 where rs274 goes to 6)
    prog = checked_iso(SHEETCAM_FLOATING_HEAD, LINUXCNC)
    z = [(b.line, round(float(b.target[2]), 6)) for b in prog.blocks if b.kind != "dwell"]
    assert z[2:5] == [(9, 3.0), (11, 6.0), (14, 4.5)]  # G28.1's G0 to Z3; then Z3, Z1.5 above the new zero
    # the stored position is where the tool stood before the move (convert_modal_0 runs before convert_motion)
    stored = parse_program("G21 G90\nG0 X1 Y2 Z10\nG1 F100 X2\nG28.1 X5\nG0 Z20\nG28\nM2\n", context=LINUXCNC)
    assert [b.target.tolist() for b in stored.blocks][-3:] == [[5.0, 2.0, 10.0], [5.0, 2.0, 20.0], [2.0, 2.0, 10.0]]


@pytest.mark.parametrize("code", ["G30.1", "G92.1", "G92.2", "G92.3", "G4 P0.5"])
def test_linuxcnc_other_group_0_codes_leave_their_axis_words_to_the_motion(code):
    # the same rule for G30.1, G92.1-G92.3 and a dwell with its P (rs274: the dwell, then the move). Before: the Z
    # word was dropped (G30.1, G92.x) or refused ("word Z not allowed in a dwell block")
    prog = parse_program(f"G21 G90\nG0 X1 Y2 Z10\nG92 X0\n{code} Z3\nG1 X5 F100\nM2\n", context=LINUXCNC)
    moves = [b for b in prog.blocks if b.kind != "dwell"]
    assert moves[1].line == 4 and moves[1].kind == "rapid" and float(moves[1].target[2]) == 3.0
    # G92.1/G92.2 dropped the G92 shift of X (1 mm) before the move, G92.3 brought back the one saved with it
    assert float(moves[2].target[0]) == (6.0 if code in ("G30.1", "G92.3", "G4 P0.5") else 5.0)


def test_linuxcnc_dwell_with_p_leaves_x_to_the_motion():
    # with P and X, X is the modal motion's (LinuxCNC: the dwell, then the move), not the dwell time (G04 X<s>
    # alone stays Fanuc's dwell, noted). Before: "G04 needs exactly one of P or X"
    dwell_x = checked_iso("G21 G90\nG0 X1 Y2 Z10\nG1 F100\nG4 P0.5 X3\nM2\n", LINUXCNC)
    assert [(b.kind, float(b.target[0])) for b in dwell_x.blocks][1:] == [("dwell", 1.0), ("line", 3.0)]
