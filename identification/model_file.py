"""Reading the model file (``vcnc.axis-model/1`` to ``/4``, :mod:`identification.model_format`):
validation with errors naming the key at fault, and the rebuilt model — an
:class:`identification.augmented.AugmentedAxisModel` when the file lists effects, so that the loaded
model simulates them. Extra keys are kept on reading.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

from identification.augmented import FORMS, augment, from_model
from identification.model_format import FORMAT_DELAY, FORMAT_FILTER, FORMAT_FORM, FORMATS
from identification.parameters import PARAMETER_NAMES
from identification.reduced_model import ReducedAxisModel
from vcnc.core.axes import AXIS_NAMES
from vcnc.core.errors import InputError, ModelFileError

__all__ = ["model_from_dict", "load_model"]


def _number(d: dict, key: str, where: str, src: str | None) -> float:
    if key not in d:
        raise ModelFileError(f"key '{where}{key}' missing", file=src)
    v = d[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)):
        raise ModelFileError(f"key '{where}{key}' must be a finite number", file=src, text=repr(v))
    return float(v)


def model_from_dict(d: Any, *, source: str | None = None) -> ReducedAxisModel:
    """Build a model from a ``vcnc.axis-model/1`` to ``/4`` dictionary; ModelFileError naming the key at fault."""
    if not isinstance(d, dict):
        raise ModelFileError("a model file must hold a JSON object", file=source)
    fmt = d.get("format")
    if fmt not in FORMATS:
        raise ModelFileError(f"key 'format' must be one of {', '.join(map(repr, FORMATS))}", file=source,
                             text=repr(fmt))
    delay_s = _number(d, "delay_s", "", source) if fmt in (FORMAT_DELAY, FORMAT_FILTER, FORMAT_FORM) else 0.0
    filter_s = _number(d, "setpoint_filter_s", "", source) if fmt in (FORMAT_FILTER, FORMAT_FORM) else 0.0
    form, viscous_rate = _form(d, source)
    if filter_s < 0.0:
        raise ModelFileError("key 'setpoint_filter_s' [s] must be >= 0", file=source, text=repr(filter_s))
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
            setpoint_filter_s=filter_s,
        )
    except InputError as exc:
        raise ModelFileError(exc.message, file=source) from exc
    if model.effects:
        # Effects found by the residual diagnosis: rebuild their elements so the loaded model
        # simulates them (identification.augmented).
        try:
            model = from_model(model)
        except InputError as exc:
            raise ModelFileError(f"key 'effects': {exc.message}", file=source) from exc
    if form == "exact":
        return model
    return augment(model, getattr(model, "elements", ()), viscous_rate=viscous_rate, form=form)


def _form(d: dict, source: str | None) -> tuple[str, float]:
    """``(form, plant viscous rate [1/s])`` of the model file ``d``: key ``form`` (absent: the exact form, as every
    file before ``vcnc.axis-model/4`` means), and ``plant_viscous_rate_1_s`` with the split form."""
    form = d.get("form", "exact")
    if form not in FORMS:
        raise ModelFileError(f"key 'form' must be one of {', '.join(map(repr, FORMS))}", file=source,
                             text=repr(form))
    if form == "exact":
        return form, 0.0
    c = _number(d, "plant_viscous_rate_1_s", "", source)
    if c < 0.0:
        raise ModelFileError("key 'plant_viscous_rate_1_s' [1/s] must be >= 0", file=source, text=repr(c))
    return form, c


def load_model(path: str | os.PathLike[str]) -> ReducedAxisModel:
    """Read a ``vcnc.axis-model/1`` to ``/4`` JSON file.

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
