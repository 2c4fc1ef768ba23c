"""Kinematic limits of one machine axis, used by the feed-profile planners."""

from __future__ import annotations

import dataclasses
import math

from vcnc.core.errors import InputError

__all__ = ["AxisLimits", "DEFAULT_LIMITS", "DEFAULT_ROTARY_LIMITS", "DEFAULT_SECONDARY_LIMITS"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class AxisLimits:
    """Limits of one axis: a linear axis (x, y, z, u, v, w) in mm, a rotary axis (a, b, c) in deg.

    Attributes
    ----------
    velocity : float
        Maximum axis velocity [mm/s] (rotary: [deg/s]) for feed moves.
    acceleration : float
        Maximum axis acceleration [mm/s^2] (rotary: [deg/s^2]).
    jerk : float
        Maximum axis jerk [mm/s^3] (rotary: [deg/s^3]; used by the S-curve profile; ``inf`` allowed
        for trapezoid only).
    rapid : float, optional
        Rapid traverse rate [mm/s] (rotary: [deg/s]) for G00 / FMAX; defaults to ``velocity``.
    """

    velocity: float
    acceleration: float
    jerk: float = math.inf
    rapid: float | None = None

    def __post_init__(self) -> None:
        for name, unit in (("velocity", "mm/s"), ("acceleration", "mm/s^2"), ("jerk", "mm/s^3")):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and v > 0 and not math.isnan(v)):
                raise InputError(f"axis limit {name} must be > 0 {unit}, got {v!r}")
        if self.rapid is not None and not (self.rapid > 0 and math.isfinite(self.rapid)):
            raise InputError(f"axis limit rapid must be a finite value > 0 mm/s, got {self.rapid!r}")

    @property
    def rapid_rate(self) -> float:
        """Rapid traverse rate [mm/s]."""
        return self.velocity if self.rapid is None else self.rapid


#: Limits used when no machine is given (``interpolate(limits=None)``, ``vcnc interpolate``
#: without ``--machine``), the same for x, y and z: feed velocity 250 mm/s (15 m/min, the largest
#: feed of the thesis' identification tests, Sec. 4.3.2), acceleration 2000 mm/s^2 (the
#: interpolator limit of the thesis' identification test, Sec. 3.4), jerk 50 000 mm/s^3
#: (50 m/s^3, a typical machining-centre value) and rapid rate 500 mm/s (30 m/min).
DEFAULT_LIMITS: dict[str, AxisLimits] = {
    axis: AxisLimits(velocity=250.0, acceleration=2000.0, jerk=50_000.0, rapid=500.0) for axis in ("x", "y", "z")
}

#: Rotary-axis limits used when no machine is given, the same for a, b and c: feed velocity
#: 180 deg/s (30 rev/min), acceleration 1800 deg/s^2 (full feed speed in 0.1 s), jerk
#: 36 000 deg/s^3 (full acceleration in 0.05 s) and rapid rate 360 deg/s (60 rev/min), the order of
#: a compact fourth-axis rotary table. A machine file states its own (``[axes.a.limits]``, in deg).
DEFAULT_ROTARY_LIMITS: dict[str, AxisLimits] = {
    axis: AxisLimits(velocity=180.0, acceleration=1800.0, jerk=36_000.0, rapid=360.0) for axis in ("a", "b", "c")
}

#: Limits of the secondary linear axes u, v, w (parallel to x, y, z) used when no machine is given:
#: those of :data:`DEFAULT_LIMITS`. A machine file states its own (``[axes.u.limits]``, in mm).
DEFAULT_SECONDARY_LIMITS: dict[str, AxisLimits] = {
    u: DEFAULT_LIMITS[x] for u, x in zip(("u", "v", "w"), ("x", "y", "z"))
}
