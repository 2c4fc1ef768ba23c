"""Diagnosis effects at their realistic defaults, and where a capture observes the axis."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.engine.machine import load_machine, reference_control
from vcnc.errors import MachineError
from vcnc.setpoints import Setpoints

BASE = load_machine("fadal-pid").with_axis_options("x", backlash=None)


def _moves(n: int = 2000) -> Setpoints:
    ts = BASE.sample_time
    t = np.arange(n) * ts
    x = 4.0 * np.sin(2 * np.pi * 0.7 * t) + 1.0 * np.sin(2 * np.pi * 3.1 * t)
    return Setpoints.from_positions(x, sample_time=ts)


SP = _moves()


def test_measurement_table_records_the_table_scale_and_keeps_the_loop_on_the_encoder() -> None:
    clean = BASE.with_axis_options("x", noise=None, encoder=None, drift=1e-3)
    fb = clean.simulate(SP)
    scale = clean.with_axis_options("x", measurement="table").simulate(SP)
    # same loop (closed on the drifting motor encoder), only the recorded signal differs
    np.testing.assert_array_equal(fb.table, scale.table)
    np.testing.assert_array_equal(scale.measured, scale.table)
    t = SP.t
    # the feedback reading is the table plus the drift: the loop holds it on the command
    np.testing.assert_allclose(fb.measured[:, 0] - fb.table[:, 0], 1e-3 * t, atol=1e-12)
    # with noise and encoder, the scale has its own noise draw and the same resolution
    noisy = BASE.with_axis_options("x", measurement="table").simulate(SP, seed=3)
    res = BASE.axis("x").encoder.resolution
    assert np.allclose(noisy.measured / res, np.round(noisy.measured / res), atol=1e-6)
    assert 0 < np.std(noisy.measured - noisy.table) < 5 * BASE.axis("x").noise.std + res
    with pytest.raises(MachineError, match="measurement"):
        BASE.with_axis_options("x", measurement="laser")


def test_default_measurement_is_unchanged() -> None:
    a = BASE.simulate(SP, seed=2)
    b = BASE.with_axis_options("x", measurement="feedback").simulate(SP, seed=2)
    np.testing.assert_array_equal(a.measured, b.measured)
    assert BASE.axis("x").measurement == "feedback"


def test_drift_effect_is_visible_in_measured_and_old_behaviour_is_available() -> None:
    clean = BASE.with_axis_options("x", noise=None)
    ref = clean.simulate(SP)
    m = clean.with_effect("x", "drift")
    assert m.axis("x").measurement == "table" and m.axis("x").feedback == "motor"
    cap = m.simulate(SP)
    rate = m.axis("x").drift.rate
    shift = cap.measured[-200:, 0] - ref.measured[-200:, 0]
    np.testing.assert_allclose(shift, -rate * SP.t[-200:], atol=3e-4)  # encoder counts of 0.25 um
    old = clean.with_effect("x", "drift", {"measurement": "feedback"})
    assert old.axis("x").measurement == "feedback"
    cap_old = old.simulate(SP)
    assert np.max(np.abs(cap_old.measured - ref.measured)) <= 2.6e-4
    with pytest.raises(MachineError, match="measurement"):
        clean.with_effect("x", "drift", {"measurement": "motor"})


def test_backlash_effect_puts_the_play_where_measured_sees_it() -> None:
    m = BASE.with_effect("x", "backlash")
    assert m.axis("x").feedback == "table" and m.axis("x").backlash.width == 0.01
    semi = BASE.with_effect("x", "backlash", {"feedback": "motor"}).axis("x")
    assert (semi.feedback, semi.measurement) == ("motor", "table")
    keep = BASE.with_effect("x", "backlash", {"feedback": "axis"}).axis("x")
    assert (keep.feedback, keep.measurement) == ("motor", "feedback")
    clean = BASE.with_axis_options("x", noise=None)
    base_cap = clean.simulate(SP)
    for params, visible in (({}, True), ({"feedback": "motor"}, True), ({"feedback": "axis"}, False)):
        cap = clean.with_effect("x", "backlash", params).simulate(SP)
        diff = np.max(np.abs(cap.measured - base_cap.measured))
        assert (diff > 2e-3) == visible, (params, diff)
    with pytest.raises(MachineError, match="feedback"):
        BASE.with_effect("x", "backlash", {"feedback": "scale"})


def test_saturation_default_saturates_a_few_percent_of_the_reference_test() -> None:
    ax = BASE.axis("x")
    u = np.abs(reference_control(ax, BASE.sample_time))
    lim = BASE.with_effect("x", "saturation").axis("x").control_limit()
    assert 0.7 * u.max() < lim < u.max()
    assert 0.025 <= np.mean(u > lim) <= 0.035
    assert BASE.with_effect("x", "saturation", {"voltage_limit_v": 3.5}).axis("x").control_limit() == 3.5
    lim5 = BASE.with_effect("x", "saturation", {"saturated_fraction": 0.05}).axis("x").control_limit()
    assert lim5 < lim
    with pytest.raises(MachineError, match="not both"):
        BASE.with_effect("x", "saturation", {"voltage_limit_v": 3.5, "saturated_fraction": 0.05})


def test_stribeck_default() -> None:
    f = BASE.with_effect("x", "friction_stribeck").axis("x").friction
    assert f.static_positive == pytest.approx(2.0 * f.coulomb_positive)
    assert f.stribeck_velocity == 5.0


def test_machine_file_measurement_key() -> None:
    from vcnc.engine.machine import Machine, builtin_machine_text

    text = builtin_machine_text("fadal-pid").replace(
        'feedback = "motor"          # rotary encoder on the motor (semi-closed loop)\n\n[axes.x.limits]',
        'feedback = "motor"\nmeasurement = "table"\n\n[axes.x.limits]',
    )
    m = Machine._from_text(text, file="<test>", default_name="t")
    assert m.axis("x").measurement == "table" and m.axis("y").measurement == "feedback"
    with pytest.raises(MachineError, match="measurement"):
        Machine._from_text(text.replace('measurement = "table"', 'measurement = "laser"'), file="<test>",
                           default_name="t")
