"""ISO programs of the fourth wild set (issue 18): what their own controls run, with end points derived by hand."""

from __future__ import annotations

import dataclasses

import pytest

from interpolators import parse_program
from interpolators.context import DIALECTS, MachineContext
from tests.interpolators.iso_checks import checked_iso
from vcnc.errors import GCodeError

CTX = MachineContext(work_offsets={"G54": (100.0, 50.0, -20.0)}, home=(0.0, 0.0, 100.0))


def _in_dialect(name: str) -> MachineContext:
    return dataclasses.replace(CTX, dialect=DIALECTS[name])


def test_fanuc_skips_the_text_after_the_first_percent_of_the_file():
    # aardel/nc-file-converter test.nc opens with "%1" (Fanuc B-63524EN/01 8 "File format": data between
    # the first % and the next LF is skipped). G54 at (100, 50, -20): X1.5 Y2 Z0.1 -> (101.5, 52, -19.9),
    # the feed to X2.5 Y3 -> (102.5, 53, -19.9) at 100 mm/min, then Z1 -> -19.
    text = "%1 (LABEL\nG21 G54 G0 G40 G49 G80 G90\nX1.5 Y2.0 Z0.1\nG1 X2.5 Y3.0 F100\nG0 Z1.0\nM30\n%\n"
    prog = checked_iso(text, _in_dialect("fanuc"))
    assert [b.target.tolist() for b in prog.blocks] == [[101.5, 52, -19.9], [102.5, 53, -19.9], [102.5, 53, -19]]
    assert prog.blocks[1].feed == pytest.approx(100 / 60)


def test_fanuc_percent_with_text_after_the_first_stays_refused():
    # the first '%' line is the label; a second one with text is no block of any control
    with pytest.raises(GCodeError, match=r":3:1: '%' must stand alone on its line \(got '%2000'\)"):
        parse_program("%\nG21 G90 G0 X1\n%2000\nG0 X2\n", context=_in_dialect("fanuc"))


@pytest.mark.parametrize("name", ["linuxcnc", "haas"])  # grbl: a CNCjs macro line (test_iso_programs)
def test_percent_with_text_is_refused_outside_fanuc(name):
    with pytest.raises(GCodeError, match=r":1:1: '%' must stand alone on its line \(got '%1'\)"):
        parse_program("%1\nG21 G90 G0 X1\n", context=_in_dialect(name))


def test_linuxcnc_o_word_keywords_may_be_spelt_with_blanks():
    # machinekit g29.ngc ends its subroutine with "o<g29> end sub": LinuxCNC drops blanks outside comments
    # before reading a line (interp_internal.cc close_and_downcase), so "end sub" is "endsub", "else if"
    # "elseif", "end if" "endif" and "end while" "endwhile". The if takes its first branch: X1; the
    # subroutine called with 3 moves Y to 3; the while runs twice (#2 = 0, 1): X11, X12 -- in G54
    # (100, 50, -20), the power-on work system.
    text = ("G21 G90 G0 X0 Y0 Z0\nF100\no100 if [1 GT 0]\nG1 X1\no100 else if [1 LT 0]\nG1 X2\no100 end if\n"
            "o<s> sub\nG1 Y#1\no<s> end sub\no<s> call [3]\n#2 = 0\no101 while [#2 LT 2]\nG1 X[11 + #2]\n"
            "#2 = [#2 + 1]\no101 END WHILE\nM2\n")
    prog = checked_iso(text, _in_dialect("linuxcnc"))
    ends = [[0, 0, 0], [1, 0, 0], [1, 3, 0], [11, 3, 0], [12, 3, 0]]
    assert [b.target.tolist() for b in prog.blocks] == [[x + 100, y + 50, z - 20] for x, y, z in ends]


def test_an_unknown_o_word_keyword_is_still_named():
    with pytest.raises(GCodeError, match=r"O-word 'end': unknown O-word keyword"):
        parse_program("G21\no100 sub\nG0 X1\no100 end\n", context=_in_dialect("linuxcnc"))


@pytest.mark.parametrize(("name", "what"), [("linuxcnc", "remapped or user M code"),
                                            ("grbl", "machine- or firmware-specific M code"),
                                            ("fanuc", "machine- or firmware-specific M code")])
def test_m_codes_above_m199_are_named_as_their_control_knows_them(name, what):
    # armindevelopertec-max (Inkscape unicorn plotter output, "M300 S30" pen servo): grbl has no remaps
    with pytest.raises(GCodeError, match=f"{what} 'M300' \\(above M199"):
        parse_program("M300 S30\nG21 G90 G0 X1\n", context=_in_dialect(name))


@pytest.mark.parametrize("name", ["fanuc", "linuxcnc"])
@pytest.mark.parametrize(("header", "what"), [("%_N_PART_MPF", "Siemens SINUMERIK 840D program header"),
                                              ("%MPF  90", "Siemens SINUMERIK main/subprogram header"),
                                              ("%PM", "Philips/MillPlus program header")])
def test_a_foreign_control_s_file_header_is_named(name, header, what):
    # GCodeProjects/GCodeWorkShop EXAMPLES: SINUMERIK 840D/850 and Philips files are no ISO programs; the
    # Fanuc label skip must not run into their native syntax
    with pytest.raises(GCodeError, match=f":1:1: {what} '{header}': that control's native language is not ISO"):
        parse_program(f"{header}\nR11=384.553\nG0 X1\n", context=_in_dialect(name))


def test_g92_with_s_alone_is_named_a_lathe_spindle_limit():
    with pytest.raises(GCodeError, match=r"2:1: G92 needs at least one axis word \(G92 S alone is the Fanuc lathe"):
        parse_program("G21\nG92 S500\n", context=_in_dialect("fanuc"))


def test_fanuc_vacant_words_and_g04_x_leave_the_tool_where_it_is():
    # mojimould Renishaw macros O9701 ("G01X#31Y#32F#119" with #31 #32 #119 never set) and O9890
    # ("G04X1.0"): a word whose variable is vacant is left out (Fanuc custom macro "Undefined variable"),
    # so the block moves nothing; G04 X is a dwell of 1 s, not a move to X1. In G54 (100, 50, -20):
    # the rapid to (105, 55, -20), the dwell there, the feed to X6 -> (106, 55, -20).
    text = "G21 G90 G54 F100\nG0 X5 Y5 Z0\nG01 X#31 Y#32 F#119\nG04 X1.0\nG1 X6\nM30\n"
    prog = checked_iso(text, _in_dialect("fanuc"))
    assert [b.target.tolist() for b in prog.blocks] == [[105, 55, -20], [105, 55, -20], [106, 55, -20]]
    assert prog.blocks[1].dwell == pytest.approx(1.0)
