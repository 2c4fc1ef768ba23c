"""The model's state at the first sample of a record that starts with the axis in motion.

:func:`identification.reduced_model.simulate` starts from rest (its simulation contract). A record
triggered during a move, or the loop's frame of a trace whose reference leads (its first
``delay_s`` cut off), starts with the axis moving and no rest in its first half
(:func:`identification.segments.settled_start` is None): simulated from rest, the model answers
with a start transient that decays with its slowest pole, and the output-error fit bends the
poles to imitate it (a 2 s record of fadal-pid at 3 ms, reference leading by 0.1 s: p 67 % off).

The linear part of the sampled loop (module docstring of :mod:`identification.reduced_model`)
adds the free response of a state ``xi_0`` at the first sample to the response from rest::

    x_k = x_k(rest) + C Phi^k xi_0

so for given parameters the best initial state is a linear least-squares problem in the three
states (variable projection: eliminated inside each residual evaluation of
:func:`identification.output_error.refine_output_error`, not added to its search). The friction
switches on the velocity of the response from rest; where the two velocities differ in sign
(the first tens of ms, while the free response is large) the friction is the only part that is
not exact.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from identification.reduced_model import discretize
from identification.regressor import RegressorOptions, SufficientStatistics, regressor
from identification.segments import SETTLED_SHARE, settled_start

__all__ = ["starts_in_motion", "free_response_basis", "fit_initial_state", "centred_statistics"]

#: Rows computed by matrix powers before the rest is built block by block [samples].
_BLOCK = 128


def starts_in_motion(reference: np.ndarray, measured: np.ndarray) -> bool:
    """Whether a record starts with the axis under way and never rests in its first half.

    True when the reference or the axis moves at the first sample (a first step over
    :data:`identification.segments.SETTLED_SHARE` of the reference's largest) and
    :func:`identification.segments.settled_start` finds no rest to start from. A record that
    starts at rest without settling by that test (EMPS: the axis held off its reference by
    friction) is not: a free initial state would fit a slow pole's drift there, not a start
    transient (EMPS' validation run predicted 40 % worse).

    Parameters
    ----------
    reference, measured : ndarray, shape (N,)
        Commanded (in the loop's frame) and measured position [mm].
    """
    xr = np.asarray(reference, float)
    x = np.asarray(measured, float)
    if xr.size < 2:
        return False
    big = float(np.max(np.abs(np.diff(xr))))
    first = max(abs(xr[1] - xr[0]), abs(x[1] - x[0]))
    return big > 0.0 and first > SETTLED_SHARE * big and settled_start(xr, x) is None


def free_response_basis(parameters: Mapping[str, float], sample_time: float, n: int) -> np.ndarray:
    """Position response [mm] to a unit initial causal state, one column per state.

    Parameters
    ----------
    parameters : mapping
        a1..d1 of Eq. (3.3).
    sample_time : float
        T [s].
    n : int
        Samples.

    Returns
    -------
    ndarray, shape (n, 3)
        Row k is ``C Phi^k`` of the discrete model (:func:`identification.reduced_model.discretize`).
    """
    m = discretize(parameters, sample_time)
    k0 = min(n, _BLOCK)
    rows = np.empty((n, 3))
    row = np.array(m.c, float)
    for k in range(k0):
        rows[k] = row
        row = row @ m.phi
    step = np.linalg.matrix_power(m.phi, k0)
    power = step.copy()
    for start in range(k0, n, k0):
        stop = min(start + k0, n)
        rows[start:stop] = rows[:stop - start] @ power
        power = power @ step
    return rows


def fit_initial_state(parameters: Mapping[str, float], sample_time: float, residual: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The initial state whose free response best cancels ``residual`` (least squares).

    Parameters
    ----------
    parameters : mapping
        a1..d1 of Eq. (3.3).
    sample_time : float
        T [s].
    residual : ndarray, shape (N,)
        Simulated from rest minus measured position [mm].

    Returns
    -------
    state : ndarray, shape (3,)
        Causal state ``xi_0`` at the first sample [mm].
    response : ndarray, shape (N,)
        Its free response [mm], to add to the simulation from rest.
    """
    r = np.asarray(residual, float)
    basis = free_response_basis(parameters, sample_time, r.size)
    if not np.all(np.isfinite(basis)):
        return np.zeros(3), np.zeros_like(r)
    scale = np.linalg.norm(basis, axis=0)
    scale[scale == 0.0] = 1.0
    coef = np.linalg.lstsq(basis / scale, -r, rcond=1e-10)[0]
    state = coef / scale
    return state, basis @ state


def centred_statistics(reference: np.ndarray, measured: np.ndarray, sample_time: float, *,
                       options: RegressorOptions | None = None) -> SufficientStatistics:
    """The regression of Eq. (3.11) with the controller integrator's value at the first sample free.

    The column ``e_i`` integrates the tracking error from the first sample (0 there); a record
    that starts in motion starts with the integrator at an unknown ``e_i,0``, which adds the
    constant ``alpha_i e_i,0`` to every row. The rows and ``Y`` centred on their means eliminate
    that constant exactly (least squares with an intercept). When the axis never rests the
    friction columns sum to one on every row and the constant is not identifiable:
    :func:`identification.solve.solve_statistics` then names the column.

    Parameters
    ----------
    reference, measured : ndarray, shape (N,)
        Commanded and measured position [mm] in the loop's frame.
    sample_time : float
        T [s].
    options : RegressorOptions, optional
    """
    phi, y = regressor(reference, measured, sample_time, options=options)
    stats = SufficientStatistics(8)
    stats.update(phi - phi.mean(axis=0), y - y.mean())
    return stats
