"""The fit: a capture in, a :class:`ReducedAxisModel` out (no diagnosis).

Steps: check the capture axis (:func:`identification.capture_checks.check_capture`), estimate the
reference dead time (:mod:`identification.dead_time`), stream the regression of Eq. (3.11) into
sufficient statistics, solve the constrained problem (:func:`identification.solve`), widen the
pole box when the data put p on its bound, refine by output error
(:mod:`identification.output_error`), and measure the fit by simulating the model on the
capture's reference. :func:`identification.identify` (:mod:`identification.pipeline`) runs this
fit and then the residual diagnosis.

The default refinement is ``"output-error"``: on held-out data it predicts the tracking error
better than the equation-error solution it starts from (evidence in
``tests/identification/test_output_error.py`` and ``benchmarks/identification.py``).
"""

from __future__ import annotations

import dataclasses
import logging
import math
from collections.abc import Mapping

import numpy as np

from identification.bounds import WIDE_P_MIN_HZ, PoleBounds, as_bounds
from identification.capture_checks import check_capture
from identification.dead_time import delay_reference, estimate_delay, loop_capture
from identification.ga import GAOptions
from identification.output_error import refine_output_error
from identification.reduced_model import ReducedAxisModel, simulate
from identification.regressor import RegressorOptions, SufficientStatistics, iter_regressor
from identification.solve import METHODS, SolveResult, solve_statistics
from vcnc.core.capture import Capture
from vcnc.core.errors import IdentificationError
from vcnc.core.metrics import error_metrics

__all__ = ["fit_reduced_model", "REFINEMENTS"]

log = logging.getLogger(__name__)

#: Refinements of the equation-error solution.
REFINEMENTS: tuple[str, ...] = ("output-error", "none")



def fit_reduced_model(
    capture: Capture,
    *,
    axis: str = "x",
    method: str = "exact",
    bounds: PoleBounds | Mapping | None = None,
    refine: str = "output-error",
    regressor_options: RegressorOptions | None = None,
    seed: int = 0,
    ga_options: GAOptions | None = None,
    delay: str | float = "auto",
) -> ReducedAxisModel:
    """Fit the reduced model of one axis to a capture (thesis Ch. 3-4, plus refinement).

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
        report (``solver``), ``method`` (e.g. ``"exact+oe"``), ``bounds`` and ``delay_s``.
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
    fit = {
        "equation_error": {**error_metrics(x - simulate(sol.parameters, xr, T)), "objective_mm2": sol.objective},
        "solver": sol.to_dict(),
        "samples": int(x.size),
        "regressor": dataclasses.asdict(opt),
        "delay": delay_fit,
    }
    if widened is not None:
        fit["bounds_widened"] = widened
    params, poles, label, err = _refine(sol, xr, x, T, b, method=method, refine=refine, fit=fit)
    fit.update(error_metrics(err))
    if not math.isfinite(fit["rms_um"]):
        raise IdentificationError("the identified model diverges on its own data (non-finite prediction)")
    return ReducedAxisModel(
        parameters=params,
        sample_time=T,
        axis=axis,
        method=label,
        poles=poles,
        bounds=b.as_dict(),
        fit=fit,
        delay_s=delay_s,
    )


def _refine(sol: SolveResult, xr: np.ndarray, x: np.ndarray, T: float, b: PoleBounds, *, method: str, refine: str,
            fit: dict) -> tuple[dict, dict, str, np.ndarray]:
    """``(parameters, poles, method label, prediction error [mm])`` after the output-error
    refinement (kept only when it predicts no worse; recorded in ``fit["output_error"]``)."""
    params, poles = dict(sol.parameters), dict(sol.poles)
    err = x - simulate(params, xr, T)
    if refine != "output-error":
        return params, poles, method, err
    oe = refine_output_error(params, poles, xr, x, T, bounds=b)
    oe_err = x - simulate(oe["parameters"], xr, T)
    if not np.sqrt(np.mean(oe_err * oe_err)) <= np.sqrt(np.mean(err * err)):  # pragma: no cover - descent only
        return params, poles, method, err
    fit["output_error"] = {"nfev": oe["nfev"], "message": oe["message"], "cost_mm2": oe["cost"]}
    return oe["parameters"], oe["poles"], f"{method}+oe", oe_err


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
