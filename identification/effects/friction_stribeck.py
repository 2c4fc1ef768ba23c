"""``friction_stribeck``: friction higher near standstill (Stribeck curve) than the Coulomb level."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free
from vcnc.core.errors import InputError

__all__ = ["FrictionStribeck"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class FrictionStribeck(Effect):
    """Extra friction ``(PV s+ + NV s-) exp(-(v / v_s)^2)`` in w [mm/s^2].

    Parameters
    ----------
    velocity : float
        Stribeck velocity v_s [mm/s] (nonlinear: found by a 1-D search).
    excess_positive, excess_negative : float
        Static minus Coulomb level for + / - motion [mm/s^2] (linear: s+, s-; same signs as d0, d1).
    stick : bool
        Simulate it in the split form (:mod:`identification.augmented`), where a stopped mass stays at rest
        until the force on it leaves the static band ``d1 + s-`` .. ``d0 + s+`` (Karnopp): stiction that holds
        each move's start from rest. False: the exact loop, whose friction switches on the sampled sign of the
        velocity and holds nothing. JSON ``stick_at_rest`` (written only when true; a record without it is the
        exact form).

    Notes
    -----
    The thesis' model has Coulomb friction only (Eq. 3.2, Sec. 3.2). Static/Coulomb ratio is
    ``(d0 + s+) / d0``. Representable in an FMU in either form (a smooth term of w; the split form with
    ``stick``, with the plant's viscous rate).
    """

    velocity: float
    excess_positive: float = 0.0
    excess_negative: float = 0.0
    stick: bool = False

    NAME: ClassVar[str] = "friction_stribeck"
    KIND: ClassVar[str] = "disturbance"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"stribeck_velocity_mm_s": "mm/s", "excess_positive_mm_s2": "mm/s^2",
                                       "excess_negative_mm_s2": "mm/s^2"}
    DESCRIPTION: ClassVar[str] = "friction changes near standstill (Stribeck curve)"

    def parameters(self):
        out = {"stribeck_velocity_mm_s": self.velocity, "excess_positive_mm_s2": self.excess_positive,
               "excess_negative_mm_s2": self.excess_negative}
        if self.stick:
            out["stick_at_rest"] = True
        return out

    @classmethod
    def from_parameters(cls, p):
        stick = p.get("stick_at_rest", False)
        if not isinstance(stick, bool):
            raise InputError(f"effect parameter 'stick_at_rest' must be true or false (got {stick!r})")
        return cls(velocity=cls._require(p, "stribeck_velocity_mm_s", "mm/s"),
                   excess_positive=cls._require(p, "excess_positive_mm_s2", "mm/s^2"),
                   excess_negative=cls._require(p, "excess_negative_mm_s2", "mm/s^2"), stick=stick)

    def summary(self):
        held = ", stick at rest" if self.stick else ""
        return f"v_s {self.velocity:.3g} mm/s, +{self.excess_positive:.4g}/{self.excess_negative:.4g} mm/s^2{held}"

    @property
    def in_loop(self):
        return self.stick

    @staticmethod
    def basis(velocity: np.ndarray, vs: float) -> np.ndarray:
        """Columns (PV exp(-(v/vs)^2), NV exp(..)) whose coefficients are (s+, s-)."""
        g = np.exp(-((velocity / vs) ** 2))
        return np.column_stack([g * (velocity > 0), g * (velocity < 0)])

    @classmethod
    def grid(cls, vmax: float) -> np.ndarray:
        """Stribeck velocities searched [mm/s]: 0.05 mm/s to 20 % of the peak speed."""
        return np.geomspace(0.05, max(0.2 * vmax, 0.1), 24)

    def with_coefficients(self, coef):
        return dataclasses.replace(self, excess_positive=float(coef[0]), excess_negative=float(coef[1]))

    def pack(self, spec, *, model_sample_time):
        spec.structured = spec.structured or self.stick
        spec.stribeck = np.array([self.velocity, self.excess_positive, self.excess_negative])

    def free(self):
        s = max(abs(self.excess_positive), abs(self.excess_negative), 1.0)
        return [Free("log_velocity", math.log(self.velocity), math.log(1e-3), math.log(1e4), 1.0),
                Free("excess_positive", self.excess_positive, scale=s, linear=True),
                Free("excess_negative", self.excess_negative, scale=s, linear=True)]

    def with_free(self, values):
        return dataclasses.replace(self, velocity=math.exp(values[0]), excess_positive=float(values[1]),
                                   excess_negative=float(values[2]))
