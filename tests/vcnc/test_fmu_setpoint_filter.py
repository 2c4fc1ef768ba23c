"""FMU export of the setpoint filter ``setpoint_filter_s`` (identification.setpoint_filter), with real binaries.

The FMU's moving average of the delayed reference must give ``model.simulate(x_ref)`` bit for bit:
the order of operations of identification.kernels.moving_average, in C.
"""

from __future__ import annotations

import dataclasses
import json
import shutil

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from identification import ReducedAxisModel, load_model
from vcnc.errors import ExportError
from vcnc.fmu import FmuAxis, export_fmu, export_spec
from vcnc.fmu._oracle import check_reference

pytestmark = pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("cc") is None,
                                reason="building FMUs needs cmake and a C compiler")

TS = 0.001
# the closed loop of tests/vcnc/test_fmu.py (poles near 50 Hz and 70 Hz, asymmetric Coulomb friction)
PARAMETERS = {"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0, "d1": -70.0}
FILTER_S = 0.0163  # a 16 ms jerk filter as fitted: 16.3 samples, whole and fractional part


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("delay_s", [0.0, 0.0125])
def test_fmu_with_setpoint_filter_equals_model_bit_for_bit(version, delay_s, tmp_path):
    model = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="x", delay_s=delay_s,
                             setpoint_filter_s=FILTER_S)
    path = tmp_path / "model.json"
    model.to_json(path)
    export_fmu(path, tmp_path / "f.fmu", fmi_version=version)
    assert validate_fmu(str(tmp_path / "f.fmu")) == []
    names = {v.name: v for v in read_model_description(str(tmp_path / "f.fmu")).modelVariables}
    assert float(names["setpoint_filter_s"].start) == FILTER_S
    ref = check_reference(4000, TS, seed=5, start=3.0)
    expected = model.simulate(ref)
    with FmuAxis(tmp_path / "f.fmu") as axis:
        got = axis.simulate_reference(ref, TS)
    np.testing.assert_array_equal(got, expected)
    # a real test: the filter changes the prediction by far more than rounding
    unfiltered = dataclasses.replace(model, setpoint_filter_s=0.0).simulate(ref)
    assert np.max(np.abs(expected - unfiltered)) > 0.1


@pytest.mark.parametrize("version", [2, 3])
def test_setpoint_filter_with_an_element_equals_model_bit_for_bit(version, tmp_path):
    """The filter feeds the split form too (an in-loop element)."""
    from identification.augmented import from_model as augment_model
    from identification.effects import Backlash

    base = ReducedAxisModel(parameters={"a1": 300.0, "a2": 3.0e4, "a3": 1.0e6, "b0": 0.0, "b1": 150.0, "b2": 2.8e4,
                                        "d0": 80.0, "d1": -70.0}, sample_time=0.001, axis="y",
                            setpoint_filter_s=0.008)
    data = base.to_dict()
    data["effects"] = [Backlash(width=0.01).record()]
    path = tmp_path / "model.json"
    path.write_text(json.dumps(data))
    model = load_model(path)
    assert model.setpoint_filter_s == 0.008 and export_spec(path).structured
    export_fmu(path, tmp_path / "f.fmu", fmi_version=version)
    ref = check_reference(3000, 0.001, seed=2)
    with FmuAxis(tmp_path / "f.fmu") as axis:
        got = axis.simulate_reference(ref, 0.001)
    np.testing.assert_array_equal(got, augment_model(model).simulate(ref))


def test_no_filter_adds_no_parameter():
    spec = export_spec(ReducedAxisModel(parameters=PARAMETERS, sample_time=TS))
    assert spec.setpoint_filter_s == 0.0 and "setpoint_filter_s" not in {v.name for v in spec.variables}
    assert "setpoint_filter_s" not in spec.start()


def test_too_long_a_filter_is_refused_by_name():
    with pytest.raises(ExportError, match="setpoint_filter_s"):
        export_spec(ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, setpoint_filter_s=5.0))
