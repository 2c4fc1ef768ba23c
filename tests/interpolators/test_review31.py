"""Defects found by the session-31 review, each with the case that showed it."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.profiles import ruckig_duration, scurve_phases


def test_a_nanometre_segment_whose_end_speed_differs_by_rounding_is_planned():
    """A 27 nm piece between dense chords under the S-curve, its end speed a few 1e-15 mm/s below its start: ruckig
    raised on it (twice, also with the limits shrunk) and the whole program failed with "ruckig found no S-curve
    profile". Planned at its start speed it takes its length over that speed."""
    L, v0, v1 = 2.7470315416695077e-08, 21.717261742099023, 21.71726174209902
    limits = (195.48333333333332, 180.42342820599683, 4510.585705149921)
    assert ruckig_duration(L, v0, v1, *limits) == pytest.approx(L / v0, rel=1e-9)
    dur, _, v, a, j = scurve_phases(np.array([L]), np.array([v0]), np.array([v1]), *(np.array([x]) for x in limits))
    assert dur.sum() == pytest.approx(L / v0, rel=1e-9)
    assert np.all(v == pytest.approx(v0, abs=1e-9))
    assert np.abs(a).max() <= limits[1] and np.abs(j).max() <= limits[2]
