"""The vocabulary of effects: one registry that the machine, the FMU export, the sweeps and the
diagnosis read (ARCHITECTURE.md, "Effect names").

Each entry says what the effect is, which parameters set its realistic default on a simulated
axis (:func:`vcnc.engine.machine.realistic_effect`, with their defaults and units), which of them
a sweep's ``magnitude`` sets, whether it needs a physical plant (not a discrete transfer
function), and how an exported FMU represents it. It lives with the drives because the effects
are properties of feed drives, and every reader sits above this layer.
"""

from __future__ import annotations

import dataclasses
import types
from collections.abc import Mapping

__all__ = ["EffectInfo", "EFFECTS", "EFFECT_NAMES"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class EffectInfo:
    """One effect of the vocabulary.

    Attributes
    ----------
    name : str
        The effect's name in model files, reports and the command line.
    summary : str
        What it is, in a line.
    parameters : mapping of str to str
        Parameters of its realistic default on a simulated axis -> their meaning, default and unit.
    magnitude : str
        The parameter a sweep's ``magnitude`` sets.
    needs_plant : bool
        Needs a physical plant (mass, friction, ...), not a discrete transfer function.
    fmu : str
        How an exported FMU represents it, with its FMU parameters.
    """

    name: str
    summary: str
    parameters: Mapping[str, str]
    magnitude: str
    needs_plant: bool
    fmu: str


def _entry(name: str, summary: str, parameters: dict[str, str], magnitude: str, needs_plant: bool,
           fmu: str) -> tuple[str, EffectInfo]:
    return name, EffectInfo(name=name, summary=summary, parameters=types.MappingProxyType(parameters),
                            magnitude=magnitude, needs_plant=needs_plant, fmu=fmu)


#: The effects, in the order the diagnosis reports them.
EFFECTS: Mapping[str, EffectInfo] = types.MappingProxyType(dict([
    _entry("friction_stribeck", "static friction above Coulomb at low speed (Stribeck curve)",
           {"static_ratio": "static / Coulomb friction (2.0)", "stribeck_velocity_mm_s": "Stribeck velocity (5 mm/s)"},
           "static_ratio", True,
           "(PV s+ + NV s-) exp(-(v/v_s)^2) in w: stribeck_velocity, stribeck_excess_positive, "
           "stribeck_excess_negative"),
    _entry("friction_viscous_asymmetric", "viscous friction that differs by direction",
           {"asymmetry": "relative difference by direction (0.3)"}, "asymmetry", True,
           "k_a |v| in w: viscous_asymmetry"),
    _entry("backlash", "lost motion at reversals (play in the nut or the coupling)",
           {"width_mm": "play (0.01 mm)", "feedback": "'table' (default), 'motor' or 'axis'"}, "width_mm", True,
           "play between the driven mass and the measured position in the split loop: backlash_width, "
           "plant_viscous_rate"),
    _entry("position_periodic", "a load periodic in position (cogging, torque ripple, lead error)",
           {"period_mm": "period (the screw lead, or 10 mm)", "amplitude_n": "force amplitude (5 % of the force "
            "at 1 V) [N]", "position_amplitude_mm": "position error amplitude (0 mm)"}, "amplitude_n", True,
           "Fourier series in x in w: position_period, position_periodic_sin_<h>/_cos_<h> (harmonics fixed at "
           "export)"),
    _entry("time_periodic", "an external load periodic in time (a shaker, an unbalanced spindle)",
           {"period_s": "period (0.5 s)", "amplitude_n": "force amplitude (10 % of the force at 1 V) [N]"},
           "amplitude_n", True,
           "Fourier series in t in w: time_period, time_mean, time_periodic_sin_<h>/_cos_<h> (harmonics fixed "
           "at export; t from initialisation)"),
    _entry("resonance", "a lightly damped structural mode between motor and table",
           {"frequency_hz": "frequency (60 Hz)", "damping": "damping ratio (0.05)",
            "load_fraction": "share of the mass beyond the spring (0.5)"}, "load_fraction", True,
           "two-mass plant in the split loop: resonance_frequency, resonance_damping, resonance_table_fraction, "
           "plant_viscous_rate (measured_at fixed at export)"),
    _entry("delay", "a computation or transport delay inside the loop",
           {"samples": "delay (2 samples)"}, "samples", False,
           "control action delayed by whole samples in the split loop: delay_samples, plant_viscous_rate"),
    _entry("saturation", "the amplifier's voltage limit",
           {"saturated_fraction": "share of the reference test's samples above the limit (0.03)",
            "voltage_limit_v": "the limit itself [V], instead"}, "voltage_limit_v", False,
           "acceleration demand clipped in the split loop: saturation_limit, plant_viscous_rate "
           "(its anti-windup and integral lead fixed at export)"),
    _entry("drift", "a slow offset of the measurement (thermal growth)",
           {"rate_mm_s": "rate (2e-4 mm/s)", "time_constant_s": "first-order time constant (0: linear)",
            "measurement": "'table' (default) or 'feedback'"}, "rate_mm_s", False,
           "rate * t added to the measured position: drift_rate"),
]))

#: Effect names in registry order.
EFFECT_NAMES: tuple[str, ...] = tuple(EFFECTS)
