"""``backlash``: lost motion at reversals between the driven mass and the measured position."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

from identification.effects._base import Effect, Free

__all__ = ["Backlash"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Backlash(Effect):
    """Play operator of total width ``width`` between the driven mass and the measured position.

    Parameters
    ----------
    width : float
        Backlash [mm]; found by a search over widths, then refitted.

    Notes
    -----
    Structured element of the split loop: the loop is closed on the measured (table) position, the
    driven mass crosses the gap at each reversal while the table stands (a linear-scale loop).
    A loop closed on a motor encoder cannot see its own backlash in (reference, measured) data.
    FMU: yes (a play operator, one state).
    """

    width: float

    NAME: ClassVar[str] = "backlash"
    KIND: ClassVar[str] = "element"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"width_mm": "mm"}
    DESCRIPTION: ClassVar[str] = "lost motion at reversals"

    def parameters(self):
        return {"width_mm": self.width}

    @classmethod
    def from_parameters(cls, p):
        return cls(width=cls._require(p, "width_mm", "mm"))

    def summary(self):
        return f"width {self.width * 1e3:.4g} um"

    def pack(self, spec, *, model_sample_time):
        spec.structured = True
        spec.backlash = self.width

    def free(self):
        return [Free("log_width", math.log(self.width), math.log(1e-5), math.log(10.0), 1e-2)]

    def with_free(self, values):
        return dataclasses.replace(self, width=math.exp(values[0]))
