"""Session 33's review: outputs of one command that name the same file, a model file given as compare's summary."""

from __future__ import annotations

from pathlib import Path

import pytest

from vcnc.cli import main

PROGRAM = "G21 G90 G94\nG0 X0 Y0\nG1 X5 Y0 F600\nG1 X5 Y5\nM2\n"


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("part.nc").write_text(PROGRAM)
    return tmp_path


@pytest.mark.parametrize(("argv", "message"), [
    (["interpolate", "part.nc", "-o", "sp.csv", "--blocks", "sp.csv"],
     "error: --blocks sp.csv: the same file as -o sp.csv, which it would replace; expected another file name for "
     "--blocks"),
    (["interpolate", "part.nc", "-o", "sp.csv", "--plot", "./sp.csv"],
     "error: --plot ./sp.csv: the same file as -o sp.csv, which it would replace; expected another file name for "
     "--plot"),
    (["simulate", "part.nc", "--machine", "fadal-pid", "-o", "run.csv", "--json", "run.csv"],
     "error: --json run.csv: the same file as -o run.csv, which it would replace; expected another file name for "
     "--json"),
    (["simulate", "part.nc", "--machine", "fadal-pid", "-o", "run", "--report", "run"],
     "error: --report run: the same file as -o run, which it would replace; expected another file name for "
     "--report"),
    (["identify", "c.csv", "--json", "m", "--report", "m"],
     "error: --report m: the same file as --json m, which it would replace; expected another file name for "
     "--report"),
    (["compare", "--truth", "fadal-pid", "--model", "m.json", "--json", "out", "--report", "out"],
     "error: --report out: the same file as --json out, which it would replace; expected another file name for "
     "--report"),
])
def test_two_outputs_naming_one_file_are_refused_before_any_work(work, capsys, argv, message):
    """``-o run.csv --json run.csv`` wrote the capture, then the summary over it, and ended with exit 0."""
    assert main(argv) == 2
    assert capsys.readouterr().err.strip() == message
    assert sorted(p.name for p in work.iterdir()) == ["part.nc"]


def test_compare_refuses_its_model_file_as_the_summary(work, capsys):
    """``--model m.json --json m.json`` replaced the model by the summary."""
    from identification import ReducedAxisModel
    from vcnc.engine.machine import load_machine

    m = load_machine("fadal-pid")
    ReducedAxisModel(parameters=m.axis("x").reduced_parameters(), sample_time=m.sample_time, axis="x").to_json("m.json")
    before = Path("m.json").read_text()
    assert main(["compare", "--truth", "fadal-pid", "--model", "m.json", "--json", "m.json"]) == 2
    assert capsys.readouterr().err.strip() == ("error: --json m.json: it is the input m.json itself, which the summary "
                                               "file would replace; expected another file name")
    assert main(["compare", "--truth", "fadal-pid", "--model", "x=m.json", "--model", "y=m.json",
                 "--json", "m.json"]) == 2
    assert "it is the input m.json itself" in capsys.readouterr().err
    assert Path("m.json").read_text() == before


@pytest.mark.parametrize("argv", [
    ["interpolate", "part.nc", "--tool-table", "tools.tbl", "-o", "tools.tbl"],
    ["simulate", "part.nc", "--machine", "fadal-pid", "--tool-table", "tools.tbl", "-o", "run.csv",
     "--json", "tools.tbl"],
])
def test_the_tool_table_is_an_input_no_output_may_replace(work, capsys, argv):
    """``--tool-table tools.tbl -o tools.tbl`` replaced the tool table by the setpoints."""
    table = "T1 P1 D6 Z+10 ;6 mm end mill\n"
    Path("tools.tbl").write_text(table)
    assert main(argv) == 2
    assert "it is the input tools.tbl itself" in capsys.readouterr().err
    assert Path("tools.tbl").read_text() == table
