"""FMU export of the reference dead time ``delay_s`` (identification.dead_time), with real binaries.

The FMU's delay line must give ``model.simulate(x_ref)`` bit for bit: the loop reference is
numpy.interp of the past inputs, with numpy's arithmetic.
"""

from __future__ import annotations

import dataclasses
import json
import shutil
from importlib import resources
from pathlib import Path

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

TS = 0.003  # a TNCscope-like 3 ms trace
# the closed loop of tests/vcnc/test_fmu.py (poles near 50 Hz and 70 Hz, asymmetric Coulomb friction)
PARAMETERS = {"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0, "d1": -70.0}
DELAY_S = 0.1  # 33.33 samples: whole and fractional part


@pytest.fixture(scope="module")
def model() -> ReducedAxisModel:
    return ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="x", delay_s=DELAY_S)


@pytest.fixture(scope="module")
def fmus(model, tmp_path_factory) -> dict[int, Path]:
    d = tmp_path_factory.mktemp("fmu_delay")
    path = d / "model.json"
    model.to_json(path)
    out = {}
    for version in (2, 3):
        out[version] = d / f"drive{version}.fmu"
        export_fmu(path, out[version], fmi_version=version)
    return out


def test_c_and_python_agree_on_the_longest_reference_delay():
    from vcnc.fmu._variables import MAX_REF_DELAY

    header = resources.files("vcnc.fmu.c").joinpath("vcnc_model.h").read_text()
    assert f"#define VCNC_MAX_REF_DELAY {MAX_REF_DELAY} " in header


@pytest.mark.parametrize("version", [2, 3])
def test_delay_parameter_is_declared(fmus, version):
    assert validate_fmu(str(fmus[version])) == []
    names = {v.name: v for v in read_model_description(str(fmus[version])).modelVariables}
    assert names["reference_delay_s"].causality == "parameter"
    assert float(names["reference_delay_s"].start) == DELAY_S


@pytest.mark.parametrize("version", [2, 3])
def test_fmu_with_delay_equals_model_bit_for_bit(fmus, model, version):
    ref = check_reference(4000, TS, seed=5, start=3.0)
    expected = model.simulate(ref)
    with FmuAxis(fmus[version]) as axis:
        got = axis.simulate_reference(ref, TS)
    np.testing.assert_array_equal(got, expected)
    # a real test: the delay changes the prediction by far more than rounding
    undelayed = dataclasses.replace(model, delay_s=0.0).simulate(ref)
    assert np.max(np.abs(expected - undelayed)) > 0.1


@pytest.mark.parametrize("version", [2, 3])
def test_fmu_with_whole_sample_delay_equals_model_bit_for_bit(model, version, tmp_path):
    whole = dataclasses.replace(model, delay_s=4 * TS)
    path = tmp_path / "model.json"
    whole.to_json(path)
    export_fmu(path, tmp_path / "d.fmu", fmi_version=version)
    ref = check_reference(3000, TS, seed=9)
    with FmuAxis(tmp_path / "d.fmu") as axis:
        got = axis.simulate_reference(ref, TS)
    np.testing.assert_array_equal(got, whole.simulate(ref))


def test_negative_delay_is_refused_by_name(model):
    with pytest.raises(ExportError, match="delay_s"):
        export_spec(dataclasses.replace(model, delay_s=-0.05))


def test_zero_delay_adds_no_parameter(model):
    spec = export_spec(dataclasses.replace(model, delay_s=0.0))
    assert spec.delay_s == 0.0 and "reference_delay_s" not in {v.name for v in spec.variables}
    assert "reference_delay_s" not in spec.start()


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("structured", [False, True])
def test_dead_time_with_effects_equals_model_bit_for_bit(version, structured, tmp_path):
    """The delay line feeds both forms: the exact one (a disturbance effect) and the split one (an element)."""
    from identification.augmented import from_model as augment_model
    from identification.effects import Backlash, FrictionStribeck

    # the 25 Hz loop of tests/vcnc/test_fmu_effects.py at 1 ms, a 12.5-sample dead time
    base = ReducedAxisModel(parameters={"a1": 300.0, "a2": 3.0e4, "a3": 1.0e6, "b0": 0.0, "b1": 150.0, "b2": 2.8e4,
                                        "d0": 80.0, "d1": -70.0}, sample_time=0.001, axis="y", delay_s=0.0125)
    elements = [FrictionStribeck(velocity=2.0, excess_positive=30.0, excess_negative=-25.0)]
    if structured:
        elements.append(Backlash(width=0.01))
    data = base.to_dict()  # effect records in the model file, as the diagnosis writes them
    data["effects"] = [e.record() for e in elements]
    path = tmp_path / "model.json"
    path.write_text(json.dumps(data))
    model = load_model(path)
    assert model.delay_s == 0.0125 and len(model.effects) == len(elements)
    export_fmu(path, tmp_path / "d.fmu", fmi_version=version)
    spec = export_spec(path)
    assert spec.effect_names == [e.NAME for e in elements] and spec.structured == structured
    ref = check_reference(3000, 0.001, seed=2)
    with FmuAxis(tmp_path / "d.fmu") as axis:
        got = axis.simulate_reference(ref, 0.001)
    expected = augment_model(model).simulate(ref)
    np.testing.assert_array_equal(got, expected)
    undelayed = augment_model(dataclasses.replace(model, delay_s=0.0)).simulate(ref)
    assert np.max(np.abs(expected - undelayed)) > 0.1
