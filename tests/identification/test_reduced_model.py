"""The reduced model's simulation contract (identification/reduced_model.py module docstring)."""

from __future__ import annotations

import json

import control
import numpy as np
import pytest
import scipy.signal

from identification import ReducedAxisModel, discretize, load_model, simulate
from identification.reduced_model import continuous_state_space
from identification.synthetic import FADAL_PID_X, random_moves_reference
from vcnc.errors import InputError, ModelFileError

T = 1e-3
LINEAR = dict(FADAL_PID_X, d0=0.0, d1=0.0)


def _reference(n=3000, seed=0):
    rng = np.random.default_rng(seed)
    return 2.0 + np.cumsum(np.cumsum(rng.normal(size=n))) * 1e-4


@pytest.mark.filterwarnings("ignore::scipy.signal.BadCoefficients")
@pytest.mark.parametrize("b0", [0.0, 0.35, 1.0])
def test_friction_free_model_equals_foh_lsim(b0):
    """Without friction the sampled model is the exact FOH response of G_track (scipy lsim interpolates linearly)."""
    p = dict(LINEAR, b0=b0, b1=250.0)
    xr = _reference()
    t = np.arange(xr.size) * T
    g = scipy.signal.lti([p["b0"], p["b1"], p["b2"], p["a3"]], [1, p["a1"], p["a2"], p["a3"]])
    _, y, _ = scipy.signal.lsim(g, xr - xr[0], t)
    np.testing.assert_allclose(simulate(p, xr, T), y + xr[0], rtol=0, atol=1e-9)


def test_discretisation_matches_scipy_foh():
    ss = continuous_state_space(LINEAR)
    d = discretize(LINEAR, T)
    ad, bd, cd, dd, _ = scipy.signal.cont2discrete(
        (ss["A"], ss["B"][:, :1], ss["C"][None, :], ss["D"][None, :1]), T, method="foh"
    )
    np.testing.assert_allclose(d.phi, ad, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(d.gamma[:, 0], bd[:, 0], rtol=1e-10, atol=1e-14)
    assert d.d == pytest.approx(float(dd[0, 0]), abs=1e-14)
    phi, gamma, c, dmat = d  # unpacks as (Phi, Gamma, C, D)
    assert phi.shape == (3, 3) and gamma.shape == (3, 2) and c.shape == (3,) and dmat.shape == (2,)


def test_scaled_realisation_is_well_conditioned():
    """The scaled state matrix has entries of order a3^(1/3), not a3 (~3e5) as the companion form."""
    A = continuous_state_space(FADAL_PID_X)["A"]
    assert np.max(np.abs(A)) < 10 * FADAL_PID_X["a3"] ** (1 / 3) + FADAL_PID_X["a1"]


def test_constant_reference_stays_at_rest():
    """The initial state is the steady state x = x_r (friction-free: exactly at rest)."""
    xr = np.full(500, 7.25)
    x, v = simulate(LINEAR, xr, T, return_velocity=True)
    np.testing.assert_allclose(x, 7.25, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v, 0.0, atol=1e-9)


def test_standstill_chatter_is_bounded():
    """With Coulomb friction switched on sign(v) (Eq. 3.2) rounding noise at rest starts a small chatter
    (documented in the contract); it stays below a micrometre-scale bound."""
    x = simulate(FADAL_PID_X, np.full(2000, 7.25), T)
    assert np.abs(x - 7.25).max() < 2e-3


def test_causal_no_dependence_on_future_reference():
    xr = _reference()
    x1 = simulate(FADAL_PID_X, xr, T)
    xr2 = xr.copy()
    xr2[1500:] += 3.0
    x2 = simulate(FADAL_PID_X, xr2, T)
    np.testing.assert_array_equal(x1[:1500], x2[:1500])
    assert np.abs(x1[1501:] - x2[1501:]).max() > 1e-3


def test_friction_is_the_zoh_disturbance_switched_on_predicted_velocity():
    """Contract: friction d0/d1 by the sign of v_k, held over the sample, equals w_ext with no friction."""
    xr = random_moves_reference(moves=20, seed=4)
    x, v = simulate(FADAL_PID_X, xr, T, return_velocity=True)
    w = np.where(v > 0, FADAL_PID_X["d0"], np.where(v < 0, FADAL_PID_X["d1"], 0.0))
    x_lin = simulate(LINEAR, xr, T, disturbance=w)
    np.testing.assert_allclose(x, x_lin, rtol=0, atol=1e-9)
    assert np.abs(x - simulate(LINEAR, xr, T)).max() > 1e-3  # friction matters


def test_external_disturbance_is_zoh_through_g_dist():
    rng = np.random.default_rng(2)
    w = np.repeat(rng.normal(0, 500, 40), 50)
    xr = np.zeros(w.size)
    x = simulate(LINEAR, xr, T, disturbance=w)
    g = scipy.signal.lti([1.0, 0.0], [1, LINEAR["a1"], LINEAR["a2"], LINEAR["a3"]])
    _, y, _ = scipy.signal.lsim(g, w, np.arange(w.size) * T, interp=False)
    np.testing.assert_allclose(x, -y, rtol=0, atol=1e-10)


def test_transfer_functions_are_python_control():
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T)
    assert isinstance(m.G_track, control.TransferFunction)
    assert isinstance(m.G_dist, control.TransferFunction)
    assert control.dcgain(m.G_track) == pytest.approx(1.0)  # integral action: unity DC gain (Eq. 3.1)
    assert control.dcgain(m.G_dist) == pytest.approx(0.0)
    # Table 3.4 'Actual' PID x axis: poles 33.00 Hz / 0.45 and 1.17 Hz
    assert m.poles["omega_n_hz"] == pytest.approx(33.0, abs=0.01)
    assert m.poles["zeta"] == pytest.approx(0.45, abs=0.005)
    assert m.poles["p_hz"] == pytest.approx(1.17, abs=0.01)
    assert m.is_stable()


def test_model_file_round_trip(tmp_path):
    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T, axis="y", fit={"rms_um": 1.5, "max_um": 3.0})
    path = tmp_path / "m.json"
    m.to_json(path)
    d = json.loads(path.read_text())
    assert d["format"] == "vcnc.axis-model/1" and d["effects"] == [] and d["validation"] == {}
    m2 = load_model(path)
    assert m2.parameters == m.parameters and m2.axis == "y" and m2.sample_time == T
    np.testing.assert_array_equal(m2.simulate(_reference()), m.simulate(_reference()))


@pytest.mark.parametrize(
    ("edit", "key"),
    [
        (lambda d: d.pop("sample_time"), "sample_time"),
        (lambda d: d["parameters"].pop("b1"), "parameters.b1"),
        (lambda d: d["parameters"].__setitem__("a2", "x"), "parameters.a2"),
        (lambda d: d.__setitem__("format", "other"), "format"),
        (lambda d: d["parameters"].__setitem__("a3", -1.0), "parameters.a3"),
        (lambda d: d.__setitem__("axis", "q"), "axis"),
    ],
)
def test_model_file_errors_name_the_key(tmp_path, edit, key):
    d = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=T).to_dict()
    edit(d)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(d))
    with pytest.raises(ModelFileError, match=key.replace(".", r"\.")):
        load_model(path)


def test_model_file_invalid_json_has_line(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"format":\n  oops}')
    with pytest.raises(ModelFileError, match=r"bad\.json:2:"):
        load_model(path)


def test_bad_reference_rejected():
    with pytest.raises(InputError, match="NaN"):
        simulate(FADAL_PID_X, np.array([0.0, np.nan, 1.0]), T)
    with pytest.raises(InputError, match="a3"):
        simulate(dict(FADAL_PID_X, a3=0.0), np.zeros(3), T)


def test_tracking_response_is_g_track_without_python_control():
    """``tracking_response`` evaluates G_track as python-control does, to the last bit (the thesis' PID x axis of
    Table 3.4, ``FADAL_PID_X``), so that the setpoint filter's signature need not import python-control."""
    import numpy as np

    from identification.reduced_model import ReducedAxisModel
    from identification.synthetic import FADAL_PID_X

    m = ReducedAxisModel(parameters=FADAL_PID_X, sample_time=1e-3)
    for f in (0.3, 7.8, 37.0, 125.0, 499.0):
        s = 2j * np.pi * f
        assert complex(m.tracking_response(s)) == complex(m.G_track(s))
