"""Command line of vcnc (``vcnc ...`` and ``python -m vcnc ...``).

Each sub-command lives in its own module ``vcnc/commands/<name>.py`` that defines

* ``HELP``: one line for ``vcnc --help``;
* ``add_arguments(parser)``: its options;
* ``run(args) -> int``: the work; returns the exit status.

Exit status: 0 success, 2 bad input (one line ``error: FILE:LINE: message`` on stderr), 1 anything
else (``error: ...`` without a traceback unless ``--debug``).
"""

from __future__ import annotations

import argparse
import importlib
import logging
import os
import sys
from collections.abc import Sequence

from vcnc.core.errors import InputError, VcncError

__all__ = ["main", "COMMANDS"]

#: command name -> module under vcnc.commands
COMMANDS: dict[str, str] = {
    "machines": "machines",
    "toolpath": "toolpath",
    "interpolate": "interpolate",
    "simulate": "simulate",
    "identify": "identify",
    "compare": "compare",
    "export-fmu": "export_fmu",
    "demo": "demo",
    "sweep": "sweep",
    "convert": "convert",
}


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage errors as ``error: ...`` with exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.print_usage(sys.stderr)
        print(f"error: {self.prog}: {message}", file=sys.stderr)
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="vcnc", description="vcnc: an open virtual CNC")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on failure")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress details")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, modname in COMMANDS.items():
        mod = importlib.import_module(f"vcnc.commands.{modname}")
        p = sub.add_parser(name, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``vcnc`` console script; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.INFO if args.verbose else logging.WARNING, format="%(levelname)s %(name)s: %(message)s"
    )
    if not getattr(args, "command", None):
        parser.print_help(sys.stderr)
        return 2
    try:
        return int(args._run(args) or 0)
    except InputError as exc:
        if args.debug:
            raise
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except VcncError as exc:
        if args.debug:
            raise
        print(f"error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 1
    except BrokenPipeError:
        # the reader of stdout went away (``vcnc toolpath circle | head``): quiet, as a command in a pipe is,
        # and stdout pointed at /dev/null so that the interpreter's final flush does not complain (Python's
        # signal module documentation, "Note on SIGPIPE")
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except Exception as exc:  # noqa: BLE001 - last resort: no traceback for users
        if args.debug:
            raise
        print(f"error: internal error: {type(exc).__name__}: {exc} (run with --debug for details)", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
