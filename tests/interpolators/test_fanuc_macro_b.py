"""Fanuc/Haas custom macro B: operator precedence, MOD, the tool offset variables by offset memory type, the
message stop #3006 and the alarm #3000 (:mod:`interpolators.iso_params`, :mod:`interpolators.iso_system`,
:mod:`interpolators.iso_offsets`).

Expected values are worked out by hand from the rules the modules cite (Fanuc 0i-MD operator's manual
B-64304EN, "Custom macro"; Haas mill operator's manual, "Macros").
"""

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
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
    comparisons (1 AND 1 = 1: true) and GOTO 9 skips X1; IF [#1 EQ 2 OR #2 EQ 5] puts two comparisons in one
    bracket: an error naming them and the brackets Fanuc needs."""
    text = ("G21 G90 G1 F100\n#1=2\n#2=5\nIF [#1+1 EQ 3] THEN #3=4\nX#3\n"
            "IF [#1 EQ 2] AND [#2 EQ 5] GOTO 9\nX1\nN9 Y7\n")
    assert _ends(text) == [[4.0, 0.0, 0.0], [4.0, 7.0, 0.0]]
    with pytest.raises(GCodeError, match=r"two comparisons in one bracket \('EQ' and 'EQ'\)") as info:
        parse_program("#1=2\n#2=5\nIF [#1 EQ 2 OR #2 EQ 5] GOTO 9\nN9 M30\n", context=FANUC)
    assert info.value.line == 3 and "[#1 EQ 1] AND [#2 EQ 2]" in str(info.value)


def test_mod_is_the_non_negative_remainder():
    """Haas "Arithmetic Operators": 27 MOD 20 = 7; -7 MOD 3 = 2 (the remainder made non-negative, as LinuxCNC's);
    7.5 MOD 2 = 1.5; MOD 0 is a division by zero."""
    assert _ends("G21 G90 G1 F100\nX[27 MOD 20] Y[-7 MOD 3] Z[7.5 MOD 2]\n", HAAS) == [[7.0, 2.0, 1.5]]
    with pytest.raises(GCodeError, match="division by zero"):
        parse_program("#1 = 5 MOD 0\n", context=FANUC)
