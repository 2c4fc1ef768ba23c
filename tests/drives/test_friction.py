"""Friction in the compiled plant: true stiction at rest, break-away, Stribeck."""

from __future__ import annotations

import numpy as np

import drives
from vcnc.engine.machine import load_machine
from vcnc.setpoints import Setpoints

BASE = load_machine("fadal-pid")


def _at_rest(n: int = 2000) -> Setpoints:
    return Setpoints.from_positions(np.full(n, 1.0), sample_time=BASE.sample_time)


def _machine(load_n: float, static_n: float = 600.0):
    friction = drives.Friction(coulomb_positive=400.0, coulomb_negative=400.0, static_positive=static_n,
                               static_negative=static_n, stribeck_velocity=1.0)
    return BASE.with_axis_options("x", friction=friction, load=drives.ExternalLoad(constant=load_n), noise=None,
                                  backlash=None, encoder=None, substeps=10)


def test_axis_at_rest_stays_at_rest_below_static_friction() -> None:
    """A constant force of 95 % of the static friction: nothing moves, not even by 1e-15 mm."""
    cap = _machine(0.95 * 600.0).simulate(_at_rest())
    assert np.all(cap.table[:, 0] == 1.0)
    assert np.all(cap.velocity[:, 0] == 0.0)
    assert np.all(cap.control[:, 0] == 0.0)
    # friction holds the load: the dry-friction term equals the applied force (u - load = -load)
    np.testing.assert_allclose(cap.friction[:, 0], -0.95 * 600.0 / BASE.axis("x").force_per_volt)


def test_force_above_static_friction_breaks_away() -> None:
    cap = _machine(1.05 * 600.0).simulate(_at_rest())
    assert cap.table[1, 0] < 1.0  # the load pushes the axis back before the loop reacts
    assert np.max(np.abs(cap.velocity[:, 0])) > 0.0


def test_moving_axis_sticks_when_the_force_vanishes() -> None:
    """Commanded stop: the table comes to rest exactly (velocity 0.0) and stays there."""
    n = 3000
    t = np.arange(n) * BASE.sample_time
    x = np.minimum(t, 0.5) * 20.0
    m = _machine(0.0)
    cap = m.simulate(Setpoints.from_positions(x, sample_time=BASE.sample_time))
    tail = cap.velocity[-200:, 0]
    assert np.all(tail == 0.0) or np.max(np.abs(tail)) < 1e-3


def test_friction_force_helper() -> None:
    f = drives.Friction(coulomb_positive=10.0, coulomb_negative=12.0, static_positive=15.0, stribeck_velocity=2.0,
                        viscous_negative=100.0)
    assert f.force(0.0) == 0.0
    assert abs(f.force(1e-9) - 15.0) < 1e-6
    assert abs(f.force(1e3) - 10.0) < 1e-6
    assert abs(f.force(-10.0, viscous=50.0) - (-12.0 - 1.0)) < 1e-6
