"""Built-in machines: names, the thesis' closed-loop parameters, limits."""

from __future__ import annotations

import control
import numpy as np
import pytest

from vcnc.engine.machine import builtin_machines, load_machine
from vcnc.errors import MachineError

NAMES = ["ballscrew-ppc", "ballscrew-zpetc", "chevalier-pdf", "emps", "fadal-pid", "fadal-ppi", "fadal-smc"]

# "Actual" columns of the thesis (W. Wong 2007): Table 3.4 (PID), 3.3 (P-PI), 3.5 (SMC).
TABLES = {
    "fadal-pid": {
        "x": dict(a1=192.65, a2=44356.23, a3=316830.21, b0=0, b1=190.10, b2=44356.23, d0=441, d1=-302),
        "y": dict(a1=178.75, a2=41031.98, a3=293085.57, b0=0, b1=175.85, b2=41031.98, d0=409, d1=-388),
    },
    "fadal-ppi": {
        "x": dict(a1=372.76, a2=62009.83, a3=1527104.87, b0=0, b1=0, b2=11106.33, d0=441, d1=-302),
        "y": dict(a1=372.76, a2=61999.31, a3=1527104.86, b0=0, b1=0, b2=11095.82, d0=409, d1=-388),
    },
    "fadal-smc": {
        "x": dict(a1=390.10, a2=57029.44, a3=3801962.50, b0=1.00, b1=390.10, b2=57029.44, d0=441, d1=-302),
        "y": dict(a1=493.09, a2=87925.67, a3=5861711.35, b0=1.00, b1=493.09, b2=87925.67, d0=409, d1=-388),
    },
}


def test_builtin_names() -> None:
    assert builtin_machines() == NAMES


@pytest.mark.parametrize("name", list(TABLES))
@pytest.mark.parametrize("axis", ["x", "y"])
def test_analytic_parameters_equal_thesis_tables(name: str, axis: str) -> None:
    got = load_machine(name).axis(axis).reduced_parameters()
    for k, v in TABLES[name][axis].items():
        if v == 0:
            assert abs(got[k]) < 1e-9, k
        else:
            assert got[k] == pytest.approx(v, rel=5e-3), k


def test_fadal_pid_poles_table_3_4() -> None:
    """Poles of Table 3.4 (X): 33.00 Hz / 0.45 and 1.17 Hz."""
    g, _ = load_machine("fadal-pid").axis("x").closed_loop(0.001)
    wn, zeta, _ = control.damp(g, doprint=False)
    pairs = sorted(zip(wn / 2 / np.pi, zeta))
    assert pairs[0][0] == pytest.approx(1.17, abs=0.01)
    assert pairs[-1][0] == pytest.approx(33.0, abs=0.05) and pairs[-1][1] == pytest.approx(0.45, abs=0.005)


def test_smc_tracks_with_unit_transfer_function() -> None:
    g, _ = load_machine("fadal-smc").axis("x").closed_loop(0.001)
    w = 2 * np.pi * np.array([1.0, 10.0, 50.0])
    np.testing.assert_allclose([complex(g(1j * wi)) for wi in w], 1.0, atol=1e-9)


def test_emps_reduced_parameters_from_published_values() -> None:
    p = load_machine("emps").axis("x").reduced_parameters()
    m, fv, fc, off, g = 95.1089, 203.5034, 20.3935, -3.1648, 35.15
    assert p["a1"] == pytest.approx((fv + g * 243.45) / m)
    assert p["a2"] == pytest.approx(g * 243.45 * 160.18 / m)
    assert p["a3"] == 0.0
    assert p["d0"] == pytest.approx(1000 * (fc + off) / m)
    assert p["d1"] == pytest.approx(1000 * (-fc + off) / m)


@pytest.mark.parametrize("name", ["ballscrew-ppc", "chevalier-pdf"])
def test_discrete_machines_explain_reduced_parameters(name: str) -> None:
    with pytest.raises(MachineError, match="closed_loop"):
        load_machine(name).axis("x").reduced_parameters()


def test_limits_and_sample_time() -> None:
    for n in NAMES:
        m = load_machine(n)
        assert set(m.limits) == set(m.axes)
        assert m.sample_time == (0.00025 if n == "chevalier-pdf" else 0.001)
        for lim in m.limits.values():
            assert lim.velocity > 0 and lim.acceleration > 0 and lim.jerk > 0


def test_unknown_name_lists_builtins() -> None:
    with pytest.raises(MachineError, match="fadal-pid"):
        load_machine("no-such-machine")


def test_chevalier_pdf_settles() -> None:
    from vcnc.setpoints import Setpoints

    m = load_machine("chevalier-pdf")
    r = np.r_[np.zeros(40), np.full(4000, 20.0)]
    cap = m.simulate(Setpoints.from_positions(r, sample_time=m.sample_time))
    assert cap.measured[-1, 0] == pytest.approx(20.0, abs=1e-3)
