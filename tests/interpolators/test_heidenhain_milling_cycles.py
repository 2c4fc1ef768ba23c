"""Heidenhain milling cycles 253 SLOT MILLING and 257 CIRCULAR STUD (and the thread-milling family): hand-written
programs with end points worked out by hand from the TNC 640 cycle programming manual, each also checked against
the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n"
CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})


def run(body: str, *, reference: bool = True):
    text = HEAD + body + "\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    if reference:
        match = match_blocks(heidenhain_reference(text, CTX), blocks_table(prog)[1])
        assert match.mismatch is None, match.mismatch
        assert match.exact == len(prog.blocks)
    return prog


SLOT = ("TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+10 Y+20 Z+50 R0 FMAX\nCYCL DEF 253 SLOT MILLING {q} Q218=30 "
        "Q219=10 Q207=500 Q201=-4 Q202=2 Q206=150 Q200=2 Q203=+0 Q204=20 Q366=0 Q385=400 Q367=0\nCYCL CALL")


def test_slot_milling_253_roughs_obrounds_and_finishes_the_wall():
    # slot 30 x 10 about (10, 20), tool radius 2, allowance 0.5: the outer path has half sides 12.5 x 2.5 with
    # corner radius 2.5 (half circles at the ends), one ring inside it at half that inset; 2 depths of 2
    prog = run(SLOT.format(q="Q215=0 Q368=0.5 Q369=0 Q338=0 Q374=0 Q351=+1 Q370=1"))
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[:4]] == [[10, 20, 50], [10, 20, 2], [10, 20, -2], [11.25 + 10, 20, -2]]
    ends = [blk for blk in b if blk.kind == "arc" and round(blk.feed * 60) == 500]
    assert all(a.segment.ccw for a in ends)  # climb milling with M3: counter-clockwise
    # quarter circles, two at each end (counter-clockwise from the right end's middle: top right, top left, bottom
    # left, bottom right): the inner ring's about the end centres (10 +- 10, 20), then the outer's
    assert [a.segment.center[:2].tolist() for a in ends[:8]] == [[20, 20], [0, 20], [0, 20], [20, 20]] * 2
    assert [round(a.segment.radius, 9) for a in ends[:8]] == [1.25] * 4 + [2.5] * 4
    wall = [blk for blk in b if blk.feed * 60 == pytest.approx(400)]  # at half sides 13 x 3, corner 3
    assert np.allclose(wall[0].target, [23, 20, -4]) and np.allclose(wall[-1].target, [10, 20, -4])
    assert np.allclose(b[-1].target, [10, 20, 20])


def test_slot_milling_253_stays_inside_the_turned_slot():
    for q in ("Q215=0 Q368=0.5 Q369=0.2 Q338=1 Q374=30 Q351=+1 Q370=1", "Q215=2 Q368=0 Q369=0 Q338=0 Q374=-90 "
              "Q351=-1 Q370=0.5", "Q215=1 Q368=0 Q369=0 Q338=0 Q374=0 Q351=-1 Q370=1.4"):
        prog = run(SLOT.format(q=q))
        a = math.radians(float(q.split("Q374=")[1].split()[0]))
        for blk in prog.blocks[1:]:  # the tool centre within the slot less its radius: an obround 26 x 6
            dx, dy = blk.target[0] - 10, blk.target[1] - 20
            u, v = dx * math.cos(a) + dy * math.sin(a), -dx * math.sin(a) + dy * math.cos(a)
            assert math.hypot(max(abs(u) - 10, 0.0), v) <= 3 + 1e-9 and blk.target[2] >= -4 - 1e-9
    with pytest.raises(GCodeError, match="Q367=2"):
        run(SLOT.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q374=0 Q351=1").replace("Q367=0", "Q367=2"))
    with pytest.raises(GCodeError, match="Q366=1"):
        run(SLOT.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q374=0 Q351=1").replace("Q366=0", "Q366=1"))


STUD = ("TOOL DEF 2 L+0 R+4\nTOOL CALL 2 Z S500\nL X+0 Y+0 Z+50 R0 FMAX\nCYCL DEF 257 CIRCULAR STUD Q223=20 "
        "Q222=30 {q} Q207=500 Q201=-5 Q202=5 Q206=150 Q200=2 Q203=+0 Q204=20 Q370=1\nCYCL CALL")


def test_circular_stud_257_steps_in_from_the_blank():
    # the blank 30 with R: 19; the stud 20 with R: 14; 5 mm in 2 stepovers of 2.5 (<= Q370 x R = 4) at 16.5 and
    # 14; start 2 mm outside the blank: 15 + 2 + 4 = 21; half circles counter-clockwise onto and off the
    # revolutions, which run clockwise (climb milling round a stud)
    prog = run(STUD.format(q="Q215=1 Q368=0 Q351=+1"))
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[:4]] == [[0, 0, 50], [21, 0, 50], [21, 0, 2], [21, 0, -5]]
    on = b[4]
    assert on.kind == "arc" and on.segment.ccw and np.allclose(on.target, [16.5, 0, -5])
    rounds = [blk for blk in b[5:-3] if blk.kind == "arc"]
    assert len(rounds) == 8 and not any(a.segment.ccw for a in rounds)
    assert {round(a.segment.radius, 9) for a in rounds} == {16.5, 14}
    assert all(np.allclose(a.segment.center[:2], [0, 0]) for a in rounds)
    off = b[-3]
    assert off.segment.ccw and np.allclose(off.segment.center[:2], [17.5, 0]) and np.allclose(off.target, [21, 0, -5])
    assert np.allclose([blk.target for blk in b[-2:]], [[21, 0, 2], [21, 0, 20]])
    for blk in b[1:]:  # never inside the stud grown by the tool radius
        assert math.hypot(blk.target[0], blk.target[1]) >= 14 - 1e-9


def test_circular_stud_257_finishes_with_an_allowance_and_checks_the_blank():
    prog = run(STUD.format(q="Q215=0 Q368=0.5 Q351=-1 Q338=0 Q385=300"))
    finish = [blk for blk in prog.blocks if blk.feed * 60 == pytest.approx(300) and blk.kind == "arc"]
    assert {round(a.segment.radius, 9) for a in finish if np.allclose(a.segment.center[:2], [0, 0])} == {14}
    assert all(a.segment.ccw for a in finish if np.allclose(a.segment.center[:2], [0, 0]))  # up-cut: ccw
    with pytest.raises(GCodeError, match="at least"):
        run(STUD.format(q="Q215=0 Q368=0 Q351=1").replace("Q222=30", "Q222=18"))
