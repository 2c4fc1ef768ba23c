"""Readings settled by the shopngc40 set of public LinuxCNC programs compared with LinuxCNC's ``rs274``
(``benchmarks/linuxcnc_diff.py``): machine configs' nc_files and subroutines (Probe Basic and gmoccapy machines,
tool-change and probing macros, plasma and lathe configs) and the questions session 39 left open. The snippets are
written for these tests after those programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"], extra_axes=("a", "b", "c"))


def _y_targets(text: str) -> list[float]:
    return [float(b.target[1]) for b in parse_program(text, context=LINUXCNC).blocks if b.kind == "rapid"]


def test_feed_reads_the_rate_of_the_last_inverse_time_move():
    # interp_inverse.cc inverse_time_rate_straight/_arc store length x F as the feed rate (#<_feed>,
    # interp_namedparams.cc): rs274 moves Y to 4 (2 mm x F2), to 47.1239 (the half circle of radius 5 x F3) and,
    # a rotary move alone, to 270 (90 deg x F3). Before: 100, the G94 F before the G93
    text = ("G21 G90 G0 X0 Y0 Z10\nG94 G1 X2 F100\nG0 Y#<_feed>\nG93 G1 X0 F2\nG0 Y#<_feed>\n"
            "G3 X10 I5 F3\nG0 Y#<_feed>\nG1 A90 F3\nG0 Y#<_feed>\nM2\n")
    assert _y_targets(text)[1:] == pytest.approx([100.0, 4.0, 5 * 3.141592653589793 * 3, 270.0])


def test_feed_before_the_first_inverse_time_move_and_after_g94():
    # G93 itself keeps the feed rate (interp_convert.cc convert_feed_mode); G94 clears it to 0; a later G93 reads
    # the new G94 F until its first move (rs274: Y 100, 0, 50), not an older G93 move's rate
    text = ("G21 G0 X0 Y0\nG1 X1 F100\nG93\nG0 Y#<_feed>\nG1 X3 F2\nG94\nG0 Y#<_feed>\nG1 X4 F50\nG93\n"
            "G0 Y#<_feed>\nM2\n")
    assert _y_targets(text)[1:] == pytest.approx([100.0, 0.0, 50.0])


def test_feed_reads_the_per_revolution_f_under_g95():
    # convert_feed_rate stores the F word itself under G95 (rs274: "S1000 M3 G95 G1 X1 F0.2" then Y#<_feed> moves to
    # Y 0.2). Before: 200, F x S
    text = "G21 G0 X0 Y0\nS1000 M3\nG95 G1 X1 F0.2\nG0 Y#<_feed>\nM2\n"
    assert _y_targets(text)[1:] == pytest.approx([0.2])


def test_feed_of_an_inverse_time_move_in_inch_is_in_inch():
    # the length is in program units: from X 10 mm (0.3937 in) to X 1 in at F2, rs274 1.2126 (inch)
    text = "G21 G0 X10 Y0\nG20 G93 G1 X1 F2\nG0 Y#<_feed>\nM2\n"
    assert _y_targets(text)[1:] == pytest.approx([(1 - 10 / 25.4) * 2 * 25.4])
