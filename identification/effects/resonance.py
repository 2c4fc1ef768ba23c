"""``resonance``: a lightly damped structural mode (two masses joined by a spring and a damper)."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

import numpy as np

from identification.effects._base import Effect, Free

__all__ = ["Resonance"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Resonance(Effect):
    """The rigid plant of the split loop replaced by two masses (motor 1 - r, table r).

    Parameters
    ----------
    frequency : float
        Free-free natural frequency [Hz]; searched on a log grid. Measured at the motor, the
        anti-resonance f sqrt(1 - r) is what the data pin down best; f and r trade off a little.
    damping : float
        Modal damping ratio [-].
    table_fraction : float
        Share r of the moving mass on the table side [-], in (0, 1).
    measured_at : str
        ``"motor"`` (rotary encoder: sees the anti-resonance) or ``"table"`` (linear scale).

    Notes
    -----
    The thesis' model is rigid (Sec. 3.2). FMU: yes (two more states).
    """

    frequency: float
    damping: float = 0.05
    table_fraction: float = 0.5
    measured_at: str = "motor"

    NAME: ClassVar[str] = "resonance"
    KIND: ClassVar[str] = "element"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"frequency_hz": "Hz", "damping": "-", "table_fraction": "-",
                                       "measured_at": "", "antiresonance_hz": "Hz"}
    DESCRIPTION: ClassVar[str] = "lightly damped structural mode"

    @property
    def antiresonance(self) -> float:
        """Anti-resonance seen at the motor, f sqrt(1 - r) [Hz] (the table locked by its own inertia)."""
        return self.frequency * math.sqrt(1.0 - self.table_fraction)

    def parameters(self):
        return {"frequency_hz": self.frequency, "damping": self.damping, "table_fraction": self.table_fraction,
                "measured_at": self.measured_at, "antiresonance_hz": self.antiresonance}

    @classmethod
    def from_parameters(cls, p):
        return cls(frequency=cls._require(p, "frequency_hz", "Hz"), damping=cls._require(p, "damping", "-"),
                   table_fraction=float(p.get("table_fraction", 0.5)), measured_at=str(p.get("measured_at", "motor")))

    def summary(self):
        return (f"{self.frequency:.4g} Hz, damping {self.damping:.3g}, table share {self.table_fraction:.2f}, "
                f"measured at the {self.measured_at}")

    def pack(self, spec, *, model_sample_time):
        spec.structured = True
        spec.resonance = np.array([self.frequency, self.damping, self.table_fraction,
                                   1.0 if self.measured_at == "table" else 0.0])

    def free(self):
        r = min(max(self.table_fraction, 1e-3), 1 - 1e-3)
        return [Free("log_frequency", math.log(self.frequency), math.log(0.5), math.log(5e3), 1e-2),
                Free("log_damping", math.log(self.damping), math.log(1e-3), math.log(1.0), 1e-1),
                Free("logit_fraction", math.log(r / (1 - r)), -5.0, 5.0, 1e-1)]

    def with_free(self, values):
        return dataclasses.replace(self, frequency=math.exp(values[0]), damping=math.exp(values[1]),
                                   table_fraction=1.0 / (1.0 + math.exp(-values[2])))
