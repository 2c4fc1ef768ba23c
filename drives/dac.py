"""Digital-to-analogue converter of the control signal."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["DAC"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class DAC(Record):
    """Quantisation and range of the DAC that outputs the control signal.

    Parameters
    ----------
    bits : int
        Resolution [bit]; the step is ``2 * range / 2**bits`` (16 bit over +/-10 V: 0.305 mV).
    range : float
        Output range +/- ``range`` [V]; the signal is clipped to it.
    """

    bits: int = 16
    range: float = 10.0

    UNITS: ClassVar[dict[str, str]] = {"bits": "bit", "range": "V"}
    TABLE: ClassVar[str] = "dac"

    def __post_init__(self) -> None:
        self._integer("bits", 1, 32)
        self._positive("range")

    @property
    def lsb(self) -> float:
        """One DAC step [V]."""
        return 2.0 * self.range / 2.0**self.bits
