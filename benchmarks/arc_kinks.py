"""Kinks at line/arc and arc/arc junctions under G64: S-curve time against trapezoid time.

Run: ``.venv/bin/python benchmarks/arc_kinks.py [--feed F --tolerance P]`` (default: F1200 P0.01, then F600 P0.05)

A 5 mm line into a full G3 circle of radius 1 mm, then a 5 mm line out of it, each junction turning by the kink
angle; and a G2 half circle of radius 5 mm into a G3 arc of radius 4 mm turned 0.4 rad. Prints, for each program,
the motion duration under the trapezoid and under the S-curve (default limits, measured in the same run), their
ratio and the lowest S-curve path speed within ``tolerance + 0.01`` mm of the kink point.

Under the S-curve such a kink used to be passed at about ``0.1 J Ts^2 / turn`` (a stop); it is now blended by a
G2 quintic within the tolerance where that is faster than the stop (:func:`interpolators.lookahead.blend_corners`,
judged by ``interpolators.interpolate``'s blend model). S-curve times before -> after (trapezoid unchanged):

=====================  ===============  ===============
program                F1200 P0.01      F600 P0.05
=====================  ===============  ===============
line/arc/line 0.1 rad  1.132 -> 1.039   1.870 -> 1.806
line/arc/line 0.3 rad  1.130 -> 1.108   1.866 -> 1.800
line/arc/line 1.0 rad  1.106 -> 1.106   1.844 -> 1.826
arc/arc 0.4 rad        1.183 -> 1.183   2.238 -> 2.203
=====================  ===============  ===============

At F1200 P0.01 the 0.3 rad line/arc kink, the 1.0 rad kinks and the arc/arc kink stay stops: a blend within
0.01 mm is so tight that its speed bound makes it slower than stopping.

With the norm of the jerk vector in the curve bounds (:func:`interpolators.kinematics.curved_speed_bound`; the
path jerk what the norm leaves) the S-curve times are, in the order of the table, 1.017, 1.104, 1.103, 1.169 at
F1200 P0.01 and 1.806, 1.800, 1.800, 2.199 at F600 P0.05.

The tangent cases (kinks 0.0 rad: a line/arc curvature step of 1 1/mm; 20 tangent half circles of radius 0.6 mm
alternating in sense, steps of 3.33 1/mm) were passed at the one-sample rule (``sqrt(J Ts / dk)``, about 3.8 mm/s
between the half circles); their curvature steps are now blended by a curvature ramp within the tolerance where
that passes faster (:func:`interpolators.lookahead._kink_blend`). S-curve seconds before -> after: line/arc/line
0.0 rad 1.071 -> 1.030 (F1200 P0.01), 1.818 -> 1.805 (F600 P0.05); alternating arcs 4.298 -> 3.901 (F1200 P0.01),
5.327 -> 4.892 (F600 P0.05); trapezoid 0.925, 1.734, 2.497, 4.876 s, unchanged.

The alternating arcs' ramps (opposite-sense arcs: a ramp that ends on both arcs with their tangents must overshoot
their curvature) then had their leg bisected to the longest that fits and their shape ranked by the planner's own
bound (:func:`interpolators.kinematics.curved_speed_bound`): 3.901 -> 3.534 s at F1200 P0.01 (the legs of every
ramp between lines and arcs bisected; now of those between opposite-sense arcs only), the ramp's bound 11.88 ->
12.33 mm/s, about what the best piecewise-linear curvature profile within P allows (12.5 mm/s, a linear
program on the linearised offset). Then each chain keeps the faster of its curves' speed at 0.3 and at 0.6 of the
jerk limit (``interpolators.interpolate._faster_jerk_share``). S-curve seconds at the start of that work -> now, in
the table's order: F1200 P0.01 1.030 -> 1.005 (0.0 rad), 1.017 -> 1.003, 1.104 -> 1.088, 1.103, 1.169 (kept),
alternating arcs 3.901 -> 3.028; F600 P0.05 1.805, 1.806, 1.800 (kept), 1.801 -> 1.778, 2.199, 4.892 (kept).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from interpolators import interpolate, parse_program  # noqa: E402
from interpolators.context import INTERPOLATION_CONTEXT  # noqa: E402


def line_arc_line(turn: float, feed: float, tolerance: float) -> str:
    """Line, full circle of radius 1 mm at (1, 0) (tangent +Y there), line; both junctions turn by ``turn``."""
    dx, dy = math.sin(turn), math.cos(turn)
    return (f"G21 G90 G17 G64 P{tolerance}\nG0 X{1 - 5 * dx:.6f} Y{-5 * dy:.6f}\nF{feed:.0f}\nG1 X1 Y0\n"
            f"G3 X1 Y0 I-1 J0\nG1 X{1 + 5 * dx:.6f} Y{5 * dy:.6f}\nM30\n")


def arc_arc(feed: float, tolerance: float) -> str:
    """G2 half circle of radius 5 mm ending at (10, 0) along -Y, then a G3 of radius 4 mm turned 0.4 rad."""
    c = (4.0 * math.cos(0.4), 4.0 * math.sin(0.4))
    end = math.pi + 0.4 + 1.5
    return (f"G21 G90 G17 G64 P{tolerance}\nG0 X0 Y0\nF{feed:.0f}\nG2 X10 Y0 I5 J0\n"
            f"G3 X{10 + c[0] + 4 * math.cos(end):.6f} Y{c[1] + 4 * math.sin(end):.6f} I{c[0]:.6f} J{c[1]:.6f}\nM30\n")


def alternating_arcs(feed: float, tolerance: float, n: int = 20, radius: float = 0.6) -> str:
    """A line along +Y into ``n`` tangent half circles of ``radius`` alternating in sense along X, then a line:
    tangent junctions with curvature steps of ``2 / radius`` (no kink)."""
    arcs = "".join(f"G{2 if k % 2 == 0 else 3} X{2 * radius * (k + 1):.4f} Y0 R{radius}\n" for k in range(n))
    return (f"G21 G90 G17 G64 P{tolerance}\nG0 X0 Y-5\nF{feed:.0f}\nG1 X0 Y0\n{arcs}"
            f"G1 X{2 * radius * n:.4f} Y{5.0 if n % 2 == 0 else -5.0}\nM30\n")


def with_a(text: str, rate: float | None, *, before: str | None = None) -> str:
    """``text`` with A turning ``rate`` deg per mm of path on every feed move (None: A still), and the feed move
    ``before`` (e.g. ``G1 Z-1 A5``) ahead of its first feed move: a 4-axis chain (the axes beyond X, Y, Z take part
    in the look-ahead, :mod:`interpolators.axis_blends`)."""
    prog = parse_program(text, context=INTERPOLATION_CONTEXT)
    feed_lines = {b.line: b.segment.length for b in prog.blocks if b.kind in ("line", "arc")}
    out, a = [], 0.0
    for number, line in enumerate(text.splitlines(), start=1):
        if before is not None and number == min(feed_lines):
            out.append(before)
        if number in feed_lines and rate is not None:
            a += rate * feed_lines[number]
            line += f" A{a:.4f}"
        out.append(line)
    return "\n".join(out) + "\n"


def rotary_cases(feed: float, tolerance: float) -> None:
    """The tangent and kinked cases with A moving (0.5 deg/mm on every block), and the alternating arcs after one
    move ``G1 Z-1 A5`` (A still on them), each against the same program without A (its ``G1 Z-1`` instead), under the
    S-curve at 1 and 0.25 ms. Before session 33 chains moving A left their line/arc kinks and curvature steps to the
    one-sample rule and planned their curves at 0.3 of the jerk limits only; ratios to the time without A at 1 / 0.25
    ms, before -> after: F1200 P0.01 line/arc/line 0.0 rad 1.066 / 1.096 -> 1.000 / 1.000, 0.1 rad 1.126 / 1.126 ->
    1.000 / 1.000, alternating arcs after the A move 1.431 / 1.562 -> 1.024 / 1.024 (the A move's own 0.075 s:
    3.118 + 0.075 = 3.193 s); F600 P0.05 1.007 / 1.019, 1.033 / 1.032, 1.096 / 1.141 -> 1.000, 1.000, 1.009."""
    cases = [(f"line/arc/line {t} rad with A", with_a(line_arc_line(t, feed, tolerance), 0.5),
              with_a(line_arc_line(t, feed, tolerance), None)) for t in (0.0, 0.1)]
    arcs = alternating_arcs(feed, tolerance)
    cases.append(("alternating arcs after G1 Z-1 A5", with_a(arcs, None, before="G1 Z-1 A5"),
                  with_a(arcs, None, before="G1 Z-1")))
    for name, text, reference in cases:
        prog, ref = (parse_program(t, context=INTERPOLATION_CONTEXT) for t in (text, reference))
        for Ts in (1e-3, 2.5e-4):
            sp, sp0 = (interpolate(p, profile="scurve", sample_time=Ts) for p in (prog, ref))
            print(f"{name:34s} F{feed:.0f} P{tolerance} Ts {Ts * 1e3:g} ms: S-curve {sp.duration:.3f} s, without A "
                  f"{sp0.duration:.3f} s, ratio {sp.duration / sp0.duration:.3f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--feed", type=float, help="feed [mm/min]")
    ap.add_argument("--tolerance", type=float, help="G64 P [mm]")
    args = ap.parse_args()
    settings = [(1200.0, 0.01), (600.0, 0.05)]
    if args.feed is not None or args.tolerance is not None:
        settings = [(args.feed or 1200.0, args.tolerance or 0.01)]
    for feed, tolerance in settings:
        cases = [(f"line/arc/line, kinks {t} rad", line_arc_line(t, feed, tolerance), (1.0, 0.0))
                 for t in (0.0, 0.1, 0.3, 1.0)]
        cases.append(("arc/arc, kink 0.4 rad", arc_arc(feed, tolerance), (10.0, 0.0)))
        cases.append(("20 tangent R0.6 arcs, alternating", alternating_arcs(feed, tolerance), (1.2, 0.0)))
        for name, text, kink in cases:
            prog = parse_program(text)
            trap, scurve = (interpolate(prog, profile=p) for p in ("trapezoid", "scurve"))
            near = np.linalg.norm(scurve.position[:, :2] - np.asarray(kink), axis=1) <= tolerance + 0.01
            v = float(np.linalg.norm(scurve.velocity[near][:, :2], axis=1).min()) if near.any() else math.nan
            print(f"{name:30s} F{feed:.0f} P{tolerance}: trapezoid {trap.duration:.3f} s, S-curve "
                  f"{scurve.duration:.3f} s, S-curve / trapezoid {scurve.duration / trap.duration:.3f}; "
                  f"S-curve speed at the kink {v:.2f} mm/s")
        rotary_cases(feed, tolerance)


if __name__ == "__main__":
    main()
