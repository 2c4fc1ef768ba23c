"""A drift of the measured channel against the commanded one: estimated, named, and removed when it matters.

Thermal growth moves a position measured beside the loop's own encoder (a linear scale, a laser, a
probe on the table while the drive closes on its motor's encoder) by some um per minute, and an offset
between the channels may creep as a machine warms up. The reduced model of Eq. (3.3) settles at the
reference and has no term for it: fitted as it is, fadal-pid's capture with 100 um/min on its measured
channel gave p 0.02 Hz for 1.14 Hz (2.12 um RMS for 0.75), with 20 um/s p on its bound. The
diagnosis' ``drift`` effect (:class:`identification.effects.Drift`) does not undo that: it is proposed
after the fit, whose slow pole already imitates the drift, so it lowers the held-out error too little
to be kept ("no effect lowers the held-out error significantly" at 120 um/min).

:func:`estimate_drift` takes the drift from the regression of Eq. (3.11), as
:func:`identification.datum_offset.estimate_offset` takes an offset; :func:`measured_drift` runs it in a
fitted model's loop frame (its dead time and datum offset; a recorded lead misfits the regression and
bends the polynomial by hundreds of um); :func:`identification.pipeline.identify` records it in
``fit.drift`` (:func:`drift_record`) and, by default when the drift is large against the prediction error
and its removal predicts twice better, takes it off the measured channel and fits again
(:func:`fit_with_drift`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from identification.capture_checks import NO_INTEGRAL_P_HZ
from identification.loop_frame import loop_frame, offset_of
from identification.regressor import RegressorOptions, regressor
from vcnc.core.capture import Capture
from vcnc.core.errors import IdentificationError

__all__ = ["estimate_drift", "measured_drift", "drift_curve", "without_drift", "drift_record", "fit_with_drift",
           "drift_left_in",
           "DRIFT_MODES", "DRIFT_DEGREE", "DRIFT_RATIO", "MIN_DRIFT_UM", "DRIFT_GAIN"]

#: Degree of the polynomial in time a drift is estimated as (:func:`estimate_drift`): a ramp and its bend,
#: enough for thermal growth over a record of seconds to minutes, linear or settling.
DRIFT_DEGREE = 2
#: A drift is named (``fit.drift.named``) when it moves the measured channel, over the record, by at least
#: this many times the model's prediction RMS [-]: fadal-pid with 100 um/min (13.1 um over 7.9 s, p fitted
#: at 0.02 Hz for 1.14, 2.12 um RMS): 6.2, with an offset settling by 10 um (time constant 3 s; p 0.07
#: Hz): 4.1; fadal-ppi's harness capture with that settling offset (p on its 0.2 Hz bound, 3.43 um): 2.3,
#: with 10 um/min (its pair 7 % off): 1.7; the records of ``benchmarks/recorded_traces.py`` without a
#: drift at most 0.4.
DRIFT_RATIO = 1.5
#: ... and when it moves it by at least this much [um] (mdeg on a rotary axis): a record without noise is
#: predicted to within numerical error (the exact model of ``tests/identification/test_trace_pathologies.py``:
#: 2e-7 um RMS) and a smaller estimate (0.03 um there, at most 0.31 um on the records of
#: ``benchmarks/recorded_traces.py`` without a drift) is then many times its RMS; a drift this small does not
#: bend the fit of a record with noise (fadal-pid with 1 um/min, 0.13 um: its poles as without).
MIN_DRIFT_UM = 0.5
#: Least ratio of prediction RMS (the drift kept / removed) for ``drift="auto"`` to remove a named drift [-], as
#: for a datum offset (:data:`identification.datum_offset.MIN_GAIN`): fadal-pid with 100 um/min 2.12 -> 0.754 um,
#: with an offset settling by 10 um 1.95 -> 0.776 um.
DRIFT_GAIN = 2.0
#: What :func:`fit_with_drift` does with the drift: remove it when it is named and its removal predicts
#: :data:`DRIFT_GAIN` times better, always, or never (only record it).
DRIFT_MODES = ("auto", "remove", "keep")


def estimate_drift(reference: np.ndarray, measured: np.ndarray, sample_time: float, *,
                   options: RegressorOptions | None = None, degree: int = DRIFT_DEGREE
                   ) -> np.polynomial.Polynomial:
    """The drift of ``measured`` against ``reference`` [mm] as a polynomial in the time from the first
    sample [s], 0 there: a slow offset that grows over the record (thermal growth of a scale or laser
    logged beside the loop's own encoder).

    The regression of Eq. (3.11) with a polynomial in time beside its columns, as
    :func:`identification.datum_offset.estimate_offset` takes a constant one: a measured position
    ``x + d(t)`` with ``d = sum_j c_j t^j`` turns the measured velocity into ``v + d'``, the acceleration
    into ``a + d''`` and the integrated tracking error into ``e_i - int d``, so
    ``Y = theta^T Phi + d + alpha_i int d + alpha_1 d' + alpha_2 d''`` holds exactly: a polynomial of
    one degree more, whose coefficients are linear in the ``c_j`` given the fitted ``alpha``. Its
    coefficients are fitted beside theta, and the ``c_j`` solved from them by
    least squares (the constant is the datum offset's, left out). On fadal-pid's capture with a drift of
    100 um/min (13.2 um over its 7.9 s) it finds 13.1 um; with none, under 0.5 um. The reference must be in
    the loop's frame (its dead time removed): a recorded lead misfits the regression, and the misfit bends
    the polynomial (hundreds of um).
    """
    phi, y = regressor(reference, measured, sample_time, options=options)
    n_rows = y.size
    duration = max((np.asarray(reference).size - 1) * sample_time, sample_time)
    skip = (np.asarray(reference).size - n_rows) // 2  # rows whose differences need samples outside
    tau = (np.arange(n_rows) + skip) * sample_time / duration
    a = np.column_stack([phi] + [tau ** j for j in range(degree + 2)])
    scale = np.linalg.norm(a, axis=0)
    scale[scale == 0.0] = 1.0
    coef = np.linalg.lstsq(a / scale, y, rcond=None)[0] / scale
    alpha_i, alpha_1, alpha_2 = coef[0], coef[1], coef[2]
    # d = sum c_j tau^j (tau = t / duration): int d dt, d', d'' in powers of tau
    mapping = np.zeros((degree + 2, degree + 1))
    for j in range(degree + 1):
        mapping[j, j] += 1.0
        mapping[j + 1, j] += alpha_i * duration / (j + 1)
        if j >= 1:
            mapping[j - 1, j] += alpha_1 * j / duration
        if j >= 2:
            mapping[j - 2, j] += alpha_2 * j * (j - 1) / duration ** 2
    c = np.linalg.lstsq(mapping, coef[phi.shape[1]:], rcond=None)[0]
    c[0] = 0.0  # the constant is the datum offset's (estimate_offset)
    return np.polynomial.Polynomial(c / duration ** np.arange(c.size))


def measured_drift(capture: Capture, model, axis: str) -> np.polynomial.Polynomial:
    """The drift [mm] of ``axis``' measured channel against the commanded one, a polynomial in the time from
    ``capture``'s first sample [s] (0 there), estimated in the fitted ``model``'s loop frame
    (:func:`estimate_drift`)."""
    framed, _ = loop_frame(capture, axis, offset_mm=offset_of(model.fit),
                           delay_samples=model.delay_s / model.sample_time)
    i = framed.axis_index(axis)
    poly = estimate_drift(framed.reference[:, i], framed.measured[:, i], model.sample_time)
    moved = poly(np.polynomial.Polynomial([float(capture.t[0] - framed.t[0]), 1.0]))  # from the capture's start
    return moved - moved(0.0)


def drift_curve(capture: Capture, drift: np.polynomial.Polynomial | list) -> np.ndarray:
    """The drift [mm] at each sample of ``capture``: ``drift`` a polynomial as :func:`measured_drift` gives, or
    its coefficients as ``fit.drift.polynomial_mm`` holds them."""
    poly = drift if isinstance(drift, np.polynomial.Polynomial) else np.polynomial.Polynomial(drift)
    return poly(np.asarray(capture.t, float) - float(capture.t[0]))


def without_drift(capture: Capture, axis: str, drift: np.polynomial.Polynomial | list) -> Capture:
    """``capture`` with ``drift`` (:func:`drift_curve`) taken off ``axis``' measured channel."""
    measured = np.array(capture.measured, dtype=float)
    measured[:, capture.axis_index(axis)] -= drift_curve(capture, drift)
    return dataclasses.replace(capture, measured=measured)


def drift_record(capture: Capture, drift: np.polynomial.Polynomial, rms_um: float, p_hz: float) -> dict:
    """``fit.drift``: ``polynomial_mm`` (the coefficients of :func:`measured_drift`, mm, mm/s, mm/s^2 from the
    capture's first sample), ``span_um`` (at the record's end), ``rate_um_min`` (its mean rate), ``max_um``
    (largest distance from the start), ``ratio`` (``max_um`` over the prediction RMS ``rms_um``), ``removed``
    (taken off before the fit: :func:`fit_with_drift` sets it) and ``named`` (a ratio of at least
    :data:`DRIFT_RATIO` and a drift of at least :data:`MIN_DRIFT_UM`, by a fit with integral action).

    A loop without integral action (the fit's slow pole ``p_hz`` at most
    :data:`identification.capture_checks.NO_INTEGRAL_P_HZ`) rests off its reference by its load over its
    gain, which friction and the direction of travel change over the record: a slow offset the regression
    cannot tell from a drift (EMPS, p on its 0.001 Hz bound: 4.5 um over DATA_EMPS.mat's 25 s, 136 um over
    DATA_EMPS_PULSES.mat, twice the prediction error each), so such a fit's drift is not named."""
    d = drift_curve(capture, drift)
    duration_s = float(capture.t[-1] - capture.t[0])
    span_um, max_um = float(d[-1]) * 1e3, float(np.max(np.abs(d))) * 1e3
    ratio = max_um / rms_um if rms_um > 0 else float("inf")
    return {"polynomial_mm": [float(c) for c in drift.coef], "span_um": span_um,
            "rate_um_min": span_um * 60.0 / duration_s if duration_s > 0 else 0.0, "max_um": max_um,
            "ratio": ratio, "removed": False,
            "named": bool(ratio >= DRIFT_RATIO and max_um >= MIN_DRIFT_UM and p_hz > NO_INTEGRAL_P_HZ)}


def fit_with_drift(capture: Capture, axis: str, fit, mode: str = "auto"):
    """``(capture, model)``: ``fit(capture)``, and with the measured channel's drift (:func:`measured_drift`, in
    that fit's loop frame) taken off and fitted again as ``mode`` says (:data:`DRIFT_MODES`); the model's
    ``fit.drift`` records it (:func:`drift_record`; with ``rms_kept_um`` and ``rms_removed_um`` when the refit
    was made). The capture returned is the one the model was fitted to. Under ``"auto"`` a refit the identification
    refuses (its own loop frame leaving too few samples) keeps the first fit, its reason in ``refit_refused``."""
    if mode not in DRIFT_MODES:
        raise ValueError(f"drift must be one of {DRIFT_MODES}, got {mode!r}")
    model = fit(capture)
    drift = measured_drift(capture, model, axis)
    record = drift_record(capture, drift, float(model.fit["rms_um"]), float(model.poles["p_hz"]))
    if mode == "remove" or (mode == "auto" and record["named"]):
        corrected = without_drift(capture, axis, drift)
        try:
            refit = fit(corrected)
        except IdentificationError as exc:  # the refit's own frame refused (fewer samples left in it, ...)
            if mode == "remove":
                raise
            record["refit_refused"] = str(exc)
        else:
            kept, removed = float(model.fit["rms_um"]), float(refit.fit["rms_um"])
            record.update(rms_kept_um=kept, rms_removed_um=removed)
            if mode == "remove" or kept >= DRIFT_GAIN * removed:
                capture, model = corrected, refit
                record["removed"] = True
    model.fit["drift"] = record
    return capture, model


def drift_left_in(fit: dict | None) -> dict | None:
    """``fit.drift`` (:func:`drift_record`) when the drift was named and not taken out, which then holds the slow
    pole p where the reduced model imitates it; else None."""
    rec = (fit or {}).get("drift") or {}
    return rec if rec.get("named") and not rec.get("removed") else None
