"""Readings settled by the shopngc40 set of public LinuxCNC programs compared with LinuxCNC's ``rs274``
(``benchmarks/linuxcnc_diff.py``): machine configs' nc_files and subroutines (Probe Basic and gmoccapy machines,
tool-change and probing macros, plasma and lathe configs) and the questions session 39 left open. The snippets are
written for these tests after those programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"], extra_axes=("a", "b", "c"))


def _y_targets(text: str) -> list[float]:
    return [float(b.target[1]) for b in parse_program(text, context=LINUXCNC).blocks if b.kind == "rapid"]


def test_feed_reads_the_rate_of_the_last_inverse_time_move():
    # interp_inverse.cc inverse_time_rate_straight/_arc store length x F as the feed rate (#<_feed>,
    # interp_namedparams.cc): rs274 moves Y to 4 (2 mm x F2), to 47.1239 (the half circle of radius 5 x F3) and,
    # a rotary move alone, to 270 (90 deg x F3). Before: 100, the G94 F before the G93
    text = ("G21 G90 G0 X0 Y0 Z10\nG94 G1 X2 F100\nG0 Y#<_feed>\nG93 G1 X0 F2\nG0 Y#<_feed>\n"
            "G3 X10 I5 F3\nG0 Y#<_feed>\nG1 A90 F3\nG0 Y#<_feed>\nM2\n")
    assert _y_targets(text)[1:] == pytest.approx([100.0, 4.0, 5 * 3.141592653589793 * 3, 270.0])


def test_feed_before_the_first_inverse_time_move_and_after_g94():
    # G93 itself keeps the feed rate (interp_convert.cc convert_feed_mode); G94 clears it to 0; a later G93 reads
    # the new G94 F until its first move (rs274: Y 100, 0, 50), not an older G93 move's rate
    text = ("G21 G0 X0 Y0\nG1 X1 F100\nG93\nG0 Y#<_feed>\nG1 X3 F2\nG94\nG0 Y#<_feed>\nG1 X4 F50\nG93\n"
            "G0 Y#<_feed>\nM2\n")
    assert _y_targets(text)[1:] == pytest.approx([100.0, 0.0, 50.0])


def test_feed_reads_the_per_revolution_f_under_g95():
    # convert_feed_rate stores the F word itself under G95 (rs274: "S1000 M3 G95 G1 X1 F0.2" then Y#<_feed> moves to
    # Y 0.2). Before: 200, F x S
    text = "G21 G0 X0 Y0\nS1000 M3\nG95 G1 X1 F0.2\nG0 Y#<_feed>\nM2\n"
    assert _y_targets(text)[1:] == pytest.approx([0.2])


def test_feed_of_an_inverse_time_move_in_inch_is_in_inch():
    # the length is in program units: from X 10 mm (0.3937 in) to X 1 in at F2, rs274 1.2126 (inch)
    text = "G21 G0 X10 Y0\nG20 G93 G1 X1 F2\nG0 Y#<_feed>\nM2\n"
    assert _y_targets(text)[1:] == pytest.approx([(1 - 10 / 25.4) * 2 * 25.4])


def test_an_uncalled_subroutine_after_the_program_end_is_not_read():
    # rs274 runs "o100 call [4] / M30 / o200 sub / foo )": nothing calls o200, so LinuxCNC never reads it (its
    # text is no G-code). Before: "8:5: ')' without '('"
    text = "G21\no100 sub\nG0 X#1\no100 endsub\no100 call [4]\nM30\no200 sub\nfoo )\n"
    prog = parse_program(text, context=LINUXCNC)
    assert [float(b.target[0]) for b in prog.blocks] == pytest.approx([4.0])
    assert "lines after M2/M30 not read (LinuxCNC ends the program there)" in prog.notes


def test_a_called_subroutine_after_the_program_end_is_still_read():
    # the label as LinuxCNC compares it (lower case, without blanks, o0100 is o100): the call before the end
    # finds it
    text = "G21\nO0100 CALL [2]\nM2\nfoo )\no100 sub\nG0 X#1\no100 endsub\no< Other > sub\nbar )\no<other> endsub\n"
    prog = parse_program(text, context=LINUXCNC)
    assert [float(b.target[0]) for b in prog.blocks] == pytest.approx([2.0])


@pytest.mark.parametrize("end", ["m 0 2", "M3 0"])
def test_an_end_written_with_blanks_in_its_number_ends_the_text(end):
    # close_and_downcase (interp_read.cc) takes the blanks out: rs274 reads "m 0 2" as M2 and nothing after it.
    # vcnc reads no number with blanks inside: it refuses that line, naming it (before: the line after it)
    with pytest.raises(GCodeError, match=r"<input>:2:\d+: number '[02]' without its letter"):
        parse_program(f"G21 G0 X1\n{end}\nfoo )\n", context=LINUXCNC)


def test_an_end_with_blanks_before_its_number_ends_the_text():
    # "M 30": a blank between the letter and its number, which vcnc reads (rs274: X1, then the end)
    prog = parse_program("G21 G0 X1\nM 30\nfoo )\n", context=LINUXCNC)
    assert [float(b.target[0]) for b in prog.blocks] == pytest.approx([1.0])


def test_g92_of_an_axis_the_machine_lacks_at_0_offsets_nothing():
    # a post's "G92 A0" on a machine without A: the A0 is left out as on a move (noted), as under G52 A0 and
    # G10 L2 A0, and the G92 sets nothing (rs274, whose standalone machine has A, keeps X Y: moves to X 2 Y 1).
    # LinuxCNC with an INI without A refuses the A word ("Bad character 'a' used", rs274ngc_pre.cc: no reader for
    # an axis outside the axis mask). Before: "G92 needs at least one axis word"
    three = MachineContext(dialect=DIALECTS["linuxcnc"])
    prog = parse_program("G21 G0 X1 Y1\nG92 A0\nG0 X2\nM2\n", context=three)
    assert [tuple(b.target[:2]) for b in prog.blocks] == [(1.0, 1.0), (2.0, 1.0)]
    assert "A0 (rotary axis A stays at 0)" in prog.notes
    with pytest.raises(GCodeError, match="G92 needs at least one axis word"):
        parse_program("G21 G0 X1\nG92\nM2\n", context=three)
    with pytest.raises(GCodeError, match="axis word 'A' is not supported"):
        parse_program("G21 G0 X1\nG92 A5\nM2\n", context=three)


def test_an_endsub_of_another_label_returns_and_does_not_close_the_definition():
    # Skyfire-community/SVM2-LinuxCNC subroutines/atc/basic-tool-change.ngc leaves early by "o<toolchange> endsub
    # [1]" followed by M2 inside its o<basic-tool-change> sub: LinuxCNC skips the definition up to the endsub of its
    # own name (interp_read.cc read_o) and returns at the other one when it runs (execute_return checks no label).
    # rs274 runs the file alone (no motion) and a caller of it. Before: "1:1: o<t> sub: no matching endsub" (the
    # M2 after the early endsub was read as the end of the main program)
    text = ("G21\no<t> call [1]\nG0 X#<_value>\nM2\no<t> sub\no1 if [#1 EQ 1]\n o<other> endsub [7]\nM2\n"
            "o1 endif\nG0 X3\no<t> endsub [2]\n")
    prog = parse_program(text, context=LINUXCNC)
    assert [float(b.target[0]) for b in prog.blocks] == pytest.approx([7.0])
    alone = "o<t> sub\no1 if [#1 EQ 1]\n o<other> endsub [1]\nM2\no1 endif\nG0 X3\no<t> endsub [1]\nG0 X5\nM2\n"
    assert [float(b.target[0]) for b in parse_program(alone, context=LINUXCNC).blocks] == pytest.approx([5.0])


def test_an_early_endsub_of_its_own_label_inside_an_if_keeps_the_rest_of_the_file():
    # Skyfire's toolchange.ngc: "O10 if [..] / o<toolchange> endsub [1] / M2 / O10 endif" early in its body, the
    # last endsub and M2 at the end. LinuxCNC's definition ends at the first endsub of its name, so the M2 after it
    # ends the program: rs274 runs this with no motion, as vcnc does; the text after that M2 is still read (the
    # if block the early endsub leaves open closes there: a call runs past it). A guard of the endsub rule above
    # (closing every block inside the subroutine at its endsub refused this: "o10 if: no matching endif")
    text = ("o<tc> sub\no10 if [#1 EQ 1]\n o<tc> endsub [1]\n M2\no10 endif\nG0 X3\no<tc> endsub [2]\n"
            "o<tc> call [0]\nG0 Y#<_value>\nM2\n")
    assert len(parse_program(text, context=LINUXCNC).blocks) == 0
