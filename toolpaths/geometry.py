"""Exact path geometry: straight lines, circular arcs, helices and clothoid corner blends in 3-D.

All points are length-3 float arrays ``(x, y, z)`` in millimetres. Every primitive is
parametrised by its arc length ``s`` [mm], ``0 <= s <= length``; ``point_at(0)`` is exactly
``start`` and ``point_at(length)`` is exactly ``end`` (bit for bit, not only to rounding).

Arc planes follow ISO 6983 / Fanuc: the plane is named by its normal axis, and the two in-plane
axes ``(p, q)`` are ordered so that ``(p, q, normal)`` is right-handed:

====== ======= ============ ==============
G code  plane   ``plane``    ``plane_axes``
====== ======= ============ ==============
G17     XY      2 (z)        (0, 1)  x, y
G18     ZX      1 (y)        (2, 0)  z, x
G19     YZ      0 (x)        (1, 2)  y, z
====== ======= ============ ==============

Counter-clockwise (``ccw=True``, G03, Heidenhain ``DR+``) means the in-plane angle, measured
from ``p`` towards ``q``, increases: counter-clockwise when looking from the positive normal
axis towards the origin.

:class:`ClothoidPair` is the curvature-continuous corner blend of the G64 look-ahead: two Euler
spirals (curvature linear in arc length) in the plane of a corner, from zero curvature on the
incoming line to a peak at the middle and back to zero on the outgoing line. It may lie in any
plane, not only the principal ones.

:class:`SplineCurve` is a piece of a smooth (C2) cubic B-spline curve in any orientation,
re-parametrised by arc length: the curve the G64 look-ahead fits through a run of dense short
lines (:mod:`interpolators.dense`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterator, Sequence

import numba
import numpy as np

from vcnc.core.errors import InputError

__all__ = ["Line", "Arc", "ClothoidPair", "SplineCurve", "Path", "Segment", "PLANE_AXES", "AXIS_LETTERS",
           "euler_spiral", "rows_by_owner", "piece_of", "curve_frame_rates"]

#: Axis letters of the three linear axes, in index order.
AXIS_LETTERS: tuple[str, str, str] = ("x", "y", "z")

#: normal-axis index -> the two in-plane axis indices (p, q), right-handed with the normal.
PLANE_AXES: dict[int, tuple[int, int]] = {2: (0, 1), 1: (2, 0), 0: (1, 2)}


def _point(value: Sequence[float] | np.ndarray, name: str) -> np.ndarray:
    arr = np.array(value, dtype=float)
    if arr.ndim != 1:
        arr = arr.reshape(-1)
    # math.isfinite on the three floats: the same test as np.isfinite, without numpy's per-call cost
    if arr.shape != (3,) or not all(map(math.isfinite, arr.tolist())):
        raise InputError(f"{name} must be 3 finite coordinates [mm], got {value!r}")
    arr.setflags(write=False)
    return arr


def _rows(value: np.ndarray, name: str) -> np.ndarray:
    """Rows of 3 finite coordinates [mm], as a read-only copy (the batch form of :func:`_point`)."""
    arr = np.array(value, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 3 or not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be rows of 3 finite coordinates [mm], got an array of shape {arr.shape}")
    arr.setflags(write=False)
    return arr


def _read_only(arr: np.ndarray) -> np.ndarray:
    """``arr`` itself if it is read-only, else a read-only copy."""
    if arr.flags.writeable:
        arr = arr.copy()
        arr.setflags(write=False)
    return arr


def _unit_rows(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Row norms of ``d`` and the unit rows (zero rows where the norm is 0), read-only."""
    norm = np.sqrt(np.einsum("ij,ij->i", d, d))
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(norm[:, None] > 0, d / norm[:, None], 0.0)
    u.setflags(write=False)
    return norm, u


class Line:
    """Straight segment from ``start`` to ``end``.

    Parameters
    ----------
    start, end : array_like, shape (3,)
        End points [mm].

    Attributes
    ----------
    start, end : ndarray, shape (3,)
        End points [mm] (read-only arrays).
    length : float
        Length [mm].
    direction : ndarray, shape (3,)
        Unit tangent (zero vector for a zero-length line).
    """

    __slots__ = ("start", "end", "length", "direction")
    kind = "line"

    def __init__(self, start: Sequence[float] | np.ndarray, end: Sequence[float] | np.ndarray) -> None:
        self.start = _point(start, "Line start")
        self.end = _point(end, "Line end")
        d = self.end - self.start
        self.length = math.sqrt(d.dot(d))  # the same ddot and correctly rounded root as float(np.sqrt(d @ d))
        u = d / self.length if self.length > 0 else np.zeros(3)
        u.setflags(write=False)
        self.direction = u

    @classmethod
    def from_points(cls, start: np.ndarray, end: np.ndarray) -> Line:
        """``Line(start, end)`` for two float arrays of shape (3,) that are known to be finite (a reader's
        positions): the same line, made without the checks. A read-only point is kept as it is, shared with the
        caller (a reader's block and the next line start on the same array); a writeable one is copied."""
        line = object.__new__(cls)
        line.start = a = _read_only(start)
        line.end = b = _read_only(end)
        d = b - a
        line.length = n = math.sqrt(d.dot(d))
        u = d / n if n > 0 else np.zeros(3)
        u.setflags(write=False)
        line.direction = u
        return line

    @classmethod
    def from_arrays(cls, start: np.ndarray, end: np.ndarray) -> list[Line]:
        """Lines from rows of end points, built at once: the same as ``Line(start[i], end[i])`` per row
        (to rounding: the lengths are computed by one vectorised expression).

        Parameters
        ----------
        start, end : ndarray, shape (n, 3)
            End points [mm].

        Returns
        -------
        list of Line
        """
        start, end = _rows(start, "Line start"), _rows(end, "Line end")
        length, direction = _unit_rows(end - start)
        new = object.__new__
        out = [new(cls) for _ in range(len(length))]
        for line, a, b, n, u in zip(out, list(start), list(end), length.tolist(), list(direction)):
            line.start, line.end, line.length, line.direction = a, b, n, u
        return out

    def point_at(self, s: np.ndarray | float) -> np.ndarray:
        """Points at arc length ``s`` [mm]; shape ``s.shape + (3,)``."""
        s = np.asarray(s, dtype=float)
        if self.length == 0:
            return np.broadcast_to(self.start, s.shape + (3,)).copy()
        f = (s / self.length)[..., None]
        p = self.start + (self.end - self.start) * f
        return np.where((s >= self.length)[..., None], self.end, np.where((s <= 0)[..., None], self.start, p))

    def tangent_at(self, s: np.ndarray | float) -> np.ndarray:
        """Unit tangents d(point)/ds at ``s``; shape ``s.shape + (3,)``."""
        s = np.asarray(s, dtype=float)
        return np.broadcast_to(self.direction, s.shape + (3,)).copy()

    def curvature_at(self, s: np.ndarray | float) -> np.ndarray:
        """Curvature vectors d^2(point)/ds^2 [1/mm] (zero for a line)."""
        s = np.asarray(s, dtype=float)
        return np.zeros(s.shape + (3,))

    def __repr__(self) -> str:
        return f"Line(start={self.start.tolist()}, end={self.end.tolist()})"


class Arc:
    """Circular arc, optionally helical along the plane normal.

    Parameters
    ----------
    start, end : array_like, shape (3,)
        End points [mm]. ``start`` must lie at distance ``radius`` from ``center`` in the plane;
        the in-plane position of ``end`` must lie on the same circle (checked to 1e-9 relative;
        the G-code parser checks programs against a looser, documented tolerance and moves the
        centre so that both ends are exactly on the circle).
    center : array_like, shape (3,)
        Centre [mm]; its normal-axis coordinate is ignored and replaced by ``start``'s.
    ccw : bool
        Direction: True counter-clockwise (G03, DR+), False clockwise (G02, DR-).
    plane : int
        Index of the normal axis: 2 for XY (G17), 1 for ZX (G18), 0 for YZ (G19).
    turns : int
        Extra full turns (>= 0) added to the sweep.

    Attributes
    ----------
    start, end, center : ndarray, shape (3,)
        [mm]; ``center[plane] == start[plane]``.
    radius : float
        Radius [mm] (> 0).
    plane : int
        Normal-axis index (see module table).
    plane_axes : tuple of int
        In-plane axis indices ``(p, q)``.
    ccw : bool
        True if counter-clockwise seen from the positive normal axis.
    start_angle : float
        Angle of ``start`` about ``center``, from ``p`` towards ``q`` [rad].
    sweep : float
        Signed swept angle [rad]; positive counter-clockwise; ``abs(sweep) <= 2*pi*(turns+1)``;
        a full circle (end equal to start in the plane) has ``abs(sweep) == 2*pi``.
    helix : float
        Displacement along the normal axis over the arc, ``end[plane] - start[plane]`` [mm].
    length : float
        Arc length ``hypot(radius*|sweep|, helix)`` [mm].
    """

    __slots__ = (
        "start", "end", "center", "radius", "plane", "plane_axes", "ccw",
        "start_angle", "sweep", "helix", "length", "_ep", "_eq", "_en",
    )
    kind = "arc"

    def __init__(
        self,
        start: Sequence[float] | np.ndarray,
        end: Sequence[float] | np.ndarray,
        center: Sequence[float] | np.ndarray,
        *,
        ccw: bool,
        plane: int = 2,
        turns: int = 0,
    ) -> None:
        if plane not in PLANE_AXES:
            raise InputError(f"Arc plane must be the normal axis index 0, 1 or 2, got {plane!r}")
        if int(turns) != turns or turns < 0:
            raise InputError(f"Arc turns must be an integer >= 0, got {turns!r}")
        self.start = _point(start, "Arc start")
        self.end = _point(end, "Arc end")
        c = np.array(_point(center, "Arc center"))
        c[plane] = self.start[plane]
        c.setflags(write=False)
        self.center = c
        self.plane = int(plane)
        p, q = PLANE_AXES[plane]
        self.plane_axes = (p, q)
        self.ccw = bool(ccw)
        rs = math.hypot(self.start[p] - c[p], self.start[q] - c[q])
        re = math.hypot(self.end[p] - c[p], self.end[q] - c[q])
        if not rs > 0:
            raise InputError("Arc radius must be > 0 mm (start point equals centre)")
        if abs(rs - re) > 1e-9 * max(rs, 1.0):
            raise InputError(f"Arc end is not on the circle: start radius {rs!r} mm, end radius {re!r} mm")
        self.radius = rs
        a0 = math.atan2(self.start[q] - c[q], self.start[p] - c[p])
        a1 = math.atan2(self.end[q] - c[q], self.end[p] - c[p])
        chord = math.hypot(self.end[p] - self.start[p], self.end[q] - self.start[q])
        two_pi = 2.0 * math.pi
        if chord <= 1e-12 * max(rs, 1.0):
            sweep = two_pi
        else:
            sweep = (a1 - a0) % two_pi if ccw else (a0 - a1) % two_pi
            if sweep == 0.0:  # chord > 0 but angles round equal: the shortest representable arc
                sweep = 1e-300
        sweep += two_pi * int(turns)
        self.start_angle = a0
        self.sweep = sweep if ccw else -sweep
        self.helix = float(self.end[plane] - self.start[plane])
        self.length = math.hypot(rs * abs(self.sweep), self.helix)
        ep = np.zeros(3)
        ep[p] = 1.0
        eq = np.zeros(3)
        eq[q] = 1.0
        en = np.zeros(3)
        en[plane] = 1.0
        self._ep, self._eq, self._en = ep, eq, en

    @classmethod
    def from_arrays(cls, start: np.ndarray, end: np.ndarray, center: np.ndarray, *, ccw: np.ndarray,
                    plane: np.ndarray) -> list[Arc | None]:
        """Arcs (without extra turns) from rows, built at once: the same as ``Arc(start[i], end[i], center[i],
        ccw=ccw[i], plane=plane[i])`` per row (to rounding), None where that raises :class:`vcnc.InputError`
        (radius 0, end not on the circle).

        Parameters
        ----------
        start, end, center : ndarray, shape (n, 3)
            [mm]
        ccw : ndarray of bool, shape (n,)
        plane : ndarray of int, shape (n,)
            Normal-axis index of each arc (0, 1 or 2).

        Returns
        -------
        list of Arc or None
        """
        start, end = _rows(start, "Arc start"), _rows(end, "Arc end")
        c = np.array(_rows(center, "Arc center"))
        ccw = np.asarray(ccw, dtype=bool)
        plane = np.asarray(plane, dtype=np.int64)
        if not np.all(np.isin(plane, list(PLANE_AXES))):
            raise InputError("Arc plane must be the normal axis index 0, 1 or 2")
        r = np.arange(len(start))
        p = np.array([PLANE_AXES[k][0] for k in range(3)])[plane]
        q = np.array([PLANE_AXES[k][1] for k in range(3)])[plane]
        c[r, plane] = start[r, plane]
        c.setflags(write=False)
        rs = np.hypot(start[r, p] - c[r, p], start[r, q] - c[r, q])
        re = np.hypot(end[r, p] - c[r, p], end[r, q] - c[r, q])
        ok = (rs > 0) & ~(np.abs(rs - re) > 1e-9 * np.maximum(rs, 1.0))
        a0 = np.arctan2(start[r, q] - c[r, q], start[r, p] - c[r, p])
        a1 = np.arctan2(end[r, q] - c[r, q], end[r, p] - c[r, p])
        chord = np.hypot(end[r, p] - start[r, p], end[r, q] - start[r, q])
        two_pi = 2.0 * math.pi
        sweep = np.where(ccw, (a1 - a0) % two_pi, (a0 - a1) % two_pi)
        sweep = np.where(sweep == 0.0, 1e-300, sweep)  # as in __init__: the shortest representable arc
        sweep = np.where(chord <= 1e-12 * np.maximum(rs, 1.0), two_pi, sweep)
        sweep = np.where(ccw, sweep, -sweep)
        helix = end[r, plane] - start[r, plane]
        length = np.hypot(rs * np.abs(sweep), helix)
        eye = np.eye(3)
        eye.setflags(write=False)
        unit = list(eye)
        out: list[Arc | None] = []
        for row in zip(ok.tolist(), start, end, c, plane.tolist(), p.tolist(), q.tolist(), ccw.tolist(), rs.tolist(),
                       a0.tolist(), sweep.tolist(), helix.tolist(), length.tolist()):
            if not row[0]:
                out.append(None)
                continue
            arc = object.__new__(cls)
            (_, arc.start, arc.end, arc.center, arc.plane, pi, qi, arc.ccw, arc.radius, arc.start_angle, arc.sweep,
             arc.helix, arc.length) = row
            arc.plane_axes = (pi, qi)
            arc._ep, arc._eq, arc._en = unit[pi], unit[qi], unit[arc.plane]
            out.append(arc)
        return out

    def angle_at(self, s: np.ndarray | float) -> np.ndarray:
        """In-plane angle about the centre at arc length ``s`` [rad]."""
        return self.start_angle + self.sweep * (np.asarray(s, dtype=float) / self.length)

    def point_at(self, s: np.ndarray | float) -> np.ndarray:
        """Points at arc length ``s`` [mm]; shape ``s.shape + (3,)``."""
        s = np.asarray(s, dtype=float)
        f = s / self.length
        phi = (self.start_angle + self.sweep * f)[..., None]
        pts = self.center + self.radius * (np.cos(phi) * self._ep + np.sin(phi) * self._eq)
        pts = pts + (self.helix * f)[..., None] * self._en
        return np.where((s >= self.length)[..., None], self.end, np.where((s <= 0)[..., None], self.start, pts))

    def tangent_at(self, s: np.ndarray | float) -> np.ndarray:
        """Unit tangents d(point)/ds at ``s``; shape ``s.shape + (3,)``."""
        s = np.asarray(s, dtype=float)
        phi = self.angle_at(s)[..., None]
        w = self.radius * self.sweep / self.length
        return w * (-np.sin(phi) * self._ep + np.cos(phi) * self._eq) + (self.helix / self.length) * self._en

    def curvature_at(self, s: np.ndarray | float) -> np.ndarray:
        """Curvature vectors d^2(point)/ds^2 [1/mm], pointing to the helix axis."""
        s = np.asarray(s, dtype=float)
        phi = self.angle_at(s)[..., None]
        k = self.radius * (self.sweep / self.length) ** 2
        return -k * (np.cos(phi) * self._ep + np.sin(phi) * self._eq)

    def __repr__(self) -> str:
        return (
            f"Arc(start={self.start.tolist()}, end={self.end.tolist()}, center={self.center.tolist()}, "
            f"ccw={self.ccw}, plane={self.plane}, sweep={self.sweep:.6g})"
        )


def piece_of(element: Line | Arc, start: Sequence[float] | np.ndarray, end: Sequence[float] | np.ndarray
             ) -> Line | Arc:
    """The segment of ``element``'s kind from ``start`` to ``end``: a line, or the arc about the same centre,
    in the same direction and plane (two of the element's points give a piece of it)."""
    if isinstance(element, Line):
        return Line(start, end)
    return Arc(start, end, element.center, ccw=element.ccw, plane=element.plane)


def euler_spiral(phi: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Normalised Euler-spiral integrals ``X(phi) = int_0^1 cos(phi u^2) du`` and ``Y`` (sin).

    A clothoid of sharpness ``c`` [1/mm^2] starting with zero curvature along ``e_x`` reaches
    ``(s X(c s^2/2), s Y(c s^2/2))`` at arc length ``s``. Power series, exact to rounding for
    ``|phi| <= pi/2`` (the blends use ``phi <= theta/2 < pi/2``).
    """
    phi = np.asarray(phi, dtype=float)
    x = np.zeros_like(phi)
    y = np.zeros_like(phi)
    term = np.ones_like(phi)  # phi^k / k!
    for k in range(28):
        sign = 1.0 if k % 4 < 2 else -1.0  # i^k = 1, i, -1, -i
        if k % 2 == 0:
            x = x + sign * term / (2 * k + 1)
        else:
            y = y + sign * term / (2 * k + 1)
        term = term * phi / (k + 1)
    return x, y


class ClothoidPair:
    """Symmetric pair of clothoids (Euler spirals) blending the corner of two straight lines.

    The curve leaves ``start`` along ``corner - start`` with zero curvature, its curvature grows
    linearly with arc length up to ``peak_curvature`` at the middle (where the tangent has turned
    by half the ``deflection``) and falls linearly back to zero at ``end``, where it is tangent to
    ``end - corner``. Position, tangent and curvature are continuous across both ends and the
    middle: joined to the two lines the path is curvature continuous (G2).

    Parameters
    ----------
    start, corner, end : array_like, shape (3,)
        Tangent points on the incoming and outgoing lines and the corner between them [mm];
        ``|corner - start| == |end - corner|`` (checked to 1e-9 relative), deflection in
        ``(0, pi)``.

    Attributes
    ----------
    start, end, corner : ndarray, shape (3,)
        [mm] (read-only arrays).
    length : float
        Arc length [mm] (``2 * half_length``).
    half_length : float
        Length of each clothoid [mm].
    deflection : float
        Angle between the incoming and outgoing directions [rad].
    sharpness : float
        Magnitude of the curvature derivative ``|dk/ds|`` [1/mm^2].
    peak_curvature : float
        Curvature at the middle [1/mm] (the largest on the blend).
    deviation : float
        Distance of the middle point from the corner [mm], the largest distance of the blend
        from the two lines it replaces.
    u_in, u_out : ndarray, shape (3,)
        Unit directions of the incoming and outgoing lines.
    w_in, w_out : ndarray, shape (3,)
        Unit in-plane normals at ``start`` and ``end``, pointing to the inside of the turn.
    normal : ndarray, shape (3,)
        Unit normal of the corner plane, ``u_in x u_out / |u_in x u_out|``.

    Notes
    -----
    With ``phi = sharpness s^2 / 2`` the first half is ``start + s X(phi) u_in + s Y(phi) w_in``
    and the second half, with ``r = length - s``, ``end - r X(phi_r) u_out + r Y(phi_r) w_out``
    (:func:`euler_spiral`). For a deflection ``theta`` and half length ``lam``: sharpness
    ``theta / lam^2``, peak curvature ``2 theta / length``, tangent length
    ``|corner - start| = lam (X + Y tan(theta/2))`` and deviation ``lam Y / cos(theta/2)``,
    with ``X, Y`` at ``phi = theta/2``: both lengths are proportional to ``lam`` for a given
    deflection (:meth:`for_corner` uses this to fit the blend to a tolerance in closed form).

    Nearest point (for contour errors): the foot ``s`` of a point ``P`` solves
    ``g(s) = (P - point_at(s)) . tangent_at(s) = 0``, ``g'(s) = -1 + (P - point_at(s)) .
    curvature_at(s)``; :meth:`nearest` runs Newton's method on each half from the projection of
    ``P`` on the incoming / outgoing line (``g' < 0`` near the curve since the deviation of
    interest is far below the radius of curvature).
    """

    __slots__ = ("start", "end", "corner", "length", "half_length", "deflection", "sharpness", "peak_curvature",
                 "deviation", "u_in", "u_out", "w_in", "w_out", "normal")
    kind = "clothoid"

    def __init__(
        self,
        start: Sequence[float] | np.ndarray,
        corner: Sequence[float] | np.ndarray,
        end: Sequence[float] | np.ndarray,
    ) -> None:
        self.start = _point(start, "ClothoidPair start")
        self.corner = _point(corner, "ClothoidPair corner")
        self.end = _point(end, "ClothoidPair end")
        a = self.corner - self.start
        b = self.end - self.corner
        da, db = float(np.sqrt(a @ a)), float(np.sqrt(b @ b))
        if not (da > 0 and db > 0):
            raise InputError("ClothoidPair needs start, corner and end distinct")
        if abs(da - db) > 1e-9 * max(da, db):
            raise InputError(f"ClothoidPair legs must be equal: |corner - start| = {da!r}, |end - corner| = {db!r}")
        ua, ub = a / da, b / db
        cos_t = float(np.clip(ua @ ub, -1.0, 1.0))
        n = np.cross(ua, ub)
        nn = float(np.sqrt(n @ n))
        theta = math.atan2(nn, cos_t)
        if not (nn > 0 and 0.0 < theta < math.pi):
            raise InputError(f"ClothoidPair deflection must be in (0, pi) rad, got {theta!r}")
        w_in = ub - cos_t * ua
        w_in = w_in / np.sqrt(w_in @ w_in)
        w_out = cos_t * ub - ua
        w_out = w_out / np.sqrt(w_out @ w_out)
        d = 0.5 * (da + db)
        half = 0.5 * theta
        xm, ym = (float(v) for v in euler_spiral(half))
        lam = d / (xm + ym * math.tan(half))
        for name, v in (("u_in", ua), ("u_out", ub), ("w_in", w_in), ("w_out", w_out), ("normal", n / nn)):
            v = np.array(v, dtype=float)
            v.setflags(write=False)
            setattr(self, name, v)
        self.half_length = lam
        self.length = 2.0 * lam
        self.deflection = theta
        self.sharpness = theta / (lam * lam)
        self.peak_curvature = theta / lam
        self.deviation = lam * ym / math.cos(half)

    @classmethod
    def from_arrays(cls, start: np.ndarray, corner: np.ndarray, end: np.ndarray) -> list[ClothoidPair | None]:
        """Blends from rows, built at once: the same as ``ClothoidPair(start[i], corner[i], end[i])`` per row
        (to rounding), None where that raises :class:`vcnc.InputError` (legs zero or unequal, deflection not
        in (0, pi)).

        Parameters
        ----------
        start, corner, end : ndarray, shape (n, 3)
            [mm]

        Returns
        -------
        list of ClothoidPair or None
        """
        start, corner, end = (_rows(v, f"ClothoidPair {k}") for v, k in ((start, "start"), (corner, "corner"),
                                                                         (end, "end")))
        da, ua = _unit_rows(corner - start)
        db, ub = _unit_rows(end - corner)
        cos_t = np.clip(np.einsum("ij,ij->i", ua, ub), -1.0, 1.0)
        nn, normal = _unit_rows(np.cross(ua, ub))
        theta = np.arctan2(nn, cos_t)
        ok = (da > 0) & (db > 0) & ~(np.abs(da - db) > 1e-9 * np.maximum(da, db))
        ok &= (nn > 0) & (theta > 0.0) & (theta < math.pi)
        _, w_in = _unit_rows(ub - cos_t[:, None] * ua)
        _, w_out = _unit_rows(cos_t[:, None] * ub - ua)
        half = 0.5 * theta
        xm, ym = euler_spiral(half)
        with np.errstate(divide="ignore", invalid="ignore"):
            lam = 0.5 * (da + db) / (xm + ym * np.tan(half))
            sharpness, peak = theta / (lam * lam), theta / lam
        deviation = lam * ym / np.cos(half)
        out: list[ClothoidPair | None] = []
        for row in zip(ok.tolist(), start, corner, end, lam.tolist(), theta.tolist(), sharpness.tolist(),
                       peak.tolist(), deviation.tolist(), ua, ub, w_in, w_out, normal):
            if not row[0]:
                out.append(None)
                continue
            blend = object.__new__(cls)
            (_, blend.start, blend.corner, blend.end, blend.half_length, blend.deflection, blend.sharpness,
             blend.peak_curvature, blend.deviation, blend.u_in, blend.u_out, blend.w_in, blend.w_out,
             blend.normal) = row
            blend.length = 2.0 * blend.half_length
            out.append(blend)
        return out

    @staticmethod
    def shape_factors(deflection: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Tangent length and deviation per unit half length [-] for a ``deflection`` [rad] (array or scalar)."""
        half = 0.5 * np.asarray(deflection, dtype=float)
        xm, ym = euler_spiral(half)
        return xm + ym * np.tan(half), ym / np.cos(half)

    @classmethod
    def for_corner(cls, corner: np.ndarray, u_in: np.ndarray, u_out: np.ndarray, *, tolerance: float,
                   max_leg: float) -> ClothoidPair | None:
        """Largest blend of the corner with deviation <= ``tolerance`` [mm] and legs <= ``max_leg`` [mm].

        ``u_in``, ``u_out`` are the unit directions of the lines; None when the corner cannot be
        blended (deflection not in (0, pi), or degenerate sizes).
        """
        cos_t = float(np.clip(u_in @ u_out, -1.0, 1.0))
        theta = math.atan2(float(np.linalg.norm(np.cross(u_in, u_out))), cos_t)
        if not (0.0 < theta < math.pi) or not (tolerance > 0 and max_leg > 0):
            return None
        leg_f, dev_f = (float(f) for f in cls.shape_factors(theta))
        lam = min(tolerance / dev_f, max_leg / leg_f)
        d = lam * leg_f
        if not (d > 1e-9):
            return None
        try:
            return cls(corner - d * u_in, corner, corner + d * u_out)
        except InputError:
            return None

    def _halves(self, s: np.ndarray):
        s = np.asarray(s, dtype=float)
        first = s <= self.half_length
        r = np.clip(np.where(first, s, self.length - s), 0.0, self.half_length)
        phi = 0.5 * self.sharpness * r * r
        return s, first[..., None], r, phi

    def point_at(self, s: np.ndarray | float) -> np.ndarray:
        """Points at arc length ``s`` [mm]; shape ``s.shape + (3,)``."""
        s, first, r, phi = self._halves(s)
        x, y = euler_spiral(phi)
        x, y = (r * x)[..., None], (r * y)[..., None]
        pts = np.where(first, self.start + x * self.u_in + y * self.w_in, self.end - x * self.u_out + y * self.w_out)
        return np.where((s >= self.length)[..., None], self.end, np.where((s <= 0)[..., None], self.start, pts))

    def tangent_at(self, s: np.ndarray | float) -> np.ndarray:
        """Unit tangents d(point)/ds at ``s``; shape ``s.shape + (3,)``."""
        _, first, _, phi = self._halves(s)
        c, sn = np.cos(phi)[..., None], np.sin(phi)[..., None]
        return np.where(first, c * self.u_in + sn * self.w_in, c * self.u_out - sn * self.w_out)

    def curvature_at(self, s: np.ndarray | float) -> np.ndarray:
        """Curvature vectors d^2(point)/ds^2 [1/mm], pointing to the inside of the turn."""
        _, first, r, phi = self._halves(s)
        c, sn = np.cos(phi)[..., None], np.sin(phi)[..., None]
        k = (self.sharpness * r)[..., None]
        return k * np.where(first, c * self.w_in - sn * self.u_in, c * self.w_out + sn * self.u_out)

    def nearest(self, points: np.ndarray, *, iterations: int = 8) -> tuple[np.ndarray, np.ndarray]:
        """Arc length [mm] of the nearest point on the blend and the distance [mm] to it.

        Parameters
        ----------
        points : array_like, shape (m, 3)
            [mm]

        Returns
        -------
        s, distance : ndarray, shape (m,)
        """
        P = np.asarray(points, dtype=float).reshape(-1, 3)
        best_s = np.zeros(len(P))
        best_d = np.full(len(P), np.inf)
        for lo, hi, s0 in ((0.0, self.half_length, (P - self.start) @ self.u_in),
                           (self.half_length, self.length, self.length - (self.end - P) @ self.u_out)):
            s = np.clip(s0, lo, hi)
            for _ in range(iterations):
                e = P - self.point_at(s)
                g = np.einsum("ij,ij->i", e, self.tangent_at(s))
                dg = -1.0 + np.einsum("ij,ij->i", e, self.curvature_at(s))
                s = np.clip(s - g / np.where(dg < -1e-12, dg, -1e-12), lo, hi)
            d = np.linalg.norm(P - self.point_at(s), axis=1)
            better = d < best_d
            best_s, best_d = np.where(better, s, best_s), np.where(better, d, best_d)
        return best_s, best_d

    def __repr__(self) -> str:
        return (f"ClothoidPair(start={self.start.tolist()}, corner={self.corner.tolist()}, end={self.end.tolist()}, "
                f"deflection={self.deflection:.6g})")


#: Gauss-Legendre nodes and weights on [0, 1] (5 points) for the arc length of spline curves.
_GL_X, _GL_W = (0.5 * (np.polynomial.legendre.leggauss(5)[0] + 1.0), 0.5 * np.polynomial.legendre.leggauss(5)[1])


class SplineCurve:
    """A piece ``u0 <= u <= u1`` of a 3-D cubic B-spline curve ``C(u)``, parametrised by arc length.

    Parameters
    ----------
    spline : scipy.interpolate.BSpline
        Vector-valued (coefficients of shape ``(m, 3)``) cubic spline [mm]; pieces of one curve may
        share it.
    u0, u1 : float
        Parameter range of the piece (``u0 < u1``), best at knots so that the piece is one
        polynomial per knot interval.
    start, end : array_like, shape (3,), optional
        Exact end points [mm] (default ``C(u0)``, ``C(u1)``), e.g. the programmed points a fitted
        curve interpolates, so that ``point_at(0)`` / ``point_at(length)`` are bit-exact.
    subdivisions : int
        Table nodes per knot interval for the arc length (default 8).
    derivatives : tuple of three scipy.interpolate.BSpline, optional
        ``spline.derivative(1)``, ``(2)`` and ``(3)`` when already at hand (the pieces of one curve share them).

    Attributes
    ----------
    start, end : ndarray, shape (3,)
        [mm]
    length : float
        Arc length [mm].
    u0, u1 : float
        Parameter range.

    Notes
    -----
    The arc length ``s(u) = int |C'|`` is tabulated with 5-point Gauss-Legendre quadrature on
    ``subdivisions`` sub-intervals of every knot interval; ``u(s)`` is the quintic Hermite
    interpolant of the table with the exact ``du/ds = 1/|C'(u)|`` and ``d2u/ds2 = -(C'.C'')/|C'|^4``
    (its error is far below a nanometre for the curves the look-ahead fits: ``|C'|`` is close to 1 and
    smooth), so the points' second derivative along ``s`` is continuous across the table's nodes: the
    cubic Hermite of ``u`` matched only ``du/ds``, and its ``d2u/ds2`` stepped at each node, a tangential
    acceleration step ``v^2 |C'| d(d2u/ds2)`` that finite differences read as jerk (16 mm/s^2 at 11 mm/s on
    a merged curve: Y 6.6 % over its jerk limit at Ts = 0.28 ms, setpoint fuzzer cam seed 40037). Tangent
    ``t = C'/|C'|`` and curvature vector ``k = (C'' - (C''.t) t)/|C'|^2``; its derivative
    ``dk/ds`` follows from the third derivative (:meth:`bounds`).
    """

    __slots__ = ("spline", "u0", "u1", "start", "end", "length", "_d", "_s_nodes", "_u_poly", "_nodes", "_bounds")
    kind = "spline"

    def __init__(self, spline, u0: float, u1: float, *, start: Sequence[float] | np.ndarray | None = None,
                 end: Sequence[float] | np.ndarray | None = None, subdivisions: int = 8,
                 derivatives: tuple | None = None) -> None:
        if not (math.isfinite(u0) and math.isfinite(u1) and u0 < u1):
            raise InputError(f"SplineCurve needs u0 < u1, got {u0!r}, {u1!r}")
        d = derivatives or (spline.derivative(1), spline.derivative(2), spline.derivative(3))
        nodes = _table_nodes(spline.t, u0, u1, subdivisions)
        q = _quadrature_points(nodes)
        speed = np.linalg.norm(d[0](q.ravel()), axis=1).reshape(q.shape)
        self._fill(spline, u0, u1, d, nodes, speed, d[0](nodes), d[1](nodes), spline(u0) if start is None else start,
                   spline(u1) if end is None else end)

    def _fill(self, spline, u0: float, u1: float, d: tuple, nodes: np.ndarray, speed: np.ndarray, d1: np.ndarray,
              d2: np.ndarray, start, end) -> None:
        """Set the piece from its table ``nodes``, ``|C'|`` at their quadrature points (``speed``, shape
        ``(len(nodes) - 1, 5)``), ``C'`` and ``C''`` at the nodes (``d1``, ``d2``) and its end points."""
        self.spline, self.u0, self.u1, self._d = spline, float(u0), float(u1), d
        s_nodes = np.concatenate([[0.0], np.cumsum(np.diff(nodes) * (speed @ _GL_W))])
        self._nodes = nodes
        self._s_nodes = s_nodes
        # u(s): quintic Hermite on each table interval through u, du/ds = 1/|C'| and d2u/ds2 = -(C'.C'')/|C'|^4 at
        # its nodes, as power-form coefficients (highest first) in s - s_j
        g11 = np.einsum("ij,ij->i", d1, d1)
        du = 1.0 / np.sqrt(g11)
        ddu = -np.einsum("ij,ij->i", d1, d2) / (g11 * g11)
        h = np.diff(s_nodes)
        rest = np.diff(nodes) - (du[:-1] + ddu[:-1] * h / 2) * h
        rate = (np.diff(du) - ddu[:-1] * h) * h
        curv = np.diff(ddu) * h * h
        self._u_poly = np.stack([(6 * rest - 3 * rate + curv / 2) / h**5, (-15 * rest + 7 * rate - curv) / h**4,
                                 (10 * rest - 4 * rate + curv / 2) / h**3, ddu[:-1] / 2, du[:-1], nodes[:-1]])
        self.length = float(s_nodes[-1])
        self.start = _point(start, "SplineCurve start")
        self.end = _point(end, "SplineCurve end")
        self._bounds: tuple[float, float, np.ndarray] | None = None

    @classmethod
    def pieces(cls, spline, breaks: np.ndarray, *, start: np.ndarray | None = None, end: np.ndarray | None = None,
               subdivisions: int = 8) -> tuple[SplineCurve, ...]:
        """The pieces ``breaks[i] <= u <= breaks[i + 1]`` of one curve, the first from ``start`` and the last to
        ``end`` (default the curve's points), the inner ends ``C(breaks[i])``; their :meth:`bounds` computed.

        The same pieces, bit for bit, as ``SplineCurve(spline, breaks[i], breaks[i + 1], ...)`` one by one (each
        value is evaluated point by point, by the same expressions), with the curve and its derivatives evaluated
        once for all the pieces instead of a few times per piece.
        """
        brk = np.asarray(breaks, dtype=float)
        if not (np.all(np.isfinite(brk)) and np.all(brk[1:] > brk[:-1])) or len(brk) < 2:
            raise InputError(f"SplineCurve.pieces needs increasing finite breaks, got {brk!r}")
        d = (spline.derivative(1), spline.derivative(2), spline.derivative(3))
        nodes = [_table_nodes(spline.t, u0, u1, subdivisions) for u0, u1 in zip(brk[:-1], brk[1:])]
        q = [_quadrature_points(nd) for nd in nodes]
        speed = np.linalg.norm(d[0](np.concatenate([x.ravel() for x in q])), axis=1)
        all_nodes = np.concatenate(nodes)
        d1, d2 = d[0](all_nodes), d[1](all_nodes)
        at = spline(brk)
        ends = [*at[:-1], at[-1]]
        if start is not None:
            ends[0] = start
        if end is not None:
            ends[-1] = end
        out = []
        iq = i_n = 0
        for i, (nd, qi) in enumerate(zip(nodes, q)):
            piece = object.__new__(cls)
            piece._fill(spline, brk[i], brk[i + 1], d, nd, speed[iq:iq + qi.size].reshape(qi.shape).copy(),
                        d1[i_n:i_n + len(nd)], d2[i_n:i_n + len(nd)], ends[i], ends[i + 1])
            iq, i_n = iq + qi.size, i_n + len(nd)
            out.append(piece)
        _set_table_bounds(out)
        return tuple(out)

    @classmethod
    def hermite(cls, start: np.ndarray, tangent_in: np.ndarray, curvature_in: np.ndarray, end: np.ndarray,
                tangent_out: np.ndarray, curvature_out: np.ndarray, *, stretch: float = 1.0, subdivisions: int = 32
                ) -> SplineCurve:
        """The quintic from ``start`` to ``end`` with the given unit tangents and curvature vectors [1/mm] at its
        ends (a G2 Hermite curve, one Bezier piece on ``0 <= u <= 1``): ``C'(0) = c t_in``, ``C''(0) = c^2 k_in``
        and likewise at ``u = 1``, ``c`` the chord ``|end - start|`` times ``stretch``, so that position, tangent
        and curvature match the curves it joins (the Bezier control points follow from the end derivatives of a quintic,
        ``B1 = B0 + C'(0) / 5``, ``B2 = 2 B1 - B0 + C''(0) / 20``). ``subdivisions`` table nodes per piece: the
        bounds (:meth:`bounds`) are sampled there (a quintic's curvature derivative is not linear)."""
        from scipy.interpolate import BSpline

        controls = cls.hermite_controls(start, tangent_in, curvature_in, end, tangent_out, curvature_out,
                                        stretch=stretch)
        # a Bezier piece: its derivatives are Bezier pieces of the control points' scaled differences
        steps = [controls]
        for k in (5, 4, 3):
            steps.append(k * np.diff(steps[-1], axis=0))
        spline, *d = (BSpline(np.r_[np.zeros(6 - r), np.ones(6 - r)], c, 5 - r) for r, c in enumerate(steps))
        return cls(spline, 0.0, 1.0, start=controls[0], end=controls[-1], subdivisions=subdivisions,
                   derivatives=tuple(d))

    @staticmethod
    def hermite_controls(start: np.ndarray, tangent_in: np.ndarray, curvature_in: np.ndarray, end: np.ndarray,
                         tangent_out: np.ndarray, curvature_out: np.ndarray, *, stretch: float = 1.0) -> np.ndarray:
        """The six Bezier control points [mm] of :meth:`hermite`'s quintic, shape (6, 3)."""
        p0, p1 = _point(start, "hermite start"), _point(end, "hermite end")
        c = float(np.linalg.norm(p1 - p0)) * stretch
        b1 = p0 + c * np.asarray(tangent_in, dtype=float) / 5.0
        b2 = 2.0 * b1 - p0 + c * c * np.asarray(curvature_in, dtype=float) / 20.0
        b4 = p1 - c * np.asarray(tangent_out, dtype=float) / 5.0
        b3 = 2.0 * b4 - p1 + c * c * np.asarray(curvature_out, dtype=float) / 20.0
        return np.array([p0, b1, b2, b3, b4, p1])

    def trimmed(self, s0: float, s1: float, *, start: np.ndarray | None = None, end: np.ndarray | None = None
                ) -> SplineCurve:
        """The part ``s0 <= s <= s1`` [mm] of the piece (arc lengths along it), on the same spline; its ends
        ``start``, ``end`` when given (default the points at ``s0``, ``s1``; the piece's own end points where
        ``s0 = 0`` or ``s1 = length``)."""
        u0 = self.u0 if s0 <= 0.0 else float(self.parameter_at(s0))
        u1 = self.u1 if s1 >= self.length else float(self.parameter_at(s1))
        if start is None:
            start = self.start if s0 <= 0.0 else self.spline(u0)
        if end is None:
            end = self.end if s1 >= self.length else self.spline(u1)
        sub = max(1, (len(self._nodes) - 1) // max(1, int(np.count_nonzero((self.spline.t > self.u0)
                                                                          & (self.spline.t < self.u1))) + 1))
        return SplineCurve(self.spline, u0, u1, start=start, end=end, subdivisions=sub, derivatives=self._d)

    def parameter_at(self, s: np.ndarray | float) -> np.ndarray:
        """Spline parameter ``u`` at arc length ``s`` [mm] (clipped to the piece)."""
        # np.minimum/np.maximum: np.clip's own overhead dominates on the few samples of a piece
        s = np.minimum(np.maximum(np.asarray(s, dtype=float), 0.0), self.length)
        j = np.minimum(np.maximum(np.searchsorted(self._s_nodes, s, side="right") - 1, 0), len(self._s_nodes) - 2)
        x = s - self._s_nodes[j]
        c = self._u_poly[:, j]
        return np.minimum(np.maximum(((((c[0] * x + c[1]) * x + c[2]) * x + c[3]) * x + c[4]) * x + c[5], self.u0),
                          self.u1)

    @staticmethod
    def parameters(pieces: Sequence[SplineCurve], piece: np.ndarray, s: np.ndarray) -> np.ndarray:
        """``pieces[piece[i]].parameter_at(s[i])`` for every ``i``, bit for bit, the arithmetic done at once."""
        piece = np.asarray(piece, dtype=np.int64)
        length = np.array([p.length for p in pieces])
        s = np.minimum(np.maximum(np.asarray(s, dtype=float), 0.0), length[piece])
        # each row's table interval in its own piece's table, as an index into the pieces' tables laid end to end
        size = np.array([len(p._s_nodes) for p in pieces], dtype=np.int64)
        s_nodes = np.concatenate([p._s_nodes for p in pieces])
        j = np.empty(len(s), dtype=np.int64)
        _table_intervals(s, piece, np.cumsum(size) - size, size, s_nodes, j)
        x = s - s_nodes[j]
        c = np.concatenate([np.hstack([p._u_poly, np.zeros((6, 1))]) for p in pieces], axis=1)[:, j]
        u0 = np.array([p.u0 for p in pieces])[piece]
        u1 = np.array([p.u1 for p in pieces])[piece]
        return np.minimum(np.maximum(((((c[0] * x + c[1]) * x + c[2]) * x + c[3]) * x + c[4]) * x + c[5], u0), u1)

    @staticmethod
    def evaluate_pieces(pieces: Sequence[SplineCurve], piece: np.ndarray, s: np.ndarray, *, frame: bool = True
                        ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """Point, unit tangent and curvature vector at arc length ``s[i]`` (clipped to the piece) along
        ``pieces[piece[i]]``: ``point_at``, ``tangent_at`` and ``curvature_at`` of each row, bit for bit, with
        each curve (the pieces of one spline) evaluated once for all its rows (``frame=False``: the points
        only, None for the others)."""
        piece = np.asarray(piece, dtype=np.int64)
        length = np.array([p.length for p in pieces])[piece]
        s = np.minimum(np.maximum(np.asarray(s, dtype=float), 0.0), length)
        u = SplineCurve.parameters(pieces, piece, s)
        pts = np.empty((len(s), 3))
        tan = np.empty((len(s), 3)) if frame else None
        curv = np.empty((len(s), 3)) if frame else None
        for k, rows in rows_by_owner([p.spline for p in pieces], piece):
            p = pieces[k]
            pts[rows] = p.spline(u[rows])
            if frame:
                tan[rows], curv[rows] = p.frame(u[rows])
        start = np.array([p.start for p in pieces]).reshape(-1, 3)[piece]
        end = np.array([p.end for p in pieces]).reshape(-1, 3)[piece]
        pts = np.where((s >= length)[:, None], end, np.where((s <= 0)[:, None], start, pts))
        return pts, tan, curv

    def frame(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Unit tangent and curvature vector [1/mm] at the spline parameters ``u``."""
        d1, d2 = self._d[0](u), self._d[1](u)
        sigma2 = np.einsum("...i,...i->...", d1, d1)
        tan = d1 / np.sqrt(sigma2)[..., None]
        curv = (d2 - np.einsum("...i,...i->...", d2, tan)[..., None] * tan) / sigma2[..., None]
        return tan, curv

    def point_at(self, s: np.ndarray | float) -> np.ndarray:
        """Points at arc length ``s`` [mm]; shape ``s.shape + (3,)``."""
        s = np.asarray(s, dtype=float)
        pts = self.spline(self.parameter_at(s))
        return np.where((s >= self.length)[..., None], self.end, np.where((s <= 0)[..., None], self.start, pts))

    def tangent_at(self, s: np.ndarray | float) -> np.ndarray:
        """Unit tangents at arc length ``s``; shape ``s.shape + (3,)``."""
        return self.frame(self.parameter_at(s))[0]

    def curvature_at(self, s: np.ndarray | float) -> np.ndarray:
        """Curvature vectors d^2(point)/ds^2 [1/mm] at arc length ``s``."""
        return self.frame(self.parameter_at(s))[1]

    def bounds(self) -> tuple[float, float, np.ndarray]:
        """Largest curvature [1/mm], largest ``|dk/ds|`` normal to the tangent [1/mm^2] and largest
        ``|t_i|`` per axis over the piece, from the arc-length table nodes (each knot interval
        evaluated from its own side, where the third derivative jumps); ``|t_i|`` bounded between the
        nodes too (the node value plus the curvature times half the node spacing, at most 1).

        ``dk/ds = k_u / |C'|`` with ``k = N / |C'|^4``, ``N = C'' |C'|^2 - (C'.C'') C'`` and
        ``N_u = C''' |C'|^2 + (C'.C'') C'' - (C'.C''' + C''.C'') C'``.
        Computed once, then kept (the piece does not change).
        """
        if self._bounds is None:
            _set_table_bounds([self])
        kappa, dkappa, t_abs = self._bounds
        return kappa, dkappa, t_abs.copy()

    def __repr__(self) -> str:
        return f"SplineCurve(start={self.start.tolist()}, end={self.end.tolist()}, length={self.length:.6g})"


def rows_by_owner(owners: Sequence[object], piece: np.ndarray) -> list[tuple[int, np.ndarray]]:
    """The rows ``i`` grouped by the object ``owners[piece[i]]`` (by identity: the pieces of one spline, or of one
    merged run, share it), so that each owner is evaluated once for all its rows: ``(k, rows)`` per owner with
    rows, ``k`` the first index of ``owners`` holding it, in the order the owners first appear, the rows
    increasing."""
    group: dict[int, int] = {}
    first: list[int] = []
    of = np.empty(len(owners), dtype=np.int64)
    for k, owner in enumerate(owners):
        of[k] = g = group.setdefault(id(owner), len(group))
        if g == len(first):
            first.append(k)
    at = of[np.asarray(piece, dtype=np.int64)]
    order = np.argsort(at, kind="stable")
    cuts = np.searchsorted(at[order], np.arange(len(first) + 1)).tolist()
    return [(first[g], order[cuts[g]:cuts[g + 1]]) for g in range(len(first)) if cuts[g + 1] > cuts[g]]


def _table_nodes(knots: np.ndarray, u0: float, u1: float, subdivisions: int) -> np.ndarray:
    """Arc-length table nodes of the piece ``u0 <= u <= u1``: ``subdivisions`` per knot interval."""
    t = np.asarray(knots, dtype=float)
    brk = np.unique(np.concatenate([[u0, u1], t[(t > u0) & (t < u1)]]))
    f = np.linspace(0.0, 1.0, subdivisions + 1)[:-1]
    return np.append((brk[:-1, None] + np.diff(brk)[:, None] * f[None, :]).ravel(), brk[-1])


def _quadrature_points(nodes: np.ndarray) -> np.ndarray:
    """Gauss-Legendre points of each table interval, shape ``(len(nodes) - 1, 5)``."""
    h = np.diff(nodes)
    return nodes[:-1, None] + h[:, None] * _GL_X[None, :]


@numba.njit(cache=True, nogil=True)
def _table_intervals(s, piece, offset, size, s_nodes, out):  # pragma: no cover - compiled
    """``out[i]``: ``offset[k] + j`` with ``j = searchsorted(table, s[i], side="right") - 1`` clipped to
    ``0 .. size[k] - 2``, ``table = s_nodes[offset[k]:offset[k] + size[k]]`` of the row's piece ``k = piece[i]``
    (the first table node above ``s[i]``, by bisection)."""
    for i in range(s.shape[0]):
        k = piece[i]
        lo = 0
        hi = size[k]
        while lo < hi:
            mid = (lo + hi) >> 1
            if s_nodes[offset[k] + mid] <= s[i]:
                lo = mid + 1
            else:
                hi = mid
        out[i] = offset[k] + min(max(lo - 1, 0), size[k] - 2)


def curve_frame_rates(d1: np.ndarray, d2: np.ndarray, d3: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Curvature vector [1/mm], its arc-length derivative normal to the tangent [1/mm^2] and the unit tangent of
    a curve at points where its first three parameter derivatives are ``d1``, ``d2``, ``d3`` (rows), as
    :meth:`SplineCurve.bounds` states them."""
    g11 = np.einsum("ij,ij->i", d1, d1)
    g12 = np.einsum("ij,ij->i", d1, d2)
    g22 = np.einsum("ij,ij->i", d2, d2)
    g13 = np.einsum("ij,ij->i", d1, d3)
    n = d2 * g11[:, None] - g12[:, None] * d1
    n_u = d3 * g11[:, None] + g12[:, None] * d2 - (g13 + g22)[:, None] * d1
    k = n / (g11 * g11)[:, None]
    k_u = n_u / (g11 * g11)[:, None] - n * (4.0 * g12 / g11**3)[:, None]
    sigma = np.sqrt(g11)
    tan = d1 / sigma[:, None]
    k_s = k_u / sigma[:, None]
    return k, k_s - np.einsum("ij,ij->i", k_s, tan)[:, None] * tan, tan


def _set_table_bounds(pieces: list[SplineCurve]) -> None:
    """:meth:`SplineCurve.bounds` of pieces of one curve, their derivatives evaluated at once (each row by the
    same expressions as for one piece; the maxima are exact)."""
    d = pieces[0]._d
    u = np.concatenate([np.concatenate([p._nodes[:-1] + 1e-9 * (p.u1 - p.u0), p._nodes[1:] - 1e-9 * (p.u1 - p.u0)])
                        for p in pieces])
    k, k_perp, tan = curve_frame_rates(d[0](u), d[1](u), d[2](u))
    first = np.cumsum([0] + [2 * (len(p._nodes) - 1) for p in pieces[:-1]])
    kappa = np.maximum.reduceat(np.linalg.norm(k, axis=1), first)
    dkappa = np.maximum.reduceat(np.linalg.norm(k_perp, axis=1), first)
    t_abs = np.maximum.reduceat(np.abs(tan), first, axis=0)
    # between two nodes h apart a tangent component exceeds the larger of its node values by at most kappa h / 2
    # (|dt/ds| = kappa): a curve whose tangent turns through an axis between nodes ran that axis over its
    # velocity limit (setpoint fuzzer, tnc_cam seed 239: 0.46 %)
    between = kappa * np.array([np.diff(p._s_nodes).max() for p in pieces]) / 2
    t_abs = np.where(t_abs > 0, np.minimum(t_abs + between[:, None], 1.0), 0.0)
    for p, a, b, c in zip(pieces, kappa.tolist(), dkappa.tolist(), t_abs):
        p._bounds = (a, b, c)


Segment = Line | Arc | ClothoidPair


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class Path:
    """Ordered exact primitives of a toolpath.

    Attributes
    ----------
    segments : tuple of Line, Arc or ClothoidPair
        The primitives, each starting where the previous one ends (for a program path;
        a path with blended corners starts a new segment where the blend leaves the line).
    blocks : tuple of int
        For each segment, the index of the program block it belongs to (``Program.blocks``).
    axes : tuple of str
        Axes the path is reported on (canonical order, subset of ``x, y, z``).
    """

    segments: tuple[Segment, ...]
    blocks: tuple[int, ...]
    axes: tuple[str, ...] = AXIS_LETTERS

    def __post_init__(self) -> None:
        if len(self.segments) != len(self.blocks):
            raise InputError(
                f"Path needs one block index per segment: {len(self.segments)} segments, {len(self.blocks)} blocks"
            )

    def __len__(self) -> int:
        return len(self.segments)

    def __iter__(self) -> Iterator[Segment]:
        return iter(self.segments)

    def __getitem__(self, i: int) -> Segment:
        return self.segments[i]

    @property
    def length(self) -> float:
        """Total length [mm]."""
        return float(sum(seg.length for seg in self.segments))

    def points(self, *, step: float = 0.1) -> np.ndarray:
        """Points along the whole path, at most ``step`` [mm] apart (for plots); shape (M, 3)."""
        out = []
        for seg in self.segments:
            n = max(2, int(math.ceil(seg.length / step)) + 1)
            out.append(seg.point_at(np.linspace(0.0, seg.length, n)))
        return np.concatenate(out) if out else np.zeros((0, 3))

    def plot(self, ax=None, **kwargs):  # noqa: ANN001 - matplotlib Axes
        """Draw the path in the plane of its first two axes; returns the Axes."""
        if ax is None:
            import matplotlib.pyplot as plt

            _, ax = plt.subplots()
        idx = [AXIS_LETTERS.index(a) for a in self.axes if a in AXIS_LETTERS][:2] or [0, 1]
        if len(idx) == 1:
            idx = [idx[0], 1 if idx[0] != 1 else 0]
        pts = self.points()
        ax.plot(pts[:, idx[0]], pts[:, idx[1]], **kwargs)
        ax.set_xlabel(f"{AXIS_LETTERS[idx[0]]} [mm]")
        ax.set_ylabel(f"{AXIS_LETTERS[idx[1]]} [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        return ax
