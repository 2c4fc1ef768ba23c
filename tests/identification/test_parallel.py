"""identification.parallel: the maps give the results of a plain loop, in order, wherever they run."""

from __future__ import annotations

import os
import sys
import time

import numpy as np
import pytest

from identification.parallel import process_map, thread_map

linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="process_map forks on Linux only")


def test_thread_map_is_the_loop():
    assert thread_map(lambda k: k * k, range(7)) == [k * k for k in range(7)]


@linux_only
def test_process_map_runs_closures_in_this_and_a_forked_process_in_order(monkeypatch):
    monkeypatch.setenv("VCNC_THREADS", "2")
    data = np.arange(1000.0)  # inherited by the forked worker, never pickled

    def task(k):
        time.sleep(0.1)  # each process takes a task while the other works
        return k, float(data[k:].sum()), os.getpid()

    out = process_map(task, [5, 1, 9, 3])
    assert [o[0] for o in out] == [5, 1, 9, 3]
    assert [o[1] for o in out] == [float(data[k:].sum()) for k in (5, 1, 9, 3)]
    pids = {o[2] for o in out}
    assert len(pids) == 2 and os.getpid() in pids  # the caller is one of the two workers


@linux_only
def test_process_map_inside_a_worker_runs_serially(monkeypatch):
    monkeypatch.setenv("VCNC_THREADS", "2")

    def inner(k):
        pids = process_map(lambda j: os.getpid(), range(3))
        threads = thread_map(lambda j: j + k, range(3))
        return os.getpid(), pids, threads

    out = process_map(inner, [10, 20])
    for pid, pids, _ in out:
        assert pids == [pid] * 3  # no second level of workers: the worker itself ran them
    assert [t for _, _, t in out] == [[10, 11, 12], [20, 21, 22]]


@linux_only
def test_process_map_raises_a_task_s_exception(monkeypatch):
    monkeypatch.setenv("VCNC_THREADS", "2")

    def fail_on_two(k):
        if k == 2:
            raise ValueError(f"task {k} failed")
        return k

    with pytest.raises(ValueError, match="task 2 failed"):
        process_map(fail_on_two, [1, 2, 3])
    assert process_map(fail_on_two, [1, 3]) == [1, 3]  # the map is usable again afterwards


def test_process_map_with_one_worker_stays_in_this_process(monkeypatch):
    monkeypatch.setenv("VCNC_THREADS", "1")
    assert process_map(lambda k: (k, os.getpid()), [1, 2]) == [(1, os.getpid()), (2, os.getpid())]


@linux_only
def test_process_map_reports_a_worker_that_dies(monkeypatch):
    """A worker killed mid-task (os._exit stands in for a crash in compiled code) is an error, not a hang."""
    from concurrent.futures.process import BrokenProcessPool

    monkeypatch.setenv("VCNC_THREADS", "2")
    caller = os.getpid()

    def task(k):
        if os.getpid() != caller:
            os._exit(3)  # the forked worker dies on the first task it takes
        time.sleep(0.2)
        return k

    with pytest.raises(BrokenProcessPool, match="died"):
        process_map(task, [1, 2, 3])
    assert process_map(lambda k: k + 1, [1, 2]) == [2, 3]


def test_a_nested_thread_map_shares_its_items_with_a_free_worker(monkeypatch):
    """One long task's inner map spreads over the worker that finished its own task (issue #20)."""
    import threading

    monkeypatch.setenv("VCNC_THREADS", "2")

    def inner(j):
        time.sleep(0.05)  # long enough for the other worker to claim items
        return j * j, threading.current_thread().name

    def outer(k):
        return thread_map(inner, range(8)) if k == 0 else [(k, threading.current_thread().name)]

    out = thread_map(outer, [0, 1])
    assert [v for v, _ in out[0]] == [j * j for j in range(8)]
    assert out[1][0][0] == 1
    assert len({name for _, name in out[0]}) == 2  # both workers ran inner items


def test_nested_thread_maps_give_the_loop_and_raise_in_item_order(monkeypatch):
    monkeypatch.setenv("VCNC_THREADS", "2")

    def leaf(j):
        if j in (5, 3):
            raise ValueError(f"item {j}")
        return j + 1

    def mid(k):
        return thread_map(lambda j: sum(thread_map(lambda i: i * j, range(4))), range(k))

    assert thread_map(mid, range(5)) == [[sum(i * j for i in range(4)) for j in range(k)] for k in range(5)]
    with pytest.raises(ValueError, match="item 3"):
        thread_map(lambda k: thread_map(leaf, range(7)), [0, 1])
