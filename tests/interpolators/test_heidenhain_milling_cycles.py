"""Heidenhain milling cycles 253 SLOT MILLING and 257 CIRCULAR STUD (and the thread-milling family): hand-written
programs with end points worked out by hand from the TNC 640 cycle programming manual, each also checked against
the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n"
CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})


def run(body: str, *, reference: bool = True):
    text = HEAD + body + "\nEND PGM T MM\n"
    return checked_program(text, CTX, check=reference)


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


@pytest.mark.parametrize("plunge", ["Q366=0", "Q366=1", "Q366=2"])
def test_slot_milling_253_stays_inside_the_turned_slot(plunge):
    for q in ("Q215=0 Q368=0.5 Q369=0.2 Q338=1 Q374=30 Q351=+1 Q370=1", "Q215=2 Q368=0 Q369=0 Q338=0 Q374=-90 "
              "Q351=-1 Q370=0.5", "Q215=1 Q368=0 Q369=0 Q338=0 Q374=0 Q351=-1 Q370=1.4"):
        prog = run(SLOT.format(q=q).replace("Q366=0", plunge))
        a = math.radians(float(q.split("Q374=")[1].split()[0]))
        for blk in prog.blocks[1:]:  # the tool centre within the slot less its radius: an obround 26 x 6
            dx, dy = blk.target[0] - 10, blk.target[1] - 20
            u, v = dx * math.cos(a) + dy * math.sin(a), -dx * math.sin(a) + dy * math.cos(a)
            assert math.hypot(max(abs(u) - 10, 0.0), v) <= 3 + 1e-9 and blk.target[2] >= -4 - 1e-9
    with pytest.raises(GCodeError, match="Q367=-1 is not a position"):
        run(SLOT.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q374=0 Q351=1").replace("Q367=0", "Q367=-1"))
    with pytest.raises(GCodeError, match="Q366=3 is not a plunging strategy"):
        run(SLOT.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q374=0 Q351=1").replace("Q366=0", "Q366=3"))


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


THREADS = "TOOL DEF 2 L+0 R+4\nTOOL CALL 2 Z S500\nL X+0 Y+0 Z+50 R0 FMAX\nL X+10 Y+20 FMAX\n{cycle}\nCYCL CALL"


def moves(prog):
    """(kind, x, y, z) of the cycle's moves, and the arcs' (centre x, y, counter-clockwise)."""
    out = []
    for b in prog.blocks[2:]:
        row = (b.kind, *np.round(b.target, 9).tolist())
        if b.kind == "arc":
            row += (*np.round(b.segment.center[:2], 9).tolist(), b.segment.ccw)
        out.append(row)
    return out


def test_thread_milling_countersinking_263_countersinks_then_mills_one_pitch():
    # M12 x 1.5 right-hand, tool radius 4: the helix radius 2 about (10, 20); countersinking depth 2: at Q253 to
    # the set-up clearance above it (Z0), at Q254 to Z-2, a circle on the helix radius; then the thread as 262
    prog = run(THREADS.format(cycle="CYCL DEF 263 THREAD MLLNG/CNTSNKG Q335=12 Q239=+1.5 Q201=-6 Q356=-2 Q253=750 "
                                    "Q351=+1 Q200=2 Q357=0 Q358=+0 Q359=+0 Q203=+0 Q204=20 Q254=200 Q207=300"))
    assert moves(prog) == [
        ("rapid", 10, 20, 2), ("line", 10, 20, 0), ("line", 10, 20, -2),
        ("arc", 12, 20, -2, 11, 20, True), ("arc", 12, 20, -2, 10, 20, True), ("arc", 10, 20, -2, 11, 20, True),
        ("line", 10, 20, -6), ("arc", 12, 20, -6, 11, 20, True), ("arc", 12, 20, -4.5, 10, 20, True),
        ("arc", 10, 20, -4.5, 11, 20, True), ("rapid", 10, 20, 2), ("rapid", 10, 20, 20)]
    feeds = [round(b.feed * 60, 6) for b in prog.blocks[3:6]]
    assert feeds == [750, 200, 200]


def test_bore_thread_milling_264_drills_countersinks_at_the_front_then_mills():
    # drilled to Q356 = 10 in infeeds of 5 (re-entry Q258 = 0.5 above the last depth), countersunk at the front
    # 1 deep on a circle of Q359 = 1, then a left-hand thread climb-milled: downward from one pitch above -8
    prog = run(THREADS.format(cycle="CYCL DEF 264 BORE/THREAD MLLNG Q335=12 Q239=-1.5 Q201=-8 Q356=-10 Q253=750 "
                                    "Q351=+1 Q202=5 Q258=0.5 Q257=0 Q256=0 Q358=-1 Q359=1 Q200=2 Q203=+0 Q204=20 "
                                    "Q206=100 Q207=300"))
    assert moves(prog) == [
        ("rapid", 10, 20, 2), ("line", 10, 20, -5), ("rapid", 10, 20, 2), ("rapid", 10, 20, -4.5),
        ("line", 10, 20, -10), ("rapid", 10, 20, 2), ("line", 10, 20, -1),
        ("arc", 11, 20, -1, 10.5, 20, True), ("arc", 11, 20, -1, 10, 20, True), ("arc", 10, 20, -1, 10.5, 20, True),
        ("line", 10, 20, -6.5), ("arc", 12, 20, -6.5, 11, 20, True), ("arc", 12, 20, -8, 10, 20, True),
        ("arc", 10, 20, -8, 11, 20, True), ("rapid", 10, 20, 2), ("rapid", 10, 20, 20)]
    assert round(prog.blocks[3].feed * 60, 6) == 100 and round(prog.blocks[9].feed * 60, 6) == 100  # Q254: Q206


def test_helical_bore_thread_milling_265_runs_down_from_the_surface_and_countersinks_after():
    # right-hand: clockwise downward, 2 turns from Z0 to Z-3; Q360 = 1: the front countersinking after the thread
    prog = run(THREADS.format(cycle="CYCL DEF 265 HEL. BORE/THRD MLLNG Q335=12 Q239=+1.5 Q201=-3 Q253=750 Q358=-0.5 "
                                    "Q359=0.5 Q360=1 Q200=2 Q203=+0 Q204=20 Q254=150 Q207=300"))
    assert moves(prog) == [
        ("rapid", 10, 20, 2), ("line", 10, 20, 0), ("arc", 12, 20, 0, 11, 20, False),
        ("arc", 12, 20, -3, 10, 20, False), ("arc", 10, 20, -3, 11, 20, False), ("line", 10, 20, -0.5),
        ("arc", 10.5, 20, -0.5, 10.25, 20, False), ("arc", 10.5, 20, -0.5, 10, 20, False),
        ("arc", 10, 20, -0.5, 10.25, 20, False), ("rapid", 10, 20, 2), ("rapid", 10, 20, 20)]
    helix = prog.blocks[5].segment
    assert math.isclose(helix.length, math.hypot(2 * 2 * math.pi * 2, 3))  # two turns of radius 2, 3 down


def test_outside_thread_milling_267_runs_round_the_stud_from_outside():
    # M20 x 2 right-hand stud, tool radius 4: the helix on 10 + 4 = 14; start one pitch outside (16) on +X;
    # climb milling outside runs clockwise, for a right-hand thread downward from one pitch above the depth
    prog = run(THREADS.format(cycle="CYCL DEF 267 OUTSIDE THREAD MLLNG Q335=20 Q239=+2 Q201=-10 Q355=0 Q253=500 "
                                    "Q351=+1 Q200=2 Q358=+0 Q359=+0 Q203=+0 Q204=20 Q254=0 Q207=300"))
    assert moves(prog) == [
        ("rapid", 10, 20, 2), ("rapid", 26, 20, 2), ("line", 26, 20, -8), ("arc", 24, 20, -8, 25, 20, True),
        ("arc", 24, 20, -10, 10, 20, False), ("arc", 26, 20, -10, 25, 20, True), ("rapid", 26, 20, 2),
        ("rapid", 26, 20, 20)]
    up = run(THREADS.format(cycle="CYCL DEF 267 OUTSIDE THREAD MLLNG Q335=20 Q239=+2 Q201=-10 Q355=1 Q253=500 "
                                  "Q351=-1 Q200=2 Q358=+0 Q359=+0 Q203=+0 Q204=20 Q254=0 Q207=300"))
    for b in up.blocks[3:]:  # up-cut: counter-clockwise, upward over the whole stud; never inside 14
        assert math.hypot(b.target[0] - 10, b.target[1] - 20) >= 14 - 1e-9 and b.target[2] >= -10 - 1e-9
    assert [b.target[2] for b in up.blocks if b.kind == "arc"] == [-10, 0, 0] and up.blocks[6].segment.ccw
    with pytest.raises(GCodeError, match="countersinking at the front"):
        run(THREADS.format(cycle="CYCL DEF 267 OUTSIDE THREAD MLLNG Q335=20 Q239=+2 Q201=-10 Q355=0 Q253=500 "
                                 "Q351=+1 Q200=2 Q358=-1 Q359=1 Q203=+0 Q204=20 Q254=100 Q207=300"))


POCKET = ("TOOL DEF 2 L+0 R+4\nTOOL CALL 2 Z S500\nL X+10 Y+20 Z+50 R0 FMAX\nCYCL DEF 252 CIRCULAR POCKET Q215=1 "
          "Q223=30 Q368=0 Q207=500 Q351=+1 Q201=-4 Q202=2 Q369=0 Q206=150 Q338=0 Q200=2 Q203=+0 Q204=20 Q370=1 "
          "{q}\nCYCL CALL")


def test_helical_plunging_q366_1_turns_once_on_the_tool_radius():
    # circular pocket 30 about (10, 20), tool radius 4: the helix on R = 4 about the centre, one turn per infeed,
    # counter-clockwise (climb), out from and back to the centre at Q206; then the rings as before
    prog = run(POCKET.format(q="Q366=1"))
    b = prog.blocks
    assert [(blk.kind, *np.round(blk.target, 9).tolist()) for blk in b[1:5]] == [
        ("rapid", 10, 20, 2), ("line", 14, 20, 2), ("arc", 14, 20, -2), ("line", 10, 20, -2)]
    helix = b[3].segment
    assert helix.ccw and np.allclose(helix.center[:2], [10, 20]) and round(b[3].feed * 60, 6) == 150
    assert math.isclose(helix.length, math.hypot(2 * math.pi * 4, 4))  # from the clearance 2 down to -2
    second = [blk for blk in b if blk.kind == "arc" and blk.target[2] == -4 and round(blk.feed * 60) == 150]
    assert len(second) == 1 and np.allclose(second[0].target, [14, 20, -4])  # from 2 above -2, down to -4
    for blk in b[1:]:
        assert math.hypot(blk.target[0] - 10, blk.target[1] - 20) <= 11 + 1e-9
    with pytest.raises(GCodeError, match="Q366=2 is not a plunging strategy"):
        run(POCKET.format(q="Q366=2"))


def test_reciprocating_plunging_q366_2_runs_along_the_slot():
    # slot 30 x 10, tool radius 2, no allowance: out to 15 - 2 = 13 along the slot axis (turned 90 degrees: +Y),
    # to the other end halfway down, back to the first end at the depth, to the centre
    prog = run(SLOT.format(q="Q215=1 Q368=0 Q369=0 Q338=0 Q374=90 Q351=+1 Q370=1").replace("Q366=0", "Q366=2"))
    got = [np.round(blk.target, 9).tolist() for blk in prog.blocks[2:6]]
    assert got == [[10, 33, 2], [10, 7, 0], [10, 33, -2], [10, 20, -2]]
    assert all(blk.kind == "line" and round(blk.feed * 60) == 150 for blk in prog.blocks[2:6])


def test_cycle_feeds_written_auto_are_the_feed_of_tool_call():
    # a shop program (iTNC 530): "TOOL CALL 7 Z S4100 F350" then "CYCL DEF 253 .. Q207= AUTO .. Q206= AUTO"
    body = SLOT.format(q="Q215=1 Q368=0 Q369=0 Q338=0 Q374=90 Q351=+1 Q370=1").replace("Q207=500", "Q207= AUTO")
    body = body.replace("Q206=150", "Q206= AUTO").replace("TOOL CALL 2 Z S500", "TOOL CALL 2 Z S500 F350")
    prog = run(body)
    assert {round(b.feed * 60, 6) for b in prog.blocks if b.kind in ("line", "arc")} == {350}
    with pytest.raises(GCodeError, match="Q207=AUTO without a feed in the TOOL CALL"):
        run(body.replace(" F350", ""))


ARC_SLOT = ("TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+0 Y+0 Z+50 R0 FMAX\nCYCL DEF 254 CIRCULAR SLOT Q219=10 "
            "Q375=60 Q367=0 Q216=+0 Q217=+0 Q376=+0 Q248=90 {q} Q207=500 Q201=-2 Q202=2 Q206=150 Q338=0 Q200=2 "
            "Q203=+0 Q204=20 Q385=400 Q370=1\nCYCL CALL")


def test_circular_slot_254_mills_each_slot_along_its_arc():
    # a 10 wide slot on the pitch circle 60 about (0, 0) from 0 to 90 degrees, tool radius 2: rings 2 and 3 from
    # the centre line; two slots 180 degrees apart (Q377 = 2, Q378 = 180)
    prog = run(ARC_SLOT.format(q="Q215=1 Q368=0 Q369=0 Q351=+1 Q366=0 Q378=180 Q377=2"))
    b = prog.blocks
    assert [np.round(x.target, 9).tolist() for x in b[1:5]] == [[30, 0, 50], [30, 0, 2], [30, 0, -2], [32, 0, -2]]
    ring = [(x.kind, *np.round(x.target[:2], 9).tolist(), *np.round(x.segment.center[:2], 9).tolist(), x.segment.ccw)
            for x in b[5:9]]
    assert ring == [("arc", 0, 32, 0, 0, True), ("arc", 0, 28, 0, 30, True), ("arc", 28, 0, 0, 0, False),
                    ("arc", 32, 0, 30, 0, True)]
    second = [x for x in b if np.allclose(x.target, [-30, 0, 2]) and x.kind == "rapid"]
    assert second, "the second slot starts over (-30, 0)"
    for x in b[1:]:  # inside the slots: within 3 of the centre line arc or over it
        r, a = math.hypot(x.target[0], x.target[1]), math.degrees(math.atan2(x.target[1], x.target[0])) % 360
        ends = min(math.hypot(x.target[0] - e[0], x.target[1] - e[1]) for e in ((30, 0), (0, 30), (-30, 0), (0, -30)))
        on_arc = abs(r - 30) <= 3 + 1e-9 and (a <= 90 + 1e-6 or 180 - 1e-6 <= a <= 270 + 1e-6)
        assert on_arc or ends <= 3 + 1e-9 or x.target[2] > 0


def test_circular_slot_254_up_cut_finishing_and_helical_plunge():
    prog = run(ARC_SLOT.format(q="Q215=0 Q368=0.5 Q369=0 Q351=-1 Q366=1 Q378=0 Q377=1"))
    arcs = [x.segment for x in prog.blocks if x.kind == "arc"]
    assert any(not a.ccw and np.allclose(a.center[:2], [30, 0]) for a in arcs)  # up-cut: clockwise round the end
    assert np.allclose(prog.blocks[4].segment.center[:2], [30, 0])  # the helix about the first end, on R = 2
    with pytest.raises(GCodeError, match="Q367=1"):
        run(ARC_SLOT.format(q="Q215=0 Q368=0 Q369=0 Q351=1 Q366=0 Q378=0 Q377=1").replace("Q367=0", "Q367=1"))


OLD_POCKET = ("TOOL DEF 2 L+0 R+3\nTOOL CALL 2 Z S500\nCYCL DEF 5.0 CIRCULAR POCKET\nCYCL DEF 5.1 SET UP {setup}\n"
              "CYCL DEF 5.2 DEPTH -5\nCYCL DEF 5.3 PECKG 3 F100\nCYCL DEF 5.4 RADIUS 9\nCYCL DEF 5.5 F300 {dr}\n"
              "L X+10 Y+20 Z+2 R0 FMAX M99")


def test_old_circular_pocket_5_plunges_and_mills_out_from_the_starting_position():
    # TNC 426 manual, cycle 5: the surface is SET UP below the starting point Z+2 (Z0); plunging depths 3, 2 at
    # F100; rings 3 (K x R) apart out to 9 - 3 = 6 at F300, counter-clockwise for DR+; back to the start
    prog = run(OLD_POCKET.format(setup=2, dr="DR+"))
    b = prog.blocks
    assert [x.target.tolist() for x in b[:6]] == [[10, 20, 2], [10, 20, -3], [13, 20, -3], [13, 20, -3],
                                                 [16, 20, -3], [16, 20, -3]]
    assert [round(x.feed * 60) for x in b[1:6]] == [100, 300, 300, 300, 300]
    assert all(x.segment.ccw for x in b if x.kind == "arc")
    assert [x.target.tolist() for x in b[6:9]] == [[16, 20, -1], [10, 20, -1], [10, 20, -5]]
    assert b[-1].target.tolist() == [10, 20, 2] and b[-1].kind == "rapid"
    up = run(OLD_POCKET.format(setup="+1,5", dr="DR-"))  # up-cut: clockwise; decimal comma
    assert not any(x.segment.ccw for x in up.blocks if x.kind == "arc")
    assert up.blocks[1].target.tolist() == [10, 20, -2.5]
    for blk in prog.blocks + up.blocks:  # the tool centre never leaves the pocket less the tool radius
        assert math.hypot(blk.target[0] - 10, blk.target[1] - 20) <= 6 + 1e-9


def test_old_circular_pocket_5_needs_all_its_lines_and_room_for_the_tool():
    with pytest.raises(GCodeError, match="cycle 5 CIRCULAR POCKET lacks 5.4"):
        run(OLD_POCKET.replace("CYCL DEF 5.4 RADIUS 9\n", "").format(setup=2, dr="DR+"), reference=False)
    with pytest.raises(GCodeError, match=r"cycle 5: the tool \(radius 3 mm\) and the radius 5.4 fill the pocket"):
        run(OLD_POCKET.replace("RADIUS 9", "RADIUS 3").format(setup=2, dr="DR+"), reference=False)
    with pytest.raises(GCodeError, match="unexpected 'X' in cycle 5.5"):
        run(OLD_POCKET.format(setup=2, dr="DR+ X"), reference=False)


OLD_RECT = ("TOOL DEF 2 L+0 R+3\nTOOL CALL 2 Z S500\nCYCL DEF 4.0 POCKET MILLING\nCYCL DEF 4.1 SET UP 2\n"
            "CYCL DEF 4.2 DEPTH -5\nCYCL DEF 4.3 PECKG 5 F100\nCYCL DEF 4.4 X{x}\nCYCL DEF 4.5 Y{y}\n"
            "CYCL DEF 4.6 F300 {dr} RADIUS 4\nL X+10 Y+20 Z+2 R0 FMAX\nCYCL CALL")


@pytest.mark.parametrize(("x", "y", "first"), [(20, 30, [10, 20 + 12 - 2 * 7 / 3, -5]), (30, 20, [22 - 14 / 3, 20, -5]),
                                               (20, 20, [10, 27 - 14 / 3, -5])])
def test_old_pocket_milling_4_starts_along_the_longer_side_and_stays_inside(x, y, first):
    # TNC 426 manual, cycle 4: "first in the positive direction of the longer side (in square pockets, in the
    # positive Y direction)", then from the inside out: rings 7 / 3 apart (half the shorter side less R = 7, in
    # steps of at most R) out to the pocket less R, corners rounded by 4 - R = 1; one depth of 5 below the surface
    # Z0 (SET UP 2 below the start), then back up to the start
    for dr in ("DR+", "DR-"):
        prog = run(OLD_RECT.format(x=x, y=y, dr=dr))
        b = prog.blocks
        assert b[1].target.tolist() == [10, 20, -5] and round(b[1].feed * 60) == 100
        assert b[2].target == pytest.approx(first)
        assert all(a.segment.ccw == (dr == "DR+") for a in b if a.kind == "arc")
        for blk in b:
            assert abs(blk.target[0] - 10) <= x / 2 - 3 + 1e-9 and abs(blk.target[1] - 20) <= y / 2 - 3 + 1e-9
        assert b[-1].target.tolist() == [10, 20, 2]


def test_old_pocket_milling_4_needs_its_sides():
    with pytest.raises(GCodeError, match="cycle 4 POCKET MILLING lacks 4.5"):
        run(OLD_RECT.replace("CYCL DEF 4.5 Y{y}\n", "").format(x=20, dr="DR+"), reference=False)
    with pytest.raises(GCodeError, match="cycle 4: the tool .* and the sides 4.4, 4.5 fill the pocket"):
        run(OLD_RECT.format(x=6, y=30, dr="DR+"), reference=False)


def test_circular_stud_257_finishing_only_q215_2_runs_no_roughing_revolution():
    # Q215 = 2 (TNC 640 cycle programming manual, cycles 256/257, Q215 "machining operation": 0 roughing and
    # finishing, 1 roughing only, 2 finishing only): only the revolution at the finished size (stud 20 + R 4:
    # radius 14) at Q385, none of the roughing stepovers at 16.5 from the blank
    prog = run(STUD.format(q="Q215=2 Q368=0.5 Q351=+1 Q338=0 Q385=300"))
    rounds = [blk for blk in prog.blocks if blk.kind == "arc" and np.allclose(blk.segment.center[:2], [0, 0])]
    assert rounds and {round(a.segment.radius, 9) for a in rounds} == {14}
    assert all(a.feed * 60 == pytest.approx(300) for a in rounds)
