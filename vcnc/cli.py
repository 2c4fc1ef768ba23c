"""Command line of vcnc (``vcnc ...`` and ``python -m vcnc ...``).

Each sub-command lives in its own module ``vcnc/commands/<name>.py`` that defines

* ``HELP``: one line for ``vcnc --help``;
* ``add_arguments(parser)``: its options;
* ``run(args) -> int``: the work; returns the exit status.

Exit status: 0 success, 2 bad input (one line ``error: FILE:LINE: message`` on stderr), 1 anything
else (``error: ...`` without a traceback unless ``--debug``); a run stopped by a signal exits 128 + its number, as
a shell reports a command killed by it (Ctrl-C, SIGINT: 130; ``kill``, SIGTERM: 143), after one line
``error: interrupted (SIGINT)`` and with its outputs' temporary files removed (:func:`vcnc.core.io.atomic_path`).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import logging
import os
import signal
import sys
import threading
import warnings
from collections.abc import Iterator, Sequence

from vcnc.core.errors import InputError, VcncError, VcncWarning

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


class Interrupted(KeyboardInterrupt):
    """A signal that ends the run (SIGTERM; SIGINT stays Python's own :class:`KeyboardInterrupt`), raised in the
    main thread so that the outputs' context managers remove their temporary files as on Ctrl-C."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _raise_interrupted(signum: int, frame) -> None:  # noqa: ANN001 - a signal handler's frame
    raise Interrupted(signum)


def _interrupt_status(exc: KeyboardInterrupt) -> int:
    """The exit status of a run ``exc`` stopped, 128 + the signal's number (the shell's convention, Bash
    manual "Exit Status"), its one line printed: nothing the run was writing is left (temporary names removed)."""
    signum = exc.signum if isinstance(exc, Interrupted) else int(signal.SIGINT)
    print(f"error: interrupted ({signal.Signals(signum).name})", file=sys.stderr)
    return 128 + signum


class _LineFormatter(logging.Formatter):
    """A log record as one line ``warning: message`` (its level in lower case, as the command line's ``error:``)."""

    def format(self, record: logging.LogRecord) -> str:
        return f"{record.levelname.lower()}: {record.getMessage()}"


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
    handler = logging.StreamHandler()
    # without -v a library's warning reads as the command's own lines do ("warning: ...", as vcnc's warnings and
    # notes); with -v the logger's name tells where each progress line comes from
    handler.setFormatter(logging.Formatter("%(levelname)s %(name)s: %(message)s") if args.verbose else _LineFormatter())
    logging.basicConfig(level=logging.INFO if args.verbose else logging.WARNING, handlers=[handler])
    if not getattr(args, "command", None):
        parser.print_help(sys.stderr)
        return 2
    with _terminate_as_interrupt(), warnings.catch_warnings():
        warnings.simplefilter("default", VcncWarning)  # each once, whatever filters the caller set
        warnings.showwarning = _show_warning
        return _run(args)


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:  # noqa: ANN001, PLR0913
    """vcnc's own warnings (:class:`vcnc.core.errors.VcncWarning`) as one line ``warning: ...`` on stderr; any other
    as Python prints it."""
    if issubclass(category, VcncWarning):
        print(f"warning: {message}", file=sys.stderr)
    else:
        sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


@contextlib.contextmanager
def _terminate_as_interrupt() -> Iterator[None]:
    """SIGTERM raises :class:`Interrupted` while the command runs (in the main thread, when no caller set its own
    handler), the handler restored after it: a ``kill`` removes the temporary outputs as Ctrl-C does (left behind
    before: a 14 MB ``.cap.csv.*.part`` of ``vcnc simulate``)."""
    own = threading.current_thread() is threading.main_thread() and signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
    if own:
        signal.signal(signal.SIGTERM, _raise_interrupted)
    try:
        yield
    finally:
        if own:
            signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _run(args: argparse.Namespace) -> int:
    """The command's run; its exit status, every failure turned into one line on stderr (unless ``--debug``)."""
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
    except KeyboardInterrupt as exc:
        return _interrupt_status(exc)
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
