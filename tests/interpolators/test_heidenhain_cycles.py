"""Heidenhain machining cycles 201, 202, 206, 207, 209, 240 and the pattern cycles 220, 221: hand-written
programs with the tool-axis moves worked out by hand from the TNC 320 cycle programming manual, each
also checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S500\n2 L X+0 Y+0 Z+50 R0 FMAX\n"
CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})


def run(body: str):
    text = HEAD + body + "\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h", context=CTX)
    match = match_blocks(heidenhain_reference(text, CTX), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    assert match.exact == len(prog.blocks)
    return prog


def moves(prog):
    """(kind, x, y, z, feed [mm/min] or dwell [s]) after the first rapid."""
    return [(b.kind, *np.round(b.target, 6).tolist(), b.dwell if b.kind == "dwell" else round(b.feed * 60, 6))
            for b in prog.blocks[1:]]


def test_reaming_201_retracts_at_q208():
    prog = run("CYCL DEF 201 REAMING Q200=2 Q201=-10 Q206=100 Q211=0.5 Q208=200 Q203=+0 Q204=20\nL X+5 FMAX M99")
    assert moves(prog) == [("rapid", 5, 0, 50, math.inf), ("rapid", 5, 0, 2, math.inf), ("line", 5, 0, -10, 100),
                           ("dwell", 5, 0, -10, 0.5), ("line", 5, 0, 2, 200), ("rapid", 5, 0, 20, math.inf)]


def test_boring_202_moves_off_the_wall_before_the_retraction():
    prog = run("CYCL DEF 202 BORING Q200=2 Q201=-10 Q206=100 Q211=0 Q208=0 Q203=+0 Q204=20 Q214=4 Q336=0\nCYCL CALL")
    assert moves(prog) == [("rapid", 0, 0, 2, math.inf), ("line", 0, 0, -10, 100), ("rapid", 0, 0.2, -10, math.inf),
                           ("line", 0, 0.2, 2, 100), ("rapid", 0, 0, 2, math.inf), ("rapid", 0, 0, 20, math.inf)]


def test_tapping_206_and_rigid_tapping_207_feed_in_and_out():
    prog = run("CYCL DEF 206 TAPPING NEW Q200=2 Q201=-8 Q206=150 Q211=0.25 Q203=+0 Q204=5\nCYCL CALL\n"
               "CYCL DEF 207 RIGID TAPPING NEW Q200=2 Q201=-8 Q239=+1.25 Q203=+0 Q204=5\nCYCL CALL")
    assert moves(prog) == [("rapid", 0, 0, 2, math.inf), ("line", 0, 0, -8, 150), ("dwell", 0, 0, -8, 0.25),
                           ("line", 0, 0, 2, 150), ("rapid", 0, 0, 5, math.inf),
                           ("rapid", 0, 0, 2, math.inf), ("line", 0, 0, -8, 625), ("line", 0, 0, 2, 625),
                           ("rapid", 0, 0, 5, math.inf)]  # 207: S500 x 1.25 mm = 625 mm/min


def test_tapping_with_chip_breaking_209_backs_off_pitches():
    prog = run("CYCL DEF 209 TAPPING W/ CHIP BRKG Q200=2 Q201=-10 Q239=+1 Q203=+0 Q204=20 Q257=4 Q256=1 Q336=0 "
               "Q403=2\nCYCL CALL")
    zs = [(b.kind, b.target[2], round(b.feed * 60, 6)) for b in prog.blocks[1:]]
    assert zs == [("rapid", 2, math.inf), ("line", -4, 500), ("line", -3, 1000), ("line", -8, 500),
                  ("line", -7, 1000), ("line", -10, 500), ("line", 2, 1000), ("rapid", 20, math.inf)]


def test_polar_pattern_220_runs_centering_240_on_a_full_circle():
    prog = run("CYCL DEF 240 CENTERING Q200=2 Q343=0 Q201=-2 Q344=-9 Q206=100 Q211=0 Q203=+0 Q204=20\n"
               "CYCL DEF 220 POLAR PATTERN Q216=+50 Q217=+50 Q244=20 Q245=+0 Q246=+360 Q247=+0 Q241=4 Q200=2 "
               "Q203=+1 Q204=30 Q301=0 Q365=0")
    holes = [b.target[:2] for b in prog.blocks if b.kind == "line"]
    assert np.allclose(holes, [[60, 50], [50, 60], [40, 50], [50, 40]])
    zs = [b.target[2] for b in prog.blocks[1:]]
    # 2nd set-up clearance 1 + 30, over the first hole, down to the set-up clearance 3, depth -1, back to 3,
    # to the next hole at 3; after the last: 31
    assert zs == [31, 31, 3, -1, 3, 3, -1, 3, 3, -1, 3, 3, -1, 3, 31]


def test_cartesian_pattern_221_meanders_and_turns_about_its_start():
    prog = run("CYCL DEF 200 DRILLING Q200=2 Q201=-3 Q206=100 Q202=3 Q210=0 Q203=+0 Q204=30 Q211=0\n"
               "CYCL DEF 221 CARTESIAN PATTERN Q225=+10 Q226=+10 Q237=+10 Q238=+5 Q242=3 Q243=2 Q224=+90 "
               "Q200=2 Q203=+0 Q204=30 Q301=1")
    holes = [b.target[:2] for b in prog.blocks if b.kind == "line"]
    assert np.allclose(holes, [[10, 10], [10, 20], [10, 30], [5, 30], [5, 20], [5, 10]])
    plane = [b for b in prog.blocks[1:] if b.kind == "rapid" and not np.allclose(b.start[:2], b.target[:2])]
    assert len(plane) == 6 and all(b.start[2] == b.target[2] == 30 for b in plane)  # Q301=1: at the 2nd clearance


def test_bore_milling_208_helix_then_a_full_circle():
    prog = run("TOOL DEF 1 L+0 R+3\nTOOL CALL 1 Z S1000\nL X+10 Y+10 FMAX\n"
               "CYCL DEF 208 BORE MILLING Q200=2 Q201=-10 Q206=150 Q334=5 Q203=+0 Q204=20 Q335=16 Q342=0 Q351=-1\n"
               "CYCL CALL")
    b = prog.blocks[2:]
    a = math.radians(-360 * 12 / 5)  # 12 mm down at 5 mm per turn, clockwise (up-cut)
    assert [x.kind for x in b] == ["rapid", "line", "arc", "arc", "line", "rapid", "rapid"]
    assert np.allclose(b[1].target, [15, 10, 2])  # on the helix radius 8 - 3 along +X
    assert np.allclose(b[2].target, [10 + 5 * math.cos(a), 10 + 5 * math.sin(a), -10]) and not b[2].segment.ccw
    assert b[2].length == pytest.approx(math.hypot(2.4 * 2 * math.pi * 5, 12))
    assert np.allclose(b[3].target, b[2].target) and b[3].length == pytest.approx(2 * math.pi * 5)
    assert [x.target[2] for x in b[4:]] == [-10, 2, 20]


def test_forms_of_real_posts_fusion_32_2_and_german_cycle_names():
    # Fusion 360's TNC post writes "CYCL DEF 32.2 HSC-MODE:0 TA0.5"; German TNCs name the items
    # ("9.1 V.ZEIT 1", "1.1 ABST 2") and the cycles in German
    prog = run("CYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1 T0.01\nCYCL DEF 32.2 HSC-MODE:0 TA0.5\n"
               "CYCL DEF 9.0 VERWEILZEIT\nCYCL DEF 9.1 V.ZEIT 1.5\nCYCL DEF 1.0 TIEFBOHREN\nCYCL DEF 1.1 ABST 2\n"
               "CYCL DEF 1.2 TIEFE -4\nCYCL DEF 1.3 ZUSTLG 4\nCYCL DEF 1.4 V.ZEIT 0\nCYCL DEF 1.5 F100\n"
               "L X+0 Y+0 Z+2 FMAX M99")
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == [1.5]
    assert [b.target[2] for b in prog.blocks[2:]] == [2, -4, 2]
    assert any("32.2 HSC-MODE:0 TA0.5 ignored" in n for n in prog.notes)
    dwell = parse_heidenhain(HEAD + "FUNCTION DWELL TIME 2\nFUNCTION DWELL REV 10\nEND PGM T MM\n", source="t.h")
    assert [b.dwell for b in dwell.blocks[1:]] == [2.0, pytest.approx(1.2)]  # 10 turns at S500


def test_old_tapping_cycles_2_and_17_from_the_starting_point():
    # TNC 426/430 manual: 2 TAPPING in at F, dwell, out at F; 17 RIGID TAPPING at S x pitch (S500 x 1)
    prog = run("L X+50 Y+50 Z+2 FMAX\nCYCL DEF 2.0 TAPPING\nCYCL DEF 2.1 SET UP 2\nCYCL DEF 2.2 DEPTH -12\n"
               "CYCL DEF 2.3 DWELL 0.5\nCYCL DEF 2.4 F100\nCYCL CALL\nCYCL DEF 17.0 RIGID TAPPING\n"
               "CYCL DEF 17.1 SET UP 2\nCYCL DEF 17.2 DEPTH -10\nCYCL DEF 17.3 PITCH +1\nCYCL CALL")
    assert moves(prog)[1:] == [("line", 50, 50, -12, 100), ("dwell", 50, 50, -12, 0.5), ("line", 50, 50, 2, 100),
                               ("line", 50, 50, -10, 500), ("line", 50, 50, 2, 500)]


def test_m89_calls_the_cycle_at_every_positioning_block_until_m99():
    prog = run("CYCL DEF 240 CENTERING Q200=2 Q343=0 Q201=-1 Q206=100 Q211=0 Q203=+0 Q204=10\n"
               "L X+10 Y+0 FMAX M89\nL X+20 F500\nCC X+0 Y+0\nL X+30 M99\nL X+40\nM89\nL X+50\nCYCL CALL\nL X+60")
    holes = [b.target[0] for b in prog.blocks if b.kind == "line" and b.target[2] < 0]
    assert holes == [10, 20, 30, 50, 50]  # X40 after M99: no call; CYCL CALL at X50 ends M89: none at X60


def test_parameter_lines_without_tilde_as_older_tncs_save_them():
    prog = run("3 CYCL DEF 200 DRILLING\n  Q200=+2    ;SET-UP CLEARANCE\n  Q201=-6   ;DEPTH\n"
               "  Q206=+150  ;FEED RATE FOR PLNGNG\n  Q202=+3 ;PLUNGING DEPTH\n  Q210=+0\n  Q203=+0\n  Q204=+50\n"
               "  Q211=+0\n4 PATTERN DEF\n  POS1 (X+25 Y+30 Z+0)\n  POS2 (X+15 IY+5 Z-1)\n5 CYCL CALL PAT FMAX M13")
    holes = [b.target.tolist() for b in prog.blocks if b.kind == "line"]
    assert holes == [[25, 30, -3], [25, 30, -6], [15, 35, -4], [15, 35, -7]]
    assert {b.line for b in prog.blocks[1:]} == {16}  # the line of CYCL CALL PAT


@pytest.mark.parametrize("body, words", [
    ("CYCL DEF 204 BACK BORING Q200=2", "cycle 204 lacks Q249, Q250"),
    ("L X+0 Y+0 R0 F100 M136", "feed per revolution (FU, M136) without a spindle speed"),
    ("TCH PROBE 414 DATUM OUTSIDE CORNER Q263=+50", "TCH PROBE 414 is not modelled"),
    ("CYCL DEF 253 SLOT MILLING Q215=0", "cycle 253 lacks Q218, Q219"),
    ("CYCL DEF 254 CIRCULAR SLOT Q215=0", "cycle 254 lacks Q219, Q375"),
    ("CYCL DEF 255 UNKNOWN Q215=0", "cycle 255 is not supported"),
    ("CYCL DEF 251 RECTANGULAR POCKET Q215=0", "cycle 251 lacks Q218, Q219"),
    ("CYCL DEF 201 REAMING Q200=2 Q201=-10 Q206=100", "cycle 201 lacks Q203, Q204"),
    ("TOOL CALL 2 Z\nCYCL DEF 207 RIGID TAPPING Q200=2 Q201=-8 Q239=+1 Q203=+0 Q204=5", "no speed is known"),
    ("CYCL DEF 240 CENTERING Q200=2 Q343=1 Q201=-2 Q344=-9 Q206=100 Q211=0 Q203=+0 Q204=20\nL X+0 Y+0 FMAX M99",
     "Q343=1"),  # at the call: the point angle is the called tool's
    ("CYCL DEF 220 POLAR PATTERN Q216=+50 Q217=+50 Q244=20 Q245=+0 Q246=+360 Q247=+0 Q241=4 Q200=2 Q203=+1 "
     "Q204=30", "cycle 220 without a machining cycle"),
])
def test_errors_name_the_cycle(body, words):
    with pytest.raises(GCodeError) as info:
        parse_heidenhain("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", source="t.h")
    assert words in str(info.value)
    assert info.value.file == "t.h" and info.value.line >= 2


THREAD = ("TOOL DEF 2 L+0 R+4\nTOOL CALL 2 Z S500\nL X+10 Y+20 FMAX\nCYCL DEF 262 THREAD MILLING Q335=+12 {q} Q201=-6 "
          "Q253=750 Q200=2 Q203=+0 Q204=20 Q207=300\nCYCL CALL")


def test_thread_milling_262_one_helix_climbing_a_right_hand_thread():
    # M6 x 1.5 inside, tool radius 4: helix radius 2 about (10, 20); right-hand + climb: counter-clockwise, upward
    # from the depth -6 by one pitch; half circles in (centre (11, 20)) and out (centre (11, 20) at -4.5)
    prog = run(THREAD.format(q="Q239=+1.5 Q351=+1 Q355=0"))
    got = [(b.kind, *np.round(b.target, 6).tolist(), round(b.feed * 60, 6)) for b in prog.blocks[2:]]
    assert got == [("rapid", 10, 20, 2, math.inf), ("line", 10, 20, -6, 750), ("arc", 12, 20, -6, 300),
                   ("arc", 12, 20, -4.5, 300), ("arc", 10, 20, -4.5, 300), ("rapid", 10, 20, 2, math.inf),
                   ("rapid", 10, 20, 20, math.inf)]
    arcs = [b.segment for b in prog.blocks if b.kind == "arc"]
    assert all(a.ccw for a in arcs)
    assert [a.center[:2].tolist() for a in arcs] == [[11, 20], [10, 20], [11, 20]]


def test_thread_milling_262_continuous_and_downward_helices_stay_in_the_thread():
    # up-cut on a right-hand thread: clockwise, downward; Q355=1: from the surface to the depth, 4 turns of 1.5
    down = run(THREAD.format(q="Q239=+1.5 Q351=-1 Q355=1"))
    zs = [b.target[2] for b in down.blocks[2:]]
    assert zs == [2, 0, 0, -6, -6, 2, 20]
    helix = down.blocks[5]
    assert not helix.segment.ccw and np.allclose(helix.target, [12, 20, -6])
    # a left-hand thread climb-milled runs downward too: from one pitch above the depth
    left = run(THREAD.format(q="Q239=-1.5 Q351=+1 Q355=0"))
    assert [b.target[2] for b in left.blocks[2:]] == [2, -4.5, -4.5, -6, -6, 2, 20]
    for prog in (down, left, run(THREAD.format(q="Q239=+1.25 Q351=+1 Q355=1"))):
        for b in prog.blocks[2:]:  # within the thread: radius 6 less the tool's 4, between the depth and the top
            assert math.hypot(b.target[0] - 10, b.target[1] - 20) <= 2 + 1e-9 and -6 - 1e-9 <= b.target[2]
    with pytest.raises(GCodeError, match="Q355=2.5 is not a number of threads"):
        run(THREAD.format(q="Q239=+1.5 Q351=+1 Q355=2.5"))
    with pytest.raises(GCodeError, match="not narrower than the thread"):
        run(THREAD.format(q="Q239=+1.5 Q351=+1 Q355=0").replace("R+4", "R+6"))


def test_universal_pecking_205_breaks_the_chip_every_q257_within_an_infeed():
    # infeeds of 5; within each a chip break after every 2 mm, 0.5 back at rapid; between infeeds out to the
    # set-up clearance and back to Q258 = 0.5 above the last depth
    prog = run("CYCL DEF 205 UNIVERSAL PECKING Q200=2 Q201=-10 Q206=100 Q202=5 Q203=+0 Q204=20 Q212=0 Q205=0 "
               "Q258=0.5 Q259=0.5 Q257=2 Q256=0.5 Q211=0\nCYCL CALL")
    r = math.inf
    assert [(b.kind, b.target[2], round(b.feed * 60, 6)) for b in prog.blocks[1:]] == [
        ("rapid", 2, r), ("line", -2, 100), ("rapid", -1.5, r), ("line", -4, 100), ("rapid", -3.5, r),
        ("line", -5, 100), ("rapid", 2, r), ("rapid", -4.5, r), ("line", -7, 100), ("rapid", -6.5, r),
        ("line", -9, 100), ("rapid", -8.5, r), ("line", -10, 100), ("rapid", 2, r), ("rapid", 20, r)]


def test_universal_drilling_203_is_checked_by_the_reference():
    # decrement Q212, smallest infeed Q205, one chip break (Q213) before each retraction at Q208 (0: Q206)
    prog = run("CYCL DEF 203 UNIVERSAL DRILLING Q200=+2 Q201=-9 Q206=+60 Q202=+3 Q210=+0.5 Q203=+0 Q204=+2 "
               "Q212=+1 Q213=+1 Q205=+1 Q211=+0 Q208=+0 Q256=+0.5\nL X+5 FMAX M99")
    assert [b.target[2] for b in prog.blocks if b.kind == "line"] == [-3, -2.5, -5, 2, -6, -5.5, -7, 2, -8, -7.5,
                                                                        -9, 2]
    assert sum(b.kind == "dwell" for b in prog.blocks) == 2  # Q210 at the top before each re-entry


POCKET = ("TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+10 Y+20 FMAX\nCYCL DEF 252 CIRCULAR POCKET {q} Q223=20 "
          "Q207=500 Q201=-5 Q202=2.5 Q206=150 Q200=2 Q203=+0 Q204=20 Q366=0 Q385=400\nCYCL CALL")


def test_circular_pocket_252_roughs_in_rings_and_finishes_wall_and_floor():
    # 20 mm pocket about (10, 20), tool radius 2, stepover Q370 x R = 2; allowances 0.5 side, 0.2 floor:
    # roughing circles of radius 2, 4, 6 and 7.5 (10 - 0.5 - 2) at -2.5 and -4.8, then the wall at radius 8
    # (half circle out, full circle, half circle back) and the floor at -5 with circles out to 8
    prog = run(POCKET.format(q="Q215=0 Q368=0.5 Q369=0.2 Q338=0 Q351=+1 Q370=1"))
    moves = [(b.kind, *np.round(b.target, 6).tolist(), round(b.feed * 60, 6)) for b in prog.blocks[2:]]
    r = math.inf
    level = [("line", 12, 20, -2.5, 500), ("arc", 12, 20, -2.5, 500), ("line", 14, 20, -2.5, 500),
             ("arc", 14, 20, -2.5, 500), ("line", 16, 20, -2.5, 500), ("arc", 16, 20, -2.5, 500),
             ("line", 17.5, 20, -2.5, 500), ("arc", 17.5, 20, -2.5, 500)]
    assert moves[:12] == [("rapid", 10, 20, 2, r), ("line", 10, 20, -2.5, 150), *level,
                          ("rapid", 17.5, 20, -0.5, r), ("rapid", 10, 20, -0.5, r)]
    assert moves[12:21] == [("line", 10, 20, -4.8, 150), *[(k, x, y, -4.8, f) for k, x, y, _, f in level]]
    assert moves[23:27] == [("line", 10, 20, -5, 150), ("arc", 18, 20, -5, 400), ("arc", 18, 20, -5, 400),
                            ("arc", 10, 20, -5, 400)]
    assert moves[-2:] == [("rapid", 10, 20, 2, r), ("rapid", 10, 20, 20, r)]
    assert all(b.segment.ccw for b in prog.blocks if b.kind == "arc")  # climb milling with M3


def test_circular_pocket_252_stays_inside_the_pocket():
    for q in ("Q215=1 Q368=0 Q369=0 Q338=0 Q351=-1 Q370=1.4", "Q215=2 Q368=0 Q369=0 Q338=2 Q351=+1 Q370=0.5",
              "Q215=0 Q368=0.3 Q369=0.3 Q338=1 Q351=-1 Q370=1"):
        prog = run(POCKET.format(q=q))
        for b in prog.blocks[2:]:
            assert math.hypot(b.target[0] - 10, b.target[1] - 20) <= 10 - 2 + 1e-9 and b.target[2] >= -5 - 1e-9
            if b.kind == "arc":  # the arcs' far side too: centre distance plus radius
                c = b.segment.center
                far = math.hypot(c[0] - 10, c[1] - 20) + math.hypot(b.target[0] - c[0], b.target[1] - c[1])
                assert far <= 8 + 1e-9
    with pytest.raises(GCodeError, match="Q366=2 is not a plunging strategy"):  # 252: 0 vertical, 1 helical
        run(POCKET.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q351=1 Q370=1").replace("Q366=0", "Q366=2"))
    with pytest.raises(GCodeError, match="fill the pocket"):
        run(POCKET.format(q="Q215=0 Q368=8.5 Q369=0 Q338=0 Q351=1 Q370=1"))


RECT = ("TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+10 Y+20 FMAX\nCYCL DEF 251 RECTANGULAR POCKET {q} Q218=30 "
        "Q219=16 Q207=500 Q201=-2 Q202=2 Q206=150 Q200=2 Q203=+0 Q204=20 Q370=1 Q366=0 Q385=400 Q367=0\nCYCL CALL")


def test_rectangular_pocket_251_roughs_in_rectangles_and_finishes_the_wall():
    # 30 x 16 about (10, 20), tool radius 2, side allowance 0.5: the outer rectangle has half sides 12.5 x 5.5,
    # its corners rounded by 3 - 0.5 - 2 = 0.5; 3 rings (5.5 / 2 mm stepover), inset by 5.5 / 3 each
    prog = run(RECT.format(q="Q215=0 Q368=0.5 Q369=0 Q338=0 Q220=3 Q224=0 Q351=+1"))
    b = prog.blocks
    third = 5.5 / 3
    assert np.allclose(b[4].target, [10 + 12.5 - 2 * third, 20, -2]) and b[4].kind == "line"
    assert np.allclose(b[5].target, [10 + 12.5 - 2 * third, 20 + 5.5 - 2 * third, -2])
    outer = [blk for blk in b if blk.kind == "arc" and round(blk.feed * 60) == 500]
    assert len(outer) == 4 and all(a.segment.ccw for a in outer)
    assert np.allclose(outer[0].segment.center[:2], [22, 25]) and np.allclose(outer[0].target[:2], [22, 25.5])
    # the wall at half sides 13 x 6, corners 1, at Q385, then back to the centre
    wall = [blk for blk in b if blk.feed * 60 == pytest.approx(400)]
    assert np.allclose(wall[0].target, [23, 20, -2]) and np.allclose(wall[-1].target, [10, 20, -2])
    assert np.allclose(wall[2].segment.center[:2], [22, 25]) and np.allclose(wall[2].target[:2], [22, 26])


def test_rectangular_pocket_251_stays_inside_the_turned_pocket():
    for q in ("Q215=0 Q368=0.5 Q369=0.2 Q338=1 Q220=3 Q224=30 Q351=+1", "Q215=2 Q368=0 Q369=0 Q338=0 Q220=0 Q224=-90 "
              "Q351=-1", "Q215=1 Q368=0 Q369=0 Q338=0 Q220=9 Q224=0 Q351=-1"):
        prog = run(RECT.format(q=q))
        a = math.radians(float(q.split("Q224=")[1].split()[0]))
        for blk in prog.blocks[2:]:  # in the pocket's own axes, within the half sides less the tool radius
            dx, dy = blk.target[0] - 10, blk.target[1] - 20
            u, v = dx * math.cos(a) + dy * math.sin(a), -dx * math.sin(a) + dy * math.cos(a)
            assert abs(u) <= 13 + 1e-9 and abs(v) <= 6 + 1e-9 and blk.target[2] >= -2 - 1e-9
    with pytest.raises(GCodeError, match="Q367=5 is not a position"):
        run(RECT.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q220=0 Q224=0 Q351=1").replace("Q367=0", "Q367=5"))


STUD = ("TOOL DEF 2 L+0 R+2\nTOOL CALL 2 Z S500\nL X+10 Y+20 FMAX\nCYCL DEF 256 RECTANGULAR STUD {q} Q218=20 Q424=26 "
        "Q219=10 Q425=14 Q207=500 Q201=-2 Q202=2 Q206=150 Q200=2 Q203=+0 Q204=20 Q385=400 Q367=0\nCYCL CALL")


def test_rectangular_stud_256_steps_in_from_the_blank():
    # TNC 640 cycle manual, cycle 256: start 2 mm right of the blank (13 + 2 + R = 17 from the centre), a half
    # circle onto the contour, revolutions stepping in from the blank (15 x 9 with R) to the stud plus Q368
    # and R (12.5 x 7.5) in 2 steps of 1.25 (<= Q370 x R = 2), clockwise (climb), a half circle back out;
    # then one finishing revolution at 12 x 7 (corner Q220 + R = 3) at Q385
    prog = run(STUD.format(q="Q215=0 Q368=0.5 Q369=0 Q338=0 Q220=1 Q224=0 Q351=+1 Q370=1"))
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[2:5]] == [[27, 20, 50], [27, 20, 2], [27, 20, -2]]
    assert b[5].kind == "arc" and b[5].segment.ccw and np.allclose(b[5].target, [23.75, 20, -2])
    assert np.allclose(b[6].target, [23.75, 16, -2]) and not b[7].segment.ccw  # down the right side, clockwise
    assert np.allclose(b[7].segment.center[:2], [19, 16]) and np.allclose(b[7].target[:2], [19, 11.25])
    sides = sorted({round(float(blk.target[0]), 6) for blk in b if blk.kind == "line" and blk.target[1] == 20})
    assert sides == [22, 22.5, 23.75, 27]  # the revolutions close on the reference axis; the plunge at 27
    finish = [blk for blk in b if blk.feed * 60 == pytest.approx(400)]
    assert np.allclose(finish[0].target, [22, 20, -2]) and np.allclose(finish[-1].target, [27, 20, -2])
    assert np.allclose(b[-2].target, [27, 20, 2]) and np.allclose(b[-1].target, [27, 20, 20])


def test_rectangular_stud_256_never_cuts_into_the_stud():
    for q in ("Q215=1 Q368=0 Q369=0.3 Q338=0 Q220=0 Q224=0 Q351=-1 Q370=0.6",
              "Q215=2 Q368=0 Q369=0 Q338=1 Q220=4 Q224=0 Q351=+1 Q370=1",
              "Q215=0 Q368=0.2 Q369=0 Q338=0 Q220=2 Q224=30 Q351=+1 Q370=1.5"):
        prog = run(STUD.format(q=q)) if "Q224=0 " in q else parse_heidenhain(
            HEAD + STUD.format(q=q) + "\nEND PGM T MM\n", source="t.h", context=CTX)
        a = math.radians(float(q.split("Q224=")[1].split()[0]))
        for blk in prog.blocks[3:]:  # the tool centre stays R outside the stud 20 x 10 (its corners rounded)
            dx, dy = blk.target[0] - 10, blk.target[1] - 20
            u, v = abs(dx * math.cos(a) + dy * math.sin(a)), abs(-dx * math.sin(a) + dy * math.cos(a))
            outside = math.hypot(max(u - 10, 0.0), max(v - 5, 0.0))
            assert outside >= 2 - 1e-9 and blk.target[2] >= -2 - 1e-9
    with pytest.raises(GCodeError, match="Q424, Q425 at least"):
        run(STUD.format(q="Q215=0 Q368=0 Q369=0 Q338=0 Q220=0 Q224=0 Q351=1").replace("Q424=26", "Q424=18"))


def test_back_boring_204_goes_under_the_plate_off_centre_and_bores_upwards():
    # plate 20 thick from Z0 down, underside Z-20; tooth 3 above the tip: in until the tooth is 2 below the
    # underside (tip -25), back to the centre, up until the tooth is 5 above the underside (tip -18)
    prog = run("CYCL DEF 204 BACK BORING Q200=2 Q249=+5 Q250=20 Q251=3.5 Q252=3 Q253=MAX Q254=200 Q255=0.5 "
               "Q203=+0 Q204=50 Q214=1 Q336=0\nCYCL CALL")
    assert moves(prog) == [("rapid", 0, 0, 2, math.inf), ("rapid", -3.5, 0, 2, math.inf),
                           ("rapid", -3.5, 0, -25, math.inf), ("rapid", 0, 0, -25, math.inf),
                           ("line", 0, 0, -18, 200), ("dwell", 0, 0, -18, 0.5), ("rapid", 0, 0, -25, math.inf),
                           ("rapid", -3.5, 0, -25, math.inf), ("rapid", -3.5, 0, 2, math.inf),
                           ("rapid", 0, 0, 2, math.inf), ("rapid", 0, 0, 50, math.inf)]


def test_back_boring_204_prepositions_at_q253_and_rejects_max_elsewhere():
    prog = run("CYCL DEF 204 Q200=2 Q249=+5 Q250=20 Q251=3.5 Q252=3 Q253=500 Q254=200 Q255=0 "
               "Q203=+0 Q204=50 Q214=4 Q336=0\nCYCL CALL")
    assert [mv[:4] for mv in moves(prog)][1:4] == [("rapid", 0, 3.5, 2), ("line", 0, 3.5, -25), ("rapid", 0, 0, -25)]
    assert moves(prog)[2][4] == 500
    with pytest.raises(GCodeError, match="Q206=MAX"):
        run("CYCL DEF 200 Q200=2 Q201=-10 Q206=MAX Q202=5 Q210=0 Q203=+0 Q204=20 Q211=0\nCYCL CALL")


def test_retraction_feed_q208_max_is_rapid_as_the_fusion_post_writes_it():
    # Fusion 360's TNC post: cycle 203 with "Q208=MAX ;RETRACTION FEED RATE"; 201 the same
    prog = run("CYCL DEF 203 UNIVERSAL DRILLING ~\n  Q200=2 ;SET-UP CLEARANCE ~\n  Q201=-6 ;DEPTH ~\n"
               "  Q206=100 ;FEED RATE FOR PLUNGING ~\n  Q202=3 ;INFEED DEPTH ~\n  Q210=0 ;DWELL AT TOP ~\n"
               "  Q203=+0 ;SURFACE COORDINATE ~\n  Q204=20 ;2ND SET-UP CLEARANCE ~\n  Q212=0 ;DECREMENT ~\n"
               "  Q213=0 ;BREAKS ~\n  Q205=0 ;MIN. PLUNGING DEPTH ~\n  Q211=0 ;DWELL TIME AT DEPTH ~\n"
               "  Q208=MAX ;RETRACTION FEED RATE ~\n  Q256=0.2 ;DIST. FOR CHIP BRKNG\nCYCL CALL")
    assert [(k, z) for k, _, _, z, _ in moves(prog)] == [("rapid", 2), ("line", -3), ("rapid", 2), ("rapid", -1),
                                                          ("line", -6), ("rapid", 2), ("rapid", 20)]
    prog = run("CYCL DEF 201 REAMING Q200=2 Q201=-10 Q206=100 Q211=0 Q208=MAX Q203=+0 Q204=20\nCYCL CALL")
    assert [(k, z) for k, _, _, z, _ in moves(prog)] == [("rapid", 2), ("line", -10), ("rapid", 2), ("rapid", 20)]


GUN_DRILL = ("CYCL DEF 241 SINGLE-LIP DEEP-HOLE DRILLING ~\n Q200=3 ;SET-UP CLEARANCE ~\n Q201=-40 ;DEPTH ~\n"
             " Q206=50 ;FEED RATE FOR PLUNGING ~\n Q211=0.5 ;DWELL TIME AT DEPTH ~\n Q203=+0 ;SURFACE COORDINATE ~\n"
             " Q204=30 ;2ND SET-UP CLEARANCE ~\n Q379={q379} ;STARTING POINT ~\n Q253=750 ;F PRE-POSITIONING ~\n"
             " Q208=1000 ;RETRACT FEED RATE ~\n Q426=3 ;DIR. OF SPINDLE ROT. ~\n Q427=50 ;ENTRY EXIT SPEED ~\n"
             " Q428=1790 ;DRILLING SPEED ~\n Q429=8 ;COOLANT ON ~\n Q430=9 ;COOLANT OFF ~\n Q435=0 ;DWELL DEPTH\n"
             "CYCL CALL")


def test_single_lip_deep_hole_241_drills_in_one_infeed_and_retracts_at_q208():
    prog = run(GUN_DRILL.format(q379=0))
    assert moves(prog) == [("rapid", 0, 0, 3, math.inf), ("line", 0, 0, -40, 50), ("dwell", 0, 0, -40, 0.5),
                           ("line", 0, 0, 3, 1000), ("rapid", 0, 0, 30, math.inf)]


def test_single_lip_241_with_a_deepened_starting_point_enters_the_pilot_hole_at_q253():
    # hyperMILL's gun drilling: Q379=16 (the pilot hole's depth), Q200=3: at Q253 = 750 mm/min down to 3 mm
    # above the deepened starting point, Z-13; then at Q206 to Q201, dwell Q211, out at Q208 to Z+3, up to Q204
    prog = run(GUN_DRILL.format(q379=16))
    assert moves(prog) == [("rapid", 0, 0, 3, math.inf), ("line", 0, 0, -13, 750), ("line", 0, 0, -40, 50),
                           ("dwell", 0, 0, -40, 0.5), ("line", 0, 0, 3, 1000), ("rapid", 0, 0, 30, math.inf)]
    # Q379 shallower than the set-up clearance: the set-up clearance above it lies above the surface
    assert moves(run(GUN_DRILL.format(q379=2)))[:3] == [("rapid", 0, 0, 3, math.inf), ("line", 0, 0, 1, 750),
                                                        ("line", 0, 0, -40, 50)]


def test_single_lip_241_dwells_at_the_dwell_depth_and_drills_on_at_the_reduced_feed_q401():
    prog = run(GUN_DRILL.format(q379=16).replace("Q435=0", "Q435=30 ~\n Q401=50"))
    assert moves(prog) == [("rapid", 0, 0, 3, math.inf), ("line", 0, 0, -13, 750), ("line", 0, 0, -30, 50),
                           ("dwell", 0, 0, -30, 0.5), ("line", 0, 0, -40, 25), ("dwell", 0, 0, -40, 0.5),
                           ("line", 0, 0, 3, 1000), ("rapid", 0, 0, 30, math.inf)]


@pytest.mark.parametrize(("change", "match"), [
    ("Q379=50", "cycle 241: the deepened starting point Q379 must lie within the depth Q201"),
    ("Q435=40", "cycle 241: the dwell depth Q435 must lie within the depth Q201"),
    ("Q379=10 ~\n Q202=5", "infeeds Q202 shorter")])
def test_single_lip_241_refuses_what_it_cannot_run_naming_the_parameter(change, match):
    with pytest.raises(GCodeError, match=match):
        run(GUN_DRILL.format(q379=0).replace("Q379=0", change) if "Q379" in change
            else GUN_DRILL.format(q379=0).replace("Q435=0", change))


def test_back_boring_204_at_the_points_of_a_pattern():
    # CYCL CALL PAT: up to the clearance (Q204 = 15 above the surface) between the holes, 204 at each
    prog = run("CYCL DEF 204 Q200=2 Q249=+4 Q250=10 Q251=2 Q252=0 Q253=MAX Q254=100 Q255=0 Q203=+0 Q204=15 "
               "Q214=3 Q336=0\nPATTERN DEF ~\nPOS1 (X+10 Y+0 Z+0) ~\nPOS2 (X+20 Y+0 Z+0)\nCYCL CALL PAT FMAX")
    lows = [tuple(round(v, 6) for v in b.target) for b in prog.blocks if b.kind == "line"]
    assert lows == [(10, 0, -6), (20, 0, -6)]  # the tooth (= tip, Q252 = 0) up to 4 above the underside Z-10


def test_orientation_13_moves_nothing():
    # TNC 426/430 manual, "ORIENTATION (Cycle 13)": 13.1 ANGLE sets the oriented spindle stop; no axis moves
    prog = run("CYCL DEF 13.0 ORIENTATION\nCYCL DEF 13.1 ANGLE 180\nL X+5 FMAX")
    assert moves(prog) == [("rapid", 5, 0, 50, math.inf)]
    assert any(n.startswith("CYCL DEF 13 ORIENTATION") for n in prog.notes)
    with pytest.raises(GCodeError, match="cycle 13 has no line 2"):
        run("CYCL DEF 13.0 ORIENTATION\nCYCL DEF 13.2 ANGLE 180")
