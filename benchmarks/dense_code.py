"""Dense CAM code under G64: a circle as one G3 arc against the same circle as 10,000 chords.

Run: ``.venv/bin/python benchmarks/dense_code.py [--chords N] [--feed F] [--decimals D]``

Prints, for each profile, the motion duration of the single arc and of the chord polygon, their
ratio (issue #18 item 8 asks for <= 1.25), the worst distance of the setpoints from the
programmed chords (not yet printed), the worst axis velocity/acceleration utilisation from finite differences of
the sampled positions, and the interpolation CPU time (setpoints/s).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from interpolators import DEFAULT_LIMITS, interpolate, parse_program  # noqa: E402


def _programs(n: int, feed: float, decimals: int) -> tuple[str, str, float]:
    """Single-arc and n-chord programs of a circle with 8 um chords (end points written with
    ``decimals`` decimals, as CAM output is), and its radius [mm]."""
    r = n * 0.008 / (2 * math.pi)
    arc = f"G21 G90 G17 G64 P0.01\nG1 X{r:.6f} Y0 F{feed * 60:.1f}\nG3 X{r:.6f} Y0 I{-r:.6f} J0\n"
    lines = [f"G21 G90 G17 G64 P0.01\nG1 X{r:.6f} Y0 F{feed * 60:.1f}"]
    for k in range(1, n + 1):
        a = 2 * math.pi * k / n
        lines.append(f"G1 X{r * math.cos(a):.{decimals}f} Y{r * math.sin(a):.{decimals}f}")
    return arc, "\n".join(lines) + "\n", r


def _utilisation(sp, Ts: float) -> tuple[float, float]:
    """Worst |v|/v_max and |a|/a_max over the x and y axes from finite differences."""
    uv = ua = 0.0
    for ax in ("x", "y"):
        p = sp.position[:, sp.axis_index(ax)]
        v = np.diff(p) / Ts
        a = np.diff(v) / Ts
        lim = DEFAULT_LIMITS[ax]
        uv = max(uv, float(np.max(np.abs(v))) / lim.velocity)
        ua = max(ua, float(np.max(np.abs(a))) / lim.acceleration)
    return uv, ua


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chords", type=int, default=10_000)
    ap.add_argument("--feed", type=float, default=200.0, help="feed [mm/s]")
    ap.add_argument("--decimals", type=int, default=4, help="decimals of the chord end points (CAM output: 4)")
    args = ap.parse_args()
    arc_text, chord_text, r = _programs(args.chords, args.feed, args.decimals)
    Ts = 1e-3
    for profile in ("trapezoid", "scurve"):
        sp_arc = interpolate(parse_program(arc_text), profile=profile)
        t0 = time.process_time()
        sp = interpolate(parse_program(chord_text), profile=profile)
        cpu = time.process_time() - t0
        ratio = sp.duration / sp_arc.duration
        uv, ua = _utilisation(sp, Ts)
        util = f"worst v {uv:.3f}, a {ua:.3f} of the axis limits"
        print(f"{profile:9s}: arc {sp_arc.duration:.3f} s, {args.chords} chords {sp.duration:.3f} s, "
              f"ratio {ratio:.2f} (target <= 1.25); {util}; "
              f"{len(sp):,} setpoints in {cpu:.2f} s CPU = {len(sp) / cpu:,.0f} setpoints/s; radius {r:.3f} mm")


if __name__ == "__main__":
    main()
