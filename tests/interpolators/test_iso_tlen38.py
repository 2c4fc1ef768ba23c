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

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

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


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_h_word_alone_in_g43_mode_changes_the_offset(dialect):
    """G43 H1 (machine Z 60 at program 10), then "H2" alone under the modal G01: the offset becomes H2's, 30, and
    the block feeds Z by the -20 change (as "G43 H2" would, TOS = 0); "H0 X12." cancels it, Z by -30 with the X
    move. Before: the H words were ignored ("H word without G43"), Z stayed at 60."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG1 X5. F100.\nH2\nX10.\nH0 X12.\nG0 Z5.\nM30\n"
    assert z_rows(text, dialect)[2:] == [(3, "line", 60.0), (4, "line", 40.0), (5, "line", 40.0), (6, "line", 10.0),
                                         (7, "rapid", 5.0)]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_h_word_alone_keeps_the_g44_direction_and_is_ignored_after_g49(dialect):
    """G44 H1 Z10. puts Z at 10 - 50 = -40; "G91 H2" makes the offset -30 (Z +20 in its G00 block: -20); after G49
    (Z +30) an H2 alone changes nothing. Before: Z stayed at -40 until the G49, which then moved +50."""
    text = "G21 G90 G0 X0 Y0 Z0\nG44 H1 Z10.\nG91 H2\nG0 Z-1.\nG49\nH2\nG0 X3.\nG90 G0 Z5.\nM30\n"
    assert z_rows(text, dialect)[1:] == [(2, "rapid", -40.0), (3, "rapid", -20.0), (4, "rapid", -21.0),
                                         (5, "rapid", 9.0), (7, "rapid", 9.0), (8, "rapid", 5.0)]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_h_word_alone_in_a_hole_block_is_taken_up_at_r(dialect):
    """"H2 X5." in a G98 G81 series (H1 before): the hole's R positioning takes the -20 change, R 2 + 30 = 32, bottom
    25, back to the initial level 60 - 20 = 40. Before: drilled with H1, R 52, back to 60."""
    text = "G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG98 G81 X0 Y0 Z-5. R2. F100.\nH2 X5.\nG80\nG91 G0 Z-1.\nM30\n"
    assert z_rows(text, dialect)[-5:] == [(4, "rapid", 60.0), (4, "rapid", 32.0), (4, "line", 25.0),
                                          (4, "rapid", 40.0), (6, "rapid", 39.0)]


def test_an_h_word_alone_under_linuxcnc_stays_ignored():
    """LinuxCNC reads H with G43 only: "H2" alone is noted and moves nothing (the offset stays H1's)."""
    prog = checked_iso("G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nH2\nG0 X5.\nM2\n", context("linuxcnc"))
    assert [round(float(b.target[2]), 9) for b in prog.blocks] == [0.0, 60.0, 60.0]
    assert any("H word without G43" in n for n in prog.notes)


def _fanuc(text: str):
    return checked_iso(text, MachineContext(dialect=DIALECTS["fanuc"]))


def test_fanuc_an_s_word_between_m29_and_its_tap_is_refused():
    """Fanuc alarm 0203 "PROGRAM MISS AT RIGID TAPPING" ("position for a rigid M code (M29) or an S command is
    incorrect"): "M29 S500 / S600 / G84 .." names line 3 and the S word. Before: the tap ran at S600."""
    text = "G21 G90 G0 X0 Y0 Z10.\nM29 S500\nS600\nG84 Z-5. R2. F1.\nG80\nM30\n"
    with pytest.raises(GCodeError, match=r":3:1: S word after M29 \(line 2\).*alarm 0203") as err:
        parse_program(text, context=MachineContext(dialect=DIALECTS["fanuc"]))
    assert "expected the tap's speed in the M29 block" in str(err.value)


def test_fanuc_m29_while_a_tapping_cycle_is_in_force_is_refused():
    """Alarm 0203 (the M29 after its tapping command): a floating G84 series, then "M29 S500" with no motion code,
    is refused at the M29 (line 4, column 1); so is "X5. M29" in a rigid series (line 4, column 5). Before: both
    ran, the M29 arming the taps that followed."""
    floating = "G21 G90 G0 X0 Y0 Z10.\nS500 M03\nG84 Z-5. R2. F500.\nM29 S500\nX5.\nG80\nM30\n"
    rigid = "G21 G90 G0 X0 Y0 Z10.\nM29 S500\nG84 Z-5. R2. F500.\nX5. M29\nG80\nM30\n"
    for text, at in ((floating, ":4:1:"), (rigid, ":4:5:")):
        with pytest.raises(GCodeError, match=at + r" M29 while the G84 tapping cycle is in force.*alarm 0203"):
            parse_program(text, context=MachineContext(dialect=DIALECTS["fanuc"]))


def test_fanuc_m29_taps_an_s_in_the_tap_block_and_m29_in_a_block_that_names_the_cycle():
    """Our reading of 0203's positions: "M29 / G84 .. S700" taps at S700, and "G80 M29 S500" after a floating series
    arms the next G84 (G80 ends the series first); G74 is armed as G84 is. Each runs as the reference does."""
    for text in ("G21 G90 G0 X0 Y0 Z10.\nM29\nG84 Z-5. R2. F500. S700\nX5.\nG80\nM30\n",
                 "G21 G90 G0 X0 Y0 Z10.\nS500 M03\nG84 Z-5. R2. F500.\nG80 M29 S500\nG84 Z-5. R2. F500.\nG80\nM30\n",
                 "G21 G90 G0 X0 Y0 Z10.\nM29 S500\nG74 Z-5. R2. F500.\nX5.\nG80\nM30\n"):
        prog = _fanuc(text)
        assert [round(float(b.target[2]), 9) for b in prog.blocks if b.kind == "line"][:2] == [-5.0, 2.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_an_incremental_x_under_a_g18_rotation_moves_z_too(dialect):
    """G18 G68 X0 Z0 R30.: a "G91 G0 X2." is the vector 2 along the rotated X, (2 cos 30, -2 sin 30) in X Z: Z goes
    from 10 to 9. Before: Z stayed at 10 (the reader moved Z only for a Z word, as under LinuxCNC's G10 R about Z)."""
    text = "G21 G90 G0 X0 Y0 Z10.\nG18\nG68 X0 Z0 R30.\nG91 G0 X2.\nG90 X5.\nG69\nG17\nM30\n"
    prog = checked_iso(text, context(dialect))
    assert [round(float(v), 6) for v in prog.blocks[1].target] == [1.732051, 0.0, 9.0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_pending_length_change_under_a_g18_rotation_travels_along_machine_z(dialect):
    """H1 (machine Z 60), G49 left to travel (an arc block before it), then G18 G68 R30. and "G91 G0 Z-1.": the
    rotated Z-1 is (-0.5, -0.866) in X Z, and the -50 of the length change goes along the machine Z, the tool's
    axis, unrotated: X -0.5, Z 60 - 0.866 - 50 = 9.134. Before: X 0 (the rotated step's X part dropped)."""
    text = ("G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG2 X0 Y0 I1. F100.\nG91 G49\nG90 G18\nG68 X0 Z0 R30.\n"
            "G91 G0 Z-1.\nG90 X5.\nG69\nG17\nM30\n")
    prog = checked_iso(text, context(dialect))
    assert [round(float(v), 6) for v in prog.blocks[3].target] == [-0.5, 0.0, 9.133975]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_pending_length_change_in_a_cycle_under_g51_scaling_is_not_scaled(dialect):
    """G51 X0 Y0 Z0 P2. with H1 (machine Z 60, program 30 scaled), G49 left to travel, then a G98 G81 R2. Z-5.: the
    R positioning takes up the -50 unscaled (tool compensation applies after the program's transformations: FANUC
    15i-MA B-63324EN/03, coordinate system rotation, "Tool compensation"), R at 2 x 2 = 4, bottom -10, and the G98
    return to the tool's level under the new offset, machine 10. The reference added the -50 to the scaled program
    level (a return to R at 4)."""
    text = ("G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG51 X0 Y0 Z0 P2.\nG2 X0 Y0 I1. F100.\nG49\n"
            "G98 G81 X5. Y0 Z-5. R2. F100.\nX8.\nG80\nG50\nM30\n")
    assert z_rows(text, dialect)[-8:] == [(6, "rapid", 60.0), (6, "rapid", 4.0), (6, "line", -10.0),
                                          (6, "rapid", 10.0), (7, "rapid", 10.0), (7, "rapid", 4.0),
                                          (7, "line", -10.0), (7, "rapid", 10.0)]
