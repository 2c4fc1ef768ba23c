"""Heidenhain touch probe cycles 408 - 413, 417, 419 run on the nominal workpiece: hand-written programs with the
touch points, the moves between them and their feeds worked out by hand from the TNC 320 cycle programming manual
(340 55x-04, "Executing touch probe cycles", cycles 408 - 413, 417, 419; the order of the four touch points of
410/411 is our reading, see interpolators.heidenhain_probing) and the touch probe table of the machine
context (vcnc's defaults: SET_UP 2 mm, F 100 mm/min, FMAX 2000 mm/min, DIST 20 mm), each also checked against
the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool, TouchProbe
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.core.errors import MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import GCodeError

HEAD = "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S50\n2 L X+0 Y+0 Z+100 R0 FMAX\n"
CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -200.0), "G55": (10.0, 10.0, 10.0)})


def run(body: str, context: MachineContext = CTX):
    return checked_program(HEAD + body + "\nEND PGM T MM\n", context)


def moves(prog, line: int):
    """(x, y, z, feed [mm/min]) of the blocks of program line ``line``, in G54's program coordinates."""
    g54 = np.array(CTX.offset("G54"))
    return [(*np.round(b.target - g54, 6).tolist(), round(b.feed * 60, 6)) for b in prog.blocks if b.line == line]


def test_417_probes_down_to_q294_and_sets_the_datum_there():
    prog = run("3 TCH PROBE 417 DATUM IN TS AXIS ~\n  Q263=+10 ;1ST POINT 1ST AXIS ~\n  Q264=+5 ;1ST POINT 2ND AXIS ~\n"
               "  Q294=-2 ~\n  Q320=+3 ~\n  Q260=+50 ~\n  Q305=+0 ~\n  Q333=+0 ~\n  Q303=+1\n"
               "12 L X+0 Y+0 Z+10 FMAX\n13 FN 0: Q1 = Q160")
    # above the clearance height 50: across at Z100, down to Q294 + Q320 + SET_UP = -2 + 3 + 2, probe at F to
    # -2, back at FMAX, up to Q260
    assert moves(prog, 4) == [(10, 5, 100, 2000), (10, 5, 3, 2000), (10, 5, -2, 100), (10, 5, 3, 2000),
                              (10, 5, 50, 2000)]
    # the datum: Z-2 of the old one is Z+0 now, so Z+10 ends 2 mm lower than before the cycle
    assert np.allclose(prog.blocks[-1].target, CTX.offset("G54") + np.array([0.0, 0.0, 8.0]))
    assert "touch probe cycle 417: run on the nominal workpiece (touch points where the data put the surface)" \
        in prog.notes


def test_417_below_the_clearance_height_rises_first():
    prog = run("3 L Z+20 FMAX\n4 TCH PROBE 417 Q263=+0 Q264=+0 Q294=+0 Q320=+0 Q260=+30 Q305=0 Q333=+5")
    assert moves(prog, 5) == [(0, 0, 30, 2000), (0, 0, 2, 2000), (0, 0, 0, 100), (0, 0, 2, 2000), (0, 0, 30, 2000)]


def test_413_outside_circle_four_points_at_clearance_height_between_them():
    ctx = MachineContext(work_offsets=CTX.work_offsets, tools={1: Tool(number=1, length=0.0, radius=3.0)})
    prog = run("3 TCH PROBE 413 DATUM OUTSIDE CIRCLE Q321=+20 Q322=+0 Q262=+40 Q325=+0 Q247=+90 Q261=-5 Q320=+3 "
               "Q260=+50 Q301=+1 Q305=+0 Q331=+0 Q332=+0 Q303=+1 Q423=4 Q365=1\n"
               "4 L X+0 Y+0 FMAX\n5 FN 0: Q1 = Q151 + 1000 * Q153", context=ctx)
    # touch: radius 20 + tip 3 = 23 from (20, 0); start 5 mm (Q320 + SET_UP) further out
    rows = moves(prog, 4)
    assert rows[:5] == [(48, 0, 100, 2000), (48, 0, -5, 2000), (43, 0, -5, 100), (48, 0, -5, 2000), (48, 0, 50, 2000)]
    assert rows[5:8] == [(20, 28, 50, 2000), (20, 28, -5, 2000), (20, 23, -5, 100)]
    # across, down; touch, back; 3 x (up, across, down, touch, back); up
    assert rows[-1] == (20, -28, 50, 2000) and len(rows) == 2 + 2 + 3 * 5 + 1
    # the datum: the centre (20, 0) is (Q331, Q332) = (0, 0) now
    assert np.allclose(prog.blocks[-1].target[:2], np.array(CTX.offset("G54"))[:2] + [20.0, 0.0])


def test_412_inside_circle_arcs_at_measuring_height_and_results():
    prog = run("3 TCH PROBE 412 DATUM INSIDE CIRCLE Q321=+0 Q322=+0 Q262=+30 Q325=+45 Q247=+120 Q261=-3 Q320=+1 "
               "Q260=+20 Q301=+0 Q305=+0 Q331=+5 Q332=-5 Q423=3 Q365=1\n4 L X+0 Y+0 FMAX")
    kinds = [b.kind for b in prog.blocks if b.line == 4]
    assert kinds.count("arc") == 2  # between the three points, at the measuring height (Q365=1: Line=0/arc=1)
    assert [round(b.feed * 60, 6) for b in prog.blocks if b.line == 4 and b.kind == "arc"] == [2000, 2000]
    # touch points on the wall (tip radius 0: the tool has none), 15 mm from the centre at 45, 165, 285 degrees
    touches = [b.target for b in prog.blocks if b.line == 4 and abs(b.feed * 60 - 100) < 1e-9]
    g54 = np.array(CTX.offset("G54"))
    assert np.allclose([np.hypot(*(p - g54)[:2]) for p in touches], 15.0)
    assert prog.blocks[-1].target[0] == pytest.approx(g54[0] - 5.0)  # the centre is X+5 Y-5 now
    assert prog.blocks[-1].target[1] == pytest.approx(g54[1] + 5.0)


def test_412_small_hole_probes_from_the_centre():
    prog = run("3 TCH PROBE 412 Q321=+0 Q322=+0 Q262=+6 Q325=+0 Q247=+90 Q261=-3 Q320=+2 Q260=+20 Q301=+1")
    rows = moves(prog, 4)
    probes = [r for r in rows if r[3] == 100]
    assert probes == [(3, 0, -3, 100), (0, 3, -3, 100), (-3, 0, -3, 100), (0, -3, -3, 100)]
    assert all(r[2] == -3 for r in rows[2:-1])  # no clearance-height moves between the touches


def test_413_q381_also_probes_the_touch_probe_axis():
    prog = run("3 TCH PROBE 413 Q321=+0 Q322=+0 Q262=+20 Q325=+0 Q247=+90 Q261=-5 Q320=+1 Q260=+10 Q301=+1 Q305=0 "
               "Q331=+0 Q332=+0 Q381=+1 Q382=+0 Q383=+0 Q384=+2 Q333=+0\n4 L X+0 Y+0 Z+5 FMAX")
    rows = moves(prog, 4)
    # after the fourth touch (start at Y-13): up to Q260, across to (Q382, Q383), down to Q384 + 3, probe to Q384
    assert rows[-6:] == [(0, -13, 10, 2000), (0, 0, 10, 2000), (0, 0, 5, 2000), (0, 0, 2, 100), (0, 0, 5, 2000),
                         (0, 0, 10, 2000)]
    assert np.allclose(prog.blocks[-1].target, np.array(CTX.offset("G54")) + [0, 0, 7])  # Z+2 is Z+0 now


TOOL3 = MachineContext(work_offsets=CTX.work_offsets, tools={1: Tool(number=1, length=0.0, radius=3.0)})


def test_411_outside_rectangle_paraxial_round_the_corners():
    prog = run("3 TCH PROBE 411 DATUM OUTS. RECTAN. ~\n  Q321=+10 ~\n  Q322=+0 ~\n  Q323=+40 ~\n  Q324=+20 ~\n"
               "  Q261=-5 ~\n  Q320=+3 ~\n  Q260=+50 ~\n  Q301=+0 ~\n  Q305=+0 ~\n  Q331=+0 ~\n  Q332=+0\n"
               "17 L X+0 Y+0 FMAX\n18 FN 0: Q1 = Q151 + 1000 * Q152\n19 L X+Q1 Y+Q154 Z+Q155 FMAX", context=TOOL3)
    # tip 3 + clearance Q320 3 + SET_UP 2: the tip's centre touches 23 / 13 mm from the centre (10, 0), starts
    # 28 / 18 mm out; points left, bottom, right, top, paraxially round the corners at the measuring height
    assert moves(prog, 4) == [
        (-18, 0, 100, 2000), (-18, 0, -5, 2000), (-13, 0, -5, 100), (-18, 0, -5, 2000),
        (-18, -18, -5, 2000), (10, -18, -5, 2000), (10, -13, -5, 100), (10, -18, -5, 2000),
        (38, -18, -5, 2000), (38, 0, -5, 2000), (33, 0, -5, 100), (38, 0, -5, 2000),
        (38, 18, -5, 2000), (10, 18, -5, 2000), (10, 13, -5, 100), (10, 18, -5, 2000), (10, 18, 50, 2000)]
    g54 = np.array(CTX.offset("G54"))
    # the centre (10, 0) is X+0 Y+0 now; Q151 = 10, Q152 = 0, Q154 = 40, Q155 = 20
    assert np.allclose(prog.blocks[-2].target[:2], g54[:2] + [10.0, 0.0])
    assert np.allclose(prog.blocks[-1].target - prog.blocks[-2].target, [10.0, 40.0, 20.0 - 50.0])


def test_410_inside_rectangle_at_clearance_height_between_points():
    prog = run("3 TCH PROBE 410 DATUM INSIDE RECTAN. Q321=+0 Q322=+0 Q323=+60 Q324=+40 Q261=-3 Q320=+1 Q260=+20 "
               "Q301=+1 Q305=+0 Q331=+5 Q332=-5 Q303=+1\n4 L X+0 Y+0 FMAX")
    # no tip radius (the tool has none): touches 30 / 20 mm from the centre, starts 3 mm (Q320 + SET_UP) inside
    assert moves(prog, 4) == [
        (-27, 0, 100, 2000), (-27, 0, -3, 2000), (-30, 0, -3, 100), (-27, 0, -3, 2000),
        (-27, 0, 20, 2000), (0, -17, 20, 2000), (0, -17, -3, 2000), (0, -20, -3, 100), (0, -17, -3, 2000),
        (0, -17, 20, 2000), (27, 0, 20, 2000), (27, 0, -3, 2000), (30, 0, -3, 100), (27, 0, -3, 2000),
        (27, 0, 20, 2000), (0, 17, 20, 2000), (0, 17, -3, 2000), (0, 20, -3, 100), (0, 17, -3, 2000),
        (0, 17, 20, 2000)]
    g54 = np.array(CTX.offset("G54"))
    assert np.allclose(prog.blocks[-1].target[:2], g54[:2] + [-5.0, 5.0])  # the centre is X+5 Y-5 now


def test_410_small_pocket_probes_from_the_centre():
    prog = run("3 TCH PROBE 410 Q321=+0 Q322=+0 Q323=+8 Q324=+30 Q261=-3 Q320=+2 Q260=+20 Q301=+1")
    rows = moves(prog, 4)
    # 4 mm from the centre to the short sides is less than the 4 mm clearance: all four touches from the centre
    assert [r for r in rows if r[3] == 100] == [(-4, 0, -3, 100), (0, -15, -3, 100), (4, 0, -3, 100),
                                               (0, 15, -3, 100)]
    assert all(r[2] == -3 for r in rows[1:-1]) and rows[-1] == (0, 0, 20, 2000)


def test_408_slot_centre_sets_the_datum_in_the_measuring_axis_only():
    prog = run("3 TCH PROBE 408 SLOT CENTER REF PT Q321=+50 Q322=+20 Q311=+12 Q272=+1 Q261=-4 Q320=+1 Q260=+10 "
               "Q301=+0 Q305=+0 Q405=+0 Q303=+1\n4 L X+0 Y+0 FMAX\n5 L X+Q157 Y+Q166 FMAX")
    # touches 6 mm either side of X50, starts 3 mm (Q320 1 + SET_UP 2) inside; Q301=0: across at the measuring height
    assert moves(prog, 4) == [(47, 20, 100, 2000), (47, 20, -4, 2000), (44, 20, -4, 100), (47, 20, -4, 2000),
                              (53, 20, -4, 2000), (56, 20, -4, 100), (53, 20, -4, 2000), (53, 20, 10, 2000)]
    g54 = np.array(CTX.offset("G54"))
    assert np.allclose(prog.blocks[-2].target[:2], g54[:2] + [50.0, 0.0])  # X50 is X0; Y keeps its datum
    assert np.allclose(prog.blocks[-1].target[:2], g54[:2] + [100.0, 12.0])  # Q157 = 50, Q166 = 12


def test_409_ridge_always_passes_over_at_the_clearance_height():
    prog = run("3 TCH PROBE 409 RIDGE CENTER REF PT Q321=+0 Q322=+0 Q311=+10 Q272=+2 Q261=-2 Q320=+0 Q260=+15 "
               "Q305=+0 Q405=+3\n4 L X+0 Y+0 FMAX")
    assert moves(prog, 4) == [(0, -7, 100, 2000), (0, -7, -2, 2000), (0, -5, -2, 100), (0, -7, -2, 2000),
                              (0, -7, 15, 2000), (0, 7, 15, 2000), (0, 7, -2, 2000), (0, 5, -2, 100),
                              (0, 7, -2, 2000), (0, 7, 15, 2000)]
    assert prog.blocks[-1].target[1] == pytest.approx(CTX.offset("G54")[1] - 3.0)  # Y0 of old is Y+3 now


def test_419_datum_in_one_axis():
    prog = run("3 TCH PROBE 419 DATUM IN ONE AXIS Q263=-55 Q264=+0 Q261=-4 Q320=+2 Q260=+5 Q272=+1 Q267=+1 "
               "Q305=+0 Q333=-40 Q303=+1\n4 L X-40 Y+0 FMAX", context=TOOL3)
    # probing in +X: the tip's centre (radius 3) stops at X-58, starts 4 mm (Q320 + SET_UP) before it
    assert moves(prog, 4) == [(-62, 0, 100, 2000), (-62, 0, -4, 2000), (-58, 0, -4, 100), (-62, 0, -4, 2000),
                              (-62, 0, 5, 2000)]
    assert prog.blocks[-1].target[0] == pytest.approx(CTX.offset("G54")[0] - 55.0)  # X-55 reads X-40 now


def test_419_in_the_touch_probe_axis_probes_down_to_q261():
    prog = run("3 TCH PROBE 419 Q263=+5 Q264=+5 Q261=+2 Q320=+0 Q260=+30 Q272=+3 Q267=-1 Q333=+0\n"
               "4 L Z+10 FMAX")
    assert moves(prog, 4) == [(5, 5, 100, 2000), (5, 5, 4, 2000), (5, 5, 2, 100), (5, 5, 4, 2000), (5, 5, 30, 2000)]
    assert prog.blocks[-1].target[2] == pytest.approx(CTX.offset("G54")[2] + 12.0)


def test_421_measure_hole_results_deviations_and_status():
    prog = run("3 TCH PROBE 421 MEASURE HOLE Q273=+50 Q274=+50 Q262=+75 Q325=+0 Q247=+60 Q261=-5 Q320=+0 Q260=+20 "
               "Q301=+1 Q275=+75.12 Q276=+74.95 Q279=+0.1 Q280=+0.1 Q281=+1 Q309=+0 Q330=+0 Q423=4 Q365=1\n"
               "4 L X+Q151 Y+Q152 Z+Q153 FMAX\n5 L X+Q161 Y+Q162 Z+Q163 FMAX\n6 L X+Q180 Y+Q181 Z+Q182 FMAX")
    touches = [r for r in moves(prog, 4) if r[3] == 100]
    # four touches on the D75 wall at 0, 60, 120, 180 degrees (no tip radius), probed from 2 mm inside
    assert [(round(np.hypot(x - 50, y - 50), 6), round(np.degrees(np.arctan2(y - 50, x - 50)), 6), z)
            for x, y, z, _ in touches] == [(37.5, 0, -5), (37.5, 60, -5), (37.5, 120, -5), (37.5, 180, -5)]
    g54 = np.array(CTX.offset("G54"))
    # the datum stays; Q151, Q152 = the centre, Q153 = the diameter, deviations 0, Q180 = 1 (within tolerance)
    assert [tuple(np.round(b.target - g54, 6)) for b in prog.blocks[-3:]] == [(50, 50, 75), (0, 0, 0), (1, 0, 0)]
    assert "TCH PROBE 421: the measuring log (Q281=1) is not written" in prog.notes


def test_424_measure_rectangle_outside_paraxial_and_results():
    prog = run("3 TCH PROBE 424 MEAS. RECTAN. OUTS. Q273=+0 Q274=+0 Q282=+60 Q283=+40 Q261=-5 Q320=+2 Q260=+30 "
               "Q301=+0 Q284=+0 Q285=+0 Q286=+0 Q287=+0 Q279=+0 Q280=+0 Q281=+0\n"
               "4 L X+Q154 Y+Q155 Z+Q164 FMAX")
    rows = moves(prog, 4)
    assert [r for r in rows if r[3] == 100] == [(-30, 0, -5, 100), (0, -20, -5, 100), (30, 0, -5, 100),
                                               (0, 20, -5, 100)]
    assert (-34, -24, -5, 2000) in rows and (34, 24, -5, 2000) in rows  # round the stud's corners, 4 mm off
    assert np.allclose(prog.blocks[-1].target - CTX.offset("G54"), [60.0, 40.0, 0.0])


def test_423_nominal_outside_its_own_limits_is_scrap():
    prog = checked_program(HEAD + "3 TCH PROBE 423 Q273=+0 Q274=+0 Q282=+60 Q283=+40 Q261=-5 Q320=+2 Q260=+30 "
                           "Q284=+59.9 Q285=+59.8\n4 L X+Q180 Y+Q181 Z+Q182 FMAX\nEND PGM T MM\n", CTX, check=False)
    # a pocket larger than its maximum: scrap (TNC 320 cycle manual 16.1, "Classification of results")
    assert np.allclose(prog.blocks[-1].target - CTX.offset("G54"), [0.0, 0.0, 1.0])
    assert "TCH PROBE 423: the nominal workpiece is outside the cycle's limits (scrap)" in prog.notes


def test_427_measure_coordinate():
    prog = run("3 TCH PROBE 427 MEASURE COORDINATE Q263=+10 Q264=+3.5 Q261=-5 Q320=+0 Q272=+2 Q267=-1 Q260=+20 "
               "Q281=+0 Q288=+0 Q289=+0 Q309=+0 Q330=+0\n4 L X+Q160 FMAX", context=TOOL3)
    # probing in -Y onto Y+3.5: the tip's centre (radius 3) stops at Y+6.5, starts SET_UP 2 mm before it
    assert moves(prog, 4) == [(10, 8.5, 100, 2000), (10, 8.5, -5, 2000), (10, 6.5, -5, 100), (10, 8.5, -5, 2000),
                              (10, 8.5, 20, 2000)]
    assert prog.blocks[-1].target[0] == pytest.approx(CTX.offset("G54")[0] + 3.5)  # Q160 = 3.5


def test_426_ridge_width_first_touch_in_the_minus_direction():
    prog = run("3 TCH PROBE 426 MEASURE RIDGE WIDTH Q263=+25 Q264=+0 Q265=-25 Q266=+0 Q272=+1 Q261=-5 Q320=+0 "
               "Q260=+10 Q311=+50 Q288=+0 Q289=+0 Q281=+0\n4 L X+Q156 Y+Q157 Z+Q166 FMAX", context=TOOL3)
    # the tip's centre (radius 3) stops 3 mm off each face, starts SET_UP 2 mm before it; over Q260 between
    assert moves(prog, 4) == [(30, 0, 100, 2000), (30, 0, -5, 2000), (28, 0, -5, 100), (30, 0, -5, 2000),
                              (30, 0, 10, 2000), (-30, 0, 10, 2000), (-30, 0, -5, 2000), (-28, 0, -5, 100),
                              (-30, 0, -5, 2000), (-30, 0, 10, 2000)]
    assert np.allclose(prog.blocks[-1].target - CTX.offset("G54"), [50.0, 0.0, 0.0])  # Q156 50, Q157 0, Q166 0


def test_420_measure_angle_two_touches_at_the_clearance_height_between():
    prog = run("3 TCH PROBE 420 MEASURE ANGLE Q263=+10 Q264=+10 Q265=+15 Q266=+40 Q272=+1 Q267=-1 Q261=-5 Q320=+0 "
               "Q260=+10 Q301=+1 Q281=+0\n4 L X+Q150 FMAX")
    assert moves(prog, 4) == [(12, 10, 100, 2000), (12, 10, -5, 2000), (10, 10, -5, 100), (12, 10, -5, 2000),
                              (12, 10, 10, 2000), (17, 40, 10, 2000), (17, 40, -5, 2000), (15, 40, -5, 100),
                              (17, 40, -5, 2000), (17, 40, 10, 2000)]
    # Q150: the line through (10, 10) and (15, 40) from the reference axis
    assert prog.blocks[-1].target[0] == pytest.approx(CTX.offset("G54")[0] + np.degrees(np.arctan2(30, 5)))


def test_400_basic_rotation_is_zero_and_leaves_the_presets():
    prog = run("3 TCH PROBE 400 BASIC ROTATION Q263=+20 Q264=+5 Q265=+20 Q266=-5 Q272=+1 Q267=+1 Q261=-3 "
               "Q320=+2 Q260=+10 Q301=+0 Q307=+0 Q305=+2\n4 CYCL DEF 247 DATUM SETTING Q339=2\n5 L X+0 Y+0 FMAX")
    assert moves(prog, 4) == [(16, 5, 100, 2000), (16, 5, -3, 2000), (20, 5, -3, 100), (16, 5, -3, 2000),
                              (16, -5, -3, 2000), (20, -5, -3, 100), (16, -5, -3, 2000), (16, -5, 10, 2000)]
    assert np.allclose(prog.blocks[-1].target[:2], CTX.offset("G55")[:2])  # row 2 keeps its datum
    assert "TCH PROBE 400: basic rotation 0 (the nominal workpiece is not misaligned)" in prog.notes


def test_431_measure_plane_three_touches_down():
    prog = run("3 TCH PROBE 431 MEASURE PLANE Q263=+0 Q264=+0 Q294=+0 Q265=+50 Q266=+0 Q295=+0 Q296=+0 Q297=+30 "
               "Q298=+0 Q320=+0 Q260=+20 Q281=+0\n4 L X+Q170 Y+Q173 Z+Q175 FMAX")
    assert [r for r in moves(prog, 4) if r[3] == 100] == [(0, 0, 0, 100), (50, 0, 0, 100), (0, 30, 0, 100)]
    assert moves(prog, 4)[3:6] == [(0, 0, 20, 2000), (50, 0, 20, 2000), (50, 0, 2, 2000)]
    assert np.allclose(prog.blocks[-1].target, CTX.offset("G54"))


def test_q305_row_of_the_preset_table_activated_by_cycle_247():
    prog = run("3 TCH PROBE 417 Q263=+0 Q264=+0 Q294=+10 Q320=+0 Q260=+30 Q305=2 Q333=+0 Q303=1\n"
               "4 L X+0 Y+0 Z+40 FMAX\n5 CYCL DEF 247 DATUM SETTING Q339=2\n6 L X+0 Y+0 Z+40 FMAX")
    g54 = np.array(CTX.offset("G54"))
    assert np.allclose(prog.blocks[-2].target, g54 + [0, 0, 40])  # row 2 written, the active datum kept
    assert np.allclose(prog.blocks[-1].target, g54 + [0, 0, 50])  # preset 2 (G55) = G54's point Z+10


def test_touch_probe_table_from_the_context():
    ctx = MachineContext(touch_probe=TouchProbe(set_up=1.0, feed=50.0, fmax=5000.0, dist=10.0))
    prog = checked_program(HEAD + "3 TCH PROBE 417 Q263=+0 Q264=+0 Q294=+0 Q320=+0 Q260=+30\nEND PGM T MM\n", ctx)
    # already over the point: down to Q294 + SET_UP 1 at FMAX 5000, probe at F 50, back, up to Q260
    assert [round(b.feed * 60, 6) for b in prog.blocks if b.line == 4] == [5000, 50, 5000, 5000]
    assert [round(float(b.target[2]), 6) for b in prog.blocks if b.line == 4] == [1, 0, 1, 30]


def test_touch_probe_table_from_the_machine_file(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + "\n[program.touch_probe]\nset_up = 1.5\nfmax = 3000\n")
    assert load_machine(str(path)).context.touch_probe == TouchProbe(set_up=1.5, fmax=3000.0)
    path.write_text(builtin_machine_text("fadal-pid") + "\n[program.touch_probe]\nspeed = 1\n")
    with pytest.raises(MachineError, match="unknown key 'program.touch_probe.speed'"):
        load_machine(str(path))
    path.write_text(builtin_machine_text("fadal-pid") + "\n[program.touch_probe]\nfeed = 0\n")
    with pytest.raises(MachineError, match="feed must be > 0"):
        load_machine(str(path))


@pytest.mark.parametrize("body, words", [
    ("TCH PROBE 401 ROT OF 2 HOLES Q268=+0", "TCH PROBE 401 is not modelled: the holes' diameters are not in its"),
    ("TCH PROBE 444 PROBING IN 3-D Q263=+0", "TCH PROBE 444 is not modelled (vcnc runs the touch probe cycles 400,"),
    ("TCH PROBE 410 Q321=+0 Q322=+0 Q323=+50 Q261=-3 Q320=+2 Q260=+20", "TCH PROBE 410 lacks Q324"),
    ("TCH PROBE 431 Q263=+0 Q264=+0 Q294=+0 Q265=+50 Q266=+0 Q295=+1 Q296=+0 Q297=+30 Q298=+0 Q320=+0 Q260=+20",
     "a tilted plane (its spatial angles Q170 - Q172) is not modelled"),
    ("TCH PROBE 420 Q263=+0 Q264=+0 Q265=+0 Q266=+9 Q272=+4 Q267=+1 Q261=-3 Q320=+2 Q260=+20", "Q272 = 1, 2 or 3"),
    ("TCH PROBE 408 Q321=+0 Q322=+0 Q311=+10 Q272=+3 Q261=-3 Q320=+2 Q260=+20", "Q272 = 1 or 2"),
    ("TCH PROBE 419 Q263=+0 Q264=+0 Q261=-3 Q320=+2 Q260=+20 Q272=+1 Q267=+0", "Q267 = +1 or -1"),
    ("TCH PROBE 411 Q321=+0 Q322=+0 Q323=+50 Q324=+50 Q261=-3 Q320=+30 Q260=+20", "beyond the touch probe"),
    ("TCH PROBE 413 Q321=+0 Q322=+0 Q262=+20 Q325=+0 Q247=+90 Q261=-3 Q320=+2 Q260=+20 Q381=1 Q382=+0",
     "with Q381=1 (the touch point in the touch probe axis)"),
    ("TCH PROBE 481 CAL. TOOL LENGTH Q340=1", "the tool setter's position is not known"),
    ("TCH PROBE 413 Q321=+0 Q322=+0 Q325=+0 Q247=+90 Q261=-3 Q320=+2 Q260=+20", "TCH PROBE 413 lacks Q262"),
    ("TCH PROBE 417 Q263=+0 Q264=+0 Q294=+0 Q320=+30 Q260=+50", "beyond the touch probe table's DIST"),
    ("TCH PROBE 412 Q321=+0 Q322=+0 Q262=+6 Q325=+0 Q247=+90 Q261=-3 Q320=+2 Q260=+20 Q423=5", "Q423 = 3 or 4"),
    ("TOOL DEF 1 L+0 R+4\n4 TOOL CALL 1 Z\n5 TCH PROBE 412 Q321=+0 Q322=+0 Q262=+6 Q325=+0 Q247=+90 Q261=-3 Q320=+2 "
     "Q260=+20", "does not fit the hole"),
])
def test_errors_name_the_probe_cycle(body, words):
    with pytest.raises(GCodeError) as info:
        parse_heidenhain(HEAD + "3 " + body + "\nEND PGM T MM\n", source="t.h")
    assert words in str(info.value)
    assert info.value.file == "t.h" and info.value.line == 3 + body.count("\n") + 1
