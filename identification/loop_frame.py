"""A recorded capture as the position loop saw it.

A trace records the commanded and the measured position where the control taps them, not where
the loop runs. Three differences are undone before the reduced model is fitted or diagnosed,
each found by its own module and recorded in the model's ``fit``:

1. a constant datum offset between the two channels (:mod:`identification.datum_offset`,
   ``fit.offset``): removed from the measured position;
2. the reference dead time (:mod:`identification.dead_time`, ``delay_s``): the reference
   delayed, the samples the shift leaves unknown dropped;
3. a record that starts with the axis moving (:func:`identification.segments.settled_start`,
   ``fit.record_start``): the samples before the axis first rests dropped, so that the model's
   simulation from rest starts where the axis is at rest.

The model itself describes the loop (it is simulated on the reference delayed by ``delay_s``);
the offset and the dropped samples describe the recording and stay in ``fit``.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from identification.dead_time import loop_capture
from identification.segments import settled_start
from vcnc.core.capture import Capture

__all__ = ["without_offset", "loop_frame", "offset_of"]


def without_offset(capture: Capture, axis: str, offset_mm: float) -> Capture:
    """``capture`` with ``offset_mm`` [mm] taken off ``axis``' measured position."""
    if offset_mm == 0.0:
        return capture
    i = capture.axis_index(axis)
    measured = np.array(capture.measured, dtype=float)
    measured[:, i] -= offset_mm
    return dataclasses.replace(capture, measured=measured)


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
    shifted = loop_capture(without_offset(capture, axis, offset_mm), axis, delay_samples)
    i = shifted.axis_index(axis)
    start = settled_start(shifted.reference[:, i], shifted.measured[:, i])
    if start == 0:
        return shifted, 0
    return shifted.slice(start, len(shifted)), start


def offset_of(fit: dict) -> float:
    """The datum offset [mm] a model's ``fit`` record says was removed (0 for none)."""
    rec = fit.get("offset") or {}
    return float(rec.get("offset_mm", 0.0)) if rec.get("applied") else 0.0
