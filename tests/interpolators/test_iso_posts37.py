"""Constructs the posts of SheetCAM, CamBam, Siemens NX Post Builder and Mastercam write, read as their controls read
them (session 37, posts37).

Each program is hand-written in the output style of the post named in its test (formats, modal suppression and
block order as the post prints them); the posts were read, not run."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])

#: SheetCAM's Mach3 floating-head plasma posts (``OnPenDown``): ``G28.1 Z3.00`` (Mach3: to Z3, then reference
#: Z onto the floating head's switch), ``G92 Z0.0``, ``G00 Z<pierce height>``, ``M03``, ``G04 P<delay>``.
SHEETCAM_FLOATING_HEAD = ("(Filename: part.tap)\n(Post processor: Mach3 plasma floating head.scpost)\n"
                          "G21 (Units: Metric)\nG40 G90\nF1\n(Part: part)\nG00 Z10.0000\nX20.0000 Y10.0000\n"
                          "G28.1 Z3.00\nG92 Z0.0\nG00 Z3.0000\nM03\nG04 P0.5\nG01 Z1.5000 F1500.0\n"
                          "G03 X20.0000 Y10.0000 I-10.0000 J0.0000\nM05\nG00 Z10.0000\nG00 X0.0000 Y0.0000\nM05 M30\n")


def test_linuxcnc_axis_words_of_g28_1_move_by_the_modal_motion():
    # LinuxCNC rs274ngc interp_check.cc enhance_block: of the group 0 codes only G10, G28, G30, G52 and G92 use axis
    # words ("mode_zero_covets_axes"); "if there is an axis value in the block and no g-code to use it ... set
    # motion_to_be to be the last motion saved". rs274 (benchmarks/linuxcnc_diff.py) runs "G28.1 Z3.00" as: store
    # the position, then G0 to Z3. Before: vcnc dropped the Z word; the G92 Z0 then zeroed Z at 10, not 3, and the
    # pierce ran 7 mm high (Z 13 where rs274 goes to 6)
    prog = checked_iso(SHEETCAM_FLOATING_HEAD, LINUXCNC)
    z = [(b.line, round(float(b.target[2]), 6)) for b in prog.blocks if b.kind != "dwell"]
    assert z[2:5] == [(9, 3.0), (11, 6.0), (14, 4.5)]  # G28.1's G0 to Z3; then Z3, Z1.5 above the new zero
    # the stored position is where the tool stood before the move (convert_modal_0 runs before convert_motion)
    stored = parse_program("G21 G90\nG0 X1 Y2 Z10\nG1 F100 X2\nG28.1 X5\nG0 Z20\nG28\nM2\n", context=LINUXCNC)
    assert [b.target.tolist() for b in stored.blocks][-3:] == [[5.0, 2.0, 10.0], [5.0, 2.0, 20.0], [2.0, 2.0, 10.0]]


@pytest.mark.parametrize("code", ["G30.1", "G92.1", "G92.2", "G92.3", "G4 P0.5"])
def test_linuxcnc_other_group_0_codes_leave_their_axis_words_to_the_motion(code):
    # the same rule for G30.1, G92.1-G92.3 and a dwell with its P (rs274: the dwell, then the move). Before: the Z
    # word was dropped (G30.1, G92.x) or refused ("word Z not allowed in a dwell block")
    prog = parse_program(f"G21 G90\nG0 X1 Y2 Z10\nG92 X0\n{code} Z3\nG1 X5 F100\nM2\n", context=LINUXCNC)
    moves = [b for b in prog.blocks if b.kind != "dwell"]
    assert moves[1].line == 4 and moves[1].kind == "rapid" and float(moves[1].target[2]) == 3.0
    # G92.1/G92.2 dropped the G92 shift of X (1 mm) before the move, G92.3 brought back the one saved with it
    assert float(moves[2].target[0]) == (6.0 if code in ("G30.1", "G92.3", "G4 P0.5") else 5.0)


def test_linuxcnc_dwell_with_p_leaves_x_to_the_motion():
    # with P and X, X is the modal motion's (LinuxCNC: the dwell, then the move), not the dwell time (G04 X<s>
    # alone stays Fanuc's dwell, noted). Before: "G04 needs exactly one of P or X"
    dwell_x = checked_iso("G21 G90\nG0 X1 Y2 Z10\nG1 F100\nG4 P0.5 X3\nM2\n", LINUXCNC)
    assert [(b.kind, float(b.target[0])) for b in dwell_x.blocks][1:] == [("dwell", 1.0), ("line", 3.0)]


FANUC = MachineContext(dialect=DIALECTS["fanuc"])

#: Siemens NX Post Builder's Fanuc 30i post (Unigraphics/PostBuilder fanuc_30i.def): block template ``nurbs``
#: "G06.2 X Y Z K F P<rank>", a block "X Y Z K" per control point, then ``knots`` "K" alone, rank times; here the
#: rational quadratic (rank 3) whose middle weight cos 45 deg makes it a quarter of the circle of radius 50 about
#: X0 Y0 (control points X50 Y0, X50 Y50, X0 Y50; knots 0 0 0 1 1 1).
NX_FANUC_NURBS = ("%\nO0001\nN0010 G40 G17 G90 G21\nN0020 G91 G28 Z0.0\nN0030 T01 M06\n"
                  "N0040 G00 G90 G54 X50. Y0.0 S5000 M03\nN0050 G43 Z10. H01\nN0060 G05.1 Q1\n"
                  "N0070 G01 Z0.0 F500.\nN0080 G06.2 X50. Y0.0 Z0.0 K0.0 F1000. P3\nN0090 X50. Y50. K0.0 R.70710678\n"
                  "N0100 X0.0 Y50. K0.0\nN0110 K1.\nN0120 K1.\nN0130 K1.\nN0140 G01 Y60.\nN0150 G05.1 Q0\n"
                  "N0160 G91 G28 Z0\nN0170 G90\nN0180 M30\n%\n")


def _nurbs_rows(prog):
    return [b for b in prog.blocks if b.line == 15]  # the last knot block's line


def test_fanuc_g06_2_nurbs_runs_the_curve_of_its_knots_and_weights():
    # FANUC Series 15i/150i-MA operator's manual (programming), "NURBS interpolation (G06.2)": "G06.2 [P_] K_ IP_
    # [R_] [F_] ; K_ IP_ [R_] ; ... K_ ; K_ ;", P the rank (2-4, default 4), R the weight (default 1.0), K the knots
    # (control points + rank of them), P(t) = sum N_ik w_i P_i / sum N_ik w_i. Before: refused ("G06.2 NURBS
    # interpolation (Fanuc option): not supported")
    prog = parse_program(NX_FANUC_NURBS, context=FANUC)
    rows = _nurbs_rows(prog)
    ends = np.array([b.target for b in rows])
    assert len(rows) > 4 and all(b.kind == "line" for b in rows)
    assert np.allclose(rows[0].start, [50.0, 0.0, 0.0]) and np.allclose(ends[-1], [0.0, 50.0, 0.0])
    # every chord end on the circle, every chord within 1 um of it (its middle at most 1 um inside)
    assert np.abs(np.hypot(ends[:, 0], ends[:, 1]) - 50.0).max() < 1e-6  # R.70710678: cos 45 deg to 8 digits
    mids = np.array([(b.start + b.target) / 2 for b in rows])
    assert 50.0 - np.hypot(mids[:, 0], mids[:, 1]).min() <= 1e-3
    assert rows[0].feed * 60 == pytest.approx(1000.0)  # F1000. [mm/min] of the G06.2 block; feeds in mm/s
    assert "G06.2 NURBS run as chords within 1 um of the curve" in prog.notes
    after = [b for b in prog.blocks if b.line == 16]
    assert after[0].target.tolist() == pytest.approx([0.0, 60.0, 0.0])  # G01 Y60. ends the NURBS mode


def test_fanuc_g06_2_rank_2_is_the_polygon_of_its_control_points():
    # rank 2 (degree one): the curve is the polygon; knots 0 0 1 2 2 (the first and last two equal). The first
    # block's control point omitted: the current position (15i-MA: "If a control point command is omitted in the
    # first block, the current position where NURBS interpolation is started is the first control point")
    text = "G21 G90 G17\nG00 X0 Y0 Z0\nG01 F600.\nG06.2 P2 K0.\nK0. X10. Y0.\nK1. X10. Y10.\nK2.\nK2.\nM30\n"
    prog = parse_program(text, context=FANUC)
    ends = np.array([b.target for b in prog.blocks if b.line == 8])
    assert np.allclose(ends[-1], [10.0, 10.0, 0.0])
    on_first = np.isclose(ends[:, 1], 0.0) & (ends[:, 0] <= 10.0 + 1e-12)
    on_second = np.isclose(ends[:, 0], 10.0)
    assert np.all(on_first | on_second) and any(np.allclose(p, [10.0, 0.0, 0.0]) for p in ends)


@pytest.mark.parametrize(("edit", "message"), [
    (("N0120 K1.\n", "N0120 X5. K1.\n"), r"a control point after the knot-only blocks began"),
    (("N0100 X0.0 Y50. K0.0\n", "N0100 X0.0 Y50.\n"), r":12:.*without its knot K \(Fanuc alarm 1002\)"),
    (("N0110 K1.\n", "N0110 K.5\n"), r"the first 3 knots are not equal, nor the last 3 \(Fanuc alarm 1007"),
    (("N0130 K1.\n", "N0130 G01 X0.\n"), r":15:.*G06.2 NURBS of line 10: 1 knot-only block\(s\) K missing"),
    (("N0080 G06.2 X50.", "N0080 G06.2 X45."), r"the first control point is not the current position"),
    (("P3\n", "P5\n"), r"G06.2 NURBS rank P5: the rank is 2, 3 or 4"),
    (("N0070 G01 Z0.0", "N0070 G91 G01 Z0.0"), r"G06.2 NURBS under G91"),
])
def test_fanuc_g06_2_refusals_name_what_is_wrong(edit, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(NX_FANUC_NURBS.replace(*edit), context=FANUC)
    # the program's end before the last knot block
    with pytest.raises(GCodeError, match=r"G06.2 NURBS of line 10: 3 knot-only block"):
        parse_program(NX_FANUC_NURBS.split("N0110")[0], context=FANUC)


def test_g06_2_stays_a_named_refusal_outside_fanuc():
    for dialect in ("linuxcnc", "haas"):
        with pytest.raises(GCodeError, match=r"G06.2 NURBS interpolation \(Fanuc option; --dialect fanuc\)"):
            parse_program(NX_FANUC_NURBS.replace("G05.1 Q1", "").replace("G05.1 Q0", ""),
                          context=MachineContext(dialect=DIALECTS[dialect]))
