"""The operating range a record covers: how fast and how hard its reference moves the axis.

A reduced model is fitted to what its record shows. A record of a CAM program at its cutting feeds (a few mm/s)
fixes the model's response there and leaves the terms that only matter faster almost free: the equation error is
flat along them (``fit['solver']['identifiability']``), and a model that predicts its own record within 1.5 um may
predict a 200 mm/s diamond three times too large (fadal-pid+z running corpus program 0126 at F500 mm/min: contour
error 177 um predicted for 55 um true; models of the same machine's identification test program: 52 um). So the
model file records the range its record covered, ``fit['excitation']``, and the tools that run a model on another
reference (``vcnc compare``) say when that reference goes beyond it.

The range is the speed where the record spends its moving time, the 99th percentile over the samples that move
(speed over :data:`MOVING_SHARE` of the largest), and the largest acceleration: the speed-dependent part of the
response builds up while the axis runs at a speed, the acceleration-dependent part in every ramp, so a record
covers an acceleration once its ramps reach it. A CAM program's rapids reach 40 mm/s for a moment while its cuts
run at 8.3 mm/s: 0126's range on x is 8.3 mm/s (largest 40.4) and 1975 mm/s^2, and its models predict the
diamond's largest contour error at 110 um for the true 78 um at 50 mm/s, 177 for 55 um at 200 mm/s; the
identification test program's range is 171 mm/s (largest 191) and 2000 mm/s^2. A reference is beyond the range
when its largest speed or acceleration exceeds the record's by :data:`BEYOND_FACTOR`.

The speed and acceleration are central differences of the reference over +-:data:`WINDOW_S` (at least one sample):
over that window the quantisation of a recorded reference (1 um at 1 ms would put +-1000 mm/s^2 of noise into a
one-sample second difference) shrinks by the window's square, and a trapezoidal profile's acceleration plateaus of
more than twice the window keep their value.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["WINDOW_S", "PERCENTILE", "MOVING_SHARE", "BEYOND_FACTOR", "excitation", "beyond_range"]

#: Half-width of the central differences [s].
WINDOW_S = 0.004
#: Percentile of the moving samples' speed that bounds the range [%].
PERCENTILE = 99.0
#: A sample moves when its speed exceeds this share of the record's largest.
MOVING_SHARE = 0.01
#: A reference is beyond a model's range when its speed or acceleration exceeds the record's by this factor.
BEYOND_FACTOR = 1.25


def excitation(reference: np.ndarray, sample_time: float) -> dict[str, float]:
    """The operating range of a reference [mm] (deg on a rotary axis: deg/s, deg/s^2) sampled every
    ``sample_time`` [s] (module notes): ``"speed_mm_s"`` (the 99th percentile over the moving samples),
    ``"speed_max_mm_s"``, ``"acceleration_max_mm_s2"`` (the largest) and ``"window_s"`` (the half-width of
    the central differences)."""
    speed, acceleration, h = _central_differences(reference, sample_time)
    if speed.size == 0 or not np.any(speed > 0):
        return {"speed_mm_s": 0.0, "speed_max_mm_s": 0.0, "acceleration_max_mm_s2": 0.0, "window_s": h}
    moving = speed > MOVING_SHARE * speed.max()
    return {"speed_mm_s": float(np.percentile(speed[moving], PERCENTILE)), "speed_max_mm_s": float(speed.max()),
            "acceleration_max_mm_s2": float(acceleration.max()), "window_s": h}


def beyond_range(identified: dict, reference: np.ndarray, sample_time: float, *,
                 samples: np.ndarray | None = None) -> dict[str, tuple[float, float]]:
    """What of a reference goes beyond the range of the record a model was identified from (``identified`` =
    ``model.fit['excitation']``): ``{"speed": (the reference's largest, the record's range), "acceleration":
    (...)}`` for each that exceeds the record's range by more than :data:`BEYOND_FACTOR` (empty when none
    does, or when the record has no range). ``samples``: a mask of the reference's samples that count (e.g.
    the feed moves a contour error covers); all when None."""
    speed, acceleration, h = _central_differences(reference, sample_time)
    if samples is not None and speed.size:
        k = int(round(h / sample_time))
        counted = np.asarray(samples, dtype=bool)[k:-k]
        speed, acceleration = speed[counted], acceleration[counted]
    used = {"speed": float(speed.max(initial=0.0)), "acceleration": float(acceleration.max(initial=0.0))}
    out: dict[str, tuple[float, float]] = {}
    for name, key in (("speed", "speed_mm_s"), ("acceleration", "acceleration_max_mm_s2")):
        seen = float(identified.get(key, math.nan))
        if math.isfinite(seen) and used[name] > BEYOND_FACTOR * seen:
            out[name] = (used[name], seen)
    return out


def _central_differences(reference: np.ndarray, sample_time: float) -> tuple[np.ndarray, np.ndarray, float]:
    """|speed|, |acceleration| of a reference by central differences over +-:data:`WINDOW_S` (at least one
    sample; empty for a record shorter than the window), and the half-width [s]."""
    r = np.asarray(reference, dtype=float).ravel()
    k = max(1, int(round(WINDOW_S / sample_time)))
    h = k * sample_time
    if r.size < 2 * k + 1:
        return np.zeros(0), np.zeros(0), h
    ahead, here, back = r[2 * k:], r[k:-k], r[: -2 * k]
    return np.abs(ahead - back) / (2 * h), np.abs(ahead - 2 * here + back) / (h * h), h
