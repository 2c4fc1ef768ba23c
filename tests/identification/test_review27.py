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
