"""Readings settled by the shopngc39 set of public LinuxCNC programs compared with LinuxCNC's ``rs274``
(``benchmarks/linuxcnc_diff.py``): subroutine libraries and configs of LinuxCNC users (NativeCAM, Probe Basic, QtDragon
and probe-screen configs, cnc-club's features), engraving and laser files written for LinuxCNC. The snippets are
written for these tests after those programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])


@pytest.mark.parametrize("tail", ["(Using default footer.)\n(end)\n%ir.)\n(end)\n", "foo bar )\n",
                                  "G1 X2 (unclosed\n", "%\nG0 X9 Y9\n"])
def test_text_after_the_program_end_is_not_read(tail):
    # overview.adoc 'Format of a Program': "Lines of a file that occur after the end of a program are not to be
    # executed. The interpreter does not even read them." A laser file (pestami/Projects_DIY MidHeaven_0001.nc)
    # holds the rest of an older footer after its M2; rs274 runs it. Before: "3:5: ')' without '('"
    prog = parse_program(f"G21 G0 X1\nM2\n{tail}", context=LINUXCNC)
    assert [b.target[0] for b in prog.blocks] == pytest.approx([1.0])
    assert "lines after M2/M30 not read (LinuxCNC ends the program there)" in prog.notes


def test_text_after_the_program_end_is_still_read_under_fanuc():
    # the rule is LinuxCNC's (its docs above); the other readings are unchanged
    with pytest.raises(GCodeError, match=r":3:9: '\)' without '\('"):
        parse_program("G21 G0 X1\nM30\nfoo bar )\n", context=MachineContext(dialect=DIALECTS["fanuc"]))


def test_a_subroutine_after_the_program_end_is_still_called():
    # rs274 2.9.0~pre1 finds a subroutine defined after the M2 and skips the text around it:
    # "o100 call / M2 / foo bar ) / o100 sub / G0 X5 / o100 endsub" moves to X5
    text = "G21\nG0 X1\no100 call\nM2\nfoo bar )\no100 sub\nG0 X5\no100 endsub\n(end) ]\n"
    prog = parse_program(text, context=LINUXCNC)
    assert [b.target[0] for b in prog.blocks] == pytest.approx([1.0, 5.0])


def test_an_m2_inside_an_o_word_block_does_not_end_the_text():
    # the M2 in a branch ends the program only when the branch runs (rs274: "o100 if [0] / M2 / o100 endif / G0 X3"
    # moves to X3); a line after it is read as before
    prog = parse_program("G21\nG0 X1\no100 if [0]\nM2\no100 endif\nG0 X3\nM2\n", context=LINUXCNC)
    assert [b.target[0] for b in prog.blocks] == pytest.approx([1.0, 3.0])
    with pytest.raises(GCodeError, match=r":5:5: "):
        parse_program("G21\no100 if [0]\nM2\no100 endif\nfoo )\nM2\n", context=LINUXCNC)
