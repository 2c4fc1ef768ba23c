"""SL cycles of Heidenhain programs: CYCL DEF 14 CONTOUR GEOMETRY, 20 CONTOUR DATA, 25 CONTOUR TRAIN.

Each program is hand-written with its end points worked out by hand (tool radius 3 mm, tool length 10 mm:
machine Z = program Z + 10), and checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})

HEAD = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L Z+100 R0 FMAX\n3 CYCL DEF 14.0 CONTOUR\n"
        "4 CYCL DEF 14.1 CONTOUR LABEL 1\n")
TRAIN = ("5 CYCL DEF 25 CONTOUR TRAIN ~\n  Q1=-10 ;MILLING DEPTH ~\n  Q3=+{q3} ;ALLOWANCE FOR SIDE ~\n"
         "  Q5=+0 ;SURFACE COORDINATE ~\n  Q7=+50 ;CLEARANCE HEIGHT ~\n  Q10=+5 ;PLUNGING DEPTH ~\n"
         "  Q11=100 ;FEED RATE FOR PLUNGING ~\n  Q12=350 ;FEED RATE FOR MILLING ~\n  Q15={q15} ;CLIMB OR UP-CUT\n")
CALL = "6 L X-10 Y-10 R0 FMAX\n7 CYCL CALL\n8 L X-10 Y-10 Z+100 R0 FMAX M30\n"
LINES = "9 LBL 1\n10 L X+0 Y+0 {side}\n11 L X+40\n12 L Y+30\n13 LBL 0\n"


def run(text: str):
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    match = match_blocks(heidenhain_reference(text, CTX), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    assert match.exact + match.within >= len(prog.blocks)
    return prog


def train(*, q15: str = "+1", side: str = "RL", q3: str = "0", contour: str = LINES):
    return run(HEAD + TRAIN.format(q3=q3, q15=q15) + CALL + contour.format(side=side) + "END PGM T MM\n")


def moves(prog, first: int = 2, last: int = -1):
    """(kind, x, y, z, feed [mm/min]) of the cycle's blocks."""
    out = []
    for b in prog.blocks[first:last]:
        kind = b.kind if b.kind != "arc" else ("arc_ccw" if b.segment.ccw else "arc_cw")
        out.append((kind, *np.round(b.target, 6).tolist(), round(b.feed * 60, 6) if np.isfinite(b.feed) else "max"))
    return out


def test_contour_train_follows_an_rl_contour_at_each_infeed_with_climb_milling():
    # RL, Q15=+1 (climb: the tool left of its path) runs as programmed: at Q7 (Z50 + 10) over the first
    # point moved R = 3 left of X+, i.e. (0, 3); Q11 down to Z-5; X+40 ends at the inside corner (37, 3); Y+30
    # ends 3 left of it at (37, 30); FMAX up to Q7; again at Z-10; the tool ends at Q7 over (37, 30)
    prog = train()
    assert moves(prog) == [
        ("rapid", -10, -10, 60, "max"), ("rapid", 0, 3, 60, "max"), ("line", 0, 3, 5, 100),
        ("line", 37, 3, 5, 350), ("line", 37, 30, 5, 350), ("rapid", 37, 30, 60, "max"),
        ("rapid", 0, 3, 60, "max"), ("line", 0, 3, 0, 100), ("line", 37, 3, 0, 350), ("line", 37, 30, 0, 350),
        ("rapid", 37, 30, 60, "max")]


def test_contour_train_runs_an_rl_contour_backwards_for_up_cut_milling():
    prog = train(q15="-1")
    assert [m[:4] for m in moves(prog)][:6] == [
        ("rapid", -10, -10, 60), ("rapid", 37, 30, 60), ("line", 37, 30, 5), ("line", 37, 3, 5),
        ("line", 0, 3, 5), ("rapid", 0, 3, 60)]


def test_contour_train_alternates_direction_with_q15_0_and_keeps_the_allowance_q3():
    # RR with Q3 = 0.5: the tool centre 3.5 right of the contour; the outside corner at (40, 0) gets an arc
    # about it; the second infeed starts where the first ended and runs back
    prog = train(q15="0", side="RR", q3="0.5")
    assert [m[:4] for m in moves(prog)] == [
        ("rapid", -10, -10, 60), ("rapid", 0, -3.5, 60), ("line", 0, -3.5, 5), ("line", 40, -3.5, 5),
        ("arc_ccw", 43.5, 0, 5), ("line", 43.5, 30, 5), ("line", 43.5, 30, 0), ("line", 43.5, 0, 0),
        ("arc_cw", 40, -3.5, 0), ("line", 0, -3.5, 0), ("rapid", 0, -3.5, 60)]


def test_contour_train_with_an_arc_element_in_the_contour():
    contour = "9 LBL 1\n10 L X+0 Y+0 {side}\n11 L X+40\n12 CC X+40 Y+20\n13 C X+60 Y+20 DR+\n14 L Y+50\n15 LBL 0\n"
    prog = train(contour=contour)
    # RL on a counter-clockwise arc of radius 20 about (40, 20): the tool runs inside it, on radius 17
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    assert len(arcs) == 2 and all(abs(b.segment.radius - 17.0) < 1e-9 for b in arcs)
    assert moves(prog)[4][:4] == ("arc_ccw", 57, 20, 5)


def test_contour_data_20_is_read_and_moves_nothing():
    data = ("5 CYCL DEF 20 CONTOUR DATA ~\n  Q1=-10 ~\n  Q2=+1 ~\n  Q3=+0 ~\n  Q4=+0 ~\n  Q5=+0 ~\n  Q6=+2 ~\n"
            "  Q7=+50 ~\n  Q8=+0.2 ~\n  Q9=-1\n6 L X+1 Y+2 R0 FMAX\n")
    prog = run(HEAD + data + "END PGM T MM\n")
    assert [np.round(b.target, 6).tolist() for b in prog.blocks] == [[0, 0, 110], [1, 2, 110]]


@pytest.mark.parametrize(("text", "match"), [
    (HEAD + "5 CYCL DEF 22 ROUGH-OUT Q10=-5 Q11=100 Q12=350 Q18=0 Q19=0 Q208=99999\n", "without CONTOUR DATA"),
    (HEAD + "5 CYCL DEF 23 FLOOR FINISHING Q11=100 Q12=350 Q208=99999\n", "cycle 23 without CONTOUR DATA"),
    (HEAD + TRAIN.format(q3="0", q15="+2") + CALL, "Q15=2 is not a milling direction"),
    ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z\n" + TRAIN.format(q3="0", q15="+1") + CALL, "without a contour"),
    (HEAD + TRAIN.format(q3="0", q15="+1") + CALL + "9 LBL 1\n10 L X+0 Y+0 RL\n11 L X+40 Z-5\n12 LBL 0\n",
     "moves along the tool axis"),
    (HEAD + TRAIN.format(q3="0", q15="+1") + "6 L X-10 Y-10 R0 FMAX\n7 CYCL CALL POS X+0 Y+0 Z+0\n", "CONTOUR TRAIN"),
])
def test_sl_cycles_refuse_what_they_cannot_run_with_a_clear_error(text, match):
    with pytest.raises(GCodeError, match=match):
        parse_heidenhain(text + "END PGM T MM\n", source="t.h", context=CTX)


ROUGH = ("5 CYCL DEF 20 CONTOUR DATA ~\n  Q1=-10 ;MILLING DEPTH ~\n  Q2=+1 ;TOOL PATH OVERLAP ~\n"
         "  Q3=+0.5 ;ALLOWANCE FOR SIDE ~\n  Q4=+0.5 ;ALLOWANCE FOR FLOOR ~\n  Q5=+0 ;SURFACE COORDINATE ~\n"
         "  Q6=+2 ;SET-UP CLEARANCE ~\n  Q7=+50 ;CLEARANCE HEIGHT ~\n  Q8=+0 ;ROUNDING RADIUS ~\n"
         "  Q9=+1 ;ROTATIONAL DIRECTION\n"
         "6 CYCL DEF 22 ROUGH-OUT ~\n  Q10=-5 ;PLUNGING DEPTH ~\n  Q11=100 ;FEED RATE FOR PLUNGING ~\n"
         "  Q12=350 ;FEED RATE FOR ROUGHING ~\n  Q18=0 ;COARSE ROUGHING TOOL ~\n  Q19=0 ;FEED RECIPROCATION ~\n"
         "  Q208=MAX ;RETRACTION FEED RATE\n7 L X+0 Y+0 R0 FMAX\n8 CYCL CALL\n9 L X+0 Y+0 Z+100 R0 FMAX M30\n")

#: Pockets as polygons (x, y) [mm] (the circle: 0.5 degree chords), each written as a contour subprogram.
RECTANGLE = [(0, 0), (40, 0), (40, 30), (0, 30)]
L_SHAPE = [(0, 0), (40, 0), (40, 10), (10, 10), (10, 30), (0, 30)]
NECK = [(0, 0), (20, 0), (20, 10), (25, 10), (25, 0), (45, 0), (45, 30), (25, 30), (25, 19), (20, 19), (20, 30),
        (0, 30)]
CIRCLE = [(20 + 20 * np.cos(a), 20 + 20 * np.sin(a)) for a in np.radians(np.arange(-90.0, 270.0, 0.5))]


def pocket_program(points, *, circle: bool = False) -> str:
    if circle:
        body = "11 L X+20 Y+0 RR\n12 CC X+20 Y+20\n13 C X+20 Y+0 DR+\n"
    else:
        body = "".join(f"{11 + i} L X{x:+g} Y{y:+g}{' RL' if i == 0 else ''}\n" for i, (x, y) in
                       enumerate([*points, points[0]]))
    return HEAD + ROUGH + "10 LBL 1\n" + body + "30 LBL 0\nEND PGM T MM\n"


def _distance_to_polygon(pts: np.ndarray, poly: np.ndarray) -> np.ndarray:
    a, b = poly, np.roll(poly, -1, axis=0)
    u = b - a
    t = np.clip(np.einsum("nkd,kd->nk", pts[:, None, :] - a[None], u) / np.einsum("kd,kd->k", u, u), 0, 1)
    return np.min(np.linalg.norm(pts[:, None, :] - (a[None] + t[..., None] * u[None]), axis=2), axis=1)


def _inside_polygon(pts: np.ndarray, poly: np.ndarray) -> np.ndarray:
    inside = np.zeros(len(pts), bool)
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0)):
        crosses = (y0 > pts[:, 1]) != (y1 > pts[:, 1])
        xs = x0 + (pts[:, 1] - y0) * (x1 - x0) / ((y1 - y0) if y1 != y0 else 1.0)
        inside ^= crosses & (pts[:, 0] < xs)
    return inside


@pytest.mark.parametrize("name", ["rectangle", "l_shape", "neck", "circle"])
def test_rough_out_22_keeps_every_move_below_the_surface_inside_the_pocket_clear_of_the_allowance(name):
    points = {"rectangle": RECTANGLE, "l_shape": L_SHAPE, "neck": NECK, "circle": CIRCLE}[name]
    text = pocket_program(points, circle=name == "circle")
    # the straight-edged pockets are checked block by block against the reference too (its rings its own)
    prog = parse_heidenhain(text, source="t.h", context=CTX) if name == "circle" else run(text)
    poly = np.array(points, float)
    # the moves that reach below the surface (machine Z 10), but the first one, up from home
    below = [b for b in prog.blocks[1:] if b.segment is not None and min(b.start[2], b.target[2]) < 10.0]
    pts = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 50)))[:, :2]
                          for b in below])
    assert np.all(_inside_polygon(pts, poly))
    # the tool's edge (R = 3) keeps Q3 = 0.5 from the wall; the circle's chords are 0.0004 mm inside it
    assert _distance_to_polygon(pts, poly).min() >= 3.5 - 1e-3
    # the depths: Q10 = 5 down to Q1 + Q4 = 9.5 (machine Z = program Z + 10), plunged at Q11 from Q6 above Q5
    plunges = [b for b in prog.blocks if b.kind == "line" and b.start[2] != b.target[2]]
    assert [(round(b.start[2], 9), round(b.target[2], 9), round(b.feed * 60, 9)) for b in plunges] == [
        (12.0, 5.0, 100.0), (12.0, 0.5, 100.0)]


@pytest.mark.parametrize("q9", ["+1", "-1"])
def test_rough_out_22_runs_the_pocket_in_the_sense_q9_whichever_way_it_is_written(q9):
    for points in (L_SHAPE, L_SHAPE[::-1]):
        prog = run(pocket_program(points).replace("Q9=+1", "Q9=" + q9))
        ring = [b.target[:2] for b in prog.blocks if b.target[2] == 5.0 and b.kind == "line"][-7:]
        area = sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(ring, ring[1:] + ring[:1]))
        assert (area > 0) == (q9 == "+1")


def test_rough_out_22_rectangle_rings_from_the_inside_out_the_last_one_r_plus_q3_from_the_wall():
    prog = run_rough(RECTANGLE)
    ends = [tuple(np.round(b.target[:2], 6).tolist()) for b in prog.blocks
            if b.kind == "line" and b.text.startswith("12 ") and b.target[2] == 5.0]
    # Q9=+1 counter-clockwise; rings Q2 x R = 3 apart from 3.5 in: 3.5, 6.5, 9.5, 12.5 (15.5 > 15, half the
    # width); each ring starts and ends at the middle of the first element (X+40 from X+0 Y+0: X20), so that
    # element's two halves end at the ring's corner and back at X20
    assert ends == [(27.5, 12.5), (20, 12.5), (30.5, 9.5), (20, 9.5), (33.5, 6.5), (20, 6.5), (36.5, 3.5), (20, 3.5)]
    last = [b for b in prog.blocks if b.target[2] == 5.0][-1]
    assert tuple(np.round(last.target, 6)) == (20.0, 3.5, 5.0)  # back at the middle of the first element


def run_rough(points):
    return run(pocket_program(points))


def test_rough_out_22_rest_machining_needs_a_larger_coarse_tool():
    text = pocket_program(RECTANGLE).replace("Q18=0 ", "Q18=2 ")
    with pytest.raises(GCodeError, match="coarse roughing tool Q18 = 2 has no radius larger"):
        parse_heidenhain(text, source="t.h", context=CTX)


#: A 50 x 50 pocket (LBL 1, clockwise with RR: the tool inside) with two islands: a 10 x 10 square (LBL 2,
#: clockwise with RL: the tool outside) and a circle of radius 8 about (35, 35) (LBL 3, counter-clockwise with
#: RR: outside), as kt_SLII001 (drunsinn/language-klartext) writes them.
ISLANDS = ("4 CYCL DEF 14.1 CONTOUR LABEL 1 /2 /3\n" + ROUGH +
           "10 LBL 1\n11 L X+0 Y+25 RR\n12 L X+0 Y+50\n13 L X+50 Y+50\n14 L X+50 Y+0\n15 L X+0 Y+0\n"
           "16 L X+0 Y+25\n17 LBL 0\n18 LBL 2\n19 L X+5 Y+8 RL\n20 L X+5 Y+15\n21 L X+15 Y+15\n22 L X+15 Y+5\n"
           "23 L X+5 Y+5\n24 L X+5 Y+8\n25 LBL 0\n26 LBL 3\n27 CC X+35 Y+35\n28 L X+35 Y+43 RR\n"
           "29 C X+35 Y+43 DR+\n30 LBL 0\nEND PGM T MM\n")


def _island_distance(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The exact distance of points to the three contours of ISLANDS and whether they lie in the region."""
    square, pocket = np.array(RECTANGLE_10, float), np.array([(0, 0), (50, 0), (50, 50), (0, 50)], float)
    circle = np.abs(np.linalg.norm(pts - [35.0, 35.0], axis=1) - 8.0)
    d = np.minimum(np.minimum(_distance_to_polygon(pts, pocket), _distance_to_polygon(pts, square)), circle)
    inside = (_inside_polygon(pts, pocket) & ~_inside_polygon(pts, square)
              & (np.linalg.norm(pts - [35.0, 35.0], axis=1) > 8.0))
    return d, inside


RECTANGLE_10 = [(5, 5), (15, 5), (15, 15), (5, 15)]


def _islands_run(q9: str = "+1"):
    text = HEAD.replace("4 CYCL DEF 14.1 CONTOUR LABEL 1\n", "") + ISLANDS.replace("Q9=+1", "Q9=" + q9)
    return run(text)  # the reference checks the rise to Q7 and the end at Q7 over the pocket


@pytest.mark.slow
def test_rough_out_22_with_two_islands_stays_r_plus_q3_from_every_contour_and_clears_the_rest():
    prog = _islands_run()
    below = [b for b in prog.blocks[1:] if b.segment is not None and min(b.start[2], b.target[2]) < 10.0]
    pts = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 20)))[:, :2]
                          for b in below])
    d, inside = _island_distance(pts)
    assert np.all(inside)
    # R + Q3, the rings within TOLERANCE (1 um) of it; the circle is just 2 (R + Q3) from the wall, where the
    # rings pinch
    assert d.min() >= 3.5 - 1e-3
    # coverage at the last depth: every point of the region 3.5 or more from the contours lies within Q2 x R
    # = 3 mm of the path (the rings are 3 mm apart)
    last = [b for b in below if b.start[2] == b.target[2] == 0.5]
    path = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 40)))[:, :2]
                           for b in last])
    gx, gy = np.meshgrid(np.arange(0.25, 50, 0.5), np.arange(0.25, 50, 0.5))
    grid = np.stack([gx.ravel(), gy.ravel()], axis=1)
    dg, ing = _island_distance(grid)
    grid = grid[ing & (dg >= 3.5)]
    far = np.array([np.min(np.linalg.norm(path - g, axis=1)) for g in grid])
    assert far.max() <= 3.0 * 1.05
    # the depths: Q10 = 5, then Q1 + Q4 = 9.5 (machine Z = program Z + 10), each plunged at Q11 from Q6 above Q5
    plunges = {(round(b.start[2], 9), round(b.target[2], 9)) for b in prog.blocks
               if b.kind == "line" and b.start[2] != b.target[2]}
    assert plunges == {(12.0, 5.0), (12.0, 0.5)}


@pytest.mark.slow
@pytest.mark.parametrize("q9", ["+1", "-1"])
def test_rough_out_22_runs_round_an_island_clockwise_for_climb_milling_q9_plus_1(q9):
    prog = _islands_run(q9)
    # the moves round the circular island (their ends 3.5 from it, the first ring): their turning about its centre
    moves = [b for b in prog.blocks if b.kind == "line" and b.start[2] == b.target[2] == 0.5
             and abs(np.linalg.norm(b.target[:2] - [35, 35]) - 11.5) < 1e-2
             and abs(np.linalg.norm(b.start[:2] - [35, 35]) - 11.5) < 1e-2]
    turn = sum((b.start[0] - 35) * (b.target[1] - 35) - (b.start[1] - 35) * (b.target[0] - 35) for b in moves)
    assert moves and (turn < 0) == (q9 == "+1")  # climb milling with M3: the material on the tool's right


def _sl_program(cycles: str) -> str:
    """ISLANDS with its cycle 22 call replaced by ``cycles`` (definitions and calls)."""
    text = HEAD.replace("4 CYCL DEF 14.1 CONTOUR LABEL 1\n", "") + ISLANDS
    return text.replace("8 CYCL CALL\n", cycles)


SIDE = ("81 CYCL DEF 24 SIDE FINISHING ~\n  Q9=+1 ;ROTATIONAL DIRECTION ~\n  Q10=-5 ;PLUNGING DEPTH ~\n"
        "  Q11=100 ;FEED RATE FOR PLUNGING ~\n  Q12=300 ;FEED RATE FOR MILLING ~\n  Q14=+0 ;ALLOWANCE FOR SIDE\n"
        "82 CYCL CALL\n")
FLOOR = ("83 CYCL DEF 23 FLOOR FINISHING ~\n  Q11=100 ;FEED RATE FOR PLUNGING ~\n  Q12=200 ;FEED RATE FOR ROUGHING\n"
         "84 CYCL CALL\n")
PILOT = ("71 CYCL DEF 21 PILOT DRILLING ~\n  Q10=+5 ;PLUNGING DEPTH ~\n  Q11=100 ;FEED RATE FOR PLUNGING ~\n"
         "  Q13=1 ;ROUGH-OUT TOOL\n72 CYCL CALL\n")


@pytest.mark.slow
def test_side_finishing_24_runs_every_wall_r_plus_q14_off_at_each_infeed():
    prog = run(_sl_program(SIDE))
    flat = [b for b in prog.blocks if b.text.startswith("82 ") and b.kind == "line" and b.start[2] == b.target[2]]
    assert {round(b.target[2], 9) for b in flat} == {5.0, 0.0}  # Q10 = 5 down to Q1 = -10 (machine Z + 10)
    pts = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 9)))[:, :2]
                          for b in flat])
    d, inside = _island_distance(pts)
    assert np.all(inside) and d.min() >= 3.0 - 1e-9 and d.max() <= 3.0 + 1e-3  # R + Q14, within 1 um
    # each contour is finished: the path comes to R from the pocket wall, the square and the circle
    square, pocket = np.array(RECTANGLE_10, float), np.array([(0, 0), (50, 0), (50, 50), (0, 50)], float)
    for dist in (_distance_to_polygon(pts, pocket), _distance_to_polygon(pts, square),
                 np.abs(np.linalg.norm(pts - [35.0, 35.0], axis=1) - 8.0)):
        assert dist.min() == pytest.approx(3.0, abs=1e-3)
    plunges = {(round(b.start[2], 9), round(b.target[2], 9), round(b.feed * 60, 6)) for b in prog.blocks
               if b.text.startswith("82 ") and b.kind == "line" and b.start[2] != b.target[2]}
    assert plunges == {(12.0, 5.0, 100.0), (5.0, 0.0, 100.0)}


@pytest.mark.slow
def test_floor_finishing_23_clears_at_the_depth_q1_in_one_infeed_keeping_the_side_allowance():
    prog = run(_sl_program(FLOOR))
    mine = [b for b in prog.blocks if b.text.startswith("84 ") and b.segment is not None]
    plunges = {(round(b.start[2], 9), round(b.target[2], 9)) for b in mine if b.kind == "line"
               and b.start[2] != b.target[2]}
    assert plunges == {(12.0, 0.0)}  # from Q6 above Q5 to Q1 = -10, the floor allowance Q4 cleared
    flat = [b for b in mine if b.start[2] == b.target[2] == 0.0]
    pts = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 9)))[:, :2]
                          for b in flat])
    d, inside = _island_distance(pts)
    assert np.all(inside) and d.min() >= 3.5 - 1e-9 and all(b.feed * 60 == pytest.approx(200.0) for b in flat)


@pytest.mark.slow
def test_pilot_drilling_21_drills_where_the_rough_out_plunges_to_q1_less_q4():
    rough = ISLANDS.split("6 CYCL DEF 22")[1].split("7 L X+0")[0]
    prog = run(_sl_program(PILOT + "73 CYCL DEF 22" + rough + "74 CYCL CALL\n"))
    drills = [b for b in prog.blocks if b.text.startswith("72 ") and b.kind == "line"]
    plunges = [b for b in prog.blocks if b.text.startswith("74 ") and b.kind == "line" and b.start[2] == 12.0
               and b.target[2] == 5.0]
    holes = {tuple(np.round(b.target[:2], 6)) for b in drills}
    assert holes == {tuple(np.round(b.target[:2], 6)) for b in plunges} and len(holes) >= 1
    # pecked as cycle 1: Q10 = 5 deep each, down to Q1 + Q4 = -9.5 (machine Z 0.5), at Q11
    assert sorted({round(b.target[2], 9) for b in drills}) == [0.5, 5.0]
    assert all(b.feed * 60 == pytest.approx(100.0) for b in drills if b.target[2] < b.start[2])


@pytest.mark.parametrize(("text", "match"), [
    (HEAD + "5 CYCL DEF 21 PILOT DRILLING Q10=5 Q11=100 Q13=1\n", "cycle 21 without CONTOUR DATA"),
    (HEAD + ROUGH.split("6 CYCL DEF 22")[0] + "6 CYCL DEF 24 SIDE FINISHING Q9=1 Q10=5 Q11=100 Q12=300\n",
     "cycle 24 lacks Q14"),
    (HEAD.replace("LABEL 1", "LABEL 1 /2") + ROUGH + "10 LBL 1\n11 L X+0 Y+0 RR\n12 L X+0 Y+20\n13 L X+20 Y+20\n"
     "14 L X+0 Y+0\n15 LBL 0\n16 LBL 2\n17 L X+5 Y+5 R0\n18 L X+5 Y+8\n19 L X+8 Y+8\n20 L X+5 Y+5\n21 LBL 0\n",
     "contour 2 of cycle 14 has no RL/RR"),
    (HEAD.replace("LABEL 1", "LABEL 1 /2") + ROUGH + "10 LBL 1\n11 L X+0 Y+0 RL\n12 L X+0 Y+20\n13 L X+20 Y+20\n"
     "14 L X+0 Y+0\n15 LBL 0\n16 LBL 2\n17 L X+5 Y+5 RL\n18 L X+5 Y+8\n19 L X+8 Y+8\n20 L X+5 Y+5\n21 LBL 0\n",
     "all islands"),
])
def test_sl_cycles_21_to_24_name_what_they_lack(text, match):
    with pytest.raises(GCodeError, match=match):
        parse_heidenhain(text.replace("9 L X+0 Y+0 Z+100 R0 FMAX M30\n", "9 L X+0 Y+0 Z+100 R0 FMAX M30\n")
                         + "END PGM T MM\n", source="t.h", context=CTX)


@pytest.mark.slow
def test_rest_machining_22_q18_cuts_only_near_what_the_coarse_tool_left_and_together_they_clear_the_region():
    rough = ISLANDS.split("6 CYCL DEF 22")[1].split("7 L X+0")[0]
    rest = ("73 TOOL CALL 2 Z S3000\n74 CYCL DEF 22" + rough.replace("Q18=0", "Q18=1") + "75 CYCL CALL\n")
    ctx = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)},
                         tools={1: Tool(number=1, length=10.0, radius=3.0), 2: Tool(number=2, length=10.0, radius=1.0)})
    text = _sl_program("8 CYCL CALL\n" + rest)
    prog = parse_heidenhain(text, source="t.h", context=ctx)
    match = match_blocks(heidenhain_reference(text, ctx), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch

    def flat(line_text: str, z: float) -> np.ndarray:
        moves = [b for b in prog.blocks if b.text.startswith(line_text) and b.segment is not None
                 and b.start[2] == b.target[2] == z]
        return np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 20)))[:, :2]
                               for b in moves])

    coarse, fine = flat("8 ", 0.5), flat("75 ", 0.5)
    d, inside = _island_distance(fine)
    assert np.all(inside) and d.min() >= 1.5 - 1e-3  # the small tool: R 1 + Q3 0.5 from every contour
    # the rest is a fraction of a full roughing with the small tool (its rings 1 mm apart would run ~4x as long)
    assert len(fine) < len(coarse)
    # together: every point 1.5 or more from the contours lies within 3 (x 1.05) of the coarse tool's path or
    # within 1 (x 1.05) of the small tool's
    gx, gy = np.meshgrid(np.arange(0.25, 50, 0.5), np.arange(0.25, 50, 0.5))
    grid = np.stack([gx.ravel(), gy.ravel()], axis=1)
    dg, ing = _island_distance(grid)
    grid = grid[ing & (dg >= 1.5)]
    near_coarse = np.array([np.min(np.linalg.norm(coarse - g, axis=1)) for g in grid]) <= 3.0 * 1.05
    near_fine = np.array([np.min(np.linalg.norm(fine - g, axis=1)) for g in grid]) <= 1.0 * 1.05
    assert np.all(near_coarse | near_fine)


def _channel_program(pocket: tuple[float, float], islands: list[tuple[float, float, float, float]]) -> str:
    """Cycle 22 with a 5.502 mm tool and Q3 = 0.5 (the rings 6.002 from the contours) in a ``pocket`` (width,
    height from the origin) with rectangle ``islands`` (x0, y0, x1, y1), as slfuzz writes them (issue 19)."""
    w, h = pocket
    labels = [f"LBL 1\nL X+0 Y+{h / 2:g} RR\nL X+0 Y+{h:g}\nL X+{w:g} Y+{h:g}\nL X+{w:g} Y+0\nL X+0 Y+0\n"
              f"L X+0 Y+{h / 2:g}\nLBL 0\n"]
    for k, (x0, y0, x1, y1) in enumerate(islands):
        ym = round((y0 + y1) / 2, 4)
        labels.append(f"LBL {k + 2}\nL X{x0:+g} Y{ym:+g} RL\nL X{x0:+g} Y{y1:+g}\nL X{x1:+g} Y{y1:+g}\n"
                      f"L X{x1:+g} Y{y0:+g}\nL X{x0:+g} Y{y0:+g}\nL X{x0:+g} Y{ym:+g}\nLBL 0\n")
    return ("BEGIN PGM T MM\nTOOL DEF 1 L+0 R+5.502\nTOOL CALL 1 Z S1000\nL Z+100 R0 FMAX\nCYCL DEF 14.0 CONTOUR\n"
            f"CYCL DEF 14.1 CONTOUR LABEL {' /'.join(str(k + 1) for k in range(len(labels)))}\n"
            "CYCL DEF 20 CONTOUR DATA Q1=-6 Q2=+0.659 Q3=+0.5 Q4=+0 Q5=+0 Q6=+2 Q7=+50 Q8=+0 Q9=+1\n"
            "CYCL DEF 22 ROUGH-OUT Q10=-3 Q11=100 Q12=350 Q18=0 Q19=0 Q208=MAX\nL X+0 Y+0 R0 FMAX\nCYCL CALL\n"
            "L Z+100 R0 FMAX M30\n" + "".join(labels) + "END PGM T MM\n")


@pytest.mark.slow
@pytest.mark.parametrize(("pocket", "islands"), [
    ((77.056, 68.546), [(53.677, 49.81, 65.04, 61.9), (19.338, 59.631, 22.003, 65.941)]),
    ((770.56, 685.46), [(747.181, 49.81, 758.544, 61.9)])])
def test_rough_out_22_follows_a_channel_only_12_um_wider_than_the_rings_into_its_closed_end(pocket, islands):
    """The island leaves a channel 12.016 mm wide to the right wall (the ring needs 2 x 6.002) whose far end is
    closed (the island 6.646 below the top wall): the ring at 6.002 runs up it and back 11 um apart, which no grid
    over the pocket separated (the small pocket stopped with "did not settle", the large one at the grid cap);
    each move keeps 6.002 from the contours and the ring reaches the channel's end."""
    prog = parse_heidenhain(_channel_program(pocket, islands), source="sl.h")
    below = [b for b in prog.blocks if b.segment is not None and max(b.start[2], b.target[2]) < 0.0]
    pts = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 20)))[:, :2]
                          for b in below])
    walls = np.array([(0, 0), (pocket[0], 0), pocket, (0, pocket[1])], float)
    boxes = [np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)]) for x0, y0, x1, y1 in islands]
    assert np.all(_inside_polygon(pts, walls)) and not any(np.any(_inside_polygon(pts, b)) for b in boxes)
    d = np.min([_distance_to_polygon(pts, walls), *(_distance_to_polygon(pts, b) for b in boxes)], axis=0)
    assert d.min() >= 6.002 - 1e-9
    x1, y1 = islands[0][2], islands[0][3]
    end = (pts[:, 0] > x1 + 6.0) & (pts[:, 1] > y1)  # the channel's end, 6.0025 below the top wall
    assert pts[end, 1].max() == pytest.approx(pocket[1] - 6.0025, abs=1e-6)


def test_rough_out_22_finds_the_small_rings_either_side_of_a_circle_island_that_a_grid_missed():
    """A 20.055 x 23.089 pocket, an island strip along its top and a circle of radius 3.968 about (12.837, 10.58):
    the rings 4.601 from the contours (R 4.601, Q3 0) lie only left of the circle, one below it and one above it,
    each about 2 x 12 mm (slfuzz seed 6: a grid of 1.5 mm missed them and the cycle stopped, "fits nowhere")."""
    text = _channel_program((20.055, 23.089), [(-0.019, 21.056, 16.969, 26.227)]).replace("R+5.502", "R+4.601")
    text = text.replace("Q2=+0.659 Q3=+0.5", "Q2=+0.991 Q3=+0").replace("LABEL 1 /2", "LABEL 1 /2 /3").replace(
        "END PGM", "LBL 3\nCC X+12.837 Y+10.580\nL X+12.837 Y+14.548 RR\nC X+12.837 Y+14.548 DR+\nLBL 0\nEND PGM")
    prog = parse_heidenhain(text, source="sl.h")
    below = [b for b in prog.blocks if b.segment is not None and max(b.start[2], b.target[2]) < 0.0]
    pts = np.concatenate([np.asarray(b.segment.point_at(np.linspace(0, b.segment.length, 20)))[:, :2]
                          for b in below])
    walls = np.array([(0, 0), (20.055, 0), (20.055, 23.089), (0, 23.089)], float)
    strip = np.array([(-0.019, 21.056), (16.969, 21.056), (16.969, 26.227), (-0.019, 26.227)])
    circle = np.linalg.norm(pts - [12.837, 10.58], axis=1) - 3.968
    assert np.all(_inside_polygon(pts, walls)) and not np.any(_inside_polygon(pts, strip)) and circle.min() > 0
    d = np.min([_distance_to_polygon(pts, walls), _distance_to_polygon(pts, strip), circle], axis=0)
    assert d.min() >= 4.601 - 1e-9
    assert pts[:, 1].min() < 10.58 - 4.0 and pts[:, 1].max() > 10.58 + 4.0 and pts[:, 0].max() < 8.0


def test_rough_out_22_rounds_the_rings_inside_corners_by_q8():
    # cycle 20 Q8 = 2 (the rounding radius of the tool-centre path's inside corners): each ring's four corners
    # become quarter circles of radius 2 tangent to its sides; the sides stay where the sharp rings have them
    sharp = run(pocket_program(RECTANGLE))
    prog = run(pocket_program(RECTANGLE).replace("Q8=+0 ", "Q8=+2 "))
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    corners = [b for b in sharp.blocks if b.kind == "line" and b.start[2] == b.target[2] < 10.0]
    assert not any(b.kind == "arc" for b in sharp.blocks)
    # each ring ends back at its start, the middle of its first side (X 20): one such block per ring and infeed
    rings = sum(1 for b in sharp.blocks if b.kind == "line" and b.start[2] == b.target[2] < 10.0
                and b.target[0] == 20.0 and b.start[0] != 20.0)
    assert rings == 8 and len(arcs) == 4 * rings  # 4 rings x 2 infeeds, 4 corners each
    assert all(abs(a.segment.radius - 2.0) < 1e-9 and abs(abs(a.segment.sweep) - math.pi / 2) < 1e-9 for a in arcs)
    # the outermost ring lies R + Q3 = 3.5 inside the walls: its corner arcs are about (5.5, 5.5) .. (34.5, 24.5)
    centres = {tuple(np.round(a.segment.center[:2], 9)) for a in arcs}
    assert {(5.5, 5.5), (34.5, 5.5), (34.5, 24.5), (5.5, 24.5)} <= centres
    assert {round(b.target[0], 9) for b in corners} >= {3.5, 36.5}  # the sides: as the sharp rings'
    assert not any("Q8" in n for n in prog.notes)


# a pocket 60 x 40 with a circular island of radius 5 about (30, 20); tool radius 3 (CTX), Q3 = 0, Q2 = 1.9: rings
# 3 and 3 + 1.9 x 3 = 8.7 from the contours (at 14.4 the island's offset, radius 19.4, covers what the walls'
# offsets leave)
ISLAND_Q8 = ("4 CYCL DEF 14.1 CONTOUR LABEL 1 /2\n"
             "5 CYCL DEF 20 CONTOUR DATA Q1=-4 Q2=+1.9 Q3=+0 Q4=+0 Q5=+0 Q6=+2 Q7=+50 Q8=+{q8} Q9=+1\n"
             "6 CYCL DEF 22 ROUGH-OUT Q10=+4 Q11=100 Q12=350 Q18=0 Q19=0 Q208=MAX\n7 L X+30 Y+20 R0 FMAX\n"
             "8 CYCL CALL\n9 L Z+100 R0 FMAX M30\n10 LBL 1\n11 L X+0 Y+0 RL\n12 L X+60\n13 L Y+40\n14 L X+0\n"
             "15 L Y+0\n16 LBL 0\n17 LBL 2\n18 L X+25 Y+20 RL\n19 CC X+30 Y+20\n20 C X+25 Y+20 DR-\n21 LBL 0\n"
             "END PGM T MM\n")


def _cut_points(prog) -> np.ndarray:
    """The plane points of the moves at the depth (machine Z 10 - 4)."""
    return np.array([b.target[:2] for b in prog.blocks if b.kind == "line" and b.start[2] == b.target[2] == 6.0])


def test_rough_out_22_with_an_island_rounds_the_rings_inside_corners_by_q8():
    # Q8 = 2 rounds the tool-centre path's inside corners (TNC 426/430 manual, cycle 20: "referenced to the tool
    # midpoint path"): the circle of radius 2 tangent to both offsets meeting there, its centre 2 farther from both
    # contours than the ring; the rings lie 0.5 um beyond their level (toolpaths.pockets.TOLERANCE / 2)
    text = HEAD.replace("4 CYCL DEF 14.1 CONTOUR LABEL 1\n", "") + ISLAND_Q8
    sharp, prog = _cut_points(run(text.format(q8="0"))), _cut_points(run(text.format(q8="2")))

    def passes(pts, xy) -> bool:
        return bool(np.min(np.hypot(*(pts - np.asarray(xy)).T)) < 2e-3)

    # ring 3, the walls' corners: (3, 3) sharp; rounded about (5, 5), tangent at (5, 3) and (3, 5)
    assert passes(sharp, (3, 3)) and not passes(prog, (3, 3))
    for xy in [(5, 3), (3, 5), (55, 3), (57, 5), (57, 35), (55, 37), (3, 35), (5, 37)]:
        assert passes(prog, xy), xy
    assert np.min(np.hypot(*prog.T)) == pytest.approx(5 * math.sqrt(2) - 2, abs=3e-3)  # from the corner (0, 0)
    # ring 8.7: the line Y 8.7 meets the island's offset (radius 13.7) at X 30 -+ sqrt(13.7^2 - 11.3^2); the
    # rounding circle's centre lies at Y 10.7 and 15.7 from (30, 20), at X 30 -+ sqrt(15.7^2 - 9.3^2), touching the
    # line below it and the offset circle 13.7 / 15.7 of the way from (30, 20) to it; the walls' corner (8.7, 8.7)
    # rounded about (10.7, 10.7)
    dx = math.sqrt(15.7**2 - 9.3**2)
    for sx in (-1, 1):
        for sy in (-1, 1):
            assert passes(sharp, (30 + sx * math.sqrt(13.7**2 - 11.3**2), 20 + sy * 11.3))
            assert passes(prog, (30 + sx * dx, 20 + sy * 11.3))
            assert passes(prog, (30 + sx * dx * 13.7 / 15.7, 20 + sy * 9.3 * 13.7 / 15.7))
            assert passes(prog, (30 + sx * 19.3, 20 + sy * 11.3)) and passes(prog, (30 + sx * 21.3, 20 + sy * 9.3))
    # nowhere nearer the contours than the outer ring: 3 from the walls, 3 from the island
    walls = np.minimum.reduce([prog[:, 0], 60 - prog[:, 0], prog[:, 1], 40 - prog[:, 1]])
    assert walls.min() >= 3.0 and np.min(np.hypot(prog[:, 0] - 30, prog[:, 1] - 20) - 5) >= 3.0 - 1e-9
    assert not any("Q8" in n for n in run(text.format(q8="2")).notes)
