"""The ISO reader's plain-move shortcut (:mod:`interpolators.iso_fast`) with rotary A B C and secondary linear U V W
words: the blocks the general executor makes, bit for bit.

Each program is read twice, with the shortcut and every block the general way (``shortcuts=False``), under each
dialect, on a five-axis machine with all six extra axes and an A/C tilting table, and the two readings must be the
same: every field of every block (the extra axes' start and end positions and the feed of a move of the rotary axes
alone by their bytes), the notes, the messages and the axes, or the same error with the same message. The programs are
hand-written, one per modal state the shortcut models with the extra axes (units -- A B C never scaled by G20, U V W
are --, G90/G91, a work offset and a G92 offset of A, the planes, arcs and helices turning A) or declines (inverse time
G93 -- taken since g93fast35, test_reader_fast_g93.py --, feed per revolution G95, tool centre point control
G43.4/G43.5/G234, a tilted working plane G68.2/G53.1, cutter compensation, a G10 R rotation, a canned cycle, G53 and
G28 with A, a word of an axis the machine lacks, a Fanuc A without a decimal point): for the declined states also the
reading of the plain lines after the state must differ from their reading without it (so that the identity says
something). Generated programs (fixed seeds) mix moves of random subsets of X Y Z A B C U V W with these states. The
corpus' programs with rotary words, when the corpus is present, are read both ways too.
"""

from __future__ import annotations

import random
import re

import numpy as np
import pytest

from benchmarks.gcode_corpus import corpus_dir, extra_axis_lines, without_remapped_m
from interpolators.context import MachineContext, Tool
from interpolators.iso import parse_iso
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.block_digest import corpus_programs
from tests.interpolators.test_reader_fast import reading

#: A tilts about X round (0, 0, -80), C turns about Z through (5, 0, 0) (as tests/interpolators/test_tcp5x.py).
AC = Kinematics(axes=(RotaryAxis(name="a", pivot=(0.0, 0.0, -80.0), limits=(-120.0, 120.0)),
                      RotaryAxis(name="c", pivot=(5.0, 0.0, 0.0))))
FIVE_AXIS = MachineContext(extra_axes=("a", "b", "c", "u", "v", "w"), kinematics=AC,
                           work_offsets={"G54": np.array([10.0, 5.0, 0.0]), "G55": np.array([100.0, 50.0, -20.0])},
                           tools={1: Tool(number=1, length=20.0, radius=3.0)}, home=np.array([0.0, 0.0, 10.0]))
#: A machine with an A axis only: B, C, U, V, W words are the general path's note (value 0) or error.
A_ONLY = MachineContext(extra_axes=("a",), home=np.array([0.0, 0.0, 10.0]))

#: Moves of the extra axes as a 4/5-axis CAM post writes them: with X Y Z, alone (the F then deg/min along the
#: rotary distance, or mm/min along U V W), both ways, arcs and a helix turning A, F changes, N numbers, case.
ROTARY_MOVES = """N10 G0 X0. Y0. Z5. A0. C0.
N20 G1 Z-1. F300.
N30 G1 X10.5 Y-2.25 A15.
N40 A30. C-45.
N50 G1 A45. F3600.
N60 G1 X12. B10. F450.
N70 G2 X22. Y-2.25 I5. J0. A60.
N80 G3 X12. Y-2.25 Z-1.5 I-5. J0. C90. F500.
N90 G1 U5. F200.
N100 G1 X1. U6. V-2. W.5 A50.
N110 G0 A0. C0. U0. V0. W0.
N120 G0 X3. B-15.
x4. y1. a12.5 c7.25
N130 G1 X4. Y1. A12.5
N140 G1 Z2. A-7.5 F1200.
N150 G0 C400.
"""

#: The states the shortcut models with the extra axes: each a program of the moves above in that state.
MODELLED = {
    "mm, absolute": "G21 G17 G90 G94 G64\n" + ROTARY_MOVES,
    "inch": "G20 G17 G90\n" + ROTARY_MOVES,
    "incremental": "G21 G91\nG0 X1. Y1. Z5. A5.\nG1 Z-6. A10. F300.\nG1 A-20. C5.\nG1 X10. U2. F400.\n"
                   "G2 X10. Y0. I5. J0. A15.\nG1 V-1. W2.\nG0 B30.\n",
    "work offset G55": "G21 G55 G90\n" + ROTARY_MOVES,
    "work offset of A (G10 L2)": "G21 G90\nG10 L2 P1 A30. C-10. U1.\n" + ROTARY_MOVES,
    "G92 offset with A": "G21 G90\nG0 X1. Y1. Z1. A20.\nG92 X0. Y0. Z0. A0.\n" + ROTARY_MOVES,
    "tool length": "G21 G90\nT1 M6\nG43 H1\n" + ROTARY_MOVES,
    "exact stop": "G21 G61\n" + ROTARY_MOVES,
    "G18 plane": "G21 G18 G90\nG0 X0. Y0. Z0. B0.\nG1 X1. F100.\nG2 X3. Z0. I1. K0. B20.\nG3 X1. Z0. I-1. K0. A5.\n",
    "G19 plane": "G21 G19 G90\nG0 X0. Y0. Z0.\nG1 Y1. F100.\nG3 Y3. Z0. J1. K0. A-10.\nG1 Y0. Z1. C5.\n",
    "after G93 and G94 again": "G21 G90\nG93 G1 X1. A10. F2.\nG94 F300.\n" + ROTARY_MOVES,
    "after tool centre point control": "G21 G90\nG43.4 H1 X0. Y0. Z50.\nG1 X5. A10. F300.\nG49\n" + ROTARY_MOVES,
    "after a tilted plane": "G21 G90\nG68.2 X0. Y0. Z0. I0. J30. K0.\nG53.1\nG69\n" + ROTARY_MOVES,
}

#: The states the shortcut declines (with their preamble); the rotary moves follow.
DECLINED = {
    "inverse time G93": "G21 G90 G93\nG1 X5. Y5. A10. F10.\n",
    "feed per revolution G95": "G21 G90 S1000 M3 G95\nG1 X5. Y5. A10. F0.1\n",
    "tool centre point control G43.4": "G21 G90\nG43.4 H1 X0. Y0. Z50.\n",
    "tool centre point control G43.5": "G21 G90\nG0 G43.5 H1 X0. Y0. Z0. I0. J0. K1.\n",
    "tool centre point control G234": "G21 G90\nG234 H1 X0. Y0. Z50.\n",
    "tilted plane G68.2": "G21 G90\nG68.2 X0. Y0. Z0. I0. J30. K0.\nG53.1\n",
    "cutter compensation G41": "G21 G90\nG0 X-5. Y-5.\nG41 D1 G1 X0. Y0. F100.\n",
    "rotated work offset G10 L2 R": "G21 G90\nG10 L2 P1 X0 Y0 Z0 R30.\nG54\n",
    "a canned cycle modal": "G21 G90 G98\nG81 X5. Y5. Z-2. R1. F100.\n",
    "G53 with A": "G21 G90\nG53 G0 X1. A90.\n",
    "G28 with A": "G21 G90\nG0 A45.\nG28 A0.\n",
}

#: Single lines the shortcut leaves to the general path (an error, a note or another reading).
ODD_LINES = [
    "G21 G90\nG1 X1. A10 F100.\n",  # Fanuc: A10 without a decimal point
    "G21 G90\nG1 X1. A1. A2. F100.\n",  # a letter twice
    "G21 G90\nG1 A10.\n",  # no feed
    "G21 G90\nG1 A10. F0\n",  # F0
    "G21 G90\nG2 A10. I1. J0. F100.\n",  # an arc turning A only (the full circle)
    "G21 G90\nG0 A10. I1.\n",  # I on G0
    "G21 G90\nG1 X1. F100.\nG80\nA10.\n",  # an A word after G80
    "G21 G90 F100.\nG1 A1e5\n",  # an exponent
    "G21 G90\nG1 X1. F100.\nG41 D1 G1 X2.\nG1 X3. A10.\n",  # A under compensation: an error
    "G21 G90\nG81 X1. Y1. Z-1. R1. A10. F100.\n",  # A in a cycle: an error
]

#: On a machine with an A axis only: B0 is a note, B5 and U1 errors naming the axis.
LACKING = ["G21 G90\nG1 X1. A10. B0. F100.\n", "G21 G90\nG1 X1. B5. F100.\n", "G21 G90\nG0 X1. U1.\n",
           "G20 G90\nG1 X1. A10. F100.\nA20.\nC0\n"]


def assert_same(text: str, context: MachineContext) -> list[str]:
    fast = reading(text, context, shortcuts=True)
    assert fast == reading(text, context, shortcuts=False)
    return fast


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas", "grbl"])
@pytest.mark.parametrize("state", list(MODELLED))
def test_modelled_states_give_the_general_blocks(state, dialect):
    context = FIVE_AXIS.with_dialect(dialect)
    got = assert_same(MODELLED[state] + "M2\n", context)
    if got[0].startswith("error"):  # a code the dialect lacks (G43.4, G68.2 are Fanuc/Haas codes)
        assert dialect != "fanuc" and state.startswith("after"), got[0]
        return
    prog = parse_iso(MODELLED[state] + "M2\n", context=context)
    assert sum(bool(np.any(b.extra_delta != 0)) for b in prog.blocks) >= 2  # the extra axes move


def test_the_moves_are_taken_by_the_shortcut(monkeypatch):
    """The rotary moves go the short way: a reading with the general executor's block maker broken still reads
    them (so the identities above compare two paths, not one with itself)."""
    import interpolators.iso as iso

    def refused(*args, **kwargs):
        raise AssertionError("the general path ran a plain rotary move")

    text = "G21 G90 G94\nG0 X0. Y0. Z5. A0.\n"
    prog = parse_iso(text, context=FIVE_AXIS)
    monkeypatch.setattr(iso, "motion_block", refused)
    body = ROTARY_MOVES.split("\n", 1)[1]  # after N10's first rapid
    fast = parse_iso(text + body + "M2\n", context=FIVE_AXIS)
    assert len(fast.blocks) > len(prog.blocks) + 10
    pure = fast.blocks[4]  # N50 G1 A45. F3600.: a move of A alone runs at 3600 deg/min
    assert pure.feed == 60.0 and pure.length == 0.0 and pure.extra_target[0] == 45.0


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas"])
@pytest.mark.parametrize("state", list(DECLINED))
def test_declined_states_give_the_general_blocks(state, dialect):
    context = FIVE_AXIS.with_dialect(dialect)
    got = assert_same(DECLINED[state] + ROTARY_MOVES + "M2\n", context)
    plain = assert_same("G21 G90 G0 X0. Y0. Z5.\n" + ROTARY_MOVES + "M2\n", context)
    assert got[-len(plain) + 1:] != plain[1:] or got[0].startswith("error")  # the state changes the moves


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas", "grbl"])
@pytest.mark.parametrize("text", ODD_LINES)
def test_odd_lines_give_the_general_blocks_or_error(text, dialect):
    context = FIVE_AXIS.with_dialect(dialect)
    assert_same(text, context)
    assert_same(text + "M2\n", context)


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc"])
@pytest.mark.parametrize("text", LACKING)
def test_axes_the_machine_lacks_keep_the_general_note_or_error(text, dialect):
    got = assert_same(text + "M2\n", A_ONLY.with_dialect(dialect))
    if re.search(r"\b[BU][15]\.", text):
        assert "this machine has no" in got[0]
    elif "B0." in text:
        assert "B0 (rotary axis B stays at 0)" in got[0]


def test_feed_of_moves_of_the_extra_axes_alone():
    """RS274/NGC 3 Sec. 2.1.2.5 (LinuxCNC G-code overview, "Feed Rate"): with X Y Z still, F runs along U V W in
    mm/min (inch/min under G20), else along A B C in deg/min, never scaled by G20; with X Y Z moving, along XYZ."""
    text = "G20 G90 G0 X0. Y0. Z0.\nG1 A90. F60.\nG1 U1. A0.\nG1 X1. A45.\nM2\n"
    for shortcuts in (True, False):
        prog = parse_iso(text, context=FIVE_AXIS, shortcuts=shortcuts)
        rot, lin, xyz = prog.blocks[1:4]
        assert rot.feed == 1.0  # 60 deg/min
        assert lin.feed == pytest.approx(60 * 25.4 / 60) and lin.extra_target[3] == pytest.approx(25.4)
        assert xyz.feed == pytest.approx(25.4) and xyz.target[0] - prog.blocks[0].target[0] == pytest.approx(25.4)


_LETTERS = "XYZABCUVW"


#: Tool centre point control on, by dialect (LinuxCNC has none: there the general path refuses the code).
_TCP = {"fanuc": "G43.4 H1", "haas": "G234 H1", "linuxcnc": "G43 H1"}


def random_program(rng: random.Random, dialect: str) -> str:
    """Moves of random subsets of X Y Z A B C U V W (G0, G1, G2/G3 turning A about a centre on the circle),
    among F changes, G90/G91, G20/G21, offsets and the declined states (an F on every feed move under G93)."""
    lines = [rng.choice(["G21", "G20"]) + " G17 G90", "G0 X0. Y0. Z0. A0. B0. C0.", "G1 F500."]
    changes = ["G90", "G91", "G20", "G21", "G55", "G54", "G92 X0. A0.", "G92.1", "G10 L2 P1 A5. C-3.", "G93",
               "G94 F300.", _TCP[dialect], "G49", "G61", "G64", "T1 M6\nG43 H1", "M0", "G0 A0. C0.", "G1 F0"]
    inverse = tcp = False
    for _ in range(rng.randint(10, 40)):
        if rng.random() < 0.15:
            change = rng.choice(changes[:-1] if rng.random() < 0.9 else changes)
            inverse = change == "G93" or inverse and not change.startswith("G94")
            tcp = change == _TCP[dialect] or tcp and change != "G49"
            lines += [change, "G90 G0 X0. Y0. Z0."]
            continue
        if rng.random() < 0.1 and not tcp:
            r = rng.uniform(0.5, 3.0)
            lines += ["G90 G0 X0. Y0. Z0.",
                      f"G{rng.choice([2, 3])} X{2 * r:.4f} Y0. I{r:.4f} J0. A{rng.uniform(-90, 90):.3f} F100.",
                      "G90 G0 X0. Y0. Z0."]
            continue
        words = [rng.choice(["G0", "G1", "G01", ""])]
        for letter in rng.sample(_LETTERS, rng.randint(1, 4)):
            value = rng.uniform(-30, 30)
            words.append(f"{letter}{value:.4f}" if rng.random() < 0.97 else f"{letter}{round(value)}")
        if inverse or rng.random() < 0.3:
            words.append(rng.choice(["F100.", "F2.", "F1200", "F3600."]))
        lines.append(" ".join(w for w in words if w))
    lines.append("M30")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("seed", range(6))
def test_random_rotary_programs_read_alike(seed):
    rng = random.Random(seed)
    accepted = 0
    for _ in range(25):
        for dialect in ("linuxcnc", "fanuc", "haas"):
            text = random_program(rng, dialect)
            accepted += not assert_same(text, FIVE_AXIS.with_dialect(dialect))[0].startswith("error")
    assert accepted >= 30


def rotary_corpus() -> list[tuple[str, str, MachineContext]]:
    """The corpus' ISO programs with extra-axis words, each read on a machine with all six extra axes; a program
    with remapped M codes (above M199) also with those lines blanked, so that its moves are read."""
    out = []
    for name, text, context in corpus_programs("iso"):
        if extra_axis_lines(text) < 3:
            continue
        out.append((name, text, context))
        blanked = without_remapped_m(text)
        if blanked is not None:
            out.append((name + " (remapped M lines blanked)", blanked, context))
    return out


@pytest.mark.skipif(corpus_dir() is None, reason="gcode corpus absent (../shared/data/gcode-corpus)")
def test_corpus_programs_with_rotary_words_read_alike():
    """The corpus' programs with rotary words (LinuxCNC's 5-axis boat-xyzac, foam, cone, b-index ..), in the
    context of their origin (``vcnc interpolate``'s: all six extra axes)."""
    programs = rotary_corpus()
    assert len(programs) >= 3, [name for name, _, _ in programs]
    turning = 0
    for _, text, context in programs:
        got = assert_same(text, context)
        if not got[0].startswith("error"):
            prog = parse_iso(text, context=context)
            turning += sum(bool(np.any(b.extra_delta[:3] != 0)) for b in prog.blocks)
    assert turning > 100  # moves of the rotary axes were compared
