"""The figure of a model's prediction of a record: the measured and predicted tracking errors and the residual
(``vcnc identify --report``, ``vcnc identify --check --report``)."""

from __future__ import annotations

__all__ = ["tracking_figure"]


def tracking_figure(t, xr, x, xp, unit: str):
    """The measured and predicted tracking error ``xr - x``, ``xr - xp`` over ``t`` [s] and the residual ``x - xp``
    (positions [mm], drawn in ``unit``, um or mdeg): the figure of ``vcnc identify --report`` and of ``--check``."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 6))
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    ax1.plot(t, (xr - x) * 1e3, label="measured tracking error")
    ax1.plot(t, (xr - xp) * 1e3, "--", label="predicted tracking error")
    ax1.set_ylabel(f"x_r - x [{unit}]")
    ax1.legend()
    ax2.plot(t, (x - xp) * 1e3, color="C3")
    ax2.set_ylabel(f"residual x - x_pred [{unit}]")
    ax2.set_xlabel("time [s]")
    return fig
