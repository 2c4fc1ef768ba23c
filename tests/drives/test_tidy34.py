"""A structural mode as the loop's feedback sees it (:meth:`drives.StructuralMode.share`), which the sampled loop of
:meth:`vcnc.engine.axis.AxisDefinition.sampled_loop` (and so ``Machine.unstable_axes`` and ``benchmarks/ident_fuzz.py``)
multiplies into the rigid plant."""

from __future__ import annotations

import numpy as np
import pytest

from drives import StructuralMode


def _two_mass(mode: StructuralMode, mass: float, s: complex) -> tuple[complex, complex]:
    """x1 / F and x2 / F of the class notes' two masses (force on m1, no viscous term), solved at ``s``."""
    m1, m2 = (1.0 - mode.load_fraction) * mass, mode.load_fraction * mass
    k = mode.omega ** 2 * m1 * m2 / mass
    c = 2.0 * mode.damping * mode.omega * m1 * m2 / mass
    a = np.array([[m1 * s * s + c * s + k, -(c * s + k)], [-(c * s + k), m2 * s * s + c * s + k]])
    return tuple(np.linalg.solve(a, [1.0, 0.0]))


@pytest.mark.parametrize("mode", [StructuralMode(frequency_hz=84.7, damping=0.074, load_fraction=0.54),
                                  StructuralMode(frequency_hz=30.0, damping=0.3, load_fraction=0.2)])
def test_the_share_is_the_two_mass_model_over_the_rigid_body(mode):
    mass = 2.5e-3  # [V s^2/mm]: any mass, the shares are ratios
    for f_hz in (3.0, 60.0, mode.frequency_hz * np.sqrt(1.0 - mode.load_fraction), 84.7, 400.0):
        s = 2j * np.pi * f_hz
        motor, table = _two_mass(mode, mass, s)
        rigid = 1.0 / (mass * s * s)
        assert complex(mode.share("motor")(s)) == pytest.approx(motor / rigid, rel=1e-9)
        assert complex(mode.share("table")(s)) == pytest.approx(table / rigid, rel=1e-9)


def test_the_motor_side_sees_the_anti_resonance_and_both_shares_are_one_at_rest():
    mode = StructuralMode(frequency_hz=60.0, damping=0.05, load_fraction=0.5)
    anti = 2j * np.pi * 60.0 * np.sqrt(0.5)  # omega sqrt(1 - r): the motor side's zero (undamped part)
    assert abs(complex(mode.share("motor")(anti))) < 0.2 * abs(complex(mode.share("motor")(2j * np.pi * 20.0)))
    assert complex(mode.share("motor")(0.0)) == pytest.approx(1.0)
    assert complex(mode.share("table")(0.0)) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="feedback must be 'motor' or 'table'"):
        mode.share("scale")
