"""Machines with one effect changed, and machines with external (non-compiled) axes."""

from __future__ import annotations

import numpy as np
import pytest

import drives
from interpolators.limits import AxisLimits
from vcnc.engine.machine import EFFECTS, Machine, load_machine
from vcnc.errors import InputError, MachineError
from vcnc.setpoints import Setpoints

BASE = load_machine("fadal-pid")


def _moves(m: Machine, n: int = 3000) -> Setpoints:
    t = np.arange(n) * m.sample_time
    x = 4.0 * np.sin(2 * np.pi * 0.7 * t) + 1.0 * np.sin(2 * np.pi * 3.1 * t)
    return Setpoints.from_positions(x, sample_time=m.sample_time)


@pytest.mark.parametrize("effect", EFFECTS)
def test_every_effect_changes_the_response(effect: str) -> None:
    base = BASE.with_axis_options("x", noise=None)
    m = base.with_effect("x", effect)
    assert m.name.startswith("fadal-pid") and m.name.endswith(f"+{effect}")
    sp = _moves(base)
    a, b = base.simulate(sp), m.simulate(sp)
    diff = max(np.max(np.abs(a.measured - b.measured)), np.max(np.abs(a.table - b.table)))
    assert diff > 2e-4, f"{effect} changed the measured or table position by only {diff} mm"
    assert np.all(np.isfinite(b.measured))
    # the base machine is untouched (frozen records)
    assert base.axis("x") is not m.axis("x")


def test_with_axis_options_shorthands_and_removal() -> None:
    m = BASE.with_axis_options("x", backlash=0.02, noise=None, delay=1, drift=1e-4, encoder=1e-3)
    ax = m.axis("x")
    assert ax.backlash == drives.Backlash(width=0.02)
    assert ax.noise is None and ax.delay.samples == 1 and ax.drift.rate == 1e-4
    assert ax.encoder.resolution == 1e-3
    assert BASE.axis("x").backlash.width == 0.003
    with pytest.raises(MachineError, match="resolution"):
        BASE.with_axis_options("x", encoder=-1.0)


def test_effect_parameters_override_and_errors() -> None:
    m = BASE.with_effect("x", "resonance", {"frequency_hz": 90.0, "damping": 0.02})
    assert m.axis("x").resonance.frequency_hz == 90.0
    with pytest.raises(MachineError, match="unknown effect"):
        BASE.with_effect("x", "gremlins")
    with pytest.raises(MachineError, match="unknown parameter"):
        BASE.with_effect("x", "backlash", {"widht_mm": 0.1})


class _Follower:
    """An external axis: a first-order lag of the reference."""

    limits = AxisLimits(velocity=100.0, acceleration=1000.0, jerk=1e5)

    def simulate_reference(self, reference: np.ndarray, sample_time: float) -> np.ndarray:
        out = np.empty_like(reference)
        y = reference[0]
        for k, r in enumerate(reference):
            out[k] = y
            y += 0.1 * (r - y)
        return out


def test_external_axes() -> None:
    m = Machine.from_axes({"x": BASE.axis("x"), "y": _Follower()}, sample_time=0.001, name="mixed")
    assert m.axes == ("x", "y") and m.limits["y"].velocity == 100.0
    pos = np.c_[np.linspace(0, 1, 500), np.linspace(0, 2, 500)]
    cap = m.simulate(Setpoints.from_positions(pos, sample_time=0.001, axes=("x", "y")), seed=2)
    np.testing.assert_allclose(cap.measured[:, 1], _Follower().simulate_reference(pos[:, 1], 0.001))
    assert cap.control is None and cap.meta["machine"] == "mixed" and cap.meta["seed"] == 2


def test_simulate_input_checks() -> None:
    with pytest.raises(InputError, match="sample_time"):
        BASE.simulate(Setpoints.from_positions(np.zeros(10), sample_time=0.002))
    with pytest.raises(InputError, match="does not have"):
        BASE.simulate(Setpoints.from_positions(np.zeros((10, 1)), sample_time=0.001, axes=("z",)))
    with pytest.raises(MachineError, match="no axis"):
        BASE.axis("z")


def test_capture_contract() -> None:
    sp = _moves(BASE, 500)
    cap = BASE.simulate(sp, seed=5)
    assert cap.meta == {"machine": "fadal-pid", "seed": 5, "sample_time": 0.001}
    assert cap.path is sp.path
    for name in ("measured", "table", "velocity", "control", "friction"):
        assert getattr(cap, name).shape == (500, 1)
    assert np.max(np.abs(cap.control)) <= 7.5  # 15 A / 2 A/V
    # the true position of the measured point: the reading without noise (0.1 um) and 0.25 um steps
    true = cap.aux["measured_true"]
    assert true.shape == (500, 1)
    err = cap.measured - true
    assert 0.0 < np.std(err) < 5e-4 and np.max(np.abs(err)) < 2e-3
    clean = BASE.with_axis_options("x", noise=None, encoder=None).simulate(sp)
    np.testing.assert_array_equal(clean.measured, clean.aux["measured_true"])
    # a table scale records the table: its true position is the table's
    scale = BASE.with_axis_options("x", measurement="table", backlash=0.01).simulate(sp)
    np.testing.assert_array_equal(scale.aux["measured_true"], scale.table)


def test_unstable_loop_reports_divergence() -> None:
    import controllers
    from vcnc.errors import SimulationError

    m = BASE.with_axis_options("x", controller=controllers.PID(kp=5000.0, kd=0.0), saturation=None, dac=None)
    with pytest.raises(SimulationError, match="diverged"):
        m.simulate(_moves(BASE, 2000))
