"""ISO programs of the eleventh wild round (issue 18, set /tmp/isowild10): how the ones no target control
runs are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas"])
@pytest.mark.parametrize("text, column, sign, operator", [
    # a PC control's sample programs compare with C's signs: a call repeated 'L[#100 = 0]' times, a flag
    # '#101 = [#100 > 5]'; LinuxCNC ("Binary Operators") and Fanuc macro B write EQ NE GT GE LT LE
    ("G21 G90\n#100 = 1\nM98 P2 L[#100 = 0]\nM30\nO2\nG0 X1\nM99\n", 15, "=", "EQ"),
    ("G21 G90\n#100 = 7\n#101 = [#100 > 5]\nG0 X#101\nM30\n", 14, ">", "GT"),
    ("G21 G90\n#100 = 7\n#101 = [#100 >= 5]\nG0 X#101\nM30\n", 14, ">=", "GE"),
    ("G21 G90\n#100 = 7\n#101 = [#100 != 5]\nG0 X#101\nM30\n", 14, "!=", "NE"),
])
def test_a_comparison_written_with_a_sign_names_the_two_letter_operator(name, text, column, sign, operator):
    with pytest.raises(GCodeError, match=rf"comparison written '{sign}' in an expression: G-code compares with "
                                         rf"the two-letter operators EQ NE GT GE LT LE \('{sign}' is {operator}; "
                                         rf"LinuxCNC and Fanuc macro B read no sign\).*expected \[a {operator} b\]") \
            as err:
        parse_program(text, context=_in_dialect(name))
    assert (err.value.line, err.value.column) == (3, column)


def test_the_two_letter_comparisons_still_compute():
    prog = parse_program("G21 G90\n#100 = 7\n#101 = [#100 GT 5]\n#102 = [#100 EQ 5]\nG0 X#101 Y#102\nM30\n",
                         context=_in_dialect("linuxcnc"))
    assert prog.blocks[-1].target[:2].tolist() == [101.0, 50.0]


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc"])
@pytest.mark.parametrize("head", [":O1001", ": O 1001"])
def test_colon_and_o_together_before_a_program_number_are_named(name, head):
    # a handheld router's Fusion post writes '%' then ':O1001': ':' is the program-number address of ISO code
    # and O that of EIA code; no manual shows the two together, so the number is not guessed
    with pytest.raises(GCodeError, match=r":2:1: ':' and 'O' both before the program number: ':' is ISO code's "
                                         r"program-number address, O EIA code's; a program number takes one of them"
                                         r".*expected O1001 or :1001"):
        parse_program(f"%\n{head}\nG21 G90 G0 X0 Y0\nM30\n%\n", context=_in_dialect(name))


def test_a_colon_program_number_alone_is_still_read():
    prog = parse_program("%\n:1001\nG21 G90 G0 X5 Y0\nM30\n%\n", context=_in_dialect("fanuc"))
    assert prog.blocks[-1].target[:2].tolist() == [105.0, 50.0]


# A numbered subprogram called with words of its own on the M98 line. LinuxCNC reads 'M98 P100' as "analogous to
# the traditional o100 call" (o-code.adoc, "Fanuc-Style Numbered Programs") and runs the call alone, as rs274
# shows (X5 S1000 here: no move to X5); Fanuc and Haas run the line's other words before the call.
M98_WORDS = "G21 G90 G0 X0 Y0 Z5\nF200\nN5 M98 P100 L2 X5 S1000\nM30\nO100\nG91 G1 X1\nG90\nM99\n"


def test_linuxcnc_runs_an_m98_line_as_the_call_alone():
    prog = checked_iso(M98_WORDS, _in_dialect("linuxcnc"))
    assert [b.target[0] for b in prog.blocks] == [100.0, 101.0, 102.0]
    assert "X5 S1000 on an M98 line not executed (LinuxCNC runs an M98 block as a call only" in " ".join(prog.notes)


@pytest.mark.parametrize("name", ["fanuc", "haas"])
def test_fanuc_and_haas_move_before_the_call(name):
    prog = checked_iso(M98_WORDS, _in_dialect(name))
    assert [b.target[0] for b in prog.blocks] == [100.0, 105.0, 106.0, 107.0]
    assert not any("M98 line" in n for n in prog.notes)


def test_a_feed_on_an_m98_line_is_named_when_linuxcnc_has_none():
    # a PC control's sample sets the feed on the call ('M98 P81 F100'); LinuxCNC's subprogram then feeds at zero
    text = "G21 G90 G0 X0 Y0 Z5\nM98 P81 F100\nM30\nO81\nG1 Z-1\nG0 Z5\nM99\n"
    with pytest.raises(GCodeError, match=r":5:1: G01 feed move without a feed: no F word before it \(F100 of the "
                                         r"M98 line 2 is not executed: LinuxCNC runs an M98 block as a call only\)"):
        parse_program(text, context=_in_dialect("linuxcnc"))
    assert checked_iso(text, _in_dialect("fanuc")).blocks[-2].target[2] == -21.0


# A motion card's demo turns the length offset on with the radius compensation already on (D3 G42, then G43 H3).
# LinuxCNC refuses every length offset change under G41/G42 (interp_convert.cc convert_tool_length_offset);
# Fanuc and Haas run it.
G43_UNDER_G42 = ("G21 G90 G0 X-10 Y0 Z5\nG42 D1 G1 X0 Y0 F100\nG43 H1\nG1 X10\nY10\nG40 G49 G0 X20 Y20\n"
                 "G41 D1 G1 X0 F100\nG40 G0 Z10\nG43 H1\nM30\n")


@pytest.mark.parametrize("code", ["G43 H1", "G49", "G43.1 Z2"])
def test_linuxcnc_refuses_a_length_offset_change_under_radius_compensation(code):
    text = G43_UNDER_G42.replace("G43 H1\nG1 X10", f"{code}\nG1 X10")
    word = code.split()[0]
    with pytest.raises(GCodeError, match=rf":3:1: {word}: cannot change tool offset with cutter radius compensation "
                                         rf"on \(LinuxCNC\).*expected G40 before {word}"):
        parse_program(text, context=_in_dialect("linuxcnc"))


def test_linuxcnc_changes_the_length_offset_after_g40_on_the_same_line():
    prog = checked_iso(G43_UNDER_G42.replace("G43 H1\nG1 X10", "G1 X10"), _in_dialect("linuxcnc"))
    assert prog.blocks[-1].target.tolist() == [100.0, 70.0, -10.0]


@pytest.mark.parametrize("name", ["fanuc", "haas"])
def test_fanuc_and_haas_change_the_length_offset_under_radius_compensation(name):
    assert checked_iso(G43_UNDER_G42, _in_dialect(name)).blocks


def test_linuxcnc_m48_m49_take_no_p_word():
    # a motion card's demo writes 'M49 P1 (Disable FRO)'; LinuxCNC's M48/M49 switch both overrides and read no P
    # (interp_check.cc check_other_codes: "P word with no ... M50 M51 M52 M53 ... to use it")
    with pytest.raises(GCodeError, match=r":3:5: M49 P: M48 and M49 take no P \(LinuxCNC; M50 P.. and M51 P.. "
                                         r"switch the feed and the spindle speed override one by one\)"):
        parse_program("G21 G90 G0 X0 Y0\nF200\nM49 P1\nG1 X20\nM30\n", context=_in_dialect("linuxcnc"))
    prog = checked_iso("G21 G90 G0 X0 Y0\nF200\nM49\nM50 P0\nM51 P1\nG1 X20\nM48\nM30\n", _in_dialect("linuxcnc"))
    assert prog.blocks[-1].target[0] == 120.0


def test_linuxcnc_reads_no_k_on_a_drilling_cycle():
    # a motion card's G83 sample ends its block with 'K0.05'; LinuxCNC repeats with L and refuses K there
    # (interp_check.cc check_other_codes: "K word with no G2, G3, G33, G33.1, G76, or G87 to use it")
    text = "G21 G90 G0 X0 Y0 Z5\nG99 G81 X1 Y1 Z-2 R1 F100 K2\nG80\nM30\n"
    with pytest.raises(GCodeError, match=r":2:27: word K on the G81 drilling cycle: LinuxCNC repeats a cycle with L "
                                         r"and reads no K \(K is Fanuc's repeat count\)"):
        parse_program(text, context=_in_dialect("linuxcnc"))
    holes = [b for b in checked_iso(text.replace("G90 G0", "G91 G0"), _in_dialect("fanuc")).blocks
             if b.kind == "line"]
    assert len(holes) == 2
    assert len([b for b in checked_iso(text.replace("K2", "L2").replace("G90 G0", "G91 G0"),
                                       _in_dialect("linuxcnc")).blocks if b.kind == "line"]) == 2
