"""Canned-cycle details of session 38 (cycles38): Fadal cycles started below R, Fanuc peck rigid tapping, Haas
G12/G13 without Z, and the messages of Mazak's G05 P2 and Hurco's G75. Each input is hand-written."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.reference_iso import ReferenceError as IsoReferenceError
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks, reader_rows
from vcnc.commands.interpolate import blocks_table
from vcnc.errors import GCodeError


def _ctx(dialect: str) -> MachineContext:
    return MachineContext(dialect=DIALECTS[dialect])


def _targets(text: str, context: MachineContext) -> list[tuple[int, str, list[float]]]:
    prog = parse_program(text, context=context, source="t.nc")
    return [(b.line, b.kind, [round(float(v), 6) for v in b.target]) for b in prog.blocks]


def _matches(text: str, context: MachineContext) -> str | None:
    prog = parse_program(text, context=context, source="t.nc")
    return match_blocks(iso_reference(text, context), reader_rows(*blocks_table(prog))).mismatch


FADAL_BELOW_R = "G21 G90 G0 X0 Y0 Z0\nG99 G81 X5. Y0 Z-5. R2. F100.\nG80\nM30\n"


def test_fadal_cycle_started_below_r_moves_over_then_up_as_fanuc():
    # fuzz38's fadal seed 630376, minimal: the tool at Z0, R2.: over to the hole at Z0, then up to R (Fanuc's rule)
    moves = [m for m in _targets(FADAL_BELOW_R, _ctx("fadal")) if m[0] == 2]
    assert moves[0] == (2, "rapid", [5.0, 0.0, 0.0])
    assert moves[1] == (2, "rapid", [5.0, 0.0, 2.0])
    assert np.allclose(moves[2][2], [5.0, 0.0, -5.0])


def test_fadal_cycle_started_below_r_reference_agrees():
    assert _matches(FADAL_BELOW_R, _ctx("fadal")) is None


@pytest.mark.parametrize("dialect", ["fanuc", "haas"])
def test_g05_p2_is_refused_naming_mazaks_high_speed_machining_mode(dialect):
    # Keycult's Mazak HCN post: "Enables G5 P2 for this operation"
    text = "G21 G90 G0 X0 Y0 Z0\nG05 P2\nG1 X1. F100.\nG05 P0\nM30\n"
    with pytest.raises(GCodeError, match=r"t\.nc:2:.*G05 P2 is Mazak's high-speed machining mode"):
        parse_program(text, context=_ctx(dialect), source="t.nc")


@pytest.mark.parametrize("dialect", ["fanuc", "haas", "linuxcnc"])
def test_bare_g75_is_refused_naming_hurco_bnc(dialect):
    # Fusion's hurco.cps with its isnc property off writes "G75" (multi-quadrant arc mode) at the program start
    text = "G75\nG90 G0 X0 Y0 Z0\nM30\n"
    with pytest.raises(GCodeError, match=r"t\.nc:1:1: G75 .*Hurco's Basic NC \(BNC\)"):
        parse_program(text, context=_ctx(dialect), source="t.nc")


def test_g75_with_lathe_words_keeps_the_grooving_message():
    with pytest.raises(GCodeError, match="G75 lathe grooving cycle: not supported") as err:
        parse_program("G90 G0 X0 Y0 Z0\nG75 R1.\nM30\n", context=_ctx("fanuc"), source="t.nc")
    assert "Hurco" not in str(err.value)


HAAS_POCKET_AT_DEPTH = "G20 G90 G0 X0 Y0 Z0.1\nG1 Z-0.2 F10.\nG13 I0.5 F20.\nG0 Z1.\nM30\n"


def test_haas_g13_without_z_cuts_at_the_current_z():
    # Haas workbook 96-8000 "Circular pocket milling": single pass "Using I only"; the tool fed to Z-0.2 before
    moves = [m for m in _targets(HAAS_POCKET_AT_DEPTH, _ctx("haas")) if m[0] == 3]
    assert {m[1] for m in moves} == {"line", "arc"}
    assert all(np.isclose(m[2][2], -0.2 * 25.4) for m in moves)
    assert max(m[2][0] for m in moves) == pytest.approx(0.5 * 25.4)


def test_haas_g13_without_z_under_g91_repeats_at_the_current_z():
    text = "G20 G90 G0 X0 Y0 Z0.1\nG1 Z-0.2 F10.\nG91 G12 I0.5 L2 F20.\nG90 G0 Z1.\nM30\n"
    moves = [m for m in _targets(text, _ctx("haas")) if m[0] == 3]
    assert all(np.isclose(m[2][2], -0.2 * 25.4) for m in moves)
    assert sum(m[1] == "arc" for m in moves) == 4
    assert _matches(text, _ctx("haas")) is None


def test_haas_g13_without_z_reference_agrees():
    assert _matches(HAAS_POCKET_AT_DEPTH, _ctx("haas")) is None


def test_haas_g13_without_i_is_still_refused():
    with pytest.raises(GCodeError, match="no I word"):
        parse_program("G20 G90 G0 X0 Y0 Z0.1\nG13 Z-0.2 F20.\nM30\n", context=_ctx("haas"), source="t.nc")


RIGID_PECK = "G21 G90 G94 G0 X0 Y0 Z10.\nM29 S500\nG84 X5. Y0 Z-10. R2. Q2. F500.\nG80\nM30\n"


@pytest.mark.parametrize("code", ["G84", "G74"])
def test_fanuc_peck_rigid_tap_is_refused_by_name(code):
    # 0i-F "Peck rigid tapping cycle": Q the depth of each cut, PCP No. 5200#5 and d No. 5213 machine parameters
    with pytest.raises(GCodeError, match=rf"t\.nc:3:\d+: {code} .*with Q after M29: Fanuc's peck rigid tapping"):
        parse_program(RIGID_PECK.replace("G84", code), context=_ctx("fanuc"), source="t.nc")


def test_fanuc_floating_tap_with_q_notes_the_unused_q():
    prog = parse_program(RIGID_PECK.replace("M29 S500", "M3 S500"), context=_ctx("fanuc"), source="t.nc")
    assert any(n.startswith("G84 Q without M29 (Fanuc): the Q is not used") for n in prog.notes)
    tap = [b for b in prog.blocks if b.line == 3 and b.kind == "line"]
    assert [round(float(b.target[2]), 6) for b in tap] == [-10.0, 2.0]


def test_fanuc_rigid_tap_without_q_still_runs():
    prog = parse_program(RIGID_PECK.replace(" Q2.", ""), context=_ctx("fanuc"), source="t.nc")
    assert [round(float(b.target[2]), 6) for b in prog.blocks if b.line == 3 and b.kind == "line"] == [-10.0, 2.0]


def test_reference_refuses_the_peck_rigid_tap_too():
    with pytest.raises(IsoReferenceError, match="peck rigid tapping"):
        iso_reference(RIGID_PECK, _ctx("fanuc"))
