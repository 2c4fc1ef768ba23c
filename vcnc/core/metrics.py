"""The error figures every report gives: RMS and largest absolute value, in micrometres."""

from __future__ import annotations

import numpy as np

__all__ = ["error_metrics", "true_runs"]


def error_metrics(error_mm: np.ndarray) -> dict[str, float]:
    """``{"rms_um", "max_um"}`` of an error [mm]; NaN for an empty one."""
    e = np.asarray(error_mm, dtype=float)
    if e.size == 0:
        return {"rms_um": float("nan"), "max_um": float("nan")}
    return {"rms_um": float(np.sqrt(np.mean(e * e)) * 1e3), "max_um": float(np.max(np.abs(e)) * 1e3)}


def true_runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Contiguous stretches ``[start, stop)`` of samples where ``mask`` is True."""
    edges = np.diff(np.concatenate([[0], np.asarray(mask, bool).astype(np.int8), [0]]))
    return [(int(a), int(b)) for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1))]
