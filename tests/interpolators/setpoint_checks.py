"""Checks of sampled setpoints shared by the interpolation tests: every axis limit by finite
differences and in the analytic columns, the setpoints' distance from the programmed path, and the
rest-to-rest time of a trapezoidal profile."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["check_limits", "distance_to_path", "path_distances", "trapezoid_time", "xyz"]


def check_limits(sp, program, limits, *, jerk: bool = False, feed: bool = False, rel: float = 1e-6) -> None:
    """Every axis of ``sp`` within ``limits[axis]``: the finite differences of the sampled positions and
    the analytic velocity and acceleration columns (the rapid rate on rapid blocks, the velocity limit
    elsewhere), and the jerk when ``jerk``; with ``feed`` also the X/Y/Z path speed never above the
    block's programmed feed. ``rel`` is the relative allowance for rounding; the finite differences of order k
    also allow the rounding of the positions themselves, ``2^k eps max|p| / Ts^k`` (the third difference of
    positions near 245 mm at Ts = 0.31 ms rounds by up to 0.014 mm/s^3: fanuc_generator seed 42082 under the
    setpoint fuzzer read 1.0000027 x a 1354 mm/s^3 jerk limit)."""
    Ts = sp.sample_time
    rapid = np.array([b.kind == "rapid" for b in program.blocks])
    for i, axis in enumerate(sp.axes):
        lim = limits[axis]
        p = sp.position[:, i]
        eps = np.finfo(float).eps * float(np.abs(p).max(initial=0.0))  # the rounding of one position
        v_lim = np.where(rapid[sp.block], lim.rapid_rate, lim.velocity) * (1 + rel) + 1e-9
        assert np.all(np.abs(sp.velocity[:, i]) <= v_lim), axis
        # a step across a rapid's end runs partly at the rapid rate
        v_step = np.maximum(v_lim[1:], v_lim[:-1])
        assert np.all(np.abs(np.diff(p)) / Ts <= v_step + 2 * eps / Ts), (axis, np.abs(np.diff(p)).max() / Ts)
        assert np.all(np.abs(sp.acceleration[:, i]) <= lim.acceleration * (1 + rel)), axis
        a_fd = np.abs(np.diff(p, 2)) / Ts**2
        assert np.all(a_fd <= lim.acceleration * (1 + rel) + 1e-6 + 4 * eps / Ts**2), (axis, a_fd.max())
        if jerk:
            j_col = np.abs(np.diff(sp.acceleration[:, i])) / Ts
            assert np.all(j_col <= lim.jerk * (1 + rel) + 1e-6), (axis, j_col.max())
            j_fd = np.abs(np.diff(p, 3)) / Ts**3
            assert np.all(j_fd <= lim.jerk * (1 + rel) + 1e-3 + 8 * eps / Ts**3), (axis, j_fd.max())
    if feed:
        xyz = [i for i, a in enumerate(sp.axes) if a in ("x", "y", "z")]
        speed = np.linalg.norm(sp.velocity[:, xyz], axis=1)
        programmed = np.array([b.feed for b in program.blocks])[sp.block]
        over = speed - programmed * (1 + rel) - 1e-12
        assert np.all(over <= 0), ("feed", int(np.argmax(over)), float(speed[np.argmax(over)]),
                                   float(programmed[np.argmax(over)]))


def xyz(sp) -> np.ndarray:
    """The X, Y, Z positions of ``sp`` [mm], shape (n, 3); an axis the setpoints lack stays at 0."""
    out = np.zeros((len(sp), 3))
    for i, ax in enumerate(sp.axes):
        if ax in ("x", "y", "z"):
            out[:, "xyz".index(ax)] = sp.position[:, i]
    return out


def path_distances(path, points: np.ndarray, step: float | None = None) -> np.ndarray:
    """Distance [mm] of each of ``points`` (n, 3) from ``path``, less the half ``step`` of the points it is measured
    against (a lower bound: a distance above a tolerance is a real deviation); ``step`` [mm] by default the path's
    length / 200 000, within 20 nm - 0.5 um."""
    from scipy.spatial import cKDTree

    if step is None:
        step = min(max(sum(s.length for s in path.segments) / 2e5, 2e-5), 5e-4)
    return cKDTree(path.points(step=step)).query(points)[0] - step / 2


def distance_to_path(sp, step: float = 2e-4) -> float:
    """Worst distance [mm] of the setpoints from the programmed path (``meta["programmed_path"]``, the chords
    before blending and merging, else ``sp.path``), taken at points ``step`` apart."""
    path = sp.meta.get("programmed_path") or sp.path
    return float(path_distances(path, xyz(sp), step).max())


def trapezoid_time(length: float, v: float, a: float) -> float:
    """Rest-to-rest time [s] of a trapezoidal profile over ``length`` at speed ``v``, acceleration ``a``."""
    return length / v + v / a if v * v / a <= length else 2.0 * math.sqrt(length / a)
