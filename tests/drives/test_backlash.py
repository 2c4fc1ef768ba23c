"""Backlash: lost motion between motor and table, seen or not by the feedback."""

from __future__ import annotations

import numpy as np

import controllers
from vcnc.engine.machine import load_machine
from vcnc.setpoints import Setpoints

BASE = load_machine("fadal-pid")
WIDTH = 0.02


def _open_loop_machine(feedback: str = "motor"):
    """Acceleration feedforward only (kp = 0): the drive follows the commanded motion open loop."""
    ax = BASE.axis("x")
    ff = controllers.PID(kp=0.0, ka=1.0 / ax.drive.gain, kv=ax.drive.viscous_rate / ax.drive.gain)
    return BASE.with_axis_options("x", controller=ff, backlash=WIDTH, friction=None, noise=None, encoder=None,
                                  dac=None, feedback=feedback)


def _there_and_back() -> Setpoints:
    ts = BASE.sample_time
    t = np.arange(0, 2.0, ts)
    x = 2.0 * (1 - np.cos(np.pi * t))  # out 4 mm and back, smooth
    return Setpoints.from_positions(x, sample_time=ts)


def test_table_lags_motor_by_exactly_the_backlash_after_reversal() -> None:
    cap = _open_loop_machine().simulate(_there_and_back())
    motor = cap.measured[:, 0]
    table = cap.table[:, 0]
    k_rev = int(np.argmax(motor))
    # after the reversal, the table has moved back by exactly WIDTH less than the motor
    d_motor = motor[k_rev] - motor[-1]
    d_table = table[k_rev] - table[-1]
    assert d_motor > 3.0
    np.testing.assert_allclose(d_motor - d_table, WIDTH, atol=1e-12)
    # while crossing the gap the table does not move
    crossing = (motor[k_rev] - motor < WIDTH - 1e-9) & (np.arange(len(motor)) > k_rev)
    assert np.ptp(table[crossing]) < 1e-12


def test_linear_scale_sees_the_backlash_motor_encoder_does_not() -> None:
    semi = BASE.with_axis_options("x", backlash=WIDTH, noise=None, encoder=None)
    closed = semi.with_axis_options("x", feedback="table")
    sp = _there_and_back()
    cs, cc = semi.simulate(sp), closed.simulate(sp)
    err_table_semi = np.abs(cs.reference[:, 0] - cs.table[:, 0])
    err_table_closed = np.abs(cc.reference[:, 0] - cc.table[:, 0])
    assert np.max(err_table_semi[-100:]) > 0.4 * WIDTH  # semi-closed loop: the table ends off by ~w/2
    assert np.max(err_table_closed[-100:]) < 0.2 * WIDTH  # the scale closes the loop on the table
