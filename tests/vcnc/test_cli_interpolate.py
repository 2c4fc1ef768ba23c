"""``vcnc interpolate`` and ``vcnc toolpath``: outputs, exit statuses, no partial files."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.cli import main


def test_toolpath_then_interpolate(tmp_path, capsys):
    prog = tmp_path / "circle.nc"
    assert main(["toolpath", "circle", "--radius", "5", "--feed", "6000", "--center", "1,2", "-o", str(prog)]) == 0
    out = tmp_path / "sp.csv"
    png = tmp_path / "sp.png"
    assert main(["interpolate", str(prog), "-o", str(out), "--profile", "scurve", "--ts", "0.002",
                 "--plot", str(png)]) == 0
    header = out.read_text().splitlines()[0].split(",")
    assert header == ["t", "x_ref", "x_vel", "x_acc", "y_ref", "y_vel", "y_acc", "block"]
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.allclose(np.diff(data[:, 0]), 0.002)
    assert png.stat().st_size > 1000
    # the run in one line on stdout: the CSV's length, its sample time and axes
    n = len(data)
    assert capsys.readouterr().out.splitlines()[-1] == (
        f"{prog}: interpolated {(n - 1) * 0.002:.6g} s ({n} samples at Ts = 0.002 s, axes x, y); setpoints {out}")


def test_identification_programs(tmp_path, capsys):
    for args in (["--kind", "random", "--n", "20", "--seed", "3"], ["--kind", "slow", "--n", "10"],
                 ["--kind", "fast", "--n", "10"]):
        f = tmp_path / "id.nc"
        assert main(["toolpath", "identification", *args, "-o", str(f)]) == 0
        assert main(["interpolate", str(f), "-o", str(tmp_path / "id.csv")]) == 0
    assert main(["toolpath", "diamond", "--side", "10"]) == 0
    assert "G01" in capsys.readouterr().out


def test_bad_program_exit_2_and_no_output(tmp_path, capsys):
    prog = tmp_path / "bad.nc"
    prog.write_text("G01 X10 F100\nG01 X5 Q3\n")
    out = tmp_path / "sp.csv"
    assert main(["interpolate", str(prog), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and f"{prog}:2:8" in err
    assert not out.exists() and list(tmp_path.iterdir()) == [prog]


def test_missing_program_exit_2(tmp_path, capsys):
    assert main(["interpolate", str(tmp_path / "none.nc"), "-o", str(tmp_path / "x.csv")]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_bad_toolpath_option_exit_2(tmp_path, capsys):
    assert main(["toolpath", "circle", "--radius", "-1", "-o", str(tmp_path / "c.nc")]) == 2
    assert not (tmp_path / "c.nc").exists()


def test_subroutine_and_user_m_paths_on_the_command_line(tmp_path, capsys, monkeypatch):
    """--subroutine-path / --user-m-path (LinuxCNC INI [RS274NGC] SUBROUTINE_PATH, USER_M_PATH), relative to the
    working folder, searched before the machine's; they survive --dialect."""
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "square.ngc").write_text("o<square> sub\nG1 X#1 F600\nG1 Y#1\no<square> endsub\nM2\n")
    (tmp_path / "mfiles").mkdir()
    m101 = tmp_path / "mfiles" / "M101"
    m101.write_text("#!/bin/sh\nexit 0\n")
    m101.chmod(0o755)
    part = tmp_path / "part" / "part.ngc"
    part.parent.mkdir()
    part.write_text("G21 G90\nG0 X0 Y0\nM101\no<square> call [7]\nM2\n")
    blocks = tmp_path / "b.csv"
    out = tmp_path / "sp.csv"
    assert main(["interpolate", str(part), "-o", str(out)]) == 2
    assert "M101" in capsys.readouterr().err and not out.exists()
    monkeypatch.chdir(tmp_path)
    assert main(["interpolate", str(part), "-o", str(out), "--blocks", str(blocks), "--subroutine-path", "lib",
                 "--user-m-path", "mfiles", "--dialect", "linuxcnc"]) == 0
    rows = [r.split(",") for r in blocks.read_text().splitlines()[1:]]
    assert [(float(r[3]), float(r[4])) for r in rows][-2:] == [(7.0, 0.0), (7.0, 7.0)]


def test_interpolate_refuses_a_program_beyond_its_memory_guard_naming_max_seconds(tmp_path, capsys):
    # 1200 moves of 100 mm at 5 mm/s: 24000 s, 24 million samples at 1 ms, beyond vcnc interpolate's guard (20
    # million); refused before any sample is computed, and nothing is written
    from vcnc.commands.interpolate import MAX_SAMPLES

    prog = tmp_path / "long.nc"
    prog.write_text("G21 G90\nG0 X0 Y0\n" + "G1 X100 F300\nG1 X0\n" * 600 + "M30\n")
    out = tmp_path / "sp.csv"
    assert main(["interpolate", str(prog), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}: the program needs at least ")
    assert f"more than the {MAX_SAMPLES} vcnc interpolate holds in memory; expected --max-seconds S" in err
    assert not out.exists()
    # its first 30 s (the first 100 mm move, 20 s, then 10 s of the way back: a prefix of the program fits one
    # try of the cut, vcnc.facade.TRY_SAMPLES), and a note saying so
    assert main(["interpolate", str(prog), "-o", str(out), "--max-seconds", "30"]) == 0
    said = capsys.readouterr().out
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert data[-1, 0] == pytest.approx(30.0) and np.all(np.isfinite(data))
    assert f"{prog}: only the first 30 s of at least 24000 s interpolated (budget 30 s)" in said
    assert data[-1, 1] == pytest.approx(50.0, abs=0.05)  # 5 mm/s back from 100 mm for 10 s, less the reversal


def test_default_dialect_error_names_the_dialect_that_reads_the_program(tmp_path, capsys):
    """A Haas program (Haas NGC mill manual: G00 is the power-on motion mode, "G81 ... R optional") that
    the default LinuxCNC reading refuses: the error stays (exit 2, no output) and says that --dialect
    fanuc or haas reads it; a program no dialect reads gets no such hint, nor does an explicit --dialect."""
    prog = tmp_path / "o1001.nc"
    prog.write_text("%\nO1001\nG20 G90 G54\nX1. Y1.\nG43 H1 Z0.1\nG81 G98 Z-0.2 F10.\nG80\nM30\n%\n")
    out = tmp_path / "sp.csv"
    assert main(["interpolate", str(prog), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{prog}:4:1: axis words before any motion code" in err
    assert "--dialect fanuc or haas: the program reads as that control's G-code" in err
    assert not out.exists()
    assert main(["interpolate", str(prog), "-o", str(out), "--dialect", "haas"]) == 0
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv")]) == 2
    assert "--dialect fanuc or haas" in capsys.readouterr().err
    assert main(["interpolate", str(prog), "-o", str(out), "--dialect", "linuxcnc"]) == 2
    assert "--dialect fanuc" not in capsys.readouterr().err
    bad = tmp_path / "bad.nc"
    bad.write_text("G01 X10 F100\nG01 X5 Q3\n")
    assert main(["interpolate", str(bad), "-o", str(out)]) == 2
    assert "--dialect" not in capsys.readouterr().err
    # a message of the reader that names the dialects itself gets no second hint (review28: ',R' said both
    # "(or --dialect fanuc / haas)" and ", or --dialect fanuc or haas: ...")
    corner = tmp_path / "corner.nc"
    corner.write_text("G21 G90 G17\nG0 X0 Y0\nG1 X10 Y0 ,R2 F3000\nG1 X10 Y10\nM30\n")
    assert main(["interpolate", str(corner), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "(or --dialect fanuc / haas)" in err and err.count("--dialect") == 1
