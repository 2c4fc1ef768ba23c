"""One registry of effects (drives.effects): the machine, the FMU export, the sweeps and the
diagnosis all know the same effects under the same names."""

from __future__ import annotations

import pytest

from drives.effects import EFFECT_NAMES, EFFECTS
from identification.effects import EFFECTS as DIAGNOSIS_EFFECTS
from vcnc.engine.machine import EFFECTS as MACHINE_EFFECTS
from vcnc.engine.machine import load_machine, realistic_effect
from vcnc.errors import MachineError
from vcnc.fmu import REPRESENTABLE_EFFECTS
from vcnc.sweeps import MAGNITUDE_KEYS


def test_every_reader_has_the_registrys_effects():
    assert MACHINE_EFFECTS == EFFECT_NAMES
    assert set(DIAGNOSIS_EFFECTS) == set(EFFECT_NAMES)
    assert list(REPRESENTABLE_EFFECTS) == list(EFFECT_NAMES)
    assert list(MAGNITUDE_KEYS) == list(EFFECT_NAMES)


@pytest.mark.parametrize("name", EFFECT_NAMES)
def test_each_effect_builds_and_its_magnitude_is_one_of_its_parameters(name):
    info = EFFECTS[name]
    assert info.magnitude in info.parameters
    axis = load_machine("fadal-pid").axis("x")
    assert realistic_effect(axis, name, sample_time=1e-3)  # field changes of the axis
    with pytest.raises(MachineError, match="unknown parameter"):
        realistic_effect(axis, name, {"nonsense": 1.0}, sample_time=1e-3)
