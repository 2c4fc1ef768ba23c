"""Heidenhain programs of a fourth wild set (hyperMILL, NX and Fusion posts, shop programs of TNC 530/640): the
forms the reader read without saying so, refused without naming the cause or refused though a simple reading
exists (M128 on positioned rotary axes), each as a hand-written program, with end points worked out by hand
and, where the reader runs it, checked against the independent reference."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.test_heidenhain_wild import ends, run
from vcnc.errors import GCodeError

ZERO = MachineContext()


def test_a_position_read_before_any_stop_is_the_simulated_one():
    # ID240: machine coordinates; ID270: in the active system (here shifted by cycle 7 X+5)
    prog = run("1 CYCL DEF 7.0 DATUM SHIFT\n2 CYCL DEF 7.1 X+5\n3 L X+12 Y+3 Z+20 R0 FMAX\n"
               "4 FN 18: SYSREAD Q1 = ID240 NR1 IDX1\n5 FN 18: SYSREAD Q2 = ID270 NR1 IDX1\n"
               "6 L X+Q2 Y+Q1 R0 FMAX", ZERO)
    assert ends(prog)[-1] == [12.0 + 5.0, 17.0, 20.0]  # X = 12 + shift 5, Y = 17 (X in machine coordinates)


@pytest.mark.parametrize("stop", ["STOP", "M0", "M1", "L X+5 R0 FMAX M0", "STOP M5"])
def test_a_position_read_after_a_program_stop_is_where_the_program_stopped_with_a_note(stop):
    # as the corpus' XDIAL.h: STOP, the operator jogs to a feature, SYSREAD reads where the machine stands; vcnc
    # reads the position where the program stopped (start pressed without a jog) and notes the stop's line
    prog = run(f"1 L X+0 Y+0 Z+20 R0 FMAX\n2 {stop}\n3 FN 18: SYSREAD Q1 = ID270 NR1 IDX1\n4 Q2 = Q1 + 1\n"
               "5 L Y+Q2 R0 FMAX", ZERO)
    x = 5.0 if "X+5" in stop else 0.0
    assert ends(prog)[-1] == [x, x + 1.0, 20.0]
    assert ("FN 18 ID270 after STOP (line 3): the position where the program stopped; a jog by the operator is "
            "not modelled") in prog.notes


def test_a_move_after_the_stop_makes_the_position_known_again():
    prog = run("1 L X+0 Y+0 Z+20 R0 FMAX\n2 STOP\n3 L X+7 R0 FMAX\n4 FN 18: SYSREAD Q1 = ID240 NR1 IDX1\n"
               "5 L Y+Q1 R0 FMAX", ZERO)
    assert ends(prog)[-1] == [7.0, 7.0, 20.0]
    assert not any("after STOP" in n for n in prog.notes)


def test_cycle_12_called_by_cycl_call_pos_is_named(tmp_path):
    # before: "cycle call without a machining cycle", though cycle 12 was defined
    (tmp_path / "SUB.h").write_text("0 BEGIN PGM SUB MM\n1 L IZ-5 F100\n2 END PGM SUB MM\n")
    main = tmp_path / "MAIN.h"
    main.write_text("0 BEGIN PGM MAIN MM\n1 L X+0 Y+0 Z+10 R0 FMAX\n2 CYCL DEF 12.0 PGM CALL\n"
                    "3 CYCL DEF 12.1 PGM SUB.h\n4 CYCL CALL POS X+10 Y+10 Z+2 FMAX\n5 END PGM MAIN MM\n")
    with pytest.raises(GCodeError, match=r"MAIN\.h:5:.*cycle 12 PGM CALL by a pattern or CYCL CALL POS"):
        parse_heidenhain(main.read_text(), source=str(main), context=ZERO)


def test_a_spindle_speed_on_a_positioning_block_is_named():
    # an NX post writes "L Z-45. F1000. S6000": the TNC programs S in TOOL CALL (before: "unknown word 'S6000'")
    text = "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S4500\n2 L X+0 Y+0 Z+5 R0 FMAX\n3 L Z-4.5 F1000 S6000\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match=r"t\.h:4:.*spindle speed 'S6000' in a positioning block") as err:
        parse_heidenhain(text, source="t.h", context=ZERO)
    assert "TOOL CALL" in err.value.expected


#: A B/C trunnion table (B tilts about Y, C turns about Z), pivots at the machine zero.
BC_TABLE = MachineContext(extra_axes=("b", "c"), kinematics=Kinematics(axes=(
    RotaryAxis(name="b", direction="Y", limits=(-120.0, 120.0)), RotaryAxis(name="c", direction="Z"))))


def test_lines_under_m128_on_positioned_rotary_axes_are_the_tool_tip_on_the_turned_part():
    # the NX post's 3+2 form: rotary axes positioned, M128, straight lines, M129. A table at B+90 turns the part
    # the other way (ISO 841): its point (10, 0, 0) lies at machine (0, 0, 10), (10, 0, 5) at (-5, 0, 10). The F
    # after M128 is the feed of its compensation movements, not the path's (TNC 620 DIN/ISO manual, M128).
    prog = run("1 L X+0 Y+0 Z+50 R0 FMAX\n2 L B+90 C+0 FMAX\n3 L M128 F3000\n4 L X+10 Y+0 Z+0 FMAX\n5 L Z+5 F3000\n"
               "6 L IY+2\n7 M129\n8 L X+1 FMAX", BC_TABLE)
    assert ends(prog)[2:] == [[0.0, 0.0, 10.0], [-5.0, 0.0, 10.0], [-5.0, 2.0, 10.0], [1.0, 2.0, 10.0]]
    assert any(n.startswith("M128: TCPM (lines of the tool tip") for n in prog.notes)


def test_a_turned_c_axis_carries_the_part_point_round():
    # C+90: the table turns the part by -90 degrees about Z, so its point (10, 0) is at machine (0, -10)
    prog = run("1 L X+0 Y+0 Z+50 R0 FMAX\n2 L B+0 C+90 FMAX\n3 M128\n4 L X+10 Y+0 F500", BC_TABLE)
    assert ends(prog)[-1] == pytest.approx([0.0, -10.0, 50.0])


@pytest.mark.parametrize(("body", "message"), [
    ("3 CC X+0 Y+0\n4 C X+0 Y+10 DR+ F500", "C under M128 is not supported"),
    ("3 CYCL DEF 200 DRILLING ~\n Q200=2 ~\n Q201=-5 ~\n Q206=100 ~\n Q202=5 ~\n Q210=0 ~\n Q203=0 ~\n Q204=5 ~\n"
     " Q211=0\n4 L X+5 Y+5 FMAX M99", "a move under M128 other than a straight line"),
])
def test_what_m128_does_not_read_is_named(body, message):
    text = f"0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+50 R0 FMAX\n2 L B+30 C+0 FMAX\n2 M128\n{body}\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match=message):
        parse_heidenhain(text, source="t.h", context=BC_TABLE)


def test_m128_without_a_tilting_table_is_named():
    for context, message in ((ZERO, "needs the machine's kinematics"),
                             (MachineContext(extra_axes=("b", "c"), kinematics=Kinematics(kind="head",
                                                                                         axes=BC_TABLE.kinematics.axes)),
                              "head-tilting machine")):
        with pytest.raises(GCodeError, match=message):
            parse_heidenhain("0 BEGIN PGM T MM\n1 L M128\nEND PGM T MM\n", source="t.h", context=context)
