"""Method ``exact``: variable projection, global grid search over the pole box, local polish.

Not in the thesis. After eliminating theta_2 (Eq. 4.9-4.12, see :mod:`identification.problem`)
the objective is f(v) = 1/2 (|T theta_1(v) - c|^2 + rho^2), a convex quadratic in theta_1 seen
through the smooth map v = (p, omega_n, zeta) -> theta_1 of Eq. (3.14). So:

1. if the unconstrained least-squares minimum (Case 1 of Table 3.1) is realised by poles inside
   the box, it is the global optimum and nothing else is needed;
2. otherwise f is evaluated on a grid of the box (logarithmic in p and omega_n, linear in zeta;
   about 55,000 points in one vectorised pass), and
3. the best separated grid points are polished by a bounded Gauss-Newton trust region
   (``scipy.optimize.least_squares``, ``trf``) on the 3-vector residual in (log p, log omega_n,
   zeta), with the analytic Jacobian of Eq. (3.15);
4. the optimum is reported with its active bounds, their multipliers (the objective's slope into
   the box, >= 0 at a minimum: the Kuhn-Tucker conditions of Eq. 3.22) and the projected gradient.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import scipy.optimize

from identification.problem import ReducedProblem

__all__ = ["ExactOptions", "solve_exact"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class ExactOptions:
    """Settings of the ``exact`` method.

    Attributes
    ----------
    grid : (int, int, int)
        Grid points in p, omega_n (log-spaced) and zeta (linear).
    starts : int
        Separated grid minima polished locally.
    """

    grid: tuple[int, int, int] = (48, 48, 24)
    starts: int = 4


def _grid(problem: ReducedProblem, opts: ExactOptions):
    (plo, phi), (wlo, whi), (zlo, zhi) = problem.bounds.rad()
    ps = np.geomspace(plo, phi, opts.grid[0])
    ws = np.geomspace(wlo, whi, opts.grid[1])
    zs = np.linspace(zlo, zhi, opts.grid[2])
    P, Wn, Z = np.meshgrid(ps, ws, zs, indexing="ij")
    f = problem.objective(P, Wn, Z)
    return (ps, ws, zs), f


def _starts(axes, f: np.ndarray, k: int) -> list[np.ndarray]:
    """Up to k grid points, best first, at least 3 cells apart in some direction."""
    order = np.argsort(f, axis=None)
    picked: list[tuple[int, int, int]] = []
    for flat in order[: max(200, 20 * k)]:
        idx = np.unravel_index(flat, f.shape)
        if all(max(abs(int(a) - int(b)) for a, b in zip(idx, q)) >= 3 for q in picked):
            picked.append(tuple(int(i) for i in idx))
            if len(picked) == k:
                break
    return [np.array([axes[0][i], axes[1][j], axes[2][m]]) for i, j, m in picked]


def _polish(problem: ReducedProblem, v0: np.ndarray) -> tuple[np.ndarray, int]:
    (plo, phi), (wlo, whi), (zlo, zhi) = problem.bounds.rad()
    lo = np.array([math.log(plo), math.log(wlo), zlo])
    hi = np.array([math.log(phi), math.log(whi), zhi])

    def to_v(u):
        return np.array([math.exp(u[0]), math.exp(u[1]), u[2]])

    def fun(u):
        return problem.residual(to_v(u))

    def jac(u):
        v = to_v(u)
        return problem.residual_jacobian(v) * np.array([v[0], v[1], 1.0])[None, :]

    u0 = np.clip(np.array([math.log(v0[0]), math.log(v0[1]), v0[2]]), lo, hi)
    res = scipy.optimize.least_squares(
        fun, u0, jac=jac, bounds=(lo, hi), method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=200
    )
    return problem.clip(to_v(res.x)), int(res.nfev)


def solve_exact(problem: ReducedProblem, options: ExactOptions | None = None) -> dict:
    """Global minimum of f over the pole box (see module docstring).

    Returns
    -------
    dict
        ``v`` (p, omega_n, zeta in rad/s), ``objective`` [mm^2], ``nfev``, ``nit`` (local
        polishes), ``message``, ``global_certificate`` (True when Case 1 was feasible).
    """
    opts = options or ExactOptions()
    problem.nfev = 0
    inside = [v for v in problem.unconstrained_poles() if problem.in_box(v)]
    if inside:
        v = inside[0]
        return {
            "v": v,
            "objective": float(problem.objective(*v)),
            "nfev": problem.nfev,
            "nit": 0,
            "message": "unconstrained least-squares minimum lies inside the bounds (Table 3.1 case 1): global optimum",
            "global_certificate": True,
        }
    axes, f = _grid(problem, opts)
    starts = _starts(axes, f, opts.starts)
    for v in problem.unconstrained_poles():  # its projection is often close to the constrained optimum
        starts.append(problem.clip(v))
    best_v, best_f, nit = None, math.inf, 0
    for v0 in starts:
        v, _ = _polish(problem, v0)
        nit += 1
        fv = float(problem.objective(*v))
        if fv < best_f:
            best_v, best_f = v, fv
    return {
        "v": best_v,
        "objective": best_f,
        "nfev": problem.nfev,
        "nit": nit,
        "message": f"grid {opts.grid[0]}x{opts.grid[1]}x{opts.grid[2]} over the bounds, {nit} local polishes",
        "global_certificate": False,
    }
