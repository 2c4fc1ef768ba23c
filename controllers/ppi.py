"""P-PI cascade: P position loop around a PI velocity loop, with feedforward (Fig. 3.2a)."""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar

import numpy as np

from controllers._base import Controller, DiscreteLaw, velocity_estimator
from controllers._feedforward import FF_UNITS, common_checks, coulomb_after_feedforward, integrator, pack_law

__all__ = ["PPI"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class PPI(Controller):
    """P-PI cascade control in the notation of Eq. (3.4) of the thesis.

    Parameters
    ----------
    kp : float
        Position-loop gain K_p [1/s].
    kd : float
        Velocity-loop proportional gain K_d [V s/mm].
    ki : float
        Velocity-loop integral gain K_i [V/mm] (0: P-P cascade, as the EMPS bench).
    kv : float
        Velocity feedforward K_v [s] (1/K_p for full velocity feedforward).
    ka : float
        Acceleration feedforward K_a [s^2].
    friction_feedforward_positive, friction_feedforward_negative : float
        Coulomb friction compensation by sign of the commanded velocity [V].
    velocity_filter : str
        Velocity estimate of the inner loop: "difference" or "fir2" (EMPS).

    Notes
    -----
    ``v_c = K_p (e + K_v v_r + K_a a_r)``, ``u = (K_d + K_i/s)(v_c - x')``. On the rigid drive this
    gives Eq. (3.4): a1 = (B + K K_d)/J, a2 = K (K_d K_p + K_i)/J, a3 = K K_p K_i/J,
    b0 = K K_p K_d K_a/J, b1 = K K_p (K_d K_v + K_a K_i)/J, b2 = K K_p (K_d + K_v K_i)/J,
    d0 = (K/J) d+, d1 = (K/J) d-. The EMPS law ``v = k_v (k_p (q_r - q) - q')`` is the case K_i = 0.
    At the actuator limit the velocity loop's integral stops (conditional integration,
    ``anti_windup``: see :class:`controllers.Controller`); with K_i = 0 nothing winds up.
    """

    kp: float
    kd: float
    ki: float = 0.0
    kv: float = 0.0
    ka: float = 0.0
    friction_feedforward_positive: float = 0.0
    friction_feedforward_negative: float = 0.0
    velocity_filter: str = "difference"

    KIND: ClassVar[int] = 1
    TABLE: ClassVar[str] = "ppi"
    UNITS: ClassVar[dict[str, str]] = {
        **Controller.UNITS,
        "kp": "1/s",
        "kd": "V s/mm",
        "ki": "V/mm",
        "kv": "s",
        "ka": "s^2",
        **FF_UNITS,
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        self._positive("kp", "kd")
        self._nonnegative("ki")
        self._finite("kv", "ka")
        common_checks(self)

    def pack(self, drive: Any, sample_time: float) -> np.ndarray:
        return pack_law(self, (self.kp, self.ki, self.kd, self.kv, self.ka))

    def reduced_parameters(self, drive: Any, *, coulomb: tuple[float, float] = (0.0, 0.0)) -> dict[str, float]:
        """Eq. (3.4) of the thesis."""
        g, beta = drive.gain, drive.viscous_rate
        kp, kd, ki, kv, ka = self.kp, self.kd, self.ki, self.kv, self.ka
        dp, dn = coulomb_after_feedforward(self, coulomb)
        return {
            "a1": beta + g * kd,
            "a2": g * (kd * kp + ki),
            "a3": g * kp * ki,
            "b0": g * kp * kd * ka,
            "b1": g * kp * (kd * kv + ka * ki),
            "b2": g * kp * (kd + kv * ki),
            "d0": g * dp,
            "d1": g * dn,
        }

    def discrete_law(self, drive: Any, sample_time: float) -> DiscreteLaw:
        pi = self.kd + self.ki * integrator(sample_time)
        v = velocity_estimator(self.velocity_filter, sample_time)
        kp = self.kp
        return DiscreteLaw(pi * kp, pi * (kp * self.kv), pi * (kp * self.ka), pi * (v + kp), sample_time)
