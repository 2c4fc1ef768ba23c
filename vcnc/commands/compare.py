"""``vcnc compare``: contour error of a toolpath on the true machine vs. as predicted by models.

``--model`` is given once for all axes (the same model on each moving axis, as in the thesis'
X/Y cases when one axis was identified) or once per axis as ``AXIS=FILE``
(``--model x=mx.json --model y=my.json``). The two forms do not mix. Everything is computed
before anything is written; a failure leaves no file behind.

A program file run on a simulated truth is read as ``vcnc simulate`` reads it
(:func:`vcnc.commands.simulate.read_for_machine`): in the true machine's context (its rotary axes, its
dialect and tool table, ``--dialect`` and the other reader options), its notes printed, a move of an axis the
machine lacks refused naming the line and the way forward (``NAME+z``, an ``[axes.a]`` section). With a captured
truth the program is read as ``vcnc interpolate`` reads it (the reader options, its notes printed).

``--max-seconds S`` compares the blocks that run within the first S seconds, cut as ``vcnc simulate`` cuts them
(:func:`vcnc.facade.interpolate`; a note and the summary's ``truncated`` say where); without it a program needing
more than :data:`MAX_SAMPLES` samples is refused naming the option (the guard of ``vcnc simulate`` and ``vcnc
interpolate``, :func:`vcnc.commands.interpolate.sample_guard`).
"""

from __future__ import annotations

import argparse
import sys

from vcnc.commands.export_fmu import check_model_file
from vcnc.commands.interpolate import add_context_arguments, print_program_notes, read_program, sample_guard
from vcnc.commands.trace_options import add_trace_arguments, read_trace_argument
from vcnc.core.errors import InputError

HELP = "compare the contour error of a toolpath on a true machine with that predicted by axis models"

#: Samples ``vcnc compare`` runs without ``--max-seconds`` (25 min at Ts = 1 ms): a longer program is refused, naming
#: the option, rather than running the machine out of memory. It keeps the setpoints, the true and sensed contour of the
#: first noise run and the two predictions' contours while it simulates the next run: measured peak (/usr/bin/time -v)
#: 0.75 GB at 0.6 and 1.80 GB at 1.8 million samples of four axes (a 4-axis program, XYZA on a machine file, ten noise
#: runs; the report adds nothing to the peak), so 0.23 GB + 0.88 kB a sample, about 1.55 GB here.
MAX_SAMPLES = 1_500_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--truth", required=True, metavar="NAME|FILE|CAPTURE",
                        help="built-in machine name or machine TOML file (all non-idealities on), or a capture or "
                             "control trace of the toolpath run on the real machine (detected by content)")
    parser.add_argument("--model", required=True, action="append", metavar="[AXIS=]MODEL.json",
                        help="model file: once for all axes, or AXIS=FILE once per axis")
    parser.add_argument("--toolpath", default="circle", metavar="circle|diamond|PROGRAM",
                        help="built-in toolpath (circle 40 mm diameter, diamond 40 mm across) or a program file")
    parser.add_argument("--feed", type=float, default=None, metavar="MM_S",
                        help="feed of the built-in toolpaths [mm/s] (default 200)")
    parser.add_argument("--acceleration", type=float, default=None, metavar="MM_S2",
                        help="axis acceleration limit of the interpolation [mm/s^2] (default: the machine's)")
    parser.add_argument("--profile", choices=("trapezoid", "scurve"), default="trapezoid", help="feed profile")
    parser.add_argument("--seed", type=int, default=0, help="seed of the true machine's measurement noise")
    parser.add_argument("--truth-runs", type=int, default=None, metavar="N",
                        help="noise realisations of the true machine, seeds SEED..SEED+N-1; its contour error is "
                             "their mean (default 10 when the machine has measurement noise, else 1)")
    parser.add_argument("--max-seconds", type=float, metavar="S",
                        help="compare only the blocks of the toolpath that run within its first S seconds on a "
                             "simulated truth (a note and the summary's 'truncated' say where the program was cut; "
                             f"default: the whole program, refused beyond {MAX_SAMPLES:,} samples)")
    parser.add_argument("--json", metavar="F", help="write the summary JSON")
    parser.add_argument("--report", metavar="DIR", help="write an HTML report with figures into DIR")
    add_trace_arguments(parser)
    add_context_arguments(parser)


def parse_models(values: list[str]) -> str | dict[str, str]:
    """``--model`` values -> one file, or a dict axis -> file; InputError on a bad form."""
    from vcnc.core.setpoints import AXIS_NAMES

    per_axis: dict[str, str] = {}
    plain: list[str] = []
    for v in values:
        axis, sep, file = v.partition("=")
        if sep and axis.strip().lower() in AXIS_NAMES and not file.strip():
            raise InputError(f"--model {v!r}: no model file after '='", expected="AXIS=FILE")
        if sep and axis.strip().lower() in AXIS_NAMES:
            a = axis.strip().lower()
            if a in per_axis:
                raise InputError(f"--model given twice for axis {a}", text=v)
            per_axis[a] = file
        elif sep and len(axis) <= 2:
            raise InputError(f"--model {v!r}: unknown axis {axis!r}", expected=f"AXIS=FILE with AXIS one of "
                             f"{', '.join(AXIS_NAMES)}")
        else:
            plain.append(v)
    if plain and per_axis:
        raise InputError("--model: give either one file for all axes or AXIS=FILE for each axis, not both")
    if len(plain) > 1:
        raise InputError(f"--model given {len(plain)} times without an axis; use AXIS=FILE for each axis")
    return plain[0] if plain else per_axis


def _truth(args: argparse.Namespace):
    """``--truth``: a machine name or TOML file as given, or the capture a trace file holds."""
    from pathlib import Path

    from vcnc.traces import trace_format

    trace_options = args.columns or args.time_unit or args.unit or args.axis_names
    if Path(args.truth).is_file() and (trace_options or trace_format(args.truth) != "delimited"):
        return read_trace_argument(args.truth, args)
    return args.truth


def _machine_and_program(truth, toolpath: str, args: argparse.Namespace) -> tuple:
    """(truth, toolpath): for a program file, the program read with the reader options (``--dialect`` ..., its
    notes printed): for a simulated truth the machine loaded and the program read for it as ``vcnc simulate``
    reads it, for a captured truth as ``vcnc interpolate`` reads it (the capture's commanded positions are the
    setpoints, the program gives its path); else both as given."""
    from pathlib import Path

    from vcnc.commands.simulate import read_for_machine
    from vcnc.contour_compare import SHAPES
    from vcnc.engine.machine import load_machine

    if toolpath in SHAPES or not Path(toolpath).is_file() or args.feed is not None:
        return truth, toolpath  # (compare refuses --feed with a program, naming it)
    program_args = argparse.Namespace(**{**vars(args), "program": toolpath})
    if isinstance(truth, str):
        truth = load_machine(truth)
        program = read_for_machine(program_args, truth, option="--truth")
    else:
        program = read_program(program_args)
    print_program_notes(program, toolpath)
    return truth, program


def run(args: argparse.Namespace) -> int:
    from vcnc.contour_compare import compare
    from vcnc.core.io import check_distinct_outputs, check_output

    models = parse_models(args.model)
    model_files = (models,) if isinstance(models, str) else tuple(models.values())
    inputs = (args.truth, args.toolpath, args.tool_table, args.datum_table, *model_files)
    check_output(args.json, option="--json", what="the summary file", inputs=inputs)
    check_output(args.report, option="--report", what="the report", folder=True)
    check_distinct_outputs((("--json", args.json), ("--report", args.report)))
    for file in model_files:
        check_model_file(file)
    truth, toolpath = _machine_and_program(_truth(args), args.toolpath, args)
    with sample_guard(command="compare", max_samples=MAX_SAMPLES):
        result = compare(truth, models, toolpath, feed=args.feed, acceleration=args.acceleration,
                         profile=args.profile, seed=args.seed, truth_runs=args.truth_runs,
                         max_duration=args.max_seconds, max_samples=None if args.max_seconds else MAX_SAMPLES)
    summary = result.to_dict()
    rep = result.report() if args.report else None
    if args.json:
        result.to_json(args.json)
    if rep is not None:
        rep.write(args.report)
    out = sys.stdout
    t, p, pe = summary["true"], summary["predicted"], summary["prediction_error_pct"]
    out.write(f"{summary['toolpath']} on {summary['truth']}: {summary['samples']} samples, "
              f"Ts {summary['sample_time']:g} s\n")
    runs = ""
    if "spread" in t:
        lo, hi = t["spread"]["contour_max_um"]
        runs = f" (mean of {t['runs']} noise realisations; max {lo:.4g}-{hi:.4g} um)"
    out.write(f"true      contour error: max {t['contour_max_um']:.4g} um, rms {t['contour_rms_um']:.4g} um{runs}\n")
    label = "augmented" if "before_augmentation" in summary else "predicted"
    if "before_augmentation" in summary:
        b = summary["before_augmentation"]
        out.write(f"identified contour error: max {b['contour_max_um']:.4g} um, rms {b['contour_rms_um']:.4g} um "
                  f"(max {b['prediction_error_pct']['max']:+.2f} %, rms {b['prediction_error_pct']['rms']:+.2f} %)\n")
    out.write(f"{label:9s} contour error: max {p['contour_max_um']:.4g} um, rms {p['contour_rms_um']:.4g} um "
              f"(max {pe['max']:+.2f} %, rms {pe['rms']:+.2f} %)\n")
    for note in summary.get("notes", []):
        out.write(note + "\n" if note.startswith("warning: ") else f"note: {note}\n")
    return 0
