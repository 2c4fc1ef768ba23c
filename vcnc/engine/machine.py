"""Virtual machines: axes of drives and controllers simulated from setpoints into captures.

A machine comes from a built-in name (``vcnc machines`` lists them) or a TOML file (schema in
:mod:`vcnc.engine.machine_file`)::

    m = load_machine("fadal-pid")
    capture = m.simulate(setpoints, seed=1)
    m.axis("x").reduced_parameters()          # a1..d1 of Eq. (3.3)
    g_track, g_dist = m.axis("x").closed_loop(m.sample_time)
    worse = m.with_axis_options("x", backlash=0.02)          # one non-ideality changed
    worse = m.with_effect("x", "resonance")                  # a diagnosis effect, realistic size

Axes may also be external objects (an identified model, an FMU) with
``simulate_reference(reference, sample_time) -> measured`` [mm]; see :meth:`Machine.from_axes`.
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import importlib.resources
import logging
import math
import os
import tomllib
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np

import drives
from drives.effects import EFFECT_NAMES
from drives.effects import EFFECTS as EFFECT_REGISTRY
from interpolators.context import DEFAULT_CONTEXT, MachineContext
from interpolators.limits import AxisLimits
from vcnc.core.capture import Capture
from vcnc.core.errors import InputError, MachineError, PlausibilityWarning, SimulationError
from vcnc.core.setpoints import AXIS_NAMES, Setpoints
from vcnc.engine.axis import AxisDefinition
from vcnc.engine.layout import N_OUT
from vcnc.engine.machine_file import parse_machine_text

__all__ = [
    "Machine",
    "AxisDefinition",
    "ExternalAxis",
    "load_machine",
    "builtin_machines",
    "builtin_machine_text",
    "is_builtin_name",
    "EFFECTS",
    "realistic_effect",
    "reference_control",
]

log = logging.getLogger(__name__)

_BUILTIN_PACKAGE = "vcnc.machines"


@runtime_checkable
class ExternalAxis(Protocol):
    """An axis simulated outside the compiled kernel (identified model, FMU, ...)."""

    def simulate_reference(self, reference: np.ndarray, sample_time: float) -> np.ndarray:
        """Measured position [mm] for the commanded position ``reference`` [mm]."""
        ...


#: The linear axes a built-in machine's name can add after a ``+`` (``fadal-pid+z``, ``emps+yz``), each a
#: copy of the machine's X axis.
ADDABLE_AXES = "yz"


def builtin_machines() -> list[str]:
    """Names of the built-in machines (sorted)."""
    root = importlib.resources.files(_BUILTIN_PACKAGE)
    return sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml"))


def is_builtin_name(name: str) -> bool:
    """Whether ``name`` is a built-in machine, with or without added axes (``fadal-pid+z``)."""
    return name.partition("+")[0] in builtin_machines()


def builtin_machine_text(name: str) -> str:
    """TOML text of a built-in machine; MachineError listing the names if unknown.

    ``NAME+z`` (``+y``, ``+yz``) is built-in machine NAME with those linear axes, which it lacks, added as copies
    of its X axis: every ``[axes.x...]`` table repeated as ``[axes.z...]`` (drive, controller, limits, effects).
    The thesis, seed 004 and EMPS describe the X (and Y) drives only; a part program moves Z too. The copy is
    vcnc's assumption for running such programs, not a measured drive (no gravity, no heavier head), and the
    text's first lines, its ``name`` and ``description`` say so."""
    base, plus, added = name.partition("+")
    if base not in builtin_machines():
        raise MachineError(f"unknown machine {name!r}; built-in machines: {', '.join(builtin_machines())}")
    text = (importlib.resources.files(_BUILTIN_PACKAGE) / f"{base}.toml").read_text()
    return _with_x_copies(text, base, added, spec=name) if plus else text


def _with_x_copies(text: str, base: str, added: str, *, spec: str) -> str:
    """The TOML ``text`` of built-in ``base`` with the axes ``added`` (letters of :data:`ADDABLE_AXES`) as copies
    of its ``[axes.x...]`` tables, renamed ``spec``."""
    lines = text.splitlines()
    headers = [i for i, ln in enumerate(lines) if ln.startswith("[")]
    present = set(tomllib.loads(text).get("axes", {}))
    if (not added or any(a not in ADDABLE_AXES for a in added) or len(set(added)) != len(added)
            or any(a in present for a in added)):
        raise MachineError(
            f"machine {spec!r}: {base} has the axes {', '.join(sorted(present))}; after '+' name the linear axes "
            f"to add, each a copy of its X axis ({', '.join(ADDABLE_AXES)}, the ones it lacks), e.g. "
            f"{base}+{''.join(a for a in ADDABLE_AXES if a not in present)}")
    x_tables = [
        "\n".join(lines[i:next((j for j in headers if j > i), len(lines))]).rstrip()
        for i in headers if lines[i] == "[axes.x]" or lines[i].startswith("[axes.x.")]
    names = " and ".join(a.upper() for a in ADDABLE_AXES if a in added)
    note = (f"{names} {'a copy' if len(added) == 1 else 'copies'} of the X axis (vcnc's assumption for programs "
            f"that move {names}; {base}'s source describes no such drive)")
    out = [f"# {spec}: {base} with {note}."]
    for ln in lines:
        if ln.startswith("name = "):
            ln = f'name = "{spec}"'
        elif ln.startswith("description = "):
            ln = ln.rstrip()[:-1] + f'; {note}"'
        out.append(ln)
    for a in (a for a in ADDABLE_AXES if a in added):
        out += ["", f"# Axis {a.upper()}: a copy of [axes.x] (assumed)."]
        for t in x_tables:
            out += [t.replace("[axes.x", f"[axes.{a}", 1), ""]
    return "\n".join(out).rstrip() + "\n"


def load_machine(name_or_path: str | Path) -> Machine:
    """A built-in machine by name (``NAME+z``: with a Z axis copied from X, see :func:`builtin_machine_text`), or
    a machine TOML file.

    Raises
    ------
    MachineError
        Unknown name (listing the built-in names), unreadable file, or a definition that fails
        the schema (naming the key, its unit, the file and the line).
    """
    s = str(name_or_path)
    if is_builtin_name(s):
        text = builtin_machine_text(s)
        return Machine._from_text(text, file=f"<built-in {s}>", default_name=s)
    p = Path(s)
    if p.suffix.lower() != ".toml" and not p.exists():
        raise MachineError(
            f"unknown machine {s!r}: neither a built-in name ({', '.join(builtin_machines())}) nor a .toml file"
        )
    try:
        text = p.read_text()
    except OSError as exc:
        raise MachineError(f"cannot read machine file ({exc.strerror or exc})", file=s) from None
    return Machine._from_text(text, file=s, default_name=p.stem)


class Machine:
    """A multi-axis virtual machine.

    Attributes
    ----------
    name : str
        Machine name (built-in name or the TOML ``name``).
    axes : tuple of str
        Axis names in definition order.
    sample_time : float
        Servo and interpolation period Ts [s].
    limits : dict of str to AxisLimits
        Kinematic limits per axis for the interpolator.
    description : str
        Free text.
    source : str or None
        Where the definition came from.
    context : MachineContext
        What the control applies to part programs: work offsets, tool table, home and reference
        positions, dialect (the TOML's ``[program]`` table; the default changes nothing).
    """

    def __init__(
        self,
        *,
        name: str,
        axes: Mapping[str, AxisDefinition | ExternalAxis],
        sample_time: float,
        limits: Mapping[str, AxisLimits],
        description: str = "",
        source: str | None = None,
        context: MachineContext = DEFAULT_CONTEXT,
    ) -> None:
        if not (isinstance(sample_time, (int, float)) and math.isfinite(sample_time) and sample_time > 0):
            raise MachineError(f"Machine.sample_time [s] must be a finite number > 0, got {sample_time!r}")
        if not axes:
            raise MachineError("a machine needs at least one axis")
        for a, ax in axes.items():
            if a not in AXIS_NAMES:
                raise MachineError(f"unknown axis name {a!r}; expected some of {AXIS_NAMES}")
            if not isinstance(ax, AxisDefinition) and not isinstance(ax, ExternalAxis):
                raise MachineError(
                    f"axis {a}: {type(ax).__name__} is neither an AxisDefinition nor has "
                    "simulate_reference(reference, sample_time)"
                )
            if a not in limits:
                raise MachineError(f"axis {a}: no limits given (AxisLimits: velocity, acceleration, jerk)")
        self.name = name
        self._axes = dict(axes)
        self.axes: tuple[str, ...] = tuple(axes)
        self.sample_time = float(sample_time)
        self.limits: dict[str, AxisLimits] = {a: limits[a] for a in self.axes}
        self.description = description
        self.source = source
        self.context = context

    @property
    def file(self) -> str | None:
        """The machine file this machine was read from, or None (a built-in machine: ``source`` ``<built-in>``)."""
        return self.source if self.source and not self.source.startswith("<") else None

    # ------------------------------------------------------------------ construction
    @classmethod
    def _from_text(cls, text: str, *, file: str, default_name: str) -> Machine:
        spec = parse_machine_text(text, file=file, default_name=default_name)
        for message in spec.warnings:
            warnings.warn(message, PlausibilityWarning, stacklevel=3)
        axes: dict[str, Any] = {}
        for a, ax in spec.axes.items():
            if isinstance(ax, tuple) and ax[0] == "fmu":
                axes[a] = _load_fmu_axis(ax[1], file=file, line=ax[2])
            else:
                axes[a] = ax
        return cls(
            name=spec.name,
            axes=axes,
            sample_time=spec.sample_time,
            limits=spec.limits,
            description=spec.description,
            source=file,
            context=spec.context,
        )

    @classmethod
    def from_axes(
        cls,
        axes: Mapping[str, AxisDefinition | ExternalAxis],
        *,
        sample_time: float,
        limits: Mapping[str, AxisLimits] | None = None,
        name: str = "custom",
        description: str = "",
    ) -> Machine:
        """A machine from axis objects.

        Parameters
        ----------
        axes : mapping of axis name to AxisDefinition or external axis
            External axes implement ``simulate_reference(reference: ndarray, sample_time: float)
            -> ndarray`` giving the measured position [mm] for the commanded one [mm] (an identified
            reduced model, ``vcnc.fmu.FmuAxis``); they are simulated outside the compiled kernel.
        sample_time : float
            Ts [s].
        limits : mapping of axis name to AxisLimits, optional
            Defaults to the AxisDefinition's own limits, or an external axis' ``limits``
            attribute.
        """
        lim: dict[str, AxisLimits] = {}
        for a, ax in axes.items():
            if limits is not None and a in limits:
                lim[a] = limits[a]
            elif isinstance(ax, AxisDefinition):
                lim[a] = ax.limits
            elif isinstance(getattr(ax, "limits", None), AxisLimits):
                lim[a] = ax.limits
        return cls(name=name, axes=axes, sample_time=sample_time, limits=lim, description=description)

    # ------------------------------------------------------------------ access
    def axis(self, name: str) -> AxisDefinition | ExternalAxis:
        """The definition of axis ``name`` (an AxisDefinition, or the external axis object)."""
        try:
            return self._axes[name]
        except KeyError:
            raise MachineError(f"machine {self.name!r} has no axis {name!r} (axes: {', '.join(self.axes)})") from None

    def __repr__(self) -> str:
        return f"Machine(name={self.name!r}, axes={self.axes}, sample_time={self.sample_time})"

    # ------------------------------------------------------------------ variants
    def unstable_axes(self) -> dict[str, float]:
        """The axes whose sampled closed loop is unstable at this machine's ``sample_time``: axis -> the largest
        pole magnitude |z| (>= 1) of its loop (controller law, ZOH plant with its structural mode, computation
        delay: :meth:`vcnc.engine.axis.AxisDefinition.sampled_loop`). Laws tuned in continuous time (PID, P-PI,
        SMC) lose stability when sampled too coarsely (fadal-pid's gains at 5 ms: |z| = 1.16), which a run shows
        only as a saturated actuator and errors beyond the travel; a delay with a lightly damped mode rings the
        loop (ballscrew-zpetc, 2 samples and an 84.7 Hz mode: |z| = 1.12, stable without the mode). FMU axes and
        loops that cannot be built here are left out."""
        out: dict[str, float] = {}
        for a in self.axes:
            ax = self.axis(a)
            if not isinstance(ax, AxisDefinition):
                continue
            try:
                _, g_dist = ax.sampled_loop(self.sample_time)
            except (MachineError, ValueError, ArithmeticError):
                continue
            poles = g_dist.poles()
            radius = float(np.max(np.abs(poles))) if len(poles) else 0.0
            if radius >= 1.0:
                out[a] = radius
        return out

    def with_axis(self, name: str, definition: AxisDefinition | ExternalAxis, *, suffix: str = "") -> Machine:
        """A copy with axis ``name`` replaced (or added)."""
        axes = dict(self._axes)
        axes[name] = definition
        limits = dict(self.limits)
        if isinstance(definition, AxisDefinition):
            limits[name] = definition.limits
        return Machine(
            name=self.name + suffix,
            axes=axes,
            sample_time=self.sample_time,
            limits=limits,
            description=self.description,
            source=self.source,
            context=self.context,
        )

    def with_axis_options(
        self,
        axis: str,
        *,
        friction: drives.Friction | None | object = ...,
        backlash: drives.Backlash | float | None | object = ...,
        encoder: drives.Encoder | float | None | object = ...,
        dac: drives.DAC | None | object = ...,
        saturation: drives.Saturation | None | object = ...,
        noise: drives.MeasurementNoise | float | None | object = ...,
        delay: drives.ComputationalDelay | int | None | object = ...,
        resonance: drives.StructuralMode | None | object = ...,
        position_periodic: drives.PositionPeriodic | None | object = ...,
        load: drives.ExternalLoad | None | object = ...,
        drift: drives.Drift | float | None | object = ...,
        feedback: str | object = ...,
        measurement: str | object = ...,
        substeps: int | object = ...,
        controller: Any = ...,
        drive: Any = ...,
    ) -> Machine:
        """A copy of the machine with non-idealities of one axis set, replaced or removed.

        Every keyword left out keeps its value; ``None`` removes the effect. Shorthands:
        ``backlash=0.02`` [mm width], ``encoder=5e-4`` [mm], ``noise=1e-4`` [mm std],
        ``delay=1`` [samples], ``drift=2e-5`` [mm/s]. Records of ``drives`` give full control, e.g.
        ``resonance=drives.StructuralMode(frequency_hz=80, damping=0.03)``. ``feedback`` ("motor" or
        "table") is what the loop closes on, ``measurement`` ("feedback" or "table") what a
        capture's ``measured`` records (see :class:`AxisDefinition`). The new machine's name gets a
        ``+`` suffix.
        """
        ax = self.axis(axis)
        if not isinstance(ax, AxisDefinition):
            raise MachineError(f"axis {axis} of {self.name!r} is external; its options cannot be changed")
        shorthand = {
            "backlash": lambda v: drives.Backlash(width=float(v)),
            "encoder": lambda v: drives.Encoder(resolution=float(v)),
            "noise": lambda v: drives.MeasurementNoise(std=float(v)),
            "delay": lambda v: drives.ComputationalDelay(samples=int(v)),
            "drift": lambda v: drives.Drift(rate=float(v)),
        }
        given = {
            "friction": friction,
            "backlash": backlash,
            "encoder": encoder,
            "dac": dac,
            "saturation": saturation,
            "noise": noise,
            "delay": delay,
            "resonance": resonance,
            "position_periodic": position_periodic,
            "load": load,
            "drift": drift,
            "feedback": feedback,
            "measurement": measurement,
            "substeps": substeps,
            "controller": controller,
            "drive": drive,
        }
        changes: dict[str, Any] = {}
        for k, v in given.items():
            if v is ...:
                continue
            if k in shorthand and isinstance(v, (int, float)) and not isinstance(v, bool):
                v = shorthand[k](v)
            changes[k] = v
        return self.with_axis(axis, dataclasses.replace(ax, **changes), suffix="+")

    def with_effect(self, axis: str, effect: str, parameters: Mapping[str, Any] | None = None) -> Machine:
        """A copy with one diagnosis effect (ARCHITECTURE.md vocabulary) added at a realistic size.

        ``effect`` is one of :data:`EFFECTS`; ``parameters`` override the defaults of
        :func:`realistic_effect` (same keys). Two effects also set where the axis is observed, so
        that a capture shows them the way a real machine would:

        - ``backlash`` closes the loop on a table scale by default (``feedback = "table"``): a
          motor encoder never sees nut backlash. ``{"feedback": "motor"}`` keeps a semi-closed
          loop and records a table scale instead; ``{"feedback": "axis"}`` leaves the axis as it
          is (on the fadal machines: backlash invisible in ``measured``).
        - ``drift`` records an independent table scale (``measurement = "table"``), where the
          drift of the feedback shows; ``{"measurement": "feedback"}`` records the feedback, which
          the loop holds on the command (drift only in ``Capture.table``).
        """
        ax = self.axis(axis)
        if not isinstance(ax, AxisDefinition):
            raise MachineError(f"axis {axis} of {self.name!r} is external; effects cannot be added")
        changes = realistic_effect(ax, effect, parameters, sample_time=self.sample_time)
        m = self.with_axis(axis, dataclasses.replace(ax, **changes), suffix=f"+{effect}")
        return m

    # ------------------------------------------------------------------ simulation
    def simulate(self, setpoints: Setpoints, *, seed: int | None = None) -> Capture:
        """Simulate the commanded motion; deterministic for a given seed.

        Parameters
        ----------
        setpoints : Setpoints
            Commanded position [mm], velocity [mm/s], acceleration [mm/s^2] per axis, sampled at
            the machine's ``sample_time``. Axes of the machine absent from the setpoints are not
            simulated; an axis in the setpoints that the machine lacks is an error.
        seed : int, optional
            Seed of the measurement noise (``None`` means 0: runs are always reproducible).

        Returns
        -------
        Capture
            ``reference``, ``measured`` [mm] (the feedback signal, or a table scale for an axis with
            ``measurement = "table"``), and when every axis is compiled also ``table`` (true
            table position [mm]), ``velocity`` [mm/s], ``control`` [V], ``friction`` (dry friction
            as control signal [V]) and ``aux["measured_true"]``: the true position of the measured
            point [mm], i.e. ``measured`` without sensor noise, encoder quantisation and drift, and
            ``aux["saturated"]``: where the control signal was at its limit (bool, shape (N, n_axes)): the
            actuator passed its limit value (:meth:`AxisDefinition.actuator_limit`), or the law's
            anti-windup held a step back because its demand was beyond it (``Controller.anti_windup``).
            ``path`` is the setpoints' path; ``meta`` records the machine name, seed and sample time.
            Each axis starts at rest at its first commanded position.
        """
        seed_v = self._check_run(setpoints, seed)
        n = len(setpoints)
        jobs, external = self._axis_jobs(setpoints, seed_v)
        measured, table, velocity, control, friction, position, limited = self._run_jobs(jobs, n, len(setpoints.axes))
        for i, y in external.items():
            measured[:, i] = y
        all_compiled = not external
        meta = {"machine": self.name, "seed": seed_v, "sample_time": self.sample_time}
        return Capture(
            t=np.asarray(setpoints.t, dtype=float),
            axes=tuple(setpoints.axes),
            reference=np.array(setpoints.position, dtype=float),
            measured=measured,
            control=control if all_compiled else None,
            table=table if all_compiled else None,
            velocity=velocity if all_compiled else None,
            friction=friction if all_compiled else None,
            aux={"measured_true": position, "saturated": limited > 0.5}
            if all_compiled else {},
            meta=meta,
            path=setpoints.path,
        )

    def _check_run(self, setpoints: Setpoints, seed: int | None) -> int:
        """InputError unless ``setpoints`` fit this machine; the noise seed to use."""
        if not isinstance(setpoints, Setpoints):
            raise InputError(f"simulate needs Setpoints, got {type(setpoints).__name__}")
        if not math.isclose(setpoints.sample_time, self.sample_time, rel_tol=1e-6):
            raise InputError(
                f"setpoints are sampled at {setpoints.sample_time} s but machine {self.name!r} runs at "
                f"sample_time {self.sample_time} s; interpolate with the machine's sample time"
            )
        missing = [a for a in setpoints.axes if a not in self._axes]
        if missing:
            raise InputError(
                f"setpoints command axis {', '.join(missing)} which machine {self.name!r} does not have "
                f"(axes: {', '.join(self.axes)})"
            )
        seed_v = 0 if seed is None else int(seed)
        if not 0 <= seed_v < 2**32:
            raise InputError(f"seed must be an integer in [0, 2**32), got {seed!r}")
        return seed_v

    def _axis_jobs(self, setpoints: Setpoints, seed_v: int) -> tuple[list, dict[int, np.ndarray]]:
        """The compiled axes' kernel calls, and the measured position of the external axes (run here)
        by column."""
        n = len(setpoints)
        jobs, external = [], {}
        for i, a in enumerate(setpoints.axes):
            ax = self._axes[a]
            ref = np.ascontiguousarray(setpoints.position[:, i], dtype=float)
            if not isinstance(ax, AxisDefinition):
                y = np.asarray(ax.simulate_reference(ref, self.sample_time), dtype=float).reshape(-1)
                if y.shape != (n,):
                    raise SimulationError(f"external axis {a} returned {y.shape[0]} samples, expected {n}")
                external[i] = y
                continue
            p, c = ax.pack(self.sample_time)
            ref_c = np.ascontiguousarray(ax.controller.prefilter(ref, ax.drive, self.sample_time), dtype=float)
            # each axis gets its own noise stream, derived from the seed and the axis name
            axis_seed = (seed_v * 7919 + AXIS_NAMES.index(a) * 104729) % (2**32)
            args = (
                ref_c,
                np.ascontiguousarray(setpoints.velocity[:, i], dtype=float),
                np.ascontiguousarray(setpoints.acceleration[:, i], dtype=float),
                p,
                c,
                float(ref[0]) if n else 0.0,
                axis_seed,
                np.empty((n, N_OUT)),
            )
            jobs.append((i, a, args))
        return jobs, external

    def _run_jobs(self, jobs: list, n: int, n_axes: int) -> list[np.ndarray]:
        """Run the kernel calls (one thread per axis for long multi-axis runs: the kernel releases the
        GIL); the seven outputs (measured, table, velocity, control, friction, position, limited), each
        ``(n, n_axes)``, filled column by column, each axis' kernel output released once copied (a
        long run holds twice its outputs at most, not three times)."""
        from vcnc.engine.kernel import simulate_axis

        if n:
            if len(jobs) > 1 and n * len(jobs) >= 200_000:
                with concurrent.futures.ThreadPoolExecutor(max_workers=min(len(jobs), os.cpu_count() or 1)) as ex:
                    status = list(ex.map(lambda job: simulate_axis(*job[2]), jobs))
            else:
                status = [simulate_axis(*job[2]) for job in jobs]
            for (_i, a, _args), st in zip(jobs, status):
                if st >= 0:
                    raise SimulationError(
                        f"machine {self.name!r}, axis {a}: the simulation diverged at "
                        f"t = {st * self.sample_time:.6g} s (unstable loop?)"
                    )
        outs = [np.empty((n, n_axes)) for _ in range(N_OUT)]
        while jobs:
            i, _a, args = jobs.pop(0)
            for c in range(N_OUT):
                outs[c][:, i] = args[-1][:, c]
            del args
        return outs


def _load_fmu_axis(path: str, *, file: str, line: int | None) -> ExternalAxis:
    from vcnc.engine.fmu_axis import FmuAxis  # loads fmpy, only for machines with FMU axes

    try:
        return FmuAxis(path)
    except InputError as exc:
        raise MachineError(f"fmu = {path!r}: {exc}", file=file, line=line) from None


# ---------------------------------------------------------------------- effects
#: diagnosis effect names (ARCHITECTURE.md; the registry :mod:`drives.effects`) that
#: :meth:`Machine.with_effect` can add
EFFECTS: tuple[str, ...] = EFFECT_NAMES


def realistic_effect(
    axis: AxisDefinition,
    effect: str,
    parameters: Mapping[str, Any] | None = None,
    *,
    sample_time: float | None = None,
) -> dict[str, Any]:
    """Field changes of ``axis`` that add ``effect`` at a realistic magnitude.

    Defaults (override by ``parameters``, same keys). They are chosen so that the effect is both
    realistic and visible in a capture of an identification test (random moves at the axis'
    acceleration limit, thesis Table 3.2 style); ``benchmarks/diagnosis.py`` checks that the
    residual diagnosis finds each of them.

    - friction_stribeck: ``static_ratio`` 2.0 (static / Coulomb), ``stribeck_velocity_mm_s`` 5.0;
      an axis without Coulomb friction gets 2 % of the force at 1 V first. Sources: the static
      friction of lubricated guideways and ball screws is 1.3-2 times the Coulomb level and the
      Stribeck velocity a few to ~10 mm/s (Armstrong-Helouvry, Dupont, Canudas de Wit, "A survey
      of models, analysis tools and compensation methods for the control of machines with
      friction", Automatica 30(7), 1994; the LuGre example of Canudas de Wit et al., IEEE TAC
      40(3), 1995, uses F_s/F_c = 1.5, v_s = 1 mm/s for a servo). At the upper end of the range,
      because on the Fadal axes a ratio of 1.5 at 2 mm/s changes the tracking error by less than
      the noise floor of an identification capture.
    - friction_viscous_asymmetric: ``asymmetry`` 0.3: viscous +/-30 % by direction.
    - backlash: ``width_mm`` 0.01; ``feedback`` "table" (default): the axis is closed on a linear
      scale at the table, so the play is inside the loop and in ``measured`` (the controller
      hunts across the gap at every reversal); "motor": semi-closed loop on the motor encoder,
      the capture records a table scale (``measurement = "table"``) where the lost motion
      shows; "axis": keep the axis' own ``feedback`` and ``measurement``. A motor encoder alone
      cannot see nut backlash, so with the built-in semi-closed machines (fadal-*) "axis" hides
      the effect from ``measured`` (only ``Capture.table`` shows it).
    - position_periodic: ``period_mm`` the screw lead (10 mm for others), ``amplitude_n`` 5 % of the
      force at 1 V (a torque ripple), ``position_amplitude_mm`` 0.
    - time_periodic: ``period_s`` 0.5, ``amplitude_n`` 10 % of the force at 1 V.
    - resonance: ``frequency_hz`` 60, ``damping`` 0.05, ``load_fraction`` 0.5.
    - delay: ``samples`` 2.
    - saturation: ``saturated_fraction`` 0.03: the amplifier limit [V] is the level that 3 % of
      the samples of |control| exceed when the axis runs, without a limit, a reference
      identification test (:func:`reference_control`: 40 random moves within +/-10 mm at its
      velocity and acceleration limits, thesis Table 3.2 style). The drive then saturates briefly
      in the hardest accelerations (reversals after short moves), at 0.7-0.95 of the peak demand
      depending on the law. Fadal X axes: pid 3.34 V (peak 4.10 V), ppi 2.53 V, smc 2.78 V; on a
      Table 3.2 test at 2000 mm/s^2 (seed 1) 3.6 %, 3.7 % and 4.3 % of the samples are at the limit
      (``Capture.aux["saturated"]``; 3.9 %, 4.4 % and 4.5 % with the bare laws, ``anti_windup = false``). At
      2 % the effect is at the edge of what the residual diagnosis detects on fadal-pid.
      ``voltage_limit_v`` sets the limit [V] directly instead.
    - drift: ``rate_mm_s`` 2e-4, ``time_constant_s`` 0 (linear); ``measurement`` "table"
      (default): the feedback the loop closes on reads the table position plus the drift (e.g.
      thermal growth of the screw between the motor encoder and the table), and the capture
      records an independent linear scale on the table, where the table is seen to drift by
      ``-rate`` (the loop holds the drifting reading on the command). "feedback": the capture
      records the drifting feedback itself, which the loop keeps on the command, so the drift
      shows only in ``Capture.table``.

    ``sample_time`` [s] is the servo period used for the saturation reference move (the machine's,
    when called through :meth:`Machine.with_effect`; default 1 ms, or the discrete plant's).
    """
    info = EFFECT_REGISTRY.get(effect)
    if info is None:
        raise MachineError(f"unknown effect {effect!r}; expected one of: {', '.join(EFFECTS)}")
    if info.needs_plant and axis.discrete_plant:
        raise MachineError(
            f"effect {effect!r} needs a physical plant; axis {axis.name} is a discrete transfer function"
        )
    p = _EffectParameters(effect, parameters)
    out = _REALISTIC[effect](axis, p, sample_time)
    p.all_used()
    return out


class _EffectParameters:
    """The caller's parameters of one effect, taken one by one with their defaults."""

    def __init__(self, effect: str, parameters: Mapping[str, Any] | None) -> None:
        self.effect = effect
        self.left = dict(parameters or {})

    def get(self, key: str, default: float) -> float:
        return float(self.left.pop(key, default))

    def choice(self, key: str, default: str, allowed: tuple[str, ...]) -> str:
        v = self.left.pop(key, default)
        if v not in allowed:
            raise MachineError(f"effect {self.effect!r}: {key} must be one of {', '.join(map(repr, allowed))}, "
                               f"got {v!r}")
        return str(v)

    def all_used(self) -> None:
        if self.left:
            raise MachineError(f"unknown parameter(s) {sorted(self.left)} for effect {self.effect!r}")


def _stribeck(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    fpv = axis.drive.force_per_volt
    f = axis.friction or drives.Friction(coulomb_positive=0.02 * fpv, coulomb_negative=0.02 * fpv)
    ratio = p.get("static_ratio", 2.0)
    return {"friction": dataclasses.replace(
        f,
        static_positive=f.coulomb_positive * ratio,
        static_negative=f.coulomb_negative * ratio,
        stribeck_velocity=p.get("stribeck_velocity_mm_s", 5.0),
    ), "substeps": max(axis.substeps, 10)}


def _viscous_asymmetric(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    f = axis.friction or drives.Friction()
    b = axis.drive.viscous_rate * axis.drive.equivalent_mass
    if b == 0:
        b = 0.5 * axis.drive.equivalent_mass
    a = p.get("asymmetry", 0.3)
    return {"friction": dataclasses.replace(f, viscous_positive=b * (1 - a), viscous_negative=b * (1 + a))}


def _backlash(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    out: dict[str, Any] = {"backlash": drives.Backlash(width=p.get("width_mm", 0.01))}
    fb = p.choice("feedback", "table", ("table", "motor", "axis"))
    if fb == "table":
        out["feedback"] = "table"
    elif fb == "motor":
        out["feedback"] = "motor"
        out["measurement"] = "table"
    return out


def _position_periodic(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    lead = getattr(axis.drive, "lead", 10.0)
    return {"position_periodic": drives.PositionPeriodic(
        period=p.get("period_mm", lead),
        force_amplitude=p.get("amplitude_n", 0.05 * axis.drive.force_per_volt),
        position_amplitude=p.get("position_amplitude_mm", 0.0),
    )}


def _time_periodic(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    old = axis.load or drives.ExternalLoad()
    return {"load": dataclasses.replace(old, amplitude=p.get("amplitude_n", 0.1 * axis.drive.force_per_volt),
                                        period=p.get("period_s", 0.5))}


def _resonance(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    return {"resonance": drives.StructuralMode(
        frequency_hz=p.get("frequency_hz", 60.0),
        damping=p.get("damping", 0.05),
        load_fraction=p.get("load_fraction", 0.5),
    )}


def _delay(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    return {"delay": drives.ComputationalDelay(samples=int(p.get("samples", 2)))}


def _saturation(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    if "voltage_limit_v" in p.left:
        if "saturated_fraction" in p.left:
            raise MachineError("effect 'saturation': give voltage_limit_v or saturated_fraction, not both")
        limit = p.get("voltage_limit_v", 0.0)
    else:
        frac = p.get("saturated_fraction", 0.03)
        if not 0.0 < frac < 1.0:
            raise MachineError(f"effect 'saturation': saturated_fraction must be in (0, 1), got {frac!r}")
        u = np.abs(reference_control(axis, sample_time))
        limit = float(np.quantile(u, 1.0 - frac))
        if not (math.isfinite(limit) and limit > 0):
            raise MachineError(f"axis {axis.name}: the reference test gives no control level to saturate; "
                               "give the saturation effect an explicit voltage_limit_v")
    return {"saturation": drives.Saturation(voltage_limit=limit)}


def _drift(axis: AxisDefinition, p: _EffectParameters, sample_time: float | None) -> dict[str, Any]:
    out: dict[str, Any] = {"drift": drives.Drift(rate=p.get("rate_mm_s", 2e-4),
                                                 time_constant=p.get("time_constant_s", 0.0))}
    out["measurement"] = p.choice("measurement", "table", ("table", "feedback"))
    return out


#: effect name -> the builder of its realistic default (the registry's parameters, with defaults).
_REALISTIC = {
    "friction_stribeck": _stribeck,
    "friction_viscous_asymmetric": _viscous_asymmetric,
    "backlash": _backlash,
    "position_periodic": _position_periodic,
    "time_periodic": _time_periodic,
    "resonance": _resonance,
    "delay": _delay,
    "saturation": _saturation,
    "drift": _drift,
}


def reference_control(
    axis: AxisDefinition, sample_time: float | None = None, *, moves: int = 40, span: float = 10.0, seed: int = 0
) -> np.ndarray:
    """Control signal [V] of ``axis``, without an amplifier limit, on a reference identification test.

    The test is a thesis Table 3.2-style program (:func:`toolpaths.random_moves`: ``moves`` random
    targets within +/-``span`` mm at the axis' velocity limit, fixed ``seed``), interpolated with
    trapezoidal feed profiles at the axis' limits and simulated noise-free at ``sample_time`` [s]
    (the discrete plant's, else 1 ms by default). Its largest values come from the hardest
    accelerations: reversals after short moves, while the loop is still in a transient.
    """
    import interpolators
    import toolpaths
    from vcnc.engine.kernel import simulate_axis

    ts = getattr(axis.drive, "sample_time", None) or sample_time or 1e-3
    ax = dataclasses.replace(axis, saturation=None, noise=None)
    program = interpolators.parse_program(
        toolpaths.random_moves(moves, span, 60.0 * ax.limits.velocity, seed=seed, axes=(ax.name,))
    )
    sp = interpolators.interpolate(program, limits={ax.name: ax.limits}, sample_time=ts)
    i = sp.axes.index(ax.name)
    pos = np.ascontiguousarray(sp.position[:, i], dtype=float)
    p, c = ax.pack(ts)
    ref = np.ascontiguousarray(ax.controller.prefilter(pos, ax.drive, ts), dtype=float)
    out = np.empty((len(pos), N_OUT))
    status = simulate_axis(
        ref,
        np.ascontiguousarray(sp.velocity[:, i], dtype=float),
        np.ascontiguousarray(sp.acceleration[:, i], dtype=float),
        p, c, float(pos[0]), 0, out,
    )
    if status >= 0:
        raise MachineError(f"axis {axis.name}: the reference identification test diverged at sample {status}")
    return out[:, 3].copy()
