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
