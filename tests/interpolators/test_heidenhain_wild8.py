"""Heidenhain programs of an eighth wild set (a TNC simulator's tests built on the TNC 426/430 manual's
examples, a German shop's probing and tilting program, a face-milling macro calling its cycle program, Chinese
5-axis CAM output, a TNC 640 tool-check macro): what the reader refused or named unclearly, each as a
hand-written program checked against the independent reference where it runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()
AC_TABLE = MachineContext(extra_axes=("a", "c"),
                          kinematics=Kinematics(axes=(RotaryAxis(name="a"), RotaryAxis(name="c"))))


def checked(body: str):
    """The program read, and its blocks matched against the reference."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO)


def test_ctp_is_the_tangential_arc_to_a_polar_end_point():
    # TNC7 basic user's manual, "Overview of path functions with polar coordinates": CTP, "circular path with
    # tangential connection to the preceding contour element", its end point by PR/PA about the pole CC (the TNC
    # 426/430 manual's example writes 'CTP PR+30 PA+30'); it was refused as 'CTP is not supported'.
    # The line from (0, 35) to the polar point PR 25 PA 120 about (40, 35), then CTP to PR 30 PA 30 = (40 + 30 cos 30,
    # 35 + 15): the arc leaves along the line's direction
    prog = checked("1 CC X+40 Y+35\n2 L X+0 Y+35 Z+0 R0 F250\n3 LP PR+25 PA+120\n4 CTP PR+30 PA+30")
    start, end = prog.blocks[-2].target, prog.blocks[-1].target
    assert np.allclose(start, [40 - 12.5, 35 + 25 * math.sin(math.radians(120)), 0])
    assert np.allclose(end, [40 + 30 * math.cos(math.radians(30)), 50, 0])
    arc = prog.blocks[-1].segment
    line_dir = (start - np.array([0, 35, 0]))[:2] / np.linalg.norm((start - np.array([0, 35, 0]))[:2])
    tangent = np.asarray(arc.tangent_at(0.0), float).reshape(3)[:2]
    assert np.allclose(tangent / np.linalg.norm(tangent), line_dir)


def test_ctp_with_incremental_polar_words_and_a_helix_axis():
    # IPA from the current angle about the pole, IPR added to the current radius; Z ends the arc lower (a helix,
    # as CT with Z): from (10, 0) along +Y after the line from (10, -10), to PR 10 + 0 = 10 at 0 + 90 = (0, 10)
    prog = checked("1 CC X+0 Y+0\n2 L X+10 Y-10 Z+0 R0 F100\n3 L Y+0\n4 CTP IPR+0 IPA+90 Z-2")
    assert np.allclose(prog.blocks[-1].target, [0, 10, -2])


def test_ctp_needs_a_pole_and_a_preceding_element():
    with pytest.raises(GCodeError, match=r"t.h:3:3: CTP without a pole .*expected a CC block before CTP"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+0 R0 F100\n2 CTP PR+10 PA+0\nEND PGM T MM\n",
                         source="t.h", context=ZERO)
    with pytest.raises(GCodeError, match=r"CTP without a preceding contour element"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 CC X+0 Y+0\n2 TOOL CALL 1 Z S100 F100\n3 CTP PR+10 PA+0\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


TCH_413 = ("TCH PROBE 413 DATUM OUTSIDE CIRCLE\n Q321=+25\n Q322=+25\n Q262=30\n Q325=+90\n Q247=+45\n Q261=-5\n"
           " Q320=2\n Q260=+10\n Q301=0\n Q305=0\n Q331=+0\n Q332=+10\n Q303=+0\n Q381=1\n Q382=+25\n Q383=+25\n"
           " Q384=+25\n Q333=+0\n Q423=4\n Q365=1\n")


def test_touch_probe_parameters_on_lines_of_their_own_without_tilde():
    # the manuals print a touch probe cycle's parameters one per line without '~', as they do a CYCL DEF's (iTNC 530
    # touch probe cycles manual, example of cycle 412); the reader took them for the cycle's only for CYCL DEF 2xx
    # and said 'TCH PROBE 413 lacks Q321, ...'. The manual's example of cycle 413 (TNC 426/430 manual 15.13): the
    # stud's centre (25, 25) reads X0 Y10, its top (Q381 = 1 at Q384 = 25) Z0: X+0 Y+10 Z+0 is machine (25, 25, 25)
    prog = checked("1 TOOL CALL 1 Z\n2 L Z+50 R0 FMAX\n" + TCH_413 + "3 L X+0 Y+10 Z+0 R0 FMAX")
    assert np.allclose(prog.blocks[-1].target, [25, 25, 25])


def test_a_division_by_zero_names_the_divisor():
    # a face-milling cycle program divides by its step 'Q1963 = Q1812 * Q108 * 2', Q108 the tool radius, 0 when the
    # tool table lacks the tool: before, only "division by zero"
    text = "0 BEGIN PGM T MM\n1 Q1963 = Q1812 * Q108 * 2\n2 Q1961 = INT ( ( 100 / Q1963 ) + 0.999 )\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match=r"t.h:3:.*division by zero \(Q1963 is 0\)"):
        parse_heidenhain(text, source="t.h", context=ZERO)
    with pytest.raises(GCodeError, match=r"division by zero \(\( Q1 - Q2 \) is 0\)"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 Q3 = 5 / ( Q1 - Q2 )\nEND PGM T MM\n", source="t.h", context=ZERO)


@pytest.mark.parametrize("tilde", [" ~", ""])
def test_a_cycle_parameter_without_equals_is_named(tilde):
    # a TNC simulator's test program writes 'Q206 FAUTO' among the lines of CYCL DEF 200 (the TNC writes
    # 'Q206=FAUTO'); with '~' the reader said "unexpected 'Q206' in a cycle definition", without it
    # "cycle 200 lacks Q206, Q203, Q204" on the CYCL DEF line
    lines = ["Q200=2", "Q201=-10", "Q206 FAUTO", "Q202=5", "Q210=0", "Q203=+0", "Q204=50"]
    body = "\n".join(("  " + q + (tilde if i < len(lines) - 1 else "")) for i, q in enumerate(lines))
    text = f"0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000 F100\n2 CYCL DEF 200 DRILLING{tilde}\n{body}\n3 END PGM T MM\n"
    # the line and column where Q206 is written, the block's sixth line (tncwild14: a continued block's pieces)
    with pytest.raises(GCodeError, match=r"t.h:6:3: cycle parameter Q206 without '=' \(got 'Q206 FAUTO'\); "
                                         r"expected Q206=value"):
        parse_heidenhain(text, source="t.h", context=ZERO)


def test_sysread_reads_the_tool_table_columns_of_the_manuals_table_as_0():
    # a TNC 640 tool-check macro reads 'FN 18: SYSREAD Q2 = ID50 NR19 IDXQ1' (R-OFFS) and NR1 (the length): the
    # TNC 426/430 technical manual's table of system data numbers group 50 NR1 - NR23 (L, R, R2, DL, DR, DR2, TL,
    # RT, TIME1, TIME2, CUR. TIME, PLC, LCUTS, ANGLE, CUT, LTOL, RTOL, DIRECT, R-OFFS, L-OFFS, LBREAK, RBREAK, PLC
    # value); vcnc's tool table holds L and R: the others read 0 with a note. NR19 was refused
    text = ("0 BEGIN PGM T MM\n1 TOOL DEF 5 L+40 R+3\n2 TOOL CALL 5 Z S1000\n3 FN 18: SYSREAD Q1 = ID20 NR1\n"
            "4 FN 18: SYSREAD Q2 = ID50 NR19 IDXQ1\n5 FN 18: SYSREAD Q3 = ID50 NR7 IDX5\n"
            "6 FN 18: SYSREAD Q4 = ID50 NR1 IDXQ1\n7 L X+Q1 Y+Q2 Z+Q4 R0 FMAX\n8 L X+Q3 FMAX\nEND PGM T MM\n")
    prog = parse_heidenhain(text, source="t.h", context=ZERO)
    assert np.allclose([b.target for b in prog.blocks], [[5, 0, 40 + 40], [0, 0, 80]])  # Z: program 40 + length 40
    assert any("ID50 NR19 (R-OFFS)" in n and "0" in n for n in prog.notes)
    with pytest.raises(GCodeError, match=r"FN 18 SYSREAD 'SYSREAD Q3 = ID50 NR36 IDX5' is not supported"):
        parse_heidenhain(text.replace("NR7 IDX5", "NR36 IDX5"), source="t.h", context=ZERO)


def test_thread_milling_with_several_threads_per_step():
    # TNC 426/430 user's manual p. 251, cycle 262 Q355: ">1 = several helical paths with approach and departure;
    # between them, the TNC offsets the tool by Q355, multiplied by the pitch" (refused before). A right-hand
    # thread milled up-cut runs downward; our reading: one turn ending at the depth -20, and one at every
    # 3 x 1.5 = 4.5 above it while it still reaches below the surface: ends at -2, -6.5, -11, -15.5, -20, each
    # one pitch long, the highest first, at Q253 along the axis between them
    prog = checked("1 TOOL DEF 1 L+0 R+3\n2 TOOL CALL 1 Z S2000\n3 L X+50 Y+50 Z+50 R0 FMAX M3\n"
                   "4 CYCL DEF 262 THREAD MILLING Q335=16 Q239=+1.5 Q201=-20 Q355=3 Q253=750 Q351=-1 Q200=2 "
                   "Q203=+0 Q204=50 Q207=500\n5 CYCL CALL")
    helices = [b for b in prog.blocks if b.kind == "arc" and abs(b.segment.sweep) > math.pi + 0.1]
    assert [round(float(b.target[2]), 6) for b in helices] == [-2, -6.5, -11, -15.5, -20]
    assert all(not b.segment.ccw and np.isclose(b.segment.radius, 8 - 3) for b in helices)  # clockwise on R 5
    moves_in = [round(float(b.target[2]), 6) for b in prog.blocks if b.kind == "line"]
    assert moves_in == [-0.5, -5, -9.5, -14, -18.5]  # each turn's start, at Q253
    assert np.allclose(prog.blocks[-1].target, [50, 50, 50])
    # cycle 267 about a stud alike (Q355=2, pitch 1, depth 6: turns ending at -2, -4, -6, outside on R 8 + 3)
    stud = checked("1 TOOL DEF 1 L+0 R+3\n2 TOOL CALL 1 Z S2000\n3 L X+50 Y+50 Z+50 R0 FMAX M3\n"
                   "4 CYCL DEF 267 OUTSIDE THREAD MLLNG Q335=16 Q239=+1 Q201=-6 Q355=2 Q253=750 Q351=+1 Q200=2 "
                   "Q358=+0 Q359=+0 Q203=+0 Q204=50 Q254=150 Q207=500\n5 CYCL CALL")
    helices = [b for b in stud.blocks if b.kind == "arc" and abs(b.segment.sweep) > math.pi + 0.1]
    assert [round(float(b.target[2]), 6) for b in helices] == [-2, -4, -6]
    assert all(np.isclose(b.segment.radius, 11) for b in helices)


def test_a_tilted_plane_keeps_the_datum_a_touch_probe_cycle_set():
    # a German shop's program probes, then tilts (PLANE SPATIAL .. TURN) and machines: the tilted plane's zero is
    # the active preset's, also one TCH PROBE 417 Q305=0 has just set (iTNC 530 cycle manual 15.6: "the TNC
    # automatically sets the display so that the new datum is on the probed surface"); the reader tilted about the
    # context's work offset and lost it. Z+20 over the surface probed at Z 5 is machine Z 25, tilted or not
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+100 R0 FMAX\n"
            "3 TCH PROBE 417 DATUM IN TS AXIS Q263=+10 Q264=+10 Q294=+5 Q320=+2 Q260=+50 Q305=+0 Q333=+0 Q303=+1\n"
            "4 L X+0 Y+0 Z+20 R0 FMAX\n5 PLANE SPATIAL SPA+0 SPB+0 SPC+0 TURN FMAX\n6 L X+0 Y+0 Z+20 R0 FMAX\n"
            "7 PLANE RESET TURN FMAX\n8 L X+0 Y+0 Z+20 R0 FMAX\nEND PGM T MM\n")
    prog = checked_program(text, AC_TABLE)
    assert [float(b.target[2]) for b in prog.blocks if b.number in (4, 6, 8)] == [25.0, 25.0, 25.0]


def test_a_touch_probe_cycle_in_a_tilted_plane_sets_the_datum_of_the_plane():
    # the German shop's program probes Z (cycle 417, Q305=0) in the plane PLANE SPATIAL SPA-90 .. TURN: refused as
    # 'under a tilted plane' before. The probe moves in the tilted plane (on an A/C table its Z is the machine's);
    # the probed face, 5 above the plane's zero, becomes Z0 of the plane; the preset, untilted, moves along the
    # part's +Y, the direction the tilted Z has on the part (our reading): after PLANE RESET, X0 Y0 is machine Y 5
    text = ("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+100 R0 FMAX\n"
            "3 PLANE SPATIAL SPA-90 SPB+0 SPC+0 TURN FMAX\n4 L X+0 Y+0 Z+100 R0 FMAX\n"
            "5 TCH PROBE 417 DATUM IN TS AXIS Q263=+10 Q264=+20 Q294=+5 Q320=+2 Q260=+50 Q305=+0 Q333=+0 Q303=+1\n"
            "6 L X+10 Y+20 Z+0 R0 FMAX\n7 PLANE RESET TURN FMAX\n8 L X+0 Y+0 Z+50 R0 FMAX\nEND PGM T MM\n")
    prog = checked_program(text, AC_TABLE)
    touch = [b for b in prog.blocks if b.number == 5]
    assert np.allclose([b.target for b in touch], [[10, 20, 100], [10, 20, 9], [10, 20, 5], [10, 20, 9],
                                                   [10, 20, 50]])
    assert np.allclose(next(b for b in prog.blocks if b.number == 6).target, [10, 20, 5])
    assert np.allclose(prog.blocks[-1].target, [0, 5, 50])
    with pytest.raises(GCodeError, match=r"TCH PROBE 417 in the tilted plane of PLANE SPATIAL .* writing row 3 of the "
                                         r"preset table \(Q303=1\) is not modelled"):
        parse_heidenhain(text.replace("Q305=+0", "Q305=+3"), source="t.h", context=AC_TABLE)


def test_m128_with_the_feed_of_its_compensation_movements():
    # 'M128 FQ20' (the German shop's program) and 'L .. F125 M128 F1000' (the iTNC 530 manual's example): the F after
    # M128 is "another feed rate, at which the TNC will carry out the compensation movements in the linear axes"
    # (TNC 620 DIN/ISO user's manual 34056x-04, M128), not the path feed: F125 stays; it was refused
    prog = checked_program("0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 FN 0: Q20 = 10000\n3 M128 FQ20\n"
                           "4 L X+0 Y+38.5 Z+5 R0 F125 M128 F1000\n5 L X+10\n6 M129\nEND PGM T MM\n", AC_TABLE)
    assert [round(b.feed * 60, 6) for b in prog.blocks] == [125, 125]
    assert any("M128 F1000: the feed of compensation movements" in n for n in prog.notes)
