"""Synthetic identification data: random point-to-point moves through a known reduced model.

Used to check the solvers against known parameters without a machine simulator: a reference
like the thesis' Table 3.2 test (random targets within +/- range, trapezoidal velocity with
exact stop at each target, Sec. 3.4) is run through :func:`identification.reduced_model.simulate`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from drives.resonance import StructuralMode
from identification.reduced_model import simulate
from vcnc.core.capture import Capture
from vcnc.core.errors import InputError

__all__ = [
    "random_moves_reference",
    "back_and_forth_reference",
    "synthetic_capture",
    "table_3_2_program",
    "VALIDATION_PROGRAM",
    "FADAL_PID_X",
    "BALLSCREW_AXIAL_MODE",
]

#: True parameters of the thesis' PID-controlled Fadal x axis (Table 3.4 / Table 4.1, "Actual").
FADAL_PID_X: dict[str, float] = {
    "a1": 192.65,
    "a2": 44356.23,
    "a3": 316830.21,
    "b0": 0.0,
    "b1": 190.10,
    "b2": 44356.23,
    "d0": 441.0,
    "d1": -302.0,
}


def _trapezoid(distance: float, v: float, a: float, T: float) -> np.ndarray:
    """Positions (relative, excluding t = 0, ending exactly at distance) of one stop-to-stop move."""
    d = abs(distance)
    if d == 0:
        return np.zeros(0)
    if d >= v * v / a:
        ta, tc = v / a, (d - v * v / a) / v
    else:
        ta, tc = math.sqrt(d / a), 0.0
        v = a * ta
    total = 2 * ta + tc
    n = max(1, math.ceil(total / T - 1e-9))
    t = np.arange(1, n + 1) * T
    s = np.where(
        t < ta,
        0.5 * a * t * t,
        np.where(t < ta + tc, 0.5 * a * ta * ta + v * (t - ta), d - 0.5 * a * np.clip(total - t, 0, None) ** 2),
    )
    s[-1] = d
    return math.copysign(1.0, distance) * np.minimum(s, d)


def random_moves_reference(
    *,
    moves: int = 200,
    span: float = 10.0,
    feed: float = 200.0,
    acceleration: float = 2000.0,
    sample_time: float = 1e-3,
    dwell: float = 0.0,
    seed: int = 0,
) -> np.ndarray:
    """Reference of random moves within +/- span [mm] (Table 3.2 style).

    Parameters
    ----------
    moves : int
        Number of moves (200 in Table 3.2).
    span : float
        Targets uniform in [-span, span] [mm].
    feed : float
        Maximum velocity [mm/s] (F12000 mm/min = 200 mm/s).
    acceleration : float
        [mm/s^2] (2000 in Sec. 3.4).
    sample_time : float
        [s].
    dwell : float
        Stop at each target [s].
    seed : int
        Random seed.

    Returns
    -------
    ndarray
        Positions [mm] starting at 0 with 0.1 s at rest at each end.
    """
    if not (feed > 0 and acceleration > 0 and sample_time > 0 and span > 0 and moves >= 1):
        raise InputError("moves, span [mm], feed [mm/s], acceleration [mm/s^2], sample_time [s] must be positive")
    rng = np.random.default_rng(seed)
    targets = rng.uniform(-span, span, moves)
    rest = np.zeros(int(round(0.1 / sample_time)))
    parts = [rest]
    pos = 0.0
    nd = int(round(dwell / sample_time))
    for tgt in targets:
        seg = pos + _trapezoid(tgt - pos, feed, acceleration, sample_time)
        parts.append(seg)
        pos = float(tgt)
        if nd:
            parts.append(np.full(nd, pos))
    parts.append(np.full(rest.size, pos))
    return np.concatenate(parts)


def back_and_forth_reference(
    *,
    amplitude: float = 20.0,
    feed: float = 70.71,
    acceleration: float = 424.26,
    cycles: int = 2,
    sample_time: float = 1e-3,
) -> np.ndarray:
    """+/- amplitude back-and-forth moves (the validation trajectory of Sec. 4.3.1)."""
    rest = np.zeros(int(round(0.1 / sample_time)))
    parts = [rest]
    pos = 0.0
    for tgt in [amplitude, -amplitude] * cycles + [0.0]:
        parts.append(pos + _trapezoid(tgt - pos, feed, acceleration, sample_time))
        pos = tgt
    parts.append(np.full(rest.size, pos))
    return np.concatenate(parts)


def synthetic_capture(
    parameters: Mapping[str, float],
    reference: np.ndarray,
    *,
    sample_time: float = 1e-3,
    noise: float = 0.0,
    resolution: float = 0.0,
    seed: int = 0,
    axis: str = "x",
) -> Capture:
    """A one-axis capture of the reduced model's response.

    Parameters
    ----------
    parameters : mapping
        a1..d1 of Eq. (3.3).
    reference : ndarray
        x_r [mm].
    noise : float
        Standard deviation of white measurement noise [mm].
    resolution : float
        Encoder step [mm] (0: none); the measurement is rounded to it.
    """
    x = simulate(parameters, reference, sample_time)
    if noise > 0:
        x = x + np.random.default_rng(seed).normal(0.0, noise, x.shape)
    if resolution > 0:
        x = np.round(x / resolution) * resolution
    t = np.arange(reference.size) * sample_time
    return Capture(
        t=t,
        axes=(axis,),
        reference=np.asarray(reference, float)[:, None],
        measured=x[:, None],
        meta={"source": "identification.synthetic"},
    )


def table_3_2_program(*, seed: int = 1, moves: int = 200, span: float = 10.0, feed: float = 12000.0) -> str:
    """G-code of the Table 3.2 kind: random G01 moves within +/- span [mm] at F feed [mm/min], in mm
    and exact stop (stated: every move starts and ends at rest, whatever the control's default)."""
    rng = np.random.default_rng(seed)
    lines = ["G21 G61", f"N0000 G00 X0.000 F{feed:g}"]
    lines += [f"N{10 * (i + 1):04d} G01 X{v:.3f}" for i, v in enumerate(rng.uniform(-span, span, moves))]
    return "\n".join(lines) + "\n"


#: Sec. 4.3.1 validation move: +/-20 mm back and forth at 70.71 mm/s (F4242.6); the 424.26 mm/s^2
#: acceleration comes from the axis limits the caller interpolates with.
VALIDATION_PROGRAM = "G21 G61\nG00 X0\nG01 X20.000 F4242.6\nG01 X-20.000\nG01 X20.000\nG01 X-20.000\nG01 X0\n"


#: A first axial mode for the thesis' ball-screw bench (Sec. 3.4.2), not published: a lightly damped
#: mode below Nyquist with most of the inertia on the table side. With it, ballscrew-zpetc shows the
#: Table 4.2 situation (the solution on zeta_min); the rigid built-in bench does not.
BALLSCREW_AXIAL_MODE = StructuralMode(frequency_hz=80.0, damping=0.05, load_fraction=0.7)
