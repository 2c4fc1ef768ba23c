"""A record that starts with the axis in motion: the model's state at its first sample is fitted.

Truth: the thesis' PID x axis as the exact reduced model (``FADAL_PID_X``, Table 3.4) for the free
response, and for a short record of the virtual fadal-pid the fit of its whole capture at the same
sample time (its poles and its prediction error)"""

from __future__ import annotations

import numpy as np
import pytest

import toolpaths
import vcnc
from identification import identify
from identification.dead_time import delay_reference
from identification.initial_state import fit_initial_state, starts_in_motion
from identification.poles import poles_from_denominator
from identification.reduced_model import simulate
from identification.synthetic import FADAL_PID_X
from vcnc.capture import Capture


def _one_axis(reference: np.ndarray, measured: np.ndarray, sample_time: float) -> Capture:
    return Capture(t=np.arange(reference.size) * sample_time, axes=("x",), reference=reference[:, None],
                   measured=measured[:, None], meta={"source": "initial-state test"})


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


@pytest.mark.slow
def test_a_short_record_in_motion_with_a_leading_reference():
    """fadal-pid's x axis (200 random moves within +/-10 mm at F12000, the traceid harness' capture),
    2 s of it cut during a move, sampled at 3 ms, its reference leading by 0.1 s: the loop's frame
    starts in motion and never rests in its first half. Simulated from rest (before this fix) the
    fit bent the poles to the start transient: p 0.40 Hz for the 3 ms capture's 1.45, 10.3 um RMS."""
    machine = vcnc.machine("fadal-pid")
    program = vcnc.parse_program(toolpaths.random_moves(200, 10.0, 12000.0, seed=1))
    whole = machine.simulate(vcnc.interpolate(program, machine), seed=1).select_axes(("x",))
    T = 3 * whole.sample_time
    ref, meas = whole.reference[::3, 0], whole.measured[::3, 0]
    truth = identify(_one_axis(ref, meas, T), axis="x", diagnose=False, delay=0.0)
    ref_cut, meas_cut = whole.reference[2000:4000:3, 0], whole.measured[2000:4000:3, 0]
    model = identify(_one_axis(delay_reference(ref_cut, -0.1 / T), meas_cut, T), axis="x", diagnose=False)
    assert abs(model.delay_s - 0.1) <= 2 * T
    assert max(abs(model.poles[k] - truth.poles[k]) / truth.poles[k] for k in EXACT) < 0.25
    assert model.fit["rms_um"] <= 1.5 * truth.fit["rms_um"]
    assert model.fit["initial_state"]["start_response_max_um"] > 10.0
