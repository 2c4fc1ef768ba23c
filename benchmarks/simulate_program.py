"""``vcnc simulate`` of whole part programs, stage by stage: where the time and the memory go.

Run: ``.venv/bin/python benchmarks/simulate_program.py [PROGRAM ...] [--machine fadal-pid+z]``

Each program (default: two long ones of the G-code corpus, ``VCNC_GCODE_CORPUS``, default
``../shared/data/gcode-corpus`` beside the repository: a 20 min CAM profile with G64 dense code and a
LinuxCNC trajectory-planner test) goes the way ``vcnc simulate PROGRAM --machine M -o F.csv`` takes it:
reading, interpolation, ``Machine.simulate``, the summary (``summarize``: tracking and contour error) and
the capture CSV. Printed per stage: wall and CPU time, and the ratio to the drive simulation
(``Machine.simulate``, the reference measured in the same run: the work the command exists for); then the
CSV writer again against the Python ``%`` writer it replaced (kept here as the reference,
:func:`python_rows`; same bytes checked), and the peak resident memory of the process.

Measured, ``vcnc simulate PROGRAM --machine fadal-pid+z -o F.csv --json F.json`` of main f5fa286 and of this
branch alternately, twice each (2 cores shared with other work at load 6-9, so the wall times are stretched;
the outputs, CSV and JSON, byte for byte the same): corpus 0274 (1.24 million samples) 131.9 / 135.4 s wall and
21.6 / 22.0 s CPU before, 77.3 / 68.9 s wall and 13.4 / 12.3 s CPU after (1.8x wall, 1.7x CPU), peak memory
1.17 GB both; at load ~6, 43.8 / 42.6 s before and 26.0 / 27.6 s after without the last two steps (the garbage
collector off, the column blocks). Corpus 0058 (0.15 million samples): 3.9 s CPU before, 2.9 s after, peak
307-317 MB before, 308 MB after. This script on 0274, main's code against this branch's at load ~8: the summary
(contour) 13.3 s -> 2.3 s CPU, the capture CSV 6.6 s -> 2.1 s CPU (and written while the summary is computed);
the CSV rows 3.2-4x faster than the Python ``%`` writer in every run.
"""

from __future__ import annotations

import argparse
import io
import os
import resource
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from interpolators import load_program  # noqa: E402
from vcnc.commands.interpolate import program_context  # noqa: E402
from vcnc.engine.machine import load_machine  # noqa: E402
from vcnc.facade import interpolate, program_meta  # noqa: E402
from vcnc.simulation_report import summarize  # noqa: E402

CORPUS = Path(os.environ.get("VCNC_GCODE_CORPUS", Path(__file__).resolve().parents[2] / "shared" / "data"
                             / "gcode-corpus"))
PROGRAMS = ("0274_BackFastening_2_OutCut.nc", "0058_LHchips4.ngc")


def python_rows(out: io.StringIO, data: np.ndarray, fmt: list[str], chunk: int = 2000) -> None:
    """The reference CSV writer: ``%`` on the row format repeated over a chunk of rows (main f5fa286)."""
    row = ",".join(fmt) + "\n"
    for start in range(0, len(data), chunk):
        part = data[start : start + chunk]
        out.write((row * len(part)) % tuple(part.ravel().tolist()))


class Stages:
    """Wall and CPU seconds of named stages."""

    def __init__(self) -> None:
        self.wall: dict[str, float] = {}
        self.cpu: dict[str, float] = {}
        self.peak: dict[str, float] = {}

    def run(self, name: str, fn, *args, **kwargs):  # noqa: ANN001, ANN201
        w, c = time.perf_counter(), time.process_time()
        out = fn(*args, **kwargs)
        self.wall[name] = self.wall.get(name, 0.0) + time.perf_counter() - w
        self.cpu[name] = self.cpu.get(name, 0.0) + time.process_time() - c
        self.peak[name] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        return out


def one(path: Path, machine_name: str, tmp: Path) -> None:
    machine = load_machine(machine_name)
    st = Stages()
    args = argparse.Namespace(dialect=None, machine=machine_name)
    program = st.run("read", load_program, path, context=program_context(args, machine))
    sp = st.run("interpolate", interpolate, program, machine, profile="trapezoid")
    capture = st.run("simulate (reference)", machine.simulate, sp, seed=0)
    capture.meta.update(program_meta(sp, path.name, profile="trapezoid"))
    summary = st.run("summary (contour)", summarize, capture)
    st.run("capture CSV", capture.to_csv, tmp / "capture.csv")
    ref = st.wall["simulate (reference)"]
    print(f"\n{path.name} on {machine_name}: {len(capture)} samples; contour "
          f"{summary.get('contour', {}).get('max_um', float('nan')):.4g} um max")
    for name in st.wall:
        print(f"  {name:<22} {st.wall[name]:7.2f} s wall {st.cpu[name]:7.2f} s CPU  {st.wall[name] / ref:6.2f} x "
              f"the simulation; peak memory so far {st.peak[name]:5.0f} MB")
    total = sum(st.wall.values())
    print(f"  {'total':<22} {total:7.2f} s wall {sum(st.cpu.values()):7.2f} s CPU  {total / ref:6.2f} x the simulation")
    n = min(len(capture), 200_000)  # the CSV writers on the first rows of the capture's columns
    signals = [capture.reference, capture.measured, capture.control, capture.table, capture.velocity, capture.friction]
    data = np.column_stack([capture.t[:n], *(a[:n] for a in signals if a is not None)])
    fmt = ["%.12g"] * data.shape[1]
    from vcnc.core.io import write_rows

    mine, ref_out = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    write_rows(mine, data, fmt)
    t1 = time.perf_counter()
    python_rows(ref_out, data, fmt)
    t2 = time.perf_counter()
    same = "yes" if mine.getvalue() == ref_out.getvalue() else "NO"
    print(f"  CSV rows ({data.size} numbers): write_rows {t1 - t0:.3f} s, Python % (reference) {t2 - t1:.3f} s: "
          f"{(t2 - t1) / (t1 - t0):.1f}x faster; same bytes: {same}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("programs", nargs="*", type=Path)
    ap.add_argument("--machine", default="fadal-pid+z")
    a = ap.parse_args()
    programs = a.programs or [CORPUS / p for p in PROGRAMS]
    missing = [p for p in programs if not p.is_file()]
    if missing:
        print(f"skipped: {', '.join(map(str, missing))} not found (VCNC_GCODE_CORPUS)")
        programs = [p for p in programs if p.is_file()]
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        for p in programs:
            one(p, a.machine, Path(tmp))
    print(f"\npeak resident memory {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")


if __name__ == "__main__":
    main()
