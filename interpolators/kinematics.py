"""Path-speed, path-acceleration and path-jerk bounds that keep every axis within its limits.

A point moving along a segment with path speed ``v``, path acceleration ``a`` and path jerk
``j`` has axis velocity ``t v``, axis acceleration ``t a + k v^2`` and axis jerk
``t j + 3 k v a + k' v^3``, where ``t`` is the unit tangent and ``k`` the curvature vector.

Lines: ``|t_i|`` is constant, so ``v <= V_i/|t_i|``, ``a <= A_i/|t_i|``, ``j <= J_i/|t_i|``.

Arcs (radius ``R``, in-plane share of the motion ``cos(alpha) = R |sweep| / length``): the
in-plane motion has speed ``v_p = v cos(alpha)``; its acceleration vector is
``a_p t + (v_p^2 / R) n`` and its jerk vector ``(j_p - v_p^3/R^2) t + (3 v_p a_p / R) n``. Every
in-plane axis component is bounded by the vector's norm, so with ``A`` and ``J`` the smaller
limits of the two in-plane axes:

* centripetal share: ``v_p^2 / R <= CENTRIPETAL_SHARE * A`` (this caps the feed on small arcs);
* tangential: ``sqrt(a_p^2 + (v_max,p^2/R)^2) <= A``;
* jerk (S-curve only): ``v_p^3/R^2 <= JERK_SPEED_SHARE * J``,
  ``3 v_p a_p / R <= JERK_ACCEL_SHARE * J``, and ``j_p`` takes what is left of ``J``.

The helix axis sees ``v sin(alpha)``, ``a sin(alpha)``, ``j sin(alpha)`` and is bounded like a
line. The bounds are therefore sufficient (not necessary): no axis can exceed its limit
anywhere on the arc, whatever the orientation of the arc.
"""

from __future__ import annotations

import numpy as np

from interpolators.limits import AxisLimits
from toolpaths.geometry import AXIS_LETTERS
from toolpaths.packed import ARC, LINE, PackedSegments
from vcnc.errors import InputError

__all__ = [
    "AxisLimitArrays",
    "path_limits",
    "junction_speed_limit",
    "CENTRIPETAL_SHARE",
    "JERK_SPEED_SHARE",
    "JERK_ACCEL_SHARE",
]

#: Share of the axis acceleration limit the centripetal acceleration may take on an arc.
CENTRIPETAL_SHARE: float = 0.7
#: Share of the axis jerk limit taken by ``v^3/R^2`` on an arc (S-curve).
JERK_SPEED_SHARE: float = 0.3
#: Share of the axis jerk limit taken by ``3 v a / R`` on an arc (S-curve).
JERK_ACCEL_SHARE: float = 0.3


class AxisLimitArrays:
    """Limits of the x, y, z axes as arrays (inf for an axis without limits that never moves).

    Attributes
    ----------
    velocity, acceleration, jerk, rapid : ndarray, shape (3,)
        [mm/s], [mm/s^2], [mm/s^3], [mm/s].
    """

    def __init__(self, limits: dict[str, AxisLimits], moving: set[int]) -> None:
        self.velocity = np.full(3, np.inf)
        self.acceleration = np.full(3, np.inf)
        self.jerk = np.full(3, np.inf)
        self.rapid = np.full(3, np.inf)
        for i, a in enumerate(AXIS_LETTERS):
            lim = limits.get(a)
            if lim is None:
                if i in moving:
                    raise InputError(
                        f"no limits for axis {a!r}, which the program moves",
                        expected=f"limits for the axes {', '.join(AXIS_LETTERS[k] for k in sorted(moving))}",
                    )
                continue
            if not isinstance(lim, AxisLimits):
                raise InputError(f"limits[{a!r}] must be an AxisLimits, got {type(lim).__name__}")
            self.velocity[i] = lim.velocity
            self.acceleration[i] = lim.acceleration
            self.jerk[i] = lim.jerk
            self.rapid[i] = lim.rapid_rate

    def scaled(self, *, acceleration: float = 1.0, jerk: float = 1.0) -> AxisLimitArrays:
        """A copy with acceleration and jerk limits multiplied by the given factors."""
        out = object.__new__(AxisLimitArrays)
        out.velocity, out.rapid = self.velocity, self.rapid
        out.acceleration = self.acceleration * acceleration
        out.jerk = self.jerk * jerk
        return out


def _min_ratio(limit: np.ndarray, share: np.ndarray) -> np.ndarray:
    """min over axes of limit_i / share_i, ignoring axes with share 0; shapes (3,), (n, 3)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(share > 1e-15, limit[None, :] / share, np.inf)
    return r.min(axis=1)


def path_limits(
    packed: PackedSegments,
    feed: np.ndarray,
    rapid: np.ndarray,
    limits: AxisLimitArrays,
    *,
    jerk_limited: bool,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bounds of path speed, acceleration and jerk per segment.

    Parameters
    ----------
    packed : PackedSegments
        Motion segments (lines and arcs of non-zero length).
    feed : ndarray, shape (n,)
        Programmed feed [mm/s] (ignored for rapids).
    rapid : ndarray of bool, shape (n,)
        True for rapid moves (speed bounded by the axes' rapid rates instead of feed and
        velocity limit).
    limits : AxisLimitArrays
        Axis limits.
    jerk_limited : bool
        True to include the jerk terms of arcs (S-curve profile).

    Returns
    -------
    v_max, a_max, j_max : ndarray, shape (n,)
        [mm/s], [mm/s^2], [mm/s^3]; ``j_max`` is inf when the jerk limits are infinite.
    """
    n = len(packed)
    v_max = np.where(rapid, np.inf, feed).astype(float)
    a_max = np.full(n, np.inf)
    j_max = np.full(n, np.inf)
    kind = packed.kind
    vel_lim = np.where(rapid[:, None], limits.rapid[None, :], limits.velocity[None, :])

    il = np.flatnonzero(kind == LINE)
    if len(il):
        u = np.abs(packed.end[il] - packed.start[il]) / packed.length[il, None]
        v_max[il] = np.minimum(v_max[il], _min_ratio_rows(vel_lim[il], u))
        a_max[il] = _min_ratio(limits.acceleration, u)
        j_max[il] = _min_ratio(limits.jerk, u)

    ia = np.flatnonzero(kind == ARC)
    if len(ia):
        L = packed.length[ia]
        R = packed.radius[ia]
        cos_a = R * np.abs(packed.sweep[ia]) / L
        sin_a = np.abs(packed.helix[ia]) / L
        inplane = packed.e_p[ia] + packed.e_q[ia]  # 1 on the two in-plane axes
        normal = packed.e_n[ia]
        big = np.inf

        def plane_min(lim_rows: np.ndarray) -> np.ndarray:
            return np.where(inplane > 0, lim_rows, big).min(axis=1)

        def normal_val(lim_rows: np.ndarray) -> np.ndarray:
            return np.where(normal > 0, lim_rows, big).min(axis=1)

        acc_rows = np.broadcast_to(limits.acceleration, (len(ia), 3))
        jerk_rows = np.broadcast_to(limits.jerk, (len(ia), 3))
        V_p, V_n = plane_min(vel_lim[ia]), normal_val(vel_lim[ia])
        A_p, A_n = plane_min(acc_rows), normal_val(acc_rows)
        J_p, J_n = plane_min(jerk_rows), normal_val(jerk_rows)
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.minimum(v_max[ia], V_p / cos_a)
            v = np.minimum(v, np.where(sin_a > 0, V_n / sin_a, np.inf))
            v = np.minimum(v, np.sqrt(CENTRIPETAL_SHARE * A_p * R) / cos_a)
            if jerk_limited:
                v = np.minimum(v, np.cbrt(JERK_SPEED_SHARE * J_p * R * R) / cos_a)
            vp = v * cos_a
            a_n = vp * vp / R
            a = np.sqrt(np.maximum(A_p * A_p - a_n * a_n, 0.0)) / cos_a
            a = np.minimum(a, np.where(sin_a > 0, A_n / sin_a, np.inf))
            if jerk_limited:
                a = np.minimum(a, JERK_ACCEL_SHARE * J_p * R / (3.0 * vp * cos_a))
                j_left = J_p - vp**3 / (R * R) - 3.0 * vp * (a * cos_a) / R
                j = np.maximum(j_left, 0.0) / cos_a
                j = np.minimum(j, np.where(sin_a > 0, J_n / sin_a, np.inf))
            else:
                j = np.full(len(ia), np.inf)
        v_max[ia], a_max[ia], j_max[ia] = v, a, j
    if not (np.all(v_max > 0) and np.all(a_max > 0) and np.all(j_max > 0)):  # pragma: no cover - limits > 0
        raise InputError("axis limits leave no admissible path speed")
    if not np.all(np.isfinite(v_max)):
        raise InputError("a rapid move needs a finite rapid rate on its axes")
    if not np.all(np.isfinite(a_max)):
        raise InputError("the path acceleration is unbounded: give finite axis acceleration limits")
    return v_max, a_max, j_max


def _min_ratio_rows(limit_rows: np.ndarray, share: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(share > 1e-15, limit_rows / share, np.inf)
    return r.min(axis=1)


def junction_speed_limit(
    tangent_jump: np.ndarray,
    curvature_jump: np.ndarray,
    limits: AxisLimitArrays,
    *,
    sample_time: float,
    share: float,
    jerk_limited: bool,
) -> np.ndarray:
    """Largest speed at junctions with a tangent and curvature discontinuity.

    The discontinuity is passed within one sample; it may use ``share`` of the axis acceleration
    limit (velocity step ``v |dt_i| <= share A_i Ts``) and, for the S-curve, of the jerk limit
    (``v |dt_i| <= share J_i Ts^2`` and acceleration step ``v^2 |dk_i| <= share J_i Ts``).

    Parameters
    ----------
    tangent_jump, curvature_jump : ndarray, shape (m, 3)
        Unit-tangent change [-] and curvature-vector change [1/mm] across each junction.

    Returns
    -------
    ndarray, shape (m,)
        [mm/s]
    """
    dt = np.abs(tangent_jump)
    dk = np.abs(curvature_jump)
    v = _min_ratio(share * limits.acceleration * sample_time, dt)
    if jerk_limited:
        v = np.minimum(v, _min_ratio(share * limits.jerk * sample_time**2, dt))
        v = np.minimum(v, np.sqrt(_min_ratio(share * limits.jerk * sample_time, dk)))
    return v

