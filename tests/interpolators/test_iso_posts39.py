"""Constructs of more CAM posts and shop macros, read as their controls read them (session 39, posts39).

Each program is hand-written in the output style of the post or program named in its test; the posts were read,
not run."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.tilted import Kinematics, RotaryAxis
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"], tools={1: Tool(number=1, length=10.0, radius=1.0)})

#: The end of a program from keycult/mazak-hcn's Fusion post (mazak.cps, Mazak HCN-5000 with a pallet changer):
#: the parts count checked in a multi-line IF block before the final retract (its SWAP_PALLET.EIA macro has
#: IF [..] THEN / ELSE / ENDIF as well).
MAZAK_END = ("%\nO1001\nG17 G21 G40 G49 G80 G90 G94\n#3901 = 0\n#3902 = 5\nM6 T1\nS8000\nM3\nG54\n"
             "G90 G0 X10. Y10.\nG90 G0 G43 Z15. H1\nG1 Z-2. F300.\nG0 Z15.\n"
             "IF [#3902 EQ 0.] GOTO 99999\nIF [#3901 GE #3902] THEN\n  M30\nENDIF\n"
             "N99999\nG90 G53 G0 Z0. M5 M9\nM30\n%\n")


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_a_multi_line_if_block_is_refused_not_run_whatever_its_condition(dialect):
    # "IF [#3901 GE #3902] THEN" alone on its line opens a block closed by ENDIF (Mazak EIA macros). Before: read
    # as an empty one-line THEN, so the M30 inside the false block ended the program before its final retract
    # (the G53 Z0. move lost, no error)
    context = MachineContext(dialect=DIALECTS[dialect], tools={1: Tool(number=1, length=10.0, radius=1.0)})
    with pytest.raises(GCodeError, match=r":15:20: IF \[\.\.\] THEN with nothing after THEN: the start of a "
                                         r"multi-line IF \.\. ELSE \.\. ENDIF block"):
        parse_program(MAZAK_END, context=context)
    # the one-line form stays: THEN and one macro statement
    prog = parse_program(MAZAK_END.replace("THEN\n  M30\nENDIF\n", "THEN #100 = 1\n"), context=context)
    assert prog.blocks[-1].line == 17  # the final G53 Z0. retract


#: Keycult's Mazak HCN post (keycult/mazak-hcn post-processor/mazak.cps, a fork of Fusion's mazak.cps): the
#: machining mode of an operation, "G61.1 P<level>", back to cutting mode with G64.
MAZAK_G61_1 = ("G21 G90 G17\nG54\nG61.1 P2\nG0 X0. Y0. Z5.\nG1 Z-1. F500.\nX10.\nY10.\nX0.\nG64\nG1 Y0.\n"
               "G0 Z5.\nM30\n")


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_mazak_g61_1_geometry_compensation_is_a_continuous_path(dialect):
    # Mazak VORTEX i-series manual, 5 Supplement, "G-code (Group13)", "A. Geometry compensation": G61.1 reduces
    # geometry errors with pre-interpolation acceleration/deceleration, feedforward and optimum corner
    # deceleration; it is no exact stop. Fanuc and Haas define no G61.1. Before: read as LinuxCNC's G61.1, exact
    # stop mode: every block of the operation ended at rest, without a note
    prog = parse_program(MAZAK_G61_1, context=MachineContext(dialect=DIALECTS[dialect]))
    assert not any(b.exact_stop for b in prog.blocks if b.line in (5, 6, 7, 8))
    assert "G61.1 geometry compensation (Mazak): continuous path, as G64 (P2: its level, not modelled)" in prog.notes
    # under linuxcnc G61.1 stays LinuxCNC's exact stop mode (without the Mazak P)
    prog = parse_program(MAZAK_G61_1.replace(" P2", ""), context=MachineContext(dialect=DIALECTS["linuxcnc"]))
    assert all(b.exact_stop for b in prog.blocks if b.line in (5, 6, 7, 8))


@pytest.mark.parametrize("dialect", ["fanuc", "linuxcnc"])
def test_a_centroid_m_code_with_an_axis_argument_is_named(dialect):
    # swissi2000's Fusion post for Centroid CNC12 (centroid.cps, property resetRotary) ends with "M26/A" and
    # "G92 A0". Before: "'/' after the word 'M26': arithmetic on a word's value needs brackets (M[.../])", which
    # names no Centroid form
    text = "G21 G90\nG0 X0. Y0. Z5.\nM5\nM26/A\nG92 A0\nM30\n"
    with pytest.raises(GCodeError, match=r":4:4: 'M26/A': an M code with an axis after '/', Centroid CNC12's form"):
        parse_program(text, context=MachineContext(dialect=DIALECTS[dialect], extra_axes=("a",)))
    # a '/' and a number after a word stays the bracket hint
    with pytest.raises(GCodeError, match=r"'/2' after the word 'X1\.': arithmetic on a word's value needs brackets"):
        parse_program("G21 G90\nG0 X1./2\nM30\n", context=MachineContext(dialect=DIALECTS[dialect]))


#: Fusion's mazak.cps (Autodesk 2023, OpenPostProject/mazak): the tilted plane, then "G53.1 P1" when the first
#: rotary axis' angle is positive, "P2" when negative. A/C trunnion: A tilts about X, C turns the table.
MAZAK_TILT = ("G90 G94 G17 G49\nG21\nT1 M6\nG54\nG69\nG68.2 X0. Y0. Z0. I0. J30. K0.\nG53.1 P1\nG0 X0. Y0.\n"
              "G43 Z50. H1\nG1 Z5. F500.\nG1 X10. F1000.\nG0 Z50.\nG49\nG69\nM30\n")
AC_TABLE = MachineContext(kinematics=Kinematics(axes=(RotaryAxis(name="a", limits=(-120.0, 120.0)),
                                                      RotaryAxis(name="c"))),
                          extra_axes=("a", "c"), dialect=DIALECTS["fanuc"], tools={1: Tool(number=1, length=10.0)})


def test_mazak_g53_1_p_that_asks_for_the_other_rotary_solution_is_refused():
    # G68.2 I0 J30 K0 (Euler ZXZ: 30 deg about X) is reached with A+30 C0 or A-30 C180; FANUC's rule (the master
    # axis' smallest move from A0 C0, then the tie to the positive master angle) takes A+30. Before: the P of
    # "G53.1 P2" was dropped without a word and the part was machined with A+30 C0, not A-30 C180
    prog = parse_program(MAZAK_TILT, context=AC_TABLE)
    assert prog.blocks[0].extra_target[0] == pytest.approx(30.0)
    assert "G53.1 P1: the solution with a positive A (Mazak), as FANUC's rule took it" in prog.notes
    with pytest.raises(GCodeError, match=r":7:7: G53.1 P2: the solution with a negative A .*vcnc took A\+30 C\+0 "
                                         r"at the G68.2"):
        parse_program(MAZAK_TILT.replace("P1", "P2"), context=AC_TABLE)
    with pytest.raises(GCodeError, match=r":7:7: G53.1 P3: P1 or P2"):
        parse_program(MAZAK_TILT.replace("P1", "P3"), context=AC_TABLE)
    # without P, FANUC's G53.1 as before
    assert parse_program(MAZAK_TILT.replace(" P1", ""), context=AC_TABLE).blocks[0].extra_target[0] == pytest.approx(30)


def test_a_block_delete_goto_that_runs_is_noted():
    # keycult's Mazak post (mazak.cps, BlockSkipController.writeSkip): "/<level> GOTO <n>" skips the work of a
    # fixture whose block delete switch is off. The branch runs (vcnc's switch is off); before: the lines of NC words
    # that started with '/' were noted, a macro statement's were not
    prog = parse_program("G21 G90\nG0 X1. Y1. Z1.\n/1 GOTO 2\nG0 X2.\nN2\nG0 X3.\nM30\n", context=FANUC)
    assert [b.line for b in prog.blocks] == [2, 6]
    assert "/ block delete lines run (switch off)" in prog.notes


@pytest.mark.parametrize(("block", "column", "word"), [("S5000 M3 M8 P0 R20.", 13, "word P with M7/M8"),
                                                       ("S5000 M3 M8 E12.", 13, "word 'E12.' outside M66-M68")])
def test_tormach_smartcool_words_are_named(block, column, word):
    # Fusion's tormach.cps with "SmartCool equipped": "M8 P0 R<sweep>" (side milling), "M8 E<top of part>"
    # (drilling), PathPilot's nozzle positions. Before: P was named as the Snapmaker firmware's M3 spindle power,
    # E12 as a Fadal fixture offset
    text = f"G21 G90\nG0 X1 Y1 Z1\n{block}\nG0 X2\nM30\n"
    with pytest.raises(GCodeError, match=rf":3:{column}: {word}.*Tormach PathPilot's SmartCool nozzle"):
        parse_program(text, context=MachineContext(dialect=DIALECTS["linuxcnc"]))
