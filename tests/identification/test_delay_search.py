"""The diagnosis' delay search (identification.searches.search_delay) on captures where it missed the delay."""

from __future__ import annotations

import vcnc
from identification import identify


def test_two_sample_delay_the_reduced_model_took_as_a_lightly_damped_pair():
    """ident_fuzz seed 71 case 38, reduced: fadal-pid/x with a 2-sample delay (and its 5 um backlash). The reduced
    model took the delay's lag as a pair on its damping bound (zeta 0.2), which the delay made unstable (the current
    parameters with the delay diverged), and the regression's starts screened worse than the current model (before:
    delays 2 and 3 at 49.3 and 32.9 um against 17.5): the delay was never refitted and a 105 Hz "resonance" of
    damping 0.02 imitated it, held out as the best answer. The best regression starts are now refined by
    Gauss-Newton before they are ranked, and the neighbouring delays' starts go to the refit, which keeps the delay
    that predicts best: the 2-sample delay is named first and no mode."""
    import toolpaths

    m = (vcnc.machine("fadal-pid").with_axis_options("x", encoder=2.5e-4)
         .with_effect("x", "delay", {"samples": 2}).with_effect("x", "backlash", {"width_mm": 0.00508}))
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(46, 3.0, 9761, seed=1, axes=("x",))), m)
    cap = m.simulate(sp, seed=1).select_axes(("x",))
    model = identify(cap, axis="x")
    names = [e.name for e in model.effects]
    assert names[0] == "delay"
    assert model.effects[0].parameters["samples"] == 2
    assert "resonance" not in names


def test_an_element_without_parameters_of_its_own_faces_its_null_by_the_folds():
    """A whole-sample delay adds no fitted parameter to its null (the split form without it): the two are models of
    one size, judged by the held-out folds as they stand. A backlash adds its width: it must bring the relative gain
    too (DiagnosisOptions.min_gain)."""
    from identification.diagnosis import DiagnosisOptions, adds_no_parameter, beats_the_model_without
    from identification.effects import Backlash, Delay

    opt = DiagnosisOptions()
    delay, backlash = Delay(samples=1, sample_time=1e-3), Backlash(width=0.01)
    assert adds_no_parameter(delay) and not adds_no_parameter(backlash)
    null = (1.73, [1.67, 1.52, 1.86, 1.88])
    better = (1.54, [1.69, 1.34, 1.49, 1.67])  # 11 % lower pooled, lower on 3 of 4 folds
    assert beats_the_model_without(delay, null, better, opt)
    assert not beats_the_model_without(backlash, null, better, opt)
    # lower on half of the folds only, or by less than min_gain_um pooled, or one fold made worse by the gain
    assert not beats_the_model_without(delay, null, (1.60, [1.60, 1.40, 1.90, 1.90]), opt)
    assert not beats_the_model_without(delay, null, (1.70, [1.60, 1.50, 1.80, 1.86]), opt)
    assert not beats_the_model_without(delay, null, (1.50, [2.20, 1.00, 1.50, 1.50]), opt)


def test_one_sample_delay_on_a_loop_with_acceleration_feedforward():
    """ident_fuzz seed 71 case 29 and seed 51 case 38, reduced: fadal-smc/x (sliding-mode law, model-based
    feedforward) with a one-sample delay. The refitted split form without the delay imitates most of its lag (held
    out 1.71 um without, 1.44 um with it, from 4.31 um of the reduced model, on this capture), and the delay was
    refused for a gain under 25 % over its null although it predicts every held-out fold but one better; the same
    program on the machine without the delay predicts worse with one. It is named now."""
    import toolpaths

    m = (vcnc.machine("fadal-smc").with_axis_options("x", noise=3e-4, encoder=1e-3)
         .with_effect("x", "delay", {"samples": 1}))
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(36, 3.0, 4125, seed=1, axes=("x",))), m)
    cap = m.simulate(sp, seed=1).select_axes(("x",))
    model = identify(cap, axis="x")
    assert [e.name for e in model.effects][:1] == ["delay"]
    assert model.effects[0].parameters["samples"] == 1


def test_the_same_capture_without_the_delay_names_none():
    """The null rule's other side: the program and noise of test_one_sample_delay_on_a_loop_with_acceleration_
    feedforward on fadal-smc without the delay. A parameter-free element faces its null by the folds alone
    (diagnosis.beats_the_model_without): on this clean capture no delay is named (nor anything else; review36,
    seeds 1-3 of this program alike)."""
    import toolpaths

    m = vcnc.machine("fadal-smc").with_axis_options("x", noise=3e-4, encoder=1e-3)
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(36, 3.0, 4125, seed=1, axes=("x",))), m)
    cap = m.simulate(sp, seed=1).select_axes(("x",))
    assert [e.name for e in identify(cap, axis="x").effects] == []
