"""``vcnc identify TRACE --check MODEL.json``: a model predicts another record of the same machine, fitting nothing."""

from __future__ import annotations

import dataclasses
import json
import re

import numpy as np
import pytest

from identification import load_model
from identification.dead_time import delay_reference
from identification.reduced_model import ReducedAxisModel
from identification.synthetic import random_moves_reference, synthetic_capture
from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.commands.identify_check import check_record
from vcnc.core.capture import Capture

TS = 0.001
# hand-written: a 3rd-order closed loop (poles near 50 Hz, 0.7 damping, and 70 Hz) with feedforward zeros and
# asymmetric Coulomb friction, as tests/vcnc/test_fmu.py takes it (the range of thesis Tables 3.3-3.5)
PARAMETERS = {"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0, "d1": -70.0}


def record(path, *, seed: int, delay_s: float = 0.0, axis: str = "x", sample_time: float = TS,
           noise: float = 0.0, dwell: float = 0.0) -> str:
    """A record of the machine of PARAMETERS: random moves, the loop receiving the recorded reference ``delay_s``
    later (the recorded reference leads), the measured position simulated."""
    ref = random_moves_reference(moves=25, span=10.0, seed=seed, sample_time=sample_time, dwell=dwell)
    loop = delay_reference(ref, delay_s / sample_time)
    cap = synthetic_capture(PARAMETERS, loop, sample_time=sample_time, noise=noise, seed=seed, axis=axis)
    dataclasses.replace(cap, reference=ref[:, None]).to_csv(path)
    return str(path)


def table_row(out: str, label: str) -> list[float]:
    """The numbers of the summary table's row ``label`` (NaN for '-')."""
    line = next(x for x in out.splitlines() if x.startswith(label) and re.search(r"\d", x[len(label):]))
    return [float("nan") if c == "-" else float(c) for c in line[36:].split()]


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    """A model identified (no diagnosis) on one noisy record, and another record of the same machine."""
    d = tmp_path_factory.mktemp("check")
    first = record(d / "first.csv", seed=1, noise=2e-4)
    other = record(d / "other.csv", seed=7, noise=2e-4)
    model = str(d / "model.json")
    assert main(["identify", first, "--no-diagnose", "--json", model]) == 0
    return model, other


def test_the_check_prints_what_the_python_api_predicts(identified, capsys):
    model_path, other = identified
    capsys.readouterr()
    assert main(["identify", other, "--check", model_path]) == 0
    out = capsys.readouterr().out
    model, cap = load_model(model_path), read_capture(other)
    # the lead's hand check (/tmp/s40/eha/xval.py): the model simulated on the record's reference
    e = (model.simulate_reference(cap.reference[:, 0], cap.sample_time) - cap.measured[:, 0]) * 1e3
    rms, worst = float(np.sqrt(np.mean(e * e))), float(np.abs(e).max())
    row = table_row(out, "this record")
    assert row[0] == pytest.approx(rms, rel=1e-3) and row[1] == pytest.approx(worst, rel=1e-3)
    check = check_record(cap, model, "x")
    assert (check.first, check.stop) == (0, len(cap))
    np.testing.assert_allclose(check.predicted, model.simulate_reference(cap.reference[:, 0], cap.sample_time),
                               rtol=0, atol=1e-12)
    # the model's own figures from its file beside them
    own = table_row(out, "its own record")
    assert own[0] == pytest.approx(model.fit["rms_um"], rel=1e-3)
    assert "fitted nothing" in out


def test_the_models_dead_time_is_applied(tmp_path, capsys):
    # the loop receives the recorded reference 25 ms later: the model with that dead time predicts the record
    # exactly (the CSV's rounding aside), the same loop without it does not
    rec = record(tmp_path / "lead.csv", seed=3, delay_s=0.025)
    with_delay, without = str(tmp_path / "with.json"), str(tmp_path / "without.json")
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, delay_s=0.025).to_json(with_delay)
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).to_json(without)
    assert main(["identify", rec, "--check", with_delay]) == 0
    out = capsys.readouterr().out
    assert "reference dead time 0.025 s (used as it is)" in out
    assert table_row(out, "this record")[0] < 0.01
    assert main(["identify", rec, "--check", without]) == 0
    assert table_row(capsys.readouterr().out, "this record")[0] > 10.0


def test_a_record_at_another_period_is_simulated_at_its_own(tmp_path, capsys):
    # the same machine logged every 2 ms (the 1 ms loop's samples, every other one kept), its model identified at
    # 1 ms: simulated at the record's 2 ms (on 1 ms sub-steps, as identify predicts a record slower than 1 ms) the
    # continuous-time model predicts it within the spline's error between samples; the note names both periods
    fine = read_capture(record(tmp_path / "fine.csv", seed=4))
    rec = str(tmp_path / "slow.csv")
    Capture(t=fine.t[::2], axes=fine.axes, reference=fine.reference[::2], measured=fine.measured[::2]).to_csv(rec)
    model = str(tmp_path / "model.json")
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).to_json(model)
    assert main(["identify", rec, "--check", model]) == 0
    out = capsys.readouterr().out
    assert "sampled every 0.002 s and the model was identified at 0.001 s" in out
    rms = table_row(out, "this record")[0]
    following = float(re.search(r"commanded position itself rms ([\d.e+-]+)", out).group(1))
    assert rms < 0.1 and rms < 1e-3 * following, (rms, following)


def test_a_record_of_another_axis_is_refused_naming_both(tmp_path, capsys):
    rec = record(tmp_path / "y.csv", seed=5, axis="y")
    model = str(tmp_path / "model.json")
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="x").to_json(model)
    assert main(["identify", rec, "--check", model]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and rec in err and "holds axis y" in err and "of axis x" in err
    assert "--axis-names x" in err
    rec_x = record(tmp_path / "x.csv", seed=5)
    assert main(["identify", rec_x, "--check", model, "--axis", "y"]) == 2
    err = capsys.readouterr().err
    assert "--axis y" in err and "of axis x" in err


@pytest.mark.parametrize(("option", "named"), [(["--delay", "0.01"], "dead time is used as it is"),
                                               (["--json", "out.json"], "--json"), (["--method", "ga"], "--method")])
def test_fit_options_are_refused_with_check(tmp_path, capsys, option, named):
    rec = record(tmp_path / "r.csv", seed=6)
    model = str(tmp_path / "model.json")
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).to_json(model)
    assert main(["identify", rec, "--check", model, *option]) == 2
    assert named in capsys.readouterr().err


def test_a_capture_given_as_the_model_is_an_error_naming_it(tmp_path, capsys):
    rec = record(tmp_path / "r.csv", seed=6)
    assert main(["identify", rec, "--check", rec]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and f"{rec}:1:1" in err


def test_the_report_holds_the_check(tmp_path, capsys):
    rec = record(tmp_path / "r.csv", seed=8)
    model = str(tmp_path / "model.json")
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).to_json(model)
    assert main(["identify", rec, "--check", model, "--report", str(tmp_path / "rep")]) == 0
    summary = json.loads((tmp_path / "rep" / "summary.json").read_text())["check"]
    assert summary["axis"] == "x" and summary["rms_um"] < 0.01 and (tmp_path / "rep" / "tracking.png").is_file()


def test_a_record_cut_in_motion_is_predicted_from_its_first_rest(tmp_path, capsys):
    # identify's start rule (identification.segments.settled_start): a record triggered during a move is predicted
    # from where the axis first rests, and the note says how many samples were left out
    whole = read_capture(record(tmp_path / "whole.csv", seed=9, dwell=0.3))
    moving = np.flatnonzero(np.abs(np.diff(whole.reference[:, 0])) > 0)
    cut = int(moving[0]) + 30  # 30 ms into the first move, accelerating
    rec = str(tmp_path / "cut.csv")
    whole.slice(cut, len(whole)).to_csv(rec)
    model = str(tmp_path / "model.json")
    ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).to_json(model)
    assert main(["identify", rec, "--check", model]) == 0
    out = capsys.readouterr().out
    first = int(re.search(r"samples not predicted: the first (\d+) \(the record starts with the axis moving", out)[1])
    assert first > 0
    cap = read_capture(rec)
    e = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).simulate(cap.reference[:, 0]) - cap.measured[:, 0]
    from_first = float(np.sqrt(np.mean(e * e))) * 1e3  # from rest at the first sample, the axis moving there
    assert table_row(out, "this record")[0] < 0.1 * from_first
    # without a rest between the moves there is no start but the first sample: said, the transient kept
    rec = str(tmp_path / "no_rest.csv")
    read_capture(record(tmp_path / "moves.csv", seed=9)).slice(cut, len(whole)).to_csv(rec)
    assert main(["identify", rec, "--check", model]) == 0
    out = capsys.readouterr().out
    assert "does not rest early enough" in out and "samples not predicted" not in out
