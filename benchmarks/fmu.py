"""Speed of an exported axis FMU: steps per second through fmpy.simulate_fmu, through a direct
FMU2Slave loop (fmpy's object API and vcnc.fmu.FmuAxis' raw calls), beside model.simulate().

Run: ``.venv/bin/python benchmarks/fmu.py [steps]`` (default 20,000 steps). Prints figures only.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout, not an installed copy

import numpy as np  # noqa: E402


def best_of(fn, repeat: int = 3) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main(n: int = 20_000) -> None:
    from fmpy import extract, read_model_description, simulate_fmu
    from fmpy.fmi2 import FMU2Slave

    from identification import ReducedAxisModel
    from vcnc.fmu import FmuAxis, export_fmu

    ts = 0.001
    model = ReducedAxisModel(
        parameters={"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0,
                    "d1": -70.0},
        sample_time=ts,
    )
    rng = np.random.default_rng(0)
    ref = np.cumsum(rng.normal(scale=0.01, size=n))
    t = np.arange(n) * ts
    work = Path(tempfile.mkdtemp(prefix="vcnc-bench-fmu-"))
    try:
        t0 = time.perf_counter()
        fmu = export_fmu(model, work / "drive.fmu", fmi_version=2)
        t_export = time.perf_counter() - t0

        model.simulate(ref)  # compile (numba) outside the timing
        t_model = best_of(lambda: model.simulate(ref))

        signals = np.zeros(n, dtype=[("time", float), ("x_ref", float), ("w_ext", float)])
        signals["time"], signals["x_ref"] = t, ref
        t_simulate_fmu = best_of(lambda: simulate_fmu(str(fmu), input=signals, output=["position"],
                                                      stop_time=t[-1], output_interval=ts), repeat=2)

        md = read_model_description(str(fmu))
        unzipdir = extract(str(fmu))

        def slave_loop() -> None:
            s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier,
                          instanceName="bench")
            s.instantiate()
            s.setupExperiment(startTime=0.0)
            s.enterInitializationMode()
            s.setReal([1], [ref[0]])
            s.exitInitializationMode()
            for k in range(n):
                s.setReal([1], [ref[k]])
                s.getReal([3])
                s.doStep(k * ts, ts)
            s.terminate()
            s.freeInstance()

        t_slave = best_of(slave_loop, repeat=2)
        with FmuAxis(fmu) as axis:
            t_axis = best_of(lambda: axis.simulate_reference(ref, ts), repeat=2)
        shutil.rmtree(unzipdir, ignore_errors=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    print(f"FMU export (generate, build, validate, check), FMI 2.0: {t_export:.2f} s")
    print(f"{'path':<44}{'steps/s':>14}{'time [s]':>10}")
    for label, dt in (
        ("model.simulate() (numba)", t_model),
        ("fmpy.simulate_fmu (FMI 2.0 CS)", t_simulate_fmu),
        ("FMU2Slave loop: setReal/getReal/doStep", t_slave),
        ("vcnc.fmu.FmuAxis.simulate_reference", t_axis),
    ):
        print(f"{label:<44}{n / dt:>14,.0f}{dt:>10.4f}")
    print(f"({n} steps of {ts} s, best of 2-3 runs)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20_000)
