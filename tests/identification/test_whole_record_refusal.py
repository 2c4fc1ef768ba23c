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
machine and accepted on session 34's. The rule now judges the model at the mean the whole record puts it
(diagnosis.coulomb_mean_at_rest, coulomb35): on the same runs (/tmp/coulomb35/lottery.py) the mean is set to
-801 .. -806 mm/s^2 (the load at the rest position is +800 mm/s^2), the final model predicts all samples with
1.147 .. 1.155 um and the idle stretch with 0.33 um, and the effect is accepted every time.
"""

from __future__ import annotations

import numpy as np
import pytest

from identification.augmented import augment
from identification.bounds import as_bounds
from identification.diagnosis import (
    coulomb_mean_at_rest,
    diagnose_report,
    format_before_after,
    refusal_lines,
    with_coulomb_mean,
)
from identification.effects import PositionPeriodic, TimePeriodic
from identification.reduced_model import ReducedAxisModel
from identification.searches import Data
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.capture import Capture

T = 0.001


def capture_and_model(idle_s: float = 4.0, load=None, seed: int = 1) -> tuple[Capture, ReducedAxisModel]:
    moves = random_moves_reference(moves=12, span=10.0, feed=100.0, acceleration=1000.0, sample_time=T, dwell=0.3,
                                   seed=3)
    idle = int(idle_s / T)
    xr = np.concatenate([np.full(idle, moves[0]), moves])
    reduced = ReducedAxisModel(parameters=dict(FADAL_PID_X, d0=4000.0, d1=-4000.0), sample_time=T)
    load = load or PositionPeriodic(period=2.0, coefficients=((1500.0, 800.0),))
    x = augment(reduced, [load]).simulate(xr)
    x[:idle] = xr[0]  # the truth rests (stiction holds it against the load), the model of the load moves
    x = x + np.random.default_rng(seed).normal(0.0, 0.3e-3, x.size)
    cap = Capture(t=np.arange(xr.size) * T, axes=("x",), reference=xr[:, None], measured=x[:, None],
                  meta={"source": "test"})
    return cap, reduced


def rms_um(error_mm: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(error_mm)))) * 1e3


def test_the_whole_record_decides_an_effect_the_held_out_folds_accept():
    cap, reduced = capture_and_model()
    rep = diagnose_report(cap, reduced, axis="x")
    first = rep.rounds[0]
    assert first["best"] == "position_periodic"
    assert first["gain_pct"] == pytest.approx(92.2, abs=2.0)  # the held-out test alone would take it
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    before = rms_um(reduced.simulate(xr) - x)
    assert before == pytest.approx(15.11, rel=0.02)
    # judged at the Coulomb mean the record puts it, the model holds at rest: accepted on any platform, wherever the
    # joint refit left the mean (9.96 .. 38.17 um over all samples before coulomb35)
    assert first["accepted"] == "position_periodic" and "worse_on_the_record_um" not in first
    assert rep.effects == ["position_periodic"]
    after = rep.model.simulate(xr) - x
    assert rms_um(after) < 0.2 * before  # 1.15 um
    assert rms_um(after[: int(4.0 / T)]) < 1.0  # the idle stretch: 0.33 um
    mean = 0.5 * (rep.model.parameters["d0"] + rep.model.parameters["d1"])
    assert mean == pytest.approx(-800.0, abs=100.0)  # it cancels the load at the rest position, +800 mm/s^2
    text = format_before_after(rep.model)
    assert not refusal_lines(rep.model.validation)
    assert "no effect lowers the held-out error significantly" not in text


def test_an_effect_that_moves_the_model_at_rest_whatever_the_mean_is_refused():
    """The axis of the scenario above at rest 12 s before its moves, the truth with a 4 Hz load of 1500 mm/s^2 that
    stiction holds at rest: the model of the load oscillates at rest, which no Coulomb mean cancels. The held-out
    folds take it (24.48 -> 4.74 um, coulomb35's machine), the whole record refuses it (13.78 -> 18.89 um; 17.22 um
    is the 25 % line), and the reduced model stands."""
    cap, reduced = capture_and_model(idle_s=12.0, load=TimePeriodic(period=0.25, coefficients=((1500.0, 0.0),)))
    rep = diagnose_report(cap, reduced, axis="x")
    first = rep.rounds[0]
    assert first["best"] == "time_periodic" and first["gain_pct"] > 50.0
    b, a = first["worse_on_the_record_um"]["time_periodic"]
    assert b == pytest.approx(rms_um(reduced.simulate(cap.reference[:, 0]) - cap.measured[:, 0]), rel=1e-6)
    assert a - b >= 0.25 * b and a - b >= 0.05
    assert first["accepted"] is None and rep.effects == []
    assert refusal_lines(rep.model.validation)[0].startswith("refused: time_periodic lowers the held-out error")


def _data(cap: Capture, idle: int) -> Data:
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    active = np.arange(x.size) >= idle
    return Data(xr=xr, x=x, T=T, train=active, valid=active, bounds=as_bounds(None, T), active=active)


@pytest.mark.parametrize("load", ["position", "time"])
def test_the_coulomb_mean_at_rest_does_not_depend_on_where_the_refit_left_it(load):
    """The model judged on the whole record predicts it alike whatever the joint refit's Coulomb mean: from the three
    means of session 34's lottery (-6731, 0, +18654 mm/s^2) to one whole-record RMS within 0.1 %.

    position: the scenario above, its model with the load of the truth; the mean cancels the load at the rest
    position (+800 mm/s^2) and the whole record falls below the reduced model's 15.1 um, accepted whatever the mean.
    time: the same axis at rest 12 s before its moves, the truth with a 4 Hz load of 1500 mm/s^2 that stiction holds
    at rest; its model oscillates at rest whatever the mean (a mean cannot cancel a periodic force): 19.63 um over
    all samples against the reduced model's 13.78, refused whatever the mean (from 0 the mean stays: -412 mm/s^2
    predicts 0.05 % better)."""
    if load == "position":
        cap, reduced = capture_and_model()
        idle, effect = int(4.0 / T), PositionPeriodic(period=2.0, coefficients=((1500.0, 800.0),))
    else:
        idle, effect = int(12.0 / T), TimePeriodic(period=0.25, coefficients=((1500.0, 0.0),))
        cap, reduced = capture_and_model(idle_s=12.0, load=effect)
    data = _data(cap, idle)
    xr, x = cap.reference[:, 0], cap.measured[:, 0]
    before = rms_um(reduced.simulate(xr) - x)
    settled = [coulomb_mean_at_rest(with_coulomb_mean(augment(reduced, [effect]), mean), reduced, data)
               for mean in (-6731.0, 0.0, 18654.0)]
    means = [0.5 * (m.parameters["d0"] + m.parameters["d1"]) for m in settled]
    rms = [rms_um(m.simulate(xr) - x) for m in settled]
    # the whole record judged alike, whatever the refit's mean (a mean is moved only for a 0.1 % better prediction)
    assert max(rms) <= 1.001 * min(rms)
    for m in settled:
        assert m.parameters["d0"] - m.parameters["d1"] == pytest.approx(8000.0)  # the difference kept
    if load == "position":
        assert max(means) - min(means) < 50.0  # of a Coulomb level of 4000 mm/s^2
        assert means[0] == pytest.approx(-800.0, abs=100.0)
        assert rms[0] < 0.2 * before
    else:
        assert rms[0] > 1.25 * before  # the 25 % of the whole-record rule, at any mean


def test_the_active_samples_do_not_determine_the_coulomb_mean():
    # the refits of the scenario above: d0 - d1 = 7834 mm/s^2 and means -6731 (session 34) and +18654 mm/s^2
    # (session 33's refusal, 38.17 um over all samples); the load of the truth
    cap, _ = capture_and_model()
    xr, idle = cap.reference[:, 0], int(4.0 / T)
    load = PositionPeriodic(period=2.0, coefficients=((1500.0, 800.0),))
    runs = [augment(ReducedAxisModel(parameters=dict(FADAL_PID_X, d0=mean + 3917.0, d1=mean - 3917.0),
                                     sample_time=T), [load]).simulate(xr) for mean in (-6731.0, 0.0, 18654.0)]
    for x in runs[1:]:
        assert rms_um(x[idle:] - runs[0][idle:]) < 0.01  # the active samples: the same prediction
    at_rest = [rms_um(x[:idle] - xr[0]) for x in runs]
    assert at_rest[2] > 3.0 * at_rest[0] > 9.0 * at_rest[1]  # the idle stretch: the mean decides


def test_an_effect_the_whole_record_refuses_is_named_with_both_errors():
    # the first round of the scenario above on session 34's machine with the load's first coefficient changed by
    # 1e-9 (/tmp/envfix34/lottery.py 1 1e-9), before coulomb35: the refit's Coulomb mean landed at +18654 mm/s^2,
    # as on session 33's; the wording of a refusal holds whatever refuses
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
