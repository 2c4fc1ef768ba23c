"""Thesis reproduction on the built-in virtual machines (vcnc.machine): Tables 3.2-3.5, 4.1, 4.2,
Sec. 4.3.1, and the PDF scale gains of seed 004 on the chevalier-pdf machine.

Measured with the default pipeline (exact + output-error refinement), seed 0, and recorded in
examples/01_thesis_reproduction.py.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

import interpolators
from identification import ReducedAxisModel, identify
from identification.gain_scales import PAPER_K1, PAPER_K2, pdf_gain_scales
from identification.synthetic import BALLSCREW_AXIAL_MODE, VALIDATION_PROGRAM, table_3_2_program
from interpolators.limits import AxisLimits
from vcnc.contour_compare import compare
from vcnc.engine.machine import load_machine

pytestmark = pytest.mark.slow  # identifies every thesis machine with three solvers


def validation_capture(machine):
    """Sec. 4.3.1: +/-20 mm back and forth at 70.71 mm/s with 424.26 mm/s^2."""
    lim = {a: AxisLimits(velocity=70.71, acceleration=424.26, jerk=1e6, rapid=250.0) for a in machine.limits}
    prog = interpolators.parse_program(VALIDATION_PROGRAM)
    sp = interpolators.interpolate(prog, limits=lim, sample_time=machine.sample_time)
    return machine.simulate(sp, seed=1)


@functools.cache
def _identify(name):
    return _identify_machine(load_machine(name))


def _identify_machine(m):
    sp = interpolators.interpolate(
        interpolators.parse_program(table_3_2_program()), limits=m.limits, sample_time=m.sample_time
    )
    cap = m.simulate(sp, seed=0)
    assert 21.0 < len(cap) * m.sample_time < 23.5  # "about 22 s" (Sec. 3.4)
    return m, cap, identify(cap, diagnose=False)


def _validation_errors(machine, model):
    """(true, predicted) tracking errors of the Sec. 4.3.1 move on ``machine`` [mm]."""
    vc = validation_capture(machine)
    xr = vc.reference[:, 0]
    return xr - vc.measured[:, 0], xr - model.simulate(xr, sample_time=vc.sample_time)


def _tracking_mismatch(machine, model):
    """RMS(predicted - true tracking error) / RMS(true tracking error) on the Sec. 4.3.1 move."""
    e_true, e_pred = _validation_errors(machine, model)
    return float(np.sqrt(np.mean((e_true - e_pred) ** 2)) / np.sqrt(np.mean(e_true**2)))


@pytest.fixture(scope="module")
def pid():
    return _identify("fadal-pid")


def test_pid_poles_closer_than_the_paper(pid):
    """Table 3.4 / 4.1: true 33 Hz / 0.45 / 1.17 Hz; the paper estimated 38.21 / 0.42 / 1.89."""
    m, _, model = pid
    true = ReducedAxisModel(parameters=m.axis("x").reduced_parameters(), sample_time=m.sample_time).poles
    est = model.poles
    assert abs(est["omega_n_hz"] - true["omega_n_hz"]) <= abs(38.21 - 33.0)
    assert abs(est["zeta"] - true["zeta"]) <= abs(0.42 - 0.45) + 1e-9
    assert abs(est["p_hz"] - true["p_hz"]) <= abs(1.89 - 1.17)
    assert model.is_stable() and model.fit["rms_um"] < 1.0


@pytest.mark.parametrize("name", ["fadal-pid", "fadal-ppi"])
def test_validation_tracking_error_within_5_percent(name, pid):
    """Sec. 4.3.1: predicted tracking error within 5% RMS of the true machine's (the paper: 10-15%)."""
    m, _, model = pid if name == "fadal-pid" else _identify(name)
    assert _tracking_mismatch(m, model) < 0.05


def _rms_level_error(e_true, e_pred):
    """|RMS(predicted tracking error) / RMS(true tracking error) - 1|."""
    return abs(float(np.sqrt(np.mean(e_pred**2)) / np.sqrt(np.mean(e_true**2))) - 1.0)


@pytest.fixture(scope="module")
def smc():
    return _identify("fadal-smc")


@pytest.mark.parametrize("name", ["fadal-pid", "fadal-ppi", "fadal-smc"])
def test_three_methods_agree(name):
    """Sec. 4.3 (GA within 2-3 % of LM): on the three thesis loops (Tables 3.3-3.5) exact, ga and kkt
    give the same identified model through the whole pipeline (solver + output-error refinement);
    measured: within 1e-5 relative in a1..d1. On fadal-ppi the GA alone ends in the mirror labelling
    of the same three real poles and stalls along the valley of the fast pair (up to 9 % in omega_n,
    see test_solvers.py::test_ga_mirror_is_the_same_model_relabelled); its relabelled start lets the
    refinement reach the same model (started in the mirror labelling it stopped 31 % away, where the
    two fast poles meet)."""
    m, cap, exact = _identify(name)
    for method in ("ga", "kkt"):
        other = identify(cap, diagnose=False, method=method)
        for k, v in exact.parameters.items():
            assert other.parameters[k] == pytest.approx(v, rel=1e-3), (method, k)
        for k, v in exact.poles.items():
            assert other.poles[k] == pytest.approx(v, rel=1e-3), (method, k)
        assert other.fit["rms_um"] == pytest.approx(exact.fit["rms_um"], rel=1e-4)


def test_smc_pole_zero_cancellation(smc):
    """Table 3.5: feedforward cancels poles and zeros (G_track ~ 1); the tracking error of the validation move
    is only ~1.4 um RMS. The identified model is stable, flat in tracking (|G_track| within 5% of 1 up to
    30 Hz), predicts the RMS of that error within 5 % (measured: 1.1 %) and its course no worse than the true
    reduced model does (sample by sample 22 %: 0.15 um of the 0.32 um difference is the sensor's noise and
    encoder steps, the rest the discrete loop that the continuous reduced model only approximates)."""
    m, _, model = smc
    true = ReducedAxisModel(parameters=m.axis("x").reduced_parameters(), sample_time=m.sample_time)
    f = np.linspace(0.1, 30.0, 50)
    assert np.all(np.abs(np.abs(model.G_track(2j * np.pi * f)) - 1) < 0.05)
    assert _rms_level_error(*_validation_errors(m, model)) < 0.05
    assert _tracking_mismatch(m, model) <= _tracking_mismatch(m, true) + 0.05


def test_ballscrew_zpetc_table_4_2_situation(pid):
    """Table 4.2: ZPETC cancels the closed-loop dynamics, the poles are not identifiable. The paper's
    solution sat near zeta_min; on the rigid virtual bench ours is stable and inside the bounds (for the
    bound, see the next test: it takes the bench's structure), in a valley of the objective that
    spans a factor 2 in omega_n (within 1 % of the minimum: about 20-42 Hz, the true 30 Hz inside), and
    still predicts the ~5 um RMS tracking error of the validation move within 25% (1.25 um encoder
    steps alone account for 7 %). The same measure pins the PID loop's poles to a grid step."""
    m, _, model = _identify("ballscrew-zpetc")
    b = model.bounds
    assert model.is_stable()
    assert b["zeta"][0] <= model.poles["zeta"] <= b["zeta"][1]
    assert _tracking_mismatch(m, model) < 0.25
    valley = model.fit["solver"]["identifiability"]
    assert not valley["identifiable"]
    assert valley["omega_n_hz"][1] / valley["omega_n_hz"][0] > 1.5
    assert valley["omega_n_hz"][0] <= 30.0 <= valley["omega_n_hz"][1]
    pid_valley = pid[2].fit["solver"]["identifiability"]
    assert pid_valley["identifiable"]
    assert pid_valley["omega_n_hz"][1] / pid_valley["omega_n_hz"][0] < 1.1


def test_ballscrew_zpetc_with_an_axial_mode_sits_on_the_damping_bound():
    """Table 4.2: on the real bench the LM solution was 77.83 Hz / zeta 0.203 / p 4.36 Hz, zeta "very
    close to its minimum acceptable limit" 0.2. The rigid virtual bench does not land there (test
    above: its optimum is inside the box on every program tried). A real ball screw has axial modes;
    with one (BALLSCREW_AXIAL_MODE) the ZPETC, having cancelled the rigid closed loop, leaves the mode's lightly
    damped residue as the dynamics the three poles must fit, and the equation-error solution sits on
    zeta_min (Table 3.1 case 2; measured 57.1 Hz / 0.200 / 4.91 Hz; the GA 57.1 / 0.201 / 4.88, as the
    paper's GA sat beside its LM), the refined model beside it (27.2 Hz / 0.204 / 8.96 Hz). The same
    mode without the ZPETC (ballscrew-ppc) leaves every bound free (measured 37.1 Hz / 0.61 /
    13.3 Hz): the cancellation is what drives the solution to the bound.
    Over modes of 60 Hz (damping 0.02-0.1, load fraction 0.3-0.7) and 80 Hz at load fraction 0.7 the
    solution was on zeta_min every time; at 80 Hz / 0.5 it sat at 0.23-0.25, from 100 Hz up at 0.26-0.52.

    The model still predicts the tracking error: the peak of the Sec. 4.3.1 move within 10 %
    (measured +2.5 %), its RMS within 15 % (+9.5 %; sample by sample the mode's ringing is not
    reproduced, 63 %), and the max contour error of the Fig. 3.14 circle (100 mm/s, 600 mm/s^2)
    within 10 % (+3.0 %)."""
    m = load_machine("ballscrew-zpetc").with_axis_options("x", resonance=BALLSCREW_AXIAL_MODE)
    _, cap, model = _identify_machine(m)
    ee, b = model.fit["solver"], model.bounds
    assert ee["case"] == 2 and ee["active"] == {"p": "free", "omega_n": "free", "zeta": "lower"}
    assert ee["poles"]["zeta"] == pytest.approx(b["zeta"][0], abs=1e-9)
    assert ee["objective"] > ee["unconstrained_objective"]  # the bound bites
    assert ee["poles"]["p_hz"] < ee["poles"]["omega_n_hz"] / 5  # slow real pole, fast lightly damped pair
    assert model.is_stable()
    assert b["zeta"][0] <= model.poles["zeta"] <= 1.1 * b["zeta"][0]  # the refined model near the bound
    ga = identify(cap, method="ga", refine="none", diagnose=False)  # Table 4.2: GA beside LM at the bound
    for k, v in ee["poles"].items():
        assert ga.poles[k] == pytest.approx(v, rel=0.03), k

    e_true, e_pred = _validation_errors(m, model)
    assert np.max(np.abs(e_pred)) == pytest.approx(np.max(np.abs(e_true)), rel=0.10)
    assert _rms_level_error(e_true, e_pred) < 0.15
    circle = compare(m, model, "circle", feed=100.0, acceleration=600.0).to_dict()
    assert abs(circle["prediction_error_pct"]["max"]) <= 10.0

    rigid_loop = load_machine("ballscrew-ppc").with_axis_options("x", resonance=BALLSCREW_AXIAL_MODE)
    assert all(v == "free" for v in _identify_machine(rigid_loop)[2].fit["solver"]["active"].values())


def test_chevalier_pdf_scale_gains_within_1_percent():
    """Seed 004, Sec. 4: k1 = 6.942e-2 and k2 = 2.359e-4 recovered within 1% from (e, u, y)."""
    m = load_machine("chevalier-pdf")
    sp = interpolators.interpolate(
        interpolators.parse_program(table_3_2_program(moves=30, span=20.0)), limits=m.limits, sample_time=m.sample_time
    )
    cap = m.simulate(sp, seed=0)
    e = cap.reference[:, 0] - cap.measured[:, 0]
    r = pdf_gain_scales(
        e, cap.control[:, 0], cap.measured[:, 0], integer_parameters=(19, 260), sample_time=m.sample_time,
        position_scale=1e-3,  # the paper's loop works in metres
    )
    assert r["k1"] == pytest.approx(PAPER_K1, rel=0.01)
    assert r["k2"] == pytest.approx(PAPER_K2, rel=0.01)
