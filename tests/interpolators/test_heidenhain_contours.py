"""SL cycles of Heidenhain programs: CYCL DEF 14 CONTOUR GEOMETRY, 20 CONTOUR DATA, 25 CONTOUR TRAIN.

Each program is hand-written with its end points worked out by hand (tool radius 3 mm, tool length 10 mm:
machine Z = program Z + 10), and checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

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
    (HEAD + "5 CYCL DEF 22 ROUGH-OUT Q10=-5 Q11=100 Q12=350 Q18=0 Q19=0 Q208=99999\n", "cycle 22 ROUGH-OUT"),
    (HEAD + TRAIN.format(q3="0", q15="+2") + CALL, "Q15=2 is not a milling direction"),
    ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z\n" + TRAIN.format(q3="0", q15="+1") + CALL, "without a contour"),
    (HEAD + TRAIN.format(q3="0", q15="+1") + CALL + "9 LBL 1\n10 L X+0 Y+0 RL\n11 L X+40 Z-5\n12 LBL 0\n",
     "moves along the tool axis"),
    (HEAD + TRAIN.format(q3="0", q15="+1") + "6 L X-10 Y-10 R0 FMAX\n7 CYCL CALL POS X+0 Y+0 Z+0\n", "CONTOUR TRAIN"),
])
def test_sl_cycles_refuse_what_they_cannot_run_with_a_clear_error(text, match):
    with pytest.raises(GCodeError, match=match):
        parse_heidenhain(text + "END PGM T MM\n", source="t.h", context=CTX)
