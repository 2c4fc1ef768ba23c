"""Program flow of ISO G-code: O-word subroutines and control flow, Fanuc M98/M99 (Haas M97) subprograms.

LinuxCNC "O Codes" (https://linuxcnc.org/docs/html/gcode/o-code.html):

* ``o100 sub`` ... ``o100 endsub`` defines a subroutine (also ``o<name> sub``), skipped where it
  stands; ``o100 call [a] [b] ...`` runs it with ``#1``, ``#2``, ... = the arguments (local),
  ``o100 return [v]`` / ``endsub [v]`` leave it (the value goes to ``#<_value>``);
* ``if``/``elseif``/``else``/``endif``, ``while``/``endwhile``, ``do``/``while``,
  ``repeat [n]``/``endrepeat``, ``break`` and ``continue``, each tied by its O number or name;
* ``o<name> call`` of a subroutine not in the file runs ``<name>.ngc`` of the program's folder
  or of a folder of the dialect's ``subroutine_path``, as LinuxCNC finds it on its INI's
  SUBROUTINE_PATH; a numbered subroutine in such a file cannot be called (LinuxCNC reads the file
  from its ``o<name> sub`` on), and subroutine definitions do not nest.

Fanuc/Haas subprograms (Haas mill operator's manual, "M98 Subprogram Call"): ``M98 P1000 L3``
runs the program ``O1000`` three times, from the same file or else from the program file of its
folder that holds ``O1000`` (the control keeps programs by number); ``M99`` returns, ``M99 P<n>``
to the block ``N<n>`` of the calling program, and in the main program ``M99`` ends it (the control
would rewind; vcnc runs the program once). ``M98 P1000 Q20`` starts ``O1000`` at its block ``N20``
(Mitsubishi's and Mach4's form, :func:`_start_block`). Haas ``M97 P1000 L2`` ("M97 Local Sub-Program Call")
runs the blocks from ``N1000`` of the same program to its ``M99`` twice, then the block after the
call (the main program ends with M30 before such local subprograms).

Fanuc/Haas custom macro B simple call ``G65 P9001 L2 A1. C2.5 V10100.`` (Fanuc Series 16i/18i
operator's manual B-63684EN, 16 "Custom macro", "Simple call (G65)"; Haas mill operator's manual,
"G65 Macro Subroutine Call" and "Local Variables"): runs program ``O9001`` (found as for M98) L
times with a new set of locals ``#1``-``#33``, vacant but for the arguments: A B C -> #1 #2 #3,
I J K -> #4 #5 #6, D E F -> #7 #8 #9, H -> #11, M -> #13, Q R S T U V W X Y Z -> #17 .. #26, and
the n-th repeated I J K -> #(3n+1) #(3n+2) #(3n+3) (argument specification II; the later word wins).
The arguments are set on the first repetition only; ``M99`` returns. An argument written as a
number without a decimal point is an error: the control scales it by its least input increment
("The value of an argument passed without a decimal point may vary according to the system
configuration of the machine"). The rest of macro B, ``IF [..] GOTO n``, ``IF [..] THEN``,
``GOTO n`` and ``WHILE [..] DO m`` / ``END m``, runs as :mod:`interpolators.iso_macro` describes.

A comment ``(ABORT, text)`` ends the run where it is reached with an error carrying the text, its
parameters substituted (LinuxCNC G-code overview, "Abort Messages", "Comment Parameters"); the other
active comments (``(MSG, ..)``, ``(DEBUG, ..)``, ``(PRINT, ..)``, ``(LOG, ..)``,
:mod:`interpolators.iso_messages`) go to the caller's ``on_comment`` where the run reaches them, after
the parameters the line sets (LinuxCNC sets them before it executes the block).

A ``:`` starting a line is the ISO-code program-number address (``O`` of EIA code, e.g. ``:1234``).

A ``%`` stands alone on its line (LinuxCNC: the percent line of a program delimited by percents;
grbl ignores it). Under Fanuc (``tape_leader``) the text after the first ``%`` of a file up to the end
of its line is skipped (Fanuc Series 16i/18i-TB operator's manual B-63524EN/01, 8 "Data input/output",
"File format": "A file starts with % or LF, followed by the actual data. [...] In a read operation,
data between the first % and the next LF is skipped"): ``%1`` or ``%2000`` opening a file is its
label, not a block. A later ``%`` line with text stays an error, and so does a first one that holds
bare CRs (a file of mixed line ends, whose blocks the skip would swallow unseen).

:func:`run` yields the lines to execute in order, with their words read (parameters and
expressions evaluated by :mod:`interpolators.iso_params`).
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable, Generator, Iterator
from pathlib import Path
from typing import NoReturn

from interpolators._words import Where, lines_of, program_text
from interpolators.iso_macro import MAX_LOOP_PASSES, MacroFlow
from interpolators.iso_macro_args import macro_arguments
from interpolators.iso_messages import active_comment, comment_output, expand
from interpolators.iso_modal_call import MODAL_CALL_CODES, ModalCall, ModalCalls
from interpolators.iso_params import (
    Parameters,
    address_values,
    evaluate_at,
    evaluate_condition,
    has_parameters,
    read_line,
)
from interpolators.iso_words import PLAIN_NUMBER, Word, block_comment, plain_words, read_words, strip_comments
from vcnc.core.errors import GCodeError
from vcnc.core.text import BinaryDataError

__all__ = ["FlowLine", "run", "one_line_end", "sinumerik_construct", "MAX_EXECUTED_LINES", "MAX_CALL_LEVELS",
           "SKIP_AFTER_NUMBER", "BLOCK_DELETE_RUN"]

#: Largest number of lines a program may execute beyond its own length (a guard against endless loops: a
#: loop is stopped within seconds, before its blocks fill the memory; a CAM file of any length runs once).
MAX_EXECUTED_LINES = 300_000

#: Deepest nesting of subroutine and subprogram calls (O-word call, M98, G65): LinuxCNC refuses a tenth level
#: (interp_internal.hh INTERP_SUB_ROUTINE_LEVELS = 10, interp_o_word.cc NCE_TOO_MANY_SUBROUTINE_LEVELS); Fanuc
#: nests subprograms ten deep. A call that recurses without end stops here, at its line, not at the line limit.
MAX_CALL_LEVELS = 10

#: An O-word line: label (``<name>``, a number, or a computed number ``#1``, ``#<n>``, ``[expr]``), keyword, rest.
_O_LINE = re.compile(r"^\s*(?:[nN]\s*\d+\s*)?[oO]\s*(<[^>]*>|\d+|#\s*<[^>]*>|#\s*\d+|\[(?:[^\[\]]|\[[^\[\]]*\])*\])"
                     r"\s*([a-zA-Z]+)?(.*)$")
#: A line of words of a letter (not O) and a plain number, and blanks: an ordinary block (no O-word, program
#: number, comment, macro statement, ``%``, ``/`` or header can be one), of which only the N number is indexed.
_PLAIN_BLOCK = re.compile(r"[ \t]*(?:[A-NP-Za-np-z][ \t]*" + PLAIN_NUMBER + r"[ \t]*)*")
_FANUC_PROGRAM = re.compile(r"^\s*(?:[oO]|:)\s*(\d+)\s*$")
#: A program name that is not a Fanuc number ("O7997A", "OWASHER": shop programs name variants so),
#: alone on its line: the name of the program; M98 cannot call it (Fanuc O numbers are digits).
#: File suffixes of part programs searched for a subprogram in another file.
_PROGRAM_SUFFIXES = frozenset({".nc", ".ngc", ".cnc", ".tap", ".gcode", ".txt", ".iso", ".min", ".mpf", ".spf", ""})
_NAMED_PROGRAM = re.compile(r"^\s*[oO]\s*(?:\d+[a-zA-Z]\w*|[a-zA-Z]\w*)\s*$")
_KEYWORDS = {"sub", "endsub", "call", "return", "if", "elseif", "else", "endif", "while", "endwhile", "do",
             "repeat", "endrepeat", "break", "continue"}
#: An O-word keyword written with blanks between its letters ("end sub", "else if"): LinuxCNC drops blanks and
#: tabs outside comments before it reads a line (interp_internal.cc close_and_downcase), so they are one word.
_SPACED_KEYWORD = re.compile("(" + "|".join("[ \t]*".join(k) for k in sorted(_KEYWORDS, key=len, reverse=True))
                             + ")(?![a-zA-Z])", re.IGNORECASE)


#: File headers of controls whose native language is not ISO G-code: Siemens SINUMERIK 840D ("%_N_NAME_MPF"),
#: SINUMERIK 8xx ("%MPF 90", "%SPF 12": main and subprogram numbers), Philips / Heidenhain MillPlus ("%PM"),
#: Okuma OSP ("$NAME.MIN%": a file sent to the control starts with its name, .MIN a main program, .SUB/.SSB/.SDF
#: subprograms, .LIB a library; our reading of the OSP examples "$OKUMA.SSB%", "$BR0137.MIN%" that GCodeWorkShop
#: ships, whose programs go on in OSP's own language: CALL O.., VC variables, N-label GOTO).
_FOREIGN_HEADERS = ((re.compile(r"%_N_", re.I), "Siemens SINUMERIK 840D program header"),
                    (re.compile(r"%\s*[MS]PF\b", re.I), "Siemens SINUMERIK main/subprogram header"),
                    (re.compile(r"%\s*PM\b", re.I), "Philips/MillPlus program header"),
                    (re.compile(r"\$[^\s%]+\.(?:MIN|SUB|SSB|SDF|MSB|LIB)%", re.I), "Okuma OSP program file header"))


#: Constructs of SINUMERIK's own language that no ISO G-code control reads, each with what it is. Siemens,
#: SINUMERIK 840D "Manual, 5-axis machining", 7.1 "Overview of higher-order functions" ("commands that go beyond
#: the requirements laid down in DIN 66025": CIP, CT, TURN=, CR=, AP=, RP=, AR=, I1= ...), and the SINUMERIK
#: programming manuals' "Fundamentals" (T="name", X=AC(..)/IC(..), R parameters, DEF, GOTOF/GOTOB, frames TRANS
#: ... AMIRROR, MSG("..")) and "Job planning" (CYCLE81(..) ... cycle calls, MCALL, EXTCALL). Read on a line
#: without its ';' comment and its ISO '(..)' comments (a '(' right after a name is a call, kept).
_SINUMERIK = ((re.compile(r'\bT\s*=\s*"'), 'T="..." (a tool called by its name)'),
              (re.compile(r"\b[A-Z]{1,2}\d*\s*=\s*(?:AC|IC|DC|ACP|ACN)\s*\("),
               "X=AC(..)/IC(..) (absolute or incremental per word)"),
              (re.compile(r"(?<![\w#])(?:CR|AR|AP|RP|TURN|I1|J1|K1)\s*="), "CR=/AR=/AP=/RP=/TURN= (arc radius, "
               "opening angle, polar words)"),
              (re.compile(r"(?<![\w#<])R\d+\s*=(?!=)"), "R1=.. (an R parameter set)"),
              (re.compile(r"\b[A-Z]\s*=\s*-?R\d+\b"), "X=R1 (an axis word from an R parameter)"),
              (re.compile(r"\b(?:CYCLE\d{2,3}|POCKET\d|SLOT\d|LONGHOLE|HOLES\d|MCALL|EXTCALL|WORKPIECE)\s*\("),
               "a cycle call NAME(..)"),
              (re.compile(r'\bMSG\s*\(\s*"'), 'MSG("..") (a message)'),
              (re.compile(r"\bDEF\s+(?:REAL|INT|BOOL|STRING|CHAR|AXIS|FRAME)\b"), "DEF (a variable definition)"),
              (re.compile(r"\b(?:GOTOF|GOTOB|GOTOC|ENDWHILE|ENDLOOP|ENDFOR|TRAORI|TRAFOOF|G500|G64[1-5]|FFWON|FFWOF|"
                          r"SUPA|DIAMON|DIAMOF|SPOS|ATRANS|AROT|ASCALE|AMIRROR)\b"), "a SINUMERIK keyword"),
              (re.compile(r"^\s*(?:N\d+\s+)?(?:TRANS|ROT|SCALE|MIRROR)\b"), "TRANS/ROT/SCALE/MIRROR (a programmable "
               "frame)"))
_ISO_COMMENT = re.compile(r"(?<![A-Za-z0-9_])\([^()]*\)")


def sinumerik_construct(text: str) -> str | None:
    """Where ``text`` (a program) first uses a construct of SINUMERIK's language (:data:`_SINUMERIK`): "line N
    'code': <what>", or None. Said with an ISO reader's error, so that a Siemens program is named for what it is
    rather than by the first word ISO G-code reads otherwise."""
    for number, line in enumerate(text.splitlines()[:2000], start=1):
        code = _ISO_COMMENT.sub("", line.split(";", 1)[0])
        for pattern, what in _SINUMERIK:
            if pattern.search(code):
                shown = code.strip() if len(code.strip()) <= 60 else code.strip()[:57] + "..."
                return f"line {number} {shown!r}: {what}"
    return None


#: The first block of a Heidenhain TNC program in DIN/ISO: '%', the program name and the unit, G71 (mm) or G70
#: (inch), ended by '*' ("%NAME G71 *"; the last block repeats it after N99999999). HEIDENHAIN TNC 320 ISO
#: Programming User's Manual 10/2017, 3.2 "Structure of an NC program in ISO format": "The first block of a
#: program is identified by %, the program name and the active unit of measure"; TNC 426/430 ISO manual, 4.6.
_HEIDENHAIN_ISO_HEADER = re.compile(r"%[ \t]*[A-Za-z0-9_.\-]+[ \t]+G7[01][ \t]*\*?[ \t]*$", re.I)


def refuse_heidenhain_iso(line: str, where: Where) -> None:
    """Refuse ``line`` if it is the first block of a Heidenhain TNC program in DIN/ISO
    (:data:`_HEIDENHAIN_ISO_HEADER`), naming it: vcnc reads the TNC's conversational language, not its ISO mode."""
    if _HEIDENHAIN_ISO_HEADER.match(line):
        where.fail(f"Heidenhain DIN/ISO program header {line!r} (a TNC program in ISO mode: '%NAME G71 *' ... "
                   "'N99999999 %NAME G71 *'): not supported; vcnc reads Heidenhain conversational and ISO "
                   "G-code of Fanuc/Haas/LinuxCNC/grbl", column=1, text=line,
                   expected="a Heidenhain conversational program (BEGIN PGM ... END PGM) or an ISO G-code program")


def _refuse_colon_block(line: str, column: int, where: Where) -> NoReturn:
    """The error for a line that starts with ':' but is no ISO program number (':1234')."""
    both = _FANUC_PROGRAM.match(line[1:])
    if both:
        # ":O1001": both program-number addresses at once (':' stands for O in ISO code); our reading: no
        # control's manual shows the pair, so the program number is not guessed from it
        where.fail("':' and 'O' both before the program number: ':' is ISO code's program-number address, O EIA "
                   "code's; a program number takes one of them", column=column, text=line,
                   expected=f"O{both.group(1)} or :{both.group(1)}")
    # ISO 6983-1 also knows ':' before a block as the alignment function (a "main block" where a program may
    # restart), which NUM controls and Fusion's NUM post write (": G90 G40 G94", ":T3 M6"); those programs go
    # on in NUM's own forms (I J the arc centre's coordinates): not read here
    where.fail("':' (the program-number address of ISO code, O of EIA code) without a program number (before a "
               "block: ISO 6983's main-block mark, as NUM controls write it; NUM programs are not supported)",
               column=column, text=line, expected="':' followed by the program number, e.g. :1234")


def _refuse_colon(line: str, code: str, where: Where) -> NoReturn:
    """The error for a line that starts with ':' (``code``: without its comments) and is not read as a program
    number: a program number ``:1248`` where the dialect has no ISO-code address (LinuxCNC's rs274ngc knows no ':',
    interp_read.cc ``read_one_item``: rs274 stops at ':1248' with "Bad character ':' used"; its numbered programs are
    O-words, o-code.adoc "Fanuc-Style Numbered Programs"), else :func:`_refuse_colon_block`."""
    column = code.index(":") + 1
    number = _FANUC_PROGRAM.match(code)
    if number is None:
        _refuse_colon_block(line, column, where)
    n = number.group(1)
    where.fail("':' before a program number (ISO code's program-number address, O of EIA code): LinuxCNC refuses "
               "it (rs274: \"Bad character ':' used\")", column=column, text=line,
               expected=f"O{n} (--dialect fanuc reads :{n} as O{n})")


def _refuse_foreign_header(line: str, where: Where) -> None:
    """Refuse a ``%`` line that heads a program of a control whose native language is not ISO G-code, or a
    Heidenhain TNC program in DIN/ISO (:func:`refuse_heidenhain_iso`)."""
    refuse_heidenhain_iso(line, where)
    for pattern, what in _FOREIGN_HEADERS:
        if pattern.match(line):
            where.fail(f"{what} {line!r}: that control's native language is not ISO G-code (vcnc reads ISO "
                       "G-code and Heidenhain conversational)", column=1, text=line,
                       expected="an ISO G-code program (Fanuc, Haas, LinuxCNC, grbl)")


def _refuse_folder_line(line: str, where: Where) -> None:
    """Refuse a Fanuc folder line ``&F=/USER/PATH1/``: the Series 30i/0i-F controls punch all the programs of
    their memory into one file, each folder opened by such a line (``&F=//CNC_MEM/``, ``&F=/USER/LIBRARY/``);
    the file is a backup of many programs, not one to run (our reading of such backups: no manual at hand)."""
    where.fail(f"Fanuc folder line {line!r}: this file is a backup of the control's program folders (an all-"
               "program punch of a Series 30i/0i-F memory), not one program", column=1, text=line,
               expected="one program (O<number> ... M30), e.g. the one to run cut out of the backup")


_SKIP_LEVEL = re.compile(r"[ \t]*/([1-9])")
#: The sequence number of a line whose next character is '/' ("N45 /G1 X10", "N45/2 G1 X10").
SKIP_AFTER_NUMBER = re.compile(r"[ \t]*[Nn][ \t]*\d+(?:\.\d*)?[ \t]*(?=/)")
#: The note of a line that starts with '/' and runs (the block delete switch off), an NC block or a macro statement.
BLOCK_DELETE_RUN = "/ block delete lines run (switch off)"


def _block_delete(code: str, where: Where, *, levels: bool, start: int = 0) -> str:
    """A line opened by '/' (block delete; ``start``: the index its '/' follows, with blanks between, as after a
    sequence number), the '/' blanked: the line runs, as with its switch off. With
    ``levels`` (Fanuc) '/1'-'/9' opens it as well: the optional block skip of level n, '/1' the same as '/'
    (FANUC 0i-MF operator's manual, "Optional block skip", the additional optional block skip option;
    ISG kernel "Extended skipping (skip levels)": '/1'-'/10', '/' and '/1' one switch); its switch off too.
    Without (LinuxCNC, Haas, grbl, whose manuals give only '/') the level is named, with the dialect that
    reads it: a Mazak program of Keycult's writes "/1 #[#22 + 1] = 0" per level."""
    m = _SKIP_LEVEL.match(code, start)
    if m is None:
        return code.replace("/", " ", 1)
    if not levels:
        where.fail(f"'/{m.group(1)}': optional block skip level {m.group(1)} (Fanuc's additional optional block "
                   "skip /2-/9), which this dialect does not have (--dialect fanuc reads it)",
                   column=m.start(1), text=f"/{m.group(1)}", expected="'/' block delete")
    return code[:start] + " " * (m.end() - start) + code[m.end():]


def _skip_after_number(code: str, where: Where, *, levels: bool, reads: bool) -> str:
    """A '/' right after the line's sequence number (``N45 /G1 X10``), read as the block delete of a line opened
    by it (:func:`_block_delete`: the block runs, its switch off). grbl's protocol.c drops a '/' wherever it
    stands ("Block delete NOT SUPPORTED. Ignore character."). Fanuc's "Optional block skip" (0i-MF operator's
    manual) places the '/' at the head of a block; no text at hand says what a '/' after the sequence number
    does: our reading, for Fanuc, Haas and Fadal, is that the number labels the block and the '/' still stands
    before its words, so that with the switch off the whole block runs (noted). Without ``reads`` (LinuxCNC) it
    is refused: LinuxCNC's G-code overview, "Format of a Line", orders "an optional block delete character,
    which is a slash '/'" before "an optional line number", and "'/': Block Delete" counts it "when placed first
    on a line"; rs274 stops with "Bad character '/' used"."""
    m = SKIP_AFTER_NUMBER.match(code)
    if m is None:
        return code
    if not reads:
        number = code[:m.end()].strip()
        where.fail(f"'/' after the line number {number!r}: LinuxCNC reads block delete only as a line's first "
                   "character, before its line number (G-code overview, \"Format of a Line\")", column=m.end() + 1,
                   text="/", expected=f"'/{number} ...' (the '/' first) or no '/'")
    return _block_delete(code, where, levels=levels, start=m.end())


def _keyword(code: str, m: re.Match[str] | None) -> tuple[str | None, str, int]:
    """The keyword of the O-word line ``code`` (``m`` its :data:`_O_LINE` match, None if it is none), the
    text after it and that text's 1-based column; a keyword spelt with blanks ("end sub") is joined."""
    if m is None or not m.group(2):
        return None, "", 0
    keyword = m.group(2).lower()
    if keyword not in _KEYWORDS:
        spaced = _SPACED_KEYWORD.match(code, m.start(2))
        if spaced:
            return re.sub(r"[ \t]", "", spaced.group(1)).lower(), code[spaced.end():], spaced.end() + 1
    return keyword, m.group(3), m.start(3) + 1



def one_line_end(text: str) -> str:
    """``text`` with its line ends as ``\\n``: CR LF (DOS) and LF (Unix) end a line, and in a text with
    no LF at all (classic Mac OS editors, some controls' serial output) a bare CR does. A CR alone in a
    text that has LF line ends stays part of its line (a stray CR in a comment does not split it, as
    in the Heidenhain corpus files 0199-0201), so lines are numbered as an editor shows them."""
    return text.replace("\r", "\n") if "\n" not in text else text.replace("\r\n", "\n")


@dataclasses.dataclass(frozen=True)
class FlowLine:
    """One executed line: 1-based ``line`` of its ``file``, its ``raw`` text and its ``words``."""

    line: int
    raw: str
    words: list[Word]
    file: str | None = None


@dataclasses.dataclass(frozen=True)
class _OWord:
    label: str
    keyword: str
    rest: str
    column: int  # 1-based column of the rest
    computed: int = 0  # 1-based column of a computed label (o#1 call, O[#2*10] call), else 0


@dataclasses.dataclass
class _Frame:
    return_pc: int
    start_pc: int
    repeats: int
    kind: str  # "oword" (o-call: parameter frame, endsub returns), "m98", "g65" or "g66" (M99 returns)
    #: the modal calls (:mod:`interpolators.iso_modal_call`) the frame's blocks may make: those specified before
    #: the one with this index (the frame runs its macro, or is called from there); None: all (the main program's)
    modal: int | None = None


#: The largest Fanuc program number: eight digits (Series 30i/31i/32i-B, "8-digit program number"; older controls
#: take four, O1-O9999, newer five).
MAX_FANUC_PROGRAM = 99_999_999


def _program_number(fm: re.Match, where: Where) -> None:
    """Refuse a Fanuc program number out of its range: "program number zero (O0 or O0000) is not allowed" (P. Smid,
    as quoted at https://en.cncforum.net/t/cnc-program-name-and-number-identification/382: "Programs for older Fanuc
    controls must be within the range of O1 - O9999 ... Newer controls allow 5-digit program numbers"), nor one of
    more than eight digits (:data:`MAX_FANUC_PROGRAM`)."""
    number = int(fm.group(1))
    if not 1 <= number <= MAX_FANUC_PROGRAM:
        why = "zero (O0, O0000) is not allowed" if number == 0 else f"above {MAX_FANUC_PROGRAM} (eight digits)"
        where.fail(f"program number {fm.group(0).strip()}: {why} (Fanuc)", column=fm.start(1) + 1,
                   text=fm.group(0).strip(), expected=f"O1 .. O{MAX_FANUC_PROGRAM} (O0001: program 1), or no "
                                                      "program number")


def _refuse_percent_line(s: str, code: str, where: Where, *, first: bool) -> NoReturn:
    """Refuse a line ``s`` (its ``code``) that begins with '%' and holds more, naming what it likely is: a file of
    mixed line ends, a Fanuc tape's first line, a program name after '%' on the file's ``first`` line, a CNCjs
    macro line."""
    _refuse_foreign_header(s, where)
    mixed = " (the line holds bare CRs: its file mixes CR and LF line ends)" if "\r" in s else ""
    if not mixed and re.match(r"%[ \t]*[Oo]\d", s):  # "%O1200(TOKARKA)": a Fanuc tape's first line
        mixed = (" (a Fanuc tape's first line, whose text after the '%' a Fanuc control skips: "
                 "--dialect fanuc reads it)")
    elif not mixed and re.fullmatch(r"%[A-Za-z_]\w*", s) and first:
        # the file's first line: FreeCAD's UCCNC post (uccnc_post.py) starts with "%" + the program
        # name, "%prog1"; a Fanuc control skips a tape's leader up to its end of block
        mixed = (" (a program name after the '%', as FreeCAD's UC-CNC post writes '%prog1': --dialect "
                 "fanuc skips it as a tape's leader; or a CNCjs macro line: --dialect grbl)")
    elif not mixed and re.match(r"%[ \t]*[A-Za-z_]", s):  # iso_grbl: CNCjs's "%wait", "%x0=posx"
        mixed = (" (a macro line of the CNCjs sender, which evaluates it and streams the rest to "
                 "grbl: --dialect grbl reads the file as CNCjs streams it)")
    where.fail(f"'%' must stand alone on its line{mixed}", column=code.index("%") + 1, text=s,
               expected="'%' alone")


class _Program:
    """The lines of a program, classified, with the O-word structure indexed."""

    def __init__(self, text: str, source: str | None, *, max_loop_passes: int = MAX_LOOP_PASSES,
                 subroutine_path: tuple[str, ...] = (), tape_leader: bool = False,
                 abbreviations: bool = False, skip_levels: bool = False, tape_forms: bool = True,
                 program_numbers: bool = False) -> None:
        self.source = source
        self.program_numbers = program_numbers  # Fanuc's range of O numbers: _program_number
        self.skip_levels = skip_levels
        self.tape_forms = tape_forms
        self.subroutine_path = subroutine_path
        self.tape_leader = tape_leader
        self.raw: list[str] = []
        self.sources: list[str | None] = []
        self.code: list[str | None] = []
        self.oword: dict[int, _OWord] = {}
        self.fanuc: dict[int, int] = {}
        self.by_label: dict[str, list[int]] = {}
        self.files: set[str] = set()
        self.first_line: dict[str | None, int] = {}  # index of each file's first line
        self.macro = MacroFlow(max_passes=max_loop_passes, abbreviations=abbreviations)
        self.active: dict[int, tuple[str, str]] = {}  # line -> keyword and text of its active comment
        self.span = 0
        self.plain: set[int] = set()  # lines of plain words only (iso_words.plain_words reads them)
        self._index(text, source)
        self.main_end = len(self.code)

    def _index(self, text: str, source: str | None) -> None:
        """Append the lines of ``text`` (from ``source``), classified, O-words and numbers indexed."""
        text = one_line_end(text)
        self.first_line.setdefault(source, len(self.code))
        self.span += 1  # each file, and each O program in it, is a program of its own (macro B GOTO)
        leader = self.tape_leader  # Fanuc: the rest of the file's first '%' line is skipped
        for raw in lines_of(text):
            i = len(self.code)
            self.raw.append(raw)
            self.sources.append(source)
            if _PLAIN_BLOCK.fullmatch(raw):  # most of a CAM program: nothing to index but its N number
                self.macro.add_block(i, raw, self.span)
                self.code.append(raw if raw.strip(" \t") else None)
                self.plain.add(i)
                continue
            where = self.where(i)
            if leader and raw.lstrip().startswith("%") and "\r" not in raw:  # a bare CR: see the error below
                _refuse_foreign_header(raw.strip(), where)
                leader = False
                self.macro.add_line(i, None, self.span, where)
                self.code.append(None)
                continue
            code = strip_comments(raw, where)
            comment = block_comment(raw, where)
            active = None if comment is None else active_comment(comment)
            if active is not None:
                self.active[i] = active
            s = code.strip()
            if _FANUC_PROGRAM.match(code) or _NAMED_PROGRAM.match(code):
                self.span += 1
            self.macro.add_line(i, None, self.span, where)
            if not s or s == "%":
                self.code.append(None)
                continue
            if s.startswith("$"):  # an Okuma OSP file header; other '$' words are read (and refused) as words
                _refuse_foreign_header(s, where)
            if s.upper().startswith("&F="):
                _refuse_folder_line(s, where)
            if s.startswith("%"):
                _refuse_percent_line(s, code, where, first=not any(self.code))
            if s.startswith("/"):
                code = _block_delete(code, where, levels=self.skip_levels)
            elif "/" in code:
                code = _skip_after_number(code, where, levels=self.skip_levels, reads=self.tape_forms)
            if s.startswith(":") and not (self.tape_forms and _FANUC_PROGRAM.match(code)):
                _refuse_colon(s, code, where)
            if self.macro.add_line(i, code, self.span, where) is not None:
                self.code.append(None)  # IF / GOTO / WHILE .. DO / END: run by self.macro
                continue
            m = _O_LINE.match(code)
            keyword, rest, rest_at = _keyword(code, m)
            if _NAMED_PROGRAM.match(code) and keyword not in _KEYWORDS:
                self.code.append(None)  # "O7997A", "OWASHER": the program's name
                continue
            if keyword in _KEYWORDS:
                label = m.group(1).lower().replace(" ", "")
                if label[0] in "#[":  # LinuxCNC read_o reads the number as any integer value
                    if keyword != "call":
                        where.fail(f"O-word o{m.group(1)} {keyword}: only a call may compute its O number",
                                   column=m.start(1) + 1, text=s, expected=f"o<number> {keyword}")
                    self.oword[i] = _OWord(label, keyword, rest, rest_at, computed=m.start(1) + 1)
                    self.code.append(None)
                    continue
                label = str(int(label)) if label.isdigit() else label  # o0100 is o100 (read as an integer)
                self.oword[i] = _OWord(label, keyword, rest, rest_at)
                self.by_label.setdefault(label, []).append(i)
                self.code.append(None)
                continue
            if m and m.group(2):
                # LinuxCNC interp_read.cc read_o: "Unknown control command in o word"
                where.fail(f"O-word {m.group(2)!r}: unknown O-word keyword", column=m.start(2) + 1, text=m.group(2),
                           expected="sub, endsub, call, return, if, elseif, else, endif, while, endwhile, do, "
                                    "repeat, endrepeat, break or continue")
            fm = _FANUC_PROGRAM.match(code)
            if fm:
                if self.program_numbers:
                    _program_number(fm, where)
                self.fanuc.setdefault(int(fm.group(1)), i)
                self.code.append(None)
                continue
            if m and m.group(1).startswith("<"):
                if source == self.source and all(c is None for c in self.code[self.first_line[source]:]):
                    self.code.append(None)  # "O<name>" first in the main program: its title (LinuxCNC)
                    continue
                where.fail(f"O-word o{m.group(1)} without a keyword", column=1, text=s, expected="o<name> call ...")
            self.code.append(code)
        self._check_structure()

    def _check_structure(self) -> None:
        """Every opening O-word has its closing one after it (LinuxCNC checks this before running),
        every macro B ``DO m`` its ``END m``."""
        self.macro.match_loops(self.where)
        closers = {"sub": ("endsub",), "if": ("endif",), "repeat": ("endrepeat",), "do": ("while",)}
        self._check_nested_subs()
        for i, ow in self.oword.items():
            if ow.keyword == "while":
                opened_by_do = any(self.oword[j].keyword == "do" and j < i for j in self.by_label[ow.label])
                if opened_by_do:
                    continue
                self.next_of(i, ("endwhile",))
            elif ow.keyword in closers:
                self.next_of(i, closers[ow.keyword])

    def _check_nested_subs(self) -> None:
        """A subroutine definition inside another is an error (LinuxCNC tests/interp/nested-sub-error:
        ``o100 sub`` between ``o<nested> sub`` and its ``endsub``)."""
        inside: int | None = None
        for i in sorted(self.oword):
            ow = self.oword[i]
            if ow.keyword == "sub":
                if inside is not None and self.sources[inside] == self.sources[i]:
                    outer = self.oword[inside].label
                    self.fail(i, f"O-word o{ow.label} sub inside the definition of o{outer}: subroutine "
                                 "definitions cannot nest", f"o{outer} endsub before o{ow.label} sub")
                inside = i
            elif ow.keyword == "endsub" and inside is not None and ow.label == self.oword[inside].label:
                inside = None

    def where(self, i: int) -> Where:
        src = self.sources[i]  # line numbers count within each file
        return Where(src, i - self.first_line[src] + 1, self.raw[i].strip())

    def include(self, path: Path) -> None:
        """Append another program file (a subprogram it holds), once."""
        key = str(path)
        if key in self.files:
            return
        self.files.add(key)
        try:
            text = program_text(key)
        except (OSError, BinaryDataError) as exc:
            raise GCodeError(f"cannot read the subprogram file: {getattr(exc, 'strerror', None) or exc}",
                             file=key) from None
        self._index(text, key)
        self._check_structure()

    def external_fanuc(self, number: int) -> int | None:
        """Index of program ``O<number>`` after including the file of the main program's directory, or of a
        folder of :attr:`subroutine_path` (the folders that stand for the control's memory: a shop's main program
        calling the programs of its subfolders), that holds it: Fanuc and Haas keep programs in memory by number,
        a file per program; the candidates are the files whose name ends with the number (``o1002.nc``,
        ``gauge_tool_o1002.cnc``, ``1002.nc``), and the first holding an ``O1002`` line is taken."""
        if number in self.fanuc:
            return self.fanuc[number]
        if self.source is None:
            return None
        pattern = re.compile(rf"(?:^|[^0-9])[oO]?0*{number}$")
        home = Path(self.source).parent
        folders = (home, *(home / p for p in self.subroutine_path))
        for cand in (c for folder in folders if folder.is_dir() for c in sorted(folder.iterdir())):
            if cand.is_file() and cand.suffix.lower() in _PROGRAM_SUFFIXES and pattern.search(cand.stem):
                try:
                    text = program_text(str(cand))
                except (OSError, BinaryDataError):
                    continue
                if re.search(rf"^\s*[oO:]0*{number}\b", text, re.M):
                    self.include(cand)
                    return self.fanuc.get(number)
        return None

    def unnumbered(self, number: float) -> str:
        """``" (1002.nc there holds no O1002 line)"`` when a file of the main program's folder is named
        after the number but does not number its program (a simulator's file-per-program convention;
        Fanuc and Haas find a called program by its O number), else ``""``."""
        if self.source is None or number != int(number):
            return ""
        folder = Path(self.source).parent
        pattern = re.compile(rf"[oO]?0*{int(number)}")
        names = [c.name for c in sorted(folder.iterdir()) if c.is_file() and c.suffix.lower() in _PROGRAM_SUFFIXES
                 and pattern.fullmatch(c.stem)] if folder.is_dir() else []
        return f" ({names[0]} there holds no O{int(number)} line)" if names else ""

    def external_sub(self, label: str) -> int | None:
        """Start of subroutine ``o<label>`` after including ``<label>.ngc`` from the main
        program's directory or a folder of :attr:`subroutine_path` (LinuxCNC searches its INI's
        SUBROUTINE_PATH for ``<name>.ngc``; relative folders start at the program's)."""
        if self.sub_start(label) is not None or self.source is None or not label.startswith("<"):
            return self.sub_start(label)
        folder = Path(self.source).parent
        for place in (folder, *(folder / p for p in self.subroutine_path)):
            cand = place / f"{label[1:-1]}.ngc"
            if cand.is_file():
                self.include(cand)
                break
        return self.sub_start(label)

    def fail(self, i: int, message: str, expected: str) -> None:
        ow = self.oword.get(i)
        self.where(i).fail(message, column=1, text=self.raw[i].strip(),
                           expected=expected if ow is None else expected)

    def next_of(self, i: int, keywords: tuple[str, ...]) -> int:
        """The next line after ``i`` with the same O label and one of ``keywords``."""
        label = self.oword[i].label
        for j in self.by_label[label]:
            if j > i and self.oword[j].keyword in keywords:
                return j
        ow = self.oword[i]
        self.fail(i, f"O-word o{label} {ow.keyword}: no matching {' or '.join(keywords)}",
                  f"o{label} {keywords[-1]} closing it")
        raise AssertionError("unreachable")

    def prev_of(self, i: int, keywords: tuple[str, ...]) -> int | None:
        label = self.oword[i].label
        for j in reversed(self.by_label[label]):
            if j < i and self.oword[j].keyword in keywords:
                return j
        return None

    def sub_start(self, label: str) -> int | None:
        for j in self.by_label.get(label, ()):
            if self.oword[j].keyword == "sub":
                return j
        return None


def _args(prog: _Program, i: int, params: Parameters) -> list[float]:
    """The bracketed values after an O-word keyword (call arguments, conditions, counts)."""
    ow = prog.oword[i]
    raw = prog.raw[i]
    code = strip_comments(raw, prog.where(i))
    pos = ow.column - 1
    values = []
    while True:
        while pos < len(code) and code[pos] in " \t\r":
            pos += 1
        if pos >= len(code):
            return values
        v, pos = evaluate_at(code, pos, prog.where(i), params)
        values.append(v)


def _computed_label(prog: _Program, i: int, ow: _OWord, params: Parameters) -> str:
    """The O number of ``o#1 call`` / ``O[#2*10] call``: the value, a whole number."""
    code = strip_comments(prog.raw[i], prog.where(i))
    value, _ = evaluate_at(code, ow.computed - 1, prog.where(i), params)
    if value != int(value):
        prog.fail(i, f"O-word call: the computed O number {value:g} is not a whole number", "o[integer] call")
    return str(int(value))


def _condition(prog: _Program, i: int, params: Parameters) -> bool:
    values = _args(prog, i, params)
    if len(values) != 1:
        ow = prog.oword[i]
        prog.fail(i, f"O-word o{ow.label} {ow.keyword} needs one condition [expression]",
                  f"o{ow.label} {ow.keyword} [expression]")
    return values[0] != 0.0


def _calls(words: list[Word]) -> list[Word]:
    """The block's words that call or return: G65, G66, G66.1, G67, M97, M98, M99."""
    return [w for w in words if w.letter == "G" and (w.value == 65 or w.value in MODAL_CALL_CODES)
            or w.letter == "M" and w.value in (97, 98, 99)]


def _may_call(code: str, words: list[Word]) -> bool:
    """Whether the block of plain words ``words`` (its text ``code``) calls or returns: only with an M word
    or a "65", "66" or "67" in its text is there one to look for."""
    return ("M" in code or "m" in code or "65" in code or "66" in code or "67" in code) and bool(_calls(words))


def _modal_limit(frames: list[_Frame]) -> int | None:
    """The modal calls the blocks of the innermost frame may make (:attr:`_Frame.modal`)."""
    return frames[-1].modal if frames else None


def _modal_code(prog: _Program, pc: int, words: list[Word], code: Word, modal: ModalCalls, frames: list[_Frame],
                decimal_point_input: str | None, on_note: Callable[[str], None] | None) -> list[Word]:
    """A G66 / G66.1 block (specifies a modal call; nothing of it runs) or a G67 block (cancels the modal call
    specified last); returns the words left to run: a G67 block's others (:mod:`interpolators.iso_modal_call`)."""
    where = prog.where(pc)
    others = [w for w in words if w is not code and w.letter == "G" and w.value in MODAL_CALL_CODES]
    if others:
        where.fail(f"{code.text} and {others[0].text} in one block (modal macro calls, one group)",
                   column=others[0].column, text=others[0].text, expected="one of G66, G66.1, G67 per block")
    if code.value == 67:
        modal.cancel()
        return [w for w in words if w is not code]
    name = "G66.1" if code.value != 66 else "G66"
    if _modal_limit(frames) is not None:
        where.fail(f"{name} in a macro that a modal call runs: a modal call specified from inside a modal "
                   "call's macro is not modelled", column=code.column, text=code.text,
                   expected=f"{name} in the main program, an M98 subprogram or a G65 macro")
    start = _called_program(prog, words, code, where, f"{name} modal macro call")
    arguments, count = macro_arguments(words, where, name, skip=(code,), decimal_point_input=decimal_point_input,
                                       on_note=on_note)
    program = int(next(w for w in words if w.letter == "P").value)
    modal.specify(ModalCall(each_block=code.value != 66, program=program, start=start, arguments=arguments,
                            repeats=count))
    return []


def _modal_call(prog: _Program, pc: int, words: list[Word], modal: ModalCalls, index: int, params: Parameters,
                frames: list[_Frame], decimal_point_input: str | None, on_note: Callable[[str], None] | None) -> int:
    """Make the modal call ``index`` for the block at ``pc`` (its ``words``: a G66.1 call's arguments): enter its
    program with a new local level; returns the next program counter (the block after ``pc`` if L is 0)."""
    call = modal.calls[index]
    arguments = call.arguments
    if call.each_block:
        block, _ = macro_arguments(words, prog.where(pc), "G66.1", decimal_point_input=decimal_point_input,
                                   on_note=on_note, call_block=False)
        arguments = {**arguments, **block}
    if call.repeats == 0:
        return pc + 1
    params.push_macro(arguments)
    _push(prog, pc, frames, _Frame(return_pc=pc + 1, start_pc=call.start, repeats=call.repeats - 1, kind="g66",
                                   modal=index))
    return call.start


def run(text: str, *, source: str | None = None, params: Parameters | None = None,  # noqa: C901
        max_lines: int = MAX_EXECUTED_LINES, max_loop_passes: int = MAX_LOOP_PASSES,
        subroutine_path: tuple[str, ...] = (), tape_leader: bool = False,
        on_comment: Callable[[str, str, Where], None] | None = None,
        on_note: Callable[[str], None] | None = None, decimal_point_input: str | None = None,
        on_call_words: Callable[[list[Word], Where], None] | None = None,
        modal_calls: ModalCalls | None = None, tape_forms: bool = True) -> Iterator[FlowLine]:
    """Yield the lines of a program in execution order, their words read.

    ``max_lines`` bounds the lines executed, ``max_loop_passes`` the times one macro B loop end or backward GOTO sends
    execution back (:mod:`interpolators.iso_macro`): guards against endless loops. ``subroutine_path`` lists further
    folders searched for ``<name>.ngc`` (LinuxCNC SUBROUTINE_PATH). ``tape_leader``: the text after the first ``%`` of
    each file, to its line end, is skipped (Fanuc). ``decimal_point_input``: Fanuc's DPI setting
    (``MachineContext.decimal_point_input``, the ``fanuc`` dialect) for the G65 arguments written without a decimal
    point (:func:`_plain_argument`); None: they are errors. ``on_comment(keyword, text, where)`` receives each active
    comment the run reaches but ABORT (:func:`interpolators.iso_messages.comment_output`: the text as shown); without it
    they are comments. ``on_note(text)`` receives what the run read in a form its manuals do not give (``M98 Q``).
    ``on_call_words(words, where)``: when given, an M98 block only calls and its other words, read and not executed, go
    to it (LinuxCNC, :func:`_call_words_only`); without it they run before the call (Fanuc, Haas). ``modal_calls``: G66,
    G66.1 and G67 run as Fanuc's modal macro calls (:mod:`interpolators.iso_modal_call`), in force in it; without it
    they are yielded as words (which the reader refuses). ``tape_forms``: a '/' right after the line's sequence number
    runs as block delete (Fanuc, Haas, grbl) and ``:1234`` is program O1234; False: both refused, as LinuxCNC does.

    The caller stops iterating at the program end (M2/M30). ``M99`` in the main program yields a
    line whose ``M99`` is replaced by ``M30``.

    Raises
    ------
    vcnc.GCodeError
        Unmatched O-words, calls of undefined subroutines, runaway loops, bad expressions.
    """
    params = Parameters() if params is None else params
    prog = _Program(text, source, max_loop_passes=max_loop_passes, subroutine_path=subroutine_path,
                    tape_leader=tape_leader, abbreviations=params.fanuc, skip_levels=params.fanuc,
                    tape_forms=tape_forms, program_numbers=params.fanuc)
    frames: list[_Frame] = []
    taken: dict[str, bool] = {}
    repeats: dict[int, int] = {}
    pc = 0
    executed = 0
    while pc < len(prog.code) and (frames or pc < prog.main_end):
        executed += 1
        if executed > max_lines + len(prog.code):
            prog.fail(pc, f"more than {max_lines} lines executed beyond the program's {len(prog.code)}: an endless "
                      "loop? (vcnc's guard against one: repetitions that end, but only beyond it, stop here too)",
                      f"a loop that ends within {max_lines} lines")
        ow = prog.oword.get(pc)
        if ow is not None:
            pc = _oword(prog, pc, ow, params, frames, taken, repeats)
            continue
        nxt, code = _statement_or_code(prog, pc, params, on_note)  # code None: none, or a Haas condition that fails
        if nxt is not None:
            pc = nxt
            continue
        words = None if code is None or pc in prog.active else plain_words(code, checked=pc in prog.plain)
        if words is not None and not _may_call(code, words) and not (modal_calls and modal_calls.calls):  # CAM output
            line = object.__new__(FlowLine)  # without the frozen dataclass's per-field object.__setattr__
            line.__dict__.update(line=pc - prog.first_line[prog.sources[pc]] + 1, raw=prog.raw[pc].strip(), words=words,
                                 file=prog.sources[pc])
            yield line
            pc += 1
            continue
        where = prog.where(pc)
        words = [] if code is None else read_line(code, where, params) if has_parameters(code) else \
            read_words(code, where)
        if pc in prog.active:
            keyword, text = prog.active[pc]
            if keyword == "abort":  # LinuxCNC "Abort Messages": (ABORT, text) ends the run with the message
                prog.fail(pc, f"(ABORT) the program aborts here: {expand(text, params, where).strip()}",
                          "a program that does not reach its (ABORT, ...) comment")
            shown = None if on_comment is None else comment_output(keyword, text, params, where)
            if shown is not None:
                on_comment(keyword, shown, where)
        if code is None:
            pc += 1
            continue
        calls = _calls(words)
        modal_code = next((w for w in calls if w.letter == "G" and w.value != 65), None) if modal_calls else None
        if modal_code is not None:
            words = _modal_code(prog, pc, words, modal_code, modal_calls, frames, decimal_point_input, on_note)
            calls = _calls(words)
            if not words:
                pc += 1
                continue
        g65 = next((w for w in calls if w.letter == "G" and w.value == 65), None)
        if g65 is not None:
            pc = _macro_call(prog, pc, words, g65, params, frames, decimal_point_input, on_note)
            continue
        m98 = next((w for w in calls if w.letter == "M" and w.value in (97, 98)), None)
        m99 = next((w for w in calls if w.letter == "M" and w.value == 99), None)
        if m98 is None and m99 is None:
            pc = yield from _block(prog, pc, words, where, None if modal_code else modal_calls, params, frames,
                                   decimal_point_input, on_note)
            continue
        if m98 is not None and on_call_words is not None:
            words = _call_words_only(words, m98, where, on_call_words)
        pc = yield from _call_or_return(prog, pc, words, m98, m99, where, params, frames, on_note)
        if pc < 0:  # M99 in the main program: the run ends there
            return
    _no_return(prog, frames)


def _block(prog: _Program, pc: int, words: list[Word], where: Where, modal: ModalCalls | None, params: Parameters,
           frames: list[_Frame], decimal_point_input: str | None, on_note: Callable[[str], None] | None
           ) -> Generator[FlowLine, None, int]:
    """An ordinary block at ``pc`` (:func:`run`): yields it, then makes the G66 call it is due, or makes the G66.1
    call it is due instead of running (the call takes its words); returns the next line's index."""
    due = None if modal is None else modal.due(words, _modal_limit(frames))
    if due is None or not modal.calls[due].each_block:
        if params.macro_b:  # Fanuc/Haas round a computed address value to its increment
            words = address_values(words, inch=bool(params.inch and params.inch()))
        yield FlowLine(where.line, where.text, words, where.file)
    if due is None:
        return pc + 1
    return _modal_call(prog, pc, words, modal, due, params, frames, decimal_point_input, on_note)


def _repeat_count(words: list[Word], m98: Word, where: Where) -> int:
    """The number of calls an M97/M98 block makes: its L (or K) word, else 1. A whole number of at least 0 (``L0``
    calls nothing, as rs274 runs it); rs274 refuses ``L-1`` ("Negative l word used") and ``L0.5`` ("Non integer
    value for integer"), and so does vcnc; FANUC's L is a repetition count 1-9999 (0i-MC operator's manual
    B-64124EN 12.3 "Subprogram")."""
    rep = next((w for w in words if w.letter in "LK"), None)
    if rep is None:
        return 1
    if rep.value < 0 or rep.value != int(rep.value):
        where.fail(f"M{m98.value:g} {rep.letter}{rep.value:g}: the number of calls must be a whole number of at "
                   "least 0", column=rep.column, text=rep.text, expected=f"{rep.letter}<count> (0 calls nothing)")
    return int(rep.value)


def _call_words_only(words: list[Word], m98: Word, where: Where,
                     on_call_words: Callable[[list[Word], Where], None]) -> list[Word]:
    """The words of an M98 block LinuxCNC executes: the call's own (M98 P L). LinuxCNC reads ``M98 P100`` as
    "analogous to the traditional o100 call" (o-code.adoc, "Fanuc-Style Numbered Programs") and runs a block
    with an O-word call as the call alone (rs274ngc_pre.cc ``Interp::execute``: ``convert_control_functions``,
    not ``execute_block``): ``M98 P81 F100`` sets no feed, as rs274 shows. Fanuc and Haas run such words."""
    kept = [w for w in words if w is m98 or w.letter in "NPL"]
    if len(kept) < len(words):
        on_call_words([w for w in words if not any(w is k for k in kept)], where)
    return kept


def _call_or_return(prog: _Program, pc: int, words: list[Word], m98: Word | None, m99: Word | None, where: Where,
                    params: Parameters, frames: list[_Frame], on_note: Callable[[str], None] | None
                    ) -> Generator[FlowLine, None, int]:
    """The line at ``pc`` with its M97/M98 call ``m98`` or its M99 return ``m99`` (:func:`run`): yields its other
    words, pushes or pops the frame; returns the next line's index, -1 when an M99 ends the main program."""
    if m98 is not None:
        if params.fanuc:
            words = _fanuc_packed_count(prog, words, m98)
        start, q = _subprogram_start(prog, pc, words, m98, where, on_note)
        count = _repeat_count(words, m98, where)
        rest = [w for w in words if w is not m98 and w is not q and w.letter not in "PLK"]
        if rest:
            yield FlowLine(where.line, where.text, rest, where.file)
        if count <= 0:
            return pc + 1
        _push(prog, pc, frames, _Frame(return_pc=pc + 1, start_pc=start, repeats=count - 1, kind="m98",
                                       modal=_modal_limit(frames)))
        return start
    back_to = next((w for w in words if w.letter == "P"), None) if frames or params.macro_b else None
    rest = [w for w in words if w is not m99 and w is not back_to]
    if not frames and back_to is not None:
        if rest:
            yield FlowLine(where.line, where.text, rest, where.file)
        return _branch_here(prog, pc, back_to, where)
    if not frames:
        if on_note is not None:
            on_note(_main_m99_note(prog, pc))
        yield FlowLine(where.line, where.text, rest + [Word("M", 30.0, m99.column, m99.text)], where.file)
        return -1
    if rest:
        yield FlowLine(where.line, where.text, rest, where.file)
    frame = frames[-1]
    if frame.kind == "oword":
        prog.fail(pc, "M99 inside an O-word subroutine", "o<name> endsub or return")
    if back_to is not None and params.macro_b and not params.fanuc:  # Haas: a branch within the subprogram
        return _branch_here(prog, pc, back_to, where)
    if frame.repeats > 0:  # a G65 repetition keeps the locals as the last one left them (Haas manual)
        frame.repeats -= 1
        return frame.start_pc
    frames.pop()
    if frame.kind in ("g65", "g66"):
        params.pop()
    return frame.return_pc if back_to is None else _return_to(prog, frame, back_to, where)


#: An M99 word in a line of code.
_M99 = re.compile(r"M\s*0*99(?![0-9.])", re.I)
#: A Haas conditional M99: a bracketed expression opens the block (after its sequence number), an M99 follows.
_CONDITIONAL_M99 = re.compile(r"\s*(?:N\s*\d+\s*)?\[.*\]\s*M\s*0*99(?![0-9.])", re.I)


def _statement_or_code(prog: _Program, pc: int, params: Parameters,
                       on_note: Callable[[str], None] | None) -> tuple[int | None, str | None]:
    """``(next line, None)`` when line ``pc`` is a macro B statement, run here; else ``(None, code)``: the code the
    line runs as a block (:func:`_conditional_m99`), or of a Haas ``IF [..] THEN <block>`` whose condition holds
    its block (:meth:`interpolators.iso_macro.MacroFlow.then_block`; None when the condition fails)."""
    if pc not in prog.macro.statements:
        return None, _conditional_m99(prog, pc, params)
    if on_note is not None and prog.raw[pc].lstrip().startswith("/"):  # a statement on a '/' line that runs
        on_note(BLOCK_DELETE_RUN)  # (:func:`interpolators.iso_text.line_notes` notes the other '/' lines)
    code = prog.macro.then_block(pc, prog.where(pc), params)
    if code is None:
        return prog.macro.execute(pc, prog.where(pc), params), None
    return None, code or None


def _conditional_m99(prog: _Program, pc: int, params: Parameters) -> str | None:
    """The code of line ``pc``; of a Haas block ``N50 [#100 LT 10] M99 P10`` (``haas``: macro B without Fanuc's
    rules), without its condition when the condition holds, else ``None`` (the block is skipped, as an empty line:
    "otherwise processing continues with the next program line in sequence"). Haas mill
    operator's manual 96-8000 (1999), "Macros", "Conditional Expressions": "With macros enabled, M99 can be used
    with a conditional expression to branch conditionally ... N50 [#100 LT 10] M99 P10 ; ... the branch occurs
    only when #100 is less than 10" (the same text in Haas's online "Conditional Expressions" page, #10000).
    Under ``fanuc``, whose macro B branches by ``IF [..] GOTO n`` alone (B-64304EN "Branch and repetition"), such
    a block is an error naming the Haas form."""
    code = prog.code[pc]
    if code is None or not params.macro_b or not _CONDITIONAL_M99.match(code):
        return code
    start = code.index("[")
    if params.fanuc:
        prog.where(pc).fail("a conditional M99 ('[condition] M99') is Haas's form, which Fanuc's macro B lacks",
                            column=start + 1, text=code[start:].strip(),
                            expected="IF [condition] GOTO n, or --dialect haas for a Haas program")
    holds, end = evaluate_condition(code, start, prog.where(pc), params)
    return code[:start] + " " * (end - start) + code[end:] if holds else None


def _branch_here(prog: _Program, pc: int, p: Word, where: Where) -> int:
    """``M99 P<n>`` in the main program (``fanuc``, ``haas``) and, under ``haas``, in a subprogram: go on at the
    block ``N<n>`` of the program it stands in, the call (if any) still open (Haas mill operator's manual 96-8000,
    June 1999, "Macros", "Conditional Expressions", p. 376, and haascnc.com "Conditional Expressions": "M99 in the
    HAAS control has the ability to branch unconditionally to any line in the current subroutine by placing a P
    code on the same line ... N50 M99 P10 ; branches to line N10. It does not return control to the calling
    subroutine"; Fanuc's M99 P<n> in a subprogram returns to the caller's N<n>, :func:`_return_to`. In a main
    program, whose M99 alone loops back to its start, our reading is the same branch within it), found as a
    macro B GOTO finds it and counted as a backward GOTO is."""
    n = round(p.value)
    target = prog.macro.find(n, pc) if p.value == n else None
    if target is None:
        where.fail(f"M99 P{p.value:g}: no block N{p.value:g} in this program", column=p.column, text=p.text,
                   expected="M99 P<n> with a block N<n> in the same program")
    if target <= pc:
        prog.macro.count_back(pc, where, f"M99 P{n}")
    return target


def _main_m99_note(prog: _Program, pc: int) -> str:
    """The note of an ``M99`` the main program reaches: Fanuc and Haas return to its start and run it again
    (Haas mill operator's manual, "M99 Subprogram Return or Loop": in a main program M99 "loops back to the
    start"), vcnc runs it once; programs the file holds after it (a subprogram stored before its main
    program, ``O1000 ... M99 % O0001 (MAIN) ... M98 P1000``) are not run."""
    later = sorted((i, n) for n, i in prog.fanuc.items() if i > pc)
    after = f"; the file's later programs ({', '.join(f'O{n:04d}' for _, n in later)}) are not run" if later else ""
    return f"M99 ends the main program (Fanuc/Haas would run it again from its start){after}"


def _no_return(prog: _Program, frames: list[_Frame]) -> None:
    """Fail when the run left the text inside a called program: it reached the end of the file without
    the ``M99`` that returns (Haas mill operator's manual, "M98 Subprogram Call": a subprogram ends with
    M99; the call would otherwise end the whole program silently). Named at the innermost call."""
    if frames:
        call = {"g65": "G65 macro call", "g66": "G66/G66.1 modal macro call"}.get(frames[-1].kind,
                                                                                  "M98/M97 subprogram call")
        prog.fail(frames[-1].return_pc - 1, f"{call}: the called blocks run to the end of the file without the M99 "
                  "that returns", "M99 at the end of the called program (M17 ends a subprogram on Siemens "
                  "and CNCSimulator Pro, not on Fanuc/Haas)")


def _return_to(prog: _Program, frame: _Frame, p: Word, where: Where) -> int:
    """``M99 P<n>`` in a subprogram (``fanuc``; under ``haas`` it branches within the subprogram,
    :func:`_branch_here`): return to the block ``N<n>`` of the calling program instead of the block after the
    call (Fanuc 0i-MD B-64304EN, "Subprogram", "Special usage": "If P is used to specify a sequence number when a
    subprogram is terminated, control does not return to the block after the calling block, but returns to the
    block with the sequence number specified by P"), found as a macro B GOTO finds it."""
    n = round(p.value)
    target = prog.macro.find(n, frame.return_pc - 1) if p.value == n else None
    if target is None:
        where.fail(f"M99 P{p.value:g}: no block N{p.value:g} in the calling program", column=p.column, text=p.text,
                   expected="M99 P<n> with a block N<n> in the program that called this one")
    return target


def _local_subprogram(prog: _Program, pc: int, words: list[Word], call: Word, where: Where, letter: str = "P") -> int:
    """The line ``N<P>`` of this program that a Haas ``M97 P<n> L<count>`` calls (Haas mill operator's
    manual 96-8000, "M97 Local Sub-Program Call": "used to call a subroutine referenced by a line
    number (N) within the same program ... The subroutine must end with an M99. An Lnn code in the
    M97 block will repeat the subroutine call that nn times"); found as a macro B GOTO finds it.
    ``letter`` "Q": the block ``N<Q>`` of an ``M98 Q<n>`` without P (:func:`_subprogram_start`)."""
    p = next((w for w in words if w.letter == letter), None)
    target = None if p is None or p.value != round(p.value) else prog.macro.find(round(p.value), pc)
    what = "M97 local subprogram call" if letter == "P" else "M98 Q subprogram call (no P: this program)"
    expected = f"{call.text.upper()} {letter}<n> with a block N<n> in the same program, ending with M99"
    if target is None:
        missing = f"no {letter} word" if p is None else f"no block N{p.value:g} in this program"
        where.fail(f"{what}: {missing}", column=call.column, text=call.text, expected=expected)
    if target <= pc and not any(c is not None and _M99.search(c) for c in prog.code[target:pc]):
        # the called blocks run into this call again before any M99: it would call itself without end
        where.fail(f"{what}: block N{p.value:g} comes before the call and reaches it again without an M99",
                   column=call.column, text=call.text, expected=expected)
    return target


def _subprogram_start(prog: _Program, pc: int, words: list[Word], call: Word, where: Where,
                      on_note: Callable[[str], None] | None) -> tuple[int, Word | None]:
    """The first line an ``M97``/``M98`` block runs, and the ``Q`` word of an ``M98 P Q`` (else None).

    ``M98 Q<n>`` without P calls the block ``N<n>`` of the program being run, to its M99, as Haas M97
    does (Mitsubishi M70/Meldas programming manual, "Subprogram call: M98, M99": P is the "program No.
    of the subprogram to be called (own program if omitted)", Q/H the sequence number to start at; as
    summarised in https://industrialmonitordirect.com/blogs/knowledgebase/mitsubishi-meldas-m98-subprogram-call-h-address-syntax).
    Fanuc 0i-MD shop programs (Doosan DNM) write ``M98 Q3021`` with ``N3021 ... M99`` after M30; no Fanuc
    manual at hand states it, so it is noted."""
    if call.value == 97:
        return _local_subprogram(prog, pc, words, call, where), None
    q = next((w for w in words if w.letter == "Q"), None)
    if q is not None and not any(w.letter == "P" for w in words):
        if on_note is not None:
            on_note("M98 Q without P: the block N<Q> of this program is called, to its M99 (Mitsubishi form; "
                    "read as on Fanuc 0i-MD shop programs)")
        return _local_subprogram(prog, pc, words, call, where, "Q"), q
    start = _called_program(prog, words, call, where, "M98 subprogram call")
    if q is None:
        return start, None
    if on_note is not None:
        on_note("M98 P Q: the subprogram starts at its block N<Q> (Mitsubishi/Mach4 form, not Fanuc's)")
    return _start_block(prog, start, q, where), q


def _start_block(prog: _Program, start: int, q: Word, where: Where) -> int:
    """``M98 P<program> Q<n>``: the called program runs from its block ``N<n>`` (Mitsubishi M70 programming
    manual, "Subprogram call: M98, M99": "M98 P__ Q__ L__ ... Q = sequence number in subprogram to be
    called", http://cncprograming.blogspot.com/2011/07/subprogram-call-m98-m99.html; Mach4 writes the same
    form; Fanuc's manuals give M98 P and L only); repetitions start there too."""
    n = round(q.value)
    target = prog.macro.find(n, start - 1) if q.value == n else None
    if target is None or prog.macro.span_of[target] != prog.macro.span_of[start]:
        where.fail(f"M98 Q{q.value:g}: no block N{q.value:g} in the called program", column=q.column, text=q.text,
                   expected="M98 P<program> Q<n> with a block N<n> in that program (the block it starts at)")
    return target


def _probing_macro(number: float) -> str:
    """What a called O9810-O9834 is: the Renishaw Inspection Plus probing macros a machine with a spindle probe
    keeps in its control (Renishaw Inspection Plus programming manual H-2000-6222: O9810 protected positioning,
    O9811-O9823 measuring cycles, O9832/O9833 probe on/off; Haas WIPS calls the same numbers), which a program
    only calls; they measure the part, which vcnc has not."""
    if not 9810 <= number <= 9834:
        return ""
    return (" (a Renishaw Inspection Plus probing macro stored in the machine's control: it measures the part, "
            "which vcnc cannot; a copy of the macro beside the program would run as written)")


def _fanuc_packed_count(prog: _Program, words: list[Word], m98: Word) -> list[Word]:
    """Fanuc's ``M98 P<count><program>``: the last four digits of P are the program, those before them the
    number of calls (FANUC Series 0i-MC operator's manual B-64124EN 12.3 "Subprogram": "M98 P51002 ... Call the
    subprogram (number 1002) five times in succession"), read so when the block has no L and the file holds no
    program ``O<P>`` but one ``O<last four digits>`` (a program number beyond four digits, 30i's eight-digit O
    numbers, is taken as written: our reading)."""
    p = next((w for w in words if w.letter == "P"), None)
    if m98.value != 98 or p is None or p.value != int(p.value) or p.value < 10000 or \
            any(w.letter in "LKQ" for w in words) or prog.external_fanuc(int(p.value)) is not None:
        return words
    count, number = divmod(int(p.value), 10000)
    if prog.external_fanuc(number) is None:
        return words
    return [Word("P", float(number), w.column, w.text) if w is p else w for w in words] + \
        [Word("L", float(count), p.column, p.text)]


def _called_program(prog: _Program, words: list[Word], call: Word, where: Where, what: str) -> int:
    """First line of the program ``O<P>`` that an M98 or G65 block calls."""
    p = next((w for w in words if w.letter == "P"), None)
    if p is None or p.value != int(p.value) or prog.external_fanuc(int(p.value)) is None:
        target = "no P word" if p is None else (f"program O{p.value:g} is neither in this file nor in a "
                                                "program file of its folder" + prog.unnumbered(p.value)
                                                + _probing_macro(p.value))
        where.fail(f"{what}: {target}", column=call.column, text=call.text,
                   expected=f"{call.text.upper()} P<number> of an O<number> program in this file or its folder "
                            "(or a folder of --subroutine-path, [program] subroutine_path)")
    return prog.fanuc[int(p.value)] + 1


def _macro_call(prog: _Program, pc: int, words: list[Word], g65: Word, params: Parameters,
                frames: list[_Frame], decimal_point_input: str | None = None,
                on_note: Callable[[str], None] | None = None) -> int:
    """A G65 block: enter program ``O<P>`` with its arguments as locals; returns the next program counter."""
    where = prog.where(pc)
    start = _called_program(prog, words, g65, where, "G65 macro call")
    locals_, count = macro_arguments(words, where, "G65", skip=(g65,), decimal_point_input=decimal_point_input,
                                     on_note=on_note)
    if count == 0:
        return pc + 1
    params.push_macro(locals_)
    _push(prog, pc, frames, _Frame(return_pc=pc + 1, start_pc=start, repeats=count - 1, kind="g65",
                                   modal=_modal_limit(frames)))
    return start


def _push(prog: _Program, pc: int, frames: list[_Frame], frame: _Frame) -> None:
    """Enter a call made at line ``pc`` (:data:`MAX_CALL_LEVELS`)."""
    if len(frames) + 1 >= MAX_CALL_LEVELS:
        prog.fail(pc, f"subroutine calls nested {len(frames) + 1} deep (a call that never returns?)",
                  f"at most {MAX_CALL_LEVELS - 1} nested calls")
    frames.append(frame)


def _oword(prog: _Program, pc: int, ow: _OWord, params: Parameters, frames: list[_Frame],  # noqa: C901
           taken: dict[str, bool], repeats: dict[int, int]) -> int:
    """Execute one O-word line; returns the next program counter."""
    k = ow.keyword
    if k == "sub":
        return prog.next_of(pc, ("endsub",)) + 1
    if k == "call":
        label = _computed_label(prog, pc, ow, params) if ow.computed else ow.label
        start = prog.external_sub(label)
        if start is None:
            prog.fail(pc, f"O-word o{label} call: the subroutine is neither in this file nor in "
                          f"{label.strip('<>')}.ngc beside it or in a folder of the subroutine path (the machine's "
                          f"[program] subroutine_path, --subroutine-path)", f"o{label} sub ... endsub")
        if not label.startswith("<") and prog.sources[start] != prog.source:
            # LinuxCNC interp_o_word.cc: LinuxCNC reads a subroutine file from its o<name> sub on, so a
            # numbered subroutine there is neither in its offset table nor a file of its own
            prog.fail(pc, f"O-word o{label} call: subroutine o{label} is defined in the subroutine file "
                          f"{Path(prog.sources[start]).name}, where LinuxCNC does not find numbered subroutines",
                      f"o{label} sub in the main program, or a named o<name> sub in <name>.ngc")
        args = _args(prog, pc, params)
        params.push(args)
        _push(prog, pc, frames, _Frame(return_pc=pc + 1, start_pc=start + 1, repeats=0, kind="oword",
                                       modal=_modal_limit(frames)))
        return start + 1
    if k in ("endsub", "return"):
        values = _args(prog, pc, params)
        if not frames or frames[-1].kind != "oword":
            if k == "endsub" and not frames:
                prog.fail(pc, f"O-word o{ow.label} endsub without a call", "o-word call of the subroutine")
            prog.fail(pc, f"O-word o{ow.label} {k} outside a subroutine", "return inside o-sub ... endsub")
        frame = frames.pop()
        params.pop()
        # LinuxCNC interp_read.cc read_o: a return without a value sets #<_value> to 0
        params.named["_value"] = values[0] if values else 0.0
        params.named["_value_returned"] = 1.0 if values else 0.0
        return frame.return_pc
    if k == "if":
        if _condition(prog, pc, params):
            taken[ow.label] = True
            return pc + 1
        taken[ow.label] = False
        return prog.next_of(pc, ("elseif", "else", "endif"))
    if k == "elseif":
        if taken.get(ow.label, False):
            return prog.next_of(pc, ("endif",))
        if _condition(prog, pc, params):
            taken[ow.label] = True
            return pc + 1
        return prog.next_of(pc, ("elseif", "else", "endif"))
    if k == "else":
        if taken.get(ow.label, False):
            return prog.next_of(pc, ("endif",))
        return pc + 1
    if k == "endif":
        taken.pop(ow.label, None)
        return pc + 1
    if k == "do":
        return pc + 1
    if k == "while":
        do = prog.prev_of(pc, ("do",))
        if do is not None and not any(prog.oword[j].keyword == "endwhile" for j in prog.by_label[ow.label]):
            return do + 1 if _condition(prog, pc, params) else pc + 1
        return pc + 1 if _condition(prog, pc, params) else prog.next_of(pc, ("endwhile",)) + 1
    if k == "endwhile":
        head = prog.prev_of(pc, ("while",))
        if head is None:
            prog.fail(pc, f"O-word o{ow.label} endwhile without while", f"o{ow.label} while [condition]")
        return head
    if k == "repeat":
        if pc not in repeats:
            values = _args(prog, pc, params)
            if len(values) != 1 or values[0] != int(values[0]) or values[0] < 0:
                prog.fail(pc, f"O-word o{ow.label} repeat needs a whole count >= 0", f"o{ow.label} repeat [n]")
            repeats[pc] = int(values[0])
        if repeats[pc] > 0:
            repeats[pc] -= 1
            return pc + 1
        del repeats[pc]
        return prog.next_of(pc, ("endrepeat",)) + 1
    if k == "endrepeat":
        head = prog.prev_of(pc, ("repeat",))
        if head is None:
            prog.fail(pc, f"O-word o{ow.label} endrepeat without repeat", f"o{ow.label} repeat [n]")
        return head
    # break / continue: the loop of the same label
    head = prog.prev_of(pc, ("while", "repeat", "do"))
    if head is None:
        prog.fail(pc, f"O-word o{ow.label} {k} outside a loop", f"{k} inside o{ow.label} while/repeat/do")
    kind = prog.oword[head].keyword
    if kind == "repeat":
        end = prog.next_of(head, ("endrepeat",))
        if k == "break":
            repeats.pop(head, None)
            return end + 1
        return head
    if kind == "do":
        closer = prog.next_of(head, ("while",))
        return closer + 1 if k == "break" else closer
    end = prog.next_of(head, ("endwhile",))
    return end + 1 if k == "break" else head
