"""The geometry of the tilted working plane on a tilting-table machine (interpolators/tilted.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.tilted import (
    Kinematics,
    RotaryAxis,
    Solution,
    TiltError,
    euler,
    points,
    projected,
    relative,
    spatial,
    tilted_frame,
    vector,
)
from vcnc.core.errors import InputError, MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine

AC = Kinematics(axes=(RotaryAxis(name="a", limits=(-120.0, 120.0)), RotaryAxis(name="c")))
BC = Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0), limits=(-10.0, 110.0)),
                      RotaryAxis(name="c", pivot=(5.0, 0.0, 0.0))))


def angles(s: Solution) -> tuple[float, float]:
    return s.outer, s.inner


def test_itnc_example_of_a_tilting_table_a_and_rotary_table_c():
    """iTNC 530 user's manual (DIN/ISO, 2010), "The PLANE Function", example of a machine with a tilting
    table A and a rotary table C, PLANE SPATIAL SPA+0 SPB+45 SPC+0: from A+0 C+0 (not programmed SEQ)
    A+45 C+90; from A+0 C-105 A-45 C-90; SEQ+ from A+0 C-135: A+45 C+90; with -90 < A < +10 A-45 C-90,
    and with SEQ+ an error."""
    plane = spatial(0.0, 45.0, 0.0)
    assert angles(AC.choose(plane, Solution(0.0, 0.0))) == pytest.approx((45.0, 90.0))
    assert angles(AC.choose(plane, Solution(0.0, -105.0))) == pytest.approx((-45.0, -90.0))
    assert angles(AC.choose(plane, Solution(0.0, -135.0), sequence=1)) == pytest.approx((45.0, 90.0))
    assert angles(AC.choose(plane, Solution(0.0, 0.0), sequence=-1)) == pytest.approx((-45.0, -90.0))
    limited = Kinematics(axes=(RotaryAxis(name="a", limits=(-90.0, 10.0)), RotaryAxis(name="c")))
    assert angles(limited.choose(plane, Solution(0.0, 0.0))) == pytest.approx((-45.0, -90.0))
    with pytest.raises(TiltError, match="positive A within their limits"):
        limited.choose(plane, Solution(0.0, 0.0), sequence=1)


def test_b45_on_a_bc_trunnion_with_a_pivot_by_hand():
    """SPB+45 on a B/C table: B+45 (C+0) or B-45 (C+180). The part turns by -45 deg about Y round the
    B pivot (0, 0, -50); the datum (10, 0, 0) is (10, 0, 50) from it, turned: x = 10 cos45 - 50 sin45 =
    -28.284, z = 10 sin45 + 50 cos45 = 42.426, i.e. -7.574 in the machine; the tilted X runs along the
    machine's X (theta 0)."""
    plane = spatial(0.0, 45.0, 0.0)
    s = BC.choose(plane, Solution(0.0, 0.0))
    assert angles(s) == pytest.approx((45.0, 0.0))
    theta, origin = tilted_frame(BC, plane, s, (10.0, 0.0, 0.0))
    r = math.sqrt(0.5)
    assert theta == pytest.approx(0.0, abs=1e-12)
    assert origin == pytest.approx([10 * r - 50 * r, 0.0, 10 * r + 50 * r - 50.0])
    other = BC.solutions(plane)[1]  # outside the B limits -10 .. 110: choose never takes it
    assert angles(other) == pytest.approx((-45.0, 180.0))
    assert angles(BC.choose(plane, Solution(-10.0, 180.0))) == pytest.approx((45.0, 0.0))
    theta2, origin2 = tilted_frame(BC, plane, other, (10.0, 0.0, 0.0))
    # C+180 turns the part half round the C pivot (5, 0, 0) first: the datum comes to (0, 0, 0), which is
    # (0, 0, 50) from the B pivot; B-45 turns the part +45 deg about Y: x = 50 sin45, z = 50 cos45 - 50
    assert abs(theta2) == pytest.approx(180.0)
    assert origin2 == pytest.approx([50 * r, 0.0, 50 * r - 50.0])


@pytest.mark.parametrize("seed", range(5))
def test_tilted_plane_is_parallel_to_the_machine_xy(seed):
    """For any reachable plane, each solution maps program points p of the tilted plane to
    Rz(theta) p + origin: the tilted XY plane is parallel to the machine's, its arcs stay XY arcs."""
    rng = np.random.default_rng(seed)
    free = Kinematics(axes=(RotaryAxis(name="b", pivot=tuple(rng.uniform(-50, 50, 3)), limits=(-180, 180)),
                            RotaryAxis(name="c", pivot=tuple(rng.uniform(-50, 50, 3)))))
    plane = spatial(*rng.uniform(-60, 60, 3))
    datum = rng.uniform(-100, 100, 3)
    sols = free.solutions(plane)
    assert len(sols) == 2
    for s in sols:
        theta, origin = tilted_frame(free, plane, s, datum)
        c, si = math.cos(math.radians(theta)), math.sin(math.radians(theta))
        for p in rng.uniform(-30, 30, (4, 3)):
            machine = free.place(datum + plane @ p, s)
            assert machine == pytest.approx(origin + np.array([c * p[0] - si * p[1], si * p[0] + c * p[1], p[2]]))


def test_plane_definitions_agree():
    """Each PLANE form gives the same plane when it describes the same one."""
    assert spatial(30, 0, 0) == pytest.approx(euler(0, 30, 0))
    assert projected(25, 0, 0) == pytest.approx(spatial(0, 25, 0))
    assert projected(0, -35, 0) == pytest.approx(spatial(-35, 0, 0))
    r = spatial(20, -30, 40)
    assert vector(r[:, 0] * 3 + r[:, 2], r[:, 2] * 2) == pytest.approx(r)
    assert points((1, 2, 3), (1, 2, 3) + r[:, 0] * 5, (1, 2, 3) + r[:, 0] + r[:, 1] * 2) == pytest.approx(r)
    # the tilted Y of SPC+90 is the untilted -X: turning about it is turning about -X after the SPC turn
    assert relative(spatial(0, 0, 90), "Y", 45) == pytest.approx(spatial(-45, 0, 0) @ spatial(0, 0, 90))
    # TNC7 user's manual, "PLANE SPATIAL", notes: the spatial angles equal three PLANE RELATIV, first
    # SPC, then SPB, then SPA
    stepwise = relative(relative(relative(np.eye(3), "Z", 40), "Y", -30), "X", 20)
    assert stepwise == pytest.approx(spatial(20, -30, 40))
    assert BC.axial(Solution(45.0, 0.0)) == pytest.approx(spatial(0, 45, 0))
    with pytest.raises(TiltError, match="three points on a line"):
        points((0, 0, 0), (1, 0, 0), (2, 0, 0))


def test_one_tilting_axis_reaches_the_planes_square_to_it():
    """A 4-axis machine (one A table): Rx(A) e_z = (0, -sin A, cos A) is the tilted Z: SPA-90 -> A-90;
    a tilt about Y is out of its reach."""
    four = Kinematics(axes=(RotaryAxis(name="a", limits=(-120.0, 120.0)),))
    assert four.solutions(spatial(-90, 0, 0)) == [Solution(-90.0, 0.0)]
    assert angles(four.choose(spatial(30, 0, 0), Solution(0.0, 0.0))) == pytest.approx((30.0, 0.0))
    assert four.solutions(spatial(0, 30, 0)) == []
    with pytest.raises(TiltError, match="rotary axes A cannot tilt"):
        four.choose(spatial(0, 30, 0), Solution(0.0, 0.0))


def test_planes_the_axes_cannot_reach_and_head_machines():
    """A B/C table cannot turn the tool axis about X alone beyond its B limits; head kinematics are refused."""
    with pytest.raises(TiltError, match="cannot tilt the part"):
        BC.choose(spatial(0, -45, 0), Solution(0.0, 0.0), sequence=-1)
    head = Kinematics(kind="head", axes=BC.axes)
    with pytest.raises(TiltError, match="head tilts is not supported"):
        head.require_table()
    with pytest.raises(InputError, match="perpendicular"):
        Kinematics(axes=(RotaryAxis(name="b"), RotaryAxis(name="a", direction="Y")))
    with pytest.raises(InputError, match="outer axis c turns about the spindle"):
        Kinematics(axes=(RotaryAxis(name="c"), RotaryAxis(name="a")))
    with pytest.raises(InputError, match="limits"):
        RotaryAxis(name="b", limits=(10.0, -10.0))


def _machine_with_rotary_axes() -> str:
    base = builtin_machine_text("fadal-pid")  # axes x, y and no [program] table: its y tables are the last
    y = base[base.index("[axes.y]"):]
    return base + "\n" + y.replace("axes.y", "axes.b") + "\n" + y.replace("axes.y", "axes.c") + "\n"


def test_machine_file_reads_the_kinematics(tmp_path):
    path = tmp_path / "m.toml"
    kin = ('\n[program.kinematics]\nkind = "table"\n[[program.kinematics.axes]]\nname = "b"\ndirection = "Y"\n'
           'pivot = [0.0, 0.0, -50.0]\nlimits = [-10.0, 110.0]\n[[program.kinematics.axes]]\nname = "c"\n'
           'pivot = [5.0, 0.0, 0.0]\n')
    path.write_text(_machine_with_rotary_axes() + kin)
    ctx = load_machine(str(path)).context
    assert ctx.kinematics == BC
    assert MachineContext().kinematics is None
    one = kin[:kin.index('[[program.kinematics.axes]]\nname = "c"')]
    path.write_text(_machine_with_rotary_axes() + one)
    assert load_machine(str(path)).context.kinematics == Kinematics(axes=BC.axes[:1])
    path.write_text(_machine_with_rotary_axes() + kin.replace('name = "c"', 'name = "a"'))
    with pytest.raises(MachineError, match="names axis 'a', which has no"):
        load_machine(str(path))
    path.write_text(_machine_with_rotary_axes() + kin.replace('pivot = [5.0, 0.0, 0.0]', 'pivot = [5.0]'))
    with pytest.raises(MachineError, match="pivot"):
        load_machine(str(path))
