"""Heidenhain coordinate transformation cycles 8, 10, 11, 26 (and the cycle 19 reset): hand-written
programs with end points worked out by hand, each also checked against the independent reference
(``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n"
CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, 10.0)}, tools={1: Tool(number=1, length=30.0)},
                     home=(0.0, 0.0, 300.0))


def run(body: str, context: MachineContext = CTX):
    """The program run by the reader, after checking it against the reference block by block."""
    text = HEAD + body + "\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    assert match.exact + match.within == len(prog.blocks)
    return prog


def ends(prog, origin=(100.0, 50.0, 40.0)):
    """End points in program coordinates (preset and tool length taken off) [mm]."""
    return np.round([np.asarray(b.target) - origin for b in prog.blocks], 9).tolist()


def test_rotation_turns_lines_and_arcs_about_the_datum():
    prog = run("TOOL CALL 1 Z\nL X+0 Y+0 Z+0 R0 F100\nCYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+10\n"
               "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+90\nL X+10 Y+0\nCC X+0 Y+0\nC X+0 Y+10 DR+\n"
               "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 IROT-45\nL X+2 Y+0\nCYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+0\n"
               "L X+0 Y+0")
    s = 2 ** 0.5
    # about the shifted datum (10, 0): (10, 0) -> (10, 10); the arc (0, 10) -> (0, 0) counter-clockwise
    assert ends(prog) == [[0, 0, 0], [10, 10, 0], [0, 0, 0], pytest.approx([10 + s, s, 0]), [10, 0, 0]]
    assert prog.blocks[2].segment.ccw and np.allclose(prog.blocks[2].segment.center[:2], [110, 50])


def test_mirror_image_reverses_arcs_and_keeps_rotation_inside_the_mirror():
    prog = run("L X+10 Y+5 Z+0 R0 F100\nCYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X\nL X+10 Y+5\nCC X+10 Y+0\n"
               "C X+15 Y+0 DR+\nCP IPA+90 DR+\nCYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+90\nL X+10 Y+0\n"
               "CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X Y\nCYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+0\nL X+1 Y+2\n"
               "CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1\nL X+1 Y+2", context=MachineContext())
    b = prog.blocks
    assert ends(prog, origin=(0, 0, 0)) == [[10, 5, 0], [-10, 5, 0], [-15, 0, 0], [-10, 5, 0], [-0.0, 10, 0],
                                            [-1, -2, 0], [1, 2, 0]]
    assert not b[2].segment.ccw and not b[3].segment.ccw  # DR+ mirrored in one axis turns clockwise


def test_polar_moves_turn_and_mirror_with_the_coordinate_system():
    prog = parse_heidenhain(HEAD + "CC X+0 Y+0\nL X+10 Y+0 Z+0 R0 F100\nCYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+90\n"
                            "LP PR+10 PA+0\nCP IPA+90 DR+\nCYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 Y\nLP PR+5 PA+0\n"
                            "CP PA+90 DR+\nEND PGM T MM\n", source="t.h")
    b = prog.blocks
    # rotated: PA 0 -> 90 deg, (0, 10); IPA+90 -> (-10, 0); rotated then Y mirrored: PA 0 -> (0, -5),
    # PA 90 -> rotated (-5, 0), mirrored (-5, 0), reached clockwise (DR+ mirrored once)
    assert np.allclose([x.target[:2] for x in b[1:]], [[0, 10], [-10, 0], [0, -5], [-5, 0]], atol=1e-12)
    assert b[2].segment.ccw and not b[4].segment.ccw and abs(b[4].segment.sweep) == pytest.approx(np.pi / 2)


def test_scaling_and_axis_specific_scaling():
    prog = run("TOOL CALL 1 Z\nL X+0 Y+0 Z+10 R0 F100\nCYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 0.5\n"
               "L X+10 Y+20 Z+4\nCC X+0 Y+20\nC X-10 Y+20 DR-\nCYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 1\n"
               "CYCL DEF 26.0 AXIS-SPECIFIC SCALING\nCYCL DEF 26.1 X2 CCX+10\nL X+20 Y+4\n"
               "CYCL DEF 26.0 AXIS-SPECIFIC SCALING\nCYCL DEF 26.1 X1\nL X+20")
    assert ends(prog) == [[0, 0, 10], [5, 10, 2], [-5, 10, 2], [30, 4, 2], [20, 4, 2]]


def test_drilling_under_scaling_scales_the_cycle_depths():
    prog = run("L X+0 Y+0 Z+50 R0 FMAX\nCYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 2\n"
               "CYCL DEF 200 DRILLING Q200=+2 Q201=-5 Q206=+100 Q202=+5 Q210=+0 Q203=+0 Q204=+10 Q211=0\n"
               "L X+5 Y+5 FMAX M99", context=MachineContext())
    zs = [b.target[2] for b in prog.blocks]
    assert zs == [50, 50, 4, -10, 4, 20]  # surface 0, clearance 2 x 2, depth 2 x -5, 2nd clearance 2 x 10


def test_radius_compensation_swaps_sides_under_a_mirror():
    ctx = MachineContext(tools={2: Tool(number=2, length=0.0, radius=1.0)})
    prog = run("TOOL CALL 2 Z\nL X+0 Y-5 Z+0 R0 FMAX\nCYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X\n"
               "L X+0 Y+0 RL F100\nL X+10 Y+0\nL X+10 Y+10 R0", context=ctx)
    # program: along +X with the tool left (above, y = +1); mirrored the path runs along -X and the
    # tool stays on the mirror image's side, y = +1
    assert prog.blocks[2].target[1] == pytest.approx(1.0)
    assert prog.blocks[2].target[0] == pytest.approx(-10.0)


def test_cycle_247_selects_a_work_offset_of_the_context_as_the_preset():
    # and resets the datum shift and the transformations (TNC 640 cycle manual, cycle 247)
    ctx = MachineContext(work_offsets={"G54": (100.0, 0.0, 0.0), "G55": (0.0, 200.0, 0.0), "G59.1": (0.0, 0.0, -5.0)})
    prog = run("L X+1 Y+1 Z+1 R0 FMAX\nCYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+50\nCYCL DEF 10.0 ROTATION\n"
               "CYCL DEF 10.1 ROT+90\nCYCL DEF 247 DATUM SETTING ~\n  Q339=+2 ;DATUM NUMBER\nL X+1 Y+1 Z+1 FMAX\n"
               "CYCL DEF 247 DATUM SETTING\n  Q339=+7\nL X+1 Y+1 Z+1 FMAX\nCYCL DEF 247 Q339=+0\nL X+1 Y+1 Z+1 FMAX\n"
               # a row beyond the context's nine work offsets (a shop's "Q339=+15"): zero, as G54 without an entry
               "CYCL DEF 247 Q339=+15\nL X+1 Y+1 Z+1 FMAX",
               context=ctx)
    assert ends(prog, origin=(0, 0, 0)) == [[101, 1, 1], [1, 201, 1], [1, 1, -4], [101, 1, 1], [1, 1, 1]]
    assert any(n.startswith("CYCL DEF 247 Q339=15: preset 15 is beyond") for n in prog.notes)


def test_cycle_19_reset_is_no_motion_and_tilts_are_errors():
    prog = run("L X+1 Y+1 Z+1 R0 F100\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 A+0 B+0 C+0\nL X+2",
               context=MachineContext())
    assert len(prog.blocks) == 2


def test_trans_functions_are_the_transformation_cycles():
    prog = run("L X+0 Y+0 Z+0 R0 F100\nTRANS DATUM AXIS X+10 Y+5\nL X+0 Y+0\nTRANS DATUM AXIS IX+1\nL X+0 Y+0\n"
               "TRANS ROTATION ROT+90\nL X+1 Y+0\nTRANS MIRROR AXIS Y\nL X+1 Y+0\nTRANS SCALE SCL2\nL X+1 Y+0\n"
               "TRANS SCALE RESET\nTRANS MIRROR RESET\nTRANS ROTATION RESET\nTRANS DATUM RESET\nL X+1 Y+0",
               context=MachineContext())
    # rotation first, then the mirror of Y: (1, 0) -> (0, 1) -> (0, -1), about the datum (11, 5)
    assert ends(prog, origin=(0, 0, 0)) == [[0, 0, 0], [10, 5, 0], [11, 5, 0], [11, 6, 0], [11, 4, 0], [11, 3, 0],
                                            [1, 0, 0]]


def test_plane_reset_and_zero_angles_are_no_motion():
    prog = run("L X+1 Y+1 Z+1 R0 F100\nPLANE RESET STAY\nPLANE SPATIAL SPA+0 SPB+0 SPC+0 TURN MB MAX FMAX SEQ+\n"
               "FUNCTION RESET TCPM\nL X+2", context=MachineContext())
    assert len(prog.blocks) == 2 and any("PLANE RESET" in n for n in prog.notes)


def test_tool_def_alone_preselects_and_tool_call_by_name():
    ctx = MachineContext(tools={3: Tool(number=3, length=50.0)})
    prog = parse_heidenhain(HEAD + "TOOL CALL 3 Z\nTOOL DEF 4\nL X+0 Y+0 Z+0 R0 FMAX\nTOOL CALL \"MILL_D10\" Z S3000 "
                            "DL+0.5\nL Z+0 FMAX\nEND PGM T MM\n", source="t.h", context=ctx)
    assert [b.target[2] for b in prog.blocks] == [50.0, 0.5]
    assert any('"MILL_D10"' in n for n in prog.notes)


@pytest.mark.parametrize("body, words", [
    ("PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX", "PLANE SPATIAL (a tilted working plane) is not supported"),
    ("PLANE VECTOR BX+1 BY+0 BZ+0 NX+0 NY+0 NZ+1 STAY", "PLANE VECTOR"),
    ("FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS", "FUNCTION TCPM (TCPM, tool centre point management) needs"),
    ("L X+0 Y+0 R0 FMAX M128", "M128 (TCPM"),
    ("TRANS DATUM TABLE TABLINE 3", "TRANS DATUM TABLE: row 3 of the datum table is not known"),
    ("CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 Z", "MIRROR IMAGE of the tool axis Z"),
    ("CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 0", "SCL must be > 0"),
    ("CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 45", "cycle 10 ROTATION without ROT"),
    ("CYCL DEF 26.0 AXIS\nCYCL DEF 26.1 X2\nL X+0 Y+0 R0 F100\nCC X+5 Y+0\nC X+10 Y+0 DR+", "distorts arcs"),
    # cycle 10 under RL/RR cancels it (the cycle manuals; tncwild40): scaling stays an error
    ("L X+0 Y+0 RL F100\nCYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 0.5", "while radius compensation RL"),
    ("CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+45", "cycle 19 WORKING PLANE"),
    ("CYCL DEF 18.0 THREAD CUTTING", "cycle 18 THREAD CUTTING (spindle-synchronised"),
    ("CYCL DEF 3.0 SLOT MILLING\nCYCL DEF 3.1 SET UP 2", "cycle 3 SLOT MILLING (the old cycle: no manual page"),
    ("CYCL DEF 258 POLYGON STUD Q573=+0 Q571=+50", "cycle 258 POLYGON STUD (the manual found"),
    ("CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 #5", "row 5 of the datum table is not known (the machine context has no"),
    ("CYCL DEF 247 DATUM SETTING Q339=+1.5", "cycle 247: preset 1.5 is not a row of the preset table"),
])
def test_errors_name_the_cycle(body, words):
    with pytest.raises(GCodeError) as info:
        parse_heidenhain(HEAD + body + "\nEND PGM T MM\n", source="t.h")
    assert words in str(info.value)
    assert info.value.file == "t.h" and info.value.line >= 2
