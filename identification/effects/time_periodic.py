"""``time_periodic``: an external load periodic in time (cutting, pulses, an unbalanced spindle)."""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free
from identification.effects._fourier import fourier_basis, fourier_eval

__all__ = ["TimePeriodic"]


@functools.lru_cache(maxsize=2)
def _sampled_basis(period: float, n: int, sample_time: float, harmonics: int) -> np.ndarray:
    b = fourier_basis(2.0 * np.pi * np.arange(n) * sample_time / period, harmonics)
    b.flags.writeable = False
    return b


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

    Notes
    -----
    The load acts where the thesis' disturbance w acts (Eq. 3.1: on the control signal scaled to
    acceleration), so :meth:`load` is directly comparable with a force or voltage added to the
    control signal (times the drive's K/J). FMU: yes (a function of time added to w).
    """

    period: float
    coefficients: tuple = ((0.0, 0.0),)
    mean: float = 0.0
    with_mean: bool = False

    NAME: ClassVar[str] = "time_periodic"
    KIND: ClassVar[str] = "disturbance"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"period_s": "s", "harmonics": "-", "coefficients_mm_s2": "mm/s^2",
                                       "mean_mm_s2": "mm/s^2", "peak_to_peak_mm_s2": "mm/s^2"}
    DESCRIPTION: ClassVar[str] = "external load periodic in time"

    @property
    def harmonics(self) -> int:
        return len(self.coefficients)

    def load(self, t: np.ndarray) -> np.ndarray:
        """The estimated load w(t) [mm/s^2] at times t [s]."""
        return self.mean + fourier_eval(2.0 * np.pi * np.asarray(t, float) / self.period, self.coefficients)

    def sampled_load(self, n: int, sample_time: float) -> np.ndarray:
        """The load at t = k T, k = 0..n-1 (the basis is cached: refits change only coefficients)."""
        b = _sampled_basis(float(self.period), int(n), float(sample_time), self.harmonics)
        return self.mean + b @ np.asarray(self.coefficients, float).ravel()

    def peak_to_peak(self) -> float:
        w = self.load(np.linspace(0.0, self.period, 512, endpoint=False))
        return float(np.ptp(w))

    def parameters(self):
        return {"period_s": self.period, "harmonics": self.harmonics,
                "coefficients_mm_s2": [list(c) for c in self.coefficients], "mean_mm_s2": self.mean,
                "peak_to_peak_mm_s2": self.peak_to_peak()}

    @classmethod
    def from_parameters(cls, p):
        coef = tuple((float(a), float(b)) for a, b in p.get("coefficients_mm_s2", [(0.0, 0.0)]))
        mean = float(p.get("mean_mm_s2", 0.0))
        return cls(period=cls._require(p, "period_s", "s"), coefficients=coef, mean=mean, with_mean=mean != 0.0)

    def summary(self):
        return f"period {self.period:.5g} s, {self.harmonics} harmonics, peak-to-peak {self.peak_to_peak():.4g} mm/s^2"

    @staticmethod
    def basis(t: np.ndarray, period: float, harmonics: int = 1) -> np.ndarray:
        return fourier_basis(2.0 * np.pi * t / period, harmonics)

    def with_coefficients(self, coef, mean: float | None = None):
        c = np.asarray(coef, float).reshape(-1, 2)
        return dataclasses.replace(self, coefficients=tuple((float(a), float(b)) for a, b in c),
                                   mean=self.mean if mean is None else float(mean))

    def pack(self, spec, *, model_sample_time):
        spec.wext = spec.wext + self.sampled_load(spec.n, spec.sample_time)

    def free(self):
        c = np.array(self.coefficients, float).ravel()
        s = max(float(np.max(np.abs(c))), 1.0)
        out = [Free("log_period", math.log(self.period), math.log(1e-4), math.log(1e5), 1e-3)]
        if self.with_mean:
            out.append(Free("mean", self.mean, scale=s, linear=True))
        return out + [Free(f"coef{i}", float(v), scale=s, linear=True) for i, v in enumerate(c)]

    def with_free(self, values):
        k = 2 if self.with_mean else 1
        mean = values[1] if self.with_mean else self.mean
        return dataclasses.replace(self.with_coefficients(values[k:], mean=mean), period=math.exp(values[0]))
