"""The reduced model's split base form (``form`` "split", identstick40): Coulomb friction that holds a stopped axis.

The exact loop's Coulomb friction switches on the sampled sign of the velocity and holds nothing; the split form
(plant + sampled controller, :mod:`identification.augmented`) holds a stopped mass while the force on it lies between
the Coulomb levels (Karnopp). A model carries it as ``form`` "split"; the model file records it as ``form`` with
``plant_viscous_rate_1_s`` (``vcnc.axis-model/4``), a file without the key is the exact form as before.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from identification import ReducedAxisModel, load_model
from identification.augmented import augment
from identification.model_file import model_from_dict
from identification.model_format import FORMAT_FORM, model_to_dict, write_model
from vcnc.core.errors import InputError, ModelFileError

T = 0.001
# a 25 Hz closed loop (tests/vcnc/test_fmu_effects.py's PARAMETERS) with Coulomb levels of 800 / -700 mm/s^2
PARAMETERS = {"a1": 300.0, "a2": 3.0e4, "a3": 1.0e6, "b0": 0.0, "b1": 150.0, "b2": 2.8e4, "d0": 800.0, "d1": -700.0}
VISCOUS_RATE = 6.0  # plant viscous rate c [1/s] of the split form


def _reference() -> np.ndarray:
    """20 moves between +-0.5..1 mm at 40 mm/s, each reversal after a 20 ms dwell, smoothed over 15 ms [mm]."""
    rng = np.random.default_rng(3)
    parts, x = [np.zeros(100)], 0.0
    for k in range(20):
        target = (1.0 if k % 2 == 0 else -1.0) * (0.5 + 0.5 * rng.random())
        n = int(abs(target - x) / 40.0 / T) + 1
        parts += [np.linspace(x, target, n + 1)[1:], np.full(20, target)]
        x = target
    r = np.concatenate([*parts, np.full(100, x)])
    return np.convolve(np.pad(r, (7, 7), mode="edge"), np.ones(15) / 15, mode="valid")


def _truth(form: str):
    return augment(ReducedAxisModel(parameters=PARAMETERS, sample_time=T, axis="x"), [], viscous_rate=VISCOUS_RATE,
                   form=form)


def test_the_split_form_holds_the_stopped_axis_at_each_reversal():
    xr = _reference()
    v_split, v_exact = _truth("split").velocity(xr), _truth("exact").velocity(xr)
    # at each of the 20 reversals the split form's axis stands still for a few samples; the exact loop's never does
    assert np.sum(v_split == 0.0) > 100
    assert np.sum(v_exact[100:-100] == 0.0) == 0


def test_the_model_file_records_the_form_and_reads_it_back(tmp_path):
    m = _truth("split")
    path = tmp_path / "split.json"
    write_model(m, path)
    d = json.loads(path.read_text())
    assert d["format"] == FORMAT_FORM and d["form"] == "split" and d["plant_viscous_rate_1_s"] == VISCOUS_RATE
    back = load_model(path)
    assert back.form == "split" and back.viscous_rate == VISCOUS_RATE and back.structured
    xr = _reference()
    np.testing.assert_array_equal(back.simulate(xr), m.simulate(xr))
    # a file without the key is the exact form, as every file before it means
    plain = model_to_dict(ReducedAxisModel(parameters=PARAMETERS, sample_time=T, axis="x"))
    assert "form" not in plain
    assert getattr(model_from_dict(plain), "form", "exact") == "exact"


@pytest.mark.parametrize("change, key", [({"form": "stick"}, "'form'"), ({"form": None}, "'form'"),
                                         ({"plant_viscous_rate_1_s": "6"}, "'plant_viscous_rate_1_s'"),
                                         ({"plant_viscous_rate_1_s": -1.0}, "'plant_viscous_rate_1_s'")])
def test_a_bad_form_is_a_model_file_error_naming_the_key(change, key):
    d = dict(model_to_dict(_truth("split")), **change)
    with pytest.raises(ModelFileError, match=key):
        model_from_dict(d, source="m.json")
    d = model_to_dict(_truth("split"))
    del d["plant_viscous_rate_1_s"]
    with pytest.raises(ModelFileError, match="'plant_viscous_rate_1_s' missing"):
        model_from_dict(d, source="m.json")


def test_an_unknown_form_is_refused_by_the_model():
    with pytest.raises(InputError, match="form must be one of"):
        _truth("stick")
