"""``vcnc demo``: the whole story on the built-in default machine, or on the real EMPS data."""

from __future__ import annotations

import argparse
import os

HELP = "run the end-to-end demo and write a report folder"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", default=None, help="report folder (default vcnc-demo, or vcnc-demo-emps with --emps)")
    p.add_argument("--machine", default=None, help="built-in machine name or TOML file (default fadal-pid)")
    p.add_argument("--effect", default=None,
                   help="effect hidden on the X axis of the true machine (default backlash; 'none' hides nothing)")
    p.add_argument("--seed", type=int, default=1, help="seed of the identification program and noise")
    p.add_argument("--no-fmu", action="store_true", help="skip the FMU export stage")
    p.add_argument("--emps", nargs="?", const="", default=None, metavar="DIR",
                   help="run on the real EMPS data in DIR (default: $VCNC_EMPS_DIR)")


def run(args: argparse.Namespace) -> int:
    from vcnc import demo
    from vcnc.core.io import check_output

    check_output(args.out, option="--out", what="the report", folder=True)
    if args.emps is not None:
        out = args.out or "vcnc-demo-emps"
        summary = demo.run_emps_demo(args.emps or os.environ.get("VCNC_EMPS_DIR"), out)
    else:
        out = args.out or "vcnc-demo"
        effect = args.effect or demo.DEFAULT_EFFECT
        summary = demo.run_demo(
            out,
            machine=args.machine or demo.DEFAULT_MACHINE,
            effect=None if effect == "none" else effect,
            seed=args.seed,
            fmu=not args.no_fmu,
        )
    demo.describe(summary)
    print(f"report: {os.path.join(out, 'index.html')}")
    return 0
