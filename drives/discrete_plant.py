"""A plant known only as a discrete transfer function (e.g. identified by ARX)."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from drives._record import Record

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["DiscretePlantDrive"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class DiscretePlantDrive(Record):
    """Plant ``P(z) = y/u = (b1 z^-1 + ... + bn z^-n) / (1 + a1 z^-1 + ... + an z^-n)``.

    Parameters
    ----------
    numerator : tuple of float
        ``(b1, ..., bn)``, coefficients of z^-1 ... z^-n [output unit/V]; strictly proper.
    denominator : tuple of float
        ``(a1, ..., an)`` (the leading 1 implied) [-].
    sample_time : float
        Period the coefficients hold for [s]; must equal the machine's sample time.
    output_unit : float
        Size of one output unit [mm] (1000 when the plant was identified in metres).

    Notes
    -----
    Used for the grinding-machine axis of seed 004, Eq. (11):
    ``P*(z) = 1.218 z^-1 / (1 - 1.892 z^-1 + 0.886 z^-2)``. Friction, backlash and structural
    modes cannot be added to such a plant (they need a physical model); actuator and sensor
    effects can.
    """

    numerator: tuple[float, ...]
    denominator: tuple[float, ...]
    sample_time: float
    output_unit: float = 1.0

    UNITS: ClassVar[dict[str, str]] = {
        "numerator": "output unit/V",
        "denominator": "-",
        "sample_time": "s",
        "output_unit": "mm",
    }
    TABLE: ClassVar[str] = "discrete"

    def __post_init__(self) -> None:
        for name in ("numerator", "denominator"):
            v = getattr(self, name)
            if isinstance(v, (list, np.ndarray)):
                object.__setattr__(self, name, tuple(float(c) for c in v))
                v = getattr(self, name)
            if not isinstance(v, tuple) or not v or not all(
                isinstance(c, (int, float)) and not isinstance(c, bool) and math.isfinite(c) for c in v
            ):
                raise self._fail(name, "must be a non-empty list of finite numbers")
        if len(self.numerator) > len(self.denominator):
            raise self._fail("numerator", f"must have at most {len(self.denominator)} coefficients (proper plant)")
        if len(self.denominator) > 8:
            raise self._fail("denominator", "must have at most 8 coefficients")
        if all(c == 0 for c in self.numerator):
            raise self._fail("numerator", "must not be all zero")
        self._positive("sample_time", "output_unit")

    @property
    def order(self) -> int:
        return len(self.denominator)

    def transfer_function(self) -> control.TransferFunction:
        """P(z) from u [V] to the table position [mm], discrete with dt = ``sample_time``."""
        import control
        n = self.order
        num = np.zeros(n + 1)
        num[1 : 1 + len(self.numerator)] = np.asarray(self.numerator) * self.output_unit
        den = np.concatenate([[1.0], self.denominator])
        return control.tf(num, den, self.sample_time)

    @property
    def gain(self) -> float:
        """Not defined for a discrete plant (no K/J); NaN."""
        return math.nan

    @property
    def viscous_rate(self) -> float:
        return math.nan

    @property
    def force_per_volt(self) -> float:
        return math.nan
