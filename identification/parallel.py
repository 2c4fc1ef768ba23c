"""Independent simulations of the diagnosis run side by side on the machine's cores.

The compiled loops of :mod:`identification.kernels` release the GIL (``nogil=True``), so threads
run them in parallel with no copies of the capture. Each simulation is independent and its result
lands in its own slot, so the outcome is the same, bit for bit, for any number of workers.

``VCNC_THREADS`` (environment) caps the workers; the default is every core ``os.cpu_count()``
reports.

The linear algebra of the diagnosis is on tall, narrow matrices (a record's samples by a dozen
parameters), where a multi-threaded BLAS spends its time synchronising: an SVD of 21,648 x 11
took 34 ms with two OpenBLAS threads and 4.4 ms with one (measured 2026-11-23 on the 2-core
development machine). :func:`serial_blas` runs a block with one BLAS thread; the parallelism is
then the simulations'.
"""

from __future__ import annotations

import concurrent.futures
import os
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import Any

from threadpoolctl import threadpool_limits

__all__ = ["workers", "thread_map", "serial_blas"]

_POOL: concurrent.futures.ThreadPoolExecutor | None = None
_LOCK = threading.Lock()
_LOCAL = threading.local()


def workers() -> int:
    """Number of worker threads: ``VCNC_THREADS`` if set, else the number of cores."""
    env = os.environ.get("VCNC_THREADS", "").strip()
    if env.isdigit() and int(env) > 0:
        return int(env)
    return max(1, os.cpu_count() or 1)


def _pool() -> concurrent.futures.ThreadPoolExecutor:
    global _POOL
    with _LOCK:
        if _POOL is None:
            _POOL = concurrent.futures.ThreadPoolExecutor(max_workers=workers(), thread_name_prefix="vcnc-sim")
        return _POOL


def thread_map(fn: Callable[[Any], Any], items: Iterable[Any]) -> list[Any]:
    """``[fn(x) for x in items]``, evaluated on the worker threads (in order, same results).

    Also the map-like ``workers`` argument of ``scipy.optimize.least_squares``, which then computes
    its finite-difference Jacobian columns side by side.

    A call made from inside a worker runs serially, so nested maps never wait on themselves.
    """
    items = list(items)
    if len(items) < 2 or workers() < 2 or getattr(_LOCAL, "inside", False):
        return [fn(x) for x in items]

    def run(x):
        _LOCAL.inside = True
        try:
            return fn(x)
        finally:
            _LOCAL.inside = False

    return list(_pool().map(run, items))


@contextmanager
def serial_blas() -> Iterator[None]:
    """Run the block with one BLAS/LAPACK thread (module docstring)."""
    with threadpool_limits(limits=1, user_api="blas"):
        yield
