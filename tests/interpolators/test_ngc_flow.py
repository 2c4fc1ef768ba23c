"""LinuxCNC parameter, expression and O-word semantics of the ISO reader's flow (:mod:`interpolators.iso_flow`).

Expected values are worked out from the LinuxCNC manual ("Numbered Parameters", "Expressions", "O Codes",
https://linuxcnc.org/docs/html/gcode/overview.html and .../o-code.html).
"""

import pathlib

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


def test_mod_is_non_negative_and_fix_fup_are_floor_and_ceiling():
    # LinuxCNC interp_internal.cc: fmod made non-negative by adding |divisor|; FIX = floor, FUP = ceil.
    assert _words("G1 X[-7 MOD 3] Y[FIX[-1.5]] Z[FUP[-1.5]]\n") == [(1, [("G", 1.0), ("X", 2.0), ("Y", -2.0),
                                                                         ("Z", -1.0)])]


def test_m98_with_l_repeats_a_program_after_m30():
    lines = _words("O1\nG0 X1\nM98 P2 L2\nM30\nO2\nG1 Y1\nM99\n")
    assert [n for n, _ in lines[:4]] == [2, 6, 6, 4]


def test_globals_persist_and_locals_stay_in_the_sub():
    text = "#<_g>=1\no1 sub\n#<loc>=5\n#<_g>=[#<_g>+1]\no1 endsub\no1 call\nG1 X#<_g> Y[EXISTS[#<loc>]]\nM30\n"
    assert _words(text)[0] == (7, [("G", 1.0), ("X", 2.0), ("Y", 0.0)])


def test_do_while_with_continue_and_repeat():
    text = "#1=0\no1 do\n#1=[#1+1]\no1 if [#1 EQ 2]\no1 continue\no1 endif\nG1 X#1\no1 while [#1 LT 4]\n"
    assert [w[1][1] for _, w in _words(text)] == [1.0, 3.0, 4.0]
    assert len(_words("o1 repeat [3]\nG1 X1\no1 endrepeat\n")) == 3


@pytest.mark.parametrize(("text", "needle"), [
    ("o1 sub\nG1 X1\n", "no matching endsub"),
    ("o1 endwhile\n", "endwhile without while"),
    ("o<other> call\n", "neither in this file nor in other.ngc"),
])
def test_structure_errors(text, needle):
    with pytest.raises(GCodeError, match=needle):
        _words(text)


_CORPUS = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "data" / "gcode-corpus"
#: LinuxCNC nc_files programs of the shared corpus (MANIFEST.tsv) built on parameters, O-word subs and loops.
_FLOW_PROGRAMS = ("0010_cone.ngc", "0011_daisy.ngc", "0012_factorial.ngc", "0013_flowsnake.ngc",
                  "0014_g20sub.ngc", "0061_bezel_ex_37tick.ngc", "0043_retval.ngc", "0045_skeleton.ngc",
                  "0054_useful-subroutines.ngc", "0037_mmount.ngc")


@pytest.mark.parametrize("name", _FLOW_PROGRAMS)
def test_corpus_programs_with_parameters_and_o_words_run(name):
    path = _CORPUS / name
    if not path.is_file():
        pytest.skip(f"gcode corpus absent ({path})")
    executed = 0
    for fl in run(path.read_text(errors="replace"), source=str(path), max_lines=200_000):
        executed += 1
        if any(w.letter == "M" and w.value in (2.0, 30.0) for w in fl.words):
            break
    assert executed > 0


def test_subprograms_from_other_files_of_the_folder(tmp_path):
    """Fanuc/Haas keep programs by number: M98 P2001 runs the file of the folder that holds O2001;
    LinuxCNC finds o<side> in side.ngc (its SUBROUTINE_PATH). Errors there name that file."""
    from interpolators import load_program

    (tmp_path / "main.nc").write_text("G21 G90 F600\nG0 X0 Y0\nM98 P2001 L2\no<side> call [5]\nM30\n")
    (tmp_path / "part_o2001.nc").write_text("%\nO2001 (step)\nG91 G1 X10\nG90\nM99\n%\n")
    (tmp_path / "side.ngc").write_text("o<side> sub\nG1 Y#1\no<side> endsub\nM2\n")
    prog = load_program(tmp_path / "main.nc")
    assert [b.target.tolist() for b in prog.blocks] == [[0, 0, 0], [10, 0, 0], [20, 0, 0], [20, 5, 0]]
    assert {"subprogram from part_o2001.nc", "subprogram from side.ngc"} <= set(prog.notes)
    (tmp_path / "side.ngc").write_text("o<side> sub\nG1 Y#1 Q7\no<side> endsub\nM2\n")
    with pytest.raises(GCodeError) as info:
        load_program(tmp_path / "main.nc")
    assert info.value.file == str(tmp_path / "side.ngc") and info.value.line == 2
    (tmp_path / "main.nc").write_text("G21 M98 P3003\nM30\n")
    with pytest.raises(GCodeError, match="O3003 is neither in this file nor in a program file of its folder"):
        load_program(tmp_path / "main.nc")


def test_exists_of_numbered_and_computed_parameters():
    """LinuxCNC tests/interp/exists: EXISTS[#n] is 1 for 1 <= n < 5602 (read_parameter with
    check_exists), the number itself may be a parameter (##1 = #2 = 99999); expected STRAIGHT_TRAVERSE
    (1, 0, 1) and (1, 0, 0)."""
    text = ("#<a>=999\nG0 X EXISTS[#1] Y EXISTS[#99999] Z EXISTS[#<a>]\n#1=2\n#2=99999\n"
            "G0 X EXISTS[##1] Y EXISTS[##2] Z EXISTS[###1]\n")
    assert [[v for _, v in w[1:]] for _, w in _words(text)] == [[1.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
    # tests/interp/bad/exists-3.ngc: ###2 reads #99999, "Parameter number out of range"
    with pytest.raises(GCodeError, match="parameter number #99999 out of range"):
        _words("#2=99999\nG0 X EXISTS[###2]\n")


def test_a_parameter_number_may_be_a_function_value():
    """LinuxCNC tests/interp/namedparam-bug424: #atan[1]/[1]=3 sets #45 (ATAN[1]/[1] = 45 degrees)."""
    assert _words("#<a>=2\n#atan[1]/[1]=3\n#3=4\ng0 x#<a> y#45 z#3\n") == [
        (4, [("G", 0.0), ("X", 2.0), ("Y", 3.0), ("Z", 4.0)])]


def test_value_starts_at_0_and_a_return_without_value_resets_it():
    """LinuxCNC tests/interp/return-value: #<_value> is 0 before any call, a plain return sets it to
    0, return [v] and endsub [v] to v (interp_read.cc read_o)."""
    text = ("o1 sub\no2 if [#1 GT 0]\no1 return [123*[#1]]\no2 endif\no3 if [#1 LT 0]\no1 return\no3 endif\n"
            "o1 endsub [4712]\nG0 X#<_value>\no1 call [2]\nG0 X#<_value> Y#<_value_returned>\no1 call [-1]\n"
            "G0 X#<_value> Y#<_value_returned>\no1 call [0]\nG0 X#<_value>\n")
    assert [w[1][1] for _, w in _words(text)] == [0.0, 246.0, 0.0, 4712.0]
    assert [w[2][1] for _, w in _words(text) if len(w) > 2] == [1.0, 0.0]


def test_call_with_a_computed_o_number_and_a_named_main_program():
    """LinuxCNC tests/interp/m98m99/14-o-expression-call and oword-bug315-p2: O[#2*10] call runs o100,
    o#<sub> call runs o2, M98 P[expression] runs O200; m98m99/13-named-program: O<MyProgram> first in
    the file is the program's title."""
    text = ("#2 = 10\nO[#2 * 10] call\nM98 P[5 * 5 * 2 * 2 + 100]\n#<sub> = 2\no#<sub> call\nM30\n"
            "O100 sub\nG0 X1\nO100 endsub\no2 sub\nG0 X2\no2 endsub\nO200\nG0 X3\nM99\n")
    assert [w[1][1] for _, w in _words(text)[:3]] == [1.0, 3.0, 2.0]
    assert _words("%\nO<MyProgram>\nG0 X1\nM30\n%\n")[0] == (3, [("G", 0.0), ("X", 1.0)])
    with pytest.raises(GCodeError, match="only a call may compute its O number"):
        _words("o#1 sub\no1 endsub\n")
    with pytest.raises(GCodeError, match="without a keyword"):
        _words("G0 X1\nO<late>\n")


def test_machine_state_parameters_are_not_read_as_zero():
    """LinuxCNC keeps machine state above #5000 (#5021-#5029 machine position, tests/interp/
    machine-coord-params; #5061 probe result; #5161 G28 home; #5211 G92 offset): the flow alone
    does not know it, so reading one the program has not set is an error, not a silent 0
    (:func:`interpolators.parse_program` supplies the machine state, tests/interpolators/test_macro_b.py)."""
    for number in (5021, 5061, 5161, 5211):
        with pytest.raises(GCodeError, match=f"parameter #{number}: this system parameter .* is not modelled"):
            _words(f"#1 = #{number}\n")
    assert _words("#5100 = 7\nG0 X#5100\n") == [(2, [("G", 0.0), ("X", 7.0)])]


def test_m98_shares_the_callers_parameters_and_o_call_has_locals():
    """LinuxCNC tests/interp/m98m99/02-variables, its PRINTs as moves: an M98 subprogram sees and
    changes the caller's #1 #30 #31 (Fanuc parameters are global); an O-word sub starts with #1-#30
    unset (0) and its #1 #30 are gone on return, while #31 is global."""
    text = ("#1 = 42.01\n#30 = 42.30\n#31 = 42.31\nM98 P1\nG0 X#1 Y#30 Z#31\n#1 = 42.01\n#30 = 42.30\n"
            "#31 = 42.31\nO2 call\nG0 X#1 Y#30 Z#31\nM30\nO1\nG1 X#1 Y#30 Z#31\n#1 = 13.01\n#30 = 13.30\n"
            "#31 = 13.31\nM99\nO2 sub\nG1 X#1 Y#30 Z#31\n#1 = 13.01\n#30 = 13.30\n#31 = 13.31\nO2 endsub\n")
    moves = [[v for _, v in w[1:]] for _, w in _words(text)][:4]
    assert moves == [[42.01, 42.3, 42.31], [13.01, 13.3, 13.31], [0.0, 0.0, 42.31], [42.01, 42.3, 13.31]]


def test_subroutine_path_and_linuxcnc_sub_file_rules(tmp_path):
    """LinuxCNC tests/interp sub-call-from-sub (SUBROUTINE_PATH=subs: a sub file calls another),
    nested-sub-error (a sub defined inside another) and nested-sub-in-file-error (a numbered sub of a
    sub file is not found)."""
    from interpolators import load_program
    from interpolators.context import Dialect, MachineContext

    subs = tmp_path / "subs"
    subs.mkdir()
    (tmp_path / "main.ngc").write_text("G21 F100\no<caller> call [1] [2]\nM2\n")
    (subs / "caller.ngc").write_text("o<caller> sub\no<helper> call [#1 + 3]\no<caller> endsub\nM2\n")
    (subs / "helper.ngc").write_text("o<helper> sub\nG1 X#1\no<helper> endsub\nM2\n")
    ctx = MachineContext(dialect=Dialect(subroutine_path=("subs",)))
    assert load_program(tmp_path / "main.ngc", context=ctx).blocks[0].target.tolist() == [4.0, 0.0, 0.0]
    with pytest.raises(GCodeError, match="neither in this file nor in caller.ngc"):
        load_program(tmp_path / "main.ngc")
    (subs / "caller.ngc").write_text("o<caller> sub\no100 sub\no100 endsub\no<caller> endsub\nM2\n")
    with pytest.raises(GCodeError, match="o100 sub inside the definition of o<caller>"):
        load_program(tmp_path / "main.ngc", context=ctx)
    (subs / "caller.ngc").write_text("o<caller> sub\no200 call\no<caller> endsub\no200 sub\no200 endsub\nM2\n")
    with pytest.raises(GCodeError, match="o200 is defined in the subroutine file caller.ngc"):
        load_program(tmp_path / "main.ngc", context=ctx)


def test_abort_comment_ends_the_run_with_its_message():
    """LinuxCNC "Abort Messages" and tests/interp/abort-hot-comment: (ABORT, ...) inside a branch ends the
    run when it is reached, its parameters printed as %f; an unreached one changes nothing."""
    text = ("#42 = 0\n#<named> = 4711\no100 while [#42 lt 100]\no200 if [#42 eq 20]\n"
            "(abort, param42=#42 named=#<named>)\no200 endif\n#42 = [#42 + 1]\no100 endwhile\nM2\n")
    with pytest.raises(GCodeError, match=r"\(ABORT\) the program aborts here: param42=20.000000 named=4711.000000") \
            as info:
        _words(text)
    assert info.value.line == 5
    assert _words("o1 if [0]\n(ABORT, never)\no1 endif\nG0 X1\n") == [(4, [("G", 0.0), ("X", 1.0)])]


def test_calls_nest_nine_deep_and_a_tenth_level_is_an_error_at_its_line():
    # LinuxCNC interp_internal.hh INTERP_SUB_ROUTINE_LEVELS = 10: the tenth nested call level is refused
    # (NCE_TOO_MANY_SUBROUTINE_LEVELS); a self-recursive call stops there at once, not at the line limit.
    recurse = "o<r> sub\no<s> if [#1 GT 0]\no<r> call [#1-1]\no<s> endif\nG1 X#1\no<r> endsub\no<r> call [{}]\nM2\n"
    assert len(_words(recurse.format(8))) == 10  # nine nested levels: G1 from each, then M2
    with pytest.raises(GCodeError, match=r":3:1: subroutine calls nested 10 deep"):
        _words(recurse.format(9))
    with pytest.raises(GCodeError, match="nested 10 deep"):
        _words("o<r> sub\no<r> call\no<r> endsub\no<r> call\nM2\n")
