"""Adaptive sliding-mode control (Altintas, Erkorkmaz, Zhu, CIRP Annals 49(1), 2000)."""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar

import numpy as np

from controllers._base import Controller, DiscreteLaw, velocity_estimator
from controllers._feedforward import FF_UNITS, common_checks, coulomb_after_feedforward, integrator, pack_law

__all__ = ["SlidingMode"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class SlidingMode(Controller):
    """Sliding-mode control with model-based feedforward and an adapted disturbance.

    Parameters
    ----------
    lam : float
        Sliding-surface bandwidth lambda [1/s].
    ks : float
        Feedback gain on the sliding surface K_s [V s/mm].
    rho : float
        Disturbance adaptation gain rho [V/mm]: d_hat' = rho S.
    mass_estimate : float, optional
        m_hat = J_hat/K [V s^2/mm]; default the drive's true J/K.
    viscous_estimate : float, optional
        c_hat = B_hat/K [V s/mm]; default the drive's true B/K.
    friction_feedforward_positive, friction_feedforward_negative : float
        Extra Coulomb compensation by sign of the commanded velocity [V].
    velocity_filter : str
        Velocity estimate: "difference" or "fir2".

    Notes
    -----
    The law implemented (the disturbance-only adaptive form used for Table 3.5 of the thesis)::

        e = x_r - x,  S = lambda e + de/dt
        u = m_hat (a_r + lambda de/dt) + c_hat x' + K_s S + d_hat,   d_hat = rho int(S) dt

    With exact estimates the plant ``m x'' + c x' = u - d`` gives ``m S' + K_s S + rho int(S) = d``,
    so the closed loop factorises as (s + lambda)(m s^2 + K_s s + rho) and Eq. (3.3) has
    a1 = lambda + K K_s/J + (B - B_hat)/J, a2 = K (K_s lambda + rho)/J, a3 = K rho lambda/J,
    b0 = J_hat/J, b1 = lambda J_hat/J + K K_s/J, b2 = a2, d0 = (K/J) d+, d1 = (K/J) d-:
    G_track = 1 with exact estimates (Table 3.5). Adapting m_hat and c_hat as well (the full law
    of the paper) is not implemented. At the actuator limit the adaptation of d_hat stops (``anti_windup``,
    ours: the paper does not treat the limit; see :class:`controllers.Controller`).
    """

    lam: float
    ks: float
    rho: float
    mass_estimate: float | None = None
    viscous_estimate: float | None = None
    friction_feedforward_positive: float = 0.0
    friction_feedforward_negative: float = 0.0
    velocity_filter: str = "difference"

    KIND: ClassVar[int] = 2
    TABLE: ClassVar[str] = "smc"
    UNITS: ClassVar[dict[str, str]] = {
        **Controller.UNITS,
        "lam": "1/s",
        "ks": "V s/mm",
        "rho": "V/mm",
        "mass_estimate": "V s^2/mm",
        "viscous_estimate": "V s/mm",
        **FF_UNITS,
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        self._positive("lam", "ks")
        self._nonnegative("rho")
        if self.mass_estimate is not None:
            self._positive("mass_estimate")
        if self.viscous_estimate is not None:
            self._nonnegative("viscous_estimate")
        common_checks(self)

    def estimates(self, drive: Any) -> tuple[float, float]:
        """(m_hat, c_hat) [V s^2/mm, V s/mm], the drive's true values where not given."""
        m = 1.0 / drive.gain if self.mass_estimate is None else self.mass_estimate
        c = drive.viscous_rate / drive.gain if self.viscous_estimate is None else self.viscous_estimate
        return m, c

    def pack(self, drive: Any, sample_time: float) -> np.ndarray:
        m, c = self.estimates(drive)
        return pack_law(self, (self.lam, self.ks, self.rho, m, c))

    def reduced_parameters(self, drive: Any, *, coulomb: tuple[float, float] = (0.0, 0.0)) -> dict[str, float]:
        g, beta = drive.gain, drive.viscous_rate
        m, c = self.estimates(drive)
        lam, ks, rho = self.lam, self.ks, self.rho
        dp, dn = coulomb_after_feedforward(self, coulomb)
        return {
            "a1": beta - g * c + g * m * lam + g * ks,
            "a2": g * (ks * lam + rho),
            "a3": g * rho * lam,
            "b0": g * m,
            "b1": g * m * lam + g * ks,
            "b2": g * (ks * lam + rho),
            "d0": g * dp,
            "d1": g * dn,
        }

    def discrete_law(self, drive: Any, sample_time: float) -> DiscreteLaw:
        m, c = self.estimates(drive)
        v = velocity_estimator(self.velocity_filter, sample_time)
        w = self.ks + self.rho * integrator(sample_time)
        c_y = (m * self.lam - c) * v + w * (v + self.lam)
        return DiscreteLaw(w * self.lam, w + m * self.lam, m, c_y, sample_time)
