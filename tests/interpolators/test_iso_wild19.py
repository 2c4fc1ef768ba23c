"""ISO programs of the nineteenth wild round (set /tmp/wild19/set): svg2gcode and cncjs test fixtures, TinyG's
gcode samples, machinekit's trajectory-planner tests, a Polish shop's Fadal programs, Fanuc macro B of a Russian
shop, Free CNC Simulator samples, Mazak EIA output of a Fusion post, FluidNC post fixtures, BlenderCAM test data,
gSender and UGS examples, Tormach PathPilot subroutines. The snippets are written for these tests after those
programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

LINUXCNC = MachineContext().with_dialect("linuxcnc")

# a mill program begun from a lathe template: G8 (LinuxCNC lathe radius mode, the default at power up) in its
# safety line; inch, a G2 arc after it
LATHE_TEMPLATE = "G40 G90\nG20 G17\nG40 G8\nF30\nG0 X0.75 Y0.77\nG1 Z-0.03\nG2 X1.75 Y0.77 I0.5 J0\nM2\n"


def test_g8_lathe_radius_mode_moves_nothing_under_linuxcnc():
    prog = checked_iso(LATHE_TEMPLATE, LINUXCNC)
    moves = [b for b in prog.blocks if b.kind in ("rapid", "line", "arc")]
    ends = [[19.05, 19.558, 0.0], [19.05, 19.558, -0.762], [44.45, 19.558, -0.762]]
    assert [b.target.tolist() for b in moves] == [pytest.approx(e) for e in ends]
    assert moves[-1].kind == "arc"
    assert any(n.startswith("G8 lathe radius mode (LinuxCNC's default at power up)") for n in prog.notes)


def test_g7_lathe_diameter_mode_stays_refused_under_linuxcnc():
    # diameter mode halves X on a lathe: vcnc does not, and says so
    with pytest.raises(GCodeError, match=r":3:1: G7 lathe diameter mode: not supported \(got 'G7'\)"):
        parse_program(LATHE_TEMPLATE.replace("G40 G8", "G7"), context=LINUXCNC)


# LinuxCNC tests/m70-m73/m73autorestore, rewritten: a subroutine saves the modal state with M73, goes absolute and
# returns (endsub, then "return" inside an if); called twice in a row, each call's G91 comes back at its return
M73_TWICE = """G21
o100 sub
M73
G90
G0 X5 Y20
o101 if [#1 EQ 1]
o101   return
o101 endif
o100 endsub
G91
G0 X10 Y10
o100 call [0]
o100 call [1]
G0 X-5 Y-20
M2
"""


def test_m73_state_returns_at_each_of_two_calls_in_a_row():
    prog = checked_iso(M73_TWICE, LINUXCNC)
    assert [b.target[:2].tolist() for b in prog.blocks if b.kind == "rapid"] == [[10.0, 10.0], [5.0, 20.0],
                                                                                [5.0, 20.0], [0.0, 0.0]]
    assert "M73 modal state restored at the subroutine's return x2" in prog.notes


def test_m73_state_of_a_call_is_not_restored_without_m73():
    # the same calls without M73: the subroutine's G90 stays, the last move is absolute
    prog = checked_iso(M73_TWICE.replace("M73\n", ""), LINUXCNC)
    assert [b.target[:2].tolist() for b in prog.blocks if b.kind == "rapid"][-1] == [-5.0, -20.0]


FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")

# a Fusion Fanuc turning post's start: G50 S (maximum spindle speed) then G96 (constant surface speed); X is a diameter
TURNING = ("%\nO0001\nG98 G18\nG21\nG50 S6000\nG28 U0.\nT0100\nG54\nG99\nG97 S364 M3\nG0 X80. Z5.\nG50 S5000\n"
           "G96 S91 M3\nG0 Z0.6\nX58.8\nG1 Z-59.188 F0.127\nM30\n%\n")


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_a_fanuc_lathe_program_is_refused_naming_its_lathe_codes(context):
    # (newuser34: its T0100, the lathe's tool and offset number, is the second lathe code, at line 7)
    with pytest.raises(GCodeError, match=r":7:1: a lathe program: a T word of four digits \(T0101: a lathe's tool "
                                         r"and offset number\) here and G50 S \(the lathe's maximum spindle speed\) at "
                                         r"line 5 are a Fanuc/Haas lathe's codes \(its X is a diameter, U and W "
                                         r"incremental X and Z\): not supported"):
        parse_program(TURNING, context=context)
    # with a mill's T word, G96 at line 13 is the second
    with pytest.raises(GCodeError, match=r":13:1: a lathe program: G96 \(constant surface speed\) here and G50 S "
                                         r"\(the lathe's maximum spindle speed\) at line 5 are a Fanuc/Haas lathe's "
                                         r"codes \(its X is a diameter, U and W incremental X and Z\): not supported"):
        parse_program(TURNING.replace("T0100", "T1"), context=context)


@pytest.mark.parametrize("context", [FANUC, HAAS])
@pytest.mark.parametrize("line", ["G50 S3000", "G96 S100 M3"])
def test_either_lathe_code_alone_stays_a_note_in_a_mill_program(context, line):
    prog = checked_iso(f"G21 G90 G17\n{line}\nG0 X10. Y10.\nG1 X20. F500.\nM30\n", context)
    assert [b.target.tolist() for b in prog.blocks][-2:] == [[10.0, 10.0, 0.0], [20.0, 10.0, 0.0]]


@pytest.mark.parametrize("context", [LINUXCNC, FANUC])
def test_m98_with_l0_calls_nothing(context):
    # LinuxCNC tests/interp/m98m99/05-M98-loops, "Test with 0 loops": L0 runs the subprogram no time (rs274 agrees)
    text = "G21 G90\nG0 X0 Y0 Z1.\nM98 P1 L0\nG0 X5.\nM98 P1 L2\nM30\nO1\nG91 G0 X1.\nG90\nM99\n"
    prog = checked_iso(text, context)
    assert [b.target[0] for b in prog.blocks if b.kind == "rapid"] == [0.0, 5.0, 6.0, 7.0]
