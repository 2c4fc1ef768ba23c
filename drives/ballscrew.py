"""Rigid ball-screw feed drive (Fig. 2.4 and Sec. 3.2 of the thesis)."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, ClassVar

from drives._record import Record

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["BallScrewDrive"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class BallScrewDrive(Record):
    """Rigid ball-screw drive: amplifier, rotary motor, optional gear, screw and table.

    Parameters
    ----------
    inertia : float
        Equivalent inertia J reflected on the motor shaft [kg m^2] (rotor, screw, coupling and the
        table mass times (lead/2pi)^2).
    viscous : float
        Equivalent viscous damping B on the motor shaft [N m s/rad].
    amplifier_gain : float
        Current amplifier gain K_amp [A/V].
    torque_constant : float
        Motor torque constant K_t [N m/A].
    lead : float
        Screw lead [mm/rev]; the transmission gain is r_g = lead / (2 pi) [mm/rad].
    gear_ratio : float
        Screw revolutions per motor revolution n [-] (1 for a direct coupling).

    Notes
    -----
    The axis obeys ``J theta'' + B theta' = K_amp K_t (u - d)`` with ``x = r_g n theta``, i.e.
    ``x'' = (K/J) (u - d) - (B/J) x'`` with ``K = K_amp K_t r_g n`` [N m mm/(V rad)], the gain of
    Sec. 3.2 of the thesis; ``d`` is the disturbance expressed as control signal [V].
    """

    inertia: float
    viscous: float
    amplifier_gain: float
    torque_constant: float
    lead: float
    gear_ratio: float = 1.0

    UNITS: ClassVar[dict[str, str]] = {
        "inertia": "kg m^2",
        "viscous": "N m s/rad",
        "amplifier_gain": "A/V",
        "torque_constant": "N m/A",
        "lead": "mm/rev",
        "gear_ratio": "-",
    }
    TABLE: ClassVar[str] = "ballscrew"

    def __post_init__(self) -> None:
        self._positive("inertia", "amplifier_gain", "torque_constant", "lead", "gear_ratio")
        self._nonnegative("viscous")

    @property
    def transmission(self) -> float:
        """r_g n: table travel per motor radian [mm/rad]."""
        return self.lead / (2.0 * math.pi) * self.gear_ratio

    @property
    def K(self) -> float:  # noqa: N802 - the thesis' symbol
        """K = K_amp K_t r_g n [N m mm/(V rad)] (Sec. 3.2 of the thesis)."""
        return self.amplifier_gain * self.torque_constant * self.transmission

    @property
    def gain(self) -> float:
        """K/J: table acceleration per volt [mm/(V s^2)]."""
        return self.K / self.inertia

    @property
    def viscous_rate(self) -> float:
        """B/J [1/s]."""
        return self.viscous / self.inertia

    @property
    def force_per_volt(self) -> float:
        """Force at the table per volt of control signal [N/V] (converts friction and loads)."""
        return self.amplifier_gain * self.torque_constant / (self.transmission * 1e-3)

    @property
    def equivalent_mass(self) -> float:
        """J reflected to the table [kg]."""
        return self.inertia / (self.transmission * 1e-3) ** 2

    def transfer_function(self) -> control.TransferFunction:
        """Open-loop plant x(s)/u(s) = (K/J) / (s (s + B/J)) [mm/V]."""
        import control
        return control.tf([self.gain], [1.0, self.viscous_rate, 0.0])
