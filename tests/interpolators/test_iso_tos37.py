"""Tool length compensation by an axis movement (Fanuc parameter TOS = 0) in a block without a Z word, TOS as a
machine setting, and G44 in the independent reference.

FANUC Series 30i/31i/32i-MODEL A connection manual (function) B-63943EN-1/02, 12.5.2 "Tool Length Compensation
Shift Types": under TOS = 1 (No. 5006#6, shift of the coordinate system) "if no move command is specified together
with the G43, G44, or G49 command, the tool will not move along the axis" -- the mark of that type, so under TOS = 0
(the default, compensation by an axis movement) such a block moves the tool by the change of the offset vector;
"Offset direction": G43 shifts to the + side, G44 to the - side. The Allen-Bradley 8520 9/Series mill manual
(chapter 20 "Tool Control Functions", Example 20.2) asks the block that starts or cancels an offset, "N2 G43 H01;",
"N8 G49;", to be a linear block (G00 or G01). Every program here is checked against the independent reference too
(:func:`tests.interpolators.iso_checks.checked_iso`), which models G44 since this session.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.commands.machines import PROGRAM_TABLE_DOC
from vcnc.core.errors import MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine

TOOLS = {1: Tool(number=1, length=50.0), 2: Tool(number=2, length=30.0)}
MOVING = ["fanuc", "haas", "fadal"]


def context(dialect: str, **changes) -> MachineContext:
    return MachineContext(dialect=dataclasses.replace(DIALECTS[dialect], **changes), tools=TOOLS)


def rows(text: str, ctx: MachineContext) -> list[tuple[int, str, list[float]]]:
    """(line, kind, machine end point [mm]) of each block, checked against the reference."""
    return [(b.line, b.kind, [round(float(v), 9) for v in b.target]) for b in checked_iso(text, ctx).blocks]


@pytest.mark.parametrize("dialect", MOVING)
@pytest.mark.parametrize("distance", ["G90", "G91"])
def test_a_g43_block_alone_moves_z_by_the_offset(dialect, distance):
    """12.5.2, TOS = 0: "G43 H1" alone is a rapid (the modal G00) of Z by +50 in its own block, under G90 and G91;
    the next block keeps that Z. Before: no block at line 2, Z stayed at 0 until the next Z word."""
    text = f"G21 G90 G0 X0 Y0 Z0\n{distance} G43 H1\nG0 X10.\nM30\n"
    assert rows(text, context(dialect)) == [(1, "rapid", [0.0, 0.0, 0.0]), (2, "rapid", [0.0, 0.0, 50.0]),
                                            (3, "rapid", [10.0, 0.0, 50.0])]


@pytest.mark.parametrize("dialect", MOVING)
def test_a_g43_block_with_x_and_y_only_moves_z_too(dialect):
    """12.5.2, TOS = 0: "G43 H1 X5. Y5." ends 50 above where it started in Z (before: Z 0 until a later Z word)."""
    text = "G21 G90 G0 X0 Y0 Z10.\nG43 H1 X5. Y5.\nG0 Z20.\nM30\n"
    assert rows(text, context(dialect)) == [(1, "rapid", [0.0, 0.0, 10.0]), (2, "rapid", [5.0, 5.0, 60.0]),
                                            (3, "rapid", [5.0, 5.0, 70.0])]


@pytest.mark.parametrize("dialect", MOVING)
def test_g49_alone_under_g01_feeds_z_back_by_the_offset(dialect):
    """12.5.2, TOS = 0: "G49" alone under the modal G01 is a feed move of Z by -50 at the modal F; the incremental Z
    after it moves by its word alone. Before: no block at line 3, and the G91 Z5. ended 45 mm lower (5 - 50)."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 G1 Z10. F200.\nG49\nG91 Z5.\nM30\n"
    prog = checked_iso(text, context(dialect))
    assert [(b.line, b.kind, round(float(b.target[2]), 9)) for b in prog.blocks] == [
        (1, "rapid", 0.0), (2, "line", 60.0), (3, "line", 10.0), (4, "line", 15.0)]
    assert prog.blocks[2].feed == pytest.approx(200.0 / 60.0)  # [mm/s]: the modal F200.


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
@pytest.mark.parametrize("g53", ["G53 G49 M05", "G49 G53 G0 X5. Y5."])
def test_g49_in_a_g53_block_cancels_the_vector_without_moving_z(dialect, g53):
    """Fanuc 0i-MB B-63844EN/02 14.1.2, "G49G53P_;": the length vector is cancelled with the block's movement, not
    travelled: a Fanuc post's "G53 G49 M05" leaves Z where it is, and the G91 Z-5. after it moves 5 alone. Before:
    the -50 mm change waited for that Z-5. and ended 50 mm low (Z 5)."""
    text = f"G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\n{g53}\nG91 G0 Z-5.\nM30\n"
    assert [r[2][2] for r in rows(text, context(dialect))][-2:] == [60.0, 55.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_g44_subtracts_and_moves_the_same_way(dialect):
    """12.5.2 "Offset direction": G44 H1 shifts to the - side: "G44 H1" alone rapids Z by -50, a G90 Z10. then ends
    at 10 - 50. Before: the reference refused G44 ("G44 tool length mode")."""
    text = "G21 G90 G0 X0 Y0 Z0\nG44 H1\nG90 Z10.\nG43 H2 Z10.\nM30\n"
    assert [r[2][2] for r in rows(text, context(dialect))] == [0.0, -50.0, -40.0, 40.0]


def test_g44_under_a_coordinate_shift():
    """LinuxCNC's rule (TOS = 1): G44 H1 moves nothing; the next Z word ends at its value minus the offset."""
    text = "G21 G90 G0 X0 Y0 Z0\nG44 H1\nG0 Z10.\nM30\n"
    assert [r[2][2] for r in rows(text, context("fanuc", length_offset_motion=False))] == [0.0, -40.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_arc_mode_leaves_the_change_to_the_next_z_word(dialect):
    """A G43 H1 block under the modal G02 moves nothing (a linear block takes the change, 8520 Example 20.2): the
    G91 Z-5. after it travels the change too."""
    text = "G21 G90 G0 X0 Y0 Z0\nG2 X10. R5. F100.\nG43 H1\nG91 G0 Z-5.\nM30\n"
    assert [r[2][2] for r in rows(text, context(dialect))] == [0.0, 0.0, 45.0]


def test_tos_1_is_the_coordinate_shift():
    """length_offset_motion=False (Fanuc TOS = 1): "G43 H1" alone moves nothing and "G91 G0 G43 Z-50. H1" moves the
    50 mm of its word, as LinuxCNC does (12.5.2: "the coordinate system will be shifted first, then the tool will
    move along the axis")."""
    ctx = context("fanuc", length_offset_motion=False)
    assert [r[2][2] for r in rows("G21 G90 G0 X0 Y0 Z0\nG43 H1\nG0 X10.\nM30\n", ctx)] == [0.0, 0.0]
    freecad = "G21 G90 G0 X0 Y0 Z0\nG91 G0 G43 G54 Z-50. H1\nG90 G0 Z10.\nM30\n"
    assert [r[2][2] for r in rows(freecad, ctx)] == [0.0, -50.0, 60.0]


def test_the_machine_file_sets_tos(tmp_path):
    """``[program] length_offset_motion``: false on a fanuc machine is TOS = 1; --dialect keeps a value that differs
    from the machine dialect's default, and takes the new dialect's otherwise."""
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndialect = "fanuc"\n'
                    'length_offset_motion = false\n')
    ctx = load_machine(str(path)).context
    assert ctx.dialect.length_offset_motion is False
    assert ctx.with_dialect("haas").dialect.length_offset_motion is False
    plain = tmp_path / "p.toml"
    plain.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndialect = "linuxcnc"\n')
    assert load_machine(str(plain)).context.with_dialect("fanuc").dialect.length_offset_motion is True
    assert "length_offset_motion" in PROGRAM_TABLE_DOC


@pytest.mark.parametrize("value", ['"TOS=1"', "0", '"yes"'])
def test_a_bad_tos_value_names_the_key_and_the_file(tmp_path, value):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + f"\n[program]\nlength_offset_motion = {value}\n")
    with pytest.raises(MachineError, match=r"'program.length_offset_motion' must be true .* or false") as err:
        load_machine(str(path))
    assert "m.toml" in str(err.value)


def test_a_linuxcnc_machine_with_tos_0_moves_like_fanuc():
    """The setting is the machine's, whatever the dialect: a linuxcnc context with it moves Z in "G43 H1"."""
    ctx = context("linuxcnc", length_offset_motion=True)
    assert np.allclose(checked_iso("G21 G90 G0 X0 Y0 Z0\nG43 H1\nM30\n", ctx).blocks[-1].target, [0.0, 0.0, 50.0])


# FANUC Series 0i-MB operator's manual B-63844EN/02, 14.1.2 "G53, G28, and G30 Commands in Tool Length Offset Mode":
# the vector of the tool length offset axis is "canceled upon movement to a reference position being performed"
# (G53: "upon movement being performed according to a specified value"), "the previously specified modal G code
# remains displayed", and restored afterwards.
FUSION_END = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG28 G91 Z0\nG90\nG49\nG28 G91 X0 Y0\nM30\n"


@pytest.mark.parametrize("dialect", MOVING)
def test_g49_after_a_reference_return_moves_nothing(dialect):
    """Fusion 360's Fanuc post ends "G28 G91 Z0 / G90 / G49": the vector is cancelled at the reference already, so the
    G49 moves nothing and Z stays home (a guard: moving Z in a G49 block must not plunge the tool 50 mm here)."""
    assert [r[2][2] for r in rows(FUSION_END, context(dialect))] == [0.0, 60.0, 60.0, 0.0, 0.0, 0.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
@pytest.mark.parametrize("to_z", ["G91 G28 Z0", "G90 G53 G0 Z0"])
def test_the_next_incremental_z_restores_the_vector(dialect, to_z):
    """14.1.2: after G28 Z (or G53 Z) under G43 H1 the vector is restored by the next Z move: G91 Z-5. ends at the
    reference + 50 - 5. Before: the reference return took the offset up for good, Z ended at -5."""
    text = f"G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\n{to_z}\nG91 G0 Z-5.\nM30\n"
    assert rows(text, context(dialect))[-1][2][2] == pytest.approx(45.0)


def test_an_absolute_z_after_the_reference_return_is_unchanged():
    """Under G90 the restored vector is in the end point already: G43 H1, G91 G28 Z0, G90 Z10. ends at 10 + 50."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG91 G28 Z0\nG90 G0 Z10.\nM30\n"
    assert rows(text, context("fanuc"))[-1][2][2] == pytest.approx(60.0)


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_g29_brings_the_vector_back_once(dialect):
    """G29 Z through the G28 intermediate point (a program point, the offset in it): after it a G91 Z-5. moves 5
    alone (the restored vector is not travelled twice)."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG91 G28 Z0\nG90 G29 Z20.\nG91 G0 Z-5.\nM30\n"
    assert [r[2][2] for r in rows(text, context(dialect))][-2:] == [70.0, 65.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_incremental_g60_z_travels_the_change(dialect):
    """G60 single-direction positioning (a rapid here) under G91 after a reference return: its Z word travels the
    restored vector as any incremental Z (14.1.2)."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG91 G28 Z0\nG91 G60 Z-5.\nG0 Z-5.\nM30\n"
    assert [r[2][2] for r in rows(text, context(dialect))][-2:] == [45.0, 40.0]
