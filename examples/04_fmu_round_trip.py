"""Round trip through an FMU: export a reduced axis model, validate it, and run it as the
"true machine" of a vcnc simulation next to the Python model.

Run: ``.venv/bin/python examples/04_fmu_round_trip.py [MODEL.json] [--out DIR]``
(without a model file it uses a typical ball-screw axis; without --out it works in a temporary
folder). The same export from the command line: ``vcnc export-fmu MODEL.json -o drive.fmu --fmi 3``.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np
from fmpy.validation import validate_fmu

from identification import ReducedAxisModel, load_model
from interpolators.limits import AxisLimits
from vcnc.engine.machine import Machine
from vcnc.fmu import FmuAxis, export_fmu
from vcnc.setpoints import Setpoints

TYPICAL = {"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0, "d1": -70.0}


def point_to_point(n: int, *, seed: int) -> np.ndarray:
    """Random smooth moves with dwells [mm], like an identification test."""
    rng = np.random.default_rng(seed)
    out, pos = [], 0.0
    while sum(map(len, out)) < n:
        target, m = rng.uniform(-10, 10), int(rng.integers(50, 250))
        out.append(pos + (target - pos) * (0.5 - 0.5 * np.cos(np.pi * np.arange(1, m + 1) / m)))
        out.append(np.full(int(rng.integers(0, 60)), target))
        pos = target
    return np.concatenate(out)[:n]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", nargs="?", help="model file (vcnc.axis-model/1); default: a typical axis")
    parser.add_argument("--out", help="folder for the FMUs (default: a temporary folder)")
    args = parser.parse_args()

    model = load_model(args.model) if args.model else ReducedAxisModel(parameters=TYPICAL, sample_time=0.001)
    ts = model.sample_time
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(args.out or tmp)
        fmus = {v: export_fmu(model, out / f"axis_{model.axis}_fmi{v}.fmu", fmi_version=v) for v in (2, 3)}
        for v, path in fmus.items():
            print(f"FMI {v}.0: {path.name}, {path.stat().st_size} bytes, fmpy validation problems: "
                  f"{len(validate_fmu(str(path)))}")

        ref = point_to_point(10_000, seed=1)
        setpoints = Setpoints.from_positions(ref, sample_time=ts, axes=(model.axis,))
        limits = {model.axis: AxisLimits(velocity=500.0, acceleration=1e4)}
        predicted = Machine.from_axes({model.axis: model}, sample_time=ts, limits=limits).simulate(setpoints)
        for v, path in fmus.items():
            with FmuAxis(path) as axis:
                machine = Machine.from_axes({model.axis: axis}, sample_time=ts, limits=limits)
                capture = machine.simulate(setpoints)
            diff = np.max(np.abs(capture.measured - predicted.measured))
            err = np.max(np.abs(capture.measured[:, 0] - ref)) * 1e3
            print(f"FMI {v}.0 as the true machine: max tracking error {err:.2f} um; "
                  f"max difference to model.simulate() {diff:.1e} mm over {len(ref)} samples")
        if args.out:
            print(f"FMUs left in {out}")


if __name__ == "__main__":
    main()
