"""Traces with the following error (lag) in the actual position's place (vcnc.traces.lag).

A capture simulated by ``vcnc simulate`` is written here in each format twice, once with its actual
position and once with its following error (commanded - actual, printed to 6 decimals, 1 nm), and
the two must read to the same capture; a following error of the wrong sign is refused naming the
file, the line and the channel; ``vcnc convert`` and ``vcnc identify`` read the lag traces, and the
model identified from one equals the original capture's within what the printed digits change.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import toolpaths
from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError
from vcnc.traces.lag import check_lag_sign

#: Digits after the decimal point the traces print (1 nm in mm).
DIGITS = 6
#: Largest difference between a measured position formed from a printed lag and the printed actual
#: position: each printed value is within half a unit of the 6th decimal of the true one [mm].
PRINTED = 1.01e-6


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    """``vcnc simulate`` of random moves on fadal-ppi (x axis, 1 ms samples; it lags by 18 ms at
    speed, vcnc.traces.lag), the capture read back."""
    d = tmp_path_factory.mktemp("sim")
    program = d / "moves.ngc"
    program.write_text(toolpaths.random_moves(40, 5.0, 6000.0, seed=3))
    out = d / "c.csv"
    assert main(["simulate", str(program), "--machine", "fadal-ppi", "-o", str(out), "--seed", "0",
                 "--settle", "0"]) == 0  # (newuser34: the capture ends with the reference, as the traces do)
    return read_capture(out).select_axes(("x",))


def _printed(a: np.ndarray) -> np.ndarray:
    return np.array([float(f"{v:.{DIGITS}f}") for v in np.ravel(a)])


def _channels(capture, *, sign=1.0):
    """Time [s], commanded and actual position and following error (commanded - actual, times
    ``sign``), each as printed."""
    ref, act = capture.reference[:, 0], capture.measured[:, 0]
    return capture.t, _printed(ref), _printed(act), _printed(sign * (ref - act))


# ------------------------------------------------------------------------------------ writers
def _rows(t, ref, curves, time_format):
    """One row per sample: the time, the commanded position and each curve's value."""
    return [";".join([time_format(tk), f"{r:.{DIGITS}f}", *(f"{v[k]:.{DIGITS}f}" for _, v in curves)])
            for k, (tk, r) in enumerate(zip(t, ref))]


def _tncscope(path, t, ref, curves):
    """A TNCscope export: ``s noml`` and the ``curves`` (``[(channel type, values)]``) of axis X."""
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", f"%SAMPLING={t[1] * 1e6:.0f}",
             "%[CURVE1]", "%NAME=s noml/X", "%CHANNELTYPE=s noml", "%AXISTYPE=X", "%DIMENSION=mm", "%COLUMN=1"]
    for k, (kind, _) in enumerate(curves, start=2):
        lines += [f"%[CURVE{k}]", f"%NAME={kind}/X", f"%CHANNELTYPE={kind}", "%AXISTYPE=X", "%DIMENSION=mm",
                  f"%COLUMN={k}"]
    lines += ["%[DATA]"] + [row + ";" for row in _rows(t, ref, curves, lambda tk: f"{tk * 1e6:.0f}")]
    path.write_bytes(("\r\n".join(lines) + "\r\n").encode("latin-1"))


def _halscope(path, t, ref, curves):
    """A LinuxCNC 2.9+ halscope log: ``joint.0.pos-cmd`` and the ``curves`` (``[(pin, values)]``)."""
    lines = [f"# Sampling period is {round(t[1] * 1e9)} ns", ";".join(["joint.0.pos-cmd", *(f"joint.0.{pin}"
                                                                                         for pin, _ in curves)])]
    lines += [row.split(";", 1)[1] for row in _rows(t, ref, curves, str)]
    path.write_text("\n".join(lines) + "\n")


def _twincat(path, t, ref, curves):
    """A TwinCAT Scope CSV export (``;``, one acquisition group): ``SetPos`` and the ``curves``."""
    names = ["SetPos", *(name for name, _ in curves)]
    head = ["Name;axis_trace", "File;C:\\scope\\axis_trace.csv",
            "Starttime of export;132959733843760000;Montag, 2. Mai 2022;15:56:24.376", "", "",
            ";".join(["Name", *(f"MAIN.Axis1.NcToPlc.{n}" for n in names)]),
            ";".join(["SampleTime[ms]", *(f"{t[1] * 1e3:g}" for _ in names)]), ""]
    path.write_bytes(("\r\n".join(head + _rows(t, ref, curves, lambda tk: f"{tk * 1e3:g}")) + "\r\n").encode())


def _delimited(path, t, ref, curves):
    """A logger's CSV: ``Zeit`` [s], ``Soll`` and the ``curves``."""
    lines = [";".join(["Zeit", "Soll", *(name for name, _ in curves)])]
    path.write_text("\n".join(lines + _rows(t, ref, curves, lambda tk: f"{tk:.4f}")) + "\n")


def _halscope_lag(ref, act):
    """motion's f-error: against the previous sample's pos-cmd (LinuxCNC control.c); the first
    sample's against its own."""
    return _printed(np.r_[ref[0], ref[:-1]] - act)


#: format -> (writer, its actual-position channel, its following-error channel, read options)
FORMATS = {
    "tncscope": (_tncscope, "s actl", "s diff", {}),
    "halscope": (_halscope, "pos-fb", "f-error", {}),
    "twincat": (_twincat, "ActPos", "PosDiff", {}),
    "delimited": (_delimited, "Ist", "Schlepp", {"t": "Zeit", "x_ref": "Soll"}),
}
SUFFIX = {"tncscope": "sco", "halscope": "log", "twincat": "csv", "delimited": "csv"}


def _write(fmt, path, capture, *, lag: bool, sign=1.0):
    """The trace of ``capture`` in ``fmt``, with the actual position or the following error; the
    read options (the mapping of delimited text)."""
    writer, actual, following, options = FORMATS[fmt]
    t, ref, act, fe = _channels(capture, sign=sign)
    if fmt == "halscope" and lag:
        fe = sign * _halscope_lag(capture.reference[:, 0], capture.measured[:, 0])
    writer(path, t, ref, [(following, fe) if lag else (actual, act)])
    if fmt != "delimited":
        return {}
    return {"columns": {**options, ("x_lag" if lag else "x"): following if lag else actual}}


# ------------------------------------------------------------------------------------ reading
@pytest.mark.parametrize("fmt", FORMATS)
def test_lag_trace_reads_as_the_actual_position_trace(simulated, tmp_path, fmt):
    """commanded - following error gives the printed actual position (halscope: one sample later)."""
    f_act, f_lag = tmp_path / f"act.{SUFFIX[fmt]}", tmp_path / f"lag.{SUFFIX[fmt]}"
    cap_act = read_capture(f_act, **_write(fmt, f_act, simulated, lag=False))
    cap_lag = read_capture(f_lag, **_write(fmt, f_lag, simulated, lag=True))
    if fmt == "halscope":  # the first sample has no previous pos-cmd: dropped
        assert "dropped_first" in cap_lag.meta
        cap_act = cap_act.slice(1, len(cap_act))
    assert cap_lag.axes == ("x",) and len(cap_lag) == len(cap_act)
    np.testing.assert_allclose(cap_lag.t - cap_lag.t[0], cap_act.t - cap_act.t[0], atol=1e-12)
    np.testing.assert_array_equal(cap_lag.reference, cap_act.reference)
    np.testing.assert_allclose(cap_lag.measured, cap_act.measured, rtol=0, atol=PRINTED)
    assert " - " in cap_lag.meta["measured"] and "lags" in cap_lag.meta["following_error"]
    assert "commanded - following error" in cap_lag.meta["following_error"]
    assert "following_error" not in cap_act.meta


def test_halscope_f_error_is_against_the_previous_pos_cmd(simulated, tmp_path):
    """The same row's pos-cmd would put the measured position one sample's travel ahead: the
    reader takes the previous row's (LinuxCNC computes f-error before it moves pos-cmd on)."""
    f = tmp_path / "lag.log"
    _write("halscope", f, simulated, lag=True)
    cap = read_capture(f)
    act = _printed(simulated.measured[1:, 0])
    np.testing.assert_allclose(cap.measured[:, 0], act, rtol=0, atol=PRINTED)
    same_row = _printed(simulated.reference[1:, 0]) - _halscope_lag(simulated.reference[:, 0],
                                                                     simulated.measured[:, 0])[1:]
    assert np.max(np.abs(same_row - act)) > 100 * PRINTED  # what reading it from the same row would have made


@pytest.mark.parametrize("fmt", FORMATS)
def test_reversed_following_error_is_refused_naming_file_line_and_channel(simulated, tmp_path, fmt):
    f = tmp_path / f"reversed.{SUFFIX[fmt]}"
    options = _write(fmt, f, simulated, lag=True, sign=-1.0)
    with pytest.raises(CaptureError) as info:
        read_capture(f, **options)
    text = str(info.value)
    channel = {"tncscope": "col2 (s diff/X)", "halscope": "joint.0.f-error", "twincat": "MAIN.Axis1.NcToPlc.PosDiff",
               "delimited": "Schlepp"}[fmt]
    line = {"tncscope": 10, "halscope": 3, "twincat": 6, "delimited": 1}[fmt]
    assert text.startswith(f"{f}:{line}: following error channel {channel!r}: the commanded position less it leads "
                           "the command by ")
    assert "expected a following error of" in text and "is the channel's sign reversed?" in text


def _sinumerik(path, t, ref, fe):
    """A SINUMERIK trace of the setpoint and the following error of axis 1."""
    head = ['<traceSession version="1">', "<traceData>", "<dataFrame>", '<frameHeader name="frame1"/>',
            '<dataSignal id="f1" name="/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 1]" '
            'description="Position setpoint (64 bit)" interval="0.001000"/>',
            '<dataSignal id="f4" name="/Nck/!SD/nckServoDataContDev64 [u1, 1]" '
            'description="Following error (64 bit)" interval="0.001000"/>']
    rows = [f'<rec time="{tk:.6f}" f1="{r:.6f}" f4="{e:.6f}"/>' for tk, r, e in zip(t, ref, fe)]
    path.write_text("\n".join(head + rows + ["</dataFrame>", "</traceData>", "</traceSession>"]) + "\n")


def test_sinumerik_following_error_sign_is_checked(simulated, tmp_path):
    t, ref, act, fe = _channels(simulated)
    f = tmp_path / "trace.xml"
    _sinumerik(f, t, ref, fe)
    cap = read_capture(f)
    assert "lags" in cap.meta["signals"]
    np.testing.assert_allclose(cap.measured[:, 0], act, rtol=0, atol=PRINTED)
    _sinumerik(f, t, ref, -fe)
    with pytest.raises(CaptureError, match=r"following error channel '/Nck/!SD/nckServoDataContDev64 \[u1, 1\] "
                                           r"\(Following error \(64 bit\)\)': the commanded position less it leads"):
        read_capture(f)


@pytest.mark.parametrize("fmt", ["tncscope", "halscope", "twincat"])
def test_an_actual_position_beside_the_following_error_is_used(simulated, tmp_path, fmt):
    """With both channels the actual position is read (it needs no sign convention); the
    following error, reversed here, is not used."""
    writer, actual, following, _ = FORMATS[fmt]
    t, ref, act, fe = _channels(simulated)
    f = tmp_path / f"both.{SUFFIX[fmt]}"
    writer(f, t, ref, [(following, -fe), (actual, act)])
    cap = read_capture(f)
    expected = {"tncscope": "x:col3", "halscope": "x:joint.0.pos-fb", "twincat": "x:MAIN.Axis1.NcToPlc.ActPos"}
    assert cap.meta["measured"] == expected[fmt] and "following_error" not in cap.meta
    np.testing.assert_array_equal(cap.measured[:, 0], act)


def test_mapping_with_both_the_position_and_the_lag_of_an_axis_is_an_error(simulated, tmp_path):
    f = tmp_path / "log.csv"
    _write("delimited", f, simulated, lag=True)
    with pytest.raises(CaptureError, match=r"gives both x= \(the measured position\) and x_lag= \(the following "
                                           r"error\) for one axis: give one"):
        read_capture(f, columns={"t": "Zeit", "x_ref": "Soll", "x": "Schlepp", "x_lag": "Schlepp"})
    with pytest.raises(CaptureError, match=r"needs '<axis>_ref=...' and '<axis>=...' \(or '<axis>_lag=...'"):
        read_capture(f, columns={"t": "Zeit", "x_lag": "Schlepp"})


# ------------------------------------------------------------------------------- command line
@pytest.mark.parametrize("fmt", FORMATS)
def test_convert_reads_a_lag_trace_and_refuses_a_reversed_one(simulated, tmp_path, capsys, fmt):
    f = tmp_path / f"lag.{SUFFIX[fmt]}"
    options = _write(fmt, f, simulated, lag=True)
    columns = ["--columns", ",".join(f"{k}={v}" for k, v in options["columns"].items())] if options else []
    out = tmp_path / "c.csv"
    assert main(["convert", str(f), "-o", str(out), *columns]) == 0
    assert "following_error: x:" in capsys.readouterr().out
    first = 1 if fmt == "halscope" else 0  # halscope: the first sample dropped
    np.testing.assert_allclose(read_capture(out).measured[:, 0], _printed(simulated.measured[first:, 0]), rtol=0,
                               atol=PRINTED)
    _write(fmt, f, simulated, lag=True, sign=-1.0)
    assert main(["convert", str(f), "-o", str(tmp_path / "r.csv"), *columns]) == 2
    assert f"{f}:" in capsys.readouterr().err


def _model(args):
    assert main(["identify", *args, "--no-diagnose"]) == 0
    return json.loads(open(args[args.index("--json") + 1]).read())


def test_identify_a_lag_trace_gives_the_model_of_the_capture(simulated, tmp_path, capsys):
    """The model identified from each lag trace (1 nm digits) equals the simulated capture's (for
    halscope, whose first sample is dropped, the capture's from its second sample): its poles
    within 1 %, its prediction within 0.05 um RMS."""
    base = {}
    for name, cap in (("all", simulated), ("halscope", simulated.slice(1, len(simulated)))):
        cap.to_csv(tmp_path / f"{name}.csv")
        base[name] = _model([str(tmp_path / f"{name}.csv"), "--json", str(tmp_path / f"{name}.json")])
    for fmt in FORMATS:
        f = tmp_path / f"lag.{SUFFIX[fmt]}"
        options = _write(fmt, f, simulated, lag=True)
        columns = ["--columns", ",".join(f"{k}={v}" for k, v in options["columns"].items())] if options else []
        model = _model([str(f), *columns, "--json", str(tmp_path / f"{fmt}.json")])
        original = base.get(fmt, base["all"])
        for key, value in original["poles"].items():
            assert model["poles"][key] == pytest.approx(value, rel=0.01, abs=1e-3), (fmt, key)
        assert model["fit"]["rms_um"] == pytest.approx(original["fit"]["rms_um"], abs=0.05), fmt
    capsys.readouterr()


def test_halscope_old_layout_motor_pins_and_a_pid_error_mapped_as_lag(simulated, tmp_path):
    """A LinuxCNC 2.8 log of ``motor-pos-cmd`` and ``f-error`` (the layout of a real Mesa log,
    tracewild): paired without a mapping, the f-error against the previous sample; a ``pid.N.error``
    mapped as the lag (command - feedback of the same period, pid(9)) against the same sample."""
    _, ref, act, fe = _channels(simulated)
    shifted = _halscope_lag(simulated.reference[:, 0], simulated.measured[:, 0])
    lines = ["Sampling period is 1000000 nSec ", ""]
    lines += [f"joint.0.motor-pos-cmd {r:+.6f} joint.0.f-error {s:+.6f} pid.x.error {e:+.6f} (null) +0.00000000000000 "
              for r, s, e in zip(ref, shifted, fe)]
    lines += [lines[-1]]  # the row written past the record by LinuxCNC <= 2.8
    f = tmp_path / "old.log"
    f.write_text("\n".join(lines) + "\n")
    cap = read_capture(f)
    assert cap.meta["measured"] == "x:joint.0.motor-pos-cmd - joint.0.f-error"
    np.testing.assert_allclose(cap.measured[:, 0], act[1:], rtol=0, atol=PRINTED)
    cap = read_capture(f, columns={"x_ref": "joint.0.motor-pos-cmd", "x_lag": "pid.x.error"})
    assert "dropped_first" not in cap.meta and len(cap) == len(act)
    np.testing.assert_allclose(cap.measured[:, 0], act, rtol=0, atol=PRINTED)


def test_tncscope_s_diff_in_um_is_converted_from_its_dimension(simulated, tmp_path):
    t, ref, act, fe = _channels(simulated)
    f = tmp_path / "um.sco"
    _tncscope(f, t, ref, [("s diff", np.round(fe * 1000, 3))])
    f.write_bytes(f.read_bytes().replace(b"%NAME=s diff/X\r\n%CHANNELTYPE=s diff\r\n%AXISTYPE=X\r\n%DIMENSION=mm",
                                         "%NAME=s diff/X\r\n%CHANNELTYPE=s diff\r\n%AXISTYPE=X\r\n%DIMENSION=µm"
                                         .encode("latin-1")))
    cap = read_capture(f)
    assert cap.meta["converted"] == "col2x0.001"
    np.testing.assert_allclose(cap.measured[:, 0], act, rtol=0, atol=PRINTED)


def test_sign_check_on_a_lag_proportional_to_the_velocity():
    """A ramp up, a run at speed and a ramp down, sampled at 1 ms: a following error of tau times
    the velocity is a lag of tau; a lead within a sample is accepted and recorded, beyond it refused;
    a command at rest is not judged."""
    ts = 0.001
    v = np.r_[np.linspace(0, 100, 200), np.full(600, 100.0), np.linspace(100, 0, 200)]
    ref = np.cumsum(v) * ts
    assert check_lag_sign(ref, 0.02 * v, ts, channel="lag", src="f") == "lags 20 ms at speed"
    assert check_lag_sign(ref, -0.0004 * v, ts, channel="lag", src="f").startswith("leads 0.4 ms at speed: within")
    with pytest.raises(CaptureError, match=r"^f:7: following error channel 'lag': the commanded position less it "
                                           r"leads the command by 20 ms at speed"):
        check_lag_sign(ref, -0.02 * v, ts, channel="lag", src="f", line=7)
    assert check_lag_sign(np.zeros(50), np.full(50, 1e-3), ts, channel="lag", src="f").startswith("sign not judged")
