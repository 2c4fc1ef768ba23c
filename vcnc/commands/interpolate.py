"""``vcnc interpolate``: G-code program -> sampled axis setpoints (CSV, optional plot)."""

from __future__ import annotations

import argparse
import contextlib
import io
import re
import sys

from vcnc.core.text import ZIP_SIGNATURE

HELP = "interpolate a program (ISO or Heidenhain) into setpoints sampled every Ts (CSV)"

#: Samples ``vcnc interpolate`` computes without ``--max-seconds`` (5.6 h at Ts = 1 ms): a longer program is
#: refused, naming the option, rather than running the machine out of memory (measured peak: 1.06 GB for the
#: 4.95 million samples of three axes of a corpus program, 0283_Enclosure.nc, so about 4.3 GB here).
MAX_SAMPLES = 20_000_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("program", help="part program (ISO G-code or Heidenhain conversational, detected)")
    parser.add_argument("-o", "--output", required=True, metavar="CSV",
                        help="setpoints file: t, <axis>_ref, <axis>_vel, <axis>_acc, block")
    parser.add_argument("--profile", choices=("trapezoid", "scurve"), default="trapezoid",
                        help="feed profile: trapezoid (acceleration limited) or scurve (jerk limited, ruckig)")
    parser.add_argument("--ts", type=float, default=None, metavar="S",
                        help="sample time [s] (default: the machine's, else 0.001)")
    parser.add_argument("--plot", metavar="PNG", help="also draw the path and speed/acceleration over time")
    parser.add_argument("--machine", metavar="NAME|FILE",
                        help="take axis limits, Ts and the program context (work offsets, tool table, home, "
                             "dialect, axes A B C U V W) from a machine (default: interpolators.DEFAULT_LIMITS, "
                             "DEFAULT_ROTARY_LIMITS and DEFAULT_SECONDARY_LIMITS, no offsets, axes A B C U V W)")
    add_context_arguments(parser)
    parser.add_argument("--blocks", metavar="CSV",
                        help="also write the interpreted motion blocks: block, line, kind, x, y, z (machine "
                             "coordinates, mm), a, b, c (deg; a wrapping axis unwrapped, as its motor turns), u, "
                             "v, w (mm) for those the program uses, cx, cy, "
                             "cz (arc centre), feed (mm/min; deg/min on a pure rotary move)")
    parser.add_argument("--max-seconds", type=float, metavar="S",
                        help="interpolate only the blocks that run within the first S seconds (a note says where "
                             f"the program was cut; default: the whole program, refused beyond {MAX_SAMPLES:,} "
                             "samples)")


def add_context_arguments(parser: argparse.ArgumentParser) -> None:
    """``--dialect``, ``--tool-table``, ``--datum-table``, ``--subroutine-path``, ``--user-m-path`` and
    ``--initial-feed``, shared by the commands that read part programs."""
    parser.add_argument("--dialect", choices=("linuxcnc", "fanuc", "haas", "grbl", "fadal"),
                        help="G-code dialect: unit of G04 P (s: linuxcnc, grbl; ms: fanuc, fadal, haas "
                             "without a decimal point) "
                             "(default: the machine's, else linuxcnc)")
    parser.add_argument("--tool-table", metavar="FILE",
                        help="tool table for G43 H, G41/G42 D and TOOL CALL n|\"NAME\": LinuxCNC's "
                             "(T1 P1 D6.0 Z+12.5 ;comment) or a Heidenhain TOOL.T (BEGIN TOOL .T MM, columns "
                             "T NAME L R DL DR)")
    parser.add_argument("--datum-table", metavar="FILE",
                        help="Heidenhain datum table (BEGIN ZEROSHIFT.D MM, columns D X Y Z) whose rows "
                             "CYCL DEF 7.1 #n selects (default: none, and such a block is an error)")
    parser.add_argument("--subroutine-path", metavar="DIR[:DIR]",
                        help="folders searched for the file <name>.ngc of an o<name> call, and (Fanuc, Haas) for "
                             "the program file of an M98/G65 P<number> call, after the program's own folder (LinuxCNC "
                             "INI [RS274NGC] SUBROUTINE_PATH; before the machine's)")
    parser.add_argument("--user-m-path", metavar="DIR[:DIR]",
                        help="folders holding the M100-M199 user programs (LinuxCNC INI [RS274NGC] USER_M_PATH; "
                             "before the machine's)")
    parser.add_argument("--initial-feed", type=float, metavar="F",
                        help="feed [mm/min] of feed moves before any F word, the control's power-on feed (Fanuc "
                             "parameter 1411; default: the machine's [program] initial_feed, else such a move is an "
                             "error, as on LinuxCNC and grbl)")
    parser.add_argument("--default-units", choices=("mm", "inch"),
                        help="units of a program without G20/G21, the control's power-on units (Haas Setting 9 "
                             "Dimensioning; LinuxCNC INI [RS274NGC] RS274NGC_STARTUP_CODE; default: the machine's "
                             "[program] default_units, else mm)")


def program_context(args: argparse.Namespace, machine=None):
    """The MachineContext for reading a program: the machine's (without one:
    ``interpolators.context.INTERPOLATION_CONTEXT``, axes A B C U V W), with --dialect, --tool-table, --datum-table,
    --subroutine-path, --user-m-path (the paths searched before the machine's), --initial-feed and --default-units
    applied."""
    import dataclasses
    import os

    from interpolators.context import INTERPOLATION_CONTEXT, read_datum_table, read_tool_table

    context = machine.context if machine is not None else INTERPOLATION_CONTEXT
    if getattr(args, "dialect", None):
        context = context.with_dialect(args.dialect)
    changes = {}
    if getattr(args, "tool_table", None):
        changes["tools"] = {**context.tools, **read_tool_table(args.tool_table)}
    if getattr(args, "datum_table", None):
        changes["datum_table"] = {**context.datum_table, **read_datum_table(args.datum_table)}
    paths = {key: tuple(os.path.abspath(p) for p in getattr(args, key).split(":") if p)  # relative: to the cwd
             for key in ("subroutine_path", "user_m_path")
             if getattr(args, key, None)}
    dialect_changes = {k: v + getattr(context.dialect, k) for k, v in paths.items()}
    if getattr(args, "initial_feed", None) is not None:
        dialect_changes["initial_feed"] = args.initial_feed
    if getattr(args, "default_units", None):
        dialect_changes["default_units"] = args.default_units
    if dialect_changes:
        changes["dialect"] = dataclasses.replace(context.dialect, **dialect_changes)
    return dataclasses.replace(context, **changes) if changes else context


#: Largest program [bytes] that a failed read is read again under the other dialects for
#: :func:`read_program`'s hint (the reader takes about 50 us a line: some 5 s per dialect at this size).
HINT_MAX_BYTES = 4_000_000


#: How the files vcnc itself reads and writes begin, for :func:`other_file_kind`: (start of the text, what it is).
_OTHER_FILES = (
    (ZIP_SIGNATURE, "a zip archive (an FMU?)"),
    (b"{", "a JSON file (a model file?)"),
    (b"# machine:", "a capture (CSV)"),
    (b"t,", "a capture or setpoints (CSV)"),
)
#: A line of a machine definition (its first lines may be comments, as `vcnc machines --show` writes them; no
#: program line starts with these).
_MACHINE_LINE = re.compile(rb"^(sample_time\s*=|\[axes\.[a-z]\])", re.MULTILINE)


def other_file_kind(path: str) -> str | None:
    """What the file ``path`` is when it is plainly no part program: empty (nothing but white space), or one of
    the files vcnc writes and reads elsewhere (a capture or setpoints CSV, a model JSON, a machine TOML, an
    FMU), told by how it begins; None otherwise (a missing file is the reader's error). A program starts with
    a block, a comment, ``%`` or ``BEGIN PGM``, never with these, so nothing a reader would take is refused."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(4096)
    except OSError:
        return None
    if not head.strip():
        return "an empty file"
    start = head.lstrip(b"\xef\xbb\xbf \t\r\n")
    for prefix, kind in _OTHER_FILES:
        if start.startswith(prefix):
            return kind
    return "a machine definition (TOML)" if _MACHINE_LINE.search(head) else None


def read_program(args: argparse.Namespace, machine=None):
    """The part program ``args.program`` read in :func:`program_context`.

    A program that the default dialect (LinuxCNC's, neither ``--dialect`` nor a machine's ``[program]
    dialect`` chosen) refuses is read again as Fanuc, Haas and grbl G-code; when one of them reads it,
    the error says so ("...; expected ..., or --dialect haas: the program reads as that control's
    G-code"), since the same text means different things to those controls (a Haas program starts in G00
    and drills without an R word; LinuxCNC refuses both) and vcnc must not guess which one was meant.
    The error stays an error: a program is read as its control reads it or not at all."""
    from pathlib import Path

    from interpolators import load_program
    from vcnc.core.errors import GCodeError

    context = program_context(args, machine)
    kind = other_file_kind(args.program)
    if kind is not None:
        raise GCodeError(f"this is {kind}, not a part program", file=args.program,
                         expected="a part program (ISO G-code or Heidenhain conversational)")
    try:
        return load_program(args.program, context=context)
    except GCodeError as exc:
        path = Path(args.program)
        if getattr(args, "dialect", None) or context.dialect.name != "linuxcnc" or not path.is_file() \
                or path.stat().st_size > HINT_MAX_BYTES:
            raise
        readers: list[str] = []
        for name in ("fanuc", "haas", "grbl", "fadal"):
            if name == "fadal" and readers:  # Fadal reads what Fanuc reads: named only for Fadal's own words
                break
            try:
                load_program(path, context=context.with_dialect(name))
            except GCodeError:
                continue
            readers.append(name)
        if readers and "--dialect" not in str(exc):  # (the reader's own message may name the dialects already)
            hint = (f"--dialect {' or '.join(readers)}: the program reads as that control's G-code (vcnc reads "
                    "LinuxCNC's unless told)")
            exc.expected = f"{exc.expected}, or {hint}" if exc.expected else hint
            exc.args = (str(exc),)
        raise


@contextlib.contextmanager
def sample_guard(*, command: str, max_samples: int):
    """The memory guard of a command with ``--max-seconds``: a :class:`vcnc.ProgramTooLongError` raised within
    (an interpolation refused beyond ``max_samples`` samples) becomes a :class:`vcnc.GCodeError` naming the
    program, the samples it needs, the ``max_samples`` vcnc ``command`` holds and ``--max-seconds``."""
    from vcnc.core.errors import GCodeError, ProgramTooLongError

    try:
        yield
    except ProgramTooLongError as exc:
        raise GCodeError(
            f"the program needs {'at least ' if exc.at_least else ''}{exc.samples} samples "
            f"({exc.samples * exc.sample_time / 3600:.3g} h at Ts = {exc.sample_time:g} s), more than the "
            f"{max_samples} vcnc {command} holds in memory",
            file=exc.file, expected=f"--max-seconds S to {command} its first S seconds",
        ) from None


def interpolate_within(program, machine, args: argparse.Namespace, *, command: str, max_samples: int,
                       sample_time: float | None = None):
    """The setpoints of ``program`` on ``machine`` (None: the interpolator's default limits) for a command
    with ``--profile`` and ``--max-seconds``: the first ``args.max_seconds`` seconds (a note on stdout says
    where the program was cut), or the whole program when it needs at most ``max_samples`` samples; beyond
    them a :class:`vcnc.GCodeError` naming the program and ``--max-seconds`` (:func:`sample_guard`)."""
    from vcnc.facade import interpolate, truncation_note

    with sample_guard(command=command, max_samples=max_samples):
        sp = interpolate(program, machine, profile=args.profile, sample_time=sample_time,
                         max_duration=args.max_seconds, max_samples=None if args.max_seconds else max_samples)
    note = truncation_note(sp, done=f"{command}d")
    if note:
        print(f"{program.source}: {note}")
    return sp


def blocks_table(program) -> tuple[list[str], list[list]]:
    """Header and rows of ``--blocks``: what LinuxCNC's canonical calls carry, one row per block.

    Columns ``block, line, kind, x, y, z``, then in LinuxCNC's axis order ``a, b, c`` [deg] and
    ``u, v, w`` [mm] for those the program uses (``program.axes``), then ``cx, cy, cz, feed``
    [mm/min; deg/min on a pure rotary move]. An axis that wraps at 360 deg (``[axes.a] wrap = true``) is listed
    unwrapped, as its motor has turned (350, then ``A10`` the short way: 370), as LinuxCNC's canonical calls carry
    it; the control shows the angle reduced below 360 deg (:mod:`interpolators.rotary_wrap`)."""
    import numpy as np

    from toolpaths.geometry import Arc
    from vcnc.core.axes import EXTRA_NAMES

    extra = [i for i, a in enumerate(EXTRA_NAMES) if a in program.axes]
    header = ["block", "line", "kind", "x", "y", "z", *(EXTRA_NAMES[i] for i in extra), "cx", "cy", "cz", "feed"]
    rows = []
    for i, b in enumerate(program.blocks):
        if b.kind == "dwell":
            kind = "dwell"
        elif b.kind == "arc":
            kind = "arc_ccw" if b.segment.ccw else "arc_cw"
        else:
            kind = "rapid" if b.kind == "rapid" else "feed"
        centre = list(b.segment.center) if isinstance(b.segment, Arc) else [np.nan] * 3
        feed = b.feed * 60.0 if np.isfinite(b.feed) else np.nan
        angles = [float(b.extra_target[k]) if b.extra_target is not None else 0.0 for k in extra]
        rows.append([i, b.line, kind, *map(float, b.target), *angles, *map(float, centre), feed])
    return header, rows


def write_blocks(program, path: str) -> None:
    """Write :func:`blocks_table` as CSV (atomically; empty fields for no centre / no feed)."""
    import csv

    from vcnc.core.io import atomic_path

    header, rows = blocks_table(program)
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for r in rows:
            w.writerow([v if isinstance(v, (int, str)) else ("" if v != v else f"{float(v):.12g}") for v in r])


def notes_summary(program) -> str | None:
    """One line naming what the reader accepted without motion or assumed, or None."""
    return "ignored/noted: " + ", ".join(program.notes) if program.notes else None


def message_lines(program) -> list[str]:
    """The program's operator messages as ``vcnc interpolate`` prints them on stderr, one line each:
    ``file:line: (MSG) text``, as LinuxCNC shows MSG and DEBUG comments to the operator and writes
    PRINT comments to its console (G-code overview, "Messages", "Debug Messages", "Print
    Messages"); LOG lines go to a log file vcnc does not write (a note says so)."""
    return [f"{m.file or program.source}:{m.line}: ({m.kind.upper()}) {m.text.strip()}"
            for m in program.messages if m.kind != "log"]


def print_program_notes(program, path) -> None:
    """What ``vcnc interpolate`` and ``vcnc simulate`` say about a program they read: its operator
    messages on stderr (:func:`message_lines`), then the one-line summary of what was ignored or
    noted on stdout (:func:`notes_summary`)."""
    for line in message_lines(program):
        print(line, file=sys.stderr)
    summary = notes_summary(program)
    if summary:
        print(f"{path}: {summary}")


def _machine(name: str):
    from vcnc.engine.machine import load_machine

    return load_machine(name)


def plot_setpoints(setpoints, *, title: str | None = None):
    """Figure with the path (left) and path speed / acceleration magnitude over time (right)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    import numpy as np

    fig, (ax_path, ax_v) = plt.subplots(1, 2, figsize=(11, 4.5))
    pos = setpoints.position
    if pos.shape[1] >= 2:
        ax_path.plot(pos[:, 0], pos[:, 1], lw=1)
        ax_path.set_xlabel(f"{setpoints.axes[0]} [mm]")
        ax_path.set_ylabel(f"{setpoints.axes[1]} [mm]")
        ax_path.set_aspect("equal", adjustable="datalim")
    else:
        ax_path.plot(setpoints.t, pos[:, 0], lw=1)
        ax_path.set_xlabel("t [s]")
        ax_path.set_ylabel(f"{setpoints.axes[0]} [mm]")
    ax_path.set_title("path")
    speed = np.linalg.norm(setpoints.velocity, axis=1)
    acc = np.linalg.norm(setpoints.acceleration, axis=1)
    ax_v.plot(setpoints.t, speed, lw=1, color="C0")
    ax_v.set_xlabel("t [s]")
    ax_v.set_ylabel("speed [mm/s]", color="C0")
    ax_a = ax_v.twinx()
    ax_a.plot(setpoints.t, acc, lw=0.8, color="C3", alpha=0.7)
    ax_a.set_ylabel("|acceleration| [mm/s^2]", color="C3")
    ax_v.set_title("speed and acceleration")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def run(args: argparse.Namespace) -> int:
    from vcnc.core.io import atomic_path, check_distinct_outputs, check_output

    inputs = (args.program, args.machine, args.tool_table, args.datum_table)
    check_output(args.output, option="-o", what="the setpoints (CSV)", inputs=inputs)
    check_output(args.blocks, option="--blocks", what="the block table (CSV)", inputs=inputs)
    check_output(args.plot, option="--plot", what="the plot (PNG)", inputs=inputs)
    check_distinct_outputs((("-o", args.output), ("--blocks", args.blocks), ("--plot", args.plot)))
    ts = 1e-3
    machine = None
    if args.machine:
        machine = _machine(args.machine)
        ts = float(getattr(machine, "sample_time", ts) or ts)
    program = read_program(args, machine)
    print_program_notes(program, args.program)
    if args.ts is not None:
        ts = args.ts
    sp = interpolate_within(program, machine, args, command="interpolate", max_samples=MAX_SAMPLES, sample_time=ts)
    png = None
    if args.plot:
        import matplotlib.pyplot as plt

        fig = plot_setpoints(sp, title=f"{args.program} ({args.profile}, Ts = {ts:g} s)")
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=120)
        plt.close(fig)
        png = buf.getvalue()
    sp.to_csv(args.output)
    if args.blocks:
        write_blocks(program, args.blocks)
    if png is not None:
        with atomic_path(args.plot) as tmp:
            tmp.write_bytes(png)
    print(f"{args.program}: interpolated {sp.duration:.6g} s ({len(sp)} samples at Ts = {sp.sample_time:g} s, "
          f"axes {', '.join(sp.axes)}); setpoints {args.output}")
    return 0
