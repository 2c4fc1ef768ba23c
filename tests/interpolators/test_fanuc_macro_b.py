"""Fanuc/Haas custom macro B: operator precedence, MOD, the tool offset variables by offset memory type, the
message stop #3006 and the alarm #3000 (:mod:`interpolators.iso_params`, :mod:`interpolators.iso_system`,
:mod:`interpolators.iso_offsets`).

Expected values are worked out by hand from the rules the modules cite (Fanuc 0i-MD operator's manual
B-64304EN, "Custom macro"; Haas mill operator's manual, "Macros").
"""

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from vcnc.core.errors import InputError, MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
HAAS = MachineContext(dialect=DIALECTS["haas"])
LINUXCNC = MachineContext()


def _ends(text: str, context: MachineContext = FANUC) -> list[list[float]]:
    return [[round(float(v), 9) + 0.0 for v in b.target] for b in parse_program(text, context=context).blocks]


@pytest.mark.parametrize("context", [FANUC, HAAS], ids=["fanuc", "haas"])
def test_macro_b_ranks_and_with_times_and_or_xor_with_plus(context):
    """Functions, then * / AND (MOD), then + - OR XOR, left to right within a level:
    2+3AND1 = 2+[3 AND 1] = 2+1 = 3; 6 OR 1*2 = 6 OR 2 = 6 (0b110 | 0b010); 1+2 OR 4 = 3 OR 4 = 7;
    4 XOR 1+2 = [4 XOR 1]+2 = 7; 12 AND 10 * 2 = [12 AND 10] * 2 = 16; 2*3 MOD 4 = 6 MOD 4 = 2;
    SIN[30]*4 AND 3 = [0.5*4] AND 3 = 2."""
    text = ("G21 G90 G1 F100\n#1=2+3AND1\n#2=6OR1*2\n#3=1+2OR4\nX#1 Y#2 Z#3\n"
            "#4=4XOR1+2\n#5=12AND10*2\n#6=2*3MOD4\nX#4 Y#5 Z#6\n#7=SIN[30]*4AND3\nX#7\n")
    assert _ends(text, context) == [[3.0, 6.0, 7.0], [7.0, 16.0, 2.0], [2.0, 16.0, 2.0]]


def test_linuxcnc_keeps_its_logical_operators_lowest():
    """LinuxCNC ("Binary Operators"): AND OR XOR below + and the comparisons, logical: [2+3 AND 1] = [5 AND 1]
    = 1; [6 OR 1*2] = 1; [1+2 OR 4] = 1; [4 XOR 1+2] = [4 XOR 3] = 0."""
    text = "G21 G90 G1 F100\n#1=[2+3AND1]\n#2=[6OR1*2]\n#3=[1+2OR4]\nX#1 Y#2 Z#3\n#4=[4XOR1+2]\nX#4\n"
    assert _ends(text, LINUXCNC) == [[1.0, 1.0, 1.0], [0.0, 1.0, 1.0]]


def test_comparisons_come_last_and_join_only_in_their_own_brackets():
    """IF [#1+1 EQ 3] compares the sum (#1 = 2: true); IF [#1 EQ 2] AND [#2 EQ 5] joins two bracketed
    comparisons (1 AND 1 = 1: true) and GOTO 9 skips X1. IF [#1 EQ 3 OR #2 EQ 5 AND #1 GT 1] joins
    comparisons in one bracket: read comparisons first, [0 OR 1 AND 1] = [[0 OR 1] AND 1] = 1 (LinuxCNC's AND OR
    XOR: one level, left to right), with a note
    (Fanuc's precedence would compare #1 EQ [3 OR #2] with [5 AND #1], false), and so are the nested and
    assigned forms; a bracket inside keeps Fanuc's precedence ([2 + 3 AND 1] = 3)."""
    text = ("G21 G90 G1 F100\n#1=2\n#2=5\nIF [#1+1 EQ 3] THEN #3=4\nX#3\n"
            "IF [#1 EQ 2] AND [#2 EQ 5] GOTO 9\nX1\nN9 Y7\n")
    assert _ends(text) == [[4.0, 0.0, 0.0], [4.0, 7.0, 0.0]]
    for context in (FANUC, HAAS):
        prog = parse_program("G21 G90 G1 F100\n#1=2\n#2=5\nIF [#1 EQ 3 OR #2 EQ 5 AND #1 GT 1] GOTO 9\nX1\n"
                             "N9 #4 = #1 LT 9 AND [2 + 3 AND 1] EQ 3\nY#4 Z[[#1 GT 0 AND #2 GT 6] + 5]\nM30\n",
                             context=context)
        assert [[float(v) for v in b.target] for b in prog.blocks] == [[0.0, 1.0, 5.0]]
        assert ("comparisons joined by AND/OR/XOR in one bracket read comparisons first, [a GT b] AND [c LT d] "
                "(Fanuc writes each in its own brackets) x3") in prog.notes


def test_mod_is_the_non_negative_remainder():
    """Haas "Arithmetic Operators": 27 MOD 20 = 7; -7 MOD 3 = 2 (the remainder made non-negative, as LinuxCNC's);
    7.5 MOD 2 = 1.5; MOD 0 is a division by zero."""
    assert _ends("G21 G90 G1 F100\nX[27 MOD 20] Y[-7 MOD 3] Z[7.5 MOD 2]\n", HAAS) == [[7.0, 2.0, 1.5]]
    with pytest.raises(GCodeError, match="division by zero"):
        parse_program("#1 = 5 MOD 0\n", context=FANUC)


def test_memory_c_variables_and_g10_set_h_and_d_geometry_and_wear_apart():
    """Fanuc 0i-MD "System variables", memory C (the default): #11000+n H geometry (#2200+n), #10000+n H wear
    (#2000+n), #13000+n D geometry, #12000+n D wear. Tool 3: H 50 - 0.2 = 49.8 (G43 H3 Z0 at machine Z 49.8);
    D 5 - 0.1 = 4.9 (G41 D3 along +X: Y 4.9). G10 L10 P4 R30 is #11004 = #2204 = 30; G91 G10 L11 P4 R0.5 twice:
    #10004 = 1; G10 L12 P4 R2 and L13 R0.25: #13004 = 2, #12004 = 0.25."""
    text = ("G21 G90\n#11003 = 50.\n#10003 = -0.2\n#13003 = 5.\n#12003 = -0.1\nG43 H3 G0 Z0\n"
            "G41 D3 G1 X10. Y0 F100\nG40 X20.\nG49 G53 G0 X#2203 Y#2003 Z0\n"
            "G10 L10 P4 R30.\nG91 G10 L11 P4 R0.5\nG10 L11 P4 R0.5\nG90 G10 L12 P4 R2.\nG10 L13 P4 R0.25\n"
            "G53 G0 X#11004 Y#2204 Z#10004\nG53 G0 X#13004 Y#12004\n")
    assert _ends(text) == [[0.0, 0.0, 49.8], [10.0, 4.9, 49.8], [20.0, 0.0, 49.8], [50.0, -0.2, 0.0],
                           [30.0, 30.0, 1.0], [2.0, 0.25, 1.0]]


B = MachineContext(dialect=DIALECTS["fanuc"], tool_offset_memory="B")


def test_memory_b_shares_one_geometry_and_wear_between_h_and_d():
    """Memory B: offset n has one geometry (#11000+n, #2200+n; G10 L10) and one wear (#10000+n, #2000+n; G10
    L11), which H n and D n both use: #11005 = 6, #10005 = -0.5 -> G43 H5 Z0 at machine Z 5.5 and G41 D5 offset
    5.5. #13005 (a memory C variable) and G10 L12 are errors naming memory B."""
    text = ("G21 G90\n#11005 = 6.\n#10005 = -0.5\nG43 H5 G0 Z0\nG41 D5 G1 X10. Y0 F100\nG40 X20.\n"
            "G49 G53 G0 X#2205 Y#2005 Z#11005\nG10 L10 P6 R7.\nG53 G0 X#11006\n")
    assert _ends(text, B) == [[0.0, 0.0, 5.5], [10.0, 5.5, 5.5], [20.0, 0.0, 5.5], [6.0, -0.5, 6.0],
                              [7.0, -0.5, 6.0]]
    with pytest.raises(GCodeError, match="#13005: a tool offset variable that tool compensation memory B does not"):
        parse_program("G21\n#1 = #13005\n", context=B)
    with pytest.raises(GCodeError, match="G10 L12: tool compensation memory B has no such offset"):
        parse_program("G21\nG10 L12 P5 R3.\n", context=B)


def test_memory_b_reads_the_machine_table_when_length_and_radius_agree():
    """The machine's table keeps a length and a radius per tool: under memory B offset n is one register, read
    as their common value or the one that is not 0 (tool 8: length 100, radius 0 -> 100); two different values
    (tool 7: length 100, radius 4) are an error naming both."""
    tools = {7: Tool(number=7, length=100.0, radius=4.0), 8: Tool(number=8, length=100.0)}
    context = dataclasses.replace(B, tools=tools)
    assert _ends("G21 G90\nG53 G0 X#11008 Z#13008\n", dataclasses.replace(context, tool_offset_memory="C")) \
        == [[100.0, 0.0, 0.0]]
    assert _ends("G21 G90\nG53 G0 X#11008\n", context) == [[100.0, 0.0, 0.0]]
    with pytest.raises(GCodeError, match="length 100 and radius 4 mm"):
        parse_program("G21\n#1 = #11007\n", context=context)


def test_memory_a_has_one_value_per_offset():
    """Memory A: #10000+n (#2000+n) is the whole offset, no wear; G10 L11 (L1) sets it, G10 L10 is an error;
    #11006 is not a memory A variable. #10006 = 3: G43 H6 Z0 at machine Z 3; G10 L1 P6 R4: #2006 = 4."""
    a = dataclasses.replace(B, tool_offset_memory="A")
    text = "G21 G90\n#10006 = 3.\nG43 H6 G0 Z0\nG10 L1 P6 R4.\nG49 G53 G0 X#2006 Z0\n"
    assert _ends(text, a) == [[0.0, 0.0, 3.0], [4.0, 0.0, 0.0]]
    with pytest.raises(GCodeError, match="G10 L10: tool compensation memory A has no such offset .its G10: L1 L11"):
        parse_program("G21\nG10 L10 P6 R4.\n", context=a)
    with pytest.raises(GCodeError, match="#11006: a tool offset variable that tool compensation memory A"):
        parse_program("G21\n#1 = #11006\n", context=a)
    with pytest.raises(GCodeError, match="#13006 cannot be set: a tool offset variable that tool compensation memory"):
        parse_program("G21\n#13006 = 1.\n", context=a)


def test_haas_keeps_its_own_tool_variables_and_general_purpose_10000s():
    """Haas: #2401+n is tool n's diameter geometry whatever the Fanuc memory setting (#2403 = 10: G41 D3 offset
    5); its #10001.. are general-purpose variables, not tool offsets."""
    haas_b = dataclasses.replace(HAAS, tool_offset_memory="B")
    text = "G21 G90\n#2403 = 10.\n#10001 = 7.\nG41 D3 G1 X10. Y0 F100\nG40 X20.\nG0 X#10001 Y#2003\n"
    assert _ends(text, haas_b) == [[10.0, 5.0, 0.0], [20.0, 0.0, 0.0], [7.0, 0.0, 0.0]]


def test_the_memory_type_is_checked_and_read_from_the_machine_file(tmp_path):
    with pytest.raises(InputError, match="tool_offset_memory must be one of A, B, C"):
        MachineContext(tool_offset_memory="D")
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndialect = "fanuc"\ntool_offset_memory = "B"\n')
    assert load_machine(str(path)).context.tool_offset_memory == "B"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ntool_offset_memory = "c"\n')
    with pytest.raises(MachineError, match="'program.tool_offset_memory' must be 'A', 'B' or 'C'"):
        load_machine(str(path))


def test_message_stop_ends_the_path_at_rest_before_it_and_notes_the_message():
    """#3006 = 1 (TURN PART): the blocks before it run and the program stops as at M0 (the block before it ends
    at rest under G64), with the block's comment shown; a position read at once after it is the stop's (noted).
    LinuxCNC reads #3006 as a user parameter: no stop."""
    text = "G21 G90 G64 G1 F100\nX10.\nX20.\n#3006=1 (TURN PART)\n#1=#5001\nX[#1+5.]\nX30.\nM30\n"
    prog = parse_program(text, context=FANUC)
    assert [(b.target[0], b.exact_stop) for b in prog.blocks] == [(10.0, False), (20.0, True), (25.0, False),
                                                                  (30.0, False)]
    assert "#3006 message stop at line 4 (TURN PART): the program waits for cycle start" in prog.notes
    assert "position read after a program stop (line 4): the position where the program stopped; a jog by the " \
           "operator is not modelled" in prog.notes
    linuxcnc = parse_program(text.replace("#5001", "#5420"), context=LINUXCNC)
    assert [b.exact_stop for b in linuxcnc.blocks] == [False] * 4


def test_message_stop_in_a_loop_stops_each_pass():
    """Haas: WHILE [#1 LT 2] with IF [..] THEN #3006 = 1 (CHECK) after each move: both moves end at rest, one note
    counted twice."""
    text = ("G21 G90 G64 G1 F100\n#1 = 0\nWHILE [#1 LT 2] DO1\n#1 = #1 + 1\nG1 X[#1 * 10]\n"
            "IF [#1 GT 0] THEN #3006 = 1 (CHECK)\nEND1\nG1 Y5.\nM30\n")
    prog = parse_program(text, context=HAAS)
    assert [b.exact_stop for b in prog.blocks] == [True, True, False]
    assert "#3006 message stop at line 6 (CHECK): the program waits for cycle start x2" in prog.notes


def test_macro_alarm_names_its_number_and_message():
    """#3000 = 101 (TOOL BROKEN): an error at its line naming the alarm number and the message."""
    with pytest.raises(GCodeError, match=r"macro alarm #3000 = 101 \(TOOL BROKEN\): the program raises an alarm") \
            as info:
        parse_program("G21 G90\nG0 X1.\n#3000 = 101 (TOOL BROKEN)\nG0 X2.\n", context=FANUC)
    assert info.value.line == 3


def test_clocks_may_be_reset_but_not_read():
    """#3001 = 0 (start a timing) is taken without effect; reading #3001 (a wait on the milliseconds clock) is an
    error naming the clock and G04, and so is #3012 (the time of day); LinuxCNC reads #3001 as a user parameter."""
    assert _ends("G21 G90\n#3001 = 0\n#3002 = 0\nG0 X1.\n") == [[1.0, 0.0, 0.0]]
    with pytest.raises(GCodeError, match=r"parameter #3001: the milliseconds clock, .*G04 waits a given time") as info:
        parse_program("G21\n#3001 = 0\nWHILE [#3001 LT 2000] DO1\nEND1\nM30\n", context=HAAS)
    assert info.value.line == 3
    with pytest.raises(GCodeError, match="#3012: the time of day of a run"):
        parse_program("#1 = #3012\n", context=FANUC)
    with pytest.raises(GCodeError, match="#3011 cannot be set: the date of a run"):
        parse_program("#3011 = 0\n", context=FANUC)
    assert _ends("G21 G90\n#3001 = 4\nG0 X#3001\n", LINUXCNC) == [[4.0, 0.0, 0.0]]


def test_a_wear_update_of_the_tool_in_the_spindle_through_an_indirect_variable():
    """A shop macro's wear update, #[10000+#4120] = #[10000+#4120] + #100 (memory C: H wear of the tool in the
    spindle): tool 3 of the machine's table (length 80) gets -0.05 twice, so G43 H3 Z0 is at machine Z 79.9 and
    #[11000+#4120] (H geometry) still reads 80."""
    context = dataclasses.replace(FANUC, tools={3: Tool(number=3, length=80.0)})
    text = ("G21 G90\nT3 M6\n#100 = -0.05\n#[10000+#4120] = #[10000+#4120] + #100\n"
            "#[10000+#4120] = #[10000+#4120] + #100\nG43 H3 G0 Z0\nG49 G53 G0 X#[11000+#4120] Y#10003\n")
    assert _ends(text, context) == [[0.0, 0.0, 79.9], [80.0, -0.1, 79.9]]


def test_haas_part_timers_may_be_reset_but_the_power_on_timer_not():
    """Haas's system variables (zappettiniconsulting.com/wiki/haas-system-variables, from the Haas "Macros" table):
    "#3020 Power on timer (read only)", #3021 cycle start, #3022 feed, #3023-#3025 part timers without that mark: a
    program resets them as it resets #3001 (``#3023 = 0`` before a part); before review35 such a write was refused
    as "cannot be set". Reading them stays an error (the time comes from the run)."""
    assert _ends("G21 G90\n#3021 = 0\n#3023 = 0\nG0 X1.\n", HAAS) == [[1.0, 0.0, 0.0]]
    with pytest.raises(GCodeError, match=r"#3020 cannot be set: Haas's power-on timer") as info:
        parse_program("G21 G90\n#3020 = 0\nG0 X1.\n", context=HAAS)
    assert info.value.line == 2
    with pytest.raises(GCodeError, match=r"parameter #3023: Haas's present part timer"):
        parse_program("G21 G90\n#3023 = 0\n#1 = #3023\n", context=HAAS)
