"""Traces in the layouts seen in tracewild6: ECP Executive's "Export Raw Data" (a MATLAB matrix literal under names
set apart by runs of spaces, positions in encoder counts), a PI controller's data recorder saved as a GCS array
(``# KEY = value`` header, no time column, no unit) and a TwinCAT 2 Scope View export; and of tracewild7, robot
controllers' logs: KUKA RSI's Cartesian ``RIst``/``RSol`` with its ``IPOC`` millisecond stamp beside a logging PC's
whole-second time stamp, and Universal Robots RTDE recordings (``target_q_N``/``actual_q_N`` joint positions in rad).
Each file is a few lines written here after a real export's layout or the tool's documentation, not the export
itself."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks import trace_fuzz
from vcnc.capture import read_capture
from vcnc.errors import CaptureError
from vcnc.traces.delimited import read_delimited
from vcnc.traces.gcsarray import gcs_array_header

_ECP_NAMES = " Sample   Time     Commanded Pos   Encoder 1 Pos   Encoder 2 Pos   Control Effort\n\n"


def _ecp_rows(cmd: list[int], enc1: list[int], enc2: list[int] | None = None) -> str:
    """Rows as ECP Executive writes them: ``[`` before the first, ``;`` after each but the last, ``]`` after it;
    sample number, time [s] to 3 decimals at 8.84 ms, positions in counts, the control effort last."""
    out = []
    for k, (c, e) in enumerate(zip(cmd, enc1)):
        cells = [f"{k:6d}", f"{k * 0.00884:8.3f}", f"{c:15d}", f"{e:15d}"]
        cells += [f"{enc2[k]:15d}"] if enc2 is not None else []
        cells.append(f"{0.25 - 0.001 * k:15.4f}")
        end = "]" if k == len(cmd) - 1 else ";"
        out.append(("[" if k == 0 else " ") + "".join(cells) + end + "\n")
    return "".join(out)


def _ecp_motion(n: int = 12) -> tuple[list[int], list[int]]:
    cmd = [min(100 * k, 600) for k in range(n)]
    return cmd, [max(c - 40, 0) for c in cmd]


def test_ecp_export_reads_its_names_rows_and_counts(tmp_path):
    cmd, enc = _ecp_motion()
    f = tmp_path / "closed_loop.csv"
    f.write_text(" Sample   Time     Commanded Pos   Encoder 1 Pos   Control Effort\n\n" + _ecp_rows(cmd, enc))
    with pytest.raises(CaptureError) as err:  # counts are never read as mm
        read_capture(f)
    assert ("closed_loop.csv:1: x='Encoder 1 Pos' is logged in increments ('counts') and the file does not state "
            "their size; expected --unit with the size of one count") in str(err.value)
    cap = read_capture(f, unit="0.005mm")
    assert cap.t.size == 12  # the first row, after '[', and the last, before ']', are read too
    assert cap.meta["commanded"] == "x:Commanded Pos" and cap.meta["measured"] == "x:Encoder 1 Pos"
    np.testing.assert_allclose(cap.reference[:, 0], np.array(cmd) * 0.005, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(enc) * 0.005, atol=1e-12)
    assert cap.t[-1] == pytest.approx(11 * 0.00884, abs=6e-4)  # three decimals printed: a uniform step within them


def test_ecp_export_with_two_encoders_asks_which(tmp_path):
    cmd, enc = _ecp_motion()
    f = tmp_path / "two.csv"
    f.write_text(_ECP_NAMES + _ecp_rows(cmd, enc, [e // 2 for e in enc]))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert ("columns found: ['Sample', 'Time', 'Commanded Pos', 'Encoder 1 Pos', 'Encoder 2 Pos', 'Control Effort'] "
            "(not read from the names: axis x: several columns could be the measured position: ['Encoder 1 Pos', "
            "'Encoder 2 Pos'])") in msg
    cap = read_capture(f, columns={"t": "Time", "x_ref": "Commanded Pos", "x": "Encoder 2 Pos"}, unit="1um")
    np.testing.assert_allclose(cap.measured[:, 0], np.array([e // 2 for e in enc]) * 1e-3, atol=1e-12)


def test_a_bracket_or_semicolon_elsewhere_is_no_matrix(tmp_path):
    # a ';'-separated log whose rows end with the delimiter stays a ';' table (no MATLAB matrix: no '[' opens it)
    f = tmp_path / "semi.csv"
    f.write_text("Zeit [s];Soll [mm];Ist [mm];\n" + "".join(f"{0.001 * k:.3f};{0.1 * k:.2f};{0.1 * k - 0.01:.3f};\n"
                                                           for k in range(20)))
    cap = read_capture(f)
    assert cap.meta["format"] == "delimited text (semicolon)"
    assert cap.reference[5, 0] == pytest.approx(0.5)


def _gcs(names: list[str], rows: list[list[float]], *, sep: str = " ", sample: str = "0.0005") -> str:
    head = ["# REM C-884.4DC", "#", "# TYPE = 1", f"# SEPARATOR = {ord(sep)}", f"# DIM = {len(names)}",
            f"# SAMPLE_TIME = {sample}", f"# NDATA = {len(rows)}", "#"]
    head += [f"# NAME{k} = {n}" for k, n in enumerate(names)] + ["#", "# END_HEADER"]
    return "\n".join(head + [sep.join(f"{v:.6f}" for v in r) for r in rows]) + "\n"


def test_gcs_array_header_is_read():
    text = _gcs(["Commanded Position of axis 1", "Actual Position of axis 1"], [[0.0, 0.0]] * 3)
    header = gcs_array_header(text)
    assert header is not None
    assert header.names == ["Commanded Position of axis 1", "Actual Position of axis 1"]
    assert (header.sample_time, header.sample_line, header.end_line, header.separator) == (0.0005, 6, 12, " ")
    assert gcs_array_header("# DIM = 2\n# NAME0 = a\n# END_HEADER\n1 2\n") is None  # NAME1 missing: not one
    assert gcs_array_header("time,x_ref,x\n0,0,0\n") is None


def test_gcs_array_asks_for_the_axis_unit_then_reads_on_its_sample_time(tmp_path):
    ref = [0.0, 0.0, 0.1, 0.3, 0.6, 0.8, 0.9, 1.0, 1.0, 1.0]
    act = [0.0, 0.0, 0.05, 0.2, 0.45, 0.7, 0.85, 0.95, 1.0, 1.0]
    f = tmp_path / "drr.dat"
    f.write_text(_gcs(["Commanded Position of axis 1", "Actual Position of axis 1"], [list(p) for p in zip(ref, act)]))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert ("drr.dat:12: the PI GCS array (data recorder tables ['Commanded Position of axis 1', 'Actual Position of "
            "axis 1']; read as x_ref=Commanded Position of axis 1, x=Actual Position of axis 1) does not state the "
            "axis' unit") in str(err.value)
    cap = read_capture(f, unit="um")
    np.testing.assert_allclose(cap.t, np.arange(10) * 0.0005, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], np.array(ref) * 1e-3, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(act) * 1e-3, atol=1e-12)
    assert cap.meta["format"] == "PI GCS array (data recorder)"
    assert cap.meta["sampling"] == "0.0005 s, stated in line 6 (SAMPLE_TIME)"


def test_gcs_array_tab_separated_with_a_position_error(tmp_path):
    # PIPython's documented example: SEPARATOR 9, "Real Position" before "Target Position"
    rows = [[0.01 * k - 0.001, 0.01 * k, 0.001] for k in range(8)]
    f = tmp_path / "testfile.dat"
    f.write_text(_gcs(["Real Position", "Target Position", "Position Error"], rows, sep="\t", sample="9.999999e-05"))
    cap = read_delimited(f, unit="mm")
    assert cap.meta["commanded"] == "x:Target Position" and cap.meta["measured"] == "x:Real Position"
    np.testing.assert_allclose(cap.measured[:, 0], [r[0] for r in rows], atol=1e-12)
    assert cap.t[1] == pytest.approx(9.999999e-05, rel=1e-9)
    with pytest.raises(CaptureError, match="--time-unit applies to a time column; a PI GCS array has none"):
        read_delimited(f, unit="mm", time_unit="ms")


def test_gcs_array_without_a_sample_time_asks_for_it(tmp_path):
    f = tmp_path / "nosample.dat"
    f.write_text(_gcs(["Target Position", "Real Position"], [[0.0, 0.0]] * 5, sample="?"))
    with pytest.raises(CaptureError) as err:
        read_capture(f, unit="mm")
    assert "does not state its SAMPLE_TIME as a number of seconds; expected --sample-time S" in str(err.value)
    cap = read_capture(f, unit="mm", sample_time=0.001)
    assert cap.meta["sampling"] == "0.001 s, given" and cap.t[-1] == pytest.approx(0.004)


def test_twincat2_scope_view_export_reads_as_twincat(tmp_path):
    # TcScope2 "Export to CSV" (Beckhoff infosys): a header block, the channel rows, then time [ms] and value per
    # channel, decimal comma
    head = ["Name\tScope01", "File\t", "StartRecord\t128783093223690000\tDonnerstag, 5. Februar 2009\t13:08:42",
            "EndRecord\t128783093339880000\tDonnerstag, 5. Februar 2009\t13:08:53", ""]
    keys = [("Name", "Axis_X.NcToPlc.SetPos", "Axis_X.NcToPlc.ActPos"), ("SampleTime[ms]", "1", "1"),
            ("SymbolName", "Axis_X.NcToPlc.SetPos", "Axis_X.NcToPlc.ActPos"),
            ("Data-Type", "ADST_REAL64", "ADST_REAL64")]
    head += [f"{k}\t{a}\t{k}\t{b}" for k, a, b in keys]
    rows = [f"{k}\t{0.5 * k:.1f}\t{k}\t{0.5 * k - 0.1:.1f}".replace(".", ",") for k in range(10)]
    f = tmp_path / "scope2.csv"
    f.write_text("\n".join(head + rows) + "\n")
    cap = read_capture(f)
    assert cap.meta["format"] == "TwinCAT Scope CSV"
    np.testing.assert_allclose(cap.t, np.arange(10) * 1e-3, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], 0.5 * np.arange(10) - 0.1, atol=1e-12)


def test_nc_axes_are_named_by_the_letter_their_names_carry(tmp_path):
    # an NC axis a machine calls Y is axis y (before: x, the first pair); without a letter (MAIN.Axis1) x, y... stay
    head = ["Name\tY.NcToPlc.SetPos\tName\tY.NcToPlc.PosDiff\tName\tAxis_Z.NcToPlc.SetPos\tName\tAxis_Z.NcToPlc.ActPos"]
    rows = [f"{k}\t{0.5 * k}\t{k}\t0.1\t{k}\t{-0.2 * k}\t{k}\t{-0.2 * k + 0.05}" for k in range(12)]
    f = tmp_path / "yz.csv"
    f.write_text("\n".join(head + rows) + "\n")
    cap = read_capture(f)
    assert cap.axes == ("y", "z")
    assert cap.meta["commanded"] == "y:Y.NcToPlc.SetPos,z:Axis_Z.NcToPlc.SetPos"
    np.testing.assert_allclose(cap.measured[:, 0], 0.5 * np.arange(12) - 0.1, atol=1e-12)  # set - lag
    np.testing.assert_allclose(cap.measured[:, 1], -0.2 * np.arange(12) + 0.05, atol=1e-12)
    g = tmp_path / "main.csv"
    g.write_text("Name\tMAIN.Axis1.NcToPlc.SetPos\tName\tMAIN.Axis1.NcToPlc.ActPos\n"
                 + "".join(f"{k}\t{0.1 * k}\t{k}\t{0.1 * k - 0.01}\n" for k in range(12)))
    assert read_capture(g).axes == ("x",)
    # a letter with a number names no axis: MAIN.A1 is often "Achse 1" (axis 1), not a rotary A in deg (review29)
    h = tmp_path / "a1.csv"
    h.write_text("Name\tMAIN.A1.NcToPlc.SetPos\tName\tMAIN.A1.NcToPlc.ActPos\n"
                 + "".join(f"{k}\t{0.1 * k}\t{k}\t{0.1 * k - 0.01}\n" for k in range(12)))
    assert read_capture(h).axes == ("x",)


def test_gcs_array_of_two_axes_asks_which_without_a_time_column(tmp_path):
    names = ["Commanded Position of axis 1", "Actual Position of axis 1", "Commanded Position of axis 2",
             "Actual Position of axis 2"]
    f = tmp_path / "two.dat"
    f.write_text(_gcs(names, [[0.1 * k, 0.1 * k - 0.01, -0.2 * k, -0.2 * k + 0.02] for k in range(10)]))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert ("two.dat:14: which tables of the PI GCS array are the commanded and measured positions? give --columns "
            "x_ref=NAME,x=NAME (SAMPLE_TIME times its rows); tables: ['Commanded Position of axis 1', 'Actual Position "
            "of axis 1', 'Commanded Position of axis 2', 'Actual Position of axis 2'] (not read from the names: axes "
            "[1, 2] each have a commanded and a measured position") in str(err.value)
    cap = read_capture(f, columns={"y_ref": names[2], "y": names[3]}, unit="mm")
    assert cap.axes == ("y",)
    np.testing.assert_allclose(cap.measured[:, 0], -0.2 * np.arange(10) + 0.02, atol=1e-12)


def _rsi_rows(n: int, *, pc_stamp: bool) -> tuple[str, list[float], list[float]]:
    """A KUKA RSI log as a UDP logger writes it: the PC's time stamp to the second (when ``pc_stamp``), the Cartesian
    actual (``RIst``) and setpoint (``RSol``) X..C, the controller's ``IPOC`` counting ms in steps of 12 (IPO mode)."""
    sol = [192.2 - 0.1 * max(k - 2, 0) for k in range(n)]
    ist = [192.4 - 0.1 * max(k - 3, 0) for k in range(n)]
    names = ["X_RIst", "Y_RIst", "A_RIst", "X_RSol", "Y_RSol", "A_RSol", "Delay", "IPOC"]
    rows = [",".join((["2024-09-24 14:05:15"] if pc_stamp else []) + [
        "1279.5", f"{ist[k]:.1f}", "80.4", "1279.5", f"{sol[k]:.1f}", "80.5", "0", str(1210441551 + 12 * k)])
        for k in range(n)]
    return ",".join((["Timestamp"] if pc_stamp else []) + names) + "\n" + "\n".join(rows) + "\n", sol, ist


def test_kuka_rsi_log_reads_ist_and_sol_on_the_controllers_ipoc_clock(tmp_path):
    text, sol, ist = _rsi_rows(12, pc_stamp=True)
    f = tmp_path / "robot_data.csv"
    f.write_text(text)
    cap = read_capture(f)  # IPOC, not the PC's whole seconds (12 rows in one second), is the time
    assert cap.axes == ("x", "y")  # A_RIst/A_RSol: the tool's orientation angle, no axis (tracewild8)
    assert cap.meta["commanded"] == "x:X_RSol,y:Y_RSol"
    assert cap.meta["measured"] == "x:X_RIst,y:Y_RIst"
    assert cap.meta["columns"].startswith("from the header names: t=IPOC, x_ref=X_RSol, x=X_RIst")
    assert "left out ['A_RIst', 'A_RSol']: KUKA RSI's orientation angles of the tool" in cap.meta["columns"]
    assert cap.meta["time_unit"] == "ms"
    np.testing.assert_allclose(cap.t, np.arange(12) * 0.012, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 1], sol, atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 1], ist, atol=1e-9)


def test_kuka_rsi_ipoc_given_as_the_time_column_counts_milliseconds(tmp_path):
    text, sol, _ = _rsi_rows(6, pc_stamp=False)
    f = tmp_path / "rsi.csv"
    f.write_text(text)
    cap = read_capture(f, columns={"t": "IPOC", "y_ref": "Y_RSol", "y": "Y_RIst"})
    assert cap.t[1] == pytest.approx(0.012)  # not 12 s
    np.testing.assert_allclose(cap.reference[:, 0], sol, atol=1e-9)


def _rtde(names: list[str], rows: list[list[float]]) -> str:
    """UR's RTDE ``record.py`` (``rtde/csv_writer.py``): names and values separated by one space."""
    return " ".join(names) + "\n" + "".join(" ".join(repr(v) for v in r) + "\n" for r in rows)


@pytest.mark.parametrize("q, t0, start, step, unit, scale, message", [
    ("q", 1234.5, 0.5, 0.01, "rad", 180.0 / np.pi,
     "(not read from the names: Universal Robots RTDE joint positions target_q_N (commanded) and actual_q_N "
     "(measured), joints [0], in rad: choose a joint and name it as a rotary axis, e.g. --columns "
     "t=timestamp,a_ref=target_q_0,a=actual_q_0 --unit rad)"),
    ("TCP_pose", 0.0, -0.58, 0.001, "m", 1000.0,
     "Universal Robots RTDE tool (TCP) pose target_TCP_pose_N (commanded) and actual_TCP_pose_N (measured): "
     "N = 0, 1, 2 are x, y, z in m (3-5 a rotation vector), e.g. --columns "
     "t=timestamp,x_ref=target_TCP_pose_0,x=actual_TCP_pose_0 --unit m"),
], ids=["joint_rad", "tcp_m"])
def test_ur_rtde_positions_are_a_question_never_millimetres(tmp_path, q, t0, start, step, unit, scale, message):
    # joint positions in rad (a rotary axis), the tool pose in m: neither is read as mm from the names
    target = [start + step * k for k in range(8)]
    actual = [start + step * max(k - 1, 0) for k in range(8)]
    f = tmp_path / "robot_data.csv"
    f.write_text(_rtde(["timestamp", f"target_{q}_0", f"actual_{q}_0"],
                       [[t0 + 0.008 * k, target[k], actual[k]] for k in range(8)]))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert message in str(err.value)
    ax = "a" if unit == "rad" else "x"
    cap = read_capture(f, columns={"t": "timestamp", f"{ax}_ref": f"target_{q}_0", ax: f"actual_{q}_0"}, unit=unit)
    np.testing.assert_allclose(cap.reference[:, 0], np.multiply(target, scale), atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], np.multiply(actual, scale), atol=1e-9)
    np.testing.assert_allclose(cap.t, np.arange(8) * 0.008, atol=1e-9)
    if unit == "m":
        assert cap.reference[5, 0] == pytest.approx(-575.0) and cap.measured[5, 0] == pytest.approx(-576.0)


def test_ur_rtde_question_comes_before_a_repeated_name(tmp_path):
    # a recipe listing target_current twice writes its columns twice; the joints' question is the useful one
    names = ["timestamp"] + [f"actual_q_{i}" for i in range(2)] + ["target_current_0", "target_current_0"] + [
        f"target_q_{i}" for i in range(2)]
    f = tmp_path / "gui.csv"
    f.write_text(",".join(names) + "\n" + "".join(f"{0.008 * k},1.3,-1.5,0.0,0.0,1.3,-1.5\n" for k in range(4)))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "joints [0, 1], in rad" in str(err.value) and "repeats a name" not in str(err.value)


def test_digits_grouped_by_thousands_are_refused_naming_the_cell(tmp_path):
    # a spreadsheet's "#,##0.00" re-save: with a tab no number reads at all, quoted in a ';' file the cell is text
    f = tmp_path / "grouped.txt"
    f.write_text("Time [s]\tX Soll [mm]\tX Ist [mm]\n" + "".join(f"0.00{k}\t4,263.{60 + k}\t4,263.{50 + k}\n"
                                                             for k in range(4)))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert ("grouped.txt:1: no rows of numbers separated by tab, ';', ',', '|' or spaces: '4,263.60' (line 2) "
            "writes its digits grouped by thousands (a spreadsheet's number format); vcnc reads no digit grouping: "
            "save the numbers without thousands separators") in str(err.value)
    g = tmp_path / "quoted.csv"
    g.write_text('Time [s];X Soll [mm];X Ist [mm]\n0.000;"1.263,66";1263.60\n0.001;999.76;998.70\n'
                 '0.002;1000.5;999.80\n')
    with pytest.raises(CaptureError) as err:
        read_capture(g)
    assert ("quoted.csv:2:2: not a number in column 2 ('X Soll [mm]', used as x_ref): '1.263,66' writes its digits "
            "grouped by thousands") in str(err.value)


def test_ur_rtde_actual_positions_alone_say_the_command_is_missing(tmp_path):
    f = tmp_path / "actual.csv"
    f.write_text(_rtde([f"actual_q_{i}" for i in range(3)] + ["actual_TCP_pose_0"],
                       [[-1.6007, -1.7271, -2.203, -0.144]] * 4))
    with pytest.raises(CaptureError) as err:
        read_capture(f, sample_time=0.008)
    assert ("Universal Robots RTDE joint positions actual_q_N only (N = [0, 1, 2]), no target_q_N: identification "
            "needs the commanded and the measured position (record both target_q and actual_q)") in str(err.value)


def test_counts_under_a_stated_resolution_with_three_decimals_are_grouped_not_fractions(tmp_path):
    # trace_fuzz seeds 31000532 / 31001005 (the lead's): a German drive export, tab, decimal comma, '.' grouping
    # thousands, a stated resolution and --unit given; 19.725 counts was read silently (a thousand times too small)
    f = tmp_path / "drive.txt"
    f.write_text("Resolution: 0.5 um\nAbtastzeit: 125 us\nXPosCmd\tXPosLag\t\n"
                 + "".join(f"{19.725 - 0.071 * k:.3f}\t{-71 * k}\t\n" for k in range(8)))
    with pytest.raises(CaptureError) as err:
        read_capture(f, unit="0.5um")
    assert ("drive.txt:4: x_ref='XPosCmd': '19.725' beside counts (line 1 states 'Resolution: 0.5 um') reads as "
            "digits grouped by thousands as well as a decimal; vcnc reads no digit grouping") in str(err.value)
    g = tmp_path / "plain.txt"  # the same counts written whole read as counts of 0.5 um
    g.write_text("Resolution: 0.5 um\nAbtastzeit: 125 us\nXPosCmd\tXPosLag\t\n"
                 + "".join(f"{19725 - 71 * k}\t{-71 * k}\t\n" for k in range(8)))
    cap = read_capture(g, unit="0.5um")
    assert cap.reference[1, 0] == pytest.approx(19654 * 0.5e-3) and cap.t[1] == pytest.approx(125e-6)
    cap = read_capture(f, unit="mm")  # a plain unit given: the user says these are mm, not counts
    assert cap.reference[1, 0] == pytest.approx(19.654)


def test_fuzz_dump_creates_its_folder(tmp_path, capsys):
    out = tmp_path / "new" / "folder"
    assert trace_fuzz.main(["--dump", "7", "--out", str(out)]) == 0
    assert (out / "fuzz_7.csv").is_file() and str(out / "fuzz_7.csv") in capsys.readouterr().out


def test_a_stated_resolution_leaves_columns_in_mm_with_three_decimals_read(tmp_path):
    # a drive tool states its encoder's resolution above columns it names in mm: 19.725 there is 19.725 mm, not a
    # count grouped by thousands (refused as such after tracewild7; read before it)
    f = tmp_path / "mm.txt"
    f.write_text("Resolution: 0.5 um\nTime [s]\tX Soll [mm]\tX Ist [mm]\n"
                 + "".join(f"{0.001 * k:.3f}\t{19.725 + 0.013 * k:.3f}\t{19.720 + 0.013 * k:.3f}\n" for k in range(8)))
    cap = read_capture(f)
    assert cap.reference[1, 0] == pytest.approx(19.738) and cap.measured[1, 0] == pytest.approx(19.733)
    with pytest.raises(CaptureError, match="'19.725' beside counts"):  # the user says they are counts of 0.5 um
        read_capture(f, unit="0.5um")
