"""What the hand-written ISO program tests share: a program read and checked against the independent reference."""

from __future__ import annotations

from interpolators import parse_program
from interpolators.context import MachineContext
from interpolators.program import Program
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table


def checked_iso(text: str, context: MachineContext) -> Program:
    """The program, its interpreted blocks (``--blocks`` rows, the A-W axes it uses included) matched one by one
    against :func:`tests.interpolators.reference_iso.iso_reference`: no mismatch, and every row accounted for."""
    prog = parse_program(text, context=context)
    rows = reader_rows(*blocks_table(prog))
    match = match_blocks(iso_reference(text, context), rows)
    assert match.mismatch is None, match.mismatch
    assert match.exact + match.within == len(rows) > 0
    return prog
