"""The compiled moments of the period searches (identification.kernels.sinusoid_moments,
windowed_fourier_moments) against the same sums written out with numpy's sin and cos or a stored basis,
and the tangent-linear exact loop (run_exact_tangent) against forward differences of the loop."""

from __future__ import annotations

import numpy as np
import pytest

from identification.effects import TimePeriodic
from identification.kernels import (
    SINCOS_MAX_PHASE,
    fourier_gram,
    run_exact,
    run_exact_tangent,
    sinusoid_moments,
    windowed_fourier_moments,
)
from identification.reduced_model import discretize


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


@pytest.mark.parametrize("harmonics", [1, 5, 64])
def test_windowed_fourier_moments_match_stored_basis(harmonics):
    # the Gram matrix from trigonometric sums, and the products with r and q, against the stored columns
    rng = np.random.default_rng(7)
    n = 4000
    t = np.sort(rng.uniform(0.0, 300.0, n))
    phase = 2.0 * np.pi * t
    g = np.where(rng.uniform(size=n) < 0.7, rng.uniform(0.2, 1.0, n), 0.0)
    r = rng.standard_normal(n)
    q_t = np.ascontiguousarray(rng.standard_normal((4, n)))
    C = TimePeriodic.basis(t, 1.0, harmonics) * g[:, None]
    cs, ss, cr, qc = windowed_fourier_moments(np.sin(phase), np.cos(phase), g, r, q_t, harmonics)
    scale = float(np.sum(g * g))
    np.testing.assert_allclose(fourier_gram(cs, ss, harmonics), C.T @ C, rtol=0, atol=1e-11 * scale)
    np.testing.assert_allclose(cr, C.T @ r, rtol=0, atol=1e-11 * np.sqrt(scale) * np.linalg.norm(r))
    np.testing.assert_allclose(qc, q_t @ C, rtol=0, atol=1e-11 * np.sqrt(scale) * np.max(np.linalg.norm(q_t, axis=1)))


def test_run_exact_tangent_matches_forward_differences():
    # Stribeck, asymmetric viscous and position-periodic terms, whose slopes the tangent carries;
    # the perturbations keep every velocity sign (the Coulomb jump has no slope)
    p = {"a1": 104.1, "a2": 18546.9, "a3": 116.5, "b0": -0.054, "b1": -14.6, "b2": 18546.1,
         "d0": -1008.4, "d1": -1569.2}
    T = 0.001
    dm = discretize(p, T)
    t = np.arange(3000) * T
    xr = 20.0 * t + 0.5 * np.sin(2.0 * np.pi * 3.0 * t)
    st = np.array([5.0, 200.0, -150.0])
    asym, pp_period, pp_coef = 0.3, 7.0, np.array([[20.0, -10.0], [5.0, 3.0]])
    rng = np.random.default_rng(11)
    u = np.ascontiguousarray(rng.standard_normal((t.size, 3)) * 10.0)

    def run(wext):
        pos, vel = np.empty(t.size), np.empty(t.size)
        run_exact(dm.phi, dm.gamma, dm.c, dm.d, dm.cv, dm.dv, dm.dvs, dm.d0, dm.d1, xr, wext, st, asym, pp_period,
                  pp_coef, pos, vel)
        return pos, vel

    pos, vel = run(np.zeros(t.size))
    sens = run_exact_tangent(dm.phi, dm.gamma, dm.c, dm.cv, pos, vel, st, asym, pp_period, pp_coef, u)
    for j in range(u.shape[1]):
        eps = 1e-4
        (up, vu), (dn, vd) = run(eps * u[:, j]), run(-eps * u[:, j])
        assert np.array_equal(np.sign(vu), np.sign(vel)) and np.array_equal(np.sign(vd), np.sign(vel))
        fd = (up - dn) / (2.0 * eps)
        np.testing.assert_allclose(sens[:, j], fd, rtol=0, atol=1e-6 * np.max(np.abs(fd)))
