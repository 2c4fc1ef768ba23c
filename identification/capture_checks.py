"""Checks a capture axis must pass before identification or diagnosis.

Shared by :mod:`identification.identify` (the fit) and :mod:`identification.diagnosis` (the
augmentation), so that neither imports the other.
"""

from __future__ import annotations

import numpy as np

from identification.regressor import RegressorOptions
from vcnc.core.capture import Capture, check_sampling
from vcnc.core.errors import CaptureError, IdentificationError

__all__ = ["check_capture", "check_channels", "MIN_SAMPLES", "MAX_SPAN_RATIO", "MAX_LAG_S"]

#: Fewest samples accepted (the thesis' test has 22,000 at 1 ms; Sec. 4.3.3 4,096 at 0.6 ms).
MIN_SAMPLES = 500
#: Largest ratio of the measured to the commanded span (either way) of a position loop's record [-].
#: A loop follows its reference, so the spans agree within the tracking error and the overshoot (a
#: loop at 5 Hz, damping 0.33, on short moves: 1.6; a sluggish one on a short record: 0.2); a ratio
#: near one of :data:`_UNIT_RATIOS` (10 %) or beyond this is a channel in another unit.
MAX_SPAN_RATIO = 50.0
#: Lags scanned when telling a flipped measured channel [s]: the reference dead time's scan
#: (:data:`identification.dead_time.MAX_DELAY_S`) and the loop's own lag.
MAX_LAG_S = 0.4

#: Unit ratios a span ratio is compared with, for the message.
_UNIT_RATIOS = {1000.0: "um beside mm", 25.4: "mm beside inch", 25400.0: "um beside inch", 10.0: "0.1 mm or 1/10 "
                "units", 1e4: "0.1 um increments beside mm"}
#: Relative distance from a unit ratio within which a span ratio is taken for it [-].
_UNIT_TOLERANCE = 0.1

def check_capture(capture: Capture, axis: str, *, options: RegressorOptions | None = None) -> tuple:
    """Validate one axis of a capture for identification; returns ``(reference, measured, T)``.

    Raises
    ------
    CaptureError
        Unknown axis, NaN/inf, time not increasing or not uniform.
    IdentificationError
        Fewer than :data:`MIN_SAMPLES` samples, no motion, motion in one direction only,
        measurement identical to the reference, positions that look like metres, a measured
        channel in another unit or with a flipped sign (:func:`check_channels`).
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
            f"no motion on axis {axis!r}: reference and measurement stay at {float(xr[0])!r} mm", file=src
        )
    if span == 0.0:
        raise IdentificationError(
            f"no commanded motion on axis {axis!r}: the reference stays at {float(xr[0])!r} mm", file=src
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
    check_channels(xr, x, T, axis, src)
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


def _unit_hint(ratio: float) -> str:
    """A guess at the unit mix-up behind a span ratio (measured / commanded)."""
    big = ratio if ratio >= 1.0 else 1.0 / ratio
    which = "measured" if ratio >= 1.0 else "commanded"
    for r, text in _UNIT_RATIOS.items():
        if abs(big / r - 1.0) < _UNIT_TOLERANCE:
            return f" (about {r:g}: the {which} channel in a {r:g}x finer unit, {text}?)"
    return ""


def check_channels(reference: np.ndarray, measured: np.ndarray, sample_time: float, axis: str,
                   src: str | None = None) -> None:
    """IdentificationError unless the measured channel follows the commanded one in scale and sign.

    A position loop's measured position spans what its reference spans (within the tracking error)
    and moves the same way. Two channels in different units (mm and um, mm and inch, increments)
    or a measured channel whose sign is flipped (an encoder counting the other way, a trace
    channel negated) would otherwise be fitted silently: the flipped one to a model with
    negative gain, the rescaled one to nonsense poles.

    Parameters
    ----------
    reference, measured : ndarray
        Commanded and measured position [mm].
    sample_time : float
        [s].
    axis : str
        For the message.
    src : str, optional
        The capture's file, for the message.

    Notes
    -----
    The sign is the sign of the strongest correlation between the two positions (less their means:
    a datum offset changes nothing) over lags of +-:data:`MAX_LAG_S`: a reference recorded ahead of
    the loop (issue #16) moves the peak away from lag 0 but keeps its sign. Positions, not
    velocities: the velocity of a lightly damped loop (5 Hz, damping 0.22) correlates at -0.88 with
    its reference's half a period later. The span is the 0.1-99.9 % range, so a
    spike or a settling overshoot does not set it.
    """
    xr = np.asarray(reference, float)
    x = np.asarray(measured, float)
    span_r = float(np.subtract(*np.percentile(xr, [99.9, 0.1])))
    span_x = float(np.subtract(*np.percentile(x, [99.9, 0.1])))
    if span_r > 0 and span_x > 0:
        ratio = span_x / span_r
        if not 1.0 / MAX_SPAN_RATIO <= ratio <= MAX_SPAN_RATIO or _unit_hint(ratio):
            raise IdentificationError(
                f"axis {axis!r}: the measured position spans {span_x:.6g} and the commanded {span_r:.6g} (ratio "
                f"{ratio:.6g}){_unit_hint(ratio)}; a position loop follows its reference, so the two channels must be "
                "in the same unit: give each channel's unit (a trace's unit row or header, --unit) or rescale one",
                file=src,
            )
    vr, v = xr - xr.mean(), x - x.mean()
    norm = float(np.sqrt(np.dot(vr, vr) * np.dot(v, v)))
    if not norm > 0:
        return
    n = vr.size
    lag = min(int(round(MAX_LAG_S / sample_time)), n - 1)
    size = 1 << int(np.ceil(np.log2(2 * n)))
    cc = np.fft.irfft(np.fft.rfft(v, size) * np.conj(np.fft.rfft(vr, size)), size)
    window = np.concatenate([cc[:lag + 1], cc[size - lag:]]) / norm
    k = int(np.argmax(np.abs(window)))
    peak = float(window[k])
    if peak < 0 and abs(peak) > 0.5:
        raise IdentificationError(
            f"axis {axis!r}: the measured position moves against the commanded one (correlation "
            f"{peak:.3f}): the measured channel's sign is flipped (an encoder or trace channel counting the other "
            "way); negate it before identification",
            file=src,
        )
