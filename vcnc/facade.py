"""The everyday entry points that tie the packages together (``vcnc.interpolate``)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from vcnc.core.setpoints import Setpoints

if TYPE_CHECKING:  # pragma: no cover
    from interpolators import Program
    from vcnc.engine.machine import Machine

__all__ = ["interpolate"]


def interpolate(
    program: Program | str | os.PathLike[str],
    machine: Machine | str | None = None,
    *,
    profile: str = "trapezoid",
    sample_time: float | None = None,
) -> Setpoints:
    """Interpolate a part program with a machine's axis limits and sample time.

    Parameters
    ----------
    program : Program or path
        A parsed program, or the path of a program file (ISO or Heidenhain, detected by content).
    machine : Machine or str, optional
        The machine (or a built-in name / TOML path) whose axis limits and sample time apply;
        without one the interpolator's documented default limits and 1 ms are used.
    profile : {"trapezoid", "scurve"}
        Feed profile along the path.
    sample_time : float, optional
        Interpolation period [s]; defaults to the machine's.
    """
    import interpolators

    if not hasattr(program, "blocks"):
        program = interpolators.load_program(program)
    limits = None
    ts = sample_time
    if machine is not None:
        if isinstance(machine, (str, os.PathLike)):
            from vcnc.engine.machine import load_machine

            machine = load_machine(machine)
        limits = machine.limits
        ts = machine.sample_time if ts is None else ts
    return interpolators.interpolate(program, limits=limits, sample_time=1e-3 if ts is None else ts, profile=profile)
