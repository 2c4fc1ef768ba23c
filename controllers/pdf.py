"""Pseudo-derivative-feedback control with integer parameters and scale gains (seed 004)."""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar

import numpy as np

from controllers._base import N_PARAMS, Controller, DiscreteLaw

__all__ = ["PDF"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class PDF(Controller):
    """PDF law of an integer-processor servo (Liu, Lai, Yen, IJMTM 48 (2008), Fig. 5).

    Parameters
    ----------
    p1, p2 : int
        Integer parameters set in the controller (19 and 260 on the Chevalier FGP-608LM).
    k1, k2 : float
        Unknown scale gains relating them to the actual law (identified: 6.942e-2, 2.359e-4).
    position_unit : float
        The position unit of the controller [mm] (1000: the published gains act on metres).

    Notes
    -----
    ``C1(z) = p1 T k1 / (1 - z^-1)`` on the error and ``C2 = p2 k2`` on the feedback (Eq. (8) of
    seed 004)::

        u(k) = u1(k) - p2 k2 y(k),   u1(k) = u1(k-1) + p1 T k1 e(k)

    Feedback enters with a minus sign: with the sign of Eq. (9) as printed the loop on the printed
    plant P*(z) is unstable (poles at 1.23 and 1.005); with negative feedback its poles are at
    0.994 and 0.983 (168 Hz, zeta 0.065) for T = 250 us. At the actuator limit u1 stops
    accumulating (``anti_windup``, ours: seed 004 does not treat the limit; see
    :class:`controllers.Controller`). The printed plant P*(z) has a pole at z = 1.040, outside the
    unit circle: a limit below what a move demands loses the table with or without anti-windup.
    """

    p1: int
    p2: int
    k1: float
    k2: float
    position_unit: float = 1.0

    KIND: ClassVar[int] = 4
    CONTINUOUS: ClassVar[bool] = False
    TABLE: ClassVar[str] = "pdf"
    UNITS: ClassVar[dict[str, str]] = {
        **Controller.UNITS, "p1": "-", "p2": "-", "k1": "-", "k2": "-", "position_unit": "mm"}

    def __post_init__(self) -> None:
        super().__post_init__()
        self._integer("p1", 0, 2**31 - 1)
        self._integer("p2", 0, 2**31 - 1)
        self._positive("k1", "position_unit")
        self._nonnegative("k2")

    def gains(self, sample_time: float) -> tuple[float, float]:
        """(c1, c2): C1 = c1/(1 - z^-1) [V/mm], C2 = c2 [V/mm] in vcnc units."""
        return (
            self.p1 * sample_time * self.k1 / self.position_unit,
            self.p2 * self.k2 / self.position_unit,
        )

    def pack(self, drive: Any, sample_time: float) -> np.ndarray:
        p = np.zeros(N_PARAMS)
        p[:2] = self.gains(sample_time)
        return p

    def discrete_law(self, drive: Any, sample_time: float) -> DiscreteLaw:
        import control
        c1, c2 = self.gains(sample_time)
        ci = control.tf([c1, 0.0], [1.0, -1.0], sample_time)
        return DiscreteLaw(ci, 0.0, 0.0, ci + c2, sample_time)
