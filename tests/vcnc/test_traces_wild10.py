"""Traces in the layouts of tracewild10's real set (session 34): a drive logger's headerless tab-separated rows of
a rotary actuator (time in ms, target, demand, actual position, speed, current, as nicolazande/camber-control's
EccA logs) read with a column mapping; TwinCAT Scope exports with separator space (CagtayFabry/pytcs's real export
``Seperator_1``), whose names and units hold spaces. Each file is a few lines written here after the layout, not
the export itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError
from vcnc.traces.names import columns_from_names

_ROWS = [(0, 0.0, 0.0, 0.0), (13, 1.0, 0.5, 0.1), (26, 2.0, 1.5, 0.6), (39, 3.0, 2.5, 1.5), (52, 3.0, 3.0, 2.4),
         (65, 3.0, 3.0, 2.9)]


def test_rotary_axis_without_a_unit_is_named_in_degrees(tmp_path):
    """A rotary axis mapped without --unit is read in degrees, and the capture's ``meta["unit"]`` says so (it said
    'mm': the camber EccA log, --columns t=1,a_ref=2,a=4); beside a linear axis both units are named."""
    f = tmp_path / "ecc.txt"
    f.write_text("".join(f"{t}\t{r}\t{d}\t{a}\t0\t272\n" for t, r, d, a in _ROWS))
    cap = read_capture(f, columns={"t": "1", "a_ref": "2", "a": "4"}, time_unit="ms")
    assert cap.axes == ("a",) and cap.meta["unit"] == "deg"
    np.testing.assert_array_equal(cap.measured[:, 0], [r[3] for r in _ROWS])
    cap = read_capture(f, columns={"t": "1", "x_ref": "2", "x": "3", "a_ref": "2", "a": "4"}, time_unit="ms")
    assert cap.meta["unit"] == "deg,mm"


_T = [0, 2, 4, 6, 8, 10]
_SOLL = [0.0, 500.0, 1500.0, 3000.0, 4500.0, 5500.0]  # um
_IST = [0.0, 200.0, 1000.0, 2400.0, 3900.0, 5100.0]


def _space_export(path, groups: list[list[tuple[str, str]]]) -> None:
    """A TwinCAT Scope export with separator space, as pytcs' ``Seperator_1`` file: each group a time column and
    its channels ``(name, unit)``, every channel here valued from ``_SOLL`` then ``_IST`` in turn."""
    def row(key, cell):
        return " ".join(c for g in groups for c in [key, *[cell(ch) for ch in g]])

    values = [_SOLL, _IST, _SOLL]
    head = ["Name axis_trace", "File C:\\scope\\axis_trace.csv", "", "", row("Name", lambda ch: ch[0]),
            row("Data-Type", lambda ch: "REAL64"), row("SampleTime[ms]", lambda ch: "2"),
            row("Unit", lambda ch: ch[1]), "Unit ScaleFactor 1" + " 1" * (sum(map(len, groups)) - 1), ""]
    body = []
    for k, t in enumerate(_T):
        cells, n = [], 0
        for g in groups:
            cells.append(str(t))
            for _ in g:
                cells.append(f"{values[n][k]:g}")
                n += 1
        body.append(" ".join(cells))
    path.write_text("\r\n".join(head + body) + "\r\n", encoding="utf-8")


def test_space_separated_twincat_export_rejoins_names_and_units(tmp_path):
    """With separator space, TwinCAT writes a name or unit holding a space as two words: 'Achse X Soll' and
    'µm (Length)' stood a column off, ActPos took '(Length)' as its unit and was read in mm, 1000 times off
    (tracewild10, on pytcs' real space-separated export: func_timeshift was read with its neighbour's values).
    A group of one channel takes all its words; units rejoin at their parenthesis."""
    f = tmp_path / "scope.csv"
    _space_export(f, [[("Achse X Soll", "µm (Length)")], [("Achse X Ist", "µm (Length)")]])
    cap = read_capture(f, columns={"x_ref": "Achse X Soll", "x": "Achse X Ist"})
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SOLL) / 1000)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_IST) / 1000)
    _space_export(f, [[("MAIN.X.SetPos", "µm (Length)"), ("MAIN.X.ActPos", "µm (Length)")]])
    cap = read_capture(f)
    assert cap.meta["measured"] == "x:MAIN.X.ActPos" and cap.meta["unit"] == "um"
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_IST) / 1000)


def test_space_separated_twincat_names_that_cannot_be_told_apart(tmp_path):
    """Two channels of one group named with spaces: three words for two names is a question, never a guess."""
    f = tmp_path / "scope.csv"
    _space_export(f, [[("Pos Soll", "mm"), ("Pos_Ist", "mm")]])
    with pytest.raises(CaptureError, match=r"2 channels of the group at column 1 read as 3 words \['Pos', 'Soll', "
                                           r"'Pos_Ist'\]: which words form one name cannot be told") as err:
        read_capture(f, columns={"x_ref": "Pos Soll", "x": "Pos_Ist"})
    assert err.value.line == 5


def test_positions_naming_no_axis_beside_one_named_axis(tmp_path):
    """``pos_cmd`` and ``pos_fb`` beside ``X Following Error`` (trace_fuzz seed 35100, cases 105390 and 105800 of
    six alike): the bare positions fill axis x's missing roles, and the measured position is used before the lag.
    A bare position whose role the named axis already has is left alone."""
    f = tmp_path / "log.csv"
    f.write_text("time;pos_cmd;pos_fb;X Following Error\n[us];[mm];[mm];[mm]\n" + "".join(
        f"{500 * k};{s / 1000};{i / 1000};{(s - i) / 1000}\n" for k, (s, i) in enumerate(zip(_SOLL, _IST))))
    cap = read_capture(f)
    assert cap.meta["commanded"] == "x:pos_cmd" and cap.meta["measured"] == "x:pos_fb"
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_IST) / 1000)
    assert columns_from_names(["t", "X_pos_cmd", "X_pos_fb", "spindle_pos_cmd"]) == (
        {"t": "t", "x_ref": "X_pos_cmd", "x": "X_pos_fb"}, "")


def _aligned(rows: list[list[str]]) -> str:
    """Rows of cells right-aligned in columns 10 wide, a blank cell left blank."""
    return "".join("".join(f"{c:>10}" for c in r) + "\n" for r in rows)


def test_space_aligned_columns_with_blank_cells_at_the_ends(tmp_path):
    """A recorder printing fixed-width columns leaves the command's cell blank in the first and last row (trace_fuzz
    seed 35100 case 105730: 'only one row of numbers (6 values) among 401 lines'): the cells are placed by the
    column they end at, the two rows skipped as rows with an empty cell. A blank between numbers is still an error."""
    rows = [[f"{t}", f"{s / 1000:.3f}", f"{i / 1000:.3f}"] for t, s, i in zip(_T, _SOLL, _IST)]
    rows[0][1] = rows[-1][1] = ""
    f = tmp_path / "print.txt"
    f.write_text("Date: 2024-05-02\n" + _aligned([["Time[ms]", "XPosCmd", "XPosAct"], *rows]))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.t, np.array(_T[1:-1]) / 1000 - 0.002)
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SOLL[1:-1]) / 1000)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_IST[1:-1]) / 1000)
    rows[0][1], rows[-1][1], rows[2][1] = "0.000", "5.500", ""
    f.write_text("Date: 2024-05-02\n" + _aligned([["Time[ms]", "XPosCmd", "XPosAct"], *rows]))
    with pytest.raises(CaptureError, match="XPosCmd") as err:
        read_capture(f)
    assert err.value.line == 5
