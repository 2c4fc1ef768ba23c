"""Checks a capture axis must pass before identification or diagnosis.

Shared by :mod:`identification.identify` (the fit) and :mod:`identification.diagnosis` (the
augmentation), so that neither imports the other.
"""

from __future__ import annotations

import numpy as np

from identification.regressor import RegressorOptions
from vcnc.core.capture import Capture, check_sampling
from vcnc.core.errors import CaptureError, IdentificationError

__all__ = ["check_capture", "MIN_SAMPLES"]

#: Fewest samples accepted (the thesis' test has 22,000 at 1 ms; Sec. 4.3.3 4,096 at 0.6 ms).
MIN_SAMPLES = 500

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
    T = capture.sample_time  # the nominal period (time stamps as decimals give 0.0010000000000000009)
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
