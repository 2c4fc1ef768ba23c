"""The Heidenhain reader's shortcut for plain blocks (:mod:`interpolators.heidenhain_fast`) makes the general path's
blocks.

:func:`interpolators.heidenhain_fast.plain_words` reads the words of the blocks it takes and refuses every other
block (hand-written codes below, one per form it leaves to the general path). Each program below is read twice,
with the shortcut (``parse_heidenhain``'s default) and every block the general way (``shortcuts=False``), and the
two readings must be the same bit for bit: every field of every block (end points and feeds by their bytes, the
segment's geometry), the notes in their order, the axes and the name, or the same error with the same message.
The programs are hand-written, one per modal state the shortcut models (MM/INCH, incremental words, the preset
and cycle 7's datum shift, the tool length and tool axis, a pole in another plane, cycle 32's path tolerance,
M128 on positioned rotary axes, the states after compensation, a transformation or a program stop are over) or
declines (cycles 8, 10, 11, 26, TRANS, a tilted plane, RL/RR, RND/CHF and APPR waiting for their next element,
FK, M89): a shortcut that took a block it does not model would give a different block or no error. For the
declined states the test also checks that the state changes what the plain blocks after it mean (so that the
identity says something). Generated programs (fixed seeds) mix plain lines, arcs about CC and by radius,
F changes, M functions and block numbers with these states, Q parameters and errors. The corpus' TNC programs,
when present, are read both ways too (slow).
"""

from __future__ import annotations

import dataclasses
import math
import random
import re

import numpy as np
import pytest

from benchmarks.gcode_corpus import corpus_dir
from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.heidenhain_fast import PlainWords, plain_words
from interpolators.heidenhain_words import source_blocks
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.block_digest import corpus_programs, program_digest
from vcnc.errors import GCodeError, InputError

#: A B/C trunnion table with its B pivot off the machine zero (M128, PLANE), tools with length and radius.
KINEMATICS = Kinematics(axes=(RotaryAxis(name="b", direction="Y", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)),
                              RotaryAxis(name="c", direction="Z")))
CONTEXT = MachineContext(work_offsets={"G54": np.array([10.0, -5.0, 2.0]), "G55": np.array([100.0, 50.0, -20.0])},
                         tools={n: Tool(number=n, length=20.0 + n, radius=1.5 + 0.5 * n) for n in range(1, 6)},
                         home=np.array([0.0, 0.0, 300.0]), extra_axes=("b", "c"), kinematics=KINEMATICS)

#: A CAM-like run of plain blocks: rapids, feeds, incremental words, arcs about CC both ways, arcs by radius
#: (R- beyond 180 degrees), a helix, F changes, M functions, block numbers or none, tabs.
MOVES = """10 L X+0 Y+0 Z+5 R0 FMAX M3
11 L Z-1 F300 M8
12 L X+10.5 Y-2.25
13 CC X+15.5 Y-2.25
14 C X+20.5 Y-2.25 DR+
15 C X+10.5 Y-2.25 Z-1.5 DR- F450
16 CR X+15.5 Y+2.75 R+5 DR+
17 CR X+10.5 Y-2.25 R-5 DR+ M90
18 L IX-0.5 IY+.25 IZ+0.5 F1200. M90 M126
L X+3.	Y+4 Z-0.75
19 L X+2.5 F600
20 L X-1.25 Y+2 Z+5 FMAX M9
"""

HEAD = "0 BEGIN PGM T MM\n1 TOOL CALL 1 Z S3000\n"
TAIL = "99 END PGM T MM\n"

#: The states the shortcut models: each a program of plain blocks in that state.
MODELLED = {
    "mm": HEAD + MOVES,
    "inch": "0 BEGIN PGM T INCH\n1 TOOL CALL 1 Z S3000\n" + MOVES,
    "no tool": "0 BEGIN PGM T MM\n" + MOVES,
    "tool length of TOOL DEF and DL": "0 BEGIN PGM T MM\n1 TOOL DEF 7 L+42.5 R+3\n2 TOOL CALL 7 Z S3000 DL+0.1\n"
                                      + MOVES,
    "datum shift cycle 7": HEAD + "2 CYCL DEF 7.0 DATUM SHIFT\n3 CYCL DEF 7.1 X+12.5\n4 CYCL DEF 7.2 Y-3\n"
                                  "5 CYCL DEF 7.3 Z+1\n" + MOVES,
    "preset cycle 247": HEAD + "2 CYCL DEF 247 DATUM SETTING ~\n  Q339=+2 ;DATUM NUMBER\n" + MOVES,
    "tool axis X": "0 BEGIN PGM T MM\n1 TOOL CALL 2 X S3000\n2 L X+5 Y+0 Z+0 R0 FMAX\n3 L X-1 F300\n"
                   "4 CC Y+5 Z+0\n5 C Y+10 Z+0 DR-\n6 CR Y+0 Z+0 R+5 DR+\n7 L IX+2 IY-1\n",
    "tool axis Y": "0 BEGIN PGM T MM\n1 TOOL CALL 2 Y S3000\n2 L X+0 Y+5 Z+0 R0 FMAX\n3 L Y-1 F300\n"
                   "4 CC Z+5 X+0\n5 C Z+10 X+0 DR+\n6 CR Z+0 X+0 R+5 DR-\n7 L IY+2 IZ-1\n",
    "a pole in another plane": HEAD + "2 L X+0 Y+0 Z+5 R0 FMAX\n3 L Z+0 F300\n4 CC Y+5 Z+0\n5 C Y+10 Z+0 DR+\n"
                                      "6 L X+1\n7 CC X+0 Z+0\n8 C X+0 Z+1 DR-\n9 CC X+0 Y+0\n10 C X+10 Y+0 DR+\n",
    "path tolerance cycle 32": HEAD + "2 CYCL DEF 32.0 TOLERANCE\n3 CYCL DEF 32.1 T0.05\n" + MOVES,
    "after radius compensation": HEAD + "2 L X-5 Y-5 Z+5 R0 FMAX\n3 L X+0 Y+0 RL F100\n4 L X+10\n5 L Y+10\n"
                                        "6 L X-5 Y-5 R0\n" + MOVES,
    "after a transformation": HEAD + "2 CYCL DEF 10.0 ROTATION\n3 CYCL DEF 10.1 ROT+30\n4 L X+1 Y+1 F100\n"
                                     "5 CYCL DEF 10.0 ROTATION\n6 CYCL DEF 10.1 ROT+0\n" + MOVES,
    "after a program stop": HEAD + "2 L X+1 Y+1 Z+5 R0 FMAX\n3 STOP\n" + MOVES
                            + "21 FN 18: SYSREAD Q1 = ID240 NR1 IDX1\n22 L X+Q1 FMAX\n",
    "after RND and CHF": HEAD + "2 L X+0 Y+0 Z+0 R0 F100\n3 L X+10\n4 RND R2\n5 L Y+10\n6 CHF 1\n7 L X+0\n" + MOVES,
    "block skip and comments": HEAD + "/2 L X+1 Y+1 Z+1 R0 FMAX ;a comment\n3 L X+2 F100 ;\n* - structure\n"
                                      "4 /L X+3\n" + MOVES,
    "a section repeat and a subprogram": HEAD + "2 LBL 1\n" + MOVES + "30 CALL LBL 1 REP 2\n31 CALL LBL 5\n"
                                                "32 L X+0 FMAX\n33 M30\n34 LBL 5\n35 L IX+1 Y+0 F100\n36 CC IX+1 Y+0\n"
                                                "37 C IX+2 DR+\n38 LBL 0\n",
    "a decimal comma": HEAD + re.sub(r"(?<=\d)\.(?=\d)", ",", MOVES),
    "M128 on positioned rotary axes": HEAD + "2 L X+0 Y+0 Z+50 R0 FMAX\n3 L B+30 C+45 FMAX\n4 L M128 F3000\n"
                                             "5 L X+10 Y+0 Z+0 FMAX\n6 L Z+5 F3000\n7 L IY+2 F500\n8 CC X+0 Y+0\n"
                                             "9 L X+1.5 Y-2 Z+1 M8\n10 M129\n11 L X+1 FMAX\n",
}

#: The states the shortcut declines (after HEAD and a first position), each followed by MOVES without its R0 (so
#: that RL/RR stay on).
DECLINED = {
    "mirror cycle 8": "CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X\n",
    "rotation cycle 10": "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30\n",
    "scaling cycle 11": "CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 2\n",
    "axis scaling cycle 26": "CYCL DEF 26.0 AXIS-SPECIFIC SCALING\nCYCL DEF 26.1 X1.5 Y1.5\n",
    "TRANS ROTATION": "TRANS ROTATION ROT+90\n",
    "TRANS MIRROR": "TRANS MIRROR AXIS Y\n",
    "a tilted plane": "PLANE SPATIAL SPA+0 SPB+30 SPC+0 TURN FMAX\n",
    "a tilted plane, its rotary axes not positioned": "PLANE SPATIAL SPA+0 SPB+30 SPC+0 STAY\n",
    "radius compensation RL": "L X-5 Y-5 RL F100\n",
    "radius compensation RR": "L X-5 Y-5 RR F100\n",
    "RND waiting": "L X-5 Y-5 F100\nL X-5 Y+0\nRND R1\n",
    "CHF waiting": "L X-5 Y-5 F100\nL X-5 Y+0\nCHF 1\n",
    "APPR waiting": "APPR LT X+0 Y+0 LEN5 RL F100\n",
    "APPR LT waiting, R0": "APPR LT X+0 Y+0 LEN5 R0 F100\n",
    "FK waiting": "FL X+10 Y+0 F100\nFL IAN+90 LEN 5\n",
    "M89 modal cycle call": "CYCL DEF 200 DRILLING ~\n Q200=2 ~\n Q201=-1 ~\n Q206=100 ~\n Q202=1 ~\n Q210=0 ~\n"
                            " Q203=+0 ~\n Q204=10 ~\n Q211=0\nL Z+2 FMAX M89\n",
}

#: Blocks whose words the shortcut leaves to the general path (which reads them, notes them or refuses them).
DECLINED_CODES = [
    "L X+Q1 Y+2 F100", "L X+(1+2) F100", "L X+1 Y+2 RL F100", "L X+1 RR", "LN X+1 Y+1 Z+1 NX+1 NY+0 NZ+0",
    "LP PR+5 PA+30", "CP IPA+90 DR+", "CT X+1 Y+2", "L X+1 A+0", "L X+1 B+30 C+0 FMAX", "L X+1 F AUTO",
    "L X+1 FU0.1", "L X+1 FZ0.1", "L X+1 F MAX", "L X+1 R F M", "L +5", "L X +1", "L X+1Y+2", "l x+1 fmax",
    "L X+1.5.5", "L X+1e5", "L X+nan", "L X+1 M", "L M3", "L F200", "L X+1 IX+2", "L X+1 F100 FMAX", "L X+1 F0",
    "L X+1 F-5", "L X+1 DR+", "L X+1 R+5", "CC X+1 F100", "CC X+1 R0", "C X+1 Y+1 FMAX", "CR X+1 Y+1 DR+",
    "C X+1 Y+1 R+5 DR+", "C DR+", "L X+1 M2", "L X+1 M30", "L X+1 M0", "L X+1 M1", "L X+1 M91", "L X+1 M92",
    "L X+1 M89", "L X+1 M99", "L X+1 M128", "L X+1 M129", "L X+1 M136", "L X+1 M140 MB MAX", "L X+1 DR+ DR-",
    "CR X+1 R+1 R+2 DR+", "L X+1 R0 R0", "L X+1 S500", "L X+1 ;", "L X+1 *", "LBL 1", "FN 0: Q1 = +5",
]

#: Odd blocks in a program: errors the general path words, notes, a number without an axis letter.
ODD = [
    "L X+1 F0", "L IX+1 X+2 F100", "L X+1 Y+2", "C X+1 Y+1 DR+", "CC X+0 Y+0\nC X+1 Y+1", "CC X+0 Y+0\nC X+5 Y+1 DR+",
    "CC X+0 Y+0 Z+0", "CR X+100 Y+0 R+1 DR+", "L X+1 F100\nL +5\nL Y+2\nL +3", "L X+1 Y+2 F100 M2\nL X+5",
    "L X+1 F100 M30\nL X+5", "L X+1 F100\nL X+999999999999999999999999999999999999999999999999999" + "9" * 300,
    "L X+1 F" + "9" * 400 + "\nL X+2", "L X+5 F100 M91", "L X+1 F100 M140 MB MAX\nL X+2", "Q1 = 5\nL X+Q1 F100\nL X+1",
]


def reading(text: str, context: MachineContext, *, shortcuts: bool, source: str = "t.h") -> list[str]:
    """Everything a reading gives, bit for bit (or its error)."""
    try:
        prog = parse_heidenhain(text, source=source, context=context, shortcuts=shortcuts)
    except (GCodeError, InputError) as exc:
        return [f"error: {exc}"]
    return program_digest(prog)


def assert_same(text: str, context: MachineContext = CONTEXT) -> list[str]:
    fast = reading(text, context, shortcuts=True)
    assert fast == reading(text, context, shortcuts=False)
    return fast


def test_plain_words_are_read():
    assert plain_words("L X+1.5 IY-2 Z+0 R0 F200 M3 M90") == PlainWords(
        "L", {0: (False, 1.5), 1: (True, -2.0), 2: (False, 0.0)}, (3, 90), 200.0, False, None, None)
    assert plain_words("L IZ-.5 FMAX") == PlainWords("L", {2: (True, -0.5)}, (), None, True, None, None)
    assert plain_words("CC X+15 Y-2.") == PlainWords("CC", {0: (False, 15.0), 1: (False, -2.0)}, (), None, False,
                                                     None, None)
    assert plain_words("C X+20.5\tY-2.25 DR+ F450") == PlainWords("C", {0: (False, 20.5), 1: (False, -2.25)}, (),
                                                                  450.0, False, None, True)
    assert plain_words("CR X+5 Y+5 R-20 DR-") == PlainWords("CR", {0: (False, 5.0), 1: (False, 5.0)}, (), None,
                                                            False, -20.0, False)
    assert plain_words("L X-0 M0003 M08").m == (3, 8)


@pytest.mark.parametrize("code", DECLINED_CODES)
def test_other_blocks_are_left_to_the_general_path(code):
    assert plain_words(code) is None


@pytest.mark.parametrize("state", list(MODELLED))
def test_modelled_states_give_the_general_blocks(state):
    got = assert_same(MODELLED[state] + TAIL)
    assert len(got) > 5 and not got[0].startswith("error"), got[0]


@pytest.mark.parametrize("state", list(DECLINED))
def test_declined_states_give_the_general_blocks(state):
    start = "2 L X+0 Y+0 Z+5 R0 FMAX\n"
    moves = MOVES.replace(" R0", "")
    got = assert_same(HEAD + start + DECLINED[state] + moves + TAIL)
    plain = assert_same(HEAD + start + moves + TAIL)
    assert got[-len(plain) + 1:] != plain[1:] or got[0].startswith("error")  # the state changes the blocks


@pytest.mark.parametrize("body", ODD)
def test_odd_blocks_give_the_general_blocks_or_error(body):
    assert_same(HEAD + "2 L X+0 Y+0 Z+5 R0 FMAX\n" + body + "\n" + TAIL)
    assert_same(HEAD + "2 L X+0 Y+0 Z+5 R0 FMAX\n" + body + "\n")


@pytest.mark.parametrize("code", DECLINED_CODES)
def test_declined_codes_in_a_program_give_the_general_blocks(code):
    assert_same(HEAD + "2 L X+0 Y+0 Z+5 R0 F100\n3 CC X+1 Y+1\n4 Q1 = 2\n5 " + code + "\n" + MOVES + TAIL)


#: Lines in the forms programs are saved in: the same line with a ``;`` comment after it goes the general way of
#: :func:`interpolators.heidenhain_words.source_blocks`, without it the one-pattern way where it applies.
SOURCE_LINES = ["5 L X+1 Y-2 FMAX", "  12   L X+1", "L X+1 R0 F100", "12", "12L X+1", "5 L X+1 *", "5 L X+1*",
                "/5 L X+1", "5 /L X+1", "5 L X+1,5", "5 L X+1 ~", "\f5 L X+1", "5 \fL X+1", "5 * - a structure block",
                "5\tL\tX+1", "007 CC X+0 Y+0", "5 CYCL DEF 200 DRILLING", "5 PATTERN DEF", "5 CYCL DEF 7.0 DATUM SHIFT",
                "5 TOOL CALL 1 Z S3000", "9999999999 L X+1", "\u0665 L X+1", "  ", "", "*", "5 L X+1 \u00a0"]


@pytest.mark.parametrize("line", SOURCE_LINES)
def test_source_lines_read_alike(line):
    """A line read as one block with one pattern gives the block the general reading gives: its line, number,
    code, column and skip mark (its text differs by the comment), also before a cycle's parameter line."""
    for after in ("\nQ200=+2\n", "\n6 L X+2\n", ""):
        fast = [dataclasses.astuple(b)[:4] + (b.skip,) for b in source_blocks(line + after)]
        general = [dataclasses.astuple(b)[:4] + (b.skip,) for b in source_blocks(line + " ;" + after)]
        assert fast == general


def test_an_fk_element_waiting_is_left_to_the_general_path():
    """An FK line whose length is open: the general path refuses the L after it (the TNC resolves FK elements
    from the FK blocks that follow them), which the shortcut must not run."""
    got = assert_same(HEAD + "2 L X+0 Y+0 Z+0 R0 F100\n3 FL AN+0\n4 L X+5 Y+0\n5 FL X+20 Y+0\n" + TAIL)
    assert got[0].startswith("error") and "FL" in got[0]


def test_the_approach_after_a_plain_rapid_starts_as_a_rapid():
    """APPR LT moves from its start point as the block before it did (a rapid after FMAX): the shortcut keeps
    the kind of the last plain block for it."""
    got = assert_same(HEAD + "2 L X+40 Y+10 Z+0 R0 FMAX\n3 APPR LT X+20 Y+20 LEN15 R0 F100\n4 L X+35 Y+35\n" + TAIL)
    assert " 'rapid' " in got[2]


def test_a_called_program_reads_alike(tmp_path):
    """A called program in INCH with a datum shift of its own, and the caller's plain blocks after it in MM."""
    (tmp_path / "SUB.h").write_text("0 BEGIN PGM SUB INCH\n1 CYCL DEF 7.0 DATUM SHIFT\n2 CYCL DEF 7.1 X+1\n"
                                    + MOVES + "3 END PGM SUB INCH\n")
    main = tmp_path / "MAIN.h"
    text = HEAD + MOVES + "40 CALL PGM SUB.h\n" + MOVES + TAIL
    main.write_text(text)
    fast = reading(text, CONTEXT, shortcuts=True, source=str(main))
    assert fast == reading(text, CONTEXT, shortcuts=False, source=str(main))
    assert len(fast) == 1 + 3 * 11


def test_a_long_cam_program_reads_alike():
    """Thousands of plain lines on a spiral with an arc about CC every 40 blocks, in MM and INCH."""
    lines = ["0 BEGIN PGM CAM MM", "1 TOOL CALL 3 Z S8000", "2 L X+0 Y+0 Z+5 R0 FMAX", "3 L Z-1 F300"]
    x = y = 0.0
    for i in range(3000):
        if i % 40 == 20:
            lines += [f"{i + 10} CC X+0 Y+0", f"C X{-x:+.4f} Y{-y:+.4f} DR+"]
            x, y = -x, -y
        else:
            x, y = 20 * math.cos(0.01 * i), 20 * math.sin(0.01 * i)
            lines.append(f"{i + 10} L X{x:+.4f} Y{y:+.4f} Z{-1 - 1e-4 * i:+.4f} F{900 + i % 5 * 100} M90")
    text = "\n".join(lines) + "\nEND PGM CAM MM\n"
    assert len(assert_same(text)) == 3003
    assert len(assert_same(text.replace(" MM", " INCH"))) == 3003


@pytest.mark.slow
@pytest.mark.skipif(corpus_dir() is None, reason="gcode corpus absent (../shared/data/gcode-corpus)")
def test_corpus_reads_alike():
    """Every TNC program of the corpus, in the context of its origin: the same reading both ways."""
    checked = 0
    for name, text, context in corpus_programs("heidenhain"):
        fast = reading(text, context, shortcuts=True)
        assert fast == reading(text, context, shortcuts=False), name
        checked += len(fast)
    assert checked > 20_000


def _number(rng, v: float) -> tuple[str, float]:
    """A coordinate as a TNC post writes it (signed, 4 decimals, now and then its trailing zeros cut), and its
    value."""
    text = f"{v:+.4f}"
    text = text.rstrip("0") if rng.random() < 0.3 else text
    return text, float(text)


def _random_move(rng, st: dict) -> list[str]:
    """Plain blocks from the generator's position ``st["pos"]`` (program coordinates, X Y the working plane)."""
    pos = st["pos"]
    kind = rng.choice(["L", "L", "L", "LI", "C", "CR", "FMAX"])
    tail = []
    if rng.random() < 0.3:
        tail.append(rng.choice(["F100", "F250.5", "F1200", "F.5", "F+300", "F50."]))
    if rng.random() < 0.2:
        tail.append(rng.choice(["M3", "M8", "M90", "M126", "M05"]))
    if rng.random() < 0.1:
        tail.insert(0, "R0")
    if kind in ("C", "CR"):
        r, a0, sweep = rng.uniform(0.5, 5.0), rng.uniform(0, 2 * math.pi), rng.uniform(0.1, 6.0)
        (cx, x0), (cy, y0) = _number(rng, pos[0] + r * math.cos(a0)), _number(rng, pos[1] + r * math.sin(a0))
        r = math.hypot(pos[0] - x0, pos[1] - y0)
        end = [x0 + r * math.cos(a0 + math.pi + sweep), y0 + r * math.sin(a0 + math.pi + sweep), pos[2]]
        if rng.random() < 0.3:
            end[2] += rng.uniform(-1, 1)  # a helix
        if rng.random() < 0.01:
            end[0] += 0.5  # off the circle: an error
        words = []
        for i in range(3 if end[2] != pos[2] else 2):
            text, end[i] = _number(rng, end[i])
            words.append("XYZ"[i] + text)
        sense = rng.choice(["DR+", "DR-"])
        st["pos"] = end
        if kind == "C":
            return [f"CC X{cx} Y{cy}", " ".join(["C", *words, sense, *tail])]
        big = (sweep > math.pi) == (sense == "DR+")
        return [" ".join(["CR", *words, f"R{'-' if big else '+'}{r:.4f}", sense, *tail])]
    new = list(pos)
    words = []
    for i in sorted(rng.sample(range(3), rng.randint(1, 3))):
        v = rng.uniform(-20, 20)
        text, value = _number(rng, v if kind == "LI" else pos[i] + v)
        new[i] = pos[i] + value if kind == "LI" else value
        words.append(("I" if kind == "LI" else "") + "XYZ"[i] + text)
    st["pos"] = new
    if kind == "FMAX":
        tail = [w for w in tail if not w.startswith("F")] + ["FMAX"]
    return [" ".join(["L", *words, *tail])]


#: Blocks that change the modal state (the shortcut models them or declines the blocks after them), each a
#: self-contained stretch; the generator returns to X+0 Y+0 Z+0 after each.
_CHANGES = ["CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+5\nCYCL DEF 7.2 Y-2",
            "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+0",
            "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+30", "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+0",
            "CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X", "CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1",
            "CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 1.5", "CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 1",
            "TOOL CALL 2 Z S4000 DL+0.5", "TOOL CALL 1 Z S2000", "CYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1 T0.02",
            "STOP", "M5", "Q1 = 2.5\nL X+Q1 Y+0 F100", "L X+0 Y+0 Z+0 F100\nL X+5 Y+0\nRND R1\nL X+5 Y+5",
            "L X+0 Y+0 Z+0 F100\nL X+5 Y+0\nCHF 1\nL X+5 Y+5",
            "L X+0 Y+0 RL F100\nL X+20 Y+0\nL X+20 Y+20\nL X+0 Y+20\nL X+0 Y+0\nL X-10 Y-10 R0",
            "LBL {label}\nL IX+1 F100\nCALL LBL {label} REP 1", "CC X+0 Y+0\nLP PR+3 PA+45 F100", "L X+1 M91 FMAX",
            "* - a structure block", "; a comment", "/L X+1 F100"]
#: Blocks that refuse the program or end it (drawn less often).
_ENDS = ["L X+1 F0", "C X+1 Y+1", "L IX+1 X+1", "L X+1 M30\nL X+2 F100", "CR X+100 Y+0 R+1 DR+", "M2",
         "L X+1 F100 M99"]


def random_program(rng) -> str:
    """A program of plain blocks among modal changes the shortcut models or declines."""
    st = {"pos": [0.0, 0.0, 0.0]}
    unit = rng.choice(["MM", "INCH"])
    lines = [f"BEGIN PGM R {unit}", "TOOL CALL 1 Z S3000", "L X+0 Y+0 Z+0 R0 FMAX", "L F500"]
    for label in range(rng.randint(10, 50)):
        if rng.random() < 0.75:
            lines.extend(_random_move(rng, st))
            continue
        lines.extend(rng.choice(_ENDS if rng.random() < 0.02 else _CHANGES).format(label=label + 1).split("\n"))
        lines.append("L X+0 Y+0 Z+0 R0 FMAX")
        st["pos"] = [0.0, 0.0, 0.0]
    lines.append(f"END PGM R {unit}")
    numbered = rng.random() < 0.7
    return "\n".join(f"{i} {ln}" if numbered else ln for i, ln in enumerate(lines)) + "\n"


@pytest.mark.parametrize("seed", range(8))
def test_random_programs_read_alike(seed):
    """Generated programs (fixed seeds): plain lines, incremental lines, rapids, arcs about CC and by radius,
    helices, F changes, M functions, block numbers, among modal changes, Q parameters, comments, block skips
    and errors: the same reading both ways; and enough of them run for the comparison to say something."""
    rng = random.Random(seed)
    accepted = blocks = 0
    for _ in range(30):
        got = assert_same(random_program(rng))
        if not got[0].startswith("error"):
            accepted += 1
            blocks += len(got) - 1
    assert accepted >= 15 and blocks >= 300
