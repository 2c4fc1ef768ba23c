"""Arc construction from programmed words (centre or radius), shared by both dialects."""

from __future__ import annotations

import math

import numpy as np

from toolpaths.geometry import PLANE_AXES, Arc
from vcnc.core.errors import InputError

__all__ = ["ARC_TOLERANCE", "ArcWordError", "arc_from_center", "arc_from_radius", "spiral_tolerance",
           "SPIRAL_ABS_TOLERANCE_MM", "SPIRAL_ABS_TOLERANCE_INCH", "SPIRAL_RELATIVE_TOLERANCE", "RADIUS_TOLERANCE_MM",
           "ARC_RULES", "center_arc_tolerance", "radius_arc_tolerance"]

#: Largest accepted difference between the start and end radius of a centre-programmed arc, and
#: largest accepted excess of the chord over the diameter of a radius-programmed arc [mm].
ARC_TOLERANCE: float = 0.002


#: LinuxCNC's end-radius tolerances of centre-format arcs (interp_internal.hh:
#: CENTER_ARC_RADIUS_TOLERANCE_MM/_INCH = 2 * 0.01 mm * sqrt 2 / 2 * 0.001 in * sqrt 2, and
#: SPIRAL_RELATIVE_TOLERANCE = 0.001), in mm.
SPIRAL_ABS_TOLERANCE_MM: float = 2 * 0.01 * math.sqrt(2.0)
SPIRAL_ABS_TOLERANCE_INCH: float = 2 * 0.001 * math.sqrt(2.0) * 25.4
SPIRAL_RELATIVE_TOLERANCE: float = 0.001

#: LinuxCNC's tolerance of radius-format arcs (interp_internal.hh RADIUS_TOLERANCE_INCH = 0.00005 in,
#: RADIUS_TOLERANCE_MM the same length in mm; interp_arc.cc arc_data_r accepts a half chord longer
#: than |R| by at most this and then takes the arc as a half circle) [mm].
RADIUS_TOLERANCE_MM: float = 0.00005 * 25.4


def spiral_tolerance(start: np.ndarray, end: np.ndarray, center: np.ndarray, *, plane: int, inch: bool) -> float:
    """Largest end-radius mismatch [mm] LinuxCNC accepts for this centre-format arc.

    LinuxCNC (interp_arc.cc, ``arc_data_ijk``) refuses an arc when the difference of the start and
    end radii exceeds 100 times the absolute tolerance, or exceeds both the absolute tolerance
    (0.0283 mm; 0.00283 in under G20) and 0.1 % of the larger radius. Within that it runs a
    spiral; vcnc moves the centre onto the chord's bisector instead (an exact arc through both
    programmed end points), which departs from LinuxCNC's spiral by at most the mismatch.
    """
    a, b, c = _in_plane(start, plane), _in_plane(end, plane), _in_plane(center, plane)
    rmax = max(float(np.hypot(*(a - c))), float(np.hypot(*(b - c))))
    abs_tol = SPIRAL_ABS_TOLERANCE_INCH if inch else SPIRAL_ABS_TOLERANCE_MM
    return min(100.0 * abs_tol, max(abs_tol, SPIRAL_RELATIVE_TOLERANCE * rmax))


#: Controls whose end-radius rule is written here (``Dialect.arc_rule``).
ARC_RULES: tuple[str, ...] = ("linuxcnc", "grbl")

#: grbl 1.1's end-radius rule of centre-format arcs (gcode.c, "[Arc definition error]"): a mismatch
#: above 0.005 mm is refused when it exceeds 0.5 mm or 0.1 % of the start radius [mm, -, mm].
GRBL_ABS_TOLERANCE_MM: float = 0.005
GRBL_RELATIVE_TOLERANCE: float = 0.001
GRBL_MAX_MISMATCH_MM: float = 0.5

#: Excess of a radius-format arc's chord over the diameter that is floating-point noise, not a
#: programming error [mm] (grbl refuses any excess: ``4 R^2 - chord^2 < 0`` is error 33).
_FLOAT_NOISE_MM: float = 1e-9


def center_arc_tolerance(start: np.ndarray, end: np.ndarray, center: np.ndarray, *, plane: int, inch: bool,
                         rule: str = "linuxcnc") -> float:
    """Largest end-radius mismatch [mm] the control of ``rule`` accepts for this centre-format arc.

    ``"linuxcnc"``: :func:`spiral_tolerance`. ``"grbl"``: ``max(0.005, min(0.5, 0.001 * r_start))``
    mm whatever the units (grbl converts to mm before its check; gcode.c of grbl 1.1). Fanuc and
    Haas check against a machine parameter (Fanuc No. 3410, set by the machine builder; alarm
    PS0020 above it), which vcnc does not know: their dialects use LinuxCNC's rule.
    """
    if rule == "grbl":
        a, c = _in_plane(start, plane), _in_plane(center, plane)
        r_start = float(np.hypot(*(a - c)))
        return max(GRBL_ABS_TOLERANCE_MM, min(GRBL_MAX_MISMATCH_MM, GRBL_RELATIVE_TOLERANCE * r_start))
    return spiral_tolerance(start, end, center, plane=plane, inch=inch)


def radius_arc_tolerance(rule: str = "linuxcnc") -> float:
    """Largest excess of a radius-format arc's chord over the diameter [mm] the control of ``rule``
    accepts (then a half circle): LinuxCNC twice ``RADIUS_TOLERANCE_MM`` (its tolerance is on the
    half chord, interp_arc.cc ``arc_data_r``); grbl none (gcode.c: ``h_x2_div_d < 0`` is "Arc radius
    error")."""
    return _FLOAT_NOISE_MM if rule == "grbl" else 2.0 * RADIUS_TOLERANCE_MM


class ArcWordError(ValueError):
    """Arc words that describe no arc; the parser adds the location."""

    def __init__(self, message: str, expected: str) -> None:
        super().__init__(message)
        self.message = message
        self.expected = expected


def _arc(start: np.ndarray, end: np.ndarray, center: np.ndarray, *, ccw: bool, plane: int) -> Arc:
    try:
        return Arc(start, end, center, ccw=ccw, plane=plane)
    except InputError as exc:  # numerically degenerate (e.g. tiny radius at huge coordinates)
        raise ArcWordError(f"degenerate arc: {exc.message}", "an arc with a radius well above 1e-9 mm") from None


def _in_plane(v: np.ndarray, plane: int) -> np.ndarray:
    p, q = PLANE_AXES[plane]
    return np.array([v[p], v[q]])


def arc_from_center(
    start: np.ndarray,
    end: np.ndarray,
    center: np.ndarray,
    *,
    ccw: bool,
    plane: int,
    tolerance: float = ARC_TOLERANCE,
) -> Arc:
    """Arc from start to end about a programmed centre.

    Parameters
    ----------
    start, end, center : ndarray, shape (3,)
        [mm]. The centre's normal coordinate is ignored.
    ccw : bool
        Counter-clockwise (G03 / DR+).
    plane : int
        Normal-axis index (2: G17 XY, 1: G18 ZX, 0: G19 YZ).
    tolerance : float
        Largest accepted ``|end radius - start radius|`` [mm].

    Returns
    -------
    Arc
        End equal to start in the plane gives a full circle. Otherwise the centre is moved to
        the nearest point of the chord's perpendicular bisector (by at most ``tolerance``) so that
        both ends lie exactly on the circle.

    Raises
    ------
    ArcWordError
        Radius zero, or end point off the circle by more than ``tolerance``.
    """
    p, q = PLANE_AXES[plane]
    a, b, c = _in_plane(start, plane), _in_plane(end, plane), _in_plane(center, plane)
    ra = float(np.hypot(*(a - c)))
    rb = float(np.hypot(*(b - c)))
    if ra <= 1e-9:
        raise ArcWordError("arc radius is zero: the centre is the start point", "a centre offset I/J/K != 0")
    if abs(ra - rb) > tolerance:
        raise ArcWordError(
            f"arc end point is not on the circle: start radius {ra:.6g} mm, end radius {rb:.6g} mm "
            f"(difference {abs(ra - rb):.3g} mm > tolerance {tolerance:g} mm)",
            "an end point on the circle through the start point",
        )
    chord = b - a
    clen = float(np.hypot(*chord))
    if clen > 1e-12 * max(ra, 1.0):
        m = 0.5 * (a + b)
        perp = np.array([-chord[1], chord[0]]) / clen
        c = m + perp * float((c - m) @ perp)
    else:
        b = a  # full circle: the end is the start in the plane
    c3 = np.array(start, dtype=float)
    c3[p], c3[q] = c[0], c[1]
    e3 = np.array(end, dtype=float)
    e3[p], e3[q] = b[0], b[1]
    return _arc(start, e3, c3, ccw=ccw, plane=plane)


def arc_from_radius(
    start: np.ndarray,
    end: np.ndarray,
    radius: float,
    *,
    ccw: bool,
    plane: int,
    tolerance: float = ARC_TOLERANCE,
) -> Arc:
    """Arc from start to end with a programmed radius (ISO ``R``, Heidenhain ``CR``).

    Parameters
    ----------
    radius : float
        [mm]; positive for a sweep of at most 180 degrees, negative for more.
    tolerance : float
        Largest accepted excess of the chord over the diameter [mm]; within it the arc is a
        half circle.

    Raises
    ------
    ArcWordError
        Zero radius, end point equal to start (a full circle needs a centre), or chord longer
        than the diameter by more than ``tolerance``.
    """
    p, q = PLANE_AXES[plane]
    a, b = _in_plane(start, plane), _in_plane(end, plane)
    r = abs(float(radius))
    if r <= 1e-9:
        raise ArcWordError("arc radius R must not be zero", "R != 0 mm")
    chord = b - a
    clen = float(np.hypot(*chord))
    if clen <= 1e-9:
        raise ArcWordError(
            "a radius arc cannot end at its start point (a full circle needs a centre)",
            "I/J/K (or CC) for a full circle",
        )
    if clen > 2.0 * r + tolerance:
        raise ArcWordError(
            f"arc chord {clen:.6g} mm is longer than the diameter 2R = {2 * r:.6g} mm", "|R| >= half the chord"
        )
    h = math.sqrt(max(r * r - 0.25 * clen * clen, 0.0))
    left = np.array([-chord[1], chord[0]]) / clen
    # the centre of a <=180 degree counter-clockwise arc lies to the left of the chord
    side = 1.0 if (ccw == (radius > 0)) else -1.0
    c = 0.5 * (a + b) + side * h * left
    if clen > 2.0 * r:  # within tolerance: a half circle of radius clen/2
        c = 0.5 * (a + b)
    c3 = np.array(start, dtype=float)
    c3[p], c3[q] = c[0], c[1]
    return _arc(start, end, c3, ccw=ccw, plane=plane)
