"""Review of session 38's ISO changes: combinations of the new features with older ones (review38).

Tools: H1 = 50 mm, H2 = 30 mm (hand-written). Every program is checked against the independent reference as well
(:func:`tests.interpolators.iso_checks.checked_iso`).
"""

from __future__ import annotations

import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso

TOOLS = {1: Tool(number=1, length=50.0), 2: Tool(number=2, length=30.0)}


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
@pytest.mark.parametrize("change", ["H2", "G43 H2"])
def test_a_length_change_under_a_g18_rotation_keeps_the_rotated_z_of_the_tool(dialect, change):
    """G43 H1 (machine Z 60, program Z 10), G18 G68 X0 Z0 R30., then "G0 X5. H2" (or "G43 H2"): the rotated Z
    the tool holds is the one under the offset it travelled, so X5 ends where "G0 X5." alone does (machine X
    5 cos 30 = 8.660, program Z 5), and the -20 change travels along the machine Z in the block (TOS = 0): Z 55 - 20
    = 35. Before: the held rotated Z was read under the new, 20 mm shorter offset, rotated into X: X 17.321, Z 30."""
    text = f"G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG18\nG68 X0 Z0 R30.\nG0 X5. {change}\nG91 Z-1.\nG90 G69\nG17\nM30\n"
    prog = checked_iso(text, MachineContext(dialect=DIALECTS[dialect], tools=TOOLS))
    assert [round(float(v), 3) for v in prog.blocks[2].target] == [8.66, 0.0, 35.0]


def test_an_h_or_d_word_alone_under_linuxcnc_is_a_noted_leniency():
    """rs274 2.9.0~pre1 refuses "H2" alone after G43 H1 ("H word with no G43 or G76 to use it") and "D2" alone ("D
    word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it"); vcnc runs the program without them
    and its note says LinuxCNC refuses them, which benchmarks/linuxcnc_diff.py counts as a noted leniency. Fanuc
    keeps the plain note (a post writes D apart). Before: the note did not say so ("vcnc only" in the diff)."""
    from benchmarks.linuxcnc_diff import NOTED

    linuxcnc = MachineContext(dialect=DIALECTS["linuxcnc"], tools=TOOLS)
    prog = checked_iso("G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nH2\nD2\nG0 X5.\nM2\n", linuxcnc)
    assert [round(float(b.target[2]), 9) for b in prog.blocks] == [0.0, 60.0, 60.0]
    for refusal in ("H word with no G43 or G76 to use it", "D word with no G41, G41.1, G42 or G96 to use it"):
        key = next(v for k, v in NOTED.items() if refusal.startswith(k))
        assert any(key in n and "LinuxCNC refuses" in n for n in prog.notes)
    fanuc = checked_iso("G21 G90 G0 X0 Y0 Z0\nD2\nG0 X5.\nM30\n", MachineContext(dialect=DIALECTS["fanuc"]))
    assert "D word without G41/G42 (ignored)" in fanuc.notes


@pytest.mark.parametrize("block", ["G15 H2", "G15 G43 H2"])
def test_g15_with_an_h_in_g43_mode_is_fanucs_polar_cancel_and_length_change(block):
    """An Okuma OSP "G15 H1" (work offset selection) is refused by name (posts38), but in G43 mode a Fanuc's "G15
    H2" is the polar cancel and an H word alone (tlen38: the length offset becomes H2's, 30, and the block under the
    modal G00 moves Z down 20, TOS = 0), and "G15 G43 H2" is plainly Fanuc's: neither names Okuma. Before: both
    were refused as Okuma OSP programs."""
    text = f"G21 G90 G0 X0 Y0 Z0\nG43 H1 Z10.\nG16\nG0 X10. Y90.\n{block}\nG0 X1. Y0\nM30\n"
    prog = checked_iso(text, MachineContext(dialect=DIALECTS["fanuc"], tools=TOOLS))
    assert [round(float(v), 6) for v in prog.blocks[-1].target] == [1.0, 0.0, 40.0]


@pytest.mark.parametrize(("mode", "h", "why"), [("G43", "H1.5", "no decimal point after H"),
                                                ("G44", "H-2", "whole number >= 0")])
def test_a_bad_h_alone_in_g43_mode_is_named_by_its_mode(mode, h, why):
    """isomisc38 refuses a non-whole or negative H of G43/G44; an H alone in G43/G44 mode (tlen38) is refused
    alike, the message naming the mode and the word once at line 3, column 1. Before: "H1.5 H1.5: the offset
    number ..." and "expected H1.5 H<n>" (the H word taken for the G code)."""
    from interpolators import parse_program
    from vcnc.errors import GCodeError

    text = f"G21 G90 G0 X0 Y0 Z0\n{mode} H1 Z10.\n{h}\nM30\n"
    with pytest.raises(GCodeError, match=rf":3:1: {mode} mode {h}: the offset number H .*{why}") as err:
        parse_program(text, context=MachineContext(dialect=DIALECTS["fanuc"], tools=TOOLS))
    assert f"{h} {h}" not in str(err.value) and f"expected {mode} mode H<n>" in str(err.value)
