"""Constructs Autodesk Fusion/HSM post processors write, read as the control reads them (session 36, cps36).

Each program is hand-written in the output style of the post named in its test (formats, modal suppression and
block order as the post prints them); the posts were read, not run: elcf-robot/autodesk-fanuc ``fanuc.cps``
(Autodesk's Fanuc post, 2025/26), OpenPostProject/haas ``haas.cps`` (Autodesk's Haas post, 2023)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
HAAS = MachineContext(dialect=DIALECTS["haas"])

#: fanuc.cps ``writeDrillCycle`` "tapping" with ``useG95`` (or ``usePitchForTapping``) and ``useRigidTapping``
#: "without" (no spindle direction block): ``M29 S..`` then ``G84 .. P0 F<pitch>`` under G95, no M03 before it.
FANUC_RIGID_TAP = ("%\nO1001 (TAP)\nN10 G90 G94 G17 G49 G40 G80\nN15 G21\nN20 G28 G91 Z0.\nN25 G90\n\n(TAP1)\n"
                   "N30 T03 M06\nN35 G17 G90 G95\nN40 G54\nN45 M08\nN50 G00 X10. Y10.\nN55 G43 Z15. H03\n"
                   "N60 G00 Z5.\nN65 G95\nN70 M29 S500\nN75 G98 G84 X10. Y10. Z-10. R5. P0 F1.25\nN80 X20.\n"
                   "N85 G95 G80\nN90 M09\nN95 G28 G91 Z0.\nN100 G90\nN105 G49\nN110 M30\n%\n")


def test_fanuc_rigid_tapping_after_m29_feeds_per_revolution_without_m03():
    # Fanuc 0i-B connection manual (function) B-63833EN "Rigid tapping": "G99 ; M29 S1000 ; G84 Z-100. R-20. F1. ;"
    # (Series 0i-M writes feed per revolution G95): the control turns the spindle in step with Z.
    # Before: "G84 tapping cycle under G95 feed per revolution with the spindle stopped"
    prog = checked_iso(FANUC_RIGID_TAP, FANUC)
    feeds = [b for b in prog.blocks if b.kind == "line"]
    assert [round(float(b.target[2]), 6) for b in feeds] == [-10.0, 5.0, -10.0, 5.0]  # in, out to R (G84), twice
    assert feeds[0].feed * 60 == pytest.approx(1.25 * 500)  # F1.25 mm/rev x S500 [mm/min]; feed in mm/s
    assert any(n.startswith("M29 S.. rigid tapping (Fanuc)") for n in prog.notes)


def test_fanuc_per_revolution_tapping_without_m29_or_m03_stays_refused():
    # without M29 a Fanuc G84 is a floating-holder tap whose spindle the program must start (M03)
    with pytest.raises(GCodeError, match=r"G84 tapping cycle under G95 feed per revolution with the spindle stopped"):
        parse_program(FANUC_RIGID_TAP.replace("N70 M29 S500\n", "N70 S500\n"), context=FANUC)
    # and M29's rigid mode ends at G80: a later G84 under G95 needs M29 (or M03) again
    again = FANUC_RIGID_TAP.replace("N90 M09\n", "N90 G98 G84 X30. Y10. Z-10. R5. P0 F1.25\n")
    with pytest.raises(GCodeError, match=r":21:9: G84 tapping cycle under G95"):
        parse_program(again, context=FANUC)


def test_fanuc_rigid_tapping_ends_with_the_cycle_a_motion_code_cancels():
    # a group 01 code (G00) ends the canned cycle as G80 does (B-64304EN "Canned cycle for drilling": a cycle is
    # canceled by G80 or a group 01 G code) and with it the rigid mode M29 armed (our reading: M29 arms the tapping
    # cycle that follows it). Before (review36): N90's G84 ran as a rigid tap with no M29 or M03, the spindle never
    # started
    again = FANUC_RIGID_TAP.replace("N85 G95 G80\n", "N85 G00 Z15.\n").replace(
        "N90 M09\n", "N90 G98 G84 X30. Y10. Z-10. R5. P0 F1.25\n")
    with pytest.raises(GCodeError, match=r":21:9: G84 tapping cycle under G95"):
        parse_program(again, context=FANUC)
    # M29 in the block of the motion code still arms the cycle after it
    armed = again.replace("N85 G00 Z15.\n", "N85 G00 Z15. M29 S500\n")
    assert [b for b in parse_program(armed, context=FANUC).blocks if b.line == 21]


#: haas.cps ``onCyclePoint`` "right-tapping" with ``useG95forTapping``: ``G95`` then ``G98 G84 .. F<pitch>``; the
#: post starts the spindle in ``onSection``, but a tapping operation after an ``M05`` (or a program that stops the
#: spindle before the tap, as shops edit them) reaches the G84 with it stopped.
HAAS_TAP = ("%\nO01001 (TAP)\nN10 G90 G17\nN15 G21\nN20 G53 G00 Z0.\nN25 T3 M06\nN30 S500 M03\nN35 G54\n"
            "N40 G00 G90 X40. Y30.\nN45 G43 Z15. H03\nN50 G00 Z5.\nN55 M05\nN60 G95\n"
            "N65 G98 G84 X40. Y30. Z-10. R5. F1.25\nN70 G80\nN75 G94\nN80 G53 G00 Z0.\nN85 M30\n%\n")


def test_haas_tapping_cycle_turns_the_spindle_itself():
    # Haas mill operator's manual "G84 Tapping Canned Cycle": "It is not necessary to start the spindle CW before
    # this canned cycle. The control does this automatically." Before: refused as a G95 feed with the spindle stopped
    prog = checked_iso(HAAS_TAP, HAAS)
    tap = [b for b in prog.blocks if b.kind == "line"]
    assert [round(float(b.target[2]), 6) for b in tap] == [-10.0, 5.0]
    assert tap[0].feed * 60 == pytest.approx(625.0)  # F1.25 x S500 [mm/min]
    # a drilling cycle under G95 still needs the spindle turning
    with pytest.raises(GCodeError, match=r"G81 drilling cycle under G95 feed per revolution with the spindle stop"):
        parse_program(HAAS_TAP.replace("G84", "G81"), context=HAAS)


#: A subprogram stored after the main program in the same file (haas.cps ``useSubroutines`` writes M97 local
#: subprograms ``N<n> .. M99``; a shop's edit adds the branch ``M99 P<n>``). Both programs hold an N20.
M99_P_IN_SUB = ("%\nO00001 (MAIN)\nG90 G17 G21\nG00 X0. Y0. Z10.\nM98 P1000\nN10 G00 X5.\nN20 G00 Y7.\nM30\n%\n"
                "O01000 (SUB)\nG00 X1.\nM99 P20\nG00 X2.\nN20 G00 Z-1.\nM99\n%\n")


def test_haas_m99_p_in_a_subprogram_branches_within_it():
    # Haas mill operator's manual 96-8000 (June 1999) p. 376, "Conditional Expressions" (also haascnc.com
    # "Conditional Expressions"): "M99 in the HAAS control has the ability to branch unconditionally to any line in
    # the current subroutine by placing a P code on the same line ... N50 M99 P10 ; branches to line N10. It does not
    # return control to the calling subroutine." Before: vcnc returned to the caller's N20 (Fanuc's rule)
    prog = checked_iso(M99_P_IN_SUB, HAAS)  # the reference too since iso37 (it returned to the caller's N20)
    assert [b.target.tolist() for b in prog.blocks] == [
        [0.0, 0.0, 10.0], [1.0, 0.0, 10.0], [1.0, 0.0, -1.0], [5.0, 0.0, -1.0], [5.0, 7.0, -1.0]]
    # Fanuc's M99 P20 returns to the calling program's N20 (B-64304EN "Subprogram", "Special usage")
    prog = checked_iso(M99_P_IN_SUB, FANUC)
    assert [b.target.tolist() for b in prog.blocks] == [[0.0, 0.0, 10.0], [1.0, 0.0, 10.0], [1.0, 7.0, 10.0]]


def test_haas_conditional_m99_p_loops_inside_a_local_subprogram():
    # haas.cps writes "M97 P<n>" and the local subprogram "N<n> (comment) .. M99" after M30; a conditional
    # "[cond] M99 P<n>" inside it loops within the subprogram, the final M99 returns to the block after the M97
    text = ("%\nO01002 (LOOP)\nG90 G17 G21\n#100 = 0\nM97 P1000\nG00 X50.\nM30\n\nN1000 (SUB)\nN1001 #100 = #100 + 1\n"
            "N1002 G00 X#100\nN1003 [#100 LT 3] M99 P1001\nN1004 M99\n%\n")
    prog = parse_program(text, context=HAAS)
    assert [float(b.target[0]) for b in prog.blocks] == [1.0, 2.0, 3.0, 50.0]


#: haas.cps ``onCyclePoint`` "chip-breaking" with ``useG73Retract`` and an accumulated depth below the hole's depth:
#: ``G98 G73 X.. Y.. Z.. R.. Q<incremental depth> K<accumulated depth> F..``.
HAAS_G73_KQ = ("%\nO01003 (CHIP BREAK)\nN10 G90 G17\nN15 G21\nN20 T2 M06\nN25 S2000 M03\nN30 G54\n"
               "N35 G00 G90 X10. Y10.\nN40 G43 Z15. H02\nN45 G00 Z5.\n"
               "N50 G98 G73 X10. Y10. Z-12. R5. Q2. K6. F200.\nN55 G80\nN60 M30\n%\n")


def test_haas_g73_with_k_and_q_returns_to_r_every_k():
    # Haas mill operator's manual 96-8000 (June 1999) "G73": "If K and Q are both specified ... the tool is returned
    # to the R plane after a number of passes totals up to the K amount". Before: K was ignored (chip breaks only)
    prog = checked_iso(HAAS_G73_KQ, HAAS)
    hole = [round(float(b.target[2]), 3) for b in prog.blocks if b.line == 11]
    assert hole == [3.0, 3.254, 1.0, 1.254, -1.0, 5.0, -0.746, -3.0, -2.746, -5.0, -4.746, -7.0, 5.0, -6.746,
                    -9.0, -8.746, -11.0, -10.746, -12.0, 5.0]
    # Fanuc reads K as the repeat count (one hole here): no return to R between the pecks
    fanuc = parse_program(HAAS_G73_KQ.replace("K6.", "K1"), context=FANUC)
    assert [round(float(b.target[2]), 3) for b in fanuc.blocks if b.line == 11].count(5.0) == 1


def test_haas_display_media_m130_moves_nothing():
    # Fusion's "HAAS - NGC M130" post (AntonTroskin/posts "haas_next_generation_m130(DPRINT).cps") writes
    # "M130 (tool<n>.png)" before each tool change and DPRNT lines with the date and time; Haas NGC mill operator's
    # manual "M130 Display Media / M131 Cancel Display Media". Before: refused as a machine builder's M code
    text = ("%\nO01004 (NGC)\nM130 (part.png)\nG90 G17\nG21\nG187\nG53 G00 Z0.\n\n"
            "DPRNT[1001**START*DATETIME****#3011[80]-#3012[60]]\n\nM130 (tool1.png)\nT1 M06\nS8000 M03\nG154 P1\n"
            "G00 G90 X0. Y0.\nG43 Z15. H01\nG187 P1 E0.01\nG01 Z-1. F500.\nX10.\nG00 Z15.\nM131\nG187\nG53 G00 Z0.\n"
            "M30\n%\n")
    prog = checked_iso(text, HAAS)
    assert prog.blocks[-1].target.tolist() == pytest.approx([10.0, 0.0, 0.0])
    assert "M130/M131 display media (Haas) x3" in prog.notes
    with pytest.raises(GCodeError, match=r"machine-specific M code 'M130'"):  # a Fanuc's M130 is its builder's
        parse_program(text, context=FANUC)


#: haas.cps ``setWorkPlane`` with ``useMultiAxisFeatures`` (DWO) on a UMC (A about X, C about Z): ``G00 A.. C..``,
#: ``G254``, the operation in the machine's axes, ``G255`` before the next indexing.
HAAS_DWO = ("%\nO01005 (DWO)\nG90 G17\nG21\nG53 G00 Z0.\nT1 M06\nS8000 M03\nG54\nG00 G90 A0. C0.\n"
            "G00 A30. C90.\nG254\nG00 G90 X0. Y0.\nG43 Z15. H01\nG01 Z0. F500.\nX10.\nG02 X20. Y0. I5. J0.\n"
            "G98 G81 X20. Y0. Z-2. R3. F100.\nG80\nG00 Z15.\nG255\nG53 G00 Z0.\nG00 A0. C0.\nG00 X0. Y0.\nM30\n%\n")


def _umc_context(**changes) -> MachineContext:
    from interpolators.tilted import Kinematics, RotaryAxis
    kin = Kinematics(axes=(RotaryAxis(name="a", direction="X", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)),
                           RotaryAxis(name="c")))
    return MachineContext(dialect=DIALECTS["haas"], kinematics=kin, extra_axes=("a", "c"), **changes)


def test_haas_dynamic_work_offset_carries_the_work_zero_with_the_table():
    # Haas mill operator's manual (NGC) "G254 Dynamic Work Offset (DWO)": for 3+1 / 3+2 positioning the work offset
    # follows the rotary axes about their centres. The work zero (G54 at the origin, 50 mm above the A pivot) at
    # A30 is turned about X round (0, 0, -50): (0, 50 sin30, -50 + 50 cos30) = (0, 25, -6.699); C90 turns it about
    # the C axis through it, which leaves it in place. Before: "G254 dynamic work offset ...: not supported"
    prog = checked_iso(HAAS_DWO, _umc_context())  # the reference models G254 since iso37
    zero = np.array([0.0, 25.0, -50.0 + 50.0 * np.cos(np.radians(30.0))])
    ends = {b.line: b.target for b in prog.blocks}
    assert ends[12][:2] == pytest.approx(zero[:2])  # X0 Y0: over the carried work zero
    assert ends[13] == pytest.approx(zero + [0.0, 0.0, 15.0])
    assert ends[15] == pytest.approx(zero + [10.0, 0.0, 0.0])
    arc = next(b for b in prog.blocks if b.line == 16)
    assert arc.target == pytest.approx(zero + [20.0, 0.0, 0.0])
    drill = [b.target for b in prog.blocks if b.line == 17]
    assert min(t[2] for t in drill) == pytest.approx(zero[2] - 2.0)
    assert prog.blocks[-1].target == pytest.approx([0.0, 0.0, 0.0])  # G255: G54 itself again
    assert "G254/G255 dynamic work offset x2" in prog.notes


@pytest.mark.parametrize("change, message", [
    ("G00 X10.\nG00 A40.\n", r"axis word A under G254 dynamic work offset: not supported"),
    ("G234 H01\n", r"G234 tool centre point control under G254 dynamic work offset: not supported"),
])
def test_haas_dynamic_work_offset_refuses_turning_the_table_under_it(change, message):
    text = HAAS_DWO.replace("G00 G90 X0. Y0.\n", "G00 G90 X0. Y0.\n" + change, 1)
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=_umc_context())


def test_haas_dynamic_work_offset_needs_the_tables_kinematics():
    with pytest.raises(GCodeError, match=r":11:1: G254 dynamic work offset needs the machine's kinematics"):
        parse_program(HAAS_DWO, context=MachineContext(dialect=DIALECTS["haas"], extra_axes=("a", "c")))


def test_fadal_peck_drilling_with_i_j_k_as_the_fusion_fadal_post_writes_it():
    # 85vmh/LinuxCNCFusionPosts fadal.cps (Autodesk's Fadal post) "deep-drilling" with a peck reduction:
    # "G98 G90 G83 X.. Y.. Z.. R+.. I<first peck> J<reduction> K<minimum peck> F..", as its Haas post writes it.
    # Before: K0.05 was read as Fanuc's repeat count ("repeat count must be a whole number")
    text = ("%\nN1 O1001 (FADAL)\nN2 G90 G94 G17 H0 E0\nN3 G20\nN4 G0 G90 H0 Z0.\nN5 T2 M6\nN6 S1000 M3\nN7 G17\n"
            "N8 G0 G90 E1 X2. Y2.\nN9 G0 H2 Z0.6\nN10 G98 G90 G83 X2. Y2. Z-0.5 R+0.2 I0.2 J0.05 K0.05 F10.\n"
            "N11 G80\nN12 G0 G90 H0 Z0.\nN13 M30\n%\n")
    prog = checked_iso(text, MachineContext(dialect=DIALECTS["fadal"]))
    bottoms = [round(float(b.target[2]) / 25.4, 4) for b in prog.blocks if b.kind == "line"]
    # I0.2 from R0.2, then 0.15, 0.1, and 0.05 (K) onwards
    assert bottoms == [0.0, -0.15, -0.25, -0.3, -0.35, -0.4, -0.45, -0.5]


#: elcf-robot/autodesk-fanuc fanuc.cps ``onCircular`` with "Allow 3D arcs" for an arc in no axis plane:
#: ``G02.4 X Y Z`` of the arc's middle (``getPositionU(0.5)``), then ``X Y Z`` of its end.
FANUC_ARC3D = ("%\nO1003 (3D ARC)\nN10 G90 G94 G17 G49 G40 G80\nN15 G21\nN20 G54\nN25 S1000 M03\n"
               "N30 G00 X0. Y0. Z10.\nN35 G01 X10. Y0. Z0. F500.\nN40 G02.4 X0. Y10. Z5.\nN45 X-10. Y0. Z0.\n"
               "N50 G01 X-12.\nN55 M30\n%\n")


def test_fanuc_three_dimensional_arc_runs_through_its_three_points():
    # Mitsubishi M700V programming manual 6.14 (the Fanuc command's description found): "an arc shape determined by
    # the three points (start point, intermediate point, end point)"; "G02.4 and G03.4 operations are the same".
    # The circle through (10, 0, 0), (0, 10, 5) and (-10, 0, 0): centre on the perpendicular
    # bisector of the first and last points, in their plane z = y / 2: |c - a| = |c - m| gives c = (0, 1, 0.5).
    # Before: "unknown G code 'G02.4'"
    prog = checked_iso(FANUC_ARC3D, FANUC)  # the reference models G02.4 since iso37
    arc = [b for b in prog.blocks if b.line == 10]
    points = np.array([b.target for b in arc])
    a, m, e = np.array([10.0, 0.0, 0.0]), np.array([0.0, 10.0, 5.0]), np.array([-10.0, 0.0, 0.0])
    normal = np.cross(m - a, e - a)
    centre = np.array([0.0, 1.0, 0.5])
    assert np.linalg.norm(a - centre) == pytest.approx(np.linalg.norm(m - centre))
    radius = np.linalg.norm(a - centre)
    assert np.allclose(np.linalg.norm(points - centre, axis=1), radius)  # every chord end on the circle
    assert np.allclose((points - centre) @ normal, 0.0)  # in the plane of the three points
    assert points[-1] == pytest.approx(e)
    assert min(np.linalg.norm(points - m, axis=1)) < 0.2  # it passes the intermediate point
    chords = np.linalg.norm(np.diff(np.vstack([a, points]), axis=0), axis=1)
    assert radius * (1 - np.cos(np.max(chords) / radius / 2)) <= 0.001 + 1e-12  # within SPLINE_TOLERANCE
    assert all(b.feed * 60 == pytest.approx(500.0) for b in arc)
    assert prog.blocks[-1].target.tolist() == pytest.approx([-12.0, 0.0, 0.0])
    # G03.4 is the same arc; an end block without Z keeps the intermediate point's Z
    same = parse_program(FANUC_ARC3D.replace("G02.4", "G03.4"), context=FANUC)
    assert np.allclose([b.target for b in same.blocks if b.line == 10], points)
    flat = parse_program(FANUC_ARC3D.replace("N45 X-10. Y0. Z0.", "N45 X-10. Y0."), context=FANUC)
    assert [b.target for b in flat.blocks if b.line == 10][-1] == pytest.approx([-10.0, 0.0, 5.0])


def test_fanuc_three_dimensional_arc_through_points_on_a_line_runs_straight():
    # M700V 6.14: three points on one line: "axes move in the order of start point, intermediate point, and end
    # point"; under G91 the end point is relative to the intermediate point
    text = FANUC_ARC3D.replace("N40 G02.4 X0. Y10. Z5.\nN45 X-10. Y0. Z0.",
                               "N40 G91 G02.4 X-5. Y0. Z0.\nN45 X5. Y0. Z0.")  # back to the start: 10 - 5 + 5
    prog = parse_program(text, context=FANUC)
    assert [b.target.tolist() for b in prog.blocks if b.line == 10] == [[5.0, 0.0, 0.0], [10.0, 0.0, 0.0]]


@pytest.mark.parametrize("change, context, message", [
    ("N45 X-10. Y0. Z0.\n", FANUC, r":9:.*three-dimensional arc: the intermediate point of line 9 has no end point"),
    ("N45 G01 X-10. Y0. Z0.\n", FANUC, r":10:1: three-dimensional arc: the intermediate point of line 9"),
    ("N45 X-10. Y0. Z0. A5.\n", MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a",)),
     r"G02.4 three-dimensional arc with axis word A: not supported"),
    (None, HAAS, r"G02.4 three-dimensional circular interpolation \(Fanuc option; --dialect fanuc\)"),
])
def test_fanuc_three_dimensional_arc_refusals(change, context, message):
    text = FANUC_ARC3D if change is None else FANUC_ARC3D.replace("N45 X-10. Y0. Z0.\n", change)
    if change == "N45 X-10. Y0. Z0.\n":
        text = FANUC_ARC3D.replace("N45 X-10. Y0. Z0.\nN50 G01 X-12.\n", "")
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=context)


@pytest.mark.parametrize("line, message", [
    # fanuc.cps onOpen on a head machine with tilted planes: parameter No. 5006 bit 6 must be set (before: "unknown
    # function 'PRM'", which read as a typo)
    ("IF[PRM[5006,6]NE1]THEN#3000=91(PARAMETER_5006_BIT_6_MUST_BE_SET_TO_1)",
     r":3:4: malformed value: PRM\[..\] reads a parameter of the control \(Fanuc 30i 'Reading parameters'\)"),
    # fanuc.cps setProbeAngle / onClose with probeAngleMethod "G54.4" (before: "unknown G code 'G54.4'")
    ("G54.4 P1", r":3:1: G54.4 workpiece setting error compensation \(Fanuc option: its data comes from the "
                 r"machine's probing\): not supported"),
])
def test_fanuc_post_constructs_that_read_the_machine_are_named(line, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"%\nO1002\n{line}\nG21\nG00 X1.\nM30\n%\n", context=FANUC)


def test_fanuc_smooth_tolerance_control_names_its_axes_without_moving_them():
    # fanuc.cps setSmoothing with useNanoSmoothing: "G05.1 Q3 X0 Y0 Z0 R<level>" (A0 B0 C0 on a 5-axis operation),
    # "G05.1 Q0" to end it. Before: "G05.1 needs Q0 or Q1 or Q2"
    text = ("%\nO1005\nG90 G94 G17 G49 G40 G80\nG21\nG54\nS1000 M03\nG00 X10. Y10. Z10.\n"
            "G05.1 Q3 X0 Y0 Z0 A0 R5\nG01 X20. F500.\nG05.1 Q0\nM30\n%\n")
    prog = checked_iso(text.replace(" A0", ""), FANUC)
    assert [b.target.tolist() for b in prog.blocks] == [[10.0, 10.0, 10.0], [20.0, 10.0, 10.0]]
    assert "G05.1 Q3 smooth tolerance+ control" in prog.notes
    five = parse_program(text, context=MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a",)))
    assert [b.target.tolist() for b in five.blocks] == [[10.0, 10.0, 10.0], [20.0, 10.0, 10.0]]


@pytest.mark.parametrize("order", ["G55\nG254\n", "G254 G55\n", "G254\nG55\n"])
def test_haas_dynamic_work_offset_carries_the_work_offset_in_force(order):
    # Haas NGC manual "G254 Dynamic Work Offset (DWO)": the control uses the MRZP and "the location of the workpiece
    # (active work offset)". G55 at Y10 Z20 (G54 at 0), (0, 10, 70) from the A pivot (0, 0, -50): at A30 it is
    # carried as test_haas_dynamic_work_offset_carries_the_work_zero_with_the_table turns G54's, to
    # (0, 10 cos30 + 70 sin30, -50 + 70 cos30 - 10 sin30) = (0, 43.660, 5.622), wherever G55 stands: before G254,
    # in its block or after it. Before (review36): after G254, or in its block, the shift of G54's zero
    # (0, 25, -6.699) was added to G55's own offset: Z5. at (0, 35, 18.301)
    text = "%\nO1\nG90 G17 G21\nG54\nG00 A30. C0.\n" + order + "G00 X0. Y0.\nZ5.\nG255\nM30\n%\n"
    prog = parse_program(text, context=_umc_context(work_offsets={"G55": np.array([0.0, 10.0, 20.0])}))
    c, s = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    zero = np.array([0.0, 10.0 * c + 70.0 * s, -50.0 + 70.0 * c - 10.0 * s])
    assert prog.blocks[-1].target == pytest.approx(zero + [0.0, 0.0, 5.0])
