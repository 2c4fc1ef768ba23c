"""Defects found in the review of session 27's readers (review27), each with a hand-written program."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain

ZERO = MachineContext()
DRILL = ("CYCL DEF 200 DRILLING Q200=2 Q201=-5 Q206=150 Q202=5 Q210=0 Q203=+0 Q204=20 Q211=0\n")


def heidenhain(body: str, context: MachineContext = ZERO):
    return parse_heidenhain("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", source="t.h", context=context)


def test_cycle_call_pos_keeps_its_positioning_feed_beside_an_m140_retract_feed():
    # 'CYCL CALL POS .. F300 M140 MB 30 F700': F300 positions the tool, F700 is the retraction's (TNC 640
    # user's manual, M140: "you can also enter a feed rate" after MB); the positioning ran at F700
    prog = heidenhain("TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+10 R0 F500\n" + DRILL
                      + "CYCL CALL POS X+20 Y+0 Z+0 F300 M140 MB 30 F700")
    moves = [(b.kind, round(b.feed * 60, 6), list(np.round(b.target, 6))) for b in prog.blocks if b.line == 5]
    assert moves[:3] == [("line", 700.0, [0.0, 0.0, 40.0]), ("line", 300.0, [20.0, 0.0, 40.0]),
                         ("line", 300.0, [20.0, 0.0, 0.0])]


def test_cycle_call_with_an_m140_retract_feed_is_no_positioning_feed():
    prog = heidenhain("TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+10 R0 F500\n" + DRILL + "CYCL CALL M140 MB 30 F700")
    first = prog.blocks[1]
    assert (first.kind, first.feed * 60) == ("line", pytest.approx(700.0))
    assert np.asarray(first.target) == pytest.approx([0.0, 0.0, 40.0])
    assert not any("CYCL CALL F" in n for n in prog.notes)
