"""Running a sweep on Dask (dask.distributed): local cluster or a scheduler by address.

The client submits one task per point not yet in the results (task key ``sweep-point-<id>``),
collects results as they complete and appends each to the journal. A worker that dies mid-task
is Dask's to handle: the scheduler reruns its tasks on the remaining workers. The writer keeps
one row per point id, so a point reported twice is written once.
"""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import os
import sys
import time
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import Any

import pyarrow as pa

from vcnc.core.errors import InputError, VcncError
from vcnc.sweeps.spec import SweepSpec, load_spec
from vcnc.sweeps.store import ResultStore

__all__ = ["sweep", "SweepResult", "PointFunction"]

log = logging.getLogger(__name__)

#: what runs on a worker: a task dict (``id``, parameters, ``geometry``, ``outputs``) in,
#: a row out (``id``, ``status``, metrics); it should not raise
PointFunction = Callable[[Mapping[str, Any]], Mapping[str, Any]]

#: parameter columns copied from the task into each row (the worker returns only metrics)
_TASK_COLUMNS = ("machine", "toolpath", "feed", "gain", "noise", "effect", "magnitude", "seed", "axis", "profile")

#: tasks in flight per worker thread; more are submitted as results come back
_IN_FLIGHT_PER_THREAD = 8


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class SweepResult:
    """The results of a sweep.

    Attributes
    ----------
    table : pyarrow.Table
        One row per point (this run's and earlier runs'): parameters, ``status``, ``error``,
        metrics and timings (columns in :data:`vcnc.sweeps.store.COLUMNS`).
    path : Path
        The results file.
    computed : int
        Points computed in this run.
    skipped : int
        Points of the spec found finished in earlier runs (resumed).
    failed : int
        Points of this run recorded with ``status = "error"``.
    elapsed_s : float
        Wall time of the computation in this run (cluster start excluded) [s].
    workers : int
        Workers the computation ran on.
    """

    table: pa.Table
    path: Path
    computed: int = 0
    skipped: int = 0
    failed: int = 0
    elapsed_s: float = 0.0
    workers: int = 0

    def __len__(self) -> int:
        return self.table.num_rows

    @property
    def points_per_s(self) -> float:
        """Points computed per second of wall time in this run."""
        return self.computed / self.elapsed_s if self.elapsed_s > 0 else float("nan")

    def rows(self) -> list[dict[str, Any]]:
        """The rows as dicts."""
        return self.table.to_pylist()

    def column(self, name: str) -> list[Any]:
        """One column as a list."""
        return self.table.column(name).to_pylist()

    def to_pandas(self):  # noqa: ANN201 - pandas.DataFrame (pandas is optional)
        """The table as a pandas DataFrame (needs pandas)."""
        return self.table.to_pandas()

    def plot(self, ax=None):  # noqa: ANN001, ANN201 - matplotlib
        """Summary plot (:func:`vcnc.sweeps.plot.plot_summary`); returns the Figure."""
        from vcnc.sweeps.plot import plot_summary

        return plot_summary(self.table, ax=ax)


def _check_address(address: str) -> None:
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        _, location = parse_address(address)
        parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise InputError(f"scheduler address {address!r} is not valid ({exc}); expected tcp://HOST:PORT") from None


@contextlib.contextmanager
def _quiet_distributed() -> Iterator[None]:
    """Keep dask.distributed's INFO chatter (cluster start and stop) off the console unless the
    root logger is at DEBUG."""
    import distributed  # noqa: F401 - it sets its loggers' levels on import; adjust them after

    logger = logging.getLogger("distributed")
    old = logger.level
    if logging.getLogger().getEffectiveLevel() > logging.DEBUG:
        logger.setLevel(logging.WARNING)
    try:
        yield
    finally:
        logger.setLevel(old)


@contextlib.contextmanager
def _client(scheduler: str | None, workers: int | None, n_points: int) -> Iterator[Any]:
    """A dask.distributed Client: to ``scheduler``, or to a LocalCluster on 127.0.0.1."""
    from distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise VcncError(f"cannot connect to the Dask scheduler at {scheduler}: {exc}") from None
        try:
            yield client
        finally:
            client.close()
        return
    n = workers or min(os.cpu_count() or 1, max(n_points, 1))
    cluster = LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
        # no dashboard; the scheduler's small HTTP server (health, metrics) on a free loopback port
        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        silence_logs=logging.ERROR,
    )
    try:
        client = Client(cluster)
        try:
            yield client
        finally:
            client.close()
    finally:
        cluster.close()


def _progress(total: int, enabled: bool | None) -> Any:
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=total, unit="point", desc="sweep")


def sweep(
    spec: SweepSpec | str | os.PathLike[str],
    output: str | os.PathLike[str],
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    retry_failed: bool = False,
    point_function: PointFunction | None = None,
    callback: Callable[[Mapping[str, Any]], None] | None = None,
    timeout: float | None = None,
    progress: bool | None = None,
) -> SweepResult:
    """Run a parameter sweep on Dask; results go to ``output`` incrementally and resume.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep (a spec TOML file, schema in :mod:`vcnc.sweeps.spec`).
    output : path
        ``*.parquet`` or ``*.csv``. Points whose id is already in it (or in its journal
        ``<output>.partial.jsonl`` left by an interrupted run) are not computed again.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:port``); its workers must be able to
        import vcnc and read the machine files named in the spec. Default: a LocalCluster of
        ``workers`` processes on 127.0.0.1.
    workers : int, optional
        Local workers (one thread each); default the number of CPUs. Not with ``scheduler``.
    retry_failed : bool
        Compute again the points recorded with ``status = "error"``.
    point_function : callable, optional
        Runs on the workers: task dict in, row out (default :func:`vcnc.sweeps.point.run_point`,
        the real simulation). Must be importable by the workers.
    callback : callable, optional
        Called on the client with each row right after it is written (e.g. to watch progress).
    timeout : float, optional
        Give up after this many seconds [s] (the rows so far are kept); VcncError.
    progress : bool, optional
        Progress bar; default only on a terminal.

    Returns
    -------
    SweepResult

    Raises
    ------
    InputError
        Bad spec, output that is not ``.parquet``/``.csv`` or cannot be read back, ``workers``
        with ``scheduler``. Nothing is written then.
    VcncError
        Scheduler unreachable, timeout, points lost with the scheduler; the rows finished are kept
        and running the sweep again resumes.
    """
    if not isinstance(spec, SweepSpec):
        spec = load_spec(spec)
    if scheduler is not None:
        _check_address(scheduler)
    if scheduler is not None and workers is not None:
        raise InputError("give either a scheduler address or a number of local workers, not both")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InputError(f"workers must be an integer >= 1, got {workers!r}")
    store = ResultStore(output)
    points = spec.points()
    done = store.load()
    todo = [p for p in points
            if p["id"] not in done or (retry_failed and done[p["id"]].get("status") == "error")]
    skipped = len(points) - len(todo)
    log.info("sweep: %d points, %d finished earlier, %d to compute", len(points), skipped, len(todo))
    if not todo:
        table = store.consolidate()
        return SweepResult(table=table, path=store.output, skipped=skipped)
    if point_function is None:
        from vcnc.sweeps.point import run_point

        point_function = run_point
    with _quiet_distributed(), _client(scheduler, workers, len(todo)) as client:
        return _run(client, store, todo, point_function, callback=callback, timeout=timeout, progress=progress,
                    skipped=skipped)


def _run(
    client: Any,
    store: ResultStore,
    todo: list[dict[str, Any]],
    fn: PointFunction,
    *,
    callback: Callable[[Mapping[str, Any]], None] | None,
    timeout: float | None,
    progress: bool | None,
    skipped: int,
) -> SweepResult:
    from distributed import as_completed

    by_id = {p["id"]: p for p in todo}
    nthreads = client.nthreads()
    if not nthreads:
        log.warning("the Dask scheduler has no workers yet; points wait until workers join")
    threads = max(1, sum(nthreads.values()))
    n_workers = len(nthreads)
    window = max(32, _IN_FLIGHT_PER_THREAD * threads)
    queue = list(reversed(todo))
    written: set[str] = set()
    failed = 0
    lost: list[str] = []
    bar = _progress(len(todo), progress)
    t0 = time.perf_counter()
    deadline = None if timeout is None else t0 + timeout
    store.open()
    futures: dict[Any, str] = {}

    def submit() -> Any:
        task = queue.pop()
        fut = client.submit(fn, task, key=f"sweep-point-{task['id']}", pure=False)
        futures[fut] = task["id"]
        return fut

    try:
        ac = as_completed([submit() for _ in range(min(window, len(queue)))], with_results=True,
                          raise_errors=False, timeout=timeout)
        for fut, result in ac:
            pid = futures.pop(fut)
            if fut.status == "cancelled":
                # not a result of the point (scheduler lost, task cancelled): left for the next
                # run, and nothing more is submitted to a cluster that drops tasks
                lost.append(pid)
                lost.extend(t["id"] for t in queue)
                queue.clear()
                continue
            if queue:
                ac.add(submit())
            if pid in written:
                continue  # exactly once: the first row of a point is the one kept
            row = _row(by_id[pid], fut, result)
            store.append(row)
            written.add(pid)
            failed += row.get("status") != "ok"
            if bar is not None:
                bar.update(1)
            if callback is not None:
                callback(row)
            if deadline is not None and time.perf_counter() > deadline and queue:
                raise TimeoutError
    except TimeoutError:
        raise VcncError(
            f"sweep timed out after {timeout} s with {len(written)} of {len(todo)} points computed; "
            f"they are kept in {store.output} - run the sweep again to resume"
        ) from None
    finally:
        elapsed = time.perf_counter() - t0
        if bar is not None:
            bar.close()
        if futures:
            client.cancel(list(futures))
        # an interrupted or failed run still leaves one valid results file
        table = store.consolidate()
    if lost:
        raise VcncError(
            f"{len(lost)} points were lost by the cluster (scheduler or client restarted?); the {len(written)} "
            f"finished are in {store.output} - run the sweep again to compute the rest"
        )
    return SweepResult(table=table, path=store.output, computed=len(written), skipped=skipped, failed=failed,
                       elapsed_s=elapsed, workers=n_workers)


def _row(task: Mapping[str, Any], fut: Any, result: Any) -> dict[str, Any]:
    row: dict[str, Any] = {"id": task["id"]}
    row.update({k: task.get(k) for k in _TASK_COLUMNS})
    if fut.status == "error":
        exc = result[1] if isinstance(result, tuple) and len(result) == 3 else result
        row.update(status="error", error=f"{type(exc).__name__}: {exc}")
    elif not isinstance(result, Mapping):
        row.update(status="error", error=f"point function returned {type(result).__name__}, expected a dict")
    else:
        res = dict(result)
        res.pop("id", None)
        row.update(res)
        row.setdefault("status", "ok")
    return row
