"""``vcnc machines``: list the built-in machines, or print one's definition."""

from __future__ import annotations

import argparse
import sys

HELP = "list built-in machines (--show NAME|FILE prints a definition)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--show", metavar="NAME|FILE", help="print the TOML definition of a machine")


def run(args: argparse.Namespace) -> int:
    from vcnc.machine import builtin_machine_text, builtin_machines, load_machine

    if args.show:
        name = args.show
        if name in builtin_machines():
            text = builtin_machine_text(name)
        else:
            machine = load_machine(name)  # checks the file (MachineError -> exit 2)
            with open(machine.source or name) as fh:
                text = fh.read()
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        return 0
    names = builtin_machines()
    width = max(len(n) for n in names)
    for n in names:
        m = load_machine(n)
        print(f"{n:<{width}}  {', '.join(m.axes)}  Ts={m.sample_time * 1e3:g} ms  {m.description}")
    return 0
