"""Contouring test programs: circle, diamond, back-and-forth."""

from __future__ import annotations

import math
from collections.abc import Sequence

from toolpaths.writer import ProgramWriter
from vcnc.core.errors import InputError

__all__ = ["circle", "diamond", "back_and_forth"]


def _positive(name: str, value: float, unit: str) -> float:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name} must be a finite value > 0 {unit}, got {value!r}")
    return float(value)


def _center(center: Sequence[float]) -> tuple[float, float]:
    c = tuple(float(v) for v in center)
    if len(c) != 2 or not all(math.isfinite(v) for v in c):
        raise InputError(f"center must be two finite coordinates (x, y) [mm], got {center!r}")
    return c  # type: ignore[return-value]


def circle(
    radius: float = 10.0,
    feed: float = 12000.0,
    *,
    center: Sequence[float] = (0.0, 0.0),
    ccw: bool = True,
    dialect: str = "iso",
) -> str:
    """Full circle in the XY plane, started and ended at its rightmost point.

    Parameters
    ----------
    radius : float
        [mm]
    feed : float
        [mm/min] (12000 mm/min = 200 mm/s, the thesis' contouring feed, Sec. 4.3.2).
    center : (float, float)
        Centre (x, y) [mm].
    ccw : bool
        Counter-clockwise (G03 / DR+) or clockwise.
    dialect : {"iso", "heidenhain"}

    Returns
    -------
    str
        Program: rapid to ``(cx + R, cy)``, one full-circle block, M30.
    """
    r = _positive("radius", radius, "mm")
    f = _positive("feed", feed, "mm/min")
    cx, cy = _center(center)
    w = ProgramWriter(dialect, name="CIRCLE", comment=f"circle R{r:g} mm at F{f:g} mm/min")
    start = (cx + r, cy)
    w.rapid({"x": start[0], "y": start[1]})
    w.arc(start, (cx, cy), start, ccw=ccw, feed=f)
    return w.end()


def diamond(
    side: float = 20.0,
    feed: float = 12000.0,
    *,
    center: Sequence[float] = (0.0, 0.0),
    dialect: str = "iso",
) -> str:
    """Square turned by 45 degrees (a diamond), run counter-clockwise from its right vertex.

    Parameters
    ----------
    side : float
        Side length [mm]; the vertices lie ``side / sqrt(2)`` from the centre on the axes.
    feed : float
        [mm/min]
    center : (float, float)
        [mm]
    dialect : {"iso", "heidenhain"}

    Returns
    -------
    str
        Program: rapid to the right vertex, four G01 sides, M30.
    """
    a = _positive("side", side, "mm")
    f = _positive("feed", feed, "mm/min")
    cx, cy = _center(center)
    d = a / math.sqrt(2.0)
    w = ProgramWriter(dialect, name="DIAMOND", comment=f"diamond side {a:g} mm at F{f:g} mm/min")
    w.rapid({"x": cx + d, "y": cy})
    for x, y in ((cx, cy + d), (cx - d, cy), (cx, cy - d), (cx + d, cy)):
        w.line({"x": x, "y": y}, feed=f)
    return w.end()


def back_and_forth(
    length: float = 20.0,
    feed: float = 4242.6,
    *,
    axes: Sequence[str] = ("x", "y"),
    cycles: int = 1,
    dialect: str = "iso",
) -> str:
    """Forward and backward moves of +/-``length`` along the diagonal of ``axes``.

    With the defaults this is the validation trajectory of the thesis (Sec. 4.3.1): +/-20 mm
    along a 45 degree line in XY at 70.71 mm/s (4242.6 mm/min).

    Parameters
    ----------
    length : float
        Distance from the origin to each turning point along the line [mm].
    feed : float
        Path feed [mm/min].
    axes : sequence of str
        Axes moved together (equal shares: the line's direction is their diagonal).
    cycles : int
        Number of out-and-back cycles (origin -> +length -> -length -> origin).
    dialect : {"iso", "heidenhain"}
    """
    L = _positive("length", length, "mm")
    f = _positive("feed", feed, "mm/min")
    ax = [str(a).lower() for a in axes]
    if not ax or any(a not in ("x", "y", "z") for a in ax) or len(set(ax)) != len(ax):
        raise InputError(f"axes must be distinct names among x, y, z, got {axes!r}")
    if not (isinstance(cycles, int) and cycles >= 1):
        raise InputError(f"cycles must be an integer >= 1, got {cycles!r}")
    c = L / math.sqrt(len(ax))
    w = ProgramWriter(dialect, name="BACKFORTH", comment=f"+/-{L:g} mm along {'+'.join(ax)} at F{f:g} mm/min")
    origin = {a: 0.0 for a in ax}
    w.rapid(origin)
    for _ in range(cycles):
        w.line({a: c for a in ax}, feed=f)
        w.line({a: -c for a in ax}, feed=f)
        w.line(origin, feed=f)
    return w.end()
