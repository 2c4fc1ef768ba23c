"""Traces users' controls record, session 40 (traces40): a record that starts with the axis under way.

The inputs are written here: the thesis' PID x axis (``identification.synthetic.FADAL_PID_X``, Table 3.4) answering
random moves with dwells, cut where the first move runs at over 100 mm/s; and a hand-made capture moving at
100 mm/s from its first sample beside model records written by hand.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture
from vcnc.capture import Capture, read_capture
from vcnc.cli import main
from vcnc.commands.identify import record_start_lines
from vcnc.errors import CaptureError

T = 1e-3


def _under_way() -> Capture:
    """2 s of x: the command at 100 mm/s from its first sample, stopping at 0.5 s; the axis 1 mm behind it."""
    t = np.arange(2000) * T
    xr = np.minimum(t, 0.5) * 100.0
    x = np.minimum(np.maximum(t - 0.01, 0.0), 0.5) * 100.0 + np.where(t < 0.01, t * 100.0 - 1.0, 0.0)
    return Capture(t=t, axes=("x",), reference=xr[:, None], measured=x[:, None], meta={"source": "test"})


def test_a_record_cut_at_its_first_rest_is_named_with_its_speeds():
    cap = _under_way()
    model = ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=T,
                             fit={"rms_um": 1.0, "max_um": 2.0,
                                  "record_start": {"dropped_samples": 520, "dropped_s": 0.52}})
    (line,) = record_start_lines(cap, model, "x", 1.0)
    assert line.startswith("warning: the record starts with the axis under way (the axis moves at 100 mm/s, its "
                           "command at 100 mm/s at its first sample)")
    assert "0.52 s in (520 samples left out" in line and "vcnc simulate and vcnc compare" in line


def test_a_record_fitted_from_its_start_state_says_what_a_simulation_from_rest_costs():
    cap = _under_way()
    fit = {"rms_um": 0.3, "max_um": 2.1, "initial_state": {"state_mm": [0.1, 2.0, 0.09], "first_sample": 101,
                                                           "start_response_max_um": 381.5}}
    model = ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=T, fit=fit, delay_s=0.1)
    (line,) = record_start_lines(cap, model, "x", 567.6)
    assert "at sample 101, where the fit starts (the recorded reference leads the loop by 0.1 s" in line
    assert "a free response of up to 381.5 um" in line and "rms 567.6 um against the fit's 0.3 um" in line
    # a record that starts at rest gets no such line
    assert record_start_lines(cap, ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=T,
                                                    fit={"rms_um": 1.0, "max_um": 2.0}), "x", 1.0) == []


def test_identify_warns_of_a_record_triggered_during_a_move(tmp_path, capsys):
    """Session 39 cut such a record at its first rest without a word: the summary said nothing of the 89 samples
    (0.089 s, fadal-pid's model on 20 moves, /tmp/traces40/motion) a simulation from rest gets wrong."""
    ref = random_moves_reference(moves=6, dwell=0.2, sample_time=T, seed=1)
    x = synthetic_capture(dict(FADAL_PID_X), ref, sample_time=T, noise=1e-4, seed=1).measured[:, 0]
    k = int(np.flatnonzero(np.abs(np.diff(ref)) > 0.1)[0]) + 5  # 5 samples after the first move passes 100 mm/s
    f = tmp_path / "triggered.csv"
    rows = [f"{i * T:.3f},{r:.6f},{m:.6f}" for i, (r, m) in enumerate(zip(ref[k:], x[k:]))]
    f.write_text("t,x_ref,x\n" + "\n".join(rows) + "\n")
    out = tmp_path / "m.json"
    assert main(["identify", str(f), "--no-diagnose", "--json", str(out)]) == 0
    text = " ".join(capsys.readouterr().out.split())
    dropped = json.loads(out.read_text())["fit"]["record_start"]["dropped_samples"]
    assert "warning: the record starts with the axis under way" in text
    assert f"({dropped} samples left out of the fit and the table)" in text


def _tncscope_noml_diff(noml: np.ndarray, diff: np.ndarray, ts: float) -> str:
    """A TNCscope text export of Y with ``s noml`` and ``s diff`` (no actual position), as issue #17 describes it."""
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", f"%SAMPLING={ts * 1e6:g}",
             "%[CURVE1]", "%NAME=s noml/Y", "%CHANNELTYPE=s noml", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=1",
             "%[CURVE2]", "%NAME=s diff/Y", "%CHANNELTYPE=s diff", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=2",
             "%[DATA]"]
    lines += [f"{k * ts * 1e6:.0f};{r:.6f};{e:.6f};" for k, (r, e) in enumerate(zip(noml, diff))]
    return "\n".join(lines) + "\n"


def test_a_leading_nominal_with_its_servo_lag_reads_as_the_actual_position_and_keeps_its_lead(tmp_path):
    """Heidenhain's servo lag is "the difference between nominal and actual positions" (TNC 426/425/415 B/407 user's
    manual, MOD functions, "Position Display Types"): ``s diff`` against the ``s noml`` of the same sample. So the
    reader's ``s noml - s diff`` is the actual position however far the nominal leads the loop, and the lead stays
    in the record for the dead-time scan, as with ``s actl`` (session 39: 0.1003 s on fadal-pid's random moves)."""
    from identification.dead_time import delay_reference, estimate_delay

    ts = 0.001
    loop = random_moves_reference(moves=6, sample_time=ts, seed=3)  # the loop's command
    noml = np.round(delay_reference(loop, -100.0), 6)  # recorded 0.1 s ahead of the loop
    actual = np.round(synthetic_capture(dict(FADAL_PID_X), loop, sample_time=ts).measured[:, 0], 6)
    f = tmp_path / "lead.txt"
    f.write_text(_tncscope_noml_diff(noml, noml - actual, ts), encoding="utf-8")
    got = read_capture(f)
    np.testing.assert_allclose(got.measured[:, 0], actual, atol=2e-6)
    np.testing.assert_allclose(got.reference[:, 0], noml, atol=1e-9)
    assert abs(estimate_delay(got.reference[:, 0], got.measured[:, 0], ts).delay_s - 0.1) < 2 * ts


def test_plc_symbol_paths_are_read_by_their_last_element(tmp_path):
    """A TwinCAT Scope View CSV export (its preamble, FILETIME stamps in 100 ns, ``SampleTime`` in ms) whose channels
    are named by their symbol paths, as anderssandstrom/amci_resolver_issue's real exports name theirs
    (``MAIN.afbAxes[3].stAxisStruct.stStatus.fActPosition``): ``stStatus`` made the position a status word and
    ``afbAxes`` (an array of function blocks) an axis A's feedback, so the pair was refused; the last element names
    the role, the structures before it name none."""
    set_, act = (f"MAIN.afbAxes[3].stAxisStruct.stStatus.f{w}Position" for w in ("Set", "Act"))
    t0 = 132900081483250000
    ref = np.round(np.linspace(0.0, 3.0, 300) ** 2, 6)
    meas = np.concatenate([[0.0, 0.0], ref[:-2]])
    rows = [f"{t0 + k * 100000};{r};{m}" for k, (r, m) in enumerate(zip(ref, meas))]
    text = "\n".join(["Name;Axis 3;", "File;C:\\Scope\\axis3.csv;",
                      "Starttime of export;132900081483250000;Tuesday, February 22, 2022;13:55:48.325", "", "",
                      "TriggerGroup;Count;ReleaseTime;Comment;", "", f"Name;{set_};{act}",
                      "SymbolComment;Set position value;Actual position value", "Data-Type;REAL64;REAL64",
                      "SampleTime;10;10", f"SymbolName;{set_};{act}", "Unit;(None);(None)", "", "", *rows]) + "\n"
    f = tmp_path / "scope.csv"
    f.write_text(text)
    got = read_capture(f)
    assert got.axes == ("x",)
    np.testing.assert_allclose(got.reference[:, 0], ref)
    np.testing.assert_allclose(got.measured[:, 0], meas)
    assert abs(got.sample_time - 0.01) < 1e-12


def test_a_loggers_file_headed_by_t_asks_its_own_question(tmp_path):
    """``t`` first and a ``#`` line above look like vcnc's capture CSV; a logger's names under them are read (session
    37), and when that file is refused for another reason, its own question is the one asked: here whether the
    whole numbers are counts of the stated 0.5 um (trace_fuzz seed 52000248, its layout written by hand). The capture
    CSV's "unknown column 'X Commanded Position'" was raised, sending the user to map columns the names had mapped."""
    f = tmp_path / "counts.csv"
    f.write_text("# Resolution: 0.5 um\nt,X Commanded Position,X Actual Position\n12.500,56918,56918\n"
                 "12.501,56547,56918\n12.502,56176,56899\n")
    with pytest.raises(CaptureError, match=r"states the size of one count .*expected --unit 0\.5um \(counts\)") as err:
        read_capture(f)
    assert err.value.line == 2
    got = read_capture(f, unit="0.5um")
    np.testing.assert_allclose(got.reference[:, 0], np.array([56918, 56547, 56176]) * 0.5e-3)
    # a header that names nothing a logger would still gets the capture CSV's own message
    g = tmp_path / "typo.csv"
    g.write_text("t,x_ref,xx\n0,0,0\n0.001,1,1\n")
    with pytest.raises(CaptureError, match="unknown column 'xx'"):
        read_capture(g)
