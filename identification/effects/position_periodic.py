"""``position_periodic``: a force periodic in the axis position (cogging, torque ripple, lead)."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free
from identification.effects._fourier import fourier_basis

__all__ = ["PositionPeriodic"]


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
