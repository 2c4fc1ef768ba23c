"""Fanuc G68.2 (Euler angles, P0, P1 roll/pitch/yaw) / G53.1 on a B/C tilting table (interpolators/iso_tilt.py):
end points worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.iso import parse_iso
from interpolators.tilted import Kinematics, RotaryAxis
from vcnc.errors import GCodeError

R = math.sqrt(0.5)
KIN = Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0), limits=(-10.0, 110.0)), RotaryAxis(name="c")))
FANUC = MachineContext(kinematics=KIN, extra_axes=("b", "c"), work_offsets={"G54": (10.0, 0.0, 0.0)},
                       dialect=DIALECTS["fanuc"])


def test_g68_2_euler_plane_and_g53_1_on_a_bc_table():
    """G68.2 I0 J45 K0 tilts the plane about X by 45 deg: its tool axis (0, -sin45, cos45) = Rz(C) Ry(B) e_z
    gives B+45 C-90 (B-45 is beyond the B limit -10). The table turns the part +90 deg about Z (C pivot at
    the origin), the work zero (10, 0, 0) to (0, 10, 0), then -45 deg about Y round the B pivot (0, 0, -50):
    (0, 10, 50) from it becomes (-50 sin45, 10, 50 cos45), i.e. (-35.355, 10, -14.645). The tilted X (the
    part's X) turns to the machine's Y (theta 90 deg). G53.1 turns B and C at rapid, X Y Z stay; G69 cancels
    the plane (the rotary axes stay)."""
    prog = parse_iso("G21 G90 G54\nG0 X0 Y0 Z100.\nG68.2 X0 Y0 Z0 I0 J45. K0\nG53.1\nG0 X0 Y0 Z5.\nG1 X10. F100.\n"
                     "G2 X0 Y10. I-10. J0\nG69\nG0 X0 Y0 Z0\n", context=FANUC)
    zero = np.array([-50 * R, 10.0, 50 * R - 50.0])
    b = prog.blocks
    assert b[1].target == pytest.approx([10.0, 0.0, 100.0]) and b[1].extra_target[1:3] == pytest.approx([45, -90])
    assert math.isinf(b[1].feed)
    assert b[2].target == pytest.approx(zero + [0.0, 0.0, 5.0])
    assert b[3].target == pytest.approx(zero + [0.0, 10.0, 5.0])
    # the clockwise arc from tilted (10, 0) to (0, 10) about the tilted zero, turned by 90 deg
    assert b[4].segment.plane == 2 and not b[4].segment.ccw
    assert np.asarray(b[4].segment.center) == pytest.approx(zero + [0.0, 0.0, 5.0])
    assert b[4].target == pytest.approx(zero + [-10.0, 0.0, 5.0])
    assert b[5].target == pytest.approx([10.0, 0.0, 0.0]) and b[5].extra_target[1:3] == pytest.approx([45, -90])
    assert prog.axes == ("x", "y", "z", "b", "c")


def test_g68_2_with_its_own_zero_and_a_tool_length():
    """The plane's zero X5 (in the work coordinates) and tool 1's 20 mm (G43 H1): the part point (15, 0, 0)
    turned as above is (0, 15, 0), then (-50 sin45, 15, 50 cos45 - 50); Z moves along the spindle by 20."""
    ctx = MachineContext(kinematics=KIN, extra_axes=("b", "c"), work_offsets={"G54": (10.0, 0.0, 0.0)},
                         dialect=DIALECTS["fanuc"], tools={1: Tool(number=1, length=20.0)})
    prog = parse_iso("G21 G90 G54\nT1 M6\nG43 H1 Z100.\nG68.2 X5. Y0 Z0 I0 J45. K0\nG53.1\nG0 X0 Y0 Z0\n",
                     context=ctx)
    assert prog.blocks[-1].target == pytest.approx([-50 * R, 15.0, 50 * R - 50.0 + 20.0])


@pytest.mark.parametrize(("context", "text", "message"), [
    (FANUC, "G68.2 X0 Y0 Z0 I0 J45. K0 R5.", "G68.2 tilted working plane: only X Y Z"),
    (FANUC, "G68.2 P0 Q123 I0 J45. K0", "G68.2 tilted working plane: only X Y Z"),  # Q is P1's
    (FANUC, "G68.2 P1 Q123 I30. J20.", r"G68.2 P1 with I, J non-zero: not supported"),
    (FANUC, "G68.2 P1 Q123 I30. J20. K10.", r"G68.2 P1 with I, J, K non-zero: not supported"),
    (FANUC, "G68.2 P1 Q124 J30.", r"G68.2 P1 Q124: not an order of rotation about X, Y and Z"),
    (FANUC, "G68.2 P1 Q123 J400.", r"G68.2 P1 J400: beyond the setting range"),
    (FANUC, "G68.2 P2 Q1 X0 Y0 Z0", r"G68.2 P2 \(three points\): not supported"),
    (FANUC, "G68.2 P2 Q0 X0 Y0 Z0 R0", r"G68.2 P2 \(three points\): not supported"),
    (FANUC, "G68.2 P3 Q1 X0 Y0 Z0 I1. J0 K0", r"G68.2 P3 \(two vectors\): not supported"),
    (FANUC, "G68.2 P4 X0 Y0 Z0 I10. J10. K0", r"G68.2 P4 \(projection angles\): not supported"),
    (FANUC, "G68.2 P5 I10.", "G68.2 P5: no such definition"),
    (MachineContext(dialect=DIALECTS["fanuc"]), "G68.2 P2 Q1 X0 Y0 Z0", r"G68.2 P2 \(three points\)"),
    (FANUC, "G68.3 X0 Y0 Z0", r"G68.3 tilted working plane \(5-axis\): not supported"),
    (FANUC, "G53.1", "G53.1 without a G68.2"),
    (FANUC, "G68 X0 Y0 R30.\nG68.2 X0 Y0 Z0 I0 J45. K0", "without cutter compensation, G68"),
    (FANUC, "G68.2 X0 Y0 Z0 I0 J150. K0", "cannot tilt the part"),  # B+150 is beyond the B limit 110
    (MachineContext(dialect=DIALECTS["fanuc"]), "G68.2 X0 Y0 Z0 I0 J45. K0", r"\[program.kinematics\]"),
    (MachineContext(), "G68.2 X0 Y0 Z0 I0 J45 K0", "G68.2 tilted working plane \\(5-axis\\): not supported"),
])
def test_g68_2_errors(context, text, message):
    with pytest.raises(GCodeError, match=message):
        parse_iso(f"G21 G90\n{text}\n", context=context)


def test_g68_2_refusal_points_at_the_word_at_fault():
    """A P1 plane with two angles is refused at the second angle's column, a P2 form at its P."""
    with pytest.raises(GCodeError, match=r"<input>:2:20: G68.2 P1 with I, J non-zero") as err:
        parse_iso("G21 G90\nG68.2 P1 Q123 I30. J20.\n", context=FANUC)
    assert "expected one non-zero roll (I), pitch (J) or yaw (K) angle" in str(err.value)
    with pytest.raises(GCodeError, match=r"<input>:2:7: G68.2 P2 \(three points\)"):
        parse_iso("G21 G90\nG68.2 P2 Q1 X0 Y0 Z0\n", context=FANUC)


def _plane_run(plane: str):
    return parse_iso(f"G21 G90 G54\nG0 X0 Y0 Z100.\n{plane}\nG53.1\nG0 X0 Y0 Z5.\nG1 X10. F100.\nG69\nG0 X0 Y0 Z0\n",
                     context=FANUC).blocks


def test_g68_2_p0_and_p1_roll_are_the_euler_plane_about_x():
    """Mazak's ``G68.2 P0`` is the Euler form; ``G68.2 P1 Q123 I45.`` (roll 45 deg about X, the only turn) is the
    same plane as ``G68.2 I0 J45. K0``: B+45 C-90, the work zero (10, 0, 0) at (-50 sin45, 10, 50 cos45 - 50)
    (see the first test), the tilted X along the machine's Y. G69 cancels it (the rotary axes stay)."""
    zero = np.array([-50 * R, 10.0, 50 * R - 50.0])
    for plane in ("G68.2 P0 X0 Y0 Z0 I0 J45. K0", "G68.2 P1 Q123 X0 Y0 Z0 I45.", "G68.2 P1 Q321 I45. J0 K0"):
        b = _plane_run(plane)
        assert b[1].extra_target[1:3] == pytest.approx([45.0, -90.0])
        assert b[2].target == pytest.approx(zero + [0.0, 0.0, 5.0])
        assert b[3].target == pytest.approx(zero + [0.0, 10.0, 5.0])
        assert b[4].target == pytest.approx([10.0, 0.0, 0.0]) and b[4].extra_target[1:3] == pytest.approx([45, -90])


def test_g68_2_p1_pitch_turns_b_only():
    """``G68.2 P1 Q123 J30.``: pitch 30 deg about Y, tool axis (sin30, 0, cos30) = Ry(B) e_z, so B+30 C0. The
    table turns the part -30 deg about Y round the B pivot (0, 0, -50): the work zero (10, 0, 0), (10, 0, 50) from
    the pivot, goes to (10 cos30 - 50 sin30, 0, 10 sin30 + 50 cos30 - 50); the tilted X (cos30, 0, -sin30) turns
    onto the machine's X."""
    c, s = math.cos(math.radians(30.0)), 0.5
    zero = np.array([10 * c - 50 * s, 0.0, 10 * s + 50 * c - 50.0])
    b = _plane_run("G68.2 P1 Q123 X0 Y0 Z0 J30.")
    assert b[1].extra_target[1:3] == pytest.approx([30.0, 0.0])
    assert b[2].target == pytest.approx(zero + [0.0, 0.0, 5.0])
    assert b[3].target == pytest.approx(zero + [10.0, 0.0, 5.0])
    assert b[4].target == pytest.approx([10.0, 0.0, 0.0])


def test_g68_2_p1_yaw_turns_the_plane_about_z_with_its_zero():
    """``G68.2 P1 Q123 X5. K30.``: yaw 30 deg about Z; the tool axis stays the spindle's, so B and C stay at 0
    and the plane's X runs at 30 deg in the machine's XY plane from its zero, X5 of the work coordinates
    (machine (15, 0, 0)): X10 in the plane is (15 + 10 cos30, 10 sin30)."""
    b = _plane_run("G68.2 P1 Q123 X5. Y0 Z0 K30.")
    assert b[1].extra_target[1:3] == pytest.approx([0.0, 0.0])
    assert b[2].target == pytest.approx([15.0, 0.0, 5.0])
    assert b[3].target == pytest.approx([15.0 + 10 * math.cos(math.radians(30.0)), 5.0, 5.0])
