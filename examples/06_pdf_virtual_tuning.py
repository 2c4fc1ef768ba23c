"""Virtual tuning of an integer-parameter PDF loop (Liu, Lai, Yen 2008, seed 004).

The grinding-machine table ``chevalier-pdf`` runs a PDF controller whose integer settings
(K_I = 19, K_F = 260) act through unknown scale gains k1, k2. From one recorded motion (error,
control signal and output only) the scale gains are found by least squares (seed 004, Eqs. 4-6
and 10); with them the loop can be re-tuned on the computer: the step response with the
paper's settings (19, 260) is compared with (22, 220). The paper (Sec. 4) reports the overshoot
of the real machine gone with (22, 220); its plant model P*(z) has no base resonance, so what
our model shows is reported as measured, not matched to the paper.

Run: ``.venv/bin/python examples/06_pdf_virtual_tuning.py [--plots DIR]``
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

import interpolators
import toolpaths
from identification.gain_scales import PAPER_K1, PAPER_K2, overshoot, pdf_gain_scales
from vcnc.engine.machine import load_machine
from vcnc.setpoints import Setpoints

#: Settings compared by the paper (seed 004, Sec. 4).
SETTINGS = ((19, 260), (22, 220))


def identify_scales(seed: int = 3) -> dict[str, float]:
    """Run a random-move test on chevalier-pdf and identify k1, k2 from (e, u, y)."""
    machine = load_machine("chevalier-pdf")
    program = interpolators.parse_program(toolpaths.random_moves(40, 2.0, 3000.0, seed=seed), source="pdf-test.nc")
    setpoints = interpolators.interpolate(program, limits=machine.limits, sample_time=machine.sample_time)
    cap = machine.simulate(setpoints, seed=seed)
    y = cap.measured[:, 0]
    e = cap.reference[:, 0] - y
    u = cap.control[:, 0]
    res = pdf_gain_scales(e, u, y, integer_parameters=SETTINGS[0], sample_time=cap.sample_time, position_scale=1e-3)
    return {"k1": res["k1"], "k2": res["k2"]}


def step_responses(k1: float, k2: float, *, step_mm: float = 1.0, duration_s: float = 0.4) -> dict:
    """Step responses of the loop with each setting of :data:`SETTINGS`, using scales k1, k2."""
    machine = load_machine("chevalier-pdf")
    ts = machine.sample_time
    n = int(round(duration_s / ts))
    ref = np.full(n, step_mm)
    ref[:20] = 0.0
    sp = Setpoints.from_positions(ref, sample_time=ts, axes=("x",))
    base = machine.axis("x").controller
    out = {}
    for p1, p2 in SETTINGS:
        ctrl = dataclasses.replace(base, p1=p1, p2=p2, k1=k1, k2=k2)
        cap = machine.with_axis_options("x", controller=ctrl).simulate(sp, seed=0)
        y = cap.measured[:, 0]
        settled = np.flatnonzero(np.abs(y - step_mm) > 0.02 * step_mm)
        out[(p1, p2)] = {
            "t": cap.t,
            "y": y,
            "overshoot_pct": 100.0 * overshoot(y[20:], step_mm),
            "settling_time_s": float(cap.t[settled[-1]] - cap.t[20]) if settled.size else 0.0,
        }
    return out


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plots", type=Path, default=None, help="folder for the step-response figure")
    args = ap.parse_args(argv)
    scales = identify_scales()
    print(f"identified scale gains: k1 = {scales['k1']:.5g} (paper {PAPER_K1}), "
          f"k2 = {scales['k2']:.5g} (paper {PAPER_K2})")
    responses = step_responses(scales["k1"], scales["k2"])
    for (p1, p2), r in responses.items():
        print(f"settings ({p1}, {p2}): overshoot {r['overshoot_pct']:.2f} %, "
              f"2 % settling {r['settling_time_s'] * 1e3:.1f} ms")
    if args.plots:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 4))
        for (p1, p2), r in responses.items():
            ax.plot(r["t"] * 1e3, r["y"], label=f"K_I={p1}, K_F={p2}: overshoot {r['overshoot_pct']:.1f} %")
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("position [mm]")
        ax.set_title("chevalier-pdf: step response with identified scale gains")
        ax.grid(True, alpha=0.3)
        ax.legend()
        args.plots.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.plots / "pdf_virtual_tuning.png", dpi=110, bbox_inches="tight")
    return {"scales": scales, "responses": responses}


if __name__ == "__main__":
    main()
