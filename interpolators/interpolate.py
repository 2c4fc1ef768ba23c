"""From a program to sampled setpoints: path, feed profile, sampling."""

from __future__ import annotations

import dataclasses
import logging
import math
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from interpolators.axis_blends import (
    CHECK_SHARES,
    corner_positions,
    excess,
    hermite_axes,
    hermite_bounds,
    ramp_half_length,
)
from interpolators.dense import MergedRun, fit_axes, merge_dense_runs
from interpolators.kinematics import (
    CURVE_BOUND_MARGIN,
    JERK_SPEED_SHARE,
    AxisLimitArrays,
    curvature_step_speed_limit,
    curve_limits,
    curved_speed_bound,
    extra_curve_bounds,
    extra_junction_speed_limit,
    extra_path_bounds,
    junction_speed_limit,
    line_limits,
    path_limits,
)
from interpolators.limits import DEFAULT_LIMITS, DEFAULT_ROTARY_LIMITS, DEFAULT_SECONDARY_LIMITS, AxisLimits
from interpolators.lookahead import DEFAULT_TOLERANCE, JUNCTION_SHARE, CornerBlends, blend_corners, junction_speeds
from interpolators.profiles import PROFILES, phase_clock, phase_states, reach_many, scurve_phases, trapezoid_phases
from interpolators.program import Program
from toolpaths.geometry import AXIS_LETTERS, Arc, Line, Path, SplineCurve, piece_of, rows_by_owner
from toolpaths.packed import HOLD, PackedSegments
from vcnc.core.axes import AXIS_NAMES, EXTRA_NAMES
from vcnc.core.errors import InputError, ProgramTooLongError
from vcnc.core.setpoints import Setpoints

__all__ = ["interpolate", "MAX_SAMPLES"]

log = logging.getLogger(__name__)

#: Junctions whose geometric speed bound is below this share of the neighbouring segments' speed
#: bounds are exact stops (passing them barely moving is not worth the acceleration reserve).
MIN_JUNCTION_SPEED_SHARE: float = 0.1

#: Share of the axis limits below which a junction's discontinuity counts as continuous: chains
#: whose junctions are all below it (G2 blends, tangent steps at rounding level) plan with the full
#: limits instead of reserving JUNCTION_SHARE.
NEGLIGIBLE_SHARE: float = 1e-7

#: Largest distance [mm] of the polyline that stands for a smooth curve (a merged run of dense
#: lines) in ``Setpoints.path`` from the curve: points ``sqrt(8 CURVE_PATH_ERROR / k_max)`` apart.
CURVE_PATH_ERROR: float = 1e-4

#: Points per merged-run piece at which the axes beyond X, Y, Z are placed along it and their derivatives bounded.
_ARC_TABLE: int = 32

#: Default bound on the number of samples ``interpolate`` produces (guards memory).
MAX_SAMPLES: int = 50_000_000

#: Samples evaluated at once: the temporaries of one chunk (phase states, per-segment geometry, about 250 B per
#: sample) stay about 35 MB, whatever the program's length; only the setpoints themselves grow with it.
SAMPLE_CHUNK: int = 1 << 17


class _Items:
    """The items the planner takes (one per block that takes time), in program order: one flat list per field, of
    which each chain is a range (a program of a million exact-stop blocks has a million chains: lists of their
    own would cost about half a kB per chain)."""

    __slots__ = ("segments", "blocks", "feeds", "rapid", "tolerances")

    def __init__(self) -> None:
        self.segments: list[Line | Arc | np.ndarray] = []  # an array: a hold (dwell, or X Y Z still)
        self.blocks: list[int] = []
        self.feeds: list[float] = []
        self.rapid: list[bool] = []
        self.tolerances: list[float] = []


class _Chain:
    """Consecutive items planned together, starting and ending at rest: the items ``lo`` to ``hi`` (excluded)
    of ``items``; their fields as lists by the properties of the same names."""

    __slots__ = ("items", "lo", "hi", "dwell", "extra")

    def __init__(self, items: _Items) -> None:
        self.items = items
        self.lo = self.hi = len(items.segments)
        self.dwell = 0.0  # > 0: a dwell chain (one hold segment)
        self.extra = False  # blocks moving an axis beyond X, Y, Z and feed moves keeping them still: _extra_block

    @classmethod
    def of(cls, segments: list, blocks: list[int], feeds: list[float], rapid: list[bool],
           tolerances: list[float]) -> _Chain:
        """A chain of these items, in items of its own."""
        items = _Items()
        items.segments, items.blocks, items.feeds, items.rapid, items.tolerances = (
            segments, blocks, feeds, rapid, tolerances)
        ch = cls(items)
        ch.lo, ch.hi = 0, len(segments)
        return ch

    def add(self, segment: Line | Arc | np.ndarray, block: int, feed: float, rapid: bool, tolerance: float) -> None:
        """Append an item: the chain is the last one of its items."""
        it = self.items
        it.segments.append(segment)
        it.blocks.append(block)
        it.feeds.append(feed)
        it.rapid.append(rapid)
        it.tolerances.append(tolerance)
        self.hi += 1

    @property
    def segments(self) -> list:
        return self.items.segments[self.lo:self.hi]

    @property
    def blocks(self) -> list[int]:
        return self.items.blocks[self.lo:self.hi]

    @property
    def feeds(self) -> list[float]:
        return self.items.feeds[self.lo:self.hi]

    @property
    def rapid(self) -> list[bool]:
        return self.items.rapid[self.lo:self.hi]

    @property
    def tolerances(self) -> list[float]:
        """The path tolerance of each item (its block's; a dwell's is never used)."""
        return self.items.tolerances[self.lo:self.hi]

    @property
    def junction_tolerances(self) -> list[float]:
        """The path tolerance of the junction after each item: the smaller of its two items' (a program that
        changes G64 P between two moves blends their corner within both: LinuxCNC's ``tcFindBlendTolerance``,
        src/emc/tp/tc.c, takes ``fmin(T1, T2)`` of the two segments, "in case it dropped between moves"); the
        last item's own."""
        t = self.tolerances
        return [min(a, b) for a, b in zip(t, t[1:])] + t[-1:]


def _chains(program: Program) -> list[_Chain]:
    items = _Items()
    chains: list[_Chain] = []
    cur: _Chain | None = None
    for i, b in enumerate(program.blocks):
        if b.kind == "dwell":
            cur = None
            if b.dwell > 0:
                ch = _Chain(items)
                ch.add(b.start, i, 0.0, False, DEFAULT_TOLERANCE)
                ch.dwell = b.dwell
                chains.append(ch)
            continue
        seg = b.segment
        if b.extra_start is not None and (np.any(b.extra_delta != 0) or _joins_extra(cur, b)):
            if (cur is not None and not cur.extra and np.any(b.extra_delta != 0) and b.kind != "rapid"
                    and seg is not None and seg.length > 0):
                cur = _feeds_after_rapid(chains, cur)
                if cur is not None:  # a G64 chain of feed moves with these axes still, into a feed move of X, Y, Z
                    cur.extra = True  # that moves them too (it joins: _extra_block); a rapid or a move of these
                    # axes alone starts its own
            cur = _extra_block(chains, items, cur, i, b, program.blocks)
            continue
        if seg is None or seg.length <= 0:
            continue  # zero-length moves take no time
        if cur is None or cur.extra:
            cur = _Chain(items)
            chains.append(cur)
        cur.add(seg, i, b.feed, b.kind == "rapid", _tolerance(b))
        if b.exact_stop:
            cur = None
    return chains


def _rapid_feed_stops(stop: bool, before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """Which junctions, between moves ``before`` and ``after`` (each a rapid or not, one entry per junction), are
    stops because the control stops where a rapid meets a feed move (``stop``: ``Program.rapid_feed_stop``, the
    dialect's :attr:`interpolators.context.Dialect.rapid_feed_stop`: LinuxCNC's ``handleModeChange``, Fanuc's and
    Haas' G00 with its in-position check; grbl and the TNC pass that junction at speed, bounded as any other).
    Whatever the path mode: under G64 such a junction is neither blended (:func:`_blend_worth`) nor passed at speed
    (:func:`_corner_stops` splits the chain there), as under G61. The rapid and the feed move stay one chain until
    then, so that the corners of a program of short rapids and feed moves are blended chain by chain as before
    (a chain per move costs its own look-ahead pass: twice the interpolation time of such programs). The chains of
    the axes beyond X, Y, Z stop there under every control (:func:`_extra_block`)."""
    before, after = np.asarray(before, dtype=bool), np.asarray(after, dtype=bool)
    return before != after if stop else np.zeros(before.shape, dtype=bool)


def _feeds_after_rapid(chains: list[_Chain], cur: _Chain) -> _Chain | None:
    """The chain of the feed moves of ``cur`` (the last of ``chains``) after its last rapid, split off it as a chain
    of its own (the last of ``chains``), for a feed move that moves the axes beyond X, Y, Z to join; ``cur`` itself
    without a rapid; None where ``cur`` ends in a rapid (the feed move starts a chain of its own). A chain that
    moves those axes takes no rapid beside a feed move (:func:`_extra_block`), so before session 34 a feed move
    starting A after ``G0 .. G1 ..`` (an approach, a plunge, the contour's first lines) stopped where A started,
    whatever its rate step, and only such a junction inside the chain passed at speed (a ramp of A,
    :func:`_ramped_extra`, or its blend). The junction of the rapid and the first feed move is now a stop instead:
    the feed move's speed is its bound there, and the rapid decelerates to it either way."""
    rapid = cur.rapid
    if not any(rapid):
        return cur
    last = len(rapid) - 1 - rapid[::-1].index(True)
    if last == len(rapid) - 1:
        return None
    tail = _Chain(cur.items)
    tail.lo, tail.hi = cur.lo + last + 1, cur.hi
    cur.hi = tail.lo
    chains.append(tail)
    return tail


def _joins_extra(cur: _Chain | None, b) -> bool:
    """Whether a feed move of X, Y, Z that keeps the axes beyond them still continues the chain ``cur`` that moves
    them (G64, no rapid before it): its junctions are passed at speed with those axes starting or stopping (their
    rate per mm of path steps from or to 0, bounded as any rate step: :func:`_extra_block`). 4-axis CAM output puts
    a rotary word on some blocks only, and a stop wherever A starts or stops cost more than the axis' limits ask."""
    seg = b.segment
    return (cur is not None and cur.extra and b.kind != "rapid" and seg is not None and seg.length > 0
            and not cur.items.rapid[cur.hi - 1])


def _extra_block(chains: list[_Chain], items: _Items, cur: _Chain | None, i: int, b, blocks: Sequence
                 ) -> _Chain | None:
    """Add a block that moves an axis beyond X, Y, Z; returns the chain the next block may join.

    A feed move with X, Y or Z moving joins the chain of the previous such block when that one
    did not end in exact stop (G64) and was no rapid: look-ahead passes their junction at speed, bounded for
    every axis (:func:`interpolators.kinematics.extra_junction_speed_limit`); their runs of dense short lines are
    merged, X, Y, Z and the other axes together (:func:`_merged_extra`), and their line/line corners blended
    across every axis (:func:`_blended_extra`). A rapid joins only the rapid before it from
    the same source line that did not end in exact stop: the chords of one rapid under tool centre point
    control (:func:`interpolators.tcp.tcp_chords`), which is one move of the control, not one per chord. A feed
    move of X, Y, Z keeping these axes still joins such a chain too (:func:`_joins_extra`), and a G64 chain of
    feed moves turns into one where they start moving.
    Any other such block (a rapid, a move with X, Y, Z still: a hold at its XYZ position whose profile runs
    along ``Block.extra_length``) is a chain of its own, at rest at both ends.
    """
    seg = b.segment
    moves_xyz = seg is not None and seg.length > 0
    rapid = b.kind == "rapid"
    after_rapid = cur is not None and cur.extra and items.rapid[cur.hi - 1]
    if rapid:
        joins = moves_xyz and after_rapid and blocks[items.blocks[cur.hi - 1]].line == b.line
    else:
        joins = moves_xyz and not after_rapid
    if not (joins and cur is not None and cur.extra):
        cur = _Chain(items)
        cur.extra = True
        chains.append(cur)
    cur.add(seg if moves_xyz else b.start, i, b.feed, rapid, _tolerance(b))
    return cur if moves_xyz and not b.exact_stop else None


def _resolve_limits(limits: Mapping[str, AxisLimits] | None) -> dict[str, AxisLimits]:
    if limits is None:
        return {**DEFAULT_LIMITS, **DEFAULT_ROTARY_LIMITS, **DEFAULT_SECONDARY_LIMITS}
    if not isinstance(limits, Mapping):
        raise InputError(f"limits must be a dict of axis name -> AxisLimits, got {type(limits).__name__}")
    return {str(k).lower(): v for k, v in limits.items()}


def interpolate(
    program: Program,
    *,
    limits: Mapping[str, AxisLimits] | None = None,
    sample_time: float = 1e-3,
    profile: str = "trapezoid",
    max_samples: int = MAX_SAMPLES,
) -> Setpoints:
    """Interpolate a program into setpoints sampled every ``sample_time``.

    Parameters
    ----------
    program : Program
        From :func:`interpolators.parse_program` / :func:`interpolators.load_program`.
    limits : dict of str to AxisLimits, optional
        Per-axis limits (velocity [mm/s], acceleration [mm/s^2], jerk [mm/s^3], rapid [mm/s];
        rotary axes a, b, c in deg); :data:`interpolators.DEFAULT_LIMITS`,
        :data:`interpolators.DEFAULT_ROTARY_LIMITS` and :data:`interpolators.DEFAULT_SECONDARY_LIMITS`
        when omitted. Every axis the program moves needs an entry.
    sample_time : float
        Interpolation period Ts [s] (default 1 ms).
    profile : {"trapezoid", "scurve"}
        Trapezoidal (velocity and acceleration limited, closed form) or S-curve (also jerk
        limited; profiles computed by ruckig).
    max_samples : int
        Refuse programs that would need more samples than this (memory guard).

    Returns
    -------
    Setpoints
        Axes ``program.axes``; ``block`` indexes ``program.blocks``; ``path`` is the geometry the
        samples follow (a :class:`toolpaths.Path`: the programmed one, with blends at G64 corners:
        tangent arcs for the trapezoid, curvature-continuous clothoid pairs
        (:class:`toolpaths.geometry.ClothoidPair`) for the S-curve and for corners outside the
        principal planes); ``meta`` records ``source``, ``profile``, ``dialect``, ``sample_time``,
        ``duration`` and, when corners were blended, ``programmed_path``.

    Notes
    -----
    * Every chain of blocks between two stops (each block under G61, the default) starts and
      ends at rest. Its duration is rounded up to a whole number of samples by slowing it down
      uniformly (speeds scale by ``T/T'``, accelerations by its square, jerks by its cube), so
      every stop, and every exact-stop block end point, falls exactly on a sample.
    * G00 / F MAX is a straight line at the largest speed that keeps every moving axis at or
      below its rapid rate.
    * Programmed feeds above the axes' velocity limits are clamped to them; on arcs the speed is
      further capped so that the centripetal acceleration (and, for the S-curve, jerk) fits the
      axis limits (see :mod:`interpolators.kinematics`).
    * Dwells are rounded up to whole samples.
    * The axes beyond X, Y, Z (``Block.extra_start``/``extra_target``: rotary a, b, c [deg],
      secondary linear u, v, w [mm]) move in proportion to the path: with X, Y or Z moving the
      profile runs along the XYZ path at its feed; with X, Y, Z still along the U V W distance at
      the feed [mm/s], or with U, V, W still too along the rotary distance at the feed [deg/s]
      (RS274/NGC 3, Sec. 2.1.2.5; ``Block.extra_length``). The path bounds are capped so that each
      of these axes keeps its limits (:func:`interpolators.kinematics.extra_path_bounds`). Under G64 consecutive feed
      moves of X/Y/Z with these axes are passed at speed where every axis' velocity step fits in one sample
      (:func:`interpolators.kinematics.extra_junction_speed_limit`, see ``_extra_block``; dense runs merged with the
      other axes, :func:`interpolators.dense.fit_axes`; line/line corners, S-curve also line/arc kinks and curvature
      steps, blended with every axis on a quintic, :mod:`interpolators.axis_blends`); the chords of one TCP rapid
      likewise; other blocks moving them start and end at rest. Setpoint columns ``a, b, c`` in deg, ``u, v, w`` in mm.
    * G64: line/line corners are blended within the tolerance ``P`` when passing the blend is
      faster than stopping (a model of both, see ``_blend_worth``; sharp corners stay stops).
      Chains whose junctions are all continuous (blends, rounding-level steps; see
      :data:`NEGLIGIBLE_SHARE`) plan with the full axis limits; chains that pass a discontinuity
      at speed reserve :data:`interpolators.lookahead.JUNCTION_SHARE` of them for it. S-curve: kinks beside arcs and
      merged curves, and tangent junctions with a curvature step, are blended within ``P`` by a G2 quintic where that
      pays (:func:`interpolators.lookahead.blend_corners`); a tangent curvature jump left unblended is passed where each
      axis' acceleration step fits in one sample (:func:`interpolators.kinematics.curvature_step_speed_limit`).
    * G64, dense code: runs of short lines (CAM output) are merged into one smooth curve within
      the tolerance (:mod:`interpolators.dense`; under the S-curve also the chords of tight curves,
      :func:`interpolators.dense.curve_junctions`), planned with the curve's curvature bounds; the
      samples on it carry the block of the chord they pass, and ``path`` holds the curve as a fine
      polyline (within :data:`CURVE_PATH_ERROR`).

    Raises
    ------
    vcnc.InputError
        Bad limits, sample time or profile name, or missing limits for a moving axis.
    vcnc.ProgramTooLongError
        A program that would need more than ``max_samples`` samples.
    """
    if profile not in PROFILES:
        raise InputError(f"unknown profile {profile!r}", expected=" or ".join(PROFILES))
    if not (isinstance(sample_time, (int, float)) and math.isfinite(sample_time) and sample_time > 0):
        raise InputError(f"sample_time must be a finite value > 0 s, got {sample_time!r}")
    if not isinstance(program, Program):
        raise InputError(f"program must be a Program (see parse_program), got {type(program).__name__}")
    Ts = float(sample_time)
    jerk_limited = profile == "scurve"
    chains = _chains(program)
    lim = _axis_limits(chains, limits, jerk_limited)
    every = _resolve_limits(limits)
    g = _geometry(chains, lim, jerk_limited, program, Ts, every)
    c = _corner_stops(g, chains, lim, Ts, jerk_limited, every, rapid_feed_stop=program.rapid_feed_stop)
    del chains  # the rest works on the packed geometry: the chains' items are not kept through the sampling
    v_max, a_max, j_max, v0, v1 = _faster_jerk_share(g, c, lim, _path_bounds(g, c, lim, jerk_limited), jerk_limited,
                                                     every)
    ph, total_N = _phases(g, c, v0, v1, v_max, a_max, j_max, Ts, jerk_limited, program, max_samples)
    return _sample(program, g, ph, total_N, Ts, profile)


@dataclasses.dataclass
class _Extra:
    """The axes a, b, c, u, v, w along the segments: ``start + (s / length) * delta`` at path
    parameter ``s``; a move with X, Y, Z still is a hold whose path is ``Block.extra_length``."""

    start: np.ndarray  # (n_seg, 6) [deg, mm]
    delta: np.ndarray  # (n_seg, 6) [deg, mm]
    length: np.ndarray  # (n_seg,) path length of the profile [mm, or deg on a pure rotary move]
    pure: np.ndarray  # (n_seg,) bool: X, Y, Z still, the profile runs along Block.extra_length
    fits: dict = dataclasses.field(default_factory=dict)  # curve piece -> (axes spline r(S), S at its start)


@dataclasses.dataclass
class _Geom:
    """Step 1: the chains' segments (G64 corners blended), packed, with their block, chain, feed."""

    segments: list
    block: list[int]
    chain: np.ndarray
    feed: np.ndarray
    rapid: np.ndarray
    packed: PackedSegments
    blended: bool
    runs: dict[int, MergedRun]  # segment index -> the dense run its SplineCurve piece belongs to
    fits: dict  # segment index -> (spline of the axes beyond X, Y, Z along its run, arc length at its start)
    extra: _Extra | None = None  # None: the program moves no axis beyond X, Y, Z

    @property
    def profile_length(self) -> np.ndarray:
        """Length each segment's profile runs along [mm; deg on a pure rotary move]."""
        return self.packed.length if self.extra is None else self.extra.length


@dataclasses.dataclass
class _Chains:
    """Step 2: the chains after splitting at corners that must be stops."""

    of_segment: np.ndarray
    count: int
    dwell: np.ndarray
    length: np.ndarray
    reserved_segment: np.ndarray  # segments of chains that pass a discontinuity at speed
    inner: np.ndarray  # junctions passed at speed (index of the segment before)
    junction_limit: np.ndarray


def _axis_limits(chains: list[_Chain], limits: Mapping[str, AxisLimits] | None,
                 jerk_limited: bool) -> AxisLimitArrays:
    """The limits of the axes the chains move (finite jerks for the S-curve)."""
    # the chains of _chains are ranges of one _Items: its segments are all of theirs, in order
    segs = [seg for seg in (chains[0].items.segments if chains else ()) if isinstance(seg, (Line, Arc))]
    ends = np.array([(seg.start, seg.end) for seg in segs]).reshape(-1, 2, 3)
    moving = {int(i) for i in np.flatnonzero(np.any(ends[:, 1] != ends[:, 0], axis=0))}
    moving.update(i for seg in segs if isinstance(seg, Arc) for i in seg.plane_axes)
    lim = AxisLimitArrays(_resolve_limits(limits), moving)
    if jerk_limited:
        bad = [AXIS_LETTERS[i] for i in sorted(moving) if not math.isfinite(lim.jerk[i])]
        if bad:
            raise InputError(f"the S-curve profile needs finite jerk limits; axis {', '.join(bad)} has none")
    return lim


def _geometry(chains: list[_Chain], lim: AxisLimitArrays, jerk_limited: bool, program: Program, Ts: float,
              limits: Mapping[str, AxisLimits]) -> _Geom:
    """1. The geometry of each chain, its G64 corners blended (``Ts``: the sample time the kinks' junction bounds
    are judged at, :func:`_blend_worth`; ``limits``: every axis', for the blends of the axes beyond X, Y, Z)."""
    all_segs: list[Line | Arc | np.ndarray] = []
    seg_block: list[int] = []
    chain_len: list[int] = []  # segments of each chain, blended
    seg_feed: list[float] = []
    seg_rapid: list[bool] = []
    blended = False
    runs: dict[int, MergedRun] = {}
    fits: dict = {}
    for ch in chains:
        fit_of: dict = {}
        if ch.extra and ch.hi - ch.lo > 1:
            merged, run_of, fit_of = _merged_extra(ch, jerk_limited, program)
            segs, blks, fit_of = _blended_extra(merged, fit_of, lim, limits, jerk_limited, Ts, program)
            segs, blks, fit_of = _ramped_extra(segs, blks, fit_of, program,
                                               worth=_ramp_worth(merged, lim, limits, jerk_limited, Ts))
        if not fit_of and (ch.hi - ch.lo == 1 or ch.extra):  # no corner to blend: the chain's own items
            it, lo, hi = ch.items, ch.lo, ch.hi
            all_segs += it.segments[lo:hi]
            seg_block += it.blocks[lo:hi]
            seg_feed += it.feeds[lo:hi]
            seg_rapid += it.rapid[lo:hi]
            chain_len.append(hi - lo)
            continue
        if fit_of:  # a chain moving the axes beyond X, Y, Z: its runs merged, its line/line corners blended
            ch = merged
        else:
            ch, run_of = _merged(ch, jerk_limited)
            segs, blks = blend_corners(ch.segments, ch.blocks, ch.junction_tolerances,
                                       worth=_blend_worth(ch, lim, jerk_limited, Ts,
                                                          rapid_feed_stop=program.rapid_feed_stop),
                                       curvature_continuous=jerk_limited,
                                       kink_limits=(float(np.min(lim.acceleration)), float(np.min(lim.jerk))),
                                       offsets=[run_of[id(s)].deviation if id(s) in run_of else 0.0
                                                for s in ch.segments])
        blended = blended or len(segs) != len(ch.segments) or bool(run_of)
        feed_of = dict(zip(ch.blocks, ch.feeds))
        rapid_of = dict(zip(ch.blocks, ch.rapid))
        run_of_spline = {id(r.pieces[0].spline): r for r in run_of.values()}
        for j, (s, b) in enumerate(zip(segs, blks)):
            feed, rapid = feed_of[b], rapid_of[b]
            if id(s) in fit_of:
                fits[len(all_segs)] = fit_of[id(s)]
            if id(s) in run_of:
                runs[len(all_segs)] = run_of[id(s)]
            elif isinstance(s, SplineCurve):  # a piece cut by a kink blend (of its run), or the blend
                run = run_of_spline.get(id(s.spline))
                if run is None:  # the blend, always between two segments (a cut piece may end the chain)
                    nxt = segs[j + 1]
                    run = _blend_run(
                        _chords_beside(all_segs[-1], b, runs.get(len(all_segs) - 1), at_start=False),
                        _chords_beside(nxt, blks[j + 1], run_of_spline.get(id(getattr(nxt, "spline", None))),
                                       at_start=True), s)
                    # its second half carries the outgoing block: neither block's feed is exceeded on it
                    feed, rapid = min(feed, feed_of[blks[j + 1]]), rapid and rapid_of[blks[j + 1]]
                runs[len(all_segs)] = run
            all_segs.append(s)
            seg_block.append(b)
            seg_feed.append(feed)
            seg_rapid.append(rapid)
        chain_len.append(len(segs))
    # a curve piece is packed as the chord of its end points with the curve's length; _evaluate and
    # _limits give its own geometry and bounds
    packed = PackedSegments.from_segments([Line(s.start, s.end) if isinstance(s, SplineCurve) else s
                                           for s in all_segs])
    for i in runs:
        packed.length[i] = all_segs[i].length
    seg_chain = np.repeat(np.arange(len(chains), dtype=np.int64), chain_len)
    extra = None
    if any(b.extra_start is not None for b in program.blocks):
        extra = _extra_geometry(chains, all_segs, seg_block, seg_chain, program, packed, fits)
    return _Geom(segments=all_segs, block=seg_block, chain=seg_chain,
                 feed=np.asarray(seg_feed, dtype=float), rapid=np.asarray(seg_rapid, dtype=bool),
                 packed=packed, blended=blended, runs=runs, fits=fits, extra=extra)


def _chords_beside(segment, block: int, run: MergedRun | None, *, at_start: bool) -> tuple[np.ndarray, np.ndarray]:
    """The programmed chords a kink blend replaces beside ``segment`` (of the chain block ``block``; ``at_start``:
    the blend ends where ``segment`` starts, else it starts where ``segment`` ends): their blocks, in path order,
    and the share of the replaced part (its curve parameter range between the cut and the original piece's end)
    at which each ends. A line or arc is one block; a merged curve piece (of ``run``) its chords there."""
    if run is None:
        return np.array([block]), np.array([1.0])
    cut = segment.u0 if at_start else segment.u1
    ends = np.array([p.u0 if at_start else p.u1 for p in run.pieces])
    # the original piece's end beside the blend: the nearest piece break beyond the cut
    beyond = ends[ends < cut] if at_start else ends[ends > cut]
    end = (beyond.max() if at_start else beyond.min()) if len(beyond) else cut
    lo, hi = min(cut, end), max(cut, end)
    inner = run.vertex_u[(run.vertex_u > lo) & (run.vertex_u < hi)]
    edges = np.concatenate([[lo], inner, [hi]])
    blocks = run.block_at(0.5 * (edges[:-1] + edges[1:]))
    return blocks, ((edges[1:] - lo) / (hi - lo) if hi > lo else np.ones(len(blocks)))


def _blend_run(before: tuple[np.ndarray, np.ndarray], after: tuple[np.ndarray, np.ndarray],
               blend: SplineCurve) -> MergedRun:
    """A kink blend as a run of one piece whose samples carry the blocks of the programmed chords it replaces:
    ``before`` (the incoming segment's, :func:`_chords_beside`) over the first half of its parameter range,
    ``after`` (the outgoing one's) over the second, each in proportion to the replaced length, as the samples of
    a merged curve carry the chord they pass; so each sample lies near its block's programmed segment
    (:func:`interpolators.lookahead.blend_corners` gives the blend the incoming block)."""
    mid = 0.5 * (blend.u0 + blend.u1)
    first = blend.u0 + (mid - blend.u0) * before[1][:-1]
    second = mid + (blend.u1 - mid) * after[1][:-1]
    return MergedRun(pieces=(blend,), vertex_u=np.concatenate([[blend.u0], first, [mid], second, [blend.u1]]),
                     blocks=np.concatenate([before[0], after[0]]).astype(np.int64))


def _extra_geometry(chains: list[_Chain], segments: list, seg_block: list[int], seg_chain: np.ndarray,
                    program: Program, packed: PackedSegments, fits: dict) -> _Extra:
    """Start and motion of the axes beyond X, Y, Z on each segment; only an extra chain's segments
    (one per block, or the pieces of a merged run, ``fits``: their values at the ends) move them."""
    n = len(seg_block)
    start = np.zeros((n, len(EXTRA_NAMES)))
    delta = np.zeros((n, len(EXTRA_NAMES)))
    length = np.array(packed.length, dtype=float)
    pure = np.zeros(n, dtype=bool)
    for k, (b, c) in enumerate(zip(seg_block, seg_chain.tolist())):
        blk = program.blocks[b]
        if blk.extra_start is not None:
            start[k] = blk.extra_start
        if chains[c].extra and isinstance(segments[k], Line) and segments[k] is not blk.segment:
            value, rate = _on_line([blk], np.asarray(segments[k].start)[None])  # a line shortened by corner blends
            start[k], delta[k] = value[0], rate[0] * segments[k].length
        elif chains[c].extra:
            delta[k] = blk.extra_delta
            if packed.kind[k] == HOLD:
                pure[k] = True
                length[k] = blk.extra_length
    for k, (spl, s0) in fits.items():
        still = np.all(spl.c == spl.c[0], axis=0)  # an axis the run keeps still stays exact
        start[k] = np.where(still, spl.c[0], spl(s0))
        delta[k] = np.where(still, 0.0, spl(s0 + length[k]) - start[k])
    return _Extra(start=start, delta=delta, length=length, pure=pure, fits=fits)


def _extra_bounds(g: _Geom, c: _Chains, v_max: np.ndarray, a_max: np.ndarray, j_max: np.ndarray,
                  limits: Mapping[str, AxisLimits], jerk_limited: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """3b. The path bounds of segments that move the axes beyond X, Y, Z, capped so that each stays
    within its limits (chains passing a junction at speed keep JUNCTION_SHARE of the acceleration
    and jerk limits in reserve, as for X, Y, Z); with X, Y, Z still the speed is the feed along
    ``Block.extra_length`` [mm/s or deg/s] (RS274/NGC 3, Sec. 2.1.2.5) or, for a rapid, the axes'
    rapid rates."""
    r = g.extra
    fitted = np.array(sorted(r.fits), dtype=np.int64)
    moving = np.any(r.delta != 0, axis=1)
    moving[fitted] = False
    idx = np.flatnonzero(moving)
    v_max, a_max, j_max = v_max.copy(), a_max.copy(), j_max.copy()
    if len(fitted):
        share = np.where(c.reserved_segment[fitted], 1.0 - JUNCTION_SHARE, 1.0)
        v, a, j = extra_curve_bounds(*_fit_derivatives(r.fits, fitted, r.length), v_max[fitted], limits,
                                     share=share, jerk_limited=jerk_limited)
        v_max[fitted], a_max[fitted], j_max[fitted] = v, np.minimum(a_max[fitted], a), np.minimum(j_max[fitted], j)
    if not len(idx):
        return v_max, a_max, j_max
    ratio = np.abs(r.delta[idx]) / r.length[idx, None]
    v, a, j = extra_path_bounds(ratio, g.rapid[idx], limits)
    share = np.where(c.reserved_segment[idx], 1.0 - JUNCTION_SHARE, 1.0)  # the bounds scale with A and J
    a, j = a * share, j * share
    pure = r.pure[idx]
    feed = np.where(g.rapid[idx], np.inf, g.feed[idx])
    v_max[idx] = np.where(pure, np.minimum(feed, v), np.minimum(v_max[idx], v))
    a_max[idx] = np.where(pure, a, np.minimum(a_max[idx], a))
    j_max[idx] = np.where(pure, j, np.minimum(j_max[idx], j))
    if not np.all(np.isfinite(v_max[idx])):
        raise InputError("a rapid of the axes beyond X, Y, Z needs a finite rapid rate on its axes")
    if jerk_limited and not np.all(np.isfinite(j_max[idx])):
        raise InputError("the S-curve profile needs finite jerk limits on the A-W axes the program moves")
    return v_max, a_max, j_max


def _merged_extra(ch: _Chain, jerk_limited: bool, program: Program) -> tuple[_Chain, dict[int, MergedRun], dict]:
    """A chain moving the axes beyond X, Y, Z with its runs of dense short lines merged (:func:`_merged`) and,
    for each curve piece (by ``id``), the spline those axes follow along its run and the run's arc length at the
    piece's start (:func:`interpolators.dense.fit_axes`, within the run's tolerance in each axis' unit). A run
    whose axes fit no spline keeps its chords (:func:`_restore_runs`), the others stay merged, and so does a run of
    chords under tool centre point control (``Block.tcp``: X, Y, Z follow the tip through the rotary axes, a fit
    of those apart would move the tip off the tolerance by the pivot distance); the chain as it was (no runs, no
    fits) when none is left."""
    merged, run_of = _merged_between_starts(ch, jerk_limited, program)
    fit_of: dict = {}
    failed: set[int] = set()
    for run in {id(r): r for r in run_of.values()}.values():
        s, s0 = _vertex_arc_lengths(run)
        blocks = [program.blocks[b] for b in run.blocks.tolist()]
        if any(b.tcp for b in blocks):
            failed.add(id(run))
            continue
        values = np.array([blocks[0].extra_start, *(b.extra_target for b in blocks)], dtype=float)
        tol = DEFAULT_TOLERANCE if blocks[0].tolerance is None else blocks[0].tolerance
        spl = fit_axes(s, values, tol)
        if spl is None:
            failed.add(id(run))
            continue
        fit_of.update((id(p), (spl, float(x))) for p, x in zip(run.pieces, s0))
    if not fit_of:
        return ch, {}, {}
    if failed:
        merged, run_of = _restore_runs(ch, merged, run_of, failed)
    return merged, run_of, fit_of


def _merged_between_starts(ch: _Chain, jerk_limited: bool, program: Program) -> tuple[_Chain, dict[int, MergedRun]]:
    """:func:`_merged` (``unblended``) of a chain moving the axes beyond X, Y, Z, each stretch between two junctions
    where they start or stop (every one still on one side, :func:`_joins_extra`) merged apart: a staircase of those
    axes along a run (A moving on every tenth chord) fits no spline within ``P`` and would keep all its chords, while
    the stretches fit one each and the junctions between them pass at their rate steps' bound."""
    moving = [bool(np.any(program.blocks[b].extra_delta != 0)) for b in ch.blocks]
    cuts = [0, *(i for i in range(1, len(moving)) if moving[i] != moving[i - 1]), len(moving)]
    if len(cuts) == 2:
        return _merged(ch, jerk_limited, unblended=True)
    out, run_of = _Chain.of([], [], [], [], []), {}
    for lo, hi in zip(cuts, cuts[1:]):
        part, runs = _merged(_Chain.of(ch.segments[lo:hi], ch.blocks[lo:hi], ch.feeds[lo:hi], ch.rapid[lo:hi],
                                       ch.tolerances[lo:hi]), jerk_limited, unblended=True)
        for k in range(part.hi - part.lo):
            out.add(part.segments[k], part.blocks[k], part.feeds[k], part.rapid[k], part.tolerances[k])
        run_of.update(runs)
    return out, run_of


def _blended_extra(ch: _Chain, fit_of: dict, lim: AxisLimitArrays, limits: Mapping[str, AxisLimits],
                   jerk_limited: bool, Ts: float, program: Program) -> tuple[list, list[int], dict]:
    """The segments and blocks of a chain moving the axes beyond X, Y, Z (``ch``, its runs merged, ``fit_of`` their
    axis splines, :func:`_merged_extra`) with its corners blended as in a chain of X, Y, Z
    (:func:`interpolators.lookahead.blend_corners`: line/line corners, and under the S-curve the kinks and tangent
    curvature steps between lines and arcs, not those beside a merged curve), and ``fit_of`` with the axes' splines
    along each blend and each arc piece a kink blend leaves (:mod:`interpolators.axis_blends`, one spline for all,
    each blend's arc length from its offset; :func:`_with_cut_arcs`; a shortened line's are
    :func:`_extra_geometry`'s, by :func:`_on_line`). Before session 33 the kinks were left to the one-sample rule
    here: a contour after one move with A ran slower than alone, and at 0.25 ms every tangent line/arc junction of a
    chain moving A was a stop (our reading of G64 P for these axes as for line/line corners,
    :mod:`interpolators.axis_blends`). A blend whose
    axes leave the tolerance is made again within the tolerance scaled down by the excess, then dropped; corners
    beside a rapid or a chord under tool centre point control are not blended (its tip would leave ``P``, as
    :func:`_merged_extra`). Without a blend, the chain's own segments and ``fit_of``."""
    segments, blocks = ch.segments, ch.blocks
    allowed = np.array(ch.junction_tolerances, dtype=float)
    tol = allowed.copy()  # the XYZ tolerance each corner is blended within
    kept = np.array([program.blocks[b].tcp for b in blocks], dtype=bool) | np.array(ch.rapid, dtype=bool)
    tol[:-1][kept[:-1] | kept[1:]] = 0.0
    plain = [isinstance(sg, Line) or (isinstance(sg, Arc) and abs(sg.sweep) <= 2.0 * math.pi) for sg in segments]
    kinks = [plain[k] and plain[k + 1] for k in range(len(segments) - 1)]  # not beside a merged curve
    corner_of = {b: k for k, (sg, b) in enumerate(zip(segments, blocks)) if plain[k]}
    blk = program.blocks

    def ends(blends: list, corners: list[int]) -> tuple[np.ndarray, ...]:  # the axes at the blends' ends
        r0, m0 = _on_line([blk[blocks[k]] for k in corners], np.array([b.start for b in blends]).reshape(-1, 3),
                          near_end=True)
        r1, m1 = _on_line([blk[blocks[k + 1]] for k in corners], np.array([b.end for b in blends]).reshape(-1, 3))
        return np.array([b.length for b in blends], dtype=float), r0, r1, m0, m1

    def cap(blends: CornerBlends) -> np.ndarray:  # the blends' speed bound from those axes' limits
        d1, d2, d3 = hermite_bounds(*ends(blends.blends, blends.corner.tolist()))
        n = len(d1)
        return extra_curve_bounds(d1, d2, d3, np.full(n, np.inf), limits, share=np.full(n, 1.0 - JUNCTION_SHARE),
                                  jerk_limited=jerk_limited)[0]

    worth = _blend_worth(ch, lim, jerk_limited, Ts, cap, rapid_feed_stop=program.rapid_feed_stop)
    for attempt in range(3):
        segs, blks = blend_corners(segments, blocks, tol.tolist(), worth=worth, curvature_continuous=jerk_limited,
                                   kink_limits=(float(np.min(lim.acceleration)), float(np.min(lim.jerk))),
                                   kinks=kinks)
        if len(segs) == len(segments) and all(a is b for a, b in zip(segs, segments)):
            return segments, blocks, fit_of
        original = {id(sg) for sg in segments}
        new = [(sg, b) for sg, b in zip(segs, blks) if id(sg) not in original and not isinstance(sg, Line)]
        # the blends, and the pieces kink blends cut of a block's arc (a line/line blend belongs to a line)
        cut = [(sg, b) for sg, b in new if isinstance(sg, Arc) and isinstance(blk[b].segment, Arc)]
        made = [(sg, corner_of[b]) for sg, b in new if not (isinstance(sg, Arc) and isinstance(blk[b].segment, Arc))]
        corners = [k for _, k in made]
        args = ends([sg for sg, _ in made], corners)
        points = _points_at_shares([sg for sg, _ in made])
        sides = [np.array([_corner_direction(segments[k + j], at) for k in corners]).reshape(-1, 3)
                 for j, at in ((0, "end"), (1, "start"))]
        along = corner_positions(points, np.array([segments[k].end for k in corners], dtype=float).reshape(-1, 3),
                                 *sides)  # the axes at the programmed path's point nearest the blend's
        for i, k in enumerate(corners):
            if isinstance(segments[k], Arc) or isinstance(segments[k + 1], Arc):  # beside an arc: along the arc
                along[i] = _arc_corner_positions(points[i], segments[k], segments[k + 1])
        ratio = excess(*args, np.array([blk[blocks[k]].extra_target for k in corners]), allowed[corners], along=along)
        if np.all(ratio <= 1.0):
            spl, offsets = hermite_axes(*_with_cut_arcs(args, cut, blk))  # one spline for the chain's blends
            pieces = [sg for sg, _ in made] + [sg for sg, _ in cut]
            return segs, blks, {**fit_of, **{id(sg): (spl, float(o)) for sg, o in zip(pieces, offsets)}}
        # the XYZ deviation its size gives, scaled down: the axes' excess grows as the blend's length, so does the
        # deviation of a corner blend (its middle's distance from the corner), that of a tangent junction's curvature
        # ramp (within the tolerance it was made in) as its square
        ramp = np.linalg.norm(sides[1] - sides[0], axis=1) <= _TANGENT_STEP
        for i in np.flatnonzero(ratio > 1.0).tolist():
            sg, k = made[i]
            reach = float(np.linalg.norm(sg.point_at(0.5 * sg.length) - segments[k].end))
            tol[k] = 0.0 if attempt == 1 else (0.95 * tol[k] / ratio[i] ** 2 if ramp[i] else 0.95 * reach / ratio[i])
    return segments, blocks, fit_of


def _arc_corner_positions(points: np.ndarray, before: Line | Arc, after: Line | Arc) -> np.ndarray:
    """:func:`interpolators.axis_blends.corner_positions` of the points ``points`` (c, 3) near the junction of
    ``before`` and ``after``, one of them an arc (of at most one turn): the signed path distance from the junction
    of the nearest point of either, on an arc by the angle about its centre (the tangent line there put a point
    0.89 mm along a circle of radius 1 mm at 0.78 mm)."""
    side = []
    for seg, sign in ((before, -1.0), (after, 1.0)):
        corner = np.asarray(seg.end if sign < 0 else seg.start, dtype=float)
        rel = points - corner
        if isinstance(seg, Arc):
            p, q = seg.plane_axes
            c = np.asarray(seg.center, dtype=float)
            turn = np.arctan2(points[:, q] - c[q], points[:, p] - c[p]) - math.atan2(corner[q] - c[q], corner[p] - c[p])
            turn = (turn + math.pi) % (2.0 * math.pi) - math.pi  # in (-pi, pi], positive along the arc's sense
            t = turn * math.copysign(1.0, seg.sweep) * seg.length / abs(seg.sweep)
        else:
            t = rel @ ((np.asarray(seg.end, dtype=float) - np.asarray(seg.start, dtype=float)) / seg.length)
        t = np.minimum(t, 0.0) if sign < 0 else np.maximum(t, 0.0)
        t = np.maximum(t, -seg.length) if sign < 0 else np.minimum(t, seg.length)
        nearest = seg.point_at(seg.length + t if sign < 0 else t)
        side.append((t, np.linalg.norm(points - nearest, axis=1)))
    (t_in, d_in), (t_out, d_out) = side
    return np.where(d_in <= d_out, t_in, t_out)


def _with_cut_arcs(args: tuple[np.ndarray, ...], cut: list, blk: Sequence) -> tuple[np.ndarray, ...]:
    """The arguments of :func:`interpolators.axis_blends.hermite_axes` for a chain's blends (``args``) followed by
    those of the pieces ``cut`` (arc, block) that kink blends left of the blocks' arcs: the axes along each piece
    from their programmed values at its ends, at the arc's rate (equal end rates: the straight line, the axes
    proportional to the path as programmed)."""
    if not cut:
        return args
    blocks = [blk[b] for _, b in cut]
    r0, m = _on_line(blocks, np.array([sg.start for sg, _ in cut], dtype=float).reshape(-1, 3))
    r1, _ = _on_line(blocks, np.array([sg.end for sg, _ in cut], dtype=float).reshape(-1, 3), near_end=True)
    length = np.array([sg.length for sg, _ in cut], dtype=float)
    return tuple(np.concatenate([a, b]) for a, b in zip(args, (length, r0, r1, m, m)))


def _points_at_shares(blends: list) -> np.ndarray:
    """The points of corner blends (arcs, clothoid pairs: all at once,
    :meth:`toolpaths.packed.PackedSegments.evaluate`; kink blends, :class:`toolpaths.geometry.SplineCurve`, each
    by its own) at ``CHECK_SHARES`` of their lengths, shape (m, c, 3)."""
    c = len(CHECK_SHARES)
    out = np.empty((len(blends), c, 3))
    curves = [i for i, b in enumerate(blends) if isinstance(b, SplineCurve)]
    for i in curves:
        out[i] = blends[i].point_at(CHECK_SHARES * blends[i].length)
    rest = [i for i, b in enumerate(blends) if not isinstance(b, SplineCurve)]
    if rest:
        packed = PackedSegments.from_segments([blends[i] for i in rest])
        seg = np.repeat(np.arange(len(rest), dtype=np.int64), c)
        s = (CHECK_SHARES[None, :] * np.asarray(packed.length, dtype=float)[:, None]).ravel()
        out[rest] = packed.evaluate(seg, s, np.ones(len(s)), np.zeros(len(s)))[0].reshape(len(rest), c, 3)
    return out


#: Share of a line or arc a rate-step ramp may take at each of its ends (:func:`_ramped_extra`): the rest at least
#: 10 % of it. And the share of the ramp's largest length (:func:`interpolators.axis_blends.ramp_half_length`) it takes,
#: its deviation below FIT_SHARE * P by more than the rounding of :func:`interpolators.axis_blends.excess`.
_RAMP_SHARE, _RAMP_MARGIN = 0.45, 0.95


def _ramped_extra(segs: list, blks: list[int], fit_of: dict, program: Program, *,
                  worth: Callable[[list, list[int], np.ndarray, np.ndarray, tuple], np.ndarray]
                  ) -> tuple[list, list[int], dict]:
    """The segments of a chain moving the axes beyond X, Y, Z (``segs``, ``blks``, ``fit_of``: of
    :func:`_blended_extra`)
    with the rate steps of those axes at the junctions of two lines or arcs carried by ramps: the quintic of
    :mod:`interpolators.axis_blends` along the programmed path over a length centred on the junction
    (:func:`interpolators.axis_blends.ramp_half_length` each side, at most :data:`_RAMP_SHARE` of either segment),
    each segment cut into its ramps and the rest, which keeps its programmed rate (a quintic with equal end rates:
    the straight line). X, Y, Z keep their programmed path; the junction then passes at its X, Y, Z bound instead of
    the one-sample rule of a rate step (a stop, at 0.5 deg/mm and the default limits), within ``P`` of the
    programmed motion of every axis (RS274/NGC 3, Sec. 2.1.2.5: proportional to the path on each block; our reading
    of G64 P for these axes, :mod:`interpolators.axis_blends`), where ``worth(segs, blks, joints, rates, ramps)``
    (:func:`_ramp_worth`) finds passing the ramp faster than the junction's own bound (a short ramp of a large
    step, 7 deg/mm within P0.05, is passed at 1.5 mm/s: slower than a stop). Junctions beside a merged run, a blend, a
    rapid or a chord under tool centre point control keep the rule."""
    blk = program.blocks
    n = len(segs)
    plain = [(isinstance(sg, Line) or (isinstance(sg, Arc) and abs(sg.sweep) <= 2.0 * math.pi))  # no extra turns:
             and id(sg) not in fit_of and blk[b].kind != "rapid" and not blk[b].tcp  # its pieces are plain arcs
             for sg, b in zip(segs, blks)]
    rate = np.array([blk[b].extra_delta / blk[b].segment.length if plain[k] else np.zeros(len(EXTRA_NAMES))
                     for k, b in enumerate(blks)], dtype=float).reshape(n, len(EXTRA_NAMES))
    joints = [k for k in range(n - 1) if plain[k] and plain[k + 1] and np.any(rate[k + 1] != rate[k])]
    if not joints:
        return segs, blks, fit_of
    k = np.array(joints)
    length = np.array([sg.length for sg in segs])
    start = np.array([_value_at_start(sg, blk[b]) for sg, b in zip(segs, blks)]).reshape(n, len(EXTRA_NAMES))
    tol = np.array([min(_tolerance(blk[blks[i]]), _tolerance(blk[blks[i + 1]])) for i in joints])
    half = np.minimum(_RAMP_SHARE * np.minimum(length[k], length[k + 1]),
                      _RAMP_MARGIN * ramp_half_length(rate[k + 1] - rate[k], tol))
    half = np.where(tol > 0, half, 0.0)
    corner = start[k] + rate[k] * length[k, None]
    ramps = (2.0 * half, corner - rate[k] * half[:, None], corner + rate[k + 1] * half[:, None], rate[k], rate[k + 1])
    half = np.where(worth(segs, blks, k, rate, ramps), half, 0.0)
    if not np.any(half > 0):
        return segs, blks, fit_of
    cut = np.zeros((n, 2))  # the ramp's length at each segment's start and end
    cut[k, 1], cut[k + 1, 0] = half, half
    units: list[tuple[float, np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []  # hermite_axes' arguments
    pieces: list[tuple[int, float, float, int, float]] = []  # segment, from, to, unit, offset in it
    for i in np.flatnonzero(cut.sum(axis=1) > 0).tolist():
        h0, h1, m = cut[i, 0], cut[i, 1], rate[i]
        if h0 > 0:  # the second half of the ramp at its start (the first half was made with segment i - 1)
            pieces.append((i, 0.0, h0, len(units) - 1, h0))
        middle = (h0, length[i] - h1)
        units.append((middle[1] - middle[0], start[i] + m * middle[0], start[i] + m * middle[1], m, m))
        pieces.append((i, *middle, len(units) - 1, 0.0))
        if h1 > 0:
            corner = start[i] + m * length[i]
            units.append((2.0 * h1, corner - m * h1, corner + rate[i + 1] * h1, m, rate[i + 1]))
            pieces.append((i, length[i] - h1, length[i], len(units) - 1, 0.0))
    spl, offsets = hermite_axes(*(np.array(x) for x in zip(*units)))
    out_segs, out_blks, out_fit, by_seg = [], [], dict(fit_of), {}
    for i, lo, hi, u, off in pieces:
        sg = segs[i]
        piece = piece_of(sg, sg.point_at(lo) if lo > 0 else sg.start, sg.point_at(hi) if hi < length[i] else sg.end)
        by_seg.setdefault(i, []).append(piece)
        out_fit[id(piece)] = (spl, float(offsets[u] + off))
    for i, (sg, b) in enumerate(zip(segs, blks)):
        for piece in by_seg.get(i, [sg]):
            out_segs.append(piece)
            out_blks.append(b)
    return out_segs, out_blks, out_fit


def _ramp_worth(ch: _Chain, lim: AxisLimitArrays, limits: Mapping[str, AxisLimits], jerk_limited: bool, Ts: float):
    """Predicate of :func:`_ramped_extra` for the chain ``ch``: is passing each junction ``k`` (between ``segs[k]``
    and ``segs[k + 1]``, the axes' rates per mm ``rate``) through its ramp (``ramps``: the arguments of
    :func:`interpolators.axis_blends.hermite_axes`) faster than at the junction's own bound? The model of
    :func:`_blend_worth` (:func:`_pass_beats`): the ramp passed at the lower of its bound (its axes' derivatives at
    ``1 - JUNCTION_SHARE`` of their limits; over its length where that is the lower; its speed changes within its
    path bounds) and the X, Y, Z junction's (:func:`interpolators.kinematics.junction_speed_limit`, at a tangent
    junction under the S-curve the larger :func:`_kink_junction_bound`; at the junction alone), the junction
    alone at the lower of that and its rate step's one-sample rule, either a stop below
    ``MIN_JUNCTION_SPEED_SHARE`` of the speed ``V`` of the two segments (their bounds from X, Y, Z and every axis,
    and the speed reached over half of either from rest)."""
    feed_of = dict(zip(ch.blocks, ch.feeds))

    def worth(segs: list, blks: list[int], k: np.ndarray, rate: np.ndarray, ramps: tuple) -> np.ndarray:
        m = len(k)
        d1, d2, d3 = hermite_bounds(*ramps)
        v_ramp, a_ramp, j_ramp = extra_curve_bounds(d1, d2, d3, np.full(m, np.inf), limits,
                                                    share=np.full(m, 1.0 - JUNCTION_SHARE), jerk_limited=jerk_limited)
        step = np.array([_corner_direction(segs[i + 1], "start") - _corner_direction(segs[i], "end")
                         for i in k.tolist()]).reshape(-1, 3)
        bend = np.array([_end_curvature(segs[i + 1], "start") - _end_curvature(segs[i], "end")
                         for i in k.tolist()]).reshape(-1, 3)
        v_xyz = junction_speed_limit(step, bend, lim, sample_time=Ts, share=JUNCTION_SHARE, jerk_limited=jerk_limited)
        tangent = np.linalg.norm(step, axis=1) <= _TANGENT_STEP
        if jerk_limited and tangent.any():  # a curvature step: the larger rule of _corner_stops
            v_xyz[tangent] = np.maximum(v_xyz[tangent], _kink_junction_bound(segs, k[tangent], lim, Ts))
        v_step = extra_junction_speed_limit(rate[k + 1] - rate[k], limits, sample_time=Ts, share=JUNCTION_SHARE,
                                            jerk_limited=jerk_limited)
        V, A, J = np.full(m, np.inf), np.full(m, np.inf), np.full(m, np.inf)
        for i, at in ((k, "end"), (k + 1, "start")):
            v_i, A_i, J_i = line_limits(np.array([_corner_direction(segs[j], at) for j in i.tolist()]).reshape(-1, 3),
                                        np.array([feed_of[blks[j]] for j in i.tolist()], dtype=float),
                                        np.zeros(m, dtype=bool), lim)
            v_e, A_e, J_e = extra_path_bounds(np.abs(rate[i]), np.zeros(m, dtype=bool), limits)
            A_i, J_i = np.minimum(A_i, A_e), np.minimum(J_i, J_e)
            half = np.array([0.5 * segs[j].length for j in i.tolist()])
            reach = reach_many(np.zeros(m), half, A_i, J_i, jerk_limited=jerk_limited)
            V = np.minimum(V, np.minimum(reach, np.minimum(np.minimum(v_i, v_e), _curved_bound(
                [segs[j] for j in i.tolist()], (1.0 - JUNCTION_SHARE) * A_i, (1.0 - JUNCTION_SHARE) * J_i,
                jerk_limited))))
            A, J = np.minimum(A, A_i), np.minimum(J, J_i)
        v_alone, v_b = (np.where(v < MIN_JUNCTION_SPEED_SHARE * V, 0.0, v)  # below: a stop either way
                        for v in (np.minimum(v_xyz, v_step), np.minimum(v_ramp, v_xyz)))
        slow = np.where(v_ramp < v_xyz, ramps[0], 0.0)  # the ramp's length, where its own bound is the lower
        passing = (np.minimum(A, a_ramp), np.minimum(J, j_ramp))  # the ramp's own path bounds
        return (v_b > v_alone) & ((v_b >= V) | _pass_beats(V, v_alone, v_b, slow, A, J, jerk_limited, passing))

    return worth


def _tolerance(block) -> float:
    """A block's G64 path tolerance [mm]: its ``P``, else :data:`interpolators.lookahead.DEFAULT_TOLERANCE`."""
    return DEFAULT_TOLERANCE if block.tolerance is None else block.tolerance


def _value_at_start(segment: Line | Arc, block) -> np.ndarray:
    """The axes beyond X, Y, Z at the start of a line or arc of ``block`` (a line may start past the block's start,
    shortened by a corner blend; an arc cut by a kink blend carries a fit and is not ramped)."""
    if isinstance(segment, Line) and block.extra_start is not None and segment is not block.segment:
        return _on_line([block], np.asarray(segment.start, dtype=float)[None])[0][0]
    return np.asarray(block.extra_start if block.extra_start is not None else np.zeros(len(EXTRA_NAMES)), dtype=float)


def _on_line(blocks: Sequence, points: np.ndarray, *, near_end: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The axes beyond X, Y, Z at ``points`` (n, 3) of the lines or arcs (of at most one turn) of ``blocks`` (feed
    moves moving them) and their rates per mm of them, shape (n, 6) each: they move in proportion to the path
    (RS274/NGC 3, Sec. 2.1.2.5), on an arc by the length of its piece from the block's start to the point, or
    (``near_end``: points in the arc's second half) its length less that of the piece from the point to its end (a
    full circle's end is its start)."""
    n = len(blocks)
    start = np.array([b.extra_start for b in blocks], dtype=float).reshape(n, len(EXTRA_NAMES))
    delta = np.array([b.extra_delta for b in blocks], dtype=float).reshape(n, len(EXTRA_NAMES))
    origin = np.array([b.segment.start for b in blocks], dtype=float).reshape(n, 3)
    rate = delta / np.array([b.segment.length for b in blocks], dtype=float)[:, None]
    along = np.linalg.norm(points - origin, axis=1)
    for i, b in enumerate(blocks):
        arc = b.segment
        if isinstance(arc, Arc) and near_end:
            to_end = np.asarray(arc.end, dtype=float)
            along[i] = arc.length - (piece_of(arc, points[i], to_end).length
                                     if np.any(points[i] != to_end) else 0.0)
        elif isinstance(arc, Arc) and along[i] > 0.0:
            along[i] = piece_of(arc, origin[i], points[i]).length
    return start + rate * along[:, None], rate


def _restore_runs(ch: _Chain, merged: _Chain, run_of: dict[int, MergedRun], failed: set[int]
                  ) -> tuple[_Chain, dict[int, MergedRun]]:
    """The merged chain ``merged`` of ``ch`` with the runs ``failed`` (by ``id``) put back as their chords (the
    items of ``ch``: one per block in a chain moving the axes beyond X, Y, Z), and the run of each piece left."""
    index = {b: i for i, b in enumerate(ch.blocks)}
    out = _Chain.of([], [], [], [], [])
    for k, seg in enumerate(merged.segments):
        run = run_of.get(id(seg))
        if run is None or id(run) not in failed:
            out.add(seg, merged.blocks[k], merged.feeds[k], merged.rapid[k], merged.tolerances[k])
        elif seg is run.pieces[0]:
            for i in (index[b] for b in run.blocks.tolist()):
                out.add(ch.segments[i], ch.blocks[i], ch.feeds[i], ch.rapid[i], ch.tolerances[i])
    return out, {key: run for key, run in run_of.items() if id(run) not in failed}


def _vertex_arc_lengths(run: MergedRun) -> tuple[np.ndarray, np.ndarray]:
    """Arc length along the run's curve of each of its programmed points (from their curve parameters
    ``vertex_u``, the pieces' arc-length tables inverted at :data:`_ARC_TABLE` points per piece) and at the start
    of each piece."""
    pieces = run.pieces
    lengths = np.array([p.length for p in pieces])
    s0 = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
    piece = np.repeat(np.arange(len(pieces)), _ARC_TABLE + 1)
    s_local = (np.linspace(0.0, 1.0, _ARC_TABLE + 1)[None, :] * lengths[:, None]).ravel()
    out = np.interp(run.vertex_u, SplineCurve.parameters(pieces, piece, s_local), s0[piece] + s_local)
    out[0], out[-1] = 0.0, s0[-1] + lengths[-1]  # the ends exactly where the samples reach them
    return out, s0


def _fit_derivatives(fits: dict, idx: np.ndarray, length: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Largest ``|r_1|``, ``|r_2|``, ``|r_3|`` (the path derivatives, shape (len(idx), 6)) of the axis splines
    ``fits`` on the curve pieces ``idx`` (of lengths ``length``): at :data:`_ARC_TABLE` points of each piece and
    at the middles of the spline's knot intervals in it (``r_3`` is constant between knots), by
    CURVE_BOUND_MARGIN; each spline evaluated once for all its pieces."""
    out = np.zeros((3, len(idx), len(EXTRA_NAMES)))
    splines = [fits[k][0] for k in idx.tolist()]
    s0 = np.array([fits[k][1] for k in idx.tolist()])
    s1 = s0 + length[idx]
    grid = np.linspace(0.0, 1.0, _ARC_TABLE + 1)
    for j, rows in rows_by_owner(splines, np.arange(len(idx))):
        spl = splines[j]
        t = np.unique(spl.t)
        mid = 0.5 * (t[1:] + t[:-1])
        at = [np.concatenate([s0[r] + grid * (s1[r] - s0[r]), mid[(mid > s0[r]) & (mid < s1[r])]]) for r in rows]
        cuts = np.cumsum([0, *(len(a) for a in at)])[:-1]
        at_all = np.concatenate(at)
        for nu in range(3):
            d = np.where(np.any(spl.c != spl.c[0], axis=0), np.abs(spl(at_all, nu + 1)), 0.0)  # still: exactly 0
            out[nu, rows] = np.maximum.reduceat(d, cuts, axis=0) * CURVE_BOUND_MARGIN
    return out[0], out[1], out[2]


def _fit_ends(g: _Geom, nu: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``nu``-th derivative along the path of the axes beyond X, Y, Z at the start and the end of each
    segment: on a line ``delta / length`` (``nu = 1``) or 0, on a merged run's piece its spline's."""
    r = g.extra
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.where(r.length[:, None] > 0, r.delta / r.length[:, None], 0.0) if nu == 1 else np.zeros_like(r.delta)
    at_start, at_end = rate, rate.copy()
    keys = np.array(sorted(r.fits), dtype=np.int64)
    splines = [r.fits[k][0] for k in keys.tolist()]
    s0 = np.array([r.fits[k][1] for k in keys.tolist()])
    for j, rows in rows_by_owner(splines, np.arange(len(keys))):  # each spline evaluated once for all its pieces
        spl, k = splines[j], keys[rows]
        moving = np.any(spl.c != spl.c[0], axis=0)  # an axis the run keeps still: exactly 0
        at_start[k] = np.where(moving, spl(s0[rows], nu), 0.0)
        at_end[k] = np.where(moving, spl(s0[rows] + r.length[k], nu), 0.0)
    return at_start, at_end


def _merged(ch: _Chain, jerk_limited: bool, *, unblended: bool = False) -> tuple[_Chain, dict[int, MergedRun]]:
    """The chain with its runs of dense short lines merged into smooth curves
    (:func:`interpolators.dense.merge_dense_runs`; ``jerk_limited``: tight curves too), and the run of each curve
    piece (by ``id``)."""
    blocks, feeds, rapid, tolerances = ch.blocks, ch.feeds, ch.rapid, ch.tolerances
    segs, first, runs = merge_dense_runs(ch.segments, blocks, feeds, rapid, tolerances,
                                         curvature_continuous=jerk_limited, unblended=unblended)
    if not runs:
        return ch, {}
    # the last input segment each stands for: the pieces of one run share its first, so the one before the next
    # item's first that differs (the run's last block: not the block before the run, that item's tolerance)
    nxt = np.searchsorted(first, first, side="right")
    last = [first[k] - 1 if k < len(first) else len(blocks) - 1 for k in nxt.tolist()]
    slowest = [min(feeds[f:e + 1]) for f, e in zip(first, last)]  # a run's feeds may differ (unblended)
    out = _Chain.of(segs, [blocks[i] for i in first], slowest, [rapid[i] for i in first],
                    [tolerances[i] for i in last])
    return out, {id(segs[k]): run for k, run in runs.items()}


def _evaluate(g: _Geom, seg: np.ndarray, s: np.ndarray, v: np.ndarray, a: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity and acceleration on the segments ``seg`` (nondecreasing) at arc lengths ``s``
    (:meth:`PackedSegments.evaluate`, smooth curve pieces evaluated on their curve)."""
    pos, vel, acc = g.packed.evaluate(seg, s, v, a)
    _, curves, piece, rows = _curve_rows(g, seg)
    if len(rows):
        pos[rows], tan, curv = SplineCurve.evaluate_pieces(curves, piece, s[rows])
        vel[rows] = tan * v[rows, None]
        acc[rows] = tan * a[rows, None] + curv * (v[rows] ** 2)[:, None]
    return pos, vel, acc


def _curve_rows(g: _Geom, seg: np.ndarray) -> tuple[list[int], list[SplineCurve], np.ndarray, np.ndarray]:
    """The smooth curve pieces of ``g`` that rows of ``seg`` (nondecreasing: samples in time order, junctions in
    chain order) are on (their segment indices and the pieces, in segment order) and, for those rows, the piece
    (index into that list) and the row of each, found by bisection rather than one scan of ``seg`` per piece. Only
    the pieces a chunk of samples is on: the work per chunk does not grow with the program's pieces."""
    pieces = np.array(sorted(g.runs), dtype=np.int64)
    lo = np.searchsorted(seg, pieces, side="left")
    n = np.searchsorted(seg, pieces, side="right") - lo
    on = np.flatnonzero(n)
    ids, lo, n = pieces[on].tolist(), lo[on], n[on]
    piece = np.repeat(np.arange(len(ids)), n)
    rows = np.arange(int(n.sum())) + np.repeat(lo - (np.cumsum(n) - n), n)
    return ids, [g.segments[i] for i in ids], piece, rows


def _curve_blocks(g: _Geom, ids: list[int], piece: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The block of the chord each point on the curve pieces (index into ``ids``, the segment indices of pieces of
    ``g``, as from :func:`_curve_rows`; spline parameter ``u``) passes
    (:meth:`interpolators.dense.MergedRun.block_at`), each run's rows at once."""
    run_of = [g.runs[i] for i in ids]  # the run of each of the curves
    out = np.empty(len(u), dtype=np.int64)
    for k, rows in rows_by_owner(run_of, piece):
        out[rows] = run_of[k].block_at(u[rows])
    return out


def _limits(g: _Geom, idx: np.ndarray, lims: AxisLimitArrays, jerk_limited: bool,
            jerk_share: float = JERK_SPEED_SHARE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`path_limits` of the motion segments ``idx``; smooth curve pieces by :func:`curve_limits`."""
    v, a, j = path_limits(g.packed.subset(idx), g.feed[idx], g.rapid[idx], lims, jerk_limited=jerk_limited,
                          jerk_share=jerk_share)
    on_curve = np.flatnonzero(np.isin(idx, list(g.runs))) if g.runs else np.zeros(0, dtype=np.int64)
    if len(on_curve):
        k = idx[on_curve]
        v[on_curve], a[on_curve], j[on_curve] = curve_limits([g.segments[i] for i in k], g.feed[k], lims,
                                                             jerk_limited=jerk_limited, jerk_share=jerk_share)
    return v, a, j


def _corner_stops(g: _Geom, chains: list[_Chain], lim: AxisLimitArrays, Ts: float, jerk_limited: bool,
                  limits: Mapping[str, AxisLimits], *, rapid_feed_stop: bool) -> _Chains:
    """2. The geometric speed bound at each junction inside a chain; a junction whose bound is
    negligible (a real corner or reversal) becomes a stop, splitting the chain, so that only
    chains passing discontinuous junctions at speed pay the JUNCTION_SHARE reserve. The axes
    beyond X, Y, Z take part by the same rule (their rate steps, :func:`_extra_junctions`). A junction of a rapid
    and a feed move is a stop too where the control stops there (``rapid_feed_stop``, :func:`_rapid_feed_stops`)."""
    packed, seg_chain_a = g.packed, g.chain
    n_seg = len(g.segments)
    L = packed.length
    inner = np.flatnonzero(seg_chain_a[1:] == seg_chain_a[:-1]) if n_seg > 1 else np.zeros(0, dtype=np.int64)
    jl = np.zeros(len(inner))
    if len(inner):
        ones, zeros = np.ones(len(inner)), np.zeros(len(inner))
        _, t_out, k_out = _evaluate(g, inner, L[inner], ones, zeros)
        _, t_in, k_in = _evaluate(g, inner + 1, zeros, ones, zeros)
        jl = junction_speed_limit(t_in - t_out, k_in - k_out, lim, sample_time=Ts, share=JUNCTION_SHARE,
                                  jerk_limited=jerk_limited)
        # worth passing at speed only if the bound is a fair share of the neighbours' speeds
        motion_idx = np.flatnonzero(packed.kind != HOLD)
        v_full = np.zeros(n_seg)
        j_full = np.zeros(n_seg)
        if len(motion_idx):
            v_full[motion_idx], _, j_full[motion_idx] = _limits(g, motion_idx, lim, jerk_limited)
        if jerk_limited:
            jl = _curvature_steps(g, inner, t_out, t_in - t_out, k_in - k_out, v_full, j_full, jl, lim, Ts)
        # continuous junctions (G2 blends, rounding-level steps) need no reserve
        jl_tiny = junction_speed_limit(t_in - t_out, k_in - k_out, lim, sample_time=Ts, share=NEGLIGIBLE_SHARE,
                                       jerk_limited=jerk_limited)
        if g.extra is not None:
            jl, jl_tiny = _extra_junctions(g, inner, jl, jl_tiny, v_full, limits, Ts, jerk_limited)
        v_stop = MIN_JUNCTION_SPEED_SHARE * np.minimum(v_full[inner], v_full[inner + 1])
        keep_j = (jl > v_stop) & ~_rapid_feed_stops(rapid_feed_stop, g.rapid[inner], g.rapid[inner + 1])
        split = inner[~keep_j]
        rough = inner[keep_j & (jl_tiny < np.maximum(v_full[inner], v_full[inner + 1]))]
        inner, jl = inner[keep_j], jl[keep_j]
    else:
        split = rough = inner
    new_chain = np.ones(n_seg, dtype=bool)
    if n_seg:
        new_chain[1:] = seg_chain_a[1:] != seg_chain_a[:-1]
        new_chain[split + 1] = True
    old_chain = seg_chain_a
    seg_chain_a = np.cumsum(new_chain) - 1
    n_chains = int(seg_chain_a[-1]) + 1 if n_seg else 0
    dwell_of_chain = np.zeros(n_chains)
    if n_seg:
        dwell_of_chain[seg_chain_a] = np.array([ch.dwell for ch in chains])[old_chain]
    chain_len = np.bincount(seg_chain_a, minlength=n_chains) if n_seg else np.zeros(0, dtype=np.int64)
    reserved = np.zeros(n_chains, dtype=bool)
    reserved[seg_chain_a[rough]] = True
    in_multi = reserved[seg_chain_a] if n_seg else np.zeros(0, dtype=bool)
    return _Chains(of_segment=seg_chain_a, count=n_chains, dwell=dwell_of_chain, length=chain_len,
                   reserved_segment=in_multi, inner=inner, junction_limit=jl)


def _curvature_steps(g: _Geom, inner: np.ndarray, tangent: np.ndarray, tangent_jump: np.ndarray,
                     curvature_jump: np.ndarray, v_full: np.ndarray, j_full: np.ndarray, jl: np.ndarray,
                     lim: AxisLimitArrays, Ts: float) -> np.ndarray:
    """2a. S-curve: the bound ``jl`` of the junctions with a curvature step where the JUNCTION_SHARE rule
    binds (line/arc, arc/arc of another radius or sense, line/merged curve; tangent up to rounding)
    raised to :func:`interpolators.kinematics.curvature_step_speed_limit` (each axis' own jerk budget)
    where that is larger; the tangent step keeps its acceleration bound. It applies between lines, arcs
    without helix and merged curve pieces longer than the finite-difference window on both sides (one
    step per window); ``j_full`` (the path jerk bounds with the whole limits) bounds the profiles'
    jerk. These junctions are not negligible (NEGLIGIBLE_SHARE), so their chains keep the
    JUNCTION_SHARE reserve the rule counts on."""
    packed = g.packed
    a, b = inner, inner + 1
    stepped = (np.abs(curvature_jump).max(axis=1) > 0) & (jl < np.maximum(v_full[a], v_full[b]))
    kappa = np.zeros(len(g.segments))
    dkappa = np.zeros(len(g.segments))
    simple = np.ones(len(g.segments), dtype=bool)
    for i in np.unique(np.concatenate([a[stepped], b[stepped]])):
        seg = g.segments[i]
        if i in g.runs:
            k, dk, _ = seg.bounds()
            kappa[i], dkappa[i] = k * CURVE_BOUND_MARGIN, dk * CURVE_BOUND_MARGIN
        elif isinstance(seg, Arc):
            kappa[i] = 1.0 / packed.radius[i]
            simple[i] = packed.helix[i] == 0.0
        else:
            simple[i] = isinstance(seg, Line)
    cand = np.flatnonzero(stepped & simple[a] & simple[b])
    if not len(cand):
        return jl
    ia, ib = a[cand], b[cand]
    jp = np.maximum(j_full[ia], j_full[ib])
    v = curvature_step_speed_limit(tangent[cand], tangent_jump[cand], curvature_jump[cand],
                                   np.maximum(kappa[ia], kappa[ib]), np.maximum(dkappa[ia], dkappa[ib]), jp, lim,
                                   sample_time=Ts, share=JUNCTION_SHARE)
    v = np.minimum(v, junction_speed_limit(tangent_jump[cand], np.zeros((len(cand), 3)), lim, sample_time=Ts,
                                           share=JUNCTION_SHARE, jerk_limited=False))
    window = 2.0 * 3.0 * (v + 4.5 * jp * Ts * Ts) * Ts  # both finite-difference windows inside the segments
    fits = window < np.minimum(packed.length[ia], packed.length[ib])
    out = jl.copy()
    out[cand] = np.where(fits, np.maximum(jl[cand], v), jl[cand])
    return out


def _extra_junctions(g: _Geom, inner: np.ndarray, jl: np.ndarray, jl_tiny: np.ndarray, v_full: np.ndarray,
                     limits: Mapping[str, AxisLimits], Ts: float, jerk_limited: bool
                     ) -> tuple[np.ndarray, np.ndarray]:
    """2b. The junction bounds (at JUNCTION_SHARE and at NEGLIGIBLE_SHARE) lowered for the rate steps
    of the axes beyond X, Y, Z (:func:`interpolators.kinematics.extra_junction_speed_limit`, the
    XYZ tangent rule per axis); ``v_full`` (in place) capped by their limits on the segments that
    move them."""
    r = g.extra
    fitted = np.array(sorted(r.fits), dtype=np.int64)
    is_moving = np.any(r.delta != 0, axis=1)
    is_moving[fitted] = False
    moving = np.flatnonzero(is_moving)
    if len(moving):
        ratio = np.abs(r.delta[moving]) / r.length[moving, None]
        v_full[moving] = np.minimum(v_full[moving], extra_path_bounds(ratio, g.rapid[moving], limits)[0])
    if len(fitted):
        v_full[fitted] = extra_curve_bounds(*_fit_derivatives(r.fits, fitted, r.length), v_full[fitted], limits,
                                            share=np.ones(len(fitted)), jerk_limited=jerk_limited)[0]
    rate_in, rate_out = _fit_ends(g, 1)
    step = rate_in[inner + 1] - rate_out[inner]
    second = None
    if r.fits:
        second_in, second_out = _fit_ends(g, 2)
        second = second_in[inner + 1] - second_out[inner]
    jl = np.minimum(jl, extra_junction_speed_limit(step, limits, sample_time=Ts, share=JUNCTION_SHARE,
                                                   jerk_limited=jerk_limited, second_jump=second))
    jl_tiny = np.minimum(jl_tiny, extra_junction_speed_limit(step, limits, sample_time=Ts, share=NEGLIGIBLE_SHARE,
                                                             jerk_limited=jerk_limited, second_jump=second))
    return jl, jl_tiny


def _path_bounds(g: _Geom, c: _Chains, lim: AxisLimitArrays, jerk_limited: bool,
                 jerk_share: float = JERK_SPEED_SHARE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """3. The path's speed, acceleration and jerk bounds per segment (chains passing a
    discontinuity at speed keep JUNCTION_SHARE of the limits in reserve; ``jerk_share``: the share of the jerk
    limits a curve's speed may take, :func:`interpolators.kinematics.curved_speed_bound`)."""
    n_seg = len(g.segments)
    lim_chain = lim.scaled(acceleration=1.0 - JUNCTION_SHARE, jerk=1.0 - JUNCTION_SHARE)
    v_max = np.zeros(n_seg)
    a_max = np.ones(n_seg)
    j_max = np.ones(n_seg)
    motion = g.packed.kind != HOLD
    for mask, lims in ((motion & ~c.reserved_segment, lim), (motion & c.reserved_segment, lim_chain)):
        idx = np.flatnonzero(mask)
        if len(idx):
            v, a, j = _limits(g, idx, lims, jerk_limited, jerk_share)
            v_max[idx], a_max[idx], j_max[idx] = v, a, j
    return v_max, a_max, j_max


#: Share of the jerk limits a curve's speed may take (``v^3 |(k^2, dk/ds)|``) tried beside
#: :data:`interpolators.kinematics.JERK_SPEED_SHARE` in each chain under the S-curve (:func:`_faster_jerk_share`):
#: with ``3 k v a`` at :data:`interpolators.kinematics.JERK_ACCEL_SHARE` (0.3) the path jerk keeps at least
#: ``sqrt(1 - (0.3 + s sin(phi))^2) - s cos(phi) >= 0.26`` of the limit whatever the share of ``k^2`` and ``dk/ds``
#: (angle ``phi``); at 0.7 it keeps none where ``dk/ds`` dominates (a curve piece then has no path jerk at all).
_CRUISE_JERK_SHARE = 0.6


def _faster_jerk_share(g: _Geom, c: _Chains, lim: AxisLimitArrays, bounds: tuple[np.ndarray, ...], jerk_limited: bool,
                       limits: Mapping[str, AxisLimits]) -> tuple[np.ndarray, ...]:
    """3b-4. The plan ``(v_max, a_max, j_max, v0, v1)``: the path ``bounds`` (of :func:`_path_bounds`, capped by the
    axes beyond X, Y, Z, :func:`_extra_bounds`) and the junction speeds (:func:`_junction_speeds`) they give; under
    the S-curve, in each chain where that is faster, the bounds of its curves at :data:`_CRUISE_JERK_SHARE` of the
    jerk limits for ``v^3 |(k^2, dk/ds)|`` instead of :data:`interpolators.kinematics.JERK_SPEED_SHARE`, capped
    likewise (before session 33 programs moving those axes kept the first, so a contour after one move with A ran
    slower than alone: alternating tangent arcs 3.118 -> 3.721 s at F1200 P0.01).

    The share splits one budget: at constant speed the jerk of a curve is ``v^3 |(k^2, dk/ds)|`` alone, while a
    speed change on it needs the rest for ``3 k v a`` and the path jerk (:mod:`interpolators.kinematics`).
    Either bound set keeps every axis within its limits (the jerk vector's norm); which is faster depends on how
    much the speed changes on the curves, so both are planned and each chain (it starts and ends at rest, its
    time its own) keeps the shorter, measured by the segments' S-curve profiles. Controls let the share follow
    need likewise: LinuxCNC's ``pmCircleActualMaxVel`` (``src/emc/tp/blendmath.c``) gives an arc's normal
    acceleration what its speed needs, at most ``BLEND_ACC_RATIO_NORMAL`` (sqrt(3)/2) of the limit, and the
    tangential acceleration the rest; no manual found states a jerk split (our reading: choose the faster)."""
    if g.extra is not None:
        bounds = _extra_bounds(g, c, *bounds, limits, jerk_limited)
    plan = (*bounds, *_junction_speeds(g, c, *bounds, jerk_limited))
    if not jerk_limited:
        return plan
    v_max, a_max, j_max, v0, v1 = plan
    alt = _path_bounds(g, c, lim, True, _CRUISE_JERK_SHARE)
    if g.extra is not None:
        alt = _extra_bounds(g, c, *alt, limits, True)
    differs = (alt[0] != v_max) | (alt[1] != a_max) | (alt[2] != j_max)
    chains = np.unique(c.of_segment[differs])
    if not len(chains):
        return plan
    v0_alt, v1_alt = _junction_speeds(g, c, *alt, True)
    rows = np.flatnonzero(np.isin(c.of_segment, chains) & (g.packed.kind != HOLD))
    length = g.profile_length[rows]
    times = [np.bincount(c.of_segment[rows], weights=scurve_phases(length, b[3][rows], b[4][rows], b[0][rows],
                                                                   b[1][rows], b[2][rows])[0].sum(axis=1),
                         minlength=c.count)
             for b in (plan, (*alt, v0_alt, v1_alt))]
    take = np.isin(c.of_segment, np.flatnonzero(times[1] < times[0]))
    return tuple(np.where(take, new, old) for old, new in zip(plan, (*alt, v0_alt, v1_alt)))


def _junction_speeds(g: _Geom, c: _Chains, v_max: np.ndarray, a_max: np.ndarray, j_max: np.ndarray,
                     jerk_limited: bool) -> tuple[np.ndarray, np.ndarray]:
    """4. Entry and exit speed of each segment (the look-ahead over each chain)."""
    n_seg = len(g.segments)
    L = g.packed.length
    v0 = np.zeros(n_seg)
    v1 = np.zeros(n_seg)
    multi_chains = np.flatnonzero(c.length > 1)
    if len(multi_chains):
        first = np.concatenate([[0], np.cumsum(c.length)[:-1]])
        jl_at = np.zeros(n_seg)
        jl_at[c.inner] = c.junction_limit
        for k in multi_chains.tolist():
            s0, n = int(first[k]), int(c.length[k])
            sl = slice(s0, s0 + n)
            vj = junction_speeds(L[sl], v_max[sl], a_max[sl], j_max[sl], jl_at[s0:s0 + n - 1],
                                 jerk_limited=jerk_limited)
            v0[sl], v1[sl] = vj[:-1], vj[1:]
    return v0, v1


def _check_samples(total_N: float, Ts: float, program: Program, max_samples: int, *, at_least: bool = False) -> None:
    """Refuse a program of ``total_N`` sample periods (``at_least``: a lower bound) when it needs more than
    ``max_samples`` samples."""
    if total_N + 1 > max_samples:
        exc = ProgramTooLongError(
            f"program needs {'at least ' if at_least else ''}{total_N + 1:.0f} samples at Ts = {Ts:g} s "
            f"({total_N * Ts:.6g} s), more than max_samples = {max_samples}",
            file=program.source,
            expected="a shorter program, a larger sample time or a larger max_samples",
        )
        exc.samples, exc.at_least, exc.sample_time = int(total_N + 1), at_least, Ts
        raise exc


def _phases(g: _Geom, c: _Chains, v0: np.ndarray, v1: np.ndarray, v_max: np.ndarray, a_max: np.ndarray,
            j_max: np.ndarray, Ts: float, jerk_limited: bool, program: Program, max_samples: int
            ) -> tuple[dict[str, np.ndarray], int]:
    """5-6. The profiles of the segments, each chain stretched to whole samples: the phase table
    (segment, start time, duration, position, speed, acceleration, jerk) and the number of samples."""
    packed = g.packed
    n_seg = len(g.segments)
    seg_chain_a, n_chains = c.of_segment, c.count
    motion = packed.kind != HOLD
    length = g.profile_length
    if g.extra is not None:  # X, Y, Z still: a hold in XYZ with a profile along Block.extra_length
        motion = motion | g.extra.pure
    mi = np.flatnonzero(motion)
    # lower bound first (each segment at its speed bound, dwells): a program far too long for max_samples is
    # refused before its profiles are computed (ruckig raises on lengths of 1e8 mm)
    moving = mi[v_max[mi] > 0]
    least_T = float(np.sum(length[moving] / v_max[moving])) + float(c.dwell.sum())
    _check_samples(least_T / Ts, Ts, program, max_samples, at_least=True)
    if jerk_limited:
        dur, p0, pv, pa, pj = scurve_phases(length[mi], v0[mi], v1[mi], v_max[mi], a_max[mi], j_max[mi])
    else:
        dur, p0, pv, pa, pj = trapezoid_phases(length[mi], v0[mi], v1[mi], v_max[mi], a_max[mi])
    n_ph = dur.shape[1]
    seg_dur = np.zeros(n_seg)
    seg_dur[mi] = dur.sum(axis=1)
    hold = np.flatnonzero(~motion)
    seg_dur[hold] = c.dwell[seg_chain_a[hold]]
    # whole samples per chain; uniform slow-down (lambda <= 1) to fit them
    chain_T = np.bincount(seg_chain_a, weights=seg_dur, minlength=n_chains) if n_seg else np.zeros(0)
    chain_N = np.ceil(chain_T / Ts * (1.0 - 1e-12)).astype(np.int64)
    chain_N = np.maximum(chain_N, 1)
    total_N = int(chain_N.sum())
    _check_samples(total_N, Ts, program, max_samples)
    lam = np.where(chain_T > 0, chain_T / (chain_N * Ts), 1.0)
    chain_n0 = np.concatenate([[0], np.cumsum(chain_N)[:-1]]).astype(np.int64) if n_chains else np.zeros(0, np.int64)

    # phase table: one row per phase of positive duration
    ph_seg = np.concatenate([np.repeat(mi, n_ph), hold])
    lam_ph = lam[seg_chain_a[ph_seg]]
    ph_dur = np.concatenate([dur.reshape(-1), seg_dur[hold]]) / lam_ph
    ph_p = np.concatenate([p0.reshape(-1), np.zeros(len(hold))])
    ph_v = np.concatenate([pv.reshape(-1), np.zeros(len(hold))]) * lam_ph
    ph_a = np.concatenate([pa.reshape(-1), np.zeros(len(hold))]) * lam_ph**2
    ph_j = np.concatenate([pj.reshape(-1), np.zeros(len(hold))]) * lam_ph**3
    order = np.argsort(ph_seg, kind="stable")
    ph_seg, ph_dur, ph_p, ph_v, ph_a, ph_j = (x[order] for x in (ph_seg, ph_dur, ph_p, ph_v, ph_a, ph_j))
    # each phase's start as a whole sample and a fraction of one after it, counted from its chain's first sample
    ph_n0, ph_rel = phase_clock(seg_chain_a[ph_seg], ph_dur, chain_n0, Ts)
    # the last phase of a segment ends exactly at the segment end (no rounding residue)
    last_of_seg = np.ones(len(ph_seg), dtype=bool)
    last_of_seg[:-1] = ph_seg[1:] != ph_seg[:-1]
    keep = (ph_dur > 0) | last_of_seg
    ph_seg, ph_dur, ph_p, ph_v, ph_a, ph_j, ph_rel, ph_n0, last_of_seg = (
        x[keep] for x in (ph_seg, ph_dur, ph_p, ph_v, ph_a, ph_j, ph_rel, ph_n0, last_of_seg)
    )
    # the first sample at or after each phase's start
    ph_first = ph_n0 + (ph_rel > 0)
    return {"seg": ph_seg, "dur": ph_dur, "p": ph_p, "v": ph_v, "a": ph_a, "j": ph_j, "first": ph_first,
            "rel": ph_rel, "n0": ph_n0, "last": last_of_seg}, total_N


def _sample(program: Program, g: _Geom, ph: dict[str, np.ndarray], total_N: int, Ts: float,
            profile: str) -> Setpoints:
    """7. The setpoints at every sample time, evaluated :data:`SAMPLE_CHUNK` samples at a time."""
    axes = program.axes or ("x",)
    ax_idx = [AXIS_NAMES.index(a) for a in axes]
    linear = tuple(a for a in axes if a in AXIS_LETTERS) or AXIS_LETTERS
    t = np.arange(total_N + 1) * Ts
    if len(ph["seg"]) == 0:
        first = program.blocks[0] if program.blocks else None
        start = np.zeros(len(AXIS_NAMES))
        if first is not None:
            start[:3] = first.start
            if first.extra_start is not None:
                start[3:] = first.extra_start
        pos = np.broadcast_to(start[ax_idx], (1, len(axes))).copy()
        return Setpoints(
            t=np.zeros(1), axes=axes, position=pos, velocity=np.zeros_like(pos), acceleration=np.zeros_like(pos),
            block=np.full(1, 0 if program.blocks else -1, dtype=np.int64), sample_time=Ts,
            path=program.path(), meta=_meta(program, profile, Ts, 0.0),
        )
    n_ax = len(axes)
    pos, vel, acc = (np.empty((len(t), n_ax)) for _ in range(3))
    block = np.empty(len(t), dtype=np.int64)
    # per phase and per segment, shared by the chunks: where a segment's last phase must end, each segment's block
    phase_end = np.where(ph["last"], g.profile_length[ph["seg"]], np.nan)
    seg_block = np.asarray(g.block, dtype=np.int64)
    for lo in range(0, len(t), SAMPLE_CHUNK):
        hi = min(len(t), lo + SAMPLE_CHUNK)
        pos[lo:hi], vel[lo:hi], acc[lo:hi], block[lo:hi] = _sample_chunk(g, ph, phase_end, seg_block, lo, t[lo:hi],
                                                                         Ts, ax_idx, last=hi == len(t))
    meta = _meta(program, profile, Ts, float(t[-1]))
    if g.blended:
        meta["programmed_path"] = program.path()
    return Setpoints(t=t, axes=axes, position=pos, velocity=vel, acceleration=acc, block=block,
                     sample_time=Ts, path=_sampled_path(g, linear), meta=meta)


def _sample_chunk(g: _Geom, ph: dict[str, np.ndarray], phase_end: np.ndarray, seg_block: np.ndarray, lo: int,
                  t: np.ndarray, Ts: float, ax_idx: list[int], *, last: bool
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity, acceleration (of the axes ``ax_idx``) and block at the sample times ``t`` (samples
    ``lo``, ``lo + 1``, ...); ``last``: ``t`` ends the program, whose last sample is at rest exactly on its end
    point. ``phase_end``: the path parameter a segment's last phase ends on (NaN for the others); ``seg_block``:
    each segment's block. The time into a phase is counted in whole samples from the last sample at or before
    its start (less the fraction of a sample it starts after that one), not from the program's start: minutes
    into a program, that time's rounding (1e-13 s at 300 s) times the speed moved the samples by 1e-10 mm, a
    1e-4 excess of jerk by finite differences on a 1 m/s rapid at Ts = 0.35 ms (setpoint fuzzer tnc seed 31017)."""
    ph_seg, sample = ph["seg"], np.arange(lo, lo + len(t))
    k = np.searchsorted(ph["first"], sample, side="right") - 1
    np.clip(k, 0, len(ph_seg) - 1, out=k)
    t_phase = (sample - ph["n0"][k]) * Ts
    s, v, a = phase_states(t_phase, k, ph["rel"], ph["dur"], ph["p"], ph["v"], ph["a"], ph["j"], phase_end)
    seg = ph_seg[k]
    if last:
        s[-1] = g.profile_length[seg[-1]]
        v[-1] = a[-1] = 0.0
    pos, vel, acc = _evaluate(g, seg, s, v, a)
    if g.extra is not None:
        pos, vel, acc = _with_extra(g.extra, seg, s, v, a, pos, vel, acc)
    if ax_idx != list(range(pos.shape[1])):
        pos, vel, acc = pos[:, ax_idx], vel[:, ax_idx], acc[:, ax_idx]
    block = seg_block[seg]
    ids, curves, piece, rows = _curve_rows(g, seg)
    if len(rows):
        block[rows] = _curve_blocks(g, ids, piece, SplineCurve.parameters(curves, piece, s[rows]))
    return pos, vel, acc, block


def _sampled_path(g: _Geom, axes: tuple[str, ...]) -> Path:
    """The geometry the samples follow; a smooth curve piece as a polyline of its points within
    :data:`CURVE_PATH_ERROR` of the curve, each line with the block of its middle."""
    polylines = _curve_polylines(g)
    segs: list = []
    blocks: list[int] = []
    for i, (s_, b) in enumerate(zip(g.segments, g.block)):
        if isinstance(s_, np.ndarray):
            continue
        if i in polylines:
            lines, mid_blocks = polylines[i]
            segs.extend(lines)
            blocks.extend(mid_blocks)
            continue
        segs.append(s_)
        blocks.append(b)
    return Path(segments=tuple(segs), blocks=tuple(blocks), axes=axes)


def _curve_polylines(g: _Geom) -> dict[int, tuple[list[Line], list[int]]]:
    """For each smooth curve piece (segment index): the lines of its polyline, points
    ``sqrt(8 CURVE_PATH_ERROR / k_max)`` apart, and the block of each line's middle; all evaluated at once."""
    order = sorted(g.runs)
    if not order:
        return {}
    curves = [g.segments[i] for i in order]
    s_k = []
    for piece in curves:
        kappa = piece.bounds()[0] * CURVE_BOUND_MARGIN
        n = max(1, int(math.ceil(piece.length * math.sqrt(kappa / (8.0 * CURVE_PATH_ERROR)))))
        s_k.append(np.linspace(0.0, piece.length, n + 1))
    counts = np.array([len(s) - 1 for s in s_k])
    which = np.arange(len(curves))
    p = SplineCurve.evaluate_pieces(curves, np.repeat(which, counts + 1), np.concatenate(s_k), frame=False)[0]
    mid_piece = np.repeat(which, counts)
    mid = np.concatenate([0.5 * (s[1:] + s[:-1]) for s in s_k])
    mid_blocks = _curve_blocks(g, order, mid_piece, SplineCurve.parameters(curves, mid_piece, mid)).tolist()
    starts = np.delete(np.arange(len(p)), np.cumsum(counts + 1) - 1)  # each piece's last point starts no line
    lines = Line.from_arrays(p[starts], p[starts + 1])
    out = {}
    k = 0
    for i, n in zip(order, counts.tolist()):
        out[i] = (lines[k:k + n], mid_blocks[k:k + n])
        k += n
    return out


def _with_extra(r: _Extra, seg: np.ndarray, s: np.ndarray, v: np.ndarray, a: np.ndarray, pos: np.ndarray,
                 vel: np.ndarray, acc: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The x, y, z columns followed by a, b, c [deg, deg/s, deg/s^2], u, v, w [mm, ...]: they move in
    proportion to the path parameter ``s`` (module :mod:`interpolators.kinematics`)."""
    L = r.length[seg]
    with np.errstate(divide="ignore", invalid="ignore"):
        per_s = np.where(L[:, None] > 0, r.delta[seg] / L[:, None], 0.0)  # [deg per path unit]
    rot = r.start[seg] + per_s * s[:, None]
    rot_v, rot_a = per_s * v[:, None], per_s * a[:, None]
    if r.fits:  # on a merged run's piece: its spline r(S) at the run's arc length S
        pieces = np.array(sorted(r.fits), dtype=np.int64)
        on = np.flatnonzero(np.isin(seg, pieces))
        which = np.searchsorted(pieces, seg[on])
        splines = [r.fits[k][0] for k in pieces.tolist()]
        s0 = np.array([r.fits[k][1] for k in pieces.tolist()])
        for j, rows in rows_by_owner(splines, which):
            spl, k = splines[j], on[rows]
            S = s0[which[rows]] + s[k]
            d1, d2 = spl(S, 1), spl(S, 2)
            cols = np.flatnonzero(np.any(spl.c != spl.c[0], axis=0))  # the others: start, delta 0 (_extra_geometry)
            rot[np.ix_(k, cols)] = spl(S)[:, cols]
            rot_v[np.ix_(k, cols)] = (d1 * v[k, None])[:, cols]
            rot_a[np.ix_(k, cols)] = (d1 * a[k, None] + d2 * (v[k] ** 2)[:, None])[:, cols]
    return np.hstack([pos, rot]), np.hstack([vel, rot_v]), np.hstack([acc, rot_a])


#: Largest tangent step [-] of a junction taken as tangent by :func:`_blend_worth` (a curvature step: its blend is
#: kept wherever it passes faster than the junction's own bound); our reading: the rounding of end points written
#: with 3 decimals on segments of a millimetre or more.
_TANGENT_STEP = 1e-3


def _blend_worth(ch: _Chain, lim: AxisLimitArrays, jerk_limited: bool, Ts: float,
                 cap: Callable[[CornerBlends], np.ndarray] | None = None, *, rapid_feed_stop: bool):
    """Predicate: is passing each corner through its blend faster than stopping at it?

    Model of one corner between lines cruising at ``V`` (their speed bound, or the speed they can
    reach over half their length): stopping takes two speed changes ``V -> 0 -> V``; blending
    takes ``V -> v_b``, the blend of length ``l`` at ``v_b`` (its speed bound) and ``v_b -> V``.
    Both are compared over the same distance (the shorter one completed at ``V``). A speed change
    ``dv`` with zero end accelerations takes ``dv/A + A/J`` or ``2 sqrt(dv/J)`` (``dv/A``
    without jerk limit). This keeps G64 from crawling through sharp corners a stop passes faster.
    The predicate judges all the corners of the chain at once (:class:`interpolators.lookahead.CornerBlends`).
    Beside an arc or curve ``V`` is at most its own speed bound (:func:`_curved_bound`). A kink blend (a
    :class:`toolpaths.geometry.SplineCurve`: a line/arc, arc/arc or curve junction, kinked or tangent with a
    curvature step) is compared with the junction passed unblended at its own bound ``v_j``
    (:func:`_kink_junction_bound`, at the sample time ``Ts``) instead of a stop, and must pass faster than
    ``v_j``: a rounding-level kink stays a junction on the programmed path. A tangent junction (tangent step up
    to :data:`_TANGENT_STEP`) is blended wherever its blend passes faster than ``v_j``: the model's ``V``, the
    speed reached over half of either neighbour from rest, underestimates the speed through a contour of
    tangent arcs and lines, where no stop is near (measured: the random tangent contours and the rounded
    rectangles of ``tests/interpolators/test_curvature_junctions.py`` ran up to 13 % slower with the model alone).
    ``cap(blends)``, when given, lowers each blend's speed bound (the axes beyond X, Y, Z across it,
    :func:`_blended_extra`). A corner of a rapid and a feed move is never worth it where the control stops there
    (``rapid_feed_stop``, :func:`_rapid_feed_stops`).
    """
    share = 1.0 - JUNCTION_SHARE  # the blend's bound in a chain that may reserve the junction share
    segments, feeds, rapid = ch.segments, np.asarray(ch.feeds), np.asarray(ch.rapid)

    def worth(blends: CornerBlends) -> np.ndarray:
        k = blends.corner
        A_b = share * np.where(blends.plane, lim.acceleration, np.inf).min(axis=1)
        J_b = share * np.where(blends.plane, lim.jerk, np.inf).min(axis=1)
        v_b = curved_speed_bound(blends.curvature, blends.curvature_rate, A_b, J_b, jerk_limited=jerk_limited)
        if cap is not None:
            v_b = np.minimum(v_b, cap(blends))
        V, A, J = np.full(len(k), np.inf), np.full(len(k), np.inf), np.full(len(k), np.inf)
        for i, at in ((k, "end"), (k + 1, "start")):
            lines = [segments[j] for j in i.tolist()]
            v_i, A_i, J_i = line_limits(np.array([_corner_direction(ln, at) for ln in lines]).reshape(-1, 3),
                                        feeds[i], rapid[i], lim)
            half = np.array([0.5 * ln.length for ln in lines])
            reach = reach_many(np.zeros(len(half)), half, A_i, J_i, jerk_limited=jerk_limited)
            V = np.minimum(V, np.minimum(reach, np.minimum(v_i, _curved_bound(lines, A_b, J_b, jerk_limited))))
            A, J = np.minimum(A, A_i), np.minimum(J, J_i)

        kink = np.array([isinstance(b, SplineCurve) for b in blends.blends], dtype=bool)
        v_j = np.zeros(len(k))  # the corner unblended: a stop, or a kink at its junction bound
        if kink.any():
            v_j[kink] = np.minimum(_kink_junction_bound(segments, k[kink], lim, Ts), V[kink])
        faster = (v_b >= V) | _pass_beats(V, v_j, v_b, blends.length, A, J, jerk_limited)
        tangent = np.zeros(len(k), dtype=bool)  # kinks of the program's rounding: curvature steps, faster blended
        if kink.any():
            tangent[kink] = [float(np.linalg.norm(_corner_direction(segments[i + 1], "start")
                                                  - _corner_direction(segments[i], "end"))) <= _TANGENT_STEP
                             for i in k[kink].tolist()]
        faster[kink] = (faster[kink] | tangent[kink]) & (v_b[kink] > v_j[kink])
        return faster & ~_rapid_feed_stops(rapid_feed_stop, rapid[k], rapid[k + 1])

    return worth


def _pass_beats(V: np.ndarray, v_j: np.ndarray, v_b: np.ndarray, length: np.ndarray, A: np.ndarray, J: np.ndarray,
                jerk_limited: bool, passing: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """:func:`_blend_worth`'s model: is a corner passed faster at ``v_b`` over ``length`` (a blend or ramp) than at
    ``v_j`` (0: a stop), from and back to ``V``, with path bounds ``A``, ``J`` (``passing``: those of the speed
    changes to ``v_b``, when lower)? Both compared over the same distance (the shorter one completed at ``V``)."""
    A_b, J_b = (A, J) if passing is None else passing

    def change(dv: np.ndarray, A: np.ndarray, J: np.ndarray) -> np.ndarray:
        if not jerk_limited:
            return dv / A
        return np.where(dv >= A * A / J, dv / A + A / J, 2.0 * np.sqrt(dv / J))

    with np.errstate(divide="ignore", invalid="ignore"):  # v_b >= V: no speed change, passes anyway
        c_stop, c_pass = change(V - v_j, A, J), change(V - v_b, A_b, J_b)
        t_stop, t_pass = 2.0 * c_stop, 2.0 * c_pass + length / v_b
        d_stop, d_pass = (V + v_j) * c_stop, (V + v_b) * c_pass + length
        return t_pass + np.maximum(d_stop - d_pass, 0.0) / V <= t_stop + np.maximum(d_pass - d_stop, 0.0) / V


def _curved_bound(segments: list, A: np.ndarray, J: np.ndarray, jerk_limited: bool) -> np.ndarray:
    """:func:`interpolators.kinematics.curved_speed_bound` of each of ``segments`` (an arc's ``1 / R``, a curve's
    :meth:`toolpaths.geometry.SplineCurve.bounds`) with the path bounds ``A``, ``J``; inf on a line."""
    kappa, dkappa = np.zeros(len(segments)), np.zeros(len(segments))
    for i, seg in enumerate(segments):
        if isinstance(seg, Arc):
            kappa[i] = 1.0 / seg.radius
        elif isinstance(seg, SplineCurve):
            kappa[i], dkappa[i], _ = seg.bounds()
    return curved_speed_bound(kappa, dkappa, A, J, jerk_limited=jerk_limited)


def _kink_junction_bound(segments: list, k: np.ndarray, lim: AxisLimitArrays, Ts: float) -> np.ndarray:
    """The speed [mm/s] at which the junctions ``k`` (between ``segments[k]`` and ``segments[k + 1]``) would pass
    unblended under the S-curve, as :func:`_corner_stops` bounds them: the tangent step within one sample at
    JUNCTION_SHARE of the accelerations, and a curvature step at the larger of the JUNCTION_SHARE rule and
    :func:`interpolators.kinematics.curvature_step_speed_limit` (its smooth jerk taken at the whole limit: a
    lower bound). A tangent junction with a curvature step is thus blended where the blend passes faster."""
    t_end = np.array([_corner_direction(segments[i], "end") for i in k.tolist()]).reshape(-1, 3)
    step = np.array([_corner_direction(segments[i + 1], "start") for i in k.tolist()]).reshape(-1, 3) - t_end
    k_end = np.array([_end_curvature(segments[i], "end") for i in k.tolist()]).reshape(-1, 3)
    k_start = np.array([_end_curvature(segments[i + 1], "start") for i in k.tolist()]).reshape(-1, 3)
    tangent = junction_speed_limit(step, np.zeros_like(step), lim, sample_time=Ts, share=JUNCTION_SHARE,
                                   jerk_limited=False)
    jl = junction_speed_limit(step, k_start - k_end, lim, sample_time=Ts, share=JUNCTION_SHARE, jerk_limited=True)
    kappa = np.maximum(np.linalg.norm(k_end, axis=1), np.linalg.norm(k_start, axis=1))
    csl = curvature_step_speed_limit(t_end, step, k_start - k_end, kappa, np.zeros(len(k)),
                                     np.full(len(k), float(np.min(lim.jerk))), lim, sample_time=Ts,
                                     share=JUNCTION_SHARE)
    return np.minimum(tangent, np.maximum(jl, csl))


def _end_curvature(seg: Line | Arc | SplineCurve, at: str) -> np.ndarray:
    """The curvature vector [1/mm] of ``seg`` at its ``at`` ("start" or "end") end (zero on a line)."""
    if isinstance(seg, Line):
        return np.zeros(3)
    return seg.curvature_at(0.0 if at == "start" else seg.length)


def _corner_direction(seg: Line | Arc | SplineCurve, at: str) -> np.ndarray:
    """The direction of ``seg`` at its ``at`` ("start" or "end") end: a line's direction, a curve's tangent there
    (:func:`_blend_worth` bounds the speed beside a corner as on a line in that direction)."""
    if isinstance(seg, Line):
        return seg.direction
    return seg.tangent_at(0.0 if at == "start" else seg.length)


def _meta(program: Program, profile: str, Ts: float, duration: float) -> dict:
    return {
        "source": program.source,
        "dialect": program.dialect,
        "profile": profile,
        "sample_time": Ts,
        "duration": duration,
        "blocks": len(program.blocks),
    }



