"""The ISO program's text before the reader runs it and the notes around the run (:mod:`interpolators.iso`): grbl's
``$`` lines and ``$H`` taken out (:mod:`interpolators.iso_grbl`), CNCSimulator Pro directives
(:mod:`interpolators.iso_simulator`), LinuxCNC's ``%``-wrapped file read up to its second ``%`` line, the notes of
external output commands and of expressions LinuxCNC refuses, a subprogram file (last block M99) and its program
number, LinuxCNC active comments as messages, Fanuc/Haas ``#3006`` message stops, and the notes a line and the
whole reading leave."""

from __future__ import annotations

import collections
import re
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from interpolators._words import Where
from interpolators.context import DIALECTS, Dialect
from interpolators.iso_flow import BLOCK_DELETE_RUN, SKIP_AFTER_NUMBER
from interpolators.iso_grbl import system_lines
from interpolators.iso_params import Parameters
from interpolators.iso_simulator import simulator_lines
from interpolators.program import MESSAGE_KINDS, Block, Message, end_at_rest

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["prepared_text", "expression_notes", "ends_with_m99", "program_name", "note_comment", "message_stops",
           "line_notes", "closing_notes", "units_note"]


def prepared_text(text: str, source: str | None, dialect: str, notes: Notes) -> tuple[str, list[int], bool]:
    """The program text the reader runs, the lines of grbl's ``$H`` homing commands taken out of it, and whether
    a LinuxCNC file is wrapped in ``%`` lines (read up to the second); notes of what was taken out or is not
    sent."""
    homing: list[int] = []
    if dialect == "grbl":
        text, homing = _grbl_lines(text, source, notes)
    text, directives = simulator_lines(text, dollar=dialect != "grbl")
    for _ in range(directives):
        notes.add("CNCSimulator Pro $-command and #region lines not run (simulator directives, not G-code)")
    wrapped = False
    if dialect == "linuxcnc":
        text, wrapped = _until_closing_percent(_until_program_end(text, notes), notes)
    if _OUTPUT_COMMAND.search(text):
        notes.add("POPEN/DPRNT/BPRNT/PCLOS external output not sent")
    return text, homing, wrapped


def message_stops(params: Parameters, st: State, blocks: list[Block], notes: Notes) -> None:
    """Fanuc/Haas ``#3006 = n (message)`` reached since the last line (:attr:`Parameters.stops`): the path comes to
    rest at the last block before it, as at M0, and the run notes the message shown until cycle start."""
    for line, message in params.stops:
        end_at_rest(blocks)
        st.stopped, st.stop_line = True, line  # the operator may jog before the next move
        notes.add(f"#3006 message stop at line {line} ({message or 'no message'}): the program waits for cycle start")
    params.stops.clear()


def line_notes(fl, source: str | None, external: set[str | None], notes: Notes) -> None:
    """Notes of a line read: a block-delete line run, the first line of a subprogram file."""
    if fl.raw.lstrip().startswith("/"):
        notes.add(BLOCK_DELETE_RUN)
    elif "/" in fl.raw and SKIP_AFTER_NUMBER.match(fl.raw):
        notes.add("/ block skip after the sequence number (N45 /G1 ..): the block runs (switch off)")
    if fl.file != source and fl.file not in external:
        external.add(fl.file)
        notes.add(f"subprogram from {Path(fl.file).name}")


def closing_notes(st: State, blocks: list[Block], dialect: Dialect, notes: Notes, *, reading: str) -> None:
    """What the whole program's reading assumed: positions read after a stop, the initial feed taken, the
    units of a program that states none."""
    for line in sorted(st.stops_read):
        notes.add(f"position read after a program stop (line {line}): the position where the program stopped; a "
                  "jog by the operator is not modelled")
    if st.parts_read:
        notes.add("parts counters #3901/#3902 read as the program set them, 0 before (the virtual machine's count "
                  "starts at 0)")
    if st.initial_feed_line is not None:
        notes.add(f"feed moves before any F word (from line {st.initial_feed_line}) run at the machine's initial feed "
                  f"{dialect.initial_feed:g} mm/min ([program] initial_feed, --initial-feed; Fanuc parameter 1411; "
                  "LinuxCNC and grbl refuse such a move)")
    if not st.units_stated and any(b.kind != "dwell" for b in blocks):
        notes.add(units_note(dialect, reading))


def units_note(dialect: Dialect, reading: str) -> str:
    """The note on a program without G20/G21: the units it is read in, whose default they are, and how to read it
    in the others. The control's power-on units decide (Haas mill operator's manual, Setting 9 "Dimensioning":
    inch or metric; LinuxCNC INI [RS274NGC] RS274NGC_STARTUP_CODE); an inch program without G20, as a Haas set
    to inch runs it, comes out 25.4 times too small in mm."""
    other = "inch" if dialect.default_units == "mm" else "mm"
    base = DIALECTS.get(dialect.name)
    stock = base is None or dialect.default_units == base.default_units
    whose = f"{reading} default" if stock else "the machine's power-on units"
    return (f"no G20/G21: {dialect.default_units} assumed ({whose}; a control powered on in {other} reads it in "
            f"{other}: --default-units {other}, [program] default_units)")


#: A ``(`` inside a ``( ... )`` comment (before any ``;`` comment): rs274 stops at it (interp_internal.cc
#: close_and_downcase: "Nested comment found"); vcnc reads the comment as nested (:mod:`interpolators.iso_words`).
_NESTED_COMMENT = re.compile(r"^[^;\n]*\([^)\n]*\(", re.M)
#: A Fanuc/Haas custom macro B statement opening a line (``IF [..] GOTO n``, ``WHILE [..] DO m``, ``GOTO n``,
#: ``END m``; :mod:`interpolators.iso_macro`): LinuxCNC has no such words, its flow control is O-words (rs274:
#: "Unknown word starting with f" for IF, "Bad character 'w' used" for WHILE, "Unknown word where unary operation
#: could be" for GOTO and END).
_MACRO_B_STATEMENT = re.compile(r"^[ \t]*/?[ \t]*(?:N\d+[ \t]*)?(?:IF[ \t]*\[|WHILE[ \t]*\[|GOTO[ \t]*[\d#\[]|"
                                r"END[ \t]*[123](?![\d.]))", re.M | re.I)
#: An O-word line: its label and keyword. One pattern for both readings of the O-words: the nesting of sub, if,
#: while, do and repeat blocks (:func:`_until_program_end`, :func:`_nest` passes over break and continue) and the
#: loop and label notes (:func:`_loop_notes`, :func:`_duplicate_labels` pass over the closing keywords).
#: An O-word opening an if, while or repeat block: LinuxCNC keeps one line per
#: label and refuses a second block of the same label when it runs (interp_o_word.cc convert_control_functions,
#: O_if / O_while / O_repeat: "duplicate O-word label"; rs274 2.9.0~pre1 refuses a second 'o100 while' so, and runs
#: a second 'o100 do' loop, whose 'o100 while' closes it).
#: Its offsets are kept per call frame, so the same label in two subroutines is no duplicate (rs274 2.9.0~pre1 runs
#: that; sub and endsub lines bound a body here).
_OWORD_LINE = re.compile(r"^[ \t]*/?[ \t]*(?:N\d+[ \t]*)?O[ \t]*(<[^>\n]*>|\d+)[ \t]*"
                         r"(SUB|ENDSUB|IF|ENDIF|WHILE|ENDWHILE|DO|REPEAT|ENDREPEAT|BREAK|CONTINUE)\b", re.M | re.I)
#: The keywords of :data:`_OWORD_LINE` that open a block or bound a body (the duplicate-label check).
_OPENING_KEYWORDS = ("if", "while", "do", "repeat", "sub", "endsub")


#: An M2 or M30 word (program end) in a line's code, comments taken out.
#: LinuxCNC takes the spaces and tabs out of a line before reading it (interp_read.cc ``close_and_downcase``), so
#: ``m 0 2`` and ``M3 0`` end the program too, and ``M2 5`` is M25.
_PROGRAM_END = re.compile(r"[Mm](?:[ \t]*0)*[ \t]*(?:2|3[ \t]*0)(?![ \t]*[\d.])")
#: What may not stand right before the M of :data:`_PROGRAM_END` (a word of a name, ``#<m2>``), checked after the
#: search: a look-behind in the pattern makes it three times slower on a long CAM program.
_BEFORE_NO_END = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_<#")
#: An O-word call: its label (a subroutine after the program end that no line calls is not read).
_OWORD_CALL = re.compile(r"O[ \t]*(<[^>\n]*>|\d+|\[|#)[ \t]*CALL\b", re.I)
#: A Fanuc-style program number alone on its line (``O1``), which LinuxCNC 2.9's M98 calls.
_FANUC_PROGRAM_LINE = re.compile(r"^\s*O\s*\d+\s*$", re.I)
#: An M97 or M98 call of a subprogram, which a Haas or Fanuc program keeps after its M30.
_LOCAL_CALL = re.compile(r"(?<![A-Za-z_<#])M[ \t]*0*9[78](?![\d.])", re.I)
#: The comments of a line: ``( ... )`` and a ``;`` comment to its end.
_LINE_COMMENTS = re.compile(r"\([^)\n]*\)|;.*")


def _until_program_end(text: str, notes: Notes) -> str:
    """The text with the lines after the main program's end blanked (line numbers stay), but for subroutine
    definitions: LinuxCNC ends the program at an M2 or M30 outside any O-word block ("Lines of a file that occur
    after the end of a program are not to be executed. The interpreter does not even read them", overview.adoc
    'Format of a Program'), so text there that is no G-code (a footer of a post, the rest of a file that was
    written over) is never refused; a subroutine defined after it is still found by a call before it (rs274
    2.9.0~pre1 runs ``o100 call`` / ``M2`` / ``o100 sub`` ... ``o100 endsub``, and skips a line ``foo bar )``
    between them), one that no line calls is never read (rs274 runs ``M30`` / ``o200 sub`` / ``foo )``), and
    from a Fanuc-style ``O1`` .. ``M99`` subprogram on (M98, tests/interp/m98m99 of LinuxCNC 2.9) the text is
    read as it is. The lines before the first M2/M30 are scanned for O-words only."""
    first = _program_end(text)
    if first is None:
        return text
    at = text.rfind("\n", 0, first.start()) + 1
    lines = text[at:].split("\n")
    if not any(_LINE_COMMENTS.sub("", raw).strip(" \t\r%") for raw in lines[1:]):
        return text  # nothing after it (most programs): no need to follow the O-words before it
    if _LOCAL_CALL.search(text, 0, at):
        return text  # M97/M98 subprograms after the end (run as Haas and Fanuc run them, noted): read as before
    stack: list[tuple[str, str]] = []
    for m in _OWORD_LINE.finditer(text, 0, at):
        _nest(stack, m.group(1).lower(), m.group(2).lower())
    called = {_label(c.group(1)) for c in _OWORD_CALL.finditer(text)}
    ended = dropped = False
    uncalled = 0  # the depth of the uncalled subroutine after the end being left out (0: none)
    for i, raw in enumerate(lines):
        code = _LINE_COMMENTS.sub("", raw)
        m = _OWORD_LINE.match(raw)
        if ended and not stack and _FANUC_PROGRAM_LINE.match(code):
            break  # a Fanuc-style O<number> .. M99 subprogram (LinuxCNC 2.9 M98): read on, as before
        sub = bool(m) and m.group(2).lower() == "sub"
        if ended and not stack and sub and not called & {_label(m.group(1)), "[", "#"}:
            uncalled = 1  # no line calls it (by its label or a computed one): LinuxCNC never reads it
        if uncalled or ended and not stack and not sub:
            if m:
                _nest(stack, m.group(1).lower(), m.group(2).lower())
            uncalled = len(stack) if uncalled and stack else 0
            dropped = dropped or bool(code.strip(" \t\r%"))
            lines[i] = ""
        elif m:
            _nest(stack, m.group(1).lower(), m.group(2).lower())
        elif not stack and _program_end(code):
            ended = True
    if not dropped:
        return text
    notes.add("lines after M2/M30 not read (LinuxCNC ends the program there)")
    return text[:at] + "\n".join(lines)


def _label(text: str) -> str:
    """An O-word label as LinuxCNC compares it: lower case, without spaces (``close_and_downcase``), a number
    without its leading zeros."""
    label = re.sub(r"[ \t]", "", text).lower()
    return str(int(label)) if label.isdigit() else label


def _program_end(text: str) -> re.Match | None:
    """The first M2 or M30 word of the text (:data:`_PROGRAM_END`), or None."""
    return next((m for m in _PROGRAM_END.finditer(text) if not m.start() or text[m.start() - 1] not in
                 _BEFORE_NO_END), None)


def _nest(stack: list[tuple[str, str]], label: str, keyword: str) -> None:
    """Follow an O-word line (its label and keyword) into or out of the sub, if, while, do and repeat blocks:
    a ``while`` after a ``do`` of its label closes that loop. An ``endsub`` closes the subroutine of its label only:
    one of another label inside a body returns from it when it runs (LinuxCNC checks no label of an endsub or return
    against the subroutine it leaves, interp_o_word.cc ``execute_return``, and skips a definition up to the endsub of
    its own name, interp_read.cc ``read_o``; Skyfire's basic-tool-change.ngc returns by ``o<toolchange> endsub``)."""
    if keyword in ("sub", "if", "do", "repeat") or keyword == "while" and stack[-1:] != [(label, "do")]:
        stack.append((label, keyword))
    elif keyword == "endsub":
        if (label, "sub") in stack:  # the blocks an early endsub leaves open stay open: their closers follow
            stack.remove((label, "sub"))
    elif keyword in ("endif", "endwhile", "endrepeat", "while") and stack:
        stack.pop()


def _until_closing_percent(text: str, notes: Notes) -> tuple[str, bool]:
    """The text up to the second ``%`` line of a file whose first non-blank line is ``%`` (later lines blank, so
    that line numbers stay): LinuxCNC ends the program there (interp_read.cc read_text: INTERP_ENDFILE at a ``%``
    line once the file began with one; rs274 2.9.0~pre1 runs nothing after it); and whether it had both."""
    lines = text.split("\n")
    filled = [i for i, raw in enumerate(lines) if raw.strip()]
    opened = bool(filled) and lines[filled[0]].strip() == "%"
    stray = [i for i in filled[1 if opened else 0:] if lines[i].strip().startswith("%") and lines[i].strip() != "%"
             or lines[i].strip() == "%" and not opened]
    if stray:  # "% ; start flag", or a % after comment lines: rs274 stops there ("Bad character '%' used")
        notes.add("'%' lines LinuxCNC refuses (not the file's first line, or with a comment) skipped")
    if not opened:
        return text, False
    for i in filled[1:]:
        if lines[i].strip() == "%":
            if any(raw.strip() for raw in lines[i + 1:]):
                notes.add("lines after the closing % not run (LinuxCNC ends the program there)")
            return "\n".join(lines[:i + 1] + [""] * (len(lines) - i - 1)), True
    return text, False


def note_comment(keyword: str, text: str, where: Where, *, messages: list[Message], notes: Notes) -> None:
    """A LinuxCNC active comment the run reached (:mod:`interpolators.iso_messages`): a message, or a note
    for the log file vcnc does not write and the Python code it does not run."""
    if keyword in MESSAGE_KINDS:
        messages.append(Message(line=where.line, kind=keyword, text=text, file=where.file))
    if keyword in ("log", "logopen", "logappend", "logclose"):
        notes.add("(LOG...) comments: no log file written")
    elif keyword.startswith("py"):
        notes.add(f"({keyword.upper()},...) Python comment not run")


#: A Haas M97 word (a local subprogram call, :func:`interpolators.iso_flow.run`), which LinuxCNC does not have (rs274:
#: "Unknown m code used: M97").
_M97 = re.compile(r"(?<![A-Z\d.])M0*97(?![\d.])", re.I)
#: A Fanuc/Haas external output command at the start of a line (:mod:`interpolators.iso_macro`).
_OUTPUT_COMMAND = re.compile(r"^[ \t]*(?:N[ \t]*\d+[ \t]*)?(?:POPEN|PCLOS|[DB]PRNT[ \t]*\[)", re.I | re.M)


def ends_with_m99(text: str) -> bool:
    """True when the last block of the text (comments, ``%`` and blank lines aside) has M99."""
    for raw in reversed(text.splitlines()):
        code = re.sub(r"\([^)]*\)|;.*", "", raw).strip()
        if code and code != "%":
            return re.search(r"M\s*0*99(?![0-9.])", code, re.I) is not None
    return False


def program_name(text: str) -> str | None:
    """``O<number>`` of the first program-number line (``O1234`` or ``:1234``), if any."""
    m = re.search(r"^[ \t]*(?:%[ \t]*)?(?:[oO]|:)[ \t]*(\d+)\b(?![ \t]*[a-zA-Z])", text, re.M)
    return f"O{int(m.group(1))}" if m else None


def _grbl_lines(text: str, source: str | None, notes: Notes) -> tuple[str, list[int]]:
    """The text with grbl's system-command lines and the sender's lines blanked
    (:func:`interpolators.iso_grbl.system_lines`), each kind noted, and the lines of its ``$H`` homing cycles."""
    grbl = system_lines(text, source)
    for _ in range(grbl.blanked):
        notes.add("grbl $ system commands (reports, settings) not run")
    for _ in range(grbl.closed):
        notes.add("unclosed ( comments read to the end of the line (grbl)")
    for _ in range(grbl.resumes):
        notes.add("grbl ~ cycle start (resumes a hold or M0 pause) dropped")
    for _ in range(grbl.sender):
        notes.add("CNCjs % macro lines (%wait, variables) not run (the sender evaluates them)")
    return grbl.text, list(grbl.homing)


def expression_notes(text: str, params: Parameters, dialect: str, notes: Notes,
                     called: Iterable[str | None] = ()) -> None:
    """Notes of how the program's expressions were read: what LinuxCNC refuses (``linuxcnc`` only; a label reused
    in a subroutine file of ``called``, the files the run called, too), and macro B brackets that join comparisons
    (``iso_params`` reads them comparisons first)."""
    if dialect == "linuxcnc":
        _linuxcnc_refusals(text, params, notes)
        for name in sorted(f for f in called if f is not None):
            try:
                _duplicate_labels(_OWORD_LINE.finditer(Path(name).read_text(encoding="latin-1")), notes)
            except OSError:  # read a moment ago by the run: gone since, nothing to note
                continue
    for line, n in params.plain_alarms:  # Fanuc 0i-MF / Haas macros: #3000 alarm, #3006 stop with a message
        what = "raises macro alarm n there and stops" if n == 3000 else "stops there with its message"
        notes.add(f"#{n} set at line {line} as a plain parameter (a Fanuc or Haas control {what}: --dialect fanuc "
                  "or haas)")
    for line in params.exact_stop_suppressed:  # Fanuc/Haas #3004 bit 2
        notes.add(f"#3004 at line {line} suppresses the exact stop check (bit 2): not modelled, G09/G61 blocks still "
                  "end at rest")
    for _ in range(params.joined_comparisons):
        notes.add("comparisons joined by AND/OR/XOR in one bracket read comparisons first, [a GT b] AND [c LT d] "
                  "(Fanuc writes each in its own brackets)")


def _in_code(text: str, at: int) -> bool:
    """Whether ``text[at]`` is outside the comments of its line: no ';' before it, no '(' left open."""
    before = text[text.rfind("\n", 0, at) + 1:at]
    return ";" not in before and before.count("(") <= before.count(")")


def _loop_notes(owords: list[tuple[str, str]], notes: Notes) -> None:
    """Notes of loops LinuxCNC runs otherwise than vcnc (interp_o_word.cc ``convert_control_functions``):
    ``break`` or ``continue`` on a ``repeat`` loop's label, which LinuxCNC refuses (o-code.adoc, errors: "a label
    on break or continue which does not point to a matching while or do"), and a ``do`` loop after a ``break``
    out of a ``while`` loop: LinuxCNC clears the flag a break sets (``doing_break``) only at a do loop's closing
    while, so that the first do loop to close after the break leaves after one pass, where vcnc runs it as
    o-code.adoc describes ("do ... while: the loop runs while the condition is true"). ``owords``: the program's
    O-word lines as (label, keyword), lower case."""
    loops: dict[str, str] = {}
    broken_while = False
    for label, keyword in owords:
        if keyword not in ("while", "do", "repeat", "break", "continue"):
            continue
        if keyword in ("break", "continue"):
            kind = loops.get(label)
            if kind == "repeat":
                notes.add(f"O-word o{label} {keyword} in a repeat loop, run as in a while loop (LinuxCNC refuses "
                          "it: \"no matching while/do label\")")
            broken_while = broken_while or (keyword == "break" and kind == "while")
        elif keyword == "while" and loops.get(label) == "do":
            loops.pop(label)
        elif keyword == "do" and broken_while:
            notes.add(f"O-word o{label} do loop after a break out of a while loop: LinuxCNC leaves the first do loop "
                      "that closes after such a break after one pass (its break flag stays set), vcnc runs it to "
                      "its condition")
            broken_while = False
            loops[label] = keyword
        else:
            loops[label] = keyword


def _duplicate_labels(matches, notes: Notes) -> list[tuple[str, str]]:
    """Note each O-word label that opens two if, while or repeat blocks in one program or subroutine body (its
    :data:`_OWORD_LINE` ``matches``); the labels and keywords of the O-word lines, in order."""
    opened: collections.Counter = collections.Counter()
    body, doing = "", set()  # doing: the labels of do loops open, whose while closes them
    owords = [(m.group(1).lower().replace(" ", ""), m.group(2).lower()) for m in matches]
    for label, keyword in owords:
        if keyword not in _OPENING_KEYWORDS:
            continue
        if keyword in ("sub", "endsub"):
            body = label if keyword == "sub" else ""
        elif keyword == "do":
            doing.add((body, label))
        elif keyword == "while" and (body, label) in doing:
            doing.discard((body, label))
        else:
            opened[body, label, keyword] += 1
    for (_, label, keyword), count in sorted(opened.items()):
        if count > 1:
            notes.add(f"O-word label o{label} opens {count} {keyword} blocks in one program or subroutine, each run in "
                      "its place (LinuxCNC refuses the second when it runs: \"duplicate O-word label\"; FluidNC "
                      "reuses labels)")
    return owords


def _linuxcnc_refusals(text: str, params: Parameters, notes: Notes) -> None:
    """Notes of what the ``linuxcnc`` dialect read although LinuxCNC refuses it: macro B statements, comments with
    a '(' inside, and parameter assignments with an operation outside [ ]
    (:func:`interpolators.iso_params.read_line`)."""
    if _MACRO_B_STATEMENT.search(text):
        notes.add("Fanuc/Haas custom macro B statements (IF, WHILE .. DO, GOTO, END) run as Fanuc runs them "
                  "(LinuxCNC refuses them: its flow control is O-words; --dialect fanuc or haas)")
    owords = _duplicate_labels(_OWORD_LINE.finditer(text), notes)
    _loop_notes(owords, notes)
    if any(_in_code(text, m.start()) for m in _M97.finditer(text)):
        notes.add("M97 local subprogram calls run as Haas runs them (LinuxCNC refuses them: \"Unknown m code used\"; "
                  "--dialect haas)")
    if _NESTED_COMMENT.search(text):
        notes.add("comments with '(' inside read as nested (LinuxCNC refuses them: \"Nested comment found\")")
    for _ in range(params.unbracketed):
        notes.add("parameter assignment with an operation outside [ ], read as Fanuc macro B does (LinuxCNC "
                  "refuses it: \"Bad character used\")")
