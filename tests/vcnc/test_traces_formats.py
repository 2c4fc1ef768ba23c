"""SINUMERIK trace XML, TwinCAT Scope CSV, halscope logs and generic delimited text (issue #17).

Each fixture is written here, in the format, from a capture of the project's virtual fadal-pid
machine, and must read back to the capture it came from, exact to the printed precision
(multi-rate signals and change-only rows included).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import toolpaths
import vcnc
from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError
from vcnc.traces import read_trace, trace_format


def _six(a: np.ndarray) -> np.ndarray:
    """Values as a trace printing 6 decimals holds them."""
    return np.array([float(f"{v:.6f}") for v in np.ravel(a)])


@pytest.fixture(scope="module")
def capture():
    """About 1.5 s of the x axis of fadal-pid running random moves (1 ms samples)."""
    machine = vcnc.machine("fadal-pid")
    program = vcnc.parse_program(toolpaths.random_moves(6, 5.0, 6000.0, seed=3))
    cap = machine.simulate(vcnc.interpolate(program, machine), seed=0).select_axes(("x",))
    return cap.slice(0, 1500)


# ----------------------------------------------------------------------------------- SINUMERIK
def _sinumerik(path, t, ref, *, fe=None, meas=None, axis=7, meas_every=2):
    """A SINUMERIK trace: setpoint (and following error) every sample, measPos1 every
    ``meas_every`` samples, each written only when its printed value changed."""
    head = ['<?xml version="1.0" encoding="UTF-8"?>', '<traceSession version="1">', "<traceData>", "<dataFrame>",
            '<frameHeader name="frame1"/>',
            f'<dataSignal id="f1" key="s14" name="/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, {axis}]" '
            f'description="Position setpoint (64 bit)" interval="0.001000" datapointCount="{t.size}" '
            'unitsType="posn"/>',
            '<dataSignal id="f2" key="s15" name="/Nck/!SD/nckServoDataActVelMot64 [u1, 3]" '
            'description="Actual speed (64 bit)" interval="0.001000" unitsType="vel"/>']
    if fe is not None:
        head.append(f'<dataSignal id="f4" key="s16" name="/Nck/!SD/nckServoDataContDev64 [u1, {axis}]" '
                    'description="Following error (64 bit)" interval="0.001000" unitsType="posn"/>')
    if meas is not None:
        head.append(f'<dataSignal id="f8" key="s20" name="/Nck/!SD/measPos1 [u1, {axis}]" '
                    'description="Actual position value for measuring system 1" interval="0.002000" unitsType="posn"/>')
    last: dict[str, str] = {}
    rows = []
    for k in range(t.size):
        attrs = []
        signals = [("f1", ref[k]), ("f2", 0.0)]
        if fe is not None:
            signals.append(("f4", fe[k]))
        if meas is not None and k % meas_every == 0:
            signals.append(("f8", meas[k]))
        for sid, v in signals:
            text = f"{v:.6f}"
            if last.get(sid) != text:
                attrs.append(f'{sid}="{text}"')
                last[sid] = text
        rows.append(f'<rec time="{t[k]:.6f}" {" ".join(attrs)}/>')
    path.write_text("\n".join(head + rows + ["</dataFrame>", "</traceData>", "</traceSession>"]) + "\n")


def test_sinumerik_setpoint_minus_following_error_reads_back(capture, tmp_path):
    ref, x = _six(capture.reference), capture.measured[:, 0]
    fe = _six(ref - x)
    f = tmp_path / "trace.xml"
    _sinumerik(f, capture.t, ref, fe=fe, meas=x)
    assert trace_format(f) == "sinumerik"
    cap = read_capture(f)
    assert cap.axes == ("x",) and cap.meta["axis_numbers"] == "x:7"
    assert "following error" in cap.meta["signals"]
    np.testing.assert_array_equal(cap.t, np.round(capture.t - capture.t[0], 12))
    np.testing.assert_array_equal(cap.reference[:, 0], ref)
    np.testing.assert_array_equal(cap.measured[:, 0], _six(ref - fe))  # exact decimals; change-only rows held
    assert np.max(np.abs(cap.measured[:, 0] - x)) <= 1.01e-6  # two values printed with 6 decimals


def test_sinumerik_measuring_system_at_ipo_rate(capture, tmp_path):
    """Without a following error the measured position is measPos1 at its own 2 ms rate."""
    ref, meas = _six(capture.reference), _six(capture.measured)
    f = tmp_path / "trace.xml"
    _sinumerik(f, capture.t, ref, meas=meas, axis=2)
    cap = read_capture(f, axes=("y",))
    assert cap.axes == ("y",) and cap.meta["axis_numbers"] == "y:2" and cap.sample_time == 0.002
    assert "measuring system 1" in cap.meta["signals"]
    np.testing.assert_array_equal(cap.reference[:, 0], ref[::2])
    np.testing.assert_array_equal(cap.measured[:, 0], meas[::2])


def test_sinumerik_bad_input_names_the_element(capture, tmp_path, capsys):
    ref = _six(capture.reference)
    f = tmp_path / "trace.xml"
    _sinumerik(f, capture.t[:50], ref[:50], meas=ref[:50])
    text = f.read_text()
    f.write_text(text.replace('<rec time="0.010000"', '<rec time="0.001000"'))
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out)]) == 2
    assert "<rec> number 11: time goes backwards" in capsys.readouterr().err and not out.exists()
    f.write_text(text.replace('description="Actual position value for measuring system 1"', 'description="x"')
                 .replace("measPos1", "something"))
    with pytest.raises(CaptureError, match="no position setpoint with .*signals found:.*Actual speed"):
        read_capture(f)
    f.write_text(text.replace('<rec time="0.010000" ', '<rec time="0.010000" f9="1.0" '))
    with pytest.raises(CaptureError, match="'f9' names no <dataSignal>"):
        read_capture(f)


def test_identify_sinumerik_trace_and_converted_csv_give_the_same_model(capture, tmp_path):
    machine = vcnc.machine("fadal-pid")
    program = vcnc.parse_program(toolpaths.random_moves(12, 10.0, 9000.0, seed=4))
    cap = machine.simulate(vcnc.interpolate(program, machine), seed=0).select_axes(("x",))
    ref = _six(cap.reference)
    f = tmp_path / "trace.xml"
    _sinumerik(f, cap.t, ref, fe=_six(ref - cap.measured[:, 0]))
    csv = tmp_path / "capture.csv"
    assert main(["convert", str(f), "-o", str(csv)]) == 0
    models = []
    for src in (f, csv):
        out = tmp_path / f"{src.stem}.json"
        assert main(["identify", str(src), "--no-diagnose", "--json", str(out)]) == 0
        models.append(json.loads(out.read_text())["parameters"])
    assert models[0] == models[1]


# ------------------------------------------------------------------------------------- TwinCAT
def _twincat(path, t_ms, cmd, act):
    """A TwinCAT 3 Scope CSV export (tab, decimal comma, one time column per channel)."""
    def row(key, a, b):
        return f"{key}\t{a}\t{key}\t{b}"

    lines = ["Name\taxis_trace", "File\tC:\\scope\\axis_trace.csv",
             "Starttime of export\t132959733843760000\tMontag, 2. Mai 2022\t15:56:24.376", "", "",
             row("Name", "MAIN.fPosCmd", "MAIN.fPosAct"), row("SymbolComment", "", ""),
             row("Data-Type", "REAL64", "REAL64"), row("SampleTime[ms]", "1", "1"),
             row("Unit", "mm", "mm"), row("ScaleFactor", "1", "1"), ""]
    for k in range(t_ms.size):
        lines.append("\t".join(f"{v:.6f}".replace(".", ",") if i % 2 else f"{v:g}".replace(".", ",")
                               for i, v in enumerate((t_ms[k], cmd[k], t_ms[k], act[k]))))
    lines.append("EOF")
    path.write_text("\r\n".join(lines) + "\r\n", encoding="utf-8")


def test_twincat_scope_csv_reads_back(capture, tmp_path, capsys):
    ref, meas = _six(capture.reference), _six(capture.measured)
    f = tmp_path / "scope.csv"
    _twincat(f, capture.t * 1e3, ref, meas)
    assert trace_format(f) == "twincat"
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--columns", "x_ref=MAIN.fPosCmd,x=MAIN.fPosAct"]) == 0
    assert "TwinCAT Scope CSV" in capsys.readouterr().out
    cap = read_capture(out)
    np.testing.assert_allclose(cap.t, capture.t - capture.t[0], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(cap.reference[:, 0], ref)
    np.testing.assert_array_equal(cap.measured[:, 0], meas)
    # without --columns, PLC variables whose names leave no doubt are read from the names (tracewild2)
    named = read_capture(f)
    np.testing.assert_array_equal(named.measured[:, 0], meas)
    assert named.meta["columns"] == "from the channel names: x_ref=MAIN.fPosCmd, x=MAIN.fPosAct"


# ------------------------------------------------------------------------------------ halscope
def _halscope(path, ref, meas, period_ns=1_000_000):
    """LinuxCNC <= 2.8 ``write_log_file``: pairs, and one row past the record (``n <= samples``)."""
    lines = [f"Sampling period is {period_ns} ns ", ""]
    lines += [f"joint.0.motor-pos-cmd {r:+.14f} joint.0.motor-pos-fb {m:+.14f} " for r, m in zip(ref, meas)]
    lines += [f"joint.0.motor-pos-cmd {0:+.14f} joint.0.motor-pos-fb {0:+.14f} "]
    path.write_text("\n".join(lines) + "\n")


def test_halscope_log_pairs_the_joint_pins(capture, tmp_path):
    ref, meas = capture.reference[:, 0], capture.measured[:, 0]
    f = tmp_path / "scope.log"
    _halscope(f, ref, meas)
    assert trace_format(f) == "halscope"
    cap = read_capture(f)
    assert cap.axes == ("x",) and cap.sample_time == 0.001 and len(cap) == len(ref)
    assert cap.meta["dropped"].startswith(f"line {len(ref) + 3}: one sample past the record")
    np.testing.assert_array_equal(cap.reference[:, 0], [float(f"{v:+.14f}") for v in ref])
    np.testing.assert_array_equal(cap.measured[:, 0], [float(f"{v:+.14f}") for v in meas])
    with pytest.raises(CaptureError, match="channel\\(s\\) \\['nope'\\] not found; channels found"):
        read_capture(f, columns={"x_ref": "nope", "x": "joint.0.motor-pos-fb"})


# ------------------------------------------------------------------------------ generic delimited
def test_logger_csv_with_preamble_semicolons_and_decimal_comma(capture, tmp_path):
    ref, meas = _six(capture.reference), _six(capture.measured)
    f = tmp_path / "logger.txt"
    rows = [f"{t * 1e3:.0f};{r:.6f};{m:.6f}".replace(".", ",") for t, r, m in zip(capture.t, ref, meas)]
    f.write_text("Logger 3000 export\nChannels: 3\n\nZeit;Soll;Ist\n" + "\n".join(rows) + "\n")
    assert trace_format(f) == "delimited"
    # the names say which column is which (vcnc.traces.names), but not the units: a time column stepping by 1
    # is no drive trace in seconds
    with pytest.raises(CaptureError, match="the time column 'Zeit' \\(read from its name\\) steps by 1 and the file "
                                           "does not state its unit.*expected --time-unit"):
        read_capture(f)
    mapped = read_capture(f, columns={"t": "Zeit", "x_ref": "Soll", "x": "Ist"}, time_unit="ms", unit="um")
    named = read_capture(f, time_unit="ms", unit="um")
    for cap in (mapped, named):
        np.testing.assert_allclose(cap.t, capture.t - capture.t[0], rtol=0, atol=1e-12)
        np.testing.assert_array_equal(cap.reference[:, 0], ref * 1e-3)
        np.testing.assert_array_equal(cap.measured[:, 0], meas * 1e-3)
    assert "columns" not in mapped.meta
    assert named.meta["columns"] == ("from the header names: t=Zeit, x_ref=Soll, x=Ist (--columns, --time-unit, "
                                     "--unit set them)")
    with pytest.raises(CaptureError, match="column 'Pos' not found; columns found: \\['Zeit', 'Soll', 'Ist'\\]"):
        read_capture(f, columns={"t": "Zeit", "x_ref": "Pos", "x": "Ist"})


def test_rotary_axis_in_degrees(capture, tmp_path, capsys):
    f = tmp_path / "rotary.csv"
    rows = [f"{t:.3f},{r:.6f},{m:.6f}" for t, r, m in zip(capture.t, capture.reference[:, 0], capture.measured[:, 0])]
    f.write_text("time,cmd,act\n" + "\n".join(rows) + "\n")
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--columns", "t=time,a_ref=cmd,a=act", "--unit", "deg"]) == 0
    assert "axes a [deg]" in capsys.readouterr().out
    assert read_capture(out).axes == ("a",)
    assert main(["identify", str(out), "--no-diagnose"]) == 0
    assert "rms" in (summary := capsys.readouterr().out) and " mdeg, max " in summary and " um" not in summary
    assert main(["convert", str(f), "-o", str(out), "--columns", "t=time,x_ref=cmd,x=act", "--unit", "deg"]) == 2
    assert "unit 'deg' is for rotary axes" in capsys.readouterr().err


def test_positions_logged_in_counts(capture, tmp_path, capsys):
    """A log of integer increments without a header or time column, as Mitsubishi's sampling output writes it
    (C70 manual, 2.7.9.4 "Data Output Format": one line per sample, the channels' values in their output unit,
    e.g. "B(1μm)", separated by commas, CR+LF): ``--unit 0.1um`` gives the size of one count."""
    counts = np.round(np.column_stack([capture.reference[:, 0], capture.measured[:, 0]]) / 1e-4).astype(int)
    f = tmp_path / "sampling.txt"
    f.write_text("".join(f"{r}, {m}\r\n" for r, m in counts))
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--columns", "x_ref=1,x=2", "--sample-time", "0.001",
                 "--unit", "0.1um"]) == 0
    cap = read_capture(out)
    np.testing.assert_allclose(cap.reference[:, 0], counts[:, 0] * 1e-4, rtol=1e-12, atol=0)
    np.testing.assert_allclose(cap.measured[:, 0], counts[:, 1] * 1e-4, rtol=1e-12, atol=0)
    assert np.max(np.abs(cap.measured[:, 0] - capture.measured[:, 0])) <= 0.5e-4 + 1e-12  # half a count
    in_nm = read_capture(f, columns={"x_ref": "1", "x": "2"}, sample_time=0.001, unit="100nm")
    np.testing.assert_allclose(in_nm.measured, cap.measured, rtol=1e-12, atol=0)
    for bad in ("0um", "0.1 furlong", "-1um", "um0.1"):
        assert main(["convert", str(f), "-o", str(out), "--columns", "x_ref=1,x=2", "--sample-time", "0.001",
                     f"--unit={bad}"]) == 2
        assert f"position unit {bad!r}: expected one of mm, um, nm" in capsys.readouterr().err
    assert main(["convert", str(f), "-o", str(out), "--columns", "x_ref=1,x=2", "--sample-time", "0.001",
                 "--unit", "0.001deg"]) == 2
    assert "unit '0.001deg' is for rotary axes" in capsys.readouterr().err


def test_delimited_bad_input(tmp_path, capsys):
    f = tmp_path / "bad.csv"
    f.write_text("time,cmd,act\n0,0,0\n0.002,1,1\n0.001,2,2\n")
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--columns", "t=time,x_ref=cmd,x=act"]) == 2
    err = capsys.readouterr().err
    assert "bad.csv:4" in err and "time does not increase" in err and not out.exists()
    assert main(["convert", str(f), "-o", str(out), "--columns", "t=time,x_ref=cmd"]) == 2
    assert "needs '<axis>_ref=...' and '<axis>=...'" in capsys.readouterr().err
    assert main(["convert", str(f), "-o", str(out), "--columns", "t=time,q=cmd"]) == 2
    assert "--columns part 'q=cmd'" in capsys.readouterr().err
    f.write_text("no numbers here\n")
    with pytest.raises(CaptureError, match="no rows of numbers"):
        read_trace(f, columns={"t": "1", "x_ref": "2", "x": "3"})
