"""Contour prediction: true machine vs identified models (issue 6).

Thesis cases (seed 000, W. Wong, "Rapid Identification of Virtual CNC Drives"): circle of 40 mm
diameter and a diamond of the same extent at 200 mm/s with 2000 mm/s^2 trapezoidal transients on
the Fadal P-PI, PID and SMC axes (Sec. 3.4.1, Figs. 3.6, 3.7, 3.9, 3.11), and the circle at
100 mm/s with 600 mm/s^2 on the ball-screw bench under PPC+KF and PPC+KF+ZPETC (Sec. 3.4.2, Fig.
3.14). The models are identified from a Table 3.2-style random-move test run on the true machine
(60 moves within +/-10 mm at 200 mm/s; the table has 200, 60 keep the test fast and give the same
numbers to within 0.5 %: see benchmarks/contour.py). Target: predicted max contour error within 5 %
of the true machine's (the VCNC literature reports 10 %).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import interpolators
import toolpaths
from identification import ReducedAxisModel, identify
from identification.diagnosis import diagnose
from vcnc.capture import Capture
from vcnc.cli import main
from vcnc.contour_compare import compare
from vcnc.engine.machine import Machine, load_machine
from vcnc.errors import InputError

CASES = {  # machine: (toolpaths, feed [mm/s], acceleration [mm/s^2])
    "fadal-pid": (("circle", "diamond"), None, None),
    "fadal-ppi": (("circle", "diamond"), None, None),
    "fadal-smc": (("circle", "diamond"), None, None),
    "ballscrew-ppc": (("circle",), 100.0, 600.0),
    "ballscrew-zpetc": (("circle",), 100.0, 600.0),
}


def _identify(name: str) -> tuple[dict, object]:
    m = load_machine(name)
    prog = interpolators.parse_program(toolpaths.random_moves(60, 10.0, 12000, seed=1, axes=m.axes))
    cap = m.simulate(interpolators.interpolate(prog, limits=m.limits, sample_time=m.sample_time), seed=1)
    return {a: identify(cap, axis=a, diagnose=False) for a in m.axes}, cap


def _one_or_all(models: dict):
    return next(iter(models.values())) if len(models) == 1 else models


@pytest.fixture(scope="session")
def thesis_results() -> dict:
    """Per (machine, toolpath): the ContourReport of the identified models and, when the residual
    diagnosis added effects, of the augmented ones (the report then holds both)."""
    out = {}
    for name, (paths, feed, acc) in CASES.items():
        models, cap = _identify(name)
        augmented = {a: diagnose(cap, models[a], axis=a) for a in models}
        out["models", name] = models
        for tp in paths:
            out[name, tp] = compare(name, _one_or_all(models), tp, feed=feed, acceleration=acc)
            out[name, tp, "augmented"] = compare(name, _one_or_all(augmented), tp, feed=feed, acceleration=acc)
    return out


THESIS_CASES = [(n, tp) for n, (tps, _, _) in CASES.items() for tp in tps]


@pytest.mark.slow  # the thesis cases: identification and diagnosis of three machines (minutes)
@pytest.mark.parametrize(("name", "toolpath"), THESIS_CASES)
def test_thesis_case_predicted_max_contour_error(thesis_results, name, toolpath):
    """Issue 6 target: predicted max contour error within 5 % of the true machine's. The truths
    have measurement noise in their loops, so the reference is the mean of ten noise realisations
    (vcnc.contour_compare module notes); against single realisations the fadal-smc diamond ranges
    over +3.0..+5.9 % (its true maximum over 8.81-9.06 um)."""
    d = thesis_results[name, toolpath].to_dict()
    assert d["true"]["contour_max_um"] > 1.0
    m = load_machine(name)
    noisy = any(m.axis(a).noise is not None for a in m.axes)  # the ball-screw bench: encoder steps only
    assert d["true"]["runs"] == (10 if noisy else 1)
    assert abs(d["prediction_error_pct"]["max"]) <= 5.0, d["prediction_error_pct"]
    # the models' record (200 mm/s random moves) covers the toolpath's speeds: no extrapolation noted
    assert not any("beyond the operating range" in n for n in d["notes"])


def test_a_model_of_a_slow_record_is_noted_beyond_its_range():
    """A record at 10 mm/s (F600, as CAM programs cut) fixes the model where it ran; the 200 mm/s diamond is
    beyond that range, and the comparison says so per axis (identification.excitation)."""
    m = load_machine("fadal-pid")
    prog = interpolators.parse_program(toolpaths.random_moves(20, 5.0, 600, seed=2, axes=m.axes))
    cap = m.simulate(interpolators.interpolate(prog, limits=m.limits, sample_time=m.sample_time), seed=1)
    models = {a: identify(cap, axis=a, diagnose=False) for a in m.axes}
    assert all(0.5 < mod.fit["excitation"]["speed_mm_s"] <= 10.0 + 1e-9 for mod in models.values())
    notes = [n for n in compare("fadal-pid", models, "diamond", truth_runs=1).notes if "beyond the operating" in n]
    assert [n.split()[3] for n in notes] == ["x", "y"]
    assert all("at speed 14" in n for n in notes)  # 200 mm/s along the diamond's 45 deg sides: 141 mm/s per axis
    slow = compare("fadal-pid", models, "diamond", feed=5.0, truth_runs=1).notes
    assert not any("beyond the operating" in n for n in slow)


@pytest.mark.slow  # the thesis cases: identification and diagnosis of three machines (minutes)
@pytest.mark.parametrize(("name", "toolpath"), THESIS_CASES)
def test_thesis_case_after_augmentation(thesis_results, name, toolpath):
    """Before and after the residual diagnosis: both within 5 %; when the diagnosis finds nothing
    (these clean machines) the model and its prediction are unchanged."""
    before = thesis_results[name, toolpath].to_dict()
    rep = thesis_results[name, toolpath, "augmented"]
    after = rep.to_dict()
    assert abs(after["prediction_error_pct"]["max"]) <= 5.0, after["prediction_error_pct"]
    if rep.main_label == "augmented":
        assert abs(after["before_augmentation"]["prediction_error_pct"]["max"]) <= 5.0
    else:  # nothing significant found: the model is unchanged, and so is the prediction
        assert after["prediction_error_pct"] == before["prediction_error_pct"]


@pytest.mark.slow  # the thesis cases: identification and diagnosis of three machines (minutes)
def test_noisy_truth_is_judged_on_the_mean_of_its_noise_realisations(thesis_results):
    """The mean over the runs is the reference; each run's numbers and the error against each
    single run are reported beside it; truth_runs=1 is the single seeded run."""
    rep = thesis_results["fadal-smc", "diamond"]
    d = rep.to_dict()
    assert rep.runs == 10 and d["true"]["seeds"] == list(range(10))
    maxima = [r["max_um"] for r in rep.true_runs]
    assert len(set(maxima)) > 1  # the noise changes the true contour error
    assert d["true"]["contour_max_um"] == pytest.approx(float(np.mean(maxima)))
    assert d["true"]["spread"]["contour_max_um"] == [min(maxima), max(maxima)]
    lo, hi = d["prediction_error_pct_range"]["max"]
    assert lo <= d["prediction_error_pct"]["max"] <= hi
    assert rep.true.metrics()["max_um"] == maxima[0]  # histories and plots: the first run
    assert "noise realisations" in " ".join(d["notes"])
    single = compare("fadal-smc", thesis_results["models", "fadal-smc"], "diamond", truth_runs=1).to_dict()
    assert "spread" not in single["true"] and single["true"]["runs"] == 1
    assert single["true"]["contour_max_um"] == maxima[0]


def test_noise_free_truth_runs_once():
    _, models = _exact_machine()
    quiet = load_machine("fadal-pid").with_axis_options("x", noise=None).with_axis_options("y", noise=None)
    rep = compare(quiet, models, "circle", feed=100.0)
    assert rep.runs == 1 and rep.true_runs == [] and "spread" not in rep.to_dict()["true"]
    with pytest.raises(InputError, match="truth_runs"):
        compare("fadal-pid", models, "circle", truth_runs=0)


def test_augmented_model_is_compared_before_and_after():
    truth, models = _exact_machine()

    class Augmented:  # an augmented model: effects it simulates, and its reduced part
        effects = [{"name": "drift", "parameters": {"offset_mm": 0.005}}]

        def __init__(self, base):
            self.base_model = base

        def reduced(self):
            return self.base_model

        def simulate_reference(self, reference, sample_time):
            return self.base_model.simulate_reference(reference, sample_time) + 0.005

    rep = compare(truth, {a: Augmented(m) for a, m in models.items()}, "circle", feed=100.0)
    d = rep.to_dict()
    assert set(rep.predicted) == {"identified", "augmented"}
    assert d["before_augmentation"]["prediction_error_pct"] == {"max": 0.0, "rms": 0.0}
    assert d["prediction_error_pct"]["max"] != 0.0


@pytest.mark.slow  # the thesis cases: identification and diagnosis of three machines (minutes)
def test_truth_is_where_the_axes_are_and_the_sensor_reading_is_beside_it(thesis_results, tmp_path):
    """A simulated truth is judged on the true position of its measured points; the sensor's
    reading (noise, encoder steps) is reported beside it, with the prediction error against it."""
    rep = thesis_results["fadal-smc", "circle"]
    d = rep.to_dict()
    sensor = d["true_as_measured"]
    assert sensor["contour_max_um"] != d["true"]["contour_max_um"]
    assert abs(sensor["contour_max_um"] - d["true"]["contour_max_um"]) < 1.0  # 0.1 um noise, 0.25 um steps
    assert set(sensor["prediction_error_pct"]) == {"max", "rms"}
    rep.report().write(tmp_path / "r")
    assert "true, as its sensors read it" in (tmp_path / "r" / "index.html").read_text()


@pytest.mark.slow  # the thesis cases: identification and diagnosis of three machines (minutes)
def test_single_axis_bench_drives_both_axes(thesis_results):
    rep = thesis_results["ballscrew-ppc", "circle"]
    assert rep.setpoints.axes == ("x", "y")
    assert any("copy" in n for n in rep.notes)


# ------------------------------------------------------------------ plumbing with exact models
def _exact_machine(name: str = "fadal-pid"):
    m = load_machine(name)
    models = {a: ReducedAxisModel(parameters=m.axis(a).reduced_parameters(), sample_time=m.sample_time, axis=a)
              for a in m.axes}
    return Machine.from_axes(models, sample_time=m.sample_time, limits=m.limits, name="exact"), models


def test_identical_models_predict_exactly():
    truth, models = _exact_machine()
    rep = compare(truth, models, "diamond")
    d = rep.to_dict()
    assert set(d) >= {"toolpath", "true", "predicted", "prediction_error_pct"}
    assert set(d["true"]) >= {"contour_max_um", "contour_rms_um"}
    assert d["prediction_error_pct"] == {"max": 0.0, "rms": 0.0}
    np.testing.assert_array_equal(rep.true.error, rep.predicted["identified"].error)
    assert d["true"]["corner_max_um"] == pytest.approx(d["true"]["contour_max_um"])


def test_one_model_for_all_axes_and_from_files(tmp_path):
    truth, models = _exact_machine()
    models["x"].to_json(tmp_path / "mx.json")
    r1 = compare(truth, str(tmp_path / "mx.json"), "circle", feed=100.0)
    r2 = compare(truth, {"x": models["x"], "y": models["x"]}, "circle", feed=100.0)
    np.testing.assert_array_equal(r1.predicted["identified"].error, r2.predicted["identified"].error)
    # issue #21: a model standing in for an axis without one is said, in the log and the report
    assert "axis y has none of its own" in r1.models["identified"]["y"]
    assert "none of its own" not in r1.models["identified"]["x"]
    with pytest.raises(InputError, match="no model for axis y"):
        compare(truth, {"x": models["x"]}, "circle")



def test_cli_one_model_for_two_axes_warns(tmp_path, caplog):
    truth, models = _exact_machine()
    models["x"].to_json(tmp_path / "mx.json")
    with caplog.at_level("WARNING"):
        assert main(["compare", "--truth", "fadal-pid", "--model", str(tmp_path / "mx.json"), "--toolpath",
                     "diamond", "--json", str(tmp_path / "c.json")]) == 0
    assert "the model of axis x stands in for axis y" in caplog.text

def test_program_file_and_real_capture_as_truth(tmp_path):
    truth, models = _exact_machine()
    prog = tmp_path / "part.nc"
    prog.write_text("G90 G17\nG00 X0 Y0\nG01 X10 Y0 F9000\nG02 X20 Y-10 I0 J-10\nG01 X0 Y-10\nM30\n")
    rep = compare(truth, models, str(prog))
    assert rep.toolpath == str(prog)
    sp = rep.setpoints
    cap = truth.simulate(sp)
    real = Capture(t=cap.t, axes=cap.axes, reference=cap.reference, measured=cap.measured, source="real.csv")
    rep2 = compare(real, models, str(prog))  # the program gives the path of a capture read from a file
    assert rep2.to_dict()["true"]["contour_max_um"] == pytest.approx(rep.to_dict()["true"]["contour_max_um"])
    assert "true_as_measured" not in rep2.to_dict()  # a real capture has only its measurement
    with pytest.raises(InputError, match="no path"):
        compare(real, models, None)


def test_cli_truth_may_be_a_capture_file(tmp_path, capsys):
    """`vcnc compare --truth CAPTURE --toolpath PROGRAM`: the capture is read by content (issue #17)."""
    truth, models = _exact_machine()
    prog = tmp_path / "part.nc"
    prog.write_text("G90 G17\nG00 X0 Y0\nG01 X10 Y0 F9000\nG02 X20 Y-10 I0 J-10\nG01 X0 Y-10\nM30\n")
    rep = compare(truth, models, str(prog))
    truth.simulate(rep.setpoints).to_csv(tmp_path / "real.csv")
    for a, m in models.items():
        m.to_json(tmp_path / f"m{a}.json")
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", str(tmp_path / "real.csv"), "--model", f"x={tmp_path / 'mx.json'}",
                 "--model", f"y={tmp_path / 'my.json'}", "--toolpath", str(prog), "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["truth"] == str(tmp_path / "real.csv")
    assert d["true"]["contour_max_um"] == pytest.approx(rep.to_dict()["true"]["contour_max_um"], rel=1e-6)

def test_report_and_plot(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    truth, models = _exact_machine()
    rep = compare(truth, models, "circle", feed=100.0, acceleration=1000.0)
    ax = rep.plot()
    assert len(ax) == 2
    rep.report().write(tmp_path / "r")
    assert {p.name for p in (tmp_path / "r").iterdir()} >= {"index.html", "summary.json", "contour.png"}


# ------------------------------------------------------------------ command line
def test_cli_compare(tmp_path, capsys):
    truth, models = _exact_machine()
    for a, m in models.items():
        m.to_json(tmp_path / f"m{a}.json")
    out = tmp_path / "c.json"
    rc = main(["compare", "--truth", "fadal-pid", "--model", f"x={tmp_path / 'mx.json'}", "--model",
               f"y={tmp_path / 'my.json'}", "--toolpath", "diamond", "--json", str(out)])
    assert rc == 0
    d = json.loads(out.read_text())
    assert d["toolpath"] == "diamond"
    assert set(d["prediction_error_pct"]) == {"max", "rms"}
    # the true machine has all non-idealities; the exact linear models still predict within 5 %
    assert abs(d["prediction_error_pct"]["max"]) < 5.0
    assert "contour error" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--model", "MISSING.json"], "MISSING.json"),
        (["--model", "x=MX", "--model", "MY"], "not both"),
        (["--model", "q=m.json"], "unknown axis"),
        (["--model", "MX", "--toolpath", "nope.nc"], "nope.nc"),
        (["--model", "MX", "--toolpath", "BAD"], "BAD.nc:2"),
        (["--model", "MX", "--truth", "no-such-machine"], "no-such-machine"),
        (["--model", "MX", "--truth-runs", "0"], "truth_runs"),
    ],
)
def test_cli_bad_input_exits_2_without_output(tmp_path, capsys, args, message):
    _, models = _exact_machine()
    models["x"].to_json(tmp_path / "mx.json")
    (tmp_path / "BAD.nc").write_text("G90\nG01 X10 Q5 F100\nM30\n")
    repl = {"MX": str(tmp_path / "mx.json"), "MY": str(tmp_path / "mx.json"), "BAD": str(tmp_path / "BAD.nc")}
    args = [repl.get(a, a.replace("MX", repl["MX"])) for a in args]
    argv = ["compare", "--truth", "fadal-pid", *args, "--json", str(tmp_path / "out.json"), "--report",
            str(tmp_path / "rep")]
    if args.count("--truth"):
        argv = ["compare", *args, "--json", str(tmp_path / "out.json"), "--report", str(tmp_path / "rep")]
    rc = main(argv)
    err = capsys.readouterr().err
    assert rc == 2
    assert err.startswith("error:") and message in err
    assert not (tmp_path / "out.json").exists() and not (tmp_path / "rep").exists()
