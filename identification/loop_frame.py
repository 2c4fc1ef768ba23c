"""A recorded capture as the position loop saw it.

A trace records the commanded and the measured position where the control taps them, not where
the loop runs. Three differences are undone before the reduced model is fitted or diagnosed,
each found by its own module and recorded in the model's ``fit``:

1. a constant datum offset between the two channels (:mod:`identification.datum_offset`,
   ``fit.offset``): removed from the measured position;
2. the reference dead time (:mod:`identification.dead_time`, ``delay_s``): the reference
   delayed; the samples the shift leaves unknown are dropped, unless the record starts with the
   axis at rest (then the loop's reference before the record is the first value, held). The
   delay is taken on the sub-step grid the record is predicted on (:mod:`identification.substeps`:
   the cubic spline through the samples, 1 ms or finer), as the joint dead-time refinement and
   the setpoint filter's search take it, not linearly between the recorded samples: on a record
   at 3 ms the chord misses an accelerating reference by a T^2 f (1 - f) / 2 at a fractional shift
   f (2.2 um at 2000 mm/s^2 and f = 0.4), and the model fitted on it imitated that error with its
   poles (fadal-smc recorded 0.1 s ahead at 3 ms: p 16.4 Hz at 0.81 um RMS; on the sub-step
   delay, p on the record's 167 Hz Nyquist bound at 0.75 um, as the 1 ms capture fitted at that
   dead time puts it beyond, 270 Hz; the smclag helper, ``benchmarks/recorded_traces.py``);
3. a record that starts with the axis moving (:func:`identification.segments.settled_start`,
   ``fit.record_start``): the samples before the axis first rests dropped, so that the model's
   simulation from rest starts where the axis is at rest.

The model itself describes the loop (it is simulated on the reference delayed by ``delay_s``);
the offset and the dropped samples describe the recording and stay in ``fit``.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from identification.segments import SETTLED_SHARE, settled_start, starts_from_standstill
from identification.substeps import substep_reference
from vcnc.core.capture import Capture

__all__ = ["without_offset", "loop_frame", "offset_of", "starts_at_rest"]


def without_offset(capture: Capture, axis: str, offset_mm: float) -> Capture:
    """``capture`` with ``offset_mm`` [mm] taken off ``axis``' measured position."""
    if offset_mm == 0.0:
        return capture
    i = capture.axis_index(axis)
    measured = np.array(capture.measured, dtype=float)
    measured[:, i] -= offset_mm
    return dataclasses.replace(capture, measured=measured)


def starts_at_rest(recorded: np.ndarray, delayed: np.ndarray, measured: np.ndarray) -> bool:
    """Whether the loop's reference before a record may be taken as its first value held.

    True when the axis rests at the first sample (:func:`identification.segments.settled_start`
    of the delayed reference and the measured position is 0) and the recorded reference stands still
    there too, or sets off from standstill (:func:`identification.segments.starts_from_standstill`):
    a reference that leads by ``delay_s`` and is already under way at the first sample moved before
    the record (fadal-pid's reference advanced by 20 ms: a 25 um first step, as large as the next),
    and the loop received that motion within the first ``delay_s``. The axis must also stand still
    while the delayed reference holds its first value (vcnc addition, tracerobust): a reference
    leading by 1 s whose first sample fell on a stop between two moves passed the other tests while
    the axis ran the first second's moves, and the frame kept them against a held reference
    (fadal-pid: the 1 s shift predicted 2913 um for 5016 without and was rejected).
    """
    if not (starts_from_standstill(recorded) and settled_start(delayed, measured) == 0):
        return False
    held = int(np.argmax(delayed != delayed[0])) if np.any(delayed != delayed[0]) else delayed.size
    steps = np.abs(np.diff(np.asarray(recorded, float)))
    return not np.any(np.abs(np.diff(np.asarray(measured, float)[:held + 1])) > SETTLED_SHARE * steps.max())


def loop_frame(capture: Capture, axis: str, *, offset_mm: float = 0.0, delay_samples: float = 0.0
               ) -> tuple[Capture, int]:
    """The capture in the loop's frame (module docstring) and the samples dropped at its start
    after the shift (0 when the record, shifted, starts at rest).

    Parameters
    ----------
    capture : Capture
    axis : str
    offset_mm : float
        Datum offset to remove [mm].
    delay_samples : float
        Reference dead time [samples] (> 0: the recorded reference leads).
    """
    base = without_offset(capture, axis, offset_mm)
    i = base.axis_index(axis)
    xr = base.reference[:, i]
    shifted = base
    if delay_samples != 0.0:
        delayed = substep_reference(xr, base.sample_time).delayed(delay_samples).at_samples()
        if delay_samples > 0 and starts_at_rest(xr, delayed, base.measured[:, i]):
            # a record that starts at rest: the loop's reference before the first recorded sample is
            # the first value held, so nothing needs cutting
            return _with_reference(base, i, delayed), 0
        n, cut = len(base), int(math.ceil(abs(delay_samples)))
        lo, hi = (cut, n) if delay_samples > 0 else (0, n - cut)
        shifted = _with_reference(base, i, delayed).slice(lo, hi)
    start = settled_start(shifted.reference[:, i], shifted.measured[:, i]) or 0
    if start == 0:
        return shifted, 0
    return shifted.slice(start, len(shifted)), start


def _with_reference(capture: Capture, i: int, reference: np.ndarray) -> Capture:
    """``capture`` with axis ``i``'s reference replaced by ``reference``."""
    whole = np.array(capture.reference, dtype=float)
    whole[:, i] = reference
    return dataclasses.replace(capture, reference=whole)


def offset_of(fit: dict) -> float:
    """The datum offset [mm] a model's ``fit`` record says was removed (0 for none)."""
    rec = fit.get("offset") or {}
    return float(rec.get("offset_mm", 0.0)) if rec.get("applied") else 0.0
