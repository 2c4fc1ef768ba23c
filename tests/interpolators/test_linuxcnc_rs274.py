"""vcnc's ``linuxcnc`` dialect against LinuxCNC's own interpreter: programs where ``benchmarks/linuxcnc_diff.py``
found vcnc and ``rs274`` (LinuxCNC 2.9.0~pre1, the Debian package linuxcnc-uspace, ``rs274 -g prog.ngc``) apart.
The expected end points are rs274 2.9.0~pre1 output written out (STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED
end points, G21: mm), so that the tests need no rs274. Where vcnc is more lenient than rs274 it says so in
``Program.notes``."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
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
