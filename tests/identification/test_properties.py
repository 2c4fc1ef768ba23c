"""Property: over random drives and random captures the identified model is stable and inside the bounds."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from identification import PoleBounds, identify
from identification.poles import denominator
from identification.synthetic import random_moves_reference, synthetic_capture

T = 1e-3


@st.composite
def drives(draw):
    """A random true drive (poles, zeros, friction) and a random capture of it."""
    wn = 2 * math.pi * draw(st.floats(5.0, 120.0))
    z = draw(st.floats(0.1, 2.5))
    p = 2 * math.pi * draw(st.floats(0.05, 80.0))
    a1, a2, a3 = denominator(p, wn, z)
    params = {
        "a1": a1,
        "a2": a2,
        "a3": a3,
        "b0": draw(st.floats(-0.5, 1.0)),
        "b1": a1 * draw(st.floats(-1.0, 1.5)),
        "b2": a2 * draw(st.floats(0.3, 1.2)),
        "d0": draw(st.floats(0.0, 2000.0)),
        "d1": -draw(st.floats(0.0, 2000.0)),
    }
    seed = draw(st.integers(0, 2**31 - 1))
    noise = draw(st.sampled_from([0.0, 1e-4, 1e-3]))
    lo = draw(st.floats(0.1, 2.0))
    return params, seed, noise, lo


@pytest.mark.slow  # hypothesis over identifications, ~20 s
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(drives())
def test_identified_model_is_stable_and_inside_bounds(case):
    params, seed, noise, lo = case
    xr = random_moves_reference(moves=12, span=5.0, seed=seed % 1000)
    cap = synthetic_capture(params, xr, noise=noise, seed=seed)
    bounds = PoleBounds(p_hz=(lo, 500.0), omega_n_hz=(lo, 500.0), zeta=(0.2, 2.0))
    m = identify(cap, bounds=bounds, refine="none", diagnose=False)
    assert m.is_stable()
    assert bounds.contains(m.poles, rtol=1e-9)
    assert np.all(np.isfinite(m.simulate(xr)))
