"""Rigid direct (linear-motor) feed drive."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, ClassVar

from drives._record import Record

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["LinearMotorDrive"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class LinearMotorDrive(Record):
    """Rigid direct drive: amplifier, linear motor and moving table.

    Parameters
    ----------
    mass : float
        Moving mass M [kg].
    viscous : float
        Viscous friction coefficient F_v [N s/m].
    amplifier_gain : float
        Current amplifier gain [A/V].
    force_constant : float
        Motor force constant [N/A]. Only the product with ``amplifier_gain`` (the drive gain,
        e.g. g_tau of the EMPS bench [N/V]) enters the dynamics.

    Notes
    -----
    ``M x'' + F_v x' = K_amp K_f (u - d)``; in vcnc units ``x'' = (K/J)(u - d) - (B/J) x'`` with
    ``K/J = 1000 K_amp K_f / M`` [mm/(V s^2)] and ``B/J = F_v / M`` [1/s] (Eq. (5) of the EMPS
    description, Sec. 3.2 of the thesis).
    """

    mass: float
    viscous: float
    amplifier_gain: float
    force_constant: float

    UNITS: ClassVar[dict[str, str]] = {
        "mass": "kg",
        "viscous": "N s/m",
        "amplifier_gain": "A/V",
        "force_constant": "N/A",
    }
    TABLE: ClassVar[str] = "linear"

    def __post_init__(self) -> None:
        self._positive("mass", "amplifier_gain", "force_constant")
        self._nonnegative("viscous")

    @property
    def gain(self) -> float:
        """K/J: table acceleration per volt [mm/(V s^2)]."""
        return 1000.0 * self.force_per_volt / self.mass

    @property
    def viscous_rate(self) -> float:
        """B/J = F_v / M [1/s]."""
        return self.viscous / self.mass

    @property
    def force_per_volt(self) -> float:
        """Force at the table per volt [N/V]."""
        return self.amplifier_gain * self.force_constant

    @property
    def equivalent_mass(self) -> float:
        """Moving mass [kg]."""
        return self.mass

    def transfer_function(self) -> control.TransferFunction:
        """Open-loop plant x(s)/u(s) = (K/J) / (s (s + B/J)) [mm/V]."""
        import control
        return control.tf([self.gain], [1.0, self.viscous_rate, 0.0])
