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
