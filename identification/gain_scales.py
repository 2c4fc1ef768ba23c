"""Scale gains of an integer-parameter controller (Liu, Lai, Yen 2008, seed 004, Sec. 3).

A controller running on an integer processor takes integer settings whose relation to the real
gains is unknown: each coefficient is ``k_j * (integer setting)_j`` with an unknown scale gain
k_j. With the measurement vector phi(k) of past errors, outputs and control signals, the control
law is linear in the scale gains (Eqs. 4-6 of the paper)::

    u(k) = phi(k)^T Theta psi,    Theta = diag(integer settings),  psi = (k_d0, ..., k_g,p)

so psi follows from recorded (e, u, y) by least squares. For the PDF loop of the paper's grinding
machine (integral of the error with setting K_I = 19, feedback of the output with setting
K_F = 260, T = 250 us), Eq. (10) reads::

    u(k) = [e(k), u(k-1), y(k) - y(k-1)] diag(K_I T, 1, -K_F) [k1, 1, k2]^T

Sign: Eqs. (9)-(12) as printed add ``+ 260 k2 (y(k) - y(k-1))``; with the paper's own plant
P*(z) = 1.218 z^-1 / (1 - 1.892 z^-1 + 0.886 z^-2) and the reported k1, k2 that loop diverges,
while the pseudo-derivative-feedback law u = K_I/s e - K_F y (negative feedback of y) is stable
and has the paper's k2 > 0. We therefore use the minus sign. Eq. (12) - the output increment
predicted by the plant model from past data instead of the measured y(k) - is available with
``plant=``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from vcnc.core.errors import IdentificationError

__all__ = ["GainScaleResult", "identify_gain_scales", "pdf_gain_scales", "simulate_pdf_loop", "overshoot"]

#: The paper's simulation plant P*(z) = 1.218 z^-1/(1 - 1.892 z^-1 + 0.886 z^-2), Eq. (11).
PAPER_PLANT: tuple[tuple[float, ...], tuple[float, ...]] = ((0.0, 1.218), (1.0, -1.892, 0.886))
#: The paper's sampling time [s] (Sec. 3.2).
PAPER_SAMPLE_TIME = 250e-6
#: Averaged scale gains the paper reports (Sec. 4, Table 1).
PAPER_K1, PAPER_K2 = 6.942e-2, 2.359e-4


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class GainScaleResult:
    """Least-squares scale gains.

    Attributes
    ----------
    psi : ndarray
        All scale gains (known ones included), in the order of the measurement vector.
    names : tuple of str
        Their names.
    residual_rms : float
        RMS of u - phi^T Theta psi [units of u].
    condition : float
        Condition number of the scaled regression (persistence of excitation, Sec. 3.2).
    samples : int
    """

    psi: np.ndarray
    names: tuple[str, ...]
    residual_rms: float
    condition: float
    samples: int

    def __getitem__(self, name: str) -> float:
        return float(self.psi[self.names.index(name)])

    def to_dict(self) -> dict:
        return {
            "gains": {n: float(v) for n, v in zip(self.names, self.psi)},
            "residual_rms": self.residual_rms,
            "condition": self.condition,
            "samples": self.samples,
        }


def identify_gain_scales(
    phi: np.ndarray,
    u: np.ndarray,
    integer_parameters: Sequence[float],
    *,
    known: Mapping[int, float] | None = None,
    names: Sequence[str] | None = None,
) -> GainScaleResult:
    """Least squares for psi in u(k) = phi(k)^T Theta psi (Eqs. 4-6 of seed 004).

    Parameters
    ----------
    phi : ndarray, shape (N, q)
        Measurement vectors phi(k) (rows).
    u : ndarray, shape (N,)
        Control signal u(k).
    integer_parameters : sequence of float, length q
        Diagonal of Theta (the settings entered in the controller, with any fixed factor).
    known : mapping of int to float, optional
        Scale gains known in advance (e.g. ``{1: 1.0}`` for the u(k-1) term of Eq. 10).
    names : sequence of str, optional
    """
    phi = np.asarray(phi, float)
    u = np.asarray(u, float).ravel()
    theta = np.asarray(integer_parameters, float)
    if phi.ndim != 2 or phi.shape[0] != u.size or phi.shape[1] != theta.size:
        raise IdentificationError(
            f"phi has shape {phi.shape}, u {u.shape}, Theta {theta.shape}; expected (N, q), (N,), (q,)"
        )
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(u))):
        raise IdentificationError("e, u, y must be finite")
    known = dict(known or {})
    A = phi * theta[None, :]
    free = [j for j in range(theta.size) if j not in known]
    rhs = u - sum((A[:, j] * v for j, v in known.items()), np.zeros_like(u))
    Af = A[:, free]
    col = np.linalg.norm(Af, axis=0)
    if np.any(col == 0):
        j = free[int(np.argmin(col))]
        raise IdentificationError(f"measurement column {j} is zero: its scale gain is not identifiable")
    sol, *_ = np.linalg.lstsq(Af / col, rhs, rcond=None)
    psi = np.empty(theta.size)
    for j, v in known.items():
        psi[j] = v
    psi[free] = sol / col
    s = np.linalg.svd(Af / col, compute_uv=False)
    resid = u - A @ psi
    return GainScaleResult(
        psi=psi,
        names=tuple(names) if names is not None else tuple(f"k{j}" for j in range(theta.size)),
        residual_rms=float(np.sqrt(np.mean(resid**2))),
        condition=float(s[0] / s[-1]) if s[-1] > 0 else float("inf"),
        samples=int(u.size),
    )


def pdf_gain_scales(
    e: np.ndarray,
    u: np.ndarray,
    y: np.ndarray,
    *,
    integer_parameters: tuple[float, float] = (19.0, 260.0),
    sample_time: float = PAPER_SAMPLE_TIME,
    plant: tuple[Sequence[float], Sequence[float]] | None = None,
    position_scale: float = 1.0,
) -> GainScaleResult:
    """Scale gains k1 (integral setting) and k2 (feedback setting) of a PDF loop (Eq. 10 / 12).

    Parameters
    ----------
    e, u, y : ndarray, shape (N,)
        Error r - y, control signal, output, sampled every ``sample_time``.
    integer_parameters : (K_I, K_F)
        Controller settings (19, 260 in the paper).
    sample_time : float
        T [s] (the integral's factor: 19 T = 4.75e-3 at 250 us).
    plant : (b, a), optional
        Plant P(z) = (b0 + b1 z^-1 + ...)/(1 + a1 z^-1 + ...); when given, y(k) in the regressor
        is predicted from past u, y (Eq. 12) instead of measured (Eq. 10).
    position_scale : float
        Factor from the units of ``e`` and ``y`` to those the controller works in (1e-3 when a
        capture in mm comes from the paper's loop, which works in metres).

    Returns
    -------
    GainScaleResult
        ``result["k1"]``, ``result["k2"]`` (and ``"k_u"`` = 1, fixed).
    """
    e, u, y = (np.asarray(a, float).ravel() for a in (e, u, y))
    e, y = e * position_scale, y * position_scale
    if not (e.size == u.size == y.size) or e.size < 10:
        raise IdentificationError(f"e, u, y must have the same length >= 10 (got {e.size}, {u.size}, {y.size})")
    ki, kf = integer_parameters
    if plant is None:
        yk = y
    else:
        b = np.asarray(plant[0], float)
        a = np.asarray(plant[1], float)
        yk = np.array([_plant_output(b, a, u, y, k) for k in range(y.size)])
    k0 = 2
    phi = np.column_stack([e[k0:], u[k0 - 1 : -1], yk[k0:] - y[k0 - 1 : -1]])
    return identify_gain_scales(
        phi, u[k0:], (ki * sample_time, 1.0, -kf), known={1: 1.0}, names=("k1", "k_u", "k2")
    )


def _plant_output(b: np.ndarray, a: np.ndarray, u: np.ndarray, y: np.ndarray, k: int) -> float:
    """y(k) of P(z) = (b0 + b1 z^-1 + ...)/(a0 + a1 z^-1 + ...) from past u and y (b0 unused:
    the plant has at least one sample of delay)."""
    acc = 0.0
    for j in range(1, b.size):
        if k - j >= 0:
            acc += b[j] * u[k - j]
    for j in range(1, a.size):
        if k - j >= 0:
            acc -= a[j] * y[k - j]
    return acc / a[0]


def simulate_pdf_loop(
    reference: np.ndarray,
    *,
    k1: float,
    k2: float,
    integer_parameters: tuple[float, float],
    sample_time: float = PAPER_SAMPLE_TIME,
    plant: tuple[Sequence[float], Sequence[float]] = PAPER_PLANT,
) -> dict[str, np.ndarray]:
    """Closed PDF loop u(k) = u(k-1) + K_I T k1 e(k) - K_F k2 (y(k) - y(k-1)) around P(z).

    Returns ``{"y", "u", "e"}`` (same length as ``reference``).
    """
    r = np.asarray(reference, float)
    b = np.asarray(plant[0], float)
    a = np.asarray(plant[1], float)
    ki, kf = integer_parameters
    n = r.size
    y, u, e = np.zeros(n), np.zeros(n), np.zeros(n)
    for k in range(n):
        y[k] = _plant_output(b, a, u, y, k)
        e[k] = r[k] - y[k]
        du = ki * sample_time * k1 * e[k] - kf * k2 * (y[k] - (y[k - 1] if k else 0.0))
        u[k] = (u[k - 1] if k else 0.0) + du
    return {"y": y, "u": u, "e": e}


def overshoot(y: np.ndarray, target: float) -> float:
    """Overshoot of a response past ``target``, in % of |target| (0 when it never passes it)."""
    if target == 0:
        raise IdentificationError("overshoot needs a non-zero target")
    past = (np.asarray(y) - target) * np.sign(target)
    return float(max(0.0, past.max()) / abs(target) * 100.0)
