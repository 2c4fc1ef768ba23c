"""An axis standing at the first sample where it is commanded starts the record at rest, however its reference sets
off; an axis standing several counts behind its command, or creeping under a coarse encoder, does not
(``identification.segments.settled_start``, ``stands_where_commanded``; identstart39)."""
import numpy as np
import pytest

from identification import identify
from identification.segments import measured_count, settled_start, stands_where_commanded


def _moves(first_steps_mm: list[float]) -> np.ndarray:
    """A reference from 0: the given first steps, a move at 0.03 mm a sample, a rest, the way back, a rest."""
    steps = np.concatenate([first_steps_mm, np.full(200, 0.03), np.linspace(0.03, 0.0, 20), np.zeros(100),
                            np.full(200, -0.03), np.linspace(-0.03, 0.0, 20), np.zeros(100)])
    return np.concatenate([[0.0], np.cumsum(steps)])


def _encoder(x: np.ndarray, count_mm: float) -> np.ndarray:
    return count_mm * np.round(x / count_mm)


def _follows(xr: np.ndarray, dead: int) -> np.ndarray:
    """An axis at 0 that answers ``dead`` samples late, then closes a fifth of its error a sample (settling to its
    command by steps down to the encoder's count at every rest)."""
    x = np.zeros(xr.size)
    for k in range(1, xr.size):
        x[k] = x[k - 1] + 0.2 * ((xr[k - 1 - dead] if k - 1 >= dead else 0.0) - x[k - 1])
    return x


# the reference steps alike at first (a 5 um move in two samples of 2.5 um, then a ramp: no ramp from standstill,
# whose steps grow 1, 3, 5, as ident_fuzz seed 21 case 30 sets off), so its steps cannot tell a start from rest
FIRST = [0.0025, 0.0025, 0.004, 0.012, 0.02, 0.028]


def test_an_axis_standing_where_it_is_commanded_starts_the_record_at_rest():
    xr = _moves(FIRST)
    # a 0.25 um encoder; the axis stands 5 samples at 0, its loop not answering yet (or its friction holding it)
    x = _encoder(_follows(xr, 4), 0.00025)
    assert np.all(x[:6] == 0.0)
    assert measured_count(x, 0.03) == pytest.approx(0.00025)
    assert stands_where_commanded(xr, x)
    assert settled_start(xr, x) == 0


def test_an_axis_standing_behind_its_command_or_creeping_does_not():
    xr = _moves(FIRST)
    # the reference leads by 3 samples (a loop frame cutting the start of the move off): the axis stands 9 um, 4.5
    # counts of its 2 um encoder, behind the command's first sample (ident_fuzz seed 111 case 21: 8.9 um)
    lead = xr[3:]
    x = _encoder(np.concatenate([np.zeros(5), xr[:-8]]), 0.002)
    assert not stands_where_commanded(lead, x)
    assert settled_start(lead, x) != 0
    # where it is commanded but creeping: a 1 um encoder hides 0.4 um a sample for a sample (0.4 um is 1.3 % of the
    # largest reference step, 30 um); standing one sample is no rest
    creep = xr.copy()
    creep[:4] = 0.0004 * np.arange(4)
    x = _encoder(np.concatenate([creep[:4], creep[4:] - 0.002]), 0.001)
    assert x[1] == x[0] != x[2]
    assert not stands_where_commanded(creep, x)
    # triggered during a move: the axis moves between its first samples
    moving = np.concatenate([0.03 * np.arange(10) + 0.3, 0.57 + xr])
    assert not stands_where_commanded(moving, moving - 0.01)


def test_an_axis_that_stood_at_the_programs_start_leaves_no_load_in_the_fit():
    """ident_fuzz seed 21 case 30: ballscrew-ppc's x, 47 random moves over +/-1 mm logged every 2 ms, a 0.25 um
    encoder. Its reference steps 2.5, 2.5, 4 um from 0 while the axis stands 5 samples where it is commanded: the
    record was cut at sample 89 (0.178 s) and simulated from rest there, where the integral action held the friction,
    and the fit took a constant load (both Coulomb levels positive), 4.81 um held out (1.20 um now). From its first
    sample the levels oppose the motion each way."""
    from benchmarks.ident_fuzz import build, draw_case

    case = draw_case(21, 30)
    assert (case["machine"], case["axis"], case["step"], case["effects"]) == ("ballscrew-ppc", "x", 2, {})
    rec, _, _, _ = build(case)
    model = identify(rec, axis="x", diagnose=False)
    assert (model.fit.get("record_start") or {}).get("dropped_samples", 0) == 0
    assert model.parameters["d0"] > 0.0 > model.parameters["d1"]
