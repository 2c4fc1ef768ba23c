"""``vcnc compare`` as a process planner runs it with models identified from real traces and real programs (the
comparewild audit, session 28): the program is read for the true machine as ``vcnc simulate`` reads it, a move of an
axis the machine lacks is refused naming the line and ``--truth NAME+z``, an axis only named runs, a rotary axis of a
machine file is read, and the notes say what the numbers rest on (a model of a coarse record, dead times that differ,
a rotary axis outside the contour). Hand-written programs modelled on the wild ones; synthetic models."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest

from identification import ReducedAxisModel
from tests.vcnc.test_simulate_wild import machine_with_a, write
from vcnc.capture import Capture
from vcnc.cli import main
from vcnc.contour import feature_points, path_features
from vcnc.contour_compare import compare
from vcnc.engine.machine import Machine, load_machine
from vcnc.errors import InputError

#: An inch program that names Z at Z0 in every block without moving it (as corpus 0085, a dodecagon, does).
NAMED_Z = ("G61 G90 G20\nG0 X-.1 Y0 Z0\nG1 X0 Y0 Z0 F20\nG64\nG1 X0.0866 Y-0.05 Z0 F10\nG1 X0.1366 Y-0.1366 Z0\n"
           "G1 X0.1366 Y-0.2366 Z0\nM2\n")
#: A helix down in Z (as corpus 0089): it moves Z.
HELIX = "G21 G90 G17\nG0 X10 Y0 Z0\nG1 X10 Y0 F600\nG3 X10 Y0 Z-1 I-10 J0\nM30\n"
#: A 4-axis finish pass as CAM posts it: X Y feed moves, the table turned by A.
ROTARY = "G21 G90\nG0 X0 Y0\nG1 X10 Y5 F600\nG1 A90 F3600\nG1 X0 Y0 A0 F600\nM30\n"


def models_of(machine: str = "fadal-pid", **changes) -> dict[str, ReducedAxisModel]:
    """The exact reduced models of a built-in machine's axes, with ``changes`` per axis (``y={"delay_s": 0.05}``)."""
    m = load_machine(machine)
    out = {}
    for a in m.axes:
        model = ReducedAxisModel(parameters=m.axis(a).reduced_parameters(), sample_time=m.sample_time, axis=a)
        out[a] = dataclasses.replace(model, **changes.get(a, {}))
    return out


def model_files(tmp_path: Path, models: dict[str, ReducedAxisModel]) -> list[str]:
    args = []
    for a, m in models.items():
        m.to_json(tmp_path / f"m{a}.json")
        args += ["--model", f"{a}={tmp_path / f'm{a}.json'}"]
    return args


def test_a_program_moving_z_on_a_two_axis_truth_names_the_line_and_truth_plus_z(tmp_path, capsys):
    prog = write(tmp_path, HELIX)
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", "fadal-pid", *model_files(tmp_path, models_of()), "--toolpath", str(prog),
                 "--json", str(out)]) == 2
    err = capsys.readouterr().err
    # vcnc.facade.check_program_axes, as vcnc simulate reports it, with compare's option for the machine
    assert err.startswith(f"error: {prog}:4: the program moves axis Z, which machine 'fadal-pid' does not have "
                          "(its axes: X, Y); expected a machine with axis Z: `--truth fadal-pid+z` runs Z on a copy")
    assert not out.exists()


def test_a_program_that_only_names_z_runs_on_a_two_axis_truth(tmp_path, capsys):
    prog = write(tmp_path, NAMED_Z)
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", "fadal-pid", *model_files(tmp_path, models_of()), "--toolpath", str(prog),
                 "--truth-runs", "1", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert set(d["models"]["identified"]) == {"x", "y"}
    assert d["true"]["runs"] == 1
    assert set(d["true"]["tracking"]) == {"x", "y"}  # Z, only named, is no column of the setpoints
    assert d["samples"] == 2379  # the feed moves at F10 in/min and F20 in/min, then the settle time
    # the reduced models of the true machine's axes (its non-idealities off) predict its contour within 10 %
    assert abs(d["prediction_error_pct"]["max"]) < 10.0
    assert "contour error" in capsys.readouterr().out


def test_a_program_that_only_dwells_is_refused_naming_the_file(tmp_path, capsys):
    prog = write(tmp_path, "G21 G90\nM3 S1000\nG4 P2\nM5\nM2\n")
    assert main(["compare", "--truth", "fadal-pid", *model_files(tmp_path, models_of()), "--toolpath",
                 str(prog)]) == 2
    assert capsys.readouterr().err == (f"error: {prog}: the program moves no axis (it only dwells or switches): there "
                                       "is no contour to compare; expected a program with a feed move (G1, G2, G3, L, "
                                       "C)\n")


def test_a_rotary_axis_of_the_machine_file_is_read_and_kept_out_of_the_contour(tmp_path, capsys):
    prog = write(tmp_path, ROTARY)
    models = models_of()
    models["a"] = dataclasses.replace(models["x"], axis="a")
    out, rep = tmp_path / "c.json", tmp_path / "rep"
    assert main(["compare", "--truth", str(machine_with_a(tmp_path)), *model_files(tmp_path, models), "--toolpath",
                 str(prog), "--truth-runs", "1", "--json", str(out), "--report", str(rep)]) == 0
    d = json.loads(out.read_text())
    assert set(d["true"]["tracking"]) == {"x", "y", "a"}
    assert ("rotary axis a does not enter the contour error (measured on X, Y, Z in mm); its tracking error is in "
            "mdeg") in d["notes"]
    html = (rep / "index.html").read_text()
    assert "mdeg" in html  # the tracking table's unit column: mdeg for a, um for x and y
    # without the axis in the machine the reader refuses the word, naming how to add it
    assert main(["compare", "--truth", "fadal-pid", *model_files(tmp_path, models_of()), "--toolpath",
                 str(prog)]) == 2
    err = capsys.readouterr().err
    assert f"{prog}:4:4: axis word 'A' is not supported" in err
    assert "add an [axes.a] section" in err


def test_a_model_of_a_coarse_record_is_named_with_its_nyquist_frequency():
    truth = load_machine("fadal-pid")
    models = models_of(x={"sample_time": 0.1})
    rep = compare(truth, models, "circle", truth_runs=1)
    assert ("the model of x was identified from a record sampled every 0.1 s (content up to its Nyquist frequency "
            "5 Hz); it runs here at the toolpath's 0.001 s: its response above 5 Hz is extrapolated, not identified"
            ) in rep.notes
    assert not any("model of y" in n for n in rep.notes)  # y's record was sampled at the toolpath's step


def test_models_whose_dead_times_differ_are_named_with_the_path_they_bend():
    truth = load_machine("fadal-pid")
    rep = compare(truth, models_of(y={"delay_s": 0.05}), "circle", truth_runs=1)
    (note,) = [n for n in rep.notes if "dead times differ" in n]
    # the top speed of the feed moves the metrics cover (the rapid from the origin is left out)
    speed = np.linalg.norm(np.diff(rep.setpoints.position, axis=0), axis=1)[rep.true.include[1:]] / 0.001
    top = float(np.max(speed))
    assert note.startswith("the models' reference dead times differ (x 0 s, y 0.05 s): the axes' commands are "
                           "shifted against each other by up to 0.05 s, which alone bends the path by up to ")
    assert re.search(r"up to ([0-9.]+) mm at the toolpath's top speed ([0-9.]+) mm/s$", note).groups() == (
        f"{top * 0.05:.4g}", f"{top:.4g}")
    # and it does: 0.05 s at the circle's 200 mm/s puts the predicted contour millimetres off
    assert rep.to_dict()["predicted"]["contour_max_um"] > 1000.0
    same = compare(truth, models_of(x={"delay_s": 0.05}, y={"delay_s": 0.05}), "circle", truth_runs=1)
    assert not any("dead times differ" in n for n in same.notes)


def test_a_capture_of_one_axis_is_refused_as_truth_saying_why():
    t = np.arange(200) * 0.001
    ref = np.minimum(t, 0.1)[:, None] * 100.0
    cap = Capture(t=t, axes=("y",), reference=ref, measured=ref * 0.99, source="scope.sco")
    with pytest.raises(InputError) as exc:
        compare(cap, models_of(), None)
    assert str(exc.value).startswith("scope.sco: the capture's commanded positions move 1 linear axis (y of y): a "
                                     "contour error needs two or more axes recorded on one time base; expected")


def test_feature_points_are_those_of_path_features_computed_once():
    truth = Machine.from_axes(models_of(), sample_time=0.001, limits=load_machine("fadal-pid").limits, name="exact")
    rep = compare(truth, models_of(), "diamond")
    path = rep.setpoints.path
    pts = feature_points(path)
    assert pts is feature_points(path)
    np.testing.assert_array_equal(pts["corners"][0], np.asarray(path_features(path)["corners"], dtype=float))
    # the diamond's vertices 20 mm from the centre on the axes: each corner point is one of them (or the start)
    corners = {tuple(round(v, 6) for v in p[:2]) for p in pts["corners"][1]}
    assert corners <= {(20.0, 0.0), (0.0, 20.0), (-20.0, 0.0), (0.0, -20.0), (0.0, 0.0)}
    assert rep.to_dict()["prediction_error_pct"] == {"max": 0.0, "rms": 0.0}


def test_a_single_axis_truth_is_copied_for_the_axes_the_program_moves_not_those_it_names():
    """emps (one axis) on a program naming Z at Z0: x and y are copies of its axis, Z needs no model."""
    models = {a: dataclasses.replace(models_of()["x"], axis=a) for a in ("x", "y")}
    program = interpolators_program(NAMED_Z)
    rep = compare("emps", models, program, truth_runs=1)
    assert rep.setpoints.axes == ("x", "y")
    assert "machine 'emps' has one axis (x); each of x, y is a copy of it" in rep.notes
    # the feed moves' top speed is F20 in/min = 8.467 mm/s; no dead time differs, so no note bends the path
    assert not any("dead times differ" in n for n in rep.notes)


def interpolators_program(text: str):
    import interpolators

    return interpolators.parse_program(text, source="named_z.nc")


def test_the_built_in_toolpaths_dwell_settle_s_after_the_rapid_not_a_thousand_times_more():
    """G4 P is seconds in LinuxCNC G-code (the reader's default): the circle's dwell is 0.2 s, not P200 = 200 s."""
    from vcnc.contour_compare import SETTLE_S

    rep = compare("fadal-pid", models_of(), "circle", truth_runs=1)
    sp = rep.setpoints
    # rapid to (20, 0), dwell 0.2 s, the circle (125.7 mm at up to 200 mm/s), the final settle 0.2 s: about 1.5 s
    assert 1.0 < sp.t[-1] < 2.5
    assert len(sp) == 1470
    # the steps at rest: the first stretch is the dwell after the rapid, SETTLE_S at Ts = 1 ms
    rest = np.flatnonzero(np.all(np.diff(sp.position, axis=0) == 0, axis=1))
    first = rest[: np.flatnonzero(np.diff(rest) > 1)[0] + 1]
    assert len(first) == round(SETTLE_S / 0.001) == 200


def test_the_report_of_a_dense_program_colours_the_path_by_the_contour_error(tmp_path):
    """A CAM raster of over vcnc.contour.DENSE_SEGMENTS moves: the magnified errors would cover its passes, so
    contour.png colours the path by the true and the predicted contour error (as vcnc simulate's path.png)."""
    from vcnc.contour import DENSE_SEGMENTS

    moves = "\n".join(f"G1 X{(i % 2) * 5} Y{i * 0.05:.2f}" for i in range(1, DENSE_SEGMENTS + 2))
    prog = write(tmp_path, f"G21 G90 G17\nG0 X0 Y0\nF3000\n{moves}\nM2\n", "raster.nc")
    rep = compare("fadal-pid", models_of(), str(prog), truth_runs=1)
    assert len(rep.true.path) > DENSE_SEGMENTS
    rep.report().write(tmp_path / "rep")
    html = (tmp_path / "rep" / "index.html").read_text()
    assert ("samples coloured by the contour error: the true machine and the identified models on one colour scale "
            f"(a path of {len(rep.true.path)} segments") in html
    assert (tmp_path / "rep" / "contour.png").stat().st_size > 0
