"""A work offset change and a tool length change within a series of canned cycles, and an H word alone in G43/G44
mode (tlen38).

The series' initial level is a level in program coordinates, as LinuxCNC keeps it (interp_cycles.cc ``cycle_il``):
a work offset (G55), a G10 rewriting the offset in force, G52/G92 and a tool length change made between the series'
blocks move it with the program zero; a tool length change not yet travelled (Fanuc TOS = 0) is taken up at the
positioning to R (FANUC 15i-MA B-63784EN, canned cycles, "Tool length compensation"). Tools: H1 = 50 mm, H2 = 30
mm; G55 = X 10, Z -100 (hand-written). Every program is checked against the independent reference as well
(:func:`tests.interpolators.iso_checks.checked_iso`).
"""

from __future__ import annotations

import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso

TOOLS = {1: Tool(number=1, length=50.0), 2: Tool(number=2, length=30.0)}


def context(dialect: str) -> MachineContext:
    return MachineContext(dialect=DIALECTS[dialect], tools=TOOLS, work_offsets={"G55": (10.0, 0.0, -100.0)})


def z_rows(text: str, dialect: str) -> list[tuple[int, str, float]]:
    """(line, kind, machine Z [mm]) of each block, checked against the reference."""
    return [(b.line, b.kind, round(float(b.target[2]), 9)) for b in checked_iso(text, context(dialect)).blocks]


def test_linuxcnc_g98_after_g55_within_the_series_returns_to_the_program_level():
    """rs274 (2.9), "G0 Z10. / G98 G81 X0 Y0 Z-5. R2. F100. / G55 X5." with G55's Z offset -100: the hole at X5
    returns to program Z 10 in G55, machine -90 (its canonical STRAIGHT_TRAVERSE(5, 0, 10) after
    SET_G5X_OFFSET(2, 10, 0, -100)). Before: back to machine 10, the initial level kept as a machine Z."""
    text = "G21 G90 G0 X0 Y0 Z0\nG0 Z10.\nG98 G81 X0 Y0 Z-5. R2. F100.\nG55 X5.\nG80\nM2\n"
    assert z_rows(text, "linuxcnc")[-4:] == [(4, "rapid", 10.0), (4, "rapid", -98.0), (4, "line", -105.0),
                                             (4, "rapid", -90.0)]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_g55_and_g43_in_one_hole_block_return_to_the_level_in_g55(dialect):
    """G43 H2 G55 in the second block of a G98 series: R 2 and bottom -5 in G55 with H2 (-68, -75), and the return
    to the initial level, program Z 10 + the -20 length change taken up at R, in G55: -60; a G91 G0 Z-1. then ends
    at -61, nothing left to travel. Before: the return went to machine 60, 120 mm above."""
    text = ("G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG98 G81 X0 Y0 Z-5. R2. F100.\nG43 H2 G55 X5.\nG80\nG91 G0 Z-1.\n"
            "M30\n")
    assert z_rows(text, dialect)[-5:] == [(4, "rapid", 60.0), (4, "rapid", -68.0), (4, "line", -75.0),
                                          (4, "rapid", -60.0), (6, "rapid", -61.0)]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_g10_g52_and_g49_within_a_g91_series_move_its_initial_level(dialect):
    """A G91 G98 series from the initial level 60 (R-3. Z-5.): G10 L2 P1 Z-20. rewrites the G54 in force (initial 40:
    R 37, bottom 32, back to 40); G52 Z5. and G49 (-50, taken up at R) put it at -5: R -8, bottom -13, back to -5;
    the G0 Z-1. after G80 ends at -6. Before: the holes after the G10 drilled at R 57 (the level kept at machine
    60)."""
    text = ("G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG91 G98 G81 X0 Y0 Z-5. R-3. F100.\nG10 L2 P1 Z-20.\nX5.\nG52 Z5.\n"
            "G49 X5.\nG80\nG0 Z-1.\nM30\n")
    assert z_rows(text, dialect)[-9:] == [(5, "rapid", 60.0), (5, "rapid", 37.0), (5, "line", 32.0),
                                          (5, "rapid", 40.0), (7, "rapid", 40.0), (7, "rapid", -8.0),
                                          (7, "line", -13.0), (7, "rapid", -5.0), (9, "rapid", -6.0)]
