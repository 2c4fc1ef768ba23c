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
    ("PAT1 (X+0 Y+0 DX+5 DY+5 NUMX1000 NUMY1000)", "NUMX1000 x NUMY1000 points"),  # checked before they are made
])
def test_pattern_def_pat_and_frame_name_what_is_wrong(form, match):
    with pytest.raises(GCodeError, match=match):
        parse_heidenhain(f"0 BEGIN PGM T MM\n1 PATTERN DEF {form}\n2 END PGM T MM\n", source="t.h", context=CTX)


# -- CONTOUR DEF, the simple contour formula -----------------------------------------------------------------------

#: Cycle 20 and 22 (tool radius 3, Q3 = 0.5: the rings keep 3.5 from every contour; one infeed Q10 = 5 to Q1 = -5
#: less Q4 = 0.5: machine Z -4.5 + 10 = 5.5), called at Z+100.
SL = ("1 TOOL CALL 1 Z S1000\n2 L Z+100 R0 FMAX\n{contour}"
      "4 CYCL DEF 20 CONTOUR DATA Q1=-5 Q2=1 Q3=+0.5 Q4=+0.5 Q5=+0 Q6=2 Q7=+50 Q8=0 Q9=+1\n"
      "5 CYCL DEF 22 ROUGH-OUT Q10=+5 Q11=100 Q12=350 Q18=0 Q19=0\n6 CYCL CALL\n7 L Z+100 R0 FMAX M30\n"
      "8 LBL 1\n9 L X+0 Y+0 RL\n10 L X+30\n11 L Y+30\n12 L X+0\n13 L Y+0\n14 LBL 0\n"
      "15 LBL 2\n16 L X+10 Y+10 RL\n17 L X+20\n18 L Y+20\n19 L X+10\n20 L Y+10\n21 LBL 0\n")
CYCLE_14 = "3 CYCL DEF 14.0 CONTOUR\n3 CYCL DEF 14.1 CONTOUR LABEL {labels}\n"


def _sl(contour: str, *, exact: bool = True):
    return checked_program("0 BEGIN PGM T MM\n" + SL.format(contour=contour) + "END PGM T MM\n", CTX, exact=exact)


def _cut(prog) -> np.ndarray:
    """The X/Y of points along every move wholly below the surface (machine Z 10)."""
    below = [b for b in prog.blocks if b.segment is not None and max(b.start[2], b.target[2]) < 10.0 - 1e-9]
    return np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 20)))[:, :2]
                           for b in below])


def _outside_square(pts: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """The distance of points to the square [lo, hi]^2 (0 inside)."""
    d = np.maximum(np.maximum(lo - pts, pts - hi), 0.0)
    return np.hypot(d[:, 0], d[:, 1])


def test_contour_def_with_one_pocket_runs_as_cycle_14_with_its_label():
    # TNC 640 cycle programming manual, "SL cycles with simple contour formula": CONTOUR DEF P1 = LBL 1 instead of
    # CYCL DEF 14; cycle 22 clears the 30 x 30 pocket of LBL 1 as it does for cycle 14 (the reference models the
    # rings of one pocket exactly). It was refused as 'CONTOUR DEF ... is not supported'.
    formula = _sl("3 CONTOUR DEF P1 = LBL 1\n")
    cycle = _sl(CYCLE_14.format(labels="1"))
    assert [b.target.tolist() for b in formula.blocks] == [b.target.tolist() for b in cycle.blocks]
    assert np.round(_cut(formula).min(axis=0), 9).tolist() == [3.5, 3.5]  # R + Q3 from the walls


def test_contour_def_island_is_an_island_by_its_letter_whatever_its_direction_and_rl():
    # LBL 2 runs counter-clockwise with RL, as LBL 1 does: cycle 14 reads both as pockets (the tool inside each)
    # and clears the square 10..20 too; CONTOUR DEF's I2 makes it an island, which every cut keeps R + Q3 = 3.5
    # clear of (the TNC manual: P a pocket, I an island). Continued over lines with '~', with DI2 = 0 (Q1 applies).
    islands = _sl("3 CONTOUR DEF ~\n  P1 = LBL 1 ~\n  I2 = LBL 2 ~\n  DI2 = 0\n", exact=False)
    pts = _cut(islands)
    assert _outside_square(pts, 10.0, 20.0).min() >= 3.5 - 1e-3
    assert _outside_square(pts, 10.0, 20.0).min() <= 3.5 + 1e-2  # the first ring runs round the island
    assert np.all((pts >= 3.5 - 1e-3) & (pts <= 26.5 + 1e-3))  # and within the pocket
    pockets = _sl(CYCLE_14.format(labels="1 /2"), exact=False)
    assert _outside_square(_cut(pockets), 10.0, 20.0).min() == 0.0  # cycle 14: LBL 2 a pocket, cut inside


def test_contour_def_orders_the_subcontours_by_their_numbers_for_cycle_25():
    # cycle 25 CONTOUR TRAIN runs the first subcontour: P1 although it is written after I2 (the numbers order the
    # formula); the train along LBL 1 with R0 (the tool centre on it) at the depth Q1 = -5 in one infeed
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L Z+100 R0 FMAX\n3 CONTOUR DEF I2 = LBL 2 P1 = LBL 1\n"
            "4 CYCL DEF 25 CONTOUR TRAIN Q1=-5 Q3=+0 Q5=+0 Q7=+50 Q10=+5 Q11=100 Q12=350 Q15=+1\n"
            "5 L X-10 Y-10 R0 FMAX\n6 CYCL CALL\n7 L Z+100 R0 FMAX M30\n8 LBL 1\n9 L X+0 Y+0 R0\n10 L X+30\n"
            "11 L Y+30\n12 LBL 0\n13 LBL 2\n14 L X+10 Y+10 R0\n15 L X+20\n16 LBL 0\nEND PGM T MM\n")
    prog = checked_program(text, CTX)
    flat = [np.round(b.target, 9).tolist() for b in prog.blocks if b.kind == "line" and b.target[2] == 5.0]
    assert flat[-2:] == [[30.0, 0.0, 5.0], [30.0, 30.0, 5.0]]


@pytest.mark.parametrize("contour, match", [
    ("3 CONTOUR DEF P1 = LBL 1 DP1 = -5\n", "depth DP1 = -5 of a subcontour of its own is not supported"),
    ("3 CONTOUR DEF P1 = LBL 1 I2 = LBL 2 DI2 = +Q5\n", None),  # Q5 = 0 (unset): Q1 applies
    ('3 CONTOUR DEF P1 = "POCKET.H"\n', "subcontour P1 = \"POCKET.H\" in another program is not supported"),
    ("3 CONTOUR DEF I1 = LBL 2\n", "CONTOUR DEF names islands only"),
    ("3 CONTOUR DEF P1 = LBL 1 DI2 = 0\n", "depth DI2 of a subcontour I2 not defined"),
    ("3 CONTOUR DEF P1 = LBL 1 P1 = LBL 2\n", "subcontour number P1"),
    ("3 CONTOUR DEF P10 = LBL 1\n", "subcontour number P10"),
    ("3 CONTOUR DEF P1 = LBL 1 X+5\n", "'X\\+5' is not a subcontour"),
    ("3 CONTOUR DEF P1 = LBL 7\n", "label 7 is not defined"),
    ("3 QC1 = QC2 \\ QC3\n", "contour formula QCn"),
    ('3 DECLARE CONTOUR QC1 = "POCKET"\n', "DECLARE CONTOUR"),
])
def test_contour_def_names_what_it_does_not_run(contour, match):
    text = "0 BEGIN PGM T MM\n" + SL.format(contour=contour) + "END PGM T MM\n"
    if match is None:
        assert parse_heidenhain(text, source="t.h", context=CTX).blocks
        return
    with pytest.raises(GCodeError, match=match):
        parse_heidenhain(text, source="t.h", context=CTX)
