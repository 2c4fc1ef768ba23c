"""Command-line options for reading a trace (``convert``, ``identify``, ``compare --truth``)."""

from __future__ import annotations

import argparse

from vcnc.core.capture import Capture

__all__ = ["add_trace_arguments", "read_trace_argument"]


def add_trace_arguments(parser: argparse.ArgumentParser, *, axes: bool = True) -> None:
    """The column mapping and units of delimited text, and the axis names of a trace."""
    group = parser.add_argument_group("trace formats (detected by content; see README, 'Bring your own machine')")
    group.add_argument("--columns", metavar="t=NAME,x_ref=NAME,x=NAME",
                       help="delimited text: which column is time, commanded and measured position per axis "
                            "(header names, or 1-based column numbers); x_lag=NAME instead of x=NAME takes a "
                            "following error (commanded - actual), the measured position being x_ref - x_lag")
    group.add_argument("--time-unit", choices=("s", "ms", "us", "ns"), default=None,
                       help="delimited text: unit of the time column (default s; TwinCAT ms; rostopic echo -p ns)")
    group.add_argument("--unit", default=None, metavar="UNIT",
                       help="delimited text: unit of the positions, mm, um, nm, m, in or deg (default mm; deg for "
                            "rotary axes a b c), or the size of one count of positions logged in increments "
                            "(0.1um, 0.0001in, 0.001deg)")
    group.add_argument("--sample-time", type=float, default=None, metavar="S",
                       help="delimited text without a time column (LinuxCNC halsampler): the sampling period in s "
                            "(the servo period); with it a t= column counts samples (halsampler -t)")
    group.add_argument("--resample", action="store_true",
                       help="TNCscope, TwinCAT, delimited text: interpolate time stamps that are not uniform (a "
                            "logging PC's jitter, dropped samples) linearly onto the median step instead of refusing "
                            "them")
    if axes:
        group.add_argument("--axis-names", metavar="A,B,...", default=None,
                           help="names of the traced axes (SINUMERIK: in axis-number order; halscope: in joint "
                                "order); default x,y,z,...")


def read_trace_argument(path: str, args: argparse.Namespace) -> Capture:
    """Read ``path`` with the options of :func:`add_trace_arguments` (CaptureError on bad input)."""
    from vcnc.traces import parse_columns, read_trace

    names = getattr(args, "axis_names", None)
    return read_trace(path, columns=parse_columns(args.columns) if args.columns else None,
                      time_unit=args.time_unit, unit=args.unit,
                      axes=tuple(a.strip().lower() for a in names.split(",")) if names else None,
                      resample=getattr(args, "resample", False), sample_time=getattr(args, "sample_time", None))
