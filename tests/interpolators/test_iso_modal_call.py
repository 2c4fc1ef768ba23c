"""Fanuc modal macro calls G66 / G66.1 / G67 (:mod:`interpolators.iso_modal_call`).

Hand-written programs; the expected end points are worked out by hand from the Fanuc 0i-MD operator's manual
(B-64304EN, "Custom macro", "Modal call: call after the move command (G66)": after every block with a move until
G67 the macro runs with the G66 block's arguments, not in the G66 block, not for a block without a move) and for
nesting from the Mitsubishi M700V manual 13.5 Note 2 and the NCT 99M manual 20 (the modal call specified last is
made first, its macro's moves make the one before; G67 cancels the last one).
"""

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
START = "O0001\nG21 G17 G90 G40 G49 G80\nG0 X0 Y0 Z10.\n"


def _rows(text: str, context: MachineContext = FANUC) -> list[tuple[int, list[float]]]:
    """(line, end point) of each block."""
    return [(b.line, [round(float(v), 9) + 0.0 for v in b.target])
            for b in parse_program(text, context=context).blocks]


def _ends(text: str) -> list[list[float]]:
    return [end for _, end in _rows(text)]


#: A drilling macro: down to -#1 at rapid, to -#2 at feed, back up to Z10 (its lines are 4-6 after O9100).
DRILL = "O9100\nG0 Z-#1\nG1 Z-#2 F300.\nG0 Z10.\nM99\n"


def test_g66_calls_the_macro_after_each_move_until_g67():
    """Moves X10 and Y20 and X30 Y40 each run O9100 (Z-2, Z-5, Z10 with A2. B5.); M5 and a macro statement move
    nothing and call nothing; after G67 the move X0 Y0 runs alone. The macro's rows carry its own line numbers."""
    text = (START + "G66 P9100 A2. B5.\nX10.\nY20.\nM5\n#100 = 1.\nX30. Y40.\nG67\nX0 Y0\nM30\n" + DRILL)
    drill = [(14, [0, 0, -2.0]), (15, [0, 0, -5.0]), (16, [0, 0, 10.0])]

    def at(x, y):
        return [(line, [x, y, z]) for line, (_, _, z) in drill]
    assert _rows(text) == [(3, [0, 0, 10.0]), (5, [10.0, 0, 10.0]), *at(10.0, 0), (6, [10.0, 20.0, 10.0]),
                           *at(10.0, 20.0), (9, [30.0, 40.0, 10.0]), *at(30.0, 40.0), (11, [0, 0, 10.0])]


def test_the_g66_block_moves_nothing_and_its_axis_words_are_arguments():
    """``G66 P9101 X5. Z-1.``: X and Z are arguments #24 and #26 (no move, no call in that block); the macro moves
    to X#24 at each call."""
    text = START + "G66 P9101 X5. Z-1.\nY7.\nG67\nM30\nO9101\nG1 X#24 Z#26 F100.\nM99\n"
    assert _ends(text) == [[0, 0, 10.0], [0, 7.0, 10.0], [5.0, 7.0, -1.0]]


def test_each_call_starts_from_the_g66_arguments_and_l_repeats_keep_the_locals():
    """The macro adds 10 to #1 and goes to Z#1: with A1. each call starts at #1 = 1 (Z11 after each move, not Z21
    at the second), and with L2 the second repetition of one call sees the first's #1 (Z11, Z21), as for G65."""
    macro = "O9102\n#1 = #1 + 10.\nG0 Z#1\nM99\n"
    once = START + "G66 P9102 A1.\nX1.\nX2.\nG67\nM30\n" + macro
    assert _ends(once) == [[0, 0, 10.0], [1.0, 0, 10.0], [1.0, 0, 11.0], [2.0, 0, 11.0], [2.0, 0, 11.0]]
    twice = START + "G66 P9102 L2 A1.\nX1.\nG67\nM30\n" + macro
    assert _ends(twice) == [[0, 0, 10.0], [1.0, 0, 10.0], [1.0, 0, 11.0], [1.0, 0, 21.0]]


def test_the_macro_moves_do_not_call_it_again_and_m98_subprogram_moves_do():
    """The macro's own moves make no call (a single G66 does not nest itself); the moves of an M98 subprogram
    called in G66 mode do (our reading: M98 keeps the local level)."""
    text = (START + "G66 P9103\nM98 P2000\nG67\nM30\nO2000\nX10.\nX20.\nM99\n"
            "O9103\nG91 G0 Z-1.\nG90\nM99\n")
    assert _ends(text) == [[0, 0, 10.0], [10.0, 0, 10.0], [10.0, 0, 9.0], [20.0, 0, 9.0], [20.0, 0, 8.0]]


def test_nested_g66_the_last_one_first_and_its_moves_call_the_one_before():
    """G66 P9104 (Z down 1, incremental) then G66 P9105 (Y up 5): a main move calls O9105, whose move calls
    O9104; G67 cancels O9105, and the next move calls O9104 alone."""
    text = (START + "G66 P9104\nG66 P9105\nX10.\nG67\nX20.\nG67\nX30.\nM30\n"
            "O9104\nG91 G0 Z-1.\nG90\nM99\nO9105\nG91 G0 Y5.\nG90\nM99\n")
    assert _ends(text) == [[0, 0, 10.0], [10.0, 0, 10.0], [10.0, 5.0, 10.0], [10.0, 5.0, 9.0],
                           [20.0, 5.0, 9.0], [20.0, 5.0, 8.0], [30.0, 5.0, 8.0]]


def test_g66_1_calls_the_macro_for_each_block_with_its_words_as_arguments():
    """``G66.1 P9106 Z-3.``: the blocks X10. Y5. and X20. do not run; each calls O9106 with #24/#25 from the block
    and #26 = -3 from the G66.1 block; in the second #25 is vacant, so Y#25 is left out (Fanuc "Undefined
    variable"). A macro statement between them runs as itself."""
    text = (START + "G66.1 P9106 Z-3.\nX10. Y5.\n#1 = 2.\nX20.\nG67\nX0\nM30\n"
            "O9106\nG0 X#24 Y#25\nG1 Z#26 F100.\nG0 Z5.\nM99\n")
    assert _ends(text) == [[0, 0, 10.0], [10.0, 5.0, 10.0], [10.0, 5.0, -3.0], [10.0, 5.0, 5.0],
                           [20.0, 5.0, 5.0], [20.0, 5.0, -3.0], [20.0, 5.0, 5.0], [0, 5.0, 5.0]]


def test_g67_in_the_macro_cancels_the_modal_call_for_the_moves_after_it():
    """The macro's G67 cancels its own G66 (the one specified last): X1. calls it, X2. after it does not."""
    text = START + "G66 P9109\nX1.\nX2.\nM30\nO9109\nG67\nG0 Z5.\nM99\n"
    assert _ends(text) == [[0, 0, 10.0], [1.0, 0, 10.0], [1.0, 0, 5.0], [2.0, 0, 5.0]]


def test_g67_with_a_move_in_its_block_runs_the_move_without_a_call():
    text = START + "G66 P9100 A1. B2.\nG67 X5.\nM30\n" + DRILL
    assert _ends(text) == [[0, 0, 10.0], [5.0, 0, 10.0]]


@pytest.mark.parametrize(("body", "needle"), [
    ("G66 A1.\n", "G66 modal macro call: no P word"),
    ("G66 P9999 A1.\n", "G66 modal macro call: program O9999 is neither in this file"),
    ("G66 P9100 G1 A1.\n", "G66 macro call: G is not an argument address"),
    ("G66 P9100 G67\n", "G66 and G67 in one block"),
    ("G66.1 P9100\nG1 X10.\n", "G66.1 macro call: G is not an argument address"),
    ("G66 P9107\nX1.\n", "G66 in a macro that a modal call runs"),
])
def test_errors_name_the_call(body, needle):
    text = START + body + "M30\n" + DRILL + "O9107\nG66 P9100\nM99\n"
    with pytest.raises(GCodeError, match=needle):
        parse_program(text, context=FANUC)


def test_an_argument_without_a_decimal_point_follows_the_dpi_setting():
    """As for G65 (:mod:`interpolators.iso_macro_args`): read as written and noted under calculator-type input
    (Fanuc DPI = 1), an error for an axis address under DPI = 0 (its least input increment is not modelled)."""
    text = START + "G66 P9101 X5 Z-1.\nY7.\nG67\nM30\nO9101\nG1 X#24 Z#26 F100.\nM99\n"
    prog = parse_program(text, context=FANUC)
    assert prog.blocks[-1].target[0] == 5.0
    assert "G66 argument X5 without a decimal point read as 5 (calculator-type input, Fanuc DPI=1)" in prog.notes
    increment = MachineContext(dialect=DIALECTS["fanuc"], decimal_point_input="increment")
    with pytest.raises(GCodeError, match=":4:11: G66 macro call: argument 'X5' without a decimal point"):
        parse_program(text, context=increment)


def test_a_modal_macro_without_m99_is_an_error_at_the_call():
    with pytest.raises(GCodeError, match="G66/G66.1 modal macro call: the called blocks run to the end"):
        parse_program(START + "G66 P9108\nX1.\nM30\nO9108\nG0 Z5.\n", context=FANUC)


@pytest.mark.parametrize("dialect", ["haas", "linuxcnc", "grbl"])
@pytest.mark.parametrize("code", ["G66", "G66.1", "G67"])
def test_other_dialects_refuse_modal_calls_naming_them(dialect, code):
    """Haas mills list G65 but no G66/G67 (Haas mill operator's manual, G-code list); LinuxCNC and grbl have none."""
    with pytest.raises(GCodeError, match=rf"{code} modal macro call.*--dialect fanuc; Haas mills have G65 only"):
        parse_program(START.replace("O0001\n", "") + f"{code} P9100\nM30\n",
                      context=MachineContext(dialect=DIALECTS[dialect]))


def test_system_variable_4012_reads_the_modal_call_in_force():
    """Fanuc "Modal information": #4012 is the G code of group 12, 66 / 66.1 while a modal call is in force, 67
    after G67."""
    text = (START + "G66 P9100 A1. B1.\n#101 = #4012\nG67\nG66.1 P9100\n#102 = #4012\nG67\n#103 = #4012\n"
            "G1 X#101 Y#102 Z#103 F100.\nM30\n" + DRILL)
    assert _ends(text)[-1] == [66.0, 66.1, 67.0]
