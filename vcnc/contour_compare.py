"""Virtual process planning: the contour error of a 'true' machine against that of its models.

The same setpoints run on the true machine (a built-in name, a TOML file or a Machine, every
non-ideality on) and on a *predicted machine* whose axes are identified models
(:meth:`vcnc.Machine.from_axes`); the contour errors of both runs are measured on the exact
programmed path (:func:`vcnc.contour.contour_error`) and compared, as the thesis does in Figs.
3.6, 3.7, 3.9, 3.11, 3.14, 4.9 and 4.10. The truth may also be a real capture: its commanded
positions are then passed through the models (Sec. 4.3.3: "the command trajectory captured from
the machine's interpolator was passed through the virtual drive models").

Models
------
A model file holds one axis. ``models`` is either one model for every moving axis (the thesis'
ball-screw bench, Sec. 3.4.2, where one identified axis stands for both X and Y) or a mapping
axis -> model. A model that carries diagnosis ``effects`` and simulates them (an augmented model)
is compared twice: as given ("augmented", the summary's ``predicted``) and reduced to its
identified linear part (``model.reduced()``: "identified", the summary's ``before_augmentation``).
The diagnosis may have refitted the parameters, so that part can differ slightly from the model
identified before the diagnosis; compare that model itself for the strict "before".

Toolpaths
---------
``"circle"``: a full circle of 40 mm diameter (R = 20 mm) counter-clockwise from (20, 0);
``"diamond"``: the square turned by 45 degrees with vertices 20 mm from the centre on the axes (the
same 40 mm extent as the circle; side 28.28 mm), counter-clockwise. Both at 200 mm/s (F12000)
unless ``feed`` says otherwise, started with a rapid from the origin and a dwell of
:data:`SETTLE_S` so that the contour starts from rest; the rapid is excluded from the metrics
(contour errors of positioning moves do not mark the part). Any other string is a
program file (ISO or Heidenhain); a :class:`interpolators.Program` or :class:`vcnc.Setpoints` may
be given directly. A single-axis true machine drives every axis of the toolpath with copies of
its axis (the thesis ran its single-axis bench this way, Fig. 3.14).

Noise realisations
------------------
Measurement noise inside a true machine's loop makes its contour error a random quantity: the
loop acts on the noisy reading. On the fadal-smc diamond the true maximum ranges over 8.81-9.06 um
across ten noise seeds (+/-1.4 %; 9.04 um with the noise off), a spread of the order of the model
error being judged. A deterministic model predicts the *expected*
contour error, so a simulated truth with measurement noise is run :data:`TRUTH_RUNS` times
(seeds ``seed, seed + 1, ...``): ``true`` reports the mean of the runs' metrics and their range,
the prediction error is taken against the mean, and its range against the single runs is
reported beside it. The histories and plots show the first run. A noise-free truth (or a real
capture) is run once.
"""

from __future__ import annotations

import dataclasses
import json
import logging
import math
import os
from collections.abc import Iterator, Mapping
from pathlib import Path as FsPath
from typing import Any, Protocol

import numpy as np

from interpolators.program import Program
from toolpaths.geometry import AXIS_LETTERS
from vcnc.contour import (
    DENSE_SEGMENTS,
    ContourError,
    auto_magnification,
    commanded_points,
    contour_error,
    feed_segments,
    moving_axes,
    plot_error_colours,
    plot_plane,
)
from vcnc.core.axes import axis_unit
from vcnc.core.capture import Capture
from vcnc.core.errors import InputError
from vcnc.core.jsonsafe import plain
from vcnc.core.setpoints import Setpoints
from vcnc.engine.machine import Machine


class AxisModel(Protocol):
    """What compare needs of an axis model (identification.ReducedAxisModel, an FMU axis, ...)."""

    def simulate_reference(self, reference: np.ndarray, sample_time: float) -> np.ndarray: ...


#: A model object, or its model file (``vcnc.axis-model/1`` or ``/2``).
ModelSource = AxisModel | str | os.PathLike[str]

__all__ = ["compare", "ContourReport", "SHAPES", "DEFAULT_FEED_MM_S", "SETTLE_S", "TRUTH_RUNS"]

log = logging.getLogger(__name__)

#: Built-in toolpaths and their size: circle radius [mm], diamond side [mm] (vertices 20 mm out).
SHAPES: dict[str, float] = {"circle": 20.0, "diamond": 40.0 / math.sqrt(2.0)}

#: Feed of the built-in toolpaths [mm/s] (200 mm/s: Secs. 3.4.1 and 4.3.3 of the thesis).
DEFAULT_FEED_MM_S = 200.0

#: Time [s] the final position is held after the program so that the axes settle.
SETTLE_S = 0.2

#: Noise realisations of a simulated truth with measurement noise (module notes).
TRUTH_RUNS = 10


def _pct(pred: float, true: float) -> float:
    return float(100.0 * (pred - true) / true) if true > 0 else float("nan")


def _pct_of(t: Mapping[str, Any], p: Mapping[str, Any]) -> dict[str, float]:
    """``{"max", "rms"}``: 100 (predicted - true) / true of the contour error [%], from metrics."""
    return {"max": _pct(p["max_um"], t["max_um"]), "rms": _pct(p["rms_um"], t["rms_um"])}


def _mean_tree(items: list) -> Any:
    """Element-wise mean of metrics of the same layout (dicts, lists, numbers; NaN where all are).

    Lists of different lengths (a corner whose window no sample of one run reached) are the first run's: their
    items would not pair up; so is one list object that every run holds. Plain Python on the scalars: a long
    program's metrics hold tens of thousands of corners, and numpy's per-call overhead on ten numbers was 15 s of a
    compare (3D_Chips)."""
    first = items[0]
    if isinstance(first, Mapping):
        return {k: _mean_tree([it[k] for it in items]) for k in first}
    if isinstance(first, (list, tuple)):
        # one object in every run (a corner's position_mm, vcnc.contour.feature_points'): nothing to average
        if all(it is first for it in items) or any(len(it) != len(first) for it in items):
            return first
        return [_mean_tree([it[i] for it in items]) for i in range(len(first))]
    if isinstance(first, bool) or not isinstance(first, (int, float, np.number)):
        return first
    vals = [float(v) for v in items]
    finite = [v for v in vals if not math.isnan(v)]
    if not finite:
        return float("nan")
    if isinstance(first, (int, np.integer)) and all(v == vals[0] for v in vals):
        return int(first)
    return math.fsum(finite) / len(finite)


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class ContourReport:
    """True and predicted contour errors of one toolpath.

    Attributes
    ----------
    toolpath : str
        Name of the toolpath (``circle``, ``diamond`` or the program file).
    truth : str
        Name of the true machine or capture.
    setpoints : Setpoints
        The commanded motion both runs received.
    true : ContourError
        Contour error of the true machine: for a simulated machine, of the true position of each
        axis' measured point (``Capture.aux["measured_true"]``: what its sensor reads, without the
        sensor's noise, quantisation and drift); for a real capture, of its measured positions.
    predicted : dict of str to ContourError
        ``"identified"`` (the reduced models) and, when the models carry effects they simulate,
        ``"augmented"``.
    models : dict
        Per label, per axis: a short description of the model used.
    notes : list of str
        What the numbers rest on (e.g. a copied axis, effects that could not be simulated).
    true_as_measured : ContourError or None
        Simulated truth only: the contour error of the true machine as its sensors read it
        (``Capture.measured``: noise, encoder steps and drift included), shown beside ``true``.
    true_runs, true_as_measured_runs : list of dict
        Metrics of every noise realisation of a simulated truth (module notes), ``true`` being
        the first; empty for a single run.
    seeds : list of int
        Noise seeds of the truth's runs (empty for a real capture).
    """

    toolpath: str
    truth: str
    setpoints: Setpoints
    true: ContourError
    predicted: dict[str, ContourError]
    models: dict = dataclasses.field(default_factory=dict)
    notes: list = dataclasses.field(default_factory=list)
    true_as_measured: ContourError | None = None
    true_runs: list = dataclasses.field(default_factory=list)
    true_as_measured_runs: list = dataclasses.field(default_factory=list)
    seeds: list = dataclasses.field(default_factory=list)
    #: metrics computed once per label (a noisy truth's mean over its runs, each prediction's): the summary, the
    #: prediction errors and the report ask for them many times
    _memo: dict = dataclasses.field(default_factory=dict, init=False, repr=False)

    @property
    def truncated(self) -> str | None:
        """Where the toolpath was cut to its first seconds (``compare(max_duration=...)``,
        :func:`vcnc.facade.truncation_note`), or None when it ran whole."""
        from vcnc.facade import truncation_note

        return truncation_note(self.setpoints, done="compared")

    @property
    def runs(self) -> int:
        """Noise realisations of the truth behind ``metrics()["true"]``."""
        return max(1, len(self.true_runs))

    @property
    def main_label(self) -> str:
        """The prediction of the models as given: ``augmented`` when present, else ``identified``."""
        return "augmented" if "augmented" in self.predicted else "identified"

    def metrics(self) -> dict[str, dict[str, Any]]:
        """Metrics of every run (see :meth:`ContourError.metrics`), by label; the truth's are the
        mean over its noise realisations."""
        out = {"true": self._true_metrics()}
        if self.true_as_measured is not None:
            out["true_as_measured"] = self._true_metrics(as_measured=True)
        out.update({k: self._predicted_metrics(k) for k in self.predicted})
        return out

    def _true_metrics(self, *, as_measured: bool = False) -> dict[str, Any]:
        key = "true_as_measured" if as_measured else "true"
        if key not in self._memo:
            runs = self.true_as_measured_runs if as_measured else self.true_runs
            self._memo[key] = _mean_tree(runs) if runs else (self.true_as_measured if as_measured
                                                             else self.true).metrics()
        return self._memo[key]

    def _predicted_metrics(self, label: str) -> dict[str, Any]:
        if ("predicted", label) not in self._memo:
            self._memo["predicted", label] = self.predicted[label].metrics()
        return self._memo["predicted", label]

    def prediction_error_pct(self, label: str | None = None) -> dict[str, float]:
        """``{"max", "rms"}``: 100 (predicted - true) / true of the contour error [%], against the
        mean of the truth's noise realisations."""
        return _pct_of(self._true_metrics(), self._predicted_metrics(label or self.main_label))

    def prediction_error_as_measured_pct(self, label: str | None = None) -> dict[str, float] | None:
        """As :meth:`prediction_error_pct`, against :attr:`true_as_measured` (None without it)."""
        if self.true_as_measured is None:
            return None
        return _pct_of(self._true_metrics(as_measured=True), self._predicted_metrics(label or self.main_label))

    def prediction_error_range_pct(self, label: str | None = None) -> dict[str, list[float]] | None:
        """``{"max": [lo, hi], "rms": [lo, hi]}``: the prediction error [%] against each single
        noise realisation of the truth (None for a single run)."""
        if not self.true_runs:
            return None
        p = self._predicted_metrics(label or self.main_label)
        per = [_pct_of(t, p) for t in self.true_runs]
        return {k: [min(x[k] for x in per), max(x[k] for x in per)] for k in ("max", "rms")}

    def true_spread(self) -> dict[str, list[float]] | None:
        """``{"contour_max_um": [lo, hi], "contour_rms_um": [lo, hi]}`` over the truth's noise
        realisations (None for a single run)."""
        if not self.true_runs:
            return None
        out = {}
        for k in ("max", "rms"):
            vals = [t[f"{k}_um"] for t in self.true_runs]
            out[f"contour_{k}_um"] = [min(vals), max(vals)]
        return out

    def to_dict(self) -> dict[str, Any]:
        """The ``vcnc compare`` summary (ARCHITECTURE.md contract), with details beside it."""
        m = self.metrics()

        def block(label: str) -> dict[str, Any]:
            x = m[label]
            out = {"contour_max_um": x["max_um"], "contour_rms_um": x["rms_um"],
                   "corner_max_um": _nan_none(x["corner_max_um"]), "quadrant_max_um": _nan_none(x["quadrant_max_um"])}
            if self.true.signed:
                out["max_outside_um"] = x["max_outside_um"]
                out["max_inside_um"] = x["max_inside_um"]
            if "tracking" in x:
                out["tracking"] = x["tracking"]
            return out

        main = self.main_label
        true = block("true")
        if self.seeds:
            true["runs"] = self.runs
            true["seeds"] = list(self.seeds)
        if self.true_runs:
            true["spread"] = self.true_spread()
        d: dict[str, Any] = {
            "toolpath": self.toolpath,
            "true": true,
            "predicted": block(main),
            "prediction_error_pct": self.prediction_error_pct(main),
        }
        if self.true_runs:
            d["prediction_error_pct_range"] = self.prediction_error_range_pct(main)
        if main == "augmented":
            d["before_augmentation"] = {**block("identified"),
                                        "prediction_error_pct": self.prediction_error_pct("identified")}
            if self.true_runs:
                d["before_augmentation"]["prediction_error_pct_range"] = self.prediction_error_range_pct("identified")
        if self.true_as_measured is not None:
            d["true_as_measured"] = {**block("true_as_measured"),
                                     "prediction_error_pct": self.prediction_error_as_measured_pct(main)}
        d["truth"] = self.truth
        d["models"] = self.models
        d["samples"] = len(self.setpoints)
        d["sample_time"] = self.setpoints.sample_time
        d["metrics_cover"] = int(m["true"]["samples"])
        d["signed"] = self.true.signed
        cut = self.truncated
        if cut:
            d["truncated"] = cut
        if self.notes:
            d["notes"] = list(self.notes)
        return d

    def to_json(self, path: str | os.PathLike[str]) -> None:
        """Write :meth:`to_dict` as JSON (atomic)."""
        from vcnc.core.io import atomic_path

        text = json.dumps(plain(self.to_dict()), indent=2) + "\n"
        with atomic_path(path) as tmp:
            tmp.write_text(text)

    # ------------------------------------------------------------------ plots
    def _legend(self, label: str) -> str:
        if label == "true" and self.true_runs:
            return f"true (noise seed {self.seeds[0]}, 1 of {self.runs})"
        return label

    def _runs(self) -> list[tuple[str, ContourError]]:
        labels = [k for k in ("identified", "augmented") if k in self.predicted]
        return [("true", self.true)] + [(k, self.predicted[k]) for k in labels]

    def plot_contour(self, ax=None, *, magnification: float | None = None):  # noqa: ANN001 - matplotlib Axes
        """The path with the true and predicted contour errors magnified (thesis style)."""
        if ax is None:
            import matplotlib.pyplot as plt

            _, ax = plt.subplots(figsize=(6, 6))
        if magnification is None:
            worst = max(float(np.max(np.abs(ce.error[ce.covered()]), initial=0.0)) for _, ce in self._runs())
            magnification = auto_magnification(self.true.path, worst)
        styles = {"true": {"color": "k", "lw": 1.4}, "identified": {"color": "C0", "ls": "--"},
                  "augmented": {"color": "C3", "ls": ":"}}
        for i, (label, ce) in enumerate(self._runs()):
            if i == 0:
                ce.plot(ax, magnification=magnification, label=self._legend(label), **styles[label])
            else:
                mag = np.where(ce.covered()[:, None], ce.magnified(magnification), np.nan)
                a, b = plot_plane(self.true)
                ax.plot(mag[:, a], mag[:, b], label=f"{label} (error x{magnification:g})", **styles[label])
        ax.legend(loc="best", fontsize="small")
        ax.set_title(f"{self.toolpath} on {self.truth}: contour error x{magnification:g}")
        return ax

    def plot_error(self, ax=None):  # noqa: ANN001 - matplotlib Axes
        """Contour error [um] against path arc length [mm], true and predicted overlaid."""
        styles = {"true": {"color": "k", "lw": 1.4}, "identified": {"color": "C0", "ls": "--"},
                  "augmented": {"color": "C3", "ls": ":"}}
        for label, ce in self._runs():
            ax = ce.plot_error(ax, label=self._legend(label), **styles[label])
        return ax

    def plot(self, ax=None):  # noqa: ANN001 - matplotlib Axes or a pair of them
        """Both pictures: the magnified contour and the error along the path.

        ``ax``: None (a new figure), one Axes (the magnified contour only) or two Axes.
        Returns the Axes used.
        """
        if ax is None:
            import matplotlib.pyplot as plt

            _, ax = plt.subplots(1, 2, figsize=(13, 5.5))
        if isinstance(ax, (list, tuple, np.ndarray)):
            axes = list(np.ravel(ax))
            self.plot_contour(axes[0])
            if len(axes) > 1:
                self.plot_error(axes[1])
            return ax
        return self.plot_contour(ax)

    def _dense_contour_figure(self):  # -> matplotlib Figure
        """The commanded path in its plane twice, coloured by the true and the predicted contour error [um] of the
        samples the metrics cover (:func:`vcnc.contour.plot_error_colours`), one colour scale."""
        from matplotlib.figure import Figure

        a, b = plot_plane(self.true)
        sp = self.setpoints
        xy = np.column_stack([sp.position[:, sp.axis_index(AXIS_LETTERS[i])] if AXIS_LETTERS[i] in sp.axes
                              else np.zeros(len(sp)) for i in (a, b)])
        runs = [("true", self.true), (self.main_label, self.predicted[self.main_label])]
        errs = [np.where(ce.covered(), np.abs(ce.error) * 1e3, np.nan) for _, ce in runs]
        top = max(float(np.nanmax(e, initial=0.0)) for e in errs) or None
        fig = Figure(figsize=(13, 6))
        axs = fig.subplots(1, 2)
        for ax, (label, _), err in zip(axs, runs, errs):
            dots = plot_error_colours(ax, xy, err, vmax=top)
            ax.set_title(f"{self._legend(label)}: max {np.nanmax(err, initial=0.0):.4g} um", fontsize=9)
            ax.set_xlabel(f"{AXIS_LETTERS[a]} [mm]")
        axs[0].set_ylabel(f"{AXIS_LETTERS[b]} [mm]")
        fig.colorbar(dots, ax=list(axs), label="contour error [um]")
        fig.suptitle(f"{self.toolpath} on {self.truth}: contour error along the path")
        return fig

    def report(self):  # -> vcnc.report.Report
        """An HTML report (:class:`vcnc.report.Report`): metrics table, both figures, summary."""
        from matplotlib.figure import Figure

        from vcnc.report import Report

        rep = Report(f"vcnc compare: {self.toolpath} on {self.truth}")
        rep.heading("Contour error: true machine and prediction")
        m = self.metrics()
        rows = []
        nan = {"max": float("nan"), "rms": float("nan")}
        spread = self.true_spread()
        for label, _ in self._runs():
            x = m[label]
            pe = self.prediction_error_pct(label) if label != "true" else nan
            name = label
            if label == "true" and spread is not None:
                lo, hi = spread["contour_max_um"]
                name = f"true, mean of {self.runs} noise realisations (max {lo:.4g}-{hi:.4g} um)"
            rows.append([name, x["max_um"], x["rms_um"], x["corner_max_um"], x["quadrant_max_um"], pe["max"],
                         pe["rms"]])
            if label == "true" and "true_as_measured" in m:
                x = m["true_as_measured"]
                rows.append(["true, as its sensors read it", x["max_um"], x["rms_um"], x["corner_max_um"],
                             x["quadrant_max_um"], nan["max"], nan["rms"]])
        rep.table(["run", "max [um]", "RMS [um]", "corners max [um]", "quadrants max [um]", "max error [%]",
                   "RMS error [%]"], rows,
                  caption="Prediction error = 100 (predicted - true) / true. Feed moves only (rapids excluded)."
                  + (f" The truth has measurement noise in its loop: its numbers are the mean of {self.runs} "
                     f"noise realisations (seeds {self.seeds[0]}-{self.seeds[-1]}), the figures show the first."
                     if self.true_runs else ""))
        trows = []
        for label, _ in self._runs():
            for a, v in m[label].get("tracking", {}).items():
                trows.append([label, a, v["max_um"], v["rms_um"], axis_unit(a, small=True)])
        if trows:
            rep.table(["run", "axis", "tracking max", "tracking RMS", "unit"], trows)
        if self.models:
            rep.table(["model", "axis", "description"],
                      [[lab, a, desc] for lab, per in self.models.items() for a, desc in per.items()])
        for note in self.notes:
            rep.text(note)
        if len(self.true.path) > DENSE_SEGMENTS:
            rep.figure("contour", self._dense_contour_figure(),
                       caption="Programmed path (grey), its feed moves' samples coloured by the contour error: the "
                       f"true machine and the {self.main_label} models on one colour scale (a path of "
                       f"{len(self.true.path)} segments: the magnified errors would cover it)")
        else:
            fig = Figure(figsize=(7, 7))
            self.plot_contour(fig.subplots())
            rep.figure("contour", fig, caption="Programmed path (grey) and the contours, errors magnified")
        fig = Figure(figsize=(10, 4.5))
        self.plot_error(fig.subplots())
        rep.figure("contour_error", fig, caption="Contour error along the path, true and predicted")
        rep.summary = plain(self.to_dict())
        return rep


def _nan_none(v: float) -> float | None:
    return None if v is None or (isinstance(v, float) and math.isnan(v)) else v


# ------------------------------------------------------------------------------ inputs
def _truth_machine(truth: Any) -> Machine:
    from vcnc.engine.machine import load_machine

    if isinstance(truth, Machine):
        return truth
    if isinstance(truth, (str, os.PathLike)):
        return load_machine(truth)
    raise InputError(f"truth must be a machine name, a machine TOML file, a Machine or a Capture; got "
                     f"{type(truth).__name__}")


def _load_one(model: Any, where: str):
    if isinstance(model, (str, os.PathLike)):
        from identification import load_model

        return load_model(model)
    if not hasattr(model, "simulate_reference"):
        raise InputError(f"{where}: a model needs simulate_reference(reference, sample_time); got "
                         f"{type(model).__name__}")
    return model


def _models_per_axis(models: Any, axes: tuple[str, ...]) -> dict[str, Any]:
    if isinstance(models, Mapping):
        if not models:
            raise InputError("no model given; give one model for all axes or one per axis")
        unknown = [a for a in models if a not in axes]
        missing = [a for a in axes if a not in models]
        if missing:
            raise InputError(
                f"no model for axis {', '.join(missing)} (models given for {', '.join(models)}); give one model "
                "per moving axis, or a single model for all axes"
            )
        if unknown:
            log.info("models for axes %s are not used: the toolpath moves %s", unknown, axes)
        per_axis = {a: _load_one(models[a], f"model of axis {a}") for a in axes}
        for a, model in per_axis.items():
            _check_unit(getattr(model, "axis", None), [a], f"--model {a}={models[a]}"
                        if isinstance(models[a], (str, os.PathLike)) else f"the model of axis {a}")
        return per_axis
    one = _load_one(models, "model")
    own = getattr(one, "axis", None)
    borrowed = [a for a in axes if own is not None and a != own]
    _check_unit(own, borrowed, f"--model {models}" if isinstance(models, (str, os.PathLike)) else "the model")
    if borrowed:
        log.warning("the model of axis %s stands in for axis %s, which has no model of its own: the prediction "
                    "assumes the axes are alike (give --model %s=FILE for each axis)", own, ", ".join(borrowed),
                    "/".join(borrowed))
    return {a: one for a in axes}


def _check_unit(own: str | None, axes: list[str], given: str) -> None:
    """:class:`InputError` when a model identified on axis ``own`` is to predict an axis of ``axes`` in another unit
    (a rotary axis' model, in deg, for a linear axis in mm, or the reverse): its friction and offsets are in its
    own axis' unit, and the contour error would mix the two (our reading: no control couples them so)."""
    if own is None:
        return
    other = [a for a in axes if axis_unit(a) != axis_unit(own)]
    if other:
        raise InputError(
            f"{given}: a model identified on axis {own} [{axis_unit(own)}] cannot predict axis "
            f"{', '.join(other)} [{axis_unit(other[0])}]",
            expected=f"a model of each such axis: {' '.join(f'--model {a}=FILE' for a in other)}")


def _other_axis_notes(models: Any, per_axis: dict[str, Any]) -> list[str]:
    """A note per axis given its own model (``{axis: model}``) that names another axis as the one it was identified
    on: ``model y.json (identified on axis y) used for x``. The report's model table says it too, but a planner who
    mixed the files up reads the command's notes (our reading; one model for all axes, the thesis' Sec. 3.4.2 case,
    is said by :func:`_models_per_axis`'s warning instead)."""
    if not isinstance(models, Mapping):
        return []
    notes = []
    for a, model in per_axis.items():
        own = getattr(model, "axis", None)
        if own not in (None, a):
            given = models[a]
            name = str(given) if isinstance(given, (str, os.PathLike)) else f"{type(model).__name__} object"
            notes.append(f"model {name} (identified on axis {own}) used for {a}: the prediction assumes {a}'s drive "
                         f"is like {own}'s (a model identified on {a}, --model {a}=FILE, if there is one)")
    return notes


def _identified_part(model: Any):
    """The model without its diagnosis effects (the reduced linear model of Eq. 3.3).

    ``model.reduced()`` (identification.AugmentedAxisModel) when the model has it; a model with
    no effects is its own identified part.
    """
    if not getattr(model, "effects", None):
        return model
    reduced = getattr(model, "reduced", None)
    if callable(reduced):
        reduced = reduced()
    if reduced is not None and hasattr(reduced, "simulate_reference"):
        return reduced
    return model


def _stand_in(model: Any, axis: str) -> str:
    """A note when ``model`` was identified on another axis than the one it predicts."""
    own = getattr(model, "axis", None)
    return f" (the model of axis {own}: axis {axis} has none of its own)" if own not in (None, axis) else ""


def _describe(model: Any) -> str:
    poles = getattr(model, "poles", None) or {}
    parts = [type(model).__name__]
    if poles:
        parts.append(", ".join(f"{k} {float(v):.4g}" for k, v in poles.items()))
    delay_s = float(getattr(model, "delay_s", 0.0) or 0.0)
    if delay_s:
        parts.append(f"reference dead time {delay_s:.4g} s (simulated on the delayed reference)")
    filter_s = float(getattr(model, "setpoint_filter_s", 0.0) or 0.0)
    if filter_s:
        parts.append(f"setpoint filter {filter_s * 1e3:.4g} ms (a moving average between the reference and the loop)")
    effects = getattr(model, "effects", None)
    if effects:
        parts.append("effects: " + ", ".join(str(e.get("name", "?")) if isinstance(e, dict) else str(e)
                                             for e in effects))
    return "; ".join(parts)


def _shape_program(name: str, feed_mm_s: float) -> str:
    import toolpaths

    f = feed_mm_s * 60.0
    text = toolpaths.circle(SHAPES["circle"], f) if name == "circle" else toolpaths.diamond(SHAPES["diamond"], f)
    # a dwell after the rapid: the contour starts from rest, as in the thesis' tests. G4 P is in seconds in the
    # LinuxCNC G-code the program is read as (LinuxCNC G-code reference, "G4 Dwell": "P - seconds to dwell"); a
    # P in milliseconds (Fanuc's reading) made it 200 s
    lines = text.splitlines()
    i = next(k for k, line in enumerate(lines) if "G00" in line)
    lines.insert(i + 1, f"G04 P{SETTLE_S:g}")
    return "\n".join(lines) + "\n"


def _program(toolpath: Any, feed: float | None):
    """(program or None, setpoints or None, name)."""
    import interpolators

    if isinstance(toolpath, Setpoints):
        if toolpath.path is None:
            raise InputError("the setpoints have no path (Setpoints.path); the contour needs the programmed geometry")
        return None, toolpath, str(toolpath.meta.get("source") or "setpoints")
    if isinstance(toolpath, interpolators.Program):
        return toolpath, None, str(toolpath.source or "program")
    if isinstance(toolpath, str) and toolpath in SHAPES:
        f = DEFAULT_FEED_MM_S if feed is None else feed
        if not (isinstance(f, (int, float)) and math.isfinite(f) and f > 0):
            raise InputError(f"feed must be a finite value > 0 mm/s, got {feed!r}")
        return interpolators.parse_program(_shape_program(toolpath, f), source=f"<{toolpath}>"), None, toolpath
    if isinstance(toolpath, (str, os.PathLike)):
        p = FsPath(toolpath)
        if not p.is_file():
            raise InputError(
                f"toolpath {str(toolpath)!r} is neither a built-in toolpath ({', '.join(SHAPES)}) nor a program file",
                file=str(toolpath),
            )
        if feed is not None:
            raise InputError("feed applies to the built-in toolpaths only; a program sets its own feeds (F)")
        return interpolators.load_program(p), None, str(toolpath)
    raise InputError(f"toolpath must be 'circle', 'diamond', a program file, a Program or Setpoints; got "
                     f"{type(toolpath).__name__}")


def _limits(machine, axes: tuple[str, ...], acceleration: float | None, feed: float | None) -> dict:
    from interpolators import AxisLimits

    src = machine.limits
    base = src[axes[0]] if len(src) == 1 else None
    out = {}
    for a in axes:
        lim = src.get(a, base)
        if acceleration is not None:
            if not (isinstance(acceleration, (int, float)) and math.isfinite(acceleration) and acceleration > 0):
                raise InputError(f"acceleration must be a finite value > 0 mm/s^2, got {acceleration!r}")
            lim = dataclasses.replace(lim, acceleration=float(acceleration))
        if feed is not None and lim.velocity < feed:
            lim = dataclasses.replace(lim, velocity=float(feed), rapid=max(lim.rapid_rate, float(feed)))
        out[a] = lim if isinstance(lim, AxisLimits) else AxisLimits(**dataclasses.asdict(lim))
    return out


def _expand_machine(machine, axes: tuple[str, ...], notes: list[str]):
    """The machine itself, or a copy driving every axis of the toolpath with its single axis."""
    from vcnc.engine.machine import Machine

    missing = [a for a in axes if a not in machine.axes]
    if not missing:
        return machine
    if len(machine.axes) != 1:
        raise InputError(
            f"the toolpath moves axis {', '.join(missing)} which machine {machine.name!r} does not have "
            f"(axes: {', '.join(machine.axes)})"
        )
    (only,) = machine.axes
    ax = machine.axis(only)
    axes_map = {}
    for a in axes:
        axes_map[a] = dataclasses.replace(ax, name=a) if dataclasses.is_dataclass(ax) and hasattr(ax, "name") else ax
    notes.append(f"machine {machine.name!r} has one axis ({only}); each of {', '.join(axes)} is a copy of it")
    return Machine.from_axes(axes_map, sample_time=machine.sample_time,
                             limits={a: machine.limits[only] for a in axes}, name=machine.name,
                             description=machine.description)


# ------------------------------------------------------------------------------ compare
def compare(
    truth: str | os.PathLike[str] | Machine | Capture,
    models: ModelSource | Mapping[str, ModelSource],
    toolpath: str | os.PathLike[str] | Program | Setpoints | None = "circle",
    *,
    feed: float | None = None,
    acceleration: float | None = None,
    profile: str = "trapezoid",
    seed: int = 0,
    settle_s: float = SETTLE_S,
    truth_runs: int | None = None,
    max_duration: float | None = None,
    max_samples: int | None = None,
) -> ContourReport:
    """Contour error of a toolpath on the true machine and as predicted by axis models.

    Parameters
    ----------
    truth : str, os.PathLike, vcnc.Machine or vcnc.Capture
        Built-in machine name or machine TOML (every non-ideality on), a Machine, or a capture of
        a real run (its ``reference`` is the command both see; needs ``path``, or a program as
        ``toolpath`` whose programmed geometry is then used).
    models : model, path, or mapping of axis -> model or path
        One ``vcnc.axis-model/1`` file / model object for every moving axis, or one per axis.
        Objects need ``simulate_reference(reference, sample_time)``.
    toolpath : {"circle", "diamond"}, path, Program or Setpoints
        See the module notes.
    feed : float, optional
        Feed of the built-in toolpaths [mm/s] (default 200).
    acceleration : float, optional
        Axis acceleration limit of the interpolation [mm/s^2] (default: the true machine's).
        The thesis' cases: 2000 (Sec. 3.4.1), 600 (Sec. 3.4.2 at 100 mm/s).
    profile : {"trapezoid", "scurve"}
        Feed profile of the interpolation.
    seed : int
        Seed of the true machine's measurement noise (of its first run).
    settle_s : float
        The final position is held this long [s] after the program so the axes settle.
    truth_runs : int, optional
        Noise realisations of a simulated truth, seeds ``seed .. seed + truth_runs - 1`` (module
        notes); default :data:`TRUTH_RUNS` when an axis of the true machine has measurement noise,
        else 1.
    max_duration : float, optional
        Compare only the first ``max_duration`` seconds of a program or built-in toolpath run on a simulated truth
        (:func:`vcnc.facade.interpolate`: cut after the last block that ends within it; the report's
        ``truncated`` and a note say where). Without it the whole program runs.
    max_samples : int, optional
        Without ``max_duration``: refuse (:class:`vcnc.ProgramTooLongError`) a program that needs more samples
        (default: the interpolator's guard). ``vcnc compare`` passes its ``MAX_SAMPLES``.

    Returns
    -------
    ContourReport

    Raises
    ------
    vcnc.InputError
        Unknown machine or toolpath, unreadable model or program (naming the file and line), a
        model missing for a moving axis, a capture without a path.
    """
    if truth_runs is not None and not (isinstance(truth_runs, (int, np.integer)) and not isinstance(truth_runs, bool)
                                       and 1 <= truth_runs <= 1000):
        raise InputError(f"truth_runs must be an integer in [1, 1000], got {truth_runs!r}")
    if isinstance(truth, Capture):
        if max_duration is not None:
            raise InputError("max_duration (--max-seconds) applies to a toolpath run on a simulated truth; a "
                             "capture is compared as recorded", file=truth.source)
        run = _captured_truth(truth, toolpath)
    else:
        run = _simulated_truth(truth, toolpath, feed=feed, acceleration=acceleration, profile=profile, seed=seed,
                               settle_s=settle_s, truth_runs=truth_runs,
                               guard={"max_duration": max_duration, "max_samples": max_samples})
    notes = run.notes
    moving = moving_axes(run.setpoints.position, run.axes)
    if len(moving) < 2:
        notes.append(f"the toolpath moves only {', '.join(moving) or 'no axis'}: the contour error is the "
                     "deviation from a straight line")
    include = None if run.program is None else feed_segments(run.path, run.program)
    kw = {"reference": run.setpoints.position, "t": run.setpoints.t, "sample_time": run.sample_time,
          "include_segments": include,
          "commanded": commanded_points(run.path, run.setpoints.position, run.axes)}  # one for all runs
    true_ce, true_sensor, true_runs, sensor_runs = _true_contours(run, kw)
    several = len(true_runs) > 1
    if several:
        notes.append(f"the true machine has measurement noise in its loop: its contour error is the mean of "
                     f"{len(true_runs)} noise realisations (seeds {run.seeds[0]}-{run.seeds[-1]}); plots show the "
                     "first")
    per_axis = _models_per_axis(models, run.axes)
    notes.extend(_other_axis_notes(models, per_axis))
    predicted, descr = _predictions(per_axis, run, kw, seed=seed, notes=notes)
    notes.extend(_beyond_range_notes(per_axis, run, true_ce.include))
    notes.extend(_model_notes(per_axis, run, true_ce.include))
    if include is not None:
        notes.append("metrics cover feed moves only; rapid (G00 / FMAX) moves are excluded")
    return ContourReport(toolpath=run.toolpath, truth=run.name, setpoints=run.setpoints, true=true_ce,
                         predicted=predicted, models=descr, notes=notes, true_as_measured=true_sensor,
                         true_runs=true_runs if several else [],
                         true_as_measured_runs=sensor_runs if several else [], seeds=run.seeds)


@dataclasses.dataclass
class _Truth:
    """The true side of a comparison: the commanded setpoints, the programmed path, and the true
    positions (and sensor readings) of each run."""

    setpoints: Setpoints
    axes: tuple[str, ...]
    path: Any
    program: Program | None
    toolpath: str
    name: str
    sample_time: float
    positions: Iterator[tuple[np.ndarray, np.ndarray | None]]
    seeds: list[int]
    notes: list[str]
    #: where a simulated truth's servo period comes from ("'sample_time' [s] of FILE"); None for a captured truth
    servo_period_of: str | None = None


def _captured_truth(capture: Capture, toolpath: str | os.PathLike[str] | Program | Setpoints | None) -> _Truth:
    """A real run: its commanded positions are the setpoints, its measured ones the truth."""
    program = None
    moving = moving_axes(capture.reference, capture.axes)
    if len(moving) < 2:
        # a control's trace of one axis (TNCscope, halscope, a SINUMERIK trace of one drive): no contour to compare
        raise InputError(
            f"the capture's commanded positions move {len(moving)} linear axis ({', '.join(moving) or 'none'} of "
            f"{', '.join(capture.axes)}): a contour error needs two or more axes recorded on one time base",
            file=capture.source, expected="a trace of the axes that made the contour (X and Y), or a built-in machine "
            "or machine file as --truth; the model of one axis is checked against a record of that axis by vcnc "
            "identify CAPTURE --check MODEL.json")
    if toolpath is not None and not (isinstance(toolpath, str) and toolpath in SHAPES):
        program, _, tp_name = _program(toolpath, None)
    else:
        tp_name = str(capture.meta.get("program") or capture.source or "capture")
    path = program.path() if program is not None else capture.path
    if path is None:
        raise InputError("the capture has no path; give the program it ran as toolpath", file=capture.source)
    axes = tuple(a for a in capture.axes if a in ("x", "y", "z"))
    cols = [capture.axis_index(a) for a in axes]
    sp = Setpoints.from_positions(capture.reference[:, cols], sample_time=capture.sample_time, axes=axes)
    return _Truth(setpoints=dataclasses.replace(sp, path=path), axes=axes, path=path, program=program,
                  toolpath=tp_name, name=capture.source or "capture", sample_time=capture.sample_time,
                  positions=iter([(capture.measured[:, cols], None)]), seeds=[], notes=[])


def _simulated_truth(truth: str | os.PathLike[str] | Machine, toolpath, *, feed: float | None,
                     acceleration: float | None, profile: str, seed: int, settle_s: float,
                     truth_runs: int | None, guard: dict) -> _Truth:
    """The true machine run on the toolpath, lazily, one noise seed at a time; ``guard``: the ``max_duration``
    and ``max_samples`` of :func:`vcnc.facade.interpolate`."""
    from vcnc.facade import check_program_axes, interpolate, truncation_note

    notes: list[str] = []
    machine = _truth_machine(truth)
    program, sp, tp_name = _program(toolpath, feed)
    if sp is None:
        axes = tuple(program.axes or ("x",))
        if len(machine.axes) > 1:
            # as vcnc simulate: a move of an axis the machine lacks is refused naming its line and the way
            # forward; an axis the program only names (G0 Z0 at Z0) is left out of the setpoints
            check_program_axes(program, machine, option="--truth")
            axes = tuple(a for a in axes if a in machine.axes)
        limits = _limits(machine, axes, acceleration, feed)
        sp = interpolate(program, limits=limits, sample_time=machine.sample_time, profile=profile, **guard)
        if len(machine.axes) == 1:  # its axis is copied for each axis the program moves (not those it only names)
            pos = sp.position
            axes = tuple(a for i, a in enumerate(sp.axes) if len(pos) and float(np.ptp(pos[:, i])) > 0) or axes
        if tuple(sp.axes) != axes:
            sp = sp.select_axes(axes)
        machine = _expand_machine(machine, axes, notes)
        if sp.path is not None and not sp.path.segments:
            raise InputError("the program moves no axis (it only dwells or switches): there is no contour to "
                             "compare", file=program.source, expected="a program with a feed move (G1, G2, G3, L, C)")
    else:
        if guard["max_duration"] is not None:
            raise InputError("max_duration (--max-seconds) applies to a program or built-in toolpath; the "
                             "setpoints given are compared as they are")
        machine = _expand_machine(machine, tuple(sp.axes), notes)
    cut = truncation_note(sp, done="compared")
    if cut:  # first: every number below is of the first seconds only
        notes.insert(0, f"{tp_name}: {cut}")
    sp = sp.held(settle_s)
    axes = tuple(sp.axes)
    n_runs = truth_runs if truth_runs is not None else (TRUTH_RUNS if _noisy(machine, axes) else 1)
    seeds = [int(seed) + k for k in range(int(n_runs))]
    source = machine.file
    return _Truth(setpoints=sp, axes=axes, path=sp.path, program=program, toolpath=tp_name, name=machine.name,
                  sample_time=machine.sample_time, positions=(_truth_run(machine, sp, s) for s in seeds),
                  seeds=seeds, notes=notes, servo_period_of=f"'sample_time' [s] of {source}" if source
                  else f"the built-in {machine.name}'s sample_time")


def _true_contours(run: _Truth, kw: dict) -> tuple[ContourError, ContourError | None, list[dict], list[dict]]:
    """The first run's contour errors (true position, sensor reading) and every run's metrics."""
    true_ce = true_sensor = None
    true_runs: list[dict] = []
    sensor_runs: list[dict] = []
    for k, (pos, sensor) in enumerate(run.positions):
        ce = contour_error(run.path, pos, run.axes, **kw)
        ce_sensor = None if sensor is None else contour_error(run.path, sensor, run.axes, **kw)
        if k == 0:
            true_ce, true_sensor = ce, ce_sensor
        true_runs.append(ce.metrics())
        if ce_sensor is not None:
            sensor_runs.append(ce_sensor.metrics())
        # a run's positions and contours go before the next run is simulated: held over it, they were a quarter of
        # the peak memory (2.1 GB for 1.8 million samples of four axes)
        del pos, sensor, ce, ce_sensor
    return true_ce, true_sensor, true_runs, sensor_runs


def _predictions(per_axis: dict[str, Any], run: _Truth, kw: dict, *, seed: int, notes: list[str]
                 ) -> tuple[dict[str, ContourError], dict[str, dict[str, str]]]:
    """Contour errors predicted by the models' identified parts and, when they have effects, by
    the models as given; and a description of each model."""
    import interpolators

    identified = {a: _identified_part(m) for a, m in per_axis.items()}
    augmented = per_axis if any(identified[a] is not per_axis[a] for a in run.axes) else None
    plain_with_effects = [a for a, m in per_axis.items() if getattr(m, "effects", None) and identified[a] is m]
    if plain_with_effects:
        notes.append(f"the models of {', '.join(plain_with_effects)} list effects but offer no reduced() part; "
                     "they are shown as given")
    # the predicted machine's limits only label it (its setpoints are given); any valid record does
    limits = {a: interpolators.DEFAULT_LIMITS["x"] for a in run.axes}
    predicted: dict[str, ContourError] = {}
    descr: dict[str, dict[str, str]] = {}
    for label, mods in (("identified", identified), ("augmented", augmented)):
        if mods is None:
            continue
        pm = Machine.from_axes(mods, sample_time=run.sample_time, limits=limits, name=f"{label} models")
        pred = pm.simulate(run.setpoints, seed=seed).measured
        if not np.all(np.isfinite(pred)):
            raise InputError(f"the {label} model prediction is not finite (an unstable model?)")
        predicted[label] = contour_error(run.path, pred, run.axes, **kw)
        descr[label] = {a: _describe(m) + _stand_in(m, a) for a, m in mods.items()}
    return predicted, descr


def _beyond_range_notes(per_axis: dict[str, Any], run: _Truth, samples: np.ndarray | None) -> list[str]:
    """A note for each axis whose commanded speed or acceleration on the ``samples`` the metrics cover goes
    beyond the operating range of the record its model was identified from (``fit['excitation']``,
    :mod:`identification.excitation`)."""
    from identification.excitation import beyond_range

    notes = []
    for i, a in enumerate(run.axes):
        rec = (getattr(per_axis.get(a), "fit", None) or {}).get("excitation")
        beyond = beyond_range(rec, run.setpoints.position[:, i], run.sample_time, samples=samples) if rec else {}
        if beyond:
            u = axis_unit(a)
            units = {"speed": f"{u}/s", "acceleration": f"{u}/s^2"}
            used = " and ".join(f"{k} {v[0]:.4g} {units[k]}" for k, v in beyond.items())
            seen = " and ".join(f"{v[1]:.4g} {units[k]}" for k, v in beyond.items())
            notes.append(f"the toolpath commands {a} at {used}, beyond the operating range of the record its model "
                         f"was identified from ({seen}): the prediction extrapolates the "
                         "model (identify from a record that reaches them, e.g. the program of `vcnc toolpath "
                         "identification`)")
    return notes


def _model_notes(per_axis: dict[str, Any], run: _Truth, samples: np.ndarray | None) -> list[str]:
    """What the numbers rest on beyond the models' parameters (our reading of what a process planner must be told):

    - a model identified from a record sampled more coarsely than the toolpath runs (a 100 ms log applied to 1 ms
      setpoints) is simulated at the toolpath's step (its continuous-time parameters discretised there,
      ``identification.discretize``), but the record held nothing above its Nyquist frequency 1 / (2 Ts): the
      model's response there is extrapolation;
    - models whose reference dead times (``delay_s``) differ shift the axes' commands against each other by the
      difference, which alone bends the path by up to the toolpath's top speed (over the ``samples`` the metrics
      cover: its feed moves) times it (a circle at 167 mm/s with 0.11 s between x and y: millimetres);
    - a rotary axis (A, B, C) does not enter the contour error, measured on X, Y, Z in mm; its tracking error is in
      mdeg (the summary's ``_um`` keys, as ``vcnc simulate``'s)."""
    from vcnc.core.axes import ROTARY_AXES

    notes = _servo_period_notes(per_axis, run)
    for a in run.axes:
        ts = float(getattr(per_axis[a], "sample_time", 0.0) or 0.0)
        if ts > run.sample_time * (1 + 1e-9):
            notes.append(f"the model of {a} was identified from a record sampled every {ts:g} s (content up to its "
                         f"Nyquist frequency {0.5 / ts:.4g} Hz); it runs here at the toolpath's {run.sample_time:g} s: "
                         f"its response above {0.5 / ts:.4g} Hz is extrapolated, not identified")
    delays = {a: float(getattr(per_axis[a], "delay_s", 0.0) or 0.0) for a in run.axes}
    spread = max(delays.values()) - min(delays.values())
    if spread > run.sample_time:
        linear = [i for i, a in enumerate(run.axes) if a not in ROTARY_AXES]
        speed = np.linalg.norm(np.diff(run.setpoints.position[:, linear], axis=0), axis=1)
        if samples is not None:
            speed = speed[samples[1:]]
        top = float(np.max(speed, initial=0.0)) / run.sample_time
        each = ", ".join(f"{a} {d:.4g} s" for a, d in delays.items())
        notes.append(f"the models' reference dead times differ ({each}): the axes' commands are shifted against "
                     f"each other by up to {spread:.4g} s, which alone bends the path by up to {top * spread:.4g} "
                     f"mm at the toolpath's top speed {top:.4g} mm/s")
    pos = run.setpoints.position
    rotary = [a for i, a in enumerate(run.axes) if a in ROTARY_AXES and len(pos) and float(np.ptp(pos[:, i])) > 0]
    if rotary:
        notes.append(f"rotary axis {', '.join(rotary)} does not enter the contour error (measured on X, Y, Z in mm); "
                     "its tracking error is in mdeg")
    return notes


def _servo_period_notes(per_axis: dict[str, Any], run: _Truth) -> list[str]:
    """A warning when a simulated truth's servo period differs from the sampling of the record a model was
    identified from (newuser34: ``--truth machine.toml`` at 2 ms against models of a 1 ms capture said nothing). A
    digital position loop's dynamics change with its period (the controller's discrete law, a sample of computation
    delay: fadal-pid's gains unstable at 4 ms, README "A machine definition"), so the model predicts the loop it was
    identified on, not this machine's; mostly a slip, the machine file's ``sample_time`` or the wrong model. One
    sentence for the axes whose models share a period. A captured truth (``servo_period_of`` None) is sampled by its
    logger, not necessarily at the servo period: a note for a model from a finer record only (a coarser one is
    :func:`_model_notes`'s)."""
    periods: dict[float, list[str]] = {}
    for a in run.axes:
        ts = float(getattr(per_axis[a], "sample_time", 0.0) or 0.0)
        if ts > 0 and not math.isclose(ts, run.sample_time, rel_tol=1e-6):
            periods.setdefault(ts, []).append(a)
    if run.servo_period_of is None:  # a record's sampling, not a servo period: only a finer model is news
        return [f"the model of {', '.join(axes)} was identified from a record sampled every {ts:g} s, finer than the "
                f"capture's {run.sample_time:g} s: it runs at the capture's step (its continuous-time parameters "
                "discretised there), which predicts the loop it was identified on, not one closed at another period"
                for ts, axes in periods.items() if ts < run.sample_time]
    return [f"warning: the true machine's servo period {run.sample_time:g} s ({run.servo_period_of}) differs from "
            f"the {ts:g} s of the record the model of {', '.join(axes)} was identified from: a digital loop's "
            "dynamics change with its period, so the prediction is of the loop at the model's period, not of this "
            "machine (a machine file's sample_time in ms, or the model of another machine?)"
            for ts, axes in periods.items()]


def _truth_run(machine, sp: Setpoints, seed: int) -> tuple[np.ndarray, np.ndarray | None]:
    """One run of a simulated truth: the true position of each axis' measured point [mm] and, when
    the simulation tells them apart, the sensors' reading of it (else None)."""
    cap = machine.simulate(sp, seed=seed)
    if "measured_true" in cap.aux:
        return cap.aux["measured_true"], cap.measured
    return cap.measured, None


def _noisy(machine, axes: tuple[str, ...]) -> bool:
    """True when a moving axis of the machine has measurement noise (a random truth)."""
    for a in axes:
        noise = getattr(machine.axis(a), "noise", None) if a in machine.axes else None
        if noise is not None and float(getattr(noise, "std", 0.0)) > 0.0:
            return True
    return False
