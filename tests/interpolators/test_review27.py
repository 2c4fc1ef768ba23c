"""Defects found in the review of session 27's readers (review27), each with a hand-written program."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

ZERO = MachineContext()
#: A B/C tilting table, B about Y with its pivot 50 mm below the part's zero, C about Z.
TILT = MachineContext(home=(0.0, 0.0, 300.0), extra_axes=("b", "c"),
                      kinematics=Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0),
                                                             limits=(-120.0, 120.0)), RotaryAxis(name="c"))))
DRILL = ("CYCL DEF 200 DRILLING Q200=2 Q201=-5 Q206=150 Q202=5 Q210=0 Q203=+0 Q204=20 Q211=0\n")


def heidenhain(body: str, context: MachineContext = ZERO):
    return parse_heidenhain("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", source="t.h", context=context)


def test_cycle_call_pos_keeps_its_positioning_feed_beside_an_m140_retract_feed():
    # 'CYCL CALL POS .. F300 M140 MB 30 F700': F300 positions the tool, F700 is the retraction's (TNC 640
    # user's manual, M140: "you can also enter a feed rate" after MB); the positioning ran at F700
    prog = heidenhain("TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+10 R0 F500\n" + DRILL
                      + "CYCL CALL POS X+20 Y+0 Z+0 F300 M140 MB 30 F700")
    # M140 is effective at the block's end: the retract 30 up from the cycle's 2nd set-up clearance comes last
    moves = [(b.kind, round(b.feed * 60, 6), list(np.round(b.target, 6))) for b in prog.blocks if b.line == 5]
    assert moves[:2] == [("line", 300.0, [20.0, 0.0, 10.0]), ("line", 300.0, [20.0, 0.0, 0.0])]
    assert moves[-1] == ("line", 700.0, [20.0, 0.0, 50.0])


def test_cycle_call_with_an_m140_retract_feed_is_no_positioning_feed():
    prog = heidenhain("TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+10 R0 F500\n" + DRILL + "CYCL CALL M140 MB 30 F700")
    last = prog.blocks[-1]  # the retract after the cycle (M140 at the block's end), at its own F700
    assert (last.kind, last.feed * 60) == ("line", pytest.approx(700.0))
    assert np.asarray(last.target) == pytest.approx([0.0, 0.0, 50.0])
    assert not any("CYCL CALL F" in n for n in prog.notes)


@pytest.mark.parametrize("block, column, got", [
    ("CYCL DEF 19.1 B+10 C+90 F0", 25, "F0"),
    ("CYCL DEF 19.1 B+10 C+90 FQ12", 25, "FQ12"),
    ("PLANE SPATIAL SPA+0 SPB+10 SPC+90 MOVE F0", 40, "F0"),
])
def test_a_rotary_positioning_feed_of_zero_is_named(block, column, got):
    # the positioning line at F0 failed later as "axis limits leave no admissible path speed", without a line
    with pytest.raises(GCodeError, match=rf"t.h:5:{column}: .*must be > 0 \(got '{got}'\)"):
        heidenhain(f"TOOL CALL 1 Z S2000\nFN 0: Q12 = +0\nL Z+100 R0 FMAX M91\n{block}\nL X+10 R0 FMAX", TILT)


def test_cycle_19_without_angles_but_with_f_says_that_the_axes_turn_back():
    # the note said "(no motion)" over the line that turns B and C back to 0 at F1000
    prog = heidenhain("TOOL CALL 1 Z S2000\nL Z+100 R0 FMAX M91\nL B+5 C+5 R0 FMAX\nCYCL DEF 19.0 WORKING PLANE\n"
                      "CYCL DEF 19.1 F1000", TILT)
    turn = prog.blocks[-1]
    assert (turn.kind, turn.feed * 60) == ("line", pytest.approx(1000.0))
    assert turn.extra_target[1:3] == pytest.approx([0.0, 0.0])
    assert ("CYCL DEF 19 without angles: the tilted working plane is cancelled (the rotary axes turn to 0 at its F)"
            in prog.notes)


def test_a_haas_dwell_p_with_a_decimal_point_is_seconds():
    # Haas mill operator's manual, G04 Dwell: "G04 P10. is a dwell of 10 seconds", "G04 P10 is a dwell of 10
    # milliseconds"; --dialect haas read both in ms (and noted P10. as a seconds post's). A cycle's P0.5 is
    # seconds too, also for the next hole of the series (P sticky), and P500 stays 500 ms
    prog = checked_iso("G20 G90 G17\nG04 P10\nG04 P10.\nG0 X1. Y1. Z0.1\nG82 X1. Y1. Z-0.2 R0.1 P0.5 F10.\n"
                       "X2.\nG82 X3. Z-0.2 R0.1 P500\nG80\nM30\n", MachineContext().with_dialect("haas"))
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == pytest.approx([0.01, 10.0, 0.5, 0.5, 0.5])
    assert not any("decimal point" in n for n in prog.notes)


@pytest.mark.parametrize("words, column, got", [("B+10 C+90 F MAX", 25, "F"), ("B+10 C+90 FMAX", 25, "FMAX"),
                                                ("B+10 C+90 F1000 MB 50", 31, "MB")])
def test_a_word_cycle_19_has_not_is_named_at_the_cycle(words, column, got):
    # 'F MAX' (the cycle's feed takes a number) was skipped, the rotary axes left where they were, and the error
    # blamed the next move ('while the rotary axes are not at its positions'); 'MB 50' was dropped without a word
    with pytest.raises(GCodeError, match=rf"t.h:5:{column}: '{got}' is no word of CYCL DEF 19.1; expected CYCL DEF "
                                         r"19.1 A.. B.. C.. \[F<feed>\] \[ABST<clearance>\]"):
        heidenhain(f"TOOL CALL 1 Z S2000\nL Z+100 R0 FMAX M91\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 {words}\n"
                   "L X+10 Y+10 R0 FMAX", TILT)
