"""The spectral signature of a setpoint filter: the moving average's gain in the record.

A moving average of length L passes a sine of frequency f with the gain
|sin(pi f L) / (pi f L)|: 2 / pi at f = 1 / (2 L) and zeros at f = k / L (S. W. Smith, *The
Scientist and Engineer's Guide to Digital Signal Processing*, ch. 15, "Moving Average Filters",
Eq. 15-2; a continuous average, :mod:`identification.setpoint_filter`). A loop that receives the
reference through such a filter responds to the reference with the model's loop times that gain;
a model whose filter imitates something else (an unmodelled mode in the loop, which the prediction
alone rewards too: a 150 Hz mode logged at 2 ms imitated by a 9.7 ms filter for 1.57x) leaves the
record's response where the loop and the mode put it. :func:`signature` measures the record's
response from the reference to the measured position over the model's loop's (the filter taken
out) at 1 / (2 L), as a share of 2 / pi, and at 1 / L. Measured (the traceid5 audit): vcnc's
machines with a 16 ms jerk filter (``benchmarks/recorded_traces.py`` case ``jerkf``) and the exact
model with a 12 or 16 ms filter, also with 0.5 um noise: 0.94-1.06 and 0.02-0.11 (fadal-smc the
most, its length 14.5 ms for the 16-sample average); that mode: 0.86 and 0.17; fadal-smc without a
filter, searched at 2.8 ms: 0.67 and 0.03. :func:`shows_filter` asks for the gain within
:data:`HALF_TOLERANCE` and the zero at most :data:`MAX_AT_ZERO`, which is loose: the response of
the friction at the reversals, which the reference does not drive linearly, fills the zero (0.21 on
the exact model with a 12 ms filter on 40 slower moves with dwells, where its gain is 1.00), and a
record without the filter shows about 1 there.

The response is estimated as the cross-spectrum over the reference's spectrum at the one
frequency (the H1 estimate: noise on the measured channel does not bias it), summed over
Hann-windowed half-overlapping segments at least :data:`SEGMENT_LENGTHS` filter lengths long, of
both channels' second differences (the same operator on both leaves the response as it is, and it
flattens the reference's steep low-frequency spectrum, whose leakage through the window would
otherwise dominate the estimate at 1 / L).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from identification.reduced_model import ReducedAxisModel

__all__ = ["notch_ratio", "signature", "shows_filter", "SEGMENT_LENGTHS", "MIN_SEGMENT", "HALF_TOLERANCE",
           "MAX_AT_ZERO"]

#: Segments of the estimate are at least this many filter lengths long [-] (a main lobe of the
#: Hann window of +-1/4 of the frequency 1/L).
SEGMENT_LENGTHS = 8.0
#: Fewest samples of a segment (rounded up to a power of two) [-].
MIN_SEGMENT = 256
#: Largest relative difference of the record's response at 1 / (2 L) from the filter's 2 / pi [-].
HALF_TOLERANCE = 0.1
#: Largest record's response at the filter's first zero, 1 / L [-].
MAX_AT_ZERO = 0.5


def notch_ratio(reference: np.ndarray, measured: np.ndarray, sample_time: float, length_s: float,
                parameters: Mapping[str, float], *, at: float = 1.0) -> float:
    """|response of ``measured`` to ``reference`` at ``at`` / ``length_s``| over |the loop's of the
    reduced model ``parameters`` there| [-] (module docstring); ``reference`` is the one the filter
    acts on (after the dead time). NaN when the record is shorter than two samples or than its
    frequency's period, or the reference carries nothing there."""
    T = sample_time
    f = at / length_s
    r, m = np.diff(np.asarray(reference, float), 2), np.diff(np.asarray(measured, float), 2)
    n = min(1 << int(math.ceil(math.log2(max(MIN_SEGMENT, SEGMENT_LENGTHS * length_s / T)))), r.size)
    if n < 2 or n * T * f < 1.0:
        return math.nan
    w = np.hanning(n) * np.exp(-2j * np.pi * f * T * np.arange(n))
    starts = np.arange(0, r.size - n + 1, max(1, n // 2))
    R = np.array([r[s:s + n] @ w for s in starts])
    X = np.array([m[s:s + n] @ w for s in starts])
    power = float(np.sum(np.abs(R) ** 2))
    if not power > 0.0:
        return math.nan
    H = np.sum(X * R.conj()) / power
    G = ReducedAxisModel(parameters=dict(parameters), sample_time=T).tracking_response(2j * np.pi * f)
    return float(abs(H) / abs(complex(G)))


def signature(reference: np.ndarray, measured: np.ndarray, sample_time: float, length_s: float,
              parameters: Mapping[str, float]) -> dict[str, float] | None:
    """``{"half": response at 1 / (2 L) over 2 / pi, "zero": response at 1 / L}``, each over the
    loop's of ``parameters`` (:func:`notch_ratio`; module docstring); None when the record cannot
    tell (too short, or no reference there)."""
    half = notch_ratio(reference, measured, sample_time, length_s, parameters, at=0.5) * math.pi / 2.0
    zero = notch_ratio(reference, measured, sample_time, length_s, parameters)
    return {"half": half, "zero": zero} if math.isfinite(half) and math.isfinite(zero) else None


def shows_filter(sig: dict[str, float] | None) -> bool:
    """Whether a :func:`signature` is the moving average's (module docstring; None: no)."""
    return sig is not None and abs(sig["half"] - 1.0) <= HALF_TOLERANCE and sig["zero"] <= MAX_AT_ZERO
