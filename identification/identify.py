"""The fit: a capture in, a :class:`ReducedAxisModel` out (no diagnosis).

Steps: check the capture axis (:func:`identification.capture_checks.check_capture`: the measured
channel must follow the commanded one in unit and sign), remove a large datum offset
(:mod:`identification.datum_offset`), estimate the reference dead time
(:mod:`identification.dead_time`), take the capture into the loop's frame
(:mod:`identification.loop_frame`: offset off, reference delayed, a start in motion dropped), stream
the regression of Eq. (3.11) into
sufficient statistics, solve the constrained problem (:func:`identification.solve`), widen the
pole box when the data put p on its bound, refine by output error
(:mod:`identification.output_error`; with a small datum offset when that halves the error, and
with the estimated dead time, refined jointly; for a loop frame that starts in motion with no rest
to start from, with the state at its first sample, :mod:`identification.initial_state`), and measure
the fit by simulating the model on the
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
from identification.capture_checks import check_capture, check_scale, travelled_direction
from identification.datum_offset import COARSE_SHARE, MIN_GAIN, OffsetEstimate, estimate_offset
from identification.dead_time import FINEST_STEP_S, delay_reference, estimate_delay
from identification.excitation import excitation
from identification.filter_signature import shows_filter, signature
from identification.ga import GAOptions
from identification.initial_state import centred_statistics, fit_initial_state, starts_in_motion
from identification.loop_frame import loop_frame, starts_at_rest, without_offset
from identification.output_error import refine_output_error
from identification.pair_starts import pair_starts
from identification.reduced_model import ReducedAxisModel
from identification.regressor import RegressorOptions, SufficientStatistics, iter_regressor
from identification.segments import settled_start
from identification.solve import METHODS, SolveResult, solve_statistics
from identification.substeps import simulate_record, substep_count, substep_reference
from vcnc.core.capture import Capture
from vcnc.core.errors import IdentificationError
from vcnc.core.metrics import error_metrics

__all__ = ["fit_reduced_model", "REFINEMENTS"]

log = logging.getLogger(__name__)

#: Refinements of the equation-error solution.
REFINEMENTS: tuple[str, ...] = ("output-error", "none")
#: Least ratio of prediction RMS (slow pole near 0 Hz / datum offset) for a widened box's slow pole to be
#: replaced by a datum offset [-] (:func:`_offset_for_slow_pole`; fadal-pid with 10 um left at 3 ms: 1.57).
OFFSET_OVER_SLOW_POLE = 1.25
#: Dead times below the equation error's estimate that are fitted before the joint refinement [s]
#: (:func:`_delay_by_candidates`): its bias is the loop's own lag, up to 13.7 ms on fadal-ppi.
DELAY_CANDIDATES_S = (0.0, 0.005, 0.010, 0.015, 0.020)
#: Savitzky-Golay window of the output-error refinement's second start [s] and its fewest samples
#: (:func:`_smoothed_start`).
SMOOTHED_START_S = 0.009
SMOOTHED_START_MIN = 7
#: Restarts of the joint dead-time refinement (:func:`_restarted_delay`): this far either side of
#: its result [samples], at most this many rounds, kept when the cost falls by this share [-].
DELAY_RESTART_SAMPLES = 0.5
DELAY_RESTARTS = 3
DELAY_RESTART_GAIN = 0.01
#: The setpoint filter's search (:func:`_with_setpoint_filter`): the lengths its regression screen
#: tries [s], the largest ratio of regression objectives (best length / none) for the search to go
#: on [-], its longest length [s], the shortest length kept [samples] (shorter is the sampled loop's
#: own lag, as for the dead time) and the least ratio of prediction RMS (without / with) for it to
#: be kept [-]: a 150 Hz mode in the loop, recorded at 2 ms, is imitated by a 9.7 ms filter for
#: 1.56x (``tests/identification/test_diagnosis_folds.py``, which the diagnosis must name), the least
#: a jerk filter gained on vcnc's machines is 1.66x (ballscrew-ppc, ``benchmarks/recorded_traces.py``
#: case ``jerkf``; the others 2.6-32x): a thin margin, so the record must also show the moving
#: average's gain (:func:`identification.filter_signature.shows_filter`).
FILTER_SCREEN_S = (0.004, 0.008, 0.016, 0.032, 0.064)
FILTER_SCREEN_RATIO = 0.9
FILTER_MAX_S = 0.1
MIN_FILTER_SAMPLES = 2.0
FILTER_GAIN = 1.6
#: Fits again on the record less the datum offset found, at most (:func:`_refit_without_offset`) [-]. The first
#: removal is always fitted again, with the offset gone from the record, not refined beside the loop's parameters:
#: with it free the refinement of ident_fuzz seed 11 case 55 (ballscrew-ppc with 2.409 mm) found 24.8 Hz, p 194 Hz at
#: 3.18 um, where the backlash's screen gained too little to be refitted; fitted again, 51.8 Hz, p 25 Hz at 3.32 um,
#: and the backlash was named, 3.37 -> 1.25 um held out.
OFFSET_REFITS = 2
#: Share of the box's upper frequency bound above which the refined model's fastest pole counts as on it,
#: and the refinement is started again with the pair complex (:func:`_pair_below_nyquist`) [-].
NEAR_NYQUIST = 0.9



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
    setpoint_filter: bool = True,
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
    setpoint_filter : bool
        Search a moving-average setpoint filter between the reference and the loop
        (:mod:`identification.setpoint_filter`, :func:`_with_setpoint_filter`; default); the model
        carries ``setpoint_filter_s`` (0 when none was found or searched).

    Returns
    -------
    ReducedAxisModel
        With ``fit`` holding the prediction of the capture (``rms_um``, ``max_um``) and the solver
        report (``solver``), ``method`` (e.g. ``"exact+oe"``), ``bounds`` and ``delay_s``.
    """
    _check_choices(method, refine)
    opt = regressor_options or RegressorOptions()
    original = capture
    options = {"method": method, "bounds": bounds, "refine": refine, "regressor_options": regressor_options,
               "seed": seed, "ga_options": ga_options, "setpoint_filter": setpoint_filter}
    xr, x, T = check_capture(capture, axis, options=opt)
    if opt.friction == "two-way":
        opt = dataclasses.replace(opt, friction=travelled_direction(x, T, axis, capture.source, options=opt))
    b = as_bounds(bounds, T)
    capture, start, offset, delay_s, delay_fit = _in_loop_frame(capture, axis, delay, xr, x, T, opt, b)
    if delay_s and delay_fit["estimated"] and refine == "output-error" and "delay_candidate" not in original.meta:
        delay_s = _delay_by_candidates(original, axis, delay_s, delay_fit, **options)
        capture, start, offset, _, _ = _in_loop_frame(original, axis, delay_s, xr, x, T, opt, b)
    if capture is not original:
        xr, x, T = check_capture(capture, axis, options=opt)
    frame = _frame_samples(original.t.size, x.size, delay_s / T)
    stats, sol, centred = _equation_error(xr, x, T, opt, b, method=method, seed=seed, ga_options=ga_options)
    widened, narrow = None, sol
    if bounds is None and not offset.applied:  # after a removed offset, what is left of it puts p on the bound
        sol, b, widened = _widen_for_p(stats, sol, b, xr, x, T, method=method, seed=seed, ga_options=ga_options)
    fit = _equation_error_fit(sol, xr, x, T, opt, delay_fit=delay_fit, offset=offset, centred=centred, start=start,
                              widened=widened)
    params, poles, label, err = _refine(sol, xr, x, T, b, method=method, refine=refine, fit=fit, opt=opt,
                                        offset=offset.applied, first=frame.start)
    if label.endswith("+oe"):
        params, poles, err, b = _after_refinement(stats, narrow, params, poles, err, xr, x, T, b, fit,
                                                  default_box=bounds is None, widened=widened,
                                                  offset_applied=offset.applied)
    if delay_s and delay_fit["estimated"] and label.endswith("+oe"):
        params, poles, err, delay_s = _with_refined_delay(original, axis, params, poles, err, T, b, delay_s, fit)
    fit.update(error_metrics(err))
    if not math.isfinite(fit["rms_um"]):
        raise IdentificationError("the identified model diverges on its own data (non-finite prediction)")
    moved = fit["offset"]["offset_mm"] - offset.offset_mm
    refits = original.meta.get("offset_refit", 0)
    # the first removal always fitted again (OFFSET_REFITS), a further pass when the offset moved
    if fit["offset"]["applied"] and (abs(moved) > 1e-4 * fit["rms_um"] or not refits) and refits < OFFSET_REFITS:
        return _refit_without_offset(original, axis, fit, delay=delay, **options)
    filter_s = 0.0
    if setpoint_filter and label.endswith("+oe") and "delay_candidate" not in original.meta:
        free = bool(delay_s and delay_fit["estimated"])
        params, poles, err, delay_s, filter_s = _with_setpoint_filter(original, axis, params, poles, err, T, b,
                                                                      delay_s, fit, free_delay=free)
        fit.update(error_metrics(err))
    params = _one_way_friction(original, axis, params, err, T, opt, fit, delay_s=delay_s, filter_s=filter_s)
    check_scale(params, x.size * T, axis, original.source)
    return ReducedAxisModel(parameters=params, sample_time=T, axis=axis, method=label, poles=poles, bounds=b.as_dict(),
                            fit=fit, delay_s=delay_s, setpoint_filter_s=filter_s)


def _check_choices(method: str, refine: str) -> None:
    """An :class:`IdentificationError` naming a ``method`` or ``refine`` that :func:`fit_reduced_model` lacks."""
    if method not in METHODS:
        raise IdentificationError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")
    if refine not in REFINEMENTS:
        raise IdentificationError(f"unknown refinement {refine!r}; expected one of {', '.join(REFINEMENTS)}")


def _one_way_friction(original: Capture, axis: str, params: dict, err: np.ndarray, T: float, opt: RegressorOptions,
                      fit: dict, *, delay_s: float, filter_s: float) -> dict:
    """``params`` with the untravelled direction's Coulomb level set to the mirror of the travelled one on a record
    that moves one way only (:func:`_mirrored_friction`; ``fit``'s error metrics updated), else as they are."""
    if opt.friction == "two-way":
        return params
    recorded = np.asarray(original.reference[:, original.axis_index(axis)], float)
    params, err = _mirrored_friction(params, err, recorded, T, opt.friction, delay_s=delay_s, filter_s=filter_s)
    fit.update(error_metrics(err))
    return params


def _after_refinement(stats: SufficientStatistics, narrow: SolveResult, params: dict, poles: dict, err: np.ndarray,
                      xr: np.ndarray, x: np.ndarray, T: float, b: PoleBounds, fit: dict, *, default_box: bool,
                      widened: dict | None, offset_applied: bool) -> tuple[dict, dict, np.ndarray, PoleBounds]:
    """The output-error fit's later stages, in :func:`fit_reduced_model`'s order: under the default box
    (``default_box``) the box widened for p after the refinement (:func:`_widen_refined`, when the equation error
    did not widen it and no offset was removed), the pair moved below Nyquist (:func:`_pair_below_nyquist`) and
    started across its frequency (:func:`identification.pair_starts.pair_starts`, without a removed offset); after a
    widened box, the offset tried for the slow pole (:func:`_offset_for_slow_pole`). Returns ``(parameters, poles,
    error, box)``."""
    if default_box and widened is None and not offset_applied:
        params, poles, err, b, widened = _widen_refined(params, poles, err, xr, x, T, b, fit)
    if default_box and "initial_state" not in fit:
        params, poles, err = _pair_below_nyquist(stats, params, poles, err, xr, x, T, b, fit)
        if not fit["offset"]["applied"]:
            params, poles, err = pair_starts(stats, params, poles, err, xr, x, T, b, fit)
    if widened is not None and not fit["offset"]["applied"] and "initial_state" not in fit:
        params, poles, err = _offset_for_slow_pole(narrow, xr, x, T, b, params, poles, err, fit)
    return params, poles, err, b


def _equation_error_fit(sol: SolveResult, xr: np.ndarray, x: np.ndarray, T: float, opt: RegressorOptions, *,
                        delay_fit: dict, offset: OffsetEstimate, centred: bool, start: int,
                        widened: dict | None) -> dict:
    """The model's ``fit`` record after the equation-error solution: its prediction, the solver's report,
    the regressor options, the dead time and offset found, and what the record's framing changed."""
    fit = {
        "equation_error": {**error_metrics(x - simulate_record(sol.parameters, xr, T)), "objective_mm2": sol.objective},
        "solver": sol.to_dict(),
        "samples": int(x.size),
        "regressor": dataclasses.asdict(opt),
        "delay": delay_fit,
        "offset": offset.to_dict(),
        "excitation": excitation(xr, T),
    }
    if centred:
        fit["equation_error"]["integrator_start_free"] = True
    if substep_count(T) > 1:
        fit["substeps"] = substep_count(T)
    if start:
        fit["record_start"] = {"dropped_samples": start, "dropped_s": start * T}
    if widened is not None:
        fit["bounds_widened"] = widened
    if opt.friction != "two-way":
        fit["friction"] = one_way_friction(opt.friction)
    return fit


def _mirrored_friction(params: dict, err: np.ndarray, recorded: np.ndarray, T: float, direction: str, *,
                       delay_s: float, filter_s: float) -> tuple:
    """``(parameters, error)`` with the Coulomb level of the direction the record does not travel set to the mirror of
    the other's (:func:`one_way_friction`): the refinements move both levels, and the untravelled one only by the few
    samples where the prediction moves that way. The prediction error [mm] takes the change of the simulated record
    (the ``recorded`` reference through the model's dead time and setpoint filter; the fit's error covers the
    record's last ``err.size`` samples, the loop frame dropping only its start)."""
    known, unknown = ("d0", "d1") if direction == "positive" else ("d1", "d0")
    mirrored = {**params, unknown: -params[known]}
    if mirrored[unknown] != params[unknown] and 0 < err.size <= recorded.size:
        shift = {"delay_samples": delay_s / T, "filter_samples": filter_s / T}
        change = simulate_record(params, recorded, T, **shift) - simulate_record(mirrored, recorded, T, **shift)
        err = err + change[recorded.size - err.size:]
    return mirrored, err


def one_way_friction(direction: str) -> dict:
    """The ``fit["friction"]`` record of a model fitted on a record that moves ``direction`` only
    (:func:`identification.capture_checks.travelled_direction`): the level identified, the one assumed, and a
    sentence saying so."""
    known, unknown = ("d0", "d1") if direction == "positive" else ("d1", "d0")
    other = "negative" if direction == "positive" else "positive"
    return {"travelled": direction, "identified": known, "assumed": {unknown: f"-{known}"},
            "statement": f"the record moves in the {direction} direction only: the Coulomb level of the {other} "
                         f"direction ({unknown}) is unknown; the model takes it as the mirror of the {direction} one "
                         f"({unknown} = -{known}, friction of the same size both ways)"}


def _equation_error(xr: np.ndarray, x: np.ndarray, T: float, opt: RegressorOptions, b: PoleBounds, *, method: str,
                    seed: int, ga_options: GAOptions | None) -> tuple[SufficientStatistics, SolveResult, bool]:
    """``(statistics, solution, centred)`` of the constrained regression of Eq. (3.11).

    The regressor's integrated tracking error starts at 0 at the first sample: right for a record
    that starts at rest, wrong for one that starts in motion
    (:func:`identification.initial_state.starts_in_motion`), whose controller integrator holds an
    unknown value there (fadal-ppi triggered 1.234 s into its test: p on the 0.2 Hz bound and the
    pair at 17.6 Hz on zeta's 2.0 bound, for 4.6 Hz and 52.7 Hz / 0.93 on the whole record). For
    such a record the regression is also solved with that value free
    (:func:`identification.initial_state.centred_statistics`: 64.7 Hz / 1.07, 4.70 Hz, as on the
    whole record) and the solution whose model predicts the record better (its state at the first
    sample fitted) is kept; ``centred`` says which. A centred solution with p on the box's lower
    bound has no integral action whose start could be free (EMPS, a P-P cascade: its constant
    took up the load's offset force and the fit ended on p = 0.2 Hz, 3.3 um for 1.4): the plain
    regression is kept for :func:`_widen_for_p`.
    """
    stats = SufficientStatistics(8)
    for phi, y in iter_regressor(xr, x, T, options=opt):
        stats.update(phi, y)
    sol = solve_statistics(stats, bounds=b, method=method, seed=seed, ga_options=ga_options, identifiability=True)
    if not starts_in_motion(xr, x):
        return stats, sol, False
    try:
        free = centred_statistics(xr, x, T, options=opt)
        sol2 = solve_statistics(free, bounds=b, method=method, seed=seed, ga_options=ga_options, identifiability=True)
    except IdentificationError:  # the constant is a combination of the friction columns (never at rest)
        return stats, sol, False
    if sol2.poles["p_hz"] <= 1.5 * b.p_hz[0]:  # no integral action to start: the box is widened instead
        return stats, sol, False
    rms = [_prediction_rms_from(s.parameters, xr, x, T, moving=True) for s in (sol, sol2)]
    if not rms[1] < rms[0]:
        return stats, sol, False
    log.info("record in motion: the regression with its integrator's start free predicts %.4g -> %.4g um",
             rms[0] * 1e3, rms[1] * 1e3)
    return free, sol2, True


def _delay_by_candidates(original: Capture, axis: str, delay_s: float, record: dict, **options) -> float:
    """The dead time [s] to refine from: of the equation error's estimate ``delay_s`` and the
    :data:`DELAY_CANDIDATES_S` below it, the one whose fit (:func:`fit_reduced_model` with that
    dead time fixed) predicts the record best; ``record`` (``fit.delay``) gets ``equation_error_s``
    and ``candidates`` (``[[delay_s, rms_um], ...]``).

    The equation error's shift trades the loop's own lag for dead time (fadal-ppi, no shift: 13.7
    samples; a reference recorded 20 ms late: -6.6 ms), and the joint output-error refinement
    started there stays in the local minimum it finds, the fast pole pair bent to make up the
    difference (fadal-ppi, reference leading by 0.1 s: 105.4 ms, the pair at 150 Hz / 1.84 for
    52.7 Hz / 0.93, 0.62 um for 0.17; the traceid2 truth harness, ``benchmarks/recorded_traces.py``).
    Fitted with the dead time fixed, the prediction is best at the true one (fadal-ppi: 0.25 um at
    100 ms, 0.50 at 94, 0.56 at 106, 5.1 at the estimate's 113.3). A candidate whose fit fails is
    skipped. A record faster than :data:`identification.dead_time.FINEST_STEP_S` is judged decimated
    to about that step (chevalier-pdf at 0.25 ms: 48 s without).
    """
    i = original.axis_index(axis)
    q = max(1, int(round(FINEST_STEP_S / original.sample_time)))
    marked = Capture(t=original.t[::q], axes=(axis,), reference=original.reference[::q, [i]],
                     measured=original.measured[::q, [i]], meta={**original.meta, "delay_candidate": True})
    n_max = original.t.size * original.sample_time / 3  # the longest dead time a fit accepts
    tried = []
    for step in DELAY_CANDIDATES_S:
        c = delay_s - step
        if abs(c) >= n_max:
            continue
        try:
            rms = fit_reduced_model(marked, axis=axis, delay=c, **options).fit["rms_um"]
        except IdentificationError:
            continue
        tried.append([c, float(rms)])
    record.update(equation_error_s=delay_s, candidates=tried)
    best = min(tried, key=lambda v: v[1])[0] if tried else delay_s
    log.info("reference dead time: %.4g s from the candidates %s", best, tried)
    return best


def _prediction_rms_from(parameters: dict, xr: np.ndarray, x: np.ndarray, T: float, *, moving: bool) -> float:
    """RMS [mm] of the model's prediction of ``x``, simulated from rest; for a record that starts in
    motion (``moving``) with its state at the first sample fitted
    (:func:`identification.initial_state.fit_initial_state`)."""
    e = x - simulate_record(parameters, xr, T)
    if moving:
        e = e - fit_initial_state(parameters, T, e)[1]
    return float(np.sqrt(np.mean(e * e)))


def _refit_without_offset(original: Capture, axis: str, fit: dict, **options) -> ReducedAxisModel:
    """The model fitted again on ``original`` less the output error's datum offset of ``fit``
    (:func:`fit_reduced_model` with ``options``): that offset is exact where the regression's was a
    few um off, and the slow pole is not left where the residual offset had put it. The refit may
    move the offset again and run once more (:data:`OFFSET_REFITS`): chevalier-pdf with a 0.5 mm
    offset, its first pass' offset (the slow pole's, :func:`_offset_for_slow_pole`) 0.5 um short,
    which again put p on its bound in the refit's regression: the refinement ended pole-swapped
    (the pair at 1.0 Hz / 2.0, p 215 Hz, for 172 Hz / 0.21 and 3.7 Hz, 0.021 um RMS) and found the
    offset's rest; refitted on that, 0.05 % off at 1.5e-6 um (the traceid5 truth harness)."""
    again = dataclasses.replace(without_offset(original, axis, fit["offset"]["offset_mm"]),
                                meta={**original.meta, "offset_refit": original.meta.get("offset_refit", 0) + 1})
    model = fit_reduced_model(again, axis=axis, **options)
    rec = model.fit["offset"]
    rec.update(offset_mm=rec["offset_mm"] + fit["offset"]["offset_mm"], applied=True,
               estimated_mm=fit["offset"]["estimated_mm"], rms_without_um=fit["offset"]["rms_without_um"],
               rms_with_um=model.fit["rms_um"])
    return model


def _checked_frame(capture: Capture, framed: Capture, axis: str, opt: RegressorOptions) -> tuple:
    """:func:`check_capture` of the capture in the loop's frame; a refusal for its length says how many of the
    record's samples the frame dropped (a user who gave 250 samples was told "only 131 samples")."""
    try:
        return check_capture(framed, axis, options=opt)
    except IdentificationError as e:
        dropped = capture.t.size - framed.t.size
        if not (dropped > 0 and e.message.startswith("only ")):
            raise
        raise IdentificationError(f"{e.message}; {dropped} of the record's {capture.t.size} samples were dropped "
                                  "before the loop's frame starts (the reference's dead time and a start with the "
                                  "axis not yet settled)", file=e.file) from e


def _in_loop_frame(capture: Capture, axis: str, delay: str | float, xr: np.ndarray, x: np.ndarray, T: float,
                   opt: RegressorOptions, b: PoleBounds):
    """``(capture in the loop's frame, samples dropped at its start, OffsetEstimate, delay_s [s],
    fit["delay"] record)``: a large datum offset is removed before the dead time is estimated (an
    offset hides it), and judged again in the loop's frame, where a smaller one shows."""
    first = _datum_offset(xr, x, T, opt, b)
    delay_s, delay_fit = _dead_time(delay, xr, x - first.offset_mm, T, opt, b, free_offset=first.applied)
    framed, start = loop_frame(capture, axis, offset_mm=first.offset_mm, delay_samples=delay_s / T)
    second = _datum_offset(*_checked_frame(capture, framed, axis, opt), opt, b)
    offset = _combined(first, second)
    if offset.offset_mm != first.offset_mm:
        framed, start = loop_frame(capture, axis, offset_mm=offset.offset_mm, delay_samples=delay_s / T)
    return framed, start, offset, delay_s, delay_fit


def _refine(sol: SolveResult, xr: np.ndarray, x: np.ndarray, T: float, b: PoleBounds, *, method: str, refine: str,
            fit: dict, opt: RegressorOptions, offset: bool = False,
            first: int = 0) -> tuple[dict, dict, str, np.ndarray]:
    """``(parameters, poles, method label, prediction error [mm])`` after the output-error
    refinement (kept only when it predicts no worse; recorded in ``fit["output_error"]``), started
    from ``sol`` and from :func:`_smoothed_start`, the lower cost kept (``fit.output_error.start``).
    With ``offset`` (a datum offset was removed) the refinement also fits what remains of it,
    added to ``fit["offset"]["offset_mm"]``. ``first``: the recorded sample the loop frame starts at
    (``fit.initial_state.first_sample``, counted in the recorded capture as everywhere)."""
    params, poles = dict(sol.parameters), dict(sol.poles)
    err = x - simulate_record(params, xr, T)
    if refine != "output-error":
        return params, poles, method, err
    moving = starts_in_motion(xr, x)  # no rest in the first half: fit the state at the first sample
    starts = {"equation-error": sol, "smoothed": _smoothed_start(xr, x, T, b, opt)}
    runs = {name: _refined(lambda state, s=s: refine_output_error(s.parameters, s.poles, xr, x, T, bounds=b,
                                                                 offset=offset, initial_state=state), moving)
            for name, s in starts.items() if s is not None}
    best = min(runs, key=lambda name: runs[name]["cost"])
    oe = runs[best]
    oe_err = x - oe["offset_mm"] - simulate_record(oe["parameters"], xr, T) - oe.get("start_response", 0.0)
    if not np.sqrt(np.mean(oe_err * oe_err)) <= np.sqrt(np.mean(err * err)):  # pragma: no cover - descent only
        return params, poles, method, err
    fit["output_error"] = {"nfev": sum(r["nfev"] for r in runs.values()), "message": oe["message"],
                           "cost_mm2": oe["cost"], "start": best}
    if offset:
        fit["offset"]["offset_mm"] += oe["offset_mm"]
    elif abs(np.mean(oe_err)) > 0.25 * np.sqrt(np.mean(oe_err * oe_err)):  # a small offset the fit bends to
        oe2 = refine_output_error(oe["parameters"], oe["poles"], xr, x, T, bounds=b, offset=True,
                                  initial_state="initial_state" in oe)
        err2 = x - oe2["offset_mm"] - simulate_record(oe2["parameters"], xr, T) - oe2.get("start_response", 0.0)
        rms1, rms2 = (float(np.sqrt(np.mean(e * e))) for e in (oe_err, err2))
        if rms2 * MIN_GAIN <= rms1:
            fit["offset"].update(offset_mm=oe2["offset_mm"], applied=True, rms_without_um=rms1 * 1e3,
                                 rms_with_um=rms2 * 1e3)
            fit["output_error"].update(nfev=oe["nfev"] + oe2["nfev"], cost_mm2=oe2["cost"])
            _record_initial_state(fit, oe2, first)
            return oe2["parameters"], oe2["poles"], f"{method}+oe", err2
    _record_initial_state(fit, oe, first)
    return oe["parameters"], oe["poles"], f"{method}+oe", oe_err


def _smoothed_start(xr: np.ndarray, x: np.ndarray, T: float, b: PoleBounds,
                    opt: RegressorOptions) -> SolveResult | None:
    """The second start of the output-error refinement: the equation-error solution (exact solver)
    with the derivatives taken by Savitzky-Golay filters :data:`SMOOTHED_START_S` wide (at least
    :data:`SMOOTHED_START_MIN` samples); None when the regression already smooths or fails.

    Central differences of a noisy measured position bias the regression, and its solution can
    start the refinement in another basin than the truth's: fadal-ppi with 0.5 um white noise on
    the measured channel, the pair at 115 Hz / 1.09 for 52.7 Hz / 0.93, refined to 80 Hz / 1.26 at
    0.575 um RMS with a 3 um ridge between it and the truth's 0.523 um; smoothed over 9 samples
    the regression starts at 54 Hz / 0.80 and the refinement ends 1.8 % off (the traceid3 truth
    harness, ``benchmarks/recorded_traces.py``, cases ``noise``/``quant``). The output error judges
    between the two starts; the smoothed regression alone would bend the poles (25 samples:
    34.6 Hz / 0.50).
    """
    if opt.smoothing_window:
        return None
    w = max(SMOOTHED_START_MIN, int(round(SMOOTHED_START_S / T)) | 1)
    stats = SufficientStatistics(8)
    try:
        for phi, y in iter_regressor(xr, x, T, options=dataclasses.replace(opt, smoothing_window=w)):
            stats.update(phi, y)
        return solve_statistics(stats, bounds=b, method="exact", identifiability=True)
    except IdentificationError:
        return None


def _offset_for_slow_pole(narrow: SolveResult, xr: np.ndarray, x: np.ndarray, T: float, b: PoleBounds, params: dict,
                          poles: dict, err: np.ndarray, fit: dict) -> tuple[dict, dict, np.ndarray]:
    """``(parameters, poles, error [mm])``: a datum offset instead of a slow pole near 0 Hz.

    A small datum offset left in the record (below what :func:`_datum_offset` removes: 10 um on
    fadal-pid at 3 ms, or what remains of a removed one) puts p on the thesis' 0.2 Hz bound; the
    box is widened (:func:`_widen_for_p`) and the refinement, started there, imitates the offset
    with p on 0.001 Hz (1.75 um RMS), a local minimum: started from the thesis box's solution with
    the offset free it finds the offset to 0.02 um and p 1.42 Hz (1.12 um). Kept (``fit.offset``
    updated) when it predicts :data:`OFFSET_OVER_SLOW_POLE` times better (RMS); a loop without
    integral action (EMPS) keeps its slow pole.
    """
    oe = refine_output_error(narrow.parameters, narrow.poles, xr, x, T, bounds=b, offset=True)
    e = x - oe["offset_mm"] - simulate_record(oe["parameters"], xr, T)
    rms0, rms1 = (float(np.sqrt(np.mean(v * v))) for v in (err, e))
    if not rms1 * OFFSET_OVER_SLOW_POLE <= rms0:
        return params, poles, err
    log.info("a datum offset of %.4g mm instead of a slow pole of %.3g Hz: %.4g -> %.4g um RMS", oe["offset_mm"],
             poles["p_hz"], rms0 * 1e3, rms1 * 1e3)
    fit["offset"].update(offset_mm=oe["offset_mm"], applied=True, rms_without_um=rms0 * 1e3, rms_with_um=rms1 * 1e3)
    fit["output_error"].update(nfev=fit["output_error"]["nfev"] + oe["nfev"], cost_mm2=oe["cost"])
    return oe["parameters"], oe["poles"], e


def _refined(run, moving: bool) -> dict:
    """The output-error result ``run(False)``; for a record that starts in motion
    (:func:`identification.initial_state.starts_in_motion`) the one that also fits the state at
    its first sample, ``run(True)``, when it predicts at least
    :data:`identification.datum_offset.MIN_GAIN` times better (RMS). A free state also fits what
    a slow pole's free response can imitate, a drift or a constant (EMPS, p on its 0.001 Hz bound:
    2.2 -> 1.6 um on its estimation run, its validation run 40 % worse), so a start transient must
    show clearly before it is modelled."""
    oe = run(False)
    if not moving:
        return oe
    with_state = run(True)
    return with_state if with_state["cost"] * MIN_GAIN**2 <= oe["cost"] else oe


def _record_initial_state(fit: dict, oe: dict, first: int) -> None:
    """``fit["initial_state"]`` from an output-error result that fitted the state at its first
    sample (``first``, counted in the recorded capture); removed when it did not."""
    fit.pop("initial_state", None)
    if "initial_state" in oe:
        fit["initial_state"] = {"state_mm": [float(v) for v in oe["initial_state"]], "first_sample": int(first),
                                "start_response_max_um": float(np.max(np.abs(oe["start_response"]))) * 1e3}


def _frame_samples(n: int, framed: int, samples: float) -> slice:
    """The samples of a record of ``n`` whose loop frame (:func:`identification.loop_frame.loop_frame`)
    at a dead time of ``samples`` kept ``framed`` of them: it drops them at its start, except the last
    ``ceil(-samples)`` of an advanced reference."""
    stop = n - int(math.ceil(max(-samples, 0.0)))
    return slice(stop - framed, stop)


def _with_refined_delay(capture: Capture, axis: str, params: dict, poles: dict, err: np.ndarray, T: float,
                        b: PoleBounds, delay_s: float, fit: dict):
    """``(parameters, poles, error [mm], delay_s [s])`` after :func:`_refine_delay` on the recorded
    capture (the datum offset of ``fit`` removed), ``fit`` updated; unchanged when not kept."""
    i = capture.axis_index(axis)
    recorded = (capture.reference[:, i], capture.measured[:, i] - fit["offset"]["offset_mm"])
    refined = _refine_delay(params, poles, *recorded, T, b, delay_s / T, offset=bool(fit["offset"]["applied"]),
                            rms_now=float(np.sqrt(np.mean(err * err))))
    if refined is None:
        return params, poles, err, delay_s
    params, poles, err, d, c, oe = refined
    _record_initial_state(fit, oe, oe.get("first_sample", 0))
    fit["delay"].setdefault("equation_error_s", delay_s)
    fit["delay"].update(delay_s=d * T, samples=d, refined="output-error")
    fit["offset"]["offset_mm"] += c
    return params, poles, err, d * T


def _refine_delay(params: dict, poles: dict, xr: np.ndarray, x: np.ndarray, T: float, b: PoleBounds, samples: float,
                  *, offset: bool, rms_now: float):
    """The estimated dead time refined with the model by output error, on the recorded reference.

    The estimate of :func:`identification.dead_time.estimate_delay` is the equation error's, which
    trades a loop's own lag for a shift (fadal-ppi: 13.7 samples) and is biased by the noise of
    the differentiated measurement at fast sampling (0.125 ms: 54 samples); the simulated position
    is not. The shift is searched within 25 % (at least 5 samples) of the estimate, jointly with the
    model; returns ``(parameters, poles, error [mm], samples, offset [mm], output-error result)``, or None when it
    predicts no better on the same samples, or worse than the model it starts from did in the
    loop's frame (``rms_now`` [mm]: the error the fit reports does not grow). Both judgments take
    the reference delayed on the sub-step grid, as the loop frame now does
    (:mod:`identification.loop_frame`): on a 3 ms record the frame's linear delay had put the model
    started from 1.96 um off on the refinement's reference for its 0.81 in the frame, and fadal-smc's
    3 ms record with a 0.1 s lead refused 100.28 ms for that (the traceid5 audit). Judging both only
    on the frame's samples from the same start instead (the smclag helper's trial: the candidate was
    fitted on later ones) refused the refinement of fadal-smc's 1 ms records leading by 50 and 300 ms
    (50.08 and 300.00 ms at 1.03 and 1.35 um, for 50.64 and 300.64 ms at 0.575 and 0.581 um).
    """
    w = max(5.0, 0.25 * abs(samples))
    d_lo, d_hi = samples - w, samples + w
    keep, moving = _kept_samples(xr, x, samples, d_lo, d_hi)
    if keep.stop - keep.start < x.size // 2:
        return None
    def run(start: float, model: dict) -> dict:
        return _refined(lambda state: refine_output_error(model["parameters"], model["poles"], xr, x, T, bounds=b,
                                                          offset=offset, delay=(start, d_lo, d_hi), keep=keep,
                                                          initial_state=state), moving)

    oe = _restarted_delay(run, run(samples, {"parameters": params, "poles": poles}), d_lo, d_hi)
    held = substep_reference(xr, T)
    before = x[keep] - held.delayed(samples).simulate(params, keep)
    if "initial_state" in oe:
        before = before - fit_initial_state(params, T, -before)[1]
    oe["first_sample"] = keep.start
    d = oe["delay_samples"]
    err = (x[keep] - oe["offset_mm"] - held.delayed(d).simulate(oe["parameters"], keep)
           - oe.get("start_response", 0.0))
    rms = float(np.sqrt(np.mean(err * err)))
    if not (rms < np.sqrt(np.mean((before - np.median(before) * offset) ** 2)) and rms <= rms_now):
        return None
    log.info("reference dead time refined by output error: %.4g -> %.4g samples", samples, d)
    return oe["parameters"], oe["poles"], err, d, oe["offset_mm"], oe


def _with_setpoint_filter(capture: Capture, axis: str, params: dict, poles: dict, err: np.ndarray, T: float,
                          b: PoleBounds, delay_s: float, fit: dict, *, free_delay: bool):
    """``(parameters, poles, error [mm], delay_s [s], setpoint_filter_s [s])``: the model with a
    moving-average setpoint filter (:mod:`identification.setpoint_filter`) when the record shows one.

    On the recorded reference (the datum offset of ``fit`` removed), at the dead time of the fit
    and, when that was estimated and is shorter than half the longest filter, also at none (a
    moving average of L resembles a dead time of L/2, which the estimate took up: ballscrew-ppc's
    7.6 ms), the regression of Eq. (3.11) is solved on the reference through the filters of
    :data:`FILTER_SCREEN_S` (:func:`_filter_screen`). When the best of them lowers the regression's
    objective below :data:`FILTER_SCREEN_RATIO` times that without a filter, the filter's length is
    refined by output error jointly with the model (up to :data:`FILTER_MAX_S`) from that solution
    and from the central-difference regression at the same filter, the lower cost kept, and kept
    when it is at least :data:`MIN_FILTER_SAMPLES` long, predicts the same samples
    :data:`FILTER_GAIN` times better (RMS) than the model without it did, on them or in the loop's
    frame (``err`` [mm]), and the record shows the moving average's gain, 2/pi at 1/(2L) and its
    zero at 1/L (:func:`identification.filter_signature.shows_filter`; the gain alone: a 150 Hz
    mode logged at 2 ms imitated by a 9.7 ms filter for 1.57x). ``fit["setpoint_filter"]``
    records a search that ran.

    Measured on vcnc's machines with the reference through a 16 ms moving average before the loop
    (``benchmarks/recorded_traces.py``, case ``jerkf``): fitted without the filter, fadal-ppi's
    pair at 30.8 Hz / 0.64 for 52.3 Hz / 0.93 and 0.74 um RMS for 0.18; with it, 15.7 ms, 0.3 %
    off and 0.18 um. The refinement started from the model without the filter instead stopped on
    the way back from the poles it had bent (chevalier-pdf's 172 Hz pair 47 % off at 0.002 um
    RMS), and, on a record without a filter, far from none (the Table 3.2 test: 16 ms at 2.0 um
    RMS for 0.35 without, after 5.5 s). The screen's Savitzky-Golay derivatives (9 ms) smooth away
    a pair faster than about 100 Hz: from the screen's solution alone chevalier-pdf's 172 Hz pair
    ended on the 2000 Hz Nyquist bound (1057 % off, 16.0 ms found, the truth's poles predicting
    300x better); from the central-difference start it is 0.05 % off (the traceid5 truth harness).
    """
    i = capture.axis_index(axis)
    xr, x = capture.reference[:, i], capture.measured[:, i] - fit["offset"]["offset_mm"]
    d, longest = delay_s / T, FILTER_MAX_S / T
    delays = (d, 0.0) if free_delay and 0.0 < abs(d) <= 0.5 * longest else (d,)
    keep, moving = _kept_samples(xr, x, d, min(delays), max(delays))
    held = substep_reference(xr, T)
    screen = _filter_screen(held, x, keep, delays, T, b)
    if screen is None:
        return params, poles, err, delay_s, 0.0
    d, start, sol, ratio = screen
    offset = bool(fit["offset"]["applied"])
    before = x[keep] - held.delayed(delay_s / T).simulate(params, keep)
    if moving:
        before = before - fit_initial_state(params, T, -before)[1]
    rms_before = min(float(np.sqrt(np.mean((before - np.median(before) * offset) ** 2))),
                     float(np.sqrt(np.mean(err * err))))
    shifted = held.delayed(d)
    starts = [s for s in (sol, _screen_solution(shifted, x, keep, start, T, b, RegressorOptions())) if s is not None]
    runs = [_refined(lambda state, s=s: refine_output_error(s.parameters, s.poles, xr, x, T, bounds=b, offset=offset,
                                                           delay=d, keep=keep, initial_state=state,
                                                           setpoint_filter=(start, 0.0, longest)), moving)
            for s in starts]
    oe = {**min(runs, key=lambda r: r["cost"]), "nfev": sum(r["nfev"] for r in runs)}
    n = oe["filter_samples"]
    e = x[keep] - oe["offset_mm"] - shifted.filtered(n).simulate(oe["parameters"], keep)
    e = e - oe.get("start_response", 0.0)
    rms = float(np.sqrt(np.mean(e * e)))
    shown = (signature(shifted.at_samples(keep), x[keep], T, n * T, oe["parameters"])
             if n >= MIN_FILTER_SAMPLES else None)
    record = {"filter_s": 0.0, "searched_s": n * T, "screen_ratio": ratio, "rms_without_um": rms_before * 1e3,
              "rms_with_um": rms * 1e3, "signature": shown}
    fit["setpoint_filter"] = record
    if not (n >= MIN_FILTER_SAMPLES and rms * FILTER_GAIN <= rms_before and shows_filter(shown)):
        return params, poles, err, delay_s, 0.0
    log.info("setpoint filter: a moving average of %.4g ms, prediction %.4g -> %.4g um", n * T * 1e3,
             rms_before * 1e3, rms * 1e3)
    record.update(filter_s=n * T, samples=n)
    if d != delay_s / T:
        fit["delay"].update(delay_s=d * T, samples=d, refined="replaced by the setpoint filter")
    fit["offset"]["offset_mm"] += oe["offset_mm"]
    _record_initial_state(fit, {**oe, "first_sample": keep.start}, keep.start)
    fit.setdefault("output_error", {})["nfev"] = fit.get("output_error", {}).get("nfev", 0) + oe["nfev"]
    return oe["parameters"], oe["poles"], e, d * T, n * T


def _filter_screen(held, x: np.ndarray, keep: slice, delays: tuple, T: float, b: PoleBounds):
    """``(dead time [samples], filter [samples], SolveResult, objective ratio)`` of the exact-solver
    regression of Eq. (3.11) on ``x[keep]`` with the lowest objective over the dead times ``delays``
    and the filters of :data:`FILTER_SCREEN_S`; None when it does not lower the objective without a
    filter at the same dead time below :data:`FILTER_SCREEN_RATIO` times. The regression's
    derivatives are Savitzky-Golay ones (:func:`_smoothed_start`): central differences of a noisy
    measured position bias it towards a smoother reference (the Table 3.2 test, 0.2 um noise and
    1 um steps, no filter: 0.67 at 16 ms)."""
    best, without = None, {}
    opt = RegressorOptions(smoothing_window=max(SMOOTHED_START_MIN, int(round(SMOOTHED_START_S / T)) | 1))
    for c in delays:
        base = held.delayed(c)
        for length in (0.0, *FILTER_SCREEN_S):
            sol = _screen_solution(base, x, keep, length / T, T, b, opt)
            if sol is None:
                continue
            if length == 0.0:
                without[c] = sol.objective
            elif best is None or sol.objective < best[2].objective:
                best = (c, length / T, sol)
    if best is None or best[0] not in without or not best[2].objective <= FILTER_SCREEN_RATIO * without[best[0]]:
        return None
    return (*best, best[2].objective / without[best[0]])


def _screen_solution(base, x: np.ndarray, keep: slice, samples: float, T: float, b: PoleBounds,
                     opt: RegressorOptions) -> SolveResult | None:
    """The exact-solver regression of Eq. (3.11) on ``x[keep]`` with the (delayed) sub-step reference
    ``base`` through a moving average of ``samples``, its derivatives as ``opt`` says; None when it fails."""
    ref = base.filtered(samples).at_samples(keep)
    stats = SufficientStatistics(8)
    try:
        for phi, y in iter_regressor(ref, x[keep], T, options=opt):
            stats.update(phi, y)
        return solve_statistics(stats, bounds=b, method="exact", identifiability=True)
    except IdentificationError:
        return None


def _kept_samples(xr: np.ndarray, x: np.ndarray, samples: float, d_lo: float, d_hi: float) -> tuple[slice, bool]:
    """``(samples the joint refinement's residual is taken on, whether to fit the state at the first)``
    for a recorded reference ``xr`` delayed by ``samples`` within [``d_lo``, ``d_hi``]: those the shift
    leaves unknown left out at the end, and at the start unless the record starts at rest
    (:mod:`identification.loop_frame`); then the first kept sample is where the axis first rests,
    or, with no rest in the first half, where the state is fitted."""
    hi = x.size - int(math.ceil(max(-d_lo, 0.0)))
    delayed = delay_reference(xr, samples)
    lo, moving = 0, False  # simulated from rest (identification.loop_frame)
    if not starts_at_rest(xr[:hi], delayed[:hi], x[:hi]):
        lo = int(math.ceil(max(d_hi, 0.0)))
        moving = starts_in_motion(delayed[lo:hi], x[lo:hi])  # no rest in the first half: fit the state there
        lo += settled_start(delayed[lo:hi], x[lo:hi]) or 0
    return slice(lo, hi), moving


def _restarted_delay(run, oe: dict, d_lo: float, d_hi: float) -> dict:
    """The joint output-error result ``oe`` restarted (``run(start [samples], model)``) from its
    model with the dead time :data:`DELAY_RESTART_SAMPLES` either side of its own, while a restart
    lowers the cost by at least :data:`DELAY_RESTART_GAIN` (at most :data:`DELAY_RESTARTS` rounds).

    The joint cost is not smooth in the dead time: the friction switches on the sign of the
    *predicted* velocity, and near each reversal a shift of a fraction of a sample flips it at one
    sample (a 2 um step over ten samples on the exact FADAL_PID_X model), so the cost along the
    shift is a bowl with a step at each of the record's reversals and the trust region stops on
    one of them. The exact model with its reference recorded 50 samples ahead, started at the
    equation error's 50.47: stopped at 50.44 (0.133 um RMS) with the friction pattern frozen too (a
    true local minimum); restarted at 49.94 or 50.19: 50.000008 (0.000001 um); at 49.44: 49.49
    (0.110 um). Half a sample steps over such steps and stays in the bowl.
    """
    for _ in range(DELAY_RESTARTS):
        d = oe["delay_samples"]
        tries = [run(c, oe) for c in (d - DELAY_RESTART_SAMPLES, d + DELAY_RESTART_SAMPLES) if d_lo <= c <= d_hi]
        best = min(tries, key=lambda o: o["cost"], default=oe)
        if not best["cost"] <= (1.0 - DELAY_RESTART_GAIN) * oe["cost"]:
            break
        log.info("joint dead time restarted: %.4g -> %.4g samples, cost %.4g -> %.4g mm^2", d,
                 best["delay_samples"], oe["cost"], best["cost"])
        oe = {**best, "nfev": best["nfev"] + oe["nfev"]}
    return oe


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
    wide = _wide_box(sol.poles, b)
    if wide is None:
        return sol, b, None
    sol2 = solve_statistics(stats, bounds=wide, method=method, seed=seed, ga_options=ga_options, identifiability=True)
    rms = [_prediction_rms_from(s.parameters, xr, x, T, moving=False) for s in (sol, sol2)]
    if not rms[1] <= 0.99 * rms[0]:
        return sol, b, None
    log.info("slow pole on the %.3g Hz bound; p allowed down to %.3g Hz (prediction %.4g -> %.4g um RMS)",
             b.p_hz[0], WIDE_P_MIN_HZ, rms[0] * 1e3, rms[1] * 1e3)
    return sol2, wide, _widened_record(b, rms)


def _wide_box(poles: dict, b: PoleBounds) -> PoleBounds | None:
    """The box with p allowed down to :data:`identification.bounds.WIDE_P_MIN_HZ` when the slowest closed-loop
    pole (p, or the slow root of the pair when all three poles are real) lies within 1.5x of p's lower bound,
    else None."""
    lo, zeta = b.p_hz[0], poles["zeta"]
    pair_slow = poles["omega_n_hz"] * (zeta - math.sqrt(zeta * zeta - 1.0)) if zeta >= 1.0 else poles["omega_n_hz"]
    if not (min(poles["p_hz"], pair_slow) <= lo * 1.5 and lo > WIDE_P_MIN_HZ):
        return None
    return dataclasses.replace(b, p_hz=(WIDE_P_MIN_HZ, b.p_hz[1]))


def _widened_record(b: PoleBounds, rms: list[float]) -> dict:
    """``fit.bounds_widened``: p's lower bound before and after, and the prediction RMS before and after (``rms`` in
    mm, recorded in um)."""
    return {"p_hz_from": b.p_hz[0], "p_hz_to": WIDE_P_MIN_HZ, "rms_before_um": rms[0] * 1e3,
            "rms_after_um": rms[1] * 1e3}


def _widen_refined(params: dict, poles: dict, err: np.ndarray, xr: np.ndarray, x: np.ndarray, T: float,
                   b: PoleBounds, fit: dict) -> tuple[dict, dict, np.ndarray, PoleBounds, dict | None]:
    """``(parameters, poles, error [mm], box, record)``: :func:`_widen_for_p` for the refined model.

    Noise biases the equation-error solution off the 0.2 Hz bound, and only the output-error refinement
    puts p on it: EMPS with 1 um noise and a 2 um encoder (18 moves of +-3 mm, 1.3 s) is solved at
    35.7 Hz / 0.21 / p 0.51 Hz, refined to 20.7 Hz / 0.37 / p 0.2 Hz (1.96 um RMS), where without noise
    the box is widened and p ends at 0.012 Hz. Left on the bound, the slow pole's integral action
    pulls the rest error of a loop without one to zero, and the diagnosis named a ``drift`` that is not
    there (2.5 um/s; ``benchmarks/ident_fuzz.py``). The refinement is run again from there with p down to
    :data:`identification.bounds.WIDE_P_MIN_HZ` and kept, as in :func:`_widen_for_p`, when it predicts at
    least 1 % better (``fit.bounds_widened`` with ``after: "output-error"``). A fitted initial state is
    left as it is (it imitates a slow pole's free response, :func:`_refined`).
    """
    wide = None if "initial_state" in fit else _wide_box(poles, b)
    if wide is None:
        return params, poles, err, b, None
    oe = refine_output_error(params, poles, xr, x, T, bounds=wide)
    err2 = x - simulate_record(oe["parameters"], xr, T)
    rms = [float(np.sqrt(np.mean(e * e))) for e in (err, err2)]
    if not rms[1] <= 0.99 * rms[0]:
        return params, poles, err, b, None
    log.info("refined slow pole on the %.3g Hz bound; p allowed down to %.3g Hz (prediction %.4g -> %.4g um RMS)",
             b.p_hz[0], WIDE_P_MIN_HZ, rms[0] * 1e3, rms[1] * 1e3)
    fit["output_error"].update(nfev=fit["output_error"]["nfev"] + oe["nfev"], cost_mm2=oe["cost"])
    widened = {**_widened_record(b, rms), "after": "output-error"}
    fit["bounds_widened"] = widened
    return oe["parameters"], oe["poles"], err2, wide, widened


def _fastest_pole_hz(poles: dict) -> float:
    """The fastest closed-loop pole [Hz]: p, or the pair's fast root when all three poles are real."""
    wn, zeta = poles["omega_n_hz"], poles["zeta"]
    return max(poles["p_hz"], wn * (zeta + math.sqrt(zeta * zeta - 1.0)) if zeta >= 1.0 else wn)


def _pair_below_nyquist(stats: SufficientStatistics, params: dict, poles: dict, err: np.ndarray, xr: np.ndarray,
                        x: np.ndarray, T: float, b: PoleBounds, fit: dict) -> tuple[dict, dict, np.ndarray]:
    """``(parameters, poles, error [mm])``: the refinement started again with the poles' pair complex when
    the refined model has its fastest pole near the box's upper bound (the record's Nyquist frequency).

    A fast real pole near Nyquist and a second real one below it can stand in for a damped pair: fadal-ppi
    (P-PI, no feedforward: p 4.68 Hz and a pair at 36.3 Hz / 0.75) on CAM program 0136 was solved by the
    equation error at p on 500 Hz and a pair at 9.6 Hz / 1.26 (real poles 4.70, 19.5 Hz), refined to 0.517 um
    RMS with its third pole at 496 Hz; the same regression solved with zeta <= 1 (p 4.70 Hz, pair 65.9 Hz
    / 1.0) refines to 0.462 um off the bound (p 4.62 Hz, pair 68.4 Hz / 0.98; the fine descent alone
    stops at 3.39 um, so the coarse one always follows here), and the truth's poles
    refine to 0.42 um (38.9 Hz / 0.75): the record pins p, and the pair below its bound. Kept when it
    predicts better (RMS), recorded in ``fit.output_error.pair_restart``.
    """
    if _fastest_pole_hz(poles) < NEAR_NYQUIST * b.p_hz[1] or b.zeta[0] >= 1.0:
        return params, poles, err
    complex_box = dataclasses.replace(b, zeta=(b.zeta[0], min(b.zeta[1], 1.0)))
    try:
        start = solve_statistics(stats, bounds=complex_box, method="exact")
    except IdentificationError:
        return params, poles, err
    oe = refine_output_error(start.parameters, start.poles, xr, x, T, bounds=b, coarse=True)
    err2 = x - simulate_record(oe["parameters"], xr, T)
    rms = [float(np.sqrt(np.mean(e * e))) for e in (err, err2)]
    fit["output_error"]["nfev"] += oe["nfev"]
    fit["output_error"]["pair_restart"] = {"rms_before_um": rms[0] * 1e3, "rms_after_um": rms[1] * 1e3,
                                           "kept": bool(rms[1] < rms[0])}
    if not rms[1] < rms[0]:
        return params, poles, err
    log.info("fastest pole %.4g Hz near the %.4g Hz bound; started again with a complex pair: %.4g -> %.4g um RMS",
             _fastest_pole_hz(poles), b.p_hz[1], rms[0] * 1e3, rms[1] * 1e3)
    fit["output_error"]["cost_mm2"] = oe["cost"]
    return oe["parameters"], oe["poles"], err2


def _dead_time(delay: str | float, xr: np.ndarray, x: np.ndarray, T: float, opt: RegressorOptions, b: PoleBounds,
               *, free_offset: bool = False):
    """``(delay_s, record)``: the estimated or given dead time [s] and what to report of it.

    An estimated shift is kept only when the constrained model fitted on the shifted reference
    predicts the measured position at least twice better (RMS of the simulation, on the same
    samples) than the one fitted without it: the regression alone can trade loop lag for a shift
    (fadal-ppi, no shift: the regression's best shift is 13.7 samples; its model predicts 19.4 um RMS, 16.7 without).
    The samples the shift leaves unknown are left out at the end; at the start only when the record
    does not start at rest (:func:`identification.loop_frame.starts_at_rest`; otherwise the
    delayed reference's held first value is right). Cutting the start regardless left chevalier-pdf,
    whose x axis never stands still after it, with a record in motion whose first "rest" was a
    0.6 mm/s slowdown: its reference recorded 20 ms late, found exactly (-80 samples at 0.25 ms),
    was rejected (118 um for 121) and the fit ended at 1720 Hz for 172 (45 um RMS).
    """
    if isinstance(delay, str):
        if delay != "auto":
            raise IdentificationError(f"delay must be 'auto' or a number of seconds, got {delay!r}")
        est = estimate_delay(xr, x, T, options=opt)
        record = {"estimated": True, **est.to_dict()}
        if est.delay_s:
            m = int(math.ceil(abs(est.samples)))
            first = 0 if starts_at_rest(xr, delay_reference(xr, est.samples), x) else m
            rms0, rms1 = (_prediction_rms(xr, x, T, d, opt, b, keep=slice(first, x.size - m), free_offset=free_offset)
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


def _datum_offset(xr: np.ndarray, x: np.ndarray, T: float, opt: RegressorOptions, b: PoleBounds) -> OffsetEstimate:
    """The datum offset (:mod:`identification.datum_offset`), removed before the fit when it is a
    large one (over :data:`identification.datum_offset.COARSE_SHARE` of the RMS tracking error:
    the regression's own bias is a few um, fadal-pid 2.0, fadal-ppi 1.5) and removing it lets the
    exact-solver model predict at least :data:`identification.datum_offset.MIN_GAIN` times better.
    Smaller offsets are left to the output-error refinement (:func:`_refine`)."""
    c = estimate_offset(xr, x, T, options=opt)
    if not (math.isfinite(c) and abs(c) > COARSE_SHARE * float(np.sqrt(np.mean((x - xr) ** 2)))):
        return OffsetEstimate(0.0, c if math.isfinite(c) else 0.0, False)
    rms0, rms1 = (_prediction_rms(xr, x - d, T, 0.0, opt, b, keep=slice(None)) for d in (0.0, c))
    applied = rms1 * MIN_GAIN <= rms0
    return OffsetEstimate(c if applied else 0.0, c, applied, rms0 * 1e3, rms1 * 1e3)


def _combined(first: OffsetEstimate, second: OffsetEstimate) -> OffsetEstimate:
    """The offset removed in two passes (before and after the dead time) as one record."""
    if not second.applied:
        return first if first.applied else second
    total = first.offset_mm + second.offset_mm
    return OffsetEstimate(total, first.offset_mm + second.estimated_mm, True,
                          first.rms_without_um if first.applied else second.rms_without_um, second.rms_with_um)


def _prediction_rms(xr: np.ndarray, x: np.ndarray, T: float, samples: float, opt: RegressorOptions, b: PoleBounds,
                    *, keep: slice, free_offset: bool = False) -> float:
    """RMS [mm] of the exact-solver model fitted on the reference delayed by ``samples``, on x[keep];
    with ``free_offset`` (a datum offset was removed, its estimate a few um off) less its median error."""
    ref = delay_reference(xr, samples)[keep]
    meas = x[keep]
    start = settled_start(ref, meas) or 0  # simulated from rest: start where the axis rests
    ref, meas = ref[start:], meas[start:]
    st = SufficientStatistics(8)
    for phi, y in iter_regressor(ref, meas, T, options=opt):
        st.update(phi, y)
    sol = solve_statistics(st, bounds=b, method="exact")
    err = meas - simulate_record(sol.parameters, ref, T)
    if free_offset:
        err = err - np.median(err)
    return float(np.sqrt(np.mean(err * err)))
