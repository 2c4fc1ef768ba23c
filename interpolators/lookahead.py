"""Continuous-path (G64) look-ahead: corner blending and junction speeds.

Runs of dense short lines (CAM output) are first merged into smooth curves within the tolerance
(:mod:`interpolators.dense`); the corners left between lines are blended here.

Corners between two straight lines are replaced by a blend whose distance from the corner is at
most the path tolerance (G64 ``P``, or :data:`DEFAULT_TOLERANCE`) and which uses at most half of
either line:

* a symmetric clothoid pair (:class:`toolpaths.geometry.ClothoidPair`) when the blend must be
  curvature continuous (``curvature_continuous=True``, the S-curve: a curvature step at speed
  is an acceleration step, which the jerk limit forbids) or when the corner plane is not a
  principal plane (no :class:`toolpaths.Arc` exists there);
* otherwise a tangent circular arc, whose curvature step at its ends costs nothing under a
  trapezoidal profile (acceleration steps are allowed) and whose peak curvature is half the
  clothoid pair's, so the corner is passed faster.

The path then stays tangent-continuous (and, with clothoids, curvature-continuous), and the
blend's own speed bound (centripetal acceleration and, for the S-curve, jerk including the
curvature derivative; see :mod:`interpolators.kinematics`) sets the corner speed.

Junctions that remain discontinuous (line/arc and arc/arc corners, reversals, curvature steps of
tangent-continuous line/arc and arc/arc junctions) are passed at a speed that keeps the step within one sample: see
:func:`interpolators.kinematics.junction_speed_limit` and, for the curvature steps of tangent junctions under the
S-curve, :func:`interpolators.kinematics.curvature_step_speed_limit` (each axis' own jerk budget). A backward
and a forward pass then lower the junction speeds until every segment can change from its entry to its exit speed
within its length (exactly for the trapezoid, with zero end accelerations for the S-curve).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from interpolators.profiles import scurve_reach, trapezoid_reach
from toolpaths.geometry import Arc, ClothoidPair, Line
from vcnc.core.errors import InputError

__all__ = ["DEFAULT_TOLERANCE", "JUNCTION_SHARE", "blend_corners", "junction_speeds"]

#: Path tolerance of G64 without ``P`` [mm].
DEFAULT_TOLERANCE: float = 0.01
#: Share of the axis acceleration (and, S-curve, jerk) limits reserved, inside G64 chains, for
#: the discontinuities passed between two samples.
JUNCTION_SHARE: float = 0.1
#: Smallest corner angle that is blended [rad]; smaller direction changes pass as junctions.
_MIN_BLEND_ANGLE = 1e-7
#: Largest corner angle that is blended [rad] (sharper corners are near-reversals: stop).
_MAX_BLEND_ANGLE = math.pi - 1e-3


Blend = Arc | ClothoidPair


def _blend(a: Line, b: Line, tolerance: float, *, curvature_continuous: bool
           ) -> tuple[np.ndarray, Blend, np.ndarray] | None:
    """Blend replacing the corner a.end == b.start, or None when not blendable."""
    ua, ub = a.direction, b.direction
    cos_t = float(np.clip(ua @ ub, -1.0, 1.0))
    theta = math.acos(cos_t)
    if not (_MIN_BLEND_ANGLE < theta < _MAX_BLEND_ANGLE):
        return None
    n = np.cross(ua, ub)
    plane = int(np.argmax(np.abs(n)))
    nn = abs(n[plane])
    principal = not (np.max(np.abs(np.delete(n, plane))) > 1e-12 * nn or abs(ua[plane]) > 1e-12
                     or abs(ub[plane]) > 1e-12)
    d_max = 0.5 * min(a.length, b.length)
    if curvature_continuous or not principal:
        clo = ClothoidPair.for_corner(a.end, ua, ub, tolerance=tolerance, max_leg=d_max)
        return None if clo is None else (clo.start, clo, clo.end)
    half = 0.5 * theta
    sec_m1 = 1.0 / math.cos(half) - 1.0
    radius = tolerance / sec_m1 if sec_m1 > 0 else math.inf
    d = radius * math.tan(half)
    if d > d_max:
        d = d_max
        radius = d / math.tan(half)
    if radius < 1e-6 or d < 1e-9:
        return None
    corner = a.end
    p1 = corner - d * ua
    p2 = corner + d * ub
    inward = ub - cos_t * ua
    inward = inward / np.linalg.norm(inward)
    center = p1 + radius * inward
    try:
        arc = Arc(p1, p2, center, ccw=bool(n[plane] > 0), plane=plane)
    except InputError:
        return None
    return p1, arc, p2


def blend_corners(
    segments: list[Line | Arc],
    blocks: list[int],
    tolerances: list[float],
    *,
    worth: Callable[[int, Blend], bool] | None = None,
    curvature_continuous: bool = False,
) -> tuple[list[Line | Arc | ClothoidPair], list[int]]:
    """Blend line/line corners of a continuous chain.

    Parameters
    ----------
    segments : list of Line or Arc
        Consecutive segments of one G64 chain.
    blocks : list of int
        Program block index of each segment.
    tolerances : list of float
        Path tolerance [mm] of each junction ``k`` (between segment ``k`` and ``k+1``).
    worth : callable, optional
        ``worth(k, blend)`` decides whether blending junction ``k`` with ``blend`` pays off (e.g.
        the blend's speed bound is a fair share of the lines' feeds); a rejected corner stays
        sharp.
    curvature_continuous : bool
        Blend every corner with a clothoid pair (G2); otherwise with a circular arc where the
        corner lies in a principal plane and with a clothoid pair elsewhere.

    Returns
    -------
    segments, blocks : list
        The chain with blend arcs inserted (a blend belongs to the block of the incoming line)
        and the lines shortened accordingly; zero-length leftovers are dropped.
    """
    out: list[Line | Arc | ClothoidPair] = []
    out_blocks: list[int] = []
    cur = segments[0]
    for k in range(len(segments) - 1):
        nxt = segments[k + 1]
        res = None
        if isinstance(cur, Line) and isinstance(nxt, Line) and cur.length > 0 and nxt.length > 0:
            # the original lengths bound the blends: each end may take at most half a line
            res = _blend(segments[k], nxt, tolerances[k], curvature_continuous=curvature_continuous)
            if res is not None and worth is not None and not worth(k, res[1]):
                res = None
        if res is None:
            out.append(cur)
            out_blocks.append(blocks[k])
            cur = nxt
            continue
        p1, arc, p2 = res
        head = Line(cur.start, p1)
        if head.length > 1e-12:
            out.append(head)
            out_blocks.append(blocks[k])
        out.append(arc)
        out_blocks.append(blocks[k])
        cur = Line(p2, nxt.end)
    if cur.length > 1e-12 or not out:
        out.append(cur)
        out_blocks.append(blocks[-1])
    return out, out_blocks


def junction_speeds(
    length: np.ndarray,
    v_max: np.ndarray,
    a_max: np.ndarray,
    j_max: np.ndarray,
    junction_limit: np.ndarray,
    *,
    jerk_limited: bool,
) -> np.ndarray:
    """Speeds at the junctions of a chain that starts and ends at rest.

    Parameters
    ----------
    length, v_max, a_max, j_max : ndarray, shape (n,)
        Per segment: length [mm] and path bounds [mm/s, mm/s^2, mm/s^3].
    junction_limit : ndarray, shape (n - 1,)
        Speed bound of each inner junction from its geometry [mm/s].
    jerk_limited : bool
        Use the jerk-limited reach (S-curve) instead of the constant-acceleration one.

    Returns
    -------
    ndarray, shape (n + 1,)
        Speed at the chain start (0), at each inner junction, and at the end (0) [mm/s].
    """
    n = len(length)
    v = np.zeros(n + 1)
    if n > 1:
        v[1:n] = np.minimum(np.minimum(junction_limit, v_max[:-1]), v_max[1:])
    shrink = 1.0 - 1e-9  # margin against rounding: the profile must fit in the segment
    Ls = length * shrink
    vl = v.tolist()
    if jerk_limited:
        for k in range(n - 1, 0, -1):
            vl[k] = min(vl[k], scurve_reach(vl[k + 1], Ls[k], a_max[k], j_max[k]))
        for k in range(1, n):
            vl[k] = min(vl[k], scurve_reach(vl[k - 1], Ls[k - 1], a_max[k - 1], j_max[k - 1]))
    else:
        for k in range(n - 1, 0, -1):
            vl[k] = min(vl[k], trapezoid_reach(vl[k + 1], Ls[k], a_max[k]))
        for k in range(1, n):
            vl[k] = min(vl[k], trapezoid_reach(vl[k - 1], Ls[k - 1], a_max[k - 1]))
    return np.asarray(vl) * shrink
