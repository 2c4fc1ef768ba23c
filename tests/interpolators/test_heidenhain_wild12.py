"""Heidenhain programs of a twelfth wild set (Fusion posts for a Mikron VCP1000 / TNC 426, a Spinner U1530 /
TNC 620 and a Mikron WF41C / TNC 355, a DMU 60eVo shop's TNC 640 utilities, a C# engraving generator,
school programs in Czech, Polish, Italian, Spanish, Slovenian and German dialog, identification runs) and
the four open questions settled from the manuals: M140 at the end of its block (after the block's cycle),
M91 without tool length, 'DWELL.5', F9998. Each a hand-written program, checked against the independent
reference where it runs."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()
HOME = MachineContext(home=(0.0, 0.0, 300.0))
#: A B/C tilting table, B about Y with its pivot 50 mm below the part's zero, C about Z.
TILT = MachineContext(home=(0.0, 0.0, 300.0), extra_axes=("b", "c"),
                      kinematics=Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0),
                                                             limits=(-120.0, 120.0)), RotaryAxis(name="c"))))
DRILL = ("CYCL DEF 200 DRILLING ~\n Q200=+2 ;SET-UP CLEARANCE ~\n Q201=-10 ;DEPTH ~\n Q206=+150 ;FEED ~\n"
         " Q202=+10 ;PLUNGING DEPTH ~\n Q210=+0 ;DWELL TOP ~\n Q203=+0 ;SURFACE ~\n Q204=+15 ;2ND SET-UP ~\n"
         " Q211=+0 ;DWELL BOTTOM\n")


def checked(body: str, context: MachineContext = ZERO, *, exact: bool = True):
    """The program read, and its blocks matched against the reference (``exact=False``: radius-compensated rows
    within the tool radius)."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", context, exact=exact)


def rows(prog, line: int) -> list[tuple[str, list[float]]]:
    return [(b.kind, np.round(b.target, 6).tolist()) for b in prog.blocks if b.line == line]


def test_m140_in_a_cycle_call_block_retracts_after_the_cycle():
    # TNC 640 user's manual, "Retraction in the tool axis: M140": M140 is effective at the end of its block; a
    # Spinner U1530 (TNC 620) post writes 'CYCL CALL M140 MB MAX': the hole is drilled where the tool stands,
    # then the tool leaves upward (home z 300 stands in for the limit). vcnc retracted first and drilled from
    # nowhere near the part's clearance plane (the cycle's first move went down from z 300)
    prog = checked("TOOL CALL 12 Z S3000\nL X+20 Y+20 R0 FMAX\nL Z+15 R0 FMAX\n" + DRILL
                   + "L X+60 Y+20 R0 FMAX\nCYCL CALL M140 MB MAX", HOME)
    moves = rows(prog, 15)  # the CYCL CALL block (the cycle's lines 5-13 continued with '~')
    assert moves[0] == ("rapid", [60.0, 20.0, 2.0])
    assert ("line", [60.0, 20.0, -10.0]) in moves
    assert moves[-2:] == [("rapid", [60.0, 20.0, 15.0]), ("rapid", [60.0, 20.0, 300.0])]


def test_m140_beside_m99_retracts_after_the_called_cycle():
    # 'L X.. Y.. FMAX M99 M140 MB 50': both act at the block's end; the cycle is the block's machining, the
    # retract from it comes after (our reading: the manual orders no two functions of a block's end)
    prog = checked("TOOL CALL 12 Z S3000\nL X+20 Y+20 R0 FMAX\nL Z+15 R0 FMAX\n" + DRILL
                   + "L X+60 Y+20 R0 FMAX M99 M140 MB 50")
    moves = rows(prog, 14)
    assert moves[0] == ("rapid", [60.0, 20.0, 15.0])
    assert ("line", [60.0, 20.0, -10.0]) in moves
    assert moves[-1] == ("rapid", [60.0, 20.0, 65.0])


def test_m91_positions_without_the_tool_length_and_keeps_radius_compensation():
    # TNC 310 user's manual, 7.3 "Miscellaneous functions for coordinate data" (M91/M92): "Radius compensation
    # remains the same in blocks that are programmed with M91 or M92. The tool length, however, is not
    # compensated." A 100 mm tool: 'L Z-5 M91' puts the machine's Z (no length) at -5; a program Z+10 at 110;
    # 'L X+40 Y+0 RL M91' keeps the tool 5 mm left of its path
    tools = MachineContext(home=(0.0, 0.0, 300.0), tools={1: Tool(number=1, length=100.0, radius=5.0)})
    prog = parse_heidenhain("0 BEGIN PGM T MM\nTOOL CALL 1 Z S1000\nL X+0 Y+0 R0 FMAX\nL Z+10 R0 FMAX\n"
                            "L Z-5 R0 FMAX M91\nL Z+10 R0 FMAX\nL X+20 Y+0 RL F500\nL X+40 Y+0 RL M91\n"
                            "L X+60 Y+0 R0\nEND PGM T MM\n", source="t.h", context=tools)
    assert rows(prog, 5) == [("rapid", [0.0, 0.0, -5.0])]
    assert rows(prog, 6) == [("rapid", [0.0, 0.0, 110.0])]
    assert rows(prog, 8) == [("line", [40.0, 5.0, 110.0])]


@pytest.mark.parametrize(("item", "seconds"), [("DWELL.5", 0.5), ("DWELL .5", 0.5), ("DWELL 5", 5.0),
                                                ("DWELL5", 5.0), ("V.ZEIT2", 2.0), ("CZAS ZWL.0.5", 0.5)])
def test_dwell_written_without_a_blank(item, seconds):
    # 'CYCL DEF 9.1 DWELL.5': the TNC's English item name DWELL has no dot of its own, so the dot is the
    # number's (0.5 s, our reading); it read 5 s. An abbreviated name's dot (German V.ZEIT, Polish CZAS ZWL.)
    # still ends the name
    prog = checked(f"TOOL CALL 1 Z S1000\nL Z+10 R0 FMAX\nCYCL DEF 9.0 DWELL TIME\nCYCL DEF 9.1 {item}")
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == [pytest.approx(seconds)]


def test_old_pecking_cycle_item_with_its_decimal_point_after_the_name():
    # 'CYCL DEF 1.4 DWELL.5' in the old pecking cycle (TNC 355 form): half a second at the bottom, not 5
    prog = parse_heidenhain("0 BEGIN PGM T MM\nTOOL CALL 1 Z S1000\nL X+0 Y+0 Z+2 R0 FMAX\nCYCL DEF 1.0 PECKING\n"
                            "CYCL DEF 1.1 SET UP 2\nCYCL DEF 1.2 DEPTH -6\nCYCL DEF 1.3 PECKG 6\n"
                            "CYCL DEF 1.4 DWELL.5\nCYCL DEF 1.5 F100\nCYCL CALL\nEND PGM T MM\n", source="t.h",
                            context=ZERO)
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == [pytest.approx(0.5)]


def test_tnc355_post_f9998_is_a_feed_of_9998_mm_per_min():
    # the Fusion 'TNC 355' post (Mikron WF41C) writes its rapids as 'L .. R0 F9998': no TNC manual we could
    # search gives F9998/F9999 a meaning of its own; the control runs a line at the feed, limited by the
    # machine's maximum (our reading; FMAX is the TNC's rapid). A line at 9998 mm/min, not a rapid
    prog = checked("TOOL CALL 5 Z S630\nL X+20 Y+20 R0 F9998\nL Z+5 R0 F9999\nL Z-2 F80")
    moves = [(b.kind, round(b.feed * 60, 6)) for b in prog.blocks if b.kind != "dwell"]
    assert moves == [("line", 9998.0), ("line", 9999.0), ("line", 80.0)]


def test_empty_cycle_32_tolerance_item_resets_the_tolerance():
    # the Mikron VCP1000 (TNC 426) post cancels its tolerance with 'CYCL DEF 32.1' and no T (TNC 426 user's
    # manual, cycle 32 TOLERANCE: "cancel by ... entering tolerance 0"): no error, no motion
    prog = checked("TOOL CALL 3 Z S4000\nCYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1 T0.013\nL X+10 Y+0 Z+5 R0 FMAX\n"
                   "L X+20 F800\nCYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1\nL X+30")
    assert [b.target[0] for b in prog.blocks] == [pytest.approx(10.0), pytest.approx(20.0), pytest.approx(30.0)]


def test_f_auto_in_an_engraving_fragment_without_a_tool_call_names_the_missing_feed():
    # a C# engraving generator's letter files ('L Z-0.2 FAUTO') have no TOOL CALL: the control has no feed
    # for F AUTO; the error names what is missing
    with pytest.raises(GCodeError, match=r"t\.h:4:\d+: F AUTO without a feed in the TOOL CALL"):
        parse_heidenhain("0 BEGIN PGM T MM\nL X1.5 Y6.5 FMAX\nL Z2.0 FMAX\nL Z-0.2 FAUTO\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


@pytest.mark.parametrize(("mb", "z"), [("MB 50", 150.0), ("MB MAX", 300.0)])
def test_plane_turn_retracts_by_mb_before_the_table_turns(mb, z):
    # a Fusion post with useM140 writes 'PLANE SPATIAL .. TURN MB MAX FMAX' (TNC 640 user's manual, PLANE
    # positioning behaviour: MB retracts along the tool axis before the rotary axes turn); the reference now
    # holds it too: first the retract, then B to 30 with X, Y, Z standing
    prog = checked(f"TOOL CALL 3 Z S6000\nL X+0 Y+0 Z+100 R0 FMAX\nPLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN {mb} FMAX\n"
                   "L X-20 Y+0 R0 FMAX\nPLANE RESET TURN FMAX", TILT)
    turn = [b for b in prog.blocks if b.line == 4]
    assert [(b.kind, np.round(b.target, 6).tolist()) for b in turn] == [("rapid", [0.0, 0.0, z]),
                                                                        ("rapid", [0.0, 0.0, z])]
    assert turn[0].extra_target[1] == pytest.approx(0.0)
    assert turn[1].extra_target[1] == pytest.approx(30.0)


def test_old_circular_pocket_item_name_with_dots():
    # a Czech school program: 'CYCL DEF 5.1 BEZP.VZD. 2' (the dialog's abbreviated name for the set-up clearance);
    # the dots are the name's (as 'V.ZEIT' in cycle 9): clearance 2, first peck 5 down from the surface at z 0.
    # It was 'malformed number .VZD.'
    prog = checked("TOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z S1500\nL X+50 Y+50 R0 FMAX\nL Z+2 R0 FMAX\n"
                   "CYCL DEF 5.0 KRUHOVA KAPSA\nCYCL DEF 5.1 BEZP.VZD. 2\nCYCL DEF 5.2 HLOUBKA -10\n"
                   "CYCL DEF 5.3 PRISUV 5 F100\nCYCL DEF 5.4 RADIUS 20\nCYCL DEF 5.5 F300 DR+\nCYCL CALL")
    plunges = [b.target[2] for b in prog.blocks if b.line == 12 and b.kind == "line" and b.target[0] == 50.0
               and b.target[1] == 50.0]
    assert plunges[:2] == [pytest.approx(-5.0), pytest.approx(-10.0)]


def test_italian_pocket_depth_prof_is_no_feed():
    # 'CYCL DEF 4.2 PROF -8' (Italian dialog): PROF names the depth; its F is no feed word. The reader took it
    # so; the reference read F-8 as a feed and refused
    prog = checked("TOOL DEF 1 L+0 R+4\nTOOL CALL 1 Z S2000\nL X+50 Y+50 R0 FMAX\nL Z+2 R0 FMAX\n"
                   "CYCL DEF 4.0 FRESATURA TASCA\nCYCL DEF 4.1 DIST 2\nCYCL DEF 4.2 PROF -8\n"
                   "CYCL DEF 4.3 INCR 4 F80\nCYCL DEF 4.4 X+40\nCYCL DEF 4.5 Y+30\nCYCL DEF 4.6 F250 DR- RAGGIO 5\n"
                   "CYCL CALL")
    assert min(b.target[2] for b in prog.blocks) == pytest.approx(-8.0)


def test_compensated_arc_with_a_rounded_end_point_is_checked_with_that_slack():
    # an old TNC 355 style contour: 'C X+90 Y+62.679 DR- R F M' (62.6795 rounded) under RL with a 5 mm tool, then
    # down the line X+90: the inside corner is where the offset circle (radius 25) meets X+95, at Y+60. The
    # reference allowed no difference between the arc's start and end radii under RL and refused the 1.4e-5 mm
    prog = checked("TOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z S1000\nL X+40 Y+60 Z-5 R0 FMAX\nL X+60 Y+80 RL F300\n"
                   "CC X+80 Y+80\nC X+90 Y+62.679 DR- R F M\nL Y+10 R F M\nL X+120 Y+10 R0", exact=False)
    corner = [b.target for b in prog.blocks if b.line == 7]
    assert corner[-1][:2] == pytest.approx([95.0, 60.0], abs=1e-3)


def test_cycle_call_pos_checked_from_above_and_below_the_surface():
    # a Polish school program's 'CYCL CALL POS X+50 Y+50 Z+0 FMAX M3' now runs through the reference too (TNC 640
    # cycle programming manual, "Calling a cycle with CYCL CALL POS": Z the starting position and an additional
    # shift of Q203). From above (Z+100): over the point, then down to Z; from below (Z-5, after the first hole):
    # up to the 2nd set-up clearance 15 above the shifted surface 5 first, then over, then to Z+5
    prog = checked("TOOL CALL 12 Z S3000\nL X+0 Y+0 Z+100 R0 FMAX\n" + DRILL
                   + "CYCL CALL POS X+50 Y+50 Z+0 FMAX\nL Z-5 F100\nCYCL CALL POS X+20 Y+10 Z+5 F500")
    first, second = rows(prog, 13), rows(prog, 15)
    assert first[:2] == [("rapid", [50.0, 50.0, 100.0]), ("rapid", [50.0, 50.0, 0.0])]
    assert second[:3] == [("line", [50.0, 50.0, 20.0]), ("line", [20.0, 10.0, 20.0]), ("line", [20.0, 10.0, 5.0])]
    assert ("line", [20.0, 10.0, -5.0]) in second
