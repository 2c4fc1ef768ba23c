"""Old TNC cycles as shop programs call them (session 39): an iTNC 530 shop program (weigl_02, a plate with a
pitch circle of tapped holes) taps with the old cycle 2 TAPPING on the positions of cycle 220 POLAR PATTERN.
Each program is hand-written in the style of the program that showed it.

The old cycles 1 PECKING, 2 TAPPING and 17 RIGID TAPPING run from the tool's position, their depth counted from
their own set-up clearance below it (TNC 426/430 user's manual, cycles 1 and 2: "Set-up clearance: distance
between tool tip (at starting position) and workpiece surface"). From which height cycle 220/221 starts such a
cycle at its positions, and whether its Q200/Q203/Q204 act on it, no manual page found says (the pattern's run
is given for the 200-series cycles, whose Q200/Q203/Q204 it replaces: TNC 320 user's manual for cycle
programming 9/2016, "POLAR PATTERN (Cycle 220)"). The reader refuses the combination with the reason; the
reference, which ran the old cycle from the pattern's 2nd set-up clearance, now refuses it too."""

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


def _program(old: int, pattern: int) -> str:
    return ("BEGIN PGM P MM\nBLK FORM 0.1 Z X+0 Y+0 Z-20\nBLK FORM 0.2 X+100 Y+100 Z+0\nTOOL CALL 1 Z S500\n"
            "L Z+50 R0 FMAX\nL X+50 Y+50 R0 FMAX M3\n" + OLD_CYCLES[old] + PATTERNS[pattern]
            + "L Z+50 R0 FMAX\nEND PGM P MM\n")


@pytest.mark.parametrize("pattern", sorted(PATTERNS))
@pytest.mark.parametrize("old", sorted(OLD_CYCLES))
def test_a_pattern_calling_an_old_cycle_is_refused_by_the_reader_and_the_reference(old, pattern):
    text = _program(old, pattern)
    with pytest.raises(GCodeError, match=rf"t\.h:\d+:\d+: cycle {pattern} with cycle {old}: a pattern runs the "
                                         r"machining cycles of the 200 series here \(an old cycle runs from the "
                                         r"tool's position: from which height a pattern starts it"):
        parse_heidenhain(text, source="t.h", context=CTX)
    # the reference ran the old cycle from the pattern's 2nd set-up clearance (tapping from Z+20 to Z+3)
    with pytest.raises(ReferenceError, match=rf"cycle {pattern} with cycle {old}: a pattern runs"):
        heidenhain_reference(text, CTX)


def test_the_old_cycle_called_at_the_positions_by_hand_runs_in_both():
    # what the shop program's cycle 220 stands for, written as the TNC runs an old cycle: pre-positioned at the
    # set-up clearance over each hole, CYCL CALL (the 4 positions of the pitch circle above, 40 mm across)
    holes = "".join(f"L X{x:+g} Y{y:+g} R0 FMAX\nL Z+2 R0 FMAX\nCYCL CALL\nL Z+20 R0 FMAX\n"
                    for x, y in ((70, 50), (50, 70), (30, 50), (50, 30)))
    text = ("BEGIN PGM P MM\nTOOL CALL 1 Z S500\nL Z+50 R0 FMAX\nL X+50 Y+50 R0 FMAX M3\n" + OLD_CYCLES[2]
            + holes + "END PGM P MM\n")
    prog = checked_program(text, CTX)
    bottoms = [b.target for b in prog.blocks if abs(b.target[2] - (-15.0 + 10.0)) < 1e-9]
    # each hole tapped to DEPTH -15 below the surface (Z+2 minus SET UP 2 = Z0), the tool 10 mm long
    # (the dwell at the bottom repeats the point)
    points = list(dict.fromkeys(tuple(round(float(v), 6) for v in t[:2]) for t in bottoms))
    assert points == [(70, 50), (50, 70), (30, 50), (50, 30)]
