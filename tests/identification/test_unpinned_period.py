"""A position-periodic force over a travel that covers its period about once: the period is not pinned.

ident_fuzz seed 51 case 1 (ballscrew-ppc's x, a 5 mm load, 32 moves of +/-3 mm, 5.67 mm of travel) named a period
of 8.33 mm (session 34's machine), 7.12 mm with two harmonics (session 35's): over one period of travel any smooth
force of position is fitted by a long period and its harmonics as well as by the true one (the refits from 5 mm
and from 7.12 mm with one harmonic both end at 5.95 mm, 0.617 um on the active samples, the two-harmonic ones at
7.31 and 8.33 mm, 0.608 and 0.615 um). The period is now reported as not pinned by the record
(``EffectRecord.unpinned``, :data:`identification.effects.position_periodic.MIN_PERIODS_COVERED`), never as a
measured number.
"""

from __future__ import annotations

import vcnc
from identification import identify
from identification.diagnosis import format_before_after
from identification.effects import PositionPeriodic
from identification.effects.position_periodic import MIN_PERIODS_COVERED


def test_a_period_is_pinned_only_by_a_travel_that_covers_it_one_and_a_half_times():
    e = PositionPeriodic(period=5.0, coefficients=((300.0, 0.0),))
    assert e.unpinned(travel=MIN_PERIODS_COVERED * 5.0, duration=1.0) == {}
    assert e.unpinned(travel=20.0, duration=1.0) == {}
    why = e.unpinned(travel=5.67, duration=1.0)
    assert list(why) == ["period_mm"]
    assert "5.67 mm" in why["period_mm"] and "1.1 times" in why["period_mm"]


def test_a_travel_of_about_one_period_reports_the_period_as_not_pinned():
    """Hand-made: ballscrew-ppc's x with its 5 mm position-periodic load, 0.1 um noise, 30 random moves of +/-3 mm
    (5.8 mm of travel). Before, the diagnosis named a period of 10.89 mm with three harmonics as measured. Whatever
    period the refit ends at on a platform, the travel covers fewer than 1.5 of any period the force can be fitted
    with here but a harmonic below 3.9 mm, so the record pins none: the model names the force, and its period is
    reported as not pinned, with why, in the record and on the command line."""
    import toolpaths

    m = vcnc.machine("ballscrew-ppc").with_axis_options("x", noise=1e-4, encoder=None)
    m = m.with_effect("x", "position_periodic", {"period_mm": 5.0})
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(30, 3.0, 9000, seed=3)), m)
    cap = m.simulate(sp, seed=3).select_axes(("x",))
    travel = float(cap.measured.max() - cap.measured.min())
    assert travel < MIN_PERIODS_COVERED * 5.0
    model = identify(cap, axis="x")
    pp = [e for e in model.effects if e.name == "position_periodic"]
    assert pp, model.validation["rounds"]
    period = pp[0].parameters["period_mm"]
    assert period > travel / MIN_PERIODS_COVERED  # no shorter period (a harmonic) was named instead
    assert "period_mm" in pp[0].unpinned
    assert f"{travel:.4g} mm" in pp[0].unpinned["period_mm"]
    assert "not pinned by the record: period_mm" in pp[0].summary
    text = format_before_after(model)
    assert f"not pinned: position_periodic period_mm {period:.4g} is one of many values that fit" in text
    # the model file keeps it
    saved = [e for e in model.to_dict()["effects"] if e["name"] == "position_periodic"]
    assert saved[0]["unpinned"] == dict(pp[0].unpinned)
