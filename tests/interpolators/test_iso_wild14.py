"""ISO programs of the fourteenth wild round (issue 18, set /tmp/isowild14): CAMotics' examples, a LinuxCNC plasma
table's and a LinuxCNC knee mill's shop programs (o<name> subroutines beside them, user M codes), Fanuc-style test
programs of a G-code plotter, a mould shop's Fanuc macro B subprograms, ncEFI's templates, UGS's and gSender's
test files, qtpyvcp's samples. What their controls refuse is refused naming what the text is."""

from __future__ import annotations

import pytest

from interpolators import load_program, parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

PLACEHOLDER = r"a template's placeholder '\({}\)' where the number goes: a generator fills it in, so the file is a " \
              r"template, not a program"


@pytest.mark.parametrize(("line", "column", "letter", "name"), [
    ("G00 Z(GCODE_OP_SAFEZ)", 5, "Z", "GCODE_OP_SAFEZ"),  # ncEFI's ncPRG_end.nc
    ("F(GCODE_OP_BFEED)      (base feed rate, set in code)", 1, "F", "GCODE_OP_BFEED"),  # its ncPRG_start.nc
    ("G1 X10 Y ( SAFE_Y )", 8, "Y", "SAFE_Y")])
@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl", "fanuc", "haas"])
def test_a_template_placeholder_is_named(line, column, letter, name, dialect):
    with pytest.raises(GCodeError, match=f":2:{column}: malformed number for word {letter} "
                                         f"\\({PLACEHOLDER.format(name)}\\)"):
        parse_program(f"G21 G90\n{line}\nM2\n", context=MachineContext().with_dialect(dialect))


def test_a_comment_of_prose_after_a_bare_axis_letter_is_no_placeholder():
    # lowercase prose, or one word without '_': still the 3D printer's axis flag
    for line in ("G1 X (move)", "G1 X (SAFE)"):
        with pytest.raises(GCodeError, match=r":2:4: malformed number for word X \(an axis letter without its "
                                             r"number, as 3D printer firmware such as Marlin takes axis flags\)"):
            parse_program(f"G21 G90\n{line}\nM2\n", context=MachineContext())


LATHE = r"\(I and K without J: a ZX arc as a lathe program writes it, a lathe starting in G18; a mill program " \
        r"selects G18 before it\)"


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas"])
def test_a_lathe_arc_in_g17_is_named(dialect):
    # a turning program (T01M06, G97, X diameters and Z) from a plotter's samples: its G03 with I and K
    text = "G21 G90 F100\nG0 X191.735 Z1.\nG1 Z0. X192.735\nG03 X193.84 Z-.366 I0. K-.6\nM30\n"
    with pytest.raises(GCodeError, match=f":4:24: word K is outside the arc plane \\(G17\\) {LATHE}"):
        parse_program(text, context=MachineContext().with_dialect(dialect))
    # (its X are diameters: the arc lies on its circle only so.) A ZX quarter circle with the plane named runs,
    # checked by the reference: from (0, 0, 0) about (0, 0, -0.6) to (0.6, 0, -0.6)
    prog = checked_iso("G18 G21 G90 F100\nG0 X0 Z1\nG1 Z0\nG03 X.6 Z-.6 I0 K-.6\nM30\n",
                       MachineContext().with_dialect(dialect))
    assert prog.blocks[-1].target.tolist() == pytest.approx([0.6, 0.0, -0.6])


def test_a_j_word_or_a_y_move_gets_no_lathe_hint():
    for arc in ("G03 X1 Y1 I0 J1 K2", "G03 X1 Y1 Z-1 I0 K2"):
        with pytest.raises(GCodeError, match=r"outside the arc plane \(G17\) \(got") as err:
            parse_program(f"G21 G90 F100\n{arc}\nM30\n", context=MachineContext())
        assert "lathe" not in str(err.value)


BEYOND = r"\(#901200: beyond the Fanuc/Haas variables vcnc models, locals #1-#33, common #100-#199 and #500-#999, " \
         r"Haas #10000-#10999, system variables below #100000; the larger common-variable ranges that some controls " \
         r"add as an option are not modelled\)"


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_variable_beyond_the_modelled_ones_is_named_under_macro_b(dialect):
    # a mould shop's subprogram keeps the work offset in #901200 ("#901200=#4012")
    ctx = MachineContext().with_dialect(dialect)
    with pytest.raises(GCodeError, match=f":2:1: parameter #901200: system parameters cannot be set {BEYOND}"):
        parse_program("G21 G90 G54\n#901200=#4012\nM30\n", context=ctx)
    with pytest.raises(GCodeError, match=f":2:5: parameter number #901200 out of range {BEYOND}"):
        parse_program("G21 G90\nG0 X#901200\nM30\n", context=ctx)


def test_linuxcnc_keeps_its_own_message_for_such_a_number():
    with pytest.raises(GCodeError, match=r":1:1: parameter #901200: system parameters cannot be set \(got"):
        parse_program("#901200=1\n", context=MachineContext())


SUB = "o<drill_here> sub\n\tM101 (enable Z)\n\tG0 X#1 Y#2\n\tG1 Z#3 F10\n\tG0 Z0.5\no<drill_here> endsub\nM2\n"


def test_a_user_m_code_beside_the_program_runs_under_linuxcnc(tmp_path):
    """LinuxCNC INI [DISPLAY] PROGRAM_PREFIX: "the location for user-defined M-codes ... searched for the file
    name before the subroutine path and user M path". A knee mill's programs call subroutine files that switch
    its Z on with M101 (a halcmd script in nc_files): the script beside them is found as the subroutine is."""
    (tmp_path / "drill_here.ngc").write_text(SUB)
    (tmp_path / "M101").write_text("#!/bin/bash\nhalcmd sets z-override True\nexit 0\n")
    (tmp_path / "part.ngc").write_text("G20\nG10 L1 P1 Z0 R.125\nT1 M6\nG54\no<drill_here> call [1][2][-.3]\n"
                                       "o<drill_here> call [3][2][-.3]\nM2\n")
    prog = load_program(tmp_path / "part.ngc", context=MachineContext())
    inch = 25.4
    ends = [[x * inch, 2 * inch, z * inch] for x, z in ((1, 0), (1, -0.3), (1, 0.5), (3, 0.5), (3, -0.3), (3, 0.5))]
    assert [b.target.tolist() for b in prog.blocks] == [pytest.approx(e) for e in ends]
    # the same file beside a program read in a Fanuc dialect: the builder's M code, refused as before
    (tmp_path / "part.nc").write_text("G20 G90\nM101\nG0 X1\nM30\n")
    with pytest.raises(GCodeError, match=r":2:1: machine-specific M code 'M101' .*: M101 not found "
                                         r"\(folders: none given\)"):
        load_program(tmp_path / "part.nc", context=MachineContext().with_dialect("fanuc"))


def test_g10_l1_sets_the_radius_g41_then_uses():
    # the knee mill's header "G10 L1 P1 Z0.0 R.125 ; set tool": a 1/4 in end mill, then a compensated square
    text = ("G20 G90 G17 G40\nG10 L1 P1 Z0.0 R.125\nT1 M6\nG0 X-1 Y-1\nG41 D1 G1 X0 Y0 F10\nX2\nY2\nX0\nY0\n"
            "G40 G0 X-1 Y-1\nM2\n")
    prog = checked_iso(text, MachineContext())
    inch = 25.4
    # the square's edges run 0.125 in inside it: its first corners at (1.875, 0.125) and (1.875, 1.875) in
    corners = [b.target.tolist() for b in prog.blocks[3:5]]
    assert corners[0] == pytest.approx([1.875 * inch, 0.125 * inch, 0.0])
    assert corners[1] == pytest.approx([1.875 * inch, 1.875 * inch, 0.0])


def test_break_and_continue_with_comments_after_their_words():
    """FluidNC's flow control test suite (LinuxCNC-style o-words, 59 tests, all passed here): its TEST 59/60 put
    a comment after every o-word; a break leaves the loop at 5, a continue skips the third count."""
    text = ("G21 G90\n#1 = 0\no1 while [#1 LT 10] (loop)\n  o2 if [#1 EQ 5] (stop here)\n    o1 break (leave)\n"
            "  o2 endif (inner)\n  #1 = [#1 + 1]\no1 endwhile (done)\nG0 X#1\n"
            "#2 = 0\n#3 = 0\no3 while [#2 LT 5] (count)\n  #2 = [#2 + 1]\n  o4 if [#2 EQ 3] (skip)\n"
            "    o3 continue (next)\n  o4 endif\n  #3 = [#3 + 1]\no3 endwhile\nG0 Y#2 Z#3\nM2\n")
    prog = checked_iso(text, MachineContext())
    assert [b.target.tolist() for b in prog.blocks] == [[5.0, 0.0, 0.0], [5.0, 5.0, 4.0]]


ABSOLUTE = "G21 G90\nG90.1\nG0 X-22.135 Y-4.495\nG2 X-26.513 Y4.495 I-24.273 J0.025 F244.3\nM30\n"


def test_g90_1_is_refused_under_grbl_and_runs_where_the_control_has_it():
    """grbl 1.1 gcode.c: "if ((mantissa != 10) || (int_value == 90)) { FAIL(STATUS_GCODE_UNSUPPORTED_COMMAND); }
    // [G90.1 not supported]" (grblHAL alike): its I J K are offsets from the start, so a program written for
    absolute centres (a plotter's samples: 'G2X-26.513Y4.495Z1.977I-24.273J0.025') cannot run there."""
    with pytest.raises(GCodeError, match=r":2:1: G90.1 absolute arc centres: grbl has none \(gcode.c: '\[G90.1 not "
                                         r"supported\]', error 20 unsupported command; its I J K are always offsets "
                                         r"from the arc's start\)"):
        parse_program(ABSOLUTE, context=MachineContext().with_dialect("grbl"))
    # LinuxCNC G90.1: the centre (-24.273, 0.025), radius 5 at both ends; checked by the reference
    prog = checked_iso(ABSOLUTE, MachineContext())
    assert prog.blocks[-1].target.tolist() == pytest.approx([-26.513, 4.495, 0.0])
    # G91.1 is grbl's own mode ("G91.1 does nothing"): the same arc written as offsets runs
    prog = checked_iso(ABSOLUTE.replace("G90.1", "G91.1").replace("I-24.273 J0.025", "I-2.138 J4.52"),
                       MachineContext().with_dialect("grbl"))
    assert prog.blocks[-1].target.tolist() == pytest.approx([-26.513, 4.495, 0.0])


def test_the_absolute_centre_hint_says_grbl_lacks_g90_1():
    # the plotter sample's arc without G90.1: off its circle as offsets, on it as absolute centres
    text = ABSOLUTE.replace("G90.1\n", "")
    with pytest.raises(GCodeError, match=r":3:20: arc end point is not on the circle.*; I/J/K as absolute centre "
                                         r"coordinates would fit: a program for a control with LinuxCNC's G90.1, "
                                         r"which grbl lacks \(got 'I-24.273'\)"):
        parse_program(text, context=MachineContext().with_dialect("grbl"))
    with pytest.raises(GCodeError, match=r"; I/J/K as absolute centre coordinates \(LinuxCNC G90.1\) would fit"):
        parse_program(text, context=MachineContext().with_dialect("fanuc"))


@pytest.mark.parametrize(("line", "note"), [
    ("G64 P0.01", "G64 path blending"),  # UGS's test files of a ShapeOko (pcb and CAM outputs)
    ("G98", "G98 canned cycle retract to the initial level"),
    ("G59.1", "G59.1 work offset run as grblHAL runs it (grbl 1.1 refuses it: error 23)"),  # "value not integer"
    ("G92.2", "G92.2 G92 offset suspended"),
    ("T1 M6", "M6 tool change"),  # gSender's and UGS's examples, a Fusion MPCNC post
    ("M62 P1", "M62 digital output"),  # FluidNC's user_io test, the MPCNC post's relays
    ("M48", "M48 overrides enabled")])
def test_codes_grbl_refuses_and_grblhal_runs_are_noted(line, note):
    """grbl 1.1 gcode.c refuses them (error 20: "default: FAIL(STATUS_GCODE_UNSUPPORTED_COMMAND)"); grblHAL's
    gcode.c runs them (G64 when built with path blending, M6 per its tool change mode, M62 on a board with
    outputs): they run as there, with a note; the moves are those of the reference."""
    prog = checked_iso(f"G21 G90\nG0 X1 Y2\n{line}\nG1 X3 F100\nM30\n", MachineContext().with_dialect("grbl"))
    assert (note if "error" in note else f"{note} run as grblHAL runs it (grbl 1.1 refuses it: error 20)") \
        in prog.notes
    assert prog.blocks[-1].target.tolist() == [3.0, 2.0, 0.0]


def test_g61_1_is_refused_under_grbl():
    # FluidNC's parser test streams "G61.1" among the codes it checks: grbl 1.1 answers error 20
    with pytest.raises(GCodeError, match=r":2:1: G61.1 exact stop mode: grbl has none \(gcode.c: '\[G61.1 not "
                                         r"supported\]', error 20 unsupported command; G61 is its only path mode\)"):
        parse_program("G21 G90\nG61.1\nG0 X1\n", context=MachineContext().with_dialect("grbl"))
    prog = checked_iso("G21 G90\nG61\nG0 X1\nM30\n", MachineContext().with_dialect("grbl"))
    assert prog.blocks[-1].target.tolist() == [1.0, 0.0, 0.0]
