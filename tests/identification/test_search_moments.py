"""The equation-error screens of the time-periodic search from moments (SearchContext.ee_partial_fourier,
ee_validation_fourier) against the same screens with the stored windowed Fourier columns."""

from __future__ import annotations

import numpy as np
import pytest

import vcnc
from identification import identify
from identification.augmented import augment
from identification.bounds import as_bounds
from identification.capture_checks import check_capture
from identification.effects import TimePeriodic
from identification.searches import Data, SearchContext


@pytest.fixture(scope="module")
def context():
    import toolpaths

    machine = vcnc.machine("fadal-pid").with_axis_options("x", backlash=None)
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(20, 10.0, 12000.0, seed=1)), machine)
    cap = machine.with_effect("x", "time_periodic", None).simulate(sp, seed=1)
    model = identify(cap, axis="x", diagnose=False)
    xr, x, T = check_capture(cap, "x")
    valid = np.arange(x.size) >= int(0.8 * x.size)
    data = Data(xr=np.asarray(xr, float), x=np.asarray(x, float), T=T, train=~valid, valid=valid,
                bounds=as_bounds(model.bounds or None, T))
    return SearchContext(data, augment(model, []))


@pytest.mark.parametrize("harmonics,window", [(1, None), (8, None), (24, "mid")])
def test_ee_partial_fourier_matches_stored_columns(context, harmonics, window):
    _, _, t = context.ee_rows()
    win = None if window is None else (float(t[0] + 0.2 * np.ptp(t)), float(t[0] + 0.7 * np.ptp(t)))
    e = TimePeriodic(period=0.5, coefficients=((0.0, 0.0),) * harmonics, window=win)
    want = context.ee_partial(-e.window_basis(t))[0]
    got = context.ee_partial_fourier(t, 0.5, harmonics, e.envelope_weights(t)[0])
    assert got == pytest.approx(want, rel=1e-9)
    assert got < context.ee_rss


@pytest.mark.parametrize("window", [None, "mid"])
def test_ee_validation_fourier_matches_stored_columns(context, window):
    d = context.data
    t_tr, t_va = d.t[d.rows[d.tr_rows]], d.t[d.rows[d.va_rows]]
    win = None if window is None else (float(t_tr[0] + 0.2 * np.ptp(t_va)), float(t_va[-1] - 0.1 * np.ptp(t_va)))
    ladder = [1, 2, 3, 5, 8, 12]
    want = []
    for h in ladder:
        e = TimePeriodic(period=0.49, coefficients=((0.0, 0.0),) * h, window=win)
        want.append(context.ee_validation_rss(-e.window_basis(t_tr), -e.window_basis(t_va)))
    np.testing.assert_allclose(context.ee_validation_fourier(0.49, ladder, win), want, rtol=1e-9)
