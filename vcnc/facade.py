"""The everyday entry points that tie the packages together (``vcnc.interpolate``)."""

from __future__ import annotations

import dataclasses
import math
import os
from typing import TYPE_CHECKING

import numpy as np

from vcnc.core.errors import GCodeError, InputError, ProgramTooLongError
from vcnc.core.setpoints import Setpoints

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Mapping

    from interpolators import AxisLimits, Program
    from vcnc.engine.machine import Machine

__all__ = ["interpolate", "check_program_axes", "truncation_note", "program_meta"]


def interpolate(
    program: Program | str | os.PathLike[str],
    machine: Machine | str | None = None,
    *,
    profile: str = "trapezoid",
    sample_time: float | None = None,
    max_duration: float | None = None,
    max_samples: int | None = None,
    limits: Mapping[str, AxisLimits] | None = None,
) -> Setpoints:
    """Interpolate a part program with a machine's axis limits and sample time.

    Parameters
    ----------
    program : Program or path
        A parsed program, or the path of a program file (ISO or Heidenhain, detected by content).
    machine : Machine or str, optional
        The machine (or a built-in name / TOML path) whose axis limits and sample time apply;
        without one the interpolator's documented default limits and 1 ms are used. A program
        that moves an axis the machine lacks is refused (:func:`check_program_axes`); one it only
        names (``G0 Z0`` at Z0) runs, without that axis' constant column.
    profile : {"trapezoid", "scurve"}
        Feed profile along the path.
    sample_time : float, optional
        Interpolation period [s]; defaults to the machine's.
    max_duration : float, optional
        Budget [s]: a program that runs longer is cut after the last block that ends within it
        (see Notes); ``meta["truncated"]`` then says where. Without it the whole program runs.
    max_samples : int, optional
        Without ``max_duration``: refuse (:class:`vcnc.ProgramTooLongError`) a program that needs
        more samples (default: the interpolator's guard, ``interpolators.interpolate``).
    limits : mapping of axis name to interpolators.AxisLimits, optional
        Axis limits used instead of the machine's (without a machine: instead of the interpolator's
        defaults), e.g. ``vcnc compare``'s ``--acceleration``.

    Notes
    -----
    The cut keeps the first ``k`` blocks, ``k`` the largest whose run fits in ``max_duration``
    (a first guess from a lower bound of the block times, then, when that prefix is too long, a
    guess in proportion to the samples it needs and bisection; each try bounded by the budget's
    samples).
    Its samples equal the whole program's up to the last exact stop before the cut; after it, the
    last block ends at rest where the whole program may pass at speed (G64), which the note says.
    """
    import interpolators

    if not hasattr(program, "blocks"):
        program = interpolators.load_program(program)
    ts = sample_time
    if machine is not None:
        if isinstance(machine, (str, os.PathLike)):
            from vcnc.engine.machine import load_machine

            machine = load_machine(machine)
        check_program_axes(program, machine)
        limits = machine.limits if limits is None else limits
        ts = machine.sample_time if ts is None else ts
    ts = 1e-3 if ts is None else ts
    if max_duration is None:
        guard = {} if max_samples is None else {"max_samples": max_samples}
        sp = interpolators.interpolate(program, limits=limits, sample_time=ts, profile=profile, **guard)
    elif isinstance(max_duration, (int, float)) and math.isfinite(max_duration) and max_duration > 0:
        sp = _first_seconds(program, limits=limits, sample_time=ts, profile=profile, max_duration=float(max_duration))
    else:
        raise InputError(f"max_duration must be a finite value > 0 s, got {max_duration!r}")
    return sp if machine is None else _machine_axes(sp, machine.axes)


def _machine_axes(setpoints: Setpoints, axes: tuple[str, ...]) -> Setpoints:
    """``setpoints`` without the columns of axes not in ``axes``: those the program names but never
    moves (:func:`check_program_axes` refused the others), constant, so the machine can run it."""
    keep = tuple(a for a in setpoints.axes if a in axes)
    return setpoints if len(keep) == len(setpoints.axes) else setpoints.select_axes(keep)


def check_program_axes(program: Program, machine: Machine, *, option: str = "--machine") -> None:
    """:class:`vcnc.GCodeError` naming the program, the line of the first move of an axis that
    ``machine`` lacks, the machine's axes and how to add one; nothing when all axes are there.

    An axis the program only names without moving it (``G0 Z0`` from Z0) is no obstacle: the
    interpolator needs limits only for the axes that move. ``option``: the command's option that names the
    machine, in the way forward (``vcnc compare``'s is ``--truth``)."""
    from toolpaths.geometry import Arc
    from vcnc.core.axes import AXIS_NAMES, EXTRA_NAMES

    # only the axes the machine lacks are looked at (a program of 200,000 blocks on a machine with all of
    # them costs no per-block work beyond the loop)
    no_xyz = [i for i, a in enumerate("xyz") if a not in machine.axes]
    no_extra = [i for i, a in enumerate(EXTRA_NAMES) if a not in machine.axes]
    first, lacking = None, set()
    for b in program.blocks:
        missing = set()
        if no_xyz:
            moved = [i for i in no_xyz if b.start[i] != b.target[i]]
            if isinstance(b.segment, Arc):  # a full circle ends where it starts, but moves its plane's axes
                moved += [i for i in b.segment.plane_axes if i in no_xyz]
            missing = {"xyz"[i] for i in moved}
        if no_extra and b.extra_start is not None and b.extra_target is not None:
            d = b.extra_delta
            missing |= {EXTRA_NAMES[i] for i in no_extra if d[i] != 0}
        if missing and first is None:
            first = (b, missing)
        lacking |= missing
    if first is not None:
        b, missing = first
        missing = [a for a in AXIS_NAMES if a in missing]  # in the machine's order
        names = ", ".join(a.upper() for a in missing)
        raise GCodeError(
            f"the program moves axis {names}, which machine {machine.name!r} does not have (its axes: "
            f"{', '.join(a.upper() for a in machine.axes)})",
            file=program.source,
            line=b.line,
            expected=f"a machine with axis {names}: {_add_axis_hint(machine, lacking, option)}"
            f"{_axis_section_hint(machine, missing[0])}",
        )


def _axis_section_hint(machine: Machine, axis: str) -> str:
    """Where the ``[axes.AXIS]`` section goes: the machine's own file when it came from one (``vcnc machines
    --show`` knows only built-in names), else a TOML file written from the built-in machine."""
    from vcnc.core.axes import ROTARY_NAMES

    unit = " in degrees (limits in deg/s, deg/s^2, deg/s^3)" if axis in ROTARY_NAMES else ""
    if machine.file:
        return f"add an [axes.{axis}] section{unit} to {machine.file}"
    return f"write `vcnc machines --show {machine.name}` to a TOML file and add an [axes.{axis}] section{unit}"


def _add_axis_hint(machine: Machine, lacking: set[str], option: str) -> str:
    """``OPTION NAME+z runs ... or `` when a built-in machine's name can add the axes the program moves and it
    ``lacking``, else ''."""
    from vcnc.engine.machine import ADDABLE_AXES

    if not (machine.source or "").startswith("<built-in ") or not lacking <= set(ADDABLE_AXES):
        return ""
    added = machine.name.partition("+")[2] + "".join(lacking)
    name = machine.name.partition("+")[0] + "+" + "".join(a for a in ADDABLE_AXES if a in added)
    axes = " and ".join(a.upper() for a in ADDABLE_AXES if a in lacking)
    return f"`{option} {name}` runs {axes} on a copy of its X drive (an assumption), or "


def truncation_note(setpoints: Setpoints, *, done: str = "simulated") -> str | None:
    """One line saying where :func:`interpolate` cut the program under ``max_duration``, or None;
    ``done`` says what happened to the first seconds (``"simulated"``, ``"interpolated"``)."""
    cut = setpoints.meta.get("truncated")
    if not cut:
        return None
    return (
        f"only the first {cut['duration']:.6g} s of at least {cut['program_at_least']:.6g} s {done} (budget "
        f"{cut['budget']:g} s): {cut['blocks']} of {cut['of']} blocks complete, cut in the block at line "
        f"{cut['line']}; the rest is not run" + ("" if cut["exact"] else
                                                  ", and the blocks before the cut may slow down where the "
                                                  "whole program passes at speed")
    )


def program_meta(setpoints: Setpoints, program_name: str, *, profile: str) -> dict[str, str]:
    """What a capture simulated from a program records besides the machine's entries: ``program``
    (file name), ``profile`` and, when :func:`interpolate` cut it, ``truncated`` (the note)."""
    note = truncation_note(setpoints)
    return {"program": program_name, "profile": profile, **({"truncated": note} if note else {})}


#: Samples one try of :func:`interpolate`'s cut may hold (at least; more when the budget needs them): a
#: prefix of the program up to this length is interpolated whole and cut, one try instead of a
#: bisection over its blocks (about 200 MB for 9 axes' position, velocity and acceleration).
TRY_SAMPLES = 1_000_000


def _least_times(program: Program, limits) -> np.ndarray:
    """A lower bound of each block's end time [s]: XYZ lengths at the programmed feed capped by the
    norm of the axes' velocity limits (rapids at the norm of the rapid rates), plus the dwells."""
    from interpolators import DEFAULT_LIMITS

    lim = [v for a, v in (limits if limits is not None else DEFAULT_LIMITS).items() if a in ("x", "y", "z")]
    v_cap = math.hypot(*(x.velocity for x in lim)) if lim else math.inf
    rapid_cap = math.hypot(*(x.rapid_rate for x in lim)) if lim else math.inf
    t = np.empty(len(program.blocks))
    for i, b in enumerate(program.blocks):
        speed = rapid_cap if math.isinf(b.feed) else min(b.feed, v_cap)
        t[i] = (b.length / speed if speed > 0 else 0.0) + b.dwell
    return np.cumsum(t)


def _first_seconds(program: Program, *, limits, sample_time: float, profile: str, max_duration: float) -> Setpoints:
    """The first ``max_duration`` [s] of ``program``'s setpoints (see :func:`interpolate`)."""
    import interpolators

    budget = int(math.floor(max_duration / sample_time + 1e-9)) + 1
    margin = min(1.0 + 0.1 * max_duration, 60.0)  # [s] after the cut, where the prefix's own stop may begin
    enough = budget + int(math.ceil(margin / sample_time))  # a prefix this long gives the whole program's samples
    cap = max(budget + int(2 * margin / sample_time), TRY_SAMPLES)  # the samples one try may hold (memory)

    def run(k: int) -> Setpoints | int:
        """The setpoints of the first ``k`` blocks, or the samples they need beyond ``cap``."""
        part = program if k == len(program.blocks) else dataclasses.replace(program, blocks=program.blocks[:k])
        try:
            return interpolators.interpolate(part, limits=limits, sample_time=sample_time, profile=profile,
                                             max_samples=cap)
        except ProgramTooLongError as exc:
            return exc.samples

    least = _least_times(program, limits)
    k = min(int(np.searchsorted(least, max_duration + margin, side="right")) + 1, len(program.blocks))
    got = run(k)
    if isinstance(got, Setpoints):
        sp = got
        if k == len(program.blocks) and len(sp) <= budget:
            return sp
    else:  # slower than the bound: the longest prefix within cap, from a proportional guess, then bisection
        lo, hi, sp = 0, k, None
        guess = max(1, int(k * cap / got * 0.9))
        while hi - lo > 1:
            mid = guess if lo < guess < hi else (lo + hi) // 2
            guess = 0
            got = run(mid)
            lo, hi, sp = (mid, hi, got) if isinstance(got, Setpoints) else (lo, mid, sp)
            if sp is not None and len(sp) >= enough:  # long enough: a longer prefix would change nothing
                break
        if sp is None or sp.duration == 0.0:  # nothing before the block that does not fit moves or dwells
            raise GCodeError(f"this block alone runs longer than one try of the {max_duration:g} s cut holds "
                             f"({cap} samples, {cap * sample_time:g} s), and no block before it moves or dwells",
                             file=program.source, line=program.blocks[lo].line,
                             expected=f"a block within {cap * sample_time:g} s (its length at its feed)")
        k = lo
    exact = sp.duration >= max_duration + margin or k == len(program.blocks)
    out = sp.slice(0, budget)
    # the blocks before the one the cut falls in are complete (all of the prefix when nothing was cut)
    done = k if len(out) == len(sp) else int(out.block[-1])
    out.meta["truncated"] = {
        "budget": max_duration,
        "duration": out.duration,
        "program_at_least": max(float(least[-1]), sp.duration),
        "blocks": done,
        "of": len(program.blocks),
        "line": program.blocks[done].line,
        "exact": bool(exact),
    }
    return out
