"""``vcnc convert``: turn a control's trace export into the capture CSV (issue #17)."""

from __future__ import annotations

import argparse

HELP = "convert a trace export (TNCscope text, capture CSV) into the capture CSV"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("trace", metavar="TRACE", help="trace file, format detected by content")
    parser.add_argument("-o", "--output", required=True, metavar="CSV", help="capture CSV to write (atomically)")


def run(args: argparse.Namespace) -> int:
    from vcnc.capture import read_capture

    cap = read_capture(args.trace)
    dt = float(cap.t[1] - cap.t[0]) if cap.t.size > 1 else float("nan")
    print(f"{args.trace}: {cap.t.size} samples, sample time {dt * 1e3:.6g} ms, axes {' '.join(cap.axes)}")
    for key, value in cap.meta.items():
        print(f"  {key}: {value}")
    cap.to_csv(args.output)
    print(f"wrote {args.output}")
    return 0
