"""Parameter sweeps and Monte-Carlo identification studies on Dask (dask.distributed).

::

    import vcnc
    result = vcnc.sweep("study.toml", "results.parquet")            # LocalCluster on 127.0.0.1
    result = vcnc.sweep("study.toml", "results.csv", scheduler="tcp://127.0.0.1:8786")
    result.table                 # pyarrow Table, one row per point
    result.plot()                # contour error over feed and gain, diagnosis accuracy, ...

A sweep is a grid or a random sample over machines, controller gain scales, feeds, toolpaths,
measurement noise, injected effects and their magnitude, and noise seeds (spec schema in
:mod:`vcnc.sweeps.spec` and ``docs/sweep.md``). Each point simulates the machine variant on the
toolpath and records tracking and contour errors; optionally it identifies the axis (error of the
identified poles and parameters against the true loop) and diagnoses it (was the injected effect
named?). Results are appended as points finish; an interrupted sweep resumes without computing
finished points again; a failing point is recorded with its error and the sweep goes on.

Files: ``spec.py`` (schema, validation, points and their ids), ``point.py`` (the work of one
point), ``store.py`` (journal and results file), ``run.py`` (the Dask client side),
``plot.py`` (summary plot).
"""

from __future__ import annotations

from vcnc.sweeps.plot import plot_summary, write_plot
from vcnc.sweeps.run import PointFunction, SweepResult, sweep
from vcnc.sweeps.spec import MAGNITUDE_KEYS, SweepSpec, load_spec, parse_spec
from vcnc.sweeps.store import COLUMNS, read_results

__all__ = [
    "sweep",
    "SweepResult",
    "SweepSpec",
    "PointFunction",
    "load_spec",
    "parse_spec",
    "read_results",
    "plot_summary",
    "write_plot",
    "COLUMNS",
    "MAGNITUDE_KEYS",
]
