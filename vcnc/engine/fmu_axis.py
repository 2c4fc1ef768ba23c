"""A machine axis backed by an FMU (exported by vcnc or a third-party drive), run through fmpy."""

from __future__ import annotations

import ctypes
import logging
import os
import shutil
import weakref
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from vcnc.core.errors import MachineError, SimulationError

__all__ = ["FmuAxis"]

log = logging.getLogger(__name__)

_LENGTH_UNITS_MM = {"mm": 1.0, "m": 1000.0, "um": 1e-3, "µm": 1e-3}


def _mm_per_unit(md, var) -> float:
    """Millimetres per unit of ``var`` (1 when it has no length unit)."""
    unit = var.unit or (var.declaredType.unit if var.declaredType is not None else None)
    if unit is None:
        return 1.0
    for u in md.unitDefinitions:
        if u.name == unit and u.baseUnit is not None:
            b = u.baseUnit
            if b.m == 1 and not any(getattr(b, k) for k in ("kg", "s", "A", "K", "mol", "cd", "rad")):
                return float(b.factor) * 1000.0
            return 1.0
    return _LENGTH_UNITS_MM.get(unit, 1.0)


class FmuAxis:
    """One machine axis simulated by a Co-Simulation FMU (FMI 2.0 or 3.0).

    Parameters
    ----------
    path : path
        The ``.fmu`` file.
    input : str, optional
        Name of the input that takes the commanded position. Default ``x_ref`` when the FMU has
        it (FMUs exported by vcnc), else its only real input.
    output : str, optional
        Name of the output that gives the measured position. Default ``position`` when present,
        else its only real output.
    start_values : mapping, optional
        Parameter values set before initialisation (name -> value), e.g. ``{"d0": 0.0}``.

    Notes
    -----
    Positions are in mm; an FMU whose input/output are declared in metres (or any length unit
    with a ``BaseUnit``) is converted. Each sample k the axis sets the input to x_r,k, reads the
    output (the measured position at t_k, with direct feedthrough) and advances one sample with
    ``doStep``; the FMU is instantiated afresh for every :meth:`simulate_reference`, at rest at
    the first reference sample. Use as a context manager (or call :meth:`close`) to remove the
    extracted files early; they are removed at garbage collection otherwise.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        *,
        input: str | None = None,
        output: str | None = None,
        start_values: Mapping[str, float] | None = None,
    ) -> None:
        from fmpy import extract, read_model_description

        self.path = Path(path)
        src = str(self.path)
        if not self.path.is_file():
            raise MachineError("no such FMU file", file=src)
        try:
            md = read_model_description(src)
        except Exception as exc:  # noqa: BLE001 - fmpy raises plain Exception for bad files
            raise MachineError(f"not a readable FMU ({exc})", file=src) from exc
        if md.coSimulation is None:
            raise MachineError("the FMU has no Co-Simulation interface (Model Exchange is not supported)", file=src)
        self.model_description = md
        self.fmi_version = 2 if md.fmiVersion == "2.0" else 3
        real = {"Real", "Float64"}
        variables = {v.name: v for v in md.modelVariables}
        self._input = self._pick(variables, input, "input", "x_ref", real, src)
        self._output = self._pick(variables, output, "output", "position", real, src)
        self._in_scale = _mm_per_unit(md, self._input)
        self._out_scale = _mm_per_unit(md, self._output)
        self._start = dict(start_values or {})
        for name in self._start:
            v = variables.get(name)
            if v is None or v.causality not in ("parameter", "input"):
                raise MachineError(f"start value for {name!r}: the FMU has no such parameter or input", file=src)
        self._variables = variables
        self._unzipdir = extract(src)
        self._finalizer = weakref.finalize(self, shutil.rmtree, self._unzipdir, True)
        step = md.defaultExperiment.stepSize if md.defaultExperiment is not None else None
        #: the FMU's default communication step [s] (None when it declares none)
        self.sample_time = float(step) if step is not None else None
        self.messages: list[str] = []

    @staticmethod
    def _pick(variables, name, causality, default, types, src):
        if name is not None:
            v = variables.get(name)
            if v is None or v.causality != causality or v.type not in types:
                choices = [n for n, x in variables.items() if x.causality == causality and x.type in types]
                raise MachineError(f"the FMU has no real {causality} named {name!r}", file=src,
                                   expected=", ".join(choices) or f"an FMU with a real {causality}")
            return v
        v = variables.get(default)
        if v is not None and v.causality == causality and v.type in types:
            return v
        candidates = [x for x in variables.values() if x.causality == causality and x.type in types]
        if len(candidates) == 1:
            return candidates[0]
        names = ", ".join(x.name for x in candidates) or "none"
        raise MachineError(f"cannot tell which {causality} is the axis position (real {causality}s: {names}); "
                           f"name it with {causality}=...", file=src)

    # ------------------------------------------------------------------ life cycle
    def close(self) -> None:
        """Remove the extracted FMU."""
        self._finalizer()

    def __enter__(self) -> FmuAxis:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"FmuAxis({str(self.path)!r}, input={self._input.name!r}, output={self._output.name!r})"

    # ------------------------------------------------------------------ simulation
    def _log(self, status: int, message: str) -> None:
        text = message.decode("utf-8", "replace") if isinstance(message, bytes) else str(message)
        self.messages.append(text)
        if status >= 2:
            log.warning("%s: %s", self.path.name, text)
        else:
            log.debug("%s: %s", self.path.name, text)

    def _open(self):
        md = self.model_description
        kwargs = dict(guid=md.guid, unzipDirectory=self._unzipdir,
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName="vcnc_axis")
        self.messages = []
        if self.fmi_version == 2:
            from fmpy import calloc, free
            from fmpy.fmi2 import (
                FMU2Slave,
                fmi2CallbackAllocateMemoryTYPE,
                fmi2CallbackFreeMemoryTYPE,
                fmi2CallbackFunctions,
                fmi2CallbackLoggerTYPE,
            )

            fmu = FMU2Slave(**kwargs)
            cb = fmi2CallbackFunctions()
            cb.logger = fmi2CallbackLoggerTYPE(lambda env, name, status, cat, msg: self._log(status, msg))
            cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
            cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
            # no fmpy.logging.addLoggerProxy here: it keeps one process-wide logger, which would
            # leave fmpy's default callbacks pointing at this (soon freed) one. Messages arrive
            # unformatted (printf arguments of third-party FMUs are not expanded).
            fmu._vcnc_callbacks = cb  # keep alive as long as the instance
            fmu.instantiate(callbacks=cb)
        else:
            from fmpy.fmi3 import FMU3Slave

            fmu = FMU3Slave(**kwargs)
            fmu.instantiate(logMessage=lambda env, status, cat, msg: self._log(status, msg))
        return fmu

    def _set_start(self, fmu) -> None:
        for name, value in self._start.items():
            v = self._variables[name]
            if v.type in ("Real", "Float64"):
                (fmu.setReal if self.fmi_version == 2 else fmu.setFloat64)([v.valueReference], [float(value)])
            elif v.type in ("Integer", "Int32"):
                (fmu.setInteger if self.fmi_version == 2 else fmu.setInt32)([v.valueReference], [int(value)])
            elif v.type == "Boolean":
                fmu.setBoolean([v.valueReference], [bool(value)])
            else:
                raise MachineError(f"start value for {name!r}: type {v.type} is not supported", file=str(self.path))

    def simulate_reference(self, reference: np.ndarray, sample_time: float) -> np.ndarray:
        """Measured position [mm] for the commanded positions ``reference`` [mm] every ``sample_time`` [s].

        Raises
        ------
        SimulationError
            The FMU refused a call (its own message is included), e.g. a sample time that is not
            a whole multiple of the FMU's.
        """
        from fmpy.fmi1 import FMICallException

        ref = np.ascontiguousarray(reference, dtype=float)
        if ref.ndim != 1 or ref.size == 0:
            raise ValueError(f"reference must be a non-empty 1-D array [mm], got shape {ref.shape}")
        T = float(sample_time)
        if not (np.isfinite(T) and T > 0):
            raise ValueError(f"sample_time [s] must be > 0, got {sample_time!r}")
        fmu = self._open()
        out = np.empty_like(ref)
        k = 0
        try:
            c = fmu.component
            vr_in = (ctypes.c_uint32 * 1)(self._input.valueReference)
            vr_out = (ctypes.c_uint32 * 1)(self._output.valueReference)
            u = (ctypes.c_double * 1)(ref[0] / self._in_scale)
            y = (ctypes.c_double * 1)()
            if self.fmi_version == 2:
                fmu.setupExperiment(startTime=0.0)
                self._set_start(fmu)
                fmu.enterInitializationMode()
                fmu.fmi2SetReal(c, vr_in, 1, u)
                fmu.exitInitializationMode()
                set_u, get_y, step = fmu.fmi2SetReal, fmu.fmi2GetReal, fmu.fmi2DoStep
                for k in range(ref.size):
                    u[0] = ref[k] / self._in_scale
                    set_u(c, vr_in, 1, u)
                    get_y(c, vr_out, 1, y)
                    out[k] = y[0]
                    if k + 1 < ref.size:
                        step(c, k * T, T, 1)
            else:
                self._set_start(fmu)
                fmu.enterInitializationMode(startTime=0.0)
                fmu.fmi3SetFloat64(c, vr_in, 1, u, 1)
                fmu.exitInitializationMode()
                set_u, get_y, step = fmu.fmi3SetFloat64, fmu.fmi3GetFloat64, fmu.fmi3DoStep
                flags = [ctypes.c_bool() for _ in range(3)]
                last = ctypes.c_double()
                refs = [ctypes.byref(f) for f in flags]
                for k in range(ref.size):
                    u[0] = ref[k] / self._in_scale
                    set_u(c, vr_in, 1, u, 1)
                    get_y(c, vr_out, 1, y, 1)
                    out[k] = y[0]
                    if k + 1 < ref.size:
                        step(c, k * T, T, True, refs[0], refs[1], refs[2], ctypes.byref(last))
            fmu.terminate()
        except FMICallException as exc:
            detail = "; ".join(self.messages[-3:])
            raise SimulationError(
                f"{self.path}: {exc} at t = {k * T:g} s" + (f": {detail}" if detail else "")
            ) from exc
        finally:
            try:
                fmu.freeInstance()
            except Exception:  # noqa: BLE001 - nothing more to do for a broken instance
                pass
        return out * self._out_scale
