"""ISO programs of the sixteenth wild round (issue 18, set /tmp/isowild16): programs of production machining centres
and their shops: Fusion 360 Fanuc/Haas posts, a Haas shop's Renishaw probing and helical thread milling macros, a
Mazak HCN shop's EIA macros (Keycult), a shop's macro B programs with G52 and local subprograms."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")

# a Mazak shop's block skip macro (SET_BSKIP_VARS.EIA): a variable set per skip level, reset on a '/n' line
SKIP_LEVELS = ("G21 G90 G17\n#22 = 900\n#[#22 + 1] = 1\n/1 #[#22 + 1] = 0\n#[#22 + 2] = 1\n/2 #[#22 + 2] = 0\n"
               "G1 X[10 + #901] Y[20 + #902] F100.\n/3 G1 Y5.\nM30\n")


def test_fanuc_optional_block_skip_levels_run_with_their_switches_off():
    # FANUC 0i-MF "Optional block skip" (the additional optional block skip option, /2-/9; /1 is /): with every
    # switch off each '/n' line runs, so #901 and #902 end at 0 and the last line's move is made
    prog = checked_iso(SKIP_LEVELS, FANUC)
    assert [b.target.tolist()[:2] for b in prog.blocks] == [[10.0, 20.0], [10.0, 5.0]]
    assert [b.line for b in prog.blocks] == [7, 8]


@pytest.mark.parametrize("context", [HAAS, LINUXCNC])
def test_a_skip_level_is_named_where_the_dialect_has_only_block_delete(context):
    with pytest.raises(GCodeError, match=r":4:1: '/1': optional block skip level 1 \(Fanuc's additional optional "
                                         r"block skip /2-/9\), which this dialect does not have \(--dialect fanuc "
                                         r"reads it\)"):
        parse_program(SKIP_LEVELS, context=context)


def test_block_delete_alone_still_runs_on_every_dialect():
    for context in (FANUC, HAAS, LINUXCNC):
        prog = checked_iso("G21 G90 G17\n/G1 X10. F100.\n/ G1 Y5.\nM30\n", context)
        assert prog.blocks[-1].target.tolist()[:2] == [10.0, 5.0]


def test_a_missing_renishaw_probing_macro_is_named():
    # a Haas shop's WCS alignment macro: "G65 P9832" (probe on), "G65 P9810 Z.." (protected positioning), whose
    # programs stay in the control (Renishaw Inspection Plus, H-2000-6222)
    text = "G20 G90 G17\nG0 X0 Y0\nG65 P9832\nG65 P9810 Z1.0 F50.\nM30\n"
    with pytest.raises(GCodeError, match=r":3:1: G65 macro call: program O9832 is neither in this file nor in a "
                                         r"program file of its folder \(a Renishaw Inspection Plus probing macro "
                                         r"stored in the machine's control"):
        parse_program(text, context=HAAS)
    with pytest.raises(GCodeError, match=r"program O1234 is neither in this file nor in a program file of its "
                                         r"folder \(got"):
        parse_program(text.replace("P9832", "P1234"), context=HAAS)


def test_m98_with_macro_arguments_is_named_as_needing_g65():
    # a Haas shop's thread milling main program: "M98 P9998 I10. D2.0 Z-1.0 T10 V.1 F40. R1.5 X1.0 Y2.0", whose
    # O9998 reads #4, #7, #26 ... as G65 arguments; M98 passes none and runs the words first, where I is refused
    text = "G20 G90 G17\nG0 X0 Y0 Z1.\nM98 P9998 I10. D2.0 Z-1.0 F40. R1.5 X1.0 Y2.0\nM30\nO9998\nG1 X2. F10.\nM99\n"
    with pytest.raises(GCodeError, match=r":3:11: word I is only allowed on arcs .*M98 passes no arguments to its "
                                         r"subprogram: a call with arguments is G65 P<program> \(macro B\)"):
        parse_program(text, context=HAAS)
    with pytest.raises(GCodeError, match=r"a G02/G03 meant\?"):
        parse_program("G20 G90 G17\nG0 X1. I10.\nM30\n", context=HAAS)


def test_m97_under_linuxcnc_runs_as_haas_runs_it_with_a_note():
    # a shop's macro B program (isowild16): "M97 P5 L#5" repeats the local subprogram N5 at six angles; read with
    # the default dialect it runs as a Haas runs it, and the note says LinuxCNC refuses M97 (rs274 2.9.0~pre1:
    # "Unknown m code used: M97")
    text = "G21 G90 G17\nG0 X0 Y0 Z5\nM97 P5 L2 (two passes)\nM30\nN5 G91 G1 X1. F100.\nG90\nM99\n"
    prog = checked_iso(text, LINUXCNC)
    assert [b.target.tolist()[0] for b in prog.blocks[1:]] == [1.0, 2.0]
    assert any('LinuxCNC refuses them: "Unknown m code used"; --dialect haas' in n for n in prog.notes)
    assert not any("M97" in n for n in checked_iso(text, HAAS).notes)
    commented = checked_iso("G21 G90\n(M97 P5 is not used)\nG1 X1. F100. ; M97\nM30\n", LINUXCNC)
    assert not any("M97" in n for n in commented.notes)


def test_a_machine_variable_below_100000_is_named_as_the_machines():
    # a Mazak HCN shop's pallet macro (SWAP_PALLET.EIA): "IF [#51998 EQ 1.] THEN M912"
    with pytest.raises(GCodeError, match=r"#51998 out of range \(#51998: a system variable of the machine's "
                                         r"control, which vcnc does not model"):
        parse_program("G21 G90\nIF [#51998 EQ 1.] THEN #100 = 1\nG1 X1. F100.\nM30\n", context=FANUC)
    with pytest.raises(GCodeError, match=r"#51998 out of range \(got"):
        parse_program("G21 G90\n#100 = #51998\nG1 X1. F100.\nM30\n", context=LINUXCNC)


def test_reading_the_macro_alarm_variable_is_named():
    # a Haas shop's thread milling macro: "IF [#20 EQ 0] THEN #3000 = 4 (...)" per argument, then
    # "IF [#3000 NE 0] GOTO 9999": #3000 is written to raise an alarm; what a read gives no manual says
    text = "G20 G90\n#20 = 10.\nIF [#20 EQ 0] THEN #3000 = 4 (TOOL MISSING)\nIF [#3000 NE 0] GOTO 9\nN9 M30\n"
    with pytest.raises(GCodeError, match=r":4:5: #3000 read: it is the macro alarm, which a program writes to stop "
                                         r"with an alarm"):
        parse_program(text, context=HAAS)
    with pytest.raises(GCodeError, match=r":3:.*macro alarm #3000 = 4"):
        parse_program(text.replace("#20 = 10.", "#20 = 0"), context=HAAS)


@pytest.mark.parametrize(("code", "column", "message"), [
    ("G05.1 Q1 R5", 7, r"unknown word 'Q1' outside a drilling cycle \(G05.1 Q1 / Q0 is Fanuc's AI contour control, "
                       r"look-ahead on / off: --dialect fanuc; LinuxCNC's G5.1 is a quadratic spline through I J\)"),
    ("G08 P1", 1, r"G8 lathe radius mode: not supported \(G08 P1 / P0 with a P is Fanuc's AI advanced preview "
                  r"control, a mill's look-ahead: --dialect fanuc\)")])
def test_fanuc_look_ahead_codes_are_named_under_linuxcnc(code, column, message):
    # high-speed options of a Fanuc post read with the default dialect, where G5.1 is a spline and G8 lathe radius
    # mode; the fanuc dialect reads them as look-ahead, which changes no point of the path
    text = f"G21 G90 G17\n{code}\nG0 X0 Y0 Z5\nG1 X10. F1000.\nM30\n"
    with pytest.raises(GCodeError, match=f":2:{column}: {message}"):
        parse_program(text, context=LINUXCNC)
    prog = checked_iso(text, FANUC)
    assert prog.blocks[-1].target.tolist() == [10.0, 0.0, 5.0]
    if code.startswith("G08"):  # a bare G8 is LinuxCNC's lathe radius mode, its default at power up: no motion
        prog = checked_iso(text.replace("G08 P1", "G8"), LINUXCNC)
        assert prog.blocks[-1].target.tolist() == [10.0, 0.0, 5.0]


def test_the_macro_alarm_and_message_stop_set_under_linuxcnc_are_noted():
    # a Haas shop's macro read with the default dialect: LinuxCNC takes #3000 and #3006 as parameters like any other
    # (the program runs on), where a Haas raises macro alarm 4 at line 3 and stops
    text = "G21 G90\n#20 = 0\nIF [#20 EQ 0] THEN #3000 = 4 (TOOL MISSING)\n#3006 = 1 (CHECK)\nG1 X1. F100.\nM30\n"
    prog = checked_iso(text, LINUXCNC)
    assert prog.blocks[-1].target.tolist() == [1.0, 0.0, 0.0]
    assert "#3000 set at line 3 as a plain parameter (a Fanuc or Haas control raises macro alarm n there and stops: " \
           "--dialect fanuc or haas)" in prog.notes
    assert any(n.startswith("#3006 set at line 4 as a plain parameter") for n in prog.notes)
    with pytest.raises(GCodeError, match=r":3:20: macro alarm #3000 = 4 \(TOOL MISSING\)"):
        parse_program(text, context=HAAS)


@pytest.mark.parametrize(("block", "column", "message"), [
    ("G82 X1. Y1. Z-1. R1. P1. F100.\nP2.", 1, r"word P in a block of the modal G82 drilling cycle with dwell that "
                                                r"does not name it: LinuxCNC refuses it"),
    ("G83 X1. Y1. Z-1. R1. Q0.5 F100.\nQ0.3", 1, r"word Q in a block of the modal G83 peck drilling cycle that does "
                                                  r"not name it: LinuxCNC refuses it"),
    ("G81 X1. Y1. Z-1. R1. F100.\nG80 P1.", 5, r"word P needs G04 \(dwell\)"),
    ("G73 X1. Y1. Z-1. R1. Q0.5 F100.\nG0 X0 Q1.", 7, r"unknown word 'Q1.' outside a drilling cycle")])
def test_p_and_q_outside_the_block_that_names_their_cycle_are_refused_under_linuxcnc(block, column, message):
    # review26's reproducers: rs274 2.9.0~pre1 refuses each ("P word with no G2 G3 G4 G10 G64 ... G82 G86 G88 G89
    # ... to use it", "Q word with no G5, G10, G64, G73, G76, G83 ... that uses it": interp_check.cc
    # check_other_codes reads the G codes of the block itself); Fanuc and Haas read the modal cycle's new P or Q
    text = f"G21 G90 G17\nG0 X0 Y0 Z5.\n{block}\nG80\nM2\n"
    with pytest.raises(GCodeError, match=f":4:{column}: {message}"):
        parse_program(text, context=LINUXCNC)
