"""ISO programs of the eighteenth wild round (set /tmp/isowild18): laser programs of LightBurn and LaserGRBL, Marlin
laser and CNC firmware (a Snapmaker, a DexArm, Gfix's post-processed LaserGRBL files), FreeCAD Path posts, PyCut,
an NX Post Builder output and the macros of a DDCS Expert controller. The snippets are written for these tests after
those programs."""

from __future__ import annotations

import pytest

from interpolators import parse_program
from interpolators.context import MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

FANUC = MachineContext().with_dialect("fanuc")
HAAS = MachineContext().with_dialect("haas")
LINUXCNC = MachineContext().with_dialect("linuxcnc")
GRBL = MachineContext().with_dialect("grbl")
ALL = [LINUXCNC, GRBL, FANUC, HAAS]

# a LaserGRBL test pattern: grbl's laser mode set first ($32=1), then M4 with the power as S
LASERGRBL = ("$32=1\nF500;\nG49 G80;\nG17 G21;\nG90;\nM05 S0;\nM04 F1100;\nS500;\nG00 X1.000 Y1.000;\n"
             "G01 X1.000 Y9.000;\nG01 X9.000 Y9.000;\nM05;\n")


def test_a_grbl_laser_program_with_its_settings_line_runs_under_grbl():
    prog = checked_iso(LASERGRBL, GRBL)
    moves = [b for b in prog.blocks if b.kind in ("rapid", "line")]
    assert [tuple(b.target[:2]) for b in moves] == [(1.0, 1.0), (1.0, 9.0), (9.0, 9.0)]
    assert moves[-1].feed == pytest.approx(1100 / 60)


@pytest.mark.parametrize("context", [LINUXCNC, FANUC, HAAS])
def test_a_grbl_settings_line_names_grbl_under_the_other_dialects(context):
    with pytest.raises(GCodeError, match=r":1:1: unknown word '\$32=1' \(a grbl setting or system command, such as "
                                         r"\$32=1 \(laser mode\) or \$H \(homing\), which grbl reads on a line of its "
                                         r"own: read the program with --dialect grbl\)"):
        parse_program(LASERGRBL, context=context)


# a LightBurn GRBL device profile: the power as S on the first G1 of a layer, the feed modal
LIGHTBURN = ("; LightBurn 1.2.01\n; GRBL device profile, absolute coords\nG00 G17 G40 G21 G54\nG90\nM4\nM8\n"
             "G0 X125Y0.041\nG1 Y37.5S970F100\nG1 X131\nG1 Y0.041\nM9\nG1 S0\nM5\nG90\nG0 X0 Y0\nM2\n")


@pytest.mark.parametrize("context", ALL)
def test_a_lightburn_laser_program_runs_under_every_dialect(context):
    prog = checked_iso(LIGHTBURN, context)
    cuts = [b for b in prog.blocks if b.kind == "line"]
    assert [tuple(b.target[:2]) for b in cuts] == [(125.0, 37.5), (131.0, 37.5), (131.0, 0.041)]
    assert all(b.feed == pytest.approx(100 / 60) for b in cuts)


@pytest.mark.parametrize("context", ALL)
@pytest.mark.parametrize("spindle", ["M3", "M4"])
def test_marlins_inline_laser_mode_is_named(context, spindle):
    # Gfix's output for a Marlin laser (an Ender 3 S1 Pro): "M3 I" first, then "M3 S0" / "G1 ... S250"
    with pytest.raises(GCodeError, match=r":1:4: malformed number for word I \(M3 I / M4 I: Marlin's inline "
                                         r"laser power mode, 'M3 \[I<mode>\]', which a Marlin laser program sets; no "
                                         r"ISO control reads it: M3 S<power> is the form the grbl dialect reads\)"):
        parse_program(f"{spindle} I\nG0 X5 Y5 S0 F1000\nG1 X6 S250\n", context=context)


def test_an_i_word_without_its_number_elsewhere_is_not_called_marlins():
    with pytest.raises(GCodeError, match=r"malformed number for word I") as err:
        parse_program("G2 X1 Y1 I J1 F100\n", context=LINUXCNC)
    assert "Marlin" not in str(err.value)


DDCS_IF = (r"IF #n==v GOTO n, a statement of the DDCS controllers' macro language \(a C-style condition such as "
           r"#1==0 or #1<#2, without brackets and without THEN\)")


@pytest.mark.parametrize(("text", "column", "what"), [
    # DDCS Expert macros: C's == in a condition, a prompt variable #1505
    ("#1505=1\nIF #1505==0 GOTO999\nG0 X1\nN999\nM30\n", "2:2", DDCS_IF),
    ("#1=2\nIF #1!=2 GOTO9\nN9\nM30\n", "2:2", DDCS_IF),
    ("#569=5\n#792=9\nIF #569<#792 GOTO1\nG0 Z#569\nN1\nM30\n", "3:2", DDCS_IF),
])
@pytest.mark.parametrize("context", [FANUC, LINUXCNC])
def test_ddcs_conditions_are_named(text, column, what, context):
    with pytest.raises(GCodeError, match=rf":{column}: malformed value: '\w+' is neither a number, a parameter nor "
                                         rf"a function \({what}; vcnc reads ISO G-code with Fanuc macro B or "
                                         r"LinuxCNC O-codes\)"):
        parse_program(text, context=context)


@pytest.mark.parametrize("context", [FANUC, LINUXCNC])
def test_a_condition_with_then_stays_centroids(context):
    with pytest.raises(GCodeError, match=r":2:2: .*\(IF #n THEN \.\.\., a statement of Centroid CNC12's macro "
                                         r"language;"):
        parse_program("#100=1\nIF #100 == 1 THEN GOTO 10\nN10\nM30\n", context=context)


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_a_fanuc_condition_without_brackets_is_named(context):
    with pytest.raises(GCodeError, match=r":2:2: .*\(IF #n GT v GOTO n: a condition without its brackets, which "
                                         r"Fanuc macro B writes IF \[#1 GT 0\] GOTO n;"):
        parse_program("#1=1\nIF #1 GT 0 GOTO 10\nN10\nM30\n", context=context)


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_a_ddcs_loop_without_brackets_is_named(context):
    with pytest.raises(GCodeError, match=r":2:1: WHILE condition without its brackets \(as the DDCS controllers "
                                         r"write 'WHILE #18<#3 DO2': Fanuc macro B brackets it\)"):
        parse_program("#1=0\nWHILE #1<3 DO1\n#1=#1+1\nEND1\nM30\n", context=context)


def test_a_fanuc_loop_with_its_brackets_runs():
    prog = checked_iso("G21 G90\n#1=0\nWHILE [#1 LT 3] DO1\n#1=#1+1\nG1 X#1 F600\nEND1\nM30\n", FANUC)
    assert [b.target[0] for b in prog.blocks if b.kind == "line"] == [1.0, 2.0, 3.0]


# FreeCAD's maxmake post for a CNCjs sender: "%" lines CNCjs evaluates, "[...]" lines it substitutes
CNCJS = ("G21 G90\nG0 Z5.000\nM5\n%global.gz = mposz - posz\n[global.gz < 0 ? \"(ok)\" : \"M0\"]\n"
         "G0 X1 Y1\nM30\n")


def test_a_cncjs_macro_line_names_cncjs_and_the_grbl_dialect():
    with pytest.raises(GCodeError, match=r":4:1: '%' must stand alone on its line \(a macro line of the CNCjs "
                                         r"sender, which evaluates it and streams the rest to grbl: --dialect grbl "
                                         r"reads the file as CNCjs streams it\)"):
        parse_program(CNCJS, context=LINUXCNC)


def test_a_cncjs_expression_line_is_named_under_grbl():
    with pytest.raises(GCodeError, match=r":5:1: .* in brackets where a word should start \(a template's "
                                         r"placeholder, or an expression the CNCjs sender evaluates, as a CNCjs macro "
                                         r"writes 'G0 X\[xmin\]'\?\)"):
        parse_program(CNCJS, context=GRBL)


# NX Post Builder's legacy practice post: "G40 G17 G90 G71" first, G71 for mm as on a Siemens control
NX = ("%\nN10 G40 G17 G90 G71\nN20 G91 G28 Z0.0\nN30 T01 M06\nN40 G54\nN50 G00 G90 X150. Y12.53 S1000 M03\n"
      "N60 G43 Z4. H01\nN70 Z3.875\nN80 G01 Z.875 F300. M08\nN90 X100.\nN100 G02 Y46.25 I0.0 J16.86\nN110 M02\n%\n")


def test_an_nx_legacy_post_reads_g71_as_mm_under_fanuc():
    prog = checked_iso(NX, FANUC)
    arc = [b for b in prog.blocks if b.kind == "arc"][-1]
    assert tuple(arc.target[:2]) == pytest.approx((100.0, 46.25))
    assert arc.feed == pytest.approx(300 / 60)  # mm/min, not inch/min


def test_an_nx_legacy_post_names_g71_under_linuxcnc():
    with pytest.raises(GCodeError, match=r":2:17: G71 lathe roughing cycle: not supported \(a unit code on Siemens, "
                                         r"Fagor and Heidenhain ISO controls: mm input; write G21, or read the "
                                         r"program with --dialect fanuc\)"):
        parse_program(NX, context=LINUXCNC)


# a Fanuc lathe program of GCodeWorkShop's examples opens "%O1200(TOKARKA)"
@pytest.mark.parametrize("context", [LINUXCNC, HAAS])
def test_a_fanuc_tape_leader_with_the_program_number_names_fanuc(context):
    with pytest.raises(GCodeError, match=r":1:1: '%' must stand alone on its line \(a Fanuc tape's first line, whose "
                                         r"text after the '%' a Fanuc control skips: --dialect fanuc reads it\) "
                                         r"\(got '%O1200'\)"):
        parse_program("%O1200(TOKARKA)\nG21 G90 G0 X1\nM30\n%\n", context=context)


def test_the_fanuc_dialect_skips_the_text_of_the_first_percent_line():
    prog = checked_iso("%O1200(TOKARKA)\nG21 G90 G0 X1\nM30\n%\n", FANUC)
    assert [b.target[0] for b in prog.blocks if b.kind == "rapid"] == [1.0]


def test_a_lathe_programs_g50_s_is_noted_under_fanuc():
    # GCodeWorkShop's Fanuc 0T example: "N01G50S0600" (the lathe's spindle speed clamp), then X as a diameter
    prog = checked_iso("O0358\nN01G50S0600\nG00X86.Z0.25\nG01X118.F0.3\nM30\n", FANUC)
    assert [b.target[0] for b in prog.blocks if b.kind in ("rapid", "line")] == [86.0, 118.0]
    assert ("G50 S read as the mill's scaling cancel and a spindle speed (on a Fanuc lathe G50 S is the maximum "
            "spindle speed: a lathe program, whose X is a diameter?)") in prog.notes
    assert "G50 cancel" not in prog.notes  # the lathe note says it (review28: both were given)


def test_a_mill_programs_g50_alone_is_not_called_a_lathes():
    prog = checked_iso("G21 G90\nG51 X0 Y0 P2000\nG0 X1\nG50\nG0 X2\nM30\n", FANUC)
    assert not any("lathe" in n for n in prog.notes)


# Brown Industries' O9250 (dynamic work offset rotation) reads the external work offset #5201 onwards
def test_the_external_work_offset_names_the_fanuc_dialect_under_linuxcnc():
    with pytest.raises(GCodeError, match=r":1:4: parameter #5201: this system parameter \(machine state above #5000\) "
                                         r"is not modelled \(#5201-#5206: the external work offset of Fanuc and Haas, "
                                         r"which --dialect fanuc or haas reads\)"):
        parse_program("#1=#5201\nG0 X#1\nM30\n", context=LINUXCNC)


@pytest.mark.parametrize("context", [FANUC, HAAS])
def test_the_external_work_offset_reads_under_fanuc_and_haas(context):
    # the reference reader leaves #5201 out (the machine's state): the value is checked here
    prog = parse_program("G21 G90\nG10 L2 P0 X5.\nG54\n#1=#5201\nG0 X#1\nM30\n", context=context)
    assert [b.target[0] for b in prog.blocks if b.kind == "rapid"] == [10.0]  # X5 in G54 shifted by EXT X5
