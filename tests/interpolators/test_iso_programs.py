"""Hand-written ISO programs for each feature of the reader, with the end points LinuxCNC's
G-code reference gives (https://linuxcnc.org/docs/html/gcode/g-code.html, o-code.html,
overview.html), written out."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pytest

from interpolators import iso_flow, parse_program
from interpolators.context import DIALECTS, MachineContext, Tool, read_tool_table
from interpolators.iso_cycles import RAPID_DELTA_INCH
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError, InputError

CTX = MachineContext(
    work_offsets={"G54": (100.0, 50.0, -20.0), "G55": (200.0, 0.0, 0.0)},
    tools={1: Tool(number=1, length=12.5, radius=0.0), 2: Tool(number=2, length=-3.0, radius=3.0)},
    home=(0.0, 0.0, 100.0), reference2=(10.0, 20.0, 90.0),
)


def ends(text: str, context: MachineContext = CTX, *, kinds: bool = False):
    prog = parse_program(text, context=context)
    pts = [b.target.tolist() for b in prog.blocks if b.kind != "dwell"]
    return (pts, [b.kind for b in prog.blocks]) if kinds else pts


def test_program_starts_at_home_and_work_offsets_apply():
    prog = parse_program("G21 G90\nG0 X1 Y2 Z3\nG55 X1\nG54\nG91 X1\n", context=CTX)
    assert prog.blocks[0].start.tolist() == [0, 0, 100]
    assert [b.target.tolist() for b in prog.blocks] == [[101, 52, -17], [201, 52, -17], [202, 52, -17]]


def test_tool_length_g43_h_and_current_tool_g49():
    # G43 with H1 adds 12.5 mm along Z; G43 without H takes the tool of the last M6; G49 cancels
    pts = ends("G21 G90 G54\nT1 M6\nG43 H1 G0 Z10\nG49 G0 Z10\nT2 M6\nG43\nG0 Z10\nG44 H1 Z10\n")
    assert [p[2] for p in pts] == [2.5, -10.0, -13.0, -22.5]


def test_g28_through_the_intermediate_point_and_g30():
    pts = ends("G21 G90 G54 G0 X0 Y0 Z0\nG28 Z5\nG30\n")
    # intermediate Z5 (program) = -15 machine, then only Z goes home (100); G30: all axes
    assert pts == [[100, 50, -20], [100, 50, -15], [100, 50, 100], [10, 20, 90]]


def test_g28_incremental_zero_is_the_fanuc_idiom():
    assert ends("G21 G90 G54 G0 X1 Y1 Z1\nG91 G28 Z0\n")[-2:] == [[101, 51, -19], [101, 51, 100]]


def test_g53_machine_coordinates_for_one_block():
    assert ends("G21 G90 G54 G0 X0\nG53 G0 Z-5\nX1\n") == [[100, 0, 100], [100, 0, -5], [101, 0, -5]]


def test_g92_offsets_and_g92_1():
    pts = ends("G21 G90 G54\nG0 X10 Y0 Z0\nG92 X0\nG0 X5\nG92.1\nG0 X5\n")
    assert [p[0] for p in pts] == [110, 115, 105]


def test_g10_l2_and_l20_set_work_offsets():
    pts = ends("G21 G90\nG10 L2 P2 X7 Y8 Z9\nG55 G0 X0 Y0 Z0\nG10 L20 P2 X1\nG0 X1\n")
    assert pts == [[7, 8, 9], [7, 8, 9]]



def test_g10_r_rotates_the_coordinate_system_about_its_origin():
    """LinuxCNC G10 L2 R: program X Y (plus G92) are rotated about the work offset's origin
    (emccanon.cc rotate_and_offset_pos); G91 steps and arc centres are in the rotated system. With
    G54 at (10, 0) turned 90 degrees, program (1, 0) is machine (10, 1), G91 X1 moves along machine
    +Y, and a clockwise arc about program (0, 0) turns about machine (10, 0); a G18/G19 arc, which
    then lies in no axis plane, runs as chords within 1 um. G92 takes its offset in the rotated
    system (LinuxCNC convert_axis_offsets: offset = current + offset - value; tests/interp/g10/
    g10-with-g92). Drilling cycles run in the rotated program coordinates (test_linuxcnc_fuzz)."""
    prog = parse_program("G21 G90 F100\nG10 L2 P1 X10 R90\nG0 X1 Y0\nG91 G1 X1\nG90 G2 X0 Y-2 I-2 J0\n",
                         context=MachineContext())
    assert [np.round(b.target, 12).tolist() for b in prog.blocks] == [[10, 1, 0], [10, 2, 0], [12, 0, 0]]
    assert np.allclose(prog.blocks[-1].segment.center, [10, 0, 0]) and not prog.blocks[-1].segment.ccw
    assert ends("G21 G90\nG10 L2 P1 X1 R0\nG54 G0 X0\n", MachineContext()) == [[1, 0, 0]]
    # G92 X0 at program (1, 0): offset (1, 0); program (1, 0) is then (2, 0) turned 90 degrees, plus (10, 0)
    pts = ends("G21 G90\nG10 L2 P1 X10 R90\nG0 X1 Y0\nG92 X0 Y0\nG0 X1 Y0\n", MachineContext())
    assert np.round(pts[-1], 12).tolist() == [10, 2, 0]
    # a G19 half circle about program (0, 0, 1) turned 90 degrees lies in the machine XZ plane: chords
    # whose ends are on that circle and whose middles are within 1 um of it
    prog = parse_program("G21 G90 F100\nG10 L2 P1 R90\nG0 X0 Y0 Z0\nG19 G2 Y0 Z2 K1\n", context=MachineContext())
    pts = np.array([b.target for b in prog.blocks[1:]])
    assert len(pts) == math.ceil(math.pi / (2 * math.acos(1 - 0.001)))  # chords of 1 um sagitta on R1
    assert pts[-1].tolist() == [0, 0, 2] and np.all(np.abs(pts[:, 1]) < 1e-12)
    assert np.allclose(np.hypot(pts[:, 0], pts[:, 2] - 1.0), 1.0, atol=1e-12)
    mid = (np.vstack([[0, 0, 0], pts[:-1]]) + pts) / 2
    assert np.all(1.0 - np.hypot(mid[:, 0], mid[:, 2] - 1.0) <= 0.001)
    for text, message in [("G21\nG10 L20 P1 X0 R30\n", "R not allowed in G10 L20")]:
        with pytest.raises(GCodeError, match=message):
            parse_program(text, context=MachineContext())
    # G10 L20 in a system turned 45 degrees (tests/interp/g10/g10-l20-while-active): at machine (0, 0),
    # L20 X-1 makes the position read X-1, so program X0 is one unit along the rotated X axis
    pts = ends("G21 G90 F60\nG10 L2 P1 R45\nG53 G0 X0 Y0\nG10 L20 P1 X-1\nG1 X0\nG10 L20 P1 X1 Y1\nG1 X0 Y0\n",
               MachineContext())
    # then L20 X1 Y1 there: X0 Y0 is (-1, -1) along the rotated axes, machine (h, h) + (0, -2h)
    h = math.sqrt(0.5)
    assert np.allclose(pts[1:], [[h, h, 0], [h, -h, 0]])


def test_words_without_motion_are_noted_not_refused():
    prog = parse_program("%\nO0100 (demo)\nN10 G17 G40 G49 G80 G90 G94\nT1 M6\nS2000 M3\nM8\nG0\nG1 F300\n"
                         "X1\nM1\nM5 M9\nM30\n%\n", context=CTX)
    assert prog.name == "O100"
    assert [b.kind for b in prog.blocks] == ["line"]
    notes = " ".join(prog.notes)
    for what in ("T/M6 tool change", "S/M3-M5 spindle", "M7-M9 coolant", "M0/M1 program stop",
                 "no G20/G21: mm assumed"):
        assert what in notes, notes


def test_motion_word_alone_sets_the_mode():
    pts, kinds = ends("G21 G0 G90\nX1\nG1 F100\nY1\n", MachineContext(), kinds=True)
    assert pts == [[1, 0, 0], [1, 1, 0]] and kinds == ["rapid", "line"]


def test_arc_centre_modes_and_zero_out_of_plane_words():
    inc = ends("G21 G90 G0 X10 Y0\nG17 G91.1 G3 X0 Y10 I-10 J0 K0 F100\n", MachineContext())
    absolute = ends("G21 G90 G0 X10 Y0\nG17 G90.1 G3 X0 Y10 I0 J0 F100\n", MachineContext())
    assert inc == absolute == [[10, 0, 0], [0, 10, 0]]
    with pytest.raises(GCodeError, match="outside the arc plane"):
        parse_program("G21 G17 G3 X0 Y10 I-10 K1 F100\n")


def test_arc_end_radius_within_linuxcnc_tolerance_is_accepted():
    # inch program, 4 decimals: end radius off by 0.0001 in (FreeCAD/Fusion output)
    prog = parse_program("G20 G90 G0 X1 Y0\nG3 X0 Y1.0001 I-1 J0 F10\n")
    arc = prog.blocks[1].segment
    assert np.allclose(arc.end, [0, 1.0001 * 25.4, 0])
    with pytest.raises(GCodeError, match="tolerance"):
        parse_program("G21 G90 G0 X10 Y0\nG3 X0 Y10.05 I-10 J0 F10\n")


def test_g81_returns_to_initial_level_under_g98_and_to_r_under_g99():
    g98 = ends("G21 G90 G0 X0 Y0 Z10\nG98 G81 X1 Y1 Z-2 R2 F120\nX2\nG80\n", MachineContext())
    assert g98 == [[0, 0, 10], [1, 1, 10], [1, 1, 2], [1, 1, -2], [1, 1, 10], [2, 1, 10], [2, 1, 2], [2, 1, -2],
                   [2, 1, 10]]
    g99 = ends("G21 G90 G0 X0 Y0 Z10\nG99 G81 X1 Y1 Z-2 R2 F120\nX2\n", MachineContext())
    assert g99[3:] == [[1, 1, -2], [1, 1, 2], [2, 1, 2], [2, 1, -2], [2, 1, 2]]


def test_g83_pecks_retract_to_r_and_g73_breaks_chips():
    d = RAPID_DELTA_INCH * 25.4
    g83 = ends("G21 G90 G0 X0 Y0 Z5\nG98 G83 X0 Y0 Z-2.5 R1 Q1 F60\n", MachineContext())
    zs = [p[2] for p in g83[1:]]
    assert zs == pytest.approx([1, 0, 1, d, -1, 1, -1 + d, -2, 1, -2 + d, -2.5, 5])
    g73 = ends("G21 G90 G0 X0 Y0 Z5\nG99 G73 X0 Y0 Z-2.5 R1 Q1 F60\n", MachineContext())
    assert [p[2] for p in g73[1:]] == pytest.approx([1, 0, d, -1, -1 + d, -2, -2 + d, -2.5, 1])


def test_g82_dwell_and_g85_feed_out():
    prog = parse_program("G21 G90 G0 X0 Y0 Z5\nG99 G82 X1 Z-1 R1 P0.5 F60\nG85 X2 Z-1 R1 F60\n")
    kinds = [(b.kind, round(b.dwell, 3)) for b in prog.blocks]
    assert ("dwell", 0.5) in kinds
    last = prog.blocks[-2:]
    assert last[0].kind == "line" and last[0].target.tolist() == [2, 0, -1]
    assert last[1].kind == "line" and last[1].target.tolist() == [2, 0, 1]  # feeds out to R


def test_incremental_cycle_with_repeats():
    # G91: R from the start Z, Z from R, X/Y step per repeat (LinuxCNC G81 example with L)
    pts = ends("G21 G90 G0 X0 Y0 Z5\nG91 G98 G81 X2 Y0 R-4 Z-3 L3 F60\n", MachineContext())
    holes = [p for p in pts if p[2] == -2]
    assert holes == [[2, 0, -2], [4, 0, -2], [6, 0, -2]]
    assert pts[-1] == [6, 0, 5]


def test_cycle_errors_name_the_cycle():
    with pytest.raises(GCodeError, match="G83 peck drilling cycle: peck depth Q"):
        parse_program("G21 G90 G0 Z5\nG83 X0 Y0 Z-1 R1 F10\n")
    with pytest.raises(GCodeError, match="G81 drilling cycle: no R"):
        parse_program("G21 G90 G0 Z5\nG81 X0 Y0 Z-1 F10\n")


def test_fanuc_g80_restores_the_motion_mode():
    assert ends("G21 G90 G1 F100 X0 Y0 Z5\nG81 X1 R1 Z-1\nG80\nX3\n",
                MachineContext(dialect=DIALECTS["fanuc"]))[-1] == [3, 0, 5]  # G98 at power-on (LinuxCNC: G99)


def test_parameters_and_expressions():
    text = ("G21 G90\n#1 = 2\n#<r> = [#1 * 3 + 1]\nG1 F100 X#<r> Y[SIN[30] * 4] Z[2 ** 3 - 7 MOD 3]\n"
            "#2 = [ATAN[1]/[1]]\nX#2 #2 = 100\nY#2\n#3 = [FIX[-1.5] + FUP[1.2] + ROUND[2.5] + ABS[-1] + SQRT[16]]\n"
            "Z#3\nX[[1 LT 2] AND [3 GE 3]]\n")
    pts = ends(text, MachineContext())
    assert pts[0] == pytest.approx([7, 2, 7])
    assert pts[1][0] == pytest.approx(45.0)  # the line's assignment takes effect after the line
    assert pts[2][1] == pytest.approx(100.0)
    assert pts[3][2] == pytest.approx(-2 + 2 + 3 + 1 + 4)
    assert pts[4][0] == 1.0


def test_o_word_subroutine_loops_and_conditions():
    text = """G21 G90 G1 F100
o<side> sub
  G91 X#1
  o<side> return
  X999
o<side> endsub
#<i> = 0
o10 while [#<i> LT 3]
  o<side> call [2]
  #<i> = [#<i> + 1]
  o11 if [#<i> EQ 2]
    o10 break
  o11 endif
o10 endwhile
o20 repeat [2]
  o<side> call [0.5]
o20 endrepeat
o30 do
  o<side> call [-1]
o30 while [0]
o40 if [0]
  X100
o40 elseif [1]
  X0.25
o40 else
  X200
o40 endif
M30
"""
    xs = [p[0] for p in ends(text, MachineContext())]
    assert xs == pytest.approx([2, 4, 4.5, 5, 4, 4.25])


def test_fanuc_m98_subprogram_with_repeats_and_m99():
    text = "%\nO1000\nG21 G91 G1 F100\nM98 P2000 L3\nX10\nM30\nO2000\nY1\nM99\n%\n"
    pts = ends(text, MachineContext())
    assert pts == [[0, 1, 0], [0, 2, 0], [0, 3, 0], [10, 3, 0]]


def test_flow_errors():
    with pytest.raises(GCodeError, match="neither in this file nor in elsewhere.ngc"):
        parse_program("o<elsewhere> call\n")
    with pytest.raises(GCodeError, match="no matching endwhile"):
        parse_program("o1 while [1]\nG0 X1\n")
    with pytest.raises(GCodeError, match="endless loop"):
        list(iso_flow.run("G21 G0 X0\no1 while [1]\nG4 P0\no1 endwhile\n", max_lines=10_000))
    with pytest.raises(GCodeError, match="division by zero"):
        parse_program("#1 = [1 / 0]\n")
    with pytest.raises(GCodeError, match="read before it is set"):
        parse_program("G0 X#<nothing>\n")
    with pytest.raises(GCodeError, match="#5061: the probe result"):
        parse_program("G0 X#5061\n")
    with pytest.raises(GCodeError, match="#5420 is read-only"):
        parse_program("#5420 = 1\n")


def test_dialect_dwell_unit_and_default_path_mode():
    linuxcnc = parse_program("G21 G4 P2\n").blocks[0].dwell
    fanuc = parse_program("G21 G4 P2000\n", context=MachineContext(dialect=DIALECTS["fanuc"])).blocks[0].dwell
    assert linuxcnc == fanuc == 2.0
    assert parse_program("G21 G1 X1 F100\n").blocks[0].exact_stop is False  # continuous path by default
    stop = MachineContext(dialect=DIALECTS["linuxcnc"].__class__(name="x", continuous_path=False))
    assert parse_program("G21 G1 X1 F100\n", context=stop).blocks[0].exact_stop is True
    inch = MachineContext(dialect=DIALECTS["haas"].__class__(name="haas", dwell_p_unit="ms", default_units="inch"))
    prog = parse_program("G1 X1 F10\n", context=inch)
    assert prog.blocks[0].target[0] == 25.4 and any("inch assumed" in n for n in prog.notes)


def test_unsupported_features_are_named():
    for text, feature in (("G38.2 Z-5 F10\n", "G38 probing"), ("G76 P1 Z-1\n", "G76 threading"),
                          ("G7\n", "lathe diameter mode"), ("G0 A10\n", "no rotary axis A"),
                          ("M101\n", "user M code")):
        with pytest.raises(GCodeError, match=feature):
            parse_program(text)


def test_cutter_compensation_with_radius_zero_keeps_the_path():
    assert ends("G21 G90 G41 G1 X10 F100\nG40 X0\n", MachineContext()) == [[10, 0, 0], [0, 0, 0]]


def test_cutter_compensation_inside_a_square_with_d_from_the_tool_table():
    # G41 (left of travel) on a counter-clockwise square: the tool runs inside, 3 mm (tool 2) off
    # each side; inside corners are intersections; the entry ends 3 mm left of the entry move,
    # then an arc about the programmed corner turns onto the first side (LinuxCNC entry rule)
    prog = parse_program("G21 G90 G17 G0 X-5 Y-5 Z0\nT2 M6\nG41 D2 G1 X0 Y0 F100\nX20\nY20\nX0\nY0\n"
                         "G40 G0 X-5 Y-5\n", context=MachineContext(tools={2: Tool(number=2, radius=3.0)}))
    pts = [np.round(b.target[:2], 9).tolist() for b in prog.blocks]
    s = round(3 / math.sqrt(2), 9)
    assert pts == [[-5, -5], [-s, s], [0, 3], [17, 3], [17, 17], [3, 17], [3, 0], [-5, -5]]
    arc = prog.blocks[2].segment
    assert arc.center.tolist()[:2] == [0, 0] and arc.radius == pytest.approx(3.0)
    with pytest.raises(GCodeError, match="G41 cutter radius compensation"):
        parse_program("G21 G90 G0 X-5 Y0\nG41 D2 G1 X0 Y0 F100\nX20\nY1\nX0\nG40 X-5\n",
                      context=MachineContext(tools={2: Tool(number=2, radius=3.0)}))


def test_linuxcnc_tool_table(tmp_path):
    f = tmp_path / "tool.tbl"
    f.write_text("T1 P1 D6.0 Z+12.5 ;end mill\n\n;comment only\nT2 P2 Z-1 D0.5\n")
    tools = read_tool_table(str(f))
    assert tools[1] == Tool(number=1, length=12.5, radius=3.0, comment="end mill")
    assert tools[2].radius == 0.25 and tools[2].length == -1.0
    f.write_text("P1 D6\n")
    with pytest.raises(InputError, match=r"tool\.tbl:1: tool-table line without a T word"):
        read_tool_table(str(f))


def test_helix_and_full_circle_with_offsets():
    prog = parse_program("G21 G90 G54 G0 X10 Y0 Z0\nG3 I-10 Z-1 F100\n", context=CTX)
    arc = prog.blocks[1].segment
    assert arc.center.tolist()[:2] == [100, 50] and math.isclose(arc.sweep, 2 * math.pi)


def test_a_rotary_word_that_keeps_the_axis_at_zero_is_noted():
    prog = parse_program("G21 G90 G0 X1 A0\nG1 X2 B0 F100\n")
    assert [b.target[0] for b in prog.blocks] == [1, 2]
    assert "A0 (rotary axis A stays at 0)" in prog.notes and "B0 (rotary axis B stays at 0)" in prog.notes


def test_polar_coordinates_absolute_incremental_and_in_cycles():
    """LinuxCNC G-code overview, "Polar Coordinates" (and interp_find.cc): G90 @ ^ about the
    program origin; G91 adds @ to the distance and ^ to the angle; cycles repeat the increments."""
    ctx = MachineContext()
    square = ends("G21 G90 F100\nG1 @10 ^90\nG91 ^90\n^90\n^90\n", ctx)
    np.testing.assert_allclose(square, [[0, 10, 0], [-10, 0, 0], [0, -10, 0], [10, 0, 0]], atol=1e-12)
    spiral = ends("G21 G90 F100\nG1 X10 Y0\nG91 @.5 ^90\n", ctx)
    np.testing.assert_allclose(spiral[-1], [0, 10.5, 0], atol=1e-12)  # @ first, then ^ (interp_find.cc)
    keep_r = ends("G21 G90 G54 F100\nG1 X3 Y4\n^0\n", CTX)  # G90 ^ alone keeps the distance, about G54's zero
    np.testing.assert_allclose(keep_r[-1], [105, 50, 100], atol=1e-12)  # Z stays at home
    holes = parse_program("G21 G90 G0 X15 Y0 Z5\nG91 G81 R1 Z-6 ^120 L3 F60\n", context=ctx)
    bottoms = [b.target[:2] for b in holes.blocks if b.kind == "line"]
    np.testing.assert_allclose(bottoms, [[15 * math.cos(a), 15 * math.sin(a)] for a in
                                         (2 * math.pi / 3, 4 * math.pi / 3, 2 * math.pi)], atol=1e-12)
    for text, message in [("G21 G1 F100 X1 @2 ^3\n", r"polar coordinates @ \^ and X"),
                          ("G21 G18 G1 F100 @2 ^3\n", "only in the XY plane"),
                          ("G21 G91 G1 F100 ^90\n", "indeterminate at the origin"),
                          ("G21 G1 F100 @5\n", "without an angle"),
                          ("G21 G28 @1 ^2\n", "can only be used for motion")]:
        with pytest.raises(GCodeError, match=message):
            parse_program(text, context=ctx)


def test_g93_inverse_time_feed():
    """LinuxCNC G-code reference, G93: F means the move takes 1/F minutes; an F on every G1/G2/G3
    block; G94 resets the feed rate (interp_convert.cc convert_feed_mode)."""
    prog = parse_program("G21 G90 G0 X0 Y0\nG93 G1 X30 F2\nG2 X30 Y20 I0 J10 F6\nG94 G1 X0 F600\n",
                         context=MachineContext())
    line, arc, back = prog.blocks[1:]
    assert line.feed == pytest.approx(30 * 2 / 60)  # 30 mm in 0.5 min
    assert arc.feed == pytest.approx(10 * math.pi * 6 / 60)  # a half circle of R10 in 1/6 min
    assert back.feed == pytest.approx(600 / 60)
    with pytest.raises(GCodeError, match="inverse time \\(G93\\) without an F word"):
        parse_program("G21 G93 G1 X1 F2\nX2\n", context=MachineContext())
    with pytest.raises(GCodeError, match="feed move without a feed"):
        parse_program("G21 G1 F100 X1\nG93 G1 X2 F3\nG94\nX3\n", context=MachineContext())
    # a G5.1 spline under G93 takes its 1/F minutes as a whole, over all its chords
    spline = parse_program("G21 G90 G0 X0 Y0\nG93 G5.1 X20 Y0 I10 J10 F4\n", context=MachineContext())
    chords = spline.blocks[1:]
    assert len(chords) > 10
    minutes = sum(b.segment.length / b.feed for b in chords) / 60.0
    assert minutes == pytest.approx(1 / 4)


def test_radius_arc_chord_tolerance_is_linuxcncs():
    """interp_arc.cc arc_data_r: a half chord up to RADIUS_TOLERANCE (0.00005 in = 0.00127 mm)
    longer than |R| is a half circle; more is an error."""
    ok = parse_program("G21 G0 X0 Y0\nG2 X10.0024 Y0 R5 F100\n", context=MachineContext())
    arc = ok.blocks[-1].segment
    assert arc.radius == pytest.approx(5.0012) and abs(arc.sweep) == pytest.approx(math.pi)
    with pytest.raises(GCodeError, match="longer than the diameter"):
        parse_program("G21 G0 X0 Y0\nG2 X10.003 Y0 R5 F100\n", context=MachineContext())


def test_io_m_codes_take_their_words():
    """LinuxCNC M62-M68 (digital/analog outputs, M66 wait): their P/E/L/Q words are theirs, noted,
    no motion; E anywhere else is an error. (An analog input E is read at once, L0: rs274 refuses "M66 E1 L3 Q5",
    "Can't select analog input with wait type != immediate return"; test_iso_wild22.)"""
    prog = parse_program("G21 M68 E0 Q0\nM64 P2\nM66 P1 L3 Q5\nG1 X5 F100\n", context=MachineContext())
    assert [b.target.tolist() for b in prog.blocks] == [[5, 0, 0]]
    assert "M62-M68 digital/analog I/O x3" in prog.notes
    with pytest.raises(GCodeError, match="outside M66-M68"):
        parse_program("G21 G1 X1 F100 E3\n", context=MachineContext())


def test_named_programs_and_a_paren_inside_a_comment():
    """Shop programs name themselves "O7997A" or "OWASHER"; "(X1 (move up)" is one comment that
    ends at the first ')' (it does not close as a nested one)."""
    prog = parse_program("%\nOWASHER(washer)\nG21 G1 X1 F100 (X2 (move up)\nO7997A\nG1 X3\n%\n",
                         context=MachineContext())
    assert [b.target[0] for b in prog.blocks] == [1, 3]
    with pytest.raises(GCodeError, match="unclosed comment"):
        parse_program("G21 G1 X1 F100 (no end\n", context=MachineContext())


def test_m61_q_sets_the_tool_and_5599_may_be_set():
    """LinuxCNC M61 Q<tool> sets the current tool (G43 then takes its length); #5599 switches
    (DEBUG,) output and may be written; other system parameters may not."""
    prog = parse_program("G21 #5599 = 1\nM61 Q1 G43\nG0 Z0\n", context=CTX)
    assert prog.blocks[-1].target[2] == pytest.approx(-20 + 12.5)  # G54 Z -20, tool 1 length 12.5
    with pytest.raises(GCodeError, match="#5220 is read-only"):
        parse_program("G21 #5220 = 2\n", context=CTX)
    with pytest.raises(GCodeError, match="system parameters cannot be set"):
        parse_program("G21 #5500 = 2\n", context=CTX)


def test_g5_and_g5_1_splines_as_chords_within_a_micrometre():
    """LinuxCNC G-code reference: G5.1 X2 I2 J-8 from X-2 Y4 is the parabola y = x^2 (inch);
    G5 without I J continues the previous G5's tangent (I J = -P -Q)."""
    prog = parse_program("G20 G90 G17 F10\nG0 X-2 Y4\nG5.1 X2 I2 J-8\n", context=MachineContext())
    pts = np.array([b.target for b in prog.blocks[1:]]) / 25.4
    assert np.allclose(pts[:, 1], pts[:, 0] ** 2, atol=1e-12) and pts[-1].tolist() == [2, 4, 0]
    mid = (pts[:-1] + pts[1:]) / 2  # the chords stay within 1 um of the curve
    assert np.max(np.abs(mid[:, 1] - mid[:, 0] ** 2)) * 25.4 <= 0.001
    prog = parse_program("G21 G90 G17 F100\nG0 X0 Y0\nG5 I0 J3 P0 Q-3 X1 Y1\nG5 P0 Q-3 X2 Y2\n",
                         context=MachineContext())
    ends_ = [b.target for b in prog.blocks]
    first_end = [i for i, p in enumerate(ends_) if p.tolist() == [1, 1, 0]][0]
    into, out = ends_[first_end] - ends_[first_end - 1], ends_[first_end + 1] - ends_[first_end]
    assert abs(into[0] * out[1] - into[1] * out[0]) <= 1e-6 * np.linalg.norm(into) * np.linalg.norm(out)
    assert ends_[-1].tolist() == [2, 2, 0]
    for text, message in [("G21 F1 G5 X1 Y1 I1 J1\n", "P and Q must both be given"),
                          ("G21 F1 G5 X1 Y1 P1 Q1\n", "I and J are needed on the first G5"),
                          ("G21 F1 G5.1 X1 Y1\n", "I and J both unspecified"),
                          ("G21 F1 G18 G5.1 X1 I1\n", "only in the XY plane")]:
        with pytest.raises(GCodeError, match=message):
            parse_program(text, context=MachineContext())


#: A Haas-style main program calling macro O9001 with G65 (the Pythagorean side, as in Don Payne's
#: advanced-arcs example): B = sqrt(C^2 - A^2) is stored in the variable whose number V gives.
PROGRAM_G65 = """\
G21 G90 G0 X0 Y0 Z0
#1 = 7.
#10100 = 0.
G65 P9001 A3. C5. V10100.
G1 F100 X#10100 Y#1
G65 P9002 A1. I2. J3. K4. I5. J6. K7.
G65 P9003 L3 A10.
M30
O9001
#[#22] = SQRT[[#3 * #3] - [#1 * #1]]
M99
O9002
G1 X#7 Y#9 Z#6
M99
O9003
#1 = #1 + 1.
G1 X#1
M99
"""


def test_g65_macro_call_arguments_locals_and_repeats():
    """Fanuc/Haas custom macro B, G65 simple call: A C V -> #1 #3 #22 (argument specification I),
    the n-th I J K -> #(3n+1)..#(3n+3) (specification II); the call gets fresh locals (the caller's
    #1 = 7 is back after M99); with L3 the arguments are set once and the locals carry over from one
    repetition to the next (Haas mill operator's manual, "Local Variables"); #10100 is a Haas NGC
    general-purpose variable."""
    pts = ends(PROGRAM_G65, MachineContext())
    assert pts[1] == [4.0, 7.0, 0.0]  # B = sqrt(25 - 9) = 4 into #10100; the caller's #1 is 7 again
    assert pts[2] == [5.0, 7.0, 4.0]  # #7 = second I, #9 = second K, #6 = first K
    assert [p[0] for p in pts[3:]] == [11.0, 12.0, 13.0]


def test_g65_errors_name_the_problem():
    """An argument without a decimal point is scaled by the machine's least input increment (Fanuc
    16i manual, "Simple call (G65)"): an error; #0, Fanuc's null variable, cannot be set (it is what
    #[#22] names when #22 is vacant: no V argument, or the macro program run on its own); G, L, N, O,
    P are no argument addresses. A vacant local read in the macro leaves its word out (X#24 with no X
    argument moves no X: Fanuc 0i-MD B-64304EN, "Undefined variable")."""
    for text, message in [
        ("G65 P9001 A3 C5. V100.\nM30\nO9001\nM99\n", "without a decimal point"),
        ("G65 P9001 A3. C5.\nM30\nO9001\n#[#22] = 1.\nM99\n", "#0 cannot be set"),
        ("O9001\n#[#22] = 1.\nM99\n", "#0 cannot be set"),
        ("G65 P9001 A3. O5.\nM30\nO9001\nM99\n", "O is not an argument address"),
        ("G65 P9005 A3.\nM30\n", "G65 macro call: program O9005 is neither in this file"),
    ]:
        with pytest.raises(GCodeError, match=message):
            parse_program(text, context=MachineContext())
    assert ends("G21 F1\nG0 X2\nG65 P9001 Y3.\nM30\nO9001\nG1 X#24 Y#25\nM99\n", MachineContext())[-1] == [2, 3, 0]


def test_fanuc_macro_text_that_is_not_run_is_named():
    """A Fanuc macro B assignment needs no enclosing brackets (#2=[#1-1]/2); a GOTO to a missing
    block and crossing WHILE..DO loops are named in an error; a ':' program-number address (ISO
    code) needs its number; a '/' after a word's value is neither arithmetic (which needs brackets)
    nor a block skip that vcnc reads."""
    pts = ends("G21 G90 F100\n#1 = 5.\n#2 = [#1 - 1] / 2 + 1\nG1 X#2\n", MachineContext())
    assert pts == [[3.0, 0.0, 0.0]]
    # under fanuc: LinuxCNC refuses ':' (rs274 "Bad character ':' used"; test_iso_leftovers37.py)
    assert parse_program(":1234\nG21 G0 X1\n", context=MachineContext(dialect=DIALECTS["fanuc"])).name == "O1234"
    for text, message in [
        ("G21\nIF [#1 EQ 0] GOTO 10\nN11 G0 X1\n", "GOTO 10: no block N10 in this program"),
        ("G21\nWHILE [#1 LT 3] DO1\nEND2\n", "END 2 closes no open DO 2"),
        ("G21\n:(comment)\nG0 X1\n", "':' .* without a program number"),
        ("G21 G0 X#1/2\n", "'/2' after the word 'X#1': arithmetic on a word's value needs brackets"),
        ("G21 #region\nG0 X1\n", "'#region' is not a parameter"),
        ("#regionx\nG21 G0 X1\n", "'#regionx' is not a parameter"),
        ("O[your six digit birthdate]\nG21\n", "'your' is neither a number"),
        ("G21 G1 [your xy start position] F12\n", "'\\[your xy start position\\]' in brackets where a word"),
    ]:
        with pytest.raises(GCodeError, match=message):
            parse_program(text, context=MachineContext())


def test_cncsimulator_directive_lines_are_skipped_with_a_note():
    """CNCSimulator Pro's $-commands and #region/#endregion lines (its user guide, 6.3 "$-commands and
    regions": simulation commands that "have nothing to do with CNC codes") are not run, with a note;
    under grbl a $ line stays a grbl system command, and a # followed by a letter inside a line is no
    parameter."""
    text = "#region Setup\n$Inches (alarm if not inch)\n$AddRegPart 1 X2.9 Y2.0\n#endregion\nG21 G0 X1 Y2\nM30\n"
    for name in ("linuxcnc", "fanuc", "haas"):
        prog = parse_program(text, context=MachineContext(dialect=DIALECTS[name]))
        assert [b.target.tolist() for b in prog.blocks] == [[1, 2, 0]]
        assert "CNCSimulator Pro $-command and #region lines not run (simulator directives, not G-code) x4" \
            in prog.notes
    grbl = MachineContext(dialect=DIALECTS["grbl"])
    assert ends("#region\n#endregion\nG21 G0 X1\n", grbl) == [[1, 0, 0]]
    with pytest.raises(GCodeError, match="unknown grbl system command"):
        parse_program(text, context=grbl)
    assert ends("#1 = 2\nG21 G0 X#1\n", MachineContext()) == [[2, 0, 0]]
    with pytest.raises(GCodeError, match=r"unknown word '\$SLP'"):  # grbl's sleep, not a simulator command
        parse_program("$SLP\nG21 G0 X1\n", context=MachineContext(dialect=DIALECTS["haas"]))


def test_a_subprogram_that_runs_off_the_end_of_the_file_is_named():
    """An M98 or G65 call whose program has no M99 (here an M17, the subprogram end of Siemens and
    CNCSimulator Pro) would end the whole program silently at the end of the file: an error at the call."""
    for text in ("G21\nM98 P1001\nG0 X5\nM30\nO1001\nG0 X1\nM17\n", "G21\nG65 P1001\nM30\nO1001\nG0 X1\n"):
        with pytest.raises(GCodeError, match=r":2:1: .* call: the called blocks run to the end of the file without"):
            parse_program(text, context=MachineContext(dialect=DIALECTS["haas"]))


def test_rejections_name_the_controls_rule():
    """Programs every control refuses get an error saying why: a feed move before any F (LinuxCNC
    "Cannot do g1 with zero feed rate", grbl error 22), with a hint when the file is a subprogram
    that ends with M99 (its caller sets the feed); a first cycle block without R (LinuxCNC "R
    clearance plane unspecified in cycle"); I on G0 (LinuxCNC "I word with no G2, G3 ... to use it",
    grbl error 36); an unknown O-word keyword (LinuxCNC "Unknown control command in o word")."""
    for text, message in [
        ("G21 G0 X1\nG1 X2\nM30\n", "G01 feed move without a feed: no F word before it \\(got"),
        ("O1002\nG21 G1 X2\nM99\n%\n", "ends with M99: a subprogram, whose feed comes from the program that calls it"),
        ("G21 F1\nG93 G1 X1 F2\nG94 G1 X2\n", "G94 after G93 resets the feed"),
        ("G21 F100 G0 Z5\nG81 G98 Z-1\n", "no R \\(retract plane\\) word in the first block of the series"),
        ("G21 G0 X1 Y0 I0 J-1\n", "word I is only allowed on arcs \\(G02/G03\\), not on G00"),
        ("G21\no<g20sub> callsub\n", "O-word 'callsub': unknown O-word keyword"),
    ]:
        with pytest.raises(GCodeError, match=message):
            parse_program(text, context=MachineContext())


def test_arc_end_radius_rule_follows_the_dialect():
    """grbl 1.1 (gcode.c, "[Arc definition error]") refuses an end-radius mismatch above 0.005 mm that
    exceeds 0.5 mm or 0.1 % of the start radius, and any excess of an R arc's chord over the diameter;
    LinuxCNC (interp_arc.cc) accepts 0.0283 mm absolute or 0.1 % of the larger radius, at most
    2.83 mm, and an R chord up to 0.00254 mm longer than the diameter."""
    grbl = MachineContext(dialect=DIALECTS["grbl"])
    linuxcnc = MachineContext(dialect=DIALECTS["linuxcnc"])

    def arc(radius: float, mismatch: float) -> str:  # G2 from (r, 0) about the origin to (0, r + mismatch)
        return f"G21 G90 F100\nG0 X{radius} Y0\nG3 X0 Y{radius + mismatch:.6f} I{-radius} J0\n"

    for text, grbl_ok, linuxcnc_ok in [
        (arc(1.0, 0.004), True, True),      # within grbl's 0.005 mm
        (arc(1.0, 0.006), False, True),     # > 0.005 mm and > 0.1 % of 1 mm; LinuxCNC: < 0.0283 mm
        (arc(100.0, 0.08), True, True),     # 0.1 % of 100 mm = 0.1 mm for both
        (arc(1000.0, 0.6), False, True),    # grbl: > 0.5 mm; LinuxCNC: 0.1 % of 1000 mm = 1 mm
        ("G21 G90 F100\nG0 X0 Y0\nG2 X10.001 Y0 R5\n", False, True),  # chord 0.001 mm over 2R
    ]:
        for context, ok in ((grbl, grbl_ok), (linuxcnc, linuxcnc_ok)):
            if ok:
                end = parse_program(text, context=context).blocks[-1].target
                assert end[1] == pytest.approx(float(text.split("Y")[-1].split()[0]), abs=1e-12)
            else:
                with pytest.raises(GCodeError, match="arc end point is not on the circle|longer than the diameter"):
                    parse_program(text, context=context)
    with pytest.raises(InputError, match="arc_rule"):
        dataclasses.replace(DIALECTS["fanuc"], arc_rule="fanuc")


def test_exit_move_after_g40_without_xy_words_returns_to_the_programmed_path():
    """LinuxCNC interp_convert.cc convert_cutter_compensation_off: the programmed position becomes
    the current one, so the first move after G40 (here a Z retract) ends at its programmed X Y and
    every later move follows the program (found by the corpus reference: 0054, 0134)."""
    from interpolators.context import Tool

    ctx = MachineContext(tools={1: Tool(number=1, radius=1.0)})
    prog = parse_program("G21 G90 G0 X0 Y0 Z5\nG1 F100 G41 D1 X-5 Y0\nX-10\nG40\nG0 Z10\nX-20\n", context=ctx)
    *_, contour, exit_move, after = prog.blocks
    assert contour.target[1] == pytest.approx(-1.0)  # left of a move towards -X: y - 1
    assert exit_move.target.tolist() == pytest.approx([-10.0, 0.0, 10.0])
    assert after.start.tolist() == pytest.approx([-10.0, 0.0, 10.0])
    assert after.target.tolist() == pytest.approx([-20.0, 0.0, 10.0])


def test_g53_without_axis_words_moves_nothing():
    """A Fanuc post's "G53 G49 M05": G53 with no axis word is no motion (it made a zero-length move). Read as the
    Fanuc control it is written for: LinuxCNC refuses it ("Must use G0 or G1 with G53", test_iso_posts36b)."""
    prog = parse_program("G21 G90 G0 X1 Y2 Z3\nG53 G49 M05\nG0 X4\n",
                         context=MachineContext(dialect=DIALECTS["fanuc"]))
    assert [b.line for b in prog.blocks] == [1, 3]


def test_g10_l1_l10_l11_write_the_tool_table_and_g43_reads_it():
    """LinuxCNC "G10 L1/L10/L11" (interp_convert.cc convert_setup_tool): L1 sets tool P's length Z and
    radius R; L10 the length that makes the current Z read the programmed value in the current system
    (without the tool length offset); L11 the same in G59.3 without G92. The next G43 applies it."""
    ctx = MachineContext(work_offsets={"G54": (0.0, 0.0, -20.0), "G59.3": (0.0, 0.0, -50.0)})
    text = ("G21 G90 F100\nG10 L1 P1 Z5 R2\nT1 M6 G43\nG0 X0 Y0 Z0\nG0 Z1\nG10 L10 P1 Z0\nG43\nG0 Z2\n"
            "G10 L11 P2 Z3\nT2 M6 G43\nG0 Z0\nG41 G1 X10\nG40 G1 X20\n")
    pts = ends(text, ctx)
    assert pts[0] == [0.0, 0.0, -15.0]  # G54 Z-20 + length 5
    # at machine Z -14 (program 1): L10 Z0 makes the length -14 + 20 = 6, so Z2 is machine -20 + 6 + 2
    assert pts[2] == [0.0, 0.0, -12.0]
    # L11 P2 Z3 at machine -12: length -12 + 50 - 3 = 35; G43 with tool 2, Z0 at -20 + 35
    assert pts[3] == [0.0, 0.0, 15.0]
    assert pts[4][1] == 0.0  # tool 2 has no radius: G41 leaves the path
    with pytest.raises(GCodeError, match="G10 L1 without offsets"):
        parse_program("G21 G10 L1 P1\n", context=ctx)


def test_g52_sets_the_shared_offset_and_5210_follows_g92_family():
    """LinuxCNC convert_axis_offsets G_52: the named axes' offset becomes the value (not a position);
    G92.2 suspends it, G92.3 restores it; #5210 says whether it is applied, #5211.. keep the stored
    offset (tests/interp/g52/g52-g92-interaction)."""
    text = ("G21 G90\nG0 X5 Y5\nG52 X2 Y3\nG0 X0 Y0\nG92.2\nG0 X#5210 Y#5212\nG92.3\nG0 X#5210 Y0\nG92.1\n"
            "G0 X#5211 Y#5210\n")
    assert ends(text, MachineContext()) == [[5, 5, 0], [2, 3, 0], [0, 3, 0], [3, 3, 0], [0, 0, 0]]


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


def test_grbl_system_command_lines_and_status_query_are_not_g_code():
    # a file for a grbl sender: $ reports and settings, '?' status queries (gnea/grbl protocol.c, serial.c)
    text = ("$I  ; build info\n$$\n$G\n?  ; status\n$100=100.5 ; X steps/mm\n$N0=G20\n"
            "G21 G90\nG0 X1 Y2 Z3?\nG1 X4 F100\n")
    prog = checked_iso(text, _in_dialect("grbl"))
    # G54 is (100, 50, -20): X1 Y2 Z3 then X4, on the lines the file numbers them
    assert [b.target.tolist() for b in prog.blocks] == [[101, 52, -17], [104, 52, -17]]
    assert [b.line for b in prog.blocks] == [8, 9]
    assert "grbl $ system commands (reports, settings) not run x5" in prog.notes


@pytest.mark.parametrize("line, name", [("$J=G91 X10 F100", "$J= jog"),
                                        ("$C", "$C check g-code mode"), ("$RST=#", "$RST= restore")])
def test_grbl_system_commands_that_move_or_change_the_run_are_refused(line, name):
    with pytest.raises(GCodeError, match=rf"2:1: grbl {re.escape(name)}: not supported"):
        parse_program(f"G21\n{line}\nG0 X1\n", context=_in_dialect("grbl"))


def test_grbl_cycle_start_is_dropped_and_feed_hold_refused():
    # grbl commands.md: "~ Cycle Start / Resume ... Command is otherwise ignored"; "!" holds the feed
    prog = checked_iso("G21 G90\nG0 X1\nM5\n~\nG0 Y2~\n", _in_dialect("grbl"))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 0, 100], [101, 52, 100]]
    assert "grbl ~ cycle start (resumes a hold or M0 pause) dropped x2" in prog.notes
    with pytest.raises(GCodeError, match=r"3:6: grbl ! feed hold: not supported"):
        parse_program("G21\nG0 X1\nG0 X2!\n", context=_in_dialect("grbl"))


def test_grbl_homing_cycle_moves_z_home_then_x_y_and_keeps_the_offsets():
    """grbl ``$H`` (doc/markdown/commands.md; config.h HOMING_CYCLE_0 = Z, HOMING_CYCLE_1 = X Y): with
    home at machine (0, 0, 100) and G54 at (100, 50, -20), from program (1, 2, 3) = machine
    (101, 52, -17) Z goes up to 100, then X Y to 0 0; G54 still holds, so X5 is machine 105 and Y
    stays at machine 0. A ``$H`` after the last block runs too."""
    text = "G21 G90\nG0 X1 Y2 Z3\n$H\nG0 X5\n$H\n"
    prog = checked_iso(text, _in_dialect("grbl"))
    assert [b.target.tolist() for b in prog.blocks] == [
        [101, 52, -17], [101, 52, 100], [0, 0, 100], [105, 0, 100], [105, 0, 100], [0, 0, 100]]
    assert [(b.line, b.kind) for b in prog.blocks][1:3] == [(3, "rapid"), (3, "rapid")]
    assert prog.blocks[1].text == "$H"
    assert "grbl $H homing run as rapids to home (Z, then X Y) x2" in prog.notes


def test_grbl_reads_an_unclosed_comment_to_the_end_of_the_line():
    # grbl protocol.c: "ignore all characters until ')' or EOL"; LinuxCNC: "Unclosed comment found"
    text = "G21 G90\nG0 X1 (to the left; Y9\nG0 Y2\n"
    prog = checked_iso(text, _in_dialect("grbl"))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 0, 100], [101, 52, 100]]
    assert "unclosed ( comments read to the end of the line (grbl)" in prog.notes
    with pytest.raises(GCodeError, match="2:7: unclosed comment"):
        parse_program(text, context=_in_dialect("linuxcnc"))


def test_cncjs_macro_lines_are_the_sender_s_and_move_nothing():
    """CNCjs evaluates a line beginning with '%' itself (User Guide "Macro": "Lines beginning with % are
    used to create variables"; v1.9.4: "%wait ; Wait for the planner queue to empty") and never streams
    it to grbl: from program (1, 2) the tool goes to (4, 2) in G54 (100, 50, -20), Z at home (100),
    whatever the % lines say; a '%' alone is still the tape marker."""
    text = "%\nG21 G90\nG0 X1 Y2\n%wait\n%x0=posx,y0=posy\n% vfd enable (remark)\nG0 X4\n%\n"
    prog = checked_iso(text, _in_dialect("grbl"))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 52, 100], [104, 52, 100]]
    assert [b.line for b in prog.blocks] == [3, 7]
    assert "CNCjs % macro lines (%wait, variables) not run (the sender evaluates them) x3" in prog.notes
    # LinuxCNC has no sender of its own: a '%' with text after it is no line it reads; the message names CNCjs
    with pytest.raises(GCodeError, match=r":4:1: '%' must stand alone on its line \(a macro line of the CNCjs "
                                         r"sender, .*--dialect grbl.*\) \(got '%wait'\)"):
        parse_program(text, context=_in_dialect("linuxcnc"))


@pytest.mark.parametrize("name", ["haas", "fanuc"])
def test_external_output_commands_move_nothing(name):
    """Haas "Formatted Output" (DPRNT[<text> <#nnnn[wf]>...], the only command of its block) and
    Fanuc "External output commands" (POPEN, DPRNT, BPRNT, PCLOS): the tool goes from program
    (1, 2) to (3, 2) in G54 (100, 50, -20), Z staying at home (100), whatever is printed between."""
    text = ("%\nO0001\nPOPEN\nDPRNT[DATE*(AAMMDD):*#3011]\nG21 G90 G0 X1 Y2\nN10 DPRNT[X#5041[44]*Y#5042[44]]\n"
            "BPRNT[A#1[3]]\nPCLOS\nX3\nM30\n%\n")
    prog = checked_iso(text, _in_dialect(name))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 52, 100], [103, 52, 100]]
    assert "POPEN/DPRNT/BPRNT/PCLOS external output not sent" in prog.notes


@pytest.mark.parametrize("line, message", [
    ("DPRNT[X#5041[44]] G0 X1", r"2:1: DPRNT external output: must be the only command of its block"),
    ("DPRNT[X#5041[44]", r"2:1: DPRNT\[ external output without its closing '\]'"),
    ("POPEN X1", r"2:1: POPEN external output: must be the only command of its block")])
def test_external_output_commands_stand_alone(line, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21\n{line}\nG0 X1\n", context=_in_dialect("haas"))


def test_a_number_in_exponent_notation_is_named_as_such():
    # CAM scripts printing floats write "J -8.775e-05"; G-code numbers have no exponent (LinuxCNC
    # overview.adoc "Numbers"), so the control reads an E word and refuses it
    with pytest.raises(GCodeError, match=r"2:23: number '-8.775e-05' in exponent notation"):
        parse_program("G21 G90 F100\nG2 X1 Y0 I0.5 J -8.775e-05\n", context=CTX)
    with pytest.raises(GCodeError, match=r"word 'E5' outside M66-M68"):
        parse_program("G21 G90 F100\nG1 X1 E5\n", context=CTX)


def test_dollar_lines_are_an_error_outside_the_grbl_dialect():
    with pytest.raises(GCodeError, match=r"unknown word '\$I'"):
        parse_program("$I\nG21 G0 X1\n", context=_in_dialect("linuxcnc"))


@pytest.mark.parametrize("name", ["grbl", "fanuc", "haas"])
def test_axis_words_before_any_motion_code_are_a_rapid_where_g00_is_the_power_on_mode(name):
    # grbl gc_init (G0), Fanuc parameter 3402#0 = 0 (G00), Haas group 01 default G00
    text = "G21 G90\nZ10\nX1 Y2\nG1 X3 F100\n"
    checked_iso(text, _in_dialect(name))
    pts, kinds = ends(text, _in_dialect(name), kinds=True)
    # from home (0, 0, 100): Z alone keeps X Y there; G54 is (100, 50, -20)
    assert pts == [[0, 0, -10], [101, 52, -10], [103, 52, -10]]
    assert kinds == ["rapid", "rapid", "line"]


def test_linuxcnc_starts_in_g80_so_axis_words_need_a_motion_code():
    with pytest.raises(GCodeError, match="2:1: axis words before any motion code"):
        parse_program("G21 G90\nZ10\n", context=_in_dialect("linuxcnc"))


def test_task_parameter_is_one_as_when_the_machine_runs_the_program():
    # LinuxCNC #<_task>: 1 in milltask (emctaskmain.cc), 0 only in a preview
    assert ends("G21 G90\no1 if [#<_task> ne 0]\nG0 X1\no1 else\nG0 X2\no1 endif\n") == [[101, 0, 100]]


def test_g95_feed_per_revolution_is_f_times_s():
    # LinuxCNC g-code.adoc G95: F units per spindle revolution; 0.1 mm/rev at S600 is 60 mm/min, and the
    # same F at S1200 is 120 mm/min; G94 afterwards resets the feed (convert_feed_mode), F200 per minute
    text = ("G21 G90 G54 S600 M3\nG0 X0 Y0 Z5\nG95 G1 Z0 F0.1\nS1200\nG1 X10\n"
            "G20 G1 X1 F0.01\nG21 G94 G1 X0 F200\nM30\n")
    prog = checked_iso(text, CTX)
    assert [round(b.feed * 60.0, 9) for b in prog.blocks[1:]] == [60.0, 120.0, 0.254 * 1200, 200.0]
    assert prog.blocks[3].target.tolist() == [125.4, 50, -20]
    # a drilling cycle under G95: 0.05 mm/rev at S2000 feeds at 100 mm/min
    drill = checked_iso("G21 G90 G54 G0 X0 Y0 Z10\nS2000 M3\nG95\nG98 G81 Z-5 R2 F0.05\nG80\nM30\n",
                     _in_dialect("fanuc"))
    assert [round(b.feed * 60.0, 9) for b in drill.blocks if b.kind == "line"] == [100.0]
    # a G84 tap under G95 (the reference does not model G84): F is the pitch, 1 mm/rev at S300 is
    # 300 mm/min in and out
    tap = parse_program("G21 G90 G54 G0 X0 Y0 Z10\nS300 M3\nG95 G98 G84 Z-5 R2 F1\nG80\nM30\n",
                        context=_in_dialect("fanuc"))
    assert [round(b.feed * 60.0, 9) for b in tap.blocks if b.kind == "line"] == [300.0, 300.0]


@pytest.mark.parametrize("text, why", [("G21 S600 M3\nG95\nG1 X1\n", "no F word since G95"),
                                       ("G21 S600 M3\nF100\nG95 G1 X1\n", "no F word since G95"),
                                       ("G21 M3\nG95 G1 X1 F0.1\n", "without a spindle speed: S0 .*rs274: "
                                        "\"Cannot feed with zero spindle speed in feed per rev mode\""),
                                       ("G21 S600\nG95 G1 X1 F0.1\n", "with the spindle stopped")])
def test_g95_needs_f_a_spindle_speed_and_a_turning_spindle(text, why):
    with pytest.raises(GCodeError, match=why):
        parse_program(text, context=CTX)


def test_g10_l0_reloads_the_tool_table_only_without_a_loaded_tool():
    # LinuxCNC G10 L0: reload the tool table (an error with a tool in the spindle, convert_modal_0)
    prog = parse_program("G21 G90 G54\nG10 L0\nG0 X1\n", context=CTX)
    assert prog.blocks[0].target.tolist() == [101, 0, 100]
    assert "G10 L0 tool table reload (table unchanged)" in prog.notes
    with pytest.raises(GCodeError, match="3:1: G10 L0 not allowed with loaded tool T1"):
        parse_program("G21\nT1 M6\nG10 L0\n", context=CTX)


def test_f0_is_a_zero_feed_rate_refused_only_at_a_feed_move():
    # LinuxCNC read_f refuses a negative F only; F0 on a rapid is accepted, a G1 at F0 is an error
    prog = parse_program("G20 G90 G54\nG0 X1 F0\nG1 X2 F10\n", context=CTX)
    assert [b.target[0] for b in prog.blocks] == pytest.approx([125.4, 150.8])
    assert prog.blocks[1].feed * 60.0 == pytest.approx(254.0)
    with pytest.raises(GCodeError, match="3:1: G01 feed move without a feed: F0, a zero feed rate"):
        parse_program("G21 G1 X1 F100\nG0 X0 F0\nG1 X1\n", context=CTX)


@pytest.mark.parametrize("text, message", [
    ("G21\nN10 21 G40 G90\n", r"2:5: number '21' without its letter"),
    ("G21\n...\nG0 X1\n", r"2:1: '\.\.\.' where a word should start \(an ellipsis"),
    ("% \rO1000\nG21\n", r"1:1: '%' must stand alone on its line \(the line holds bare CRs"),
])
def test_a_line_that_is_not_g_code_is_named_for_what_it_is(text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=_in_dialect("fanuc"))


def test_a_named_program_line_before_the_percent_is_its_name():
    # "OPIS" (a shop file's title) alone on the first line: a program name, not a block; G54 (100, 50, -20)
    prog = checked_iso("OPIS\n%\nN10 G54\nN20 G21 G90 G0 X1 Y2\n%\n", _in_dialect("fanuc"))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 52, 100]]


def test_haas_m97_runs_the_local_subprogram_at_its_n_number_l_times():
    """Haas mill operator's manual "M97 Local Sub-Program Call" (its example, in mm): the blocks from
    N1000 to M99 run twice, then the block after the call. G54 (100, 50, -20), tool 1 12.5 long:
    Z1 is machine -6.5, Z0 -7.5; each pass steps Z down 0.1 twice, out to X2 (machine 102) and back."""
    text = ("%\nO00011 (M97 CALL)\nG21 G90 G54\nT1 M06\nG00 X0 Y0\nG43 H01 Z1.\nG01 Z0 F20.\nM97 P1000 L2\n"
            "G00 G90 Z1.\nM30\nN1000 (N line that runs after M97 P1000)\nG01 G91 Z-0.1\nG90 X2.\nG91 Z-0.1\n"
            "G90 X0\nM99\n%\n")
    prog = checked_iso(text, _in_dialect("haas"))
    pts = [b.target.tolist() for b in prog.blocks]
    expected = [[100, 50, 100], [100, 50, -6.5], [100, 50, -7.5]]
    z = -7.5
    for _ in range(2):
        expected += [[100, 50, z - 0.1], [102, 50, z - 0.1], [102, 50, z - 0.2], [100, 50, z - 0.2]]
        z -= 0.2
    expected.append([100, 50, -6.5])
    assert np.allclose(pts, expected, atol=1e-9)
    with pytest.raises(GCodeError, match=r"3:1: M97 local subprogram call: no block N2000 in this program"):
        parse_program("G21\nG0 X1\nM97 P2000\nM30\n", context=_in_dialect("haas"))


@pytest.mark.parametrize("code, name", [("G47 P0 (ABC) X0 Y0 I0 J.1 R.05 Z-.005 F15.", "G47 text engraving (Haas)"),
                                        ("G150 P1000 X0 Y0 Z-1 Q.1 R.1 F10.", "G150 general purpose pocket milling"),
                                        ("G31 Z-1 F100", "G31 skip function (probing)"),
                                        ("G28.2 Z0", "G28.2 homing cycle (TinyG/g2core)")])
def test_unsupported_control_specific_g_codes_are_named(code, name):
    with pytest.raises(GCodeError, match=rf"2:1: {re.escape(name)}.*: not supported"):
        parse_program(f"G21 G90\n{code}\n", context=_in_dialect("haas"))


@pytest.mark.parametrize("dialect, code, name", [
    # Haas NGC mill manual "G254 Dynamic Work Offset (DWO)": read under haas on a table's kinematics (session 36,
    # test_iso_posts36.py), named elsewhere
    ("fanuc", "G254", "G254 dynamic work offset (Haas DWO"), ("fanuc", "G255", "G255 dynamic work offset cancel"),
    # Fanuc "NURBS interpolation (G06.2)", as an industrial post (PowerMill, NX) writes it: read under fanuc
    # (posts37, test_iso_posts37.py), named elsewhere
    ("haas", "G06.2 P3 K0. X0 Y0 Z0 R1.", "G06.2 NURBS interpolation (Fanuc option; --dialect fanuc)")])
def test_industrial_post_codes_without_known_motion_are_named(dialect, code, name):
    with pytest.raises(GCodeError, match=rf"2:1: {re.escape(name)}.*: not supported"):
        parse_program(f"G21 G90\n{code}\nG0 X1.\n", context=_in_dialect(dialect))


def test_fanuc_g16_polar_coordinates_place_holes_on_a_circle():
    """Fanuc Series 16/18-MC operator's manual 9.2 "Polar coordinate command (G15, G16)": under G90 the
    X word is the radius and Y the angle about the work zero (G54 at machine (100, 50, -20)); a block
    with Y alone keeps the radius. Drilling at radius 50 at 0, 90 and 180 degrees: machine (150, 50),
    (100, 100), (50, 50); then radius 20 at 45 degrees; G15 returns to X Y."""
    text = ("%\nO1\nG21 G90 G17 G54\nG0 X0 Y0 Z5\nG16\nG81 X50. Y0 Z-10. R2. F100.\nY90.\nY180.\nG80\n"
            "G0 X20. Y45.\nG15\nG0 X1 Y1\nM30\n%\n")
    prog = checked_iso(text, _in_dialect("fanuc"))
    bottoms = [b.target.tolist() for b in prog.blocks if b.kind == "line"]
    assert np.allclose(bottoms, [[150, 50, -30], [100, 100, -30], [50, 50, -30]], atol=1e-9)
    r = 20 / math.sqrt(2)
    assert np.allclose(prog.blocks[-2].target, [100 + r, 50 + r, -15], atol=1e-9)
    assert np.allclose(prog.blocks[-1].target, [101, 51, -15], atol=1e-9)
    with pytest.raises(GCodeError, match=r"G16 polar coordinates under G91"):
        parse_program("G21 G90 G16\nG91 G0 X10 Y45\n", context=_in_dialect("fanuc"))
    with pytest.raises(GCodeError, match=r"G16 polar coordinates: not supported"):
        parse_program("G21 G90 G16\nG0 X10 Y45\n", context=_in_dialect("haas"))


def test_linuxcnc_arc_p_adds_full_turns():
    """LinuxCNC g-code.adoc "G2, G3 Arc Move": "if a 180 degree arc is programmed with a P2, the
    resulting motion will be 1 1/2 rotations". A half circle of radius 5 with P3 sweeps 5 pi clockwise;
    as a helix down 4 mm its length is the hypotenuse of 25 pi and 4; the end point is the programmed one."""
    prog = checked_iso("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 Z-4 P3 F600\nG3 X0 Y0 R5 P1\n",
                    _in_dialect("linuxcnc"))
    helix, back = prog.blocks[1], prog.blocks[2]
    assert helix.segment.sweep == pytest.approx(-5 * math.pi)
    assert helix.segment.length == pytest.approx(math.hypot(25 * math.pi, 4))
    assert helix.target.tolist() == [110, 50, -24]
    assert back.segment.sweep == pytest.approx(math.pi)
    for bad, message in [("P1.5", "P \\(number of turns\\) must be a whole number >= 1"),
                         ("P0", "P \\(number of turns\\) must be a whole number >= 1")]:
        with pytest.raises(GCodeError, match=message):
            parse_program(f"G21 G90 G0 X0 Y0\nG2 X10 Y0 I5 J0 {bad} F600\n", context=_in_dialect("linuxcnc"))
    with pytest.raises(GCodeError, match="word P needs G04"):
        parse_program("G21 G90 G0 X0 Y0\nG2 X10 Y0 I5 J0 P2 F600\n", context=_in_dialect("fanuc"))


def test_fanuc_haas_corner_rounding_and_chamfer_words_are_named_outside_their_dialects():
    # run under fanuc/haas: tests/interpolators/test_iso_corners.py
    for word, what in [(",R5.", "corner rounding"), (",C2.", "chamfering")]:
        with pytest.raises(GCodeError, match=rf"2:9: '{word}' {what} between two moves .*not in the linuxcnc"):
            parse_program(f"G21 G90\nG1 X50. {word} F100.\nY50.\n", context=_in_dialect("linuxcnc"))
