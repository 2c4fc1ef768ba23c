"""Program stops and tool changes halt the path (:func:`interpolators.program.end_at_rest`), whatever the path mode.

LinuxCNC M-codes "M0, M1 Program Pause" / "M60", Fanuc 0i-MD B-64304EN "Miscellaneous function" (M00: "automatic
operation is stopped after a block containing M00 is executed"), HEIDENHAIN TNC 640 user's manual "STOP": the
axes are at rest where the program stops; a tool change (M6, TOOL CALL n) is made at rest. M1 stops only with the
optional stop switch on, which the virtual machine's is not. Each program runs collinear moves at F3000 (50 mm/s)
under continuous path, where the look-ahead passes every joint at speed unless the machine comes to rest there.
"""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import interpolate, parse_program
from interpolators.context import DIALECTS, MachineContext

#: The feed of the programs [mm/s] (F3000 mm/min).
SPEED = 50.0


def _speed_at(text: str, xs: tuple[float, ...], context: MachineContext | None = None) -> list[float]:
    """The commanded X speed [mm/s] of the sample nearest each position in ``xs``."""
    sp = interpolate(parse_program(text, context=context or MachineContext()))
    x, vx = sp.position[:, 0], sp.velocity[:, 0]
    return [float(abs(vx[np.argmin(abs(x - p))])) for p in xs]


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas"])
def test_m0_and_m6_bring_the_axes_to_rest_and_m1_does_not(dialect):
    text = ("G21 G90 G64 F3000\nG1 X10\nM0\nG1 X20\nM1\nG1 X30\nT2 M6\nG1 X40\nS2000 M3\nG1 X50\nG0 X50\n"
            "G1 X60 M0\nG1 X70\nM30\n")
    at_rest, at_speed = 0.0, pytest.approx(SPEED, rel=0.02)
    assert _speed_at(text, (10, 20, 30, 40, 60), MachineContext(dialect=DIALECTS[dialect])) == [
        at_rest, at_speed, at_rest, at_speed, at_rest]


def test_without_a_stop_the_same_joints_pass_at_speed():
    assert _speed_at("G21 G90 G64 F3000\nG1 X10\nG1 X20\nG1 X30\nM30\n", (10, 20)) == [
        pytest.approx(SPEED, rel=0.02)] * 2


def test_tnc_stop_m0_and_a_tool_change_bring_the_axes_to_rest():
    """TNC: STOP and M0 halt the path, M1 does not; TOOL CALL 2 changes the tool (rest), TOOL CALL Z S2000 only the
    speed (no rest). Cycle 32 T0.01 makes the path continuous."""
    text = ("0 BEGIN PGM S MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+0 R0 F3000\n3 CYCL DEF 32.0 TOLERANCE\n"
            "4 CYCL DEF 32.1 T0.01\n5 L X+10 M0\n6 L X+20\n7 L X+30 M1\n8 L X+40\n9 STOP\n10 L X+50\n"
            "11 TOOL CALL 2 Z S1000\n12 L X+60\n13 TOOL CALL Z S2000\n14 L X+70\n15 END PGM S MM\n")
    at_rest, at_speed = 0.0, pytest.approx(SPEED, rel=0.02)
    assert _speed_at(text, (10, 20, 30, 40, 50, 60)) == [at_rest, at_speed, at_speed, at_rest, at_rest, at_speed]


def test_tnc_a_tool_called_by_name_brings_the_axes_to_rest():
    """TOOL CALL "MILL_D10" Z: a tool change by name (not in the tool table: length and radius 0, noted)."""
    text = ("0 BEGIN PGM N MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+0 R0 F3000\n3 CYCL DEF 32.0 TOLERANCE\n"
            "4 CYCL DEF 32.1 T0.01\n5 L X+10\n6 TOOL CALL \"MILL_D10\" Z S1000\n7 L X+20\n8 L X+30\n"
            "9 END PGM N MM\n")
    assert _speed_at(text, (10, 20)) == [0.0, pytest.approx(SPEED, rel=0.02)]
