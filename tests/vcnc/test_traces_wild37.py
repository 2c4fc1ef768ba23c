"""Traces in layouts of tracewild37 (session 37): drive tools' channel names and units not read before, and the
fuzzer's cases (``benchmarks/trace_fuzz.py``, seeds 41-43). Each file is a few lines written here after the layout,
not an export itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_SET = [0.0, 100.0, 300.0, 600.0, 900.0, 1100.0]
_ACT = [0.0, 40.0, 200.0, 480.0, 790.0, 1020.0]


def _table(path, names, *, sep=",", step=1.0):
    rows = [sep.join([f"{k * step:g}", f"{s:g}", f"{a:g}"]) for k, (s, a) in enumerate(zip(_SET, _ACT))]
    path.write_text("\n".join([sep.join(names), *rows]) + "\n", encoding="utf-8")
    return path


def test_acopos_user_units_are_counts_of_a_size_given(tmp_path):
    """B&R ACOPOS drives trace their position setpoint and actual position (ParIDs ``PCTRL_S_SET``,
    ``PCTRL_S_ACT``) in the axis' user ``Units``, whose size the axis' scaling sets: ``[Units]`` asks for ``--unit``
    with the size of one unit, as ``[LU]`` and ``[reference units]`` do (it said no column was a position)."""
    f = _table(tmp_path / "acopos.csv", ["Time [ms]", "PCTRL_S_SET [Units]", "PCTRL_S_ACT [Units]"])
    with pytest.raises(CaptureError, match=r"increments \('units'\).*--unit") as err:
        read_capture(f)
    assert str(f) in str(err.value)
    cap = read_capture(f, unit="0.01mm")
    assert cap.axes == ("x",)
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 0.01)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 0.01)


def test_spaced_table_with_left_aligned_index_and_blank_end_cells(tmp_path):
    """A recorder printing ``%-6d`` sample numbers (left-aligned) beside ``%9.3f`` positions (right-aligned) leaves
    the commanded position's cell blank before its first sample: each column is aligned at one of its edges, and
    the blank cell is a missing value, its row skipped (trace_fuzz seeds 41000762 and 41000969 were refused as
    'only one row of numbers': the rule of tracewild10 wanted every column aligned at the same edge)."""
    rows = ["# Sample time: 1 ms", f"{'Index':<6}{'x_cmd':>9}{'x_fb':>9}", f"{8:<6}{'':>9}{_ACT[0]:>9.3f}"]
    rows += [f"{k + 8:<6}{s:>9.3f}{a:>9.3f}" for k, (s, a) in enumerate(zip(_SET, _ACT)) if k]
    rows += [f"{len(_SET) + 8:<6}{'':>9}{1100.0:>9.3f}"]  # numbers 8 to 14: index cells end at two places
    f = tmp_path / "printed.txt"
    f.write_text("\n".join(rows) + "\n")
    cap = read_capture(f)
    assert cap.axes == ("x",)
    np.testing.assert_array_equal(cap.reference[:, 0], _SET[1:])
    np.testing.assert_array_equal(cap.measured[:, 0], _ACT[1:])
    np.testing.assert_allclose(np.diff(cap.t), 0.001)


def test_spaced_rows_with_unaligned_blank_cells_are_named_as_such(tmp_path):
    """Rows separated by single runs of spaces, one with a blank cell its neighbours do not line up with, cannot be
    placed: the error names the two rows and their cell counts (it called the file a printout with one row of
    numbers among text: trace_fuzz seed 41000969)."""
    rows = ["Index x_cmd x_fb", *(f"{k} {s:g} {a:g}" for k, (s, a) in enumerate(zip(_SET, _ACT))), "6  1020"]
    rows += [f"# note {k}" for k in range(25)]
    f = tmp_path / "ragged.txt"
    f.write_text("\n".join(rows) + "\n")
    with pytest.raises(CaptureError, match=r"rows of numbers with 3 and 2 cells \(lines 7 and 8\)") as err:
        read_capture(f, sample_time=0.001)
    assert f"{f}:7" in str(err.value)


def test_whole_numbers_grouped_by_thousands_are_named(tmp_path):
    """Quoted cells of whole numbers with two or more group marks (``"20,296,998"`` nm) are digits grouped by
    thousands whatever the decimal mark: the error names the cell (it said no rows were found: trace_fuzz seed
    41001082), also where such a row above the rows was taken for the names (seed 41000672)."""
    f = tmp_path / "grouped.csv"
    rows = ['"y_ref","y_act"', '"[nm]","[nm]"'] + [f'"{s * 1e5:,.0f}","{a * 1e5:,.0f}"' for s, a in zip(_SET, _ACT)]
    f.write_text("\n".join(rows[:2] + rows[3:]) + "\n")  # the row of zeros left out: every row has grouped cells
    with pytest.raises(CaptureError, match=r"'10,000,000' \(line 3\) writes its digits grouped by thousands"):
        read_capture(f, sample_time=0.001)
    f = tmp_path / "grouped_names.csv"
    rows = ['"No.","x_cmd[nm]","x_fb[nm]","Current[A]"', '"0","1,000,000","1,000,000","1.5"']
    rows += [f'"{k}","{s:,.3f}","{a:,.3f}","1.5"' for k, (s, a) in enumerate(zip(_SET, _ACT), 1)]
    f.write_text("# Sample time: 1 ms\n" + "\n".join(rows) + "\n")
    with pytest.raises(CaptureError, match=r"'1,000,000' writes its digits grouped by thousands") as err:
        read_capture(f)
    assert f"{f}:3" in str(err.value)


def test_positions_grouped_by_thousands_in_whole_thousands_are_refused(tmp_path):
    """``"100,000"`` nm beside ``"0"`` is grouped by thousands even where every position is a whole number of
    thousands (it read 100 nm, a thousand times too small: the check looked only at columns with a fraction)."""
    f = tmp_path / "thousands.csv"
    rows = ['"No.","x_cmd[nm]","x_fb[nm]"']
    rows += [f'"{k}","{s * 1e3:,.0f}","{a * 1e3:,.0f}"' for k, (s, a) in enumerate(zip(_SET[:5], _ACT[:5]))]
    f.write_text("# Sample time: 1 ms\n" + "\n".join(rows) + "\n")
    with pytest.raises(CaptureError, match=r"'100,000' beside whole numbers like '0' reads as digits grouped"):
        read_capture(f)


@pytest.mark.parametrize("lines", [
    [f"<Run|MPos:{k * 0.1:.3f},0.000,-1.000|FS:600,0>" for k in range(6)],  # Grbl v1.1, the log's first line
    ["Grbl 1.1h ['$' for help]", *(f"ok\n<Run|WPos:{k * 0.1:.3f},0.000,0.000|Bf:15,128|FS:600,0>" for k in range(6))],
    [f"<Run,MPos:{k * 0.1:.3f},0.000,0.000,WPos:{k * 0.1:.3f},0.000,0.000>" for k in range(6)],  # Grbl v0.9
])
def test_grbl_status_report_log_is_named(tmp_path, lines):
    """A sender's log of Grbl's status reports (grbl/grbl doc/markdown/interface.md, 'Real-time Status Reports') is
    named as such with the fields it holds, no trace (it was called an XML file with root <Run>, or a file with no
    rows of numbers)."""
    f = tmp_path / "grbl.log"
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaptureError, match=r"Grbl's real-time status reports \(6 reports .*fields \[.*Pos'") as err:
        read_capture(f)
    assert str(f) in str(err.value) and "no commanded position" in str(err.value)


def test_ipoc_with_its_unit_after_a_slash_is_the_time(tmp_path):
    """KUKA RSI's ``IPOC`` named with its unit after a slash (``IPOC/ms``, DIN 1313's quantity/unit) is the time as
    ``IPOC`` and ``IPOC [ms]`` are (trace_fuzz seed 42000516 asked which column is the time)."""
    f = _table(tmp_path / "rsi.csv", ["IPOC/ms", "X_RSol/mm", "X_RIst/mm"], step=12.0)
    cap = read_capture(f)
    assert cap.axes == ("x",)
    np.testing.assert_allclose(np.diff(cap.t), 0.012)
    np.testing.assert_array_equal(cap.reference[:, 0], _SET)


def test_one_row_among_rows_grouped_by_thousands_names_the_grouping(tmp_path):
    """Rows whose cells are mostly grouped by thousands (``"94,157,019.0"``) leave one row that reads as numbers:
    the error names the grouping (it said 'only one row of numbers among text': trace_fuzz seed 42000917)."""
    rows = ['"No.","Y Sollposition [nm]","Y Schleppabstand [nm]","Speed [mm/s]"', '"0","1,000.5","0.0","0.0"']
    rows += [f'"{k}","{s * 1e3 + 1000:,.1f}","{(s - a) * 1e3 + 1000:,.1f}","17.5"'
             for k, (s, a) in enumerate(zip(_SET, _ACT), 1)]
    f = tmp_path / "grouped_rows.csv"
    f.write_text("Abtastzeit: 125 us\n" + "\n".join(rows + [f"# {k}" for k in range(20)]) + "\n")
    with pytest.raises(CaptureError, match=r"only one row of numbers .*'1,000.5' \(line 3\) writes its digits grouped"):
        read_capture(f)


def _indraworks_xml(signals: list[tuple[str, list[float], list[float]]], units: str = "") -> str:
    """An IndraWorks oscilloscope XML export after the layout a real parser of them reads (root / OscilloscopeData /
    Devices / Device / Measurements / Measurement / Signals / Signal with Name, XValue, YValue joined by '|')."""
    ns = "http://www.boschrexroth.de/indraworks.textformatter.xsd"
    sig = "".join(f"<Signal><Name>{n}</Name>{units}<XValue>{'|'.join(f'{v:g}' for v in x)}</XValue>"
                  f"<YValue>{'|'.join(f'{v:g}' for v in y)}</YValue></Signal>" for n, x, y in signals)
    return (f'<?xml version="1.0" encoding="utf-8"?>\n<root xmlns="{ns}"><OscilloscopeData><Devices><Device>'
            f"<Measurements><Measurement><Signals>{sig}</Signals></Measurement></Measurements></Device></Devices>"
            "</OscilloscopeData></root>\n")


def test_indraworks_oscilloscope_xml_is_read_by_its_signal_names(tmp_path):
    """Rexroth IndraWorks saves oscilloscope data as XML, each signal its name (IDN and name) and its time stamps
    and values joined by '|': read under the names, S-0-0047 commanded and S-0-0051 measured (it was refused as
    an XML file with root <root>); the time stamps' unit is asked for where the file states none; signals on
    other time stamps are an error naming the signal."""
    t = [k * 0.0005 for k in range(len(_SET))]
    f = tmp_path / "osc.xml"
    f.write_text(_indraworks_xml([("S-0-0047.0.0 Position command value", t, _SET),
                                  ("S-0-0051.0.0 Position feedback value 1", t, _ACT),
                                  ("S-0-0040.0.0 Velocity feedback value", t, [0.0] * len(t))]))
    with pytest.raises(CaptureError, match=r"states no unit of its time stamps.*--time-unit"):
        read_capture(f)
    cap = read_capture(f, time_unit="s")
    assert cap.axes == ("x",) and "IndraWorks" in cap.meta["format"]
    np.testing.assert_array_equal(cap.reference[:, 0], _SET)
    np.testing.assert_array_equal(cap.measured[:, 0], _ACT)
    np.testing.assert_allclose(np.diff(cap.t), 0.0005)
    f.write_text(_indraworks_xml([("S-0-0047.0.0 Position command value", [v * 1e3 for v in t], _SET),
                                  ("S-0-0051.0.0 Position feedback value 1", [v * 1e3 for v in t], _ACT)],
                                 units="<XUnit>ms</XUnit><YUnit>um</YUnit>"))  # a unit element, where one is written
    cap = read_capture(f)
    np.testing.assert_allclose(np.diff(cap.t), 0.0005)
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 1e-3)
    f.write_text(_indraworks_xml([("S-0-0047.0.0 Position command value", t, _SET),
                                  ("S-0-0051.0.0 Position feedback value 1", [v + 0.0002 for v in t], _ACT)]))
    with pytest.raises(CaptureError, match=r"'S-0-0051.0.0 Position feedback value 1'.*time stamps"):
        read_capture(f, time_unit="s")


def test_two_column_spaced_table_with_a_lone_cell_row(tmp_path):
    """In a table of two columns aligned by spaces, a row whose other cell is blank holds one number: placed by its
    edge as well (trace_fuzz seed 43000558, 'pos_cmd/um   pos_fb/um' with the first and last feedback blank, said
    the file had no header line)."""
    rows = ["Sample time [ms]: 1", f"{'pos_cmd/um':<12}{'pos_fb/um':<12}", f"{_SET[0]:<12.2f}"]
    rows += [f"{s:<12.2f}{a:<12.2f}" for s, a in zip(_SET[1:], _ACT[1:])] + [f"{1100.0:<12.2f}"]
    f = tmp_path / "two.txt"
    f.write_text("\n".join(rows) + "\n")
    cap = read_capture(f)
    np.testing.assert_array_equal(cap.reference[:, 0], np.array(_SET[1:]) * 1e-3)
    np.testing.assert_array_equal(cap.measured[:, 0], np.array(_ACT[1:]) * 1e-3)


def test_unaligned_lone_cell_above_the_rows_is_named(tmp_path):
    """A row of one number above rows of two, in columns that do not line up, is named as a blank cell that cannot be
    placed (it said the file had no header line: trace_fuzz seed 43000558)."""
    rows = ["pos_cmd/um   pos_fb/um", "-40920.13", *(f"{s:g}   {a:g}" for s, a in zip(_SET[1:], _ACT[1:]))]
    f = tmp_path / "ragged_two.txt"
    f.write_text("\n".join(rows) + "\n")
    with pytest.raises(CaptureError, match=r"rows of numbers with 1 and 2 cells \(lines 2 and 3\)"):
        read_capture(f, sample_time=0.001)
