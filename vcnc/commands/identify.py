"""``vcnc identify CAPTURE``: fit the reduced closed-loop model of one axis to a capture.

Reads a capture CSV or an EMPS ``.mat`` file, identifies the model of Eq. (3.3) of the thesis
(``--method exact|ga|kkt``, output-error refinement by default), prints a summary, and writes the
model file (``--json``) and an HTML report (``--report``: measured vs predicted, residual, FRFs,
parameter table). Everything is computed before anything is written; a failure leaves no file.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from vcnc.commands.trace_options import add_trace_arguments, read_trace_argument
from vcnc.core.axes import axis_unit

HELP = "identify the reduced closed-loop model of an axis from a capture (CSV, control trace or EMPS .mat)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("capture", metavar="CAPTURE",
                        help="capture CSV, control trace (TNCscope, SINUMERIK XML, TwinCAT, halscope, camonitor, "
                             "delimited text) or EMPS .mat file, detected by content")
    parser.add_argument("--axis", default=None, help="axis to identify (default: x, or the only axis)")
    parser.add_argument("--method", choices=("exact", "ga", "kkt"), default="exact", help="constrained solver")
    parser.add_argument(
        "--refine",
        choices=("output-error", "none"),
        default="output-error",
        help="refine the equation-error solution by output error (default)",
    )
    parser.add_argument("--seed", type=int, default=0, help="random seed (ga)")
    parser.add_argument("--json", metavar="MODEL.json",
                        help="write the model file (vcnc.axis-model/1; /2 with a reference dead time, /3 with a "
                             "setpoint filter)")
    parser.add_argument("--report", metavar="DIR", help="write an HTML report with figures into DIR")
    parser.add_argument("--no-diagnose", action="store_true", help="skip the residual diagnosis")
    parser.add_argument("--p-min-hz", type=float, default=None,
                        help="lower bound of the real pole p [Hz] (default 0.2; lower it for loops without "
                             "integral action, e.g. EMPS)")
    parser.add_argument("--omega-min-hz", type=float, default=None, help="lower bound of omega_n [Hz] (default 0.2)")
    parser.add_argument("--delay", type=_delay, default="auto", metavar="auto|SECONDS",
                        help="dead time of the recorded reference [s] (> 0: it leads the loop); 'auto' estimates it "
                             "(default auto, kept only when it halves the prediction error)")
    parser.add_argument("--no-setpoint-filter", action="store_true",
                        help="do not search a moving-average setpoint filter between the recorded reference and "
                             "the loop (by default one is kept when it predicts 1.6x better)")
    parser.add_argument("--drift", choices=("auto", "remove", "keep"), default="auto",
                        help="a slow drift of the measured channel against the commanded one (thermal growth of a "
                             "scale or laser logged beside the loop's encoder): 'auto' takes it out and fits again "
                             "when it is large against the prediction error and that predicts twice better (default), "
                             "'remove' always, 'keep' never (it is still named)")
    parser.add_argument("--zeta", type=float, nargs=2, metavar=("MIN", "MAX"), default=None,
                        help="bounds of the damping ratio (default 0.2 2.0)")
    add_trace_arguments(parser)


def _delay(text: str) -> str | float:
    """``--delay``: 'auto' or a finite number of seconds (anything else exits 2, named by argparse)."""
    if text == "auto":
        return text
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected 'auto' or a finite number of seconds, got {text!r}")
    return value


def delay_lines(model) -> list[str]:
    """What to say of the reference dead time ``model.delay_s`` and its ``fit['delay']`` record."""
    rec = model.fit.get("delay") or {}
    T = model.sample_time
    d = float(getattr(model, "delay_s", 0.0))
    if rec.get("estimated"):
        how = (f"estimated {rec.get('samples', 0.0):.3g} samples (objective ratio "
               f"{rec.get('objective_ratio', float('nan')):.3g})")
        if "rms_with_um" in rec:
            how += (f", prediction {rec['rms_without_um']:.4g} -> {rec['rms_with_um']:.4g} "
                    f"{axis_unit(model.axis, small=True)} with the shift")
        if d == 0.0 and rec.get("samples"):
            how += f"; not used: {_unused_shift(rec)}"
    elif rec:
        how = "given"
    else:
        how = "none"
    lines = [f"reference dead time: {d:.6g} s ({d / T:.4g} samples; {how})"]
    if rec.get("estimated") and rec.get("scanned_s"):
        lo, hi = rec["scanned_s"]
        found = rec.get("equation_error_s", rec.get("samples", 0.0) * T)
        if hi > lo and min(found - lo, hi - found) <= 2.0 * T:
            which = "leads" if found > 0.5 * (lo + hi) else "lags"
            lines.append(f"warning: the best shift of the reference, {found:.4g} s, sits at the edge of the scanned "
                         f"{lo:.4g}..{hi:.4g} s: the recorded reference probably {which} the loop by more; give the "
                         "dead time with --delay SECONDS, or record a trace whose channels are sampled together")
    return lines


def _unused_shift(rec: dict) -> str:
    """Why the scan's best shift of the reference (``fit['delay']``) was not taken as the dead time
    (:func:`identification.dead_time.estimate_delay`'s rule)."""
    from identification.dead_time import MAX_OBJECTIVE_RATIO, MIN_DELAY_SAMPLES

    if 0.0 <= rec["samples"] < MIN_DELAY_SAMPLES:
        return (f"shorter than {MIN_DELAY_SAMPLES:g} samples, which the loop model's own lag cannot be told from")
    ratio = rec.get("objective_ratio", float("nan"))
    if not ratio <= MAX_OBJECTIVE_RATIO:
        where = "ahead of" if rec["samples"] > 0 else "behind"
        return (f"it lowers the equation error to {100 * ratio:.3g} % only, where a reference recorded {where} the "
                f"loop lowers it below {100 * MAX_OBJECTIVE_RATIO:g} %")
    if "rms_with_um" in rec:  # identification.identify._dead_time: kept when it predicts twice better
        return (f"the exact-solver model fitted on the shifted reference predicts {rec['rms_with_um']:.4g} for "
                f"{rec['rms_without_um']:.4g} without the shift, not twice better (both before the output-error "
                "refinement; the final prediction is the one above)")
    return "not kept by the fit"


def weak_poles_line(model) -> str:
    """What to say when the equation error barely depends on the poles (``fit['solver']['identifiability']``).

    The ranges are those of the first stage, the equation-error problem, around its own solution; the
    output-error refinement may then have moved the poles outside them (a fadal-pid copy at 0.5 ms on
    CAM program 0126: omega_n 136-581 Hz around the equation error's 186 Hz, p 0.2 Hz; refined, the pair
    at 33.0 Hz / 0.59 and p 1.76 Hz, truth 33.0 Hz / 0.45 and 1.17 Hz; continued with the coarse step,
    the refinement reached 92.6 Hz / 0.96 and p 1.99 Hz at 1.147 um RMS, where the truth's poles predict
    1.119 um: the record pins the prediction, not the poles). The line says whose ranges they
    are, and whether the poles above lie in them, so that it does not read as the tool contradicting
    itself, and what to trust: the prediction. A flat valley comes from a loop whose tracking barely
    depends on its poles, as when feedforward cancels the closed loop (thesis Tables 3.5 and 4.2), or
    from a record that excites them too little."""
    fit = model.fit
    valley = fit["solver"]["identifiability"]
    ee = fit["solver"].get("poles", {})
    line = (f"poles weakly identifiable: in the first stage, the equation error, the poles are pinned only to "
            f"omega_n {valley['omega_n_hz'][0]:.3g}-{valley['omega_n_hz'][1]:.3g} Hz, zeta "
            f"{valley['zeta'][0]:.2f}-{valley['zeta'][1]:.2f}, p {valley['p_hz'][0]:.3g}-{valley['p_hz'][1]:.3g} Hz "
            f"(its error within {valley['tolerance']:.0%} of its minimum")
    line += (f" at omega_n {ee['omega_n_hz']:.3g} Hz, zeta {ee['zeta']:.2f}, p {ee['p_hz']:.3g} Hz)" if ee else ")")
    outside = [k for k in ("omega_n_hz", "zeta", "p_hz")
               if not valley[k][0] * (1 - 1e-9) <= model.poles[k] <= valley[k][1] * (1 + 1e-9)]
    if outside:
        line += ("; the output-error refinement, which fits the simulated position, ended outside those ranges, "
                 "at the poles above")
    return line + ("; the record hardly shows the poles (feedforward cancelling the closed loop, as in thesis "
                   "Tables 3.5 and 4.2, or too little excitation): trust the model's prediction above, within "
                   "the record's operating range, not its poles")


def pair_restart_line(model) -> str | None:
    """What to say when the refinement was started again with a complex pair and that start was kept
    (``fit['output_error']['pair_restart']``, :func:`identification.identify.fit_reduced_model`): the first
    result had its fastest pole near the record's Nyquist frequency. None otherwise."""
    rec = model.fit.get("output_error", {}).get("pair_restart")
    if not rec or not rec["kept"]:
        return None
    u = axis_unit(model.axis, small=True)
    return (f"note: the refinement from the equation error's solution ended with its fastest pole near the record's "
            f"Nyquist frequency ({rec['rms_before_um']:.4g} {u} RMS); started again with the poles' pair complex it "
            f"predicts {rec['rms_after_um']:.4g} {u}, kept; the two fits' poles differ far more than their "
            "predictions do: the record pins the prediction better than the poles")


def pair_pinned_line(model) -> str | None:
    """What to say when refinements started across the pair's frequency ended at distinct poles that predict the
    record nearly equally (``fit['output_error']['pair_starts']``, :mod:`identification.pair_starts`): the record
    does not pin the poles, and those printed are one of several sets. None otherwise."""
    rec = model.fit.get("output_error", {}).get("pair_starts")
    if not rec or rec["pinned"]:
        return None
    from identification.pair_starts import TIED_RMS

    u = axis_unit(model.axis, small=True)
    tied = rec["tied"]
    return (f"poles not pinned by this record: refined from {len(rec['fits'])} starts across the pair's frequency, "
            f"fits with omega_n {tied['omega_n_hz'][0]:.3g}-{tied['omega_n_hz'][1]:.3g} Hz, zeta "
            f"{tied['zeta'][0]:.2f}-{tied['zeta'][1]:.2f}, p {tied['p_hz'][0]:.3g}-{tied['p_hz'][1]:.3g} Hz predict "
            f"within {TIED_RMS - 1:.0%} of the best ({rec['fits'][rec['kept']][3]:.4g} {u} RMS); the poles above are "
            "the best of them, not a measurement of the loop's: trust the prediction, not the poles")


def closed_loop_poles_line(model) -> str:
    """The three closed-loop poles as the loop has them (thesis Tables 3.3-3.5), beside omega_n, zeta and p: with
    zeta > 1 the pair is two real poles, and the same three real poles can be written with either as p (a TNCscope
    trace quantised to 1 um: omega_n 16.3 Hz, zeta 1.29, p 0.77 Hz and omega_n 2.39 Hz, zeta 1.77, p 167 Hz both
    have real poles near 0.75 and 7.7 Hz and differ in the fast third one), so an engineer compares these."""
    rows = []
    for r in sorted(model.pole_table(), key=lambda r: r["frequency_hz"]):
        if r["imag"] < 0.0:
            continue  # a complex pair is named once
        rows.append(f"{r['frequency_hz']:.4g} Hz " + (f"(pair, damping {r['damping']:.3g})" if r["imag"] else "(real)"))
    return "closed-loop poles: " + ", ".join(rows)


def excitation_line(model) -> str:
    """The operating range the record covered (``fit['excitation']``, :mod:`identification.excitation`)."""
    rec = model.fit["excitation"]
    u = axis_unit(model.axis)
    return (f"operating range of the record: commanded speed up to {rec['speed_mm_s']:.4g} {u}/s (99 % of its moving "
            f"time; largest {rec['speed_max_mm_s']:.4g} {u}/s), acceleration up to {rec['acceleration_max_mm_s2']:.4g} "
            f"{u}/s^2: the model is fitted there, and predicts a faster reference by extrapolation (vcnc compare "
            "notes it)")


def setpoint_filter_lines(model) -> list[str]:
    """What to say of the setpoint filter ``model.setpoint_filter_s`` and its ``fit['setpoint_filter']`` record."""
    rec = model.fit.get("setpoint_filter")
    if not rec:
        return []
    u = axis_unit(model.axis, small=True)
    L = float(getattr(model, "setpoint_filter_s", 0.0))
    if not L:
        return [f"setpoint filter: none (the best, {rec['searched_s']:.4g} s, predicts {rec['rms_without_um']:.4g} -> "
                f"{rec['rms_with_um']:.4g} {u})"]
    return [f"setpoint filter: moving average of {L:.6g} s ({L / model.sample_time:.4g} samples; prediction "
            f"{rec['rms_without_um']:.4g} -> {rec['rms_with_um']:.4g} {u} with it)"]


#: The option that moves each bound of the pole box, for the message.
_BOUND_OPTIONS = {("omega_n_hz", 0): "--omega-min-hz", ("p_hz", 0): "--p-min-hz", ("zeta", 0): "--zeta MIN MAX",
                  ("zeta", 1): "--zeta MIN MAX"}


def drift_lines(model) -> list[str]:
    """What to say of the measured channel's drift (``fit['drift']``, :func:`drift_record`)."""
    rec = model.fit.get("drift")
    if not rec or not rec["named"]:
        return []
    u = axis_unit(model.axis, small=True)
    what = (f"the measured channel drifts against the commanded one by {rec['span_um']:.4g} {u} over the record "
            f"({rec['rate_um_min']:.4g} {u}/min on average, at most {rec['max_um']:.4g} {u} from where it started)")
    tried = "rms_removed_um" in rec
    how = f"prediction {rec.get('rms_kept_um', 0.0):.4g} -> {rec.get('rms_removed_um', 0.0):.4g} {u}"
    if rec["removed"]:
        return [f"drift: {what}; taken out before the fit" + (f" ({how})" if tried else "")]
    if tried:
        return [f"drift: {what}; left in: taking it out predicts {how}, less than twice better (--drift remove takes "
                "it out)"]
    if "refit_refused" in rec:
        return [f"drift: {what}; left in: the fit with it taken out was refused ({rec['refit_refused']})"]
    return [f"warning: {what}, {rec['ratio']:.3g} times the prediction error: thermal growth of a scale or laser "
            "logged beside the loop's own encoder, or an offset that creeps; the reduced model has no term for it and "
            "bends its slow pole p to imitate it; fit again with --drift remove"]


def bound_lines(model) -> list[str]:
    """What to say of a pole variable the fit left on a bound of its box (``model.poles_on_bounds()``): the data
    did not place it there, the box did; at the record's Nyquist frequency the loop may be faster than the record
    resolves (thesis Sec. 4.3: the box reaches the Nyquist frequency). A slow pole on its lower bound beside a
    drift the fit did not remove (:func:`drift_lines`) is the drift's doing: the line says so instead of advising
    ``--p-min-hz``. On the widened bound (:data:`identification.bounds.WIDE_P_MIN_HZ`, which the fit only opens when
    the data put p on 0.2 Hz) p is a loop without integral action, as the diagnosis reads it too
    (:func:`identification.diagnosis.diagnose` leaves it out of its bound warning): a note, not a warning to move the
    bound (EMPS, a LinuxCNC halscope trace and a 100 ms CNC log were all told "the box, not the data, placed it
    there")."""
    from identification.bounds import WIDE_P_MIN_HZ
    from identification.measured_drift import drift_left_in

    drifting = drift_left_in(model.fit) is not None
    out = []
    names = {"omega_n_hz": ("omega_n", "Hz"), "p_hz": ("p", "Hz"), "zeta": ("zeta", "")}
    for key, side, at_nyquist in model.poles_on_bounds():
        name, unit = names[key]
        shown = f"{model.poles[key]:.4g} {unit}".rstrip()
        what = f"{name} {shown} sits on the {('lower', 'upper')[side]} bound of its box"
        if at_nyquist:
            out.append(f"warning: {what}, the record's Nyquist frequency ({0.5 / model.sample_time:.4g} Hz at Ts = "
                       f"{model.sample_time:g} s): the loop may be faster than this record resolves; record it "
                       "at a shorter sample time")
        elif drifting and key == "p_hz":
            out.append(f"warning: {what}: the measured channel's drift (above) holds it there; fit again with "
                       "--drift remove")
        elif key == "p_hz" and side == 0 and model.bounds["p_hz"][0] <= WIDE_P_MIN_HZ:
            out.append(f"p {shown} sits on the widened lower bound of its box: the loop shows no integral action "
                       "(p -> 0, a proportional position loop such as EMPS'; the slow pole is slower than this record "
                       "can tell and the model predicts as reported)")
        else:
            option = _BOUND_OPTIONS.get((key, side))
            out.append(f"warning: {what}: the box, not the data, placed it there"
                       + (f" (move the bound with {option})" if option else ""))
    return out


def from_rest_rms_um(capture, model, axis: str) -> float:
    """The model's prediction error [um] of all the capture's samples simulated from rest, as ``vcnc simulate`` and
    ``vcnc compare`` and the diagnosis' table ('all RMS') predict: ``fit['rms_um']`` unless the fit also fitted the
    state at the first sample (``fit['initial_state']``, :mod:`identification.initial_state`), whose free response
    is part of that number and of no later prediction."""
    rec = (model.validation or {}).get("record_rms_um")
    if rec:
        return float(rec[-1])
    if "initial_state" not in model.fit:
        return float(model.fit["rms_um"])
    import numpy as np

    e = capture.measured[:, capture.axis_index(axis)] - predicted_record(capture, model, axis)
    return float(np.sqrt(np.mean(e * e))) * 1e3


def prediction_line(model, from_rest_um: float) -> str:
    """The summary's prediction of the capture: ``fit['rms_um']``, and with a fitted state at the first sample
    (``fit['initial_state']``) also the error simulated from rest, which the table, the naive comparison and every
    later use of the model share. An ODrive joint-motor record whose first row is a logger's zeros was fitted at
    77.85 mdeg with a start state whose free response reached 3307 mdeg, and predicts 3146 mdeg from rest (the
    table's 'all RMS'); the summary said 77.85 and "11.3 times better" than the 879 mdeg following error."""
    fit = model.fit
    u = axis_unit(model.axis, small=True)
    line = f"prediction of the capture: rms {fit['rms_um']:.4g} {u}, max {fit['max_um']:.4g} {u}"
    start = fit.get("initial_state")
    if not start:
        return line
    return (line + f" with the state at its first sample fitted (a free response of up to "
            f"{start['start_response_max_um']:.4g} {u}: the record starts with the axis under way or off its "
            f"reference); simulated from rest, as the table below, vcnc simulate and vcnc compare predict, rms "
            f"{from_rest_um:.4g} {u}")


def _speeds_at(capture, axis: str, k: int) -> str:
    """The commanded and the measured speed of ``axis`` at sample ``k``, over its next few samples, in words."""
    i = capture.axis_index(axis)
    n = len(capture)
    k = min(max(int(k), 0), n - 2)
    m = min(START_SPEED_SAMPLES, n - 1 - k)
    T = float(capture.t[1] - capture.t[0])
    u = axis_unit(axis)
    cmd, meas = (abs(float(c[k + m, i] - c[k, i])) / (m * T) for c in (capture.reference, capture.measured))
    return f"the axis moves at {meas:.4g} {u}/s, its command at {cmd:.4g} {u}/s"


#: Samples over which :func:`record_start_lines` measures the speeds at the sample where the fit starts.
START_SPEED_SAMPLES = 3


def record_start_lines(capture, model, axis: str, rest_um: float) -> list[str]:
    """A warning for a record that starts with the axis under way, which the fit handled in one of two ways
    (:mod:`identification.loop_frame`): its first samples dropped up to the first rest (``fit['record_start']``,
    :func:`identification.segments.settled_start`), or, with no rest in its first half, the model's state at its
    first sample fitted (``fit['initial_state']``, :mod:`identification.initial_state`).

    Our reading of what a user tuning a drive needs (traces40; no source states it): the model describes the loop
    either way, but ``vcnc simulate`` and ``vcnc compare`` start it from rest at the record's first sample, where the
    axis was moving, and answer with a start transient the loop never had; that was said nowhere when samples were
    dropped (a CAMBER record's first 1.71 s left out without a word), and only inside the prediction line when the
    state was fitted. The warning names the speeds at the sample where the fit starts, what was done, what it costs
    a simulation from rest, and the cure: a trace triggered with the axis at rest."""
    fit = model.fit
    u = axis_unit(axis, small=True)
    cure = "trigger the trace with the axis at rest to keep the whole record"
    crop = fit.get("record_start")
    if crop:
        n = int(crop["dropped_samples"])
        return [f"warning: the record starts with the axis under way ({_speeds_at(capture, axis, 0)} at its first "
                f"sample): the fit starts where the axis first rests, {crop['dropped_s']:.4g} s in ({n} samples left "
                "out of the fit and the table); vcnc simulate and vcnc compare start the model from rest at the "
                f"record's first sample and predict those samples with a start transient the loop never had; {cure}"]
    start = fit.get("initial_state")
    if not start:
        return []
    first = int(start.get("first_sample", 0))
    where = "its first sample" if first == 0 else f"sample {first}, where the fit starts"
    led = getattr(model, "delay_s", 0.0) or 0.0
    if first > 0 and led > 0:
        where += (f" (the recorded reference leads the loop by {led:.4g} s: the loop's reference before it is "
                  "not in the record)")
    return [f"warning: the record starts with the axis under way ({_speeds_at(capture, axis, first)} at {where}) "
            f"and does not rest in its first half: the fit took the model's state there from the record (a free "
            f"response of up to {start['start_response_max_um']:.4g} {u}); simulated from rest, as the table, the "
            f"naive comparison, vcnc simulate and vcnc compare predict, the model answers with a start transient "
            f"the loop never had: rms {rest_um:.4g} {u} against the fit's {fit['rms_um']:.4g} {u}; {cure}"]


def baseline_lines(capture, model, axis: str, rest_um: float | None = None) -> list[str]:
    """The model against the two naive predictions of the capture (:func:`identification.dead_time.
    pure_delay_baseline`): the commanded position itself and the commanded position delayed by the best whole
    number of samples. Our reading (no source states it): a machine-tool engineer trusts a loop model when it
    explains what a pure delay does not; one that predicts the capture, or its held-out folds, no better than a
    pure delay has learnt nothing of the loop's dynamics from this record, whatever its poles, and the report says
    so instead of letting the poles stand as the loop's (a 100 ms CNC log: model 190 um, raw following error
    207 um, held-out 218 um). Like is compared with like: the model's prediction of all the samples with the naive
    ones of all the samples, its held-out error (the diagnosis' active samples) with the naive ones of the active
    samples in the diagnosis' frame (``validation.naive_active``: the reference as the loop saw it); a hydraulic
    rig's held-out 249 um was said to lose to a pure delay's 158 um, which covered its idle seconds too.
    ``rest_um``: :func:`from_rest_rms_um` where the caller has it already."""
    from identification.dead_time import pure_delay_baseline
    from identification.diagnosis import before_after_rows

    i = capture.axis_index(axis)
    base = pure_delay_baseline(capture.reference[:, i], capture.measured[:, i], capture.sample_time)
    u = axis_unit(axis, small=True)
    rows = before_after_rows(model) if model.validation else []
    # all the samples from rest, as the naive predictions (no fitted state at the first sample) and the table
    rms = from_rest_rms_um(capture, model, axis) if rest_um is None else rest_um
    held = float(rows[-1]["validation_rms_um"] or math.nan) if rows else math.nan
    fe, pd, k = base["following_error_rms_um"], base["pure_delay_rms_um"], base["pure_delay_samples"]
    naive = min(fe, pd)
    # the held-out errors cover the diagnosis' active samples: compared with the naive predictions of those
    active = (model.validation or {}).get("naive_active") or {}
    naive_held = min(active["following_error_rms_um"], active["pure_delay_rms_um"]) if active else naive
    line = (f"naive predictions of the capture: the commanded position itself rms {fe:.4g} {u} (the following "
            "error), " + (f"delayed by {k} samples ({base['pure_delay_s']:.4g} s) rms {pd:.4g} {u}" if k else
                          "and no whole-sample delay of it predicts better"))
    if naive > 0.0 and rms > 0.0:
        line += (f"; the model predicts {naive / rms:.3g} times better" if rms < naive else
                 f"; the model predicts {rms / naive:.3g} times worse")
    if active and math.isfinite(held):
        frame = (" (the reference as the loop sees it, after the dead time and setpoint filter above)"
                 if getattr(model, "delay_s", 0.0) or getattr(model, "setpoint_filter_s", 0.0) else "")
        line += (f"; on the {model.validation['samples']['identification']} active samples the held-out errors cover"
                 f"{frame}: following error {active['following_error_rms_um']:.4g} {u}, best pure delay "
                 f"{active['pure_delay_rms_um']:.4g} {u}, the model held out {held:.4g} {u}")
    out = [line]
    if not rms < naive:
        out.append(f"warning: the model predicts the capture ({rms:.4g} {u} rms) no better than the commanded position "
                   f"{'itself' if naive == fe else 'delayed by a whole number of samples'} ({naive:.4g} {u}): it "
                   "has learnt nothing of the loop's dynamics from this record (sampled slower than the loop responds, "
                   "or a measured channel that is not the loop's?); do not take its poles as the loop's")
    elif held >= naive_held:
        ref = active or base
        which = "itself" if naive_held == ref["following_error_rms_um"] else "delayed by a whole number of samples"
        out.append(f"warning: on its held-out folds the model predicts worse ({held:.4g} {u} rms) than the commanded "
                   f"position {which} ({naive_held:.4g} {u}" + (" on the same active samples" if active else "")
                   + "): what it fitted does not carry over to motion it was not fitted on; do not take its poles as "
                   "the loop's")
    return out


#: The diagnosis table's columns, headed as the summary heads them (:func:`identification.diagnosis.
#: format_before_after`), and the keys of :func:`identification.diagnosis.before_after_rows` they show.
DIAGNOSIS_COLUMNS = {"all RMS": "record_rms_um", "ident RMS": "identification_rms_um",
                     "ident max": "identification_max_um", "valid RMS": "validation_rms_um",
                     "valid max": "validation_max_um"}


def fit_lines(model, rest_um: float) -> list[str]:
    """The summary's lines on the fit, which the report's Fit section repeats word for word: the prediction of the
    capture (:func:`prediction_line`), the reference's dead time and setpoint filter, drift, poles on their bounds or
    not pinned by the record, and the record's operating range."""
    fit = model.fit
    lines = [prediction_line(model, rest_um)]
    lines += delay_lines(model) + setpoint_filter_lines(model) + drift_lines(model) + bound_lines(model)
    valley = fit.get("solver", {}).get("identifiability")
    if valley and not valley["identifiable"]:
        lines.append(weak_poles_line(model))
    lines += [line for line in (pair_restart_line(model), pair_pinned_line(model)) if line]
    if "excitation" in fit:
        lines.append(excitation_line(model))
    return lines


def predicted_record(capture, model, axis: str):
    """The model's prediction [mm] of the capture's measured channel ``axis`` simulated from rest, as the fit
    predicted the record (sub-steps below 1 ms) and with the datum offset the fit removed (``fit['offset']``) put
    back: the prediction :func:`from_rest_rms_um` measures, which the report plots."""
    from identification.augmented import predict_record
    from identification.loop_frame import offset_of

    return predict_record(model, capture.reference[:, capture.axis_index(axis)]) + offset_of(model.fit)


def prediction_rows(capture, model, axis: str, rest_um: float) -> list[list]:
    """The report's table of the prediction of the capture (RMS and max [um, mdeg on a rotary axis]), in the terms
    of the summary's :func:`prediction_line`: the fit's own number, and where the fit also fitted the state at the
    first sample (``fit['initial_state']``) the prediction simulated from rest beside it (``rest_um``, the
    summary's and the diagnosis table's 'all RMS'), which every later use of the model shares. The report showed
    the start-state fit's number alone (an ODrive record: 77.85 mdeg, 3146 mdeg from rest)."""
    import numpy as np

    i = capture.axis_index(axis)
    xr, x = capture.reference[:, i], capture.measured[:, i]
    fit = model.fit
    if fit.get("initial_state"):
        rest_max = float(np.max(np.abs(x - predicted_record(capture, model, axis)))) * 1e3
        rows = [["identified model, the state at its first sample fitted", fit["rms_um"], fit["max_um"]],
                ["identified model simulated from rest (as vcnc simulate and vcnc compare predict)", rest_um,
                 rest_max]]
    else:
        rows = [["identified model", fit["rms_um"], fit["max_um"]]]
    if "equation_error" in fit:
        rows.append(["equation-error solution", fit["equation_error"]["rms_um"], fit["equation_error"]["max_um"]])
    rows.append(["tracking error itself", float(np.sqrt(np.mean((xr - x) ** 2)) * 1e3),
                 float(np.max(np.abs(xr - x)) * 1e3)])
    return rows


def build_report(capture, model, axis: str, baseline: list[str], rest_um: float):
    """The HTML report of ``vcnc identify --report`` (:class:`vcnc.report.Report`): the model, the fit in the
    summary's words (:func:`fit_lines`, :func:`prediction_rows`), the figures and the diagnosis."""
    import numpy as np
    from matplotlib.figure import Figure

    from vcnc.report import Report

    i = capture.axis_index(axis)
    t = capture.t - capture.t[0]
    xr = capture.reference[:, i]
    x = capture.measured[:, i]
    xp = predicted_record(capture, model, axis)  # from rest, offset included: the table's and the summary's
    rep = Report(f"vcnc identify: axis {axis} of {capture.source or 'capture'}")
    u = axis_unit(axis, small=True)  # um, or mdeg on a rotary axis
    rep.heading("Model parameters (Eq. 3.3)")
    from identification.reduced_model import PARAMETER_UNITS

    # d0, d1 in the axis' unit: deg/s^2 on a rotary axis, as the model file's positions
    rep.table(["parameter", "value", "unit"], [[k, v, PARAMETER_UNITS[k].replace("mm", axis_unit(axis))]
                                               for k, v in model.parameters.items()])
    rep.table(
        ["pole variable", "value"],
        [["omega_n [Hz]", model.poles.get("omega_n_hz")], ["zeta [-]", model.poles.get("zeta")],
         ["p [Hz]", model.poles.get("p_hz")]],
        caption=f"method {model.method}; bounds {model.bounds}",
    )
    valley = model.fit.get("solver", {}).get("identifiability")
    if valley:
        rep.table(
            ["pole variable", "range with the equation error within " + f"{valley['tolerance']:.0%} of its minimum"],
            [["omega_n [Hz]", f"{valley['omega_n_hz'][0]:.4g} - {valley['omega_n_hz'][1]:.4g}"],
             ["zeta [-]", f"{valley['zeta'][0]:.3g} - {valley['zeta'][1]:.3g}"],
             ["p [Hz]", f"{valley['p_hz'][0]:.4g} - {valley['p_hz'][1]:.4g}"]],
            caption="identifiable" if valley["identifiable"] else
            "weakly identifiable poles, ranges of the equation error around its own solution (the first stage, "
            "before the output-error refinement, which may leave them): feedforward cancelling the closed loop "
            "(cf. thesis Tables 3.5, 4.2) or too little excitation; trust the prediction, not the poles",
        )
    rep.table(
        ["", "frequency [Hz]", "damping [-]"],
        [[f"pole {j + 1}", r["frequency_hz"], r["damping"]] for j, r in enumerate(model.pole_table())]
        + [[f"zero {j + 1}", r["frequency_hz"], r["damping"]] for j, r in enumerate(model.zero_table())],
        caption="Poles and zeros as in Tables 3.3-3.5",
    )
    rep.heading("Fit")
    for line in fit_lines(model, rest_um) + record_start_lines(capture, model, axis, rest_um) + baseline:
        rep.text(line)
    rep.table(["prediction of the capture", f"RMS [{u}]", f"max [{u}]"], prediction_rows(capture, model, axis, rest_um))
    fig = Figure(figsize=(10, 6))
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    ax1.plot(t, (xr - x) * 1e3, label="measured tracking error")
    ax1.plot(t, (xr - xp) * 1e3, "--", label="predicted tracking error")
    ax1.set_ylabel(f"x_r - x [{u}]")
    ax1.legend()
    ax2.plot(t, (x - xp) * 1e3, color="C3")
    ax2.set_ylabel(f"residual x - x_pred [{u}]")
    ax2.set_xlabel("time [s]")
    rep.figure("tracking", fig, caption="Measured vs predicted tracking error (the model simulated from rest, as the "
                                        "table above), and the residual")
    fig = Figure(figsize=(10, 6))
    model.plot(fig.subplots(2, 2, sharex=True))
    rep.figure("frf", fig, caption="Tracking and disturbance FRFs of the identified model (cf. Fig. 3.5)")
    if model.validation:
        from identification.diagnosis import after_table_lines, before_after_rows, report_figure

        rep.heading("Residual diagnosis: effects the reduced model lacks")
        rows = before_after_rows(model)
        rep.table(["model", *DIAGNOSIS_COLUMNS], [[r["label"], *(r.get(k) for k in DIAGNOSIS_COLUMNS.values())]
                                                  for r in rows],
                  caption=f"RMS and max error [{u}] of the reduced model, each effect in turn, and the final model")
        # the summary's lines after its table: which samples, the folds, refusals, warnings, the residual
        for line in after_table_lines(model):
            rep.text(line.strip())
        axs = report_figure(capture, model, axis=axis)
        rep.figure("residual", np.ravel(axs)[0].figure,
                   caption="Residual before and after the diagnosis: time, velocity, position, spectrum")
    rep.summary = {"model": model.to_dict()}
    rep.attach("model.json", (json.dumps(model.to_dict(), indent=2) + "\n").encode())
    return rep


def _bounds(args: argparse.Namespace, capture) -> dict | None:
    """The pole box from the command line (thesis defaults for what is not given)."""
    if args.p_min_hz is None and args.omega_min_hz is None and args.zeta is None:
        return None
    from identification.bounds import default_bounds

    b = default_bounds(capture.sample_time).as_dict()
    if args.p_min_hz is not None:
        b["p_hz"] = (args.p_min_hz, b["p_hz"][1])
    if args.omega_min_hz is not None:
        b["omega_n_hz"] = (args.omega_min_hz, b["omega_n_hz"][1])
    if args.zeta is not None:
        b["zeta"] = tuple(args.zeta)
    return b


def run(args: argparse.Namespace) -> int:
    from identification import identify
    from vcnc.core.io import check_distinct_outputs, check_output

    check_output(args.json, option="--json", what="the model file", inputs=(args.capture,))
    check_output(args.report, option="--report", what="the report", folder=True)
    check_distinct_outputs((("--json", args.json), ("--report", args.report)))
    capture = read_trace_argument(args.capture, args)  # a unit given or stated: meta[UNIT_GIVEN] (vcnc.traces)
    axis = args.axis or ("x" if "x" in capture.axes or len(capture.axes) != 1 else capture.axes[0])
    model = identify(
        capture,
        axis=axis,
        bounds=_bounds(args, capture),
        method=args.method,
        refine=args.refine,
        seed=args.seed,
        diagnose=not args.no_diagnose,
        delay=args.delay,
        setpoint_filter=not args.no_setpoint_filter,
        drift=args.drift,
    )
    if model.fit["drift"]["removed"]:
        from identification.measured_drift import without_drift

        capture = without_drift(capture, axis, model.fit["drift"]["polynomial_mm"])
    rest_um = from_rest_rms_um(capture, model, axis)  # a simulation of the record when a start state was fitted
    baseline = baseline_lines(capture, model, axis, rest_um)
    rep = build_report(capture, model, axis, baseline, rest_um) if args.report else None
    if args.json:
        model.to_json(args.json)
    if rep is not None:
        rep.write(args.report)
    from identification.diagnosis import format_before_after, wrapped_lines

    p, poles = model.parameters, model.poles
    lines = []
    if "columns" in capture.meta:  # a delimited trace's mapping read from its header names
        lines.append(f"{args.capture}: columns {capture.meta['columns']}")
    lines.append(f"axis {axis}: {len(capture)} samples, Ts {model.sample_time:g} s, method {model.method}")
    lines.append(f"poles: omega_n {poles['omega_n_hz']:.4g} Hz, zeta {poles['zeta']:.4g}, p {poles['p_hz']:.4g} Hz")
    lines.append(closed_loop_poles_line(model))
    lines.append("parameters: " + ", ".join(f"{k} {v:.6g}" for k, v in p.items()))
    if (model.fit or {}).get("friction"):
        lines.append(f"friction: {model.fit['friction']['statement']}")
    lines += fit_lines(model, rest_um) + record_start_lines(capture, model, axis, rest_um)
    if model.validation:
        lines.append(format_before_after(model).rstrip("\n"))
    lines += baseline
    # at most 100 columns (diagnosis.TABLE_COLUMNS), as the table; the report prints the same lines unwrapped
    sys.stdout.write("".join(f"{line}\n" for text in lines for line in wrapped_lines(text)))
    return 0
