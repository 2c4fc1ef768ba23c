"""``delay``: whole samples of transport delay between the controller and the plant."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from identification.effects._base import Effect

__all__ = ["Delay"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Delay(Effect):
    """The control action u reaches the plant ``samples`` sample periods late (split form).

    Parameters
    ----------
    samples : int
        Delay [samples], >= 1; found by an exhaustive search over 1..:attr:`MAX` with the
        delayed split-form regression, then the joint refit.

    Notes
    -----
    The thesis' model has none (Sec. 3.2). Stored with the model's sample time; at another
    sample time the delay in seconds is kept (rounded to whole samples). FMU: yes (a delay line).
    """

    samples: int

    MAX: ClassVar[int] = 8
    NAME: ClassVar[str] = "delay"
    KIND: ClassVar[str] = "element"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"samples": "samples", "delay_s": "s"}
    DESCRIPTION: ClassVar[str] = "transport delay of the control action"

    sample_time: float = 0.0

    def parameters(self):
        return {"samples": int(self.samples), "delay_s": self.samples * self.sample_time}

    @classmethod
    def from_parameters(cls, p):
        s = cls._require(p, "samples", "samples")
        return cls(samples=int(round(s)), sample_time=float(p.get("delay_s", 0.0)) / max(s, 1))

    def summary(self):
        return f"{self.samples} samples"

    def pack(self, spec, *, model_sample_time):
        spec.structured = True
        spec.delay = int(round(self.samples * model_sample_time / spec.sample_time))
