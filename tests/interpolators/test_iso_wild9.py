"""ISO programs of the ninth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


def _xy(prog) -> list[list[float]]:
    return [b.target[:2].tolist() for b in prog.blocks]


def test_m98_q_without_p_calls_a_block_of_the_same_program():
    # a Doosan (Fanuc 0i-MD) shop program: the pattern after M30 starts at N3021 and ends with M99; each
    # 'M98 Q3021' runs it under a new G52 shift, as Haas M97 P3021 would, and comes back after the call
    text = ("%\nO0033\nG21 G90 G54 G0 X0 Y0 Z10\nG52 X0 Y0\nM98 Q3021\nG52 X20 Y0\nM98 Q3021 L2\nG52 X0 Y0\n"
            "G0 X-5 Y-5\nM30\nN3021 (PATTERN)\nG0 X1 Y1\nG1 Z-1 F100\nG0 Z10\nM99\n%\n")
    prog = parse_program(text, context=_in_dialect("fanuc"))
    corners = [xy for xy in _xy(prog) if xy[1] == 51.0]
    assert corners == [[101.0, 51.0]] * 3 + [[121.0, 51.0]] * 6
    assert _xy(prog)[-1] == [95.0, 45.0]
    assert any("M98 Q without P" in n for n in prog.notes)


def test_m98_q_without_p_names_a_missing_block():
    with pytest.raises(GCodeError, match=r":2:1: M98 Q subprogram call \(no P: this program\): no block N77 in "
                                         r"this program.*expected M98 Q<n> with a block N<n> in the same program"):
        parse_program("G21 G90 G0 X0 Y0\nM98 Q77\nM30\n", context=_in_dialect("fanuc"))
