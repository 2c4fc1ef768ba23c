"""Contour error: the shortest distance from the actual tool position to the programmed path.

The path is the exact geometry of the program (:class:`toolpaths.Path`: lines, arcs, helices), not
a polyline through the setpoints, so the error of an ideal machine is zero to rounding on every
primitive, and a lag along a straight line is no contour error at all.

Finding the nearest point efficiently
-------------------------------------
Samples are ordered along the path. When the commanded positions are known (every simulated or
captured run has them), they are first located on the path by a monotone walk (the commanded
segment index never decreases; each step looks ahead only as far as the command moved). The
actual position of sample k is then projected, in closed form (lines, arcs) or by a 1-D Newton
iteration (helices), onto the segments the command visited between ``k - back`` and
``k + ahead`` samples (``window_s``, default 0.5 s back and 0.05 s ahead: the tool may lag several
segments behind at corners). Segments whose bounding sphere is farther than the best distance
found are skipped, and so are blocks of 16 segments whose common ball is (a line's sphere stands on
it as diameter, an arc of at most half a turn's on its chord, by Thales; any ball that holds the
segment gives the same nearest point, a tighter one spares projections). Without commanded
positions every segment is a candidate (a robust but slower global search). Coincident geometry
(a circle run twice, a full circle's start and end) is told apart by the arc length of the command.

Sign
----
For a planar path (all motion in one coordinate plane, arcs in that plane) the error is signed:
positive to the right of the direction of travel seen from the positive plane normal, i.e.
outside a counter-clockwise contour (a circle cut with G03, the diamond of
:func:`toolpaths.diamond`) and inside a clockwise one; negative on the other side. Where the
nearest point is a corner the side is judged from the bisector of the two tangents (an overshoot
of a convex corner is outside), and an overshoot of the path's first or last point counts as
positive. For paths moving three axes the error is the (positive) distance.

Units: positions and errors mm in the arrays, metrics in um (``*_um``), arc length mm.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import weakref
from collections.abc import Sequence
from typing import Any

import numpy as np

from toolpaths.geometry import AXIS_LETTERS, Arc, ClothoidPair, Line, Path
from toolpaths.packed import PackedSegments
from vcnc.contour_kernel import ARC, BLOCK, CLOTHOID, LINE, locate, nearest
from vcnc.core.errors import InputError
from vcnc.core.metrics import error_metrics

__all__ = ["ContourError", "contour_error", "commanded_points", "contour_metrics", "path_features", "feed_segments",
           "auto_magnification", "moving_axes", "plot_plane"]

# ``compare`` and ``ContourReport`` (vcnc.contour_compare) are also reachable from here, lazily.

log = logging.getLogger(__name__)

#: Default search window (back, ahead) [s] around each sample's commanded segment.
WINDOW_S: tuple[float, float] = (0.5, 0.05)

#: Tangent-direction change [deg] above which a junction of two segments counts as a corner.
CORNER_ANGLE_DEG = 1.0

#: Half width [mm] of the stretch of path around a corner or quadrant change whose largest error
#: is reported for it.
FEATURE_WINDOW_MM = 2.0

#: A commanded position farther than this [mm] from the path means the capture and the path do
#: not belong together.
REFERENCE_TOLERANCE_MM = 0.05


# --------------------------------------------------------------------------------- geometry
@dataclasses.dataclass(frozen=True, eq=False)
class _Geometry:
    """Segments packed into arrays, projected onto the axes the positions have."""

    kind: np.ndarray
    start: np.ndarray
    end: np.ndarray
    direc: np.ndarray
    length: np.ndarray
    center: np.ndarray
    ep: np.ndarray
    eq: np.ndarray
    en: np.ndarray
    radius: np.ndarray
    phi0: np.ndarray
    sweep: np.ndarray
    helix: np.ndarray
    frame: np.ndarray  # (M, 4, 3) clothoid blends: u_in, w_in, u_out, w_out
    sharp: np.ndarray  # (M,) clothoid sharpness [1/mm^2]
    cum: np.ndarray  # (M + 1,) arc length at the start of each segment, and the total
    sphere_c: np.ndarray
    sphere_r: np.ndarray
    t_start: np.ndarray  # unit tangents at the start and end of each segment
    t_end: np.ndarray
    block_c: np.ndarray  # balls holding the spheres of each BLOCK segments
    block_r: np.ndarray

    def arrays(self) -> tuple:
        return (self.kind, self.start, self.end, self.direc, self.length, self.center, self.ep, self.eq, self.en,
                self.radius, self.phi0, self.sweep, self.helix, self.frame, self.sharp)

    def search_arrays(self) -> tuple:
        return self.cum, self.sphere_c, self.sphere_r, self.t_start, self.t_end, self.block_c, self.block_r


def _check_projectable(path: Path, present: Sequence[bool]) -> None:
    """InputError unless every segment of ``path`` projects onto the axes ``present``."""
    if all(present) and {type(seg) for seg in path.segments} <= {Line, Arc, ClothoidPair}:
        return  # every segment projects onto x, y, z
    for i, seg in enumerate(path.segments):
        if isinstance(seg, Arc):
            p, q = seg.plane_axes
            if not (present[p] and present[q]):
                raise InputError(
                    f"segment {i} is an arc in the {AXIS_LETTERS[p]}{AXIS_LETTERS[q]} plane but the positions have "
                    f"no {AXIS_LETTERS[p] if not present[p] else AXIS_LETTERS[q]} axis; "
                    "an arc cannot be projected onto the axes given"
                )
        elif isinstance(seg, ClothoidPair):
            fr = np.array([seg.u_in, seg.w_in, seg.u_out, seg.w_out])
            if np.any(fr[:, [k for k in range(3) if not present[k]]] != 0.0):
                raise InputError(
                    f"segment {i} is a corner blend that moves an axis the positions do not have; "
                    "give positions for every axis the program moves"
                )
        elif not isinstance(seg, Line):
            raise InputError(f"segment {i} of the path is not a Line, Arc or ClothoidPair: {type(seg).__name__}")


#: :func:`_pack` of the paths measured lately, by path (identity; dropped with the path) and axes present.
_PACKED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _pack(path: Path, present: Sequence[bool]) -> _Geometry:
    """Pack ``path`` (:class:`toolpaths.packed.PackedSegments`), with the coordinates of absent
    axes set to zero; once per path and axes, as :func:`feature_points` (``vcnc compare`` measures one path 22
    times: 8 s of a 65 s compare of corpus 0274, 38,000 segments)."""
    per_path = _PACKED.setdefault(path, {})
    key = tuple(bool(p) for p in present)
    if key not in per_path:
        per_path[key] = _pack_now(path, present)
    return per_path[key]


def _pack_now(path: Path, present: Sequence[bool]) -> _Geometry:
    _check_projectable(path, present)
    ps = PackedSegments.from_segments(path.segments)
    mask = np.array([1.0 if p else 0.0 for p in present])
    M = len(ps)
    kind = ps.kind  # the contour kernel uses the packer's kinds (lines, arcs, clothoid blends; no holds here)
    start, end, center = ps.start * mask, ps.end * mask, ps.center * mask
    ep, eq, en = ps.e_p, ps.e_q, ps.e_n
    radius, phi0, sweep = ps.radius, ps.start_angle, ps.sweep
    helix = np.where(en @ mask > 0, ps.helix, 0.0)
    frame = ps.frame if ps.frame is not None else np.zeros((M, 4, 3))
    sharp = ps.sharpness if ps.sharpness is not None else np.zeros(M)
    line, arc, clo = kind == LINE, kind == ARC, kind == CLOTHOID
    d = end - start
    # |d| as ``d @ d`` computes it per row (the stacked matmul is the same dot product, bit for bit)
    span = np.sqrt(np.matmul(d[:, None, :], d[:, :, None])[:, 0, 0])
    length = np.where(line, span, ps.length)
    length[arc] = np.hypot(radius[arc] * np.abs(sweep[arc]), helix[arc])
    direc = np.zeros((M, 3))
    moves = line & (span > 0)
    direc[moves] = d[moves] / span[moves, None]
    corner = np.zeros((M, 3))
    corner[clo] = np.array([path.segments[i].corner for i in np.flatnonzero(clo).tolist()]).reshape(-1, 3) * mask
    cum = np.concatenate([[0.0], np.cumsum(length)])
    sphere_c, sphere_r = _bounding_spheres(line, clo, start, end, center, en, radius, sweep, helix, length, corner)
    t_start = direc.copy()
    t_end = direc.copy()
    t_start[clo] = frame[clo, 0]
    t_end[clo] = frame[clo, 2]
    sig = np.where(sweep[arc] > 0, 1.0, -1.0)[:, None]
    turn = np.abs(sweep[arc])
    scale = (length[arc] / turn)[:, None]
    for psi, out in ((phi0[arc], t_start), (phi0[arc] + sweep[arc], t_end)):
        out[arc] = (radius[arc, None] * sig * (-np.sin(psi)[:, None] * ep[arc] + np.cos(psi)[:, None] * eq[arc])
                    + (helix[arc] / turn)[:, None] * en[arc]) / scale
    return _Geometry(kind, start, end, direc, length, center, ep, eq, en, radius, phi0, sweep, helix, frame, sharp,
                     cum, sphere_c, sphere_r, t_start, t_end, *_block_spheres(sphere_c, sphere_r))


def _bounding_spheres(line: np.ndarray, clo: np.ndarray, start: np.ndarray, end: np.ndarray, center: np.ndarray,
                      en: np.ndarray, radius: np.ndarray, sweep: np.ndarray, helix: np.ndarray, length: np.ndarray,
                      corner: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centres and radii of balls that hold each segment, for the search's pruning (a lower bound of the
    distance to a segment: any valid ball gives the same nearest points, a tighter one fewer projections).

    A line: the ball on it as diameter. An arc of at most half a turn: the ball on its chord as diameter
    (the arc sees its chord under an angle of at least 90 degrees: Thales), widened by half the helical rise;
    a longer arc: the ball about its centre. A corner blend: the ball about the corner through the blend's
    ends (it lies inside the triangle start-corner-end)."""
    chord = np.linalg.norm(end - start - helix[:, None] * en, axis=1)  # in the arc's plane
    short = ~line & ~clo & (np.abs(sweep) <= np.pi)
    sphere_c = np.where(line[:, None], 0.5 * (start + end), center + 0.5 * helix[:, None] * en)
    sphere_r = np.where(line, 0.5 * length, np.hypot(radius, 0.5 * helix))
    sphere_c[short] = 0.5 * (start[short] + end[short])
    # + 1e-12 relative: the rounding of the ball's numbers must not cut into the segment
    sphere_r[short] = np.hypot(0.5 * chord[short], 0.5 * helix[short]) * (1.0 + 1e-12) + 1e-12
    sphere_c[clo] = corner[clo]
    sphere_r[clo] = np.linalg.norm(start[clo] - corner[clo], axis=1)
    return sphere_c, sphere_r


def _block_spheres(centre: np.ndarray, radius: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A ball around the spheres of each :data:`vcnc.contour_kernel.BLOCK` consecutive segments (the last
    block padded with its last sphere): centred in their bounding box, reaching the farthest sphere."""
    M = len(radius)
    n = -(-M // BLOCK) * BLOCK
    c = np.concatenate([centre, np.repeat(centre[-1:], n - M, axis=0)]).reshape(-1, BLOCK, 3)
    r = np.concatenate([radius, np.repeat(radius[-1:], n - M)]).reshape(-1, BLOCK)
    mid = 0.5 * ((c - r[..., None]).min(axis=1) + (c + r[..., None]).max(axis=1))
    reach = (np.linalg.norm(c - mid[:, None, :], axis=2) + r).max(axis=1)
    return mid, reach * (1.0 + 1e-12) + 1e-12  # the rounding must not cut into a sphere


def _plane_normal(g: _Geometry) -> int | None:
    """Index of the normal axis when the (projected) path lies in one coordinate plane, else None."""
    if len(g.kind) == 0:
        return None
    pts = np.concatenate([g.start, g.end])
    moving = [bool(np.ptp(pts[:, i]) > 1e-12 * (1.0 + np.abs(pts[:, i]).max())) for i in range(3)]
    arcs = g.kind == ARC
    normals = set(np.unique(np.argmax(g.en[arcs], axis=1)).tolist())
    if np.any(g.helix[arcs] != 0.0) or len(normals) > 1:
        return None
    if normals:
        (nrm,) = normals
        return nrm if not moving[nrm] else None
    still = [i for i in (2, 1, 0) if not moving[i]]
    return still[0] if still else None


def path_features(path: Path, *, corner_angle_deg: float = CORNER_ANGLE_DEG) -> dict[str, np.ndarray]:
    """Corners and quadrant changes of a path, as arc lengths [mm] from its start.

    Corners are junctions where the tangent turns by more than ``corner_angle_deg``, and the
    middles of G64 corner blends (:class:`toolpaths.ClothoidPair`). Quadrant
    changes are the points inside arcs where the in-plane angle crosses a multiple of 90 degrees:
    one axis reverses there (friction and backlash glitches).

    Returns
    -------
    dict
        ``corners`` and ``quadrants``: ndarray of arc lengths [mm].
    """
    cum = np.concatenate([[0.0], np.cumsum([seg.length for seg in path.segments])])
    segs = path.segments
    # a G64 blend is a segment that is not the first of its block (the look-ahead gives the
    # blend the block of the line it leaves), or a clothoid pair
    blend = [isinstance(seg, ClothoidPair) or (i > 0 and path.blocks[i] == path.blocks[i - 1])
             for i, seg in enumerate(segs)]
    corners = [cum[i] + 0.5 * seg.length for i, seg in enumerate(segs) if blend[i]]
    cos_lim = math.cos(math.radians(corner_angle_deg))
    for i in range(len(segs) - 1):
        t_out = segs[i].tangent_at(segs[i].length)
        t_in = segs[i + 1].tangent_at(0.0)
        if float(np.dot(t_out, t_in)) < cos_lim:
            corners.append(cum[i + 1])
    quadrants = []
    for i, seg in enumerate(segs):
        if isinstance(seg, Arc) and not blend[i]:
            a0, sw = seg.start_angle, seg.sweep
            lo, hi = sorted((a0, a0 + sw))
            k = math.floor(lo / (math.pi / 2)) + 1
            while k * math.pi / 2 < hi - 1e-9:
                ang = k * math.pi / 2
                if ang > lo + 1e-9:
                    quadrants.append(cum[i] + (ang - a0) / sw * seg.length)
                k += 1
    return {"corners": np.sort(np.asarray(corners)), "quadrants": np.sort(np.asarray(quadrants))}


# --------------------------------------------------------------------------------- result
@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class ContourError:
    """Contour (and tracking) error of one run along a path.

    Attributes
    ----------
    error : ndarray, shape (N,)
        Contour error [mm]: signed for planar paths (positive right of the travel, i.e. outside
        a counter-clockwise contour; see the module notes), the distance otherwise.
    signed : bool
        Whether ``error`` carries a sign.
    normal : int or None
        Normal-axis index of the plane of a planar path (2 for XY).
    segment : ndarray of int, shape (N,)
        Index of the path segment holding the nearest point.
    arc_length : ndarray, shape (N,)
        Path arc length of the nearest point [mm].
    positions : ndarray, shape (N, k)
        Actual positions [mm], columns ``axes``.
    axes : tuple of str
        Column names of ``positions``.
    path : toolpaths.Path
        The programmed path.
    t : ndarray, shape (N,), optional
        Time [s].
    tracking : ndarray, shape (N, k), optional
        Tracking error, commanded minus actual position per axis [mm].
    commanded_segment, commanded_arc_length : ndarray, optional
        Where the command was on the path at each sample (segment index, arc length [mm]).
    include : ndarray of bool, shape (N,), optional
        Samples the metrics cover (e.g. feed moves only, rapids excluded); all when None.
    """

    error: np.ndarray
    signed: bool
    normal: int | None
    segment: np.ndarray
    arc_length: np.ndarray
    positions: np.ndarray
    axes: tuple[str, ...]
    path: Path
    t: np.ndarray | None = None
    tracking: np.ndarray | None = None
    commanded_segment: np.ndarray | None = None
    commanded_arc_length: np.ndarray | None = None
    include: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.error)

    @property
    def distance(self) -> np.ndarray:
        """Unsigned contour error [mm]."""
        return np.abs(self.error)

    def covered(self) -> np.ndarray:
        """Boolean mask of the samples the metrics cover (``include``; all samples without it)."""
        return np.ones(len(self.error), dtype=bool) if self.include is None else self.include

    def metrics(self, *, window_mm: float = FEATURE_WINDOW_MM) -> dict[str, Any]:
        """Summary numbers [um].

        Parameters
        ----------
        window_mm : float
            Half width [mm] of the stretch of path around each corner / quadrant change whose
            largest error is attributed to it.

        Returns
        -------
        dict
            ``max_um``, ``rms_um`` (over the covered samples); for a signed error also
            ``max_outside_um`` (largest positive) and ``max_inside_um`` (largest negative, as a
            positive number); ``corners`` and ``quadrants``: lists of ``{"arc_length_mm",
            "position_mm", "max_um"}``, and ``corner_max_um`` / ``quadrant_max_um`` (NaN when
            there are none); ``tracking``: per axis ``{"max_um", "rms_um"}`` when known;
            ``samples``: samples covered.
        """
        cov = self.covered()
        e = self.error[cov]
        out: dict[str, Any] = {**error_metrics(e), "samples": int(cov.sum())}
        if self.signed:
            out["max_outside_um"] = float(max(0.0, e.max()) * 1e3) if e.size else float("nan")
            out["max_inside_um"] = float(max(0.0, -e.min()) * 1e3) if e.size else float("nan")
        feats = feature_points(self.path)
        # samples sorted by arc length: each feature's window is one slice (a long program has tens
        # of thousands of corners and millions of samples)
        order = np.argsort(self.arc_length[cov], kind="stable")
        s, abs_e = self.arc_length[cov][order], np.abs(e[order])
        # one reduceat over the windows [lo, hi) (a 0 after the samples: hi may be their end) instead of a numpy
        # call per corner, 12 s of a 65 s compare of corpus 0274's 68,000 corners
        padded = np.append(abs_e, 0.0)
        for key, name in (("corners", "corner_max_um"), ("quadrants", "quadrant_max_um")):
            s0s, points = feats[key]
            lo = np.searchsorted(s, s0s - window_mm, side="left")
            hi = np.searchsorted(s, s0s + window_mm, side="right")
            keep = np.flatnonzero(hi > lo)
            top = (np.maximum.reduceat(padded, np.column_stack([lo[keep], hi[keep]]).ravel())[::2] * 1e3).tolist() \
                if keep.size else []
            out[key] = [{"arc_length_mm": float(s0s[k]), "position_mm": points[k], "max_um": v}
                        for k, v in zip(keep.tolist(), top)]
            out[name] = max(top, default=float("nan"))
        if self.tracking is not None:
            out["tracking"] = {a: error_metrics(self.tracking[cov, i]) for i, a in enumerate(self.axes)}
        return out

    def to_dict(self) -> dict[str, Any]:
        """Metrics plus what the error was measured on (JSON-ready)."""
        return {"signed": self.signed, "samples_total": len(self), "axes": list(self.axes), **self.metrics()}

    def magnified(self, magnification: float) -> np.ndarray:
        """Positions [mm] (x, y, z) of the path's nearest points displaced by the magnified error.

        The picture of the thesis' contouring figures: the deviation from the path is drawn
        ``magnification`` times its size.
        """
        foot = _points_at(self.path, self.segment, self.arc_length)
        pos = np.zeros((len(self), 3))
        for i, a in enumerate(self.axes):
            if a in AXIS_LETTERS:
                pos[:, AXIS_LETTERS.index(a)] = self.positions[:, i]
        present = [a in self.axes for a in AXIS_LETTERS]
        foot = foot * np.array([1.0 if p else 0.0 for p in present])
        return foot + magnification * (pos - foot)

    def plot(self, ax=None, *, magnification: float | None = None, label: str = "actual", **kwargs):  # noqa: ANN001
        """Draw the path and the actual contour with its error magnified; returns the Axes.

        ``magnification`` defaults to a 1-2-5 value that draws the largest error at about 10 %
        of the path's extent.
        """
        if ax is None:
            import matplotlib.pyplot as plt

            _, ax = plt.subplots()
        if magnification is None:
            magnification = auto_magnification(self.path, float(np.max(np.abs(self.error), initial=0.0)))
        i, j = plot_plane(self)
        pts = self.path.points(step=max(self.path.length / 2000, 1e-3))
        ax.plot(pts[:, i], pts[:, j], color="0.6", lw=1.0, label="programmed")
        cov = self.covered()
        mag = self.magnified(magnification)
        mag = np.where(cov[:, None], mag, np.nan)
        ax.plot(mag[:, i], mag[:, j], label=f"{label} (error x{magnification:g})", **kwargs)
        ax.set_xlabel(f"{AXIS_LETTERS[i]} [mm]")
        ax.set_ylabel(f"{AXIS_LETTERS[j]} [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(loc="best", fontsize="small")
        return ax

    def plot_error(self, ax=None, *, label: str = "actual", **kwargs):  # noqa: ANN001
        """Contour error [um] against path arc length [mm]; returns the Axes."""
        if ax is None:
            import matplotlib.pyplot as plt

            _, ax = plt.subplots()
        cov = self.covered()
        s = np.where(cov, self.arc_length, np.nan)
        e = self.error * 1e3
        # Break the line where the nearest point jumps along the path (the seam of a closed
        # contour, where samples near the start/end point belong to either end).
        span = float(np.nanmax(s) - np.nanmin(s)) if np.any(cov) else 0.0
        jumps = np.flatnonzero(np.abs(np.diff(s)) > max(0.05 * span, 1e-9)) + 1
        if jumps.size:
            s = np.insert(s, jumps, np.nan)
            e = np.insert(e, jumps, np.nan)
        ax.plot(s, e, label=label, **kwargs)
        ax.set_xlabel("path arc length [mm]")
        ax.set_ylabel("contour error [um]" + (" (+ right of travel)" if self.signed else ""))
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize="small")
        return ax


def auto_magnification(path: Path, max_error_mm: float) -> float:
    """A 1-2-5 magnification that draws ``max_error_mm`` at about 10 % of the path's extent."""
    pts = path.points(step=max(path.length / 500, 1e-3)) if len(path) else np.zeros((1, 3))
    extent = float(np.max(np.ptp(pts, axis=0))) if len(pts) else 1.0
    if not (max_error_mm > 0 and extent > 0):
        return 1.0
    raw = 0.1 * extent / max_error_mm
    exp = math.floor(math.log10(raw))
    for m in (5, 2, 1):
        if m * 10**exp <= raw:
            return float(m * 10**exp)
    return float(10**exp)  # pragma: no cover


def plot_plane(ce: ContourError) -> tuple[int, int]:
    """Indices of the two axes a plot of ``ce`` shows (its plane, or the first two axes)."""
    if ce.normal is not None:
        from toolpaths.geometry import PLANE_AXES

        p, q = PLANE_AXES[ce.normal]
        return (p, q) if p < q else (q, p)
    idx = [AXIS_LETTERS.index(a) for a in ce.axes if a in AXIS_LETTERS]
    return (idx + [1, 0])[:2] if len(idx) < 2 else (idx[0], idx[1])


#: Segments of a programmed path above which a report colours the path by its contour error instead of drawing
#: the magnified deviation beside it (``vcnc simulate``'s ``path.png``, ``vcnc compare``'s ``contour.png``): a CAM
#: raster's passes lie closer than the magnified error (corpus 0274, wild w022: 0.2-0.5 mm stepover, the error
#: drawn x100 is 5 mm), which then covers the path in one block of colour (our reading of the figure, seen on a
#: 4000 s program).
DENSE_SEGMENTS = 1000

#: Points drawn in a coloured path: the samples in as many stretches, the largest error of each.
DENSE_POINTS = 200_000


def plot_error_colours(ax, xy: np.ndarray, error_um: np.ndarray, *, vmax: float | None = None,
                       label: str = "commanded"):  # noqa: ANN001, ANN201 - matplotlib Axes and PathCollection
    """Draw the path ``xy`` [mm] (N x 2) grey with its samples coloured by ``error_um`` [um] (NaN: not drawn):
    the largest of each of at most :data:`DENSE_POINTS` stretches of samples, so that no peak is lost, largest
    drawn last; ``vmax`` the top of the colour scale (shared by several panels). Returns the scatter's
    collection (for a colour bar)."""
    err = np.where(np.isnan(error_um), -1.0, error_um)
    k = -(-len(err) // DENSE_POINTS)
    pad = np.concatenate([err, np.full(-len(err) % k, -1.0)]).reshape(-1, k)
    idx = np.arange(pad.shape[0]) * k + np.argmax(pad, axis=1)
    idx = idx[err[idx] >= 0]
    idx = idx[np.argsort(err[idx], kind="stable")]
    ax.plot(xy[:, 0], xy[:, 1], lw=0.3, color="0.75", label=label)
    dots = ax.scatter(xy[idx, 0], xy[idx, 1], c=err[idx], s=1.5, cmap="viridis", rasterized=True, vmin=0.0,
                      vmax=vmax)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    return dots


#: :func:`feature_points` of the paths measured lately, by path (identity; dropped with the path).
_FEATURES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def feature_points(path: Path) -> dict[str, tuple[np.ndarray, list[list[float]]]]:
    """``{"corners", "quadrants"}``: the arc lengths [mm] of :func:`path_features` and the points [mm] there.

    Computed once per path: the metrics of every run of one toolpath (``vcnc compare``'s noise realisations and
    models, 27 on a noisy truth) share them (3D_Chips, 4,700 blocks: 0.67 s of features and 1 s of points each
    time, 45 s of a 60 s compare; ``benchmarks/compare_program.py``)."""
    got = _FEATURES.get(path)
    if got is None:
        feats = path_features(path)
        cum = np.concatenate([[0.0], np.cumsum([seg.length for seg in path.segments])])
        got = {}
        for key in ("corners", "quadrants"):
            s0s = np.asarray(feats[key], dtype=float)
            got[key] = (s0s, [[float(v) for v in _point_at(path, float(s0), cum)] for s0 in s0s])
        _FEATURES[path] = got
    return got


def _point_at(path: Path, s: float, cum: np.ndarray) -> np.ndarray:
    """The point at arc length ``s`` [mm]; ``cum``: the segments' cumulative lengths from 0."""
    i = int(np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(path) - 1))
    return path.segments[i].point_at(s - cum[i])


def _points_at(path: Path, seg: np.ndarray, s: np.ndarray) -> np.ndarray:
    from toolpaths.packed import PackedSegments

    cum = np.concatenate([[0.0], np.cumsum([g.length for g in path.segments])])
    packed = PackedSegments.from_segments(list(path.segments))
    return packed.evaluate(seg, s - cum[seg])[0]


# --------------------------------------------------------------------------------- evaluation
def _columns(axes: Sequence[str], n_cols: int) -> np.ndarray:
    axes = tuple(str(a) for a in axes)
    if len(axes) != n_cols:
        raise InputError(f"positions have {n_cols} column(s) but {len(axes)} axis name(s) were given: {axes}")
    cols = np.full(3, -1, dtype=np.int64)
    for i, a in enumerate(AXIS_LETTERS):
        if a in axes:
            cols[i] = axes.index(a)
    if np.all(cols < 0):
        raise InputError(f"contour error needs at least one of the axes x, y, z; got {axes}")
    return cols


def _as_positions(name: str, arr: Any, n: int | None = None) -> np.ndarray:
    a = np.asarray(arr, dtype=float)
    if a.ndim == 1:
        a = a[:, None]
    if a.ndim != 2:
        raise InputError(f"{name} must be an array of shape (N, n_axes) [mm], got shape {a.shape}")
    if n is not None and a.shape[0] != n:
        raise InputError(f"{name} has {a.shape[0]} samples but positions have {n}")
    bad = np.flatnonzero(~np.isfinite(a).all(axis=1))
    if bad.size:
        raise InputError(f"{name} is not finite at sample {int(bad[0])}")
    return np.ascontiguousarray(a)


def _commanded_points(R: np.ndarray, cols: list[int], g: _Geometry) -> tuple[np.ndarray, np.ndarray]:
    """Segment and arc length of each commanded position on the path; InputError when a command
    lies off the path (the path does not belong to the positions)."""
    tol = 1e-9 * (1.0 + float(g.cum[-1]))
    cseg, s_cmd, dref = locate(R, cols, *g.arrays(), g.cum, tol)
    if len(R) and float(dref.max()) > REFERENCE_TOLERANCE_MM:
        k = int(np.argmax(dref))
        raise InputError(
            f"the commanded position at sample {k} is {dref[k]:.4g} mm from the path (more than "
            f"{REFERENCE_TOLERANCE_MM} mm): the path does not belong to these positions"
        )
    return cseg, s_cmd


def commanded_points(path: Path, reference: np.ndarray, axes: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
    """Segment index and arc length [mm] of each commanded position on ``path`` (the ``commanded_segment`` and
    ``commanded_arc_length`` of :func:`contour_error`), for ``contour_error(commanded=...)``: the runs of one set of
    setpoints share them (``vcnc compare``'s noise runs and predictions: 8 s of a 65 s compare of corpus 0274).
    :class:`vcnc.InputError` when a command lies off the path."""
    R = _as_positions("reference", reference)
    cols = _columns(axes, R.shape[1])
    return _commanded_points(R, cols, _pack(path, [c >= 0 for c in cols]))


def _command_on_path(reference, P: np.ndarray, cols, g, commanded) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(tracking error, commanded segment, commanded arc length) of :func:`contour_error`'s ``reference``: its
    points on the path as given (``commanded``, checked against the samples) or searched."""
    N = P.shape[0]
    R = _as_positions("reference", reference, N)
    if R.shape[1] != P.shape[1]:
        raise InputError(f"reference has {R.shape[1]} columns but positions have {P.shape[1]}")
    if commanded is None:
        cseg, s_cmd = _commanded_points(R, cols, g)
    elif len(commanded[0]) == N and len(commanded[1]) == N:
        cseg, s_cmd = commanded
    else:
        raise InputError(f"commanded holds {len(commanded[0])} points but positions have {N} samples")
    return R - P, cseg, s_cmd


def contour_error(
    path: Path,
    positions: np.ndarray,
    axes: Sequence[str],
    *,
    reference: np.ndarray | None = None,
    sample_time: float | None = None,
    t: np.ndarray | None = None,
    window_s: tuple[float, float] = WINDOW_S,
    include_segments: np.ndarray | None = None,
    commanded: tuple[np.ndarray, np.ndarray] | None = None,
) -> ContourError:
    """Contour error of sampled positions with respect to an exact path.

    Parameters
    ----------
    path : toolpaths.Path
        Programmed geometry (``Setpoints.path`` / ``Capture.path``).
    positions : ndarray, shape (N, k)
        Actual positions [mm], ordered in time, columns ``axes``.
    axes : sequence of str
        Column names; x, y, z enter the distance (other axes are ignored). The path is projected
        onto the axes present (a missing axis does not count), so an arc needs both its plane
        axes.
    reference : ndarray, shape (N, k), optional
        Commanded positions [mm], same columns. When given, the nearest point is searched near
        the command (see the module notes) and the tracking error is recorded; without it every
        segment is searched.
    sample_time : float, optional
        Sampling period [s] that turns ``window_s`` into samples (default: from ``t``, else 1 ms).
    t : ndarray, shape (N,), optional
        Time stamps [s], kept for plots.
    window_s : (float, float)
        How far back and ahead of each sample [s] the command's segments are searched.
    include_segments : ndarray of bool, shape (n_segments,), optional
        Segments whose samples (by the commanded segment) the metrics cover, e.g. feed moves
        only. All samples when None.
    commanded : (ndarray, ndarray), optional
        With ``reference``: its :func:`commanded_points` on ``path``, computed once for several runs of it.

    Returns
    -------
    ContourError

    Raises
    ------
    vcnc.InputError
        Shapes that do not match, non-finite values, an empty path, an arc whose plane axes are
        missing, or a reference that does not follow the path (farther than
        :data:`REFERENCE_TOLERANCE_MM`).
    """
    if not isinstance(path, Path):
        raise InputError(f"path must be a toolpaths.Path, got {type(path).__name__}")
    if len(path) == 0:
        raise InputError("the path has no segments: there is no contour to measure an error from")
    P = _as_positions("positions", positions)
    cols = _columns(axes, P.shape[1])
    present = [c >= 0 for c in cols]
    g = _pack(path, present)
    normal = _plane_normal(g)
    nvec = np.zeros(3)
    if normal is not None:
        nvec[normal] = 1.0
    if sample_time is None:
        sample_time = float(np.median(np.diff(t))) if t is not None and len(t) > 1 else 1e-3
    if not (math.isfinite(sample_time) and sample_time > 0):
        raise InputError(f"sample_time must be a finite value > 0 s, got {sample_time!r}")
    back = int(math.ceil(window_s[0] / sample_time))
    ahead = int(math.ceil(window_s[1] / sample_time))
    tracking = cseg = s_cmd = None
    if reference is not None:
        tracking, cseg, s_cmd = _command_on_path(reference, P, cols, g, commanded)
    # without a command every segment is searched (empty hints)
    hint_seg = cseg if cseg is not None else np.zeros(0, dtype=np.int64)
    hint_s = s_cmd if s_cmd is not None else np.zeros(0)
    err, seg, s = nearest(P, cols, *g.arrays(), *g.search_arrays(), hint_seg, hint_s, back, ahead, nvec,
                          normal is not None)
    include = None
    if include_segments is not None:
        inc = np.asarray(include_segments, dtype=bool)
        if inc.shape != (len(path),):
            raise InputError(f"include_segments needs one flag per segment ({len(path)}), got shape {inc.shape}")
        include = inc[cseg if cseg is not None else seg]
    return ContourError(
        error=err,
        signed=normal is not None,
        normal=normal,
        segment=seg,
        arc_length=s,
        positions=P,
        axes=tuple(str(a) for a in axes),
        path=path,
        t=None if t is None else np.asarray(t, dtype=float),
        tracking=tracking,
        commanded_segment=cseg,
        commanded_arc_length=s_cmd,
        include=include,
    )


def moving_axes(reference: np.ndarray, axes: Sequence[str]) -> list[str]:
    """Linear axes (x, y, z) whose commanded position changes."""
    ref = np.asarray(reference, dtype=float)
    return [a for i, a in enumerate(axes) if a in AXIS_LETTERS and ref.shape[0] and float(np.ptp(ref[:, i])) > 0]


def feed_segments(path: Path, program: Any) -> np.ndarray | None:
    """Flags of the path segments that are feed moves (not G00 / FMAX), for ``include_segments``.

    ``program`` is the :class:`interpolators.Program` the path was interpolated from (``path.blocks``
    index its blocks). None when the path has no feed move at all (then every sample counts).
    """
    kinds = [program.blocks[b].kind if 0 <= b < len(program.blocks) else "line" for b in path.blocks]
    inc = np.array([k != "rapid" for k in kinds], dtype=bool)
    return inc if inc.any() else None


def contour_metrics(capture: Any, *, include_segments: np.ndarray | None = None) -> dict[str, float] | None:
    """The ``contour`` entry of the ``vcnc simulate`` summary: ``{"max_um", "rms_um"}``.

    Parameters
    ----------
    capture : vcnc.Capture
        With ``path`` (the programmed geometry) and ``reference``/``measured``.
    include_segments : ndarray of bool, optional
        Segments the metrics cover (see :func:`contour_error`).

    Returns
    -------
    dict or None
        None when fewer than two of x, y, z move (a contour needs two axes) or the capture has
        no path.
    """
    if getattr(capture, "path", None) is None or len(moving_axes(capture.reference, capture.axes)) < 2:
        return None
    ce = contour_error(capture.path, capture.measured, capture.axes, reference=capture.reference,
                       t=capture.t, include_segments=include_segments)
    m = error_metrics(ce.error[ce.covered()])  # the corners and quadrants of ce.metrics() are not asked for
    return {"max_um": m["max_um"], "rms_um": m["rms_um"]}
