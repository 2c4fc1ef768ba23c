"""Cases ported from LinuxCNC's own interpreter tests (github.com/LinuxCNC/linuxcnc, tests/interp/g81/g17/g98
and g17/g99: a test .ngc and its expected canonical calls). The programs are the test programs without comments;
the end points are the STRAIGHT_TRAVERSE/STRAIGHT_FEED X, Y, Z of the ``expected`` files [inch], written out."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from vcnc.errors import GCodeError

INCH = 25.4  # [mm/inch]

#: tests/interp/g81/g17/g98 program (G20, G17) [inch].
PROGRAM_G98 = """\
g17
g98
g90
g20
f10
g0 x0 y0 z2
g81 x1 y1 z-1 r1
g81 x1 y2 z0.5 r3
g81 x1 y3 z4 r5
g90 g0 x10 y0 z2
g91 g81 x1 y1 z-2 r-1 l2
g90 g0 x20 y0 z2
g91 g81 x1 y1 z-2.5 r1 l2
g90 g0 x30 y0 z2
g91 g81 x1 y1 z-1 r3 l2
m2
"""
#: tests/interp/g81/g17/g98/expected: (kind, X, Y, Z) [inch], rapid = STRAIGHT_TRAVERSE, line = STRAIGHT_FEED.
EXPECTED_G98 = [
    ('rapid', 0.0, 0.0, 2.0),
    ('rapid', 1.0, 1.0, 2.0),
    ('rapid', 1.0, 1.0, 1.0),
    ('line', 1.0, 1.0, -1.0),
    ('rapid', 1.0, 1.0, 2.0),
    ('rapid', 1.0, 1.0, 3.0),
    ('rapid', 1.0, 2.0, 3.0),
    ('line', 1.0, 2.0, 0.5),
    ('rapid', 1.0, 2.0, 3.0),
    ('rapid', 1.0, 2.0, 5.0),
    ('rapid', 1.0, 3.0, 5.0),
    ('line', 1.0, 3.0, 4.0),
    ('rapid', 1.0, 3.0, 5.0),
    ('rapid', 10.0, 0.0, 2.0),
    ('rapid', 11.0, 1.0, 2.0),
    ('rapid', 11.0, 1.0, 1.0),
    ('line', 11.0, 1.0, -1.0),
    ('rapid', 11.0, 1.0, 2.0),
    ('rapid', 12.0, 2.0, 2.0),
    ('rapid', 12.0, 2.0, 1.0),
    ('line', 12.0, 2.0, -1.0),
    ('rapid', 12.0, 2.0, 2.0),
    ('rapid', 20.0, 0.0, 2.0),
    ('rapid', 20.0, 0.0, 3.0),
    ('rapid', 21.0, 1.0, 3.0),
    ('line', 21.0, 1.0, 0.5),
    ('rapid', 21.0, 1.0, 3.0),
    ('rapid', 22.0, 2.0, 3.0),
    ('line', 22.0, 2.0, 0.5),
    ('rapid', 22.0, 2.0, 3.0),
    ('rapid', 30.0, 0.0, 2.0),
    ('rapid', 30.0, 0.0, 5.0),
    ('rapid', 31.0, 1.0, 5.0),
    ('line', 31.0, 1.0, 4.0),
    ('rapid', 31.0, 1.0, 5.0),
    ('rapid', 32.0, 2.0, 5.0),
    ('line', 32.0, 2.0, 4.0),
    ('rapid', 32.0, 2.0, 5.0),
]

#: tests/interp/g81/g17/g99 program (G20, G17) [inch].
PROGRAM_G99 = """\
g17
g99
g90
g20
f10
g0 x0 y0 z2
g81 x1 y1 z-1 r1
g81 x1 y2 z0.5 r3
g81 x1 y3 z4 r5
g90 g0 x10 y0 z2
g91 g81 x1 y1 z-2 r-1 l2
g90 g0 x20 y0 z2
g91 g81 x1 y1 z-2.5 r1 l2
g90 g0 x30 y0 z2
g91 g81 x1 y1 z-1 r3 l2
m2
"""
#: tests/interp/g81/g17/g99/expected: (kind, X, Y, Z) [inch], rapid = STRAIGHT_TRAVERSE, line = STRAIGHT_FEED.
EXPECTED_G99 = [
    ('rapid', 0.0, 0.0, 2.0),
    ('rapid', 1.0, 1.0, 2.0),
    ('rapid', 1.0, 1.0, 1.0),
    ('line', 1.0, 1.0, -1.0),
    ('rapid', 1.0, 1.0, 1.0),
    ('rapid', 1.0, 1.0, 3.0),
    ('rapid', 1.0, 2.0, 3.0),
    ('line', 1.0, 2.0, 0.5),
    ('rapid', 1.0, 2.0, 3.0),
    ('rapid', 1.0, 2.0, 5.0),
    ('rapid', 1.0, 3.0, 5.0),
    ('line', 1.0, 3.0, 4.0),
    ('rapid', 1.0, 3.0, 5.0),
    ('rapid', 10.0, 0.0, 2.0),
    ('rapid', 11.0, 1.0, 2.0),
    ('rapid', 11.0, 1.0, 1.0),
    ('line', 11.0, 1.0, -1.0),
    ('rapid', 11.0, 1.0, 1.0),
    ('rapid', 12.0, 2.0, 1.0),
    ('line', 12.0, 2.0, -1.0),
    ('rapid', 12.0, 2.0, 1.0),
    ('rapid', 20.0, 0.0, 2.0),
    ('rapid', 20.0, 0.0, 3.0),
    ('rapid', 21.0, 1.0, 3.0),
    ('line', 21.0, 1.0, 0.5),
    ('rapid', 21.0, 1.0, 3.0),
    ('rapid', 22.0, 2.0, 3.0),
    ('line', 22.0, 2.0, 0.5),
    ('rapid', 22.0, 2.0, 3.0),
    ('rapid', 30.0, 0.0, 2.0),
    ('rapid', 30.0, 0.0, 5.0),
    ('rapid', 31.0, 1.0, 5.0),
    ('line', 31.0, 1.0, 4.0),
    ('rapid', 31.0, 1.0, 5.0),
    ('rapid', 32.0, 2.0, 5.0),
    ('line', 32.0, 2.0, 4.0),
    ('rapid', 32.0, 2.0, 5.0),
]


@pytest.mark.parametrize(("program", "expected"), [(PROGRAM_G98, EXPECTED_G98), (PROGRAM_G99, EXPECTED_G99)],
                         ids=["g17-g98-g81", "g17-g99-g81"])
def test_g81_canonical_moves_match_linuxcnc(program, expected):
    prog = parse_program(program, context=MachineContext())
    got = [(b.kind, *(round(v / INCH, 4) for v in b.target)) for b in prog.blocks if b.kind != "dwell"]
    assert got == expected


def test_g81_outside_g17_is_refused_by_name():
    # LinuxCNC runs tests/interp/g81/g18 and g19 too; vcnc's cycles are XY-plane only and say so.
    with pytest.raises(GCodeError, match="only in the XY plane"):
        parse_program("G18 G98 G90 G20 F10\nG0 X0 Y0 Z2\nG81 X1 Y1 Z-1 R1\n", context=MachineContext())


#: tests/interp/m98m99/01-basics/test.ngc (Fanuc-style M98 P1 L3 sub drilling three holes; units as in the file).
PROGRAM_M98 = """\
%
F40
G90 G0 X0 Y0 Z0.25
M98 P1 L3
M30
O1
G91 G0 X1
G90 G99 G81 Z-1.0 R0.25
M99
%
"""
#: tests/interp/m98m99/01-basics/expected, consecutive repeats dropped (LinuxCNC emits a zero-length
#: STRAIGHT_TRAVERSE to the R plane when the tool is already there; vcnc emits no zero-length block).
EXPECTED_M98 = [
    ("rapid", 0.0, 0.0, 0.25),
    ("rapid", 1.0, 0.0, 0.25), ("line", 1.0, 0.0, -1.0), ("rapid", 1.0, 0.0, 0.25),
    ("rapid", 2.0, 0.0, 0.25), ("line", 2.0, 0.0, -1.0), ("rapid", 2.0, 0.0, 0.25),
    ("rapid", 3.0, 0.0, 0.25), ("line", 3.0, 0.0, -1.0), ("rapid", 3.0, 0.0, 0.25),
]


def test_m98_sub_with_g81_matches_linuxcnc():
    prog = parse_program(PROGRAM_M98, context=MachineContext())
    got = [(b.kind, *(round(float(v), 4) for v in b.target)) for b in prog.blocks if b.kind in ("rapid", "line")]
    assert got == EXPECTED_M98


#: tests/interp/m98m99/05-M98-loops/test.ngc (comments and PRINTs left out): an incremental G81 in an
#: M98 subprogram run L10, L0 and L2 times; units as in the file.
PROGRAM_M98_LOOPS = """\
%
F40
#1 = 0
G90 G0 X0 Y0 Z0.25
M98 P1 L10
#1 = 0
G90 G0 X0 Y0 Z0.25
M98 P1 L0
#1 = 0
G90 G0 X0 Y0 Z0.25
M98 P1 L2
M30
O1
G91 G99 G81 X1 Z-1.0 R0.25
#1 = [#1 + 1]
M99
%
"""
#: tests/interp/m98m99/05-M98-loops/expected, consecutive repeats dropped. Each call's G81 block is
#: a block of the same series (G81 stays modal), so under G91 its R is 0.25 above the series'
#: initial level Z0.25 (interp_cycles.cc: r = R + cycle_il), not above the current Z: every hole
#: has R at 0.5 and its bottom at -0.5. L0 runs the subprogram no time.
EXPECTED_M98_LOOPS = [
    ('rapid', 0.0, 0.0, 0.25), ('rapid', 0.0, 0.0, 0.5), ('rapid', 1.0, 0.0, 0.5),
    ('line', 1.0, 0.0, -0.5), ('rapid', 1.0, 0.0, 0.5), ('rapid', 2.0, 0.0, 0.5),
    ('line', 2.0, 0.0, -0.5), ('rapid', 2.0, 0.0, 0.5), ('rapid', 3.0, 0.0, 0.5),
    ('line', 3.0, 0.0, -0.5), ('rapid', 3.0, 0.0, 0.5), ('rapid', 4.0, 0.0, 0.5),
    ('line', 4.0, 0.0, -0.5), ('rapid', 4.0, 0.0, 0.5), ('rapid', 5.0, 0.0, 0.5),
    ('line', 5.0, 0.0, -0.5), ('rapid', 5.0, 0.0, 0.5), ('rapid', 6.0, 0.0, 0.5),
    ('line', 6.0, 0.0, -0.5), ('rapid', 6.0, 0.0, 0.5), ('rapid', 7.0, 0.0, 0.5),
    ('line', 7.0, 0.0, -0.5), ('rapid', 7.0, 0.0, 0.5), ('rapid', 8.0, 0.0, 0.5),
    ('line', 8.0, 0.0, -0.5), ('rapid', 8.0, 0.0, 0.5), ('rapid', 9.0, 0.0, 0.5),
    ('line', 9.0, 0.0, -0.5), ('rapid', 9.0, 0.0, 0.5), ('rapid', 10.0, 0.0, 0.5),
    ('line', 10.0, 0.0, -0.5), ('rapid', 10.0, 0.0, 0.5), ('rapid', 0.0, 0.0, 0.25),
    ('rapid', 0.0, 0.0, 0.5), ('rapid', 1.0, 0.0, 0.5), ('line', 1.0, 0.0, -0.5),
    ('rapid', 1.0, 0.0, 0.5), ('rapid', 2.0, 0.0, 0.5), ('line', 2.0, 0.0, -0.5),
    ('rapid', 2.0, 0.0, 0.5),
]


def test_m98_loops_with_an_incremental_cycle_match_linuxcnc():
    prog = parse_program(PROGRAM_M98_LOOPS, context=MachineContext())
    got = [(b.kind, *(round(float(v), 4) for v in b.target)) for b in prog.blocks if b.kind in ("rapid", "line")]
    got = [g for i, g in enumerate(got) if i == 0 or got[i - 1][1:] != g[1:]]  # zero-length G0 repeats
    assert got == EXPECTED_M98_LOOPS


#: tests/interp/g84/g17/g98/expected: the program of g81/g17/g98 with G84 (and M3 S1000); LinuxCNC's
#: tap feeds out to the clear level (interp_cycles.cc convert_cycle_g74_g84) [inch].
EXPECTED_G84_G98 = [
    ('rapid', 0.0, 0.0, 2.0), ('rapid', 1.0, 1.0, 2.0), ('rapid', 1.0, 1.0, 1.0),
    ('line', 1.0, 1.0, -1.0), ('line', 1.0, 1.0, 2.0), ('rapid', 1.0, 1.0, 3.0),
    ('rapid', 1.0, 2.0, 3.0), ('line', 1.0, 2.0, 0.5), ('line', 1.0, 2.0, 3.0),
    ('rapid', 1.0, 2.0, 5.0), ('rapid', 1.0, 3.0, 5.0), ('line', 1.0, 3.0, 4.0),
    ('line', 1.0, 3.0, 5.0), ('rapid', 10.0, 0.0, 2.0), ('rapid', 11.0, 1.0, 2.0),
    ('rapid', 11.0, 1.0, 1.0), ('line', 11.0, 1.0, -1.0), ('line', 11.0, 1.0, 2.0),
    ('rapid', 12.0, 2.0, 2.0), ('rapid', 12.0, 2.0, 1.0), ('line', 12.0, 2.0, -1.0),
    ('line', 12.0, 2.0, 2.0), ('rapid', 20.0, 0.0, 2.0), ('rapid', 20.0, 0.0, 3.0),
    ('rapid', 21.0, 1.0, 3.0), ('line', 21.0, 1.0, 0.5), ('line', 21.0, 1.0, 3.0),
    ('rapid', 22.0, 2.0, 3.0), ('line', 22.0, 2.0, 0.5), ('line', 22.0, 2.0, 3.0),
    ('rapid', 30.0, 0.0, 2.0), ('rapid', 30.0, 0.0, 5.0), ('rapid', 31.0, 1.0, 5.0),
    ('line', 31.0, 1.0, 4.0), ('line', 31.0, 1.0, 5.0), ('rapid', 32.0, 2.0, 5.0),
    ('line', 32.0, 2.0, 4.0), ('line', 32.0, 2.0, 5.0),
]


def test_g84_taps_out_to_the_clear_level_as_linuxcnc():
    program = PROGRAM_G98.replace("g81", "g84").replace("f10\n", "f10\nM3 S1000\n")
    prog = parse_program(program, context=MachineContext())
    got = [(b.kind, *(round(v / INCH, 4) for v in b.target)) for b in prog.blocks if b.kind != "dwell"]
    assert got == EXPECTED_G84_G98


#: tests/interp/g10/g10-l2-while-active/test.ngc without its (debug) lines [inch].
PROGRAM_G10_ROTATION = """\
g54
g20
g10 l2 p1 x0 y0 z0 r0
g1 x0 y0 z0 f60
g10 l2 p1 x1
g1 x0 y0 z0
g10 l2 p1 r-45
g1 y sqrt[2]
g10 l2 p1 x2 y1 r90
g1 y3
g10 l2 p1 x0 y0
g1 x0 y0
g10 l2 p1 r0
m2
"""
#: Its expected STRAIGHT_FEEDs (0,0,0) (0,0,0) (0,1.4142,0) (0,3,0) (0,0,0) in machine coordinates:
#: rotated by the SET_XY_ROTATION in effect and moved by SET_G5X_OFFSET (emccanon.cc
#: rotate_and_offset_pos: X Y plus G92, rotated, plus the work offset) [inch].
EXPECTED_G10_ROTATION = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 1.0, 0.0), (-1.0, 1.0, 0.0), (0.0, 0.0, 0.0)]


def test_g10_l2_rotation_while_active_matches_linuxcnc():
    prog = parse_program(PROGRAM_G10_ROTATION, context=MachineContext())
    got = [tuple(round(v / INCH, 4) + 0.0 for v in b.target) for b in prog.blocks]
    assert got == EXPECTED_G10_ROTATION
