"""The old Heidenhain finishing cycles 212 POCKET FINISHING, 213 STUD FINISHING, 214 CIRCULAR POCKET FINISHING and
215 CIRCULAR STUD FINISHING, and the old slots 210 SLOT RECIP. PLNG and 211 CIRCULAR SLOT: hand-written programs
with end points worked out by hand from the cycles' runs (TNC 426/430 user's manual, "Cycles for milling pockets,
studs and slots"; TNC 370 user's manual p. 8-20), each also checked against the independent reference
(``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\nTOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z S1000\nL X+0 Y+0 Z+100 R0 FMAX\n"
CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})
#: depth 10 in plunges of 5 about the centre (50, 40); set-up clearance 2, 2nd set-up clearance 30
COMMON = "Q200=2 Q201=-10 Q206=150 Q202=5 Q207=500 Q203=+0 Q204=30 Q216=+50 Q217=+40"


def run(definition: str, *, reference: bool = True):
    text = HEAD + f"CYCL DEF {definition}\nCYCL CALL\nEND PGM T MM\n"
    return checked_program(text, CTX, check=reference)


def start_and_levels(prog) -> tuple[list, list]:
    b = prog.blocks
    plunges = [blk.target[2] for blk in b if blk.kind == "line" and blk.feed * 60 == pytest.approx(150)]
    return [blk.target.tolist() for blk in b[1:4]], plunges


def test_pocket_finishing_212_runs_the_wall_at_each_plunging_depth():
    # to the 2nd set-up clearance Z+30, over the centre, FMAX to Z+2, at Q206 to -5 and -10; the wall of the
    # pocket 80 x 60 less R: half sides 35 x 25 (X 15 .. 85, Y 15 .. 65); no floor pass; the end over the centre
    prog = run(f"212 POCKET FINISHING {COMMON} Q218=80 Q219=60 Q220=5 Q221=0")
    head, plunges = start_and_levels(prog)
    assert head == [[0, 0, 30], [50, 40, 30], [50, 40, 2]] and plunges == [-5, -10]
    wall = [blk.target[:2].tolist() for blk in prog.blocks if blk.feed * 60 == pytest.approx(500)]
    assert {tuple(p) for p in wall} == {(85, 40), (85, 65), (15, 65), (15, 15), (85, 15), (50, 40)}
    assert prog.blocks[-1].target.tolist() == [50, 40, 30]


def test_circular_pocket_finishing_214_runs_252s_finishing_circle():
    # the wall circle of radius 40 - 5 about (50, 40), counter-clockwise (climb milling), reached by half circles
    prog = run(f"214 C. POCKET FINISHING {COMMON} Q222=70 Q223=80")
    arcs = [blk for blk in prog.blocks if blk.kind == "arc"]
    assert len(arcs) == 6 and all(blk.segment.ccw for blk in arcs)
    assert max(blk.target[0] for blk in arcs) == pytest.approx(85)
    assert start_and_levels(prog)[1] == [-5, -10]


def test_stud_finishing_213_one_revolution_per_depth_from_q221():
    # the start Q221 = 3 beyond the stud plus R: X 50 + 40 + 3 + 5 = 98; one clockwise revolution round the stud
    # grown by R (half sides 45 x 35, corners 5 + 5) at each depth; the end over the centre
    prog = run(f"213 STUD FINISHING {COMMON} Q218=80 Q219=60 Q220=5 Q221=3")
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[1:5]] == [[0, 0, 30], [50, 40, 30], [98, 40, 30], [98, 40, 2]]
    corners = [blk for blk in b if blk.kind == "arc" and round(blk.segment.radius, 9) == 10]
    assert len(corners) == 8 and not any(blk.segment.ccw for blk in corners)
    assert b[-1].target.tolist() == [50, 40, 30]


def test_circular_stud_finishing_215_starts_at_the_blank():
    # the start at the blank Q222 / 2 plus R: X 50 + 45 + 5 = 100; the stud circle of radius 40 + 5
    prog = run(f"215 C. STUD FINISHING {COMMON} Q222=90 Q223=80")
    b = prog.blocks
    assert b[3].target.tolist() == [100, 40, 30]
    ring = [blk for blk in b if blk.kind == "arc" and round(blk.segment.radius, 9) == 45]
    assert ring and all(math.hypot(*(blk.target[:2] - [50, 40])) == pytest.approx(45) for blk in ring)
    assert np.allclose(b[-1].target, [50, 40, 30])


def test_finishing_cycles_bad_definitions_are_errors():
    with pytest.raises(GCodeError, match="cycle 212 lacks Q216"):
        run("212 POCKET FINISHING Q200=2 Q201=-10 Q206=150 Q202=5 Q207=500 Q203=+0 Q204=30 Q217=+40 Q218=80 "
            "Q219=60", reference=False)
    with pytest.raises(GCodeError, match="blank Q222 must be at least"):
        run(f"215 C. STUD FINISHING {COMMON} Q222=70 Q223=80", reference=False)


SLOT = "Q200=2 Q201=-6 Q207=500 Q202=3 Q215={op} Q203=+0 Q204=20 Q216=+50 Q217=+40"


def test_slot_210_reciprocates_down_along_the_slot_and_finishes_its_wall():
    # the slot 60 x 12 about (50, 40): the end circles' centres (the tool radius inside the ends) at X 25 and 75;
    # each stroke out to one end, back to the other 1.5 down, out again 3 down (Q202 per reciprocation), at Q207
    prog = run(f"210 SLOT RECIP. PLNG {SLOT.format(op=0)} Q218=60 Q219=12 Q224=+0 Q338=0")
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[1:4]] == [[0, 0, 20], [50, 40, 20], [50, 40, 2]]
    assert [blk.target.tolist() for blk in b[4:7]] == [[75, 40, 2], [25, 40, -0.5], [75, 40, -3]]
    assert all(blk.feed * 60 == pytest.approx(500) for blk in b if blk.kind != "rapid")
    # the wall: the obround of half width 6 - 5 = 1 round the end centres, climbing (counter-clockwise)
    ends = [blk for blk in b if blk.kind == "arc"]
    assert ends and all(blk.segment.ccw and abs(blk.segment.radius - 1) < 1e-9 for blk in ends)
    assert min(blk.target[2] for blk in b) == -6 and b[-1].target.tolist() == [50, 40, 20]


def test_circular_slot_211_runs_254s_slot_on_the_pitch_circle():
    # the pitch circle of diameter 80 about (50, 40) from 0 over 90 degrees: the first end at (90, 40); the slot
    # width 12 with R 5: the tool centre 1 off the pitch circle, inside and out
    prog = run(f"211 CIRCULAR SLOT {SLOT.format(op=0)} Q244=80 Q219=12 Q245=+0 Q248=90 Q338=0")
    b = prog.blocks
    assert b[1].target.tolist() == [90, 40, 100] and b[2].target.tolist() == [90, 40, 2]
    for blk in b[3:]:
        r = math.hypot(*(blk.target[:2] - [50, 40]))
        a = math.degrees(math.atan2(blk.target[1] - 40, blk.target[0] - 50))
        assert 39 - 1e-9 <= r <= 41 + 1e-9 or math.hypot(*(blk.target[:2] - [90, 40])) <= 1 + 1e-9
        assert -1e-9 <= a <= 90 + 1e-9 or r < 1e-9
    assert [blk.target[2] for blk in b if blk.kind == "line" and blk.start[2] != blk.target[2]][:2] == [-3, -6]


def test_old_slots_bad_definitions_are_errors():
    with pytest.raises(GCodeError, match="slot length Q218 must exceed its width"):
        run(f"210 SLOT RECIP. PLNG {SLOT.format(op=0)} Q218=10 Q219=12 Q224=+0", reference=False)
    with pytest.raises(GCodeError, match="Q215 must be 0, 1 or 2"):
        run(f"211 CIRCULAR SLOT {SLOT.format(op=3)} Q244=80 Q219=12 Q245=+0 Q248=90", reference=False)
