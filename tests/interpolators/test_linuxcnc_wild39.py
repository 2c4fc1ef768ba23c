"""Readings settled by the shopngc39 set of public LinuxCNC programs compared with LinuxCNC's ``rs274``
(``benchmarks/linuxcnc_diff.py``): subroutine libraries and configs of LinuxCNC users (NativeCAM, Probe Basic, QtDragon
and probe-screen configs, cnc-club's features), engraving and laser files written for LinuxCNC. The snippets are
written for these tests after those programs."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import load_program, parse_program
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


#: LinuxCNC's predefined named parameters of the modal state, read by configs' subroutines (NativeCAM's
#: shcs_size.ngc "#<_metric>", lead_out.ngc "#<_ccomp>", Probe Basic's backup_status.ngc "#<_retract_old_z>",
#: probe-screen's _psng_modal_save.ngc "#<_absolute>"), with the values rs274 2.9.0~pre1 prints for them
#: ("(DEBUG, #<_plane>)" after "G21 G0 X0": 170, ...; after G20 G98 G55 G90.1 G1 F3 S1200 T5: 10, 0, 550, ...).
NAMED_STATE = ("G21 G0 X0\n#1 = #<_motion_mode>\n#2 = #<_plane>\n#3 = #<_ccomp>\n#4 = #<_metric>\n"
               "#5 = #<_absolute>\n#6 = #<_units_per_minute>\n#7 = #<_coord_system>\n#8 = #<_retract_r_plane>\n"
               "#9 = #<_ijk_absolute_mode>\n#10 = #<_tool_offset>\n"
               "G20 G98 G55 G90.1 S1200 T5 G1 X0 F3\n#11 = #<_motion_mode>\n#12 = #<_imperial>\n"
               "#13 = #<_coord_system>\n#14 = #<_retract_old_z>\n#15 = #<_ijk_absolute_mode>\n#16 = #<_feed>\n"
               "#17 = #<_rpm>\n#18 = #<_selected_tool>\n#19 = #<_incremental>\n"
               "G21 G18 G59.2\n#20 = #<_plane>\n#21 = #<_coord_system>\n"
               "G0 X[#1 + #2 + #3 + #4 + #5 + #6 + #7 + #8 + #9 + #10] Y[#11 + #12 + #13 + #14 + #15 + #16 + #17 + #18 "
               "+ #19] Z[#20 + #21]\nM2\n")


def test_the_predefined_named_parameters_of_the_modal_state():
    # overview.adoc "Predefined Named Parameters", interp_namedparams.cc lookup_named_param. Before: "named parameter
    # #<_motion_mode> is read before it is set"
    prog = parse_program(NAMED_STATE, context=LINUXCNC)
    x = 0 + 170 + 400 + 1 + 1 + 1 + 540 + 1 + 0 + 0  # G0, G17, G40, mm, G90, G94, G54, G99 (power-on), G91.1, none
    y = 10 + 1 + 550 + 1 + 1 + 3 + 1200 + 5 + 0  # in inch: G1, G55, G98, G90.1, F3, S1200, T5, G90
    assert prog.blocks[-1].target.tolist() == pytest.approx([x, y, 180 + 592])
    with pytest.raises(GCodeError, match=r"named parameter #<_metric> is read-only"):
        parse_program("G21\n#<_metric> = 5\nM2\n", context=LINUXCNC)


def test_the_call_level_counts_the_o_word_calls():
    # interp_namedparams.cc NP_CALL_LEVEL: 0 in the main program, 1 in a subroutine it calls
    text = "G21\no100 sub\nG0 X[#<_call_level> + 1]\no100 endsub\nG0 Y[#<_call_level> + 1]\no100 call\nM2\n"
    prog = parse_program(text, context=LINUXCNC)
    assert prog.blocks[-1].target.tolist() == pytest.approx([2.0, 1.0, 0.0])


@pytest.mark.parametrize("level", [1, 10, 11])
def test_a_tool_table_entry_for_tool_0_is_refused(level):
    # Probe Basic's lathe touch-off subroutines write "G10 L1 P #5400 X[..]" (5400 = the tool in the spindle), which
    # is 0 before any tool change; LinuxCNC refuses it (interp_check.cc: "P value out of range with G10 L1" for
    # P < 1, rs274 2.9.0~pre1 so). Before: vcnc ran it
    with pytest.raises(GCodeError, match=rf":2:\d+: G10 L{level} P0: no tool 0 in the tool table"):
        parse_program(f"G21\nG10 L{level} P#5400 Z1\nG0 X1\nM2\n", context=LINUXCNC)
    prog = parse_program(f"G21\nG10 L{level} P1 Z1\nG0 X1\nM2\n", context=LINUXCNC)
    assert prog.blocks[-1].target[0] == pytest.approx(1.0)


def test_the_g28_and_g30_positions_may_be_written():
    # a tool-change subroutine (sttts/linuxcnc-configs toolchange_touch_off.ngc) moves the G30 position and puts it
    # back: "#5181 = #<_G30_oldX>"; LinuxCNC's G28/G30 read #5161-#5169 / #5181-#5189 (interp_convert.cc
    # convert_home), rs274 2.9.0~pre1 runs this program to the same points. Before: "parameter #5181 is read-only"
    text = ("G21 G0 X1 Y2 Z3\nG30.1\n#<_ox> = #5181\n#5181 = 10.5\n#5182 = [#5182 - 3]\n#5163 = 7\nG30\nG0 X0\n"
            "G28\n#5181 = #<_ox>\nG30 Z9\nG30\nM2\n")
    ends = [b.target for b in parse_program(text, context=LINUXCNC).blocks]
    want = [[1, 2, 3], [10.5, -1, 3], [0, -1, 3], [0, 0, 7], [0, 0, 9], [0, 0, 3], [1, -1, 3]]
    assert np.allclose(ends, want)


def test_a_label_reused_in_a_subroutine_file_is_noted(tmp_path):
    # NativeCAM's lib/utilities/isect_line_arc.ngc opens "o10 if" twice in its body (the second inside another if):
    # rs274 refuses the second when it runs ("28: duplicate O-word label - already defined in line 10"), vcnc runs
    # both and notes it, as it notes it in the main file. Before: no note for a called file
    (tmp_path / "s.ngc").write_text("o<s> sub\no10 if [1]\nG0 X1\no10 endif\no20 if [1]\n  o10 if [1]\n  G0 X2\n"
                                    "  o10 endif\no20 endif\no<s> endsub\nM2\n")
    (tmp_path / "main.ngc").write_text("G21\no<s> call\nM2\n")
    prog = load_program(tmp_path / "main.ngc", context=LINUXCNC)
    assert [b.target[0] for b in prog.blocks] == pytest.approx([1.0, 2.0])
    assert any(n.startswith("O-word label o10 opens 2 if blocks") for n in prog.notes)
