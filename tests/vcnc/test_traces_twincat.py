"""TwinCAT 3 Scope CSV exports in the layouts TwinCAT writes (vcnc/traces/twincat.py docstring).

The fixtures are written here, in the layouts of the real exports of TwinCAT 3 Scope 3.4 (the
test data of CagtayFabry/pytcs): acquisition groups sharing a time column, a faster group whose
rows run on with blank cells and then end early, each separator, a decimal comma, FILETIME
stamps, an ``EOF`` line.
"""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.errors import CaptureError
from vcnc.traces import trace_format

N = 200
T_MS = np.arange(N) * 2.0  # 2 ms
REF = np.round(10 * np.sin(T_MS * 3e-3), 6)
ACT = np.round(REF - 0.02 * np.cos(T_MS * 3e-3), 6)


def _export(path, d=";", comma=True, *, fast=True, ticks=False, keys=("Name", "SampleTime[ms]"), eof=True,
            names=("MAIN.Axis1.NcToPlc.SetPos", "MAIN.Axis1.NcToPlc.ActPos")):
    """Group 1: time, the two ``names`` at 2 ms. With ``fast``: group 2, time and ``fTorque`` at
    0.5 ms (4x the rows), and group 3, time and ``fSpare`` at 2 ms; once groups 1 and 3 end, a row
    holds blank cells for group 1 and ends after group 2, as Scope writes them."""
    def num(v, fmt):
        text = format(v, fmt)
        return text.replace(".", ",") if comma else text

    groups = [(names, "REAL64", 2.0)] + ([(("fTorque",), "REAL32", 0.5), (("fSpare",), "REAL32", 2.0)] if fast else [])
    head = [f"Name{d}axis_trace", f"File{d}C:\\scope\\axis_trace.csv",
            f"Starttime of export{d}132959733843760000{d}Montag, 2. Mai 2022{d}15:56:24.376", "", ""]
    values = {"Name": lambda chans, typ, ts: list(chans),
              "SymbolName": lambda chans, typ, ts: [f"MAIN.{c}" for c in chans],
              "Data-Type": lambda chans, typ, ts: [typ] * len(chans),
              "SampleTime[ms]": lambda chans, typ, ts: [num(ts, "g")] * len(chans)}
    for key in keys:
        head.append(d.join(cell for chans, typ, ts in groups for cell in [key, *values[key](chans, typ, ts)]))
    head.append("")
    body = []
    for k in range(4 * N if fast else N):
        t = str(132959733843760000 + int(T_MS[k]) * 10_000) if ticks and k < N else num(T_MS[min(k, N - 1)], "g")
        cells = [t, num(REF[k], ".6f"), num(ACT[k], ".6f")] if k < N else [" ", " ", " "]
        if fast:
            cells += [num(k * 0.5, "g"), num(0.1 * k, ".3f")]
            cells += [t, "1,5" if comma else "1.5"] if k < N else []
        body.append(d.join(cells))
    path.write_bytes(("\r\n".join(head + body + (["EOF"] if eof else [])) + "\r\n").encode("utf-8"))


@pytest.mark.parametrize("d", ["\t", ";", ",", ":", " "])
def test_every_separator_and_groups_with_blank_and_missing_cells(tmp_path, d):
    f = tmp_path / "scope.csv"
    _export(f, d=d, comma=d != ",", fast=d != " ")  # with spaces a blank cell would be ambiguous: Scope writes none
    assert trace_format(f) == "twincat"
    cap = read_capture(f)  # SetPos / ActPos pair up without --columns
    assert cap.axes == ("x",) and cap.meta["separator"] in ("tab", "semicolon", "comma", "colon", "space")
    np.testing.assert_array_equal(cap.t, np.round(T_MS * 1e-3, 9))
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)
    assert cap.meta["commanded"] == "x:MAIN.Axis1.NcToPlc.SetPos"


def test_channels_of_different_rates_meet_on_the_slower_grid(tmp_path):
    f = tmp_path / "scope.csv"
    _export(f)
    cap = read_capture(f, columns={"x_ref": "MAIN.Axis1.NcToPlc.SetPos", "x": "fTorque"})
    np.testing.assert_array_equal(cap.t, np.round(T_MS * 1e-3, 9))  # 0.5 ms samples on the 2 ms instants
    np.testing.assert_allclose(cap.measured[:, 0], 0.1 * 4 * np.arange(N), atol=1e-9)


def test_filetime_stamps_name_only_header_and_axis_names(tmp_path, capsys):
    f = tmp_path / "scope.csv"
    _export(f, d="\t", ticks=True, fast=False, keys=("Name",), eof=False)
    assert trace_format(f) == "twincat"
    out = tmp_path / "cap.csv"
    assert main(["convert", str(f), "-o", str(out), "--axis-names", "y"]) == 0
    assert "100 ns ticks" in capsys.readouterr().out
    cap = read_capture(out)
    assert cap.axes == ("y",) and cap.sample_time == 0.002
    np.testing.assert_allclose(cap.t, T_MS * 1e-3, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)


def test_repeated_time_stamps_hold_one_sample(tmp_path):
    """Scope repeats a slower group's last row; the repeat is one sample, not two."""
    f = tmp_path / "scope.csv"
    _export(f, fast=False)
    lines = f.read_bytes().decode().split("\r\n")
    k = lines.index(next(ln for ln in lines if ln.startswith("10;")))
    f.write_bytes("\r\n".join(lines[: k + 1] + [lines[k]] + lines[k + 1:]).encode())
    cap = read_capture(f)
    assert len(cap) == N and np.all(np.diff(cap.t) > 0)


def test_channel_lookup_by_symbol_name_and_errors(tmp_path):
    f = tmp_path / "scope.csv"
    _export(f, keys=("Name", "SampleTime[ms]", "SymbolName"),
            names=("SetPos", "ActPos"))
    cap = read_capture(f, columns={"x_ref": "SetPos", "x": "MAIN.fTorque"})
    assert cap.meta["measured"] == "x:MAIN.fTorque"
    with pytest.raises(CaptureError, match=r"channel 'nope' not found; channels found: \['SetPos', 'ActPos', "
                                           r"'fTorque', 'fSpare'\]"):
        read_capture(f, columns={"x_ref": "nope", "x": "ActPos"})
    _export(f, names=("pos", "pos"), fast=False)
    with pytest.raises(CaptureError, match="2 channels are named 'pos'"):
        read_capture(f, columns={"x_ref": "pos", "x": "pos"})
    with pytest.raises(CaptureError, match=r"give --columns x_ref=NAME,x=NAME \(or x_lag=NAME for a following "
                                           r"error\); channels found: \['pos', 'pos'\]"):
        read_capture(f)


@pytest.mark.parametrize("keys", [("Name",), ("Name", "SampleTime[ms]")])
def test_export_without_its_header_block(tmp_path, keys):
    """With the exporter's header setting off, the channel ``Name`` row comes first."""
    f = tmp_path / "scope.csv"
    _export(f, d="\t", keys=keys)
    f.write_bytes(b"\r\n".join(f.read_bytes().split(b"\r\n")[5:]))
    assert trace_format(f) == "twincat"
    cap = read_capture(f)
    np.testing.assert_array_equal(cap.measured[:, 0], ACT)


def test_channel_scaling_is_named_not_applied(tmp_path):
    """Scope applies a channel's ScaleFactor / Offset and Unit ScaleFactor / Unit Offset only with
    "Scale values before export" (Beckhoff infosys TE13xx, "Export to csv"); the pytcs exports hold
    the same recording unscaled (default) and scaled (simple export), so the values are read as
    they stand and the scaling is named."""
    f = tmp_path / "scope.csv"
    _export(f, fast=False, eof=False)
    lines = f.read_bytes().decode("utf-8").split("\r\n")
    k = next(i for i, ln in enumerate(lines) if ln.startswith("SampleTime[ms]"))
    lines[k + 1:k + 1] = ["ScaleFactor;0,001;1", "Offset;0;0", "Unit;mm;mm", "Unit ScaleFactor;1;1",
                          "Unit Offset;0;0"]
    f.write_bytes("\r\n".join(lines).encode("utf-8"))
    cap = read_capture(f)
    np.testing.assert_array_equal(cap.reference[:, 0], REF)
    assert cap.meta["scaling"].startswith("MAIN.Axis1.NcToPlc.SetPos (ScaleFactor 0,001): applied by Scope only")
    assert "ActPos" not in cap.meta["scaling"]
    f.write_bytes("\r\n".join(lines).replace("ScaleFactor;0,001;1", "ScaleFactor;1;1").encode("utf-8"))
    assert "scaling" not in read_capture(f).meta
