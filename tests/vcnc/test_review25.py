"""Defects found in the review of session 25's trace readers, each with a hand-written file that failed before its
fix."""

from __future__ import annotations

import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError


@pytest.mark.parametrize(("header", "message"), [
    ("time [s],c_ref [rad],c [rad]", r"far\.csv:5: 'c_ref \[rad\]' \(rad\) is 1e\+16 deg in this row"),  # delimited
    ("t,c_ref,c", r"far\.csv: the reference position of axis c is 1e\+16 deg at sample 3"),  # vcnc's capture CSV
    ("t,x_ref,x", r"far\.csv: the reference position of axis x is 1e\+16 mm at sample 3"),
])
def test_a_position_beyond_reach_is_named_in_its_axis_unit(tmp_path, header, message):
    # the scaled value of a rotary axis is in deg, of a linear axis in mm (it said "mm or deg" for both)
    far = 1e16 / 57.29577951308232 if "rad" in header else 1e16
    rows = "".join(f"{k * 0.001:.3f},{far if k == 3 else k * 0.01!r},{k * 0.01!r}\n" for k in range(8))
    f = tmp_path / "far.csv"
    f.write_text(header + "\n" + rows)
    with pytest.raises(CaptureError, match=message):
        read_capture(f)
