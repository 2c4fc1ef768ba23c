"""Simultaneous 5-axis tool centre point control on a tilting table (interpolators/tcp.py, heidenhain_tcpm.py,
iso_tcp.py): hand-written programs whose rotary axes move under M128 / FUNCTION TCPM / G43.4 / G234. The
interpolated setpoints are mapped back to the part (``Kinematics.unplace``) and the tool tip checked against
the programmed line; end points against the table's map worked out here; the feed against tip length / F."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import interpolators.tcp
from interpolators import AxisLimits, interpolate
from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.iso import parse_iso
from interpolators.lookahead import DEFAULT_TOLERANCE
from interpolators.tilted import Kinematics, RotaryAxis, Solution
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

LENGTH = 20.0
#: B tilts about Y round (0, 0, -50), C turns about Z through the machine zero.
BC = Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)), RotaryAxis(name="c")))
#: A tilts about X round (0, 0, -80), C turns about Z through (5, 0, 0).
AC = Kinematics(axes=(RotaryAxis(name="a", pivot=(0.0, 0.0, -80.0), limits=(-120.0, 120.0)),
                      RotaryAxis(name="c", pivot=(5.0, 0.0, 0.0))))
PRESET = (10.0, 5.0, 0.0)
TNC = MachineContext(extra_axes=("b", "c"), kinematics=BC, tools={1: Tool(number=1, length=LENGTH)},
                     work_offsets={"G54": PRESET})
FANUC = MachineContext(extra_axes=("a", "c"), kinematics=AC, tools={1: Tool(number=1, length=LENGTH)},
                       work_offsets={"G54": PRESET}, dialect=DIALECTS["fanuc"])
HAAS = dataclasses.replace(FANUC, dialect=DIALECTS["haas"])
HEAD = "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+50 R0 FMAX\n"


def tnc(body: str, context: MachineContext = TNC):
    text = HEAD + body + "\nEND PGM T MM\n"
    prog = parse_heidenhain(text, source="t.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def iso(text: str, context: MachineContext = FANUC):
    prog = parse_iso(text, source="t.nc", context=context)
    match = match_blocks(iso_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def machine(kin: Kinematics, part, angles: Solution) -> np.ndarray:
    """The machine position of the tip on part point ``part`` [mm, machine coordinates at rotary 0, the tip]."""
    return kin.place(np.asarray(part, dtype=float), angles) + [0.0, 0.0, LENGTH]


def tips(prog, kin: Kinematics, rows: list[int], **options) -> np.ndarray:
    """The tool tip on the part (rotary axes at 0) at every setpoint of blocks ``rows``."""
    sp = interpolate(prog, **options)
    col = {a: i for i, a in enumerate(sp.axes)}
    names = kin.names
    out = []
    for k in np.flatnonzero(np.isin(sp.block, rows)):
        angles = [sp.position[k, col[n]] for n in names]
        at = Solution(outer=angles[0], inner=angles[-1])
        out.append(kin.unplace(sp.position[k, :3] - [0.0, 0.0, LENGTH], at))
    return np.array(out)


def distance_to_line(points: np.ndarray, a, b) -> np.ndarray:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = b - a
    t = np.clip((points - a) @ d / (d @ d), 0.0, 1.0) if d @ d > 0 else np.zeros(len(points))
    return np.linalg.norm(points - (a + t[:, None] * d), axis=1)


def block_seconds(blocks) -> float:
    """The time the blocks' feeds give them: X Y Z length over feed, or the rotary distance with X Y Z still."""
    return sum((b.length if b.length > 0 else b.extra_length) / b.feed for b in blocks)


def test_m128_line_with_b_and_c_moving_keeps_the_tip_on_the_line():
    # the tip from part (10, 0, 0) to (40, 10, 5) (from the preset (10, 5, 0)) while B 0 -> 30, C 0 -> 45
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 Y+10 Z+5 B+30 C+45 F600")
    chords = [b for b in prog.blocks if b.number == 5]
    start, end = np.array([20.0, 5.0, 0.0]), np.array([50.0, 15.0, 5.0])  # tip positions at rotary 0
    assert len(chords) > 5 and not any(b.exact_stop for b in chords[:-1]) and chords[-1].exact_stop
    assert chords[-1].target == pytest.approx(machine(BC, end, Solution(30.0, 45.0)), abs=1e-9)
    assert chords[-1].extra_target[1:3] == pytest.approx([30.0, 45.0])
    rows = [i for i, b in enumerate(prog.blocks) if b.number == 5]
    off = distance_to_line(tips(prog, BC, rows), start, end)
    assert off.max() <= DEFAULT_TOLERANCE * 1.001
    assert off.max() > DEFAULT_TOLERANCE / 20  # the chords use the tolerance, they do not waste blocks
    # F600 is the tip's feed on the part: the block takes its length over 10 mm/s
    assert block_seconds(chords) == pytest.approx(np.linalg.norm(end - start) / 10.0, rel=1e-9)


def test_the_tip_moves_at_f_on_the_part():
    # with axes far faster than the feed asks, the setpoints show the tip at 10 mm/s (F600) on the part for
    # the block's length over F, while the machine's X Y Z run faster or slower along the chords
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 Y+10 Z+5 B+30 C+45 F600")
    rows = [i for i, b in enumerate(prog.blocks) if b.number == 5]
    fast = {a: AxisLimits(velocity=1e4, acceleration=1e7, jerk=1e10) for a in "xyzbc"}
    tip = tips(prog, BC, rows, limits=fast, sample_time=5e-4)
    assert len(tip) * 5e-4 == pytest.approx(np.linalg.norm([30.0, 10.0, 5.0]) / 10.0, abs=1e-3)
    speed = np.linalg.norm(np.diff(tip, axis=0), axis=1) / 5e-4
    assert np.median(speed) == pytest.approx(10.0, rel=1e-3) and speed.max() < 10.5


def test_cycle_32_tolerance_sets_the_chords():
    body = "3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 Y+10 Z+5 B+30 C+45 F600"
    coarse = [b for b in tnc(body).blocks if b.number == 5]
    fine = tnc("CYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1 T0.001\n" + body)
    chords = [i for i, b in enumerate(fine.blocks) if b.number == 5]
    assert len(chords) > 2 * len(coarse)
    off = distance_to_line(tips(fine, BC, chords), [20.0, 5.0, 0.0], [50.0, 15.0, 5.0])
    assert off.max() <= 0.001 * 1.001


def test_a_turn_about_the_tip_keeps_the_tip_still():
    # L B+40 C-60 alone: the tip stays on part (30, 5, -10); its time is the rotary distance at F deg/min
    prog = tnc("3 M128\n4 L X+20 Y+0 Z-10 F1000\n5 L B+40 C-60 F1200\n6 M129")
    rows = [i for i, b in enumerate(prog.blocks) if b.number == 5]
    tip = np.array([30.0, 5.0, -10.0])
    assert np.linalg.norm(tips(prog, BC, rows) - tip, axis=1).max() <= DEFAULT_TOLERANCE * 1.001
    chords = [prog.blocks[i] for i in rows]
    assert chords[-1].target == pytest.approx(machine(BC, tip, Solution(40.0, -60.0)), abs=1e-9)
    assert block_seconds(chords) == pytest.approx(math.hypot(40.0, 60.0) / 20.0, rel=1e-9)


def test_ln_with_a_tool_orientation_under_m128_turns_the_rotary_axes():
    # T = (sin 30, 0, cos 30) in the part: B+30 C+0 makes it the spindle's axis (B-30 C+180 too, farther from
    # B0 C0); DR+0.5 in the TOOL CALL displaces the part point along N = (0, 0, 1) by 0.5
    prog = tnc("3 TOOL CALL 1 Z S1000 DR+0.5\n4 L X+0 Y+0 Z+50 R0 FMAX\n5 M128\n6 L X+10 Y+0 Z+0 FMAX\n"
               "7 LN X+30 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0.5 TY+0 TZ+0.8660254 F600")
    chords = [b for b in prog.blocks if b.number == 7]
    assert len(chords) > 1 and chords[-1].extra_target[1:3] == pytest.approx([30.0, 0.0], abs=1e-6)
    assert chords[-1].target == pytest.approx(machine(BC, [40.0, 5.0, 0.5], Solution(30.0, 0.0)), abs=1e-6)
    assert not any("ignored without M128" in n for n in prog.notes)


def test_function_tcpm_reads_as_m128_and_reset_ends_it():
    m128 = tnc("3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 Y+10 Z+5 B+30 C+45 F600\n6 M129\n7 L X+0 FMAX")
    tcpm = tnc("3 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS REFPNT TIP-TIP\n4 L X+10 Y+0 Z+0 FMAX\n"
               "5 L X+40 Y+10 Z+5 B+30 C+45 F600\n6 FUNCTION RESET TCPM\n7 L X+0 FMAX")
    assert [b.target.tolist() for b in m128.blocks] == [b.target.tolist() for b in tcpm.blocks]
    # after the reset X+0 is the machine's preset X again (no table map): 10 + 0
    assert tcpm.blocks[-1].target[0] == pytest.approx(10.0)


def test_a_rapid_under_m128_with_rotary_words_is_chords_of_rapids():
    prog = tnc("3 M128\n4 L X+0 Y+0 Z+30 B-20 C+90 FMAX")
    chords = [b for b in prog.blocks if b.number == 4]
    assert all(b.kind == "rapid" and math.isinf(b.feed) for b in chords)
    assert chords[-1].target == pytest.approx(machine(BC, [10.0, 5.0, 30.0], Solution(-20.0, 90.0)), abs=1e-9)


def test_the_chords_of_a_rapid_under_tcp_are_one_move():
    """The chords of one rapid form one chain (interpolate's _extra_block), whose junctions the look-ahead passes
    at speed where their kinks allow (here a slow rapid: B turns 3 degrees over 60 mm), rather than a stop at
    every chord end; a rapid of another line, and the feed block after it, start chains of their own."""
    prog = tnc("3 M128\n4 L X+60 Y+0 Z+30 B-3 FMAX\n5 L X+0 FMAX\n6 L X+20 B+0 F600")
    rapid = [i for i, b in enumerate(prog.blocks) if b.number == 4]
    assert len(rapid) > 2
    slow = {**{a: AxisLimits(velocity=250.0, acceleration=2000.0, jerk=5e4, rapid=30.0) for a in "xyz"},
            **{a: AxisLimits(velocity=180.0, acceleration=1800.0, jerk=3.6e4, rapid=360.0) for a in "bc"}}
    sp = interpolate(prog, limits=slow)
    inside = np.flatnonzero(np.isin(sp.block, rapid))
    speed = np.linalg.norm(sp.velocity[inside][:, :3], axis=1)
    assert np.all(speed[1:-1] > 0.0)
    assert 0.99 * 30.0 < np.abs(sp.velocity[inside][:, :3]).max() <= 30.0 + 1e-9  # X near its rapid rate
    # at rest where the rapid ends (the next line's rapid is its own move)
    assert np.allclose(sp.velocity[inside[-1] + 1], 0.0, atol=1e-9)
    stops = np.flatnonzero(np.all(np.abs(sp.velocity) < 1e-9, axis=1))
    assert not np.any((stops > inside[0]) & (stops < inside[-1]))


@pytest.mark.parametrize(("body", "message"), [
    ("3 FUNCTION TCPM F CONT AXIS POS PATHCTRL AXIS", "F CONT"),
    ("3 FUNCTION TCPM F TCP AXIS SPAT PATHCTRL AXIS\n4 L X+5 U+5 F100", "'U\\+5' under FUNCTION TCPM AXIS SPAT"),
    ("3 FUNCTION TCPM F TCP AXIS POS PATHCTRL VECTOR", "PATHCTRL VECTOR"),
    ("3 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS REFPNT TIP-CENTER", "REFPNT TIP-CENTER"),
    ("3 FUNCTION TCPM F TCP AXIS POS ROT", "unexpected 'ROT'"),
    ("3 FUNCTION RESET TCPM NOW", "malformed FUNCTION RESET TCPM"),
    ("3 M128\n4 PLANE SPATIAL SPA+0 SPB+30 SPC+0 STAY\n5 L X+5 B+30 F100", "TCPM in a tilted working"),
    ("3 M128\n4 L X+5 Y+0 RL F500", "RL/RR under M128"),
    ("3 M128\n4 LN X+5 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0 TY+0.5 F500", "only part of the tool orientation"),
    ("3 M128\n4 LN X+5 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0 TY+0 TZ-1 F500", "cannot tilt the part"),
    ("3 M128\n4 CC X+0 Y+0\n5 C X+0 Y+10 B+5 DR+ F500", "not allowed in C|C under M128"),
])
def test_what_tcpm_does_not_read_is_named(body, message):
    with pytest.raises(GCodeError, match=message):
        parse_heidenhain(HEAD + body + "\nEND PGM T MM\n", source="t.h", context=TNC)


def test_tcpm_needs_kinematics_and_names_the_function():
    with pytest.raises(GCodeError, match=r"t\.h:5:.*FUNCTION TCPM \(TCPM, tool centre point management\) needs"):
        parse_heidenhain(HEAD + "3 L Z+10 FMAX\n4 FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS\nEND PGM T MM\n",
                         source="t.h", context=MachineContext(tools=TNC.tools))


def test_a_block_beyond_the_chord_limit_is_an_error(monkeypatch):
    monkeypatch.setattr(interpolators.tcp, "MAX_CHORDS", 3)
    with pytest.raises(GCodeError, match=r"t\.h:6:.*more than 3 chords") as err:
        parse_heidenhain(HEAD + "3 M128\n4 L X+100 Y+0 Z+0 FMAX\n5 L C+180 F500\nEND PGM T MM\n", source="t.h",
                         context=TNC)
    assert "cycle 32" in err.value.expected


# --- Fanuc G43.4, Haas G234 ---------------------------------------------------------------------------

def test_g43_4_line_with_a_and_c_moving_keeps_the_tip_on_the_line():
    prog = iso("G21 G90 G54 G64\nG0 A0 C0\nG43.4 H1 X0 Y0 Z50.\nG1 X20. Y10. Z5. A30. C45. F600.\nG49\nM30\n")
    rows = [i for i, b in enumerate(prog.blocks) if b.line == 4]
    start, end = np.array([10.0, 5.0, 50.0]), np.array([30.0, 15.0, 5.0])
    assert prog.blocks[rows[0] - 1].target == pytest.approx(start + [0.0, 0.0, LENGTH])  # G43.4 at A0 C0
    last = prog.blocks[rows[-1]]
    assert last.target == pytest.approx(machine(AC, end, Solution(30.0, 45.0)), abs=1e-9)
    assert distance_to_line(tips(prog, AC, rows), start, end).max() <= DEFAULT_TOLERANCE * 1.001
    assert block_seconds([prog.blocks[i] for i in rows]) == pytest.approx(np.linalg.norm(end - start) / 10.0)
    assert any(n.startswith("G43.4 tool centre point control") for n in prog.notes)


def test_g43_4_plain_moves_on_turned_axes_and_the_fast_path():
    # rotary axes positioned before G43.4: X Y Z are the tip on the part the table carries (a straight machine
    # line); the shortcut for plain moves declines under TCP, so both readings agree
    text = "G21 G90 G54\nG0 A-30. C90.\nG43.4 H1\nG1 X10. Y0 Z0 F300.\nG1 Y10.\nG1 Y10. A-30.\nG49\nM30\n"
    prog = iso(text)
    at = Solution(-30.0, 90.0)
    line = {b.line: b for b in prog.blocks}
    assert line[4].target == pytest.approx(machine(AC, [20.0, 5.0, 0.0], at))
    assert line[5].target == pytest.approx(machine(AC, [20.0, 15.0, 0.0], at))
    # a block that moves nothing: one block where it is, at the programmed feed (5 mm/s)
    assert line[6].target.tolist() == line[5].target.tolist() and line[6].feed == 5.0
    # G49 (Fanuc TOS = 0, a G01 block) takes the 20 mm tool length off along Z (isoleft39: the length G43.4 H1 set
    # travelled in line 4, so its cancel travels too)
    assert line[7].target == pytest.approx(line[6].target - [0.0, 0.0, LENGTH])
    slow = parse_iso(text, source="t.nc", context=FANUC, shortcuts=False)
    assert [b.target.tolist() for b in slow.blocks] == [b.target.tolist() for b in prog.blocks]


def test_g43_4_turn_about_the_tip_and_g93_inverse_time():
    prog = iso("G21 G90 G54\nG43.4 H1 X10. Y0 Z0\nG1 A20. C-30. F3600.\nG93 G1 X0 A0 C0 F2.\nG94 G0 G49\nM30\n")
    turn = [b for b in prog.blocks if b.line == 3]
    tip = np.array([20.0, 5.0, 0.0])
    assert turn[-1].target == pytest.approx(machine(AC, tip, Solution(20.0, -30.0)), abs=1e-9)
    assert block_seconds(turn) == pytest.approx(math.hypot(20.0, 30.0) / 60.0)  # F3600 deg/min
    inverse = [b for b in prog.blocks if b.line == 4]
    assert block_seconds(inverse) == pytest.approx(30.0)  # G93 F2: half a minute
    assert inverse[-1].target == pytest.approx(machine(AC, [10.0, 5.0, 0.0], Solution(0.0, 0.0)), abs=1e-9)


def test_g43_5_turns_the_rotary_axes_to_the_tool_direction():
    # I J K (0, -0.5, 0.866) in the part: A+30 C0 (A-30 C180 is farther from A0 C0); then (0.5, 0, 0.866): A+30
    # C+90 (A-30 C-90 is farther from A30 C0)
    prog = iso("G21 G90 G54\nG0 G43.5 H1 X0 Y0 Z0 I0 J0 K1.\nG1 X20. I0 J-0.5 K0.8660254 F600.\n"
               "G1 Y10. I0.5 J0 K0.8660254\nG49\nM30\n")
    first = [b for b in prog.blocks if b.line == 3]
    second = [b for b in prog.blocks if b.line == 4]
    assert first[-1].extra_target[[0, 2]] == pytest.approx([30.0, 0.0], abs=1e-6)
    assert second[-1].extra_target[[0, 2]] == pytest.approx([30.0, 90.0], abs=1e-6)
    assert second[-1].target == pytest.approx(machine(AC, [30.0, 15.0, 0.0], Solution(30.0, 90.0)), abs=1e-6)
    assert prog.axes == ("x", "y", "z", "a", "c")


def test_g234_on_haas_and_g49_ends_it():
    prog = iso("G21 G90 G54\nG0 A0 C0\nG234 H1 X0 Y0 Z20.\nG1 X10. A15. C30. F500.\nG49\nG0 Z100.\nM30\n", HAAS)
    chords = [b for b in prog.blocks if b.line == 4]
    assert chords[-1].target == pytest.approx(machine(AC, [20.0, 5.0, 20.0], Solution(15.0, 30.0)), abs=1e-9)
    # after G49 Z is the machine's Z without the tool length: the linear axes alone, the table stays turned
    assert prog.blocks[-1].target == pytest.approx([*chords[-1].target[:2], 100.0])


@pytest.mark.parametrize(("text", "context", "message"), [
    ("G43.4 H1\n", dataclasses.replace(FANUC, kinematics=None), "G43.4 tool centre point control needs the machine's"),
    ("G43.4 H1\n", dataclasses.replace(FANUC, kinematics=Kinematics(kind="head", axes=AC.axes)), "head-tilting"),
    ("G43.4 H1\n", dataclasses.replace(FANUC, dialect=DIALECTS["linuxcnc"]), "G43.4 tool centre point control"),
    ("G43.5 H1 X0 Y0 Z0 I0 J0 K1\n", HAAS, "G43.5 tool centre point control type 2"),
    ("G43.5 H1\nG1 X10. A5. F100.\n", FANUC, "word A under G43.5: not allowed"),
    ("G43.4 H1\nG1 X10. I0 J0 K1. F100.\n", FANUC, "word I under G43.4: not allowed"),
    ("G43.5 H1\nG1 X10. I0 J0 K-1. F100.\n", FANUC, "cannot tilt the part"),
    ("G43.4 H1\nG2 X10. Y0 I5. J0 F100.\n", FANUC, "motion other than G00/G01"),
    ("G43.4 H1\nG41 D1 G1 X10. Y0 F100.\n", FANUC, "cutter compensation"),
    ("G68.2 X0 Y0 Z0 I0 J30. K0\nG53.1\nG43.4 H1\n", FANUC, "tilted plane"),
    ("G43.4 H1\nG81 X0 Y0 Z-5. R2. F100.\n", FANUC, "motion other than G00/G01"),
    ("G43.4 H1\nG93 G1 X10. A5. F100.\nG1 X20. A10.\n", FANUC, "inverse time \\(G93\\) without an F > 0"),
])
def test_what_g43_4_does_not_read_is_named(text, context, message):
    with pytest.raises(GCodeError, match=message):
        parse_iso("G21 G90 G54 G0 X0 Y0 Z50.\n" + text, source="t.nc", context=context)


def test_incremental_words_under_tcp_start_from_the_tip_on_the_part():
    # IX+10 / G91 X10.: ten millimetres along the part's X from where the tip is on it, while the axes turn
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+0 B+10 C+20 F500\n5 L IX+10 B+20 C+40")
    assert prog.blocks[-1].target == pytest.approx(machine(BC, [30.0, 5.0, 0.0], Solution(20.0, 40.0)), abs=1e-9)
    prog = iso("G21 G90 G54\nG43.4 H1 X0 Y0 Z0 A10. C20.\nG91 G1 X10. A10. C20. F500.\nG90 G49\nM30\n")
    end = [b for b in prog.blocks if b.line == 3][-1]
    assert end.target == pytest.approx(machine(AC, [20.0, 5.0, 0.0], Solution(20.0, 40.0)), abs=1e-9)


def test_g43_4_on_a_single_tilting_axis():
    # a 4-axis table: A alone tilts the part about X round (0, 0, -80)
    kin = Kinematics(axes=(RotaryAxis(name="a", pivot=(0.0, 0.0, -80.0)),))
    context = dataclasses.replace(FANUC, kinematics=kin, extra_axes=("a",))
    prog = iso("G21 G90 G54\nG43.4 H1 X0 Y0 Z0\nG1 Y30. A45. F1000.\nG49\nM30\n", context)
    rows = [i for i, b in enumerate(prog.blocks) if b.line == 3]
    assert prog.blocks[rows[-1]].target == pytest.approx(machine(kin, [10.0, 35.0, 0.0], Solution(45.0, 0.0)))
    assert distance_to_line(tips(prog, kin, rows), [10.0, 5.0, 0.0], [10.0, 35.0, 0.0]).max() <= 0.01 * 1.001


def test_positions_read_under_tcp_are_the_tip_on_the_part():
    # Fanuc #5001-#5003 (end point) and #5041-#5043 (current position, work coordinates) under G43.4: the tip
    # on the part as programmed, so a point read back and programmed again does not move, and Z+1 moves the tip
    # 1 mm along the part's Z (the table tilted by A30 turns the part by -30 deg about X: machine (0, sin 30, cos 30))
    text = ("G21 G90 G54\nG0 A0 C0\nG43.4 H1 X0 Y0 Z50.\nG1 X10. Y0 Z10. A30. C20. F500.\n"
            "#1=#5001 #2=#5002 #3=#5003\n#11=#5041 #12=#5042 #13=#5043\nG1 X#1 Y#2 Z#3\nG1 X#11 Y#12 Z[#13+1.]\n"
            "G49\nM30\n")
    prog = parse_iso(text, source="t.nc", context=FANUC)
    at = Solution(30.0, 20.0)
    tip = machine(AC, [20.0, 5.0, 10.0], at)
    last = {b.line: b for b in prog.blocks}
    assert last[4].target == pytest.approx(tip, abs=1e-9)
    assert last[7].target == pytest.approx(tip, abs=1e-9)  # #5001-#5003: X10 Y0 Z10
    assert last[8].target == pytest.approx(machine(AC, [20.0, 5.0, 11.0], at), abs=1e-9)
    assert last[8].target - tip == pytest.approx([0.0, 0.5, math.sqrt(3.0) / 2.0], abs=1e-9)


def test_fn18_id270_under_m128_reads_the_tip_on_the_part():
    # ID270 (the position in the active coordinate system) under M128: the tip's X Y Z as programmed, not the
    # machine axes' (which the table's turn moved): L X+Q1 Y+Q2 Z+Q3 stays where it is; ID240 stays the machine
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+10 B+20 C+10 F500\n5 FN 18: SYSREAD Q1 = ID270 NR1 IDX1\n"
               "6 FN 18: SYSREAD Q2 = ID270 NR1 IDX2\n7 FN 18: SYSREAD Q3 = ID270 NR1 IDX3\n"
               "8 FN 18: SYSREAD Q4 = ID240 NR1 IDX1\n9 L X+Q1 Y+Q2 Z+Q3\n10 M129\n11 L X+Q4 Y+Q2 Z+Q3 B+0 C+0")
    tip = machine(BC, [20.0, 5.0, 10.0], Solution(20.0, 10.0))
    at = {b.number: b for b in prog.blocks}
    assert at[4].target == pytest.approx(tip, abs=1e-9)
    assert at[9].target == pytest.approx(tip, abs=1e-9)
    # after M129, X+Q4 is the machine X read by ID240 (from the preset: machine X = 10 + Q4)
    assert at[11].target[0] == pytest.approx(10.0 + tip[0], abs=1e-9)


def test_dense_chords_under_tcp_are_never_merged():
    """200 short G43.4 moves round R30 with A and C turning: their chords are ``Block.tcp`` and the look-ahead keeps
    them (no merged curve, ``meta["programmed_path"]`` absent), so the tool tip stays within the G64 P the chords
    were cut to (a fit of A and C apart from X, Y, Z would move the tip by the pivot distance times the angle's
    error: review30 measured the chain merged once its inverse-time-like feeds were allowed to differ by 1 %)."""
    lines = ["G21 G90 G54 G64 P0.01", "G0 A0 C0", "G43.4 H1 X30. Y0 Z0", "G1 F2000."]
    pts = []
    for i in range(1, 201):
        t = math.pi * i / 200
        pts.append((30 * math.cos(t), 30 * math.sin(t), 0.0))
        lines.append(f"X{pts[-1][0]:.4f} Y{pts[-1][1]:.4f} Z0 A{10 * math.sin(t):.4f} C{math.degrees(t):.4f}")
    prog = parse_iso("\n".join([*lines, "G49", "M30"]) + "\n", source="t.nc", context=FANUC)
    turning = [b.extra_start is not None and bool(np.any(b.extra_target != b.extra_start)) for b in prog.blocks]
    assert sum(turning) >= 200 and [b.tcp for b in prog.blocks] == [t and k > 0 for k, t in enumerate(turning)]
    rows = [k for k, b in enumerate(prog.blocks) if b.kind == "line" and b.line <= len(lines)][2:]  # not G49's
    poly = np.array([(30.0, 0.0, 0.0), *pts]) + np.array(PRESET)
    u = np.linspace(0.0, 1.0, 200)[None, :, None]
    dense = (poly[:-1, None] + (poly[1:] - poly[:-1])[:, None] * u).reshape(-1, 3)
    for profile in ("trapezoid", "scurve"):
        assert "programmed_path" not in interpolate(prog, profile=profile).meta
        tip = tips(prog, AC, rows, profile=profile)
        assert np.linalg.norm(tip[:, None] - dense[None, ::7], axis=2).min(axis=1).max() <= 0.01 + 0.003


def test_moves_under_m128_are_tcp_chords():
    prog = tnc("3 M128\n4 L X+10 Y+0 Z+0 FMAX\n5 L X+40 Y+10 Z+5 B+30 C+45 F600\n6 M129\n7 L X+0 F600")
    assert [b.tcp for b in prog.blocks if b.number == 5] and all(b.tcp for b in prog.blocks if b.number == 5)
    assert not any(b.tcp for b in prog.blocks if b.number in (2, 7))
