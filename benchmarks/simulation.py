"""Simulation speed: the compiled closed loop against python-control's ``forced_response``.

Run: ``.venv/bin/python benchmarks/simulation.py [--seconds 300] [--hour]``

Measures axis-samples per second of the full nonlinear ``fadal-pid`` machine (friction, backlash,
DAC, encoder, current limit, noise; both axes) over ``--seconds`` of motion at 1 kHz, and the
same number of samples through ``control.forced_response`` on the linear closed loop G_track of
one axis, in the same run. With ``--hour`` also a one-hour three-axis program (x, y of
``fadal-pid`` and a copy as z) at 1 kHz. Prints figures and ratios; asserts nothing.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout, not an installed copy

import control  # noqa: E402
import numpy as np  # noqa: E402

from vcnc.engine.machine import Machine, load_machine  # noqa: E402
from vcnc.setpoints import Setpoints  # noqa: E402


def motion(seconds: float, ts: float, axes: tuple[str, ...]) -> Setpoints:
    """Smooth multi-axis motion: sums of sines of 0.05-3 Hz, +/-20 mm."""
    t = np.arange(int(round(seconds / ts))) * ts
    rng = np.random.default_rng(0)
    cols = []
    for _ in axes:
        f = rng.uniform(0.05, 3.0, 4)
        a = rng.uniform(1.0, 8.0, 4) / (1 + f)
        p = rng.uniform(0, 2 * np.pi, 4)
        cols.append((a * np.sin(2 * np.pi * np.outer(t, f) + p)).sum(1))
    return Setpoints.from_positions(np.column_stack(cols), sample_time=ts, axes=axes)


def best_of(fn, repeat: int) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=300.0, help="seconds of motion (100-1000)")
    ap.add_argument("--hour", action="store_true", help="also simulate a one-hour three-axis program")
    args = ap.parse_args()

    m = load_machine("fadal-pid")
    ts = m.sample_time
    sp = motion(args.seconds, ts, m.axes)
    m.simulate(motion(1.0, ts, m.axes))  # compile / load the cached kernel
    n_axis_samples = len(sp) * len(m.axes)
    t_vcnc = best_of(lambda: m.simulate(sp, seed=1), 3)
    rate_vcnc = n_axis_samples / t_vcnc

    g_track, _ = m.axis("x").closed_loop(ts)
    ref = sp.position[:, 0]
    n_pc = len(sp)

    def run_pc() -> None:
        control.forced_response(g_track, T=sp.t, U=ref)

    t_pc = best_of(run_pc, 1)
    rate_pc = n_pc / t_pc

    print(f"motion: {args.seconds:g} s at Ts = {ts * 1e3:g} ms, {len(sp)} samples per axis")
    print(f"vcnc fadal-pid (nonlinear, {len(m.axes)} axes): {t_vcnc:.3f} s -> {rate_vcnc / 1e6:.1f} M axis-samples/s")
    print(f"python-control forced_response (linear G_track, 1 axis): {t_pc:.3f} s -> {rate_pc / 1e6:.2f} M samples/s")
    print(f"ratio vcnc / python-control: {rate_vcnc / rate_pc:.0f}x   (goals: >= 10 M/s, >= 50x)")

    if args.hour:
        x = m.axis("x")
        m3 = Machine.from_axes({"x": x, "y": m.axis("y"), "z": x.__class__(**{**x.__dict__, "name": "z"})},
                               sample_time=ts, name="fadal-pid-3axis")
        sp3 = motion(3600.0, ts, ("x", "y", "z"))
        t0 = time.perf_counter()
        m3.simulate(sp3, seed=1)
        t3 = time.perf_counter() - t0
        print(f"one hour, three axes at 1 kHz ({3 * len(sp3) / 1e6:.1f} M axis-samples): {t3:.2f} s "
              f"({3 * len(sp3) / t3 / 1e6:.1f} M axis-samples/s, incl. setpoint handling)")


if __name__ == "__main__":
    main()
