"""``friction_stribeck`` in the split form (``stick``): stiction that holds a stopped mass (stick36, session 36).

The exact loop switches friction on the sampled sign of the velocity and holds nothing; the split form holds a
stopped mass while the force on it stays inside the static band (Karnopp). The flag is the effect's, recorded in
its model-file parameters as ``stick_at_rest`` (a record without it is the exact form, as before).
"""

from __future__ import annotations

import numpy as np
import pytest

from identification import ReducedAxisModel
from identification.augmented import augment, from_model
from identification.effects import FrictionStribeck, effect_from_record
from vcnc.core.errors import InputError

# a 25 Hz closed loop (tests/vcnc/test_fmu_effects.py's PARAMETERS), static / Coulomb friction 2
PARAMETERS = {"a1": 300.0, "a2": 3.0e4, "a3": 1.0e6, "b0": 0.0, "b1": 150.0, "b2": 2.8e4, "d0": 80.0, "d1": -70.0}
T = 0.001


def _reference() -> np.ndarray:
    """0.5 s at rest, 5 mm at 10 mm/s, 2 s at rest [mm]."""
    t = np.arange(3000) * T
    return np.clip(t - 0.5, 0.0, 0.5) * 10.0


def _model(stick: bool):
    base = ReducedAxisModel(parameters=PARAMETERS, sample_time=T, axis="x")
    return augment(base, [FrictionStribeck(velocity=1.0, excess_positive=80.0, excess_negative=-70.0, stick=stick)],
                   viscous_rate=6.0)


def test_the_split_form_holds_the_stopped_mass_the_exact_loop_does_not():
    ref = _reference()
    exact, held = _model(False), _model(True)
    assert not exact.structured and held.structured
    v_exact, v_held = exact.velocity(ref), held.velocity(ref)
    # after the move (it ends at 1.0 s) the mass stops and stays: the velocity is exactly 0 on most samples of the
    # final 1.9 s in the split form (1780 of 1900), on almost none in the exact loop (1)
    assert np.sum(v_held[1100:] == 0.0) > 1500
    assert np.sum(v_exact[1100:] == 0.0) < 10
    x = held.simulate(ref)
    assert np.ptp(x[2000:]) == 0.0 and abs(x[-1] - 5.0) < 1e-3


def test_the_flag_is_recorded_only_when_set_and_read_back():
    e = FrictionStribeck(velocity=1.0, excess_positive=80.0, excess_negative=-70.0)
    assert "stick_at_rest" not in e.parameters()
    assert effect_from_record(e.record()) == e
    s = FrictionStribeck(velocity=1.0, excess_positive=80.0, excess_negative=-70.0, stick=True)
    assert s.parameters()["stick_at_rest"] is True and s.in_loop and not e.in_loop
    assert effect_from_record(s.record()) == s
    with pytest.raises(InputError, match="stick_at_rest"):
        FrictionStribeck.from_parameters({**s.parameters(), "stick_at_rest": "yes"})


def test_a_model_file_with_the_split_form_simulates_as_written():
    held = _model(True)
    records = held.effect_records()
    assert records[0]["parameters"]["plant_viscous_rate_1_s"] == 6.0
    base = ReducedAxisModel(parameters=PARAMETERS, sample_time=T, axis="x", effects=records)
    back = from_model(base)
    assert back.structured and back.viscous_rate == 6.0 and back.element("friction_stribeck").stick
    ref = _reference()
    np.testing.assert_array_equal(back.simulate(ref), held.simulate(ref))
    # the same record without the key is the exact form, as before
    plain = [dict(records[0], parameters={k: v for k, v in records[0]["parameters"].items()
                                          if k != "stick_at_rest"})]
    exact = from_model(ReducedAxisModel(parameters=PARAMETERS, sample_time=T, axis="x", effects=plain))
    assert not exact.structured
    np.testing.assert_array_equal(exact.simulate(ref), _model(False).simulate(ref))
