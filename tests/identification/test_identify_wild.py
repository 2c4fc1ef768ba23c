"""Findings of the audit of ``vcnc identify`` on real traces (session 27, identwild), each on a small synthetic case.

The traces (halscope, TNCscope, a hydraulic rig's logger, a 100 ms CNC log, EMPS) are not in the repository; the
cases below reproduce what went wrong on them: a record cropped in motion whose first rest came after its last move
(a TNCscope trace: "regressor column 'v_r' is zero at every sample"), a model no better than the commanded position
delayed (a 100 ms CNC log: 190 um for 207 um of following error, 218 um held out), a drift advice repeated after the
drift was tried and predicted worse, a bound advice about p for a damping on its bound, a dead-time line whose
numbers were not the final prediction's, and poles named as omega_n, zeta, p only.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from identification import identify
from identification.capture_checks import check_jumps
from identification.dead_time import pure_delay_baseline
from identification.diagnosis import bound_advice, drift_advice, in_sample_warnings
from identification.reduced_model import ReducedAxisModel
from identification.segments import settled_start
from identification.synthetic import FADAL_PID_X, synthetic_capture
from vcnc.commands.identify import baseline_lines, bound_lines, closed_loop_poles_line, delay_lines
from vcnc.core.capture import Capture
from vcnc.errors import IdentificationError

T = 1e-3
KEYS = ("a1", "a2", "a3", "b0", "b1", "b2", "d0", "d1")


def _model(fit: dict, *, validation: dict | None = None, parameters: dict | None = None) -> ReducedAxisModel:
    model = ReducedAxisModel(parameters=parameters or dict.fromkeys(KEYS, 1.0), sample_time=T, axis="x")
    return dataclasses.replace(model, fit=fit, validation=validation)


def _steps(*runs: tuple[int, float]) -> np.ndarray:
    """A reference from (samples, speed mm/s) runs, integrated at T."""
    return np.cumsum(np.concatenate([np.full(n, v) for n, v in runs])) * T


def test_pure_delay_baseline_finds_the_whole_sample_lag():
    xr = _steps((100, 0.0), (400, 20.0), (200, 0.0), (400, -20.0), (100, 0.0))
    x = np.concatenate([np.zeros(7), xr[:-7]])  # the reference 7 samples late, at rest before
    base = pure_delay_baseline(xr, x, T)
    assert base["pure_delay_samples"] == 7
    assert base["pure_delay_s"] == 7 * T
    assert base["pure_delay_rms_um"] == 0.0
    assert abs(base["following_error_rms_um"] - float(np.sqrt(np.mean((xr - x) ** 2))) * 1e3) < 1e-9
    assert 100.0 < base["following_error_rms_um"] < 150.0  # 20 mm/s x 7 ms = 140 um while moving


def _capture(xr: np.ndarray, x: np.ndarray) -> Capture:
    return Capture(t=np.arange(xr.size) * T, axes=("x",), reference=xr[:, None], measured=x[:, None], source="t.csv")


def test_a_model_no_better_than_a_pure_delay_is_called_so():
    xr = _steps((100, 0.0), (400, 20.0), (200, 0.0), (400, -20.0), (100, 0.0))
    x = np.concatenate([np.zeros(7), xr[:-7]])
    lines = baseline_lines(_capture(xr, x), _model({"rms_um": 50.0}), "x")
    assert lines[0].startswith("naive predictions of the capture: the commanded position itself rms ")
    assert "delayed by 7 samples (0.007 s) rms 0 um" in lines[0]
    assert lines[1] == ("warning: the model predicts the capture (50 um rms) no better than the commanded position "
                        "delayed by a whole number of samples (0 um): it has learnt nothing of the loop's dynamics "
                        "from this record (sampled slower than the loop responds, or a measured channel that is not "
                        "the loop's?); do not take its poles as the loop's")


def test_a_model_worse_than_the_following_error_on_held_out_folds_is_called_so():
    # the 100 ms CNC log: identification 190 um, held out 218 um, raw following error 207 um, no lag to find
    xr = _steps((10, 0.0), (400, 20.0), (10, 0.0), (400, -20.0), (10, 0.0))
    x = xr + 0.2 * np.sin(np.arange(xr.size))  # 141 um RMS of following error that no shift explains
    model = _model({"rms_um": 100.0, "max_um": 200.0}, validation={"rms_before_um": 180.0, "max_before_um": 300.0})
    model = dataclasses.replace(model, effects=[])
    lines = baseline_lines(_capture(xr, x), model, "x")
    assert lines[0] == ("naive predictions of the capture: the commanded position itself rms 141.4 um (the following "
                        "error), and no whole-sample delay of it predicts better; the model predicts 1.41 times better")
    assert lines[1] == ("warning: on its held-out folds the model predicts worse (180 um rms) than the commanded "
                        "position itself (141.4 um): what it fitted does not carry over to motion it was not fitted "
                        "on; do not take its poles as the loop's")


def test_a_model_that_beats_the_baselines_gets_no_warning():
    xr = _steps((100, 0.0), (400, 20.0), (200, 0.0), (400, -20.0), (100, 0.0))
    x = np.concatenate([np.zeros(7), xr[:-7]]) + 1e-3 * np.cos(np.arange(xr.size))
    lines = baseline_lines(_capture(xr, x), _model({"rms_um": 0.1}), "x")
    assert len(lines) == 1
    assert lines[0].endswith("rms 0.7071 um; the model predicts 7.07 times better")


def test_a_rest_after_the_last_move_is_not_a_start():
    # cropped 0.1 s into a move that reverses at once, then rests: the first rest leaves no motion after it
    xr = _steps((200, 20.0), (400, -20.0), (2000, 0.0))
    assert settled_start(xr, xr.copy()) is None
    # with a move both ways after the rest, the rest is where the simulation may start
    xr2 = _steps((200, 20.0), (300, 0.0), (400, 20.0), (400, -20.0), (100, 0.0))
    assert settled_start(xr2, xr2.copy()) == 199  # the step from sample 199 to 200 is the first that stays
    # a record that starts at rest starts there, whatever follows
    assert settled_start(_steps((50, 0.0), (400, 20.0), (2000, 0.0)), _steps((50, 0.0), (400, 20.0), (2000, 0.0))) == 0


def test_a_trace_cropped_in_motion_before_its_last_rest_is_identified():
    # a TNCscope trace cropped in motion failed: "regressor column 'v_r' ... is zero at every sample"
    v = np.concatenate([np.zeros(300), np.full(300, 20.0), np.full(400, -20.0), np.zeros(2000)])
    cap = synthetic_capture(FADAL_PID_X, np.cumsum(v) * T, sample_time=T)
    crop = cap.slice(400, cap.t.size)
    crop = dataclasses.replace(crop, t=crop.t - crop.t[0], source="crop.csv")
    model = identify(crop, diagnose=False)
    assert abs(model.poles["omega_n_hz"] - 32.9995) < 1e-3
    assert abs(model.poles["zeta"] - 0.44680) < 1e-4
    assert abs(model.poles["p_hz"] - 1.17293) < 1e-4
    assert model.fit["rms_um"] < 1e-3


def test_drift_advice_follows_what_the_fit_tried():
    assert drift_advice({}).endswith("vcnc identify --drift remove takes it out before the fit")
    tried = {"drift": {"named": True, "removed": False, "rms_kept_um": 474.3, "rms_removed_um": 527.1}}
    assert drift_advice(tried) == ("; the measured channel's drift was tried out of the fit and predicts 474.3 -> "
                                   "527.1 um, not twice better: this trend in time is not a drift the fit can be freed "
                                   "of, and the model does not explain it")
    assert "remains after the measured channel's drift was taken out" in drift_advice({"drift": {"removed": True}})


def test_bound_advice_names_the_bound_that_binds():
    assert bound_advice(["p_hz = 0.2 at its lower bound"]) == (
        "widen the bounds if the loop has no integral action (p -> 0)")
    zeta = bound_advice(["zeta = 0.2 at its lower bound"])
    assert "p -> 0" not in zeta
    assert zeta.startswith("move a zeta or omega_n bound only where the loop is known to lie beyond it")


def test_closed_loop_poles_are_named_as_the_loop_has_them():
    w = 2 * np.pi
    wn, zeta, p = 16.29 * w, 1.29, 0.7654 * w  # a TNCscope trace's fit: zeta > 1, three real poles
    over = {"a1": 2 * zeta * wn + p, "a2": wn * wn + 2 * zeta * wn * p, "a3": wn * wn * p}
    model = _model({}, parameters={**dict.fromkeys(KEYS, 1.0), **over})
    assert closed_loop_poles_line(model) == "closed-loop poles: 0.7654 Hz (real), 7.739 Hz (real), 34.29 Hz (real)"
    wn, zeta, p = 20.32 * w, 0.3874, 0.001 * w  # EMPS: a complex pair is named once
    pair = {"a1": 2 * zeta * wn + p, "a2": wn * wn + 2 * zeta * wn * p, "a3": wn * wn * p}
    model = _model({}, parameters={**dict.fromkeys(KEYS, 1.0), **pair})
    assert closed_loop_poles_line(model) == "closed-loop poles: 0.001 Hz (real), 20.32 Hz (pair, damping 0.387)"


def test_an_unused_shift_names_the_models_it_compared():
    # a hydraulic rig: the final model predicts 127 um; the shift's comparison is of exact-solver models
    fit = {"delay": {"estimated": True, "samples": 245.0, "objective_ratio": 0.226, "rms_without_um": 513.0,
                     "rms_with_um": 1296.0, "delay_s": 0.0}}
    assert delay_lines(_model(fit)) == [
        "reference dead time: 0 s (0 samples; estimated 245 samples (objective ratio 0.226), prediction 513 -> 1296 "
        "um with the shift; not used: the exact-solver model fitted on the shifted reference predicts 1296 for 513 "
        "without the shift, not twice better (both before the output-error refinement; the final prediction is the "
        "one above))"]


def test_p_on_the_widened_bound_is_a_loop_without_integral_action():
    # EMPS, a LinuxCNC halscope trace: p on the 1 mHz bound the fit opened was a warning to move the bound
    box = {"p_hz": (0.001, 500.0), "omega_n_hz": (0.2, 500.0), "zeta": (0.2, 2.0)}
    model = dataclasses.replace(_model({}), poles={"omega_n_hz": 20.32, "zeta": 0.3874, "p_hz": 0.001}, bounds=box)
    assert bound_lines(model) == ["p 0.001 Hz sits on the widened lower bound of its box: the loop shows no integral "
                                  "action (p -> 0, a proportional position loop such as EMPS'; the slow pole is slower "
                                  "than this record can tell and the model predicts as reported)"]
    thesis = dataclasses.replace(model, poles={"omega_n_hz": 20.32, "zeta": 0.3874, "p_hz": 0.2},
                                 bounds={**box, "p_hz": (0.2, 500.0)})
    assert bound_lines(thesis) == ["warning: p 0.2 Hz sits on the lower bound of its box: the box, not the data, "
                                   "placed it there (move the bound with --p-min-hz)"]


def test_in_sample_folds_are_named():
    # EMPS and a TNCscope trace: every fold fell back to the full fit, its "held-out" RMS equal to the identification's
    assert in_sample_warnings([], None) == []
    assert in_sample_warnings([0, 1, 2, 3], None) == [
        "the reduced model's held-out error on folds 1, 2, 3, 4 is its identification error there: no refit on the "
        "other folds lowered their error, so it is no out-of-sample check"]
    assert in_sample_warnings([], [2]) == [
        "the final model's held-out error on fold 3 is its identification error there: no refit on the other "
        "folds lowered their error, so it is no out-of-sample check"]


def test_a_burst_of_vibration_is_no_jump_but_a_lasting_step_is():
    # a SINUMERIK emergency-braking trace: +-10 um per 2 ms sample at 105 mm/s for 50 ms, refused as a 12 um jump
    xr = 50.0 * (1.0 - np.cos(2.0 * np.pi * np.arange(2400) * T / 2.4))  # up to 131 mm/s, smooth
    x = np.concatenate([np.zeros(6), xr[:-6]])
    burst = x.copy()
    burst[1200:1206] += np.array([0.0, -0.012, 0.002, -0.010, 0.001, 0.0])  # the position dips and comes back
    check_jumps(xr, burst, T, "x", "trace.xml")
    lasting = x.copy()
    lasting[1200:] -= 0.012  # a glitch that shifts the position for good (less its neighbours' median step)
    with pytest.raises(IdentificationError, match=r"trace.xml: axis 'x': the measured position jumps by -0.01166 mm "
                                                  r"at sample 1200"):
        check_jumps(xr, lasting, T, "x", "trace.xml")
