"""ISO programs of the third wild set (issue 18): what their own controls run, with end points derived by hand."""

from __future__ import annotations

import dataclasses
import math

import pytest

from interpolators import load_program, parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from toolpaths.geometry import PLANE_AXES
from vcnc.errors import GCodeError

CTX = MachineContext(
    work_offsets={"G54": (100.0, 50.0, -20.0), "G55": (200.0, 0.0, 0.0)},
    tools={1: Tool(number=1, length=12.5, radius=0.0)},
    home=(0.0, 0.0, 100.0), reference2=(10.0, 20.0, 90.0),
)


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


def test_fanuc_takes_the_last_of_two_distance_codes_in_a_block():
    # efgarro/20-IDEAR (Fusion 360 for a Fanuc-type mill): "G91 G28 X0 Y0 Z100. G90" -- Fanuc: the
    # last G code of a group is valid, so the G28 runs under G90: through the intermediate point
    # X0 Y0 Z5 of G54 (100, 50, -15) to home (0, 0, 100); then X1 is absolute: 101.
    text = "G21 G90 G54\nG0 X1 Y1 Z1\nG91 G28 X0 Y0 Z5. G90\nG0 X1\n"
    prog = checked_iso(text, _in_dialect("fanuc"))
    assert [b.target.tolist() for b in prog.blocks] == [[101, 51, -19], [100, 50, -15], [0, 0, 100],
                                                         [101, 0, 100]]
    assert "two G codes of the distance group in one block: the last one is valid (Fanuc)" in prog.notes


@pytest.mark.parametrize("name", ["linuxcnc", "haas", "grbl"])
def test_other_controls_refuse_two_distance_codes_in_a_block(name):
    # LinuxCNC interp_check.cc: NCE_TWO_G_CODES_USED_FROM_SAME_MODAL_GROUP; grbl error 21 (modal group violation)
    with pytest.raises(GCodeError, match=r"two G codes of the distance group in one block \(G91 and G90\)"):
        parse_program("G21 G90 G54\nG91 G28 X0 Y0 Z5. G90\n", context=_in_dialect(name))


def test_fanuc_last_plane_and_units_code_is_valid():
    # "G17 G18": the ZX plane; "G20 G21": millimetres (G54 at 100, 50, -20): the G02 half circle in ZX
    # from X0 Z0 to X10 Z0 about I5 ends at X10 Z0 = (110, 50, -20), at F100 mm/min = 100/60 mm/s
    prog = checked_iso("G20 G21 G90 G54\nG0 X0 Y0 Z0\nG17 G18 G02 X10 Z0 I5 K0 F100\n", _in_dialect("fanuc"))
    arc = prog.blocks[-1]
    assert arc.target.tolist() == [110, 50, -20]
    assert arc.segment.center.tolist() == [105, 50, -20]
    assert PLANE_AXES[arc.segment.plane] == (2, 0)  # ZX
    assert arc.feed == pytest.approx(100 / 60)


def test_fanuc_two_motion_codes_in_a_block_stay_refused():
    with pytest.raises(GCodeError, match="two G codes of the motion group"):
        parse_program("G21 G90\nG0 G1 X1 F100\n", context=_in_dialect("fanuc"))


def test_tool_position_offset_is_named_at_its_line_outside_fanuc():
    # obirimelvin/machinist 2003.nc "G00 G45 H03 Z2.0": Fanuc's one-shot tool position offset (G45-G48), which
    # --dialect fanuc runs (test_iso_wild10)
    with pytest.raises(GCodeError, match=r":3:5: G45 tool position offset increase \(Fanuc; --dialect fanuc\): not "
                                         r"supported"):
        parse_program("G20 G90 G54\nG00 X0 Y0\nG00 G45 H03 Z2.0\n", context=_in_dialect("haas"))
    prog = parse_program("G20 G90 G54\nG00 X0 Y0\nG00 G45 H03 Z2.0\n", context=_in_dialect("fanuc"))
    assert "H3 not in the tool table (offset 0)" in prog.notes


def test_unknown_g_code_names_the_dialect():
    with pytest.raises(GCodeError, match="expected a G code of the fanuc milling set vcnc reads"):
        parse_program("G21\nG06 X1\n", context=_in_dialect("fanuc"))


@pytest.mark.parametrize("name, dwell, out", [
    # Fanuc: feed out to R (-18), dwell P there too ("dwell time at the bottom of the hole and at point R when a
    # return is made", isomacro40), then rapid to the initial level (-10) under G98
    ("fanuc", "P100", [("line", -18), ("dwell", -18), ("rapid", -10)]),
    # LinuxCNC g-code.adoc "G84": "Move the Z-axis at the current feed rate to clear Z"
    ("linuxcnc", "P0.1", [("line", -10)]),
])
def test_g84_tapping_ends_against_the_reference(name, dwell, out):
    # G54 = (100, 50, -20); from Z10 (machine -10): XY at the initial level, R2 (-18), bottom Z-5 (-25),
    # the dwell P (0.1 s) at the bottom, then out as the control retracts a tap
    text = f"G21 G90 G54\nG0 X0 Y0 Z10\nS500 M3\nG98 G84 X10 Y5 Z-5 R2 {dwell} F500\nG80\n"
    prog = checked_iso(text, _in_dialect(name))
    tap = [(b.kind, b.target.tolist()) for b in prog.blocks if b.line == 4]
    assert tap == [("rapid", [110, 55, -10]), ("rapid", [110, 55, -18]), ("line", [110, 55, -25]),
                   ("dwell", [110, 55, -25]), *((k, [110, 55, z]) for k, z in out)]
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == [pytest.approx(0.1)] * (2 if name == "fanuc" else 1)


def test_m98_names_a_file_of_the_number_that_does_not_number_its_program(tmp_path):
    # ailtonbsj/free-cnc-simulator-wine: M98_P_inch.nc calls P6001, and 6001.nc starts "(W)" with no
    # O6001 line (the simulator finds programs by file name; Fanuc and Haas by their O number)
    main = tmp_path / "main.nc"
    main.write_text("G20 G90 G54\nG0 X0 Y0 Z0.1 F10\nM98 P6001\nM30\n")
    (tmp_path / "6001.nc").write_text("(W)\nG91 G01 X0.5\nM99\n")
    with pytest.raises(GCodeError, match=r"main.nc:3:1: M98 subprogram call: program O6001 is neither in this "
                                         r"file nor in a program file of its folder \(6001.nc there holds no "
                                         r"O6001 line\)"):
        load_program(main, context=_in_dialect("fanuc"))
    # numbered, it runs: X0 then 0.5 in = 12.7 mm further (G54 X100)
    (tmp_path / "6001.nc").write_text("O6001 (W)\nG91 G01 X0.5\nM99\n")
    assert load_program(main, context=_in_dialect("fanuc")).blocks[-1].target.tolist() == [112.7, 50, -17.46]


def test_fanuc_i_j_alone_in_the_modal_g02_is_a_full_circle():
    # MaestroFusion360/easy_gcode_plot VINT_360arc.NC: a helix of "X15.Y0Z-1.I-15.J0" blocks, then
    # "I-15.J0": Fanuc 0i "Circular interpolation": X, Y, Z omitted with I J K is a 360 deg circle.
    # G54 = (100, 50, -20): the helix turn ends at X10 Y0 Z-1 (110, 50, -21); the circle about X0 Y0
    # (100, 50, -21) comes back there, clockwise, one whole turn
    text = "G21 G90 G54\nG0 X10 Y0 Z0\nG02 X10 Y0 Z-1 I-10 J0 F100\nI-10 J0\n"
    prog = checked_iso(text, _in_dialect("fanuc"))
    circle = prog.blocks[-1]
    assert (circle.kind, circle.line, circle.target.tolist()) == ("arc", 4, [110, 50, -21])
    assert circle.segment.center.tolist() == [100, 50, -21]
    assert circle.segment.sweep == pytest.approx(-2 * math.pi)


@pytest.mark.parametrize("name, line", [("linuxcnc", "R5"), ("haas", "I-10 J0"), ("fanuc", "R5")])
def test_arc_words_alone_in_the_modal_g02_are_refused_elsewhere(name, line):
    # an R alone is no circle (LinuxCNC: "R word with no G code that uses it"; I J alone is a circle there,
    # test_iso_wild15)
    with pytest.raises(GCodeError, match=f"word {line[0]} without an arc motion"):
        parse_program(f"G21 G90 G54\nG0 X10 Y0 Z0\nG02 X10 Y0 Z-1 I-10 J0 F100\n{line}\n", context=_in_dialect(name))


def test_g53_without_a_motion_mode_says_so():
    # Michael-F-Bryan/gcode-rs _mach3.gcode: "G53 G90 G40" first (Mach3 ignores it; LinuxCNC: "Must use G0
    # or G1 with G53")
    with pytest.raises(GCodeError, match=r":2:1: G53 needs G0 or G1 \(no motion mode is set yet\)"):
        parse_program("G20\nG53 G90 G40\nG0 X1\n", context=_in_dialect("linuxcnc"))
