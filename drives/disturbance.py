"""Disturbances: position-periodic (cogging, torque ripple, lead error) and external loads."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["PositionPeriodic", "ExternalLoad"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class PositionPeriodic(Record):
    """A disturbance periodic in the motor-side position.

    Parameters
    ----------
    period : float
        Spatial period [mm] (screw lead for lead error and torque ripple per revolution, pole
        pitch for linear-motor cogging).
    force_amplitude : float
        Amplitude of a periodic force (cogging, torque ripple) [N].
    position_amplitude : float
        Amplitude of a periodic error of the table position (lead error) [mm]; it moves the table
        but not the motor, so a motor encoder does not see it.
    phase : float
        Phase at position 0 [rad].

    Notes
    -----
    ``F = A_F sin(2 pi x / period + phase)``; ``x_table += A_x sin(2 pi x / period + phase)``.
    """

    period: float
    force_amplitude: float = 0.0
    position_amplitude: float = 0.0
    phase: float = 0.0

    UNITS: ClassVar[dict[str, str]] = {
        "period": "mm",
        "force_amplitude": "N",
        "position_amplitude": "mm",
        "phase": "rad",
    }
    TABLE: ClassVar[str] = "position_periodic"

    def __post_init__(self) -> None:
        self._positive("period")
        self._nonnegative("force_amplitude", "position_amplitude")
        self._finite("phase")


@dataclasses.dataclass(frozen=True, kw_only=True)
class ExternalLoad(Record):
    """An external force on the table, constant plus periodic in time (e.g. cutting, gravity).

    Parameters
    ----------
    constant : float
        Constant force [N] opposing + motion when positive (gravity on a vertical axis, the
        EMPS ``offset``).
    amplitude : float
        Amplitude of a force periodic in time [N].
    period : float
        Its period [s] (required when ``amplitude`` > 0).
    phase : float
        Its phase at t = 0 [rad].

    Notes
    -----
    ``F(t) = constant + amplitude sin(2 pi t / period + phase)``.
    """

    constant: float = 0.0
    amplitude: float = 0.0
    period: float = 1.0
    phase: float = 0.0

    UNITS: ClassVar[dict[str, str]] = {"constant": "N", "amplitude": "N", "period": "s", "phase": "rad"}
    TABLE: ClassVar[str] = "load"

    def __post_init__(self) -> None:
        self._finite("constant", "phase")
        self._nonnegative("amplitude")
        self._positive("period")
