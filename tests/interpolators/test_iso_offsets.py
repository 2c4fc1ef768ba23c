"""Additional work offsets (Fanuc G54.1 P, Haas G154 P / G110-G129), Fanuc/Haas G10 L2/L20 and the Fanuc
G52 local system, with end points worked out by hand from the controls' manuals (Fanuc 0i-MD B-64304EN
"Adding workpiece coordinate systems", "Changing workpiece coordinate system", "Local coordinate system";
Haas mill operator's manual "G154", "G10 Set Offsets")."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool, work_offset_code
from tests.interpolators.reference_iso import iso_reference
from tests.interpolators.reference_match import match_blocks
from vcnc.commands.interpolate import blocks_table
from vcnc.core.errors import InputError
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import GCodeError, MachineError

TABLE = {"G54": (100.0, 0.0, 0.0), "G55": (200.0, 0.0, 0.0), "G54.1 P2": (10.0, 20.0, -30.0),
         "G54.1 P48": (1.0, 2.0, 3.0), "G54.1 P300": (-5.0, 0.0, 0.0)}
FANUC = MachineContext(work_offsets=TABLE, dialect=DIALECTS["fanuc"])
HAAS = MachineContext(work_offsets={"G110": (10.0, 20.0, -30.0), "G154 P21": (0.0, 7.0, 0.0),
                                    "G154 P99": (0.0, 0.0, 9.0)}, dialect=DIALECTS["haas"])


def ends(text: str, context: MachineContext, *, reference: bool = True) -> list[tuple[float, ...]]:
    """End points [mm, machine] of the program's blocks, rounded to 1 nm; with ``reference`` also checked
    against the independent reference (:mod:`tests.interpolators.reference_iso`)."""
    prog = parse_program(text, context=context)
    if reference:
        _, rows = blocks_table(prog)
        match = match_blocks(iso_reference(text, context), [r + [0.0] * 6 for r in rows])
        assert match.mismatch is None, match.mismatch
        assert match.exact + match.within == len(rows)
    return [tuple(round(float(v), 6) + 0.0 for v in b.target) for b in prog.blocks]


def test_fanuc_g54_1_selects_the_table_entry_and_stays_modal():
    # X1 Y2 Z3 in P2 (10, 20, -30) -> (11, 22, -27); the next block stays in P2; P48 and P300 (the option)
    text = ("G21 G90\nG54.1 P2 G0 X1 Y2 Z3\nX0\nG54.1 P48 X0 Y0 Z0\nG54.1 P300 X0\nG54 X0\n")
    assert ends(text, FANUC) == [(11, 22, -27), (10, 22, -27), (1, 2, 3), (-5, 2, 3), (100, 2, 3)]


def test_fanuc_g54_p_is_g54_1_p_unless_the_p_is_another_word_s():
    # Fanuc "G54.1 Pn or G54 Pn"; G54 G04 P1000 dwells 1 s in G54; G54 M98 P.. calls (the P is M98's)
    assert ends("G21 G90\nG54 P2 G0 X1 Y2 Z3\nG54 X0\n", FANUC) == [(11, 22, -27), (100, 22, -27)]
    prog = parse_program("G21 G90\nG54 G04 P1000\nG0 X0\n", context=FANUC)
    assert [(b.kind, float(b.target[0]), b.dwell) for b in prog.blocks] == [("dwell", 0.0, 1.0), ("rapid", 100.0, 0.0)]
    with pytest.raises(GCodeError, match="word P needs G04"):
        parse_program("G21\nG54 P2\n", context=dataclasses.replace(FANUC, dialect=DIALECTS["linuxcnc"]))


def test_fanuc_g54_1_without_p_is_p1():
    ctx = dataclasses.replace(FANUC, work_offsets={"G54.1 P1": (4.0, 0.0, 0.0)})
    prog = parse_program("G21 G90\nG54.1\nG0 X1\n", context=ctx)
    assert prog.blocks[0].target[0] == pytest.approx(5.0)
    assert "G54.1 without P: P1" in prog.notes


def test_fanuc_g10_l20_sets_an_additional_offset_absolute_and_incremental():
    # G90 G10 L20 P3: the offset is the value; G91 G10 L20 P3 X1: added (X 5 -> 6); Y Z kept
    text = ("G21 G90\nG10 L20 P3 X5 Y6 Z7\nG54.1 P3 G0 X0 Y0 Z0\nG91 G10 L20 P3 X1\nG90 G0 X0\n"
            "G91 G10 L2 P1 Y-1\nG90 G54 X0 Y0 Z0\n")
    # G54 (100, 0, 0) moved by G91 G10 L2 P1 Y-1 -> (100, -1, 0)
    assert ends(text, FANUC) == [(5, 6, 7), (6, 6, 7), (100, -1, 0)]


def test_fanuc_g10_l2_sets_g54_to_g59_with_g90_values():
    assert ends("G21 G90\nG10 L2 P2 X50 Y60\nG55 G0 X1 Y1 Z0\n", FANUC) == [(51, 61, 0)]


def test_fanuc_additional_offset_system_variables():
    # #7001 + 20 (n - 1) + axis, n <= 48; #14001 + 20 (n - 1) + axis, n <= 300; #4014 54.1, #4130 = P
    text = ("G21 G90\nG54.1 P2\n#1 = #7021\n#2 = #7022\n#3 = #14023\n#4 = #4130\n#5 = #4014\n#6 = #7941\n"
            "#7 = #19981\nG53 G0 X#1 Y#2 Z#3\nG53 X#4 Y#5 Z[#6 + #7]\n")
    # (the reference reads no system variables)
    assert ends(text, FANUC, reference=False) == [(10, 20, -30), (2, 54.1, -4)]


def test_haas_g154_and_g110_to_g129_name_the_same_table():
    # G110 = G154 P1 (10, 20, -30); G154 P21 (0, 7, 0) has no G1xx alias; G129 = P20 (zero)
    text = "G21 G90\nG110 G0 X1 Y1 Z0\nG154 P1 X2\nG154 P21 X0 Y0 Z0\nG129 X0 Y0\nG154 P99 Z0\n"
    assert ends(text, HAAS) == [(11, 21, -30), (12, 21, -30), (0, 7, 0), (0, 0, 0), (0, 0, 9)]


def test_haas_g10_l20_and_macro_variables():
    # Haas "G10 L20 P2 G90 X100. Y80." sets G111 = G154 P2; #7021 (G111 X) and #14022 (G154 P2 Y)
    text = "G21 G90\nG10 L20 P2 X100 Y80\nG111 G0 X0 Y0\n#1 = #7021\n#2 = #14022\nG53 X#1 Y#2\n"
    assert ends(text, HAAS, reference=False) == [(100, 80, 0), (100, 80, 0)]
    assert ends("G21 G90\nG10 L20 P2 X100 Y80\nG111 G0 X0 Y0\n", HAAS) == [(100, 80, 0)]


def test_g92_shifts_every_system_additional_ones_included():
    # Fanuc: G92 in G54.1 P2 makes the position read the value and shifts G54-G59 and G54.1 alike.
    # At machine (11, 22, -27) = P2 (1, 2, 3): G92 X0 Y0 -> shift (1, 2); G54 X0 Y0 -> 100 + 1, 0 + 2
    text = "G21 G90\nG54.1 P2 G0 X1 Y2 Z3\nG92 X0 Y0\nG54 X0 Y0\nG54.1 P48 X0 Y0\n"
    assert ends(text, FANUC)[1:] == [(101, 2, -27), (2, 4, -27)]


def test_fanuc_g52_is_kept_apart_from_the_g92_shift():
    # G54 (100): at X10 G92 X0 shifts by 10; G52 X5 adds a local system on top (115); G52 X0 cancels
    # only it (111); G55 keeps the G92 shift (210). LinuxCNC's G52 replaces the same offset G92 set.
    text = "G21 G90 G54\nG0 X10\nG92 X0\nG52 X5\nG0 X0\nG52 X0\nG0 X1\nG55 X0\n"
    assert [p[0] for p in ends(text, FANUC)] == [110, 115, 111, 210]
    linuxcnc = dataclasses.replace(FANUC, dialect=DIALECTS["linuxcnc"])
    assert [p[0] for p in ends(text, linuxcnc)] == [110, 105, 101, 200]


def test_fanuc_g92_cancels_the_local_system_of_the_axes_it_names():
    # G52 X5 Y5, then at program X0 Y0 (machine 105, 5) G92 X0: X's local system is cancelled (the shift
    # alone makes X read 0), Y keeps its local 5: G52 X0 Y0 then cancels Y's local only -> X0 Y0 at (105, 0)
    text = "G21 G90 G54\nG52 X5 Y5\nG0 X0 Y0\nG92 X0\nG52 X0 Y0\nG0 X0 Y0\n"
    assert ends(text, FANUC) == [(105, 5, 0), (105, 0, 0)]


@pytest.mark.parametrize(("context", "text", "message"), [
    (MachineContext(), "G54.1 P1", "G54.1 P additional work offsets"),
    (MachineContext(), "G154 P1", "G154 P additional work offsets"),
    (FANUC, "G54.1 P301", "P301 is not an additional work offset number"),
    (FANUC, "G54.1 P1.5", "P1.5 is not an additional work offset number"),
    (HAAS, "G154 P100", "P100 is not an additional work offset number"),
    (FANUC, "G10 L20 P0 X1", "G10 L20 needs P1 .. P300"),
    (FANUC, "G10 L2 P7 X1", "G10 L2 needs P0 .. P6"),
    (FANUC, "G10 L2 P1 R45", "R .* is LinuxCNC's G10 L2 R"),
])
def test_bad_offset_words_are_named_errors(context, text, message):
    with pytest.raises(GCodeError, match=message):
        parse_program(f"G21\n{text}\n", context=context)


def test_work_offset_codes_of_the_table():
    assert [work_offset_code(c) for c in ("G54", "G59.3", "g54.1p7", "G154 P99", "G110", "G129")] == \
        ["G54", "G59.3", "G54.1 P7", "G54.1 P99", "G54.1 P1", "G54.1 P20"]
    for bad in ("G54.1 P301", "G154 P100", "G130", "G53"):
        with pytest.raises(InputError, match="unknown work offset"):
            work_offset_code(bad)
    with pytest.raises(InputError, match="given twice"):
        MachineContext(work_offsets={"G110": (0, 0, 0), "G154 P1": (1, 0, 0)})
    assert np.allclose(HAAS.offset("G154 P1"), (10, 20, -30))


def test_machine_file_reads_additional_offsets(tmp_path):
    base = builtin_machine_text("fadal-pid")  # a built-in machine without a [program] table
    path = tmp_path / "m.toml"
    path.write_text(base + '\n[program]\ndialect = "haas"\n[program.work_offsets]\nG110 = [1.0, 2.0, 3.0]\n'
                    '"G54.1 P5" = [4.0, 5.0, 6.0]\n')
    ctx = load_machine(str(path)).context
    assert np.allclose(ctx.offset("G154 P1"), (1, 2, 3)) and np.allclose(ctx.offset("G154 P5"), (4, 5, 6))
    path.write_text(base + '\n[program.work_offsets]\nG110 = [1.0, 2.0, 3.0]\n"G154 P1" = [0.0, 0.0, 0.0]\n')
    with pytest.raises(MachineError, match="same work offset"):
        load_machine(str(path))
    path.write_text(base + '\n[program.work_offsets]\nG130 = [1.0, 2.0, 3.0]\n')
    with pytest.raises(MachineError, match="unknown work offset"):
        load_machine(str(path))


@pytest.mark.parametrize("code", ["G92 X0 Y0", "G52 X5", "G54", "G54.1 P2", "G28 X0", "G53 G0 X0"])
def test_fanuc_refuses_coordinate_changes_under_a_g51_1_mirror(code):
    """Fanuc "Programmable mirror image", limitations: G27-G30 and the coordinate-system codes (G52 to G59,
    G92) must not be specified in mirror image mode: named errors, G50.1 first."""
    with pytest.raises(GCodeError, match="in programmable mirror image mode \\(G51.1\\)"):
        parse_program(f"G21 G90 G54\nG0 X10 Y10 Z0\nG51.1 X0\n{code}\n", context=FANUC)


def test_fanuc_g92_after_the_mirror_is_cancelled():
    # mirror about X0: X10 runs at program -10 (machine 90); G50.1 cancels it, the tool stays at machine
    # (90, 10), program (-10, 10); G92 X0 Y0 makes that the zero (shift -10, 10): X5 Y5 -> machine (95, 15)
    text = "G21 G90 G54\nG0 X0 Y10 Z0\nG51.1 X0\nX10\nG50.1 X0\nG92 X0 Y0\nX5 Y5\n"
    assert ends(text, FANUC) == [(100, 10, 0), (90, 10, 0), (95, 15, 0)]


@pytest.mark.parametrize(("units", "program_units", "want"), [("mm", "G21", 25.4), ("mm", "G20", 25.4),
                                                               ("inch", "G21", 1.0), ("inch", "G20", 1.0)])
def test_stored_offsets_read_in_the_machine_units_whatever_g20_g21(units, program_units, want):
    """LinuxCNC tests/interp/unit-conversion: the parameters behind the work and G92 offsets "stay constant
    because they are stored in user INI units". G54 X = 25.4 mm (1 inch), a G92 shift of 25.4 mm and tool 1's
    length 50.8 mm read in the machine's unit: X#5221, Y-#5211, Z#5403/2 (G53, mm: times 25.4 under G20)."""
    ctx = MachineContext(work_offsets={"G54": (25.4, 0.0, 0.0)}, tools={1: Tool(number=1, length=50.8)},
                         linear_units=units)
    shift = "1" if program_units == "G20" else "25.4"
    text = (f"{program_units} G90 G54\nG0 X0 Y0 Z0\nG92 Y-{shift}\nT1 M6\n"
            "#1 = #5221\n#2 = #5212\n#3 = #5403\nG53 G0 X#1 Y#2 Z[#3 / 2]\n")
    k = 25.4 if program_units == "G20" else 1.0
    assert ends(text, ctx, reference=False)[-1] == pytest.approx((want * k, want * k, want * k))


def test_machine_file_linear_units(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\nlinear_units = "inch"\n')
    assert load_machine(str(path)).context.linear_units == "inch"
    path.write_text(builtin_machine_text("fadal-pid") + '\n[program]\nlinear_units = "cm"\n')
    with pytest.raises(MachineError, match="linear_units"):
        load_machine(str(path))


def test_fanuc_and_haas_programs_write_work_offsets_through_system_variables():
    # Fanuc 0i "System variables" (workpiece zero point offsets read/write); Haas "Offsets" ("can be read and
    # set within a macro expression"): #5221 G54 X 100 -> 110 at once; #7001/#14002 G54.1 P1 X 5, Y 6
    text = "G21 G90 G54\n#5221 = #5221 + 10.\nG0 X0 Y0\n#7001 = 5.\n#14002 = 6.\nG54.1 P1 X0 Y0\n#1 = #5221\nX#1\n"
    assert ends(text, FANUC, reference=False) == [(110, 0, 0), (5, 6, 0), (115, 6, 0)]
    haas = dataclasses.replace(HAAS, work_offsets={})
    assert ends("G21 G90\n#14021 = 7.\n#7022 = 8.\nG154 P2 G0 X0 Y0\n", haas, reference=False) == [(7, 8, 0)]
    # LinuxCNC keeps the write for the next selection of another system (rs274 2.9.0~pre1; test_linuxcnc_params39)
    prog = parse_program("G21 G0 X0\n#5221 = 1\nG0 X0\nG55\nG54 X0\n", context=MachineContext())
    assert [b.target[0] for b in prog.blocks] == pytest.approx([0.0, 0.0, 1.0])


@pytest.mark.parametrize(("dialect", "d_factor"), [("fanuc", 1.0), ("haas", 0.5)])
def test_fanuc_haas_g10_tool_offsets_geometry_and_wear(dialect, d_factor):
    """Fanuc "Changing of tool compensation value (G10)" (memory C) and Haas "G10 Set Offsets": L10 length
    geometry, L11 (Haas also L1) length wear, L12 radius (Haas: diameter) geometry, L13 its wear; G90 sets,
    G91 adds; G43 H / G41 D apply geometry + wear. H2: 50 - 0.5 = 49.5; G91 L10 +10: 59.5; tool 1 (table
    length 100) with wear 1: 101; D3: 5 - 0.1 = 4.9 (Haas: diameters, radius 2.45) to the left of +X."""
    ctx = MachineContext(dialect=DIALECTS[dialect], tools={1: Tool(number=1, length=100.0)})
    text = ("G21 G90\nG10 L10 P2 R50.\nG10 L11 P2 R-0.5\nG43 H2 G0 Z0\nG91 G10 L10 P2 R10.\nG90 G43 H2 Z0\n"
            "G10 L1 P1 R1.\nG43 H1 Z0\nG10 L12 P3 R5.\nG10 L13 P3 R-0.1\nG41 D3 G1 X10 Y0 F100\nX20\nG40 X30\n")
    r = round(4.9 * d_factor, 6)
    assert ends(text, ctx) == [(0, 0, 49.5), (0, 0, 59.5), (0, 0, 101), (10, r, 101), (20, r, 101), (30, 0, 101)]
    with pytest.raises(GCodeError, match="G10 L10 sets offset P1 from R"):
        parse_program("G21\nG10 L10 P1 Z5\n", context=ctx)


def test_haas_tool_offset_variables():
    # Haas "Tool Offsets" variables: #2001+ length geometry, #2201+ length wear, #2401+ diameter geometry,
    # #2601+ diameter wear (tool n at + n - 1). Tool 2: length 80 + wear -0.2; D 10 + wear -0.1 (radius 4.95).
    text = ("G21 G90\n#2002 = 80.\n#2202 = -0.2\n#2402 = 10.\n#2602 = -0.1\nG43 H2 G0 Z0\n"
            "G41 D2 G1 X10 Y0 F100\nX20\nG40 X30\n#1 = #2002 + #2202\nG49 G53 G0 Z#1\n")
    assert ends(text, HAAS, reference=False) == [(0, 0, 79.8), (10, 4.95, 79.8), (20, 4.95, 79.8), (30, 0, 79.8),
                                                 (30, 0, 79.8)]
    # Fanuc (tool compensation memory C, the default): #2002 is H wear of offset 2, #2402 no tool offset
    assert ends("G21 G90\n#2002 = 0.5\n#1 = #10002\nG53 G0 X#1\n", FANUC, reference=False) == [(0.5, 0, 0)]
    with pytest.raises(GCodeError, match="#2402: this Fanuc system variable"):
        parse_program("G21\n#1 = #2402\n", context=FANUC)


def test_fanuc_g10_l2_p0_external_offset_shifts_every_system():
    # Fanuc "External workpiece zero point offset" (G10 L2 P0; Haas: the G52 entry): G54 (100) + EXT X5 -> 105,
    # G55 (200) + 5; G91 G10 L2 P0 X1 -> EXT 6; G92 X0 at machine 206 keeps EXT in the shared shift; #5201 reads 6
    text = ("G21 G90 G54\nG10 L2 P0 X5\nG0 X0\nG55 X0\nG91 G10 L2 P0 X1\nG90 X0\nG92 X0\nG10 L2 P0 X0\nX0\n"
            "#1 = #5201\nG53 X#1\n")
    assert [p[0] for p in ends(text, FANUC, reference=False)] == [105, 205, 206, 200, 0]
    assert [p[0] for p in ends(text.replace("#1 = #5201\nG53 X#1\n", ""), FANUC)] == [105, 205, 206, 200]


def test_fanuc_g10_l2_p0_sets_the_external_offset_of_a_rotary_axis_too():
    # B-64304EN "G10 L2 Pp IP_", p=0 the external offset "for each axis" (Mastercam: G10 L2 P0 X0. Y0. Z0. B0.):
    # EXT B10 -> G54 B0 at 10, G55 B5 at 15; G91 P0 B-4 -> EXT 6: B0 at 6; G54's own B3 adds: B0 at 9
    ctx = dataclasses.replace(FANUC, extra_axes=("b",))
    text = "G21 G90 G54\nG10 L2 P0 X5 B10.\nG0 X0 B0\nG55 B5\nG91 G10 L2 P0 B-4.\nG90 B0\nG10 L2 P1 B3.\nG54 B0\n"
    header, rows = blocks_table(parse_program(text, context=ctx))
    assert [(r[header.index("x")], r[header.index("b")]) for r in rows] == [(105, 10), (105, 15), (105, 6), (105, 9)]
    match = match_blocks(iso_reference(text, ctx), rows)
    assert match.mismatch is None and match.exact == 4
    # #5205 reads the external offset of B (X Y Z A B C in the order of #5201-#5206): 6 -> machine B 6
    prog = parse_program(text + "#1 = #5205\nG53 B#1\n", context=ctx)
    assert round(float(prog.blocks[-1].extra_target[1]), 9) == 6.0


def test_linuxcnc_refuses_a_coordinate_system_change_under_cutter_compensation():
    # interp_convert.cc convert_coordinate_system: "Cannot change coordinate systems with cutter radius
    # compensation on" (checked before "already using this origin"); G40 in the same block runs first
    ctx = MachineContext(tools={1: Tool(number=1, radius=1.0)})
    with pytest.raises(GCodeError, match="G55: cannot change coordinate systems with cutter radius compensation"):
        parse_program("G21 G0 X0 Y0\nG41 D1 G1 X10 F100\nG55 X20\nG40 X30\n", context=ctx)
    assert ends("G21 G0 X0 Y0\nG41 D1 G1 X10 F100\nG40 G55 X20\n", ctx)[-1] == (20, 0, 0)
