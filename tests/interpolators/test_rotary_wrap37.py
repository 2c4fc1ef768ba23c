"""Rotary axes that wrap at 360 deg (``[axes.a] wrap = true``, :mod:`interpolators.rotary_wrap`): the direction of
an absolute move as each control takes it, checked against the manuals' own examples, against LinuxCNC's ``rs274``
with ``WRAPPED_ROTARY = 1`` in its INI, and against the independent references (tests/interpolators/reference_iso.py,
reference_heidenhain.py). Before: every rotary axis read as a linear one (350 deg, then ``A10``: -340 deg)."""

from __future__ import annotations

import dataclasses
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.iso import parse_iso
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.commands.machines import PROGRAM_TABLE_DOC
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import GCodeError, MachineError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"], extra_axes=("a", "c"), wrapped_axes=("a", "c"))
FANUC = MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a",), wrapped_axes=("a",))
TNC = MachineContext(extra_axes=("b", "c"), wrapped_axes=("c",))

#: A LinuxCNC program on wrapped A and C; G10 L2 P1 A30 shifts A's program zero.
LINUXCNC_PROGRAM = """G21 G90
G0 A350
G0 A10
G0 A-350
G0 A-10
G1 A90 F100
G91 G1 A400
G90 G0 A-0
G0 A0
G0 C-90
G0 C270
G10 L2 P1 A30
G0 A10
G0 A-10
G0 A200
M2
"""
#: rs274 (LinuxCNC 2.9.0~pre1, linuxcnc-uspace) ``-i`` an INI with ``[AXIS_A]``/``[AXIS_C] WRAPPED_ROTARY = 1``:
#: the A and C of each STRAIGHT_TRAVERSE / STRAIGHT_FEED, program coordinates (A's machine = program + 30 after G10),
#: moves that move nothing dropped.
RS274_A_C = [(350, 0), (370, 0), (350, 0), (10, 0), (90, 0), (490, 0), (360, 0), (360, -270), (360, -90),
             (370, -90), (560, -90)]

#: Machine-coordinate words and reference returns under a 30 deg A offset on LinuxCNC, where its interpreter
#: unwraps |word - offset| (interp_find.cc find_ends G53 branch, find_relative; G28.1 stores the angle reduced).
LINUXCNC_MACHINE_PROGRAM = """G21 G90
G10 L2 P1 A30
G0 A340
G53 G0 A5
G53 G0 A-100
G28.1
G0 A10
G28
G0 A200
G91 G28 A0
G90 G0 A-10
G30
M2
"""
#: rs274 2.9.0~pre1 -i the same INI: A (program coordinates, machine = program + 30) of each move that moves.
RS274_MACHINE_A = [-20, 25, -230, 10, 130, 200, 490, 370, 390]


def _iso(text: str, context: MachineContext):
    prog = parse_iso(text, source="t.ngc", context=context)
    match = match_blocks(iso_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def _tnc(body: str, context: MachineContext = TNC):
    text = "0 BEGIN PGM W MM\n" + body + "\nEND PGM W MM\n"
    prog = parse_heidenhain(text, source="w.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def _moves(prog, column: int) -> list[float]:
    """The turn of each block that moves the axis of ``column`` [deg]."""
    turns = [float(b.extra_target[column] - b.extra_start[column]) for b in prog.blocks]
    return [round(t, 9) + 0.0 for t in turns if abs(t) > 1e-12]


def _a_c_program(prog, offsets: list[float]) -> list[tuple[float, float]]:
    """A and C of the blocks that move, in program coordinates (A minus its offset from that block on)."""
    out = []
    for b, off in zip(prog.blocks, offsets, strict=True):
        if np.any(b.extra_target != b.extra_start):
            out.append((round(float(b.extra_target[0]) - off, 9) + 0.0, round(float(b.extra_target[2]), 9) + 0.0))
    return out


def test_linuxcnc_wrapped_rotary_takes_the_sign_as_the_direction_as_rs274_does():
    """LinuxCNC INI docs, WRAPPED_ROTARY: "Positive Numbers will move the axis in a positive direction and negative
    numbers will move the axis in the negative direction"; G91 adds as ever; A-0 turns negative; C-90 is 90 deg
    reached turning negative (-270). Before: A10 after A350 went back to 10 (rs274: 370)."""
    prog = _iso(LINUXCNC_PROGRAM, LINUXCNC)
    offsets = [30.0 if b.line >= 13 else 0.0 for b in prog.blocks]
    assert _a_c_program(prog, offsets) == [(float(a), float(c)) for a, c in RS274_A_C]


def test_linuxcnc_g53_and_g28_on_a_wrapped_axis_with_an_offset_follow_rs274():
    """rs274 unwraps a G53 word or the G28/G30 position less the program offset (``G53 G0 A5`` under a 30 deg
    offset ends at machine 55 deg: rotary_wrap.linuxcnc_machine_word); vcnc's linuxcnc dialect does the same."""
    prog = parse_iso(LINUXCNC_MACHINE_PROGRAM, source="t.ngc", context=LINUXCNC)
    assert [a for a, _ in _a_c_program(prog, [30.0] * len(prog.blocks))] == [float(a) for a in RS274_MACHINE_A]


@pytest.mark.skipif(shutil.which("rs274") is None, reason="LinuxCNC's rs274 is not installed")
@pytest.mark.parametrize(("program", "expected"), [
    (LINUXCNC_PROGRAM, [(float(a), float(c)) for a, c in RS274_A_C]),
    (LINUXCNC_MACHINE_PROGRAM, [(float(a), 0.0) for a in RS274_MACHINE_A]),
])
def test_linuxcnc_against_rs274_with_a_wrapped_rotary_ini(tmp_path: Path, program, expected):
    """The programs through rs274 -i INI (WRAPPED_ROTARY = 1 on A and C) give the ends written out above."""
    ini = tmp_path / "w.ini"
    (tmp_path / "w.var").write_text("")
    ini.write_text(f"[RS274NGC]\nPARAMETER_FILE = {tmp_path / 'w.var'}\n[TRAJ]\nLINEAR_UNITS = mm\n"
                   "ANGULAR_UNITS = degree\n[AXIS_A]\nWRAPPED_ROTARY = 1\n[AXIS_C]\nWRAPPED_ROTARY = 1\n")
    ngc = tmp_path / "p.ngc"
    ngc.write_text(program)
    out = subprocess.run(["rs274", "-i", str(ini), "-g", str(ngc)], capture_output=True, text=True, timeout=60,
                         cwd=tmp_path).stdout
    ends = [tuple(float(v) for v in m.group(1).split(","))
            for m in re.finditer(r"STRAIGHT_(?:TRAVERSE|FEED)\(([^)]*)\)", out)]
    got, last = [], (0.0, 0.0)
    for e in ends:
        here = (e[3], e[5])
        if here != last:
            got.append(here)
        last = here
    assert got == expected


def test_linuxcnc_a_wrapped_word_of_360_or_more_is_an_error_naming_it():
    """rs274ngc interp_find.cc unwrap_rotary: "Invalid absolute position .. for wrapped rotary axis A"."""
    with pytest.raises(GCodeError, match=r"t\.ngc:2:.*invalid absolute position 370 for wrapped rotary axis A"):
        parse_iso("G21 G90\nG0 A370\nM2\n", source="t.ngc", context=LINUXCNC)
    prog = parse_iso("G21 G91\nG0 A370\nM2\n", source="t.ngc", context=LINUXCNC)  # G91: a turn of 370
    assert _moves(prog, 0) == [370.0]


@pytest.mark.parametrize(("block", "column"), [("G92 A400", 5), ("G10 L20 P1 A-360", 12), ("G52 A370", 5)])
def test_linuxcnc_an_offset_word_of_360_or_more_on_a_wrapped_axis_is_an_error(block, column):
    """rs274 refuses these too (interp_convert.cc convert_axis_offsets, convert_setup): "Invalid absolute position
    400.00 for wrapped rotary axis A"; a G92 within a turn shifts as ever (G92 A350 at 0, then A10: rs274 370, our
    machine 20)."""
    with pytest.raises(GCodeError, match=rf"t\.ngc:2:{column}: .*invalid absolute position -?\d+ for wrapped"):
        parse_iso(f"G21\n{block}\nG0 A10\nM2\n", source="t.ngc", context=LINUXCNC)
    assert _moves(parse_iso("G21\nG92 A350\nG0 A10\nM2\n", context=LINUXCNC), 0) == [20.0]
    assert _moves(parse_iso("G21\nG92 A400\nG0 A10\nM30\n", context=FANUC), 0) == [-30.0]  # Fanuc: no such check


def test_fanuc_roll_over_takes_the_shorter_way_as_the_manual_example():
    """Fanuc B-63534EN/02 20.2.1 "Rotary axis roll-over" (ROA = 1, RAB = 0, No. 1260 = 360): from A0, ``G90 A-150.``
    -150, ``G90 A540.`` -30, ``G90 A-620.`` -80, ``G91 A380.`` +380, ``G91 A-840.`` -840."""
    text = "G21 G90 G0 A0\nA-150.\nA540.\nA-620.\nG91 A380.\nG91 A-840.\nM30\n"
    assert _moves(_iso(text, FANUC), 0) == [-150.0, -30.0, -80.0, 380.0, -840.0]
    # exactly half a turn: the positive way (Fanuc 15i B-63783EN-1, 1.6.3: "the normal direction")
    assert _moves(_iso("G21 G90 G0 A90.\nA270.\nM30\n", FANUC), 0) == [90.0, 180.0]
    # Haas and Fadal take Fanuc's default
    for name in ("haas", "fadal"):
        assert _moves(_iso("G21 G90 G0 A350.\nA10.\nM30\n", dataclasses.replace(FANUC, dialect=DIALECTS[name])),
                      0) == [-10.0, 20.0]


def test_fanuc_rab_1_takes_the_sign_and_g53_the_machine_angle():
    """Fanuc 20.2.2 "Rotary axis control" (RAB = 1): the sign is the direction, the magnitude the end angle;
    ``wrap_direction = "sign"``. A G53 word is a machine angle (no work offset), reached by the same rule."""
    ctx = dataclasses.replace(FANUC, wrap_direction="sign", work_offsets={})
    assert _moves(_iso("G21 G90 G0 A350.\nA10.\nA-350.\nG53 A-10.\nM30\n", ctx), 0) == [350.0, 20.0, -20.0,
                                                                                           -340.0]


def test_without_wrap_nothing_changes():
    """The default machine (no ``wrap``): 350 deg then A10 turns back 340 deg, as before."""
    ctx = MachineContext(dialect=DIALECTS["linuxcnc"], extra_axes=("a",))
    assert _moves(_iso("G21 G90 G0 A350\nA10\nA-10\nM2\n", ctx), 0) == [350.0, -340.0, -20.0]


def test_g28_returns_a_wrapped_axis_less_than_a_turn():
    """G28 A0 on a wrapped axis at 350 deg: to the reference angle 0 by the rule (LinuxCNC: the positive way, to
    360, never back through 350 deg; Fanuc roll-over: the shorter way, from -170 to 0)."""
    assert _moves(_iso("G21 G90 G0 A350\nG91 G28 A0\nM2\n", LINUXCNC), 0) == [350.0, 10.0]
    assert _moves(_iso("G21 G90 G0 A190.\nG91 G28 A0\nM30\n", FANUC), 0) == [-170.0, 170.0]


def test_tnc_m126_takes_the_shorter_way_and_m127_the_difference():
    """TNC 640 / 620 user's manuals, "Shorter-path traverse of rotary axes: M126": without it, actual 350 nominal 10
    traverses -340, 10 to 340 +330; with it +20 and -30; M127 ends it; an incremental word turns as written."""
    body = ("1 L C+350 FMAX\n2 L C+10 FMAX\n3 L C+340 FMAX\n4 L C+350 FMAX M126\n5 L C+10 FMAX\n6 L C+340 FMAX\n"
            "7 L IC+400 FMAX\n8 L C+10 FMAX M127\n9 L B+30 FMAX")
    assert _moves(_tnc(body), 2) == [350.0, -340.0, 330.0, 10.0, 20.0, -30.0, 400.0, -10.0]
    # B does not wrap: a linear-like rotary axis still
    assert _moves(_tnc("1 L B+350 FMAX M126\n2 L B+10 FMAX"), 1) == [350.0, -340.0]


def test_tnc_m126_in_a_plain_block_and_a_machine_that_always_takes_the_shorter_way():
    """M126 on a plain ``L X.. F..`` block (the fast path's kind) switches it too; ``wrap_direction = "shortest"``
    is the TNC's machine parameter shortestDistance (No. 300401): the shorter way without M126."""
    assert _moves(_tnc("1 L C+350 FMAX\n2 L X+5 F100 M126\n3 L C+10 FMAX"), 2) == [350.0, 20.0]
    always = dataclasses.replace(TNC, wrap_direction="shortest")
    assert _moves(_tnc("1 L C+350 FMAX\n2 L C+10 FMAX", always), 2) == [-10.0, 20.0]


def test_the_blocks_carry_the_unwrapped_angle_and_the_time_follows_the_short_turn():
    """``--blocks`` lists the end as the motor has turned (370, not 10): the simulation's turn is 20 deg."""
    prog = _iso("G21 G90 G0 A350\nG1 A10 F600\nM2\n", LINUXCNC)
    header, rows = blocks_table(prog)
    assert float(rows[-1][header.index("a")]) == 370.0
    assert prog.blocks[-1].extra_start[0] == 350.0


#: A built-in machine with an A axis: a copy of its X axis, ``wrap = WRAP`` in its table.
_BASE = builtin_machine_text("fadal-pid")
_X = _BASE[_BASE.index("[axes.x]"):_BASE.index("[axes.y]")]
MACHINE = (_BASE + "\n" + _X.replace("[axes.x", "[axes.a").replace("[axes.a]\n", "[axes.a]\nwrap = WRAP\n", 1)
           + '\n[program]\ndialect = "fanuc"\n')


def _machine(tmp_path: Path, text: str):
    f = tmp_path / "w.toml"
    f.write_text(text)
    return load_machine(f)


def test_the_machine_file_sets_wrap_and_the_direction(tmp_path: Path):
    m = _machine(tmp_path, MACHINE.replace("WRAP", "true") + 'wrap_direction = "sign"\n')
    assert m.context.wrapped_axes == ("a",) and m.context.wrap_direction == "sign"
    assert _machine(tmp_path, MACHINE.replace("WRAP", "false")).context.wrapped_axes == ()
    assert "wrap_direction" in PROGRAM_TABLE_DOC


@pytest.mark.parametrize(("change", "message"), [
    (lambda t: t.replace("WRAP", '"yes"'), r"w\.toml:\d+.*'axes\.a\.wrap' must be true or false"),
    (lambda t: t.replace("WRAP", "false").replace("[axes.x]\n", "[axes.x]\nwrap = true\n", 1),
     r"w\.toml:\d+.*'axes\.x\.wrap' = true: only a rotary axis"),
    (lambda t: t.replace("WRAP", "true") + 'wrap_direction = "nearest"\n',
     r"w\.toml:\d+.*'program\.wrap_direction' must be 'sign'"),
])
def test_a_bad_wrap_setting_names_the_key_and_the_file(tmp_path: Path, change, message):
    with pytest.raises(MachineError, match=message):
        _machine(tmp_path, change(MACHINE))


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas", "grbl", "fadal"])
def test_the_iso_shortcut_declines_wrapped_words_and_reads_alike(dialect):
    """interpolators.iso_fast leaves a word of a wrapping axis to the general path: the blocks of a 4-axis program
    on a wrapped A are the same, bit for bit, with and without the shortcut, and differ from a machine without wrap
    (so that the identity says something)."""
    from tests.interpolators.test_reader_fast import reading

    text = ("G21 G90 G94\nG0 X0. Y0. Z5. A0.\nG1 Z-1. F300.\nG1 X10. A350. F600.\nG1 X20. A10.\nG1 A-20.\n"
            "G91 G1 A400. X1.\nG90 G1 X5. A90.\nG1 X6. Y1.\nM2\n")
    wrapped = dataclasses.replace(LINUXCNC, extra_axes=("a",), wrapped_axes=("a",)).with_dialect(dialect)
    fast = reading(text, wrapped, shortcuts=True)
    assert fast == reading(text, wrapped, shortcuts=False)
    assert fast != reading(text, dataclasses.replace(wrapped, wrapped_axes=()), shortcuts=True)


def test_the_tnc_shortcut_leaves_m126_to_the_general_path_and_reads_alike():
    """interpolators.heidenhain_fast runs ``L X+5 F100 M126`` on a machine without wrapping axes (M126 noted as
    before), and leaves it to the general path on one with them (the switch then holds): the same blocks and notes
    both ways."""
    from tests.interpolators.block_digest import program_digest

    text = ("0 BEGIN PGM W MM\n1 L C+350 FMAX\n2 L X+5 F100 M126\n3 L C+10 FMAX\n4 L X+6 M127\n5 L C+350 FMAX\n"
            "END PGM W MM\n")
    for ctx in (TNC, dataclasses.replace(TNC, wrapped_axes=())):
        fast = program_digest(parse_heidenhain(text, source="w.h", context=ctx))
        assert fast == program_digest(parse_heidenhain(text, source="w.h", context=ctx, shortcuts=False))
    assert _moves(parse_heidenhain(text, context=TNC), 2) == [350.0, 20.0, 340.0]  # M127: 10 shown, +340
    notes = parse_heidenhain(text, context=dataclasses.replace(TNC, wrapped_axes=())).notes
    assert any("M126 ignored" in n for n in notes)


def test_vcnc_interpolate_with_a_wrapping_machine_turns_the_short_way_and_takes_less_time(tmp_path: Path, capsys):
    """``vcnc interpolate --machine`` with ``[axes.a] wrap = true`` (linuxcnc): ``G1 X10 A10`` after A350 turns +20
    deg (--blocks: 370) and the run is shorter than on the same machine without wrap (-340 deg: 10)."""
    from vcnc.cli import main

    prog = tmp_path / "p.ngc"
    prog.write_text("G21 G90 G94\nG0 X0 A350\nG1 X10 A10 F600\nM2\n")
    seconds = {}
    for wrap in ("true", "false"):
        machine = tmp_path / f"m_{wrap}.toml"
        machine.write_text(MACHINE.replace("WRAP", wrap).replace('dialect = "fanuc"', 'dialect = "linuxcnc"'))
        blocks = tmp_path / f"b_{wrap}.csv"
        assert main(["interpolate", str(prog), "--machine", str(machine), "--blocks", str(blocks),
                     "-o", str(tmp_path / f"o_{wrap}.csv")]) == 0
        assert blocks.read_text().splitlines()[-1].split(",")[6] == ("370" if wrap == "true" else "10")
        seconds[wrap] = float(re.search(r"interpolated ([\d.]+) s", capsys.readouterr().out).group(1))
    assert seconds["true"] < seconds["false"]
