"""Heidenhain ``CALL PGM`` / ``SEL PGM`` / ``CALL SELECTED PGM``: hand-written programs in files of a
temporary directory, end points worked out by hand and checked against the reference."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from interpolators import load_program
from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (10.0, 20.0, 0.0)})


def write(folder: Path, name: str, body: str, unit: str = "MM") -> Path:
    stem = name.rsplit("/", 1)[-1].split(".")[0]
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"0 BEGIN PGM {stem} {unit}\n{body}\nEND PGM {stem} {unit}\n")
    return path


def checked(main: Path):
    """Load ``main`` and compare it with the reference (CALL PGM resolved in its directory)."""
    prog = load_program(main, context=CTX)

    def resolve(name: str) -> str:  # the TNC's file names are not case sensitive
        rel = name.replace("\\", "/").lower()
        files = {str(f.relative_to(main.parent)).lower(): f for f in main.parent.rglob("*") if f.is_file()}
        return (files.get(rel) or files[rel + ".h"]).read_text()

    match = match_blocks(heidenhain_reference(main.read_text(), CTX, resolve=resolve), blocks_table(prog)[1])
    assert match.mismatch is None, match.mismatch
    assert match.exact == len(prog.blocks)
    return prog


def test_call_pgm_shares_q_parameters_and_returns_after_end_pgm(tmp_path):
    write(tmp_path, "SUB1.h", "1 L IX+Q1\n2 Q2 = Q1 * 2")
    main = write(tmp_path, "main.h", "1 L X+0 Y+0 Z+0 R0 F100\n2 Q1 = 5\n3 CALL PGM SUB1\n4 L X+Q2\n5 CALL PGM SUB1.h")
    prog = checked(main)
    assert [b.target[0] - 10 for b in prog.blocks] == [0, 5, 10, 15]
    assert [b.line for b in prog.blocks] == [2, 2, 5, 2]  # each block reports its own file's line


def test_a_called_program_has_ql_parameters_of_its_own(tmp_path):
    # TNC 640 user's manual (34059x-02, 5/2013), 9.1: "Local parameters QL are only effective within the
    # respective program, and are not applied as part of program calls"; Q and QR are. SUB sees QL1 = 0 (X0 + 5)
    # and the QR2 = 3 the caller set; back in main, QL1 is main's 20 again (vcnc shared QL with the called
    # program before: X+25, then X+25)
    write(tmp_path, "SUB.h", "1 QL1 = QL1 + 5\n2 QR2 = QR2 + 1\n3 L X+QL1 R0 FMAX")
    main = write(tmp_path, "main.h", "1 QL1 = 20\n2 QR2 = 3\n3 L X+0 Y+0 Z+10 R0 FMAX\n4 CALL PGM SUB\n"
                                     "5 L X+QL1 Y+QR2 R0 FMAX")
    prog = checked(main)
    assert [tuple(b.target[:2]) for b in prog.blocks] == [(10, 20), (15, 20), (30, 24)]


def test_called_program_keeps_its_own_unit_and_paths_are_relative(tmp_path):
    write(tmp_path, "sub/inch.h", "1 L IY+1", unit="INCH")
    main = write(tmp_path, "main.h", "1 L X+0 Y+0 Z+0 R0 F100\n2 CALL PGM sub\\inch.h\n3 L IY+1")
    prog = checked(main)
    assert [b.target[1] - 20 for b in prog.blocks] == [0, pytest.approx(25.4), pytest.approx(26.4)]


def test_sel_pgm_and_call_selected_pgm_and_a_control_drive_path(tmp_path):
    write(tmp_path, "Part7.H", "1 L IZ-1")
    main = write(tmp_path, "main.h", "1 L X+0 Y+0 Z+0 R0 F100\n2 SEL PGM \"PART7.H\"\n3 CALL SELECTED PGM\n"
                                     "4 CALL PGM TNC:\\nc_prog\\part7.h")
    prog = load_program(main, context=CTX)
    assert [b.target[2] for b in prog.blocks] == [0, -1, -2]
    assert any("control drive path" in n for n in prog.notes)


def test_transformations_of_a_called_program_stay_in_effect(tmp_path):
    write(tmp_path, "rot.h", "1 CYCL DEF 10.0 ROTATION\n2 CYCL DEF 10.1 ROT+90")
    main = write(tmp_path, "main.h", "1 L X+0 Y+0 Z+0 R0 F100\n2 CALL PGM rot\n3 L X+5 Y+0")
    prog = checked(main)
    assert np.allclose(prog.blocks[-1].target, [10, 25, 0])


def test_cycle_12_calls_a_program_like_a_cycle(tmp_path):
    write(tmp_path, "hole.h", "1 L IZ-2 F50\n2 L IZ+2 FMAX")
    main = write(tmp_path, "main.h", "1 L X+0 Y+0 Z+0 R0 F100\n2 CYCL DEF 12.0 PGM CALL\n3 CYCL DEF 12.1 PGM hole\n"
                                     "4 L X+5 FMAX M99\n5 L X+9 FMAX\n6 CYCL CALL\n"
                                     "7 CYCL DEF 200 DRILLING Q200=2 Q201=-3 Q206=100 Q202=3 Q210=0 Q203=+0 Q204=5\n"
                                     "8 L X+20 FMAX M99")
    prog = checked(main)
    ends = [(b.target[0] - 10, b.target[2]) for b in prog.blocks]
    assert ends == [(0, 0), (5, 0), (5, -2), (5, 0), (9, 0), (9, -2), (9, 0), (20, 0), (20, 2), (20, -3), (20, 2),
                    (20, 5)]  # after CYCL DEF 200 the cycle is the drilling cycle again


@pytest.mark.parametrize("files, body, words", [
    ({}, "CALL PGM NOPE", "no program 'NOPE.h'"),
    ({"e.h": "1 L X+1 F100 M30"}, "CALL PGM e", "M2/M30 in a called program"),
    ({"a.h": "1 CALL PGM main"}, "CALL PGM a", "calls a program that is running"),
    ({"iso.i": "G0 X1"}, "CALL PGM iso.i", "ISO program (.I)"),
    ({}, "CALL SELECTED PGM", "CALL SELECTED PGM without SEL PGM"),
])
def test_errors_name_the_call(tmp_path, files, body, words):
    for name, text in files.items():
        write(tmp_path, name, text)
    main = write(tmp_path, "main.h", "1 L X+0 Y+0 Z+0 R0 F100\n2 " + body)
    with pytest.raises(GCodeError) as info:
        load_program(main)
    assert words in str(info.value)
    assert info.value.line is not None and info.value.expected


def test_call_pgm_needs_the_calling_file():
    with pytest.raises(GCodeError, match="not read from a file"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 CALL PGM SUB\n2 END PGM T MM\n")
