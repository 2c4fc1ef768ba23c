"""vcnc's ``linuxcnc`` dialect against LinuxCNC's own interpreter on generated programs: the differences that
``benchmarks/linuxcnc_diff.py --generate`` (programs of ``benchmarks/linuxcnc_fuzz.py``) found, shrunk to a few
lines. The expected end points are rs274 2.9.0~pre1 output (the Debian package linuxcnc-uspace, ``rs274 -g``)
written out (STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED end points, G21: mm), so that the tests need no rs274.
"""

from __future__ import annotations

import numpy as np

from benchmarks.linuxcnc_fuzz import FEATURES, generate
from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"], linear_units="inch", extra_axes=("a", "b", "c"))


def _ends(prog) -> list[tuple]:
    return [(b.kind, *(round(float(v), 4) + 0.0 for v in b.target)) for b in prog.blocks if b.kind != "dwell"]


def test_g89_feeds_out_to_the_clear_level():
    """LinuxCNC's G89 feeds out to the clear level (interp_cycles.cc ``convert_cycle_g89``: ``cycle_feed`` to
    ``clear_z``; g-code.adoc G89: "Retract the Z-axis at the current feed rate to clear Z"), with G98 the
    initial level, not to R and a rapid on. rs274 2.9.0~pre1: STRAIGHT_TRAVERSE(5, 5, 10), (5, 5, 2),
    STRAIGHT_FEED(5, 5, -3), STRAIGHT_FEED(5, 5, 10), then the same at X10."""
    prog = parse_program("G21 G17 G90\nG0 X0 Y0 Z10\nM3 S1000\nG98 G89 X5 Y5 R2 Z-3 P0.5 F100\nX10\nG80\nM2\n",
                         context=LINUXCNC)
    hole = [("rapid", 5.0, 5.0, 10.0), ("rapid", 5.0, 5.0, 2.0), ("line", 5.0, 5.0, -3.0), ("line", 5.0, 5.0, 10.0)]
    second = [(k, 10.0 if x == 5.0 else x, y, z) for k, x, y, z in hole]
    assert _ends(prog) == [("rapid", 0.0, 0.0, 10.0), *hole, *second]


def test_g89_under_fanuc_still_feeds_out_to_r():
    """The Fanuc dialect keeps its G89: feed out to R, then a rapid to the initial level (G98)."""
    fanuc = MachineContext(dialect=DIALECTS["fanuc"])
    prog = parse_program("G21 G17 G90\nG0 X0 Y0 Z10\nM3 S1000\nG98 G89 X5 Y5 R2 Z-3 P500 F100\nG80\nM30\n",
                         context=fanuc)
    assert _ends(prog)[-2:] == [("line", 5.0, 5.0, 2.0), ("rapid", 5.0, 5.0, 10.0)]


def test_the_generator_is_reproducible_and_vcnc_reads_its_programs():
    """The same seed gives the same program; every feature group's programs are read by vcnc's linuxcnc
    dialect without an error (rs274 accepts them too: ``linuxcnc_diff.py --generate``)."""
    assert generate(7) == generate(7)
    assert generate(7)[0] != generate(8)[0]
    for k, group in enumerate(FEATURES):
        text, used = generate(100 + k, features=(group,))
        assert set(used) == {group}
        assert parse_program(text, context=LINUXCNC).blocks


def test_an_inside_corner_after_a_nearly_straight_one_is_on_the_programmed_offset_line():
    """G41.1: a turn of 0.048 rad at X2.519 (under LinuxCNC's 0.05, no corner arc: the next line starts where the
    tool is, a little off its programmed direction), then an inside corner at X17.878. LinuxCNC backs off from
    the tool's offset end along the programmed direction by r / tan(half the corner) (interp_convert.cc
    ``convert_straight_comp2``, line -> line), which puts the corner on the programmed offset line. rs274
    2.9.0~pre1: STRAIGHT_FEED(2.5528, -24.4539), STRAIGHT_FEED(16.4725, -24.1179), STRAIGHT_FEED(16.4725,
    -1.5340); vcnc had -24.1180 (the intersection with the line the tool runs)."""
    prog = parse_program("G21 G17 G90\nG0 X-20 Y-30 Z0\nG1 F250\nG41.1 D2.811\nG1 X-12.841 Y-25.49\n"
                         "G1 X2.519 Y-25.859\nG1 X17.878 Y-25.49\nG1 X17.878 Y-1.534\nG40\nG0 X30 Y-40\nM2\n",
                         context=LINUXCNC)
    ends = _ends(prog)
    assert ends[0] == ("rapid", -20.0, -30.0, 0.0) and ends[1] == ("line", -13.5902, -24.3008, 0.0)
    assert ends[2][0].startswith("arc") and ends[2][1:] == (-12.8072, -24.0849, 0.0)
    assert ends[3:] == [("line", 2.5528, -24.4539, 0.0), ("line", 16.4725, -24.1179, 0.0),
                        ("line", 16.4725, -1.534, 0.0), ("rapid", 30.0, -40.0, 0.0)]


def test_a_spline_under_a_g10_rotation_turns_with_the_coordinate_system():
    """G5.1 under ``G10 L2 P1 R90``: LinuxCNC builds the spline in program coordinates and turns the arcs it
    makes of it (emccanon.cc ``NURBS_FEED``: ``biarc`` -> ARC_FEED, rotated as every move); vcnc refused it.
    The quadratic Bezier from (0, 0) over (0, 10) to (10, 0), turned by 90 degrees: from (0, 0) over (-10, 0)
    to (0, 10); its point at t = 1/2, (2.5, 5) turned, is (-5, 2.5). rs274 2.9.0~pre1 ends it at the
    programmed end: the next move, ``G1 X12``, is STRAIGHT_FEED(12.0000, 0.0000, ...), (0, 12) in machine X Y."""
    prog = parse_program("G21 G17 G90\nG10 L2 P1 X0 Y0 R90\nG54\nG0 X0 Y0 Z0\nG1 F100\nG5.1 I0 J10 X10 Y0\n"
                         "G1 X12\nM2\n", context=LINUXCNC)
    chords = np.array([b.target[:2] for b in prog.blocks if b.line == 6])
    assert np.allclose(chords[-1], [0.0, 10.0], atol=1e-9)
    t = np.linspace(0.0, 1.0, 200_001)[:, None]
    curve = 2 * (1 - t) * t * np.array([-10.0, 0.0]) + t**2 * np.array([0.0, 10.0])
    assert np.min(np.linalg.norm(curve - [-5.0, 2.5], axis=1)) < 1e-9
    assert max(np.min(np.linalg.norm(curve - c, axis=1)) for c in chords) < 0.002
    assert _ends(prog)[-1] == ("line", 0.0, 12.0, 0.0)


def test_loops_linuxcnc_runs_otherwise_are_noted():
    """A ``break`` on a ``repeat`` loop's label: rs274 2.9.0~pre1 refuses it ("4: no matching while/do label",
    interp_o_word.cc; o-code.adoc lists it among the errors), vcnc leaves the loop and says so. A ``do`` loop
    after a ``break`` out of a ``while`` loop: rs274 runs its body once (the break flag ``doing_break`` stays set
    until a do loop's closing while) where o-code.adoc has it loop while the condition holds: vcnc runs it twice
    (X2, X4) and says so."""
    repeat = parse_program("G21\no10 repeat [3]\nG91 G1 X1 F100\no10 break\no10 endrepeat\nM2\n", context=LINUXCNC)
    assert _ends(repeat) == [("line", 1.0, 0.0, 0.0)]
    assert any("o10 break in a repeat loop" in n and "LinuxCNC refuses" in n for n in repeat.notes)
    after = parse_program("G21\n#<i> = 0\no1 while [#<i> LT 2]\no1 break\no1 endwhile\no2 do\nG91 G1 X2 F100\n"
                          "#<i> = [#<i> + 1]\no2 while [#<i> LT 2]\nM2\n", context=LINUXCNC)
    assert _ends(after) == [("line", 2.0, 0.0, 0.0), ("line", 4.0, 0.0, 0.0)]
    assert any("o2 do loop after a break" in n for n in after.notes)
    plain = parse_program("G21\n#<i> = 0\no2 do\nG91 G1 X2 F100\n#<i> = [#<i> + 1]\no2 while [#<i> LT 2]\nM2\n",
                          context=LINUXCNC)
    assert _ends(plain) == _ends(after) and not any("O-word" in n for n in plain.notes)


def test_turns_of_a_g19_arc_under_a_g10_rotation():
    """``G3 J1 K0.5 P2`` in G19 under ``G10 L2 P1 R30``: LinuxCNC runs two full turns (rs274 2.9.0~pre1:
    ARC_FEED(1.0000, 0.0000, 2.0000, 0.5000, 2, 1.0000, ...)), then ``G3 Y3 Z0 X2 J1 K0 P3`` half a turn and two
    more along X to Y3 (ARC_FEED(3.0000, 0.0000, 2.0000, 0.0000, 3, 2.0000, ...)); vcnc, which runs such arcs as
    chords in program coordinates, refused their P ("word P needs G04 ..."). The chords' lengths: 2 turns of
    radius sqrt(1.25), 2.5 turns of radius 1 rising 1 along X."""
    prog = parse_program("G21 G90\nG10 L2 P1 X3 Y2 R30\nG54\nG0 X1 Y1 Z0\nG1 F100\nG19\nG3 J1 K0.5 P2\n"
                         "G3 Y3 Z0 X2 J1 K0 P3\nG17\nG1 X0 Y0\nM2\n", context=LINUXCNC)
    lengths = [sum(b.segment.length for b in prog.blocks if b.line == n) for n in (7, 8)]
    assert np.allclose(lengths, [4 * np.pi * np.sqrt(1.25), np.hypot(5 * np.pi, 1.0)], rtol=1e-3)
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))
    end = [b for b in prog.blocks if b.line == 8][-1].target
    assert np.allclose(end, [3 + 2 * c - 3 * s, 2 + 2 * s + 3 * c, 0.0], atol=1e-9)


def test_rigid_tapping_under_a_g10_rotation():
    """``G33.1`` under ``G10 L2 P1 X5 Y2 Z1 R30``: rs274 2.9.0~pre1 taps (RIGID_TAP(4.0000, 3.0000, -3.0000),
    then RIGID_TAP(6.0000, 1.0000, -2.0000)) in program coordinates, which LinuxCNC's canon turns and offsets as
    every move (emccanon.cc ``rotate_and_offset_pos``); vcnc refused G33.1 in a rotated coordinate system. Each
    tap goes to its point and back to where it began."""
    prog = parse_program("G21 G17 G90\nG10 L2 P1 X5 Y2 Z1 R30\nG54\nG0 X4 Y3 Z5\nM3 S500\nG33.1 Z-3 K1\n"
                         "G33.1 X6 Y1 Z-2 K1.25\nG0 Z10\nM2\n", context=LINUXCNC)
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))
    top = (round(4 * c - 3 * s + 5, 4), round(4 * s + 3 * c + 2, 4))
    side = (round(6 * c - s + 5, 4), round(6 * s + c + 2, 4))
    assert _ends(prog) == [("rapid", *top, 6.0), ("line", *top, -2.0), ("line", *top, 6.0), ("line", *side, -1.0),
                           ("line", *top, 6.0), ("rapid", *top, 11.0)]


def test_a_drilling_cycle_under_a_g10_rotation():
    """``G81`` under ``G10 L2 P1 X5 Y2 Z1 R30``, then two more holes by ``G91 X2 Y2 L2``: LinuxCNC runs the cycle
    in program coordinates (interp_cycles.cc) and its canon turns each move (emccanon.cc
    ``rotate_and_offset_pos``); vcnc refused cycles under G10 R. rs274 2.9.0~pre1 (program coordinates):
    STRAIGHT_TRAVERSE(10, 3, 5), (10, 3, 2), STRAIGHT_FEED(10, 3, -3), STRAIGHT_TRAVERSE(10, 3, 5); under G91 the
    sticky R2 Z-3 are increments (R at 7, the bottom at 4): STRAIGHT_TRAVERSE(10, 3, 7), (12, 5, 7),
    STRAIGHT_FEED(12, 5, 4), STRAIGHT_TRAVERSE(12, 5, 7), (14, 7, 7), STRAIGHT_FEED(14, 7, 4),
    STRAIGHT_TRAVERSE(14, 7, 7)."""
    prog = parse_program("G21 G17 G90\nG10 L2 P1 X5 Y2 Z1 R30\nG54\nG0 X4 Y3 Z5\nG98 G81 X10 Y3 R2 Z-3 F100\n"
                         "G91 X2 Y2 L2\nG90 G80\nM2\n", context=LINUXCNC)
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))

    def machine(kind, x, y, z):
        return kind, round(x * c - y * s + 5, 4), round(x * s + y * c + 2, 4), z + 1.0

    want = [machine("rapid", 4, 3, 5), machine("rapid", 10, 3, 5), machine("rapid", 10, 3, 2),
            machine("line", 10, 3, -3), machine("rapid", 10, 3, 5), machine("rapid", 10, 3, 7)]
    for x, y in ((12, 5), (14, 7)):
        want += [machine("rapid", x, y, 7), machine("line", x, y, 4), machine("rapid", x, y, 7)]
    assert _ends(prog) == want


def test_g84_in_g18_taps_along_y_and_notes_linuxcnc_s_order():
    """``G99 G84 Z1 X2 R5 Y0`` in G18 taps along Y at X2 Z1 (g-code.adoc "G84": the cycles in G18 drill along Y).
    rs274 2.9.0~pre1 rapids there, STRAIGHT_TRAVERSE(2, 10, 1), (2, 5, 1), then feeds to STRAIGHT_FEED(0, 1, 2)
    and (5, 1, 2): interp_cycles.cc ``convert_cycle_g74_g84`` hands the plane's coordinates to ``cycle_feed`` in
    another order than every other cycle (LinuxCNC 2.9 and master). vcnc taps as documented and says so."""
    prog = parse_program("G21 G18 G90\nM3 S500\nG0 X0 Y10 Z0\nG99 G84 Z1 X2 R5 Y0 F100\nG80\nM2\n", context=LINUXCNC)
    assert _ends(prog) == [("rapid", 0.0, 10.0, 0.0), ("rapid", 2.0, 10.0, 1.0), ("rapid", 2.0, 5.0, 1.0),
                           ("line", 2.0, 0.0, 1.0), ("line", 2.0, 5.0, 1.0)]
    assert any(n.startswith("G84 tapping cycle in G18: tapped along") for n in prog.notes)
    g17 = parse_program("G21 G17 G90\nM3 S500\nG0 X0 Y0 Z10\nG99 G84 X2 Y1 R5 Z0 F100\nG80\nM2\n", context=LINUXCNC)
    assert not any("G84" in n for n in g17.notes)


def test_a_g19_cycle_series_under_a_g10_rotation_keeps_its_initial_level_in_program_x():
    """G19 drills along X; under ``G10 L2 P1 R-45`` program X is no machine axis. LinuxCNC keeps the series'
    initial level in program coordinates (interp_cycles.cc ``cycle_il``): rs274 2.9.0~pre1 prints, in program
    coordinates, STRAIGHT_TRAVERSE(5, 1, 2), (3, 1, 2), STRAIGHT_FEED(-2, 1, 2), STRAIGHT_TRAVERSE(5, 1, 2),
    then for ``Y2 Z4`` (5, 2, 4), (3, 2, 4), STRAIGHT_FEED(-2, 2, 4), STRAIGHT_TRAVERSE(5, 2, 4); vcnc kept the
    level as a machine X and retracted the second hole elsewhere."""
    prog = parse_program("G21 G90\nG10 L2 P1 R-45\nG54 G19\nG0 X5 Y0 Z0\nG98 G81 Y1 Z2 R3 X-2 F100\nY2 Z4\nG80\nM2\n",
                         context=LINUXCNC)
    c, s = np.cos(np.radians(-45)), np.sin(np.radians(-45))

    def machine(kind, x, y, z):
        return kind, round(x * c - y * s, 4) + 0.0, round(x * s + y * c, 4) + 0.0, float(z)

    want = [machine("rapid", 5, 0, 0)]
    for y, z in ((1, 2), (2, 4)):
        want += [machine("rapid", 5, y, z), machine("rapid", 3, y, z), machine("line", -2, y, z),
                 machine("rapid", 5, y, z)]
    assert _ends(prog) == want


def test_polar_words_under_a_g10_rotation():
    """``@ ^`` under ``G10 L2 P1 X5 Y2 R30``: LinuxCNC reads them in the (rotated) program coordinates
    (interp_find.cc ``find_ends``) and its canon turns the point; vcnc refused them. rs274 2.9.0~pre1 (program
    coordinates): STRAIGHT_FEED(7.0711, 7.0711, 5), (3.1058, 11.5911, 5) for ``G91 @2 ^30``, a rapid to
    (11.5911, -3.1058, 5) for ``^-90``, STRAIGHT_FEED(4.8296, -1.2941, 2) for ``G90 @5 Z2``."""
    prog = parse_program("G21 G17 G90\nG10 L2 P1 X5 Y2 R30\nG54\nG0 X4 Y3 Z5\nG1 @10 ^45 F100\nG91 G1 @2 ^30\n"
                         "G0 ^-90\nG90 G1 @5 Z2\nM2\n", context=LINUXCNC)
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))

    def machine(kind, x, y, z):
        return kind, round(x * c - y * s + 5, 4), round(x * s + y * c + 2, 4), float(z)

    got = _ends(prog)
    want = [machine("rapid", 4, 3, 5), machine("line", 7.0711, 7.0711, 5), machine("line", 3.1058, 11.5911, 5),
            machine("rapid", 11.5911, -3.1058, 5), machine("line", 4.8296, -1.2941, 2)]
    assert [g[0] for g in got] == [w[0] for w in want]
    assert np.allclose([g[1:] for g in got], [w[1:] for w in want], atol=2e-4)


def test_every_feed_move_after_a_repeated_g94_has_a_feed():
    """``chunk_inverse_time`` writes G94 again while G94 is on (LinuxCNC clears the feed: interp_convert.cc
    ``convert_feed_mode``); the next feed move must carry its F, or rs274 and vcnc both refuse the program ("Cannot
    do g1 with zero feed rate") and nothing after it is compared. It did not, 1 time in 7 (``linuxcnc_diff.py
    --generate``: 'both refuse' 354990, 355969, ...; 10 of seeds 0-299 of this chunk alone). The refusal itself is
    test_reader_fast_g93's "G94 again without F"."""
    for seed in range(300):
        text, _ = generate(seed, features=("inverse_time",), chunks=(1, 1))
        assert parse_program(text, context=LINUXCNC).blocks, seed
