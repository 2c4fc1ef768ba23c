"""Pole-placement control with a Kalman-filter disturbance observer, optionally with ZPETC.

Sec. 3.4.2 of the thesis (Fig. 3.13): the single-axis ball-screw bench, Ts = 1 ms, closed-loop
poles at 30 Hz / zeta 0.7 (z = 0.86846 +/- j0.11762), ZPETC with a two-sample preview.
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from controllers._base import N_PARAMS, Controller, DiscreteLaw
from controllers.zpetc import ZPETC, design_zpetc
from vcnc.core.errors import MachineError

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["PolePlacement", "design_pole_placement", "PolePlacementDesign"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class PolePlacementDesign:
    """Result of :func:`design_pole_placement` (discrete, at the sample time).

    Attributes
    ----------
    phi, gamma : ndarray
        Augmented model x_{k+1} = phi x_k + gamma u_k, state (position [mm], velocity [mm/s],
        input disturbance [V]).
    feedback : ndarray, shape (3,)
        u = L_x (r - x_hat) - L_v v_hat + d_hat: ``(L_x [V/mm], L_v [V s/mm], -1 or 0)``.
    observer_gain : ndarray, shape (3,)
        Steady-state Kalman gain M of the current estimator.
    poles : ndarray
        Closed-loop poles placed [z].
    observer_poles : ndarray
        Poles of the estimator (I - M H) phi [z].
    """

    phi: np.ndarray
    gamma: np.ndarray
    feedback: np.ndarray
    observer_gain: np.ndarray
    poles: np.ndarray
    observer_poles: np.ndarray


def design_pole_placement(
    gain: float,
    viscous_rate: float,
    sample_time: float,
    *,
    frequency_hz: float,
    damping: float,
    measurement_std: float,
    velocity_std: float,
    disturbance_std: float,
    cancel: bool = True,
) -> PolePlacementDesign:
    """Place the poles of the ZOH rigid plant and design the steady-state Kalman filter.

    Parameters
    ----------
    gain, viscous_rate : float
        Design model K/J [mm/(V s^2)] and B/J [1/s].
    sample_time : float
        Ts [s].
    frequency_hz, damping : float
        Closed-loop pole pair: z = exp(s Ts), s = -zeta w_n +/- j w_n sqrt(1 - zeta^2).
    measurement_std : float
        Position measurement noise [mm] (an encoder count / sqrt(12) for quantisation).
    velocity_std, disturbance_std : float
        Process noise per sample on velocity [mm/s] and on the disturbance [V].
    """
    import control
    import scipy.linalg
    ts = sample_time
    # canonical physical coordinates: exact ZOH of [x, v]
    a = np.array([[0.0, 1.0], [0.0, -viscous_rate]])
    b = np.array([[0.0], [gain]])
    m = scipy.linalg.expm(np.block([[a, b], [np.zeros((1, 3))]]) * ts)
    phi2, gam2 = m[:2, :2], m[:2, 2]
    wn = 2 * math.pi * frequency_hz
    s = complex(-damping * wn, wn * math.sqrt(max(1.0 - damping**2, 0.0)))
    z = np.exp(s * ts)
    poles = np.array([z, np.conj(z)])
    lfb = control.place(phi2, gam2[:, None], poles).ravel()
    phi = np.zeros((3, 3))
    phi[:2, :2] = phi2
    phi[:2, 2] = -gam2
    phi[2, 2] = 1.0
    gamma = np.array([gam2[0], gam2[1], 0.0])
    h = np.array([[1.0, 0.0, 0.0]])
    q = np.diag([1e-30, velocity_std**2, disturbance_std**2])
    r = np.array([[measurement_std**2]])
    p = scipy.linalg.solve_discrete_are(phi.T, h.T, q, r)
    mgain = (p @ h.T / (h @ p @ h.T + r)).ravel()
    obs = np.linalg.eigvals((np.eye(3) - np.outer(mgain, h)) @ phi)
    feedback = np.array([lfb[0], lfb[1], -1.0 if cancel else 0.0])
    return PolePlacementDesign(
        phi=phi, gamma=gamma, feedback=feedback, observer_gain=mgain, poles=poles, observer_poles=obs
    )


@dataclasses.dataclass(frozen=True, kw_only=True)
class PolePlacement(Controller):
    """PPC + Kalman-filter disturbance observer and cancellation (+ optional ZPETC).

    Parameters
    ----------
    frequency_hz : float
        Natural frequency of the placed closed-loop pole pair [Hz] (30 in Sec. 3.4.2).
    damping : float
        Its damping ratio [-] (0.7).
    measurement_std : float
        Measurement noise assumed by the Kalman filter [mm]; default a 1.25 um count / sqrt(12).
    velocity_std : float
        Process noise on velocity per sample [mm/s].
    disturbance_std : float
        Process noise on the disturbance per sample [V]; sets how fast friction is observed.
    cancel_disturbance : bool
        Add the observed disturbance to the control signal.
    zpetc : bool
        Pre-filter the reference with the ZPETC of the nominal closed loop (Eq. 3.24).
    model_gain, model_viscous_rate : float, optional
        Design model K/J [mm/(V s^2)], B/J [1/s]; default the drive's true values.

    Notes
    -----
    Current estimator on the model x_{k+1} = phi x_k + gamma (u_k - d_k), d_{k+1} = d_k:
    x_bar = phi x_hat_{k-1} + gamma u_{k-1}; x_hat_k = x_bar + M (y_k - x_bar_1);
    u_k = L_x (r*_k - x_hat_1) - L_v x_hat_2 + x_hat_3. The tracking transfer function is
    G(z) = L_x B(z)/A(z) (Eq. 3.23), the estimator poles cancelling; the ZPETC of Eq. (3.24) makes the
    overall x/x_r = B^-(z) B^-(z^-1)/B^-(1)^2 (Eq. 3.25), zero phase, with a preview of
    (relative degree + number of cancelled-out zeros) samples. With ``anti_windup`` the estimator is
    fed u_k clipped to the actuator limit, the control the drive receives (see
    :class:`controllers.Controller`).
    """

    frequency_hz: float = 30.0
    damping: float = 0.7
    measurement_std: float = 1.25e-3 / math.sqrt(12.0)
    velocity_std: float = 1.0
    disturbance_std: float = 0.01
    cancel_disturbance: bool = True
    zpetc: bool = False
    model_gain: float | None = None
    model_viscous_rate: float | None = None

    KIND: ClassVar[int] = 3
    CONTINUOUS: ClassVar[bool] = False
    TABLE: ClassVar[str] = "ppc"
    UNITS: ClassVar[dict[str, str]] = {
        **Controller.UNITS,
        "frequency_hz": "Hz",
        "damping": "-",
        "measurement_std": "mm",
        "velocity_std": "mm/s",
        "disturbance_std": "V",
        "cancel_disturbance": "",
        "zpetc": "",
        "model_gain": "mm/(V s^2)",
        "model_viscous_rate": "1/s",
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        self._positive("frequency_hz", "measurement_std")
        self._in_range("damping", 0.05, 1.0)
        self._nonnegative("velocity_std", "disturbance_std")
        self._boolean("cancel_disturbance", "zpetc")
        if self.model_gain is not None:
            self._positive("model_gain")
        if self.model_viscous_rate is not None:
            self._nonnegative("model_viscous_rate")

    # ------------------------------------------------------------------ design
    def design(self, drive: Any, sample_time: float) -> PolePlacementDesign:
        """The discrete design for ``drive`` at ``sample_time``."""
        if not math.isfinite(getattr(drive, "gain", math.nan)):
            raise MachineError("the pole-placement law needs a rigid drive (ballscrew or linear), not a discrete plant")
        if self.frequency_hz * sample_time >= 0.25:
            raise MachineError(
                f"PolePlacement.frequency_hz [Hz] = {self.frequency_hz} is too high for sample_time {sample_time} s"
            )
        g = drive.gain if self.model_gain is None else self.model_gain
        b = drive.viscous_rate if self.model_viscous_rate is None else self.model_viscous_rate
        return design_pole_placement(
            g,
            b,
            sample_time,
            frequency_hz=self.frequency_hz,
            damping=self.damping,
            measurement_std=self.measurement_std,
            velocity_std=self.velocity_std,
            disturbance_std=self.disturbance_std,
            cancel=self.cancel_disturbance,
        )

    def nominal_loop(self, drive: Any, sample_time: float) -> control.TransferFunction:
        """G(z) = x/r* of the design model with the estimator cancelled: L_x B(z)/A(z) (Eq. 3.23)."""
        import control
        d = self.design(drive, sample_time)
        phi2 = d.phi[:2, :2]
        g2 = d.gamma[:2, None]
        k = d.feedback[:2][None, :]
        sys = control.ss(phi2 - g2 @ k, g2 * d.feedback[0], np.array([[1.0, 0.0]]), 0.0, sample_time)
        return control.tf(sys)

    def zpetc_filter(self, drive: Any, sample_time: float) -> ZPETC:
        return design_zpetc(self.nominal_loop(drive, sample_time))

    def preview(self, drive: Any, sample_time: float) -> int:
        return self.zpetc_filter(drive, sample_time).preview if self.zpetc else 0

    def prefilter(self, reference: np.ndarray, drive: Any, sample_time: float) -> np.ndarray:
        if not self.zpetc:
            return reference
        return self.zpetc_filter(drive, sample_time).apply(reference)

    def prefilter_tf(self, drive: Any, sample_time: float) -> control.TransferFunction | None:
        """The ZPETC as a causal discrete TF (delayed by the preview), or the identity."""
        import control
        if not self.zpetc:
            return control.tf([1.0], [1.0], sample_time)
        return self.zpetc_filter(drive, sample_time).causal_tf(sample_time)

    # ------------------------------------------------------------------ kernel / analysis
    def pack(self, drive: Any, sample_time: float) -> np.ndarray:
        d = self.design(drive, sample_time)
        p = np.zeros(N_PARAMS)
        p[0:3] = d.feedback
        p[3:12] = d.phi.ravel()
        p[12:15] = d.gamma
        p[15:18] = d.observer_gain
        return p

    def discrete_law(self, drive: Any, sample_time: float) -> DiscreteLaw:
        import control
        d = self.design(drive, sample_time)
        h = np.array([[1.0, 0.0, 0.0]])
        imh = np.eye(3) - np.outer(d.observer_gain, h)
        kf = np.array([[d.feedback[0], d.feedback[1], d.feedback[2]]])
        n = d.feedback[0]
        ac = imh @ (d.phi - d.gamma[:, None] @ kf)
        br = imh @ d.gamma[:, None] * n
        mm = d.observer_gain[:, None]
        ts = sample_time
        c_r = control.ss(ac, br, -kf, n, ts)
        c_y = control.ss(ac, mm, kf @ ac, kf @ mm, ts)
        return DiscreteLaw(c_r, 0.0, 0.0, c_y, ts)



