"""Findings of the session 40 fuzz runs (fuzz40): the ISO fuzz generators now write work offset variables, Haas
``IF .. THEN`` moves, Fanuc peck rigid tapping, ``G66`` modal calls and ``G93`` inverse time; each real failure
they found, and each reference fault, has a hand-written input here."""

from __future__ import annotations

import numpy as np

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.reference_iso import iso_reference

G54 = (-300.0, -200.0, -400.0)


def _ctx(dialect: str) -> MachineContext:
    return MachineContext(dialect=DIALECTS[dialect], work_offsets={"G54": G54})


def _ends(text: str, context: MachineContext, line: int) -> list[tuple[float, ...]]:
    prog = parse_program(text, context=context, source="t.nc")
    return [tuple(round(float(v), 6) for v in b.target) for b in prog.blocks if b.line == line]


# --- 1. Fanuc/Haas #5201-#5203: the external work offset written by a macro ----------------------------------------

EXTERNAL = "G21 G90 G54 G0 X0. Y0. Z0.\n#5201=10.\n#5202=-5.\n#5203=2.5\nG0 X1. Y1. Z1.\n#5201=0.\nG0 X1.\nM30\n"


def test_external_offset_variable_write_shifts_every_system():
    # Fanuc 0i-MD B-64304EN "System variables": #5201-#5206 the external workpiece zero point offset, read/write; it
    # adds to every workpiece system as G10 L2 P0 does: X 1 + 10 - 300, Y 1 - 5 - 200, Z 1 + 2.5 - 400; the reader
    # refused the write as read-only
    for dialect in ("fanuc", "haas"):
        assert _ends(EXTERNAL, _ctx(dialect), 5) == [(-289.0, -204.0, -396.5)]
        assert _ends(EXTERNAL, _ctx(dialect), 7) == [(-299.0, -204.0, -396.5)]


def test_reference_takes_the_external_offset_variable_as_g10_l2_p0():
    rows = iso_reference(EXTERNAL, _ctx("fanuc"))
    assert np.allclose(rows[0].end, (-300.0, -200.0, -400.0))
    assert np.allclose(rows[1].end, (-289.0, -204.0, -396.5))
    assert np.allclose(rows[2].end, (-299.0, -204.0, -396.5))
