"""Readings settled by the wild21 set of public programs (/tmp/wild21/set, 212 programs: Fusion 360 personal-use
and MPCNC posts, a Haas student's Mastercam and hand-written mill programs, Eagle's stepcraft.ulp for UCCNC, dxf2gcode
and Inkscape plasma files for LinuxCNC, GrblGru, Universal G-code Sender's test files, Fanuc 0i-MD macro programs)."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
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
