"""Fanuc/Haas custom macro B, session 40 (isomacro40): what the manuals say of system variables, functions and calls
that the reader read otherwise. Each input is hand-written in the style of shop macros."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError


def _ctx(dialect: str = "fanuc", **dialect_changes) -> MachineContext:
    return MachineContext(dialect=dataclasses.replace(DIALECTS[dialect], **dialect_changes),
                          tools={1: Tool(number=1, length=20.0, radius=3.0)})


def _ends(text: str, dialect: str = "fanuc") -> list[list[float]]:
    prog = checked_iso(text, _ctx(dialect))
    return [[round(float(v), 6) for v in b.target] for b in prog.blocks]


# --- 1. ROUND in an NC address rounds to the address's least input increment -----------------------------------

# Fanuc's own example (30i/0i-F "ROUND function"): #1 = 1.2345, G00 G91 X-ROUND[#1] moves 1.235 mm
ROUND_MM = ("O1000\nG21 G90 G94 G17 G0 X0 Y0 Z0\n#1=1.2345\n#2=27/32\nG00 G91 X-ROUND[#1]\n"
            "X[ROUND[#2]] Y[ROUND[#2]+ROUND[#2]]\n#3=ROUND[#2]\nG90 X#3 Y#[ROUND[1.4]]\nM30\n")


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_round_in_an_address_rounds_to_the_least_input_increment(dialect):
    # X-ROUND[1.2345] = -1.235 (not -1); 27/32 = 0.84375 rounds to 0.844 in the address (Machinery's Handbook's
    # example), to 1 in an assignment; a variable's number #[ROUND[1.4]] stays whole (#1 = 1.2345, which Y#1 rounds
    # to the increment as any computed address value)
    assert _ends(ROUND_MM, dialect) == [[0, 0, 0], [-1.235, 0, 0], [-0.391, 1.688, 0], [1.0, 1.235, 0]]


def test_round_in_an_inch_address_keeps_four_places_haas_example():
    # Haas 96-8000 "Round": #1 = 1.00333, G0 X[ROUND[#1] + ROUND[#1]] moves to 2.0066 in
    text = "O1\nG20 G90 G0 X0 Y0\n#1=1.00333\nG0 X[ROUND[#1]+ROUND[#1]]\nM30\n"
    assert _ends(text, "haas")[-1][0] == pytest.approx(2.0066 * 25.4)


@pytest.mark.parametrize(("line", "match"), [
    ("G1 X1. F[ROUND[100.4]]", "ROUND in address F"),
    ("G21 X[ROUND[#1]]", "block that changes the unit"),
    ("G65 P2 A[ROUND[#1]]", "macro call's argument"),
])
def test_round_in_an_address_whose_increment_is_not_modelled_is_refused(line, match):
    text = f"O1\nG20 G90 G0 X0\n#1=1.00333\n{line}\nM30\nO2\nM99\n"
    with pytest.raises(GCodeError, match=match):
        parse_program(text, context=_ctx(), source="t.nc")


# --- 2. Fanuc G84/G74 P dwells at the bottom and at point R on the way out ----------------------------------------

TAP = ("O1\nG21 G90 G94 G17 G0 X0 Y0 Z20.\nS500 M3\nG98 G84 X10. Y0 Z-10. R2. P300 F500.\nG99 G74 X20. P0\n"
       "X30. P200\nG80\nM30\n")


def _moves(text: str, dialect: str, line: int) -> list[tuple[str, float, float]]:
    prog = checked_iso(text, _ctx(dialect))
    return [(b.kind, round(float(b.target[2]), 6), round(float(getattr(b, "dwell", 0.0)), 6))
            for b in prog.blocks if b.line == line]


def test_fanuc_tap_dwells_p_at_the_bottom_and_again_at_r():
    # G98: in to -10, dwell 0.3 s, out to R 2, dwell 0.3 s there (the spindle turns forward again), up to 20
    assert [d for k, _, d in _moves(TAP, "fanuc", 4) if k == "dwell"] == [0.3, 0.3]
    assert [(k, z) for k, z, _ in _moves(TAP, "fanuc", 4)] == [
        ("rapid", 20.0), ("rapid", 2.0), ("line", -10.0), ("dwell", -10.0), ("line", 2.0), ("dwell", 2.0),
        ("rapid", 20.0)]
    # P0 dwells nowhere; G99 with P200 dwells at the bottom and at R, where it stays
    assert [k for k, _, _ in _moves(TAP, "fanuc", 5)] == ["rapid", "rapid", "line", "line"]
    assert [(k, z) for k, z, _ in _moves(TAP, "fanuc", 6)] == [
        ("rapid", 2.0), ("line", -10.0), ("dwell", -10.0), ("line", 2.0), ("dwell", 2.0)]


def test_haas_tap_dwells_at_the_bottom_only():
    assert [k for k, _, _ in _moves(TAP, "haas", 4)] == ["rapid", "rapid", "line", "dwell", "line", "rapid"]


# --- 3. A canned cycle outside the G68 plane is refused under fanuc ------------------------------------------------

ROTATED_G18_CYCLE = ("O1\nG21 G90 G94 G17 G0 X0 Y0 Z20.\nG68 X0 Y0 R30.\nG18\nG81 X10. Z-5. Y-10. R2. F100.\nG80\n"
                     "G17 G69\nM30\n")


def test_fanuc_canned_cycle_in_another_plane_than_g68s_is_refused():
    # 15i-MA B-63324EN/03: "G17, G18 or G19 must not be designated in the mode of coordinate system rotation"
    with pytest.raises(GCodeError, match=r"t.nc:5:.*G81 drilling cycle in G18 while G68 rotates the G17 plane"):
        parse_program(ROTATED_G18_CYCLE, context=_ctx(), source="t.nc")


def test_haas_canned_cycle_in_another_plane_than_g68s_drills_along_the_turned_axis():
    prog = checked_iso(ROTATED_G18_CYCLE, _ctx("haas"))
    assert any(b.line == 5 and b.kind == "line" for b in prog.blocks)


def test_fanuc_canned_cycle_in_the_g68_plane_runs():
    text = "O1\nG21 G90 G94 G17 G0 X0 Y0 Z20.\nG68 X0 Y0 R90.\nG81 X10. Y0 Z-5. R2. F100.\nG80\nG69\nM30\n"
    prog = checked_iso(text, _ctx())
    assert [round(float(v), 6) for v in [b for b in prog.blocks if b.kind == "line"][0].target] == [0.0, 10.0, -5.0]


# --- 4. Fanuc/Haas #5041.. (current position) include the tool length offset, #5001.. (block end) do not --------

@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_current_position_includes_the_tool_length_and_block_end_does_not(dialect):
    # a shop macro's "current work Z": #735 = #5043 - #[2000 + #4111] (memory A: #2001 is offset 1, 20 mm here)
    context = MachineContext(dialect=DIALECTS[dialect], tools={1: Tool(number=1, length=20.0)},
                             tool_offset_memory="A" if dialect == "fanuc" else "C")
    text = ("O1000\nG21 G90 G94 G17 G0 X0 Y0 Z50.\nG43 H1 Z10.\n#100=#5003\n#101=#5043\n#102=#5043-#[2000+#4111]\n"
            "G0 X#100 Y#101 Z#102\nM30\n")
    prog = parse_program(text, context=context, source="t.nc")
    # X = #5003 = 10 (programmed), Y = #5043 = 30 (10 + the 20 mm length), Z = 30 - 20 = 10 (machine Z 30)
    assert [round(float(v), 6) for v in prog.blocks[-1].target] == [10.0, 30.0, 30.0]


# --- 5. A GOTO may leave a WHILE loop but not enter one -------------------------------------------------------------

def test_goto_into_a_loop_from_outside_is_refused():
    text = "O1\nG21 G90 G0 X0 Y0 Z0\n#1=0\nGOTO 7\nWHILE[#1 LT 3]DO1\nN7 G0 X1.\n#1=#1+1\nEND1\nM30\n"
    with pytest.raises(GCodeError, match=r"t.nc:4:.*GOTO 7: N7 lies within the loop DO 1"):
        parse_program(text, context=_ctx(), source="t.nc")


def test_goto_out_of_a_loop_within_it_and_to_its_while_runs():
    # N5 is the WHILE block itself (the loop starts there); N8 skips within the loop; GOTO 20 leaves it
    text = ("O1\nG21 G90 G0 X0 Y0 Z0\n#1=0\nGOTO 5\nN5 WHILE[#1 LT 5]DO1\n#1=#1+1\nIF[#1 EQ 2]GOTO 8\nG0 X#1\n"
            "N8 IF[#1 GE 3]GOTO 20\nEND1\nN20 G0 Y1.\nM30\n")
    assert _ends(text) == [[0, 0, 0], [1, 0, 0], [3, 0, 0], [3, 1, 0]]


# --- 6. #3004 bit 2 (exact stop check suppressed) is noted --------------------------------------------------------

def test_exact_stop_check_suppression_is_noted_and_feed_hold_alone_is_not():
    text = "O1\nG21 G90 G94 G0 X0 Y0 Z0\n#3004=3\n#3004=7\nG61 G1 X1. F100.\n#3004=0\nM30\n"
    prog = checked_iso(text, _ctx())
    assert [n for n in prog.notes if "#3004" in n] == [
        "#3004 at line 4 suppresses the exact stop check (bit 2): not modelled, G09/G61 blocks still end at rest"]


# --- 7. A computed tool, offset or M number is rounded ------------------------------------------------------------

@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_computed_d_h_t_and_m_numbers_are_rounded(dialect):
    # Haas 96-8000 "Round": "D[1.67] (Diameter 2 is made current)"; Sinha: #1 = 3.5, M#1 is M04; H#2 with #2 = 1.6 is
    # H2 (the 40 mm tool: G43 H2 Z10. ends at machine Z 50); T#3 with #3 = 0.6 is T1
    context = MachineContext(dialect=DIALECTS[dialect], tools={1: Tool(number=1, length=20.0, radius=3.0),
                                                               2: Tool(number=2, length=40.0, radius=0.0)})
    text = ("O1\nG21 G90 G94 G0 X0 Y0 Z50.\n#1=3.5\n#2=1.6\n#3=0.6\nM#1 S1000\nT#3 M6\nG43 H#2 Z10.\n"
            "G41 D[1.67] G1 X10. F100.\nG40 X20.\nM30\n")
    prog = checked_iso(text, context)
    assert [round(float(b.target[2]), 6) for b in prog.blocks if b.line == 8] == [50.0]
    assert [round(float(b.target[1]), 6) for b in prog.blocks if b.line == 9] == [0.0]  # D2: radius 0


def test_a_macro_calls_computed_h_and_d_arguments_are_not_rounded():
    # G65 P2000 H#2 D#3: #11 = 1.6 and #7 = 0.4 as passed (arguments are values, not offset numbers)
    text = "O1\nG21 G90 G0 X0 Y0 Z0\n#2=1.6\n#3=0.4\nG65 P2000 H#2 D#3\nM30\nO2000\nG0 X#11 Y#7\nM99\n"
    prog = parse_program(text, context=_ctx(), source="t.nc")
    assert [round(float(v), 6) for v in prog.blocks[-1].target] == [1.6, 0.4, 0.0]


# --- 8. #4001 in a canned cycle reads the group 01 code the cycle left in force -----------------------------------

def test_group_01_modal_information_in_a_canned_cycle():
    # G01 before the series: #4001 = 1 while G81 (#4009 = 81) is in force; it was refused as not modelled
    text = ("O1\nG21 G90 G94 G0 X0 Y0 Z10.\nG1 X1. F100.\nG81 X2. Z-1. R1.\n#1=#4001\n#2=#4009\nG80\n"
            "G0 X#1 Y#2\nM30\n")
    prog = parse_program(text, context=_ctx(), source="t.nc")
    assert [round(float(v), 6) for v in prog.blocks[-1].target] == [1.0, 81.0, 10.0]


# --- 9. Any computed address value is rounded to the address's least input increment ------------------------------

def test_fanuc_round_example_does_not_return_to_the_start():
    # Fanuc "ROUND function": #1 = 1.2345, #2 = 2.3456; G91 X-#1 moves 1.235, X-#2 2.346, X[#1+#2] 3.580: 0.001 short
    text = "O1\nG21 G90 G94 G0 X0 Y0 Z0\n#1=1.2345\n#2=2.3456\nG91 G00 X-#1\nG01 X-#2 F300.\nG00 X[#1+#2]\nG90\nM30\n"
    assert [e[0] for e in _ends(text)] == [0.0, -1.235, -3.581, -0.001]


@pytest.mark.parametrize(("units", "x"), [("G20", 0.1235 * 25.4), ("G21", 0.123)])
def test_haas_address_substitution_rounds_to_the_least_significant_digit(units, x):
    # haascnc.com "Address substitution": "#1=.123456, then G01 X#1 would move ... to .1235 ... metric ... .123";
    # a number written out keeps its digits
    text = f"O1\n{units} G90 G94 G0 X0 Y0 Z0\n#1=.123456\nG01 X#1 Y.123456 F10.\nM30\n"
    end = [float(v) for v in checked_iso(text, _ctx("haas")).blocks[-1].target]
    assert end[0] == pytest.approx(x, abs=1e-9)
    assert end[1] == pytest.approx(0.123456 * (25.4 if units == "G20" else 1.0), abs=1e-9)


# --- 10. G68's R is an angle: a computed R rounds to 0.001 deg in an inch program too (review40) ------------------

@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_computed_g68_angle_rounds_to_the_angle_increment_in_inch(dialect):
    # Haas 96-8000 "Round": "For metric and angle dimensions, three-place precision is the default. For inch,
    # four-place": #1 = 10.00049 in G68's R is 10.000 deg, not 10.0005 (the reader and the reference rounded it as an
    # inch length: X10 turned 0.0022 mm further)
    text = "O1\nG20 G90 G17 G0 X0 Y0 Z0\n#1=10.00049\nG68 X0 Y0 R#1\nG1 X10 Y0 F10\nG69\nM30\n"
    a = np.radians(10.0)
    assert np.allclose(_ends(text, dialect)[1], [254.0 * np.cos(a), 254.0 * np.sin(a), 0.0], atol=2e-6)
