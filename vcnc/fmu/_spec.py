"""What gets exported: the model's parameters and the effects the FMU represents exactly.

An FMU represents an effect only when its binary reproduces ``model.simulate()`` of the
:class:`identification.augmented.AugmentedAxisModel` with that effect (to
:data:`vcnc.fmu.CHECK_TOLERANCE_MM`, checked at every export); any other effect makes the export
fail with an :class:`~vcnc.errors.ExportError` naming it.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from typing import Any

from drives.effects import EFFECTS as EFFECT_REGISTRY
from vcnc.core.axes import PARAMETER_NAMES
from vcnc.core.errors import ExportError, InputError, ModelFileError
from vcnc.fmu._variables import EFFECT_VARIABLES, MAX_DELAY, MAX_HARMONICS, MAX_REF_DELAY, Variable, variables

__all__ = ["ExportSpec", "REPRESENTABLE_EFFECTS", "export_spec"]


#: effect name -> how the FMU represents it (its FMU parameters): every effect of the registry
REPRESENTABLE_EFFECTS: dict[str, str] = {name: info.fmu for name, info in EFFECT_REGISTRY.items()}


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
    elements : tuple
        The effects (``identification.effects`` instances) of the model, all representable.
    viscous_rate : float
        Plant viscous rate c [1/s] of the split form (used when an element is present or ``form`` is split).
    form : str
        The model's base form (:data:`identification.augmented.FORMS`): ``"split"`` exports the split loop even
        without an element (its Coulomb friction holds a stopped axis), as an element's split form is exported.
    delay_s : float
        Reference dead time [s] (>= 0, the model's ``delay_s``): the loop runs on ``x_ref`` delayed
        by it; the FMU's parameter ``reference_delay_s`` (present only when it is not zero).
    setpoint_filter_s : float
        Setpoint filter [s] (>= 0, the model's ``setpoint_filter_s``): the loop runs on the moving
        average of the delayed ``x_ref`` over it; the FMU's parameter ``setpoint_filter_s`` (present
        only when it is not zero).
    """

    axis: str
    sample_time: float
    parameters: dict
    elements: tuple = ()
    viscous_rate: float = 0.0
    delay_s: float = 0.0
    setpoint_filter_s: float = 0.0
    form: str = "exact"

    @property
    def model_identifier(self) -> str:
        return f"vcnc_axis_{self.axis}"

    @property
    def structured(self) -> bool:
        """True when the FMU runs the split (plant + sampled controller) form: the model's base form is split, or
        an element needs it (the rule of :attr:`identification.augmented.AugmentedAxisModel.structured`)."""
        return self.model().structured if self.elements or self.form != "exact" else False

    def effect(self, name: str) -> Any:
        """The element called ``name``, or None."""
        return next((e for e in self.elements if e.NAME == name), None)

    @property
    def effect_names(self) -> list[str]:
        """Names of the exported effects, in the model's order (for reports)."""
        return [e.NAME for e in self.elements]

    @property
    def harmonics(self) -> dict[str, int]:
        """Effect name -> Fourier harmonics (0 for the non-periodic ones), in the FMU's order."""
        return {name: int(getattr(self.effect(name), "harmonics", 0)) for name in REPRESENTABLE_EFFECTS
                if self.effect(name) is not None}

    @property
    def variables(self) -> tuple[Variable, ...]:
        """The FMU's variables."""
        return variables(self.harmonics, structured=self.structured, reference_delay=self.delay_s != 0.0,
                         setpoint_filter=self.setpoint_filter_s != 0.0)

    def model(self) -> Any:
        """The Python model the FMU reproduces (its ``simulate`` is the export check's oracle)."""
        from identification import ReducedAxisModel
        from identification.augmented import augment

        base = ReducedAxisModel(parameters=dict(self.parameters), sample_time=self.sample_time, axis=self.axis,
                                delay_s=self.delay_s, setpoint_filter_s=self.setpoint_filter_s)
        if not self.elements and self.form == "exact":
            return base
        return augment(base, list(self.elements), viscous_rate=self.viscous_rate, form=self.form)

    def start(self) -> dict[str, float | int]:
        """Start value of every variable of the FMU with one (name -> value)."""
        out: dict[str, float | int] = {
            "x_ref": 0.0,
            "w_ext": 0.0,
            **{k: float(self.parameters[k]) for k in PARAMETER_NAMES},
            "sample_time": float(self.sample_time),
        }
        for e in self.elements:
            name = e.NAME
            if name == "friction_stribeck":
                out.update(stribeck_velocity=float(e.velocity), stribeck_excess_positive=float(e.excess_positive),
                           stribeck_excess_negative=float(e.excess_negative))
            elif name == "friction_viscous_asymmetric":
                out["viscous_asymmetry"] = float(e.coefficient)
            elif name in ("position_periodic", "time_periodic"):
                if name == "position_periodic":
                    out["position_period"] = float(e.period)
                else:
                    out.update(time_period=float(e.period), time_mean=float(e.mean))
                for h, (s, c) in enumerate(e.coefficients, start=1):
                    out[f"{name}_sin_{h}"] = float(s)
                    out[f"{name}_cos_{h}"] = float(c)
            elif name == "drift":
                out["drift_rate"] = float(e.rate)
            elif name == "delay":
                out["delay_samples"] = int(e.samples)
            elif name == "saturation":
                out["saturation_limit"] = float(e.limit)
            elif name == "backlash":
                out["backlash_width"] = float(e.width)
            elif name == "resonance":
                out.update(resonance_frequency=float(e.frequency), resonance_damping=float(e.damping),
                           resonance_table_fraction=float(e.table_fraction))
        if self.structured:
            out["plant_viscous_rate"] = float(self.viscous_rate)
        if self.delay_s != 0.0:
            out["reference_delay_s"] = float(self.delay_s)
        if self.setpoint_filter_s != 0.0:
            out["setpoint_filter_s"] = float(self.setpoint_filter_s)
        return out


def _load(model: Any):
    """A ReducedAxisModel (an AugmentedAxisModel when it has effects) from a path, a dict or the model."""
    from identification import load_model
    from identification.model_file import model_from_dict

    if isinstance(model, (str, os.PathLike)):
        return load_model(model)
    if isinstance(model, Mapping):
        return model_from_dict(dict(model))
    if hasattr(model, "parameters") and hasattr(model, "sample_time"):
        return model
    raise TypeError(f"model must be a model file path, a model dictionary or a ReducedAxisModel, got {type(model)}")


def _check_values(e: Any, source: str | None) -> None:
    """Effect parameters the Python model accepts but cannot simulate (NaN) or the FMU cannot hold."""
    name = e.NAME
    if name == "time_periodic" and getattr(e, "window", None) is not None:
        raise ExportError(f"effect 'time_periodic' acts only in the window {list(e.window)} s (with its amplitude "
                          "envelope); the FMU's load has no window yet, so it cannot be exported without changing "
                          "the model")
    if name == "time_periodic" and not e.period > 0:
        raise ModelFileError("effect 'time_periodic' parameter 'period_s' must be > 0", file=source,
                             text=repr(e.period))
    numbers = {k: v for k, v in e.parameters().items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    for k, v in numbers.items():
        if not math.isfinite(float(v)):
            raise ModelFileError(f"effect '{name}' parameter '{k}' must be a finite number", file=source, text=repr(v))
    if name in ("position_periodic", "time_periodic"):
        coef = [float(x) for pair in e.coefficients for x in pair]
        if not all(math.isfinite(x) for x in coef):
            raise ModelFileError(f"effect '{name}' coefficients must be finite numbers", file=source)
        if len(e.coefficients) > MAX_HARMONICS:
            raise ExportError(f"effect '{name}' has {len(e.coefficients)} harmonics; an FMU holds at most "
                              f"{MAX_HARMONICS}")
    if name == "delay" and not 0 <= e.samples <= MAX_DELAY:
        raise ModelFileError(f"effect 'delay' parameter 'samples' must be a whole number in [0, {MAX_DELAY}]",
                             file=source, text=repr(e.samples))
    if name == "resonance" and e.frequency > 0 and not 0 < e.table_fraction < 1:
        raise ModelFileError("effect 'resonance' parameter 'table_fraction' must be in (0, 1)", file=source,
                             text=repr(e.table_fraction))


def export_spec(model: Any) -> ExportSpec:
    """What :func:`vcnc.fmu.export_fmu` exports for ``model``.

    Raises
    ------
    ModelFileError
        A model file that breaks the ``vcnc.axis-model/1`` contract (also a malformed effect).
    ExportError
        Effects the FMU cannot represent exactly (named in the message, with the representable ones);
        a negative (non-causal) or too long reference dead time ``delay_s``, or too long a setpoint
        filter ``setpoint_filter_s``.
    """
    from identification.augmented import AugmentedAxisModel, from_model
    from identification.effects import EFFECTS

    m = _load(model)
    source = str(model) if isinstance(model, (str, os.PathLike)) else None
    if not isinstance(m, AugmentedAxisModel):
        try:
            m = from_model(m)  # a model object carrying effect records
        except InputError as exc:
            raise ModelFileError(f"key 'effects': {exc.message}", file=source) from exc
    elements = tuple(getattr(m, "elements", ()) or ())
    unsupported, seen, duplicated = [], set(), set()
    for e in elements:
        name = getattr(e, "NAME", None) or type(e).__name__
        if name not in REPRESENTABLE_EFFECTS or type(e) is not EFFECTS.get(name):
            unsupported.append(name)
        elif name in seen:
            duplicated.add(name)
        seen.add(name)
    where = f" of {source}" if source else ""
    if unsupported:
        raise ExportError(
            f"the FMU cannot represent the effect(s) {', '.join(sorted(set(unsupported)))}{where}; "
            f"representable: {', '.join(REPRESENTABLE_EFFECTS)} (or export the model without those effects)"
        )
    if duplicated:
        raise ExportError(f"the effect(s) {', '.join(sorted(duplicated))}{where} appear more than once; an FMU "
                          "represents each effect at most once")
    for e in elements:
        _check_values(e, source)
    delay_s = float(getattr(m, "delay_s", 0.0) or 0.0)
    if not math.isfinite(delay_s) or delay_s < 0.0:
        raise ExportError(f"the reference dead time delay_s = {delay_s!r} s{where} is negative (the recorded "
                          "reference lags the loop): the FMU would need future inputs, so it cannot be exported")
    if delay_s / float(m.sample_time) > MAX_REF_DELAY:
        raise ExportError(f"the reference dead time delay_s = {delay_s!r} s{where} is longer than an FMU holds "
                          f"({MAX_REF_DELAY} samples of {float(m.sample_time)!r} s)")
    filter_s = float(getattr(m, "setpoint_filter_s", 0.0) or 0.0)
    if not (math.isfinite(filter_s) and 0.0 <= filter_s / float(m.sample_time) <= MAX_REF_DELAY):
        raise ExportError(f"the setpoint filter setpoint_filter_s = {filter_s!r} s{where} must be in [0, "
                          f"{MAX_REF_DELAY} samples of {float(m.sample_time)!r} s]")
    assert set(EFFECT_VARIABLES) == set(REPRESENTABLE_EFFECTS)
    return ExportSpec(
        axis=str(getattr(m, "axis", "x")),
        sample_time=float(m.sample_time),
        parameters={k: float(m.parameters[k]) for k in PARAMETER_NAMES},
        elements=elements,
        viscous_rate=float(getattr(m, "viscous_rate", 0.0)),
        delay_s=delay_s,
        setpoint_filter_s=filter_s,
        form=str(getattr(m, "form", "exact")),
    )
