"""Virtual feed-drive plants and their non-idealities.

Plants: :class:`BallScrewDrive`, :class:`LinearMotorDrive` (rigid bodies, Sec. 3.2 of the thesis)
and :class:`DiscretePlantDrive` (a plant known as a discrete transfer function, seed 004).
Non-idealities, each optional: :class:`Friction` (Coulomb, static, Stribeck, direction-dependent
viscous), :class:`Backlash`, :class:`Encoder`, :class:`DAC`, :class:`Saturation`,
:class:`MeasurementNoise`, :class:`ComputationalDelay`, :class:`StructuralMode`,
:class:`PositionPeriodic`, :class:`ExternalLoad`, :class:`Drift`.

All are frozen keyword-only dataclasses with their units in ``UNITS``; they only hold
parameters. The compiled simulation (``vcnc.engine``) owns the run-time state.
"""

from drives.backlash import Backlash
from drives.ballscrew import BallScrewDrive
from drives.dac import DAC
from drives.delay import ComputationalDelay
from drives.discrete_plant import DiscretePlantDrive
from drives.disturbance import ExternalLoad, PositionPeriodic
from drives.drift import Drift
from drives.encoder import Encoder
from drives.friction import Friction
from drives.linear_motor import LinearMotorDrive
from drives.noise import MeasurementNoise
from drives.resonance import StructuralMode
from drives.saturation import Saturation

__all__ = [
    "BallScrewDrive",
    "LinearMotorDrive",
    "DiscretePlantDrive",
    "Friction",
    "Backlash",
    "Encoder",
    "DAC",
    "Saturation",
    "MeasurementNoise",
    "ComputationalDelay",
    "StructuralMode",
    "PositionPeriodic",
    "ExternalLoad",
    "Drift",
    "PLANTS",
    "NONIDEALITIES",
]

#: TOML ``type`` of ``[axes.<a>.drive]`` -> plant class
PLANTS = {cls.TABLE: cls for cls in (BallScrewDrive, LinearMotorDrive, DiscretePlantDrive)}

#: TOML table name under ``[axes.<a>]`` -> non-ideality class
NONIDEALITIES = {
    cls.TABLE: cls
    for cls in (
        Friction,
        Backlash,
        Encoder,
        DAC,
        Saturation,
        MeasurementNoise,
        ComputationalDelay,
        StructuralMode,
        PositionPeriodic,
        ExternalLoad,
        Drift,
    )
}
