"""What an exported FMU must output: ``identification.simulate`` plus the representable effects.

The export checks its binary against this before reporting success; the tests use it too.
"""

from __future__ import annotations

import numpy as np

from vcnc.fmu._spec import ExportSpec

__all__ = ["expected_position"]


def _play(x: np.ndarray, width: float) -> np.ndarray:
    """Play operator of total width ``width`` [mm], centred at the first sample."""
    half = 0.5 * width
    out = np.empty_like(x)
    load = x[0]
    for k, xk in enumerate(x):  # test oracle only: short signals
        if xk - load > half:
            load = xk - half
        elif xk - load < -half:
            load = xk + half
        out[k] = load
    return out


def expected_position(spec: ExportSpec, reference: np.ndarray, *, disturbance: np.ndarray | None = None) -> np.ndarray:
    """Measured position [mm] the FMU of ``spec`` gives for ``reference`` [mm] (and ``disturbance``)."""
    from identification import simulate

    ref = np.asarray(reference, dtype=float)
    n = spec.delay_samples
    seen = ref if n == 0 else np.concatenate([np.full(min(n, ref.size), ref[0]), ref[: max(ref.size - n, 0)]])
    x = simulate(spec.parameters, seen, spec.sample_time, disturbance=disturbance)
    return _play(x, spec.backlash) if spec.backlash > 0 else x
