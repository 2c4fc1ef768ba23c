"""Hand-written ISO programs for G33/G33.1 spindle-synchronised motion, G64 R, tool offsets on X/Y,
line ends and number errors, with the end points and feeds LinuxCNC's G-code reference gives
(LinuxCNC docs/src/gcode/g-code.adoc "G33", "G33.1", "G64", "G10 L1", "G43"), written out."""

from __future__ import annotations

import pytest

from interpolators import load_program, parse_program
from interpolators.context import MachineContext, read_tool_table
from vcnc.errors import GCodeError

CTX = MachineContext(home=(0.0, 0.0, 50.0))


def _moves(text: str, context: MachineContext = CTX) -> list[tuple[str, list[float], float]]:
    """(kind, end point [mm], feed [mm/min]) of each block."""
    return [(b.kind, b.target.tolist(), b.feed * 60.0) for b in parse_program(text, context=context).blocks]


def test_g33_feeds_at_pitch_times_spindle_speed_and_ends_at_the_end_point():
    # g-code.adoc "G33": G33 Z-15 K1.5 moves 15 mm while the spindle turns 10 times; at S400 that is
    # 1.5 mm/rev x 400 rev/min = 600 mm/min
    moves = _moves("G21 G90\nG0 X10 Y0 Z2\nS400 M3\nG33 Z-15 K1.5\nG0 X15\nZ2\nM5\nM2\n")
    assert moves[1] == ("line", [10.0, 0.0, -15.0], pytest.approx(600.0))
    assert [m[1] for m in moves[2:]] == [[15.0, 0.0, -15.0], [15.0, 0.0, 2.0]]


def test_g33_tapered_drive_line_and_inch_pitch():
    # K follows the drive line X Z (g-code.adoc NOTE); G20: K 0.0625 in/rev = 1.5875 mm/rev, S100
    moves = _moves("G20 G90\nG0 X0 Y0 Z0\nM3 S100\nG33 X0.1 Z-1 K0.0625\n")
    assert moves[1][0] == "line"
    assert moves[1][1] == pytest.approx([2.54, 0.0, -25.4])
    assert moves[1][2] == pytest.approx(0.0625 * 25.4 * 100)


def test_g33_1_rigid_tap_goes_to_depth_and_back_with_i_speeding_the_return():
    # g-code.adoc "G33.1": tap to Z-0.750 (inch) at K x S, then back to the start (I2: twice the speed)
    moves = _moves("G20 G90\nG0 X1 Y1 Z0.1\nS100 M3\nG33.1 Z-0.75 K0.05 I2\nG0 X2\n")
    assert [m[0] for m in moves] == ["rapid", "line", "line", "rapid"]
    assert moves[1][1] == pytest.approx([25.4, 25.4, -19.05])
    assert moves[2][1] == pytest.approx([25.4, 25.4, 2.54])
    assert moves[1][2] == pytest.approx(0.05 * 25.4 * 100) and moves[2][2] == pytest.approx(2 * 0.05 * 25.4 * 100)
    assert moves[3][1] == pytest.approx([50.8, 25.4, 2.54])  # the tap ended where it began


@pytest.mark.parametrize("text, message", [
    ("G21 S100\nG33 Z-1 K1\n", "G33 spindle-synchronised motion with the spindle not turning"),
    ("G21 S100 M3 M5\nG33.1 Z-1 K1\n", "G33.1 rigid tapping with the spindle not turning"),
    ("G21 M3\nG33 Z-1 K1\n", "with spindle speed S0"),
    ("G21 S100 M3\nG33 Z-1\n", "without a K word"),
    ("G21 S100 M3\nG33 Z-1 K1 F100\n", "with word F (the feed follows from K"),
    ("G21 S100 M3\nG33 K1\n", "all axis words omitted"),
    ("G21 S100 M3\nG33 Z-1 K1 I2\n", "with word I"),
    ("G21 S100 M3\nM2\nG33 Z-1 K1\n", None),  # nothing after M2 runs
])
def test_g33_errors_name_the_missing_piece(text, message):
    if message is None:
        assert parse_program(text, context=CTX).blocks == ()
        return
    with pytest.raises(GCodeError, match=message.replace("(", r"\(")):
        parse_program(text, context=CTX)


def test_g64_r_planner_word_is_accepted_and_changes_no_end_point():
    # g-code.adoc "G64 R: planner selection" (LinuxCNC 2.10): the R word picks the planner, not the path
    text = "G21 G90\nG64 P0.05 R0.5\nG1 X10 F600\nG64 P0.05 R0\nG1 Y10\n"
    prog = parse_program(text, context=CTX)
    assert [b.target.tolist() for b in prog.blocks] == [[10.0, 0.0, 50.0], [10.0, 10.0, 50.0]]
    assert all(b.tolerance == pytest.approx(0.05) and not b.exact_stop for b in prog.blocks)
    assert any("G64 R" in n for n in prog.notes)


@pytest.mark.parametrize("text, message", [
    ("G21\nG64 M19 R90 S0\n", "ambiguous"),  # LinuxCNC tests/interp/bad/g64-m19-r-ambiguous.ngc
    ("G21\nG61 R0.5\n", "word R without an arc motion"),  # tests/interp/bad/g64-r-on-g61.ngc
])
def test_g64_r_errors_as_linuxcnc(text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=CTX)


def test_g43_applies_the_tools_x_y_and_z_offsets():
    # g-code.adoc "G10 L1" sets tool P's offsets; "G43": all the tool's offsets apply; G49 cancels them
    text = "G21 G90\nG10 L1 P1 X1 Y2 Z3\nT1 M6 G43\nG0 X0 Y0 Z0\nX5\nG49\nG0 X0 Y0 Z0\nG43.1 X-1\nG0 X0\n"
    assert [m[1] for m in _moves(text)] == [[1.0, 2.0, 3.0], [6.0, 2.0, 3.0], [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]


def test_g10_l10_tool_offsets_in_a_rotated_system_as_linuxcnc():
    # LinuxCNC tests/interp/g10/g10-l1-l10, last part, in mm: G10 L2 R45, at X0 Y0, G10 L10 P1 X1 makes the
    # offsets -0.707 -0.707 (#5401 #5402), the current position then reads X1 Y0 (#5420 #5421); L10 Y1 keeps
    # the part along the rotated X: 0 -1.414, and the position reads X1 Y1
    text = ("G21\nG10 L2 P1 R45\nG0 X0 Y0 Z0\nG10 L10 P1 X0 Y0 Z0\nT1 M6 G43\nG10 L10 P1 X1\n"
            "(debug, #5401 #5402 #5403)\nG43\n(debug, #5420 #5421)\nG10 L10 P1 Y1\n(debug, #5401 #5402 #5403)\n"
            "G43\n(debug, #5420 #5421)\nG0 X0 Y0\n")
    prog = parse_program(text, context=CTX)
    got = [[float(v) for v in m.text.split()] for m in prog.messages]
    assert got[0] == pytest.approx([-0.707107, -0.707107, 0.0], abs=1e-6)
    assert got[1] == pytest.approx([1.0, 0.0], abs=1e-6)
    assert got[2] == pytest.approx([0.0, -1.414214, 0.0], abs=1e-6)
    assert got[3] == pytest.approx([1.0, 1.0], abs=1e-6)
    # program X0 Y0 of the rotated system is machine 0 0 plus the tool's offsets
    assert prog.blocks[-1].target.tolist() == pytest.approx([0.0, -2 ** 0.5, 0.0], abs=1e-12)


def test_tool_table_x_y_columns_are_read(tmp_path):
    # LinuxCNC tool table (config/tool-table.adoc): T P X Y Z D columns, ';' comment
    path = tmp_path / "tool.tbl"
    path.write_text("T1 P1 X1.5 Y-2 Z10 D4 ;offset head\nT2 P2 Z5\n")
    tools = read_tool_table(str(path))
    assert (tools[1].offset_x, tools[1].offset_y, tools[1].length, tools[1].radius) == (1.5, -2.0, 10.0, 2.0)
    assert (tools[2].offset_x, tools[2].offset_y) == (0.0, 0.0)
    inch = read_tool_table(str(path), units="inch")
    assert inch[1].offset_x == pytest.approx(1.5 * 25.4)
    moves = _moves("G21 G90\nT1 M6 G43\nG0 X0 Y0 Z0\n", MachineContext(tools=tools))
    assert moves[0][1] == [1.5, -2.0, 10.0]


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_cr_lf_and_crlf_line_ends_read_alike(end, tmp_path):
    # LF (Unix), CR LF (DOS) and a bare CR (classic Mac OS) each end a line; lines keep their numbers
    lines = ["G21 G90", "G0 X1 Y2", "G1 X5 F100", "G1 Y[1 +]"]
    path = tmp_path / "p.ngc"
    path.write_bytes(end.join(lines[:3]).encode() + end.encode())
    prog = load_program(path, context=CTX)
    assert [(b.line, b.target.tolist()) for b in prog.blocks] == [(2, [1.0, 2.0, 50.0]), (3, [5.0, 2.0, 50.0])]
    path.write_bytes(end.join(lines).encode())
    with pytest.raises(GCodeError) as err:
        load_program(path, context=CTX)
    assert err.value.line == 4


@pytest.mark.parametrize("text, column, message", [
    # LinuxCNC interp_read.cc read_operation: an 'e' after a number is "Unknown operation name starting with e"
    ("G21 G0 X[1e308]\n", 11, "number with an exponent '1e308': G-code numbers have no exponent notation"),
    ("G21 G0 X[2 * 1.5E-3]\n", 17, "number with an exponent '1.5E-3'"),
    ("G21 G0 X[1 foo 2]\n", 12, "unknown operation 'foo' in an expression"),
    ("G21 G0 X[1 + 2\n", 9, "unclosed '\\[' in an expression"),
])
def test_expression_errors_name_the_real_problem_at_its_column(text, column, message):
    with pytest.raises(GCodeError, match=message) as err:
        parse_program(text, context=CTX)
    assert (err.value.line, err.value.column) == (1, column)


def test_a_stray_cr_in_a_text_with_lf_line_ends_stays_in_its_line():
    # a CR inside a comment of an LF file (Heidenhain corpus 0200_11.h has one) does not end the line
    prog = parse_program("G21 G90 (tool 6 mm\r flute 32)\nG0 X1\n", context=CTX)
    assert [(b.line, b.target.tolist()) for b in prog.blocks] == [(2, [1.0, 0.0, 50.0])]


def test_g74_left_hand_tapping_moves_as_g84_and_needs_m4():
    # g-code.adoc "G74 Left-hand Tapping Cycle with Dwell": feed to Z, dwell P, feed out to the clear level
    # (G98: the Z before the series), F = S x pitch (S100 x 1.25 mm = F125); interp_cycles.cc
    # check_g74_g84_spindle refuses G74 with the spindle stopped or turning clockwise
    moves = _moves("G21 G90 G98\nG0 X0 Y0 Z10\nS100 M4\nG74 X5 Y5 Z-3 R2 P0.5 F125\nG80\n")
    assert [(k, p) for k, p, _ in moves] == [("rapid", [0.0, 0.0, 10.0]), ("rapid", [5.0, 5.0, 10.0]),
                                             ("rapid", [5.0, 5.0, 2.0]), ("line", [5.0, 5.0, -3.0]),
                                             ("dwell", [5.0, 5.0, -3.0]), ("line", [5.0, 5.0, 10.0])]
    assert moves[3][2] == pytest.approx(125.0) and moves[5][2] == pytest.approx(125.0)
    with pytest.raises(GCodeError, match="spindle turning clockwise"):
        parse_program("G21 G90\nG0 Z10\nS100 M3\nG74 X5 Y5 Z-3 R2 F125\n", context=CTX)
    with pytest.raises(GCodeError, match="spindle not turning"):
        parse_program("G21 G90\nG0 Z10\nG74 X5 Y5 Z-3 R2 F125\n", context=CTX)
