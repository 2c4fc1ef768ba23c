"""Shared pieces of the two G-code readers: numbers, source positions, error raising."""

from __future__ import annotations

import dataclasses
import re

from vcnc.core.errors import GCodeError
from vcnc.core.text import decode_text

#: A decimal number as written in part programs: optional sign, digits with an optional point
#: (``12``, ``-0.79``, ``+.5``, ``5.``); no exponent.
NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)")

#: Largest accepted magnitude of a programmed number (mm, mm/min, ms, ...).
MAX_MAGNITUDE: float = 1e9

#: mm per inch.
INCH: float = 25.4


@dataclasses.dataclass(frozen=True)
class Where:
    """Source position for error messages.

    ``pieces``: a block continued over several lines (a Heidenhain cycle definition's ``~`` lines) read as one
    text; each ``(start, line, column)`` says that the text from index ``start`` on comes from ``line`` at
    ``column`` (1-based), so that an error names the line and column where the word is written.
    """

    file: str | None
    line: int
    text: str
    pieces: tuple[tuple[int, int, int], ...] = ()

    def fail(self, message: str, *, column: int | None = None, text: str | None = None, expected: str | None = None):
        """Raise a GCodeError at this line (``column`` 1-based, of the block's text read as one)."""
        line = self.line
        for start, piece_line, piece_column in reversed(self.pieces if column is not None else ()):
            if column >= start:  # from the blank that joins the piece to the one before
                line, column = piece_line, piece_column + max(column - 1 - start, 0)
                break
        raise GCodeError(message, file=self.file, line=line, column=column, text=text, expected=expected)


def lines_of(text: str) -> list[str]:
    """Lines split at newline only (editors' numbering), without a trailing carriage return."""
    return [ln[:-1] if ln.endswith("\r") else ln for ln in text.split("\n")]


def token_at(line: str, pos: int) -> str:
    """The run of characters at ``pos`` up to the next space or tab (at least one character)."""
    m = re.compile(r"[^ \t]+").match(line, pos)
    return m.group(0) if m else line[pos : pos + 1]


def checked_float(tok: str, where: Where, *, column: int, what: str) -> float:
    """``float(tok)`` with the magnitude check of :data:`MAX_MAGNITUDE`."""
    value = float(tok)
    if abs(value) > MAX_MAGNITUDE:
        where.fail(f"number out of range for {what}", column=column, text=tok,
                   expected=f"a magnitude <= {MAX_MAGNITUDE:g}")
    return value


#: Statements of Siemens SINUMERIK's NC language, which a G-code reader meets as a letter without a number
#: (SINUMERIK 840D sl Programming Manual Fundamentals, 6FC5398-2EP40-0BA0, 2.12 "Coordinate transformations
#: (frames)": TRANS/ATRANS, ROT/AROT, ROTS/AROTS, SCALE/ASCALE, MIRROR/AMIRROR; motion commands CIP, CT,
#: ASPLINE/BSPLINE/CSPLINE, SUPA; Job Planning: DEF, GOTOF/GOTOB, LOOP/ENDLOOP, FOR/ENDFOR, WHILE/ENDWHILE,
#: REPEAT/UNTIL, STOPRE, MSG, MCALL, PROC; technology cycles CYCLEnn).
_SINUMERIK = re.compile(r"(?:DEF|A?TRANS|A?ROTS?|A?SCALE|A?MIRROR|CIP|CT|[ABC]SPLINE|SUPA|GOTO[FBC]|ENDLOOP|"
                        r"ENDFOR|ENDWHILE|ENDIF|REPEAT|UNTIL|STOPRE|MSG|MCALL|PROC|CYCLE\d+)", re.I)
#: A SINUMERIK address with '=': "X=R0", "X=IC(5)", circle radius "CR=5", polar "AP=30" "RP=10" (Fundamentals:
#: "Circular interpolation with radius and end point: G2/G3 X... Y... CR=..."; ISO G-code has no '=' after an
#: address letter).
_SINUMERIK_ADDRESS = re.compile(r"(?:[A-Z]|CR|AP|RP|AR|TURN)=", re.I)


#: A DATRON SimPL motion or work-offset statement: "Rapid X=10 Y=20", "Line Z=-1", "LoadWcs name=\"1\"" (the
#: keyword, blanks, then an address with '=').
_SIMPL = re.compile(r"(?:Rapid|Line|Arc|LoadWcs)[ \t]+[A-Za-z]+[ \t]*=")


#: A line that is a Markdown code fence or its language tag ("```gcode", "gcode"): a program copied out of a
#: README or a chat answer with its fence (CommonMark 0.31, 4.5 "Fenced code blocks": the opening fence's
#: "info string", whose first word names the language).
_FENCE = re.compile(r"[ \t]*(?:```+|~~~+)?[ \t]*(?:g-?code|nc|ngc|cnc|tap)?[ \t]*", re.I)


def fence_hint(line: str) -> str:
    """What a line that is a Markdown code fence or only its language tag is (:data:`_FENCE`); "" otherwise."""
    if line.strip() and _FENCE.fullmatch(line):
        return " (a Markdown code fence or its language tag: text copied from a README or a chat answer?)"
    return ""


#: Axis letters, whose word without a number :func:`_bare_axis_hint` names.
_AXIS_LETTERS = frozenset("XYZABCUVW")


def _bare_axis_hint(line: str, w0: int) -> str:
    """Why an axis letter stands without its number: 3D printer firmware writes axes as flags ("G28 X":
    Marlin's G-code reference, G28 Auto Home, "X: flag to go back to the X axis origin"; RepRapFirmware
    likewise), and a generator for such a machine writes them so. An ISO control needs the number (LinuxCNC
    and grbl refuse the bare letter, "Bad number format"; Fanuc alarm PS0005 "no data after address"), and
    its G28 moves through the point the axis words name first, so that ``G91 G28 X0`` returns X alone
    (LinuxCNC G28, Fanuc "Reference position return")."""
    letter = line[w0].upper()
    if re.search(r"\bG0*28\b", line[:w0], re.I):
        return (f" (an axis letter without its number: 'G28 {letter}', home {letter}, as 3D printer firmware such as "
                f"Marlin writes it; an ISO control needs a number: G91 G28 {letter}0 returns {letter} alone)")
    return " (an axis letter without its number, as 3D printer firmware such as Marlin takes axis flags)"


#: A comment that is one identifier of capitals joined by underscores, "(GCODE_OP_SAFEZ)", right after a word's
#: letter: a generator's template, whose placeholders the generator replaces with numbers (ncEFI's
#: "ncPRG_start.nc": "F(GCODE_OP_BFEED)", "G00 Z(GCODE_OP_SAFEZ)").
_PLACEHOLDER = re.compile(r"[ \t]*\([ \t]*([A-Z][A-Z0-9]*(?:_[A-Z0-9]+)+)[ \t]*\)")


def _placeholder_hint(letter: str, raw: str) -> str:
    """The hint for a word whose number is a template's placeholder comment (:data:`_PLACEHOLDER`) in the
    source line ``raw``; "" when there is none."""
    for m in re.finditer(re.escape(letter), raw, re.I):
        hole = _PLACEHOLDER.match(raw, m.end())
        if hole:
            return (f" (a template's placeholder '({hole.group(1)})' where the number goes: a generator fills "
                    "it in, so the file is a template, not a program)")
    return ""


def _number_hint(line: str, w0: int, j: int, raw: str = "") -> str:
    """Why a word at ``w0`` has no number at ``j``, when the text says: a template's placeholder comment in the
    source line ``raw``, the letter O for the digit 0, a Siemens SINUMERIK statement or ``=`` address, a keyword
    of another control's language."""
    fence = fence_hint(line)
    if fence:
        return fence
    # "M3 I": Marlin's inline laser power mode ("M3 [I<mode>] [O<power>] [S<power>]", "[I<mode>] Inline mode
    # ON / OFF", marlinfw.org/docs/gcode/M003.html), as Marlin laser programs start
    if line[w0:w0 + 1] in "iI" and re.search(r"M0*[34][ \t]*$", line[:w0], re.I):
        return (" (M3 I / M4 I: Marlin's inline laser power mode, 'M3 [I<mode>]', which a Marlin laser program "
                "sets; no ISO control reads it: M3 S<power> is the form the grbl dialect reads)")
    # "M117 Cutting Toolpath 1": Marlin's LCD message, "M117 [string]" (marlinfw.org/docs/gcode/M117.html; M118
    # "Serial print" likewise), which Vectric's and Estlcam's Marlin posts (MPCNC routers) write: the rest of the line
    # is text
    marlin = re.search(r"(?<![A-Za-z])M0*(11[78])(?![0-9.])", line[:w0], re.I)
    if marlin:
        return (f" (M{marlin.group(1)} <text>: Marlin's {'LCD message' if marlin.group(1) == '117' else 'serial print'}"
                ", whose text is no G-code; a 3D printer firmware's code, which no dialect of vcnc reads: remove the "
                "line to run the rest with --dialect grbl)")
    placeholder = _placeholder_hint(line[w0], raw) if raw and (j >= len(line) or line[j] in " \t") else ""
    if placeholder:
        return placeholder
    if j < len(line) and line[j] in "oO" and re.match(r"[oO0-9.]+(?![A-Za-z])", line[j:]):  # "GOO", "X1O"
        return " (the letter O where the digit 0 was meant?)"
    siemens = re.match(r"[A-Za-z]+\d*(?![A-Za-z0-9_])", line[w0:])
    if siemens and _SINUMERIK.fullmatch(siemens.group(0)):
        return f" ({siemens.group(0)!r}: a Siemens SINUMERIK statement; vcnc reads ISO G-code, not SINUMERIK programs)"
    address = _SINUMERIK_ADDRESS.match(line, w0)
    if address:
        return (f" ({address.group(0)!r}: a Siemens SINUMERIK address with '='; vcnc reads ISO G-code, not "
                "SINUMERIK programs)")
    # the letter then blanks, and the end of the block or another word: not a keyword such as ASKBOOL
    if line[w0:w0 + 1].upper() in _AXIS_LETTERS and (j >= len(line) or j > w0 + 1 and line[j].isalpha()):
        return _bare_axis_hint(line, w0)
    # "CALL OO30": Okuma OSP's subprogram call (the Autodesk OKUMA OSP-P300 post's "CALL OO88" for 3+2
    # machining; Okuma user tasks are called "with the word CALL xxxx", as MachinistFTW/OkumaMacros' README says)
    if re.match(r"CALL\s*O\w", line[w0:], re.I):
        return " ('CALL O<name>': Okuma OSP's subprogram call; vcnc reads ISO G-code, not OSP programs)"
    # "Rapid X=10 Y=20 Z=5", "Line X=20", "LoadWcs name=..": DATRON's SimPL, the language of the DATRON next
    # control, as Autodesk's "datron next.cps" writes it (its writeBlock("Rapid" ..), xOutput prefix " X=",
    # extension "simpl"); no ISO G-code
    if _SIMPL.match(line, w0):
        return (" (DATRON SimPL, the language of the DATRON next control, as Fusion's 'datron next.cps' writes "
                "'Rapid X=.. Y=..' and 'Line X=..': vcnc reads ISO G-code, not SimPL programs)")
    # "PRINT", "ASKBOOL": a statement of a control's own language (KinetiC-NC's BASIC-like lines), not a word
    keyword = re.match(r"[A-Za-z]{4,}\b", line[w0:])
    return f" ({keyword.group(0)!r}: a statement of another control's language, such as KinetiC-NC's PRINT?)" \
        if keyword else ""


def read_number(line: str, pos: int, where: Where, *, what: str, word_start: int | None = None) -> tuple[float, int]:
    """Read a number at ``pos`` (spaces before it allowed); returns (value, end position).

    Errors point at ``word_start`` (the address letter) when given.
    """
    w0 = pos if word_start is None else word_start
    n = len(line)
    j = pos
    while j < n and line[j] in " \t":
        j += 1
    m = NUMBER_RE.match(line, j)
    if m is None:
        where.fail(
            f"malformed number for {what}{_number_hint(line, w0, j, where.text)}",
            column=w0 + 1,
            text=token_at(line, w0),
            expected="a decimal number such as 12, -0.79 or +.5",
        )
    end = m.end()
    value = float(m.group(0))
    if abs(value) > MAX_MAGNITUDE:
        where.fail(f"number out of range for {what}", column=w0 + 1, text=token_at(line, w0),
                   expected=f"a magnitude <= {MAX_MAGNITUDE:g}")
    # a number glued to another point or digit-like junk ("1.2.3", "5x") is malformed
    if end < n and (line[end] == "." or line[end].isdigit()):
        where.fail(f"malformed number for {what}", column=w0 + 1, text=token_at(line, w0),
                   expected="a decimal number")
    return value, end


def program_text(path: str) -> str:
    """A program file's text (:func:`vcnc.core.text.decode_text`: UTF-8 or UTF-16 by its byte-order mark,
    else UTF-8, else Windows-1252), without a BOM.

    Raises ``OSError`` when the file cannot be read and ``vcnc.core.text.BinaryDataError`` when it holds no
    text (the callers name the file).
    """
    with open(path, "rb") as fh:
        raw = fh.read()
    text = decode_text(raw)
    return text[1:] if text.startswith("\ufeff") else text
