"""Reading throughput of the ISO and Heidenhain readers: lines and blocks per second of ``load_program``.

Run: ``.venv/bin/python benchmarks/reader.py [--lines N] [--tnc-lines N] [--rotary-lines N] [--rotary-only]
[--g93-lines N] [--g93-only] [--largest K] [--repeat R] [FILE ...]``

Programs: the ``K`` largest ISO programs of the G-code corpus (``VCNC_GCODE_CORPUS``, default
``../shared/data/gcode-corpus`` beside the repository; skipped with a message when absent), read with the
context of ``vcnc interpolate`` (``INTERPOLATION_CONTEXT``); a generated CAM program of ``N`` lines (default
1,000,000: ``N`` numbers, ``G1 X Y Z F`` moves, ``G2``/``G3`` arcs with ``I J``, comments); and two programs of
the general machinery: a LinuxCNC O-word ``while`` loop with ``#`` parameters and ``[expressions]``, and the
same moves written with ``#`` parameters on every line. 4/5-axis programs: the corpus' ISO programs with
A B C U V W words on 20 lines or more and a generated 4-axis wrap program of ``N`` lines (default 50,000:
``X Z A`` on every line, as Universal G-code Sender's ``rotation.ngc``), each beside the same program with its
A-W words taken out, read in the same run (the reference: how much the rotary words cost); a generated 5-axis
G93 inverse-time program of ``N`` lines (default 50,000: ``X Y Z A C F`` on every line, the F each move's 1/min), read
with the shortcut and all the general way, beside the same moves in G94 (the reference its ratios are against) and
that G94 form without its A-W words. Heidenhain TNC
programs: the ``K`` largest of the corpus
(by content, :func:`interpolators.detect_dialect`) and a generated CAM program of ``N`` lines (default 200,000:
``L X Y Z F`` lines, ``L IX IY``, ``CC`` + ``C .. DR-``, ``CR .. R.. DR+``, ``L .. FMAX``, ``L .. R0``, M functions,
``;`` comments and ``*`` structure blocks). Any ``FILE`` given is measured too (a wild program kept outside the
repository). Each is timed as ``load_program`` (file read, lexing, execution into blocks), best of ``R`` runs.

The references, measured in the same run on the same file: reading the text and splitting every line into
its space-separated tokens with ``str.split`` (no numbers converted, no state): the least a reader that
looks at every word must spend. The ratio says how many times that the reader takes (for the loop, whose
7 lines run 60,000 times, it says what a loop costs against its text). And for the ISO programs, where LinuxCNC's
standalone interpreter is installed (``rs274``, Debian's ``linuxcnc-uspace``): ``rs274 -g`` on the same file, its
canonical calls written to /dev/null, with its own ``HOME`` in a temporary folder (as
``benchmarks/linuxcnc_diff.py`` runs it); the ratio says how many times rs274's time vcnc takes, and
"refused" marks a program rs274 stops at with an error (its time then covers the lines up to it). Times are
CPU times (``time.process_time`` of this process, ``resource.getrusage`` of the rs274 child: the machine may
be shared).
"""

from __future__ import annotations

import argparse
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.gcode_corpus import extra_axis_lines, without_remapped_m  # noqa: E402
from interpolators import detect_dialect, load_program  # noqa: E402
from interpolators._words import program_text  # noqa: E402
from interpolators.context import INTERPOLATION_CONTEXT  # noqa: E402
from interpolators.iso import parse_iso  # noqa: E402

CORPUS = Path(os.environ.get("VCNC_GCODE_CORPUS", Path(__file__).resolve().parents[2] / "shared" / "data"
                             / "gcode-corpus"))


def cam_program(lines: int) -> str:
    """A CAM-like program of about ``lines`` lines: a spiral of short feed moves, an arc every 50 lines, a
    comment every 500, block numbers on every line, 3-decimal mm coordinates."""
    out = ["(generated CAM program: benchmarks/reader.py)", "G21 G17 G90 G94", "G0 X0 Y0 Z5", "G1 Z-1 F300"]
    x = y = 0.0
    n = 10
    for i in range(lines - len(out)):
        if i % 500 == 0:
            out.append(f"(pass {i // 500})")
            continue
        a = 0.01 * i
        r = 20.0 + 0.0005 * i
        if i % 50 == 25:  # a half circle over to the opposite point and back on the next arc
            out.append(f"N{n} G2 X{-x:.3f} Y{-y:.3f} I{-x:.3f} J{-y:.3f}")
            x, y = -x, -y
        else:
            x, y = r * math.cos(a), r * math.sin(a)
            out.append(f"N{n} G1 X{x:.3f} Y{y:.3f} Z{-1 - 0.00001 * i:.4f} F{1200 + i % 7 * 100}")
        n += 10
    out.append("M30")
    return "\n".join(out) + "\n"


def rotary_program(lines: int) -> str:
    """A 4-axis wrap program as a CAM post for a rotary table writes it (Universal G-code Sender's
    ``test_files/rotation.ngc`` is one): passes along X at a stepped A angle, ``X Z A`` on every line (modal G1,
    1-decimal X, 4-decimal Z and A), the depth following a surface, a rapid retract and an A step between passes."""
    out = ["(generated 4-axis wrap program: benchmarks/reader.py)", "G21 G90 G94", "G0 X0.0 Z45.0 A0.0",
           "G1 F50.0 X0.0 Z20.0 A0.0", "G1 F100.0"]
    per_pass = 161
    i = 0
    while len(out) < lines - 1:
        a = -1.1465 * (i // per_pass)
        k = i % per_pass
        x = 0.5 * (k if (i // per_pass) % 2 == 0 else per_pass - 1 - k)
        out.append(f"X{x:.1f} Z{19.9 + 0.002 * math.sin(0.05 * x + 0.02 * a):.4f} A{a:.4f}")
        i += 1
    out.append("M30")
    return "\n".join(out) + "\n"


def five_axis_program(lines: int, *, inverse_time: bool = True) -> str:
    """A 5-axis simultaneous program of about ``lines`` lines as a CAM post for an A/C table writes it: passes of
    200 moves ``X Y Z A C`` (4 decimals, the tool flank along a twisted ruled surface: A tilting 20-40 deg, C turning
    with the pass), a rapid retract and approach between passes. ``inverse_time``: G93 with each move's F in 1/min
    (its time: the XYZ length over 1,500 mm/min, 4 significant decimals, as a post computes it), ``G93`` on the first
    feed move of a pass and ``G94`` back on the retract; else the same moves in G94 with ``F1500.`` on a pass's first
    feed move (the modal feed after it)."""
    out = [f"(generated 5-axis {'G93 inverse time' if inverse_time else 'G94'} program: benchmarks/reader.py)",
           "G21 G17 G90 G94", "G0 X0. Y0. Z50. A0. C0."]
    k = 0
    while len(out) < lines - 1:
        z0 = -0.01 * (k % 50)
        pts = []
        for i in range(200):
            t = 2 * math.pi * (k + i / 200.0) / 7.0
            r = 40.0 + 5.0 * math.sin(3 * t)
            pts.append((r * math.cos(t), r * math.sin(t), z0 - 8.0 * math.sin(t) ** 2,
                        30.0 + 10.0 * math.sin(2 * t), math.degrees(t) % 360.0))
        x, y, z, a, c = pts[0]
        out += [f"G0 X{x:.4f} Y{y:.4f} Z5. A{a:.4f} C{c:.4f}", f"G1 Z{z:.4f} F300."]
        prev = pts[0]
        for j, (x, y, z, a, c) in enumerate(pts[1:]):
            words = f"X{x:.4f} Y{y:.4f} Z{z:.4f} A{a:.4f} C{c:.4f}"
            if inverse_time:
                length = math.dist(prev[:3], (x, y, z)) or 1e-3
                out.append(f"{'G93 G1 ' if j == 0 else ''}{words} F{1500.0 / length:.4f}")
            else:
                out.append(f"{words}{' F1500.' if j == 0 else ''}")
            prev = (x, y, z, a, c)
        out.append(("G94 " if inverse_time else "") + "G0 Z5.")
        k += 1
    out.append("M30")
    return "\n".join(out) + "\n"


def without_extra_words(text: str) -> str:
    """``text`` with its A B C U V W words taken out: the same program on three axes (the reference of a rotary
    program's reading)."""
    return re.sub(r"[ \t]?[ABCUVW]-?[\d.]+", "", text)


def tnc_program(lines: int) -> str:
    """A TNC program as a CAM post writes it, of about ``lines`` lines: a spiral of short ``L`` moves with block
    numbers and 4-decimal signed coordinates, every 50th block an arc about ``CC`` (``C .. DR-``) and every 50th
    (25 later) one by radius (``CR .. R.. DR+``), incremental lines, feed changes and M functions now and then, a
    rapid retract and a structure block every 1,000 lines, a ``;`` comment every 500."""
    out = ["0 BEGIN PGM CAM MM", "1 BLK FORM 0.1 Z X-60 Y-60 Z-20", "2 BLK FORM 0.2 X+60 Y+60 Z+0",
           "3 TOOL CALL 5 Z S12000", "4 L X+0 Y+0 Z+5 R0 FMAX M3", "5 L Z-1 F300 M8"]
    x = y = 0.0
    i = 0
    while len(out) < lines - 1:
        i += 1
        n = len(out)
        if i % 1000 == 999:
            out.append(f"* - pass {i // 1000}")
            continue
        if i % 500 == 0:
            out.append(f"{n} ;finishing pass {i // 500}")
            continue
        a = 0.01 * i
        r = 20.0 + 0.0005 * i
        if i % 1000 == 998:
            out.append(f"{n} L Z+5 R0 FMAX")
        elif i % 50 == 20:  # a half circle about the centre, to the opposite point
            out.append(f"{n} CC X+0 Y+0")
            out.append(f"{n + 1} C X{-x:+.4f} Y{-y:+.4f} DR-")
            x, y = -x, -y
        elif i % 50 == 45:  # a half circle by radius, over to the opposite point
            out.append(f"{n} CR X{-x:+.4f} Y{-y:+.4f} R+{math.hypot(x, y) + 0.001:.4f} DR+")
            x, y = -x, -y
        elif i % 50 == 10:
            out.append(f"{n} L IX+0.001 IY-0.001")
            x, y = x + 0.001, y - 0.001
        else:
            x, y = r * math.cos(a), r * math.sin(a)
            feed = f" F{1200 + i % 11 * 100}" if i % 7 == 0 else ""
            out.append(f"{n} L X{x:+.4f} Y{y:+.4f} Z{-1 - 0.00001 * i:+.4f}{feed}{' M90' if i % 3 == 0 else ''}")
    out.append(f"{len(out)} END PGM CAM MM")
    return "\n".join(out) + "\n"


def param_loop_program(passes: int) -> str:
    """A LinuxCNC O-word ``while`` loop of ``passes`` passes: ``#`` parameters, expressions, a feed move each."""
    return (f"G21 G90 G94 F1000\n#1 = 0\no100 while [#1 LT {passes}]\n"
            "  G1 X[20 * COS[#1 * 0.5]] Y[20 * SIN[#1 * 0.5]] Z[-0.001 * #1]\n"
            "  #1 = [#1 + 1]\no100 endwhile\nM2\n")


def param_lines_program(lines: int) -> str:
    """``lines`` feed moves, each setting a parameter and reading it back in an expression."""
    out = ["G21 G90 G94 F1000"]
    for i in range(lines):
        out.append(f"#<x> = {20 * math.cos(0.01 * i):.4f}")
        out.append(f"G1 X#<x> Y[{20 * math.sin(0.01 * i):.4f} + 1] Z-1")
    out.append("M2")
    return "\n".join(out) + "\n"


def reference(path: Path) -> float:
    """Seconds to read the file's text and split every line into tokens (best of 3)."""
    best = math.inf
    for _ in range(3):
        t0 = time.process_time()
        text = path.read_text(encoding="latin-1")
        n = sum(len(ln.split()) for ln in text.split("\n"))
        best = min(best, time.process_time() - t0)
    assert n >= 0
    return best


def rs274_reference(path: Path) -> tuple[float, bool] | None:
    """CPU seconds of ``rs274 -g`` on the file (best of 3) and whether it refused the program; None without
    rs274."""
    if shutil.which("rs274") is None:
        return None
    best, refused = math.inf, False
    with tempfile.TemporaryDirectory(prefix="reader-rs274-") as home:
        for _ in range(3):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            run = subprocess.run(["rs274", "-g", str(path.resolve())], cwd=home, env=dict(os.environ, HOME=home),
                                 stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            best = min(best, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
            refused = run.returncode != 0
    return best, refused


def measure(label: str, path: Path, repeat: int, *, rs274: bool = True, shortcuts: bool = True,
            against: tuple[str, float] | None = None) -> float:
    """Print lines/s, blocks/s of ``load_program`` and the ratios to :func:`reference` and (``rs274``: an ISO
    program) :func:`rs274_reference`; return the time [s]. ``shortcuts=False``: an ISO program read all the general
    way (``parse_iso(shortcuts=False)``); ``against``: the name and time of another reading of the same run, whose
    ratio is printed too."""
    lines = path.read_bytes().count(b"\n")
    best = math.inf
    for _ in range(repeat):
        t0 = time.process_time()
        if shortcuts:
            program = load_program(path, context=INTERPOLATION_CONTEXT)
        else:
            program = parse_iso(program_text(str(path)), source=str(path), context=INTERPOLATION_CONTEXT,
                                shortcuts=False)
        best = min(best, time.process_time() - t0)
    ref = reference(path)
    rs274 = rs274_reference(path) if rs274 else None
    other = "" if rs274 is None else (f"  x{best / rs274[0]:5.1f} rs274 ({rs274[0]:.2f} s, {lines / rs274[0]:,.0f} "
                                      f"lines/s{', refused' if rs274[1] else ''})")
    if against is not None:
        other += f"  x{best / against[1]:5.2f} {against[0]}"
    print(f"{label:44s} {lines:>9,d} lines {len(program.blocks):>9,d} blocks  {best:7.2f} s  "
          f"{lines / best:>10,.0f} lines/s {len(program.blocks) / best:>10,.0f} blocks/s  "
          f"x{best / ref:6.0f} the str.split reference ({ref * 1e3:.1f} ms){other}")
    return best


def g93_section(lines: int, repeat: int) -> None:
    """A 5-axis G93 program of ``lines`` lines (:func:`five_axis_program`) read with the shortcut and all the general
    way (what it took before the shortcut took G93), beside its G94 form and its XYZ form (the G94 form without its
    A-W words, :func:`without_extra_words`); the ratios against the G94 form, measured in the same run."""
    g94 = five_axis_program(lines, inverse_time=False)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "program.ngc"
        path.write_text(g94)
        reference_time = measure(f"5-axis G94 form, {lines:,d} lines", path, repeat, rs274=False)
        against = ("the G94 form", reference_time)
        path.write_text(five_axis_program(lines))
        measure(f"5-axis G93, {lines:,d} lines", path, repeat, rs274=False, against=against)
        measure("5-axis G93, all the general way", path, repeat, rs274=False, shortcuts=False, against=against)
        path.write_text(without_extra_words(g94))
        measure("its XYZ form (G94, A-W words out)", path, repeat, rs274=False, against=against)


def rotary_section(lines: int, repeat: int) -> None:
    """4/5-axis programs, each measured beside its reference read in the same run: the same program with its
    A B C U V W words taken out (:func:`without_extra_words`). The corpus' ISO programs with extra-axis words on 20
    lines or more (a LinuxCNC configuration's remapped M codes blanked, :func:`without_remapped_m`), and a generated
    4-axis wrap program of ``lines`` lines (:func:`rotary_program`)."""
    programs = []
    if CORPUS.is_dir():
        for p in sorted(CORPUS.iterdir()):
            text = p.read_bytes().decode("latin-1")
            if p.suffix.lower() not in (".tsv", ".md") and detect_dialect(text) == "iso" \
                    and extra_axis_lines(text) >= 20:
                programs.append((f"corpus {p.name[:30]}", without_remapped_m(text) or text))
    programs.append((f"generated 4-axis wrap, {lines:,d} lines", rotary_program(lines)))
    with tempfile.TemporaryDirectory() as tmp:
        for label, text in programs:
            for suffix, body in (("", text), (", A-W words out", without_extra_words(text))):
                path = Path(tmp) / "program.ngc"
                path.write_text(body)
                measure(label[:44 - len(suffix)] + suffix, path, repeat, rs274=False)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lines", type=int, default=1_000_000, help="lines of the generated CAM program")
    ap.add_argument("--tnc-lines", type=int, default=200_000, help="lines of the generated TNC program")
    ap.add_argument("--largest", type=int, default=3, help="how many of the corpus' largest ISO and TNC programs")
    ap.add_argument("--rotary-lines", type=int, default=50_000, help="lines of the generated 4-axis program")
    ap.add_argument("--repeat", type=int, default=1, help="runs per program (the best is shown)")
    ap.add_argument("files", nargs="*", type=Path, help="further programs to measure")
    ap.add_argument("--rotary-only", action="store_true", help="only the 4/5-axis programs and their references")
    ap.add_argument("--g93-lines", type=int, default=50_000, help="lines of the generated 5-axis G93 program")
    ap.add_argument("--g93-only", action="store_true", help="only the 5-axis G93 program and its references")
    args = ap.parse_args()
    if args.g93_only:
        g93_section(args.g93_lines, args.repeat)
        return
    if CORPUS.is_dir() and not args.rotary_only:
        by_size = [p for p in sorted(CORPUS.iterdir(), key=lambda p: -p.stat().st_size)
                   if p.suffix.lower() not in (".tsv", ".md")]
        dialects = {p: detect_dialect(p.read_bytes().decode("latin-1")) for p in by_size}
        for dialect in ("iso", "heidenhain"):
            for p in [p for p in by_size if dialects[p] == dialect][:args.largest]:
                measure(f"corpus {p.name[:37]}", p, args.repeat, rs274=dialect == "iso")
    elif not CORPUS.is_dir():
        print(f"G-code corpus not found at {CORPUS} (set VCNC_GCODE_CORPUS): corpus programs skipped")
    rotary_section(args.rotary_lines, args.repeat)
    g93_section(args.g93_lines, args.repeat)
    if args.rotary_only:
        return
    with tempfile.TemporaryDirectory() as tmp:
        for label, text in ((f"generated CAM, {args.lines:,d} lines", cam_program(args.lines)),
                            ("O-word while loop, 20,000 passes", param_loop_program(20_000)),
                            ("# parameters on every line, 2 x 50,000", param_lines_program(50_000))):
            path = Path(tmp) / "program.ngc"
            path.write_text(text)
            measure(label, path, args.repeat)
        path = Path(tmp) / "program.h"
        path.write_text(tnc_program(args.tnc_lines))
        measure(f"generated TNC, {args.tnc_lines:,d} lines", path, args.repeat, rs274=False)
    for path in args.files:
        measure(path.name[:44], path, args.repeat,
                rs274=detect_dialect(path.read_bytes().decode("latin-1")) == "iso")


if __name__ == "__main__":
    main()
