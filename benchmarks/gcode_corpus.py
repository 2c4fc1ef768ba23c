"""Run every program of the shared G-code corpus through vcnc: accepted and rejected by reason.

Reads ``../shared/data/gcode-corpus`` (``MANIFEST.tsv``: file, source repository, path, size,
origin tag; or the folder in ``VCNC_GCODE_CORPUS``). For each program: ``load_program`` (ISO or
Heidenhain, by content; the context of ``vcnc interpolate`` without a machine,
``INTERPOLATION_CONTEXT``: axes A B C U V W, read in the dialect of the control the origin tag names,
as its user would with ``--dialect``: :func:`origin_context`), then ``interpolate`` with the default limits
(S-curve off) up to ``--max-samples`` samples. Prints accepted/rejected counts overall, by origin
and by dialect, the
rejections grouped by the feature their message names, the share of milling programs that run
(lathe, probing and remap programs are out of scope, classified by the feature named), and the
interpolation rate in setpoints/s.

Usage: ``python benchmarks/gcode_corpus.py [--parse-only] [--list]``
"""

from __future__ import annotations

import argparse
import collections
import csv
import os
import re
import sys
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from interpolators import Program, detect_dialect, interpolate, load_program  # noqa: E402
from interpolators.context import INTERPOLATION_CONTEXT, MachineContext  # noqa: E402
from vcnc.errors import GCodeError  # noqa: E402

#: Features whose programs are not milling programs (out of scope by the issue): matched against
#: the rejection message.
OUT_OF_SCOPE = re.compile(r"lathe|G7 |G8 |G38 probing|user M code", re.I)


def origin_context(origin: str, base: MachineContext = INTERPOLATION_CONTEXT) -> MachineContext:
    """The context a program of the manifest's ``origin`` tag is read in: ``base`` with the dialect of the
    control the tag names (``haas-*``: hand-written and student programs for Haas mills and lathes,
    ``--dialect haas``: G04 P in ms, G00 the power-on motion mode, G84 out to R); other tags name a CAM
    system or a collection, not a control, and keep ``base``'s dialect (linuxcnc by default)."""
    return base.with_dialect("haas") if origin.startswith("haas-") else base


def corpus_dir() -> Path | None:
    """The corpus folder, or None when it is absent."""
    env = os.environ.get("VCNC_GCODE_CORPUS")
    d = Path(env) if env else ROOT.parent / "shared" / "data" / "gcode-corpus"
    return d if (d / "MANIFEST.tsv").is_file() else None


def manifest(d: Path) -> list[dict[str, str]]:
    with open(d / "MANIFEST.tsv", newline="") as fh:
        return list(csv.DictReader(fh, delimiter="\t"))


def reason(message: str) -> str:
    """The feature a rejection names: the message without file position and the offending text."""
    text = message.split(": ", 1)[-1]
    text = re.sub(r" \(got .*", "", text)
    text = re.sub(r"; expected .*", "", text)
    return text[:90]


#: A word of an axis beyond X Y Z outside a comment (not a parameter ``#<a>``, not the end of another word).
_EXTRA_WORD = re.compile(r"(?<![A-Z#<_])[ABCUVW]\s*[-+]?[.\d]", re.IGNORECASE)
_COMMENT = re.compile(r"\([^)]*\)|;.*")
#: A line with a LinuxCNC configuration's remapped M code (above M199, such as the sims' TCP switch M428).
_REMAPPED_M = re.compile(r"^\s*M\s*0*(?:[2-9]\d\d|\d{4,})\b.*$", re.IGNORECASE | re.MULTILINE)


def extra_axis_lines(text: str) -> int:
    """How many lines of the program have a word of an axis beyond X Y Z (A B C U V W) outside comments."""
    return sum(bool(_EXTRA_WORD.search(_COMMENT.sub("", line))) for line in text.splitlines())


def without_remapped_m(text: str) -> str | None:
    """The program with its lines of remapped M codes (above M199, which vcnc refuses by name) blanked, so that
    its moves can be read; None when it has none."""
    return _REMAPPED_M.sub("", text) if _REMAPPED_M.search(text) else None


def run_corpus(d: Path, *, interpolate_too: bool = True, max_samples: int = 2_000_000,
               visit: Callable[[Path, Program], dict] | None = None) -> dict:
    """Run the corpus; returns the per-program outcomes and the totals. ``visit(path, program)``,
    when given, is called with each program read, and what it returns is added to its record."""
    rows = manifest(d)
    out = []
    samples = 0
    t_interp = 0.0
    for r in rows:
        path = d / r["file"]
        rec = {"file": r["file"], "origin": r["origin"], "ok": False, "reason": "", "dialect": ""}
        try:
            prog = load_program(path, context=origin_context(r["origin"]))
            rec["dialect"] = prog.dialect
            if visit is not None:
                rec.update(visit(path, prog))
            if interpolate_too and prog.blocks:
                t0 = time.perf_counter()
                sp = interpolate(prog, max_samples=max_samples)
                t_interp += time.perf_counter() - t0
                samples += len(sp)
            rec["ok"] = True
        except GCodeError as exc:
            rec["reason"] = reason(str(exc))
            rec["dialect"] = detect_dialect(path.read_bytes().decode("latin-1")) if path.is_file() else ""
            if "max_samples" in str(exc):
                rec["ok"] = True  # parsed; too long to sample here
                rec["reason"] = ""
        out.append(rec)
    return {"programs": out, "samples": samples, "interpolation_s": t_interp}


def _accepted_by(progs: list[dict], key: str) -> list[tuple[str, tuple[int, int]]]:
    """(value of ``key``, (programs accepted, programs)) for each value, sorted."""
    counts: dict[str, list[int]] = collections.defaultdict(lambda: [0, 0])
    for p in progs:
        counts[p[key]][0] += p["ok"]
        counts[p[key]][1] += 1
    return [(k, (a, n)) for k, (a, n) in sorted(counts.items())]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parse-only", action="store_true", help="do not interpolate")
    ap.add_argument("--list", action="store_true", help="list every rejection with its message")
    args = ap.parse_args()
    d = corpus_dir()
    if d is None:
        print("gcode corpus not found (../shared/data/gcode-corpus): nothing to run")
        return 0
    t0 = time.perf_counter()
    res = run_corpus(d, interpolate_too=not args.parse_only)
    wall = time.perf_counter() - t0
    progs = res["programs"]
    ok = sum(p["ok"] for p in progs)
    print(f"corpus: {len(progs)} programs, {ok} accepted, {len(progs) - ok} rejected ({wall:.1f} s)")
    milling = [p for p in progs if p["ok"] or not OUT_OF_SCOPE.search(p["reason"])]
    mok = sum(p["ok"] for p in milling)
    print(f"milling programs (rejections naming lathe/probing/remap features excluded): "
          f"{mok} of {len(milling)} run = {100 * mok / len(milling):.1f} %")
    print("\nby origin:")
    for o, (a, n) in _accepted_by(progs, "origin"):
        print(f"  {o:<34} {a:>3} / {n:<3}")
    print("\nby dialect (of the text, also for the rejected programs):")
    for o, (a, n) in _accepted_by(progs, "dialect"):
        print(f"  {o:<34} {a:>3} / {n:<3} = {100 * a / n:.1f} %")
    reasons = collections.Counter(p["reason"] for p in progs if not p["ok"])
    print("\nrejections by feature:")
    for r, c in reasons.most_common():
        print(f"  {c:>3}  {r}")
    if args.list:
        print("\nrejected programs:")
        for p in progs:
            if not p["ok"]:
                print(f"  {p['file']}: {p['reason']}")
    if not args.parse_only and res["interpolation_s"] > 0:
        print(f"\ninterpolation: {res['samples']} setpoints in {res['interpolation_s']:.1f} s = "
              f"{res['samples'] / res['interpolation_s']:.3g} setpoints/s (trapezoid, default limits, Ts 1 ms)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
