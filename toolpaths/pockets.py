"""Pockets with islands: a region of the plane bounded by closed contours of lines and arcs, the exact
distance to its boundary and its contour-parallel offset rings (the tool-centre paths that clear it).

The region is the union of the pockets less the union of the islands (HEIDENHAIN's SL cycles superimpose
their contours so: TNC 426/430 user's manual, "SL Cycles", "Overlapping contours"). Its boundary is found
exactly: every edge is cut where it meets another one, and a piece is kept when the region lies on one side of
it only. The distance of a point to that boundary is exact (lines and arcs), signed: > 0 inside the region.

An offset ring at level ``r`` is a closed polyline on ``{x: d(x) = r}``, traced exactly: a point at the distance
``r`` lies on the offset of the boundary piece nearest to it, so the boundary's offset curves (lines parallel to
the lines, arcs about the arcs' centres, arcs about the corners the region wraps round) are cut where they meet,
the parts at the distance ``r`` kept and joined end to start; narrow necks, fingers and thin rings of the level set
come out as they are. Should those parts not join up (rounding at a degenerate meeting), the level is traced on a
grid of the distance (``contourpy``'s marching squares, at most ``_MAX_CELLS`` points) instead. Each vertex is
then moved onto the exact level with Newton steps along the distance's gradient (``|grad d| = 1``, one step lands
exactly while the nearest boundary point stays the same), and chords are split or merged until each of them keeps
within :data:`TOLERANCE` of the level set at 7 points along it, never nearer the boundary than ``r`` (but where
the ring pinches: ``r - TOLERANCE``).
"""

from __future__ import annotations

import dataclasses
import functools
import math

import contourpy
import numba
import numpy as np

__all__ = ["TOLERANCE", "Edge", "Region", "region", "offset_rings", "segment_clear"]

#: The chord tolerance of the offset rings [mm]: each ring lies between ``r`` and ``r + TOLERANCE`` from the
#: boundary (its vertices within 1e-9 mm of ``r + TOLERANCE / 2``), but where it pinches (two offsets crossing by
#: less than the tolerance, as when a gap is just 2 r wide): there its chord keeps ``r - TOLERANCE``.
TOLERANCE = 1e-3
_MAX_CELLS = 600_000  # grid points of the distance field, at most
_FRACTIONS = np.linspace(0.125, 0.875, 7)  # where a chord is checked


@dataclasses.dataclass(frozen=True, kw_only=True)
class Edge:
    """A line (``centre`` None) or an arc of a contour in the plane, in mm.

    Attributes
    ----------
    start, end : numpy.ndarray
        The end points (2,) [mm].
    centre : numpy.ndarray or None
        The arc's centre (2,) [mm]; ``None`` for a line.
    radius, a0, sweep : float
        The arc's radius [mm], start angle and signed sweep (> 0 counter-clockwise) [rad]; 0 for a line.
    """

    start: np.ndarray
    end: np.ndarray
    centre: np.ndarray | None = None
    radius: float = 0.0
    a0: float = 0.0
    sweep: float = 0.0

    def at(self, u: np.ndarray) -> np.ndarray:
        """Points (n, 2) at the fractions ``u`` (n,) of the edge."""
        u = np.asarray(u, dtype=float)[:, None]
        if self.centre is None:
            return self.start + u * (self.end - self.start)
        a = self.a0 + u[:, 0] * self.sweep
        return self.centre + self.radius * np.stack([np.cos(a), np.sin(a)], axis=1)

    def fraction(self, point: np.ndarray) -> float:
        """The fraction of the edge at ``point`` (on or next to it; outside [0, 1] when beyond the ends)."""
        if self.centre is None:
            u = self.end - self.start
            return float((point - self.start) @ u / (u @ u))
        v = point - self.centre
        rel = (math.atan2(v[1], v[0]) - self.a0) * (1.0 if self.sweep > 0 else -1.0) % (2 * math.pi)
        if rel > abs(self.sweep) + 1e-12 and 2 * math.pi - rel < 1e-9:
            rel -= 2 * math.pi
        return rel / abs(self.sweep)

    def piece(self, u0: float, u1: float) -> Edge:
        """The part of the edge between the fractions ``u0 < u1``."""
        a, b = self.at(np.array([u0, u1]))
        if self.centre is None:
            return Edge(start=a, end=b)
        return Edge(start=a, end=b, centre=self.centre, radius=self.radius, a0=self.a0 + u0 * self.sweep,
                    sweep=(u1 - u0) * self.sweep)


def _y_monotone(edges: list[Edge]) -> list[Edge]:
    """The edges cut where arcs turn in y (at the angles +-pi/2), for exact ray casting."""
    out = []
    for e in edges:
        if e.centre is None:
            out.append(e)
            continue
        cuts = [0.0, 1.0]
        for k in range(-4, 5):
            turn = math.pi / 2 + k * math.pi
            u = (turn - e.a0) / e.sweep
            if 1e-12 < u < 1 - 1e-12:
                cuts.append(u)
        cuts.sort()
        pieces = [e.piece(a, b) for a, b in zip(cuts, cuts[1:])]
        # the edge's own ends, not their recomputed angles (sin(-2 pi) != 0): a vertex on a ray counts once
        pieces[0] = dataclasses.replace(pieces[0], start=e.start)
        pieces[-1] = dataclasses.replace(pieces[-1], end=e.end)
        out += pieces
    return out


def _inside_loop(points: np.ndarray, monotone: list[Edge]) -> np.ndarray:
    """Even-odd ray casting (+x) of ``points`` (n, 2) against a closed loop of y-monotone edges, exact."""
    x, y = points[:, 0], points[:, 1]
    inside = np.zeros(len(points), dtype=bool)
    for e in monotone:
        (x0, y0), (x1, y1) = e.start, e.end
        crosses = (y0 > y) != (y1 > y)
        if not np.any(crosses):
            continue
        if e.centre is None:
            xs = x0 + (y - y0) * (x1 - x0) / ((y1 - y0) or 1.0)
        else:
            side = 1.0 if math.cos(e.a0 + e.sweep / 2) >= 0 else -1.0
            xs = e.centre[0] + side * np.sqrt(np.maximum(e.radius ** 2 - (y - e.centre[1]) ** 2, 0.0))
        inside ^= crosses & (x < xs)
    return inside


def _packed(edges: tuple[Edge, ...]) -> tuple[np.ndarray, np.ndarray]:
    """The edges as arrays for :func:`_nearest_kernel`: ``(is_arc (m,), values (m, 9))``, the values being
    start x, y, end x, y, centre x, y, radius, a0, sweep (centre, radius, a0, sweep 0 for a line)."""
    is_arc = np.array([e.centre is not None for e in edges], dtype=np.bool_)
    values = np.array([[*e.start, *e.end, *(e.centre if e.centre is not None else (0.0, 0.0)), e.radius, e.a0,
                        e.sweep] for e in edges], dtype=float).reshape(len(edges), 9)
    return is_arc, values


@numba.njit(cache=True, nogil=True)
def _nearest_kernel(points, is_arc, values, best, near, which):  # pragma: no cover - compiled
    """:func:`_nearest` as one loop over the points and edges (the same formulas as the edges' geometry): the
    distance of each point to the nearest edge into ``best``, that point into ``near``, the edge into ``which``;
    an arc's nearest point is its radial projection while that lies on the arc, else its nearer end."""
    two_pi = 2.0 * math.pi
    for i in range(points.shape[0]):
        x, y = points[i, 0], points[i, 1]
        b, bx, by, bk = math.inf, 0.0, 0.0, 0
        for k in range(is_arc.shape[0]):
            sx, sy, ex, ey = values[k, 0], values[k, 1], values[k, 2], values[k, 3]
            if not is_arc[k]:
                ux, uy = ex - sx, ey - sy
                uu = ux * ux + uy * uy
                t = 0.0
                if uu > 0:
                    t = min(max(((x - sx) * ux + (y - sy) * uy) / uu, 0.0), 1.0)
                qx, qy = sx + t * ux, sy + t * uy
            else:
                cx, cy, radius, a0, sweep = values[k, 4], values[k, 5], values[k, 6], values[k, 7], values[k, 8]
                vx, vy = x - cx, y - cy
                rel = ((math.atan2(vy, vx) - a0) * (1.0 if sweep > 0 else -1.0)) % two_pi
                if rel <= abs(sweep):
                    norm = math.sqrt(vx * vx + vy * vy)
                    if norm > 0:
                        qx, qy = cx + radius * (vx / norm), cy + radius * (vy / norm)
                    else:
                        qx, qy = cx + radius, cy
                elif math.sqrt((x - sx) ** 2 + (y - sy) ** 2) <= math.sqrt((x - ex) ** 2 + (y - ey) ** 2):
                    qx, qy = sx, sy
                else:
                    qx, qy = ex, ey
            d = math.sqrt((x - qx) ** 2 + (y - qy) ** 2)
            if d < b:
                b, bx, by, bk = d, qx, qy, k
        best[i] = b
        near[i, 0] = bx
        near[i, 1] = by
        which[i] = bk


def _nearest(points: np.ndarray, packed: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The distance of each point (n, 2) to the nearest edge of ``packed`` (:func:`_packed`) [mm], that nearest
    point (n, 2) and the edge's index."""
    points = np.ascontiguousarray(points, dtype=float)
    best = np.full(len(points), np.inf)
    near = np.zeros_like(points)
    which = np.zeros(len(points), dtype=np.int64)
    _nearest_kernel(points, packed[0], packed[1], best, near, which)
    return best, near, which


def _meet(e: Edge, f: Edge) -> list[np.ndarray]:
    """The points where the lines/circles of ``e`` and ``f`` meet."""
    if e.centre is None and f.centre is None:
        u, v, w = e.end - e.start, f.end - f.start, f.start - e.start
        den = u[0] * v[1] - u[1] * v[0]
        if abs(den) < 1e-15 * (u @ u + v @ v):
            return []
        return [e.start + (w[0] * v[1] - w[1] * v[0]) / den * u]
    if e.centre is None or f.centre is None:
        line, arc = (e, f) if e.centre is None else (f, e)
        u = line.end - line.start
        w = line.start - arc.centre
        a, b, c = u @ u, 2 * (w @ u), w @ w - arc.radius ** 2
        disc = b * b - 4 * a * c
        if disc < 0:
            return []
        return [line.start + (-b + s * math.sqrt(disc)) / (2 * a) * u for s in (-1.0, 1.0)]
    dv = f.centre - e.centre
    dist = math.hypot(*dv)
    if dist < 1e-12 or dist > e.radius + f.radius or dist < abs(e.radius - f.radius):
        return []
    a = (e.radius ** 2 - f.radius ** 2 + dist ** 2) / (2 * dist)
    h = math.sqrt(max(e.radius ** 2 - a * a, 0.0))
    mid, perp = e.centre + a * dv / dist, np.array([-dv[1], dv[0]]) / dist
    return [mid + h * perp, mid - h * perp]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Region:
    """The union of the ``pockets`` less the union of the ``islands`` (each a closed loop of edges), with
    its ``boundary``: the pieces of their edges with the region on one side only."""

    pockets: tuple[tuple[Edge, ...], ...]
    islands: tuple[tuple[Edge, ...], ...]
    boundary: tuple[Edge, ...]
    monotone: tuple[tuple[tuple[Edge, ...], ...], tuple[tuple[Edge, ...], ...]]

    @functools.cached_property
    def packed_boundary(self) -> tuple[np.ndarray, np.ndarray]:
        """The boundary's edges as arrays for the compiled distance (:func:`_packed`)."""
        return _packed(self.boundary)

    def contains(self, points: np.ndarray) -> np.ndarray:
        """Which of the points (n, 2) lie inside the region (exactly, up to rounding)."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        inner = np.zeros(len(points), dtype=bool)
        for loop in self.monotone[0]:
            inner |= _inside_loop(points, list(loop))
        for loop in self.monotone[1]:
            inner &= ~_inside_loop(points, list(loop))
        return inner

    def distance(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The signed distance of the points (n, 2) to the boundary [mm] (> 0 inside) and its gradient (n, 2)."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        d, near, _ = _nearest(points, self.packed_boundary)
        sign = np.where(self.contains(points), 1.0, -1.0)
        diff = points - near
        grad = sign[:, None] * np.divide(diff, d[:, None], out=np.zeros_like(diff), where=d[:, None] > 0)
        return sign * d, grad

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """The lower and upper corners of a box around the pockets [mm]."""
        pts = np.concatenate([e.at(np.linspace(0, 1, 33)) for loop in self.pockets for e in loop])
        return pts.min(axis=0), pts.max(axis=0)


def region(pockets: list[list[Edge]], islands: list[list[Edge]]) -> Region:
    """The region of the closed loops ``pockets`` less ``islands`` (each loop's edges end to end)."""
    monotone = (tuple(tuple(_y_monotone(p)) for p in pockets), tuple(tuple(_y_monotone(i)) for i in islands))
    draft = Region(pockets=tuple(map(tuple, pockets)), islands=tuple(map(tuple, islands)), boundary=(),
                   monotone=monotone)
    edges = [e for loop in (*pockets, *islands) for e in loop]
    cuts: list[list[float]] = [[0.0, 1.0] for _ in edges]
    for i, e in enumerate(edges):
        for j in range(i + 1, len(edges)):
            for p in _meet(e, edges[j]):
                ue, uf = e.fraction(p), edges[j].fraction(p)
                if -1e-12 <= ue <= 1 + 1e-12 and -1e-12 <= uf <= 1 + 1e-12:
                    cuts[i].append(min(max(ue, 0.0), 1.0))
                    cuts[j].append(min(max(uf, 0.0), 1.0))
    kept = []
    for e, us in zip(edges, cuts):
        us = sorted(set(us))
        for u0, u1 in zip(us, us[1:]):
            if u1 - u0 < 1e-12:
                continue
            piece = e.piece(u0, u1)
            mid, ahead = piece.at(np.array([0.5, 0.5 + 1e-6]))
            tangent = (ahead - mid) / (np.linalg.norm(ahead - mid) or 1.0)
            normal = np.array([-tangent[1], tangent[0]]) * 1e-7 * max(1.0, float(np.max(np.abs(mid))))
            left, right = draft.contains(np.array([mid + normal, mid - normal]))
            if left != right:
                kept.append(piece)
    return dataclasses.replace(draft, boundary=tuple(kept))


def _project(region_: Region, v: np.ndarray, target: float) -> np.ndarray:
    for _ in range(6):
        d, g = region_.distance(v)
        if np.all(np.abs(d - target) < 1e-12):
            break
        v = v - (d - target)[:, None] * g
    return v


def _offset_curve(region_: Region, x: np.ndarray) -> Edge:
    """The offset curve through ``x`` of the boundary piece nearest to it: a line parallel to a line piece, or a
    circle about an arc's centre or about the piece's end nearest to ``x`` (as an edge; only its line or circle
    is used)."""
    _, near, which = _nearest(x[None], region_.packed_boundary)
    e, p = region_.boundary[int(which[0])], near[0]
    at_end = min(np.linalg.norm(p - e.start), np.linalg.norm(p - e.end)) < 1e-12
    if e.centre is None and not at_end:
        return Edge(start=x, end=x + (e.end - e.start))
    centre = e.centre if e.centre is not None and not at_end else p
    return Edge(start=x, end=x, centre=centre, radius=float(np.linalg.norm(x - centre)), sweep=2 * math.pi)


def _corner(region_: Region, a: np.ndarray, b: np.ndarray, target: float, tolerance: float) -> np.ndarray | None:
    """The corner of the level set ``target`` between its points ``a`` and ``b``, if they lie on the offsets of
    two different boundary pieces and those offsets meet on the level set near the chord; else ``None``."""
    ea, eb = _offset_curve(region_, a), _offset_curve(region_, b)
    chord = float(np.linalg.norm(b - a))
    best = None
    for c in _meet(ea, eb):
        gap = min(np.linalg.norm(c - a), np.linalg.norm(c - b))
        if gap < tolerance / 10 or np.linalg.norm(c - (a + b) / 2) > 1000 * chord:
            continue
        u = np.linspace(0.0, 1.0, 65)[:, None]
        sides = np.concatenate([a + u * (c - a), c + u * (b - c)])
        reach = max(np.linalg.norm(c - a), np.linalg.norm(c - b))
        if region_.distance(sides)[0].min() < target - tolerance / 2 - reach / 4:
            continue  # the corner of another part of the ring: a chord to it dips farther than an arc's would
        if abs(region_.distance(c[None])[0][0] - target) < tolerance / 20 and (
                best is None or np.linalg.norm(c - (a + b) / 2) < np.linalg.norm(best - (a + b) / 2)):
            best = c
    return best


class _Unsettled(ValueError):
    """A traced ring whose chords cannot be brought within the tolerance: the grid joined two rings across a
    neck narrower than its cells (or missed a sharp turn); a finer grid separates them."""


def _project_across(region_: Region, a: np.ndarray, b: np.ndarray, target: float, tolerance: float) -> np.ndarray:
    """The middles of the chords ``a``-``b`` (n, 2) moved square to them onto the level ``target`` (Newton along
    the chord's normal, which finds the ring between the chord's ends even at its sharp corners); where that
    fails, along the distance's gradient."""
    m = (a + b) / 2
    u = b - a
    n = np.stack([-u[:, 1], u[:, 0]], axis=1) / np.maximum(np.linalg.norm(u, axis=1), 1e-300)[:, None]
    t = np.zeros(len(m))
    reach = np.linalg.norm(u, axis=1)
    for _ in range(12):
        d, g = region_.distance(m + t[:, None] * n)
        if np.all(np.abs(d - target) < 1e-12):
            break
        slope = np.sum(g * n, axis=1)
        step = np.divide(d - target, slope, out=np.zeros_like(d), where=np.abs(slope) > 1e-3)
        t = np.clip(t - step, -reach, reach)
    p = m + t[:, None] * n
    far = np.flatnonzero(region_.distance(m)[0] > target + tolerance / 2)
    for k in far:  # a sharp corner of the ring between the ends: where their offset curves meet
        corner = _corner(region_, a[k], b[k], target, tolerance)
        if corner is not None:
            p[k] = corner
    miss = np.abs(region_.distance(p)[0] - target) > tolerance / 20
    p[miss] = _project(region_, m[miss], target)
    return p


def _merged(v: np.ndarray, deviation: float) -> np.ndarray | None:
    """The closed polyline with every other vertex dropped, pass after pass, that lies within ``deviation`` [mm] of
    its neighbours' chord, down to a triangle; ``None`` when fewer than 3 vertices are left."""
    for _ in range(60):
        if len(v) < 4:
            return v if len(v) == 3 else None
        a, b = np.roll(v, 1, axis=0), np.roll(v, -1, axis=0)
        u = b - a
        ln = np.linalg.norm(u, axis=1)
        dev = np.abs(u[:, 0] * (v - a)[:, 1] - u[:, 1] * (v - a)[:, 0]) / np.where(ln > 0, ln, 1.0)
        drop = (dev < deviation) & (np.arange(len(v)) % 2 == 1)
        if not np.any(drop):
            drop = (dev < deviation) & (np.arange(len(v)) % 2 == 0) & (np.arange(len(v)) < len(v) - 1)
            if not np.any(drop):
                break
        v = v[~drop]
    return v


def _polish(region_: Region, v: np.ndarray, level: float, tolerance: float, *, merge: bool) -> np.ndarray | None:
    """The closed polyline ``v`` (n, 2) moved onto the level set ``level + tolerance / 2`` and its chords split
    (and first merged, when ``merge``: a grid's dense points) to keep each within ``[level, level + tolerance]``
    (at 7 points); ``None`` when it vanishes."""
    target = level + tolerance / 2
    v = _project(region_, v, target)
    v = v[np.abs(region_.distance(v)[0] - target) < tolerance / 20]
    v = _merged(v, tolerance / 4) if merge else (v if len(v) >= 3 else None)
    if v is None:
        return None
    fractions = _FRACTIONS
    todo = np.ones(len(v), dtype=bool)
    for _ in range(60):  # split: each chord off the band gets its projected middle
        b = np.roll(v, -1, axis=0)
        bad = np.zeros(len(v), dtype=bool)
        pts = v[todo, None, :] + fractions[None, :, None] * (b[todo] - v[todo])[:, None, :]
        d = region_.distance(pts.reshape(-1, 2))[0].reshape(len(pts), len(fractions))
        # a chord shorter than tolerance / 4 is within it anyway
        bad[todo] = (d.min(axis=1) < level - 1e-9) | (d.max(axis=1) > level + tolerance)
        bad &= np.linalg.norm(b - v, axis=1) > tolerance / 4
        if len(v) > 200_000:
            break
        if not np.any(bad):
            return _merged(v, 1e-9)  # the points the splitting left on straight stretches
        mids = _project_across(region_, v[bad], b[bad], target, tolerance)
        out = np.empty((len(v) + len(mids), 2))
        idx = np.arange(len(v)) + np.concatenate([[0], np.cumsum(bad)[:-1]])
        out[idx] = v
        out[idx[bad] + 1] = mids
        v = out
        todo = np.zeros(len(v), dtype=bool)  # only the chords of the new points are checked again
        todo[idx[bad]] = todo[idx[bad] + 1] = True
    b = np.roll(v, -1, axis=0)
    pts = v[:, None, :] + fractions[None, :, None] * (b - v)[:, None, :]
    d = region_.distance(pts.reshape(-1, 2))[0]
    if d.min() < level - tolerance or d.max() > level + 2 * tolerance:
        raise _Unsettled(f"an offset ring at {level:g} mm did not settle within {tolerance:g} mm")
    return v  # where the ring pinches (two offsets crossing by less than the tolerance): within it of the level


def _reversed(e: Edge) -> Edge:
    """The edge run the other way."""
    if e.centre is None:
        return Edge(start=e.end, end=e.start)
    return Edge(start=e.end, end=e.start, centre=e.centre, radius=e.radius, a0=e.a0 + e.sweep, sweep=-e.sweep)


def _tangent(e: Edge, u: float) -> np.ndarray:
    """The unit direction of the edge at the fraction ``u``."""
    if e.centre is None:
        return (e.end - e.start) / np.linalg.norm(e.end - e.start)
    a = e.a0 + u * e.sweep
    return math.copysign(1.0, e.sweep) * np.array([-math.sin(a), math.cos(a)])


def _arc(centre: np.ndarray, radius: float, a0: float, sweep: float) -> Edge:
    """The arc about ``centre`` from the angle ``a0`` through ``sweep`` [rad]."""
    a1 = a0 + sweep
    return Edge(start=centre + radius * np.array([math.cos(a0), math.sin(a0)]),
                end=centre + radius * np.array([math.cos(a1), math.sin(a1)]), centre=centre, radius=radius, a0=a0,
                sweep=sweep)


def _raw_offset(region_: Region, target: float) -> list[Edge]:
    """The boundary's offset curves at ``target`` [mm] into the region, each run with the region on its left: a
    line parallel to each line piece, an arc about each arc's centre (none where the arc's radius is smaller on
    the region's side), and an arc about each corner the region wraps round (turning right), from one
    neighbour's offset to the other's. The level set ``{d = target}`` is made of parts of these curves."""
    left = []
    for e in region_.boundary:
        mid, tangent = e.at(np.array([0.5]))[0], _tangent(e, 0.5)
        left.append(mid + np.array([-tangent[1], tangent[0]]) * 1e-7 * max(1.0, float(np.max(np.abs(mid)))))
    inside = region_.contains(np.array(left).reshape(-1, 2))
    pieces = [e if keep else _reversed(e) for e, keep in zip(region_.boundary, inside)]  # the region on the left
    curves = []
    for e in pieces:
        if e.centre is None:
            t = _tangent(e, 0.0)
            n = target * np.array([-t[1], t[0]])
            curves.append(Edge(start=e.start + n, end=e.end + n))
        else:
            rho = e.radius - target if e.sweep > 0 else e.radius + target  # ccw: the region towards the centre
            if rho > 1e-12:
                curves.append(_arc(e.centre, rho, e.a0, e.sweep))
    starts = np.array([e.start for e in pieces])
    for a in pieces:  # the corner at its end, with the piece that leaves it
        gap = np.linalg.norm(starts - a.end, axis=1)
        near = np.flatnonzero(gap <= 1e-7 * max(1.0, float(np.max(np.abs(a.end)))))
        t_in = _tangent(a, 1.0)
        for b in (pieces[k] for k in near):
            t_out = _tangent(b, 0.0)
            turn = math.atan2(t_in[0] * t_out[1] - t_in[1] * t_out[0], t_in @ t_out)
            if turn < -1e-9:  # a right turn: the region wraps round the corner
                curves.append(_arc(a.end, target, math.atan2(t_in[0], -t_in[1]), turn))
    return curves


def _box(e: Edge) -> list[float]:
    """The edge's bounding box: lower x, y, upper x, y [mm] (an arc's ends and the quarter points it passes)."""
    pts = [e.start, e.end]
    if e.centre is not None:
        for k in range(4):
            if (k * math.pi / 2 - e.a0) * math.copysign(1.0, e.sweep) % (2 * math.pi) <= abs(e.sweep):
                pts.append(e.centre + e.radius * np.array([math.cos(k * math.pi / 2), math.sin(k * math.pi / 2)]))
    return [*np.min(pts, axis=0), *np.max(pts, axis=0)]


def _cut_points(curves: list[Edge]) -> list[list[float]]:
    """The fractions of each curve where it meets another (its ends included)."""
    box = np.array([_box(c) for c in curves]).reshape(len(curves), 4)
    margin = 1e-9 * max(1.0, float(np.max(np.abs(box)))) if len(curves) else 0.0
    pairs = []
    for k in range(0, len(curves), 500):  # the boxes that overlap, 500 rows at a time
        b = box[k:k + 500, None, :]
        overlap = ((b[..., 0] <= box[None, :, 2] + margin) & (box[None, :, 0] <= b[..., 2] + margin)
                   & (b[..., 1] <= box[None, :, 3] + margin) & (box[None, :, 1] <= b[..., 3] + margin))
        i, j = np.nonzero(overlap)
        pairs += [(a + k, c) for a, c in zip(i.tolist(), j.tolist()) if c > a + k]
    cuts: list[list[float]] = [[0.0, 1.0] for _ in curves]
    for i, j in pairs:
        for p in _meet(curves[i], curves[j]):
            ui, uj = curves[i].fraction(p), curves[j].fraction(p)
            if -1e-9 <= ui <= 1 + 1e-9 and -1e-9 <= uj <= 1 + 1e-9:
                cuts[i].append(min(max(ui, 0.0), 1.0))
                cuts[j].append(min(max(uj, 0.0), 1.0))
    return cuts


def _level_pieces(region_: Region, target: float, tolerance: float) -> list[np.ndarray]:
    """The parts of the boundary's offset curves (:func:`_raw_offset`) that lie on the level set ``target``,
    each as points (n, 2) from its start to its end, its chords within ``0.4 tolerance`` of it (``target`` being
    the band's middle, they keep within the band whichever side of them the region lies)."""
    curves = _raw_offset(region_, target)
    parts = []
    for c, us in zip(curves, _cut_points(curves)):
        us = sorted(set(us))
        parts += [c.piece(u0, u1) for u0, u1 in zip(us, us[1:]) if u1 - u0 > 1e-12]
    if not parts:
        return []
    mids = np.array([p.at(np.array([0.5]))[0] for p in parts])
    on = region_.distance(mids)[0] >= target - 1e-9 * max(1.0, float(np.max(np.abs(mids))))
    out = []
    for p in (p for p, keep in zip(parts, on) if keep):
        if p.centre is None:
            out.append(np.array([p.start, p.end]))
            continue
        chord = 2 * math.acos(max(1.0 - 0.4 * tolerance / p.radius, -1.0))
        out.append(p.at(np.linspace(0.0, 1.0, max(1, math.ceil(abs(p.sweep) / chord)) + 1)))
    return out


def _exact_lines(region_: Region, target: float, tolerance: float) -> list[np.ndarray]:
    """The closed lines (each (n, 2), its last point its first) of the level set ``target`` [mm], made of the
    parts of the boundary's offset curves on it (:func:`_level_pieces`) joined end to start, each to the nearest
    start (within ``tolerance``: a join across a finger of the level set that narrow keeps its chord in the band).
    """
    pieces = _level_pieces(region_, target, tolerance)
    starts = np.array([p[0] for p in pieces]).reshape(-1, 2)
    free = np.ones(len(pieces), dtype=bool)
    lines = []
    while np.any(free):
        first = int(np.argmax(free))
        free[first] = False
        loop, k = [pieces[first]], first
        while True:
            gap = np.linalg.norm(starts - pieces[k][-1], axis=1)
            gap[~free] = np.inf
            gap[first] = np.linalg.norm(starts[first] - pieces[k][-1])
            k = int(np.argmin(gap))
            if gap[k] > tolerance:
                raise _Unsettled(f"the offset at {target:g} mm does not close (a gap of {gap[k]:.3g} mm)")
            if k == first:
                break
            free[k] = False
            loop.append(pieces[k])
        line = np.concatenate([p[:-1] for p in loop])
        lines.append(np.concatenate([line, line[:1]]))
    return lines


def offset_rings(region_: Region, levels: list[float], *, step: float, tolerance: float = TOLERANCE,
                 left_higher: bool = True) -> list[list[np.ndarray]]:
    """The closed offset rings (each (n, 2), first point not repeated) at each of ``levels`` [mm] from the
    region's boundary, traced from the boundary's offset curves (:func:`_exact_lines`) or, should those not join
    up, on a grid of about ``step`` [mm], then made exact within ``tolerance`` [mm]. Each ring runs with the
    region's inside (the higher distance) on its left when ``left_higher`` (counter-clockwise round a pocket,
    clockwise round an island), else the other way."""
    grid: list[contourpy.ContourGenerator] = []
    out = []
    for level in levels:
        target = level + tolerance / 2
        try:  # the exact lines are sparse already, their chords within the band: not merged
            rings = _traced_rings(region_, level, _exact_lines(region_, target, tolerance), tolerance, left_higher,
                                  merge=False)
        except _Unsettled:
            grid = grid or [_grid(region_, step)]
            rings = _traced_rings(region_, level, grid[0].lines(target), tolerance, left_higher, merge=True)
        out.append(rings)
    return out


def _grid(region_: Region, step: float) -> contourpy.ContourGenerator:
    """The marching squares of the region's distance on a grid of about ``step`` [mm] (at most ``_MAX_CELLS``
    points) round the pockets."""
    lo, hi = region_.bounds()
    step = max(step, math.sqrt(float(np.prod(hi - lo + 4 * step)) / _MAX_CELLS))
    xs = np.arange(lo[0] - 2 * step, hi[0] + 2 * step + step / 2, step)
    ys = np.arange(lo[1] - 2 * step, hi[1] + 2 * step + step / 2, step)
    gx, gy = np.meshgrid(xs, ys)
    z = region_.distance(np.stack([gx.ravel(), gy.ravel()], axis=1))[0].reshape(gx.shape)
    return contourpy.contour_generator(xs, ys, z, line_type=contourpy.LineType.Separate)


def _traced_rings(region_: Region, level: float, lines, tolerance: float, left_higher: bool, *,
                  merge: bool) -> list[np.ndarray]:
    """The closed ``lines`` (each (n, 2), its last point its first) of the level, polished (:func:`_polish`) and
    turned the way asked."""
    rings = []
    for line in lines:
        if len(line) < 4 or np.linalg.norm(line[0] - line[-1]) > 1e-9:
            continue
        v = _polish(region_, np.asarray(line[:-1], dtype=float), level, tolerance, merge=merge)
        if v is None:
            continue
        b = np.roll(v, -1, axis=0)
        _, g = region_.distance((v + b) / 2)
        t = b - v
        if (np.sum(t[:, 0] * g[:, 1] - t[:, 1] * g[:, 0]) > 0) != left_higher:
            v = v[::-1].copy()
        rings.append(v)
    return rings


def segment_clear(region_: Region, a: np.ndarray, b: np.ndarray, level: float, *,
                  tolerance: float = TOLERANCE) -> bool:
    """Whether every point of the straight segment ``a``-``b`` lies at least ``level - tolerance`` [mm] inside
    the region: proven by halving, since the distance changes no faster than the path (``|grad d| <= 1``)."""
    todo = [(np.asarray(a, dtype=float), np.asarray(b, dtype=float))]
    while todo:
        starts = np.array([s for s, _ in todo])
        ends = np.array([e for _, e in todo])
        d = region_.distance(np.concatenate([starts, ends]))[0]
        da, db = d[:len(todo)], d[len(todo):]
        length = np.linalg.norm(ends - starts, axis=1)
        if np.any(np.minimum(da, db) < level - tolerance):
            return False
        open_ = (da + db - length) / 2 < level - tolerance
        if np.any(open_ & (length < tolerance)):
            return False
        mids = (starts + ends) / 2
        todo = [pair for k in np.flatnonzero(open_) for pair in ((starts[k], mids[k]), (mids[k], ends[k]))]
        if len(todo) > 1_000_000:
            return False
    return True
