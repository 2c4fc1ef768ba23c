"""Labellings of the reduced model's poles (identification.poles): with three real poles,
(p, omega_n, zeta) of Eq. (3.7) is not unique; results are reported in one canonical labelling."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from identification.bounds import default_bounds
from identification.poles import TWO_PI, canonical, canonical_mask, denominator, pole_splits

BOUNDS = default_bounds(1e-3)


def _labellings(roots_hz):
    """Every (p, omega_n, zeta) [rad/s] with the real roots ``roots_hz`` [Hz] as its poles."""
    r = np.array(roots_hz) * TWO_PI
    out = []
    for j in range(3):
        a, b = np.delete(r, j)
        wn = np.sqrt(a * b)
        out.append((r[j], wn, (a + b) / (2 * wn)))
    return out


def test_every_labelling_maps_to_the_slowest_p():
    rng = np.random.default_rng(4)
    for _ in range(200):
        roots = np.sort(rng.uniform(1.0, 120.0, 3))
        labs = _labellings(roots)
        fits = [lab for lab in labs if BOUNDS.contains_rad(*lab)]
        want = fits[0]  # slowest p whose pair fits zeta <= 2
        for lab in fits:
            c = canonical(*lab, BOUNDS)
            assert c == pytest.approx(want, rel=1e-9)
            assert np.allclose(denominator(*c), denominator(*lab), rtol=1e-9)  # same polynomial
        mask = canonical_mask(*np.array(fits).T, BOUNDS)
        assert mask.tolist() == [i == 0 for i in range(len(fits))]


def test_the_pair_must_fit_the_bounds():
    """Roots 1, 5 and 100 Hz: with p = 1 Hz the pair (5, 100) needs zeta = 2.35 > 2, so the canonical
    labelling takes p = 5 Hz (pair 1 and 100 Hz would need zeta 5.05; pair 1 and 5 Hz: zeta 1.34)."""
    slow, mid, fast = _labellings([1.0, 5.0, 100.0])
    assert slow[2] > 2.0
    c = canonical(*fast, BOUNDS)
    assert c[0] / TWO_PI == pytest.approx(100.0) and c[2] == pytest.approx(1.342, abs=1e-3)
    assert canonical_mask(*fast, BOUNDS)
    assert canonical(*mid, BOUNDS) == pytest.approx(fast, rel=1e-12)  # mid itself needs zeta 5.05: outside
    assert not canonical_mask(*mid, BOUNDS)
    wide = dataclasses.replace(BOUNDS, zeta=(0.2, 3.0))
    assert canonical(*fast, wide) == pytest.approx(slow, rel=1e-12)


def test_complex_and_double_pairs_are_kept():
    for z in (0.3, 0.99, 1.0):
        v = (10.0 * TWO_PI, 50.0 * TWO_PI, z)
        assert canonical(*v, BOUNDS) == v
        assert canonical_mask(*v, BOUNDS)


def test_pole_splits_lists_the_canonical_labelling_first():
    p, wn, z = _labellings([3.0, 40.0, 90.0])[2]
    first = pole_splits(*denominator(p, wn, z))[0]
    c = canonical(p, wn, z, BOUNDS)
    assert first["p_hz"] * TWO_PI == pytest.approx(c[0], rel=1e-9)
    assert first["omega_n_hz"] * TWO_PI == pytest.approx(c[1], rel=1e-9)
