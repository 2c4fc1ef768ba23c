"""Heidenhain forms met in real TNC programs (session 40) where the independent reference (``reference_heidenhain``)
disagreed with the reader. Each program is hand-written in the style of the program that showed it: a TNC program
writer of a proton-therapy workshop (collimators, compensators, modulators; ``RND R0,5 F``, ``L Z+Q3 R F M``, a ring
``LP .. RL`` / ``RND R2`` / ``CP IPA+360`` / ``RND R2`` / ``L X+0 Y+0 R0``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

CTX = MachineContext()


def _arc_rows(prog, line: int):
    return [b for b in prog.blocks if b.line == line and b.kind == "arc"]


# -- a rounding radius below 1 mm written without its sign: 'RND R0.5', 'RND R0,5' (the decimal comma of a TNC set to
#    it), 'CR .. R0.5'. The reference read 'R0' as the compensation word and '.5' as its value (KeyError 'R');
#    the reader takes the radius 0.5 (iTNC 530 user's manual, "Rounding corners RND": R, the rounding radius) ------

def test_a_rounding_radius_below_one_written_r0_point_is_a_radius():
    text = ("0 BEGIN PGM R05 MM\n1 TOOL CALL 1 Z S3000 F500\n2 L X+0 Y+0 Z+10 R0 FMAX M3\n3 L Z-1 F200\n"
            "4 L X+10 F500\n5 RND R0.5\n6 L Y+10\n7 RND R0,5 F300\n8 L X+0\n9 CR X-0.5 Y+9.5 R0.5 DR+\n"
            "10 L Y+0\n11 END PGM R05 MM\n")
    prog = checked_program(text, CTX)  # the reference raised KeyError 'R' at 'RND R0.5'
    for line, centre in ((6, (9.5, 0.5)), (8, (9.5, 9.5)), (10, (0.0, 9.5))):
        (arc,) = _arc_rows(prog, line)
        assert arc.segment.radius == pytest.approx(0.5)
        assert np.allclose(arc.segment.center[:2], centre, atol=1e-9)
    assert _arc_rows(prog, 8)[0].feed == pytest.approx(300.0 / 60.0)  # 'RND R0,5 F300': its own feed [mm/s]


# -- a rounding programmed under RL/RR right before the block that cancels it with R0: the corner is the compensated
#    contour's (the tool leaves it from the corner's end). The reference took the compensation as off at the corner:
#    it cut an outside rounding exactly on the programmed contour (the reader: on the tool centre's path, the radius
#    out) and an inside one no larger than the tool (which the reader leaves to the tool centre paths, as it does
#    within a contour) as an arc into the wall -------------------------------------------------------------------

def test_an_outside_rounding_before_the_r0_block_is_on_the_tool_centre_path():
    text = ("0 BEGIN PGM RX MM\n1 TOOL DEF 1 L+0 R+3\n2 TOOL CALL 1 Z S3000 F500\n3 L X+0 Y+0 Z+10 R0 FMAX M3\n"
            "4 L Z-1 F200\n5 L X+10 Y+0 RL F500\n6 L X+10 Y+20\n7 RND R5\n8 L X+30 Y+20 R0\n9 L X+30 Y+0\n"
            "10 L Y+10 RR\n11 L X+50\n12 RND R2\n13 L X+50 Y+30 R0\n14 L Z+10 R0 FMAX\n15 END PGM RX MM\n")
    prog = checked_program(text, CTX, exact=False)  # the reference expected the arc's end at X+15 Y+20
    (arc,) = _arc_rows(prog, 8)
    assert arc.segment.radius == pytest.approx(8.0)  # R5 + the tool radius 3, about the corner's centre
    assert np.allclose(arc.segment.center[:2], (15.0, 15.0)) and np.allclose(arc.target[:2], (15.0, 23.0))
    (arc,) = _arc_rows(prog, 13)  # RR, turning left: outside too
    assert arc.segment.radius == pytest.approx(5.0) and np.allclose(arc.segment.center[:2], (48.0, 12.0))


def test_an_inside_rounding_no_larger_than_the_tool_before_the_r0_block_is_left_to_the_tool():
    text = ("0 BEGIN PGM RING MM\n1 TOOL DEF 1 L+0 R+6.97\n2 TOOL CALL 1 Z S2000\n3 L X+0 Y+0 Z+30 R0 FMAX M13\n"
            "4 CC X+0 Y+0\n5 L Z+25 R0 F MAX M\n6 LP PR+20 PA+0.000 RL F100 M\n7 RND R2 F\n8 CP IPA+360 DR+ RL F M\n"
            "9 RND R2 F\n10 L X+0.000 Y+0.000 R0 F MAX M\n11 END PGM RING MM\n")
    prog = checked_program(text, CTX, exact=False)  # the reference cut the second RND R2 on the contour, exactly
    assert not _arc_rows(prog, 8 - 1) and not _arc_rows(prog, 10)  # no rounding arcs (blocks 7, 9: lines 8, 10)
    ring = _arc_rows(prog, 9)
    assert len(ring) == 1 and ring[0].segment.radius == pytest.approx(20.0 - 6.97)
    assert np.allclose(prog.blocks[-1].target, (0.0, 0.0, 25.0))


# -- cycle 10 ROTATION defined while RL/RR is active (the workshop's modulator: a wing under RL, then 'CYCL DEF 10.1
#    IROT+120' and the next wing's 'LP PR+20 PA+Q5 RL'). iTNC 530 / TNC 640 cycle programming manuals, ROTATION
#    (cycle 10): "An active radius compensation is canceled by defining Cycle 10 and must therefore be
#    reprogrammed, if necessary". The reader refused it ('R0 before a coordinate transformation'); now the
#    compensated run ends where its last element's tool centre ends, and the next RL/RR enters anew --------------

ROTATION_UNDER_RL = """0 BEGIN PGM R MM
1 TOOL DEF 1 L+0 R+3
2 TOOL CALL 1 Z S3000 F500
3 L X+0 Y-20 Z+5 R0 FMAX M3
4 L Z-2 F200
5 L X+0 Y+0 RL F500
6 L X+20 Y+0
7 CYCL DEF 10.0 ROTATION
8 CYCL DEF 10.1 ROT+90
9 L Z+5 R0 FMAX
10 L X+0 Y+0 R0 FMAX
11 L Z-2 F200
12 L X+10 Y+0 RL F500
13 L X+10 Y+10
14 L X+20 Y+20 R0
15 CYCL DEF 10.0 ROTATION
16 CYCL DEF 10.1 ROT+0
17 END PGM R MM
"""


def test_cycle_10_under_rl_cancels_the_compensation():
    prog = checked_program(ROTATION_UNDER_RL, CTX, exact=False)  # refused before: 'cycle 10 while RL is active'
    at = {b.line: b.target for b in prog.blocks}
    assert np.allclose(at[7], (20.0, 3.0, -2.0))  # the run's last element ends beside X+20 Y+0, RL: +Y
    assert np.allclose(at[10], (20.0, 3.0, 5.0))  # no move to the contour's point: the tool stays there
    assert np.allclose(at[13], (0.0, 7.0, -2.0))  # RL anew under ROT+90: program X+10 Y+0, beside the next line
    assert np.allclose(at[15], (-20.0, 20.0, -2.0))
    assert any("cycle 10 cancels radius compensation RL" in n for n in prog.notes)


def test_other_transformations_under_rl_are_still_refused():
    text = ROTATION_UNDER_RL.replace("7 CYCL DEF 10.0 ROTATION\n8 CYCL DEF 10.1 ROT+90",
                                     "7 CYCL DEF 11.0 SCALING\n8 CYCL DEF 11.1 SCL 0.5")
    with pytest.raises(GCodeError, match="cycle 11 while radius compensation RL is active"):
        checked_program(text, CTX, check=False)
