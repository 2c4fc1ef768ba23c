"""LinuxCNC's active comments: (MSG, ..), (DEBUG, ..), (PRINT, ..), (LOG, ..) as Program.messages.

Semantics from LinuxCNC's G-code overview ("Comments", "Messages", "Debug Messages", "Print Messages",
"Comment Parameters") and interp_convert.cc convert_comment / convert_param_comment; the expected texts
are what those functions print (printf "%lf", "%.0f", "%.4f", "%.Nf"; "######" for a missing parameter).
"""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from interpolators.program import Message
from vcnc.cli import main
from vcnc.errors import GCodeError, InputError


def _messages(text: str, dialect: str = "linuxcnc") -> list[tuple[int, str, str]]:
    prog = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    return [(m.line, m.kind, m.text) for m in prog.messages]


def test_msg_is_shown_as_written_without_substitution():
    assert _messages("#1 = 2\n(MSG, Tool #1: check it)\nM2\n") == [(2, "msg", " Tool #1: check it")]


def test_keywords_ignore_case_and_leading_space_but_not_a_space_before_the_comma():
    text = "( msg,a)\n(Debug,b)\n(PRINT,c)\n(MSG ,d)\n(message, e)\nM2\n"
    assert _messages(text) == [(1, "msg", "a"), (2, "debug", "b"), (3, "print", "c")]


def test_debug_prints_parameters_with_lf_by_default_and_the_magic_formats():
    text = "#1 = 3.14159265\n#<r> = 2.5\n(debug, #1 %d#1 %f#1 %.2f#1 then #<r> #< R >)\nM2\n"
    assert _messages(text) == [(3, "debug", " 3.141593 3 3.1416 3.14 then 2.50 2.50")]


def test_bad_format_strings_print_as_characters():
    # "%" before another character stays; "%." without a digit and "f" loses its "%" (convert_param_comment)
    assert _messages("#1 = 1\n(debug,50% %.x %.3g #1)\nM2\n") == [(2, "debug", "50% .x .3g 1.000000")]


def test_missing_parameters_print_hashes_and_near_zero_prints_zero():
    text = "#1 = -0.0000001\n(print,#1 #<unset> #6000 # x)\nM2\n"
    assert _messages(text) == [(2, "print", "0.000000 ###### ###### # x")]


def test_parameter_5599_switches_debug_output_off_and_on():
    text = "(debug,one)\n#5599 = 0\n(debug,two)\n(msg,three)\n#5599 = 1\n(debug,four)\nM2\n"
    assert _messages(text) == [(1, "debug", "one"), (4, "msg", "three"), (6, "debug", "four")]


def test_only_the_last_comment_of_a_line_is_active():
    text = "(foo)(debug,shown)\n(debug,hidden)(foo)\nG0 X1 (debug,with a move) ; (debug,semicolon)\nM2\n"
    assert _messages(text) == [(1, "debug", "shown"), (3, "debug", "with a move")]


def test_messages_follow_the_run_loops_subroutines_and_same_line_assignments():
    text = """\
o10 sub
  (debug,in sub #1)
o10 endsub
#2 = 0
o20 while [#2 LT 2]
  #2 = [#2 + 1] (debug,pass %d#2 at line %d#<_line>)
o20 endwhile
o10 call [7]
o30 if [0]
  (msg,never)
o30 endif
M2
"""
    assert _messages(text) == [(6, "debug", "pass 1 at line 6"), (6, "debug", "pass 2 at line 6"),
                               (2, "debug", "in sub 7.000000")]


def test_log_comments_are_messages_of_their_own_with_a_note():
    prog = parse_program("(LOGOPEN,probe.txt)\n#1 = 4\n(LOG,x=#1)\n(LOGCLOSE)\nM2\n")
    assert [(m.kind, m.text) for m in prog.messages] == [("log", "x=4.000000")]
    assert any("no log file written" in n for n in prog.notes)


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "grbl"])
def test_other_dialects_read_a_comment_as_a_comment(dialect):
    assert _messages("(MSG, hello)\n(DEBUG, #<x>)\nG0 X1\nM2\n", dialect) == []


def test_unterminated_parameter_in_a_debug_comment_is_an_error_naming_the_line():
    with pytest.raises(GCodeError, match="not terminated") as info:
        parse_program("G0 X1\n(debug, value #<x)\nM2\n", source="part.ngc")
    assert "part.ngc:2" in str(info.value)


def test_message_kind_is_checked():
    with pytest.raises(InputError, match="message kind"):
        Message(line=1, kind="shout", text="x")


def test_cli_prints_msg_debug_and_print_on_stderr_with_file_and_line(tmp_path, capsys):
    prog = tmp_path / "part.ngc"
    prog.write_text("G21\n#1 = 6\n(MSG, Clamp the part)\nG1 X1 F100\n(DEBUG, depth %d#1)\n(PRINT, done)\nM2\n")
    assert main(["interpolate", str(prog), "-o", str(tmp_path / "sp.csv")]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err == [f"{prog}:3: (MSG) Clamp the part", f"{prog}:5: (DEBUG) depth 6", f"{prog}:6: (PRINT) done"]


def test_simulate_prints_the_messages_as_interpolate_does(tmp_path, capsys):
    prog = tmp_path / "part.ngc"
    prog.write_text("G21\n(MSG, Clamp the part)\nG1 X1 F600\nM2\n")
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "cap.csv")]) == 0
    assert capsys.readouterr().err.splitlines() == [f"{prog}:2: (MSG) Clamp the part"]
