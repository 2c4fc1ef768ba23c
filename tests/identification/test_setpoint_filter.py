"""The setpoint filter term of the reduced model (identification.setpoint_filter) and its model file."""

from __future__ import annotations

import json

import numpy as np
import pytest

from identification import ReducedAxisModel, identify, load_model
from identification.augmented import augment
from identification.effects import Resonance
from identification.filter_signature import shows_filter, signature
from identification.setpoint_filter import filter_reference
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture
from vcnc.capture import Capture
from vcnc.errors import ModelFileError


def test_a_ramp_comes_out_delayed_by_half_the_filter():
    """The mean of a ramp over L before t is the ramp at t - L/2 (exact for a reference linear
    between samples, whole and fractional lengths)."""
    ramp = 5.0 + 0.01 * np.arange(200.0)
    for samples in (16.0, 7.3, 0.4):
        got = filter_reference(ramp, samples)
        np.testing.assert_allclose(got[20:], 5.0 + 0.01 * (np.arange(20, 200) - samples / 2), rtol=0, atol=1e-12)


def test_a_reference_at_rest_stays_exactly_where_it_is():
    xr = np.full(50, 123.456)
    assert np.array_equal(filter_reference(xr, 16.3), xr)
    assert np.array_equal(filter_reference(xr, 0.0), xr)


def test_the_filter_length_is_continuous():
    """A step through the filter: lengths a hair apart give responses a hair apart (the fractional
    part is the interval before the whole ones, not a jump to the next sample)."""
    step = np.r_[np.zeros(10), np.ones(40)]
    a, b = filter_reference(step, 6.0), filter_reference(step, 6.0 + 1e-9)
    assert np.max(np.abs(a - b)) < 1e-8


def test_a_model_with_a_filter_is_written_as_format_3_and_read_back(tmp_path):
    model = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=0.001, delay_s=0.004, setpoint_filter_s=0.0163)
    path = tmp_path / "model.json"
    model.to_json(path)
    data = json.loads(path.read_text())
    assert data["format"] == "vcnc.axis-model/3"
    assert data["setpoint_filter_s"] == 0.0163 and data["delay_s"] == 0.004
    back = load_model(path)
    assert back.setpoint_filter_s == 0.0163 and back.delay_s == 0.004
    ref = np.r_[np.zeros(20), np.linspace(0.0, 10.0, 300), np.full(200, 10.0)]
    assert np.array_equal(back.simulate(ref), model.simulate(ref))


@pytest.mark.parametrize(("delay_s", "fmt"), [(0.0, "vcnc.axis-model/1"), (0.1, "vcnc.axis-model/2")])
def test_a_model_without_a_filter_keeps_its_old_format(tmp_path, delay_s, fmt):
    """Files without a filter are written (and read) as before, so that older readers still read them."""
    path = tmp_path / "model.json"
    ReducedAxisModel(parameters=FADAL_PID_X, sample_time=0.001, delay_s=delay_s).to_json(path)
    data = json.loads(path.read_text())
    assert data["format"] == fmt and "setpoint_filter_s" not in data
    assert load_model(path).setpoint_filter_s == 0.0


def test_a_format_3_file_without_its_filter_is_named(tmp_path):
    path = tmp_path / "model.json"
    data = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=0.001, setpoint_filter_s=0.01).to_dict()
    del data["setpoint_filter_s"]
    path.write_text(json.dumps(data))
    with pytest.raises(ModelFileError, match="setpoint_filter_s"):
        load_model(path)
    data["setpoint_filter_s"] = -0.01
    path.write_text(json.dumps(data))
    with pytest.raises(ModelFileError, match="setpoint_filter_s"):
        load_model(path)


def test_a_contour_comparison_names_the_models_filter():
    """vcnc compare describes each model; a filtered one says its filter (it is simulated with it)."""
    from vcnc.contour_compare import compare

    model = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=0.001, axis="x", setpoint_filter_s=0.016)
    report = compare("fadal-pid", {"x": model, "y": model}, "circle", truth_runs=1).to_dict()
    described = json.dumps(report["models"])
    assert "setpoint filter 16 ms" in described


# ------------------------------------------------------------------ the filter's signature (traceid5)
def _random_moves(sample_time: float) -> np.ndarray:
    return random_moves_reference(moves=40, span=10.0, feed=200.0, acceleration=2000.0, sample_time=sample_time,
                                  dwell=0.05, seed=3)


def test_a_filter_in_the_record_shows_its_gain_and_its_zero():
    """The exact model fed through a 12 ms moving average, with 0.2 um noise: the record's response
    over the loop's is the average's 2/pi at 1/(2L) and near its zero at 1/L (Smith, ch. 15; not 0:
    the response to the friction at reversals and dwells is not driven linearly by the reference)."""
    T = 1e-3
    xr = _random_moves(T)
    cap = synthetic_capture(FADAL_PID_X, filter_reference(xr, 12.0), sample_time=T, noise=0.2e-3, seed=2)
    sig = signature(xr, cap.measured[:, 0], T, 0.012, FADAL_PID_X)
    assert abs(sig["half"] - 1.0) < 0.02 and sig["zero"] < 0.3
    assert shows_filter(sig)
    # without the filter the same loop passes its own response there: no signature
    plain = synthetic_capture(FADAL_PID_X, xr, sample_time=T, noise=0.2e-3, seed=2)
    sig = signature(xr, plain.measured[:, 0], T, 0.012, FADAL_PID_X)
    assert abs(sig["half"] - np.pi / 2) < 0.1 and sig["zero"] > 0.8
    assert not shows_filter(sig)


def test_a_filter_imitating_a_mode_is_not_kept():
    """A 150 Hz mode (damping 0.1) in the loop logged at 2 ms, 0.2 um noise and a 0.1 um encoder
    (as in test_diagnosis_folds): the search imitates it with a 9.7 ms filter that predicts 1.57x
    better, near the 1.6x a filter must gain (ballscrew-ppc's real 16 ms one gains 1.66x); the
    record's response is not the moving average's (0.86 of 2/pi at 1/(2L), 0.17 at 1/L)."""
    T = 2e-3
    xr = _random_moves(T)
    truth = augment(ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T),
                    [Resonance(frequency=150.0, damping=0.1, table_fraction=0.5)], viscous_rate=4.0)
    x = truth.simulate(xr)
    x = np.round((x + np.random.default_rng(1).normal(0.0, 0.2e-3, x.size)) / 1e-4) * 1e-4
    cap = Capture(t=np.arange(x.size) * T, axes=("x",), reference=xr[:, None], measured=x[:, None], meta={})
    model = identify(cap, axis="x", diagnose=False)
    rec = model.fit["setpoint_filter"]
    assert model.setpoint_filter_s == 0.0 and rec["searched_s"] > 4 * T
    assert not shows_filter(rec["signature"])
