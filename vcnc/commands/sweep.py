"""``vcnc sweep SPEC.toml -o results.parquet|csv``: a parameter sweep on Dask.

Runs every point of the spec (schema: ``docs/sweep.md``) on a local Dask cluster (``--workers``
processes on 127.0.0.1) or on a running scheduler (``--scheduler tcp://HOST:PORT``). Results are
appended as points finish; running the same command again resumes: finished points are kept and
not computed again. A failing point is recorded with its error (``status = error``).
"""

from __future__ import annotations

import argparse
import logging

HELP = "run a parameter sweep or Monte-Carlo identification study on Dask (resumable)"

log = logging.getLogger(__name__)


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer >= 1, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected an integer >= 1, got {text!r}")
    return n


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("spec", metavar="SPEC.toml", help="sweep specification (docs/sweep.md)")
    parser.add_argument("-o", "--output", required=True, metavar="RESULTS",
                        help="results file, .parquet or .csv (existing results are resumed, never overwritten)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="address of a running Dask scheduler (tcp://host:port)")
    where.add_argument("--workers", type=_positive_int, metavar="N",
                       help="local worker processes (default: number of CPUs)")
    parser.add_argument("--retry-failed", action="store_true", help="compute again the points recorded as errors")
    parser.add_argument("--plot", metavar="FILE.png", help="write the summary plot")
    parser.add_argument("--timeout", type=float, metavar="S", help="stop after S seconds (finished points are kept)")


def run(args: argparse.Namespace) -> int:
    from vcnc.core.errors import InputError
    from vcnc.core.io import check_distinct_outputs, check_output
    from vcnc.sweeps import load_spec, sweep, write_plot

    check_output(args.output, option="-o", what="the results", inputs=(args.spec,))
    check_output(args.plot, option="--plot", what="the plot", inputs=(args.spec,))
    check_distinct_outputs((("-o", args.output), ("--plot", args.plot)))
    if args.plot and not args.plot.lower().endswith((".png", ".svg", ".pdf")):
        raise InputError("--plot must name a .png, .svg or .pdf file", file=args.plot)
    spec = load_spec(args.spec)
    result = sweep(spec, args.output, scheduler=args.scheduler, workers=args.workers,
                   retry_failed=args.retry_failed, timeout=args.timeout)
    if args.plot:
        write_plot(result.table, args.plot)
    statuses = result.column("status")
    errors = sum(s != "ok" for s in statuses)
    rate = f", {result.points_per_s:.2f} points/s on {result.workers} workers" if result.computed else ""
    print(
        f"{args.output}: {len(result)} points ({result.computed} computed{rate}, {result.skipped} resumed, "
        f"{errors} with errors)"
    )
    return 0
