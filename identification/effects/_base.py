"""The protocol shared by every effect: parameters with units, how it enters, JSON, FMU flag."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

from vcnc.core.errors import InputError
from vcnc.core.jsonsafe import plain

__all__ = ["Effect", "Free"]


@dataclasses.dataclass(frozen=True)
class Free:
    """One continuous parameter of the joint refit.

    ``value`` is in the refit's coordinates (``log`` of a positive parameter when ``log``);
    ``lo``/``hi`` bound it there; ``scale`` is its typical size (finite-difference steps).
    ``linear`` marks a coefficient the output depends on (nearly) linearly: the refit solves those
    by linear least squares on simulated sensitivities instead of by the nonlinear solver.
    """

    name: str
    value: float
    lo: float = -math.inf
    hi: float = math.inf
    scale: float = 1.0
    linear: bool = False


@dataclasses.dataclass(frozen=True, kw_only=True)
class Effect:
    """Base of the effects a diagnosis can add (ARCHITECTURE.md, "Effect names").

    Class attributes
    ----------------
    NAME : str
        Effect name of the diagnosis vocabulary.
    KIND : str
        ``"disturbance"`` (a term of w, linear in its coefficients given a nonlinear parameter),
        ``"element"`` (a structured element of the split loop) or ``"output"`` (added to the
        predicted measurement); see :mod:`identification.augmented`.
    FMU : bool
        Whether the FMU export can represent it.
    UNITS : dict
        Unit of each JSON parameter.
    DESCRIPTION : str
        One line for reports.
    """

    NAME: ClassVar[str] = ""
    KIND: ClassVar[str] = "disturbance"
    FMU: ClassVar[bool] = False
    UNITS: ClassVar[dict[str, str]] = {}
    DESCRIPTION: ClassVar[str] = ""

    # ------------------------------------------------------------------ JSON
    def parameters(self) -> dict[str, Any]:
        """JSON parameters (names carry their unit, e.g. ``period_s``)."""
        raise NotImplementedError

    @classmethod
    def from_parameters(cls, parameters: Mapping[str, Any]) -> Effect:
        """Inverse of :meth:`parameters`."""
        raise NotImplementedError

    def record(self) -> dict[str, Any]:
        """``{"name": .., "parameters": {..}, "units": {..}, "fmu": ..}``."""
        return {"name": self.NAME, "parameters": plain(self.parameters()), "units": dict(self.UNITS),
                "fmu": self.FMU}

    def summary(self) -> str:
        """Short text for tables, e.g. ``delay 2 samples``."""
        return self.NAME

    @property
    def in_loop(self) -> bool:
        """True when the model needs the split (plant + sampled controller) form for this effect: an element, or
        a term that holds a stopped mass (:class:`identification.effects.FrictionStribeck` with ``stick``)."""
        return self.KIND == "element"

    def unpinned(self, *, travel: float, duration: float) -> dict[str, str]:
        """The parameters a record of ``travel`` [mm or deg] and ``duration`` [s] does not pin, each with why
        (``{}`` when it pins them all): the model still simulates with the fitted value, but the report must not
        state it as measured (:meth:`identification.effects.PositionPeriodic.unpinned`)."""
        return {}

    # ------------------------------------------------------------------ simulation
    def pack(self, spec, *, model_sample_time: float) -> None:
        """Write this effect's contribution into a :class:`identification.augmented.SimSpec`."""
        raise NotImplementedError

    # ------------------------------------------------------------------ refit
    def free(self) -> list[Free]:
        """Continuous parameters refitted jointly with the reduced model (may be empty)."""
        return []

    def with_free(self, values: np.ndarray) -> Effect:
        """A copy with :meth:`free` values replaced (same order and coordinates)."""
        return self

    @staticmethod
    def _require(parameters: Mapping[str, Any], key: str, unit: str) -> float:
        if key not in parameters:
            raise InputError(f"effect parameter {key!r} [{unit}] missing")
        v = parameters[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)):
            raise InputError(f"effect parameter {key!r} [{unit}] must be a finite number (got {v!r})")
        return float(v)


