"""An effect that the held-out folds accept and the whole record may refuse (diagnosis._worse_on_the_record).

The SINUMERIK trace of session 28 in small: a reduced model with large Coulomb levels (d0, d1 = +-4000 mm/s^2,
switched on the sign of the simulated velocity) whose axis rests 4 s before its first move, recorded at 1 ms. The
truth adds a position-periodic load (1500, 800 mm/s^2, period 2 mm) and rests through the idle stretch (stiction
holds it against the load there). The model of the load pushes the model at rest, its Coulomb levels switch on and
it moves in the idle stretch (about a second, until its integral action settles it), which the held-out folds trim.
The held-out error falls by 92 %; whether the error over all samples rises by the 25 % that refuses the effect
depends on how far the model at rest moves.

That distance is set by the mean of the refitted Coulomb levels, (d0 + d1)/2, and nothing in the active samples
determines it: once the load has set the model in motion the friction is d0 or d1, never 0 again, and a constant
part of the disturbance w passes G_dist = s/(s^3 + a1 s^2 + a2 s + a3) as zero
(test_the_active_samples_do_not_determine_the_coulomb_mean). The joint refit leaves it where the finite-difference
noise of the trust-region steps carries it: d0 - d1 = 7833..7838 mm/s^2 on every run, the mean from -7695 to
+18654 mm/s^2 (noise seeds 1-4, the load's first coefficient changed by +-1e-9, 1 or 2 threads;
/tmp/envfix34/lottery.py of session 34), the whole-record RMS 15.11 -> 9.96 .. 38.17 um, refused on session 33's
machine and accepted on session 34's. The end-to-end test therefore asserts the rule, whichever way the refit lands,
and the refusal's wording is checked on the record of a run that lands as session 33's did.
"""

from __future__ import annotations

import numpy as np
import pytest

from identification.augmented import augment
from identification.diagnosis import diagnose_report, format_before_after, refusal_lines
from identification.effects import PositionPeriodic
from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.capture import Capture

T = 0.001


def _capture_and_model() -> tuple[Capture, ReducedAxisModel]:
    moves = random_moves_reference(moves=12, span=10.0, feed=100.0, acceleration=1000.0, sample_time=T, dwell=0.3,
                                   seed=3)
    idle = int(4.0 / T)
    xr = np.concatenate([np.full(idle, moves[0]), moves])
    reduced = ReducedAxisModel(parameters=dict(FADAL_PID_X, d0=4000.0, d1=-4000.0), sample_time=T)
    load = PositionPeriodic(period=2.0, coefficients=((1500.0, 800.0),))
    x = augment(reduced, [load]).simulate(xr)
    x[:idle] = xr[0]  # the truth rests (stiction holds it against the load), the model of the load moves
    x = x + np.random.default_rng(1).normal(0.0, 0.3e-3, x.size)
    cap = Capture(t=np.arange(xr.size) * T, axes=("x",), reference=xr[:, None], measured=x[:, None],
                  meta={"source": "test"})
    return cap, reduced


def _rms_um(error_mm: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(error_mm)))) * 1e3


def test_the_whole_record_decides_an_effect_the_held_out_folds_accept():
    cap, reduced = _capture_and_model()
    rep = diagnose_report(cap, reduced, axis="x")
    first = rep.rounds[0]
    assert first["best"] == "position_periodic"
    assert first["gain_pct"] == pytest.approx(92.2, abs=2.0)  # the held-out test alone would take it
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    before = _rms_um(reduced.simulate(xr) - x)
    assert before == pytest.approx(15.11, rel=0.02)
    text = format_before_after(rep.model)
    worse = (first.get("worse_on_the_record_um") or {}).get("position_periodic")
    if worse is None:
        # accepted: the final model does not raise the whole record's error by the 25 % a refusal needs
        assert first["accepted"] == "position_periodic"
        assert _rms_um(rep.model.simulate(xr) - x) < 1.25 * before
        assert not refusal_lines(rep.model.validation)
    else:
        b, a = worse
        assert b == pytest.approx(before, rel=1e-6)
        assert a - b >= 0.25 * b and a - b >= 0.05
        assert first["accepted"] is None and rep.model.effects == []
        held = first["refitted"]["position_periodic"]["validation_rms_um"]
        assert "diagnosis: no effect is kept; the reduced model stands" in text
        assert (f"refused: position_periodic lowers the held-out error {first['current_validation_rms_um']:.4g} -> "
                f"{held:.4g} um, but raises the RMS over all the record's samples {b:.4g} -> {a:.4g} um") in text
    assert "no effect lowers the held-out error significantly" not in text


def test_the_active_samples_do_not_determine_the_coulomb_mean():
    # the refits of the scenario above: d0 - d1 = 7834 mm/s^2 and means -6731 (session 34) and +18654 mm/s^2
    # (session 33's refusal, 38.17 um over all samples); the load of the truth
    cap, _ = _capture_and_model()
    xr, idle = cap.reference[:, 0], int(4.0 / T)
    load = PositionPeriodic(period=2.0, coefficients=((1500.0, 800.0),))
    runs = [augment(ReducedAxisModel(parameters=dict(FADAL_PID_X, d0=mean + 3917.0, d1=mean - 3917.0),
                                     sample_time=T), [load]).simulate(xr) for mean in (-6731.0, 0.0, 18654.0)]
    for x in runs[1:]:
        assert _rms_um(x[idle:] - runs[0][idle:]) < 0.01  # the active samples: the same prediction
    at_rest = [_rms_um(x[:idle] - xr[0]) for x in runs]
    assert at_rest[2] > 3.0 * at_rest[0] > 9.0 * at_rest[1]  # the idle stretch: the mean decides


def test_an_effect_the_whole_record_refuses_is_named_with_both_errors():
    # the first round of the scenario above on session 34's machine with the load's first coefficient changed by
    # 1e-9 (/tmp/envfix34/lottery.py 1 1e-9): the refit's Coulomb mean landed at +18654 mm/s^2, as on session 33's
    rounds = [{"refitted": {"position_periodic": {"validation_rms_um": 1.53704}},
               "current_validation_rms_um": 19.4425,
               "worse_on_the_record_um": {"position_periodic": [15.1065, 38.1704]}}]
    assert refusal_lines({"rounds": rounds}) == [
        "refused: position_periodic lowers the held-out error 19.44 -> 1.537 um, but raises the RMS over all the "
        "record's samples 15.11 -> 38.17 um: it moves the model where the axis rests (the idle stretches the held-out "
        "folds trim)"]


def test_an_effect_a_fold_contradicts_is_named_with_the_fold():
    # the record of a TNCscope trace's first round (tncscope_tum_FeedStep150_N300_H55): a 55 Hz time-periodic load
    # lowered the pooled held-out error by 47 % and raised fold 4's from 0.596 to 0.786 um
    rounds = [{"refitted": {"time_periodic": {"validation_rms_um": 1.12769, "fold_rms_um": [1.125, 1.317, 1.239,
                                                                                             0.78642]},
                            "drift": {"validation_rms_um": 2.5, "fold_rms_um": [2.5, 2.5, 2.5, 2.5]}},
               "current_validation_rms_um": 2.13258, "contradicted_by_folds": {"time_periodic": [4], "drift": [1]}}]
    assert refusal_lines({"rounds": rounds}) == [
        "refused: time_periodic lowers the held-out error 2.133 -> 1.128 um, but raises that of fold 4 to 0.7864 um, "
        "by as much as a gain must lower it: what it fits does not hold over the whole record (an effect present in "
        "part of it, or fitted to something else)"]  # the drift, worse on the pooled folds too, is no refusal
    assert refusal_lines({"rounds": rounds}, "mdeg")[0].startswith(
        "refused: time_periodic lowers the held-out error 2.133 -> 1.128 mdeg")
