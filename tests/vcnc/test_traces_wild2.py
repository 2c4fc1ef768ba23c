"""Delimited traces in the layouts of drive tuning tools (tracewild2): a sampling period and a count size stated
above the table, sample-number columns, positions in increments, trailers after the data, and the drive tools'
channel names. Each file is a few lines written here after the tool's documented layout, not a real export."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError
from vcnc.traces import trace_format
from vcnc.traces.columns import unit_in_name
from vcnc.traces.names import columns_from_names, counted, is_sample_number
from vcnc.traces.preamble import stated_count_size, stated_period


def _motion(n: int = 300, dt: float = 1e-3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Time [s], commanded and measured position [mm] of a 2 Hz cosine move lagging by up to 20 um."""
    t = np.arange(n) * dt
    ref = 10.0 * (1 - np.cos(2 * np.pi * 2 * t))
    return t, ref, ref - 0.02 * np.sin(2 * np.pi * 2 * t)


@pytest.mark.parametrize(("line", "seconds"), [
    ("Sampling time: 0.5 ms", 5e-4),
    ("Sampling time;0,5;ms", 5e-4),  # a German export: the unit in its own cell, a decimal comma
    ('"Sampling Time","125.0us"', 125e-6),  # quoted cells
    ("Sample time [ms]: 1", 1e-3),  # the unit after the key
    ("Abtastzeit = 250 µs", 250e-6),
    ("Sampling rate: 2 kHz", 5e-4),
    ("Trace cycle: 4 ms", 4e-3),  # SINAMICS trace
    ("# sampling period = 0.001 s", 1e-3),
])
def test_stated_sampling_periods(line, seconds):
    found = stated_period(["Trace 1", line, ""])
    assert found is not None and found.value == pytest.approx(seconds, rel=1e-12)
    assert (found.line, found.text) == (2, line)


@pytest.mark.parametrize("lines", [
    ["Sampling time: 1"],  # no unit: nothing stated
    ["Device cycle: 1 ms"],  # the drive's cycle is not the trace's
    ["Sampling time: 1 ms", "Sampling time: 2 ms"],  # two that disagree
    ["Sampling time: 0.5 ms, trigger 3"],
])
def test_no_sampling_period_is_stated(lines):
    assert stated_period(lines) is None


@pytest.mark.parametrize(("line", "size"), [
    ("Resolution: 0.1 um", "0.1um"),
    ("Encoder resolution = 10000 inc/mm", "0.0001mm"),  # counts per length
    ("Count size: 0.0001 mm/inc", "0.0001mm"),
    ("Auflösung: 0,001 mm", "0.001mm"),
    ("Resolution = 0.001 mm/PUU", "0.001mm"),
])
def test_stated_count_sizes(line, size):
    found = stated_count_size([line])
    assert found is not None and (found.value, found.line) == (size, 1)


@pytest.mark.parametrize("line", ["Resolution: 16 bit", "Encoder resolution: 10000 counts/rev"])
def test_no_count_size_is_stated(line):
    assert stated_count_size([line]) is None


@pytest.mark.parametrize(("name", "unit"), [
    ("Position command (PUU)", "puu"),  # Delta ASDA
    ("r2665 EPOS position setpoint [LU]", "lu"),  # SINAMICS
    ("Cumulative feedback pulses", "pulses"),  # Mitsubishi, no unit in brackets
    ("Position Error [reference unit]", "reference unit"),  # Yaskawa
    ("Actual Position (counts)", "counts"),
    ("X Ist [mm]", None),
    ("Encoder count", None),  # a counter, not a position
])
def test_counted_names(name, unit):
    assert counted(name) == unit


@pytest.mark.parametrize(("name", "kind", "unit"), [
    ("Zeit in ms", "time", "ms"), ("Zeit/ms", "time", "ms"), ("time_us", "time", "us"), ("rel_time_s", "time", "s"),
    ("X Ist in mm", "length", "mm"), ("x_cmd_um", "length", "um"), ("Position in inch", "length", "in"),
    ("x_in", "length", None),  # an input, not inches
    ("x_fb", "length", None), ("speed_mm/min", "length", None),
])
def test_units_after_the_name(name, kind, unit):
    assert unit_in_name(name, kind) == unit


def test_counted_cjk_names():
    assert counted("溜りパルス") == "溜りパルス"  # Mitsubishi's droop pulses


@pytest.mark.parametrize(("name", "sample"), [
    ("Sample #", True), ("No.", True), ("Index", True), ("Nr.", True), ("Sample Number", True), ("#", True),
    ("Time", False), ("Sample time", False), ("X Soll", False),
])
def test_sample_number_names(name, sample):
    assert is_sample_number(name) is sample


@pytest.mark.parametrize(("header", "mapping"), [
    # Kollmorgen AKD WorkBench: PL. position loop; VL./IL. velocity and current loop (AKD User Guide) are not positions
    (["Time (ms)", "PL.CMD (mm)", "PL.FB (mm)", "VL.CMD (rpm)", "VL.FB"],
     {"t": "Time (ms)", "x_ref": "PL.CMD (mm)", "x": "PL.FB (mm)"}),
    # Rexroth IndraDrive IDNs: S-0-0047 position command value, S-0-0051 position feedback value 1
    (["Time [ms]", "S-0-0047 Position command value [mm]", "S-0-0051 Position feedback value 1 [mm]",
      "S-0-0189 Following distance [mm]"],
     {"t": "Time [ms]", "x_ref": "S-0-0047 Position command value [mm]",
      "x": "S-0-0051 Position feedback value 1 [mm]"}),
    # B&R ACOPOS position controller parameters
    (["Time[s]", "PCTRL_S_SET", "PCTRL_S_ACT", "PCTRL_LAG_ERROR"],
     {"t": "Time[s]", "x_ref": "PCTRL_S_SET", "x": "PCTRL_S_ACT"}),
    # Omron Sysmac axis variables: the velocities are not positions
    (["Time[ms]", "MC_Axis000.Cmd.Pos", "MC_Axis000.Act.Pos", "MC_Axis000.Cmd.Vel"],
     {"t": "Time[ms]", "x_ref": "MC_Axis000.Cmd.Pos", "x": "MC_Axis000.Act.Pos"}),
    # Aerotech's data collection signals
    (["Time", "PositionCommand", "PositionFeedback", "PositionError"],
     {"t": "Time", "x_ref": "PositionCommand", "x": "PositionFeedback"}),
    # Mitsubishi's cumulative pulses beside the droop pulses: the measured position is taken
    (["Time[ms]", "Motor speed[r/min]", "Cumulative command pulses[pulse]", "Cumulative feedback pulses[pulse]",
      "Droop pulses[pulse]"],
     {"t": "Time[ms]", "x_ref": "Cumulative command pulses[pulse]", "x": "Cumulative feedback pulses[pulse]"}),
    # the measured position named as its command without the command's word (HEBI logs: position, positionCmd)
    (["time", "position", "positionCmd", "velocity", "velocityCmd"],
     {"t": "time", "x_ref": "positionCmd", "x": "position"}),
    (["t", "X", "X Soll", "Y", "Y Soll"], {"t": "t", "x_ref": "X Soll", "x": "X", "y_ref": "Y Soll", "y": "Y"}),
    (["time", "x_cmd", "x_fb", "x"], {"t": "time", "x_ref": "x_cmd", "x": "x_fb"}),  # a named measurement first
    # units after the names without brackets: DIN 1313's 'Zeit/ms', 'Zeit in ms', and loggers' 'rel_time_s'
    (["Zeit in ms", "X Soll in mm", "X Ist in mm"], {"t": "Zeit in ms", "x_ref": "X Soll in mm", "x": "X Ist in mm"}),
    (["rel_time_s", "cmd_position", "actual_position"],
     {"t": "rel_time_s", "x_ref": "cmd_position", "x": "actual_position"}),
    (["Zeit/ms", "Soll/mm", "Ist/mm"], {"t": "Zeit/ms", "x_ref": "Soll/mm", "x": "Ist/mm"}),
    # Japanese and Chinese exports (MR Configurator2, MINAS, Chinese drive tools): compounds read by their parts
    (["時間[ms]", "指令位置[mm]", "フィードバック位置[mm]", "モータ速度[r/min]"],
     {"t": "時間[ms]", "x_ref": "指令位置[mm]", "x": "フィードバック位置[mm]"}),
    (["时间(ms)", "X轴指令位置(mm)", "X轴实际位置(mm)", "X轴速度"],
     {"t": "时间(ms)", "x_ref": "X轴指令位置(mm)", "x": "X轴实际位置(mm)"}),
])
def test_drive_tool_channel_names(header, mapping):
    assert columns_from_names(header) == (mapping, "")


def test_time_words_with_other_words_are_named_not_guessed():
    # a logger's two clocks (EPFL's EPOS telemetry: sensor_time and motor_time): the user picks one
    assert columns_from_names(["sensor_time [ms]", "motor_position [inc]", "motor_position_demand [inc]",
                               "motor_time [ms]"]) == (
        None, "no column is named as time (only names with more than time words: ['sensor_time [ms]', "
              "'motor_time [ms]']; give --columns t=NAME,...)")


def test_sample_numbers_or_no_time_column_with_a_known_period():
    # MEI Motion Scope's export starts with "Sample #"; halsampler and MTX recordings have no time column at all
    assert columns_from_names(["Sample #", "Ax 0 Cmd Pos", "Ax 0 Act Pos"], period_known=True) == (
        {"t": "Sample #", "x_ref": "Ax 0 Cmd Pos", "x": "Ax 0 Act Pos"}, "")
    assert columns_from_names(["X_SOLL", "X_IST"], period_known=True) == ({"x_ref": "X_SOLL", "x": "X_IST"}, "")
    assert columns_from_names(["No.", "Index", "x_cmd", "x_fb"], period_known=True) == (
        None, "several columns are named as sample numbers: ['No.', 'Index']")


def test_sinamics_trace_cycle_sample_numbers_and_length_units(tmp_path, capsys):
    # a trace cycle stated above a table of sample numbers and positions in LU, whose size --unit gives
    t, ref, act = _motion()
    f = tmp_path / "trace.csv"
    f.write_text("Trace: Trace_1\nTrace cycle: 1 ms\n\nSample;r2665 EPOS position setpoint [LU];"
                 "r2521[0] LR position actual value [LU]\n"
                 + "".join(f"{k + 1};{round(r * 1e3)};{round(a * 1e3)}\n" for k, (r, a) in enumerate(zip(ref, act))))
    with pytest.raises(CaptureError, match=r"trace.csv:4: x_ref='r2665 EPOS position setpoint \[LU\]' is logged in "
                                           r"increments \('lu'\) and the file does not state their size; expected "
                                           r"--unit with the size of one count"):
        read_capture(f)
    cap = read_capture(f, unit="1um")
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref * 1e3) * 1e-3, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act * 1e3) * 1e-3, atol=1e-12)
    assert cap.meta["time_unit"] == "sample numbers x 0.001 s"
    assert cap.meta["sampling"] == "0.001 s, stated in line 2 ('Trace cycle: 1 ms')"
    assert main(["convert", str(f), "--unit", "1um", "-o", str(tmp_path / "c.csv")]) == 0
    assert "  sampling: 0.001 s, stated in line 2 ('Trace cycle: 1 ms')\n" in capsys.readouterr().out


def test_delta_scope_period_and_resolution_stated(tmp_path):
    # the sampling time and the size of one PUU stated above a table numbered by "No.": read without options
    t, ref, act = _motion()
    f = tmp_path / "scope.csv"
    f.write_text("Sampling Time = 0.5 ms\nResolution = 0.001 mm/PUU\n"
                 "No.,Position command (PUU),Feedback position (PUU),Position error (PUU),Motor speed (r/min)\n"
                 + "".join(f"{k},{round(r * 1e3)},{round(a * 1e3)},0,0\n" for k, (r, a) in enumerate(zip(ref, act))))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.t, t / 2, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act * 1e3) * 1e-3, atol=1e-12)
    assert cap.meta["count_size"] == ("0.001mm per count for x_ref, x, stated in line 2 ('Resolution = 0.001 "
                                      "mm/PUU')")
    assert cap.meta["columns"] == ("from the header names: t=No., x_ref=Position command (PUU), x=Feedback position "
                                   "(PUU) (--columns, --time-unit, --unit set them)")


def test_counts_mapped_by_hand_still_need_their_size(tmp_path):
    # --columns naming a column in counts, without --unit: an error, not counts read as millimetres
    t, ref, act = _motion(20)
    f = tmp_path / "cme2.csv"
    f.write_text("Time (ms),Commanded Position (counts),Actual Position (counts)\n"
                 + "".join(f"{a * 1e3:.0f},{round(b * 1e3)},{round(c * 1e3)}\n" for a, b, c in zip(t, ref, act)))
    columns = {"t": "Time (ms)", "x_ref": "Commanded Position (counts)", "x": "Actual Position (counts)"}
    with pytest.raises(CaptureError, match=r"cme2.csv:1: x_ref='Commanded Position \(counts\)' is logged in "
                                           r"increments \('counts'\)"):
        read_capture(f, columns=columns)
    cap = read_capture(f, columns=columns, unit="0.001mm")
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref * 1e3) * 1e-3, atol=1e-12)


def test_a_units_row_of_increments_needs_their_size(tmp_path):
    t, ref, act = _motion(20)
    f = tmp_path / "units.csv"
    f.write_text("Zeit;Soll;Ist\nms;Inc;Inc\n"
                 + "".join(f"{a * 1e3:.0f};{round(b * 1e3)};{round(c * 1e3)}\n" for a, b, c in zip(t, ref, act)))
    with pytest.raises(CaptureError, match=r"x_ref='Soll' is logged in increments \('inc'\)"):
        read_capture(f, columns={"t": "Zeit", "x_ref": "Soll", "x": "Ist"})


def test_motion_scope_sample_numbers_need_the_period(tmp_path):
    t, ref, act = _motion()
    f = tmp_path / "Controller 0, Recorder 0.txt"
    f.write_text("Sample #\tAx 0 Cmd Pos\tAx 0 Act Pos\n"
                 + "".join(f"{k}\t{r * 1e3:.3f}\t{a * 1e3:.3f}\n" for k, (r, a) in enumerate(zip(ref, act))))
    with pytest.raises(CaptureError, match=r"no column is named as time \('Sample #' counts samples: give "
                                           r"--sample-time S, the sampling period\)"):
        read_capture(f)
    cap = read_capture(f, sample_time=1e-3, unit="um")
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act * 1e3, 3) * 1e-3, atol=1e-12)
    assert cap.meta["time_unit"] == "sample numbers x 0.001 s"


def test_time_unit_from_the_stated_period(tmp_path):
    # a time column without a unit whose step is the stated sampling time in ms: read as ms, and said
    t, ref, act = _motion()
    f = tmp_path / "log.csv"
    f.write_text("Sampling time: 1 ms\nTime,x_cmd,x_fb\n"
                 + "".join(f"{a * 1e3:.0f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    assert cap.meta["time_unit"] == "ms"
    assert cap.meta["time_unit_from_period"] == ("ms: the step of 'Time' is the sampling period stated in line 1 "
                                                 "('Sampling time: 1 ms')")


def test_speeds_and_torques_only_are_no_position_trace(tmp_path):
    f = tmp_path / "trace.csv"
    f.write_text('"Sampling Time","125.0us"\n"No.","Torque Reference [%]","Motor Speed [min-1]",'
                 '"Position Reference Speed [min-1]"\n' + "".join(f"{k},0,{k},{k}\n" for k in range(20)))
    # (tracewild3: the error leads with what the file is, not with a question of which columns to map)
    with pytest.raises(CaptureError, match=r"trace.csv:2: no position in the file: its columns \['No.', 'Torque "
                                           r"Reference \[%\]', 'Motor Speed \[min-1\]', 'Position Reference Speed "
                                           r"\[min-1\]'\] are time, sample numbers or other quantities \(speeds, "
                                           r"currents, voltages, torques... by their names or units\); vcnc identifies "
                                           r"a drive from a trace of its commanded and its measured position"):
        read_capture(f)


def test_a_trailer_after_the_data_is_skipped(tmp_path):
    # Rexroth MTX's recording ends with a [Statistics] section below its [Data] rows
    t, ref, act = _motion()
    f = tmp_path / "rec.txt"
    f.write_text("[Settings]\n[RECTIME]\nRECTIME: 1, AutoStop: 0\n[Data]\nX_SOLL X_IST\n"
                 + "".join(f"{b:.6f} {c:.6f}\n" for b, c in zip(ref, act))
                 + "[Statistics]\nNmbOfSamples 300\nLimitUsedBuffers 4\n")
    cap = read_capture(f, sample_time=1e-3)
    assert cap.t.size == 300
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 6), atol=1e-12)
    assert cap.meta["time_unit"] == "rows every 0.001 s"


def test_a_bad_row_below_the_data_is_named(tmp_path):
    # a row of the table's width, mostly numbers, below the data is a row with a bad cell, not a trailer
    t, ref, act = _motion(20)
    f = tmp_path / "log.csv"
    f.write_text("time,x_cmd,x_fb\n" + "".join(f"{a:.3f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, ref, act))
                 + "0.020,1.5,x\n")
    with pytest.raises(CaptureError, match=r"log.csv:22:3: not a number in column 3 \('x_fb', used as x\) "
                                           r"\(got 'x'\)"):
        read_capture(f)


def test_the_size_of_one_count_in_the_header(tmp_path):
    # a header giving the size of one count in brackets ("motor_pos [0.1 deg]", Mitsubishi's "B(1μm)")
    t, ref, act = _motion(20)
    f = tmp_path / "log.csv"
    f.write_text("time [ms];b_cmd [0.1 deg];b_act [0.1 deg]\n"
                 + "".join(f"{a * 1e3:.0f};{round(b * 10)};{round(c * 10)}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    assert cap.axes == ("b",)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref * 10) / 10, atol=1e-12)
    assert cap.meta["unit"] == "0.1deg"


@pytest.mark.parametrize(("names", "ending"), [("Time [s];X Soll [mm];X Ist [mm]", ";"),  # rows end with ';'
                                               ("Time [s];X Soll [mm];X Ist [mm];", "")])  # the names do
def test_a_delimiter_ending_the_rows_or_the_names(tmp_path, names, ending):
    t, ref, act = _motion(20)
    f = tmp_path / "log.csv"
    f.write_text(names + "\n" + "".join(f"{a:.3f};{b:.6f};{c:.6f}{ending}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 6), atol=1e-12)
    assert cap.meta["commanded"] == "x:X Soll [mm]"


def test_a_file_without_a_table_names_its_first_line(tmp_path):
    f = tmp_path / "notes.txt"
    f.write_text("Axis 1 moved to 19.5 at 15:05\nno trace recorded\n")
    with pytest.raises(CaptureError, match=r"notes.txt:1: no rows of numbers separated by tab, ';', ',', '\|' or "
                                           r"spaces \(got 'Axis 1 moved to 19.5 at 15:05'\)"):
        read_capture(f)


def _camonitor(path, dt_act: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An ecmc axis monitored with camonitor: PosSet and PosAct every 10 ms (PosAct ``dt_act`` s later)."""
    t, ref, act = _motion(60, dt=0.01)
    lines = []
    for a, b, c in zip(t, ref, act):
        for pv, when, v in (("IOC:Axis1-PosSet", a, b), ("IOC:Axis1-PosAct", a + dt_act, c)):
            sec = 40 + when
            lines.append(f"{pv} 2020-12-09 15:05:{sec:09.6f} {v:.8f}")
    lines[-1] += " HIHI MAJOR"  # an alarm status and severity after the value
    path.write_text("\n".join(lines) + "\n")
    return t, ref, act


def test_camonitor_log_of_an_ecmc_axis(tmp_path):
    f = tmp_path / "axis1.log"
    t, ref, act = _camonitor(f)
    assert trace_format(f) == "camonitor"
    cap = read_capture(f)  # time stamps every 10 ms to the microsecond: uniform
    np.testing.assert_allclose(cap.t, t, atol=1e-9)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 8), atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 8), atol=1e-12)
    assert cap.meta["columns"] == "from the PV names: x_ref=IOC:Axis1-PosSet, x=IOC:Axis1-PosAct"
    with pytest.raises(CaptureError, match="--sample-time applies to delimited text"):
        read_capture(f, sample_time=0.01)


def test_camonitor_updates_at_other_times_are_held_and_resampled(tmp_path):
    # PosAct reported 3 ms after PosSet: each PV holds its last value; the union of stamps is not uniform
    f = tmp_path / "axis1.log"
    t, ref, act = _camonitor(f, dt_act=0.003)
    with pytest.raises(CaptureError, match="sampling is not uniform.*--resample"):
        read_capture(f)
    cap = read_capture(f, resample=True)
    assert cap.meta["resampled"] == "linear, onto a 0.005 s step from 119 samples with steps of 0.003 to 0.007 s"
    np.testing.assert_allclose(cap.reference[::2, 0], np.round(ref, 8)[: cap.t[::2].size], atol=1e-12)


def test_camonitor_errors_name_the_line(tmp_path):
    f = tmp_path / "axis1.log"
    f.write_text("IOC:Axis1-PosSet 2020-12-09 15:05:40.300000 0\nIOC:Axis1-PosAct 2020-12-09 15:05:40.300000 0\n"
                 "IOC:Axis1-PosAct 2020-12-09 15:05:40.310000 <undefined>\n")
    with pytest.raises(CaptureError, match=r"axis1.log:3: the value of IOC:Axis1-PosAct is not a number "
                                           r"\(got '<undefined>'\)"):
        read_capture(f)
    f.write_text("IOC:A-PosAct 2020-12-09 15:05:40.3 0\nIOC:B-PosAct 2020-12-09 15:05:40.3 0\n")
    with pytest.raises(CaptureError, match=r"which PVs are the commanded and measured positions\? give --columns "
                                           r"x_ref=PV,x=PV; PVs found: \['IOC:A-PosAct', 'IOC:B-PosAct'\]"):
        read_capture(f)


def test_a_column_of_text_is_read_around(tmp_path):
    # the University of Michigan CNC mill data set (Kaggle "CNC Mill Tool Wear"): the machining step in words in
    # each row, no time column (sampled every 100 ms); text in a column mapped is an error naming it
    t, ref, act = _motion(20, dt=0.1)
    f = tmp_path / "experiment_01.csv"
    f.write_text("X_ActualPosition,X_ActualVelocity,X_SetPosition,X_CurrentFeedback,M_sequence_number,"
                 "Machining_Process\n"
                 + "".join(f"{c:.3f},0,{b:.3f},0.18,{k},{'Prep' if k < 5 else 'Layer 1 Up'}\n"
                           for k, (b, c) in enumerate(zip(ref, act))))
    cap = read_capture(f, sample_time=0.1)
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 3), atol=1e-12)
    assert cap.meta["commanded"] == "x:X_SetPosition"
    with pytest.raises(CaptureError, match=r"experiment_01.csv:2:6: not a number in column 6 \('Machining_Process', "
                                           r"used as x\) \(got 'Prep'\)"):
        read_capture(f, columns={"x_ref": "X_SetPosition", "x": "Machining_Process"}, sample_time=0.1)


def test_time_stamps_rounded_to_their_printed_digits(tmp_path):
    # MATLAB's %g prints five significant digits: the steps of 1/157 s differ by more than the timing check allows,
    # but every stamp is within the rounding of its last digit, so the step is uniform (a headerless EC-Master log)
    step = 1 / 157
    t, ref, act = _motion(200, dt=step)
    f = tmp_path / "test_trj.txt"
    f.write_text("".join(f"{a:.5g},{b:.5g},{c:.5g}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f, columns={"t": "1", "x_ref": "2", "x": "3"})
    np.testing.assert_allclose(np.diff(cap.t), step, rtol=1e-6)
    assert cap.meta["time_rounded"].startswith("time stamps printed to 5 digits, read as a uniform step of 0.006369")
    # a lost sample is no rounding: still the timing error naming it
    f.write_text("".join(f"{a:.5g},{b:.5g},{c:.5g}\n" for k, (a, b, c) in enumerate(zip(t, ref, act)) if k != 50))
    with pytest.raises(CaptureError, match=r"test_trj.txt:51: 1 sample\(s\) missing in 1 gap\(s\)"):
        read_capture(f, columns={"t": "1", "x_ref": "2", "x": "3"})


def test_a_headerless_file_names_no_line_zero(tmp_path):
    f = tmp_path / "gather.txt"
    f.write_text("".join(f"{k} {k}\n" for k in range(10)))
    with pytest.raises(CaptureError) as exc:
        read_capture(f)
    assert str(exc.value).startswith(f"{f}: which columns are time, commanded and measured position?")


def test_twincat_plc_variables_named_ambiguously_still_ask(tmp_path):
    # a TwinCAT Scope export of PLC variables: read from the names when they leave no doubt, else the question
    # with the reason (here two commanded candidates)
    def row(*cells):
        return "\t".join(cells)

    lines = ["Name\ttrace", "", row("Name", "MAIN.fSollPos", "Name", "MAIN.fSollPosFilt", "Name", "MAIN.fIstPos"),
             row("SampleTime[ms]", "1", "SampleTime[ms]", "1", "SampleTime[ms]", "1"), ""]
    lines += [row(*(f"{v:g}" for v in (k, k * 0.1, k, k * 0.1, k, k * 0.1))) for k in range(20)]
    f = tmp_path / "scope.csv"
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaptureError, match=r"channels found: \['MAIN.fSollPos', 'MAIN.fSollPosFilt', "
                                           r"'MAIN.fIstPos'\] \(not read from the names: axis x: several columns "
                                           r"could be the commanded position"):
        read_capture(f)


def test_halscope_pid_pins_read_from_their_names(tmp_path):
    # a PID tuning session scopes the pid component's command and feedback pins, not the joint's
    t, ref, act = _motion(50)
    f = tmp_path / "scope.log"
    f.write_text("# Sampling period is 1000000 ns\npid.x.command;pid.x.feedback;pid.x.output\n"
                 + "".join(f"{b:.14f};{c:.14f};0.5\n" for b, c in zip(ref, act)))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=1e-13)
    assert cap.meta["columns"] == "from the channel names: x_ref=pid.x.command, x=pid.x.feedback"
    f.write_text("# Sampling period is 1000000 ns\npid.x.command;pid.y.command;pid.x.output\n"
                 + "".join(f"{b:.14f};{c:.14f};0.5\n" for b, c in zip(ref, act)))
    with pytest.raises(CaptureError, match=r"channels found: \['pid.x.command', 'pid.y.command', 'pid.x.output'\] "
                                           r"\(not read from the names: no pair of a commanded and a measured "
                                           r"position is named \(positions found"):
        read_capture(f)


def test_names_grouped_under_merged_cells(tmp_path):
    # a spreadsheet's merged cells: the axis over its two columns, Soll/Ist repeated under it
    t, ref, act = _motion(20)
    f = tmp_path / "messung.csv"
    f.write_text("Messung 3\n;X;;Y;\nZeit [ms];Soll [mm];Ist [mm];Soll [mm];Ist [mm]\n"
                 + "".join(f"{a * 1e3:.0f};{b:.6f};{c:.6f};{b + 1:.6f};{c + 1:.6f}\n".replace(".", ",")
                           for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    assert cap.axes == ("x", "y")
    np.testing.assert_allclose(cap.measured[:, 1], np.round(act, 6) + 1, atol=1e-9)
    assert cap.meta["commanded"] == "x:X Soll [mm],y:Y Soll [mm]"
