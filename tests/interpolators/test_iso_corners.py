"""Fanuc/Haas ``,R`` corner rounding and ``,C`` chamfering (:mod:`interpolators.iso_corners`).

End points, tangent points and centres are worked out by hand for each program (a 90 degree
corner of two lines with ``,R5``: the tangent points 5 mm before and after the corner, the centre
5 mm inside along both lines); the straight-line programs are also checked against the independent
reference (:mod:`tests.interpolators.reference_iso`, its own implementation of the words).
Sources: Fanuc 0i-MF operator's manual, "Optional chamfering and corner R"; Haas mill operator's
manual, "G01 Corner Rounding and Chamfering".
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

BASE = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0),
                      tools={1: Tool(number=1, radius=2.0, length=0.0)})
FANUC = dataclasses.replace(BASE, dialect=DIALECTS["fanuc"])
HAAS = dataclasses.replace(BASE, dialect=DIALECTS["haas"])
OFF = np.array([100.0, 50.0, -20.0])


def rows(text: str, context: MachineContext = FANUC, *, reference: bool = True) -> list[dict]:
    """The ``--blocks`` rows of the program (positions less the G54 offset), checked against the
    reference when ``reference``."""
    prog = parse_program(text, context=context)
    header, table = blocks_table(prog)
    if reference:
        match = match_blocks(iso_reference(text, context), [r + [0.0] * 6 for r in table])
        assert match.mismatch is None, match.mismatch
        assert match.exact + match.within == len(table)
    out = []
    for r in table:
        d = dict(zip(header, r))
        d["end"] = np.array([d["x"], d["y"], d["z"]], float) - OFF
        if d["kind"].startswith("arc"):
            d["centre"] = np.array([d["cx"], d["cy"], d["cz"]], float) - OFF
        out.append(d)
    return out


SQUARE = """G21 G90 G17 G54
G0 X0 Y0 Z0
G1 X50. {word} F600.
Y40.
X0 F300.
M30
"""


@pytest.mark.parametrize("context", [FANUC, HAAS], ids=["fanuc", "haas"])
def test_rounding_a_right_angle_corner_of_two_lines(context):
    r = rows(SQUARE.format(word=",R5."), context)
    assert [(d["line"], d["kind"]) for d in r] == [(2, "rapid"), (3, "feed"), (3, "arc_ccw"), (4, "feed"),
                                                   (5, "feed")]
    # the corner (50, 0); a left turn: tangent points 5 mm before it on X and 5 mm after it on Y,
    # the centre 5 mm inside along both lines
    assert r[1]["end"] == pytest.approx([45, 0, 0], abs=1e-9)
    assert r[2]["end"] == pytest.approx([50, 5, 0], abs=1e-9)
    assert r[2]["centre"][:2] == pytest.approx([45, 5], abs=1e-9)
    assert r[3]["end"] == pytest.approx([50, 40, 0], abs=1e-9)
    # the corner arc runs at the feed of the block with the word
    assert [d["feed"] for d in r[1:]] == pytest.approx([600, 600, 600, 300])


def test_chamfering_a_right_angle_corner_cuts_the_distance_from_the_corner_along_each_line():
    r = rows(SQUARE.format(word=",C3."))
    assert [d["kind"] for d in r] == ["rapid", "feed", "feed", "feed", "feed"]
    assert r[1]["end"] == pytest.approx([47, 0, 0], abs=1e-9)
    assert r[2]["end"] == pytest.approx([50, 3, 0], abs=1e-9)
    assert r[2]["line"] == 3
    assert r[3]["end"] == pytest.approx([50, 40, 0], abs=1e-9)


def test_rounding_an_oblique_corner_right_turn_in_inch_incremental():
    # from (0,0) 2 in along +X, then to (4, -2) in: a right turn of 45 degrees; ,R0.5 in = 12.7 mm
    r = rows("G20 G90 G17 G54\nG0 X0 Y0 Z0\nG91 G1 X2. ,R0.5 F10.\nX2. Y-2.\nM30\n")
    t = math.radians(45.0)
    d = 12.7 * math.tan(t / 2)
    corner = np.array([50.8, 0.0])
    assert r[1]["end"][:2] == pytest.approx(corner - [d, 0], abs=1e-9)
    assert r[2]["kind"] == "arc_cw"
    assert r[2]["end"][:2] == pytest.approx(corner + d * np.array([math.cos(t), -math.sin(t)]), abs=1e-9)
    assert r[2]["centre"][:2] == pytest.approx(corner - [d, 12.7], abs=1e-9)
    assert r[1]["feed"] == r[2]["feed"] == pytest.approx(254.0)


@pytest.mark.parametrize("plane, text, corner, centre", [
    ("G18", "G0 X0 Y0 Z0\nG1 X30. ,R4. F500.\nZ-20.\n", (30, 0, 0), (26, 0, -4)),
    ("G19", "G0 X0 Y0 Z0\nG1 Y30. ,R4. F500.\nZ20.\n", (0, 30, 0), (0, 26, 4)),
])
def test_rounding_in_the_zx_and_yz_planes(plane, text, corner, centre):
    r = rows(f"G21 G90 {plane} G54\n{text}M30\n")
    arc = r[2]
    assert arc["centre"] == pytest.approx(centre, abs=1e-9)
    assert float(np.linalg.norm(arc["end"] - arc["centre"])) == pytest.approx(4.0)
    assert float(np.linalg.norm(r[1]["end"] - arc["centre"])) == pytest.approx(4.0)


def test_rounding_follows_g68_rotation_and_the_work_offset():
    # G68 R90 about the origin: the square's first line runs along +Y, the corner at (0, 50)
    r = rows("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG68 X0 Y0 R90.\nG1 X50. ,R5. F600.\nY40.\nG69\nM30\n")
    assert r[1]["end"] == pytest.approx([0, 45, 0], abs=1e-9)
    assert r[2]["end"] == pytest.approx([-5, 50, 0], abs=1e-9)
    assert r[2]["centre"][:2] == pytest.approx([-5, 45], abs=1e-9)


def test_rounding_under_g51_scaling_scales_the_radius():
    r = rows("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG51 X0 Y0 P2000\nG1 X25. ,R2.5 F600.\nY20.\nG50\nM30\n")
    assert r[1]["end"] == pytest.approx([45, 0, 0], abs=1e-9)
    assert r[2]["centre"][:2] == pytest.approx([45, 5], abs=1e-9)


def test_consecutive_corners_each_trim_the_move_between_them():
    r = rows("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG1 X50. ,R5. F600.\nY40. ,C2.\nX0\nM30\n")
    assert [(d["line"], d["kind"]) for d in r[1:]] == [(3, "feed"), (3, "arc_ccw"), (4, "feed"), (4, "feed"),
                                                       (5, "feed")]
    assert r[3]["end"] == pytest.approx([50, 38, 0], abs=1e-9)
    assert r[4]["end"] == pytest.approx([48, 40, 0], abs=1e-9)


def test_fanuc_rounds_between_a_line_and_an_arc():
    # a line along +X to (50, 0), then a clockwise arc of radius 20 about (70, 0) to (70, 20): it leaves
    # (50, 0) heading +Y, a 90 degree left turn onto the circle
    r = rows("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG1 X50. ,R5. F600.\nG2 X70. Y20. I20. J0\nM30\n")
    arc = r[2]
    # the rounding circle (radius 5) touches the line y = 0 from above: centre y = 5; it touches the
    # circle of radius 20 about (70, 0) from outside: distance 25 from (70, 0): x = 70 - sqrt(25^2 - 5^2)
    cx = 70.0 - math.sqrt(25.0 ** 2 - 5.0 ** 2)
    assert arc["centre"][:2] == pytest.approx([cx, 5.0], abs=1e-9)
    assert r[1]["end"] == pytest.approx([cx, 0, 0], abs=1e-9)
    # the tangent point on the big circle lies on the line of the centres, 20 from (70, 0)
    u = (np.array([cx, 5.0]) - [70.0, 0.0]) / 25.0
    assert arc["end"][:2] == pytest.approx(np.array([70.0, 0.0]) + 20 * u, abs=1e-9)
    assert r[2]["kind"] == "arc_ccw"
    assert r[3]["kind"] == "arc_cw" and r[3]["end"] == pytest.approx([70, 20, 0], abs=1e-9)
    assert r[3]["centre"][:2] == pytest.approx([70, 0], abs=1e-9)


def test_fanuc_chamfer_on_an_arc_is_the_chord_from_the_corner():
    r = rows("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG1 X50. ,C4. F600.\nG2 X70. Y20. I20. J0\nM30\n")
    assert r[1]["end"] == pytest.approx([46, 0, 0], abs=1e-9)
    assert float(np.linalg.norm(r[2]["end"][:2] - [50, 0])) == pytest.approx(4.0)
    assert float(np.linalg.norm(r[2]["end"][:2] - [70, 0])) == pytest.approx(20.0)
    assert r[2]["end"][1] > 0  # on the arc as it runs (up from (50, 0)), not behind its start
    assert r[3]["centre"][:2] == pytest.approx([70, 0], abs=1e-9)


def test_rounding_under_g41_offsets_the_rounded_contour():
    # the tool (radius 2) left of a counter-clockwise square: the rounding (R5, outside corner for
    # the contour, the tool inside) is offset to a concentric arc of radius 5 - 2 = 3
    text = ("G21 G90 G17 G54\nG0 X-10. Y-10. Z0\nG41 D1 G1 X0 Y0 F600.\nX50. ,R5.\nY40.\nX0\nG40 G1 X-10. Y-10.\n"
            "M30\n")
    r = rows(text)
    # Fanuc's start-up (type A) ends the entry perpendicular to the next block at its start, (0, 2): no corner
    # arc about (0, 0) as LinuxCNC's rule (perpendicular to the entry move) makes; the rounding follows
    assert r[1]["end"][:2] == pytest.approx([0, 2], abs=1e-9)
    assert [d["kind"] for d in r if d["line"] == 4] == ["feed", "arc_ccw"]
    arc = r[3]
    assert arc["centre"][:2] == pytest.approx([45, 5], abs=1e-6)
    assert arc["end"][:2] == pytest.approx([48, 5], abs=1e-6)
    line_end = [d for d in r if d["line"] == 4 and d["kind"] == "feed"][-1]
    assert line_end["end"][:2] == pytest.approx([45, 2], abs=1e-6)


@pytest.mark.parametrize("text, message", [
    ("G1 X50. ,R5. F600.\nG0 Y40.\n", r"',R5\.' corner rounding \(line 3\) is not followed by a move: a G00 rapid"),
    ("G1 X50. ,R5. F600.\nM8\nY40.\n", r"not followed by a move: this block has no move"),
    ("G1 X50. ,R5. F600.\nG4 P100\nY40.\n", r"this block makes a dwell"),
    ("G1 X50. ,R5. F600.\nM30\n", r"not followed by a move: this block has no move"),
    ("G1 X50. ,R5. F600.\nG18 Z-10.\n", r"the plane changed from G17 to G18"),
    ("G1 X50. ,R5. F600.\nZ-10.\n", r"this block moves along the plane's normal axis"),
    ("G1 X50. Z-5. ,R5. F600.\nY40.\n", r"line 3 moves along the plane's normal axis"),
    ("G1 X50. ,R60. F600.\nY40.\n", r"',R60\.' corner rounding: rounding radius 60 mm does not fit.*PS0055"),
    ("G1 X50. ,C60. F600.\nY40.\n", r"',C60\.' chamfering: chamfer 60 mm is longer than a line"),
    ("G1 X50. ,R5. F600.\nX80.\n", r"between collinear lines"),
    ("G1 X50. ,R5. ,C2. F600.\nY40.\n", r"',C' chamfering and ',R' corner rounding in one block"),
    ("G1 X50. ,R0 F600.\nY40.\n", r"the value must be > 0"),
    ("G0 X50. ,R5.\nG1 Y40. F600.\n", r"on a G00 rapid block"),
    ("G1 ,R5. F600.\nY40.\n", r"on a block without a G01/G02/G03 move"),
    ("G93 G1 X50. ,R5. F2.\nY40. F2.\n", r"under G93 inverse time"),
])
def test_fanuc_alarms(text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90 G17 G54\nG0 X0 Y0 Z0\n{text}M30\n", context=FANUC)


def test_a_corner_at_the_end_of_the_file_is_an_error():
    with pytest.raises(GCodeError, match=r"3:9: ',R5\.' corner rounding \(line 3\) is not followed by a move: "
                       "the program ends"):
        parse_program("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG1 X50. ,R5. F600.\n", context=FANUC)


def test_haas_takes_the_words_between_g01_moves_only():
    with pytest.raises(GCodeError, match=r"a G02/G03 arc \(haas: only G01\)"):
        parse_program("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG1 X50. ,R5. F600.\nG3 X70. Y20. I20. J0\nM30\n", context=HAAS)
    with pytest.raises(GCodeError, match=r"on a G03 block \(haas: only on G01\)"):
        parse_program("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG3 X20. Y0 I10. J0 ,R2. F600.\nG1 X0\nM30\n", context=HAAS)


def test_linuxcnc_and_grbl_refuse_the_words():
    for name in ("linuxcnc", "grbl"):
        ctx = dataclasses.replace(BASE, dialect=DIALECTS[name])
        with pytest.raises(GCodeError, match=rf"not in the {name} dialect"):
            parse_program(SQUARE.format(word=",R5."), context=ctx)


def test_bare_r_on_a_mill_g01_stays_an_error_naming_the_lathe_form():
    for context in (FANUC, HAAS):
        with pytest.raises(GCodeError, match=r"word R on G01: the lathe form of corner rounding .*expected ,R5\."):
            parse_program(SQUARE.format(word="R5."), context=context)
    with pytest.raises(GCodeError, match="word R is only allowed on arcs"):
        parse_program(SQUARE.format(word="R5."), context=dataclasses.replace(BASE, dialect=DIALECTS["linuxcnc"]))


def test_fanuc_rounds_between_two_arcs():
    # G3 about (10, 0) from (0, 0) runs below the axis and reaches (20, 0) heading +Y; G3 about (20, 10)
    # leaves (20, 0) heading +X: a right turn of 90 degrees, the corner's inside to the right of both
    # arcs, which turn left: the rounding circle lies outside both circles
    r = rows("G21 G90 G17 G54\nG0 X0 Y0 Z0\nG3 X20. Y0 I10. J0 ,R2. F600.\nG3 X30. Y10. I0 J10.\nM30\n")
    arc = r[2]
    assert arc["kind"] == "arc_cw" and arc["line"] == 3
    # the rounding circle (radius 2) touches both circles of radius 10 from outside: 12 from each centre,
    # on the side of the corner (20, 0)
    c = arc["centre"][:2]
    assert float(np.hypot(*(c - [10, 0]))) == pytest.approx(12.0, abs=1e-9)
    assert float(np.hypot(*(c - [20, 10]))) == pytest.approx(12.0, abs=1e-9)
    assert float(np.hypot(*(c - [20, 0]))) < 3.0
    # the tangent points on the lines of the centres
    assert r[1]["end"][:2] == pytest.approx(np.array([10.0, 0]) + 10 * (c - [10, 0]) / 12, abs=1e-9)
    assert arc["end"][:2] == pytest.approx(np.array([20.0, 10]) + 10 * (c - [20, 10]) / 12, abs=1e-9)
    assert r[3]["end"] == pytest.approx([30, 10, 0], abs=1e-9)
