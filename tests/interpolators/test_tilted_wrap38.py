"""A tilted plane or a tool direction on a rotary axis that wraps at 360 deg (``[axes.c] wrap = true``): the
solution the control takes is the one its axes really turn least to (:meth:`interpolators.tilted.Kinematics.choose`
``turns``), its wrapping axis' angle stated as the axis shows it, in [0, 360); G53.1 ranks FANUC's way (the master
axis' move first). Hand-written programs, each worked out here, also checked against the independent references
(reference_heidenhain.py; reference_iso.py, which models G68.2 / G53.1 since session 38). Before session 38
``choose`` compared the unwrapped angles: C shown at 280 with ``PLANE SPATIAL SPA+0 SPB+30 SPC+90`` took B+30 C+90 (C
turning 190 deg) where B-30 C-90 (C270 shown) is 10 deg away."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from interpolators.iso import parse_iso
from interpolators.rotary_wrap import wrapped_end
from interpolators.tilted import Kinematics, RotaryAxis, Solution, spatial
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table

#: A B/C tilting table: B about Y (tilting, -120..120 deg), C about Z (the part's), pivots at the machine zero.
BC = Kinematics(axes=(RotaryAxis(name="b", direction="Y", limits=(-120.0, 120.0)), RotaryAxis(name="c")))
#: An A/C tilting table, A about X.
AC = Kinematics(axes=(RotaryAxis(name="a", direction="X", limits=(-120.0, 120.0)), RotaryAxis(name="c")))
#: The TNC on the B/C table, C wrapping, the TNC's own rule (no M126: the difference to the angle shown).
TNC = MachineContext(extra_axes=("b", "c"), wrapped_axes=("c",), kinematics=BC, tools={1: Tool(number=1, length=20.0)})
#: A Fanuc on the A/C table, C a roll-over axis (RAB = 0: the shorter way).
FANUC = MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a", "c"), wrapped_axes=("c",), kinematics=AC,
                       tools={1: Tool(number=1, length=20.0)})


def _tnc(body: str, context: MachineContext = TNC):
    text = "0 BEGIN PGM W MM\n1 TOOL CALL 1 Z S1000\nL X+0 Y+0 Z+50 B+0 C+0 R0 FMAX\n" + body + "\nEND PGM W MM\n"
    prog = parse_heidenhain(text, source="w.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def _iso(text: str, context: MachineContext):
    """The ISO reader's blocks of ``text``, checked against tests/interpolators/reference_iso.py."""
    prog = parse_iso(text, source="t.nc", context=context)
    match = match_blocks(iso_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def _bc(prog) -> list[list[float]]:
    return [[round(float(b.extra_target[i]), 6) + 0.0 for i in (1, 2)] for b in prog.blocks]


@pytest.mark.parametrize(("rule", "expected"), [
    ("shortest", (-30.0, 270.0)),  # C 280 -> 270: -10 deg (C90: +170)
    ("difference", (-30.0, 270.0)),  # the shown 280 to 270: -10 (to 90: -190)
    ("sign", (30.0, 90.0)),  # a positive word turns positive: to 90 +170, to 270 +350
])
def test_choose_weighs_a_wrapping_axis_by_the_turn_it_makes(rule: str, expected: tuple[float, float]):
    """B/C table, C shown at 280: ``PLANE SPATIAL SPA+0 SPB+30 SPC+90`` needs B+30 C+90 or B-30 C-90 (= C270)."""
    plane = spatial(0.0, 30.0, 90.0)
    turn = {"c": lambda angle: wrapped_end(angle, 280.0, 0.0, rule) - 280.0}
    got = BC.choose(plane, Solution(0.0, 280.0), turns=turn)
    assert (got.outer, got.inner) == pytest.approx(expected)
    # an axis that does not wrap: the unwrapped distance, |90 - 280| against |-90 - 280|
    plain = BC.choose(plane, Solution(0.0, 280.0))
    assert (plain.outer, plain.inner) == pytest.approx((30.0, 90.0))


def test_choose_on_a_wrapping_axis_keeps_seq_and_the_limits():
    """SEQ+ keeps B+30 C90 whatever C's turn (the master axis' sign), and a plane C cannot reach modulo its
    limits is still refused."""
    plane = spatial(0.0, 30.0, 90.0)
    turn = {"c": lambda angle: wrapped_end(angle, 280.0, 0.0, "shortest") - 280.0}
    got = BC.choose(plane, Solution(0.0, 280.0), sequence=1, turns=turn)
    assert (got.outer, got.inner) == pytest.approx((30.0, 90.0))
    narrow = Kinematics(axes=(BC.axes[0], RotaryAxis(name="c", limits=(0.0, 100.0))))
    got = narrow.choose(plane, Solution(0.0, 280.0), turns=turn)  # C270 (= -90) has no turn within 0..100
    assert (got.outer, got.inner) == pytest.approx((30.0, 90.0))


@pytest.mark.parametrize(("start", "end"), [("L C+280 FMAX", 270.0), ("L IC+640 FMAX", 630.0)])
def test_tnc_plane_turn_takes_the_solution_c_turns_least_to(start: str, end: float):
    """C shown at 280 (``L C+280``, or 640 unwrapped): ``PLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN`` takes B-30 C270,
    -10 deg by the TNC's own rule (TNC7 user's manual 81762x-17, "Tilting solution": "choose the possible solution
    with the shortest path"); before, B+30 C+90, -190 deg. Q122 holds 270, the angle shown."""
    prog = _tnc(f"{start}\nPLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN FMAX\nPLANE RESET STAY\nL X+Q122 Y+Q121 FMAX")
    assert _bc(prog)[2] == [-30.0, end]
    assert prog.blocks[-1].target[:2] == pytest.approx([270.0, -30.0])


def test_tnc_plane_under_m126_and_seq_on_a_wrapping_axis():
    """Under M126 ``L C+280`` turns -80 (C at -80, shown 280); the shorter way to 270 (-10, to -90) picks the same;
    SEQ+ keeps B+30, C to 90 the shorter way (+170)."""
    assert _bc(_tnc("L C+280 FMAX M126\nPLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN FMAX"))[-2:] == [[0.0, -80.0],
                                                                                            [-30.0, -90.0]]
    prog = _tnc("L C+280 FMAX M126\nPLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN FMAX SEQ+")
    assert _bc(prog)[-1] == [30.0, 90.0]


def test_tnc_cycle_19_with_f_takes_the_nearest_solution_of_a_wrapping_axis():
    """Cycle 19 positions the axes itself with F (as PLANE .. MOVE): from C shown 280 to B-30 C270."""
    prog = _tnc("L C+280 FMAX\nCYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 A+0 B+30 C+90 F1000")
    assert _bc(prog)[-1] == [-30.0, 270.0]


def test_tnc_tool_direction_under_m128_turns_a_wrapping_axis_the_shorter_way():
    """C at 370 (``L IC+370``), ``LN .. TX+0 TY+0.5 TZ+0.866`` under M128: T = (cos C sin B, sin C sin B, cos B)
    gives B+30 C+90 or B-30 C-90. A wrapping C turns +80 to 450 (B+30); as a linear axis within its limits -360..360
    the nearest are 90 (-280) and 270 (-100), so B-30 C270 (before: the same on a wrapping C)."""
    body = "L IC+370 FMAX\nM128\nLN X+10 Y+0 Z+0 NX+0 NY+0 NZ+1 TX+0 TY+0.5 TZ+0.8660254 F600"
    assert _bc(_tnc(body))[-1] == pytest.approx([30.0, 450.0], abs=1e-6)
    linear = dataclasses.replace(TNC, wrapped_axes=())
    assert _bc(_tnc(body, linear))[-1] == pytest.approx([-30.0, 270.0], abs=1e-6)


@pytest.mark.parametrize(("rule", "expected"), [(None, [-30.0, 270.0]), ("shortest", [-30.0, 270.0]),
                                                ("sign", [30.0, 450.0])])
def test_g53_1_takes_the_solution_a_wrapping_axis_turns_least_to(rule, expected):
    """C at 280 (``G91 C280.``), ``G68.2 I90. J30. K0`` (A+30 C+90 or A-30 C-90), ``G53.1``. A roll-over C (Fanuc
    RAB = 0, the dialect's own) reaches C270 turning -10 deg, C90 +170: A-30 C270 (before: A+30 C+90, +170). Under
    RAB = 1 (``sign``) the positive word turns positive: to 90 +170, to 270 +350, so A+30 to 450."""
    ctx = dataclasses.replace(FANUC, wrap_direction=rule)
    prog = _iso("G21 G90\nG0 A0 C0\nG91 G0 C280.\nG90\nG68.2 X0 Y0 Z0 I90. J30. K0\nG53.1\nM30\n", ctx)
    last = prog.blocks[-1]
    assert [float(last.extra_target[0]), float(last.extra_target[2])] == pytest.approx(expected)
    assert np.allclose(last.target, last.start)


def test_g43_5_turns_a_wrapping_axis_the_shorter_way():
    """C at 370 (``G91 C370.``), ``G43.5 .. I0.5 J0 K0.866``: T = (sin C sin A, -cos C sin A, cos A) gives A+30 C+90
    or A-30 C-90. FANUC 15i B-63323EN-1/03 10.4.10 note 4 ("shortcut control so that the amount of movement does not
    exceed 180°"): a wrapping C turns +80 to 450 with A+30 (before: the K1 block had brought C back within its limits
    -360..360, to 10, as it still does on a C that does not wrap, then A+30 C+90)."""
    text = ("G21 G90\nG0 A0 C0\nG91 G0 C370.\nG90\nG0 G43.5 H1 X0 Y0 Z50. I0 J0 K1.\n"
            "G1 X10. I0.5 J0 K0.8660254 F600.\nG49\nM30\n")
    for ctx, expected in ((FANUC, [30.0, 450.0]), (dataclasses.replace(FANUC, wrapped_axes=()), [30.0, 90.0])):
        prog = _iso(text, ctx)
        chords = [b for b in prog.blocks if b.line == 6]
        assert float(chords[0].extra_start[2]) == (370.0 if ctx.wrapped_axes else 10.0)  # after the K1 block
        last = chords[-1]
        assert [float(last.extra_target[0]), float(last.extra_target[2])] == pytest.approx(expected, abs=1e-6)


@pytest.mark.parametrize(("start", "expected"), [
    ("G0 A5. C-170.", [30.0, -270.0]),  # A moves 25 (A-30: 35); C to -270, 100 deg, where -90 is 80
    ("G0 A0 C-170.", [-30.0, -90.0]),  # A moves 30 either way: the smaller C move, 80 to -90 (to -270: 100)
    ("G0 A0 C0", [30.0, 90.0]),  # a tie in every rule: the positive master angle
])
def test_g53_1_takes_fanucs_output_angles(start: str, expected: list[float]):
    """FANUC Series 16i/18i-MB operator's manual, "Angle of rotation axis": of the "computed angles" (every turn of 360
    deg of the two solutions, within the limits), the pair whose master (first rotation) axis moves least, then the
    slave. On the A/C table, C not wrapping, ``G68.2 I90. J30. K0`` needs A+30 C+90 or A-30 C-90. From A5 C-170 the
    master rule takes A+30 C-270; before session 38 the sum of both travels, each angle in (-180, 180] first, took
    A-30 C-90."""
    ctx = dataclasses.replace(FANUC, wrapped_axes=())
    prog = _iso(f"G21 G90\n{start}\nG68.2 X0 Y0 Z0 I90. J30. K0\nG53.1\nM30\n", ctx)
    last = prog.blocks[-1]
    assert [float(last.extra_target[0]), float(last.extra_target[2])] == pytest.approx(expected)


def test_g53_1_leaves_a_wrapping_axis_where_it_is_when_the_plane_needs_no_turn():
    """``G68.2 .. I0 J0 K114.823`` keeps the tool axis along Z: A to 0, C stays (any C will do). C at -110.319 under
    RAB = 1 (``sign``): the angle it shows, 249.681 reduced in floating point to 249.68099999999998, is where C is,
    not a whole turn away (before: G53.1 turned C +360 deg to 249.681)."""
    ctx = dataclasses.replace(FANUC, wrap_direction="sign")
    prog = _iso("G21 G90\nG0 A0 C0\nG91 G0 C-110.319\nG90\nG0 A47.203\nG68.2 X0 Y0 Z0 I0 J0 K114.823\nG53.1\nM30\n",
                ctx)
    assert [float(prog.blocks[-1].extra_target[i]) for i in (0, 2)] == pytest.approx([0.0, -110.319])


def test_g43_5_from_beyond_the_limits_takes_the_nearest_turn_within_them():
    """C at 880 (``G91 C880.``, beyond its limits -360..360, not wrapping), ``G43.5 .. I0.5 J0 K0.866``: A+30 C+90 or
    A-30 C-90. Within the limits C90 is 790 deg away and 270 (= -90) 610: A-30 C270 (before: the turns searched only
    around 880, none within the limits, so C-90, 970 deg away, and A+30 C90 won)."""
    ctx = dataclasses.replace(FANUC, wrapped_axes=())
    prog = _iso("G21 G90\nG0 A0 C0\nG91 G0 C880.\nG90\nG0 G43.5 H1 X0 Y0 Z50. I0.5 J0 K0.8660254\nG49\nM30\n", ctx)
    last = [b for b in prog.blocks if b.line == 5][-1]
    assert [float(last.extra_target[0]), float(last.extra_target[2])] == pytest.approx([-30.0, 270.0], abs=1e-6)
