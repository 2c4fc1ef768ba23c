"""A tool length change under a modal canned cycle (Fanuc compensation by an axis movement, TOS = 0), and G44 where
the control has none.

FANUC Series 15i/150i-MA programming manual B-63784EN, canned cycles, "Tool length compensation": "When a tool length
offset (G43, G44, or G49) is specified in the canned cycle, the offset is applied at the time of positioning to point
R." The positioning to R travels the change, so nothing of it is left for a later incremental Z (it was travelled
twice), and under G91 the R level, measured from the initial level, moves by it. Tools: H1 = 50 mm, H2 = 30 mm
(hand-written). Every program is checked against the independent reference as well
(:func:`tests.interpolators.iso_checks.checked_iso`).

G44 (the offset subtracted) is no LinuxCNC code (its G-code reference has G43, G43.1, G43.2 and G49; rs274 answers
"Unknown g code used"), nor grbl's (gnea/grbl gcode.c ``case 43: case 49:`` takes G43.1 and G49, anything else error
20; grblHAL's ``tool_offset_mode_t`` has G49, G43, G43.1, G43.2).
"""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.test_iso_tos37 import MOVING, context
from vcnc.errors import GCodeError

START = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\n"  # machine Z 60


def z_rows(text: str, dialect: str) -> list[tuple[int, str, float]]:
    """(line, kind, machine Z [mm]) of each block, checked against the reference."""
    return [(b.line, b.kind, round(float(b.target[2]), 9)) for b in checked_iso(text, context(dialect)).blocks]


@pytest.mark.parametrize("dialect", MOVING)
def test_a_change_in_a_g90_cycle_is_travelled_once(dialect):
    """G43 H2 in a G99 G81 series: the hole at X5 is drilled from R 2 + 30 = 32 to -5 + 30 = 25, and the G91 Z-1.
    after G80 ends at 31. Before: the -20 change was travelled again by that Z-1. (Z 11)."""
    text = START + "G99 G81 X0 Y0 Z-5. R2. F100.\nG43 H2 X5.\nG80\nG91 G0 Z-1.\nM30\n"
    assert z_rows(text, dialect)[-5:] == [(4, "rapid", 52.0), (4, "rapid", 32.0), (4, "line", 25.0),
                                          (4, "rapid", 32.0), (6, "rapid", 31.0)]


@pytest.mark.parametrize("dialect", MOVING)
def test_a_change_in_a_g91_cycle_moves_the_r_level(dialect):
    """Under G91 R-3. Z-5. from the initial level 60: the first hole at R 57, bottom 52; after G43 H2 the R
    positioning takes -20: R 37, bottom 32; a G0 Z-1. after G80 ends at 36. Before: the second hole at 57/52 and
    the Z-1. at 36 by travelling the change there, 21 mm below the hole's R (reference: 37/32 and Z 16)."""
    text = START + "G91 G99 G81 X0 Y0 Z-5. R-3. F100.\nG43 H2 X5.\nG80\nG0 Z-1.\nM30\n"
    assert z_rows(text, dialect)[-4:] == [(4, "rapid", 37.0), (4, "line", 32.0), (4, "rapid", 37.0),
                                          (6, "rapid", 36.0)]


@pytest.mark.parametrize("dialect", MOVING)
def test_g49_before_a_g91_cycle_is_taken_up_at_r(dialect):
    """G91 G49 in an arc's modal state (no move of its own), then a G91 G81 R-3. Z-5.: the R positioning takes
    the -50 up, R 60 - 3 - 50 = 7, bottom 2; the G0 Z-1. after G80 ends at 6. Before: R 57 and bottom 52 (50 mm off),
    the Z-1. ending at 6 by travelling the -50 there."""
    text = START + "G2 X0 Y0 I1. F100.\nG91 G49\nG99 G81 X5. Y0 Z-5. R-3. F100.\nG80\nG0 Z-1.\nM30\n"
    assert z_rows(text, dialect)[-5:] == [(5, "rapid", 60.0), (5, "rapid", 7.0), (5, "line", 2.0),
                                          (5, "rapid", 7.0), (7, "rapid", 6.0)]


@pytest.mark.parametrize("dialect", MOVING)
def test_g98_returns_to_the_initial_level_under_the_new_offset(dialect):
    """G98: the initial level is Z 10 in the work system (machine 60 with H1); after G43 H2 in the series the hole
    at X5 returns to 10 + 30 = 40, and a G91 Z-1. after G80 ends at 39. Before: back to machine 60, the Z-1. to 39
    by the pending change, where the reference returned to 40."""
    text = START + "G98 G81 X0 Y0 Z-5. R2. F100.\nG43 H2 X5.\nG80\nG91 G0 Z-1.\nM30\n"
    assert z_rows(text, dialect)[-4:] == [(4, "rapid", 32.0), (4, "line", 25.0), (4, "rapid", 40.0),
                                          (6, "rapid", 39.0)]


def test_linuxcnc_g98_after_a_g43_within_the_series_returns_to_the_program_level():
    """LinuxCNC keeps the series' initial level in program coordinates (interp_cycles.cc ``cycle_il``): after
    "G43 H2" between two G98 G81 blocks rs274 (installed; tools 1 and 2) retracts the second hole to program Z 10,
    machine 10 + 30 = 40, and the G91 Z-1. after G80 to 39. Before: the reader went back to machine 60 (the
    reference to 40)."""
    text = START + "G98 G81 X0 Y0 Z-5. R2. F100.\nG43 H2\nX5.\nG80\nG91 G0 Z-1.\nM2\n"
    assert z_rows(text, "linuxcnc")[-4:] == [(5, "rapid", 32.0), (5, "line", 25.0), (5, "rapid", 40.0),
                                             (7, "rapid", 39.0)]


def test_g44_under_linuxcnc_runs_with_the_note_that_linuxcnc_refuses_it():
    """Under linuxcnc G44 runs as Fanuc's (Z10. ends at 10 - 50, the coordinate shift) with the note that rs274
    stops there. Before: it ran without a word of it."""
    ctx = MachineContext(tools={1: Tool(number=1, length=50.0)}).with_dialect("linuxcnc")
    prog = parse_program("G21 G90 G0 X0 Y0 Z0\nG44 H1 Z10.\nM2\n", context=ctx)
    assert [float(b.target[2]) for b in prog.blocks] == [0.0, -40.0]
    assert any("G44" in n and 'LinuxCNC refuses it: "Unknown g code used"' in n for n in prog.notes)


def test_g44_under_grbl_is_refused_naming_the_line():
    """grbl 1.1 answers G44 with error 20 and grblHAL has no G44: an error at line 2, column 1. Before: it ran."""
    ctx = MachineContext(tools={1: Tool(number=1, length=50.0)}).with_dialect("grbl")
    with pytest.raises(GCodeError, match=r":2:1: G44 tool length offset subtracted: grbl has none .*error 20"):
        parse_program("G21 G90 G0 X0 Y0 Z0\nG44 H1 Z10.\nM2\n", context=ctx)
