"""ISO programs of the thirteenth wild round (issue 18, set /tmp/isowild12): hobby routers' and lasers' generators
(GrblGru, jscut, GCodeKit4, Fusion personal posts, a Python panel engraver, drl2gcode, pcb-gcode), student Haas
programs, a CATIA Haas VF6 post, a MillMaster Pro file. What their controls refuse is refused naming what the
text is and how that control says it."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

SLASH = r"'//' comment line \(Syntec/DDCS macro and MillMaster Pro style\)"


@pytest.mark.parametrize("line", ['// Tool is a 3/4" (or whatever you decide', "  // see note)", "//O0000 RAIL-HOLE"])
def test_a_slash_comment_line_is_named_before_its_parentheses(line):
    # a MillMaster Pro file's header: prose after '//', an unclosed '(' in it; before, "unclosed comment"
    with pytest.raises(GCodeError, match=f":2:{line.index('//') + 2}: {SLASH}.*expected a \\( \\) or ; comment"):
        parse_program(f"G70\n{line}\nG0 X1\n", context=MachineContext().with_dialect("fanuc"))


def test_a_block_delete_line_still_runs():
    prog = checked_iso("G21 G90\n/G0 X1 (skip) Y2\nM30\n", MachineContext())
    assert [b.target.tolist() for b in prog.blocks] == [[1.0, 2.0, 0.0]]


@pytest.mark.parametrize(("line", "column", "what"), [
    ("G28  X         ; home X", 6, r"'G28 X', home X, as 3D printer firmware such as Marlin writes it; an ISO control "
                                  r"needs a number: G91 G28 X0 returns X alone"),
    ("G28 X Y", 5, r"'G28 X', home X"),
    ("G1 Z F100", 4, r"as 3D printer firmware such as Marlin takes axis flags")])
@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl", "fanuc"])
def test_an_axis_letter_without_its_number_is_named(line, column, what, dialect):
    # a panel engraver's output for a Marlin-style router: "G28  X ; home X" (LinuxCNC, grbl: "Bad number format")
    with pytest.raises(GCodeError, match=f":2:{column}: malformed number for word [XZ] \\(an axis letter without its "
                                         f"number.*{what}"):
        parse_program(f"G21 G90 F100\n{line}\nM30\n", context=MachineContext().with_dialect(dialect))


def test_a_keyword_is_not_read_as_an_axis_flag():
    with pytest.raises(GCodeError, match=r"'ASKBOOL': a statement of another control's language"):
        parse_program("G21\nASKBOOL 5\n", context=MachineContext().with_dialect("fanuc"))


@pytest.mark.parametrize(("dialect", "how"), [
    ("grbl", r"grbl error 22: feed rate has not yet been set or is undefined"),
    ("linuxcnc", r"LinuxCNC: cannot do G1 with zero feed rate"),
    ("fanuc", r"Fanuc alarm PS0011: feed zero"),
    ("haas", r"refused by LinuxCNC, grbl \(error 22\) and Fanuc \(alarm PS0011\) alike")])
def test_a_feed_move_at_f0_names_how_its_control_refuses_it(dialect, how):
    # a laser template's post-processed output: rapids and the plunge written with "F0.000000"
    text = "G21 G90\nG0 F0.000000 X1.49 Y12 Z4\nG1 F0.000000 X1.49 Y12 Z-5\nM30\n"
    with pytest.raises(GCodeError, match=f":3:1: G01 feed move without a feed: F0, a zero feed rate \\({how}\\)"):
        parse_program(text, context=MachineContext().with_dialect(dialect))
    ends = checked_iso(text.replace("G1 F0.000000", "G1 F1000"), MachineContext().with_dialect(dialect))
    assert [b.target.tolist() for b in ends.blocks] == [[1.49, 12.0, 4.0], [1.49, 12.0, -5.0]]


FENCE = r"a Markdown code fence or its language tag: text copied from a README or a chat answer\?"


@pytest.mark.parametrize(("text", "where"), [
    ("gcode\n(Program: EXAMPLE)\nG21 G90\n", r":1:1: malformed number for word G"),  # a chat answer's "```gcode"
    ("```gcode\nG21 G90\nG0 X1\n```\n", r":1:1: unknown word '```gcode'"),
    ("G21 G90\nG0 X1\n```\n", r":3:1: unknown word '```'")])
@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl", "haas"])
def test_a_markdown_fence_line_is_named(text, where, dialect):
    with pytest.raises(GCodeError, match=f"{where}.*\\({FENCE}\\)"):
        parse_program(text, context=MachineContext().with_dialect(dialect))


def test_a_tilde_fence_is_named_where_it_is_no_grbl_cycle_start():
    with pytest.raises(GCodeError, match=f":3:1: unknown word '~~~' \\({FENCE}\\)"):
        parse_program("G21 G90\nG0 X1\n~~~\n", context=MachineContext().with_dialect("fanuc"))
    # grbl's receive interrupt takes '~' (cycle start) out of the stream: the line is empty there
    prog = parse_program("G21 G90\nG0 X1\n~~~\n", context=MachineContext().with_dialect("grbl"))
    assert [b.target.tolist() for b in prog.blocks] == [[1.0, 0.0, 0.0]]


def test_a_word_that_merely_looks_like_a_tag_keeps_its_own_hint():
    with pytest.raises(GCodeError, match=r"word G \(the letter O where the digit 0 was meant\?\)"):
        parse_program("G21\nGOO X1\n", context=MachineContext())
    prog = checked_iso("G21 G90\nN10 G0 X1\nM30\n", MachineContext())
    assert [b.target.tolist() for b in prog.blocks] == [[1.0, 0.0, 0.0]]


@pytest.mark.parametrize(("dialect", "what"), [
    ("grbl", r"M code 'M107' unknown to grbl \(gcode\.c: M0-M5, M7-M9, M30, M56 only; error 20\)"),
    ("linuxcnc", r"user M code 'M107' \(M100-M199 runs the executable file M107 of the user M path"),
    ("haas", r"machine-specific M code 'M107' \(M100-M199 on a Haas control")])
def test_a_3d_printer_m_code_is_named_as_marlin_s(dialect, what):
    # a Marlin laser's file: "M107 S0" (fan off = laser off), "M106 S255" (fan on = laser on)
    text = "M107 S0\nG90 G21\nG1 F3000 X196.662 Y25.2978\nM106 S255\n"
    with pytest.raises(GCodeError, match=f":1:1: {what}.* \\(Marlin's M107 fan off: a 3D printer's code, which laser "
                                         r"conversions use for the laser\): M107 not found"):
        parse_program(text, context=MachineContext().with_dialect(dialect))


def test_a_user_m_code_of_no_printer_meaning_keeps_its_message():
    with pytest.raises(GCodeError, match=r":1:5: user M code 'M110' \(M100-M199 runs the executable file M110 of "
                                         r"the user M path, LinuxCNC USER_M_PATH\): M110 not found"):
        parse_program("G21 M110\nG0 X1\n", context=MachineContext())


def _with_radius(dialect: str, radius: float) -> MachineContext:
    return MachineContext(tools={2: Tool(number=2, length=0.0, radius=radius)}).with_dialect(dialect)


# A SolidWorks CAM post's profile for wear-only offsets: the path is the tool centre's, D002 holds the wear,
# and the start-up moves 0.0002 mm (from X-0.2522 to) before the contour turns up +Y.
WEAR_ONLY = ("G21 G90 G17\nM6 T2\nG0 X-0.2522 Y-3.3 Z4\nG1 Z-1 F60\nG41 D002 G1 X-0.252 F60.\nY3.3\nX-5\n"
             "G40 G1 X-5 Y4\nM30\n")


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_start_up_shorter_than_the_radius_runs_as_fanuc_type_a(dialect):
    # Fanuc cutter compensation C, start-up type A (parameter 5003#0 SUP = 0): the start-up block ends at the
    # vector perpendicular to the next block at its start point; Fanuc has no rule on the start-up's length
    prog = checked_iso(WEAR_ONLY, _with_radius(dialect, 0.02))
    ends = [b.target.tolist()[:2] for b in prog.blocks if b.kind == "line"]
    # left of +Y is -X: the start-up ends 0.02 to the left of (-0.252, -3.3); the turn onto -X is an inside
    # corner, where both offsets meet (-0.272, 3.28); the exit (G40) runs to the programmed (-5, 4)
    assert np.allclose(ends[1:], [[-0.272, -3.3], [-0.272, 3.28], [-5.0, 3.28], [-5.0, 4.0]], rtol=0, atol=1e-12)


def test_linuxcnc_keeps_its_entry_rule():
    # interp_convert.cc convert_straight_comp1: "Length of cutter compensation entry move is not greater than the
    # tool radius"
    with pytest.raises(GCodeError, match=r":5:1: G41 cutter radius compensation: length of cutter compensation "
                                         r"entry move \(0\.0002 mm\) is not greater than the tool radius \(0\.02 mm\)"):
        parse_program(WEAR_ONLY, context=_with_radius("linuxcnc", 0.02))
    long_entry = WEAR_ONLY.replace("Y-3.3 Z4", "Y-4.3 Z4").replace("X-0.252 F60.", "X-0.252 Y-3.3 F60.")  # 1 mm long
    ends = [b.target.tolist()[:2] for b in checked_iso(long_entry, _with_radius("linuxcnc", 0.02)).blocks
            if b.kind == "line"]
    assert ends[1][0] == pytest.approx(-0.252 - 0.02 * 1 / (1 + 0.0002 ** 2) ** 0.5, abs=1e-9)
