"""Cases ported from LinuxCNC's own interpreter tests (github.com/LinuxCNC/linuxcnc, tests/interp/g81/g17/g98
and g17/g99: a test .ngc and its expected canonical calls). The programs are the test programs without comments;
the end points are the STRAIGHT_TRAVERSE/STRAIGHT_FEED X, Y, Z of the ``expected`` files [inch], written out."""

from __future__ import annotations

import io
import math
import os
import re
import shutil
import subprocess
import tarfile
from pathlib import Path

import numpy as np
import pytest

from benchmarks.linuxcnc_diff import canonical_moves
from interpolators import load_program, parse_program
from interpolators.context import Dialect, MachineContext, read_tool_table
from tests.interpolators.linuxcnc_ported_cases import PORTED_CASES
from vcnc.core.axes import EXTRA_NAMES
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


def test_g81_in_g18_drills_along_y():
    """LinuxCNC "Canned Cycles" in G18 (tests/interp/g81/g18): Z X place the hole, Y is the bottom and
    R a Y level; G98 returns to the Y the series started at."""
    prog = parse_program("G18 G98 G90 G20 F10\nG0 X0 Y2 Z0\nG81 X1 Z1 Y-1 R1\n", context=MachineContext())
    got = [(b.kind, *(round(v / INCH, 4) + 0.0 for v in b.target)) for b in prog.blocks]
    assert got == [("rapid", 0.0, 2.0, 0.0), ("rapid", 1.0, 2.0, 1.0), ("rapid", 1.0, 1.0, 1.0),
                   ("line", 1.0, -1.0, 1.0), ("rapid", 1.0, 2.0, 1.0)]


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


# --- LinuxCNC's tests/interp and tests/ccomp, run in place ------------------------------------------------------
#
# Each case of LinuxCNC's interpreter tests (and of its cutter compensation tests, tests/ccomp) is a program and the
# canonical calls rs274 prints for it. The cases are read from the tests of Debian's linuxcnc source package, which
# `make test` downloads from Debian's archive, checks against the archive's SHA-256 and unpacks under .cache
# (VCNC_LINUXCNC_TESTS, holding interp/ and ccomp/; never copied into this repository), or from a LinuxCNC git checkout
# (VCNC_LINUXCNC_REPO); the six cases LinuxCNC added after Debian's snapshot are written out in
# linuxcnc_ported_cases.py. The program runs through vcnc with the
# case's tool table and SUBROUTINE_PATH, and the end points of STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED, mapped to
# machine coordinates with the offsets the calls set (SET_G5X_OFFSET, SET_G92_OFFSET, SET_XY_ROTATION,
# USE_TOOL_LENGTH_OFFSET) in the units they name, are compared with the blocks' (zero-length moves dropped, as vcnc
# emits none). A case whose test.sh keeps only MESSAGE lines checks that vcnc accepts the program; one whose test.sh
# expects rs274 to fail checks that vcnc refuses it. The messages (MESSAGE calls of MSG and DEBUG comments, the lines
# PRINT comments print) are compared with Program.messages, text and order, as the case's test.sh passes them on.

_LINUXCNC_TESTS = Path(os.environ.get("VCNC_LINUXCNC_TESTS",
                                      Path(__file__).resolve().parents[2] / ".cache" / "linuxcnc-tests"))
_LINUXCNC_REPO = Path(os.environ.get("VCNC_LINUXCNC_REPO", "/work/.mirror/LinuxCNC+linuxcnc/repo"))

#: Cases whose motion vcnc reproduces (tests/interp/<case>).
INTERP_MOTION = ("cam-nisley", "exists", "flowsnake", "g10/g10-l2-while-active", "g10/g10-l20-while-active",
                 "g10/g10-with-g92", "g81/g17/g98", "g81/g18/g98", "g81/g18/g99", "g81/g19/g98", "g81/g19/g99",
                 "g81/g17/g99", "g84/g17/g98", "g84/g17/g99", "inverse-time-with-comp", "m98m99/01-basics",
                 "m98m99/05-M98-loops", "m98m99/12-M99-endless-main-program", "namedparam-bug424", "oword-bug315-p2",
                 "rotation/g28", "rotation/g53", "g10/g10-l11", "unit-conversion", "crazy-paths", "inside-corners",
                 "g33.1", "g10/g10-l1-l10")
#: Cases whose expected output has no motion: vcnc runs them (the cases with messages are in INTERP_MESSAGES).
INTERP_ACCEPTED = ("fractional-linenumbers", "g52/g52-g92-interaction", "g6164", "m19", "m98m99/13-named-program",
                   "g64-r-planner")
#: Cases that still differ, and why (not run: documentation for the next step).
INTERP_DIFFERENT = {
    "abort-hot-comment": "the (abort, ...) message prints #<_ini[a]value> as written (vcnc reads no INI file)",
    "g84/g18/g98 g84/g18/g99 g84/g19/g98 g84/g19/g99": "LinuxCNC's convert_cycle_g74_g84 passes the XZ/YZ "
        "coordinates in another order (its expected file taps hole X1 Z1 Y-1 at X-1 Y1 Z1); vcnc taps the hole",
    "iniparam": "#<_ini[..]> values: vcnc reads no INI file (an error naming it)",
    "m98m99/09-disable-fanuc-subs": "the INI switch that disables M98/M99 is not modelled (vcnc always runs them)",
    "oword-unwind": "rs274 -n 0 continues after an error; vcnc stops at it",
    "pymove python-self value-returned": "Python subroutines and remaps (out of scope, an error naming the call)",
    "g76 g71-* g72-*": "lathe threading and lathe cycles (out of scope, an error naming them)",
}
#: Cases of LinuxCNC's cutter compensation tests (tests/ccomp/<case>: the same rs274 run and expected calls) whose
#: motion vcnc reproduces: arc and line entries, Z changes under compensation, G90/G91/G92 mixed under G41.
CCOMP_MOTION = ("mill-line-arc-entry", "mill-zchanges", "mill-g90g91g92")
#: tests/ccomp cases that differ or are no rs274 run, and why (not run: documentation for the next step).
CCOMP_DIFFERENT = {
    "lathe-comp": "G18 compensation with lathe tools: the tool table's orientation Q1-Q9 (the tip's quadrant) moves "
        "the compensated path; vcnc compensates a round (mill) tool and ends 1.27 mm (0.05 in) away on Z",
    "early-exit": "runs linuxcnc with a GUI test script, not rs274",
}
#: Cases rs274 refuses, and vcnc with it.
INTERP_REFUSED = ("iniparam-failassign", "m98m99/03-error-M98-no-P-word", "m98m99/04-M98-but-no-sub",
                  "m98m99/06-error-mixed-sub-styles", "nested-sub-error",
                  "nested-sub-in-file-error")


def _case_dir(case: str, tmp_path: Path, suite: str = "interp") -> Path:
    """The files of LinuxCNC's ``tests/<suite>/<case>`` (``interp`` or ``ccomp``), copied or extracted under
    ``tmp_path``."""
    dest = tmp_path / "tests" / suite / case
    if suite == "interp" and case in PORTED_CASES:  # newer than Debian's source: written out
        for name, text in PORTED_CASES[case].items():
            (dest / name).parent.mkdir(parents=True, exist_ok=True)
            (dest / name).write_text(text)
        return dest
    if (_LINUXCNC_TESTS / suite).is_dir():
        shutil.copytree(_LINUXCNC_TESTS / suite / case, dest)
        return dest
    if not (_LINUXCNC_REPO / "HEAD").is_file() and not (_LINUXCNC_REPO / ".git").exists():
        pytest.skip(f"LinuxCNC's interpreter tests absent ({_LINUXCNC_TESTS}: `make test` downloads them from "
                    f"Debian's archive; or a checkout in VCNC_LINUXCNC_REPO)")
    archive = subprocess.run(["git", "-C", str(_LINUXCNC_REPO), "archive", "HEAD", f"tests/{suite}/{case}"],
                             capture_output=True, check=True).stdout
    with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
        tar.extractall(tmp_path, filter="data")
    return tmp_path / "tests" / suite / case


def _rs274_run(case_dir: Path) -> tuple[list[Path], MachineContext, str]:
    """The programs test.sh runs, the context its options give (-t tool table, -i SUBROUTINE_PATH), test.sh."""
    sh = (case_dir / "test.sh").read_text()
    args = " ".join(re.findall(r"rs274\s+([^|\n;]*)", sh)).split()
    # rs274 standalone runs an inch machine: its tool table is in inch (cam-nisley: D0.0625 cuts 0.79375 mm wide
    # of the G21 path)
    tools = read_tool_table(str(case_dir / args[args.index("-t") + 1]), units="inch") if "-t" in args else {}
    path: tuple[str, ...] = ()
    if "-i" in args:
        m = re.search(r"SUBROUTINE_PATH\s*=\s*(\S+)", (case_dir / args[args.index("-i") + 1]).read_text())
        path = tuple(m.group(1).split(":")) if m else ()
    programs = [case_dir / a for a in args if a.endswith(".ngc")] or sorted(case_dir.glob("*.ngc"))
    # and its stored offsets (#5211.., #5221.., #5401..) read in inch whatever G20/G21 says (unit-conversion)
    return programs, MachineContext(tools=tools, extra_axes=EXTRA_NAMES, dialect=Dialect(subroutine_path=path),
                                    linear_units="inch"), sh


def _canonical_moves(expected: str) -> list[tuple[str, np.ndarray]]:
    """(kind, end point [mm, machine]) of the STRAIGHT_TRAVERSE/STRAIGHT_FEED/ARC_FEED/RIGID_TAP calls of an
    expected file (:func:`benchmarks.linuxcnc_diff.canonical_moves`: the canon's offsets, rotation, tool length
    and plane followed as emccanon.cc does)."""
    return [(m.kind, m.xyz) for m in canonical_moves(expected)]


#: How far two end points may differ and be the same point: rs274 prints 4 decimals, 0.0001 inch = 0.00254 mm [mm].
_PRINTED = 3e-3


def _without_repeats(moves: list[tuple[str, np.ndarray]]) -> list[tuple[str, np.ndarray]]:
    """The moves without those that end where the one before ended (zero-length, up to the printed digits)."""
    out: list[tuple[str, np.ndarray]] = []
    for kind, p in moves:
        if not (out and kind != "arc" and np.allclose(out[-1][1], p, atol=_PRINTED)):
            out.append((kind, p))
    return out


@pytest.mark.parametrize(("suite", "case"),
                         [("interp", c) for c in INTERP_MOTION] + [("ccomp", c) for c in CCOMP_MOTION])
def test_linuxcnc_interp_case_motion(suite, case, tmp_path):
    case_dir = _case_dir(case, tmp_path, suite)
    programs, context, _ = _rs274_run(case_dir)
    want = _without_repeats(_canonical_moves((case_dir / "expected").read_text()))
    got = _without_repeats([("arc" if b.kind.startswith("arc") else b.kind, np.asarray(b.target, dtype=float))
                            for p in programs for b in load_program(p, context=context).blocks if b.kind != "dwell"])
    assert [k for k, _ in got] == [k for k, _ in want]
    assert np.allclose(np.array([p for _, p in got]), np.array([p for _, p in want]), atol=_PRINTED)


@pytest.mark.parametrize("case", INTERP_ACCEPTED)
def test_linuxcnc_interp_case_runs(case, tmp_path):
    case_dir = _case_dir(case, tmp_path)
    programs, context, sh = _rs274_run(case_dir)
    assert "awk '/" in sh or not _canonical_moves((case_dir / "expected").read_text())  # messages only
    for p in programs:
        load_program(p, context=context)


#: A canonical call line of rs274's output (``   12 N..... NAME(args)``, the counter dropped by test.sh's awk).
_CANONICAL = re.compile(r"^\s*(?:\d+\s+)?N[.\d]+\s+([A-Z_][A-Z0-9_.]*)\((.*)\)\s*$")


def _shown(sh: str, line: str) -> str:
    """An output line of rs274 as the case's test.sh passes it on: ``awk '{$1=""; print}'`` drops the
    first field and joins the others with single spaces; ``sed 's/A/B/g'`` replaces."""
    if "awk '{$1=\"\"; print}'" in sh:
        line = " " + " ".join(line.split()[1:])
    for old, new in re.findall(r"sed '?s/((?:[^/\\]|\\.)*)/((?:[^/\\]|\\.)*)/g", sh):
        line = re.sub(old, new.replace("\\", ""), line)
    return line


def _expected_messages(expected: str) -> list[tuple[str, str]]:
    """The messages of an expected file in order: ``("MESSAGE", text)`` / ``("LOG", text)`` for those canonical
    calls (from MSG, DEBUG and LOG comments), ``("PRINT", line)`` for a line that is no canonical call (PRINT)."""
    out = []
    for line in expected.splitlines():
        m = _CANONICAL.match(line)
        if m is None:
            out.append(("PRINT", line))
        elif m.group(1) in ("MESSAGE", "LOG"):
            out.append((m.group(1), m.group(2)[1:-1]))
    return out


def _vcnc_messages(messages, sh: str) -> list[tuple[str, str]]:
    """vcnc's messages as rs274 prints them (saicanon.cc ``MESSAGE("%s")``, ``LOG("%s")``; PRINT as its text)
    and the case's test.sh passes them on."""
    out = []
    for m in messages:
        if m.kind == "print":
            out.append(("PRINT", _shown(sh, m.text)))
        else:
            call = "LOG" if m.kind == "log" else "MESSAGE"
            shown = _CANONICAL.match(_shown(sh, f"1 N..... {call}(\"{m.text}\")"))
            out.append((call, shown.group(2)[1:-1]))
    return out


#: Cases whose messages (MSG/DEBUG as MESSAGE calls, PRINT lines) vcnc gives as rs274 does, text and order.
INTERP_MESSAGES = ("cam-nisley", "do-while-break", "g10/g10-l2-while-active", "g10/g10-l20-while-active",
                   "g10/g10-with-g92", "m98m99/02-variables", "m98m99/05-M98-loops", "m98m99/07-nested-subs",
                   "m98m99/08-sub-follows-main", "m98m99/10-M98-P001", "m98m99/12-M99-endless-main-program",
                   "m98m99/14-o-expression-call", "machine-coord-params", "magic_comments/param_format_printing",
                   "oword-bug315", "oword-bug315-p2", "return-value", "rotation/abs-pts", "sequence-number",
                   "sub-call-from-sub", "subs-follow-main", "g10/g10-l11", "g10/g10-l1-l10",
                   "g52/g52-g92-interaction", "unit-conversion")
#: Cases with messages that differ, and why (not run).
INTERP_MESSAGES_DIFFERENT = {
    "g52/g92-offset-persistence": "G92 offsets persisting in a parameter file (rs274 -v) are not modelled",
}


@pytest.mark.parametrize("case", INTERP_MESSAGES)
def test_linuxcnc_interp_case_messages(case, tmp_path):
    case_dir = _case_dir(case, tmp_path)
    programs, context, sh = _rs274_run(case_dir)
    want = _expected_messages((case_dir / "expected").read_text())
    got = [m for p in programs for m in _vcnc_messages(load_program(p, context=context).messages, sh)]
    assert want  # a case with messages
    assert got == want


@pytest.mark.parametrize("case", INTERP_REFUSED)
def test_linuxcnc_interp_case_refused(case, tmp_path):
    case_dir = _case_dir(case, tmp_path)
    programs, context, _ = _rs274_run(case_dir)
    for p in programs:
        with pytest.raises(GCodeError):
            load_program(p, context=context)


def test_a_printed_point_turned_by_g10_l2_r_keeps_its_rounding():
    # rs274 prints the point before the canon turns it by G10 L2 R (emccanon.cc rotate_and_offset_pos), each
    # coordinate to 4 decimals; turned 45 degrees a machine coordinate carries both roundings: (sqrt 2 - 1) x half
    # a digit more than unturned (fuzz seed 306464, a G41 arc end under R-45 in inch, 1.8 um off, matched)
    head = "    1 N..... USE_LENGTH_UNITS(CANON_UNITS_INCHES)\n"
    feed = "    3 N..... STRAIGHT_FEED(1.0000, 2.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
    (turned,) = canonical_moves(head + "    2 N..... SET_XY_ROTATION(-45.0000)\n" + feed)
    (plain,) = canonical_moves(head + feed)
    assert turned.slack == pytest.approx((math.sqrt(2.0) - 1.0) * 0.5e-4 * 25.4)
    assert plain.slack == 0.0
    r = math.sqrt(0.5) * 25.4
    assert turned.xyz.tolist() == pytest.approx([3.0 * r, r, 0.0])
