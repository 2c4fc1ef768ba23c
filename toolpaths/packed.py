"""Segments packed into arrays, for evaluating many points on mixed lines, arcs and clothoid blends at once."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numba
import numpy as np

from toolpaths.geometry import Arc, ClothoidPair, Line

__all__ = ["PackedSegments", "LINE", "ARC", "HOLD", "CLOTHOID", "euler_spiral_point"]

#: Segment kinds in :attr:`PackedSegments.kind`.
LINE, ARC, HOLD, CLOTHOID = 0, 1, 2, 3

_KIND = {Line: LINE, Arc: ARC, ClothoidPair: CLOTHOID}


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class PackedSegments:
    """Array form of a sequence of segments.

    Attributes
    ----------
    kind : ndarray of int, shape (n,)
        ``LINE`` (0), ``ARC`` (1), ``HOLD`` (2: a fixed point, e.g. a dwell; ``start == end``) or
        ``CLOTHOID`` (3: a :class:`toolpaths.ClothoidPair` corner blend).
    length : ndarray, shape (n,)
        Arc length [mm] (0 for a hold).
    start, end : ndarray, shape (n, 3)
        End points [mm].
    center, e_p, e_q, e_n : ndarray, shape (n, 3)
        Arc centre [mm] and unit vectors of the in-plane axes p, q and of the normal (zero rows
        for lines and holds).
    radius, start_angle, sweep, helix : ndarray, shape (n,)
        Arc radius [mm], start angle [rad], signed sweep [rad], helix rise [mm] (zero for lines).
    frame : ndarray, shape (n, 4, 3), optional
        Clothoid blends: ``u_in, w_in, u_out, w_out`` (see :class:`toolpaths.ClothoidPair`);
        zero rows for the other kinds. None when there is no clothoid.
    sharpness : ndarray, shape (n,), optional
        Clothoid blends: ``|dk/ds|`` [1/mm^2] (zero for the other kinds); None when there is no
        clothoid.
    """

    kind: np.ndarray
    length: np.ndarray
    start: np.ndarray
    end: np.ndarray
    center: np.ndarray
    e_p: np.ndarray
    e_q: np.ndarray
    e_n: np.ndarray
    radius: np.ndarray
    start_angle: np.ndarray
    sweep: np.ndarray
    helix: np.ndarray
    frame: np.ndarray | None = None
    sharpness: np.ndarray | None = None

    @classmethod
    def from_segments(cls, segments: Sequence[Line | Arc | ClothoidPair | np.ndarray]) -> PackedSegments:
        """Pack lines, arcs, clothoid blends and hold points (a length-3 array [mm] stands for a hold)."""
        n = len(segments)
        kind = np.array([_KIND.get(type(seg), HOLD) for seg in segments], dtype=np.int64).reshape(n)
        length = np.zeros(n)
        start = np.zeros((n, 3))
        end = np.zeros((n, 3))
        center = np.zeros((n, 3))
        e_p = np.zeros((n, 3))
        e_q = np.zeros((n, 3))
        e_n = np.zeros((n, 3))
        radius = np.zeros(n)
        start_angle = np.zeros(n)
        sweep = np.zeros(n)
        helix = np.zeros(n)
        frame = sharpness = None
        moving = np.flatnonzero(kind != HOLD)
        if len(moving):
            segs = [segments[i] for i in moving.tolist()]
            length[moving] = [seg.length for seg in segs]
            start[moving] = [seg.start for seg in segs]
            end[moving] = [seg.end for seg in segs]
        hold = np.flatnonzero(kind == HOLD)
        if len(hold):
            start[hold] = end[hold] = [np.asarray(segments[i], dtype=float) for i in hold.tolist()]
        ia = np.flatnonzero(kind == ARC)
        if len(ia):
            arcs = [segments[i] for i in ia.tolist()]
            center[ia] = [a.center for a in arcs]
            r = np.arange(len(ia))
            pq = np.array([a.plane_axes for a in arcs]).reshape(-1, 2)
            plane = np.array([a.plane for a in arcs])
            for field, col in ((e_p, pq[:, 0]), (e_q, pq[:, 1]), (e_n, plane)):
                unit = np.zeros((len(ia), 3))
                unit[r, col] = 1.0
                field[ia] = unit
            radius[ia] = [a.radius for a in arcs]
            start_angle[ia] = [a.start_angle for a in arcs]
            sweep[ia] = [a.sweep for a in arcs]
            helix[ia] = [a.helix for a in arcs]
        ic = np.flatnonzero(kind == CLOTHOID)
        if len(ic):
            blends = [segments[i] for i in ic.tolist()]
            frame, sharpness = np.zeros((n, 4, 3)), np.zeros(n)
            frame[ic] = [(b.u_in, b.w_in, b.u_out, b.w_out) for b in blends]
            sharpness[ic] = [b.sharpness for b in blends]
        return cls(kind=kind, length=length, start=start, end=end, center=center, e_p=e_p, e_q=e_q, e_n=e_n,
                   radius=radius, start_angle=start_angle, sweep=sweep, helix=helix, frame=frame,
                   sharpness=sharpness)

    def subset(self, idx: np.ndarray) -> PackedSegments:
        """The segments ``idx`` (an index array or boolean mask) as a new PackedSegments."""
        return PackedSegments(**{f: None if getattr(self, f) is None else getattr(self, f)[idx]
                                 for f in self.__dataclass_fields__})

    def __len__(self) -> int:
        return len(self.kind)

    def evaluate(
        self, seg: np.ndarray, s: np.ndarray, v: np.ndarray | None = None, a: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """Position, velocity and acceleration of points moving along the segments.

        Parameters
        ----------
        seg : ndarray of int, shape (m,)
            Segment index of each point.
        s : ndarray, shape (m,)
            Arc length along its segment [mm], clipped to ``[0, length]``.
        v, a : ndarray, shape (m,), optional
            Path speed [mm/s] and path acceleration ds^2/dt^2 [mm/s^2].

        Returns
        -------
        position : ndarray, shape (m, 3)
            [mm]; exactly ``start`` at ``s <= 0`` and exactly ``end`` at ``s >= length``.
        velocity, acceleration : ndarray, shape (m, 3) or None
            ``tangent * v`` [mm/s] and ``tangent * a + curvature * v**2`` [mm/s^2] (None when
            ``v`` / ``a`` are not given; the acceleration needs ``v``).
        """
        seg = np.asarray(seg, dtype=np.int64)
        s = np.asarray(s, dtype=float)
        m = len(seg)
        pos = np.empty((m, 3))
        vel = np.empty((m, 3)) if v is not None else None
        acc = np.empty((m, 3)) if v is not None and a is not None else None
        none = np.zeros(0)
        frame = self.frame if self.frame is not None else np.zeros((0, 4, 3))
        sharpness = self.sharpness if self.sharpness is not None else none
        _evaluate(seg, s, none if v is None else np.asarray(v, dtype=float),
                  none if a is None else np.asarray(a, dtype=float), self.kind, self.length, self.start, self.end,
                  self.center, self.e_p, self.e_q, self.e_n, self.radius, self.start_angle, self.sweep, self.helix,
                  frame, sharpness, pos, none.reshape(0, 3) if vel is None else vel,
                  none.reshape(0, 3) if acc is None else acc)
        return pos, vel, acc


@numba.njit(cache=True, nogil=True, inline="always")
def euler_spiral_point(phi):  # pragma: no cover - compiled
    """:func:`toolpaths.geometry.euler_spiral` of one phase, the same series in the same order (compiled, for
    the sampling loop here and the contour kernel of :mod:`vcnc.contour_kernel`)."""
    x = 0.0
    y = 0.0
    term = 1.0
    for k in range(28):
        sign = 1.0 if k % 4 < 2 else -1.0
        if k % 2 == 0:
            x = x + sign * term / (2 * k + 1)
        else:
            y = y + sign * term / (2 * k + 1)
        term = term * phi / (k + 1)
    return x, y


@numba.njit(cache=True, nogil=True)
def _evaluate(seg, s_in, v, a, kind, length, start, end, center, e_p, e_q, e_n, radius, start_angle, sweep, helix,
              frame, sharpness, pos, vel, acc):  # pragma: no cover - compiled
    """:meth:`PackedSegments.evaluate` as one loop over the points (no temporaries per kind): fills ``pos`` and,
    when ``v`` (and ``a``) are not empty, ``vel`` (and ``acc``); the formulas of the lines, arcs (Arc.point_at,
    tangent_at, curvature_at) and clothoid pairs (ClothoidPair, both halves) in the same order."""
    tan = np.zeros(3)
    curv = np.zeros(3)
    for i in range(seg.shape[0]):
        m = seg[i]
        L = length[m]
        s = min(max(s_in[i], 0.0), L)
        safe_L = L if L > 0 else 1.0
        f = s / safe_L
        k = kind[m]
        for j in range(3):
            tan[j] = 0.0
            curv[j] = 0.0
        if k == LINE:
            for j in range(3):
                d = end[m, j] - start[m, j]
                pos[i, j] = start[m, j] + d * f
                tan[j] = d / safe_L
        elif k == HOLD:
            for j in range(3):
                pos[i, j] = start[m, j]
        elif k == ARC:
            sw = sweep[m]
            phi = start_angle[m] + sw * f
            c = math.cos(phi)
            sn = math.sin(phi)
            r = radius[m]
            hel = helix[m]
            w = r * sw / safe_L
            kk = r * (sw / safe_L) ** 2
            for j in range(3):
                radial = c * e_p[m, j] + sn * e_q[m, j]
                pos[i, j] = center[m, j] + r * radial + (hel * f) * e_n[m, j]
                tan[j] = w * (c * e_q[m, j] - sn * e_p[m, j]) + (hel / safe_L) * e_n[m, j]
                curv[j] = -kk * radial
        else:  # CLOTHOID: the first half from the start, the second backwards from the end
            first = s <= 0.5 * L
            r = s if first else L - s
            phi = 0.5 * sharpness[m] * r * r
            x, y = euler_spiral_point(phi)
            c = math.cos(phi)
            sn = math.sin(phi)
            sgn = 1.0 if first else -1.0
            ku = 0 if first else 2
            for j in range(3):
                u = frame[m, ku, j]
                w = frame[m, ku + 1, j]
                base = start[m, j] if first else end[m, j]
                pos[i, j] = base + (sgn * r * x) * u + (r * y) * w
                tan[j] = c * u + (sgn * sn) * w
                curv[j] = (sharpness[m] * r) * (c * w - (sgn * sn) * u)
        if k != HOLD:
            if s <= 0:
                for j in range(3):
                    pos[i, j] = start[m, j]
            elif s >= L:
                for j in range(3):
                    pos[i, j] = end[m, j]
        if v.shape[0]:
            for j in range(3):
                vel[i, j] = tan[j] * v[i]
            if a.shape[0]:
                for j in range(3):
                    acc[i, j] = tan[j] * a[i] + curv[j] * (v[i] * v[i])
