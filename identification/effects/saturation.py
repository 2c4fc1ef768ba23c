"""``saturation``: the actuator limit, as a clip of the acceleration demand of the split loop."""

from __future__ import annotations

import dataclasses
import math
from typing import ClassVar

from identification.effects._base import Effect, Free
from vcnc.core.errors import InputError

__all__ = ["Saturation"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Saturation(Effect):
    """u = clip(u_demand, -limit, +limit) in the split form (:mod:`identification.augmented`).

    Parameters
    ----------
    limit : float
        Largest acceleration demand the actuator delivers [mm/s^2] (current or voltage limit
        times K/J). Found from the samples whose measured acceleration demand piles up at a level,
        then refitted.
    anti_windup : bool
        True: the law's accumulator does not take the step of a sample whose demand is beyond the
        limit when the step pushes it further out (conditional integration, as the machines' servo
        laws do by default: :class:`controllers.Controller`; K. J. Astrom, L. Rundqwist, "Integrator
        windup and how to avoid it", ACC 1989; K. J. Astrom, R. M. Murray, "Feedback Systems",
        Sec. 10.4). False: nothing is held back, as in the thesis' bare PID. A model file without
        the key reads as False (as the element read before the key existed).
    integral_lead : float
        tau [s] (>= 0, with ``anti_windup``): the accumulator is ``a3 int(e + tau de/dt) dt +
        (b2 - a2) x_r`` of the split controller (module :mod:`identification.augmented`). Which
        share of Eq. (3.3)'s proportional gain a2 lives in the law's integrator is not in the
        reduced model: 0 for a PID (its integral is that of e alone, Eq. 3.5); 1/K_p for a P-PI,
        whose velocity-loop integrator integrates K_p e + K_p k_v v_r - v, so that it holds
        a3 int(e) + (a3/K_p) e + (b2 - a2) x_r (K_p the position-loop gain, 30 1/s on fadal-ppi:
        33 ms); 1/lambda for the sliding-mode law, whose adapted disturbance integrates
        s = lambda e + de/dt (lambda = 200 1/s on fadal-smc: 5 ms). Derived by expanding the laws
        of :mod:`controllers` against Eq. (3.3) (ours). Refitted with the limit.

    Notes
    -----
    Not linear in parameters (Assumption 2 of Sec. 3.2 fails): the structured element, not a
    regressor. A loop whose demand stays within the limit is the same in both forms. The
    diagnosis tries both forms (and a few leads) and keeps the one that fits better. FMU: yes (a
    clip; the anti-windup a structural switch fixed at export, the lead a parameter).
    """

    limit: float
    anti_windup: bool = False
    integral_lead: float = 0.0

    NAME: ClassVar[str] = "saturation"
    KIND: ClassVar[str] = "element"
    FMU: ClassVar[bool] = True
    UNITS: ClassVar[dict[str, str]] = {"limit_mm_s2": "mm/s^2", "anti_windup": "", "integral_lead_s": "s"}
    DESCRIPTION: ClassVar[str] = "actuator limit (clipped acceleration demand)"

    def parameters(self):
        out = {"limit_mm_s2": self.limit, "anti_windup": bool(self.anti_windup)}
        if self.anti_windup:
            out["integral_lead_s"] = self.integral_lead
        return out

    @classmethod
    def from_parameters(cls, p):
        aw = p.get("anti_windup", False)
        if not isinstance(aw, bool):
            raise InputError(f"effect parameter 'anti_windup' of saturation must be true or false (got {aw!r})")
        lead = cls._require(p, "integral_lead_s", "s") if "integral_lead_s" in p else 0.0
        if lead < 0.0:
            raise InputError(f"effect parameter 'integral_lead_s' [s] of saturation must be >= 0 (got {lead!r})")
        return cls(limit=cls._require(p, "limit_mm_s2", "mm/s^2"), anti_windup=aw, integral_lead=lead)

    def summary(self):
        if not self.anti_windup:
            return f"limit {self.limit:.5g} mm/s^2"
        return f"limit {self.limit:.5g} mm/s^2, anti-windup (lead {self.integral_lead * 1e3:.3g} ms)"

    def pack(self, spec, *, model_sample_time):
        spec.structured = True
        spec.saturation = self.limit
        spec.anti_windup = bool(self.anti_windup)
        spec.integral_lead = float(self.integral_lead)

    def free(self):
        out = [Free("log_limit", math.log(self.limit), math.log(1.0), math.log(1e8), 1e-2)]
        if self.anti_windup:
            out.append(Free("integral_lead_s", self.integral_lead, 0.0, 1.0, 1e-3))
        return out

    def with_free(self, values):
        lead = float(values[1]) if self.anti_windup else self.integral_lead
        return dataclasses.replace(self, limit=math.exp(values[0]), integral_lead=lead)
