"""ISO programs of the seventeenth wild round (set /tmp/isowild17): controls outside the Fanuc/Haas/LinuxCNC mainstream,
Centroid CNC12 (Intercon, MillWrite and SFP posts, Acorn router macros), Tormach PathPilot subroutines, PlanetCNC TNG
scripts, Okuma OSP user tasks and a Mach4 subroutine. The snippets are written for these tests after those programs."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")

# an Intercon (Centroid CNC12) post: "G4 P3.00 ; pause for dwell" after the tool change, a drilling cycle with P
INTERCON = ("G20 G90 G17 G40 G80\nT1 M6\nM3 S1200\nG4 P3.00 ; pause for dwell\nG0 X1. Y1. Z0.1\n"
            "G82 X1. Y1. Z-0.2 R0.1 P0.5 F10.\nG80\nM30\n")
POINT_NOTE = ("dwell P with a decimal point read in milliseconds, as {} reads P (where P is seconds, as on LinuxCNC "
              "and grbl: --dialect linuxcnc, it dwells 1000 times longer)")


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_a_dwell_p_with_a_decimal_point_read_in_milliseconds_is_noted(context):
    prog = checked_iso(INTERCON, context)
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == pytest.approx([0.003, 0.0005])
    assert POINT_NOTE.format(context.dialect.name) + " x2" in prog.notes  # the G4 and the G82


def test_the_same_dwells_read_in_seconds_where_p_is_seconds():
    prog = checked_iso(INTERCON, LINUXCNC)
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == pytest.approx([3.0, 0.5])
    assert not any("decimal point read in milliseconds" in n for n in prog.notes)


@pytest.mark.parametrize("dwell", ["G04 P500", "G04 X0.5", "#1 = 2.5\nG04 P#1"])
def test_a_dwell_p_without_a_literal_decimal_point_is_not_noted(dwell):
    prog = checked_iso(f"G21 G90\n{dwell}\nM30\n", FANUC)
    assert len([b for b in prog.blocks if b.kind == "dwell"]) == 1
    assert not any("decimal point read in milliseconds" in n for n in prog.notes)
