"""Programs written for Fadal VMCs (``--dialect fadal``, :mod:`interpolators.iso_fadal`).

Sources: Fadal User Manual (April 2003) section 1 NC word summary ("E Fixture offset", "L Subroutine
definition or call") and section 6 "Fixed Subroutines" (L9101 probe, L9201 engraving); helmancnc.com "Fadal G
Codes M Codes Fixed Subroutines" (G4 P in milliseconds, G8/G9 feed ramps, G15, G51 ramp slope control); the
Fusion "Fadal" post processor (Format 1: ``G0 H<n> Z..``, ``H0 E0``; fixture n as ``E<n>`` or ``G<53+n>``;
cycle planes ``R0+<v>``; ``G84.2`` then ``G84.1`` for rigid tapping). The programs are hand-written in the
layout of Fadal shop programs.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool, work_offset_code
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.core.errors import InputError
from vcnc.engine.machine_file import parse_machine_text
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0), "G55": (300.0, 0.0, -20.0), "E7": (200.0, 10.0, -30.0)},
                     tools={n: Tool(number=n, length=10.0 * n, radius=0.5 * n) for n in range(1, 6)},
                     home=(0.0, 0.0, 100.0), dialect=DIALECTS["fadal"])

#: Subroutines 1 (two holes) and 2 (calls 1, then a third hole), the M30 that ends them, the main program.
SUBROUTINES = """N1 O12 (PLATE)
N2 L100
N3 X10. Y0.
N4 X20. Y0.
N5 M17
N6 L200
N7 L101
N8 X30. Y0.
N9 M17
N10 M30
N11 G0 G90 X0 Y0 E1
N12 H1 Z20.
N13 G98 G81 X0 Y0 Z-1. R2. F100. L0
N14 L202
N15 G80
N16 G0 Z20.
N17 M30
"""


def _parse(text: str, context: MachineContext = CTX):
    return parse_program(text, context=context)


def _reference_matches(text: str, context: MachineContext = CTX) -> str:
    """The reader's ``--blocks`` rows against the independent reference (tests/interpolators/reference_iso.py)."""
    return match_blocks(iso_reference(text, context), reader_rows(*blocks_table(_parse(text, context)))).mismatch


def test_dialect_reads_g4_p_in_milliseconds():
    """helmancnc.com's Fadal list: "G4 Dwell P= Time in Milliseconds"."""
    assert DIALECTS["fadal"].dwell_p_unit == "ms"
    prog = _parse("G21 G90 G0 X0 Y0 Z10.\nG4 P500\nM30\n")
    assert [b.dwell for b in prog.blocks if b.kind == "dwell"] == [0.5]


def test_fixture_offsets_e1_to_e48_and_e0():
    """E1-E6 are the table's G54-G59 (the Fusion post writes offset n as E<n> or G<53+n>), E7-E48 keys of their
    own, E0 no fixture offset: machine coordinates. The offset applies from the block it is on, also to the
    plain moves after it."""
    assert [work_offset_code(c) for c in ("E1", "E6", "E7", "E48")] == ["G54", "G59", "E7", "E48"]
    for bad in ("E0", "E49"):  # E0 is no offset: nothing to set
        with pytest.raises(InputError, match="unknown work offset"):
            work_offset_code(bad)
    with pytest.raises(InputError, match="given twice"):
        MachineContext(work_offsets={"E1": (0, 0, 0), "G54": (1, 0, 0)})
    prog = _parse("G21 G90 G0 X1. Y2. Z0 E1\nX1. Y2. E2\nX1. Y2. E7\nX1. Y2.\nE0 X1. Y2.\nX3. Y4.\nM30\n")
    assert [b.target.tolist() for b in prog.blocks] == [
        [101.0, 52.0, -20.0], [301.0, 2.0, -20.0], [201.0, 12.0, -20.0], [201.0, 12.0, -20.0], [1.0, 2.0, -20.0],
        [3.0, 4.0, -20.0]]
    assert "E0: no fixture offset (Fadal)" in prog.notes
    with pytest.raises(GCodeError, match=r":2:4: E49 is not a Fadal fixture offset.*expected E0 \(none\) or E1 .. E48"):
        _parse("G21\nG0 E49 X0\nM30\n")


def test_machine_file_keys_fadal_fixture_offsets():
    """A machine's [program] table: dialect = "fadal" and the fixture offsets E7 .. E48 by name."""
    text = (Path(__file__).resolve().parents[2] / "vcnc" / "machines" / "fadal-pid.toml").read_text()
    text += '\n[program]\ndialect = "fadal"\n\n[program.work_offsets]\nE1 = [1.0, 2.0, 3.0]\nE12 = [4.0, 5.0, 6.0]\n'
    context = parse_machine_text(text, file="f.toml", default_name="f").context
    assert context.dialect.name == "fadal"
    assert context.offset("G54").tolist() == [1.0, 2.0, 3.0]
    assert context.offset("E12").tolist() == [4.0, 5.0, 6.0]
    assert context.offset("E0").tolist() == [0.0, 0.0, 0.0]


def test_h_without_g43_applies_the_tool_length_and_h0_cancels_it():
    """Fadal Format 1 positions Z with ``G0 H<n> Z..`` (no G43) and cancels with ``H0`` (Fusion Fadal post)."""
    prog = _parse("G21 G90 G0 X0 Y0 E1\nH2 Z20.\nG1 Z-1. F100.\nG0 H0 Z0.\nM30\n")
    z = [b.target[2] for b in prog.blocks]
    assert z == pytest.approx([100.0, 20.0 - 20.0 + 20.0, -1.0 - 20.0 + 20.0, -20.0])
    assert "H without G43: the tool length applied (Fadal)" in prog.notes


def test_h_on_a_g41_block_names_the_diameter_offset():
    """Fadal Format 1 writes the cutter radius offset as H on the G41/G42 block (the Fusion post's dOutput)."""
    prog = _parse("G21 G90 G0 X-10. Y0 Z0 E1\nG1 G41 H4 X0 Y0 F100.\nY10.\nG40 X-10.\nM30\n")
    assert prog.blocks[1].target[0] == pytest.approx(100.0 - 2.0)  # tool 4: radius 2, left of +Y
    assert "H on a G41/G42 block: the diameter offset (Fadal Format 1), read as D" in prog.notes


def test_subroutines_before_m30_run_where_called():
    """L<nn>00 .. M17 define subroutine nn before the M30; the main program after it calls L<nn><rr>
    (subroutine nn, rr times). A cycle stored with L0 drills at each position of the subroutine."""
    prog = _parse(SUBROUTINES)
    holes = [(b.line, b.target[0] - 100.0) for b in prog.blocks if b.kind == "line" and b.target[2] < 0]
    # L202 runs subroutine 2 twice; each runs subroutine 1 (lines 3 and 4), then its own hole (line 8)
    assert holes == [(3, 10.0), (4, 20.0), (8, 30.0)] * 2
    assert 13 not in {b.line for b in prog.blocks if b.kind == "line"}  # L0: no hole at X0 Y0
    assert "Fadal subroutines defined before the M30; the main program runs after it" in prog.notes
    assert _reference_matches(SUBROUTINES) is None


@pytest.mark.parametrize(("text", "error"), [
    ("G21\nL100\nX0\nM17\n", r":2: subroutine definitions from L100 not ended by an M30"),
    ("G21\nL100\nX0\nL200\nM17\nM30\n", r":4: L200 opens subroutine 2 inside subroutine 1"),
    ("G21\nL100\nX0\nM30\n", r":4: M30 inside subroutine 1 \(no M17 closes it\)"),
    ("G21\nL100\nX0\nM99\nM30\n", r":4: M99 inside subroutine 1 \(no M17 closes it; M99 returns from an M98 "),
    ("G21\nL100\nX0\nM17\nG0 X1.\nL200\nM17\nM30\n", r":5: a block between Fadal subroutine definitions"),
    ("G21\nL100\nG0 X0\nM17\nM30\nL201\nM30\n", r":6:1: L201 calls subroutine 2, which is not defined"),
    ("G21 G0 X0 Z5.\nL9101 R1+1. Z-1.\nM30\n", r"Fadal R1 word .*: not supported"),
    ("G21 G0 X0 Z5.\nL9201 Z-1. F10.\nM30\n", r":2:1: Fadal fixed subroutine L9201 engraving \(Fadal User Manual "
                                              r"section 6\): not supported"),
    ("G21 G0 X0\nX1. L100\nM30\n", r":2:5: L100 opens a subroutine: definitions stand before the M30"),
    ("G21 G0 X0\nM17\nM30\n", r":2:1: M17 outside a subroutine definition"),
    ("G21\nL100\nL101\nM17\nM30\nL101\nM30\n", r"subroutine calls nested more than 10 deep"),
])
def test_subroutine_structure_errors_name_the_rule(text, error):
    with pytest.raises(GCodeError, match=error):
        _parse(text)


def test_fixed_subroutine_probe_is_refused_by_name():
    """Fadal User Manual section 6: "L9101 Probe"."""
    with pytest.raises(GCodeError, match=r"Fadal fixed subroutine L9101 probing"):
        _parse("G21 G0 X0 Z5.\nL9101 Z-1.\nM30\n")


def test_arc_with_l_runs_l_times():
    """``G91 G3 I-2. Z-0.2 L3``: the full circle with its helix step runs three times (a helix 0.6 deep);
    X/Y/Z alone in the modal G3 after it is a straight move (our reading)."""
    text = "G21 G90 G0 X0 Y0 Z0 E1\nG91 G1 X2. F200.\nG91 G3 I-2. Z-0.2 L3\nG3 I-2. L2\nX-2.\nG90 G0 Z20.\nM30\n"
    prog = _parse(text)
    arcs = [b for b in prog.blocks if b.kind == "arc"]
    assert [b.line for b in arcs] == [3, 3, 3, 4, 4]
    assert [round(b.target[2] + 20.0, 6) for b in arcs] == [-0.2, -0.4, -0.6, -0.6, -0.6]
    back = next(b for b in prog.blocks if b.line == 5)
    assert back.kind == "line" and back.target.tolist() == pytest.approx([100.0, 50.0, -20.6])
    assert _reference_matches(text) is None


def test_feed_ramp_and_tapping_codes():
    """G8/G9 and G51 ramp slope control change no path (noted); G84.2 sets rigid tapping up and G84.1 taps as
    G84; a cycle plane written ``R0+2.`` (Format 1, the Fusion post) is R2."""
    text = ("G21 G90 G0 X0 Y0 E1\nH1 Z20.\nG8\nG51 R0+1.5\nG84.2\nG98 G84.1 X5. Y0 Z-5. R0+2. F100. S100\n"
            "G80\nG50\nG9\nM30\n")
    prog = _parse(text)
    z = [round(b.target[2] + 10.0, 6) for b in prog.blocks]
    assert z == [110.0, 20.0, 20.0, 2.0, -5.0, 2.0, 20.0]  # program Z (tool 1: 10 mm, G54 Z -20); out to R
    for note in ("G8 feed ramps off (Fadal): path unchanged", "G51 ramp slope control (Fadal): feed ramps not "
                 "modelled, path unchanged", "G84.2 rigid tapping set-up (Fadal)", "G84.1 rigid tapping (Fadal) "
                 "run as G84"):
        assert note in prog.notes
    assert _reference_matches(text) is None


@pytest.mark.parametrize(("text", "error"), [
    ("G21\nG15 G3 Y1. Z0 A90.\nM30\n", r"G15 YZ circular interpolation with the A axis \(Fadal\): not supported"),
    ("G21\nG17.1\nM30\n", r"G17.1 A/B word swap \(Fadal\): not supported"),
    ("G21\nG0 X0\nG81 X0 Z-1. R1+2. F10.\nM30\n", r":3:13: Fadal R1 word"),
])
def test_fadal_codes_without_a_model_are_refused_by_name(text, error):
    with pytest.raises(GCodeError, match=error):
        _parse(text)


def test_other_dialects_point_at_fadal():
    """Under the Fanuc dialect E and L<nn>00 are refused naming ``--dialect fadal``; the fadal dialect reads
    the same program (no detection without being told)."""
    text = "G21\nG90 G0 X0 Y0 E1\nM30\n"
    with pytest.raises(GCodeError, match=r"E1-E48 select a Fadal fixture offset: use --dialect fadal"):
        _parse(text, dataclasses.replace(CTX, dialect=DIALECTS["fanuc"]))
    assert _parse(text).blocks[-1].target.tolist() == [100.0, 50.0, 100.0]


def test_command_line_dialect_fadal(tmp_path, capsys):
    from vcnc.cli import main

    program = tmp_path / "plate.nc"
    program.write_text(SUBROUTINES)
    blocks = tmp_path / "blocks.csv"
    assert main(["interpolate", str(program), "--dialect", "fadal", "--blocks", str(blocks),
                 "-o", str(tmp_path / "sp.csv")]) == 0
    lines = [int(row.split(",")[1]) for row in blocks.read_text().splitlines()[1:]]
    assert {3, 4, 8} <= set(lines)  # the subroutines' own lines
    assert re.search(r"interpolated", capsys.readouterr().out)
    assert np.isfinite(np.loadtxt(tmp_path / "sp.csv", delimiter=",", skiprows=1)).all()


def test_default_reading_names_dialect_fadal(tmp_path, capsys):
    """A Fadal program without --dialect: LinuxCNC's reading refuses it and the error names --dialect fadal
    (Fanuc, Haas and grbl refuse it too); nothing is read as Fadal without being told."""
    from vcnc.cli import main

    program = tmp_path / "plate.nc"
    program.write_text(SUBROUTINES)
    assert main(["interpolate", str(program), "-o", str(tmp_path / "sp.csv")]) == 2
    err = capsys.readouterr().err
    # the reader's own message names it ("a Fadal subroutine definition or call: use --dialect fadal"), and the
    # command adds no second hint (it adds "--dialect fadal: the program reads as that control's G-code" only to a
    # message naming no dialect)
    assert "use --dialect fadal" in err and err.count("--dialect") == 1
    assert not (tmp_path / "sp.csv").exists()


def test_g10_sets_fixtures_lengths_and_diameters():
    """helmancnc.com's Fadal list: G10 "L02= Fixture X, Y, Z, A, B, P= 0, 1-48", "L10= Length, P= 1-99, R0=
    Amount", "L12= Diameter, P= 1-99, R0= Amount" (R0 written with its sign, as the Fusion post writes R0)."""
    text = ("G21 G90 G10 L02 P2 X10. Y20. Z-5.\nG10 L10 P3 R0+12.5\nG10 L12 P3 R0+8.\nG0 X0 Y0 E2\nH3 Z0\n"
            "G1 G41 D3 X10. F100.\nG40 X20.\nM30\n")
    prog = _parse(text)
    assert prog.blocks[0].target.tolist() == [10.0, 20.0, 100.0]
    assert prog.blocks[1].target[2] == pytest.approx(-5.0 + 12.5)
    assert prog.blocks[2].target[1] == pytest.approx(20.0 + 4.0)  # radius 4 (diameter 8), left of the +X travel
    assert "G10 L12 R: a diameter (Fadal), half of it the radius" in prog.notes
    assert _reference_matches(text) is None
    with pytest.raises(GCodeError, match=r"G10 L02 P7-P48: setting Fadal fixture offsets E7-E48: not supported"):
        _parse("G21 G10 L02 P7 X1.\nM30\n")


def test_g45_to_g48_change_the_travel_by_the_h_offset():
    """helmancnc.com's Fadal list: G45 "Tool Length Offset Single Expansion", G46 "Single Reduction" (G47, G48
    double): Fanuc's tool position offsets (increase, decrease) by the value the H word names, not G43."""
    text = "G21 G90 G0 X0 Y0 Z0 E1\nG91 G45 X10. H1\nG46 Y10. H1\nG90\nM30\n"
    prog = _parse(text)
    assert [b.target[:2].tolist() for b in prog.blocks[1:]] == [[120.0, 50.0], [120.0, 50.0]]  # H1: 10 mm
    assert not any("H without G43" in n for n in prog.notes)
    assert _reference_matches(text) is None


def test_format_2_m98_subprograms_keep_their_l_count():
    """Format 2 is "Fanuc style" (Fusion Fadal post): an M98 P L call runs its O program L times, its L no
    Fadal subroutine call."""
    text = "O0001\nG21 G90 G0 X0 Y0 Z0 E1\nM98 P1000 L2\nG90\nM30\nO1000\nG91 G0 X1.\nM99\n"
    prog = _parse(text)
    assert [b.target[0] for b in prog.blocks] == [100.0, 101.0, 102.0]
    assert _reference_matches(text) is None
