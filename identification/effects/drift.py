"""``drift``: a slow offset between the measured and the modelled position (thermal growth)."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free

__all__ = ["Drift"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Drift(Effect):
    """Measured = model + ``rate * t`` [mm] (t from the first sample).

    Parameters
    ----------
    rate : float
        Drift rate [mm/s] (linear in the output error: no search).

    Notes
    -----
    A drift of the position the loop is closed on is removed by the loop and cannot be seen in
    (reference, measured) data; this is a drift of the *recorded* position relative to the one
    the loop controls (e.g. a table measured by a scale while the drive closes on a growing
    screw). FMU: yes (an output offset in time).
    """

    rate: float = 0.0

    NAME: ClassVar[str] = "drift"
    KIND: ClassVar[str] = "output"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"rate_mm_s": "mm/s"}
    DESCRIPTION: ClassVar[str] = "slow offset of the measured position"

    def parameters(self):
        return {"rate_mm_s": self.rate}

    @classmethod
    def from_parameters(cls, p):
        return cls(rate=cls._require(p, "rate_mm_s", "mm/s"))

    def summary(self):
        return f"rate {self.rate * 1e3 * 3600:.4g} um/h"

    def with_coefficients(self, coef):
        return dataclasses.replace(self, rate=float(coef[0]))

    def pack(self, spec, *, model_sample_time):
        off = self.rate * spec.t
        spec.offset = off if spec.offset is None else spec.offset + off

    def free(self):
        return [Free("rate", self.rate, scale=max(abs(self.rate), 1e-6), linear=True)]

    def with_free(self, values):
        return dataclasses.replace(self, rate=float(values[0]))

    @staticmethod
    def output_basis(t: np.ndarray) -> np.ndarray:
        return np.asarray(t, float)[:, None]
