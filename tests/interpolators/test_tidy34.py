"""Places of the readers that share one home after tidy34, pinned by hand-written programs: the end of a TNC
cycle's run at a hole (out to the set-up clearance Q200, then to the 2nd set-up clearance Q204 when it is higher:
:func:`interpolators.heidenhain_cycles.to_second_clearance`); the ISO codes that read a P, LinuxCNC's drilling
cycles among them (:data:`interpolators.iso.LINUXCNC_CYCLE_WORDS`); cycle 22's rest machining naming its tools."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext
from interpolators.parse import parse_program

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})
LINUXCNC = MachineContext().with_dialect("linuxcnc")
TOOL = "TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+10 Y+20 Z+50 R0 FMAX\n"

#: One definition of each cycle whose run ends at the clearances, written from the TNC 640 cycle programming
#: manual's parameter lists; ``{s}`` the surface Q203, ``{c2}`` the 2nd set-up clearance Q204 (Q200 = 2).
CYCLES = {
    "200 hole_moves": "CYCL DEF 200 DRILLING Q200=2 Q201=-10 Q206=120 Q202=4 Q210=0 Q203={s} Q204={c2} Q211=0",
    "203 hole_moves, out at Q208": "CYCL DEF 203 UNIVERSAL DRILLING Q200=2 Q201=-10 Q206=120 Q202=4 Q210=0 Q203={s} "
                                   "Q204={c2} Q212=0 Q213=0 Q205=0 Q211=0 Q208=500 Q256=0.2",
    "204 back_boring_moves": "CYCL DEF 204 BACK BORING Q200=2 Q249=+5 Q250=20 Q251=3.5 Q252=3 Q253=MAX Q254=200 "
                             "Q255=0 Q203={s} Q204={c2} Q214=1 Q336=0",
    "208 _bore_milling": "CYCL DEF 208 BORE MILLING Q200=2 Q201=-10 Q206=150 Q334=5 Q203={s} Q204={c2} Q335=16 "
                         "Q342=0 Q351=-1",
    "241 single_lip_moves": "CYCL DEF 241 SINGLE-LIP DEEP-HOLE DRILLING Q200=2 Q201=-40 Q206=50 Q211=0 Q203={s} "
                            "Q204={c2} Q379=0 Q253=750 Q208=1000 Q426=3 Q427=50 Q428=1790 Q429=8 Q430=9 Q435=0",
    "252 _circular_pocket": "CYCL DEF 252 CIRCULAR POCKET Q215=0 Q223=20 Q368=0 Q207=500 Q351=+1 Q201=-5 Q202=2.5 "
                            "Q369=0 Q206=150 Q338=0 Q200=2 Q203={s} Q204={c2} Q370=1 Q366=0 Q385=400",
    "256 _rectangular_stud": "CYCL DEF 256 RECTANGULAR STUD Q218=20 Q424=26 Q219=10 Q425=14 Q220=0 Q368=0 Q224=0 "
                             "Q367=0 Q207=500 Q351=+1 Q201=-2 Q202=2 Q206=150 Q200=2 Q203={s} Q204={c2} Q370=1 "
                             "Q215=0 Q369=0 Q338=0 Q385=400",
    "262 _thread_milling": "CYCL DEF 262 THREAD MILLING Q335=+12 Q239=+1.5 Q201=-6 Q355=0 Q253=750 Q351=+1 Q200=2 "
                           "Q203={s} Q204={c2} Q207=300",
}


def _tail(cycle: str, *, surface: float, second: float) -> list[tuple[str, float]]:
    """The kinds and Z levels of the moves after the cycle's last move below the set-up clearance, one per level (204
    moves back over the centre in the plane at the set-up clearance)."""
    text = "0 BEGIN PGM T MM\n" + TOOL + cycle.format(s=f"{surface:+g}", c2=f"{second:g}") + "\nCYCL CALL\n"
    prog = parse_program(text + "END PGM T MM\n", context=CTX)
    moves = [(b.kind, float(b.target[2])) for b in prog.blocks]
    last_low = max(i for i, (_, z) in enumerate(moves) if z < surface + 2 - 1e-9)
    tail = moves[last_low + 1:]
    return [mv for k, mv in enumerate(tail) if k == 0 or mv[1] != tail[k - 1][1]]


@pytest.mark.parametrize("name", sorted(CYCLES))
@pytest.mark.parametrize("surface", [0.0, -7.5])
def test_a_cycle_ends_at_the_set_up_clearance_then_at_the_higher_2nd_one(name, surface):
    tail = _tail(CYCLES[name], surface=surface, second=20.0)
    # 203 retracts at Q208, 241 at its Q208 (a feed move), the others at FMAX; then FMAX to Q203 + Q204
    assert [z for _, z in tail] == pytest.approx([surface + 2, surface + 20])
    assert tail[-1][0] == "rapid"


@pytest.mark.parametrize("name", sorted(CYCLES))
@pytest.mark.parametrize("second", [0.0, 2.0])
def test_a_2nd_set_up_clearance_not_above_the_set_up_clearance_adds_no_move(name, second):
    tail = _tail(CYCLES[name], surface=0.0, second=second)
    assert [z for _, z in tail] == pytest.approx([2.0])


# LinuxCNC's drilling cycles that read P (interpolators.iso.LINUXCNC_CYCLE_WORDS) are among the codes that own a
# block's P, so a G8 beside them is LinuxCNC's lathe radius mode, not Fanuc's G08 P1 look-ahead (rs274ngc
# interp_check.cc check_other_codes: "P word with no G2 G3 G4 G10 G64 G5 G5.2 G6, G6.2, G76 G82 G86 G88 G89 ...")
@pytest.mark.parametrize(("spindle", "cycle", "kinds"), [
    ("M3", "G82", ["line", "dwell", "rapid"]), ("M3", "G84", ["line", "dwell", "line"]),
    ("M4", "G74", ["line", "dwell", "line"]), ("M3", "G89", ["line", "dwell", "line"]),
])
def test_g8_beside_a_drilling_cycle_that_reads_p_is_the_lathe_radius_mode(spindle, cycle, kinds):
    from interpolators.iso import LINUXCNC_CYCLE_WORDS

    assert int(cycle[1:]) * 10 in LINUXCNC_CYCLE_WORDS["P"]
    text = f"G21 G90 G17 G0 Z5\n{spindle} S500\nG8 {cycle} X1 Y1 Z-1 R1 P0.5 F100\nG80\nM2\n"
    prog = parse_program(text, context=LINUXCNC)
    assert [b.kind for b in prog.blocks][-3:] == kinds
    assert any(n.startswith("G8 lathe radius mode") for n in prog.notes)


def test_g8_beside_a_drilling_cycle_that_reads_no_p_is_named_as_fanucs_look_ahead():
    from vcnc.errors import GCodeError

    with pytest.raises(GCodeError, match=r":3:1: G8 lathe radius mode: not supported \(G08 P1 / P0 with a P is "):
        parse_program("G21 G90 G17 G0 Z5\nM3 S500\nG8 G81 X1 Y1 Z-1 R1 P0.5 F100\nG80\nM2\n", context=LINUXCNC)


# cycle 22 ROUGH-OUT with Q18 (TNC 426/430 user's manual, "ROUGH-OUT (Cycle 22)": Q18 the coarse roughing tool,
# 0: none): the tool of the TOOL CALL before the cycle call machines what Q18's tool left, so Q18's tool must be
# the larger one; the error names both
ROUGH_22 = ("0 BEGIN PGM T MM\n1 TOOL DEF 2 L+0 R+1\n2 TOOL CALL 1 Z S1000\n3 L Z+100 R0 FMAX\n"
            "4 CYCL DEF 14.0 CONTOUR\n5 CYCL DEF 14.1 CONTOUR LABEL 1\n"
            "6 CYCL DEF 20 CONTOUR DATA Q1=-10 Q2=+1 Q3=+0.5 Q4=+0.5 Q5=+0 Q6=+2 Q7=+50 Q8=+0 Q9=+1\n"
            "7 CYCL DEF 22 ROUGH-OUT Q10=-5 Q11=100 Q12=350 Q18={q18} Q19=150\n8 CYCL CALL\n9 M30\n10 LBL 1\n"
            "11 L X+0 Y+0 RL\n12 L X+40 Y+0\n13 L X+40 Y+30\n14 L X+0 Y+30\n15 L X+0 Y+0\n16 LBL 0\nEND PGM T MM\n")


@pytest.mark.parametrize("q18", [2, 7])  # tool 2: R 1 mm, smaller than tool 1; tool 7: in no TOOL DEF or table
def test_rest_machining_22_names_the_tool_called_for_it_when_q18_is_no_larger(q18):
    from interpolators.context import Tool
    from vcnc.errors import GCodeError

    ctx = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})
    with pytest.raises(GCodeError, match=rf":9:3: cycle 22: the coarse roughing tool Q18 = {q18} has no radius "
                                         r"larger than that of tool 1 \(3 mm\), the rest-machining tool"):
        parse_program(ROUGH_22.format(q18=q18), context=ctx)


def test_cycle_220_q365_1_under_axis_specific_scaling_names_the_pattern_block():
    # Machine.lengths with the pattern's block: the error stands at cycle 220's definition (block 6 on line 7, after its
    # block number), names what needs the plane's one factor and what cycle 26 did
    from vcnc.errors import GCodeError

    text = ("0 BEGIN PGM T MM\n1 TOOL DEF 1 L+0 R+2\n2 TOOL CALL 1 Z S1000\n3 CYCL DEF 26.0 AXIS-SPECIFIC SCALING\n"
            "4 CYCL DEF 26.1 X1.5 Y1\n5 CYCL DEF 200 DRILLING Q200=2 Q201=-5 Q206=150 Q202=5 Q210=0 Q203=+0 Q204=10 "
            "Q211=0\n6 CYCL DEF 220 POLAR PATTERN Q216=+50 Q217=+50 Q244=80 Q245=+0 Q246=+360 Q247=+0 Q241=4 "
            "Q200=2 Q203=+0 Q204=10 Q301=0 Q365=1\n7 END PGM T MM\n")
    with pytest.raises(GCodeError) as err:
        parse_program(text, context=CTX)
    assert str(err.value).startswith(
        "<input>:7:3: cycle 220 Q365=1 (arcs on the pitch circle) under axis-specific scaling 1.5 and 1 in the working "
        "plane distorts arcs (got 'CYCL DEF 220 POLAR PATTERN")
    assert str(err.value).endswith("expected the same factor for both axes of the working plane (cycle 26)")
