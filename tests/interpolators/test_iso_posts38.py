"""Constructs of more CAM posts and of hand-written shop programs (Haas mill programming workbook style), read as
their controls read them (session 38, posts38).

Each program is hand-written in the output style of the post or manual named in its test; the posts were read,
not run."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import interpolate, parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
HAAS = MachineContext(dialect=DIALECTS["haas"], tools={1: Tool(number=1, length=10.0, radius=1.0)})

#: A Haas workbook-style series without G80 between a G83 with I J K (first peck, reduction, minimum) and a G76
#: fine bore with its shift Q.
HAAS_PECK_THEN_BORE = ("%\nO40005\nT1 M06\nG00 G90 G54 X1. Y1. S1500 M03\nG43 H01 Z1. M08\n"
                       "G83 G98 Z-1.5 Q0.25 I0.3 J0.05 K0.15 R0.1 F10.\nX3.\nG76 G99 Z-0.5 Q0.01 R0.1 F5.\n"
                       "X4.\nG80 G00 Z1.\nM30\n%\n")


def _shifts(prog, line):
    """The X Y offsets [mm] of a G76 block's rapids from its hole."""
    moves = [b for b in prog.blocks if b.line == line and b.kind == "rapid"]
    hole = moves[0].target
    return {(round(float(b.target[0] - hole[0]), 6), round(float(b.target[1] - hole[1]), 6)) for b in moves}


@pytest.mark.parametrize("line", [8, 9])
def test_haas_g76_shifts_by_its_q_not_by_the_i_j_of_a_g83_before_it(line):
    # Haas mill operator's manual 96-8000 (June 1999), "G76 Fine Boring" / "G77 Back Bore": "I Optional shift
    # value, if Q is not specified ... If Q is not specified, the optional I and J values are used to determine
    # the shift direction and distance" (Q along Setting 27, +X by default). Before: the G83's I0.3 J0.05 (its
    # first peck and reduction, sticky in the series) shifted the boring bar 0.3 X 0.05 Y, not Q 0.01 along +X
    prog = checked_iso(HAAS_PECK_THEN_BORE, HAAS)
    assert _shifts(prog, line) == {(0.0, 0.0), (0.01, 0.0)}


def test_haas_g76_with_i_j_and_no_q_shifts_by_i_j_for_the_series():
    # the same manual: without Q the shift is I J; a G76 block that writes I J after one that wrote Q shifts by
    # I J from there on (and the I J stay for the next holes)
    text = ("T1 M06\nG00 G90 G54 X1. Y1. S1500 M03\nG43 H01 Z1.\nG76 G99 Z-0.5 Q0.01 R0.1 F5.\n"
            "X2. I-0.02 J0.03\nX3.\nG80\nM30\n")
    prog = checked_iso(text, HAAS)
    assert _shifts(prog, 4) == {(0.0, 0.0), (0.01, 0.0)}
    assert _shifts(prog, 5) == _shifts(prog, 6) == {(0.0, 0.0), (-0.02, 0.03)}


#: Fusion's Okuma post (konkers/Mill-Post-Processors okuma.cps, "OKUMA OSP"): work offset "G15 H<n>", length
#: offset "G0 G56 Z.. H<n>", cycle return level "G71 Z..", cycles ended by M53.
OKUMA = ("%\nO1001\nG17 G90 G21\nT1 M6\nS5000 M3\nG15 H1\nG0 X10. Y10.\nG0 G56 Z15. H1\nG71 Z15.\n"
         "G81 X10. Y10. Z-5. R5. F300. M53\nG80\nM30\n%\n")


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "linuxcnc"])
def test_an_okuma_osp_program_is_refused_at_g15_h(dialect):
    # Okuma OSP programming manuals: G15 H<n> selects a work coordinate system (modal), G56 H the tool length
    # offset, G71 Z the return level. Before: under fanuc/haas "G15 H1" was Fanuc's polar cancel with an unused H
    # (noted), G56 the third work offset, "G71 Z15." metric input and a move: the program ran 10 mm low
    # (no tool length) and without its work offset, with no error
    context = MachineContext(dialect=DIALECTS[dialect], tools={1: Tool(number=1, length=10.0, radius=1.0)})
    with pytest.raises(GCodeError, match=r":6:1: G15 H1: Okuma OSP's work coordinate system selection"):
        parse_program(OKUMA, context=context)
    # G15 alone stays Fanuc's polar cancel
    assert parse_program("G21 G90\nG16\nG1 X10 Y90 F100\nG15\nG1 X0 Y0\nM30\n", context=FANUC).blocks[-1].line == 5


def test_fanuc_comma_a_angle_is_refused_naming_direct_drawing_dimensions():
    # hand-written Fanuc programs: "G1 X20. ,A30." (the line's angle, one end coordinate; FANUC "Direct drawing
    # dimension programming", an option). ,R and ,C are read (interpolators.iso_corners); before: "unknown word
    # ',A30.'" without saying what it is
    with pytest.raises(GCodeError, match=r":3:9: unknown word ',A30\.' \(Fanuc's ,A: the angle of a line in direct "
                                         r"drawing dimension programming"):
        parse_program("G21 G90\nG0 X0 Y0 Z5\nG1 X20. ,A30. F100\nM30\n", context=FANUC)


def _duration(text: str, dialect: str, **context) -> float:
    prog = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect], **context))
    return float(interpolate(prog).t[-1])


def test_fanuc_helix_feed_is_along_its_arc_in_the_plane():
    # FANUC 15i-B connection manual B-63783EN-1, 6.7 "Helical interpolation B": with HTG = 0 (the default) "a
    # feedrate along an arc is specified by an F command", the linear axis at F x its length / the arc's length.
    # A full turn of radius 10 mm (62.83 mm in the plane) dropping 50 mm at F600 (10 mm/s): 6.28 s of feed on a
    # Fanuc, 8.03 s along the 80.3 mm helix under LinuxCNC's rule. Before: 8.03 s under fanuc too
    text = "G21 G90 G17\nG0 X10 Y0 Z0\nG2 X10 Y0 Z-50 I-10 J0 F600\nM30\n"
    fanuc, linuxcnc = _duration(text, "fanuc"), _duration(text, "linuxcnc")
    assert 2 * np.pi < fanuc < 2 * np.pi + 0.5  # the arc at F, plus the ramps of the default limits
    assert linuxcnc - fanuc == pytest.approx(np.hypot(20 * np.pi, 50) / 10 - 2 * np.pi, abs=0.05)


def test_fanuc_line_with_a_rotary_axis_takes_its_degrees_as_lengths():
    # FANUC Power Mate i-D/H operator's manual B-63174EN/03, 4.2 "Linear interpolation (G01)": "G91 G01 X20.0
    # C40.0 F300.0 ; This changes the unit of the C axis from 40.0 deg to 40mm with metric input", the block taking
    # sqrt(20^2 + 40^2) / 300 = 0.14907 min (8.94 s); LinuxCNC moves X20 at F300 (4 s), C following. Before: 4 s
    # under fanuc too
    text = "G21 G90 G17\nG0 X0 Y0 Z0 C0\nG91 G01 X20.0 C40.0 F300.0\nM30\n"
    fanuc = _duration(text, "fanuc", extra_axes=("c",))
    linuxcnc = _duration(text, "linuxcnc", extra_axes=("c",))
    assert fanuc - linuxcnc == pytest.approx(np.hypot(20, 40) / 5 - 4, abs=0.05)
    assert 0.14907 * 60 < fanuc < 0.14907 * 60 + 0.5
