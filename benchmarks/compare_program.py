"""``vcnc compare`` of a part program against ``vcnc simulate`` of it: how much more the comparison costs.

Run: ``.venv/bin/python benchmarks/compare_program.py [PROGRAM ...] [--machine fadal-pid+z]``

Each program (default: corpus 0001_3D_Chips.ngc, 4,700 blocks of 3D surfacing, of the G-code corpus
``VCNC_GCODE_CORPUS``, default ``../shared/data/gcode-corpus`` beside the repository) is interpolated for the machine,
then timed twice in the same run: the work of ``vcnc simulate`` (``Machine.simulate`` and ``summarize``: tracking and
contour error, the reference) and ``vcnc.contour_compare.compare`` with the machine's own reduced models (the true
machine run once per noise realisation, 10 on a machine with measurement noise, the models' predictions, the
contour of each and the summary). Printed: CPU and wall seconds of both, their ratio, and the ratio per simulation
run (compare runs the machine ``runs`` times and the models twice).

Measured (comparewild, session 28; 2 cores shared with five other jobs, so CPU time is the figure), 3D_Chips
(62,417 samples, 17,727 segments) on fadal-pid+z: simulate + summary 0.08 s CPU; compare 13.3 s CPU on main
4f38df7 (ratio 171, 14.2 per simulation run: the contour metrics of its 22 contours each finding the path's corners
and their points again, and the noise realisations' mean through numpy on every corner's numbers) and 3.1 s on
this branch (ratio 41, 3.4 per simulation run: ``vcnc.contour.feature_points`` once per path, each label's
metrics once, the mean in plain Python). The main figure from this script with ``sys.path`` on /work/main.

Measured (compareguard, session 28, same conditions), main c44e16d -> this branch: 3D_Chips 3.01 -> 1.88 s CPU (ratio
39 -> 24, 3.25 -> 2.03 per simulation run); corpus 0274_BackFastening_2_OutCut.nc (1,241,431 samples, 196,180
segments) 47.6 -> 29.9 s CPU (ratio 30 -> 15, 2.52 -> 1.26 per simulation run): the path packed
(``vcnc.contour._pack``) and the command located on it (``vcnc.contour.commanded_points``) once instead of 22 times,
each corner's window maximum in one ``np.maximum.reduceat`` instead of a numpy call per corner (134,647 corners), a
corner's position, the same object in every run, not averaged. What is left is the work itself: per simulation run
one machine simulation and two nearest-point searches (true position and sensor reading), where simulate's summary
does one search.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from identification import ReducedAxisModel  # noqa: E402
from interpolators import load_program  # noqa: E402
from vcnc.contour_compare import compare  # noqa: E402
from vcnc.engine.machine import load_machine  # noqa: E402
from vcnc.facade import interpolate  # noqa: E402
from vcnc.simulation_report import summarize  # noqa: E402

CORPUS = Path(os.environ.get("VCNC_GCODE_CORPUS", Path(__file__).resolve().parents[2] / "shared" / "data"
                             / "gcode-corpus"))
PROGRAMS = ("0001_3D_Chips.ngc",)


def timed(fn, *args):
    """(result, CPU seconds, wall seconds) of ``fn(*args)``."""
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn(*args)
    return out, time.process_time() - c0, time.perf_counter() - w0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("programs", nargs="*", help="program files (default: corpus 0001_3D_Chips.ngc)")
    ap.add_argument("--machine", default="fadal-pid+z")
    args = ap.parse_args()
    machine = load_machine(args.machine)
    models = {a: ReducedAxisModel(parameters=machine.axis(a).reduced_parameters(), sample_time=machine.sample_time,
                                  axis=a) for a in machine.axes}
    for name in args.programs or [str(CORPUS / p) for p in PROGRAMS]:
        if not Path(name).is_file():
            print(f"{name}: not found (set VCNC_GCODE_CORPUS)")
            continue
        program = load_program(name, context=machine.context)
        sp = interpolate(program, machine)
        moving = {a: models[a] for a in sp.axes}
        _, sim_cpu, sim_wall = timed(summarize, machine.simulate(sp), program)  # the capture's summary
        _, sim_cpu2, sim_wall2 = timed(machine.simulate, sp)
        sim_cpu, sim_wall = sim_cpu + sim_cpu2, sim_wall + sim_wall2
        report, cmp_cpu, cmp_wall = timed(compare, machine, moving, program)
        rep, sum_cpu, sum_wall = timed(report.to_dict)
        cmp_cpu, cmp_wall = cmp_cpu + sum_cpu, cmp_wall + sum_wall
        runs = rep["true"].get("runs", 1)
        print(f"{Path(name).name}: {len(sp)} samples, {len(sp.path.segments)} segments on {machine.name}")
        print(f"  simulate + summary (reference): {sim_cpu:7.2f} s CPU {sim_wall:7.2f} s wall")
        print(f"  compare ({runs} truth runs, 2 predictions): {cmp_cpu:7.2f} s CPU {cmp_wall:7.2f} s wall; "
              f"ratio {cmp_cpu / sim_cpu:.2f} CPU, {cmp_cpu / sim_cpu / (runs + 2):.2f} per simulation run")


if __name__ == "__main__":
    main()
