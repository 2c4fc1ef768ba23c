"""Tool length compensation by an axis movement (Fanuc parameter TOS = 0; Haas, Fadal): the change of the offset is
added to an incremental Z travel, where LinuxCNC shifts the program's coordinates.

FANUC Series 30i/31i/32i-MODEL A connection manual (function) B-63943EN-1/02, 12.5.2 "Tool Length Compensation
Shift Types": parameter TOS (No. 5006#6) chooses between compensation by an axis movement (0, the default) and by a
shift of the coordinate system (1, under which "If no move command is specified together with the G43, G44, or G49
command, the tool will not move along the axis"). LinuxCNC g-code.adoc "G43": "The next time a compensated axis is
moved, that axis's endpoint is the compensated location". Every program here is checked against the independent
reference too (:func:`tests.interpolators.iso_checks.checked_iso`).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso

TOOLS = {1: Tool(number=1, length=50.0), 2: Tool(number=2, length=30.0)}


def context(dialect: str) -> MachineContext:
    return MachineContext(dialect=DIALECTS[dialect], tools=TOOLS)


def ends(text: str, dialect: str) -> list[float]:
    """Machine Z [mm] at the end of each block."""
    return [round(float(b.target[2]), 9) for b in checked_iso(text, context(dialect)).blocks]


# FreeCAD's 2026 Fanuc post (fcpost36): "G91 G0 G43 G54 Z-[#[2000+#4120]] H#4120", written with the number
FREECAD = "G21 G90 G0 X0 Y0 Z0\nG91 G0 G43 G54 Z-50. H1\nG90 G0 Z10.\nM30\n"


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "fadal"])
def test_g91_z_with_g43_travels_the_offset_too(dialect):
    """12.5.2 (TOS = 0): G43 H1 (50 mm) with G91 Z-50. leaves the machine where it was; G90 Z10. is 10 + 50."""
    assert ends(FREECAD, dialect) == [0.0, 0.0, 60.0]


def test_linuxcnc_moves_by_the_increment_alone():
    """g-code.adoc "G43": the offset shifts the coordinates, the G91 Z-50. moves 50 mm down."""
    assert ends(FREECAD, "linuxcnc") == [0.0, -50.0, 60.0]


def test_grbl_moves_by_the_increment_alone():
    """grbl G43.1 (LinuxCNC's rule): the dynamic offset shifts the coordinates."""
    assert ends("G21 G90 G0 X0 Y0 Z0\nG43.1 Z50.\nG91 G0 Z-50.\nG90 G0 Z10.\nM30\n", "grbl") == [0.0, -50.0, 60.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "fadal"])
def test_g90_ends_at_the_same_point_either_way(dialect):
    """Under G90 the end point is the programmed Z plus the new offset under both rules."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z5.\nG0 Z-5.\nM30\n"
    assert ends(text, dialect) == ends(text, "linuxcnc") == [0.0, 55.0, 45.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "fadal"])
def test_g49_and_a_new_h_under_g91(dialect):
    """G49 under G91 travels minus the offset; H2 under G43 H1 travels the change 30 - 50."""
    text = ("G21 G90 G0 X0 Y0 Z100.\nG43 H1 Z10.\nG91 G43 H2 Z0.\nG49 Z0.\nG90 G0 Z100.\nM30\n")
    assert ends(text, dialect) == [100.0, 60.0, 40.0, 10.0, 100.0]
    assert ends(text, "linuxcnc") == [100.0, 60.0, 60.0, 60.0, 100.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_g43_block_without_z_moves_z_in_that_block(dialect):
    """G43 H1 alone moves Z by +50 in its own block (TOS = 0; tos37, test_iso_tos37.py), an X move keeps that Z,
    then G91 Z-50. takes it back: the machine ends where it started in Z."""
    text = "G21 G90 G0 X0 Y0 Z0\nG91 G43 H1\nG0 X10.\nG0 Z-50.\nG90 X0\nM30\n"
    prog = checked_iso(text, context(dialect))
    assert [round(float(b.target[2]), 9) for b in prog.blocks] == [0.0, 50.0, 50.0, 0.0, 0.0]
    assert np.allclose(prog.blocks[-1].target, [0.0, 0.0, 0.0])


def test_a_g91_arc_with_z_travels_the_change():
    """A helix under G91 after G43 H1 (Fanuc): the Z of the helix ends 50 mm above the increment's end."""
    text = "G21 G90 G0 X10. Y0 Z0\nG91 G43 H1\nG17 G3 X-20. Y0 Z-50. R10. F100.\nM30\n"
    blocks = checked_iso(text, context("fanuc")).blocks
    assert np.allclose(blocks[-1].target, [-10.0, 0.0, 0.0])


def test_the_dialect_property():
    assert [name for name, d in DIALECTS.items() if d.length_offset_motion] == ["fanuc", "haas", "fadal"]
    assert not dataclasses.replace(DIALECTS["fanuc"], name="x", length_offset_motion=False).length_offset_motion


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_reference_return_takes_the_length_change_up(dialect):
    """G49 alone, then G91 G28 Z0 (the Fanuc post's end of a tool) and a G91 Z move: at its reference Z has travelled
    the change (12.5.2, TOS = 0: the G49 block moved it already), so the next incremental Z moves by its word alone.
    Before the fix the -50 mm change waited for that Z-5. and ended 50 mm low."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG49\nG91 G28 Z0\nG91 G0 Z-5.\nM30\n"
    z = ends(text, dialect)
    assert z[-1] == pytest.approx(-5.0)  # the home is at the origin: Z-5. from it


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_incremental_intermediate_point_of_g28_travels_the_change(dialect):
    """G49 alone moves Z by -50 at once on the control (TOS = 0); G91 G28 Z20. goes through 20 above that, then home."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z100.\nG49\nG91 G28 Z20.\nM30\n"
    z = ends(text, dialect)
    assert z[-2:] == pytest.approx([150.0 - 50.0 + 20.0, 0.0])


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_machine_coordinate_z_takes_the_length_change_up(dialect):
    """G49 alone, G53 G0 Z0 (the machine's Z zero, which no offset shifts), then G91 Z-5.: 5 below machine zero."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG49\nG53 G0 Z0\nG91 G0 Z-5.\nM30\n"
    assert ends(text, dialect)[-1] == pytest.approx(-5.0)
