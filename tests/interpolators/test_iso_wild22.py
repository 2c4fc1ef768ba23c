"""Readings settled by the wild22 set of public programs (/tmp/wild22/set and /tmp/wild22/callers: Probe Basic's
LinuxCNC subroutines and example programs (kcjengr/probe_basic), a maker space's VCarve programs and LinuxCNC
probing subroutines (fortcollinscreatorhub/cnc), ConversationalGCode's generated pockets, a Carvera 4-axis wrapped
finishing program, Escriba's and a school computer project's engraving files, Okuma OSP user tasks, student Haas
programs). The snippets are written for these tests after those programs."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])

#: Probe Basic's tool changer macros (configs/probe_basic/subroutines/retractatc.ngc, clamptool.ngc, m24.ngc): wait
#: for a sensor with a timeout, abort when #5399 says the wait timed out, then move on.
RETRACT_ATC = ("G21 G90\no<retract> sub\nM64 P1\nM66 P0 L3 Q4 ; check carousel in position sensor\n"
               "o100 if [#5399 LT 0]\n(abort, Failed to send carousel home)\no100 endif\nG0 X10\n"
               "o<retract> endsub\no<retract> call\nG0 Y5\nM2\n")


def _x_of(text: str, **changes) -> float:
    """The X the program's last move ends at, read under LinuxCNC (``changes``: of its dialect)."""
    ctx = MachineContext(dialect=dataclasses.replace(DIALECTS["linuxcnc"], **changes))
    return float(parse_program(text, context=ctx).blocks[-1].target[0])


def test_the_result_of_a_wait_on_input_is_the_awaited_level():
    # LinuxCNC m-code.adoc "M66 Wait on Input": the input's value goes to #5399, -1 after the Q timeout; vcnc's
    # machine has no inputs, the wait ends with the event it waits for (1 after L1 RISE / L3 HIGH, 0 after L2 FALL /
    # L4 LOW) and L0 reads an input nothing drives (0, as LinuxCNC reads an unconnected motion.digital-in pin).
    # Before: "parameter #5399: this system parameter (machine state above #5000) is not modelled"
    prog = parse_program(RETRACT_ATC, context=LINUXCNC)
    assert prog.blocks[-1].target.tolist() == pytest.approx([10.0, 5.0, 0.0])
    assert any(n.startswith("M66 wait on input: the input taken as answering at once") for n in prog.notes)
    for mode, level in (("L1 Q2", 1.0), ("L2 Q2", 0.0), ("L3 Q2", 1.0), ("L4 Q2", 0.0), ("L0", 0.0), ("", 0.0)):
        assert _x_of(f"G21\nM66 P3 {mode}\nG0 X[5 + #5399]\nM2\n") == pytest.approx(5.0 + level), mode
    assert _x_of("G21\nM66 E0 L0\nG0 X[5 + #5399]\nM2\n") == pytest.approx(5.0)
    # before any M66 #5399 reads 0: LinuxCNC's parameters start at 0 and only M66 writes it (rs274 -g prints
    # STRAIGHT_TRAVERSE(5.0000, ...) for "G21 / G0 X[#5399+5]")
    assert _x_of("G21\nG0 X[5 + #5399]\nM2\n") == pytest.approx(5.0)


@pytest.mark.parametrize("m66, column, message", [
    ("M66 P0 E0", 8, r"both a digital \(P\) and an analog \(E\) input \(LinuxCNC: \"Invalid to select both"),
    ("M66 L0", 1, r"no input to wait on \(LinuxCNC: \"Need to have either a valid P or a valid E word with M66\"\)"),
    ("M66 P-1", 5, r"no input to wait on"),
    ("M66 E1 L3 Q1", 8, r"an analog input is read at once \(LinuxCNC: \"Can't select analog input with wait type"),
    ("M66 P0 L3", 8, r"a wait \(L3\) needs a timeout Q > 0 \[s\] \(LinuxCNC: \"Zero timeout with wait type"),
    ("M66 P0 L1 Q0", 8, r"a wait \(L1\) needs a timeout Q > 0"),
    ("M66 P0 L-1 Q1", 8, r"wait mode L must be a whole number >= 0 \(LinuxCNC: \"Negative l word used\""),
])
def test_a_wait_on_input_linuxcnc_refuses(m66, column, message):
    # rs274 -g refuses each of these lines with the message quoted (interp_convert.cc / interp_check.cc, M66);
    # before, vcnc ran them all as a note
    with pytest.raises(GCodeError, match=rf":2:{column}: {m66}: {message}"):
        parse_program(f"G21\n{m66}\nG0 X1\nM2\n", context=LINUXCNC)


def test_an_undocumented_wait_mode_leaves_the_result_unknown():
    # m-code.adoc defines L0-L4 only; rs274 runs "M66 P0 L5 Q1", so vcnc does too, but what #5399 then holds is
    # the machine's: reading it is an error naming the M66
    parse_program("G21\nM66 P0 L5 Q1\nG0 X1\nM2\n", context=LINUXCNC)
    with pytest.raises(GCodeError, match=r":3:5: parameter #5399: the result of M66 P0 L5 Q1 at line 2, whose wait "
                                         r"mode L5 is none of LinuxCNC's L0-L4"):
        parse_program("G21\nM66 P0 L5 Q1\nG0 X#5399\nM2\n", context=LINUXCNC)


def test_fanuc_reads_no_linuxcnc_wait_result():
    # #5399 is LinuxCNC's; on a Fanuc control M66 is a machine maker's code and #5399 a system variable vcnc does
    # not model
    with pytest.raises(GCodeError, match=r"parameter #5399"):
        parse_program("G21\nM66\nG0 X#5399\nM30\n", context=MachineContext(dialect=DIALECTS["fanuc"]))


HAAS = MachineContext(dialect=DIALECTS["haas"])

#: Haas mill operator's manual 96-8000 (1999), "Macros", "Conditional Expressions": "N50 [#100 LT 10] M99 P10 ;
#: ... the branch occurs only when #100 is less than 10, otherwise processing continues with the next program
#: line" (the M99 conditional construct "is unique to the HAAS control"); a loop written so.
HAAS_CONDITIONAL_M99 = "%\nO1\n#100 = 5\nN10 #100 = #100 - 1\nG0 X#100\nN50 [#100 GT 1] M99 P10\nG0 Y1\nM30\n%\n"


def test_haas_conditional_m99_branches_while_its_condition_holds():
    # before: "'[#100 GT 1]' in brackets where a word should start"
    prog = parse_program(HAAS_CONDITIONAL_M99, context=HAAS)
    assert [b.target[:2].tolist() for b in prog.blocks] == [[4, 0], [3, 0], [2, 0], [1, 0], [1, 1]]


@pytest.mark.parametrize("dialect", ["haas", "fanuc"])
def test_m99_p_in_the_main_program_branches_within_it(dialect):
    # Haas (same section): "N50 M99 P10 ; branches to line N10" of the current program; in a main program, our
    # reading for Fanuc too. Before: "word P needs G04 (dwell), G64 ...". A branch that never ends is an endless
    # loop, named
    text = "%\nO1\n#1 = 3\nN10 #1 = #1 - 1\nG0 X#1\nIF [#1 LE 0] GOTO 30\nM99 P10\nN30 G0 Y1\nM30\n%\n"
    prog = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    assert [b.target[:2].tolist() for b in prog.blocks] == [[2, 0], [1, 0], [0, 0], [0, 1]]
    with pytest.raises(GCodeError, match=r":4:1: M99 P10 has sent execution back more than \d+ times: an endless"):
        parse_program("%\nO1\nN10 G0 X1\nM99 P10\nM30\n%\n", context=MachineContext(dialect=DIALECTS[dialect]))
    with pytest.raises(GCodeError, match=r":3:5: M99 P20: no block N20 in this program"):
        parse_program("%\nO1\nM99 P20\nM30\n%\n", context=MachineContext(dialect=DIALECTS[dialect]))


def test_haas_timers_are_named_and_not_read():
    # a Russian shop's Haas templates (RomanBoreyko/r_cod2 "6-grannik/O00001.nc") open with "#10002= #3020 - #10000";
    # Haas's #3020-#3025 are its power-on, cycle start, feed and part timers (zappettiniconsulting.com/wiki/
    # haas-system-variables): the time the machine has run, unknown to a reading of the text as the clocks #3001 and
    # #3002 are. Before: "#3020: this Fanuc system variable ... is not modelled". Since shopiso39 the value may be
    # held by the common variable it is stored in (iso_params, Parameters.held); its use is the error naming it.
    with pytest.raises(GCodeError, match=r":4:5: parameter #10002 holds a value vcnc cannot know \(#3020 read at "
                                         r"line 3: Haas's power-on timer, which counts the time the machine has run"):
        parse_program("%\nO1\n#10002= #3020 - #10000\nG0 X#10002\nM30\n%\n", context=HAAS)
    with pytest.raises(GCodeError, match=r"#3020: this Fanuc system variable"):
        parse_program("%\nO1\n#102= #3020 - #100\nG0 X1\nM30\n%\n", context=MachineContext(dialect=DIALECTS["fanuc"]))


def test_a_conditional_m99_under_fanuc_names_the_haas_form():
    # Fanuc has no such construct (the Haas manual: "unique to the HAAS control"); its macro B branches by IF [..]
    # GOTO: the Haas block was refused as a CNCjs placeholder before review35 ("'[#100 GT 1]' in brackets where a
    # word should start ... CNCjs")
    with pytest.raises(GCodeError, match=r":6:5: a conditional M99 \('\[condition\] M99'\) is Haas's form.*"
                                         r"expected IF \[condition\] GOTO n, or --dialect haas"):
        parse_program(HAAS_CONDITIONAL_M99, context=MachineContext(dialect=DIALECTS["fanuc"]))
