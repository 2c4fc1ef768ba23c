"""The compiled moments of the period searches (identification.kernels.sinusoid_moments) against
the same sums written out with numpy's sin and cos."""

from __future__ import annotations

import numpy as np
import pytest

from identification.kernels import SINCOS_MAX_PHASE, sinusoid_moments


def _direct(scaled, periods, r, q_t):
    m, qs, qc = [], [], []
    for p in periods:
        s, c = np.sin(scaled / p), np.cos(scaled / p)
        m.append([s @ s, s @ c, c @ c, r @ s, r @ c])
        qs.append(q_t @ s)
        qc.append(q_t @ c)
    return np.array(m), np.array(qs), np.array(qc)


@pytest.mark.parametrize("top", [1.0, 300.0, 2.0 * np.pi * 3600.0 / 0.01], ids=["small", "mm", "one-hour-at-10ms"])
def test_sinusoid_moments_match_numpy(top):
    # phases up to 2 pi 3600 s / 0.01 s = 2.3e6 rad lie beyond the fast reduction's range: libm's path
    rng = np.random.default_rng(3)
    scaled = 2.0 * np.pi * np.sort(rng.uniform(-top, top, 3000))
    periods = np.geomspace(0.01, 40.0, 25)
    r = rng.standard_normal(scaled.size)
    q_t = np.ascontiguousarray(rng.standard_normal((4, scaled.size)))
    for got, want in zip(sinusoid_moments(scaled, periods, r, q_t), _direct(scaled, periods, r, q_t)):
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * np.max(np.abs(want)))
    assert (np.max(np.abs(scaled)) / periods[0] > SINCOS_MAX_PHASE) == (top > 1000.0)


def test_sinusoid_moments_at_quadrant_boundaries():
    # phases exactly on and beside multiples of pi/4 and pi/2, where the reduction switches quadrant
    k = np.arange(-40, 41)
    phases = np.concatenate([k * np.pi / 4, k * np.pi / 2 + 1e-9, k * np.pi / 2 - 1e-9, [0.0, -0.0, 1e-300]])
    r = np.ones(phases.size)
    q_t = np.ones((1, phases.size))
    for j in range(phases.size):
        one = phases[j:j + 1]
        m, _, _ = sinusoid_moments(one, np.array([1.0]), r[:1], q_t[:, :1])
        assert m[0, 3] == pytest.approx(np.sin(one[0]), abs=2.3e-16)
        assert m[0, 4] == pytest.approx(np.cos(one[0]), abs=2.3e-16)
