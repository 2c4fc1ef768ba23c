"""ISO programs of the tenth wild round (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.cli import main
from vcnc.core.errors import InputError, MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str, **dialect) -> MachineContext:
    return dataclasses.replace(CTX, dialect=dataclasses.replace(DIALECTS[name], **dialect))


def _xy(prog) -> list[list[float]]:
    return [b.target[:2].tolist() for b in prog.blocks]


# A student's Fanuc program, and a subprogram file whose feed comes from its caller: neither writes an F before
# its first G01. Fanuc parameter No. 1411 (the cutting feed at power-on) gives the feed such moves run at.
NO_F = "G21 G90 G54\nG0 X0 Y0 Z5\nG1 Z-1\nG2 X10 Y0 R5\nF250\nG1 X20\nM30\n"


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas", "grbl"])
def test_a_feed_move_before_any_f_is_refused_and_the_setting_named(name):
    with pytest.raises(GCodeError, match=r":3:1: G01 feed move without a feed: no F word before it.*expected "
                                         r"F > 0 \[mm/min\] \(or a machine's initial feed: --initial-feed F, "
                                         r"\[program\] initial_feed\)"):
        parse_program(NO_F, context=_in_dialect(name))


def test_the_initial_feed_runs_the_moves_before_the_first_f():
    prog = parse_program(NO_F, context=_in_dialect("fanuc", initial_feed=600.0))
    feeds = [round(b.feed * 60.0, 9) for b in prog.blocks if b.kind != "rapid"]
    assert feeds == [600.0, 600.0, 250.0]  # G1 Z-1 and the arc at 600 mm/min, then the program's own F250
    assert any("initial feed 600 mm/min" in n and "from line 3" in n for n in prog.notes)


def test_the_initial_feed_is_noted_only_when_a_move_takes_it():
    prog = parse_program("G21 G90 G0 X0 Y0\nG1 X5 F100\nM30\n", context=_in_dialect("fanuc", initial_feed=600.0))
    assert not any("initial feed" in n for n in prog.notes)


def test_the_initial_feed_runs_a_drilling_cycle_without_f():
    prog = parse_program("G21 G90 G54 G0 X0 Y0 Z10\nG81 X5 Y5 Z-2 R2\nG80\nM30\n",
                         context=_in_dialect("fanuc", initial_feed=120.0))
    assert [round(b.feed * 60.0, 9) for b in prog.blocks if b.kind == "line"] == [120.0]


@pytest.mark.parametrize("text, why", [
    ("G21 G90 G0 X0 Y0\nF0\nG1 X5\nM30\n", "F0, a zero feed rate"),
    ("G21 G90 G0 X0 Y0\nG95 S1000 M3\nG1 X5\nM30\n", "G95 feed per revolution: no F word since G95"),
    ("G21 G90 G0 X0 Y0\nG93 G1 X1 F2\nG94\nG1 X5\nM30\n", "G94 after G93 resets the feed"),
])
def test_the_initial_feed_never_stands_for_an_f_the_program_needs(text, why):
    # an F0, a G95 feed per revolution and the F after G93 are the program's own feeds: no setting replaces them
    with pytest.raises(GCodeError, match=why):
        parse_program(text, context=_in_dialect("fanuc", initial_feed=600.0))


def test_the_machine_file_sets_the_initial_feed_and_dialect_keeps_it(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndialect = "fanuc"\ninitial_feed = 450\n')
    context = load_machine(str(path)).context
    assert context.dialect.initial_feed == 450.0
    assert context.with_dialect("haas").dialect.initial_feed == 450.0


@pytest.mark.parametrize("value", ["0", "-5", "true", '"fast"'])
def test_a_bad_initial_feed_is_refused_naming_it(tmp_path, value):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + f"\n[program]\ninitial_feed = {value}\n")
    with pytest.raises(MachineError, match=r"'program.initial_feed' \[mm/min\] must be a number > 0"):
        load_machine(str(path))
    with pytest.raises(InputError, match=r"initial_feed must be > 0 \[mm/min\]"):
        dataclasses.replace(DIALECTS["fanuc"], initial_feed=-5.0)


# Fanuc custom macro, "Abbreviations of macro statements" (0i/16i/30i operator's manuals): the first two characters
# of a macro word stand for it (ROUND -> RO, FIX -> FI); programs written for Fanuc controls write WH [..] DO1.
ABBREVIATED_LOOP = ("G21 G90 G54 G0 X0 Y0 Z5\n#1 = 0\nWH [#1 LT 3] DO1\nG1 X[#1 * 10] Y[RO[#1 * 1.6]] F100\n"
                    "#1 = #1 + 1\nEN1\nIF [#1 EQ 3] GO 20\nG0 X99\nN20 G0 Z[SQ[16]]\nIF [#1 GT 0] TH #2 = 7\n"
                    "G0 Y#2\nM30\n")


def test_fanuc_reads_abbreviated_macro_words():
    prog = checked_iso(ABBREVIATED_LOOP, _in_dialect("fanuc"))  # and as the reference reads it
    # RO[..] in the address Y rounds to the least input increment (0.001 mm), not to a whole number (isomacro40)
    assert np.allclose(_xy(prog), [[100.0, 50.0], [100.0, 50.0], [110.0, 51.6], [120.0, 53.2], [120.0, 53.2],
                                   [120.0, 57.0]], atol=1e-9)
    assert prog.blocks[-2].target[2] == -16.0  # Z4 (SQ[16]) plus the G54 offset -20; the GO 20 skipped X99


@pytest.mark.parametrize("name", ["haas", "linuxcnc"])
def test_other_controls_refuse_the_abbreviations_naming_the_word(name):
    with pytest.raises(GCodeError, match=r":3:1: loop head 'WH' \[..\] DO m: the keyword of a loop is WHILE \(WH is "
                                         r"Fanuc's abbreviation of it: --dialect fanuc\)"):
        parse_program(ABBREVIATED_LOOP, context=_in_dialect(name))


def test_an_ambiguous_abbreviation_is_refused_naming_the_functions():
    # EXP and EXISTS (LinuxCNC's, read under every dialect) share their first two characters
    with pytest.raises(GCodeError, match=r":2:6: EX: an ambiguous abbreviation \(of EXISTS and EXP\)"):
        parse_program("G21 G90 G0 X0 Y0\n#1 = EX[1]\nM30\n", context=_in_dialect("fanuc"))


def test_a_g01_typed_with_the_letter_o_is_not_read_as_go():
    with pytest.raises(GCodeError, match=r"letter O where the digit 0 was meant"):
        parse_program("G21 G90 G0 X0 Y0\nGO1 X5 F100\nM30\n", context=_in_dialect("fanuc"))


# Fanuc 0i-MD B-64304EN II-14.2 "Tool position offset (G45 to G48)"; the cases as the Mitsubishi M700V programming
# manual 12.6 tabulates them (offset l = 10 here: a radius of 10 under D1, a length of 3 under H1)
TOOLS = {1: Tool(number=1, radius=10.0, length=3.0), 2: Tool(number=2, radius=-10.0)}


def _fanuc_tools() -> MachineContext:
    return dataclasses.replace(_in_dialect("fanuc"), tools=TOOLS, work_offsets={})


@pytest.mark.parametrize("block, x", [
    ("G45 X100. D1", 110.0), ("G45 X-100. D1", -110.0), ("G46 X100. D1", 90.0), ("G46 X-100. D1", -90.0),
    ("G47 X100. D1", 120.0), ("G48 X100. D1", 80.0), ("G45 X100. D2", 90.0),  # a negative offset reverses G45
    ("G48 X15. D1", -5.0),  # "the tool will proceed to move in the opposite direction"
    ("G45 X0 D1", 10.0), ("G45 X-0 D1", -10.0), ("G46 X0 D1", -10.0), ("G46 X-0 D1", 10.0),  # incremental zeros
])
def test_fanuc_tool_position_offset_changes_the_travel(block, x):
    prog = checked_iso(f"G21 G91 G0 X0 Y0\n{block} F100\nM30\n", dataclasses.replace(_fanuc_tools(),
                                                                                      home=(0.0, 0.0, 0.0)))
    assert prog.blocks[-1].target[0] == x


def test_fanuc_tool_position_offset_in_absolute_mode():
    # under G90 the travel is the end point minus the start point; a zero travel does not move; H takes the length
    text = "G21 G90 G0 X20. Y0\nG45 G1 X50. Y0 F100 D1\nG46 Z-10. H1\nX0\nM30\n"
    prog = checked_iso(text, dataclasses.replace(_fanuc_tools(), home=(0.0, 0.0, 0.0)))
    assert [b.target.tolist() for b in prog.blocks] == [[20.0, 0.0, 0.0], [60.0, 0.0, 0.0], [60.0, 0.0, -7.0],
                                                        [0.0, 0.0, -7.0]]  # one-shot: X0 is plain again
    assert "G45 tool position offset increase" in prog.notes and "G46 tool position offset decrease" in prog.notes


@pytest.mark.parametrize("text, why", [
    ("G45 G1 X10. F100", "without D or H"),
    ("G45 G2 X10. R5. D1 F100", "on an arc"),
    ("G41 D1 G1 X10. F100\nG45 X20. D1", r"with cutter compensation on \(G41\)"),
    ("G45 G1 X10. A5. D1 F100", "with axis word A"),
])
def test_fanuc_tool_position_offset_refusals_name_the_case(text, why):
    ctx = dataclasses.replace(_fanuc_tools(), extra_axes=("a",))
    with pytest.raises(GCodeError, match=r"G45 tool position offset increase " + why):
        parse_program(f"G21 G90 G0 X0 Y0\n{text}\nM30\n", context=ctx)


@pytest.mark.parametrize("name, what", [("haas", "G47 text engraving"), ("linuxcnc", "G47 text engraving")])
def test_g47_stays_refused_outside_fanuc(name, what):
    with pytest.raises(GCodeError, match=what + r" \(Haas\) / tool position offset double increase \(Fanuc; "
                                                r"--dialect fanuc\): not supported"):
        parse_program("G21 G90 G0 X0 Y0\nG47 X10. D1\nM30\n", context=_in_dialect(name))


def test_a_statement_of_another_language_is_named():
    # a Fusion 360 KinetiC-NC post writes BASIC-like lines ('PRINT "x-offset = ";#100'): no G-code control reads them
    with pytest.raises(GCodeError, match=r":2:1: malformed number for word P \('PRINT': a statement of another "
                                         r"control's language"):
        parse_program('G21 G90\nPRINT "x = ";#100\nM30\n', context=_in_dialect("linuxcnc"))


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc"])
def test_a_num_main_block_mark_is_named(name):
    # Fusion's NUM post: ': G90 G40 G94', ISO 6983's main-block mark, in a program whose arcs are NUM's own
    with pytest.raises(GCodeError, match=r":1:1: ':' .* without a program number \(before a block: ISO 6983's "
                                         r"main-block mark, as NUM controls write it; NUM programs are not "
                                         r"supported\)"):
        parse_program(": G90 G40 G94\nG0 X0 Y0\nM30\n", context=_in_dialect(name))


def test_initial_feed_on_the_command_line(tmp_path, capsys):
    part = tmp_path / "part.nc"
    part.write_text(NO_F)
    blocks, out = tmp_path / "b.csv", tmp_path / "sp.csv"
    assert main(["interpolate", str(part), "-o", str(out), "--dialect", "fanuc"]) == 2
    assert "--initial-feed F" in capsys.readouterr().err and not out.exists()
    assert main(["interpolate", str(part), "-o", str(out), "--dialect", "fanuc", "--initial-feed", "600",
                 "--blocks", str(blocks)]) == 0
    assert "initial feed 600 mm/min" in capsys.readouterr().out
    feeds = [r.split(",")[-1] for r in blocks.read_text().splitlines()[1:]]
    assert feeds == ["", "600", "600", "250"]  # the rapid, G1 Z-1 and the arc at the initial feed, then F250
    assert main(["interpolate", str(part), "-o", str(out), "--initial-feed", "0"]) == 2
    assert "initial_feed must be > 0 [mm/min]" in capsys.readouterr().err


def test_a_corner_word_may_have_blanks_after_its_comma():
    # a student's Fanuc program writes "G01 X 92 Y 50, R 15": blanks are read past anywhere in a block, as in "Y 50"
    text = "G21 G90 G54 G0 X0 Y0 Z0\nG01 X 10 Y 0, R 2 F100\nG01 Y 10\nM30\n"
    spaced = checked_iso(text, _in_dialect("fanuc"))
    tight = parse_program(text.replace(", R 2", ",R2"), context=_in_dialect("fanuc"))
    assert [b.target.tolist() for b in spaced.blocks] == [b.target.tolist() for b in tight.blocks]
    assert len(spaced.blocks) == 4  # the rapid, the shortened line, the rounding arc, the line on


# Fanuc 0i-MD B-64304EN "Custom macro": an argument without a decimal point counts in its address's least input
# increment, which Fanuc's DPI (No. 3401#0) sets: DPI = 1 (calculator, vcnc's default) reads it as written
MACRO_CALL = "G21 G90 G54 G0 X0 Y0\nG65 P9001 X10 F800\nM30\nO9001\nG1 X#24 F#9\nM99\n"


def test_fanuc_g65_arguments_without_a_decimal_point_under_calculator_input():
    prog = checked_iso(MACRO_CALL, _in_dialect("fanuc"))  # the reference runs the G65 call too
    assert prog.blocks[-1].target[0] == 110.0 and round(prog.blocks[-1].feed * 60.0, 9) == 800.0
    assert "G65 argument X10 without a decimal point read as 10 (calculator-type input, Fanuc DPI=1)" in prog.notes


def test_fanuc_g65_arguments_without_a_decimal_point_under_increment_input():
    ctx = dataclasses.replace(_in_dialect("fanuc"), decimal_point_input="increment")
    with pytest.raises(GCodeError, match=r":2:11: G65 macro call: argument 'X10' without a decimal point"):
        parse_program(MACRO_CALL, context=ctx)  # its increment (0.001 mm under IS-B) is not modelled for G65
    prog = parse_program(MACRO_CALL.replace("X10", "X10."), context=ctx)  # F counts in mm/min either way
    assert round(prog.blocks[-1].feed * 60.0, 9) == 800.0


def test_other_controls_refuse_g65_arguments_without_a_decimal_point():
    with pytest.raises(GCodeError, match=r"argument 'X10' without a decimal point"):
        parse_program(MACRO_CALL, context=_in_dialect("haas"))
