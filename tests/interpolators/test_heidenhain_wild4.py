"""Heidenhain programs of a fourth wild set (hyperMILL, NX and Fusion posts, shop programs of TNC 530/640): the
forms the reader read wrongly or refused without naming the cause, each as a hand-written program, with end
points worked out by hand and, where the reader runs it, checked against the independent reference."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
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
def test_a_position_read_after_a_program_stop_names_the_operators_jog(stop):
    # as the corpus' XDIAL.h: STOP, the operator jogs to a feature, SYSREAD reads where the machine stands
    text = f"0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+20 R0 FMAX\n2 {stop}\n3 FN 18: SYSREAD Q1 = ID270 NR1 IDX1\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match=r"t\.h:4:.*ID270 after a program stop reads where the operator jogged") as err:
        parse_heidenhain(text, source="t.h", context=ZERO)
    assert "before the STOP/M0/M1 (line 3)" in err.value.expected


def test_a_move_after_the_stop_makes_the_position_known_again():
    prog = run("1 L X+0 Y+0 Z+20 R0 FMAX\n2 STOP\n3 L X+7 R0 FMAX\n4 FN 18: SYSREAD Q1 = ID240 NR1 IDX1\n"
               "5 L Y+Q1 R0 FMAX", ZERO)
    assert ends(prog)[-1] == [7.0, 7.0, 20.0]


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
