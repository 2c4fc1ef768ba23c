"""Fanuc decimal-point input (:mod:`interpolators.iso_decimal`): parameter DPI (No. 3401#0) = 0 reads
``X10`` in least input increments (IS-B: 0.010 mm, 0.0010 in), DPI = 1 ("calculator-type") as 10 mm.
End points worked out by hand from the Fanuc 0i-MF operator's manual, "Decimal point programming"."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.core.errors import InputError, MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
INCREMENT = dataclasses.replace(FANUC, decimal_point_input="increment")


def ends(text: str, context: MachineContext) -> list[list[float]]:
    prog = parse_program(text, context=context)
    return [np.round(b.target, 9).tolist() for b in prog.blocks if b.kind != "dwell"]


def test_increment_input_counts_integers_in_thousandths_of_a_mm():
    text = "G21 G90 G17\nG0 X0 Y0 Z0\nG1 X10 Y2.5 Z-5 F600\nG91 X-250.\nM30\n"
    assert ends(text, INCREMENT) == [[0, 0, 0], [0.01, 2.5, -0.005], [-249.99, 2.5, -0.005]]
    prog = parse_program(text, context=INCREMENT)
    assert prog.blocks[1].feed == pytest.approx(10.0)  # F600 is 600 mm/min under either setting
    assert ends(text, FANUC) == [[0, 0, 0], [10, 2.5, -5], [-240, 2.5, -5]]


def test_increment_input_in_inch_counts_ten_thousandths():
    text = "G20 G90 G17\nG0 X0 Y0 Z0\nG1 X10 Y1. F20\nM30\n"
    assert ends(text, INCREMENT)[1] == pytest.approx([0.001 * 25.4, 25.4, 0.0])


def test_arc_centre_and_radius_words_follow_the_setting():
    # G2 from (0, 0) to (20 um, 0) about I10 (10 um): a half circle of radius 0.010 mm
    prog = parse_program("G21 G90 G17\nG0 X0 Y0 Z0\nG2 X20 Y0 I10 J0 F100.\nG3 X0 Y0 R10\nM30\n", context=INCREMENT)
    assert prog.blocks[1].segment.radius == pytest.approx(0.010)
    assert prog.blocks[2].segment.radius == pytest.approx(0.010)


def test_values_from_variables_and_expressions_carry_their_own_decimal_point():
    text = "G21 G90 G17\n#1=10\nG0 X#1 Y[5] Z0\nM30\n"
    assert ends(text, INCREMENT) == [[10, 5, 0]]


def test_a_canned_cycle_repeat_count_k_is_not_a_distance():
    text = "G21 G90 G17\nG0 X0 Y0 Z10.\nG91 G81 X10. Y0 Z-5. R-8. K3 F100.\nG80\nM30\n"
    holes = [b for b in parse_program(text, context=INCREMENT).blocks if b.kind == "line"]
    assert len(holes) == 3


def test_look_ahead_switches_are_not_distances():
    prog = parse_program("G21 G90\nG05.1 Q1\nG0 X10 Y0 Z0\nG05.1 Q0\nM30\n", context=INCREMENT)
    assert prog.blocks[0].target.tolist() == [0.01, 0.0, 0.0]


def test_dwell_x_without_a_decimal_point_counts_milliseconds_under_increment_input():
    text = "G21 G90\nG0 X0 Y0 Z0\nG4 X1500\nG4 P1500\nG4 X1.5\nM30\n"
    dwells = [b.dwell for b in parse_program(text, context=INCREMENT).blocks if b.kind == "dwell"]
    assert dwells == pytest.approx([1.5, 1.5, 1.5])
    dwells = [b.dwell for b in parse_program(text, context=FANUC).blocks if b.kind == "dwell"]
    assert dwells == pytest.approx([1500.0, 1.5, 1.5])


def test_calculator_input_notes_the_first_integer_word_once():
    prog = parse_program("G21 G90\nG0 X0 Y0 Z0\nG1 X10 Y20 F600\nX30\nM30\n", context=FANUC)
    notes = [n for n in prog.notes if "decimal point" in n]
    assert notes == ["X10 without a decimal point read as 10 mm (calculator-type input, Fanuc DPI=1); a Fanuc "
                     "with DPI=0 reads 0.010 mm"]
    for context in (FANUC, MachineContext(dialect=DIALECTS["haas"]), MachineContext()):
        prog = parse_program("G21 G90\nG0 X0 Y0. Z0\nG1 X10. F600\nM30\n", context=context)
        assert not [n for n in prog.notes if "decimal point" in n]
    prog = parse_program("G21 G90\nG0 X0 Y0 Z0\nG1 X10 F600\nM30\n", context=MachineContext(dialect=DIALECTS["haas"]))
    assert not [n for n in prog.notes if "decimal point" in n]
    assert prog.blocks[-1].target[0] == 10.0


def test_the_setting_is_checked_and_read_from_the_machine_file(tmp_path):
    with pytest.raises(InputError, match="decimal_point_input must be 'calculator' or 'increment'"):
        MachineContext(decimal_point_input="dpi0")
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndialect = "fanuc"\n'
                    'decimal_point_input = "increment"\n')
    assert load_machine(str(path)).context.decimal_point_input == "increment"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndecimal_point_input = "dpi"\n')
    with pytest.raises(MachineError, match="decimal_point_input"):
        load_machine(str(path))
