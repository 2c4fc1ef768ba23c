"""Compiled nearest-point search of sampled positions on exact line / arc / helix geometry.

Private to :mod:`vcnc.contour`. The geometry arrives packed (one row per segment, see
:class:`_Geometry`); positions arrive as an ``(N, k)`` array plus the column of each of x, y, z
(``-1``: axis absent, coordinate taken as 0 after the geometry was projected the same way).

Two searches share one closed-form projection (:func:`_project`):

* :func:`locate` walks the commanded positions along the path in order (the segment index never
  decreases) and returns the commanded segment and arc length of every sample;
* :func:`nearest` finds, for every actual position, the nearest point among the segments the
  command visited in a time window around the sample (or among all segments when no command is
  known), pruned by bounding spheres.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from toolpaths.packed import ARC, CLOTHOID, LINE, euler_spiral_point

__all__ = ["LINE", "ARC", "CLOTHOID", "locate", "nearest", "TIE_MM", "BLOCK"]

#: Segments per block of the search's pruning (:func:`nearest`).
BLOCK = 16

#: Distances closer than this [mm] count as equal; ties go to the candidate nearest in arc length
#: to the hint (the commanded position), which separates coincident geometry (a circle run twice).
TIE_MM = 1e-9

_TWO_PI = 2.0 * math.pi


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _project(px, py, pz, m, kind, start, end, direc, length, center, ep, eq, en, radius, phi0, sweep, helix,
             frame, sharp, hint_u):  # pragma: no cover - compiled
    """Nearest point of segment ``m`` to P: (distance, u, foot x/y/z, unit tangent x/y/z)."""
    if kind[m] == LINE:
        L = length[m]
        dx, dy, dz = direc[m, 0], direc[m, 1], direc[m, 2]
        ax, ay, az = start[m, 0], start[m, 1], start[m, 2]
        u = (px - ax) * dx + (py - ay) * dy + (pz - az) * dz
        if u < 0.0:
            u = 0.0
        elif u > L:
            u = L
        fx, fy, fz = ax + u * dx, ay + u * dy, az + u * dz
        if u >= L:
            fx, fy, fz = end[m, 0], end[m, 1], end[m, 2]
        d = math.sqrt((px - fx) ** 2 + (py - fy) ** 2 + (pz - fz) ** 2)
        return d, u, fx, fy, fz, dx, dy, dz
    if kind[m] == CLOTHOID:
        return _project_clothoid(px, py, pz, m, start, end, length, frame, sharp)
    # arc or helix: relative angle phi in [0, S] along the travel, psi = phi0 + sig * phi
    cx, cy, cz = center[m, 0], center[m, 1], center[m, 2]
    rx, ry, rz = px - cx, py - cy, pz - cz
    a = rx * ep[m, 0] + ry * ep[m, 1] + rz * ep[m, 2]
    b = rx * eq[m, 0] + ry * eq[m, 1] + rz * eq[m, 2]
    n = rx * en[m, 0] + ry * en[m, 1] + rz * en[m, 2]
    R = radius[m]
    sw = sweep[m]
    sig = 1.0 if sw > 0 else -1.0
    S = abs(sw)
    h = helix[m]
    k = h / S  # rise per radian [mm/rad]
    L = length[m]
    scale = L / S  # arc length per radian
    rho = math.hypot(a, b)
    theta = math.atan2(b, a)
    base = (sig * (theta - phi0[m])) % _TWO_PI
    if h == 0.0:
        phi = _planar_angle(a, b, R, phi0[m], sw, base, scale, hint_u)
    else:
        phi = _helix_angle(a, b, n, R, rho, theta, phi0[m], sig, S, k, base, scale, hint_u)
    psi = phi0[m] + sig * phi
    cps, sps = math.cos(psi), math.sin(psi)
    qn = k * phi
    if phi >= S:
        fx, fy, fz = end[m, 0], end[m, 1], end[m, 2]
    elif phi <= 0.0:
        fx, fy, fz = start[m, 0], start[m, 1], start[m, 2]
    else:
        fx = cx + R * (cps * ep[m, 0] + sps * eq[m, 0]) + qn * en[m, 0]
        fy = cy + R * (cps * ep[m, 1] + sps * eq[m, 1]) + qn * en[m, 1]
        fz = cz + R * (cps * ep[m, 2] + sps * eq[m, 2]) + qn * en[m, 2]
    w = R * sig / scale
    hz = k / scale
    tx = w * (-sps * ep[m, 0] + cps * eq[m, 0]) + hz * en[m, 0]
    ty = w * (-sps * ep[m, 1] + cps * eq[m, 1]) + hz * en[m, 1]
    tz = w * (-sps * ep[m, 2] + cps * eq[m, 2]) + hz * en[m, 2]
    d = math.sqrt((px - fx) ** 2 + (py - fy) ** 2 + (pz - fz) ** 2)
    return d, phi * scale, fx, fy, fz, tx, ty, tz


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _planar_angle(a, b, R, phi0, sw, base, scale, hint_u):  # pragma: no cover - compiled
    """Travel angle of the nearest point of a planar arc (P at in-plane angle ``base`` from the start).

    Every in-range turn of the in-plane angle is at the same distance; the hint (the command's arc
    length) picks the turn; no trigonometry until the foot is known. Outside the swept angle: the
    nearer end point.
    """
    S = abs(sw)
    eps = 1e-12 * (1.0 + S)
    best_phi = -1.0
    best_gap = np.inf
    n_turns = int(S / _TWO_PI) + 2
    for j in range(-1, n_turns + 1):
        phi = base + _TWO_PI * j
        if phi < -eps or phi > S + eps:
            continue
        phi = min(max(phi, 0.0), S)
        gap = abs(phi * scale - hint_u)
        if gap < best_gap:
            best_phi, best_gap = phi, gap
    if best_phi >= 0.0:
        return best_phi
    c0, s0 = math.cos(phi0), math.sin(phi0)
    c1, s1 = math.cos(phi0 + sw), math.sin(phi0 + sw)
    d0 = (a - R * c0) ** 2 + (b - R * s0) ** 2
    d1 = (a - R * c1) ** 2 + (b - R * s1) ** 2
    return 0.0 if d0 <= d1 else S


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _helix_newton(phi, n, R, rho, theta, phi0, sig, S, k):  # pragma: no cover - compiled
    """1-D Newton on d^2(phi)/2 = -R rho cos(psi - theta) + (n - k phi)^2 / 2 (+ const), in [0, S]."""
    for _ in range(30):
        c = math.cos(phi0 + sig * phi - theta)
        s = math.sin(phi0 + sig * phi - theta)
        g = R * rho * sig * s - k * (n - k * phi)
        gp = R * rho * c + k * k
        if gp <= 0.0:
            break
        new = min(max(phi - g / gp, 0.0), S)
        if abs(new - phi) < 1e-15 * (1.0 + S):
            return new
        phi = new
    return phi


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _helix_angle(a, b, n, R, rho, theta, phi0, sig, S, k, base, scale, hint_u):  # pragma: no cover - compiled
    """Travel angle of the nearest point of a helix rising ``k`` mm per radian.

    Newton starts: every turn where the in-plane angle matches, and the foot along the axis (n / k,
    for a steep helix whose nearest point the in-plane angle alone does not find, as when P's angle
    lies outside a sweep of less than a turn); then both end points as they are.
    """
    eps = 1e-12 * (1.0 + S)
    best_d = np.inf
    best_phi = 0.0
    best_gap = np.inf
    n_turns = int(S / _TWO_PI) + 2
    for j in range(-1, n_turns + 4):
        if j <= n_turns:
            phi = base + _TWO_PI * j
            if phi < -eps or phi > S + eps:
                continue
            phi = _helix_newton(min(max(phi, 0.0), S), n, R, rho, theta, phi0, sig, S, k)
        elif j == n_turns + 1:
            phi = _helix_newton(min(max(n / k, 0.0), S), n, R, rho, theta, phi0, sig, S, k)
        else:
            phi = 0.0 if j == n_turns + 2 else S
        psi = phi0 + sig * phi
        qa, qb, qn = R * math.cos(psi), R * math.sin(psi), k * phi
        d = math.sqrt((a - qa) ** 2 + (b - qb) ** 2 + (n - qn) ** 2)
        gap = abs(phi * scale - hint_u)
        if d < best_d - 1e-9 or (d <= best_d + 1e-9 and gap < best_gap):
            best_d, best_phi, best_gap = d, phi, gap
    return best_phi


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _clothoid_point(m, s, start, end, length, frame, sharp):  # pragma: no cover - compiled
    """Point, unit tangent and curvature vector of clothoid pair ``m`` at arc length ``s``."""
    L = length[m]
    first = s <= 0.5 * L
    r = s if first else L - s
    phi = 0.5 * sharp[m] * r * r
    X, Y = euler_spiral_point(phi)
    c, sn = math.cos(phi), math.sin(phi)
    k = sharp[m] * r
    pt = np.empty(3)
    tg = np.empty(3)
    cv = np.empty(3)
    for i in range(3):
        if first:
            u, w = frame[m, 0, i], frame[m, 1, i]
            pt[i] = start[m, i] + r * X * u + r * Y * w
            tg[i] = c * u + sn * w
            cv[i] = k * (c * w - sn * u)
        else:
            u, w = frame[m, 2, i], frame[m, 3, i]
            pt[i] = end[m, i] - r * X * u + r * Y * w
            tg[i] = c * u - sn * w
            cv[i] = k * (c * w + sn * u)
    return pt, tg, cv


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _project_clothoid(px, py, pz, m, start, end, length, frame, sharp):  # pragma: no cover - compiled
    """Newton on g(s) = (P - X(s)) . T(s) on each half, from the projection on its line."""
    L = length[m]
    half = 0.5 * L
    best_d = np.inf
    best_s = 0.0
    for part in range(2):
        if part == 0:
            lo, hi = 0.0, half
            s = ((px - start[m, 0]) * frame[m, 0, 0] + (py - start[m, 1]) * frame[m, 0, 1]
                 + (pz - start[m, 2]) * frame[m, 0, 2])
        else:
            lo, hi = half, L
            s = L - ((end[m, 0] - px) * frame[m, 2, 0] + (end[m, 1] - py) * frame[m, 2, 1]
                     + (end[m, 2] - pz) * frame[m, 2, 2])
        s = min(max(s, lo), hi)
        for _ in range(12):
            pt, tg, cv = _clothoid_point(m, s, start, end, length, frame, sharp)
            ex, ey, ez = px - pt[0], py - pt[1], pz - pt[2]
            g = ex * tg[0] + ey * tg[1] + ez * tg[2]
            dg = -1.0 + ex * cv[0] + ey * cv[1] + ez * cv[2]
            if dg > -1e-12:
                dg = -1e-12
            new = min(max(s - g / dg, lo), hi)
            if abs(new - s) < 1e-14 * (1.0 + L):
                s = new
                break
            s = new
        pt, tg, cv = _clothoid_point(m, s, start, end, length, frame, sharp)
        d = math.sqrt((px - pt[0]) ** 2 + (py - pt[1]) ** 2 + (pz - pt[2]) ** 2)
        if d < best_d:
            best_d, best_s = d, s
    pt, tg, cv = _clothoid_point(m, best_s, start, end, length, frame, sharp)
    fx, fy, fz = pt[0], pt[1], pt[2]
    if best_s <= 0.0:
        fx, fy, fz = start[m, 0], start[m, 1], start[m, 2]
    elif best_s >= L:
        fx, fy, fz = end[m, 0], end[m, 1], end[m, 2]
    d = math.sqrt((px - fx) ** 2 + (py - fy) ** 2 + (pz - fz) ** 2)
    return d, best_s, fx, fy, fz, tg[0], tg[1], tg[2]


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _coord(P, k, col):  # pragma: no cover - compiled
    return P[k, col] if col >= 0 else 0.0


@numba.njit(cache=True, nogil=True, error_model="numpy")
def locate(P, cols, kind, start, end, direc, length, center, ep, eq, en, radius, phi0, sweep, helix,
           frame, sharp, cum, tol):  # pragma: no cover - compiled
    """Commanded segment and path arc length of each sample of a commanded trajectory.

    The segment index never decreases. Each step looks ahead only as far along the path as the
    command moved since the previous sample (x1.5, + ``tol`` [mm]); candidates whose distances
    differ by less than ``tol`` + half that move are ties, resolved by the arc length predicted
    from the move. Returns ``(segment, s, distance)``.
    """
    N = P.shape[0]
    M = kind.shape[0]
    seg = np.zeros(N, dtype=np.int64)
    s_out = np.zeros(N)
    dist = np.zeros(N)
    if N == 0 or M == 0:
        return seg, s_out, dist
    cx, cy, cz = cols[0], cols[1], cols[2]
    # first sample: nearest over all segments, earliest on ties
    px, py, pz = _coord(P, 0, cx), _coord(P, 0, cy), _coord(P, 0, cz)
    best_d = np.inf
    j = 0
    s = 0.0
    for m in range(M):
        d, u, fx, fy, fz, tx, ty, tz = _project(px, py, pz, m, kind, start, end, direc, length, center, ep, eq,
                                                en, radius, phi0, sweep, helix, frame, sharp, 0.0)
        if d < best_d - tol:
            best_d, j, s = d, m, cum[m] + u
    seg[0], s_out[0], dist[0] = j, s, best_d
    for i in range(1, N):
        qx, qy, qz = px, py, pz
        px, py, pz = _coord(P, i, cx), _coord(P, i, cy), _coord(P, i, cz)
        step = math.sqrt((px - qx) ** 2 + (py - qy) ** 2 + (pz - qz) ** 2)
        s_pred = s + step
        reach = s + 1.5 * step + tol
        tie = tol + 0.5 * step
        best_d = np.inf
        best_gap = np.inf
        bj = j
        bs = s
        m = j
        while m < M and (m == j or cum[m] <= reach):
            d, u, fx, fy, fz, tx, ty, tz = _project(px, py, pz, m, kind, start, end, direc, length, center, ep,
                                                    eq, en, radius, phi0, sweep, helix, frame, sharp,
                                                    s_pred - cum[m])
            sm = cum[m] + u
            gap = abs(sm - s_pred)
            if d < best_d - tie or (d <= best_d + tie and gap < best_gap):
                best_d, best_gap, bj, bs = d, gap, m, sm
            m += 1
        j, s = bj, bs
        seg[i], s_out[i], dist[i] = j, s, best_d
    return seg, s_out, dist


@numba.njit(cache=True, nogil=True, error_model="numpy")
def nearest(P, cols, kind, start, end, direc, length, center, ep, eq, en, radius, phi0, sweep, helix, frame,
            sharp, cum,
            sphere_c, sphere_r, t_start, t_end, block_c, block_r, cseg, s_cmd, back, ahead, normal,
            signed):  # pragma: no cover
    """Nearest path point of each actual position.

    With ``cseg`` (commanded segment per sample, non-decreasing) the candidates of sample k are
    segments ``cseg[k - back] .. cseg[k + ahead]``; with an empty ``cseg`` all segments are
    searched and the previous sample's arc length is the tie hint. Segments whose bounding
    sphere lies farther than the best distance so far are skipped, and whole blocks of :data:`BLOCK`
    segments (``block_c``, ``block_r``: a ball holding the spheres of segments ``BLOCK * b ..``) likewise.

    Returns ``(error, segment, s)``: error signed (+ right of the travel, seen from ``normal``)
    when ``signed``, else the distance [mm]; nearest segment; path arc length of the nearest
    point [mm]. Where the nearest point is a junction of two segments the side is taken from the
    bisector of their tangents (``t_end`` of the first, ``t_start`` of the second), so that both
    segments agree on it; beyond either end of the path (an overshoot of the end point) it is +.
    """
    N = P.shape[0]
    M = kind.shape[0]
    err = np.zeros(N)
    seg = np.zeros(N, dtype=np.int64)
    s_out = np.zeros(N)
    windowed = cseg.shape[0] == N
    cx, cy, cz = cols[0], cols[1], cols[2]
    nx, ny, nz = normal[0], normal[1], normal[2]
    prev_s = 0.0
    for i in range(N):
        px, py, pz = _coord(P, i, cx), _coord(P, i, cy), _coord(P, i, cz)
        if windowed:
            lo = cseg[max(i - back, 0)]
            hi = cseg[min(i + ahead, N - 1)]
            first = cseg[i]
            hint = s_cmd[i]
        else:
            lo = 0
            hi = M - 1
            first = seg[i - 1] if i > 0 else 0
            hint = prev_s
        best_d = np.inf
        best_gap = np.inf
        bm = first
        bs = 0.0
        bfx = bfy = bfz = 0.0
        btx = bty = btz = 0.0
        jj = lo - 1
        while jj <= hi:
            m = first if jj == lo - 1 else jj
            jj += 1
            if m == first and jj > lo:
                continue
            if jj > lo and (m % BLOCK == 0 or m == lo):  # entering a block: all of it may be out of reach
                b = m // BLOCK
                dbx = px - block_c[b, 0]
                dby = py - block_c[b, 1]
                dbz = pz - block_c[b, 2]
                if math.sqrt(dbx * dbx + dby * dby + dbz * dbz) - block_r[b] > best_d + TIE_MM:
                    jj = (b + 1) * BLOCK
                    continue
            dsx = px - sphere_c[m, 0]
            dsy = py - sphere_c[m, 1]
            dsz = pz - sphere_c[m, 2]
            if math.sqrt(dsx * dsx + dsy * dsy + dsz * dsz) - sphere_r[m] > best_d + TIE_MM:
                continue
            d, u, fx, fy, fz, tx, ty, tz = _project(px, py, pz, m, kind, start, end, direc, length, center, ep,
                                                    eq, en, radius, phi0, sweep, helix, frame, sharp,
                                                    hint - cum[m])
            sm = cum[m] + u
            gap = abs(sm - hint)
            if d < best_d - TIE_MM or (d <= best_d + TIE_MM and gap < best_gap):
                best_d, best_gap, bm, bs = d, gap, m, sm
                bfx, bfy, bfz, btx, bty, btz = fx, fy, fz, tx, ty, tz
        e = best_d
        if signed and best_d > 0.0:
            bu = bs - cum[bm]
            nb = -1
            if bu <= 0.0 and bm > 0:
                nb = bm - 1
                sx, sy, sz = t_end[nb, 0] + t_start[bm, 0], t_end[nb, 1] + t_start[bm, 1], t_end[nb, 2] + t_start[bm, 2]
            elif bu >= length[bm] and bm < M - 1:
                nb = bm + 1
                sx, sy, sz = t_end[bm, 0] + t_start[nb, 0], t_end[bm, 1] + t_start[nb, 1], t_end[bm, 2] + t_start[nb, 2]
            if nb >= 0:
                ns = math.sqrt(sx * sx + sy * sy + sz * sz)
                if ns > 1e-9:
                    btx, bty, btz = sx / ns, sy / ns, sz / ns
            elif (bu <= 0.0 and bm == 0) or (bu >= length[bm] and bm == M - 1):
                btx = bty = btz = 0.0  # beyond an end of the path: an overshoot, counted outside (+)
            # right of the travel: (tangent x normal) . (P - foot)
            rx = bty * nz - btz * ny
            ry = btz * nx - btx * nz
            rz = btx * ny - bty * nx
            side = rx * (px - bfx) + ry * (py - bfy) + rz * (pz - bfz)
            if side < 0.0 and (btx != 0.0 or bty != 0.0 or btz != 0.0):
                e = -best_d
        err[i] = e
        seg[i] = bm
        s_out[i] = bs
        prev_s = bs
    return err, seg, s_out
