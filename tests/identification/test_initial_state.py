"""A record that starts with the axis in motion: the model's state at its first sample is fitted.

Truth: the thesis' PID x axis as the exact reduced model (``FADAL_PID_X``, Table 3.4), so the
poles are known exactly and the prediction floor is the added noise (0.5 um).
"""

from __future__ import annotations

import numpy as np

from identification import identify
from identification.dead_time import delay_reference
from identification.initial_state import fit_initial_state, starts_in_motion
from identification.poles import poles_from_denominator
from identification.reduced_model import simulate
from identification.synthetic import FADAL_PID_X, synthetic_capture
from vcnc.capture import Capture

EXACT = poles_from_denominator(FADAL_PID_X["a1"], FADAL_PID_X["a2"], FADAL_PID_X["a3"])


def _never_resting(sample_time: float, seconds: float) -> np.ndarray:
    """Five sines, 0.37 to 11.3 Hz [mm]: the axis sets off from rest and never rests again."""
    t = np.arange(int(seconds / sample_time)) * sample_time
    parts = ((5.0, 0.37, 0.0), (2.0, 1.1, 1.0), (0.8, 2.9, 2.0), (0.3, 6.1, 3.0), (0.1, 11.3, 4.0))
    return sum(a * np.sin(2 * np.pi * f * t + ph) for a, f, ph in parts) * np.minimum(t / 0.5, 1.0) ** 3


def test_the_free_response_continues_a_linear_simulation_exactly():
    """Without friction the model is linear: the simulation from rest of a record's tail plus the
    free response of the fitted initial state is the whole record's simulation, to rounding."""
    linear = {**FADAL_PID_X, "d0": 0.0, "d1": 0.0}
    T = 0.001
    ref = _never_resting(T, 3.0)
    whole = simulate(linear, ref, T)
    tail = simulate(linear, ref[1500:], T)
    state, response = fit_initial_state(linear, T, tail - whole[1500:])
    assert np.max(np.abs(tail + response - whole[1500:])) < 1e-9
    assert np.max(np.abs(tail - whole[1500:])) > 0.05  # a start transient of more than 50 um
    assert not starts_in_motion(ref, whole)  # sets off from rest


def test_a_record_in_motion_with_a_leading_reference_keeps_the_poles():
    """A 3 ms record cut 2 s into a motion that never rests, its reference leading by 0.1 s: the
    loop's frame starts in motion. Simulated from rest (before this fix) the fit bent the poles to
    the start transient: 57.9 % off (p 1.85 Hz for 1.18) and 4.55 um RMS for 0.5 um of noise."""
    T = 0.003
    cap = synthetic_capture(FADAL_PID_X, _never_resting(T, 6.0), sample_time=T, noise=0.5e-3, seed=2)
    start = int(2.0 / T)
    ref = delay_reference(cap.reference[:, 0], -0.1 / T)[start:]
    meas = cap.measured[start:, 0]
    rec = Capture(t=np.arange(ref.size) * T, axes=("x",), reference=ref[:, None], measured=meas[:, None],
                  meta={"source": "initial-state test"})
    model = identify(rec, axis="x", diagnose=False)
    assert abs(model.delay_s - 0.1) <= 2 * T
    assert max(abs(model.poles[k] - EXACT[k]) / EXACT[k] for k in EXACT) < 0.1
    assert model.fit["rms_um"] <= 2 * 0.5
    state = model.fit["initial_state"]
    assert state["first_sample"] > 0 and state["start_response_max_um"] > 10.0
