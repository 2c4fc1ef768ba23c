"""An arc after a turn of at most LinuxCNC's ``small`` (TOLERANCE_CONCAVE_CORNER) under cutter compensation.

LinuxCNC queues such an arc from where the tool is, not from its offset start (interp_convert.cc
``convert_arc_comp2``, "convex, one arc needed": ``set_endpoint(cx, cy)``), and ``move_endpoint_and_flush``
(interp_queue.cc) measures its sweep from there when the next move is a line, an inside corner, G40 or the program
end: more than 0.001 rad (inch programs; 0.0254 rad in mm) over the programmed sweep is "Arc move in concave corner
cannot be reached by the tool without gouging". Into an arc at an outside corner it is flushed unchecked
(``dequeue_canons``).

Found by ``benchmarks/linuxcnc_diff.py --generate 3000 --seed 338100`` (seed 340802, "vcnc only"), shrunk by hand.
The outcomes are rs274's (LinuxCNC 2.9.0~pre1, ``rs274 -g``): two G3 arcs meeting at a turn of 1.2 deg, tool
right (G42.1, diameter 0.0825 in): the second arc starts 0.09 deg (0.0016 rad) before its offset start.
"""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from vcnc.core.errors import InputError

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])

HEAD = "G20 G17 G90 G40\nG0 X-2.4358 Y-2.7415 Z0.1145\nG1 F3.937\nG42.1 D0.0825\nG1 X-0.0583 Y-1.0745\n" \
       "G3 X1.2086 R1.0365\nG3 Y-0.2198 R0.5493\n"

#: What follows the second arc -> whether rs274 refuses the program.
TAILS = {
    "a line at an outside corner": ("G1 X-0.0583 Y-0.2198\nG40\nG0 X-2.5913 Y-2.9773\nM2\n", True),
    "a rapid under compensation": ("G0 X-2.5913 Y-2.9773\nM2\n", True),
    "G40": ("G40\nG0 X-2.5913 Y-2.9773\nM2\n", True),
    "the program end with compensation on": ("M2\n", True),
    "an arc at an outside corner": ("G3 X0.5 Y0.2 R2\nG1 X0 Y0.5\nG1 X-1 Y0.5\nG40\nG0 X-2.5913 Y-2.9773\nM2\n",
                                    False),
}


@pytest.mark.parametrize("name", list(TAILS))
def test_an_inch_arc_started_where_the_tool_is_gouges_as_in_rs274(name):
    tail, refused = TAILS[name]
    if refused:
        with pytest.raises(InputError, match=r"t\.ngc:7:.*Arc move in concave corner cannot be reached"):
            parse_program(HEAD + tail, context=LINUXCNC, source="t.ngc")
    else:
        assert parse_program(HEAD + tail, context=LINUXCNC, source="t.ngc").blocks


def test_the_same_program_in_mm_is_read():
    """In G21 the same numbers (mm) pass: the growth is under 0.0254 rad (rs274 runs it to the end)."""
    tail = TAILS["a line at an outside corner"][0]
    prog = parse_program((HEAD + tail).replace("G20", "G21"), context=LINUXCNC, source="t.ngc")
    assert prog.blocks[-1].kind == "rapid"

