"""Heidenhain reader: the M functions with parameters, the feed per revolution, FN 20, QS string parameters,
CYCL CALL PAT F and SPL splines (issue #19), hand-written programs checked with exact numbers and against the
independent reference (:mod:`tests.interpolators.reference_heidenhain`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext, Tool
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

CTX = MachineContext()


def program(body: str, unit: str = "MM") -> str:
    return f"0 BEGIN PGM T {unit}\n" + body + f"\nEND PGM T {unit}\n"


def run(body: str, context: MachineContext = CTX, **kw):
    return checked_program(program(body), context, **kw)


def refused(body: str, context: MachineContext = CTX, unit: str = "MM") -> GCodeError:
    with pytest.raises(GCodeError) as info:
        parse_heidenhain(program(body, unit), source="t.h", context=context)
    assert info.value.file == "t.h"
    return info.value


def ends(prog):
    return [np.round(b.target, 6).tolist() for b in prog.blocks]


# --- M functions with parameters ---------------------------------------------------------------

STEP = ("TOOL DEF 1 L+0 R+2\nTOOL CALL 1 Z S1000\nL X-10 Y+0 Z-5 R0 FMAX\nL X+0 Y+0 RL F300{m}\nL X+20\nL Y+20\n"
        "L X+0\nL Y+0\nL X-10 R0")


def test_m120_look_ahead_runs_the_compensated_path_as_without_it():
    """TNC 640 user's manual, "Calculating the radius-compensated path in advance (LOOK AHEAD): M120": LA blocks
    calculated in advance; where the tool fits, the path is the compensated one."""
    plain = run(STEP.format(m=""), exact=False)
    ahead = run(STEP.format(m=" M120 LA3"), exact=False)
    assert ends(ahead) == ends(plain)
    assert any("M120 LA" in n for n in ahead.notes)


def test_m120_names_itself_where_the_tool_does_not_fit():
    err = refused("TOOL DEF 1 L+0 R+5\nTOOL CALL 1 Z\nL X-20 Y+0 Z-5 R0 FMAX\nL X+0 Y+0 RL F300 M120 LA5\nL X+20\n"
                  "L Y+2\nL X+22\nL Y+20\nL X+0\nL Y+0\nL X-20 R0")
    assert "M120 LA would leave the undercut out" in str(err)


def test_m118_handwheel_limits_and_m124_filter_do_not_move():
    """TNC 640 user's manual, "Superimposing handwheel positioning during program run: M118"; TNC 407 manual, M124 T:
    a filter of M112's points. The moves are those of the blocks without them."""
    prog = run("L X+10 Y+0 Z+0 R0 F500 M118 X1 Y1\nM118 Z2\nL X+20 M124 T0.01\nM124 T0.5")
    assert ends(prog) == [[10, 0, 0], [20, 0, 0]]
    assert any(n.startswith("M118:") for n in prog.notes) and any(n.startswith("M124 T:") for n in prog.notes)


def test_m112_tolerance_as_cycle_32_until_m113():
    """TNC 426/430 user's manual, "Insert rounding arc between straight lines: M112" (HEIDENHAIN recommends cycle 32
    TOLERANCE for the same): the blocks after M112 T0.02 run continuously within 0.02 mm, M113 ends it."""
    prog = run("L X+0 Y+0 Z+0 R0 F500\nL X+10 M112 T0.02 A10\nL Y+10\nL X+0 M113\nL Y+0")
    assert [(b.exact_stop, b.tolerance) for b in prog.blocks] == [(True, None), (False, 0.02), (False, 0.02),
                                                                  (True, None), (True, None)]


C_AXIS = MachineContext(extra_axes=("c",))


def test_m94_reduces_the_rotary_display_before_the_next_absolute_angle():
    """TNC 426 B/430 user's manual, "Reducing display of a rotary axis to a value less than 360 deg: M94": at 538 deg,
    L C+180 FMAX M94 traverses +2 deg (the manual's example); the axis itself does not move at the reduction."""
    prog = run("L C+538 FMAX\nL C+180 FMAX M94", C_AXIS)
    assert [b.extra_target[2] for b in prog.blocks] == [538.0, 540.0]
    prog = run("L C+538 FMAX\nM94 C\nL C+90 FMAX\nL IC+10 FMAX\nL M94\nL C+0 FMAX", C_AXIS)
    assert [b.extra_target[2] for b in prog.blocks] == [538.0, 450.0, 460.0, 360.0]


def test_m136_feed_per_revolution_until_m137():
    """TNC 640 user's manual, "Feed rate in millimeters per spindle revolution: M136": F in mm/rev from the start
    of the M136 block, times the TOOL CALL's S; M137 back to mm/min."""
    prog = run("TOOL CALL 1 Z S2000\nL X+0 Y+0 Z+0 R0 FMAX\nL X+10 F0.05 M136\nL X+20\nL X+30 F0.1\nM137\n"
               "L X+40 F300")
    assert [round(b.feed * 60, 9) for b in prog.blocks[1:]] == [100.0, 100.0, 200.0, 300.0]


def test_m136_needs_a_spindle_speed_and_millimetres():
    assert "feed per revolution (FU, M136) without a spindle speed" in str(refused("L X+10 F0.1 M136"))
    assert "M136 in an inch program" in str(refused("TOOL CALL 1 Z S1000\nL X+1 F0.01 M136", unit="INCH"))


def test_fn20_wait_for_is_met_at_once():
    prog = run("FN 20: WAIT FOR SYNC\nL X+5 Y+0 Z+0 R0 FMAX\nFN 20: WAIT FOR M4095==1")
    assert ends(prog) == [[5, 0, 0]]
    assert "FN 20: WAIT FOR (PLC synchronisation) read as met at once (no motion) x2" in prog.notes


# --- QS string parameters ----------------------------------------------------------------------

def test_string_parameters_name_the_tool():
    """TNC 640 user's manual, "String parameters": DECLARE STRING, || joins; TOOL CALL QSn calls the tool of that
    name (the table's NAME column)."""
    ctx = MachineContext(tools={7: Tool(number=7, length=40.0, radius=3.0, name="MILL_D6")})
    prog = run('DECLARE STRING QS1 = "MILL"\nQS2 = QS1 || "_" || "D6"\nTOOL CALL QS2 Z S3000\nL X+0 Y+0 Z+0 R0 FMAX',
               ctx)
    assert ends(prog) == [[0, 0, 40]]


def test_string_functions_tochar_and_substr():
    ctx = MachineContext(tools={3: Tool(number=3, length=10.0, name="T2.50")})
    prog = checked_program(program('Q5 = 2.5\nQS1 = "T" || TOCHAR( DAT+Q5 DECIMALS2 )\nQS2 = SUBSTR( SRC_QS1 BEG0 '
                                   'LEN5 )\nTOOL CALL QS2 Z\nL Z+0 FMAX'), ctx, check=False)
    assert ends(prog)[-1][2] == 10.0


def test_call_pgm_by_string_parameter(tmp_path):
    (tmp_path / "SUB.H").write_text("0 BEGIN PGM SUB MM\n1 L X+7 Y+0 Z+0 R0 FMAX\n2 END PGM SUB MM\n")
    main = tmp_path / "MAIN.H"
    main.write_text(program('DECLARE STRING QS9 = "SUB.H"\nCALL PGM QS9'))
    prog = parse_heidenhain(main.read_text(), source=str(main), context=CTX)
    assert ends(prog) == [[7, 0, 0]]


@pytest.mark.parametrize("body, words", [
    ("QS1 = SYSSTR( ID10010 NR1 )", "string function SYSSTR (system or machine data) is not supported"),
    ('DECLARE STRING QS1 = "12"\nQ1 = TONUMB( SRC_QS1 )', "string function TONUMB in a formula is not supported"),
    ("TOOL CALL QS4 Z", "string parameter QS4 is used before it is assigned"),
    ('QS1 = "A" "B"', "malformed string formula"),
])
def test_string_uses_vcnc_cannot_honour_are_named(body, words):
    assert words in str(refused(body))


# --- CYCL CALL PAT F -------------------------------------------------------------------------------

PATTERN = ("TOOL CALL 1 Z S2000\nL X+0 Y+0 Z+20 R0 FMAX\nCYCL DEF 200 DRILLING Q200=2 Q201=-5 Q206=150 Q202=5 Q210=0 "
           "Q203=+0 Q204=10 Q211=0\nPATTERN DEF\n  POS1 (X+10 Y+10 Z+0)\n  POS2 (X+40 Y+10 Z+0)\nCYCL CALL PAT {f}")


def test_cycl_call_pat_positions_at_its_feed_between_the_points():
    """The F of CYCL CALL PAT (TNC 640 user's manual, cycle programming, "Calling a cycle with CYCL CALL PAT"): the
    moves between the points at that feed, F MAX at rapid."""
    fast = run(PATTERN.format(f="F MAX"))
    slow = run(PATTERN.format(f="F1200 M13"))
    assert ends(fast) == ends(slow)
    def across(prog):  # the moves in the plane from point to point
        return [(b.kind, round(b.feed * 60, 6)) for b in prog.blocks[1:] if b.start[2] == b.target[2]]

    assert across(slow) == [("line", 1200.0), ("line", 1200.0)]
    assert across(fast) == [("rapid", math.inf), ("rapid", math.inf)]


# --- SPL ------------------------------------------------------------------------------------------

#: The iTNC 530 user's manual's example (60642x-04, p. 539): two spline blocks from X+28.338 Y+19.385 Z-0.5.
MANUAL_SPL = ("L X+28.338 Y+19.385 Z-0.5 R0 FMAX\n"
              "SPL X24.875 Y15.924 Z-0.5 K3X-4.688E-002 K2X2.459E-002 K1X3.486E+000 ~\n"
              "  K3Y-4.563E-002 K2Y2.155E-002 K1Y3.486E+000 ~\n  K3Z0.000E+000 K2Z0.000E+000 K1Z0.000E+000 F10000\n"
              "SPL X17.952 Y9.003 Z-0.500 K3X5.159E-002 K2X-5.644E-002 K1X6.928E+000 ~\n"
              "  K3Y3.753E-002 K2Y-2.644E-002 K1Y6.910E+000 ~\n  K3Z0.000E+000 K2Z0.000E+000 K1Z0.000E+000")


def test_spline_blocks_follow_their_polynomials():
    """X(t) = K3X t^3 + K2X t^2 + K1X t + X, t from 1 to 0 (iTNC 530 user's manual, "Spline interpolation"): every
    chord end lies on the curve, the chords stay within 1 um of it, and the block ends at its end point."""
    prog = run(MANUAL_SPL, exact=False)  # the reference checks each block's end (its last chord)
    second = [b for b in prog.blocks if b.line == 6]  # the second SPL block
    assert len(second) > 2 and ends(prog)[-1] == [17.952, 9.003, -0.5]
    k = np.array([[5.159e-2, -5.644e-2, 6.928], [3.753e-2, -2.644e-2, 6.910]])
    end = np.array([17.952, 9.003])

    def curve(t):
        t = np.asarray(t, float)[:, None]
        return k[:, 0] * t**3 + k[:, 1] * t**2 + k[:, 2] * t + end

    t = np.linspace(1.0, 0.0, 4001)
    dense = curve(t)
    for b in second:  # each chord end on the curve: its nearest dense point within the sampling step
        assert np.min(np.linalg.norm(dense - b.target[:2], axis=1)) < 2e-3
    for b in second:  # the curve between the chord's ends lies within 1 um of the chord
        a, c = b.start[:2], b.target[:2]
        u = (c - a) / np.linalg.norm(c - a)
        inside = dense[(np.dot(dense - a, u) > 0) & (np.dot(dense - c, u) < 0)]
        d = inside - a
        off = np.abs(u[0] * d[:, 1] - u[1] * d[:, 0])  # distance from the chord's line
        assert off.size == 0 or off.max() <= 1.0e-3 + 1e-9
    assert [b.exact_stop for b in second] == [False] * (len(second) - 1) + [True]
    assert all(math.isclose(b.feed * 60, 10000.0) for b in second)


@pytest.mark.parametrize("body, words", [
    ("L X+1 Y+0 Z+0 R0 FMAX\nSPL X+0 Y+0 Z+0 K3X+0 K2X+0 K1X+1.01 K3Y+0 K2Y+0 K1Y+0 K3Z+0 K2Z+0 K1Z+0 F100",
     "SPL starts 0.0100 mm (in one axis) from the end of the previous element"),
    ("L X+1 Y+0 Z+0 R0 FMAX\nSPL X+0 Y+0 K3X+0 K2X+0 K1X+1 F100", "axis Y without its end point and K3Y, K2Y, K1Y"),
    ("L X+1 Y+0 Z+0 R0 FMAX\nSPL X+0 A+5 K3X+0 K2X+0 K1X+1 K3A+0 K2A+0 K1A+1 F100", "SPL with the axis A"),
    ("TOOL DEF 1 L+0 R+2\nTOOL CALL 1 Z\nL X+1 Y+0 Z+0 RL F100\nSPL X+0 K3X+0 K2X+0 K1X+1", "SPL under RL/RR"),
])
def test_spline_errors(body, words):
    assert words in str(refused(body))


# --- FUNCTION FEED DWELL ---------------------------------------------------------------------------

def test_feed_dwell_stops_after_every_f_time_of_feed_motion():
    """TNC 640 user's manual, "Cyclic dwell time: FUNCTION FEED DWELL": D-TIME 0.5 s after every F-TIME 2 s of feed
    motion (here 20 mm at 600 mm/min), lines and arcs alike, not during rapids, until RESET."""
    prog = checked_program(program("L X+0 Y+0 Z+0 R0 F600\nFUNCTION FEED DWELL D-TIME0.5 F-TIME2\nL X+50\n"
                                   "CC X+25 Y+0\nC X+0 Y+0 DR+\nL Z+10 FMAX\nL Z+0 FMAX\nL X+10 F600\n"
                                   "FUNCTION FEED DWELL RESET\nL X+50"), CTX)
    dwells = [b for b in prog.blocks if b.kind == "dwell"]
    assert [b.dwell for b in dwells] == [0.5] * 6
    assert [np.round(b.target[:2], 9).tolist() for b in dwells[:2]] == [[20, 0], [40, 0]]
    arc = [b.segment for b in prog.blocks if b.kind == "arc"]
    # 10 mm of the half circle (radius 25) after X50, then every 20 mm of it
    assert np.allclose([a.length for a in arc], [10.0, 20.0, 20.0, 20.0, 25 * math.pi - 70.0], rtol=0, atol=1e-9)
    assert np.allclose(dwells[2].target, arc[0].end) and np.allclose(arc[-1].end, [0, 0, 0])
    # the rapids do not count: 8.54 mm of arc + the 10 mm line stay below 20 mm, no dwell; after RESET none
    assert [(b.kind, b.target[0]) for b in prog.blocks[-3:]] == [("rapid", 0.0), ("line", 10.0), ("line", 50.0)]


def test_feed_dwell_on_lines_agrees_with_the_reference():
    """The same reading checked against the reference (lines only, the reference does not split arcs): F-TIME 1.5 s
    at F1200 (20 mm/s) is 30 mm of feed motion, counted across blocks and over an F change: X+50 is cut at X30, the
    20 mm left of it and the 10 mm of IY+10 end the count at Y10, then at F600 (10 mm/s) it is 15 mm: Y25, Y40,
    2 mm before the line ends at Y42; the rapid and the lines after RESET have no dwell."""
    prog = checked_program(program("L X+0 Y+0 Z+0 R0 F1200\nFUNCTION FEED DWELL D-TIME0.25 F-TIME1.5\nL X+50\n"
                                   "L IY+10\nL IY+32 F600\nL Z+5 FMAX\nFUNCTION FEED DWELL RESET\nL X+0 F1200"), CTX)
    dwells = [np.round(b.target, 9).tolist() for b in prog.blocks if b.kind == "dwell"]
    assert dwells == [[30, 0, 0], [50, 10, 0], [50, 25, 0], [50, 40, 0]]
    assert all(b.dwell == 0.25 for b in prog.blocks if b.kind == "dwell")
    assert [b.kind for b in prog.blocks[-2:]] == ["rapid", "line"]


def test_feed_dwell_errors():
    assert "malformed FUNCTION FEED DWELL" in str(refused("FUNCTION FEED DWELL D-TIME0.5"))
    assert "F-TIME > 0" in str(refused("FUNCTION FEED DWELL D-TIME0.5 F-TIME0"))


def test_m103_plunging_feed_follows_the_manuals_table():
    """TNC 410/426/430 user's manual, "Feed rate for plunging: M103": F500 M103 F20, then the contouring feeds 500,
    100 (Z-2.5), 141 (Y+5 Z-5), 500, 500 (Z up); M103 without F ends it."""
    prog = run("L X+0 Y+0 Z+0 R0 F500\nL X+20 Y+20 F500 M103 F20\nL Y+50\nL IZ-2.5\nL IY+5 IZ-5\nL X+50\nL Z+5\nM103\n"
               "L Z-5")
    assert [round(b.feed * 60, 3) for b in prog.blocks[1:]] == [500, 500, 100, 141.421, 500, 500, 500]


@pytest.mark.parametrize("block, note", [
    ("FN 19: PLC=+10/+20", "FN 19: values sent to the PLC (no motion)"),
    ("FN 29: PLC=+1/+2", "FN 29: values sent to the PLC (no motion)"),
    ("FN 37: EXPORT Q1", "FN 37: EXPORT (Q parameters are shared here) (no motion)"),
    ('FN 38: SEND /"DONE"', "FN 38: SEND of a text (no motion)"),
    ("FUNCTION LIFTOFF ANGLE TCS SPB+0 SPC+0", "FUNCTION LIFTOFF: the lift-off of the tool at an NC stop (no motion)"),
    ("FUNCTION S-PULSE P-TIME10 SCALE5", "FUNCTION S-PULSE: a pulsing spindle speed (no motion)"),
    ("FUNCTION COUNT INC", "FUNCTION COUNT: the machining counter (no motion)"),
    ("M138 B C", "M138: the rotary axes M128 takes (vcnc's M128 takes the kinematics' axes)"),
])
def test_functions_without_motion_are_noted(block, note):
    prog = checked_program(program("L X+5 Y+0 Z+0 R0 FMAX\n" + block + "\nL X+6 FMAX"), CTX, check=False)
    assert ends(prog) == [[5, 0, 0], [6, 0, 0]]
    assert note in prog.notes
