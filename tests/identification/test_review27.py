"""Defects found in the review of session 27's identification changes (review27)."""

from __future__ import annotations

import numpy as np
import pytest

from identification.capture_checks import check_jumps
from vcnc.errors import IdentificationError

T = 1e-3


def test_a_larger_burst_of_vibration_does_not_hide_a_lasting_jump():
    # check_jumps judged only the largest step: a +-10 um burst that passes hid an 8 um datum jump 4 s later, which
    # alone is refused
    t = np.arange(10000) * T
    xr = 10.0 * np.sin(2.0 * np.pi * 0.5 * t)
    x = np.interp(t - 0.01, t, xr)
    x[3000:3050] += 0.01 * (-1.0) ** np.arange(50)
    check_jumps(xr, x, T, "x", "log.csv")  # the burst alone passes
    x[7000:] += 0.008
    with pytest.raises(IdentificationError, match=r"log.csv: axis 'x': the measured position jumps by 0.007997 mm at "
                                                  r"sample 7000"):
        check_jumps(xr, x, T, "x", "log.csv")


def test_pure_delay_baseline_equals_the_best_delayed_reference():
    # the baseline's sums of squares stand for delay_reference's whole-sample shifts (held ends included): the same
    # best shift and RMS as shifting and interpolating each time, the way it was computed before (10x slower)
    from identification.dead_time import delay_reference, pure_delay_baseline

    rng = np.random.default_rng(7)
    t = np.arange(3000) * T
    xr = 5.0 * np.sin(2.0 * np.pi * 1.3 * t) + rng.normal(0.0, 1e-3, t.size)
    for lag in (0.017, -0.006):
        x = np.interp(t - lag, t, xr) + rng.normal(0.0, 2e-3, t.size)
        rms = {s: float(np.sqrt(np.mean((x - delay_reference(xr, s)) ** 2))) for s in range(-500, 501)}
        s = min(rms, key=rms.get)
        base = pure_delay_baseline(xr, x, T)
        assert base["pure_delay_samples"] == s == round(lag / T)
        assert base["pure_delay_rms_um"] == pytest.approx(rms[s] * 1e3, rel=1e-12)
        assert base["following_error_rms_um"] == pytest.approx(rms[0] * 1e3, rel=1e-12)


def test_a_lone_spike_is_named_and_a_burst_passes():
    # identwild's lasting rule let a single corrupted sample pass (it departs and comes back in one sample, as a burst
    # of vibration does); a lone spike, its neighbours quiet, is refused again, naming its sample; the burst of the
    # first test, and a spike within it, still pass
    t = np.arange(10000) * T
    xr = 10.0 * np.sin(2.0 * np.pi * 0.5 * t)
    x = np.interp(t - 0.01, t, xr)
    spiked = x.copy()
    spiked[5000] += 0.05
    with pytest.raises(IdentificationError, match=r"log.csv: axis 'x': the measured position leaves its path by "
                                                  r"0.05 mm at sample 5000 .* and is back at the next sample"):
        check_jumps(xr, spiked, T, "x", "log.csv")
    burst = x.copy()
    burst[3000:3050] += 0.01 * (-1.0) ** np.arange(50)
    burst[3020] += 0.02
    check_jumps(xr, burst, T, "x", "log.csv")
