"""``vcnc simulate``: run a part program through a virtual machine into a capture."""

from __future__ import annotations

import argparse
import contextlib
import gc
import json
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from vcnc.commands.interpolate import (
    HINT_MAX_BYTES,
    add_context_arguments,
    interpolate_within,
    print_program_notes,
    program_context,
    read_program,
)

HELP = "simulate a part program on a virtual machine (capture CSV, summary JSON, report)"

#: Samples ``vcnc simulate`` runs without ``--max-seconds`` (83 min at Ts = 1 ms): a longer program is
#: refused, naming the option, rather than running the machine out of memory (measured peak: 7.8 GB
#: for 9 million samples of three axes between interpolation, simulation, contour and CSV; a 5 h
#: program failed with MemoryError after 9 GB).
MAX_SAMPLES = 5_000_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("program", help="part program (ISO G-code or Heidenhain conversational)")
    parser.add_argument("--machine", required=True, metavar="NAME|FILE", help="built-in machine name or TOML file")
    parser.add_argument("-o", "--output", required=True, metavar="CAPTURE.csv", help="capture file to write")
    parser.add_argument("--json", metavar="FILE", help="write the summary (tracking and contour errors) as JSON")
    parser.add_argument("--report", metavar="DIR", help="write plots: tracking error and control per axis, path")
    parser.add_argument("--profile", choices=("trapezoid", "scurve"), default="trapezoid", help="feed profile")
    parser.add_argument("--seed", type=int, default=0, help="seed of the measurement noise (default 0)")
    parser.add_argument("--max-seconds", type=float, metavar="S",
                        help="simulate only the blocks that run within the first S seconds (a note says where the "
                             "program was cut; default: the whole program)")
    parser.add_argument("--settle", type=float, default=None, metavar="S",
                        help="run on after the last setpoint, the command held, until the following error of every "
                             "axis has settled, for at most S seconds (default 2; 0: the capture ends with the "
                             "reference; none after a cut by --max-seconds)")
    add_context_arguments(parser)


def run(args: argparse.Namespace) -> int:
    # a long program's blocks and segments are hundreds of thousands of objects that live to the end; the cyclic
    # garbage collector, triggered by their allocation, would walk all of them again and again (1.4 s of 12 s on
    # corpus 0274; the peak memory is the same): it runs once the command is done
    enabled = gc.isenabled()
    gc.disable()
    try:
        return _run(args)
    finally:
        if enabled:
            gc.enable()


def check_outputs(args: argparse.Namespace) -> None:
    """:class:`vcnc.InputError` before any work when an output cannot be written where it is asked
    (:func:`vcnc.core.io.check_output`: a long program would otherwise run to its end and fail on the rename)."""
    from vcnc.core.io import check_distinct_outputs, check_output

    inputs = (args.program, args.machine, args.tool_table, args.datum_table)
    check_output(args.output, option="-o", what="the capture file (CSV)", inputs=inputs)
    check_output(args.json, option="--json", what="the summary file", inputs=inputs)
    check_output(args.report, option="--report", what="the report", folder=True)
    check_distinct_outputs((("-o", args.output), ("--json", args.json), ("--report", args.report)))


def sampling_note(summary: dict, machine) -> str | None:
    """A warning naming the machine's ``sample_time`` when an axis' sampled loop is unstable at it
    (:meth:`vcnc.engine.machine.Machine.unstable_axes`): a servo period too coarse for the gains (a unit slip
    such as 0.01 s for 1 ms, or fadal-pid's gains at 4 ms, |z| = 1.015, whose run of corpus 0077 ends with
    plausible errors of 130 um). Checked for a machine from a file, where a user sets
    the period (before the run, which such a slip can make fail: ``sample_time = 1`` leaves the contour step 1 s
    samples that skip whole blocks), and after a saturated run (``summary["saturated"]``), whose own note points at
    the acceleration limits instead; the built-in machines are stable at theirs (the check imports python-control,
    2 s). A computation delay counts (fadal-ppi with a 2-sample delay: |z| = 1.008, the limit cycle that
    ``benchmarks/ident_fuzz.unstable_delay`` skips)."""
    if not (machine.file or summary.get("saturated")):
        return None
    unstable = machine.unstable_axes()
    if not unstable:
        return None
    poles = ", ".join(f"{a} |z| = {r:.3g}" for a, r in unstable.items())
    return (f"warning: at the machine's sample_time {machine.sample_time:g} s the closed loop of axis "
            f"{', '.join(unstable)} is unstable (largest pole {poles}): the controller's gains need a shorter "
            f"servo period (or less [axes.*.delay]); check 'sample_time' [s] in {machine.source or machine.name}")


def read_for_machine(args: argparse.Namespace, machine, *, option: str = "--machine"):
    """The program ``args.program`` read for ``machine`` (:func:`vcnc.commands.interpolate.read_program`).

    The machine's context takes the words of its own axes only (``A180`` is an error on a machine without
    an A axis), and the reader's error says which word, not how to run the program. When the program reads
    with every axis letter (A B C U V W, as ``vcnc interpolate`` without a machine reads it) and
    :func:`vcnc.facade.check_program_axes` then finds a move of an axis the machine lacks, the reader's error
    is kept and its "expected" names that check's way forward too: a machine with the axis (a built-in
    NAME+z, or an ``[axes.a]`` section in a machine file). Otherwise, or for a program above
    ``HINT_MAX_BYTES`` (read once more only when it is small), the reader's error stands as it is. ``option``
    names the machine in that way forward (:func:`vcnc.facade.check_program_axes`)."""
    import dataclasses

    from interpolators import load_program
    from vcnc.core.axes import EXTRA_NAMES
    from vcnc.core.errors import GCodeError
    from vcnc.facade import check_program_axes

    try:
        return read_program(args, machine)
    except GCodeError as exc:
        path = Path(args.program)
        context = program_context(args, machine)
        if set(EXTRA_NAMES) <= set(context.extra_axes) or not path.is_file() \
                or path.stat().st_size > HINT_MAX_BYTES:
            raise
        try:
            wider = load_program(path, context=dataclasses.replace(context, extra_axes=EXTRA_NAMES))
        except GCodeError:
            raise exc from None
        try:
            check_program_axes(wider, machine, option=option)
        except GCodeError as lacking:
            exc.expected = f"{exc.expected}, or {lacking.expected}" if exc.expected else lacking.expected
            exc.args = (str(exc),)
        raise


def _settle_seconds(args: argparse.Namespace) -> float:
    """``--settle S`` [s], checked (InputError naming the option: a number in [0, 600])."""
    from vcnc.core.errors import InputError
    from vcnc.engine.settling import BOUND_S

    bound = BOUND_S if args.settle is None else float(args.settle)
    if not 0.0 <= bound <= 600.0:  # (NaN fails too)
        raise InputError(f"--settle {args.settle:g}: the settling tail's bound must be a number of seconds in "
                         "[0, 600]", expected="--settle 2 (the default), or 0 for no tail")
    return bound


def _simulate_and_settle(machine, setpoints, args: argparse.Namespace):
    """The capture of ``setpoints`` on ``machine``, run on with the last command held until the axes settled
    (:func:`vcnc.engine.settling.settling_tail`, at most ``--settle`` seconds; a note on stdout and in the
    capture's header says how long); a program cut by ``--max-seconds`` stops mid-motion and gets no tail."""
    from vcnc.engine.settling import settling_tail

    bound = _settle_seconds(args)
    if bound == 0.0 or setpoints.meta.get("truncated"):
        return machine.simulate(setpoints, seed=args.seed)
    capture = machine.simulate(setpoints.held(bound), seed=args.seed)
    if len(capture) == len(setpoints):  # a bound under one sample
        return capture
    tail = settling_tail(capture, len(setpoints))
    capture = capture.slice(0, tail.samples)
    note = tail.note(bound)
    capture.meta["settle"] = note
    print(f"{args.program}: {note}")
    return capture


def _run(args: argparse.Namespace) -> int:
    from vcnc.core.errors import GCodeError
    from vcnc.core.io import atomic_path
    from vcnc.engine.machine import load_machine
    from vcnc.facade import program_meta
    from vcnc.simulation_report import build_report, feed_contour_line, result_line, saturation_note, summarize

    check_outputs(args)
    _settle_seconds(args)  # checked before any work
    machine = load_machine(args.machine)
    program = read_for_machine(args, machine)
    print_program_notes(program, args.program)
    setpoints = interpolate_within(program, machine, args, command="simulate", max_samples=MAX_SAMPLES)
    if len(setpoints) < 2:  # a capture holds at least two samples
        raise GCodeError("the program neither moves an axis nor dwells: nothing to simulate", file=args.program,
                         expected="a program with a move or a dwell")
    meta = program_meta(setpoints, Path(args.program).name, profile=args.profile)
    # a machine from a file is checked before the run, whose contour step an unstable loop can fail
    stability = sampling_note({}, machine)
    if stability:
        print(f"{args.program}: {stability}")
    capture = _simulate_and_settle(machine, setpoints, args)
    capture.meta.update(meta)
    with contextlib.ExitStack() as stack:
        # everything goes to temporary names, renamed into place only when all parts succeeded
        json_tmp = stack.enter_context(atomic_path(args.json)) if args.json else None
        cap_tmp = stack.enter_context(atomic_path(args.output))
        # the capture file is written while the summary is computed: the CSV formatting and the contour
        # search are compiled loops that release the GIL (the pool is left, waiting for the writer, before
        # the temporary names are renamed or removed)
        writing = stack.enter_context(ThreadPoolExecutor(max_workers=1)).submit(capture.to_csv, cap_tmp)
        summary = summarize(capture, program)
        # a machine from a file was checked before the run (the same machine: the same answer)
        later = None if machine.file else sampling_note(summary, machine)
        for line in (saturation_note(summary), later, feed_contour_line(summary)):
            if line:
                print(f"{args.program}: {line}")
        report = build_report(capture, summary) if args.report else None
        if report is not None:
            report.write(args.report)
        if json_tmp is not None:
            json_tmp.write_text(json.dumps(summary, indent=2) + "\n")
        writing.result()
    print(f"{args.program}: {result_line(summary)}; capture {args.output}")
    return 0
