"""Parameters and expressions of ISO G-code, as LinuxCNC defines them.

LinuxCNC G-code overview (https://linuxcnc.org/docs/html/gcode/overview.html, sections
"Parameters", "Expressions", "Binary Operators", "Functions"):

* numbered parameters ``#1`` .. ``#5399`` (unset ones read 0; ``#1``-``#30`` are local to a
  subroutine call, where they hold its arguments), named parameters ``#<name>`` (local to the
  subroutine unless the name starts with ``_``: global; reading an unset one is an error);
* an assignment ``#1 = value`` takes effect after the whole line is read, so ``#1=2 X#1`` moves to
  the old value of ``#1``; its value may be an expression without enclosing brackets,
  ``#152=[#146-#140]/2``, as Fanuc custom macro B writes it (LinuxCNC would reject the text after
  the first value);
* expressions ``[ ... ]`` with ``**`` (power), ``* / MOD``, ``+ -``, ``EQ NE GT GE LT LE`` and
  ``AND OR XOR``, in falling precedence, left to right within a level; unary minus on any value;
* functions ``ABS ACOS ASIN COS EXP FIX FUP ROUND LN SIN SQRT TAN`` of ``[arg]`` (angles in
  degrees), ``ATAN[y]/[x]`` and ``EXISTS[#<name>]`` (``EXISTS[#n]``: 1 for 1 <= n < 5602), and
  Fanuc's ``BIN`` (BCD to binary) and ``BCD`` (binary to BCD) of whole numbers >= 0;
* a parameter number may be any value: ``##1``, ``#[#1+1]``, even ``#ATAN[1]/[1]`` (#45);
* ``#<_value>`` (the value the last subroutine returned, 0 if none) and ``#<_value_returned>``
  are predefined and start at 0; ``#<_line>`` is the line being executed, counted in its file
  (LinuxCNC ``interp_namedparams.cc`` NP_LINE: the sequence number, tests/interp/sequence-number).

System parameters that read the machine state (``#5001`` and above) come from the reader's state
(:mod:`interpolators.iso_system`: positions, offsets, tools; read-only); one it does not model is an
error naming it unless the program has set it. So do LinuxCNC's read-only named aliases ``#<_x>`` ..
``#<_w>`` (#5420..), ``#<_abs_x>`` .. (#5021..) and ``#<_current_tool>`` (#5400); ``#<_ini[..]..>``
(INI file values) is an error, as is assigning any of them.

Fanuc/Haas custom macro B (Fanuc 0i-MD operator's manual B-64304EN, "Custom macro", "Variables";
Mitsubishi M700V programming manual 13.5 "User macro", "Undefined variables"; Haas mill operator's
manual, "Macros"):

* *vacant* variables: ``#0`` is always vacant and cannot be set; under the ``fanuc`` and ``haas``
  dialects every numbered parameter no assignment has set is vacant, and the locals ``#1``-``#33``
  of a G65 macro call are vacant but for its arguments under every dialect (LinuxCNC has no G65;
  elsewhere LinuxCNC reads unset parameters as 0). A word whose value is a vacant parameter alone
  is left out (``G0 X#1 Y10`` is ``G0 Y10``); ``#2 = #1`` makes ``#2`` vacant; in arithmetic and
  functions vacant counts 0 (``#1 + 10`` is 10, ``#1 * 5`` is 0); in comparisons ``EQ`` and ``NE``
  tell vacant from 0 (``#1 EQ #0`` holds, ``#1 EQ 0`` does not) while ``GT GE LT LE`` take it as 0;
  a vacant condition is false.
* under the ``fanuc`` and ``haas`` dialects a variable or expression in an NC address is rounded to the address's
  least input increment (0.001 mm, 0.0001 in, 0.001 deg; D H M T to whole numbers: :func:`address_values`), and a
  ``ROUND`` inside it rounds to that increment, not to a whole number (:meth:`_Reader.address_round`); in an
  assignment ``#1 = ROUND[..]`` rounds to a whole number.
* ``AND``, ``OR`` and ``XOR`` work bit by bit on the integer parts of their operands under the ``fanuc`` and
  ``haas`` dialects (Fanuc 0i-MD B-64304EN "Arithmetic and logic operation": "Logical operations are performed
  on binary numbers bit by bit"; Haas mill operator's manual, "Macros", "Logical operations": "only the integer
  portion of the floating point number is used"): ``5 OR 3`` is 7, ``5 XOR 3`` is 6; on comparisons (1 or 0)
  they are the logical ones LinuxCNC has.
* precedence under the ``fanuc`` and ``haas`` dialects is Fanuc's (Fanuc 0i-MD B-64304EN "Custom macro",
  "Arithmetic and logic operation", "Priority of operations": functions first, then the operations of the
  multiplication group ``* / AND``, then those of the addition group ``+ - OR XOR``; the manual's operator
  table groups them so, as zappettiniconsulting.com/wiki/macro-arithmetic copies it, its "Priority of
  operations" text itself is not in our search index; ``MOD`` of the 0i-F/30i ranks with ``*``, our reading):
  ``2 + 3 AND 1`` is ``2 + [3 AND 1]`` = 3, ``6 OR 1 * 2`` is 6, ``1 + 2 OR 4`` is ``[1 + 2] OR 4`` = 7,
  left to right within a level. The comparisons ``EQ NE GT GE LT LE`` come last: Fanuc writes one per
  conditional expression of IF and WHILE ("[<expression> EQ <expression>]") and joins conditions as
  ``[#1 EQ 1] AND [#2 EQ 2]``. A bracket that joins two comparisons without brackets of their own
  (``[#1 GT 0 AND #1 LT 9]``) would compare ``#1 GT [0 AND #1]`` with 9, which no program means: it is read in
  LinuxCNC's precedence instead, the comparisons first (as LinuxCNC reads it, and as CNCSimulator's macro
  manual shows ``[#4GT#2AND#4GT#3]``), with a note (our reading: Haas's manual only says that conditional
  expressions "can make use of Boolean operators"); in an assignment (``#1 = [#2 GT 3]``, which Fanuc
  refuses) a comparison gives 1 or 0 as Haas ("all expressions set a conditional value") and LinuxCNC do.
  Haas's manual ("Macros", "Operators") states no precedence: our reading is Fanuc's, as Haas reads custom
  macro B.
* ``MOD`` is the remainder made non-negative, as LinuxCNC's (Haas "Arithmetic Operators": ``27 MOD 20`` is
  7; how Fanuc rounds its operands is not in the manuals of our search index: our reading keeps them as
  they are).
* under the ``fanuc`` and ``haas`` dialects ``#1000``-``#4999`` are system variables, not user
  parameters: the modal information ``#4001``.. comes from the reader's state
  (:mod:`interpolators.iso_system`), ``#3000 = n (message)`` is a macro alarm (an error naming the line, n
  and the message: the comment of its block), ``#3006 = n (message)`` a stop with a message (Fanuc 0i-MD
  B-64304EN "System variables", "Stop with a message": the blocks before it run, then the program stops with
  the comment of the block shown until the operator presses cycle start; Haas "Macros", #3006 programmable stop
  with a message; neither manual's own text is in our search index): it is kept in :attr:`Parameters.stops` for
  the reader, which ends the path at rest there as at M0,
  other writes are kept without effect (output signals, ``#3003``/``#3004`` single-block and
  feed-hold switches: the virtual machine has no operator to press feed hold and runs at 100 % override), but a
  ``#3004`` with bit 2 set (Fanuc 0i-MD B-64304EN "System variables": exact stop check suppressed) is noted: the
  G09/G61 blocks under it still end at rest; reading an unmodelled one is an error naming it.
* a value vcnc cannot know (a clock, Haas's timers, a jogged or probed position: ``system`` gives the reason)
  may be stored in a common variable (``#100`` up) and is then *held* there (:attr:`Parameters.held`): reading
  that variable, or one set from it, is the error naming the first reading, its line and its reason. A program that
  only logs a time (a Haas shop's cycle-time count ``#10002 = #3020 - #10000`` ... ``#10000 = #3020``, whose
  variables steer nothing) so reads; one steered by it is refused where the value is used (our reading: nothing the
  tool does depends on a value no block reads, so the value itself need not be known).
* a G65 macro call's locals are ``#1``-``#33`` per call level (Haas, "Local Variables": "Local
  variables range between #1 and #33 ... During a G65 call, all new local variables are cleared");
  ``#100``-``#199`` and ``#500``-``#999`` are common (global) variables, and the Haas Next
  Generation Control's general-purpose variables ``#10000``-``#10999`` ("saved on power off", Haas
  NGC macro variable table) are global parameters too (the NGC's second, legacy number of some of
  them, ``#100``-``#199`` and ``#500``-``#999``, is a different parameter here).
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable
from typing import NoReturn

from interpolators._words import MAX_MAGNITUDE, Where, token_at
from interpolators.iso_decimal import address_increment
from interpolators.iso_words import Word, block_comment, read_words

__all__ = ["Parameters", "read_line", "evaluate_at", "evaluate_condition", "has_parameters", "address_values"]

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)")
_NAME = re.compile(r"<([^>]*)>")
_FUNCTIONS = ("ABS", "ACOS", "ASIN", "ATAN", "BCD", "BIN", "COS", "EXISTS", "EXP", "FIX", "FUP", "ROUND", "LN",
              "SIN", "SQRT", "TAN")
_COMPARISONS = ("EQ", "NE", "GT", "GE", "LT", "LE")
#: LinuxCNC's binary operators by precedence, lowest first ("Binary Operators").
_BINARY = [("OR", "XOR", "AND"), _COMPARISONS, ("+", "-"), ("*", "/", "MOD"), ("**",)]
#: Fanuc custom macro B's, lowest first (module docstring): the comparisons, then ``+ - OR XOR``, then
#: ``* / AND MOD``; ``**`` (not Fanuc's: ``POW[a,b]``) stays above them.
_MACRO_B_BINARY = [_COMPARISONS, ("+", "-", "OR", "XOR"), ("*", "/", "AND", "MOD"), ("**",)]


def _operator_table(levels: list[tuple[str, ...]]) -> dict[str, tuple[tuple[str, int], ...]]:
    """The binary operators by their first character, longest first (``**`` before ``*``), with their level."""
    return {c: tuple(sorted(((op, level) for level, ops in enumerate(levels) for op in ops if op[0] == c),
                            key=lambda e: -len(e[0])))
            for c in {op[0] for ops in levels for op in ops}}


_OPERATORS = _operator_table(_BINARY)
_MACRO_B_OPERATORS = _operator_table(_MACRO_B_BINARY)
#: Highest of LinuxCNC's user parameters (#31-#5000, "Numbered Parameters"); above it they hold
#: machine state (#5021-#5029 machine position, #5061-#5070 probe result, #5161-#5169 G28 home,
#: #5211-#5219 G92 offsets, ...; Fanuc's #5001-#5028 are positions too): reading one the program has
#: not set is an error rather than a silent 0.
_LAST_USER_PARAMETER = 5000
#: Highest numbered parameter a program may set without naming machine state.
_MAX_USER_PARAMETER = 5219
#: System parameters a program may set: #5599, LinuxCNC's switch for (DEBUG,) output
#: (LinuxCNC "Numbered Parameters"); it moves nothing.
_WRITABLE_SYSTEM = frozenset({5599})
#: LinuxCNC's number of numbered parameters (RS274NGC_MAX_PARAMETERS): EXISTS[#n] is 1 for 1 <= n < it.
_LINUXCNC_PARAMETERS = 5602
#: Haas NGC general-purpose macro variables (global, readable and writable).
_HAAS_GENERAL = range(10000, 11000)
#: LinuxCNC's predefined read-only named parameters that alias system parameters ("Predefined Named
#: Parameters": #<_x> = #5420 ... #<_w> = #5428, #<_abs_x> = #5021 ..., #<_current_tool> = #5400).
_NAMED_SYSTEM = {**{f"_{a}": 5420 + i for i, a in enumerate("xyzabcuvw")},
                 **{f"_abs_{a}": 5021 + i for i, a in enumerate("xyzabcuvw")}, "_current_tool": 5400}
#: Fanuc/Haas system variables below #5000 (interface signals #1000-, tool offsets #2001-, alarm #3000,
#: clocks and settings #3001-, modal information #4001-): under LinuxCNC they are user parameters.
_FANUC_SYSTEM = range(1000, 5000)
#: Fanuc/Haas macro alarm: setting it stops the program with an alarm.
_FANUC_ALARM = 3000
#: Fanuc/Haas stop with a message: setting it stops the program as M0 does (:attr:`Parameters.stops`).
_FANUC_MESSAGE_STOP = 3006
#: Fanuc/Haas feed hold, feedrate override and exact stop check suppression (bits 0, 1, 2): kept without effect, a
#: suppressed exact stop check noted (the G09/G61 blocks still end at rest).
_FANUC_SUPPRESSION = 3004
#: Locals of a LinuxCNC O-word call (#1-#30) and of a Fanuc/Haas G65 macro call (#1-#33).
OWORD_LOCALS = 30
MACRO_LOCALS = 33


#: Statements of controls whose macro language is not Fanuc's or LinuxCNC's, read as an address letter and a
#: name: Centroid CNC12's ``DEFINE <name> #n`` and ``IF #n THEN GOTO n`` (our reading of CNC12 macros, e.g.
#: Centroid's stock ``mfunc53.mac`` as github.com/tcmaker/cnc1325 keeps it, "IF #50010 ;Prevent lookahead from
#: parsing past here", "IF #4201 || #4202 THEN GOTO 1000", "Please see TB300 for tips on writing custom macros"),
#: Okuma OSP's variables written ``V<name>=`` (our reading of OSP user tasks, ``VFST=#81H``), and the DDCS
#: (Digital Dream) controllers' ``IF #1505==0 GOTO999`` and ``IF #569<#792 GOTO1``, whose conditions compare as C
#: does (``==``, ``!=``, ``<``) and jump without CNC12's THEN (our
#: reading of the DDCS Expert M350 macros github.com/fchabot-dxf/DDCS-Studio keeps: "IF #1505==0 GOTO999",
#: "WHILE #18<#3 DO2", "//" comments; no DDCS manual at hand). A Fanuc condition left without its brackets,
#: ``IF #1 GT 0 GOTO 10``, is named as such (FANUC 0i-MF operator's manual, custom macro, "Conditional branch":
#: "IF [<conditional expression>] GOTO n").
_FOREIGN_STATEMENTS = (
    (re.compile(r"IF\s*#(?:(?!THEN)[^\[])*?(==|!=|<|>)(?:(?!THEN)[^\[])*GOTO", re.I),
     "IF #n==v GOTO n, a statement of the DDCS controllers' macro language (a C-style condition such as "
     "#1==0 or #1<#2, without brackets and without THEN)"),
    (re.compile(r"IF\s*#(?:(?!THEN)[^\[])*\b(EQ|NE|GT|GE|LT|LE)\b", re.I),
     "IF #n GT v GOTO n: a condition without its brackets, which Fanuc macro B writes IF [#1 GT 0] GOTO n"),
    (re.compile(r"DEFINE\b", re.I), "DEFINE <name> #n, a statement of Centroid CNC12's macro language"),
    (re.compile(r"IF\s*#[^\[]*(THEN|$)", re.I), "IF #n THEN ..., a statement of Centroid CNC12's macro language"),
    (re.compile(r"V[A-Z]{2,}\s*=", re.I), "V<name>=, a variable of Okuma OSP's user task language"),
)


#: Fanuc macro functions that read the control itself, named in the error (fanuc, haas): FANUC Series 30i-B
#: operator's manual B-64484EN, "Custom macro", "Reading parameters": "PRM[n]" and "PRM[n, bit]" read the
#: parameter No. n (Fusion's fanuc.cps writes "IF[PRM[5006,6]NE1]THEN#3000=91" on head machines).
_MACHINE_FUNCTIONS = {"PRM": "PRM[..] reads a parameter of the control (Fanuc 30i 'Reading parameters'), which "
                             "vcnc does not model"}


def _foreign_statement(code: str, p: int) -> str:
    """Why the name at ``p`` of ``code`` is no value, when the address letter before it starts a statement of
    another control's language (:data:`_FOREIGN_STATEMENTS`); else the placeholder hint."""
    start = p - 1 if p > 0 and code[p - 1].isalpha() else p
    for pattern, what in _FOREIGN_STATEMENTS:
        if start < p and pattern.match(code, start):
            return f" ({what}; vcnc reads ISO G-code with Fanuc macro B or LinuxCNC O-codes)"
    if code[:p].rstrip().endswith("["):  # "G0 X[xmin]": a CNCjs macro's expression (iso_words.read_words)
        return (" (text left in brackets, such as a template's placeholder, or an expression the CNCjs sender "
                "evaluates before grbl reads the line, as a CNCjs macro writes 'G0 X[xmin]'?)")
    return " (text left in brackets, such as a template's placeholder?)"


class Parameters:
    """Parameter store: global numbered and named parameters and a stack of call frames.

    Parameters
    ----------
    macro_b : bool
        Fanuc/Haas custom macro B semantics (the ``fanuc`` and ``haas`` dialects): a numbered
        parameter no assignment has set is *vacant*, not 0, and ``FIX``/``FUP`` round towards / away
        from zero. Without it, unset parameters read 0 (LinuxCNC) except the locals of a G65 macro
        call, which are vacant under every dialect (LinuxCNC has no G65), and ``FIX``/``FUP`` are
        floor and ceiling (LinuxCNC ``interp_execute.cc``).
    system : callable, optional
        ``system(n)`` gives ``(value, why)`` for the system parameter ``#n`` from the machine state
        (:func:`interpolators.iso_system.system_parameter`): the value, or ``None`` with the reason
        it cannot be known (an error naming it), or ``(None, "")`` when ``#n`` is not modelled. A
        parameter it models is read-only, unless ``set_system`` takes it.
    named_state : callable, optional
        ``named_state(name)`` gives LinuxCNC's predefined named parameter ``#<name>`` of the modal state
        (:func:`interpolators.iso_system.named_state_parameter`) as ``(value, why)``: the value, or None with the
        reason the machine and not the program knows it (an error naming it), ``(None, "")`` for another name; with it
        ``#<_call_level>`` reads the O-word call depth. They are read-only.
    set_system : callable, optional
        ``set_system(n, value)`` sets a system parameter the control lets a program write (Fanuc/Haas
        work offsets: :func:`interpolators.iso_system.set_system_parameter`); True when it did.
    fanuc : bool
        Fanuc's own rules (the ``fanuc`` dialect). Its abbreviated macro words (:mod:`interpolators.iso_macro`
        gives the source): a function written by its first two characters (``RO[#1]`` is ``ROUND[#1]``, ``SQ``
        is ``SQRT``); two characters that begin more than one function's name are an error naming them. The
        statement words (``WH``, ``GO``, ``EN``, ``TH``) are read by :mod:`interpolators.iso_macro`. Its
        functions (Fanuc 0i-MD B-64304EN and 0i-MF B-64604EN "Custom macro", "Arithmetic and logic operation"):
        ``ATAN[y]/[x]`` is 0 to 360 deg (parameter NAT, No. 6004#0, = 0, its default: ``ATAN[-1]/[-1]`` is 225;
        LinuxCNC's and Haas's atan2 gives -135), and the Series 0i-F/30i forms ``ATAN[y,x]`` and ``POW[a,b]``
        (a to the power b) read.
    inch : callable, optional
        ``inch()``: G20 is in force (macro B ``ROUND`` in an address rounds to 0.0001 in, else to 0.001 mm:
        :meth:`_Reader.address_round`); None: mm.
    """

    def __init__(self, *, macro_b: bool = False,
                 system: Callable[[int], tuple[float | None, str]] | None = None,
                 set_system: Callable[[int, float | None], bool] | None = None, fanuc: bool = False,
                 named_state: Callable[[str], tuple[float | None, str]] | None = None,
                 inch: Callable[[], bool] | None = None) -> None:
        self.numbered: dict[int, float] = {}
        self.named: dict[str, float] = {"_value": 0.0, "_value_returned": 0.0}  # LinuxCNC's predefined ones
        self.frames: list[tuple[dict[int, float], dict[str, float], int]] = []
        self.lowest_depth = 0  # the fewest frames since lowest_since_last() last read it
        self.macro_b = macro_b
        self.unbracketed = 0  # assignments "#1 = #1 + 2" read without macro_b (LinuxCNC wants [#1 + 2])
        self.system = system
        self.set_system = set_system
        self.named_state = named_state
        self.fanuc = fanuc
        self.inch = inch
        self.stops: list[tuple[int, str]] = []  # #3006 message stops reached: line, message
        self.plain_alarms: list[tuple[int, int]] = []  # without macro B: #3000 / #3006 set at line, as parameters
        self.exact_stop_suppressed: list[int] = []  # macro B: lines whose #3004 write suppresses the exact stop check
        self.joined_comparisons = 0  # macro B brackets that join comparisons without brackets of their own
        #: common variables holding a value vcnc cannot know: #n -> (line, reason) of the first reading
        self.held: dict[int, tuple[int, str]] = {}
        self._holding: list[tuple[int, str] | None] | None = None  # while an assignment's value is read

    def held_value(self, key: int | str, read: Callable[[], tuple[float | None, int]]) -> tuple[float | None, int]:
        """``read()`` of the value a macro B assignment gives ``key``: when ``key`` is a common variable (#100
        up, not a call's local), a value vcnc cannot know read there is held by it (module docstring) instead of
        an error; ``held`` then says so until the variable is set again."""
        if not isinstance(key, int) or key < 100 or self._holding is not None:
            return read()
        self._holding = [None]
        try:
            result = read()
        finally:
            origin, self._holding = self._holding[0], None
        if origin is None:
            self.held.pop(key, None)
        else:
            self.held[key] = origin
        return result

    def _local_numbered(self, n: int) -> dict[int, float]:
        return self.frames[-1][0] if self.frames and 1 <= n <= self.frames[-1][2] else self.numbered

    def _scope(self, name: str) -> dict[str, float]:
        return self.frames[-1][1] if self.frames and not name.startswith("_") else self.named

    def get_numbered(self, n: int, where: Where, column: int, text: str) -> float | None:
        """The value of ``#n``; ``None`` when it is vacant (``#0``, or unset under Fanuc semantics)."""
        if n == 0:
            return None  # Fanuc's null variable: always vacant
        state, why = self.system(n) if self.system is not None and self._is_system(n) else (None, "")
        if (n < 1 or n >= _LINUXCNC_PARAMETERS) and n not in _HAAS_GENERAL and not (
                self.macro_b and (state is not None or why)):  # Fanuc #7001.., #10001..
            where.fail(f"parameter number #{n} out of range{self._beyond_macro_b(n)}", column=column, text=text,
                       expected="a parameter #1 .. #5601 (or Haas #10000 .. #10999)")
        if state is not None:
            return state
        if why and self._holding is not None:  # an assignment's value: held by the variable it sets (docstring)
            self._holding[0] = self._holding[0] or (where.line, f"#{n} read at line {where.line}: {why}")
            return 0.0
        if why:
            where.fail(f"parameter #{n}: {why}", column=column, text=text,
                       expected="a parameter whose value the program determines")
        store = self._local_numbered(n)
        if n in self.held and store is self.numbered:
            if self._holding is not None:
                self._holding[0] = self._holding[0] or self.held[n]
                return 0.0
            where.fail(f"parameter #{n} holds a value vcnc cannot know ({self.held[n][1]})", column=column,
                       text=text, expected="a parameter whose value the program determines")
        if self.macro_b and n == _FANUC_ALARM and n not in store:
            where.fail("#3000 read: it is the macro alarm, which a program writes to stop with an alarm (#3000 = n "
                       "(message)); what reading it gives is not modelled (no Fanuc or Haas manual found says)",
                       column=column, text=text, expected="#3000 only written, as '#3000 = n (message)'")
        if self.macro_b and n in _FANUC_SYSTEM and n not in store:
            where.fail(f"#{n}: this Fanuc system variable (#1000-#4999: interface signals, tool offsets, "
                       "alarms, clocks, modal information) is not modelled", column=column, text=text,
                       expected="a common variable #100-#199, #500-#999, or a modelled one (#2001-#2400 tool "
                                "offsets (Haas #2001-#2800), #4001-#4016 and #4022 modal G codes, #4107 D, #4109 F, "
                                "#4111 H, #4119 S, #4120 T, #3901/#3902 parts counters, #5001.. positions)")
        if (n > _MAX_USER_PARAMETER or (n > _LAST_USER_PARAMETER and n not in store)) and n not in _HAAS_GENERAL:
            fanuc = (" (#5201-#5206: the external work offset of Fanuc and Haas, which --dialect fanuc or haas "
                     "reads)") if 5201 <= n <= 5206 else ""
            where.fail(f"parameter #{n}: this system parameter (machine state above #5000) is not modelled{fanuc}",
                       column=column, text=text,
                       expected="a parameter #1 .. #5000, one the program has set, or a modelled system parameter "
                                "(#5161-#5169, #5181-#5189, #5211-#5219, #5220-#5389, #5400-#5409, #5420-#5428)")
        if n not in store and (self.macro_b or (self.frames and self.frames[-1][2] == MACRO_LOCALS
                                               and n <= MACRO_LOCALS)):
            return None
        return store.get(n, 0.0)

    def _beyond_macro_b(self, n: int) -> str:
        """Under macro B, what a variable numbered 5602 or more that vcnc does not model is: below 100000 a
        system variable of the machine (our reading: Fanuc and Haas number their system variables from #5000 up
        and machine makers add their own, as a Mazak HCN shop's pallet macro reads #51998); from 100000 beyond
        every variable vcnc models (the ranges this module names; our reading, no manual at hand: one of the further
        common variables some controls add as an option, as a mould shop's Fanuc programs keep their settings in
        #900000-#901999); "" otherwise."""
        if not self.macro_b or n < _LINUXCNC_PARAMETERS:
            return ""
        if n < 100000:  # our reading: a numbered system variable of the machine (a Mazak HCN shop's #51998)
            return (f" (#{n}: a system variable of the machine's control, which vcnc does not model: Fanuc and Haas "
                    "controls keep positions, offsets and their maker's variables from #5000 up)")
        return (f" (#{n}: beyond the Fanuc/Haas variables vcnc models, locals #1-#33, common #100-#199 and "
                "#500-#999, Haas #10000-#10999, system variables below #100000; the larger common-variable ranges "
                "that some controls add as an option are not modelled)")

    def _is_system(self, n: int) -> bool:
        """Whether ``#n`` may report machine state: above #5000, and under macro B #1000-#4999 too."""
        return n > _LAST_USER_PARAMETER or (self.macro_b and n in _FANUC_SYSTEM)

    def get_named(self, name: str, where: Where, column: int, text: str) -> float:
        key = name.lower().replace(" ", "")
        if key.startswith("_ini["):
            where.fail(f"named parameter #<{name}>: INI file values are not available (vcnc reads no INI file)",
                       column=column, text=text, expected="a parameter the program sets")
        if key.startswith("_hal["):
            # LinuxCNC overview.adoc "Named Parameters": "#<_hal[HAL item]> Allows G-code programs to read the values
            # of HAL pins" ([RS274NGC] HAL_PIN_VARS); QtPlasmaC's programs take their cut feed so
            where.fail(f"named parameter #<{name}>: a HAL pin's value, read from the running machine (LinuxCNC "
                       "HAL_PIN_VARS), which vcnc does not have (no HAL)", column=column, text=text,
                       expected="a number, or a parameter the program sets, in place of the HAL pin")
        if key == "_line":
            return float(where.line)
        if key == "_task":
            # 1 when the machine runs the program (emctaskmain.cc ``int _task = 1``), 0 in a preview
            # (gcodemodule.cc) or the standalone rs274 (sai/driver.cc without -T); vcnc runs it as the machine
            return 1.0
        if key in _NAMED_SYSTEM and self.system is not None:
            value = self.get_numbered(_NAMED_SYSTEM[key], where, column, text)
            return 0.0 if value is None else value
        state, why = (None, "") if self.named_state is None else self.named_state(key)
        if state is not None:
            return state
        if why:
            where.fail(f"named parameter #<{name}>: {why}", column=column, text=text,
                       expected="a parameter whose value the program determines")
        if key == "_call_level" and self.named_state is not None:
            return float(len(self.frames))  # the O-word call depth (interp_namedparams.cc NP_CALL_LEVEL)
        scope = self._scope(key)
        if key not in scope:
            where.fail(f"named parameter #<{name}> is read before it is set", column=column, text=text,
                       expected=f"#<{name}> = value before its first use")
        return scope[key]

    def exists(self, name: str) -> bool:
        key = name.lower().replace(" ", "")
        return key in self._scope(key)

    def assign(self, key: int | str, value: float | None, where: Where, column: int, text: str) -> None:
        """Set a parameter; ``None`` (a vacant value, ``#1 = #0``) makes a numbered one vacant."""
        if isinstance(key, int):
            if key == 0:
                where.fail("parameter #0 cannot be set: #0 is the null variable (Fanuc macro B: always vacant); "
                           "a #[#n] whose #n is unset names it, as in a macro program run on its own instead of "
                           "through its G65 call", column=column, text=text,
                           expected="a parameter #1 .. #5219 (a macro program is run by its G65 call)")
            if self.macro_b and key == _FANUC_ALARM:
                # Fanuc/Haas: "#3000 = n (message)" stops the program with macro alarm n (Haas: "Alarms")
                message = block_comment(where.text, where)
                shown = f" ({message.strip()})" if message and message.strip() else ""
                where.fail(f"macro alarm #3000 = {value if value is not None else 0:g}{shown}: the program raises an "
                           "alarm here", column=column, text=where.text, expected="a program that does not reach its "
                           "alarm")
            if not self.macro_b and key in (_FANUC_ALARM, _FANUC_MESSAGE_STOP):
                self.plain_alarms.append((where.line, key))  # LinuxCNC: parameters like any other below #5000
            if self.macro_b and key == _FANUC_MESSAGE_STOP:
                message = block_comment(where.text, where)
                self.stops.append((where.line, message.strip() if message else ""))
                return
            if self.macro_b and key == _FANUC_SUPPRESSION and value is not None and int(value) & 4:
                self.exact_stop_suppressed.append(where.line)  # noted by the reader (iso_text.expression_notes)
            if self.set_system is not None and self.set_system(key, value):
                return
            state, why = self.system(key) if self.system is not None and self._is_system(key) else (None, "")
            if state is not None or why:
                what = f"cannot be set: {why}" if why else "is read-only: it reports the machine state"
                where.fail(f"parameter #{key} {what}", column=column, text=text,
                           expected="a user parameter #1 .. #5000 (set offsets with G10, G92, G43)")
            if (key < 1 or key > _MAX_USER_PARAMETER) and key not in _WRITABLE_SYSTEM and key not in _HAAS_GENERAL:
                where.fail(f"parameter #{key}: system parameters cannot be set{self._beyond_macro_b(key)}",
                           column=column, text=text,
                           expected="a parameter #1 .. #5219 (or #5599, the DEBUG output switch)")
            store = self._local_numbered(key)
            if value is None:
                store.pop(key, None)
            else:
                store[key] = value
        else:
            k = key.lower().replace(" ", "")
            if k.startswith("_ini[") or (k in _NAMED_SYSTEM and self.system is not None) or (
                    self.named_state is not None and (k == "_call_level" or self.named_state(k) != (None, ""))):
                # LinuxCNC "Cannot assign to read-only parameter" (tests/interp/iniparam-failassign)
                where.fail(f"named parameter #<{key}> is read-only", column=column, text=text,
                           expected="a named parameter of the program's own")
            if value is None:
                where.fail(f"named parameter #<{key}> cannot be set to a vacant value", column=column, text=text,
                           expected="a value")
            self._scope(k)[k] = value

    def push(self, args: list[float]) -> None:
        """Enter an O-word subroutine: ``#1``.. hold ``args``, the other locals (to ``#30``) start unset."""
        self.frames.append(({i + 1: v for i, v in enumerate(args)}, {}, OWORD_LOCALS))

    def push_macro(self, values: dict[int, float]) -> None:
        """Enter a G65 macro: the locals ``#1``-``#33`` named by ``values`` are set, the others vacant."""
        self.frames.append((dict(values), {}, MACRO_LOCALS))

    def pop(self) -> None:
        self.frames.pop()
        self.lowest_depth = min(self.lowest_depth, len(self.frames))

    def lowest_since_last(self) -> int:
        """The fewest call frames there were since the last call of this (a return followed by a call between
        two lines leaves as many frames as before, yet the called level was left and entered anew)."""
        lowest, self.lowest_depth = min(self.lowest_depth, len(self.frames)), len(self.frames)
        return lowest


def has_parameters(code: str) -> bool:
    """True when a line needs the parameter reader (``#`` or ``[``)."""
    return "#" in code or "[" in code


class _JoinedComparisons(Exception):
    """A macro B bracket joins two comparisons without brackets of their own (:meth:`_Reader.grouped`)."""


class _Reader:
    """Recursive-descent reader of LinuxCNC real values on one comment-free line."""

    def __init__(self, code: str, where: Where, params: Parameters) -> None:
        self.code = code
        self.up = code.upper()
        self.where = where
        self.params = params
        self.logical = False  # this bracket joins comparisons: LinuxCNC's precedence (grouped)
        self.address: str | None = None  # the NC address whose value is being read (macro B ROUND: address_round)
        self.rounded: tuple[int, str] | None = None  # the first ROUND read in an address: column, address

    def skip(self, pos: int) -> int:
        while pos < len(self.code) and self.code[pos] in " \t\r":
            pos += 1
        return pos

    def fail(self, message: str, pos: int, expected: str):
        tok = token_at(self.code, min(pos, max(len(self.code) - 1, 0)))
        self.where.fail(message, column=pos + 1, text=tok, expected=expected)

    def parameter(self, pos: int) -> tuple[int | str, int]:
        """``#n``, ``#<name>`` or ``#[expr]``/``##n`` at ``pos`` (the ``#``): the key and end."""
        p = self.skip(pos + 1)
        if p < len(self.code) and self.code[p] == "<":
            m = _NAME.match(self.code, p)
            if m is None:
                self.fail("unclosed parameter name", pos, "#<name>")
            return m.group(1), m.end()
        if p < len(self.code) and self.code[p].isalpha() and not any(self.up.startswith(f, p) for f in _FUNCTIONS):
            name = re.match(r"[^\W\d]\w*", self.code[p:]).group(0)  # any letter, as str.isalpha (e.g. 'À')
            why = ("CNCSimulator Pro's #region and $ lines are skipped only alone on their line"
                   if name.lower().startswith(("region", "endregion")) else
                   "a placeholder a sender fills in before it streams the program, as GRBL-Plotter's tool-change "
                   "scripts' #TOAZ: vcnc reads the program as the control receives it")
            self.fail(f"'#{name}' is not a parameter ({why})", pos, "#<number>, #<name> or #[expression]")
        address, self.address = self.address, None  # a variable's number is no address value (#[ROUND[#1]])
        value, end = self.real(p)
        self.address = address
        if value != int(value):
            self.fail(f"parameter number {value:g} is not a whole number", pos, "#<whole number>")
        return int(value), end

    def read_parameter(self, pos: int) -> tuple[float | None, int]:
        key, end = self.parameter(pos)
        text = self.code[pos:end]
        if isinstance(key, int):
            return self.params.get_numbered(key, self.where, pos + 1, text), end
        return self.params.get_named(key, self.where, pos + 1, text), end

    def real(self, pos: int) -> tuple[float, int]:
        """A real value where a number is needed (a vacant one counts 0, as in Fanuc arithmetic)."""
        v, end = self.operand(pos)
        return (0.0 if v is None else v), end

    def operand(self, pos: int) -> tuple[float | None, int]:
        """A real value: number, parameter, [expression], function, with unary signs; ``None`` when
        it is a vacant parameter alone (``#1``, ``-#1``, ``[#1]``), which Fanuc keeps vacant."""
        p = self.skip(pos)
        if p >= len(self.code):
            self.fail("missing value", pos, "a number, #parameter or [expression]")
        ch = self.code[p]
        if ch in "+-" and not _NUMBER.match(self.code, p):
            v, end = self.operand(p + 1)
            return (-v if ch == "-" and v is not None else v), end
        if ch == "[":
            v, end = self.grouped(p + 1)
            end = self.skip(end)
            if end >= len(self.code) or self.code[end] != "]":
                self.unclosed(p, end)
            return v, end + 1
        if ch == "#":
            return self.read_parameter(p)
        m = _NUMBER.match(self.code, p)
        if m:
            v = float(m.group(0))
            if abs(v) > MAX_MAGNITUDE:
                self.fail("number out of range", p, f"a magnitude <= {MAX_MAGNITUDE:g}")
            return v, m.end()
        for name in _FUNCTIONS:
            if self.up.startswith(name, p):
                return self.function(name, p)
        if self.params.fanuc and self.up.startswith("POW", p):
            return self.function("POW", p)
        word = re.match(r"[A-Za-z]\w*", self.code[p:])
        if word and self.params.fanuc and len(word.group(0)) == 2 \
                and self.code[self.skip(p + 2):].startswith("["):
            return self.abbreviated(word.group(0).upper(), p)
        if word and self.code[self.skip(p + word.end()):].startswith("["):
            known = _MACHINE_FUNCTIONS.get(word.group(0).upper()) if self.params.macro_b else None
            self.fail(f"malformed value: {known}: not supported" if known else
                      f"malformed value: unknown function {word.group(0)!r}", p,
                      "a function of " + ", ".join(_FUNCTIONS))
        if word:
            self.fail(f"malformed value: '{word.group(0)}' is neither a number, a parameter nor a function"
                      f"{_foreign_statement(self.code, p)}", p,
                      "a number, #parameter, [expression] or function such as SIN[30]")
        self.fail("malformed value", p, "a number, #parameter, [expression] or function such as SIN[30]")
        raise AssertionError("unreachable")

    def unclosed(self, start: int, end: int) -> NoReturn:
        """The error for an expression opened at ``start`` that does not close at ``end``: the text
        there, an exponent (``1e308``: RS274/NGC numbers have none; LinuxCNC interp_read.cc
        read_operation says "Unknown operation name starting with e") or the end of the line."""
        if end >= len(self.code) or self.code[end] in ";(":
            self.fail("unclosed '[' in an expression", start, "']' closing the expression")
        exponent = re.match(r"[eE][+-]?\d", self.code[end:])
        if exponent and end > 0 and (self.code[end - 1].isdigit() or self.code[end - 1] == "."):
            number = re.search(r"[\d.]+$", self.code[:end]).group(0)
            tail = re.match(r"[eE][+-]?\d+", self.code[end:]).group(0)
            self.fail(f"number with an exponent '{number}{tail}': G-code numbers have no exponent notation "
                      "(LinuxCNC: unknown operation name starting with e)", end,
                      "a plain decimal number such as 1000.0, or an operator (+ - * / ** MOD EQ AND ...) or ']'")
        sign = re.match(r"==|!=|<>|<=|>=|=<|=>|[=<>]", self.code[end:])
        if sign:
            self.comparison_sign(sign.group(0), end)
        word = re.match(r"[A-Za-z]\w*", self.code[end:])
        what = f"unknown operation '{word.group(0)}'" if word else f"unexpected '{self.code[end]}'"
        self.fail(f"{what} in an expression", end, "an operator (+ - * / ** MOD EQ NE GT LT AND OR XOR) or ']'")

    def comparison_sign(self, sign: str, at: int) -> NoReturn:
        """The error for a comparison written with a sign (``[#100 > 5]``, ``L[#1=1]``), as C and some PC
        controls' readers take it: LinuxCNC's relational operators are the two-letter EQ NE GT GE LT LE
        (g-code overview, "Binary Operators"; interp_read.cc read_operation knows no sign), and Fanuc's
        macro B writes them so (0i-MD operator's manual B-64304EN, "Custom macro", "Branch and repetition",
        the operator table: each operator "consists of two letters", and "the inequality sign cannot be
        used")."""
        name = {"=": "EQ", "==": "EQ", "!=": "NE", "<>": "NE", ">": "GT", ">=": "GE", "=>": "GE", "<": "LT",
                "<=": "LE", "=<": "LE"}[sign]
        self.fail(f"comparison written '{sign}' in an expression: G-code compares with the two-letter operators "
                  f"EQ NE GT GE LT LE ('{sign}' is {name}; LinuxCNC and Fanuc macro B read no sign)", at,
                  f"[a {name} b]")

    def abbreviated(self, short: str, p: int) -> tuple[float, int]:
        """The function Fanuc's abbreviation ``short`` (its first two characters) names, applied at ``p``."""
        names = [f for f in _FUNCTIONS if f.startswith(short)]
        if len(names) > 1:
            self.fail(f"{short}: an ambiguous abbreviation (of {' and '.join(names)})", p,
                      f"the function's full name ({' or '.join(names)})")
        if not names:
            self.fail(f"malformed value: {short!r} abbreviates no function", p,
                      "a function, by its name or its first two characters: " + ", ".join(_FUNCTIONS))
        return self.function(names[0], p, length=2)

    def function(self, name: str, p: int, *, length: int | None = None) -> tuple[float, int]:
        """``name[arg]`` at ``p``, the name written in ``length`` characters (all of them by default)."""
        q = self.skip(p + (len(name) if length is None else length))
        if q >= len(self.code) or self.code[q] != "[":
            self.fail(f"function {name} needs its argument in [ ]", p, f"{name}[value]")
        if name == "EXISTS":  # LinuxCNC read_parameter(check_exists): a number exists when 1 <= n < 5602
            q2 = self.skip(q + 1)
            if self.code[q2:q2 + 1] != "#":
                self.fail("EXISTS needs a parameter", p, "EXISTS[#<name>] or EXISTS[#n]")
            key, end = self.parameter(q2)
            end = self.skip(end)
            if self.code[end:end + 1] != "]":
                self.fail("EXISTS needs one parameter in [ ]", p, "EXISTS[#<name>] or EXISTS[#n]")
            found = self.params.exists(key) if isinstance(key, str) else 1 <= key < _LINUXCNC_PARAMETERS
            return (1.0 if found else 0.0), end + 1
        if name in ("ATAN", "POW") and self.params.fanuc:
            pair = self.pair(q)
            if pair is not None:
                return (self.binary("**", pair[0], pair[1], p) if name == "POW" else self.atan(pair[0], pair[1]),
                        pair[2])
            if name == "POW":
                self.fail("POW needs two arguments", p, "POW[a,b]")
        arg, end = self.real(q)
        if name == "ATAN":
            s = self.skip(end)
            if self.code[s:s + 1] != "/":
                self.fail("ATAN needs two arguments", p, "ATAN[y]/[x]" + (" or ATAN[y,x]" if self.params.fanuc else ""))
            x, end = self.real(s + 1)
            return self.atan(arg, x), end
        if name == "ROUND" and self.params.macro_b and self.address is not None:
            return self.address_round(arg, p), end
        if self.params.macro_b and name in ("FIX", "FUP"):  # Fanuc: on the absolute value, sign kept
            magnitude = math.floor(abs(arg)) if name == "FIX" else math.ceil(abs(arg))
            return math.copysign(float(magnitude), arg) if magnitude else 0.0, end
        try:
            return _apply(name, arg), end
        except (ValueError, OverflowError):
            self.fail(f"{name}[{arg:g}] is undefined", p, f"an argument in the domain of {name}")
        raise AssertionError("unreachable")

    def address_round(self, arg: float, p: int) -> float:
        """Macro B ``ROUND`` in an NC address (``G91 X-ROUND[#1]``): ``arg`` rounded to the address's least input
        increment (:func:`interpolators.iso_decimal.address_increment`), not to a whole number. Fanuc 30i/0i-F
        "Custom macro", "ROUND function": "When the ROUND function is used in NC statement addresses, the ROUND
        function rounds off the specified value according to the least input increment of the address" (the text as
        Machinery's Handbook 31st ed., "CNC subroutines and macros", gives it: ``#101 = 27/32``, ``G91 G00
        X[ROUND[#101]]`` moves 0.844 mm, where ``#101 = ROUND[27/32]`` is 1.0); Haas mill operator's manual 96-8000,
        "Macros", "Round": "When round is used in an address expression, 'Round' is rounded to the significant
        precision. For metric and angle dimensions, three-place precision is the default. For inch, four-place
        precision", its example ``#1 = 1.00333``, ``G0 X[ROUND[#1] + ROUND[#1]]`` moving to 2.0066. Half an
        increment rounds away from zero, as ROUND does. An address whose increment is not modelled (F, E) is an
        error naming it; the block's own checks (:func:`check_address_rounding`) follow the line."""
        letter = self.address or ""
        inch = self.params.inch() if self.params.inch is not None else False
        step = address_increment(letter, inch=inch)
        if step is None:
            self.fail(f"ROUND in address {letter}: Fanuc and Haas round it to the least input increment of the "
                      f"address, which vcnc does not model for {letter}", p,
                      f"{letter}[..] without ROUND, or ROUND in an assignment (#1 = ROUND[..]), which rounds to a "
                      "whole number")
        if self.rounded is None:
            self.rounded = (p + 1, letter)
        units = _apply("ROUND", arg / step)
        return round(units * step, 6) if step < 1.0 else units

    def pair(self, q: int) -> tuple[float, float, int] | None:
        """``[a,b]`` at ``q`` (the ``[``): a, b (vacant counts 0) and the end; None when no comma follows a."""
        a, end = self.expression(q + 1)
        end = self.skip(end)
        if self.code[end:end + 1] != ",":
            return None
        b, end = self.expression(end + 1)
        end = self.skip(end)
        if self.code[end:end + 1] != "]":
            self.unclosed(q, end)
        return (0.0 if a is None else a), (0.0 if b is None else b), end + 1

    def atan(self, y: float, x: float) -> float:
        """The angle [deg] of the point (x, y): -180 to 180, under :attr:`Parameters.fanuc` 0 to 360."""
        angle = math.degrees(math.atan2(y, x))
        return angle + 360.0 if self.params.fanuc and angle < 0 else angle

    def expression(self, pos: int, level: int = 0) -> tuple[float | None, int]:
        """Binary expression at precedence ``level`` (0: logic, lowest); ``None`` for a vacant operand alone.

        Read by precedence climbing: an operand, then each operator of ``level`` or higher with its right
        operand (the operators of higher levels after it bind first, those of the same level associate to the
        left): the same values, evaluated in the same order, as one recursive call per level."""
        left, p = self.operand(pos)
        return self._operations(left, p, level)

    def grouped(self, pos: int) -> tuple[float | None, int]:
        """The expression of a bracket (or of a condition or assignment) at ``pos``: in macro B precedence, and
        when it joins two comparisons (``#1 GT 0 AND #1 LT 9``) in LinuxCNC's, the comparisons first (module
        docstring), counted for a note."""
        if not self.params.macro_b:  # LinuxCNC's precedence already reads comparisons first
            return self.expression(pos)
        outer = self.logical
        self.logical = False
        try:
            return self.expression(pos)
        except _JoinedComparisons:
            self.logical = True
            value, end = self.expression(pos)
            self.params.joined_comparisons += 1
            return value, end
        finally:
            self.logical = outer

    def _operations(self, left: float | None, p: int, level: int) -> tuple[float | None, int]:
        """``left`` combined with the operators of precedence ``level`` or higher that follow at ``p``.

        Under macro B a second comparison in one bracket raises :class:`_JoinedComparisons`: Fanuc compares
        two values once ("[<expression> EQ <expression>]"), and its precedence would make
        ``[#1 EQ 1 AND #2 EQ 2]`` compare ``#1 EQ [1 AND #2]`` with 2, which no program means
        (:meth:`grouped` reads the bracket again)."""
        macro_b = self.params.macro_b and not self.logical
        table = _MACRO_B_OPERATORS if macro_b else _OPERATORS
        compared = False
        while True:
            q = self.skip(p)
            found = _operator_at(self.up, q, table)
            if found is None or found[1] < level:
                return left, p
            op, op_level = found
            if macro_b and op in _COMPARISONS:
                if compared:
                    raise _JoinedComparisons
                compared = True
            right, p = self.operand(q + len(op))
            right, p = self._operations(right, p, op_level + 1)
            divisor = self.code[q + len(op):p].strip()
            if op in ("/", "MOD") and not right and not _LITERAL.fullmatch(divisor):
                # name the divisor: its value came from elsewhere (a tool table, a call's argument, a loop)
                value = "vacant (counts 0)" if right is None else "0"
                self.fail(f"division by zero: the divisor {divisor!r} is {value}", q, "a divisor other than 0")
            left = self.binary(op, left, right, q)

    def binary(self, op: str, a: float | None, b: float | None, pos: int) -> float:
        if op in ("EQ", "NE") and (a is None or b is None):
            # Fanuc: vacant and 0 differ for EQ and NE only; vacant EQ vacant holds
            same = a is None and b is None
            return 1.0 if same == (op == "EQ") else 0.0
        a, b = (0.0 if a is None else a), (0.0 if b is None else b)  # vacant counts 0 in arithmetic
        if op in ("/", "MOD") and b == 0:
            self.fail("division by zero", pos, "a divisor other than 0")
        if self.params.macro_b and op in ("AND", "OR", "XOR"):  # bit by bit (module docstring)
            a_int, b_int = _integer_part(a), _integer_part(b)
            return float(a_int & b_int if op == "AND" else a_int | b_int if op == "OR" else a_int ^ b_int)
        try:
            return _binary(op, a, b)
        except (ValueError, OverflowError, ZeroDivisionError, TypeError):
            self.fail(f"{a:g} {op} {b:g} is undefined", pos, "a defined arithmetic result")
        raise AssertionError("unreachable")


_COMPARE = {"EQ": float.__eq__, "NE": float.__ne__, "GT": float.__gt__, "GE": float.__ge__, "LT": float.__lt__,
            "LE": float.__le__}


#: A number written as such (a divisor that needs no naming).
_LITERAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)")


def _operator_at(up: str, q: int, table: dict[str, tuple[tuple[str, int], ...]] = _OPERATORS
                 ) -> tuple[str, int] | None:
    """The binary operator at ``q`` of the upper-case line and its precedence level in ``table`` (LinuxCNC's by
    default), if one starts there."""
    for op, level in table.get(up[q:q + 1], ()):
        if up.startswith(op, q):
            return op, level
    return None


def _integer_part(x: float) -> int:
    """The integer part of ``x``, taken after rounding ``x`` to 9 decimals: a value that is a whole number
    within the precision of macro variables (Fanuc Power Mate i-D/H B-63174EN/03 "Custom macro": "the
    precision of variable values is about 8 decimal digits") is that number, so ``SIN[30] * 4``,
    1.9999999999999998 in binary floating point, is 2 for AND, OR and XOR."""
    return math.trunc(round(x, 9))


def _binary(op: str, a: float, b: float) -> float:
    a, b = float(a), float(b)
    if op == "**":
        return float(a ** b)
    if op == "*":
        return a * b
    if op == "/":
        return a / b
    if op == "MOD":  # LinuxCNC: fmod, made non-negative
        m = math.fmod(a, b)
        return m + abs(b) if m < 0 else m
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op in _COMPARE:
        return 1.0 if _COMPARE[op](a, b) else 0.0
    if op == "AND":
        return 1.0 if (a != 0 and b != 0) else 0.0
    if op == "OR":
        return 1.0 if (a != 0 or b != 0) else 0.0
    return 1.0 if (a != 0) != (b != 0) else 0.0  # XOR


def _apply(name: str, x: float) -> float:
    if name == "ABS":
        return abs(x)
    if name == "ACOS":
        return math.degrees(math.acos(x))
    if name == "ASIN":
        return math.degrees(math.asin(x))
    if name == "COS":
        return math.cos(math.radians(x))
    if name == "SIN":
        return math.sin(math.radians(x))
    if name == "TAN":
        return math.tan(math.radians(x))
    if name == "EXP":
        return math.exp(x)
    if name == "LN":
        return math.log(x)
    if name == "SQRT":
        return math.sqrt(x)
    if name == "FIX":
        return float(math.floor(x))
    if name == "FUP":
        return float(math.ceil(x))
    if name in ("BIN", "BCD"):  # Fanuc: binary-coded decimal to binary and back, whole numbers >= 0
        if x < 0 or x != int(x):
            raise ValueError(name)
        n = int(x)
        if name == "BCD":
            return float(int(str(n), 16))
        digits = f"{n:x}"
        if any(c not in "0123456789" for c in digits):
            raise ValueError(name)
        return float(int(digits))
    if name == "ROUND":
        return float(math.floor(x + 0.5)) if x >= 0 else -float(math.floor(-x + 0.5))
    raise ValueError(name)


def _too_deep(where: Where) -> NoReturn:
    """Thousands of nested brackets, signs or ``#``: the recursive reader ran out of stack (no program nests so)."""
    where.fail("expression nested deeper than this reader follows", text=where.text if len(where.text) < 60 else None,
               expected="an expression nested a few levels")
    raise AssertionError("unreachable")


def evaluate_at(code: str, pos: int, where: Where, params: Parameters) -> tuple[float, int]:
    """The real value (usually a ``[expression]``) starting at ``pos``; returns (value, end)."""
    try:
        return _Reader(code, where, params).real(pos)
    except RecursionError:
        _too_deep(where)


def evaluate_condition(code: str, pos: int, where: Where, params: Parameters) -> tuple[bool, int]:
    """A condition starting at ``pos`` (``[#1 EQ 2]``, also ``[a] AND [b]`` as macro B writes it):
    true when its value is not 0; a vacant value is false. Returns (truth, end)."""
    try:
        value, end = _Reader(code, where, params).grouped(pos)
    except RecursionError:
        _too_deep(where)
    return (value is not None and value != 0.0), end


#: Macro B addresses of whole numbers (tool, offsets, M code) that round a variable's or expression's value: Haas
#: mill operator's manual 96-8000, "Macros", "Round": "D[1.67] (Diameter 2 is made current)"; S. K. Sinha, "CNC
#: Programming Using Fanuc Custom Macro B" (McGraw-Hill 2010), "Real versus integer values": a real number "used in
#: place of integer numbers [is] automatically rounded", ``#1 = 3.5`` ``M#1`` is M04, "M3.0" written as a number
#: stays illegal, and so for all addresses but the G codes. S, P and L keep their values (a spindle speed with a
#: fraction is close enough; P and L are checked by the blocks that read them).
_WHOLE_ADDRESSES = frozenset("DHMT")
#: Addresses whose computed value is kept as it is: the feed and E (no increment modelled), the G code, N and O, and
#: S, P and L as above.
_KEPT_ADDRESSES = frozenset("EFGLNOPS")
_LITERAL_WORD = re.compile(r",?\s*[A-Za-z]\s*[+-]?\s*(?:\d+\.?\d*|\.\d+)")
#: G codes x 10 of blocks whose computed words keep their values: scaling factors (G51), the look-ahead switches
#: (G05, G05.1, G08), tool axis vectors (G43.4, G43.5), NURBS knots and weights (G06.2), macro calls (G65, G66).
_UNROUNDED_BLOCKS = frozenset({510, 50, 51, 80, 434, 435, 62, 650, 660, 661})


def address_values(words: list[Word], *, inch: bool) -> list[Word]:
    """The words of a macro B NC block (not a macro call's arguments: G65, G66, a G66.1 call) as Fanuc and Haas read
    a variable or expression in an address: rounded to the address's least input increment (``inch``: G20 in force
    before the block). Haas "Address substitution" (haascnc.com, mill macros): "When a variable or expression is used
    in place of an address value, the value is rounded to the least significant digit. If #1=.123456, then G01 X#1
    would move the machine tool to .1235 on the X axis. If the control is in the metric mode, the machine would be
    moved to .123"; Fanuc's "ROUND function" example (30i/0i-F "Custom macro"): with #1 = 1.2345 and #2 = 2.3456,
    ``G00 X[#1+#2]`` travels 3.580 (3.5801 rounded), not the 1.235 + 2.346 that ``G91 X-#1`` and ``X-#2`` moved.
    The distances and angles (:func:`interpolators.iso_decimal.address_increment`) go to 0.001 mm, 0.0001 in or
    0.001 deg (G68's R too: Haas 96-8000 "Round", "For metric and angle dimensions, three-place precision"); D, H,
    M and T to whole numbers (:data:`_WHOLE_ADDRESSES`); a number written out (``X1.23456``,
    ``H1.5``) stays as written, for the block's own checks, and so do the words of :data:`_UNROUNDED_BLOCKS`."""
    codes = {round(w.value * 10) for w in words if w.letter == "G"}
    if codes & _UNROUNDED_BLOCKS:
        return words
    inch = 200 in codes or inch and 210 not in codes
    out = words
    for i, w in enumerate(words):
        letter = "A" if w.letter == "R" and 680 in codes else w.letter  # G68's R is an angle: 0.001 deg in inch too
        step = (1.0 if letter in _WHOLE_ADDRESSES else None if letter in _KEPT_ADDRESSES
                else address_increment(letter, inch=inch))
        if step is None or _LITERAL_WORD.fullmatch(w.text):
            continue
        units = _apply("ROUND", w.value / step)
        value = units if step == 1.0 else round(units * step, 6)
        if value != w.value:
            out = list(out) if out is words else out
            out[i] = dataclasses.replace(w, value=value)
    return out


#: G codes x 10 whose blocks a ROUND in an address is refused in: the macro calls, whose argument addresses the
#: manuals give no increment for a ROUND (G65, G66, G66.1), and the unit changes (G20, G21), which set the increment
#: of the block they are in.
_ROUND_REFUSED = {650: "a macro call's argument (the manuals give its ROUND no increment)",
                  660: "a macro call's argument (the manuals give its ROUND no increment)",
                  661: "a macro call's argument (the manuals give its ROUND no increment)",
                  200: "a block that changes the unit (the increment is the new unit's)",
                  210: "a block that changes the unit (the increment is the new unit's)"}


def check_address_rounding(words: list[Word], rounded: tuple[int, str], where: Where, params: Parameters) -> None:
    """Refuse a macro B ``ROUND`` in an address (:meth:`_Reader.address_round`) where its increment is not the one
    the reader took: in a macro call's arguments (our reading: no manual says what increment their ROUND takes) or
    in a G20/G21 block that changes the unit."""
    column, letter = rounded
    inch = params.inch() if params.inch is not None else False
    for w in words:
        code = round(w.value * 10) if w.letter == "G" else None
        if code in _ROUND_REFUSED and (code not in (200, 210) or (code == 200) != inch):
            where.fail(f"ROUND in address {letter} of {_ROUND_REFUSED[code]}: not modelled", column=column,
                       text=f"{letter}[ROUND[..]]", expected="the value rounded in an assignment before the block "
                       "(#1 = ROUND[#1 * 1000] / 1000)")


def read_line(code: str, where: Where, params: Parameters) -> list[Word]:
    """Words of a comment-free line whose values may be parameters or expressions.

    Parameter assignments on the line are applied after all its values are read (LinuxCNC). A
    word whose value is a vacant parameter alone (Fanuc: ``X#1`` with ``#1`` vacant) is left out.
    """
    r = _Reader(code, where, params)
    assignments: list[tuple[int | str, float | None, int, str]] = []

    def assign(i: int) -> int:
        key, end = r.parameter(i)
        eq = r.skip(end)
        if code[eq:eq + 1] != "=":
            r.fail("a parameter outside a word must be assigned", i, "#n = value")
        if params.macro_b:
            value, end = params.held_value(key, lambda: r.grouped(eq + 1))  # "#1=#2+#3" needs no brackets
        else:
            # LinuxCNC overview.adoc "Parameter Setting": "# , a real value ..., an equal sign = , and a real
            # value"; a real value is "a number, an expression, a parameter value, or a unary function value",
            # and an expression is enclosed in [ ]: rs274 refuses "#<a> = #<a> + 2" ("Bad character '+' used").
            # Read as macro B does, and counted for a note.
            value, end = r.operand(eq + 1)
            if _operator_at(r.up, r.skip(end)) is not None:
                params.unbracketed += 1
                value, end = r.expression(eq + 1)
        assignments.append((key, value, i + 1, code[i:end].strip()))
        return end

    def address_value(pos: int, letter: str) -> tuple[float | None, int]:
        r.address = letter
        try:
            return r.operand(pos)
        finally:
            r.address = None

    try:
        words = read_words(code, where, value=address_value, assignment=assign)
    except RecursionError:
        _too_deep(where)
    if r.rounded is not None:
        check_address_rounding(words, r.rounded, where, params)
    for key, value, column, text in assignments:
        params.assign(key, value, where, column, text)
    return words
