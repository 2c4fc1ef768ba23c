"""LinuxCNC parameter, expression and O-word semantics of the ISO reader's flow (:mod:`interpolators.iso_flow`).

Expected values are worked out from the LinuxCNC manual ("Numbered Parameters", "Expressions", "O Codes",
https://linuxcnc.org/docs/html/gcode/overview.html and .../o-code.html).
"""

import pytest

from interpolators.iso_flow import run
from vcnc.errors import GCodeError


def _words(text: str, **kw) -> list[tuple[int, list[tuple[str, float]]]]:
    return [(fl.line, [(w.letter, w.value) for w in fl.words]) for fl in run(text, **kw) if fl.words]


def test_assignments_take_effect_after_the_whole_line_is_read():
    # LinuxCNC "Parameters": all values on a line are read before any assignment on it, so #2 gets the old #1.
    assert _words("#1=1\n#1=2 #2=#1\nG1 X#2 Y#1\n") == [(3, [("G", 1.0), ("X", 1.0), ("Y", 2.0)])]


def test_precedence_power_first_and_unary_minus_binds_tightest():
    # ** before * before +; LinuxCNC applies unary minus to the operand, so -2**2 = (-2)**2 = 4.
    assert _words("G1 X[2+3*2**2] Y[-2**2]\n") == [(1, [("G", 1.0), ("X", 14.0), ("Y", 4.0)])]


def test_comparisons_logic_and_functions_in_degrees():
    lines = _words("G1 X[1 LT 2 AND 3 GT 2] Y[ATAN[1]/[1]] Z[ROUND[2.5]]\n")
    assert lines == [(1, [("G", 1.0), ("X", 1.0), ("Y", pytest.approx(45.0)), ("Z", 3.0)])]


def test_sub_with_argument_and_return_value():
    text = "o<a> sub\nG1 X#1\no<a> endsub [#1*2]\no<a> call [3]\nG1 Y#<_value>\nM30\n"
    assert _words(text) == [(2, [("G", 1.0), ("X", 3.0)]), (5, [("G", 1.0), ("Y", 6.0)]), (6, [("M", 30.0)])]


def test_block_delete_is_off_so_the_line_runs():
    assert _words("/G1 X1\n") == [(1, [("G", 1.0), ("X", 1.0)])]


@pytest.mark.parametrize(("text", "needle"), [
    ("o1 while [1]\no1 endwhile\n", "endless loop"),
    ("G1 X[1/0]\n", "division by zero"),
    ("G1 X[FOO[1]]\n", "malformed value"),
    ("G1 X#5420\n", "#5420"),
])
def test_errors_name_the_problem(text, needle):
    with pytest.raises(GCodeError, match=needle):
        _words(text, max_lines=1000)
