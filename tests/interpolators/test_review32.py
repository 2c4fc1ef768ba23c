"""Session 32 review: defects found in the day's changes, each with the program that showed it."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

LINUXCNC = MachineContext().with_dialect("linuxcnc")


@pytest.mark.parametrize("line, kinds", [("G40 G8 G64 P0.01", ["rapid"]), ("G8 G4 P0.5", ["dwell", "rapid"])])
def test_g8_beside_a_code_that_takes_p_is_the_lathe_radius_mode(line, kinds):
    # LinuxCNC g-code.adoc "Modal Groups": G8 (group 15) takes no P, the block's G64 or G4 owns it; review32: the P
    # made G8 Fanuc's G08 P1 look-ahead and the block was refused naming --dialect fanuc
    prog = checked_iso(f"G21 G90\n{line}\nG0 X5\nM2\n", LINUXCNC)
    assert [b.kind for b in prog.blocks] == kinds
    assert prog.blocks[-1].target[0] == 5.0
    assert any(n.startswith("G8 lathe radius mode") for n in prog.notes)


def test_g8_with_a_p_of_its_own_is_still_named_as_fanucs_look_ahead():
    with pytest.raises(GCodeError, match=r":2:1: G8 lathe radius mode: not supported \(G08 P1 / P0 with a P is "
                                         r"Fanuc's AI advanced preview control"):
        parse_program("G21\nG08 P1\nG0 X1\nM2\n", context=LINUXCNC)
