"""Defects found in the review of session 25's work (tool centre point control, the ISO and TNC wild sets),
each with a hand-written program that failed before its fix."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import DEFAULT_CONTEXT
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Solution
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from tests.interpolators.test_tcp5x import AC, BC, HEAD, TNC, distance_to_line, iso, machine, tips, tnc
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError


def test_m129_ends_m128_at_the_end_of_its_block():
    # TNC 426/430 ISO manual, M128: "M128 becomes effective at the start of block, M129 at the end of block":
    # 'L X+40 B+30 C+20 F600 M129' is still a line of the tip on the turned part, the next line a machine line
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 B+30 C+20 F600 M129\n6 L X+50")
    rows = [i for i, b in enumerate(prog.blocks) if b.number == 5]
    end = machine(BC, [50.0, 5.0, 0.0], Solution(30.0, 20.0))
    assert len(rows) > 1 and prog.blocks[rows[-1]].target == pytest.approx(end, abs=1e-9)
    assert distance_to_line(tips(prog, BC, rows), [20.0, 5.0, 0.0], [50.0, 5.0, 0.0]).max() <= 0.01 * 1.001
    # after M129 X+50 is the machine's X (preset 10 + 50), Z where the table left the tip
    assert prog.blocks[-1].target == pytest.approx([60.0, end[1], end[2]], abs=1e-9)
    assert prog.blocks[-1].extra_target[1:3] == pytest.approx([30.0, 20.0])


@pytest.mark.parametrize("after", ["\x1a", "%\n", "3 not a block\n"])
def test_what_follows_end_pgm_is_not_read(after):
    # the program ends at END PGM (TNC 640 user's manual, "Program structure"): a DOS transfer's Ctrl-Z or a
    # '%' after it is not a block of the program; a block of no TNC language before it still is an error
    text = "0 BEGIN PGM T MM\n1 L X+10 Y+5 Z+2 R0 FMAX\n2 END PGM T MM\n" + after
    prog = parse_heidenhain(text, source="t.h")
    assert [b.target.tolist() for b in prog.blocks] == [[10.0, 5.0, 2.0]]
    assert match_blocks(heidenhain_reference(text, DEFAULT_CONTEXT), reader_rows(*blocks_table(prog))).mismatch is None
    with pytest.raises(GCodeError, match=r"t\.h:3:3: unknown or unsupported block 'not'"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 M30\n2 not a block\n3 END PGM T MM\n", source="t.h")


def test_g92_under_g43_4_sets_the_tip_position():
    # G92 X0 Y0 Z0 under TCP with the table at A10: the tip's point on the part becomes the program's zero, so
    # Y10. moves the tip 10 mm along the part's Y (it took the machine position, 23.6 mm off on the part)
    text = "G21 G90 G54\nG43.4 H1 X0 Y0 Z0 A10.\nG92 X0 Y0 Z0\nG1 Y10. F100.\nG49\nM30\n"
    prog = iso(text)
    end = [b for b in prog.blocks if b.line == 4][-1]
    assert end.target == pytest.approx(machine(AC, [10.0, 15.0, 0.0], Solution(10.0, 0.0)), abs=1e-9)


def test_g43_5_reads_a_component_left_out_as_zero():
    # Fanuc 15i B-63323EN-1/03, 10.4.10, type 2: "When any of I, J, and K is omitted, the omitted I, J, or K is
    # assumed to be 0": 'I0.5 K0.8660254' is the direction (0.5, 0, 0.866), A+30 C+90 from A+30 C0 (it was an error)
    prog = iso("G21 G90 G54\nG0 G43.5 H1 X0 Y0 Z0 I0 J0 K1.\nG1 X20. I0 J-0.5 K0.8660254 F600.\n"
               "G1 Y10. I0.5 K0.8660254\nG49\nM30\n")
    second = [b for b in prog.blocks if b.line == 4]
    assert second[-1].extra_target[[0, 2]] == pytest.approx([30.0, 90.0], abs=1e-6)
    assert second[-1].target == pytest.approx(machine(AC, [30.0, 15.0, 0.0], Solution(30.0, 90.0)), abs=1e-6)


def test_a_line_under_m128_after_a_tool_call_in_y_is_an_error():
    # M128 reads only tool axis Z (heidenhain_tcpm.check_tcpm_on at M128); a TOOL CALL .. Y after it made the
    # next line a TCP line on a Z spindle
    with pytest.raises(GCodeError, match=r"t\.h:6:1: a line under M128 with tool axis Y is not supported"):
        tnc("3 M128\n4 TOOL CALL 1 Y S100\n5 L X+1 Y+0 Z+0 B+30 F100")
    for shortcuts in (True, False):  # a plain line too, which the shortcut for plain blocks would take
        with pytest.raises(GCodeError, match=r"t\.h:7:1: a line under M128 with tool axis Y is not supported"):
            parse_heidenhain(HEAD + "3 L B+30 FMAX\n4 M128\n5 TOOL CALL 1 Y S100\n6 L X+1 F100\nEND PGM T MM\n",
                             source="t.h", context=TNC, shortcuts=shortcuts)


def test_a_tool_direction_turns_the_rotary_axes_the_short_way():
    # Fanuc 15i B-63323EN-1/03, 10.4.10, type 2, note 4: the rotary axes move by a shortcut, never more than 180
    # deg. From C+170 the direction (sin 30 cos 190, sin 30 sin 190, cos 30) is A+30 C+190 (it was C-170: -340 deg)
    i, j = 0.5 * np.sin(np.radians(190.0)), -0.5 * np.cos(np.radians(190.0))
    prog = iso(f"G21 G90 G54\nG0 A30. C170.\nG0 G43.5 H1 X0 Y0 Z0\nG1 X10. I{i:.7f} J{j:.7f} K0.8660254 F600.\nG49\n"
               "M30\n")
    assert [b for b in prog.blocks if b.line == 4][-1].extra_target[[0, 2]] == pytest.approx([30.0, 190.0], abs=1e-5)
    # LN .. TX TY TZ under M128 likewise (our reading): from C+170 to C+190 with B+30
    tx, ty = 0.5 * np.cos(np.radians(190.0)), 0.5 * np.sin(np.radians(190.0))
    prog = tnc(f"3 L B+30 C+170 FMAX\n4 M128\n"
               f"5 LN X+10 Y+0 Z+0 NX+0 NY+0 NZ+1 TX{tx:+.7f} TY{ty:+.7f} TZ+0.8660254 F600")
    assert [b for b in prog.blocks if b.number == 5][-1].extra_target[1:3] == pytest.approx([30.0, 190.0], abs=1e-5)


def test_m129_with_m128_in_one_block_ends_tcpm():
    # M128 acts at the block's start, M129 at its end (TNC 426/430 ISO manual, M128), in either order: after
    # 'M129 M128' the line is a machine line, as after M129
    both = tnc("3 L B+30 FMAX\n4 M128\n5 M129 M128\n6 L X+10 Y+0 Z+0 F100")
    after = tnc("3 L B+30 FMAX\n4 M128\n5 M129\n6 L X+10 Y+0 Z+0 F100")
    assert after.blocks[-1].target == pytest.approx([20.0, 5.0, 20.0])
    assert both.blocks[-1].target == pytest.approx([20.0, 5.0, 20.0])
