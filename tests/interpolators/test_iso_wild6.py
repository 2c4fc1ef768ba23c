"""ISO programs of the sixth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


@pytest.mark.parametrize("head, dialect", [("WH[#1GT0]DO1", "haas"), ("N10 WHIL [#1 GT 0] DO 1", "fanuc")])
def test_a_loop_head_that_is_not_while_is_named(head, dialect):
    # a Fanuc 0i-MD macro of the set writes "WH[..]DO1", Fanuc's abbreviation of WHILE (test_iso_wild10), which
    # Haas does not document; "WHIL" abbreviates nothing: the message names the keyword instead of an END 1 that
    # closes nothing
    with pytest.raises(GCodeError, match=r":3:\d+: loop head 'WHI?L?' \[..\] DO m: the keyword of a loop is WHILE"
                                         r".*expected WHILE \[condition\] DO m"):
        parse_program(f"O1\n#1=2\n{head}\nG91 G1 X1 F100\n#1=#1-1\nEND1\nM30\n", context=_in_dialect(dialect))


def test_grbl_refuses_an_arc_without_an_end_point_in_its_plane():
    # CNCjs' example "full-circle-without-xyz" writes "G2 J-1.1"; grbl's arc checks (gnea/grbl grbl/gcode.c,
    # "[No axis words in plane]") refuse it, LinuxCNC and Fanuc run the full circle
    text = "G21 G90 G17 F100\nG0 X0 Y0\nG2 J-1.1\nG2 X0 I1 Z-1\nM2\n"
    with pytest.raises(GCodeError, match=r":3:1: G02 arc without an end point in its plane: grbl refuses it "
                                         r".*expected X and/or Y with G02 in G17"):
        parse_program(text, context=_in_dialect("grbl"))
    for name in ("linuxcnc", "fanuc"):
        arcs = [b for b in parse_program(text, context=_in_dialect(name)).blocks if b.kind == "arc"]
        assert len(arcs) == 2
        assert arcs[0].target.tolist() == arcs[0].start.tolist()  # a full turn back to its start
    with pytest.raises(GCodeError, match=r":3:1: G02 arc without an end point in its plane"):
        parse_program(text.replace("G2 J-1.1", "G2 Z-1 J-1.1"), context=_in_dialect("grbl"))


@pytest.mark.parametrize("name", ["fanuc", "haas"])
def test_a_tool_offset_zero_is_not_set(name):
    # a Robodrill post writes "G10 L11 P#4120 R-1.0" (the wear of the tool in the spindle) before its first T:
    # #4120 is 0 then, and offset 0 (H00) "always means 0" and cannot be set (Fanuc B-64304EN "Tool length
    # compensation"): the G10 changes nothing and says so; offset 2 is set as before (tool length 12.5 - 1)
    tools = {2: Tool(number=2, length=12.5)}
    ctx = dataclasses.replace(_in_dialect(name), tools=tools)
    prog = parse_program("G90 G0\nG10 L11 P#4120 R-1.0\nX0 Y0\nG43 Z50.\nM30\n", context=ctx)
    assert prog.blocks[-1].target.tolist() == [100.0, 50.0, 30.0]  # G54 (100, 50, -20), no tool length
    assert "G10 L11 P0: offset 0 (H00/D00) always means 0 and cannot be set: ignored" in prog.notes
    prog = parse_program("G90 G0\nG10 L11 P2 R-1.0\nX0 Y0\nG43 H2 Z50.\nM30\n", context=ctx)
    assert prog.blocks[-1].target.tolist() == [100.0, 50.0, 41.5]


def test_linuxcnc_refuses_a_tool_change_under_cutter_compensation():
    # a hand-written student program turns G42 on, then changes tools: rs274 stops at the M06 ("Cannot change
    # tools with cutter radius compensation on", interp_convert.cc convert_tool_change); vcnc said so only at
    # a later block
    text = "G20 G90 F10\nG42\nM06 T1\nG0 X1\nG40\nM2\n"
    with pytest.raises(GCodeError, match=r":3:1: M6 tool change with cutter radius compensation on \(G42\): "
                                         r"LinuxCNC refuses it .*expected G40 before the tool change"):
        parse_program(text, context=_in_dialect("linuxcnc"))
    prog = parse_program(text.replace("G42\nM06 T1", "G42\nG40\nM06 T1"), context=_in_dialect("linuxcnc"))
    assert prog.blocks[-1].target.tolist() == [125.4, 0.0, 100.0]  # G54 X100 + 1 in, Y and Z not moved


def test_m98_q_starts_the_subprogram_at_its_block_n():
    # Mach4's examples write "M98 P9010 Q1" (Mitsubishi M70 "M98 P__ Q__ L__": Q the sequence number the
    # subprogram is called at); each repetition starts there too, and the run says it read the form
    text = "O1\nG90 G0 X0 Y0\nM98 P100 Q20 L2\nM30\nO100\nN10 G91 G0 X5\nN20 G91 G0 Y5\nM99\n"
    prog = parse_program(text, context=_in_dialect("fanuc"))
    assert [b.target.tolist()[:2] for b in prog.blocks] == [[100.0, 50.0], [100.0, 55.0], [100.0, 60.0]]
    assert any(n.startswith("M98 P Q: the subprogram starts at its block N<Q>") for n in prog.notes)
    with pytest.raises(GCodeError, match=r":3:\d+: M98 Q30: no block N30 in the called program"):
        parse_program(text.replace("Q20", "Q30"), context=_in_dialect("fanuc"))
