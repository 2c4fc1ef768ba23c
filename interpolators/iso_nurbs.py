"""LinuxCNC's G5.2/G5.3 NURBS block, as a chain of chords.

LinuxCNC G-code reference (``docs/src/gcode/g-code.adoc`` "G5.2 G5.3 NURBS Block"; the interpreter's
``interp_convert.cc`` ``convert_nurbs`` and the canon's ``emccanon.cc`` ``NURBS_G5_FEED`` with
``nurbs_additional_functions.cc``): ``G5.2`` opens a block of control points, the current position the
first one; each line ``X- Y- P-`` (the plane's two axes) adds one with weight ``P``; ``L`` sets the order
(default 3; only an L above 3 changes it); ``G5.3`` closes the block and the tool follows the curve to the
last control point, at the modal feed. The curve is the rational B-spline of order ``k`` over the control
points ``P_0 .. P_n`` with LinuxCNC's clamped uniform knot vector ``t_i`` (i = 0 .. n + k): 0 for
``i < k``, ``i - k + 1`` for ``k <= i <= n``, ``n - k + 2`` above (``nurbs_G5_knot_vector_creator``), for
the parameter ``u`` from 0 to ``n - k + 2``:

    C(u) = sum_i N_i,k(u) w_i P_i / sum_i N_i,k(u) w_i

with the Cox-de Boor basis ``N_i,k`` (``nurbs_G5_Nmix``); it starts at ``P_0`` and ends at ``P_n``.
LinuxCNC's canon runs it as ``4 (n + 1)`` biarcs fitted to points and tangents of the curve; vcnc runs the
curve itself, as straight chords whose distance from it is at most
:data:`interpolators.iso_splines.SPLINE_TOLERANCE` (checked at the quarter points of each chord).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

import numpy as np

from interpolators.iso_splines import MAX_CHORDS, SPLINE_TOLERANCE
from interpolators.program import Block
from toolpaths.geometry import Line

__all__ = ["knot_vector", "nurbs_points", "nurbs_chords", "chord_blocks"]


def knot_vector(n: int, k: int) -> np.ndarray:
    """LinuxCNC's knot vector of ``n + 1`` control points and order ``k``: ``n + k + 1`` knots."""
    i = np.arange(n + k + 1)
    return np.where(i < k, 0, np.where(i <= n, i - k + 1, n - k + 2)).astype(float)


def _basis(u: np.ndarray, knots: np.ndarray, n: int, k: int) -> np.ndarray:
    """The basis functions ``N_i,k(u)`` (rows: the parameters ``u``, columns: i = 0 .. n), Cox-de Boor; the
    last span is closed at its end so that the curve reaches its last control point."""
    last = knots[-1]
    spans = (knots[:-1, None] <= u) & (u < knots[1:, None])
    spans |= (u == last) & (knots[:-1, None] < last) & (knots[1:, None] == last)
    b = spans.T.astype(float)  # order 1: len(knots) - 1 columns
    for order in range(2, k + 1):
        left_den = knots[order - 1:-1] - knots[:-order]
        right_den = knots[order:] - knots[1:-order + 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            left = np.where(left_den > 0, (u[:, None] - knots[:-order]) / left_den, 0.0) * b[:, :-1]
            right = np.where(right_den > 0, (knots[order:] - u[:, None]) / right_den, 0.0) * b[:, 1:]
        b = left + right
    return b[:, : n + 1]


def nurbs_points(control: np.ndarray, weights: np.ndarray, order: int, u: np.ndarray,
                 knots: np.ndarray | None = None) -> np.ndarray:
    """Points [mm] of the curve at the parameters ``u`` (``knots[0]`` .. ``knots[-1]``; LinuxCNC's
    :func:`knot_vector` when ``knots`` is None: 0 .. ``n - order + 2``)."""
    n = len(control) - 1
    knots = knot_vector(n, order) if knots is None else np.asarray(knots, dtype=float)
    nw = _basis(np.asarray(u, dtype=float), knots, n, order) * weights
    return (nw @ control) / nw.sum(axis=1)[:, None]


def nurbs_chords(control: np.ndarray, weights: np.ndarray, order: int, *, knots: np.ndarray | None = None,
                 tolerance: float = SPLINE_TOLERANCE) -> list[np.ndarray]:
    """End points of the chords of the curve (the first point, ``control[0]``, left out; the last exactly
    ``control[-1]``): ``4 (n + 1)`` equal parameter steps as LinuxCNC's canon divides it, each halved until
    the curve at its quarter points lies within ``tolerance`` [mm] of its chord.

    Parameters
    ----------
    control : ndarray, shape (n + 1, 3)
        Control points [mm].
    weights : ndarray, shape (n + 1,)
        Their weights (> 0).
    order : int
        The order ``k`` (degree ``k - 1``), ``2 <= k <= n + 1``.
    knots : ndarray, shape (n + k + 1,), optional
        The knot vector, non-decreasing, its first and last ``k`` knots equal (the curve then starts at
        ``control[0]`` and ends at ``control[-1]``: Fanuc's G06.2); default LinuxCNC's :func:`knot_vector`.
    """
    control = np.asarray(control, dtype=float)
    weights = np.asarray(weights, dtype=float)
    n = len(control) - 1
    knots = knot_vector(n, order) if knots is None else np.asarray(knots, dtype=float)
    u = np.linspace(knots[0], knots[-1], 4 * (n + 1) + 1)
    for _ in range(40):
        a, b = u[:-1], u[1:]
        pa, pb = (nurbs_points(control, weights, order, a, knots), nurbs_points(control, weights, order, b, knots))
        worst = np.zeros(len(a))
        for f in (0.25, 0.5, 0.75):
            p = nurbs_points(control, weights, order, a + f * (b - a), knots)
            worst = np.maximum(worst, _distance_to_chord(p, pa, pb))
        bad = worst > tolerance
        if not bad.any() or len(u) > MAX_CHORDS:
            break
        u = np.sort(np.concatenate([u, 0.5 * (a[bad] + b[bad])]))
    points = nurbs_points(control, weights, order, u[1:], knots)
    points[-1] = control[-1]  # the last control point exactly
    return list(points)


def _distance_to_chord(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of each point ``p`` from the segment ``a``-``b`` (row-wise)."""
    d = b - a
    length2 = np.einsum("ij,ij->i", d, d)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.where(length2 > 0, length2, 1.0), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * d), axis=1)


def chord_blocks(chords: Iterable[np.ndarray], st, blocks: list[Block], where, number, feed: Callable) -> None:
    """Append a line block from the reader's position (``st.pos`` [mm, machine]) through each point of ``chords``,
    leaving out chords of no length (coincident control points), at ``feed(st, segment)`` [mm/s]; ``st.pos`` ends
    at the last point. LinuxCNC G5.2 (:mod:`interpolators.iso_motion`) and Fanuc G06.2
    (:mod:`interpolators.iso_fanuc_nurbs`) run their curves so."""
    chain = [st.pos.copy()]
    for point in chords:
        if np.any(point != chain[-1]):
            chain.append(point)
    for a, b in zip(chain[:-1], chain[1:]):
        seg = Line(a, b)
        blocks.append(Block(line=where.line, number=number, text=where.text, kind="line", start=np.array(a),
                            target=np.array(b), feed=feed(st, seg), segment=seg, exact_stop=st.exact_stop,
                            tolerance=st.tolerance))
    st.pos = np.array(chain[-1], dtype=float)
