"""Variants of the trace formats met outside the issue's description, each in a fixture written
here: halscope logs of LinuxCNC 2.9 and later, SINUMERIK traces whose signals are named in the
setup, TNCscope exports in UTF-16 or with a decimal comma, and the timing checks."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError
from vcnc.traces import trace_format

N = 150
REF = np.round(5 * np.sin(np.arange(N) * 0.05), 6)
ACT = np.round(REF - 0.01 * np.cos(np.arange(N) * 0.05), 6)


# ------------------------------------------------------------------------------------ halscope
def _halscope29(path, *, labels=("joint.0.motor-pos-cmd", "joint.0.motor-pos-fb"), comments=True):
    """``write_log_file`` of LinuxCNC 2.9+: '# Sampling period', names, '# Position'/'# Scale', rows."""
    head = ["# Sampling period is 1000000 ns", ";".join(labels)]
    if comments:
        head += ["# Position: " + ";".join("0.000000" for _ in labels), "# Scale: " + ";".join("5" for _ in labels)]
    extra = [f"{0.5:.14f}"] * (len(labels) - 2)
    rows = [";".join([f"{r:.14f}", f"{a:.14f}", *extra]) for r, a in zip(REF, ACT)]
    path.write_text("\n".join(head + rows) + "\n")


@pytest.mark.parametrize("comments", [True, False])
def test_halscope_log_of_linuxcnc_29(tmp_path, comments):
    f = tmp_path / "scope.log"
    _halscope29(f, labels=("joint.0.motor-pos-cmd", "joint.0.motor-pos-fb", "spindle.0.speed-out"), comments=comments)
    assert trace_format(f) == "halscope"
    cap = read_capture(f)
    assert cap.axes == ("x",) and cap.sample_time == 0.001
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)


def test_halscope_signal_names_pair_by_axis_letter(tmp_path):
    f = tmp_path / "scope.log"
    _halscope29(f, labels=("z-pos-cmd", "z-pos-fb"))
    cap = read_capture(f)
    assert cap.axes == ("z",) and cap.meta["commanded"] == "z:z-pos-cmd"


def test_halscope_joint_pins_prefer_motor_positions(tmp_path):
    f = tmp_path / "scope.log"
    _halscope29(f, labels=("joint.1.pos-cmd", "joint.1.pos-fb", "joint.1.motor-pos-cmd", "joint.1.motor-pos-fb"))
    cap = read_capture(f, axes=("y",))
    assert cap.axes == ("y",) and cap.meta["measured"] == "y:joint.1.motor-pos-fb"


def test_halscope_29_bad_rows(tmp_path):
    f = tmp_path / "scope.log"
    _halscope29(f)
    lines = f.read_text().splitlines()
    f.write_text("\n".join(lines[:10] + ["0.1;0.2;0.3"] + lines[10:]) + "\n")
    with pytest.raises(CaptureError, match=r"scope.log:11: 3 values, expected 2"):
        read_capture(f)
    f.write_text("\n".join(lines[:10] + ["0.1;nan"] + lines[10:]) + "\n")
    with pytest.raises(CaptureError, match=r"scope.log:11: channel 'joint.0.motor-pos-fb': 'nan' is not a number"):
        read_capture(f)
    f.write_text("\n".join(lines + ["0.123"]) + "\n")  # a log cut short in its last line
    assert len(read_capture(f)) == N


def _halscope28(path, *, comma=False):
    """A log as LinuxCNC 2.8 wrote it on a real machine: ``nSec``, an encoder as feedback, a channel
    not enabled labelled ``(null)``, numbers in the user's locale, ``-nan`` in an unused channel,
    and one row past the record (LinuxCNC ``scope_files.c`` before commit 8eae446b80)."""
    def num(v):
        return f"{v:+.14f}".replace(".", "," if comma else ".")

    rows = [(num(r), num(a), "-nan" if k == 7 else num(0)) for k, (r, a) in enumerate(zip(REF, ACT))]
    rows.append((num(0), num(0), num(0)))
    lines = ["Sampling period is 1000000 nSec ", ""]
    lines += [f"joint.0.motor-pos-cmd {r} hm2_7i76e.0.encoder.02.position {a} acc.out {o} (null) {num(0)} "
              for r, a, o in rows]
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("comma", [False, True])
def test_halscope_log_of_linuxcnc_28_as_written(tmp_path, capsys, comma):
    f = tmp_path / "halscope.log"
    _halscope28(f, comma=comma)
    with pytest.raises(CaptureError, match=r"joint.0.motor-pos-cmd has no -fb pin: give --columns "
                                           r"x_ref=joint.0.motor-pos-cmd,x=FEEDBACK; .*other position channels: "
                                           r"\['hm2_7i76e.0.encoder.02.position'\]$"):
        read_capture(f)
    columns = {"x_ref": "joint.0.motor-pos-cmd", "x": "hm2_7i76e.0.encoder.02.position"}
    cap = read_capture(f, columns=columns)
    assert len(cap) == N and cap.sample_time == 0.001
    assert cap.meta["dropped"] == f"line {N + 3}: one sample past the record (LinuxCNC <= 2.8)"
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)
    with pytest.raises(CaptureError, match=r"halscope.log:10: channel 'acc.out': '-nan' is not a number"):
        read_capture(f, columns={"x_ref": "joint.0.motor-pos-cmd", "x": "acc.out"})
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--columns",
                 "x_ref=joint.0.motor-pos-cmd,x=hm2_7i76e.0.encoder.02.position"]) == 0
    assert f"{N} samples, sample time 1 ms" in capsys.readouterr().out


# ----------------------------------------------------------------------------------- SINUMERIK
def test_sinumerik_signals_named_in_the_setup(tmp_path):
    """A ``<dataSignal>`` with only id, key and interval takes its name from the setup's
    ``<signal key=...>``; the root may be ``<traceDataRoot>``."""
    f = tmp_path / "trace.xml"
    setup = ('<traceDisplaySetup_V20><signals>'
             '<signal key="s14" name="/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 3]" description="Position setpoint"/>'
             '<signal key="s5" name="/Nck/!SD/nckServoDataFlwErr64 [u1, 3]" description="Following Error (64 bit)"/>'
             '</signals></traceDisplaySetup_V20>')
    recs = "".join(f'<rec time="{k * 0.002:.6f}" f1="{r:.6f}" f2="{r - a:.6f}"/>\n'
                   for k, (r, a) in enumerate(zip(REF, ACT)))
    f.write_text('<?xml version="1.0" encoding="utf-8"?>\n<traceDataRoot>' + setup +
                 '<traceData><dataFrame><frameHeader dropOuts="0"/>'
                 '<dataSignal id="f1" key="s14" interval="0.002000"/><dataSignal id="f2" key="s5" interval="0.002000"/>'
                 + recs + "</dataFrame></traceData></traceDataRoot>\n")
    assert trace_format(f) == "sinumerik"
    cap = read_capture(f, axes=("z",))
    assert cap.meta["axis_numbers"] == "z:3" and "following error" in cap.meta["signals"]
    np.testing.assert_allclose(cap.measured[:, 0], ACT, rtol=0, atol=1e-12)


def test_xml_that_is_not_a_trace_names_its_root(tmp_path, capsys):
    f = tmp_path / "freq.xml"
    f.write_text('<?xml version="1.0" encoding="ISO-8859-1"?>\n<!-- 4.7 -->\n<ResponseTestCustom ver="4"/>\n')
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out)]) == 2
    assert "root <ResponseTestCustom>, not a SINUMERIK trace" in capsys.readouterr().err and not out.exists()


# ------------------------------------------------------------------------------------ TNCscope
def _tnc(ctypes=("s soll", "s ist"), comma=False, skip=None):
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", "%CONTROL=TNC640", "%SAMPLING=3000"]
    for n, ctype in enumerate(ctypes, start=1):
        lines += [f"%[CURVE{n}]", f"%NAME={ctype}/X", f"%CHANNELTYPE={ctype}", "%AXISTYPE=X", "%DIMENSION=mm",
                  f"%COLUMN={n}"]
    lines.append("%[DATA]")
    for k, (r, a) in enumerate(zip(REF, ACT)):
        if k != skip:
            row = f"{k * 3000};{r:.6f};{a:.6f};"
            lines.append(row.replace(".", ",") if comma else row)
    return "\r\n".join(lines) + "\r\n"


@pytest.mark.parametrize(("encoding", "comma", "ctypes"), [("utf-16", False, ("s soll", "s ist")),
                                                           ("utf-8-sig", True, ("s noml", "s actl")),
                                                           ("latin-1", True, ("s nom", "s act"))])
def test_tncscope_encodings_decimal_comma_and_english_names(tmp_path, encoding, comma, ctypes):
    f = tmp_path / "x.sco"
    f.write_bytes(_tnc(ctypes, comma).encode(encoding))
    assert trace_format(f) == "tncscope"
    cap = read_capture(f)
    assert cap.axes == ("x",) and cap.sample_time == 0.003
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)


def test_tncscope_curves_without_column_and_name(tmp_path):
    """The ``.sco`` layout the MATLAB reader ``read_tncscope_file.m`` reads: blocks closed by a
    ``%`` line, ``%COUNT``/``%CYCLETIME`` per curve, no ``%COLUMN``/``%NAME`` (curves in column order)."""
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", "%SAMPLING=3000", "%"]
    for ctype in ("v act.", "s noml", "s actl"):
        lines += ["%[CURVE]", f"%CHANNELTYPE={ctype}", "%AXISTYPE=X", "%DIMENSION=mm", f"%COUNT={N}",
                  "%CYCLETIME=3000", "%"]
    lines.append("%[DATA]")
    lines += [f"{k * 3000};{0.5:.6f};{r:.6f};{a:.6f};" for k, (r, a) in enumerate(zip(REF, ACT))]
    f = tmp_path / "x.sco"
    f.write_bytes(("\r\n".join(lines) + "\r\n").encode("latin-1"))
    cap = read_capture(f)
    assert cap.meta["commanded"] == "x:col2" and cap.meta["measured"] == "x:col3"
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)
    f.write_bytes(("\r\n".join(lines).replace("%CHANNELTYPE=s noml", "%CHANNELTYPE=s noml\r\n%COLUMN=2") + "\r\n")
                  .encode("latin-1"))
    with pytest.raises(CaptureError, match=r"x.sco:5: curve 'v act. X' has no %COLUMN while 1 other curve"):
        read_capture(f)


# -------------------------------------------------------------------------------------- timing
def test_dropped_samples_and_jitter_are_named(tmp_path):
    f = tmp_path / "x.sco"
    f.write_bytes(_tnc(skip=40).encode("latin-1"))
    with pytest.raises(CaptureError, match=r"x.sco:\d+: 1 sample\(s\) missing in 1 gap\(s\), the first 0.006 s long "
                                           r"after t = 0.117 s"):
        read_capture(f)
    g = tmp_path / "log.csv"
    t = np.arange(N) * 0.001 + np.where(np.arange(N) % 3 == 0, 0.0002, 0.0)
    g.write_text("t,cmd,act\n" + "\n".join(f"{tk:.4f},{r},{a}" for tk, r, a in zip(t, REF, ACT)) + "\n")
    with pytest.raises(CaptureError, match=r"log.csv:3:1: sampling is not uniform.*jitter by up to 0.0002 s"):
        read_capture(g, columns={"t": "t", "x_ref": "cmd", "x": "act"})


def test_resample_interpolates_jitter_and_gaps_onto_the_median_step(tmp_path, capsys):
    """A logging PC's time stamps (steps of 9 to 11 ms, one sample dropped) with --resample: the
    capture is on the 10 ms grid, linear between the samples, and says so."""
    k = np.arange(N)
    t = k * 10.0 + np.where(k % 4 == 1, 1.0, 0.0) - np.where(k % 4 == 3, 1.0, 0.0)  # ms
    keep = k != 60
    ref, act = 2.0 * t * 1e-3, 2.0 * t * 1e-3 - 0.01  # ramps: linear interpolation is exact on them
    f = tmp_path / "log.txt"
    f.write_text("\n".join(f"{a:.0f}\t{b:.6f}\t{c:.6f}" for a, b, c in zip(t[keep], ref[keep], act[keep])) + "\n")
    out = tmp_path / "cap.csv"
    argv = ["convert", str(f), "-o", str(out), "--columns", "t=1,x_ref=2,x=3", "--time-unit", "ms"]
    assert main(argv) == 2 and "--resample" in capsys.readouterr().err and not out.exists()
    assert main([*argv, "--resample"]) == 0
    cap = read_capture(out)
    assert cap.sample_time == 0.01 and "linear, onto a 0.01 s step" in cap.meta["resampled"]
    np.testing.assert_allclose(cap.t, np.arange(len(cap)) * 0.01, rtol=0, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], 2.0 * cap.t, rtol=0, atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], 2.0 * cap.t - 0.01, rtol=0, atol=1e-9)


def test_units_from_the_header_and_the_twincat_unit_row(tmp_path):
    """``Zeit [ms]`` and ``Soll (µm)`` give the units when --time-unit/--unit are not given; a
    TwinCAT channel's ``Unit`` row too. Given units win."""
    t_ms = np.arange(N) * 2.0
    f = tmp_path / "log.csv"
    f.write_text("Zeit [ms];Soll (µm);Ist (µm)\n" + "\n".join(
        f"{t:.0f};{r * 1e3:.3f};{a * 1e3:.3f}".replace(".", ",") for t, r, a in zip(t_ms, REF, ACT)) + "\n",
        encoding="utf-8")
    cols = {"t": "Zeit [ms]", "x_ref": "Soll (µm)", "x": "Ist (µm)"}
    cap = read_capture(f, columns=cols)
    assert cap.sample_time == 0.002 and cap.meta["unit"] == "um"
    np.testing.assert_allclose(cap.reference[:, 0], REF, rtol=0, atol=1e-12)
    assert read_capture(f, columns=cols, time_unit="s", unit="mm").sample_time == 2.0
    g = tmp_path / "scope.csv"
    rows = [f"{t:g}\t{r * 1e3:.3f}\t{a * 1e3:.3f}" for t, r, a in zip(t_ms, REF, ACT)]
    g.write_text("\n".join(["Name\tscope", "File\tx.csv", "", "Name\tcmd\tact", "Unit\tµm (Length)\tµm (Length)"]
                           + rows) + "\n", encoding="utf-8")
    cap = read_capture(g, columns={"x_ref": "cmd", "x": "act"})
    assert cap.meta["unit"] == "um"
    np.testing.assert_allclose(cap.measured[:, 0], ACT, rtol=0, atol=1e-12)


@pytest.mark.parametrize("stamp", ["%Y-%m-%d %H:%M:%S.{ms}", "%Y-%m-%dT%H:%M:%S.{ms}Z", "%d.%m.%Y %H:%M:%S,{ms}",
                                   "%H:%M:%S.{ms}"])
def test_time_stamps_in_the_time_column(tmp_path, stamp):
    """A logger's wall-clock time stamps are read as seconds from the first (across midnight
    with a date), whatever --time-unit says."""
    import datetime

    t0 = datetime.datetime(2024, 5, 2, 23, 59, 59, 500_000)
    times = [t0 + datetime.timedelta(milliseconds=2 * k) for k in range(N)]
    if "%d" not in stamp:
        times = [t - datetime.timedelta(hours=1) for t in times]  # time of day alone cannot cross midnight
    cells = [t.strftime(stamp.format(ms=f"{t.microsecond // 1000:03d}")) for t in times]
    f = tmp_path / "log.csv"
    d = ";" if "," in stamp else ","
    f.write_text(f"Stamp{d}Soll{d}Ist\n" + "\n".join(f"{c}{d}{r:.6f}{d}{a:.6f}" for c, r, a in zip(cells, REF, ACT)))
    cap = read_capture(f, columns={"t": "Stamp", "x_ref": "Soll", "x": "Ist"}, time_unit="ms")
    assert cap.meta["time_unit"] == "time stamps" and cap.sample_time == 0.002
    np.testing.assert_array_equal(cap.t, np.round(np.arange(N) * 0.002, 6))
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)


def test_quoted_cells_and_quoted_decimal_commas(tmp_path):
    f = tmp_path / "log.csv"
    rows = [f'"{k * 0.002:.3f}","{r:.6f}","{a:.6f}"'.replace(".", ",") for k, (r, a) in enumerate(zip(REF, ACT))]
    f.write_text('"Time [s]","Soll","Ist"\n' + "\n".join(rows) + "\n")
    cap = read_capture(f, columns={"t": "Time [s]", "x_ref": "Soll", "x": "Ist"})
    assert cap.sample_time == 0.002
    np.testing.assert_array_equal(cap.reference[:, 0], REF)


def test_a_row_of_units_under_the_names(tmp_path):
    f = tmp_path / "log.csv"
    rows = [f"{k * 2};{r * 1e3:.3f};{a * 1e3:.3f}".replace(".", ",") for k, (r, a) in enumerate(zip(REF, ACT))]
    f.write_text("DAQ export\nZeit;Soll;Ist\n[ms];[µm];[µm]\n" + "\n".join(rows) + "\n", encoding="utf-8")
    cap = read_capture(f, columns={"t": "Zeit", "x_ref": "Soll", "x": "Ist"})
    assert cap.sample_time == 0.002 and cap.meta["unit"] == "um"
    np.testing.assert_allclose(cap.measured[:, 0], ACT, rtol=0, atol=1e-12)


# ---------------------------------------------------------------------------------- halsampler
def _halsampler(path, *, tags=False, lost=None):
    """LinuxCNC ``halsampler`` output (man halsampler(1), ``sampler_usr.c``): per sample a line of
    ``%f `` values (here commanded, feedback, a bit), the sample number first with ``-t``; samples
    ``lost`` from the FIFO replaced by an ``overrun`` line."""
    lines = []
    for k, (r, a) in enumerate(zip(REF, ACT)):
        if lost and k in lost:
            if k == lost[0]:
                lines.append("overrun")
            continue
        lines.append((f"{k} " if tags else "") + f"{r:f} {a:f} 1 ")
    path.write_text("\n".join(lines) + "\n")


def test_halsampler_output_with_the_servo_period(tmp_path, capsys):
    f = tmp_path / "samples.txt"
    _halsampler(f)
    with pytest.raises(CaptureError, match=r"--columns needs t=NAME \(the time column\), or --sample-time S"):
        read_capture(f, columns={"x_ref": "1", "x": "2"})
    with pytest.raises(CaptureError, match=r"samples.txt:2: time does not increase: 1 s after 1 s$"):
        read_capture(f, columns={"t": "3", "x_ref": "1", "x": "2"})  # the bit column taken for time
    cap = read_capture(f, columns={"x_ref": "1", "x": "2"}, sample_time=0.001)
    assert cap.meta["format"] == "delimited text (spaces)" and cap.meta["time_unit"] == "rows every 0.001 s"
    assert cap.sample_time == 0.001 and len(cap) == N
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--columns", "x_ref=1,x=2", "--sample-time", "0.001"]) == 0
    assert f"{N} samples, sample time 1 ms" in capsys.readouterr().out


def test_halsampler_overrun_is_a_gap(tmp_path):
    f = tmp_path / "samples.txt"
    _halsampler(f, lost=[40, 41, 42])
    with pytest.raises(CaptureError, match=r"samples.txt:41: 'overrun': halsampler lost samples here"):
        read_capture(f, columns={"x_ref": "1", "x": "2"}, sample_time=0.001)
    _halsampler(f, tags=True, lost=[40, 41, 42])
    tagged = {"t": "1", "x_ref": "2", "x": "3"}
    with pytest.raises(CaptureError, match=r"samples.txt:42: 3 sample\(s\) missing in 1 gap\(s\)"):
        read_capture(f, columns=tagged, sample_time=0.001)
    cap = read_capture(f, columns=tagged, sample_time=0.001, resample=True)
    assert len(cap) == N and cap.meta["time_unit"] == "sample numbers x 0.001 s"
    np.testing.assert_allclose(cap.reference[:39, 0], REF[:39], rtol=0, atol=0)
    with pytest.raises(CaptureError, match=r"--time-unit and --sample-time"):
        read_capture(f, columns=tagged, sample_time=0.001, time_unit="ms")
