"""``vcnc toolpath``: write a ready-made part program (circle, diamond, identification, ...)."""

from __future__ import annotations

import argparse
import sys

HELP = "write a test program: circle, diamond, identification (random|slow|fast) or back-and-forth"

_SHAPES = ("circle", "diamond", "identification", "back-and-forth")


def _center(text: str) -> tuple[float, float]:
    try:
        parts = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected 'X,Y' in mm, got {text!r}") from None
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected two coordinates 'X,Y' in mm, got {text!r}")
    return parts[0], parts[1]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("shape", choices=_SHAPES, help="program to write")
    parser.add_argument("-o", "--output", metavar="FILE", help="output program file (default: standard output)")
    parser.add_argument("--dialect", choices=("iso", "heidenhain"), default=None,
                        help="ISO G-code or Heidenhain conversational (default: iso; heidenhain for --kind slow|fast)")
    parser.add_argument("--feed", type=float, default=None,
                        help="feed [mm/min] (default 12000; 15000 for slow/fast; 4242.6 for back-and-forth)")
    parser.add_argument("--radius", type=float, default=10.0, help="circle radius [mm] (default 10)")
    parser.add_argument("--cw", action="store_true", help="clockwise circle (default counter-clockwise)")
    parser.add_argument("--side", type=float, default=20.0, help="diamond side [mm] (default 20)")
    parser.add_argument("--center", type=_center, default=(0.0, 0.0), metavar="X,Y",
                        help="circle / diamond centre [mm] (default 0,0)")
    parser.add_argument("--kind", choices=("random", "slow", "fast"), default="random",
                        help="identification program: random moves (Table 3.2), slow or fast (Tables 4.3/4.4)")
    parser.add_argument("--n", type=int, default=None, help="number of identification moves")
    parser.add_argument("--span", type=float, default=None,
                        help="identification targets within +/-SPAN [mm] (default 10; 0.03 slow; 9.375 fast)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument("--axes", default=None,
                        help="axes moved, e.g. 'x' or 'xy' (default: x for identification, xy for back-and-forth)")
    parser.add_argument("--length", type=float, default=20.0, help="back-and-forth amplitude [mm] (default 20)")
    parser.add_argument("--cycles", type=int, default=1, help="back-and-forth cycles (default 1)")


def run(args: argparse.Namespace) -> int:
    import toolpaths
    from vcnc.core.errors import InputError
    from vcnc.core.io import check_output

    if args.output != "-":
        check_output(args.output, option="-o", what="the program")

    def opt_feed(default: float) -> float:
        return default if args.feed is None else args.feed

    axes = None if args.axes is None else tuple(args.axes.replace(",", "").lower())
    if args.shape == "circle":
        text = toolpaths.circle(args.radius, opt_feed(12000.0), center=args.center, ccw=not args.cw,
                                dialect=args.dialect or "iso")
    elif args.shape == "diamond":
        text = toolpaths.diamond(args.side, opt_feed(12000.0), center=args.center, dialect=args.dialect or "iso")
    elif args.shape == "back-and-forth":
        text = toolpaths.back_and_forth(args.length, opt_feed(4242.6), axes=axes or ("x", "y"),
                                        cycles=args.cycles, dialect=args.dialect or "iso")
    elif args.kind == "random":
        text = toolpaths.random_moves(200 if args.n is None else args.n, 10.0 if args.span is None else args.span,
                                      opt_feed(12000.0), seed=args.seed, axes=axes or ("x",),
                                      dialect=args.dialect or "iso")
    else:
        if args.dialect == "iso":
            raise InputError("the slow/fast identification programs exist in Heidenhain form only",
                             expected="--dialect heidenhain (or no --dialect)")
        if axes is not None and len(axes) != 1:
            raise InputError(f"the slow/fast identification programs move one axis, got --axes {args.axes!r}")
        text = toolpaths.heidenhain_identification(args.kind, n=args.n, span=args.span, feed=opt_feed(15000.0),
                                                   seed=args.seed, axis=(axes or ("x",))[0])
    if args.output in (None, "-"):
        sys.stdout.write(text)
    else:
        toolpaths.write_program(text, args.output)
    return 0
