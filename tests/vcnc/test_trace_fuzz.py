"""Trace layouts nobody wrote by hand: the seeded fuzzer of ``benchmarks/trace_fuzz.py`` (every file read as the
truth or refused naming the file), and the minimal files of what it found (session 30, tracefuzz), each asserting
the values read or the error."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.trace_fuzz import FAILURES, generate, judge, mutate_formats, run, write
from identification.capture_checks import check_capture
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture
from vcnc.core.capture import UNIT_GIVEN
from vcnc.errors import CaptureError, IdentificationError
from vcnc.traces import read_trace


def test_generated_layouts_read_as_written_or_refused(tmp_path):
    """150 generated delimited files (seed 30) and 60 mutated TNCscope/halscope/TwinCAT files: no traceback, no
    wrong role, unit, axis, time or value; most are read."""
    counts = run(150, 30, tmp_path)
    assert not {k: counts[k] for k in FAILURES if counts[k]}
    assert counts["read"] >= 100 and counts["read"] + counts["refused"] == 150
    formats = mutate_formats(60, 30, tmp_path)
    assert not [k for k in formats if k.endswith((":changed", ":traceback", ":error-without-file"))]
    assert sum(c for k, c in formats.items() if k.endswith(":same")) >= 15


def test_a_generated_case_is_its_seed(tmp_path):
    """The same seed writes the same file and judges it the same way."""
    a, b = generate(12345), generate(12345)
    assert a.text == b.text and a.layout == b.layout and a.kwargs == b.kwargs
    path = tmp_path / "case.csv"
    write(a, path)
    assert judge(a, path)[0] in ("read", "refused")


def _rows(values: list[tuple[float, ...]], delimiter: str = ";") -> str:
    return "\n".join(delimiter.join(f"{v:g}" for v in row) for row in values) + "\n"


ROWS = [(k * 0.001, 2.0 * k, 2.0 * k - 0.5 * (k > 0)) for k in range(6)]


def test_a_unit_after_a_slash_is_inch(tmp_path):
    """``ActPos/in`` (DIN 1313's quantity/unit) is inch, read x 25.4 (it was read as mm); ``_in`` is not a unit."""
    f = tmp_path / "slash.csv"
    f.write_text("Time/s;X_Soll/in;X_Ist/in\n" + _rows(ROWS))
    cap = read_trace(f)
    np.testing.assert_allclose(cap.reference[:, 0], [25.4 * r[1] for r in ROWS])
    np.testing.assert_allclose(cap.measured[:, 0], [25.4 * r[2] for r in ROWS])
    assert cap.meta["unit"] == "in"
    assert cap.meta[UNIT_GIVEN] == "stated in the file: x_ref in in, x in in"


def test_a_stated_count_size_over_positions_without_a_unit_is_a_question(tmp_path):
    """``Resolution: 0.1 um`` above ``x_cmd``/``x_fb`` that name no unit: counts or mm? (read as mm they were 10,000
    times too large, had they been counts)."""
    f = tmp_path / "counts.csv"
    f.write_text("Resolution: 0.1 um\nt;x_cmd;x_fb\n" + _rows(ROWS))
    with pytest.raises(CaptureError) as info:
        read_trace(f)
    msg = str(info.value)
    assert info.value.line == 2
    assert ("line 1 states the size of one count ('Resolution: 0.1 um'), and x_ref='x_cmd', x='x_fb' state no "
            "unit") in msg
    assert "--unit 0.1um (counts) or --unit mm" in msg
    cap = read_trace(f, unit="0.1um")
    np.testing.assert_allclose(cap.reference[:, 0], [1e-4 * r[1] for r in ROWS])


def test_digits_grouped_by_thousands_are_refused(tmp_path):
    """A spreadsheet's ``"1,234"`` counts beside ``"523"`` (delimiter ``,``) read as decimal commas were 1000 times
    too small; ``1.234`` beside ``523`` likewise. A column of three-place decimals is read."""
    f = tmp_path / "grouped.csv"
    f.write_text('"t","x_cmd [inc]","x_fb [inc]"\n"0","523","500"\n"0.001","1,234","1,100"\n"0.002","2,345","2,200"\n'
                 '"0.003","3,456","3,300"\n')
    with pytest.raises(CaptureError) as info:
        read_trace(f, unit="1um")
    assert info.value.line == 3
    assert "x_ref='x_cmd [inc]': '1,234' beside whole numbers like '523' reads as digits grouped" in str(info.value)
    g = tmp_path / "decimals.csv"
    g.write_text("t;x_cmd;x_fb\n0;523;500\n0.001;1.234;1.100\n0.002;2.345;2.200\n0.003;3.456;3.301\n")
    with pytest.raises(CaptureError, match="grouped by thousands"):
        read_trace(g)
    german = tmp_path / "german.csv"  # every position grouped; the current column's decimal comma tells
    german.write_text("Axis_Y.SetPos;Axis_Y.ActPos;Y Current\n-69.113;-69.113;1,500\n-67.999;-69.113;1,491\n"
                      "-66.885;-69.023;1,463\n")
    with pytest.raises(CaptureError) as info:
        read_trace(german, unit="0.5um", sample_time=0.002)
    assert info.value.line == 2
    assert "y_ref='Axis_Y.SetPos': '-69.113' beside '1,500' in another column reads as digits" in str(info.value)
    h = tmp_path / "places.csv"
    h.write_text("t;x_cmd;x_fb\n0;0.523;0.500\n0.001;1.234;1.100\n0.002;2.345;2.200\n0.003;3.456;3.301\n")
    np.testing.assert_allclose(read_trace(h).reference[:, 0], [0.523, 1.234, 2.345, 3.456])


def test_a_header_starting_with_t_that_is_no_capture_csv_is_read_by_its_names(tmp_path):
    """``t,X Commanded Position,X Actual Position`` is another logger's file (``t`` is the commonest time name), not
    a capture CSV with unknown columns."""
    f = tmp_path / "t_first.csv"
    f.write_text("t,X Commanded Position,X Actual Position\n" + _rows(ROWS, ","))
    cap = read_trace(f)
    assert cap.axes == ("x",)
    np.testing.assert_allclose(cap.measured[:, 0], [r[2] for r in ROWS])
    assert cap.meta["columns"].startswith("from the header names: t=t, x_ref=X Commanded Position")
    bad = tmp_path / "bad.csv"
    bad.write_text("t,x_ref,q\n0,0,0\n0.001,0,0\n")
    with pytest.raises(CaptureError, match="unknown column 'q'"):
        read_trace(bad)


def test_pipe_separated_rows(tmp_path):
    """Columns separated by ``|`` (our reading: database and report tools' exports)."""
    f = tmp_path / "pipe.txt"
    f.write_text("Time [ms]|X Soll [um]|X Ist [um]\n" + _rows([(1e3 * t, r, m) for t, r, m in ROWS], "|"))
    cap = read_trace(f)
    assert cap.meta["format"] == "delimited text (pipe)"
    np.testing.assert_allclose(cap.t, [r[0] for r in ROWS])
    np.testing.assert_allclose(cap.reference[:, 0], [1e-3 * r[1] for r in ROWS])


# ------------------------------------------------------------------------------------------ stated units
def test_every_stated_unit_is_marked(tmp_path):
    """``unit=`` given, a unit in every position column's name, a TNCscope ``%DIMENSION``: ``meta[UNIT_GIVEN]``;
    a unit assumed (no unit anywhere) is not marked."""
    f = tmp_path / "plain.csv"
    f.write_text("t;x_cmd;x_fb\n" + _rows(ROWS))
    assert UNIT_GIVEN not in read_trace(f).meta
    assert read_trace(f, unit="um").meta[UNIT_GIVEN] == "unit um given"
    g = tmp_path / "named.csv"
    g.write_text("t;x_cmd [um];x_fb\n" + _rows(ROWS))
    assert UNIT_GIVEN not in read_trace(g).meta  # x_fb states none: mm assumed
    h = tmp_path / "row.csv"
    h.write_text("t;x_cmd;x_fb\ns;um;um\n" + _rows(ROWS))
    assert read_trace(h).meta[UNIT_GIVEN] == "stated in the file: x_ref in um, x in um"
    sco = tmp_path / "y.sco"
    sco.write_text("\n".join(["%TNCscopeNT data file", "%[GLOBAL]", "%SAMPLING=3000", "%[CURVE1]", "%NAME=s soll/Y",
                              "%CHANNELTYPE=s soll", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=1", "%[CURVE2]",
                              "%NAME=s ist/Y", "%CHANNELTYPE=s ist", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=2",
                              "%[DATA]", "0;1.0;1.0;", "3000;1.5;1.1;", "6000;2.0;1.4;"]) + "\n")
    assert read_trace(sco).meta[UNIT_GIVEN] == "stated by %DIMENSION: col1 in mm, col2 in mm"


def test_a_unit_the_header_states_is_not_taken_for_metres(tmp_path):
    """A 0.5 um move logged under ``[um]`` headers is refused as too small a motion in the unit the file states,
    not as metres (before, only ``--unit`` counted)."""
    small = synthetic_capture(FADAL_PID_X, random_moves_reference(moves=40, seed=2), noise=2e-4, seed=1)
    ref_um, meas_um = small.reference[:, 0] / 20, small.measured[:, 0] / 20  # 1/20000 of the mm, in um
    f = tmp_path / "piezo.csv"
    f.write_text("Time [s];Pos_Soll [um];Pos_Ist [um]\n"
                 + "\n".join(f"{t:.4f};{r:.9f};{m:.9f}" for t, r, m in zip(small.t, ref_um, meas_um)) + "\n")
    cap = read_trace(f)
    with pytest.raises(IdentificationError) as info:
        check_capture(cap, "x")
    msg = str(info.value)
    assert "too small a motion to identify on axis 'x'" in msg and "metres" not in msg
    assert "(stated in the file: x_ref in um, x in um)" in msg
