"""Held-out folds that are held out, and a diagnosis table that says which samples its numbers cover.

Captures come from the reduced model of the thesis' Fadal x axis (``identification.synthetic``, Table 3.4
parameters, Coulomb levels d0 = 441 and d1 = -302 mm/s^2) on the project's random moves, sampled at 10 ms like the
camber rig's traces, with white measurement noise of 0.5 um and a 1 um encoder. ``hold=2`` holds every second
reference sample, as a hydraulic rig's controller logged at half the record's rate (eha_processed_1_1): the
simulated velocity then falls to rounding level at every held sample, where the Coulomb level switches on its sign.
"""

from __future__ import annotations

import numpy as np
import pytest

from identification import identify
from identification.augmented import augment
from identification.diagnosis import HELD_OUT_DIFF_STEP, diagnose_report
from identification.least_squares import damped_steps
from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.capture import Capture

T = 0.01


def _capture(hold: int) -> Capture:
    xr = random_moves_reference(moves=30, span=10.0, feed=100.0, acceleration=1000.0, sample_time=T, dwell=0.1,
                                seed=3)
    if hold > 1:
        xr = np.repeat(xr[::hold], hold)[:xr.size]
    n = xr.size
    x = augment(ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T), []).simulate(xr)
    x = np.round((x + np.random.default_rng(1).normal(0.0, 0.5e-3, n)) / 1e-3) * 1e-3
    return Capture(t=np.arange(n) * T, axes=("x",), reference=xr[:, None], measured=x[:, None],
                   meta={"source": "test"})


_CACHE: dict = {}


def _report(hold: int):
    if hold not in _CACHE:
        cap = _capture(hold)
        _CACHE[hold] = (diagnose_report(cap, identify(cap, axis="x", diagnose=False), axis="x"), cap)
    return _CACHE[hold]


def test_the_coulomb_switching_leaves_the_fit_no_slope_a_small_difference_can_measure():
    # the finding behind the held-out refit's sensitivities: the output is linear in b0 between sign changes of the
    # simulated velocity, and a held reference makes b0 (its dx_r/dt term) move the velocity across zero at held
    # samples; the slope of the error that forward differences measure in b0 (step h in b0/a2, as the refit
    # searches it) then does not settle as h shrinks, and at 1e-6 (the old held-out sensitivities) it points the
    # other way from the central differences of HELD_OUT_DIFF_STEP
    rep, cap = _report(2)
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    p = rep.stages[0].train_model.parameters  # the diagnosis' fit on the active samples

    def sim(b0):
        return ReducedAxisModel(parameters=dict(p, b0=b0), sample_time=T).simulate(xr)

    y0 = sim(p["b0"])

    def slope(h, central=False):
        up = sim(p["b0"] + h * p["a2"])
        down = sim(p["b0"] - h * p["a2"]) if central else y0
        return float((up - down) @ (x - y0)) / (h * (2 if central else 1))

    forward = [slope(h) for h in (1e-6, 1e-5, 1e-4)]
    assert forward == pytest.approx([761.2, 364.1, 14.06], rel=0.02)
    assert slope(HELD_OUT_DIFF_STEP, central=True) == pytest.approx(-1.06, rel=0.02)


def test_a_held_reference_no_longer_leaves_a_fold_in_sample():
    # before: the fit sat on the edge of a step of its own error, the forward differences of 1e-6 measured the
    # step, and no Gauss-Newton step of 1 to 1/1024 lowered fold 1's training error: it kept the full fit, in
    # sample (held-out 3.32, 3.77, 3.17, 3.19 um, the other folds moved along the false slope); now every fold is
    # refitted on the others
    rep, _ = _report(2)
    assert rep.effects == [], rep.rounds
    assert [s.in_sample_folds for s in rep.stages] == [[]]
    v = rep.model.validation
    assert not any("identification error there" in w for w in v.get("warnings", []))
    got = [f["rms_before_um"] for f in v["folds"]]
    assert got == pytest.approx([1.0933, 1.0722, 0.9085, 2.2307], rel=0.02)


def test_damped_steps_run_from_gauss_newton_to_a_short_steepest_descent():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(200, 3)) * np.array([1.0, 10.0, 100.0])
    y = rng.normal(size=200)
    G, b = A.T @ A, A.T @ y
    gn, mid, far = damped_steps(G, b, (0.0, 1.0, 1e6))
    assert gn == pytest.approx(np.linalg.lstsq(A, y, rcond=None)[0], rel=1e-9)
    assert np.linalg.norm(A @ mid - y) > np.linalg.norm(A @ gn - y)
    # heavily damped: the scaled steepest descent S^-2 A'y / (lam top), shortened
    sc = np.linalg.norm(A, axis=0)
    sd = b / sc ** 2
    assert far / np.linalg.norm(far) == pytest.approx(sd / np.linalg.norm(sd), abs=1e-5)
    assert np.linalg.norm(far * sc) < 1e-5 * np.linalg.norm(gn * sc)
