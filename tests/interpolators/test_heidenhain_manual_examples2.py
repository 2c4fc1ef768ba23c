"""Forms of HEIDENHAIN's own example programs (the user's manuals' Q parameter examples, HEIDENHAIN's published NC
solutions and HIT training solutions) that the reader refused or ran otherwise, each as a few hand-written blocks
with its end points worked out by hand and checked against the independent reference (``reference_heidenhain``).
The examples themselves ran through ``/tmp/tncman10/run.py`` (kept out of the repository)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()


def checked(body: str, *, exact: bool = True):
    """The program read, and its blocks matched against the reference (``exact=False``: compensated rows within
    the tool radius)."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO, exact=exact)


def test_polar_arc_without_an_angle_is_a_full_circle():
    # HEIDENHAIN's NC solution 11101 mills a bore as a helix 'CP IPA+9000 Z-30 DR+' and then its floor with
    # 'CP DR+': no PA, so the end angle stays the current one (as an LP without PA keeps it) and the end is the
    # start: one whole turn. Pole (50, 50), start (60, 50): the floor circle ends at (60, 50) after 360 deg
    prog = checked("1 L X+60 Y+50 Z+0 R0 F500\n2 CC X+50 Y+50\n3 CP IPA+720 Z-4 DR+\n4 CP DR+\n5 L X+50 Y+50")
    helix, floor = prog.blocks[1], prog.blocks[2]
    assert np.allclose(helix.target, [60, 50, -4]) and np.allclose(floor.target, [60, 50, -4])
    assert floor.segment.ccw and math.isclose(floor.segment.sweep, 2 * math.pi)
    cw = checked("1 L X+60 Y+50 Z+0 R0 F500\n2 CC X+50 Y+50\n3 CP DR-")
    assert not cw.blocks[-1].segment.ccw and math.isclose(cw.blocks[-1].segment.sweep, -2 * math.pi)


def test_polar_full_circle_under_radius_compensation():
    # the NC solution's form: 'LP PR+5 PA+0 RL' switches RL on at the bore's radius, the helix and the floor circle
    # follow; tool radius 2 (TOOL DEF): RL on a counter-clockwise circle of radius 5 puts the centre at radius 3
    prog = checked("1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n3 L X+0 Y+0 Z+0 R0 F300\n4 CC X+0 Y+0\n"
                   "5 LP PR+5 PA+0 RL\n6 CP IPA+360 Z-2 DR+\n7 CP DR+\n8 L X+0 Y+0 R0", exact=False)
    arcs = [b for b in prog.blocks if b.kind != "line"]
    assert len(arcs) == 2 and all(np.isclose(b.segment.radius, 3.0) for b in arcs)
    assert np.allclose(arcs[-1].target, [3, 0, -2])


def test_polar_arc_without_angle_or_direction_is_an_error():
    with pytest.raises(GCodeError, match=r"CP arc without direction .*expected DR\+ or DR-"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L X+10 Y+0 Z+0 R0 F100\n2 CC X+0 Y+0\n3 CP\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


# the TNC 640 user's manual's Q parameter example "Sphere" turns the part with cycle 10 ROTATION between its arcs
# and moves on each in the Z/X plane: 'CC Z+0 X+Q108' (Q108: the tool radius) and 'LP PR+Q6 PA+Q24'. With the
# rotation ROT+90 the program's X is the machine's Y: about the pole (Z 0, X 0) at radius 10 and PA+30 (from +Z
# toward +X) the program point is X 5, Z 8.660, so the machine point is (0, 5, 8.660)
SPHERE = ("1 L X+0 Y+0 Z+20 R0 FMAX\n2 CYCL DEF 10.0 ROTATION\n3 CYCL DEF 10.1 ROT+90\n4 FN 0: Q108 = +0\n"
          "5 FN 1: Q26 = +10 + +Q108\n6 CC Z+0 X+Q108\n7 LP PR+Q26 PA+30 R0 F300\n8 LP IPA-30\n")


def test_polar_line_about_a_pole_in_zx_under_a_rotation():
    prog = checked(SPHERE)
    assert np.allclose(prog.blocks[-2].target, [0, 5, 10 * math.cos(math.radians(30))])
    # IPA-30 from there: PA 0, on +Z above the pole
    assert np.allclose(prog.blocks[-1].target, [0, 0, 10])


def test_arc_about_a_pole_in_zx_under_a_rotation_stays_an_error():
    # an arc in a plane turned out of the machine's axes is not modelled; the CC itself is read
    with pytest.raises(GCodeError, match=r"CP about a CC outside the working plane under R0 or a coordinate "
                                         r"transformation"):
        checked(SPHERE + "9 CP IPA+90 DR+")

