"""Generated Fanuc and Haas mill programs (tests/interpolators/fanuc_generator.py) against the independent
reference, and the disagreements the generator found, each as a hand-written program: Fanuc's ``M98 P<count>
<program>`` refused; the centre of ``G51`` read in whole millimetres under DPI = 0; the reference's G89 retract and
its outside corners of a G41 contour under a one-axis mirror."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.fanuc_generator import context, generate
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

BASE = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0),
                      tools={1: Tool(number=1, length=10.0, radius=2.0)})
FANUC = dataclasses.replace(BASE, dialect=DIALECTS["fanuc"])
HAAS = dataclasses.replace(BASE, dialect=DIALECTS["haas"])
FANUC_DPI0 = dataclasses.replace(FANUC, decimal_point_input="increment")


def ends(text: str, context: MachineContext) -> list[tuple[int, str, list[float]]]:
    """Line, kind and end point [mm, less the G54 offset] of each block, after checking them against the
    reference."""
    prog = checked_iso(text, context)
    return [(b.line, b.kind, np.round(b.target - [100.0, 50.0, -20.0], 6).tolist()) for b in prog.blocks]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_generated_programs_are_read_as_the_reference_reads_them_or_refused_cleanly(dialect):
    # 120 seeded programs per dialect mixing G20/G21, G54-G59, G54.1 P / G154 P / G110-G129, G52, G92, G10 L2/L20,
    # G10 L10-L13, G28 through a point, G53, G43 H, T M06, G0/G1 in G90/G91, G2/G3 by I J K and R in G17-G19, full
    # circles, helices, G41/G42 rectangles and slots (also under G68, G51, G51.1/G101, G52), drilling, boring and
    # Haas pattern / pocket cycles in G90 and G91 with K/L repeats (also under G68 and a mirror), M98/M97/M99,
    # Macro B loops and functions, G65, G68, G51 (P, I J K), G16, ,R / ,C, G04, block delete, tool length changes
    # under G91, G84 under G95 (Fanuc after M29), Haas G73 Q K and M99 P in a subprogram, and for a third of the
    # Fanuc seeds DPI = 0 with distances as integers of least input increments
    accepted = 0
    for seed in range(120):
        text, ctx = generate(seed, dialect), context(seed, dialect)
        try:
            prog = parse_program(text, context=ctx, source="t.nc")
        except GCodeError as e:
            assert str(e).startswith("t.nc:") and "expected" in str(e), (seed, str(e))
            continue
        match = match_blocks(iso_reference(text, ctx), reader_rows(*blocks_table(prog)))
        assert match.mismatch is None, (seed, match.mismatch)
        accepted += 1
    assert accepted >= 110


def test_generator_is_seeded():
    assert generate(7, "fanuc") == generate(7, "fanuc")
    assert generate(7, "fanuc") != generate(8, "fanuc")
    assert generate(7, "haas") != generate(7, "fanuc")
    assert generate(3, "haas").startswith("%\nO4003 (FUZZ 3)\n")


SUB = "O1000\nG91 G1 X5. F100.\nG90\nM99\n"


def test_fanuc_m98_p_with_the_count_before_the_program_number():
    # Fanuc 0i-MC operator's manual B-64124EN 12.3 "Subprogram": "M98 P51002 ... Call the subprogram (number
    # 1002) five times in succession"; vcnc looked for an O31000 and refused the program
    text = "G90 G54 G0 X0 Y0 Z10.\nM98 P31000\nG0 X0\nM30\n" + SUB
    assert [e[2][0] for e in ends(text, FANUC)] == [0.0, 5.0, 10.0, 15.0, 0.0]
    # with an O31000 in the file, P31000 is that program (30i's longer program numbers)
    own = text + "O31000\nG91 G1 Y7. F100.\nG90\nM99\n"
    assert [e[2][:2] for e in ends(own, FANUC)] == [[0.0, 0.0], [0.0, 7.0], [0.0, 7.0]]
    # Haas numbers programs O00001-O99999 and gives the count as L: P31000 is program 31000
    with pytest.raises(GCodeError, match=r"t.nc:2:1: M98 subprogram call: program O31000 is neither"):
        parse_program(text, context=HAAS, source="t.nc")
    assert [e[2][0] for e in ends(text.replace("P31000", "P1000 L3"), HAAS)] == [0.0, 5.0, 10.0, 15.0, 0.0]


def test_scaling_centre_without_a_decimal_point_under_dpi_0():
    # Fanuc 0i-MF "Scaling": G51 X_ Y_ Z_ is the centre, a position; under DPI = 0 (parameter No. 3401#0) X10000
    # is 10 mm as in any other block (the factor P2000 is 2 by the scaling's own rule). vcnc read the centre as
    # 10000 mm and sent X20000 (20 mm) to -9960 mm
    text = "G90 G54 G0 X0 Y0 Z10.\nG51 X10000 Y0 P2000\nG1 X20000 F100.\nG50\nG1 X20000\nM30\n"
    assert [e[2][0] for e in ends(text, FANUC_DPI0)] == [0.0, 30.0, 20.0]


def test_fanuc_g89_feeds_back_to_r_then_rapids_to_the_initial_level():
    # FANUC 30i operator's manual B-63944EN-2 5.1.9 "Boring cycle (G85)": "When point Z has been reached, cutting
    # feed is performed to return to point R", under G98 a rapid on to the initial level; G89 the same after its
    # dwell (0i-MF "Boring cycle G89"). The reference fed to the initial level, as LinuxCNC's G89 does
    text = "G90 G54 G0 X10. Y5. Z20.\nG98 G89 Z-5. R2. P500 F100.\nG80\nM30\n"
    want = [(1, "rapid", [10.0, 5.0, 20.0]), (2, "rapid", [10.0, 5.0, 2.0]), (2, "line", [10.0, 5.0, -5.0]),
            (2, "dwell", [10.0, 5.0, -5.0]), (2, "line", [10.0, 5.0, 2.0]), (2, "rapid", [10.0, 5.0, 20.0])]
    assert ends(text, FANUC) == want
    assert ends(text, HAAS) == want


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_cutter_compensation_under_a_one_axis_mirror_keeps_its_side_of_the_contour(context):
    # Fanuc 0i-MF "Programmable mirror image": with one axis of the plane mirrored "the offset direction is
    # reversed" (Haas "G101": the cutter runs on the mirrored side): G41 on a counter-clockwise square stays inside
    # it, mirrored to X -20..0. The reference put Fanuc's outside-corner points on the machine's left
    mirror, cancel = ("G51.1 X0", "G50.1 X0") if context is FANUC else ("G101 X0.", "G100 X0.")
    text = (f"G90 G54 G0 X0 Y0 Z10.\n{mirror}\nG0 X10. Y-10.\nG1 Z-1. F100.\nG41 D1 G1 Y0.\nX20.\nY20.\nX0.\nY0.\n"
            f"X10.\nG40 G1 Y-10.\n{cancel}\nM30\n")
    got = [e[2][:2] for e in ends(text, context)][3:]
    assert got == [[-10.0, 2.0], [-18.0, 2.0], [-18.0, 18.0], [-2.0, 18.0], [-2.0, 2.0], [-10.0, 2.0],
                   [-10.0, -10.0]]


def test_g98_block_after_g99_holes_positions_where_the_tool_is_then_rapids_up_to_a_higher_r():
    # Fanuc 0i-MF "Canned cycle for drilling": operation 1 positions X Y, operation 2 rapids to point R. After a
    # G99 hole the tool waits at R3; a G98 block with R5 moves over at Z3, rises to R5, drills and returns to
    # the initial level Z20. vcnc rose diagonally to Z20 over the new hole and came down to R5
    text = "G90 G54 G0 X0 Y0 Z20.\nG99 G81 X10. Z-6. R3. F100.\nG98 Y5. R5.\nG80\nM30\n"
    assert [e for e in ends(text, FANUC) if e[0] == 3] == [
        (3, "rapid", [10.0, 5.0, 3.0]), (3, "rapid", [10.0, 5.0, 5.0]), (3, "line", [10.0, 5.0, -6.0]),
        (3, "rapid", [10.0, 5.0, 20.0])]


def test_pecks_that_divide_the_depth_end_at_the_bottom():
    # G73 from R0.15 to Z-0.45 in Q0.1 steps: six pecks, the sixth at the bottom, then the retract (Fanuc 0i-MF
    # "High-speed peck drilling cycle"; the control's decimal arithmetic). vcnc's doubles left the sixth peck
    # a hair above -0.45 and added a seventh: a 0.010 in retract and a feed back to the same depth
    text = "G20 G90 G54 G0 X0 Y0 Z1.\nG99 G73 Z-0.45 R0.15 Q0.1 F10.\nG80\nM30\n"
    feeds = [round(e[2][2] / 25.4, 6) for e in ends(text, FANUC) if e[1] == "line"]
    assert feeds == [0.05, -0.05, -0.15, -0.25, -0.35, -0.45]
    assert ends(text, FANUC)[-1] == (2, "rapid", [0.0, 0.0, 3.81])


def test_g73_pecks_that_divide_the_depth_make_no_peck_at_the_bottom_in_increments():
    # fanuc_generator seed 501518, shrunk: an inch program under DPI = 0 (Z-7000 is 0.7 in), G73 from R 0.1 in
    # to Z-0.6 in with Q 0.1 in: six pecks of 2.54 mm and the seventh feed reaches the bottom, then back to R
    # (Fanuc 0i-MF "High-speed peck drilling cycle (G73)"; the control counts in decimal, so no chip break and
    # re-feed at the bottom). In mm the reference's pecks landed within rounding above the bottom and it expected
    # that extra peck; it now counts as Fanuc does
    ctx = MachineContext(dialect=DIALECTS["fanuc"], decimal_point_input="increment",
                         tools={5: Tool(number=5, length=50.0)}, work_offsets={"G57": (-270.0, -185.0, -393.0)})
    text = ("%\nO1\nG20 G90 G57 G0 X2. Y-0.5 Z1.\nG43 H5 Z0.5\n"
            "G91 G99 G73 X-2500 Y2500 Z-7000 R-4000 Q1000 F20\nG80 G90\nM30\n%\n")
    prog = checked_iso(text, ctx)
    z = [round(float(b.target[2]) + 393.0 - 50.0, 4) for b in prog.blocks if b.line == 5]
    pecks = [round(0.1 * 25.4 - 2.54 * k, 4) for k in range(1, 7)]
    assert z == [12.7, 2.54, *[v for p in pecks for v in (p, round(p + 0.254, 4))], -15.24, 2.54]
