"""ISO programs of the fifteenth wild round (issue 18, set /tmp/isowild15) and the first run of the old sets through
LinuxCNC's own interpreter (``benchmarks/linuxcnc_diff.py``, rs274 2.9.0~pre1): PCB programs of pcb-gcode, FlatCAM
and drl2gcode, a grbl pen plotter's examples, college mill programs, a LinuxCNC plasma table's macros, the sample
programs and sim configurations of a LinuxCNC fork with QtPlasmaC. Where ``linuxcnc`` ran what rs274 refuses it now
refuses it as rs274 does, or says so in a note; what rs274 runs, it runs."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from benchmarks.linuxcnc_diff import SPLINE, Move, first_difference, naive_cam_tolerance
from interpolators import load_program, parse_program
from interpolators.context import MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

LINUXCNC = MachineContext().with_dialect("linuxcnc")


def test_i_j_alone_in_the_modal_g02_is_a_full_circle_under_linuxcnc():
    # a plotter's test program (isowild14 TEST_G90.NC): a helix of "X7.5Y0Z-1.I-7.5J0" blocks, then "I-7.5J0".
    # rs274 2.9.0~pre1 runs it (interp_internal.cc enhance_block: a block like "i1" in arc mode takes the modal
    # G2/G3): ARC_FEED back to the start about the centre, one clockwise turn. Checked by the reference.
    text = "G21 G17 G90 F100\nG0 X10 Y0 Z0\nG02 X10 Y0 Z-1 I-5 J0\nI-5 J0\nM2\n"
    prog = checked_iso(text, LINUXCNC)
    circle = prog.blocks[-1]
    assert (circle.kind, circle.line, circle.target.tolist()) == ("arc", 4, [10, 0, -1])
    assert circle.segment.center.tolist() == [5, 0, -1]
    assert circle.segment.sweep == pytest.approx(-2 * math.pi)


@pytest.mark.parametrize(("cycle", "column", "letter", "name"), [
    ("G83 X10 Y0 Z-5 R2 P500 Q2", 19, "P", "G83 peck drilling cycle"),  # a Fanuc/Haas post's dwell (isowild14)
    ("G81 X10 Y0 Z-5 R2 P0.5", 19, "P", "G81 drilling cycle"),
    ("G85 X10 Y0 Z-5 R2 P1", 19, "P", "G85 boring cycle"),
    ("G81 X10 Y0 Z-5 R2 Q1", 19, "Q", "G81 drilling cycle")])
def test_a_cycle_word_linuxcnc_does_not_read_is_refused(cycle, column, letter, name):
    # rs274 2.9.0~pre1: "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 ... to use it", "Q word with
    # no G5, G10, G64, G73, G76, G83, ... that uses it" (interp_check.cc check_other_codes)
    text = f"G21 G90 G17 F100\nG0 X0 Y0 Z5\nS500 M3\n{cycle}\nG80\nM2\n"
    with pytest.raises(GCodeError, match=f":4:{column}: word {letter} in a {name}: LinuxCNC refuses it"):
        parse_program(text, context=LINUXCNC)
    assert parse_program(text, context=MachineContext().with_dialect("haas")).blocks  # Haas posts write them


@pytest.mark.parametrize("cycle", ["G82 X10 Y0 Z-5 R2 P0.5", "G83 X10 Y0 Z-5 R2 Q2", "G73 X10 Y0 Z-5 R2 Q2",
                                   "G84 X10 Y0 Z-5 R2 P0.5", "G86 X10 Y0 Z-5 R2 P0.5", "G89 X10 Y0 Z-5 R2 P0.5"])
def test_the_cycles_that_read_p_or_q_run_under_linuxcnc(cycle):
    # rs274 2.9.0~pre1 runs each: the hole at X10 Y0 down to Z-5, out to the R plane Z2 (its startup retract mode)
    prog = checked_iso(f"G21 G90 G17 F100\nG0 X0 Y0 Z5\nS500 M3\n{cycle}\nG80\nM2\n", LINUXCNC)
    assert min(float(b.target[2]) for b in prog.blocks) == pytest.approx(-5.0)
    assert prog.blocks[-1].target.tolist() == pytest.approx([10.0, 0.0, 2.0])


def test_g53_in_incremental_mode_is_refused_under_linuxcnc():
    # a student Haas program (isowild12): "N1775 G53 G49 Z0." after G91 moves. rs274: "Cannot use g53 incremental"
    # (interp_check.cc check_g_codes), with or without axis words
    for block in ("G53 G0 Z0", "G53 G49"):
        with pytest.raises(GCodeError, match=r":4:1: G53 in incremental distance mode \(G91\): LinuxCNC refuses "
                                             r"it \(\"Cannot use G53 incremental\"\)"):
            parse_program(f"G21 G90\nG0 X1 Y1 Z1\nG91 X1\n{block}\nM2\n", context=LINUXCNC)
    # with G90 in the block it is absolute again: the machine's Z0
    prog = parse_program("G21 G90\nG0 X1 Y1 Z1\nG91 X1\nG90 G53 G0 Z0\nM2\n", context=LINUXCNC)
    assert prog.blocks[-1].target.tolist() == [2, 1, 0]


def test_macro_b_statements_under_linuxcnc_are_noted():
    # a mould shop's Fanuc subprogram (isowild14 O220001.nc) read with the default dialect: rs274 refuses its
    # "IF[#01EQ#0]GOTO8000" ("Unknown word starting with f"); vcnc runs it as Fanuc does and says so
    text = "G21 G90\n#1=0\nIF[#1EQ#0]GOTO100\nG0 X1\nN100 G0 X5\nM2\n"
    prog = parse_program(text, context=LINUXCNC)
    assert [b.target.tolist() for b in prog.blocks] == [[1, 0, 0], [5, 0, 0]]
    assert any("macro B statements" in n and "LinuxCNC refuses" in n for n in prog.notes)
    plain = parse_program("G21 G90\n#1=0\nG0 X1\nM2\n", context=LINUXCNC)
    assert not any("macro B" in n for n in plain.notes)
    fanuc = parse_program(text, context=MachineContext().with_dialect("fanuc"))
    assert not any("macro B" in n for n in fanuc.notes)


def test_a_hal_pin_read_is_named():
    # QtPlasmaC's sample programs: "F#<_hal[plasmac.cut-feed-rate]>" (LinuxCNC overview.adoc, "#<_hal[HAL item]>")
    with pytest.raises(GCodeError, match=r":2:2: named parameter #<_hal\[plasmac.cut-feed-rate\]>: a HAL pin's "
                                         r"value, read from the running machine \(LinuxCNC HAL_PIN_VARS\), which "
                                         r"vcnc does not have"):
        parse_program("G21 G90\nF#<_hal[plasmac.cut-feed-rate]>\nG1 X1\nM2\n", context=LINUXCNC)


def test_qtplasmac_material_change_is_named(tmp_path: Path):
    # QtPlasmaC's "M190 P1" (qtplasmac.adoc, Automatic Material Handling), not Marlin's bed temperature
    path = tmp_path / "cut.ngc"
    path.write_text("G21 G90\nM190 P1\nM66 P3 L3 Q1\nG0 X1\nM2\n")
    with pytest.raises(GCodeError, match=r"\(QtPlasmaC's M190 Pn material change") as err:
        load_program(path, context=LINUXCNC)
    assert "Marlin" not in str(err.value)
    path.write_text("G21 G90\nM190 S60\nG0 X1\nM2\n")  # a printer's start code keeps its Marlin name
    with pytest.raises(GCodeError, match=r"\(Marlin's M190 wait for bed temperature"):
        load_program(path, context=LINUXCNC)


def test_the_naive_cam_tolerance_of_a_program():
    # g-code.adoc G64: Q is the naive CAM tolerance, P when Q is not given; in the program's units
    assert naive_cam_tolerance("G21\nG64 P0.05\nG1 X1\n") == pytest.approx(0.05)
    assert naive_cam_tolerance("G21\nG64 P0.05 Q0.01\n") == pytest.approx(0.01)
    assert naive_cam_tolerance("G20 F6\nG64 P0.001 (blend)\n") == pytest.approx(0.0254)
    assert naive_cam_tolerance("G21\nG61\n(G64 P1 in a comment)\n") == 0.0


def test_moves_rs274_joined_are_passed_over_within_the_tolerance():
    # rs274 joined (0,0)-(1,0.004)-(2,0) into one feed; vcnc keeps the middle point, 0.004 mm off the line
    def line(x, y):
        return Move(kind="line", xyz=np.array([x, y, 0.0]), abc=np.zeros(3))
    want = [line(0, 0), line(2, 0)]
    got = [line(0, 0), line(1, 0.004), line(2, 0)]
    assert first_difference(want, got, merge=0.005) == ""
    assert first_difference(want, got, merge=0.001).startswith("move 2 (vcnc line 0): end [1.0, 0.004, 0.0] mm")


def test_a_nurbs_end_block_holds_the_spline():
    # LinuxCNC's butterfly.ngc: G5.2 .. G5.3 NURBS; vcnc's chords are the G5.3 block's, rs274 prints NURBS_FEED
    assert all(SPLINE.search(t) for t in ("G5.3", "g5.2 X3.53 Y-1.50 P2", "G5 X1 Y1 I1 J0 P0 Q1", "G5.1 X1 I1 J1"))
    assert not any(SPLINE.search(t) for t in ("G53 G0 Z0", "G5.4", "G54"))


def test_a_reused_o_word_label_is_noted_under_linuxcnc():
    # FluidNC's flow control test suite (isowild14) opens every verbose check with "o999 if": each runs in its place,
    # rs274 refuses the second ("5: duplicate O-word label - already defined in line 2")
    text = "G21\no9 if [0]\nG0 X1\no9 endif\no9 if [1]\nG0 X2\no9 endif\nM2\n"
    prog = parse_program(text, context=LINUXCNC)
    assert [b.target.tolist() for b in prog.blocks] == [[2, 0, 0]]
    assert any(n.startswith("O-word label o9 opens 2 if blocks") and "LinuxCNC refuses" in n for n in prog.notes)
    # in two subroutines the same label is no duplicate (rs274 runs both: its offsets are per call frame)
    subs = ("G21\no<a> sub\no9 if [1]\nG0 X1\no9 endif\no<a> endsub\no<b> sub\no9 if [1]\nG0 X2\no9 endif\n"
            "o<b> endsub\no<a> call\no<b> call\nM2\n")
    prog = parse_program(subs, context=LINUXCNC)
    assert [b.target.tolist() for b in prog.blocks] == [[1, 0, 0], [2, 0, 0]]
    assert not any("O-word label" in n for n in prog.notes)


@pytest.mark.parametrize(("code", "message"), [
    ("g84.2 x1 y2 z3 q5 r1", r"G84.2 rigid tapping cycle .*: not supported \(not a LinuxCNC code: it runs where a "
                             r"configuration remaps it, REMAP=G84.2 in its INI, which vcnc does not read\)"),
    ("G88.3 X1", r"unknown G code 'G88.3' \(not a LinuxCNC code: it runs where a configuration remaps it, "
                 r"REMAP=G88.3 in its INI")])
def test_a_code_linuxcnc_runs_only_remapped_is_named(code, message):
    # a LinuxCNC fork's remap examples (configs/sim/axis/remap/cycle: "g84.2 x1 y2 z3 q5 r1"); rs274 without the
    # configuration: "Unknown g code used"
    with pytest.raises(GCodeError, match=f":2:1: {message}"):
        parse_program(f"G21 F100\n{code}\nM2\n", context=LINUXCNC)
    # LinuxCNC's own codes vcnc does not run get no remap hint; other dialects neither
    for text, context in (("G38.2 Z-1", LINUXCNC), (code, MachineContext().with_dialect("fanuc"))):
        with pytest.raises(GCodeError) as err:
            parse_program(f"G21 F100\n{text}\nM2\n", context=context)
        assert "REMAP" not in str(err.value)


def test_g43_h0_is_the_loaded_tool_under_linuxcnc():
    # a Mastercam post's "N3 T212 M6 ... N5 G43 H0 Z10." (corpus): LinuxCNC's find_tool_index takes tool 0 as
    # index 0, the spindle's tool, so the offset is T212's (rs274 2.9.0~pre1: USE_TOOL_LENGTH_OFFSET of T5 below,
    # Z10 + 3.81 in machine coordinates). Fanuc's H0 is the zero offset. Checked by the reference.
    tools = {5: Tool(number=5, length=3.81, radius=1.0)}
    text = "G21 G90\nT5 M6\nG43 H0\nG0 X1 Z10\nM2\n"
    prog = checked_iso(text, MachineContext(tools=tools).with_dialect("linuxcnc"))
    assert prog.blocks[-1].target.tolist() == pytest.approx([1.0, 0.0, 13.81])
    fanuc = parse_program(text, context=MachineContext(tools=tools).with_dialect("fanuc"))
    assert fanuc.blocks[-1].target.tolist() == pytest.approx([1.0, 0.0, 10.0])
