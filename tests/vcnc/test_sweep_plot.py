"""The sweep summary plot says why it is empty: no finished points, or none of its x axes varies."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pyarrow as pa

from vcnc.sweeps.plot import plot_summary


def _texts(fig) -> list[str]:  # noqa: ANN001 - matplotlib Figure
    return [t.get_text() for ax in fig.axes for t in ax.texts]


def _row(i: int, effect: str, status: str = "ok") -> dict:
    return {"id": f"p{i}", "status": status, "feed": 6000.0, "gain": 1.0, "effect": effect,
            "contour_max_um": 41.3, "ident_pole_error_pct": 11.7}


def test_finished_points_over_no_varied_axis_are_named_not_called_unfinished():
    fig = plot_summary(pa.Table.from_pylist([_row(0, "none"), _row(1, "backlash")]))
    assert _texts(fig) == ["nothing to plot: none of feed, gain, magnitude, noise\nvaries over the 2 finished points"]
    plt.close(fig)


def test_no_finished_points():
    fig = plot_summary(pa.Table.from_pylist([_row(0, "none", status="error")]))
    assert _texts(fig) == ["no finished points to plot"]
    plt.close(fig)


def test_a_varied_feed_draws_the_contour_panel():
    rows = [_row(0, "none"), {**_row(1, "none"), "feed": 12000.0, "contour_max_um": 60.0}]
    fig = plot_summary(pa.Table.from_pylist(rows))
    assert _texts(fig) == []
    assert fig.axes[0].get_title() == "max contour error over feed and gain"
    assert list(fig.axes[0].lines[0].get_ydata()) == [41.3, 60.0]
    plt.close(fig)
