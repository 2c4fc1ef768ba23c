"""Fanuc and Haas mill features of the ``fanuc`` and ``haas`` dialects, with end points worked out by
hand from the controls' manuals (Haas mill operator's manual, G-code chapter; Fanuc 0i-MF operator's
manual), and each program also checked against the independent reference
(:mod:`tests.interpolators.reference_iso`)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

BASE = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))
FANUC = dataclasses.replace(BASE, dialect=DIALECTS["fanuc"])
HAAS = dataclasses.replace(BASE, dialect=DIALECTS["haas"])
LINUXCNC = dataclasses.replace(BASE, dialect=DIALECTS["linuxcnc"])
S = math.sqrt(0.5)


def run(text: str, context: MachineContext = HAAS):
    """The program's blocks, after checking them against the reference."""
    return checked_iso(text, context)


def ends(text: str, context: MachineContext = HAAS) -> list[list[float]]:
    """End points [mm, machine, less the G54 offset] of the non-dwell blocks, rounded to 1 nm."""
    off = np.array([100.0, 50.0, -20.0])
    return [np.round(b.target - off, 6).tolist() for b in run(text, context).blocks if b.kind != "dwell"]


# --- look-ahead and smoothing words ------------------------------------------------------------------

@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_lookahead_words_move_nothing(context):
    text = ("G21 G90 G54\nG187 P3 E0.02\nG103 P4\nG05.1 Q1 R5\nG08 P1\nG05 P10000\nG0 X10 Y5 Z2\nG1 X20 F600\n"
            "G05.1 Q0\nG08 P0\nG05 P0\nG187\nG1 X30\nM30\n")
    prog = run(text, context)
    assert [b.target.tolist() for b in prog.blocks] == [[110, 55, -18], [120, 55, -18], [130, 55, -18]]
    # G187 E is the corner rounding: the path tolerance; G187 alone returns to the default
    assert [b.tolerance for b in prog.blocks] == [0.02, 0.02, context.dialect.tolerance]
    assert not prog.blocks[0].exact_stop
    assert any("G187" in n for n in prog.notes) and any("G05.1" in n for n in prog.notes)


def test_g187_e_in_inches_and_g05_1_q2_axis_words_are_no_motion():
    prog = run("G20 G90 G54\nG187 P1 E0.001\nG05.1 Q2 X0 Y0 Z0\nG0 X1\n", FANUC)
    assert prog.blocks[0].tolerance == pytest.approx(0.0254)
    assert len(prog.blocks) == 1


@pytest.mark.parametrize(("line", "message"), [("G187 P4", "G187 needs P1 or P2 or P3"),
                                                ("G05 P3", "G05"), ("G08 P2", "G08 needs P0 or P1"),
                                                ("G103 P16", "G103 P")])
def test_lookahead_words_with_undefined_values_are_errors(line, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21\n{line}\n", context=FANUC)


def test_linuxcnc_keeps_its_own_meanings():
    with pytest.raises(GCodeError, match="unknown G code 'G187'"):
        parse_program("G21\nG187 P1\n", context=LINUXCNC)
    with pytest.raises(GCodeError, match="G68 coordinate rotation: not supported"):
        parse_program("G21\nG68 X0 Y0 R10\n", context=LINUXCNC)


# --- G68 / G69 coordinate rotation ---------------------------------------------------------------------

def test_g68_rotates_lines_arcs_incremental_moves_and_cycles():
    text = ("G21 G17 G90 G54\nG0 X0 Y0 Z5\nG68 X10 Y0 R90\nG1 X20 Y0 F600\nG2 X10 Y10 I-10 J0\n"
            "G3 X10 Y-10 R10\nG91 G1 X5\nG90 G98 G81 X20 Y0 Z-2 R1\nG80\nG69\nG0 X20 Y0\nM30\n")
    # about (10, 0) by 90 deg: (x, y) -> (10 - y, x - 10)
    assert ends(text) == [[0, 0, 5], [10, 10, 5], [0, 0, 5], [20, 0, 5], [20, 5, 5],
                          [10, 10, 5], [10, 10, 1], [10, 10, -2], [10, 10, 5], [20, 0, 5]]
    prog = run(text)
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    assert [np.round(np.array(a.segment.center) - [100, 50, -20], 6).tolist() for a in arcs] == [[10, 0, 5]] * 2
    assert arcs[0].segment.ccw is False and arcs[1].segment.ccw is True


def test_g68_centre_defaults_to_the_current_position_and_r_is_absolute_under_g91():
    # Haas: no centre words -> the current position; Setting 73 off (default): R absolute
    text = "G21 G90 G54\nG0 X10 Y10 Z0\nG91 G68 R45\nG68 R45\nG90 G1 X20 Y10 F100\nM30\n"
    assert ends(text, FANUC) == [[10, 10, 0], pytest.approx([10 + 10 * S, 10 + 10 * S, 0], abs=1e-6)]


def test_g68_in_g18_rotates_z_and_x():
    # G18: the centre is X Z, counter-clockwise seen from +Y takes +Z to +X: (z, x) -> (-x, z) about (0, 0)
    assert ends("G21 G90 G54\nG0 X0 Y0 Z0\nG18 G68 X0 Z0 R90\nG1 X10 Z0 F100\nG69 G17\nM30\n") == [
        [0, 0, 0], [0, 0, -10]]


def test_g68_rejects_a_word_it_does_not_read():
    with pytest.raises(GCodeError, match="G68 coordinate rotation: only the centre"):
        parse_program("G21\nG68 X0 Y0 R10 Q2\n", context=HAAS)


# --- mill canned cycles: G74, G76, G87 (Haas G77) -------------------------------------------------------

@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g76_fine_boring_shifts_q_along_plus_x_at_the_bottom(context):
    text = "G21 G17 G90 G54\nG0 X0 Y0 Z10\nG98 G76 X5 Y0 Z-10 R2 Q0.5 P500 F100\nG80\nM30\n"
    prog = run(text, context)
    assert ends(text, context) == [[0, 0, 10], [5, 0, 10], [5, 0, 2], [5, 0, -10], [5.5, 0, -10], [5.5, 0, 10],
                                   [5, 0, 10]]
    assert [b.kind for b in prog.blocks][3:5] == ["line", "dwell"] and prog.blocks[4].dwell == 0.5


def test_g76_shift_by_i_j_and_g99_returns_to_r():
    assert ends("G21 G90 G54\nG0 X0 Y0 Z10\nG99 G76 X5 Y5 Z-10 R2 I-0.3 J0.4 F100\nG80\n")[3:] == [
        [5, 5, -10], [4.7, 5.4, -10], [4.7, 5.4, 2], [5, 5, 2]]


def test_g74_counter_tap_moves_as_g84():
    text = "G21 G90 G54\nG0 X0 Y0 Z10\nG99 G74 X10 Z-8 R3 F100\nG80\n"
    assert ends(text, FANUC) == [[0, 0, 10], [10, 0, 10], [10, 0, 3], [10, 0, -8], [10, 0, 3]]
    kinds = [b.kind for b in run(text, FANUC).blocks]
    assert kinds == ["rapid", "rapid", "rapid", "line", "line"]


@pytest.mark.parametrize(("context", "code"), [(FANUC, "G87"), (HAAS, "G77")])
def test_back_boring_from_below(context, code):
    # from the initial level Z3: shift 1 in +X, rapid down to R-20, back, feed up to Z-5, shift, rapid up
    text = f"G21 G90 G54\nG0 X0 Y0 Z3\nG98 {code} X20 Y0 Z-5 R-20 Q1 F50\nG80\n"
    assert ends(text, context) == [[0, 0, 3], [20, 0, 3], [21, 0, 3], [21, 0, -20], [20, 0, -20], [20, 0, -5],
                                   [21, 0, -5], [21, 0, 3], [20, 0, 3]]
    with pytest.raises(GCodeError, match="G99 cannot be used"):
        parse_program(text.replace("G98", "G99"), context=context)


@pytest.mark.parametrize(("context", "line", "message"), [
    (HAAS, "G87 X0 Z-5 R-20 Q1 F50", "G87 .*manual retract"), (FANUC, "G88 X0 Z-5 R1 F50", "G88 boring cycle"),
    (FANUC, "G77 X0 Z-5 R1 F50", "G77 back boring cycle"), (LINUXCNC, "G76 X0 Z-5 R1 F50", "G76 threading"),
    (FANUC, "G76 X0 Z-5 R1 F50", "G76 fine boring cycle: no shift")])
def test_cycles_a_dialect_does_not_run_are_named(context, line, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90\nG0 Z10\n{line}\n", context=context)


# --- Haas bolt-hole patterns G70, G71, G72 -------------------------------------------------------------

def _holes(prog) -> list[list[float]]:
    """X Y [mm, less G54] of the feeds to the bottom of each hole."""
    return [np.round(b.target[:2] - [100.0, 50.0], 6).tolist() for b in prog.blocks if b.kind == "line"]


def test_g70_bolt_hole_circle_about_the_current_point():
    # Haas: L4 holes on radius I10 about X10 Y10, the first at J90 deg; the G81 block's L0 drills nothing
    prog = run("G21 G90 G54\nG0 X10 Y10 Z5\nG98 G81 Z-2 R1 F100 L0\nG70 I10 J90 L4\nG80\nM30\n")
    assert _holes(prog) == [[10, 20], [0, 10], [10, 0], [20, 10]]
    assert ends("G21 G90 G54\nG0 X10 Y10 Z5\nG98 G81 Z-2 R1 F100 L0\nG70 I10 J90 L4\nG80\n")[-1] == [20, 10, 5]


def test_g71_arc_and_g72_line_incremental():
    prog = run("G21 G90 G54\nG0 X0 Y0 Z5\nG99 G81 Z-2 R1 F100 L0\nG71 I10 J0 K-90 L2\nG72 X0 Y0 I5 J90 L2\n"
               "G80\nG91 G99 G81 Z-3 R-4 L0\nG72 I5 J0 L2\nM30\n")
    assert _holes(prog) == [[10, 0], [0, -10], [0, 5], [0, 10], [5, 10], [10, 10]]
    # G91: R-4 from the initial level Z1, Z-3 from R
    assert [round(b.target[2] + 20.0, 6) for b in prog.blocks if b.kind == "line"][-2:] == [-6, -6]


def test_bolt_holes_need_an_active_cycle_and_are_lathe_cycles_in_fanuc():
    with pytest.raises(GCodeError, match="G70 bolt hole circle without an active canned cycle"):
        parse_program("G21\nG0 X0 Y0 Z5\nG70 I10 J0 L4\n", context=HAAS)
    with pytest.raises(GCodeError, match="G70 lathe finishing cycle: not supported"):
        parse_program("G21\nG0 X0 Y0 Z5\nG81 Z-1 R1 F10 L0\nG70 I10 J0 L4\n", context=FANUC)
    with pytest.raises(GCodeError, match="the number of holes L"):
        parse_program("G21\nG0 X0 Y0 Z5\nG81 Z-1 R1 F10 L0\nG70 I10 J0 L2.5\n", context=HAAS)


# --- G51.1 / G50.1 mirror image, G51 / G50 scaling -------------------------------------------------------

MIRROR = ("G21 G17 G90 G54\nG0 X0 Y0 Z0\nG51.1 X0\nG1 X10 Y0 F100\nG2 X20 Y10 R10\nG3 X10 Y20 I-10 J0\n"
          "G50.1 X0\nG1 X0 Y0\nM30\n")


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g51_1_mirror_reverses_arcs(context):
    # X mirrored about X0: x -> -x; G02 runs as G03 (Fanuc "Programmable mirror image")
    prog = run(MIRROR, context)
    assert ends(MIRROR, context) == [[0, 0, 0], [-10, 0, 0], [-20, 10, 0], [-10, 20, 0], [0, 0, 0]]
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    assert [a.segment.ccw for a in arcs] == [True, False]
    assert [np.round(np.array(a.segment.center)[:2] - [100, 50], 6).tolist() for a in arcs] == [[-20, 0], [-10, 10]]


def test_g51_scaling_fanuc_p_in_thousandths_haas_p_as_written():
    body = "G1 X10 Y0 F100\nG2 X20 Y10 R10\nG50\nG1 X0 Y0\n"
    for context, p in ((FANUC, "P2000"), (FANUC, "P2."), (HAAS, "P2.")):
        text = f"G21 G90 G54\nG0 X0 Y0 Z0\nG51 X0 Y0 {p}\n{body}"
        assert ends(text, context) == [[0, 0, 0], [20, 0, 0], [40, 20, 0], [0, 0, 0]]


def test_g51_per_axis_scaling_and_the_arc_it_cannot_scale():
    assert ends("G21 G90 G54\nG0 X10 Y10 Z0\nG51 X10 Y10 I2000 J500\nG1 X20 Y20 F100\nG50\n", FANUC)[-1] == [30, 15, 0]
    with pytest.raises(GCodeError, match="G02 arc under G51 scaling with different factors"):
        parse_program("G21\nG0 X0 Y0\nG51 X0 Y0 I2000 J1000\nG2 X10 Y0 R5 F10\n", context=FANUC)


def test_mirror_swaps_cutter_compensation_side():
    # a 10 mm square traced counter-clockwise with G41 (tool radius 2) is cut from inside (x 2..8). Under a
    # mirror in X it is traced clockwise; Fanuc offsets it as G42, so the tool is again inside: the exact
    # mirror image, x -8..-2 (without the swap it would run outside, x -12..2)
    ctx = dataclasses.replace(FANUC, tools={1: Tool(number=1, radius=2.0)})
    square = "G41 D1 G1 X0 Y-5 F100\nX10\nY5\nX0\nY-5\nG40 G1 X-20 Y-20\n"
    plain = parse_program(f"G21 G90 G54\nG0 X-20 Y-20 Z0\n{square}", context=ctx)
    mirrored = parse_program(f"G21 G90 G54\nG0 X20 Y-20 Z0\nG51.1 X0\n{square}G50.1 X0\n", context=ctx)
    a = [b.target[:2] - [100.0, 50.0] for b in plain.blocks if b.kind == "line"]
    m = [b.target[:2] - [100.0, 50.0] for b in mirrored.blocks if b.kind == "line"]
    assert [p[0] for p in a[1:-1]] == pytest.approx([8, 8, 2, 2])
    assert np.allclose([[-p[0], p[1]] for p in a], m)


# --- Haas G12 / G13 circular pocket milling -------------------------------------------------------------

def test_g12_single_circle_and_g13_stepped_radii():
    text = ("G21 G90 G54\nG0 X10 Y10 Z1\nG12 I5 F300 Z-2\nG0 Z1\nG13 X30 Y10 I2 K6 Q2.5 Z-1\nM30\n")
    prog = run(text)
    rows = [(b.kind, np.round(b.target - [100, 50, -20], 6).tolist(),
             None if b.kind != "arc" else (np.round(np.array(b.segment.center)[:2] - [100, 50], 6).tolist(),
                                           b.segment.ccw)) for b in prog.blocks]
    # G12 I5: down at the centre, half circle (centre 12.5) out to X15, the full circle, back to the centre
    assert rows[1:5] == [("line", [10, 10, -2], None), ("arc", [15, 10, -2], ([12.5, 10], False)),
                         ("arc", [15, 10, -2], ([10, 10], False)), ("line", [10, 10, -2], None)]
    # G13 I2 K6 Q2.5: radii 2, 4.5, 6 (the last step cut short at K), counter-clockwise
    arcs = [r for r in rows[7:] if r[0] == "arc"]
    assert [(a[1][0], a[2][0][0], a[2][1]) for a in arcs] == [
        (32, 31, True), (32, 30, True), (34.5, 33.25, True), (34.5, 30, True), (36, 35.25, True), (36, 30, True)]
    assert rows[-1] == ("line", [30, 10, -1], None)


def test_g12_tool_radius_and_incremental_passes():
    ctx = dataclasses.replace(HAAS, tools={3: Tool(number=3, radius=1.5)})
    prog = run("G21 G90 G54\nG0 X0 Y0 Z0\nG91 G12 I5 Z-1 L2 D3 F100\nM30\n", ctx)
    ends_ = [np.round(b.target - [100, 50, -20], 6).tolist() for b in prog.blocks]
    # the circle's radius less the tool's: 3.5; two passes, 1 mm deeper each
    assert ends_[1:] == [[0, 0, -1], [3.5, 0, -1], [3.5, 0, -1], [0, 0, -1],
                         [0, 0, -2], [3.5, 0, -2], [3.5, 0, -2], [0, 0, -2]]


def test_g12_errors_and_fanuc():
    with pytest.raises(GCodeError, match="G12 circular pocket milling: K .* needs a step Q"):
        parse_program("G21\nG0 X0 Y0 Z0\nG12 I2 K6 Z-1 F100\n", context=HAAS)
    with pytest.raises(GCodeError, match="G12 circular pocket \\(Haas\\): not supported"):
        parse_program("G21\nG0 X0 Y0 Z0\nG12 I2 Z-1 F100\n", context=FANUC)


def test_haas_g101_mirrors_about_the_work_zero():
    # Haas "G101 Enable Mirror Image": about the work coordinate zero, whatever the X value
    text = "G21 G90 G54\nG0 X0 Y0 Z0\nG101 X5\nG1 X10 Y0 F100\nG2 X20 Y10 R10\nG100 X0\nG1 X0 Y0\nM30\n"
    assert ends(text) == [[0, 0, 0], [-10, 0, 0], [-20, 10, 0], [0, 0, 0]]
    with pytest.raises(GCodeError, match="unknown G code 'G101'"):
        parse_program(text, context=FANUC)


def test_runaway_patterns_are_errors():
    with pytest.raises(GCodeError, match="exceed"):
        parse_program("G21\nG0 X0 Y0 Z5\nG81 Z-1 R1 F10 L0\nG70 I10 J0 L99999999\n", context=HAAS)
    with pytest.raises(GCodeError, match="exceed"):
        parse_program("G21\nG0 X0 Y0 Z0\nG12 I1 K1000 Q0.0000001 Z-1 F100\n", context=HAAS)


def test_haas_lathe_g70_form_is_named_as_the_lathe_cycle():
    with pytest.raises(GCodeError, match="G70 lathe finishing cycle: not supported"):
        parse_program("G21\nG0 X0 Z5\nG70 P10 Q20 F0.1\n", context=HAAS)


@pytest.mark.parametrize(("code", "message"), [("G68.2 X0 Y0 Z0 I0 J45 K0", "G68.2 tilted working plane"),
                                               ("G43.4 H1", "G43.4 tool centre point control")])
def test_five_axis_codes_are_named(code, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21\n{code}\n", context=HAAS)


def test_haas_g83_pecks_from_i_j_k_and_k_is_no_repeat_count():
    # Haas "G83": first peck I3, each next J1 less, never below K1.5; R1 to Z-10 (11 mm):
    # pecks to 1-3 = -2, -2-2 = -4, -4-1.5 = -5.5, -7, -8.5, -10 (the bottom)
    text = "G21 G90 G54\nG0 X0 Y0 Z5\nG99 G83 X0 Y0 Z-10 R1 I3 J1 K1.5 F100\nG80\n"
    prog = run(text)
    feeds = [round(b.target[2] + 20.0, 6) for b in prog.blocks if b.kind == "line"]
    assert feeds == [-2, -4, -5.5, -7, -8.5, -10]
    # Fanuc: K is the repeat count (G91: two holes 5 mm apart)
    fanuc = run("G21 G90 G54\nG0 X0 Y0 Z5\nG91 G99 G81 X5 Z-3 R-4 K2 F100\nG80\n", FANUC)
    assert [round(b.target[0] - 100.0, 6) for b in fanuc.blocks if b.kind == "line"] == [5, 10]
