"""Contour evaluator benchmark and the thesis' contour-prediction cases.

Part 1 (speed, issue 6): contour error of 10 million samples of a program of lines and arcs,
windowed search of :func:`vcnc.contour.contour_error`, printed beside a brute-force nearest-point
search (exact projection on every segment, numpy) on the same data (timed on a subset and scaled).

Part 2 (accuracy): the thesis' cases (Secs. 3.4.1 / 3.4.2): identify each axis from a Table
3.2-style random-move test on the true machine, then compare the contour error of the true machine
and of the models, before and after the residual diagnosis, and for fadal-smc also with the true
machine's measurement noise off. A truth with measurement noise is the mean of ten noise
realisations (vcnc.contour_compare); "single runs" gives the range of the prediction error against
each realisation alone.

Run: ``python benchmarks/contour.py [--samples N] [--moves N] [--skip-thesis] [--skip-speed]``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

# this checkout's packages first (not an installed copy's); benchmarks/identification.py would shadow the
# identification package when run as a script
sys.path[:] = [str(Path(__file__).resolve().parents[1])] + [
    p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

import numpy as np  # noqa: E402
import scipy.signal  # noqa: E402

import interpolators  # noqa: E402
import toolpaths  # noqa: E402
from vcnc.contour import contour_error  # noqa: E402
from vcnc.contour_compare import compare  # noqa: E402
from vcnc.engine.machine import load_machine  # noqa: E402


def _program(repeats: int) -> str:
    """A serpentine of 40 mm lines joined by half circles of 10 mm diameter, ``4 * repeats`` blocks."""
    lines = ["G21 G90 G17 G61", "G00 X0 Y0"]
    for k in range(repeats):
        x0 = 20.0 * k
        lines += [f"G01 X{x0:.3f} Y40 F12000", f"G02 X{x0 + 10:.3f} Y40 I5 J0", f"G01 X{x0 + 10:.3f} Y0",
                  f"G03 X{x0 + 20:.3f} Y0 I5 J0"]
    lines.append("M30")
    return "\n".join(lines) + "\n"


def _brute(path, P: np.ndarray) -> np.ndarray:
    """Exact distance to every segment, all segments for every sample (numpy, chunked)."""
    lines = [(s.start[:2], s.end[:2]) for s in path if isinstance(s, toolpaths.Line)]
    arcs = [s for s in path if isinstance(s, toolpaths.Arc)]
    A = np.array([a for a, _ in lines])
    D = np.array([b - a for a, b in lines])
    DD = np.maximum((D * D).sum(1), 1e-300)
    C = np.array([s.center[:2] for s in arcs])
    R = np.array([s.radius for s in arcs])
    a0 = np.array([s.start_angle for s in arcs])
    sw = np.array([s.sweep for s in arcs])
    S0 = np.array([s.start[:2] for s in arcs])
    S1 = np.array([s.end[:2] for s in arcs])
    out = np.empty(len(P))
    for k in range(0, len(P), 256):
        p = P[k : k + 256, None, :]
        u = np.clip(((p - A) * D).sum(2) / DD, 0, 1)
        dl = np.linalg.norm(p - (A + u[..., None] * D), axis=2).min(1)
        r = p - C
        ang = np.arctan2(r[..., 1], r[..., 0])
        rel = (np.sign(sw) * (ang - a0)) % (2 * math.pi)
        inside = rel <= np.abs(sw)
        d_circ = np.abs(np.linalg.norm(r, axis=2) - R)
        d_end = np.minimum(np.linalg.norm(p - S0, axis=2), np.linalg.norm(p - S1, axis=2))
        da = np.where(inside, d_circ, d_end).min(1)
        out[k : k + 256] = np.minimum(dl, da)
    return out


def speed(n_samples: int) -> None:
    prog = interpolators.parse_program(_program(125))
    sp1 = interpolators.interpolate(prog, sample_time=1e-3)
    ts = sp1.duration / n_samples
    t0 = time.perf_counter()
    sp = interpolators.interpolate(prog, sample_time=ts, max_samples=n_samples + 10_000)
    t_int = time.perf_counter() - t0
    a = math.exp(-ts / 0.02)  # first-order lag, tau 20 ms, per axis
    act = np.column_stack([scipy.signal.lfilter([1 - a], [1, -a], sp.position[:, i] - sp.position[0, i])
                           + sp.position[0, i] for i in range(2)])
    n = len(sp)
    print(f"program: {len(sp.path)} segments (lines and arcs), {n:,} samples at Ts {ts * 1e6:.3g} us "
          f"(interpolated in {t_int:.1f} s)")
    contour_error(sp.path, act[:1000], sp.axes, reference=sp.position[:1000], sample_time=ts)  # compile / load
    t0 = time.perf_counter()
    ce = contour_error(sp.path, act, sp.axes, reference=sp.position, sample_time=ts)
    t_win = time.perf_counter() - t0
    m = ce.metrics()
    print(f"windowed search : {t_win:6.2f} s for {n:,} samples ({n / t_win / 1e6:.2f} M samples/s); "
          f"max {m['max_um']:.2f} um, rms {m['rms_um']:.2f} um")
    sub = np.linspace(0, n - 1, 20_000).astype(int)
    t0 = time.perf_counter()
    bf = _brute(sp.path, act[sub])
    t_bf = (time.perf_counter() - t0) * n / len(sub)
    print(f"brute force     : {t_bf:6.1f} s for {n:,} samples (timed on {len(sub):,} and scaled), "
          f"{t_bf / t_win:.0f}x slower")
    t0 = time.perf_counter()
    glob = contour_error(sp.path, act[sub], sp.axes)
    t_glob = (time.perf_counter() - t0) * n / len(sub)
    print(f"global (no command) compiled search: {t_glob:6.1f} s scaled to {n:,} samples")
    diff = np.abs(np.abs(ce.error[sub]) - bf)
    print(f"agreement with brute force: max |difference| {diff.max() * 1e3:.2e} um over {len(sub):,} samples "
          f"(global: {np.abs(np.abs(glob.error) - bf).max() * 1e3:.2e} um)")


CASES = [("fadal-pid", None, None), ("fadal-ppi", None, None), ("fadal-smc", None, None),
         ("ballscrew-ppc", 100.0, 600.0), ("ballscrew-zpetc", 100.0, 600.0)]


def thesis(moves: int) -> None:
    from identification import identify
    from identification.diagnosis import diagnose

    print(f"\nthesis cases: models identified from {moves} random moves (+/-10 mm, 200 mm/s), true vs predicted "
          "max contour error")
    print(f"{'machine':16s} {'toolpath':8s} {'true um':>9s} {'ident um':>9s} {'err %':>7s} {'single runs %':>15s} "
          f"{'augm um':>9s} {'err %':>7s}  effects")
    for name, feed, acc in CASES:
        m = load_machine(name)
        prog = interpolators.parse_program(toolpaths.random_moves(moves, 10.0, 12000, seed=1, axes=m.axes))
        cap = m.simulate(interpolators.interpolate(prog, limits=m.limits, sample_time=m.sample_time), seed=1)
        plain = {a: identify(cap, axis=a, diagnose=False) for a in m.axes}
        aug = {a: diagnose(cap, plain[a], axis=a) for a in m.axes}
        one = len(m.axes) == 1
        for tp in (("circle", "diamond") if feed is None else ("circle",)):
            r = compare(name, plain[m.axes[0]] if one else plain, tp, feed=feed, acceleration=acc).to_dict()
            rng = r.get("prediction_error_pct_range", {}).get("max")
            single = f"{rng[0]:+.1f}..{rng[1]:+.1f}" if rng else "(one run)"
            line = (f"{name:16s} {tp:8s} {r['true']['contour_max_um']:9.2f} {r['predicted']['contour_max_um']:9.2f} "
                    f"{r['prediction_error_pct']['max']:+7.2f} {single:>15s}")
            ra = compare(name, aug[m.axes[0]] if one else aug, tp, feed=feed, acceleration=acc).to_dict()
            effects = sorted({e.get("name", "?") for mod in aug.values() for e in (mod.effects or [])})
            line += (f" {ra['predicted']['contour_max_um']:9.2f} {ra['prediction_error_pct']['max']:+7.2f}  "
                     f"{', '.join(effects) or 'none found'}")
            print(line, flush=True)
            if name == "fadal-smc":
                quiet = m
                for a in m.axes:
                    quiet = quiet.with_axis_options(a, noise=None)
                rq = compare(quiet, plain, tp).to_dict()
                print(f"{'  (noise off)':16s} {tp:8s} {rq['true']['contour_max_um']:9.2f} "
                      f"{rq['predicted']['contour_max_um']:9.2f} {rq['prediction_error_pct']['max']:+7.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=10_000_000)
    ap.add_argument("--moves", type=int, default=60)
    ap.add_argument("--skip-speed", action="store_true")
    ap.add_argument("--skip-thesis", action="store_true")
    args = ap.parse_args()
    if not args.skip_speed:
        speed(args.samples)
    if not args.skip_thesis:
        thesis(args.moves)


if __name__ == "__main__":
    main()
