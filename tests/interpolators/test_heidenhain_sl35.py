"""Heidenhain forms vcnc refused though a TNC runs them (session 35): the point-pattern grids ``PATTERN DEF PAT1``
and ``FRAME1`` with ``CYCL CALL PAT``, and the simple contour formula ``CONTOUR DEF`` of the SL cycles. Each
program is hand-written with its points worked out by hand, and checked against the independent reference
(``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})

#: Cycle 200 DRILLING at the pattern's points: 2 mm set-up clearance, 5 deep, surface Z+0, 2nd clearance 10.
DRILL = ("CYCL DEF 200 DRILLING Q200=+2 Q201=-5 Q206=+150 Q202=+5 Q210=+0 Q203=+0 Q204=+10 Q211=+0\n"
         "CYCL CALL PAT FMAX\n")


def checked(body: str):
    return checked_program("0 BEGIN PGM T MM\n" + body + "END PGM T MM\n", CTX)


def holes(prog) -> list[list[float]]:
    """The X/Y of each hole: where a feed move along the tool axis (the drilling) starts."""
    out = []
    for b in prog.blocks:
        if b.kind == "line" and b.target[2] < b.start[2] and np.allclose(b.target[:2], b.start[:2]):
            out.append(np.round(b.target[:2], 9).tolist())
    return out


def test_pattern_def_pat_drills_the_grid_row_by_row_in_meander():
    # TNC 640 cycle programming manual, "PATTERN DEF", "Defining a point pattern": PAT1 (X Y DX DY NUMX NUMY ..);
    # 3 x 2 points from (10, 20), 5 apart in X and 8 in Y: the first row left to right, the second back (the
    # meander of cycle 221 CARTESIAN PATTERN). It was refused as 'pattern PAT1 is not supported'.
    prog = checked("1 L X+0 Y+0 Z+50 R0 FMAX\n"
                   "2 PATTERN DEF PAT1 (X+10 Y+20 DX+5 DY+8 NUMX3 NUMY2 ROT+0 ROTX+0 ROTY+0 Z+0)\n" + DRILL)
    assert holes(prog) == [[10, 20], [15, 20], [20, 20], [20, 28], [15, 28], [10, 28]]


def test_pattern_def_frame_drills_only_the_outline_of_the_grid():
    # FRAME1 ("Defining a frame"): the same words, the points on the grid's outline; 3 x 3 from (0, 0) 10 apart,
    # turned by ROT+90 about the first point: the centre (10, 10) -> (-10, 10) is left out
    prog = checked("1 L X+0 Y+0 Z+50 R0 FMAX\n"
                   "2 PATTERN DEF FRAME1 (X+0 Y+0 DX+10 DY+10 NUMX3 NUMY3 ROT+90 ROTX+0 ROTY+0 Z+0)\n" + DRILL)
    assert holes(prog) == [[0, 0], [0, 10], [0, 20], [-10, 20], [-10, 0], [-20, 0], [-20, 10], [-20, 20]]


def test_pattern_def_pat_rotx_roty_turn_the_rows_and_columns_alone_and_q_parameters_give_the_words():
    # ROTX+90 turns the reference axis alone: the row runs along +Y; ROTY-90 turns the minor axis: the columns
    # run along +X (a grid of 2 x 2, DX 4, DY 6 from Q1 = 1, Q2 = 2); Z+1 raises the surface by 1
    prog = checked("1 Q1 = 1\n2 Q2 = 2\n3 L X+0 Y+0 Z+50 R0 FMAX\n"
                   "4 PATTERN DEF PAT1 (X+Q1 Y+Q2 DX+4 DY+6 NUMX2 NUMY2 ROT+0 ROTX+90 ROTY-90 Z+1)\n" + DRILL)
    assert holes(prog) == [[1, 2], [1, 6], [7, 6], [7, 2]]
    assert min(b.target[2] for b in prog.blocks) == pytest.approx(1 - 5)  # Q201 below the raised surface


@pytest.mark.parametrize("form, match", [
    ("PAT1 (X+0 Y+0 DX+5 NUMX3 NUMY2)", "PAT without DY"),
    ("PAT1 (X+0 Y+0 DX+5 DY+5 NUMX0 NUMY2)", "NUMX0"),
    ("FRAME1 (X+0 Y+0 DX+5 DY+5 NUMX2 NUMY2.5)", "NUMY2.5"),
    ("PAT1 (X+0 Y+0 DX+5 DY+5 NUMX2 NUMY2 D+3)", "word 'D\\+3'"),
])
def test_pattern_def_pat_and_frame_name_what_is_wrong(form, match):
    with pytest.raises(GCodeError, match=match):
        parse_heidenhain(f"0 BEGIN PGM T MM\n1 PATTERN DEF {form}\n2 END PGM T MM\n", source="t.h", context=CTX)
