"""ISO programs of the sixth wild set (issue 18): what their own controls run, and how the others are refused."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


@pytest.mark.parametrize("head", ["WH[#1GT0]DO1", "N10 WHIL [#1 GT 0] DO 1"])
def test_a_loop_head_that_is_not_while_is_named(head):
    # a Fanuc 0i-MD macro of the set writes "WH[..]DO1"; the manuals (B-64304EN "Branch and repetition") write
    # WHILE in full: the message names the keyword instead of an END 1 that closes nothing
    with pytest.raises(GCodeError, match=r":3:\d+: loop head 'WHI?L?' \[..\] DO m: the keyword of a loop is WHILE "
                                         r".*expected WHILE \[condition\] DO m"):
        parse_program(f"O1\n#1=2\n{head}\nG91 G1 X1 F100\n#1=#1-1\nEND1\nM30\n", context=_in_dialect("fanuc"))


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
