"""Places of the diagnosis that share one home after tidy34: an augmented model's element by its name
(:meth:`identification.AugmentedAxisModel.element`)."""

from __future__ import annotations

import pytest

from identification.augmented import augment
from identification.effects import Backlash, FrictionStribeck
from identification.reduced_model import ReducedAxisModel

# a reduced model of fadal-pid's x axis (tests/identification/test_ident_fuzz_cases.py), Coulomb +538 / -359 mm/s^2
PARAMS = {"a1": 200.0, "a2": 5.4e4, "a3": 4.0e5, "b0": 0.0, "b1": 199.0, "b2": 5.4e4, "d0": 538.0, "d1": -359.0}


def _model(*elements):
    return augment(ReducedAxisModel(parameters=PARAMS, sample_time=1e-3), list(elements))


def test_an_element_is_found_by_its_name():
    st = FrictionStribeck(velocity=5.0, excess_positive=538.0, excess_negative=-359.0)
    gap = Backlash(width=0.003)
    m = _model(gap, st)
    assert m.element("friction_stribeck") is st and m.element("backlash") is gap
    with pytest.raises(KeyError, match=r"no element 'resonance' \(its elements: \['backlash', 'friction_stribeck'\]\)"):
        m.element("resonance")

