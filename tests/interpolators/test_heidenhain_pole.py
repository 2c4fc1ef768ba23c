"""The pole CC under coordinate transformations and TOOL CALL, the transition arc at every outside corner under
RL/RR, and the tangent after a ``C`` arc whose written end misses the pole's circle by its rounding: hand-written
TNC programs, each checked against the independent reference (tests/interpolators/reference_heidenhain.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.compensation import compensate
from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.program import Block
from tests.interpolators.reference_heidenhain import checked_program
from toolpaths.geometry import Line
from vcnc.errors import GCodeError, InputError

HOME = MachineContext(home=(0.0, 0.0, 300.0))
START = "L X+0 Y+0 Z+0 R0 F100\nCC X+10 Y+0\n"


def checked(body: str, *, exact: bool = True):
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", HOME, exact=exact)


def rows(prog, line: int) -> list[tuple[str, list[float]]]:
    return [(b.kind, np.round(b.target, 6).tolist()) for b in prog.blocks if b.line == line]


# --- the pole keeps its program coordinates --------------------------------------------------------------------

def test_pole_set_before_a_datum_shift_is_measured_from_the_new_datum():
    # TNC 426 pilot, "Circle Center and Pole: CC": "An absolutely defined circle center or pole is always measured
    # from the workpiece datum"; cycle 7 moves that datum by +20: the pole X+10 is at machine 30, PR 5 at 35
    prog = checked(START + "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+20\nLP PR+5 PA+0")
    assert rows(prog, 6) == [("line", [35.0, 0.0, 0.0])]


def test_pole_set_before_a_rotation_turns_with_it():
    # ROT+90 about the datum: the pole (10, 0) is at (0, 10), PA+0 along the turned X axis (+Y): (0, 15)
    prog = checked(START + "CYCL DEF 10.0 ROTATION\nCYCL DEF 10.1 ROT+90\nLP PR+5 PA+0")
    assert rows(prog, 6) == [("line", [0.0, 15.0, 0.0])]


def test_pole_set_before_a_mirror_or_a_scaling_is_mapped_as_the_points_are():
    prog = checked(START + "CYCL DEF 8.0 MIRROR IMAGE\nCYCL DEF 8.1 X\nLP PR+5 PA+0")
    assert rows(prog, 6) == [("line", [-15.0, 0.0, 0.0])]
    prog = checked(START + "CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL2\nLP PR+5 PA+0")
    assert rows(prog, 6) == [("line", [30.0, 0.0, 0.0])]


def test_an_arc_about_a_pole_set_before_a_shift_runs_about_its_shifted_point():
    # the tool at machine 20 (program 0 after the shift): C about the pole, machine 30, to program 20 (machine 40)
    prog = checked(START + "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+20\nL X+0 Y+0\nC X+20 Y+0 DR+")
    arc = next(b for b in prog.blocks if b.line == 7)
    assert np.round(arc.target, 6).tolist() == [40.0, 0.0, 0.0]
    assert np.round(arc.segment.center, 6).tolist()[:2] == [30.0, 0.0]
    # from where the tool stands (machine 0) the same end is off that circle: refused, naming both radii
    with pytest.raises(GCodeError, match=r"t.h:6:1: arc end point is not on the circle: start radius 30 mm, end "
                                         r"radius 10 mm"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + START + "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+20\n"
                         "C X+20 Y+0 DR+\nEND PGM T MM\n", source="t.h", context=HOME)


def test_incremental_pole_after_a_shift_is_from_the_last_position_in_the_new_system():
    # TNC 310 pilot: "An incrementally defined circle center or pole is always measured from the last programmed
    # position"; the tool at machine 5 is at program -15 after the shift, the pole IX+5 at program -10 (machine 10)
    prog = checked("L X+5 Y+0 Z+0 R0 F100\nCYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X+20\nCC IX+5 IY+0\nLP PR+5 PA+90")
    assert rows(prog, 6) == [("line", [10.0, 5.0, 0.0])]


def test_cc_without_coordinates_is_the_last_programmed_position():
    # TNC 425/415 B/407 manual, "Circle Center CC": "You can define the last programmed position as circle center
    # by entering an empty CC block"
    prog = checked("L X+5 Y+0 Z+0 R0 F100\nCC\nL X+15\nLP PR+5 PA+90")
    assert rows(prog, 5) == [("line", [5.0, 5.0, 0.0])]


def test_lp_without_any_cc_is_refused():
    with pytest.raises(GCodeError, match=r"t.h:3:1: LP without a pole .*expected a CC block before LP"):
        parse_heidenhain("0 BEGIN PGM T MM\nL X+0 Y+0 Z+0 R0 F100\nLP PR+5 PA+90\nEND PGM T MM\n", source="t.h",
                         context=HOME)


def test_pole_is_a_point_of_the_part_across_a_tool_call():
    # a pole in ZX at the part's Z 0 set with a tool of length 0; after TOOL CALL of a tool 10 longer, the tip
    # still turns about the part's Z 0: PA+90 (from +Z towards +X) to X 15, Z 0, the spindle 10 higher
    tools = "TOOL DEF 1 L+0 R+2\nTOOL DEF 2 L+10 R+2\nTOOL CALL 1 Z S100\n"
    prog = checked(tools + "L X+0 Y+0 Z+0 R0 F100\nCC Z+0 X+10\nTOOL CALL 2 Z S100\nL X+0 Y+0 Z+0 R0 F100\n"
                           "LP PR+5 PA+90")
    assert rows(prog, 9) == [("line", [15.0, 0.0, 10.0])]
    prog = checked(tools + "L X+0 Y+0 Z+0 R0 F100\nCC X+10 Y+0\nTOOL CALL 2 Z S100\nL X+0 Y+0 Z+0 R0 F100\n"
                           "LP PR+5 PA+90")
    assert rows(prog, 9) == [("line", [10.0, 5.0, 10.0])]


# --- a transition arc at every outside corner -------------------------------------------------------------------

TOOL = "TOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z S100\nL X-10 Y+10 Z+0 R0 F100\n"


def test_small_outside_corner_gets_its_transition_arc():
    # TNC 640 ISO manual 34059x-05, 5.3 "Radius compensation: Machining corners": "the TNC moves the tool around
    # outside corners on a transitional arc" - also a turn of atan(0.5 / 20) = 0.025 rad, which LinuxCNC's
    # 0.05 rad tolerance joins straight: the arc of radius 5 about (20, 0) from (20, 5) to 5 along the normal of
    # the next line; the inside corner after it at the offsets' intersection ("The TNC calculates the
    # intersection of the tool center paths at inside corners")
    prog = checked(TOOL + "L X+0 Y+0 RL\nL X+20 Y+0\nL X+40 Y-0.5\nL X+60 Y-0.5\nL X+70 Y+20 R0", exact=False)
    n = np.array([0.5, 20.0]) / math.hypot(0.5, 20.0)
    corner = [b for b in prog.blocks if b.line == 7]
    assert [b.kind for b in corner] == ["arc", "line"]
    assert np.round(corner[0].start, 6).tolist() == [20.0, 5.0, 0.0]
    assert np.round(corner[0].target, 6).tolist() == np.round([20.0 + 5.0 * n[0], 5.0 * n[1], 0.0], 6).tolist()
    assert np.round(corner[0].segment.center, 6).tolist()[:2] == [20.0, 0.0]
    x = 20.0 + 5.0 * n[0] + (5.0 * n[1] - 4.5) * 40.0  # the second line's offset down to y = 4.5 (slope -1/40)
    assert np.round(corner[1].target, 6).tolist() == np.round([x, 4.5, 0.0], 6).tolist()


def test_convex_tolerance_is_the_dialects_parameter():
    # the ISO readers keep LinuxCNC's rule (no arc for a turn of at most 0.05 rad); the TNC passes its own
    def blocks(points):
        out = []
        for i, (a, b) in enumerate(zip(points[:-1], points[1:])):
            a3, b3 = np.array([*a, 0.0]), np.array([*b, 0.0])
            out.append(Block(kind="line", target=b3, start=a3, segment=Line(a3, b3), feed=10.0, line=i + 1))
        return out

    path = blocks([[-10, 0], [0, 0], [10, 0], [20, -0.2], [30, -10]])
    assert [b.kind for b in compensate(path, side="left", radius=2.0, plane=2)] == ["line"] * 4
    kinds = [b.kind for b in compensate(path, side="left", radius=2.0, plane=2, convex_tolerance=1e-9)]
    assert kinds == ["line", "line", "arc", "line", "line"]
    with pytest.raises(InputError, match="convex_tolerance must be > 0 and < pi/2 rad, got 0.0"):
        compensate(path, side="left", radius=2.0, plane=2, convex_tolerance=0.0)


# --- a C end rounded off its circle -----------------------------------------------------------------------------

ROUNDED = "L X+20 Y-10 Z+0 R0 F100\nL X+10 Y+0\nCC X+0 Y+0\nC X+7.0711 Y+7.0711 DR+\n"


def run_centre() -> np.ndarray:
    """The centre of the circle through (10, 0) and (7.0711, 7.0711) nearest CC (0, 0): on the chord's bisector."""
    a, b = np.array([10.0, 0.0]), np.array([7.0711, 7.0711])
    u = (b - a) / np.hypot(*(b - a))
    m = (a + b) / 2.0
    return -u * float(-m @ u)  # CC less its component along the chord, measured from the chord's middle


def test_dep_lt_leaves_along_the_arc_the_control_runs():
    # C X+7.0711 Y+7.0711 about (0, 0) from (10, 0): radius 10.00002 at the end, within the input tolerance
    # (TNC 410 manual, "Circular path C": "Input tolerance: up to 0.016 mm"); the arc runs on the circle through
    # both ends nearest the pole, and DEP LT leaves along that arc's end tangent (our reading: no kink)
    prog = checked("TOOL DEF 1 L+0 R+2\nTOOL CALL 1 Z S100\n" + ROUNDED.replace("L X+10 Y+0\n", "L X+10 Y+0 RL\n")
                   + "DEP LT LEN5 R0 F500", exact=False)
    c = run_centre()
    end = np.array([7.0711, 7.0711])
    radial = (end - c) / np.hypot(*(end - c))
    tangent = np.array([-radial[1], radial[0]])
    want = end + 5.0 * tangent  # DEP LT ... R0: P_N is LEN from the last contour point on its extension
    got = [b for b in prog.blocks if b.line == 8][-1].target
    assert np.round(got[:2], 6).tolist() == np.round(want, 6).tolist()
    assert abs(float(np.hypot(*c))) > 1e-6  # the run centre is not CC: the case the rounding makes


def test_ct_and_rnd_after_a_rounded_c_join_its_end_tangent():
    prog = checked(ROUNDED + "CT X+0 Y+20")
    ct = next(b for b in prog.blocks if b.line == 6)
    c, end = run_centre(), np.array([7.0711, 7.0711])
    radial = (end - c) / np.hypot(*(end - c))
    # the CT arc's centre lies on the C arc's end radius (the two arcs tangent at the end point)
    v = np.asarray(ct.segment.center[:2]) - end
    assert abs(float(v[0] * radial[1] - v[1] * radial[0])) < 1e-9
    checked(ROUNDED + "RND R2\nL X+0 Y+20")
    checked(ROUNDED + "RND R2\nC X+0 Y+10")
