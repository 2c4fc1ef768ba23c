"""The reference's faults fuzz37 found when tests/interpolators/fanuc_generator.py learned session 36's Haas forms
(``M99 P<n>`` inside a subprogram, ``G73 .. Q K``) and Fanuc/Haas tool length changes under G91: each program
hand-written, read by the reader and checked block by block against ``reference_iso``; and the generator's Fadal
programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.fanuc_generator import FADAL_FEATURES, context, features, generate
from tests.interpolators.iso_checks import checked_iso
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table

HAAS = MachineContext(dialect=DIALECTS["haas"])
FANUC = MachineContext(dialect=DIALECTS["fanuc"])

#: A Haas main program O00001 calling O01000 (Haas numbers programs O00001-O99999, ``M98 P1000`` calls O01000),
#: whose ``M99 P20`` branches past ``G00 X2.`` to its own N20; the main program holds an N20 too.
BRANCH = ("%\nO00001 (MAIN)\nG90 G17 G21\nG00 X0. Y0. Z10.\nM98 P1000\nN10 G00 X5.\nN20 G00 Y7.\nM30\n%\n"
          "O01000 (SUB)\nG00 X1.\nM99 P20\nG00 X2.\nN20 G00 Z-1.\nM99\n%\n")


def ends(text: str, context: MachineContext) -> list[list[float]]:
    return [[round(float(v), 9) for v in b.target] for b in checked_iso(text, context).blocks]


def test_haas_m99_p_in_a_subprogram_is_checked_by_the_reference():
    # Haas mill operator's manual 96-8000, "Macros", "Conditional Expressions": M99 P "branch[es] unconditionally to
    # any line in the current subroutine ... It does not return to the calling program". The reference had looked
    # for an "O1000" (not O01000) and, given one, returned to the caller's N20 as Fanuc does
    assert ends(BRANCH, HAAS) == [[0.0, 0.0, 10.0], [1.0, 0.0, 10.0], [1.0, 0.0, -1.0], [5.0, 0.0, -1.0],
                                  [5.0, 7.0, -1.0]]


def test_fanuc_m99_p_returns_to_the_callers_block_in_the_reference_too():
    # Fanuc B-64304EN "Subprogram", "Special usage": M99 P<n> returns to the calling program's N<n>
    assert ends(BRANCH, FANUC) == [[0.0, 0.0, 10.0], [1.0, 0.0, 10.0], [1.0, 7.0, 10.0]]


@pytest.mark.parametrize("count", [1, 2])
def test_haas_m99_p_branch_in_a_repeated_call(count):
    # the generator's form: a forward branch, then the subprogram's own M99 ends each of the L repetitions
    text = ("%\nO4001 (FUZZ)\nG21 G90 G0 X0. Y0. Z5.\nM98 P3500" + (f" L{count}" if count > 1 else "") +
            "\nG90 G0 X0. Y0.\nM30\nO3500 (BRANCH)\nG91 G1 X5. F500\nM99 P7000\nG1 Y40.\nN7000 G1 Y5.\nG90\nM99\n%\n")
    xy = [e[:2] for e in ends(text, HAAS)]
    assert xy[-2] == [5.0 * count, 5.0 * count]


def test_generated_fadal_programs_are_read_as_the_reference_reads_them():
    # fanuc_generator's fadal seeds (FADAL_FEATURES): Fadal G83 I J K and G73 Q K as Fusion's fadal.cps writes them,
    # tool length changes under G91, cycles, subprograms, G52/G92, rotation; none refused
    seen = set()
    for seed in range(40):
        text, ctx = generate(seed, "fadal"), context(seed, "fadal")
        match = match_blocks(iso_reference(text, ctx), reader_rows(*blocks_table(parse_program(text, context=ctx))))
        assert match.mismatch is None, (seed, match.mismatch)
        seen.update(features(seed, "fadal"))
    assert {"haas_peck", "haas_g73k", "length_motion"} <= seen <= set(FADAL_FEATURES)
