"""Session 33's review of the readers: the tool a cycle needing a radius names when it has none."""

from __future__ import annotations

import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from vcnc.errors import GCodeError

FACE = ("CYCL DEF 232 FACE MILLING ~\n Q389=+0 ~\n Q225=+0 ~\n Q226=+0 ~\n Q227=+2 ~\n Q386=+0 ~\n Q218=+60 ~\n"
        " Q219=+20 ~\n Q202=+2 ~\n Q369=+0 ~\n Q370=+1 ~\n Q207=+500 ~\n Q385=+500 ~\n Q253=+750 ~\n Q200=+2 ~\n"
        " Q357=+2 ~\n Q204=+50\n")


@pytest.mark.parametrize(("call", "named"), [
    ("", "no tool was called before it"),
    ("TOOL CALL 0 Z S3000\n", "tool 0 has none"),
    ("TOOL CALL 7 Z S3000\n", "tool 7 has none"),
    ('TOOL CALL "MILL_D10" Z S3000\n', 'tool "MILL_D10" (called by name, not in the tool table) has none'),
    # a TOOL CALL without a tool changes the spindle speed only: the tool stays
    ("TOOL CALL 7 Z S3000\nTOOL CALL Z S5000\n", "tool 7 has none"),
])
def test_face_milling_without_a_radius_names_the_active_tool(call, named):
    # before, no TOOL CALL at all and TOOL CALL 0 were both 'tool called by name has none'
    text = "0 BEGIN PGM T MM\n" + call + "L Z+50 R0 FMAX\n" + FACE + "CYCL CALL\nEND PGM T MM\n"
    with pytest.raises(GCodeError, match=r"cycle 232 FACE MILLING without a tool radius \(the stepover is Q370 x the "
                                         r"radius\); " + named.replace("(", r"\(").replace(")", r"\)") + r" \(got"):
        parse_heidenhain(text, source="t.h", context=MachineContext())
