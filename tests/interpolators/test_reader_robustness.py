"""The part-program readers on inputs nobody wrote tests for: mutated real and hand-written programs.

Seeds are the small programs of the shared corpus (``../shared/data/gcode-corpus``, ISO and
Heidenhain) and the hand-written programs below (subprograms, loops, labels, parameters). Each
example applies a few mutations (lines deleted, duplicated, swapped, the file cut mid-line, a
number replaced by ``nan``/``inf``/``1e308``/``-0``/nothing, stray words and characters, CR/LF
mixes, a BOM, tabs, long lines, unbalanced brackets and comments, ``%`` and ``N`` numbers at odd
places, huge repeat counts, recursion) and requires that :func:`interpolators.load_program` and
:func:`interpolators.interpolate` either succeed with finite setpoints or raise
:class:`vcnc.errors.InputError` naming the file (and the line, for the reader). A program that
takes longer than :data:`EXAMPLE_SECONDS` fails the test: endless loops must stop at the readers'
own limits (``iso_flow.MAX_EXECUTED_LINES``, ``heidenhain_labels.MAX_EXECUTED``).
"""

from __future__ import annotations

import math
import re
import signal
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from benchmarks.gcode_corpus import corpus_dir, manifest
from interpolators import interpolate, load_program, parse_program
from interpolators.context import INTERPOLATION_CONTEXT
from interpolators.iso_flow import run
from vcnc.cli import main
from vcnc.errors import GCodeError, InputError

CORPUS = corpus_dir()
#: Wall-clock bound of one example [s] (reading plus interpolation of a small program). It catches hangs, not
#: slow refusals: an endless loop of calls and moves runs to iso_flow.MAX_EXECUTED_LINES, about 8 s on the
#: idle 2-core machine and over 20 s while two test suites ran on it at once (2026-11-23).
EXAMPLE_SECONDS = 60.0
#: Sample budget of one interpolation: long enough for the seeds, short enough to stay fast.
MAX_SAMPLES = 300_000
#: Corpus programs up to this size [bytes] are seeds.
SEED_BYTES = 2500

HAND_SEEDS = {
    "osub.ngc": "G21 G90 G17\no100 sub\n  G1 X[#1] Y[#2] F600\no100 endsub\n#1 = 2\no101 while [#1 LT 6]\n"
                "  o100 call [#1] [#1*2]\n  #1 = [#1 + 1]\no101 endwhile\no102 repeat [3]\n  G91 G1 X1\n"
                "o102 endrepeat\nG90 G2 X10 Y0 I5 J0\nM2\n",
    "fanuc.nc": "%\nO1000 (MAIN)\nG21 G90 G54\nT1 M6\nG0 X0 Y0 Z5\nM98 P2000 L2\nG81 X5 Y5 Z-2 R1 F100\nG80\n"
                "M30\nO2000\nG91 G1 X2 F300\nG90\nM99\n%\n",
    "params.ngc": "#<side> = 5\n#3 = [SIN[30] * 4]\nG21 G0 X0 Y0\nG64 P0.01\nG1 X#<side> Y#3 F1200\n"
                  "G1 X[#<side> * 2] Y[ABS[-#3]]\nG3 X0 Y0 R20\nM30\n",
    "tnc.h": "0 BEGIN PGM FUZZ MM\n1 BLK FORM 0.1 Z X+0 Y+0 Z-20\n2 BLK FORM 0.2 X+100 Y+100 Z+0\n"
             "3 TOOL CALL 1 Z S3000\n4 Q1 = 5\n5 L X+0 Y+0 Z+5 R0 FMAX\n6 LBL 1\n7 L IX+Q1 F500\n8 LBL 0\n"
             "9 CALL LBL 1 REP 3\n10 CC X+20 Y+0\n11 C X+25 Y+0 DR+\n12 CALL LBL 2\n13 M30\n14 LBL 2\n"
             "15 L IY+2\n16 LBL 0\n17 END PGM FUZZ MM\n",
}

#: Stray words and characters inserted at random places.
TOKENS = ["G", "X", "#", "[", "]", "(", ")", "O", "Q", ";", "%", "N", "*", "=", "G1", "G2 X1 Y1 R0", "G3 I0 J0",
          "X1e5", "F0", "F-5", "G4 P-1", "M98 P1 L99999", "L99999", "REP 99999", "o1 call", "o1 sub", "o1 endsub",
          "o7 while [1]", "o7 endwhile", "#1=[#1+1]", "CALL LBL 1 REP 65535", "LBL 1", "LBL 0", "CALL LBL 1",
          "CYCL DEF 200", "Q1 = 1/0", "FN 4: Q1 = 1 DIV 0", "(nested (comment))", "((", "))", "\u00e9\u00df\u2603",
          "\ufeff", "\t", "\x00", "N99999999999999999999", "G1 X[1/0]", "G1 X[SQRT[-1]]", "#<x>", "#<>",
          "G10 L2 P99 X1", "T99999999", "S1e9", "G64 P-1", "G5.2", "G41 D1", "G43 H-1", "*   - structure",
          "G83 X1 Y1 Z-1 R1 Q0.0000001", "G81 R1 Z-1 L999999999", "Q202=0.0000001", "[" * 2000, "-" * 2000,
          "(" * 2000, "SIN " * 2000, "M98 P1000 L99999", "G65 P1000"]
#: What a number can become.
NUMBERS = ["nan", "inf", "-inf", "1e308", "-0", "", "1e9", "99999999999", ".", "-", "+-1", "0x10", "1_0", "1..2"]


def _seeds() -> dict[str, str]:
    seeds = dict(HAND_SEEDS)
    if CORPUS is not None:
        for row in manifest(CORPUS):
            path = CORPUS / row["file"]
            if path.is_file() and path.stat().st_size <= SEED_BYTES:
                seeds[row["file"]] = path.read_bytes().decode("utf-8", errors="replace")
    return seeds


SEEDS = _seeds()
SEED_NAMES = sorted(SEEDS)


def _mutate(text: str, op: str, a: int, b: int, token: str) -> str:
    """Apply one mutation ``op`` at positions chosen by ``a`` and ``b`` (any non-negative ints)."""
    lines = text.split("\n")
    i, j = a % len(lines), b % len(lines)
    if op == "delete":
        del lines[i]
    elif op == "duplicate":
        lines.insert(i, lines[i])
    elif op == "swap":
        lines[i], lines[j] = lines[j], lines[i]
    elif op == "truncate":
        return text[: a % (len(text) + 1)]
    elif op == "number":
        nums = list(re.finditer(r"[+-]?(?:\d+\.?\d*|\.\d+)", text))
        if nums:
            m = nums[a % len(nums)]
            return text[: m.start()] + NUMBERS[b % len(NUMBERS)] + text[m.end():]
    elif op == "insert":
        line = lines[i]
        k = b % (len(line) + 1)
        lines[i] = line[:k] + token + line[k:]
    elif op == "newline":
        lines.insert(i, token)
    elif op == "crlf":
        lines[i] = lines[i] + ("\r" if b % 2 else "\r\r")
    elif op == "bom":
        return "\ufeff" + text
    elif op == "long":
        lines[i] = lines[i] + " " + "X1 " * (2000 + b % 20000)
    elif op == "renumber":
        lines[i] = f"N{b % 100000} " + lines[i]
    elif op == "percent":
        lines.insert(i, "%")
    return "\n".join(lines)


OPS = ["delete", "duplicate", "swap", "truncate", "number", "insert", "newline", "crlf", "bom", "long", "renumber",
       "percent"]
MUTATION = st.tuples(st.sampled_from(OPS), st.integers(0, 10**6), st.integers(0, 10**6), st.sampled_from(TOKENS))


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout


def _check(folder: Path, name: str, text: str) -> None:
    """Load and interpolate ``text`` written as ``name`` in ``folder`` (empty: a Fanuc ``M98 P`` may read a
    sibling file): success with finite setpoints, or an InputError naming that file or a sibling."""
    path = folder / name
    path.write_bytes(text.encode("utf-8", errors="surrogatepass"))
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, EXAMPLE_SECONDS)
    stage = "load_program"
    try:
        program = load_program(path, context=INTERPOLATION_CONTEXT)
        stage = "interpolate"
        sp = interpolate(program, max_samples=MAX_SAMPLES)
    except _Timeout:
        pytest.fail(f"{stage} took more than {EXAMPLE_SECONDS} s on:\n{text[:2000]!r}")
    except InputError as exc:
        message = str(exc)
        assert exc.file is not None and Path(exc.file).parent == folder, f"{stage}: names no file: {message[:500]}"
        if stage == "load_program":
            assert exc.line is not None, f"error does not name a line: {message[:500]}"
        assert "\n" not in message.strip() and len(message) < 1000, f"not one short line: {message[:500]!r}"
        return
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert np.all(np.isfinite(sp.position)), "non-finite setpoints"
    # rapids carry feed = inf; nothing may be nan, and every end point is finite
    assert not any(math.isnan(b.feed) for b in program.blocks), "nan feed"
    assert all(np.all(np.isfinite(b.target)) for b in program.blocks), "non-finite end point"


def _run(seed: int, mutations: list) -> None:
    name = SEED_NAMES[seed % len(SEED_NAMES)]
    text = SEEDS[name]
    for op, a, b, token in mutations:
        text = _mutate(text, op, a, b, token)
    with tempfile.TemporaryDirectory() as folder:
        _check(Path(folder), name, text)


COMMON = {"derandomize": True, "deadline": None, "database": None, "suppress_health_check": [HealthCheck.too_slow]}


@settings(max_examples=200, **COMMON)
@given(seed=st.integers(0, 10**6), mutations=st.lists(MUTATION, min_size=1, max_size=4))
def test_mutated_programs_fail_cleanly(seed, mutations):
    _run(seed, mutations)


@pytest.mark.slow
@settings(max_examples=2000, **COMMON)
@given(seed=st.integers(0, 10**6), mutations=st.lists(MUTATION, min_size=1, max_size=8))
def test_mutated_programs_fail_cleanly_many(seed, mutations):
    _run(seed, mutations)


def test_corpus_seeds_present():
    if CORPUS is None:
        pytest.skip("gcode corpus absent (../shared/data/gcode-corpus): fuzzing the hand-written seeds only")
    assert len(SEEDS) > len(HAND_SEEDS)


# Regressions found by the tests above.


def test_endless_loop_stops_at_the_executed_line_limit():
    """An endless ``while`` ran 5,000,000 lines (3 min, 2.3 GB with a G1 inside) before its error;
    the limit now counts the lines executed beyond the program's own length."""
    loop = "G21\n#1=1\no101 while [#1 GE 0]\nG1 X1 F100\no101 endwhile\nM2\n"
    with pytest.raises(GCodeError, match=r"loop\.ngc:\d+:1: more than 5 lines executed beyond .*endless loop"):
        list(run(loop, source="loop.ngc", max_lines=5))
    straight = "G21\n" + "".join(f"G1 X{i} F100\n" for i in range(20)) + "M2\n"
    assert len(list(run(straight, source="straight.ngc", max_lines=5))) == 22


def test_a_huge_line_is_quoted_short():
    """A 60 kB line made a 60 kB error message; the quoted text and the message are cut, one line."""
    long_line = "G1 " + "X1 " * 20_000
    with pytest.raises(GCodeError) as info:
        parse_program(f"G21\n%{long_line}\n", source="long.nc")
    message = str(info.value)
    assert message.startswith("long.nc:2:") and re.search(r"\.\.\.', 600\d\d characters\)", message)
    assert len(message) < 600 and "\n" not in message


@pytest.mark.parametrize("block, word", [("G83 X1 Y1 Z-1 R1 Q0.0000001", "Q0.0000001"),
                                          ("G81 X1 Y1 Z-1 R1 L999999999", "L999999999")])
def test_cycle_with_millions_of_moves_is_refused(block, word):
    """``Q0.0000001`` or ``L999999999`` ran for hours (10^7 .. 10^9 moves); now an error naming the word."""
    with pytest.raises(GCodeError, match=rf"c\.nc:2:\d+: G8[13] .*cycle: .* exceed 1000000 cycle moves.*{word}"):
        parse_program(f"G21\n{block} F100\nM2\n", source="c.nc")


def test_tnc_cycle_with_a_tiny_plunging_depth_is_refused():
    """Cycle 200 with ``Q202=0.0000001`` ran for hours; now an error naming the cycle."""
    text = ("0 BEGIN PGM C MM\n1 CYCL DEF 200 DRILLING Q200=2 Q201=-20 Q206=150 Q202=0.0000001 Q210=0 Q203=+0"
            " Q204=50 Q211=0\n2 L X+1 Y+1 FMAX M99\n3 END PGM C MM\n")
    with pytest.raises(GCodeError, match=r"c\.h:2:\d+: cycle 200: .* more than 100000 infeeds"):
        parse_program(text, source="c.h")


@pytest.mark.parametrize("text", ["G21\n#1=[" + "[" * 3000 + "1" + "]" * 3001 + "\nM2\n",
                                  "G21\nG1 X[" + "-" * 3000 + "1] F100\nM2\n",
                                  "0 BEGIN PGM N MM\n1 Q1 = " + "SIN " * 3000 + "1\n2 END PGM N MM\n",
                                  "0 BEGIN PGM N MM\n1 Q1 = " + "(" * 3000 + "1" + ")" * 3000 + "\n2 END PGM N MM\n"])
def test_expression_nested_thousands_deep_is_an_error(text):
    """3000 nested brackets, signs or functions raised Python's RecursionError; now a GCodeError at the line."""
    with pytest.raises(GCodeError, match=r"n\.nc:2(:\d+)?: .*nested deeper than this reader follows"):
        parse_program(text, source="n.nc")


def test_cli_on_a_broken_program_exits_2_with_one_line_and_no_output(tmp_path, capsys):
    """``vcnc interpolate`` on a cycle of 10^7 pecks was killed for memory (exit 137); now exit 2, one line."""
    prog = tmp_path / "pecks.nc"
    prog.write_text("G21\nG1 X1 F100\nG83 X1 Y1 Z-1 R1 Q0.0000001 F100\nM2\n")
    out, blocks = tmp_path / "sp.csv", tmp_path / "blocks.csv"
    assert main(["interpolate", str(prog), "-o", str(out), "--blocks", str(blocks)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}:3:") and err.count("\n") == 1 and "Q0.0000001" in err
    assert not out.exists() and not blocks.exists()


def test_a_huge_name_in_the_expected_part_is_cut():
    """An 8 kB O-word name came back whole in the 'expected' part of the message."""
    name = "sin" * 3000
    with pytest.raises(GCodeError) as info:
        parse_program(f"o<{name}> sub\nG1 X1 F100\n", source="o.ngc")
    assert str(info.value).startswith("o.ngc:1:") and len(str(info.value)) < 1000
