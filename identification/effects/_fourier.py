"""Fourier bases shared by the periodic effects (in position and in time)."""

from __future__ import annotations

import numpy as np

__all__ = ["fourier_basis", "fourier_eval"]


def fourier_basis(phase: np.ndarray, harmonics: int) -> np.ndarray:
    """Columns sin(h phase), cos(h phase) for h = 1..harmonics (interleaved), phase [rad]."""
    h = np.arange(1, harmonics + 1)
    a = np.outer(phase, h)
    out = np.empty((phase.size, 2 * harmonics))
    out[:, 0::2] = np.sin(a)
    out[:, 1::2] = np.cos(a)
    return out


def fourier_eval(phase: np.ndarray, coef: np.ndarray) -> np.ndarray:
    """sum_h A_h sin(h phase) + B_h cos(h phase) for coef of shape (H, 2)."""
    coef = np.asarray(coef, float).reshape(-1, 2)
    return fourier_basis(phase, coef.shape[0]) @ coef.ravel()
