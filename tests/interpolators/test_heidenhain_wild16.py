"""Heidenhain programs of the sixteenth wild set (a German shop's iTNC 530 / TNC 640 programs for an A/C trunnion
table in ManuelDeV-exe/Nullpunktverschiebung_Heidenhain, 'test.h' and 'fertiges Programm zum testen.h': probing
cycles 417, 427, 419, PLANE SPATIAL ... TABLE ROT, datum shifts in labels; and the datum-table row that the generic
Fusion 360 / HSMWorks Heidenhain posts write for every work offset, 'CYCL DEF 7.0 DATUM SHIFT' / 'CYCL DEF 7.1 #n';
see /tmp/tncwild16/set/sources.tsv): the forms vcnc refused though a TNC runs them, each as a hand-written program
with end points worked out by hand and checked against the independent reference (``reference_heidenhain``)."""

from __future__ import annotations

import numpy as np
import pytest

from interpolators.context import MachineContext, read_datum_table
from interpolators.heidenhain import parse_heidenhain
from tests.interpolators.reference_heidenhain import checked_program
from vcnc.errors import GCodeError, InputError

#: A datum table of three rows (D 0, 1, 2) [mm]: row 2 leaves Y and Z empty, which are 0.
TABLE = {0: (0.0, 0.0, 0.0), 1: (100.5, 20.0, -5.0), 2: (300.0, 0.0, 0.0)}
CONTEXT = MachineContext(datum_table=TABLE)


def checked(body: str, context: MachineContext = CONTEXT):
    return checked_program("0 BEGIN PGM T MM\n" + body + "\nEND PGM T MM\n", context)


def ends(prog) -> list[list[float]]:
    return [np.round(b.target, 9).tolist() for b in prog.blocks]


def test_datum_table_row_shifts_by_its_x_y_z():
    # Fusion 360's generic Heidenhain post, onOpen/onSection with a work offset n > 0: 'CYCL DEF 7.0 DATUM SHIFT',
    # 'CYCL DEF 7.1 #n' (TNC 640 cycle programming manual, cycle 7: "#n" takes row n of the active datum table;
    # TNC7 user's manual 81762x-17, "Datum table *.d": X, Y, Z shift the workpiece coordinates). Row 1 is
    # 100.5/20/-5: X+10 Y+10 Z+5 is 110.5/30/0. It was refused as 'not supported'.
    prog = checked("1 CYCL DEF 7.0 DATUM SHIFT\n2 CYCL DEF 7.1 #1\n3 L X+10 Y+10 Z+5 R0 FMAX\n"
                   "4 CYCL DEF 7.0 DATUM SHIFT\n5 CYCL DEF 7.1 #0\n6 L X+10 FMAX")
    assert ends(prog) == [[110.5, 30.0, 0.0], [10.0, 30.0, 0.0]]  # row 0: X+10 moves X alone


def test_datum_table_row_replaces_every_axis_of_the_shift_before():
    # a table row sets X, Y and Z (row 2 has Y and Z empty: 0), not only the axes a 7.1 X.. block names: the
    # shift of Y+7 before it is gone
    prog = checked("1 CYCL DEF 7.0 DATUM SHIFT\n2 CYCL DEF 7.1 Y+7\n3 CYCL DEF 7.0 DATUM SHIFT\n4 CYCL DEF 7.1 #2\n"
                   "5 L X+0 Y+0 Z+5 R0 FMAX")
    assert ends(prog) == [[300.0, 0.0, 5.0]]


def test_datum_table_row_from_a_q_parameter_and_in_inch():
    # '#Q5' takes the row from a Q parameter; the table is in mm whatever the program's unit: 1 in in an INCH
    # program after row 1 is 25.4 + 100.5
    prog = checked("1 Q5 = 1\n2 CYCL DEF 7.0 DATUM SHIFT\n3 CYCL DEF 7.1 #Q5\n4 L X+0 Y+0 Z+5 R0 FMAX")
    assert ends(prog) == [[100.5, 20.0, 0.0]]
    inch = checked_program("0 BEGIN PGM T INCH\n1 CYCL DEF 7.0 DATUM SHIFT\n2 CYCL DEF 7.1 #1\n"
                           "3 L X+1 Y+0 Z+0 R0 FMAX\n4 END PGM T INCH\n", CONTEXT)
    assert ends(inch) == [[125.9, 20.0, -5.0]]


def test_trans_datum_table_tabline_selects_a_row_as_cycle_7_does():
    # TNC 640 user's manual, "TRANS DATUM": 'TRANS DATUM TABLE TABLINE 1' shifts to row 1 of the active datum table,
    # as 'CYCL DEF 7.1 #1' does (TABLINE Q7 from a Q parameter); it was refused as 'TRANS DATUM without an axis
    # value'. Row 1 is 100.5/20/-5, row 2 300/0/0.
    prog = checked("1 L X+0 Y+0 Z+5 R0 FMAX\n2 TRANS DATUM TABLE TABLINE 1\n3 L X+10 Y+10 FMAX\n4 Q7 = 2\n"
                   "5 TRANS DATUM TABLE TABLINEQ7\n6 L X+0 Y+0 Z+5 FMAX\n7 TRANS DATUM RESET\n8 L X+0 Y+0 FMAX")
    assert ends(prog) == [[0.0, 0.0, 5.0], [110.5, 30.0, 5.0], [300.0, 0.0, 5.0], [0.0, 0.0, 5.0]]
    # a table file of its own in the block: vcnc reads the context's table only, and says so
    with pytest.raises(GCodeError, match=r"t\.h:2:\d+: TRANS DATUM TABLE with its own table '\"TNC:\\\\ZS\.D\"'"):
        parse_heidenhain('0 BEGIN PGM T MM\n1 TRANS DATUM TABLE TABLE "TNC:\\ZS.D" TABLINE 1\n2 END PGM T MM\n',
                         source="t.h", context=CONTEXT)


def test_probed_datum_written_to_the_datum_table_is_the_row_cycle_7_selects():
    # 'TCH PROBE 417 ... Q305=+0 ;NR. IN TABELLE ... Q303=+1 ;MESSWERT-UEBERGABE' in the set's shop program writes the
    # preset; Q303=0 writes row Q305 of the datum table instead ("Write determined datum in the active datum table.
    # The reference system is the active workpiece coordinate system", iTNC 530 cycle manual 15.6, Q303), which
    # vcnc noted and dropped. The D40 hole about 50/30 (the nominal workpiece) with Q331=+10 Q332=+0: row 3 is the
    # shift 40/30/0 that puts the centre at X+10 Y+0; it takes effect with 'CYCL DEF 7.1 #3', not before.
    prog = checked("1 TOOL CALL 100 Z S50\n2 L X+50 Y+30 Z+55 R0 FMAX\n3 TCH PROBE 412 DATUM INSIDE CIRCLE Q321=+50 "
                   "Q322=+30 Q262=+40 Q325=+0 Q247=+90 Q261=-3 Q320=+2 Q260=+5 Q301=+1 Q305=+3 Q331=+10 Q332=+0 "
                   "Q303=+0 Q423=4 Q365=+1\n4 L X+0 Y+0 Z+5 FMAX\n5 CYCL DEF 7.0 DATUM SHIFT\n6 CYCL DEF 7.1 #3\n"
                   "7 L X+10 Y+0 Z+5 FMAX", MachineContext())
    assert [e for e, b in zip(ends(prog), prog.blocks) if b.line in (5, 8)] == [[0.0, 0.0, 5.0], [50.0, 30.0, 5.0]]


@pytest.mark.parametrize(("context", "row", "words"), [
    (MachineContext(), "#1", r"row 1 of the datum table is not known \(the machine context has no datum table\)"),
    (CONTEXT, "#7", r"row 7 of the datum table is not known \(the datum table has rows 0, 1, 2\)"),
    (CONTEXT, "#-1", r"malformed datum table row '#-1'"),
])
def test_datum_table_row_the_table_lacks_is_an_error_naming_it(context, row, words):
    # a TNC needs an active datum table holding the row ("To use a datum table, you must activate it", TNC7
    # user's manual): without it vcnc stops at the block, naming the row and where to give the table
    with pytest.raises(GCodeError, match=r"t\.h:4:16: cycle 7: " + words):
        parse_heidenhain(f"0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+5 R0 FMAX\n2 CYCL DEF 7.0 DATUM SHIFT\n"
                         f"3 CYCL DEF 7.1 {row}\n4 L X+1 FMAX\n5 END PGM T MM\n", source="t.h", context=context)


def test_read_datum_table_file(tmp_path):
    # the TNC's .D file: fixed widths under the header's names, an empty field 0, columns past Z read past
    path = tmp_path / "ZEROSHIFT.D"
    path.write_text("BEGIN ZEROSHIFT.D MM\nD    X           Y           Z           C        DOC\n"
                    "0    +0          +0          +0\n1    +100.5      +20         -5          +90      vise 1\n"
                    "2    +300\n[END]\n")
    table = read_datum_table(str(path))
    assert {k: v.tolist() for k, v in table.items()} == {0: [0, 0, 0], 1: [100.5, 20, -5], 2: [300, 0, 0]}
    inch = tmp_path / "INCH.D"
    inch.write_text("BEGIN INCH.D INCH\nD    X           Y           Z\n1    +1          +2          -1\n[END]\n")
    assert read_datum_table(str(inch))[1].tolist() == [25.4, 50.8, -25.4]


@pytest.mark.parametrize(("text", "words"), [
    ("BEGIN TOOL.T MM\nT  L  R\n", r"1: not a Heidenhain datum table; expected a first line BEGIN <name>\.D"),
    ("BEGIN ZS.D MM\nX Y Z\n", r"2: Heidenhain datum table without its header line"),
    ("BEGIN ZS.D MM\nD    X\n1    +1,5\n", r"3: column X holds '\+1,5', not a number"),
    ("BEGIN ZS.D MM\nD    X\nA    +1\n", r"3: row number 'A' is not a whole number"),
])
def test_read_datum_table_errors_name_file_and_line(tmp_path, text, words):
    path = tmp_path / "ZS.D"
    path.write_text(text)
    with pytest.raises(InputError, match=r"ZS\.D:" + words):
        read_datum_table(str(path))


def test_datum_table_on_the_command_line(tmp_path, capsys):
    from vcnc.cli import main

    program = tmp_path / "p.h"
    program.write_text("0 BEGIN PGM P MM\n1 CYCL DEF 7.0 DATUM SHIFT\n2 CYCL DEF 7.1 #1\n3 L X+0 Y+0 Z+5 R0 FMAX\n"
                       "4 END PGM P MM\n")
    table = tmp_path / "ZS.D"
    table.write_text("BEGIN ZS.D MM\nD    X           Y           Z\n1    +100.5      +20         -5\n[END]\n")
    blocks = tmp_path / "b.csv"
    assert main(["interpolate", str(program), "-o", str(tmp_path / "t.csv"), "--blocks", str(blocks),
                 "--datum-table", str(table)]) == 0
    assert blocks.read_text().splitlines()[1].split(",")[3:6] == ["100.5", "20", "0"]
    assert main(["interpolate", str(program), "-o", str(tmp_path / "t.csv")]) == 2
    assert "p.h:3:16: cycle 7: row 1 of the datum table" in capsys.readouterr().err
    # the table is an input the outputs must not replace
    assert main(["interpolate", str(program), "-o", str(table), "--datum-table", str(table)]) == 2
    assert "it is the input" in capsys.readouterr().err and table.read_text().startswith("BEGIN ZS.D MM")


def test_c_arc_starting_on_its_centre_names_the_circle_centre_cc():
    # the corpus' 0184_CIRSTUD.h (aamorim1913/AptPostProcessor): 'CC X+0 Y+0', the tool at X0 Y0, then 'C DR+'. A C
    # arc runs about CC from where the tool stands, so it has radius 0 there and the TNC stops; vcnc refused it
    # with the ISO wording "expected a centre offset I/J/K != 0", which a Klartext program has no words for
    with pytest.raises(GCodeError, match=r"t\.h:5:1: C arc of radius zero: the tool stands on the circle centre CC "
                                         r"\(got 'C DR\+'\); expected a CC away from the start point"):
        parse_heidenhain("0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+5 R0 FMAX\n2 CC X+0 Y+0\n3 L Z+0 F100\nC DR+\n"
                         "6 END PGM T MM\n", source="t.h", context=CONTEXT)
    prog = checked("1 L X+10 Y+0 Z+5 R0 FMAX\n2 CC X+0 Y+0\n3 C DR+ F100")  # away from CC: the full circle runs
    assert [b.kind for b in prog.blocks] == ["rapid", "arc"] and ends(prog)[-1] == [10.0, 0.0, 5.0]


def test_datum_table_in_a_machine_file(tmp_path):
    # [program] datum_table = "ZEROSHIFT.D", relative to the machine file, as tool_table is
    from vcnc.engine.machine import builtin_machine_text, load_machine

    (tmp_path / "ZEROSHIFT.D").write_text("BEGIN ZEROSHIFT.D MM\nD    X           Y           Z\n"
                                          "3    +1          +2          +3\n[END]\n")
    machine = tmp_path / "m.toml"
    machine.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndatum_table = "ZEROSHIFT.D"\n')
    assert load_machine(machine).context.datum_table[3].tolist() == [1.0, 2.0, 3.0]
    machine.write_text(builtin_machine_text("fadal-pid") + '\n[program]\ndatum_table = "MISSING.D"\n')
    with pytest.raises(InputError, match=r"m\.toml:\d+: .*MISSING\.D: cannot read datum table"):
        load_machine(machine)
