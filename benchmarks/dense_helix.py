"""Dense CAM code on tight curves: a small-radius helix as one G2 with P against the same helix as chords.

Run: ``.venv/bin/python benchmarks/dense_helix.py [--radius R] [--chord L] [--decimals D] [--turns N]``

A helical entry as FreeCAD writes it (0.05 mm chords on a radius of 0.24 mm, 3 decimals, F400, G64
without P): each chord turns by 0.21 rad, more than :data:`interpolators.dense.DENSE_MAX_TURN`. Prints, for
each profile, the duration of the single arc and of the chords measured in the same run, their ratio, the
worst distance of the setpoints from the programmed chords, the worst axis velocity/acceleration (and,
S-curve, jerk) over its limit from finite differences of the sampled positions, and the interpolation CPU
time. Before tight curves were merged under the S-curve (:func:`interpolators.dense.curve_junctions`) the
default helix ran 1.966 times the arc's time with the S-curve, now 1.006 (0.996 with the trapezoid, unchanged).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402
from scipy.spatial import cKDTree  # noqa: E402

from interpolators import DEFAULT_LIMITS, interpolate, parse_program  # noqa: E402


def _programs(radius: float, chord: float, decimals: int, turns: int, pitch: float) -> tuple[str, str]:
    """The helix as one G2 with P and as chords ``chord`` [mm] long (end points with ``decimals`` decimals),
    down ``pitch`` [mm] per turn from Z1."""
    n_turn = round(2 * math.pi * radius / chord)
    a = 2 * np.pi * np.arange(1, turns * n_turn + 1) / n_turn
    pts = np.c_[radius * np.cos(a), radius * np.sin(a), 1.0 - pitch * a / (2 * np.pi)]
    head = f"G21 G90 G17 G64\nG0 X{radius} Y0 Z1\n"
    arc = head + f"G2 X{radius} Y0 I{-radius} J0 Z{1.0 - turns * pitch:.4f} P{turns} F400\nM2\n"
    f = f"{{:.{decimals}f}}"
    chords = head + "G1 F400\n" + "\n".join(f"G1 X{f.format(x)} Y{f.format(y)} Z{f.format(z)}"
                                          for x, y, z in pts) + "\nM2\n"
    return arc, chords


def _deviation(sp, step: float = 2e-4) -> float:
    """Worst distance [mm] of the setpoints from the programmed path (its points ``step`` apart)."""
    xyz = sp.position[:, [sp.axis_index(a) for a in "xyz"]]
    return float(cKDTree(sp.meta["programmed_path"].points(step=step)).query(xyz)[0].max()) - step / 2


def _utilisation(sp) -> tuple[float, float, float]:
    """Worst |v|/v_max, |a|/a_max and |j|/j_max over x, y, z from finite differences."""
    worst = np.zeros(3)
    for ax in "xyz":
        d = np.diff(sp.position[:, sp.axis_index(ax)]) / sp.sample_time
        lim = DEFAULT_LIMITS[ax]
        for k, m in enumerate((lim.velocity, lim.acceleration, lim.jerk)):
            worst[k] = max(worst[k], float(np.abs(d).max()) / m)
            d = np.diff(d) / sp.sample_time
    return float(worst[0]), float(worst[1]), float(worst[2])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--radius", type=float, default=0.24, help="helix radius [mm]")
    ap.add_argument("--chord", type=float, default=0.05, help="chord length [mm]")
    ap.add_argument("--decimals", type=int, default=3, help="decimals of the chord end points (FreeCAD: 3)")
    ap.add_argument("--turns", type=int, default=20)
    ap.add_argument("--pitch", type=float, default=0.12, help="depth per turn [mm]")
    args = ap.parse_args()
    arc_text, chord_text = _programs(args.radius, args.chord, args.decimals, args.turns, args.pitch)
    for profile in ("trapezoid", "scurve"):
        sp_arc = interpolate(parse_program(arc_text), profile=profile)
        t0 = time.process_time()
        sp = interpolate(parse_program(chord_text), profile=profile)
        cpu = time.process_time() - t0
        uv, ua, uj = _utilisation(sp)
        print(f"{profile:9s}: r {args.radius} mm, {args.chord * 1e3:.0f} um chords: arc {sp_arc.duration:.3f} s, "
              f"chords {sp.duration:.3f} s, ratio {sp.duration / sp_arc.duration:.3f}; worst deviation from the "
              f"chords {_deviation(sp) * 1e3:.2f} um (tolerance 10 um); worst v {uv:.3f}, a {ua:.3f}"
              + (f", j {uj:.3f}" if profile == "scurve" else "") + f" of the axis limits; {cpu:.2f} s CPU")


if __name__ == "__main__":
    main()
