"""vcnc's ``linuxcnc`` dialect against LinuxCNC's own interpreter: programs where ``benchmarks/linuxcnc_diff.py``
found vcnc and ``rs274`` (LinuxCNC 2.9.0~pre1, the Debian package linuxcnc-uspace, ``rs274 -g prog.ngc``) apart.
The expected end points are rs274 2.9.0~pre1 output written out (STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED
end points, G21: mm), so that the tests need no rs274. Where vcnc is more lenient than rs274 it says so in
``Program.notes``."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import load_program, parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"], linear_units="inch", extra_axes=("a", "b", "c"))

#: A drilling cycle, G80, then a motion code again.
PROGRAM_G80_THEN_G1 = "G21 G17 G1 X0 Y0 Z5 F100\nG81 X1 Y1 Z-1 R1\nG80\nG1 Z3\nM2\n"
#: rs274 2.9.0~pre1 output for it, consecutive repeats dropped: (kind, X, Y, Z) [mm].
EXPECTED_G80_THEN_G1 = [("line", 0.0, 0.0, 5.0), ("rapid", 1.0, 1.0, 5.0), ("rapid", 1.0, 1.0, 1.0),
                        ("line", 1.0, 1.0, -1.0), ("rapid", 1.0, 1.0, 1.0), ("line", 1.0, 1.0, 3.0)]


def _ends(prog) -> list[tuple]:
    return [(b.kind, *(round(float(v), 4) + 0.0 for v in b.target)) for b in prog.blocks]


def test_g80_then_a_motion_code_matches_rs274():
    assert _ends(parse_program(PROGRAM_G80_THEN_G1, context=LINUXCNC)) == EXPECTED_G80_THEN_G1


def test_axis_words_after_g80_are_a_noted_leniency():
    """rs274 refuses ``Z3`` after G80 ("Cannot use axis values without a g code that uses them": G80 leaves no
    motion mode, interp_convert.cc convert_motion); vcnc runs it in the motion before the cycle (as Fanuc does,
    and Fusion 360 posts write it) and says so."""
    prog = parse_program(PROGRAM_G80_THEN_G1.replace("G1 Z3", "Z3"), context=LINUXCNC)
    assert _ends(prog) == EXPECTED_G80_THEN_G1
    assert any("after G80" in n and "LinuxCNC refuses" in n for n in prog.notes)
    assert not any("after G80" in n for n in parse_program(PROGRAM_G80_THEN_G1, context=LINUXCNC).notes)


def test_k0_on_a_g17_arc_is_a_noted_leniency():
    """rs274 refuses ``G2 X2 Y0 I1 J0 K0`` ("K word given for arc in xy plane"); vcnc ignores the K0 with a note
    and runs the arc rs274 2.9.0~pre1 runs without it: ARC_FEED(2.0000, 0.0000, 1.0000, 0.0000, -1, 0.0000, ...),
    end (2, 0), centre (1, 0), clockwise, one turn."""
    prog = parse_program("G21 G17\nG1 X0 Y0 F100\nG2 X2 Y0 I1 J0 K0\nM2\n", context=LINUXCNC)
    arc = prog.blocks[-1]
    assert arc.kind.startswith("arc") and np.allclose(arc.target, [2.0, 0.0, 0.0])
    assert np.allclose(arc.segment.center[:2], [1.0, 0.0]) and not arc.segment.ccw
    assert any(n.startswith("K0 on G17 arcs ignored") for n in prog.notes)


def test_a_dwell_with_another_group_0_code_is_refused():
    """rs274 2.9.0~pre1 refuses ``G4 P0.5 G28`` ("Two g codes used from same modal group": both are in LinuxCNC's
    non-modal group 0, interp_array.cc gees[]); vcnc's linuxcnc dialect too, naming both."""
    with pytest.raises(GCodeError, match=r"2:9: two G codes of LinuxCNC's non-modal group 0 in one block \(G4 and G28"):
        parse_program("G21\nG4 P0.5 G28\nM2\n", context=LINUXCNC)


def test_a_file_without_a_program_end_is_a_noted_leniency():
    """rs274 2.9.0~pre1 runs ``G21 / G0 X1`` (STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, ...)) and then refuses the
    file: "File ended with no percent sign or program end" (interp_read.cc); vcnc reads it to its end and says so.
    With M2, or between two ``%`` lines, both accept it without a word."""
    prog = parse_program("G21\nG0 X1\n", context=LINUXCNC)
    assert _ends(prog) == [("rapid", 1.0, 0.0, 0.0)]
    assert any(n.startswith("no M2/M30") for n in prog.notes)
    for text in ("G21\nG0 X1\nM2\n", "%\nG21\nG0 X1\n%\n"):
        assert not any(n.startswith("no M2/M30") for n in parse_program(text, context=LINUXCNC).notes)


def test_a_nested_comment_is_a_noted_leniency():
    """rs274 2.9.0~pre1 refuses ``G0 X1 (a (b) c)`` ("Nested comment found", interp_internal.cc
    close_and_downcase); vcnc reads the comment as nested, runs the move and says so."""
    prog = parse_program("G21\nG0 X1 (a (b) c)\nM2\n", context=LINUXCNC)
    assert _ends(prog) == [("rapid", 1.0, 0.0, 0.0)]
    assert any("nested" in n and "LinuxCNC refuses" in n for n in prog.notes)
    assert not any("nested" in n for n in parse_program("G21\nG0 X1 (a b) ; (c\nM2\n", context=LINUXCNC).notes)


def test_codes_linuxcnc_does_not_know_are_noted_as_its_refusals():
    """rs274 2.9.0~pre1 refuses ``M45`` ("Unknown m code used: M45") and ``G50`` ("Unknown g code used"): neither is
    in its tables (interp_array.cc ems[], gees[]); vcnc runs them without motion and says that LinuxCNC refuses
    them. M8 (coolant) is LinuxCNC's and noted as before."""
    notes = parse_program("G21 G50\nM45\nM8\nG0 X1\nM2\n", context=LINUXCNC).notes
    assert 'M45 (no motion; LinuxCNC refuses it: "Unknown m code used")' in notes
    assert 'G50 cancel; LinuxCNC refuses it: "Unknown g code used"' in notes
    assert not any("M7-M9" in n and "LinuxCNC" in n for n in notes)


def test_the_closing_percent_ends_the_program():
    """``%`` / ``G21`` / ``G0 X1`` / ``%`` / ``G0 X5``: rs274 2.9.0~pre1 prints STRAIGHT_TRAVERSE(1.0000, 0.0000,
    0.0000, ...) and nothing after the closing ``%`` (interp_read.cc read_text: INTERP_ENDFILE); vcnc ends there
    too under linuxcnc, with a note."""
    prog = parse_program("%\nG21\nG0 X1\n%\nG0 X5\n", context=LINUXCNC)
    assert _ends(prog) == [("rapid", 1.0, 0.0, 0.0)]
    assert any(n.startswith("lines after the closing %") for n in prog.notes)


def test_a_percent_line_rs274_refuses_is_a_noted_leniency():
    """rs274 2.9.0~pre1 refuses ``% ; flag`` as the first line and a ``%`` after a comment line ("Bad character '%'
    used"); vcnc skips such lines, runs ``G0 X1`` and says so."""
    for text in ("% ; flag\nG21\nG0 X1\nM2\n", "(c)\n%\nG21\nG0 X1\n%\n"):
        prog = parse_program(text, context=LINUXCNC)
        assert _ends(prog) == [("rapid", 1.0, 0.0, 0.0)]
        assert any(n.startswith("'%' lines LinuxCNC refuses") for n in prog.notes)
    assert not any("%" in n for n in parse_program("%\nG21\nG0 X1\n%\n", context=LINUXCNC).notes)


def test_a_motion_code_with_g28_is_a_noted_leniency():
    """rs274 2.9.0~pre1 refuses ``G00G28`` ("Cannot use two g codes that both use axis values": G28 covets the
    axis words, interp_internal.cc); vcnc runs the G28 (home: the origin here) and says so; ``G91 G28 Z0`` is
    LinuxCNC's and needs no note."""
    prog = parse_program("G21\nG0 X5 Y5\nG00G28\nM2\n", context=LINUXCNC)
    assert _ends(prog)[-1] == ("rapid", 0.0, 0.0, 0.0)
    assert "G00 with G28 in one block (LinuxCNC refuses them: \"Cannot use two g codes that both use axis " \
           "values\")" in prog.notes
    assert not any("in one block" in n for n in parse_program("G21\nG91 G28 Z0\nM2\n", context=LINUXCNC).notes)


def test_g1_alone_before_any_feed_is_a_noted_leniency():
    """rs274 2.9.0~pre1 refuses ``G1 (c)`` before any F ("Cannot do g1 with zero feed rate": convert_straight checks
    the feed first); vcnc takes it as setting the mode, says so, and runs the later ``G1 X1 F100`` as rs274 does
    once an F is set: STRAIGHT_FEED(1.0000, 0.0000, 0.0000, ...)."""
    prog = parse_program("G21\nG1 (c)\nG1 X1 F100\nM2\n", context=LINUXCNC)
    assert _ends(prog) == [("line", 1.0, 0.0, 0.0)]
    assert any(n.startswith("G1 alone before any F") for n in prog.notes)
    assert not any("G1 alone" in n for n in parse_program("G21 F100\nG1 (c)\nG1 X1\nM2\n", context=LINUXCNC).notes)


#: rs274's standalone machine with the tool table ``T1 P1 D0.2 Z0.5`` / ``T2 P2 D0.1 Z0.25`` (inch): radii 2.54 and
#: 1.27 mm.
LINUXCNC_TOOLS = dataclasses.replace(LINUXCNC, tools={1: Tool(number=1, length=12.7, radius=2.54),
                                                      2: Tool(number=2, length=6.35, radius=1.27)})
#: A G41 run closed by G40 with no exit move; ``{between}`` stands before the Z-only move that follows.
PROGRAM_G40_THEN = ("G21 G17 G90 G64\nT1 M6\nF100\nG0 X0 Y0 Z5\nG41 G0 X10 Y0\nG1 X20 Y0\nG0 Z5\nG40\n{between}"
                    "G0 Z10\nM2\n")


def test_a_tool_change_after_g40_keeps_the_offset_point_as_rs274_does():
    """After G40 with no exit move LinuxCNC's queue ends at the run's last offset point; M6 makes the interpreter
    read its position from there (interp_convert.cc convert_tool_change sets toolchange_flag, rs274ngc_pre.cc
    read_inputs: refresh_actual_position). rs274 2.9.0~pre1: without M6 the Z-only move ends at the programmed
    X Y, STRAIGHT_TRAVERSE(20.0000, 0.0000, 10.0000, ...); after ``T2 M6`` it stays at the offset point,
    STRAIGHT_TRAVERSE(20.0000, 2.5400, 10.0000, ...)."""
    run = [("rapid", 0.0, 0.0, 5.0), ("rapid", 10.0, 2.54, 5.0), ("line", 20.0, 2.54, 5.0), ("rapid", 20.0, 2.54, 5.0)]
    assert _ends(parse_program(PROGRAM_G40_THEN.format(between=""), context=LINUXCNC_TOOLS)) == \
        [*run, ("rapid", 20.0, 0.0, 10.0)]
    assert _ends(parse_program(PROGRAM_G40_THEN.format(between="M5\nT2 M6\n"), context=LINUXCNC_TOOLS)) == \
        [*run, ("rapid", 20.0, 2.54, 10.0)]


def test_a_plane_change_between_g40_and_the_exit_move_leaves_the_run_in_its_plane():
    """G40, then G18 before the exit move: the G17 run is offset in XY (it was offset in the new plane and refused
    as gouging). rs274 2.9.0~pre1 prints STRAIGHT_FEED(-1.7961, -1.7961, 0), ARC_FEED(-2.5400, 0.0000, 0, 0, -1),
    STRAIGHT_FEED(-2.5400, 25.0000, 0), ARC_FEED(-6.0000, 28.4600, -6.0000, 25.0000, 1), STRAIGHT_FEED(-12.0000,
    28.4600, 0), then the exit move STRAIGHT_TRAVERSE(5.0000, 0.0000, -5.0000)."""
    prog = parse_program("G21 G17 G90\nT1 M6\nF100\nG0 X5 Y-5 Z0\nG41 D1\nG1 X0 Y0\nG1 Y25\nG3 R6 X-6 Y31\nG1 X-12\n"
                         "G40\nG18\nG0 X5 Z-5 Y0\nM2\n", context=LINUXCNC_TOOLS)
    assert _ends(prog) == [
        ("rapid", 5.0, -5.0, 0.0), ("line", -1.7961, -1.7961, 0.0), ("arc", -2.54, 0.0, 0.0),
        ("line", -2.54, 25.0, 0.0), ("arc", -6.0, 28.46, 0.0), ("line", -12.0, 28.46, 0.0),
        ("rapid", 5.0, 0.0, -5.0)]
    corner, arc = prog.blocks[2].segment, prog.blocks[4].segment
    assert not corner.ccw and np.allclose(corner.center[:2], [0.0, 0.0])
    assert arc.ccw and np.allclose(arc.center[:2], [-6.0, 25.0])


def test_a_utf8_byte_order_mark_is_a_noted_leniency(tmp_path):
    """rs274 2.9.0~pre1 refuses a file that starts with a UTF-8 byte-order mark ("Bad character '\\357' used",
    interp_read.cc read_one_item); vcnc reads the program without it and says so under the linuxcnc dialect."""
    path = tmp_path / "bom.ngc"
    path.write_bytes(b"\xef\xbb\xbfG21\nG0 X1\nM2\n")
    prog = load_program(path, context=LINUXCNC)
    assert _ends(prog) == [("rapid", 1.0, 0.0, 0.0)]
    assert any(n.startswith("UTF-8 byte-order mark") and "LinuxCNC refuses" in n for n in prog.notes)
    haas = load_program(path, context=MachineContext(dialect=DIALECTS["haas"]))
    assert not any("byte-order" in n for n in haas.notes)
    path.write_bytes(b"G21\nG0 X1\nM2\n")
    assert not any("byte-order" in n for n in load_program(path, context=LINUXCNC).notes)
