"""The corpus' programs through the whole chain: interpolate, simulate, contour error, summary, report.

Every program the corpus runner (``benchmarks/gcode_corpus.py``) accepts is read by it
(``run_corpus`` without interpolation: ``load_program`` with ``INTERPOLATION_CONTEXT``, axes A B C
U V W allowed, in the dialect its origin tag names) and handed to this script, which runs it as ``vcnc simulate`` does:
``vcnc.facade.interpolate`` with the machine (its axis check, then the first ``--seconds`` of the
program: a longer one is cut and counted as cut), ``Machine.simulate``,
``vcnc.simulation_report.summarize``.

Machines: ``fadal-pid`` (x, y: the default) for a program that moves X and Y only. No built-in
machine has a Z or a rotary axis; a program that moves Z is first refused by ``fadal-pid`` (the
message is counted), then run on ``fadal-pid+z``, the machine whose Z axis is a copy of its X axis (drive,
controller, limits; ``vcnc simulate --machine fadal-pid+z``): our assumption to exercise the chain, not a real
machine. A
program that moves a rotary or a U V W axis is refused (counted by reason). ``--machines all`` runs
every program on every built-in machine in turn (the controller library: PID, P-PI, sliding mode, pole
placement + Kalman filter with and without ZPETC, integer PDF, the EMPS cascade), each completed the
same way where it lacks Y or Z (``NAME+yz``: copies of its X axis), and prints a line per machine.

Prints the counts (simulated, cut by the budget, refused by reason, crashed with the exception),
non-finite captures, runs whose actuator saturated (the summary's ``saturated`` entry), the worst
tracking and contour errors with their programs, the peak memory, and the setpoints/s of the
simulation against the interpolation of the same programs in the same run (the reference; it
includes the search for the cut). ``--report DIR`` also writes the ``vcnc simulate --report``
folders of the first ``--report-count`` simulated programs with a contour.

Usage: ``python benchmarks/corpus_simulation.py [--seconds 20] [--machines fadal-pid|all] [--list] [--report DIR]``
"""

from __future__ import annotations

import argparse
import collections
import math
import resource
import sys
import time
import traceback
from pathlib import Path

import numpy as np
from gcode_corpus import ROOT, corpus_dir, reason, run_corpus

sys.path.insert(0, str(ROOT))

from interpolators import Program  # noqa: E402
from vcnc.core.errors import VcncError  # noqa: E402
from vcnc.engine.machine import ADDABLE_AXES, Machine, builtin_machines, load_machine  # noqa: E402
from vcnc.facade import check_program_axes, interpolate, program_meta  # noqa: E402
from vcnc.simulation_report import build_report, summarize  # noqa: E402


def machines(name: str = "fadal-pid") -> tuple[Machine, Machine]:
    """Built-in machine ``name`` and the same with X, Y and Z, the missing ones copies of its X axis
    (``fadal-pid+z``, ``emps+yz``: :func:`vcnc.engine.machine.builtin_machine_text`)."""
    m = load_machine(name)
    return m, load_machine(name + "+" + "".join(a for a in ADDABLE_AXES if a not in m.axes))


def simulate_one(path: Path, program: Program, xy: Machine, xyz: Machine, seconds: float) -> dict:
    """One program (read by the corpus runner) through the chain: what happened, the time of each stage."""
    rec: dict = {"status": "", "reason": "", "machine": xy.name, "samples": 0}
    try:
        machine = xy
        try:
            check_program_axes(program, xy)
        except VcncError as exc:
            rec["xy_refusal"] = reason(str(exc))
            machine = xyz
            check_program_axes(program, xyz)
        rec["machine"] = machine.name
        t0 = time.perf_counter()
        sp = interpolate(program, machine, max_duration=seconds)
        t1 = time.perf_counter()
        capture = machine.simulate(sp, seed=0)
        capture.meta.update(program_meta(sp, path.name, profile="trapezoid"))
        t2 = time.perf_counter()
        summary = summarize(capture)
        t3 = time.perf_counter()
    except VcncError as exc:
        rec.update(status="refused", reason=reason(str(exc)), message=str(exc))
        return rec
    except Exception as exc:  # noqa: BLE001 - a crash is what this benchmark looks for
        rec.update(status="crashed", reason=f"{type(exc).__name__}: {exc}"[:200],
                   message=traceback.format_exc(limit=-3))
        return rec
    arrays = [capture.reference, capture.measured] + ([capture.control] if capture.control is not None else [])
    finite = all(bool(np.isfinite(a).all()) for a in arrays)
    rec.update(status="simulated" if finite else "non-finite", samples=len(capture), summary=summary,
               cut="truncated" in sp.meta, at_least=sp.meta.get("truncated", {}).get("program_at_least", sp.duration),
               t_interp=t1 - t0, t_sim=t2 - t1, t_contour=t3 - t2,
               capture=capture if finite else None)
    return rec


def worst(recs: list[dict], key) -> tuple[float, str]:
    vals = [(key(r), r["file"]) for r in recs]
    vals = [v for v in vals if v[0] is not None and math.isfinite(v[0])]
    return max(vals) if vals else (float("nan"), "-")


def print_results(recs: list[dict], wall: float, seconds: float) -> None:
    by = collections.Counter(r["status"] for r in recs)
    sim = [r for r in recs if r["status"] == "simulated"]
    print(f"\n{len(recs)} programs accepted by the corpus runner, run for up to {seconds:g} s each ({wall:.1f} s):")
    print(f"  simulated   {by['simulated']:>4}  (fadal-pid {sum(r['machine'] == 'fadal-pid' for r in sim)}, "
          f"fadal-pid+z {sum(r['machine'] == 'fadal-pid+z' for r in sim)}; cut by the budget "
          f"{sum(r['cut'] for r in sim)})")
    longest = sorted(((r["at_least"], r["file"]) for r in sim), reverse=True)[:3]
    print("  longest (a lower bound of the whole program's run): "
          + ", ".join(f"{f} >= {t / 60:.0f} min" for t, f in longest))
    print(f"  refused     {by['refused']:>4}")
    print(f"  crashed     {by['crashed']:>4}")
    print(f"  non-finite  {by['non-finite']:>4}  (NaN or inf in the capture)")
    print(f"  saturated   {sum('saturated' in r['summary'] for r in sim):>4}  (an actuator at its limit: a warning)")
    xy_refusals = collections.Counter(r["xy_refusal"] for r in recs if r.get("xy_refusal"))
    if xy_refusals:
        print("\nrefused by fadal-pid (x, y), then run on fadal-pid+z:")
        for m, c in xy_refusals.most_common(5):
            print(f"  {c:>4}  {m}")
    reasons = collections.Counter(r["reason"] for r in recs if r["status"] == "refused")
    print("\nrefused by reason:")
    for m, c in reasons.most_common():
        print(f"  {c:>4}  {m}")
    for status in ("crashed", "non-finite"):
        for r in recs:
            if r["status"] == status:
                print(f"\n{status}: {r['file']}: {r['reason']}\n{r.get('message', '')}")
    c_max, c_file = worst(sim, lambda r: r["summary"].get("contour", {}).get("max_um"))
    t_max, t_file = worst(sim, lambda r: max(s["max_um"] for s in r["summary"]["tracking"].values()))
    print(f"\nworst contour error  {c_max:.1f} um  ({c_file}); "
          f"{sum('contour' in r['summary'] for r in sim)} programs with a contour (2+ moving axes)")
    print(f"worst tracking error {t_max:.1f} um  ({t_file})")
    n = sum(r["samples"] for r in sim)
    ti, ts_, tc = (sum(r[k] for r in sim) for k in ("t_interp", "t_sim", "t_contour"))
    if n and ti > 0 and ts_ > 0:
        print(f"\n{n} setpoints: interpolation (reference) {n / ti:.3g} setpoints/s ({ti:.1f} s), simulation "
              f"{n / ts_:.3g} setpoints/s ({ts_:.1f} s) = {ti / ts_:.2f} x the interpolation's rate; contour and "
              f"summary {n / tc:.3g} setpoints/s ({tc:.1f} s)")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak memory (max RSS) {peak:.0f} MB")


def print_machines(runs: dict[str, list[dict]]) -> None:
    """One line per machine of ``--machines all``: what happened to the programs, the worst errors, the speed."""
    print(f"\n{'machine':<18}{'simulated':>10}{'refused':>8}{'crashed':>8}{'non-finite':>11}{'saturated':>10}"
          f"{'diverged':>9}{'worst contour':>20}{'worst tracking':>20}{'sim setpoints/s':>16}")
    for name, recs in runs.items():
        by = collections.Counter(r["status"] for r in recs)
        sim = [r for r in recs if r["status"] == "simulated"]
        sat = [r["summary"]["saturated"] for r in sim if "saturated" in r["summary"]]
        diverged = sum(any(v["error_beyond_travel"] for v in s.values()) for s in sat)
        c_max, _ = worst(sim, lambda r: r["summary"].get("contour", {}).get("max_um"))
        t_max, _ = worst(sim, lambda r: max(s["max_um"] for s in r["summary"]["tracking"].values()))
        n, ts_ = sum(r["samples"] for r in sim), sum(r["t_sim"] for r in sim)
        print(f"{name:<18}{by['simulated']:>10}{by['refused']:>8}{by['crashed']:>8}{by['non-finite']:>11}{len(sat):>10}"
              f"{diverged:>9}{c_max:>17.1f} um{t_max:>17.1f} um{n / ts_ if ts_ > 0 else math.nan:>16.3g}")
    for name, recs in runs.items():
        for r in recs:
            if r["status"] in ("crashed", "non-finite"):
                print(f"\n{name}: {r['status']}: {r['file']}: {r['reason']}\n{r.get('message', '')}")


def write_reports(recs: list[dict], folder: str) -> None:
    """The ``vcnc simulate --report`` folder of the programs whose capture was kept."""
    import matplotlib.pyplot as plt

    for r in (r for r in recs if "capture" in r):
        out = Path(folder) / Path(r["file"]).stem
        build_report(r["capture"], r["summary"]).write(out)
        plt.close("all")
        print(f"report: {out}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=20.0, help="budget per program [s] (default 20)")
    ap.add_argument("--list", action="store_true", help="list every refused program with its message")
    ap.add_argument("--report", metavar="DIR", help="write simulate reports of a few programs under DIR")
    ap.add_argument("--report-count", type=int, default=3, help="how many reports (default 3)")
    ap.add_argument("--machines", choices=("fadal-pid", "all"), default="fadal-pid",
                    help="fadal-pid (default), or every built-in machine in turn (a line each)")
    args = ap.parse_args()
    d = corpus_dir()
    if d is None:
        print("gcode corpus not found (../shared/data/gcode-corpus): nothing to run")
        return 0
    pairs = [machines(n) for n in (builtin_machines() if args.machines == "all" else ["fadal-pid"])]
    pairs.sort(key=lambda p: p[0].name != "fadal-pid")  # fadal-pid first: the detailed results are its
    kept = 0

    def visit(path: Path, program: Program) -> dict:
        nonlocal kept
        runs = []
        for xy, xyz in pairs:
            rec = simulate_one(path, program, xy, xyz, args.seconds)
            capture = rec.pop("capture", None)  # dropped to keep memory flat, but for the reports' few
            if args.report and capture is not None and kept < args.report_count and "contour" in rec["summary"] \
                    and not runs:
                rec["capture"], kept = capture, kept + 1
            runs.append(rec)
        return {"chain": runs[0], "runs": runs}

    t0 = time.perf_counter()
    res = run_corpus(d, interpolate_too=False, visit=visit)
    recs = [{**p["chain"], "file": p["file"]} for p in res["programs"] if p["ok"]]
    print_results(recs, time.perf_counter() - t0, args.seconds)
    if args.machines == "all":
        print_machines({xy.name: [{**p["runs"][i], "file": p["file"]} for p in res["programs"] if p["ok"]]
                        for i, (xy, _) in enumerate(pairs)})
    if args.list:
        print("\nrefused programs:")
        for r in recs:
            if r["status"] == "refused":
                print(f"  {r['message']}")
    if args.report:
        write_reports(recs, args.report)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
