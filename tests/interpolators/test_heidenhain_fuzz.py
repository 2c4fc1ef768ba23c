"""Generated TNC programs (tests/interpolators/tnc_generator.py) against the independent reference, and the
disagreements the generator found, each as a hand-written program: an incomplete CYCL DEF 1 that let the call run
the cycle before it; the reference's rounding next to arcs, under a mirror and under scaling."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_iso import ReferenceError
from tests.interpolators.reference_match import match_blocks, reader_rows
from tests.interpolators.tnc_generator import context, generate
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HOME = MachineContext(home=(0.0, 0.0, 300.0))


def checked(body: str, *, exact: bool = True):
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", HOME, exact=exact)


def rows(prog, line: int) -> list[tuple[str, list[float]]]:
    return [(b.kind, np.round(b.target, 6).tolist()) for b in prog.blocks if b.line == line]


def test_generated_programs_are_read_as_the_reference_reads_them_or_refused_cleanly():
    # 120 seeded programs mixing BEGIN PGM MM/INCH, TOOL DEF/CALL (DL, DR, F), L abs/inc, RL/RR with L or
    # APPR/DEP, CC (also bare, and kept across cycles 7-11 and TOOL CALL)/C (ends rounded off the circle too)/CR/CT/CP
    # (IZ)/LP, RND/CHF, corners down to 0.2 degrees, Q parameters in coordinates and feeds, LBL/CALL LBL REP, cycles
    # 7/8/9/10/11/32 and 1/200/203/205 by CYCL CALL, M99, POS and PAT, pockets 251/252, on a B/C table for a
    # quarter of the seeds PLANE SPATIAL / RESET and M128 with B C, M91/M92/M140. A refusal is a geometry the
    # tool cannot cut (a gouge, a rounding that does not fit), a GCodeError naming the block's line
    accepted = 0
    for seed in range(120):
        text = generate(seed)
        try:
            prog = parse_heidenhain(text, source="t.h", context=context(seed))
        except GCodeError as e:
            assert str(e).startswith("t.h:"), (seed, str(e))
            assert "expected" in str(e), (seed, str(e))
            continue
        match = match_blocks(heidenhain_reference(text, context(seed)), reader_rows(*blocks_table(prog)))
        assert match.mismatch is None, (seed, match.mismatch)
        accepted += 1
    assert accepted >= 100


def test_generator_is_seeded():
    assert generate(7) == generate(7)
    assert generate(7) != generate(8)
    assert generate(3).startswith("0 BEGIN PGM FUZZ3 ")


def test_incomplete_pecking_cycle_is_refused_at_the_call():
    # a CYCL DEF 1 that stops at 1.2: the TNC's editor always writes 1.1 .. 1.5; vcnc kept the cycle 200
    # defined before and drilled it at the call, silently. A new cycle replaces the last from its first line
    body = ("L X+0 Y+0 Z+20 R0 FMAX\nCYCL DEF 200 DRILLING Q200=+2 Q201=-3 Q206=+100 Q202=+2 Q210=+0 Q203=+2 "
            "Q204=+50 Q211=+0\nCYCL DEF 1.0 PECKING\nCYCL DEF 1.1 SET UP 2\nCYCL DEF 1.2 DEPTH -6\n")
    with pytest.raises(GCodeError, match=r"t.h:7:.*incomplete CYCL DEF 1 \(its lines 1.1 .. 1.5 not all given\)"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + body + "CYCL CALL\nEND PGM T MM\n", source="t.h")
    with pytest.raises(GCodeError, match="incomplete CYCL DEF 1"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + body + "CYCL CALL POS X+5 Y+5 Z+0 FMAX\nEND PGM T MM\n",
                         source="t.h")
    # completed, the call runs cycle 1 from where the tool stands (20): surface 18, depth 12, one peck of 6
    prog = checked(body + "CYCL DEF 1.3 PECKG 6\nCYCL DEF 1.4 DWELL 0\nCYCL DEF 1.5 F100\nCYCL CALL")
    assert [b.target[2] for b in prog.blocks if b.line == 10] == [12.0, 20.0]


def test_rounding_between_a_line_and_an_arc():
    # TNC 426/430 manual, "Rounding corners RND": the arc tangent to the element before and after. A line to
    # (10, 0), then clockwise about (20, 0) (leaving along +Y): the fillet of radius 2 is left of both, its
    # centre on y = 2 and on the circle of radius 12 about (20, 0): x = 20 - sqrt(140)
    prog = checked("L X+0 Y+0 Z+0 R0 F100\nL X+10 Y+0\nRND R2\nCC X+20 Y+0\nC X+20 Y+10 DR-")
    fx = 20.0 - math.sqrt(140.0)
    assert rows(prog, 3) == [("line", [round(fx, 6), 0.0, 0.0])]
    assert rows(prog, 4) == [("arc", [round(20.0 - math.sqrt(140.0) * 10.0 / 12.0, 6), round(2.0 * 10.0 / 12.0, 6),
                                      0.0])]
    assert rows(prog, 6) == [("arc", [20.0, 10.0, 0.0])]


def test_rounding_between_an_arc_and_a_line():
    # counter-clockwise about (0, 10) from (0, 0) to (10, 10) (leaving along +Y), then a line to (0, 20): the
    # fillet of radius 2 is left of both, on the circle of radius 8 about (0, 10) and 2 left of the line
    prog = checked("L X+0 Y+0 Z+0 R0 F100\nCC X+0 Y+10\nC X+10 Y+10 DR+\nRND R2\nL X+0 Y+20")
    d = np.array([-1.0, 1.0]) / math.sqrt(2.0)
    base = np.array([10.0, 10.0]) + 2.0 * np.array([-d[1], d[0]])  # the line moved 2 to its left
    f = base - [0.0, 10.0]
    u = -f @ d - math.sqrt((f @ d) ** 2 - (f @ f - 64.0))  # |base + u d - pole| = 8, the meeting nearer (10, 10)
    centre = base + u * d
    touch_arc = np.array([0.0, 10.0]) + 10.0 * (centre - [0.0, 10.0]) / 8.0
    assert np.linalg.norm(centre - [0.0, 10.0]) == pytest.approx(8.0)
    assert rows(prog, 4) == [("arc", [*np.round(touch_arc, 6).tolist(), 0.0])]
    assert prog.blocks[-1].target.tolist() == [0.0, 20.0, 0.0]


def test_inside_rounding_no_larger_than_the_tool_under_a_mirror():
    # mirrored in X, RL cuts on the right of the machine's path: the left turn of the program is a right turn
    # in the machine, still inside. RND R1 with a tool of radius 1: the corner where the tool centre paths meet
    # (the reader's note); the reference took the mirrored corner for an outside one
    prog = checked("TOOL DEF 1 L+0 R+1\nTOOL CALL 1 Z S2500\nCYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X\n"
                   "L X+0 Y+0 Z+0 R0 F100\nL X+10 Y+0 RL\nL X+30 Y+0\nRND R1\nL X+30 Y+20\nL X+50 Y+20 R0",
                   exact=False)
    assert rows(prog, 8) == [("line", [-29.0, 1.0, 0.0])]
    assert rows(prog, 9) == []
    assert any("RND R1 on an inside corner" in n for n in prog.notes)


def test_radius_arc_and_departure_under_scaling():
    # cycle 11 SCALING 0.5 (TNC 426/430 manual, "SCALING (Cycle 11)"): the CR half circle of R10 to X+20 is one
    # of radius 5 to X10 in the machine; DEP LT LEN10 leaves 5 along the last element
    prog = checked("CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL0.5\nL X+0 Y+0 Z+0 R0 F100\nCR X+20 Y+0 R+10 DR+\n"
                   "L X+20 Y+10 RL\nL X+40 Y+10\nDEP LT LEN10 R0", exact=False)
    arc = next(b for b in prog.blocks if b.line == 5)
    assert arc.kind == "arc" and arc.target.tolist() == [10.0, 0.0, 0.0]
    assert np.allclose(arc.segment.center, [5.0, 0.0, 0.0]) and arc.segment.ccw
    assert rows(prog, 8)[-1] == ("line", [25.0, 5.0, 0.0])


def test_pecking_advanced_stop_distance_is_not_scaled():
    # cycle 1 PECKING under SCL 0.5: set-up 2, depth -6, pecks 2 are 1, 3 and 1 mm of the machine; the
    # advanced stop distance t (0.6 mm for holes up to 30 mm, TNC 426/430 manual, cycle 1) is the control's own
    # clearance, not a programmed dimension: it stays 0.6 mm (our reading; the reference scaled it)
    prog = checked("CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL0.5\nL X+0 Y+0 Z+10 R0 FMAX\nCYCL DEF 1.0 PECKING\n"
                   "CYCL DEF 1.1 SET UP 2\nCYCL DEF 1.2 DEPTH -6\nCYCL DEF 1.3 PECKG 2\nCYCL DEF 1.4 DWELL 0\n"
                   "CYCL DEF 1.5 F100\nCYCL CALL")
    assert [(k, round(z, 6)) for k, (_, _, z) in rows(prog, 11) if k != "dwell"] == [
        ("line", 3.0), ("rapid", 5.0), ("rapid", 3.6), ("line", 2.0), ("rapid", 5.0), ("rapid", 2.6),
        ("line", 1.0), ("rapid", 5.0)]


def test_pocket_wall_finishing_starts_where_the_roughing_left_the_tool():
    # cycle 251 (TNC 640 cycle programming manual, "POCKET MILLING (Cycle 251)"): roughing to Q201 = -4 in one
    # pass (Q202 = 5), up by Q200 = 2 and back over the centre; the wall finished in passes of Q338 = 2, the first
    # at -2, where the tool already is: no plunge there (the reference expected a zero-length feed), then out to
    # the finished wall, half side 27.5 - R3 = 24.5 along X, at -2 and -4
    prog = checked("TOOL DEF 1 L+0 R+3\nTOOL CALL 1 Z S8000\nL X+50 Y+50 Z+20 R0 FMAX\n"
                   "CYCL DEF 251 RECTANGULAR POCKET Q215=+0 Q218=+55 Q219=+30 Q220=+4 Q368=+0.2 Q224=+0 Q367=+0 "
                   "Q207=+300 Q351=-1 Q201=-4 Q202=+5 Q369=+0 Q206=+150 Q338=+2 Q200=+2 Q203=+0 Q204=+50 Q370=+1 "
                   "Q366=+0 Q385=+500\nCYCL CALL")
    call = rows(prog, 6)
    k = call.index(("rapid", [50.0, 50.0, -2.0]))
    assert call[k + 1:k + 3] == [("line", [74.5, 50.0, -2.0]), ("line", [74.5, 39.0, -2.0])]
    assert ("line", [50.0, 50.0, -4.0]) in call[k + 3:] and ("line", [74.5, 50.0, -4.0]) in call[k + 3:]
    assert call[-2:] == [("rapid", [50.0, 50.0, 2.0]), ("rapid", [50.0, 50.0, 50.0])]


@pytest.mark.parametrize("body", [
    "L X+10 Y+0\nRND R5\nL X+10 Y+3",  # 90 degrees: R5 takes 5 mm of each line, the second has 3
    "L X+7 Y+0\nL X+10 Y+0\nRND R5\nL X+10 Y+20",  # the first has 3
    "L X+10 Y+0\nRND R4\nL X+10 Y+10\nRND R7\nL X+0 Y+10",  # 6 left of the second line after the first rounding
])
def test_a_rounding_longer_than_a_line_is_refused_by_the_reference_too(body):
    # the reference put the fillet where the lines offset by R meet without asking whether its tangent points
    # lie on the lines (TNC 640 manual, "Rounding corners RND": the arc is tangential to both elements); the
    # reader refuses (corners.round_corner: "it needs .. mm of each line"), the reference accepted: tnc_generator
    # seed 1100172 (drive.py tnc 1100000 1500, fuzz39)
    text = f"0 BEGIN PGM T MM\nL X+0 Y+0 Z+0 R0 F100\n{body}\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match="rounding radius"):
        parse_heidenhain(text, source="t.h", context=HOME)
    with pytest.raises(ReferenceError, match="RND radius does not fit"):
        heidenhain_reference(text, HOME)


def test_a_rounding_that_just_fits_on_the_line_left_by_the_one_before():
    prog = checked("L X+0 Y+0 Z+0 R0 F100\nL X+10 Y+0\nRND R4\nL X+10 Y+10\nRND R6\nL X+0 Y+10\nRND R4\n"
                   "L X+0 Y+30", exact=True)
    assert prog.blocks


def test_an_inside_rounding_no_larger_than_the_tool_must_fit_on_its_lines_too():
    # RL, an inside corner, RND R2 under the tool's R3: the tool centre paths meet without the arc, but the
    # programmed rounding still takes 2 mm of the 1.5 mm line after it; the reference skipped such roundings before
    # it asked (tnc_generator seeds 1100805, 1101054)
    text = ("0 BEGIN PGM T MM\nTOOL DEF 1 L+0 R+3\nTOOL CALL 1 Z S1000\nL X+0 Y-10 Z+0 R0 F100\nL X+10 Y+0 RL\n"
            "L X+30 Y+0\nRND R2\nL X+30 Y+1.5\nL X+60 Y+1.5\nL X+60 Y-20 R0\nEND PGM T MM\n")
    with pytest.raises(GCodeError, match="rounding radius 2 mm does not fit"):
        parse_heidenhain(text, source="t.h", context=HOME)
    with pytest.raises(ReferenceError, match="RND radius does not fit"):
        heidenhain_reference(text, HOME)
