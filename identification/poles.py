"""Pole parametrisation of the reduced model's characteristic polynomial.

The closed-loop characteristic polynomial of Eq. (3.7) of the thesis,

    s^3 + a1 s^2 + a2 s + a3 = (s + p)(s^2 + 2 zeta omega_n s + omega_n^2),

links the denominator parameters (a1, a2, a3) to the search variables (p, omega_n, zeta) in which
the stability bounds of Eq. (3.8) are box constraints. The normalised denominator parameters of
Eq. (3.14) are ``theta_1 = (alpha_i, alpha_1, alpha_2) = (a3, a1, 1) / a2``.

Formulas take angular frequencies [rad/s]; names ending in ``_hz`` are in Hz.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "denominator",
    "theta1",
    "theta1_jacobian",
    "poles_from_denominator",
    "pole_splits",
    "canonical",
    "canonical_mask",
    "pole_table",
    "zero_table",
]

TWO_PI = 2.0 * math.pi


def denominator(p: np.ndarray | float, omega_n: np.ndarray | float, zeta: np.ndarray | float):
    """(a1, a2, a3) of Eq. (3.7) from p [rad/s], omega_n [rad/s], zeta [-] (vectorised)."""
    a1 = p + 2.0 * zeta * omega_n
    a2 = omega_n * omega_n + 2.0 * p * zeta * omega_n
    a3 = p * omega_n * omega_n
    return a1, a2, a3


def theta1(p, omega_n, zeta) -> np.ndarray:
    """Normalised denominator parameters (alpha_i, alpha_1, alpha_2) of Eq. (3.14).

    Parameters
    ----------
    p, omega_n : array_like
        Real pole and natural frequency [rad/s].
    zeta : array_like
        Damping ratio [-].

    Returns
    -------
    ndarray, shape (..., 3)
        ``(a3/a2 [1/s], a1/a2 [s], 1/a2 [s^2])``.
    """
    a1, a2, a3 = denominator(np.asarray(p, float), np.asarray(omega_n, float), np.asarray(zeta, float))
    return np.stack([a3 / a2, a1 / a2, 1.0 / a2], axis=-1)


def theta1_jacobian(p: float, omega_n: float, zeta: float) -> np.ndarray:
    """d(alpha_i, alpha_1, alpha_2)/d(p, omega_n, zeta): the matrix G of Eq. (3.15).

    Written from the chain rule through (a1, a2, a3) rather than the printed closed form, which
    is algebraically the same but easier to check.
    """
    a1, a2, a3 = denominator(p, omega_n, zeta)
    # d(a1, a2, a3)/d(p, omega_n, zeta)
    da = np.array(
        [
            [1.0, 2.0 * zeta, 2.0 * omega_n],
            [2.0 * zeta * omega_n, 2.0 * omega_n + 2.0 * p * zeta, 2.0 * p * omega_n],
            [omega_n * omega_n, 2.0 * p * omega_n, 0.0],
        ]
    )
    # d(a3/a2, a1/a2, 1/a2)/d(a1, a2, a3)
    dt = np.array(
        [
            [0.0, -a3 / a2**2, 1.0 / a2],
            [1.0 / a2, -a1 / a2**2, 0.0],
            [0.0, -1.0 / a2**2, 0.0],
        ]
    )
    return dt @ da


def poles_from_denominator(a1: float, a2: float, a3: float) -> dict[str, float] | None:
    """(p, omega_n, zeta) of Eq. (3.7) from the denominator, or None when no such form exists.

    The cubic always has a real root; the remaining quadratic gives omega_n and zeta. When all
    three roots are real the split is not unique: the slowest root is taken as ``p`` (as in
    Tables 3.3 and 3.4 of the thesis, where the real pole is the slow one). Returns None when
    the polynomial is not stable (a root with non-negative real part).

    Returns
    -------
    dict
        ``{"p_hz", "omega_n_hz", "zeta"}``.
    """
    splits = pole_splits(a1, a2, a3)
    if not splits:
        return None
    return splits[0]


def pole_splits(a1: float, a2: float, a3: float) -> list[dict[str, float]]:
    """Every way of writing the (stable) cubic as (s + p)(s^2 + 2 zeta omega_n s + omega_n^2).

    One split when there is a complex pair; three when all roots are real (slowest ``p`` first).
    Empty when a root is not in the open left half plane.
    """
    roots = np.roots([1.0, a1, a2, a3])
    if np.any(roots.real >= 0.0):
        return []
    real = [r for r in roots if abs(r.imag) <= 1e-9 * max(1.0, abs(r))]
    out = []
    candidates = sorted(real, key=lambda r: abs(r.real)) if len(real) == 3 else real[:1]
    for r in candidates:
        p = -float(r.real)
        # remaining quadratic: s^2 + (a1 - p) s + a3 / p
        c1 = a1 - p
        c0 = a3 / p
        if c0 <= 0.0 or c1 <= 0.0:
            continue
        wn = math.sqrt(c0)
        out.append({"p_hz": p / TWO_PI, "omega_n_hz": wn / TWO_PI, "zeta": c1 / (2.0 * wn)})
    return out


def _splits_of(p, omega_n, zeta):
    """The three labellings of an all-real pole set, slowest ``p`` first (vectorised).

    For arrays p, omega_n [rad/s] and zeta > 1 [-], returns (P, W, Z, own), P, W, Z of shape
    (..., 3): split j takes the j-th slowest root as p and the other two as the pair; ``own`` is
    the index of the given labelling (ties go to the slower index).
    """
    p, wn, z = np.broadcast_arrays(*(np.asarray(a, float) for a in (p, omega_n, zeta)))
    s = np.sqrt(np.maximum(z * z - 1.0, 0.0))
    roots = np.stack([p, wn * (z - s), wn * (z + s)], axis=-1)
    order = np.argsort(roots, axis=-1, kind="stable")
    r = np.take_along_axis(roots, order, axis=-1)
    own = np.argmax(order == 0, axis=-1)
    rest = np.stack([r[..., [1, 2]], r[..., [0, 2]], r[..., [0, 1]]], axis=-2)  # (..., 3, 2)
    W = np.sqrt(rest[..., 0] * rest[..., 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        Z = (rest[..., 0] + rest[..., 1]) / (2.0 * W)
    return r, W, Z, own


def canonical_mask(p, omega_n, zeta, bounds) -> np.ndarray:
    """True where (p, omega_n, zeta) [rad/s, rad/s, -] is the canonical labelling of its poles.

    With zeta > 1 all three poles are real and (p, omega_n, zeta) is one of up to three labellings
    of the same characteristic polynomial (which root is ``p``): the objective of Eq. (3.12), the
    model parameters a1..d1 and every prediction are the same for all of them. The canonical one
    is the first labelling inside ``bounds`` (a :class:`~identification.bounds.PoleBounds`) in the
    order slowest ``p`` first (as :func:`pole_splits`, and as the thesis' tables label the slow
    real pole p). Points with zeta <= 1 (a complex or double pair), and points none of whose
    labellings lies in the box, are canonical.
    """
    P, W, Z, own = _splits_of(p, omega_n, zeta)
    inside = bounds.contains_rad(P, W, Z)
    real = np.asarray(zeta, float) > 1.0
    return ~real | ~np.any(inside, axis=-1) | (np.argmax(inside, axis=-1) == own)


def canonical(p: float, omega_n: float, zeta: float, bounds) -> tuple[float, float, float]:
    """The canonical labelling (see :func:`canonical_mask`) of the poles of (p, omega_n, zeta).

    Frequencies in rad/s. Returns the point unchanged when it is canonical.
    """
    if canonical_mask(p, omega_n, zeta, bounds):
        return float(p), float(omega_n), float(zeta)
    P, W, Z, _ = _splits_of(p, omega_n, zeta)
    j = int(np.argmax(bounds.contains_rad(P, W, Z)))
    return float(P[j]), float(W[j]), float(Z[j])


def _root_table(roots: np.ndarray) -> list[dict[str, float]]:
    """Roots as frequency [Hz] and damping [-], in the convention of Tables 3.3-3.5.

    For a root r: frequency |r| / 2 pi, damping -Re(r)/|r| (1 for a stable real root, -1 for an
    unstable real root, as the tables print zeros in the right half plane).
    """
    rows = []
    for r in sorted(roots, key=lambda z: (abs(z), z.imag)):
        mag = abs(r)
        rows.append(
            {
                "frequency_hz": float(mag / TWO_PI),
                "damping": float(-r.real / mag) if mag > 0 else 1.0,
                "real": float(r.real),
                "imag": float(r.imag),
            }
        )
    return rows


def pole_table(a1: float, a2: float, a3: float) -> list[dict[str, float]]:
    """The three closed-loop poles as frequency [Hz] and damping [-] (Tables 3.3-3.5)."""
    return _root_table(np.roots([1.0, a1, a2, a3]))


def zero_table(b0: float, b1: float, b2: float, a3: float) -> list[dict[str, float]]:
    """The zeros of G_track, numerator b0 s^3 + b1 s^2 + b2 s + a3, as frequency and damping."""
    coeffs = np.trim_zeros(np.array([b0, b1, b2, a3], float), "f")
    if coeffs.size <= 1:
        return []
    return _root_table(np.roots(coeffs))
