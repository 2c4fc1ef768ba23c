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


# --- 2. LinuxCNC #<_feed>: the F number as written, whatever G20/G21 came since -----------------------------------

FEED_UNITS = "G21 G90 G94\nG1 X1 F600\nG20\nG1 X[#<_feed> / 1000]\nG94 F50\nG21\nG1 X[#<_feed> / 10]\nM2\n"


def test_linuxcnc_feed_parameter_keeps_the_number_across_a_change_of_units():
    # rs274 2.9.0~pre1: "(debug, #<_feed>)" after "F600" then G20 prints 600 (interp's feed_rate is the F as written;
    # the canon converted it to mm when it was set), after "F50" in inch then G21 prints 50: X 0.6 in, then X 5 mm;
    # the reader converted the number (23.62, 1270)
    ctx = MachineContext(dialect=DIALECTS["linuxcnc"])
    assert _ends(FEED_UNITS, ctx, 4) == [(15.24, 0.0, 0.0)]  # 0.6 in
    assert _ends(FEED_UNITS, ctx, 7) == [(5.0, 0.0, 0.0)]


def test_linuxcnc_feed_parameter_under_g95_is_the_feed_per_revolution():
    # rs274 2.9.0~pre1: "G95 S1000 M3 G1 X3 F0.01" then "(debug, #<_feed>)" prints 0.010000 (the reader: F x S, 10)
    text = "G21 G90 G95 S1000 M3\nG1 X1 F0.25\nG1 X[#<_feed> * 10]\nM2\n"
    assert _ends(text, MachineContext(dialect=DIALECTS["linuxcnc"]), 3) == [(2.5, 0.0, 0.0)]


# --- 3. The reference's new pieces, on hand-written inputs ---------------------------------------------------------

G66_PROGRAM = """G21 G90 G54 G0 X0. Y0. Z10.
G66 P9500 Z5. F100. L2
G0 X10.
Y5.
G67
G0 X0.
M30
O9500
G91 G1 Z-#26 F#9
G0 Z#26
G90
M99
"""


def test_reference_g66_calls_the_macro_after_each_move_until_g67():
    # Fanuc 0i-MD B-64304EN "Modal call (G66)": after X10. and after Y5. the macro runs twice (L2): down 5 and up
    # again; the G66 block and the G67 block call nothing, nor do the macro's own moves
    rows = iso_reference(G66_PROGRAM, _ctx("fanuc"))
    ends = [tuple(np.round(r.end - np.array(G54), 6)) for r in rows]
    down, up = (10.0, 0.0, 5.0), (10.0, 0.0, 10.0)
    assert ends == [(0.0, 0.0, 10.0), (10.0, 0.0, 10.0), down, up, down, up,
                    (10.0, 5.0, 10.0), (10.0, 5.0, 5.0), (10.0, 5.0, 10.0), (10.0, 5.0, 5.0), (10.0, 5.0, 10.0),
                    (0.0, 5.0, 10.0)]
    prog = parse_program(G66_PROGRAM, context=_ctx("fanuc"), source="t.nc")
    assert [tuple(np.round(b.target - np.array(G54), 6)) for b in prog.blocks if b.kind != "dwell"] == ends


def test_reference_work_offset_variables_write_the_offset_at_once():
    # Fanuc 0i-MD "System variables": #5241-#5243 G55 X Y Z, #7001.. G54.1 P1; a write to the system in force moves
    # the next block's end
    ctx = MachineContext(dialect=DIALECTS["fanuc"], work_offsets={"G54": G54, "G55": (0.0, 0.0, 0.0)})
    text = "G21 G90 G54 G0 X0. Y0. Z0.\n#5241=-100.\n#5242=#5241+20.\nG55 G0 X1. Y1.\n#5243=-50.\nG0 Z1.\n" \
           "#7001=5.\nG54.1 P1 G0 X0.\nM30\n"
    rows = iso_reference(text, ctx)
    assert np.allclose(rows[1].end, (-99.0, -79.0, -400.0))  # Z stays where G54 Z0 put it
    assert np.allclose(rows[2].end, (-99.0, -79.0, -49.0))
    assert np.isclose(rows[3].end[0], 5.0)


def test_reference_reads_the_modal_information():
    # Fanuc 0i-MD "System variables", "Modal information": after G1 in G17 G90 G21 G55, #4001 = 1, #4002 = 17,
    # #4003 = 90, #4006 = 21, #4014 = 55
    ctx = MachineContext(dialect=DIALECTS["fanuc"], work_offsets={"G55": (0.0, 0.0, 0.0)})
    text = "G21 G17 G90 G55 G0 X0. Y0. Z0.\nG1 X1. F100.\n#1=#4001\n#2=#4002\n#3=#4003\n#4=#4006\n#5=#4014\n" \
           "G1 X[#1+#5-55] Y[#2-17+#3-90] Z[#4-21]\nM30\n"
    rows = iso_reference(text, ctx)
    assert np.allclose(rows[-1].end, (1.0, 0.0, 0.0))
    prog = parse_program(text, context=ctx, source="t.nc")
    assert np.allclose(prog.blocks[-1].target, (1.0, 0.0, 0.0))
