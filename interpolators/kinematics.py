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
* jerk (S-curve only): ``v_p^3/R^2 <= JERK_SPEED_SHARE * J`` (``jerk_share``: ``interpolators.interpolate`` plans
  each chain at 0.3 and at 0.6 and keeps the faster),
  ``3 v_p a_p / R <= JERK_ACCEL_SHARE * J``, and ``j_p`` takes what is left of ``J``: the norm of the jerk
  vector, whose tangential and normal parts are orthogonal, ``(|j_p| + v_p^3/R^2)^2 + (3 v_p a_p / R)^2 <=
  J^2``, so ``|j_p| <= sqrt(J^2 - (3 v_p a_p / R)^2) - v_p^3/R^2`` (the sum of the parts' magnitudes, which
  the bound used before, left ``j_p`` less).

The helix axis sees ``v sin(alpha)``, ``a sin(alpha)``, ``j sin(alpha)`` and is bounded like a
line. The bounds are therefore sufficient (not necessary): no axis can exceed its limit
anywhere on the arc, whatever the orientation of the arc.

Clothoid blends (:class:`toolpaths.ClothoidPair`, curvature ``k`` up to ``k_max`` and
``|dk/ds| = c``) lie in one plane of any orientation: the axis share of that plane is
``m_i = |(u_in_i, w_in_i)|``, the jerk vector ``(j - k^2 v^3) t + (3 k v a + c v^3) n``, and the
same shares apply with ``v^3 |(k_max^2, c)| <= JERK_SPEED_SHARE * J`` (the tangential ``k^2 v^3`` and the
normal ``c v^3`` are orthogonal: the norm, not their sum; our reading of the vector bound above), ``j`` within
``sqrt(J^2 - (3 k v a + c v^3)^2) - k^2 v^3``; the velocity bound uses
the largest ``|t_i|`` over the turn.

The axes beyond X, Y, Z, rotary a, b, c and secondary linear u, v, w (:func:`extra_path_bounds`),
move in proportion to the path parameter ``s``: axis ``i`` moves ``ratio_i = |dr_i| / L`` degrees
(or mm) per unit of path, so its velocity, acceleration and jerk are ``ratio_i`` times the path's,
with no curvature term; ``v <= V_i/ratio_i`` and so on, as for a line.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from interpolators.limits import AxisLimits
from toolpaths.geometry import AXIS_LETTERS, SplineCurve
from toolpaths.packed import ARC, CLOTHOID, LINE, PackedSegments
from vcnc.core.axes import EXTRA_NAMES, ROTARY_NAMES
from vcnc.core.errors import InputError

__all__ = [
    "AxisLimitArrays",
    "path_limits",
    "extra_path_bounds",
    "junction_speed_limit",
    "line_limits",
    "curvature_step_speed_limit",
    "extra_junction_speed_limit",
    "extra_curve_bounds",
    "curved_speed_bound",
    "curve_limits",
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
#: Factor on the largest curvature and curvature derivative sampled on a smooth curve (the
#: samples may miss the exact maximum between them by a fraction of a percent).
CURVE_BOUND_MARGIN: float = 1.02


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
    jerk_share: float = JERK_SPEED_SHARE,
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
    jerk_share : float
        Share of the jerk limit ``v^3 |(k^2, dk/ds)|`` may take on arcs and clothoids (:func:`curved_speed_bound`).

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
        u = (packed.end[il] - packed.start[il]) / packed.length[il, None]
        v_max[il], a_max[il], j_max[il] = line_limits(u, feed[il], rapid[il], limits)

    ia = np.flatnonzero(kind == ARC)
    if len(ia):
        L = packed.length[ia]
        R = packed.radius[ia]
        cos_a = R * np.abs(packed.sweep[ia]) / L
        sin_a = np.abs(packed.helix[ia]) / L
        inplane = packed.e_p[ia] + packed.e_q[ia]  # 1 on the two in-plane axes
        normal = packed.e_n[ia]
        V_p = _weighted_min(vel_lim[ia], inplane)
        A_p = _weighted_min(limits.acceleration, inplane)
        J_p = _weighted_min(limits.jerk, inplane)
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.minimum(v_max[ia], V_p / cos_a)
            v = np.minimum(v, np.where(sin_a > 0, _weighted_min(vel_lim[ia], normal) / sin_a, np.inf))
            v, a, j = _curved_bounds(v, cos_a, 1.0 / R, np.zeros(len(ia)), A_p, J_p, jerk_limited=jerk_limited,
                                     jerk_share=jerk_share)
            a = np.minimum(a, np.where(sin_a > 0, _weighted_min(limits.acceleration, normal) / sin_a, np.inf))
            if jerk_limited:
                j = np.minimum(j, np.where(sin_a > 0, _weighted_min(limits.jerk, normal) / sin_a, np.inf))
        v_max[ia], a_max[ia], j_max[ia] = v, a, j

    ic = np.flatnonzero(kind == CLOTHOID)
    if len(ic):
        fr = packed.frame[ic]
        u_in, w_in, u_out = fr[:, 0], fr[:, 1], fr[:, 2]
        # tangent and normal stay in the corner plane: |t_i|, |n_i| <= m_i = |(u_in_i, w_in_i)|
        m = np.hypot(u_in, w_in)
        cos_t = np.clip(np.einsum("ij,ij->i", u_in, u_out), -1.0, 1.0)
        theta = np.arccos(cos_t)
        # largest |t_i| while the tangent turns from u_in to u_out: m_i if the turn passes the
        # angle where axis i is tangent, else the larger end value
        psi = np.mod(np.arctan2(w_in, u_in), np.pi)
        t_abs = np.where(psi <= theta[:, None], m, np.maximum(np.abs(u_in), np.abs(u_out)))
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.minimum(v_max[ic], _min_ratio_rows(vel_lim[ic], t_abs))
            v, a, j = _curved_bounds(v, np.ones(len(ic)), packed.sharpness[ic] * 0.5 * packed.length[ic],
                                     packed.sharpness[ic], _min_ratio(limits.acceleration, m),
                                     _min_ratio(limits.jerk, m), jerk_limited=jerk_limited, jerk_share=jerk_share)
        v_max[ic], a_max[ic], j_max[ic] = v, a, j
    if not (np.all(v_max > 0) and np.all(a_max > 0) and np.all(j_max > 0)):  # pragma: no cover - limits > 0
        raise InputError("axis limits leave no admissible path speed")
    if not np.all(np.isfinite(v_max)):
        raise InputError("a rapid move needs a finite rapid rate on its axes")
    if not np.all(np.isfinite(a_max)):
        raise InputError("the path acceleration is unbounded: give finite axis acceleration limits")
    return v_max, a_max, j_max


def line_limits(direction: np.ndarray, feed: np.ndarray, rapid: np.ndarray, limits: AxisLimitArrays
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bounds of path speed, acceleration and jerk on straight lines: each axis ``i`` moves at ``|u_i|`` times
    the path's rate, so the path bound is the smallest ``limit_i / |u_i|`` (axes with ``|u_i| <= 1e-15`` do not
    count), the speed also at most the feed (rapids: the rapid rates instead of feed and velocity limits).

    Parameters
    ----------
    direction : ndarray, shape (n, 3)
        Unit directions of the lines.
    feed : ndarray, shape (n,)
        Programmed feed [mm/s] (ignored for rapids).
    rapid : ndarray of bool, shape (n,)
    limits : AxisLimitArrays

    Returns
    -------
    v_max, a_max, j_max : ndarray, shape (n,)
        [mm/s], [mm/s^2], [mm/s^3] (inf where the limits are).
    """
    u = np.abs(direction)
    rapid = np.asarray(rapid, dtype=bool)
    vel_lim = np.where(rapid[:, None], limits.rapid[None, :], limits.velocity[None, :])
    v_max = np.minimum(np.where(rapid, np.inf, feed).astype(float), _min_ratio_rows(vel_lim, u))
    return v_max, _min_ratio(limits.acceleration, u), _min_ratio(limits.jerk, u)


def curve_limits(
    curves: list[SplineCurve], feed: np.ndarray, limits: AxisLimitArrays, *, jerk_limited: bool,
    jerk_share: float = JERK_SPEED_SHARE,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bounds of path speed, acceleration and jerk on smooth curves (:class:`toolpaths.geometry.SplineCurve`).

    A curve in any orientation: every axis the curve moves sees at most the norm of the
    acceleration vector ``(a, k v^2)`` and of the jerk vector, whose normal part is at most
    ``3 k v a + |dk/ds|_perp v^3``, so the clothoid bounds apply with the curve's largest
    curvature and curvature derivative (:meth:`SplineCurve.bounds`, times :data:`CURVE_BOUND_MARGIN`)
    and ``A``, ``J`` the smallest limits of the moving axes; the speed also keeps ``v |t_i| <= V_i``.

    Parameters
    ----------
    curves : list of SplineCurve
    feed : ndarray, shape (n,)
        Programmed feed [mm/s].
    limits : AxisLimitArrays
    jerk_limited : bool
    jerk_share : float
        As in :func:`path_limits`.

    Returns
    -------
    v_max, a_max, j_max : ndarray, shape (n,)
        [mm/s], [mm/s^2], [mm/s^3]
    """
    n = len(curves)
    kappa, dkappa, t_abs = np.zeros(n), np.zeros(n), np.zeros((n, 3))
    for i, c in enumerate(curves):
        kappa[i], dkappa[i], t_abs[i] = c.bounds()
    kappa, dkappa = kappa * CURVE_BOUND_MARGIN, dkappa * CURVE_BOUND_MARGIN
    moving = (t_abs > 0).astype(float)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.minimum(np.asarray(feed, float), _min_ratio(limits.velocity, t_abs))
        v, a, j = _curved_bounds(v, np.ones(n), kappa, dkappa, _min_ratio(limits.acceleration, moving),
                                 _min_ratio(limits.jerk, moving), jerk_limited=jerk_limited, jerk_share=jerk_share)
    return v, a, j


def _weighted_min(limit: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """min over the axes where ``mask`` > 0 of ``limit`` (shape (3,) or (n, 3)); inf when none."""
    return np.where(mask > 0, limit, np.inf).min(axis=1)


def curved_speed_bound(
    kappa: np.ndarray | float, dkappa: np.ndarray | float, A: np.ndarray | float, J: np.ndarray | float, *,
    jerk_limited: bool, jerk_share: float = JERK_SPEED_SHARE
) -> np.ndarray:
    """Largest in-plane speed [mm/s] on a curve of curvature ``kappa`` [1/mm] and ``|dk/ds|`` [1/mm^2].

    ``v^2 kappa <= CENTRIPETAL_SHARE A`` and, jerk limited, ``v^3 |(kappa^2, dkappa)| <= jerk_share J``
    (:data:`JERK_SPEED_SHARE` by default; ``A``, ``J``: in-plane acceleration [mm/s^2] and jerk [mm/s^3] bounds): at
    constant speed the jerk vector is ``-k^2 v^3 t + (dk/ds)_perp v^3 n``, two orthogonal parts, so its norm.
    """
    kappa, dkappa = np.asarray(kappa, float), np.asarray(dkappa, float)
    with np.errstate(divide="ignore"):
        v = np.sqrt(CENTRIPETAL_SHARE * np.asarray(A, float) / kappa)
        if jerk_limited:
            v = np.minimum(v, np.cbrt(jerk_share * np.asarray(J, float) / np.hypot(kappa * kappa, dkappa)))
    return v


def _curved_bounds(v, cos_a, kappa, dkappa, A_p, J_p, *, jerk_limited: bool, jerk_share: float = JERK_SPEED_SHARE):
    """Speed, acceleration and jerk bounds on a curve (in-plane share ``cos_a`` of the motion).

    In the tangent/normal frame the in-plane acceleration is ``(a_p, k v_p^2)`` and the jerk
    ``(j_p - k^2 v_p^3, 3 k v_p a_p + k' v_p^3)``; each in-plane axis component is bounded by the
    norm, so the bounds hold whatever the orientation of the plane (module docstring): ``j_p`` is what keeps
    ``(|j_p| + k^2 v_p^3)^2 + (3 k v_p a_p + k' v_p^3)^2 <= J_p^2`` at the bounds ``v``, ``a``.
    """
    v = np.minimum(v, curved_speed_bound(kappa, dkappa, A_p, J_p, jerk_limited=jerk_limited,
                                         jerk_share=jerk_share) / cos_a)
    vp = v * cos_a
    a_n = vp * vp * kappa
    a = np.sqrt(np.maximum(A_p * A_p - a_n * a_n, 0.0)) / cos_a
    if jerk_limited:
        a = np.minimum(a, JERK_ACCEL_SHARE * J_p / (3.0 * vp * kappa * cos_a))
        normal = 3.0 * vp * (a * cos_a) * kappa + dkappa * vp**3
        j_left = np.sqrt(np.maximum(J_p * J_p - normal * normal, 0.0)) - vp**3 * kappa * kappa
        j = np.maximum(j_left, 0.0) / cos_a
    else:
        j = np.full(len(v), np.inf)
    return v, a, j


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
    limit (velocity step ``v |dt_i| <= share A_i Ts``) and, for the S-curve, of the jerk limit: the
    velocity step and the acceleration step ``v^2 |dk_i|`` fall in the same samples, so their finite-difference
    jerks add, ``v |dt_i| / Ts^2 + v^2 |dk_i| / Ts <= share J_i`` (:func:`_jerk_step_speed_limit`; each checked
    alone against ``share J_i`` before session 33, a nearly tangent arc/line junction took twice the share
    and its Y jerk reached 1.009 of the limit beside a path jerk at 0.9 of it: setpoint fuzzer seed 42782).

    Parameters
    ----------
    tangent_jump, curvature_jump : ndarray, shape (m, 3)
        Unit-tangent change [-] and curvature-vector change [1/mm] across each junction.

    Returns
    -------
    ndarray, shape (m,)
        [mm/s]
    """
    v = _step_speed_limit(limits.acceleration, np.abs(tangent_jump), sample_time=sample_time, share=share)
    if jerk_limited:
        v = np.minimum(v, _jerk_step_speed_limit(limits.jerk, np.abs(tangent_jump), np.abs(curvature_jump),
                                                 sample_time=sample_time, share=share))
    return v


def _jerk_step_speed_limit(jerk: np.ndarray, velocity_step: np.ndarray, acceleration_step: np.ndarray, *,
                           sample_time: float, share: float) -> np.ndarray:
    """Largest path speed ``v`` at which a velocity step ``v |dt_i|`` and an acceleration step ``v^2 |dk_i|``
    passed within the same sample keep ``v |dt_i| / Ts^2 + v^2 |dk_i| / Ts <= share J_i`` on every axis
    (shapes ``(k,)``, ``(n, k)``, ``(n, k)``): the third finite difference of a velocity step is at most the step
    over ``Ts^2``, that of an acceleration step at most 0.75 of it over ``Ts`` (:func:`curvature_step_speed_limit`),
    and one sample may hold both. The positive root of ``a v^2 + b v - c``, as ``2 c / (b + sqrt(b^2 + 4 a c))``
    (``c / b`` without an acceleration step, ``sqrt(c / a)`` without a velocity step); steps up to 1e-15 count
    as none, an axis without steps or jerk limit adds no bound."""
    c = (share * jerk * sample_time**2)[None, :]
    b = np.where(velocity_step > 1e-15, velocity_step, 0.0)
    a = np.where(acceleration_step > 1e-15, acceleration_step, 0.0) * sample_time
    with np.errstate(divide="ignore", invalid="ignore"):
        v = 2.0 * c / (b + np.sqrt(b * b + 4.0 * a * c))
    v = np.where(((a > 0) | (b > 0)) & np.isfinite(c), v, np.inf)
    return v.min(axis=1)


def curvature_step_speed_limit(
    tangent: np.ndarray,
    tangent_jump: np.ndarray,
    curvature_jump: np.ndarray,
    kappa: np.ndarray,
    dkappa: np.ndarray,
    path_jerk: np.ndarray,
    limits: AxisLimitArrays,
    *,
    sample_time: float,
    share: float,
) -> np.ndarray:
    """Largest speed at (nearly) tangent junctions with a curvature jump, jerk limited (S-curve).

    At speed ``v`` the centripetal acceleration steps by ``v^2 dk`` at the junction: an axis
    acceleration step ``v^2 |dk_i|``, which the samples see as a jerk of at most ``v^2 |dk_i| / Ts``
    in the sample that holds the junction (the finite third difference of an acceleration step is
    at most 0.75 of it); a tangent step (rounding of the program's numbers) adds the velocity step
    ``v |dt_i|``, a jerk of at most ``v |dt_i| / Ts^2``. The rule of :func:`junction_speed_limit`
    (the steps passed within one sample) with each axis' own budget instead of a fixed share: the
    steps may take what the axis' jerk limit leaves beside the profile's smooth jerk ``s_i`` in the
    samples around the junction, ``v |dt_i| / Ts^2 + v^2 |dk_i| / Ts <= J_i - s_i(v)`` on each axis
    with a step. In a chain that keeps ``share`` of the limits in reserve ``s_i <= (1 - share) J_i``;
    with the path acceleration 0 at the junction (S-curve junctions) and ``|j| <= j_path`` on both
    sides, within the window ``d = 3 v_w Ts`` of the finite differences (speed
    ``v_w = v + j_path (3 Ts)^2 / 2``, path acceleration ``a_w = 3 j_path Ts``) the axis jerk
    ``t_i (j - k^2 v^3) + 3 k_i v a + (dk/ds)_perp,i v^3`` is also at most
    ``(|t_i| + k d) (j_path + k^2 v_w^3) + 3 k v_w a_w + k' v_w^3`` (``|dt/ds| = k``).
    Where the tangent runs along an axis the curvature step falls on the others, which then take
    nearly their whole jerk limit; at other orientations the bound tends to the fixed share.
    This is the control's rule for tangent, not curvature-continuous block transitions: Beckhoff
    TwinCAT CNC, axis parameter P-AXIS-00154 ("at the block transition from linear to circular
    block or vice versa, a jump in acceleration occurs, even if there is a tangential transition
    ... the velocity is reduced to such an extent that the permissible jerk at the block transition
    is maintained", per axis; P-AXIS-00340 the jerk at tangent continuous transitions), and per axis
    as LinuxCNC's tangent kinks (``src/emc/tp/tp.c`` ``tpSetupTangent``: each axis' acceleration
    for the direction change within one ``cycleTime``, ``findAccelScale``, sets ``kink_vel``).

    Parameters
    ----------
    tangent : ndarray, shape (m, 3)
        Unit tangent at the end of the segment before each junction [-].
    tangent_jump, curvature_jump : ndarray, shape (m, 3)
        Unit-tangent [-] and curvature-vector [1/mm] change across each junction.
    kappa, dkappa : ndarray, shape (m,)
        Largest curvature [1/mm] and ``|dk/ds|`` normal to the tangent [1/mm^2] of the two segments.
    path_jerk : ndarray, shape (m,)
        Largest path jerk of the two segments' profiles [mm/s^3].
    limits : AxisLimitArrays
    sample_time : float
        Ts [s].
    share : float
        Share of the jerk limits the chain keeps in reserve for its junctions [-].

    Returns
    -------
    ndarray, shape (m,)
        [mm/s]; 0 where the junction has no step or the smooth jerk leaves no budget.
    """
    Ts = sample_time
    dk, dt = np.abs(curvature_jump), np.abs(tangent_jump)
    t_abs = np.abs(tangent)
    J = limits.jerk[None, :]
    stepped = np.isfinite(J) & ((dk > 0) | (dt > 0))
    kappa, dkappa, jp = kappa[:, None], dkappa[:, None], path_jerk[:, None]

    def excess(v: np.ndarray) -> np.ndarray:
        vw = v[:, None] + 4.5 * jp * Ts * Ts
        smooth = ((t_abs + 3.0 * kappa * vw * Ts) * (jp + kappa * kappa * vw**3)
                  + 9.0 * kappa * vw * jp * Ts + dkappa * vw**3)
        smooth = np.minimum(smooth, (1.0 - share) * J)
        use = v[:, None] * dt / (Ts * Ts) + (v[:, None] ** 2) * dk / Ts + smooth
        return np.max(np.where(stepped, use - J, -np.inf), axis=1)

    lo = np.zeros(len(dk))
    hi = np.minimum(np.sqrt(_min_ratio(limits.jerk * Ts, dk)), _min_ratio(limits.jerk * Ts * Ts, dt))
    hi = np.where(np.isfinite(hi), hi, 0.0)  # no step: the rule does not apply
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        good = excess(mid) <= 0.0
        lo = np.where(good, mid, lo)
        hi = np.where(good, hi, mid)
    return lo


def _step_speed_limit(acceleration: np.ndarray, step: np.ndarray, *, sample_time: float, share: float) -> np.ndarray:
    """Largest path speed ``v`` whose axis velocity steps ``v |step_i|``, passed within one sample, use
    at most ``share`` of each axis' acceleration limit (the jerk's: :func:`_jerk_step_speed_limit`)."""
    return _min_ratio(share * acceleration * sample_time, step)


def extra_junction_speed_limit(
    rate_jump: np.ndarray,
    limits: Mapping[str, AxisLimits],
    *,
    sample_time: float,
    share: float,
    jerk_limited: bool,
    second_jump: np.ndarray | None = None,
) -> np.ndarray:
    """Largest path speed at junctions where the axes beyond X, Y, Z change their rate.

    The criterion of :func:`junction_speed_limit` for the tangent, applied to each of the axes
    a, b, c, u, v, w: their velocity steps ``v |dr_i|`` are passed within one sample using at most
    ``share`` of the axis' acceleration limit (``v |dr_i| <= share A_i Ts``) and, for the S-curve,
    of its jerk limit together with any acceleration step (``second_jump``; :func:`_jerk_step_speed_limit`,
    ``v |dr_i| / Ts^2 <= share J_i`` without one). These axes move linearly along each segment
    (no curvature term); the profile's zero path acceleration at junctions (S-curve) leaves them no
    acceleration step.

    Parameters
    ----------
    rate_jump : ndarray, shape (m, 6)
        Change of ``dr_i / ds`` (motion per unit of path [deg/mm, mm/mm]) across each junction.
    limits : mapping of str to AxisLimits
        Limits by axis name; an axis without limits adds no bound.
    second_jump : ndarray, shape (m, 6), optional
        Change of ``d^2 r_i / ds^2`` across each junction (beside the axis curve of a merged run,
        :func:`extra_curve_bounds`): for the S-curve its acceleration step ``v^2 |d2r_i|``, passed
        within the same sample as the velocity step, shares ``share`` of the jerk limit with it
        (``v |dr_i| / Ts^2 + v^2 |d2r_i| / Ts <= share J_i``, the rule of :func:`junction_speed_limit`).

    Returns
    -------
    ndarray, shape (m,)
        [path unit/s]
    """
    acc = np.array([limits[a].acceleration if a in limits else np.inf for a in EXTRA_NAMES])
    jerk = np.array([limits[a].jerk if a in limits else np.inf for a in EXTRA_NAMES])
    v = _step_speed_limit(acc, np.abs(rate_jump), sample_time=sample_time, share=share)
    if jerk_limited:
        second = np.zeros_like(rate_jump) if second_jump is None else np.abs(second_jump)
        v = np.minimum(v, _jerk_step_speed_limit(jerk, np.abs(rate_jump), second, sample_time=sample_time,
                                                 share=share))
    return v


def extra_curve_bounds(
    d1: np.ndarray, d2: np.ndarray, d3: np.ndarray, v_cap: np.ndarray, limits: Mapping[str, AxisLimits], *,
    share: np.ndarray, jerk_limited: bool,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Path bounds that keep the axes beyond X, Y, Z within their limits where they follow a smooth curve
    ``r(s)`` of the path (a merged run, :func:`interpolators.dense.fit_axes`).

    Axis ``i`` has velocity ``r_1 v``, acceleration ``r_1 a + r_2 v^2`` and jerk ``r_1 j + 3 r_2 v a + r_3 v^3``
    (``r_k``: the ``k``-th derivative along the path ``s``), as an axis on a curved path (module docstring)
    with ``r_2`` for the curvature term. The shares are those of arcs: ``r_2 v^2 <= CENTRIPETAL_SHARE A``,
    S-curve ``r_3 v^3 <= JERK_SPEED_SHARE J`` and ``3 r_2 v a <= JERK_ACCEL_SHARE J``; the path acceleration
    and jerk take what is left at the speed bound.

    Parameters
    ----------
    d1, d2, d3 : ndarray, shape (n, 6)
        Largest ``|r_1|``, ``|r_2|``, ``|r_3|`` of each segment for the axes a, b, c, u, v, w.
    v_cap : ndarray, shape (n,)
        The segments' speed bounds from the other axes [mm/s].
    limits : mapping of str to AxisLimits
    share : ndarray, shape (n,)
        Share of the acceleration and jerk limits the segment may use (the rest kept for junctions).

    Returns
    -------
    v_max, a_max, j_max : ndarray, shape (n,)
    """
    lim = [limits.get(a) for a in EXTRA_NAMES]
    vel = np.array([np.inf if x is None else x.velocity for x in lim])
    A = np.array([np.inf if x is None else x.acceleration for x in lim])[None, :] * share[:, None]
    J = np.array([np.inf if x is None else x.jerk for x in lim])[None, :] * share[:, None]
    moves1, moves2, moves3 = d1 > 1e-15, d2 > 1e-15, d3 > 1e-15
    # a derivative below the threshold is 0 in every term: a spline's rounding (|r_2| 4e-16 /mm beside |r_1| 1e-15)
    # left in the jerk term made 3 r_2 v a exceed J at the acceleration its own term did not bound (a negative jerk
    # bound, and ruckig found no profile: setpoint_fuzz rotary_cam seed 42267)
    d2, d3 = np.where(moves2, d2, 0.0), np.where(moves3, d3, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        v_i = np.minimum(np.where(moves1, vel / d1, np.inf),
                         np.sqrt(np.where(moves2, CENTRIPETAL_SHARE * A / d2, np.inf)))
        if jerk_limited:
            v_i = np.minimum(v_i, np.cbrt(np.where(moves3, JERK_SPEED_SHARE * J / d3, np.inf)))
        v = np.minimum(v_cap, v_i.min(axis=1))[:, None]
        a_i = np.where(moves1, (A - d2 * v**2) / d1, np.inf)
        if jerk_limited:
            a_i = np.minimum(a_i, np.where(moves2, JERK_ACCEL_SHARE * J / (3.0 * d2 * v), np.inf))
        a = a_i.min(axis=1)[:, None]
        j_i = np.where(moves1, (J - 3.0 * d2 * v * a - d3 * v**3) / d1, np.inf)
    return v[:, 0], a[:, 0], j_i.min(axis=1) if jerk_limited else np.full(len(v), np.inf)



def extra_path_bounds(
    ratio: np.ndarray, rapid: np.ndarray, limits: Mapping[str, AxisLimits]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bounds of path speed, acceleration and jerk that keep the axes beyond X, Y, Z within their limits.

    Parameters
    ----------
    ratio : ndarray, shape (n, 6)
        ``|dr_i| / L`` of each segment for the axes a, b, c, u, v, w (``EXTRA_NAMES``): motion
        per unit of path [deg/mm, mm/mm; per deg or mm of a move whose path is its own distance,
        X, Y, Z still].
    rapid : ndarray of bool, shape (n,)
        True for rapid moves (the rapid rates bound the speed instead of the velocities).
    limits : mapping of str to AxisLimits
        Limits by axis name [deg/s, deg/s^2, deg/s^3 on a, b, c; mm/s ... on u, v, w]; every
        axis that moves needs one.

    Returns
    -------
    v_max, a_max, j_max : ndarray, shape (n,)
        Path bounds [path unit/s, /s^2, /s^3]; ``inf`` where none of these axes moves.

    Raises
    ------
    InputError
        A moving axis without limits.
    """
    n, k = ratio.shape
    vel = np.full((n, k), np.inf)
    acc = np.full(k, np.inf)
    jerk = np.full(k, np.inf)
    for i, a in enumerate(EXTRA_NAMES):
        moves = bool(np.any(ratio[:, i] > 0))
        lim = limits.get(a)
        if lim is None:
            if moves:
                kind, unit = ("rotary axis", "deg") if a in ROTARY_NAMES else ("secondary linear axis", "mm")
                raise InputError(f"no limits for {kind} {a!r}, which the program moves",
                                 expected=f"limits for axis {a!r} [{unit}/s, {unit}/s^2, {unit}/s^3]")
            continue
        if not isinstance(lim, AxisLimits):
            raise InputError(f"limits[{a!r}] must be an AxisLimits, got {type(lim).__name__}")
        vel[:, i] = np.where(rapid, lim.rapid_rate, lim.velocity)
        acc[i], jerk[i] = lim.acceleration, lim.jerk
    return _min_ratio_rows(vel, ratio), _min_ratio(acc, ratio), _min_ratio(jerk, ratio)
