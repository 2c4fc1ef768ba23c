"""Heidenhain tool tables (TOOL.T) and tools called by name (``TOOL CALL "NAME"``).

The table layout follows the TNC7 user's manual "Tool table tool.t" (HEIDENHAIN 81762x-17): fixed column
widths set by the header line, T (number, an index after the period), NAME (up to 32 characters), L and R,
DL and DR (oversizes "added to the parameter L" / R), DOC. The tables below are written in the test.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators.context import MachineContext, read_tool_table
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import InputError

TABLE = (
    "BEGIN TOOL     .T     MM\n"
    "T    NAME             L           R           R2          DL      DR      DOC\n"
    "0    NULLTOOL         +0          +0          +0          +0      +0      zero tool\n"
    "3    MILL D10         +80.5       +5          +0          +0.2    -0.05   rougher\n"
    "3.1  MILL D10 SISTER  +79         +5          +0          +0      +0\n"
    "7    DRILL_D6         +120.25     +3                                      \n"
    "[END]\n"
)


def write(tmp_path, text: str, name: str = "tool.t") -> str:
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_a_tool_t_reads_its_columns_under_the_header_names(tmp_path):
    tools = read_tool_table(write(tmp_path, TABLE))
    assert sorted(tools) == [0, 3, 7]  # the indexed row 3.1 is left out (vcnc's table has no indices)
    t3 = tools[3]
    assert t3.name == "MILL D10"  # a name holding a space, read by its column
    assert t3.length == pytest.approx(80.5 + 0.2) and t3.radius == pytest.approx(5 - 0.05)  # L + DL, R + DR
    assert t3.comment == "rougher"
    assert tools[7].name == "DRILL_D6" and tools[7].length == 120.25 and tools[7].radius == 3.0  # empty DL/DR: 0


def test_an_inch_tool_t_is_read_in_mm(tmp_path):
    tools = read_tool_table(write(tmp_path, TABLE.replace(".T     MM", ".T     INCH")))
    assert tools[7].length == pytest.approx(120.25 * 25.4) and tools[7].radius == pytest.approx(3 * 25.4)


@pytest.mark.parametrize("text, match", [
    ("BEGIN TOOL .T MM\n", r"tool\.t:2: Heidenhain tool table without its header line"),
    ("BEGIN TOOL .T MM\nT    NAME   L\n1    A      +5\n", r"tool\.t:2: .* header without column R"),
    ("BEGIN TOOL .T MM\nT    NAME   L      R\n1    A      +5x    +1\n", r"tool\.t:3: column L holds '\+5x'"),
    ("BEGIN TOOL .T MM\nT    NAME   L      R\nAB   A      +5     +1\n", r"tool\.t:3: tool number 'AB'"),
])
def test_a_malformed_tool_t_names_the_line(tmp_path, text, match):
    with pytest.raises(InputError, match=match):
        read_tool_table(write(tmp_path, text))


def test_tool_call_by_name_takes_the_tables_length_and_radius(tmp_path):
    ctx = dataclasses.replace(MachineContext(), tools=read_tool_table(write(tmp_path, TABLE)))
    text = ('0 BEGIN PGM T MM\n1 TOOL CALL "MILL D10" Z S3000\n2 L X+0 Y+0 Z+10 R0 FMAX\n'
            '3 L X+20 Y+0 RL F500\n4 L X+20 Y+20\n5 L X+30 R0\n6 TOOL CALL "NOSUCH" Z DL+1\n7 L Z+50 FMAX\n'
            '8 END PGM T MM\n')
    prog = parse_heidenhain(text, source="t.h", context=ctx)
    match = match_blocks(heidenhain_reference(text, ctx), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    # the length L + DL = 80.7 lifts the machine point along Z: Z+10 in the program is machine Z 90.7
    assert prog.blocks[0].target[2] == pytest.approx(10 + 80.7)
    # radius R + DR = 4.95 to the left of the line (0,0)->(20,0)->(20,20): the corner point lies 4.95 inside
    assert np.allclose(prog.blocks[2].target[:2], [20 - 4.95, 20], atol=1e-9)
    # a name not in the table: length and radius are TOOL CALL's deltas only (DL+1), with a note
    assert prog.blocks[-1].target[2] == pytest.approx(50 + 1.0)
    assert any('"NOSUCH" called by name is not in the tool table' in n for n in prog.notes)


def test_interpolate_reads_a_tool_t_given_by_tool_table(tmp_path, capsys):
    from vcnc.cli import main

    prog = tmp_path / "p.h"
    prog.write_text('0 BEGIN PGM P MM\n1 TOOL CALL "DRILL_D6" Z S3000\n2 L X+0 Y+0 Z+5 R0 FMAX\n3 END PGM P MM\n')
    blocks = tmp_path / "b.csv"
    rc = main(["interpolate", str(prog), "-o", str(tmp_path / "o.csv"), "--blocks", str(blocks),
               "--tool-table", write(tmp_path, TABLE)])
    assert rc == 0, capsys.readouterr().err
    rows = blocks.read_text().splitlines()
    z = float(rows[-1].split(",")[rows[0].split(",").index("z")])
    assert z == pytest.approx(5 + 120.25)  # DRILL_D6's L
