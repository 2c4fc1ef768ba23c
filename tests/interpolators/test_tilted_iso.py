"""Fanuc G68.2 / G53.1 on a B/C tilting table (interpolators/iso_tilt.py): end points worked out by hand."""

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
    (FANUC, "G68.2 X0 Y0 Z0 I0 J45. K0 P1", "G68.2 tilted working plane: only X Y Z"),
    (FANUC, "G53.1", "G53.1 without a G68.2"),
    (FANUC, "G68 X0 Y0 R30.\nG68.2 X0 Y0 Z0 I0 J45. K0", "without cutter compensation, G68"),
    (FANUC, "G68.2 X0 Y0 Z0 I0 J150. K0", "cannot tilt the part"),  # B+150 is beyond the B limit 110
    (MachineContext(dialect=DIALECTS["fanuc"]), "G68.2 X0 Y0 Z0 I0 J45. K0", r"\[program.kinematics\]"),
    (MachineContext(), "G68.2 X0 Y0 Z0 I0 J45 K0", "G68.2 tilted working plane \\(5-axis\\): not supported"),
])
def test_g68_2_errors(context, text, message):
    with pytest.raises(GCodeError, match=message):
        parse_iso(f"G21 G90\n{text}\n", context=context)
