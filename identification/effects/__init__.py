"""Effects the residual diagnosis can add to a reduced model (ARCHITECTURE.md vocabulary).

One class per effect, one file each, sharing :class:`Effect` (``NAME``, ``KIND``, ``FMU``,
``UNITS``, ``parameters()``/``from_parameters()``, ``pack()`` into the simulation, ``free()`` /
``with_free()`` for the joint refit). :data:`EFFECTS` maps each name to its class;
:func:`effect_from_record` rebuilds one from its model-file record.

=============================  ===========  ===  =============================================
name                           kind         FMU  enters as
=============================  ===========  ===  =============================================
friction_stribeck              disturbance  yes  (PV s+ + NV s-) exp(-(v/v_s)^2) in w (``stick``: split loop)
friction_viscous_asymmetric    disturbance  yes  k_a |v| in w
position_periodic              disturbance  yes  Fourier series in x (period P_x) in w
time_periodic                  disturbance  yes  Fourier series in t (period P_t) in w
drift                          output       yes  rate * t added to the measurement
delay                          element      yes  u held for whole samples (split loop)
saturation                     element      yes  u clipped, anti-windup or not (split loop)
backlash                       element      yes  play operator on the measured position
resonance                      element      yes  two-mass plant (split loop)
=============================  ===========  ===  =============================================
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from identification.effects._base import Effect, Free
from identification.effects.backlash import Backlash
from identification.effects.delay import Delay
from identification.effects.drift import Drift
from identification.effects.friction_stribeck import FrictionStribeck
from identification.effects.friction_viscous_asymmetric import FrictionViscousAsymmetric
from identification.effects.position_periodic import PositionPeriodic
from identification.effects.resonance import Resonance
from identification.effects.saturation import Saturation
from identification.effects.time_periodic import TimePeriodic
from vcnc.core.errors import InputError

__all__ = [
    "Effect",
    "Free",
    "EFFECTS",
    "effect_from_record",
    "Backlash",
    "Delay",
    "Drift",
    "FrictionStribeck",
    "FrictionViscousAsymmetric",
    "PositionPeriodic",
    "Resonance",
    "Saturation",
    "TimePeriodic",
]

#: effect name -> class, in the order of ARCHITECTURE.md
EFFECTS: dict[str, type[Effect]] = {
    cls.NAME: cls
    for cls in (
        FrictionStribeck,
        FrictionViscousAsymmetric,
        Backlash,
        PositionPeriodic,
        TimePeriodic,
        Resonance,
        Delay,
        Saturation,
        Drift,
    )
}


def effect_from_record(record: Mapping[str, Any]) -> Effect:
    """The effect of a model-file record ``{"name": .., "parameters": {..}}``."""
    if not isinstance(record, Mapping) or "name" not in record:
        raise InputError("an effect record must be an object with 'name' and 'parameters'")
    name = record["name"]
    cls = EFFECTS.get(name)
    if cls is None:
        raise InputError(f"unknown effect {name!r}; expected one of {', '.join(EFFECTS)}")
    params = record.get("parameters") or {}
    if not isinstance(params, Mapping):
        raise InputError(f"effect {name!r}: 'parameters' must be an object")
    return cls.from_parameters(params)
