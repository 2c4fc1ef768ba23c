"""Summary (ARCHITECTURE.md, ``vcnc simulate`` JSON) and plots of a simulated capture."""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Any

import numpy as np

from vcnc.core.axes import ROTARY_AXES, axis_unit
from vcnc.core.capture import Capture
from vcnc.core.metrics import error_metrics, true_runs

if TYPE_CHECKING:
    from vcnc.report import Report

__all__ = ["summarize", "build_report", "moving_axes", "saturation_note", "result_line", "feed_contour_line"]

log = logging.getLogger(__name__)

#: What a summary records of the run (``Capture.meta`` of ``vcnc simulate``): a summary read alone says which
#: program ran on which machine, with which feed profile and noise seed, and whether all of it ran.
SIMULATED_KEYS = ("program", "machine", "profile", "seed", "truncated")


def moving_axes(capture: Capture, *, tol: float = 1e-9) -> list[str]:
    """Axes whose commanded position changes by more than ``tol`` [mm]."""
    return [a for i, a in enumerate(capture.axes) if np.ptp(capture.reference[:, i]) > tol]


def summarize(capture: Capture, program: Any = None) -> dict[str, Any]:
    """``{"samples", "sample_time", "axes", "tracking": {a: {"max_um", "rms_um"}}, "contour"?}``, and what was
    simulated, from the capture's ``meta`` where it records it: ``"program"`` (file name), ``"machine"``,
    ``"profile"``, ``"seed"`` and, for a program cut by ``--max-seconds``, ``"truncated"`` (the note saying
    where; without it the whole program ran).

    Tracking error e = x_r - x of the measured position, in 1/1000 of the axis unit: um on a linear
    axis, mdeg on a rotary one (the keys keep the ``_um`` of the summary contract). "contour" comes from
    ``vcnc.contour.contour_metrics(capture)`` for two or more moving axes; it is left out (and the
    reason logged) when that module is not available or the capture has no programmed path. With the
    ``program`` the capture was simulated from (an :class:`interpolators.Program`), "contour_feed" is the
    same error over the samples of its feed moves only (G1/G2/G3, TNC L/C/CR at F: the cutting; rapids, G0
    and FMAX, left out), as ``vcnc compare`` measures it (``vcnc.contour.feed_segments``); left out when the
    program has no rapid (it equals "contour") or no feed move. Our reading: the thesis' contouring tests
    are feed moves, and a rapid's deviation, often the largest of a program (a PID loop lags most at the
    rapid rate), says nothing of the part.
    """
    e = capture.reference - capture.measured
    out: dict[str, Any] = {
        "samples": len(capture),
        "sample_time": float(capture.meta.get("sample_time") or capture.sample_time),
        "axes": list(capture.axes),
        **{k: capture.meta[k] for k in SIMULATED_KEYS if capture.meta.get(k) is not None},
        "tracking": {
            a: error_metrics(e[:, i]) for i, a in enumerate(capture.axes)
        },
    }
    saturated = _saturation(capture)
    if saturated:
        out["saturated"] = saturated
    if len(moving_axes(capture)) >= 2:
        c, fc = _contour_entries(capture, program)
        if fc is not None:
            out["contour_feed"] = fc
        if c is None:
            log.warning("contour error left out of the summary: the setpoints carry no programmed path")
        else:
            out["contour"] = {"max_um": float(c["max_um"]), "rms_um": float(c["rms_um"])}
    return out


def _contour_entries(capture: Capture, program: Any) -> tuple[dict[str, float] | None, dict[str, float] | None]:
    """The contour error's metrics over every sample and, with the ``program``, over those of its feed moves (None
    when it has no feed move or no rapid), from one contour search; (None, None) without a path or two moving
    linear axes (as :func:`vcnc.contour.contour_metrics`)."""
    from vcnc.contour import contour_error, feed_segments
    from vcnc.contour import moving_axes as moving_linear

    if capture.path is None or len(moving_linear(capture.reference, capture.axes)) < 2:
        return None, None
    flags = feed_segments(capture.path, program) if program is not None else None
    ce = contour_error(capture.path, capture.measured, capture.axes, reference=capture.reference, t=capture.t,
                       include_segments=flags)
    every = error_metrics(ce.error)
    if flags is None or flags.all() or ce.include is None or not ce.include.any():
        return every, None
    return every, error_metrics(ce.error[ce.include])


def _saturation(capture: Capture) -> dict[str, dict[str, float]]:
    """``{axis: {"share", "longest_s", "error_beyond_travel"}}`` of the axes whose control signal was at its
    limit (``Capture.aux["saturated"]`` of a simulation): the share of the samples, the longest
    run [s], and whether the tracking error grew beyond the axis' commanded travel (the loop diverged)."""
    sat = capture.aux.get("saturated")
    out = {}
    for i, a in enumerate(capture.axes if sat is not None else ()):
        col = np.asarray(sat[:, i], dtype=bool)
        if col.any():
            longest = max(stop - start for start, stop in true_runs(col))
            out[a] = {"share": float(col.mean()), "longest_s": float(longest * capture.sample_time),
                      "error_beyond_travel": bool(np.abs(capture.reference[:, i] - capture.measured[:, i]).max()
                                                  > np.ptp(capture.reference[:, i]))}
    return out


def saturation_note(summary: dict[str, Any]) -> str | None:
    """A warning in words when an actuator saturated during the run (``summary["saturated"]``), else None.

    A loop at its actuator limit no longer follows the linear closed loop the machine's controller was
    tuned for: the tracking error grows beyond it. With the laws' anti-windup (``anti_windup = true``,
    the default: :class:`controllers.Controller`) the loop recovers once the demand is back within the
    limit; the bare laws of the thesis (``anti_windup = false``) wind their integrators up, and an
    adaptive or model-based law may then leave its stable region altogether. The usual cause is an
    axis ``acceleration`` limit that the drive cannot deliver at its current or voltage limit."""
    sat = summary.get("saturated")
    if not sat:
        return None
    parts = ", ".join(f"{a} {100 * v['share']:.3g} % of the samples (longest {1e3 * v['longest_s']:.4g} ms)"
                      for a, v in sat.items())
    lost = [a for a, v in sat.items() if v["error_beyond_travel"]]
    diverged = (f"; on axis {', '.join(lost)} the tracking error grew beyond the commanded travel: the loop left its "
                "stable region and the numbers describe that, not the machining" if lost else "")
    return (f"warning: the actuator was at its limit on axis {parts}: the loop ran saturated there, so its "
            f"errors are not those of the tuned closed loop{diverged}; check that the axis limits (acceleration) "
            "fit what the drive delivers")


def result_line(summary: dict[str, Any]) -> str:
    """The run in one line, as ``vcnc simulate`` prints it: its length, the contour error (two or more moving
    axes) and the largest tracking error with its axis, in the summary's units (um; mdeg on a rotary axis)."""
    ts = summary["sample_time"]
    n = summary["samples"]
    parts = [f"simulated {(n - 1) * ts:.6g} s ({n} samples at Ts = {ts:g} s)"]
    contour = summary.get("contour")
    if contour:
        parts.append(f"contour error max {contour['max_um']:.3g} um, rms {contour['rms_um']:.3g} um")
    worst = max(summary["tracking"], key=lambda a: summary["tracking"][a]["max_um"])
    s = summary["tracking"][worst]
    u = axis_unit(worst, small=True)
    parts.append(f"tracking error max {s['max_um']:.3g} {u} (axis {worst}, rms {s['rms_um']:.3g} {u})")
    return "; ".join(parts)


def feed_contour_line(summary: dict[str, Any]) -> str | None:
    """The contour error of the feed moves (``summary["contour_feed"]``) in words, beside that of every move,
    or None when the summary has no such entry (no rapid, or no feed move)."""
    fc, c = summary.get("contour_feed"), summary.get("contour")
    if not fc or not c:
        return None
    return (f"contour error on the feed moves (rapids left out): max {fc['max_um']:.3g} um, rms {fc['rms_um']:.3g} um "
            f"(every move: max {c['max_um']:.3g} um)")


def build_report(capture: Capture, summary: dict[str, Any]) -> Report:
    """A :class:`vcnc.report.Report` of a simulation: the summary table, ``tracking.png`` (error
    [um] and control [V] per axis) and, for two or more moving axes, ``path.png`` (commanded path
    and the measured one with the error magnified). Nothing is written until ``Report.write``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from vcnc.contour import DENSE_SEGMENTS
    from vcnc.report import Report

    rep = Report(f"vcnc simulate: {capture.meta.get('program', '')} on {capture.meta.get('machine', '')}")
    rep.summary = summary
    if capture.meta.get("truncated"):
        rep.text(f"{capture.meta.get('program', 'the program')}: {capture.meta['truncated']}")
    for line in (saturation_note(summary), feed_contour_line(summary)):
        if line:
            rep.text(line)
    rep.table(
        ["axis", "max tracking error", "rms tracking error", "unit"],
        [[a, s["max_um"], s["rms_um"], axis_unit(a, small=True)] for a, s in summary["tracking"].items()],
        caption=f"{summary['samples']} samples at Ts = {summary['sample_time']:g} s, "
                f"{capture.meta.get('profile', 'trapezoid')} profile, seed {capture.meta.get('seed')}",
    )
    n = len(capture.axes)
    rows = 2 if capture.control is not None else 1
    fig, axs = plt.subplots(rows, n, figsize=(5 * n, 3.2 * rows), squeeze=False, sharex=True)
    t = capture.t
    for i, a in enumerate(capture.axes):
        e = (capture.reference[:, i] - capture.measured[:, i]) * 1e3
        ax = axs[0, i]
        ax.plot(t, e, lw=0.8)
        s = summary["tracking"][a]
        u = axis_unit(a, small=True)
        ax.set_title(f"axis {a}: tracking error (max {s['max_um']:.2f} {u}, rms {s['rms_um']:.2f} {u})", fontsize=9)
        ax.set_ylabel(f"{a}_r - {a} [{u}]")
        ax.grid(alpha=0.3)
        if rows == 2:
            axs[1, i].plot(t, capture.control[:, i], lw=0.8, color="C1")
            axs[1, i].set_ylabel("control u [V]")
            axs[1, i].grid(alpha=0.3)
        axs[-1, i].set_xlabel("t [s]")
    fig.tight_layout()
    rep.figure("tracking", fig, caption="tracking error and control signal per axis")
    mov = [a for a in moving_axes(capture) if a not in ROTARY_AXES]  # the path of the linear axes
    if len(mov) >= 2 and summary.get("contour") and len(capture.path) > DENSE_SEGMENTS:
        rep.figure("path", _dense_path_figure(capture, summary, mov),
                   caption=f"path of axes {mov[0]}, {mov[1]}, its points coloured by the contour error")
    elif len(mov) >= 2:
        fig, gain, what = _path_figure(capture, summary, mov)
        rep.figure("path", fig, caption=f"path of axes {mov[0]}, {mov[1]} with the {what} magnified {gain:g} times")
    return rep


def _dense_path_figure(capture: Capture, summary: dict[str, Any], mov: list[str]) -> Any:
    """The commanded path in the first two moving linear axes, grey, with its samples coloured by the contour
    error [um] (:func:`vcnc.contour.plot_error_colours`)."""
    import matplotlib.pyplot as plt

    from vcnc.contour import contour_error, plot_error_colours

    i, j = capture.axis_index(mov[0]), capture.axis_index(mov[1])
    r = capture.reference[:, [i, j]]
    ce = contour_error(capture.path, capture.measured, capture.axes, reference=capture.reference, t=capture.t)
    fig, ax = plt.subplots(figsize=(7, 6))
    dots = plot_error_colours(ax, r, np.abs(ce.error) * 1e3)
    fig.colorbar(dots, ax=ax, label="contour error [um]")
    ax.set_xlabel(f"{mov[0]} [mm]")
    ax.set_ylabel(f"{mov[1]} [mm]")
    ax.set_title(f"path in {mov[0]}, {mov[1]} coloured by the contour error in {', '.join(mov)} "
                 f"(max {summary['contour']['max_um']:.2f} um)", fontsize=9)
    fig.tight_layout()
    return fig


def _path_figure(capture: Capture, summary: dict[str, Any], mov: list[str]) -> tuple[Any, float, str]:
    """The commanded path in the first two moving linear axes and the measured one with its contour
    error magnified (:meth:`vcnc.contour.ContourError.magnified`: the deviation from the path, as the
    thesis' contouring figures draw it), or, without a programmed path, its tracking error; returns
    the figure, the magnification and what was magnified."""
    import matplotlib.pyplot as plt

    from vcnc.contour import auto_magnification, contour_error

    i, j = capture.axis_index(mov[0]), capture.axis_index(mov[1])
    r = capture.reference[:, [i, j]]
    c = summary.get("contour")
    if c is not None:
        ce = contour_error(capture.path, capture.measured, capture.axes, reference=capture.reference, t=capture.t)
        gain = auto_magnification(capture.path, float(np.max(np.abs(ce.error))) if len(ce.error) else 0.0)
        shown = ce.magnified(gain)[:, ["xyz".index(mov[0]), "xyz".index(mov[1])]]
        what = "contour error"
    else:
        err = capture.measured[:, [i, j]] - r
        extent = float(np.max(np.ptp(r, axis=0)))
        emax = float(np.max(np.abs(err))) or 1.0
        gain = max(1.0, float(10 ** np.floor(np.log10(max(0.05 * extent / emax, 1e-12)))))
        shown, what = r + gain * err, "tracking error"
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(r[:, 0], r[:, 1], lw=0.8, label="commanded")
    ax.plot(shown[:, 0], shown[:, 1], lw=0.8, label=f"measured, {what} x{gain:g}")
    ax.set_xlabel(f"{mov[0]} [mm]")
    ax.set_ylabel(f"{mov[1]} [mm]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    # the contour error is measured in every moving linear axis; the picture shows the first two
    ax.set_title(f"path in {mov[0]}, {mov[1]}" + (f" (contour error in {', '.join(mov)}: max {c['max_um']:.2f} um)"
                                                  if c else ""), fontsize=9)
    fig.tight_layout()
    return fig, gain, what
