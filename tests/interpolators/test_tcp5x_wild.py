"""5-axis TCP as real programs write it (wild set 5x: CAM posts for TNC trunnion machines): hand-written
snippets modelled on them, each checked against the reference (tests/interpolators/reference_heidenhain.py)
and against the table's map worked out here."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.tilted import Solution
from tests.interpolators.test_tcp5x import BC, block_seconds, machine, tnc
from vcnc.errors import GCodeError

#: the tip's start and end on the part (rotary axes at 0): part (10, 0, 0) -> (40, 10, 5) from the preset (10, 5, 0)
START, END = np.array([20.0, 5.0, 0.0]), np.array([50.0, 15.0, 5.0])
MOVE = "L X+10 Y+0 Z+0 F600\n{m128}\nL X+40 Y+10 Z+5 B+30 C+45"


@pytest.mark.parametrize("m128", ["M128 FQ20", "L Z+0 F600 M128 F5000"])
def test_the_f_of_an_m128_block_is_not_the_path_feed(m128):
    # 'M128 FQ20' (a German CAM post), 'L .. M128 F..' (the iTNC 530 manual's example): the F after M128 is the
    # feed of its compensation movements (TNC 640 manual, M128), so the line after it keeps F600: 10 mm/s of
    # the tip on the part
    prog = tnc("FN 0: Q20 = +10000\n" + MOVE.format(m128=m128))
    chords = [b for b in prog.blocks if b.extra_target is not None and b.extra_target[2] != 0.0]
    assert chords[-1].target == pytest.approx(machine(BC, END, Solution(30.0, 45.0)), abs=1e-9)
    assert block_seconds(chords) == pytest.approx(np.linalg.norm(END - START) / 10.0, rel=1e-9)


def test_m128_in_a_plane_that_does_not_turn_reads_as_without_it():
    # 'PLANE VECTOR BX1 BY0 BZ0 NX0 NY0 NZ1 STAY' (a CAM post writes it before every operation) leaves the
    # workpiece coordinates untilted at B+0 C+0: M128 under it moves as with no plane (our reading)
    plane = "PLANE VECTOR BX1 BY0 BZ0 NX0 NY0 NZ1 STAY SEQ- TABLE ROT\nL B+Q121 C+Q122 R0 FMAX\n"
    with_plane, without = tnc(plane + MOVE.format(m128="M128")), tnc(MOVE.format(m128="M128"))
    assert with_plane.blocks[-1].target == pytest.approx(machine(BC, END, Solution(30.0, 45.0)), abs=1e-9)
    same = [b.target for b in with_plane.blocks[-len(without.blocks) + 1:]]
    assert np.array(same) == pytest.approx(np.array([b.target for b in without.blocks[1:]]), abs=1e-12)


def test_a_rotary_move_under_m128_in_a_plane_that_turns_is_an_error_naming_it():
    # M128 itself is read there since tncposts38 (a line whose rotary axes stay is the plane's line); C+45 moves
    plane = "PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN FMAX\n"
    with pytest.raises(GCodeError, match=r"rotary axis moving under M128 / FUNCTION TCPM in a tilted working plane"):
        tnc(plane + MOVE.format(m128="M128"))
