"""Amplifier saturation: current or voltage limit."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["Saturation"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Saturation(Record):
    """Actuator limit, given either as a current or as a control-voltage limit.

    Parameters
    ----------
    current_limit : float, optional
        Peak amplifier current [A]; converted to a control-signal limit through the drive's
        amplifier gain [A/V].
    voltage_limit : float, optional
        Control-signal limit [V] (e.g. +/-10 V of the EMPS amplifier input).

    Notes
    -----
    Exactly one of the two must be given. Assumption 2 of Sec. 3.2 of the thesis (no actuator
    saturation) fails when this limit is reached.
    """

    current_limit: float | None = None
    voltage_limit: float | None = None

    UNITS: ClassVar[dict[str, str]] = {"current_limit": "A", "voltage_limit": "V"}
    TABLE: ClassVar[str] = "saturation"

    def __post_init__(self) -> None:
        if (self.current_limit is None) == (self.voltage_limit is None):
            raise self._fail("current_limit", "or voltage_limit: give exactly one of the two")
        if self.current_limit is not None:
            self._positive("current_limit")
        else:
            self._positive("voltage_limit")

    def control_limit(self, amplifier_gain: float) -> float:
        """Limit of the control signal [V] for an amplifier gain [A/V]."""
        if self.voltage_limit is not None:
            return float(self.voltage_limit)
        return float(self.current_limit) / amplifier_gain  # type: ignore[arg-type]
