"""Readings settled by the wild21 set of public programs (/tmp/wild21/set, 212 programs: Fusion 360 personal-use
and MPCNC posts, a Haas student's Mastercam and hand-written mill programs, Eagle's stepcraft.ulp for UCCNC, dxf2gcode
and Inkscape plasma files for LinuxCNC, GrblGru, Universal G-code Sender's test files, Fanuc 0i-MD macro programs)."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext, Tool
from tests.interpolators.iso_checks import checked_iso
from vcnc.cli import main
from vcnc.errors import GCodeError

#: Eagle's stepcraft.ulp 0.2 drill file for UCCNC (kinasmith/UAF sap-flux/hardware/pcb/SC4541_drill.nc): the arc
#: code and its feed alone on a line, the end point and centre on the next.
STEPCRAFT_DRILL = ("G90 G94 G49\nG21\nG00 Z5\nG00 X0Y0\nS19500 M03\nG00 Z1.000\nG00 X7.731Y2.540\nG01 Z-0.170 F30\n"
                   "G03 F360\nX7.731Y2.540 I-0.111\nG00 Z5\nM30\n")


def _in_dialect(name: str, **changes) -> MachineContext:
    return MachineContext(dialect=dataclasses.replace(DIALECTS[name], **changes))


def test_grbl_refuses_the_arc_code_alone_that_fanuc_takes_as_the_mode():
    # grbl/gcode.c: the G3 word makes the block an axis command and the arc checks fail "[No axis words]" (error
    # 26); LinuxCNC refuses it too ("R i j k words all missing for arc", rs274 on this file); Fanuc and Haas set the
    # motion mode, and the next block's X Y I is a full circle about (7.62, 2.54)
    with pytest.raises(GCodeError, match=r":9:1: G03 arc without axis words: grbl refuses it \(error 26"):
        parse_program(STEPCRAFT_DRILL, context=_in_dialect("grbl"))
    with pytest.raises(GCodeError, match=r":9:1: G03 arc without R, I, J or K \(LinuxCNC"):
        parse_program(STEPCRAFT_DRILL, context=_in_dialect("linuxcnc"))
    for name in ("fanuc", "haas"):
        arc = checked_iso(STEPCRAFT_DRILL, _in_dialect(name)).blocks[-2]
        assert arc.kind == "arc" and arc.target.tolist() == pytest.approx([7.731, 2.54, -0.17])


#: A Haas student's face milling program without G20 (CadeKiely/Hass-CNC-Programs "CNC MILL/3x3 face - o78237.nc",
#: shortened): inch words, as the Haas of a US school reads them under Setting 9 = INCH.
HAAS_INCH = ("%\nO78237\nN5 G00 G17 G40 G49 G54 G80 G90 G98\nN10 G53 Z0.\nN15 T1 M06\nN20 S4500 M03\n"
             "N30 G00 X-.750 Y.375\nN35 Z1. M08\nN40 G01 Z0. F10.\nN45 G01 X3.5 Y.375 F80.\nM30\n%\n")


def test_the_power_on_units_of_a_program_without_g20_g21():
    # Haas mill operator's manual, Setting 9 "Dimensioning": the control's inch or metric mode is what a program
    # without G20/G21 runs in; vcnc's dialects assume mm, and the note says how to read it in inch
    prog = checked_iso(HAAS_INCH, _in_dialect("haas"))
    assert prog.blocks[-1].target.tolist() == pytest.approx([3.5, 0.375, 0.0])
    assert ("no G20/G21: mm assumed (haas default; a control powered on in inch reads it in inch: --default-units "
            "inch, [program] default_units)") in prog.notes
    prog = checked_iso(HAAS_INCH, _in_dialect("haas", default_units="inch"))
    assert prog.blocks[-1].target.tolist() == pytest.approx([88.9, 9.525, 0.0])
    assert prog.blocks[-1].feed == pytest.approx(80 * 25.4 / 60)
    assert ("no G20/G21: inch assumed (the machine's power-on units; a control powered on in mm reads it in mm: "
            "--default-units mm, [program] default_units)") in prog.notes


def test_default_units_on_the_command_line(tmp_path, capsys):
    part = tmp_path / "o78237.nc"
    part.write_text(HAAS_INCH)
    blocks, out = tmp_path / "b.csv", tmp_path / "sp.csv"
    assert main(["interpolate", str(part), "-o", str(out), "--dialect", "haas", "--default-units", "inch",
                 "--blocks", str(blocks)]) == 0
    assert "no G20/G21: inch assumed" in capsys.readouterr().out
    assert blocks.read_text().splitlines()[-1].split(",")[3:6] == ["88.9", "9.525", "0"]
    with pytest.raises(SystemExit) as exc:  # argparse: a bad choice is a usage error, status 2
        main(["interpolate", str(part), "-o", str(out), "--default-units", "cm"])
    assert exc.value.code == 2 and "invalid choice: 'cm'" in capsys.readouterr().err


#: Thaddeus-Maximus/lagun-linuxcnc nc_files/programs/spw_pew.ngc, the first pass rewritten with one tool: a G41
#: entry that ramps down, a line shorter than the inside corner's retreat, then a tangent arc (G90.1 centres).
RAMPED_ENTRY = ("G21 G90 F25\nT5 M6\nG0 X2.851 Y-2.2 Z0.2\nG41\nG1 X3.1 Y-1.85 Z-0.22\nG1 X2.851 Y-1.85\n"
                "G2 I2.851 J-0.948 X2.070 Y-1.399 G90.1\nG40\nG1 X2.851 Y-1.0\nM2\n")


def test_linuxcnc_runs_a_line_whose_start_an_inside_corner_moved_past_its_end():
    # rs274 (linuxcnc_diff, tool 5 of radius 0.13335 mm): the entry ends at the corner's retreat point
    # (2.8415, -1.98335), past the end of the next line, which it then runs backwards to (2.851, -1.98335):
    # move_endpoint_and_flush (interp_queue.cc) checks a queued line only when its end is moved. The entry keeps
    # its programmed end Z: LinuxCNC moves the end in the plane only (before: Z -> 0.0328, interpolated)
    ctx = MachineContext(tools={5: Tool(number=5, radius=0.13335)})
    moves = [b.target.tolist() for b in parse_program(RAMPED_ENTRY, context=ctx).blocks]
    assert moves[1] == pytest.approx([2.84148, -1.98335, -0.22], abs=5e-5)
    assert moves[2] == pytest.approx([2.851, -1.98335, -0.22], abs=1e-9)
    assert moves[-1] == pytest.approx([2.851, -1.0, -0.22], abs=1e-12)


def test_a_trimmed_inside_corner_keeps_the_programmed_depth_of_its_vertex():
    # a helical ramp along a pocket wall into an inside corner: LinuxCNC's STRAIGHT_FEED of the first line ends at
    # the corner point with that line's programmed Z (-1), and the second line runs from there to Z -2
    text = ("G21 G90 F100\nG0 X0 Y0 Z0\nG41\nG1 X10 Y0 Z0\nG1 X20 Y0 Z-1\nG1 X20 Y10 Z-2\nG40\nG1 X30 Y10\nM2\n")
    ctx = MachineContext(tools={1: Tool(number=1, radius=1.0)})
    blocks = parse_program("T1 M6\n" + text, context=ctx).blocks
    corner = [b for b in blocks if b.line == 6][0]
    assert corner.target.tolist() == pytest.approx([19.0, 1.0, -1.0], abs=1e-12)
    assert [b for b in blocks if b.line == 7][0].start.tolist() == pytest.approx([19.0, 1.0, -1.0], abs=1e-12)
