"""Heidenhain multipass-milling cycles 232 and 233 FACE MILLING, 230 MULTIPASS MILLING and 231 RULED SURFACE:
hand-written programs whose moves are worked out by hand from the cycles' runs (TNC 640 user's manual for cycle
programming 34059x-01, p. 235-236; TNC 320 user's manual 340 551-02 p. 298; for 233 the TNC7 basic user's manual
81762x-19, "Cycle 233 FACE MILLING"; TNC 410 ISO manual p. 292 for 231's parameters; 230's and 231's runs and 233's
where the manual leaves it open as vcnc reads them, see ``interpolators.heidenhain_surfaces``), each also checked
against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n"
CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)})


def run(body: str, *, reference: bool = True):
    text = HEAD + body + "\nEND PGM T MM\n"
    return checked_program(text, CTX, check=reference)


# a face 60 x 30 from (0, 0), milled from Z+2.5 down to Z+0 with a tool of radius 10: 2 mm in infeeds of at most
# 1.5 (two of 1.0), then the allowance 0.5 at the finishing feed
FACE = ("TOOL DEF 5 L+0 R+10\nTOOL CALL 5 Z S1000\nL X+0 Y+0 Z+{z} R0 FMAX\nCYCL DEF 232 FACE MILLING ~\n"
        "Q389={s} ;STRATEGY ~\nQ225=+0 ;STARTING PNT 1ST AXIS ~\nQ226=+0 ;STARTING PNT 2ND AXIS ~\n"
        "Q227=+2.5 ;STARTING PNT 3RD AXIS ~\nQ386=+0 ;END POINT 3RD AXIS ~\nQ218={l} ;FIRST SIDE LENGTH ~\n"
        "Q219={w} ;2ND SIDE LENGTH ~\nQ202=+1.5 ;MAX. PLUNGING DEPTH ~\nQ369=+0.5 ;ALLOWANCE FOR FLOOR ~\n"
        "Q370=+1 ;MAX. OVERLAP ~\nQ207=+500 ;FEED RATE FOR MILLING ~\nQ385=+800 ;FINISHING FEED RATE ~\n"
        "Q253={pre} ;F PRE-POSITIONING ~\nQ200=+2 ;SET-UP CLEARANCE ~\nQ357=+2 ;CLEARANCE TO SIDE ~\n"
        "Q204=+50 ;2ND SET-UP CLEARANCE\nCYCL CALL")


def face(*, s: int = 0, z: float = 100, length: str = "+60", width: str = "+30", pre: str = "+2000") -> str:
    return FACE.format(s=s, z=z, l=length, w=width, pre=pre)


def mm_min(blk) -> float:
    return round(blk.feed * 60.0, 6)


def test_face_milling_232_meander_outside_the_surface():
    # Q389=0: the start R + Q357 = 12 before the near edge, the lines out to 12 beyond the far edge (60 + 12);
    # the width 30 in stepovers of at most Q370 x R = 10: lines at Y 0, 10, 20, 30; levels 1.5, 0.5 (equal
    # infeeds of 1 <= Q202) and 0 (the allowance, at Q385); each level back over the lines in reverse order
    prog = run(face())
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[:4]] == [[0, 0, 100], [-12, 0, 100], [-12, 0, 4.5], [-12, 0, 1.5]]
    assert mm_min(b[3]) == 2000  # down to the first infeed at the pre-positioning feed Q253
    cuts = [blk for blk in b if blk.kind == "line" and blk.target[0] != blk.start[0]]
    assert [(blk.target[0], blk.target[1], blk.target[2]) for blk in cuts[:5]] == [
        (72, 0, 1.5), (-12, 10, 1.5), (72, 20, 1.5), (-12, 30, 1.5), (72, 30, 0.5)]
    assert {blk.target[2]: mm_min(blk) for blk in cuts} == {1.5: 500, 0.5: 500, 0.0: 800}
    steps = [blk for blk in b if blk.kind == "line" and blk.target[1] != blk.start[1]]
    assert all(mm_min(blk) == 2000 and abs(blk.target[0]) in (12, 72) for blk in steps)  # stepovers outside
    assert len(cuts) == 12 and b[-1].kind == "rapid" and b[-1].target.tolist() == [-12, 30, 52.5]  # Q227 + Q204


def test_face_milling_232_meander_within_the_surface():
    # Q389=1: the lines end R inside the edges (X 10 and 50), the first starting from the approach point; the
    # stepovers run at the milling feed Q207 (TNC 320 manual p. 298, Q253: "transversely to the material")
    b = run(face(s=1)).blocks
    cuts = [blk for blk in b if blk.kind == "line" and blk.target[0] != blk.start[0]]
    assert cuts[0].start[0] == -12 and cuts[0].target[0] == 50
    assert {round(blk.target[0], 9) for blk in cuts[1:]} == {10, 50}
    steps = [blk for blk in b if blk.kind == "line" and blk.target[1] != blk.start[1]]
    assert steps and all(mm_min(blk) == 500 for blk in steps)


def test_face_milling_232_line_by_line_returns_over_the_surface():
    # Q389=2: every line from X-12 to X+72 (climbing the same way), up to Q200 above the level at FMAX, back
    # at Q253 to the next line's start, down at Q253
    b = run(face(s=2)).blocks
    cuts = [blk for blk in b if blk.kind == "line" and blk.target[0] != blk.start[0] and blk.target[2] <= 1.5]
    assert len(cuts) == 12 and all(blk.start[0] == -12 and blk.target[0] == 72 for blk in cuts)
    ups = [blk for blk in b[3:-1] if blk.kind == "rapid"]
    assert all(blk.target[0] == 72 and blk.target[2] - blk.start[2] == pytest.approx(2) for blk in ups)
    backs = [blk for blk in b if blk.kind == "line" and blk.target[0] == -12 and blk.start[0] == 72]
    assert backs and all(mm_min(blk) == 2000 and blk.target[2] > 1.5 for blk in backs)


def test_face_milling_232_directions_by_the_signs_and_positioning_from_below():
    # negative side lengths mill toward -X and step toward -Y; the tool starting below the 2nd set-up clearance
    # (Z+20 < 2.5 + 50) goes up to it first, then over the starting point; Q253=MAX pre-positions at rapid
    b = run(face(z=20, length="-60", width="-15", pre="MAX")).blocks
    assert [blk.target.tolist() for blk in b[1:4]] == [[0, 0, 52.5], [12, 0, 52.5], [12, 0, 4.5]]
    assert b[4].kind == "rapid" and b[4].target.tolist() == [12, 0, 1.5]
    cuts = [blk for blk in b if blk.kind == "line" and blk.target[0] != blk.start[0]]
    assert cuts[0].target.tolist() == [-72, 0, 1.5]
    assert sorted({blk.target[1] for blk in cuts}) == [-15, -7.5, 0]  # 15 in two stepovers of 7.5 <= 10


def test_face_milling_232_under_a_datum_shift_and_a_rotation():
    prog = run("CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+100\nCYCL DEF 7.2 Y+50\nCYCL DEF 10.0 ROTATION\n"
               "CYCL DEF 10.1 ROT+90\n" + face(s=1))
    cut = next(blk for blk in prog.blocks if blk.kind == "line" and blk.target[2] == 1.5 and blk.start[2] == 1.5)
    assert np.allclose(cut.target, [100, 50 + 50, 1.5])  # X+50 of the program: Y+50 turned by 90 degrees


def test_face_milling_232_bad_definitions_are_errors():
    with pytest.raises(GCodeError, match="Q389=3 is not a strategy"):
        run(face(s=3), reference=False)
    with pytest.raises(GCodeError, match="Q227 must lie above the end point Q386"):
        run(face().replace("Q386=+0", "Q386=+3"), reference=False)
    with pytest.raises(GCodeError, match="without a tool radius"):
        run(face().replace("R+10", "R+0"), reference=False)
    with pytest.raises(GCodeError, match="at positions"):
        run(face().replace("CYCL CALL", "CYCL CALL POS X+0 Y+0 Z+0 FMAX"), reference=False)


# cycle 233: the surface 60 x 30 from the tool's position (X+10 Y+5), Z+2.5 down to Z+0, tool radius 10
FACE233 = ("TOOL DEF 5 L+0 R+10\nTOOL CALL 5 Z S1000\nL X+10 Y+5 Z+{z} R0 FMAX\nCYCL DEF 233 FACE MILLING ~\n"
           "Q215={op} ;MACHINING OPERATION ~\nQ389={s} ;MILLING STRATEGY ~\nQ350={d} ;MILLING DIRECTION ~\n"
           "Q218={l} ;FIRST SIDE LENGTH ~\nQ219={w} ;2ND SIDE LENGTH ~\nQ227=+2.5 ;STARTNG PNT 3RD AXIS ~\n"
           "Q386=+0 ;END POINT 3RD AXIS ~\nQ369=+0.5 ;ALLOWANCE FOR FLOOR ~\nQ202=+1.5 ;MAX. PLUNGING DEPTH ~\n"
           "Q370=+1 ;TOOL PATH OVERLAP ~\nQ207=+500 ;FEED RATE FOR MILLNG ~\nQ385=+800 ;FINISHING FEED RATE ~\n"
           "Q253=+2000 ;F PRE-POSITIONING ~\nQ357=+2 ;CLEARANCE TO SIDE ~\nQ200=+2 ;SET-UP CLEARANCE ~\n"
           "Q204=+50 ;2ND SET-UP CLEARANCE ~\nQ347={lim} ;1ST LIMIT ~\nQ348=+0 ;2ND LIMIT ~\nQ349=+0 ;3RD LIMIT ~\n"
           "Q220=+0 ;CORNER RADIUS ~\nQ368=+0 ;ALLOWANCE FOR SIDE ~\nQ338=+0 ;INFEED FOR FINISHING\nCYCL CALL")


def face233(*, s: int = 0, d: int = 1, op: int = 0, z: float = 100, length: str = "+60", width: str = "+30",
            lim: str = "+0") -> str:
    return FACE233.format(s=s, d=d, op=op, z=z, l=length, w=width, lim=lim)


def cuts_of(blocks):
    """The milling lines: fed moves in the plane at a constant height that are not stepovers."""
    return [blk for blk in blocks if blk.kind == "line" and blk.start[2] == blk.target[2]
            and mm_min(blk) in (500, 800)]


def test_face_milling_233_meander_from_the_tool_position():
    # Q389=0: the corner where the tool stands (X+10 Y+5); the start R + Q357 = 12 before it, the lines out
    # to 12 beyond the far edge (10 + 60 + 12 = 82); Y 5, 15, 25, 35 (30 in stepovers of at most Q370 x R = 10);
    # down from Q200 above Q227 to the first infeed at the milling feed Q207, stepovers at Q253; infeeds 1 + 1
    # (equal, <= Q202 = 1.5) to Q386 + Q369 = 0.5, then the allowance at Q385; at the end FMAX to Q227 + Q204;
    # each level back over the lines in the reverse order of the last
    b = run(face233()).blocks
    assert [blk.target.tolist() for blk in b[1:5]] == [[-2, 5, 100], [-2, 5, 4.5], [-2, 5, 1.5], [82, 5, 1.5]]
    assert b[2].kind == "rapid" and b[3].kind == "line" and mm_min(b[3]) == 500
    cuts = cuts_of(b)
    assert len(cuts) == 12 and [blk.target[2] for blk in cuts[::4]] == [1.5, 0.5, 0]
    assert {blk.target[2]: mm_min(blk) for blk in cuts} == {1.5: 500, 0.5: 500, 0.0: 800}
    assert {round(blk.target[0], 9) for blk in cuts} == {-2, 82} and sorted({blk.target[1] for blk in cuts}) == [
        5, 15, 25, 35]
    steps = [blk for blk in b if blk.kind == "line" and blk.target[1] != blk.start[1]]
    assert len(steps) == 9 and all(mm_min(blk) == 2000 for blk in steps)
    assert b[-1].kind == "rapid" and b[-1].target.tolist() == [-2, 35, 52.5]  # three levels: at the far line


def test_face_milling_233_strategies_end_at_the_edge_or_line_by_line():
    # Q389=1: the end points Q357 beyond the edges (X+72 and X+8), the first line from the start X-2
    cuts = cuts_of(run(face233(s=1)).blocks)
    assert cuts[0].start[0] == -2 and {round(blk.target[0], 9) for blk in cuts} == {8, 72}
    # Q389=2 / 3: every line from the start X-2, out to X+82 / X+72; back at FMAX Q200 above the level, down at Q207
    for s, far in ((2, 82), (3, 72)):
        b = run(face233(s=s)).blocks
        cuts = cuts_of(b)
        assert len(cuts) == 12 and all(blk.start[0] == -2 and blk.target[0] == far for blk in cuts)
        backs = [blk for blk in b if blk.target[0] == -2 and blk.start[0] == far]
        assert backs and all(blk.kind == "rapid" and blk.target[2] - blk.start[2] == 0 for blk in backs)
        downs = [blk for blk in b[4:] if blk.kind == "line" and blk.target[2] < blk.start[2]]
        assert all(mm_min(blk) == 500 and blk.start[2] - blk.target[2] == pytest.approx(2) for blk in downs[:3])


def test_face_milling_233_along_the_minor_axis_and_the_operations():
    # Q350=2: the lines along Y over Q219 (30: Y from 5 - 12 to 5 + 30 + 12), 60 across in stepovers of 10 (7 lines)
    cuts = cuts_of(run(face233(d=2)).blocks)
    assert {round(blk.target[1], 9) for blk in cuts} == {-7, 47}
    assert sorted({blk.target[0] for blk in cuts}) == [10, 20, 30, 40, 50, 60, 70] and len(cuts) == 21
    # Q215=1 roughs only (levels 1.5, 0.5); Q215=2 finishes only (Z+0 at Q385)
    assert sorted({blk.target[2] for blk in cuts_of(run(face233(op=1)).blocks)}) == [0.5, 1.5]
    finish = cuts_of(run(face233(op=2)).blocks)
    assert len(finish) == 4 and {(blk.target[2], mm_min(blk)) for blk in finish} == {(0, 800)}


def test_face_milling_233_in_an_inch_program():
    # every length in inches (the tool radius of TOOL DEF too), the feeds in 0.1 inch/min (the TNC's feed unit in
    # INCH programs, as F): from X+1 Y+0.5, the start
    # R + Q357 = 0.5 before it (X+0.5), the lines out to 0.5 beyond X+3 (X+3.5), at Y 0.5, 0.9, 1.3 (0.8 in
    # stepovers of at most R = 0.4); levels 0.05 and 0 (Q202 = 0.05), milled at Q207 = 200: 20 inch/min
    text = ("0 BEGIN PGM T INCH\nTOOL DEF 5 L+0 R+0.4\nTOOL CALL 5 Z S1000\nL X+1 Y+0.5 Z+4 R0 FMAX\n"
            "CYCL DEF 233 FACE MILLING Q215=0 Q389=0 Q350=1 Q218=+2 Q219=+0.8 Q227=+0.1 Q386=+0 Q369=+0 Q202=+0.05 "
            "Q370=+1 Q207=+200 Q253=+400 Q357=+0.1 Q200=+0.1 Q204=+1\nCYCL CALL\nEND PGM T INCH\n")
    b = checked_program(text, CTX).blocks
    cuts = [blk for blk in b if blk.kind == "line" and blk.start[2] == blk.target[2] and blk.start[1] == blk.target[1]]
    assert len(cuts) == 6 and {round(blk.target[0] / 25.4, 9) for blk in cuts} == {0.5, 3.5}
    assert sorted({round(blk.target[1] / 25.4, 9) for blk in cuts}) == [0.5, 0.9, 1.3]
    assert sorted({round(blk.target[2] / 25.4, 9) for blk in cuts}) == [0.0, 0.05]
    assert all(blk.feed == pytest.approx(20 * 25.4 / 60) for blk in cuts)
    assert b[-1].target[2] == pytest.approx(1.1 * 25.4)  # Q227 + Q204


def test_face_milling_233_bad_definitions_name_the_q_parameter():
    with pytest.raises(GCodeError, match="Q389=4 is not a strategy"):
        run(face233(s=4), reference=False)
    with pytest.raises(GCodeError, match="Q350=3 is not a milling direction"):
        run(face233(d=3), reference=False)
    with pytest.raises(GCodeError, match="Q215=3 is not a machining operation"):
        run(face233(op=3), reference=False)
    with pytest.raises(GCodeError, match=r"side walls Q347=-1 are not supported"):
        run(face233(lim="-1"), reference=False)
    with pytest.raises(GCodeError, match="Q227 must lie above the end point Q386"):
        run(face233().replace("Q386=+0", "Q386=+3"), reference=False)
    with pytest.raises(GCodeError, match="lacks Q350"):
        run(face233().replace("Q350=1 ;MILLING DIRECTION ~\n", ""), reference=False)
    with pytest.raises(GCodeError, match="surface position Q367=0"):
        run(face233().replace("CYCL CALL", "").replace("Q338=+0 ;INFEED FOR FINISHING",
                                                        "Q338=+0 ;INFEED FOR FINISHING ~\nQ367=+0") + "CYCL CALL",
            reference=False)


def test_multipass_milling_230_meanders_q240_lines_at_one_height():
    # lines from R before Q225 to R beyond Q225 + Q218 (X-5 .. X+105), 5 lines 10 apart over Q219 = 40, at Z-2;
    # down at Q206, along at Q207, the stepovers at Q209; at the end up to the set-up clearance
    prog = run("TOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z S2000\nL X+50 Y+50 Z+20 R0 FMAX\nCYCL DEF 230 MULTIPASS MILLING "
               "Q225=+0 Q226=+0 Q227=-2 Q218=+100 Q219=+40 Q240=5 Q206=150 Q207=600 Q209=300 Q200=2\nCYCL CALL")
    b = prog.blocks
    assert [blk.target.tolist() for blk in b[:4]] == [[50, 50, 20], [-5, 0, 20], [-5, 0, 0], [-5, 0, -2]]
    assert mm_min(b[3]) == 150
    cuts = [blk for blk in b if blk.kind == "line" and blk.target[0] != blk.start[0]]
    assert [(blk.target[0], blk.target[1]) for blk in cuts] == [(105, 0), (-5, 10), (105, 20), (-5, 30), (105, 40)]
    assert all(mm_min(blk) == 600 for blk in cuts)
    assert all(mm_min(blk) == 300 for blk in b if blk.kind == "line" and blk.target[1] != blk.start[1])
    assert b[-1].target.tolist() == [105, 40, 0]


def test_ruled_surface_231_lines_between_two_edges():
    # points 1 (0, 5, -2), 2 (100, 5, -2), 3 (100, 45, 3), 4 (0, 45, 8): Q240 = 3 lines, from the edge 1-4 to the
    # edge 2-3, at Y 5, 25, 45, the tool axis as the edges (Z -2 / -2, 3 / 0.5, 8 / 3); the first at Q207 / 2;
    # between lines up by the tool diameter (2 x 4), back over the start, down, fed across
    prog = run("TOOL DEF 1 L+0 R+4\nTOOL CALL 1 Z S2000\nL X+0 Y+0 Z+50 R0 FMAX\nCYCL DEF 231 RULED SURFACE "
               "Q225=+0 Q226=+5 Q227=-2 Q228=+100 Q229=+5 Q230=-2 Q231=+100 Q232=+45 Q233=+3 Q234=+0 Q235=+45 "
               "Q236=+8 Q240=3 Q207=500\nCYCL CALL")
    b = prog.blocks
    assert b[1].kind == "rapid" and b[1].target.tolist() == [0, 5, -2]
    cuts = [blk for blk in b if blk.kind == "line" and blk.target[0] == 100]
    assert [blk.target.tolist() for blk in cuts] == [[100, 5, -2], [100, 25, 0.5], [100, 45, 3]]
    assert [mm_min(blk) for blk in cuts] == [250, 500, 500]
    assert b[3].kind == "rapid" and b[3].target.tolist() == [100, 5, 6]
    assert b[-1].target.tolist() == [100, 45, 16]  # the highest point Z+8 plus the diameter
