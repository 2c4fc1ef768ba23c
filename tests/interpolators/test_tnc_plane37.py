"""Heidenhain PLANE PROJECTED, POINTS, AXIAL and TABLE ROT: end points worked out by hand, and short programs in
the styles of the posts (Fusion's heidenhain.cps, NX, SolidWorks-APT) checked block by block against the
independent reference (``reference_heidenhain``, written from the TNC manuals).

The machine: a B/C table (B about Y through (0, 0, -50), C about Z through the origin; the table turns the part the
other way round: machine = Ry(-B) Rz(-C) part about the pivots), preset G54 (10, 0, 0), tool 1 of length 20.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_iso import ReferenceError
from vcnc.errors import GCodeError

R = math.sqrt(0.5)
PIVOT_B = np.array([0.0, 0.0, -50.0])
PRESET = np.array([10.0, 0.0, 0.0])
TOOL = np.array([0.0, 0.0, 20.0])
BC = Kinematics(axes=(RotaryAxis(name="b", pivot=tuple(PIVOT_B), limits=(-110.0, 110.0)), RotaryAxis(name="c")))
CTX = MachineContext(work_offsets={"G54": tuple(PRESET)}, tools={1: Tool(number=1, length=20.0)},
                     home=(0.0, 0.0, 300.0), extra_axes=("b", "c"), kinematics=BC)
#: An A/C table with pivots off the origin (A about X through (0, 20, -40), C about Z through (5, 0, 0)).
AC = Kinematics(axes=(RotaryAxis(name="a", pivot=(0.0, 20.0, -40.0), limits=(-120.0, 120.0)),
                      RotaryAxis(name="c", pivot=(5.0, 0.0, 0.0))))
CTX_AC = MachineContext(work_offsets={"G54": (10.0, 5.0, 0.0)},
                        tools={i: Tool(number=i, length=20.0 + i, radius=1.0 + i / 2) for i in range(1, 8)},
                        home=(0.0, 0.0, 300.0), extra_axes=("a", "c"), kinematics=AC)
HEAD = "0 BEGIN PGM T MM\nTOOL CALL 1 Z S1000\nL Z+150 R0 FMAX\n"


def _ry(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def machine_of(part: np.ndarray, b: float, c: float) -> np.ndarray:
    """Where the table at B, C carries the part point at ``part`` (rotary axes at 0), plus the tool length."""
    return PIVOT_B + _ry(-b) @ (_rz(-c) @ part - PIVOT_B) + TOOL


def run(body: str, context: MachineContext = CTX, *, reference: bool = True, head: str = HEAD):
    """The program run by the reader, after checking it against the reference block by block."""
    return checked_program(head + body + "\nEND PGM T MM\n", context, check=reference, exact=False)


def test_plane_axial_goes_to_the_angles_written_not_the_nearer_solution():
    """From C-10, PLANE AXIAL B+45 C+170: the other solution of that tool axis, B-45 C-10, is nearer (45 deg of
    travel against 225), and the reader took it; the TNC7 manual: the axis angles are "the nominal coordinates of
    the rotary axes". The tilted zero is the preset carried by C+170, then B+45."""
    prog = run("L C-10 FMAX\nPLANE AXIAL B+45 C+170 TURN FMAX\nL X+0 Y+0 Z+0 FMAX")
    assert prog.blocks[2].extra_target[1:3] == pytest.approx([45.0, 170.0])
    c170 = np.array([10.0 * math.cos(math.radians(170.0)), -10.0 * math.sin(math.radians(170.0)), 0.0])
    x, y, z = c170 - PIVOT_B
    assert np.asarray(prog.blocks[3].target) == pytest.approx([R * (x - z), y, R * (x + z) - 50.0 + 20.0])


def test_plane_axial_keeps_an_axis_not_written_and_refuses_an_angle_beyond_the_limits():
    prog = run("L C+25 FMAX\nPLANE AXIAL B+30 TURN FMAX")
    assert prog.blocks[-1].extra_target[1:3] == pytest.approx([30.0, 25.0])
    with pytest.raises(GCodeError, match=r"PLANE AXIAL B\+120 is outside the axis' limits -110..110"):
        run("PLANE AXIAL B+120 TURN FMAX", reference=False)


def test_plane_axial_incremental_angles_add_to_where_the_axes_are():
    """TNC7 basic user's manual, PLANE AXIAL: "absolute or incremental axis angles". From B+10 C+20: IB+25 is B+35
    (C stays), then IB+10 IC-50 is B+45 C-30; B and IB together is an error."""
    prog = run("L B+10 C+20 FMAX\nPLANE AXIAL IB+25 TURN FMAX\nPLANE AXIAL IB+10 IC-50 TURN FMAX\nL X+0 Y+0 Z+0 FMAX")
    assert prog.blocks[2].extra_target[1:3] == pytest.approx([35.0, 20.0])
    assert prog.blocks[3].extra_target[1:3] == pytest.approx([45.0, -30.0])
    assert np.asarray(prog.blocks[4].target) == pytest.approx(machine_of(PRESET, 45.0, -30.0))
    with pytest.raises(GCodeError, match="PLANE AXIAL with both B and IB"):
        run("PLANE AXIAL B+10 IB+5 TURN FMAX", reference=False)


def test_plane_projected_of_two_45_degree_traces():
    """PROPR+45 PROMIN+45: the traces (1, 0, -1) and (0, 1, 1); tool axis their cross product (1, -1, 1)/sqrt3,
    reached at B = acos(1/sqrt3) = 54.7356, C-45 (nearer from B0 C0 than B-54.7 C+135); tilted X along the first
    trace, tilted Y = Z x X = (1, 2, 1)/sqrt6."""
    prog = run("PLANE PROJECTED PROPR+45 PROMIN+45 ROT+0 TURN FMAX\nL X+0 Y+0 Z+0 FMAX\nL X+10 FMAX\nL X+0 Y+10 FMAX")
    b = math.degrees(math.acos(1.0 / math.sqrt(3.0)))
    assert prog.blocks[1].extra_target[1:3] == pytest.approx([b, -45.0])
    ends = [np.asarray(blk.target) for blk in prog.blocks[2:]]
    assert ends[0] == pytest.approx(machine_of(PRESET, b, -45.0))
    assert ends[1] == pytest.approx(machine_of(PRESET + 10.0 * np.array([R, 0.0, -R]), b, -45.0))
    assert ends[2] == pytest.approx(machine_of(PRESET + 10.0 * np.array([1.0, 2.0, 1.0]) / math.sqrt(6.0), b, -45.0))
    with pytest.raises(GCodeError, match="PROPR\\+90: a projection angle of 90 deg or more"):
        run("PLANE PROJECTED PROPR+90 PROMIN+0 ROT+0 TURN FMAX", reference=False)


def test_plane_projected_rot_turns_about_the_tilted_tool_axis():
    """ROT+90 on PROPR+45 alone (the plane of SPB+45): the tilted X becomes the plane's former Y, the part's +Y,
    which B+45 leaves along the machine's +Y."""
    prog = run("PLANE PROJECTED PROPR+45 PROMIN+0 ROT+90 TURN FMAX\nL X+0 Y+0 Z+0 FMAX\nL X+10 FMAX")
    assert prog.blocks[1].extra_target[1:3] == pytest.approx([45.0, 0.0])
    assert np.asarray(prog.blocks[3].target) - np.asarray(prog.blocks[2].target) == pytest.approx([0.0, 10.0, 0.0])


def test_plane_points_by_the_right_hand_rule():
    """P1 (0, 0, 0), P2 (0, 10, 0), P3 (-10, 0, 10): X from P1 to P2 = +Y of the part, Y toward P3 = (-1, 0, 1)/sqrt2,
    Z = X x Y = (1, 0, 1)/sqrt2: B+45 C+0. B+45 leaves the part's +Y along the machine's +Y and turns (-1, 0, 1)/sqrt2
    onto the machine's -X."""
    prog = run("PLANE POINTS P1X+0 P1Y+0 P1Z+0 P2X+0 P2Y+10 P2Z+0 P3X-10 P3Y+0 P3Z+10 TURN FMAX\n"
               "L X+0 Y+0 Z+0 FMAX\nL X+10 FMAX\nL X+0 Y+10 FMAX")
    assert prog.blocks[1].extra_target[1:3] == pytest.approx([45.0, 0.0])
    zero = machine_of(PRESET, 45.0, 0.0)
    ends = [np.asarray(blk.target) for blk in prog.blocks[2:]]
    assert ends[0] == pytest.approx(zero)
    assert ends[1] == pytest.approx(zero + [0.0, 10.0, 0.0])
    assert ends[2] == pytest.approx(zero + [-10.0, 0.0, 0.0])


def test_table_rot_turns_the_table_coord_rot_the_coordinates():
    """SPC+30 alone: TABLE ROT turns C to +30, which carries the plane's X (cos30, sin30, 0) onto the machine's X;
    COORD ROT leaves C at 0 and turns the coordinates: X+10 runs along (cos30, sin30) of the machine."""
    point = PRESET + 10.0 * np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0)), 0.0])
    table = run("PLANE SPATIAL SPA+0 SPB+0 SPC+30 TURN FMAX TABLE ROT\nL X+10 Y+0 Z+0 FMAX")
    assert table.blocks[1].extra_target[1:3] == pytest.approx([0.0, 30.0])
    assert np.asarray(table.blocks[2].target) == pytest.approx(machine_of(point, 0.0, 30.0))
    assert np.asarray(table.blocks[2].target) == pytest.approx([10.0 * math.cos(math.radians(30.0)) + 10.0,
                                                                 -10.0 * math.sin(math.radians(30.0)), 20.0])
    coord = run("PLANE SPATIAL SPA+0 SPB+0 SPC+30 TURN FMAX COORD ROT\nL X+10 Y+0 Z+0 FMAX")
    assert np.asarray(coord.blocks[-1].target) == pytest.approx(point + TOOL)


def test_a_fractional_repeat_count_is_refused_by_the_reader_and_the_reference():
    """CALL LBL 1 REPQ5 with Q5 = 1.5: no manual text found says how the TNC rounds it; the reader refuses it, and the
    reference (which had truncated it to 1) now does too rather than predict a count."""
    body = "Q5 = 1.5\nLBL 1\nL IX+1 F100\nCALL LBL 1 REPQ5"
    with pytest.raises(GCodeError, match="REP Q5 = 1.5 is not a whole number"):
        run(body, reference=False)
    with pytest.raises(ReferenceError, match="fractional repeat count"):
        heidenhain_reference(HEAD + body + "\nEND PGM T MM\n", CTX)


#: Short programs as the posts write them; each must agree with the reference at every block.
POST_STYLE = {
    # Fusion heidenhain.cps: TURN with MB MAX and SEQ, a full circle, PLANE RESET TURN
    "fusion_turn": "L M140 MB MAX\nPLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN MB MAX FMAX SEQ+\nM3\n"
                   "L X-10 Y-20 R0 FMAX\nL Z+15 FMAX\nL Z+2 F500\nL X+30 F1200\nCC X+30 Y-10\nC X+30 Y+0 DR+\n"
                   "L X-10\nL Z+15 FMAX\nL M140 MB MAX\nPLANE RESET TURN MB MAX FMAX",
    # Fusion: STAY, then the axes from Q121 / Q122, drilling cycle 200
    "fusion_stay": "PLANE SPATIAL SPA+0 SPB-40 SPC+30 STAY SEQ-\nL B+Q121 C+Q122 R0 FMAX\nL X+5 Y+5 R0 FMAX\n"
                   "L Z+10 FMAX\nCYCL DEF 200 DRILLING Q200=+2 Q201=-8 Q206=+150 Q202=+3 Q210=+0 Q203=+0 Q204=+10 "
                   "Q211=+0\nL X+5 Y+5 FMAX M99\nL X+25 FMAX M99\nL Y-15 FMAX M99\nL M140 MB MAX\nPLANE RESET STAY\n"
                   "L B+0 C+0 R0 FMAX",
    # NX: cycle 7 then cycle 19, the axes from Q121 / Q122, a radius arc, both reset
    "nx_cycle19": "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+5\nCYCL DEF 7.2 Y-3\nCYCL DEF 7.3 Z+0\n"
                  "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 A+0 B+45 C+0\nL B+Q121 C+Q122 R0 FMAX\n"
                  "L X+0 Y+0 Z+50 R0 FMAX M3\nL Z+2 FMAX\nL X+20 Y+0 Z-1 F800\nL Y+20\nCR X+0 Y+20 R+20 DR+\n"
                  "L Z+50 FMAX\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1\nCYCL DEF 7.0 DATUM SHIFT\n"
                  "CYCL DEF 7.1 X+0\nCYCL DEF 7.2 Y+0\nCYCL DEF 7.3 Z+0\nL B+0 C+0 R0 FMAX",
    # cycle 19 with F and ABST: the TNC positions the axes itself (MOVE DIST ABST)
    "cycle19_feed": "L X+0 Y+0 Z+80 R0 FMAX\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+20 C+0 F2000 ABST+10\n"
                    "L X+10 Y+10 Z+5 FMAX\nL X+30 F600\nL Z+40 FMAX\nCYCL DEF 19.0 WORKING PLANE\n"
                    "CYCL DEF 19.1 B+0 C+0 F2000 ABST+10",
    # SolidWorks-APT: a cycle 7 setup, cycle 19 then L B.., cycle 1 PECKING with M99
    "apt_cycle19": "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+12.000\nCYCL DEF 7.2 Y+4.000\nCYCL DEF 7.3 Z+0.000\n"
                   "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+45.000\nL B+45.000 C+0 FMAX\nL X+10 Y+10 Z+25 FMAX\n"
                   "CYCL DEF 1.0 PECKING\nCYCL DEF 1.1 DIST2.000\nCYCL DEF 1.2 DEPTH-5.400\nCYCL DEF 1.3 PLNGNG3.0\n"
                   "CYCL DEF 1.4 DWELL0\nCYCL DEF 1.5 F364\nL Z+2 FMAX\nL FMAX M99\nL X+30 FMAX M99\nL Z+50 FMAX\n"
                   "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+0.000\nL B+0 C+0 FMAX",
    # cycles 10 and 11 in a tilted plane
    "rotation_scaling": "PLANE SPATIAL SPA+0 SPB+60 SPC-20 TURN FMAX\nCYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30\n"
                        "CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL0.5\nL X+20 Y+10 Z+5 FMAX\nL X+40 F500\nL Y+30\n"
                        "CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL1\nCYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+0\n"
                        "L Z+50 FMAX\nPLANE RESET TURN FMAX",
    # cycle 26 under PLANE EULER .. MOVE DIST
    "euler_cycle26": "PLANE EULER EULPR+30 EULNU+40 EULROT-30 MOVE DIST+50 F3000\n"
                     "CYCL DEF 26.0 AXIS-SPECIFIC SCALING\nCYCL DEF 26.1 X1.5 Y0.8 CCX+10 CCY+5\nL X+0 Y+0 Z+3 FMAX\n"
                     "L X+20 Y+10 F400\nL X+20 Y+30\nCYCL DEF 26.0 AXIS-SPECIFIC SCALING\nCYCL DEF 26.1 X1 Y1\n"
                     "L Z+60 FMAX\nPLANE RESET MOVE DIST+50 F3000",
    # cycle 8 in a tilted plane: the arc's direction reverses
    "mirror": "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX\nCYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X\n"
              "L X+10 Y+5 Z+5 FMAX\nL X+30 F400\nCC X+30 Y+15\nC X+40 Y+15 DR+\nCYCL DEF 8.0 MIRROR IMAGE\n"
              "CYCL DEF 8.1\nL Z+50 FMAX\nPLANE RESET TURN FMAX",
    # M128 with the rotary axes in the lines (simultaneous), then M129
    "m128": "L B+0 C+0 FMAX\nM128\nL X+0 Y+0 Z+20 FMAX\nL X+10 Y+0 Z+5 B+10 C+0 F1000\nL X+20 Y+5 Z+3 B+20 C+15\n"
            "L X+30 Y+10 Z+3 B+30 C+30\nM129\nL Z+100 FMAX\nL B+0 C+0 FMAX",
    # FUNCTION TCPM .. AXIS POS (Fusion's 5-axis output)
    "function_tcpm": "FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS\nL X+0 Y+0 Z+20 B+0 C+0 FMAX\n"
                     "L X+10 Y+0 Z+5 B+15 C+0 F1000\nL X+20 Y+5 Z+3 B+25 C+10\nL X+25 Y+10 Z+3 B+25 C+40\n"
                     "FUNCTION RESET TCPM\nL Z+100 FMAX",
    # PLANE VECTOR (the manual's example), then PLANE RELATIV
    "vector_relativ": "PLANE VECTOR BX+0.8 BY-0.4 BZ-0.4472 NX+0.2 NY+0.2 NZ+0.9592 TURN FMAX\nL X+0 Y+0 Z+10 FMAX\n"
                      "L X+20 F500\nPLANE RELATIV SPB+15 TURN FMAX\nL X+0 Y+0 Z+10 FMAX\nL Y+20 F500\nL Z+60 FMAX\n"
                      "PLANE RESET TURN FMAX",
    # SYM-, MB, a MOVE with DIST and MB n, from rotary axes away from 0
    "sym_move": "L B+30 C+40 FMAX\nPLANE SPATIAL SPA+0 SPB-35 SPC+20 TURN MB MAX FMAX SYM-\nL X+5 Y+5 Z+5 FMAX\n"
                "PLANE SPATIAL SPA+10 SPB+25 SPC+0 TURN FMAX\nL X+5 Y+5 Z+5 FMAX\n"
                "PLANE SPATIAL SPA+0 SPB+50 SPC-120 MOVE DIST+30 MB+20 F2500\nL X+5 Y+5 Z+5 FMAX\n"
                "PLANE RESET TURN FMAX",
    # a datum shift before the plane, TRANS DATUM in it, reset
    "shift_in_plane": "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+15\nCYCL DEF 7.2 Y+5\n"
                      "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX\nL X+0 Y+0 Z+5 FMAX\nTRANS DATUM AXIS X+10 Y+0 Z+0\n"
                      "L X+0 Y+0 Z+5 FMAX\nTRANS DATUM RESET\nL X+0 Y+0 Z+5 FMAX\nPLANE RESET TURN FMAX\n"
                      "L X+0 Y+0 Z+5 FMAX",
    # PLANE RELATIV about the tilted tool axis, then PLANE AXIAL of one axis
    "relativ_axial": "PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN FMAX\nPLANE RELATIV SPC+40 TURN FMAX\nL X+10 Y+0 Z+5 FMAX\n"
                     "L Y+10 F300\nPLANE AXIAL B+60 TURN FMAX\nL X+10 Y+0 Z+5 FMAX\nL Y+10 F300\nPLANE RESET TURN FMAX",
    # cycle 19 with all three spatial angles, a polar arc in the plane
    "cycle19_polar": "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 A+20 B+30 C+45\nL B+Q121 C+Q122 R0 FMAX\n"
                     "L X+0 Y+0 Z+5 FMAX\nCC X+0 Y+0\nLP PR+20 PA+0 R0 F500\nCP IPA+90 DR+\nL Z+50 FMAX\n"
                     "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1\nL B+0 C+0 R0 FMAX",
    # cycle 251 in a plane turned about C by 90
    "pocket251": "PLANE SPATIAL SPA+0 SPB+45 SPC+90 TURN FMAX\nCYCL DEF 251 RECTANGULAR POCKET Q215=+0 Q218=+40 "
                 "Q219=+20 Q220=+3 Q368=+0 Q224=+15 Q367=+0 Q207=+500 Q351=+1 Q201=-6 Q202=+3 Q369=+0 Q206=+150 "
                 "Q338=+0 Q200=+2 Q203=+0 Q204=+20 Q370=+1 Q366=+0 Q385=+500\nL X+20 Y+10 Z+30 FMAX\nCYCL CALL\n"
                 "L Z+60 FMAX\nPLANE RESET TURN FMAX",
}

#: The same on an A/C table whose pivots are off the origin.
POST_STYLE_AC = {
    "projected": "PLANE PROJECTED PROPR+20 PROMIN+35 ROT+15 TURN FMAX\nL X+0 Y+0 Z+10 FMAX\nL X+15 Y-5 Z-2 F300\n"
                 "CC X+0 Y-5\nC X-15 Y-5 DR-\nL Z+30 FMAX\nPLANE RESET TURN FMAX",
    "points": "PLANE POINTS P1X+0 P1Y+0 P1Z+0 P2X+30 P2Y+31 P2Z+20 P3X+0 P3Y+41 P3Z+32.5 TURN FMAX\n"
              "L X+0 Y+0 Z+10 FMAX\nL X+12 Y+7 Z-1 F300\nL Z+40 FMAX\nPLANE RESET TURN FMAX",
    "axial": "L C-10 FMAX\nPLANE AXIAL A+40 C+170 TURN FMAX\nL X+0 Y+0 Z+10 FMAX\nL X+10 Y+5 Z-1 F300\nL Z+40 FMAX\n"
             "PLANE AXIAL C+90 MOVE DIST+20 FMAX\nL X+10 Y+5 Z+10 FMAX\nPLANE RESET TURN FMAX",
    "table_rot": "PLANE SPATIAL SPA+0 SPB+0 SPC+30 TURN FMAX TABLE ROT\nL X+10 Y+0 Z+5 FMAX\nL X+20 F300\n"
                 "PLANE SPATIAL SPA+0 SPB+0 SPC+30 TURN FMAX COORD ROT\nL X+10 Y+0 Z+5 FMAX\nL X+20 F300\n"
                 "PLANE RESET TURN FMAX",
    "tcpm_spat": "FUNCTION TCPM F TCP AXIS SPAT PATHCTRL AXIS\nL X+0 Y+0 Z+20 A+0 B+0 C+0 FMAX\n"
                 "L X+10 Y+0 Z+5 B+15 F1000\nL X+20 Y+5 Z+3 A+10 B+25\nFUNCTION RESET TCPM\nL Z+100 FMAX",
}


@pytest.mark.parametrize("name", sorted(POST_STYLE))
def test_post_style_programs_agree_with_the_reference_on_a_bc_table(name):
    run(POST_STYLE[name])


@pytest.mark.parametrize("name", sorted(POST_STYLE_AC))
def test_post_style_programs_agree_with_the_reference_on_an_ac_table(name):
    run(POST_STYLE_AC[name], CTX_AC, head="0 BEGIN PGM T MM\nTOOL CALL 2 Z S4000\nL Z+150 R0 FMAX\n")
