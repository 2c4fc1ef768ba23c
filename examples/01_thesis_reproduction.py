"""Reproduce the thesis' identification results on the built-in virtual machines.

W. Wong, "Rapid Identification of Virtual CNC Drives" (2007): the Table 3.2 test (200 random moves
within +/-10 mm, F12000, 2000 mm/s^2 trapezoidal, Ts 1 ms, about 22 s) is run on fadal-pid,
fadal-ppi, fadal-smc and ballscrew-zpetc, and on ballscrew-zpetc with a lightly damped axial mode
(the structure the rigid virtual bench lacks: with it the solution sits on zeta_min as in Table 4.2);
the reduced model is identified with each solver (the GA
also with the output-error refinement, to show the pipelines meet); true and estimated poles are
printed as in Tables 3.3-3.5 and 4.1 (three real poles labelled with p the slowest), and the
Sec. 4.3.1 validation move
(+/-20 mm at 70.71 mm/s, 424.26 mm/s^2) compares predicted and true tracking errors. With
``--plots DIR`` the FRFs (cf. Fig. 3.5) are saved.

Run: ``.venv/bin/python examples/01_thesis_reproduction.py [--plots DIR]``
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import interpolators
from identification import ReducedAxisModel, identify
from identification.synthetic import BALLSCREW_AXIAL_MODE, VALIDATION_PROGRAM, table_3_2_program
from interpolators.limits import AxisLimits
from vcnc.engine.machine import load_machine
from vcnc.errors import MachineError

#: The paper's PID estimate (Table 4.1, LM): omega_n 38.21 Hz, zeta 0.42, p 1.89 Hz.
PAPER_PID = {"omega_n_hz": 38.21, "zeta": 0.42, "p_hz": 1.89}
#: The paper's ZPETC + PPC + KF ball-screw estimate (Table 4.2, LM): 77.83 Hz, 0.203, 4.36 Hz.
PAPER_ZPETC = {"omega_n_hz": 77.83, "zeta": 0.203, "p_hz": 4.36}


def machines():
    """(label, figure file stem, machine) of every case."""
    for name in ("fadal-pid", "fadal-ppi", "fadal-smc", "ballscrew-zpetc"):
        yield name, name, load_machine(name)
    mode = BALLSCREW_AXIAL_MODE  # see test_thesis_reproduction.py::test_ballscrew_zpetc_with_an_axial_mode_...
    yield (f"ballscrew-zpetc + {mode.frequency_hz:g} Hz axial mode", "ballscrew-zpetc_mode",
           load_machine("ballscrew-zpetc").with_axis_options("x", resonance=mode))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plots", type=Path, help="folder for FRF figures")
    args = ap.parse_args()
    for name, stem, m in machines():
        sp = interpolators.interpolate(
            interpolators.parse_program(table_3_2_program()), limits=m.limits, sample_time=m.sample_time
        )
        cap = m.simulate(sp, seed=0)
        try:
            truth = ReducedAxisModel(parameters=m.axis("x").reduced_parameters(), sample_time=m.sample_time)
        except MachineError:  # discrete-time laws (PPC + ZPETC) have no exact Eq. (3.3) parameters
            truth = None
        lim = {a: AxisLimits(velocity=70.71, acceleration=424.26, jerk=1e6, rapid=250.0) for a in m.limits}
        vs = interpolators.interpolate(
            interpolators.parse_program(VALIDATION_PROGRAM), limits=lim, sample_time=m.sample_time
        )
        vc = m.simulate(vs, seed=1)
        xr = vc.reference[:, 0]
        e_true = xr - vc.measured[:, 0]
        print(f"\n{name}: {len(cap)} samples ({len(cap) * m.sample_time:.1f} s)")
        if truth is not None:
            tp = truth.poles
            print(f"  true          omega_n {tp['omega_n_hz']:7.2f} Hz  zeta {tp['zeta']:5.3f}  p {tp['p_hz']:7.2f} Hz")
        pp = PAPER_PID if name == "fadal-pid" else PAPER_ZPETC if name.startswith("ballscrew-zpetc") else None
        if pp is not None:
            print(f"  paper (LM)    omega_n {pp['omega_n_hz']:7.2f} Hz  zeta {pp['zeta']:5.3f}  p {pp['p_hz']:7.2f} Hz")
        runs = (("ga", "none"), ("ga", "output-error"), ("exact", "none"), ("kkt", "none"), ("exact", "output-error"))
        for method, refine in runs:  # the default (exact+oe) last: the lines below describe it
            model = identify(cap, method=method, refine=refine, diagnose=False)
            p = model.poles
            e_pred = xr - model.simulate(xr)
            mism = np.sqrt(np.mean((e_true - e_pred) ** 2)) / np.sqrt(np.mean(e_true**2))
            print(
                f"  {model.method:12s}  omega_n {p['omega_n_hz']:7.2f} Hz  zeta {p['zeta']:5.3f}  p {p['p_hz']:7.2f} Hz"
                f"  fit {model.fit['rms_um']:6.2f} um  validation mismatch {100 * mism:5.1f}% of "
                f"{1e3 * np.sqrt(np.mean(e_true ** 2)):.1f} um RMS"
            )
        ee = model.fit["solver"]
        active = [f"{k} at its {v} bound" for k, v in ee["active"].items() if v != "free"] or ["none"]
        print(f"  equation-error solution: Table 3.1 case {ee['case']}, active constraints: {', '.join(active)}")
        zeros = ", ".join(f"{z['frequency_hz']:.2f} Hz/{z['damping']:.2f}" for z in model.zero_table())
        print(f"  zeros of G_track (exact+oe): {zeros}")
        val = ee["identifiability"]
        rms_level = np.sqrt(np.mean(e_pred**2)) / np.sqrt(np.mean(e_true**2)) - 1.0
        print(f"  predicted RMS tracking error {100 * rms_level:+.1f}% of the true one; poles "
              f"{'identifiable' if val['identifiable'] else 'weakly identifiable'}: within 1% of the minimum for "
              f"omega_n {val['omega_n_hz'][0]:.1f}-{val['omega_n_hz'][1]:.1f} Hz, zeta {val['zeta'][0]:.2f}-"
              f"{val['zeta'][1]:.2f}")
        if args.plots:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt

            args.plots.mkdir(parents=True, exist_ok=True)
            axes = model.plot(truth=truth)
            axes[0].figure.suptitle(f"{name}: identified vs true FRFs (cf. Fig. 3.5)")
            axes[0].figure.savefig(args.plots / f"{stem}_frf.png", dpi=110)
            plt.close(axes[0].figure)


if __name__ == "__main__":
    main()
