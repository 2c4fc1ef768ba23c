"""Delimited traces without ``--columns``: the mapping read from the header names (vcnc.traces.names)."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError
from vcnc.traces.names import columns_from_names


@pytest.mark.parametrize(("header", "mapping"), [
    (["Zeit [ms]", "X Sollposition [mm]", "X Istposition [mm]"],
     {"t": "Zeit [ms]", "x_ref": "X Sollposition [mm]", "x": "X Istposition [mm]"}),
    (["Time", "Axis X Position Command", "Axis X Actual Position"],
     {"t": "Time", "x_ref": "Axis X Position Command", "x": "Axis X Actual Position"}),
    (["time", "x_cmd", "x_fb", "y_cmd", "y_fb"], {"t": "time", "x_ref": "x_cmd", "x": "x_fb", "y_ref": "y_cmd",
                                                  "y": "y_fb"}),
    (["t", "PosCmd", "PosAct"], {"t": "t", "x_ref": "PosCmd", "x": "PosAct"}),  # one unnamed axis: x
    (["timestamp", "xcmd", "xact"], {"t": "timestamp", "x_ref": "xcmd", "x": "xact"}),  # axis glued to the role
    (["Zeit", "Z Lagesollwert", "Z Lageistwert"], {"t": "Zeit", "z_ref": "Z Lagesollwert", "z": "Z Lageistwert"}),
    (["time", "X_command", "X_following_error"], {"t": "time", "x_ref": "X_command", "x_lag": "X_following_error"}),
    # a measured position and a lag of the same axis: the measurement is taken (as TwinCAT's ActPos over PosDiff)
    (["Time", "X set", "X actual", "X lag"], {"t": "Time", "x_ref": "X set", "x": "X actual"}),
    # velocities, currents and columns with a unit that is not a length are not positions
    (["Time [s]", "X Soll [mm]", "X Ist [mm]", "X Drehzahlsollwert", "X Soll [mm/min]", "X current cmd [A]"],
     {"t": "Time [s]", "x_ref": "X Soll [mm]", "x": "X Ist [mm]"}),
    # positions in counts are positions (the reader asks for their size)
    (["time", "x_cmd [counts]", "x_fb [counts]"], {"t": "time", "x_ref": "x_cmd [counts]", "x": "x_fb [counts]"}),
    # an axis with only a commanded position is left out
    (["time", "x_cmd", "x_fb", "c_cmd"], {"t": "time", "x_ref": "x_cmd", "x": "x_fb"}),
])
def test_mapping_read_from_names(header, mapping):
    assert columns_from_names(header) == (mapping, "")


@pytest.mark.parametrize(("header", "why"), [
    (["Zeit", "Soll 1", "Ist 1", "Soll 2", "Ist 2"],
     "axis x: several columns could be the commanded position: ['Soll 1', 'Soll 2']"),
    (["time", "x_cmd", "x_cmd_filtered", "x_fb"],
     "axis x: several columns could be the commanded position: ['x_cmd', 'x_cmd_filtered']"),
    (["t", "time", "x_cmd", "x_fb"], "several columns are named as time: ['t', 'time']"),
    (["x_cmd", "x_fb"], "no column is named as time (a file without one needs --sample-time S, the sampling period)"),
    (["Sample #", "x_cmd", "x_fb"], "no column is named as time ('Sample #' counts samples: give --sample-time S, "
                                    "the sampling period)"),
    (["time", "channel 1", "channel 2"], "no pair of a commanded and a measured position is named"),
    # a trace of speeds and currents only (Yaskawa's and Kollmorgen's velocity/current loop channels)
    (["time", "current [A]", "speed [rpm]", "VL.CMD"], "no pair of a commanded and a measured position is named "
     "(other quantities: ['current [A]', 'speed [rpm]', 'VL.CMD']); a position trace needs a commanded and a measured "
     "position"),
    (["time", "x_cmd [mm]", "x_speed"], "no pair of a commanded and a measured position is named (positions found: "
     "['x_cmd [mm]']; other quantities: ['x_speed'])"),
    (["time", "x_cmd", "x_cmd"], "the header repeats a name"),
])
def test_ambiguous_or_unnamed_headers_are_not_guessed(header, why):
    assert columns_from_names(header) == (None, why)


def _rows(n: int = 400, dt: float = 1e-3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t = np.arange(n) * dt
    ref = 10.0 * (1 - np.cos(2 * np.pi * t))
    return t, ref, ref - 0.002 * np.sin(2 * np.pi * t)


def test_commented_header_and_following_error(tmp_path):
    # a header behind '#' (numpy.savetxt, gnuplot) with units in parentheses, and a following error column
    t, ref, act = _rows()
    f = tmp_path / "trace.txt"
    np.savetxt(f, np.column_stack([t, ref * 1e3, (ref - act) * 1e3]), fmt="%.6f",
               header="time(s) x_cmd(um) x_following_error(um)")
    cap = read_capture(f)
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], ref, atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=2e-9)
    assert cap.meta["columns"] == ("from the header names: t=time(s), x_ref=x_cmd(um), x_lag=x_following_error(um) "
                                   "(--columns, --time-unit, --unit set them)")


def test_assumed_units_are_said(tmp_path):
    # nothing states the units: seconds and millimetres (degrees on a rotary axis) are assumed, and said
    t, ref, act = _rows()
    f = tmp_path / "log.csv"
    f.write_text("time,b_cmd,b_act\n" + "".join(f"{a:.4f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    assert cap.axes == ("b",)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 6), atol=1e-12)
    assert cap.meta["columns"].endswith("not stated in the file, assumed t in s, b_ref in deg, b in deg "
                                        "(--columns, --time-unit, --unit set them)")


def test_unreadable_header_asks_for_the_mapping_and_says_why(tmp_path):
    t, ref, act = _rows()
    f = tmp_path / "two.csv"
    f.write_text("Zeit [ms];Soll 1;Ist 1;Soll 2;Ist 2\n"
                 + "".join(f"{a * 1e3:.0f};{b:.6f};{c:.6f};{b:.6f};{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    with pytest.raises(CaptureError, match="give --columns t=NAME,x_ref=NAME,x=NAME; columns found: .*\\(not read "
                                           "from the names: axis x: several columns could be the commanded position"):
        read_capture(f)
    cap = read_capture(f, columns={"t": "Zeit [ms]", "x_ref": "Soll 2", "x": "Ist 2"})
    np.testing.assert_allclose(cap.t, t, atol=1e-12)


def test_convert_says_which_columns_it_read_from_the_names(tmp_path, capsys):
    t, ref, act = _rows()
    f, out = tmp_path / "log.tsv", tmp_path / "capture.csv"
    f.write_text("Time [ms]\tX Soll [mm]\tX Ist [mm]\tX Geschwindigkeit [mm/min]\n"
                 + "".join(f"{a * 1e3:.1f}\t{b:.6f}\t{c:.6f}\t0\n" for a, b, c in zip(t, ref, act)))
    assert main(["convert", str(f), "-o", str(out)]) == 0
    assert ("  columns: from the header names: t=Time [ms], x_ref=X Soll [mm], x=X Ist [mm] (--columns, --time-unit, "
            "--unit set them)\n") in capsys.readouterr().out
    np.testing.assert_allclose(read_capture(out).measured[:, 0], np.round(act, 6), atol=1e-9)


def test_a_row_of_numbers_behind_a_comment_mark_is_no_header(tmp_path):
    # '#' before a header is a comment mark, but a commented-out row amid the numbers stays an error naming it
    t, ref, act = _rows(20)
    rows = [f"{a:.3f},{b:.6f},{c:.6f}" for a, b, c in zip(t, ref, act)]
    rows[10] = "#" + rows[10]
    f = tmp_path / "log.csv"
    f.write_text("# time,x_cmd,x_fb\n" + "\n".join(rows) + "\n")
    with pytest.raises(CaptureError, match=":12:1: not a number in column 1 \\('time', used as t\\) "
                                           "\\(got '#0.010'\\)"):
        read_capture(f)
