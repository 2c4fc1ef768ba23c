"""Names every package shares: the axes and their units (linear axes in mm, rotary axes in degrees),
and the parameters of the reduced closed-loop axis model, Eq. (3.3) of the thesis, with their units."""

from __future__ import annotations

__all__ = ["AXIS_NAMES", "ROTARY_AXES", "ROTARY_NAMES", "SECONDARY_NAMES", "EXTRA_NAMES", "axis_unit",
           "PARAMETER_NAMES", "PARAMETER_UNITS"]

#: Axis names in their canonical order (ARCHITECTURE.md, capture file): LinuxCNC's order of the nine
#: axes, X Y Z A B C U V W (LinuxCNC G-code overview, "Numbered Parameters" 5221-5229).
AXIS_NAMES: tuple[str, ...] = ("x", "y", "z", "a", "b", "c", "u", "v", "w")

#: Rotary axes, positioned in degrees (ISO 841: A, B, C turn about X, Y, Z).
ROTARY_AXES: frozenset[str] = frozenset({"a", "b", "c"})

#: Rotary axes in their canonical order (the columns of rotary position arrays).
ROTARY_NAMES: tuple[str, str, str] = ("a", "b", "c")

#: Secondary linear axes, parallel to X, Y, Z, positioned in mm (LinuxCNC G-code overview, "U V W").
SECONDARY_NAMES: tuple[str, str, str] = ("u", "v", "w")

#: The axes beyond X, Y, Z in their canonical order (the columns of ``Block.extra_start`` and
#: ``extra_target``): the rotary axes [deg], then the secondary linear axes [mm].
EXTRA_NAMES: tuple[str, ...] = ROTARY_NAMES + SECONDARY_NAMES


def axis_unit(axis: str, *, small: bool = False) -> str:
    """Unit of a position on ``axis``: ``"mm"`` or ``"deg"``; ``small=True`` gives the unit of
    errors, 1/1000 of it (``"um"`` or ``"mdeg"``)."""
    if axis.lower() in ROTARY_AXES:
        return "mdeg" if small else "deg"
    return "um" if small else "mm"


#: Parameter names of the reduced model, Eq. (3.3), in the order of the model file.
PARAMETER_NAMES: tuple[str, ...] = ("a1", "a2", "a3", "b0", "b1", "b2", "d0", "d1")

#: Unit of each parameter.
PARAMETER_UNITS: dict[str, str] = {
    "a1": "1/s",
    "a2": "1/s^2",
    "a3": "1/s^3",
    "b0": "-",
    "b1": "1/s",
    "b2": "1/s^2",
    "d0": "mm/s^2",
    "d1": "mm/s^2",
}
