"""The main job end to end (``vcnc demo``): the whole story on one machine, as a report.

Stages (each timed and shown in the report):

1. generate the rapid-identification program (thesis Table 3.2 style, random moves on X and Y);
2. simulate it on the "true" virtual machine, which hides an effect the identifier is not told
   about (default: nut backlash four times the machine's nominal value on X, with the X loop
   closed on a linear scale so that the lost motion is inside the loop and in the capture; on
   the semi-closed-loop Fadal the motor encoder never sees backlash);
3. identify the reduced model of each axis (exact solver; GA and Lagrange/KKT for comparison,
   with their run times);
4. diagnose the residual, name the hidden effect, add it, report the error before and after;
5. compare contours (circle and diamond at 200 mm/s) of the truth, the identified and the
   augmented models;
6. export an axis model as an FMU and validate it with fmpy.

``vcnc demo --emps`` tells the same story on the real EMPS measurements (identification,
residual, diagnosis, before/after).
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from vcnc.capture import Capture, read_capture
from vcnc.core.errors import CaptureError, VcncError
from vcnc.core.metrics import error_metrics
from vcnc.report import Report

__all__ = ["run_demo", "run_emps_demo", "DEFAULT_MACHINE", "DEFAULT_EFFECT", "EMPS_URL"]

log = logging.getLogger(__name__)

DEFAULT_MACHINE = "fadal-pid"
#: The effect hidden on the X axis by default: nut backlash larger than its nominal value.
DEFAULT_EFFECT = "backlash"
#: Pole box for EMPS: its controller is a P-P cascade without integral action (EMPS description,
#: Sec. 1.3), so the real pole p of Eq. 3.7 tends to 0 and the thesis' p >= 0.2 Hz would pin the
#: fit to the box corner.
EMPS_BOUNDS = {"p_hz": (0.001, 500.0), "omega_n_hz": (0.2, 500.0), "zeta": (0.2, 2.0)}
#: Where to get the EMPS data set.
EMPS_URL = "https://www.nonlinearbenchmark.org (Electro-Mechanical Positioning System, EMPS)"


class _Stages:
    """Times stages; shows a progress bar on a terminal, stays quiet when piped or in tests."""

    def __init__(self, names: list[str], *, progress: bool | None) -> None:
        self.times: dict[str, float] = {}
        if progress is None:
            progress = sys.stderr.isatty() and "PYTEST_CURRENT_TEST" not in os.environ
        self._bar = None
        if progress:
            from tqdm import tqdm

            self._bar = tqdm(total=len(names), desc="vcnc demo", unit="stage", file=sys.stderr)

    @contextlib.contextmanager
    def stage(self, name: str) -> Iterator[None]:
        if self._bar is not None:
            self._bar.set_postfix_str(name)
        t0 = time.perf_counter()
        yield
        self.times[name] = time.perf_counter() - t0
        log.info("stage %s: %.2f s", name, self.times[name])
        if self._bar is not None:
            self._bar.update(1)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()




def run_demo(
    out: str | os.PathLike[str] = "vcnc-demo",
    *,
    machine: str = DEFAULT_MACHINE,
    effect: str | None = DEFAULT_EFFECT,
    effect_axis: str = "x",
    seed: int = 1,
    feed_mm_s: float = 200.0,
    fmu: bool = True,
    progress: bool | None = None,
) -> dict[str, Any]:
    """Run the demo on a built-in (or TOML) machine and write the report folder.

    Parameters
    ----------
    out : path
        Report folder (``index.html``, ``summary.json``, PNGs, model files, FMU).
    machine : str
        Built-in machine name or TOML file.
    effect : str or None
        Effect hidden on ``effect_axis`` of the true machine (ARCHITECTURE.md vocabulary); for
        ``backlash`` the width is set to 4x the machine's nominal value (at least 10 um). None
        hides nothing.
    effect_axis : str
        Axis carrying the hidden effect.
    seed : int
        Seed of the identification program and of the measurement noise.
    feed_mm_s : float
        Feed of the contour tests [mm/s].
    fmu : bool
        Export and validate an FMU of the final X model.
    progress : bool, optional
        Progress bar (default: on a terminal only).

    Returns
    -------
    dict
        The summary also written to ``summary.json``.
    """
    import identification
    from vcnc.engine.machine import load_machine

    stages = _Stages(
        ["program", "simulate", "identify", "compare solvers", "diagnose", "contours", "fmu", "report"],
        progress=progress,
    )
    report = Report(f"vcnc demo: rapid identification of {machine}")
    summary: dict[str, Any] = {"machine": machine, "hidden_effect": None, "seed": seed}
    try:
        nominal = load_machine(machine)
        truth, hidden = _hide_effect(nominal, effect, effect_axis)
        summary["hidden_effect"] = hidden
        axes = [a for a in truth.axes][:2]

        capture = _identification_test(truth, axes, seed, stages, summary)
        with stages.stage("identify"):
            models = {a: identification.identify(capture, axis=a, diagnose=False) for a in axes}
        with stages.stage("compare solvers"):
            solver_rows = _compare_solvers(capture, effect_axis)
        with stages.stage("diagnose"):
            from identification.diagnosis import diagnose

            augmented = {a: diagnose(capture, models[a], axis=a) for a in axes}
        summary["axes"] = {a: _axis_summary(nominal, a, models[a], augmented[a]) for a in axes}
        summary["solvers"] = solver_rows

        with stages.stage("contours"):
            contour_rows, contour_figs = _contours(truth, models, augmented, feed_mm_s)
        summary["contours"] = contour_rows
        summary["contour_feed_mm_s"] = feed_mm_s

        fmu_info: dict[str, Any] | None = None
        with stages.stage("fmu"):
            if fmu:
                fmu_info = _export_fmu(augmented[effect_axis], out)
        summary["fmu"] = fmu_info

        with stages.stage("report"):
            _write_story(report, summary, capture, models, augmented, nominal, solver_rows, contour_rows,
                         contour_figs, effect_axis)
        summary["stage_times_s"] = stages.times
        report.summary = summary
        report.write(out)
    finally:
        stages.close()
    return summary


def _hide_effect(nominal: Any, effect: str | None, axis: str) -> tuple[Any, dict | None]:
    if effect is None:
        return nominal, None
    params: dict[str, float] | None = None
    if effect == "backlash":
        ax = nominal.axis(axis)
        nominal_width = getattr(getattr(ax, "backlash", None), "width", 0.0) or 0.0
        params = {"width_mm": max(4 * nominal_width, 0.010)}
    truth = nominal.with_effect(axis, effect, params)
    return truth, {"name": effect, "axis": axis, "parameters": params or "realistic default"}


def _truth_parameters(machine: Any, axis: str) -> dict[str, float] | None:
    ax = machine.axis(axis)
    fn = getattr(ax, "reduced_parameters", None)
    if fn is None:
        return None
    try:
        return dict(fn())
    except VcncError:
        return None


def _compare_solvers(capture: Capture, axis: str) -> list[dict[str, Any]]:
    """Equation-error optimum of each solver on the same statistics, with run times."""
    import identification

    reference, measured, ts = identification.check_capture(capture, axis)
    stats = identification.statistics(reference, measured, ts)
    rows = []
    for method in ("exact", "kkt", "ga"):
        t0 = time.perf_counter()
        res = identification.solve_statistics(stats, method=method, sample_time=ts, seed=0)
        dt = time.perf_counter() - t0
        rows.append({"method": method, "time_s": dt, "objective": float(res.objective), "poles": dict(res.poles)})
    best = min(r["objective"] for r in rows)
    for r in rows:
        r["objective_rel_to_best"] = r["objective"] / best - 1.0 if best > 0 else 0.0
    return rows


def _contours(truth: Any, models: dict, augmented: dict, feed_mm_s: float):
    """Circle and diamond on the true machine vs the identified and the augmented models.

    One comparison per toolpath: :func:`vcnc.compare` runs the augmented models as given and
    their reduced (linear) part as the "identified" prediction.
    """
    from vcnc.contour_compare import compare

    rows = []
    figs = []
    for name in ("circle", "diamond"):
        rep = compare(truth, augmented, name, feed=feed_mm_s)
        m = rep.metrics()
        ident = m["identified"]
        aug = m.get("augmented", ident)
        rows.append({
            "toolpath": name,
            "true_max_um": m["true"]["max_um"],
            "true_rms_um": m["true"]["rms_um"],
            "identified_max_um": ident["max_um"],
            "identified_rms_um": ident["rms_um"],
            "augmented_max_um": aug["max_um"],
            "augmented_rms_um": aug["rms_um"],
            "identified_error_pct_max": rep.prediction_error_pct("identified")["max"],
            "augmented_error_pct_max": rep.prediction_error_pct()["max"],
        })
        figs.append((name, rep))
    return rows, figs


def _export_fmu(model: Any, out: str | os.PathLike[str]) -> dict[str, Any]:
    import tempfile

    from vcnc.fmu import export_fmu

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"drive_{model.axis}.fmu"
        t0 = time.perf_counter()
        try:
            export_fmu(model, path, fmi_version=2, check=True)
        except VcncError as exc:
            return {"exported": False, "reason": str(exc)}
        data = path.read_bytes()
        return {"exported": True, "file": path.name, "fmi": 2, "validated": True, "time_s": time.perf_counter() - t0,
                "_bytes": data}


# --------------------------------------------------------------------------- report
def _identification_test(truth: Any, axes: list[str], seed: int, stages: _Stages, summary: dict) -> Capture:
    """The rapid-identification test (200 random moves, thesis Table 3.2 style) run on the true machine."""
    import interpolators
    import toolpaths

    with stages.stage("program"):
        program_text = toolpaths.random_moves(200, 10.0, 12000.0, seed=seed, axes=axes)
        program = interpolators.parse_program(program_text, source="identification.nc")
        setpoints = interpolators.interpolate(
            program, limits=truth.limits, sample_time=truth.sample_time, profile="trapezoid"
        )
    with stages.stage("simulate"):
        capture = truth.simulate(setpoints, seed=seed)
    summary["identification_test"] = {
        "blocks": len(program.blocks),
        "samples": len(capture),
        "duration_s": float(capture.t[-1]),
        "axes": axes,
    }
    return capture


def _axis_summary(nominal: Any, axis: str, model: Any, augmented: Any) -> dict[str, Any]:
    """What the summary says of one axis: the identified model, the true parameters, the effects."""
    return {
        "identified": {"parameters": model.parameters, "poles": model.poles, "fit": model.fit},
        "true_parameters": _truth_parameters(nominal, axis),
        "effects": augmented.effects,
        "validation": augmented.validation,
    }


def _write_story(report: Report, summary: dict, capture: Capture, models: dict, augmented: dict, nominal: Any,
                 solver_rows: list, contour_rows: list, contour_figs: list, effect_axis: str) -> None:
    """The demo's report, section by section."""
    hidden = summary["hidden_effect"]
    report.text(
        "A rapid-identification test (200 random moves, thesis Table 3.2 style) runs on the virtual "
        f"machine '{summary['machine']}'. "
        + (f"The true machine hides an effect the identifier is not told about: {hidden['name']} on axis "
           f"{hidden['axis']}. " if hidden else "No effect is hidden. ")
        + "The reduced closed-loop model (thesis Eq. 3.3) is identified from commanded and measured "
        "positions only, its residual is traced to a physical effect, the effect is added, and the "
        "contour predictions of the true machine, the identified and the augmented models are compared."
    )

    _story_identification_test(report, capture, models, augmented, effect_axis)
    _story_models(report, summary, models, nominal, solver_rows, effect_axis)
    _story_diagnosis(report, capture, models, augmented, effect_axis)
    _story_contours(report, summary, contour_rows, contour_figs)
    _story_fmu(report, summary, augmented, effect_axis)


def _story_identification_test(report: Report, capture: Capture, models: dict, augmented: dict,
                               effect_axis: str) -> None:
    """Commanded, measured and predicted position of the identification test."""
    import matplotlib.pyplot as plt

    report.heading("Identification test")
    i = capture.axis_index(effect_axis)
    t = capture.t
    fig, axs = plt.subplots(2, 1, figsize=(10, 6.5))
    pred = models[effect_axis].simulate(capture.reference[:, i], sample_time=capture.sample_time)
    pred_aug = augmented[effect_axis].simulate(capture.reference[:, i], sample_time=capture.sample_time)
    # a window of a few moves, so that the lag of measured behind commanded is visible
    w = (t >= 2.0) & (t <= 4.0)
    axs[0].plot(t[w], capture.reference[w, i], label="commanded", lw=1.2)
    axs[0].plot(t[w], capture.measured[w, i], label="measured (true machine)", lw=1.2)
    axs[0].plot(t[w], pred[w], "--", label="predicted (identified model)", lw=1.2)
    axs[0].set_ylabel(f"{effect_axis} [mm]")
    axs[0].set_xlabel("time [s] (2 s window)")
    axs[0].legend(loc="best", fontsize="small")
    axs[0].grid(True, alpha=0.3)
    err_id = (capture.measured[:, i] - pred) * 1e3
    err_aug = (capture.measured[:, i] - pred_aug) * 1e3
    axs[1].plot(t, err_id, lw=0.8, label=f"identified model (RMS {np.sqrt(np.mean(err_id**2)):.3g} um)")
    axs[1].plot(t, err_aug, lw=0.8, alpha=0.8, label=f"augmented model (RMS {np.sqrt(np.mean(err_aug**2)):.3g} um)")
    axs[1].set_ylabel("measured - predicted [um]")
    axs[1].set_xlabel("time [s]")
    axs[1].legend(loc="best", fontsize="small")
    axs[1].grid(True, alpha=0.3)
    track = error_metrics(capture.reference[:, i] - capture.measured[:, i])
    fig.suptitle(f"Axis {effect_axis}: commanded, measured and predicted position "
                 f"(true tracking error RMS {track['rms_um']:.3g} um)")
    fig.tight_layout()
    report.figure("identification_test", fig, caption="Commanded vs measured vs predicted position.")


def _story_models(report: Report, summary: dict, models: dict, nominal: Any, solver_rows: list,
                  effect_axis: str) -> None:
    """The identified parameters against the true ones, the solvers, the FRFs."""
    report.heading("Identified models")
    rows = []
    for a, m in models.items():
        tp = summary["axes"][a]["true_parameters"] or {}
        for k, v in m.parameters.items():
            rows.append([a, k, tp.get(k, math.nan), v])
    report.table(["axis", "parameter", "true (linearised)", "identified"], rows,
                 caption="Parameters of Eq. 3.3 (a1 1/s, a2 1/s^2, a3 1/s^3, b0 -, b1 1/s, b2 1/s^2, d0/d1 mm/s^2)")
    report.text(
        "'true (linearised)' is Eq. 3.4/3.5 evaluated from the controller gains as if the loop were "
        "continuous; the virtual machine runs its controller sampled at 1 ms with a DAC, an encoder and "
        "friction, so its effective closed loop is faster and less damped than that formula says. The "
        "identified model describes the machine as it behaves, which is what its contour predictions need."
    )
    rows = []
    for r in solver_rows:
        rows.append([r["method"], r["time_s"] * 1e3, r["objective"], r["objective_rel_to_best"],
                     r["poles"].get("omega_n_hz"), r["poles"].get("zeta"), r["poles"].get("p_hz")])
    report.table(["solver", "time [ms]", "objective (Eq. 3.12)", "rel. to best", "omega_n [Hz]", "zeta", "p [Hz]"],
                 rows, caption=f"Axis {effect_axis}: the three solvers on the same statistics "
                 "(the thesis needed 15-20 min for LM and 2-3 min for its GA)")
    for a, m in models.items():
        fig, _ = _frf_figure(m, nominal, a)
        report.figure(f"frf_{a}", fig, caption=f"Axis {a}: tracking and disturbance FRFs, true vs identified.")


def _story_diagnosis(report: Report, capture: Capture, models: dict, augmented: dict, effect_axis: str) -> None:
    """The effects the diagnosis found and its figures."""
    report.heading("Residual diagnosis: what the reduced model does not explain")
    rows = []
    for a, m in augmented.items():
        val = m.validation or {}
        if not m.effects:
            rows.append([a, "(none found)", "", val.get("rms_before_um", math.nan), val.get("rms_after_um", math.nan)])
        for e in m.effects:
            params = _fmt_params(e.get("parameters", {}))
            rows.append([a, e["name"], params, e.get("rms_before_um", math.nan), e.get("rms_after_um", math.nan)])
    report.table(["axis", "effect", "parameters", "RMS before [um]", "RMS after [um]"], rows,
                 caption="Effects found on held-out data, in the order they were added")
    _diagnosis_figures(report, capture, models, augmented, effect_axis)


def _story_contours(report: Report, summary: dict, contour_rows: list, contour_figs: list) -> None:
    """True and predicted contour errors."""
    report.heading("Contour prediction")
    rows = [[r["toolpath"], r["true_max_um"], r["identified_max_um"], r["augmented_max_um"],
             r["identified_error_pct_max"], r["augmented_error_pct_max"]] for r in contour_rows]
    report.table(["toolpath", "true max [um]", "identified max [um]", "augmented max [um]",
                  "identified error [%]", "augmented error [%]"], rows,
                 caption="Maximum contour error: true machine vs predictions"
                 + (f" (true: mean of {contour_figs[0][1].runs} noise realisations of the machine; the figures "
                    "show the first)" if contour_figs and contour_figs[0][1].runs > 1 else ""))
    for name, rep in contour_figs:
        axs = rep.plot()
        report.figure(f"contour_{name}", axs[0].figure,
                      caption=f"{name} at {summary['contour_feed_mm_s']:g} mm/s: contour error magnified, true vs "
                      "identified vs augmented, and along the path.")


def _story_fmu(report: Report, summary: dict, augmented: dict, effect_axis: str) -> None:
    """The exported FMU and the model files."""
    report.heading("FMU export")
    info = summary.get("fmu")
    if info and info.get("exported"):
        data = info.pop("_bytes")
        report.attach(info["file"], data, caption="FMI 2.0 Co-Simulation, validated with fmpy")
        report.text(f"The final {effect_axis} model was exported as an FMU, validated with fmpy and checked "
                    "against the Python simulation to 1e-9 mm.")
    elif info:
        report.text(f"FMU not exported: {info.get('reason')}")
    for a, m in augmented.items():
        report.attach(f"model_{a}.json", _model_bytes(m), caption=f"axis {a} model (vcnc.axis-model/1)")


def _fmt_params(params: dict) -> str:
    """``k=v`` list for a table; arrays (Fourier coefficients) shown by their size only."""
    out = []
    for k, v in params.items():
        if isinstance(v, (list, tuple, np.ndarray)):
            out.append(f"{k}=[{len(v)} values]")
        elif isinstance(v, float):
            out.append(f"{k}={v:.4g}")
        else:
            out.append(f"{k}={v}")
    return ", ".join(out)


def _model_bytes(model: Any) -> bytes:
    import json

    return (json.dumps(model.to_dict(), indent=2) + "\n").encode()


def _frf_figure(model: Any, machine: Any, axis: str):
    truth = None
    ax = machine.axis(axis)
    if hasattr(ax, "reduced_parameters"):
        with contextlib.suppress(VcncError):
            truth = ax.reduced_parameters()
    fig = model.plot(truth=truth)
    if not hasattr(fig, "savefig"):
        fig = fig[0].figure if isinstance(fig, (list, tuple, np.ndarray)) else fig.figure
    return fig, truth


def _diagnosis_figures(report: Report, capture: Capture, models: dict, augmented: dict, axis: str) -> None:
    fig = _residual_figure(capture, models[axis], augmented[axis], axis)
    report.figure(f"residual_{axis}", fig,
                  caption=f"Axis {axis}: residual before/after vs time, velocity and position; spectrum.")


def _residual_figure(capture: Capture, before: Any, after: Any, axis: str):
    from identification.residual import plot_before_after

    i = capture.axis_index(axis)
    axes = plot_before_after(capture.reference[:, i], capture.measured[:, i], capture.sample_time, before, after)
    return np.ravel(axes)[0].figure


# --------------------------------------------------------------------------- EMPS
def run_emps_demo(
    emps_dir: str | os.PathLike[str] | None,
    out: str | os.PathLike[str] = "vcnc-demo-emps",
    *,
    progress: bool | None = None,
) -> dict[str, Any]:
    """The same story on the real EMPS measurements (identification, residual, diagnosis).

    Raises
    ------
    CaptureError
        When the folder does not hold ``DATA_EMPS.mat`` and ``DATA_EMPS_PULSES.mat`` (says where to
        get them).
    """
    import identification
    from identification.diagnosis import diagnose

    given = emps_dir or os.environ.get("VCNC_EMPS_DIR") or ""
    folder = Path(given)
    files = {"DATA_EMPS": folder / "DATA_EMPS.mat", "DATA_EMPS_PULSES": folder / "DATA_EMPS_PULSES.mat"}
    missing = [str(p) for p in files.values() if not p.is_file()]
    if missing or not given:
        where = ", ".join(missing) if given else "no folder given: --emps without DIR and VCNC_EMPS_DIR unset"
        raise CaptureError(
            f"EMPS data not found ({where}); download DATA_EMPS.mat and "
            f"DATA_EMPS_PULSES.mat from {EMPS_URL} and pass their folder (--emps DIR or VCNC_EMPS_DIR)",
            file=given or None,
        )
    stages = _Stages(["identify", "diagnose", "report"], progress=progress)
    report = Report("vcnc demo: the real EMPS drive")
    summary: dict[str, Any] = {"data": {}}
    try:
        for name, path in files.items():
            cap = read_capture(path)
            with stages.stage("identify"):
                model = identification.identify(cap, axis="x", diagnose=False, bounds=EMPS_BOUNDS)
            with stages.stage("diagnose"):
                aug = diagnose(cap, model, axis="x")
            summary["data"][name] = {
                "samples": len(cap),
                "identified": {"parameters": model.parameters, "poles": model.poles, "fit": model.fit,
                               "stable": bool(model.is_stable())},
                "effects": aug.effects,
                "validation": aug.validation,
            }
            report.heading(name)
            report.text(f"{len(cap)} samples at {cap.sample_time * 1e3:.3f} ms; pole box {EMPS_BOUNDS}; "
                        "identified poles: "
                        + ", ".join(f"{k} {v:.4g}" for k, v in model.poles.items()))
            rows = [[e["name"], _fmt_params(e.get("parameters", {})),
                     e.get("rms_before_um", math.nan), e.get("rms_after_um", math.nan)] for e in aug.effects]
            if not rows:
                rows = [["(none found)", "", math.nan, math.nan]]
            report.table(["effect", "parameters", "RMS before [um]", "RMS after [um]"], rows,
                         caption="Effects the data supports, in the order added (held-out judgement)")
            with stages.stage("report"):
                fig = _residual_figure(cap, model, aug, "x")
                report.figure(f"residual_{name}", fig, caption=f"{name}: residual before and after.")
        report.summary = summary
        report.write(out)
    finally:
        stages.close()
    return summary


def describe(summary: dict[str, Any], echo: Callable[[str], None] = print) -> None:
    """Print a short text account of a demo summary (the CLI's output)."""
    hidden = summary.get("hidden_effect")
    if hidden:
        echo(f"hidden effect: {hidden['name']} on axis {hidden['axis']}")
    for a, info in summary.get("axes", {}).items():
        names = [e["name"] for e in info.get("effects", [])] or ["none"]
        val = info.get("validation") or {}
        echo(f"axis {a}: effects found: {', '.join(names)}; validation RMS "
             f"{val.get('rms_before_um', math.nan):.3g} -> {val.get('rms_after_um', math.nan):.3g} um")
    for r in summary.get("contours", []):
        echo(f"{r['toolpath']}: max contour error true {r['true_max_um']:.3g} um, identified "
             f"{r['identified_max_um']:.3g} um ({r['identified_error_pct_max']:+.1f} %), augmented "
             f"{r['augmented_max_um']:.3g} um ({r['augmented_error_pct_max']:+.1f} %)")
    for name, d in summary.get("data", {}).items():
        names = [e["name"] for e in d.get("effects", [])] or ["none"]
        val = d.get("validation") or {}
        echo(f"{name}: effects found: {', '.join(names)}; validation RMS "
             f"{val.get('rms_before_um', math.nan):.3g} -> {val.get('rms_after_um', math.nan):.3g} um")
