"""Codes real Fanuc, Haas and LinuxCNC programs use around the reference position, one-shot stops and tool
offsets (issue #18): Fanuc/Haas G09, G27, G29, G60, Fanuc G22/G23 (:mod:`interpolators.iso_reference`),
LinuxCNC G43.2 and M48-M53. End points worked out by hand from the manuals each test names, and each
program checked against the independent reference (:mod:`tests.interpolators.reference_iso`)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

BASE = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0),
                      tools={1: Tool(number=1, length=10.0), 2: Tool(number=2, length=3.0, offset_x=0.5)})
FANUC = dataclasses.replace(BASE, dialect=DIALECTS["fanuc"])
HAAS = dataclasses.replace(BASE, dialect=DIALECTS["haas"])
LINUXCNC = dataclasses.replace(BASE, dialect=DIALECTS["linuxcnc"])
OFF = np.array([100.0, 50.0, -20.0])


def _ends(prog) -> list[list[float]]:
    """End points of the blocks [mm, machine less the G54 offset], rounded to 1 nm."""
    return [np.round(b.target - OFF, 6).tolist() for b in prog.blocks]


# --- G09 exact stop, one block (Fanuc 0i-MD B-64304EN "Exact stop (G09)"; Haas "G09 Exact Stop") -----------

@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g09_stops_its_block_only_and_keeps_the_path_mode(context):
    prog = checked_iso("G21 G90 G54 G64\nG0 X0. Y0. Z0.\nG1 X10. F600\nG09 X20.\nX30.\nY10.\nM30\n", context)
    stops = [b.exact_stop for b in prog.blocks[1:]]
    assert stops == [False, True, False, False]  # only the G09 block ends at rest
    assert _ends(prog)[2] == [20.0, 0.0, 0.0]
    assert any("G09" in n for n in prog.notes)


def test_g09_is_refused_under_linuxcnc_naming_it():
    # LinuxCNC has no G9 (g-code.adoc lists none; interp_array.cc gees[]: "Unknown g code used")
    with pytest.raises(GCodeError, match=r"G09 exact stop for one block \(Fanuc/Haas"):
        parse_program("G21 G90\nG1 G09 X1 F100\nM2\n", context=LINUXCNC)


# --- G27 / G29 with the G28 before them (Fanuc 0i-MD "Reference position"; Haas "G29") --------------------

def test_g29_returns_through_the_g28_intermediate_point_to_the_programmed_point():
    # G28 X20. Z30.: through X20 Z30 (program) to the reference (machine X0, Z100); G29 X1. Z2.: X and Z to the
    # intermediate point (X20 Z30), then to X1 Z2; Y, not named, stays. G91 G28 Z0.: the intermediate Z is the
    # current Z (2.); G91 G29 Z-3.: back to Z2., then 3 mm down from it.
    text = ("G21 G90 G54\nG0 X5. Y6. Z10.\nG28 X20. Z30.\nG29 X1. Z2.\nG91 G28 Z0.\nG29 Z-3.\nG90\nM30\n")
    for context in (FANUC, HAAS):
        ends = _ends(checked_iso(text, context))
        assert ends[1:] == [[20.0, 6.0, 30.0], [-100.0, 6.0, 120.0], [20.0, 6.0, 30.0], [1.0, 6.0, 2.0],
                            [1.0, 6.0, 2.0], [1.0, 6.0, 120.0], [1.0, 6.0, 2.0], [1.0, 6.0, -1.0]]


def test_g29_follows_a_change_of_work_offset():
    # Fanuc: the intermediate point is kept in workpiece coordinates: after G55 the tool returns through the
    # same program point in the new system
    ctx = dataclasses.replace(FANUC, work_offsets={"G54": (100.0, 50.0, -20.0), "G55": (0.0, 0.0, 0.0)})
    prog = checked_iso("G21 G90 G54\nG0 X5. Y6. Z10.\nG28 Z30.\nG55\nG29 Z4.\nM30\n", ctx)
    assert [b.target.tolist() for b in prog.blocks[-2:]] == [[105.0, 56.0, 30.0], [105.0, 56.0, 4.0]]


@pytest.mark.parametrize("text, message", [
    ("G21 G90\nG0 X1. Y1. Z1.\nG29 X0.\nM30\n", "no G28/G30 intermediate point for axis X"),
    ("G21 G90\nG28 Z10.\nG29 X0.\nM30\n", "no G28/G30 intermediate point for axis X"),
    ("G21 G90\nG28 Z10.\nG29\nM30\n", "G29 return from the reference position needs axis words"),
    ("G21 G90\nG28 Z10.\nG29 Z1. R2.\nM30\n", "with word R: not supported"),
])
def test_g29_errors_name_the_missing_piece(text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=FANUC)


def test_g27_goes_to_the_point_and_notes_an_axis_off_the_reference_position():
    # G27: a rapid to the point, then the check (alarm PS0092 on the control where an axis is not there):
    # machine Z100 is the reference; X-100 (program) is machine X0, the reference too
    prog = checked_iso("G21 G90 G54\nG0 X5. Y6. Z10.\nG27 X-100. Z120.\nG27 Y0.\nM30\n", FANUC)
    assert _ends(prog)[1:] == [[-100.0, 6.0, 120.0], [-100.0, 0.0, 120.0]]
    assert "G27 reference position return check: Y not at the reference position (the control alarms: PS0092)" \
        in prog.notes


@pytest.mark.parametrize("code, context, name", [
    ("G27 X0", HAAS, "G27 reference position return check"), ("G27 X0", LINUXCNC, "G27"),
    ("G29 X0", LINUXCNC, "G29 return from the reference position"), ("G22 X1 Y1", HAAS, "G22 stored stroke"),
    ("G60 X1", LINUXCNC, "G60 single direction positioning"), ("G84.2 X0 Y0 Z-5 R2 F1", FANUC, "G84.2 rigid"),
    ("G84.3 X0 Y0 Z-5 R2 F1", HAAS, "G84.3 left-handed rigid"), ("G43.2 H1", FANUC, "G43.2 additional"),
])
def test_codes_a_dialect_lacks_are_named(code, context, name):
    with pytest.raises(GCodeError, match=name.replace(".", r"\.")):
        parse_program(f"G21 G90\nG0 X0 Y0 Z0\n{code}\nM30\n", context=context)


# --- G60 and G22/G23 -------------------------------------------------------------------------------------

@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g60_positions_at_rapid_to_the_point_and_leaves_the_motion_mode(context):
    # Fanuc "Single direction positioning (G60)", Haas "G60 Uni-Directional Positioning": one-shot; the
    # overrun (a machine parameter) is not modelled: a rapid to the same end point, noted
    prog = checked_iso("G21 G90 G54\nG1 X1. Y1. Z0. F600\nG60 X10. Y-5.\nX12.\nM30\n", context)
    assert [b.kind for b in prog.blocks] == ["line", "rapid", "line"]
    assert _ends(prog) == [[1.0, 1.0, 0.0], [10.0, -5.0, 0.0], [12.0, -5.0, 0.0]]
    assert any("G60" in n and "overrun" in n for n in prog.notes)


def test_g22_words_are_the_forbidden_area_and_move_nothing():
    # Fanuc "Stored stroke check" G22 X Y Z I J K: the area's corners; G23 turns the check off
    prog = checked_iso("G21 G90 G54\nG0 X1. Y2. Z3.\nG22 X50. Y50. Z0. I-50. J-50. K-60.\nG1 X4. F300\nG23\nM30\n",
                       FANUC)
    assert _ends(prog) == [[1.0, 2.0, 3.0], [4.0, 2.0, 3.0]]
    assert any("G22 stored stroke check on" in n for n in prog.notes)


# --- LinuxCNC G43.2 (g-code.adoc "G43.2 Apply additional Tool Length Offset") and M48-M53 ------------------

def test_g43_2_adds_the_tools_offsets_and_the_axis_words_to_the_ones_in_effect():
    # G43 H1: Z +10; G43.2 H2: + tool 2's Z 3 and X 0.5; G43.2 Z0.25: + 0.25; G43 H1 replaces them all again
    text = ("G21 G90 G54\nT1 M6\nG43 H1\nG0 X0 Y0 Z0\nG43.2 H2\nG0 X1 Z0\nG43.2 Z0.25\nG0 Z1\n"
            "G43 H1\nG0 X1 Z2\nM2\n")
    prog = checked_iso(text, LINUXCNC)
    assert _ends(prog) == [[0.0, 0.0, 10.0], [1.5, 0.0, 13.0], [1.5, 0.0, 14.25], [1.0, 0.0, 12.0]]
    assert any("G43.2" in n for n in prog.notes)


@pytest.mark.parametrize("text, message", [
    ("G43.2 H1 Z1\n", "G43.2: can not have both H and axis words"),
    ("G43.2\n", "G43.2: no axes specified and H word missing"),
    ("G41 D1 G1 X5 F100\nG43.2 H1\n", "cannot change tool offset with cutter radius compensation on"),
])
def test_g43_2_errors_as_linuxcnc(text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90\nG0 X0 Y0 Z0\n{text}M2\n", context=LINUXCNC)


def test_m48_to_m53_with_p_move_nothing_and_are_refused_under_compensation():
    # m-code.adoc "M50 Feed Override Control" .. "M53 Feed Stop Control": P0 disables, P1 (or none) enables;
    # interp_convert.cc convert_m refuses them with cutter radius compensation on
    prog = checked_iso("G21 G90\nG0 X0 Y0 Z0\nM50 P0\nM51 P1\nM52 P0\nM53\nM48\nM49\nG1 X5 F100\nM2\n", LINUXCNC)
    assert _ends(prog)[-1] == [5.0, 0.0, 0.0]
    with pytest.raises(GCodeError, match="M50: cannot enable or disable overrides with cutter radius compensation"):
        parse_program("G21 G90\nG0 X0 Y0 Z0\nG41 D1 G1 X5 F100\nM50 P0\nG40 X9\nM2\n", context=LINUXCNC)


def test_g62_and_g63_run_as_continuous_path_and_g61_stops_again():
    # Fanuc modal group 15 (G61 exact stop, G62 automatic corner override, G63 tapping mode, G64 cutting mode):
    # G62 and G63 do not stop at block ends
    prog = checked_iso("G21 G90 G54 G61\nG1 X1. Y0. Z0. F600\nG62\nX2.\nG63\nX3.\nG61\nX4.\nM30\n", FANUC)
    assert [b.exact_stop for b in prog.blocks] == [True, False, False, True]
    assert sum("continuous path as G64" in n for n in prog.notes) == 2


# --- LinuxCNC G5.2/G5.3 NURBS (g-code.adoc "G5.2 G5.3 NURBS Block"; emccanon.cc NURBS_G5_FEED) -------------

NURBS = "G21 G90 G17 G54\nG0 X0 Y0 Z0\nF600\nG5.2 P1 L3\nX0 Y1 P1\nX2 Y2 P1\nX2 Y0 P1\nX0 Y0 P2\nG5.3\nG0 X0 Y1\nM2\n"


def test_nurbs_runs_the_documented_example_as_chords_on_the_g5_3_line():
    # g-code.adoc's example: five control points (the start included), weights 1 1 1 1 2, order 3; the curve
    # ends at the last control point (X0 Y0), on the G5.3 line, at the modal feed
    prog = checked_iso(NURBS, LINUXCNC)
    curve = [b for b in prog.blocks if b.line == 9]
    assert len(curve) > 20 and all(b.kind == "line" and b.feed * 60 == pytest.approx(600.0) for b in curve)
    assert (curve[-1].target - OFF).tolist() == [0.0, 0.0, 0.0]
    assert not [b for b in prog.blocks if 4 <= b.line <= 8]  # the control points move nothing themselves


def test_nurbs_chords_lie_on_the_rational_b_spline():
    # order 3, knots 0 0 0 1 2 3 3 3 (nurbs_G5_knot_vector_creator): at u = 1.5 the basis is N1 = 1/8, N2 = 3/4,
    # N3 = 1/8 (Cox-de Boor, worked out by hand), the weights of P1-P3 are 1: the curve passes through
    # 1/8 (0,1) + 3/4 (2,2) + 1/8 (2,0) = (1.75, 1.625); the chords pass within 1 um of it
    prog = parse_program(NURBS, context=LINUXCNC)
    pts = np.array([b.target[:2] - OFF[:2] for b in prog.blocks if b.line == 9])
    seg_a, seg_b = pts[:-1], pts[1:]
    d = seg_b - seg_a
    t = np.clip(np.einsum("ij,ij->i", np.array([1.75, 1.625]) - seg_a, d) / np.einsum("ij,ij->i", d, d), 0, 1)
    assert np.min(np.linalg.norm(seg_a + t[:, None] * d - [1.75, 1.625], axis=1)) < 1e-3


@pytest.mark.parametrize("text, message", [
    ("G5.3\n", "cannot use G5.3 without G5.2 first"),
    ("G5.2 X1 Y1\nX2 P1\nG5.3\n", "you must specify both X and Y coordinates"),
    ("G5.2 X1 Y1\nX2 Y2\nG5.3\n", "must specify positive weight P for every control point"),
    ("G5.2 L4 X1 Y1\nX2 Y2 P1\nG5.3\n", "at least equal to the order L = 4"),
    ("G5.2 X1 Y1 P1\nX2 Y2 P1\nG1 X0\nG5.3\n", "cannot use G5.3 without G5.2 first"),
    ("G5.2 X1 Y1 Z1 P1\n", "with word Z"),
])
def test_nurbs_errors_as_linuxcnc(text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90 G17\nG0 X0 Y0 Z0\nF600\n{text}M2\n", context=LINUXCNC)


def test_nurbs_in_g91_counts_from_the_start_point_and_is_refused_outside_linuxcnc():
    # LinuxCNC's find_ends reads incremental words from the current position, which stays at the curve's start
    # until G5.3: G91 X2 Y0 is 2 mm from the start, as is the last point X0 Y0 -> the start itself
    prog = checked_iso("G21 G90 G54\nG0 X1 Y1 Z0\nF600\nG91\nG5.2 X0 Y1 P1\nX2 Y1 P1\nX2 Y0 P1\nG5.3\nG90\nM2\n",
                       LINUXCNC)
    assert (prog.blocks[-1].target - OFF).tolist() == [3.0, 1.0, 0.0]
    with pytest.raises(GCodeError, match=r"G5\.2 NURBS block \(LinuxCNC"):
        parse_program(NURBS, context=FANUC)


# --- Haas M codes with P, and codes named in their errors --------------------------------------------------

def test_haas_output_relay_m_codes_take_their_p_and_jumps_on_inputs_are_named():
    # Haas mill operator's manual "M59 Set Output Relay" / "M69 Clear Output Relay" (P: the relay), "M96 Jump If
    # No Input" (where the program goes is the machine's)
    prog = checked_iso("G21 G90 G54\nG0 X0 Y0 Z0\nM59 P1103\nG1 X5. F300\nM69 P1103\nM30\n", HAAS)
    assert _ends(prog) == [[0.0, 0.0, 0.0], [5.0, 0.0, 0.0]]
    with pytest.raises(GCodeError, match=r"M96 jump if no input \(Haas\): not supported"):
        parse_program("G21 G90\nM96 P100 Q8\nM30\n", context=HAAS)
    with pytest.raises(GCodeError, match="word P needs G04"):  # no standard meaning on a Fanuc
        parse_program("G21 G90\nM59 P1103\nM30\n", context=FANUC)


@pytest.mark.parametrize("code, name", [
    ("G66 P9000", "G66 modal macro call"), ("G37 Z0", "G37 automatic tool length measurement"),
    ("G12.1", "G12.1 polar coordinate interpolation"), ("G07.1 C10.", "G07.1 cylindrical interpolation"),
    ("G02.2 X1. Y1.", "G02.2 involute interpolation"), ("G72.1 P1 L2", "G72.1 figure copy, rotary"),
])
def test_fanuc_codes_vcnc_does_not_run_are_named(code, name):
    with pytest.raises(GCodeError, match=name.replace(".", r"\.")):
        parse_program(f"G21 G90\n{code}\nM30\n", context=FANUC)


# --- LinuxCNC M70-M73 (m-code.adoc "M70 Save Modal State" .. "M73 Save and Autorestore Modal State") --------

def test_m70_m72_restore_the_distance_mode_and_units_but_not_the_motion_mode():
    # M70 saves G21 G90 F600; G20 G91 F10 after it; M72 brings back G21 G90 F600: X1 is 1 mm absolute again, in the
    # G1 mode set after M70 (the motion mode is not restored)
    text = "G21 G90 G54\nG0 X0 Y0 Z0\nF600\nM70\nG20 G91\nG1 X1 F10\nM72\nX1\nM2\n"
    prog = checked_iso(text, LINUXCNC)
    assert _ends(prog) == [[0.0, 0.0, 0.0], [25.4, 0.0, 0.0], [1.0, 0.0, 0.0]]
    assert [(b.kind, round(b.feed * 60, 6)) for b in prog.blocks[1:]] == [("line", 254.0), ("line", 600.0)]


def test_m72_restores_a_zero_feed_as_linuxcnc():
    # M70 before any F saves no feed: after M72 a G1 has none (LinuxCNC: "Cannot do g1 with zero feed rate")
    with pytest.raises(GCodeError, match="feed move without a feed"):
        parse_program("G21 G90\nG0 X0 Y0 Z0\nM70\nG1 X1 F10\nM72\nX2\nM2\n", context=LINUXCNC)


def test_m73_restores_the_callers_state_when_the_subroutine_returns():
    # the subroutine switches to G91 after M73; at endsub the caller's G90 is back: X5 is absolute
    text = ("o<inc> sub\nM73\nG91\nG0 X1\no<inc> endsub\nG21 G90 G54\nG0 X0 Y0 Z0\no<inc> call\nG0 X5\n"
            "o<inc> call\nG0 X0\nM2\n")
    prog = checked_iso(text, LINUXCNC)
    assert [e[0] for e in _ends(prog)] == [0.0, 1.0, 5.0, 6.0, 0.0]
    assert any("M73" in n for n in prog.notes)


def test_m71_forgets_the_state_and_m72_then_restores_nothing():
    # LinuxCNC refuses such an M72 ("missing M70/M73?"); vcnc runs on with a note, nothing restored
    prog = checked_iso("G21 G90 G54\nG0 X0 Y0 Z0\nM70\nM71\nG91\nM72\nG0 X1\nG0 X1\nM2\n", LINUXCNC)
    assert [e[0] for e in _ends(prog)] == [0.0, 1.0, 2.0]
    assert any("M72 with no modal state saved" in n for n in prog.notes)


# --- Fanuc G10 L50 and G30 P (Fanuc 0i-MD B-64304EN "Programmable parameter input", "2nd, 3rd and 4th reference
# position return") -------------------------------------------------------------------------------------------

def test_g10_l50_data_lines_up_to_g11_are_not_run():
    prog = checked_iso("G21 G90 G54\nG0 X0 Y0 Z0\nG10 L50\nN1420 P1 R10000\nN5440 P1 R-1.\nG11\nG1 X5. F300\nM30\n",
                       FANUC)
    assert _ends(prog) == [[0.0, 0.0, 0.0], [5.0, 0.0, 0.0]]
    assert any("G10 L50" in n for n in prog.notes)


def test_g30_p_selects_a_reference_position_p3_p4_noted():
    # the second reference position is the context's (machine Z 60 here); P3/P4 are machine parameters vcnc lacks
    ctx = dataclasses.replace(FANUC, reference2=(0.0, 0.0, 60.0))
    for p in ("P2", "P3"):
        prog = checked_iso(f"G21 G90 G54\nG0 X0 Y0 Z0\nG91 G30 {p} Z0.\nG90\nM30\n", ctx)
        assert prog.blocks[-1].target.tolist() == [100.0, 50.0, 60.0]
    assert any("G30 P3: the third reference position" in n for n in prog.notes)
    with pytest.raises(GCodeError, match="G30 P5: no such reference position"):
        parse_program("G21\nG30 P5 Z0.\nM30\n", context=ctx)
    # LinuxCNC refuses a P on G30 ("P word with no ... to use it"): noted, ignored
    prog = parse_program("G21\nG30 P3 Z0\nM2\n", context=LINUXCNC)
    assert any("P word on G30 ignored" in n for n in prog.notes)


def test_fanuc_g43_1_runs_as_g43_and_g30_1_is_refused():
    # Fanuc "Tool length compensation in tool axis direction (G43.1)": with the tool axis along Z, as G43 (H1: 10 mm;
    # the block's Z moves); "Floating reference position return (G30.1)": a machine position vcnc does not know
    prog = checked_iso("G21 G90 G54\nG0 X0 Y0\nG43.1 H1 Z5.\nG1 Z0. F100\nM30\n", FANUC)
    assert _ends(prog)[1:] == [[0.0, 0.0, 15.0], [0.0, 0.0, 10.0]]
    for context in (FANUC, HAAS):
        with pytest.raises(GCodeError, match="G30.1 floating reference position return"):
            parse_program("G21\nG91 G30.1 Z0.\nM30\n", context=context)
    # LinuxCNC: G43.1 Z is the dynamic offset, G30.1 stores the position
    prog = checked_iso("G21 G90 G54\nG0 X0 Y0 Z0\nG43.1 Z5\nG0 Z0\nG30.1\nM2\n", LINUXCNC)
    assert _ends(prog)[-1] == [0.0, 0.0, 5.0]


def test_a_p_on_a_line_with_g64_is_g64s_not_g92_1s():
    # "G64 P0.005 .. G92.1" (a LinuxCNC post's header): the P is the path tolerance, nothing to note on G92.1
    prog = parse_program("G20 G17 G40 G49 G64 P0.005 G80 G90 G92.1 G94\nG0 X1\nM2\n", context=LINUXCNC)
    assert not any("P word on" in n for n in prog.notes)
    assert prog.blocks[0].tolerance == pytest.approx(0.005 * 25.4)
