"""Independent simulations of the diagnosis run side by side on the machine's cores.

The compiled loops of :mod:`identification.kernels` release the GIL (``nogil=True``), so threads
run them in parallel with no copies of the capture. Each simulation is independent and its result
lands in its own slot, so the outcome is the same, bit for bit, for any number of workers.

``VCNC_THREADS`` (environment) caps the workers; the default is every core ``os.cpu_count()``
reports.

Coarse tasks that are mostly Python and small numpy steps between the compiled loops (a joint
refit of the diagnosis: scipy's trust-region iterations around the simulations) do not scale on
threads, which contend for the GIL: two refits of the long capture of ``benchmarks/diagnosis.py``
took 0.47 s on one thread and 0.39 s on two, while two processes each running the whole
diagnosis on one thread took as long as one alone (2.6 s; 2026-11-23, the 2-core development
machine). :func:`process_map` runs such tasks in this process and forked worker processes (Linux
``fork``: the workers share the capture and the compiled code copy-on-write, and only the results
are pickled back); inside such a task every map runs serially, so the results are the same, bit
for bit.

The linear algebra of the diagnosis is on tall, narrow matrices (a record's samples by a dozen
parameters), where a multi-threaded BLAS spends its time synchronising: an SVD of 21,648 x 11
took 34 ms with two OpenBLAS threads and 4.4 ms with one (measured 2026-11-23 on the 2-core
development machine). :func:`serial_blas` runs a block with one BLAS thread; the parallelism is
then the simulations'.
"""

from __future__ import annotations

import concurrent.futures
import os
import pickle
import struct
import sys
import threading
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from typing import Any

from threadpoolctl import threadpool_limits

__all__ = ["workers", "thread_map", "process_map", "serial_blas"]

_POOL: concurrent.futures.ThreadPoolExecutor | None = None
_POOL_SIZE = 0
_LOCK = threading.Lock()
_LOCAL = threading.local()
#: Most tasks :func:`process_map` forks for: their indices (4 bytes each) must fit a pipe's 64 KiB buffer,
#: written before anyone reads it (more coarse tasks than this run on threads).
_MAX_FORK_TASKS = 16_000
#: True in a worker process of :func:`process_map`: its maps run serially.
_FORKED = False


def workers() -> int:
    """Number of worker threads: ``VCNC_THREADS`` if set, else the number of cores."""
    env = os.environ.get("VCNC_THREADS", "").strip()
    if env.isdigit() and int(env) > 0:
        return int(env)
    return max(1, os.cpu_count() or 1)


def _pool() -> concurrent.futures.ThreadPoolExecutor:
    """The worker threads, as many as :func:`workers` says now (a changed ``VCNC_THREADS`` gets a
    new pool; the old one finishes its tasks and exits)."""
    global _POOL, _POOL_SIZE
    with _LOCK:
        n = workers()
        if _POOL is None or n != _POOL_SIZE:
            if _POOL is not None:
                _POOL.shutdown(wait=False)
            _POOL = concurrent.futures.ThreadPoolExecutor(max_workers=n, thread_name_prefix="vcnc-sim")
            _POOL_SIZE = n
        return _POOL


def thread_map(fn: Callable[[Any], Any], items: Iterable[Any]) -> list[Any]:
    """``[fn(x) for x in items]``, evaluated on the worker threads (in order, same results).

    Also the map-like ``workers`` argument of ``scipy.optimize.least_squares``, which then computes
    its finite-difference Jacobian columns side by side.

    A call made from inside a worker (a nested map: the frequencies of one search while the other
    searches run) shares its items with the pool (:func:`_shared_map`): a worker that has finished
    its own tasks takes them up, so that one long task does not keep a core idle.
    """
    items = list(items)
    if len(items) < 2 or workers() < 2 or _FORKED or getattr(_LOCAL, "serial", False):
        return [fn(x) for x in items]
    if getattr(_LOCAL, "inside", False):
        return _shared_map(fn, items)

    def run(x):
        _LOCAL.inside = True
        try:
            return fn(x)
        finally:
            _LOCAL.inside = False

    return list(_pool().map(run, items))


def _shared_map(fn: Callable[[Any], Any], items: list[Any]) -> list[Any]:
    """A nested :func:`thread_map` called on a worker thread: each item runs once, on whichever
    thread claims it first, the caller or a free worker.

    The caller offers every item to the pool, then runs every item nobody has claimed yet itself
    and waits only for items another thread is running, never for a queued offer (all the
    workers could be such callers, each waiting on the others' queue: a deadlock). Offers that
    find their item claimed do nothing. Each result lands in its own slot and an exception is
    raised in item order, so the outcome is that of the serial loop.
    """
    n = len(items)
    claimed = [False] * n
    done = [threading.Event() for _ in range(n)]
    out: list[Any] = [None] * n
    errors: list[BaseException | None] = [None] * n
    lock = threading.Lock()

    def claim(i: int) -> bool:
        with lock:
            if claimed[i]:
                return False
            claimed[i] = True
            return True

    def run(i: int) -> None:
        try:
            out[i] = fn(items[i])
        except BaseException as exc:  # noqa: BLE001 - re-raised below, in item order
            errors[i] = exc
        finally:
            done[i].set()

    def offer(i: int) -> None:
        if claim(i):
            _LOCAL.inside = True
            try:
                run(i)
            finally:
                _LOCAL.inside = False

    pool = _pool()
    offers = [pool.submit(offer, i) for i in range(n)]
    for i in range(n):
        if claim(i):
            run(i)
    for i in range(n):
        done[i].wait()
    for f in offers:
        f.cancel()
    # an offer cancelled, or run after its item was claimed, stays in the pool's queue until a free worker
    # drops it, holding this call's cells: the results and ``fn`` with what it captured. Released here, or
    # the nested maps of a long search kept every result they returned (the sensitivities of the resonance
    # search: 170 MB on a 172,703-sample record, benchmarks/identification.py, memory)
    results, out, fn, items = out, None, None, None
    for exc in errors:
        if exc is not None:
            raise exc
    return results


def process_map(fn: Callable[[Any], Any], items: Iterable[Any]) -> list[Any]:
    """``[fn(x) for x in items]``, evaluated in forked worker processes (in order, same results).

    For coarse tasks that hold the GIL much of the time (module docstring). ``fn`` may be a
    closure: the workers are forked after it exists and inherit it; only the task indices and
    the results (which must pickle) cross the process boundary. The calling process is one of the
    workers: it forks ``workers() - 1`` children and every process takes the next task in the
    order given when it is free (:func:`_fork_map`). An exception of a task (pickled back) is raised
    here, the first in item order; a child that dies (killed, a crash in compiled code) raises
    ``concurrent.futures.process.BrokenProcessPool``. Where ``fork`` is not the platform's way (not
    Linux), with fewer than two tasks or workers, more than :data:`_MAX_FORK_TASKS` tasks, or when
    called from inside a worker, this is :func:`thread_map`.
    """
    items = list(items)
    n = min(workers(), len(items))
    if n < 2 or _FORKED or getattr(_LOCAL, "inside", False) or getattr(_LOCAL, "serial", False) \
            or not sys.platform.startswith("linux") or len(items) > _MAX_FORK_TASKS:
        return thread_map(fn, items)
    return _fork_map(fn, items, n)


def _fork_map(fn: Callable[[Any], Any], items: list[Any], n: int) -> list[Any]:
    """:func:`process_map` on this process and ``n - 1`` forked children.

    The task indices wait in a pipe that every process reads 4 bytes at a time (a read of a pipe is
    atomic), so a free process takes the next task. Each child sends ``(index, ok, result or
    exception)`` records back on its own pipe, read by a thread here while this process works on
    its own share with serial maps (as a child does), and leaves with ``os._exit`` without waiting
    for anything; a thread reaps it. Compared with ``concurrent.futures.ProcessPoolExecutor`` this
    saves a fork, the executor's start-up and the wait for the children's exit (about 50 ms a call
    on the long capture of ``benchmarks/diagnosis.py``).
    """
    r_claim, w_claim = os.pipe()
    os.write(w_claim, struct.pack(f"<{len(items)}i", *range(len(items))))  # fits the pipe: never blocks
    os.close(w_claim)
    results: dict[int, tuple[bool, Any]] = {}
    readers, pids = [], []
    try:
        for _ in range(n - 1):
            r_res, w_res = os.pipe()
            pid = os.fork()
            if pid == 0:  # pragma: no cover - the child (coverage does not follow a fork)
                os.close(r_res)
                _child(fn, items, r_claim, w_res)
            os.close(w_res)
            pids.append(pid)
            reader = threading.Thread(target=_read_records, args=(r_res, results), daemon=True)
            reader.start()
            readers.append(reader)
        _LOCAL.serial = True
        try:
            while (i := _claim(r_claim)) is not None:
                results[i] = _attempt(fn, items[i])
        finally:
            _LOCAL.serial = False
    finally:
        os.close(r_claim)
        for reader in readers:
            reader.join()
        for pid in pids:
            threading.Thread(target=os.waitpid, args=(pid, 0), daemon=True).start()
    lost = [i for i in range(len(items)) if i not in results]
    if lost:
        raise BrokenProcessPool(f"a worker process died before returning task(s) {lost}")
    out = []
    for i in range(len(items)):
        ok, value = results[i]
        if not ok:
            raise value
        out.append(value)
    return out


def _claim(fd: int) -> int | None:
    """The next task index from the claim pipe, or None when none is left."""
    b = os.read(fd, 4)
    return struct.unpack("<i", b)[0] if len(b) == 4 else None


def _attempt(fn: Callable[[Any], Any], item: Any) -> tuple[bool, Any]:
    try:
        return True, fn(item)
    except Exception as exc:  # noqa: BLE001 - handed to the caller of process_map
        return False, exc


def _child(fn: Callable[[Any], Any], items: list[Any], r_claim: int, w_res: int) -> None:  # pragma: no cover
    """A forked worker: run claimed tasks, send each result, leave without running the parent's code."""
    global _FORKED
    _FORKED = True
    try:
        with os.fdopen(w_res, "wb") as out:
            while (i := _claim(r_claim)) is not None:
                ok, value = _attempt(fn, items[i])
                try:
                    record = pickle.dumps((i, ok, value))
                except Exception as exc:  # noqa: BLE001 - an unpicklable result or exception
                    record = pickle.dumps((i, False, RuntimeError(f"task {i}: result does not pickle: {exc}")))
                out.write(struct.pack("<q", len(record)) + record)
                out.flush()
    finally:
        os._exit(0)


def _read_records(fd: int, results: dict[int, tuple[bool, Any]]) -> None:
    """Collect a child's ``(index, ok, value)`` records until it closes its pipe."""
    with os.fdopen(fd, "rb") as f:
        while len(head := f.read(8)) == 8:
            body = f.read(struct.unpack("<q", head)[0])
            i, ok, value = pickle.loads(body)
            results[i] = (ok, value)


@contextmanager
def serial_blas() -> Iterator[None]:
    """Run the block with one BLAS/LAPACK thread (module docstring)."""
    with threadpool_limits(limits=1, user_api="blas"):
        yield
