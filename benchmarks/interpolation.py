"""Interpolation throughput: setpoints per second for a 10,000-block random program.

Run: ``.venv/bin/python benchmarks/interpolation.py [--blocks N] [--repeat R]``

Prints, for each profile, the time of ``interpolate`` (parsing timed apart) and the setpoints per
second, and a reference measured in the same run: a naive per-sample Python evaluation (a Python
loop per sample calling ruckig's ``Trajectory.at_time`` for the S-curve, the trapezoid formulas
for the trapezoid, then mapping to x/y position, velocity, acceleration) on a subset of the
blocks. Note the program's blocks move diagonally in XY, so path speed is capped by the axes.

Then the largest program of the G-code corpus (``VCNC_GCODE_CORPUS``, default ``../shared/data/gcode-corpus``
beside the repository; skipped with a message when absent; ``--corpus-program`` names another file), a long
CAM program with G64 dense code: reading and interpolation timed apart, setpoints/s for each profile,
against a reference measured in the same run: allocating and filling setpoint arrays of the same shape
(t, position, velocity, acceleration) with ``np.linspace``, the least any interpolator must spend. And the
CSV writer of ``vcnc interpolate`` (``Setpoints.to_csv``) on the trapezoid's setpoints, against ``np.savetxt``
of the same table (the reference, measured in the same run), with a check that both wrote the same bytes.
Each interpolation also prints its CPU time (a shared machine's load stretches the wall time, hardly the CPU's).

Measured (``--skip-random``, 0274, best of 3, 2 cores at load ~3, OPENBLAS_NUM_THREADS=1): before the compiled
and batched look-ahead, dense fitting and sampler (main 43cf4c4) the trapezoid took 5.20 s (0.239 M setpoints/s),
the S-curve 7.56 s (0.296 M/s); after, 4.05 s (0.307 M/s) and 5.24 s (0.427 M/s), the same setpoints bit for bit.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402
import ruckig  # noqa: E402

import toolpaths  # noqa: E402
from interpolators import DEFAULT_LIMITS, interpolate, load_program, parse_program  # noqa: E402

CORPUS = Path(os.environ.get("VCNC_GCODE_CORPUS", Path(__file__).resolve().parents[2] / "shared" / "data"
                             / "gcode-corpus"))


def _naive_trapezoid(blocks, V, A, Ts):
    """Per-sample Python loop: trapezoid formulas, then x/y position, velocity, acceleration."""
    rows = []
    for b in blocks:
        L = b.length
        ux, uy = (b.target[:2] - b.start[:2]) / L
        vp = min(V, math.sqrt(L * A))
        ta = vp / A
        tc = (L - vp * vp / A) / vp
        T = 2 * ta + tc
        t = 0.0
        while t < T:
            if t < ta:
                s, v, a = 0.5 * A * t * t, A * t, A
            elif t < ta + tc:
                s, v, a = 0.5 * A * ta * ta + vp * (t - ta), vp, 0.0
            else:
                td = T - t
                s, v, a = L - 0.5 * A * td * td, A * td, -A
            rows.append((b.start[0] + ux * s, b.start[1] + uy * s, ux * v, uy * v, ux * a, uy * a))
            t += Ts
    return len(rows)


def _naive_scurve(blocks, V, A, J, Ts):
    """Per-sample ruckig Trajectory.at_time loop, then x/y position, velocity, acceleration."""
    otg = ruckig.Ruckig(1)
    inp = ruckig.InputParameter(1)
    traj = ruckig.Trajectory(1)
    rows = []
    for b in blocks:
        L = b.length
        ux, uy = (b.target[:2] - b.start[:2]) / L
        inp.current_position, inp.current_velocity, inp.current_acceleration = [0.0], [0.0], [0.0]
        inp.target_position, inp.target_velocity, inp.target_acceleration = [L], [0.0], [0.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [V], [A], [J]
        otg.calculate(inp, traj)
        t = 0.0
        while t < traj.duration:
            (s,), (v,), (a,) = traj.at_time(t)
            rows.append((b.start[0] + ux * s, b.start[1] + uy * s, ux * v, uy * v, ux * a, uy * a))
            t += Ts
    return len(rows)


def _fill_reference(n: int, n_axes: int) -> float:
    """Time [s] to allocate and fill setpoint arrays of ``n`` samples on ``n_axes`` axes (t, block, position,
    velocity, acceleration) with ``np.linspace``."""
    t0 = time.perf_counter()
    t = np.linspace(0.0, 1.0, n)
    block = np.zeros(n, dtype=np.int64)
    cols = [np.linspace(0.0, 1.0 + k, n) for k in range(3 * n_axes)]
    arrays = [np.stack(cols[k * n_axes:(k + 1) * n_axes], axis=1) for k in range(3)]
    elapsed = time.perf_counter() - t0
    del t, block, cols, arrays
    return elapsed


def _corpus_program(path: Path | None) -> int:
    """Read and interpolate one corpus program with both profiles; print setpoints/s against the fill reference."""
    if path is None:
        files = [f for f in CORPUS.glob("*") if f.is_file() and f.suffix not in (".md", ".tsv")]
        if not files:
            print(f"corpus program: skipped, no G-code corpus at {CORPUS} (set VCNC_GCODE_CORPUS)")
            return 0
        path = max(files, key=lambda f: f.stat().st_size)
    t0 = time.perf_counter()
    prog = load_program(path)
    t_read = time.perf_counter() - t0
    print(f"corpus program {path.name}: {len(prog.blocks):,} blocks, read in {t_read:.2f} s")
    for profile in ("trapezoid", "scurve"):
        t0, c0 = time.perf_counter(), time.process_time()
        sp = interpolate(prog, profile=profile, max_samples=20_000_000)
        elapsed, cpu = time.perf_counter() - t0, time.process_time() - c0
        ref = _fill_reference(len(sp), len(sp.axes))
        print(f"{profile:9s}: {len(sp):,} setpoints ({sp.duration:.1f} s of motion) in {elapsed:.2f} s "
              f"({cpu:.2f} s CPU: {len(sp) / cpu / 1e6:.3f} M/s) = "
              f"{len(sp) / elapsed / 1e6:.3f} M setpoints/s; reference (np.linspace fill of the same arrays) "
              f"{len(sp) / ref / 1e6:.1f} M/s; interpolation takes {elapsed / ref:.0f}x the fill")
        if profile == "trapezoid":
            _csv_writer(sp)
        del sp
    return 0


def _csv_writer(sp) -> None:  # noqa: ANN001
    """Time ``Setpoints.to_csv`` against ``np.savetxt`` of the same table (the reference), and compare the bytes."""
    header, data, fmt = sp.table()
    with tempfile.TemporaryDirectory() as tmp:
        mine, ref = Path(tmp) / "mine.csv", Path(tmp) / "ref.csv"
        t0 = time.perf_counter()
        sp.to_csv(mine)
        t_mine = time.perf_counter() - t0
        t0 = time.perf_counter()
        np.savetxt(ref, data, delimiter=",", header=",".join(header), comments="", fmt=fmt)
        t_ref = time.perf_counter() - t0
        same = mine.read_bytes() == ref.read_bytes()
    print(f"CSV writer: {len(sp):,} rows in {t_mine:.2f} s = {len(sp) / t_mine / 1e6:.3f} M rows/s; reference "
          f"np.savetxt {t_ref:.2f} s; {t_ref / t_mine:.2f}x faster; same bytes: {'yes' if same else 'NO'}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--blocks", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--subset", type=int, default=300, help="blocks evaluated by the naive reference")
    ap.add_argument("--corpus-program", type=Path, default=None,
                    help="G-code file for the long-program part (default: the largest file of the corpus)")
    ap.add_argument("--skip-random", action="store_true", help="only the corpus program")
    args = ap.parse_args()
    if args.skip_random:
        return _corpus_program(args.corpus_program)
    text = toolpaths.random_moves(args.blocks, 10.0, 12000.0, seed=1, axes=("x", "y"))
    t0 = time.perf_counter()
    prog = parse_program(text)
    t_parse = time.perf_counter() - t0
    print(f"program: {args.blocks} random XY moves within +/-10 mm at F12000 (Table 3.2 style); "
          f"parse {t_parse:.3f} s ({args.blocks / t_parse:,.0f} blocks/s)")
    lim = DEFAULT_LIMITS["x"]
    subset = [b for b in prog.blocks[1 : 1 + args.subset] if b.length > 0]
    for profile in ("trapezoid", "scurve"):
        best = math.inf
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            sp = interpolate(prog, profile=profile)
            best = min(best, time.perf_counter() - t0)
        rate = len(sp) / best
        t0 = time.perf_counter()
        if profile == "trapezoid":
            n_ref = _naive_trapezoid(subset, 200.0, lim.acceleration, sp.sample_time)
        else:
            n_ref = _naive_scurve(subset, 200.0, lim.acceleration, lim.jerk, sp.sample_time)
        ref_rate = n_ref / (time.perf_counter() - t0)
        print(f"{profile:9s}: {len(sp):,} setpoints ({sp.duration:.1f} s of motion) in {best:.3f} s = "
              f"{rate / 1e6:.2f} M setpoints/s; naive per-sample Python reference "
              f"{'(ruckig at_time)' if profile == 'scurve' else '(formulas)'}: {ref_rate / 1e6:.3f} M/s; "
              f"ratio {rate / ref_rate:.1f}x")
        del sp
    return _corpus_program(args.corpus_program)


if __name__ == "__main__":
    raise SystemExit(main())
