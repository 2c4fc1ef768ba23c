"""Traces in the layouts seen in tracewild8: a SOMANET drive's recorder export (CiA 402 names, positions in increments,
a time stamp in microseconds with a logging master's jitter) and the same tool's parameter list, a SINUMERIK Operate
measuring-function file, CoDeSys V2.3's "Trace in ASCII-File" (its ``Cycle`` column), and KUKA RSI's orientation
angles. Each file is a few lines written here after a real export's layout or the tool's documentation, not the export
itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_SOMANET_NAMES = ("Timestamp [\u00b5s],Statusword,Position actual value [Inc],Position demand internal value [Inc],"
                  "Velocity actual value [RPM],Velocity demand value [RPM],Torque actual value [\u2030],"
                  "Torque demand [\u2030],Position following error [Inc],Velocity following error,"
                  "Torque following error [\u2030]\n")


def _somanet(stamps: list[int], demand: list[int], actual: list[int]) -> str:
    """Rows as the OBLAC recorder writes them: the master's time stamp in us, the statusword, actual before demand."""
    return _SOMANET_NAMES + "".join(
        f"{s},55,{a},{d},0,3,1,2,{d - a},3,1\n" for s, d, a in zip(stamps, demand, actual))


def test_somanet_recording_asks_for_the_size_of_an_increment(tmp_path):
    f = tmp_path / "Left.csv"
    f.write_text(_somanet([1000 * k for k in range(8)], [181516 + 10 * k for k in range(8)],
                          [181516 + 10 * max(k - 1, 0) for k in range(8)]), encoding="utf-8")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "x_ref='Position demand internal value [Inc]' is logged in increments ('inc')" in str(err.value)


def test_somanet_recording_reads_in_microseconds_and_the_unit_given(tmp_path):
    demand = [181516 + 10 * k for k in range(8)]
    actual = [181516 + 10 * max(k - 1, 0) for k in range(8)]
    f = tmp_path / "Left.csv"
    f.write_text(_somanet([1000 * k for k in range(8)], demand, actual), encoding="utf-8")
    cap = read_capture(f, unit="1um")
    assert cap.meta["commanded"] == "x:Position demand internal value [Inc]"
    assert cap.meta["measured"] == "x:Position actual value [Inc]"
    np.testing.assert_allclose(cap.t, np.arange(8) * 0.001, atol=1e-12)  # us, not s
    np.testing.assert_allclose(cap.reference[:, 0], np.array(demand) * 1e-3, atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(actual) * 1e-3, atol=1e-9)


def test_somanet_master_jitter_is_refused_until_resampled(tmp_path):
    stamps = [0, 1000, 2000, 3000, 4000, 5000, 6000, 7000, 8000, 9250, 10000, 11000]
    f = tmp_path / "Right.csv"
    f.write_text(_somanet(stamps, [100 * k for k in range(12)], [100 * k - 5 for k in range(12)]), encoding="utf-8")
    with pytest.raises(CaptureError) as err:
        read_capture(f, unit="1um")
    assert "sampling is not uniform: step 0.00125 s at t = 0.00925 s, expected 0.001 s" in str(err.value)
    cap = read_capture(f, unit="1um", resample=True)
    assert cap.t[1] == pytest.approx(0.001)
    assert cap.reference[9, 0] == pytest.approx(0.88)  # 9 ms, between 0.8 mm at 8 ms and 0.9 mm stamped 9.25 ms


def test_a_drives_parameter_list_is_no_recording(tmp_path):
    f = tmp_path / "LiftMotor.csv"
    entries = [f"0x20{i:02x}, {i % 4:2d}, {1000 + i}" for i in range(12)] + ["0x20f2,  0, LiftMotor"]
    f.write_text("META,FORMAT,2\n# STN-48\n# v5.1.0\n" + "\n".join(entries) + "\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert err.value.line == 4
    assert ("a drive's parameter list, not a recording: 13 lines of object index, subindex and value (line 4: "
            "'0x2000,  0, 1000') are settings, no samples over time") in str(err.value)


_SAT_HEAD = ('<?xml version="1.0" encoding="ISO-8859-1"?>\n<!-- 4.7.6.0.3 -->\n'
             '<ResponseTestCustom satclassid="174" ver="4.7.6.0.3" env="1">\n'
             '  <float name="m_dProcessUpdateTime">0.000125</float>\n</ResponseTestCustom>\n')


def test_sinumerik_measuring_function_file_is_named_as_no_trace(tmp_path):
    f = tmp_path / "freq_trace.XML"
    f.write_text(_SAT_HEAD, encoding="latin-1")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert str(err.value).endswith(
        "a SINUMERIK Operate measurement or auto servo tuning file (root <ResponseTestCustom>): a control loop's "
        "frequency or step response under its excitation, no commanded and measured position of a move; record the "
        "axis with SINUMERIK Operate's trace (Diagnostics > Trace) and save that as XML")


def test_other_xml_without_sat_classes_keeps_the_generic_message(tmp_path):
    f = tmp_path / "other.xml"
    f.write_text('<?xml version="1.0"?>\n<ResponseTestCustom ver="1"/>\n')
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "an XML file with root <ResponseTestCustom>, not a SINUMERIK trace" in str(err.value)


def _codesys(first: str, firsts: list[int], cmd: list[float], act: list[float]) -> str:
    """CoDeSys V2.3 'Trace in ASCII-File': title, project path, names, then values separated by a blank (CR LF)."""
    lines = ["CoDeSys Trace", "D:\\PROJEKTE\\PORTAL\\PORTAL.PRO", f"{first} Achse_X.fSetPosition Achse_X.fActPosition"]
    lines += [f"{c} {s:.4f} {a:.4f}" for c, s, a in zip(firsts, cmd, act)]
    return "\r\n".join(lines) + "\r\n"


def test_codesys_cycle_column_counts_samples(tmp_path):
    cmd = [0.5 * k for k in range(10)]
    act = [0.5 * max(k - 1, 0) for k in range(10)]
    f = tmp_path / "trace.txt"
    f.write_text(_codesys("Cycle", list(range(10)), cmd, act), newline="")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "('Cycle' counts samples: give --sample-time S, the sampling period)" in str(err.value)
    cap = read_capture(f, sample_time=0.004)
    assert cap.meta["commanded"] == "x:Achse_X.fSetPosition" and cap.meta["measured"] == "x:Achse_X.fActPosition"
    np.testing.assert_allclose(cap.t, np.arange(10) * 0.004, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], cmd, atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=1e-9)


def test_codesys_cycle_column_holding_milliseconds_is_no_sample_count(tmp_path):
    cmd = [0.5 * k for k in range(10)]
    f = tmp_path / "trace.txt"
    f.write_text(_codesys("Cycle", [4 * k for k in range(10)], cmd, cmd), newline="")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert str(err.value).endswith("; 'Cycle' steps by 4, not 1: a time rather than sample numbers? give --columns "
                                   "t=Cycle,... with --time-unit ms|us|s")
    with pytest.raises(CaptureError) as err:
        read_capture(f, sample_time=0.004)  # 4 x 4 ms would stretch the time four times
    assert err.value.line == 3
    assert ("the column 'Cycle', taken as sample numbers with the sampling period, steps by 4, not 1"
            in str(err.value))
    cap = read_capture(f, columns={"t": "Cycle", "x_ref": "Achse_X.fSetPosition", "x": "Achse_X.fActPosition"},
                       time_unit="ms")
    np.testing.assert_allclose(cap.t, np.arange(10) * 0.004, atol=1e-12)


def test_kuka_rsi_orientation_angles_are_left_out_and_named(tmp_path):
    names = "IPOC,X_RIst,Y_RIst,Z_RIst,A_RIst,B_RIst,C_RIst,X_RSol,Y_RSol,Z_RSol,A_RSol,B_RSol,C_RSol"
    rows = [f"{1000 + 4 * k},{1279.5 + 0.1 * max(k - 1, 0):.1f},200,977.3,80.4,60.3,116.8,"
            f"{1279.5 + 0.1 * k:.1f},200,977.3,80.5,60.3,116.8" for k in range(6)]
    f = tmp_path / "rsi.csv"
    f.write_text(names + "\n" + "\n".join(rows) + "\n")
    cap = read_capture(f)
    assert cap.axes == ("x", "y", "z")
    assert cap.reference[5, 0] == pytest.approx(1280.0) and cap.measured[5, 0] == pytest.approx(1279.9)
    assert cap.meta["columns"].endswith(
        "; left out ['A_RIst', 'B_RIst', 'C_RIst', 'A_RSol', 'B_RSol', 'C_RSol']: KUKA RSI's orientation angles of "
        "the tool (E6POS A about Z, B about Y, C about X), no axes")
    given = read_capture(f, columns={"t": "IPOC", "a_ref": "A_RSol", "a": "A_RIst"})  # the user's choice stands
    assert given.axes == ("a",) and given.reference[0, 0] == pytest.approx(80.5)


def test_an_ioc_log_with_ecmc_axis_diagnostics_points_to_camonitor(tmp_path):
    head = "2023/01/23 16:08:46.963 ecmc::  Ax     PosSet     PosAct     PosErr    PosTarg   DistLeft    CntrOut"
    rows = [f"2023/01/23 16:08:4{7 + k}.064 ecmc::   1     {49.9 * k:6.3f}     {49.9 * k:6.3f}      0.000      "
            "0.000      0.000      0.000" for k in range(2)]
    f = tmp_path / "log.log"
    f.write_text("#\n# Start at \"2023-W04\"\n#\niocshLoad ecmc.cmd\n" + head + "\n" + rows[0] + "\n"
                 "2023/01/23 16:08:47.904 Starting up EtherCAT bus: 1 second(s).\n" + rows[1] + "\n"
                 "2023/01/23 16:08:49.904 EtherCAT bus started!\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert err.value.line == 5
    assert ("an EPICS IOC's console log with ecmc's axis diagnostics (2 lines 'ecmc:: Ax PosSet PosAct PosErr ...' "
            "among its messages), no table of samples: log the axis' PosSet and PosAct records with camonitor"
            in str(err.value))


def test_an_indraworks_parameter_save_is_no_recording(tmp_path):
    f = tmp_path / "params.par"
    f.write_text("SERCOS-ASCII\n3/25/2019 2:45:05 PM\ndefault\nFWA-INDRV*-MPB-20V14\n1\n|\nS-0-0001\n"
                 "NC cycle time (TNcyc)\n01100000000100010000000000000001\nus\n250\n65000\n10000\n|\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert err.value.line == 1
    assert "a drive's parameter file, not a recording: 'SERCOS-ASCII' in line 1 begins Rexroth IndraWorks'" in str(
        err.value)


def test_a_twincat_scope_project_points_to_the_csv_export(tmp_path):
    f = tmp_path / "Phasing.tcscopex"
    f.write_text('\ufeff<?xml version="1.0" encoding="utf-8"?>\n<ScopeProject AssemblyName="TwinCAT.Measurement.'
                 'Scope.API.Model">\n  <Name>Phasing</Name>\n</ScopeProject>\n', encoding="utf-8")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert str(err.value).endswith(
        "a TwinCAT Scope project (root <ScopeProject>): the scope's configuration, its charts and channels; vcnc reads "
        "a recording exported to CSV (TwinCAT Scope: Export to csv, or TC3ScopeExportTool)")


def test_camonitor_binary_input_words_do_not_stop_the_positions(tmp_path):
    lines = ["IOC_TEST:ec0-s1-EL1004-BI1     2021-07-09 09:50:50.013168 One  "]
    for k in range(6):
        stamp = f"2021-07-09 10:29:40.{k * 10:02d}0000"
        lines += [f"IOC_TEST:Axis1-PosSet          {stamp} {10 + 0.5 * k:.4f}  ",
                  f"IOC_TEST:Axis1-PosAct          {stamp} {10 + 0.5 * max(k - 1, 0):.4f}  "]
    lines.append("IOC_TEST:ec0-s1-EL1004-BI1     2021-07-09 10:29:40.060000 Zero  ")
    f = tmp_path / "backlash_forward.log"
    f.write_text("\n".join(lines) + "\n")
    cap = read_capture(f)
    assert cap.meta["commanded"] == "x:IOC_TEST:Axis1-PosSet" and cap.meta["measured"] == "x:IOC_TEST:Axis1-PosAct"
    np.testing.assert_allclose(cap.reference[:, 0], [10 + 0.5 * k for k in range(6)], atol=1e-9)
    with pytest.raises(CaptureError) as err:
        read_capture(f, columns={"x_ref": "IOC_TEST:ec0-s1-EL1004-BI1", "x": "IOC_TEST:Axis1-PosAct"})
    assert err.value.line == 1
    assert "the value of IOC_TEST:ec0-s1-EL1004-BI1 is not a number (got 'One')" in str(err.value)


def test_a_numpy_archive_names_its_arrays(tmp_path):
    f = tmp_path / "veltest_run1.npz"
    np.savez(f, t=np.arange(4) * 0.001, cmd=np.zeros(4), pos=np.zeros(4))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "a NumPy archive (.npz) of the arrays ['t', 'cmd', 'pos']: save the time, commanded and measured" in str(
        err.value)


def test_an_excel_workbook_is_asked_as_csv(tmp_path):
    import zipfile

    f = tmp_path / "Recorded measurements.xlsx"
    with zipfile.ZipFile(f, "w") as z:
        z.writestr("[Content_Types].xml", "<Types/>")
        z.writestr("xl/workbook.xml", "<workbook/>")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "an Excel workbook (.xlsx): save the sheet that holds the trace as CSV, which vcnc reads" in str(err.value)


def test_one_row_of_numbers_in_a_printout_is_no_row_vector(tmp_path):
    f = tmp_path / "rampdown_pos.log"
    text = "".join(f"velo: 24.03{k}\npos: -738625.{k}\n" for k in range(12))
    f.write_text(text + "slopediffTime: [ 0.0597 0.0320 0.0757 0.0526]\n0.0597 0.0320 0.0757 0.0526\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "only one row of numbers (4 values) among 25 lines of text: no table of samples" in str(err.value)


def test_kuka_rsi_joint_positions_are_a_question_naming_them(tmp_path):
    f = tmp_path / "rsi_axes.csv"
    rows = [f"{1000 + 12 * k},{10 + 0.1 * max(k - 1, 0):.2f},{-90 + 0.2 * k:.2f},{10 + 0.1 * k:.2f},{-90 + 0.2 * k:.2f}"
            for k in range(6)]
    f.write_text("IPOC,A1_AIPos,A2_AIPos,A1_ASPos,A2_ASPos\n" + "\n".join(rows) + "\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert ("KUKA RSI axis-specific positions ASPos (setpoint) and AIPos (actual), joints ['A1', 'A2'], in deg: choose "
            "a joint and name it as a rotary axis, e.g. --columns a_ref=A1_ASPos,a=A1_AIPos") in str(err.value)
    cap = read_capture(f, columns={"t": "IPOC", "a_ref": "A1_ASPos", "a": "A1_AIPos"})
    assert cap.axes == ("a",) and cap.reference[5, 0] == pytest.approx(10.5) and cap.t[1] == pytest.approx(0.012)
