"""Defects found by session 39's review of its merged changes (review39); each input is hand-written and its expected
values are those LinuxCNC's ``rs274`` (2.9.0~pre1, ``rs274 -g``) prints for it."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.iso import parse_iso
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table

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


#: Fanuc peck rigid tapping (isoleft39) combined with the older features a shop program puts around it: the reader
#: and the independent reference (reference_iso) must agree on every move. Hand-written; d = 0.5 mm.
PECK_COMBINED = [
    "G21 G90 G94 G0 X0 Y0 Z10.\nM29 S500\nG91 G99 G84 X5. Z-9. R-8. Q3. K2 F500.\nG80\nG90\nM30\n",  # G91, K
    "G21 G90 G94 G0 X0 Y10. Z0\nG18\nM29 S500\nG98 G84 X5. Z0 Y-7. R2. Q3. F500.\nG80\nG17\nM30\n",  # along Y
    "G21 G90 G94 G0 X0 Y0 Z10.\nG68 X0 Y0 R30.\nM29 S500\nG98 G84 X5. Y0 Z-7. R2. Q3. F500.\nG80\nG69\nM30\n",
    "G21 G90 G94 G0 X0 Y0 Z10.\nG51.1 X0\nM29 S500\nG98 G74 X5. Y0 Z-7. R2. Q3. F500.\nG80\nG50.1 X0\nM30\n",
    "O1000\nG21 G90 G94 G0 X0 Y0 Z10.\nM98 P2000\nM30\nO2000\nM29 S500\nG98 G84 X5. Y0 Z-7. R2. Q3. F500.\nG80\n"
    "M99\n",
    "G21 G90 G94 G0 X0 Y0 Z10.\nG52 X10. Z1.\nM29 S500\nG99 G84 X5. Y0 Z-7. R2. P500 Q3. F500.\nX8.\nG80\n"
    "G52 X0 Z0\nM30\n",
    "G21 G90 G94 G0 X0 Y0 Z10.\nG43 H1 Z10.\nM29 S500\nG98 G84 X5. Y0 Z-7. R2. Q3. F500.\nG80\nG49\nM30\n",
]


@pytest.mark.parametrize("kind", ["high-speed", "standard"])
@pytest.mark.parametrize("text", PECK_COMBINED)
def test_peck_rigid_tap_with_older_features_agrees_with_the_reference(kind, text):
    context = MachineContext(dialect=dataclasses.replace(DIALECTS["fanuc"], peck_tapping=kind, peck_tapping_d=0.5),
                             tools={1: Tool(number=1, length=20.0)})
    prog = parse_iso(text, source="t.nc", context=context)
    assert sum(b.kind == "line" for b in prog.blocks) >= 5  # the pecks are there: more than the one stroke in, out
    assert match_blocks(iso_reference(text, context), reader_rows(*blocks_table(prog))).mismatch is None


@pytest.mark.parametrize("dialect", ["haas", "fanuc"])
def test_a_tapping_q_that_is_not_used_is_noted(dialect):
    # the lead, after review39: under haas a G84 Q ran as one stroke and the Q was dropped without a word (no Haas text
    # on a peck tap was found); under fanuc a Q without M29 was already noted. The tap runs in one stroke either way.
    text = "G21 G90 G17\nG0 X0 Y0 Z10.\nS500 M3\nG84 X5. Y5. Z-10. R2. Q3. F500.\nX10.\nG80\nM30\n"
    prog = parse_program(text, context=MachineContext(dialect=DIALECTS[dialect]), source="t.nc")
    assert any("Q" in n and "one stroke" in n for n in prog.notes)
    z = [round(float(b.target[2]), 6) for b in prog.blocks]
    assert z.count(-10.0) == 2  # one stroke to Z per hole, no peck levels between R and Z
    assert all(v in (10.0, 2.0, -10.0) for v in z)
