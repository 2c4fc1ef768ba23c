"""One sweep point, computed on a worker: build the machine variant, simulate, measure.

:func:`run_point` never raises: a point that fails is returned with ``status = "error"`` and the
error text, so one bad point never stops a sweep.
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import math
import time
import traceback
from collections.abc import Mapping
from typing import Any

from vcnc.core.errors import InputError

__all__ = ["run_point", "machine_variant", "program_text", "FEEDBACK_GAINS"]

log = logging.getLogger(__name__)

#: controller fields scaled by the ``gain`` parameter (the feedback gains of PID and P-PI laws)
FEEDBACK_GAINS: tuple[str, ...] = ("kp", "ki", "kd")


@functools.lru_cache(maxsize=16)
def _base_machine(ref: str, digest: str | None):  # noqa: ANN202 - vcnc.engine.machine.Machine, imported lazily
    # ``digest`` (of a machine file's content) is part of the key: a long-lived worker must not
    # reuse a machine whose file has changed since
    from vcnc.engine.machine import load_machine

    return load_machine(ref)


def machine_variant(task: Mapping[str, Any]):  # noqa: ANN201 - Machine
    """The point's machine: the base machine with gain, noise and effect applied.

    ``gain`` scales the feedback gains (:data:`FEEDBACK_GAINS`) of every axis' controller;
    ``noise`` [mm] replaces the measurement noise of every axis (0 removes it); ``effect`` is added
    to the sweep axis at ``magnitude`` (see :data:`vcnc.sweeps.spec.MAGNITUDE_KEYS`).
    """
    from vcnc.engine.axis import AxisDefinition
    from vcnc.sweeps.spec import MAGNITUDE_KEYS

    m = _base_machine(task["machine_ref"], task.get("machine_digest"))
    gain = task.get("gain", 1.0)
    noise = task.get("noise")
    for a in m.axes:
        ax = m.axis(a)
        if not isinstance(ax, AxisDefinition):
            if gain != 1.0 or noise is not None:
                raise InputError(f"axis {a} of machine {m.name!r} is external: gain and noise cannot be changed")
            continue
        changes: dict[str, Any] = {}
        if gain != 1.0:
            fields = {f.name for f in dataclasses.fields(ax.controller)} & set(FEEDBACK_GAINS)
            if not fields:
                raise InputError(
                    f"gain: controller {type(ax.controller).__name__} of axis {a} has no feedback gains "
                    f"{'/'.join(FEEDBACK_GAINS)} to scale"
                )
            changes["controller"] = dataclasses.replace(
                ax.controller, **{f: getattr(ax.controller, f) * gain for f in fields}
            )
        if noise is not None:
            changes["noise"] = noise if noise > 0 else None
        if changes:
            m = m.with_axis_options(a, **changes)
    effect = task.get("effect", "none")
    if effect != "none":
        mag = task.get("magnitude")
        m = m.with_effect(task["axis"], effect, None if mag is None else {MAGNITUDE_KEYS[effect]: mag})
    return m


def program_text(task: Mapping[str, Any]) -> str:
    """G-code of the point's toolpath (generated, or the program file's text)."""
    import toolpaths

    g = task["geometry"]
    kind = task["toolpath"]
    if task.get("program_text") is not None:
        return task["program_text"]
    if kind == "circle":
        return toolpaths.circle(g["radius"], task["feed"])
    if kind == "diamond":
        return toolpaths.diamond(g["side"], task["feed"])
    if kind == "identification":
        return toolpaths.random_moves(int(g["moves"]), g["span"], task["feed"], seed=0, axes=(task["axis"],))
    raise InputError(f"unknown toolpath {kind!r}")


@functools.lru_cache(maxsize=64)
def _setpoints(text: str, source: str, limits_key: tuple, sample_time: float, profile: str):  # noqa: ANN202
    import interpolators

    program = interpolators.parse_program(text, source=source)
    return interpolators.interpolate(program, limits=dict(limits_key), sample_time=sample_time, profile=profile)


def _worker_name() -> str:
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return "local"


def run_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """Compute one point; returns its result row (parameters, status, metrics, timings).

    Metrics: ``tracking_max_um``/``tracking_rms_um`` (worst axis), ``contour_max_um``/
    ``contour_rms_um`` (two or more moving axes), ``samples``; with ``outputs.identify``:
    ``ident_fit_rms_um`` (model prediction of the capture), ``ident_pole_error_pct`` (largest
    relative error of omega_n, zeta, p against the true loop), ``ident_param_error_pct`` (largest
    relative error over the non-zero true parameters a1..d1 of Eq. 3.3); with ``outputs.diagnose``:
    ``diag_effects`` (names found) and ``diag_hit`` (the injected effect was named; for
    ``effect = "none"``: nothing was named). Timings ``t_simulate_s``, ``t_identify_s``,
    ``t_point_s`` [s].
    """
    t0 = time.perf_counter()
    row: dict[str, Any] = {"id": task["id"], "status": "ok", "error": None, "worker": _worker_name()}
    try:
        row.update(_measure(task))
    except Exception as exc:  # noqa: BLE001 - a failing point is a result, never the end of the sweep
        row["status"] = "error"
        row["error"] = f"{type(exc).__name__}: {exc}"
        log.debug("point %s failed:\n%s", task["id"], traceback.format_exc())
    row["t_point_s"] = time.perf_counter() - t0
    return row


def _measure(task: Mapping[str, Any]) -> dict[str, Any]:
    import numpy as np

    from vcnc.contour import contour_metrics

    out: dict[str, Any] = {}
    t0 = time.perf_counter()
    m = machine_variant(task)
    text = program_text(task)
    sp = _setpoints(text, task["toolpath"], tuple(sorted(m.limits.items())), m.sample_time, task["profile"])
    cap = m.simulate(sp, seed=task["seed"])
    out["t_simulate_s"] = time.perf_counter() - t0
    e_um = np.abs(cap.reference - cap.measured) * 1e3
    out["samples"] = len(cap)
    out["tracking_max_um"] = float(np.max(e_um))
    out["tracking_rms_um"] = float(np.max(np.sqrt(np.mean(e_um**2, axis=0))))
    contour = contour_metrics(cap)
    if contour is not None:
        out["contour_max_um"] = contour["max_um"]
        out["contour_rms_um"] = contour["rms_um"]
    if task["outputs"].get("identify"):
        out.update(_identify(task, m, cap))
    return out


def _identify(task: Mapping[str, Any], machine: Any, capture: Any) -> dict[str, Any]:
    import identification
    from identification.poles import poles_from_denominator

    axis = task["axis"]
    outputs = task["outputs"]
    t0 = time.perf_counter()
    model = identification.identify(
        capture, axis=axis, method=outputs.get("method", "exact"), diagnose=bool(outputs.get("diagnose"))
    )
    out: dict[str, Any] = {"t_identify_s": time.perf_counter() - t0, "ident_fit_rms_um": model.fit.get("rms_um")}
    try:
        truth = machine.axis(axis).reduced_parameters()
    except (InputError, AttributeError) as exc:  # discrete laws and external axes have no Eq. 3.3 truth
        log.debug("no true reduced parameters for %s: %s", axis, exc)
    else:
        rel = [abs(model.parameters[k] - v) / abs(v) for k, v in truth.items() if abs(v) > 1e-12]
        out["ident_param_error_pct"] = 100.0 * max(rel) if rel else None
        true_poles = poles_from_denominator(truth["a1"], truth["a2"], truth["a3"])
        if true_poles and model.poles:
            errs = [abs(model.poles[k] - v) / abs(v) for k, v in true_poles.items()
                    if k in model.poles and v and math.isfinite(v)]
            out["ident_pole_error_pct"] = 100.0 * max(errs) if errs else None
    if outputs.get("diagnose"):
        names = [e["name"] if isinstance(e, Mapping) else getattr(e, "name", str(e)) for e in model.effects]
        out["diag_effects"] = ",".join(names)
        effect = task.get("effect", "none")
        out["diag_hit"] = (not names) if effect == "none" else (effect in names)
    return out
