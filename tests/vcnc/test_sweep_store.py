"""Sweep results on disk: journal, torn lines, consolidation, never losing finished points."""

from __future__ import annotations

import math

import pytest

from vcnc.errors import InputError
from vcnc.sweeps.store import ResultStore, read_results


def _row(i: int, **kw):
    return {"id": f"p{i}", "status": "ok", "feed": 1000.0 * i, "seed": i, "samples": 10 * i,
            "tracking_max_um": 1.5 * i, "diag_hit": i % 2 == 0, "contour_max_um": None, **kw}


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_rows_round_trip_with_types_and_extra_columns(tmp_path, suffix):
    store = ResultStore(tmp_path / f"r{suffix}")
    for i in range(3):
        store.append(_row(i, extra_value=i * 0.5))
    store.append({"id": "bad", "status": "error", "error": 'ValueError: "quoted", with comma\nand newline'})
    table = store.consolidate()
    assert not store.journal.exists()
    back = read_results(store.output)
    assert back.num_rows == table.num_rows == 4
    rows = {r["id"]: r for r in back.to_pylist()}
    assert rows["p2"]["seed"] == 2 and rows["p2"]["samples"] == 20 and rows["p2"]["diag_hit"] is True
    assert rows["p1"]["diag_hit"] is False and rows["p1"]["contour_max_um"] is None
    assert rows["p1"]["extra_value"] == 0.5
    assert rows["bad"]["error"] == 'ValueError: "quoted", with comma\nand newline'
    assert rows["bad"]["feed"] is None


def test_torn_journal_line_is_ignored_and_appending_continues(tmp_path):
    store = ResultStore(tmp_path / "r.csv")
    store.append(_row(1))
    store.append(_row(2))
    store.close()
    with open(store.journal, "a") as fh:
        fh.write('{"id": "p3", "status": "o')  # the sweep was killed mid-write
    again = ResultStore(tmp_path / "r.csv")
    assert set(again.load()) == {"p1", "p2"}
    again.open()
    again.append(_row(3))
    again.close()
    assert set(again.load()) == {"p1", "p2", "p3"}


def test_journal_rows_merge_with_the_output_one_row_per_id(tmp_path):
    store = ResultStore(tmp_path / "r.parquet")
    store.append(_row(1))
    store.append({"id": "p2", "status": "error", "error": "boom"})
    store.consolidate()
    # a later run retried p2 and added p3; the journal is newer than the output
    store.append(_row(2))
    store.append(_row(3))
    store.close()
    done = ResultStore(tmp_path / "r.parquet").load()
    assert set(done) == {"p1", "p2", "p3"} and done["p2"]["status"] == "ok"
    table = store.consolidate()
    assert sorted(table.column("id").to_pylist()) == ["p1", "p2", "p3"]
    assert not math.isnan(table.column("tracking_max_um").to_pylist()[0])


def test_unreadable_output_is_an_input_error_and_left_untouched(tmp_path):
    out = tmp_path / "r.parquet"
    out.write_bytes(b"not parquet at all")
    with pytest.raises(InputError, match="r.parquet: cannot read the existing results"):
        ResultStore(out).load()
    assert out.read_bytes() == b"not parquet at all"
    other = tmp_path / "notes.csv"
    other.write_text("a,b\n1,2\n")
    with pytest.raises(InputError, match="not a sweep result"):
        ResultStore(other).load()
    with pytest.raises(InputError, match=r"results file must end in \.parquet or \.csv"):
        ResultStore(tmp_path / "r.xlsx")
