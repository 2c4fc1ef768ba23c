"""Sweeps on a real Dask cluster: a scheduler and two worker processes on 127.0.0.1.

The cluster is started once for the module (``python -m dask scheduler`` / ``dask worker``, no
nanny, so killing a worker's process kills the worker). The last test kills a worker while it
computes a point and checks that every point is in the results exactly once.
"""

from __future__ import annotations

import functools
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import cloudpickle
import pytest

from vcnc.cli import main
from vcnc.sweeps import read_results, sweep

pytestmark = [pytest.mark.filterwarnings("ignore::DeprecationWarning"), pytest.mark.slow]  # starts Dask clusters

# the workers receive this module's point function by value: they need not import the tests
cloudpickle.register_pickle_by_value(sys.modules[__name__])

#: upper bound for anything the cluster does in these tests [s]
LIMIT_S = 60.0


def _start(args: list[str], log: Path) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[2]))
    fh = open(log, "w")  # noqa: SIM115 - closed with the process
    return subprocess.Popen([sys.executable, "-m", "dask", *args], stdout=fh, stderr=subprocess.STDOUT, env=env,
                            start_new_session=True)


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=10)


class Cluster:
    def __init__(self, tmp: Path) -> None:
        self.tmp = tmp
        self.file = tmp / "scheduler.json"
        self.scheduler = _start(["scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                                 "--dashboard-address", "127.0.0.1:0", "--scheduler-file", str(self.file)],
                                tmp / "scheduler.log")
        self.workers: dict[str, subprocess.Popen] = {}
        deadline = time.monotonic() + LIMIT_S
        while not self.file.exists() or not self.file.read_text().strip():
            if time.monotonic() > deadline or self.scheduler.poll() is not None:
                raise RuntimeError(f"scheduler did not start: {(tmp / 'scheduler.log').read_text()}")
            time.sleep(0.1)
        self.address = json.loads(self.file.read_text())["address"]
        assert self.address.startswith("tcp://127.0.0.1:")
        for name in ("w1", "w2"):
            self.workers[name] = _start(
                ["worker", self.address, "--nthreads", "1", "--no-nanny", "--no-dashboard", "--host", "127.0.0.1",
                 "--name", name, "--death-timeout", "30"], tmp / f"{name}.log")
        from distributed import Client

        with Client(self.address, timeout=LIMIT_S) as c:
            c.wait_for_workers(2, timeout=LIMIT_S)

    def close(self) -> None:
        for w in self.workers.values():
            _stop(w)
        _stop(self.scheduler)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    c = Cluster(tmp_path_factory.mktemp("dask"))
    try:
        yield c
    finally:
        c.close()


def slow_point(task, *, marker_dir: str, delay: float):
    """Test point: marks its start and end (by process id), sleeps, fails for gain 13."""
    pid = os.getpid()
    d = Path(marker_dir)
    (d / f"{task['id']}.{pid}.start").touch()
    time.sleep(delay)
    if task["gain"] == 13.0:
        raise RuntimeError("unlucky gain")
    (d / f"{task['id']}.{pid}.done").touch()
    return {"status": "ok", "value": task["feed"] * task["gain"], "pid": pid}


def _spec(tmp: Path, feeds: str, gains: str = "[1.0, 2.0]") -> Path:
    f = tmp / f"spec-{abs(hash((feeds, gains)))}.toml"
    f.write_text(f"[parameters]\nfeed = {feeds}\ngain = {gains}\n")
    return f


def _markers(d: Path, kind: str) -> list[tuple[str, int]]:
    return [(p.name.split(".")[0], int(p.name.split(".")[1])) for p in d.glob(f"*.{kind}")]


def test_failing_point_is_recorded_and_resume_skips_finished_points(cluster, tmp_path):
    out = tmp_path / "r.csv"
    m1 = tmp_path / "m1"
    m1.mkdir()
    fn = functools.partial(slow_point, marker_dir=str(m1), delay=0.05)
    r1 = sweep(_spec(tmp_path, "[100, 200]", "[1.0, 13.0]"), out, scheduler=cluster.address, point_function=fn,
               timeout=LIMIT_S)
    assert (r1.computed, r1.skipped, r1.failed) == (4, 0, 2)
    rows = {(r["feed"], r["gain"]): r for r in read_results(out).to_pylist()}
    assert rows[(100.0, 13.0)]["status"] == "error" and "RuntimeError: unlucky gain" in rows[(100.0, 13.0)]["error"]
    assert rows[(200.0, 1.0)]["status"] == "ok" and rows[(200.0, 1.0)]["value"] == 200.0

    # a bigger spec: only the new points are computed, the old rows (and the error) are kept
    m2 = tmp_path / "m2"
    m2.mkdir()
    fn2 = functools.partial(slow_point, marker_dir=str(m2), delay=0.05)
    r2 = sweep(_spec(tmp_path, "[100, 200, 300]", "[1.0, 13.0]"), out, scheduler=cluster.address,
               point_function=fn2, timeout=LIMIT_S)
    assert (r2.computed, r2.skipped, len(r2)) == (2, 4, 6)
    assert {i for i, _ in _markers(m2, "start")} == {r["id"] for r in r2.rows() if r["feed"] == 300.0}
    # retry_failed computes the failed points (gain 13) again, and only those
    r3 = sweep(_spec(tmp_path, "[100, 200, 300]", "[1.0, 13.0]"), out, scheduler=cluster.address,
               point_function=fn2, retry_failed=True, timeout=LIMIT_S)
    assert (r3.computed, r3.skipped, r3.failed, len(r3)) == (3, 3, 3, 6)


def test_interrupted_sweep_keeps_its_rows_and_resumes(cluster, tmp_path):
    out = tmp_path / "r.parquet"
    spec = _spec(tmp_path, "[1, 2, 3, 4, 5, 6]")
    m1, m2 = tmp_path / "m1", tmp_path / "m2"
    m1.mkdir()
    m2.mkdir()
    seen = []

    def stop_after_four(row):
        seen.append(row["id"])
        if len(seen) == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sweep(spec, out, scheduler=cluster.address, callback=stop_after_four, timeout=LIMIT_S,
              point_function=functools.partial(slow_point, marker_dir=str(m1), delay=0.1))
    partial = read_results(out).column("id").to_pylist()
    assert sorted(partial) == sorted(seen)
    r = sweep(spec, out, scheduler=cluster.address, timeout=LIMIT_S,
              point_function=functools.partial(slow_point, marker_dir=str(m2), delay=0.05))
    assert (r.computed, r.skipped, len(r)) == (8, 4, 12)
    assert not {i for i, _ in _markers(m2, "start")} & set(seen)
    assert sorted(r.column("id")) == sorted(set(r.column("id")))


def test_real_simulation_identification_and_failure(cluster, tmp_path):
    """The default point function: real machine, interpolation, simulation, contour, identification."""
    f = tmp_path / "real.toml"
    (tmp_path / "part.nc").write_text("G00 X0 Y0\nG01 X20 Y0 F6000\nG01 X20 Y10\nG01 X0 Y0\nM30\n")
    f.write_text(textwrap.dedent("""
        [parameters]
        machine = ["fadal-pid", "emps"]    # emps has one axis: a circle on it fails
        toolpath = ["circle", "identification", "part.nc"]
        feed = [6000.0]
        [toolpath]
        moves = 30
        [outputs]
        identify = true
    """))
    r = sweep(f, tmp_path / "real.parquet", scheduler=cluster.address, timeout=3 * LIMIT_S)
    rows = {(x["machine"], x["toolpath"]): x for x in r.rows()}
    assert len(rows) == 6 and r.computed == 6
    part = rows[("fadal-pid", "part.nc")]
    assert part["status"] == "ok" and part["feed"] is None and part["contour_max_um"] > 0, part
    circle, ident = rows[("fadal-pid", "circle")], rows[("fadal-pid", "identification")]
    assert circle["status"] == "ok", circle["error"]
    assert ident["status"] == "ok", ident["error"]
    assert 1.0 < circle["contour_max_um"] < 500.0 and circle["contour_rms_um"] <= circle["contour_max_um"]
    assert ident["contour_max_um"] is None  # one moving axis: no contour
    assert ident["ident_pole_error_pct"] < 25.0 and ident["ident_fit_rms_um"] > 0
    assert ident["t_identify_s"] > 0 and ident["worker"].startswith("tcp://127.0.0.1:")
    assert rows[("emps", "identification")]["status"] == "ok", rows[("emps", "identification")]["error"]
    for tp in ("circle", "part.nc"):
        bad = rows[("emps", tp)]
        assert bad["status"] == "error" and "axis 'y'" in bad["error"], bad
    assert r.failed == 2


def test_cli_sweep_on_the_scheduler_and_bad_input(cluster, tmp_path, capsys):
    from vcnc.engine.machine import builtin_machine_text

    text = builtin_machine_text("fadal-pid").replace('name = "fadal-pid"', 'name = "mill"')
    (tmp_path / "mill.toml").write_text(text)
    f = tmp_path / "cli.toml"
    f.write_text('[parameters]\nmachine = ["fadal-pid", "mill.toml"]\ntoolpath = "diamond"\nfeed = [3000, 9000]\n')
    out = tmp_path / "cli.csv"
    png = tmp_path / "summary.png"
    assert main(["sweep", str(f), "-o", str(out), "--scheduler", cluster.address, "--plot", str(png)]) == 0
    assert "4 points (4 computed" in capsys.readouterr().out
    rows = read_results(out).to_pylist()
    same = {r["machine"]: r["contour_max_um"] for r in rows if r["feed"] == 3000.0}
    assert same["mill.toml"] == pytest.approx(same["fadal-pid"])  # the file is the built-in machine
    assert png.stat().st_size > 1000
    before = out.read_bytes()
    f.write_text('[parameters]\ntoolpath = "diamond"\nfeed = [3000, 9000]\nspeed = 3\n')
    assert main(["sweep", str(f), "-o", str(out), "--scheduler", cluster.address]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {f}:4: [parameters] speed: unknown key")
    assert out.read_bytes() == before
    with pytest.raises(SystemExit) as ei:
        main(["sweep", str(f), "-o", str(out), "--scheduler", cluster.address, "--workers", "2"])
    assert ei.value.code == 2
    f.write_text('[parameters]\ntoolpath = "diamond"\n')
    assert main(["sweep", str(f), "-o", str(tmp_path / "new.csv"), "--scheduler", "nonsense"]) == 2
    assert "scheduler address 'nonsense' is not valid" in capsys.readouterr().err
    assert not list(tmp_path.glob("new.csv*"))


def test_local_cluster_by_default(tmp_path):
    """Without a scheduler the sweep starts (and stops) its own LocalCluster on 127.0.0.1."""
    import psutil

    markers = tmp_path / "m"
    markers.mkdir()
    before = {p.pid for p in psutil.Process().children(recursive=True)}
    r = sweep(_spec(tmp_path, "[1, 2, 3]", "[1.0]"), tmp_path / "r.parquet", workers=1, timeout=LIMIT_S,
              point_function=functools.partial(slow_point, marker_dir=str(markers), delay=0.0))
    assert (r.computed, r.workers, len(r)) == (3, 1, 3)
    assert {p for _, p in _markers(markers, "done")} - {os.getpid()}, "points ran in this process"

    def new_children() -> list[str]:
        # multiprocessing's resource tracker lives as long as this process; it is not a worker
        procs = [p for p in psutil.Process().children(recursive=True) if p.pid not in before]
        return [c for c in (" ".join(p.cmdline()) for p in procs) if "resource_tracker" not in c]

    deadline = time.monotonic() + 20
    while new_children() and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not new_children(), "worker processes left behind"


def test_killed_worker_every_point_exactly_once(cluster, tmp_path):
    """Kill worker w1 while it computes a point: the point is rerun on w2 and written once."""
    markers = tmp_path / "m"
    markers.mkdir()
    out = tmp_path / "r.csv"
    spec = _spec(tmp_path, "[1, 2, 3, 4, 5, 6, 7, 8]")  # 16 points
    victim = cluster.workers["w1"]
    killed_at: list[float] = []

    def kill_w1(row):
        if len(killed_at) == 0 and row["pid"] == victim.pid:
            # w1 just finished a point and holds the next one: kill it once it has started
            deadline = time.monotonic() + 10
            started = {i for i, p in _markers(markers, "start") if p == victim.pid}
            done = {i for i, p in _markers(markers, "done") if p == victim.pid}
            while not started - done and time.monotonic() < deadline:
                time.sleep(0.02)
                started = {i for i, p in _markers(markers, "start") if p == victim.pid}
            os.kill(victim.pid, signal.SIGKILL)
            victim.wait(timeout=10)
            killed_at.append(time.monotonic())

    r = sweep(spec, out, scheduler=cluster.address, callback=kill_w1, timeout=LIMIT_S,
              point_function=functools.partial(slow_point, marker_dir=str(markers), delay=0.3))
    assert killed_at, "worker w1 never reported a point"
    ids = read_results(out).column("id").to_pylist()
    assert len(ids) == 16 and len(set(ids)) == 16
    assert r.computed == 16 and r.failed == 0
    started_w1 = {i for i, p in _markers(markers, "start") if p == victim.pid}
    done_w1 = {i for i, p in _markers(markers, "done") if p == victim.pid}
    interrupted = started_w1 - done_w1
    assert interrupted, "w1 was not computing a point when it was killed"
    rows = {x["id"]: x for x in r.rows()}
    for i in interrupted:
        assert rows[i]["status"] == "ok" and rows[i]["pid"] != victim.pid  # recomputed elsewhere
