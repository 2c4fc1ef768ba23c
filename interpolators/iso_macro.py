"""Fanuc/Haas custom macro B control flow: ``IF [..] GOTO n``, ``IF [..] THEN``, ``GOTO n``, ``WHILE [..] DO m``.

Sources: Fanuc Series 0i-MD operator's manual (B-64304EN), "Custom macro", "Branch and repetition"
(the same chapter is "Custom macro" in the 16i/18i manual B-63684EN); Haas mill operator's manual,
"Macros" ("GOTO", "IF", "WHILE"; "Computed branch (GOTO#n and GOTO [expression])",
https://www.haascnc.com/service/online-operator-s-manuals/mill-operator-s-manual/mill-macros.html).

* ``GOTO n`` branches to the block with sequence number ``Nn`` of the same program; ``n`` may be a
  parameter or an expression (``GOTO #1``, ``GOTO [#2+10]``), rounded to a whole number as Haas
  does (4.49 goes to N4, 4.5 to N5). The block is searched forward from the branch, then from the
  start of the program (Fanuc: a backward branch takes longer than a forward one for this reason);
  the first block found with that number is taken. A missing number is an error naming it.
* ``IF [condition] GOTO n`` branches when the condition holds, else the next block runs;
  ``IF [condition] THEN #i = expression`` makes the assignment only when it holds (one macro
  statement, no NC words). The condition may join bracketed comparisons, ``[#1 EQ 2] AND [#3 GT 0]``.
  Under ``haas`` the rest of the block after ``THEN`` runs as a block when the condition holds, NC words
  too (:meth:`MacroFlow.then_block`; Haas mill operator's manual, "Macros", "Conditional Execution (IF THEN)":
  "if a conditional evaluates to FALSE (0.0), then the remainder of the IF block is ignored. This means that
  control statements can also be conditioned so that we could write something like: IF [#1 NE #0] THEN G1
  X#24 Y#26 F#9 ... IF [#1 GE 180] THEN #101=0.0 M99"); Fanuc's THEN takes one macro statement.
* ``WHILE [condition] DO m`` ... ``END m`` repeats the blocks between while the condition holds
  (tested at ``WHILE`` on each pass); ``DO m`` without ``WHILE`` repeats without end (left only
  by a ``GOTO``). ``m`` is 1, 2 or 3; loops nest up to three deep and must not cross (``END m``
  closes the innermost open ``DO``, which must carry the same ``m``); numbers may be reused one
  after another. A block ``XX [..] DO m`` whose keyword is not ``WHILE`` is an error naming it. A ``GOTO``
  may leave a loop but not enter one: a target between a loop's ``WHILE`` (or ``DO``) and its ``END`` reached
  from outside the loop is an error (Fanuc 0i/16i operator's manuals, "Repetition (WHILE statement)",
  "Nesting": "Branches cannot be made to a location within a loop", as we remember it: the text is not in our
  search index; a GOTO to the ``WHILE`` block itself starts the loop). vcnc ran such an ``END`` as if the loop
  had been entered at its top.
* Abbreviations (``fanuc`` dialect only: :attr:`interpolators.iso_params.Parameters.fanuc`): a Fanuc
  control takes the first two characters of a macro word for the word (Fanuc 0i/16i/30i operator's manuals,
  "Custom macro", "Arithmetic and logic operation", "Abbreviations of macro statements": "ROUND -> RO, FIX ->
  FI"; the text itself was not found in our search index, and that the rule covers the statement words as
  well as the functions is our reading, which programs written for Fanuc controls bear out: ``WH [..] DO1``).
  So ``WH [..] DO m`` is ``WHILE``, ``GO n`` ``GOTO n`` (only with nothing but the target after it, so
  that ``GO1 X5``, a G01 typed with the letter O, stays an error naming the letter), ``EN m`` ``END m`` and
  ``IF [..] TH`` ``THEN``. The functions' abbreviations are read by :mod:`interpolators.iso_params`. Haas
  documents no abbreviation: under ``haas`` (and LinuxCNC, grbl) they are errors naming the full word.
* The external output commands ``POPEN``, ``DPRNT[..]``, ``BPRNT[..]`` and ``PCLOS`` send text and
  variables to the serial port (Fanuc B-64304EN "External output commands"; Haas mill operator's
  manual, "Formatted Output": "DPRNT[<text> <#nnnn[wf]>...]", "DPRNT must be the only command in the
  block"). Nothing is sent, and the tool does not move: they run as empty statements. A ``DPRNT``
  without its closing bracket, or with words after it, is an error.
* Comparisons ``EQ NE GT GE LT LE``, ``AND OR XOR`` and the functions are those of
  :mod:`interpolators.iso_params`, which also holds the vacant-variable semantics (``#0``).

Endless loops: a loop whose ``END`` (or a backward ``GOTO``) has sent execution back more than
:data:`MAX_LOOP_PASSES` times in one run (a ``WHILE`` that ends starts its count afresh) is an
error naming the line, as is any program running
more than :data:`interpolators.iso_flow.MAX_EXECUTED_LINES` lines.
"""

from __future__ import annotations

import dataclasses
import math
import re

from interpolators._words import Where
from interpolators.iso_params import Parameters, evaluate_at, evaluate_condition, read_line

__all__ = ["MAX_LOOP_PASSES", "Statement", "MacroFlow", "read_statement", "sequence_number"]

#: Largest number of times one loop end (``END m``) or backward ``GOTO`` may send execution back in a run.
MAX_LOOP_PASSES = 100_000
#: Deepest nesting of ``DO`` loops (Fanuc: three levels, identification numbers 1-3).
MAX_NESTING = 3

_PREFIX = r"^\s*(?:N\s*\d+\s*)?"
_IF = re.compile(_PREFIX + r"(IF)\s*\[", re.I)
_WHILE = re.compile(_PREFIX + r"(WHILE)\s*\[.*\]\s*DO\s*(\d+)\s*$", re.I)
_WHILE_START = re.compile(_PREFIX + r"(WHILE)\b", re.I)
_LOOP_HEAD = re.compile(_PREFIX + r"([A-Z]{2,})\s*\[.*\]\s*DO\s*\d+\s*$", re.I)
_DO = re.compile(_PREFIX + r"(DO)\s*(\d+)\s*$", re.I)
_END = re.compile(_PREFIX + r"(END)\s*(\d+)\s*$", re.I)
_GOTO = re.compile(_PREFIX + r"(GOTO)\s*(?=[\d#\[+])", re.I)
_OUTPUT = re.compile(_PREFIX + r"(POPEN|PCLOS|[DB]PRNT\s*\[)", re.I)
_SEQUENCE = re.compile(r"^\s*N\s*(\d+)", re.I)
_BRANCH = re.compile(r"\s*(GOTO|THEN)", re.I)
#: Fanuc's abbreviated statement words and the words they stand for.
ABBREVIATED = {"WH": "WHILE", "GO": "GOTO", "EN": "END", "TH": "THEN"}
_WHILE_SHORT = re.compile(_PREFIX + r"(WH)\s*\[.*\]\s*DO\s*(\d+)\s*$", re.I)
_END_SHORT = re.compile(_PREFIX + r"(EN)\s*(\d+)\s*$", re.I)
_GOTO_SHORT = re.compile(_PREFIX + r"(GO)\s*(?=(?:\d+|#\s*\d+|\[.*\])\s*$)", re.I)
_BRANCH_SHORT = re.compile(r"\s*(GOTO|THEN|GO|TH)", re.I)


@dataclasses.dataclass(frozen=True)
class Statement:
    """A macro B statement: ``kind`` (if, goto, while, do, end, output), the comment-free ``code`` of its
    line, ``start`` (0-based column of the keyword), ``loop`` (``m`` of ``DO m`` / ``END m``) and ``word``, the
    keyword as written (``GO`` for an abbreviated ``GOTO``)."""

    kind: str
    code: str
    start: int
    loop: int = 0
    word: str = ""


def sequence_number(code: str) -> int | None:
    """The sequence number ``Nn`` that starts a comment-free line, if any."""
    m = _SEQUENCE.match(code)
    return int(m.group(1)) if m else None


def read_statement(code: str, where: Where, *, abbreviations: bool = False) -> Statement | None:
    """The macro B statement of a comment-free line, or ``None`` for an ordinary block; ``abbreviations``:
    Fanuc's two-letter statement words (``WH``, ``GO``, ``EN``) are read too."""
    m = _IF.match(code)
    if m:
        return Statement("if", code, m.start(1))
    m = _WHILE.match(code) or _DO.match(code) or _END.match(code)
    if m is None and abbreviations:
        m = _WHILE_SHORT.match(code) or _END_SHORT.match(code)
    if m:
        loop = int(m.group(2))
        word = "END" if m.group(1).upper() in ("END", "EN") else "DO"
        if not 1 <= loop <= MAX_NESTING:
            where.fail(f"{word} {loop}: loop identification number out of range", column=m.start(2) + 1,
                       text=code.strip(), expected=f"{word} 1, 2 or 3 (Fanuc custom macro B)")
        kind = ABBREVIATED.get(m.group(1).upper(), m.group(1)).lower()
        return Statement(kind, code, m.start(1), loop, word=m.group(1))
    m = _WHILE_START.match(code)
    if m:
        bare = re.match(r"\s*[^\s\[]", code[m.end(1):])  # after "N10 WHILE" too
        ddcs = " as the DDCS controllers write 'WHILE #18<#3 DO2': Fanuc macro B brackets it"
        if bare and re.search(r"(?<![A-Z])DO\s*\d+\s*$", code, re.I):  # its DO is there: the brackets are not
            what = f"WHILE condition without its brackets ({ddcs.strip()})"
        else:
            what = "WHILE without DO m at the end of its block" + (f" (a condition without brackets,{ddcs})"
                                                                    if bare else "")
        where.fail(what, column=m.start(1) + 1, text=code.strip(), expected="WHILE [condition] DO m (m = 1, 2 or 3)")
    m = _LOOP_HEAD.match(code)
    if m:
        short = " (WH is Fanuc's abbreviation of it: --dialect fanuc)" if m.group(1).upper() == "WH" else ""
        where.fail(f"loop head {m.group(1)!r} [..] DO m: the keyword of a loop is WHILE{short}",
                   column=m.start(1) + 1, text=code.strip(), expected="WHILE [condition] DO m (m = 1, 2 or 3)")
    m = _GOTO.match(code) or (_GOTO_SHORT.match(code) if abbreviations else None)
    if m:
        return Statement("goto", code, m.start(1), word=m.group(1))
    m = _OUTPUT.match(code)
    if m:
        keyword = m.group(1).rstrip("[ \t").upper()
        rest = code[m.end():]
        if m.group(1).endswith("["):
            depth, close = 1, -1
            for j, ch in enumerate(rest):
                depth += {"[": 1, "]": -1}.get(ch, 0)
                if depth == 0:
                    close = j
                    break
            if close < 0:
                where.fail(f"{keyword}[ external output without its closing ']'", column=m.start(1) + 1,
                           text=code.strip(), expected=f"{keyword}[text #variable[wf] ...]")
            rest = rest[close + 1:]
        if rest.strip():
            where.fail(f"{keyword} external output: must be the only command of its block",
                       column=m.start(1) + 1, text=code.strip(),
                       expected=f"{keyword}[text #variable[wf] ...] alone" if keyword.endswith("PRNT") else
                       f"{keyword} alone")
        return Statement("output", code, m.start(1))
    return None


def _closing(code: str, start: int) -> int:
    """The index of the ``]`` closing the bracket that opens at ``start`` (the line's end if none does)."""
    depth = 0
    for i in range(start, len(code)):
        depth += {"[": 1, "]": -1}.get(code[i], 0)
        if depth == 0:
            return i
    return len(code)


class MacroFlow:
    """The macro B statements of a program, its sequence numbers per program and its loops.

    Lines are numbered as :class:`interpolators.iso_flow` numbers them (all files, one index); a
    *program* (``span``) is the main program or one ``O`` program after it, or another file.
    """

    def __init__(self, *, max_passes: int = MAX_LOOP_PASSES, abbreviations: bool = False) -> None:
        self.max_passes = max_passes
        self.abbreviations = abbreviations  # Fanuc's two-letter statement words (WH, GO, EN, TH)
        self.statements: dict[int, Statement] = {}
        self.span_of: list[int] = []
        self.numbers: dict[int, dict[int, list[int]]] = {}  # span -> sequence number -> lines
        self.partner: dict[int, int] = {}  # DO/WHILE line -> END line and back
        self.loops: list[tuple[int, int]] = []  # (DO/WHILE line, END line) of every loop
        self.passes: dict[int, int] = {}

    def add_line(self, i: int, code: str | None, span: int, where: Where) -> Statement | None:
        """Index line ``i`` (comment-free ``code``, ``None`` for a blank one) of program ``span``."""
        while len(self.span_of) <= i:
            self.span_of.append(span)
        self.span_of[i] = span
        if code is None:
            return None
        n = sequence_number(code)
        if n is not None:
            self.numbers.setdefault(span, {}).setdefault(n, []).append(i)
        stmt = read_statement(code, where, abbreviations=self.abbreviations)
        if stmt is not None:
            self.statements[i] = stmt
        return stmt

    def add_block(self, i: int, code: str, span: int) -> None:
        """Index line ``i`` of program ``span``, an ordinary block of plain words (no statement can be one):
        :meth:`add_line` without the statement patterns."""
        while len(self.span_of) <= i:
            self.span_of.append(span)
        self.span_of[i] = span
        n = sequence_number(code)
        if n is not None:
            self.numbers.setdefault(span, {}).setdefault(n, []).append(i)

    def match_loops(self, where_of) -> None:
        """Pair each ``DO m`` with its ``END m`` within its program; crossing, unclosed and too
        deep loops are errors (``where_of(i)`` gives the :class:`Where` of line ``i``)."""
        self.partner.clear()
        self.loops.clear()
        open_: list[int] = []
        span = None
        for i in sorted(self.statements):
            stmt = self.statements[i]
            if stmt.kind not in ("while", "do", "end"):
                continue
            if self.span_of[i] != span:
                self._unclosed(open_, where_of)
                span = self.span_of[i]
            if stmt.kind != "end":
                if len(open_) == MAX_NESTING:
                    where_of(i).fail(f"DO {stmt.loop}: loops nested deeper than {MAX_NESTING}", column=stmt.start + 1,
                                     text=stmt.code.strip(), expected=f"at most {MAX_NESTING} nested DO loops")
                open_.append(i)
                continue
            if not open_ or self.statements[open_[-1]].loop != stmt.loop:
                inner = f" (the innermost open loop is DO {self.statements[open_[-1]].loop})" if open_ else ""
                where_of(i).fail(f"END {stmt.loop} closes no open DO {stmt.loop}{inner}: loops must nest, not cross",
                                 column=stmt.start + 1, text=stmt.code.strip(),
                                 expected=f"WHILE [..] DO {stmt.loop} before it in the same program")
            head = open_.pop()
            self.partner[head] = i
            self.partner[i] = head
            self.loops.append((head, i))
        self._unclosed(open_, where_of)

    def _unclosed(self, open_: list[int], where_of) -> None:
        if open_:
            i = open_[-1]
            stmt = self.statements[i]
            where_of(i).fail(f"DO {stmt.loop} without END {stmt.loop} in its program", column=stmt.start + 1,
                             text=stmt.code.strip(), expected=f"END {stmt.loop} closing the loop")
        open_.clear()

    def execute(self, pc: int, where: Where, params: Parameters) -> int:
        """Run the statement of line ``pc``; returns the next line to run."""
        stmt = self.statements[pc]
        code = stmt.code
        if stmt.kind in ("do", "output"):
            return pc + 1
        if stmt.kind == "while":
            holds, _ = evaluate_condition(code, code.index("[", stmt.start), where, params)
            if holds:
                return pc + 1
            self.passes.pop(self.partner[pc], None)  # the loop is left: a later run of it counts afresh
            return self.partner[pc] + 1
        if stmt.kind == "end":
            self._count(pc, where, f"END {stmt.loop}: the loop DO {stmt.loop} it closes")
            return self.partner[pc]
        if stmt.kind == "goto":
            return self._goto(pc, stmt.start + len(stmt.word), where, params)
        holds, end = evaluate_condition(code, code.index("[", stmt.start), where, params)
        m = (_BRANCH_SHORT if self.abbreviations else _BRANCH).match(code, end)
        block = "a block (Haas: '#i = expression', NC words or both)" if params.macro_b and not params.fanuc \
            else "#i = expression"
        if m is None:
            where.fail("IF [condition] must be followed by GOTO n or THEN", column=end + 1, text=code.strip(),
                       expected=f"IF [condition] GOTO n, or IF [condition] THEN {block}")
        if m.group(1).upper() in ("THEN", "TH") and not code[m.end():].strip():
            # a multi-line IF block (IF [..] THEN / ELSE / ENDIF, as Mazak EIA macros write it: keycult/mazak-hcn
            # SWAP_PALLET.EIA): read as an empty THEN, the blocks up to ENDIF would run whatever the condition
            where.fail("IF [..] THEN with nothing after THEN: the start of a multi-line IF .. ELSE .. ENDIF block, "
                       "which vcnc does not read (the blocks up to ENDIF would run whatever the condition)",
                       column=m.start() + 1, text=code.strip(),
                       expected=f"IF [condition] THEN {block} on one line, or IF [condition] GOTO n")
        if not holds:
            return pc + 1
        if m.group(1).upper() in ("GOTO", "GO"):
            return self._goto(pc, m.end(), where, params)
        rest = " " * m.end() + code[m.end():]
        words = read_line(rest, where, params)
        if words:
            where.fail(f"IF [..] THEN: NC word {words[0].text!r} after THEN", column=words[0].column,
                       text=words[0].text, expected="one macro statement after THEN, e.g. THEN #3 = 0")
        return pc + 1

    def then_block(self, pc: int, where: Where, params: Parameters) -> str | None:
        """Under ``haas``, the code of an ``IF [..] THEN <block>`` line: when its condition holds, its text up to
        and with ``THEN`` blanked (columns kept), to run as an ordinary block, assignments and NC words alike
        (module docstring, Haas "Conditional Execution (IF THEN)"); when it fails, ``""`` (nothing runs). None for
        any other statement (:meth:`execute` runs those); the condition is evaluated once either way."""
        stmt = self.statements[pc]
        if stmt.kind != "if" or params.fanuc or not params.macro_b:
            return None
        code = stmt.code
        m = _BRANCH.match(code, _closing(code, code.index("[", stmt.start)) + 1)
        if m is None or m.group(1).upper() != "THEN" or not code[m.end():].strip():
            return None
        holds, _ = evaluate_condition(code, code.index("[", stmt.start), where, params)
        return " " * m.end() + code[m.end():] if holds else ""

    def _goto(self, pc: int, pos: int, where: Where, params: Parameters) -> int:
        code = self.statements[pc].code
        value, end = evaluate_at(code, pos, where, params)
        if code[end:].strip():
            where.fail("text after the GOTO target", column=end + 1, text=code[end:].strip(),
                       expected="GOTO n alone (n a number, #parameter or [expression])")
        n = math.floor(value + 0.5)
        target = self.find(n, pc)
        if target is None:
            where.fail(f"GOTO {n}: no block N{n} in this program", column=pos + 1, text=code.strip(),
                       expected=f"a block numbered N{n} in the same program")
        entered = next(((h, e) for h, e in self.loops if h < target <= e and not h < pc < e), None)
        if entered is not None:
            loop = self.statements[entered[0]].loop
            where.fail(f"GOTO {n}: N{n} lies within the loop DO {loop} (line {where.line + entered[0] - pc} to "
                       f"{where.line + entered[1] - pc}), which the GOTO enters from outside: Fanuc macro B does not "
                       "branch into a loop", column=pos + 1, text=code.strip(),
                       expected="a GOTO to the loop's WHILE block or to a block outside it")
        if target <= pc:
            self._count(pc, where, f"GOTO {n}")
        return target

    def find(self, n: int, pc: int) -> int | None:
        """The line numbered ``Nn`` in the program of line ``pc``: the first after it, else the first
        from the program's start (Fanuc's sequence-number search); ``None`` when there is none."""
        lines = self.numbers.get(self.span_of[pc], {}).get(n, [])
        forward = [j for j in lines if j > pc]
        return forward[0] if forward else (lines[0] if lines else None)

    def count_back(self, pc: int, where: Where, what: str) -> None:
        """Count a branch back from line ``pc`` (``what`` names it in the error of an endless loop)."""
        self._count(pc, where, what)

    def _count(self, pc: int, where: Where, what: str) -> None:
        self.passes[pc] = self.passes.get(pc, 0) + 1
        if self.passes[pc] > self.max_passes:
            where.fail(f"{what} has sent execution back more than {self.max_passes} times: an endless loop?",
                       column=1, text=where.text, expected="a loop whose condition ends it")
