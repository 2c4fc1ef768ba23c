"""``friction_viscous_asymmetric``: viscous friction that depends on the direction of motion."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free

__all__ = ["FrictionViscousAsymmetric"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class FrictionViscousAsymmetric(Effect):
    """Extra term ``k_a |v|`` in w [mm/s^2]: viscous rate c + k_a moving +, c - k_a moving -.

    Parameters
    ----------
    coefficient : float
        k_a [1/s]. The symmetric part of viscous friction is already in a1 of Eq. (3.3), so only
        the direction-dependent half difference is new: ``c+ - c- = 2 k_a`` (per unit mass;
        times the moving mass it is Fv+ - Fv- of the EMPS model).

    Notes
    -----
    Linear in k_a: one regressor column ``-|v|`` in the equation error, no search. FMU: yes.
    """

    coefficient: float = 0.0

    NAME: ClassVar[str] = "friction_viscous_asymmetric"
    KIND: ClassVar[str] = "disturbance"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"coefficient_1_s": "1/s", "viscous_difference_1_s": "1/s"}
    DESCRIPTION: ClassVar[str] = "direction-dependent viscous friction"

    def parameters(self):
        return {"coefficient_1_s": self.coefficient, "viscous_difference_1_s": 2.0 * self.coefficient}

    @classmethod
    def from_parameters(cls, p):
        return cls(coefficient=cls._require(p, "coefficient_1_s", "1/s"))

    def summary(self):
        return f"c+ - c- = {2 * self.coefficient:.4g} 1/s"

    @staticmethod
    def basis(velocity: np.ndarray) -> np.ndarray:
        return np.abs(velocity)[:, None]

    def with_coefficients(self, coef):
        return dataclasses.replace(self, coefficient=float(coef[0]))

    def pack(self, spec, *, model_sample_time):
        spec.asym = self.coefficient

    def free(self):
        return [Free("coefficient", self.coefficient, scale=max(abs(self.coefficient), 0.1), linear=True)]

    def with_free(self, values):
        return dataclasses.replace(self, coefficient=float(values[0]))
