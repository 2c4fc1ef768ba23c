"""Output-error refinement: evidence that it predicts held-out data better (so it is the default)."""

from __future__ import annotations

import numpy as np
import pytest

from identification import identify
from identification.synthetic import FADAL_PID_X, back_and_forth_reference, synthetic_capture


def _rms(a):
    return float(np.sqrt(np.mean(np.asarray(a) ** 2)))


@pytest.fixture(scope="module")
def models(pid_capture):
    return identify(pid_capture, refine="none", diagnose=False), identify(pid_capture, diagnose=False)


def test_output_error_predicts_held_out_data_better(models):
    """Held out: the Sec. 4.3.1 validation move (+/-20 mm, 70.71 mm/s, 424.26 mm/s^2) on the true axis."""
    val = back_and_forth_reference()
    truth = synthetic_capture(FADAL_PID_X, val).measured[:, 0]
    e_true = val - truth
    ee, oe = models
    err_ee = _rms((val - ee.simulate(val)) - e_true) / _rms(e_true)
    err_oe = _rms((val - oe.simulate(val)) - e_true) / _rms(e_true)
    assert oe.method == "exact+oe"
    assert err_oe < err_ee
    assert err_oe < 0.01  # within 1% RMS of the true tracking error (the paper: 10-15%)
    assert oe.fit["rms_um"] < ee.fit["rms_um"]


def test_output_error_recovers_true_parameters(models):
    """Same model structure, small noise: the refinement lands on Table 3.4's 'Actual' values."""
    m = models[1]
    assert m.poles["omega_n_hz"] == pytest.approx(33.0, rel=0.005)
    assert m.poles["zeta"] == pytest.approx(0.447, rel=0.01)
    assert m.poles["p_hz"] == pytest.approx(1.173, rel=0.02)
    for k in ("d0", "d1"):
        assert m.parameters[k] == pytest.approx(FADAL_PID_X[k], rel=0.01)
