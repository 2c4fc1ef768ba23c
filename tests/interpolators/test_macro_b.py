"""Fanuc/Haas custom macro B control flow and variables (:mod:`interpolators.iso_macro`,
:mod:`interpolators.iso_params`) and the system parameters the reader knows (:mod:`interpolators.iso_system`).

Expected values are worked out by hand from the Fanuc 0i-MD operator's manual (B-64304EN, "Custom
macro": "Branch and repetition", "Variables", "Undefined variable"), the Haas mill operator's manual
("Macros") and the LinuxCNC "Numbered Parameters" list.
"""

import math

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.iso_flow import run
from interpolators.iso_macro import MAX_LOOP_PASSES
from interpolators.iso_params import Parameters
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
HAAS = MachineContext(dialect=DIALECTS["haas"])


def _ends(text: str, context: MachineContext = FANUC) -> list[list[float]]:
    return [[round(float(v), 9) + 0.0 for v in b.target] for b in parse_program(text, context=context).blocks]


def _words(text: str, **kw) -> list[list[tuple[str, float]]]:
    return [[(w.letter, w.value) for w in fl.words] for fl in run(text, **kw) if fl.words]


def test_while_loop_makes_a_polygon_with_its_corners_on_the_circle():
    """A hexagon of radius 10 by WHILE [#1 LT 6] DO1: six G1 moves to the corners at 60 degree steps."""
    text = ("G21 G90 G17 F600\nG0 X10 Y0\n#1 = 1\nWHILE [#1 LE 6] DO1\n"
            "G1 X[10 * COS[60 * #1]] Y[10 * SIN[60 * #1]]\n#1 = #1 + 1\nEND1\nM30\n")
    pts = np.array(_ends(text))[1:]
    angles = np.radians(60.0 * np.arange(1, 7))
    # on the circle within half the least input increment (0.001 mm): Fanuc/Haas round a computed address value
    assert np.allclose(pts[:, :2], np.c_[10 * np.cos(angles), 10 * np.sin(angles)], atol=0.0005 + 1e-9)
    assert pts.shape == (6, 3)


def test_nested_while_loops_visit_a_grid_row_by_row():
    """WHILE .. DO1 around WHILE .. DO2: a 3 x 2 grid of points, the inner loop (Y) fastest;
    the inner counter is reset on each outer pass."""
    text = ("G21 G90 F600\n#101 = 0\nWHILE [#101 LT 3] DO1\n#102 = 0\nWHILE [#102 LT 2] DO2\n"
            "G1 X[#101 * 5] Y[#102 * 5]\n#102 = #102 + 1\nEND2\n#101 = #101 + 1\nEND1\nM30\n")
    assert [p[:2] for p in _ends(text)] == [[0, 0], [0, 5], [5, 0], [5, 5], [10, 0], [10, 5]]


def test_loop_numbers_may_be_reused_one_after_another_and_nest_three_deep():
    text = ("#1 = 0\nWHILE [#1 LT 2] DO1\n#2 = 0\nWHILE [#2 LT 2] DO2\n#3 = 0\nWHILE [#3 LT 2] DO3\n"
            "G1 X[#1 * 100 + #2 * 10 + #3]\n#3 = #3 + 1\nEND3\n#2 = #2 + 1\nEND2\n#1 = #1 + 1\nEND1\n"
            "#1 = 0\nWHILE [#1 LT 2] DO1\nG1 Y#1\n#1 = #1 + 1\nEND1\n")
    xs = [w[1][1] for w in _words(text) if w[1][0] == "X"]
    assert xs == [0, 1, 10, 11, 100, 101, 110, 111]
    assert [w[1][1] for w in _words(text) if w[1][0] == "Y"] == [0, 1]


def test_goto_backward_makes_a_loop_and_forward_skips_blocks():
    """IF [#1 LE 3] GOTO 10 jumps back to N10 (searched from the start: Fanuc searches forward first,
    then from the beginning); GOTO 20 skips the block between."""
    text = ("G21 G90 F600\n#1 = 1\nN10 G1 X#1\n#1 = #1 + 1\nIF [#1 LE 3] GOTO 10\nGOTO 20\nG1 X99\n"
            "N20 G1 Y5\nM30\n")
    assert _ends(text) == [[1, 0, 0], [2, 0, 0], [3, 0, 0], [3, 5, 0]]


def test_goto_takes_the_next_block_of_that_number_forward_then_from_the_start():
    """Two blocks numbered N5: from before both, the first after the GOTO is taken; from after both,
    the search wraps to the start of the program and takes the first."""
    text = "#1 = 0\nGOTO 5\nN5 G1 X1\nN5 G1 X2\n#1 = #1 + 1\nIF [#1 LT 2] GOTO 5\nM30\n"
    xs = [w[2][1] for w in _words(text) if len(w) > 2]
    assert xs == [1, 2, 1, 2]


def test_computed_goto_rounds_to_the_nearest_block_number():
    """Haas "Computed branch": GOTO #1 with #1 = 4.49 goes to N4, with 4.5 to N5; GOTO [expression] too."""
    for value, x in ((4.49, 4.0), (4.5, 5.0)):
        text = f"#1 = {value}\nGOTO #1\nN4 G1 X4\nM30\nN5 G1 X5\nM30\n"
        assert _words(text)[0] == [("N", float(round(x))), ("G", 1.0), ("X", x)]
    assert _words("#2 = 2\nGOTO [#2 * 2 + 1]\nN4 G1 X4\nN5 G1 X5\n") == [[("N", 5.0), ("G", 1.0), ("X", 5.0)]]


def test_if_then_assigns_only_when_the_condition_holds():
    text = "#1 = 2\n#2 = 3\nIF [#1 EQ #2] THEN #3 = 7\nIF [#1 LT #2] THEN #4 = 8\nG1 X#3 Y#4\n"
    assert _words(text) == [[("G", 1.0), ("X", 0.0), ("Y", 8.0)]]  # LinuxCNC dialect: unset #3 reads 0
    assert _ends("G21 F1\nG1 X1 Y1\n#1 = 2\nIF [#1 EQ 3] THEN #3 = 7\nG1 X#3 Y2\n") == [[1, 1, 0], [1, 2, 0]]


def test_conditions_join_comparisons_with_and_or_xor():
    """IF [a] AND [b] GOTO n, as 0335_7997A.NC writes it (no outer brackets)."""
    text = ("#1 = 1\n#2 = 2\nIF [#1 EQ 1] AND [#2 EQ 3] GOTO 7\nG1 X1\nIF [#1 EQ 1] OR [#2 EQ 3] GOTO 8\nG1 X2\n"
            "N8 IF [#1 EQ 1] XOR [#2 EQ 2] GOTO 9\nG1 X3\nN9 M30\n")
    assert [w for w in _words(text) if w[0][0] == "G"] == [[("G", 1.0), ("X", 1.0)], [("G", 1.0), ("X", 3.0)]]


def test_vacant_variables_under_the_fanuc_dialect():
    """Fanuc "Undefined variable": X#1 with #1 vacant leaves the word out; #2 = #1 stays vacant; in
    arithmetic vacant is 0 (#1 + 5 = 5, #1 * 5 = 0); EQ and NE tell vacant from 0, GT GE LT LE do not."""
    text = ("G21 G90 F100\nG1 X10 Y10\nG1 X#1 Y20\n#2 = #1\nG1 X#2 Y[#1 + 5]\n#3 = #1 * 5\nG1 X#3\n"
            "IF [#1 EQ 0] GOTO 1\nG1 Y1\nN1 IF [#1 EQ #0] GOTO 2\nG1 Y2\nN2 IF [#1 GE 0] GOTO 3\nG1 Y3\n"
            "N3 IF [#3 NE #0] GOTO 4\nG1 Y4\nN4 M30\n")
    assert _ends(text) == [[10, 10, 0], [10, 20, 0], [10, 5, 0], [0, 5, 0], [0, 1, 0]]


def test_vacant_only_in_g65_locals_under_linuxcnc_and_hash0_is_vacant_everywhere():
    assert _words("G1 X#1 Y#0\n") == [[("G", 1.0), ("X", 0.0)]]  # LinuxCNC: unset reads 0; #0 vacant
    assert _words("G1 X#1 Y#0\n", params=Parameters(macro_b=True)) == [[("G", 1.0)]]
    with pytest.raises(GCodeError, match="#0 cannot be set"):
        _words("#0 = 1\n")


def test_fanuc_functions_fix_fup_bin_bcd_round_and_atan():
    """Fanuc FIX / FUP act on the magnitude (FIX[-1.5] = -1, FUP[-1.2] = -2), LinuxCNC's are floor and
    ceiling; BCD[12] = 0x12 = 18, BIN[18] = 12; ROUND[-2.5] = -3 (in an assignment: in an address ROUND rounds to
    the address's increment, Z ROUND[-2.5] is -2.5); ATAN[1]/[-1] = 135 degrees."""
    line = "#1 = ROUND[-2.5]\nG1 X FIX[-1.5] Y FUP[-1.2] Z ROUND[-2.5] A BCD[12] B BIN[18] C ATAN[1]/[-1] U#1\n"
    params = Parameters(macro_b=True)
    fanuc = [v for _, v in _words(line, params=params)[0][1:]]
    assert fanuc == [-1.0, -2.0, -2.5, 18.0, 12.0, pytest.approx(135.0), -3.0]
    linuxcnc = [v for _, v in _words(line)[0][1:3]]
    assert linuxcnc == [-2.0, -1.0]
    assert math.isclose(_words("G1 X[SQRT[2] * SQRT[2]]\n")[0][1][1], 2.0)


def test_logical_operators_work_bit_by_bit_under_macro_b():
    """Fanuc 0i-MD "Arithmetic and logic operation" (OR, XOR, AND "performed on binary numbers bit by bit"), Haas
    "Logical operations" (the integer part): 5 OR 3 = 0b111 = 7, 5 XOR 3 = 0b110 = 6, 12 AND 10 = 0b1000 = 8,
    5.7 OR 2.2 = 5 OR 2 = 7; on comparisons (1/0) the same as logic. LinuxCNC's are logical: 5 OR 3 = 1."""
    line = "G1 X[5 OR 3] Y[5 XOR 3] Z[12 AND 10] A[5.7 OR 2.2] B[[1 EQ 1] AND [2 EQ 2]]\n"
    bitwise = [v for _, v in _words(line, params=Parameters(macro_b=True))[0][1:]]
    assert bitwise == [7.0, 6.0, 8.0, 7.0, 1.0]
    assert [v for _, v in _words(line)[0][1:]] == [1.0, 0.0, 1.0, 1.0, 1.0]


def test_fanuc_atan_is_0_to_360_and_reads_the_two_argument_forms():
    """Fanuc ATAN (parameter NAT = 0, its default) gives 0-360 deg: ATAN[-1]/[-1] = 225 (atan2 gives -135, as
    Haas and LinuxCNC read it); the Series 0i-F/30i forms ATAN[-1,-1] = 225 and POW[2,3] = 2^3 = 8 read under
    the fanuc dialect only."""
    text = "G21 F100\nG1 X[ATAN[-1]/[-1]] Y[ATAN[-1,-1]] Z[POW[2,3]]\nM30\n"
    assert _ends(text) == [[225.0, 225.0, 8.0]]
    assert _ends("G21 F100\nG1 X[ATAN[-1]/[-1]]\nM30\n", context=HAAS) == [[-135.0, 0, 0]]
    with pytest.raises(GCodeError, match="unknown function 'POW'"):
        _ends("G21 F100\nG1 X[POW[2,3]]\nM30\n", context=HAAS)
    with pytest.raises(GCodeError, match="POW needs two arguments"):
        _ends("G21 F100\nG1 X[POW[2]]\nM30\n")


def test_g65_locals_per_level_and_common_variables():
    """Each G65 level has its own #1-#33 (the caller's #1 is back after M99); #100 and #500 are common."""
    text = ("G21 F100\n#1 = 7.\n#100 = 1.\nG65 P9001 A2.\nG1 X#1 Y#100 Z#500\nM30\nO9001\n#100 = #1 * 10\n"
            "#500 = 3.\nG65 P9002 A5.\nG1 X#1\nM99\nO9002\nG1 Y#1\nM99\n")
    assert _ends(text) == [[0, 5, 0], [2, 5, 0], [7, 20, 3]]


def test_an_endless_loop_is_an_error_naming_the_line():
    """The guard counts the passes of each loop end; a loop that ends starts afresh the next time it runs."""
    assert MAX_LOOP_PASSES == 100_000
    with pytest.raises(GCodeError, match="END 1: the loop DO 1 it closes .* more than 1000 times") as info:
        _words("#1 = 0\nWHILE [#1 GE 0] DO1\n#1 = #1 + 1\nEND1\n", max_loop_passes=1000)
    assert info.value.line == 4
    with pytest.raises(GCodeError, match="GOTO 5 .* more than 1000 times") as info:
        _words("N5 #1 = 1\nGOTO 5\n", max_loop_passes=1000)
    assert info.value.line == 2
    text = "#2 = 0\nWHILE [#2 LT 3] DO1\n#1 = 0\nWHILE [#1 LT 800] DO2\n#1 = #1 + 1\nEND2\n#2 = #2 + 1\nEND1\nG1 X#2\n"
    assert _words(text, max_loop_passes=1000) == [[("G", 1.0), ("X", 3.0)]]


@pytest.mark.parametrize(("text", "needle"), [
    ("WHILE [1 EQ 1] DO4\nEND4\n", "DO 4: loop identification number out of range"),
    ("WHILE [1 EQ 1] DO1\nG1 X1\n", "DO 1 without END 1"),
    ("WHILE [#1 LT 2] DO1\nWHILE [#1 LT 2] DO2\nEND1\nEND2\n", "END 1 closes no open DO 1"),
    ("DO1\nDO2\nDO3\nDO1\nEND1\nEND3\nEND2\nEND1\n", "nested deeper than 3"),
    ("WHILE [1 EQ 1]\n", "WHILE without DO m"),
    ("IF [1 EQ 1] G1 X1\n", "must be followed by GOTO n or THEN"),
    ("IF [1 EQ 1] THEN G1 X1\n", "NC word 'G1' after THEN"),
    ("GOTO 3 X1\n", "text after the GOTO target"),
])
def test_macro_b_errors_name_the_problem(text, needle):
    with pytest.raises(GCodeError, match=needle):
        _words(text)


def test_goto_stays_within_its_program():
    """A subprogram's GOTO 1 finds its own N1, not the main program's."""
    text = "N1 G1 X1\nM98 P100\nM30\nO100\nGOTO 1\nG1 X5\nN1 G1 Y7\nM99\n"
    assert [w[-1] for w in _words(text)][:3] == [("X", 1.0), ("Y", 7.0), ("M", 30.0)]  # the caller stops at M30
    with pytest.raises(GCodeError, match="no block N2 in this program"):
        _words("N2 G1 X1\nM98 P100\nM30\nO100\nGOTO 2\nM99\n")


def test_system_parameters_read_the_machine_state():
    """LinuxCNC "Numbered Parameters": #5021.. machine position (G53), #5420.. position in the active
    coordinate system with all offsets (program units), #5161 G28 and #5181 G30 positions, #5211 the
    G92 offset, #5221.. the G54 offset, #5220 the coordinate system, #5400 the tool, #5403 its length."""
    ctx = MachineContext(home=(1.0, 2.0, 3.0), reference2=(4.0, 5.0, 6.0),
                         work_offsets={"G55": (10.0, 20.0, 0.0)}, tools={3: Tool(number=3, length=12.5, radius=2.0)})
    text = ("G21 G90 F100\nG55 G0 X1 Y2 Z3\n#1 = #5021\n#2 = #5420\n#3 = #5220\nT3 M6\nG43 H3\n"
            "G53 G1 X#1 Y#2 Z#3\nG53 G1 X#5161 Y#5182 Z#5403\nG53 G1 X#5241 Y#5242 Z#5410\n"
            "G92 X-3\nG53 G1 X#5211 Y#5210\nG20\nG53 G1 X#5021 Y#5420\nM30\n")
    pts = _ends(text, ctx)
    assert pts[1] == [11.0, 1.0, 2.0]  # #5021 = 11 (machine), #5420 = 1, coordinate system 2 (G55)
    assert pts[2] == [1.0, 5.0, 12.5]  # G28 X, G30 Y, tool 3 length
    assert pts[3] == [10.0, 20.0, 4.0]  # G55 X Y, tool diameter
    assert pts[4] == [3.0, 1.0, 4.0]  # G92 X-3 at program X0: offset 3 (LinuxCNC axis offset), applied
    # G20: #5021 and #5420 in inch, read back as inch words: machine X 3 mm, program X 3 - 10 - 3 = -10 mm
    assert pts[5][:2] == [pytest.approx(3.0), pytest.approx(-10.0)]


def test_positions_after_a_program_stop_are_noted_and_the_probe_is_an_error():
    """A program that reads #5021 after M0 (the operator jogs to a point, as in a sheet-measuring program)
    reads where the program stopped (start pressed without a jog), with a note naming the stop's line."""
    prog = parse_program("G21 G0 X1\nG0 Y3\nM0\n#1 = #5021\n#2 = #5022\nG0 X[#1 + 1] Y#2\n", context=FANUC)
    assert [round(float(v), 9) for v in prog.blocks[-1].target] == [2, 3, 0]
    assert [n for n in prog.notes if "read after" in n] == [
        "position read after a program stop (line 3): the position where the program stopped; a jog by the "
        "operator is not modelled"]
    assert _ends("G21 G0 X1\nM0\nG0 X2\n#1 = #5021\nG0 Y#1\n")[-1] == [2, 2, 0]
    assert not [n for n in parse_program("G21 G0 X1\nM0\nG0 X2\n#1 = #5021\n", context=FANUC).notes
                if "read after" in n]  # a move since the stop: the position is known
    with pytest.raises(GCodeError, match="#5061: the probe result"):
        parse_program("G21 G0 X#5061\n")
    with pytest.raises(GCodeError, match="#5420: the current position cannot be read with cutter radius"):
        parse_program("G21 F100 G0 X0 Y0\nG41.1 D2 G1 X10\nG1 Y#5420\n")
    with pytest.raises(GCodeError, match="#5021 is read-only"):
        parse_program("#5021 = 1\n")


def test_fanuc_block_end_and_work_position_variables():
    """Fanuc/Haas #5001 (block end point) and #5041 (current position), work coordinates; under
    LinuxCNC #5001 is an ordinary parameter the program must set first."""
    assert _ends("G21 F100\nG10 L2 P1 X5\nG54 G1 X1 Y2\nG1 X[#5001 + 1] Y#5042\n")[-1] == [7, 2, 0]
    with pytest.raises(GCodeError, match="#5001"):
        parse_program("G21 G1 X#5001\n")


def test_linuxcnc_named_aliases_of_system_parameters():
    """LinuxCNC "Predefined Named Parameters": #<_x> is #5420, #<_abs_x> #5021, #<_current_tool> #5400;
    they and #<_ini[section]name> are read-only; INI values are not available to vcnc."""
    ctx = MachineContext(work_offsets={"G54": (5.0, 0.0, 0.0)})
    assert _ends("G21 G0 X1\nT3 M6\nG0 Y[#<_x> + #<_abs_x>] Z#<_current_tool>\n", ctx)[-1] == [6.0, 7.0, 3.0]
    with pytest.raises(GCodeError, match="#<_x> is read-only"):
        parse_program("#<_x> = 1\n")
    with pytest.raises(GCodeError, match="INI file values are not available"):
        parse_program("G0 X#<_ini[vars]toolchange_x>\n")


#: Macro B programs whose block ends the independent reference (tests/interpolators/reference_iso.py,
#: written from the Fanuc manual without the reader's code) predicts too.
_REFERENCE_PROGRAMS = [
    "G21 G90 F600\n#101 = 0\nWHILE [#101 LT 3] DO1\n#102 = 0\nWHILE [#102 LT 2] DO2\nG1 X[#101 * 5] Y[#102 * 5]\n"
    "#102 = #102 + 1\nEND2\n#101 = #101 + 1\nEND1\nM30\n",
    "G21 G90 F600\n#1 = 1\nN10 G1 X#1\n#1 = #1 + 1\nIF [#1 LE 3] GOTO 10\nGOTO 20\nG1 X99\nN20 G1 Y5\nM30\n",
    "G21 F1\nG1 X1 Y1\n#1 = 2\nIF [#1 EQ 3] THEN #3 = 7\nIF [#1 EQ 2] THEN #4 = 9\nG1 X#3 Y#4\n",
    "G21 F100\n#1 = 1\n#2 = 2\nIF [#1 EQ 1] AND [#2 EQ 3] GOTO 7\nG1 X1\nIF [#1 EQ 1] OR [#2 EQ 3] GOTO 8\nG1 X2\n"
    "N8 IF [#1 EQ 1] XOR [#2 EQ 2] GOTO 9\nG1 X3\nN9 M30\n",
    "G21 F100\nG1 X5 Y#0\n#3=#0\nIF [#3 EQ #0] GOTO 5\nG1 X7\nN5 G1 X8\nM30\n",
    "G21 F100\nN1 G1 X1\nM98 P100\nM30\nO100\nGOTO 1\nG1 X5\nN1 G1 Y7\nM99\n",
]


@pytest.mark.parametrize("text", _REFERENCE_PROGRAMS)
def test_macro_b_block_ends_match_the_independent_reference(text):
    from tests.interpolators.reference_iso import iso_reference

    ctx = MachineContext(work_offsets={"G54": (1.0, 2.0, 3.0)})
    got = [b.target.round(9).tolist() for b in parse_program(text, context=ctx).blocks]
    assert got == [e.end.round(9).tolist() for e in iso_reference(text, ctx)]


def test_fanuc_modal_information_alarm_and_system_variables():
    """Fanuc 0i-MD "System variables": #4003 is 90/91 and #4014 the work offset, #4109 the F (a macro
    saves and restores the modes with them: G#1); #3000 = n stops with macro alarm n; an unmodelled
    system variable such as #1000 (interface signals) is an error; LinuxCNC reads #2001 as a user parameter."""
    text = "G21 G90 F600\nG55 G91 G1 X1\n#1 = #4003\n#2 = #4014\n#3 = #4109\nG90\nG#1 X#2 Y#3\n"
    assert _ends(text) == [[1.0, 0.0, 0.0], [56.0, 600.0, 0.0]]
    with pytest.raises(GCodeError, match="macro alarm #3000 = 1") as info:
        parse_program("G21\nIF [1 EQ 1] THEN #3000 = 1 (NO TOOL)\n", context=HAAS)
    assert info.value.line == 2
    with pytest.raises(GCodeError, match="#1000: this Fanuc system variable"):
        parse_program("G21 G0 X#1000\n", context=FANUC)
    assert _ends("G21 G0 X#2001\n", MachineContext()) == [[0.0, 0.0, 0.0]]


def test_fanuc_modal_information_of_length_compensation_spindle_and_transformations():
    """Fanuc 0i-MD "System variables", "Modal information": #4008 the group 8 code (43/44/49), #4111
    its H number, #4107 the D number of G41/G42, #4119 S, #4005 94/95, #4016 68/69, #4011 50/51 and
    #4022 50.1/51.1; a group vcnc does not model (#4004) is an error naming the variable."""
    tools = MachineContext(dialect=DIALECTS["fanuc"], tools={3: Tool(number=3, length=10.0, radius=0.0)})
    text = ("G21 G90 F600\nT3 M6\nG43 H3 Z50.\nS1200 M3\nG41 D3 G1 X10. Y0.\n#1=#4008\n#2=#4111\n#3=#4107\n"
            "#4=#4119\n#5=#4005\nG40 G1 X#1 Y#2\nG1 X#3 Y#4\nG1 X#5 Z0\nG49 G95 G68 X0 Y0 R90.\n#6=#4008\n"
            "#7=#4005\n#8=#4016\nG69 G94 F600\nG51 X0 Y0 P2000\n#9=#4011\nG50\nG51.1 X0\n#10=#4022\nG50.1 X0\n"
            "G1 X#6 Y#7 Z#8\nG1 X#9 Y#10\n")
    assert _ends(text, tools)[-5:] == [[43.0, 3.0, 60.0], [3.0, 1200.0, 60.0], [94.0, 1200.0, 10.0],
                                        [49.0, 95.0, 68.0], [51.0, 51.1, 68.0]]
    with pytest.raises(GCodeError, match="#4004: this Fanuc system variable"):
        parse_program("G21 G0 X#4004\n", context=FANUC)


def test_parts_counters_start_at_zero_and_keep_what_the_program_sets():
    """Fanuc 0i-MD "System variables": #3901 number of machined parts, #3902 number of required parts, both
    read/write (Haas "Macros": M30 counts 1 and 2). The virtual machine's counters start at 0 (noted): a
    program counting its parts and comparing with the required count runs; LinuxCNC reads #3901 as a user
    parameter."""
    text = ("G21 G90 F600\n#3901 = #3901 + 1\nG1 X#3901\n#3902 = 4\n#3901 = #3901 + 2\n"
            "IF [#3901 GE #3902] GOTO 7\nG1 Y#3902\nN7 G1 X[#3902 - #3901] Y#3901\n")
    prog = parse_program(text, context=FANUC)
    assert [[round(float(v), 9) + 0.0 for v in b.target] for b in prog.blocks] == [
        [1.0, 0.0, 0.0], [1.0, 4.0, 0.0], [1.0, 3.0, 0.0]]
    assert any("parts counters #3901/#3902" in n for n in prog.notes)
    assert _ends("G21 G90 F600\n#3901 = 5\nG1 X#3901\n", HAAS) == [[5.0, 0.0, 0.0]]
    assert _ends("G21 G90 F600\n#3901 = #3901 + 2\nG1 X#3901\n", MachineContext()) == [[2.0, 0.0, 0.0]]


def test_m99_p_returns_to_a_block_of_the_calling_program():
    """Haas "M99 Subprogram Return or Loop": M99 P30 returns to N30 of the caller, skipping N20."""
    text = "G21 F100\nM98 P100\nN20 G1 X5\nN30 G1 Y7\nM30\nO100\nG1 X1\nM99 P30\n"
    assert _ends(text) == [[1, 0, 0], [1, 7, 0]]
    with pytest.raises(GCodeError, match="M99 P40: no block N40 in the calling program"):
        parse_program("G21 F100\nM98 P100\nM30\nO100\nG1 X1\nM99 P40\n", context=FANUC)
