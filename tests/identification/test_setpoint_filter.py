"""The setpoint filter term of the reduced model (identification.setpoint_filter) and its model file."""

from __future__ import annotations

import json

import numpy as np
import pytest

from identification import ReducedAxisModel, load_model
from identification.setpoint_filter import filter_reference
from identification.synthetic import FADAL_PID_X
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
