"""Dead time between the recorded reference and the position loop.

Production controls record the commanded position ahead of what the position loop receives
(setpoint buffering, trace channels sampled at another point of the interpolation chain): on a
Heidenhain iTNC 530 TNCscope trace about 0.1 s. The reduced model of Eq. (3.3) has no dead time;
fitted to such data it bends its poles to imitate one and predicts badly. vcnc therefore
identifies the model on the reference delayed by ``delay_s``:

    x_loop(t) = x_recorded(t - delay_s)

``delay_s`` > 0 when the recorded reference leads (the usual case), < 0 when it was logged late.
The shift is whole and fractional samples; between samples the reference is interpolated
linearly (:func:`delay_reference`, also the rule of the FMU's delay line). Before the record, the
delayed reference holds its first value; past it, its last.

:func:`estimate_delay` scans the shift over +-``max_delay_s`` (0.3 s by default; around the lag
at which the measured velocity follows the commanded one, :func:`follow_lag`, when that lies
beyond: a longer lead) on the
residual of the regression of Eq. (3.11), coarse to fine, and refines the best whole-sample shift
to a hundredth of a sample. Every
candidate is judged on the same samples (the first and last ``max_delay_s`` are left out), so
the objectives compare. The estimate is the dead time the model needs: the recording offset plus
the sampled loop's own lag that the continuous model lacks (about one loop sample). Shifts below
:data:`MIN_DELAY_SAMPLES` are reported as 0: so short a shift cannot be told from an in-loop delay
of the control action, which the diagnosis' ``delay`` effect models (and which a reference shift
would wrongly absorb). A negative shift (the reference recorded after the loop acted on it) counts at any
length: no in-loop delay or causal loop model explains an axis that moves before its recorded command, and a
record shows none without one (the loop's own lag biases the estimate positive; ident_fuzz seed 11 case 30,
ballscrew-zpetc at 2 ms with its reference logged one record sample late, estimated -0.95 samples at objective
ratio 0.41, was fitted without it at 3.55 um RMS, 110 Hz and zeta 1.36 for the unshifted record's 1.54 um, 35 Hz,
0.58; with it 1.54 um, 35 Hz, 0.58). A shift that lowers the objective by less than half
(:data:`MAX_OBJECTIVE_RATIO`) is not evidence of an offset and is reported as 0 too.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from identification.regressor import RegressorOptions, SufficientStatistics, iter_regressor

__all__ = ["delay_reference", "estimate_delay", "follow_lag", "pure_delay_baseline", "DelayEstimate", "MAX_DELAY_S",
           "MIN_DELAY_SAMPLES", "FINEST_STEP_S", "LAG_STEP_S", "MAX_LEAD_SHARE"]

#: Default half-width of the scan [s].
MAX_DELAY_S = 0.3
#: Shortest positive shift reported [samples]; shorter ones are left to the loop model and its diagnosis.
#: Measured on fadal-pid (1 ms): no shift gives 1.3 samples (the sampled loop's own lag, which the
#: continuous Eq. 3.3 lacks), an in-loop delay of the control action of 1 and 2 samples 2.4 and 3.5.
MIN_DELAY_SAMPLES = 5.0
#: Finest sample step the scan runs at [s]: a faster record is decimated to about this first. The
#: regression differentiates the measured position twice, and its noise biases the best shift the
#: more the faster the sampling (0.5 um noise on the exact reduced model, no shift: 1.3 samples at
#: 1 ms, 7.4 at 0.6 ms, 54.5 at 0.125 ms); the output-error refinement of the fit
#: (:mod:`identification.identify`) then resolves the shift at the full rate.
FINEST_STEP_S = 0.001
#: Resolution of the fractional part of the estimate [samples].
FRACTION_TOLERANCE = 0.01
#: Largest objective ratio (with shift / without) for a shift to count: a real recording offset
#: explains most of the residual (measured on fadal-pid: 0.10 for 10 samples, 5e-5 for 100); on
#: EMPS, with no offset, the best shift of 5.4 samples lowers it by 0.2 % only.
MAX_OBJECTIVE_RATIO = 0.5


#: Sample step of :func:`follow_lag` [s]: a record is decimated to about this first.
LAG_STEP_S = 0.004
#: Longest lead :func:`follow_lag` looks for, as a share of the record [-]: the rest overlaps.
MAX_LEAD_SHARE = 1.0 / 3.0
#: Correlations within this of the best are ties, the shortest lag wins [-]: EMPS' test repeats its
#: motion, and its velocities correlate at 0.99995 both at 8 ms and at -6.23 s.
LAG_TIE = 0.002
#: Least correlation of :func:`follow_lag` for its lag to move the dead time's scan [-] (a position
#: loop's measured velocity follows at 0.95 or more: chevalier-pdf's sluggish PDF loop 0.948, the
#: others of ``benchmarks/recorded_traces.py`` 0.98 and EMPS 0.9999).
FOLLOW_CORRELATION = 0.9


def follow_lag(reference: np.ndarray, measured: np.ndarray, sample_time: float, *,
               max_lag_s: float | None = None) -> tuple[float, float]:
    """``(lag [s], correlation [-])``: the shift at which the measured velocity best follows the commanded
    one, and their correlation there (> 0 when the measured lags the recorded reference).

    Both velocities are taken as differences on the record decimated to about :data:`LAG_STEP_S`
    and correlated over lags up to ``max_lag_s`` (default: :data:`MAX_LEAD_SHARE` of the record),
    each lag normalised by the energies of the samples it overlaps, so that a long lead is not
    penalised for its shorter overlap; of lags that correlate within :data:`LAG_TIE` of the best,
    the shortest. A position loop's measured velocity follows its reference's
    at a lag of its own response (a few ms) plus the recording's lead, with a correlation near 1;
    another signal mapped as the measured position (another axis, a velocity, a control signal)
    does not. Velocities, not positions: positions of a back-and-forth test correlate broadly over
    lags of a move's length, which would blur the peak of a long lead.
    """
    q = max(1, int(round(LAG_STEP_S / sample_time)))
    dr = np.diff(np.asarray(reference, float)[::q])
    dm = np.diff(np.asarray(measured, float)[::q])
    n = dr.size
    if n < 3:
        return 0.0, 0.0
    lag = int(n * MAX_LEAD_SHARE) if max_lag_s is None else int(round(max_lag_s / (q * sample_time)))
    lag = max(0, min(lag, n - 2))
    size = 1 << int(np.ceil(np.log2(2 * n)))
    cc = np.fft.irfft(np.fft.rfft(dm, size) * np.conj(np.fft.rfft(dr, size)), size)
    k = np.arange(-lag, lag + 1)
    raw = np.concatenate([cc[size - lag:], cc[:lag + 1]]) if lag else cc[:1]
    em, er = np.concatenate([[0.0], np.cumsum(dm * dm)]), np.concatenate([[0.0], np.cumsum(dr * dr)])
    # lag k >= 0 pairs dm[k:] with dr[:n-k]; k < 0 pairs dm[:n+k] with dr[-k:]
    energy_m = np.where(k >= 0, em[n] - em[np.clip(k, 0, n)], em[np.clip(n + k, 0, n)])
    energy_r = np.where(k >= 0, er[np.clip(n - k, 0, n)], er[n] - er[np.clip(-k, 0, n)])
    norm = np.sqrt(energy_m * energy_r)
    corr = np.divide(raw, norm, out=np.zeros_like(raw), where=norm > 0)
    near = np.flatnonzero(corr >= corr.max() - LAG_TIE)  # a repeated test correlates as well a period away
    best = int(near[np.argmin(np.abs(k[near]))])
    return float(k[best] * q * sample_time), float(corr[best])


def delay_reference(reference: np.ndarray, samples: float) -> np.ndarray:
    """``reference`` delayed by ``samples`` (whole and fractional; negative advances it).

    Linear interpolation between samples; before the record the first value is held, past it
    the last.
    """
    xr = np.asarray(reference, dtype=float)
    if samples == 0.0:
        return xr.copy()
    k = np.arange(xr.size, dtype=float) - float(samples)
    return np.interp(k, np.arange(xr.size, dtype=float), xr)


#: Longest shift :func:`pure_delay_baseline` tries [s] (the hydraulic rig eha-1-1 lags 0.25 s, a TNCscope
#: trace's reference leads by 0.11-0.14 s), and at most this share of the record.
BASELINE_MAX_SHIFT_S = 1.0
BASELINE_MAX_SHARE = 1.0 / 6.0
#: :func:`pure_delay_baseline` sums every shift exactly up to this many; beyond, only this many candidates the fast
#: Fourier transform ranks best (:func:`_likely_shifts`) [-].
BASELINE_EXACT_SHIFTS = 256
BASELINE_CANDIDATES = 32


def pure_delay_baseline(reference: np.ndarray, measured: np.ndarray, sample_time: float, *,
                        mask: np.ndarray | None = None) -> dict:
    """The two naive predictions of the measured position a model must beat: the commanded position itself
    (its error is the following error ``x_ref - x``) and the commanded position delayed by the best whole number
    of samples (a pure delay, :func:`delay_reference`; > 0 when the measured position lags).

    Returns ``{"following_error_rms_um", "pure_delay_rms_um", "pure_delay_samples", "pure_delay_s"}``, RMS over the
    whole record, or over the samples ``mask`` (the diagnosis' active samples, which its held-out errors cover: a
    held-out error is compared with the naive predictions of the same samples). Our reading: an engineer judges a
    model of the loop by how much of the error of these two it explains; a model that predicts no better than a
    pure delay has learnt nothing of the loop's dynamics from this record (a record sampled far slower than the
    loop responds, or a measured channel that is not the loop's), whatever its poles. The shift is tried up to
    :data:`BASELINE_MAX_SHIFT_S` either way, at most :data:`BASELINE_MAX_SHARE` of the record.
    """
    xr = np.asarray(reference, dtype=float)
    x = np.asarray(measured, dtype=float)
    n = x.size
    w = np.ones(n) if mask is None else np.asarray(mask, dtype=float)
    count = float(w.sum())
    rms0 = float(np.sqrt(np.sum(w * (x - xr) ** 2) / count))
    best, shift = rms0, 0
    most = int(min(BASELINE_MAX_SHIFT_S / sample_time, n * BASELINE_MAX_SHARE))
    # delay_reference(xr, s) for a whole s, without its interpolation: the first (last) value held over the s
    # samples before (after) the record, and the rest the reference shifted (the same values, a sum of squares
    # instead of a mean: O(n) per shift with no temporaries beyond one difference)
    held_first, held_last = np.cumsum(w * (x - xr[0]) ** 2), np.cumsum((w * (x - xr[-1]) ** 2)[::-1])
    for k in _likely_shifts(xr, x, w, most, held_first, held_last):
        for s in (k, -k):
            d = x[k:] - xr[:-k] if s > 0 else x[:-k] - xr[k:]
            ws = w[k:] if s > 0 else w[:-k]
            held = held_first[k - 1] if s > 0 else held_last[k - 1]
            rms = math.sqrt((float(np.einsum("i,i,i->", d, d, ws)) + float(held)) / count)
            if rms < best:
                best, shift = rms, s
    return {"following_error_rms_um": rms0 * 1e3, "pure_delay_rms_um": best * 1e3, "pure_delay_samples": shift,
            "pure_delay_s": shift * sample_time}


def _likely_shifts(xr: np.ndarray, x: np.ndarray, w: np.ndarray, most: int, held_first: np.ndarray,
                   held_last: np.ndarray) -> np.ndarray:
    """The whole shifts 1..``most`` (ascending) :func:`pure_delay_baseline` sums exactly: all of them up to
    :data:`BASELINE_EXACT_SHIFTS`, else those whose sum of squares, of either sign, the fast Fourier transform puts
    among the :data:`BASELINE_CANDIDATES` smallest (its sums expanded as sum w x^2 - 2 sum w x xr + sum w xr^2, the
    two cross terms by correlation, about the record's mean so that they cancel little), and shift 1. The loop over
    every shift (with the held first or last value's share, ``held_first``/``held_last``) was O(n) each: 8000 of
    them over 601,126 samples at 125 us took 145 s of a diagnosis (loaded cores);
    summed exactly and compared in the same order as before, the chosen shift and RMS are the loop's whenever the
    best lies among the candidates (the transform's rounding, about 1e-12 of the sums, is far below their gaps)."""
    if most <= BASELINE_EXACT_SHIFTS:
        return np.arange(1, most + 1)
    import scipy.signal

    c = float(np.mean(xr))
    a, r = x - c, xr - c
    wa2 = np.cumsum((w * a * a)[::-1])[::-1]  # sum over i >= k
    wa2_head = np.cumsum(w * a * a)  # sum over i < n - k: wa2_head[n - k - 1]
    n = x.size
    k = np.arange(1, most + 1)
    # s = +k: sum_{i>=k} w_i (a_i - r_{i-k})^2; s = -k: sum_{i<n-k} w_i (a_i - r_{i+k})^2
    cross = scipy.signal.correlate(w * a, r, mode="full", method="fft")  # index n-1+j: sum_i (w a)_{i+j} r_i
    square = scipy.signal.correlate(w, r * r, mode="full", method="fft")
    plus = wa2[k] - 2.0 * cross[n - 1 + k] + square[n - 1 + k] + held_first[k - 1]
    minus = wa2_head[n - k - 1] - 2.0 * cross[n - 1 - k] + square[n - 1 - k] + held_last[k - 1]
    sums = np.minimum(plus, minus)
    keep = np.argsort(sums, kind="stable")[:BASELINE_CANDIDATES]
    return np.union1d(k[keep], [1])


@dataclasses.dataclass(frozen=True)
class DelayEstimate:
    """Result of :func:`estimate_delay`.

    Attributes
    ----------
    delay_s : float
        Estimated dead time [s] (0 when positive and below :data:`MIN_DELAY_SAMPLES`).
    samples : float
        The same in samples (before the threshold).
    objective_ratio : float
        Equation-error objective at the estimate over the objective without a shift [-].
    scanned_s : tuple of float
        The scanned range [s].
    """

    delay_s: float
    samples: float
    objective_ratio: float
    scanned_s: tuple[float, float]

    def to_dict(self) -> dict:
        return {"delay_s": self.delay_s, "samples": self.samples, "objective_ratio": self.objective_ratio,
                "scanned_s": list(self.scanned_s)}


def _rss(xr: np.ndarray, x: np.ndarray, T: float, samples: float, margin: int, opt: RegressorOptions) -> float:
    """Residual sum of squares of the unconstrained regression of Eq. (3.11) on the shifted reference."""
    shifted = delay_reference(xr, samples)[margin:xr.size - margin]
    stats = SufficientStatistics(8)
    for phi, y in iter_regressor(shifted, x[margin:x.size - margin], T, options=opt):
        stats.update(phi, y)
    return float((stats.factor[-1, -1] / stats.scale[-1]) ** 2)


def _golden_integer(f, lo: int, hi: int) -> int:
    """Integer minimiser of a unimodal ``f`` on [lo, hi] by golden-section steps."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    while hi - lo > 3:
        a = int(round(hi - g * (hi - lo)))
        b = int(round(lo + g * (hi - lo)))
        if a == b:
            b = a + 1
        if f(a) <= f(b):
            hi = b
        else:
            lo = a
    return min(range(lo, hi + 1), key=f)


def estimate_delay(reference: np.ndarray, measured: np.ndarray, sample_time: float, *,
                   options: RegressorOptions | None = None, max_delay_s: float = MAX_DELAY_S) -> DelayEstimate:
    """Dead time [s] between the recorded reference and the loop (see the module docstring).

    Parameters
    ----------
    reference, measured : ndarray
        Recorded commanded and measured positions [mm].
    sample_time : float
        [s].
    options : RegressorOptions, optional
    max_delay_s : float
        Half-width of the scan [s] (limited to a sixth of the record).

    Notes
    -----
    The objective is the residual of the regression of Eq. (3.11) on the delayed reference (the
    least-squares fit before the pole box: the box guarantees stability, not the timing). The
    scan runs coarse on the record decimated to about 4 ms, then golden-section on whole samples
    around the best coarse shift, then golden section on the fraction within one sample of it.
    """
    xr = np.asarray(reference, float)
    x = np.asarray(measured, float)
    opt = options or RegressorOptions()
    q0 = int(round(FINEST_STEP_S / sample_time))
    if q0 >= 2:  # fast sampling: on the record decimated to about 1 ms (see FINEST_STEP_S)
        est = estimate_delay(xr[::q0], x[::q0], sample_time * q0, options=opt, max_delay_s=max_delay_s)
        return DelayEstimate(est.delay_s, est.samples * q0, est.objective_ratio, est.scanned_s)
    n = xr.size
    dmax = int(min(round(max_delay_s / sample_time), n // 6))
    if dmax < 2:
        return DelayEstimate(0.0, 0.0, 1.0, (0.0, 0.0))
    lag_s, corr = follow_lag(xr, x, sample_time)
    c = int(round(lag_s / sample_time)) if abs(lag_s) > max_delay_s and corr >= FOLLOW_CORRELATION else 0
    margin = abs(c) + dmax + 1
    q = max(1, int(round(0.004 / sample_time)))
    xr_q, x_q, dq, cq = xr[::q], x[::q], dmax // q, c // q
    coarse: dict[int, float] = {}
    if dq >= 2:
        step = max(1, dq // 15)
        for d in sorted({*range(cq - dq, cq + dq + 1, step), 0}):
            coarse[d] = _rss(xr_q, x_q, sample_time * q, float(d), abs(cq) + dq + 1, opt)
        best_q = min(coarse, key=coarse.get)
        lo, hi = max(c - dmax, (best_q - step) * q - q), min(c + dmax, (best_q + step) * q + q)
    else:
        lo, hi = c - dmax, c + dmax
    cache: dict[float, float] = {}

    def f(d: float) -> float:
        if d not in cache:
            cache[d] = _rss(xr, x, sample_time, d, margin, opt)
        return cache[d]

    best = _golden_integer(f, lo, hi)
    a, b = max(best - 1.0, float(c - dmax)), min(best + 1.0, float(c + dmax))
    g = (math.sqrt(5.0) - 1.0) / 2.0
    while b - a > FRACTION_TOLERANCE:  # golden section on the fraction
        u, v = b - g * (b - a), a + g * (b - a)
        if f(u) <= f(v):
            b = v
        else:
            a = u
    samples = float(min((best, 0.5 * (a + b)), key=lambda s: f(float(s))))
    base = f(0.0)
    ratio = f(samples) / base if base > 0 and math.isfinite(base) else 1.0
    significant = (samples >= MIN_DELAY_SAMPLES or samples < 0.0) and ratio <= MAX_OBJECTIVE_RATIO
    delay = samples * sample_time if significant else 0.0
    return DelayEstimate(delay, samples, ratio, ((c - dmax) * sample_time, (c + dmax) * sample_time))
