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


def test_convert_writes_the_same_capture(tmp_path, capsys):
    from vcnc.capture import read_capture
    from vcnc.cli import main

    t = np.arange(100) * 3000.0
    ref = np.round(np.cos(t * 1e-5), 6)
    f = tmp_path / "y.sco"
    _write(f, t, ref, ref - 0.002)
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out)]) == 0
    assert "axes y" in capsys.readouterr().out
    cap = read_capture(out)
    np.testing.assert_allclose(cap.reference[:, 0], ref, rtol=0, atol=1e-12)
    assert cap.meta["format"] == "TNCscope"


def test_convert_bad_input_exits_2_and_writes_nothing(tmp_path, capsys):
    from vcnc.cli import main

    t = np.arange(10) * 3000.0
    t[4] = 0.0
    f = tmp_path / "y.sco"
    _write(f, t, np.zeros(10), np.zeros(10))
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out)]) == 2
    assert "error:" in capsys.readouterr().err
    assert not out.exists()


def test_identify_trace_and_converted_csv_give_the_same_model(tmp_path):
    """`vcnc identify trace.sco` and `vcnc identify capture.csv` (written by convert) agree exactly."""
    import json

    from scipy.signal import lfilter

    from vcnc.cli import main

    n = 600
    t = np.arange(n) * 3000.0
    ref = np.round(10.0 * np.sin(2 * np.pi * 1.5 * t * 1e-6) ** 3, 6)
    a = np.exp(-0.003 / 0.02)  # first-order lag, 20 ms time constant, 3 ms sampling
    act = np.round(lfilter([1 - a], [1, -a], ref), 6)
    sco = tmp_path / "trace.sco"
    _write(sco, t, ref, act)
    csv = tmp_path / "capture.csv"
    assert main(["convert", str(sco), "-o", str(csv)]) == 0
    models = []
    for src in (sco, csv):
        out = tmp_path / f"{src.stem}.json"
        assert main(["identify", str(src), "--no-diagnose", "--json", str(out)]) == 0
        models.append(json.loads(out.read_text()))
    assert models[0].get("parameters") == models[1].get("parameters")
    assert models[0].get("parameters")


def test_tncscope_bad_input_names_line_and_channels(tmp_path):
    f = tmp_path / "y.sco"
    _write(f, np.arange(5) * 3000.0, np.zeros(5), np.zeros(5))
    text = f.read_bytes().decode("latin-1")
    f.write_bytes(text.replace("%CHANNELTYPE=s ist", "%CHANNELTYPE=v ist").encode("latin-1"))
    with pytest.raises(CaptureError,
                       match="no commanded position with an actual position or following error.*s soll/Y"):
        read_tncscope(f)
    f.write_bytes((text + "15000;1.0;\r\n").encode("latin-1"))
    with pytest.raises(CaptureError, match="row has 2 values, expected 3") as exc:
        read_tncscope(f)
    assert exc.value.line == 22
    f.write_bytes(text.replace("0.000000;0.000000;\r\n", "abc;0;\r\n", 1).encode("latin-1"))
    with pytest.raises(CaptureError, match="non-numeric"):
        read_tncscope(f)


def test_tncscope_english_channel_names(tmp_path):
    f = tmp_path / "y.sco"
    _write(f, np.arange(5) * 3000.0, np.ones(5), np.ones(5))
    text = f.read_bytes().decode("latin-1").replace("s soll", "s nom").replace("s ist", "s act")
    f.write_bytes(text.encode("latin-1"))
    assert read_tncscope(f).axes == ("y",)
