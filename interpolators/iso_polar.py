"""LinuxCNC polar coordinates: ``@`` distance and ``^`` angle in place of X and Y (G17 only).

LinuxCNC G-code overview, "Polar Coordinates", and its interpreter (``find_ends`` in
``src/emc/rs274ngc/interp_find.cc``, ``CYCLE_MACRO`` in ``interp_internal.hh``):

- G90: the end point is ``(@ cos ^, @ sin ^)`` about the program origin; a missing ``@`` keeps
  the current distance from the origin, a missing ``^`` the current angle.
- G91: ``@`` is added to the current distance from the origin and ``^`` to the current angle
  (so ``G91 @.5 ^90`` spirals out; ``G91 ^90`` steps round a circle), in that order.
- Polar words cannot stand with X or Y, only in the XY plane, and a G91 polar move (or an
  absolute one with ``@`` alone) is indeterminate at the origin.
"""

from __future__ import annotations

import math

__all__ = ["PolarError", "polar_xy", "POLAR_LETTERS"]

#: The two polar words: distance and angle [deg].
POLAR_LETTERS = ("@", "^")


class PolarError(ValueError):
    """Polar words that give no point; the reader adds the location."""


def polar_xy(x: float, y: float, *, distance: float | None, angle_deg: float | None,
             incremental: bool) -> tuple[float, float]:
    """The end point [program coordinates] of polar words from the current point ``(x, y)``.

    ``distance`` is in the same length unit as ``x`` and ``y``; ``None`` where the word is absent.
    """
    at_origin = x == 0.0 and y == 0.0
    if incremental:
        if at_origin:
            raise PolarError("G91 motion with polar coordinates is indeterminate at the origin")
        if distance is not None:
            theta, r = math.atan2(y, x), math.hypot(x, y) + distance
            x, y = r * math.cos(theta), r * math.sin(theta)
        if angle_deg is not None:
            theta, r = math.atan2(y, x) + math.radians(angle_deg), math.hypot(x, y)
            x, y = r * math.cos(theta), r * math.sin(theta)
        return x, y
    if distance is not None and angle_deg is None and at_origin:
        raise PolarError("polar distance @ without an angle ^ at the origin")
    r = distance if distance is not None else math.hypot(x, y)
    theta = math.radians(angle_deg) if angle_deg is not None else math.atan2(y, x)
    return r * math.cos(theta), r * math.sin(theta)
