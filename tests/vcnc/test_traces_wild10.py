"""Traces in the layouts of tracewild10's real set (session 34): a drive logger's headerless tab-separated rows of
a rotary actuator (time in ms, target, demand, actual position, speed, current, as nicolazande/camber-control's
EccA logs) read with a column mapping. Each file is a few lines written here after that layout, not the log."""

from __future__ import annotations

import numpy as np

from vcnc.capture import read_capture

_ROWS = [(0, 0.0, 0.0, 0.0), (13, 1.0, 0.5, 0.1), (26, 2.0, 1.5, 0.6), (39, 3.0, 2.5, 1.5), (52, 3.0, 3.0, 2.4),
         (65, 3.0, 3.0, 2.9)]


def test_rotary_axis_without_a_unit_is_named_in_degrees(tmp_path):
    """A rotary axis mapped without --unit is read in degrees, and the capture's ``meta["unit"]`` says so (it said
    'mm': the camber EccA log, --columns t=1,a_ref=2,a=4); beside a linear axis both units are named."""
    f = tmp_path / "ecc.txt"
    f.write_text("".join(f"{t}\t{r}\t{d}\t{a}\t0\t272\n" for t, r, d, a in _ROWS))
    cap = read_capture(f, columns={"t": "1", "a_ref": "2", "a": "4"}, time_unit="ms")
    assert cap.axes == ("a",) and cap.meta["unit"] == "deg"
    np.testing.assert_array_equal(cap.measured[:, 0], [r[3] for r in _ROWS])
    cap = read_capture(f, columns={"t": "1", "x_ref": "2", "x": "3", "a_ref": "2", "a": "4"}, time_unit="ms")
    assert cap.meta["unit"] == "deg,mm"
