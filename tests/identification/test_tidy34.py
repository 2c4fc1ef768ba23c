"""Places of the diagnosis that share one home after tidy34: an augmented model's element by its name
(:meth:`identification.AugmentedAxisModel.element`) and the test of a Stribeck term's static / Coulomb ratios
(:func:`identification.diagnosis.no_stribeck_curve`), which the round's choice and the final model's check share."""

from __future__ import annotations

import pytest

from identification.augmented import augment
from identification.diagnosis import no_stribeck_curve, stribeck_static_ratios
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


@pytest.mark.parametrize(("excesses", "why"), [
    ((538.0, -359.0), None),  # static twice Coulomb both ways
    ((0.9 * 538.0 - 538.0, -359.0), None),  # moving +: 0.9 exactly, the least a Stribeck curve has
    ((-562.0, 558.0), "its static / Coulomb friction ratios -0.0446, -0.554 are below 0.9: no Stribeck curve"),
    ((538.0, 0.5 * 359.0), "its static / Coulomb friction ratios 2, 0.5 are below 0.9: no Stribeck curve"),
])
def test_a_stribeck_term_whose_static_friction_falls_below_coulomb_is_no_stribeck_curve(excesses, why):
    # ident_fuzz seed 1 case 22 refitted excesses -562 / +558 against Coulomb +538 / -359 (diagnosis.py)
    ratios = stribeck_static_ratios(_model(FrictionStribeck(velocity=0.3, excess_positive=excesses[0],
                                                            excess_negative=excesses[1])))
    assert no_stribeck_curve(ratios) == why
