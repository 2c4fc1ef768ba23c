"""Heidenhain forms the post processors write that vcnc refused or ran otherwise than a TNC (session 36). Each
program is hand-written in the style of the post it names (repository, path) and checked against the independent
reference (``reference_heidenhain``), its end points worked out by hand where they say more."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis, Solution
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})
LENGTH = 20.0
#: A table tilting about Y round (0, 0, -50) (B) and turning about Z (C), as in test_tcp5x.
BC = Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)), RotaryAxis(name="c")))
TNC5X = MachineContext(extra_axes=("b", "c"), kinematics=BC, tools={1: Tool(number=1, length=LENGTH)},
                       work_offsets={"G54": (10.0, 5.0, 0.0)})


def checked(body: str, context: MachineContext = CTX):
    """The reader's program of ``body`` in a BEGIN/END PGM frame, every block checked against the reference."""
    return checked_program("0 BEGIN PGM 1001 MM\n" + body + "END PGM 1001 MM\n", context, exact=False)


def machine(kin: Kinematics, part, angles: Solution) -> np.ndarray:
    """Where the machine's linear axes put the tool holder for the tip at ``part`` (tool length added)."""
    return np.asarray(kin.place(np.asarray(part, float), angles)) + [0.0, 0.0, LENGTH]


# -- Autodesk Fusion heidenhain.cps (OpenPostProject/heidenhain, heidenhain.cps) -------------------------------------

def test_fusion_ln_with_the_tool_orientation_alone_turns_the_axes_and_keeps_the_point():
    # onLinear5D / onRapid5D without a machine configuration: "LN" + X Y Z + TX TY TZ + R0 + F, no NX NY NZ. TNC 620
    # user's manual 81760x-02, 12.6 "Block format with tool orientation": LN X Y Z TX TY TZ; under R0 the point is
    # not displaced. T = (sin 30, 0, cos 30) is B+30 C+0; the tip at (30, 0, 0) on the part. Refused before as
    # 'LN without a surface-normal vector'.
    prog = checked("1 TOOL CALL 1 Z S8000\n2 L X+0 Y+0 Z+50 R0 FMAX\n3 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS\n"
                   "4 LN X+10 Y+0 Z+20 TX+0 TY+0 TZ+1 R0 FMAX\n"
                   "5 LN X+30 Y+0 Z+0 TX+0.5 TY+0 TZ+0.8660254 R0 F600\n6 FUNCTION RESET TCPM\n", TNC5X)
    last = [b for b in prog.blocks if b.number == 5][-1]
    assert last.extra_target[1:3] == pytest.approx([30.0, 0.0], abs=1e-6)
    assert last.target == pytest.approx(machine(BC, [40.0, 5.0, 0.0], Solution(30.0, 0.0)), abs=1e-6)


def test_fusion_ln_with_the_tool_orientation_without_tcpm_is_a_line_to_the_point():
    # without M128 / FUNCTION TCPM the TNC ignores T (iTNC 530 user's manual, "3-D compensation without tool
    # orientation"): a line to X Y Z, the tool length 10 added along Z
    prog = checked("1 TOOL CALL 1 Z S8000\n2 L X+0 Y+0 Z+50 R0 FMAX\n3 LN X+5 Y+6 Z+7 TX+0 TY+0 TZ+1 R0 F1000\n")
    assert prog.blocks[-1].target == pytest.approx([5.0, 6.0, 17.0])


def test_ln_with_the_tool_orientation_under_rl_names_the_3d_radius_compensation():
    # the peripheral milling form under RL/RR (here from the L before it) displaces the tool square to motion and
    # tool: not modelled
    with pytest.raises(GCodeError, match="3-D radius compensation"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+5 R0 FMAX\n3 L X+5 RL F100\n"
                         "4 LN X+10 Y+0 Z+0 TX+0 TY+0 TZ+1 F100\n5 END PGM T MM\n", source="t.h", context=CTX)


@pytest.mark.parametrize("angles, direction", [
    ("B+20 C+0", [np.sin(np.radians(20)), 0.0, np.cos(np.radians(20))]),  # SPB+20 turns +Z toward +X
    ("A+20", [0.0, -np.sin(np.radians(20)), np.cos(np.radians(20))]),  # SPA+20: about X, on a B/C table too
])
def test_function_tcpm_axis_spat_reads_a_b_c_as_spatial_angles(angles, direction):
    # HSMWorks' generic Heidenhain post (2011, 'FUNCTION TCPM F TCP AXIS SPAT PATHCTRL AXIS', then its 5-axis lines
    # L X Y Z A B C) and NX TNC posts: AXIS SPAT was refused ('is not modelled'). TNC7 basic user's manual
    # 81762x-19: spatial angles "define the angle of the tool relative to the workpiece"; PLANE SPATIAL's rotations,
    # A about X, then B about Y, then C about Z, of the tool axis +Z. The table turns the part so that this direction
    # is the spindle's: rotation(B, C) @ direction = +Z; the tip stays on the programmed point.
    prog = checked("1 TOOL CALL 1 Z S8000\n2 L X+0 Y+0 Z+50 R0 FMAX\n3 FUNCTION TCPM F TCP AXIS SPAT PATHCTRL AXIS\n"
                   f"4 L X+10 Y+0 Z+5 {angles} F1000\n5 FUNCTION RESET TCPM\n", TNC5X)
    last = [b for b in prog.blocks if b.number == 4][-1]
    b, c = last.extra_target[1:3]
    assert BC.rotation(Solution(b, c)) @ np.array(direction) == pytest.approx([0.0, 0.0, 1.0], abs=1e-9)
    assert last.target == pytest.approx(machine(BC, [20.0, 5.0, 5.0], Solution(b, c)), abs=1e-6)


def test_function_tcpm_axis_spat_names_an_incremental_angle():
    with pytest.raises(GCodeError, match="'IB\\+5' under FUNCTION TCPM AXIS SPAT"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 FUNCTION TCPM F TCP AXIS SPAT PATHCTRL AXIS\n"
                         "3 L X+0 IB+5 F100\n4 END PGM T MM\n", source="t.h", context=TNC5X)


def test_fusion_file_functions_after_a_probing_cycle_move_nothing():
    # onCyclePoint of a probing cycle with printResults: "FUNCTION FILECOPY" "TCHPRnnn.TXT" TO "<comment>" and
    # "FUNCTION FILEDELETE" (the TNC 640 user's manual's file functions). Refused before as 'FUNCTION FILECOPY is
    # not supported' with a hint about TCPM.
    prog = checked("1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+50 R0 FMAX\n"
                   '3 FUNCTION FILECOPY "TNC:\\TCHPR427.TXT" TO "TNC:\\PART1.TXT"\n'
                   '4 FUNCTION FILEDELETE "TNC:\\TCHPR427.TXT"\n5 L X+10 FMAX\n')
    assert [list(b.target) for b in prog.blocks] == [[0.0, 0.0, 60.0], [10.0, 0.0, 60.0]]
    assert any("FUNCTION FILECOPY" in n for n in prog.notes)


def test_an_unknown_function_names_the_functions_vcnc_runs():
    with pytest.raises(GCodeError, match="FUNCTION MODE is not supported.*FILECOPY"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 FUNCTION MODE TURN\n2 END PGM T MM\n", source="t.h", context=CTX)


# -- leftovers of session 35 --------------------------------------------------------------------------------------

def test_pattern_def_pat1_on_a_line_of_its_own_without_a_tilde():
    # 'PATTERN DEF' / 'PAT1 (..)' on the next line without '~', as the POSn lines of older TNCs (iTNC 530 cycle
    # examples): it was refused as "unknown or unsupported block 'PAT1'". The grid of test_heidenhain_sl35.
    prog = checked("1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+50 R0 FMAX\n3 PATTERN DEF\n"
                   "PAT1 (X+10 Y+20 DX+5 DY+8 NUMX3 NUMY2 ROT+0 ROTX+0 ROTY+0 Z+0)\n"
                   "4 CYCL DEF 200 DRILLING Q200=+2 Q201=-5 Q206=+150 Q202=+5 Q210=+0 Q203=+0 Q204=+10 Q211=+0\n"
                   "5 CYCL CALL PAT FMAX\n")
    drilled = [b.target[:2].tolist() for b in prog.blocks if b.target[2] < b.start[2] and b.kind != "rapid"
               and np.allclose(b.target[:2], b.start[:2])]
    assert drilled == [[10, 20], [15, 20], [20, 20], [20, 28], [15, 28], [10, 28]]


def test_a_probed_datum_written_to_the_datum_table_in_a_tilted_plane():
    # TCH PROBE 412 with Q303=0 writes row Q305 of the datum table: "The reference system is the active workpiece
    # coordinate system" (iTNC 530 cycle manual 15.6, Q303), here the plane of PLANE SPATIAL SPB+30; it was refused
    # as 'writing row 3 of a table'. Cycle 7 #3 in the same plane then puts the probed centre (10, 5) at Q331, Q332
    # = (2, -1): X+2 Y-1 after it is where X+10 Y+5 was before.
    prog = checked("1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+100 R0 FMAX\n3 PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN FMAX\n"
                   "4 L X+10 Y+5 Z+20 R0 FMAX\n"
                   "5 TCH PROBE 412 DATUM INSIDE CIRCLE Q321=+10 Q322=+5 Q262=+20 Q325=+0 Q247=+90 Q261=-5 Q320=+2 "
                   "Q260=+20 Q301=+0 Q305=+3 Q331=+2 Q332=-1 Q303=+0 Q381=+0 Q423=+4 Q365=+1\n"
                   "6 CYCL DEF 7.0 DATUM SHIFT\n7 CYCL DEF 7.1 #3\n8 L X+2 Y-1 Z+20 R0 FMAX\n", TNC5X)
    before, after = (next(b for b in prog.blocks if b.number == n) for n in (4, 8))
    assert after.target == pytest.approx(before.target, abs=1e-9)
    assert after.extra_target[1] == pytest.approx(30.0)


def test_nx_plane_relativ_chain_is_checked_by_the_reference():
    # An NX TNC post (its PLANE RELATIV list: "PLANE RELATIV $res TURN MB MAX FMAX", then TRANS DATUM AXIS) turns the
    # active plane about its own axes; the reader ran it, the reference did not model it (now: the active plane
    # times the turn about its own X, Y or Z, iTNC 530 user's manual, "Incremental tilting: PLANE RELATIVE").
    # SPB+20 then RELATIV SPB+10 is SPB+30: the same machine point as PLANE SPATIAL SPB+30.
    relative = checked("1 TOOL CALL 1 Z S5000\n2 L X+0 Y+0 Z+100 R0 FMAX\n"
                       "3 PLANE SPATIAL SPA+0 SPB+20 SPC+0 TURN MB MAX FMAX\n4 PLANE RELATIV SPB+10 TURN MB MAX FMAX\n"
                       "5 L X+5 Y+0 Z+20 FMAX\n", TNC5X)
    direct = checked("1 TOOL CALL 1 Z S5000\n2 L X+0 Y+0 Z+100 R0 FMAX\n"
                     "3 PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN MB MAX FMAX\n5 L X+5 Y+0 Z+20 FMAX\n", TNC5X)
    assert relative.blocks[-1].target == pytest.approx(direct.blocks[-1].target, abs=1e-9)
    assert relative.blocks[-1].extra_target == pytest.approx(direct.blocks[-1].extra_target, abs=1e-9)
