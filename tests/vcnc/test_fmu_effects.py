"""FMU export of models with diagnosed effects (identification.effects): every representable
effect is exported exactly (the binary equals ``model.simulate()`` of the AugmentedAxisModel to
1e-9 mm over a 20,000-sample identification test), anything else is refused by name.

Each FMU is built once per session (a lazily filled cache); models are built directly with known
effect parameters (no diagnosis run).
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from identification import ReducedAxisModel, load_model
from identification.augmented import AugmentedAxisModel, augment
from identification.effects import (
    Backlash,
    Delay,
    Drift,
    Effect,
    FrictionStribeck,
    FrictionViscousAsymmetric,
    PositionPeriodic,
    Resonance,
    Saturation,
    TimePeriodic,
)
from vcnc.cli import main
from vcnc.errors import ExportError, ModelFileError
from vcnc.fmu import REPRESENTABLE_EFFECTS, FmuAxis, export_fmu, export_spec
from vcnc.fmu._oracle import check_reference
from vcnc.fmu._variables import EFFECT_VARIABLES

pytestmark = pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("cc") is None,
                                reason="building FMUs needs cmake and a C compiler")

TS = 0.001
# a 25 Hz closed loop that stays stable with a few samples of control delay
PARAMETERS = {"a1": 300.0, "a2": 3.0e4, "a3": 1.0e6, "b0": 0.0, "b1": 150.0, "b2": 2.8e4, "d0": 80.0, "d1": -70.0}
VISCOUS_RATE = 12.0  # plant viscous rate c [1/s] of the split form

#: one model per effect (name -> elements), with parameters that make the effect visible
EFFECT_CASES = {
    "friction_stribeck": [FrictionStribeck(velocity=2.0, excess_positive=30.0, excess_negative=-25.0)],
    "friction_viscous_asymmetric": [FrictionViscousAsymmetric(coefficient=0.5)],
    "position_periodic": [PositionPeriodic(period=5.0, coefficients=((20.0, -10.0), (5.0, 3.0)))],
    "time_periodic": [TimePeriodic(period=0.0731, coefficients=((15.0, 5.0), (3.0, -2.0), (1.0, 1.0)), mean=4.0,
                                   with_mean=True)],
    "drift": [Drift(rate=1e-3)],
    "delay": [Delay(samples=2, sample_time=TS)],
    "saturation": [Saturation(limit=4e4)],
    "backlash": [Backlash(width=0.01)],
    "resonance": [Resonance(frequency=300.0, damping=0.05, table_fraction=0.3, measured_at="table")],
}
COMBINED = {
    # every disturbance/output effect at once (exact form), and with the common elements (split form)
    "all_disturbances": [e for k in ("friction_stribeck", "friction_viscous_asymmetric", "position_periodic",
                                     "time_periodic", "drift") for e in EFFECT_CASES[k]],
    "delay_backlash_and_disturbances": [Delay(samples=1, sample_time=TS), Backlash(width=0.005),
                                        Resonance(frequency=250.0, damping=0.1, table_fraction=0.4),
                                        *EFFECT_CASES["friction_stribeck"], *EFFECT_CASES["time_periodic"],
                                        *EFFECT_CASES["drift"]],
    # the saturation element with the machines' anti-windup (conditional integration), behind a delay: at
    # this limit its response differs from the unclamped form's by 0.55 mm on the check reference
    "saturation_anti_windup": [Delay(samples=1, sample_time=TS), Saturation(limit=4e4, anti_windup=True,
                                                                          integral_lead=0.01)],
    # the Stribeck term in the split form, which holds a stopped mass (stick36): the split loop with
    # plant_viscous_rate, as for the elements
    "friction_stribeck_stick": [FrictionStribeck(velocity=2.0, excess_positive=30.0, excess_negative=-25.0,
                                                 stick=True)],
}
CASES = {**EFFECT_CASES, **COMBINED}


def build(name: str) -> AugmentedAxisModel:
    elements = CASES[name]
    base = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="y")
    structured = any(e.in_loop for e in elements)
    return augment(base, elements, viscous_rate=VISCOUS_RATE if structured else 0.0)


@pytest.fixture(scope="session")
def reference() -> np.ndarray:
    ref = check_reference(20_000, TS, seed=7)
    assert np.ptp(ref) > 20
    return ref


@pytest.fixture(scope="session")
def built(tmp_path_factory):
    """name -> exported FMU path, each built (and checked by the export itself) on first use."""
    d = tmp_path_factory.mktemp("fmu_effects")
    cache: dict[str, Path] = {}

    def get(name: str) -> Path:
        if name not in cache:
            version = 3 if list(CASES).index(name) % 2 else 2
            cache[name] = export_fmu(build(name), d / f"{name}.fmu", fmi_version=version)
        return cache[name]

    return get


# --------------------------------------------------------------------------- representable


def test_every_effect_of_the_vocabulary_is_covered():
    from identification.effects import EFFECTS

    assert set(REPRESENTABLE_EFFECTS) == set(EFFECTS) == set(EFFECT_CASES) == set(EFFECT_VARIABLES)


@pytest.mark.parametrize("name", list(CASES))
def test_effect_is_exported_exactly(built, reference, name):
    path = built(name)
    assert validate_fmu(str(path)) == []
    model = build(name)
    expected = model.simulate(reference)
    with FmuAxis(path) as axis:
        got = axis.simulate_reference(reference, TS)
    assert np.all(np.isfinite(expected))
    assert np.max(np.abs(got - expected)) <= 1e-9
    # a real test: the effect changes the response, and the response is sane
    plain = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).simulate(reference)
    assert np.max(np.abs(expected - plain)) > 1e-4
    assert np.max(np.abs(expected - reference)) < 50.0


@pytest.mark.parametrize("name", ["friction_stribeck", "delay"])
def test_effect_matches_from_any_start(built, name):
    ref = check_reference(5_000, TS, seed=3, start=-6.25)
    with FmuAxis(built(name)) as axis:
        got = axis.simulate_reference(ref, TS)
    assert np.max(np.abs(got - build(name).simulate(ref))) <= 1e-9


def test_effect_parameters_are_fmu_parameters(built):
    md = read_model_description(str(built("all_disturbances")))
    names = {v.name: v for v in md.modelVariables}
    for p in ("stribeck_velocity", "viscous_asymmetry", "position_period", "position_periodic_cos_2",
              "time_period", "time_mean", "time_periodic_sin_3", "drift_rate"):
        assert (names[p].causality, names[p].variability) == ("parameter", "fixed"), p
    assert "position_periodic_sin_3" not in names  # harmonics fixed at export
    assert "delay_samples" not in names and "plant_viscous_rate" not in names  # absent effects: no variables
    md = read_model_description(str(built("delay")))
    names = {v.name: v for v in md.modelVariables}
    assert int(names["delay_samples"].start) == 2 and float(names["plant_viscous_rate"].start) == VISCOUS_RATE


@pytest.mark.parametrize("name", ["all_disturbances", "delay_backlash_and_disturbances"])
def test_tuned_effect_parameters(built, reference, name):
    import dataclasses

    tuned_values = {"stribeck_velocity": 5.0, "stribeck_excess_positive": 10.0, "time_mean": -3.0,
                    "time_periodic_cos_1": 7.5, "drift_rate": -2e-3}
    if name == "delay_backlash_and_disturbances":
        tuned_values.update(delay_samples=2, backlash_width=0.02, plant_viscous_rate=5.0)
    ref = reference[:5_000]
    with FmuAxis(built(name), start_values=tuned_values) as axis:
        got = axis.simulate_reference(ref, TS)
    model = build(name)
    elements = []
    for e in model.elements:
        if e.NAME == "friction_stribeck":
            e = dataclasses.replace(e, velocity=5.0, excess_positive=10.0)
        elif e.NAME == "time_periodic":
            e = dataclasses.replace(e, mean=-3.0, coefficients=((15.0, 7.5), *e.coefficients[1:]))
        elif e.NAME == "drift":
            e = Drift(rate=-2e-3)
        elif e.NAME == "delay":
            e = Delay(samples=2, sample_time=TS)
        elif e.NAME == "backlash":
            e = Backlash(width=0.02)
        elements.append(e)
    tuned = augment(model, elements, viscous_rate=5.0 if model.structured else 0.0)
    assert np.max(np.abs(got - tuned.simulate(ref))) <= 1e-9
    assert np.max(np.abs(got - model.simulate(ref))) > 1e-4


def test_saturation_anti_windup_is_exported_as_a_switch_fixed_at_export(built, reference):
    """The FMU holds the integral back as the Python split loop does (to 1e-9 mm, as every effect), and
    the switch is really carried: the unclamped element's response is 0.1 mm and more away."""
    with FmuAxis(built("saturation_anti_windup")) as axis:
        got = axis.simulate_reference(reference, TS)
    model = build("saturation_anti_windup")
    assert np.max(np.abs(got - model.simulate(reference))) <= 1e-9
    unclamped = augment(model, [Delay(samples=1, sample_time=TS), Saturation(limit=4e4)], viscous_rate=VISCOUS_RATE)
    assert np.max(np.abs(got - unclamped.simulate(reference))) > 0.1
    md = read_model_description(str(built("saturation_anti_windup")))
    assert "saturation_limit" in {v.name for v in md.modelVariables}


def test_stribeck_stick_is_exported_in_the_split_form(built, reference):
    """The split form's stick (``stick_at_rest``) is the FMU's split loop with its viscous rate, not the exact loop."""
    md = read_model_description(str(built("friction_stribeck_stick")))
    assert "plant_viscous_rate" in {v.name for v in md.modelVariables}
    exact = augment(build("friction_stribeck_stick"), list(EFFECT_CASES["friction_stribeck"]), viscous_rate=0.0)
    assert np.max(np.abs(build("friction_stribeck_stick").simulate(reference) - exact.simulate(reference))) > 1e-4


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_the_split_base_form_is_exported_exactly(tmp_path, reference, fmi_version):
    """The reduced model in the split base form (``form`` "split", identstick40: Coulomb friction that holds a
    stopped axis) is the FMU's split loop with its viscous rate, as an element's split form; read from its model file
    (``vcnc.axis-model/4``), the binary equals ``model.simulate()`` to 1e-14 mm."""
    model = augment(ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="y"), [], viscous_rate=VISCOUS_RATE,
                    form="split")
    path = tmp_path / "split.json"
    model.to_json(path)
    spec = export_spec(path)
    assert spec.form == "split" and spec.structured and not spec.elements
    fmu = export_fmu(path, tmp_path / "split.fmu", fmi_version=fmi_version)
    assert validate_fmu(str(fmu)) == []
    assert "plant_viscous_rate" in {v.name for v in read_model_description(str(fmu)).modelVariables}
    expected = model.simulate(reference)
    with FmuAxis(fmu) as axis:
        got = axis.simulate_reference(reference, TS)
    assert np.all(np.isfinite(expected)) and np.max(np.abs(got - expected)) <= 1e-14
    # a real test: the split form's friction holds where the exact loop's does not
    plain = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).simulate(reference)
    assert np.max(np.abs(expected - plain)) > 1e-4


def test_model_file_with_diagnosed_effects_round_trips(tmp_path):
    """The records a diagnosis writes (``plant_viscous_rate_1_s`` with the elements) export as loaded."""
    model = build("delay_backlash_and_disturbances")
    records = []
    for e in model.elements:
        rec = e.record()
        if e.KIND == "element":
            rec["parameters"]["plant_viscous_rate_1_s"] = VISCOUS_RATE
        records.append(rec)
    data = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="y").to_dict()
    data["effects"] = records
    path = tmp_path / "diagnosed.json"
    path.write_text(json.dumps(data))
    spec = export_spec(path)
    assert [e.NAME for e in spec.elements] == [e.NAME for e in model.elements]
    assert spec.viscous_rate == VISCOUS_RATE and spec.structured
    ref = check_reference(3_000, TS, seed=2)
    np.testing.assert_array_equal(spec.model().simulate(ref), load_model(path).simulate(ref))


# ------------------------------------------------------------------------------- refused


class _Cogging(Effect):
    """An effect outside the FMU's vocabulary."""

    NAME = "cogging_table"
    KIND = "disturbance"

    def pack(self, spec, *, model_sample_time):
        pass


def test_unknown_effect_is_refused_by_name():
    model = augment(ReducedAxisModel(parameters=PARAMETERS, sample_time=TS), [_Cogging(), Drift(rate=1e-3)])
    with pytest.raises(ExportError, match="cogging_table") as info:
        export_spec(model)
    assert "representable: friction_stribeck" in str(info.value) and "backlash" in str(info.value)


def test_too_many_harmonics_are_refused():
    coef = tuple((1.0, 0.0) for _ in range(65))
    base = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS)
    model = augment(base, [TimePeriodic(period=0.1, coefficients=coef)])
    with pytest.raises(ExportError, match="65 harmonics"):
        export_spec(model)


def _model_file(tmp_path: Path, effects: list) -> Path:
    data = ReducedAxisModel(parameters=PARAMETERS, sample_time=TS).to_dict()
    data["effects"] = effects
    path = tmp_path / "m.json"
    path.write_text(json.dumps(data))
    return path


def test_cli_refuses_an_effect_it_cannot_represent_exit_1_and_no_file(tmp_path, capsys):
    # the same effect twice (the model would add or overwrite them): not represented
    path = _model_file(tmp_path, [Drift(rate=1e-3).record(), Drift(rate=2e-3).record()])
    out = tmp_path / "x.fmu"
    with pytest.raises(ExportError, match="drift"):
        export_fmu(path, out)
    assert main(["export-fmu", str(path), "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error:") and "drift" in err and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.json"]


def test_old_outside_the_loop_effect_records_are_model_file_errors(tmp_path, capsys):
    """The former FMU-only ``backlash`` (``width``) is not the diagnosis' effect: refused, never reinterpreted."""
    path = _model_file(tmp_path, [{"name": "backlash", "parameters": {"width": 0.02}}])
    with pytest.raises(ModelFileError, match="width_mm"):
        export_spec(path)
    assert main(["export-fmu", str(path), "-o", str(tmp_path / "x.fmu")]) == 2
    assert capsys.readouterr().err.startswith("error:")
    assert not (tmp_path / "x.fmu").exists()


def test_bad_effect_values_are_model_file_errors(tmp_path):
    with pytest.raises(ModelFileError, match="delay"):
        export_spec(_model_file(tmp_path, [{"name": "delay", "parameters": {"samples": -1}}]))
    with pytest.raises(ModelFileError, match="time_periodic"):
        export_spec(_model_file(tmp_path, [{"name": "time_periodic", "parameters": {"period_s": 0.0}}]))
