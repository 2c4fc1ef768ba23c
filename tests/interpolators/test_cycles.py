"""Drilling canned cycles (:func:`interpolators.iso_cycles.cycle_moves`): exact move lists against LinuxCNC 2.9.

Expected moves follow LinuxCNC's G-code reference ("Canned Cycles": preliminary motion, G98/G99,
L repeats under G91) and ``src/emc/rs274ngc/interp_cycles.cc`` (``convert_cycle_g83``: feed to
``r - q``, rapid to R, rapid down to ``G83_RAPID_DELTA`` = 0.010 in = 0.254 mm above the last
depth; G73 retracts by the same delta), with K as Fanuc's and Haas's repeat word.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from interpolators.iso_cycles import CycleError, CycleWords, cycle_moves
from vcnc.errors import GCodeError

INF = math.inf
D = 0.254  # G83_RAPID_DELTA 0.010 in [mm]


def _moves(g: int, words: dict[str, float], *, pos=(0.0, 0.0, 10.0), g99: bool = False, incremental: bool = False,
           feed: float = 2.0, p_ms: bool = False, scale: float = 1.0) -> list[tuple]:
    out = cycle_moves(g, words, cycle=CycleWords(), pos=np.array(pos, dtype=float), offset=np.zeros(3), scale=scale,
                      incremental=incremental, retract_r=g99, feed=feed, dwell_p_ms=p_ms)
    return [(m.kind, *np.round(m.target, 9).tolist(), m.feed, m.dwell) for m in out]


def test_g81_g98_returns_to_initial_level_g99_to_r():
    words = {"X": 1.0, "Y": 1.0, "Z": -2.0, "R": 2.0}
    into = [("rapid", 1, 1, 10, INF, 0), ("rapid", 1, 1, 2, INF, 0), ("line", 1, 1, -2, 2.0, 0)]
    assert _moves(81, words) == [*into, ("rapid", 1, 1, 10, INF, 0)]
    assert _moves(81, words, g99=True) == [*into, ("rapid", 1, 1, 2, INF, 0)]


def test_preliminary_rapid_up_to_r_when_below_it():
    # start below R: rapid up to R first; G98 then returns to max(R, initial Z) = R
    assert _moves(81, {"X": 1.0, "Y": 0.0, "Z": -2.0, "R": 2.0}, pos=(0.0, 0.0, 0.0)) == [
        ("rapid", 0, 0, 2, INF, 0), ("rapid", 1, 0, 2, INF, 0), ("line", 1, 0, -2, 2.0, 0), ("rapid", 1, 0, 2, INF, 0)]


def test_g82_dwells_at_the_bottom_in_seconds_or_milliseconds():
    expected = [("rapid", 0, 0, 1, INF, 0), ("line", 0, 0, -1, 2.0, 0), ("dwell", 0, 0, -1, 0.0, 0.5),
                ("rapid", 0, 0, 10, INF, 0)]
    assert _moves(82, {"X": 0.0, "Y": 0.0, "Z": -1.0, "R": 1.0, "P": 0.5}) == expected
    assert _moves(82, {"X": 0.0, "Y": 0.0, "Z": -1.0, "R": 1.0, "P": 500.0}, p_ms=True) == expected


@pytest.mark.parametrize(("dialect", "noted"), [("linuxcnc", True), ("grbl", True), ("fanuc", False), ("haas", False)])
def test_long_whole_second_dwells_are_noted_where_p_is_seconds(dialect, noted):
    # G04 P500 and G82 P500 from a Fanuc/Haas post (500 ms) dwell 500 s where P is seconds (LinuxCNC g-code.adoc
    # G4 "P- seconds"): read so, with a note naming the dialects that read P in ms; P0.5 and P59 get none
    text = "G21 G90 G54 F100\nG0 X0 Y0 Z5\nG4 P500\nG82 X1 Y1 Z-1 R1 P500\nG80\nM30\n"
    if dialect == "grbl":
        text = text.replace("G82 X1 Y1 Z-1 R1 P500\nG80\n", "")
    prog = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
    dwells = [b.dwell for b in prog.blocks if b.kind == "dwell"]
    assert dwells == ([500.0] * len(dwells) if dialect in ("linuxcnc", "grbl") else [0.5] * len(dwells))
    assert any("dwell P of 60 or more read as seconds" in n for n in prog.notes) == noted
    short = parse_program("G21 G90 G54\nG4 P0.5\nG4 P59\nM30\n", context=MachineContext())
    assert [b.dwell for b in short.blocks] == [0.5, 59.0] and not any("dwell P" in n for n in short.notes)
    odd = parse_program("G21 G90 G54\nG4 P60.5\nM30\n", context=MachineContext())
    assert not any("dwell P" in n for n in odd.notes)  # a decimal point: written as seconds


def test_g83_full_retract_pecks():
    assert _moves(83, {"X": 0.0, "Y": 0.0, "Z": -2.5, "R": 1.0, "Q": 1.0}, pos=(0.0, 0.0, 5.0), feed=1.0) == [
        ("rapid", 0, 0, 1, INF, 0),
        ("line", 0, 0, 0, 1.0, 0), ("rapid", 0, 0, 1, INF, 0), ("rapid", 0, 0, D, INF, 0),
        ("line", 0, 0, -1, 1.0, 0), ("rapid", 0, 0, 1, INF, 0), ("rapid", 0, 0, -1 + D, INF, 0),
        ("line", 0, 0, -2, 1.0, 0), ("rapid", 0, 0, 1, INF, 0), ("rapid", 0, 0, -2 + D, INF, 0),
        ("line", 0, 0, -2.5, 1.0, 0), ("rapid", 0, 0, 5, INF, 0)]


def test_g73_chip_break_pecks():
    assert _moves(73, {"X": 0.0, "Y": 0.0, "Z": -2.5, "R": 1.0, "Q": 1.0}, pos=(0.0, 0.0, 5.0), feed=1.0,
                  g99=True) == [
        ("rapid", 0, 0, 1, INF, 0),
        ("line", 0, 0, 0, 1.0, 0), ("rapid", 0, 0, D, INF, 0),
        ("line", 0, 0, -1, 1.0, 0), ("rapid", 0, 0, -1 + D, INF, 0),
        ("line", 0, 0, -2, 1.0, 0), ("rapid", 0, 0, -2 + D, INF, 0),
        ("line", 0, 0, -2.5, 1.0, 0), ("rapid", 0, 0, 1, INF, 0)]


def test_g85_and_g89_feed_out_to_r():
    words = {"X": 0.0, "Y": 0.0, "Z": -1.0, "R": 1.0}
    assert _moves(85, words) == [("rapid", 0, 0, 1, INF, 0), ("line", 0, 0, -1, 2.0, 0), ("line", 0, 0, 1, 2.0, 0),
                                 ("rapid", 0, 0, 10, INF, 0)]
    assert _moves(89, {**words, "P": 0.25}, g99=True) == [
        ("rapid", 0, 0, 1, INF, 0), ("line", 0, 0, -1, 2.0, 0), ("dwell", 0, 0, -1, 0.0, 0.25),
        ("line", 0, 0, 1, 2.0, 0)]


@pytest.mark.parametrize("repeat", ["L", "K"])
def test_incremental_repeats_step_in_xy(repeat):
    # LinuxCNC's G81 example with L: G91 R from the start Z, Z from R, X Y stepped per repeat
    moves = _moves(81, {"X": 2.0, "Y": 1.0, "R": -4.0, "Z": -3.0, repeat: 3.0}, pos=(0.0, 0.0, 5.0), incremental=True)
    expected = []
    for k in (1, 2, 3):
        expected += [("rapid", 2 * k, k, 5, INF, 0), ("rapid", 2 * k, k, 1, INF, 0), ("line", 2 * k, k, -2, 2.0, 0),
                     ("rapid", 2 * k, k, 5, INF, 0)]
    assert moves == expected


def test_inch_words_scaled_but_peck_clearance_stays_0_010_in():
    moves = _moves(83, {"X": 0.0, "Y": 0.0, "Z": -0.1, "R": 0.0, "Q": 0.06}, pos=(0.0, 0.0, 0.0), feed=1.0,
                   scale=25.4, g99=True)
    assert moves == [("line", 0, 0, -1.524, 1.0, 0), ("rapid", 0, 0, 0, INF, 0), ("rapid", 0, 0, -1.524 + D, INF, 0),
                     ("line", 0, 0, -2.54, 1.0, 0), ("rapid", 0, 0, 0, INF, 0)]


@pytest.mark.parametrize(("g", "words", "match"), [
    (83, {"Z": -1.0, "R": 1.0}, "peck depth Q must be > 0"),
    (73, {"Z": -1.0, "R": 1.0, "Q": 0.0}, "peck depth Q must be > 0"),
    (81, {"Z": -1.0}, "no R"),
    (81, {"R": 1.0}, "no Z"),
    (81, {"Z": 2.0, "R": 1.0}, "above the R plane"),
    (81, {"Z": -1.0, "R": 1.0, "L": 1.5}, "repeat count"),
])
def test_invalid_words_are_named(g, words, match):
    with pytest.raises(CycleError, match=match):
        _moves(g, {"X": 0.0, "Y": 0.0, **words})


def _series(blocks: list[dict[str, float]], *, pos, g99: bool, incremental: bool) -> list[tuple]:
    """Moves of consecutive cycle blocks of one series (one CycleWords), each from where the last ended."""
    cycle, cur, out = CycleWords(), np.array(pos, dtype=float), []
    for words in blocks:
        moves = cycle_moves(81, words, cycle=cycle, pos=cur, offset=np.zeros(3), scale=1.0, incremental=incremental,
                            retract_r=g99, feed=2.0, dwell_p_ms=False)
        out += [(m.kind, *np.round(m.target, 9).tolist()) for m in moves]
        cur = moves[-1].target
    return out


def test_later_blocks_of_a_series_use_the_initial_level_as_linuxcnc():
    """interp_cycles.cc convert_cycle_xy: under G91, R is an increment from the series' initial level
    (cycle_il), not from the current Z (G99 left the tool at R1.5 after the first hole, yet the second
    hole's R is 1 + 0.5 again); and CYCLE_MACRO goes to a hole at the clear level when the tool is not
    above R (the second G90 block, R raised to 2 from R1, rapids straight from (1, 0, 1) to (2, 0, 2))."""
    assert _series([{"X": 1.0, "Z": -1.0, "R": 0.5}, {"X": 1.0}], pos=(0, 0, 1), g99=True, incremental=True) == [
        ("rapid", 0, 0, 1.5), ("rapid", 1, 0, 1.5), ("line", 1, 0, 0.5), ("rapid", 1, 0, 1.5),
        ("rapid", 2, 0, 1.5), ("line", 2, 0, 0.5), ("rapid", 2, 0, 1.5)]
    assert _series([{"X": 1.0, "Z": -1.0, "R": 1.0}, {"X": 2.0, "R": 2.0}], pos=(0, 0, 3), g99=True,
                   incremental=False) == [
        ("rapid", 1, 0, 3), ("rapid", 1, 0, 1), ("line", 1, 0, -1), ("rapid", 1, 0, 1),
        ("rapid", 2, 0, 2), ("line", 2, 0, -1), ("rapid", 2, 0, 2)]


def test_g84_feeds_out_to_the_clear_level_or_to_r_by_dialect():
    """LinuxCNC's G84 feeds out to the clear level (interp_cycles.cc convert_cycle_g74_g84); Fanuc's
    and Haas's feed out to R and rapid to the initial level under G98 (Haas "G84 Tapping Canned
    Cycle"); both dwell P at the bottom."""
    words = {"X": 1.0, "Y": 0.0, "Z": -2.0, "R": 2.0, "P": 0.5}
    into = [("rapid", 1, 0, 10, INF, 0), ("rapid", 1, 0, 2, INF, 0), ("line", 1, 0, -2, 2.0, 0),
            ("dwell", 1, 0, -2, 0.0, 0.5)]
    assert _moves(84, words) == [*into, ("line", 1, 0, 10, 2.0, 0)]
    out = cycle_moves(84, words, cycle=CycleWords(), pos=np.array([0.0, 0.0, 10.0]), offset=np.zeros(3), scale=1.0,
                      incremental=False, retract_r=False, feed=2.0, dwell_p_ms=False, tap_out_to_r=True)
    assert [(m.kind, *m.target.tolist(), m.feed, m.dwell) for m in out] == [
        *into, ("line", 1, 0, 2, 2.0, 0), ("rapid", 1, 0, 10, INF, 0)]


@pytest.mark.parametrize(("spindle", "message"), [("", "G84 tapping cycle with the spindle not turning"),
                                                  ("S100 M4\n", "turning counter-clockwise \\(M4\\)"),
                                                  ("S100 M3\nM5\n", "with the spindle not turning")])
def test_linuxcnc_refuses_g84_unless_the_spindle_turns_clockwise(spindle, message):
    """interp_cycles.cc check_g74_g84_spindle: "Spindle not turning in G84", "Spindle turning
    counterclockwise in G84" (M5 stops it); Fanuc and Haas reverse the spindle themselves and tap."""
    program = "G21 G90 G98\nG0 X0 Y0 Z10\n{}G84 X5 Y5 Z-3 R2 F125\nG80\n"
    text = program.format(spindle)
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=MachineContext())
    for dialect in ("fanuc", "haas"):
        prog = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]))
        assert [b.target[2] for b in prog.blocks if b.kind == "line"] == [-3.0, 2.0]  # in, out to R
    # M3: LinuxCNC taps (feed in to Z-3, feed out to the clear level Z10)
    prog = parse_program(program.format("S100 M3\n"), context=MachineContext())
    assert [b.target[2] for b in prog.blocks if b.kind == "line"] == [-3.0, 10.0]


def _ends(text: str, context: MachineContext) -> list[tuple]:
    prog = parse_program(text, context=context)
    return [(b.kind, *(round(float(v), 6) + 0.0 for v in b.target)) for b in prog.blocks]


def test_cycle_series_with_g68_rotation_changing_between_holes():
    """Fanuc 0i "Coordinate system rotation (G68)": the hole X Y of each block turns about the G68 centre
    by the angle in force; Z levels are along the tool and do not turn. The initial level is where the
    tool was when the series began (machine Z -10 with G54 Z-20), whatever rotation follows: every G98
    hole returns there. Holes: (10, 0); R90 -> (0, 10); R180 -> (-10, 0); G69 -> (20, 0), plus G54 (100, 50)."""
    ctx = MachineContext(dialect=DIALECTS["fanuc"], work_offsets={"G54": (100.0, 50.0, -20.0)})
    text = ("G21 G90 G17 G54\nG0 X0 Y0 Z10\nG98 G81 X10 Y0 Z-5 R2 F100\nG68 X0 Y0 R90\nX10 Y0\nG68 X0 Y0 R180\n"
            "X10 Y0\nG69\nX20 Y0\nG80\n")
    holes = [(110, 50), (100, 60), (90, 50), (120, 50)]
    want = [("rapid", 100, 50, -10)]
    for x, y in holes:
        want += [("rapid", x, y, -10), ("rapid", x, y, -18), ("line", x, y, -25), ("rapid", x, y, -10)]
    assert _ends(text, ctx) == want


def test_cycle_series_under_g99_and_g91_in_a_rotated_system():
    """G68 R90 about X0 Y0 before the series: G91 X10 steps along the rotated X, i.e. +10 along machine Y
    (under G91 R is from the initial level and Z from R: R-8 Z-7 are the same levels, program R2 Z-5);
    G99 returns to R (machine -18); the R45 rotation that follows turns the next absolute hole (10, 0) to
    (7.071068, 7.071068)."""
    ctx = MachineContext(dialect=DIALECTS["fanuc"], work_offsets={"G54": (100.0, 50.0, -20.0)})
    text = ("G21 G90 G17 G54\nG0 X0 Y0 Z10\nG68 X0 Y0 R90\nG99 G81 X10 Y0 Z-5 R2 F100\nG91 X10 R-8 Z-7\n"
            "G90 G68 X0 Y0 R45\nX10 Y0 Z-5 R2\nG80\n")
    s = 10 * math.sqrt(0.5)
    holes = [(100, 60), (100, 70), (100 + s, 50 + s)]
    got = _ends(text, ctx)
    assert got[0] == ("rapid", 100, 50, -10)
    assert got[1:5] == [("rapid", 100, 60, -10), ("rapid", 100, 60, -18), ("line", 100, 60, -25),
                        ("rapid", 100, 60, -18)]
    for (x, y), i in zip(holes[1:], (5, 8), strict=True):
        assert [k for k, *_ in got[i:i + 3]] == ["rapid", "line", "rapid"]
        assert np.allclose([p for _, *p in got[i:i + 3]], [(x, y, -18), (x, y, -25), (x, y, -18)], atol=1e-9)


def test_cycle_series_under_g51_scaling():
    """Haas "G51 Scaling": "all X, Y, Z, I, J, K, or R values addressing machine motion are multiplied by a
    scaling factor" about the centre. G51 X0 Y0 Z0 P2 (Fanuc P2000: 0.001 units) with G54 (100, 50, -20):
    hole X10 -> X20, R2 -> 4, Z-5 -> -10 (machine 120, R -16, bottom -30); X-10 Y5 -> (-20, 10), machine
    (80, 60). The initial level is where the tool stood when the series began (program Z10 before the
    scaling: machine -10), the G98 return. After G80 G50 a G85 runs unscaled (R -18, bottom -25)."""
    for dialect, p in (("fanuc", "P2000"), ("haas", "P2.")):
        ctx = MachineContext(dialect=DIALECTS[dialect], work_offsets={"G54": (100.0, 50.0, -20.0)})
        text = (f"G21 G90 G17 G54\nG0 X0 Y0 Z10\nG51 X0 Y0 Z0 {p}\nG98 G81 X10 Y0 Z-5 R2 F100\nX-10 Y5\nG80\n"
                "G50\nG99 G85 X20 Y0 Z-5 R2\nG80\n")
        want = [("rapid", 100, 50, -10)]
        for x, y in ((120, 50), (80, 60)):
            want += [("rapid", x, y, -10), ("rapid", x, y, -16), ("line", x, y, -30), ("rapid", x, y, -10)]
        want += [("rapid", 120, 50, -10), ("rapid", 120, 50, -18), ("line", 120, 50, -25), ("line", 120, 50, -18)]
        assert _ends(text, ctx) == want


@pytest.mark.parametrize(("program", "message"), [
    ("G98 G81 X10 Y0 Z-5 R2 F100\nG51 X0 Y0 Z0 P2000\nX10 Y0\n", "the G51 scaling changed within the series"),
    ("G51 X0 Y0 Z0 P2000\nG98 G81 X10 Y0 Z-5 R2 F100\nG50\nX10 Y0\n", "the G51 scaling changed within the series"),
    ("G51 X0 Y0 Z0 P2000\nG98 G83 X10 Y0 Z-5 R2 Q1 F100\n", "G83 peck drilling cycle in a rotated coordinate "
                                                              "system \\(G51 scaling\\)"),
])
def test_cycles_under_g51_scaling_refused_where_undefined(program, message):
    """A scaling that changes within a series leaves the initial level undefined; G73/G83 pecks Q and
    G76/G87 shifts are not scaled by Fanuc (0i "Scaling") while the reader would scale them: errors."""
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90 G17\nG0 X0 Y0 Z10\n{program}", context=MachineContext(dialect=DIALECTS["fanuc"]))
