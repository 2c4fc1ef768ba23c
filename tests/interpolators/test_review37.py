"""Review of session 37's rotary axes that wrap at 360 deg (:mod:`interpolators.rotary_wrap`): a Fanuc roll-over
axis reads its position back within one rotation, and G53.1 turns a wrapping axis to a tilted plane the machine's
way. Hand-written programs; the numbers are worked by hand from the manual text each test names."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators.context import DIALECTS, MachineContext
from interpolators.heidenhain import parse_heidenhain
from interpolators.iso import parse_iso
from interpolators.tilted import Kinematics, RotaryAxis
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError


def _a_of(prog) -> list[float]:
    return [float(b.extra_target[0]) for b in prog.blocks]


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_fanuc_roll_over_axis_reads_its_position_within_one_rotation(dialect: str):
    """Fanuc Series 0i-MC B-63534EN/02, 20.2.1 "Rotary axis roll-over": A0, then ``G90 A-150.`` moves -150 and the
    "absolute coordinate value after movement end" is 210 (the machine's, Power Mate i B-63172EN/01 7.4: "normalized
    to the range from 0deg to 360deg"). The blocks carry the motor's -150; #5044, #5024 and #5004 read 210 (before:
    -150, as on a linear axis)."""
    ctx = MachineContext(dialect=DIALECTS[dialect], extra_axes=("a",), wrapped_axes=("a",))
    text = "G21 G90\nG0 A-150.\nG0 X#5044 Y#5024\nG0 X#5004\nM30\n"
    prog = parse_iso(text, source="t.nc", context=ctx)
    assert _a_of(prog) == [-150.0] * 3
    assert prog.blocks[-1].target[:2].tolist() == pytest.approx([210.0, 210.0])
    # the same machine without wrap reads the linear axis' -150
    linear = parse_iso(text, source="t.nc", context=MachineContext(dialect=DIALECTS[dialect], extra_axes=("a",)))
    assert linear.blocks[-1].target[:2].tolist() == pytest.approx([-150.0, -150.0])


def test_a_full_turn_back_reads_zero_not_a_rounding_residue():
    """A0, ``G91 A-360.``: the axis is back at 0 (Fanuc B-63534EN/02 20.2.1, N5: -840 ends at 0), read as 0."""
    ctx = MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a",), wrapped_axes=("a",))
    prog = parse_iso("G21 G91\nG0 A-0.1\nG0 A-359.9\nG90 G0 X#5044\nM30\n", source="t.nc", context=ctx)
    assert prog.blocks[-1].target[0] == pytest.approx(0.0, abs=1e-9)


def test_linuxcnc_reads_the_wrapped_axis_unwrapped():
    """rs274 (LinuxCNC 2.9.0~pre1) -i an INI with ``[AXIS_A] WRAPPED_ROTARY = 1``: ``G0 A350``, ``G0 A10``,
    ``G0 X#5423``: STRAIGHT_TRAVERSE(370, .., A 370): LinuxCNC's interpreter does not reduce the angle."""
    ctx = MachineContext(dialect=DIALECTS["linuxcnc"], extra_axes=("a",), wrapped_axes=("a",))
    prog = parse_iso("G21 G90\nG0 A350\nG0 A10\nG0 X#5423\nM2\n", source="t.ngc", context=ctx)
    assert prog.blocks[-1].target[0] == pytest.approx(370.0)


#: A tilting table: A about X (tilting), C about Z (the part's), pivots at the machine zero.
_KIN = Kinematics(kind="table", axes=(RotaryAxis(name="a", direction="X", limits=(-120.0, 120.0)),
                                      RotaryAxis(name="c", direction="Z")))


@pytest.mark.parametrize(("wrapped", "a_end", "c_end"), [(("c",), 30.0, 450.0), ((), -30.0, 270.0)])
def test_g53_1_turns_a_wrapping_axis_the_machine_way(wrapped: tuple[str, ...], a_end: float, c_end: float):
    """C at 370 (``G91 C370.``), ``G68.2 I90. J30. K0``, ``G53.1``: the plane needs A+30 C+90 or A-30 C-90. A
    roll-over C (Fanuc RAB = 0, B-63534EN/02 20.2.1: "the tool moves in the direction in which the final coordinates
    are closest") turns +80 to 450 (before: -280 to 90, as a linear axis does), the other 100 deg away. Without wrap,
    C within its limits -360..360: 90 is 280 deg away, 270 (= -90) 100 (FANUC G53.1 weighs every turn of 360 deg of
    a computed angle, the smaller slave moving angle deciding: kin38; before, A+30 C+90)."""
    ctx = MachineContext(dialect=DIALECTS["fanuc"], extra_axes=("a", "c"), wrapped_axes=wrapped, kinematics=_KIN)
    prog = parse_iso("G21 G90\nG0 A0 C0\nG91 G0 C370.\nG90\nG68.2 X0 Y0 Z0 I90. J30. K0\nG53.1\nM30\n",
                     source="t.nc", context=ctx)
    last = prog.blocks[-1]
    assert float(last.extra_target[0]) == pytest.approx(a_end)
    assert float(last.extra_target[2]) == pytest.approx(c_end)
    assert np.allclose(last.target, last.start)  # G53.1 turns the rotary axes only


#: A B/C tilting table (B about Y, C about Z), C wrapping at 360 deg, the TNC's own rule (no M126: "difference").
_BC = Kinematics(kind="table", axes=(RotaryAxis(name="b", direction="Y", limits=(-120.0, 120.0)),
                                     RotaryAxis(name="c", direction="Z")))
TNC_C = MachineContext(extra_axes=("b", "c"), wrapped_axes=("c",), kinematics=_BC)


def _tnc(body: str, context: MachineContext = TNC_C):
    """The reader's blocks of ``body``, checked against tests/interpolators/reference_heidenhain.py."""
    text = "0 BEGIN PGM W MM\nL X+0 Y+0 Z+50 B+0 C+0 FMAX\n" + body + "\nEND PGM W MM\n"
    prog = parse_heidenhain(text, source="w.h", context=context)
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    return prog


def _c_of(prog) -> list[float]:
    return [round(float(b.extra_target[2]), 9) + 0.0 for b in prog.blocks]


def test_tnc_plane_turns_a_wrapping_c_from_the_angle_it_shows():
    """C at 370 (``L IC+370``: shown 10). ``PLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN`` needs C+90 (or C-90 with B-30);
    as a nominal position of a wrapping C (TNC 640 user's manual, M126: without it "the difference between nominal
    and actual position", the actual one shown below 360) it is +80 to 450 (before: -280 to 90). ``PLANE AXIAL
    C+10`` then goes back to 370, and ``PLANE AXIAL B+20``, C not written, leaves C where it is (before: "C+370 is
    outside the axis' limits -360..360", C's unwrapped angle checked)."""
    prog = _tnc("L IC+370 FMAX\nPLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN FMAX\nPLANE RESET STAY\n"
                "PLANE AXIAL C+10 TURN FMAX\nPLANE RESET STAY\nPLANE AXIAL B+20 TURN FMAX\nPLANE RESET STAY")
    assert _c_of(prog) == [0.0, 370.0, 450.0, 370.0, 370.0]
    assert [round(float(b.extra_target[1]), 9) for b in prog.blocks] == [0.0, 0.0, 30.0, 30.0, 20.0]


def test_tnc_plane_on_an_m126_machine_and_a_linear_c_as_before():
    """With ``M126`` the same PLANE SPATIAL turns C the shorter way (10 to 90: +80, the same end); on a C that does not
    wrap (no ``wrap``) it turns -280 to 90, as a linear axis does."""
    body = "L IC+370 FMAX M126\nPLANE SPATIAL SPA+0 SPB+30 SPC+90 TURN FMAX\nPLANE RESET STAY"
    assert _c_of(_tnc(body)) == [0.0, 370.0, 450.0]
    linear = dataclasses.replace(TNC_C, wrapped_axes=())
    assert _c_of(_tnc(body, linear)) == [0.0, 370.0, 90.0]


def test_tnc_difference_rule_after_a_rounding_residue_stays():
    """C+0.3, then ``IC-0.1`` three times leaves C at 0.3 - 3 x 0.1 = -2.8e-17 deg (floating point); ``L C+0`` is
    then no move (the difference to the shown 0), not a whole turn of -360 deg (before: C ended at -360)."""
    prog = _tnc("L C+0.3 FMAX\nL IC-0.1 FMAX\nL IC-0.1 FMAX\nL IC-0.1 FMAX\nL C+0 FMAX\nL X+1 FMAX")
    assert abs(float(prog.blocks[-1].extra_target[2])) < 1e-9


def test_tnc_m127_in_a_block_of_its_own_ends_the_shorter_way_in_the_reference_too():
    """``L C+350``, ``L C+10 M126`` (+20 to 370), ``M127`` alone, ``L C+350``: the shown 10 to 350 by the difference,
    +340 to 710 (TNC 640 user's manual, M126/M127). The reader did so; the reference kept M126 (350), so a program
    with M127 on its own line was compared against the wrong end."""
    prog = _tnc("L C+350 FMAX\nL C+10 FMAX M126\nM127\nL C+350 FMAX", dataclasses.replace(TNC_C, kinematics=None))
    assert _c_of(prog) == [0.0, 350.0, 370.0, 710.0]


def test_plane_axial_without_an_angle_is_an_error_naming_the_line():
    """TNC7 basic user's manual 81762x-19, "PLANE AXIAL": the plane is defined "with anywhere from one to three
    absolute or incremental axis angles". ``PLANE AXIAL TURN FMAX`` with none was taken as the present axes, silently;
    it is now an error naming the line (the reference refused it already)."""
    text = "0 BEGIN PGM W MM\nL X+0 Y+0 Z+50 B+0 C+0 FMAX\nPLANE AXIAL TURN FMAX\nEND PGM W MM\n"
    with pytest.raises(GCodeError, match=r"w\.h:3:.*PLANE AXIAL without an axis angle.*expected PLANE AXIAL B\.\."):
        parse_heidenhain(text, source="w.h", context=TNC_C)
    assert _c_of(_tnc("PLANE AXIAL B+0 TURN FMAX\nPLANE RESET STAY")) == [0.0]  # one angle, already there: no move


@pytest.mark.parametrize(("turn", "stored"), [(370.0, 10.0), (-370.0, 350.0), (-10.0, 350.0), (720.0, 0.0)])
def test_linuxcnc_g28_1_and_g30_1_store_a_wrapped_angle_within_one_turn(turn: float, stored: float):
    """rs274 (LinuxCNC 2.9.0~pre1) -i an INI with ``[AXIS_A] WRAPPED_ROTARY = 1``: ``G91 G0 A<turn>``, ``G90``,
    ``G28.1`` (``G30.1``), ``G0 X#5164`` (``#5184``): X 10, 350, 350, 0 for A370, A-370, A-10, A720 (vcnc read the
    unwrapped 370 .. before)."""
    ctx = MachineContext(dialect=DIALECTS["linuxcnc"], extra_axes=("a",), wrapped_axes=("a",))
    for code, n in (("G28.1", 5164), ("G30.1", 5184)):
        prog = parse_iso(f"G21\nG91 G0 A{turn:g}\nG90\n{code}\nG0 X#{n}\nM2\n", source="t.ngc", context=ctx)
        assert prog.blocks[-1].target[0] == pytest.approx(stored)
        assert float(prog.blocks[-1].extra_target[0]) == turn  # the axis itself stays unwrapped
