"""ISO programs of the sixteenth wild round (issue 18, set /tmp/isowild16): programs of production machining centres
and their shops: Fusion 360 Fanuc/Haas posts, a Haas shop's Renishaw probing and helical thread milling macros, a
Mazak HCN shop's EIA macros (Keycult), a shop's macro B programs with G52 and local subprograms."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")

# a Mazak shop's block skip macro (SET_BSKIP_VARS.EIA): a variable set per skip level, reset on a '/n' line
SKIP_LEVELS = ("G21 G90 G17\n#22 = 900\n#[#22 + 1] = 1\n/1 #[#22 + 1] = 0\n#[#22 + 2] = 1\n/2 #[#22 + 2] = 0\n"
               "G1 X[10 + #901] Y[20 + #902] F100.\n/3 G1 Y5.\nM30\n")


def test_fanuc_optional_block_skip_levels_run_with_their_switches_off():
    # FANUC 0i-MF "Optional block skip" (the additional optional block skip option, /2-/9; /1 is /): with every
    # switch off each '/n' line runs, so #901 and #902 end at 0 and the last line's move is made
    prog = checked_iso(SKIP_LEVELS, FANUC)
    assert [b.target.tolist()[:2] for b in prog.blocks] == [[10.0, 20.0], [10.0, 5.0]]
    assert [b.line for b in prog.blocks] == [7, 8]


@pytest.mark.parametrize("context", [HAAS, LINUXCNC])
def test_a_skip_level_is_named_where_the_dialect_has_only_block_delete(context):
    with pytest.raises(GCodeError, match=r":4:1: '/1': optional block skip level 1 \(Fanuc's additional optional "
                                         r"block skip /2-/9\), which this dialect does not have \(--dialect fanuc "
                                         r"reads it\)"):
        parse_program(SKIP_LEVELS, context=context)


def test_block_delete_alone_still_runs_on_every_dialect():
    for context in (FANUC, HAAS, LINUXCNC):
        prog = checked_iso("G21 G90 G17\n/G1 X10. F100.\n/ G1 Y5.\nM30\n", context)
        assert prog.blocks[-1].target.tolist()[:2] == [10.0, 5.0]
