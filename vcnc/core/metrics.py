"""The error figures every report gives: RMS and largest absolute value, in micrometres."""

from __future__ import annotations

import numpy as np

__all__ = ["error_metrics"]


def error_metrics(error_mm: np.ndarray) -> dict[str, float]:
    """``{"rms_um", "max_um"}`` of an error [mm]; NaN for an empty one."""
    e = np.asarray(error_mm, dtype=float)
    if e.size == 0:
        return {"rms_um": float("nan"), "max_um": float("nan")}
    return {"rms_um": float(np.sqrt(np.mean(e * e)) * 1e3), "max_um": float(np.max(np.abs(e)) * 1e3)}
