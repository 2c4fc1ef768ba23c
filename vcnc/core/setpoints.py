"""Sampled axis setpoints: what the interpolator hands to the drives."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any

import numpy as np

from vcnc.core.axes import AXIS_NAMES
from vcnc.core.errors import InputError
from vcnc.core.io import atomic_path, write_rows

__all__ = ["Setpoints", "AXIS_NAMES"]


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class Setpoints:
    """Commanded motion sampled at a fixed period.

    Attributes
    ----------
    t : ndarray, shape (N,)
        Time [s], uniform with step ``sample_time``, starting at 0.
    axes : tuple of str
        Axis names, in the column order of the arrays (subset of ``AXIS_NAMES``).
    position, velocity, acceleration : ndarray, shape (N, n_axes)
        Commanded position [mm], velocity [mm/s], acceleration [mm/s^2]; on the rotary axes
        a, b, c [deg], [deg/s], [deg/s^2].
    block : ndarray of int, shape (N,)
        Index of the program block each sample belongs to (-1 where none, e.g. padding).
    sample_time : float
        Interpolation period Ts [s].
    path : object, optional
        The exact programmed geometry (a ``toolpaths`` path) when known, used by the contour
        evaluator. ``None`` for setpoints that do not come from a program.
    meta : dict
        Free-form provenance (program file, profile, ...).
    """

    t: np.ndarray
    axes: tuple[str, ...]
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    block: np.ndarray
    sample_time: float
    path: Any = None
    meta: dict = dataclasses.field(default_factory=dict)

    def __post_init__(self) -> None:
        n = len(self.t)
        k = len(self.axes)
        for name in ("position", "velocity", "acceleration"):
            arr = getattr(self, name)
            if arr.shape != (n, k):
                raise InputError(f"Setpoints.{name} has shape {arr.shape}, expected ({n}, {k})")
        if self.block.shape != (n,):
            raise InputError(f"Setpoints.block has shape {self.block.shape}, expected ({n},)")
        if not self.sample_time > 0:
            raise InputError(f"Setpoints.sample_time must be > 0 s, got {self.sample_time!r}")
        bad = [a for a in self.axes if a not in AXIS_NAMES]
        if bad:
            raise InputError(f"unknown axis name(s) {bad}; expected some of {AXIS_NAMES}")

    @classmethod
    def from_positions(
        cls,
        position: np.ndarray | Sequence[float],
        *,
        sample_time: float,
        axes: Sequence[str] = ("x",),
    ) -> Setpoints:
        """Build setpoints from sampled positions [mm]; velocity and acceleration by central
        differences (one-sided at the ends)."""
        pos = np.asarray(position, dtype=float)
        if pos.ndim == 1:
            pos = pos[:, None]
        n = pos.shape[0]
        vel = np.gradient(pos, sample_time, axis=0) if n > 1 else np.zeros_like(pos)
        acc = np.gradient(vel, sample_time, axis=0) if n > 1 else np.zeros_like(pos)
        return cls(
            t=np.arange(n) * sample_time,
            axes=tuple(axes),
            position=pos,
            velocity=vel,
            acceleration=acc,
            block=np.full(n, -1, dtype=np.int64),
            sample_time=float(sample_time),
        )

    def __len__(self) -> int:
        return len(self.t)

    @property
    def duration(self) -> float:
        """Time of the last sample [s]."""
        return float(self.t[-1]) if len(self.t) else 0.0

    def axis_index(self, axis: str) -> int:
        """Column of ``axis``; raises InputError naming the axes present."""
        try:
            return self.axes.index(axis)
        except ValueError:
            raise InputError(f"axis {axis!r} not in setpoints (axes: {', '.join(self.axes)})") from None

    def select_axes(self, axes: tuple[str, ...]) -> Setpoints:
        """The setpoints of ``axes`` only, in that order (InputError naming the axes present), as
        :meth:`vcnc.core.capture.Capture.select_axes`."""
        cols = [self.axis_index(a) for a in axes]
        return dataclasses.replace(self, axes=tuple(axes), position=self.position[:, cols],
                                   velocity=self.velocity[:, cols], acceleration=self.acceleration[:, cols])

    def slice(self, start: int, stop: int) -> Setpoints:
        """Samples ``start:stop`` (time kept; ``meta`` copied), as :meth:`vcnc.core.capture.Capture.slice`."""
        return dataclasses.replace(
            self, t=self.t[start:stop], position=self.position[start:stop], velocity=self.velocity[start:stop],
            acceleration=self.acceleration[start:stop], block=self.block[start:stop], meta=dict(self.meta),
        )

    def held(self, seconds: float) -> Setpoints:
        """The setpoints followed by ``seconds`` of the last position held (velocity and acceleration 0, the last
        sample's block): the time a loop is given to settle after its command stopped (``vcnc simulate``'s
        settling tail, ``vcnc compare``'s start from rest). ``self`` when that is under one sample."""
        n = int(round(seconds / self.sample_time))
        if n <= 0 or not len(self):
            return self
        zeros = np.zeros((n, len(self.axes)))
        return dataclasses.replace(
            self,
            t=np.arange(len(self) + n) * self.sample_time,
            position=np.vstack([self.position, np.repeat(self.position[-1:], n, axis=0)]),
            velocity=np.vstack([self.velocity, zeros]),
            acceleration=np.vstack([self.acceleration, zeros]),
            block=np.concatenate([self.block, np.full(n, self.block[-1])]),
        )

    def table(self) -> tuple[list[str], np.ndarray, list[str]]:
        """The CSV's columns ``t, <a>_ref, <a>_vel, <a>_acc`` per axis and ``block``: (header, data, one
        ``%``-format per column)."""
        cols = [self.t[:, None]]
        header = ["t"]
        for i, a in enumerate(self.axes):
            header += [f"{a}_ref", f"{a}_vel", f"{a}_acc"]
            cols += [self.position[:, i : i + 1], self.velocity[:, i : i + 1], self.acceleration[:, i : i + 1]]
        header.append("block")
        cols.append(self.block[:, None].astype(float))
        data = np.hstack(cols)
        return header, data, ["%.9g"] + ["%.12g"] * (data.shape[1] - 2) + ["%d"]

    def to_csv(self, path: str) -> None:
        """Write :meth:`table` as CSV (atomic)."""
        header, data, fmt = self.table()
        with atomic_path(path) as tmp, open(tmp, "w", encoding="ascii", newline="\n") as out:
            out.write(",".join(header) + "\n")
            write_rows(out, data, fmt)
