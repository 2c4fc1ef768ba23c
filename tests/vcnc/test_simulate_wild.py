"""``vcnc simulate`` as a process planner runs it on real programs (the simwild audit, session 27): a program
moving a rotary axis the machine lacks is refused naming the line, the word and how to add the axis; a machine file
with that axis runs it in degrees; the summary says what was simulated. Hand-written programs modelled on the
wild ones (a 4-axis surfacing finish pass, a CAM profile)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import interpolators
import vcnc
from vcnc.cli import main
from vcnc.contour import contour_metrics, feed_segments
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.facade import interpolate

#: A 4-axis finish pass as CAM posts it: X Y feed moves, then the table turned by A.
ROTARY = "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nG1 A90 F3600\nG1 X0 Y0 F600\nM30\n"


def write(tmp_path: Path, text: str, name: str = "part.nc") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def machine_with_a(tmp_path: Path) -> Path:
    """fadal-pid's file with an ``[axes.a]`` whose tables are those of its X axis: positions in degrees
    through the same drive (a 10 deg/rev worm stage in the ball screw's place, our reading for the test)."""
    text = builtin_machine_text("fadal-pid")
    lines = text.splitlines()
    heads = [i for i, ln in enumerate(lines) if ln.startswith("[")]
    x = [ln for i in heads if lines[i] == "[axes.x]" or lines[i].startswith("[axes.x.")
         for ln in lines[i:next((j for j in heads if j > i), len(lines))]]
    f = tmp_path / "xya.toml"
    f.write_text(text.replace('name = "fadal-pid"', 'name = "xya"') + "\n"
                 + "\n".join(ln.replace("[axes.x", "[axes.a") for ln in x) + "\n")
    return f


def test_a_rotary_move_on_a_machine_without_it_names_line_axis_and_how_to_add_it(tmp_path, capsys):
    prog = write(tmp_path, ROTARY)
    out = tmp_path / "c.csv"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    # the reader's error (line, column, the word) and the way forward of vcnc.facade.check_program_axes
    assert err.startswith(f"error: {prog}:4:4: axis word 'A' is not supported: this machine has no rotary axis A")
    assert err.endswith("(got 'A90'); expected axis words X, Y, Z, or a machine with axis A: write `vcnc machines "
                        "--show fadal-pid` to a TOML file and add an [axes.a] section in degrees (limits in deg/s, "
                        "deg/s^2, deg/s^3)\n")
    assert not out.exists()


def test_a_move_of_an_axis_the_machine_file_lacks_is_named_with_the_file_machines_axes(tmp_path, capsys):
    prog = write(tmp_path, ROTARY.replace("A90", "B-45"))
    assert main(["simulate", str(prog), "--machine", str(machine_with_a(tmp_path)),
                 "-o", str(tmp_path / "c.csv")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}:4:4: axis word 'B' is not supported: this machine has no rotary axis B")
    # the section goes into the machine's own file (`vcnc machines --show xya` knows built-in names only)
    assert err.endswith("or a machine with axis B: add an [axes.b] section in degrees (limits in deg/s, deg/s^2, "
                        f"deg/s^3) to {tmp_path / 'xya.toml'}\n") and "--machine" not in err


def test_another_error_of_a_program_naming_a_missing_axis_stays_the_readers(tmp_path, capsys):
    # the A move reads, the line after it does not: the reader's error (the wider read fails too)
    prog = write(tmp_path, ROTARY.replace("M30\n", "G1 X1 Q\nM30\n"))
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}:4:") and "axis word 'A'" in err and "[axes.a]" not in err


def test_a_program_naming_a_rotary_axis_without_moving_it_runs_on_an_xy_machine(tmp_path):
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0 A0\nG1 X10 Y5 F600\nM30\n")
    js = tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv"),
                 "--json", str(js)]) == 0
    assert json.loads(js.read_text())["axes"] == ["x", "y"]


def test_a_machine_file_with_a_rotary_axis_runs_it_in_degrees(tmp_path, capsys):
    prog = write(tmp_path, ROTARY)
    out, js = tmp_path / "c.csv", tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", str(machine_with_a(tmp_path)), "-o", str(out),
                 "--json", str(js)]) == 0
    cap = vcnc.read_capture(out)
    a = cap.measured[:, cap.axis_index("a")]
    assert cap.axes == ("x", "y", "a") and np.isfinite(cap.measured).all()
    assert a[-1] == pytest.approx(90.0, abs=0.01) and cap.reference[0, cap.axis_index("a")] == 0.0
    s = json.loads(js.read_text())
    # the rotary axis' error in mdeg (the summary's _um keys): at 60 deg/s the lag of the X drive's loop,
    # 66 mdeg measured (X: 57 um at 10 mm/s)
    assert 30.0 < s["tracking"]["a"]["max_um"] < 150.0
    assert "contour" in s and s["contour"]["max_um"] < 1000.0


def test_the_summary_says_which_program_machine_profile_and_seed_ran_the_whole_program(tmp_path):
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nG1 X0 Y0\nM30\n", name="plate.nc")
    js, rep = tmp_path / "s.json", tmp_path / "rep"
    assert main(["simulate", str(prog), "--machine", "fadal-ppi", "-o", str(tmp_path / "c.csv"), "--json", str(js),
                 "--profile", "scurve", "--seed", "7", "--report", str(rep)]) == 0
    s = json.loads(js.read_text())
    assert (s["program"], s["machine"], s["profile"], s["seed"]) == ("plate.nc", "fadal-ppi", "scurve", 7)
    assert "truncated" not in s
    assert json.loads((rep / "summary.json").read_text())["machine"] == "fadal-ppi"
    assert "scurve profile, seed 7" in (rep / "index.html").read_text()


def test_the_summary_of_a_cut_program_says_where_it_was_cut(tmp_path):
    zigzag = "G21 G90 G64 P0.01\nG0 X0 Y0\n" + "".join(f"G1 X{50 * (i % 2)} Y{i} F3000\n" for i in range(1, 21))
    prog = write(tmp_path, zigzag + "M30\n")
    js = tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv"), "--json", str(js),
                 "--max-seconds", "2"]) == 0
    s = json.loads(js.read_text())
    assert s["samples"] == 2001 and s["profile"] == "trapezoid"
    assert s["truncated"].startswith("only the first 2 s of at least") and "the rest is not run" in s["truncated"]


def test_the_contour_error_of_the_feed_moves_is_given_beside_that_of_every_move(tmp_path, capsys):
    # a long diagonal rapid (X and Y lag differently at 250 mm/s), a dwell, then a slow cut along it: the rapid's
    # deviation is the program's largest, the cut's smaller (measured). Without the dwell the cut starts where the
    # rapid stops (LinuxCNC stops between a rapid and a feed move: Dialect.rapid_feed_stop, session 35) and the axes
    # still settling from the rapid's stop give the cut's first samples the rapid's deviation
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0\nG0 X120 Y80\nG4 P0.5\nG1 X140 Y90 F300\nM30\n")
    js, rep = tmp_path / "s.json", tmp_path / "rep"
    # (--settle 0: the capture ends with the reference, as machine.simulate below; with the settling tail
    # (newuser34) fadal-pid overshoots the last point by 15.8 um after the reference stopped, the run's largest)
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv"), "--json", str(js),
                 "--report", str(rep), "--settle", "0"]) == 0
    s = json.loads(js.read_text())
    program = interpolators.load_program(prog)
    machine = load_machine("fadal-pid")
    cap = machine.simulate(interpolate(program, machine), seed=0)  # as the command ran it
    whole = contour_metrics(cap)
    feed = contour_metrics(cap, include_segments=feed_segments(cap.path, program))
    assert s["contour"]["max_um"] == pytest.approx(whole["max_um"], rel=1e-9)
    assert s["contour_feed"]["max_um"] == pytest.approx(feed["max_um"], rel=1e-9)
    assert s["contour_feed"]["max_um"] < 0.8 * s["contour"]["max_um"]
    said = capsys.readouterr().out
    line = (f"contour error on the feed moves (rapids left out): max {feed['max_um']:.3g} um, rms "
            f"{feed['rms_um']:.3g} um (every move: max {whole['max_um']:.3g} um)")
    assert f"{prog}: {line}" in said and line in (rep / "index.html").read_text()


@pytest.mark.parametrize("text", ["G21 G90\nG1 X10 Y5 F600\nG1 X0 Y0\nM30\n",  # no rapid: the two are the same
                                  "G21 G90\nG0 X10 Y5\nG0 X0 Y0\nM30\n"])  # no feed move: nothing cut
def test_no_feed_contour_entry_without_both_rapids_and_feed_moves(tmp_path, capsys, text):
    prog = write(tmp_path, text)
    js = tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv"),
                 "--json", str(js)]) == 0
    s = json.loads(js.read_text())
    assert s["contour"]["max_um"] > 0 and "contour_feed" not in s
    assert "feed moves" not in capsys.readouterr().out


def test_a_dense_raster_colours_its_path_by_the_contour_error_a_short_path_magnifies_it(tmp_path):
    # 1201 feed moves of a 0.2 mm stepover raster (a CAM finish pass): the error drawn x100 would cover it
    raster = "G21 G90 G64\nG0 X0 Y0\nF3000\n" + "".join(
        f"G1 X{20 * ((i + 1) // 2 % 2)} Y{0.2 * (i // 2):.1f}\n" for i in range(1, 1202)) + "M30\n"
    for name, text, caption in [("raster.nc", raster, "its points coloured by the contour error"),
                                ("plate.nc", "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nG1 X0 Y0\nM30\n",
                                 "with the contour error magnified")]:
        prog = write(tmp_path, text, name=name)
        rep = tmp_path / f"rep_{name}"
        assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv"),
                     "--report", str(rep)]) == 0
        assert caption in (rep / "index.html").read_text() and (rep / "path.png").stat().st_size > 10_000


@pytest.mark.parametrize(("option", "target", "said"), [
    ("-o", "folder", "-o {}: a folder of that name exists; expected a file name for the capture file (CSV)"),
    ("--json", "folder", "--json {}: a folder of that name exists; expected a file name for the summary file"),
    ("--report", "file", "--report {}: a file of that name exists; expected a folder for the report (made if absent)"),
])
def test_an_output_that_cannot_be_written_is_refused_before_the_run(tmp_path, capsys, option, target, said):
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nM30\n")
    there = tmp_path / "there"
    there.mkdir() if target == "folder" else there.write_text("keep\n")
    args = {"-o": str(tmp_path / "c.csv"), "--json": None, "--report": None, option: str(there)}
    argv = ["simulate", str(prog), "--machine", "fadal-pid", *[x for k, v in args.items() if v for x in (k, v)]]
    assert main(argv) == 2
    assert capsys.readouterr().err == f"error: {said.format(there)}\n"
    assert not (tmp_path / "c.csv").exists() and (target == "folder" or there.read_text() == "keep\n")
