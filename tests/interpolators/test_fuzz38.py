"""What the fuzzers learned in session 38 (fuzz38): session 37's readings in the generators' programs.

``fanuc_generator`` writes tool length changes in G00/G01 blocks without Z, Z at its reference or a G53 Z followed by
an incremental or absolute Z (the length vector cancelled and restored), a length change inside a canned cycle
series, Fanuc M29 rigid taps and where they end, and Fanuc G02.4/G03.4 three-dimensional arcs; ``tnc_generator``
the PLANE forms PROJECTED, EULER, VECTOR, POINTS, AXIAL and SPATIAL with TABLE ROT/COORD ROT, turned or moved;
``linuxcnc_fuzz`` G28.1/G30.1, G92.1-G92.3 and G4 P with axis words; ``setpoint_fuzz`` Fanuc CAM code with G06.2
NURBS and G02.4 arcs. Each generated program here is read by the reader and checked block by block against the
independent reference (``reference_iso``, ``reference_heidenhain``), or (setpoints) for the planner's invariants.
"""

from __future__ import annotations

import pytest

from benchmarks import linuxcnc_fuzz
from benchmarks.setpoint_fuzz import fanuc_cam_program, run_case
from interpolators import parse_program
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators import tnc_generator
from tests.interpolators.fanuc_generator import context, features, generate
from tests.interpolators.reference_heidenhain import heidenhain_reference
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table

#: The sections fuzz38 added, a form each writes and the dialects that draw them.
SECTIONS = {"length_block": ("G0 G43 H", ("fanuc", "haas", "fadal")),
            "length_reference": ("G91 G28 Z0.", ("fanuc", "haas", "fadal")),
            "length_cycle": ("G43 H", ("fanuc", "haas", "fadal")),
            "rigid_tap_end": ("M29 S", ("fanuc",)),
            "arc3d": (".4 X", ("fanuc",))}


def _first_seeds(section: str, dialect: str, count: int) -> list[int]:
    """The first ``count`` seeds from 0 whose program draws ``section``."""
    out = [seed for seed in range(2000) if section in features(seed, dialect)][:count]
    assert len(out) == count, f"{dialect} programs draw {section} {len(out)} times in 2000 seeds"
    return out


@pytest.mark.parametrize(("section", "dialect"), [(s, d) for s, (_, ds) in SECTIONS.items() for d in ds])
def test_generated_programs_of_the_new_sections_match_the_reference(section, dialect):
    texts = []
    for seed in _first_seeds(section, dialect, 6):
        text, ctx = generate(seed, dialect), context(seed, dialect)
        match = match_blocks(iso_reference(text, ctx), reader_rows(*blocks_table(parse_program(text, context=ctx))))
        assert match.mismatch is None, (seed, match.mismatch)
        texts.append(text)
    assert SECTIONS[section][0] in "".join(texts)


def test_the_fanuc_programs_write_a_length_change_in_a_cycle_and_three_dimensional_arcs():
    text = "".join(generate(seed, "fanuc") for seed in _first_seeds("length_cycle", "fanuc", 6))
    assert any(line.startswith(("G43 H", "N")) and "G43 H" in line and " X" in line and "Z" not in line
               for line in text.splitlines())
    arcs = "".join(generate(seed, "fanuc") for seed in _first_seeds("arc3d", "fanuc", 6))
    assert "G02.4 " in arcs and "G03.4 " in arcs


def test_generated_tnc_plane_forms_match_the_reference():
    """The five-axis seeds' PLANE forms (tnc_generator.plane_definition), each read as the reference reads it."""
    forms, seed = set(), 0
    wanted = {"PROJECTED", "EULER", "VECTOR", "POINTS", "AXIAL", "TABLE ROT", "COORD ROT", "MOVE DIST"}
    while not wanted <= forms and seed < 20000:
        text = tnc_generator.generate(seed)
        new = {f for f in wanted - forms if f"PLANE {f}" in text or f in text and "PLANE" in text}
        if new:
            ctx = tnc_generator.context(seed)
            prog = parse_heidenhain(text, source="t.h", context=ctx)
            match = match_blocks(heidenhain_reference(text, ctx), reader_rows(*blocks_table(prog)))
            assert match.mismatch is None, (seed, match.mismatch)
            forms |= new
        seed += 1
    assert forms == wanted


def test_linuxcnc_programs_write_group_0_codes_with_axis_words():
    """G28.1/G30.1 with Z or X Y (SheetCAM's Mach3 plasma posts' "G28.1 Z3.00"), G92.1-G92.3 with X Y in G90 and a
    dwell with X: axis words LinuxCNC moves to by the modal motion (linuxcnc_diff compares them with rs274)."""
    text = "".join(linuxcnc_fuzz.generate(seed)[0] for seed in range(300))
    lines = text.splitlines()
    assert any(line.startswith(("G28.1 ", "G30.1 ")) for line in lines)
    assert any(line.startswith(("G90 G92.1 X", "G90 G92.2 X", "G90 G92.3 X")) for line in lines)
    assert any(line.startswith("G4 P0.2 X") for line in lines)


def test_fanuc_cam_programs_write_nurbs_and_three_dimensional_arcs():
    text = "".join(fanuc_cam_program(seed) for seed in range(6))
    assert "G06.2 P" in text and "G02.4 " in text and "G05.1 Q1" in text
    assert fanuc_cam_program(3) == fanuc_cam_program(3)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fanuc_cam_programs_keep_every_setpoint_invariant(seed):
    # as test_setpoint_fuzz: both profiles, random limits and sample time
    cases = run_case("fanuc_cam", seed)
    assert [(outcome, fails) for outcome, _, _, fails in cases if outcome != "ok"] == []
    assert len(cases) == 2
