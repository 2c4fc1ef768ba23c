"""Fanuc/Haas custom macro B, session 40 (isomacro40): what the manuals say of system variables, functions and calls
that the reader read otherwise. Each input is hand-written in the style of shop macros."""

from __future__ import annotations

import dataclasses

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
    # example), to 1 in an assignment; a variable's number #[ROUND[1.4]] stays whole (#1 = 1.2345)
    assert _ends(ROUND_MM, dialect) == [[0, 0, 0], [-1.235, 0, 0], [-0.391, 1.688, 0], [1.0, 1.2345, 0]]


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
