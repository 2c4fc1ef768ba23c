"""Open questions of session 31 on the ISO reader, each a program a user may bring: a '/' after the sequence number,
G53 under G91 (Fanuc/Haas), the corner words ,R ,C under Fanuc DPI = 0, and LinuxCNC's G87/G88."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")
GRBL = MachineContext().with_dialect("grbl")
INCREMENT = dataclasses.replace(FANUC, decimal_point_input="increment")


def _ends(prog) -> list[tuple[float, ...]]:
    return [tuple(round(float(v), 6) for v in b.target[:3]) for b in prog.blocks if b.kind in ("rapid", "line", "arc")]


SKIP_AFTER_N = "G21 G90\nG0 X1 Y0\nN45 /G1 X10 F100\nN46/ Y2\nG0 Z5\nM30\n"


@pytest.mark.parametrize("context", [FANUC, HAAS, GRBL])
def test_a_slash_after_the_sequence_number_runs_its_block_with_the_switch_off(context):
    prog = checked_iso(SKIP_AFTER_N, context)
    assert _ends(prog) == [(1.0, 0.0, 0.0), (10.0, 0.0, 0.0), (10.0, 2.0, 0.0), (10.0, 2.0, 5.0)]
    assert any(n.startswith("/ block skip after the sequence number (N45 /G1 ..): the block runs (switch off)")
               for n in prog.notes)


def test_a_fanuc_skip_level_after_the_sequence_number_runs_too():
    prog = checked_iso("G21 G90\nN10/2 G1 X3 F100\nM30\n", FANUC)
    assert _ends(prog) == [(3.0, 0.0, 0.0)]


def test_a_skip_level_after_the_number_is_named_under_haas():
    with pytest.raises(GCodeError, match=r":1:5: '/2': optional block skip level 2 \(Fanuc's additional optional "
                                         r"block skip /2-/9\), which this dialect does not have"):
        parse_program("N10 /2 G1 X3 F100\nM30\n", context=HAAS)


def test_linuxcnc_refuses_a_slash_after_the_line_number_naming_its_rule():
    # rs274: "Bad character '/' used"; overview.adoc "Format of a Line": the '/' before the line number
    with pytest.raises(GCodeError, match=r":3:5: '/' after the line number 'N45': LinuxCNC reads block delete only "
                                         r"as a line's first character, before its line number \(G-code overview, "
                                         r"\"Format of a Line\"\); expected '/N45 \.\.\.' \(the '/' first\)"):
        parse_program(SKIP_AFTER_N, context=LINUXCNC)


@pytest.mark.parametrize("context", [FANUC, HAAS, GRBL, LINUXCNC])
def test_a_slash_after_another_word_stays_an_error(context):
    with pytest.raises(GCodeError, match=r":1:13: '/' after the word 'F100': arithmetic on a word's value"):
        parse_program("G1 X10 F100 /Y5\nM30\n", context=context)


G53_INCREMENTAL = "G21 G90 G0 X1 Y1 Z0\nG91 G53 G0 X5 Z-2\nG90 G0 Y3\nM30\n"


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_g53_under_g91_moves_by_its_words_under_fanuc_and_haas(context):
    prog = checked_iso(G53_INCREMENTAL, context)
    assert _ends(prog) == [(1.0, 1.0, 0.0), (6.0, 1.0, -2.0), (6.0, 3.0, -2.0)]
    assert any(n.startswith("G53 under G91: its axis words moved as increments") for n in prog.notes)


def test_g53_under_g91_moves_by_its_words_from_a_work_offset_too():
    context = dataclasses.replace(FANUC, work_offsets={**FANUC.work_offsets, "G54": (100.0, 50.0, -20.0)})
    prog = checked_iso("G21 G90 G54 G0 X1 Y1 Z0\nG91 G53 G0 X5\nM30\n", context)
    assert _ends(prog) == [(101.0, 51.0, -20.0), (106.0, 51.0, -20.0)]


def test_grbl_keeps_g53_words_machine_positions_under_g91():
    # grbl gcode.c: "ignore if absolute override is active" (the distance mode is not applied under G53)
    prog = checked_iso(G53_INCREMENTAL, GRBL)
    assert _ends(prog) == [(1.0, 1.0, 0.0), (5.0, 1.0, -2.0), (5.0, 3.0, -2.0)]


def test_linuxcnc_still_refuses_g53_under_g91():
    with pytest.raises(GCodeError, match=r"G53 in incremental distance mode \(G91\): LinuxCNC refuses it"):
        parse_program(G53_INCREMENTAL, context=LINUXCNC)


def test_a_corner_radius_without_a_decimal_point_counts_increments_under_dpi_0():
    prog = checked_iso("G21 G90 G0 X0 Y0\nG1 X10000 ,R2000 F100\nY10000\nM30\n", INCREMENT)
    assert _ends(prog) == [(0.0, 0.0, 0.0), (8.0, 0.0, 0.0), (10.0, 2.0, 0.0), (10.0, 10.0, 0.0)]
    small = checked_iso("G21 G90 G0 X0 Y0\nG1 X10. ,R2 F100\nY10.\nM30\n", INCREMENT)
    assert _ends(small)[1:3] == [(9.998, 0.0, 0.0), (10.0, 0.002, 0.0)]


def test_a_chamfer_with_a_decimal_point_is_in_mm_under_dpi_0():
    prog = checked_iso("G21 G90 G0 X0 Y0\nG1 X10. ,C2. F100\nY10.\nM30\n", INCREMENT)
    assert _ends(prog) == [(0.0, 0.0, 0.0), (8.0, 0.0, 0.0), (10.0, 2.0, 0.0), (10.0, 10.0, 0.0)]


def test_a_corner_radius_without_a_decimal_point_gets_the_calculator_note():
    prog = checked_iso("G21 G90 G0 X0. Y0.\nG1 X10. ,R2 F100\nY10.\nM30\n", FANUC)
    assert _ends(prog)[1:3] == [(8.0, 0.0, 0.0), (10.0, 2.0, 0.0)]
    assert ",R2 without a decimal point read as 2 mm (calculator-type input, Fanuc DPI=1); a Fanuc with DPI=0 " \
           "reads 0.002 mm" in prog.notes


@pytest.mark.parametrize(("code", "tail"), [
    ("G87 X5 Y5 Z-2 R2 I1 J0 K-3", "; --dialect fanuc runs Fanuc's G87 back boring"),
    ("G88 X5 Y5 Z-2 R2 P1", ""),
])
def test_linuxcnc_g87_g88_are_refused_with_what_its_documentation_says(code, tail):
    with pytest.raises(GCodeError, match=r":3:1: G8[78] .*: not supported \(LinuxCNC's G-code reference: \"currently "
                                         r"unimplemented in LinuxCNC\. It is accepted, but the behavior is "
                                         r"undefined\"" + tail):
        parse_program(f"G21 G90 G0 X0 Y0 Z10\nS1000 M3\n{code} F100\nG80\nM2\n", context=LINUXCNC)
