"""Reading one line of ISO G-code into words: comments, block delete, words and their numbers.

Follows the LinuxCNC G-code overview (https://linuxcnc.org/docs/html/gcode/overview.html):
letters are case-insensitive, spaces may stand between a letter and its number, ``( ... )``
comments may nest (``(a (b) c)``: CAM posts write them; LinuxCNC would end the comment at the
first ``)`` and then reject the rest); a ``(`` inside a comment that does not close as nested is
text, the comment ending at the first ``)`` (``(X+1 (move up)``, Fanuc), ``;`` comments
run to the end of the line, ``/`` at the start of a line marks a block-delete line (executed: the
block-delete switch is off, as in LinuxCNC's default), and ``%`` lines demarcate the program.
A line's last ``( ... )`` comment is its block comment (:func:`block_comment`), which LinuxCNC may read
as an active comment (:mod:`interpolators.iso_messages`).
Parameters (``#``), expressions (``[``) and O-words are named as such when met.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable

from interpolators._words import MAX_MAGNITUDE, Where, fence_hint, read_number, token_at

__all__ = ["Word", "WordError", "strip_comments", "comment_spans", "block_comment", "read_words", "plain_words",
           "WORD_LETTERS", "SPINDLE_SELECT", "fail_words", "foreign_hint", "firmware_dwell_hint", "offset_number"]


class WordError(ValueError):
    """A block's words that describe nothing the control runs (a cycle, a pattern, a transformation,
    a look-ahead setting); ``letter`` names the word at fault (None: the G code itself), ``expected``
    what would be right. The reader reports it at that word's column."""

    def __init__(self, message: str, *, letter: str | None = None, expected: str = "valid words") -> None:
        super().__init__(message)
        self.letter = letter
        self.expected = expected

#: Word letters the reader knows (axis letters A B C U V W are read and judged by the executor;
#: ``@`` and ``^`` are LinuxCNC's polar distance and angle, :mod:`interpolators.iso_polar`).
WORD_LETTERS = set("ABCDEFGHIJKLMNOPQRSTUVWXYZ@^")

#: LinuxCNC's spindle selection word, ``$`` and a number or an expression (``M3 $0 S1``, ``M5 $-1``; rs274 reads
#: ``$`` as a word of its own, interp_read.cc ``read_dollar``), and not a grbl setting (``$32=1``), which a line of
#: its own holds.
SPINDLE_SELECT = re.compile(r"\$(?=[ \t]*(?:[-+]?[0-9.]|\[|#))(?![ \t]*[-+]?[0-9.]*[ \t]*=)")


#: Change of the comment nesting depth at a character.
_DEPTH = {"(": 1, ")": -1}

#: The numbers of :data:`interpolators._words.NUMBER_RE` (the same strings, the same longest match), written so
#: that a line that fails to match backtracks in linear time: ``\d+\.?\d*`` may split a run of digits
#: between its two parts in as many ways as it has digits (a 16,000-digit run took 30 s to refuse).
PLAIN_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)"
#: A line of words of a letter and a plain decimal number (the number as
#: :func:`interpolators._words.read_number` reads it: spaces or tabs after the letter) and blanks only: most
#: of CAM output (``N120 G1 X-21.131 Y34.719 F400.``). It matches one way only (a number never ends where
#: a letter or a blank could start), the way the character-by-character reader reads it.
#: A Fanuc/Haas corner word's comma and letter (",R", ", C").
_CORNER = re.compile(r",[ \t]*([RrCc])")
_PLAIN_LINE = re.compile(r"[ \t\r\f\v]*(?:[A-Za-z][ \t]*" + PLAIN_NUMBER + r"[ \t\r\f\v]*)*")
#: A word of such a line: (letter, number); the text is the whole match.
_PLAIN_TOKEN = re.compile(r"([A-Za-z])[ \t]*(" + PLAIN_NUMBER + ")")


@dataclasses.dataclass(frozen=True)
class Word:
    """One word: ``letter`` (upper case; ``",R"``, ``",C"`` for Fanuc/Haas corner words), ``value``,
    1-based ``column``, source ``text``."""

    letter: str
    value: float
    column: int
    text: str


#: A bracket at the start of a block holding words of prose (two letters in a row and a blank; no '#' nor the
#: operators of a CNCjs expression, '?', '<', '>', '=', '!', '&', '|'): WinCNC's comment syntax, which Vectric's
#: CAMaster posts write ("[TOOL LIST]", "[ GET TOOL NUMBER 2 ]"), or a template's placeholder ("[put the
#: coordinates here]"); our reading from those programs' own headers ("MACHINES WITH WINCNC CONTROL ONLY"), no
#: WinCNC manual at hand.
_BRACKET_PROSE = re.compile(r"\[(?=[^\]#?<>=!&|]*[A-Za-z]{2})(?=[^\]#?<>=!&|]*\s)[^\]#?<>=!&|]*\]")


def _slash_comment_line(line: str, where: Where, *, second: int | None = None) -> None:
    """Refuse a line that opens with '//' (after its leading blanks; or, with ``second``, the line whose
    block-delete '/' was taken and whose words start with another '/' there): a line comment in Syntec/DDCS
    macro programs and the MillMaster Pro control's files ("//NC FILE - ..."), which no ISO control reads:
    Fanuc, Haas, LinuxCNC and grbl take the first '/' as block delete (Fanuc '/1'-'/9' a skip level) and
    then meet a second one. Named before anything else on such a line: its text is prose, whose '(' or ')'
    would otherwise be reported as an unclosed comment (a MillMaster Pro file's "// Tool is a 3/4" (or
    whatever ...")."""
    i = len(line) - len(line.lstrip(" \t")) + 1 if second is None else second  # the second '/', as read_words meets it
    if second is not None or line.startswith("//", i - 1):
        where.fail("'//' comment line (Syntec/DDCS macro and MillMaster Pro style): not a comment in ISO "
                   "G-code, where '/' at a line's start is block delete", column=i + 1,
                   text=token_at(line, i), expected="a ( ) or ; comment")


def comment_spans(raw: str, where: Where, *, unclosed_to_end: bool = False) -> tuple[list[tuple[int, int]], int]:
    """The ``( ... )`` comments of a line as ``(start, end)`` slices, the parentheses included (nested
    parentheses allowed), and where a ``;`` comment starts (``len(raw)`` without one). An unclosed
    ``(`` is an error, or with ``unclosed_to_end`` (grbl, :mod:`interpolators.iso_grbl`) a comment to the
    end of the line."""
    spans: list[tuple[int, int]] = []
    i, n = 0, len(raw)
    if "(" not in raw and ")" not in raw and ";" not in raw:  # most lines of CAM code: nothing to scan
        return spans, n
    while i < n:
        ch = raw[i]
        if ch == ";":
            return spans, i
        if ch == "(":
            depth, j = 1, i + 1
            while j < n and depth:
                depth += _DEPTH.get(raw[j], 0)
                j += 1
            if depth:
                # not nested after all: as Fanuc and LinuxCNC read it, the comment ends at the first ')'
                j = raw.find(")", i) + 1
                if j == 0 and unclosed_to_end:
                    spans.append((i, n))
                    return spans, n
                if j == 0:
                    _slash_comment_line(raw, where)
                    where.fail("unclosed comment", column=i + 1, text=raw[i:], expected="')' closing the comment")
            spans.append((i, j))
            i = j
            continue
        if ch == ")":
            _slash_comment_line(raw, where)
            where.fail("')' without '('", column=i + 1, text=")", expected="a word")
        i += 1
    return spans, n


def strip_comments(raw: str, where: Where) -> str:
    """Blank out comments (nested parentheses allowed), keeping columns. An unclosed ``(`` is an error."""
    spans, semicolon = comment_spans(raw, where)
    if not spans and semicolon == len(raw):
        return raw
    out = list(raw)
    for i, j in spans:
        out[i:j] = " " * (j - i)
    out[semicolon:] = " " * (len(raw) - semicolon)
    return "".join(out)


def block_comment(raw: str, where: Where) -> str | None:
    """The text of the line's last ``( ... )`` comment, without its parentheses: the one comment of
    a LinuxCNC block (``interp_read.cc`` ``read_comment`` overwrites the block's comment with each
    one read), which alone may be an active comment such as ``(DEBUG, ...)`` (G-code overview,
    "Comments": "(foo)(debug,#1)" prints, "(debug,#1)(foo)" does not). A ``;`` comment is not one
    (``read_semicolon`` only passes ``;py,`` on)."""
    spans, _ = comment_spans(raw, where)
    return raw[spans[-1][0] + 1:spans[-1][1] - 1] if spans else None


def foreign_hint(tok: str, *, first: bool = True) -> str:
    """What an unknown word is, when its text says: a RepRap/Marlin line checksum ``*57`` (the serial protocol
    of 3D printer hosts: "N<line> <command>*<checksum>", RepRap wiki "G-code", "Checking"), which no CNC control
    reads; a control character (rs274: "Bad character '\\001' used"): a damaged file or a binary header; a quoted
    text, as Centroid CNC12 macros write a prompt, ``M225 #100 "This is an example macro ..."`` (Centroid's stock
    ``mfunc53.mac`` as github.com/tcmaker/cnc1325 keeps it), and, our reading of an Acorn router's macros, a macro
    file to run, ``G65 "\\cncm\\defines.cnc"``; a grbl ``$`` line (grbl wiki "Grbl v1.1 Configuration": "$x=val",
    "$H"), which only the grbl dialect reads (:mod:`interpolators.iso_grbl`), on a line of its own (``first``: the
    token starts its line; inside a block grbl reads none); Fanuc's ``,A`` (direct drawing dimensions)."""
    if re.fullmatch(r"\*\d+", tok):
        return " (a RepRap/Marlin line checksum, which a 3D printer host adds: no CNC control reads it)"
    if ord(tok[0]) < 32:
        return f" (control character 0x{ord(tok[0]):02X}: a damaged file or a binary header?)"
    if tok.startswith("$") and not first:  # the grbl dialect too comes here with one inside a block
        return (" (a grbl setting or system command, such as $32=1 (laser mode) or $H (homing), which grbl reads "
                "only on a line of its own, not inside a block)")
    if tok.startswith("$"):
        return (" (a grbl setting or system command, such as $32=1 (laser mode) or $H (homing), which grbl reads "
                "on a line of its own: read the program with --dialect grbl)")
    if re.match(r",\s*A", tok, re.I):
        # FANUC Series 0i-TF / 30i operator's manuals, "Direct drawing dimension programming": ",A_" the angle of a
        # straight line, with one end coordinate (an option; ,C ,R are read: interpolators.iso_corners)
        return (" (Fanuc's ,A: the angle of a line in direct drawing dimension programming, an option vcnc does not "
                "read; write both end coordinates)")
    if tok.startswith('"'):
        return (" (a quoted text, as Centroid CNC12 macros write a prompt, M225 #100 \"text\", or a macro file, "
                "G65 \"file\"; vcnc reads ISO G-code with Fanuc macro B or LinuxCNC O-codes)")
    return fence_hint(tok)


def firmware_dwell_hint(letters) -> str:
    """Why a G4 block has no P, when it has an S: ``G4 S<seconds>``, the dwell of RepRapFirmware (Duet G-code
    reference, "G4: Dwell": "Pnnn Time to wait, in milliseconds; Snnn Time to wait, in seconds") and Marlin
    (marlinfw.org/docs/gcode/G004.html "S<time(s)>"), which FreeCAD's RRF post writes after M3 (rrf_post.py:
    "RRF: P for milliseconds, S for seconds, change P to S"); in ISO G-code S is the spindle speed."""
    if "S" not in letters:
        return ""
    return (" (G4 S<seconds> is the dwell of RepRapFirmware and Marlin, as FreeCAD's rrf_post writes it; an ISO "
            "control reads S as the spindle speed: write G4 P)")


def read_words(code: str, where: Where, *, value: Callable[[int, str], tuple[float | None, int]] | None = None,
               assignment: Callable[[int], int] | None = None) -> list[Word]:
    """The words of a comment-free line, left to right.

    ``value(pos, letter)`` reads a word's value after its letter (default: a plain decimal number;
    ``None``, a Fanuc vacant variable, leaves the word out);
    ``assignment(pos)`` handles a ``#`` where a word would start and returns where it ends (default:
    none allowed). :mod:`interpolators.iso_params` passes both to read parameters and expressions.
    """
    if value is None and assignment is None:
        plain = plain_words(code)
        if plain is not None:
            return plain
    words: list[Word] = []
    i, n = 0, len(code)
    while i < n:
        ch = code[i]
        if ch in " \t\r\f\v":
            i += 1
            continue
        if ch == "#" and assignment is not None:
            i = assignment(i)
            continue
        up = ch.upper()
        comma = i
        corner = _CORNER.match(code, i) if ch == "," else None
        if corner is not None:  # Fanuc/Haas ,R ,C (interpolators.iso_corners); blanks between, as anywhere in a block
            up = "," + corner.group(1).upper()
            i = corner.start(1)
        if ch == "/" and words:
            axis = re.match(r"/\s*([XYZABCUVW])(?![A-Z])", code[i:], re.I)
            if words[-1].letter == "M" and axis is not None:
                # swissi2000's Fusion post for Centroid (centroid.cps, resetRotary) writes "M26/A" before "G92 A0"
                where.fail(f"'{words[-1].text}/{axis.group(1).upper()}': an M code with an axis after '/', Centroid "
                           "CNC12's form (M26/A, as the Fusion Centroid post homes a rotary axis; M91/M92 /Z); vcnc "
                           "reads no Centroid program", column=i + 1, text=code[i:i + axis.end()],
                           expected="an M code without an axis argument (a Fanuc/Haas/LinuxCNC/grbl program)")
            tok = re.match(r"/[0-9.]*", code[i:]).group(0)
            where.fail(f"'{tok}' after the word {words[-1].text!r}: arithmetic on a word's value needs brackets "
                       f"({words[-1].letter}[...{tok}]), and a '/' block skip inside a block is not supported",
                       column=i + 1, text=tok, expected=f"{words[-1].letter}[expression]")
        if ch == "[":
            close = code.find("]", i)
            tok = code[i:close + 1] if close > i else token_at(code, i)
            if not words and _BRACKET_PROSE.fullmatch(tok):
                where.fail(f"'{tok}': text in square brackets at the start of a block, a comment as WinCNC "
                           "(CAMaster routers) writes them (Vectric's WinCNC posts head their programs so) or a "
                           "template's placeholder left in, not a word; vcnc's dialects take comments in ( ) or after "
                           "a semicolon", column=i + 1, text=tok,
                           expected="a comment in ( ) or after ; (or a control that reads [ ] comments)")
            where.fail(f"'{tok}' in brackets where a word should start (a template's placeholder, or an "
                       "expression the CNCjs sender evaluates, as a CNCjs macro writes 'G0 X[xmin]'?)",
                       column=i + 1, text=tok, expected="a word such as X12.5 or X[expression]")
        if ch == "/" and not words:
            _slash_comment_line(code, where, second=i)
        if ch == "$" and SPINDLE_SELECT.match(code, i):
            up = "$"  # LinuxCNC's spindle selection; the dialects that do not read it refuse it (iso_mcodes)
        elif up not in WORD_LETTERS and up not in (",R", ",C"):
            tok = token_at(code, i)
            if set(tok) == {"."}:
                where.fail(f"{tok!r} where a word should start (an ellipsis: the program left incomplete here?)",
                           column=i + 1, text=tok, expected="a word such as X12.5")
            if ch.isdigit() or ch in ".+-":
                where.fail(f"number {tok!r} without its letter", column=i + 1, text=tok,
                           expected="a word: a letter and its number, such as G21 or X12.5")
            where.fail(f"unknown word {tok!r}{foreign_hint(tok, first=not code[:i].strip())}", column=i + 1,
                       text=tok,
                       expected="a word of the letters " + " ".join(sorted(WORD_LETTERS)))
        if value is None:
            v, end = read_number(code, i + 1, where, what=f"word {up}", word_start=i)
        else:
            v, end = value(i + 1, up)
        if v is not None:
            start = comma if up[0] == "," else i
            words.append(Word(up, v, start + 1, code[start:end].strip()))
        i = end
    return words


def plain_words(code: str, *, checked: bool = False) -> list[Word] | None:
    """The words of a comment-free line of letters and plain numbers only, as :func:`read_words` reads
    them; ``None`` for any other line (and for a number out of range), which :func:`read_words` then
    reads, or rejects, character by character. A shortcut for the bulk of CAM output. ``checked``: the
    caller has matched the line against a pattern of such lines (:mod:`interpolators.iso_flow` indexes
    them), which is not matched again."""
    if not checked and _PLAIN_LINE.fullmatch(code) is None:
        return None
    words = []
    new = object.__new__
    # matched from each letter, not from the blanks before it: a run of blanks is then passed in one step, where
    # a pattern starting with the blanks retries the run from each of them (quadratic: minutes on a line)
    for m in _PLAIN_TOKEN.finditer(code):
        letter, number = m.groups()
        v = float(number)
        if not -MAX_MAGNITUDE <= v <= MAX_MAGNITUDE:
            return None
        w = new(Word)  # a Word without the frozen dataclass's per-field object.__setattr__: one per word read
        d = w.__dict__
        d["letter"], d["value"], d["column"], d["text"] = letter.upper(), v, m.start() + 1, m.group()
        words.append(w)
    return words


def fail_words(where: Where, name: str, exc: WordError, seen: dict, word) -> None:
    """Report ``exc`` of the feature ``name`` at the word it names (else at ``word``, the G code)."""
    bad = seen.get(exc.letter, word) if exc.letter else word
    where.fail(f"{name}: {exc}", column=bad.column, text=bad.text, expected=exc.expected)


def offset_number(w: Word, where: Where, code: str) -> int:
    """The value of ``w`` (an ``H`` or ``D`` offset number of ``code``, e.g. ``G43``) as a whole number >= 0. rs274ngc
    refuses another: "Non integer value for integer" (interp_read.cc ``read_integer_value``, ``G43 H1.5``) and
    "Requested tool -1 not found in the tool table" (``G43 H-1``); Fanuc refuses a decimal point after H or D (alarm
    PS0007 "illegal use of decimal point"; a sign there, our reading, likewise)."""
    if w.value != int(w.value) or w.value < 0:
        why = ("LinuxCNC: \"Non integer value for integer\"; Fanuc: alarm PS0007, no decimal point after "
               f"{w.letter}" if w.value != int(w.value) else
               f"LinuxCNC: \"Requested tool {w.value:g} not found in the tool table\"")
        where.fail(f"{code} {w.text.strip()}: the offset number {w.letter} must be a whole number >= 0 ({why})",
                   column=w.column, text=w.text, expected=f"{code} {w.letter}<n>, n = 0, 1, 2, ... (a tool or "
                                                          "offset number)")
    return int(w.value)
