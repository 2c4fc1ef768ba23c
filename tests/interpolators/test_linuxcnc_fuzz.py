"""vcnc's ``linuxcnc`` dialect against LinuxCNC's own interpreter on generated programs: the differences that
``benchmarks/linuxcnc_diff.py --generate`` (programs of ``benchmarks/linuxcnc_fuzz.py``) found, shrunk to a few
lines. The expected end points are rs274 2.9.0~pre1 output (the Debian package linuxcnc-uspace, ``rs274 -g``)
written out (STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED end points, G21: mm), so that the tests need no rs274.
"""

from __future__ import annotations

from benchmarks.linuxcnc_fuzz import FEATURES, generate
from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext

LINUXCNC = MachineContext(dialect=DIALECTS["linuxcnc"], linear_units="inch", extra_axes=("a", "b", "c"))


def _ends(prog) -> list[tuple]:
    return [(b.kind, *(round(float(v), 4) + 0.0 for v in b.target)) for b in prog.blocks if b.kind != "dwell"]


def test_g89_feeds_out_to_the_clear_level():
    """LinuxCNC's G89 feeds out to the clear level (interp_cycles.cc ``convert_cycle_g89``: ``cycle_feed`` to
    ``clear_z``; g-code.adoc G89: "Retract the Z-axis at the current feed rate to clear Z"), with G98 the
    initial level, not to R and a rapid on. rs274 2.9.0~pre1: STRAIGHT_TRAVERSE(5, 5, 10), (5, 5, 2),
    STRAIGHT_FEED(5, 5, -3), STRAIGHT_FEED(5, 5, 10), then the same at X10."""
    prog = parse_program("G21 G17 G90\nG0 X0 Y0 Z10\nM3 S1000\nG98 G89 X5 Y5 R2 Z-3 P0.5 F100\nX10\nG80\nM2\n",
                         context=LINUXCNC)
    hole = [("rapid", 5.0, 5.0, 10.0), ("rapid", 5.0, 5.0, 2.0), ("line", 5.0, 5.0, -3.0), ("line", 5.0, 5.0, 10.0)]
    second = [(k, 10.0 if x == 5.0 else x, y, z) for k, x, y, z in hole]
    assert _ends(prog) == [("rapid", 0.0, 0.0, 10.0), *hole, *second]


def test_g89_under_fanuc_still_feeds_out_to_r():
    """The Fanuc dialect keeps its G89: feed out to R, then a rapid to the initial level (G98)."""
    fanuc = MachineContext(dialect=DIALECTS["fanuc"])
    prog = parse_program("G21 G17 G90\nG0 X0 Y0 Z10\nM3 S1000\nG98 G89 X5 Y5 R2 Z-3 P500 F100\nG80\nM30\n",
                         context=fanuc)
    assert _ends(prog)[-2:] == [("line", 5.0, 5.0, 2.0), ("rapid", 5.0, 5.0, 10.0)]


def test_the_generator_is_reproducible_and_vcnc_reads_its_programs():
    """The same seed gives the same program; every feature group's programs are read by vcnc's linuxcnc
    dialect without an error (rs274 accepts them too: ``linuxcnc_diff.py --generate``)."""
    assert generate(7) == generate(7)
    assert generate(7)[0] != generate(8)[0]
    for k, group in enumerate(FEATURES):
        text, used = generate(100 + k, features=(group,))
        assert set(used) == {group}
        assert parse_program(text, context=LINUXCNC).blocks
