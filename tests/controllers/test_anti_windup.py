"""Anti-windup of every servo law (``Controller.anti_windup``, compiled in ``vcnc.engine.kernel``).

A drive whose actuator limit is below what its own axis limits demand (a machine file with a tight
current limit) moves 20 mm at its velocity limit, dwells 2 s, moves back and dwells again. With the
law's anti-windup (the default) the response after each saturated move is bounded and settles to
the encoder's resolution within the dwell; the bare law (``anti_windup = false``) winds up and
overshoots by tens of millimetres or more. A loop that never reaches its limit runs bit for bit
the same either way. Hand-written programs; real simulations, no mocks.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.signal

import controllers
import drives
import interpolators
from interpolators.limits import AxisLimits
from vcnc.core.errors import MachineError, SimulationError
from vcnc.engine.axis import AxisDefinition
from vcnc.engine.machine import Machine, builtin_machines, load_machine
from vcnc.engine.machine_file import parse_machine_text
from vcnc.facade import interpolate

MOVE = 20.0  # mm
PROGRAM = "G21 G90\nG1 X0 F{feed}\nG1 X{move}\nG4 P2\nG1 X0\nG4 P2\nM30\n"

# machine -> (voltage limit [V], bound on the overshoot after a saturated move with anti-windup [mm]).
# The limits are 60 % of the largest control the program asks without a limit (3.55, 2.79, 3.01 and
# 1.55 V; measured). The overshoots measured with anti-windup: 5.59, 0.0008, 5.51, 3.76 and 3.79 mm:
# the position loop saturates, and the drive cannot brake at the rate the reference does (it is
# 3-4 mm behind at the velocity limit); no state of the law winds up. The bare laws: 84, 208, 340,
# 260 and 264 mm.
SATURATING = {
    "fadal-pid": (2.13, 7.0),
    "fadal-ppi": (1.68, 0.01),
    "fadal-smc": (1.8, 7.0),
    "ballscrew-ppc": (0.93, 5.0),
    "ballscrew-zpetc": (0.93, 5.0),
}


def with_law(machine: Machine, *, anti_windup: bool, limit: float | None = None) -> Machine:
    ax = machine.axis("x")
    opts = {} if limit is None else {"saturation": drives.Saturation(voltage_limit=limit)}
    law = dataclasses.replace(ax.controller, anti_windup=anti_windup)
    return machine.with_axis_options("x", controller=law, **opts)


def back_and_forth(machine: Machine, move: float = MOVE):
    feed = 60.0 * machine.axis("x").limits.velocity
    program = interpolators.parse_program(PROGRAM.format(feed=feed, move=move))
    return interpolate(program, machine).select_axes(("x",))


def after_moves(capture, target: float) -> tuple[float, float, float]:
    """(largest overshoot beyond the target of either move [mm], |error| at the end of each dwell [mm])."""
    r, y = capture.reference[:, 0], capture.measured[:, 0]
    k = np.arange(len(r))
    arrive = int(np.flatnonzero(r == target)[0])
    back = int(np.flatnonzero((r == 0.0) & (k > arrive))[0])
    leave = int(np.flatnonzero((r < target) & (k > arrive))[0])
    overshoot = max(float(np.max(y[arrive:leave] - target)), float(np.max(-y[back:])))
    return overshoot, abs(target - y[leave - 1]), abs(y[-1])


@pytest.mark.parametrize("name", list(SATURATING))
def test_a_saturated_move_gives_a_bounded_response_that_settles(name: str) -> None:
    limit, bound = SATURATING[name]
    m = load_machine(name)
    setpoints = back_and_forth(m)
    cap = with_law(m, anti_windup=True, limit=limit).simulate(setpoints)
    sat = cap.aux["saturated"][:, 0]
    assert 0.05 < sat.mean() < 0.5  # the accelerations and decelerations, not the dwells
    overshoot, dwell1, dwell2 = after_moves(cap, MOVE)
    assert overshoot <= bound
    resolution = m.axis("x").encoder.resolution
    assert dwell1 <= 4 * resolution and dwell2 <= 4 * resolution  # settled within each 2 s dwell
    bare = with_law(m, anti_windup=False, limit=limit).simulate(setpoints)
    assert bare.aux["saturated"][:, 0].mean() > 0.9  # wound up: at its limit nearly all the time
    bare_overshoot, _, bare_end = after_moves(bare, MOVE)
    assert bare_overshoot > 10.0 * max(overshoot, 1.0) and bare_end > 1.0


def test_a_saturated_rapid_of_the_adaptive_sliding_mode_recovers() -> None:
    """The wild run's case: fadal-smc with ten times its acceleration limit; the bare law's adapted
    disturbance winds up and the axis leaves by metres (measured 2.3 m), with anti-windup the
    overshoot is the drive's braking distance (measured 2.33 mm) and the axis settles."""
    m = load_machine("fadal-smc")
    ax = m.axis("x")
    lim = dataclasses.replace(ax.limits, acceleration=10 * ax.limits.acceleration, jerk=10 * ax.limits.jerk)
    m = m.with_axis("x", dataclasses.replace(ax, limits=lim))
    program = interpolators.parse_program("G21 G90\nG0 X0\nG0 X100\nG4 P2\nG0 X0\nG4 P2\nM30\n")
    setpoints = interpolate(program, m).select_axes(("x",))
    overshoot, dwell1, dwell2 = after_moves(m.simulate(setpoints), 100.0)
    assert overshoot < 3.0 and dwell1 <= 1e-3 and dwell2 <= 1e-3
    bare = with_law(m, anti_windup=False).simulate(setpoints)
    assert np.abs(bare.reference - bare.measured).max() > 100.0  # beyond the travel


def discrete_pdf_machine(limit: float, *, anti_windup: bool) -> Machine:
    """A PDF law (seed 004's structure) on a stable discrete plant: a velocity-controlled axis
    x/u = K/(s (tau s + 1)), K = 100 mm/(V s), tau = 10 ms, at Ts = 1 ms (ZOH), so that 1 V holds
    100 mm/s. (The Chevalier plant of seed 004, Eq. (11), has a pole at z = 1.040 outside the unit
    circle: once its demand is clipped it runs away under any law.) C1 = 10 V/(mm s), C2 = 0.5 V/mm."""
    ts = 1e-3
    num, den, _ = scipy.signal.cont2discrete(([100.0], [0.01, 1.0, 0.0]), ts, method="zoh")
    plant = drives.DiscretePlantDrive(numerator=tuple(np.trim_zeros(np.ravel(num), "f")),
                                      denominator=tuple(den[1:]), sample_time=ts)
    law = controllers.PDF(p1=10, p2=1, k1=1.0, k2=0.5, anti_windup=anti_windup)
    axis = AxisDefinition(name="x", drive=plant, controller=law,
                          limits=AxisLimits(velocity=100.0, acceleration=20000.0, jerk=2e6),
                          saturation=drives.Saturation(voltage_limit=limit))
    return Machine.from_axes({"x": axis}, sample_time=ts)


def test_the_pdf_sum_does_not_wind_up() -> None:
    """At 0.8 V the axis reaches 80 mm/s of the 100 commanded: over a 100 mm move the error grows and
    the bare PDF's sum u1 with it (measured: at the limit 99 % of the time, overshoot 86 mm, 71 mm off
    after the second dwell); with anti-windup 32 % of the time, overshoot 0.3 um (measured)."""
    m = discrete_pdf_machine(0.8, anti_windup=True)
    setpoints = back_and_forth(m, 100.0)
    cap = m.simulate(setpoints)
    assert cap.aux["saturated"].mean() > 0.1
    overshoot, dwell1, dwell2 = after_moves(cap, 100.0)
    assert overshoot < 1e-3 and dwell1 < 1e-3 and dwell2 < 1e-3
    bare = discrete_pdf_machine(0.8, anti_windup=False).simulate(setpoints)
    bare_overshoot, _, bare_end = after_moves(bare, 100.0)
    assert bare_overshoot > 10.0 and bare_end > 10.0
    assert bare_overshoot > 10.0 and bare_end > 10.0


def test_the_open_loop_unstable_chevalier_plant_runs_away_at_any_clip() -> None:
    """What anti-windup cannot do: seed 004's identified plant is open-loop unstable, so a limit below
    what its own moves demand (95 % of it) loses the table with or without anti-windup."""
    m = load_machine("chevalier-pdf")
    setpoints = back_and_forth(m)
    peak = float(np.abs(m.simulate(setpoints).control).max())
    for anti_windup in (True, False):
        with pytest.raises(SimulationError, match="diverged"):
            with_law(m, anti_windup=anti_windup, limit=0.95 * peak).simulate(setpoints)


def test_a_law_without_integral_action_is_unchanged_at_its_limit() -> None:
    """EMPS' P-P cascade (K_i = 0) has no state to wind up: even saturated (2.58 V, 32 % of the
    samples) its control is the same with and without anti-windup."""
    m = load_machine("emps")
    setpoints = back_and_forth(m)
    on = with_law(m, anti_windup=True, limit=2.58).simulate(setpoints)
    off = with_law(m, anti_windup=False, limit=2.58).simulate(setpoints)
    assert on.aux["saturated"].mean() > 0.2
    np.testing.assert_array_equal(on.control, off.control)
    np.testing.assert_array_equal(on.measured, off.measured)


@pytest.mark.parametrize("name", builtin_machines())
def test_a_loop_within_its_limit_is_the_same_with_and_without_anti_windup(name: str) -> None:
    import toolpaths

    m = load_machine(name)
    axes = m.axes[:1]
    program = interpolators.parse_program(toolpaths.random_moves(20, 10.0, 6000.0, seed=2, axes=axes))
    setpoints = interpolate(program, m).select_axes(axes)
    on = with_law(m, anti_windup=True).simulate(setpoints, seed=4)
    off = with_law(m, anti_windup=False).simulate(setpoints, seed=4)
    assert not on.aux["saturated"].any() and not off.aux["saturated"].any()
    for field in ("measured", "table", "velocity", "control", "friction"):
        np.testing.assert_array_equal(getattr(on, field), getattr(off, field))


def test_the_machine_file_key_and_its_check() -> None:
    base = ('sample_time = 0.001\n[axes.x.limits]\nvelocity = 100.0\nacceleration = 1000.0\n'
            '[axes.x.drive]\ntype = "linear"\nmass = 50.0\nviscous = 100.0\n'
            'amplifier_gain = 1.0\nforce_constant = 30.0\n'
            '[axes.x.controller]\ntype = "pid"\nkp = 20.0\n')
    assert parse_machine_text(base, file="m.toml", default_name="m").axes["x"].controller.anti_windup is True
    off = parse_machine_text(base + "anti_windup = false\n", file="m.toml", default_name="m")
    assert off.axes["x"].controller.anti_windup is False
    with pytest.raises(MachineError, match=r"m.toml:14: .*anti_windup.* must be true or false"):
        parse_machine_text(base + "anti_windup = 1\n", file="m.toml", default_name="m")
    with pytest.raises(MachineError, match="anti_windup"):
        controllers.PID(kp=1.0, anti_windup=1)  # type: ignore[arg-type]
