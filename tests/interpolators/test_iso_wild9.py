"""ISO programs of the ninth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


def _xy(prog) -> list[list[float]]:
    return [b.target[:2].tolist() for b in prog.blocks]


def test_m98_q_without_p_calls_a_block_of_the_same_program():
    # a Doosan (Fanuc 0i-MD) shop program: the pattern after M30 starts at N3021 and ends with M99; each
    # 'M98 Q3021' runs it under a new G52 shift, as Haas M97 P3021 would, and comes back after the call
    text = ("%\nO0033\nG21 G90 G54 G0 X0 Y0 Z10\nG52 X0 Y0\nM98 Q3021\nG52 X20 Y0\nM98 Q3021 L2\nG52 X0 Y0\n"
            "G0 X-5 Y-5\nM30\nN3021 (PATTERN)\nG0 X1 Y1\nG1 Z-1 F100\nG0 Z10\nM99\n%\n")
    prog = parse_program(text, context=_in_dialect("fanuc"))
    corners = [xy for xy in _xy(prog) if xy[1] == 51.0]
    assert corners == [[101.0, 51.0]] * 3 + [[121.0, 51.0]] * 6
    assert _xy(prog)[-1] == [95.0, 45.0]
    assert any("M98 Q without P" in n for n in prog.notes)


def test_m98_q_without_p_names_a_missing_block():
    with pytest.raises(GCodeError, match=r":2:1: M98 Q subprogram call \(no P: this program\): no block N77 in "
                                         r"this program.*expected M98 Q<n> with a block N<n> in the same program"):
        parse_program("G21 G90 G0 X0 Y0\nM98 Q77\nM30\n", context=_in_dialect("fanuc"))


def test_fanuc_normal_direction_control_without_a_c_axis_leaves_the_path():
    # Fanuc 0i-MB B-63844EN II-14.9: G41.1/G42.1 turn the C axis normal to the XY path, G40.1 cancels; a
    # machine without C (this context: X Y Z only) has nothing to turn, the safety line's G40.1 is a note
    text = "G00 G49 G40.1 G17 G80 G50 G90\nG21\nG00 Z2\nG01 Z-0.2 F150\nG41.1 X16.82\nY16.82\nG40.1 X0\nM30\n"
    prog = parse_program(text, context=_in_dialect("fanuc"))
    assert _xy(prog)[-3:] == [[116.82, 0.0], [116.82, 66.82], [100.0, 66.82]]  # Y at home until Y16.82
    assert "G40.1 normal direction control cancel x2" in prog.notes
    assert any("no C axis to turn" in n for n in prog.notes)


def test_fanuc_normal_direction_control_with_a_c_axis_is_refused():
    ctx = dataclasses.replace(_in_dialect("fanuc"), extra_axes=("c",))
    with pytest.raises(GCodeError, match=r":2:1: G42.1 normal direction control right \(turning the C axis normal "
                                         r"to the path\): not supported"):
        parse_program("G21 G90 G0 X0 Y0 Z5\nG42.1 G1 X10 F100\nM30\n", context=ctx)


@pytest.mark.parametrize("name", ["linuxcnc", "haas", "grbl"])
def test_g40_1_is_named_as_fanuc_elsewhere(name):
    # LinuxCNC has no G40.1 (rs274: unknown G code); the message names the Fanuc feature and its dialect
    with pytest.raises(GCodeError, match=r":1:9: G40.1 normal direction control cancel \(Fanuc; --dialect fanuc\)"):
        parse_program("G00 G49 G40.1 G17 G90\nG0 X1\nM2\n", context=_in_dialect(name))


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas", "grbl"])
def test_a_double_slash_comment_line_is_named(name):
    # a MillMaster Pro file (the same style as Syntec/DDCS macro programs): '//' opens a comment there; an ISO
    # control reads the first '/' as block delete and then meets a second one
    with pytest.raises(GCodeError, match=r":2:2: '//' comment line \(Syntec/DDCS macro and MillMaster Pro style\): "
                                         r"not a comment in ISO G-code.*expected a \( \) or ; comment"):
        parse_program("%\n//NC FILE - PART.NC\nG21 G90 G0 X1\nM2\n%\n", context=_in_dialect(name))


def test_a_fagor_tool_and_offset_word_selects_both():
    # Fagor 8025/8030 'T2.5' (the 8055's 'T2 D5', programming manual 5.6): tool 2 with offset 5, whose length G43
    # without H applies (8055 manual 8.2)
    tools = {2: Tool(number=2, length=30.0), 5: Tool(number=5, length=12.5)}
    ctx = dataclasses.replace(_in_dialect("fanuc"), tools=tools)
    prog = parse_program("%00214\nN0 T2.5\nN10 M6\nN20 G0 G90 G43 Z100.\nN30 M30\n", context=ctx)
    assert prog.blocks[-1].target[2] == pytest.approx(-20.0 + 100.0 + 12.5)
    assert any("Fagor's tool and offset" in n for n in prog.notes)


def test_a_fagor_drilling_cycle_reads_z_as_the_reference_plane_and_i_as_the_depth():
    # Fagor 8055 programming manual 9.7: "G81 G98/G99 X Y Z I K", Z the reference plane, I the drilling depth; a
    # later block's Z alone is a new reference plane drilled to the same depth (no G80 before it)
    text = ("G0 G90 X0 Y0 Z20.\nG81 G99 X10. Y0 Z2. I-5. F100\nX20.\nZ10.\nG80\nM30\n")
    prog = parse_program(text, context=_in_dialect("fanuc"))
    z = [round(b.target[2] + 20.0, 6) for b in prog.blocks]
    assert z == [20.0, 20.0, 2.0, -5.0, 2.0, 2.0, -5.0, 2.0, 10.0, -5.0, 10.0]
    assert any("Fagor's drilling cycle" in n for n in prog.notes)


def test_fadal_fixture_offsets_and_subroutines_are_named():
    # Fadal User Manual section 1: E selects a fixture offset, L<nn>00 opens subroutine nn (M17 ends it)
    with pytest.raises(GCodeError, match=r":2:14: word 'E1' outside M66-M68 \(digital/analog I/O\) \(E1-E48 select "
                                         r"a Fadal fixture offset: use --dialect fadal\)"):
        parse_program("G21\nG90 G0 X0 Y0 E1\nM2\n", context=_in_dialect("fanuc"))
    with pytest.raises(GCodeError, match=r":1:4: unknown word 'L100' outside a drilling cycle \(a Fadal subroutine "
                                         r"definition or call: use --dialect fadal\)"):
        parse_program("N7 L100\nX0 Y0\nM17\nM30\n", context=_in_dialect("fanuc"))


@pytest.mark.parametrize(("code", "x"), [("G70", 125.4), ("G71", 101.0)])
def test_g70_g71_in_a_mill_post_are_inch_and_metric_input(code, x):
    # a Chinese shop's post ("G40 G17 G90 G71", as Siemens, Fagor and Heidenhain ISO mills write the units): no
    # lathe cycle in a mill program, read as the units with a note
    prog = parse_program(f"%\nN10 G40 G17 G90 {code}\nN20 G54 G0 X1 Y0\nN30 M30\n%\n", context=_in_dialect("fanuc"))
    assert prog.blocks[-1].target[0] == pytest.approx(x)
    assert any(f"{code} read as" in n for n in prog.notes)


def test_g71_with_a_lathe_cycles_words_stays_a_refused_cycle():
    with pytest.raises(GCodeError, match=r":2:1: G71 lathe roughing cycle: not supported \(its P word\)"):
        parse_program("G21 G0 X5 Z2\nG71 P100 Q200 R1\nM30\n", context=_in_dialect("fanuc"))


def test_haas_3026_is_the_tool_in_the_spindle():
    # a Haas shop macro: "#4= #[2400 + #3026]" reads the diameter geometry of the tool in the spindle (Haas mill
    # operator's manual, "Macros": #3026 tool in spindle, #2401-#2600 diameter geometry)
    tools = {4: Tool(number=4, radius=40.0)}
    ctx = dataclasses.replace(_in_dialect("haas"), tools=tools)
    prog = parse_program("G21 G90 G54\nT4 M6\n#4= #[2400. + #3026]\nG0 X#4 Y#3026\nM30\n", context=ctx)
    assert _xy(prog)[-1] == [180.0, 54.0]


def test_a_main_level_m99_and_the_programs_after_it_are_noted():
    # a simulator lesson's file: the subprogram O1000 (ending with M99) stored before its main program O0001; vcnc
    # runs the file's first program, whose M99 ends the run (a Fanuc would run it again), and says what it left
    text = "%\nO1000\nG21 G90 G0 X1 Y1 Z5\nM99\n%\n%\nO0001 (MAIN)\nT1 M06\nM98 P1000 L1\nM30\n%\n"
    prog = parse_program(text, context=_in_dialect("fanuc"))
    assert _xy(prog) == [[101.0, 51.0]]
    assert any("M99 ends the main program" in n and "later programs (O0001) are not run" in n for n in prog.notes)


def test_m98_q_without_p_that_would_call_itself_is_refused():
    # a Mach4 test file: 'M98 Q1 (Subroutines\9010.tap)' names its file in a comment; read as a call of this
    # program's N1, which lies before the call and runs into it again without an M99
    with pytest.raises(GCodeError, match=r":3:1: M98 Q subprogram call \(no P: this program\): block N1 comes before "
                                         r"the call and reaches it again without an M99"):
        parse_program("G21 G90\nN1 (SPOT DRILL)\nM98 Q1 (SUB.TAP)\nM30\n", context=_in_dialect("fanuc"))
