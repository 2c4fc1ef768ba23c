"""Dense CAM code under G64: a circle as one G3 arc against the same circle as 10,000 chords.

Run: ``.venv/bin/python benchmarks/dense_code.py [--chords N] [--feed F] [--decimals D] [--tangent-entry L]
[--helix-radius R] [--helix-chord L] [--coarse-radius R] [--coarse-chord L] [--coarse-feed F]``

Prints, for each profile, the motion duration of the single arc and of the chord polygon, their
ratio (issue #18 item 8 asks for <= 1.25), the worst distance of the setpoints from the
programmed chords (nearest of the two chords at the nearest chord end point),
the worst axis velocity/acceleration (and, S-curve, jerk) utilisation from finite differences of
the sampled positions, and the interpolation CPU time (setpoints/s).

Under G64 the chords are merged into one smooth curve within the tolerance
(:mod:`interpolators.dense`); before that (per-junction blends only) the ratios were 3.71
(trapezoid) and 28.5 (S-curve). ``--tangent-entry 10`` enters the circle along its tangent (a line
into the arc or into the merged curve: a curvature jump, passed at speed under the S-curve by
:func:`interpolators.kinematics.curvature_step_speed_limit`).

Then the same for a small-radius helix, as FreeCAD writes a helical entry (``--helix-radius`` 0.24 mm, 0.05 mm
chords with 3 decimals, 20 turns down 0.12 mm each, F400, G64 without P): one G2 with P against its chords, each
turning by 0.21 rad, more than :data:`interpolators.dense.DENSE_MAX_TURN`. Before tight curves were merged under
the S-curve (:func:`interpolators.dense.curve_junctions`) the S-curve ran them in 1.966 times the arc's time, then
1.006, now 1.002 with the kinks between the merged pieces blended (:func:`interpolators.lookahead.blend_corners`;
0.996 with the trapezoid, unchanged).

Then a helix of coarse chords (``--coarse-radius`` 1 mm, ``--coarse-chord`` 0.15 mm, 4 decimals, 5 turns,
``--coarse-feed`` F1200): each chord turns by 0.15 rad, and turn times length is 2.25 times the tolerance, above
:data:`interpolators.dense.DENSITY`. Before such chords merged under the S-curve
(:data:`interpolators.dense.CURVE_DENSITY`) the S-curve ran them in 2.348 times the arc's time (per-junction
clothoid blends), now 1.007; the trapezoid, unchanged, 0.998. The last line of each case is the S-curve time over
the trapezoid time of the same chords, measured in the same run.

Then 4- and 5-axis dense code (:func:`rotary_programs`): a helix with A, a 5-axis swarf-like chain with A and C,
A reversing along an S, a cylinder wrap in X and A; their time over the same X, Y, Z without the rotary axes
and S-curve over trapezoid. Before their runs were merged with the rotary axes the helix with A took 1.97
(trapezoid) and 5.93 (S-curve) times its time without A, the S-curve 3.07 times the trapezoid.

Then tight fillets as FreeCAD writes a tool-compensated profile (corpus program 0274): a 3 mm square of 0.25 mm
chords at F600 whose corners are fillets of radius 0.1 mm in 10 chords (3 decimals), and two laps of a circle of
30 um chords whose turns alternate 0.1 / 0.22 rad (the rounding of short chords), with the same laps as G3 arcs.
S-curve / trapezoid time of the fillets 2.939 before the merged curve was cut where its speed bound changes
(:func:`interpolators.dense._bound_breaks`), then 1.224; of the circle 3.888 (2.513 times its arcs) before a tight
curve's junction counted its two neighbours' turns together (:func:`interpolators.dense.curve_junctions`), then
1.884 (1.218 times its arcs); with the jerk vector's norm in the curve bounds
(:func:`interpolators.kinematics.curved_speed_bound`) 1.156 and 1.790 (1.165 times its arcs), the 10,000 chords'
S-curve 1.212 -> 1.155 s. Trapezoid times unchanged. With each chain keeping the faster of its curves' speed at
0.3 and at 0.6 of the jerk limit (``interpolators.interpolate._faster_jerk_share``) the fillets' S-curve 1.530 ->
1.490 s (1.056 -> 1.028 times the trapezoid), the circle's chords 0.470 -> 0.431 s and its G3 arcs 0.424 -> 0.407 s.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from interpolators import (  # noqa: E402
    DEFAULT_LIMITS,
    DEFAULT_ROTARY_LIMITS,
    DEFAULT_SECONDARY_LIMITS,
    interpolate,
    parse_program,
)

LIMITS = {**DEFAULT_LIMITS, **DEFAULT_ROTARY_LIMITS, **DEFAULT_SECONDARY_LIMITS}


def _programs(n: int, feed: float, decimals: int, lead: float = 0.0) -> tuple[str, str, float]:
    """Single-arc and n-chord programs of a circle with 8 um chords (end points written with
    ``decimals`` decimals, as CAM output is), and its radius [mm]. With ``lead`` > 0 the circle is
    entered along its tangent by a line of that length [mm] (a tangent junction with a curvature jump:
    line/arc, line/merged curve), else from the origin at a right angle."""
    r = n * 0.008 / (2 * math.pi)
    entry = f"G1 X{r:.6f} Y0 F{feed * 60:.1f}"
    if lead > 0:
        entry = f"G1 X{r:.6f} Y{-lead:.6f} F{feed * 60:.1f}\nG1 X{r:.6f} Y0"
    arc = f"G21 G90 G17 G64 P0.01\n{entry}\nG3 X{r:.6f} Y0 I{-r:.6f} J0\n"
    lines = [f"G21 G90 G17 G64 P0.01\n{entry}"]
    for k in range(1, n + 1):
        a = 2 * math.pi * k / n
        lines.append(f"G1 X{r * math.cos(a):.{decimals}f} Y{r * math.sin(a):.{decimals}f}")
    return arc, "\n".join(lines) + "\n", r


def _chord_points(n: int, r: float, decimals: int, lead: float = 0.0) -> np.ndarray:
    """The programmed path's points (x, y) [mm]: the origin (where programs start), the lead-in's start
    when ``lead`` > 0, the circle's start point, then the chord end points rounded as written."""
    a = 2 * np.pi * np.arange(n + 1) / n
    pts = np.round(np.c_[r * np.cos(a), r * np.sin(a)], decimals)
    pts[0] = (r, 0.0)
    head = [(0.0, 0.0), (r, -lead)] if lead > 0 else [(0.0, 0.0)]
    return np.vstack([head, pts])


def _chord_deviation(sp, pts: np.ndarray, first_block: int = 0) -> float:
    """Worst distance [mm] of the setpoints of blocks ``first_block`` on from the chord polygon ``pts``:
    for each setpoint, the nearer of the two chords meeting at its nearest chord end point (a tangent
    lead-in, a long line, is left out: its nearest end point may be a chord's)."""
    from scipy.spatial import cKDTree

    on = sp.block >= first_block
    xy = np.c_[sp.position[on, sp.axis_index("x")], sp.position[on, sp.axis_index("y")]]
    _, k = cKDTree(pts).query(xy)
    best = np.full(len(xy), np.inf)
    for j0 in (k - 1, k):
        j0 = np.clip(j0, 0, len(pts) - 2)
        a, b = pts[j0], pts[j0 + 1]
        ab = b - a
        t = np.clip(((xy - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(xy - a - t[:, None] * ab).T))
    return float(best.max())


def _helix_programs(radius: float, chord: float, decimals: int = 3, turns: int = 20,
                    pitch: float = 0.12, feed: float = 400.0) -> tuple[str, str]:
    """The helix as one G2 with P and as chords ``chord`` [mm] long (end points with ``decimals`` decimals),
    down ``pitch`` [mm] per turn from Z1, at ``feed`` [mm/min]."""
    n_turn = round(2 * math.pi * radius / chord)
    a = 2 * np.pi * np.arange(1, turns * n_turn + 1) / n_turn
    pts = np.c_[radius * np.cos(a), -radius * np.sin(a), 1.0 - pitch * a / (2 * np.pi)]  # clockwise, as the G2
    head = f"G21 G90 G17 G64\nG0 X{radius} Y0 Z1\n"
    arc = head + f"G2 X{radius} Y0 I{-radius} J0 Z{1.0 - turns * pitch:.4f} P{turns} F{feed:g}\nM2\n"
    f = f"{{:.{decimals}f}}"
    chords = head + f"G1 F{feed:g}\n" + "\n".join(f"G1 X{f.format(x)} Y{f.format(y)} Z{f.format(z)}"
                                          for x, y, z in pts) + "\nM2\n"
    return arc, chords


def _path_deviation(sp, step: float = 2e-4) -> float:
    """Worst distance [mm] of the setpoints from the programmed path (its points ``step`` apart)."""
    from scipy.spatial import cKDTree

    xyz = np.zeros((len(sp), 3))  # an axis the setpoints lack stayed at 0
    for i, a in enumerate("xyz"):
        if a in sp.axes:
            xyz[:, i] = sp.position[:, sp.axis_index(a)]
    path = sp.meta.get("programmed_path", sp.path)  # no corner blended: the path followed is the programmed one
    return float(cKDTree(path.points(step=step)).query(xyz)[0].max()) - step / 2


def _utilisation(sp, Ts: float) -> tuple[float, float, float]:
    """Worst |v|/v_max, |a|/a_max and |j|/j_max over the axes of the setpoints from finite differences."""
    uv = ua = uj = 0.0
    for ax in sp.axes:
        p = sp.position[:, sp.axis_index(ax)]
        v = np.diff(p) / Ts
        a = np.diff(v) / Ts
        j = np.diff(a) / Ts
        lim = LIMITS[ax]
        uv = max(uv, float(np.max(np.abs(v))) / lim.velocity)
        ua = max(ua, float(np.max(np.abs(a))) / lim.acceleration)
        uj = max(uj, float(np.max(np.abs(j))) / lim.jerk)
    return uv, ua, uj


def fillet_square(radius: float = 0.1, chords: int = 10) -> str:
    """A 3 mm square of 0.25 mm chords at F600, each corner a fillet of ``radius`` written as ``chords`` chords
    with 3 decimals (as FreeCAD writes a tool-compensated profile's fillets)."""
    out = ["G21 G90 G17 G64 P0.01", "G0 X0 Y0"]
    x, y, hx, hy = 0.0, 0.0, 1, 0
    for _ in range(4):
        out += [f"G1 X{x + hx * 0.25 * k:.3f} Y{y + hy * 0.25 * k:.3f} F600" for k in range(1, 12)]
        x, y = x + hx * 3.0, y + hy * 3.0
        cx, cy = x - hy * radius, y + hx * radius
        a0 = math.atan2(y - cy, x - cx)
        out += [f"G1 X{cx + radius * math.cos(a0 + 0.5 * math.pi * k / chords):.3f} "
                f"Y{cy + radius * math.sin(a0 + 0.5 * math.pi * k / chords):.3f}" for k in range(1, chords + 1)]
        x, y = cx + radius * math.cos(a0 + 0.5 * math.pi), cy + radius * math.sin(a0 + 0.5 * math.pi)
        hx, hy = -hy, hx
    return "\n".join([*out, "M2"]) + "\n"


def alternating_circle(turns: tuple[float, float] = (0.1, 0.22), laps: int = 2) -> tuple[str, str]:
    """Two laps of a circle of 30 um chords whose turns alternate (rounded points of short chords) from a tangent
    entry line at F600, and the same laps as G3 arcs of the mean turn's radius."""
    chord = 0.03
    out = ["G21 G90 G17 G64 P0.01", "G0 X0 Y0", "G1 X0.3 Y0 F600"]
    p, h, k, turned = np.array([0.3, 0.0]), 0.5 * math.pi, 0, 0.0
    while turned < 2.0 * math.pi * laps:
        p = p + chord * np.array([math.cos(h), math.sin(h)])
        out.append(f"G1 X{p[0]:.4f} Y{p[1]:.4f}")
        h, turned, k = h + turns[k % 2], turned + turns[k % 2], k + 1
    r = chord / (2.0 * math.sin(0.25 * sum(turns)))
    arcs = "".join(f"G3 X0.3 Y0 I{-r:.4f} J0\n" for _ in range(laps))
    return "\n".join([*out, "M2"]) + "\n", f"G21 G90 G17 G64 P0.01\nG0 X0 Y0\nG1 X0.3 Y0 F600\n{arcs}M2\n"


def _fillet_cases(Ts: float) -> None:
    """Tight fillets of CAM chords: the square of 0.1 mm fillets in 10 chords, and the circle of alternating turns
    (with its G3 reference); S-curve / trapezoid time of the same chords, measured in this run."""
    circle, circle_arcs = alternating_circle()
    for name, text, ref in (("fillets", fillet_square(), None), ("alternating circle", circle, circle_arcs)):
        took = {}
        for profile in ("trapezoid", "scurve"):
            sp = interpolate(parse_program(text), profile=profile)
            took[profile] = sp.duration
            uv, ua, uj = _utilisation(sp, Ts)
            against = ""
            if ref is not None:
                arc = interpolate(parse_program(ref), profile=profile).duration
                against = f", G3 arcs {arc:.3f} s, ratio {sp.duration / arc:.3f}"
            print(f"{profile:9s}: {name}: chords {sp.duration:.3f} s{against}; worst deviation from the chords "
                  f"{_path_deviation(sp) * 1e3:.2f} um (tolerance 10 um); worst v {uv:.3f}, a {ua:.3f}"
                  + (f", j {uj:.3f}" if profile == "scurve" else "") + " of the axis limits")
        print(f"{name}: chords S-curve / trapezoid time {took['scurve'] / took['trapezoid']:.3f}")


def rotary_programs(shape: str, rotary: bool) -> str:
    """4- and 5-axis dense CAM code under G64 P0.01 (``rotary``: with its A/C words, else X, Y, Z only):
    ``helix`` 400 chords of a two-lap R10 helix at F2000 (A 0 -> 90 deg), ``swarf`` 500 chords of an
    ellipse rising and falling in Z at F3000 (A tilting +-15 deg, C turning once), ``reversal`` 400 chords of
    0.2 mm along an S at F2400 (A swinging +-30 deg), ``wrap`` a groove on a cylinder of radius 20 mm, 600
    chords of 0.1 mm in X at F1500 with A turning up to 19 deg per mm (without A: X alone); under G64 P0.05 chords
    too coarse to merge, their corners blended across every axis: ``coarse`` the helix in 60 chords, ``corners``
    two laps of a 24-gon of radius 20 mm at F2000, A up 1 deg on one side and back on the next; with A on some
    blocks only (4-axis CAM output): ``indexed`` 40 lines of 10 mm zigzagging 1 mm at F3000, A up 5 deg on every
    other one, ``arcs`` two laps of a 30 x 40 mm rectangle of R10 corners (G3, tangent to its sides) at F3000, A up
    10 deg on each arc, under G64 P0.05, and ``staircase`` the helix with A up 2.25 deg on every tenth chord."""
    lines = {"helix": ["G0 X10 Y0 Z0 A0", "G1 F2000"], "swarf": ["G0 X30 Y0 Z0 A0 C0", "G1 F3000"],
             "reversal": ["G0 X0 Y0 A0", "G1 F2400"], "wrap": ["G0 X0 Y0 A0", "G1 F1500"],
             "coarse": ["G0 X10 Y0 Z0 A0", "G1 F2000"], "corners": ["G0 X20 Y0 A0", "G1 F2000"],
             "indexed": ["G0 X0 Y0 A0", "G1 F3000"], "arcs": ["G0 X0 Y0 A0", "F3000"],
             "staircase": ["G0 X10 Y0 Z0 A0", "G1 F2000"]}[shape]
    n = {"helix": 400, "swarf": 500, "reversal": 400, "wrap": 600, "coarse": 60, "corners": 48, "indexed": 40,
         "arcs": 16, "staircase": 400}[shape]
    for i in range(1, n + 1):
        if shape in ("helix", "coarse", "staircase"):
            t = 4 * math.pi * i / n
            turned = 90 * i / n if shape != "staircase" else (2.25 * (i // 10) if i % 10 == 0 else None)
            xyz = f"X{10 * math.cos(t):.4f} Y{10 * math.sin(t):.4f} Z{-0.5 * i / n:.4f}"
            rot = "" if turned is None else f"A{turned:.4f}"
        elif shape == "indexed":
            xyz, rot = f"X{10 * i} Y{i % 2}", (f"A{5 * (i // 2)}" if i % 2 == 0 else "")
        elif shape == "arcs":
            xyz = ["G1 X20 Y0", "G3 X30 Y10 I0 J10", "G1 X30 Y30", "G3 X20 Y40 I-10 J0", "G1 X0 Y40",
                   "G3 X-10 Y30 I0 J-10", "G1 X-10 Y10", "G3 X0 Y0 I10 J0"][(i - 1) % 8]
            rot = f"A{10 * (i // 2)}" if i % 2 == 0 else ""
        elif shape == "swarf":
            t = 2 * math.pi * i / n
            xyz = f"X{30 * math.cos(t):.4f} Y{20 * math.sin(t):.4f} Z{2 * math.sin(2 * t):.4f}"
            rot = f"A{15 * math.sin(t):.4f} C{math.degrees(t):.4f}"
        elif shape == "corners":
            t = 2 * math.pi * i / 24
            xyz, rot = f"X{20 * math.cos(t):.4f} Y{20 * math.sin(t):.4f}", f"A{i % 2:.4f}"
        elif shape == "reversal":
            xyz, rot = f"X{0.2 * i:.4f} Y{3 * math.sin(0.2 * i / 8):.4f}", f"A{30 * math.sin(0.2 * i / 10):.4f}"
        else:
            w = 40 * math.sin(0.1 * i / 6)
            xyz, rot = f"X{0.1 * i:.4f}", f"A{math.degrees(w / 20):.4f}"
        lines.append(xyz + (" " + rot if rotary and rot else ""))
    return "\n".join([f"G21 G90 G64 P{ROTARY_TOLERANCE.get(shape, 0.01)}", *lines, "M2"]) + "\n"


#: G64 P of the cases of :func:`rotary_programs` that are not P0.01 [mm].
ROTARY_TOLERANCE = {"coarse": 0.05, "corners": 0.05, "indexed": 0.05, "arcs": 0.05}


def _rotary_cases(Ts: float) -> None:
    """The 4- and 5-axis cases of :func:`rotary_programs`: time with the rotary axes over the time without
    (the same X, Y, Z; the wrap: over the time its velocity limits require, each chord at the feed or where A
    binds at ``V_A / |dA/dx|``) and S-curve over trapezoid, measured in this run.
    Before their runs were merged with the axes beyond X, Y, Z (each chord junction at the one-sample rule):
    helix with A 7.750 s trapezoid, 23.788 s S-curve (3.929 s, 4.011 s without A); wrap 23.275 s, 59.771 s;
    swarf 8.197 s, 43.789 s (3.464 s, 3.549 s without); reversal 8.110 s, 27.568 s (2.092 s, 2.129 s).
    Before their corners were blended across every axis (each at the one-sample rule or a stop): coarse 4.854 s,
    7.087 s (3.913 s, 3.993 s without A); corners 8.472 s, 10.148 s (7.723 s, 7.801 s).
    Before a chain kept the blocks leaving A still and carried A's rate steps on ramps (a stop wherever A started
    or stopped, or its rate stepped between a line and an arc): indexed 9.040 s trapezoid (8.060 s without A), now
    8.311 s; arcs 6.120 s (5.739 s), now 5.935 s. Their S-curve times are unchanged (10.600 s, 6.800 s): within
    P0.05 deg a step of 0.5 deg/mm is bent within A's jerk limit below about 14 mm/s only, slower than a stop. The
    staircase (7.062 s, 10.747 s against 3.929 s, 4.011 s without A) is unchanged: A's 7 deg/mm steps within
    P0.01 deg pass at about 2.6 mm/s at best (A's jerk), each A chord near a stop either way."""
    from interpolators.context import INTERPOLATION_CONTEXT

    for shape in ("helix", "swarf", "reversal", "wrap", "coarse", "corners", "indexed", "arcs", "staircase"):
        took = {}
        for rotary in (False, True):
            prog = parse_program(rotary_programs(shape, rotary), context=INTERPOLATION_CONTEXT)
            for profile in ("trapezoid", "scurve"):
                t0 = time.process_time()
                sp = interpolate(prog, profile=profile)
                cpu = time.process_time() - t0
                took[rotary, profile] = sp.duration
                if shape == "wrap" and not rotary:  # the time A's velocity limit requires instead
                    a = np.array([round(math.degrees(2 * math.sin(0.1 * i / 6)), 4) for i in range(601)])
                    rate = np.abs(np.diff(a)) / 0.1
                    took[rotary, profile] = float(np.sum(0.1 / np.minimum(25.0, LIMITS["a"].velocity
                                                                          / np.maximum(rate, 1e-12))))
                if rotary:
                    uv, ua, uj = _utilisation(sp, Ts)
                    print(f"{profile:9s}: {shape} with {'/'.join(a for a in sp.axes if a in 'abc')}: "
                          f"{sp.duration:.3f} s, {'A velocity bound' if shape == 'wrap' else 'without'} "
                          f"{took[False, profile]:.3f} s, ratio "
                          f"{sp.duration / took[False, profile]:.3f}; worst deviation from the chords "
                          f"{_path_deviation(sp) * 1e3:.2f} um "
                          f"(tolerance {ROTARY_TOLERANCE.get(shape, 0.01) * 1e3:.0f} um); "
                          f"worst v {uv:.3f}, a {ua:.3f}"
                          + (f", j {uj:.3f}" if profile == "scurve" else "") + f" of the axis limits; {cpu:.2f} s CPU")
        print(f"{shape}: with the rotary axes S-curve / trapezoid time "
              f"{took[True, 'scurve'] / took[True, 'trapezoid']:.3f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chords", type=int, default=10_000)
    ap.add_argument("--feed", type=float, default=200.0, help="feed [mm/s]")
    ap.add_argument("--decimals", type=int, default=4, help="decimals of the chord end points (CAM output: 4)")
    ap.add_argument("--tangent-entry", type=float, default=0.0, metavar="L",
                    help="enter the circle along its tangent by a line of L mm (default: from the origin, at 90 deg)")
    ap.add_argument("--helix-radius", type=float, default=0.24, help="radius of the helix case [mm]")
    ap.add_argument("--helix-chord", type=float, default=0.05, help="chord length of the helix case [mm]")
    ap.add_argument("--coarse-radius", type=float, default=1.0, help="radius of the coarse-chord helix [mm]")
    ap.add_argument("--coarse-chord", type=float, default=0.15, help="chord length of the coarse-chord helix [mm]")
    ap.add_argument("--coarse-feed", type=float, default=1200.0, help="feed of the coarse-chord helix [mm/min]")
    args = ap.parse_args()
    arc_text, chord_text, r = _programs(args.chords, args.feed, args.decimals, args.tangent_entry)
    Ts = 1e-3
    for profile in ("trapezoid", "scurve"):
        sp_arc = interpolate(parse_program(arc_text), profile=profile)
        t0 = time.process_time()
        sp = interpolate(parse_program(chord_text), profile=profile)
        cpu = time.process_time() - t0
        ratio = sp.duration / sp_arc.duration
        uv, ua, uj = _utilisation(sp, Ts)
        dev = _chord_deviation(sp, _chord_points(args.chords, r, args.decimals, args.tangent_entry),
                               2 if args.tangent_entry > 0 else 0)
        util = (f"worst deviation from the chords {dev * 1e3:.2f} um (tolerance 10 um); "
                f"worst v {uv:.3f}, a {ua:.3f}" + (f", j {uj:.3f}" if profile == "scurve" else "")
                + " of the axis limits")
        print(f"{profile:9s}: arc {sp_arc.duration:.3f} s, {args.chords} chords {sp.duration:.3f} s, "
              f"ratio {ratio:.2f} (target <= 1.25); {util}; "
              f"{len(sp):,} setpoints in {cpu:.2f} s CPU = {len(sp) / cpu:,.0f} setpoints/s; radius {r:.3f} mm")

    cases = (("helix", _helix_programs(args.helix_radius, args.helix_chord), args.helix_radius, args.helix_chord),
             ("coarse", _helix_programs(args.coarse_radius, args.coarse_chord, decimals=4, turns=5,
                                        feed=args.coarse_feed), args.coarse_radius, args.coarse_chord))
    for name, (arc_text, chord_text), radius, chord in cases:
        took = {}
        for profile in ("trapezoid", "scurve"):
            sp_arc = interpolate(parse_program(arc_text), profile=profile)
            sp = interpolate(parse_program(chord_text), profile=profile)
            took[profile] = sp.duration
            uv, ua, uj = _utilisation(sp, Ts)
            print(f"{profile:9s}: {name} r {radius} mm, {chord * 1e3:.0f} um chords: arc "
                  f"{sp_arc.duration:.3f} s, chords {sp.duration:.3f} s, ratio {sp.duration / sp_arc.duration:.3f}; "
                  f"worst deviation from the chords {_path_deviation(sp) * 1e3:.2f} um (tolerance 10 um); worst v "
                  f"{uv:.3f}, a {ua:.3f}" + (f", j {uj:.3f}" if profile == "scurve" else "") + " of the axis limits")
        print(f"{name}: chords S-curve / trapezoid time {took['scurve'] / took['trapezoid']:.3f}")
    _fillet_cases(Ts)
    _rotary_cases(Ts)


if __name__ == "__main__":
    main()
