"""vcnc: an open virtual CNC.

The everyday API (ARCHITECTURE.md, "Python facade")::

    import vcnc
    machine = vcnc.machine("fadal-pid")            # a built-in name or a TOML file
    program = vcnc.load_program("part.nc")         # ISO or Heidenhain, by content
    setpoints = vcnc.interpolate(program, machine) # the machine's axis limits, Ts
    capture = machine.simulate(setpoints)          # a Capture (also vcnc.read_capture(path))
    model = vcnc.identify(capture, axis="x")       # fitted reduced model with its diagnosis

Names are imported lazily so ``import vcnc`` stays fast and each part loads only when used.
"""

from __future__ import annotations

import importlib
from typing import Any

from vcnc.capture import Capture, read_capture
from vcnc.errors import *  # noqa: F403 - every exception type, listed once in vcnc.core.errors
from vcnc.errors import __all__ as _ERRORS
from vcnc.setpoints import Setpoints

__version__ = "0.1.0"

# public name -> "module:attribute", resolved on first use
_LAZY: dict[str, str] = {
    "load_program": "interpolators:load_program",
    "parse_program": "interpolators:parse_program",
    "interpolate": "vcnc.facade:interpolate",
    "machine": "vcnc.engine.machine:load_machine",
    "Machine": "vcnc.engine.machine:Machine",
    "machines": "vcnc.engine.machine:builtin_machines",
    "identify": "identification:identify",
    "ReducedAxisModel": "identification:ReducedAxisModel",
    "load_model": "identification:load_model",
    "compare": "vcnc.contour_compare:compare",
    "ContourReport": "vcnc.contour_compare:ContourReport",
    "contour_error": "vcnc.contour:contour_error",
    "export_fmu": "vcnc.fmu:export_fmu",
    "sweep": "vcnc.sweeps:sweep",
}

__all__ = [
    "Capture",
    "Setpoints",
    "read_capture",
    *_ERRORS,
    *_LAZY,
]


def __getattr__(name: str) -> Any:
    target = _LAZY.get(name)
    if target is None:
        raise AttributeError(f"module 'vcnc' has no attribute {name!r}")
    modname, _, attr = target.partition(":")
    module = importlib.import_module(modname)
    value = getattr(module, attr) if attr else module
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
