"""Residual diagnosis on captures of the project's virtual machines with an undeclared effect.

Every capture comes from ``vcnc.machine("fadal-pid")`` (backlash removed: its 3 um nut backlash is
invisible to the motor encoder anyway) running a Table 3.2-style program (40 random moves within
+/-10 mm at F12000), with one effect added by ``Machine.with_effect`` at the machine's realistic
size unless said otherwise. The identifier is never told which effect is present.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import vcnc
from identification import identify
from identification.diagnosis import DiagnosisOptions, before_after_rows, diagnose_report, format_before_after
from identification.model_file import model_from_dict
from identification.model_format import model_to_dict

pytestmark = pytest.mark.slow  # every test diagnoses a full capture (tens of seconds each)

MOVES = 40
K_J = 1008.0  # K/J of the fadal-pid x axis [mm/(V s^2)]: amplifier 2 A/V, 0.95 N m/A, lead 10 mm, J 0.003


@pytest.fixture(scope="module")
def machine():
    # the machine as it is: its PID has anti-windup (conditional integration at the 15 A limit), which the
    # saturation element models too (identification/effects/saturation.py)
    return vcnc.machine("fadal-pid").with_axis_options("x", backlash=None)


@pytest.fixture(scope="module")
def setpoints(machine):
    import toolpaths

    return vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(MOVES, 10.0, 12000.0, seed=1)), machine)


# effect -> (machine variant, parameter overrides, why)
VARIANTS = {
    "friction_stribeck": (None, {"static_ratio": 2.0, "stribeck_velocity_mm_s": 5.0}),
    "friction_viscous_asymmetric": (None, None),
    "backlash": ({"feedback": "table"}, None),
    "position_periodic": (None, None),
    "time_periodic": (None, None),
    "resonance": (None, None),
    "delay": (None, None),
    "saturation": (None, {"voltage_limit_v": 3.5}),
    "drift": (None, None),
}


def _capture(machine, setpoints, effect: str | None, seed: int = 1):
    m = machine
    if effect is not None:
        opts, params = VARIANTS[effect]
        if opts:
            m = m.with_axis_options("x", **opts)
        m = m.with_effect("x", effect, params)
    cap = m.simulate(setpoints, seed=seed)
    if effect == "drift":
        # a drift of the encoder the loop closes on is removed by the loop; what a capture can show
        # is the table (here: the machine's true table position, as a scale or laser records it)
        cap = dataclasses.replace(cap, measured=cap.table)
    return cap


_CACHE: dict = {}


def _report(machine, setpoints, effect, *, seed=1, max_effects=1):
    key = (effect, seed, max_effects)
    if key not in _CACHE:
        cap = _capture(machine, setpoints, effect, seed)
        model = identify(cap, axis="x", diagnose=False)
        _CACHE[key] = diagnose_report(cap, model, axis="x", options=DiagnosisOptions(max_effects=max_effects))
    return _CACHE[key]


def _param(rep, name):
    return next(e for e in rep.model.effects if e["name"] == name)["parameters"]


EXPECTED = {
    # effect: (parameter key, true value, relative tolerance)
    "backlash": ("width_mm", 0.010, 0.20),
    "position_periodic": ("period_mm", 10.0, 0.05),
    "time_periodic": ("period_s", 0.5, 0.05),
    "resonance": ("antiresonance_hz", 60.0 * math.sqrt(0.5), 0.05),
    # the element with the PID's anti-windup: 3532 mm/s^2 on seed 1 (0.12 %); 3636 (3 %) when only the
    # unclamped element existed
    "saturation": ("limit_mm_s2", 3.5 * K_J, 0.01),
    "drift": ("rate_mm_s", -2e-4, 0.10),  # the table lags the drifting encoder
    "friction_stribeck": ("stribeck_velocity_mm_s", 5.0, 0.30),
}


@pytest.mark.parametrize("effect", list(VARIANTS))
def test_undeclared_effect_is_named_first_and_cuts_the_held_out_error(machine, setpoints, effect):
    rep = _report(machine, setpoints, effect)
    assert rep.effects[:1] == [effect], rep.rounds
    v = rep.model.validation
    # pooled over the folds; the smallest cuts on seed 1 are friction_stribeck (48 %) and drift (44 %)
    assert v["rms_after_um"] <= 0.6 * v["rms_before_um"], v
    # every fold validated something and none is contradicted
    assert len(v["folds"]) >= 2 and all(f["active_samples"] > 0 for f in v["folds"]), v["folds"]
    assert all(math.isfinite(f["rms_after_um"]) for f in v["folds"])
    rec = rep.model.effects[0]
    assert rec["rms_after_um"] < rec["rms_before_um"]
    for k in ("rms_before_um", "rms_after_um", "validation_rms_before_um", "validation_rms_after_um"):
        assert math.isfinite(rec[k])
    if effect == "delay":
        # one effect only: the loop rings into the PID's current limit (0.6 % of the samples), which the
        # anti-windup holds back, and without the limit in the model 3 samples explain that lag best; with
        # the limit (the default options, below) the delay is 2 samples as set
        assert _param(rep, "delay")["samples"] in (2, 3)
    elif effect in EXPECTED:
        key, true, tol = EXPECTED[effect]
        got = _param(rep, effect)[key]
        assert abs(got - true) <= tol * abs(true), (key, got, true)
    if effect == "saturation":  # the machine's PID has anti-windup, and so has the element found
        assert _param(rep, "saturation")["anti_windup"] is True
    if effect == "resonance":  # the free-free frequency too (it trades off with the mass split), within 5 %
        res = _param(rep, "resonance")
        assert abs(res["frequency_hz"] - 60.0) <= 0.05 * 60.0, res
        assert abs(res["table_fraction"] - 0.5) <= 0.05, res


@pytest.mark.parametrize(("effect", "expected"), [
    ("backlash", ["backlash"]),
    ("time_periodic", ["time_periodic"]),
    ("resonance", ["resonance"]),
    # the 2-sample delay makes the loop ring into the drive's real 15 A current limit (7.5 V,
    # vcnc/machines/fadal-pid.toml): saturation is there and is named second, with the PID's anti-windup
    # (the unclamped element alone took 3 samples of delay and no limit: 4.30 um held out, now 0.20 um)
    ("delay", ["delay", "saturation"]),
])
def test_default_max_effects_adds_only_what_is_there(machine, setpoints, effect, expected):
    """With the default options (up to 3 effects), the second and third rounds add an effect only
    when it lowers the pooled held-out RMS by another 25 % (and 0.05 um), no fold contradicts it
    and an element beats its own null; on single-effect captures nothing more is added (the best
    later proposal on the time_periodic capture, a resonance, gains 63 % over the reduced model
    but 0.1 % over its null, and is refused), while a physical effect the machine really has
    (the current limit) is found after the delay that exposes it."""
    from identification.diagnosis import DiagnosisOptions as Opt

    rep = _report(machine, setpoints, effect, max_effects=Opt().max_effects)
    assert rep.effects == expected, rep.rounds
    assert rep.rounds[-1]["accepted"] is None
    for rec in rep.model.effects:
        assert rec["validation_rms_after_um"] <= 0.75 * rec["validation_rms_before_um"], rec
    if "saturation" in expected:
        assert abs(_param(rep, "saturation")["limit_mm_s2"] - 7.5 * K_J) <= 0.01 * 7.5 * K_J
        assert _param(rep, "saturation")["anti_windup"] is True
    if effect == "delay":
        assert _param(rep, "delay")["samples"] == 2
    assert rep.model.validation["unexplained"]["rms_um"] < 0.5, rep.model.validation["unexplained"]


def test_saturation_of_the_bare_pid_is_found_unclamped(machine, setpoints):
    """The thesis' bare PID (``anti_windup = false``) winds its integral up at the limit: the element
    found is the unclamped one, its limit 3520 mm/s^2 on seed 1 (0.2 % off)."""
    law = dataclasses.replace(machine.axis("x").controller, anti_windup=False)
    bare = machine.with_axis_options("x", controller=law).with_effect("x", "saturation", VARIANTS["saturation"][1])
    cap = bare.simulate(setpoints, seed=1)
    rep = diagnose_report(cap, identify(cap, axis="x", diagnose=False), axis="x",
                          options=DiagnosisOptions(max_effects=1))
    assert rep.effects == ["saturation"], rep.rounds
    got = _param(rep, "saturation")
    assert got["anti_windup"] is False and "integral_lead_s" not in got
    assert abs(got["limit_mm_s2"] - 3.5 * K_J) <= 0.01 * 3.5 * K_J
    v = rep.model.validation
    assert v["rms_after_um"] <= 0.2 * v["rms_before_um"], v


@pytest.mark.parametrize("seed", [1, 2])
def test_clean_captures_report_no_effect(machine, setpoints, seed):
    rep = _report(machine, setpoints, None, seed=seed, max_effects=3)
    assert rep.effects == [], rep.rounds
    assert rep.model.effects == []
    assert rep.model.validation["rms_after_um"] == rep.model.validation["rms_before_um"]
    assert "no effect" in format_before_after(rep.model)


def test_clean_capture_of_another_program_reports_no_effect(machine):
    import toolpaths

    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(MOVES, 5.0, 6000.0, seed=7)), machine)
    cap = machine.simulate(sp, seed=5)
    rep = diagnose_report(cap, identify(cap, axis="x", diagnose=False), axis="x")
    assert rep.effects == [], rep.rounds


def test_two_effects_at_once_are_both_found(machine, setpoints):
    m = machine.with_effect("x", "time_periodic").with_effect("x", "position_periodic")
    cap = m.simulate(setpoints, seed=3)
    rep = diagnose_report(cap, identify(cap, axis="x", diagnose=False), axis="x",
                          options=DiagnosisOptions(max_effects=2))
    assert set(rep.effects) == {"time_periodic", "position_periodic"}, rep.rounds
    assert abs(_param(rep, "time_periodic")["period_s"] - 0.5) < 0.025
    assert abs(_param(rep, "position_periodic")["period_mm"] - 10.0) < 0.5
    v = rep.model.validation
    assert v["rms_after_um"] <= 0.5 * v["rms_before_um"]


def test_model_contract_table_and_simulation(machine, setpoints):
    rep = _report(machine, setpoints, "time_periodic")
    model = rep.model
    d = model_to_dict(model)
    assert d["effects"][0]["name"] == "time_periodic"
    for k in ("rms_before_um", "rms_after_um"):
        assert isinstance(d["effects"][0][k], float)
        assert isinstance(d["validation"][k], float)
    rows = before_after_rows(model)
    assert [r["label"].split(" ")[0] for r in rows] == ["reduced", "+", "final"]
    assert rows[-1]["validation_rms_um"] == model.validation["rms_after_um"]
    text = format_before_after(model)
    assert "time_periodic" in text and "valid RMS" in text and text.splitlines()[0].endswith("[um]")
    # the same errors of a rotary axis are in mdeg (vcnc.core.axes.axis_unit), not um
    rotary = dataclasses.replace(model, axis="c")
    assert format_before_after(rotary).splitlines()[0].endswith("[mdeg]")
    # the augmented model simulates like a reduced one, and survives the model file
    from identification.augmented import from_model

    ref = rep.data.xr
    y = model.simulate(ref, sample_time=rep.data.T)
    assert y.shape == ref.shape and np.all(np.isfinite(y))
    back = from_model(model_from_dict(d))
    assert np.allclose(back.simulate(ref), y, atol=1e-9)


def test_report_figure(machine, setpoints):
    rep = _report(machine, setpoints, "time_periodic")
    axes = rep.plot()
    assert len(axes) == 4
    assert "reduced model" in axes[0].get_legend_handles_labels()[1][0]
