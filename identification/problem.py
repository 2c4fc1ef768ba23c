"""The constrained identification problem reduced to the three pole variables.

Eq. (4.8)-(4.12) of the thesis split theta into theta_1 = (alpha_i, alpha_1, alpha_2), fixed by
the poles (p, omega_n, zeta) through Eq. (3.14), and theta_2 (beta_0, beta_1, beta_2, delta+,
delta-, plus any extra linear columns) given by least squares for fixed theta_1 (Eq. 4.9). Here
the same elimination is done on the triangular factor of the statistics (variable projection):
with the columns ordered [theta_2 | theta_1 | Y] and U upper triangular,

    U = [[A22, A21, a2y],
         [  0,   T,   c],          f(theta_1) = 1/2 (|T theta_1 - c|^2 + rho^2)   (= Eq. 4.12)
         [  0,   0, rho]]          theta_2 = A22^{-1} (a2y - A21 theta_1)          (= Eq. 4.9)

which is Eq. (4.12) without forming it from P, R, gamma (so the objective keeps its digits when
it is 1e-9 of gamma). ``rho^2 / 2`` is the unconstrained least-squares optimum.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from identification.bounds import PoleBounds
from identification.parameters import search_box
from identification.poles import TWO_PI, canonical_mask, denominator, pole_splits, theta1, theta1_jacobian
from identification.regressor import COLUMN_DESCRIPTIONS, SufficientStatistics
from vcnc.core.errors import IdentificationError

__all__ = ["ReducedProblem", "table31_case"]

#: Relative size under which a normalised pivot means a column is a combination of the others.
_RANK_TOL = 1e-11


def table31_case(active: dict[str, str]) -> int | None:
    """Case number of Table 3.1 for an active set, or None when an upper p/omega_n bound is active.

    ``active`` maps ``p``, ``omega_n``, ``zeta`` to ``"lower"``, ``"upper"`` or ``"free"``.
    Case = 1 + [h3: zeta = zeta_min] + 2 [h2: omega_n = omega_n,min] + 4 [h1: p = p_min]
    + 8 [h4: zeta = zeta_max].
    """
    if active.get("p") == "upper" or active.get("omega_n") == "upper":
        return None
    return (
        1
        + (active.get("zeta") == "lower")
        + 2 * (active.get("omega_n") == "lower")
        + 4 * (active.get("p") == "lower")
        + 8 * (active.get("zeta") == "upper")
    )


class ReducedProblem:
    """f(p, omega_n, zeta) and theta_2 from sufficient statistics (module docstring).

    Parameters
    ----------
    stats : SufficientStatistics
        Statistics of [Phi, Y] with Phi's first 8 columns in the order of Eq. (3.11); further
        columns are extra linear terms solved with theta_2.
    bounds : PoleBounds
        The search box.

    Raises
    ------
    IdentificationError
        When a column of Phi is identically zero (e.g. no negative velocity: delta- not
        identifiable) or a theta_2 column is a linear combination of the others.
    """

    def __init__(self, stats: SufficientStatistics, bounds: PoleBounds) -> None:
        self.bounds = bounds
        self.names = stats.names
        n = stats.n_columns
        self.mirrored = _check_columns(stats)
        # a friction column the record never switches on is left out; its level mirrors the other's (theta2)
        kept = [j for j in range(3, n) if j != self.mirrored]
        m = len(kept) + 3  # columns solved
        self.n_theta2 = n - 3
        U = stats.factor
        if U.shape[0] < n + 1:
            U = np.vstack([U, np.zeros((n + 1 - U.shape[0], n + 1))])
        perm = kept + [0, 1, 2, n]
        Up = scipy.linalg.qr(U[:, perm], mode="r", check_finite=False)[0][: m + 1]
        norms = np.linalg.norm(Up[:, :m], axis=0)
        norms[norms == 0] = 1.0
        Up = Up.copy()
        Up[:, :m] /= norms
        scale = stats.scale
        d_y = scale[n]
        g = scale[perm[:m]] / (norms * d_y)  # theta = g * theta'' (column-normalised coordinates)
        k2 = m - 3
        piv = np.abs(np.diag(Up)[:k2])
        if piv.size and piv.min() < _RANK_TOL * max(1.0, piv.max()):
            j = perm[int(np.argmin(piv))]
            name = self.names[j]
            raise IdentificationError(
                f"regressor column {name!r} ({COLUMN_DESCRIPTIONS.get(name, 'extra column')}) is a linear "
                "combination of the other columns: its parameter is not identifiable from this capture"
            )
        n = m
        self._A22 = Up[:k2, :k2]
        self._A21 = Up[:k2, k2 : k2 + 3]
        self._a2y = Up[:k2, n]
        self._g1 = g[k2:]
        self._g2 = g[:k2]
        self.T = Up[k2 : k2 + 3, k2 : k2 + 3] / self._g1[None, :]  # acts on theta_1 directly
        self.c = Up[k2 : k2 + 3, n]
        self.rho = float(abs(Up[n, n]))
        self.y_scale = float(d_y)
        self._fscale = 0.5 / (d_y * d_y)
        self.nfev = 0

    # ------------------------------------------------------------------ objective
    def objective_theta1(self, th1: np.ndarray) -> np.ndarray:
        """f [mm^2] for theta_1 of shape (..., 3) (Eq. 4.12)."""
        r = np.asarray(th1) @ self.T.T - self.c
        self.nfev += int(np.prod(r.shape[:-1])) if r.ndim > 1 else 1
        return self._fscale * (np.sum(r * r, axis=-1) + self.rho**2)

    def objective(self, p, omega_n, zeta) -> np.ndarray:
        """f [mm^2] at p, omega_n [rad/s], zeta [-] (vectorised)."""
        return self.objective_theta1(theta1(p, omega_n, zeta))

    def valley(self, v: np.ndarray, *, tolerance: float = 0.01, points: int = 48, iterations: int = 25) -> dict:
        """How well the data pin the poles down: the profile of f along each pole variable.

        For ``points`` values of each variable across the box (log-spaced for p and omega_n), f is
        minimised over the other two (the best point of a grid, then damped Gauss-Newton, all
        values at once). A variable's range is that of the values whose profile stays within
        ``tolerance`` (relative) of f at ``v`` = (p, omega_n, zeta) [rad/s, rad/s, -], widened to
        include v. Where feedforward cancels the closed-loop poles (thesis Tables 3.5 and 4.2) the
        profile is flat over much of the box; a well-excited feedback loop pins it to one value.
        ``identifiable`` says omega_n stays within 25 % and zeta within 0.15 of the solution.
        Only canonical labellings (:func:`~identification.poles.canonical_mask`) are profiled: with
        three real poles, the other labellings of the solution's poles have the same objective and
        would show as a second valley far away in (p, omega_n, zeta) although the model is the same.

        Returns
        -------
        dict
            ``tolerance``, ``p_hz``, ``omega_n_hz``, ``zeta`` (each ``[lo, hi]``), ``identifiable``.
        """
        nfev = self.nfev
        # coordinates u = (log p, log omega_n, zeta), the poles' search variables: the box is a box in u
        lo, hi = (b[:3] for b in search_box(self.bounds))
        axes = [np.linspace(lo[i], hi[i], points if i < 2 else max(points // 2, 8)) for i in range(3)]
        G = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)  # coarse grid (n0, n1, n2, 3)

        def f(u):  # other labellings of the same poles are left out (they would mirror the valley)
            p, wn, z = np.exp(u[..., 0]), np.exp(u[..., 1]), u[..., 2]
            return np.where(canonical_mask(p, wn, z, self.bounds), self.objective(p, wn, z), np.inf)

        def r(u):  # residual of Gauss-Newton (self.residual), vectorised over the rows of u
            return self.residual(np.stack([np.exp(u[..., 0]), np.exp(u[..., 1]), u[..., 2]]))

        fg = f(G)
        f0 = float(self.objective_theta1(theta1(*v)))
        limit = (1.0 + tolerance) * f0
        out = {}
        for i, name in enumerate(("p_hz", "omega_n_hz", "zeta")):
            free = [j for j in range(3) if j != i]
            vals = axes[i]
            # best grid point of every slice as the start
            sl = np.moveaxis(fg, i, 0).reshape(vals.size, -1)
            best = np.argmin(sl, axis=1)
            g2 = np.moveaxis(G, i, 0).reshape(vals.size, -1, 3)
            u = g2[np.arange(vals.size), best].copy()
            fu = sl[np.arange(vals.size), best]
            lam = np.full(vals.size, 1e-3)
            for _ in range(iterations):  # damped Gauss-Newton on r = T theta1(u) - c, per slice
                h = 1e-6 * np.maximum(1.0, np.abs(u))
                r0 = r(u)
                J = np.empty(r0.shape + (2,))
                for k, j in enumerate(free):
                    d = np.zeros(3)
                    d[j] = 1.0
                    hj = h[:, j:j + 1]
                    J[..., k] = (r(u + hj * d) - r(u - hj * d)) / (2 * hj)
                JtJ = np.einsum("nik,nil->nkl", J, J) + lam[:, None, None] * np.eye(2)
                step = -np.linalg.solve(JtJ, np.einsum("nik,ni->nk", J, r0)[..., None])[..., 0]
                un = u.copy()
                un[:, free] = np.clip(u[:, free] + step, lo[free], hi[free])
                fn = f(un)
                better = fn < fu
                u[better], fu[better] = un[better], fn[better]
                lam = np.where(better, lam * 0.3, lam * 10.0)
            ok = fu <= limit
            x = v[i] if i == 2 else np.log(v[i])
            rng = np.append(vals[ok], x)
            lo_i, hi_i = float(rng.min()), float(rng.max())
            out[name] = [lo_i, hi_i] if i == 2 else [float(np.exp(lo_i)) / TWO_PI, float(np.exp(hi_i)) / TWO_PI]
        self.nfev = nfev  # a diagnostic, not part of the solve
        wn, z = v[1] / TWO_PI, v[2]
        return {
            "tolerance": tolerance,
            **out,
            "identifiable": bool(out["omega_n_hz"][0] >= wn / 1.25 and out["omega_n_hz"][1] <= 1.25 * wn
                                 and out["zeta"][0] >= z - 0.15 and out["zeta"][1] <= z + 0.15),
        }

    @property
    def unconstrained_objective(self) -> float:
        """Objective of the unconstrained least-squares solution (Case 1 of Table 3.1) [mm^2]."""
        return self._fscale * self.rho**2

    def residual(self, v: np.ndarray) -> np.ndarray:
        """r(v) with f = 1/2 (|r|^2 + rho^2) / d_y^2 (for Gauss-Newton), v = (p, omega_n, zeta) [rad/s]."""
        self.nfev += 1
        return theta1(v[0], v[1], v[2]) @ self.T.T - self.c

    def residual_jacobian(self, v: np.ndarray) -> np.ndarray:
        """d r / d v (3x3)."""
        return self.T @ theta1_jacobian(v[0], v[1], v[2])

    def gradient(self, v: np.ndarray) -> np.ndarray:
        """df/dv [mm^2 per rad/s, rad/s, -]."""
        r = self.residual(v)
        return 2.0 * self._fscale * (self.residual_jacobian(v).T @ r)

    # ------------------------------------------------------------- unconstrained
    def unconstrained_theta1(self) -> np.ndarray | None:
        """theta_1 of the unconstrained minimum, or None when T is singular."""
        try:
            th = scipy.linalg.solve_triangular(self.T * 1.0, self.c)
        except (np.linalg.LinAlgError, ValueError):
            return None
        if not np.all(np.isfinite(th)):
            return None
        return th

    def unconstrained_poles(self) -> list[np.ndarray]:
        """Every (p, omega_n, zeta) [rad/s] that realises the unconstrained minimum (maybe none)."""
        th = self.unconstrained_theta1()
        if th is None or th[2] <= 0:
            return []
        a2 = 1.0 / th[2]
        splits = pole_splits(th[1] * a2, a2, th[0] * a2)
        return [np.array([s["p_hz"] * TWO_PI, s["omega_n_hz"] * TWO_PI, s["zeta"]]) for s in splits]

    # ---------------------------------------------------------------- parameters
    def theta2(self, th1: np.ndarray) -> np.ndarray:
        """theta_2 (beta_0, beta_1, beta_2, delta+, delta-, extras) for theta_1 (Eq. 4.9)."""
        rhs = self._a2y - self._A21 @ (np.asarray(th1, float) / self._g1)
        th2 = self._g2 * scipy.linalg.solve_triangular(self._A22, rhs)
        if self.mirrored is None:
            return th2
        j = self.mirrored - 3  # delta- (4) or delta+ (3): the other level negated (Coulomb friction the same both ways)
        return np.insert(th2, j, -th2[3])

    def parameters(self, v: np.ndarray) -> tuple[dict[str, float], np.ndarray, np.ndarray]:
        """Model parameters for v = (p, omega_n, zeta) [rad/s].

        Returns
        -------
        parameters : dict
            a1..d1 of Eq. (3.3) via Eq. (3.10).
        theta : ndarray
            The full normalised vector (theta_1, theta_2).
        extra : ndarray
            Coefficients of extra columns multiplied by a2 (same scaling as d0, d1).
        """
        p, wn, z = (float(x) for x in v)
        a1, a2, a3 = denominator(p, wn, z)
        th1 = theta1(p, wn, z)
        th2 = self.theta2(th1)
        params = {
            "a1": a1,
            "a2": a2,
            "a3": a3,
            "b0": th2[2] * a2,
            "b1": th2[1] * a2,
            "b2": th2[0] * a2,
            "d0": th2[3] * a2,
            "d1": th2[4] * a2,
        }
        return params, np.concatenate([th1, th2]), th2[5:] * a2

    # ------------------------------------------------------------------- KKT
    def kkt_report(self, v: np.ndarray, *, rtol: float = 1e-7) -> dict:
        """Active bounds, multipliers and projected gradient at v (rad/s).

        A bound is active when v is within ``rtol`` (relative to the box width) of it. The
        multiplier of an active bound is the objective's slope into the box (>= 0 at a minimum).
        The projected gradient is scaled by the box widths (so its entries are in mm^2).
        """
        box = self.bounds.rad()
        grad = self.gradient(v)
        active, mult, proj = {}, {}, []
        for i, name in enumerate(("p", "omega_n", "zeta")):
            lo, hi = box[i]
            width = hi - lo
            g = grad[i] * width
            if v[i] - lo <= rtol * width:
                active[name] = "lower"
                mult[name] = g
                proj.append(min(g, 0.0))
            elif hi - v[i] <= rtol * width:
                active[name] = "upper"
                mult[name] = -g
                proj.append(max(g, 0.0))
            else:
                active[name] = "free"
                proj.append(g)
        return {
            "active": active,
            "multipliers": mult,
            "projected_gradient": float(np.max(np.abs(proj))),
            "case": table31_case(active),
        }

    def clip(self, v: np.ndarray) -> np.ndarray:
        """v clipped into the box (rad/s)."""
        box = self.bounds.rad()
        return np.array([min(max(v[i], box[i][0]), box[i][1]) for i in range(3)])

    def in_box(self, v: np.ndarray, *, rtol: float = 1e-12) -> bool:
        box = self.bounds.rad()
        return all(box[i][0] * (1 - rtol) <= v[i] <= box[i][1] * (1 + rtol) for i in range(3))


def _check_columns(stats: SufficientStatistics) -> int | None:
    """Name a regressor column that is identically zero; the index of a friction column that is while the other is
    not (the record moves one way only, or :class:`~identification.regressor.RegressorOptions` ``friction`` says so:
    that direction's level is not identified and mirrors the other's), else None."""
    zero = [j for j, name in enumerate(stats.names) if stats.absmax[j] == 0]
    friction = [j for j in zero if stats.names[j] in ("-PV", "-NV")]
    if len(friction) == 1:
        zero.remove(friction[0])
    for j in zero:
        name = stats.names[j]
        if name in ("-PV", "-NV"):
            raise IdentificationError(
                "friction not identifiable: the axis never moved (no sample with a measured velocity of either "
                "sign); the test must move the axis"
            )
        if name == "e_i":
            raise IdentificationError(
                "the measured position equals the reference at every sample: no tracking error to identify from"
            )
        raise IdentificationError(
            f"regressor column {name!r} ({COLUMN_DESCRIPTIONS.get(name, 'extra column')}) is zero at every "
            "sample: its parameter is not identifiable"
        )
    return friction[0] if len(friction) == 1 else None

