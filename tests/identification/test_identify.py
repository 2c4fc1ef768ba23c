"""identify(): checks on the capture, the pipeline, the command line, real EMPS data."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from identification import identify, load_model
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture
from vcnc.capture import Capture
from vcnc.cli import main
from vcnc.errors import CaptureError, IdentificationError

EMPS = Path("/work/shared/data/emps")
T = 1e-3


def _cap(xr, x, t=None):
    t = np.arange(len(xr)) * T if t is None else t
    return Capture(t=t, axes=("x",), reference=np.asarray(xr, float)[:, None], measured=np.asarray(x, float)[:, None])


def _barely_moving(n: int) -> tuple[np.ndarray, np.ndarray]:
    """A reference out 5 mm and back in 10 samples each, the measured position a sample behind: too little motion
    either way (a record moving one way only is identified, ``test_one_way.py``)."""
    ramp = np.concatenate((np.zeros(500), np.linspace(0.5, 5.0, 10), np.full(500, 5.0), np.linspace(4.5, 0.0, 10)))
    xr = np.concatenate((ramp, np.zeros(n - ramp.size)))
    return xr, np.concatenate(([0.0], xr[:-1]))


@pytest.fixture(scope="module")
def small_capture():
    return synthetic_capture(FADAL_PID_X, random_moves_reference(moves=40, seed=2), noise=2e-4, seed=1)


def test_identify_small_capture(small_capture):
    m = identify(small_capture, refine="none", diagnose=False)
    assert m.method == "exact" and m.is_stable()
    assert m.fit["rms_um"] > 0 and m.fit["solver"]["success"]
    assert m.bounds == {"p_hz": (0.2, 500.0), "omega_n_hz": (0.2, 500.0), "zeta": (0.2, 2.0)}  # Sec. 4.3
    assert m.effects == [] and m.validation == {}
    # the capture's nominal period, not the mean step of decimal time stamps (0.0010000000000000009)
    assert m.sample_time == 0.001 and m.to_dict()["sample_time"] == 0.001


@pytest.mark.parametrize(
    ("make", "error", "match"),
    [
        (lambda c: dataclasses.replace(c, measured=np.where(np.arange(len(c))[:, None] == 700, np.nan, c.measured)),
         CaptureError, "not finite at sample 700"),
        (lambda c: dataclasses.replace(c, t=c.t * np.where(np.arange(len(c)) > 900, 1.01, 1.0)), CaptureError,
         "not uniform"),
        (lambda c: dataclasses.replace(c, t=np.where(np.arange(len(c)) == 900, 0.0, c.t)), CaptureError,
         "not increasing"),
        (lambda c: c.slice(0, 249), IdentificationError, "only 249 samples; identification needs at least 250"),
        (lambda c: _cap(np.zeros(len(c)), np.zeros(len(c))), IdentificationError, "no motion"),
        (lambda c: _cap(*_barely_moving(len(c))), IdentificationError,
         "too little motion to identify on axis 'x': 10 samples with positive and 10 with negative"),
        (lambda c: _cap(c.reference[:, 0], c.reference[:, 0]), IdentificationError, "identical to the reference"),
        (lambda c: _cap(c.reference[:, 0] / 1000, c.measured[:, 0] / 1000), IdentificationError,
         r"look like metres, not mm \(or radians of a rotary joint, not deg\).*--unit m; radians: --unit rad with the "
         r"axis named a, b or c"),
    ],
)
def test_bad_captures_are_rejected_with_the_reason(small_capture, make, error, match):
    with pytest.raises(error, match=match):
        identify(make(small_capture))


def test_unknown_axis(small_capture):
    with pytest.raises(CaptureError, match="axis 'y' is not in the capture"):
        identify(small_capture, axis="y")


def test_cli_identify_writes_model_and_report(tmp_path, small_capture, capsys):
    src = tmp_path / "cap.csv"
    small_capture.to_csv(src)
    out = tmp_path / "model.json"
    rep = tmp_path / "report"
    assert main(["identify", str(src), "--json", str(out), "--report", str(rep), "--no-diagnose"]) == 0
    m = load_model(out)
    assert m.method == "exact+oe" and m.fit["rms_um"] < 1.0
    assert {"index.html", "frf.png", "tracking.png", "model.json"} <= {p.name for p in rep.iterdir()}
    assert "poles: omega_n" in capsys.readouterr().out


def test_cli_says_when_the_poles_are_weakly_identifiable(tmp_path, capsys):
    """ZPETC cancels the closed loop (Table 4.2): the command line says the poles are weakly
    identifiable, with the valley of the objective; a plain feedback loop gets no such line."""
    import interpolators
    from identification.synthetic import table_3_2_program
    from vcnc.engine.machine import load_machine

    m = load_machine("ballscrew-zpetc")
    prog = interpolators.parse_program(table_3_2_program(moves=60))
    cap = m.simulate(interpolators.interpolate(prog, limits=m.limits, sample_time=m.sample_time), seed=0)
    cap.to_csv(tmp_path / "zpetc.csv")
    assert main(["identify", str(tmp_path / "zpetc.csv"), "--no-diagnose"]) == 0
    assert "poles weakly identifiable" in capsys.readouterr().out
    assert main(["identify", str(tmp_path / "zpetc.csv"), "--no-diagnose", "--json", str(tmp_path / "m.json")]) == 0
    valley = json.loads((tmp_path / "m.json").read_text())["fit"]["solver"]["identifiability"]
    assert valley["identifiable"] is False and valley["tolerance"] == 0.01
    src = tmp_path / "pid.csv"
    synthetic_capture(FADAL_PID_X, random_moves_reference(moves=40, seed=2), noise=2e-4, seed=1).to_csv(src)
    capsys.readouterr()
    assert main(["identify", str(src), "--no-diagnose"]) == 0
    assert "weakly" not in capsys.readouterr().out


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("t,x_ref,x\n0,0,0\n0.001,nan,0\n", "not finite"),
        ("t,x_ref,x,q\n0,0,0,1\n", "unknown column"),
    ],
)
def test_cli_bad_input_exit_2_no_output(tmp_path, capsys, text, match):
    src = tmp_path / "bad.csv"
    src.write_text(text)
    out = tmp_path / "model.json"
    assert main(["identify", str(src), "--json", str(out), "--report", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and match in err and "bad.csv" in err
    assert not out.exists() and not (tmp_path / "rep").exists()


def test_cli_too_short_exit_2(tmp_path, small_capture, capsys):
    src = tmp_path / "short.csv"
    small_capture.slice(0, 200).to_csv(src)
    assert main(["identify", str(src), "--json", str(tmp_path / "m.json")]) == 2
    assert "only 200 samples; identification needs at least 250" in capsys.readouterr().err
    assert not (tmp_path / "m.json").exists()


def test_emps_real_data():
    """EMPS (README: closed loop about 20 Hz, tracking error RMS about 0.58 mm): the identified model
    predicts the estimation run within 2% of its tracking error and the validation run (force pulses,
    not modelled) within 20%."""
    from vcnc.capture import read_capture

    est = read_capture(EMPS / "DATA_EMPS.mat")
    m = identify(est, diagnose=False)
    assert 15.0 < m.poles["omega_n_hz"] < 25.0
    track = np.sqrt(np.mean((est.reference[:, 0] - est.measured[:, 0]) ** 2)) * 1e3
    assert 500 < track < 650
    assert m.fit["rms_um"] < 0.02 * track
    val = read_capture(EMPS / "DATA_EMPS_PULSES.mat")
    e = val.measured[:, 0] - m.simulate(val.reference[:, 0], sample_time=val.sample_time)
    assert np.sqrt(np.mean(e**2)) * 1e3 < 0.2 * track
    json.dumps(m.to_dict())


def test_cli_says_when_a_pole_sits_on_the_box_the_nyquist_frequency_of_a_slow_record(tmp_path, capsys):
    """chevalier-pdf's x axis (a pair near 172 Hz, simulated at 0.25 ms) logged every 3 ms, as a control logging
    slower than its loop: the box of thesis Sec. 4.3 ends at the record's Nyquist frequency, 166.7 Hz, and the
    fit sits on it; the command line says that the loop may be faster than the record resolves."""
    import toolpaths
    import vcnc

    m = vcnc.machine("chevalier-pdf")
    cap = m.simulate(vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(60, 10, 12000, seed=1)), m))
    q = round(0.003 / cap.sample_time)
    slow = Capture(t=cap.t[::q] - cap.t[0], axes=("x",), reference=cap.reference[::q, :1],
                   measured=cap.measured[::q, :1], meta={"source": "logged every 3 ms"})
    slow.to_csv(tmp_path / "slow.csv")
    assert main(["identify", str(tmp_path / "slow.csv"), "--no-diagnose"]) == 0
    out = capsys.readouterr().out.replace("\n    ", " ")  # its lines unwrapped (wrapped at 100 columns)
    assert ("warning: omega_n 166.7 Hz sits on the upper bound of its box, the record's Nyquist frequency "
            "(166.7 Hz at Ts = 0.003 s): the loop may be faster than this record resolves") in out
    # the same axis logged every 0.25 ms is resolved: no pole on a bound, no warning
    cap.select_axes(("x",)).to_csv(tmp_path / "fast.csv")
    assert main(["identify", str(tmp_path / "fast.csv"), "--no-diagnose"]) == 0
    assert "warning:" not in capsys.readouterr().out


def test_the_weak_poles_line_says_when_the_refinement_left_the_equation_errors_range():
    """The valley is the equation error's, around its own solution: when the output-error refinement moves
    the poles outside it (simwild saw omega_n 36 Hz printed beside a range of 95-112 Hz), the line names the
    equation error's solution and says so; inside it, the line does not."""
    from types import SimpleNamespace

    from vcnc.commands.identify import weak_poles_line

    valley = {"tolerance": 0.01, "identifiable": False, "omega_n_hz": [94.6, 112.0], "zeta": [0.3, 0.5],
              "p_hz": [0.5, 1.5]}
    ee = {"omega_n_hz": 100.0, "zeta": 0.4, "p_hz": 1.0}
    moved = SimpleNamespace(fit={"solver": {"identifiability": valley, "poles": ee}}, method="exact+oe",
                            poles={"omega_n_hz": 36.0, "zeta": 0.4, "p_hz": 1.0})
    line = weak_poles_line(moved)
    assert "in the first stage, the equation error, the poles are pinned only to omega_n 94.6-112 Hz" in line
    assert "(its error within 1% of its minimum at omega_n 100 Hz, zeta 0.40, p 1 Hz)" in line
    assert "ended outside those ranges, at the poles above" in line and line.endswith("not its poles")
    inside = SimpleNamespace(fit=moved.fit, method="exact+oe", poles={"omega_n_hz": 101.0, "zeta": 0.4, "p_hz": 1.0})
    assert "outside those ranges" not in weak_poles_line(inside) and "too little excitation" in weak_poles_line(inside)


def test_a_stated_unit_is_not_taken_for_metres(tmp_path, capsys, small_capture):
    """A 0.5 um move read with --unit um is refused as too small, not as metres (a PI piezo record)."""
    small = _cap(small_capture.reference[:, 0] / 20000, small_capture.measured[:, 0] / 20000)
    with pytest.raises(IdentificationError, match="look like metres"):
        identify(small, diagnose=False)
    src = tmp_path / "piezo.csv"
    dataclasses.replace(small, reference=small.reference * 1000, measured=small.measured * 1000).to_csv(src)
    assert main(["identify", str(src), "--unit", "um", "--no-diagnose"]) == 2
    err = capsys.readouterr().err
    span_mm = float(np.ptp(small.reference))
    assert f"too small a motion to identify on axis 'x': the reference spans {span_mm:.4g} mm" in err
    assert "(unit um given)" in err and "metres" not in err
