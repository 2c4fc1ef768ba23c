"""Dialect value checks and details left open (session 38, isomisc38): sequence, program, tool and offset numbers,
Fanuc's G92.1 preset, grbl's group-0 axis words, Fadal's arc centres, the reference's peck cycles.

Each input is hand-written; the expected behaviour is the control's as its own text or source gives it (rs274 runs
on LinuxCNC's side: ``benchmarks/linuxcnc_diff.py``; grbl's from gnea/grbl ``grbl/gcode.c``)."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.reference_iso import ReferenceError, iso_reference
from vcnc.errors import GCodeError

ALL = ("linuxcnc", "fanuc", "haas", "fadal", "grbl")


def _ctx(dialect: str) -> MachineContext:
    return MachineContext(dialect=DIALECTS[dialect])


def _ends(prog) -> list[list[float]]:
    return [[round(float(v), 6) for v in b.target] for b in prog.blocks if b.kind != "dwell"]


@pytest.mark.parametrize("dialect", ALL)
def test_a_negative_sequence_number_is_refused(dialect):
    # rs274: "Bad format unsigned integer" (interp_read.cc read_n_number); grbl gcode.c: N is one of the words
    # F N P T S that "cannot be negative" (error 4). Before: read as a block number -5 and run
    with pytest.raises(GCodeError, match="negative sequence number N-5"):
        parse_program("N-5 G0 X1.\nM30\n", context=_ctx(dialect))


def test_grbl_refuses_a_line_number_above_its_maximum():
    # grbl gcode.h "#define MAX_LINE_NUMBER 10000000"; gcode.c "[Exceeds max line number]" (error 27). Before: run
    with pytest.raises(GCodeError, match="above grbl's 10,000,000"):
        parse_program("N10000001 G0 X1.\nM30\n", context=_ctx("grbl"))
    assert len(parse_program("N10000000 G0 X1.\nM30\n", context=_ctx("grbl")).blocks) == 1
    assert len(parse_program("N10000001 G0 X1.\nM30\n", context=_ctx("linuxcnc")).blocks) == 1  # rs274 runs it


def test_grbl_notes_a_tool_number_grbl_1_1_refuses():
    # grbl gcode.c: "if (value > MAX_TOOL_NUMBER) { FAIL(STATUS_GCODE_MAX_VALUE_EXCEEDED); }", MAX_TOOL_NUMBER 255
    # (error 38); grblHAL takes it (config.h MAX_TOOL_NUMBER 2147483647), as the grbl dialect runs grblHAL's
    # extensions with a note. Before: no note
    prog = parse_program("T301 M6\nG0 X1.\nM30\n", context=_ctx("grbl"))
    assert any("T301" in n and "error 38" in n for n in prog.notes)
    assert not any("error 38" in n for n in parse_program("T255 M6\nG0 X1.\nM30\n", context=_ctx("grbl")).notes)


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc"])
@pytest.mark.parametrize("block, message", [
    ("G43 H-1", "Requested tool -1 not found"),  # rs274's message; before: H-1 "not in the tool table", length 0
    ("G43 H1.5", "Non integer value for integer"),  # rs274's; Fanuc PS0007. Before: read as H1
    ("G41 D-1 G1 X5. F100.", "whole number >= 0"),  # rs274: "G41 requires D word to be a whole number". Before: run
])
def test_an_offset_number_must_be_a_whole_number_at_least_0(dialect, block, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21 G90\n{block}\nG0 Z1.\nG40\nM30\n", context=_ctx(dialect))


def test_fanuc_g45_h_is_checked_as_an_offset_number():
    with pytest.raises(GCodeError, match="G45 H-2"):
        parse_program("G21 G90 G0 X0 Y0\nG45 X10. H-2\nM30\n", context=_ctx("fanuc"))


@pytest.mark.parametrize("header", ["O0", "O0000(MY GCODE)", ":0", "O100000000"])
def test_fanuc_refuses_a_program_number_out_of_its_range(header):
    # "program number zero (O0 or O0000) is not allowed" (Smid, cncforum.net "Program Name and Number
    # Identification"); eight digits at most (30i-B). Before: read as program 0
    with pytest.raises(GCodeError, match="program number"):
        parse_program(f"%\n{header}\nG21 G0 X1.\nM30\n%\n", context=_ctx("fanuc"))


def test_program_numbers_in_range_and_other_dialects_run():
    assert len(parse_program("%\nO0001\nG21 G0 X1.\nM30\n%\n", context=_ctx("fanuc")).blocks) == 1
    assert len(parse_program("%\nO99999999\nG21 G0 X1.\nM30\n%\n", context=_ctx("fanuc")).blocks) == 1
    assert len(parse_program("O0000(MY GCODE)\nG21 G0 X1.\nM30\n", context=_ctx("linuxcnc")).blocks) == 1


PRESET = "G21 G90\nG0 X1. Y1.\nG92 X5. Y5.\nG92.1 X0\nG0 X2. Y2.\nM30\n"


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_fanuc_g92_1_presets_only_the_axes_it_names(dialect):
    # Fanuc "G92.1 IP 0": the workpiece coordinate system preset of the axes named (our reading of its format): X
    # loses the G92 shift (-4), Y keeps it, nothing moves in the G92.1 block. Before: both shifts dropped (Y at 2)
    prog = checked_iso(PRESET, _ctx(dialect))
    assert _ends(prog) == [[1.0, 1.0, 0.0], [2.0, -2.0, 0.0]]


def test_fanuc_g92_1_with_a_value_other_than_0_is_refused():
    with pytest.raises(GCodeError, match="G92.1 IP 0"):
        parse_program("G21 G90\nG0 X1. Y1.\nG92.1 X3.\nM30\n", context=_ctx("fanuc"))


@pytest.mark.parametrize("dialect", ["linuxcnc", "grbl"])
def test_g92_1_axis_words_move_by_the_modal_motion_under_linuxcnc_and_grbl(dialect):
    # rs274 runs PRESET so (benchmarks/linuxcnc_diff.py: match, 3 moves): both shifts gone, then G0 to X0; grbl
    # gcode.c, NON_MODAL_RESET_COORDINATE_OFFSET: "If axis words are passed here, they are interpreted as an implicit
    # motion mode". Before: under grbl the X0 did not move
    prog = checked_iso(PRESET, _ctx(dialect))
    assert _ends(prog) == [[1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [2.0, 2.0, 0.0]]


@pytest.mark.parametrize("code", ["G28.1 X4.", "G4 P1. X4."])
def test_grbl_moves_by_the_axis_words_of_other_group_0_codes(code):
    # grbl gcode.c: only G10, G28, G30 and G92 take axis words (AXIS_COMMAND_NON_MODAL); "G28.1/30.1 ... If axis
    # words are passed here, they are interpreted as an implicit motion mode", and G4 sets no axis command either
    prog = checked_iso(f"G21 G90\nG0 X1. Y1.\n{code}\nM30\n", _ctx("grbl"))
    assert _ends(prog)[-1] == [4.0, 1.0, 0.0]


def test_fadal_arc_with_reversed_centre_words_is_refused_with_a_hint():
    # NX Post Builder's fadal.def writes I J as start minus centre; vcnc reads them as Fanuc's and Fusion's
    # fadal.cps write them (centre minus start). Before: the same refusal without the hint
    text = "G21 G90\nG0 X0 Y0\nG2 X10. Y10. I0 J-10. F100.\nM30\n"
    with pytest.raises(GCodeError, match="start minus the centre would fit"):
        parse_program(text, context=_ctx("fadal"))
    with pytest.raises(GCodeError) as fanuc:
        parse_program(text, context=_ctx("fanuc"))
    assert "start minus the centre" not in str(fanuc.value)
    prog = parse_program(text.replace("J-10.", "J10."), context=_ctx("fadal"))
    assert _ends(prog)[-1] == [10.0, 10.0, 0.0]


@pytest.mark.parametrize("cycle", ["G83 X1. Y1. Z-1. R1. Q0 F100.", "G83 X1. Y1. Z-1. R1. Q-1. F100."])
def test_the_reference_refuses_a_peck_depth_of_0_or_less(cycle):
    # rs274: "Negative or zero q value used"; the reader refuses it under every dialect. Before: the reference
    # looped without end (its pecks never went down)
    with pytest.raises(ReferenceError, match="peck depth"):
        iso_reference(f"G21 G90\nG0 X1. Y1. Z5.\n{cycle}\nG80\nM30\n", _ctx("fanuc"))


def test_grbl_refuses_a_g10_l2_rotation():
    # grbl gcode.c "[G10 L2 R not supported]" (error 20; grblHAL gcode.c the same). Before: run as LinuxCNC's rotation
    with pytest.raises(GCodeError, match="G10 L2 R"):
        parse_program("G21 G90\nG10 L2 P1 X1. R45.\nG0 X1.\nM30\n", context=_ctx("grbl"))


@pytest.mark.parametrize("block, note", [("G10 L20 P7 X1.", "error 29"), ("G10 L1 P1 Z5.", "[Unsupported L]")])
def test_grbl_notes_g10_forms_grbl_1_1_refuses(block, note):
    # grbl settings.h N_COORDINATE_SYSTEM 6 ("[Greater than N sys]", error 29) and G10 L1/L10/L11 ("[Unsupported
    # L]"); grblHAL runs both (nine systems; a tool table). Before: no note
    prog = parse_program(f"G21 G90\n{block}\nM30\n", context=_ctx("grbl"))
    assert any(note in n and "grblHAL" in n for n in prog.notes)
