"""ISO programs of the seventh wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


def _z_path(prog) -> list[tuple[str, float]]:
    return [(b.kind, round(float(b.target[2]), 6)) for b in prog.blocks if b.kind in ("rapid", "line")]


@pytest.mark.parametrize("name", ["fanuc", "haas"])
@pytest.mark.parametrize("retract", ["G98", "G99"])
def test_a_cycle_without_r_drills_from_the_initial_level(name, retract):
    # Haas student programs write "G43 H07 Z0.1" then "G81 G98 Z-0.45 F85.95" with no R: the Haas mill manual
    # lists R among the optional words of G81 ("*R ... * indicates optional"), and Fanuc's G80 clears R to no
    # distance from the initial level: the R plane is the initial level (Z5 here, G54 Z -20 -> machine -15)
    text = f"G21 G90 G54 G0 X0 Y0 Z5.\n{retract} G81 X10. Y0 Z-3. F100.\nX20.\nG80\nM30\n"
    prog = checked_iso(text, _in_dialect(name))  # and the independent reference drills the same
    hole = [("rapid", -15.0), ("line", -23.0), ("rapid", -15.0)]  # over at R = the initial level, drill, out
    assert _z_path(prog)[1:] == hole * 2
    assert [b.target[0] for b in prog.blocks if b.kind == "line"] == [110.0, 120.0]
    assert any("without R in the first block of the series: the R plane is the initial level" in n
               for n in prog.notes)


def test_an_incremental_cycle_without_r_drills_from_the_initial_level():
    # G91: R is an increment from the initial level (0 when left out), Z an increment from R
    text = "G21 G90 G54 G0 X0 Y0 Z5.\nG91 G98 G81 X10. Z-8. F100.\nG90 G80\nM30\n"
    prog = checked_iso(text, _in_dialect("fanuc"))
    assert _z_path(prog)[1:] == [("rapid", -15.0), ("line", -23.0), ("rapid", -15.0)]


def test_an_r_once_given_stays_for_the_series():
    # the R of the first block is sticky; a later block without R keeps it (and the initial level stays)
    text = "G21 G90 G54 G0 X0 Y0 Z20.\nG99 G81 X10. Z-3. R2. F100.\nX20.\nM30\n"
    prog = parse_program(text, context=_in_dialect("haas"))
    hole = [("rapid", -18.0), ("line", -23.0), ("rapid", -18.0)]
    assert _z_path(prog)[1:] == [("rapid", 0.0), *hole, *hole]  # over at the initial level, down to R2
    assert not any("without R" in n for n in prog.notes)


def test_linuxcnc_still_refuses_a_cycle_without_r():
    # rs274 (interp_cycles.cc convert_cycle): "R clearance plane unspecified in cycle"
    with pytest.raises(GCodeError, match=r":2:1: G81 drilling cycle: no R \(retract plane\) word in the first block "
                                         r".*expected R<retract level>"):
        parse_program("G21 G90 G54 G0 X0 Y0 Z5.\nG81 X10. Z-3. F100.\nM2\n", context=_in_dialect("linuxcnc"))


@pytest.mark.parametrize("name", ["fanuc", "linuxcnc"])
def test_an_okuma_osp_file_is_named(name):
    # an editor's Okuma OSP5020M example starts "$OKUMA.SSB%" and calls "CALL OCHCK": the '$' line is the OSP
    # file header (not a CNCSimulator Pro directive to skip), and the message names the control
    text = "$DEMO.MIN%\n(OSP MILL)\nCALL OSUB1\nG0 G90 X0 Y0\nM02\n"
    with pytest.raises(GCodeError, match=r":1:1: Okuma OSP program file header '\$DEMO\.MIN%': that control's "
                                         r"native language is not ISO G-code"):
        parse_program(text, context=_in_dialect(name))
    # a CNCSimulator Pro directive is still skipped
    prog = parse_program("$Millimeters\nG21 G90 G0 X1 Y2 Z3\nM30\n", context=_in_dialect(name))
    assert prog.blocks[-1].target.tolist() == [101.0, 52.0, -17.0]  # G54 (100, 50, -20)


@pytest.mark.parametrize("name", ["fanuc", "haas"])
def test_a_feed_from_a_vacant_variable_is_named(name):
    # a Fanuc warm-up program feeds "G90 G53 G01 Z0 F#650" with #650 set by another program of its machine: run
    # alone, #650 is vacant, the F word is left out (Fanuc "Undefined variable") and no feed is set: the message
    # says why the F written there does not count
    with pytest.raises(GCodeError, match=r":2:\d+: G01 feed move without a feed: F#650 is vacant \(never set\), "
                                         r"which leaves the F word out"):
        parse_program("G21 G90\nG53 G01 Z0 F#650 (feed)\nM30\n", context=_in_dialect(name))
    prog = parse_program("G21 G90\n#650=500\nG53 G01 Z0 F#650\nM30\n", context=_in_dialect(name))
    assert prog.blocks[-1].feed == pytest.approx(500.0 / 60.0)


def test_g28_goes_to_the_position_g28_1_stored():
    # a controller test program (NIST rs274 style) stores the current position with G28.1, then "g28" rapids
    # there (LinuxCNC g-code.adoc "G28, G28.1"); the reference models it too
    text = ("G21 G90 G10 L2 P6 X25 Y25 Z-40\nG59\nG0 X2 Y4 Z8\nG28.1\nG0 X90 Y80 Z0\nG28\n"
            "G0 X50 Y50 Z0\nG28 X75 Y75 Z-50\nM2\n")
    prog = checked_iso(text, _in_dialect("linuxcnc"))
    assert prog.blocks[5].target.tolist() == [27.0, 29.0, -32.0]  # the stored machine position
    assert [b.target.tolist() for b in prog.blocks[-2:]] == [[100.0, 100.0, -90.0], [27.0, 29.0, -32.0]]


def test_a_letter_o_for_a_zero_is_hinted():
    # a student program writes "GOO Z.500": the letter O where G00 was meant; a Haas stops on it too
    with pytest.raises(GCodeError, match=r":2:1: malformed number for word G \(the letter O where the digit 0 was "
                                         r"meant\?\) \(got 'GOO'\)"):
        parse_program("G20 G90\nGOO Z.500\nM30\n", context=_in_dialect("haas"))
    with pytest.raises(GCodeError, match=r"malformed number for word X \(got 'Xyz'\)"):  # no hint for other junk
        parse_program("G20 G90\nG0 Xyz\nM30\n", context=_in_dialect("haas"))


@pytest.mark.parametrize("name", ["fanuc", "haas", "linuxcnc"])
def test_arc_words_on_a_rapid_stay_refused(name):
    # a parser fixture writes "G0 X0.5 Y0. I0. J-0.5" after an arc (meant G02): no Fanuc or Haas manual found
    # lets the control ignore I J on G00 (the Haas mill manual lists X Y Z A B C for G00): refused everywhere
    with pytest.raises(GCodeError, match=r":3:\d+: word I is only allowed on arcs \(G02/G03\), not on G00 .*"
                                         r"a G02/G03 meant\?"):
        parse_program("G20 G90 G0 X-0.5 Y0 Z0\nG2 X0 Y0.5 I0.5 J0 F2.5\nG0 X0.5 Y0 I0 J-0.5\nM30\n",
                      context=_in_dialect(name))


@pytest.mark.parametrize(("name", "expected"), [("haas", r"Q > 0 \(Haas: or I J K\)"), ("fanuc", r"Q > 0$")])
def test_a_peck_cycle_without_a_peck_stays_refused(name, expected):
    # a hand-written Haas program drills "G73 X.. Y.. Z-1.25 R.1 P1. F12." with neither Q nor I: the Haas manual
    # names three ways to give the pecks (I J K, K and Q, Q alone) and none without: refused, naming them
    with pytest.raises(GCodeError, match=r":2:1: G73 peck drilling cycle: peck depth Q must be > 0 .*expected "
                                         + expected):
        parse_program("G20 G90 G0 X0 Y0 Z1.\nG73 X1. Y1. Z-1.25 R.1 P1. F12.\nG80\nM30\n", context=_in_dialect(name))
    prog = parse_program("G20 G90 G0 X0 Y0 Z1.\nG73 X1. Y1. Z-1.25 R.1 I.5 J.1 K.2 F12.\nG80\nM30\n",
                         context=_in_dialect("haas"))
    assert min(b.target[2] for b in prog.blocks) == pytest.approx(-20.0 - 1.25 * 25.4)


def test_zero_repeats_drill_no_hole_on_fanuc_and_are_refused_by_linuxcnc():
    # a Mach4 (Fanuc-style) program writes "G82 Z-5. R2. P0.250 F100. L0" to store the cycle for a subprogram's
    # holes: Haas/Fanuc drill nothing there; rs274 stops: "Cannot do zero repeats of cycle"
    text = "G21 G90 G54 G0 X0 Y0 Z25.\nG99 G82 Z-5. R2. P250 F100. L0\nX10.\nG80\nM30\n"
    prog = parse_program(text, context=_in_dialect("haas"))
    assert [round(b.target[0], 6) for b in prog.blocks if b.kind == "line"] == [110.0]  # one hole, at X10
    with pytest.raises(GCodeError, match=r":2:\d+: G82 drilling cycle with dwell: zero repeats: LinuxCNC cannot do "
                                         r"zero repeats of a cycle .*expected L1 or more"):
        parse_program(text.replace("P250", "P0.25"), context=_in_dialect("linuxcnc"))
