"""Traces in layouts of traces39 (session 39): Panasonic FP data logging/trace CSV files (FP0H user manual 1.3.3,
FPWIN Pro7 help "CSV format") and the fuzzer's cases (``benchmarks/trace_fuzz.py``, seeds 47-49). Each file is a few
lines written here after the layout, not an export itself."""

from __future__ import annotations

import numpy as np
import pytest

from identification.dead_time import delay_reference
from identification.synthetic import random_moves_reference
from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_SET = [0.0, 100.0, 300.0, 600.0, 900.0, 1100.0, 1200.0]
_ACT = [0.0, 40.0, 200.0, 480.0, 790.0, 1020.0, 1150.0]


def _fp_trace(path, *, header="Date,Time,Obtaining interval,1,2", rows=("DT100,DT102", "Command position,Actual "
              "position", "MOMENT,MOMENT", "Signed 32-bit,Signed 32-bit", "um,um"), trigger_after=4):
    """An FP trace CSV: a comment, the header line, the header rows, records 100 counts apart and a stop trigger
    60 counts after record ``trigger_after``, the next record 40 after it."""
    lines = ["Comment,axis 1 trace", header, *(",,," + r for r in rows)]
    for k, (s, a) in enumerate(zip(_SET, _ACT)):
        lines.append(f"2020/07/24,12:00:00,{0 if k == 0 else 40 if k == trigger_after + 1 else 100},{s:g},{a:g}")
        if k == trigger_after:
            lines.append("2020/07/24,12:00:00,60,STOP TRG")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_fp_trace_asks_for_its_sampling_interval(tmp_path):
    """An FP trace's intervals count 10 us (FP0H manual) or 10 ms (FPWIN Pro7 help): the file is named as what it is
    and its sampling interval asked for (it said 'the file has no header line')."""
    f = _fp_trace(tmp_path / "trace.csv")
    with pytest.raises(CaptureError, match=r"Panasonic FP data logging/trace CSV.*100 counts apart.*10 us.*10 ms"
                                           r".*--sample-time") as err:
        read_capture(f)
    assert err.value.line == 2 and str(f) in str(err.value)


def test_fp_trace_is_read_with_its_sampling_interval(tmp_path):
    """Given the period of the commonest interval, the records are read under the names and comments of their
    channels, in the unit row's unit, the stop trigger's record left out and its interval counted."""
    cap = read_capture(_fp_trace(tmp_path / "trace.csv"), sample_time=0.001)
    assert cap.axes == ("x",) and cap.meta["format"].startswith("Panasonic FP")
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 1e-3)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 1e-3)
    np.testing.assert_allclose(cap.t, np.arange(len(_SET)) * 0.001, atol=1e-12)


def test_fp_trace_in_japanese_without_unit_row(tmp_path):
    """The Japanese header (日付, 時刻, 取得間隔) and a trace without its unit row: positions in counts asked for as
    any table's without a unit (here given)."""
    f = _fp_trace(tmp_path / "trace.csv", header="\u65e5\u4ed8,\u6642\u523b,\u53d6\u5f97\u9593\u9694,1,2",
                  rows=("Command position,Actual position",), trigger_after=99)
    cap = read_capture(f, sample_time=0.002, unit="um")
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 1e-3)
    np.testing.assert_allclose(np.diff(cap.t), 0.002)


def test_fp_trace_interval_that_is_no_count(tmp_path):
    """A record whose interval is no whole number is named with its line and column."""
    f = _fp_trace(tmp_path / "trace.csv")
    f.write_text(f.read_text().replace(",12:00:00,100,300,", ",12:00:00,1.5,300,"), encoding="utf-8")
    with pytest.raises(CaptureError, match="obtaining interval") as err:
        read_capture(f, sample_time=0.001)
    assert err.value.line == 10


def _led_layouts(ref: np.ndarray, meas: np.ndarray, ts: float) -> dict[str, str]:
    """A TNCscope text export (``s soll``/``s ist`` of Y), a LinuxCNC 2.8 halscope log (``label value`` pairs, one
    line past the record) and a TwinCAT Scope export (tab, decimal comma, a time column per channel) of one record."""
    tnc = ["%TNCscopeNT data file", "%[GLOBAL]", f"%SAMPLING={ts * 1e6:g}", "%[CURVE1]", "%NAME=s soll/Y",
           "%CHANNELTYPE=s soll", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=1", "%[CURVE2]", "%NAME=s ist/Y",
           "%CHANNELTYPE=s ist", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=2", "%[DATA]"]
    tnc += [f"{k * ts * 1e6:.0f};{r:.6f};{m:.6f};" for k, (r, m) in enumerate(zip(ref, meas))]
    hal = [f"Sampling period is {ts * 1e9:.0f} ns ", ""]
    hal += [f"joint.0.motor-pos-cmd {r:+.9f} joint.0.motor-pos-fb {m:+.9f} " for r, m in [*zip(ref, meas), (0, 0)]]
    tc = ["Name\tMAIN.fPosCmd\tName\tMAIN.fPosAct", f"SampleTime[ms]\t{ts * 1e3:g}\tSampleTime[ms]\t{ts * 1e3:g}",
          "Unit\tmm\tUnit\tmm", ""]
    tc += ["\t".join(f"{v:.6f}".replace(".", ",") for v in (k * ts * 1e3, r, k * ts * 1e3, m))
           for k, (r, m) in enumerate(zip(ref, meas))]
    return {"tncscope": "\n".join(tnc), "halscope": "\n".join(hal), "twincat": "\n".join([*tc, "EOF"])}


@pytest.mark.parametrize("shift_s", [0.1, -0.02])
def test_a_reference_that_leads_or_lags_keeps_its_timing_in_three_layouts(tmp_path, shift_s):
    """A reference recorded 0.1 s ahead of the loop (a Heidenhain trace's) or 20 ms behind it, written as TNCscope,
    halscope and TwinCAT record it, reads as the capture CSV holds it: every sample in its place against the
    measured one, which the dead-time scan then finds (session 39: 0.1003 s and -0.0187 s on fadal-pid's random moves
    in all four files, their models equal to 6 digits; /tmp/traces39/lead)."""
    ts = 0.001
    loop = random_moves_reference(moves=6, sample_time=ts, seed=3)  # the loop's command; the axis 8 samples behind
    ref = np.round(delay_reference(loop, -shift_s / ts), 6)
    meas = np.round(delay_reference(loop, 8.0), 6)
    for name, text in _led_layouts(ref, meas, ts).items():
        got = read_capture(_write(tmp_path / f"{name}.txt", text))
        assert len(got) == ref.size, name
        np.testing.assert_allclose(got.reference[:, 0], ref, atol=1e-9, err_msg=name)
        np.testing.assert_allclose(got.measured[:, 0], meas, atol=1e-9, err_msg=name)
        np.testing.assert_allclose(got.t, np.arange(ref.size) * ts, atol=1e-9, err_msg=name)


def _write(path, text):
    path.write_text(text + "\n", encoding="utf-8")
    return path


def test_fp_trace_channels_without_names_are_mapped_by_their_numbers(tmp_path):
    """A trace whose header rows are all left out names its channels only by their numbers (``1,2`` after
    ``Obtaining interval``): the question lists them so, and ``--columns x_ref=1,x=2`` maps them."""
    f = _fp_trace(tmp_path / "trace.csv", rows=(), trigger_after=99)
    with pytest.raises(CaptureError, match=r"columns found: \['Date', 'Clock', 'Time \[s\]', '1', '2'\]"):
        read_capture(f, sample_time=0.001)
    cap = read_capture(f, sample_time=0.001, columns={"t": "Time [s]", "x_ref": "1", "x": "2"}, unit="um")
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 1e-3)


def test_fp_data_logging_records_are_periodic(tmp_path):
    """A data logging CSV (``Date,Time,1,2``, no obtaining interval, records stamped to the second) is named and
    asks for its interval; given, a record every interval."""
    lines = ["Date,Time,1,2", ",,Command position,Actual position", ",,um,um"]
    lines += [f"2020/07/24,12:00:0{k // 4},{s:g},{a:g}" for k, (s, a) in enumerate(zip(_SET, _ACT))]
    f = tmp_path / "log.csv"
    f.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(CaptureError, match=r"Panasonic FP data logging CSV.*stamped to the second.*--sample-time"):
        read_capture(f)
    cap = read_capture(f, sample_time=0.01)
    assert cap.meta["format"] == "Panasonic FP data logging CSV"
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 1e-3)
    np.testing.assert_allclose(cap.t, np.arange(len(_SET)) * 0.01, atol=1e-12)


def test_fp_trace_without_records(tmp_path):
    """Only the header and one record: named as such (it said the records were 0 counts apart)."""
    f = tmp_path / "trace.csv"
    f.write_text("Date,Time,Obtaining interval,1,2\n,,Command position,Actual position\n2020/07/24,12:00:00,0,0,0\n",
                 encoding="utf-8")
    with pytest.raises(CaptureError, match=r"with 1 record\(s\) below its header") as err:
        read_capture(f, sample_time=0.001)
    assert err.value.line == 1
