"""Heidenhain programs of an eleventh wild set (hyperMILL posts for a DMU 85 monoBLOCK and a DMC 105V
linear, FreeCAD's heidenhain post, a home-made APT converter, Polish-dialogue school programs, an NX
user-function post): the forms the set leans on that no earlier test held, each as a hand-written program
checked against the independent reference where it runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()
#: A B/C tilting table, B about Y with its pivot 50 mm below the part's zero, C about Z.
TILT = MachineContext(home=(0.0, 0.0, 300.0), extra_axes=("b", "c"),
                      kinematics=Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0),
                                                             limits=(-120.0, 120.0)), RotaryAxis(name="c"))))


def checked(body: str, context: MachineContext = ZERO):
    """The program read, and its blocks matched against the reference."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", context)


def dwells(prog) -> list[float]:
    return [b.dwell for b in prog.blocks if b.kind == "dwell"]


def test_polish_dwell_text_ending_in_a_dot_is_the_name_not_the_number():
    # a Polish TNC saves cycle 9 as 'CYCL DEF 9.1 CZAS ZWL.0.5' (CZAS ZWL. = dwell time): the dot closes the
    # name and 0.5 s is the dwell; it was a 'malformed number .0.5'. The hyperMILL DMC post's Hungarian
    # 'CYCL DEF9.1 V.IDO5' keeps its 5 s, and a number written '.5' after a blank stays 0.5
    prog = checked("TOOL CALL 1 Z S1000\nL Z+10 R0 FMAX\nCYCL DEF 9.0 CZAS ZATRZYMANIA\nCYCL DEF 9.1 CZAS ZWL.0.5\n"
                   "CYCL DEF9 .0 VARAKOZASI IDO\nCYCL DEF9.1 V.IDO5\nCYCL DEF 9.0 DWELL TIME\nCYCL DEF 9.1 DWELL .5")
    assert dwells(prog) == [0.5, 5.0, 0.5]


def test_polish_pocket_cycle_4_rounds_its_corners_with_promien():
    # 'CYCL DEF 4.6 F100 DR+ PROMIEN 10' (PROMIEN: radius) rounds the pocket's corners: the tool path (R 5)
    # turns on radius 10 - 5 = 5 about (80, 70) from the side at X 85 to the side at Y 75
    prog = checked("TOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z S2000\nL Z+100 R0 FMAX M3\nCYCL DEF 4.0 FREZ. KIESZENI\n"
                   "CYCL DEF 4.1 ODSTEP 2\nCYCL DEF 4.2 GLEBOKOSC -4\nCYCL DEF 4.3 DOSUW 4 F80\nCYCL DEF 4.4 X80\n"
                   "CYCL DEF 4.5 Y60\nCYCL DEF 4.6 F100 DR+ PROMIEN 10\nL X+50 Y+50 R0 FMAX\nL Z+2 R0 FMAX M99")
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    assert len(arcs) == 4
    assert np.asarray(arcs[0].segment.center)[:2] == pytest.approx([80.0, 70.0])
    assert np.asarray(arcs[0].target) == pytest.approx([80.0, 75.0, -4.0])
    assert arcs[0].feed * 60 == pytest.approx(100.0)


def test_cycle_19_with_a_feed_positions_the_rotary_axes_itself():
    # 'CYCL DEF 19.1 B+10 C+90 F1000 ABST 50' (a Polish school program, the F and ABST a TNC asks for when it
    # positions the rotary axes itself): the axes turn at F1000 as PLANE .. MOVE DIST50 would turn them, and the
    # next move is in the tilted plane; without F the program must position them (an error before the move)
    body = "TOOL CALL 1 Z S2000\nL Z+100 R0 FMAX M91\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+10 C+90{}\n" \
           "L X+10 Y+10 R0 FMAX\nL Z+5 R0 FMAX"
    cycle = checked(body.format(" F1000 ABST 50"), TILT)
    plane = checked(body.replace("CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+10 C+90{}",
                                 "PLANE SPATIAL SPA+0 SPB+10 SPC+90 MOVE DIST50 F1000"), TILT)
    turn = cycle.blocks[1]
    assert turn.kind == "line" and turn.feed * 60 == pytest.approx(1000.0)
    assert turn.extra_target[1:3] == pytest.approx([10.0, 90.0])
    assert np.array([b.target for b in cycle.blocks]) == pytest.approx(np.array([b.target for b in plane.blocks]))
    with pytest.raises(GCodeError, match=r"t.h:6:1: a move in the tilted plane of CYCL DEF 19 \(line 5\) while the "
                                         r"rotary axes are not at its positions B\+10.0000 C\+90.0000"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + body.format("") + "\nEND PGM T MM\n", source="t.h", context=TILT)


def test_cycle_19_f_of_an_nx_post_then_its_own_positioning_block():
    # an NX user-function post writes 'CYCL DEF 19.1 B30.000 C90.000 F1000' and then 'L C+Q122 B+Q121 R0 F MAX':
    # the cycle has turned the axes (B30: the tool tip keeps its place, X -75, Z 79.9 over the pivot), so the
    # block finds them there and moves nothing; 19.1 without angles and F cancels the plane without motion
    prog = checked("TOOL CALL 1 Z S2000\nL Z+100 R0 FMAX M91\nCYCL DEF 19.0 WORKING PLANE\n"
                   "CYCL DEF 19.1 B30.000 C90.000 F1000\nL C+Q122 B+Q121 R0 F MAX\nL X+10 Y+10 R0 FMAX\n"
                   "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1\nL Z+100 R0 FMAX", TILT)
    assert [b.kind for b in prog.blocks] == ["rapid", "line", "rapid", "rapid", "rapid"]
    assert prog.blocks[1].extra_target[1:3] == pytest.approx([30.0, 90.0])
    assert np.asarray(prog.blocks[1].target) == pytest.approx([-75.0, 0.0, 79.903811])
    assert np.asarray(prog.blocks[2].target) == pytest.approx(np.asarray(prog.blocks[1].target))
    assert prog.blocks[-1].extra_target[1:3] == pytest.approx([30.0, 90.0])  # the cancel turns nothing back


def test_plane_spatial_with_a_q_parameter_angle_and_turn_at_a_feed():
    # 'PLANE SPATIAL SPA+0 SPB+Q27 SPC+90 TURN F99999 SEQ-' (a TNC program held by a Klartext parser's tests): the
    # Q parameter is the angle, TURN at F99999 is a feed move of the rotary axes alone
    prog = checked("TOOL CALL 1 Z S2000\nFN 0: Q27 = +30\nL Z+100 R0 FMAX M91\n"
                   "PLANE SPATIAL SPA+0 SPB+Q27 SPC+90 TURN F99999 SEQ-\nL X+10 Y+10 R0 FMAX\n"
                   "PLANE RESET TURN F5000", TILT)
    turn = prog.blocks[1]
    assert turn.kind == "line" and turn.feed * 60 == pytest.approx(99999.0)
    assert np.asarray(turn.target) == pytest.approx([0.0, 0.0, 100.0])
    assert abs(turn.extra_target[1]) == pytest.approx(30.0)
    assert prog.blocks[-1].extra_target[1:3] == pytest.approx([0.0, 0.0])


def test_freecad_post_forms_bare_m_negative_cycle_1_distance_and_no_program_name():
    # FreeCAD's heidenhain_post.py (default settings) writes 'BEGIN PGM MM' without a name, F8000 for rapids,
    # a bare 'M' on every block after the first, and cycle 1 in Italian with the set-up clearance negative
    # (DIST = surface - R plane): from Z3 over the surface at 0 the hole goes to -10 at F100
    text = ("0 BEGIN PGM MM\n1 TOOL CALL 1 Z S1000 ;TC: Default Tool\n2 L Z10.000 R0 F8000 M3\n"
            "3 L X40.000 Y40.000 R0 F8000 M\n4 L Z3.000 R0 F8000 M\n5 CYCL DEF 1.0 FORATURA PROF.\n"
            "6 CYCL DEF 1.1 DIST-3.000\n7 CYCL DEF 1.2 PROF-10.000\n8 CYCL DEF 1.3 INCR-10.000\n9 CYCL DEF 1.4 SOSTA0\n"
            "10 CYCL DEF 1.5 F100\n11 CYCL CALL M\n12 L Z10.000 R0 F8000 M5\n13 END PGM MM\n")
    prog = checked_program(text, ZERO)
    ends = [tuple(np.round(b.target, 6)) for b in prog.blocks]
    assert ends[3:5] == [(40.0, 40.0, -10.0), (40.0, 40.0, 3.0)]
    assert prog.blocks[3].feed * 60 == pytest.approx(100.0) and math.isinf(prog.blocks[4].feed)
    assert prog.blocks[0].feed * 60 == pytest.approx(8000.0)


def test_hypermill_f_max_with_a_blank_and_signless_plane_angles():
    # the hyperMILL DMU post writes 'L X160.5 Y-35 R0 F MAX M3' (F MAX with a blank: rapid) and
    # 'PLANE SPATIAL SPA0 SPB0 SPC0 STAY SEQ+ TABLE ROT' (no tilt), then positions with 'L A+Q120 C+Q122'
    prog = checked("TOOL CALL 1 Z S6701 DL+0 DR+0\nCYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1 T0.015\n"
                   "CYCL DEF 32.2 HSC-MODE:0\nL Z0 R0 FMAX M91\nCYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X0\n"
                   "CYCL DEF 7.2 Y0\nCYCL DEF 7.3 Z0\nPLANE SPATIAL SPA0 SPB0 SPC0 STAY SEQ+ TABLE ROT\n"
                   "L X160.5 Y-35 R0 F MAX M3\nL Z25 R0 F MAX", TILT)
    assert [b.kind for b in prog.blocks][-2:] == ["rapid", "rapid"]
    assert np.asarray(prog.blocks[-1].target) == pytest.approx([160.5, -35.0, 25.0])


def test_m140_retract_at_its_own_feed():
    # a gear-cutting NC converter writes 'M11 M16 M140 MB MAX F5000' (a block of M functions): the F after MB is
    # the retraction's feed (TNC 640 user's manual, M140; its example 'L X+0 Y+38.5 F125 M140 MB 50 F750'); it was
    # a 'word in a block without motion', and in 'L M140 MB MAX F500' it silently became the path feed
    home = MachineContext(home=(0.0, 0.0, 100.0))
    prog = checked("TOOL CALL 1 Z S100\nL X+10 Y+10 Z-5 R0 F100\nM11 M16 M140 MB MAX F5000\nL X+20\n"
                   "L X+0 Y+38.5 F125 M140 MB 50 F750\nL M140 MB MAX FMAX\nL X+30", home)
    rows = [(b.kind, *np.round(b.target, 6).tolist(), round(b.feed * 60, 6)) for b in prog.blocks[1:]]
    assert rows == [("line", 10, 10, 100, 5000), ("line", 20, 10, 100, 100), ("line", 0, 38.5, 100, 125),
                    ("line", 0, 38.5, 150, 750), ("line", 30, 38.5, 150, 125)]
    with pytest.raises(GCodeError, match=r"t.h:2:13: feed F of M140 must be > 0"):
        parse_heidenhain("0 BEGIN PGM T MM\nM140 MB MAX F0\nEND PGM T MM\n", source="t.h", context=home)


def test_begin_pgm_with_the_unit_alone_is_a_program_without_a_name():
    # FreeCAD's heidenhain post writes 'BEGIN PGM MM', or with its UNITS INCH 'BEGIN PGM INCH': the lone word is
    # the unit (it was taken as the name, and the INCH program silently read in millimetres)
    inch = checked_program("0 BEGIN PGM INCH\n1 TOOL CALL 1 Z S1000\n2 L X1.000 Y1.000 Z0.500 R0 F100 M3\n"
                           "3 END PGM INCH\n", ZERO)
    assert np.asarray(inch.blocks[0].target) == pytest.approx([25.4, 25.4, 12.7])
    assert inch.blocks[0].feed * 60 == pytest.approx(2540.0 / 10)
    mm = checked_program("0 BEGIN PGM MM\n1 L X1.000 Y1.000 Z0.500 R0 F100\n2 END PGM MM\n", ZERO)
    assert np.asarray(mm.blocks[0].target) == pytest.approx([1.0, 1.0, 0.5])
