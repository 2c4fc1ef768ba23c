"""Heidenhain programs of the fifteenth wild set (a TNC 640 shop's Fusion 360 output in
polymech-info/heidenhain-simulator's samples: probing with cycles 412, 413, 417, 419, drilling 203, tapping 207,
pockets and contours with helices and arcs in the ZX and YZ planes; see /tmp/tncwild15/set/sources.tsv): the forms
the set leans on that vcnc ran differently from the TNC, each as a hand-written program with end points worked out
by hand and checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np

from interpolators.context import MachineContext, Tool
from tests.interpolators.reference_heidenhain import checked_program

#: The probe as the shop's tool table gives it (Fusion's header: "#100 D=6 CR=3 - probe").
PROBE = MachineContext(tools={100: Tool(number=100, length=0.0, radius=3.0)})


def checked(body: str, context: MachineContext = PROBE):
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", context)


def circle_probe(number: int, diameter: str, q301: str, q365: str | None) -> str:
    """A circle probing cycle in the form Fusion's TNC 640 post writes it (one parameter a line, '~')."""
    lines = [f"4 TCH PROBE {number} DATUM {'INSIDE' if number == 412 else 'OUTSIDE'} CIRCLE ~",
             "    Q321=+0    ;CENTER IN 1ST AXIS ~", "    Q322=+0    ;CENTER IN 2ND AXIS ~",
             f"    Q262={diameter}   ;NOMINAL DIAMETER ~", "    Q325=+0    ;STARTING ANGLE ~",
             "    Q247=+90   ;STEPPING ANGLE ~", "    Q261=-3    ;MEASURING HEIGHT ~",
             "    Q320=+12   ;SET-UP CLEARANCE ~", "    Q260=+5    ;CLEARANCE HEIGHT ~",
             f"    Q301={q301}    ;MOVE TO CLEARANCE ~", "    Q305=+0    ;NUMBER IN TABLE ~",
             "    Q331=+0    ;DATUM ~", "    Q332=+0    ;DATUM ~", "    Q303=+1    ;MEAS. VALUE TRANSFER ~",
             "    Q381=+0    ;PROBE IN TS AXIS ~", "    Q382=+0    ;1ST CO. FOR TS AXIS ~",
             "    Q383=+0    ;2ND CO. FOR TS AXIS ~", "    Q384=+0    ;3RD CO. FOR TS AXIS ~",
             "    Q333=+0    ;DATUM ~", "    Q423=+4    ;NO. OF MEAS. POINTS" + (" ~" if q365 else "")]
    if q365:
        lines.append(f"    Q365={q365}    ;TYPE OF TRAVERSE")
    return ("1 TOOL CALL 100 Z S50\n2 L X+0 Y+0 R0 FMAX\n3 L Z+55 R0 FMAX\n" + "\n".join(lines) +
            "\n5 L Z+55 FMAX")


def between(prog) -> list[tuple[str, list[float]]]:
    """The cycle's moves from one starting point to the next (both as far from the centre (0, 0), at one height):
    (kind, end)."""
    return [(b.kind, np.round(b.target, 6).tolist()) for b in prog.blocks
            if not np.allclose(b.start[:2], b.target[:2]) and b.start[2] == b.target[2]
            and np.isclose(np.hypot(*b.start[:2]), np.hypot(*b.target[:2]))]


def test_probing_a_stud_with_q365_1_moves_on_an_arc_about_its_centre():
    # polymech-info/heidenhain-simulator samples/a_phv3/motorflange/probe-120.h: 'TCH PROBE 413 ... Q301=+1 ...
    # Q365=+1 ;TYPE OF TRAVERSE'. Q365 is the "Type of traverse? Line=0/arc=1" (TNC 640 cycle manual 34059x-01, the
    # same parameter of cycle 220): 1 an arc about the stud's centre; vcnc took 1 for a line and 0 for an arc. The
    # D70 stud, probe tip R3, clearance Q320 12 + SET_UP 2: starting points 35 + 3 + 14 = 52 from the centre, at the
    # clearance height Z+5 between them: quarter arcs, counter-clockwise (Q247 = +90)
    prog = checked(circle_probe(413, "+70 ", "+1", "+1"))
    moves = between(prog)
    assert [k for k, _ in moves] == ["arc", "arc", "arc"]
    assert [end for _, end in moves] == [[0, 52, 5], [-52, 0, 5], [0, -52, 5]]
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    assert all(b.segment.ccw and np.allclose(b.segment.center, [0, 0, 5]) for b in arcs)


def test_probing_a_hole_with_q365_0_moves_straight_at_the_measuring_height():
    # the same cycle 412 (samples/a_phv3/brackets/probe-40.h: a D40 hole, Q301=+0) with Q365=0: straight lines
    # between the starting points 20 - 3 - 14 = 3 mm from the centre, at the measuring height Z-3
    prog = checked(circle_probe(412, "+40 ", "+0", "+0"))
    assert between(prog) == [("line", [0, 3, -3]), ("line", [-3, 0, -3]), ("line", [0, -3, -3])]


def test_a_circle_probing_cycle_without_q365_moves_on_arcs():
    # a definition of a control without Q365 (TNC 426/430, iTNC 530 before it): "the touch probe moves in a circular
    # arc either at measuring height or at clearance height to the next starting point" (TNC 320 cycle manual
    # 340 55x-04, cycle 422 "Cycle run" 3; iTNC 530 cycle manual 340 49x-06, cycle 405): vcnc moved straight
    prog = checked(circle_probe(412, "+40 ", "+0", None))
    assert [k for k, _ in between(prog)] == ["arc", "arc", "arc"]


def test_the_measuring_cycle_422_moves_as_413_does():
    # 421/422 probe as 412/413 (TNC 320 cycle manual 340 55x-04, cycle 422 "Cycle run" 3, quoted above): with
    # Q365=+1 on arcs about the nominal centre Q273/Q274, here (0, 0) at the clearance height Q260 = +5
    prog = checked("1 TOOL CALL 100 Z S50\n2 L X+0 Y+0 Z+55 R0 FMAX\n3 TCH PROBE 422 MEAS. CIRCLE OUTSIDE Q273=+0 "
                   "Q274=+0 Q262=+70 Q325=+0 Q247=+90 Q261=-3 Q320=+12 Q260=+5 Q301=+1 Q277=+0 Q278=+0 Q279=+0 "
                   "Q280=+0 Q281=+0 Q423=4 Q365=+1\n4 L Z+55 FMAX")
    assert [k for k, _ in between(prog)] == ["arc", "arc", "arc"]
