"""The protocol every servo law follows, and the closed-loop algebra they share."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from drives._record import Record
from vcnc.core.errors import MachineError

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["Controller", "DiscreteLaw", "VELOCITY_FILTERS", "velocity_estimator", "plant_zoh", "N_PARAMS"]

#: length of the parameter vector every controller packs for the compiled kernel
N_PARAMS = 24

#: how a controller estimates velocity from the sampled position:
#: "difference" (y_k - y_{k-1})/Ts, or "fir2" (y_k - y_{k-2})/(2 Ts), the EMPS filter
VELOCITY_FILTERS = ("difference", "fir2")


def velocity_estimator(kind: str, sample_time: float) -> control.TransferFunction:
    """Discrete velocity estimator V(z) [1/s] of a velocity filter name."""
    import control
    ts = sample_time
    if kind == "fir2":
        return control.tf([1.0, 0.0, -1.0], [2.0 * ts, 0.0, 0.0], ts)
    return control.tf([1.0, -1.0], [ts, 0.0], ts)


def plant_zoh(drive: Any, sample_time: float, *,
              structure: control.TransferFunction | None = None) -> control.TransferFunction:
    """The drive's rigid plant x/u [mm/V] seen through a zero-order hold at ``sample_time``; times ``structure``
    (continuous, [-]: the measured position over the rigid body's, a structural mode's
    :meth:`drives.StructuralMode.share`) before the hold when given."""
    import control
    tf = drive.transfer_function()
    if structure is not None:
        tf = tf * structure
    if tf.isdtime():
        if not math.isclose(tf.dt, sample_time, rel_tol=1e-9):
            raise MachineError(
                f"discrete plant sample_time {tf.dt} s differs from the machine sample_time {sample_time} s"
            )
        return tf
    return control.c2d(tf, sample_time, method="zoh")


class DiscreteLaw:
    """The linear part of a sampled control law as discrete transfer functions.

    ``u = C_r(z) r + C_v(z) v_r + C_a(z) a_r - C_y(z) y`` with r the (pre-filtered) commanded
    position [mm], v_r, a_r the commanded velocity [mm/s] and acceleration [mm/s^2], y the measured
    position [mm] and u the control signal [V].
    """

    def __init__(self, c_r: Any, c_v: Any, c_a: Any, c_y: Any, sample_time: float) -> None:
        import control
        ts = sample_time

        def as_tf(c: Any) -> control.TransferFunction:
            if isinstance(c, (int, float)):
                return control.tf([float(c)], [1.0], ts)
            return control.tf(c) if isinstance(c, control.StateSpace) else c

        self.c_r, self.c_v, self.c_a, self.c_y = (as_tf(c) for c in (c_r, c_v, c_a, c_y))
        self.sample_time = ts


@dataclasses.dataclass(frozen=True, kw_only=True)
class Controller(Record):
    """Protocol of the servo laws (the base of frozen keyword-only dataclasses).

    A controller only holds parameters. It tells the compiled kernel its law through ``KIND`` and
    :meth:`pack`, filters the reference where it has a feedforward filter (:meth:`prefilter`),
    gives its sampled linear law (:meth:`discrete_law`) and, for the continuous laws, the reduced
    parameters of Eq. (3.3) of the thesis (:meth:`reduced_parameters`) and the closed loop of
    Eq. (3.1) (:meth:`closed_loop`).

    Parameters
    ----------
    anti_windup : bool
        The law knows its actuator's limit (the amplifier limit or the DAC range, whichever is
        lower: ``AxisDefinition.actuator_limit``) and keeps its states from winding up while its
        demand is beyond it, as real servo controls do (default). ``False`` runs the bare law of
        the thesis and the papers, whose states integrate on whatever the actuator did, for a study
        of windup. A loop that never demands more than the limit runs identically either way.

    Notes
    -----
    Anti-windup, per law (compiled in :mod:`vcnc.engine.kernel`; the law's own output is limited,
    so the computational delay and the DAC quantisation after it do not enter):

    - PID integral, P-PI velocity-loop integral, PDF sum u1 and the sliding-mode law's adapted
      disturbance d_hat: conditional integration. The state does not take the step of a sample
      whose demand u (with the step, feedforward and friction compensation included) lies beyond
      the limit when the step pushes u further out; it integrates again as soon as the demand is
      back within the limit or the step points back. Source: K. J. Astrom, L. Rundqwist,
      "Integrator windup and how to avoid it", ACC 1989, pp. 1693-1698 (conditional integration
      and tracking; https://cse.lab.imtlucca.it/~bemporad/teaching/controllodigitale/pdf/Astrom-ACC89.pdf),
      K. J. Astrom, R. M. Murray, "Feedback Systems", Sec. 10.4 (1st ed.) "Integrator windup".
      Ours: the choice of conditional integration over back-calculation (no tracking time constant
      to choose, and no change while the demand is within the limit); its use on the sliding-mode
      adaptation (freezing an adaptive law while the input saturates is the usual remedy; the
      paper of Altintas, Erkorkmaz and Zhu (2000) does not treat the limit) and on the integer
      PDF's sum (seed 004 does not treat the limit either).
    - Pole placement + Kalman filter: the current estimator is fed the control the actuator
      passes, clip(u, -limit, limit), instead of the demand (Astrom, Rundqwist 1989: an observer
      driven by the actual actuator output gives a state-feedback law its anti-windup).
      Ours: the estimator model keeps the design's zero delay (the same sample's u, as the
      design of :func:`controllers.pole_placement.design_pole_placement` assumes) and the DAC
      quantisation is not fed back; both change nothing while the demand is within the limit.

    The thesis (Assumption 2 of Sec. 3.2) avoids saturation altogether: none of the seeds says
    how its laws behave at the limit. The papers' and book's texts were not in the searchable corpus:
    they are cited from memory of the published works (our reading).
    """

    anti_windup: bool = True

    UNITS: ClassVar[dict[str, str]] = {"anti_windup": ""}

    #: law code in the compiled kernel
    KIND: ClassVar[int] = -1
    #: True when the law is designed in continuous time (Eq. 3.3 applies exactly)
    CONTINUOUS: ClassVar[bool] = True

    def __post_init__(self) -> None:
        self._boolean("anti_windup")

    def pack(self, drive: Any, sample_time: float) -> np.ndarray:  # pragma: no cover - abstract
        """Parameter vector (length ``N_PARAMS``) of the compiled law."""
        raise NotImplementedError

    def preview(self, drive: Any, sample_time: float) -> int:
        """Future reference samples the law needs (0 unless a ZPETC is present)."""
        return 0

    def prefilter(self, reference: np.ndarray, drive: Any, sample_time: float) -> np.ndarray:
        """Reference actually fed to the loop [mm] (identity unless a feedforward filter)."""
        return reference

    def discrete_law(self, drive: Any, sample_time: float) -> DiscreteLaw:  # pragma: no cover - abstract
        raise NotImplementedError

    # ------------------------------------------------------------------ closed loop
    def reduced_parameters(self, drive: Any, *, coulomb: tuple[float, float] = (0.0, 0.0)) -> dict[str, float]:
        """Parameters a1..d1 of Eq. (3.3) for this law on the rigid ``drive``.

        ``coulomb`` = (d+, d-) is the Coulomb friction as control signal [V] (d- negative). Laws
        designed in discrete time raise :class:`MachineError`.
        """
        raise MachineError(
            f"{type(self).__name__} is a discrete-time law; Eq. (3.3) has no exact parameters for it "
            f"(use closed_loop(), a discrete transfer function)"
        )

    def closed_loop(
        self, drive: Any, *, sample_time: float | None = None
    ) -> tuple[control.TransferFunction, control.TransferFunction]:
        """(G_track, G_dist) of Eq. (3.1) [mm/mm, mm/V].

        Continuous laws give continuous transfer functions from the reduced parameters; discrete
        laws (which need ``sample_time``) give discrete ones with ``dt = sample_time``.
        """
        if self.CONTINUOUS:
            p = self.reduced_parameters(drive)
            return continuous_closed_loop(p, drive.gain)
        if sample_time is None:
            raise MachineError(f"{type(self).__name__}.closed_loop needs the sample_time [s]")
        return discrete_closed_loop(self, drive, sample_time)


def continuous_closed_loop(p: dict[str, float], gain: float) -> tuple[control.TransferFunction, ...]:
    """G_track and G_dist of Eq. (3.1) from a1..b2 and K/J [mm/(V s^2)].

    Multiplying Eq. (3.1) by s: ``G_track = (b0 s^3 + b1 s^2 + b2 s + a3)/(s^3 + a1 s^2 + a2 s + a3)``
    and ``G_dist = (K/J) s/(s^3 + a1 s^2 + a2 s + a3)``; without integral action (a3 = 0) the
    common factor s is cancelled.
    """
    import control
    a1, a2, a3, b0, b1, b2 = (p[k] for k in ("a1", "a2", "a3", "b0", "b1", "b2"))
    if a3 == 0.0:
        return control.tf([b0, b1, b2], [1.0, a1, a2]), control.tf([gain], [1.0, a1, a2])
    den = [1.0, a1, a2, a3]
    return control.tf([b0, b1, b2, a3], den), control.tf([gain, 0.0], den)


def discrete_closed_loop(
    controller: Controller, drive: Any, sample_time: float, *, delay: int = 0, velocity_input: bool = False,
    structure: control.TransferFunction | None = None,
) -> tuple[control.TransferFunction, control.TransferFunction]:
    """The sampled loop: controller law, ZOH plant and ``delay`` samples of computation delay.

    Returns ``(G_track, G_dist)``: x/r (reference pre-filter included, delayed by the preview so it
    stays causal) and x/d [mm/V] with d an input disturbance [V]. With ``velocity_input`` the
    feedforward paths are ignored (they need v_r, a_r, not r). ``structure`` multiplies the plant
    (:func:`plant_zoh`: a structural mode as the feedback sees it); the law is the one the controller
    builds from the drive's parameters.
    """
    import control
    law = controller.discrete_law(drive, sample_time)
    p = plant_zoh(drive, sample_time, structure=structure)
    if delay:
        p = p * control.tf([1.0], [1.0] + [0.0] * delay, sample_time)
    loop = control.feedback(p, law.c_y)
    g_track = control.minreal(loop * law.c_r, verbose=False)
    g_dist = control.minreal(loop, verbose=False)
    f = getattr(controller, "prefilter_tf", None)
    if f is not None:
        g_track = control.minreal(f(drive, sample_time) * g_track, verbose=False)
    return g_track, g_dist


def frequency_response(
    controller: Controller, drive: Any, sample_time: float, freqs_hz: np.ndarray, *, delay: int = 0
) -> np.ndarray:
    """x/r of the sampled loop at ``freqs_hz`` for a sinusoidal reference with exact
    feedforward signals (v_r = j w r, a_r = -w^2 r); the preview of a ZPETC is undone, so the
    result is the response to the reference as commanded."""
    law = controller.discrete_law(drive, sample_time)
    p = plant_zoh(drive, sample_time)
    w = 2 * np.pi * np.asarray(freqs_hz, dtype=float)
    z = np.exp(1j * w * sample_time)

    def ev(tf: control.TransferFunction) -> np.ndarray:
        return np.asarray(tf(z)).reshape(-1)

    pz = ev(p) * z ** (-delay)
    cr = ev(law.c_r) + 1j * w * ev(law.c_v) - w**2 * ev(law.c_a)
    g = pz * cr / (1.0 + pz * ev(law.c_y))
    f = getattr(controller, "prefilter_tf", None)
    if f is not None:
        g = g * ev(f(drive, sample_time)) * z ** controller.preview(drive, sample_time)
    return g
