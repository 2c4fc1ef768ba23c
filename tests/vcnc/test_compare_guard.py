"""``vcnc compare``'s memory guard and ``--max-seconds`` (shared with ``vcnc simulate`` and ``vcnc interpolate``:
``vcnc.commands.interpolate.sample_guard``), the summary's ``truncated``, and the note on a model identified on
another axis than the one it is used for. Hand-written programs; the exact reduced models of fadal-pid."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

import interpolators
import vcnc.commands.compare as compare_command
from identification import ReducedAxisModel
from vcnc.cli import main
from vcnc.contour import commanded_points, contour_error
from vcnc.contour_compare import compare
from vcnc.engine.machine import load_machine
from vcnc.errors import InputError

#: A 10 mm square at F600 (10 mm/s): four sides of about 1.1 s each (2000 mm/s^2 to and from 10 mm/s at the
#: exact stops of G61).
SQUARE = "G21 G90 G61\nG0 X0 Y0\nG1 X10 Y0 F600\nG1 X10 Y10\nG1 X0 Y10\nG1 X0 Y0\nM30\n"


def write(tmp_path: Path, text: str, name: str = "square.nc") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def model_file(tmp_path: Path, axis: str, name: str) -> str:
    """The exact reduced model of fadal-pid's ``axis``, written to ``name``."""
    m = load_machine("fadal-pid")
    model = ReducedAxisModel(parameters=m.axis(axis).reduced_parameters(), sample_time=m.sample_time, axis=axis)
    path = tmp_path / name
    model.to_json(path)
    return str(path)


def models(tmp_path: Path) -> list[str]:
    return ["--model", f"x={model_file(tmp_path, 'x', 'mx.json')}",
            "--model", f"y={model_file(tmp_path, 'y', 'my.json')}"]


def test_max_seconds_compares_the_first_seconds_and_the_summary_says_where_it_was_cut(tmp_path, capsys):
    prog = write(tmp_path, SQUARE)
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", "fadal-pid", *models(tmp_path), "--toolpath", str(prog), "--truth-runs", "1",
                 "--max-seconds", "1.5", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    # 1.5 s at Ts = 1 ms: samples 0..1500, then the 0.2 s the axes settle at the last position
    assert d["samples"] == 1501 + 200
    cut = d["truncated"]
    # at least the four sides' 10 mm at 10 mm/s; the rapid (line 2, no motion) and the first side are complete
    assert cut == ("only the first 1.5 s of at least 4 s compared (budget 1.5 s): 2 of 5 blocks complete, cut in the "
                   "block at line 4; the rest is not run")
    assert d["notes"][0] == f"{prog}: {cut}"
    assert f"note: {prog}: {cut}\n" in capsys.readouterr().out


def test_a_program_that_runs_whole_within_max_seconds_is_not_truncated(tmp_path):
    prog = write(tmp_path, SQUARE)
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", "fadal-pid", *models(tmp_path), "--toolpath", str(prog), "--truth-runs", "1",
                 "--max-seconds", "60", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert "truncated" not in d
    assert not any("only the first" in n for n in d["notes"])


def test_beyond_the_sample_limit_compare_is_refused_naming_the_program_and_max_seconds(tmp_path, capsys,
                                                                                       monkeypatch):
    monkeypatch.setattr(compare_command, "MAX_SAMPLES", 1000)
    prog = write(tmp_path, SQUARE)
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", "fadal-pid", *models(tmp_path), "--toolpath", str(prog), "--truth-runs", "1",
                 "--json", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {prog}: the program needs ")
    assert "more than the 1000 vcnc compare holds in memory; expected --max-seconds S to compare its first S seconds" \
        in err
    assert not out.exists()
    # within --max-seconds the limit is not asked: the cut bounds the samples
    assert main(["compare", "--truth", "fadal-pid", *models(tmp_path), "--toolpath", str(prog), "--truth-runs", "1",
                 "--max-seconds", "0.5", "--json", str(out)]) == 0
    assert json.loads(out.read_text())["samples"] == 501 + 200


def test_max_duration_is_refused_for_a_capture_truth_and_for_given_setpoints(tmp_path):
    machine = load_machine("fadal-pid")
    exact = {a: ReducedAxisModel(parameters=machine.axis(a).reduced_parameters(), sample_time=machine.sample_time,
                                 axis=a) for a in machine.axes}
    run = compare(machine, exact, "diamond", truth_runs=1)
    cap = machine.simulate(run.setpoints)
    with pytest.raises(InputError, match=r"\(--max-seconds\) applies to a toolpath run on a simulated truth"):
        compare(cap, exact, "diamond", max_duration=1.0)
    with pytest.raises(InputError, match=r"max_duration \(--max-seconds\) applies to a program or built-in toolpath"):
        compare(machine, exact, run.setpoints, max_duration=1.0)


def test_a_model_identified_on_another_axis_is_named_on_the_command_line(tmp_path, capsys):
    my = model_file(tmp_path, "y", "y.json")
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", "fadal-pid", "--model", f"x={my}", "--model", f"y={my}", "--toolpath",
                 "diamond", "--truth-runs", "1", "--json", str(out)]) == 0
    note = (f"model {my} (identified on axis y) used for x: the prediction assumes x's drive is like y's (a model "
            "identified on x, --model x=FILE, if there is one)")
    stdout = capsys.readouterr().out
    assert f"note: {note}\n" in stdout
    assert "used for y" not in stdout
    assert note in json.loads(out.read_text())["notes"]


def test_a_model_object_on_another_axis_is_named_by_its_type():
    machine = load_machine("fadal-pid")
    y = ReducedAxisModel(parameters=machine.axis("y").reduced_parameters(), sample_time=machine.sample_time, axis="y")
    rep = compare(machine, {"x": y, "y": dataclasses.replace(y)}, "circle", truth_runs=1)
    assert [n for n in rep.notes if "used for" in n] == [
        "model ReducedAxisModel object (identified on axis y) used for x: the prediction assumes x's drive is like "
        "y's (a model identified on x, --model x=FILE, if there is one)"]


def test_commanded_points_computed_once_give_the_contour_error_of_each_run():
    """compare finds where the command is on the path once for its runs (vcnc.contour.commanded_points)."""
    machine = load_machine("fadal-pid")
    run = compare(machine, {a: ReducedAxisModel(parameters=machine.axis(a).reduced_parameters(),
                                                sample_time=machine.sample_time, axis=a) for a in machine.axes},
                  "diamond", truth_runs=1)
    sp = run.setpoints
    measured = machine.simulate(sp, seed=3).measured
    alone = contour_error(sp.path, measured, sp.axes, reference=sp.position, t=sp.t)
    shared = contour_error(sp.path, measured, sp.axes, reference=sp.position, t=sp.t,
                           commanded=commanded_points(sp.path, sp.position, sp.axes))
    assert shared.error.tolist() == alone.error.tolist()
    assert shared.commanded_arc_length.tolist() == alone.commanded_arc_length.tolist()
    assert json.dumps(shared.metrics()) == json.dumps(alone.metrics())  # (NaN quadrant maxima: none on a diamond)
    with pytest.raises(InputError, match="commanded holds 10 points but positions have"):
        contour_error(sp.path, measured, sp.axes, reference=sp.position, commanded=(np.zeros(10, int), np.zeros(10)))


def test_the_corner_maxima_are_the_largest_error_within_the_window_of_each_corner():
    """ContourError.metrics takes each corner's window maximum in one reduceat: the same numbers as a slice each."""
    machine = load_machine("fadal-pid")
    prog = interpolators.parse_program("G21 G90 G64\nG0 X0 Y0\nG1 X10 Y0 F6000\nG1 X10 Y10\nG1 X0 Y10\nG1 X0 Y0\n"
                                       "M30\n")
    sp = interpolators.interpolate(prog, limits=machine.limits, sample_time=machine.sample_time)
    ce = contour_error(sp.path, machine.simulate(sp).measured, sp.axes, reference=sp.position, t=sp.t)
    m = ce.metrics(window_mm=1.0)
    s, e = ce.arc_length, np.abs(ce.error)
    want = [float(np.max(e[(s >= s0 - 1.0) & (s <= s0 + 1.0)]) * 1e3) for s0 in (10.0, 20.0, 30.0)]
    assert [c["arc_length_mm"] for c in m["corners"]] == [10.0, 20.0, 30.0]
    assert [c["max_um"] for c in m["corners"]] == want
    assert m["corner_max_um"] == max(want)


def test_the_truth_s_corners_are_the_path_s_corners_with_the_mean_of_the_runs_maxima(tmp_path):
    """The mean over noise runs averages each corner's maximum; its position, the same in every run, is kept."""
    machine = load_machine("fadal-pid")
    exact = {a: ReducedAxisModel(parameters=machine.axis(a).reduced_parameters(), sample_time=machine.sample_time,
                                 axis=a) for a in machine.axes}
    rep = compare(machine, exact, str(write(tmp_path, SQUARE)), truth_runs=3)
    corners = rep.metrics()["true"]["corners"]
    assert [c["position_mm"] for c in corners] == [[10.0, 0.0, 0.0], [10.0, 10.0, 0.0], [0.0, 10.0, 0.0]]
    for k, c in enumerate(corners):
        runs = [r["corners"][k]["max_um"] for r in rep.true_runs]
        assert len(set(runs)) > 1  # the noise moves them
        assert c["max_um"] == pytest.approx(sum(runs) / 3, rel=1e-12)
