"""What gets exported: the model's parameters and the effects the FMU can represent."""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from typing import Any

from vcnc.errors import ExportError, ModelFileError
from vcnc.fmu._variables import MAX_DELAY

__all__ = ["ExportSpec", "REPRESENTABLE_EFFECTS", "export_spec"]

PARAMETER_NAMES = ("a1", "a2", "a3", "b0", "b1", "b2", "d0", "d1")

#: effect name -> (its parameter in the model file, FMU parameter, meaning in the FMU)
REPRESENTABLE_EFFECTS: dict[str, tuple[str, str, str]] = {
    "delay": ("samples", "delay_samples", "transport delay of the command by whole samples"),
    "backlash": ("width", "backlash", "play operator of total width [mm] on the measured position, centred at rest"),
}


@dataclasses.dataclass(frozen=True, kw_only=True)
class ExportSpec:
    """The content of one exported FMU.

    Attributes
    ----------
    axis : str
        Axis name (part of the model identifier).
    sample_time : float
        Sample time [s]; the FMU's ``DefaultExperiment`` step size.
    parameters : dict
        a1..d1 of Eq. (3.3) (units of ``identification.reduced_model.PARAMETER_UNITS``).
    backlash : float
        Effect ``backlash``: total lost motion [mm]; 0 for none.
    delay_samples : int
        Effect ``delay``: command delay [samples]; 0 for none.
    """

    axis: str
    sample_time: float
    parameters: dict
    backlash: float = 0.0
    delay_samples: int = 0

    @property
    def model_identifier(self) -> str:
        return f"vcnc_axis_{self.axis}"

    def start(self) -> dict[str, float | int]:
        """Start value of every variable with one (name -> value)."""
        return {
            "x_ref": 0.0,
            "w_ext": 0.0,
            **{k: float(self.parameters[k]) for k in PARAMETER_NAMES},
            "sample_time": float(self.sample_time),
            "backlash": float(self.backlash),
            "delay_samples": int(self.delay_samples),
        }


def _load(model: Any):
    """A ReducedAxisModel from a path, a model-file dictionary or the model itself."""
    from identification import load_model
    from identification.model_file import model_from_dict

    if isinstance(model, (str, os.PathLike)):
        return load_model(model)
    if isinstance(model, Mapping):
        return model_from_dict(dict(model))
    if hasattr(model, "parameters") and hasattr(model, "sample_time"):
        return model
    raise TypeError(f"model must be a model file path, a model dictionary or a ReducedAxisModel, got {type(model)}")


def _effect_value(effect: Mapping, name: str, key: str) -> float:
    params = effect.get("parameters") or {}
    if not isinstance(params, Mapping) or key not in params:
        raise ModelFileError(f"effect '{name}' needs parameter '{key}'", text=repr(effect.get("parameters")))
    value = params[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(float(value)):
        raise ModelFileError(f"effect '{name}' parameter '{key}' must be a finite number", text=repr(value))
    return float(value)


def export_spec(model: Any) -> ExportSpec:
    """What :func:`vcnc.fmu.export_fmu` exports for ``model``.

    Raises
    ------
    ModelFileError
        A model file that breaks the ``vcnc.axis-model/1`` contract (also a malformed effect).
    ExportError
        Effects the FMU cannot represent (named in the message).
    """
    m = _load(model)
    source = str(model) if isinstance(model, (str, os.PathLike)) else None
    values: dict[str, float | int] = {"backlash": 0.0, "delay_samples": 0}
    unsupported = []
    for effect in list(getattr(m, "effects", None) or []):
        if not isinstance(effect, Mapping) or not isinstance(effect.get("name"), str):
            raise ModelFileError("each entry of 'effects' must be an object with a 'name'", file=source,
                                 text=repr(effect))
        name = effect["name"]
        if name not in REPRESENTABLE_EFFECTS:
            unsupported.append(name)
            continue
        key, target, _ = REPRESENTABLE_EFFECTS[name]
        try:
            value = _effect_value(effect, name, key)
        except ModelFileError as exc:
            raise exc.at(file=source) from None
        if name == "delay":
            if value != int(value) or not 0 <= value <= MAX_DELAY:
                raise ModelFileError(f"effect 'delay' parameter 'samples' must be a whole number in [0, {MAX_DELAY}]",
                                     file=source, text=repr(value))
            values[target] = int(value)
        else:
            if value < 0:
                raise ModelFileError("effect 'backlash' parameter 'width' [mm] must be >= 0", file=source,
                                     text=repr(value))
            values[target] = value
    if unsupported:
        raise ExportError(
            f"the FMU cannot represent the effect(s) {', '.join(sorted(set(unsupported)))}"
            + (f" of {source}" if source else "")
            + f"; representable: {', '.join(REPRESENTABLE_EFFECTS)} (or export the model without those effects)"
        )
    return ExportSpec(
        axis=str(getattr(m, "axis", "x")),
        sample_time=float(m.sample_time),
        parameters={k: float(m.parameters[k]) for k in PARAMETER_NAMES},
        backlash=float(values["backlash"]),
        delay_samples=int(values["delay_samples"]),
    )
