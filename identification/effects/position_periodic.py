"""``position_periodic``: a force periodic in the axis position (cogging, torque ripple, lead)."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free
from identification.effects._fourier import fourier_basis

__all__ = ["MIN_PERIODS_COVERED", "PositionPeriodic"]

#: Fewest periods the travel must cover for the record to pin the period [-]. A force of position is known only
#: over the travel; over fewer than two periods the record shows it repeat on the overlap alone (the travel less one
#: period), and below half a period of overlap any smooth force of position is fitted by a long period and its
#: harmonics as well as by the true one. ballscrew-ppc's x with a 5 mm load, 0.1 um noise, 30 random moves (seeds
#: 1-3, /tmp/identfuzz35/cover.py, 2026-11-26): a travel of 1.1-1.2 periods named 5.04, 5.17 and 10.9 mm, of
#: 1.4 periods 5.02, 5.37 and 5.10 mm, of 1.6-1.8 periods 4.98 to 5.05 mm; ident_fuzz seed 51 case 1 (5.67 mm of
#: travel, a 5 mm load) refitted 5.95 mm with one harmonic, 7.12 with two and 8.33 on another platform, all within
#: 1 % of one held-out error.
MIN_PERIODS_COVERED = 1.5


@dataclasses.dataclass(frozen=True, kw_only=True)
class PositionPeriodic(Effect):
    """Extra term ``sum_h A_h sin(2 pi h x / P) + B_h cos(2 pi h x / P)`` in w [mm/s^2].

    Parameters
    ----------
    period : float
        Spatial period P [mm] (screw lead, pole pitch); nonlinear, found by a search of the
        residual against position.
    coefficients : tuple of (float, float)
        (A_h, B_h) for h = 1..H [mm/s^2].

    Notes
    -----
    The thesis' model has no position-dependent force (Sec. 3.2). FMU: yes (a smooth term of w).
    """

    period: float
    coefficients: tuple = ((0.0, 0.0),)

    NAME: ClassVar[str] = "position_periodic"
    KIND: ClassVar[str] = "disturbance"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"period_mm": "mm", "harmonics": "-", "coefficients_mm_s2": "mm/s^2",
                                       "amplitude_mm_s2": "mm/s^2"}
    DESCRIPTION: ClassVar[str] = "force periodic in position (cogging, torque ripple, lead error)"

    @property
    def harmonics(self) -> int:
        return len(self.coefficients)

    @property
    def amplitude(self) -> float:
        """Amplitude of the fundamental [mm/s^2]."""
        a, b = self.coefficients[0]
        return math.hypot(a, b)

    def parameters(self):
        return {"period_mm": self.period, "harmonics": self.harmonics,
                "coefficients_mm_s2": [list(c) for c in self.coefficients], "amplitude_mm_s2": self.amplitude}

    @classmethod
    def from_parameters(cls, p):
        coef = tuple((float(a), float(b)) for a, b in p.get("coefficients_mm_s2", [(0.0, 0.0)]))
        return cls(period=cls._require(p, "period_mm", "mm"), coefficients=coef)

    def summary(self):
        return f"period {self.period:.4g} mm, amplitude {self.amplitude:.4g} mm/s^2"

    def unpinned(self, *, travel: float, duration: float) -> dict[str, str]:
        """``{"period_mm": why}`` when ``travel`` [mm] covers the period fewer than :data:`MIN_PERIODS_COVERED`
        times: the record then fixes the force along the travel, not the period it repeats with."""
        if travel >= MIN_PERIODS_COVERED * self.period:
            return {}
        return {"period_mm": f"the travel ({travel:.4g} mm) covers the period {travel / self.period:.2g} times, "
                             f"fewer than the {MIN_PERIODS_COVERED:g} that pin it: the record fixes the force along "
                             "the travel, not the period it repeats with"}

    @staticmethod
    def basis(position: np.ndarray, period: float, harmonics: int = 1) -> np.ndarray:
        return fourier_basis(2.0 * np.pi * position / period, harmonics)

    @classmethod
    def grid(cls, span: float) -> np.ndarray:
        """Periods searched [mm]: 0.5 mm to the travel span (log-spaced, fine)."""
        return np.geomspace(0.5, max(span, 1.0), 400)

    def with_coefficients(self, coef):
        c = np.asarray(coef, float).reshape(-1, 2)
        return dataclasses.replace(self, coefficients=tuple((float(a), float(b)) for a, b in c))

    def pack(self, spec, *, model_sample_time):
        spec.pp_period = self.period
        spec.pp_coef = np.array(self.coefficients, float).reshape(-1, 2)

    def free(self):
        c = np.array(self.coefficients, float).ravel()
        s = max(float(np.max(np.abs(c))), 1.0)
        return [Free("log_period", math.log(self.period), math.log(1e-3), math.log(1e4), 1e-2)] + [
            Free(f"coef{i}", float(v), scale=s, linear=True) for i, v in enumerate(c)]

    def with_free(self, values):
        return dataclasses.replace(self.with_coefficients(values[1:]), period=math.exp(values[0]))
