"""What session 36's review left of the ISO readings it added (session 37, iso37): Fanuc M29 rigid tapping, G95
without a spindle speed, Haas G254 with incremental moves, Fanuc G02.4/G03.4's two blocks, and LinuxCNC's refusal of
':' program numbers. Each program is written by hand for the test; the control's manual (or rs274, LinuxCNC's own
interpreter) gives the reading, and the independent reference (tests/interpolators/reference_iso.py) agrees."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.reference_iso import ReferenceError, iso_reference
from vcnc.errors import GCodeError

FANUC = MachineContext(dialect=DIALECTS["fanuc"])
HAAS = MachineContext(dialect=DIALECTS["haas"])
LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"])


def _refused(text: str, context: MachineContext, message: str, reference: str) -> None:
    """The reader refuses ``text`` with ``message`` and the reference with ``reference`` (regular expressions)."""
    with pytest.raises(GCodeError, match=message):
        parse_program(text, context=context)
    with pytest.raises(ReferenceError, match=reference):
        iso_reference(text, context)


def test_linuxcnc_refuses_an_iso_code_program_number():
    # rs274 (LinuxCNC 2.9's standalone interpreter) on "G21 / :1248 / G0 X1 / M2": "Bad character ':' used", at
    # line 2; O1248 it reads (o-code.adoc "Fanuc-Style Numbered Programs"). Before: read as O1248 under linuxcnc
    text = "G21\n:1248\nG0 X1\nM2\n"
    _refused(text, LINUXCNC, r":2:1: ':' before a program number .*rs274: \"Bad character ':' used\".*expected O1248",
             r"line 2: ':' refused under LinuxCNC")
    assert [b.target.tolist() for b in parse_program(text.replace(":", "O"), context=LINUXCNC).blocks] == [
        [1.0, 0.0, 0.0]]
    # Fanuc's ISO code reads ':' as O (B-64304EN "Program number"), as before
    assert [b.target.tolist() for b in parse_program(text, context=FANUC).blocks] == [[1.0, 0.0, 0.0]]
