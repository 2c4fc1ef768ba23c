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

Under the S-curve (``curvature_continuous``) the kinks (tangent steps) of line/arc, arc/line, arc/arc,
line or arc/merged-curve and curve/curve junctions are blended too, by a G2 quintic (:func:`_kink_blend`) from a
point on the incoming segment to a point on the outgoing one, matching position, tangent and curvature there,
within the tolerance of the programmed path and using just under half of either segment at most (arcs and merged
curve pieces are cut there); the samples on it carry the incoming segment's block up to its middle and the
outgoing one's after (``interpolators.interpolate``). LinuxCNC's planner blends these junctions too, with
tangent arcs sized to the tolerance and the segment lengths (``tpCreateLineArcBlend``, ``tpCreateArcLineBlend``,
``tpCreateArcArcBlend`` in ``src/emc/tp/tp.c``, ``blendComputeParameters`` in ``src/emc/tp/blendmath.c``); a
tangent arc would leave a curvature step at both of its ends, which the S-curve's jerk limit forbids at speed,
hence the quintic (our
reading). The blend's shape (end-tangent stretch) is the one of a few with the highest speed bound.

The same quintic blends a tangent junction with a curvature step (line/arc, arc/arc of another radius or sense,
line or arc/merged curve) under the S-curve: it ramps the curvature over ``2 d`` within the tolerance (its leg
starts from ``d = sqrt(8 tolerance / dk)``, the offset of such a ramp being about ``dk d^2 / 8``), where it
passes faster than the junction's own one-sample bound (``interpolators.interpolate._blend_worth``). Controls
treat these junctions as a jerk problem of their own: the ISG kernel (Beckhoff TwinCAT CNC) lowers the speed
at "tangential block transitions between circles with different radii and circles and linear blocks" only
where ``corr_v_trans_jerk`` (P-CHAN-00009, default 0: off) is set, with the transition jerk an axis parameter
(P-AXIS-00340 ``j_trans_c1``, "tangent continuous, non-curvature continuous block transitions", limited to the
jerk from the acceleration and the cycle time); SINUMERIK lets an axis exceed its jerk there
(MD32432 ``$MA_PATH_TRANS_JERK_LIM``, Function Manual Axes and Spindles B2, 06/2019, 12.2.16 "Excessive jerk
for block transitions without constant curvature"). Without such a parameter here, the blend keeps every axis
within its own jerk limit (our reading: a curvature ramp within P is what G64 allows).

The path then stays tangent-continuous (and, with clothoids, curvature-continuous), and the
blend's own speed bound (centripetal acceleration and, for the S-curve, jerk including the
curvature derivative; see :mod:`interpolators.kinematics`) sets the corner speed.

Junctions that remain discontinuous (line/arc and arc/arc corners not blended, reversals, curvature steps of
tangent-continuous line/arc and arc/arc junctions) are passed at a speed that keeps the step within one sample: see
:func:`interpolators.kinematics.junction_speed_limit` and, for the curvature steps of tangent junctions under the
S-curve, :func:`interpolators.kinematics.curvature_step_speed_limit` (each axis' own jerk budget). A backward
and a forward pass then lower the junction speeds until every segment can change from its entry to its exit speed
within its length (exactly for the trapezoid, with zero end accelerations for the S-curve).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numba
import numpy as np

from interpolators.dense import FIT_SHARE
from interpolators.kinematics import curved_speed_bound
from interpolators.profiles import reach_passes
from toolpaths.geometry import Arc, ClothoidPair, Line, SplineCurve, curve_frame_rates, piece_of

__all__ = ["DEFAULT_TOLERANCE", "JUNCTION_SHARE", "CornerBlends", "blend_corners", "junction_speeds"]

#: Path tolerance of G64 without ``P`` [mm].
DEFAULT_TOLERANCE: float = 0.01
#: Share of the axis acceleration (and, S-curve, jerk) limits reserved, inside G64 chains, for
#: the discontinuities passed between two samples.
JUNCTION_SHARE: float = 0.1
#: Smallest corner angle that is blended [rad]; smaller direction changes pass as junctions.
_MIN_BLEND_ANGLE = 1e-7
#: Smallest curvature step [1/mm] of a tangent junction that is blended (S-curve; :func:`_kink_blend`).
_MIN_BLEND_STEP = 1e-6
#: Largest corner angle that is blended [rad] (sharper corners are near-reversals: stop).
_MAX_BLEND_ANGLE = math.pi - 1e-3


Blend = Arc | ClothoidPair | SplineCurve
#: Blend lengths tried per kink and stretch, each scaled to the tolerance by the deviation measured on the previous.
_KINK_TRIES = 6
#: End-tangent stretches of the kink blends tried (times the chord; :meth:`toolpaths.geometry.SplineCurve.hermite`):
#: longer end tangents keep a longer blend within the tolerance, with a lower curvature derivative, up to a point.
_KINK_STRETCHES = (1.0, 1.15, 1.3)
#: Points of a kink blend, and of each programmed piece beside it, at which its deviation is measured.
_KINK_CHECK_POINTS = 64
#: Share of the tolerance a kink blend may use as measured (the rest covers the chords of the measurement).
_KINK_FIT_SHARE = 0.98


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class CornerBlends:
    """The blends possible at the line/line corners of a chain, for a ``worth`` predicate to judge at once.

    Attributes
    ----------
    corner : ndarray of int, shape (m,)
        Junction index ``k`` of each blend (between segment ``k`` and ``k + 1``).
    blends : list of Arc or ClothoidPair
        The blends.
    curvature, curvature_rate : ndarray, shape (m,)
        Largest curvature [1/mm] and ``|dk/ds|`` [1/mm^2] on each blend (``1 / radius`` and 0 on an arc).
    plane : ndarray of bool, shape (m, 3)
        The axes in each blend's plane (the moving axes).
    length : ndarray, shape (m,)
        Arc length of each blend [mm].
    """

    corner: np.ndarray
    blends: list[Blend]
    curvature: np.ndarray
    curvature_rate: np.ndarray
    plane: np.ndarray
    length: np.ndarray

    @classmethod
    def of(cls, corner: np.ndarray, blends: list[Blend]) -> CornerBlends:
        """Collect the arrays of the ``blends`` at the junctions ``corner``."""
        m = len(blends)
        kappa, dkappa = np.zeros(m), np.zeros(m)
        length = np.array([b.length for b in blends], dtype=float).reshape(m)
        plane = np.zeros((m, 3), dtype=bool)
        is_arc = [isinstance(b, Arc) for b in blends]
        arcs = [b for b, a in zip(blends, is_arc) if a]
        if arcs:
            i = np.flatnonzero(is_arc)
            kappa[i] = 1.0 / np.array([b.radius for b in arcs])
            axes = np.array([b.plane_axes for b in arcs])
            plane[i, axes[:, 0]] = plane[i, axes[:, 1]] = True
        is_pair = [isinstance(b, ClothoidPair) for b in blends]
        others = [b for b, a in zip(blends, is_pair) if a]
        if others:
            i = np.flatnonzero(is_pair)
            kappa[i] = [b.peak_curvature for b in others]
            dkappa[i] = [b.sharpness for b in others]
            plane[i] = np.abs(np.array([b.normal for b in others])) < 1.0 - 1e-12  # the axes in the corner plane
        for i in np.flatnonzero([isinstance(b, SplineCurve) for b in blends]).tolist():
            kappa[i], dkappa[i], t_abs = blends[i].bounds()
            plane[i] = t_abs > 0  # the axes the blend moves
        return cls(corner=np.asarray(corner, dtype=np.int64), blends=blends, curvature=kappa, curvature_rate=dkappa,
                   plane=plane, length=length)


def _arc_blends(corner: np.ndarray, ua: np.ndarray, ub: np.ndarray, cos_t: np.ndarray, theta: np.ndarray,
                n: np.ndarray, plane: np.ndarray, tolerance: np.ndarray, d_max: np.ndarray) -> list[Arc | None]:
    """Tangent arcs within ``tolerance`` [mm] of the corners, legs at most ``d_max`` [mm] (all arrays per
    corner): the arc of each corner, None where none fits."""
    half = 0.5 * theta
    sec_m1 = 1.0 / np.cos(half) - 1.0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        radius = np.where(sec_m1 > 0, tolerance / sec_m1, np.inf)
        d = radius * np.tan(half)
        short = d > d_max
        d = np.where(short, d_max, d)
        radius = np.where(short, d / np.tan(half), radius)
    fits = ~((radius < 1e-6) | (d < 1e-9))
    p1 = corner - d[:, None] * ua
    p2 = corner + d[:, None] * ub
    inward = ub - cos_t[:, None] * ua
    inward = inward / np.sqrt(np.einsum("ij,ij->i", inward, inward))[:, None]
    rows = np.flatnonzero(fits)
    arcs: list[Arc | None] = [None] * len(corner)
    built = Arc.from_arrays(p1[rows], p2[rows], p1[rows] + radius[rows, None] * inward[rows],
                            ccw=n[rows, plane[rows]] > 0, plane=plane[rows])
    for i, arc in zip(rows.tolist(), built):
        arcs[i] = arc
    return arcs


def _clothoid_blends(corner: np.ndarray, ua: np.ndarray, ub: np.ndarray, cos_t: np.ndarray, n: np.ndarray,
                     tolerance: np.ndarray, d_max: np.ndarray) -> list[ClothoidPair | None]:
    """Clothoid pairs within ``tolerance`` [mm] of the corners, legs at most ``d_max`` [mm] (the array form of
    :meth:`toolpaths.geometry.ClothoidPair.for_corner`): the blend of each corner, None where none fits."""
    theta = np.arctan2(np.sqrt(np.einsum("ij,ij->i", n, n)), cos_t)
    ok = (theta > 0.0) & (theta < math.pi) & (tolerance > 0) & (d_max > 0)
    leg_f, dev_f = ClothoidPair.shape_factors(np.where(ok, theta, 1.0))
    d = np.minimum(tolerance / dev_f, d_max / leg_f) * leg_f
    ok &= d > 1e-9
    rows = np.flatnonzero(ok)
    blends: list[ClothoidPair | None] = [None] * len(corner)
    c = corner[rows]
    built = ClothoidPair.from_arrays(c - d[rows, None] * ua[rows], c, c + d[rows, None] * ub[rows])
    for i, blend in zip(rows.tolist(), built):
        blends[i] = blend
    return blends


def _corner_blends(incoming: list[Line], outgoing: list[Line], tolerance: np.ndarray, *,
                   curvature_continuous: bool) -> list[Blend | None]:
    """The blend of each corner ``incoming[i].end == outgoing[i].start`` within ``tolerance[i]`` [mm], None where
    the corner is not blended (direction change outside ``(_MIN_BLEND_ANGLE, _MAX_BLEND_ANGLE)``, or no blend
    fits). A blend takes at most half of either line."""
    ua = np.array([ln.direction for ln in incoming]).reshape(-1, 3)
    ub = np.array([ln.direction for ln in outgoing]).reshape(-1, 3)
    corner = np.array([ln.end for ln in incoming]).reshape(-1, 3)
    d_max = 0.5 * np.minimum([ln.length for ln in incoming], [ln.length for ln in outgoing])
    m = len(corner)
    cos_t = np.clip(np.einsum("ij,ij->i", ua, ub), -1.0, 1.0)
    theta = np.arccos(cos_t)
    angle_ok = (_MIN_BLEND_ANGLE < theta) & (theta < _MAX_BLEND_ANGLE)
    n = np.cross(ua, ub)
    abs_n = np.abs(n)
    plane = np.argmax(abs_n, axis=1)
    r = np.arange(m)
    nn = abs_n[r, plane]
    others = np.where(np.arange(3)[None, :] == plane[:, None], 0.0, abs_n).max(axis=1, initial=0.0)
    principal = ~((others > 1e-12 * nn) | (np.abs(ua[r, plane]) > 1e-12) | (np.abs(ub[r, plane]) > 1e-12))
    clothoid = angle_ok & (curvature_continuous | ~principal)
    blends: list[Blend | None] = [None] * m
    k = np.flatnonzero(angle_ok & ~clothoid)
    if len(k):
        for i, b in zip(k.tolist(), _arc_blends(corner[k], ua[k], ub[k], cos_t[k], theta[k], n[k], plane[k],
                                                 tolerance[k], d_max[k])):
            blends[i] = b
    k = np.flatnonzero(clothoid)
    if len(k):
        for i, b in zip(k.tolist(), _clothoid_blends(corner[k], ua[k], ub[k], cos_t[k], n[k], tolerance[k],
                                                      d_max[k])):
            blends[i] = b
    return blends


def _frame(seg: Line | Arc | SplineCurve, s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Point, unit tangent and curvature vector [1/mm] of ``seg`` at arc length ``s`` [mm]."""
    if isinstance(seg, Line):
        return seg.point_at(s), seg.direction, np.zeros(3)
    if isinstance(seg, SplineCurve):
        return (seg.point_at(s), *seg.frame(seg.parameter_at(s)))
    return seg.point_at(s), seg.tangent_at(s), seg.curvature_at(s)


def _kinkable(seg: object) -> bool:
    """A segment whose ends a kink blend may take: a line, an arc of at most one turn, or a curve piece."""
    if isinstance(seg, Arc):
        return abs(seg.sweep) <= 2.0 * math.pi and seg.length > 0
    return isinstance(seg, (Line, SplineCurve)) and seg.length > 0


def _within_spline(a: object, b: object) -> bool:
    """Do ``a`` and ``b`` join inside one spline (consecutive pieces of a merged curve, cut where its speed bound
    changes) at a knot of multiplicity at most its degree less 2, where tangent and curvature are continuous: no
    kink blend to make (:func:`_kink_blend` would find none after evaluating both ends; 13,130 of the 19,291
    junctions it was asked about in the corpus program 0274)."""
    if not (isinstance(a, SplineCurve) and isinstance(b, SplineCurve) and a.spline is b.spline and a.u1 == b.u0):
        return False
    return int(np.count_nonzero(a.spline.t == a.u1)) <= a.spline.k - 2


@numba.njit(cache=True, nogil=True)
def _path_distance(points, path):  # pragma: no cover - compiled
    """Distance [mm] of each of ``points`` (m, 3) from the polyline ``path`` (n, 3)."""
    out = np.empty(points.shape[0])
    for i in range(points.shape[0]):
        best = np.inf
        for j in range(path.shape[0] - 1):
            ab0, ab1, ab2 = path[j + 1, 0] - path[j, 0], path[j + 1, 1] - path[j, 1], path[j + 1, 2] - path[j, 2]
            r0, r1, r2 = points[i, 0] - path[j, 0], points[i, 1] - path[j, 1], points[i, 2] - path[j, 2]
            n2 = ab0 * ab0 + ab1 * ab1 + ab2 * ab2
            t = (r0 * ab0 + r1 * ab1 + r2 * ab2) / n2 if n2 > 0.0 else 0.0
            t = min(max(t, 0.0), 1.0)
            g0, g1, g2 = r0 - t * ab0, r1 - t * ab1, r2 - t * ab2
            best = min(best, g0 * g0 + g1 * g1 + g2 * g2)
        out[i] = math.sqrt(best)
    return out


#: Power-basis coefficients of a quintic Bezier curve from its six control points: ``C(u) = sum_j u^j (M @ B)_j``.
_QUINTIC_POWER = np.array([[math.comb(5, j) * math.comb(j, i) * (-1.0) ** (j - i) if i <= j else 0.0
                            for i in range(6)] for j in range(6)])


def _quintic_basis(u: np.ndarray, order: int = 0) -> np.ndarray:
    """The matrix (len(u), 6) that maps a quintic Bezier curve's control points to its ``order``-th parameter
    derivative at ``u``."""
    j = np.arange(6)
    fall = np.array([math.perm(int(k), order) for k in j], dtype=float)  # j! / (j - order)!
    return np.where(j >= order, fall * np.power(u[:, None], np.maximum(j - order, 0)), 0.0) @ _QUINTIC_POWER


#: :func:`_quintic_basis` of the check parameters, for the curve and its first three derivatives.
_CHECK_BASIS = tuple(_quintic_basis(np.linspace(0.0, 1.0, _KINK_CHECK_POINTS), r) for r in range(4))


#: :func:`_quintic_basis` of :data:`_KINK_CHECK_POINTS` parameters between the two neighbours of each check
#: parameter (:func:`_blend_deviation`'s second pass).
_FINE_BASIS = tuple(_quintic_basis(np.linspace(max(i - 1, 0) * (1.0 / (_KINK_CHECK_POINTS - 1)),
                                               min(i + 1, _KINK_CHECK_POINTS - 1) * (1.0 / (_KINK_CHECK_POINTS - 1)),
                                               _KINK_CHECK_POINTS)) for i in range(_KINK_CHECK_POINTS))


def _blend_deviation(controls: np.ndarray, path: np.ndarray) -> float:
    """Largest distance [mm] of the quintic of ``controls`` from the polyline ``path``: at
    :data:`_KINK_CHECK_POINTS` parameters, then as many again between the two neighbours of the farthest one."""
    dist = _path_distance(_CHECK_BASIS[0] @ controls, path)
    i = int(np.argmax(dist))
    return float(max(dist[i], _path_distance(_FINE_BASIS[i] @ controls, path).max()))


def _kink_blend(a: Line | Arc | SplineCurve, b: Line | Arc | SplineCurve, tolerance: float,
                limits: tuple[float, float]) -> tuple[SplineCurve, float] | None:
    """The G2 blend of the kink where ``a`` ends and ``b`` starts, and its leg ``d`` [mm]: a quintic
    (:meth:`toolpaths.geometry.SplineCurve.hermite`) from the point ``d`` before the end of ``a`` to the point ``d``
    after the start of ``b``, matching position, tangent and curvature there, that lies within ``tolerance`` [mm]
    of the programmed path (measured against the polyline of both pieces, :func:`_blend_deviation`, within
    :data:`_KINK_FIT_SHARE` of it) and passes the kink itself within ``tolerance`` too (measured against the
    polyline of the blend's check points, which lies inside the blend), ``d`` just under half of either at most.
    The programmed path includes the corner: a blend may stay near both pieces and still cut a sharp kink by
    more than the tolerance; the line/line blends keep their distance from the corner at the tolerance
    (:func:`_arc_blends`, :func:`_clothoid_blends`), and so does LinuxCNC's planner, which sizes a blend from the
    tolerance at the segments' intersection (``blendmath.c``); our reading of G64 P for kinks.

    For each end-tangent stretch of :data:`_KINK_STRETCHES`, ``d`` starts from the clothoid pair's leg for the
    same turn and is rescaled by ``tolerance`` over the deviation measured (a kink's deviation grows as ``d``, a
    curvature ramp's as ``d^2``: rescaled by the ratio's square root), and bisected between the longest leg that
    fits and the shortest that does not once the rescaling overshoots (the largest fitting ``d`` kept: a longer
    leg bends less); of these the blend with the highest speed bound under the path limits ``limits = (A, J)`` is
    taken, :func:`interpolators.kinematics.curved_speed_bound` of its largest ``k`` and ``|dk/ds|`` at
    :data:`_KINK_CHECK_POINTS` parameters, the bound the planner gives it (with the ``k^2`` of the jerk: an
    overshoot of the curvature costs speed too). LinuxCNC sizes its line/arc
    and arc/arc blend arcs alike, the largest the tolerance and the segment lengths allow
    (``blendComputeParameters``, ``src/emc/tp/blendmath.c``). A tangent junction (turn up to
    :data:`_MIN_BLEND_ANGLE`) with a curvature step above :data:`_MIN_BLEND_STEP` starts from the leg of a curvature
    ramp within ``tolerance`` (module docstring). None where the turn is :data:`_MAX_BLEND_ANGLE` or more, where it
    is tangent without a curvature step, or where no blend fits."""
    la, lb = a.length, b.length
    (_, t_a, k_a), (_, t_b, k_b) = _frame(a, la), _frame(b, 0.0)
    theta = math.atan2(float(np.linalg.norm(np.cross(t_a, t_b))), float(t_a @ t_b))
    step = float(np.linalg.norm(k_b - k_a))
    if theta >= _MAX_BLEND_ANGLE or tolerance <= 0 or (theta <= _MIN_BLEND_ANGLE and step <= _MIN_BLEND_STEP):
        return None
    d_max = 0.49 * min(la, lb)  # under half: an arc or curve piece blended at both ends keeps a piece
    if theta > _MIN_BLEND_ANGLE:
        leg_f, dev_f = ClothoidPair.shape_factors(theta)
        d_start = float(min(tolerance / dev_f, d_max / leg_f) * leg_f)
    else:  # a tangent junction with a curvature step: the blend's curvature ramps over 2 d, off by about dk d^2 / 8
        d_start = min(math.sqrt(8.0 * tolerance / step), d_max)
    corner = b.point_at(np.zeros(1))
    at_leg = _legs(a, b)
    # a curvature ramp between arcs of opposite sense: its leg bisected to the longest that fits, the ramp's
    # curvature derivative the lower for it; elsewhere the longer legs passed slower on the whole (their bound held
    # over a longer stretch; measured: corpus 0274 1754.5 -> 1760.4 s beside merged curves, 0028 15.456 -> 15.495 s
    # at line/arc junctions)
    ramp = (theta <= _MIN_BLEND_ANGLE and isinstance(a, Arc) and isinstance(b, Arc)
            and float(np.dot(k_a, k_b)) < 0.0)
    best, best_v = None, 0.0
    for stretch in _KINK_STRETCHES:
        d, fit, fail = d_start, None, math.inf
        for _ in range(_KINK_TRIES):
            if d <= 1e-9:
                break
            ends, path = at_leg(d)
            controls = SplineCurve.hermite_controls(*ends, stretch=stretch)
            deviation = max(_blend_deviation(controls, path),
                            float(_path_distance(corner, _CHECK_BASIS[0] @ controls)[0])) / _KINK_FIT_SHARE
            if deviation > tolerance:
                fail = min(fail, d)
            elif fit is None or d > fit[2]:
                fit = (ends, controls, d)
            if deviation <= tolerance and (deviation >= 0.8 * tolerance or d >= d_max):
                break
            d = min(d * 0.95 * tolerance / max(deviation, 1e-3 * tolerance), d_max)
            if ramp and fit is not None and d >= fail:  # between the longest leg that fits and the shortest that not
                d = 0.5 * (fit[2] + fail)
        if fit is not None:
            k, k_s, _ = curve_frame_rates(*(basis @ fit[1] for basis in _CHECK_BASIS[1:]))
            v = float(curved_speed_bound(float(np.linalg.norm(k, axis=1).max()),
                                         float(np.linalg.norm(k_s, axis=1).max()), limits[0], limits[1],
                                         jerk_limited=True))
            if best is None or v > best_v:
                best, best_v = (fit[0], stretch, fit[2]), v
    if best is None:
        return None
    return SplineCurve.hermite(*best[0], stretch=best[1]), best[2]


def _legs(a: Line | Arc | SplineCurve, b: Line | Arc | SplineCurve
          ) -> Callable[[float], tuple[tuple[np.ndarray, ...], np.ndarray]]:
    """For :func:`_kink_blend`: the ends (point, tangent, curvature on ``a`` at ``d`` [mm] before its end and on
    ``b`` at ``d`` after its start) and the polyline of both pieces within ``2 d`` of the junction, for a leg
    ``d``; each leg's computed once for all the end-tangent stretches tried."""
    la, lb = a.length, b.length
    # a line's stretch of the polyline is its two end points (the points between lie on it)
    u_a, u_b = (np.linspace(0.0, 1.0, 2 if isinstance(seg, Line) else _KINK_CHECK_POINTS) for seg in (a, b))
    made: dict[float, tuple[tuple[np.ndarray, ...], np.ndarray]] = {}

    def at(d: float) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
        if d not in made:
            path = np.concatenate([a.point_at(la - min(2.0 * d, la) * (1.0 - u_a)), b.point_at(min(2.0 * d, lb) * u_b)])
            made[d] = ((*_frame(a, la - d), *_frame(b, d)), path)
        return made[d]

    return at


def _kink_blends(segments: list, candidates: list[int], tolerances: np.ndarray, limits: tuple[float, float],
                 offsets: np.ndarray) -> tuple[list[int], list[SplineCurve], list[float]]:
    """The kink blends (:func:`_kink_blend`) of the junctions ``candidates`` (``k``: between segment ``k`` and
    ``k + 1``, both :func:`_kinkable`): the junctions blended, their blends and legs. Beside a merged curve, which
    lies up to ``offsets`` [mm] (its fit's deviation; NaN: :data:`interpolators.dense.FIT_SHARE` of the tolerance,
    what its fit may take) off the programmed chords, the blend keeps within the rest of the tolerance, so that the
    path stays within the tolerance of the program (the two distances add at most)."""
    corners, blends, legs = [], [], []
    for k in candidates:
        tolerance = float(tolerances[k])
        tolerance -= float(np.nan_to_num(offsets[k:k + 2], nan=FIT_SHARE * tolerance).max())
        made = _kink_blend(segments[k], segments[k + 1], tolerance, limits)
        if made is not None:
            corners.append(k)
            blends.append(made[0])
            legs.append(made[1])
    return corners, blends, legs


def blend_corners(
    segments: list[Line | Arc],
    blocks: list[int],
    tolerances: list[float],
    *,
    worth: Callable[[CornerBlends], np.ndarray] | None = None,
    curvature_continuous: bool = False,
    kink_limits: tuple[float, float] = (1.0, 25.0),
    kinks: bool | list[bool] = True,
    offsets: list[float] | None = None,
) -> tuple[list[Line | Arc | ClothoidPair | SplineCurve], list[int]]:
    """Blend the corners of a continuous chain (line/line; with ``curvature_continuous`` every kink).

    Parameters
    ----------
    segments : list of Line or Arc
        Consecutive segments of one G64 chain.
    blocks : list of int
        Program block index of each segment.
    tolerances : list of float
        Path tolerance [mm] of each junction ``k`` (between segment ``k`` and ``k+1``).
    worth : callable, optional
        ``worth(blends)`` decides, for all the possible blends of the chain at once (a
        :class:`CornerBlends`), whether blending each corner pays off (a boolean array); a rejected
        corner stays sharp.
    curvature_continuous : bool
        Blend every corner with a clothoid pair (G2); otherwise with a circular arc where the
        corner lies in a principal plane and with a clothoid pair elsewhere. With it, the kinks
        (tangent steps) of line/arc, arc/line, arc/arc, line or arc/merged-curve and curve/curve junctions, and
        those junctions where tangent with a curvature step, are blended too, by a G2 quintic (:func:`_kink_blend`)
        that shortens both neighbours; ``worth`` judges them as well.
    kink_limits : tuple of float
        Path acceleration and jerk limits ``(A, J)`` [mm/s^2, mm/s^3] the kink blends' shapes are chosen
        for (only their ratio matters).
    kinks : bool or list of bool
        False: only the line/line corners, also under ``curvature_continuous``; a list: per junction ``k``, whether
        its kink may be blended (a chain moving the axes beyond X, Y, Z blends the kinks between lines and arcs,
        whose motion along a blend :mod:`interpolators.axis_blends` gives, not those beside its merged curves).
    offsets : list of float, optional
        Per segment, its largest distance [mm] from the programmed path: a merged curve's fit deviation
        (:attr:`interpolators.dense.MergedRun.deviation`), 0 for a line or arc; a kink blend keeps within the
        tolerance less the larger offset of its two segments. By default a curve piece
        (:class:`toolpaths.geometry.SplineCurve`) takes the :data:`interpolators.dense.FIT_SHARE` its fit may use.

    Returns
    -------
    segments, blocks : list
        The chain with blends inserted (a blend belongs to the block of the incoming segment)
        and the segments shortened accordingly; zero-length leftover lines are dropped.

    Notes
    -----
    Each corner is blended on its own: its blend takes at most half of either programmed segment, so the
    blends of consecutive corners never overlap, and all of a chain's line/line corners are computed at once.
    """
    is_line = np.array([isinstance(sg, Line) and sg.length > 0 for sg in segments], dtype=bool)
    cand = np.flatnonzero(is_line[:-1] & is_line[1:]).tolist()
    blend_at: dict[int, Blend] = {}
    if cand:
        made = _corner_blends([segments[k] for k in cand], [segments[k + 1] for k in cand],
                              np.asarray(tolerances, dtype=float)[cand], curvature_continuous=curvature_continuous)
        corners = [k for k, b in zip(cand, made) if b is not None]
        blends = [b for b in made if b is not None]
        if blends:
            accepted = [True] * len(blends) if worth is None else np.asarray(
                worth(CornerBlends.of(np.array(corners), blends)), dtype=bool).tolist()
            blend_at = {k: b for k, b, ok in zip(corners, blends, accepted) if ok}
    legs: dict[int, float] = {}
    allowed = np.broadcast_to(np.asarray(kinks, dtype=bool), (max(len(segments) - 1, 0),))
    if curvature_continuous and allowed.any():
        kinkable = np.array([_kinkable(sg) for sg in segments], dtype=bool)
        cand = [k for k in np.flatnonzero(kinkable[:-1] & kinkable[1:] & ~(is_line[:-1] & is_line[1:])
                                          & allowed).tolist()
                if not _within_spline(segments[k], segments[k + 1])]
        if offsets is None:  # NaN: a curve piece whose fit may take FIT_SHARE of the tolerance
            offsets = [math.nan if isinstance(sg, SplineCurve) else 0.0 for sg in segments]
        corners, made_kinks, leg = _kink_blends(segments, cand, np.asarray(tolerances, dtype=float), kink_limits,
                                                np.asarray(offsets, dtype=float))
        if made_kinks:
            accepted = [True] * len(made_kinks) if worth is None else np.asarray(
                worth(CornerBlends.of(np.array(corners), made_kinks)), dtype=bool).tolist()
            for k, b, d, ok in zip(corners, made_kinks, leg, accepted):
                if ok:
                    blend_at[k], legs[k] = b, d
    return _assemble(segments, blocks, blend_at, legs)


def _assemble(segments: list, blocks: list[int], blend_at: dict[int, Blend], legs: dict[int, float]
              ) -> tuple[list[Line | Arc | ClothoidPair | SplineCurve], list[int]]:
    """The chain with the blends ``blend_at`` (junction -> blend) inserted and the segments shortened to
    them (a line shorter than 1e-12 mm between two blends, or before the last one, is dropped); ``legs``: the
    length [mm] a kink blend takes of either segment (arcs and curve pieces are cut there)."""
    n = len(segments)
    cut = sorted({k for k in blend_at} | {k + 1 for k in blend_at})
    starts = np.array([blend_at[k - 1].end if k - 1 in blend_at else segments[k].start for k in cut]).reshape(-1, 3)
    ends = np.array([blend_at[k].start if k in blend_at else segments[k].end for k in cut]).reshape(-1, 3)
    lines = [i for i, k in enumerate(cut) if isinstance(segments[k], Line)]
    shortened = dict(zip([cut[i] for i in lines], Line.from_arrays(starts[lines], ends[lines])))
    for i, k in enumerate(cut):
        seg = segments[k]
        if isinstance(seg, Arc):
            shortened[k] = piece_of(seg, starts[i], ends[i])
        elif isinstance(seg, SplineCurve):
            shortened[k] = seg.trimmed(legs.get(k - 1, 0.0), seg.length - legs.get(k, 0.0), start=starts[i],
                                       end=ends[i])
    out: list[Line | Arc | ClothoidPair] = []
    out_blocks: list[int] = []
    for k in range(n):
        seg = shortened.get(k, segments[k])
        if k in blend_at:
            if seg.length > 1e-12:
                out.append(seg)
                out_blocks.append(blocks[k])
            out.append(blend_at[k])
            out_blocks.append(blocks[k])
        elif k < n - 1 or seg.length > 1e-12 or not out:
            out.append(seg)
            out_blocks.append(blocks[k])
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
    return reach_passes(v, length * shrink, a_max, j_max, jerk_limited=jerk_limited) * shrink
