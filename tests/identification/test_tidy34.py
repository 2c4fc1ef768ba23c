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


@pytest.mark.parametrize(("excesses", "d1", "why"), [
    ((3.0 * 538.0, -3.0 * 359.0), -359.0, None),  # static four times Coulomb both ways: the largest accepted
    ((5.12 * 538.0, -359.0), -359.0,
     "its static / Coulomb friction ratios 6.12, 2 exceed 4.0: a stick at standstill, no Stribeck curve"),
    ((538.0, -359.0), 0.0, None),  # no Coulomb level moving -: an infinite ratio, left to the lower bound
])
def test_a_stribeck_term_far_above_its_coulomb_level_is_no_stribeck_curve(excesses, d1, why):
    # ident_fuzz seed 21 case 30 (ballscrew-ppc, no effect added) refitted v_s 0.035 mm/s with static / Coulomb
    # 6.12 moving + (diagnosis.no_stribeck_curve): the stick of its Coulomb friction at reversals imitated
    m = augment(ReducedAxisModel(parameters={**PARAMS, "d1": d1}, sample_time=1e-3),
                [FrictionStribeck(velocity=0.035, excess_positive=excesses[0], excess_negative=excesses[1])])
    assert no_stribeck_curve(stribeck_static_ratios(m)) == why
