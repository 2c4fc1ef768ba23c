"""Axis names and their units: linear axes in mm, rotary axes in degrees."""

from __future__ import annotations

__all__ = ["AXIS_NAMES", "ROTARY_AXES", "axis_unit"]

#: Axis names in their canonical order (ARCHITECTURE.md, capture file).
AXIS_NAMES: tuple[str, ...] = ("x", "y", "z", "a", "b", "c")

#: Rotary axes, positioned in degrees (ISO 841: A, B, C turn about X, Y, Z).
ROTARY_AXES: frozenset[str] = frozenset({"a", "b", "c"})


def axis_unit(axis: str, *, small: bool = False) -> str:
    """Unit of a position on ``axis``: ``"mm"`` or ``"deg"``; ``small=True`` gives the unit of
    errors, 1/1000 of it (``"um"`` or ``"mdeg"``)."""
    if axis.lower() in ROTARY_AXES:
        return "mdeg" if small else "deg"
    return "um" if small else "mm"
