"""Stability bounds on the closed-loop poles (Eq. 3.8 of the thesis) as a search box.

The thesis bounds p >= p_min, omega_n >= omega_n,min and zeta_min <= zeta <= zeta_max (Eq. 3.8);
its GA (Sec. 4.2, 4.3) adds upper bounds p, omega_n <= Nyquist frequency. Defaults here are those
of Sec. 4.3: 0.2 Hz to the Nyquist frequency for p and omega_n, 0.2 to 2.0 for zeta.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from vcnc.core.errors import IdentificationError

__all__ = ["PoleBounds", "default_bounds", "as_bounds", "WIDE_P_MIN_HZ"]

#: Nyquist frequency assumed when no sample time is known: Ts = 1 ms, as in the thesis' data.
DEFAULT_NYQUIST_HZ = 500.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class PoleBounds:
    """Box of the search variables.

    Attributes
    ----------
    p_hz : (float, float)
        Real pole p [Hz], lower and upper bound.
    omega_n_hz : (float, float)
        Natural frequency omega_n [Hz].
    zeta : (float, float)
        Damping ratio [-].
    """

    p_hz: tuple[float, float]
    omega_n_hz: tuple[float, float]
    zeta: tuple[float, float]

    def __post_init__(self) -> None:
        for name in ("p_hz", "omega_n_hz", "zeta"):
            pair = getattr(self, name)
            try:
                lo, hi = (float(v) for v in pair)
            except (TypeError, ValueError):
                raise IdentificationError(f"bounds[{name!r}] must be a pair (lo, hi); got {pair!r}") from None
            unit = "Hz" if name.endswith("_hz") else "-"
            if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
                raise IdentificationError(
                    f"bounds[{name!r}] [{unit}] must satisfy 0 < lo < hi (finite); got ({lo!r}, {hi!r})"
                )
            object.__setattr__(self, name, (lo, hi))

    def as_dict(self) -> dict[str, tuple[float, float]]:
        """``{"p_hz": (lo, hi), "omega_n_hz": (lo, hi), "zeta": (lo, hi)}``."""
        return {"p_hz": self.p_hz, "omega_n_hz": self.omega_n_hz, "zeta": self.zeta}

    def rad(self) -> tuple[tuple[float, float], tuple[float, float], tuple[float, float]]:
        """((p_lo, p_hi), (wn_lo, wn_hi), (zeta_lo, zeta_hi)) with frequencies in rad/s."""
        k = 2.0 * math.pi
        return (
            (self.p_hz[0] * k, self.p_hz[1] * k),
            (self.omega_n_hz[0] * k, self.omega_n_hz[1] * k),
            self.zeta,
        )

    def contains(self, poles: Mapping[str, float], *, rtol: float = 1e-9) -> bool:
        """True when (p_hz, omega_n_hz, zeta) lie in the box (with a relative tolerance)."""
        k = 2.0 * math.pi
        return bool(self.contains_rad(poles["p_hz"] * k, poles["omega_n_hz"] * k, poles["zeta"], rtol=rtol))

    def contains_rad(self, p, omega_n, zeta, *, rtol: float = 1e-9) -> np.ndarray:
        """Vectorised :meth:`contains` for p, omega_n [rad/s] and zeta [-] (arrays broadcast)."""
        inside = True
        for v, (lo, hi) in zip((p, omega_n, zeta), self.rad()):
            v = np.asarray(v, float)
            inside = inside & (v >= lo * (1 - rtol)) & (v <= hi * (1 + rtol))
        return np.asarray(inside)


def default_bounds(sample_time: float | None = None) -> PoleBounds:
    """The thesis' box (Sec. 4.3): 0.2 Hz..Nyquist for p and omega_n, 0.2..2.0 for zeta.

    Parameters
    ----------
    sample_time : float, optional
        T [s]; Nyquist = 1/(2T). Without it, 500 Hz (Ts = 1 ms).
    """
    nyq = DEFAULT_NYQUIST_HZ if sample_time is None else 0.5 / float(sample_time)
    return PoleBounds(p_hz=(0.2, nyq), omega_n_hz=(0.2, nyq), zeta=(0.2, 2.0))


#: Lower bound of p [Hz] of the widened box of :func:`identification.identify` (a loop without
#: integral action has p -> 0; any p > 0 keeps the loop stable, Eq. 3.8).
WIDE_P_MIN_HZ = 1e-3


def as_bounds(bounds: PoleBounds | Mapping | str | None, sample_time: float | None = None) -> PoleBounds:
    """Normalise ``bounds`` (None or ``"thesis"``: the thesis' box; a mapping; PoleBounds); missing keys
    take the defaults."""
    if bounds is None or bounds == "thesis":
        return default_bounds(sample_time)
    if isinstance(bounds, str):
        raise IdentificationError(f"bounds must be 'thesis', a mapping of p_hz, omega_n_hz, zeta or PoleBounds; "
                                  f"got {bounds!r}")
    if isinstance(bounds, PoleBounds):
        return bounds
    if not isinstance(bounds, Mapping):
        raise IdentificationError(f"bounds must be a mapping of p_hz, omega_n_hz, zeta; got {type(bounds).__name__}")
    unknown = set(bounds) - {"p_hz", "omega_n_hz", "zeta"}
    if unknown:
        raise IdentificationError(f"unknown bounds key(s) {sorted(unknown)}; expected p_hz, omega_n_hz, zeta")
    d = default_bounds(sample_time).as_dict()
    d.update({k: tuple(v) for k, v in bounds.items()})
    return PoleBounds(**d)
