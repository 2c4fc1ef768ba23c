"""A disturbance whose equation-error coefficients predict the record worse than no effect is still refitted.

ident_fuzz seed 61 case 5: emps' x with an asymmetric viscous friction (asymmetry -0.387, 5.0 um of the measured
position), the reference logged 2 samples late. The search's starts (the equation error's coefficient and the
constrained start) screened 4.34 um, worse than the loop without the effect (2.58 um): the effect ranked 8th of 9 and
was not among the 3 refitted, and nothing was named. Refitted from any start, it predicts the held-out folds
2.67 -> 0.40 um. Each start now takes its coefficients by output error when that screens better
(``SearchContext.output_error_coefficients``).
"""

from __future__ import annotations

import numpy as np

import vcnc
from identification import identify


def test_an_asymmetric_viscous_friction_behind_a_late_reference_is_named():
    """Hand-made like that case (29 moves of +/-30 mm at 7754 mm/min, program seed 1, no noise, 1 um encoder).
    Before: screened 3.48 um against 2.51 um without the effect, not refitted, nothing named (2.57 um held out);
    after: named, 0.41 um held out. What holds on any platform: the effect is refitted in the first round, named,
    and at least halves the held-out error (its 5 um are 5 times the encoder's step)."""
    import toolpaths

    m = vcnc.machine("emps").with_axis_options("x", noise=None, encoder=1e-3)
    m = m.with_effect("x", "friction_viscous_asymmetric", {"asymmetry": -0.387})
    sp = vcnc.interpolate(vcnc.parse_program(toolpaths.random_moves(29, 30.0, 7754, seed=1)), m)
    cap = m.simulate(sp, seed=1)
    late = np.concatenate([np.full(2, cap.reference[0, 0]), cap.reference[:-2, 0]])  # logged 2 samples late
    rec = vcnc.Capture(t=cap.t, axes=("x",), reference=late[:, None], measured=cap.measured[:, :1])
    model = identify(rec, axis="x")
    first = model.validation["rounds"][0]
    assert "friction_viscous_asymmetric" in first["refitted"]
    assert [e.name for e in model.effects] == ["friction_viscous_asymmetric"]
    assert model.validation["rms_after_um"] < 0.5 * model.validation["rms_before_um"]
