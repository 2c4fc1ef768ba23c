"""Blocks and words of Heidenhain conversational programs (the lexical layer of the reader).

A program line is ``[block number] <keyword> <words> [;comment]`` (HEIDENHAIN TNC 640 user's
manual, "Programming fundamentals: NC blocks"). This module

* splits the text into :class:`SourceBlock` s: ``;`` comments removed, lines ending in ``~``
  joined with the next (a cycle definition written one Q parameter per line, as the TNC saves it;
  the older TNCs' ``Qnnn=`` / ``POSn (..)`` lines without ``~`` and block number after a
  ``CYCL DEF 2xx`` / ``PATTERN DEF`` too),
  the old block end ``*`` dropped, ``* ...`` structure blocks recognised, and the decimal comma
  of programs saved by TNCs set to it (``X+50,022``, ``CYCL DEF 32.1 T0,01``) read as a point;
* reads the words of a block (:func:`read_words`): axis words ``X+10`` / ``IX-5`` (``I`` for
  incremental), polar ``PR``/``PA`` (``IPR``/``IPA``), ``R``, ``DR+``/``DR-``, ``R0``/``RL``/``RR``,
  ``F``/``F MAX``/``FMAX``/``F AUTO`` (key ``FAUTO``), ``FU``/``FZ`` (per revolution / tooth),
  ``M``, ``MB MAX``, LN's vector components ``NX``..``TZ``, and a value that is a number, a Q parameter
  (``X+Q1``, ``IX-Q3``, ``FQ58``) or a parenthesised formula (``X+(Q1+2)``);
* reads ``R``, ``F`` and ``M`` without a value (``L X+32,000 Y+0,000 R F5000 M13``, ``L X+12,500
  R F M``, ``CYCL CALL M``, as programs of the older TNCs were saved) as key ``EMPTY``: the
  dialog's field left empty, the same as not writing the word (:data:`EMPTY_FIELD_NOTE`).
"""

from __future__ import annotations

import dataclasses
import re

from interpolators._words import NUMBER_RE, Where, lines_of, token_at
from interpolators.heidenhain_params import Q_NAME_RE, QParameters

__all__ = ["EMPTY_FIELD_NOTE", "SourceBlock", "Word", "decimal_points", "ignored_m_note", "source_blocks", "read_words",
           "read_value"]


@dataclasses.dataclass(frozen=True)
class SourceBlock:
    """One block of the program text.

    Attributes
    ----------
    line : int
        1-based line of the block's first line.
    number : int or None
        Block number as written.
    code : str
        The block without number, comment and ``*`` end (continuation lines joined).
    column : int
        1-based column of ``code`` in the first line.
    text : str
        The stripped source line (for messages).
    skip : bool
        The block is marked ``/`` (before or after its number): hidden when the operator switches
        block skip on (TNC 640 user's manual, "Hiding blocks"); it runs here, the switch off.
    pieces : tuple of (int, int, int)
        A block continued over lines: where each line's text starts in the joined line (index, its 1-based
        line and column; see :class:`interpolators._words.Where`); empty for a block of one line.
    """

    line: int
    number: int | None
    code: str
    column: int
    text: str
    skip: bool = False
    pieces: tuple[tuple[int, int, int], ...] = ()

    def where(self, source: str | None) -> Where:
        """Source position of this block for error messages."""
        return Where(source, self.line, self.text, self.pieces)


@dataclasses.dataclass(frozen=True)
class Word:
    """One word of a block: ``key`` (``"X"``, ``"IX"``, ``"F"``, ``"FMAX"``, ``"DR"``, ...)."""

    key: str
    value: object
    column: int
    text: str
    #: The parameters an M function takes after it (:data:`M_ARGUMENTS`): ``(("LA", 3.0),)`` of ``M120 LA3``,
    #: ``(("C", None),)`` of ``M94 C``.
    args: tuple[tuple[str, float | None], ...] = ()


#: How a word letter without a value is read. Programs saved by older TNCs (TNC 155/355 era: the
#: 668.klartext and 700.klartext samples of drunsinn/language-klartext) show each field of the L
#: dialog (radius compensation, feed, M function) as its letter, with nothing after it when the
#: field was not filled in. No manual describing this saved form was found; a field left empty
#: programs nothing, so ``R`` leaves the radius compensation as it is, ``F`` the modal feed, and
#: ``M`` adds no M function, and the run notes the reading.
EMPTY_FIELD_NOTE = ("R, F or M without a value read as a dialog field left empty (as older TNCs save "
                    "'R F M'): radius compensation, feed and M functions unchanged")


_HEAD_RE = re.compile(r"\s*(?P<pre>/)?\s*(?P<num>\d+)?\s*(?P<post>/(?![/*]))?\s*")


def _strip_comment(line: str) -> str:
    return line.split(";", 1)[0]


_DEFINITION_RE = re.compile(r"\s*\d*\s*(?:((?:CYCLE?\s+DEF|TCH\s+PROBE)\s*\d{3})|(PATTERN\s+DEF))(?![\d.])", re.I)
_Q_LINE_RE = re.compile(r"\s*Q\d+\s*=", re.I)
#: A pattern's item line after ``PATTERN DEF``: ``POS1 (``, and the forms ``ROW1``, ``CIRC1``, ``PITCHCIRC1``, ``PAT1``,
#: ``FRAME1`` (TNC 640 cycle programming manual, "PATTERN DEF"), each on a line of its own as the TNC saves them.
_POS_LINE_RE = re.compile(r"\s*(?:POS|ROW|PITCHCIRC|CIRC|PAT|FRAME)\d+\s*\(", re.I)
#: ``Q206 FAUTO``: a parameter line missing its ``=`` (a TNC simulator's test program): kept with its definition, so
#: that the cycle's reader names it (:func:`interpolators.heidenhain_cycles.q_assignments`).
_Q_WITHOUT_EQUALS_RE = re.compile(r"\s*Q\d+\s+[A-Z+\-\d]", re.I)


def _continues(first: str, line: str) -> bool:
    """True when ``line`` is a parameter line of the definition that ``first`` begins: the
    ``Qnnn=value ;comment`` lines after ``CYCL DEF 2xx`` or ``TCH PROBE 4xx`` and the ``POSn (...)`` lines
    (``PAT1 (..)``, ``ROW1 (..)``, every item of :data:`_POS_LINE_RE`)
    after ``PATTERN DEF``, written without a block number and without ``~`` as the iTNC 530 and TNC
    426/430 save them (iTNC 530 user's manual, cycle examples: "11 CYCL DEF 200 DRILLING /
    Q200=2 ;SET-UP CLEARANCE / ..."; the touch probe cycles' examples alike: "5 TCH PROBE 412 DATUM INSIDE
    CIRCLE / Q321=+50 ;CENTER IN 1ST AXIS / ...", iTNC 530 touch probe cycles manual, example of cycle 412)."""
    m = _DEFINITION_RE.match(first)
    if m is None:
        return False
    return (_Q_LINE_RE.match(line) is not None or _Q_WITHOUT_EQUALS_RE.match(line) is not None if m.group(1)
            else _POS_LINE_RE.match(line) is not None)


def _wrapped_comment(line: str) -> bool:
    """True when ``line``, following a line that ends in ``~`` after a ``;`` comment, goes on with
    the comment: the TNC saves a block longer than a line over several lines, each but the last
    ending in ``~`` (a long ``;`` comment of a shop program is saved as ``4 ;This program ... it~`` /
    `` under the terms ...``), so the text after a wrapped ``;comment`` is comment too, unless it is
    the next ``Qnnn=`` / ``POSn (..)`` parameter of a cycle or pattern definition (each of those
    lines carries its own comment: ``Q200=+2 ;SET-UP CLEARANCE ~``)."""
    return _Q_LINE_RE.match(line) is None and _POS_LINE_RE.match(line) is None


def _tilde_before_comment(raw: str) -> str | None:
    """The block text of ``raw`` when its ``~`` stands before a ``;`` comment (``CYCL DEF 200 BOHREN ~
    ;anbohren``), else None. The TNC saves the ``~`` at the very end of a continued line, after the
    line's comment (``Q200=2 ;SET-UP CLEARANCE ~``, TNC 640 user's manual, cycle examples); a program
    edited outside the control may put it before a comment it adds. The ``~`` still says that the
    block goes on (our reading: nothing else is meant by a ``~`` there)."""
    if raw.endswith("~") or ";" not in raw:
        return None
    code = _strip_comment(raw).rstrip()
    return code[:-1] if code.endswith("~") else None


_DECIMAL_COMMA_RE = re.compile(r'"[^"]*"|(?<=\d),(?=\d)')


def decimal_points(code: str) -> str:
    """``code`` with each decimal comma (a comma between two digits, outside ``"..."`` strings) made
    a point, character for character (columns stay).

    Programs saved by TNCs whose decimal character is the comma write ``L X+50,022``, ``TOOL CALL 3 Z
    S 5000,000`` and ``Q2 = COS (1,57 - Q4)``: HEIDENHAIN's own demonstration programs 668, 700 and
    7025 and shop programs of the iTNC 530 are saved so. The manuals print the point; a comma has no
    other use between two digits of a conversational block (our reading of those programs).
    """
    if "," not in code:
        return code
    return _DECIMAL_COMMA_RE.sub(lambda m: m.group(0) if m.group(0).startswith('"') else ".", code)


#: A line that is one block as it stands (no ``~ ; , / *``, checked apart): its block number and the blanks after
#: it, as :data:`_HEAD_RE` reads them, before the block's first character (neither a blank, a digit nor ``*``).
_PLAIN_LINE_RE = re.compile(r"[ \t]*(?:(\d+)[ \t]+)?(?=[^\s\d*])")


def source_blocks(text: str) -> list[SourceBlock]:
    """The blocks of a program text (empty lines, comments and ``*`` structure blocks left out)."""
    out: list[SourceBlock] = []
    lines = lines_of(text)
    i = 0
    while i < len(lines):
        first = i
        raw = lines[i].rstrip()
        plain = (None if "~" in raw or ";" in raw or "," in raw or "/" in raw or raw.endswith("*")
                 else _PLAIN_LINE_RE.match(raw))
        if plain is not None and (i + 1 == len(lines) or not _continues(raw, lines[i + 1])):
            # most lines of a CAM program: the block is the line (what the general reading below makes of it)
            number, pos = plain.group(1), plain.end()
            out.append(SourceBlock(i + 1, int(number[:9]) if number else None, raw[pos:], pos + 1, raw.lstrip()))
            i += 1
            continue
        parts: list[tuple[str, int, int]] = []  # each line's text, its 1-based line and the column it starts at
        comment = False
        while True:
            raw = lines[i].rstrip()
            before = _tilde_before_comment(raw)
            more = (raw.endswith("~") or before is not None) and i + 1 < len(lines)
            body = raw if not more else raw[:-1] if before is None else before
            if not (comment and _wrapped_comment(body)):
                comment = ";" in body
                part = _strip_comment(body)
                parts.append((part.strip(), i + 1, 1 + len(part) - len(part.lstrip())) if parts
                             else (part.rstrip(), i + 1, 1))
            i += 1
            if not more:
                break
        while i < len(lines) and _continues(parts[0][0], lines[i]):
            part = _strip_comment(lines[i])
            parts.append((part.strip().rstrip("~").strip(), i + 1, 1 + len(part) - len(part.lstrip())))
            i += 1
        code = decimal_points(" ".join(p for p, _, _ in parts if p))
        pieces, start = [], 0
        for p, line, column in parts:
            if p:
                pieces.append((start, line, column))
                start += len(p) + 1
        if code.endswith("*"):
            code = code[:-1].rstrip()
        m = _HEAD_RE.match(code)
        number = int(m.group("num")[:9]) if m.group("num") else None
        pos = m.end()
        rest = code[pos:]
        if not rest.strip() or rest.startswith("*"):
            continue
        out.append(SourceBlock(first + 1, number, rest, pos + 1, lines[first].strip(),
                               skip=bool(m.group("pre") or m.group("post")),
                               pieces=tuple(pieces) if len(pieces) > 1 else ()))
    return out


_VALUE_HEAD_RE = re.compile(r"\s*([+-]?)\s*")


def read_value(code: str, pos: int, where: Where, params: QParameters, *, what: str, column0: int) -> tuple[float, int]:
    """Read a value at ``pos``: signed number, signed Q parameter or ``(formula)``.

    Returns the value and the position after it. ``column0`` is the 1-based column of
    ``code[0]`` in the source line.
    """
    m = _VALUE_HEAD_RE.match(code, pos)
    sign = -1.0 if m.group(1) == "-" else 1.0
    j = m.end()
    if j < len(code) and code[j] == "(":
        depth, k = 0, j
        while k < len(code):
            depth += {"(": 1, ")": -1}.get(code[k], 0)
            k += 1
            if depth == 0:
                break
        if depth:
            where.fail(f"unclosed '(' in {what}", column=column0 + j, text=code[j:].strip(), expected="')'")
        return sign * params.evaluate(code[j:k], where, column=column0 + j), k
    q = Q_NAME_RE.match(code, j)
    if q is not None:
        return sign * params.get(q.group(0)), q.end()
    n = NUMBER_RE.match(code, j)
    if re.match(r"(nan|inf)(?![A-Z])", code[j:], re.I):
        where.fail(f"{what} is {code[j:j + 3]!r}, not a number (an undefined value written by the post-processor)",
                   column=column0 + pos, text=token_at(code, pos), expected="a finite number")
    if n is None or n.group(0)[0] in "+-":
        tok = token_at(code, pos)
        where.fail(f"malformed number for {what} in {tok!r}", column=column0 + pos, text=tok,
                   expected="a signed number, a Q parameter (X+Q1) or a formula in parentheses")
    end = n.end()
    if end < len(code) and (code[end] == "." or code[end].isalnum()):
        tok = token_at(code, pos)
        where.fail(f"malformed number for {what} in {tok!r}", column=column0 + pos, text=tok,
                   expected="a signed number, a Q parameter (X+Q1) or a formula in parentheses")
    return sign * float(n.group(0)), end


_WORD_RE = re.compile(
    r"(?P<fmax>F\s*MAX)(?![A-Z])|(?P<fauto>F\s*AUTO)(?![A-Z])|(?P<mbmax>MB\s*MAX)(?![A-Z])"
    r"|(?P<dr>DR\s*[+-])(?![\d.Q(])|(?P<rcomp>R[LR0])(?![\d.A-Z])"
    r"|(?P<len>LEN)(?=\s*[+-]?\s*[\d.Q(])|(?P<cca>CCA)(?=\s*[+-]?\s*[\d.Q(])|(?P<polar>I?P[AR])|(?P<vec>[NT][XYZ])(?=\s*[+-]?\s*[\d.Q(])|(?P<axis>I?[XYZ])|(?P<rot>I?[ABCUVW])(?=\s*[+-]?\s*[\d.Q(])"
    r"|(?P<empty>[RFM])(?=\s*$|\s+[A-PR-Z])"
    r"|(?P<m>M)(?=\s*\d)|(?P<mb>MB)|(?P<fu>F[UZ])(?=\s*[+-]?\s*[\d.Q(])|(?P<feed>F)|(?P<rad>R)(?=\s*[+-]?\s*[\d.Q(])|(?P<bare>(?=[+-]\s*[\d.Q(]))",
    re.I,
)

#: Words a motion block may carry, for messages.
WORDS_EXPECTED = ("X/Y/Z (I for incremental), PR/PA, R, DR+/DR-, R0/RL/RR, F, F MAX, M, MB MAX, LEN or CCA; "
                  "values may be numbers, Q parameters or (formulas)")


#: Where a TNC program sets the spindle speed. Our reading of the TNC 640 / iTNC 530 user's manuals, which
#: program S only in ``TOOL CALL`` ("Calling tool data"; the system data of the TNC 426 list the speed among
#: the "values programmed in TOOL CALL", ID60 NR3): an NX post's ``L Z-45. F1000. S6000`` is refused.
SPEED_EXPECTED = "S in a TOOL CALL block (TOOL CALL [n] Z S.., a speed change without a tool change)"


#: M functions that take parameters after them, and which (TNC 640 / iTNC 530 / TNC 426 user's manuals,
#: "Miscellaneous functions"): ``M94 C`` (the rotary axis whose display is reduced, a letter alone),
#: ``M103 F..`` (the plunging feed [%]), ``M138 B C`` (the rotary axes M128 / M114 take, letters alone),
#: ``M112 T.. A..`` (TNC 426/430, TNC 407: ``E``, ``H``: contour tolerance and limit angle), ``M118 X.. Y..``
#: (handwheel superimposition limits), ``M120 LA..`` (blocks calculated in advance), ``M124 T..`` (the
#: least distance of the points M112 takes).
M_ARGUMENTS = {
    94: frozenset("ABC"),
    103: frozenset({"F"}),
    138: frozenset("ABC"),
    112: frozenset({"T", "A", "E", "H"}),
    118: frozenset("XYZABCUVW"),
    120: frozenset({"LA"}),
    124: frozenset({"T"}),
}
_M_ARG_RE = re.compile(r"\s*(LA|[A-Z])", re.I)


def _m_arguments(code: str, pos: int, number: int, where: Where, params: QParameters, *,
                 column0: int) -> tuple[tuple[tuple[str, float | None], ...], int]:
    """The parameters of M function ``number`` from ``pos`` on (:data:`M_ARGUMENTS`) and the position after
    them; ``M94``'s axis letter stands alone, the others carry a value (a number, ``Qn`` or a formula)."""
    allowed = M_ARGUMENTS.get(number)
    args: list[tuple[str, float | None]] = []
    while allowed:
        am = _M_ARG_RE.match(code, pos)
        if am is None or am.group(1).upper() not in allowed:
            break
        letter, after = am.group(1).upper(), am.end()
        has_value = re.match(r"\s*[+-]?\s*[\d.Q(]", code[after:], re.I) is not None
        if number in (94, 138):
            if has_value or (after < len(code) and not code[after].isspace()):
                break
            args.append((letter, None))
            pos = after
            continue
        if not has_value:
            break
        value, pos = read_value(code, after, where, params, what=f"M{number} {letter}", column0=column0)
        args.append((letter, value))
    return tuple(args), pos


def read_words(code: str, pos: int, where: Where, params: QParameters, *, column0: int) -> list[Word]:
    """The words of a block from ``pos`` on (see the module text), with values evaluated.

    Raises
    ------
    vcnc.GCodeError
        An unknown word or a malformed value, naming the column.
    """
    out: list[Word] = []
    n = len(code)
    while pos < n:
        if code[pos] in " \t":
            pos += 1
            continue
        col = column0 + pos
        m = _WORD_RE.match(code, pos)
        if m is None:
            tok = token_at(code, pos)
            if re.fullmatch(r"S\s*[+-]?[\d.]+", tok, re.I):  # an ISO post's spindle speed on a positioning block
                where.fail(f"spindle speed {tok!r} in a positioning block", column=col, text=tok,
                           expected=SPEED_EXPECTED)
            _unknown_word(tok, col, where)
        kind = m.lastgroup
        tok = m.group(0)
        end = m.end()
        if kind == "fmax":
            out.append(Word("FMAX", None, col, tok))
        elif kind == "mbmax":
            out.append(Word("MBMAX", None, col, tok))
        elif kind == "fauto":  # the feed of the last TOOL CALL: the reader resolves it
            out.append(Word("FAUTO", None, col, tok))
        elif kind == "dr":
            out.append(Word("DR", tok.replace(" ", "")[-1], col, tok))
        elif kind == "rcomp":
            out.append(Word(tok.upper(), None, col, tok))
        elif kind == "empty":  # a dialog field left empty (EMPTY_FIELD_NOTE): the reader drops it
            out.append(Word("EMPTY", tok.upper(), col, tok))
        elif kind == "rot":  # A, B, C [deg], U, V, W: the reader checks the machine has the axis
            value, end = read_value(code, end, where, params, what=tok.upper(), column0=column0)
            out.append(Word(tok.upper(), value, col, code[pos:end].strip()))
        elif kind == "m":
            mm = re.compile(r"M\s*(\d+)", re.I).match(code, pos)
            end = mm.end()
            if end < n and not code[end].isspace():
                tok = token_at(code, pos)
                where.fail(f"malformed M function {tok!r}", column=col, text=tok, expected="M followed by digits")
            number = int(mm.group(1)[:9])
            args, end = _m_arguments(code, end, number, where, params, column0=column0)
            out.append(Word("M", number, col, code[pos:end].strip(), args))
        elif kind == "mb":
            value, end = read_value(code, end, where, params, what="MB", column0=column0)
            out.append(Word("MB", value, col, code[pos:end]))
        else:
            key = {"polar": tok.upper(), "axis": tok.upper(), "vec": tok.upper(), "feed": "F", "fu": tok.upper(),
                   "rad": "R", "bare": "BARE", "len": "LEN", "cca": "CCA"}[kind]
            value, end = read_value(code, end, where, params, what=key, column0=column0)
            out.append(Word(key, value, col, code[pos:end].strip()))
        if end < n and code[end] not in " \t":
            _unknown_word(token_at(code, pos), col, where)
        pos = end
    return out


def _unknown_word(tok: str, col: int, where: Where) -> None:
    """Fail on the word ``tok`` the block cannot hold. ``RO`` (the letter O: a hand-written warm-up
    program in a wild set wrote it) is named as the radius compensation R0 (digit zero) it stands for
    (TNC 640 user's manual, "Radius compensation": R0, RL, RR)."""
    if tok.upper() == "RO":
        where.fail(f"unknown word {tok!r}: no radius compensation is written with the letter O", column=col,
                   text=tok, expected="R0 (with the digit zero), RL or RR")
    where.fail(f"unknown word {tok!r}", column=col, text=tok, expected=WORDS_EXPECTED)


#: M functions that change the feed or a compensated corner in a way vcnc does not model (TNC 640 user's manual,
#: "Miscellaneous functions"): the note says what the run leaves out, rather than "no motion".
_M_NOT_MODELLED = {
    97: "M97: small contour steps under RL/RR machined as the TNC would (not modelled: compensated as without it)",
    98: "M98: open contour corners under RL/RR (not modelled: compensated as without it)",
    109: "M109/M110: the feed at the cutting edge on compensated arcs (not modelled: F at the tool centre)",
    110: "M109/M110: the feed at the cutting edge on compensated arcs (not modelled: F at the tool centre)",
    116: "M116: the feed of rotary axes in mm/min (not modelled: F of a rotary axis read in deg/min)",
    130: "M130 without a tilted working plane: no effect",  # in one: heidenhain_motion's M130
}


def ignored_m_note(value: int) -> str:
    """The note of an M function the run gives no meaning: what it leaves out (:data:`_M_NOT_MODELLED`), else
    ``M<n> ignored (no motion)``."""
    return _M_NOT_MODELLED.get(value, f"M{value} ignored (no motion)")
