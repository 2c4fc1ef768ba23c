"""Definition of one simulated machine axis: drive, controller, feedback and non-idealities."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

import drives
from controllers._base import Controller, discrete_closed_loop
from interpolators.limits import AxisLimits
from vcnc.core.errors import MachineError
from vcnc.engine import layout as L

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["AxisDefinition", "NONIDEALITY_FIELDS"]

#: fields of AxisDefinition holding optional non-ideality records (None = absent)
NONIDEALITY_FIELDS: tuple[str, ...] = (
    "friction",
    "backlash",
    "encoder",
    "dac",
    "saturation",
    "noise",
    "delay",
    "resonance",
    "position_periodic",
    "load",
    "drift",
)


@dataclasses.dataclass(frozen=True, kw_only=True)
class AxisDefinition:
    """One axis of a :class:`vcnc.engine.machine.Machine`.

    Parameters
    ----------
    name : str
        Axis name (x, y, z, a, b, c).
    drive : BallScrewDrive, LinearMotorDrive or DiscretePlantDrive
        The plant.
    controller : Controller
        The servo law (``controllers``).
    limits : AxisLimits
        Kinematic limits for the interpolator [mm/s, mm/s^2, mm/s^3].
    feedback : str
        "motor": position measured on the motor side (rotary encoder, semi-closed loop);
        "table": measured at the table by a linear scale (closed loop).
    measurement : str
        What a capture's ``measured`` records. "feedback" (default): the signal the loop closes on
        (motor encoder or linear scale, per ``feedback``), with its drift, noise and rounding.
        "table": an independent linear scale (or laser) reading the true table position, with the
        axis' ``noise`` (an independent draw) and ``encoder`` resolution but without the feedback's
        ``drift``; the loop still closes on ``feedback``. With ``feedback = "motor"`` this is a
        semi-closed loop observed by a scale: nut backlash, lead errors and a thermal drift between
        encoder and table become visible in ``measured``.
    substeps : int
        Integration steps per sample for the rigid plant [-]; 1 is exact without a Stribeck
        curve (the solution is analytic between friction events), more resolve the Stribeck curve
        and position-dependent forces better.
    friction, backlash, encoder, dac, saturation, noise, delay, resonance, position_periodic, load, drift
        Optional non-idealities (``drives``); ``None`` leaves the effect out.
    """

    name: str
    drive: Any
    controller: Controller
    limits: AxisLimits
    feedback: str = "motor"
    measurement: str = "feedback"
    substeps: int = 1
    friction: drives.Friction | None = None
    backlash: drives.Backlash | None = None
    encoder: drives.Encoder | None = None
    dac: drives.DAC | None = None
    saturation: drives.Saturation | None = None
    noise: drives.MeasurementNoise | None = None
    delay: drives.ComputationalDelay | None = None
    resonance: drives.StructuralMode | None = None
    position_periodic: drives.PositionPeriodic | None = None
    load: drives.ExternalLoad | None = None
    drift: drives.Drift | None = None

    UNITS: ClassVar[dict[str, str]] = {"feedback": "", "measurement": "", "substeps": "", "name": ""}

    def __post_init__(self) -> None:
        def fail(field: str, message: str) -> MachineError:
            err = MachineError(f"axis {self.name}: {field} {message}")
            err.key = field  # type: ignore[attr-defined]
            return err

        if self.feedback not in ("motor", "table"):
            raise fail("feedback", f"must be 'motor' or 'table' (got {self.feedback!r})")
        if self.measurement not in ("feedback", "table"):
            raise fail("measurement", f"must be 'feedback' or 'table' (got {self.measurement!r})")
        if isinstance(self.substeps, bool) or not isinstance(self.substeps, int) or not 1 <= self.substeps <= 1000:
            raise fail("substeps", f"must be an integer in [1, 1000] (got {self.substeps!r})")
        if not isinstance(self.controller, Controller):
            raise fail("controller", f"must be a controllers.Controller (got {type(self.controller).__name__})")
        if not isinstance(self.drive, (drives.BallScrewDrive, drives.LinearMotorDrive, drives.DiscretePlantDrive)):
            raise fail("drive", f"must be a drives plant (got {type(self.drive).__name__})")
        expected = {f: getattr(drives, cls) for f, cls in _RECORD_CLASSES.items()}
        for f, cls in expected.items():
            v = getattr(self, f)
            if v is not None and not isinstance(v, cls):
                raise fail(f, f"must be a drives.{cls.__name__} (got {type(v).__name__})")
        if self.discrete_plant:
            for f in ("friction", "backlash", "resonance", "position_periodic", "load"):
                if getattr(self, f) is not None:
                    raise fail(f, "needs a physical plant (ballscrew or linear), not a discrete transfer function")
        if self.controller.KIND == 3 and self.discrete_plant:
            raise fail("controller", "ppc needs a physical plant (ballscrew or linear)")

    # ------------------------------------------------------------------ properties
    @property
    def discrete_plant(self) -> bool:
        return isinstance(self.drive, drives.DiscretePlantDrive)

    @property
    def force_per_volt(self) -> float:
        """Force at the table per volt [N/V] (NaN for a discrete plant)."""
        return self.drive.force_per_volt

    def control_limit(self) -> float:
        """Amplifier limit of the control signal [V] (inf without saturation)."""
        if self.saturation is None:
            return math.inf
        return self.saturation.control_limit(getattr(self.drive, "amplifier_gain", 1.0))

    def actuator_limit(self) -> float:
        """Largest control signal the actuator passes [V]: the amplifier limit or the DAC range,
        whichever is lower (inf with neither)."""
        return min(self.control_limit(), self.dac.range if self.dac is not None else math.inf)

    def disturbance_levels(self) -> tuple[float, float]:
        """(d+, d-) of Eq. (3.2) [V]: Coulomb friction plus the constant load, as control signal."""
        fp = fn = 0.0
        if self.friction is not None:
            fp, fn = self.friction.coulomb_positive, -self.friction.coulomb_negative
        if self.load is not None:
            fp += self.load.constant
            fn += self.load.constant
        k = self.force_per_volt
        return fp / k, fn / k

    # ------------------------------------------------------------------ closed loop
    def reduced_parameters(self) -> dict[str, float]:
        """a1, a2, a3, b0, b1, b2, d0, d1 of Eq. (3.3) of the thesis for this axis.

        Units: a1 [1/s], a2 [1/s^2], a3 [1/s^3], b0 [-], b1 [1/s], b2 [1/s^2], d0, d1 [mm/s^2].
        From the linearised rigid loop (Eqs. (3.4), (3.5) and the sliding-mode law) and the Coulomb
        friction plus constant load (d0 = (K/J) d+, d1 = (K/J) d-, Eq. (3.3)). Sampling, delay,
        filters and the other non-idealities are not part of Eq. (3.3). Laws designed in discrete
        time (PPC, PDF) raise :class:`MachineError`; use :meth:`closed_loop`.
        """
        if self.discrete_plant:
            raise MachineError(
                f"axis {self.name}: the plant is a discrete transfer function; Eq. (3.3) has no exact parameters "
                f"for it (use closed_loop())"
            )
        return self.controller.reduced_parameters(self.drive, coulomb=self.disturbance_levels())

    def closed_loop(self, sample_time: float) -> tuple[control.TransferFunction, control.TransferFunction]:
        """(G_track [mm/mm], G_dist [mm/V]) of Eq. (3.1).

        Continuous transfer functions for continuous laws (PID, P-PI, SMC), built from
        :meth:`reduced_parameters`; discrete ones (``dt = sample_time``) for PPC (ZPETC included,
        delayed by its preview to stay causal) and PDF, including the computational delay.
        """
        if self.controller.CONTINUOUS and not self.discrete_plant:
            return self.controller.closed_loop(self.drive)
        d = 0 if self.delay is None else self.delay.samples
        return discrete_closed_loop(self.controller, self.drive, sample_time, delay=d)

    def sampled_loop(self, sample_time: float) -> tuple[control.TransferFunction, control.TransferFunction]:
        """(G_track [mm/mm], G_dist [mm/V]) of the loop as it runs sampled at ``sample_time`` [s], for every law:
        the controller's discrete law, the ZOH plant with the structural mode as the feedback sees it (the motor
        side for a motor encoder, the table for a linear scale: :meth:`drives.StructuralMode.share`) and the
        computational delay (:func:`controllers.discrete_closed_loop`)."""
        d = 0 if self.delay is None else self.delay.samples
        structure = None if self.resonance is None else self.resonance.share(self.feedback)
        return discrete_closed_loop(self.controller, self.drive, sample_time, delay=d, structure=structure)

    # ------------------------------------------------------------------ kernel
    def pack(self, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
        """(plant/options vector, law vector) for :func:`vcnc.engine.kernel.simulate_axis`."""
        p = np.zeros(L.N_TOTAL)
        c = np.asarray(self.controller.pack(self.drive, sample_time), dtype=float)
        p[L.SAMPLE_TIME] = sample_time
        p[L.CTRL_KIND] = self.controller.KIND
        p[L.SUBSTEPS] = self.substeps
        p[L.SAT] = self.control_limit()
        p[L.LAW_LIMIT] = self.actuator_limit() if self.controller.anti_windup else math.inf
        if self.discrete_plant:
            dp = self.drive
            if not math.isclose(dp.sample_time, sample_time, rel_tol=1e-9):
                raise MachineError(
                    f"axis {self.name}: drive.sample_time = {dp.sample_time} s differs from the machine "
                    f"sample_time = {sample_time} s"
                )
            p[L.PLANT_KIND] = 2
            p[L.DPLANT_ORDER] = dp.order
            p[L.DPLANT_SCALE] = dp.output_unit
            p[L.DPLANT_B : L.DPLANT_B + len(dp.numerator)] = dp.numerator
            p[L.DPLANT_A : L.DPLANT_A + dp.order] = dp.denominator
        else:
            k = self.force_per_volt
            p[L.PLANT_KIND] = 1 if self.resonance is not None else 0
            p[L.GAIN] = self.drive.gain
            beta = self.drive.viscous_rate
            p[L.BETA_POS] = p[L.BETA_NEG] = beta
            m = self.drive.equivalent_mass
            f = self.friction
            if f is not None:
                if f.viscous_positive is not None:
                    p[L.BETA_POS] = f.viscous_positive / m
                if f.viscous_negative is not None:
                    p[L.BETA_NEG] = f.viscous_negative / m
                sp, sn = f.static_levels
                p[L.FC_POS] = f.coulomb_positive / k
                p[L.FC_NEG] = f.coulomb_negative / k
                p[L.FS_POS] = sp / k
                p[L.FS_NEG] = sn / k
                p[L.V_STRIBECK] = f.stribeck_velocity
            if self.resonance is not None:
                p[L.RES_OMEGA] = self.resonance.omega
                p[L.RES_ZETA] = self.resonance.damping
                p[L.RES_FRACTION] = self.resonance.load_fraction
            if self.backlash is not None:
                p[L.BACKLASH] = self.backlash.width
            if self.position_periodic is not None:
                pp = self.position_periodic
                p[L.PP_FORCE] = pp.force_amplitude / k
                p[L.PP_POS] = pp.position_amplitude
                p[L.PP_PERIOD] = pp.period
                p[L.PP_PHASE] = pp.phase
            if self.load is not None:
                p[L.LOAD_CONST] = self.load.constant / k
                p[L.LOAD_AMP] = self.load.amplitude / k
                p[L.LOAD_PERIOD] = self.load.period
                p[L.LOAD_PHASE] = self.load.phase
        p[L.FEEDBACK_TABLE] = 1.0 if self.feedback == "table" else 0.0
        p[L.MEASURE_TABLE] = 1.0 if self.measurement == "table" else 0.0
        if self.encoder is not None:
            p[L.ENC_RES] = self.encoder.resolution
        if self.noise is not None:
            p[L.NOISE_STD] = self.noise.std
        if self.drift is not None:
            p[L.DRIFT_RATE] = self.drift.rate
            p[L.DRIFT_TAU] = self.drift.time_constant
        if self.dac is not None:
            p[L.DAC_LSB] = self.dac.lsb
            p[L.DAC_RANGE] = self.dac.range
        if self.delay is not None:
            p[L.DELAY] = self.delay.samples
        return p, c


_RECORD_CLASSES = {
    "friction": "Friction",
    "backlash": "Backlash",
    "encoder": "Encoder",
    "dac": "DAC",
    "saturation": "Saturation",
    "noise": "MeasurementNoise",
    "delay": "ComputationalDelay",
    "resonance": "StructuralMode",
    "position_periodic": "PositionPeriodic",
    "load": "ExternalLoad",
    "drift": "Drift",
}
