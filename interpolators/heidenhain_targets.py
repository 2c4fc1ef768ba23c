"""Machine points of the axis words of Heidenhain conversational blocks: absolute (``X``) and incremental
(``IX``) program coordinates through the active transformations (cycles 8, 10, 11, 26) and datum, or, under
``M91`` / ``M92``, machine coordinates (the machine state's coordinates: :class:`interpolators.heidenhain.Machine`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.heidenhain_words import Word

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine

__all__ = ["plane_coords", "program_target"]


def plane_coords(seen: dict[str, Word], m: Machine, where: Where, *, m9x: int | None) -> tuple[np.ndarray, set]:
    """Machine end point [mm] of the axis words of a block, and the axes written (M91: machine
    coordinates, M92: from ``context.home``; neither transformed; ``m9x`` 130: M130's untilted coordinates of a
    tilted plane, the tool length added). Under M91/M92 the tool length is not added
    and a radius compensation stays in force (TNC 310 user's manual, 7.3 "Miscellaneous functions for
    coordinate data": "Radius compensation remains the same in blocks that are programmed with M91 or M92.
    The tool length, however, is not compensated"; the TNC 360 manual's M91/M92 page alike)."""
    values = {k: seen[k].value * m.scale for k in ("X", "Y", "Z", "IX", "IY", "IZ") if k in seen}
    if m9x is None:
        return program_target(m, values, m.pos)
    if m9x == 130:  # M130 in a tilted plane: the untilted coordinates, tool length included (heidenhain_motion)
        origin = np.add(m.preset_value(), m.tilt.base_shift, dtype=float)
        origin[m.plane] += m.tool_length
        return _absolute_target(values, m.pos, origin)
    origin = np.zeros(3) if m9x == 91 else np.array(m.context.home, dtype=float)
    return _absolute_target(values, m.pos, origin)


def _absolute_target(values: dict[str, float], base: np.ndarray, origin: np.ndarray) -> tuple[np.ndarray, set]:
    """``base`` with the axes of ``values`` [mm] set: absolute from ``origin``, ``I`` from ``base``."""
    target = np.array(base, dtype=float)
    written = set()
    for i, a in enumerate("XYZ"):
        if a in values:
            target[i] = origin[i] + values[a]
            written.add(i)
        elif "I" + a in values:
            target[i] = base[i] + values["I" + a]
            written.add(i)
    return target, written


def program_target(m: Machine, values: dict[str, float], base: np.ndarray) -> tuple[np.ndarray, set]:
    """Machine point [mm] of program axis values [mm] (``"X"`` absolute, ``"IX"`` incremental) from the
    machine point ``base``, through the active transformations; an axis not written keeps its program
    coordinate (with none active: its machine coordinate, exactly)."""
    if m.transform.identity:
        return _absolute_target(values, base, m.origin())
    prog, written = _absolute_target(values, m.to_program(base), np.zeros(3))
    return m.to_machine(prog), written
