"""The operating range of a record (identification.excitation): where its reference runs, and when another
reference goes beyond it."""

from __future__ import annotations

import numpy as np

from identification.excitation import BEYOND_FACTOR, beyond_range, excitation


def _trapezoid(v: float, a: float, hold_s: float, T: float = 1e-3) -> np.ndarray:
    """Position [mm] of a move that ramps at ``a`` to ``v``, holds it ``hold_s``, ramps down, and rests 0.2 s."""
    ramp = v / a
    t = np.arange(0.0, 2 * ramp + hold_s + 0.2, T)
    vel = np.clip(np.minimum(a * t, a * (2 * ramp + hold_s - t)), 0.0, v)
    return np.concatenate([[0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1])) * T])


def test_range_of_a_trapezoidal_move():
    rec = excitation(_trapezoid(50.0, 1000.0, 1.0), 1e-3)
    assert abs(rec["speed_mm_s"] - 50.0) < 1e-6 and abs(rec["speed_max_mm_s"] - 50.0) < 1e-6
    assert abs(rec["acceleration_max_mm_s2"] - 1000.0) < 1e-6  # a plateau of 50 ms, wider than the +-4 ms window
    assert rec["window_s"] == 0.004


def test_the_speed_is_where_the_record_moves_and_a_brief_rapid_does_not_count():
    slow = _trapezoid(8.0, 1000.0, 10.0)
    rapid = _trapezoid(40.0, 2000.0, 0.02)
    rec = excitation(np.concatenate([slow, slow[-1] + rapid]), 1e-3)
    assert abs(rec["speed_mm_s"] - 8.0) < 1e-6  # the rapid is under 1 % of the moving time
    assert abs(rec["speed_max_mm_s"] - 40.0) < 1e-6 and abs(rec["acceleration_max_mm_s2"] - 2000.0) < 1e-6


def test_a_reference_quantised_to_1_um_keeps_its_range():
    q = np.round(_trapezoid(50.0, 1000.0, 1.0) / 1e-3) * 1e-3
    rec = excitation(q, 1e-3)
    assert abs(rec["speed_mm_s"] - 50.0) < 0.2
    assert abs(rec["acceleration_max_mm_s2"] - 1000.0) < 100.0  # 1 um / (4 ms)^2 = 62.5 mm/s^2 per count


def test_beyond_the_range_by_more_than_the_factor():
    rec = excitation(_trapezoid(50.0, 1000.0, 1.0), 1e-3)
    assert beyond_range(rec, _trapezoid(50.0 * BEYOND_FACTOR * 0.99, 1000.0, 0.5), 1e-3) == {}
    faster = _trapezoid(100.0, 3000.0, 0.5)
    out = beyond_range(rec, faster, 1e-3)
    assert set(out) == {"speed", "acceleration"}
    assert abs(out["speed"][0] - 100.0) < 1e-6 and abs(out["speed"][1] - 50.0) < 1e-6
    assert abs(out["acceleration"][0] - 3000.0) < 1e-6 and abs(out["acceleration"][1] - 1000.0) < 1e-6
    counted = np.zeros(faster.size, dtype=bool)  # only the rest at the end counts: nothing beyond
    counted[-50:] = True
    assert beyond_range(rec, faster, 1e-3, samples=counted) == {}
    assert beyond_range({}, faster, 1e-3) == {}  # a model file of before: no range, no note


def test_a_record_at_rest_or_shorter_than_the_window():
    assert excitation(np.zeros(100), 1e-3)["speed_mm_s"] == 0.0
    assert excitation(np.arange(5.0), 1e-3) == {"speed_mm_s": 0.0, "speed_max_mm_s": 0.0,
                                                "acceleration_max_mm_s2": 0.0, "window_s": 0.004}
