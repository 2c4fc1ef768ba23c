"""Regressor of Eqs. (3.9)-(3.11) and its streamed sufficient statistics (Eq. 3.19)."""

from __future__ import annotations

import numpy as np
import pytest

from identification import COLUMNS, RegressorOptions, SufficientStatistics, regressor, statistics
from vcnc.errors import IdentificationError

T = 1e-3


def test_column_order_is_eq_3_11():
    assert COLUMNS == ("e_i", "-v", "-a", "x_r", "v_r", "a_r", "-PV", "-NV")


def test_central_differences_as_in_section_3_2():
    """Sec. 3.2: v_k = (x_{k+1}-x_{k-1})/2T, a_k = (v_{k+1}-v_{k-1})/2T, e_i,k = T sum_{m<=k}(x_r,m - x_m)."""
    rng = np.random.default_rng(0)
    x = np.cumsum(rng.normal(size=50))
    xr = x + rng.normal(size=50)
    phi, y = regressor(xr, x, T)
    v = (x[2:] - x[:-2]) / (2 * T)
    a = (v[2:] - v[:-2]) / (2 * T)
    k = np.arange(2, 48)
    np.testing.assert_allclose(phi[:, 1], -v[1:-1])
    np.testing.assert_allclose(phi[:, 2], -a)
    np.testing.assert_allclose(phi[:, 0], T * np.cumsum(xr - x)[k])
    np.testing.assert_array_equal(phi[:, 3], xr[k])
    np.testing.assert_array_equal(phi[:, 6], -(v[1:-1] > 0).astype(float))
    np.testing.assert_array_equal(phi[:, 7], -(v[1:-1] < 0).astype(float))
    np.testing.assert_array_equal(y, x[k])


@pytest.mark.parametrize("window", [0, 7, 11])
def test_derivatives_exact_on_quadratics(window):
    t = np.arange(200) * T
    x = 3.0 + 40.0 * t - 900.0 * t**2
    phi, _ = regressor(x, x + 1e-3, T, options=RegressorOptions(smoothing_window=window))
    h = RegressorOptions(smoothing_window=window).half_width
    np.testing.assert_allclose(-phi[:, 1], 40.0 - 1800.0 * t[h:-h], rtol=1e-9)
    np.testing.assert_allclose(-phi[:, 2], -1800.0, rtol=1e-6)


def test_deadband_clears_friction_switches():
    x = np.concatenate([np.linspace(0, 1, 50), np.full(50, 1.0) + 1e-6 * (-1) ** np.arange(50), np.linspace(1, 0, 50)])
    phi, _ = regressor(x, x, T, options=RegressorOptions(velocity_deadband=0.01))
    still = slice(55, 90)
    assert np.all(phi[still, 6] == 0) and np.all(phi[still, 7] == 0)


@pytest.mark.parametrize("chunk", [16, 1000, 100000])
def test_streamed_statistics_equal_direct_normal_equations(pid_capture, chunk):
    xr, x = pid_capture.reference[:, 0], pid_capture.measured[:, 0]
    phi, y = regressor(xr, x, T)
    st = statistics(xr, x, T, options=RegressorOptions(chunk=chunk))
    np.testing.assert_allclose(st.P, phi.T @ phi, rtol=1e-9, atol=1e-9 * np.abs(phi.T @ phi).max())
    np.testing.assert_allclose(st.R, phi.T @ y, rtol=1e-9, atol=1e-9 * np.abs(phi.T @ y).max())
    assert st.gamma == pytest.approx(y @ y, rel=1e-12)
    assert st.n_samples == y.size


def test_statistics_reject_bad_blocks():
    st = SufficientStatistics(8)
    with pytest.raises(IdentificationError, match="shape"):
        st.update(np.zeros((3, 7)), np.zeros(3))
    with pytest.raises(IdentificationError, match="NaN"):
        st.update(np.full((3, 8), np.nan), np.zeros(3))
    with pytest.raises(IdentificationError, match="smoothing_window"):
        RegressorOptions(smoothing_window=4)
