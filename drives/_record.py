"""Shared behaviour of the parameter records of drives and controllers.

Every record is a frozen, keyword-only dataclass whose fields carry a unit in the class attribute
``UNITS``. Validation happens in ``__post_init__`` and raises :class:`vcnc.errors.MachineError`
naming the field, its unit, what was expected and what came; the error carries the field name in
``error.key`` so that the TOML loader can point at the file line holding it.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, ClassVar

from vcnc.core.errors import MachineError

__all__ = ["Record", "record_error"]


def record_error(record: str, field: str, unit: str, message: str, value: Any) -> MachineError:
    """A MachineError ``"<record>.<field> [unit] <message> (got value)"`` carrying ``key=field``."""
    unit_txt = f" [{unit}]" if unit else ""
    text = value if isinstance(value, str) else repr(value)
    err = MachineError(f"{record}.{field}{unit_txt} {message}", text=text)
    err.key = field  # type: ignore[attr-defined]
    return err


class Record:
    """Mixin of the parameter records: units, checks and plain-dict conversion."""

    #: field name -> unit (``""`` for dimensionless or text fields)
    UNITS: ClassVar[dict[str, str]] = {}
    #: short name used in messages and in TOML (``[axes.x.<TABLE>]``)
    TABLE: ClassVar[str] = ""

    # ------------------------------------------------------------------ checks
    def _fail(self, field: str, message: str) -> MachineError:
        return record_error(type(self).__name__, field, self.UNITS.get(field, ""), message, getattr(self, field))

    def _number(self, field: str) -> float:
        v = getattr(self, field)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self._fail(field, "must be a number")
        if math.isnan(v):
            raise self._fail(field, "must not be NaN")
        return float(v)

    def _positive(self, *fields: str, finite: bool = True) -> None:
        for f in fields:
            v = self._number(f)
            if not v > 0 or (finite and math.isinf(v)):
                raise self._fail(f, "must be a finite value > 0" if finite else "must be > 0")

    def _nonnegative(self, *fields: str, finite: bool = True) -> None:
        for f in fields:
            v = self._number(f)
            if v < 0 or (finite and math.isinf(v)):
                raise self._fail(f, "must be a finite value >= 0")

    def _finite(self, *fields: str) -> None:
        for f in fields:
            if not math.isfinite(self._number(f)):
                raise self._fail(f, "must be finite")

    def _in_range(self, field: str, lo: float, hi: float, *, closed_hi: bool = True) -> None:
        v = self._number(field)
        ok = lo <= v <= hi if closed_hi else lo <= v < hi
        if not ok:
            raise self._fail(field, f"must lie in [{lo}, {hi}{']' if closed_hi else ')'}")

    def _integer(self, field: str, lo: int, hi: int) -> None:
        v = getattr(self, field)
        if isinstance(v, bool) or not isinstance(v, int):
            raise self._fail(field, "must be an integer")
        if not lo <= v <= hi:
            raise self._fail(field, f"must lie in [{lo}, {hi}]")

    def _boolean(self, *fields: str) -> None:
        for f in fields:
            if not isinstance(getattr(self, f), bool):
                raise self._fail(f, "must be true or false")

    def _choice(self, field: str, choices: tuple[str, ...]) -> None:
        v = getattr(self, field)
        if v not in choices:
            raise self._fail(field, f"must be one of {', '.join(repr(c) for c in choices)}")

    # ------------------------------------------------------------------ conversion
    def to_dict(self) -> dict[str, Any]:
        """Plain dict of the fields (what a TOML table of this record holds), ``None`` left out."""
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            v = getattr(self, f.name)
            if v is None:
                continue
            out[f.name] = list(v) if isinstance(v, tuple) else v
        return out
