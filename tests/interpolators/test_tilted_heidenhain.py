"""Heidenhain PLANE and cycle 19 on a B/C tilting table: hand-written programs, end points worked out
by hand, each program also checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

R = math.sqrt(0.5)
PIVOT_B = (0.0, 0.0, -50.0)
KIN = Kinematics(axes=(RotaryAxis(name="b", pivot=PIVOT_B, limits=(-10.0, 110.0)), RotaryAxis(name="c")))
CTX = MachineContext(work_offsets={"G54": (10.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=20.0)},
                     home=(0.0, 0.0, 300.0), extra_axes=("b", "c"), kinematics=KIN)
HEAD = "0 BEGIN PGM T MM\nTOOL CALL 1 Z S1000\nL Z+100 R0 FMAX\n"
#: The tilted zero of SPB+45: the preset (10, 0, 0) is (10, 0, 50) from the B pivot; the table turns the part
#: -45 deg about Y: x = 10 cos45 - 50 sin45, z = 10 sin45 + 50 cos45 - 50 (pivot); plus the tool length 20.
ZERO45 = np.array([10 * R - 50 * R, 0.0, 10 * R + 50 * R - 50.0 + 20.0])


def run(body: str, context: MachineContext = CTX, *, reference: bool = True):
    """The program run by the reader, after checking it against the reference block by block."""
    return checked_program(HEAD + body + "\nEND PGM T MM\n", context, check=reference, exact=False)


def ends(prog):
    return [np.asarray(b.target) for b in prog.blocks]


def test_plane_spatial_turn_and_an_arc_in_the_tilted_plane():
    prog = run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX\nL X+0 Y+0 FMAX\nL Z+5 FMAX\nL X+10 Y+0 F100\n"
               "CC X+0 Y+0\nC X+0 Y+10 DR+\nL Z+50 FMAX")
    b = prog.blocks
    assert ends(prog)[0] == pytest.approx([0.0, 0.0, 120.0])  # TURN: the linear axes stay
    assert b[1].extra_target[:3] == pytest.approx([0.0, 45.0, 0.0]) and math.isinf(b[1].feed)
    # X0 Y0 keeps the program Z of (0, 0, 120): machine Z stays 120 (the tilted Z is the machine's)
    assert ends(prog)[2] == pytest.approx([ZERO45[0], 0.0, 120.0])
    assert ends(prog)[3] == pytest.approx(ZERO45 + [0.0, 0.0, 5.0])
    assert ends(prog)[4] == pytest.approx(ZERO45 + [10.0, 0.0, 5.0])
    arc = b[5].segment  # an arc of the machine's XY plane about the tilted zero, counter-clockwise
    assert arc.plane == 2 and arc.ccw and np.asarray(arc.center)[:2] == pytest.approx(ZERO45[:2])
    assert ends(prog)[5] == pytest.approx(ZERO45 + [0.0, 10.0, 5.0])
    assert prog.axes == ("x", "y", "z", "b", "c")


def test_the_same_holes_drilled_on_the_untilted_and_the_tilted_plane():
    """Cycle 200 at three positions: on a 0 deg plane the machine points are the untilted program's; on
    SPB+45 each point, turned back with the table (part = pivot + Ry(+45) (machine - pivot)), is the
    untilted point turned by the plane: part - preset = Ry(45) (untilted - preset)."""
    holes = ("CYCL DEF 200 DRILLING Q200=2 Q201=-5 Q206=150 Q202=5 Q210=0 Q203=+0 Q204=10 Q211=0\n"
             "L X+10 Y+5 FMAX M99\nL X+20 Y+5 FMAX M99\nL X+20 Y-8 FMAX M99\nL Z+50 FMAX")
    flat = run("L X+0 Y+0 Z+100 FMAX\n" + holes, MachineContext(work_offsets={"G54": (10.0, 0.0, 0.0)},
                                                         tools={1: Tool(number=1, length=20.0)}, home=(0, 0, 300)))
    zero = run("PLANE SPATIAL SPA+0 SPB+0 SPC+0 TURN FMAX\nL X+0 Y+0 Z+100 FMAX\n" + holes)
    assert np.allclose(ends(zero), ends(flat), rtol=0.0, atol=1e-12)  # B+0 C+0 already: TURN moves nothing
    tilted = run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX\nL X+0 Y+0 Z+100 FMAX\n" + holes)
    ry = np.array([[R, 0.0, R], [0.0, 1.0, 0.0], [-R, 0.0, R]])
    pivot, preset, tool = np.array(PIVOT_B), np.array([10.0, 0.0, 0.0]), np.array([0.0, 0.0, 20.0])
    for e_flat, e_tilt in zip(ends(flat)[1:], ends(tilted)[2:], strict=True):
        part = pivot + ry @ (e_tilt - tool - pivot)
        assert part - preset == pytest.approx(ry @ (e_flat - tool - preset))


def test_stay_then_the_program_positions_the_axes_from_q120_q122():
    """Fusion's idiom: PLANE .. STAY, then L B+Q121 C+Q122 R0 FMAX (the positions the TNC stored)."""
    prog = run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 STAY\nL B+Q121 C+Q122 R0 FMAX\nL X+0 Y+0 Z+5 FMAX")
    assert len(prog.blocks) == 3
    assert prog.blocks[1].extra_target[:3] == pytest.approx([0.0, 45.0, 0.0])
    assert ends(prog)[2] == pytest.approx(ZERO45 + [0.0, 0.0, 5.0])
    turned = run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 STAY\nL B+45 C+360 R0 FMAX\nL X+0 Y+0 Z+5 FMAX", reference=False)
    assert ends(turned)[2] == pytest.approx(ZERO45 + [0.0, 0.0, 5.0])  # C+360 is the table's C+0


def test_a_move_in_the_plane_before_the_axes_are_there_is_an_error():
    with pytest.raises(GCodeError, match=r"while the rotary axes are not at its positions B\+45.0000 C\+0.0000.*"
                                         r"L B\+Q121 C\+Q122"):
        run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 STAY\nL X+0 Y+0 Z+5 FMAX", reference=False)


def test_move_keeps_the_tool_tip_on_the_part_and_reset_turns_back():
    """MOVE from (0, 0, 120): the tip (0, 0, 100) is (0, 0, 150) from the B pivot; the table turns it by
    -45 deg about Y to x = -150 sin45, z = 150 cos45 - 50; the spindle point is 20 above it. PLANE RESET
    TURN turns B back to 0 and keeps the linear axes; then the untilted zero is the preset again."""
    prog = run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 MOVE DIST0 F2000\nPLANE RESET TURN FMAX\nL X+0 Y+0 Z+0 FMAX")
    e = ends(prog)
    assert e[1] == pytest.approx([-150 * R, 0.0, 150 * R - 50.0 + 20.0])
    assert prog.blocks[1].kind == "line" and prog.blocks[1].feed == pytest.approx(2000 / 60)
    assert e[2] == pytest.approx(e[1]) and prog.blocks[2].extra_target[:3] == pytest.approx([0, 0, 0])
    assert e[3] == pytest.approx([10.0, 0.0, 20.0])
    assert len(run("PLANE RESET TURN FMAX\nL X+0 Y+0 Z+0 FMAX").blocks) == 2  # at B+0 C+0 already: no move


def test_cycle_19_with_datum_shifts_before_and_after_the_tilt():
    """TNC cycle manual, cycle 19: a datum shift before the tilt shifts the untilted part, one after it
    shifts in the tilted plane. The shift X+10 before the tilt puts the tilted zero on the part at (20, 0, 0):
    (20, 0, 50) from the pivot, turned: x = 20 cos45 - 50 sin45, z = 20 sin45 + 50 cos45 - 50; X+5 after it
    moves it 5 along the tilted X, which runs along the machine's X. Resetting the tilt brings the shift of
    before it back, unless one was programmed in the plane: then that one (X+5) stands, untilted."""
    tilt = ("CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+10\nL B+45 C+0 FMAX\nCYCL DEF 19.0 WORKING PLANE\n"
            "CYCL DEF 19.1 A+0 B+45 C+0\nL X+0 Y+0 Z+0 FMAX\n")
    reset = "L Z+100 FMAX\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1\nL B+0 C+0 FMAX\nL X+0 Y+0 Z+0 FMAX"
    zero = np.array([20 * R - 50 * R, 0.0, 20 * R + 50 * R - 50.0 + 20.0])
    e = ends(run(tilt + reset))
    assert e[2] == pytest.approx(zero) and e[-1] == pytest.approx([20.0, 0.0, 20.0])
    e = ends(run(tilt + "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+5\nL X+0 Y+0 Z+0 FMAX\n" + reset))
    assert e[3] == pytest.approx(zero + [5.0, 0.0, 0.0]) and e[-1] == pytest.approx([15.0, 0.0, 20.0])


def test_a_datum_shift_reset_in_the_tilted_plane_stands_after_plane_reset():
    """hyperMILL's TNC post: CYCL DEF 7 X185 .., PLANE SPATIAL .. STAY, L B+Q121 C+Q122, machining, then its
    LBL "RESET WORKING PLANE": CYCL DEF 7 X0 Y0 Z0 and PLANE RESET STAY. The zero shift programmed in the plane
    stands after the reset (the TNC keeps one datum shift): the untilted zero is the preset again."""
    prog = run("CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+18\nCYCL DEF 7.2 Y-2\nPLANE SPATIAL SPA+0 SPB+45 SPC+0 STAY\n"
               "L B+Q121 C+Q122 R0 FMAX\nL X+0 Y+0 Z+0 FMAX\nCYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+0\n"
               "CYCL DEF 7.2 Y+0\nCYCL DEF 7.3 Z+0\nPLANE RESET STAY\nL B+0 C+0 FMAX\nL X+0 Y+0 Z+0 FMAX")
    e = ends(prog)
    assert e[2] == pytest.approx([28 * R - 50 * R, -2.0, 28 * R + 50 * R - 50.0 + 20.0])
    assert e[-1] == pytest.approx([10.0, 0.0, 20.0])


def test_seq_and_the_limits_choose_the_solution():
    """SPB-45 on this table: B-45 is below the B limit -10, so B+45 with C+180 (the part turned half
    round first); SEQ- asks for a negative B, which the limits forbid: an error naming them."""
    prog = run("PLANE SPATIAL SPA+0 SPB-45 SPC+0 TURN FMAX\nL X+0 Y+0 Z+0 FMAX")
    assert prog.blocks[1].extra_target[1:3] == pytest.approx([45.0, 180.0])
    # C+180 about the C pivot (0, 0, 0) takes the preset to (-10, 0, 0), then B+45 as above
    assert ends(prog)[2] == pytest.approx([-10 * R - 50 * R, 0.0, -10 * R + 50 * R - 50.0 + 20.0])
    with pytest.raises(GCodeError, match="with a negative B within their limits B -10..110"):
        run("PLANE SPATIAL SPA+0 SPB-45 SPC+0 TURN FMAX SEQ-", reference=False)


@pytest.mark.parametrize("plane", ["PLANE EULER EULPR+90 EULNU+45 EULROT-90", "PLANE PROJECTED PROPR+45 PROMIN+0 ROT+0",
                                   "PLANE VECTOR BX+0.7071 BY+0 BZ-0.7071 NX+0.7071 NY+0 NZ+0.7071",
                                   "PLANE POINTS P1X+0 P1Y+0 P1Z+0 P2X+1 P2Y+0 P2Z-1 P3X+0 P3Y+1 P3Z+0",
                                   "PLANE AXIAL B+45"])
def test_other_plane_forms_give_the_same_plane(plane):
    """Each form written for the plane of SPB+45 (tilted X = (1, 0, -1)/sqrt2, tilted Z = (1, 0, 1)/sqrt2)."""
    body = " TURN FMAX\nL X+0 Y+0 Z+5 FMAX\nL X+10 Y+3 F100"
    want = ends(run("PLANE SPATIAL SPA+0 SPB+45 SPC+0" + body))
    got = ends(run(plane + body))
    assert np.allclose(got, want, atol=1e-3)


def test_plane_relative_turns_the_active_plane():
    want = ends(run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX\nL X+10 Y+3 Z+5 FMAX"))
    got = ends(run("PLANE SPATIAL SPA+0 SPB+20 SPC+0 STAY\nPLANE RELATIV SPB+25 TURN FMAX\nL X+10 Y+3 Z+5 FMAX",
                   reference=False))
    assert np.allclose(got, want)


def test_cycle_19_on_a_four_axis_machine_with_one_tilting_axis():
    """A horizontal 4-axis machine's A table (as nx_training_deckel.h: L A-90 FMAX, then CYCL DEF 19.1 A-90):
    the tilted Z is Rx(-90) e_z = +Y of the part, its X the part's X, its Y the part's -Z. L X+5 Y+3 Z+2 is the
    part point (10, 0, 0) + (5, 0, 0) + 3 (0, 0, -1) + 2 (0, 1, 0) = (15, 2, -3); the table turns the part +90
    deg about X: (15, 3, 2), plus the tool length."""
    four = MachineContext(work_offsets={"G54": (10.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=20.0)},
                          home=(0.0, 0.0, 300.0), extra_axes=("a",),
                          kinematics=Kinematics(axes=(RotaryAxis(name="a", limits=(-120.0, 120.0)),)))
    prog = run("L A-90 FMAX\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 A-90\nL X+5 Y+3 Z+2 FMAX\n"
               "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 A+0\nL A+0 FMAX", four)
    assert ends(prog)[2] == pytest.approx([15.0, 3.0, 22.0])
    with pytest.raises(GCodeError, match="cannot tilt the part"):  # a tilt about Y: out of this machine's reach
        run("PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN FMAX", four, reference=False)


@pytest.mark.parametrize(("context", "body", "message"), [
    (MachineContext(), "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX", r"\[program.kinematics\]"),
    (MachineContext(), "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+45", r"\[program.kinematics\]"),
    (MachineContext(kinematics=Kinematics(kind="head", axes=KIN.axes), extra_axes=("b", "c")),
     "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX", "machine whose head tilts is not supported"),
    (CTX, "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX SPQ+1", "unexpected 'SPQ\\+1' in PLANE SPATIAL"),
    (CTX, "PLANE SPATIAL SPA+0 SPB+45 SPC+0 EULPR+5 TURN", "EULPR is not a value of PLANE SPATIAL"),
    (CTX, "PLANE AXIAL A+45 TURN", "no rotary axis A"),
    (CTX, "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX\nCYCL DEF 247 Q339=2", "cycle 247 in the tilted working"),
    (CTX, "TOOL CALL 1 X\nPLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX", "tool axis X"),
])
def test_errors_name_the_function(context, body, message):
    with pytest.raises(GCodeError, match=message):
        run(body, context, reference=False)


def test_q120_to_q122_hold_the_positions_and_mb_retracts_first():
    prog = run("PLANE SPATIAL SPA+0 SPB+30 SPC+0 STAY\nQ1 = Q121\nQ2 = Q122 + 7\nPLANE RESET STAY\nL X+Q2 Z+Q1 FMAX",
               reference=False)
    assert ends(prog)[-1] == pytest.approx([10.0 + 7.0, 0.0, 30.0 + 20.0])  # B+30, C+0
    retract = run("PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN MB MAX FMAX", reference=False)
    assert ends(retract)[1] == pytest.approx([0.0, 0.0, 300.0])
    assert retract.blocks[2].extra_target[1] == pytest.approx(45.0)
