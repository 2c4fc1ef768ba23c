"""A commanded position that is a sequence of held targets (a positioning test's, logged in place of the trajectory's
setpoint) is named as such, with its column, not taken for a measured channel that does not follow (realfit35: an
ecmc axis' ISO 230-2 test logged by EPICS camonitor, X-PosCmd with 102 target updates in 2597 s, correlation 0.16,
was sent to check its measured column)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from identification.capture_checks import channel_name, check_capture
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture
from vcnc.core.capture import Capture
from vcnc.core.errors import IdentificationError


def _targets(sample_time: float) -> object:
    """A positioning test's staircase: 12 targets every 5 mm from -20 to +35 mm, each held 8 s, the axis taken to
    each by the drive's own ramp at 2 mm/s (which the trace does not log) and the thesis' PID x loop (Table 3.4
    'Actual'); the trace's commanded column, TARGET:X-PosCmd, holds the target from the move's start."""
    held = int(round(8.0 / sample_time))
    targets = np.repeat(np.arange(-20.0, 40.0, 5.0), held)
    t = np.arange(targets.size) * sample_time
    starts = np.arange(0, targets.size, held)
    ramp = targets.copy()
    for k in starts[1:]:  # from the previous target at 2 mm/s
        ramp[k:k + held] = np.minimum(targets[k], targets[k - 1] + 2.0 * (t[k:k + held] - t[k]))
    cap = synthetic_capture(FADAL_PID_X, ramp, sample_time=sample_time, noise=2e-4, resolution=1e-4, seed=2)
    return dataclasses.replace(cap, reference=targets[:, None], meta={**cap.meta, "commanded": "x:TARGET:X-PosCmd"})


@pytest.mark.parametrize("sample_time", [0.01, 0.1])
def test_a_reference_of_held_targets_is_named_with_its_column(sample_time):
    with pytest.raises(IdentificationError, match=r"axis 'x': the commanded position \(TARGET:X-PosCmd\) is a "
                                                  r"sequence of held targets, not a trajectory: it changes 11 times"):
        check_capture(_targets(sample_time), "x")


def test_a_single_target_is_named_too():
    # a KUKA RSI weld log's z axis: Z_RSol steps by 65.8 mm once, the robot travels it over 40 samples of 12 ms
    t = np.arange(2425) * 0.012
    xr = np.where(t < 10.0, 977.3, 1043.1)
    x = np.clip(977.3 + 2.3 * (t - 10.0) / 0.012, 977.3, 1043.1)
    cap = Capture(t=t, axes=("z",), reference=xr[:, None], measured=x[:, None], meta={"commanded": "z:Z_RSol"})
    with pytest.raises(IdentificationError, match=r"the commanded position \(Z_RSol\) is a sequence of held targets, "
                                                  r"not a trajectory: it changes once in 29.1 s"):
        check_capture(cap, "z")


def test_a_trajectory_is_no_held_target():
    cap = synthetic_capture(FADAL_PID_X, random_moves_reference(moves=40, seed=2), noise=2e-4, seed=1)
    check_capture(cap, "x")  # follows: no refusal


def test_the_commanded_column_is_read_from_the_trace_meta():
    assert channel_name({"commanded": "x:X_RSol,y:Y_RSol"}, "y") == "Y_RSol"
    assert channel_name({}, "z") == "z_ref"
