"""Position measurement quantisation (incremental encoder or linear scale)."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["Encoder"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Encoder(Record):
    """Position quantisation of the feedback device.

    Parameters
    ----------
    resolution : float
        One count [mm] (e.g. 1.25e-3 for the ball-screw bench of Sec. 3.4.2 of the thesis); the
        measurement is rounded to the nearest count.
    """

    resolution: float

    UNITS: ClassVar[dict[str, str]] = {"resolution": "mm"}
    TABLE: ClassVar[str] = "encoder"

    def __post_init__(self) -> None:
        self._positive("resolution")
        if self.resolution > 1.0:
            raise self._fail("resolution", "must be at most 1 mm")
