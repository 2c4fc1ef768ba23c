"""Review of session 29: the capture checks' messages in the unit of the axis they name."""

from __future__ import annotations

import numpy as np
import pytest

from identification.capture_checks import check_capture
from vcnc.core.capture import Capture
from vcnc.errors import IdentificationError


def _capture(axis: str, reference: np.ndarray, measured: np.ndarray) -> Capture:
    t = np.arange(reference.size) * 1e-3
    return Capture(t=t, axes=(axis,), reference=reference[:, None], measured=measured[:, None])


def test_a_rotary_axis_too_small_to_identify_is_told_in_degrees():
    # a rotary table moved 0.04 deg back and forth: the message said "look like metres ... spans 0.04 mm ... mm/s"
    # and asked for "the axis named a, b or c", which it is
    ref = 0.02 * np.sin(np.linspace(0.0, 6.0 * np.pi, 2000))
    with pytest.raises(IdentificationError) as err:
        check_capture(_capture("a", ref, ref - 1e-4), "a")
    msg = str(err.value)
    assert "positions on axis 'a' look like radians, not deg: the reference spans 0.04 deg at a peak speed of" in msg
    assert "deg/s; convert the capture to deg (radians: --unit rad; a test this small" in msg
    assert "mm" not in msg and "metres" not in msg
    with pytest.raises(IdentificationError, match="no commanded motion on axis 'a': the reference stays at 5.0 deg"):
        check_capture(_capture("a", np.full(2000, 5.0), 5.0 + 1e-3 * np.sin(np.arange(2000.0))), "a")


def test_a_linear_axis_in_metres_keeps_its_message():
    ref = 0.02 * np.sin(np.linspace(0.0, 6.0 * np.pi, 2000))
    with pytest.raises(IdentificationError, match=r"positions on axis 'x' look like metres, not mm \(or radians of "
                                                  r"a rotary joint, not deg\): the reference spans 0.04 mm at a peak "
                                                  r"speed of [\d.]+ mm/s; convert the capture to mm \(a logger's "
                                                  r"metres: --unit m; radians: --unit rad with the axis named a, b or "
                                                  r"c; a test this small could not be identified anyway\)"):
        check_capture(_capture("x", ref, ref - 1e-4), "x")
