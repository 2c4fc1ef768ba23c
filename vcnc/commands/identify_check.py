"""``vcnc identify TRACE --check MODEL.json``: predict another record of the same machine with an identified model.

The held-out check a user makes of a model: identified on one record (a test, a day, a feed), how well does it
predict another? Nothing is fitted. The record is read with every option ``vcnc identify`` takes (columns, units,
axis names, sample time, resampling) and predicted as the fit predicted its own record
(:func:`identification.augmented.predict_record`): the model's reference dead time (``delay_s``, used as it is, not
estimated again), its setpoint filter and its effects, simulated from rest. The rules of the check (our reading):

- the axis is the model's; ``--axis`` naming another, or a record without the model's axis, is refused naming both;
- a record sampled at another period than the model's is simulated at the record's period, with a note naming both:
  the model's parameters are continuous-time (Eq. 3.3 of the thesis, discretised at the period it runs at, as
  ``vcnc compare`` and the FMU run it), its dead time and setpoint filter are in seconds, and its effects are packed
  for the period given (:meth:`identification.augmented.AugmentedAxisModel.spec`; a delay effect rounds to whole
  samples of that period). Refusing would forbid the common case of a 1 ms model checked on a 2 ms log;
- the start follows identify's rules (:func:`identification.loop_frame.loop_frame`,
  :func:`identification.segments.settled_start`): the reference delayed by the model's dead time, and a record that
  starts with the axis moving is predicted from its first rest (the samples before it are named, not predicted);
- no datum offset is taken off: it belongs to the recording, and fitting it would make the check a fit. The median
  residual at rest is printed so that an offset between the record's channels shows for what it is.

It prints the error over all the samples predicted and over the active ones (the reference moving, with the 0.2 s
margins of :func:`identification.segments.active_mask`), beside the figures the model's file holds for its own
record, and with ``--report`` the measured and predicted tracking errors (:func:`vcnc.commands.tracking_figure.
tracking_figure`).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys

import numpy as np

from vcnc.core.axes import axis_unit
from vcnc.core.errors import CaptureError, InputError

__all__ = ["RecordCheck", "check_record", "check_lines", "run_check"]

#: The fit's options, which ``--check`` refuses when given (option, attribute, default, why it does not apply).
FIT_OPTIONS = (
    ("--json", "json", None, "--json writes a fitted model and --check fits none (--report keeps the check)"),
    ("--method", "method", "exact", None), ("--refine", "refine", "output-error", None), ("--seed", "seed", 0, None),
    ("--no-diagnose", "no_diagnose", False, None), ("--p-min-hz", "p_min_hz", None, None),
    ("--omega-min-hz", "omega_min_hz", None, None), ("--zeta", "zeta", None, None),
    ("--delay", "delay", "auto", "the model's reference dead time is used as it is, not estimated again; identify "
                                 "the record without --check to fit one"),
    ("--no-setpoint-filter", "no_setpoint_filter", False, "the model's setpoint filter is part of the model"),
    ("--drift", "drift", "auto", None),
)


@dataclasses.dataclass(frozen=True, kw_only=True)
class RecordCheck:
    """A model's prediction of one axis of a record it was not fitted on (:func:`check_record`).

    Attributes
    ----------
    axis : str
    sample_time : float
        The record's period [s], at which the model was simulated.
    first, stop : int
        The record's samples predicted, ``first:stop`` (identify's start rules and the dead time's cut).
    reference, measured, predicted : ndarray
        The recorded reference, the measured and the predicted position of those samples [mm].
    active : ndarray of bool
        Those samples where the reference moves (with margins; :func:`identification.segments.active_mask`).
    in_motion : bool
        The samples predicted start with the axis moving (it does not rest early enough in the record to start
        there, :func:`identification.segments.settled_start`): the prediction from rest carries a start transient.
    """

    axis: str
    sample_time: float
    first: int
    stop: int
    reference: np.ndarray
    measured: np.ndarray
    predicted: np.ndarray
    active: np.ndarray
    in_motion: bool = False

    def errors_um(self, which: str = "all") -> tuple[float, float]:
        """RMS and max of ``measured - predicted`` [um, mdeg on a rotary axis] over ``"all"`` the samples predicted
        or the ``"active"`` ones (NaN when there are none)."""
        e = self.measured - self.predicted
        if which == "active":
            e = e[self.active]
        if e.size == 0:
            return math.nan, math.nan
        return float(np.sqrt(np.mean(e * e))) * 1e3, float(np.max(np.abs(e))) * 1e3

    def rest_offset_um(self) -> float | None:
        """The median residual [um] over the samples at rest (not active), None with fewer than 10 of them."""
        rest = ~self.active
        if int(rest.sum()) < 10:
            return None
        return float(np.median((self.measured - self.predicted)[rest])) * 1e3


def check_record(capture, model, axis: str) -> RecordCheck:
    """``model``'s prediction of ``capture``'s axis ``axis`` (module docstring): simulated from rest at the record's
    period with the model's dead time, setpoint filter and effects, from identify's start."""
    from identification.augmented import predict_record
    from identification.loop_frame import loop_frame
    from identification.segments import active_mask, settled_start
    from identification.substeps import substep_reference

    i = capture.axis_index(axis)
    T = float(capture.sample_time)
    xr, x = capture.reference[:, i], capture.measured[:, i]
    d = model.delay_s / T
    framed, _ = loop_frame(capture, axis, delay_samples=d)  # identify's start rules
    stop = len(capture) - (math.ceil(-d) if d < 0 else 0)  # a reference that lags loses its last samples
    first = stop - len(framed)
    # the reference the loop receives, delayed and filtered over the whole record (its history before `first`
    # included), on the sub-step grid a record slower than 1 ms is predicted on, then cut to the samples predicted
    loop = substep_reference(xr, T).delayed(d).filtered(model.setpoint_filter_s / T)
    m = loop.substeps
    held = dataclasses.replace(loop, fine=loop.fine[first * m:(stop - 1) * m + 1])
    bare = dataclasses.replace(model, delay_s=0.0, setpoint_filter_s=0.0)
    loop_xr = held.at_samples()
    predicted = predict_record(bare, loop_xr, held=held, sample_time=T)
    return RecordCheck(axis=axis, sample_time=T, first=first, stop=stop, reference=xr[first:stop],
                       measured=x[first:stop], predicted=predicted,
                       active=active_mask(loop_xr, x[first:stop], T),
                       in_motion=settled_start(loop_xr, x[first:stop]) is None)


def own_record_rows(model) -> list[list]:
    """The model file's figures for its own record, as rows ``[label, all RMS, all max, active RMS, active max]``
    (None where the file holds none): with a diagnosis (``validation``) the final model over all the record's
    samples and its active ones, in sample and held out on the folds; otherwise the fit's."""
    from identification.diagnosis import before_after_rows

    fit = model.fit or {}
    plain_fit = not model.effects and not fit.get("initial_state")  # the fit's max is the model's own
    all_max = fit.get("max_um") if plain_fit else None
    if not model.validation:
        return [["its own record (the fit)", fit.get("rms_um"), all_max, None, None]]
    final = before_after_rows(model)[-1]
    return [["its own record", final.get("record_rms_um", fit.get("rms_um")), all_max,
             final.get("identification_rms_um"), final.get("identification_max_um")],
            ["its own record, held out on folds", None, None, final.get("validation_rms_um"),
             final.get("validation_max_um")]]


def _cell(v) -> str:
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.4g}"


def check_lines(check: RecordCheck, model, *, model_path: str, record_path: str, samples: int) -> list[str]:
    """The summary of ``vcnc identify --check`` (its report repeats them): what was predicted, the table of this
    record's and the model's own errors, and the naive predictions of this record."""
    from identification.dead_time import pure_delay_baseline

    u = axis_unit(check.axis, small=True)
    T, Tm = check.sample_time, model.sample_time
    effects = ", ".join(e.get("name", "?") for e in model.effects or []) or "none"
    lines = [f"{record_path}: axis {check.axis}, {samples} samples at Ts {T:g} s, checked against {model_path} "
             f"(fitted nothing)",
             f"model: identified at Ts {Tm:g} s; reference dead time {model.delay_s:.6g} s (used as it is), setpoint "
             f"filter {model.setpoint_filter_s:.6g} s, effects: {effects}"]
    if not math.isclose(T, Tm, rel_tol=1e-6):
        lines.append(f"note: the record is sampled every {T:g} s and the model was identified at {Tm:g} s: simulated "
                     "at the record's period (its parameters are continuous-time, its dead time and filter in seconds)")
    if check.first or check.stop < samples:
        why = []
        if check.first:
            shifted = "the model's dead time shifts the reference past them, or " if model.delay_s > 0 else ""
            why.append(f"the first {check.first} ({shifted}the record starts with the axis moving: predicted from "
                       "rest where the axis first rests, as identify predicts its record)")
        if check.stop < samples:
            why.append(f"the last {samples - check.stop} (a reference that lags the loop by the dead time)")
        lines.append("note: samples not predicted: " + "; ".join(why))
    if check.in_motion:
        lines.append("note: the record starts with the axis moving and it does not rest early enough to start there: "
                     "predicted from rest at its first sample, a start transient included (as identify predicts it)")
    head = f"{'':36s}{'all RMS':>10s}{'all max':>10s}{'active RMS':>12s}{'active max':>12s}  [{u}]"
    ours = ["this record", *check.errors_um("all"), *check.errors_um("active")]
    rows = [ours, *own_record_rows(model)]
    lines.append(head)
    for r in rows:
        lines.append(f"{r[0]:36s}{_cell(r[1]):>10s}{_cell(r[2]):>10s}{_cell(r[3]):>12s}{_cell(r[4]):>12s}")
    lines.append(f"this record: {check.stop - check.first} samples predicted, {int(check.active.sum())} active")
    base = pure_delay_baseline(check.reference, check.measured, T)
    fe, pd, k = base["following_error_rms_um"], base["pure_delay_rms_um"], base["pure_delay_samples"]
    rms = ours[1]
    naive = min(fe, pd)
    line = (f"naive predictions of this record: the commanded position itself rms {fe:.4g} {u}"
            + (f", delayed by {k} samples rms {pd:.4g} {u}" if k else ""))
    if naive > 0.0 and rms > 0.0:
        line += (f"; the model predicts {naive / rms:.3g} times better" if rms < naive
                 else f"; the model predicts {rms / naive:.3g} times worse")
    lines.append(line)
    rest = check.rest_offset_um()
    if rest is not None:
        lines.append(f"at rest the axis sits a median {rest:.4g} {u} from the prediction (a datum offset between "
                     "the record's channels is not taken off: --check fits nothing)")
    return lines


def check_options(args: argparse.Namespace) -> None:
    """:class:`InputError` for a fit option given with ``--check`` (:data:`FIT_OPTIONS`)."""
    for option, attr, default, why in FIT_OPTIONS:
        if getattr(args, attr, default) != default:
            raise InputError(f"{option} with --check: " + (why or f"{option} is an option of the fit, and --check "
                                                                 "fits nothing"))


def check_axis(capture, model, requested: str | None, *, record_path: str, model_path: str) -> str:
    """The axis to check: the model's. :class:`InputError` naming both when ``--axis`` or the record names
    another."""
    if requested and requested != model.axis:
        raise InputError(f"--axis {requested}: the model {model_path} is of axis {model.axis}; a model is checked on "
                         "a record of its own axis")
    if model.axis not in capture.axes:
        hint = (f" (when the record's axis {capture.axes[0]} is that axis, name it with --axis-names {model.axis}, or "
                f"with --columns t=..,{model.axis}_ref=..,{model.axis}=..)" if len(capture.axes) == 1 else "")
        raise CaptureError(f"the record holds axis {', '.join(capture.axes)} and the model {model_path} is of axis "
                           f"{model.axis}" + hint, file=record_path)
    return model.axis


def build_check_report(check: RecordCheck, lines: list[str], *, record_path: str, model_path: str):
    """The HTML report of ``vcnc identify --check`` (:class:`vcnc.report.Report`): the summary's lines and the
    measured and predicted tracking errors."""
    from vcnc.commands.tracking_figure import tracking_figure
    from vcnc.report import Report

    rep = Report(f"vcnc identify --check: axis {check.axis} of {record_path} with {model_path}")
    rep.heading("Prediction of the record by the model")
    for line in lines:
        rep.text(line)
    t = (check.first + np.arange(check.stop - check.first)) * check.sample_time
    rep.figure("tracking", tracking_figure(t, check.reference, check.measured, check.predicted,
                                           axis_unit(check.axis, small=True)),
               caption="Measured vs predicted tracking error of the record (the model simulated from rest), and the "
                       "residual")
    all_rms, all_max = check.errors_um("all")
    act_rms, act_max = check.errors_um("active")
    rep.summary = {"check": {"record": record_path, "model": model_path, "axis": check.axis,
                             "sample_time": check.sample_time, "first": check.first, "stop": check.stop,
                             "rms_um": all_rms, "max_um": all_max, "active_rms_um": act_rms,
                             "active_max_um": act_max, "active_samples": int(check.active.sum())}}
    return rep


def run_check(args: argparse.Namespace) -> int:
    """``vcnc identify TRACE --check MODEL.json``."""
    from identification import load_model
    from identification.capture_checks import MIN_SAMPLES
    from vcnc.commands.export_fmu import check_model_file
    from vcnc.commands.trace_options import read_trace_argument
    from vcnc.core.io import check_output

    check_options(args)
    check_output(args.report, option="--report", what="the report", folder=True, inputs=(args.capture, args.check))
    check_model_file(args.check)
    model = load_model(args.check)
    capture = read_trace_argument(args.capture, args)
    axis = check_axis(capture, model, args.axis, record_path=args.capture, model_path=args.check)
    check = check_record(capture, model, axis)
    if check.stop - check.first < MIN_SAMPLES:
        raise CaptureError(f"{check.stop - check.first} samples left to predict after the model's dead time and "
                           f"identify's start rules, expected at least {MIN_SAMPLES}", file=args.capture)
    lines = check_lines(check, model, model_path=args.check, record_path=args.capture, samples=len(capture))
    if args.report:
        build_check_report(check, lines, record_path=args.capture, model_path=args.check).write(args.report)
    sys.stdout.write("".join(f"{line}\n" for line in lines))
    return 0
