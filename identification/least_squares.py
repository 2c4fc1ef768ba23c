"""Least squares on tall, narrow matrices, columns scaled to unit norm: by QR, or through the Gram matrix.

The diagnosis solves many least-squares problems with a record's samples as rows (20,000 and more)
and a few to a hundred and thirty columns (Jacobians, Fourier bases). A QR or SVD of such a matrix
reads and rewrites it several times; its Gram matrix ``A'A`` costs one pass (a BLAS-3 product) and
the rest is p x p work. Measured 2026-11-23 on the 2-core development machine with one BLAS thread,
24,841 x 100: SVD 178-282 ms, QR 250 ms, ``A'A`` 11 ms.

Squaring the matrix squares its condition number, so both solvers here scale the columns to unit
norm first and fall back on an orthogonal factorisation when the scaled Gram matrix is too
ill-conditioned for the result to keep ~6 correct digits (condition number of the scaled ``A``
above 1e5).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

__all__ = ["solve_qr", "solve_scaled", "solve_gram", "damped_steps"]

#: Largest condition number of the scaled Gram matrix solved through it (cond(A)^2 <= 1e10).
MAX_GRAM_CONDITION = 1e10


def _scaled(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    sc = np.linalg.norm(A, axis=0)
    sc[sc == 0] = 1.0
    return A / sc, sc


def solve_qr(A: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Least-squares solution of ``A x = y`` by a column-scaled QR (for a base whose columns may be
    ill-conditioned, such as the regressor of Eq. 3.11); ``numpy.linalg.lstsq`` when R is singular."""
    As, sc = _scaled(np.asarray(A, float))
    q, r = np.linalg.qr(As)
    try:
        beta = scipy.linalg.solve_triangular(r, q.T @ y)
    except (np.linalg.LinAlgError, ValueError):
        beta = np.linalg.lstsq(As, y, rcond=None)[0]
    if not np.all(np.isfinite(beta)):
        beta = np.linalg.lstsq(As, y, rcond=None)[0]
    return beta / sc


def solve_scaled(A: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Least-squares solution of ``A x = y`` (columns scaled to unit norm).

    Through the Gram matrix when it is well enough conditioned (module docstring), else by
    ``numpy.linalg.lstsq`` (SVD).
    """
    As, sc = _scaled(np.asarray(A, float))
    if As.shape[1] == 0:
        return np.zeros(0)
    G = As.T @ As
    w, V = np.linalg.eigh(G)
    if np.all(np.isfinite(w)) and w[0] > w[-1] / MAX_GRAM_CONDITION:
        x = V @ ((V.T @ (As.T @ y)) / w)
    else:
        x = np.linalg.lstsq(As, y, rcond=None)[0]
    return x / sc


def solve_gram(G: np.ndarray, b: np.ndarray) -> np.ndarray | None:
    """The least-squares solution ``x`` of ``A x = y`` from the Gram matrix ``G = A'A`` and ``b = A'y``
    alone, as :func:`solve_scaled` computes it (columns scaled to unit norm, ``sqrt(diag G)``);
    None when the scaled Gram matrix is too ill-conditioned (the caller then solves with ``A``)."""
    sc = np.sqrt(np.maximum(np.diag(G), 0.0))
    sc[sc == 0] = 1.0
    if G.shape[0] == 0:
        return np.zeros(0)
    w, V = np.linalg.eigh(G / np.outer(sc, sc))
    if not (np.all(np.isfinite(w)) and w[0] > w[-1] / MAX_GRAM_CONDITION):
        return None
    return (V @ ((V.T @ (b / sc)) / w)) / sc


def damped_steps(G: np.ndarray, b: np.ndarray, damping: tuple[float, ...], relative: float = 1e-3, *,
                 reference: np.ndarray | None = None, share: float = 0.0) -> list[np.ndarray]:
    """Levenberg-Marquardt steps ``x`` minimising ``|A x - y|^2 + lam |S x|^2`` from the Gram matrix ``G = A'A``
    and ``b = A'y``, one per ``lam`` of ``damping`` (relative to the largest eigenvalue of the scaled Gram matrix;
    ``S`` the column norms, Marquardt's scaling), all from one eigen-decomposition.

    Directions whose singular value (of ``A`` with its columns scaled to unit norm) is below ``relative`` times the
    largest are left out: with no damping the step is the truncated-SVD least-squares solution. The scaled Gram
    matrix' eigenvalues are the singular values squared, exact up to rounding relative to the largest, ~1e-16,
    far below the cut at ``relative^2``.

    ``reference`` (a Gram matrix of the same parameters on more samples, e.g. a refit's training samples and the
    whole record's): a direction whose curvature in ``G`` is below ``share`` times its curvature in ``reference``
    is left out too (the samples of ``G`` do not determine it; ``share`` a ratio of squared norms).

    Notes
    -----
    Marquardt, "An algorithm for least-squares estimation of nonlinear parameters", J. SIAM 11 (1963): the
    damping turns the Gauss-Newton step towards the scaled steepest descent and shortens it.
    """
    sc = np.sqrt(np.maximum(np.diag(G), 0.0))
    sc[sc == 0] = 1.0
    if G.shape[0] == 0:
        return [np.zeros(0) for _ in damping]
    w, V = np.linalg.eigh(G / np.outer(sc, sc))
    top = w[-1]
    keep = w > (relative * relative) * top if top > 0 else np.zeros(w.size, bool)
    if reference is not None:
        keep &= w >= share * np.einsum("ij,ik,kj->j", V, reference / np.outer(sc, sc), V)
    Vk, wk = V[:, keep], w[keep]
    c = Vk.T @ (b / sc)
    return [(Vk @ (c / (wk + lam * top))) / sc for lam in damping]
