"""``saturation``: the actuator limit, as a clip of the acceleration demand of the split loop."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

from identification.effects._base import Effect, Free

__all__ = ["Saturation"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Saturation(Effect):
    """u = clip(u_demand, -limit, +limit) in the split form (:mod:`identification.augmented`).

    Parameters
    ----------
    limit : float
        Largest acceleration demand the actuator delivers [mm/s^2] (current or voltage limit
        times K/J). Found from the samples whose measured acceleration demand piles up at a level,
        then refitted.

    Notes
    -----
    Not linear in parameters (Assumption 2 of Sec. 3.2 fails): the structured element, not a
    regressor. The controller's integrator is not clamped (no anti-windup), as in the thesis'
    PID. FMU: yes (a clip).
    """

    limit: float

    NAME: ClassVar[str] = "saturation"
    KIND: ClassVar[str] = "element"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"limit_mm_s2": "mm/s^2"}
    DESCRIPTION: ClassVar[str] = "actuator limit (clipped acceleration demand)"

    def parameters(self):
        return {"limit_mm_s2": self.limit}

    @classmethod
    def from_parameters(cls, p):
        return cls(limit=cls._require(p, "limit_mm_s2", "mm/s^2"))

    def summary(self):
        return f"limit {self.limit:.5g} mm/s^2"

    def pack(self, spec, *, model_sample_time):
        spec.structured = True
        spec.saturation = self.limit

    def free(self):
        return [Free("log_limit", math.log(self.limit), math.log(1.0), math.log(1e8), 1e-2)]

    def with_free(self, values):
        return dataclasses.replace(self, limit=math.exp(values[0]))
