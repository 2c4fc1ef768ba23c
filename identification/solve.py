"""``identification.solve``: the constrained least-squares problem of Eqs. (3.12) and (3.8).

Minimise f = 1/2 (Y - Phi theta)^T (Y - Phi theta) (Eq. 3.12) subject to the pole bounds of
Eq. (3.8) (plus upper bounds, Sec. 4.2), given the sufficient statistics of Eq. (3.19). Three
methods:

``exact`` (default)
    variable projection + global grid search + local polish (:mod:`identification.exact`);
``ga``
    the genetic algorithm of Sec. 4.2 of the thesis (:mod:`identification.ga`);
``kkt``
    the Lagrange-multiplier / Kuhn-Tucker case analysis of Sec. 3.3 and Table 3.1, solved
    numerically (:mod:`identification.kkt`).

Extra linear columns: when P has more than 8 columns, columns 9.. are further linear terms
(e.g. effects added by a diagnosis); their coefficients are solved jointly with theta_2 for every
pole candidate (Eq. 4.9 with a longer theta_2), the pole bounds stay as they are. They are
returned in ``SolveResult.extra`` multiplied by a2 (the scaling that turns delta+ into d0).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from identification.bounds import PoleBounds, as_bounds
from identification.exact import ExactOptions, solve_exact
from identification.ga import GAOptions, solve_ga
from identification.kkt import solve_kkt
from identification.poles import TWO_PI, canonical
from identification.problem import ReducedProblem
from identification.regressor import SufficientStatistics
from vcnc.core.errors import IdentificationError

__all__ = ["SolveResult", "solve", "solve_statistics", "METHODS"]

METHODS: tuple[str, ...] = ("exact", "ga", "kkt")


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class SolveResult:
    """Solution of the constrained identification problem.

    Attributes
    ----------
    parameters : dict
        a1..d1 of Eq. (3.3) (units in ``identification.reduced_model.PARAMETER_UNITS``).
    poles : dict
        ``omega_n_hz`` [Hz], ``zeta`` [-], ``p_hz`` [Hz], in the canonical labelling
        (:func:`identification.poles.canonical`: when all three poles are real, p is the slowest
        whose pair fits the bounds). A solver's point in another labelling of the same poles (same
        objective, same a1..d1) is relabelled, and ``details["relabelled_from"]`` keeps it.
    objective : float
        f of Eq. (3.12) at the solution [mm^2].
    unconstrained_objective : float
        f of the unconstrained least squares (a lower bound) [mm^2].
    theta : ndarray
        Normalised parameters (Eq. 3.10), then extra coefficients.
    extra : ndarray
        Extra-column coefficients times a2 (empty for the plain 8-column problem).
    method : str
    success : bool
        True when the Kuhn-Tucker conditions hold at the reported point (projected gradient
        small, multipliers of active bounds non-negative) - for ``ga`` it reports whether the
        best candidate passes the same test.
    message : str
    nfev : int
        Objective evaluations.
    nit : int
        Iterations (GA generations, local polishes, KKT cases solved).
    active : dict
        ``p``, ``omega_n``, ``zeta`` -> ``"lower"``, ``"upper"`` or ``"free"``.
    multipliers : dict
        Slope of f into the box at each active bound [mm^2 per box width] (Eq. 3.22).
    case : int or None
        Constraint-activation case of Table 3.1 (None when an upper p/omega_n bound is active).
    bounds : PoleBounds
    time_s : float
        Wall time of the solve [s].
    details : dict
        Method-specific information (e.g. GA history, KKT case table), and when asked for
        ``identifiability``: the pole ranges where the objective stays within 1 % of the
        solution's (:meth:`~identification.problem.ReducedProblem.valley`; not part of ``time_s``).
    """

    parameters: dict
    poles: dict
    objective: float
    unconstrained_objective: float
    theta: np.ndarray
    extra: np.ndarray
    method: str
    success: bool
    message: str
    nfev: int
    nit: int
    active: dict
    multipliers: dict
    case: int | None
    bounds: PoleBounds
    time_s: float
    details: dict = dataclasses.field(default_factory=dict)

    @property
    def x(self) -> np.ndarray:
        """(p_hz, omega_n_hz, zeta), like scipy's ``OptimizeResult.x``."""
        return np.array([self.poles["p_hz"], self.poles["omega_n_hz"], self.poles["zeta"]])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no arrays larger than theta)."""
        return {
            "method": self.method,
            "parameters": dict(self.parameters),
            "poles": dict(self.poles),
            "objective": self.objective,
            "unconstrained_objective": self.unconstrained_objective,
            "success": self.success,
            "message": self.message,
            "nfev": self.nfev,
            "nit": self.nit,
            "active": dict(self.active),
            "multipliers": {k: float(v) for k, v in self.multipliers.items()},
            "case": self.case,
            "time_s": self.time_s,
            "extra": [float(v) for v in self.extra],
            **({"identifiability": self.details["identifiability"]} if "identifiability" in self.details else {}),
        }

    def to_json(self, path) -> None:
        """Write :meth:`to_dict` as JSON (atomic)."""
        import json

        from vcnc.core.io import atomic_path

        with atomic_path(path) as tmp:
            tmp.write_text(json.dumps(self.to_dict(), indent=2) + "\n")

    def plot(self, ax=None):
        """GA convergence when available (best objective per generation), else nothing to draw."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 3.5))
        hist = self.details.get("history")
        if hist is not None:
            ax.semilogy(np.asarray(hist["best_objective"]) - self.unconstrained_objective + 1e-300)
            ax.set_xlabel("generation")
            ax.set_ylabel("f - f_unconstrained [mm^2]")
        else:
            ax.text(0.5, 0.5, f"{self.method}: f = {self.objective:.6g} mm^2", ha="center", transform=ax.transAxes)
        return ax


def solve(
    P: np.ndarray,
    R: np.ndarray,
    gamma: float,
    *,
    bounds: PoleBounds | Mapping | None = None,
    method: str = "exact",
    sample_time: float | None = None,
    seed: int = 0,
    ga_options: GAOptions | None = None,
) -> SolveResult:
    """Constrained least squares of Eqs. (3.12) and (3.8) from P = Phi^T Phi, R = Phi^T Y, gamma = Y^T Y.

    Parameters
    ----------
    P : ndarray, shape (n, n)
        Phi^T Phi (Eq. 3.19) with the first 8 columns in the order of Eq. (3.11); n >= 8.
    R : ndarray, shape (n,)
        Phi^T Y.
    gamma : float
        Y^T Y [mm^2].
    bounds : mapping or PoleBounds, optional
        ``{"p_hz": (lo, hi), "omega_n_hz": (lo, hi), "zeta": (lo, hi)}``; missing keys take the
        thesis' defaults (0.2 Hz..Nyquist, zeta 0.2..2.0; Nyquist from ``sample_time``, 500 Hz
        without it).
    method : {"exact", "ga", "kkt"}
    sample_time : float, optional
        T [s], only for the default upper bounds.
    seed : int
        Random seed (``ga`` only).
    ga_options : GAOptions, optional
        Population and generations of ``ga`` (default 4000 x 300, Sec. 4.3).

    Returns
    -------
    SolveResult

    Notes
    -----
    Objective values from P, R, gamma lose the digits of gamma (f is often 1e-9 of gamma);
    :func:`solve_statistics` on a :class:`~identification.regressor.SufficientStatistics` keeps
    them.
    """
    stats = SufficientStatistics.from_normal_equations(P, R, gamma)
    return solve_statistics(
        stats, bounds=bounds, method=method, sample_time=sample_time, seed=seed, ga_options=ga_options
    )


def solve_statistics(
    stats: SufficientStatistics,
    *,
    bounds: PoleBounds | Mapping | None = None,
    method: str = "exact",
    sample_time: float | None = None,
    seed: int = 0,
    ga_options: GAOptions | None = None,
    exact_options: ExactOptions | None = None,
    identifiability: bool = False,
) -> SolveResult:
    """:func:`solve` on accumulated statistics (same parameters).

    ``identifiability=True`` also maps the valley of the objective around the solution
    (:meth:`~identification.problem.ReducedProblem.valley`, about 35 ms on the Table 3.2 test; not in ``time_s``) into
    ``details["identifiability"]``; :func:`identification.identify` asks for it.
    """
    if method not in METHODS:
        raise IdentificationError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")
    b = as_bounds(bounds, sample_time)
    t0 = time.perf_counter()
    problem = ReducedProblem(stats, b)
    if method == "exact":
        out = solve_exact(problem, exact_options)
    elif method == "ga":
        out = solve_ga(problem, ga_options, seed=seed)
    else:
        out = solve_kkt(problem)
    v_raw = np.asarray(out["v"], float)
    v = np.array(canonical(*v_raw, b))  # the same poles, slowest real pole as p when all are real
    params, theta, extra = problem.parameters(v)
    kkt = problem.kkt_report(v)
    elapsed = time.perf_counter() - t0
    scale = max(problem.unconstrained_objective, 1e-300)
    # KKT test: slope into the box small relative to the objective's size, multipliers >= 0
    tol = 1e-6 * max(out["objective"], scale)
    ok = kkt["projected_gradient"] <= max(tol, 1e-12) and all(m >= -tol for m in kkt["multipliers"].values())
    if not all(math.isfinite(x) for x in params.values()):
        raise IdentificationError("the solution has non-finite parameters (degenerate statistics)")
    details = {k: val for k, val in out.items() if k not in ("v", "objective", "nfev", "nit", "message")}
    details["kkt"] = kkt
    if not np.array_equal(v, v_raw):
        details["relabelled_from"] = {"p_hz": v_raw[0] / TWO_PI, "omega_n_hz": v_raw[1] / TWO_PI,
                                      "zeta": float(v_raw[2])}
    if identifiability:
        details["identifiability"] = problem.valley(v)
    return SolveResult(
        parameters=params,
        poles={"omega_n_hz": v[1] / TWO_PI, "zeta": float(v[2]), "p_hz": v[0] / TWO_PI},
        objective=float(out["objective"]),
        unconstrained_objective=problem.unconstrained_objective,
        theta=theta,
        extra=extra,
        method=method,
        success=bool(ok),
        message=out["message"],
        nfev=int(out["nfev"]),
        nit=int(out["nit"]),
        active=kkt["active"],
        multipliers=kkt["multipliers"],
        case=kkt["case"],
        bounds=b,
        time_s=elapsed,
        details=details,
    )
