"""Minimal reproducers of the defects a mutation fuzzer found (issues #18/#19): each bad or odd program
gets a clean :mod:`vcnc.errors` error naming the file (and line), or runs with finite blocks and setpoints.

The fuzzer mutated the programs of the shared corpus and of ISO and Heidenhain programs from the wild
(lines deleted, duplicated, swapped; numbers replaced by 0, -0, huge values; words dropped or repeated;
random G/M codes and Heidenhain keywords inserted) and ran each mutant through
:func:`interpolators.load_program` and :func:`interpolators.interpolate` with both profiles.
"""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import interpolate, parse_program
from interpolators.context import INTERPOLATION_CONTEXT
from interpolators.limits import DEFAULT_LIMITS
from interpolators.profiles import scurve_phases
from vcnc.errors import GCodeError


def _program(text: str):
    return parse_program(text, source="bad.nc", context=INTERPOLATION_CONTEXT)


def test_scurve_refuses_a_move_too_long_for_max_samples_before_ruckig():
    """A 4e8 mm move: ruckig raised ``RuckigError`` on it before the sample count was checked; now the
    S-curve refuses it as the trapezoid does, naming the file and the sample budget."""
    program = _program("G1 X399800000 F2000\n")
    for profile in ("trapezoid", "scurve"):
        with pytest.raises(GCodeError, match=r"bad\.nc: program needs at least \d+ samples .* max_samples = 50000000"):
            interpolate(program, profile=profile)


def test_scurve_segment_on_the_border_of_two_ruckig_profile_types():
    """Limits of a move with an A axis word (``G1 X-20.131 Y23.5A9 Z-0.910 F200`` after a mutation) put a
    segment exactly on ``V = 2 A^2/J`` and ``L = 2 A^3/J^2``, where ruckig 0.19 raised ``RuckigError``
    ("error in step 1"). The retry with limits 1e-9 smaller gives the profile (0.2 s: 0.05 s of jerk up,
    0.1 s down, 0.05 s up again) within the limits."""
    L, V, A, J = (float.fromhex(h) for h in ("0x1.cfb2f4532fd4fp-5", "0x1.21cfd8b3fde51p+0",
                                             "0x1.6a43cee0fd5e5p+3", "0x1.c4d4c2993cb5fp+7"))
    assert V == pytest.approx(2 * A * A / J, rel=1e-15) and L == pytest.approx(2 * A**3 / J**2, rel=1e-15)
    dur, p0, pv, pa, pj = scurve_phases(np.array([L]), np.zeros(1), np.zeros(1), np.array([V]), np.array([A]),
                                        np.array([J]))
    assert dur.sum() == pytest.approx(0.2, rel=1e-8)
    assert np.all(np.abs(pj) <= J) and np.all(np.abs(pa) <= A * (1 + 1e-12)) and np.all(pv <= V * (1 + 1e-12))
    # end of the last phase: at the target, at rest
    t = dur[0, -1]
    end = p0[0, -1] + pv[0, -1] * t + pa[0, -1] * t**2 / 2 + pj[0, -1] * t**3 / 6
    assert end == pytest.approx(L, rel=1e-9)


def test_inverse_time_zero_length_move_has_a_finite_feed():
    """G93 (inverse time) with a repeated block: the zero-length move had feed ``inf`` in the interpreted
    blocks; it is 0 (no length in 1/F minutes) and the program interpolates with finite setpoints."""
    program = _program("G93\nG1 X1 F10\nG1 X1 F10\nG1 X2 F10\n")
    assert [b.feed for b in program.blocks] == pytest.approx([1 / 6, 0.0, 1 / 6])
    for profile in ("trapezoid", "scurve"):
        sp = interpolate(program, profile=profile, limits=DEFAULT_LIMITS)
        assert np.all(np.isfinite(sp.position)) and sp.position[-1, 0] == pytest.approx(2.0)


@pytest.mark.parametrize("line, expected", [("12.8 Z+0", "12.0 .. 12.1"), ("9.2 X+1", "9.0 .. 9.1"),
                                            ("1.6 X+1", "1.0 .. 1.5"), ("2.5 X+3", "2.0 .. 2.4")])
def test_heidenhain_cycle_line_a_cycle_does_not_have(line, expected):
    """``CYCL DEF 12.8`` (``7.3`` of a corpus program mutated to ``12.8698``) raised ``KeyError: 12``: a line
    number beyond a cycle's last (12 PGM CALL has 12.1, 9 DWELL 9.1, 1 PECKING 1.1-1.5, 2 TAPPING 2.1-2.4) is
    an error naming the cycle, the line and the lines it has."""
    from interpolators.heidenhain import parse_heidenhain

    number, sub = line.split()[0].split(".")
    with pytest.raises(GCodeError, match=rf"cycle {number}\.{sub}: cycle {number} has no line {sub}.*"
                                         rf"CYCL DEF {expected}") as info:
        parse_heidenhain(f"0 BEGIN PGM T MM\n1 CYCL DEF {line}\n2 END PGM T MM\n", source="bad.h")
    assert info.value.line == 2
