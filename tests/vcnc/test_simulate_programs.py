"""``vcnc simulate`` / ``vcnc.interpolate(program, machine)`` on the programs users bring: axes the
machine lacks, a time budget, programs without motion. Hand-written programs, real interpolation."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import interpolators
import vcnc
from vcnc.cli import main
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.facade import interpolate, truncation_note

#: A zigzag of 40 feed moves at 3000 mm/min (50 mm/s): about 40 s on fadal-pid, under G64 so the
#: moves are passed at speed (a cut then lands inside a chain).
ZIGZAG = "G21 G90 G64 P0.01\nG0 X0 Y0\n" + "".join(f"G1 X{50 * (i % 2)} Y{i} F3000\n" for i in range(1, 41)) + "M30\n"


def write(tmp_path: Path, text: str, name: str = "part.nc") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


@pytest.mark.parametrize(
    ("text", "line"),
    [
        ("G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10 Y5 F600\nM30\n", 2),  # Z moves from the origin at line 2
        ("G21 G90\nG0 X0 Y0 Z0\nG1 X10 Y5 F600\nG1 Z-1\nM30\n", 4),
        ("G21 G90 G18\nG0 X0 Y0 Z0\nG2 X0 Z0 I5 K0 F600\nM30\n", 3),  # a full circle in ZX ends where it starts
        ("G21 G90 G18\nG0 X0 Y0 Z0\nG2 X10 Z0 I5 K0 F600\nM30\n", 3),  # a half circle: Z named once
    ],
)
def test_program_moving_z_on_an_xy_machine_names_line_axis_machine(tmp_path, capsys, text, line):
    prog = write(tmp_path, text)
    out = tmp_path / "c.csv"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}:{line}: the program moves axis Z, which machine 'fadal-pid' does not have "
                          "(its axes: X, Y)")
    assert "[axes.z]" in err and not out.exists()


def test_a_helix_on_a_one_axis_machine_names_the_missing_axes_in_axis_order(tmp_path, capsys):
    prog = write(tmp_path, "G21 G90 G17\nG0 X10 Y0 Z0\nG2 X10 Y0 Z-5 I-10 J0 F600\nM30\n")  # a full turn down 5 mm
    assert main(["simulate", str(prog), "--machine", "emps", "-o", str(tmp_path / "c.csv")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}:3: the program moves axis Y, Z, which machine 'emps' does not have "
                          "(its axes: X); expected a machine with axis Y, Z")


def test_the_refusal_names_the_built_in_machine_with_the_axes_it_lacks(tmp_path, capsys):
    # the hint names every axis the program moves and the machine lacks, not only the first block's
    prog = write(tmp_path, "G21 G90\nG0 X0 Z5\nG1 Z-1 F100\nG1 X10 Y5 F600\nM30\n")
    assert main(["simulate", str(prog), "--machine", "emps", "-o", str(tmp_path / "c.csv")]) == 2
    err = capsys.readouterr().err
    assert f"{prog}:2: the program moves axis Z, which machine 'emps'" in err
    assert "`--machine emps+yz` runs Y and Z on a copy of its X drive (an assumption)" in err
    # a machine file is not offered a built-in name
    f = tmp_path / "m.toml"
    f.write_text(builtin_machine_text("emps"))
    assert main(["simulate", str(prog), "--machine", str(f), "-o", str(tmp_path / "c.csv")]) == 2
    err = capsys.readouterr().err
    assert "--machine" not in err and "[axes.z]" in err


def test_a_3_axis_program_runs_on_the_built_in_machine_with_z_copied_from_x(tmp_path, capsys):
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X10 Y5 F600\nG0 Z5\nM30\n")
    js, cap = tmp_path / "s.json", tmp_path / "c.csv"
    assert main(["simulate", str(prog), "--machine", "fadal-pid+z", "-o", str(cap), "--json", str(js)]) == 0
    s = json.loads(js.read_text())
    assert s["axes"] == ["x", "y", "z"]
    # the run in one line on stdout: its length and the errors of the summary, the worst axis named
    worst = max(s["tracking"], key=lambda a: s["tracking"][a]["max_um"])
    assert capsys.readouterr().out.splitlines()[-1] == (
        f"{prog}: simulated {(s['samples'] - 1) * 0.001:.6g} s ({s['samples']} samples at Ts = 0.001 s); "
        f"contour error max {s['contour']['max_um']:.3g} um, rms {s['contour']['rms_um']:.3g} um; "
        f"tracking error max {s['tracking'][worst]['max_um']:.3g} um (axis {worst}, "
        f"rms {s['tracking'][worst]['rms_um']:.3g} um); capture {cap}")
    c = vcnc.read_capture(cap)
    assert c.meta["machine"] == "fadal-pid+z"
    z = c.measured[:, c.axis_index("z")]
    assert np.max(z) == pytest.approx(5.0, abs=0.05) and np.min(z) == pytest.approx(-1.0, abs=0.05)


def test_interpolate_with_an_xy_machine_names_the_line_moving_z(tmp_path, capsys):
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nG1 Z-1\nM30\n")
    assert main(["interpolate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "s.csv")]) == 2
    assert capsys.readouterr().err.startswith(f"error: {prog}:4: the program moves axis Z, which machine 'fadal-pid'")


def test_program_naming_z_without_moving_it_runs_on_an_xy_machine(tmp_path):
    # Z0 written at Z0 (a habit of CAM post-processors): the machine runs X and Y; no Z column
    prog = write(tmp_path, "G21 G90\nG0 X0 Y0 Z0\nG1 X10 Y5 Z0 F600\nG3 X10 Y5 I-5 J0\nM30\n")
    js = tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv"),
                 "--json", str(js)]) == 0
    s = json.loads(js.read_text())
    assert s["axes"] == ["x", "y"] and s["contour"]["max_um"] > 0
    cap = vcnc.read_capture(tmp_path / "c.csv")
    assert cap.axes == ("x", "y") and np.isfinite(cap.measured).all()


def test_max_duration_cuts_at_the_budget_with_the_whole_programs_samples():
    machine = load_machine("fadal-pid")
    program = interpolators.parse_program(ZIGZAG, source="zigzag.nc")
    whole = interpolate(program, machine)
    assert whole.duration > 30.0
    cut = interpolate(program, machine, max_duration=5.0)
    assert len(cut) == 5001 and cut.duration == pytest.approx(5.0)
    # the samples are the whole program's: the prefix interpolated runs past the cut by the margin
    np.testing.assert_array_equal(cut.position, whole.position[: len(cut)])
    info = cut.meta["truncated"]
    assert info["of"] == 40 + 1 and info["exact"]
    assert info["blocks"] == int(cut.block[-1])  # the blocks before the one the cut falls in are complete
    assert info["line"] == program.blocks[info["blocks"]].line
    assert info["program_at_least"] >= 40 * 50 / 50.0  # 40 moves of >= 50 mm at 50 mm/s
    note = truncation_note(cut)
    assert note.startswith("only the first 5 s of at least ") and f"line {info['line']}" in note


def test_max_duration_of_short_moves_slower_than_their_feed_cuts_the_whole_programs_samples():
    # 300 moves of 0.5 mm at exact stop (G61): each is limited by the acceleration, not by F6000, so
    # the lower bound of the block times is about 4 times too short (the case that made the cut search
    # bisect over the blocks); the cut must still hold the whole program's samples up to the budget
    machine = load_machine("fadal-pid")
    text = "G21 G90 G61\nG0 X0 Y0\n" + "".join(f"G1 X{0.5 * (i % 2)} Y{0.01 * i:.2f} F6000\n"
                                                   for i in range(1, 301)) + "M30\n"
    program = interpolators.parse_program(text, source="short.nc")
    whole = interpolate(program, machine)
    cut = interpolate(program, machine, max_duration=4.0)
    assert whole.duration > 8.0 and len(cut) == 4001
    np.testing.assert_array_equal(cut.position, whole.position[: len(cut)])
    info = cut.meta["truncated"]
    assert info["exact"] and info["blocks"] == int(cut.block[-1]) and info["of"] == 301
    assert info["program_at_least"] == pytest.approx(whole.duration)  # the whole program fitted one try


def test_max_duration_longer_than_the_program_changes_nothing():
    machine = load_machine("fadal-pid")
    program = interpolators.parse_program("G21\nG0 X0 Y0\nG1 X20 Y10 F1200\nM30\n")
    whole = interpolate(program, machine)
    sp = interpolate(program, machine, max_duration=60.0)
    assert "truncated" not in sp.meta and truncation_note(sp) is None
    np.testing.assert_array_equal(sp.position, whole.position)


def test_max_duration_cuts_a_long_first_block_and_refuses_one_beyond_a_tries_memory():
    from vcnc.facade import TRY_SAMPLES

    machine = load_machine("fadal-pid")
    program = interpolators.parse_program("G21\nG1 X500 F60\nM30\n", source="slow.nc")  # 500 s
    cut = interpolate(program, machine, max_duration=1.0)
    assert len(cut) == 1001 and cut.meta["truncated"]["blocks"] == 0 and cut.meta["truncated"]["line"] == 2
    np.testing.assert_allclose(cut.position[-1, 0], 1.0, atol=0.01)  # 1 mm/s, after the start ramp
    assert TRY_SAMPLES < 20_000_000
    for text, line in (("G21\nG1 X20000 F60\nM30\n", 2),  # 20000 s
                       ("G21 G90\nG0 X0 Y0\nG1 X100 Y50 F0.001\nM30\n", 3)):  # a rapid that stays, then 6.7e6 s
        program = interpolators.parse_program(text, source="slow.nc")
        with pytest.raises(vcnc.GCodeError, match=rf"slow\.nc:{line}: this block alone runs longer than one try of the "
                           r"1 s cut holds \(1000000 samples, 1000 s\), and no block before it moves or dwells; "
                           r"expected a block within 1000 s"):
            interpolate(program, machine, max_duration=1.0)
    with pytest.raises(vcnc.InputError, match="max_duration must be a finite value > 0 s"):
        interpolate(program, load_machine("fadal-pid"), max_duration=0.0)


def test_simulate_max_seconds_says_where_it_cut_in_the_output_and_the_capture(tmp_path, capsys):
    prog = write(tmp_path, ZIGZAG)
    out, js, rep = tmp_path / "c.csv", tmp_path / "s.json", tmp_path / "rep"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out), "--json", str(js),
                 "--max-seconds", "3", "--report", str(rep)]) == 0
    said = capsys.readouterr().out
    assert f"{prog}: only the first 3 s of at least" in said and "the rest is not run" in said
    cap = vcnc.read_capture(out)
    assert len(cap) == 3001 and cap.meta["truncated"].startswith("only the first 3 s")
    assert json.loads(js.read_text())["samples"] == 3001
    assert "part.nc: only the first 3 s of at least" in (rep / "index.html").read_text()


@pytest.mark.parametrize("text", ["G21\nM30\n", "G21\nG0 X0 Y0\nM30\n"])  # no block; a move to where it is
def test_program_without_motion_or_dwell_is_refused_nothing_written(tmp_path, capsys, text):
    prog = write(tmp_path, text)
    out = tmp_path / "c.csv"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out)]) == 2
    assert capsys.readouterr().err == (f"error: {prog}: the program neither moves an axis nor dwells: nothing to "
                                       "simulate; expected a program with a move or a dwell\n")
    assert not out.exists()


@pytest.mark.parametrize(
    "text",
    [
        "G21\nG4 P1\nM30\n",  # a dwell only
        "G21\nG0 X10 Y10\nM30\n",  # a single point
        "G21 G90\nG0 X10 Y10\nG0 X20\nG0 Y0\nM30\n",  # rapids only
        "G20 G90\nG0 X0 Y0\nG1 X1 Y1 F20\nM30\n",  # inch on a metric machine: converted to mm
    ],
)
def test_programs_with_little_or_no_feed_motion_simulate_to_finite_captures(tmp_path, text):
    prog = write(tmp_path, text)
    out, js = tmp_path / "c.csv", tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out), "--json", str(js)]) == 0
    cap = vcnc.read_capture(out)
    assert len(cap) >= 1 and np.isfinite(cap.reference).all() and np.isfinite(cap.measured).all()
    s = json.loads(js.read_text())
    assert all(np.isfinite(v["max_um"]) and np.isfinite(v["rms_um"]) for v in s["tracking"].values())
    if "G20" in text:
        assert cap.reference[:, 0].max() == pytest.approx(25.4)  # 1 inch, in mm


def test_simulate_refuses_a_program_beyond_its_memory_guard_naming_max_seconds(tmp_path, capsys):
    # 1200 moves of 100 mm at 10 mm/s: 12000 s, 12 million samples at 1 ms, beyond vcnc simulate's guard (5 million)
    from vcnc.commands.simulate import MAX_SAMPLES

    prog = write(tmp_path, "G21 G90\nG0 X0 Y0\n" + "G1 X100 F600\nG1 X0\n" * 600 + "M30\n")
    out = tmp_path / "c.csv"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}: the program needs at least ")
    assert f"more than the {MAX_SAMPLES} vcnc simulate holds in memory; expected --max-seconds S" in err
    assert not out.exists()
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(out), "--max-seconds", "30"]) == 0
    assert len(vcnc.read_capture(out)) == 30001


def test_simulate_on_a_pid_machine_does_not_load_python_control(tmp_path):
    # python-control (with scipy.signal and matplotlib) takes about half of a short `vcnc simulate` run to
    # import; the compiled loop of the PID, P-PI, sliding-mode and PDF laws needs none of it (the
    # pole-placement design does: ballscrew-ppc, ballscrew-zpetc)
    import subprocess
    import sys

    prog = write(tmp_path, "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nM30\n")
    argv = ["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv")]
    code = (f"import sys\nfrom vcnc.cli import main\nassert main({argv!r}) == 0\n"
            "print(sorted(m for m in ('control', 'scipy.signal', 'matplotlib.pyplot') if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parents[2]).stdout
    assert out.strip().splitlines()[-1] == "[]"
