"""LinuxCNC's predefined named parameters of the machine's switches and version (lcparams39): each expected value is
the one rs274 2.9.0~pre1 (the Debian 12 linuxcnc-uspace) prints for the same program, "(DEBUG, #<_spindle_on> ..)"
or the canonical moves of ``rs274 -g``. Before, each was refused as "read before it is set"."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])

#: M3/M4/M5, M7/M8/M9, M48-M53 and M6 read back as digits of one number (spindle on 1, clockwise 10, mist 100,
#: flood 1000; speed override 1, feed override 10, adaptive feed 100, feed hold 1000).
SWITCHES = """G21 G0 X0
#1 = [#<_spindle_on> * 1 + #<_spindle_cw> * 10 + #<_mist> * 100 + #<_flood> * 1000]
#2 = [#<_speed_override> + #<_feed_override> * 10 + #<_adaptive_feed> * 100 + #<_feed_hold> * 1000]
S1000 M3
#3 = [#<_spindle_on> * 1 + #<_spindle_cw> * 10]
M4 M7
#4 = [#<_spindle_on> * 1 + #<_spindle_cw> * 10 + #<_mist> * 100 + #<_flood> * 1000]
M8
#5 = [#<_mist> * 100 + #<_flood> * 1000]
M9
#6 = [#<_mist> * 100 + #<_flood> * 1000]
M3
M5
#7 = [#<_spindle_on> * 1 + #<_spindle_cw> * 10]
M49
#8 = [#<_speed_override> + #<_feed_override> * 10]
M50
#9 = [#<_speed_override> + #<_feed_override> * 10]
M51 P1
M50 P0
M52 P1
M53 P0
#10 = [#<_speed_override> + #<_feed_override> * 10 + #<_adaptive_feed> * 100 + #<_feed_hold> * 1000]
M3 M8 T1 M6
#11 = [#<_spindle_on> + #<_flood> * 10]
M3
T1 M6
#12 = [#<_spindle_on> + #<_vmajor> * 10 + #<_vminor> * 100]
G0 X#1 Y#2 Z#3
G0 X#4 Y#5 Z#6
G0 X#7 Y#8 Z#9
G0 X#10 Y#11 Z#12
M2
"""


def test_the_spindle_coolant_and_override_switches():
    # rs274 -g: STRAIGHT_TRAVERSE(0, 1011, 11), (101, 1100, 0), (0, 0, 10), (101, 11, 29): the power-on switches
    # 0 and 1011, M3 on clockwise, M4 M7 counterclockwise with mist, M8 both coolants, M9 none, M5 off, M49 both
    # overrides off, M50 feed override on, M51 P1 M50 P0 M52 P1 M53 P0; "M3 M8 T1 M6" turns (M6 runs before M3),
    # "T1 M6" stops it; version 2.9 and 0
    prog = parse_program(SWITCHES, context=LINUXCNC)
    got = [v for b in prog.blocks[-4:] for v in b.target.tolist()]
    assert got == pytest.approx([0, 1011, 11, 101, 1100, 0, 0, 0, 10, 101, 11, 29])


def test_m72_restores_the_spindle_and_the_coolant():
    # rs274 -g: after "M4 M7 .. M70 .. M5 M9 .. M72" START_SPINDLE_COUNTERCLOCKWISE, MIST_ON and
    # STRAIGHT_TRAVERSE(101, 0, 0): spindle on, counterclockwise, mist on
    text = "G21\nM4 M7\nM70\nM5 M9\nM72\nG0 X[#<_spindle_on> + #<_spindle_cw> * 10 + #<_mist> * 100]\nM2\n"
    prog = parse_program(text, context=LINUXCNC)
    assert prog.blocks[-1].target.tolist() == pytest.approx([101, 0, 0])


def test_the_metric_machine_is_the_machines_linear_unit():
    # interp_namedparams.cc inicheck: [TRAJ] LINEAR_UNITS inch 0, else 1 (rs274 with INI_FILE_NAME naming an INI of
    # "LINEAR_UNITS = inch" prints 0; without that entry -1)
    text = "G21\nG0 X[#<_metric_machine> + 1]\nM2\n"
    assert parse_program(text, context=LINUXCNC).blocks[-1].target[0] == pytest.approx(2.0)
    inch = MachineContext(dialect=DIALECTS["linuxcnc"], linear_units="inch")
    assert parse_program(text, context=inch).blocks[-1].target[0] == pytest.approx(1.0)
    with pytest.raises(GCodeError, match=r"#<_metric_machine> is read-only"):
        parse_program("G21\n#<_metric_machine> = 1\nM2\n", context=LINUXCNC)


def test_a_pocket_is_the_machines_and_named_as_such():
    # rs274 reads the tool table's P column (T3 P5: "#<_selected_pocket>" 5 after T3); vcnc models no pockets
    with pytest.raises(GCodeError, match=r":2:\d+: named parameter #<_selected_pocket>: the tool changer's pocket"):
        parse_program("G21 T3\n#1 = #<_selected_pocket>\nM2\n", context=LINUXCNC)
    with pytest.raises(GCodeError, match=r"#<_current_pocket> is read-only"):
        parse_program("G21\n#<_current_pocket> = 1\nM2\n", context=LINUXCNC)


#: A program writes the work offsets #5221 .. #5390 (Probe Basic's and sttts' tool-change subroutines save and restore
#: "#5381 = #<_G59_3_X>"): before, "parameter #5241 is read-only".
OFFSET_WRITES = """G21 G0 X0
#5241 = 10
#5242 = 20
#5221 = 3
#1 = #5221
G55 G0 X0 Y0
G0 X[#1]
G54 X1
#5221 = 1
G0 X0
G10 L2 P2 Y0
G0 X0
G55 X0
G54 X0
#5230 = 90
G55 X0
G54 X1
M2
"""


def test_a_written_work_offset_is_taken_when_another_system_is_selected():
    # rs274 -g on an inch machine (linear_units inch, as rs274's standalone tables): SET_G5X_OFFSET(2, 254, 508) at
    # G55, "#5221 = 3" read back at once (X 3) but not taken by G54 in force; G54 takes 76.2 = 3 in; "#5221 = 1"
    # waits; "G10 L2 P2 Y0" leaves G54; the next G54 takes 25.4 and "#5230 = 90" turns it at its selection
    # (rs274 prints program points: G54 X1 under the 90 deg turn is (1, -228.6), machine (254, 1));
    # benchmarks/linuxcnc_diff.py: "match, 8 moves"
    inch = MachineContext(dialect=DIALECTS["linuxcnc"], linear_units="inch")
    prog = parse_program(OFFSET_WRITES, context=inch)
    xy = [v for b in prog.blocks for v in b.target[:2].tolist()]
    assert xy == pytest.approx([0, 0, 254, 508, 257, 508, 77.2, 508, 76.2, 508, 76.2, 508, 254, 508, 25.4, 508,
                                254, 508, 254, 1])


def test_a_tool_g10_leaves_a_written_work_offset_pending():
    # rs274 2.9.0~pre1 (benchmarks/linuxcnc_diff.py on this program: match): "#5221 = 10" writes G54's X while G54 is
    # in force; G10 L1 P1 sets tool 1 (P a tool number, convert_setup_tool), not the system, so the next move still
    # uses the old X offset, and only re-selecting G54 after G55 takes the write. vcnc took it at the G10 L1.
    text = "G21 G90 G54\nG0 X0 Y0 Z0\n#5221 = 10\nG10 L1 P1 R1 Z5\nG0 X1\nG55\nG54\nG0 X2\nM2\n"
    prog = parse_program(text, context=MachineContext(dialect=DIALECTS["linuxcnc"], linear_units="mm"),
                         source="t.ngc")
    xs = [round(float(b.target[0]), 6) for b in prog.blocks]
    assert xs[-2:] == [1.0, 12.0]
