"""Computational (transport) delay of the control signal."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["ComputationalDelay"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class ComputationalDelay(Record):
    """Whole samples between reading the feedback and applying the resulting control signal.

    Parameters
    ----------
    samples : int
        Delay [samples] (0 to 64); the EMPS bench has one.
    """

    samples: int

    UNITS: ClassVar[dict[str, str]] = {"samples": "samples"}
    TABLE: ClassVar[str] = "delay"

    def __post_init__(self) -> None:
        self._integer("samples", 0, 64)
