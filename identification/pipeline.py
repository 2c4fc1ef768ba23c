"""``identify``: the whole job on one axis — fit the reduced model, then diagnose its residual.

The fit (:func:`identification.identify.fit_reduced_model`) and the diagnosis
(:func:`identification.diagnosis.diagnose`) do not import each other; this module runs one after
the other. The diagnosis runs in the loop's frame (:mod:`identification.loop_frame`: datum offset
removed, reference delayed by ``delay_s`` and through the setpoint filter of
``setpoint_filter_s``, a start in motion dropped), as the fit did; a model with a reference dead
time or a setpoint filter keeps them.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np

from identification.bounds import PoleBounds
from identification.diagnosis import diagnose as diagnose_residual
from identification.ga import GAOptions
from identification.identify import fit_reduced_model
from identification.loop_frame import loop_frame, offset_of
from identification.measured_drift import fit_with_drift
from identification.parallel import serial_blas
from identification.reduced_model import ReducedAxisModel
from identification.regressor import RegressorOptions
from identification.setpoint_filter import filter_reference
from vcnc.core.capture import Capture

__all__ = ["identify", "Identifier"]


def identify(
    capture: Capture,
    *,
    axis: str = "x",
    method: str = "exact",
    bounds: PoleBounds | Mapping | str | None = None,
    refine: str = "output-error",
    diagnose: bool = True,
    regressor_options: RegressorOptions | None = None,
    seed: int = 0,
    ga_options: GAOptions | None = None,
    delay: str | float = "auto",
    setpoint_filter: bool = True,
    drift: str = "auto",
) -> ReducedAxisModel:
    """Identify the model of one axis from a capture: the reduced model (thesis Ch. 3-4) and, by
    default, the physical effects its residual shows.

    Parameters
    ----------
    capture, axis, method, bounds, refine, regressor_options, seed, ga_options, delay, setpoint_filter
        As for :func:`identification.identify.fit_reduced_model`.
    diagnose : bool
        Run the residual diagnosis (default). False returns the fitted reduced model.
    drift : str
        The measured channel's drift against the commanded one (:mod:`identification.measured_drift`),
        estimated after a first fit: ``"auto"`` (default) takes it off and fits again when it is large against
        the prediction error and its removal predicts twice better, ``"remove"`` always, ``"keep"`` never;
        ``fit.drift`` records it either way (:func:`identification.measured_drift.fit_with_drift`).

    Returns
    -------
    ReducedAxisModel
        The fitted model; after the diagnosis an :class:`identification.augmented.AugmentedAxisModel`
        when effects were added, with ``effects`` and ``validation`` filled in.
    """
    def fit(capture: Capture) -> ReducedAxisModel:
        return fit_reduced_model(capture, axis=axis, method=method, bounds=bounds, refine=refine,
                                 regressor_options=regressor_options, seed=seed, ga_options=ga_options, delay=delay,
                                 setpoint_filter=setpoint_filter)

    with serial_blas():  # tall, narrow least squares: one BLAS thread is faster (identification.parallel)
        capture, model = fit_with_drift(capture, axis, fit, drift)
    if not diagnose:
        return model
    in_loop, _ = loop_frame(capture, axis, offset_mm=offset_of(model.fit),
                            delay_samples=model.delay_s / model.sample_time)
    if not (model.delay_s or model.setpoint_filter_s):
        return diagnose_residual(in_loop, model, axis=axis)
    if model.setpoint_filter_s:
        i = in_loop.axis_index(axis)
        reference = np.array(in_loop.reference, dtype=float)
        reference[:, i] = filter_reference(reference[:, i], model.setpoint_filter_s / model.sample_time)
        in_loop = dataclasses.replace(in_loop, reference=reference)
    diagnosed = diagnose_residual(in_loop, dataclasses.replace(model, delay_s=0.0, setpoint_filter_s=0.0), axis=axis)
    return dataclasses.replace(diagnosed, delay_s=model.delay_s, setpoint_filter_s=model.setpoint_filter_s)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Identifier:
    """Estimator form of :func:`identify`: configure once, ``fit(capture)`` per axis.

    Attributes mirror the keyword arguments of :func:`identify`.
    """

    method: str = "exact"
    bounds: PoleBounds | None = None
    refine: str = "output-error"
    diagnose: bool = True
    regressor_options: RegressorOptions | None = None
    seed: int = 0
    ga_options: GAOptions | None = None
    delay: str | float = "auto"
    setpoint_filter: bool = True
    drift: str = "auto"

    def fit(self, capture: Capture, axis: str = "x") -> ReducedAxisModel:
        """The fitted model of ``axis``."""
        return identify(
            capture,
            axis=axis,
            method=self.method,
            bounds=self.bounds,
            refine=self.refine,
            diagnose=self.diagnose,
            regressor_options=self.regressor_options,
            seed=self.seed,
            ga_options=self.ga_options,
            delay=self.delay,
            setpoint_filter=self.setpoint_filter,
            drift=self.drift,
        )
