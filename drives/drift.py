"""Slow drift of the position feedback relative to the table (thermal growth of the screw, scale offset)."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["Drift"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Drift(Record):
    """A slowly growing offset d(t) between the position feedback and the true table position.

    The sensor the loop closes on reads ``table + d(t)``: a drifting scale or encoder, or thermal
    growth of the screw between the motor encoder and the table (the same on a rigid axis). The
    loop holds the reading on the command, so the table ends up at ``command - d(t)``: a capture
    that records the feedback (``measurement = "feedback"``) does not show the drift, one that
    records an independent table scale (``measurement = "table"``) does, as ``-d(t)``.

    Parameters
    ----------
    rate : float
        Initial drift rate [mm/s] (signed), e.g. 2e-5 mm/s = 72 um/h for screw growth.
    time_constant : float
        Thermal time constant [s]; 0 gives a linear drift ``rate * t``, otherwise the offset
        ``rate * tau * (1 - exp(-t / tau))`` settles at ``rate * tau``.
    """

    rate: float
    time_constant: float = 0.0

    UNITS: ClassVar[dict[str, str]] = {"rate": "mm/s", "time_constant": "s"}
    TABLE: ClassVar[str] = "drift"

    def __post_init__(self) -> None:
        self._finite("rate")
        self._nonnegative("time_constant")
        if abs(self.rate) > 1.0:
            raise self._fail("rate", "must be at most 1 mm/s in magnitude")
