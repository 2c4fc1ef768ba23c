"""Heidenhain forms met in real TNC programs (session 40) where the independent reference (``reference_heidenhain``)
disagreed with the reader. Each program is hand-written in the style of the program that showed it: a TNC program
writer of a proton-therapy workshop (collimators, compensators, modulators; ``RND R0,5 F``, ``L Z+Q3 R F M``, a ring
``LP .. RL`` / ``RND R2`` / ``CP IPA+360`` / ``RND R2`` / ``L X+0 Y+0 R0``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from tests.interpolators.reference_heidenhain import checked_program

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
