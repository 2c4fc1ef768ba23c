"""Points per second of a 50-point sweep on a local Dask cluster with 1 and 2 workers, and the
speed-up.

The sweep is ``examples/05_sweep.toml`` reduced to 50 points of real work: the identification
test (200 random moves, thesis Table 3.2) simulated on fadal-pid at 5 feeds x 5 controller gain scales x 2 noise
seeds, each identified (exact solver + output-error refinement). Points per second count the
computation only (cluster start excluded); "overall" includes each worker's first point, which
loads the compiled kernels, "after the first result" is the steady rate. Run::

    .venv/bin/python benchmarks/sweep.py [--workers 1,2] [--repeat 1]

"parallelism" is the sum of the points' own times over the computing time: close to the number
of workers when Dask keeps them all busy; a median point time that grows with the workers means
the CPUs are shared (other processes, hyper-threads). Prints figures only.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import textwrap
import time
from pathlib import Path

SPEC = textwrap.dedent("""
    [sweep]
    mode = "grid"
    [parameters]
    machine = "fadal-pid"
    toolpath = "identification"
    feed = {min = 6000, max = 12000, num = 5}
    gain = [0.8, 0.9, 1.0, 1.1, 1.25]
    seed = [0, 1]
    [toolpath]
    moves = 200
    [outputs]
    identify = true
""")


def run(workers: int, tmp: Path, tag: str) -> tuple[float, float, float, float, float]:
    """(points/s over the whole computation, points/s after the first result, wall s, median point
    time s, parallelism = sum of point times / computing time)."""
    from vcnc.sweeps import sweep

    spec = tmp / "bench.toml"
    spec.write_text(SPEC)
    out = tmp / f"bench-{workers}-{tag}.parquet"
    stamps: list[float] = []
    t0 = time.perf_counter()
    r = sweep(spec, out, workers=workers, progress=False, callback=lambda row: stamps.append(time.perf_counter()))
    wall = time.perf_counter() - t0
    assert r.computed == 50, r.computed
    assert r.failed == 0, [e for e in r.column("error") if e]
    steady = (len(stamps) - 1) / (stamps[-1] - stamps[0])
    times = sorted(r.column("t_point_s"))
    return r.points_per_s, steady, wall, times[len(times) // 2], sum(times) / r.elapsed_s


def main() -> None:
    # the workers inherit sys.path: this checkout first (not the installed copy), and this folder's
    # identification.py must not shadow the package
    here = Path(__file__).resolve().parent
    sys.path[:] = [str(here.parent)] + [p for p in sys.path if Path(p or ".").resolve() != here]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", default="1,2", help="comma-separated worker counts (default 1,2)")
    ap.add_argument("--repeat", type=int, default=1, help="runs per worker count; the best is kept")
    args = ap.parse_args()
    counts = [int(x) for x in args.workers.split(",")]
    print(f"CPUs: {os.cpu_count()}; 50 points (identification test, 200 moves, identify = true)")
    best: dict[int, tuple[float, float]] = {}
    with tempfile.TemporaryDirectory() as d:
        for n in counts:
            for k in range(args.repeat):
                pps, steady, wall, median, par = run(n, Path(d), str(k))
                print(f"  {n} worker(s): {pps:6.2f} points/s overall, {steady:6.2f} points/s after the first "
                      f"result; {50 / pps:5.1f} s computing ({wall:5.1f} s with cluster start), median point "
                      f"{median:.3f} s, parallelism {par:.2f}")
                old = best.get(n, (0.0, 0.0))
                best[n] = (max(old[0], pps), max(old[1], steady))
    if 1 in best:
        for n in counts:
            if n != 1:
                print(f"speed-up {n} vs 1 worker(s): {best[n][0] / best[1][0]:.2f}x overall, "
                      f"{best[n][1] / best[1][1]:.2f}x after the first result")


if __name__ == "__main__":
    main()
