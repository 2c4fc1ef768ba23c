"""Program.axes names every axis a block moves, also where the reader's own moves did it (simwild, session 27: a
Heidenhain CYCL CALL PAT drilled at X Y points the program never writes, and Program.axes was ('z',), so that
vcnc simulate ran Z only and reported no contour error without a word)."""

from __future__ import annotations

from interpolators import load_program, parse_program
from interpolators.program import program_axes

PATTERN = """\
0 BEGIN PGM PAT MM
1 TOOL CALL 1 Z S3000
2 L Z+10 R0 FMAX
3 PATTERN DEF ~
  POS1 (X+10 Y+10 Z+0) ~
  POS2 (X+40 Y+30 Z+0)
4 CYCL DEF 200 DRILLING ~
  Q200=2 ;SET-UP CLEARANCE ~
  Q201=-5 ;DEPTH ~
  Q206=150 ;FEED RATE FOR PLNGNG ~
  Q202=5 ;PLUNGING DEPTH ~
  Q210=0 ;DWELL TIME AT TOP ~
  Q203=+0 ;SURFACE COORDINATE ~
  Q204=10 ;2ND SET-UP CLEARANCE ~
  Q211=0 ;DWELL TIME AT DEPTH ~
  Q395=0 ;DEPTH REFERENCE
5 CYCL CALL PAT FMAX
6 END PGM PAT MM
"""


def test_a_pattern_of_holes_moves_x_and_y(tmp_path):
    path = tmp_path / "pat.h"
    path.write_text(PATTERN)
    prog = load_program(path)
    holes = {(b.target[0], b.target[1]) for b in prog.blocks if b.kind == "line"}
    assert holes == {(10.0, 10.0), (40.0, 30.0)}
    assert prog.axes == ("x", "y", "z")


def test_moved_axes_are_added_to_the_written_ones():
    prog = parse_program("G21 G90 G17\nG0 X5 Y0 Z1\nG2 X5 Y0 I-5 J0 F600\nM2\n")
    assert program_axes(set(), list(prog.blocks)) == ("x", "y", "z")
    full_circle = [b for b in prog.blocks if b.kind == "arc"]
    assert len(full_circle) == 1 and (full_circle[0].start == full_circle[0].target).all()
    # the full circle ends where it starts: its plane's axes count by its segment
    assert program_axes({2}, full_circle) == ("x", "y", "z")
    assert program_axes(set(), full_circle) == ("x", "y")
    assert program_axes({3}, []) == ("a",)
