"""Session 32 review: defects found in the day's changes, each with the program that showed it."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import interpolate, load_program, parse_program
from interpolators.context import INTERPOLATION_CONTEXT as CTX
from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.setpoint_checks import check_limits
from tests.interpolators.test_secondary_axes import LIMITS
from vcnc.errors import GCodeError

LINUXCNC = MachineContext().with_dialect("linuxcnc")


@pytest.mark.parametrize("line, kinds", [("G40 G8 G64 P0.01", ["rapid"]), ("G8 G4 P0.5", ["dwell", "rapid"]),
                                                ("G8 M66 P0 L0", ["rapid"])])
def test_g8_beside_a_code_that_takes_p_is_the_lathe_radius_mode(line, kinds):
    # LinuxCNC g-code.adoc "Modal Groups": G8 (group 15) takes no P, the block's G64 or G4 owns it; review32: the P
    # made G8 Fanuc's G08 P1 look-ahead and the block was refused naming --dialect fanuc
    prog = checked_iso(f"G21 G90\n{line}\nG0 X5\nM2\n", LINUXCNC)
    assert [b.kind for b in prog.blocks] == kinds
    assert prog.blocks[-1].target[0] == 5.0
    assert any(n.startswith("G8 lathe radius mode") for n in prog.notes)


@pytest.mark.parametrize("line", ["G08 P1", "G90 G08 P1", "G08 P0 M3 S1000"])
def test_g8_with_a_p_of_its_own_is_still_named_as_fanucs_look_ahead(line):
    # no other code of the block reads a P (rs274ngc interp_check.cc check_other_codes)
    column = line.index("G08") + 1
    with pytest.raises(GCodeError, match=rf":2:{column}: G8 lathe radius mode: not supported \(G08 P1 / P0 with a P "
                                         r"is Fanuc's AI advanced preview control"):
        parse_program(f"G21\n{line}\nG0 X1\nM2\n", context=LINUXCNC)


# one lap of a 30 x 40 mm rectangle with R10 corners, its sides tangent to the arcs, under G64 P0.01 at F3000
ROUNDED = ["G21 G90 G64 P0.01 G0 X0 Y0 Z0 A0", "G1 Z-1 F3000", "G1 X20 Y0", "G3 X30 Y10 I0 J10", "G1 X30 Y30",
           "G3 X20 Y40 I-10 J0", "G1 X0 Y40", "G3 X-10 Y30 I0 J-10", "G1 X-10 Y10", "G3 X0 Y0 I10 J0"]


@pytest.mark.parametrize("tail", ["G0 Z5 A90", "G1 A90 F3600"])
def test_a_rotary_index_after_a_contour_leaves_the_contour_as_planned(tail):
    """A rapid or a move of A alone after a 3-axis G64 contour starts a chain of its own: the contour's chain is no
    rotary chain. Review32: its chain was turned into one (interpolate._chains) though the block did not join it, and
    under the S-curve its tangent line/arc junctions lost their curvature blends: 2.848 s to the contour's end against
    2.668 s with no A in the tail."""
    ends = {}
    for t in (tail, tail.replace(" A90", " Z5" if "G1" in tail else "")):
        prog = parse_program("\n".join([*ROUNDED, t, "M2"]) + "\n", context=CTX)
        sp = interpolate(prog, profile="scurve")
        check_limits(sp, prog, LIMITS, jerk=True)
        ends[t] = float(np.flatnonzero(sp.block < len(ROUNDED) - 1)[-1]) * sp.sample_time
    with_a, without = ends.values()
    assert with_a == pytest.approx(without, abs=1e-9)
    assert with_a <= 2.67


def test_a_lathe_code_in_a_subprogram_file_names_the_file_of_the_other(tmp_path):
    # review32: the error in O1000's file named "G50 S ... at line 3" of the main program as if of its own file
    (tmp_path / "main.nc").write_text("O0001\nG21 G90\nG50 S3000\nM98 P1000\nM30\n")
    (tmp_path / "1000.nc").write_text("O1000\nG96 S100\nG0 X10.\nM99\n")
    with pytest.raises(GCodeError) as err:
        load_program(tmp_path / "main.nc", context=MachineContext().with_dialect("fanuc"))
    assert err.value.file.endswith("1000.nc") and err.value.line == 2
    assert f"G50 S (the lathe's maximum spindle speed) at {tmp_path / 'main.nc'}:3 are" in str(err.value)


_DRILL = ("0 BEGIN PGM T MM\nTOOL CALL 1 Z S4000\nL Z+50 R0 FMAX\nCYCL DEF 200 DRILLING ~\n Q200=2 ~\n Q201=-10 ~\n"
          " Q206=150 ~\n Q202=5 ~\n Q210=0 ~\n Q203=+0 ~\n Q204=50 ~\n Q211=0 ~\n Q395=0\n")


@pytest.mark.parametrize("form", ["ROW1 (X+0 Y+0 D+10 NUM2 Z+0", "POS1 (X+0 Y+0 Z+0"])
def test_a_pattern_form_left_open_is_named_as_such(form):
    # review32: "pattern 'ROW1' is not supported" for a form the reader reads (TNC 640 cycle programming manual,
    # "PATTERN DEF"), its ')' missing
    text = _DRILL + f"PATTERN DEF ~\n {form}\nCYCL CALL PAT F500\nEND PGM T MM\n"
    # at the form's own line and column (tncwild14: a block continued over lines names the line of the word)
    with pytest.raises(GCodeError, match=rf":15:2: PATTERN DEF {form[:4]} without its closing '\)'"):
        parse_heidenhain(text, context=MachineContext())


@pytest.mark.parametrize("count, column", [("L-1", 10), ("L0.5", 10)])
def test_a_call_count_that_is_no_whole_number_of_at_least_zero_is_refused(count, column):
    # review32: int(w.value) made L-1 and L0.5 call nothing (L0.5 -> 0), silently; rs274 refuses both ("Negative l
    # word used", "Non integer value for integer")
    with pytest.raises(GCodeError, match=rf":2:{column}: M98 {count}: the number of calls must be a whole number "
                                         r"of at least 0"):
        parse_program(f"G21 G90\nM98 P100 {count}\nM2\nO100\nG1 X1 F100\nM99\n", context=LINUXCNC)


def test_a_call_count_of_zero_calls_nothing_and_two_calls_twice():
    prog = checked_iso("G21 G91\nM98 P100 L0\nM98 P100 L2\nM2\nO100\nG1 X1 F100\nM99\n", LINUXCNC)
    assert [b.target[0] for b in prog.blocks] == [1.0, 2.0]
