"""Segments packed into arrays, for evaluating many points on mixed lines, arcs and clothoid blends at once."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from toolpaths.geometry import Arc, ClothoidPair, Line, euler_spiral

__all__ = ["PackedSegments", "LINE", "ARC", "HOLD", "CLOTHOID"]

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
        L = self.length[seg]
        s = np.clip(np.asarray(s, dtype=float), 0.0, L)
        m = len(seg)
        pos = np.empty((m, 3))
        tan = np.zeros((m, 3)) if v is not None else None
        curv = np.zeros((m, 3)) if a is not None else None
        kind = self.kind[seg]
        safe_L = np.where(L > 0, L, 1.0)
        f = s / safe_L

        il = np.flatnonzero(kind == LINE)
        if len(il):
            sl = seg[il]
            st = self.start[sl]
            d = self.end[sl] - st
            pos[il] = st + d * f[il, None]
            if tan is not None:
                tan[il] = d / safe_L[il, None]
        ih = np.flatnonzero(kind == HOLD)
        if len(ih):
            pos[ih] = self.start[seg[ih]]
        ia = np.flatnonzero(kind == ARC)
        if len(ia):
            sa = seg[ia]
            fa = f[ia]
            sw = self.sweep[sa]
            phi = self.start_angle[sa] + sw * fa
            c, sn = np.cos(phi)[:, None], np.sin(phi)[:, None]
            ep, eq, en = self.e_p[sa], self.e_q[sa], self.e_n[sa]
            r = self.radius[sa][:, None]
            hel = self.helix[sa][:, None]
            radial = c * ep + sn * eq
            pos[ia] = self.center[sa] + r * radial + (hel * fa[:, None]) * en
            La = safe_L[ia][:, None]
            if tan is not None:
                tan[ia] = (r * sw[:, None] / La) * (c * eq - sn * ep) + (hel / La) * en
            if curv is not None:
                curv[ia] = -(r * (sw[:, None] / La) ** 2) * radial
        ic = np.flatnonzero(kind == CLOTHOID)
        if len(ic):
            sc = seg[ic]
            Lc, s_c = L[ic], s[ic]
            first = (s_c <= 0.5 * Lc)[:, None]
            r = np.where(first[:, 0], s_c, Lc - s_c)
            phi = 0.5 * self.sharpness[sc] * r * r
            fr = self.frame[sc]
            u = np.where(first, fr[:, 0], fr[:, 2])
            w = np.where(first, fr[:, 1], fr[:, 3])
            sgn = np.where(first[:, 0], 1.0, -1.0)  # the second half runs backwards from the end
            x, y = euler_spiral(phi)
            pos[ic] = np.where(first, self.start[sc], self.end[sc]) + (sgn * r * x)[:, None] * u + (r * y)[:, None] * w
            if tan is not None or curv is not None:
                c, sn = np.cos(phi)[:, None], np.sin(phi)[:, None]
                if tan is not None:
                    tan[ic] = c * u + (sgn[:, None] * sn) * w
                if curv is not None:
                    curv[ic] = (self.sharpness[sc] * r)[:, None] * (c * w - (sgn[:, None] * sn) * u)
        at_end = (s >= L) & (kind != HOLD)
        pos[at_end] = self.end[seg[at_end]]
        at_start = (s <= 0) & (kind != HOLD)
        pos[at_start] = self.start[seg[at_start]]
        vel = acc = None
        if v is not None:
            v = np.asarray(v, dtype=float)
            vel = tan * v[:, None]
            if a is not None:
                acc = tan * np.asarray(a, dtype=float)[:, None] + curv * (v * v)[:, None]
        return pos, vel, acc
