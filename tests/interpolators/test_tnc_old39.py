"""Old TNC cycles as shop programs call them (session 39): an iTNC 530 shop program (weigl_02, a plate with a
pitch circle of tapped holes) taps with the old cycle 2 TAPPING on the positions of cycle 220 POLAR PATTERN, which
the reader refused ("a pattern runs the machining cycles of the 200 series here") and the reference ran from the
pattern's 2nd set-up clearance (tapping from Z+20 to Z+3 instead of from Z+2 to Z-15).

The old cycles 1 PECKING, 2 TAPPING and 17 RIGID TAPPING start where the tool stands, their surface their own
set-up clearance below it (TNC 426/430 user's manual, cycles 1 and 2: "Set-up clearance: distance between tool tip
(at starting position) and workpiece surface"); cycle 220/221 takes the tool to its set-up clearance Q200 above its
surface Q203 and runs the last defined cycle from there (TNC 320 user's manual for cycle programming 9/2016,
"POLAR PATTERN (Cycle 220)", "Cycle run"). With Q200 equal to the old cycle's set-up clearance both give one
surface: the reader and the reference run it; another Q200 is refused by both (which surface would count, no
manual page found says). Each program is hand-written in the style of the program that showed it."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program, heidenhain_reference
from tests.interpolators.reference_iso import ReferenceError
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (0.0, 0.0, 0.0)}, tools={1: Tool(number=1, length=10.0, radius=3.0)})

OLD_CYCLES = {
    1: ("CYCL DEF 1.0 PECKING\nCYCL DEF 1.1 SET UP 2\nCYCL DEF 1.2 DEPTH -15\nCYCL DEF 1.3 PECKG 5\n"
        "CYCL DEF 1.4 DWELL 0\nCYCL DEF 1.5 F100\n"),
    2: ("CYCL DEF 2.0 TAPPING\nCYCL DEF 2.1 SET UP 2\nCYCL DEF 2.2 DEPTH -15\nCYCL DEF 2.3 DWELL 0.5\n"
        "CYCL DEF 2.4 F100\n"),
    17: "CYCL DEF 17.0 RIGID TAPPING GS\nCYCL DEF 17.1 SET UP 2\nCYCL DEF 17.2 DEPTH -15\nCYCL DEF 17.3 PITCH +1\n",
}

PATTERNS = {
    220: ("CYCL DEF 220 POLAR PATTERN ~\n Q216=+50 ;CENTER IN 1ST AXIS ~\n Q217=+50 ;CENTER IN 2ND AXIS ~\n"
          " Q244=+40 ;PITCH CIRCLE DIAMETR ~\n Q245=+0 ;STARTING ANGLE ~\n Q246=+360 ;STOPPING ANGLE ~\n"
          " Q247=+0 ;STEPPING ANGLE ~\n Q241=+4 ;NR OF REPETITIONS ~\n Q200=+2 ;SET-UP CLEARANCE ~\n"
          " Q203=+0 ;SURFACE COORDINATE ~\n Q204=+20 ;2ND SET-UP CLEARANCE ~\n Q301=+1 ;MOVE TO CLEARANCE ~\n"
          " Q365=+0 ;TYPE OF TRAVERSE\n"),
    221: ("CYCL DEF 221 CARTESIAN PATTERN ~\n Q225=+10 ;STARTNG PNT 1ST AXIS ~\n Q226=+10 ;STARTNG PNT 2ND AXIS ~\n"
          " Q237=+20 ;SPACING IN 1ST AXIS ~\n Q238=+15 ;SPACING IN 2ND AXIS ~\n Q242=+3 ;NUMBER OF COLUMNS ~\n"
          " Q243=+2 ;NUMBER OF LINES ~\n Q224=+0 ;ANGLE OF ROTATION ~\n Q200=+2 ;SET-UP CLEARANCE ~\n"
          " Q203=+0 ;SURFACE COORDINATE ~\n Q204=+20 ;2ND SET-UP CLEARANCE ~\n Q301=+1 ;MOVE TO CLEARANCE\n"),
}


def _program(old: int, pattern: int, *, setup: float = 2.0, high: int = 1, pre: str = "") -> str:
    pat = PATTERNS[pattern].replace("Q200=+2 ", f"Q200={setup:+g} ").replace("Q301=+1 ", f"Q301={high:+d} ")
    return ("BEGIN PGM P MM\nBLK FORM 0.1 Z X+0 Y+0 Z-20\nBLK FORM 0.2 X+100 Y+100 Z+0\nTOOL CALL 1 Z S500\n"
            "L Z+50 R0 FMAX\nL X+50 Y+50 R0 FMAX M3\n" + pre + OLD_CYCLES[old] + pat + "L Z+50 R0 FMAX\nEND PGM P MM\n")


def _bottoms(prog, level: float) -> list[tuple[float, float]]:
    """The plane positions (in order, once each) where the tool reaches ``level`` along Z [mm, machine]."""
    return list(dict.fromkeys((round(float(b.target[0]), 6), round(float(b.target[1]), 6)) for b in prog.blocks
                              if abs(b.target[2] - level) < 1e-9))


@pytest.mark.parametrize("high", [1, 0])
@pytest.mark.parametrize("pattern", sorted(PATTERNS))
@pytest.mark.parametrize("old", sorted(OLD_CYCLES))
def test_a_pattern_runs_an_old_cycle_from_its_set_up_clearance(old, pattern, high):
    # refused by the reader before ('a pattern runs the machining cycles of the 200 series here')
    prog = checked_program(_program(old, pattern, high=high), CTX)
    # the holes to DEPTH -15 below the surface Z0 (the tool 10 mm long), at the pattern's positions
    holes = {220: [(70, 50), (50, 70), (30, 50), (50, 30)],
             221: [(10, 10), (30, 10), (50, 10), (50, 25), (30, 25), (10, 25)]}[pattern]
    assert _bottoms(prog, -15.0 + 10.0) == holes
    # each hole from the set-up clearance Z+2; between the holes at the 2nd set-up clearance Z+20 (Q301=1) or
    # at Z+2 (Q301=0); after the last one at Z+20
    zs = [round(float(b.target[2]) - 10.0, 6) for b in prog.blocks]
    assert zs[-2] == 20.0 and min(zs) == -15.0
    assert (20.0 in zs[4:-2]) == bool(high)  # after the first position, reached at Z+20


def test_the_shop_programs_tapping_on_a_pitch_circle_under_scaling():
    # cycle 11 SCALING 0.5 about the datum: the pattern's positions, set-up clearances and the depth scale
    prog = checked_program(_program(2, 220, pre="CYCL DEF 11.0 SCALING\nCYCL DEF 11.1 SCL 0.5\n"), CTX)
    assert _bottoms(prog, -7.5 + 10.0) == [(35, 25), (25, 35), (15, 25), (25, 15)]


@pytest.mark.parametrize("old", sorted(OLD_CYCLES))
def test_a_pattern_whose_set_up_clearance_is_not_the_old_cycles_is_refused_by_both(old):
    text = _program(old, 220, setup=5.0)
    with pytest.raises(GCodeError, match=rf"t\.h:\d+:\d+: cycle 220 with cycle {old}: the pattern's set-up "
                                         r"clearance Q200 \(5\) differs from the cycle's \(2\).*expected Q200 = 2"):
        parse_heidenhain(text, source="t.h", context=CTX)
    with pytest.raises(ReferenceError, match=rf"cycle 220 with cycle {old}: Q200 differs"):
        heidenhain_reference(text, CTX)


@pytest.mark.parametrize("old", ["CYCL DEF 4.0 POCKET MILLING\nCYCL DEF 4.1 SET UP 2\nCYCL DEF 4.2 DEPTH -5\n"
                                 "CYCL DEF 4.3 PECKG 5 F100\nCYCL DEF 4.4 X+20\nCYCL DEF 4.5 Y+10\n"
                                 "CYCL DEF 4.6 F200 DR+ RADIUS 2\n",
                                 "CYCL DEF 5.0 CIRCULAR POCKET\nCYCL DEF 5.1 SET UP 2\nCYCL DEF 5.2 DEPTH -5\n"
                                 "CYCL DEF 5.3 PECKG 5 F100\nCYCL DEF 5.4 RADIUS 8\nCYCL DEF 5.5 F200 DR+\n"])
def test_a_pattern_calling_an_old_pocket_is_refused_by_both(old):
    text = ("BEGIN PGM P MM\nTOOL CALL 1 Z S500\nL Z+50 R0 FMAX\nL X+50 Y+50 R0 FMAX M3\n" + old + PATTERNS[220]
            + "END PGM P MM\n")
    with pytest.raises(GCodeError, match=r"cycle 220 with cycle [45]: a pattern runs the machining cycles of the "
                                         r"200 series and the old cycles 1, 2, 17 here"):
        parse_heidenhain(text, source="t.h", context=CTX)
    with pytest.raises(ReferenceError, match=r"cycle 220 with cycle [45]: a pattern runs"):
        heidenhain_reference(text, CTX)


def test_the_old_cycle_called_at_the_positions_by_hand_runs_in_both():
    # what the shop program's cycle 220 stands for, written as the TNC runs an old cycle: pre-positioned at the
    # set-up clearance over each hole, CYCL CALL (the 4 positions of the pitch circle above, 40 mm across)
    holes = "".join(f"L X{x:+g} Y{y:+g} R0 FMAX\nL Z+2 R0 FMAX\nCYCL CALL\nL Z+20 R0 FMAX\n"
                    for x, y in ((70, 50), (50, 70), (30, 50), (50, 30)))
    text = ("BEGIN PGM P MM\nTOOL CALL 1 Z S500\nL Z+50 R0 FMAX\nL X+50 Y+50 R0 FMAX M3\n" + OLD_CYCLES[2]
            + holes + "END PGM P MM\n")
    # each hole tapped to DEPTH -15 below the surface (Z+2 minus SET UP 2 = Z0), the tool 10 mm long
    assert _bottoms(checked_program(text, CTX), -15.0 + 10.0) == [(70, 50), (50, 70), (30, 50), (50, 30)]


def test_the_shop_programs_form_runs_in_both():
    # weigl_02's blocks 87-94 (iTNC 530): tool at Z+1, cycle 2 with ABST 1, then CALL LBL 1 runs the cycle 220
    # of its label (Q200 = 1, Q203 = 0, Q204 = 1): two tapped holes 48 mm apart, to Z-18
    text = ("0 BEGIN PGM 02 MM\n1 TOOL DEF 6 L+0 R+4\n2 TOOL CALL 6 Z S2000 F200\n3 L X+60 Y+45 Z+1 FMAX M4\n"
            "4 CYCL DEF 2.0 GEWINDEBOHREN\n5 CYCL DEF 2.1 ABST 1\n6 CYCL DEF 2.2 TIEFE -18\n7 CYCL DEF 2.3 V.ZEIT 0.1\n"
            "8 CYCL DEF 2.4 F100\n9 CALL LBL 1\n10 L X+200 Y+200 Z+100 FMAX\n11 M30\n12 LBL 1\n"
            "13 CYCL DEF 220 MUSTER KREIS ~\n    Q216=+60 ;MITTE 1. ACHSE ~\n    Q217=+45 ;MITTE 2. ACHSE ~\n"
            "    Q244=+48 ;TEILKREIS-DURCHM. ~\n    Q245=+0 ;STARTWINKEL ~\n    Q246=+180 ;ENDWINKEL ~\n"
            "    Q247=+180 ;WINKELSCHRITT ~\n    Q241=+2 ;ANZAHL BEARBEITUNGEN ~\n    Q200=+1 ;SICHERHEITS-ABST. ~\n"
            "    Q203=+0 ;KOOR. OBERFLAECHE ~\n    Q204=+1 ;2. SICHERHEITS-ABST. ~\n"
            "    Q301=+1 ;FAHREN AUF S. HOEHE ~\n"
            "    Q365=+0 ;VERFAHRART\n14 LBL 0\n15 END PGM 02 MM\n")
    prog = checked_program(text, MachineContext())
    assert _bottoms(prog, -18.0) == [(84, 45), (36, 45)]
