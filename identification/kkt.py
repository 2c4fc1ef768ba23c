"""Method ``kkt``: the Lagrange-multiplier solution of Sec. 3.3, solved numerically.

The thesis forms f' = f + sum lambda_i h_i (Eq. 3.17) with slack variables (Eq. 3.13); the
switching conditions -2 lambda_i sigma_i = 0 (Eq. 3.22) make each constraint active
(sigma_i = 0) or inactive (lambda_i = 0): the 16 cases of Table 3.1, of which 12 are feasible.
For each case the stationarity conditions (Eqs. 3.18-3.21) are solved, the feasible solutions are
kept and the one with the lowest objective wins.

Here, without symbolic algebra: eliminating theta_2 (Eq. 4.9) and multiplying Eq. (3.18) by G^T
(Eq. 3.15) turns the stationarity conditions of a case into "the derivative of f along every
variable that is not at an active bound vanishes" (the multipliers of the active bounds are then
the derivatives along their variables). So each case is a system in 0, 1, 2 or 3 unknowns:

* 3 unknowns (Case 1): the unconstrained least squares (poles from the cubic of Eq. 3.7), plus
  the stationary points on the fold where G of Eq. (3.15) is singular (a repeated real pole,
  det G ~ p^2 - 2 p zeta omega_n + omega_n^2 = 0): there the Lagrange system written with
  G^-1 (Eq. 3.16) does not exist, yet the constrained optimum can sit there (e.g. when an upper
  omega_n bound excludes the unconstrained pair); found by root finding as below, in 3-D;
* 2 unknowns (a face of the box): Newton-type root finding (``scipy.optimize.root``, hybrid
  Powell) of the two derivatives from a grid of starting points, all distinct roots kept;
* 1 unknown (an edge): the derivative is bracketed on a fine grid and every sign change refined
  by Brent's method;
* 0 unknowns (a corner): evaluated.

The thesis' bounds (Eq. 3.8) are lower bounds on p and omega_n and both bounds on zeta; with the
GA's upper bounds on p and omega_n (Sec. 4.2) each variable is free, at its lower or at its upper
bound: 27 cases, of which the 12 with no upper p/omega_n bound active are Table 3.1's.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import scipy.optimize

from identification.poles import denominator
from identification.problem import ReducedProblem, table31_case

__all__ = ["solve_kkt"]

_NAMES = ("p", "omega_n", "zeta")


def _to_v(u: np.ndarray, log_mask: np.ndarray) -> np.ndarray:
    return np.where(log_mask, np.exp(u), u)


def _grad_many(problem: ReducedProblem, V: np.ndarray) -> np.ndarray:
    """df/dv at many points V (m, 3) [rad/s]: chain rule through (a1, a2, a3), vectorised."""
    p, wn, z = V[:, 0], V[:, 1], V[:, 2]
    a1, a2, a3 = denominator(p, wn, z)
    th = np.stack([a3 / a2, a1 / a2, 1.0 / a2], axis=-1)
    r = th @ problem.T.T - problem.c  # (m, 3)
    gth = 2.0 * problem._fscale * (r @ problem.T)  # df/dtheta1 (m, 3)
    # d theta / d a  (m, 3 [theta], 3 [a1, a2, a3])
    dth_da = np.zeros((V.shape[0], 3, 3))
    dth_da[:, 0, 1] = -a3 / a2**2
    dth_da[:, 0, 2] = 1.0 / a2
    dth_da[:, 1, 0] = 1.0 / a2
    dth_da[:, 1, 1] = -a1 / a2**2
    dth_da[:, 2, 1] = -1.0 / a2**2
    da_dv = np.zeros((V.shape[0], 3, 3))
    da_dv[:, 0] = np.stack([np.ones_like(p), 2 * z, 2 * wn], -1)
    da_dv[:, 1] = np.stack([2 * z * wn, 2 * wn + 2 * p * z, 2 * p * wn], -1)
    da_dv[:, 2] = np.stack([wn * wn, 2 * p * wn, np.zeros_like(p)], -1)
    J = np.einsum("mij,mjk->mik", dth_da, da_dv)
    problem.nfev += V.shape[0]
    return np.einsum("mi,mik->mk", gth, J)


def _edge_roots(problem, v_fixed: np.ndarray, k: int, lo: float, hi: float, log: bool) -> list[np.ndarray]:
    n = 400
    grid = np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)
    V = np.repeat(v_fixed[None, :], n, axis=0)
    V[:, k] = grid
    g = _grad_many(problem, V)[:, k]
    roots = []

    def dfk(x):
        w = v_fixed.copy()
        w[k] = x
        return _grad_many(problem, w[None, :])[0, k]

    for i in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
        x = scipy.optimize.brentq(dfk, grid[i], grid[i + 1], xtol=1e-14 * grid[i + 1], rtol=1e-15, maxiter=200)
        w = v_fixed.copy()
        w[k] = x
        roots.append(w)
    for i in np.flatnonzero(g == 0):
        roots.append(V[i].copy())
    return roots


def _face_roots(problem, v_fixed: np.ndarray, free: list[int], box, seeds: int = 8) -> list[np.ndarray]:
    """All roots of the derivatives along the free variables (2 or 3) found from a grid of starts."""
    log_mask = np.array([True, True, False])
    lo = np.array([math.log(box[i][0]) if log_mask[i] else box[i][0] for i in range(3)])
    hi = np.array([math.log(box[i][1]) if log_mask[i] else box[i][1] for i in range(3)])
    width = hi - lo
    u_fixed = np.where(log_mask, np.log(v_fixed), v_fixed)

    def fun(x):
        u = u_fixed.copy()
        u[free] = lo[free] + np.clip(x, -0.5, 1.5) * width[free]
        v = _to_v(u, log_mask)
        g = _grad_many(problem, v[None, :])[0]
        dv_du = np.where(log_mask, v, 1.0)
        return (g * dv_du * width)[free]

    found: list[np.ndarray] = []
    s = (np.arange(seeds) + 0.5) / seeds
    for x0 in itertools.product(*([s] * len(free))):
        sol = scipy.optimize.root(fun, np.array(x0), method="hybr", options={"xtol": 1e-13, "maxfev": 400})
        if not sol.success or np.any(sol.x < -1e-9) or np.any(sol.x > 1 + 1e-9):
            continue
        x = np.clip(sol.x, 0.0, 1.0)
        if any(np.max(np.abs(x - q)) < 1e-7 for q in found):
            continue
        found.append(x)
    out = []
    for x in found:
        u = u_fixed.copy()
        u[free] = lo[free] + x * width[free]
        out.append(_to_v(u, log_mask))
    return out


def solve_kkt(problem: ReducedProblem) -> dict:
    """Enumerate the constraint-activation cases (module docstring); returns the best feasible solution.

    Returns
    -------
    dict
        ``v`` [rad/s], ``objective``, ``nfev``, ``nit`` (cases solved), ``message`` and ``cases``:
        one row per case with its Table 3.1 number (None when an upper bound is active), the
        active set, the number of feasible solutions and the best objective among them.
    """
    box = problem.bounds.rad()
    problem.nfev = 0
    rows = []
    best_v, best_f = None, math.inf
    for status in itertools.product(("free", "lower", "upper"), repeat=3):
        active = dict(zip(_NAMES, status))
        free = [i for i, s in enumerate(status) if s == "free"]
        v_fixed = np.array(
            [box[i][0] if s == "lower" else box[i][1] if s == "upper" else math.sqrt(box[i][0] * box[i][1])
             for i, s in enumerate(status)]
        )
        if len(free) == 3:
            # the unconstrained least squares, plus stationary points where G (Eq. 3.15) is singular
            # (a repeated real pole): there the gradient in (p, omega_n, zeta) vanishes without
            # the gradient in theta_1 vanishing, a case Eq. (3.16) cannot express
            sols = [v for v in problem.unconstrained_poles() if problem.in_box(v)]
            sols += _face_roots(problem, v_fixed, free, box, seeds=5)
        elif len(free) == 2:
            sols = _face_roots(problem, v_fixed, free, box)
        elif len(free) == 1:
            k = free[0]
            sols = _edge_roots(problem, v_fixed, k, box[k][0], box[k][1], log=k < 2)
        else:
            sols = [v_fixed]
        fs = [float(problem.objective(*v)) for v in sols]
        row = {
            "case": table31_case(active),
            "active": active,
            "solutions": len(sols),
            "objective": min(fs) if fs else None,
        }
        rows.append(row)
        for v, fv in zip(sols, fs):
            if fv < best_f:
                best_v, best_f = v, fv
    return {
        "v": best_v,
        "objective": best_f,
        "nfev": problem.nfev,
        "nit": len(rows),
        "message": "Lagrange multipliers / Kuhn-Tucker: best feasible stationary point over 27 activation cases "
        "(Table 3.1's 12 plus the upper p, omega_n bounds)",
        "cases": rows,
    }
