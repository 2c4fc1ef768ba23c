"""The one conformance test every controller and every drive record passes.

Protocol (frozen keyword-only dataclass, units for every field, plain-dict round trip), reset (a
simulation leaves no state behind: repeating it after another run gives identical samples) and
determinism with a seed (same seed, same samples; noise follows the seed).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import controllers
import drives
from drives._record import Record
from vcnc.engine.machine import load_machine
from vcnc.errors import MachineError
from vcnc.setpoints import Setpoints

BASE = load_machine("fadal-pid")
BASE_X = BASE.axis("x")
TS = BASE.sample_time

CONTROLLERS = {
    "pid": controllers.PID(kp=44.0, ki=314.0, kd=0.1886, kv=0.01, ka=1e-4, friction_feedforward_positive=0.1),
    "ppi": controllers.PPI(kp=30.0, kd=0.367, ki=50.5, kv=0.02),
    "smc": controllers.SlidingMode(lam=200.0, ks=0.1886, rho=18.86),
    "ppc": controllers.PolePlacement(zpetc=False),
    "ppc+zpetc": controllers.PolePlacement(zpetc=True),
}
DRIVES = {
    "ballscrew": BASE_X.drive,
    "linear": drives.LinearMotorDrive(mass=95.0, viscous=200.0, amplifier_gain=1.0, force_constant=35.0),
}
OPTIONS = {
    "friction": drives.Friction(coulomb_positive=300.0, coulomb_negative=250.0, static_positive=400.0,
                                static_negative=300.0, stribeck_velocity=2.0, viscous_positive=5.0),
    "backlash": drives.Backlash(width=0.005),
    "encoder": drives.Encoder(resolution=0.001),
    "dac": drives.DAC(bits=12, range=10.0),
    "saturation": drives.Saturation(current_limit=10.0),
    "noise": drives.MeasurementNoise(std=0.0005),
    "delay": drives.ComputationalDelay(samples=1),
    "resonance": drives.StructuralMode(frequency_hz=120.0, damping=0.05, load_fraction=0.4),
    "position_periodic": drives.PositionPeriodic(period=10.0, force_amplitude=20.0, position_amplitude=0.001),
    "load": drives.ExternalLoad(constant=50.0, amplitude=30.0, period=0.2),
    "drift": drives.Drift(rate=1e-4, time_constant=0.5),
}
RECORDS = [*CONTROLLERS.values(), *DRIVES.values(), *OPTIONS.values(), controllers.PDF(p1=19, p2=260, k1=0.07, k2=2e-4),
           drives.DiscretePlantDrive(numerator=(1.218,), denominator=(-1.892, 0.886), sample_time=2.5e-4)]


def _setpoints(n: int = 1500, ts: float = TS) -> Setpoints:
    t = np.arange(n) * ts
    x = 5.0 * (1 - np.cos(2 * np.pi * 1.5 * t)) * np.exp(-t)
    return Setpoints.from_positions(x, sample_time=ts, axes=("x",))


def _check_sim(machine, *, noisy: bool) -> None:
    sp = _setpoints(ts=machine.sample_time)
    other = _setpoints(700, ts=machine.sample_time)
    a = machine.simulate(sp, seed=3)
    machine.simulate(other, seed=9)  # another run in between: no state may leak (reset)
    b = machine.simulate(sp, seed=3)
    for name in ("measured", "table", "velocity", "control", "friction"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert np.all(np.isfinite(a.measured))
    c = machine.simulate(sp, seed=4)
    assert (not np.array_equal(a.measured, c.measured)) == noisy


@pytest.mark.parametrize("record", RECORDS, ids=lambda r: type(r).__name__)
def test_record_protocol(record: Record) -> None:
    assert dataclasses.is_dataclass(record)
    params = type(record).__dataclass_params__
    assert params.frozen
    assert all(f.kw_only for f in dataclasses.fields(record))
    fields = [f.name for f in dataclasses.fields(record)]
    assert set(fields) == set(type(record).UNITS), "every field documents its unit"
    again = type(record)(**record.to_dict())
    assert again == record
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(record, fields[0], 1.0)
    numeric = [f for f in fields if isinstance(getattr(record, f), float) and type(record).UNITS[f] != "rad"]
    if numeric:  # an impossible value names the field and its unit
        with pytest.raises(MachineError, match=numeric[0]):
            dataclasses.replace(record, **{numeric[0]: float("nan")})


@pytest.mark.parametrize("name", list(CONTROLLERS))
@pytest.mark.parametrize("drive", list(DRIVES))
def test_controller_on_drive(name: str, drive: str) -> None:
    m = BASE.with_axis_options("x", controller=CONTROLLERS[name], drive=DRIVES[drive], friction=None,
                               backlash=None, noise=None)
    _check_sim(m, noisy=False)
    g_track, g_dist = m.axis("x").closed_loop(TS)
    assert abs(complex(g_track.dcgain()) - 1.0) < 1e-6
    law = CONTROLLERS[name].discrete_law(DRIVES[drive], TS)
    assert law.sample_time == TS


def test_pdf_on_discrete_plant() -> None:
    _check_sim(load_machine("chevalier-pdf"), noisy=False)
    _check_sim(load_machine("chevalier-pdf").with_axis_options("x", noise=1e-4), noisy=True)


@pytest.mark.parametrize("option", list(OPTIONS))
def test_drive_option(option: str) -> None:
    changes = {"noise": None, option: OPTIONS[option]}
    m = BASE.with_axis_options("x", **changes)
    _check_sim(m, noisy=option == "noise")
