"""The ISO reader's open questions of session 38, settled in session 39 (isoleft39): Fanuc peck rigid tapping from
the machine's PCP and d, a tool length change under tool centre point control, a canned cycle with its drilling axis
mirrored, and an arc or cutter compensation outside the G68 plane (Fanuc alarm 144). Each input is hand-written."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from interpolators.iso import parse_iso
from tests.interpolators.reference_iso import ReferenceError as IsoReferenceError
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from tests.interpolators.test_tcp5x import FANUC as FANUC_AC
from tests.interpolators.test_tcp5x import HAAS as HAAS_AC
from vcnc.commands.interpolate import blocks_table
from vcnc.commands.machines import PROGRAM_TABLE_DOC
from vcnc.core.errors import InputError, MachineError
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import GCodeError


def _ctx(dialect: str = "fanuc", **dialect_changes) -> MachineContext:
    return MachineContext(dialect=dataclasses.replace(DIALECTS[dialect], **dialect_changes),
                          tools={1: Tool(number=1, length=20.0, radius=3.0), 2: Tool(number=2, length=40.0)})


def _z_moves(text: str, context: MachineContext, line: int) -> list[tuple[str, float]]:
    prog = parse_program(text, context=context, source="t.nc")
    return [(b.kind, round(float(b.target[2]), 6)) for b in prog.blocks if b.line == line]


def _mismatch(text: str, context: MachineContext) -> str | None:
    prog = parse_iso(text, source="t.nc", context=context)
    return match_blocks(iso_reference(text, context), reader_rows(*blocks_table(prog))).mismatch


# --- 1. Fanuc peck rigid tapping (M29 S.. / G84 .. Q..) ----------------------------------------------------------

PECK = "G21 G90 G94 G0 X0 Y0 Z10.\nM29 S500\nG98 G84 X5. Y0 Z-7. R2. Q3. F500.\nX10.\nG80\nM30\n"


def test_high_speed_peck_rigid_tap_backs_off_d_after_each_cut():
    # PCP = 0, d = 1 mm: R 2, cuts to -1 and -4, each followed by 1 mm back, then to the bottom -7, out to R at the
    # tapping feed, and the rapid to the initial level (G98)
    moves = _z_moves(PECK, _ctx(peck_tapping="high-speed", peck_tapping_d=1.0), 3)
    assert moves == [("rapid", 10.0), ("rapid", 2.0), ("line", -1.0), ("line", 0.0), ("line", -4.0), ("line", -3.0),
                     ("line", -7.0), ("line", 2.0), ("rapid", 10.0)]


def test_standard_peck_rigid_tap_returns_to_r_and_comes_in_to_d_above_the_cut():
    # PCP = 1, d = 1 mm (the cutting start distance): after each cut back to R 2, in again to 1 mm above the depth cut
    moves = _z_moves(PECK, _ctx(peck_tapping="standard", peck_tapping_d=1.0), 3)
    assert moves == [("rapid", 10.0), ("rapid", 2.0), ("line", -1.0), ("line", 2.0), ("line", 0.0), ("line", -4.0),
                     ("line", 2.0), ("line", -3.0), ("line", -7.0), ("line", 2.0), ("rapid", 10.0)]


def test_the_series_keeps_q_and_a_retract_never_rises_above_r():
    # the second hole (line 4, no Q) pecks with the series' Q, as Fanuc keeps Q as modal hole data; d = 5 mm is more
    # than a cut: the high-speed retract stops at R
    moves = _z_moves(PECK, _ctx(peck_tapping="high-speed", peck_tapping_d=5.0), 4)
    assert [z for kind, z in moves if kind == "line"] == [-1.0, 2.0, -4.0, 1.0, -7.0, 2.0]


@pytest.mark.parametrize("kind", ["high-speed", "standard"])
@pytest.mark.parametrize("d", [0.0, 0.5, 5.0])
@pytest.mark.parametrize("text", [
    PECK,
    "G21 G90 G95 G0 X0 Y0 Z10.\nM29 S500\nG99 G74 X5. Y0 Z-6. R0. Q2. F1.\nG91 X10. Z-3.\nG80\nM30\n",
    "G20 G90 G94 G0 X0 Y0 Z1.\nM29 S500\nG98 G84 X.5 Y0 Z-.45 R.15 Q.1 F20.\nG80\nM30\n",
])
def test_peck_rigid_tap_reference_agrees(kind, d, text):
    assert _mismatch(text, _ctx(peck_tapping=kind, peck_tapping_d=d)) is None


def test_a_machine_that_states_no_pcp_still_refuses_naming_the_settings():
    with pytest.raises(GCodeError, match=r"t\.nc:3:\d+: .*peck rigid tapping.*expected \[program\] peck_tapping"):
        parse_program(PECK, context=_ctx(), source="t.nc")
    with pytest.raises(IsoReferenceError, match="peck rigid tapping"):
        iso_reference(PECK, _ctx())
    # a Q from the series' G83 makes the armed G84 a peck tap too
    series_q = ("G21 G90 G94 G0 X0 Y0 Z10.\nG98 G83 X0 Y0 Z-1. R2. Q3. F500.\nM29 S500\nG84 X5. Y0 Z-7. R2.\nG80\n"
                "M30\n")
    with pytest.raises(GCodeError, match=r"t\.nc:4:\d+: .*peck rigid tapping"):
        parse_program(series_q, context=_ctx(), source="t.nc")
    with pytest.raises(IsoReferenceError, match="peck rigid tapping"):
        iso_reference(series_q, _ctx())


def test_peck_rigid_tap_under_scaling_is_refused():
    text = PECK.replace("M29 S500", "G51 X0 Y0 Z0 P2.\nM29 S500")
    with pytest.raises(GCodeError, match=r"peck rigid tapping\) under G51 scaling"):
        parse_program(text, context=_ctx(peck_tapping="standard", peck_tapping_d=1.0), source="t.nc")


def test_the_machine_file_states_pcp_and_d(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndialect = "fanuc"\npeck_tapping = "standard"\n'
                    "peck_tapping_d = 0.8\n")
    ctx = load_machine(str(path)).context
    assert (ctx.dialect.peck_tapping, ctx.dialect.peck_tapping_d) == ("standard", 0.8)
    assert ctx.with_dialect("fanuc").dialect.peck_tapping_d == 0.8  # --dialect keeps the machine's setting
    assert "peck_tapping" in PROGRAM_TABLE_DOC and "peck_tapping_d" in PROGRAM_TABLE_DOC


@pytest.mark.parametrize("table", ['peck_tapping = "fast"\npeck_tapping_d = 1.0', 'peck_tapping = "standard"',
                                   'peck_tapping = "standard"\npeck_tapping_d = -1.0'])
def test_a_bad_peck_tapping_setting_names_the_key_and_the_file(tmp_path, table):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + f'\n[program]\ndialect = "fanuc"\n{table}\n')
    with pytest.raises(MachineError, match=r"'program\.peck_tapping(_d)?' (\[mm\] )?must be") as err:
        load_machine(str(path))
    assert "m.toml" in str(err.value)


def test_the_dialect_record_checks_the_pair():
    with pytest.raises(InputError, match="set together"):
        dataclasses.replace(DIALECTS["fanuc"], peck_tapping="high-speed")


# --- 3. A tool length change under G43.4 / G43.5 / G234 ----------------------------------------------------------

def _tcp(base: MachineContext) -> MachineContext:
    return dataclasses.replace(base, tools={1: Tool(number=1, length=20.0), 2: Tool(number=2, length=40.0)})


@pytest.mark.parametrize(("base", "code"), [(FANUC_AC, "G43.4"), (HAAS_AC, "G234"), (FANUC_AC, "G43.5")])
def test_a_new_length_under_tcp_travels_in_the_next_block(base, code):
    # G43 H1 Z5. puts the tip at Z5 with the 20 mm tool (machine Z 25); G43.4 H2 takes the 40 mm tool: the tip stays
    # programmed at Z5, so "G0 X2." ends at machine Z 45 (it stayed at 25, the new length never travelled)
    ctx = _tcp(base)
    text = f"G21 G90 G0 X0 Y0 Z0\nG43 H1 Z5.\n{code} H2\nG0 X2.\nG0 Z10.\nG49\nM30\n"
    prog = parse_iso(text, source="t.nc", context=ctx)
    ends = {b.line: b.target for b in prog.blocks}
    # the G54 preset (10, 5, 0) of test_tcp5x's machine
    assert ends[4] == pytest.approx([12.0, 5.0, 45.0]) and ends[5] == pytest.approx([12.0, 5.0, 50.0])
    assert _mismatch(text, ctx) is None


@pytest.mark.parametrize(("base", "code"), [(FANUC_AC, "G43.4"), (HAAS_AC, "G234")])
def test_an_h_alone_in_tcp_mode_is_that_codes_h(base, code):
    ctx = _tcp(base)
    text = f"G21 G90 G0 X0 Y0 Z0\n{code} H1\nG0 X1. Z5. A10.\nH2\nG1 X2. A20. F500.\nG0 Z10.\nG49\nM30\n"
    prog = parse_iso(text, source="t.nc", context=ctx)
    assert not any(n.startswith("H word without G43") for n in prog.notes)
    # line 6 "G0 Z10." from A20: the tip at Z10 with the 40 mm tool, seen through the table turned 20 deg
    lines = [b for b in prog.blocks if b.line == 6]
    tool_at_20 = parse_iso(text.replace("\nH2\n", "\n\n").replace(f"{code} H1", f"{code} H2"), source="t.nc",
                           context=ctx)
    assert lines[-1].target == pytest.approx([b for b in tool_at_20.blocks if b.line == 6][-1].target)
    assert _mismatch(text, ctx) is None


# --- 4. Cycles with the drilling axis mirrored; arcs and G41/G42 outside the G68 plane -----------------------------

@pytest.mark.parametrize("frame", ["G51.1 Z0", "G51 X0 Y0 Z0 I1000 J1000 K-1000"])
def test_a_cycle_with_its_drilling_axis_mirrored_is_refused(frame):
    # the hole would be drilled from R (mirrored to -2) up to +5
    text = f"G21 G90 G0 X0 Y0 Z10.\n{frame}\nG99 G81 X5. Y0 Z-5. R2. F100.\nG80\nG50.1 Z0\nG50\nM30\n"
    with pytest.raises(GCodeError, match=r"t\.nc:3:\d+: G81 drilling cycle with its drilling axis Z mirrored"):
        parse_program(text, context=_ctx(), source="t.nc")
    with pytest.raises(IsoReferenceError, match="drilling axis mirrored"):
        iso_reference(text, _ctx())


def test_a_cycle_mirrored_in_the_plane_still_runs():
    text = "G21 G90 G0 X0 Y0 Z10.\nG51.1 X0\nG99 G81 X5. Y0 Z-5. R2. F100.\nG80\nG50.1 X0\nM30\n"
    assert _z_moves(text, _ctx(), 3)[-2:] == [("line", -5.0), ("rapid", 2.0)]
    assert _mismatch(text, _ctx()) is None


@pytest.mark.parametrize("block", ["G2 X10. Z10. R10. F100.", "G2 I5. F100."])
def test_an_arc_outside_the_g68_plane_is_fanuc_alarm_144(block):
    text = f"G21 G90 G0 X0 Y0 Z10.\nG68 X0 Y0 R30.\nG18\n{block}\nG69\nM30\n"
    with pytest.raises(GCodeError, match=r"t\.nc:4:1: G02 arc in G18 while G68 rotates the G17 plane: .*alarm 144"):
        parse_program(text, context=_ctx(), source="t.nc")
    with pytest.raises(IsoReferenceError, match="alarm 144"):
        iso_reference(text, _ctx())
    # Haas: no Haas text found, the arc runs as chords in the turned plane as before
    chords = parse_program(text, context=_ctx("haas"), source="t.nc").blocks
    assert len([b for b in chords if b.line == 4 and b.kind == "line"]) > 10


def test_cutter_compensation_outside_the_g68_plane_is_fanuc_alarm_144():
    text = "G21 G90 G0 X0 Y0 Z10.\nG68 X0 Y0 R30.\nG18\nG41 D1 G1 X10. F100.\nZ5.\nG40 X0\nG69\nM30\n"
    with pytest.raises(GCodeError, match=r"cutter compensation \(G41/G42\) in G18 while G68 rotates the G17 plane"):
        parse_program(text, context=_ctx(), source="t.nc")
    with pytest.raises(IsoReferenceError, match="alarm 144"):
        iso_reference(text, _ctx())


def test_a_plane_code_in_g68_mode_alone_is_taken():
    # alarm 144 names the arc and the compensation, not the plane code: lines under G18 still turn in the XY plane
    text = "G21 G90 G0 X0 Y0 Z10.\nG68 X0 Y0 R30.\nG18\nG1 X5. F100.\nG17\nG69\nM30\n"
    prog = parse_program(text, context=_ctx(), source="t.nc")
    assert np.allclose([b.target for b in prog.blocks if b.line == 4][-1], [4.330127, 2.5, 10.0])
    assert _mismatch(text, _ctx()) is None
