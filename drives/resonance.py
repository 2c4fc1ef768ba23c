"""A lightly damped structural mode (two-mass axial or torsional model)."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, ClassVar

from drives._record import Record

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

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

    def share(self, feedback: str = "motor") -> control.TransferFunction:
        """The position the loop measures over the rigid body's for the same force, x_fb / x_rigid [-]
        (continuous): the motor side's for ``feedback="motor"`` (a rotary encoder),
        ``(s^2 / (1 - r) + 2 zeta omega s + omega^2) / (s^2 + 2 zeta omega s + omega^2)``, with the
        anti-resonance omega sqrt(1 - r) in its numerator; the table's for ``"table"`` (a linear scale),
        ``(2 zeta omega s + omega^2) / (s^2 + 2 zeta omega s + omega^2)``.

        Notes
        -----
        From the two masses of the class notes, the force on m1 and without viscous damping:
        ``m1 s^2 x1 = F - (c s + k)(x1 - x2)``, ``m2 s^2 x2 = (c s + k)(x1 - x2)`` and ``x_rigid = F / (m s^2)``.
        Multiplied into a rigid plant ``x/u``, the plant's viscous term stays on the whole mass (in the
        simulation it acts on the table mass): our approximation for the sampled loop's stability
        (:meth:`vcnc.engine.axis.AxisDefinition.sampled_loop`).
        """
        import control

        if feedback not in ("motor", "table"):
            raise ValueError(f"feedback must be 'motor' or 'table' (got {feedback!r})")
        w, z, r = self.omega, self.damping, self.load_fraction
        den = [1.0, 2.0 * z * w, w * w]
        num = [1.0 / (1.0 - r), 2.0 * z * w, w * w] if feedback == "motor" else [2.0 * z * w, w * w]
        return control.tf(num, den)
