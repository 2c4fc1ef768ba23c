"""Review of session 26's work: defects found by hand, each with the program that showed it."""

from __future__ import annotations

import math

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext, Tool, read_tool_table
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError, InputError

# a tool table may hold T-ANGLE 180 (a flat end); it was refused as a whole ('point angle must lie in (0, 180)')
FLAT = MachineContext(tools={4: Tool(number=4, radius=4.0, point_angle=180.0)})
DRILL = ("0 BEGIN PGM T MM\n1 TOOL CALL 4 Z S3000\n2 L X+0 Y+0 Z+100 R0 FMAX\n3 CYCL DEF 200 DRILLING ~\n Q200=2 ~\n"
         " Q201=-15 ~\n Q206=250 ~\n Q202=20 ~\n Q210=0 ~\n Q203=+0 ~\n Q204=50 ~\n Q211=0 ~\n Q395={ref}\n"
         "4 L X+10 Y+10 R0 FMAX M99\nEND PGM T MM\n")
CENTER = ("0 BEGIN PGM T MM\n1 TOOL CALL 4 Z S3000\n2 L X+0 Y+0 Z+100 R0 FMAX\n3 CYCL DEF 240 CENTERING ~\n"
          " Q200=2 ~\n Q343=1 ~\n Q201=+0 ~\n Q344=-9 ~\n Q206=250 ~\n Q211=0 ~\n Q203=+20 ~\n Q204=100\n"
          "4 L X+30 Y+20 R0 FMAX M99\nEND PGM T MM\n")


def test_a_tool_table_may_hold_a_flat_point_angle(tmp_path):
    path = tmp_path / "tool.t"
    path.write_text("BEGIN TOOL     .T     MM\nT    NAME             L           R           T-ANGLE\n"
                    "4    MILL_D8          +80         +4          +180\n[END]\n")
    assert read_tool_table(str(path))[4].point_angle == 180.0


def test_depth_to_the_full_diameter_of_a_flat_end_is_the_depth():
    # Q395=1 with a flat end (T-ANGLE 180): the full diameter is at the tip, the hole as deep as with Q395=0
    deepest = [min(float(b.target[2]) for b in checked_program(DRILL.format(ref=ref), FLAT).blocks) for ref in (0, 1)]
    assert deepest == [-15.0, -15.0]


def test_centering_to_a_diameter_with_a_flat_end_is_an_error():
    with pytest.raises(GCodeError, match=r"cycle 240: Q343=1 \(centering to the diameter Q344\) needs a pointed tool, "
                                         r"and the called tool's point angle is 180 deg"):
        checked_program(CENTER, FLAT, check=False)
    pointed = MachineContext(tools={4: Tool(number=4, radius=4.0, point_angle=90.0)})
    assert min(float(b.target[2]) for b in checked_program(CENTER, pointed).blocks) == pytest.approx(
        20 - 4.5 / math.tan(math.radians(45)))


def test_g43_2_h0_adds_the_loaded_tools_offsets_under_linuxcnc():
    # rs274 2.9.0~pre1 with T5 Z2.5 and T7 Z1.0 (inch) in its tool table: 'T5 M6 / G43 H7 / G43.2 H0' offsets Z by
    # 88.9 mm, T7's and T5's lengths (find_tool_index: H0 is the spindle's tool), as G43 H0 takes T5's; it added 0
    tools = {5: Tool(number=5, length=2.5), 7: Tool(number=7, length=1.0)}
    text = "G21 G90\nT5 M6\nG43 H7\nG43.2 H0\nG0 X0 Y0 Z10\nM2\n"
    prog = checked_iso(text, MachineContext(tools=tools).with_dialect("linuxcnc"))
    assert [float(v) for v in prog.blocks[-1].target] == [0.0, 0.0, 13.5]


def test_g43_h0_note_names_the_h_word_the_program_wrote():
    # 'T5 M6 / G43 H0' with T5 not in the table: the note named 'H5', a word the program does not hold
    linuxcnc = MachineContext().with_dialect("linuxcnc")
    notes = parse_program("G21 G90\nT5 M6\nG43 H0\nG0 Z10\nM2\n", context=linuxcnc).notes
    assert "H0 (the loaded tool T5) not in the tool table (length 0)" in notes
    assert not [n for n in notes if n.startswith("H5")]


# a machining cycle is call-active: CYCL DEF 200 with Q395=1 before the TOOL CALL of the drill whose point angle it
# takes was refused at the definition ('the called tool has none')
DEFINED_FIRST = ("0 BEGIN PGM T MM\n1 CYCL DEF 200 DRILLING ~\n Q200=2 ~\n Q201=-15 ~\n Q206=250 ~\n Q202=20 ~\n"
                 " Q210=0 ~\n Q203=+0 ~\n Q204=50 ~\n Q211=0 ~\n Q395=1\n2 TOOL CALL {t} Z S3000\n"
                 "3 L X+0 Y+0 Z+100 R0 FMAX\n4 L X+10 Y+10 R0 FMAX M99\nEND PGM T MM\n")
DRILLS = MachineContext(tools={2: Tool(number=2, radius=3.0, point_angle=118.0), 3: Tool(number=3, radius=3.0)})


def test_a_cycle_defined_before_the_tool_call_takes_the_called_tools_point_angle():
    prog = checked_program(DEFINED_FIRST.format(t=2), DRILLS)
    assert min(float(b.target[2]) for b in prog.blocks) == pytest.approx(-15 - 3 / math.tan(math.radians(59)))
    with pytest.raises(GCodeError, match=r"t.h:14:3: cycle 200: Q395=1 \(depth to the full diameter\) needs the tool's "
                                         r"point angle, and the called tool has none \(got '4 L X\+10"):
        checked_program(DEFINED_FIRST.format(t=3), DRILLS, check=False)


# an SL contour that ends away from its first point is closed by a line back to it (b6dce84); the closing was silent,
# so a contour left open by a mistake ran as a different pocket without a word
POCKET = ("0 BEGIN PGM T MM\n1 TOOL DEF 1 L+0 R+3\n2 TOOL CALL 1 Z S2000\n3 L X+0 Y+0 Z+50 R0 FMAX\n"
          "4 CYCL DEF 14.0 CONTOUR\n5 CYCL DEF 14.1 CONTOUR LABEL1\n6 CYCL DEF 20 CONTOUR DATA ~\n Q1=-5 ~\n Q2=1 ~\n"
          " Q3=+0 ~\n Q4=+0 ~\n Q5=+0 ~\n Q6=2 ~\n Q7=+50 ~\n Q8=0 ~\n Q9=+1\n7 CYCL DEF 22 ROUGH-OUT ~\n Q10=5 ~\n"
          " Q11=100 ~\n Q12=350 ~\n Q18=0 ~\n Q19=150\n8 CYCL CALL M3\n9 L Z+50 R0 FMAX M2\n10 LBL 1\n"
          "11 L X+0 Y+0 RL\n12 L X+40\n13 L Y+32\n14 L X+0\n{close}15 LBL 0\nEND PGM T MM\n")


def test_an_sl_contour_closed_by_the_reader_is_noted():
    note = "SL contour LBL 1 (cycle 14) ends away from its first point: closed by a line back to it"
    short = checked_program(POCKET.format(close=""), MachineContext(), exact=False)
    closed = checked_program(POCKET.format(close="14 L Y+0\n"), MachineContext(), exact=False)
    assert note in short.notes and note not in closed.notes
    assert [b.target.tolist() for b in short.blocks] == [b.target.tolist() for b in closed.blocks]


def test_a_tool_tables_point_angle_out_of_range_names_the_file_and_line(tmp_path):
    path = tmp_path / "tool.t"
    path.write_text("BEGIN TOOL     .T     MM\nT    NAME             L           R           T-ANGLE\n"
                    "2    DRILL_D6         +120        +3          +200\n[END]\n")
    with pytest.raises(InputError, match=r"tool.t:3: tool 2: point angle must lie in \[0, 180\] \[deg\] \(0: none\), "
                                         r"got 200.0"):
        read_tool_table(str(path))


def test_a_while_label_opened_twice_is_noted_and_do_loops_are_not():
    # rs274 2.9.0~pre1 refuses the second 'o100 while' ("duplicate O-word label") and runs two 'o100 do' loops, each
    # closed by its 'o100 while'; the note knew if and repeat only
    loop = "#1=0\no100 {open}\nG0 X#1\n#1=[#1+1]\no100 {close}\n"
    whiles = "G21 G90\n" + 2 * loop.format(open="while [#1 LT 2]", close="endwhile") + "M2\n"
    dos = "G21 G90\n" + 2 * loop.format(open="do", close="while [#1 LT 2]") + "M2\n"
    linuxcnc = MachineContext().with_dialect("linuxcnc")
    notes = parse_program(whiles, context=linuxcnc).notes
    assert any(n.startswith("O-word label o100 opens 2 while blocks") for n in notes)
    prog = parse_program(dos, context=linuxcnc)
    assert not [n for n in prog.notes if n.startswith("O-word label")] and len(prog.blocks) == 4
