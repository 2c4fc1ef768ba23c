"""Heidenhain programs of a ninth wild set (German shop and training programs of an iTNC 530 / TNC 640, a
Polish-dialogue drilling program, Fusion 360 and hyperMILL posts, a TNC simulator's German demo programs, a
hand-written pseudo-Klartext warm-up): what the reader named unclearly, and the forms the set leans on that no
earlier test held, each as a hand-written program checked against the independent reference where it runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpolators.context import MachineContext
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError

ZERO = MachineContext()


def checked(body: str):
    """The program read, and its blocks matched against the reference."""
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", ZERO)


def test_r_letter_o_is_named_as_the_radius_compensation_r0():
    # a hand-written warm-up program wrote 'L Z+0 RO FMAX': the letter O where the TNC's R0 has the digit zero
    # (TNC 640 user's manual, "Radius compensation": R0, RL, RR); it was a bare 'unknown word'
    with pytest.raises(GCodeError, match=r"t.h:2:9: unknown word 'RO': no radius compensation is written with "
                                         r"the letter O; expected R0 \(with the digit zero\), RL or RR"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L Z+0 RO FMAX\nEND PGM T MM\n", source="t.h", context=ZERO)
    with pytest.raises(GCodeError, match=r"unknown word 'RX'; expected X/Y/Z"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L Z+0 RX FMAX\nEND PGM T MM\n", source="t.h", context=ZERO)


def test_polar_arc_about_a_pole_in_the_yz_plane():
    # the Fusion 360 TNC post leads into a contour on a quarter arc in the plane of the tool axis: 'CC Y.. Z..'
    # sets the pole in Y/Z, 'CP IPA-90 DR-' turns about it (TNC 426/430 user's manual, "Circular path C around
    # circle centre CC": the CC's two coordinates choose the plane). From (-1.2, 88.6, -23.5) about
    # (Y 87.4, Z -23.5), radius 1.2, a quarter turn clockwise seen from +X ends at (-1.2, 87.4, -24.7)
    prog = checked("1 L X-1.2 Y+88.6 Z-23.5 R0 F200\n2 CC Y+87.4 Z-23.5\n3 CP IPA-90 DR- F600\n"
                   "4 L Y+86.2 Z-24.7\n5 CC X+0 Y+86.2\n6 CP IPA+90 DR+")
    assert np.allclose(prog.blocks[1].target, [-1.2, 87.4, -24.7])
    assert np.allclose(prog.blocks[2].target, [-1.2, 86.2, -24.7])
    # then about (0, 86.2) in X/Y, a quarter turn counterclockwise from angle 180 deg to 270 deg
    assert np.allclose(prog.blocks[-1].target, [0.0, 86.2 - 1.2, -24.7])


def test_german_old_pocket_cycles_and_polish_cycle_200():
    # an iTNC 530 training program in German dialogue: CYCL DEF 5 KREISTASCHE (5.1 ABST, 5.2 TIEFE, 5.3 ZUSTLG
    # .. F, 5.4 RADIUS, 5.5 F DR-) called where the tool is; a Polish program's cycle 200 'WIERCENIE' with
    # Q395=+0 (depth to the tip). The circular pocket's plunge goes to the depth below the start's set-up
    # clearance, and the drill's bottom is Q203 + Q201
    prog = checked("1 TOOL CALL 1 Z S2000 F200\n2 L X+60 Y+45 Z+1 R0 FMAX\n3 CYCL DEF 5.0 KREISTASCHE\n"
                   "4 CYCL DEF 5.1 ABST 1\n5 CYCL DEF 5.2 TIEFE -5.5\n6 CYCL DEF 5.3 ZUSTLG 5.5 F100\n"
                   "7 CYCL DEF 5.4 RADIUS 10\n8 CYCL DEF 5.5 F200 DR-\n9 CYCL CALL\n"
                   "10 CYCL DEF 200 WIERCENIE ~\n Q200=+1 ;BEZPIECZNA WYSOKOSC ~\n Q201=-8 ;GLEBOKOSC ~\n"
                   " Q206=+100 ;WARTOSC POSUWU WGL. ~\n Q202=+8 ;GLEBOKOSC DOSUWU ~\n Q210=+0 ;PRZER. CZAS.NA GORZE ~\n"
                   " Q203=+0 ;WSPOLRZEDNE POWIERZ. ~\n Q204=+50 ;2-GA BEZPIECZNA WYS. ~\n"
                   " Q211=+0 ;PRZERWA CZAS. DNIE ~\n"
                   " Q395=+0 ;REFERENCJA GLEB.\n11 L X+21 Y-15 R0 FMAX M99")
    zs = [b.target[2] for b in prog.blocks]
    assert math.isclose(min(zs), -8.0)
    assert any(math.isclose(z, 1.0 - 1.0 - 5.5) for z in zs)  # the pocket's floor: start 1, clearance 1, depth 5.5
    assert np.allclose(prog.blocks[-1].target, [21, -15, 50])


def test_sysread_of_the_machine_status():
    # a simulator's tool-change macro compares 'FN 18: SYSREAD Q1000 = ID20 NR2' (the prepared tool) with ID20 NR1
    # (the active tool); it was refused. iTNC 530 technical manual 07/2013, 9.5.4 "Data transfer NC > NC program
    # (FN18: SYSREAD)": ID10 NR1 mm = 0, inch = 1; ID20 NR1 active tool number, NR2 prepared tool number, NR3
    # active tool axis (0 = X, 1 = Y, 2 = Z), NR4 programmed spindle speed. The values end up in the end point
    prog = checked("1 TOOL DEF 7\n2 TOOL CALL 3 Z S1200 F300\n3 FN 18: SYSREAD Q1 = ID20 NR1\n"
                   "4 FN 18: SYSREAD Q2 = ID20 NR2\n5 FN 18: SYSREAD Q3 = ID20 NR3\n6 FN 18: SYSREAD Q4 = ID20 NR4\n"
                   "7 FN 18: SYSREAD Q5 = ID10 NR1\n8 L X+Q1 Y+Q2 Z+Q3 R0 FMAX\n9 L X+Q4 Y+Q5 FMAX")
    assert np.allclose(prog.blocks[0].target, [3, 7, 2])
    assert np.allclose(prog.blocks[1].target, [1200, 0, 2])
    # before any TOOL DEF or S: 0 (our reading: no manual page gives the value before one)
    prog = checked("1 FN 18: SYSREAD Q2 = ID20 NR2\n2 FN 18: SYSREAD Q4 = ID20 NR4\n3 L X+Q2 Y+Q4 Z+0 R0 FMAX")
    assert np.allclose(prog.blocks[0].target, [0, 0, 0])
    # the machine status has no index; other numbers stay an error naming what is read
    with pytest.raises(GCodeError, match=r"FN 18 SYSREAD 'SYSREAD Q1 = ID20 NR5' is not supported; expected .*"
                                         r"NR2..NR4 \(prepared tool, tool axis, spindle speed\)"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 FN 18: SYSREAD Q1 = ID20 NR5\nEND PGM T MM\n", source="t.h",
                         context=ZERO)
    with pytest.raises(GCodeError, match=r"ID10 NR1 IDX1' is not supported"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 FN 18: SYSREAD Q1 = ID10 NR1 IDX1\nEND PGM T MM\n", source="t.h",
                         context=ZERO)


_DRILL = ("CYCL DEF 200 BOHREN ~\n Q200=+1 ;SICHERHEITS-ABST. ~\n Q201=-10 ;TIEFE ~\n Q206=100 ;VORSCHUB TIEFENZ. ~\n"
          " Q202=+10 ;ZUSTELL-TIEFE ~\n Q210=0 ;VERWEILZEIT OBEN ~\n Q203=+0 ;KOOR. OBERFLAECHE ~\n"
          " Q204=+5 ;2. SICHERHEITS-ABST. ~\n Q211=0 ;VERWEILZEIT UNTEN")


def test_a_cycle_reads_its_q_parameters_when_called():
    # an iTNC 530 training program defines cycle 200 (Q201=-10), runs it through a pattern in a label, then for
    # the next drill writes 'Q201=-18' and calls the label again: the cycle parameters are Q parameters (TNC 640
    # ISO manual, Q200-Q1199 "used for cycles"), read when the cycle is called (our reading); vcnc kept the
    # definition's values. Three calls: Q201 -10; then -18 (two infeeds of Q202 = 10); then Q202 = 5 as well
    prog = checked(f"1 TOOL CALL 1 Z S1000 F200\n2 L X+50 Y+50 Z+10 R0 FMAX\n3 {_DRILL}\n4 CYCL CALL\n5 Q201=-18\n"
                   "6 CYCL CALL\n7 FN 0: Q202=+5\n8 L X+60 Y+50 R0 FMAX M99")
    bottoms = [b.target[2] for b in prog.blocks if b.kind in ("line", "feed")]
    assert np.allclose(bottoms, [-10, -10, -18, -5, -10, -15, -18])
    assert np.allclose(prog.blocks[-1].target, [60, 50, 5])


def test_a_pattern_in_a_label_called_again_with_a_deeper_hole():
    # the program's form: CYCL DEF 200, then LBL 1 / CYCL DEF 220 (two holes on a circle) / LBL 0, then Q201=-18 and
    # CALL LBL 1: the second run of the pattern drills to -18 at both positions
    prog = checked(f"1 TOOL CALL 1 Z S1000 F200\n2 L X+60 Y+45 Z+1 R0 FMAX\n3 {_DRILL}\n4 LBL 1\n"
                   "5 CYCL DEF 220 MUSTER KREIS ~\n Q216=+60 ~\n Q217=+45 ~\n Q244=+48 ~\n Q245=+0 ~\n Q246=+180 ~\n"
                   " Q247=+180 ~\n Q241=+2 ~\n Q200=+1 ~\n Q203=+0 ~\n Q204=+1 ~\n Q301=+1 ~\n Q365=+0\n6 LBL 0\n"
                   "7 Q201=-18\n8 CALL LBL 1")
    feeds = [b for b in prog.blocks if b.kind in ("line", "feed")]
    assert [round(float(b.target[2]), 6) for b in feeds] == [-10, -10, -10, -18, -10, -18]
    assert np.allclose([b.target[0] for b in feeds][-2:], [36, 36])


def test_bore_milling_without_an_infeed_per_helix_names_what_is_missing():
    # a TNC simulator's German demo chamfers a hole with 'CYCL DEF 208 ;Bohrfraesen' and Q334=+0: the TNC 640 cycle
    # manual allows 0 for Q334 but describes no run without an infeed per helix; the message said "must be > 0"
    body = ("1 TOOL CALL 5 Z S1800 F1000\n2 CYCL DEF 208 ~\n Q200=+2 ~\n Q201=-1 ~\n Q206=+150 ~\n Q334=+0 ~\n"
            " Q203=+20 ~\n Q204=+50 ~\n Q335=+8 ~\n Q342=+7.999 ~\n Q351=+1\n3 L X+0 Y+0 R0 FMAX M99")
    with pytest.raises(GCodeError, match=r"t.h:3:3: cycle 208 with Q334=0 \(no infeed per helix\) is not modelled: "
                                         r"no manual page found .*expected Q334 > 0 \[mm\]"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", source="t.h", context=ZERO)
    with pytest.raises(GCodeError, match=r"cycle 208: Q334 \(infeed per helix\) and Q335 \(diameter\) must be > 0"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + body.replace("Q334=+0", "Q334=-2") + "\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


def test_a_negative_tool_radius_is_named_not_a_crash_or_a_hang():
    # a TNC simulator's demo finishes a ramp with 'TOOL CALL 2 Z S2000 F5000 DL-0.536 DR-2' and 'L .. FMAX RL': with
    # tool 2 not in the context's table, R + DR = -2; compensate() raised a bare InputError (no file, no line)
    with pytest.raises(GCodeError, match=r"t.h:4:23: RL with a negative tool radius -2 mm \(the tool's radius R plus "
                                         r"DR of its TOOL CALL\) is not modelled .*expected R \+ DR >= 0"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 TOOL CALL 2 Z S2000 F5000 DR-2\n2 L X+0 Y-10 Z+10 FMAX R0\n"
                         "3 L X+0 Y-10 Z+9 FMAX RL\n4 L Y+60\n5 L Z+40 FMAX R0\nEND PGM T MM\n", source="t.h",
                         context=ZERO)
    # a pocket cycle stepped its rings by Q370 x R: with R < 0 inward for ever (the run hung)
    pocket = ("1 TOOL CALL 2 Z S2000 F500 DR-2\n2 L X+0 Y+0 Z+10 R0 FMAX\n3 CYCL DEF 252 CIRCULAR POCKET ~\n"
              " Q215=+0 ~\n Q223=+40 ~\n Q368=+0 ~\n Q207=+500 ~\n Q351=+1 ~\n Q201=-5 ~\n Q202=+5 ~\n Q369=+0 ~\n"
              " Q206=+150 ~\n"
              " Q338=+0 ~\n Q200=+2 ~\n Q203=+0 ~\n Q204=+50 ~\n Q370=+1 ~\n Q366=+0 ~\n Q385=+500\n4 CYCL CALL")
    with pytest.raises(GCodeError, match=r"cycle 252 with a negative tool radius -2 mm .* is not modelled"):
        parse_heidenhain("0 BEGIN PGM T MM\n" + pocket + "\nEND PGM T MM\n", source="t.h", context=ZERO)
    # the same pocket with R + DR = 0 still runs: the plunge to -5 at the centre
    prog = checked(pocket.replace("DR-2", "DR+0").replace("Q223=+40", "Q223=+10"))
    assert any(math.isclose(b.target[2], -5.0) for b in prog.blocks)


def test_iso_g_lines_in_a_conversational_program_are_named():
    # a training program writes its contour between APPR LCT and DEP LCT as ISO lines (' G1 X10 Y26.045',
    # ' G3 X51.908 Y70.652 I1.908 J9.816'): a TNC runs ISO only as a separate DIN/ISO program; the message said
    # "unknown or unsupported block 'G1'"
    with pytest.raises(GCodeError, match=r"t.h:3:2: the G function 'G1' is ISO \(DIN 66025\) syntax: not a TNC block; "
                                         r"expected a conversational block \(L for G0/G1, C or CR for G2/G3\)"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L X-15 Y-15 Z1 R0 FMAX\n G1 X10 Y26.045\nEND PGM T MM\n",
                         source="t.h", context=ZERO)


def test_a_block_of_no_tnc_language_is_an_error_even_where_the_flow_never_goes():
    # a simulator's tool-change macro jumps over its '##LANGUAGE AC' section when the prepared tool is the active
    # one (FN 9 on ID20 NR2 = NR1); vcnc ran it with no error because it checks a block only when it runs it. Our
    # reading of the control's 'ERROR =' marking: a TNC checks every block when it reads a program in
    text = ("0 BEGIN PGM T MM\n1 FN 18: SYSREAD Q1000 = ID20 NR2\n2 FN 18: SYSREAD Q1001 = ID20 NR1\n"
            "3 FN 9: IF +Q1000 EQU +Q1001 GOTO LBL \"NO_TOOLCHANGE\"\n##LANGUAGE AC\n4 LBL \"NO_TOOLCHANGE\"\n"
            "5 L X+1 Y+2 Z+3 R0 FMAX\nEND PGM T MM\n")
    with pytest.raises(GCodeError, match=r"t.h:5:1: unknown or unsupported block '##LANGUAGE'"):
        parse_heidenhain(text, source="t.h", context=ZERO)
    # without the foreign line the jump is taken: the one move
    prog = checked(text.replace("##LANGUAGE AC\n", "").removeprefix("0 BEGIN PGM T MM\n").removesuffix(
        "END PGM T MM\n"))
    assert np.allclose([b.target for b in prog.blocks], [[1, 2, 3]])
    # an ERROR = block after M30 (in the subprograms' part) is refused as well
    with pytest.raises(GCodeError, match=r"t.h:4:3: a block the control marked 'ERROR ='"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L X+1 R0 FMAX\n2 M30\n3 ERROR = L XQ102\nEND PGM T MM\n", source="t.h",
                         context=ZERO)
