"""The ISO reader's plain-move shortcut (:mod:`interpolators.iso_fast`) under G93 inverse time, and its G93/G94 words:
the blocks the general executor makes, bit for bit.

LinuxCNC G-code reference, "G93, G94, G95: Feed Rate Mode": under G93 "an F word means the move should be completed
in [one divided by the F number] minutes", "an F word must appear on every line which has a G1, G2, or G3 motion,
and an F word on a line that does not have G1, G2, or G3 is ignored", G0 is not affected; rs274ngc refuses a feed
move without F ("F word missing with inverse time g1 move" / "arc move", interp_convert.cc convert_straight and
convert_arc) and G94 sets the feed rate to 0 (convert_feed_mode), so the first feed move after G93 needs its own F
too. The Haas mill manual (G93: "each non-rapid motion block must have its own feedrate (F) specification") and
Fanuc's (B-62764EN 5, "Inverse time feed (G93)") say the same of the F word.

Each program is read twice, with the shortcut and all the general way (``shortcuts=False``), under each dialect, and
the two readings must be the same: every field of every block, the notes, the messages and the axes, or the same
error with the same message and line. The hand-written programs cover G93 lines, arcs and helices, moves of the
rotary axes alone and with X Y Z, G0 under G93 (with and without its ignored F), a zero-length feed move, G93 and
G94 on the move's own line, G94 back (the feed cleared: the next feed move needs an F), and the errors: a feed move
without F under G93 (alone, modal, an arc, after G93 on its line), F0, G93 G94 on one line, G95. Generated
programs (fixed seeds) mix them at random. The corpus' programs with G93, when the corpus is present, are read both
ways too.
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest

from benchmarks.gcode_corpus import corpus_dir, without_remapped_m
from interpolators.iso import parse_iso
from tests.interpolators.block_digest import corpus_programs
from tests.interpolators.test_reader_fast_rotary import FIVE_AXIS, assert_same
from vcnc.core.errors import InputError

DIALECTS = ("linuxcnc", "fanuc", "haas", "grbl")

#: 5-axis CAM output in inverse time: an F on every feed line (CAM's 1/min), rotary moves with and without X Y Z,
#: arcs and a helix, N numbers, a G0 with an F (ignored), a repeated point (a zero-length feed move).
G93_MOVES = """N10 G0 X0. Y0. Z5. A0. C0.
N20 G93 G1 Z-1. F60.
N30 G1 X10.5 Y-2.25 A15. F12.5
N40 A30. C-45. F30.
N50 G1 A45. F3.
N60 G1 X12. B10. F450.
N70 G2 X22. Y-2.25 I5. J0. A60. F4.
N80 G3 X12. Y-2.25 Z-1.5 I-5. J0. C90. F2.
N90 G1 U5. F20.
N100 G1 X1. U6. V-2. W.5 A50. F7.
N110 G0 A0. C0. U0. V0. W0. F99.
N120 G0 X3. B-15.
x4. y1. a12.5 c7.25 g1 f30
N130 G1 X4. Y1. A12.5 F100.
N140 G1 Z2. A-7.5 F1200.
N150 G2 X6. Y1. I1. J0. F10.
"""

#: Inverse time as the posts write it, each a program of whole blocks; ``G94 back`` returns to a feed per minute.
PROGRAMS = {
    "G93 on its own line": "G21 G90 G94\nG93\n" + G93_MOVES,
    "G93 on the first move's line": "G21 G90\n" + G93_MOVES,
    "inch": "G20 G90 G93\n" + G93_MOVES,
    "incremental": "G21 G91 G93\nG1 X1. A5. F10.\nG1 Z-2. F20.\nG2 X2. Y0. I1. J0. C5. F3.\nG1 A-5. F6.\nG0 X1.\n",
    "G18 and G19 arcs": "G21 G90 G93\nG0 X0. Y0. Z0.\nG18 G2 X2. Z0. I1. K0. B20. F5.\nG19 G3 Y2. Z0. J1. K0. F6.\n"
                        "G17 G1 X0. Y0. F3.\n",
    "work offset and tool length": "G21 G90 G55\nT1 M6\nG43 H1\n" + G93_MOVES,
    "G94 back on its own line": "G21 G90\n" + G93_MOVES + "G94\nG1 X5. F300.\nX6.\nG0 Z10.\nG1 X7. A5.\n",
    "G94 back on a rapid": "G21 G90\n" + G93_MOVES + "G94 G0 Z10.\nG1 X5. F300.\nX6. Y2.\n",
    "G94 back on a feed move": "G21 G90\n" + G93_MOVES + "G94 G1 X5. F300.\nX6. Y2.\n",
    "R arcs": "G21 G90 G93\nG0 X0. Y0.\nG2 X10. Y0. R5. A20. F3.\nG3 X18. Y0. R-5. F2.\n"
              "G2 X28. Y0. Z-1. R5.01 C30. F1.5\nG20 G3 X1.5 Y0. R.2 F4.\n",
    "G93 again after G94": "G21 G90 G94 F500.\nG1 X1. Y1.\nG93 G1 X2. F10.\nG1 X3. Y2. A5. F20.\nG94 G1 X4. F400.\n"
                           "G93 X5. F4.\nG94 F300.\nG1 X6.\n",
    "G94 twice, an F after the second": "G21 G90 F500.\nG93 G1 X1. F2.\nG94 G1 X2. F300.\nG94 G1 X3. F200.\nX4.\n",
    # LinuxCNC's note on a G1 alone reads the modal feed, which a G93 F leaves as it was
    "a G1 alone after a G93 move": "G21 G90\nG93 G1 X1. F2.\nG1\nG94 F300.\nG1 X2.\n",
    # length x F far under 0.1 mm/min (rs274 before 2.9.0 raised it to 0.1): test_no_floor_under_the_inverse_time_rate
    "short moves at a small F": "G21 G90 G93\nG0 X0. Y0. Z0. A0.\nG1 X.001 F1.\nG1 X1. F.01\nG1 Z-.0002 A178.639 F5.\n"
                                "G2 X1.002 Y0. I.001 J0. F.5\n",
}

#: Programs the general path refuses (the same error and line both ways) or reads with a note.
ERRORS = {
    "feed move without F (modal G1)": "G21 G90 G93\nG1 X1. F10.\nX2.\n",
    "G1 without F": "G21 G90 G93\nG0 X1.\nG1 X2. Y1.\n",
    "arc without F": "G21 G90 G93\nG0 X0. Y0.\nG2 X2. Y0. I1. J0.\n",
    "rotary move without F": "G21 G90 G93\nG1 X1. F10.\nG1 A20.\n",
    "G93 on the line, no F": "G21 G90 F300.\nG1 X1.\nG93 G1 X2.\n",
    "F0 under G93": "G21 G90 G93\nG1 X1. F0\n",
    "F0. under G93": "G21 G90 G93\nG1 X1. A5. F0.\n",
    "negative F under G93": "G21 G90 G93\nG1 X1. F-2.\n",
    "G94 back without F": "G21 G90 F300.\nG93 G1 X1. F2.\nG94\nG1 X2.\n",
    "G94 on the line without F": "G21 G90 F300.\nG93 G1 X1. F2.\nG94 G1 X2.\n",
    "G94 on the line, modal move": "G21 G90 F300.\nG93 G1 X1. F2.\nG94 X2.\n",
    "G93 and G94 on one line": "G21 G90\nG93 G94 G1 X1. F2.\n",
    "G95 on the line": "G21 G90 S1000 M3\nG95 G1 X1. F.1\n",
    "an arc off its circle": "G21 G90 G93\nG0 X1. Y1.\nG2 X5. Y1. I1. J0. F3.\n",
    "F without a decimal point (Fanuc)": "G21 G90 G93\nG1 X1. F2\nG1 X2. A10. F30\n",
    "G93 with a cycle after": "G21 G90 G93 G98\nG1 X1. F2.\nG81 X5. Y5. Z-2. R1. F100.\n",
    "G93.0 and G94.0": "G21 G90\nG93.0 G1 X1. F2.\nG94.0 G1 X2. F300.\n",
    "G93 twice on one line": "G21 G90 F500.\nG93 G93 G1 X1. F2.\n",
    # LinuxCNC refuses the last move (every G94 clears the feed: Dialect.feed_mode_clears_feed), the others read F300
    "G94 twice": "G21 G90 F500.\nG93 G1 X1. F2.\nG94 G1 X2. F300.\nG94 G1 X3.\n",
    "G94 again without F": "G21 G90 G94 F100.\nG1 X1.\nG94\nG1 X2.\n",
    "G94 again on the move's line": "G21 G90 G94 F100.\nG1 X1.\nG94 G1 X2.\nG1 X3. F50.\n",
    # the message names the F0 only while no F > 0 came after it (a G93 F too)
    "F0, G93 moves, G94 without F": "G21 G90\nF0\nG93 G1 X1. F2.\nG94\nG1 X2.\n",
}


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize("name", list(PROGRAMS))
def test_inverse_time_gives_the_general_blocks(name, dialect):
    context = FIVE_AXIS.with_dialect(dialect)
    got = assert_same(PROGRAMS[name] + "M2\n", context)
    assert not got[0].startswith("error"), got[0]
    assert len(got) >= 3  # the header and two blocks at least


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize("name", list(ERRORS))
def test_inverse_time_errors_are_the_general_ones(name, dialect):
    context = FIVE_AXIS.with_dialect(dialect)
    assert_same(ERRORS[name] + "M2\n", context)
    assert_same(ERRORS[name], context)


@pytest.mark.parametrize("name", ["feed move without F (modal G1)", "arc without F", "G93 on the line, no F",
                                  "F0 under G93", "G94 back without F", "G94 on the line without F"])
def test_the_errors_name_the_line_and_the_missing_feed(name):
    """The error of a feed move without its F under G93 (or after G94 ended it) is the general path's: file, line,
    what is missing."""
    got = assert_same(ERRORS[name] + "M2\n", FIVE_AXIS)
    line = len(ERRORS[name].splitlines())
    assert got[0].startswith(f"error: t.ngc:{line}:"), got[0]
    assert "inverse time (G93) without an F word" in got[0] or "F > 0 [1/min]" in got[0] \
        or "G94 after G93 resets the feed" in got[0], got[0]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_the_modal_feed_read_back_after_g93_moves(dialect):
    """Fanuc/Haas ``#4109`` (the modal F, :mod:`interpolators.iso_system`) after G93 moves: the F of a G93 block is
    its time, not the modal feed, so the G94 feed before G93 is read back as the general path keeps it."""
    text = "G21 G90 G94 F300.\nG1 X1.\nG93 G1 X2. A5. F2.\nG1 X3. F4.\n#100=#4109\nG94 F#100\nG1 X4.\nM30\n"
    got = assert_same(text, FIVE_AXIS.with_dialect(dialect))
    assert not got[0].startswith("error"), got[0]
    last = parse_iso(text, context=FIVE_AXIS.with_dialect(dialect)).blocks[-1]
    assert last.feed == pytest.approx(300.0 / 60.0)


@pytest.mark.parametrize("shortcuts", [True, False])
def test_fanuc_inverse_time_arcs_take_f_as_feed_over_radius(shortcuts):
    """FANUC Series 16/18-MC operator's manual (B-62764EN), "Inverse time feed (G93)": for circular interpolation
    "FRN = feedrate / arc radius" (not 1/time): a half circle of R10 at F2 runs at 20 mm/min and takes pi/2 min; a
    helix keeps R x F in its plane. LinuxCNC and Haas take 1/F minutes for every block (the arc at 62.83 mm/min, 30 s;
    rs274 prints SET_FEED_RATE(62.8319) and (127.2453) for these two arcs)."""
    text = "G21 G90 G0 X0. Y0. Z0.\nG93\nG2 X20. Y0. I10. J0. F2.\nG3 X0. Y0. Z-5. I-10. J0. F4.\n" \
           "G2 X20. Y0. R10. F2.\nM30\n"
    fanuc = parse_iso(text, context=FIVE_AXIS.with_dialect("fanuc"), shortcuts=shortcuts).blocks[1:]
    arc = fanuc[0]
    assert arc.feed * 60.0 == pytest.approx(20.0) and arc.length / arc.feed == pytest.approx(30 * math.pi)
    helix = fanuc[1]
    assert helix.length / helix.feed == pytest.approx(15 * math.pi)  # pi / 4 min: R x F = 40 mm/min in the plane
    assert fanuc[2].feed == fanuc[0].feed  # by R as by I J
    for dialect in ("linuxcnc", "haas"):
        arc, helix, by_r = parse_iso(text, context=FIVE_AXIS.with_dialect(dialect), shortcuts=shortcuts).blocks[1:]
        assert arc.feed * 60.0 == pytest.approx(62.8319, abs=1e-4) and helix.feed * 60.0 == pytest.approx(127.2453,
                                                                                                            abs=1e-4)
        assert by_r.length / by_r.feed == pytest.approx(30.0)


def test_inverse_time_moves_are_taken_by_the_shortcut(monkeypatch):
    """The G93 moves go the short way: with the general executor's block maker broken they still read (so the
    identities above compare two paths, not one with itself), each feed move taking 1/F minutes."""
    import interpolators.iso as iso

    def refused(*args, **kwargs):
        raise AssertionError("the general path ran a plain G93 move")

    prog = parse_iso(PROGRAMS["G93 on the first move's line"] + "M2\n", context=FIVE_AXIS, shortcuts=True)
    monkeypatch.setattr(iso, "motion_block", refused)
    fast = parse_iso(PROGRAMS["G93 on the first move's line"] + "M2\n", context=FIVE_AXIS)
    assert len(fast.blocks) == len(prog.blocks) == 16
    by_line = {b.line: b for b in fast.blocks}
    for line, f in ((3, 60.0), (4, 12.5), (7, 450.0), (8, 4.0), (9, 2.0), (16, 1200.0)):  # N20-N80, N140
        b = by_line[line]
        assert b.length / b.feed == pytest.approx(60.0 / f)  # seconds: 1/F minutes
    rot = by_line[6]  # N50 G1 A45. F3.: A alone, 15 deg in 1/3 min
    assert rot.length == 0.0 and rot.feed == pytest.approx(15.0 * 3 / 60)
    assert by_line[12].feed == np.inf  # N110 G0 .. F99.: a rapid, its F ignored
    assert by_line[15].length == by_line[15].feed == 0.0  # N130: the point again, no motion


@pytest.mark.parametrize("shortcuts", [True, False])
def test_no_floor_under_the_inverse_time_rate(shortcuts):
    """LinuxCNC 2.9.0 and later (rs274ngc interp_inverse.cc ``inverse_time_rate_straight`` / ``_arc``: ``rate =
    length * block->f_number``, 0.1 only for a zero-length move; commit b244b375dd for LinuxCNC issue #2410, "G93
    rotary moves with a very small linear move run too fast") run every G93 move in 1/F minutes however short it is.
    Earlier versions took ``MAX(0.1, length * F)`` units/min, so a move shorter than 0.1/F ran faster than asked
    (the Debian 12 rs274, a 2.9.0 pre-release of 2023-02-08, prints SET_FEED_RATE(0.1000) for each move below, and
    the issue's 0.0002 mm Z with 178.8 deg of A ran at A's velocity limit). vcnc follows the release."""
    text = PROGRAMS["short moves at a small F"] + "M2\n"
    short, slow, tilt, arc = parse_iso(text, context=FIVE_AXIS, shortcuts=shortcuts).blocks[1:]
    assert short.length / short.feed == pytest.approx(60.0)  # 1 um in 1 min (0.001 mm/min), not 0.6 s
    assert slow.length / slow.feed == pytest.approx(6000.0)  # 0.999 mm at F.01: 100 min, not 9.99 min
    assert tilt.length == pytest.approx(0.0002) and tilt.length / tilt.feed == pytest.approx(12.0)  # 1/5 min
    assert arc.length == pytest.approx(math.pi * 0.001) and arc.length / arc.feed == pytest.approx(120.0)


def _random_g93_move(rng: random.Random, inverse: bool) -> list[str]:
    """A move of random X Y Z A C words (sometimes an arc from X0 Y0, sometimes with a G93/G94 of its own), with an
    F as an inverse-time post writes it: on almost every feed move under G93 or after G94 ends it (left out or F0
    now and then: an error)."""
    feed = f"F{rng.uniform(0.5, 3000):.4f}" if rng.random() < 0.5 else rng.choice(["F2.", "F60.", "F1200"])
    if rng.random() < 0.02:
        feed = rng.choice(["F0", ""])
    if rng.random() < 0.12:
        r = rng.uniform(0.5, 3.0)
        arc = f"G{rng.choice([2, 3])} X{2 * r:.4f} Y0. I{r:.4f} J0."
        if rng.random() < 0.5:
            arc += f" Z{rng.uniform(-2, 2):.3f}"
        if rng.random() < 0.5:
            arc += f" A{rng.uniform(-90, 90):.3f}"
        return ["G90 G0 X0. Y0.", f"{arc} {feed}", "G0 Z0."]
    code = rng.choice(["G0", "G1", "G01", "", "", "G93 G1", "G94 G1", "G93", "G94 G0", "G0 G93"])
    words = [code]
    for letter in rng.sample("XYZAC", rng.randint(1, 4)):
        words.append(f"{letter}{rng.uniform(-30, 30):.4f}")
    if inverse or "G9" in code or rng.random() < 0.3:
        words.append(feed)
    return [" ".join(w for w in words if w)]


def random_g93_program(rng: random.Random) -> str:
    """A program of moves among G93/G94 changes (on their own lines and on the moves'), G20/G21, G90/G91, offsets."""
    lines = [rng.choice(["G21", "G20"]) + " G17 G90", "G0 X0. Y0. Z0. A0. C0.", "G1 F500."]
    inverse = False
    for _ in range(rng.randint(10, 40)):
        if rng.random() < 0.15:
            change = rng.choice(["G93", "G94 F300.", "G94 F300.", "G94", "G91", "G90", "G20", "G21", "G55",
                                 "G92 X0. A0.", "G92.1", "G0 A0. C0.", "M0"])
            lines += [change, "G90 G0 X0. Y0. Z0."]
        else:
            lines += _random_g93_move(rng, inverse)
        recent = " ".join(lines[-3:])
        inverse = "G93" in recent or inverse and "G94" not in recent
    lines.append("M30")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("seed", range(8))
def test_random_inverse_time_programs_read_alike(seed):
    """Generated programs (fixed seeds): the same reading both ways under each dialect, errors included; enough of
    them run through, and enough fail, for the comparison to say something."""
    rng = random.Random(1000 + seed)
    accepted = refused = 0
    for _ in range(20):
        text = random_g93_program(rng)
        for dialect in DIALECTS:
            got = assert_same(text, FIVE_AXIS.with_dialect(dialect))
            accepted += not got[0].startswith("error")
            refused += got[0].startswith("error")
    assert accepted >= 40 and refused >= 4, (accepted, refused)


@pytest.mark.skipif(corpus_dir() is None, reason="gcode corpus absent (../shared/data/gcode-corpus)")
def test_corpus_programs_with_g93_read_alike():
    """The corpus' programs with G93 (LinuxCNC's 5-axis boat-xyzac, remapped M lines blanked; daisy), in the
    context of their origin (``vcnc interpolate``'s: all six extra axes)."""
    checked = 0
    for _, text, context in corpus_programs("iso"):
        if "G93" not in text.upper():
            continue
        for body in (text, without_remapped_m(text)):
            if body is not None:
                got = assert_same(body, context)
                checked += len(got) if not got[0].startswith("error") else 0
    assert checked > 1000


#: Hand-written (the brief's case, checked with rs274): ``F100 / G1 X1 / G94 / G1 X2`` is "Cannot do g1 with zero
#: feed rate" in LinuxCNC's rs274 (interp_convert.cc ``convert_feed_mode`` sets the feed rate to 0 on every G94).
G94_AGAIN = "G21 G90\nF100.\nG1 X1.\nG94\nG1 X2.\nM2\n"


@pytest.mark.parametrize("shortcuts", [True, False])
def test_linuxcnc_g94_clears_the_feed_even_when_active(shortcuts):
    """LinuxCNC: the G94 word clears F100 though G94 is already on; the next feed move has no feed (both ways)."""
    with pytest.raises(InputError, match=r"t\.ngc:5:.*a G94/G95 word cleared the feed"):
        parse_iso(G94_AGAIN, context=FIVE_AXIS.with_dialect("linuxcnc"), source="t.ngc", shortcuts=shortcuts)
    # the block's own F comes after its G94 (rs274 runs ``G94 G1 X2 F50`` at F50)
    text = G94_AGAIN.replace("G1 X2.", "G1 X2. F50.").replace("G94\n", "G94 G1 X1.5 F40.\n")
    blocks = parse_iso(text, context=FIVE_AXIS.with_dialect("linuxcnc"), shortcuts=shortcuts).blocks
    assert [b.feed for b in blocks[-2:]] == [pytest.approx(40.0 / 60.0), pytest.approx(50.0 / 60.0)]


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "grbl"])
@pytest.mark.parametrize("shortcuts", [True, False])
def test_other_controls_keep_the_feed_over_a_repeated_g94(dialect, shortcuts):
    """Fanuc, Haas, grbl: G94 under G94 changes nothing; the move after it runs at F100."""
    blocks = parse_iso(G94_AGAIN, context=FIVE_AXIS.with_dialect(dialect), shortcuts=shortcuts).blocks
    assert blocks[-1].feed == pytest.approx(100.0 / 60.0)


def test_linuxcnc_g95_again_clears_the_feed_per_revolution():
    """rs274: ``G95 F0.1 S1000 M3 / G1 X1 / G95 / G1 X2`` is "Cannot do g1 with zero feed rate" (convert_feed_mode
    sets the feed rate to 0 on each G95 as well); Fanuc keeps F0.1 per revolution."""
    text = "G21 G90 S1000 M3\nG95 F0.1\nG1 X1.\nG95\nG1 X2.\nM2\n"
    with pytest.raises(InputError, match=r"t\.ngc:5:"):
        parse_iso(text, context=FIVE_AXIS.with_dialect("linuxcnc"), source="t.ngc")
    last = parse_iso(text, context=FIVE_AXIS.with_dialect("fanuc")).blocks[-1]
    assert last.feed == pytest.approx(0.1 * 1000 / 60.0)
