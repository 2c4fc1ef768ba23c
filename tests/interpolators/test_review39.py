"""Defects found by session 39's review of its merged changes (review39); each input is hand-written and its expected
values are those LinuxCNC's ``rs274`` (2.9.0~pre1, ``rs274 -g``) prints for it."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])


@pytest.mark.parametrize(("series_end", "expected"), [("G80", "800.000000"), ("G80 G21", "800.000000"),
                                                        ("G1 X2", "10.000000")])
def test_motion_mode_reads_800_after_g80(series_end, expected):
    # rs274: "G20 G0 X0 / G1 X1 F10 / G81 X1 Y1 Z-0.1 R0.1 / G80 / (DEBUG, #<_motion_mode>)" prints 800 (G80 leaves no
    # motion mode, interp_namedparams.cc NP_MOTION_MODE); the reader keeps the G1 before the series for its own
    # rules and printed 10
    text = f"G20 G0 X0\nG1 X1 F10\nG81 X1 Y1 Z-0.1 R0.1\n{series_end}\n(DEBUG, #<_motion_mode>)\nM2\n"
    prog = parse_program(text, context=LINUXCNC, source="t.ngc")
    assert [m.text.strip() for m in prog.messages] == [expected]
