"""The model file format ``vcnc.axis-model/1`` (``/2`` with a reference dead time): the model as a
plain dictionary, and writing it.

Layout (ARCHITECTURE.md, "Model file")::

    {"format": "vcnc.axis-model/1", "axis": "x", "sample_time": 0.001, "method": "exact",
     "parameters": {"a1":..,"a2":..,"a3":..,"b0":..,"b1":..,"b2":..,"d0":..,"d1":..},
     "poles": {"omega_n_hz":..,"zeta":..,"p_hz":..},
     "bounds": {"p_hz": [lo, hi], "omega_n_hz": [lo, hi], "zeta": [lo, hi]},
     "fit": {"rms_um":..,"max_um":.., ...},
     "effects": [...], "validation": {...}}

``parameters`` are those of Eq. (3.3) in the units of
:data:`identification.parameters.PARAMETER_UNITS`; ``bounds`` are the pole bounds of
Eq. (3.8) the solver used (the thesis' defaults, Sec. 4.3: 0.2 Hz to the Nyquist frequency for
p and omega_n, 0.2 to 2.0 for zeta). ``units`` is written for readers. A model with a reference
dead time is written as ``vcnc.axis-model/2`` with the extra key ``delay_s`` [s]
(:mod:`identification.dead_time`); a model with a setpoint filter as ``vcnc.axis-model/3`` with
the extra keys ``delay_s`` [s] (0 for none) and ``setpoint_filter_s`` [s] (> 0, the moving
average of :mod:`identification.setpoint_filter`); a model whose base loop is the split form
(:attr:`identification.augmented.AugmentedAxisModel.form`, its Coulomb friction holding a stopped axis) as
``vcnc.axis-model/4`` with the keys of ``/3`` and ``"form": "split"`` and ``plant_viscous_rate_1_s`` [1/s] (the
plant viscous rate c of the split form). Each is written only when the model needs it,
so that an older reader refuses a model it would predict wrongly, and reads every other one (a ``form`` absent
is the exact form, as every earlier file means).
Reading and validation: :mod:`identification.model_file`.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any

from identification.parameters import PARAMETER_NAMES, PARAMETER_UNITS
from vcnc.core.io import atomic_path
from vcnc.core.jsonsafe import plain

if TYPE_CHECKING:
    from identification.reduced_model import ReducedAxisModel

__all__ = ["FORMAT", "FORMAT_DELAY", "FORMAT_FILTER", "FORMAT_FORM", "FORMATS", "model_to_dict", "write_model"]

FORMAT = "vcnc.axis-model/1"
#: Format of a model with a reference dead time (``delay_s`` != 0); a ``/1`` reader refuses it
#: rather than predict without the delay.
FORMAT_DELAY = "vcnc.axis-model/2"
#: Format of a model with a setpoint filter (``setpoint_filter_s`` != 0); ``/1`` and ``/2`` readers refuse it.
FORMAT_FILTER = "vcnc.axis-model/3"
#: Format of a model in the split base form (``form`` "split", identstick40); ``/1`` to ``/3`` readers refuse it
#: rather than predict it in the exact form.
FORMAT_FORM = "vcnc.axis-model/4"
FORMATS = (FORMAT, FORMAT_DELAY, FORMAT_FILTER, FORMAT_FORM)


def model_to_dict(model: ReducedAxisModel) -> dict[str, Any]:
    """The model as a plain ``vcnc.axis-model/1`` dictionary (``/2`` with ``delay_s`` when it has one,
    ``/3`` with ``delay_s`` and ``setpoint_filter_s`` when it has a setpoint filter, ``/4`` with those, ``form`` and
    ``plant_viscous_rate_1_s`` when its base form is split)."""
    filter_s = getattr(model, "setpoint_filter_s", 0.0)
    if getattr(model, "form", "exact") != "exact":
        fmt, extra = FORMAT_FORM, {"delay_s": model.delay_s, "setpoint_filter_s": filter_s, "form": model.form,
                                   "plant_viscous_rate_1_s": model.viscous_rate}
    elif filter_s:
        fmt, extra = FORMAT_FILTER, {"delay_s": model.delay_s, "setpoint_filter_s": filter_s}
    elif model.delay_s:
        fmt, extra = FORMAT_DELAY, {"delay_s": model.delay_s}
    else:
        fmt, extra = FORMAT, {}
    return plain(
        {
            "format": fmt,
            **extra,
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
