"""PID position control with velocity, acceleration and friction feedforward (Fig. 3.2b)."""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar

import numpy as np

from controllers._base import Controller, DiscreteLaw
from controllers._feedforward import (
    FF_UNITS,
    common_checks,
    coulomb_after_feedforward,
    derivative,
    integrator,
    pack_law,
)

__all__ = ["PID"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class PID(Controller):
    """PID on the position error plus feedforward.

    Parameters
    ----------
    kp : float
        Proportional gain K_p [V/mm] (0 with ki = kd = 0: open loop, feedforward only).
    ki : float
        Integral gain K_i [V/(mm s)].
    kd : float
        Derivative gain K_d [V s/mm].
    kv : float
        Velocity feedforward K_v [V s/mm].
    ka : float
        Acceleration feedforward K_a [V s^2/mm].
    friction_feedforward_positive, friction_feedforward_negative : float
        Coulomb friction compensation added while the commanded velocity is + / - [V]
        (magnitudes).
    velocity_filter : str
        How the error derivative is formed: "difference" or "fir2".

    Notes
    -----
    ``u = K_p e + K_i int(e) + K_d de/dt + K_v v_r + K_a a_r (+ friction feedforward)``, e = x_r - x.
    On the rigid drive ``x'' = (K/J)(u - d) - (B/J) x'`` this gives Eq. (3.5) of the thesis:
    a1 = (B + K K_d)/J, a2 = K K_p/J, a3 = K K_i/J, b0 = K K_a/J, b1 = K (K_d + K_v)/J, b2 = a2,
    d0 = (K/J) d+, d1 = (K/J) d-. Sampled: rectangular integral, backward-difference derivative.
    At the actuator limit the integral stops (conditional integration, ``anti_windup``: see
    :class:`controllers.Controller`).
    """

    kp: float
    ki: float = 0.0
    kd: float = 0.0
    kv: float = 0.0
    ka: float = 0.0
    friction_feedforward_positive: float = 0.0
    friction_feedforward_negative: float = 0.0
    velocity_filter: str = "difference"

    KIND: ClassVar[int] = 0
    TABLE: ClassVar[str] = "pid"
    UNITS: ClassVar[dict[str, str]] = {
        **Controller.UNITS,
        "kp": "V/mm",
        "ki": "V/(mm s)",
        "kd": "V s/mm",
        "kv": "V s/mm",
        "ka": "V s^2/mm",
        **FF_UNITS,
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        self._nonnegative("kp", "ki", "kd")
        self._finite("kv", "ka")
        common_checks(self)

    def pack(self, drive: Any, sample_time: float) -> np.ndarray:
        return pack_law(self, (self.kp, self.ki, self.kd, self.kv, self.ka))

    def reduced_parameters(self, drive: Any, *, coulomb: tuple[float, float] = (0.0, 0.0)) -> dict[str, float]:
        """Eq. (3.5) of the thesis."""
        g, beta = drive.gain, drive.viscous_rate
        dp, dn = coulomb_after_feedforward(self, coulomb)
        return {
            "a1": beta + g * self.kd,
            "a2": g * self.kp,
            "a3": g * self.ki,
            "b0": g * self.ka,
            "b1": g * (self.kd + self.kv),
            "b2": g * self.kp,
            "d0": g * dp,
            "d1": g * dn,
        }

    def discrete_law(self, drive: Any, sample_time: float) -> DiscreteLaw:
        c_e = self.kp + self.ki * integrator(sample_time) + self.kd * derivative(self.velocity_filter, sample_time)
        return DiscreteLaw(c_e, self.kv, self.ka, c_e, sample_time)
