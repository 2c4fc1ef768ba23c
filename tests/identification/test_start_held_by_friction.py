"""An axis standing at its first sample where it is commanded starts the record at rest, whatever the reference's
first steps (ident39; ``identification.segments.settled_start``)."""
import numpy as np

from identification import identify
from identification.segments import settled_start


def _moves(first_steps_mm: list[float]) -> np.ndarray:
    """A reference from 0: the given first steps, a move at 0.03 mm a sample, a rest, the way back, a rest."""
    steps = np.concatenate([first_steps_mm, np.full(200, 0.03), np.linspace(0.03, 0.0, 20), np.zeros(100),
                            np.full(200, -0.03), np.linspace(-0.03, 0.0, 20), np.zeros(100)])
    return np.concatenate([[0.0], np.cumsum(steps)])


def test_an_axis_held_at_its_first_sample_starts_the_record_at_rest():
    # the reference steps alike at first (2.5, 2.5 um: no ramp from standstill, whose steps grow 1, 3, 5); the axis
    # stands 3 samples where it is commanded, held by its friction, then follows
    xr = _moves([0.0025, 0.0025, 0.004, 0.012, 0.02, 0.028])
    x = np.concatenate([np.zeros(3), xr[:-3]])
    assert settled_start(xr, x) == 0
    # triggered during a move: the axis moves between its first samples, 10 um behind its command, and the record is
    # cut at its first rest
    moving = 0.03 * np.arange(10) + 0.3
    moving = np.concatenate([moving, moving[-1] + xr])
    assert settled_start(moving, moving - 0.01) != 0


def test_friction_holding_the_first_move_leaves_no_load_in_the_fit():
    """ident_fuzz seed 21 case 30: ballscrew-ppc's x, 47 random moves over +/-1 mm logged every 2 ms, Coulomb friction
    holding the axis at each start. Its reference steps 2.5, 2.5, 4 um from 0 while the axis stands: the record was
    cut at 0.178 s and simulated from rest there, where the integral action held the friction, and the fit took a
    constant load (both Coulomb levels positive, 8788 and 4260 mm/s^2), 4.81 um held out. From its first sample, the
    levels oppose the motion each way."""
    from benchmarks.ident_fuzz import build, draw_case

    case = draw_case(21, 30)
    assert (case["machine"], case["axis"], case["step"], case["effects"]) == ("ballscrew-ppc", "x", 2, {})
    rec, _, _, _ = build(case)
    model = identify(rec, axis="x", diagnose=False)
    assert (model.fit.get("record_start") or {}).get("dropped_samples", 0) == 0
    assert model.parameters["d0"] > 0.0 > model.parameters["d1"]
