"""The model file ``vcnc.axis-model/1`` (JSON): writing, reading and validation.

Layout (ARCHITECTURE.md, "Model file")::

    {"format": "vcnc.axis-model/1", "axis": "x", "sample_time": 0.001, "method": "exact",
     "parameters": {"a1":..,"a2":..,"a3":..,"b0":..,"b1":..,"b2":..,"d0":..,"d1":..},
     "poles": {"omega_n_hz":..,"zeta":..,"p_hz":..},
     "bounds": {"p_hz": [lo, hi], "omega_n_hz": [lo, hi], "zeta": [lo, hi]},
     "fit": {"rms_um":..,"max_um":.., ...},
     "effects": [...], "validation": {...}}

``parameters`` are those of Eq. (3.3) in the units of
:data:`identification.reduced_model.PARAMETER_UNITS`; ``bounds`` are the pole bounds of
Eq. (3.8) the solver used (the thesis' defaults, Sec. 4.3: 0.2 Hz to the Nyquist frequency for
p and omega_n, 0.2 to 2.0 for zeta). Extra keys are kept on reading (``units`` is written for
readers). A model with a reference dead time is written as ``vcnc.axis-model/2`` with the extra key
``delay_s`` [s] (:mod:`identification.dead_time`); both formats are read.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

from identification.reduced_model import PARAMETER_NAMES, PARAMETER_UNITS, ReducedAxisModel
from vcnc.core.errors import InputError, ModelFileError
from vcnc.core.io import atomic_path
from vcnc.core.setpoints import AXIS_NAMES

__all__ = ["FORMAT", "FORMAT_DELAY", "FORMATS", "model_to_dict", "model_from_dict", "write_model", "load_model"]

FORMAT = "vcnc.axis-model/1"
#: Format of a model with a reference dead time (``delay_s`` != 0); a ``/1`` reader refuses it
#: rather than predict without the delay.
FORMAT_DELAY = "vcnc.axis-model/2"
FORMATS = (FORMAT, FORMAT_DELAY)


def _plain(obj: Any) -> Any:
    """JSON-safe copy (numpy scalars/arrays to Python, tuples to lists, non-finite to None)."""
    import numpy as np

    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _plain(obj.tolist())
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def model_to_dict(model: ReducedAxisModel) -> dict[str, Any]:
    """The model as a plain ``vcnc.axis-model/1`` dictionary (``/2`` with ``delay_s`` when it has one)."""
    delay = {"delay_s": model.delay_s} if model.delay_s else {}
    return _plain(
        {
            "format": FORMAT_DELAY if model.delay_s else FORMAT,
            **delay,
            "axis": model.axis,
            "sample_time": model.sample_time,
            "method": model.method,
            "parameters": {k: model.parameters[k] for k in PARAMETER_NAMES},
            "units": {**PARAMETER_UNITS, "sample_time": "s"},
            "poles": model.poles,
            "bounds": model.bounds,
            "fit": model.fit,
            "effects": model.effects or (model.effect_records() if hasattr(model, "effect_records") else []),
            "validation": model.validation,
        }
    )


def write_model(model: ReducedAxisModel, path: str | os.PathLike[str]) -> None:
    """Write ``model`` to ``path`` as JSON, atomically."""
    text = json.dumps(model_to_dict(model), indent=2) + "\n"
    with atomic_path(path) as tmp:
        tmp.write_text(text)


def _number(d: dict, key: str, where: str, src: str | None) -> float:
    if key not in d:
        raise ModelFileError(f"key '{where}{key}' missing", file=src)
    v = d[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)):
        raise ModelFileError(f"key '{where}{key}' must be a finite number", file=src, text=repr(v))
    return float(v)


def model_from_dict(d: Any, *, source: str | None = None) -> ReducedAxisModel:
    """Build a model from a ``vcnc.axis-model/1`` dictionary; ModelFileError naming the key at fault."""
    if not isinstance(d, dict):
        raise ModelFileError("a model file must hold a JSON object", file=source)
    fmt = d.get("format")
    if fmt not in FORMATS:
        raise ModelFileError(f"key 'format' must be {FORMAT!r} or {FORMAT_DELAY!r}", file=source, text=repr(fmt))
    delay_s = _number(d, "delay_s", "", source) if fmt == FORMAT_DELAY else 0.0
    axis = d.get("axis", "x")
    if axis not in AXIS_NAMES:
        raise ModelFileError(f"key 'axis' must be one of {', '.join(AXIS_NAMES)}", file=source, text=repr(axis))
    ts = _number(d, "sample_time", "", source)
    if ts <= 0:
        raise ModelFileError("key 'sample_time' [s] must be > 0", file=source, text=repr(ts))
    params = d.get("parameters")
    if not isinstance(params, dict):
        raise ModelFileError("key 'parameters' missing or not an object", file=source)
    values = {k: _number(params, k, "parameters.", source) for k in PARAMETER_NAMES}
    if values["a3"] <= 0:
        raise ModelFileError(
            "key 'parameters.a3' [1/s^3] must be > 0 (a stable closed loop)", file=source, text=repr(values["a3"])
        )
    poles = d.get("poles") or {}
    if not isinstance(poles, dict):
        raise ModelFileError("key 'poles' must be an object", file=source)
    for k in ("omega_n_hz", "zeta", "p_hz"):
        if k in poles:
            _number(poles, k, "poles.", source)
    bounds = d.get("bounds") or {}
    if not isinstance(bounds, dict):
        raise ModelFileError("key 'bounds' must be an object", file=source)
    for k, v in bounds.items():
        if not (isinstance(v, (list, tuple)) and len(v) == 2):
            raise ModelFileError(f"key 'bounds.{k}' must be a pair [lo, hi]", file=source, text=repr(v))
    for key, typ in (("fit", dict), ("effects", list), ("validation", dict)):
        if key in d and not isinstance(d[key], typ):
            raise ModelFileError(f"key '{key}' must be a JSON {'object' if typ is dict else 'array'}", file=source)
    try:
        model = ReducedAxisModel(
            parameters=values,
            sample_time=ts,
            axis=axis,
            method=str(d.get("method", "given")),
            poles={k: float(v) for k, v in poles.items() if k in ("omega_n_hz", "zeta", "p_hz")},
            bounds={k: tuple(float(x) for x in v) for k, v in bounds.items()},
            fit=dict(d.get("fit") or {}),
            effects=list(d.get("effects") or []),
            validation=dict(d.get("validation") or {}),
            delay_s=delay_s,
        )
    except InputError as exc:
        raise ModelFileError(exc.message, file=source) from exc
    if not model.effects:
        return model
    # Effects found by the residual diagnosis: rebuild their elements so the loaded model
    # simulates them (identification.augmented).
    from identification.augmented import from_model

    try:
        return from_model(model)
    except InputError as exc:
        raise ModelFileError(f"key 'effects': {exc.message}", file=source) from exc


def load_model(path: str | os.PathLike[str]) -> ReducedAxisModel:
    """Read a ``vcnc.axis-model/1`` JSON file.

    Raises
    ------
    ModelFileError
        Missing file, invalid JSON (with line and column) or a key that breaks the contract
        (named in the message).
    """
    p = Path(path)
    src = str(p)
    if not p.is_file():
        raise ModelFileError("no such model file", file=src)
    try:
        d = json.loads(p.read_text())
    except UnicodeDecodeError as exc:
        raise ModelFileError("model file is not text (expected JSON)", file=src) from exc
    except json.JSONDecodeError as exc:
        raise ModelFileError(f"invalid JSON: {exc.msg}", file=src, line=exc.lineno, column=exc.colno) from exc
    return model_from_dict(d, source=src)
