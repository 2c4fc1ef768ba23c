"""ISO programs of the fifth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


@pytest.mark.parametrize("name", ["linuxcnc", "grbl", "fanuc", "haas"])
@pytest.mark.parametrize("m", [3, 4])
def test_snapmaker_spindle_power_word_is_named(name, m):
    # Snapmaker Luban writes "M3 P100" (Snapmaker gcode_reference.md: "M3 [P] | 50< percentage <=100"); none
    # of these controls reads P with M3, and the message says what the P meant there
    with pytest.raises(GCodeError, match=rf":2:4: M{m} P: spindle power in percent \(Snapmaker 2.0 firmware\).*"
                                         rf"\(got 'P100'\); expected M{m} S<rpm>"):
        parse_program(f"G21 G90\nM{m} P100\nG0 X1\n", context=_in_dialect(name))


def test_a_p_word_without_a_spindle_code_keeps_its_message():
    with pytest.raises(GCodeError, match=r"word P needs G04 \(dwell\)"):
        parse_program("G21 G90\nG0 X1 P100\n", context=_in_dialect("linuxcnc"))
