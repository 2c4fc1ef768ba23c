"""Random measurement noise on the position feedback."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["MeasurementNoise"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class MeasurementNoise(Record):
    """White Gaussian noise added to the measured position before quantisation.

    Parameters
    ----------
    std : float
        Standard deviation [mm]. The sequence is drawn from the simulation's seed, so the same
        seed gives the same noise.
    """

    std: float

    UNITS: ClassVar[dict[str, str]] = {"std": "mm"}
    TABLE: ClassVar[str] = "noise"

    def __post_init__(self) -> None:
        self._nonnegative("std")
        if self.std > 1.0:
            raise self._fail("std", "must be at most 1 mm")
