"""Defects found in the review of session 25's work (tool centre point control, the ISO and TNC wild sets),
each with a hand-written program that failed before its fix."""

from __future__ import annotations

import pytest

from interpolators.tilted import Solution
from tests.interpolators.test_tcp5x import BC, distance_to_line, machine, tips, tnc


def test_m129_ends_m128_at_the_end_of_its_block():
    # TNC 426/430 ISO manual, M128: "M128 becomes effective at the start of block, M129 at the end of block":
    # 'L X+40 B+30 C+20 F600 M129' is still a line of the tip on the turned part, the next line a machine line
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 B+30 C+20 F600 M129\n6 L X+50")
    rows = [i for i, b in enumerate(prog.blocks) if b.number == 5]
    end = machine(BC, [50.0, 5.0, 0.0], Solution(30.0, 20.0))
    assert len(rows) > 1 and prog.blocks[rows[-1]].target == pytest.approx(end, abs=1e-9)
    assert distance_to_line(tips(prog, BC, rows), [20.0, 5.0, 0.0], [50.0, 5.0, 0.0]).max() <= 0.01 * 1.001
    # after M129 X+50 is the machine's X (preset 10 + 50), Z where the table left the tip
    assert prog.blocks[-1].target == pytest.approx([60.0, end[1], end[2]], abs=1e-9)
    assert prog.blocks[-1].extra_target[1:3] == pytest.approx([30.0, 20.0])
