"""The rule that starts the output-error refinement across the pair's frequency (identification.pair_starts), on a
hand-made record: the starts run whenever the equation error's valley does not pin the pair, whatever damping the
refinement ended with, and a long record's starts are refined on its first samples only.

Session 34 gated the starts on zeta >= 1, and the refinement of fadal-ppi on 15 s of corpus program 0136 ended at
0.999 on one platform (the starts skipped, 65.2 Hz kept) and at 1.001 on another (run, 39.2 Hz); coulomb35 dropped
the gate."""

from __future__ import annotations

import functools

import numpy as np
import pytest

import identification.pair_starts as ps
from identification import statistics
from identification.bounds import default_bounds
from identification.solve import solve_statistics
from identification.substeps import simulate_record
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture

T = 0.001


@functools.cache
def _record(moves: int = 6):
    """The thesis' PID x axis (FADAL_PID_X, Table 3.4) on random moves at 1 ms, its equation-error solution, and the
    fit record of a valley said not to pin the pair (the rule's input; the record's own valley is incidental)."""
    xr = random_moves_reference(moves=moves, sample_time=T, seed=7)
    x = synthetic_capture(FADAL_PID_X, xr, noise=2e-4, resolution=1e-3, seed=3).measured[:, 0]
    st = statistics(xr, x, T)
    b = default_bounds(T)
    sol = solve_statistics(st, bounds=b, sample_time=T)
    err = x - simulate_record(sol.parameters, xr, T)
    valley = {"omega_n_hz": [10.0, 80.0], "zeta": [0.3, 1.5], "p_hz": [0.5, 5.0], "identifiable": False}
    return st, sol.parameters, dict(sol.poles), err, xr, x, b, valley


def _fit(valley: dict) -> dict:
    return {"solver": {"identifiability": dict(valley)}, "output_error": {"nfev": 0, "cost_mm2": 0.0}}


def test_the_starts_run_on_either_side_of_zeta_1(monkeypatch):
    monkeypatch.setattr(ps, "PAIR_STARTS", 3)  # the rule does not depend on their number; fewer refinements
    st, params, poles, err, xr, x, b, valley = _record()
    recs = []
    for zeta in (0.999, 1.001):
        fit = _fit(valley)
        kept = ps.pair_starts(st, params, dict(poles, zeta=zeta), err, xr, x, T, b, fit)
        rec = fit["output_error"]["pair_starts"]  # absent under session 34's gate at 0.999
        rms = [f[3] for f in rec["fits"]]
        assert rec["fits"][rec["kept"]][3] == min(rms)
        assert float(np.sqrt(np.mean(kept[2] ** 2))) * 1e3 == pytest.approx(min(rms))
        assert rec["window"] == x.size  # a short record: each start refined on all of it
        assert len(rec["fits"]) == 1 + ps.PAIR_STARTS + 1  # the fit so far, the starts, the best refined fully
        recs.append(rec)
    assert recs[0]["omega_n_hz"] == recs[1]["omega_n_hz"] and len(recs[0]["omega_n_hz"]) == ps.PAIR_STARTS
    assert recs[0]["fits"][1:] == recs[1]["fits"][1:]  # the starts do not depend on the damping ended with


def test_a_pinned_valley_runs_no_start():
    st, params, poles, err, xr, x, b, valley = _record()
    fit = _fit(dict(valley, identifiable=True))
    assert ps.pair_starts(st, params, dict(poles, zeta=1.2), err, xr, x, T, b, fit)[0] is params
    assert "pair_starts" not in fit["output_error"]


def test_a_long_record_refines_its_starts_on_its_first_samples(monkeypatch):
    """A record longer than START_WINDOW: each start refined on its first START_WINDOW samples, each fit's RMS over
    the whole record, and the best of them refined fully on the whole record last."""
    st, params, poles, err, xr, x, b, valley = _record()
    window = x.size // 3
    monkeypatch.setattr(ps, "START_WINDOW", window)
    monkeypatch.setattr(ps, "PAIR_STARTS", 3)
    fit = _fit(valley)
    kept = ps.pair_starts(st, params, poles, err, xr, x, T, b, fit)
    rec = fit["output_error"]["pair_starts"]
    assert rec["window"] == window
    rms = [f[3] for f in rec["fits"]]
    assert len(rms) == 1 + len(rec["omega_n_hz"]) + 1
    assert rms[0] == pytest.approx(float(np.sqrt(np.mean(err ** 2))) * 1e3)
    assert rec["fits"][rec["kept"]][3] == min(rms) <= rms[0]
    assert float(np.sqrt(np.mean(kept[2] ** 2))) * 1e3 == pytest.approx(min(rms))
    assert rms[-1] <= min(rms[1:-1]) * (1.0 + 1e-9)  # the whole-record refinement starts from the best start
