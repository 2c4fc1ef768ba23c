"""Text of files written by other tools (vcnc.core.text), and part programs read through it."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import load_program
from vcnc.cli import main
from vcnc.core.text import BinaryDataError, decode_text
from vcnc.errors import GCodeError

PROGRAM = "(Bohrung \u00d8 5 f\u00fcr Pr\u00fcfung)\nG21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10 Y5\nG2 X20 Y5 R5\nM30\n"


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "utf-16", "utf-16-le", "utf-16-be", "cp1252"])
def test_every_encoding_windows_tools_write_gives_the_same_text(encoding):
    assert decode_text(PROGRAM.encode(encoding)).lstrip("\ufeff") == PROGRAM


def test_bytes_that_are_not_utf8_are_windows_1252():
    assert decode_text(b"(\x80 \xd8 \xb0)") == "(\u20ac \u00d8 \u00b0)"
    assert decode_text(b"(\x81)") == "(\ufffd)"  # undefined in Windows-1252


@pytest.mark.parametrize("raw", [b"CDF\x01\x00\x00\x00\x0a\x00\x00\x00\x00", b"G1 X1\x00\x00\x00\x07\x00\xff",
                                 b"\xff\xfeG\x00\x00\xd8"])
def test_binary_data_is_refused(raw):
    with pytest.raises(BinaryDataError):
        decode_text(raw)


def test_a_utf16_program_runs_like_its_utf8_copy(tmp_path, capsys):
    outs = []
    for encoding in ("utf-8", "utf-16"):
        prog = tmp_path / f"{encoding}.nc"
        prog.write_bytes(PROGRAM.encode(encoding))
        out = tmp_path / f"{encoding}.csv"
        assert main(["interpolate", str(prog), "-o", str(out)]) == 0
        outs.append(np.loadtxt(out, delimiter=",", skiprows=1))
    np.testing.assert_array_equal(outs[0], outs[1])


def test_a_binary_file_is_no_program_exit_2_and_no_output(tmp_path, capsys):
    prog = tmp_path / "mesh.nc"  # a NetCDF file shares the .nc suffix
    prog.write_bytes(b"CDF\x01\x00\x00\x00\x00" + bytes(range(256)) * 4)
    out = tmp_path / "sp.csv"
    assert main(["interpolate", str(prog), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{prog}:1:5: binary file" in err and "expected a text part program" in err
    assert not out.exists()


def test_a_binary_subroutine_file_is_named(tmp_path):
    (tmp_path / "sub.ngc").write_bytes(b"\x00\x01\x02" * 10)
    main_prog = tmp_path / "main.ngc"
    main_prog.write_text("G21 G90\no<sub> call\nM2\n")
    with pytest.raises(GCodeError, match=r"sub\.ngc: cannot read the subprogram file: binary file"):
        load_program(main_prog)
