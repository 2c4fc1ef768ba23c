"""Capture CSV contract (ARCHITECTURE.md, "Capture file") and the EMPS reader."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import Capture, read_capture
from vcnc.errors import CaptureError


def _capture(n: int = 50) -> Capture:
    t = np.arange(n) * 1e-3
    ref = np.column_stack([np.sin(t), np.cos(t)])
    return Capture(t=t, axes=("x", "y"), reference=ref, measured=ref * 0.99, control=ref * 0.1,
                   meta={"machine": "test"})


def test_round_trip(tmp_path):
    c = _capture()
    p = tmp_path / "c.csv"
    c.to_csv(p)
    r = read_capture(p)
    assert r.axes == ("x", "y")
    assert r.meta["machine"] == "test"
    np.testing.assert_allclose(r.measured, c.measured, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(r.control, c.control, rtol=1e-11, atol=1e-12)
    assert r.sample_time == pytest.approx(1e-3)


@pytest.mark.parametrize(
    "body, line, fragment",
    [
        ("t,x_ref,x\n0,0,0\n0.001,nan,0\n", 3, "not finite"),
        ("t,x_ref,x\n0,0,0\n0.001,abc,0\n", 3, "not a number"),
        ("t,x_ref,x\n0,0,0\n0,0,0\n", 3, "not increasing"),
        ("t,x_ref,x\n0,0,0\n0.001,0,0\n0.002,0,0\n0.004,0,0\n", 5, "not uniform"),
        ("t,x_ref,q\n0,0,0\n0.001,0,0\n", 1, "unknown column"),
        ("# a: b\nt,x_ref,x\n0,0\n", 3, "fields"),
    ],
)
def test_bad_csv_names_line(tmp_path, body, line, fragment):
    p = tmp_path / "bad.csv"
    p.write_text(body)
    with pytest.raises(CaptureError) as info:
        read_capture(p)
    assert info.value.line == line
    assert fragment in str(info.value)
    assert str(p) in str(info.value)
    assert isinstance(info.value, ValueError)


def test_blank_and_comment_rows_read_by_the_compiled_reader(tmp_path, monkeypatch):
    """A blank and a ``#`` line among the rows (a capture edited by hand) are skipped as the row-by-row
    reader skips them, by numpy's reader in one call: the row-by-row reader is not reached, and a
    non-uniform step after them is named at its file line (tracewild10)."""
    def row_by_row(*args):
        raise AssertionError("the row-by-row reader ran")

    monkeypatch.setattr("vcnc.core.capture._data_rows_checked", row_by_row)
    p = tmp_path / "c.csv"
    p.write_text("# machine: m\nt,x_ref,x\n0,0,0\n\n0.001,1,0.5\n# pause\n  \n0.002,2,1.5\n")
    c = read_capture(p)
    np.testing.assert_array_equal(c.t, [0, 0.001, 0.002])
    np.testing.assert_array_equal(c.reference[:, 0], [0, 1, 2])
    np.testing.assert_array_equal(c.measured[:, 0], [0, 0.5, 1.5])
    p.write_text("t,x_ref,x\n0,0,0\n\n0.001,1,0.5\n# pause\n0.002,2,1.5\n0.004,3,2\n")
    with pytest.raises(CaptureError, match="not uniform") as info:
        read_capture(p)
    assert info.value.line == 7


def test_missing_file(tmp_path):
    with pytest.raises(CaptureError, match="no such capture file"):
        read_capture(tmp_path / "nope.csv")


def test_emps_mat_in_mm(emps_dir):
    c = read_capture(emps_dir / "DATA_EMPS.mat")
    assert c.axes == ("x",)
    assert len(c) == 24841  # EMPS README: 24841 samples
    assert c.sample_time == pytest.approx(1e-3, rel=1e-4)  # EMPS README: Ts = 1 ms (float32 stamps)
    # metres converted to mm: the reference travels over tens of mm, not hundredths
    assert np.ptp(c.reference) > 10.0
    assert "pulses_N" not in c.aux
    p = read_capture(emps_dir / "DATA_EMPS_PULSES.mat")
    assert set(np.unique(p.aux["pulses_N"])) <= {0.0, 5.0}


def test_written_files_get_the_usual_mode(tmp_path):
    import os

    p = tmp_path / "c.csv"
    _capture().to_csv(p)
    mask = os.umask(0)
    os.umask(mask)
    assert p.stat().st_mode & 0o777 == 0o666 & ~mask


def test_csv_rows_are_the_text_np_savetxt_writes(tmp_path):
    # write_rows formats chunks of rows at once: the same bytes as np.savetxt's row by row, for values at the
    # edges of %g (signed zero, subnormal, huge, integral floats, 12-digit rounding ties, inf/nan) and a
    # length that leaves a partial chunk
    import io

    from vcnc.core.io import ROWS_PER_CHUNK, write_rows

    rng = np.random.default_rng(3)
    n = 2 * ROWS_PER_CHUNK + 7
    data = rng.standard_normal((n, 4)) * 10.0 ** rng.integers(-8, 9, size=(n, 4))
    data[:10, 0] = [-0.0, 0.0, 5e-324, 1.7976931348623157e308, 3.0, -2.5, 0.1234567890125, 1e16, np.inf, np.nan]
    data[:, 3] = np.floor(data[:, 3])
    fmt = ["%.9g", "%.12g", "%.12g", "%d"]
    data[8:10, 3] = 0.0  # %d of inf/nan is an error in both
    want, got = io.StringIO(), io.StringIO()
    np.savetxt(want, data, fmt=fmt, delimiter=",")
    write_rows(got, data, fmt)
    assert got.getvalue() == want.getvalue()
    # and a written capture is read back to the last of its 12 digits
    t = np.arange(n) * 0.001
    cap = Capture(t=t, axes=("x",), reference=data[:, 1:2].clip(-1e6, 1e6), measured=data[:, 2:3].clip(-1e6, 1e6))
    cap.to_csv(tmp_path / "c.csv")
    back = read_capture(tmp_path / "c.csv")
    assert np.allclose(back.reference, cap.reference, rtol=1e-11, atol=0)
