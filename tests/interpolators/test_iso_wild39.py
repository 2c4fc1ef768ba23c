"""Readings settled by the shopiso39 set of public shop programs (/tmp/shopiso39/progs, sources.tsv: a Russian
job shop's Haas macro programs (RomanBoreyko/r_cod2), student Haas programs, Fanuc 0i macros (dennisselyaev/gcode),
grbl senders' and plotters' test files, Fusion 360 and hobby CAM output). The snippets are written for these tests
after those programs."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import load_program, parse_program
from interpolators.context import INTERPOLATION_CONTEXT
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

HAAS = INTERPOLATION_CONTEXT.with_dialect("haas")
FANUC = INTERPOLATION_CONTEXT.with_dialect("fanuc")

#: r_cod2's pocket programs: a finishing speed and feed set only on the last pass, as an IF .. THEN with NC words.
THEN_BLOCK = ("%\nO1\n#1=5\nG0 X0 Y0 Z10\nIF [#1 GT 2] THEN G1 X10 F100\nIF [#1 LT 2] THEN G1 X20 F100\n"
              "IF [#1 EQ 5] THEN S900 G1 Y3\nM30\n%\n")


def test_haas_then_runs_the_rest_of_its_block():
    """Haas "Conditional Execution (IF THEN)": the block after THEN runs when the condition holds (NC words too),
    and is skipped when it fails; the reference agrees."""
    prog = parse_program(THEN_BLOCK, context=HAAS)
    assert [(b.line, *map(float, b.target[:2])) for b in prog.blocks] == [(4, 0, 0), (5, 10, 0), (7, 10, 3)]
    m = match_blocks(iso_reference(THEN_BLOCK, HAAS), reader_rows(*blocks_table(prog)))
    assert m.mismatch is None and m.exact == 3


def test_fanuc_then_still_takes_one_macro_statement():
    with pytest.raises(GCodeError, match=r":5:19: IF \[..\] THEN: NC word 'G1' after THEN"):
        parse_program(THEN_BLOCK, context=FANUC)


def test_division_by_zero_names_the_divisor():
    """r_cod2's passes: a step width from the tool table's diameter (#[2400 + #3026]), zero without a table; the
    error names the divisor, whose value came from elsewhere, not only the '/'."""
    text = "%\nO1\n#6=40.\n#11=#4*0.8\n#20=FIX[#6/#11]+1.\nM30\n%\n"
    with pytest.raises(GCodeError, match=r":5:11: division by zero: the divisor '#11' is 0 \(got '/#11\]\+1.'\)"):
        parse_program(text, context=HAAS)
    with pytest.raises(GCodeError, match=r":1:7: division by zero \(got '/0\]'\)"):
        parse_program("G1 X[1/0]\n", context=INTERPOLATION_CONTEXT)


def test_a_bare_if_names_the_haas_then_block():
    """r_cod2's 'IF [ #1 EQ #2 ] S900. F500.' (no THEN): refused at the text after the condition, and under haas the
    expected form names the block THEN takes there."""
    text = "%\nO1\n#1=1\n#2=1\nIF [ #1 EQ #2 ] S900. F500.\nM30\n%\n"
    with pytest.raises(GCodeError, match=r":5:16: IF \[condition\] must be followed by GOTO n or THEN .*THEN a block "
                                         r"\(Haas: '#i = expression', NC words or both\)"):
        parse_program(text, context=HAAS)


#: r_cod2's main programs: a cycle-time log in Haas's extended variables, read from the power-on timer #3020.
CYCLE_LOG = "%\nO99\n#10002= #3020 - #10000\nG0 X5 Y0\n#10000= #3020\nM30\n%\n"


def test_a_clock_stored_in_a_common_variable_is_held_there():
    """A value vcnc cannot know (Haas #3020) may be stored in a common variable: the log above runs; reading the
    variable, or one set from it, is the error naming the first reading; a call's local still refuses at once."""
    prog = parse_program(CYCLE_LOG, context=HAAS)
    assert [float(b.target[0]) for b in prog.blocks] == [5.0]
    assert match_blocks(iso_reference(CYCLE_LOG, HAAS), reader_rows(*blocks_table(prog))).mismatch is None
    steered = CYCLE_LOG.replace("G0 X5 Y0", "#101=#10002*2\nG0 X#101 Y0")
    with pytest.raises(GCodeError, match=r":5:5: parameter #101 holds a value vcnc cannot know \(#3020 read at line 3: "
                                         r"Haas's power-on timer"):
        parse_program(steered, context=HAAS)
    with pytest.raises(GCodeError, match=r":3:5: parameter #3020: Haas's power-on timer"):
        parse_program(CYCLE_LOG.replace("#10002=", "#1="), context=HAAS)
    again = CYCLE_LOG.replace("G0 X5 Y0", "#10002=3\nG0 X#10002 Y0")  # set again: known
    assert [float(b.target[0]) for b in parse_program(again, context=HAAS).blocks] == [3.0]


def test_numbered_programs_are_found_in_the_subroutine_path(tmp_path):
    """r_cod2's main programs O00999 call O10, O20 .. by M98 P, kept in the subfolders '1 VERH', '2 NIZ' (in the
    control's memory on the machine): the folders of subroutine_path (--subroutine-path) stand for that memory."""
    (tmp_path / "1 VERH").mkdir()
    (tmp_path / "O00999.nc").write_text("%\nO00999\nG0 X0 Y0\nM98 P10\nM30\n%\n")
    (tmp_path / "1 VERH" / "O00010.nc").write_text("%\nO00010\nG0 X7\nM99\n%\n")
    with pytest.raises(GCodeError, match=r":4:1: M98 subprogram call: program O10 is neither in this file nor in a "
                                         r"program file of its folder .*or a folder of --subroutine-path"):
        load_program(tmp_path / "O00999.nc", context=HAAS)
    memory = dataclasses.replace(HAAS, dialect=dataclasses.replace(HAAS.dialect, subroutine_path=("1 VERH",)))
    prog = load_program(tmp_path / "O00999.nc", context=memory)
    assert [float(b.target[0]) for b in prog.blocks] == [0.0, 7.0]


def test_a_sender_placeholder_is_not_named_as_cnc_simulator_text():
    """GRBL-Plotter's tool-change scripts ('G53 G90 G0 Z#TOAZ', filled in by the sender): the error named
    CNCSimulator Pro's #region lines, which these are not."""
    with pytest.raises(GCodeError, match=r":2:13: '#TOAZ' is not a parameter \(a placeholder a sender fills in") as exc:
        parse_program("G91 G0 Z20\nG53 G90 G0 Z#TOAZ\n", context=INTERPOLATION_CONTEXT.with_dialect("grbl"))
    assert "CNCSimulator" not in str(exc.value)
    with pytest.raises(GCodeError, match=r"'#region' is not a parameter \(CNCSimulator Pro's #region"):
        parse_program("G21 #region\nG0 X1\n", context=INTERPOLATION_CONTEXT)
