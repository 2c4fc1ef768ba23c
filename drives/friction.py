"""Guideway and screw friction: Coulomb, static (stiction), Stribeck and viscous."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

from drives._record import Record

__all__ = ["Friction"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Friction(Record):
    """Direction-dependent friction acting at the table.

    Parameters
    ----------
    coulomb_positive, coulomb_negative : float
        Coulomb friction magnitude while moving in + / - direction [N] (``d+``, ``-d-`` of
        Eq. (3.2) of the thesis times the drive's force per volt).
    static_positive, static_negative : float, optional
        Break-away (static) friction magnitude [N], at least the Coulomb level; default equal to
        it. An axis at rest stays at rest while the applied force stays within these levels.
    stribeck_velocity : float
        Velocity [mm/s] over which friction falls from the static to the Coulomb level
        (Gaussian Stribeck curve); 0 disables the Stribeck curve.
    viscous_positive, viscous_negative : float, optional
        Direction-dependent viscous friction [N s/m]; when given they replace the drive's
        symmetric viscous coefficient for motion in that direction (the EMPS bench:
        166.7 / 240.4 N s/m).

    Notes
    -----
    Friction while moving in direction sgn = sign(v)::

        F = sgn * (F_c + (F_s - F_c) exp(-(v / v_s)^2)) + F_v,dir v

    Eq. (3.2) of the thesis is the special case F_s = F_c, v_s = 0.
    """

    coulomb_positive: float = 0.0
    coulomb_negative: float = 0.0
    static_positive: float | None = None
    static_negative: float | None = None
    stribeck_velocity: float = 0.0
    viscous_positive: float | None = None
    viscous_negative: float | None = None

    UNITS: ClassVar[dict[str, str]] = {
        "coulomb_positive": "N",
        "coulomb_negative": "N",
        "static_positive": "N",
        "static_negative": "N",
        "stribeck_velocity": "mm/s",
        "viscous_positive": "N s/m",
        "viscous_negative": "N s/m",
    }
    TABLE: ClassVar[str] = "friction"

    def __post_init__(self) -> None:
        self._nonnegative("coulomb_positive", "coulomb_negative", "stribeck_velocity")
        for f in ("static_positive", "static_negative", "viscous_positive", "viscous_negative"):
            if getattr(self, f) is not None:
                self._nonnegative(f)
        for sign in ("positive", "negative"):
            s = getattr(self, f"static_{sign}")
            c = getattr(self, f"coulomb_{sign}")
            if s is not None and s < c:
                raise self._fail(f"static_{sign}", f"must be at least coulomb_{sign} = {c} N")

    @property
    def static_levels(self) -> tuple[float, float]:
        """(F_s+, F_s-) [N], defaulting to the Coulomb levels."""
        sp = self.coulomb_positive if self.static_positive is None else self.static_positive
        sn = self.coulomb_negative if self.static_negative is None else self.static_negative
        return sp, sn

    def force(self, velocity: float, *, viscous: float = 0.0) -> float:
        """Friction force [N] at a velocity [mm/s] (0 at rest: there it balances the load).

        ``viscous`` is the drive's symmetric coefficient [N s/m], used where no
        direction-dependent one is given.
        """
        if velocity == 0:
            return 0.0
        pos = velocity > 0
        fc = self.coulomb_positive if pos else self.coulomb_negative
        fs = self.static_levels[0 if pos else 1]
        level = fc
        if self.stribeck_velocity > 0:
            level = fc + (fs - fc) * math.exp(-((velocity / self.stribeck_velocity) ** 2))
        fv = self.viscous_positive if pos else self.viscous_negative
        fv = viscous if fv is None else fv
        return math.copysign(level, velocity) + fv * velocity * 1e-3
