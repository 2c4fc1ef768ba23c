"""TNCscope reader: a file written here reads back to the samples it came from."""

import numpy as np
import pytest

from vcnc.errors import CaptureError
from vcnc.traces import read_tncscope


def _write(path, t_us, ref, act):
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", "%SAMPLING=3000",
             "%[CURVE1]", "%NAME=s soll/Y", "%CHANNELTYPE=s soll", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=1",
             "%[CURVE2]", "%NAME=s ist/Y", "%CHANNELTYPE=s ist", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=2",
             "%[DATA]"]
    lines += [f"{t:.0f};{r:.6f};{a:.6f};" for t, r, a in zip(t_us, ref, act)]
    path.write_bytes("\r\n".join(lines).encode("latin-1") + b"\r\n")


def test_tncscope_reads_back(tmp_path):
    t = np.arange(300) * 3000.0
    ref = np.round(np.sin(t * 1e-5), 6)
    act = np.round(ref - 0.001, 6)
    f = tmp_path / "y.sco"
    _write(f, t, ref, act)
    cap = read_tncscope(f)
    assert cap.axes == ("y",)
    np.testing.assert_array_equal(cap.t, t * 1e-6)
    np.testing.assert_array_equal(cap.reference[:, 0], ref)
    np.testing.assert_array_equal(cap.measured[:, 0], act)


def test_tncscope_time_backwards(tmp_path):
    t = np.arange(10) * 3000.0
    t[5] = 0.0
    f = tmp_path / "y.sco"
    _write(f, t, np.zeros(10), np.zeros(10))
    with pytest.raises(CaptureError, match="time does not increase"):
        read_tncscope(f)


def test_read_capture_detects_tncscope_by_content(tmp_path):
    from vcnc.capture import read_capture

    t = np.arange(50) * 3000.0
    f = tmp_path / "trace.txt"
    _write(f, t, np.zeros(50), np.zeros(50))
    assert read_capture(f).axes == ("y",)
