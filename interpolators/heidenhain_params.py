"""Q parameters of Heidenhain conversational programs: values, formulas and the FN functions.

Semantics follow the HEIDENHAIN TNC user's manuals, chapter "Programming: Q parameters"
(iTNC 530 / TNC 640 conversational programming; TNC 426/430 manual, section 10):

* ``Q1 = <formula>`` (and ``QL``/``QR`` local and remanent parameters, kept here in one store; a called
  program's QL apart from its caller's, :meth:`QParameters.enter_program`):
  ``+ - * /``, ``^`` (power), parentheses, and the functions ``SIN COS TAN ASIN ACOS ATAN``
  (angles in degrees), ``SQ`` (square), ``SQRT``, ``LN``, ``LOG`` (base 10), ``EXP``, ``PI``,
  ``NEG``, ``INT`` (truncate), ``ABS``, ``FRAC`` and ``SGN``. A function applies to the operand
  after it, with or without parentheses (``INT Q4``, ``SQRT(Q4)``). "Multiplication and division
  before addition and subtraction"; ``^`` binds tighter than both.
* ``FN 0: Q5 = +60`` assign, ``FN 1`` add, ``FN 2`` subtract, ``FN 3`` multiply, ``FN 4: Q = a DIV b``
  divide (division by 0 is an error), ``FN 5: SQRT``, ``FN 6: SIN``, ``FN 7: COS``,
  ``FN 8: a LEN b`` (root sum of squares), ``FN 13: a ANG b`` (angle of the vector (a, b) in degrees,
  0 to 360).
* ``FN 9/10/11/12: IF a EQU/NE/GT/LT b GOTO LBL n`` conditions (the jump itself is the reader's).
* ``FN 14: ERROR`` stops the run with an error; ``FN 15/16`` prints are noted and skipped;
  ``FN 18: SYSREAD Qn = ID240 NR1 IDXi`` (nominal position, machine coordinates) and
  ``ID270 NR1 IDXi`` (position in the active coordinate system) read the simulated position:
  a simulation has no operator jogging the axes at a ``STOP``, so programs that measure
  positions set by hand read the position where the program left the tool. The machine status
  ``ID10 NR1`` (inch), ``ID20 NR1 .. NR4`` (active and prepared tool, tool axis, spindle speed) is the
  reader's (:data:`MACHINE_STATUS`).
* ``FN 17: SYSWRITE IDi NRj [IDXk] = value`` writes system data: the tool table's length and radius
  (ID50 NR1, NR2) as a ``TOOL DEF`` does; other data vcnc does not hold are noted and not written
  (:func:`run_function`).

A parameter used before it is set reads 0, as on the TNC after a reset of the Q parameters.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable

import numpy as np

from interpolators._words import MAX_MAGNITUDE, Where
from interpolators.heidenhain_formulas import Compiled, FormulaSyntaxError, compile_formula
from interpolators.heidenhain_labels import LABEL_RE, label_key

__all__ = ["QParameters", "FN_ARITHMETIC", "FN_CONDITIONS", "MACHINE_STATUS", "Q_NAME_RE", "run_function"]

#: A parameter name: ``Q12``, ``QL3``, ``QR7``.
Q_NAME_RE = re.compile(r"Q[LR]?\d+", re.I)

_TOKEN_RE = re.compile(
    r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+))|(?P<q>Q[LR]?\d+)|(?P<name>[A-Z]+)|(?P<op>[-+*/%^()]))", re.I
)

#: Formula text -> its compiled closure (:mod:`interpolators.heidenhain_formulas`), shared by all runs; at most
#: ``_MAX_COMPILED`` entries.
_COMPILED: dict[str, Compiled] = {}
_MAX_COMPILED = 4096

_FUNCTIONS = {
    "SIN": lambda v: math.sin(math.radians(v)),
    "COS": lambda v: math.cos(math.radians(v)),
    "TAN": lambda v: math.tan(math.radians(v)),
    "ASIN": lambda v: math.degrees(math.asin(v)),
    "ACOS": lambda v: math.degrees(math.acos(v)),
    "ATAN": lambda v: math.degrees(math.atan(v)),
    "SQ": lambda v: v * v,
    "SQRT": math.sqrt,
    "LN": math.log,
    "LOG": math.log10,
    "EXP": math.exp,
    "NEG": lambda v: -v,
    "INT": lambda v: float(math.trunc(v)),
    "ABS": abs,
    "FRAC": lambda v: v - math.trunc(v),
    # iTNC 530 user's manual 60642x-04, 9.8, "Check algebraic sign of a number": "If result for Q12 = 1, then Q50 >= 0;
    # If result for Q12 = -1, then Q50 < 0" (the TNC 320 and TNC 620 manuals alike): SGN 0 is 1, not 0
    "SGN": lambda v: 1.0 if v >= 0 else -1.0,
}

#: ``FN n`` arithmetic: number -> (operator word between the operands or None, function).
FN_ARITHMETIC = {
    0: (None, lambda a: a),
    1: ("+", lambda a, b: a + b),
    2: ("-", lambda a, b: a - b),
    3: ("*", lambda a, b: a * b),
    4: ("DIV", lambda a, b: a / b),
    5: ("SQRT", math.sqrt),
    6: ("SIN", _FUNCTIONS["SIN"]),
    7: ("COS", _FUNCTIONS["COS"]),
    8: ("LEN", lambda a, b: math.hypot(a, b)),
    # TNC 370 user's manual 7.3 "Trigonometric functions": FN13 ANGLE "from the arc tangent of two sides or from
    # the sine and cosine of the angle (0 < angle < 360 deg)": the angle of the vector (a, b) taken into [0, 360)
    13: ("ANG", lambda a, b: math.degrees(math.atan2(b, a)) % 360.0),
}

#: ``FN 9`` .. ``FN 12`` jump conditions: number -> (comparison word, test).
FN_CONDITIONS = {
    9: ("EQU", lambda a, b: a == b),
    10: ("NE", lambda a, b: a != b),
    11: ("GT", lambda a, b: a > b),
    12: ("LT", lambda a, b: a < b),
}


#: FN functions that exchange data with the PLC or the outside and move nothing (TNC 640 / iTNC 530 user's
#: manuals, "Additional functions": FN 19 PLC, FN 29 PLC transfer values to the PLC, FN 37 EXPORT hands local
#: parameters to the calling program (vcnc's Q parameters are shared by all programs of a run), FN 38 SEND a
#: text to the log or an external application).
_FN_NO_MOTION = {19: "values sent to the PLC", 29: "values sent to the PLC", 37: "EXPORT (Q parameters are shared "
                 "here)", 38: "SEND of a text"}

#: The functions of a Q formula that read QS texts (TONUMB, STRLEN, INSTR, STRCOMP).
_STRING_FUNCTION_RE = re.compile(r"\s*(TONUMB|STRLEN|INSTR|STRCOMP)\b", re.I)


class QParameters:
    """The Q-parameter store of one program run and the formula evaluator."""

    def __init__(self) -> None:
        self._values: dict[str, float] = {}

    def get(self, name: str) -> float:
        """Value of ``name`` (``"Q5"``, ``"QL2"``); 0 when never set."""
        return self._values.get(name.upper(), 0.0)

    def set(self, name: str, value: float, where: Where, *, column: int | None = None) -> None:
        """Assign ``value`` to ``name``, checking it is finite and within the number range."""
        if not (math.isfinite(value) and abs(value) <= MAX_MAGNITUDE):
            where.fail(f"{name.upper()} = {value!r} is out of range", column=column, text=where.text,
                       expected=f"a finite value of magnitude <= {MAX_MAGNITUDE:g}")
        self._values[name.upper()] = float(value)

    def enter_program(self) -> dict[str, float]:
        """Set the calling program's QL parameters aside for a called program, which starts without
        them; returns them for :meth:`leave_program`. TNC 640 user's manual (34059x-02, 5/2013), 9.1
        "Principle and overview of functions": "Local parameters QL are only effective within the
        respective program, and are not applied as part of program calls or macros" (Q and QR are)."""
        local = {k: v for k, v in self._values.items() if k.startswith("QL")}
        for k in local:
            del self._values[k]
        return local

    def leave_program(self, local: dict[str, float]) -> None:
        """Back in the calling program: the called program's QL parameters gone, the caller's
        (``local``, from :meth:`enter_program`) again."""
        for k in [k for k in self._values if k.startswith("QL")]:
            del self._values[k]
        self._values.update(local)

    def evaluate(self, text: str, where: Where, *, column: int = 1) -> float:
        """Value of a formula (or a plain signed number or parameter) [the parameters' units].

        Raises
        ------
        vcnc.GCodeError
            Malformed formula, unknown function, division by zero or a function outside its
            domain (``SQRT`` of a negative number, ...), naming the formula.
        """
        cached = _COMPILED.get(text)
        if cached is None:
            tokens = []
            pos = 0
            while pos < len(text):
                if text[pos:].strip() == "":
                    break
                m = _TOKEN_RE.match(text, pos)
                sm = _STRING_FUNCTION_RE.match(text, pos)
                if sm is not None:  # TNC 640 user's manual, "String parameters": numbers from texts
                    where.fail(f"string function {sm.group(1).upper()} in a formula is not supported",
                               column=column + pos, text=sm.group(1),
                               expected="a formula of numbers and Q parameters (QS texts: DECLARE STRING, ||, TOCHAR, "
                                        "SUBSTR)")
                if m is None:
                    where.fail(f"malformed formula {text.strip()!r}", column=column + pos, text=text.strip(),
                               expected="numbers, Q parameters, + - * / % ^ ( ) and functions such as SIN or SQRT")
                kind = m.lastgroup
                tokens.append((kind, m.group(kind).upper()))
                pos = m.end()
            if len(_COMPILED) >= _MAX_COMPILED:  # formulas built from changing text: keep the memory bounded
                _COMPILED.clear()
            try:
                cached = _COMPILED[text] = compile_formula(tokens, _FUNCTIONS)
            except FormulaSyntaxError as exc:
                _Formula(self, where, text.strip(), column).fail(str(exc))
        ctx = _Formula(self, where, text.strip(), column)
        value = cached(ctx)
        if not (math.isfinite(value) and abs(value) <= MAX_MAGNITUDE):
            ctx.fail(f"result {value!r} out of range")
        return value


class _Formula:
    """What a compiled formula reads (the Q parameters) and reports its errors through (naming the formula)."""

    def __init__(self, params: QParameters, where: Where, text: str, column: int) -> None:
        self.params, self.where, self.text, self.column = params, where, text, column

    def fail(self, why: str):
        self.where.fail(f"bad formula {self.text!r}: {why}", column=self.column, text=self.text,
                        expected="numbers, Q parameters, + - * / % ^ ( ) and functions such as SIN or SQRT")


_FN_RE = re.compile(r"FN\s*(\d+)\s*:\s*", re.I)


def run_function(code: str, params: QParameters, where: Where, *, column: int, position: np.ndarray,
                 active: np.ndarray, scale: float, note: Callable[[str], None],
                 tool: tuple[int, Callable[[int], tuple[float, float] | None]] = (0, lambda n: None),
                 stopped_at: int | None = None, tool_write: Callable[[int, int, float], None] | None = None,
                 system: Callable[[int, int], float] | None = None) -> str | None:
    """Run an ``FN n: ...`` block (``code`` from ``FN`` on, at 1-based ``column``).

    Parameters
    ----------
    position, active : ndarray (3,)
        For ``FN 18 SYSREAD``: the tool position in machine coordinates (ID240) and in the active coordinate
        system (ID270) [mm].
    scale : float
        mm per program unit (25.4 in INCH programs).
    note : callable
        Receives what was ignored or read in a particular way.
    tool : (int, callable)
        For ``FN 18 SYSREAD ID20`` / ``ID50``: the active tool's number (0: none) and the length and radius
        [mm] of a tool number (None: not in the program's TOOL DEFs nor the tool table).
    stopped_at : int or None
        The line of a program stop (``STOP``, ``M0``, ``M1``) with no move since, None if none: a
        position ``FN 18 SYSREAD`` reads there is the one where the program stopped, noted.
    tool_write : callable or None
        For ``FN 17 SYSWRITE ID50 NR1`` / ``NR2``: receives the tool number, 1 (length) or 2 (radius) and
        the value [mm]; None: such a write is an error.
    system : callable or None
        For ``FN 18 SYSREAD`` of the machine status (:data:`MACHINE_STATUS`): the value of ``(ID, NR)``;
        None: such a read is an error.

    Returns
    -------
    str or None
        The label to jump to (``FN 9`` .. ``FN 12`` whose condition holds), else None.
    """
    fm = _FN_RE.match(code)
    n = int(fm.group(1)[:6])
    rest = code[fm.end():]
    col = column + fm.end()
    if n in FN_ARITHMETIC:
        am = re.match(r"(Q[LR]?\d+)\s*=\s*", rest, re.I)
        if am is None:
            where.fail(f"FN {n} without 'Qn ='", column=col, text=rest.strip(), expected="FN n: Qn = ...")
        op, fn = FN_ARITHMETIC[n]
        body = rest[am.end():]
        bcol = col + am.end()
        if op is None:
            value = params.evaluate(body, where, column=bcol)
        elif op in ("SQRT", "SIN", "COS"):
            om = re.match(rf"\s*{op}\s*", body, re.I)
            if om is None:
                where.fail(f"FN {n} expects {op}", column=bcol, text=body.strip(), expected=f"FN {n}: Qn = {op} value")
            arg = params.evaluate(body[om.end():], where, column=bcol + om.end())
            try:
                value = fn(arg)
            except ValueError:
                where.fail(f"FN {n}: {op} of {arg!r} is undefined", column=bcol, text=body.strip(),
                           expected="an argument in the function's domain")
        else:
            a, b = _two_operands(body, op, params, where, bcol)
            if op == "DIV" and b == 0:
                where.fail("FN 4: division by zero", column=bcol, text=body.strip(), expected="a divisor != 0")
            value = fn(a, b)
        params.set(am.group(1), value, where, column=col)
        return None
    if n in FN_CONDITIONS:
        return _condition(n, rest, params, where, col)
    if n in (15, 16):
        note(f"FN {n}: PRINT output ignored")
        return None
    if n == 14:
        where.fail(f"the program raised FN 14: ERROR ({rest.strip()})", column=col, text=rest.strip(),
                   expected="a program run without FN 14")
    if n == 18:
        _sysread(rest, params, where, col, position=position, active=active, scale=scale, note=note, tool=tool,
                 stopped_at=stopped_at, system=system)
        return None
    if n == 17:
        _syswrite(rest, params, where, col, scale=scale, note=note, tool_write=tool_write)
        return None
    if n in _FN_NO_MOTION:
        note(f"FN {n}: {_FN_NO_MOTION[n]} (no motion)")
        return None
    if n == 20 and re.match(r"\s*WAIT\s+FOR\b", rest, re.I):
        # TNC 640 / iTNC 530 user's manuals, "FN 20: WAIT FOR: NC and PLC synchronization": the program waits for
        # a PLC condition (or, WAIT FOR SYNC, for the look-ahead); a simulation has no PLC: no motion, no wait
        note("FN 20: WAIT FOR (PLC synchronisation) read as met at once (no motion)")
        return None
    where.fail(f"FN {n} is not supported", column=column, text=code[:fm.end()].strip(),
               expected="FN 0-13 (arithmetic, jumps), FN 14 ERROR, FN 15/16 PRINT, FN 17 SYSWRITE, "
                        "FN 18 SYSREAD ID20/ID50/ID240/ID270, FN 20 WAIT FOR")


_SYSWRITE_RE = re.compile(r"\s*SYSWRITE\s+ID\s*(\d+)\s+NR\s*(\d+)(?:\s+IDX\s*(\d+|Q[LR]?\d+))?\s*=\s*(.*?)\s*$",
                          re.I)
#: What ``FN 17 SYSWRITE`` may not write: data vcnc reads back or positions by (ID, NR) -> what they are.
_SYSWRITE_REFUSED = {(20, 1): "the active tool (set by TOOL CALL)", (50, 4): "the tool's length oversize DL",
                     (50, 5): "the tool's radius oversize DR"}


def _syswrite(rest: str, params: QParameters, where: Where, col: int, *, scale: float, note: Callable[[str], None],
              tool_write: Callable[[int, int, float], None] | None) -> None:
    """``FN 17: SYSWRITE IDi NRj [IDXk] = value`` (TNC 426/430 technical manual 12/2001, 7.3.3 "Data Transfer NC
    Program -> NC (SYSWRITE)": "FN17: SYSWRITE IDxxxx NRxxxx IDXxxxx = Qxxx or numerical value", to "overwrite
    certain NC data"; its table: ID50 "Data from the tool table", NR1 tool length L, NR2 tool radius R, NR3 R2,
    NR4 DL, NR5 DR, ..., the index the tool number). ID50 NR1 / NR2 write the length / radius of tool IDX into
    the tool data ``TOOL CALL`` and ``FN 18 SYSREAD ID50`` take from then on (as a ``TOOL DEF`` of the program:
    the active tool's compensation changes at its next ``TOOL CALL``, our reading). DL and DR (NR4, NR5), which
    vcnc's tool table does not hold (``FN 18`` reads them as 0), may be written 0 only, and ID20 NR1 (the active
    tool) not at all: an error naming them. Anything else (R2, tool life, PLC data, pocket and datum tables, a
    text value such as a tool name ``= ""``) is data vcnc does not model: noted, not written."""
    sm = _SYSWRITE_RE.match(rest)
    if sm is None or not sm.group(4):
        where.fail(f"malformed FN 17 SYSWRITE {rest.strip()!r}", column=col, text=rest.strip(),
                   expected="SYSWRITE IDi NRj [IDXk] = value")
    ident, nr = int(sm.group(1)[:6]), int(sm.group(2)[:6])
    idx = sm.group(3)
    index = None if idx is None else params.get(idx) if idx[0] in "qQ" else float(idx[:9])
    what = f"FN 17 SYSWRITE ID{ident} NR{nr}" + ("" if index is None else f" IDX{index:g}")
    text = sm.group(4)
    if text[0] in "\"'":  # a text (a tool name): vcnc's tool table has no names
        note(f"{what} = {text}: a text value, not written (vcnc keeps no such data)")
        return
    value = params.evaluate(text, where, column=col + sm.start(4))
    if (ident, nr) in _SYSWRITE_REFUSED and not (ident == 50 and value == 0):
        where.fail(f"{what} = {value:g}: writing {_SYSWRITE_REFUSED[ident, nr]} is not supported", column=col,
                   text=rest.strip(), expected="FN 17 SYSWRITE ID50 NR1/NR2 IDXt (tool length / radius), DL/DR 0")
    if ident == 50 and nr in (1, 2):
        if index is None or not (index >= 0 and index == int(index)) or tool_write is None:
            where.fail(f"{what}: no tool number", column=col, text=rest.strip(),
                       expected="IDX a whole number >= 0 (the tool)")
        tool_write(int(index), nr, value * scale)
        return
    if (ident, nr) not in _SYSWRITE_REFUSED:
        note(f"{what}: system data vcnc does not model, not written")


_SYSREAD_RE = re.compile(r"\s*SYSREAD\s+(Q[LR]?\d+)\s*=\s*ID\s*(\d+)\s+NR\s*(\d+)(?:\s+IDX\s*(\d+|Q[LR]?\d+))?\s*$",
                         re.I)
#: The machine status ``FN 18 SYSREAD IDi NRj`` reads (no index): (ID, NR) -> what it is (iTNC 530 technical manual
#: 07/2013, 9.5.4, groups 10 "Program information" and 20 "Machine status"; ID20 NR1 the active tool apart).
MACHINE_STATUS = {(10, 1): "mm = 0, inch = 1", (20, 2): "prepared tool number", (20, 3): "active tool axis",
                  (20, 4): "programmed spindle speed"}
_SYSREAD_EXPECTED = ("SYSREAD Qn = ID240 NR1 IDX1..3 or ID270 NR1 IDX1..3 (nominal position), ID20 NR1 (active tool) "
                     "NR2..NR4 (prepared tool, tool axis, spindle speed), ID10 NR1 (inch) "
                     "or ID50 NR1..NR23 IDXt (tool t's columns L, R, R2, DL, DR .. TT data)")
#: The tool-table columns of ``FN 18 SYSREAD ID50 NR3 .. NR23`` (NR1 L and NR2 R are read from the table), as the
#: TNC 426/430 technical manual's table of system data lists them ("Data from the tool table", group 50).
_ID50_COLUMNS = {3: "R2", 4: "DL", 5: "DR", 6: "DR2", 7: "TL, tool locked", 8: "RT, replacement tool",
                 9: "TIME1", 10: "TIME2", 11: "CUR. TIME", 12: "PLC status", 13: "LCUTS", 14: "ANGLE",
                 15: "CUT, TT: teeth", 16: "LTOL", 17: "RTOL", 18: "DIRECT", 19: "R-OFFS", 20: "L-OFFS",
                 21: "LBREAK", 22: "RBREAK", 23: "PLC value"}


def _condition(n: int, rest: str, params: QParameters, where: Where, col: int) -> str | None:
    """FN 9-12 ``IF a OP b GOTO LBL n`` (``rest`` at column ``col``): the label key to jump to when the test holds,
    else None; a malformed condition written with another FN's comparison names that FN."""
    op, test = FN_CONDITIONS[n]
    cm = re.match(rf"\s*IF\s*(.*?)\s+{op}\s+(.*?)\s*GOTO\s*(LBL\s*.*)$", rest, re.I)
    if cm is None:
        other = [f"{word} is FN {k}" for k, (word, _) in FN_CONDITIONS.items()
                 if k != n and re.search(rf"\s{word}\s", rest, re.I)]
        where.fail(f"malformed FN {n} condition", column=col, text=rest.strip(),
                   expected=f"FN {n}: IF a {op} b GOTO LBL n" + (f" ({', '.join(other)})" if other else ""))
    a = params.evaluate(cm.group(1), where, column=col + cm.start(1))
    b = params.evaluate(cm.group(2), where, column=col + cm.start(2))
    lm = LABEL_RE.match(cm.group(3))
    if lm is None:
        where.fail("malformed jump label", column=col + cm.start(3), text=cm.group(3), expected="LBL n")
    return label_key(lm) if test(a, b) else None


def _sysread(rest: str, params: QParameters, where: Where, col: int, *, position: np.ndarray, active: np.ndarray,
             scale: float, note: Callable[[str], None],
             tool: tuple[int, Callable[[int], tuple[float, float] | None]], stopped_at: int | None,
             system: Callable[[int, int], float] | None = None) -> None:
    """``FN 18: SYSREAD Qn = IDi NRj [IDXk]`` (TNC 640 user's manual, "FN 18: SYSREAD", the table of system
    data): ID240 NR1 / ID270 NR1 IDX1..3 the nominal position in machine / active coordinates (as simulated);
    ID20 NR1 the number of the active tool; ID50 NR1 / NR2 IDXt the length / radius L, R of tool t in the tool
    table (the program's TOOL DEF stands in for the table's row, as it does at TOOL CALL); ID50 NR3 .. NR23 its
    other columns, R2, DL, DR, DR2, TL, RT, TIME1, TIME2, CUR. TIME, PLC status, LCUTS, ANGLE and the tool touch
    probe's CUT, LTOL, RTOL, DIRECT, R-OFFS, L-OFFS, LBREAK, RBREAK, PLC value (the numbering of the TNC 426/430
    technical manual's table of system data, group 50 "Data from the tool table", as a shop's tool-copy macro
    comments NR3 - NR5: Stugo/Heidenhain Tool-copy.h), 0 with a note: vcnc's tool table
    (:class:`interpolators.context.Tool`) has no such columns.
    The machine status of :data:`MACHINE_STATUS` (ID10 NR1, ID20 NR2 .. NR4) is what ``system`` gives. ID230, the
    traverse range (a generator's ``FN 18: SYSREAD Q30 = ID230 NR3 IDX3`` then ``L ZQ30 R0 FMAX M91``: up to the
    positive software limit switch), is an error saying that the machine context holds no travel.
    The index may be a Q parameter (``IDXQ11``).

    A position read after a program stop with no move since (``stopped_at``): a measuring program stops
    there (``STOP``, ``M0``, ``M1``) so that the operator can jog the machine to a feature, and reads the
    jogged position, which a program file does not say. It reads the position where the program stopped
    (the operator pressing start without a jog, as on a dry run), with a note naming the stop's line; what
    the program computes from it (a division by zero of two equal readings) is then what the control does
    without a jog."""
    sm = _SYSREAD_RE.match(rest)
    ident, nr = (int(sm.group(2)[:6]), int(sm.group(3)[:6])) if sm else (0, 0)
    idx = None
    if sm is not None and sm.group(4) is not None:
        idx = sm.group(4)
        idx = params.get(idx) if idx[0] in "qQ" else float(idx[:9])
    known = {(240, 1), (270, 1), (20, 1), (50, 1), (50, 2), *((50, nr) for nr in _ID50_COLUMNS),
             *(MACHINE_STATUS if system is not None else ())}
    if sm is not None and ident == 230:  # the table of system data's group 230, "Traverse range"
        where.fail(f"FN 18 SYSREAD ID230 NR{nr} reads the machine's traverse range (its software limit switches), "
                   "which the machine context does not hold", column=col, text=rest.strip(),
                   expected="the limit written in the program (L Z-5 R0 FMAX M91), or " + _SYSREAD_EXPECTED)
    if sm is None or (ident, nr) not in known or (idx is None) != (ident in (10, 20)) \
            or (ident in (240, 270) and idx not in (1.0, 2.0, 3.0)):
        where.fail(f"FN 18 SYSREAD {rest.strip()!r} is not supported", column=col, text=rest.strip(),
                   expected=_SYSREAD_EXPECTED)
    if (ident, nr) in MACHINE_STATUS:
        value = system(ident, nr)
    elif ident == 20:
        value = float(tool[0])
    elif ident == 50:
        if not (idx >= 0 and idx == int(idx)):
            where.fail(f"FN 18 SYSREAD ID50 of tool {idx:g}: not a tool number", column=col, text=rest.strip(),
                       expected="IDX a whole number >= 0 (the tool)")
        if nr in _ID50_COLUMNS:  # R2, DL, DR ..: columns the machine context's tool table does not hold
            note(f"FN 18 SYSREAD ID50 NR{nr} ({_ID50_COLUMNS[nr]}): no such column in the machine context's "
                 "tool table: 0")
            value = 0.0
        else:
            data = tool[1](int(idx))
            if data is None:  # as TOOL CALL of a tool the table lacks: length and radius 0
                note(f"FN 18 SYSREAD ID50: tool {int(idx)} is not in the tool table: length and radius 0")
                data = (0.0, 0.0)
            value = data[nr - 1]
    else:
        axis = int(idx) - 1
        value = position[axis] if ident == 240 else active[axis]
        if stopped_at is not None:
            note(f"FN 18 ID{ident} after STOP (line {stopped_at}): the position where the program stopped; "
                 "a jog by the operator is not modelled")
        else:
            note("FN 18 SYSREAD: positions read as simulated")
    params.set(sm.group(1), value / scale if ident in (50, 240, 270) else value, where, column=col)


def _two_operands(body: str, op: str, params: QParameters, where: Where, column: int) -> tuple[float, float]:
    # the operator word sits between two signed operands: "+Q1 + +5", "+8 DIV +Q2", "+5 LEN +4"
    pat = re.escape(op) if op in "+-*" else rf"\b{op}\b"
    for om in re.finditer(rf"(?<=[\dA-Z.)])\s*{pat}\s*", body, re.I):
        left, right = body[: om.start()], body[om.end():]
        if left.strip() and right.strip():
            return (params.evaluate(left, where, column=column),
                    params.evaluate(right, where, column=column + om.end()))
    where.fail(f"expected two operands around {op}", column=column, text=body.strip(), expected=f"a {op} b")
