"""Dense CAM code under G64: runs of short lines merged into one smooth curve within the tolerance.

CAM systems write curved surfaces as thousands of short chords (a few micrometres to a fraction
of a millimetre), with their end points rounded to the output resolution (4 decimals). Blending
each junction on its own cannot pass such a run at the speed of the curve it approximates: a
blend may use at most half of each chord, and the rounded points turn by up to ten times the
true turn per junction, so the blends' radii are a fraction of the curve's. LinuxCNC faces the
same problem: its naive-CAM detector (``G64 P- Q-``, "Q: naive cam tolerance", LinuxCNC G-code
reference, https://linuxcnc.org/docs/html/gcode/g-code.html#gcode:g64) merges collinear runs
within ``Q`` into one line, and its trajectory planner looks ahead over many segments
(``tpRunOptimization`` in ``src/emc/tp/tp.c``, blend arcs in ``src/emc/tp/blendmath.c``).

Here a run of consecutive short feed lines (:data:`DENSE_MAX_LENGTH`, at least
:data:`DENSE_MIN_SEGMENTS`, junction turns up to :data:`DENSE_MAX_TURN`, under the S-curve up to
:data:`DENSE_MAX_CURVE_TURN` on tight curves (:func:`curve_junctions`), same feed and
tolerance) whose junctions are dense against the tolerance (turn ``theta`` and shorter line
``L`` with ``theta L < 2 tolerance``: the sagitta ``theta L / 8`` of a curve through the points
is below a quarter of the tolerance, and a tangent arc blend within the tolerance, of radius
about ``8 tolerance / theta^2``, would need far more than half of the line, ``4 tolerance /
theta``; coarser chords are blended per junction, which passes them as fast: measured on the
corpus, merging them made some programs up to 7 % slower; :data:`DENSITY`) is replaced by one cubic B-spline
curve (:class:`toolpaths.geometry.SplineCurve`). Under the S-curve the chords of a curve merge as long as the
sagitta ``theta L / 8`` of the curve through their points fits in the fitted curve's share of the tolerance,
``theta L < 8 FIT_SHARE tolerance`` (:data:`CURVE_DENSITY`): there the per-junction blend is a clothoid pair
within half of each chord, whose jerk at speed ``v`` is about ``4 v^3 theta / L^2``, ``4 / theta`` times the
curve's ``v^3 theta^2 / L^2`` (:func:`curve_junctions`), so coarse chords of a curve are passed far below the
speed of the curve they approximate (chords of 0.15 mm on a radius of 1 mm at F1200: 1.86 times the time of
the G3 arc; merged 1.02). Our reading: no control documents this threshold; the fit's own tolerance check
(below) keeps the path within the tolerance whatever the bound lets in. The curve:

* it passes exactly through the run's first and last programmed points;
* its coefficients are the least-squares fit to all the run's points, parametrised by chord
  length, with interior knots every ``q`` points (knot spacing up to :data:`MAX_KNOT_SPACING`;
  the rounding noise of the points averages out over a knot interval, so the curvature is that of
  the curve the chords approximate, not of the rounded points);
* where the run continues a line or arc tangentially (turn up to :data:`DENSE_MAX_TURN`), its end
  tangent is that segment's, so the junction stays tangent-continuous;
* it is accepted only if every point of it (checked at :data:`CHECK_POINTS` points per chord)
  lies within :data:`FIT_SHARE` of the path tolerance from the chords; otherwise the knot
  spacing is halved, and a run that no spacing fits is split at its sharpest junction.

The curve is cut at knots into pieces of about :data:`PIECE_LENGTH` (under the S-curve also where the jerk bound
of the speed changes by more than :data:`BOUND_STEP` between knot intervals, :func:`_bound_breaks`), each a
segment of the chain with its own speed bound from its largest curvature and curvature derivative
(:func:`interpolators.kinematics.curve_limits`); the pieces join with continuous curvature.
Programs without such runs (every G61 program, lines longer than :data:`DENSE_MAX_LENGTH`) are
planned exactly as before.

A chain that moves the axes beyond X, Y, Z (A-C, U-W): its runs (``unblended``, from before its corners were blended:
the corners left between its lines are blended across every axis, :mod:`interpolators.axis_blends`) take lines up
to :data:`UNBLENDED_MAX_LENGTH` whatever their density, the fit's tolerance check deciding, and those axes follow
one cubic spline along the merged curve's arc length (:func:`fit_axes`, within the tolerance in each axis' unit).
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numba
import numpy as np

from toolpaths.geometry import Arc, Line, SplineCurve, curve_frame_rates

if TYPE_CHECKING:  # scipy is imported where a run is fitted: a program without dense runs starts 0.5 s sooner
    from scipy.interpolate import BSpline

__all__ = [
    "DENSE_MAX_LENGTH",
    "UNBLENDED_MAX_LENGTH",
    "UNBLENDED_FEED_SPREAD",
    "CURVE_TURN_SHARE",
    "DENSE_MAX_CURVE_TURN",
    "DENSE_MAX_TURN",
    "DENSE_MIN_SEGMENTS",
    "DENSITY",
    "CURVE_DENSITY",
    "FIT_SHARE",
    "MAX_KNOT_SPACING",
    "PIECE_LENGTH",
    "CHECK_POINTS",
    "MergedRun",
    "chord_distance",
    "cubic_basis",
    "curve_junctions",
    "fit_run",
    "fit_deviation",
    "fit_axes",
    "merge_dense_runs",
]

#: Lines at most this long [mm] may be merged.
DENSE_MAX_LENGTH: float = 1.0
#: Lines at most this long [mm] may be merged in a chain moving axes beyond X, Y, Z (``unblended``).
UNBLENDED_MAX_LENGTH: float = 5.0
#: Largest relative difference of a line's feed from the first one of its run in such a chain: inverse time (G93)
#: feeds, each chord's length over its time, differ by the rounding of the programmed words.
UNBLENDED_FEED_SPREAD: float = 0.01
#: Largest turn [rad] at a junction inside a run (sharper corners end the run and stay corners).
DENSE_MAX_TURN: float = 0.2
#: Largest turn [rad] at a junction inside a run on a tight curve, S-curve only (see ``merge_dense_runs``).
DENSE_MAX_CURVE_TURN: float = 0.5
#: Share of a junction's turn its two neighbouring junctions turn together at least for it to be on a tight curve.
CURVE_TURN_SHARE: float = 0.5
#: Fewest lines merged into one curve.
DENSE_MIN_SEGMENTS: int = 8
#: Share of the path tolerance the fitted curve may deviate from the chords.
FIT_SHARE: float = 0.9
#: Bound on ``turn * length / tolerance`` of a junction inside a run (module docstring).
DENSITY: float = 2.0
#: The same bound under the S-curve: the sagitta ``turn * length / 8`` within FIT_SHARE of the tolerance.
CURVE_DENSITY: float = 8.0 * FIT_SHARE
#: Largest knot spacing [mm] tried first.
MAX_KNOT_SPACING: float = 4.0
#: Target length of the pieces a fitted curve is cut into [mm].
PIECE_LENGTH: float = 0.5
#: Largest ratio of the jerk-limited speed bounds of two knot intervals inside one piece (:func:`_bound_breaks`).
BOUND_STEP: float = 1.25
#: Points per knot interval at which :func:`_bound_breaks` evaluates the curvature.
_BOUND_SAMPLES = 4
#: Points per chord at which the fitted curve's distance from the chords is checked.
CHECK_POINTS: int = 8
#: Fewest programmed points per knot interval.
_MIN_POINTS_PER_KNOT = 4


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class MergedRun:
    """A run of short lines replaced by a smooth curve.

    Attributes
    ----------
    pieces : tuple of SplineCurve
        The curve, cut into segments.
    vertex_u : ndarray, shape (n + 1,)
        Curve parameter of each programmed point of the run (cumulative chord length [mm]).
    blocks : ndarray of int, shape (n,)
        Program block of each chord.
    deviation : float
        Largest distance [mm] of the curve from the programmed chords, as :func:`fit_run` checks it
        (:func:`fit_deviation`); a kink blend beside the curve keeps within the rest of the tolerance.
    """

    pieces: tuple[SplineCurve, ...]
    vertex_u: np.ndarray
    blocks: np.ndarray
    deviation: float = 0.0

    def block_at(self, u: np.ndarray) -> np.ndarray:
        """Block of the chord whose parameter range holds each curve parameter ``u``."""
        j = np.searchsorted(self.vertex_u, np.asarray(u, dtype=float), side="right") - 1
        return self.blocks[np.minimum(np.maximum(j, 0), len(self.blocks) - 1)]


def chord_distance(points: np.ndarray, u: np.ndarray, curve: np.ndarray, u_eval: np.ndarray) -> float:
    """Largest distance [mm] of ``curve`` (points at parameters ``u_eval``) from the chords of
    ``points`` (vertex parameters ``u``, increasing), each point against its own chord and the two beside it
    (its projection clipped to the chord)."""
    return float(_chord_distance(*(np.ascontiguousarray(x, dtype=float) for x in (points, u, curve, u_eval))))


@numba.njit(cache=True, nogil=True)
def _chord_distance(points, u, curve, u_eval):  # pragma: no cover - compiled
    """:func:`chord_distance`, compiled: the arithmetic of the array form it replaced (numpy's, operation by
    operation)."""
    n = points.shape[0] - 1
    worst = -np.inf
    for i in range(u_eval.shape[0]):
        j = min(max(np.searchsorted(u, u_eval[i], side="right") - 1, 0), n - 1)
        best = np.inf
        for dj in range(-1, 2):
            k = min(max(j + dj, 0), n - 1)
            ab0 = points[k + 1, 0] - points[k, 0]
            ab1 = points[k + 1, 1] - points[k, 1]
            ab2 = points[k + 1, 2] - points[k, 2]
            d0 = curve[i, 0] - points[k, 0]
            d1 = curve[i, 1] - points[k, 1]
            d2 = curve[i, 2] - points[k, 2]
            # numpy's einsum sums a three-term product as (x0 y0 + x2 y2) + x1 y1
            num = (d0 * ab0 + d2 * ab2) + d1 * ab1
            den = (ab0 * ab0 + ab2 * ab2) + ab1 * ab1
            t = min(max(num / max(den, 1e-300), 0.0), 1.0)
            sq = 0.0
            for c in range(3):
                e = (curve[i, c] - points[k, c]) - t * (points[k + 1, c] - points[k, c])
                sq += e * e
            best = min(best, math.sqrt(sq))
        worst = max(worst, best)
    return worst


def cubic_basis(x: np.ndarray, knots: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The cubic B-spline design matrix at the points ``x`` (within ``knots[3] .. knots[-4]``) on the clamped
    ``knots``, row by row: the first nonzero column of each row and its four values.

    The values of :meth:`scipy.interpolate.BSpline.design_matrix` (de Boor's recursion, in the order of scipy's
    ``_deBoor_D``), bit for bit, without building its sparse matrix (compiled).

    Returns
    -------
    first : ndarray of int, shape (n,)
    values : ndarray, shape (n, 4)
    """
    x = np.ascontiguousarray(x, dtype=float)
    values = np.empty((len(x), 4))
    first = np.empty(len(x), dtype=np.int64)
    _design(x, np.ascontiguousarray(knots, dtype=float), first, values)
    return first, values


@numba.njit(cache=True, nogil=True)
def _design(x, t, first, values):  # pragma: no cover - compiled
    """:func:`cubic_basis` into ``first`` and ``values``."""
    n = t.shape[0] - 4
    hh = np.empty(3)
    ell = 3
    for r in range(x.shape[0]):
        xv = x[r]
        while ell > 3 and xv < t[ell]:  # the interval t[ell] <= x < t[ell + 1] (the last one up to t[n])
            ell -= 1
        while ell < n - 1 and t[ell + 1] <= xv:
            ell += 1
        h = values[r]
        h[0] = 1.0
        for j in range(1, 4):
            for i in range(j):
                hh[i] = h[i]
            h[0] = 0.0
            for m in range(1, j + 1):
                xb = t[ell + m]
                xa = t[ell + m - j]
                if xb == xa:
                    h[m] = 0.0
                    continue
                w = hh[m - 1] / (xb - xa)
                h[m - 1] += w * (xb - xv)
                h[m] = w * (xv - xa)
        first[r] = ell - 3


def _gram_banded(first: np.ndarray, values: np.ndarray, m: int) -> np.ndarray:
    """``B^T B`` of a cubic B-spline design matrix ``B`` (row ``r``: ``values[r]`` in the columns
    ``first[r] .. first[r] + 3``) in the upper banded form of :func:`scipy.linalg.solveh_banded`:
    ``ab[3 + i - j, j] = (B^T B)[i, j]`` for ``j - 3 <= i <= j``."""
    ab = np.zeros((4, m))
    for a in range(4):
        for b in range(a, 4):
            ab[3 - (b - a)] += np.bincount(first + b, weights=values[:, a] * values[:, b], minlength=m)
    return ab


def _solve(points: np.ndarray, u: np.ndarray, knots: np.ndarray, tangents: tuple) -> np.ndarray | None:
    """Coefficients of the clamped cubic spline through the first and last point, least squares to
    the others; an end tangent fixes the second (second-last) coefficient's direction (points in X, Y, Z; without
    tangents ``points`` may have any number of columns, as the axes beyond X, Y, Z of :func:`fit_axes`).

    The normal equations of the free coefficients are copies (x, y, z) of one banded matrix
    ``G = B_f^T B_f`` bordered by one column per imposed tangent (its length ``alpha``, shared by the three
    coordinates): ``G`` is factored once (banded Cholesky) for all right-hand sides and the tangent
    lengths follow from the Schur complement."""
    import scipy.linalg

    m, dim = len(knots) - 4, points.shape[1]
    first, values = cubic_basis(u, knots)
    c = np.zeros((m, dim))
    c[0], c[-1] = points[0], points[-1]
    dirs = []  # (column, direction): c[column] = its end point + alpha * direction
    t0, t1 = tangents
    if t0 is not None:
        dirs.append((1, np.asarray(t0, dtype=float)))
        c[1] = points[0]
    if t1 is not None and m - 2 > 1:
        dirs.append((m - 2, -np.asarray(t1, dtype=float)))
        c[m - 2] = points[-1]
    lo = 2 if t0 is not None else 1
    hi = m - 2 if dirs and dirs[-1][0] == m - 2 else m - 1
    # residual of the fixed part (end points; tangent columns at alpha = 0), then B^T of it per column
    cols = first[:, None] + np.arange(4)
    rhs = points - np.einsum("rk,rkd->rd", values, c[cols])
    bt_rhs = np.stack([np.bincount(cols.ravel(), weights=(values * rhs[:, d, None]).ravel(), minlength=m)
                       for d in range(dim)], axis=1)
    ab = _gram_banded(first, values, m)

    def gram_col(j: int) -> np.ndarray:
        col = np.zeros(m)
        for off in range(4):
            if j - off >= 0:
                col[j - off] = ab[3 - off, j]
            if j + off < m:
                col[j + off] = ab[3 - off, j + off]
        return col

    g_cols = [gram_col(j)[lo:hi] for j, _ in dirs]
    y = np.zeros((max(hi - lo, 0), dim + len(dirs)))
    if hi > lo:
        try:
            y = scipy.linalg.solveh_banded(ab[:, lo:hi], np.column_stack([bt_rhs[lo:hi], *g_cols]), lower=False)
        except np.linalg.LinAlgError:  # a singular system (too few points per knot) is a failed fit
            return None
    y_rhs, y_g = y[:, :dim], y[:, dim:]
    if dirs:
        p = len(dirs)
        schur = np.zeros((p, p))
        r_alpha = np.zeros(p)
        for a, (ja, da) in enumerate(dirs):
            r_alpha[a] = da @ bt_rhs[ja] - g_cols[a] @ (y_rhs @ da)
            for b, (jb, db) in enumerate(dirs):
                schur[a, b] = (da @ db) * (gram_col(jb)[ja] - g_cols[a] @ y_g[:, b])
        try:
            alpha = np.linalg.solve(schur, r_alpha)
        except np.linalg.LinAlgError:
            return None
        y_rhs = y_rhs - sum(alpha[a] * np.outer(y_g[:, a], da) for a, (_, da) in enumerate(dirs))
    else:
        alpha = np.zeros(0)
    if not (np.all(np.isfinite(y_rhs)) and np.all(np.isfinite(alpha))):
        return None
    c[lo:hi] = y_rhs
    for a, (j, d) in enumerate(dirs):
        if alpha[a] <= 0:
            return None  # the tangent would point backwards
        c[j] = c[j] + alpha[a] * d
    return c


def fit_run(points: np.ndarray, tolerance: float, *, tangents: tuple = (None, None)) -> BSpline | None:
    """Smooth cubic spline within ``FIT_SHARE * tolerance`` of the chords through ``points``.

    Parameters
    ----------
    points : ndarray, shape (n + 1, 3)
        The run's programmed points [mm].
    tolerance : float
        Path tolerance [mm].
    tangents : tuple of (ndarray or None)
        Unit tangents imposed at the start and end (None: free).

    Returns
    -------
    BSpline or None
        Parametrised by cumulative chord length; None when no knot spacing fits.
    """
    fitted = _fit_with_deviation(points, tolerance, tangents)
    return None if fitted is None else fitted[0]


def _fit_with_deviation(points: np.ndarray, tolerance: float, tangents: tuple) -> tuple[BSpline, float] | None:
    """:func:`fit_run`'s spline and its :func:`fit_deviation` (the check that accepted it), or None."""
    from scipy.interpolate import BSpline

    u = _chord_lengths(points)
    for knots in _knot_vectors(u):
        c = _solve(points, u, knots, tangents) if len(knots) - 4 >= 4 else None
        if c is not None:
            spl = BSpline(knots, c, 3)
            deviation = fit_deviation(spl, points)
            if deviation <= FIT_SHARE * tolerance:
                return spl, deviation
    return None


def _chord_lengths(points: np.ndarray) -> np.ndarray:
    """Cumulative chord length [mm] at each of ``points``: the curve parameter of a run's programmed points."""
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])


def fit_deviation(spl: BSpline, points: np.ndarray) -> float:
    """Largest distance [mm] of the curve ``spl`` (parametrised by chord length) from the chords through
    ``points``, at :data:`CHECK_POINTS` parameters per chord (the check of :func:`fit_run`)."""
    u = _chord_lengths(points)
    f = (np.arange(CHECK_POINTS) / CHECK_POINTS)[None, :]
    u_eval = np.append((u[:-1, None] + np.diff(u)[:, None] * f).ravel(), u[-1])
    return chord_distance(points, u, spl(u_eval), u_eval)


def _knot_vectors(u: np.ndarray):
    """The clamped cubic knot vectors a run's fit tries in turn, on the parameters ``u`` of its points: interior
    knots every ``q`` points, ``q`` from :data:`MAX_KNOT_SPACING`'s worth of the mean chord halved down to
    :data:`_MIN_POINTS_PER_KNOT`."""
    n = len(u) - 1
    q = max(_MIN_POINTS_PER_KNOT, int(MAX_KNOT_SPACING / (u[-1] / n)))
    while True:
        n_int = max(1, round(n / q))
        inner = u[np.round(np.linspace(0, n, n_int + 1)[1:-1]).astype(np.int64)]
        yield np.concatenate([[u[0]] * 4, inner, [u[-1]] * 4])
        if q <= _MIN_POINTS_PER_KNOT:
            return
        q = max(_MIN_POINTS_PER_KNOT, q // 2)


def fit_axes(s: np.ndarray, values: np.ndarray, tolerance: float) -> BSpline | None:
    """Smooth cubic spline of the axes beyond X, Y, Z along a merged run, within ``FIT_SHARE * tolerance`` of
    their programmed motion.

    The programmed motion of these axes is piecewise linear in the path: on each chord they move in
    proportion to it (RS274/NGC 3, Sec. 2.1.2.5). Along the run's fitted curve (arc length ``s``, the
    programmed points at ``s_k``) that is the polyline through ``(s_k, r_k)``; the spline replaces it as the
    curve replaces the chords: least squares with interior knots every ``q`` points (as :func:`fit_run`),
    through the first and last values exactly, accepted when it lies within the tolerance of the polyline
    at :data:`CHECK_POINTS` points per chord on every axis, else with the knot spacing halved. The tolerance
    is the path tolerance ``P`` in each axis' own unit (deg on A, B, C; mm on U, V, W): our reading of
    LinuxCNC, whose trajectory planner passes the junctions of segments moving A-C or U-W with parabolic
    blends of all axes under the one G64 P tolerance (``src/emc/tp/tp.c``, ``tcRotaryMotionCheck`` turns
    the XYZ arc blends off for them); HEIDENHAIN's cycle 32 TOLERANCE has a rotary tolerance TA of its own,
    which this reader does not take.

    Parameters
    ----------
    s : ndarray, shape (n + 1,)
        Arc length of each programmed point on the fitted curve [mm], increasing, ``s[0] = 0``.
    values : ndarray, shape (n + 1, m)
        The axes' programmed values at those points [deg or mm].
    tolerance : float
        [deg or mm].

    Returns
    -------
    BSpline or None
        ``r(s)``, values of shape (m,); None when no knot spacing fits.
    """
    from scipy.interpolate import BSpline

    f = (np.arange(CHECK_POINTS) / CHECK_POINTS)[None, :]
    s_eval = np.append((s[:-1, None] + np.diff(s)[:, None] * f).ravel(), s[-1])
    polyline = np.column_stack([np.interp(s_eval, s, col) for col in values.T])
    still = np.all(values == values[0], axis=0)
    for knots in _knot_vectors(s):
        c = _solve(values, s, knots, (None, None))
        if c is None:
            continue
        c[:, still] = values[0, still]  # an axis the run does not move: all its coefficients at its value
        spl = BSpline(knots, c, 3)
        if np.max(np.abs(spl(s_eval) - polyline)) <= FIT_SHARE * tolerance:
            return spl
    return None


def _turn(a: np.ndarray, b: np.ndarray) -> float:
    return math.acos(float(np.clip(a @ b, -1.0, 1.0)))


def _end_tangent(seg, at_start: bool) -> np.ndarray:
    """Unit tangent of ``seg`` at its end (``at_start=False``) or start."""
    if isinstance(seg, Line):
        return seg.direction
    return np.asarray(seg.tangent_at(0.0 if at_start else seg.length), dtype=float)


def _pieces(spl: BSpline, start: np.ndarray, end: np.ndarray, *, by_bound: bool) -> tuple[SplineCurve, ...]:
    """The curve cut at knots into pieces of about PIECE_LENGTH (at least two, so that no piece is closed); with
    ``by_bound`` (the S-curve) also where the jerk bound of the speed changes along it (:func:`_bound_breaks`)."""
    knots = np.unique(spl.t)
    approx = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(spl(knots), axis=0), axis=1))])
    n_p = max(2, int(round(approx[-1] / PIECE_LENGTH))) if len(knots) > 2 else 1
    cut = np.unique(knots[np.searchsorted(approx, np.linspace(0, approx[-1], n_p + 1)[1:-1])])
    if by_bound and len(knots) > 2:
        cut = np.union1d(cut, _bound_breaks(spl, knots, approx))
    brk = np.concatenate([[knots[0]], cut[(cut > knots[0]) & (cut < knots[-1])], [knots[-1]]])
    # inner ends are C(u) evaluated alike on both sides: neighbouring pieces meet bit for bit
    return SplineCurve.pieces(spl, brk, start=start, end=end)


def _bound_breaks(spl: BSpline, knots: np.ndarray, approx: np.ndarray) -> np.ndarray:
    """The knots where a piece's speed bound would change by more than :data:`BOUND_STEP`: the jerk-limited
    speed ``|(k^2, dk/ds)|^(-1/3)`` (:func:`interpolators.kinematics.curved_speed_bound`, up to the limits) of
    each knot interval, from :data:`_BOUND_SAMPLES` points of it, is compared with the range of the piece so
    far, which starts afresh once it spans :data:`PIECE_LENGTH` since its last cut (counted from these cuts, not
    from the fixed ones of :func:`_pieces`, which the union keeps too).

    A piece's bound is its largest curvature and curvature derivative (:meth:`SplineCurve.bounds`), so a 0.5 mm
    piece holding a tight fillet of CAM code (radius 0.1 mm between straight chords) ran wholly at the fillet's
    speed; cut at the fillet, only the fillet does, the rest slowing down to it and back within the jerk limit
    (the look-ahead's reach, :func:`interpolators.profiles.reach_passes`). Our reading: a controller's look-ahead
    bounds the feed per interpolation step from the local curvature (Erkorkmaz & Altintas, "High speed CNC
    system design. Part I", Int. J. Mach. Tools Manuf. 41 (2001): feed scheduled along a quintic spline from its
    local curvature); the knot intervals are the curve's own steps here."""
    f = (np.arange(_BOUND_SAMPLES) + 0.5) / _BOUND_SAMPLES
    u = (knots[:-1, None] + np.diff(knots)[:, None] * f[None, :]).ravel()
    k, k_s, _ = curve_frame_rates(spl(u, 1), spl(u, 2), spl(u, 3))
    load = np.hypot(np.einsum("ij,ij->i", k, k), np.linalg.norm(k_s, axis=1)).reshape(-1, _BOUND_SAMPLES).max(axis=1)
    speed = np.cbrt(1.0 / np.maximum(load, 1e-12))
    out = []
    lo = hi = speed[0]
    s0 = 0.0
    for i in range(1, len(speed)):
        lo, hi = min(lo, speed[i]), max(hi, speed[i])
        if hi > BOUND_STEP * lo or approx[i] - s0 >= PIECE_LENGTH:
            out.append(knots[i])
            lo = hi = speed[i]
            s0 = approx[i]
    return np.asarray(out, dtype=float)


def _merge(segments: list, lo: int, hi: int, blocks: list[int], tolerance: float, neighbours: tuple,
           turns: np.ndarray, *, by_bound: bool) -> list[tuple[int, int, MergedRun | None]]:
    """Fit lines ``lo..hi-1``; split at the sharpest junction when no curve fits."""
    if hi - lo < DENSE_MIN_SEGMENTS:
        return [(k, k + 1, None) for k in range(lo, hi)]
    points = np.array([segments[lo].start] + [segments[k].end for k in range(lo, hi)])
    before, after = neighbours
    t0 = t1 = None
    if before is not None and _turn(_end_tangent(before, False), segments[lo].direction) <= DENSE_MAX_TURN:
        t0 = _end_tangent(before, False)
    if after is not None and _turn(segments[hi - 1].direction, _end_tangent(after, True)) <= DENSE_MAX_TURN:
        t1 = _end_tangent(after, True)
    fitted = _fit_with_deviation(points, tolerance, (t0, t1))
    if fitted is None and (t0 is not None or t1 is not None):
        fitted = _fit_with_deviation(points, tolerance, (None, None))
    if fitted is not None:
        spl, deviation = fitted
        run = MergedRun(pieces=_pieces(spl, points[0], points[-1], by_bound=by_bound), vertex_u=_chord_lengths(points),
                        blocks=np.asarray(blocks[lo:hi], dtype=np.int64), deviation=deviation)
        return [(lo, hi, run)]
    k = lo + 1 + int(np.argmax(turns[lo:hi - 1]))
    return (_merge(segments, lo, k, blocks, tolerance, (before, None), turns, by_bound=by_bound)
            + _merge(segments, k, hi, blocks, tolerance, (None, after), turns, by_bound=by_bound))


def curve_junctions(turns: np.ndarray, *, curvature_continuous: bool) -> np.ndarray:
    """Which junctions of a chain (their ``turns`` [rad], NaN next to an arc) may lie inside a run.

    A junction turning by up to :data:`DENSE_MAX_TURN` may; a sharper one is a corner and ends the run. With
    ``curvature_continuous`` (the S-curve) a junction turning by up to :data:`DENSE_MAX_CURVE_TURN` may too when
    its two neighbouring junctions together turn by at least :data:`CURVE_TURN_SHARE` of its turn (a chain's
    first and last junctions have one neighbour and keep the cap): the chords of a tight curve all turn (chords
    of 50 um on a radius of 0.24 mm turn by 0.21 rad each, a helical entry as CAM writes it), where a corner is
    one sharp turn between gentle ones. The sum, not each neighbour, because the rounded end points of chords
    of 10-50 um (3 decimals, as FreeCAD writes the fillets of a profile of radius 0.05-0.1 mm) make their turns
    alternate, 0.11, 0.23, 0.22, 0.19, 0.33: each neighbour alone would cut such a fillet into runs too short to
    merge, left to per-junction clothoid blends at a third of the speed (our reading; the fit's tolerance check
    keeps the path within the tolerance whatever joins a run).

    Our reading (no control documents its look-ahead's thresholds): the per-junction blend of such chords is a
    clothoid pair within half of each chord, whose curvature rises from zero to about ``2 theta / L`` over
    ``L / 2``: its jerk at speed ``v`` is about ``4 v^3 theta / L^2``, ``4 / theta`` times the ``v^3 / r^2 =
    v^3 theta^2 / L^2`` of the curve through the points, so per-junction blends pass a tight curve at about
    ``(theta / 4)^(1/3)`` of its speed wherever the jerk limit binds (0.37 at 0.2 rad). Under the trapezoid the
    tangent arc blend of each junction has about the curve's radius and passes as fast (module docstring), so
    its runs stay as they were.
    """
    inside = turns <= DENSE_MAX_TURN
    if curvature_continuous and len(turns) > 2:
        with np.errstate(invalid="ignore"):
            shared = turns[:-2] + turns[2:] >= CURVE_TURN_SHARE * turns[1:-1]
            inside[1:-1] |= (turns[1:-1] <= DENSE_MAX_CURVE_TURN) & shared
    return inside


def _is_dense(seg, feed: float, rapid: bool, max_length: float = DENSE_MAX_LENGTH) -> bool:
    return isinstance(seg, Line) and not rapid and 0 < seg.length <= max_length and feed > 0


def merge_dense_runs(
    segments: list, blocks: list[int], feeds: list[float], rapid: list[bool], tolerances: list[float], *,
    curvature_continuous: bool = False, unblended: bool = False,
) -> tuple[list, list[int], dict[int, MergedRun]]:
    """Replace runs of dense short lines of one G64 chain by fitted smooth curves.

    Parameters
    ----------
    segments : list of Line or Arc
        Consecutive segments of one chain.
    blocks, feeds, rapid : list
        Per segment: program block, feed [mm/s], rapid flag.
    tolerances : list of float
        Path tolerance [mm] of each junction ``k`` (between segment ``k`` and ``k + 1``).
    curvature_continuous : bool
        The S-curve (its corners would be blended by clothoid pairs): junctions on a tight curve may
        turn by more than :data:`DENSE_MAX_TURN` inside a run (:func:`curve_junctions`), and coarser
        chords merge (:data:`CURVE_DENSITY` instead of :data:`DENSITY`).
    unblended : bool
        The chain moves axes beyond X, Y, Z: lines up to :data:`UNBLENDED_MAX_LENGTH` merge whatever their
        density, the fit's tolerance check decides (its corners left unmerged are blended with those axes on a
        quintic, :mod:`interpolators.axis_blends`, within the shorter blends their tolerance allows), and so do lines
        whose feeds differ by up to :data:`UNBLENDED_FEED_SPREAD` (inverse time, G93).

    Returns
    -------
    segments : list
        The chain with each merged run replaced by its pieces.
    first : list of int
        For each returned segment, the index of the first input segment it stands for (its feed,
        rapid flag and block; the tolerance after it is that of the last input segment it
        replaces: the one before the next different ``first``, as a run's pieces share theirs).
    runs : dict of int to MergedRun
        For each returned piece, the run it belongs to.
    """
    n = len(segments)
    longest = UNBLENDED_MAX_LENGTH if unblended else DENSE_MAX_LENGTH
    dense = [_is_dense(s, f, r, longest) for s, f, r in zip(segments, feeds, rapid)]
    # turn [rad] at each junction between two lines
    d = np.array([s.direction if isinstance(s, Line) else np.full(3, np.nan) for s in segments])
    turns = np.arccos(np.clip(np.einsum("ij,ij->i", d[:-1], d[1:]), -1.0, 1.0)) if n > 1 else np.zeros(0)
    inside = curve_junctions(turns, curvature_continuous=curvature_continuous)
    density = math.inf if unblended else CURVE_DENSITY if curvature_continuous else DENSITY
    spread = UNBLENDED_FEED_SPREAD if unblended else 0.0
    spans: list[tuple[int, int, MergedRun | None]] = []
    k = 0
    while k < n:
        if not dense[k]:
            spans.append((k, k + 1, None))
            k += 1
            continue
        e = k + 1
        # dense junctions only (module docstring): coarser chords are blended per junction
        while (e < n and dense[e] and abs(feeds[e] - feeds[k]) <= spread * feeds[k]
               and tolerances[e - 1] == tolerances[k] and tolerances[e - 1] > 0 and inside[e - 1]
               and turns[e - 1] * min(segments[e - 1].length, segments[e].length) < density * tolerances[e - 1]):
            e += 1
        before = segments[k - 1] if k > 0 and isinstance(segments[k - 1], (Line, Arc)) else None
        after = segments[e] if e < n and isinstance(segments[e], (Line, Arc)) else None
        tol = tolerances[k] if e - k > 1 else 0.0
        spans.extend(_merge(segments, k, e, blocks, tol, (before, after), turns, by_bound=curvature_continuous)
                     if tol > 0
                     else [(i, i + 1, None) for i in range(k, e)])
        k = e
    out: list = []
    first: list[int] = []
    runs: dict[int, MergedRun] = {}
    for lo, _hi, run in spans:
        if run is None:
            out.append(segments[lo])
            first.append(lo)
            continue
        for p in run.pieces:
            runs[len(out)] = run
            out.append(p)
            first.append(lo)
    return out, first, runs
