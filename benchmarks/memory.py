"""Memory of reading and planning a long program: bytes per block, against references measured in the same run.

Run: ``.venv/bin/python benchmarks/memory.py [--lines N] [FILE ...]``

Programs: a 3D surfacing raster as CAM output writes it, ``N`` lines (default 200,000) of ``X.. Y.. Z..``
after ``G1 Z0 F1500`` (ISO, G64 continuous path: the dense lines are merged into curves) and the same program
under G61 (every block a chain of its own, the planner's per-chain records at their largest), and as a TNC
program of ``L X.. Y.. Z..`` blocks; any ``FILE`` given is measured too. Each program is measured in child
processes of its own, so that one does not count the memory another left:

* traced (``tracemalloc``: the Python objects and NumPy arrays allocated): reading, the bytes the program holds
  after ``load_program`` and the peak during it; planning, the peak of ``interpolate`` above the program. Per
  block of the program.
* untraced: the process's max RSS after the imports (and a short program read and planned), after
  ``load_program`` and after ``interpolate`` [MB].

The references, measured in the same run on the same program: the bytes of the program's text per block (what
the file costs), and the bytes of the setpoints per block (``t``, position, velocity, acceleration and block of
every sample: what ``interpolate`` must hold anyway; the planning peak includes them).

Measured (200,000 lines, 2 shared cores), before (main ae25e37) -> after the slotted blocks sharing their position
arrays, the planner's flat chain records and the smaller sample chunks, the same setpoints bit for bit:
ISO G64 reading 1401 -> 609 B/block live, planning peak 1358 -> 646 B/block (356 of it the setpoints), max RSS
after planning 701 -> 451 MB; ISO G61 planning 2647 -> 1875 B/block (1322 the setpoints), 970 -> 713 MB; TNC
reading 1448 -> 656 B/block live (peak 2010 -> 1218); corpus 0274 (102,308 blocks, corner blends) reading
1426 -> 634 B/block, planning 4100 -> 3304 B/block (1068 the setpoints), 719 -> 614 MB.
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from interpolators import interpolate, load_program, parse_program  # noqa: E402

MB = 1 << 20


def surfacing_points(lines: int) -> list[tuple[float, float, float]]:
    """About ``lines`` points of a zigzag raster over 100 x 100 mm, 0.1 mm apart along X, rows 0.5 mm apart, on a
    smooth surface 0.5 to 1 mm deep."""
    pts = []
    for i in range(lines):
        row, k = divmod(i, 1000)
        x = 0.1 * (k if row % 2 == 0 else 999 - k)
        y = 0.5 * row
        pts.append((x, y, -1.0 + 0.5 * math.sin(math.pi * x / 200.0) * (1.0 + 0.1 * math.cos(y / 7.0))))
    return pts


def iso_program(lines: int, *, exact_stop: bool = False) -> str:
    """The raster as an ISO program (G64 continuous path, or G61 exact stop)."""
    head = ["G21 G90 G17 G54 " + ("G61" if exact_stop else "G64"), "T1 M6", "S12000 M3", "G0 X0 Y0 Z5",
            "G1 Z0 F1500"]
    body = [f"X{x:.3f} Y{y:.3f} Z{z:.4f}" for x, y, z in surfacing_points(lines)]
    return "\n".join([*head, *body, "G0 Z5", "M30"]) + "\n"


def tnc_program(lines: int) -> str:
    """The raster as a TNC program: numbered ``L`` blocks with signed coordinates."""
    head = ["BEGIN PGM SURF MM", "BLK FORM 0.1 Z X+0 Y+0 Z-40", "BLK FORM 0.2 X+100 Y+100 Z+0",
            "TOOL CALL 1 Z S12000", "L X+0 Y+0 Z+5 R0 FMAX M3", "L Z+0 F1500"]
    body = [f"L X{x:+.3f} Y{y:+.3f} Z{z:+.4f}" for x, y, z in surfacing_points(lines)]
    text = [*head, *body, "L Z+5 FMAX", "END PGM SURF MM"]
    return "\n".join(f"{n} {ln}" for n, ln in enumerate(text)) + "\n"


def _max_rss() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: kB


def child(mode: str, path: str) -> dict:
    """Measure one program in this process: ``traced`` (tracemalloc, bytes) or ``rss`` (max RSS, MB). A short
    program is read and planned first, so that the modules imported on first use are not counted."""
    interpolate(parse_program(iso_program(2000)))
    if mode == "rss":
        out = {"import": _max_rss()}
        prog = load_program(path)
        out["load"] = _max_rss()
        interpolate(prog)
        out["plan"] = _max_rss()
        return out
    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    t0 = time.process_time()
    prog = load_program(path)
    t1 = time.process_time()
    live, read_peak = tracemalloc.get_traced_memory()
    tracemalloc.reset_peak()
    sp = interpolate(prog)
    t2 = time.process_time()
    plan_peak = tracemalloc.get_traced_memory()[1]
    sp_bytes = sum(a.nbytes for a in (sp.t, sp.position, sp.velocity, sp.acceleration, sp.block))
    return {"blocks": len(prog.blocks), "live": live - base, "read_peak": read_peak - base,
            "plan_peak": plan_peak - live, "setpoints": sp_bytes, "samples": len(sp.t),
            "text": Path(path).stat().st_size, "read_s": t1 - t0, "plan_s": t2 - t1}


def _run_child(mode: str, path: Path) -> dict:
    res = subprocess.run([sys.executable, __file__, "--child", mode, str(path)], capture_output=True, text=True,
                         check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def report(name: str, path: Path) -> None:
    t = _run_child("traced", path)
    r = _run_child("rss", path)
    n = max(t["blocks"], 1)
    print(f"{name}: {t['blocks']:,} blocks, {t['samples']:,} samples (traced run: read {t['read_s']:.1f} s, "
          f"plan {t['plan_s']:.1f} s CPU)")
    print(f"  reading : live {t['live'] / n:7.0f} B/block, peak {t['read_peak'] / n:7.0f} B/block"
          f"   reference: program text {t['text'] / n:5.0f} B/block")
    print(f"  planning: peak {t['plan_peak'] / n:7.0f} B/block above the program"
          f"   reference: setpoints {t['setpoints'] / n:5.0f} B/block")
    print(f"  max RSS : imports {r['import']:.0f} MB, after reading {r['load']:.0f} MB, after planning "
          f"{r['plan']:.0f} MB")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=200_000, help="lines of the generated programs")
    ap.add_argument("--child", nargs=2, metavar=("MODE", "FILE"), help=argparse.SUPPRESS)
    ap.add_argument("files", nargs="*", help="more programs to measure")
    args = ap.parse_args()
    if args.child:
        print(json.dumps(child(*args.child)))
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        generated = {"ISO surfacing, G64": ("surf.nc", iso_program(args.lines)),
                     "ISO surfacing, G61": ("surf61.nc", iso_program(args.lines, exact_stop=True)),
                     "TNC surfacing": ("surf.h", tnc_program(args.lines))}
        for name, (file, text) in generated.items():
            path = Path(tmp) / file
            path.write_text(text)
            report(name, path)
    for f in args.files:
        report(f, Path(f))
    return 0


if __name__ == "__main__":
    sys.exit(main())
