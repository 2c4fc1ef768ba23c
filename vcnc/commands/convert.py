"""``vcnc convert``: turn a control's trace export into the capture CSV (issue #17)."""

from __future__ import annotations

import argparse

from vcnc.commands.trace_options import add_trace_arguments, read_trace_argument
from vcnc.core.axes import axis_unit

HELP = ("convert a trace export (TNCscope, SINUMERIK XML, TwinCAT, halscope, EPICS camonitor, delimited text) into "
        "the capture CSV")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("trace", metavar="TRACE", help="trace file, format detected by content")
    parser.add_argument("-o", "--output", required=True, metavar="CSV", help="capture CSV to write (atomically)")
    parser.add_argument("--axis", action="append", default=None, metavar="A",
                        help="keep only this axis (repeat for several; default all)")
    add_trace_arguments(parser)


def run(args: argparse.Namespace) -> int:
    from vcnc.core.io import check_output
    from vcnc.traces import trace_format

    check_output(args.output, option="-o", what="the capture (CSV)", inputs=(args.trace,))
    fmt = trace_format(args.trace)
    cap = read_trace_argument(args.trace, args)
    if args.axis:
        for a in args.axis:
            cap.axis_index(a)  # CaptureError naming the axes found
        cap = cap.select_axes(tuple(args.axis))
    dt = float(cap.t[1] - cap.t[0])
    print(f"{args.trace}: {fmt}, {cap.t.size} samples, sample time {dt * 1e3:.6g} ms, "
          f"{cap.t[-1]:.6g} s, axes {' '.join(cap.axes)} [{', '.join(axis_unit(a) for a in cap.axes)}]")
    for key, value in cap.meta.items():
        print(f"  {key}: {value}")
    cap.to_csv(args.output)
    print(f"wrote {args.output}")
    return 0
