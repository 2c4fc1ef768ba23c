"""Nut backlash: lost motion between the motor side and the table."""

from __future__ import annotations

import dataclasses
from typing import ClassVar

from drives._record import Record

__all__ = ["Backlash"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Backlash(Record):
    """Backlash of total width ``width`` between motor side and table (play operator).

    Parameters
    ----------
    width : float
        Total lost motion at a reversal [mm].

    Notes
    -----
    The table position follows the motor-side position through a play operator: it stays put
    while the motor crosses the gap and is pushed along once contact is made, so after a
    reversal the table lags the motor by exactly ``width``. The gap starts centred. Inertia and
    friction stay lumped on the drive (the rigid-body assumption of Sec. 3.2 of the thesis);
    whether the controller sees the gap depends on the axis' ``feedback``: a motor encoder
    (semi-closed loop) does not, a linear scale at the table (closed loop) does.
    """

    width: float

    UNITS: ClassVar[dict[str, str]] = {"width": "mm"}
    TABLE: ClassVar[str] = "backlash"

    def __post_init__(self) -> None:
        self._nonnegative("width")
        if self.width > 10.0:
            raise self._fail("width", "must be at most 10 mm (a backlash, not a gap)")
