"""Path geometry of Heidenhain conversational programs: polar coordinates, CT, RND and CHF.

Sources: HEIDENHAIN TNC 620 Klartext programming user's manual (01/2022), "Path contours -
Cartesian coordinates" (p. 154-163: CHF "chamfer between two straight lines, chamfer side
length"; RND "circular arc with tangential connection to the preceding and subsequent contour
elements, rounding radius R"; CT "circular arc with tangential connection to the preceding
contour element, coordinates of the arc end point") and "Path contours - polar coordinates"
(TNC 620 manual 340 56x-01, p. 173; TNC 426/430 manual p. 153: the pole ``CC``; ``LP PR PA``;
``CP PA DR`` about the pole with radius = distance start-pole; a helix is ``CP IPA`` with a
tool-axis coordinate; "for incremental coordinates, enter the same sign for DR and PA").

Angles ``PA`` are measured from the angle reference axis of the working plane (X in XY, Y in
YZ, Z in ZX: the first axis ``p`` of :data:`toolpaths.geometry.PLANE_AXES`) towards the second.
The corner geometry of RND and CHF lives in :mod:`interpolators.corners` (shared with the ISO
reader's ``,R`` / ``,C``) and is re-exported here.
"""

from __future__ import annotations

import math

import numpy as np

from interpolators.arcs import ARC_TOLERANCE
from interpolators.corners import (  # noqa: F401  (re-exported: the corner geometry lives there)
    PathGeometryError,
    chamfer_corner,
    end_tangent,
    on_circle,
    round_corner,
    round_elements,
)
from toolpaths.geometry import PLANE_AXES, Arc, Line

__all__ = ["PathGeometryError", "arc_end_tolerance", "polar_point", "polar_angle", "helical_arc", "end_tangent",
           "tangential_arc", "round_corner", "round_elements", "chamfer_corner", "approach_start",
           "departure_element", "approach_lct", "departure_lct", "contour_arc_radius"]


#: Places after the decimal point of a TNC coordinate: the input format "-99 999.9999 to
#: +99 999.9999 (5, 4)" of positions, coordinates and circle radii (TNC 640 user's manual DIN/ISO
#: 34059x-05, 1/2015, "Technical information", p. 631); the same digits in inch programs.
COORDINATE_DECIMALS: int = 4


def arc_end_tolerance(inch: bool) -> float:
    """Largest accepted difference [mm] between the start and end radius of a ``C`` arc about ``CC``.

    :data:`interpolators.arcs.ARC_TOLERANCE` (0.002 mm), widened to what the program's own digits
    can carry: the start (the previous end point), the end point and the centre are each rounded
    to the 4 places of the input format (:data:`COORDINATE_DECIMALS`), each off by up to
    ``sqrt(2) / 2 * 1e-4`` program units in the plane, so the two radii differ by up to
    ``(1 + 1 + 2) * sqrt(2) / 2 * 1e-4 = 2 * sqrt(2) * 1e-4`` units (the form of LinuxCNC's
    ``CENTER_ARC_RADIUS_TOLERANCE_INCH = 2 * 0.001 * M_SQRT2``, interp_internal.hh, for 3 places).
    In a millimetre program that is 0.00028 mm (below 0.002 mm: no change); in an inch program
    0.0001 in is 0.00254 mm, and a CAM system's inch arcs written to 4 places miss the circle by up
    to 0.0072 mm. The TNC's own end-point tolerance is a machine parameter set by the machine
    builder; its value is not in the user's manuals found, which is why the rounding of the input
    format is the bound taken here.
    """
    digits = 2.0 * math.sqrt(2.0) * 10.0 ** -COORDINATE_DECIMALS * (25.4 if inch else 1.0)
    return max(ARC_TOLERANCE, digits)


def polar_point(pole: np.ndarray, radius: float, angle_deg: float, *, plane: int, base: np.ndarray) -> np.ndarray:
    """Point at ``radius`` [mm] and ``angle_deg`` [deg] about ``pole`` in the plane; other axes from ``base``."""
    p, q = PLANE_AXES[plane]
    out = np.array(base, dtype=float)
    a = math.radians(angle_deg)
    out[p] = pole[p] + radius * math.cos(a)
    out[q] = pole[q] + radius * math.sin(a)
    return out


def polar_angle(point: np.ndarray, pole: np.ndarray, *, plane: int) -> tuple[float, float]:
    """Polar radius [mm] and angle [deg] of ``point`` about ``pole`` in the plane."""
    p, q = PLANE_AXES[plane]
    dx, dy = point[p] - pole[p], point[q] - pole[q]
    return math.hypot(dx, dy), math.degrees(math.atan2(dy, dx))


def helical_arc(start: np.ndarray, pole: np.ndarray, sweep_deg: float, *, plane: int, axis_end: float) -> Arc:
    """Arc (helix when ``axis_end`` differs from the start) about ``pole`` through ``sweep_deg`` [deg].

    ``sweep_deg`` is signed (positive counter-clockwise) and may exceed 360 degrees (``CP IPA+1834``):
    the whole turns become :class:`~toolpaths.geometry.Arc` ``turns``.
    """
    radius, a0 = polar_angle(start, pole, plane=plane)
    if radius <= 1e-9:
        raise PathGeometryError("arc radius is zero: the start point is the pole CC", "a pole CC away from the start")
    if abs(sweep_deg) <= 1e-9:
        raise PathGeometryError("arc angle is zero", "IPA != 0 (or PA different from the start angle)")
    ccw = sweep_deg > 0
    magnitude = abs(sweep_deg)
    whole = math.floor(magnitude / 360.0 + 1e-12)
    rest = magnitude - 360.0 * whole
    end = polar_point(pole, radius, a0 + sweep_deg, plane=plane, base=start)
    end[plane] = axis_end
    if rest <= 1e-9:  # a whole number of turns: end equals start in the plane
        p, q = PLANE_AXES[plane]
        end[p], end[q] = start[p], start[q]
        turns = whole - 1
    else:
        turns = whole
    center = np.array(start, dtype=float)
    p, q = PLANE_AXES[plane]
    center[p], center[q] = pole[p], pole[q]
    return Arc(start, end, center, ccw=ccw, plane=plane, turns=turns)


def tangential_arc(start: np.ndarray, tangent: np.ndarray, end: np.ndarray, *, plane: int) -> Arc:
    """Arc ``CT`` from ``start`` (leaving along the in-plane ``tangent``) to ``end``."""
    p, q = PLANE_AXES[plane]
    d = np.array([end[p] - start[p], end[q] - start[q]])
    left = np.array([-tangent[1], tangent[0]])
    dn = float(d @ left)
    dd = float(d @ d)
    if dd <= 1e-18 or abs(dn) <= 1e-9 * math.sqrt(dd):
        raise PathGeometryError("CT end point lies on the tangent of the preceding element (no arc)",
                                "an end point off the preceding element's tangent (or an L block)")
    s = dd / (2.0 * dn)
    center = np.array(start, dtype=float)
    center[p] += s * left[0]
    center[q] += s * left[1]
    # exactly on the circle: both ends at radius |s| by construction, up to rounding
    return Arc(start, on_circle(end, center, abs(s), plane), center, ccw=s > 0, plane=plane)


def _turned(point: np.ndarray, centre: np.ndarray, angle_deg: float, plane: int) -> np.ndarray:
    """``point`` turned about ``centre`` by ``angle_deg`` [deg] (counter-clockwise positive) in the plane."""
    p, q = PLANE_AXES[plane]
    a = math.radians(angle_deg)
    dx, dy = point[p] - centre[p], point[q] - centre[q]
    out = np.array(point, dtype=float)
    out[p] = centre[p] + dx * math.cos(a) - dy * math.sin(a)
    out[q] = centre[q] + dx * math.sin(a) + dy * math.cos(a)
    return out


def _arc_side(form: str, side: float, radius: float, angle: float) -> bool:
    """The sense of an approach/departure arc (TNC7 user's manual, "APPR CT": RL and R > 0, or RR
    and R < 0: counter-clockwise; RL and R < 0, or RR and R > 0: clockwise)."""
    if radius == 0 or not 0 < angle <= 360:
        raise PathGeometryError(f"{form} needs R != 0 and 0 < CCA <= 360", "R+.. (or R-..) and CCA between 0 and 360")
    return (side > 0) == (radius > 0)


def contour_arc_radius(form: str, radius: float, tool_radius: float) -> float:
    """The radius of the contour arc whose offset by ``tool_radius`` [mm] is the tool path of radius
    ``radius`` [mm] of an ``APPR/DEP CT`` (signed: R > 0 turns towards the tool's side) or ``LCT`` arc.

    The R of these arcs is the radius of the tool's path, not of a contour element offset by the tool
    radius: iTNC 530 conversational user's manual (2/2011), 6.3 "Contour approach and departure",
    APPR LCT: "Once these lines are known, the radius then suffices to completely define the tool path";
    TNC7 manual "APPR LCT", "The circular path is uniquely defined by the radius R". HEIDENHAIN's own
    examples approach with an arc smaller than the tool (TNC 426/430 user's manual 280 476, chapter 6
    "Example: circular movements, Cartesian": TOOL DEF 1 L+0 R+10 and APPR LCT .. R5 RL; "Example: full
    circle": R+12.5 and APPR LCT .. R5; "Example: helix": R+5 and APPR PCT .. CCA180 R+2 RL). An arc
    turning towards the tool's side (LCT always) has the tool inside it, so its contour radius is the
    tool path's plus the tool radius; one turning away, minus it (an error when nothing is left: our
    reading, no manual page found for that case)."""
    toward = form.endswith("LCT") or radius > 0
    rc = abs(radius) + tool_radius if toward else abs(radius) - tool_radius
    if rc <= 0:
        raise PathGeometryError(f"{form} R{radius:+g} turns away from the tool's side and is not larger than the "
                                f"tool radius {tool_radius:g} mm",
                                f"|R| > {tool_radius:g} (or R > 0: towards the tool)")
    return math.copysign(rc, radius)


def approach_start(form: str, pa: np.ndarray, tangent: np.ndarray, *, length: float, radius: float,
                   angle: float, side: float, plane: int) -> tuple[np.ndarray, Arc | None]:
    """The auxiliary point PH of ``APPR LT|LN|CT`` before the first contour point PA, and for CT the arc
    PH -> PA (TNC 640 user's manual, "Approaching and departing a contour"; TNC7 manual "APPR LN",
    "APPR CT").

    ``tangent`` is the first contour element's unit direction at PA in the plane (2-vector), ``side``
    +1 when the tool runs left of the contour (RL), -1 right (RR): LT puts PH ``length`` [mm] back
    along the tangent, LN ``length`` off the contour on the tool's side (perpendicular), CT at the
    start of the arc of ``radius`` [mm] through ``angle`` [deg] (CCA) that ends at PA tangentially.
    PH keeps PA's tool-axis coordinate (the caller moves it).
    """
    p, q = PLANE_AXES[plane]
    left = np.array([-tangent[1], tangent[0]])
    ph = np.array(pa, dtype=float)
    if form == "LT":
        ph[p], ph[q] = pa[p] - length * tangent[0], pa[q] - length * tangent[1]
        return ph, None
    if form == "LN":
        ph[p], ph[q] = pa[p] + side * length * left[0], pa[q] + side * length * left[1]
        return ph, None
    ccw = _arc_side("APPR CT", side, radius, angle)
    centre = np.array(pa, dtype=float)
    s = abs(radius) * (1.0 if ccw else -1.0)
    centre[p], centre[q] = pa[p] + s * left[0], pa[q] + s * left[1]
    ph = _turned(pa, centre, -angle if ccw else angle, plane)
    return ph, Arc(ph, np.array(pa, dtype=float), centre, ccw=ccw, plane=plane)


def departure_element(form: str, pe: np.ndarray, tangent: np.ndarray, *, length: float, radius: float,
                      angle: float, side: float, plane: int) -> Line | Arc:
    """The move of ``DEP LT|LN|CT`` from the last contour point PE (the mirror of
    :func:`approach_start`): LT ``length`` [mm] on along the last element's ``tangent``, LN
    ``length`` off the contour on the tool's side, CT the arc of ``radius`` through ``angle`` [deg]
    leaving PE tangentially."""
    p, q = PLANE_AXES[plane]
    left = np.array([-tangent[1], tangent[0]])
    pn = np.array(pe, dtype=float)
    if form in ("LT", "LN"):
        step = tangent if form == "LT" else side * left
        pn[p], pn[q] = pe[p] + length * step[0], pe[q] + length * step[1]
        return Line(np.array(pe, dtype=float), pn)
    ccw = _arc_side("DEP CT", side, radius, angle)
    centre = np.array(pe, dtype=float)
    s = abs(radius) * (1.0 if ccw else -1.0)
    centre[p], centre[q] = pe[p] + s * left[0], pe[q] + s * left[1]
    return Arc(np.array(pe, dtype=float), _turned(pe, centre, angle if ccw else -angle, plane), centre, ccw=ccw,
               plane=plane)


def _tangent_point(centre: np.ndarray, radius: float, point: np.ndarray, *, ccw: bool, leaving: bool,
                   plane: int) -> np.ndarray:
    """The point where a line through ``point`` touches the circle (``centre``, ``radius``) so that the
    line runs on along the circle's sense (``ccw``): into the circle (``leaving`` False: the line ends
    there) or out of it (``leaving`` True: the line starts there). Tool-axis coordinate of ``centre``."""
    p, q = PLANE_AXES[plane]
    v = np.array([point[p] - centre[p], point[q] - centre[q]])
    dist = float(np.hypot(*v))
    if dist <= radius * (1 + 1e-12):
        raise PathGeometryError(f"the point lies inside the arc of radius {radius:g} mm (no tangent line)",
                                "a smaller R or a point farther from the contour")
    theta, half = math.atan2(v[1], v[0]), math.acos(radius / dist)
    for phi in (theta + half, theta - half):
        u = np.array([math.cos(phi), math.sin(phi)])
        along = np.array([-u[1], u[0]]) if ccw else np.array([u[1], -u[0]])  # the circle's direction at u
        line = v - radius * u  # from the tangent point to the point
        if (float(line @ along) > 0) == leaving:
            out = np.array(centre, dtype=float)
            out[p], out[q] = centre[p] + radius * u[0], centre[q] + radius * u[1]
            return out
    raise AssertionError("one of the two tangents runs along the circle")  # pragma: no cover


def _lct_centre(point: np.ndarray, tangent: np.ndarray, radius: float, side: float, plane: int) -> np.ndarray:
    """Centre of the ``APPR/DEP LCT`` arc of ``radius`` [mm] through ``point`` (PA or PE), tangent there to
    the contour's unit ``tangent`` (in-plane components), on the tool's ``side`` (+1 RL, -1 RR)."""
    p, q = PLANE_AXES[plane]
    centre = np.array(point, dtype=float)
    centre[p], centre[q] = point[p] - side * radius * tangent[1], point[q] + side * radius * tangent[0]
    return centre


def _on_contour(point: np.ndarray, centre: np.ndarray, factor: float, plane: int) -> np.ndarray:
    """``point`` moved radially from ``centre`` by ``factor`` in the plane (tool path -> contour arc)."""
    p, q = PLANE_AXES[plane]
    out = np.array(point, dtype=float)
    out[p], out[q] = centre[p] + factor * (point[p] - centre[p]), centre[q] + factor * (point[q] - centre[q])
    return out


def _lct_touch(point: np.ndarray, other: np.ndarray, tangent: np.ndarray, radius: float, side: float, plane: int,
               tool_radius: float, *, leaving: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The construction ``APPR LCT`` and ``DEP LCT`` share: the arc of ``radius`` [mm] through ``point`` (PA or
    PE) tangent to the contour there (:func:`_lct_centre`), and PH, where the line from or to ``other`` (PS or
    PN, taken at ``point``'s tool-axis coordinate) touches the tool's path, ``tool_radius`` [mm] inside the arc,
    moved out onto the arc. Returns (centre, ``other`` at that coordinate, PH)."""
    centre = _lct_centre(point, tangent, radius, side, plane)
    free = np.array(other, dtype=float)
    free[plane] = point[plane]
    path = radius - tool_radius
    ph = _on_contour(_tangent_point(centre, path, free, ccw=side > 0, leaving=leaving, plane=plane), centre,
                     radius / path, plane)
    return centre, free, ph


def approach_lct(ps: np.ndarray, pa: np.ndarray, tangent: np.ndarray, *, radius: float, side: float,
                 plane: int, tool_radius: float = 0.0) -> tuple[np.ndarray, Arc]:
    """``APPR LCT`` (TNC7 user's manual, "APPR LCT"): the line from PS touches at PH the arc of
    ``radius`` [mm] that ends at PA tangentially to the first contour element (``tangent``); the arc
    turns towards the tool's ``side`` (RL: counter-clockwise). ``radius`` is the contour arc's
    (:func:`contour_arc_radius`): the line touches the tool's path, ``tool_radius`` [mm] inside it.
    Returns PH (PA's tool-axis coordinate) and the arc PH -> PA."""
    if not radius > tool_radius:
        raise PathGeometryError("APPR LCT needs R > 0", "R+.. [mm]")
    centre, _, ph = _lct_touch(pa, ps, tangent, radius, side, plane, tool_radius, leaving=False)
    return ph, Arc(ph, np.array(pa, dtype=float), centre, ccw=side > 0, plane=plane)


def departure_lct(pe: np.ndarray, pn: np.ndarray, tangent: np.ndarray, *, radius: float, side: float,
                  plane: int, tool_radius: float = 0.0) -> tuple[Arc, Line]:
    """``DEP LCT`` (TNC7 user's manual, "DEP LCT"): the arc of ``radius`` [mm] leaving PE tangentially to
    the last contour element (``tangent``), turning towards the tool's ``side``, to PH, where the line
    to PN (in the plane of PE) touches the tool's path (``tool_radius`` [mm] inside the arc, as in
    :func:`approach_lct`)."""
    if not radius > tool_radius:
        raise PathGeometryError("DEP LCT needs R > 0", "R+.. [mm]")
    centre, end, ph = _lct_touch(pe, pn, tangent, radius, side, plane, tool_radius, leaving=True)
    return Arc(np.array(pe, dtype=float), ph, centre, ccw=side > 0, plane=plane), Line(ph, end)
