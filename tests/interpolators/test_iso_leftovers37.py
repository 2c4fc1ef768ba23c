"""What session 36's review left of the ISO readings it added (session 37, iso37): Fanuc M29 rigid tapping, G95
without a spindle speed, Haas G254 with incremental moves, Fanuc G02.4/G03.4's two blocks, and LinuxCNC's refusal of
':' program numbers. Each program is written by hand for the test; the control's manual (or rs274, LinuxCNC's own
interpreter) gives the reading, and the independent reference (tests/interpolators/reference_iso.py) agrees."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.reference_iso import ReferenceError, iso_reference
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
HAAS = MachineContext(dialect=DIALECTS["haas"])
LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])


def _refused(text: str, context: MachineContext, message: str, reference: str) -> None:
    """The reader refuses ``text`` with ``message`` and the reference with ``reference`` (regular expressions)."""
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=context)
    with pytest.raises(ReferenceError, match=reference):
        iso_reference(text, context)


def test_linuxcnc_refuses_an_iso_code_program_number():
    # rs274 (LinuxCNC 2.9's standalone interpreter) on "G21 / :1248 / G0 X1 / M2": "Bad character ':' used", at
    # line 2; O1248 it reads (o-code.adoc "Fanuc-Style Numbered Programs"). Before: read as O1248 under linuxcnc
    text = "G21\n:1248\nG0 X1\nM2\n"
    _refused(text, LINUXCNC, r":2:1: ':' before a program number .*rs274: \"Bad character ':' used\".*expected O1248",
             r"line 2: ':' refused under LinuxCNC")
    assert [b.target.tolist() for b in parse_program(text.replace(":", "O"), context=LINUXCNC).blocks] == [
        [1.0, 0.0, 0.0]]
    # Fanuc's ISO code reads ':' as O (B-64304EN "Program number"), as before
    assert [b.target.tolist() for b in parse_program(text, context=FANUC).blocks] == [[1.0, 0.0, 0.0]]


#: A Fanuc rigid tap as Fusion's fanuc.cps writes it (``useRigidTapping`` "without"): ``M29 S..`` right before the
#: ``G84`` under G95, no M03; a drilling series follows.
RIGID = ("%\nO1001\nG21 G90 G17 G54\nG00 X0. Y0. Z10.\nG95\nM29 S500\nG98 G84 X10. Y10. Z-10. R2. F1.25\n"
         "G81 X20. Y10. Z-5. R2. F0.1\nG84 X30. Y10. Z-10. R2. F1.25\nG80\nM30\n%\n")


def test_fanuc_rigid_mode_ends_at_another_canned_cycle():
    # B-64304EN "Canned cycle for drilling": G81 replaces the tapping cycle; with it M29's rigid mode ends (our
    # reading, iso_rigid_tap) and the rigid tap's S is cleared ("specify an S command again after cancellation of
    # rigid tapping"): line 8's G81 under G95 has no spindle speed. Before: G81 and line 9's G84 ran, the G84 as a
    # rigid tap M29 no longer armed. The
    # rigid tap's S is cleared: the reference models no feed, the reader refuses the G81's
    with pytest.raises(GCodeError, match=r":8:1: G81 drilling cycle under G95 feed per revolution without a spindle "
                                         r"speed: S0 \(no S word > 0 before it, or the S of a rigid tap \(M29\), "
                                         r"cleared at its end"):
        parse_program(RIGID, context=FANUC)
    # with the spindle started for the drill, the G84 after it is a floating-holder tap: M29 again or refused
    started = RIGID.replace("G81 X20.", "S800 M03\nG81 X20.").replace("G84 X30.", "M05\nG84 X30.")
    with pytest.raises(GCodeError, match=r":11:1: G84 tapping cycle under G95 feed per revolution with the spindle "
                                         r"stopped"):
        parse_program(started, context=FANUC)
    again = started.replace("M05\nG84 X30.", "M05\nM29 S500\nG84 X30.")
    holes = [b.target.tolist() for b in parse_program(again, context=FANUC).blocks if b.kind == "line"]
    assert holes[-2:] == [[30.0, 10.0, -10.0], [30.0, 10.0, 2.0]]
    assert [b.end.tolist() for b in iso_reference(again, FANUC) if b.kind == "feed"][-2:] == holes[-2:]


def test_fanuc_axis_movement_between_m29_and_its_tap_is_refused():
    # the alarm lists' PS0204 "ILLEGAL AXIS OPERATION": an axis movement between the M29 block and the G84 block
    # (our reading, iso_rigid_tap). The brief's case: M29 S.., then a G81, then the G84. Before: accepted
    text = RIGID.replace("G98 G84 X10. Y10. Z-10. R2. F1.25\n", "").replace("G95\n", "G94\n").replace("F0.1", "F100.")
    _refused(text, FANUC, r":7:1: axis movement after M29 \(line 6\) before its G84/G74: Fanuc refuses it \(alarm "
             r"PS0204", r"line 7: axis movement between M29 and G84/G74 \(Fanuc alarm PS0204\)")
    # a rapid between them, too; a dwell is no movement, and a move in the M29 block itself is taken
    _refused(RIGID.replace("M29 S500\n", "M29 S500\nG00 X10.\n"), FANUC, r":7:1: axis movement after M29",
             r"line 7: axis movement")
    for ok in ("M29 S500\nG04 X1.\n", "G00 Z5. M29 S500\n"):
        text = RIGID.replace("M29 S500\n", ok).replace("G81 X20. Y10. Z-5. R2. F0.1\n", "")
        assert sum(b.kind == "line" for b in parse_program(text, context=FANUC).blocks) == 4
        iso_reference(text, FANUC)


def test_fanuc_rigid_tap_needs_a_spindle_speed():
    # M29 without S and no S in force: the alarm lists' PS0200 "ILLEGAL S CODE COMMAND" (in the rigid tap, an S
    # value is not specified; our reading). Before, under G94: tapped at S0 (F600 mm/min, no spindle)
    text = RIGID.replace("M29 S500", "M29").replace("G95\n", "G94\n").replace("F1.25", "F600.")
    _refused(text, FANUC, r":7:5: G84 tapping cycle after M29 rigid tapping without a spindle speed \(S0\): Fanuc "
             r"refuses it \(alarm PS0200", r"line 7: G84/G74 after M29 with S0 \(Fanuc alarm PS0200\)")
    # the S in force serves: S500 M03 before, M29 alone
    kept = text.replace("M29\n", "S500 M03\nM29\n").replace("G81 X20. Y10. Z-5. R2. F0.1\n", "")
    assert sum(b.kind == "line" for b in parse_program(kept, context=FANUC).blocks) == 4
    # the S of a rigid tap is cleared when it ends: a second M29 without S after G80 is refused again
    second = RIGID.replace("G81 X20. Y10. Z-5. R2. F0.1\nG84 X30.", "G80\nM29\nG84 X30.")
    _refused(second, FANUC, r":10:1: G84 tapping cycle after M29 rigid tapping without a spindle speed",
             r"line 10: G84/G74 after M29 with S0")
    # an S word in the block that ends the cycle is the next operation's
    after = RIGID.replace("G81 X20. Y10. Z-5. R2. F0.1\nG84 X30. Y10. Z-10. R2. F1.25\nG80\n",
                          "G80 S400 M03\nG01 X20. F0.1\n")
    assert parse_program(after, context=FANUC).blocks[-1].feed * 60 == pytest.approx(0.1 * 400)


@pytest.mark.parametrize("dialect, said", [
    ("fanuc", r"F0\.1 per revolution x S0 is no feed"),
    ("linuxcnc", r"rs274: \"Cannot feed with zero spindle speed in feed per rev mode\""),
    ("haas", r"F0\.1 per revolution x S0 is no feed")])
def test_feed_per_revolution_without_a_spindle_speed_names_what_is_missing(dialect, said):
    # Before: "G01 feed move without a feed: G95 feed per revolution with spindle speed S0 (LinuxCNC: ...)", expected
    # "F > 0 [mm/min]" (the F was there), and for a cycle "no feed rate (G95: F and S > 0 per revolution)"
    context = MachineContext(dialect=DIALECTS[dialect])
    with pytest.raises(GCodeError, match=r"<input>:4:1: G01 under G95 feed per revolution without a spindle speed: "
                                         rf"S0 \(no S word > 0 before it.*{said}\).*expected S<spindle speed> > 0 "
                                         r"\[rev/min\] \(and M3/M4\) before a feed move under G95"):
        parse_program("G21 G90 G0 X0 Y0 Z10\nM3\nG95\nG1 X5 F0.1\nM30\n", context=context)
    with pytest.raises(GCodeError, match=r"<input>:4:1: G81 drilling cycle under G95 feed per revolution without a "
                                         rf"spindle speed: S0 .*{said}"):
        parse_program("G21 G90 G0 X0 Y0 Z10\nM3\nG95\nG81 X5 Z-5 R2 F0.1\nG80\nM30\n", context=context)
    with pytest.raises(GCodeError, match=r"<input>:3:1: G01 under G95 feed per revolution: no F word since G95.*"
                                         r"expected F<feed per revolution> > 0 \[mm/rev\] after G95"):
        parse_program("G21 G90 S100 M3\nG95\nG1 X5\nM30\n", context=context)


def _umc(**changes) -> MachineContext:
    """A UMC-like table: A about X round (0, 0, -50), C about Z (as test_iso_posts36.py's)."""
    kin = Kinematics(axes=(RotaryAxis(name="a", direction="X", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)),
                           RotaryAxis(name="c")))
    return MachineContext(dialect=DIALECTS["haas"], kinematics=kin, extra_axes=("a", "c"), **changes)


@pytest.mark.parametrize("order", ["G55\nG254\n", "G254\nG55\n"])
def test_haas_incremental_moves_under_dynamic_work_offset(order):
    # Haas NGC mill manual "G254 Dynamic Work Offset (DWO)": DWO computes "where the work offset has gone" with the
    # rotary positions; a work offset moves the zero, and G91 moves go from where the tool is (Haas "G91 Incremental
    # Position Command"), so increments are the machine's axes' (the post turns the coordinates itself). G55 at
    # (0, 10, 20) is carried by A30 to (0, 10 cos30 + 70 sin30, -50 + 70 cos30 - 10 sin30) (X0 Y0 there, Z at machine
    # 0 still); G91 Y3. Z-2. from Z5.
    # above it; after G255 a G91 X1. goes on from the tool, the zero G55's own again. The reference models G254 now
    # (before, it ignored it: the session-36 tests compared no DWO program with it)
    text = ("%\nO1\nG90 G17 G21\nG54\nG00 A30. C0.\n" + order + "G00 X0. Y0.\nZ5.\nG91 Y3. Z-2.\nX4.\nG90 G255\n"
            "G91 X1.\nG90 Z30.\nM30\n%\n")
    prog = checked_iso(text, _umc(work_offsets={"G55": np.array([0.0, 10.0, 20.0])}))
    c, s = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    zero = np.array([0.0, 10.0 * c + 70.0 * s, -50.0 + 70.0 * c - 10.0 * s])
    ends = [b.target for b in prog.blocks][1:]
    assert np.allclose(ends, [[0, zero[1], 0], zero + [0, 0, 5], zero + [0, 3, 3], zero + [4, 3, 3],
                              zero + [5, 3, 3], [5, zero[1] + 3, 30 + 20]], atol=1e-9)


#: fanuc.cps ``onCircular`` with "Allow 3D arcs" (as test_iso_posts36.py's FANUC_ARC3D): ``G02.4`` and the
#: intermediate point, then the end point block.
ARC3D = ("%\nO1003\nN10 G90 G94 G17 G21 G54\nN15 S1000 M03\nN20 G00 X0. Y0. Z10.\nN25 G01 X10. Y0. Z0. F500.\n"
         "N30 G02.4 X0. Y10. Z5.\nN35 X-10. Y0. Z0.\nN40 G01 X-12.\nN45 M30\n%\n")


@pytest.mark.parametrize("between", ["G04 X1.", "M08", "G91", "G17"])
def test_fanuc_three_dimensional_arc_blocks_follow_each_other(between):
    # Mitsubishi M700V programming manual 6.14 (the command's description found): "G02.4(G03.4) Xx1 Yy1 Zz1 ;
    # Intermediate point designation (1st block) / Xx2 Yy2 Zz2 ; End point designation (2nd block)"; a block between
    # them is neither (our reading, iso_arc3d). Before: a dwell or an M code between them was run and the next
    # block taken as the end point
    text = ARC3D.replace("N35 ", f"N32 {between}\nN35 ")
    _refused(text, FANUC, r":8:1: three-dimensional arc: a block between the intermediate point \(line 7\) and its "
             r"end point block", r"line 8: a block between a G02.4/G03.4 intermediate point and its end point")


def test_fanuc_three_dimensional_arc_takes_a_macro_statement_between_its_blocks():
    # "#100 = 1" is a macro statement, no NC block; the reference now models G02.4 (before, it read the first block
    # as a G01 to the intermediate point, so no test compared a 3-D arc with it)
    text = ARC3D.replace("N35 ", "#100 = 1\nN35 ")
    prog = checked_iso(text, FANUC)
    assert [b.target.tolist() for b in prog.blocks if b.line == 9][-1] == pytest.approx([-10.0, 0.0, 0.0])
    assert not [b for b in prog.blocks if b.line == 7]  # the intermediate point's block moves nothing


def test_haas_g73_k_under_g91_and_without_q():
    # Haas mill operator's manual "G73 High-Speed Peck Drilling Canned Cycle": Q the peck, K the accumulated depth
    # after which the tool goes back to R. Under G91 R counts from the initial Z15. (R-10. is Z5.) and Z from R
    # (Z-15. is Z-10.): pecks of 2 to Z3., Z1., back to R at 4 mm, on to -1., -3., R again, and so on. The reader
    # and the reference agree (checked); a G73 with K and no Q nor I is refused by both (the reference had raised
    # a KeyError)
    text = ("G90 G17 G21\nG00 X10. Y10. Z15.\nS2000 M03\nG91 G98 G73 X0. Y0. Z-15. R-10. Q2. K4. F200.\nG90 G80\n"
            "M30\n")
    prog = checked_iso(text, HAAS)
    feeds = [round(float(b.target[2]), 6) for b in prog.blocks if b.kind == "line"]
    assert feeds == [3.0, 1.0, -1.0, -3.0, -5.0, -7.0, -9.0, -10.0]
    backs = [i for i, b in enumerate(prog.blocks) if b.kind == "rapid" and float(b.target[2]) == 5.0]
    assert len(backs) == 4  # to R first, then after 4, 8 and 12 mm of pecks
    _refused(text.replace(" Q2.", ""), HAAS, r"G73 peck drilling cycle: peck depth Q must be > 0",
             r"G73 without Q")
