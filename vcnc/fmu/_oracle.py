"""What an exported FMU must output: ``model.simulate()`` of the model it was exported from.

For a model without effects that is :func:`identification.simulate` (the reduced model's
contract); with effects it is :meth:`identification.augmented.AugmentedAxisModel.simulate`. The
export checks its binary against this before reporting success; the tests use it too.
"""

from __future__ import annotations

import numpy as np

from vcnc.fmu._spec import ExportSpec

__all__ = ["expected_position", "check_reference"]


def expected_position(spec: ExportSpec, reference: np.ndarray, *, disturbance: np.ndarray | None = None) -> np.ndarray:
    """Measured position [mm] the FMU of ``spec`` gives for ``reference`` [mm] (and ``disturbance``)."""
    return spec.model().simulate(np.asarray(reference, dtype=float), disturbance=disturbance)


def check_reference(n: int, sample_time: float, *, seed: int = 0, start: float = 0.0) -> np.ndarray:
    """An identification test [mm]: random smooth point-to-point moves of up to 20 mm with dwells.

    Both directions, accelerations, constant-velocity-free reversals and standstill: every effect
    is exercised. ``sample_time`` [s] scales the move durations (40..300 samples at 1 ms).
    """
    rng = np.random.default_rng(seed)
    scale = 0.001 / float(sample_time)
    out = np.empty(n)
    k, pos = 0, float(start)
    while k < n:
        target = rng.uniform(-20.0, 20.0)
        m = max(2, int(rng.integers(40, 300) * scale))
        s = 0.5 - 0.5 * np.cos(np.pi * np.arange(1, m + 1) / m)
        seg = pos + (target - pos) * s
        dwell = np.full(int(rng.integers(0, 80) * scale), target)
        seg = np.concatenate([seg, dwell])[: n - k]
        out[k : k + seg.size] = seg
        k += seg.size
        pos = target
    return out
