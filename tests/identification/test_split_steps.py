"""The split form's fast paths (issue #20) change the cost of a simulation, not its result.

* The two-mass plant steps exactly (:func:`identification.augmented.two_mass_matrices`): its free
  response is the analytic one at any mode frequency, where the former explicit substeps needed 40
  per period.
* A sample over which the driven mass slides on is one exact step instead of the substeps. A tiny
  asymmetric viscous term (1e-300 1/s, a force below any double's resolution) switches that path
  off, so comparing the two runs compares the whole-sample steps with the substeps.
* The diagnosis gives the same report with one worker thread or several.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg

import toolpaths
import vcnc
from identification import identify
from identification.augmented import SUBSTEPS, augment, two_mass_matrices
from identification.diagnosis import diagnose_report
from identification.effects import Backlash, FrictionStribeck, FrictionViscousAsymmetric, Resonance
from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X, random_moves_reference

TS = 1e-3
VISCOUS = 2.55  # [1/s] plant viscous rate of the split form, as in test_effects.py


@pytest.fixture(scope="module")
def reference() -> np.ndarray:
    return random_moves_reference(moves=30, seed=4)


def test_two_mass_step_is_the_exact_free_response():
    """Undamped, frictionless modes from 5 Hz to 2 kHz: the motor-table distance after one sample
    is cos(w T) of the initial stretch (w = 2 pi f), the centre of mass does not move."""
    for f in (5.0, 60.0, 400.0, 2000.0):
        tm = two_mass_matrices(np.array([f, 0.0, 0.3, 0.0]), 0.0, TS, SUBSTEPS)
        state = np.array([1.0, 0.0, 0.0, 0.0])  # motor 1 mm ahead of the table, at rest
        xm, vm, xt, vt = tm[1][:, :4] @ state
        assert xm - xt == pytest.approx(math.cos(2 * math.pi * f * TS), abs=1e-12)
        assert 0.7 * xm + 0.3 * xt == pytest.approx(0.7, abs=1e-12)  # masses 1 - r and r
        # ten substeps make one sample
        whole = tm[1][:, :4]
        assert np.allclose(np.linalg.matrix_power(tm[0][:, :4], SUBSTEPS), whole, atol=1e-10 * np.abs(whole).max())


def test_two_mass_input_columns_are_the_zero_order_hold():
    """The input columns integrate u (on the motor) and g (against the table) held over the step."""
    f, zeta, r, c = 60.0, 0.05, 0.4, 1.5
    tm = two_mass_matrices(np.array([f, zeta, r, 0.0]), c, TS, SUBSTEPS)
    om = 2 * math.pi * f
    A = np.array([[0, 1, 0, 0],
                  [-om * om * r, -2 * zeta * om * r, om * om * r, 2 * zeta * om * r],
                  [0, 0, 0, 1],
                  [om * om * (1 - r), 2 * zeta * om * (1 - r), -om * om * (1 - r), -2 * zeta * om * (1 - r) - c / r]])
    B = np.array([[0, 0], [1 / (1 - r), 0], [0, 0], [0, -1 / r]])
    # Bd = int_0^T expm(A s) ds B, by quadrature of the matrix exponential
    s = np.linspace(0.0, TS, 2001)
    Bd = np.trapezoid([scipy.linalg.expm(A * si) for si in s], s, axis=0) @ B
    assert np.allclose(tm[1][:, 4:], Bd, rtol=1e-6, atol=1e-12)


@pytest.mark.parametrize("elements", [
    [Resonance(frequency=60.0, damping=0.05, table_fraction=0.5, measured_at="motor")],
    [Resonance(frequency=800.0, damping=0.02, table_fraction=0.3, measured_at="table")],
    [Backlash(width=0.01)],
], ids=["mode 60 Hz", "mode 800 Hz at the table", "play"])
def test_whole_sample_steps_equal_the_substeps(reference, elements):
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS)
    fast = augment(m, elements, viscous_rate=VISCOUS).simulate(reference)
    off = FrictionViscousAsymmetric(coefficient=1e-300)  # switches the whole-sample steps off
    slow = augment(m, [*elements, off], viscous_rate=VISCOUS).simulate(reference)
    assert np.all(np.isfinite(fast))
    assert np.max(np.abs(fast - slow)) < 1e-9  # mm: rounding only


def test_whole_sample_steps_with_stribeck_friction_stay_within_a_nanometre(reference):
    """With Stribeck friction the whole-sample step is taken only beyond 3 v_s, where the
    Stribeck term is below exp(-9) of its excess: the difference stays far below a micrometre."""
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=TS)
    els = [FrictionStribeck(velocity=3.0, excess_positive=200.0, excess_negative=-150.0),
           Resonance(frequency=60.0, damping=0.05, table_fraction=0.5, measured_at="motor")]
    fast = augment(m, els, viscous_rate=VISCOUS).simulate(reference)
    slow = augment(m, [*els, FrictionViscousAsymmetric(coefficient=1e-300)], viscous_rate=VISCOUS).simulate(reference)
    assert np.max(np.abs(fast - slow)) < 1e-6  # mm


@pytest.mark.slow  # two diagnoses
def test_diagnosis_is_the_same_with_one_thread_or_several(monkeypatch):
    machine = vcnc.machine("fadal-pid").with_axis_options("x", backlash=None)
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(20, 10.0, 12000.0, seed=3)), machine)
    cap = machine.with_effect("x", "backlash", None).simulate(sp, seed=2)
    model = identify(cap, axis="x", diagnose=False)
    monkeypatch.setenv("VCNC_THREADS", "1")
    one = diagnose_report(cap, model, axis="x")
    monkeypatch.setenv("VCNC_THREADS", "2")
    two = diagnose_report(cap, model, axis="x")
    assert one.effects == two.effects
    assert one.rounds == two.rounds
    assert [dict(e.parameters) for e in one.model.effects] == [dict(e.parameters) for e in two.model.effects]
