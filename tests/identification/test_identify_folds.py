"""Held-out folds that are held out, and a diagnosis table that says which samples its numbers cover.

Captures come from the reduced model of the thesis' Fadal x axis (``identification.synthetic``, Table 3.4
parameters, Coulomb levels d0 = 441 and d1 = -302 mm/s^2) on the project's random moves, sampled at 10 ms like the
camber rig's traces, with white measurement noise of 0.5 um and a 1 um encoder. ``hold=2`` holds every second
reference sample, as a hydraulic rig's controller logged at half the record's rate (eha_processed_1_1): the
simulated velocity then falls to rounding level at every held sample, where the Coulomb level switches on its sign.
The truth is the fit's own prediction of a 10 ms record (``identification.substeps.simulate_record``: 10 sub-steps a
sample), which the diagnosis now predicts the record with too; the Coulomb finding below is one of the record's grid
(``grid=True``: the reduced model simulated at 10 ms).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from identification import identify
from identification.augmented import augment
from identification.dead_time import pure_delay_baseline
from identification.diagnosis import (
    HELD_OUT_DIFF_STEP,
    before_after_rows,
    diagnose_report,
    format_before_after,
    samples_note,
)
from identification.effects import PositionPeriodic
from identification.least_squares import damped_steps
from identification.reduced_model import ReducedAxisModel
from identification.substeps import simulate_record
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.capture import Capture
from vcnc.commands.identify import baseline_lines

T = 0.01


def _capture(hold: int, grid: bool = False) -> Capture:
    xr = random_moves_reference(moves=30, span=10.0, feed=100.0, acceleration=1000.0, sample_time=T, dwell=0.1,
                                seed=3)
    if hold > 1:
        xr = np.repeat(xr[::hold], hold)[:xr.size]
    n = xr.size
    if grid:
        x = augment(ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T), []).simulate(xr)
    else:
        x = simulate_record(FADAL_PID_X, xr, T)
    x = np.round((x + np.random.default_rng(1).normal(0.0, 0.5e-3, n)) / 1e-3) * 1e-3
    return Capture(t=np.arange(n) * T, axes=("x",), reference=xr[:, None], measured=x[:, None],
                   meta={"source": "test"})


_CACHE: dict = {}

#: the diagnosis' fit on the active samples of ``_capture(2, grid=True)`` when it simulated a 10 ms record on its
#: grid (session 28)
_GRID_TRAIN_MODEL = {"a1": 187.18524317228923, "a2": 44004.42882598108, "a3": 273001.01415470056,
                     "b0": 0.028657861475769097, "b1": 185.52468813476807, "b2": 44004.34376305145,
                     "d0": 246.3684833297903, "d1": -115.92467256561022}


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
    cap = _capture(2, grid=True)
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    p = _GRID_TRAIN_MODEL

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
    # at the recording's floor (0.5 um noise and a 1 um encoder: 0.58 um); 1.09, 1.07, 0.91, 2.23 um against a truth
    # simulated on the grid, which the diagnosis predicted on the grid too
    assert got == pytest.approx([0.545, 0.535, 0.591, 0.606], rel=0.02)


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



def test_damped_steps_leave_a_direction_the_training_rows_do_not_determine():
    # two parameters; the sum is seen almost only by the last 10 rows (the "held-out fold"), the difference by all
    t = np.linspace(0.0, 1.0, 100)
    A = np.column_stack([np.sin(9 * t) + np.where(t > 0.9, 1.0, 1e-3), -np.sin(9 * t) + np.where(t > 0.9, 1.0, 1e-3)])
    y = np.sin(9 * t) * 2.0 + 0.05
    train = t <= 0.9
    At, yt = A[train], y[train]
    G, b, G_all = At.T @ At, At.T @ yt, A.T @ A
    free = damped_steps(G, b, (0.0,))[0]
    assert free == pytest.approx(np.linalg.lstsq(At, yt, rcond=None)[0], rel=1e-9)
    assert free.sum() > 10.0  # the training rows' 1e-3 column fits the 0.05 offset with a large sum
    kept = damped_steps(G, b, (0.0,), reference=G_all, share=0.01)[0]
    assert abs(kept.sum()) < 1e-2  # the sum is left (nearly) where it was
    assert kept[0] - kept[1] == pytest.approx(2.0, rel=0.02)  # the difference fitted
    assert damped_steps(G, b, (0.0,), reference=G, share=0.5)[0] == pytest.approx(free, rel=1e-9)


# ------------------------------------------------------------------------------ which samples each number covers


def test_the_table_says_which_samples_each_number_covers():
    rep, cap = _report(2)
    model = rep.model
    v = model.validation
    n, active = len(cap), v["samples"]["identification"]
    assert v["samples"] == {"identification": active, "validation": active, "record": n}
    rows = before_after_rows(model)
    # the reduced model's row: its error on the active samples (the diagnosis' simulation), not the fit's
    # prediction of the capture on all samples, which the row showed before
    assert rows[0]["identification_rms_um"] == pytest.approx(rep.stages[0].identification_rms_um, rel=1e-12)
    # one model, one number: over all samples the table states the fit's prediction (10 sub-steps a sample)
    y = simulate_record(rep.reduced.parameters, cap.reference[:, 0], T)
    assert rows[0]["record_rms_um"] == pytest.approx(1e3 * np.sqrt(np.mean((cap.measured[:, 0] - y) ** 2)), rel=1e-9)
    assert rows[0]["record_rms_um"] == pytest.approx(rep.reduced.fit["rms_um"], rel=1e-9)
    text = format_before_after(model)
    assert text.splitlines()[0].split()[:4] == ["model", "all", "RMS", "ident"]
    assert (f"samples: 'all' the record's {n}; 'ident' and 'valid' its {active} active ones (idle stretches, where an "
            "axis at rest is predicted for free, trimmed with a 0.2 s margin), 'valid' each fold's predicted by the "
            "model refitted on the others; all simulated as the fit predicts the record, on 10 sub-steps a sample "
            "(the reference between its samples a cubic spline; an element's sampled controller at the sub-steps)"
            ) in text
    assert samples_note(rep.reduced) == ""  # an undiagnosed model has no table
    # a model file written before the 'all' column names no record count (it printed "the record's ?")
    old = dataclasses.replace(model, validation={**v, "samples": {"identification": active, "validation": active}})
    assert samples_note(old).startswith(f"samples: 'ident' and 'valid' its {active} active ones")


def test_the_naive_predictions_of_the_active_samples_judge_the_held_out_error():
    rep, cap = _report(2)
    naive = rep.model.validation["naive_active"]
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    mask = np.zeros(len(cap), bool)
    mask[100:600] = True
    whole = pure_delay_baseline(xr[100:600], x[100:600], T)
    part = pure_delay_baseline(xr, x, T, mask=mask)
    # inside the stretch the shifted reference is the record's own, not the stretch's first value held
    assert part["following_error_rms_um"] == pytest.approx(whole["following_error_rms_um"], rel=1e-12)
    assert part["pure_delay_samples"] == whole["pure_delay_samples"]
    assert pure_delay_baseline(xr, x, T, mask=np.ones(len(cap), bool)) == pure_delay_baseline(xr, x, T)
    held = rep.model.validation["rms_after_um"]
    assert held < naive["pure_delay_rms_um"]
    lines = baseline_lines(cap, rep.model, "x")
    assert not any(line.startswith("warning:") for line in lines)
    assert lines[0].endswith(f"; on the {rep.model.validation['samples']['identification']} active samples the "
                             f"held-out errors cover: following error {naive['following_error_rms_um']:.4g} um, best "
                             f"pure delay {naive['pure_delay_rms_um']:.4g} um, the model held out {held:.4g} um")
    worse = dataclasses.replace(rep.model, validation=dict(rep.model.validation, naive_active=dict(
        naive, following_error_rms_um=0.5 * held, pure_delay_rms_um=0.9 * held)))
    line = [s for s in baseline_lines(cap, worse, "x") if s.startswith("warning:")]
    assert line == [f"warning: on its held-out folds the model predicts worse ({held:.4g} um rms) than the commanded "
                    f"position itself ({0.5 * held:.4g} um on the same active samples): what it fitted does not carry "
                    "over to motion it was not fitted on; do not take its poles as the loop's"]


def test_a_load_at_the_rest_position_wakes_coulomb_levels_that_act_as_a_constant_load():
    # why the diagnosis also refuses an effect that raises the error on the whole record (idle stretches
    # included): a SINUMERIK trace's reduced fit had d0 ~ d1 ~ 3e5 mm/s^2 (the same sign: a load, not a friction),
    # harmless while the model rests exactly (v == 0: the Coulomb level is off), and its position-periodic load of
    # 1177 mm/s^2 at the starting position made the model chatter by 0.75 mm before the first move
    xr = np.concatenate([np.zeros(400), random_moves_reference(moves=4, span=10.0, feed=100.0, acceleration=1000.0,
                                                               sample_time=T, seed=3)])
    params = dict(FADAL_PID_X, d0=3e5, d1=3e5)
    reduced = augment(ReducedAxisModel(parameters=params, sample_time=T), [])
    loaded = augment(reduced, [PositionPeriodic(period=12.4, coefficients=((0.0, 1177.0),))])
    assert np.max(np.abs(reduced.simulate(xr)[:400])) == 0.0
    assert np.max(np.abs(loaded.simulate(xr)[:400])) == pytest.approx(7.4147, rel=1e-3)  # mm, before the first move
    # the same load on a model whose Coulomb levels are a friction's (opposite signs) stays within micrometres
    mild = augment(augment(ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T), []),
                   [PositionPeriodic(period=12.4, coefficients=((0.0, 1177.0),))])
    assert np.max(np.abs(mild.simulate(xr)[:400])) == pytest.approx(0.02978, rel=1e-3)
