"""ISO programs of the fifteenth wild round (issue 18, set /tmp/isowild15) and the first run of the old sets through
LinuxCNC's own interpreter (``benchmarks/linuxcnc_diff.py``, rs274 2.9.0~pre1): PCB programs of pcb-gcode, FlatCAM
and drl2gcode, a grbl pen plotter's examples, college mill programs, a LinuxCNC plasma table's macros, the sample
programs and sim configurations of a LinuxCNC fork with QtPlasmaC. Where ``linuxcnc`` ran what rs274 refuses it now
refuses it as rs274 does, or says so in a note; what rs274 runs, it runs."""

from __future__ import annotations

import math

import pytest

from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso

LINUXCNC = MachineContext().with_dialect("linuxcnc")


def test_i_j_alone_in_the_modal_g02_is_a_full_circle_under_linuxcnc():
    # a plotter's test program (isowild14 TEST_G90.NC): a helix of "X7.5Y0Z-1.I-7.5J0" blocks, then "I-7.5J0".
    # rs274 2.9.0~pre1 runs it (interp_internal.cc enhance_block: a block like "i1" in arc mode takes the modal
    # G2/G3): ARC_FEED back to the start about the centre, one clockwise turn. Checked by the reference.
    text = "G21 G17 G90 F100\nG0 X10 Y0 Z0\nG02 X10 Y0 Z-1 I-5 J0\nI-5 J0\nM2\n"
    prog = checked_iso(text, LINUXCNC)
    circle = prog.blocks[-1]
    assert (circle.kind, circle.line, circle.target.tolist()) == ("arc", 4, [10, 0, -1])
    assert circle.segment.center.tolist() == [5, 0, -1]
    assert circle.segment.sweep == pytest.approx(-2 * math.pi)
