"""Fields and helpers shared by the continuous servo laws (velocity filter, friction feedforward)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from controllers._base import N_PARAMS, VELOCITY_FILTERS, velocity_estimator

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["common_checks", "integrator", "coulomb_after_feedforward", "filter_code", "FF_UNITS"]

FF_UNITS = {
    "friction_feedforward_positive": "V",
    "friction_feedforward_negative": "V",
    "velocity_filter": "",
}


def common_checks(c: Any) -> None:
    """Checks of the shared fields (friction feedforward >= 0 V, known velocity filter)."""
    c._nonnegative("friction_feedforward_positive", "friction_feedforward_negative")
    c._choice("velocity_filter", VELOCITY_FILTERS)


def filter_code(name: str) -> float:
    return float(VELOCITY_FILTERS.index(name))


def integrator(sample_time: float) -> control.TransferFunction:
    """Rectangular (backward Euler) integrator Ts z/(z - 1) used by every integral action."""
    import control
    return control.tf([sample_time, 0.0], [1.0, -1.0], sample_time)


def derivative(name: str, sample_time: float) -> control.TransferFunction:
    return velocity_estimator(name, sample_time)


def coulomb_after_feedforward(c: Any, coulomb: tuple[float, float]) -> tuple[float, float]:
    """Coulomb friction left after the friction feedforward [V] (d+ >= 0, d- <= 0)."""
    return coulomb[0] - c.friction_feedforward_positive, coulomb[1] + c.friction_feedforward_negative


def pack_law(c: Any, gains: tuple[float, float, float, float, float]) -> np.ndarray:
    """Parameter vector of a continuous-law controller for the compiled kernel: the law's five
    gains, then the friction feedforward (+, -) and the velocity-filter code; zeros after."""
    p = np.zeros(N_PARAMS)
    p[:8] = [*gains, c.friction_feedforward_positive, c.friction_feedforward_negative,
             filter_code(c.velocity_filter)]
    return p
