"""Record shapes a user brings: identify finishes near the recording's floor, or says plainly why it cannot.

The truth is the exact reduced model of the thesis' PID Fadal x axis (``FADAL_PID_X``, Table 3.4: omega_n 33.0 Hz,
zeta 0.447, p 1.17 Hz) run at 1 ms (the loop) on random moves, its measured position with 0.5 um white noise and a
1 um encoder: the floor of any prediction is sqrt(0.5^2 + 1/12) = 0.577 um RMS.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import toolpaths
import vcnc
from identification import identify
from identification.capture_checks import through_changes
from identification.diagnosis import before_after_rows, format_before_after
from identification.residual import analyse
from identification.substeps import simulate_record
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.capture import Capture
from vcnc.core.errors import IdentificationError

LOOP_S = 0.001
FLOOR_UM = math.sqrt(0.5 ** 2 + 1 / 12)
TRUE_POLES = {"omega_n_hz": 33.0, "zeta": 0.4468, "p_hz": 1.1729}


def _recording(*, logged_s: float = LOOP_S, moves: int = 10, span: float = 10.0, hold: int = 1,
               axis: str = "x") -> Capture:
    """The truth's record logged every ``logged_s`` (a multiple of the loop's 1 ms), the reference held over
    ``hold`` loop samples (an interpolator updating every ``hold`` ms)."""
    xr = random_moves_reference(moves=moves, span=span, feed=100.0, acceleration=1000.0, sample_time=LOOP_S,
                                dwell=0.1, seed=3)
    if hold > 1:
        xr = np.repeat(xr[::hold], hold)[:xr.size]
    x = simulate_record(FADAL_PID_X, xr, LOOP_S)
    q = round(logged_s / LOOP_S)
    xr, x = xr[::q], x[::q]
    x = np.round((x + np.random.default_rng(1).normal(0.0, 0.5e-3, x.size)) / 1e-3) * 1e-3
    return Capture(t=np.arange(xr.size) * logged_s, axes=(axis,), reference=xr[:, None], measured=x[:, None],
                   meta={"source": "shape"})


def _poles_within(poles: dict, rel: float) -> bool:
    return all(abs(poles[k] / v - 1.0) <= rel for k, v in TRUE_POLES.items())


def test_an_ipo_rate_record_is_fitted_near_its_floor_and_its_report_states_one_error():
    # 4 ms: the fit and the diagnosis both predict it at 4 sub-steps a sample, so the table's error over all
    # samples is the fit's (before: the diagnosis simulated on the 4 ms grid and stated another)
    cap = _recording(logged_s=0.004, moves=20)
    model = identify(cap, axis="x")
    assert model.fit["substeps"] == 4
    assert _poles_within(model.poles, 0.02)
    assert model.fit["rms_um"] == pytest.approx(0.583, rel=0.02)
    assert model.fit["rms_um"] < 1.05 * FLOOR_UM
    rows = before_after_rows(model)
    assert rows[0]["record_rms_um"] == pytest.approx(model.fit["rms_um"], rel=1e-6)
    assert model.effects == []
    assert "all simulated as the fit predicts the record, on 4 sub-steps a sample" in format_before_after(model)
    # and the report figure's residual (identification.residual.analyse) is the same prediction
    residual = analyse(model, cap.reference[:, 0], cap.measured[:, 0], 0.004)
    assert residual.metrics()["simulation"]["rms_um"] == pytest.approx(model.fit["rms_um"], rel=1e-6)


def test_an_8_ms_record_is_fitted_at_8_sub_steps():
    cap = _recording(logged_s=0.008, moves=20)
    model = identify(cap, axis="x", diagnose=False)
    assert model.fit["substeps"] == 8
    assert _poles_within(model.poles, 0.03)
    assert model.fit["rms_um"] == pytest.approx(0.755, rel=0.03)  # the spline between 8 ms samples: 1.3x the floor


def test_a_short_record_is_refused_with_the_samples_it_needs():
    cap = _recording(logged_s=0.004, moves=20)  # a slow logger: 4 ms
    with pytest.raises(IdentificationError, match=r"only 249 samples; identification needs at least 250 \(the thesis' "
                       r"test has 22,000 at 1 ms\)"):
        identify(cap.slice(0, 249), axis="x")


def test_a_record_short_in_the_loops_frame_says_how_many_samples_were_dropped():
    # fadal-smc logged at 4 ms for 250 samples: the axis has not settled at the start, the loop's frame drops 119
    # samples, and the refusal said "only 131 samples" to a user who gave 250
    m0 = vcnc.machine("fadal-smc")
    m = m0.with_axis_options("x", noise=3e-4, encoder=2.5e-4)
    feed = round(0.5 * 60 * m.axis("x").limits.velocity)
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(60, 3.0, feed, seed=1, axes=("x",))), m)
    cap = m.simulate(sp, seed=1).select_axes(("x",))
    s = round(4e-3 / m.sample_time)
    rec = Capture(t=cap.t[::s][:250], axes=("x",), reference=cap.reference[::s][:250], measured=cap.measured[::s][:250])
    with pytest.raises(IdentificationError, match=r"only 131 samples; identification needs at least 250 \(the thesis' "
                       r"test has 22,000 at 1 ms\); 119 of the record's 250 samples were dropped before the loop's "
                       r"frame starts \(the reference's dead time and a start with the axis not yet settled\)"):
        identify(rec, axis="x", diagnose=False)


def test_a_record_at_the_floor_is_fitted_and_validated_on_its_folds():
    # 250 samples of a 4 ms logger (1 s, the first 5 of 20 moves): the poles as from the whole record, the RMS
    # near the floor, and the diagnosis' validation cuts them into 2 folds that move both ways
    cap = _recording(logged_s=0.004, moves=20).slice(0, 250)
    model = identify(cap, axis="x")
    assert model.fit["substeps"] == 4
    assert _poles_within(model.poles, 0.01)
    assert model.fit["rms_um"] == pytest.approx(0.630, rel=0.03)
    assert len(model.validation["folds"]) == 2
    assert model.validation["samples"] == {"identification": 250, "validation": 250, "record": 250}


def test_an_axis_that_barely_moves_is_told_so_not_that_its_channel_is_another():
    cap = _recording(span=0.005)
    with pytest.raises(IdentificationError) as err:
        identify(cap, axis="x")
    text = str(err.value)
    assert ("the axis barely moves: its commanded position spans 7.156 um, 7.16 times the measured position's "
            "resolution (1 um), which its velocity is made of") in text
    assert "it is not this axis' measured position" not in text


def test_a_constant_offset_between_the_channels_is_removed():
    cap = _recording()
    shifted = Capture(t=cap.t, axes=("x",), reference=cap.reference, measured=cap.measured + 0.5,
                      meta={"source": "shape"})
    model = identify(shifted, axis="x", diagnose=False)
    off = model.fit["offset"]
    assert off["applied"] and off["offset_mm"] == pytest.approx(0.5, abs=2e-5)
    assert off["rms_without_um"] > 100.0
    assert model.fit["rms_um"] < 1.02 * FLOOR_UM
    assert _poles_within(model.poles, 0.02)


def test_a_reference_that_lags_the_measurement_gets_a_negative_dead_time():
    # feedforward recorded after the loop used it (or a trace whose reference channel is logged late): 20 ms
    cap = _recording()
    k = 20
    late = np.concatenate([np.full(k, cap.reference[0, 0]), cap.reference[:-k, 0]])
    model = identify(Capture(t=cap.t, axes=("x",), reference=late[:, None], measured=cap.measured,
                             meta={"source": "shape"}), axis="x", diagnose=False)
    assert model.delay_s == pytest.approx(-0.020, abs=0.0015)
    assert model.fit["rms_um"] < 1.05 * FLOOR_UM
    assert _poles_within(model.poles, 0.03)


def test_a_reference_held_in_ipo_steps_is_no_step_command():
    # a 4 ms interpolation cycle logged at 1 ms: the reference moves 0.4 mm every fourth sample at 100 mm/s, which
    # the jump check took for a step command ("a step-response test") before
    cap = _recording(hold=4)
    model = identify(cap, axis="x", diagnose=False)
    assert model.fit["rms_um"] < 1.02 * FLOOR_UM
    assert _poles_within(model.poles, 0.01)


def test_through_changes_joins_the_first_samples_of_the_held_values_and_keeps_a_rest():
    xr = np.array([0.0] * 6 + [1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10] + [10.0] * 6
                  + [11, 11, 12, 12])
    got = through_changes(xr)
    assert got[:6].tolist() == [0.0] * 6  # the rest before the first change: its last sample is a knot
    assert got[6:12].tolist() == [1.0, 1.5, 2.0, 2.5, 3.0, 3.5]
    assert got[24:32].tolist() == [10.0] * 8  # the held 10 and the rest after it
    assert got[32:].tolist() == [11.0, 11.5, 12.0, 12.0]
    smooth = np.linspace(0.0, 1.0, 50)
    assert np.array_equal(through_changes(smooth), smooth)  # a reference that changes every sample: as recorded


def test_a_rotary_axis_reports_its_errors_in_mdeg():
    cap = _recording(span=90.0, axis="c")
    model = identify(cap, axis="c")
    assert model.fit["rms_um"] < 1.02 * FLOOR_UM  # (the fit's field name; mdeg on a rotary axis)
    text = format_before_after(model)
    assert text.splitlines()[0].endswith("[mdeg]")
    residual = next(line for line in text.splitlines() if line.startswith("residual: "))
    assert "mdeg" in residual and " um" not in residual
