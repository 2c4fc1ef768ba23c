"""Heidenhain forms other CAM systems and shop floors write that vcnc refused or ran otherwise than a TNC (session
38). Each program is hand-written in the style of its source (a post, a real program, a manual's example) and
checked against the independent reference (``reference_heidenhain``), its values worked out by hand where they
say more."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})


def checked(body: str, context: MachineContext = CTX):
    """The reader's program of ``body`` in a BEGIN/END PGM frame, every block checked against the reference."""
    return checked_program("0 BEGIN PGM 1001 MM\n" + body + "END PGM 1001 MM\n", context, exact=False)


# -- Q-parameter formulas (iTNC 530 user's manual 60642x-04, 9.8 "Entering formulas directly") -------------------

def test_modulo_in_a_formula_is_the_division_remainder():
    # the manual's example "Q12 = 400 % 360 Result: Q12 = 40", as a shop's angle reduction; % binds as * and /
    # (2 * 250 % 360 = 500 % 360 = 140). Refused before as 'malformed formula'.
    prog = checked("1 TOOL CALL 1 Z S2000 F300\n2 L X+0 Y+0 Z+10 R0 FMAX\n3 Q12 = 400 % 360\n"
                   "4 Q13 = 2 * 250 % 360\n5 L X+Q12 Y+Q13\n")
    assert prog.blocks[-1].target == pytest.approx([40.0, 140.0, 20.0])


def test_modulo_by_zero_is_an_error_naming_it():
    with pytest.raises(GCodeError, match="modulo by zero"):
        parse_heidenhain("0 BEGIN PGM 1 MM\n1 Q2 = 0\n2 Q1 = 7 % Q2\n3 END PGM 1 MM\n", source="t.h", context=CTX)


def test_sgn_of_zero_is_one():
    # the manual: "Check algebraic sign of a number, Q12 = SGN Q50: If result for Q12 = 1, then Q50 >= 0; If result
    # for Q12 = -1, then Q50 < 0" (TNC 320, TNC 620 alike). A shop's direction switch 'Q7 = SGN Q6' on a zero
    # distance: +1, the line to X+10 (read 0 before, the line to X+0).
    prog = checked("1 TOOL CALL 1 Z S2000 F300\n2 L X+5 Y+0 Z+10 R0 FMAX\n3 Q6 = 0\n4 Q7 = SGN Q6\n"
                   "5 Q8 = SGN -0.001\n6 Q9 = 10 * Q7\n7 L X+Q9 Y+Q8\n")
    assert prog.blocks[-1].target == pytest.approx([10.0, -1.0, 20.0])


# -- TCPM in a tilted working plane (hyperMILL's and NX's TNC 640 posts: PLANE .. TURN, then TCPM on) --------------

BC = Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)), RotaryAxis(name="c")))
TNC5X = MachineContext(extra_axes=("b", "c"), kinematics=BC, tools={1: Tool(number=1, length=20.0)},
                       work_offsets={"G54": (10.0, 5.0, 0.0)}, home=(0.0, 0.0, 300.0))
TILTED = ("1 TOOL CALL 1 Z S10000\n2 L Z+200 R0 FMAX M91\n"
          "3 PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN MB MAX FMAX SEQ+ TABLE ROT\n")
LINES = "5 L X+10 Y+0 Z+50 R0 FMAX M3\n6 L Z+5 F2000\n7 L X+20 Y+5\n"


@pytest.mark.parametrize("on, off", [("4 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS\n", "8 FUNCTION RESET TCPM\n"),
                                     ("4 M128\n", "8 M129\n")])
def test_tcpm_in_a_tilted_plane_runs_its_still_lines_as_the_planes(on, off):
    # the program coordinates in the tilted plane are the tool tip with or without TCPM, which acts only when a
    # rotary axis moves (TNC 640 user's manual, "Inclined-tool machining in a tilted plane"): the same machine
    # points as the program without TCPM. Refused before: 'FUNCTION TCPM (TCPM) with a tilted working plane ...'.
    plain = checked(TILTED + LINES + "9 PLANE RESET TURN FMAX\n", TNC5X)
    prog = checked(TILTED + on + LINES + off + "9 PLANE RESET TURN FMAX\n", TNC5X)
    assert np.array([b.target for b in prog.blocks]) == pytest.approx(np.array([b.target for b in plain.blocks]))
    assert prog.blocks[-2].extra_target[:3] == pytest.approx([0.0, 30.0, 0.0])


def test_a_rotary_axis_moving_under_tcpm_in_a_tilted_plane_is_an_error_naming_it():
    text = ("0 BEGIN PGM 1 MM\n" + TILTED + "4 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS\n"
            "5 L X+10 Y+0 Z+50 B+35 R0 F1000\n6 END PGM 1 MM\n")
    with pytest.raises(GCodeError, match="rotary axis moving under M128 / FUNCTION TCPM in a tilted working plane"):
        parse_heidenhain(text, source="t.h", context=TNC5X)


# -- parallel axes (TNC7 basic user's manual 81762x-19, FUNCTION PARAXCOMP / PARAXMODE) ------------------------------

def test_the_parallel_axis_resets_and_display_move_nothing():
    # a post's header resets 'FUNCTION PARAXCOMP OFF' / 'FUNCTION PARAXMODE OFF', and PARAXCOMP DISPLAY (the W
    # travel summed into Z's display only) leave the lines as written. Refused before: 'FUNCTION PARAXCOMP is not
    # supported'.
    prog = checked("1 FUNCTION PARAXCOMP OFF\n2 FUNCTION PARAXMODE OFF\n3 TOOL CALL 1 Z S2000 F300\n"
                   "4 FUNCTION PARAXCOMP DISPLAY W\n5 L X+10 Y+0 Z+5 R0 FMAX\n6 FUNCTION PARAXCOMP OFF\n")
    assert prog.blocks[-1].target == pytest.approx([10.0, 0.0, 15.0])
    assert any("PARAXCOMP DISPLAY" in n for n in prog.notes)


@pytest.mark.parametrize("block, why", [("FUNCTION PARAXCOMP MOVE W", "main axis moving against the parallel"),
                                        ("FUNCTION PARAXMODE X Y W", "parallel axis machining in place")])
def test_what_moves_the_main_axes_by_a_parallel_axis_is_an_error_naming_it(block, why):
    with pytest.raises(GCodeError, match=why):
        parse_heidenhain(f"0 BEGIN PGM 1 MM\n1 {block}\n2 END PGM 1 MM\n", source="t.h", context=CTX)


# -- M130 (TNC 640 user's manual, "Moving to positions in a non-tilted coordinate system with a tilted working plane")

M130_BODY = ("1 TOOL CALL 1 Z S2000 F300\n2 L Z+200 R0 FMAX M91\n3 CYCL DEF 7.0 DATUM SHIFT\n4 CYCL DEF 7.1 X+10\n"
             "5 PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN FMAX\n6 CYCL DEF 7.0 DATUM SHIFT\n7 CYCL DEF 7.1 X+5\n"
             "8 L X+10 Y+0 Z+50 R0 FMAX\n9 L X+20 Z+50 R0 FMAX M130\n10 L IZ+10 R0 FMAX M130\n11 L X+12 Y+1 F500\n"
             "12 PLANE RESET TURN FMAX\n")


def test_m130_runs_its_line_in_the_untilted_coordinates():
    # a post's safe move in a tilted plane: 'L X+20 Z+50 R0 FMAX M130' goes to X+20 Z+50 of the untilted system,
    # the preset (work offset 10, 5, 0) plus the shift of before the tilt (X+10), the tool length 20 along Z:
    # (40, 5, 70) in the machine, whatever the plane and its own shift X+5; IZ+10 from there; the next line in the
    # tilted plane again. Ignored before ('M130 ignored (no motion)': the line ran to X+20 Z+50 of the plane).
    prog = checked(M130_BODY, TNC5X)
    by_line = {b.number: b for b in prog.blocks}
    assert by_line[9].target == pytest.approx([40.0, 5.0, 70.0])
    assert by_line[10].target == pytest.approx([40.0, 5.0, 80.0])
    assert by_line[9].extra_target[:3] == pytest.approx([0.0, 30.0, 0.0])
    assert any("M130" in n for n in prog.notes)


def test_m130_under_radius_compensation_is_an_error_naming_it():
    body = M130_BODY.replace("8 L X+10 Y+0 Z+50 R0 FMAX", "8 L X+10 Y+0 Z+50 RL F500")
    with pytest.raises(GCodeError, match="M130 .* with radius compensation RL/RR"):
        parse_heidenhain("0 BEGIN PGM 1 MM\n" + body + "13 END PGM 1 MM\n", source="t.h", context=TNC5X)


def test_the_feed_and_corner_m_functions_not_modelled_are_noted_as_such():
    # M116 (rotary feed in mm/min), M109/M110 (feed at the cutting edge on arcs), M97/M98 (compensated corners)
    # change the run on a TNC: the note says what is left out, not 'ignored (no motion)' (TNC 640 user's manual,
    # miscellaneous functions); in the fast path (plain lines) and the general one alike
    for body in ("1 TOOL CALL 1 Z S1000 F300\n2 L X+1 Y+0 Z+5 R0 FMAX M116\n3 L X+2 M109\n4 M98\n",
                 "1 TOOL CALL 1 Z S1000 F300\n2 CYCL DEF 10.0 ROTATION\n3 CYCL DEF 10.1 ROT+10\n"
                 "4 L X+1 Y+0 Z+5 R0 FMAX M116\n5 L X+2 M109\n6 M98\n"):
        prog = checked(body)
        notes = " ".join(prog.notes)
        assert "M116: the feed of rotary axes in mm/min (not modelled" in notes
        assert "M109/M110: the feed at the cutting edge" in notes and "M98: open contour corners" in notes
        assert "ignored (no motion)" not in notes


def test_an_ln_under_tcpm_in_a_tilted_plane_is_an_error_naming_it():
    # its tool orientation TX TY TZ would turn the rotary axes there (not modelled): named, not run as a line
    text = ("0 BEGIN PGM 1 MM\n" + TILTED + "4 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS\n"
            "5 LN X+10 Y+0 Z+5 TX+0 TY+0.5 TZ+0.8660254 R0 F1000\n6 END PGM 1 MM\n")
    with pytest.raises(GCodeError, match="LN under M128 in a tilted working plane"):
        parse_heidenhain(text, source="t.h", context=TNC5X)


def test_m130_without_a_tilted_plane_has_no_effect_noted_alike_in_both_paths():
    # the fast path (plain lines) and the general one (under cycle 10) word the note the same
    prog = checked("1 TOOL CALL 1 Z S1000 F300\n2 L X+1 Y+0 Z+5 R0 FMAX M130\n3 CYCL DEF 10.0 ROTATION\n"
                   "4 CYCL DEF 10.1 ROT+5\n5 L X+2 M130\n")
    assert prog.notes == ("M130 without a tilted working plane: no effect x2",)
