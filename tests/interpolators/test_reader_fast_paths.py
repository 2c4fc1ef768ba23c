"""The reader's shortcuts give what the general machinery gives.

:func:`interpolators.iso_words.plain_words` reads a line of letters and plain numbers (most CAM output)
with one regular expression; every other line goes through :func:`interpolators.iso_words.read_words`
character by character. Here both read the same lines: the words (letter, value, column, text) must be
equal, and a line the shortcut declines must be one the general reader reads or rejects itself. The
programs of the G-code corpus (when present) are read line by line both ways.

The ISO expression reader climbs operator precedence instead of recursing once per level; the
precedence and associativity of LinuxCNC's "Binary Operators" (G-code overview: ``**`` first, then
``* / MOD``, ``+ -``, the comparisons, ``AND OR XOR``; equal levels left to right) are checked on
expressions whose values follow from those rules.
"""

from __future__ import annotations

import math

import pytest

from benchmarks.gcode_corpus import corpus_dir, manifest
from interpolators import parse_program
from interpolators._words import Where, lines_of, program_text, read_number
from interpolators.iso_words import plain_words, read_words, strip_comments
from vcnc.errors import GCodeError

WHERE = Where("t.nc", 1, "")


def general_words(code: str):
    """The words by the general reader: a value reader that is the default one (a plain number)."""
    return read_words(code, WHERE, value=lambda pos, letter: read_number(code, pos, WHERE, what=f"word {letter}",
                                                                          word_start=pos - 1))


PLAIN = ["G1 X-21.131 Y34.719 Z0.996 F400.000", "N120 G01 X10 Y+.5 Z5. F1200", "g0x1y2z3", "X 12  Y\t-3 Z +4",
         "  G2 X1 Y1 I.5 J0 K0 R1.25  ", "M30", "", "   ", "\tG17\tG90\r", "T1 M6 S10000 M3", "X1\fY2\vZ3",
         "N1G1X1.Y2.Z3.F4.", "G1 X999999999 Y-1000000000",
         "X1e5", "X١٢"]  # an E word (judged when the block runs); digits of any script, as float() reads them

NOT_PLAIN = ["G1 X1.2.3", "X1 2", "G1 X-", "X", "G1 X#1", "G1 X[1+2]", "@5 ^90", "G1 X1 /2", "G1 X1,R2",
             "X1 ... Y2", "G1 X1000000001", "G1 X\f1", "G1 X1²", "Ä1", "G1 X.", "X+-1"]


@pytest.mark.parametrize("code", PLAIN)
def test_plain_lines_read_as_the_general_reader_reads_them(code):
    fast = plain_words(code)
    assert fast is not None
    assert fast == general_words(code)
    assert read_words(code, WHERE) == fast


@pytest.mark.parametrize("code", NOT_PLAIN)
def test_other_lines_are_left_to_the_general_reader(code):
    assert plain_words(code) is None
    try:
        expected = general_words(code)
    except GCodeError as exc:
        with pytest.raises(GCodeError) as got:
            read_words(code, WHERE)
        assert str(got.value) == str(exc)
    else:
        assert read_words(code, WHERE) == expected


def test_long_blank_runs_are_read_in_one_pass():
    """A comment blanked out leaves a long run of blanks (a fuzzed program's 55,000-character comment once made
    the shortcut's pattern retry the run at each of its blanks: minutes on one line)."""
    blanks = " " * 300_000
    assert plain_words("N0" + blanks) == general_words("N0" + blanks)
    assert plain_words("N0" + blanks + "X1") == general_words("N0" + blanks + "X1")
    assert plain_words("N0" + blanks + ";") is None
    assert plain_words(blanks + "5") is None


def test_a_program_of_plain_lines_gives_the_blocks_of_its_general_reading():
    """The same moves with a ``#`` parameter on each line (read by the parameter reader, not the shortcut)."""
    plain = ("G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10.5 Y-2.25\nG2 X0 Y0 I-5.25 J1.125\n"
             "G1 X.5 Y5. Z-1.5 F1200\nM2\n")
    marked = "\n".join(f"#9={i} {ln}" if ln else ln for i, ln in enumerate(plain.split("\n"))) + "\n"
    a, b = parse_program(plain, source="p.nc"), parse_program(marked, source="p.nc")
    assert len(a.blocks) == len(b.blocks) == 5
    for x, y in zip(a.blocks, b.blocks):
        assert (x.kind, x.line, x.feed, x.start.tobytes(), x.target.tobytes()) == \
            (y.kind, y.line, y.feed, y.start.tobytes(), y.target.tobytes())
        assert x.segment.length == y.segment.length


@pytest.mark.slow
@pytest.mark.skipif(corpus_dir() is None, reason="gcode corpus absent (../shared/data/gcode-corpus)")
def test_corpus_lines_read_alike():
    """Every comment-free line of every ISO program of the corpus: the shortcut's words or none."""
    checked = 0
    folder = corpus_dir()
    for row in manifest(folder):
        path = folder / row["file"]
        if path.suffix.lower() == ".h":
            continue
        for raw in lines_of(program_text(str(path))):
            try:
                code = strip_comments(raw, WHERE)
            except GCodeError:
                continue
            fast = plain_words(code)
            if fast is None:
                continue
            assert fast == general_words(code), (row["file"], raw)
            checked += 1
    assert checked > 100_000


@pytest.mark.parametrize(("expr", "value"), [
    ("2 + 3 * 4 ** 2 / 8 - 1", 2 + 3 * 4 ** 2 / 8 - 1),
    ("2 ** 3 ** 2", (2 ** 3) ** 2),  # one level: left to right
    ("10 - 4 - 3", 3), ("12 / 2 / 3", 2), ("7 MOD 4 * 2", 6), ("2 * 7 MOD 4", 2),
    ("1 + 2 EQ 3 AND 4 GT 3", 1), ("1 OR 0 AND 0", 0), ("1 XOR 1 OR 1", 1), ("3 - 2 LT 2 - 1", 0),
    ("-2 ** 2", 4), ("SIN[30] * 2 + [1 + 1] ** 3", math.sin(math.radians(30)) * 2 + 8),
    ("ATAN[1]/[1] + 1", 46), ("2 ** -1 * 4", 2),
])
def test_expressions_follow_linuxcnc_precedence(expr, value):
    program = parse_program(f"G21 G90\n#1 = [{expr}]\nG1 X#1 F100\nM2\n", source="e.ngc")
    assert program.blocks[0].target[0] == pytest.approx(value, abs=1e-12)
