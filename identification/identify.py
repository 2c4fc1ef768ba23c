"""``identify``: a capture in, a fitted :class:`ReducedAxisModel` out.

Steps: check the capture axis (:func:`check_capture`), stream the regression of Eq. (3.11) into
sufficient statistics, solve the constrained problem (:func:`identification.solve`), optionally
refine by output error (:mod:`identification.output_error`), measure the fit by simulating the
model on the capture's reference, and - when the module ``identification.diagnosis`` exists -
hand the model to the residual diagnosis (``diagnose(capture, model, axis=...)``, which returns
the model with ``effects`` and ``validation`` filled in).

The default refinement is ``"output-error"``: on held-out data it predicts the tracking error
better than the equation-error solution it starts from (evidence in
``tests/identification/test_output_error.py`` and ``benchmarks/identification.py``).
"""

from __future__ import annotations

import dataclasses
import importlib
import logging
import math
from collections.abc import Mapping

import numpy as np

from identification.bounds import WIDE_P_MIN_HZ, PoleBounds, as_bounds
from identification.dead_time import delay_reference, estimate_delay, loop_capture
from identification.ga import GAOptions
from identification.output_error import refine_output_error
from identification.reduced_model import ReducedAxisModel, simulate
from identification.regressor import RegressorOptions, SufficientStatistics, iter_regressor
from identification.solve import METHODS, SolveResult, solve_statistics
from vcnc.core.capture import Capture, check_sampling
from vcnc.core.errors import CaptureError, IdentificationError, VcncError

__all__ = ["identify", "Identifier", "check_capture", "MIN_SAMPLES", "REFINEMENTS"]

log = logging.getLogger(__name__)

#: Fewest samples accepted (the thesis' test has 22,000 at 1 ms; Sec. 4.3.3 4,096 at 0.6 ms).
MIN_SAMPLES = 500

REFINEMENTS: tuple[str, ...] = ("output-error", "none")


def check_capture(capture: Capture, axis: str, *, options: RegressorOptions | None = None) -> tuple:
    """Validate one axis of a capture for identification; returns ``(reference, measured, T)``.

    Raises
    ------
    CaptureError
        Unknown axis, NaN/inf, time not increasing or not uniform.
    IdentificationError
        Fewer than :data:`MIN_SAMPLES` samples, no motion, motion in one direction only,
        measurement identical to the reference, positions that look like metres.
    """
    src = capture.source
    i = capture.axis_index(axis)
    t = np.asarray(capture.t, float)
    n = t.size
    if n < MIN_SAMPLES:
        raise IdentificationError(
            f"only {n} samples; identification needs at least {MIN_SAMPLES} (the thesis' test has 22,000 at 1 ms)",
            file=src,
        )
    xr = np.asarray(capture.reference[:, i], float)
    x = np.asarray(capture.measured[:, i], float)
    for name, arr in (("t", t), (f"{axis}_ref", xr), (axis, x)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise CaptureError(
                f"column {name!r} is not finite at sample {int(bad[0])} (value {arr[bad[0]]!r})", file=src
            )
    check_sampling(t, src or "<capture>")
    T = float(np.median(np.diff(t)))
    span = float(np.ptp(xr))
    if span == 0.0 and float(np.ptp(x)) == 0.0:
        raise IdentificationError(
            f"no motion on axis {axis!r}: reference and measurement stay at {xr[0]!r} mm", file=src
        )
    if span == 0.0:
        raise IdentificationError(
            f"no commanded motion on axis {axis!r}: the reference stays at {xr[0]!r} mm", file=src
        )
    vmax = float(np.max(np.abs(np.diff(xr)))) / T
    if span < 1.0 and vmax < 2.0:
        raise IdentificationError(
            f"positions on axis {axis!r} look like metres, not mm: the reference spans {span:.4g} mm at a peak "
            f"speed of {vmax:.4g} mm/s; convert the capture to mm (a test this small could not be identified anyway)",
            file=src,
        )
    if np.array_equal(xr, x):
        raise IdentificationError(
            f"the measured position of axis {axis!r} is identical to the reference at every sample: no tracking "
            f"error to identify from (was '{axis}_ref' copied into '{axis}'?)",
            file=src,
        )
    opt = options or RegressorOptions()
    v = np.diff(x) / T
    db = opt.velocity_deadband
    n_pos, n_neg = int(np.sum(v > db)), int(np.sum(v < -db))
    need = max(20, int(0.01 * (n_pos + n_neg)))
    if n_pos < need or n_neg < need:
        which = "negative" if n_neg < need else "positive"
        raise IdentificationError(
            f"friction not identifiable: axis {axis!r} moves in one direction only ({n_pos} samples with positive "
            f"and {n_neg} with negative measured velocity; at least {need} of each needed); the test must also move "
            f"in the {which} direction",
            file=src,
        )
    return xr, x, T


def _fit_metrics(err: np.ndarray) -> dict[str, float]:
    return {"rms_um": float(np.sqrt(np.mean(err * err)) * 1e3), "max_um": float(np.max(np.abs(err)) * 1e3)}


def identify(
    capture: Capture,
    *,
    axis: str = "x",
    method: str = "exact",
    bounds: PoleBounds | Mapping | None = None,
    refine: str = "output-error",
    diagnose: bool | None = None,
    regressor_options: RegressorOptions | None = None,
    seed: int = 0,
    ga_options: GAOptions | None = None,
    delay: str | float = "auto",
) -> ReducedAxisModel:
    """Identify the reduced model of one axis from a capture (thesis Ch. 3-4, plus refinement).

    Parameters
    ----------
    capture : Capture
        Commanded and measured positions [mm], uniform sampling.
    axis : str
        Axis to identify.
    method : {"exact", "ga", "kkt"}
        Solver of the constrained equation-error problem (:func:`identification.solve`).
    bounds : mapping, PoleBounds or "thesis", optional
        Pole box. Default (None): the thesis' (0.2 Hz..Nyquist, zeta 0.2..2.0), widened to
        p >= :data:`identification.bounds.WIDE_P_MIN_HZ` when the data put p on 0.2 Hz and the
        wider box fits them at least 1 % better (a loop without integral action). ``"thesis"``: the
        thesis' box as it is.
    refine : {"output-error", "none"}
        Output-error refinement of the solution (default; see module docstring).
    diagnose : bool, optional
        Residual diagnosis: None (default) runs it when ``identification.diagnosis`` exists,
        False never, True requires it.
    regressor_options : RegressorOptions, optional
        Derivatives, dead band, integration rule.
    seed : int
        Random seed of the GA.
    ga_options : GAOptions, optional
    delay : "auto" or float
        Dead time between the recorded reference and the loop [s]: ``"auto"`` (default) estimates
        it (:func:`identification.dead_time.estimate_delay`, +-0.3 s), a number fixes it (0: none).
        The model is fitted on the delayed reference and carries ``delay_s``.

    Returns
    -------
    ReducedAxisModel
        With ``fit`` holding the prediction of the capture (``rms_um``, ``max_um``) and the solver
        report (``solver``), ``method`` (e.g. ``"exact+oe"``) and ``bounds``.
    """
    if method not in METHODS:
        raise IdentificationError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")
    if refine not in REFINEMENTS:
        raise IdentificationError(f"unknown refinement {refine!r}; expected one of {', '.join(REFINEMENTS)}")
    opt = regressor_options or RegressorOptions()
    xr, x, T = check_capture(capture, axis, options=opt)
    b = as_bounds(bounds, T)
    delay_s, delay_fit = _dead_time(delay, xr, x, T, opt, b)
    if delay_s:
        capture = loop_capture(capture, axis, delay_s / T)
        xr, x, T = check_capture(capture, axis, options=opt)
    stats = SufficientStatistics(8)
    for phi, y in iter_regressor(xr, x, T, options=opt):
        stats.update(phi, y)
    sol: SolveResult = solve_statistics(stats, bounds=b, method=method, seed=seed, ga_options=ga_options,
                                        identifiability=True)
    widened = None
    if bounds is None:
        sol, b, widened = _widen_for_p(stats, sol, b, xr, x, T, method=method, seed=seed, ga_options=ga_options)
    params, poles = dict(sol.parameters), dict(sol.poles)
    ee_err = x - simulate(params, xr, T)
    fit = {
        "equation_error": {**_fit_metrics(ee_err), "objective_mm2": sol.objective},
        "solver": sol.to_dict(),
        "samples": int(x.size),
        "regressor": dataclasses.asdict(opt),
        "delay": delay_fit,
    }
    if widened is not None:
        fit["bounds_widened"] = widened
    label = method
    if refine == "output-error":
        oe = refine_output_error(params, poles, xr, x, T, bounds=b)
        err = x - simulate(oe["parameters"], xr, T)
        if np.sqrt(np.mean(err * err)) <= np.sqrt(np.mean(ee_err * ee_err)):
            params, poles = oe["parameters"], oe["poles"]
            label = f"{method}+oe"
            fit["output_error"] = {"nfev": oe["nfev"], "message": oe["message"], "cost_mm2": oe["cost"]}
        else:  # pragma: no cover - the refinement starts at the solution and only accepts descent
            err = ee_err
    else:
        err = ee_err
    fit.update(_fit_metrics(err))
    model = ReducedAxisModel(
        parameters=params,
        sample_time=T,
        axis=axis,
        method=label,
        poles=poles,
        bounds=b.as_dict(),
        fit=fit,
    )
    if not math.isfinite(fit["rms_um"]):
        raise IdentificationError("the identified model diverges on its own data (non-finite prediction)")
    model = _maybe_diagnose(capture, model, axis, diagnose)  # in the loop's time frame
    return dataclasses.replace(model, delay_s=delay_s) if delay_s else model


def _widen_for_p(stats: SufficientStatistics, sol: SolveResult, b: PoleBounds, xr: np.ndarray, x: np.ndarray,
                 T: float, *, method: str, seed: int, ga_options: GAOptions | None):
    """A loop without integral action puts p on the thesis' 0.2 Hz bound: with evidence, widen the box.

    When the solution's slowest closed-loop pole lies within 1.5x of p's lower bound (p itself, or
    the slow root of the pair when all three poles are real), the problem is solved again with p down to
    :data:`identification.bounds.WIDE_P_MIN_HZ` (still > 0: the loop stays stable, Eq. 3.8); the
    wider box is kept when its model predicts the measured position (simulation, not equation
    error: the two disagree when a bound is active) at least 1 % better. Returns ``(solution, box,
    record)`` with ``record`` None when the box stays.
    """
    lo = b.p_hz[0]
    pl = sol.poles
    zeta = pl["zeta"]
    pair_slow = pl["omega_n_hz"] * (zeta - math.sqrt(zeta * zeta - 1.0)) if zeta >= 1.0 else pl["omega_n_hz"]
    slow = min(pl["p_hz"], pair_slow)
    if not (slow <= lo * 1.5 and lo > WIDE_P_MIN_HZ):
        return sol, b, None
    wide = dataclasses.replace(b, p_hz=(WIDE_P_MIN_HZ, b.p_hz[1]))
    sol2 = solve_statistics(stats, bounds=wide, method=method, seed=seed, ga_options=ga_options, identifiability=True)
    rms = [float(np.sqrt(np.mean((x - simulate(s.parameters, xr, T)) ** 2))) for s in (sol, sol2)]
    if not rms[1] <= 0.99 * rms[0]:
        return sol, b, None
    log.info("slow pole on the %.3g Hz bound; p allowed down to %.3g Hz (prediction %.4g -> %.4g um RMS)", lo,
             WIDE_P_MIN_HZ, rms[0] * 1e3, rms[1] * 1e3)
    return sol2, wide, {"p_hz_from": lo, "p_hz_to": WIDE_P_MIN_HZ, "rms_before_um": rms[0] * 1e3,
                        "rms_after_um": rms[1] * 1e3}


def _dead_time(delay: str | float, xr: np.ndarray, x: np.ndarray, T: float, opt: RegressorOptions, b: PoleBounds):
    """``(delay_s, record)``: the estimated or given dead time [s] and what to report of it.

    An estimated shift is kept only when the constrained model fitted on the shifted reference
    predicts the measured position at least twice better (RMS of the simulation, on the same
    samples) than the one fitted without it: the regression alone can trade loop lag for a shift
    (fadal-ppi, no shift: the regression's best shift is 13.7 samples; its model predicts 19.4 um RMS, 16.7 without).
    """
    if isinstance(delay, str):
        if delay != "auto":
            raise IdentificationError(f"delay must be 'auto' or a number of seconds, got {delay!r}")
        est = estimate_delay(xr, x, T, options=opt)
        record = {"estimated": True, **est.to_dict()}
        if est.delay_s:
            rms0, rms1 = (_prediction_rms(xr, x, T, d, opt, b, margin=int(math.ceil(abs(est.samples))))
                          for d in (0.0, est.samples))
            record.update(rms_without_um=rms0 * 1e3, rms_with_um=rms1 * 1e3)
            if not rms1 <= 0.5 * rms0:
                record["delay_s"] = 0.0
                log.info("reference shift of %.3g samples not kept: prediction %.4g -> %.4g um", est.samples,
                         rms0 * 1e3, rms1 * 1e3)
                return 0.0, record
        log.info("reference dead time: %.4g s (%.3g samples)", est.delay_s, est.samples)
        return est.delay_s, record
    d = float(delay)
    if not (math.isfinite(d) and abs(d) < x.size * T / 3):
        raise IdentificationError(f"delay [s] must be finite and shorter than a third of the record, got {delay!r}")
    return d, {"estimated": False, "delay_s": d}


def _prediction_rms(xr: np.ndarray, x: np.ndarray, T: float, samples: float, opt: RegressorOptions, b: PoleBounds,
                    *, margin: int) -> float:
    """RMS [mm] of the exact-solver model fitted on the reference delayed by ``samples``, on x[margin:-margin]."""
    keep = slice(margin, x.size - margin)
    ref = delay_reference(xr, samples)[keep]
    st = SufficientStatistics(8)
    for phi, y in iter_regressor(ref, x[keep], T, options=opt):
        st.update(phi, y)
    sol = solve_statistics(st, bounds=b, method="exact")
    err = x[keep] - simulate(sol.parameters, ref, T)
    return float(np.sqrt(np.mean(err * err)))


def _maybe_diagnose(capture: Capture, model: ReducedAxisModel, axis: str, diagnose: bool | None):
    if diagnose is False:
        return model
    try:
        mod = importlib.import_module("identification.diagnosis")
    except ModuleNotFoundError as exc:
        if exc.name != "identification.diagnosis":
            raise
        if diagnose:
            raise VcncError(
                "residual diagnosis was requested but is not available (no identification.diagnosis)"
            ) from None
        log.info("residual diagnosis not available; returning the reduced model")
        return model
    return mod.diagnose(capture, model, axis=axis)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Identifier:
    """Estimator form of :func:`identify`: configure once, ``fit(capture)`` per axis.

    Attributes mirror the keyword arguments of :func:`identify`.
    """

    method: str = "exact"
    bounds: PoleBounds | None = None
    refine: str = "output-error"
    diagnose: bool | None = None
    regressor_options: RegressorOptions | None = None
    seed: int = 0
    ga_options: GAOptions | None = None
    delay: str | float = "auto"

    def fit(self, capture: Capture, axis: str = "x") -> ReducedAxisModel:
        """The fitted model of ``axis``."""
        return identify(
            capture,
            axis=axis,
            method=self.method,
            bounds=self.bounds,
            refine=self.refine,
            diagnose=self.diagnose,
            regressor_options=self.regressor_options,
            seed=self.seed,
            ga_options=self.ga_options,
            delay=self.delay,
        )
