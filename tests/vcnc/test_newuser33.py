"""A new user's whole chain with their own files (session 33): outputs that cannot be written where asked,
machine files with the usual mistakes, wrong files given to the commands."""

from __future__ import annotations

from pathlib import Path

import pytest

from vcnc.cli import main

PROGRAM = "G21 G90 G94\nG0 X0 Y0\nG1 X5 Y0 F600\nG1 X5 Y5\nM2\n"


def _run(argv: list[str], capsys) -> tuple[int, str]:
    code = main(argv)
    err = capsys.readouterr().err.strip()
    return code, err


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("part.nc").write_text(PROGRAM)
    Path("note.txt").write_text("a file, not a folder\n")
    Path("out").mkdir()
    return tmp_path


def _nothing_new(folder: Path, before: set[str]) -> None:
    assert {p.name for p in folder.iterdir()} == before  # no partial or temporary file left


def test_an_output_under_a_file_is_refused_before_any_work_naming_it(work, capsys):
    before = {p.name for p in work.iterdir()}
    code, err = _run(["interpolate", "part.nc", "-o", "note.txt/sp.csv"], capsys)
    assert code == 2
    assert err.startswith("error: -o note.txt/sp.csv: ") and "note.txt is a file, not a folder" in err
    assert "\n" not in err and "Traceback" not in err
    _nothing_new(work, before)


@pytest.mark.parametrize("argv", [
    ["interpolate", "part.nc", "-o", "out"],
    ["toolpath", "circle", "-o", "out"],
    ["simulate", "part.nc", "--machine", "fadal-pid", "-o", "out"],
])
def test_an_output_file_named_by_an_existing_folder_is_exit_2(work, capsys, argv):
    code, err = _run(argv, capsys)
    assert code == 2
    assert err.startswith("error: -o out: a folder of that name exists; expected a file name for ")
    assert list(Path("out").iterdir()) == []


def test_a_report_folder_named_by_a_file_is_exit_2_for_compare(work, capsys):
    code, err = _run(["compare", "--truth", "fadal-pid", "--model", "none.json", "--report", "note.txt"], capsys)
    assert code == 2
    assert err == ("error: --report note.txt: a file of that name exists; expected a folder for the report "
                   "(made if absent)")


def test_the_program_itself_as_output_is_refused_and_kept(work, capsys):
    code, err = _run(["interpolate", "part.nc", "-o", "part.nc"], capsys)
    assert code == 2
    assert err == ("error: -o part.nc: it is the input part.nc itself, which the setpoints (CSV) would replace; "
                   "expected another file name")
    assert Path("part.nc").read_text() == PROGRAM


def test_a_missing_output_folder_is_made(work, capsys):
    code, _ = _run(["interpolate", "part.nc", "-o", "new/deeper/sp.csv"], capsys)
    assert code == 0
    rows = Path("new/deeper/sp.csv").read_text().splitlines()
    assert rows[0].startswith("t,x_ref,")
    assert [float(v) for v in rows[-1].split(",")[:2]][1] == pytest.approx(5.0)


def test_atomic_path_turns_a_folder_in_the_way_into_an_input_error(work):
    from vcnc.core.errors import InputError
    from vcnc.core.io import atomic_path

    with pytest.raises(InputError, match=r"out: cannot write the file here: Is a directory"):
        with atomic_path("out") as tmp:
            tmp.write_text("x")
    assert list(Path("out").iterdir()) == []
    assert not [p for p in work.iterdir() if p.name.endswith(".part")]


def _machine_without(text: str, axis: str) -> str:
    """The TOML ``text`` without the tables of ``axis``."""
    out, on = [], False
    for line in text.splitlines(keepends=True):
        if line.startswith("[axes."):
            on = line.startswith(f"[axes.{axis}]") or line.startswith(f"[axes.{axis}.")
        if not on:
            out.append(line)
    return "".join(out)


def test_a_machine_file_lacking_an_axis_the_program_moves_names_that_file(work, capsys):
    from vcnc.engine.machine import builtin_machine_text

    Path("mill.toml").write_text(_machine_without(builtin_machine_text("fadal-pid"), "y").replace(
        'name = "fadal-pid"', 'name = "mill"'))
    code, err = _run(["simulate", "part.nc", "--machine", "mill.toml", "-o", "c.csv"], capsys)
    assert code == 2
    # `vcnc machines --show mill` would fail: the way forward is the user's own file
    assert err == ("error: part.nc:4: the program moves axis Y, which machine 'mill' does not have (its axes: X); "
                   "expected a machine with axis Y: add an [axes.y] section to mill.toml")
    assert not Path("c.csv").exists()


@pytest.mark.parametrize(("name", "text", "kind"), [
    ("empty.nc", "", "an empty file"),
    ("blank.nc", "\n  \n", "an empty file"),
    ("capture.csv", "# machine: fadal-pid\nt,x_ref,x\n0,0,0\n", "a capture (CSV)"),
    ("x.json", '{"format": "vcnc.axis-model/1"}\n', "a JSON file (a model file?)"),
    ("mill.toml", "# my mill\nname = \"m\"\nsample_time = 0.001\n[axes.x]\n", "a machine definition (TOML)"),
])
def test_a_file_that_is_no_program_is_named_for_what_it_is(work, capsys, name, text, kind):
    Path(name).write_text(text)
    for argv in (["interpolate", name, "-o", "sp.csv"], ["simulate", name, "--machine", "fadal-pid", "-o", "c.csv"]):
        code, err = _run(argv, capsys)
        assert code == 2
        assert err == (f"error: {name}: this is {kind}, not a part program; expected a part program (ISO G-code or "
                       "Heidenhain conversational)")
    assert not Path("sp.csv").exists() and not Path("c.csv").exists()


def test_a_program_beginning_with_a_parameter_is_still_read(work, capsys):
    Path("p.ngc").write_text("#1 = 4\nG21 G90\nG1 X#1 F600\nM2\n")
    code, _ = _run(["interpolate", "p.ngc", "-o", "sp.csv"], capsys)
    assert code == 0
    assert float(Path("sp.csv").read_text().splitlines()[-1].split(",")[1]) == pytest.approx(4.0)


def test_a_rotary_axis_model_cannot_stand_in_for_linear_axes(work, capsys):
    from identification import ReducedAxisModel
    from vcnc.engine.machine import load_machine

    m = load_machine("fadal-pid")
    ReducedAxisModel(parameters=m.axis("x").reduced_parameters(), sample_time=m.sample_time, axis="a").to_json("a.json")
    code, err = _run(["compare", "--truth", "fadal-pid", "--model", "a.json", "--toolpath", "part.nc"], capsys)
    assert code == 2
    # its friction is in deg/s^2: the contour error in mm would mix units
    assert err == ("error: --model a.json: a model identified on axis a [deg] cannot predict axis x, y [mm]; expected "
                   "a model of each such axis: --model x=FILE --model y=FILE")
    code, err = _run(["compare", "--truth", "fadal-pid", "--model", "x=a.json", "--model", "y=a.json",
                      "--toolpath", "circle"], capsys)
    assert code == 2
    assert err.startswith("error: --model x=a.json: a model identified on axis a [deg] cannot predict axis x [mm]")


def _capture_text(rows: list[str]) -> str:
    return "# machine: my-mill\nt,x_ref,x\n" + "".join(r + "\n" for r in rows)


@pytest.mark.parametrize(("bad", "message"), [
    ("0.002,0.2,nan", "c.csv:5:3: column 'x' is not finite (got 'nan')"),
    ("0.002,0.2", "c.csv:5: 2 fields, expected 3 (as in the header)"),
    ("0.002,0.2,1_0", None),  # Python's float reads 1_0 as 10: the row-by-row reading decides, as before
    ("0.002,0.2,0.1 # note", "c.csv:5:3: column 'x' is not a number (got '0.1 # note')"),
])
def test_a_capture_csv_the_fast_reader_doubts_is_read_row_by_row_with_its_line(work, bad, message):
    from vcnc.core.capture import read_capture_csv
    from vcnc.core.errors import CaptureError

    rows = ["0,0,0", "0.001,0.1,0.05", bad, "0.003,0.3,0.2"]
    Path("c.csv").write_text(_capture_text(rows))
    if message is None:
        assert read_capture_csv("c.csv").measured[2, 0] == 10.0
        return
    with pytest.raises(CaptureError) as exc:
        read_capture_csv("c.csv")
    assert str(exc.value) == message


def test_a_capture_csv_as_vcnc_writes_it_reads_the_same_numbers_with_its_lines(work):
    from vcnc.core.capture import read_capture_csv
    from vcnc.core.errors import CaptureError

    rows = [f"{k * 0.001:.12g},{k * 0.1:.12g},{k * 0.1 - 0.003:.12g}" for k in range(50)]
    Path("c.csv").write_text(_capture_text(rows))
    cap = read_capture_csv("c.csv")
    assert cap.t.size == 50 and cap.measured[49, 0] == pytest.approx(4.897)
    assert cap.reference[:, 0].tolist() == [float(f"{k * 0.1:.12g}") for k in range(50)]
    # a sampling error still names the file line of its row (header on line 2, rows from line 3)
    rows[20] = "0.0195,2,1.997"
    Path("c.csv").write_text(_capture_text(rows))
    with pytest.raises(CaptureError, match=r"^c\.csv:23:"):
        read_capture_csv("c.csv")


def test_a_servo_period_too_coarse_for_the_gains_is_named_after_a_saturated_run(work, capsys):
    from vcnc.engine.machine import builtin_machine_text, load_machine

    text = builtin_machine_text("fadal-pid")
    Path("slow.toml").write_text(text.replace("sample_time = 0.001", "sample_time = 0.01"))
    assert load_machine("fadal-pid").unstable_axes() == {}
    unstable = load_machine("slow.toml").unstable_axes()
    assert set(unstable) == {"x", "y"} and 1.8 < unstable["x"] < 2.1  # |z| of the sampled PID loop
    Path("sq.nc").write_text("G21 G90 G94\nG0 X0 Y0\nG1 X20 F600\nG1 Y20\nM2\n")
    code = main(["simulate", "sq.nc", "--machine", "slow.toml", "-o", "c.csv"])
    out = capsys.readouterr().out
    assert code == 0
    assert ("sq.nc: warning: at the machine's sample_time 0.01 s the closed loop of axis x, y is unstable (largest "
            "pole x |z| = ") in out
    assert "check 'sample_time' [s] in slow.toml" in out


def test_a_machine_file_is_checked_for_its_servo_period_on_every_run(work, capsys):
    from vcnc.engine.machine import builtin_machine_text

    text = builtin_machine_text("fadal-pid")
    Path("mine.toml").write_text(text)
    Path("coarse.toml").write_text(text.replace("sample_time = 0.001", "sample_time = 0.004"))
    assert main(["simulate", "part.nc", "--machine", "mine.toml", "-o", "a.csv"]) == 0
    assert "sample_time" not in capsys.readouterr().out  # stable at 1 ms: nothing said
    assert main(["simulate", "part.nc", "--machine", "coarse.toml", "-o", "b.csv"]) == 0
    out = capsys.readouterr().out
    # fadal-pid's X loop at 4 ms: |z| = 1.015, just outside the unit circle; Y (heavier) stays inside
    assert ("at the machine's sample_time 0.004 s the closed loop of axis x is unstable (largest pole x |z| = 1.01)"
            in out)


def test_the_servo_period_warning_comes_before_a_run_that_fails(work, capsys, monkeypatch):
    """A machine file's unstable sampled loop is said before the simulation: a run at a unit slip such as
    ``sample_time = 1`` can fail later (its contour step: 1 s samples skip whole blocks of the path), and the
    user must see the cause first."""
    from vcnc.core.errors import InputError
    from vcnc.engine.machine import Machine, builtin_machine_text

    Path("slip.toml").write_text(builtin_machine_text("fadal-pid").replace("sample_time = 0.001", "sample_time = 1"))

    def fails(self, setpoints, seed=None):
        raise InputError("the run failed")

    monkeypatch.setattr(Machine, "simulate", fails)
    code = main(["simulate", "part.nc", "--machine", "slip.toml", "-o", "c.csv"])
    captured = capsys.readouterr()
    assert code == 2 and "the run failed" in captured.err
    assert "part.nc: warning: at the machine's sample_time 1 s the closed loop of axis x, y is unstable" in captured.out
    assert not Path("c.csv").exists()
