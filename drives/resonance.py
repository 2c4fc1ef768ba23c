"""A lightly damped structural mode (two-mass axial or torsional model)."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

from drives._record import Record

__all__ = ["StructuralMode"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class StructuralMode(Record):
    """Two-mass model: motor side and table joined by a spring and a damper.

    Parameters
    ----------
    frequency_hz : float
        Free-free natural frequency of the mode [Hz] (the resonance seen with the motor free).
    damping : float
        Modal damping ratio [-], e.g. 0.02-0.1 for an axial ball-screw mode.
    load_fraction : float
        Share of the drive's inertia on the table side [-], in (0, 1).

    Notes
    -----
    With total reflected mass m = 1/(K/J) [V s^2/mm], m1 = (1 - r) m and m2 = r m, the spring
    is ``k = omega^2 m1 m2 / m`` and the damper ``c = 2 zeta omega m1 m2 / m``. Friction, viscous
    damping and loads act on the table mass. A motor encoder sees the anti-resonance, a linear
    scale the collocated mode.
    """

    frequency_hz: float
    damping: float = 0.05
    load_fraction: float = 0.5

    UNITS: ClassVar[dict[str, str]] = {"frequency_hz": "Hz", "damping": "-", "load_fraction": "-"}
    TABLE: ClassVar[str] = "resonance"

    def __post_init__(self) -> None:
        self._positive("frequency_hz")
        self._in_range("damping", 0.0, 1.0)
        v = self._number("load_fraction")
        if not 0.0 < v < 1.0:
            raise self._fail("load_fraction", "must lie strictly between 0 and 1")

    @property
    def omega(self) -> float:
        """Natural frequency [rad/s]."""
        return 2.0 * math.pi * self.frequency_hz
