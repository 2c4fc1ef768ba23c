"""Summary plot of sweep results: contour error over feed and gain, diagnosis accuracy over
effect magnitude, identification error over noise - each panel drawn when the results hold it."""

from __future__ import annotations

import math
import os
from collections import defaultdict
from typing import Any

import pyarrow as pa

__all__ = ["plot_summary", "write_plot"]


_X_LABELS = {
    "feed": "feed [mm/min]",
    "gain": "controller gain scale [-]",
    "magnitude": "effect magnitude [unit of the effect]",
    "noise": "measurement noise std [mm]",
}


def _ok_rows(table: pa.Table) -> list[dict[str, Any]]:
    return [r for r in table.to_pylist() if r.get("status") == "ok"]


def _finite(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _series(rows: list[dict], x: str, y: str, by: str) -> dict[Any, tuple[list, list]]:
    """Mean of ``y`` per ``x`` for each value of ``by``: {by: (xs, means)}."""
    acc: dict[Any, dict[Any, list[float]]] = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if _finite(r.get(x)) and (_finite(r.get(y)) or isinstance(r.get(y), bool)):
            acc[r.get(by)][r[x]].append(float(r[y]))
    out = {}
    for key, d in acc.items():
        xs = sorted(d)
        out[key] = (xs, [sum(d[v]) / len(d[v]) for v in xs])
    return out


def _varies(rows: list[dict], column: str) -> bool:
    return len({r[column] for r in rows if _finite(r.get(column))}) >= 2


def _panels(rows: list[dict]) -> list[tuple[str, str, str, str, str]]:
    """(x, y, by, y label, title) of the panels the rows can fill."""
    panels = []
    metric = "contour_max_um" if any(_finite(r.get("contour_max_um")) for r in rows) else "tracking_max_um"
    label = "max contour error [um]" if metric == "contour_max_um" else "max tracking error [um]"
    name = label.split(" [")[0]
    if _varies(rows, "feed"):
        panels.append(("feed", metric, "gain", label, f"{name} over feed and gain"))
    elif _varies(rows, "gain"):
        panels.append(("gain", metric, "toolpath", label, f"{name} over gain"))
    if any(isinstance(r.get("diag_hit"), bool) for r in rows) and _varies(rows, "magnitude"):
        panels.append(("magnitude", "diag_hit", "effect", "diagnosis accuracy [-]",
                       "diagnosis accuracy over effect magnitude"))
    if any(_finite(r.get("ident_pole_error_pct")) for r in rows):
        x = next((c for c in ("noise", "magnitude", "gain", "feed") if _varies(rows, c)), None)
        if x is not None:
            panels.append((x, "ident_pole_error_pct", "effect", "pole error [%]", f"identification error over {x}"))
    return panels


def plot_summary(table: pa.Table, *, ax=None):  # noqa: ANN001, ANN201 - matplotlib Axes / Figure
    """Draw the summary panels of a results table; returns the Figure.

    Panels (each only when the results have its data): the largest contour error (tracking error
    for one-axis toolpaths) over feed [mm/min], one line per gain scale; the share of points whose
    injected effect the diagnosis named, over magnitude, one line per effect; the identification
    pole error [%] over noise [mm], one line per effect. Values are means over the other
    parameters. ``ax`` (one Axes or a sequence) receives the panels in that order; without it a
    new pyplot figure is made.
    """
    rows = _ok_rows(table)
    panels = _panels(rows)
    if ax is None:
        import matplotlib.pyplot as plt

        n = max(1, len(panels))
        fig, axes = plt.subplots(1, n, figsize=(5.5 * n, 4.0), squeeze=False)
        axes = list(axes[0])
    else:
        axes = list(ax) if isinstance(ax, (list, tuple)) else [ax]
        fig = axes[0].figure
    _draw(rows, panels, axes)
    return fig


def _draw(rows: list[dict], panels: list[tuple[str, str, str, str, str]], axes: list[Any]) -> None:
    if not panels:
        message = "no finished points to plot" if not rows else (
            f"nothing to plot: none of feed, gain, magnitude, noise\nvaries over the {len(rows)} finished points")
        axes[0].text(0.5, 0.5, message, ha="center", va="center", transform=axes[0].transAxes)
        axes[0].set_axis_off()
        return
    for a, (x, y, by, ylabel, title) in zip(axes, panels):
        for key, (xs, ys) in sorted(_series(rows, x, y, by).items(), key=lambda kv: str(kv[0])):
            a.plot(xs, ys, marker="o", label=f"{by} = {key}")
        a.set_xlabel(_X_LABELS[x])
        a.set_ylabel(ylabel)
        a.set_title(title)
        a.grid(True, alpha=0.3)
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize="small")
    axes[0].figure.tight_layout()


def write_plot(table: pa.Table, path: str | os.PathLike[str]) -> None:
    """Write the summary plot to an image file (atomic; no pyplot, no GUI backend)."""
    from matplotlib.figure import Figure

    from vcnc.core.io import atomic_path

    rows = _ok_rows(table)
    panels = _panels(rows)
    n = max(1, len(panels))
    fig = Figure(figsize=(5.5 * n, 4.0))
    axes = list(fig.subplots(1, n, squeeze=False)[0])
    _draw(rows, panels, axes)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=os.path.splitext(str(path))[1].lstrip(".").lower() or "png", dpi=110)
