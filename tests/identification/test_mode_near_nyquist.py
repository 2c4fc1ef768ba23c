"""A mode is named only where the record tells it from its Nyquist frequency (ident39).

Sampled every T, a mode of frequency f and decay rate sigma = 2 pi zeta f rings as the Nyquist alternation (-1)^n under
an envelope beating at f_N - f; the record resolves that beat only when the ringing lasts one of its periods,
f_N - f >= sigma (``identification.diagnosis.resolved_below_nyquist``)."""
import math

import pytest

from identification import identify
from identification.diagnosis import refusal_lines, resolved_below_nyquist


def test_a_mode_is_resolved_when_its_distance_to_nyquist_is_at_least_its_decay_rate():
    T = 2e-3  # f_N = 250 Hz
    # a 225 Hz mode at damping 0.045 decays at 63.6 1/s, 25 Hz below f_N: not resolved
    assert not resolved_below_nyquist(225.0, 0.045, T)
    # the same frequency undamped, and a lightly damped mode further below, are
    assert resolved_below_nyquist(225.0, 0.0, T)
    assert resolved_below_nyquist(100.0, 0.05, T)
    # the bound f_N / (1 + 2 pi zeta) on either side
    for zeta in (0.02, 0.1, 0.3):
        edge = 250.0 / (1.0 + 2.0 * math.pi * zeta)
        assert resolved_below_nyquist(edge * (1 - 1e-9), zeta, T)
        assert not resolved_below_nyquist(edge * (1 + 1e-9), zeta, T)
    # at or above Nyquist nothing is
    assert not resolved_below_nyquist(250.0, 0.0, T)
    assert not resolved_below_nyquist(300.0, 0.01, T)


def test_a_refused_mode_is_named_on_a_refused_line_with_its_reason():
    why = "its frequency 225 Hz (damping 0.045) lies 25 Hz below the record's Nyquist frequency 250 Hz, ..."
    validation = {"rounds": [{"current_validation_rms_um": 0.58, "unphysical": {"resonance": why},
                              "refitted": {"resonance": {"validation_rms_um": 0.32}}}]}
    assert refusal_lines(validation) == [f"refused: resonance lowers the held-out error 0.58 -> 0.32 um, but {why}"]
    # a refit that does not lower the held-out error is no refusal to report
    validation["rounds"][0]["refitted"]["resonance"]["validation_rms_um"] = 0.6
    assert refusal_lines(validation) == []


@pytest.mark.parametrize("step", [2, pytest.param(1, marks=pytest.mark.slow)])
def test_friction_at_reversals_is_no_mode_near_the_nyquist_frequency(step):
    """ident_fuzz seed 61 case 27: fadal-smc's x, 60 random moves over +/-30 mm, Coulomb friction and no mode. Logged
    every 2 ms it named a 225 Hz mode at damping 0.045 (0.9 of the 250 Hz Nyquist frequency), held out 0.58 -> 0.32 um;
    logged every 1 ms a 435 Hz one (0.87 of 500 Hz): a frequency that follows the record's sampling is the reduced
    model's friction at reversals, not a mode. No mode the record does not resolve is named: a round may accept one,
    and the backward check drops it, saying why."""
    from benchmarks.ident_fuzz import build, draw_case

    case = dict(draw_case(61, 27), step=step)
    assert (case["machine"], case["axis"], case["effects"]) == ("fadal-smc", "x", {})
    rec, _, _, _ = build(case)
    model = identify(rec, axis="x")
    T = model.sample_time
    assert T == pytest.approx(step * 1e-3)
    for e in model.effects:
        if e.name == "resonance":
            p = e["parameters"]
            assert resolved_below_nyquist(p["frequency_hz"], p["damping"], T)
    assert "resonance" not in [e.name for e in model.effects]
    for r in model.validation["rounds"]:
        if r.get("accepted") == "resonance" and not resolved_below_nyquist(r["resonance_frequency_hz"],
                                                                            r["resonance_damping"], T):
            dropped = model.validation["rounds"][-1]["dropped"]["resonance"]
            assert "less than its decay rate" in dropped["reason"]
