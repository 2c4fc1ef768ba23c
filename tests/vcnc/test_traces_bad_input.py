"""Minimal reproducers of inputs that crashed a trace reader (found by fuzzing mutated fixtures):
each must now give a CaptureError naming the file, exit status 2 on the command line and no
output file."""

from __future__ import annotations

import pytest

from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError

TNC = ["%TNCscopeNT data file", "%[GLOBAL]", "%[CURVE1]", "%NAME=s soll/X", "%CHANNELTYPE=s soll", "%COLUMN={c}",
       "%[CURVE2]", "%NAME=s ist/X", "%CHANNELTYPE=s ist", "%COLUMN=2", "%[DATA]"]
ROWS = [f"{k * 3000};{k * 0.1:.6f};{k * 0.1:.6f};" for k in range(10)]


def _tnc(c="1", rows=ROWS):
    return "\r\n".join([line.format(c=c) for line in TNC] + rows) + "\r\n"


def _sinumerik(interval="0.002", last="0.02"):
    signals = ('<dataSignal id="f1" name="/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 1]" description="Position setpoint" '
               f'interval="{interval}"/><dataSignal id="f2" name="e [u1, 1]" description="Following error" '
               'interval="0.002"/>')
    recs = "".join(f'<rec time="{k * 0.002:.6f}" f1="{k * 0.1:.6f}" f2="0.001"/>' for k in range(10))
    return (f'<traceSession><traceData><dataFrame>{signals}{recs}<rec time="{last}"/></dataFrame></traceData>'
            "</traceSession>")


def _ticks(t_cell):
    rows = [f"{132959733843760000 + k * 10000}\t{k}.5\t{132959733843760000 + k * 10000}\t{k}.5" for k in range(10)]
    rows[4] = f"{t_cell}\t4.5\t{t_cell}\t4.5"
    return "\n".join(["Name\tt", "File\tx.csv", "", "Name\tcmd\tName\tact"] + rows) + "\n"


CASES = {
    "tnc_column_not_a_number.sco": (_tnc(c="a"), {}, r"%COLUMN='a' is not a column number"),
    "tnc_column_out_of_range.sco": (_tnc(c="9"), {}, r"%COLUMN=9 needs 10"),
    "tnc_no_rows.sco": (_tnc(rows=[]), {}, r"0 data row\(s\) after %\[DATA\]"),
    "sinumerik_infinite_interval.xml": (_sinumerik(interval="inf"), {}, r"interval > 0 \[s\]"),
    "sinumerik_far_time.xml": (_sinumerik(last="1e12"), {}, r"more than 1e\+08 samples"),
    "sinumerik_farthest_time.xml": (_sinumerik(last="1e308"), {}, r"more than 1e\+08 samples"),
    "twincat_tick_not_whole.csv": (_ticks("4.5"), {"columns": {"x_ref": "cmd", "x": "act"}},
                                   r"expected a FILETIME stamp"),
    "empty.csv": ("", {}, r"no rows of numbers"),
    # a cell of 1e307 m overflows to inf mm; 1e300 mm is finite but no machine's (squares overflow in the lag check)
    "overflow_in_m.csv": ("t,cmd,act\n" + "".join(f"{k * 0.001:.3f},{1e307 if k == 4 else k},{k}\n" for k in range(10)),
                          {"columns": {"t": "t", "x_ref": "cmd", "x": "act"}, "unit": "m"},
                          r"overflow_in_m.csv:6: 'cmd' \(m\) is inf mm in this row, beyond any machine's"),
    "far_position.csv": ("t,cmd,act\n" + "".join(f"{k * 0.001:.3f},{k},{1e300 if k == 2 else k}\n" for k in range(10)),
                         {"columns": {"t": "t", "x_ref": "cmd", "x": "act"}},
                         r"far_position.csv:4: 'act' \(mm\) is 1e\+300"),
    "far_capture.csv": ("t,x_ref,x\n" + "".join(f"{k * 0.001:.3f},{k},{-1e300 if k == 7 else k}\n" for k in range(10)),
                        {}, r"the measured position of axis x is -1e\+300 mm at sample 7"),
    "binary.dat": ("\x00\x01\x02MATLAB\x00" * 20, {}, r"binary file"),
}


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.filterwarnings("error::RuntimeWarning")  # no numpy warning on the way to the error either
def test_bad_input_is_a_clean_error(tmp_path, capsys, name):
    text, options, message = CASES[name]
    f = tmp_path / name
    f.write_bytes(text.encode("latin-1"))
    with pytest.raises(CaptureError, match=message) as exc:
        read_capture(f, **options)
    assert str(exc.value).count(str(f)) == 1  # named once: not an error wrapped in another
    out = tmp_path / "cap.csv"
    argv = ["convert", str(f), "-o", str(out)]
    if "columns" in options:
        argv += ["--columns", ",".join(f"{k}={v}" for k, v in options["columns"].items())]
    if "unit" in options:
        argv += ["--unit", options["unit"]]
    assert main(argv) == 2
    assert "error:" in capsys.readouterr().err and not out.exists() and list(tmp_path.glob(".cap.csv*")) == []


def test_missing_file_and_directory_exit_2(tmp_path, capsys):
    out = tmp_path / "cap.csv"
    for path in (tmp_path / "nope.csv", tmp_path):
        assert main(["convert", str(path), "-o", str(out)]) == 2
        assert "cannot read the file" in capsys.readouterr().err and not out.exists()


def test_logger_with_blank_lines_and_a_nan_cell(tmp_path):
    f = tmp_path / "log.csv"
    rows = [f"{k * 0.001:.3f},{k},{k}" for k in range(10)]
    f.write_text("t,cmd,act\n" + "\n".join(rows[:5] + [""] + rows[5:]) + "\n")
    assert len(read_capture(f, columns={"t": "t", "x_ref": "cmd", "x": "act"})) == 10
    f.write_text("t,cmd,act\n" + "\n".join(rows[:5] + ["0.005,nan,5"] + rows[6:]) + "\n")
    with pytest.raises(CaptureError, match=r"log.csv:7:2: not a number .*'nan'"):
        read_capture(f, columns={"t": "t", "x_ref": "cmd", "x": "act"})


def test_column_numbers_given_as_ints_in_python(tmp_path):
    # read_capture(f, columns={"t": 1, ...}) from Python: the numbers as the command line's "t=1" (it raised
    # AttributeError: 'int' object has no attribute 'isdigit')
    f = tmp_path / "log.txt"
    f.write_text("".join(f"{k}\t0\t{k * 0.01:.2f}\t{k * 0.01 - 0.001:.3f}\n" for k in range(10)))
    cap = read_capture(f, columns={"t": 1, "x_ref": 3, "x": 4}, time_unit="ms")
    assert len(cap) == 10 and cap.reference[3, 0] == pytest.approx(0.03) and cap.measured[3, 0] == pytest.approx(0.029)
    with pytest.raises(CaptureError, match="column '7' not found"):
        read_capture(f, columns={"t": 1, "x_ref": 7, "x": 4}, time_unit="ms")


def test_sinumerik_with_an_unknown_encoding(tmp_path):
    f = tmp_path / "trace.xml"
    f.write_text('<?xml version="1.0" encoding="utf1e400"?>\n' + _sinumerik())
    with pytest.raises(CaptureError, match=r"trace.xml:1: cannot decode the XML \(unknown encoding"):
        read_capture(f)


def test_sinumerik_trace_that_lost_records(tmp_path):
    f = tmp_path / "trace.xml"
    f.write_text(_sinumerik().replace("<dataFrame>", '<dataFrame><frameHeader dropOuts="3" stopInc="0.02"/>'))
    with pytest.raises(CaptureError, match=r"the trace lost records \(<frameHeader dropOuts='3'>\)"):
        read_capture(f)
    f.write_text(_sinumerik().replace("<dataFrame>", '<dataFrame><frameHeader dropOuts="0"/>'))
    assert len(read_capture(f)) == 11
