"""``time_periodic``: an external load periodic in time (cutting, pulses, an unbalanced spindle, a shaker).

The load may act only inside a window of the record and ramp in amplitude there (a shaker switched
on for a few seconds, a cut that deepens): ``window`` and ``coefficients_end`` (module of
:class:`TimePeriodic`).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free
from identification.effects._fourier import fourier_basis, fourier_eval
from identification.kernels import fourier_series
from vcnc.core.errors import InputError

__all__ = ["TimePeriodic"]


@functools.lru_cache(maxsize=8)
def _sampled_phase(period: float, n: int, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
    """sin and cos of the phase 2 pi k T / P, k = 0..n-1 (cached: a refit's linear steps keep P)."""
    ph = 2.0 * np.pi * np.arange(n) * sample_time / period
    s1, c1 = np.sin(ph), np.cos(ph)
    s1.flags.writeable = False
    c1.flags.writeable = False
    return s1, c1


@functools.lru_cache(maxsize=8)
def _cached_load(effect: TimePeriodic, n: int, sample_time: float) -> np.ndarray:
    """:meth:`TimePeriodic.sampled_load`, cached on the (frozen, hashable) effect: a refit's
    finite-difference Jacobian moves one parameter at a time, so most of its simulations keep the
    load of the point it differentiates at. On EMPS DATA_EMPS_PULSES (64 harmonics, 24,841 samples)
    the series took 1.4 ms of each simulation, and 442 of them went to the nonlinear solves of one
    refit (cProfile, 2026-11-23, the 2-core development machine)."""
    w = effect._sampled_load(n, sample_time)
    w.flags.writeable = False
    return w


@dataclasses.dataclass(frozen=True, kw_only=True)
class TimePeriodic(Effect):
    """Extra term ``mean + sum_h C_h sin(2 pi h t / P) + D_h cos(2 pi h t / P)`` in w [mm/s^2].

    t is the time from the first sample of the simulated reference [s].

    Parameters
    ----------
    period : float
        P [s]; nonlinear, found from the residual spectrum and refined by search.
    coefficients : tuple of (float, float)
        (C_h, D_h) for h = 1..H [mm/s^2]; H is chosen by the search (a square wave needs many odd
        harmonics, a sinusoid one).
    mean : float
        Constant part of the load [mm/s^2].
    with_mean : bool
        Whether ``mean`` is estimated: only when the axis stands still long enough to tell a
        constant load from the Coulomb levels d0, d1 (otherwise it stays 0 and the Coulomb levels
        carry it while moving).
    window : tuple of (float, float) or None
        (t_on, t_off) [s]: the load acts only for t_on <= t < t_off (None: always). Found by the
        search from the residual's short-time content and kept fixed by the refit.
    coefficients_end : tuple of (float, float) or None
        Coefficients at t_off [mm/s^2] when the amplitude ramps: inside the window the load is
        ``(1 - s) F(coefficients) + s F(coefficients_end)`` with s = (t - t_on) / (t_off - t_on)
        (a linear amplitude envelope; None: constant amplitude). Needs a window.

    Notes
    -----
    The load acts where the thesis' disturbance w acts (Eq. 3.1: on the control signal scaled to
    acceleration), so :meth:`load` is directly comparable with a force or voltage added to the
    control signal (times the drive's K/J). FMU: yes for the always-on load (a function of time
    added to w); a windowed load is not exportable (``fmu`` false in its record) - the FMU's C
    source has no window or envelope yet.
    """

    period: float
    coefficients: tuple = ((0.0, 0.0),)
    mean: float = 0.0
    with_mean: bool = False
    window: tuple | None = None
    coefficients_end: tuple | None = None

    NAME: ClassVar[str] = "time_periodic"
    KIND: ClassVar[str] = "disturbance"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"period_s": "s", "harmonics": "-", "coefficients_mm_s2": "mm/s^2",
                                       "mean_mm_s2": "mm/s^2", "peak_to_peak_mm_s2": "mm/s^2", "window_s": "s",
                                       "coefficients_end_mm_s2": "mm/s^2", "amplitude_start_mm_s2": "mm/s^2",
                                       "amplitude_end_mm_s2": "mm/s^2"}
    DESCRIPTION: ClassVar[str] = "external load periodic in time"

    @property
    def harmonics(self) -> int:
        return len(self.coefficients)

    @property
    def windowed(self) -> bool:
        return self.window is not None

    def envelope_weights(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(weight of ``coefficients``, weight of ``coefficients_end``) at times t [s] (window and ramp)."""
        t = np.asarray(t, float)
        if self.window is None:
            return np.ones(t.shape), np.zeros(t.shape)
        t0, t1 = self.window
        inside = ((t >= t0) & (t < t1)).astype(float)
        if self.coefficients_end is None:
            return inside, np.zeros(t.shape)
        s = np.clip((t - t0) / max(t1 - t0, 1e-300), 0.0, 1.0)
        return inside * (1.0 - s), inside * s

    def load(self, t: np.ndarray) -> np.ndarray:
        """The estimated load w(t) [mm/s^2] at times t [s]."""
        t = np.asarray(t, float)
        ph = 2.0 * np.pi * t / self.period
        g0, g1 = self.envelope_weights(t)
        w = g0 * fourier_eval(ph, self.coefficients)
        if self.coefficients_end is not None:
            w = w + g1 * fourier_eval(ph, self.coefficients_end)
        return self.mean + w

    def sampled_load(self, n: int, sample_time: float) -> np.ndarray:
        """The load at t = k T, k = 0..n-1 (read-only: cached, see :func:`_cached_load`)."""
        return _cached_load(self, int(n), float(sample_time))

    def _sampled_load(self, n: int, sample_time: float) -> np.ndarray:
        s1, c1 = _sampled_phase(float(self.period), int(n), float(sample_time))
        w = fourier_series(s1, c1, np.array(self.coefficients, float).reshape(-1, 2))
        if self.window is None:
            return self.mean + w
        g0, g1 = self.envelope_weights(np.arange(n) * sample_time)
        w = g0 * w
        if self.coefficients_end is not None:
            w = w + g1 * fourier_series(s1, c1, np.array(self.coefficients_end, float).reshape(-1, 2))
        return self.mean + w

    def peak_to_peak(self) -> float:
        """Peak-to-peak of one period at the larger end of the envelope [mm/s^2]."""
        ph = np.linspace(0.0, 2.0 * np.pi, 512, endpoint=False)
        out = float(np.ptp(fourier_eval(ph, self.coefficients)))
        if self.coefficients_end is not None:
            out = max(out, float(np.ptp(fourier_eval(ph, self.coefficients_end))))
        return out

    def record(self):
        rec = super().record()
        rec["fmu"] = not self.windowed
        return rec

    def parameters(self):
        out = {"period_s": self.period, "harmonics": self.harmonics,
               "coefficients_mm_s2": [list(c) for c in self.coefficients], "mean_mm_s2": self.mean,
               "peak_to_peak_mm_s2": self.peak_to_peak()}
        if self.window is not None:
            ph = np.linspace(0.0, 2.0 * np.pi, 512, endpoint=False)
            out["window_s"] = [float(self.window[0]), float(self.window[1])]
            out["amplitude_start_mm_s2"] = 0.5 * float(np.ptp(fourier_eval(ph, self.coefficients)))
            end = self.coefficients if self.coefficients_end is None else self.coefficients_end
            out["amplitude_end_mm_s2"] = 0.5 * float(np.ptp(fourier_eval(ph, end)))
            if self.coefficients_end is not None:
                out["coefficients_end_mm_s2"] = [list(c) for c in self.coefficients_end]
        return out

    @classmethod
    def from_parameters(cls, p):
        coef = tuple((float(a), float(b)) for a, b in p.get("coefficients_mm_s2", [(0.0, 0.0)]))
        mean = float(p.get("mean_mm_s2", 0.0))
        window = p.get("window_s")
        if window is not None:
            if (not isinstance(window, (list, tuple)) or len(window) != 2
                    or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in window)
                    or not window[0] < window[1]):
                raise InputError(f"effect parameter 'window_s' [s] must be [t_on, t_off] with t_on < t_off "
                                 f"(got {window!r})")
            window = (float(window[0]), float(window[1]))
        end = p.get("coefficients_end_mm_s2")
        if end is not None:
            if window is None:
                raise InputError("effect parameter 'coefficients_end_mm_s2' needs 'window_s'")
            end = tuple((float(a), float(b)) for a, b in end)
            if len(end) != len(coef):
                raise InputError(f"'coefficients_end_mm_s2' has {len(end)} harmonics, 'coefficients_mm_s2' "
                                 f"{len(coef)}")
        return cls(period=cls._require(p, "period_s", "s"), coefficients=coef, mean=mean, with_mean=mean != 0.0,
                   window=window, coefficients_end=end)

    def summary(self):
        out = f"period {self.period:.5g} s, {self.harmonics} harmonics, peak-to-peak {self.peak_to_peak():.4g} mm/s^2"
        if self.window is not None:
            p = self.parameters()
            out += (f", on {self.window[0]:.4g}..{self.window[1]:.4g} s, amplitude {p['amplitude_start_mm_s2']:.4g}"
                    f" -> {p['amplitude_end_mm_s2']:.4g} mm/s^2")
        return out

    @staticmethod
    def basis(t: np.ndarray, period: float, harmonics: int = 1) -> np.ndarray:
        return fourier_basis(2.0 * np.pi * t / period, harmonics)

    def window_basis(self, t: np.ndarray) -> np.ndarray:
        """Columns of the load linear in its coefficients at times t (``coefficients`` then
        ``coefficients_end``), the window and ramp applied; no mean column."""
        b = fourier_basis(2.0 * np.pi * np.asarray(t, float) / self.period, self.harmonics)
        g0, g1 = self.envelope_weights(t)
        if self.coefficients_end is None:
            b *= g0[:, None]
            return b
        return np.hstack([b * g0[:, None], b * g1[:, None]])

    def with_coefficients(self, coef, mean: float | None = None):
        """A copy with the coefficients (``coefficients`` then ``coefficients_end`` when ramped) replaced."""
        c = np.asarray(coef, float).reshape(-1, 2)
        if self.coefficients_end is not None:
            h = c.shape[0] // 2
            start, end = c[:h], c[h:]
            return dataclasses.replace(self, coefficients=tuple((float(a), float(b)) for a, b in start),
                                       coefficients_end=tuple((float(a), float(b)) for a, b in end),
                                       mean=self.mean if mean is None else float(mean))
        return dataclasses.replace(self, coefficients=tuple((float(a), float(b)) for a, b in c),
                                   mean=self.mean if mean is None else float(mean))

    def pack(self, spec, *, model_sample_time):
        spec.wext = spec.wext + self.sampled_load(spec.n, spec.sample_time)

    def free(self):
        c = np.array(self.coefficients, float).ravel()
        if self.coefficients_end is not None:
            c = np.concatenate([c, np.array(self.coefficients_end, float).ravel()])
        s = max(float(np.max(np.abs(c))), 1.0)
        out = [Free("log_period", math.log(self.period), math.log(1e-4), math.log(1e5), 1e-3)]
        if self.with_mean:
            out.append(Free("mean", self.mean, scale=s, linear=True))
        return out + [Free(f"coef{i}", float(v), scale=s, linear=True) for i, v in enumerate(c)]

    def with_free(self, values):
        k = 2 if self.with_mean else 1
        mean = values[1] if self.with_mean else self.mean
        return dataclasses.replace(self.with_coefficients(values[k:], mean=mean), period=math.exp(values[0]))
