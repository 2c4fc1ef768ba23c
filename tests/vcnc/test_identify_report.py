"""The HTML report of ``vcnc identify --report`` says what the summary says (realtrace11, session 35).

The report's table showed the fit's own number alone, "identified model 77.85", where the summary gives the
prediction simulated from rest beside it (an ODrive joint-motor record whose fit also fitted the state at its
first sample: 77.85 mdeg with it, 3146 mdeg from rest); its figure left out the datum offset the fit removed. The
inputs are written here: the thesis' PID x axis (``identification.synthetic.FADAL_PID_X``, Table 3.4) on a 1 mm
move, the axis held 0.5 mm off its reference for its first 0.5 s, and the ODrive record's numbers by hand.
"""

from __future__ import annotations

import html

import numpy as np

from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X
from vcnc.capture import Capture
from vcnc.commands.identify import (
    baseline_lines,
    build_report,
    fit_lines,
    from_rest_rms_um,
    predicted_record,
    prediction_line,
    prediction_rows,
)

T = 1e-3


def _capture(offset_mm: float = 0.0) -> Capture:
    t = np.arange(2000) * T
    xr = np.where(t < 1.0, 0.0, -np.minimum(t - 1.0, 0.5) * 2.0)
    x = xr.copy()
    x[1:500] = -0.5
    return Capture(t=t, axes=("x",), reference=xr[:, None], measured=(x + offset_mm)[:, None],
                   meta={"source": "test"})


def _started_model(fit: dict | None = None) -> ReducedAxisModel:
    fit = fit or {"rms_um": 77.85, "max_um": 1134.0,
                  "initial_state": {"state_mm": [-0.3, -458.0, -4234.0], "first_sample": 0,
                                    "start_response_max_um": 3307.0}}
    return ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=T, fit=fit)


def test_the_report_table_gives_the_from_rest_prediction_beside_the_start_state_fit():
    cap, model = _capture(), _started_model()
    rest = from_rest_rms_um(cap, model, "x")
    e = cap.measured[:, 0] - model.simulate(cap.reference[:, 0])
    rows = prediction_rows(cap, model, "x", rest)
    assert [r[0] for r in rows] == ["identified model, the state at its first sample fitted",
                                    "identified model simulated from rest (as vcnc simulate and vcnc compare predict)",
                                    "tracking error itself"]
    assert rows[0][1:] == [77.85, 1134.0]
    assert rows[1][1] == rest and abs(rows[1][2] - float(np.max(np.abs(e))) * 1e3) < 1e-9
    assert rest > 3 * 77.85  # the axis held off its reference: worse from rest than the fit's own number
    # a fit without a start state: its own number, one row, as the summary
    plain = _started_model({"rms_um": 12.5, "max_um": 30.0, "equation_error": {"rms_um": 14.0, "max_um": 33.0}})
    assert [r[:3] for r in prediction_rows(cap, plain, "x", 12.5)[:2]] == [["identified model", 12.5, 30.0],
                                                                           ["equation-error solution", 14.0, 33.0]]


def test_the_report_says_the_summary_lines_word_for_word():
    cap, model = _capture(), _started_model()
    rest = from_rest_rms_um(cap, model, "x")
    baseline = baseline_lines(cap, model, "x", rest)
    page = build_report(cap, model, "x", baseline, rest).html()
    lines = fit_lines(model, rest)
    assert lines[0] == prediction_line(model, rest)
    assert f"simulated from rest, as the table below, vcnc simulate and vcnc compare predict, rms {rest:.4g} um" \
           in lines[0]
    for line in lines + baseline:
        assert f"<p>{html.escape(line)}</p>" in page, line
    assert f"<td>{rest:.4g}</td>" in page  # the from-rest row of the table


def test_the_predicted_record_puts_back_the_removed_datum_offset():
    # a linear scale logged 2.5 mm off the commanded datum: the fit removed it, the prediction carries it again
    cap = _capture(offset_mm=2.5)
    model = _started_model(dict(_started_model().fit, offset={"applied": True, "offset_mm": 2.5}))
    xp = predicted_record(cap, model, "x")
    assert np.allclose(xp - 2.5, model.simulate(cap.reference[:, 0]), atol=1e-12)
    assert abs(from_rest_rms_um(cap, model, "x") - from_rest_rms_um(_capture(), _started_model(), "x")) < 1e-9


def test_the_report_heads_the_diagnosis_table_as_the_summary_and_names_rotary_units():
    # a rotary axis: positions in deg, errors in mdeg, the disturbance parameters in deg/s^2 (they read mm/s^2)
    t = np.arange(4000) * T
    xr = 5.0 * np.sin(np.pi * t)  # deg, both ways
    x = np.concatenate([np.zeros(5), xr[:-5]])  # five samples behind
    cap = Capture(t=t, axes=("a",), reference=xr[:, None], measured=x[:, None], meta={"source": "test"})
    validation = {"record_rms_um": [3146.0], "rms_before_um": 1050.0, "max_before_um": 3224.0,
                  "identification_rms_before_um": 3166.0, "identification_max_before_um": 4003.0}
    model = ReducedAxisModel(parameters=dict(FADAL_PID_X), sample_time=T, fit=_started_model().fit,
                             validation=validation)
    rest = from_rest_rms_um(cap, model, "a")
    page = build_report(cap, model, "a", baseline_lines(cap, model, "a", rest), rest).html()
    assert "<td>deg/s^2</td>" in page and "mm/s^2" not in page
    head = "".join(f"<th>{h}</th>" for h in ("model", "all RMS", "ident RMS", "ident max", "valid RMS", "valid max"))
    assert head in page and "identification_rms_um" not in page
    assert "<tr><td>reduced model</td><td>3146</td><td>3166</td><td>4003</td><td>1050</td><td>3224</td></tr>" in page
