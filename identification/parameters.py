"""The parameters of the reduced closed-loop model, Eq. (3.3) of the thesis: names and units."""

from __future__ import annotations

__all__ = ["PARAMETER_NAMES", "PARAMETER_UNITS"]

#: Parameter names of Eq. (3.3), in the order of the model file.
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
