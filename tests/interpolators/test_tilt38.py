"""Two tilted-plane solutions fuzz38 found decided by floating-point noise (session 38), each worked out by hand and
checked against the independent references (reference_heidenhain.py, reference_iso.py).

1. A tie: from B0 C30 on a B/C table, ``PLANE RELATIV SPA+10`` on a plane turned by SPC+30 needs B+10 C-60 or B-10
   C+120, both 100 deg of travel; the reader's sum came out 99.99999999999999 and took B-10 C120 where the rule (a tie
   to the positive master angle) gives B+10 C-60 (fuzz38: ``drive.py tnc 977786``).
2. Near the pole: a tool axis 5e-5 deg off the C axis was taken as one solution (``1 - beta**2 < 1e-12``) whose C
   angle came from a vector with no part square to C: B0 C0 instead of B-5e-5 C-90 (``drive.py tnc 985899``).
   :meth:`interpolators.tilted.Kinematics.solutions` now counts one solution only where the tool axis is the C axis'
   own within the same 1e-9 rad that frees the C angle (TNC7 user's manual 81762x-17, "free rotary axis": the
   rotary axis and the tool axis "parallel in the tilting situation"; the manual gives no tolerance).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.iso import parse_iso
from interpolators.tilted import Kinematics, RotaryAxis, Solution, relative, spatial
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table

#: A B/C tilting table (B about Y, -120..120 deg; C about Z), pivots at the machine zero.
BC = Kinematics(axes=(RotaryAxis(name="b", direction="Y", limits=(-120.0, 120.0)), RotaryAxis(name="c")))
#: An A/C tilting table, A about X.
AC = Kinematics(axes=(RotaryAxis(name="a", direction="X", limits=(-120.0, 120.0)), RotaryAxis(name="c")))
TNC = MachineContext(extra_axes=("b", "c"), kinematics=BC, tools={1: Tool(number=1, length=20.0)})
FANUC = MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a", "c"), kinematics=AC,
                       tools={1: Tool(number=1, length=20.0)})


def _tnc(body: str):
    text = "0 BEGIN PGM W MM\n1 TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+50 B+0 C+0 R0 FMAX\n" + body + "\nEND PGM W MM\n"
    prog = parse_heidenhain(text, source="w.h", context=TNC)
    match = match_blocks(heidenhain_reference(text, TNC), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def _g53_1(words: str) -> list[float]:
    text = f"G21 G90\nG0 A0 C0\nG68.2 X0 Y0 Z0 {words}\nG53.1\nM30\n"
    prog = parse_iso(text, source="t.nc", context=FANUC)
    match = match_blocks(iso_reference(text, FANUC), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return [float(prog.blocks[-1].extra_target[i]) for i in (0, 2)]


def test_choose_ties_travels_equal_within_the_tolerance():
    """SPC+30 then RELATIV SPA+10: the tool axis Rz(30) Rx(10) e_z = (sin 30 sin 10, -cos 30 sin 10, cos 10) =
    (cos C sin B, sin C sin B, cos B): B+10 C-60 or B-10 C+120; from B0 C30 each travels 10 + 90 deg."""
    plane = relative(spatial(0.0, 0.0, 30.0), "X", 10.0)
    total = [abs(s.outer) + abs(s.inner - 30.0) for s in BC.solutions(plane)]
    assert total[0] != total[1] and total == pytest.approx([100.0, 100.0])  # the noise the tie must not see
    chosen = BC.choose(plane, Solution(outer=0.0, inner=30.0))
    assert (chosen.outer, chosen.inner) == pytest.approx((10.0, -60.0))


def test_tnc_plane_relativ_tie_takes_the_positive_master_angle():
    """fuzz38's seed 977786 by hand: TABLE ROT turns C to 30 (the plane's X onto the machine's X), then the tie."""
    prog = _tnc("PLANE SPATIAL SPA+0 SPB+0 SPC+30 TURN FMAX TABLE ROT\nPLANE RELATIV SPA+10 TURN FMAX")
    assert [float(v) for v in prog.blocks[-2].extra_target[1:3]] == pytest.approx([0.0, 30.0])
    assert [float(v) for v in prog.blocks[-1].extra_target[1:3]] == pytest.approx([10.0, -60.0])


@pytest.mark.parametrize("tilt", [5e-5, -5e-5, 1e-6])
def test_solutions_near_the_pole_keep_their_c_angle(tilt: float):
    """A tool axis ``tilt`` deg off C, turned -90 about Z: Rz(-90) Ry(tilt) e_z = (0, -sin t, cos t), so B = +-t with
    C -90 / +90; each solution makes it the spindle axis to 1e-12 (before: one solution B0 C0, 8.7e-7 off)."""
    plane = spatial(0.0, tilt, -90.0)
    found = BC.solutions(plane)
    got = sorted((s.outer, s.inner) for s in found)
    assert [v for pair in got for v in pair] == pytest.approx([-tilt, 90.0, tilt, -90.0] if tilt > 0 else
                                                              [tilt, -90.0, -tilt, 90.0], rel=1e-9, abs=1e-12)
    for s in found:
        assert np.allclose(BC.rotation(s) @ plane[:, 2], [0.0, 0.0, 1.0], rtol=0.0, atol=1e-12)


def test_solutions_at_the_pole_leave_c_free():
    """Within 1e-9 rad of the C axis the tool axis is C's own: one solution, B0, C free (NaN)."""
    found = BC.solutions(spatial(0.0, 1e-8, -90.0))  # 1.7e-10 rad
    assert len(found) == 1 and found[0].outer == 0.0 and math.isnan(found[0].inner)


def test_tnc_plane_relativ_near_the_pole():
    """fuzz38's minimal case of seed 985899: SPB+20 SPC-90 then RELATIV SPB-20.00005 tilts the tool 5e-5 deg; from
    B+20 C-90 (TURN of the first PLANE) B-5e-5 C-90 (C stays, B moves 20) against B+5e-5 C+90 (C 180 more).
    ``L X+10 Y+0`` then lands where the reference puts it, machine (10, 10) (before: B0 C0, the point at (10, -10))."""
    prog = _tnc("PLANE SPATIAL SPA+0 SPB+20 SPC-90 TURN FMAX\nPLANE RELATIV SPB-20.00005 TURN FMAX\n"
                "L X+10 Y+0 Z+0 FMAX")
    last = prog.blocks[-1]
    assert [float(v) for v in last.extra_target[1:3]] == pytest.approx([-5e-5, -90.0], abs=1e-9)


def test_g53_1_near_the_pole_keeps_its_c_angle():
    """FANUC G68.2 shares ``Kinematics.solutions``: ``I90. J0.00005 K0`` tilts the tool Rz(90) Rx(5e-5) e_z =
    (sin 5e-5, 0, cos 5e-5) = (sin C sin A, -cos C sin A, cos A): A+5e-5 C+90 or A-5e-5 C-90; from A0 C0 both move
    the same (master, then slave), both as far from 0: the positive master angle (before: A0 C0)."""
    assert _g53_1("I90. J0.00005 K0") == pytest.approx([5e-5, 90.0], abs=1e-9)


def test_g53_1_at_the_pole_leaves_c_where_it_is():
    """``J0.00000001`` (1.7e-10 rad) is the C axis' own direction: A0, C stays at 0."""
    assert _g53_1("I90. J0.00000001 K0") == pytest.approx([0.0, 0.0], abs=1e-9)
