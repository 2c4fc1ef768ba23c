"""A G93 arc run as chords because a rotation turns its plane out of the axis planes (``iso_arcs.rotated_arc_chords``)
takes the time the same arc takes unrotated: under Fanuc |sweep|/F minutes (FANUC B-62764EN, "Inverse time feed
(G93)": "FRN = feedrate / arc radius"), under LinuxCNC and Haas 1/F minutes (g-code.adoc, G93). Hand-written
programs: a half circle of radius 10 mm in G18, F1, in a system G68 turns 30 deg about Z (Haas) or G10 L2 R30 turns
(LinuxCNC). Under Fanuc such an arc is alarm 144 (isoleft39, :func:`interpolators.iso_arcs.rotation_plane_alarm`), so
the plain arc alone carries its rule."""

import math

import pytest

from interpolators.context import DIALECTS, MachineContext
from interpolators.parse import parse_program
from vcnc.errors import GCodeError


def _feed_time(text: str, dialect: str) -> float:
    """The time [s] of the program's feed moves at their programmed feeds."""
    program = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    return sum(b.segment.length / b.feed for b in program.blocks if b.kind in ("line", "arc"))


@pytest.mark.parametrize("dialect, minutes", [("fanuc", math.pi), ("haas", 1.0), ("linuxcnc", 1.0)])
def test_rotated_g93_arc_takes_the_unrotated_arcs_time(dialect, minutes):
    plain = "G21 G90 G94 G0 X0 Y0 Z0\nG18 G93 G2 X20. Z0. I10. K0. F1.\nM30\n"
    turn = "G17 G68 X0. Y0. R30.\n" if dialect != "linuxcnc" else "G10 L2 P1 R30\nG54\n"
    rotated = f"G21 G90 G94 G0 X0 Y0 Z0\n{turn}G18 G93 G2 X20. Z0. I10. K0. F1.\nM30\n"
    assert _feed_time(plain, dialect) == pytest.approx(60.0 * minutes, rel=1e-9)
    if dialect == "fanuc":  # B-63503EN-1/01 alarm 144: the rotation plane and the arc plane must be the same
        with pytest.raises(GCodeError, match="alarm 144"):
            _feed_time(rotated, dialect)
        return
    # chords: their length a little under the arc's, each at the arc's feed
    assert _feed_time(rotated, dialect) == pytest.approx(60.0 * minutes, rel=1e-3)
