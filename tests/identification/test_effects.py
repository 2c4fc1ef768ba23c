"""The effect elements and the augmented model (identification.effects, identification.augmented)."""

from __future__ import annotations

import numpy as np
import pytest

import vcnc
from identification.augmented import AugmentedAxisModel, SimSpec, augment, from_model, simulate_augmented
from identification.effects import (
    EFFECTS,
    Backlash,
    Delay,
    Drift,
    FrictionStribeck,
    FrictionViscousAsymmetric,
    PositionPeriodic,
    Resonance,
    Saturation,
    TimePeriodic,
    effect_from_record,
)
from identification.model_file import model_from_dict
from identification.model_format import model_to_dict
from identification.reduced_model import ReducedAxisModel, simulate
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.engine.machine import EFFECTS as MACHINE_EFFECTS
from vcnc.errors import InputError

TS = 1e-3

EXAMPLES = [
    FrictionStribeck(velocity=3.0, excess_positive=200.0, excess_negative=-150.0),
    FrictionViscousAsymmetric(coefficient=-0.8),
    Backlash(width=0.01),
    PositionPeriodic(period=10.0, coefficients=((40.0, -10.0), (5.0, 1.0))),
    TimePeriodic(period=0.5, coefficients=((90.0, 20.0),), mean=3.0),
    Resonance(frequency=60.0, damping=0.05, table_fraction=0.5, measured_at="motor"),
    Delay(samples=2, sample_time=TS),
    Saturation(limit=3500.0),
    Saturation(limit=3500.0, anti_windup=True, integral_lead=0.02),
    Drift(rate=2e-4),
]


@pytest.fixture(scope="module")
def reference() -> np.ndarray:
    return random_moves_reference(moves=30, seed=4)


def test_vocabulary_is_the_architecture_one():
    # ARCHITECTURE.md "Effect names" and the machines' with_effect use the same names
    assert set(EFFECTS) == set(MACHINE_EFFECTS)
    assert {type(e).NAME for e in EXAMPLES} == set(EFFECTS)


@pytest.mark.parametrize("effect", EXAMPLES, ids=lambda e: e.summary())
def test_record_round_trip_and_units(effect):
    rec = effect.record()
    assert rec["name"] == effect.NAME and isinstance(rec["fmu"], bool)
    back = effect_from_record(rec)
    assert back.record()["parameters"] == rec["parameters"]
    assert set(rec["parameters"]) <= set(effect.UNITS)


def test_unknown_effect_record_is_refused():
    with pytest.raises(InputError, match="unknown effect"):
        effect_from_record({"name": "gremlins", "parameters": {}})
    with pytest.raises(InputError, match="period_s"):
        effect_from_record({"name": "time_periodic", "parameters": {"period_s": "soon"}})


def test_saturation_records_without_anti_windup_read_as_the_unclamped_element():
    """A model file of before session 19 (no ``anti_windup``) means the element it was fitted with."""
    old = effect_from_record({"name": "saturation", "parameters": {"limit_mm_s2": 3500.0}})
    assert old == Saturation(limit=3500.0) and old.anti_windup is False and old.integral_lead == 0.0
    assert old.record()["parameters"] == {"limit_mm_s2": 3500.0, "anti_windup": False}
    aw = effect_from_record({"name": "saturation", "parameters": {"limit_mm_s2": 3500.0, "anti_windup": True,
                                                                  "integral_lead_s": 0.02}})
    assert aw == Saturation(limit=3500.0, anti_windup=True, integral_lead=0.02)
    assert "anti-windup" in aw.summary() and "anti-windup" not in old.summary()
    with pytest.raises(InputError, match="anti_windup.*true or false"):
        effect_from_record({"name": "saturation", "parameters": {"limit_mm_s2": 3500.0, "anti_windup": 1}})
    with pytest.raises(InputError, match="integral_lead_s.*>= 0"):
        effect_from_record({"name": "saturation", "parameters": {"limit_mm_s2": 3500.0, "anti_windup": True,
                                                                 "integral_lead_s": -0.01}})


@pytest.mark.parametrize(("name", "lead_s", "limit_v"), [
    # a PID's integral is that of e alone (Eq. 3.5): no lead
    ("fadal-pid", 0.0, 3.5),
    # a P-PI's velocity-loop integrator integrates K_p e - v: lead 1/K_p (K_p = 30 1/s, vcnc/machines/fadal-ppi.toml)
    ("fadal-ppi", 1.0 / 30.0, 2.0),
])
def test_saturation_forms_are_the_machines_laws_at_their_limit(name, lead_s, limit_v):
    """The machine (noise, encoder, DAC, friction and nut play removed; its amplifier limited to
    ``limit_v``) running into its limit on reversals after short moves, against the split form with
    the machine's own reduced parameters: the element with anti-windup and the law's integral lead
    reproduces the machine with anti-windup (conditional integration, Controller.anti_windup) to
    1e-12 mm, the unclamped element the bare law; each is >= 0.1 um off the other law."""
    import dataclasses

    out = {}
    for machine_aw in (True, False):
        m0 = vcnc.machine(name)
        law = dataclasses.replace(m0.axis("x").controller, anti_windup=machine_aw)
        m = m0.with_axis_options("x", backlash=None, noise=None, encoder=None, dac=None, friction=None,
                                 controller=law).with_effect("x", "saturation", {"voltage_limit_v": limit_v})
        cap = m.simulate(vcnc.interpolate(vcnc.parse_program("G00 X0 F12000\nG01 X5\nX-3\nX2.5\nX2.4\nX0\nM30\n"), m))
        assert cap.aux["saturated"].mean() > 0.005
        ax = m.axis("x")
        base = ReducedAxisModel(parameters=ax.reduced_parameters(), sample_time=TS)
        for aw in (True, False):
            e = Saturation(limit=limit_v * ax.drive.gain, anti_windup=aw, integral_lead=lead_s if aw else 0.0)
            y = augment(base, [e], viscous_rate=ax.drive.viscous_rate).simulate(cap.reference[:, 0])
            out[machine_aw, aw] = np.max(np.abs(y - cap.measured[:, 0]))
    assert out[True, True] < 1e-12 and out[False, False] < 1e-12, out  # mm
    assert out[True, False] > 1e-4 and out[False, True] > 1e-4, out


def test_no_effect_is_the_reduced_model_bit_for_bit(reference):
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS)
    a = augment(m, [])
    assert isinstance(a, AugmentedAxisModel)
    assert np.array_equal(a.simulate(reference), simulate(FADAL_PID_X, reference, TS))
    # a disturbance effect with zero coefficients changes nothing either
    z = augment(m, [TimePeriodic(period=0.5), PositionPeriodic(period=10.0), FrictionViscousAsymmetric()])
    assert np.array_equal(z.simulate(reference), simulate(FADAL_PID_X, reference, TS))


def test_time_periodic_load_is_the_reduced_model_disturbance(reference):
    e = TimePeriodic(period=0.37, coefficients=((80.0, -30.0), (10.0, 5.0)), mean=12.0)
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS)
    w = e.load(np.arange(reference.size) * TS)
    assert np.allclose(augment(m, [e]).simulate(reference), simulate(FADAL_PID_X, reference, TS, disturbance=w),
                       rtol=0, atol=1e-12)


def test_sampled_split_form_reproduces_the_virtual_machine_with_delay():
    """The element form is the machine's structure: PID sampled with a zero-order hold, backward
    differences, 2 samples of computational delay (no noise, quantisation, limit; no friction, which
    the machine integrates exactly and the model holds over each sample like Eq. 3.3's sampled form)."""
    base = vcnc.machine("fadal-pid").with_axis_options("x", backlash=None, noise=None, encoder=None, dac=None,
                                                         saturation=None, friction=None)
    m = base.with_effect("x", "delay")
    sp = vcnc.interpolate(vcnc.parse_program("G00 X0 F12000\nG01 X5\nX-3\nX2.5\nX0\nM30\n"), m)
    cap = m.simulate(sp)
    truth = m.axis("x").reduced_parameters()
    c = m.axis("x").drive.viscous_rate
    model = augment(ReducedAxisModel(parameters=truth, sample_time=TS), [Delay(samples=2, sample_time=TS)],
                    viscous_rate=c)
    err = model.simulate(cap.reference[:, 0]) - cap.measured[:, 0]
    assert np.max(np.abs(err)) < 1e-7  # mm


def test_split_form_friction_sticks_like_the_machine():
    """With the machine's Coulomb friction on (it stops and sticks, Karnopp), the split form with
    stiction reproduces the machine to 0.07 um over reversals and short moves, one exact step per
    sample with the stop found inside it (sampled sign(v) switching, the earlier form, was 1.1 um
    off here; ten steps per sample, 0.5 nm)."""
    base = vcnc.machine("fadal-pid").with_axis_options("x", backlash=None, noise=None, encoder=None, dac=None,
                                                         saturation=None)
    m = base.with_effect("x", "delay")
    sp = vcnc.interpolate(vcnc.parse_program("G00 X0 F12000\nG01 X5\nX-3\nX2.5\nX2.4\nX2.45\nX0\nM30\n"), m)
    cap = m.simulate(sp)
    model = augment(ReducedAxisModel(parameters=m.axis("x").reduced_parameters(), sample_time=TS),
                    [Delay(samples=2, sample_time=TS)], viscous_rate=m.axis("x").drive.viscous_rate)
    err = model.simulate(cap.reference[:, 0]) - cap.measured[:, 0]
    assert np.max(np.abs(err)) < 1e-4  # mm; the tracking error itself reaches 142 um


def test_elements_change_the_response_as_physics_says(reference):
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS)
    null = augment(m, [Delay(samples=0, sample_time=TS)], viscous_rate=2.55).simulate(reference)
    # a limit far above every demand, a play of zero width: the null form
    far = augment(m, [Saturation(limit=1e9)], viscous_rate=2.55).simulate(reference)
    assert np.allclose(far, null, atol=1e-12)
    # ... in both forms: an anti-windup that never holds a step back leaves the loop bit for bit
    aw = augment(m, [Saturation(limit=1e9, anti_windup=True, integral_lead=0.03)], viscous_rate=2.55)
    assert np.array_equal(aw.simulate(reference), far)
    # backlash: lost motion at reversals of about its width, tracking otherwise
    bl = augment(m, [Backlash(width=0.02)], viscous_rate=2.55).simulate(reference)
    assert 0.002 < np.max(np.abs(bl - null)) < 0.05
    # a limit below the demand slows the moves down; the loop whose integral is held back at the limit
    # tracks closer than the unclamped one, which winds up
    sat = augment(m, [Saturation(limit=1000.0)], viscous_rate=2.55).simulate(reference)
    assert np.sqrt(np.mean((sat - reference) ** 2)) > np.sqrt(np.mean((null - reference) ** 2))
    held = augment(m, [Saturation(limit=1000.0, anti_windup=True)], viscous_rate=2.55).simulate(reference)
    assert np.sqrt(np.mean((held - reference) ** 2)) < np.sqrt(np.mean((sat - reference) ** 2))
    # drift is an output offset growing linearly
    dr = augment(m, [Drift(rate=1e-3)]).simulate(reference)
    t = np.arange(reference.size) * TS
    assert np.allclose(dr - simulate(FADAL_PID_X, reference, TS), 1e-3 * t)


def test_unstable_candidate_gives_nan_not_an_exception(reference):
    sp = SimSpec(n=reference.size, sample_time=TS, wext=np.zeros(reference.size), structured=True, delay=8,
                 viscous_rate=1.0)
    y = simulate_augmented(FADAL_PID_X, reference, sp)
    assert np.isnan(y[-1])


def test_model_file_round_trip_keeps_the_effects(reference):
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS, axis="x")
    els = [Delay(samples=2, sample_time=TS), TimePeriodic(period=0.5, coefficients=((50.0, 0.0),))]
    recs = [e.record() for e in els]
    recs[0]["parameters"]["plant_viscous_rate_1_s"] = 2.55
    a = augment(m, els, viscous_rate=2.55, effects=recs)
    back = from_model(model_from_dict(model_to_dict(a)))  # the hook model_file would call
    assert isinstance(back, AugmentedAxisModel) and back.viscous_rate == 2.55
    assert np.array_equal(back.simulate(reference), a.simulate(reference))
    assert from_model(m) is m


def test_fmu_flags():
    assert all(isinstance(cls.FMU, bool) for cls in EFFECTS.values())
    assert augment(ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS), EXAMPLES[:2]).fmu_representable


def test_time_periodic_load_locked_to_the_reference_is_not_identifiable():
    """A load whose period the reference itself repeats with cannot be told from reference-driven
    effects (friction, modes): the search refuses such periods."""
    from identification.searches import reference_repeats

    T = 1e-3
    t = np.arange(20000) * T
    xr = 5.0 * np.sin(2 * np.pi * t / 2.0)  # repeats every 2 s
    assert reference_repeats(xr, 2.0, T) == 1
    assert reference_repeats(xr, 1.0, T) == 2  # a load at 1 s is locked too (2 x 1 s)
    assert reference_repeats(xr, 0.7, T) is None
    rng = np.random.default_rng(0)
    assert reference_repeats(np.cumsum(rng.normal(size=t.size)), 0.5, T) is None


def test_an_augmented_model_built_in_python_keeps_its_elements_in_the_model_file(reference):
    """``augment(...)`` without the diagnosis has elements but no effect records: the file gets
    the elements' records, so the reloaded model simulates the same (helper finding, session 6)."""
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS)
    model = augment(m, [Backlash(width=0.02), Drift(rate=1e-3)], viscous_rate=2.55)
    d = model_to_dict(model)
    assert [e["name"] for e in d["effects"]] == ["backlash", "drift"]
    again = model_from_dict(d)
    assert np.array_equal(again.simulate(reference), model.simulate(reference))


def test_model_effects_are_typed_records_that_read_as_the_files_mappings(tmp_path):
    """issue #21: model.effects holds EffectRecord objects (typed attributes) beside model.elements."""
    from identification import EffectRecord, load_model

    rec = {"name": "backlash", "parameters": {"width_mm": 0.01, "plant_viscous_rate_1_s": 30.0},
           "rms_before_um": 2.0, "rms_after_um": 0.5, "summary": "play 10 um"}
    m = from_model(ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=TS, effects=[rec]))
    (e,) = m.effects
    assert isinstance(e, EffectRecord) and e == rec and dict(e) == rec
    assert (e.name, e.parameters["width_mm"], e.rms_before_um, e.rms_after_um, e.summary) == (
        "backlash", 0.01, 2.0, 0.5, "play 10 um")
    m.to_json(tmp_path / "m.json")
    back = load_model(tmp_path / "m.json")
    assert isinstance(back.effects[0], EffectRecord) and back.effects[0] == rec
    with pytest.raises(InputError, match="'name' string"):
        ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=TS, effects=[{"parameters": {}}])
