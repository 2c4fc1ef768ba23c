"""Corner geometry of contours: rounding (a tangent arc) and chamfering (a line) between two elements.

One home for what the Heidenhain reader calls ``RND`` / ``CHF`` (HEIDENHAIN TNC 620 Klartext
programming user's manual 01/2022, "Path contours - Cartesian coordinates", p. 154-163: CHF
"chamfer between two straight lines, chamfer side length"; RND "circular arc with tangential
connection to the preceding and subsequent contour elements, rounding radius R") and the ISO
reader calls ``,R`` / ``,C`` (Fanuc Series 0i-MF / 30i operator's manual, "Optional chamfering and
corner R"; Haas mill operator's manual, "G01 Corner Rounding and Chamfering";
:mod:`interpolators.iso_corners`). The elements are :class:`~toolpaths.geometry.Line` and
:class:`~toolpaths.geometry.Arc` in the working plane ``plane`` (the tool axis index, as
:data:`toolpaths.geometry.PLANE_AXES`); errors are :class:`PathGeometryError`, to which the
readers add the file, line and word. ``word`` names the control's word in the messages
(``"RND"``, ``",R"``).
"""

from __future__ import annotations

import math

import numpy as np

from toolpaths.geometry import PLANE_AXES, Arc, Line, piece_of

__all__ = ["PathGeometryError", "end_tangent", "on_circle", "round_corner", "round_elements", "chamfer_corner",
           "chamfer_elements"]


class PathGeometryError(ValueError):
    """Path words that describe no contour element; the reader adds the location."""

    def __init__(self, message: str, expected: str) -> None:
        super().__init__(message)
        self.message = message
        self.expected = expected



def end_tangent(segment: Line | Arc, plane: int) -> np.ndarray:
    """Unit tangent at the end of ``segment`` projected on the plane, as an in-plane 2-vector."""
    t = np.asarray(segment.tangent_at(segment.length), dtype=float).reshape(3)
    p, q = PLANE_AXES[plane]
    v = np.array([t[p], t[q]])
    n = float(np.hypot(*v))
    if n <= 1e-12:
        raise PathGeometryError("the preceding contour element has no direction in the working plane",
                                "a preceding line or arc in the working plane")
    return v / n



def on_circle(point: np.ndarray, center: np.ndarray, radius: float, plane: int) -> np.ndarray:
    p, q = PLANE_AXES[plane]
    out = np.array(point, dtype=float)
    v = np.array([out[p] - center[p], out[q] - center[q]])
    n = float(np.hypot(*v))
    out[p], out[q] = center[p] + v[0] * radius / n, center[q] + v[1] * radius / n
    return out


def _corner(a: np.ndarray, corner: np.ndarray, b: np.ndarray, plane: int, what: str):
    if abs(a[plane] - corner[plane]) > 1e-9 or abs(b[plane] - corner[plane]) > 1e-9:
        raise PathGeometryError(f"{what} needs two straight lines in the working plane",
                                "lines without a tool-axis move before and after the corner")
    p, q = PLANE_AXES[plane]
    u1 = np.array([corner[p] - a[p], corner[q] - a[q]])
    u2 = np.array([b[p] - corner[p], b[q] - corner[q]])
    l1, l2 = float(np.hypot(*u1)), float(np.hypot(*u2))
    if l1 <= 1e-9 or l2 <= 1e-9:
        raise PathGeometryError(f"{what} at a corner with a zero-length line", "two lines of non-zero length")
    return u1 / l1, u2 / l2, l1, l2


def round_corner(a: np.ndarray, corner: np.ndarray, b: np.ndarray, radius: float, *, plane: int,
                 word: str = "RND"):
    """``RND R``: the two tangent points and the rounding arc between lines a-corner and corner-b.

    Returns ``(t1, arc, t2)`` [mm]; raises :class:`PathGeometryError` when the lines are collinear
    or too short for the radius.
    """
    u1, u2, l1, l2 = _corner(a, corner, b, plane, word)
    if radius <= 0:
        raise PathGeometryError("rounding radius must be > 0", f"{word} R > 0 [mm]")
    cross = float(u1[0] * u2[1] - u1[1] * u2[0])
    turn = math.atan2(abs(cross), float(u1 @ u2))
    if turn <= 1e-9:
        raise PathGeometryError(f"{word} between collinear lines", "a corner between the lines")
    if turn >= math.pi - 1e-9:
        raise PathGeometryError(f"{word} at a reversal of direction", "a corner of less than 180 degrees")
    d = radius * math.tan(turn / 2.0)
    if d > l1 + 1e-9 or d > l2 + 1e-9:
        raise PathGeometryError(f"rounding radius {radius:g} mm does not fit: it needs {d:.6g} mm of each line",
                                f"a smaller {word} radius or longer lines")
    p, q = PLANE_AXES[plane]
    t1 = np.array(corner, dtype=float)
    t2 = np.array(corner, dtype=float)
    t1[p], t1[q] = corner[p] - u1[0] * d, corner[q] - u1[1] * d
    t2[p], t2[q] = corner[p] + u2[0] * d, corner[q] + u2[1] * d
    side = 1.0 if cross > 0 else -1.0
    center = np.array(t1)
    center[p] += -u1[1] * radius * side
    center[q] += u1[0] * radius * side
    arc = Arc(t1, on_circle(t2, center, radius, plane), center, ccw=cross > 0, plane=plane)
    return t1, arc, np.array(arc.end)


def chamfer_corner(a: np.ndarray, corner: np.ndarray, b: np.ndarray, length: float, *, plane: int,
                   word: str = "CHF"):
    """``CHF L``: the points at ``length`` [mm] before and after the corner (the chamfer's ends)."""
    u1, u2, l1, l2 = _corner(a, corner, b, plane, word)
    if length <= 0:
        raise PathGeometryError("chamfer length must be > 0", f"{word} > 0 [mm]")
    if length > l1 + 1e-9 or length > l2 + 1e-9:
        raise PathGeometryError(f"chamfer side length {length:g} mm is longer than a line of the corner",
                                "a chamfer shorter than both lines")
    p, q = PLANE_AXES[plane]
    t1 = np.array(corner, dtype=float)
    t2 = np.array(corner, dtype=float)
    t1[p], t1[q] = corner[p] - u1[0] * length, corner[q] - u1[1] * length
    t2[p], t2[q] = corner[p] + u2[0] * length, corner[q] + u2[1] * length
    return t1, t2


def _in_plane(v: np.ndarray, plane: int) -> np.ndarray:
    p, q = PLANE_AXES[plane]
    return np.array([v[p], v[q]], dtype=float)


def _offset(element: Line | Arc, corner: np.ndarray, inner: np.ndarray, radius: float, plane: int):
    """The element moved by ``radius`` towards ``inner`` (2-vector at the corner): a line as
    ``("line", point, direction)``, an arc as ``("circle", centre, radius)``."""
    if isinstance(element, Line):
        u = _in_plane(element.end - element.start, plane)
        return "line", _in_plane(corner, plane) + radius * inner, u / float(np.hypot(*u))
    o = _in_plane(element.center, plane)
    towards_centre = float(inner @ (o - _in_plane(corner, plane))) > 0
    r = element.radius - radius if towards_centre else element.radius + radius
    if r <= 1e-9:
        raise PathGeometryError(f"rounding radius {radius:g} mm does not fit inside the arc of radius "
                                f"{element.radius:g} mm", "a rounding radius smaller than the arc's")
    return "circle", o, r


def _intersections(a, b) -> list[np.ndarray]:
    """Intersection points (2-vectors) of two offset curves of :func:`_offset`."""
    if a[0] == "circle" and b[0] == "line":
        a, b = b, a
    if a[0] == "line" and b[0] == "line":
        (p1, u1), (p2, u2) = a[1:], b[1:]
        den = u1[0] * u2[1] - u1[1] * u2[0]
        if abs(den) <= 1e-12:
            return []
        d = p2 - p1
        return [p1 + u1 * ((d[0] * u2[1] - d[1] * u2[0]) / den)]
    if a[0] == "line":
        (p, u), (o, r) = a[1:], b[1:]
        f = p - o
        bq, cq = float(f @ u), float(f @ f) - r * r
        disc = bq * bq - cq
        if disc < 0:
            return []
        return [p + u * (-bq + s * math.sqrt(disc)) for s in (-1.0, 1.0)]
    (o1, r1), (o2, r2) = a[1:], b[1:]
    d = o2 - o1
    dist = float(np.hypot(*d))
    if dist <= 1e-12 or dist > r1 + r2 or dist < abs(r1 - r2):
        return []
    x = (dist * dist + r1 * r1 - r2 * r2) / (2 * dist)
    h = math.sqrt(max(r1 * r1 - x * x, 0.0))
    m = o1 + d * (x / dist)
    n = np.array([-d[1], d[0]]) / dist
    return [m + h * n, m - h * n]


def _foot(element: Line | Arc, centre: np.ndarray, like: np.ndarray, plane: int) -> np.ndarray:
    """Tangent point of the rounding circle about ``centre`` (2-vector) on ``element``, in 3-D
    (tool-axis coordinate of ``like``)."""
    p, q = PLANE_AXES[plane]
    out = np.array(like, dtype=float)
    if isinstance(element, Line):
        a = _in_plane(element.start, plane)
        u = _in_plane(element.end - element.start, plane)
        u = u / float(np.hypot(*u))
        f = a + u * float((centre - a) @ u)
    else:
        o = _in_plane(element.center, plane)
        v = centre - o
        f = o + v * (element.radius / float(np.hypot(*v)))
    out[p], out[q] = f
    return out


def _part(element: Line | Arc, start: np.ndarray, end: np.ndarray) -> Line | Arc | None:
    """The piece of ``element`` from ``start`` to ``end`` (None when it is not a piece of it)."""
    piece = piece_of(element, start, end)
    if isinstance(element, Line):
        inside = float((end - start) @ (element.end - element.start)) >= 0
        return piece if inside and piece.length <= element.length * (1 + 1e-9) + 1e-12 else None
    return piece if abs(piece.sweep) <= abs(element.sweep) * (1 + 1e-9) + 1e-12 else None


def round_elements(first: Line | Arc, second: Line | Arc, radius: float, *, plane: int, word: str = "RND"
                   ) -> tuple[Line | Arc, Arc, Line | Arc]:
    """``RND R`` between any two contour elements meeting at a corner (lines or arcs in the
    working plane): ``(first, rounding arc, second)``, the two elements trimmed to the tangent
    points.

    The rounding circle's centre is where the two elements, each moved by R towards the inside
    of the corner, meet (the intersection nearest the corner); the tangent points are its feet on
    the elements. Between two lines this is :func:`round_corner`.
    """
    if isinstance(first, Line) and isinstance(second, Line):
        t1, arc, t2 = round_corner(first.start, first.end, second.end, radius, plane=plane, word=word)
        return Line(first.start, t1), arc, Line(t2, second.end)
    for e in (first, second):
        if isinstance(e, Arc) and abs(e.helix) > 1e-9:
            raise PathGeometryError(f"{word} next to a helix", f"{word} between elements in the working plane")
    if radius <= 0:
        raise PathGeometryError("rounding radius must be > 0", f"{word} R > 0 [mm]")
    corner = np.asarray(first.end, dtype=float)
    t1 = end_tangent(first, plane)
    t2 = _in_plane(np.asarray(second.tangent_at(0.0), dtype=float).reshape(3), plane)
    t2 = t2 / float(np.hypot(*t2))
    cross = float(t1[0] * t2[1] - t1[1] * t2[0])
    if abs(cross) <= 1e-9:
        raise PathGeometryError(f"{word} where the elements meet tangentially (no corner to round)",
                                f"{word} at a corner between the elements")
    side = 1.0 if cross > 0 else -1.0
    candidates = _intersections(
        _offset(first, corner, side * np.array([-t1[1], t1[0]]), radius, plane),
        _offset(second, corner, side * np.array([-t2[1], t2[0]]), radius, plane))
    here = _in_plane(corner, plane)
    for centre in sorted(candidates, key=lambda c: float(np.hypot(*(c - here)))):
        a, b = _foot(first, centre, corner, plane), _foot(second, centre, corner, plane)
        head, tail = _part(first, np.asarray(first.start, float), a), _part(second, b, np.asarray(second.end, float))
        if head is not None and tail is not None:
            c3 = np.array(corner, dtype=float)
            c3[PLANE_AXES[plane][0]], c3[PLANE_AXES[plane][1]] = centre
            return head, Arc(a, on_circle(b, c3, radius, plane), c3, ccw=cross > 0, plane=plane), tail
    raise PathGeometryError(f"rounding radius {radius:g} mm does not fit between the elements",
                            f"a smaller {word} radius or longer elements")


def _chord_point(element: Line | Arc, corner: np.ndarray, length: float, *, before: bool, plane: int,
                 word: str) -> np.ndarray:
    """The point of ``element`` at the chord distance ``length`` [mm] from ``corner``, its end
    (``before``) or its start: along a line, on an arc where the circle of radius ``length`` about
    the corner cuts it."""
    if isinstance(element, Line):
        u = np.asarray(element.end, float) - np.asarray(element.start, float)
        if length > element.length + 1e-9:
            raise PathGeometryError(f"chamfer {length:g} mm is longer than a line of the corner "
                                    f"({element.length:.6g} mm)", f"a {word} shorter than both elements")
        return np.asarray(corner, float) + (-1.0 if before else 1.0) * u * (length / element.length)
    if abs(element.sweep) > 2.0 * math.pi + 1e-12 or abs(element.helix) > 1e-9:
        raise PathGeometryError(f"{word} next to a helix or a multi-turn arc",
                                f"{word} between elements in the working plane")
    half = length / (2.0 * element.radius)
    angle = 2.0 * math.asin(half) if half <= 1.0 else math.inf
    if angle > abs(element.sweep) + 1e-12:
        raise PathGeometryError(f"chamfer {length:g} mm is longer than the arc of radius {element.radius:g} mm "
                                "it cuts", f"a {word} whose chord fits on the arc")
    p, q = PLANE_AXES[plane]
    turn = angle * (1.0 if element.ccw else -1.0) * (-1.0 if before else 1.0)
    c, s = math.cos(turn), math.sin(turn)
    centre = np.asarray(element.center, float)
    dx, dy = corner[p] - centre[p], corner[q] - centre[q]
    out = np.array(corner, dtype=float)
    out[p], out[q] = centre[p] + c * dx - s * dy, centre[q] + s * dx + c * dy
    return out


def chamfer_elements(first: Line | Arc, second: Line | Arc, length: float, *, plane: int, word: str = "CHF"
                     ) -> tuple[Line | Arc, Line, Line | Arc]:
    """A chamfer between two contour elements (lines or arcs in the working plane) meeting at a
    corner: ``(first, chamfer, second)``, the elements trimmed to the chamfer's ends.

    The chamfer's ends lie at the chord distance ``length`` [mm] from the corner on each element:
    along a line the distance from the corner (:func:`chamfer_corner`), on an arc the chord
    (NCT 2000M operator's manual, a Fanuc-compatible control, 16.1 "Programming Chamfer and Corner
    Round": "A chamfer may also be inserted between circles or between a circle and a straight
    line. In this case value ,C is the length of the chord drawn from intersection").
    """
    if length <= 0:
        raise PathGeometryError("chamfer length must be > 0", f"{word} > 0 [mm]")
    corner = np.asarray(first.end, dtype=float)
    t1 = end_tangent(first, plane)
    t2 = _in_plane(np.asarray(second.tangent_at(0.0), dtype=float).reshape(3), plane)
    if abs(float(t1[0] * t2[1] - t1[1] * t2[0])) <= 1e-9 * float(np.hypot(*t2)) and float(t1 @ t2) > 0:
        raise PathGeometryError(f"{word} where the elements meet tangentially (no corner to chamfer)",
                                f"{word} at a corner between the elements")
    a = _chord_point(first, corner, length, before=True, plane=plane, word=word)
    b = _chord_point(second, corner, length, before=False, plane=plane, word=word)
    if isinstance(first, Line):
        head = Line(np.asarray(first.start, float), a)
    else:
        head = Arc(np.asarray(first.start, float), a, first.center, ccw=first.ccw, plane=plane)
    if isinstance(second, Line):
        tail = Line(b, np.asarray(second.end, float))
    else:
        tail = Arc(b, np.asarray(second.end, float), second.center, ccw=second.ccw, plane=plane)
    return head, Line(a, b), tail
