"""An independent reference for where the blocks of a Heidenhain conversational program end.

Test code only: it imports nothing of the readers (``interpolators.heidenhain*``), only the
machine context's tables. Written from the HEIDENHAIN TNC conversational user's manuals
(TNC 320/370/426/640, iTNC 530; e.g. https://www.easymanua.ls/heidenhain/tnc-370/manual?p=195
for cycle 1, TNC 426B "Miscellaneous functions for coordinate data" for M91/M92):

- Blocks: a leading block number, ``;`` comments, ``*`` structure blocks, ``~`` continuation
  lines (the block is reported at its first line), ``BEGIN PGM name MM|INCH``, ``END PGM``; a
  comma between two digits is a decimal point (``X+50,022``: programs saved by TNCs set to the
  decimal comma, as HEIDENHAIN's demonstration programs 668, 700, 7025 are).
- Machine position = program position + preset (``context.offset("G54")``) + the datum shift of
  ``CYCL DEF 7`` + the tool length along Z (``TOOL CALL n``: the length of ``TOOL DEF n`` in the
  program, else the tool table's, plus ``DL``). The length applies from the next move (the tool
  does not move at the TOOL CALL; an axis not named keeps its machine position).
- ``M91``: the block's coordinates are machine coordinates, and the tool length is not
  compensated (TNC 426B manual: "The tool length, however, is not compensated"); ``M92``:
  relative to the machine-defined position (here ``context.home``). ``L M140 MB MAX``: retract
  along the tool axis to the limit (here ``context.home``'s Z; no motion when the tool is above it).
- Paths: ``L`` (``I`` words incremental, ``FMAX``/``F MAX`` rapid), ``CC`` (pole; a missing or
  ``I`` coordinate from the current position), ``C`` about CC (``DR+`` counter-clockwise; a Z word:
  helix), ``CP IPA`` (polar arc from the current angle about the pole, radius = distance to the
  pole), ``APPR LT``/``DEP LT`` (straight approach tangential to the first element, ``LEN`` before
  it; straight departure ``LEN`` along the last element; the polar ``APPR P..``/``DEP PLCT``: the point by PR,
  PA; a DEP ends RL/RR unless it writes them), ``CR`` (radius arc: R > 0 under 180 degrees), ``CT`` (the arc
  leaving along the last element's direction), ``RND R`` (the arc tangent to the two lines, r tan(theta/2)
  from the corner) and ``CHF`` (the chamfer side length on each line); ``TOOL DEF n`` alone pre-selects.
- Q parameters (``Q``, ``QL``: a called program's own, ``QR``): ``FN 0``-``FN 8`` and ``FN 13`` (``SQRT``,
  ``SIN``, ``COS``, ``LEN``, ``ANG``), formulas
  with ``+ - * / ^``, parentheses and the functions ``SQ SQRT SIN COS TAN ASIN ACOS ATAN ABS INT NEG FRAC
  LN LOG EXP``; ``FN 9``-``FN 12`` (``EQU NE GT LT``) jumps; ``FN 18 SYSREAD ID270 NR1 IDXn`` (position
  in the active system), ``ID240 NR1 IDXn`` (position in the machine system), ``ID20 NR1 .. NR4`` (active and
  prepared tool, tool axis, spindle speed) and ``ID10 NR1`` (inch); ``FN 15 PRINT`` and ``FN 16
  F-PRINT`` have no effect; ``FN 17 SYSWRITE ID50 NR1/NR2 IDXt`` sets tool t's length / radius as a
  ``TOOL DEF`` (other system data: no effect).
- Labels: ``CALL LBL n REP k`` (``REPQ13``: k in a Q parameter): the section from ``LBL n`` repeated k
  times (then the counter is reset); of a label after the call, the subprogram run k + 1 times (the
  reader's reading, no manual found); ``CALL LBL n``: a subprogram up to ``LBL 0``; the main program
  ends at ``M2``/``M30``/``END PGM``.
- Cycles: ``CYCL DEF 7`` (datum shift, ``I`` values add), ``9`` (dwell, runs at once), ``32``
  (tolerance, no motion), ``1`` PECKING (from the current position: feed to each plunging depth
  below the surface (start + set-up clearance toward the depth), rapid back to the start, rapid
  to the previous depth less the advanced stop distance ``t`` (0.6 mm up to 30 mm of depth, else
  depth/50, at most 7 mm), at the bottom dwell and rapid to the start) and ``200`` DRILLING (rapid to
  Q203 + Q200, feed per Q202 to Q203 + Q201, between pecks rapid to Q203 + Q200 and back to Q200
  above the last depth, dwell Q211 at the bottom, rapid to Q203 + Q200 and then to Q203 + Q204),
  called by ``M99`` or ``CYCL CALL`` at the current position; ``203``/``205`` (pecks shrinking by
  Q212 to Q205, 203's Q213 chip breaks, 205's chip breaks every Q257 and re-entry Q258 above the last
  depth), ``262`` THREAD MILLING (half circle in from the centre on +X, the helix, half circle back) and
  ``252`` CIRCULAR POCKET (circles Q370 x R apart at each depth, wall and floor finishing), ``251``
  RECTANGULAR POCKET (the same with rounded rectangles turned by Q224) and ``256`` RECTANGULAR STUD
  (revolutions from the blank in to the stud, half circles on and off); the old ``5`` CIRCULAR POCKET
  as 252's roughing and ``4`` POCKET MILLING as 251's (turned 90 degrees when 4.5 is the longer side)
  from the starting position (surface: the set-up clearance beyond it; K = 1).
- ``DEP CT`` under RL/RR: the tool runs the arc compensated and stops beside PN, square to the arc.
- RL/RR contours the tool cannot follow are refused (:func:`_tool_path_corner`: at an inside corner the tool
  centre paths' intersection, iTNC 530 user's manual 60642x-04, "Radius compensation: Machining corners"; an
  element it consumes, or an arc curving toward the tool no larger than it), and so is an RND whose circle touches
  no point of an element as programmed (:func:`_fillet`).
- ``FUNCTION FEED DWELL D-TIME d F-TIME f`` (TNC 640 user's manual, "Cyclic dwell time"; our reading of what
  counts): the feed time of the path's lines and arcs at the modal F, across blocks; where it reaches f the element is
  cut and the tool dwells d (:func:`_feed_dwell_line`, :func:`_feed_dwell_arc`); other feed moves under it unmodelled.
- FK free contour programming (``FPOL``, ``FL``, ``FLT``, ``FC``, ``FCT``, ``FSELECT``, iTNC 530 manual section
  6.6): each element's data as equations solved numerically (:mod:`reference_heidenhain_fk`).
- ``TCH PROBE 400 / 408 - 413 / 417 / 419 - 424 / 427 / 431`` on the nominal workpiece (TNC 320 cycle manual 340
  55x-04, "Executing touch probe cycles", the cycles' sections; :func:`_touch_probe`): the touch points where the data
  put the surface, the datum moved so the probed centre / coordinate gets Q331/Q332 / Q405 / Q333 (Q305=0), or row
  Q305 of the presets; the results (measured = nominal, deviations 0, Q180 = 1).
- ``CYCL DEF 14`` (the contour's first label) or ``CONTOUR DEF`` (its subcontours by number, the islands ``In``
  apart, :func:`_contour_def`), ``CYCL DEF 25`` CONTOUR TRAIN (:func:`_contour_train`),
  ``CYCL DEF 20`` + ``22`` ROUGH-OUT of one pocket of straight edges (:func:`_rough_out`).
"""

from __future__ import annotations

import cmath
import copy
import dataclasses
import math
import re
from collections.abc import Callable

import numpy as np

from tests.interpolators.reference_heidenhain_fk import FkReference
from tests.interpolators.reference_iso import Expected, ReferenceError, turns_within, wrapped_end
from tests.interpolators.reference_match import match_blocks, reader_rows

__all__ = ["heidenhain_reference"]

_EPS = 1e-9


#: The items of PATTERN DEF (TNC 640 cycle programming manual, "PATTERN DEF": POS, ROW, CIRC, PITCHCIRC, PAT, FRAME),
#: a line of their own after it without a number or ``~`` as older TNCs save them.
_PATTERN_ITEM = r"(POS|ROW|PITCHCIRC|CIRC|PAT|FRAME)\d+\s*\("


def _blocks(text: str) -> list[tuple[int, str]]:
    """(first line, text) of each block: comments removed, continuations joined (``~``; and the
    un-numbered ``Qnnn=`` lines after ``CYCL DEF 2xx`` or ``TCH PROBE 4xx``, ``POSn (`` / ``PAT1 (`` .. lines after
    ``PATTERN DEF``, as older TNCs save them), numbers and the block skip mark ``/`` dropped."""
    out, buf, first = [], [], None
    in_comment = False  # the previous line of this block ended in "~" inside a ";" comment
    for no, raw in enumerate(text.lstrip("\ufeff").split("\n"), start=1):  # a lone CR is no line end
        cont = raw.rstrip().endswith("~")
        if first is not None and in_comment and not re.match(r"\s*(Q\d+\s*=|" + _PATTERN_ITEM + ")", raw):
            code = ""  # a long comment wrapped over lines ending in "~": still comment
        else:
            in_comment = ";" in raw
            code = raw.split(";", 1)[0].strip().rstrip("~").strip()
            if '"' not in code:  # a decimal comma (quoted strings are left alone: no comma is touched)
                code = re.sub(r"(\d),(\d)", r"\1.\2", code)
        if first is None and out and (
                (re.match(r"(CYCLE? DEF\s*2|TCH PROBE\s*4)\d\d\b", out[-1][1]) and re.match(r"Q\d+\s*=", code))
                or (out[-1][1].startswith("PATTERN DEF") and re.match(_PATTERN_ITEM, code))):
            out[-1] = (out[-1][0], out[-1][1] + " " + code)
            continue
        if first is None:
            first = no
            code = re.sub(r"^/?\s*\d+\s*(/\s*)?", "", code).lstrip("/").strip()  # "/" block skip: off, it runs
        buf.append(code)
        if not cont:
            out.append((first, " ".join(b for b in buf if b).strip()))
            buf, first, in_comment = [], None, False
    return [(no, b) for no, b in out if b and not b.startswith("*")]


class _Formula:
    """Recursive-descent Heidenhain formula: + - * / % ^, parentheses, unary functions, Q values (``%``: the
    division remainder, iTNC 530 user's manual 60642x-04 9.8, "Q12 = 400 % 360 Result: Q12 = 40"; as * and /, the
    dividend's sign)."""

    _FUNCS = {"SQRT": math.sqrt, "SQ": lambda v: v * v, "SIN": lambda v: math.sin(math.radians(v)),
              "COS": lambda v: math.cos(math.radians(v)), "TAN": lambda v: math.tan(math.radians(v)),
              "ASIN": lambda v: math.degrees(math.asin(v)), "ACOS": lambda v: math.degrees(math.acos(v)),
              "ATAN": lambda v: math.degrees(math.atan(v)), "ABS": abs, "INT": lambda v: float(math.trunc(v)),
              "NEG": lambda v: -v, "FRAC": lambda v: v - math.trunc(v), "LN": math.log, "LOG": math.log10,
              "EXP": math.exp, "SGN": lambda v: 1.0 if v >= 0 else -1.0}  # SGN: TNC 620 manual, 1 for >= 0

    def __init__(self, text: str, q: dict):
        self.toks = re.findall(r"\d+\.?\d*|\.\d+|Q[LR]?\d+|[A-Z]+|[-+*/%^()]", text.upper())
        self.i = 0
        self.q = q

    def value(self) -> float:
        v = self.expr()
        if self.i != len(self.toks):
            raise ReferenceError(f"formula: unexpected {self.toks[self.i:]}")
        return v

    def peek(self) -> str | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def take(self) -> str:
        self.i += 1
        return self.toks[self.i - 1]

    def expr(self) -> float:
        v = self.term()
        while self.peek() in ("+", "-"):
            v = v + self.term() if self.take() == "+" else v - self.term()
        return v

    def term(self) -> float:
        v = self.power()
        while self.peek() in ("*", "/", "%"):
            op = self.take()
            v = v * self.power() if op == "*" else v / self.power() if op == "/" else math.fmod(v, self.power())
        return v

    def power(self) -> float:
        v = self.unary()
        if self.peek() == "^":
            self.take()
            return v ** self.power()
        return v

    def unary(self) -> float:
        t = self.take()
        if t in ("+", "-"):
            v = self.unary()
            return -v if t == "-" else v
        if t == "(":
            v = self.expr()
            self.take()
            return v
        if t in self._FUNCS:
            return float(self._FUNCS[t](self.unary()))
        if t == "PI":
            return math.pi
        if t.startswith("Q"):
            return self.q.get(t, 0.0)
        return float(t)


def _val(text: str, q: dict) -> float:
    """A word value: a number or a Q parameter, with sign (``+Q11``, ``-Q5``, ``-2.5``)."""
    return _Formula(text, q).value()


#: ``R0`` is the compensation word only when no number follows it: ``RND R0.5``, ``CR .. R0.5`` (``R0,5`` as a TNC set
#: to the decimal comma saves it) are radii of 0.5 mm (tncwild40: a compensator maker's ``RND R0,5 F``).
_WORD = re.compile(r"(IPA|PA|IPR|PR|LEN|CCA|DR|FMAX|MB|[NT][XYZ]|I?[XYZ]|I?[ABCUVW]|R[LR]|R0(?![\d.])|R|FU|F|M)"
                   r"([-+]?(?:Q[LR]?\d+|\d+\.?\d*|\.\d+|MAX|AUTO)?)")


#: M functions with parameters after them (TNC 640 / TNC 426 user's manuals): M94 [axis], M103 F.., M112 T.. A..,
#: M118 X.. Y.., M120 LA.., M124 T.., M138 [axes]; their words are M's, not the block's.
_M_WITH_WORDS = re.compile(r"\bM(94|138)((?:\s+[ABC](?![\w+.-]))*)"
                           r"|\bM(103|112|118|120|124)((?:\s*(?:LA|[FTAEHXYZABCUVW])\s*[-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))*)"
                           r"|\bM(128)(\s*F\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))",
                           re.I)


def _m_words(rest: str, q: dict) -> tuple[str, dict[int, dict[str, float | None]]]:
    """``rest`` with the parameters of M94/M103/M112/M118/M120/M124/M138 and the F of M128 (the feed of its
    compensation movements, TNC 640 manual, M128) removed, and those by M number."""
    found: dict[int, dict[str, float | None]] = {}

    def take(mm: re.Match) -> str:
        number = int(mm.group(1) or mm.group(3) or mm.group(5))
        words = mm.group(2) if mm.group(1) else mm.group(4) if mm.group(3) else mm.group(6)
        if number in (94, 138):  # axis letters alone
            found[number] = {a.upper(): None for a in re.findall(r"[ABC]", words or "", re.I)}
        else:
            pairs = re.findall(r"(LA|[FTAEHXYZABCUVW])\s*([-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", words or "", re.I)
            found[number] = {k.upper(): _val(v.replace(" ", ""), q) for k, v in pairs}
        return f"M{number}"

    return _M_WITH_WORDS.sub(take, rest), found


def _words(rest: str, q: dict) -> dict[str, float | str]:
    rest, margs = _m_words(rest, q)
    # R, F, M standing alone: a field the older TNCs saved empty ("L X+1 R F M"): nothing programmed
    s = re.sub(r"\s+", "", re.sub(r"(?<!\S)[RFM](?=\s*$|\s+(?!MAX|AUTO)[A-PR-Z])", " ", rest.upper()))
    out: dict[str, float | str] = {}
    pos, last = 0, None
    for m in _WORD.finditer(s):
        if m.start() != pos:
            raise ReferenceError(f"unread text {s[pos:m.start()]!r}")
        pos = m.end()
        key, v = m.group(1), m.group(2)
        key, last = ("MBF" if key in ("F", "FMAX") and last == "MB" else key), key  # M140 MB .. F: its own feed
        if key == "MBF":
            out[key] = "MAX" if m.group(1) == "FMAX" else _val(v, q)
        elif key == "M":
            out.setdefault("M", [])
            out["M"].append(int(v))
        elif key in ("DR", "RL", "RR", "R0", "FMAX") or v in ("", "+", "-", "MAX", "AUTO"):  # F AUTO: a feed
            out[key] = v
        else:
            out[key] = _val(v, q)
    if pos != len(s):
        raise ReferenceError(f"unread text {s[pos:]!r}")
    if margs:
        out["MARGS"] = margs
    return out


class _Tnc:
    """Machine state: positions in machine coordinates [mm]."""

    def __init__(self, context):
        self.ctx = context
        self.datum_rows = dict(context.datum_table)  # the datum table, with the rows probing wrote (Q303=0)
        self.pos = np.array(context.home, float)
        self.scale = 1.0
        self.shift = np.zeros(3)
        self.length = 0.0
        self.radius = 0.0
        self.delta = 0.0
        self.auto: float | None = None  # F of the last TOOL CALL
        self.extra = np.zeros(6)  # A, B, C [deg], U, V, W [mm]: machine positions (their preset is 0)
        self.shown = np.zeros(3)  # M94: machine angle minus displayed angle of A, B, C [deg]
        self.m126 = False  # M126 (until M127): the shorter way on the rotary axes that wrap at 360 deg
        self.strings: dict[int, str] = {}  # QS parameters
        self.comp = False
        self.side = 1.0  # +1 RL, -1 RR
        self.entry = False
        self.tool_defs: dict[int, tuple[float, float]] = {}
        self.tool = 0  # the active tool number (FN 18 ID20 NR1)
        self.prepared = 0  # the tool a TOOL DEF n alone pre-selected (FN 18 ID20 NR2)
        self.speed = 0.0  # S of the last TOOL CALL [rpm] (FN 18 ID20 NR4)
        self.pole = np.zeros(3)  # program coordinates [mm]
        self.pole_axes = (0, 1)  # the circle's plane (reference axis, second axis): XY, or ZX / YZ after CC X Z / Y Z
        self.q: dict[str, float] = {}
        self.cycle: tuple | None = None
        self.out: list[Expected] = []
        self.last_dir: np.ndarray | None = None
        self.last_len = math.inf  # length of the last line in the plane [mm] (what an RND after it may take)
        self.rounding: tuple | None = None  # RND R / CHF waiting for the next element: (kind, size, line, row)
        self.last_start = self.pos.copy()  # where the last move in the plane began (the element an RND trims)
        self.last_ccw = False  # that move was a counter-clockwise arc
        # the last element of the RL/RR run ((start, end, centre, ccw) in the plane) and where its tool centre path
        # begins on it (:func:`_along`), for the inside corners the tool must reach (:func:`_tool_path_corner`)
        self.run: tuple | None = None
        self.modal = False  # M89 active
        self.feed = 0.0  # the modal path feed [mm/min], for FUNCTION FEED DWELL
        self.feed_dwell: tuple[float, float] | None = None  # FUNCTION FEED DWELL: (D-TIME, F-TIME) [s]
        self.cutting = 0.0  # FUNCTION FEED DWELL: the feed time since the last dwell [s]
        self.plunging = False  # M103 F.. active (a reduced plunging feed)
        self.preset = "G54"  # cycle 247: preset n = the n-th work offset G54 .. G59.3 (0: G54; > 9: None, zero)
        self.pattern: list[dict] = []  # PATTERN DEF positions
        self.overrides: dict = {}  # presets a touch probe cycle set: work offset -> machine point [mm]
        self.resolve = None  # name -> text of a called program
        self.mirror = np.ones(3)  # cycle 8: -1 on a mirrored axis
        self.rot = 0.0  # cycle 10 [deg]
        self.scl = 1.0  # cycle 11
        self.factors = np.ones(3)  # cycle 26
        self.centre = np.zeros(3)  # cycle 26 [mm]
        self.program: tuple | None = None  # the running program's (blocks, labels)
        self.contour = ""  # cycle 14: the contour's first label
        self.contours: tuple[str, ...] = ()  # cycle 14: all its labels
        self.islands: set[str] = set()  # CONTOUR DEF: the labels written as islands In
        self.loose = 0.0  # after an SL region cycle: how far the tool's plane position may be from self.pos [mm]
        self.data: dict = {}  # cycle 20's Q1 .. Q9
        self.tilt: np.ndarray | None = None  # PLANE / cycle 19: the working plane's rotation (columns X, Y, Z)
        self.tilt_angles: dict[str, float] = {}  # the rotary positions the plane needs [deg]
        self.base = np.zeros(3)  # the datum shift when the plane was tilted (untilted coordinates) [mm]
        self.shifted = False  # cycle 7 programmed in the tilted plane: its values stand after the reset
        self.tcpm = False  # M128: program points are the tool tip on the part, carried where the table holds it
        self.spat: np.ndarray | None = None  # FUNCTION TCPM .. AXIS SPAT: the spatial angles A, B, C last written
        self.fk = FkReference()  # FK free contour programming (reference_heidenhain_fk)
        self.fk_end = -1  # len(self.out) after the last FK element: the last motion was FK while it is so
        self.raw: list[str] = []  # the running program's lines (FK relative data name block numbers)

    def preset_point(self) -> np.ndarray:
        if self.preset in self.overrides:  # written by a touch probe cycle
            return self.overrides[self.preset].copy()
        return np.array(self.ctx.offset(self.preset), float) if self.preset else np.zeros(3)

    def turned(self) -> bool:
        """A tilted plane that turns the workpiece coordinates (its rotation or its rotary positions not 0)."""
        if self.tilt is None:
            return False
        return (not np.allclose(self.tilt, np.eye(3))
                or any(abs(math.remainder(v, 360.0)) > 1e-9 for v in self.tilt_angles.values()))

    def tip(self) -> bool:
        """M128 acting on the points: on, and no plane that turns (in one, a line whose rotary axes stay is the
        plane's line with or without TCPM, TNC 640 manual "Inclined-tool machining in a tilted plane")."""
        return self.tcpm and not self.turned()

    def origin(self) -> np.ndarray:
        if self.tilt is not None and not self.tip():  # the tilted zero on the tilted table (cycle 7 shifts within
            return self.machine(np.zeros(3))     # the plane)
        # under M128 in a plane that does not turn (_tcpm_switch): its zero on the part, as the untilted one
        o = self.preset_point() + (self.base + self.tilt @ self.shift if self.tilt is not None else self.shift)
        o[2] += self.length
        return o

    def affine(self) -> tuple[np.ndarray, np.ndarray]:
        """``machine = origin + A @ p + b`` for a program point p: the axes mirrored after the
        rotation, the rotation after the scaling (cycles 8, 10, 11, 26 in their numbering order)."""
        c, s = math.cos(math.radians(self.rot)), math.sin(math.radians(self.rot))
        outer = np.diag(self.mirror) @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        return outer @ np.diag(self.scl * self.factors), outer @ (self.scl * (1.0 - self.factors) * self.centre)

    def table_angles(self) -> dict[str, float]:
        """The rotary axes' present positions [deg], by name."""
        return {ax.name: self.extra["ABC".index(ax.name.upper())] for ax in self.ctx.kinematics.axes}

    def machine(self, p: np.ndarray) -> np.ndarray:
        a, b = self.affine()
        if self.tip():  # M128 on a table: the part point (rotary axes at 0) where the table carries it now
            length = np.array([0.0, 0.0, self.length])
            return _carry(self, self.origin() + a @ p + b - length, self.table_angles()) + length
        if self.tilt is not None:  # the part point, then where the tilted table carries it
            part = self.preset_point() + self.base + self.tilt @ (self.shift + a @ p + b)
            return _carry(self, part, self.tilt_angles) + np.array([0.0, 0.0, self.length])
        return self.origin() + a @ p + b

    def prog(self) -> np.ndarray:
        a, b = self.affine()
        if self.tip():
            length = np.array([0.0, 0.0, self.length])
            part = _carry(self, self.pos - length, self.table_angles(), back=True) + length
            return np.linalg.solve(a, part - self.origin() - b)
        if self.tilt is not None:
            part = _carry(self, self.pos - np.array([0.0, 0.0, self.length]), self.tilt_angles, back=True)
            q = self.tilt.T @ (part - self.preset_point() - self.base) - self.shift
            return np.linalg.solve(a, q - b)
        return np.linalg.solve(a, self.pos - self.origin() - b)

    def turns_over(self) -> bool:
        """True when the plane's sense of rotation is reversed (one of X, Y mirrored)."""
        return self.mirror[0] * self.mirror[1] < 0

    def emit(self, line: int, kind: str, end: np.ndarray, *, rows: str = "one", centre=None, plane=(0, 1),
             extra: np.ndarray | None = None) -> None:
        if self.feed_dwell is not None and kind not in ("rapid", "dwell"):
            raise ReferenceError("a feed move under FUNCTION FEED DWELL other than a line L (an arc, a cycle's)")
        if self.rounding is not None and kind != "dwell":
            _corner(self, end, centre, kind == "arc_ccw")
        start = self.pos.copy()
        if self.comp and self.radius > 0 and kind != "dwell":
            # an arc whose written end lies off its circle by a rounding (Y+62.679 for 62.6795): that much slack
            rs, re_ = (float(np.hypot(*(p - centre)[:2])) for p in (start, end)) if centre is not None else (0, 0)
            element = ("line", start, end.copy()) if centre is None else \
                ("arc", centre, re_, (0, 1), start, abs(rs - re_))
            _tool_path_corner(self, start, end, centre, kind)
            self.out.append(Expected(line=line, kind=None, end=end.copy(), tolerance=self.radius, rows="last",
                                     element=element, entry=self.entry))
            self.entry = False
        else:
            self.run = None
            slack, loose = 0.0, 0.0
            if self.loose and np.any(end[:2] == start[:2]):  # X or Y kept from the SL cycle's unknown end
                loose = self.loose
            self.loose = 0.0 if not loose else self.loose
            if centre is not None:
                ax = list(plane)
                rs, re_ = (float(np.hypot(*(p - centre)[ax])) for p in (start, end))
                chord = float(np.hypot(*(end - start)[ax]))
                slack = 2 * abs(rs - re_) * max(rs, re_) / chord if chord > 0 else 0.0
            self.out.append(Expected(line=line, kind=kind, end=end.copy(), rows=rows, centre=centre, tolerance=loose,
                                     centre_tolerance=1e-6 + slack, plane=plane, extra=extra))
        if kind != "dwell" and np.linalg.norm((end - start)[:2]) > 0:
            d = np.array([*(end - start)[:2], 0.0])
            self.last_dir = None if centre is not None else d / np.linalg.norm(d)
            self.last_len = math.inf if centre is not None else float(np.linalg.norm(d))
            self.last_start, self.last_ccw = start, kind == "arc_ccw"
        self.pos = end.copy()

    def target(self, w: dict, base: np.ndarray | None = None) -> np.ndarray:
        """Machine end point of the axis words (M91/M92 and I words); ``base``: the program point the words
        change (default: the present one)."""
        ms = w.get("M", [])
        untilted = 130 in ms and self.tilt is not None  # M130 (TNC 640 manual): the untilted coordinates,
        if untilted and (self.comp or self.tcpm or self.rot or self.scl != 1.0  # preset + shift before the tilt
                         or np.any(self.mirror != 1.0) or np.any(self.factors != 1.0)):
            raise ReferenceError("M130 with RL/RR, M128 or a transformation")
        if 91 in ms or 92 in ms or untilted:
            base = (np.zeros(3) if 91 in ms else np.array(self.ctx.home, float) if 92 in ms
                    else self.preset_point() + self.base + np.array([0.0, 0.0, self.length]))
            end = self.pos.copy()
            for i, a in enumerate("XYZ"):
                if a in w:
                    end[i] = base[i] + w[a] * self.scale
                if "I" + a in w and untilted:
                    end[i] += w["I" + a] * self.scale
            return end
        p = self.prog() if base is None else base.copy()
        for i, a in enumerate("XYZ"):
            if a in w:
                p[i] = w[a] * self.scale
            if "I" + a in w:
                p[i] += w["I" + a] * self.scale
        return self.machine(p)


def _comp_words(t: _Tnc, w: dict) -> None:
    if "RL" in w or "RR" in w:
        t.side = 1.0 if "RL" in w else -1.0
        t.entry = not t.comp
        t.comp = True
    elif "R0" in w:
        t.comp = False


def _line_block(t: _Tnc, line: int, w: dict) -> None:
    """``L``: a line (rapid with FMAX), M140 MB MAX retract, M99 cycle call."""
    _comp_words(t, w)
    _tcpm_switch(t, [v for v in w.get("M", []) if v != 129])  # M129 at the block's end (TNC 426/430 manual, M128)
    axes = any(k in w for k in ("X", "Y", "Z", "IX", "IY", "IZ"))
    # the rotary / secondary axes the machine has: absolute machine positions (A B C [deg], U V W in the
    # program's unit), I words incremental; others of value 0 are ignored
    others = [k for k in w if re.fullmatch(r"I?[ABCUVW]", k) and k[-1].lower() in t.ctx.extra_axes]
    spat = t.tcpm and t.spat is not None and any(re.fullmatch(r"I?[ABCUVW]", k) for k in w)
    _reduce_display(t, w.get("MARGS", {}))
    # M128 with the rotary axes moving: the tip's program point from where it is before they turn, carried to
    # where the table holds it at their new positions; the reader's chords, the last one's end checked
    base = t.prog() if t.tip() and (spat or any(k[-1] in "ABC" for k in others)) else None
    if spat and t.turned():
        raise ReferenceError("AXIS SPAT angles under M128 in a tilted plane that turns")
    if spat:
        others = [k for k in w if re.fullmatch(r"I?[ABCUVW]", k)]
        _spatial_angles(t, w)
    if t.ctx.wrapped_axes and {126, 127} & set(w.get("M", [])):  # TNC 640 manual, M126: from its block's start
        t.m126 = 126 in w["M"]
    now = t.extra.copy()
    for k in [] if spat else others:
        i = "ABCUVW".index(k[-1])
        v = w[k] * (1.0 if i < 3 else t.scale)
        t.extra[i] = t.extra[i] + v if k[0] == "I" else v + (t.shown[i] if i < 3 else 0.0)
        if k[0] != "I" and i < 3 and k.lower() in t.ctx.wrapped_axes:  # a modulo axis (TNC 640 manual, M126)
            t.extra[i] = wrapped_end(_rule(t), v, now[i], t.shown[i])
    if t.tcpm and t.turned() and np.any(np.abs(t.extra[:3] - now[:3]) > 1e-9):
        raise ReferenceError("a rotary axis moving under M128 in a tilted plane that turns")
    kind = "rapid" if "FMAX" in w else "feed"
    if t.feed_dwell is not None and kind == "feed" and (axes or others):
        _feed_dwell_line(t, line, t.target(w), bool(others))
    elif axes or others:
        t.emit(line, kind, t.target(w, base), extra=t.extra.copy() if others else None,
               rows="one" if base is None else "last")
    elif "MB" not in w and 99 in w.get("M", []):
        t.out.append(Expected(line=line, kind=None, end=t.pos.copy(), rows="optional"))
    ms = w.get("M", [])
    t.modal = (t.modal or 89 in ms) and 99 not in ms  # M89: modal cycle call, ended by M99 / CYCL CALL
    if 99 in ms or (t.modal and axes):
        _run_cycle(t, line)
    if "MB" in w:  # M140 at the block's end, after the block's cycle
        _retract(t, line, w["MB"], w.get("MBF", "MAX"))
    _tcpm_switch(t, [129] if 129 in ms else [])


def _spatial_angles(t: _Tnc, w: dict) -> None:
    """The A, B, C words of a line under FUNCTION TCPM .. AXIS SPAT (TNC7 basic user's manual 81762x-19, "Difference
    between spatial angles and axis angles"): spatial angles as PLANE SPATIAL's, about the fixed X, then Y, then Z;
    the tool's direction they give (+Z turned) is made the spindle's by the nearest solution (as LN's T); an
    angle not written keeps its last value (0 at first)."""
    for k in w:
        if re.fullmatch(r"I?[ABCUVW]", k):
            if k[0] == "I" or k[-1] not in "ABC":
                raise ReferenceError(f"{k} under AXIS SPAT")
            t.spat["ABC".index(k)] = w[k]
    tool = _spatial(*t.spat)[:, 2]
    for name, value in _solve(t, np.column_stack([np.zeros(3), np.zeros(3), tool]), 0, nearest=True).items():
        t.extra["ABC".index(name.upper())] = value


def _retract(t: _Tnc, line: int, mb: float | str, feed: float | str) -> None:
    """M140 MB MAX / MB n: never down (home stands in for the limit); MB n: n up; at the F after MB, else rapid."""
    end = t.pos.copy()
    end[2] = max(t.ctx.home[2], t.pos[2]) if mb == "MAX" else t.pos[2] + abs(float(mb)) * t.scale
    t.emit(line, "rapid" if feed == "MAX" else "feed", end,
           rows="optional" if abs(end[2] - t.pos[2]) <= _EPS else "one")


def _feed_dwell_line(t: _Tnc, line: int, end: np.ndarray, others: bool) -> None:
    """A line ``L`` under FUNCTION FEED DWELL D-TIME d F-TIME f (TNC 640 user's manual, "Cyclic dwell time: FUNCTION
    FEED DWELL", as the reader reads it, no manual page found: the feed time of the path's feed moves at the
    programmed feed counts across blocks; where it reaches f the line is cut and the tool dwells d there)."""
    if others or t.comp or t.rounding is not None or t.scale != 1.0 or t.plunging or not t.feed > 0:
        raise ReferenceError("FUNCTION FEED DWELL with other axes, RL/RR, RND/CHF, INCH, M103 or no feed")
    dwell, cutting = t.feed_dwell
    start = t.pos.copy()
    length, speed = float(np.linalg.norm(end - start)), t.feed / 60.0  # [mm], [mm/s]
    done = 0.0
    while done + (cutting - t.cutting) * speed < length - 1e-9:
        done += (cutting - t.cutting) * speed
        t.feed_dwell = None  # the pieces themselves
        t.emit(line, "feed", start + (end - start) * done / length)
        t.feed_dwell = (dwell, cutting)
        t.out.append(Expected(line=line, kind="dwell", end=t.pos.copy(), rows="one"))
        t.cutting = 0.0
    t.cutting += (length - done) / speed
    t.feed_dwell = None
    t.emit(line, "feed", end)
    t.feed_dwell = (dwell, cutting)


def _feed_dwell_arc(t: _Tnc, line: int, end: np.ndarray, centre: np.ndarray, ccw: bool, plane: tuple,
                    turn: float | None) -> None:
    """An arc ``C`` / ``CP`` (``turn``: its IPA [deg]) under FUNCTION FEED DWELL, as :func:`_feed_dwell_line`:
    cut where the feed time reaches F-TIME (along the arc, r x angle), a dwell there; a full circle when the
    end is the start. Helices, arcs of more than a turn, transformations other than shifts: unmodelled."""
    i, j = plane
    start = t.pos.copy()
    if (abs(end[3 - i - j] - start[3 - i - j]) > 1e-9 or (turn is not None and abs(turn) > 360.0 + 1e-9)
            or t.comp or t.rounding is not None or t.scale != 1.0 or t.plunging or not t.feed > 0
            or t.turns_over() or t.rot or t.scl != 1 or (t.factors != 1).any() or t.tilt is not None):
        raise ReferenceError("FUNCTION FEED DWELL on a helix, an arc over a turn, or with RL/RR, INCH, M103, "
                             "a transformation")
    a0, a1 = (math.atan2(q[j] - centre[j], q[i] - centre[i]) for q in (start, end))
    sweep = (a1 - a0) % (2 * math.pi) if ccw else -((a0 - a1) % (2 * math.pi))
    if abs(sweep) < 1e-9:  # back at the start: a full circle
        sweep = 2 * math.pi if ccw else -2 * math.pi
    radius = math.hypot(start[i] - centre[i], start[j] - centre[j])
    length, speed = radius * abs(sweep), t.feed / 60.0
    dwell, cutting = t.feed_dwell
    kind = "arc_ccw" if ccw else "arc_cw"
    done = 0.0
    t.feed_dwell = None  # the pieces themselves
    while done + (cutting - t.cutting) * speed < length - 1e-9:
        done += (cutting - t.cutting) * speed
        at = start.copy()
        angle = a0 + sweep * done / length
        at[i], at[j] = centre[i] + radius * math.cos(angle), centre[j] + radius * math.sin(angle)
        t.emit(line, kind, at, centre=centre, plane=plane)
        t.out.append(Expected(line=line, kind="dwell", end=t.pos.copy(), rows="one"))
        t.cutting = 0.0
    t.cutting += (length - done) / speed
    t.emit(line, kind, end, centre=centre, plane=plane)
    t.feed_dwell = (dwell, cutting)


def _feed_dwell_def(t: _Tnc, up: str) -> None:
    """``FUNCTION FEED DWELL D-TIME d F-TIME f`` / ``.. RESET``: the count of feed time starts at 0."""
    m = re.match(r"FUNCTION FEED DWELL\s+(?:(RESET)|D-TIME\s*(\S+)\s+F-TIME\s*(\S+))", up)
    dwell = 0.0 if m.group(1) else _val(m.group(2), t.q)
    t.feed_dwell = (dwell, _val(m.group(3), t.q)) if dwell > 0 else None
    t.cutting = 0.0


def _reduce_display(t: _Tnc, margs: dict) -> None:
    """M94 [axis] (TNC 426 B/430 user's manual, "Reducing display of a rotary axis to a value less than 360
    deg: M94"): at the start of the block the named rotary axis (all of them without a name) shows its angle
    modulo 360; the next absolute angle is reached from there (538 deg, then C+180: +2 deg), the axis not moving."""
    if 94 not in margs:
        return
    for i, a in enumerate("ABC"):
        if a.lower() in t.ctx.extra_axes and (not margs[94] or a in margs[94]):
            t.shown[i] = t.extra[i] - math.fmod(math.fmod(t.extra[i] - t.shown[i], 360.0) + 360.0, 360.0)


def _string_formula(t: _Tnc, text: str) -> None:
    """``[DECLARE STRING] QSn = term || term ..`` (TNC 640 user's manual, "String parameters"): quoted texts and
    QS parameters joined."""
    m = re.match(r"\s*(?:DECLARE\s+STRING\s+)?QS(\d+)\s*=(.*)$", text, re.I)
    parts = []
    for term in m.group(2).split("||"):
        term = term.strip()
        if term[:1] in "\"'" and term[-1:] == term[:1]:
            parts.append(term[1:-1])
        elif re.fullmatch(r"QS\d+", term, re.I):
            parts.append(t.strings[int(term[2:])])
        else:
            raise ReferenceError(f"string term {term!r}")
    t.strings[int(m.group(1))] = "".join(parts)


def _spline(t: _Tnc, line: int, rest: str) -> None:
    """``SPL X.. Y.. Z.. K3X.. K2X.. K1X..`` (iTNC 530 user's manual, "Spline interpolation"): X(t) = K3X t^3 +
    K2X t^2 + K1X t + X with t from 1 to 0, so the block ends at its X, Y, Z; its start (the K's sum added) lies
    within 1 um of where the tool is, in each axis. The end is checked (the chords between: rows="last")."""
    ks = {(int(n), a.upper()): float(v.replace(" ", "")) * 10.0 ** int(e or 0) for n, a, v, e in
          re.findall(r"K([123])([XYZ])\s*([-+]?\s*[\d.]+)(?:\s*E\s*([-+]?\d+))?", rest, re.I)}
    plain = re.sub(r"K[123][XYZ]\S*(\s*E\S*)?", " ", rest, flags=re.I)  # the end point's words remain
    ends = dict(re.findall(r"\b([XYZ])\s*([-+]?\s*[\d.]+)", plain, re.I))
    p, start = t.prog(), t.prog()
    for a, v in ends.items():
        i = "XYZ".index(a.upper())
        p[i] = float(v.replace(" ", "")) * t.scale
        start[i] = p[i] + sum(ks[(n, a.upper())] for n in (1, 2, 3)) * t.scale
    if np.max(np.abs(t.machine(start) - t.pos)) > 0.001 + 1e-9:
        raise ReferenceError("SPL start more than 1 um from the tool")
    t.emit(line, "feed", t.machine(p), rows="last")


def _tcpm_switch(t: _Tnc, ms: list) -> None:
    """M128 (TNC 640 manual, "Retaining the position of the tool tip when positioning tilting axes (TCPM)")
    on a table machine, M129 off; a block whose rotary axes move ends where the table at their new positions
    carries the programmed tip (:func:`_line_block`)."""
    if 128 in ms:
        if t.ctx.kinematics is None or t.ctx.kinematics.kind != "table":
            raise ReferenceError("M128 without a tilting table")
        t.tcpm, t.spat = True, None
    if 129 in ms:
        t.tcpm = False


def _tool_vector_line(t: _Tnc, line: int, w: dict) -> None:
    """``LN X Y Z NX NY NZ [TX TY TZ]`` under M128 (iTNC 530 user's manual, "Face milling: 3-D compensation with
    and without tool orientation"): the part point displaced along N by the delta values; with T the rotary axes
    turned so that T (workpiece coordinates) is the spindle's axis, the solution nearest where they are
    (:func:`_solve`), the table carrying the point there; the reader's chords, the last one's end checked."""
    if t.comp or t.turns_over() or t.rot or t.scl != 1 or (t.factors != 1).any() or t.tilt is not None:
        raise ReferenceError("LN under M128 with RL/RR, a transformation or a tilted plane")
    n = _surface_normal(w)
    p = t.prog()  # where the tip is on the part, before the axes turn
    for i, a in enumerate("XYZ"):
        if a in w:
            p[i] = w[a] * t.scale
    if "TX" in w:
        tool = np.array([w["TX"], w["TY"], w["TZ"]], float)
        for name, value in _solve(t, np.column_stack([np.zeros(3), np.zeros(3), tool / np.linalg.norm(tool)]),
                                  0, nearest=True).items():
            t.extra["ABC".index(name.upper())] = value
    t.emit(line, "rapid" if "FMAX" in w else "feed", t.machine(p + t.delta * n), extra=t.extra.copy(), rows="last")


def _surface_normal(w: dict) -> np.ndarray:
    """The unit surface normal N of an ``LN`` block; zero for ``LN X Y Z TX TY TZ`` without N, the peripheral
    milling form (TNC 620 user's manual 81760x-02, 12.6, "Block format with tool orientation": the tool is
    displaced only under RL/RR, which this reference does not model), not displaced."""
    if not any(k in w for k in ("NX", "NY", "NZ")) and all(k in w for k in ("TX", "TY", "TZ")):
        return np.zeros(3)
    n = np.array([w["NX"], w["NY"], w["NZ"]], float)
    return n / np.linalg.norm(n)


def _function_tcpm(t: _Tnc, up: str) -> None:
    """FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS [REFPNT TIP-TIP] (TNC 620 user's manual, "FUNCTION TCPM": the
    feed of the tip on the part, rotary words as positions, the tip on a straight line): as M128; FUNCTION RESET
    TCPM ends it. Any other choice is not modelled here."""
    if up.startswith("FUNCTION RESET TCPM"):
        t.tcpm, t.spat = False, None
        return
    words = re.sub(r"\s+", " ", up[len("FUNCTION TCPM"):]).strip()
    if words.replace("AXIS SPAT", "AXIS POS") not in (
            "F TCP AXIS POS PATHCTRL AXIS", "F TCP AXIS POS PATHCTRL AXIS REFPNT TIP-TIP"):
        raise ReferenceError(up)
    _tcpm_switch(t, [128])
    t.spat = np.zeros(3) if "AXIS SPAT" in words else None  # A, B, C spatial angles (_spatial_angles)


def _pole(t: _Tnc, w: dict) -> None:
    """``CC``: the pole; a coordinate not written is the current one. With Z and one other axis the
    circle lies in ZX (reference axis Z) or YZ (reference axis Y), per the TNC's table of reference axes."""
    p = t.prog()
    for i, a in enumerate("XYZ"):
        if a in w:
            t.pole[i] = w[a] * t.scale
        elif "I" + a in w:
            t.pole[i] = p[i] + w["I" + a] * t.scale
        else:
            t.pole[i] = p[i]
    named = {a for a in "XYZ" if a in w or "I" + a in w}
    t.pole_axes = {frozenset("XZ"): (2, 0), frozenset("YZ"): (1, 2)}.get(frozenset(named), (0, 1))


def _arc(t: _Tnc, line: int, w: dict, *, polar: bool) -> None:
    """``C`` about the pole to X/Y, or ``CP`` by the angle IPA/PA; a Z word makes a helix."""
    _comp_words(t, w)
    p = t.prog()
    i, j = t.pole_axes
    n = 3 - i - j  # the plane normal
    if (i, j) != (0, 1) and (t.comp or t.turns_over() or t.rot or t.scl != 1 or (t.factors != 1).any()):
        raise ReferenceError("a circle outside XY under RL/RR or a transformation")
    if polar:
        r = math.hypot(p[i] - t.pole[i], p[j] - t.pole[j])
        a = math.degrees(math.atan2(p[j] - t.pole[j], p[i] - t.pole[i]))
        # no PA: the end angle is the start's, a full circle (the arc's end is its start)
        a = a + w["IPA"] if "IPA" in w else w.get("PA", a)
        if "PR" in w or "IPR" in w:
            raise ReferenceError("CP with a radius word")
        end = t.machine(_polar_point(t, p, r, a, w))
    else:
        end = t.target(w)
    p_start = t.pos.copy()
    c = t.pole.copy()
    c[n] = t.prog()[n]
    centre = t.machine(c) if polar else _centre_through(p_start, end, t.machine(c), (i, j))
    ccw = (w.get("DR", "+") == "+") != t.turns_over()
    if t.feed_dwell is not None:
        _feed_dwell_arc(t, line, end, centre, ccw, (i, j), w.get("IPA") if polar else None)
    else:
        t.emit(line, "arc_ccw" if ccw else "arc_cw", end, centre=centre, plane=(i, j))
    _arc_tangent(t, end, centre, ccw, (i, j))


def _centre_through(start: np.ndarray, end: np.ndarray, centre: np.ndarray, plane: tuple) -> np.ndarray:
    """The centre [mm, machine] of the circle a ``C`` arc runs on: both its ends on it, nearest the pole (the point
    of the chord's perpendicular bisector closest to CC). A written end point may miss the pole's circle by its
    rounding (the TNC accepts an end within its input tolerance, "Input tolerance: up to 0.016 mm", TNC 410 user's
    manual, "Circular path C around circle center CC"); the element the control runs is that circle's arc, and a
    CT, RND or DEP after it joins its end tangent (our reading: "tangential" to the element as cut, no kink)."""
    i, j = plane
    a, b = np.array([start[i], start[j]]), np.array([end[i], end[j]])
    chord = b - a
    if not np.hypot(*chord) > 1e-9:  # a full circle: nothing to move
        return centre
    u = chord / np.hypot(*chord)
    mid = (a + b) / 2.0
    c = np.array([centre[i], centre[j]])
    c = c - u * float((c - mid) @ u)
    out = centre.copy()
    out[i], out[j] = c
    return out


def _arc_tangent(t: _Tnc, end: np.ndarray, centre: np.ndarray, ccw: bool, plane: tuple) -> None:
    """The direction an XY arc leaves its end point in (machine axes), for CT, RND, CHF and DEP after it."""
    v = (end - centre)[:2]
    if plane != (0, 1) or not np.hypot(*v) > 0:
        return
    d = np.array([-v[1], v[0], 0.0]) if ccw else np.array([v[1], -v[0], 0.0])
    t.last_dir = d / np.linalg.norm(d)


def _radius_arc(t: _Tnc, line: int, w: dict) -> None:
    """``CR X.. Y.. R.. DR..``: the arc of radius |R| to the end point; R > 0 the one under 180 degrees, R < 0
    the one over (TNC 426/430 manual, "Circular path CR with defined radius"); DR+ counter-clockwise."""
    _comp_words(t, w)
    if t.factors[0] != t.factors[1]:
        raise ReferenceError("CR under an unequal scaling of the plane")
    start, end = t.pos.copy(), t.target(w)
    r = abs(w["R"]) * t.scale * t.scl * float(t.factors[0])  # cycle 11/26 scale the circle with its ends
    ccw = (w.get("DR", "+") == "+") != t.turns_over()
    chord = (end - start)[:2]
    c = float(np.hypot(*chord))
    if not 0 < c <= 2 * r + 1e-9:
        raise ReferenceError("CR chord longer than the diameter")
    h = math.sqrt(max(r * r - c * c / 4, 0.0))
    left = np.array([-chord[1], chord[0]]) / c
    # the centre left of the chord for a counter-clockwise arc under 180 degrees, right for one over
    sgn = (1.0 if ccw else -1.0) * (1.0 if w["R"] > 0 else -1.0)
    centre = start.copy()
    centre[:2] = (start[:2] + end[:2]) / 2 + sgn * h * left
    t.emit(line, "arc_ccw" if ccw else "arc_cw", end, centre=centre)
    _arc_tangent(t, end, centre, ccw, (0, 1))


def _tangent_arc(t: _Tnc, line: int, w: dict, *, polar: bool = False) -> None:
    """``CT X.. Y..``: the arc leaving the current point along the last element's direction to the end point
    (TNC 426/430 manual, "Circular path CT with tangential connection"); ``CTP PR.. PA..`` (``polar``): the same
    arc to the end point in polar coordinates about the pole (TNC7 basic manual, "Circular path CTP")."""
    _comp_words(t, w)
    if t.last_dir is None:
        raise ReferenceError("CT without a preceding element's direction")
    if polar and tuple(t.pole_axes) != (0, 1):
        raise ReferenceError("CTP about a pole outside the XY plane")
    start, end = t.pos.copy(), _polar_end(t, w) if polar else t.target(w)
    chord = (end - start)[:2]
    n = np.array([-t.last_dir[1], t.last_dir[0]])  # left of the direction
    across = float(n @ chord)
    if abs(across) < 1e-12:
        raise ReferenceError("CT along its tangent (a straight line)")
    rho = float(chord @ chord) / (2 * across)  # signed: > 0 the centre on the left, counter-clockwise
    centre = start.copy()
    centre[:2] = start[:2] + rho * n
    ccw = rho > 0
    t.emit(line, "arc_ccw" if ccw else "arc_cw", end, centre=centre)
    _arc_tangent(t, end, centre, ccw, (0, 1))


def _start_corner(t: _Tnc, line: int, kind: str, w: dict) -> None:
    """``RND R..`` / ``CHF ..``: the corner at the current point, made when the next element is known."""
    if t.last_dir is None or not t.out or t.rounding is not None:
        raise ReferenceError(f"{kind} without a preceding line")
    size = w["R"] if kind == "RND" else w["LEN"]
    if t.factors[0] != t.factors[1]:
        raise ReferenceError(f"{kind} under an unequal scaling of the plane")
    t.rounding = (kind, abs(size) * t.scale * t.scl * float(t.factors[0]), line, len(t.out) - 1, t.comp)


def _corner(t: _Tnc, end: np.ndarray, centre, ccw_next: bool = True) -> None:
    """Cut the waiting corner between the last element (direction a at the corner P) and the next element
    from P to ``end`` (a line, or an arc about ``centre``): RND the arc of radius r tangent to both, its centre
    where the two elements offset by r into the corner meet nearest P (for two lines r tan(theta/2) from P on
    each); CHF the line between the points ``size`` from P on each line (TNC 426/430 manual, "Rounding corners
    RND": "The rounding arc is tangential to the preceding and following contour elements", "Chamfer CHF": the
    chamfer side length, between two straight lines)."""
    kind, size, line, row, comp = t.rounding
    t.rounding = None
    # the corner is the compensated contour's when RL/RR was in force at the RND/CHF, though the next block
    # cancels it with R0: that block leaves the contour from the corner's end (the reader's reading, tncwild40)
    comp = comp or t.comp
    prev = t.out[row]
    p = t.pos.copy()
    d = (end - p)[:2]
    prev_centre = prev.centre if prev.centre is not None else (
        prev.element[1] if prev.element is not None and prev.element[0] == "arc" else None)
    if not np.hypot(*d) > 0 or not np.allclose(prev.end, p) or abs(end[2] - p[2]) > 1e-12 \
            or (kind == "CHF" and (centre is not None or prev_centre is not None)):
        raise ReferenceError(f"{kind} next to an arc or a move out of the plane")
    a = t.last_dir[:2]
    if centre is None:
        b = d / np.hypot(*d)
    else:
        v = (p - centre)[:2]
        b = (np.array([-v[1], v[0]]) if ccw_next else np.array([v[1], -v[0]])) / np.hypot(*v)
    turn = float(a[0] * b[1] - a[1] * b[0])
    side = t.side * (-1.0 if t.turns_over() else 1.0)  # the tool's side in machine axes (a mirror swaps RL/RR)
    if kind == "RND" and centre is None and prev_centre is None and size * math.tan(
            math.atan2(abs(turn), float(a @ b)) / 2) > min(t.last_len, float(np.hypot(*d))) + 1e-9:
        # between lines it takes r tan(theta/2) of each, an inside one no larger than the tool as well
        raise ReferenceError("RND radius does not fit: it needs more of a line than there is")
    if kind == "RND" and comp and 0 < t.radius and size <= t.radius + 1e-9 and turn * side > 0:
        return  # an inside rounding no larger than the tool: the tool centre paths meet (the reader's note)
    if kind == "CHF":
        t1, t2 = p.copy(), p.copy()
        t1[:2], t2[:2] = p[:2] - a * size, p[:2] + b * size
    else:
        if abs(turn) < 1e-9:
            raise ReferenceError("RND where the elements meet tangentially")
        t1, t2, fc = _fillet((t.last_start[:2], p[:2], None if prev_centre is None else prev_centre[:2], t.last_ccw),
                             (p[:2], end[:2], None if centre is None else centre[:2], ccw_next), a, b, size,
                             1.0 if turn > 0 else -1.0)
        t1, t2 = np.array([*t1, p[2]]), np.array([*t2, p[2]])
    t.out[row] = dataclasses.replace(prev, end=t1, element=None if prev.element is None else
                                     ("line", prev.element[1], t1.copy()) if prev.element[0] == "line"
                                     else prev.element)
    t.pos = t1
    if t.run is not None:  # the compensated run's last element now ends where the RND/CHF begins
        (start, _, c, ccw), begun = t.run
        t.run = ((start, t1[:2].copy(), c, ccw), begun)
        if begun > _along(t.run[0], t1[:2])[0] + 1e-7:  # the inside corner at its start took more than is left
            raise ReferenceError("radius compensation: an element shorter than the inside corner and the "
                                 "RND/CHF at its ends take")
    now, t.comp = t.comp, comp
    if kind == "CHF":
        t.emit(line, "feed", t2)
    else:
        t.emit(line, "arc_ccw" if turn > 0 else "arc_cw", t2, centre=np.array([*fc, p[2]]))
    t.comp = now


def _offset_curve(p: np.ndarray, tangent: np.ndarray, centre, s: float, r: float) -> tuple:
    """The element through ``p`` (tangent there), offset by r to the side ``s`` (+1 left): ('line', point,
    direction) or ('circle', centre, radius)."""
    left = np.array([-tangent[1], tangent[0]])
    if centre is None:
        return "line", p + s * r * left, tangent
    c = np.asarray(centre, float)[:2]
    radius = float(np.hypot(*(p - c)))
    inward = float(left @ (c - p)) > 0  # the left side faces the centre (counter-clockwise)
    return "circle", c, radius - s * r if inward else radius + s * r


def _meet(e1: tuple, e2: tuple) -> list[np.ndarray]:
    """The points where two offset curves (:func:`_offset_curve`) meet."""
    if e1[0] == "circle" and e2[0] == "line":
        e1, e2 = e2, e1
    if e1[0] == "line" and e2[0] == "line":
        (_, p1, d1), (_, p2, d2) = e1, e2
        den = d1[0] * d2[1] - d1[1] * d2[0]
        if abs(den) < 1e-12:
            return []
        u = ((p2[0] - p1[0]) * d2[1] - (p2[1] - p1[1]) * d2[0]) / den
        return [p1 + u * d1]
    if e1[0] == "line":
        (_, p1, d1), (_, c, r) = e1, e2
        f = p1 - c
        bq, cq = float(f @ d1), float(f @ f) - r * r
        disc = bq * bq - cq
        return [] if disc < 0 else [p1 + (-bq + k * math.sqrt(disc)) * d1 for k in (-1.0, 1.0)]
    (_, c1, r1), (_, c2, r2) = e1, e2
    dv = c2 - c1
    dist = float(np.hypot(*dv))
    if not dist > 0:
        return []
    x = (dist * dist + r1 * r1 - r2 * r2) / (2 * dist)
    h2 = r1 * r1 - x * x
    if h2 < 0:
        return []
    u = dv / dist
    base, n = c1 + x * u, np.array([-u[1], u[0]])
    return [base + k * math.sqrt(h2) * n for k in (-1.0, 1.0)]


def _foot(q: np.ndarray, p: np.ndarray, tangent: np.ndarray, centre) -> np.ndarray:
    """The point of the element through ``p`` nearest ``q`` (its touch point with the fillet about q)."""
    if centre is None:
        return p + float((q - p) @ tangent) * tangent
    c = np.asarray(centre, float)[:2]
    radius = float(np.hypot(*(p - c)))
    return c + radius * (q - c) / np.hypot(*(q - c))


def _fillet(first: tuple, second: tuple, a: np.ndarray, b: np.ndarray, r: float, s: float) -> tuple:
    """Touch points on the element before and after the corner and the centre of the fillet of radius r inside
    the corner (side ``s``: +1 the contour turns left); the elements as (start, end, centre, ccw) in the plane, the
    corner the first's end. The fillet touches both elements ("The rounding arc is tangential to the preceding
    and following contour elements", TNC 426/430 manual, "Rounding corners RND"): of the circles of radius r
    tangent to both, the one nearest the corner whose touch points lie on the elements as programmed; none such
    (an element shorter than the rounding needs of it, an arc smaller than the rounding): it does not fit."""
    p = first[1]
    near = _meet(_offset_curve(p, a, first[2], s, r), _offset_curve(p, b, second[2], s, r))
    for fc in sorted(near, key=lambda q: float(np.hypot(*(q - p)))):
        t1, t2 = _foot(fc, p, a, first[2]), _foot(fc, p, b, second[2])
        if _on_element(first, t1) and _on_element(second, t2):
            return t1, t2, fc
    raise ReferenceError("RND radius does not fit between the elements")


def _along(el: tuple, q: np.ndarray) -> tuple[float, float]:
    """How far along the element ``el`` = (start, end, centre, ccw) in the plane the point q (on it or on an offset
    of it) lies, and the element's whole length in the same measure: for a line the distance from its start along
    it [mm], for an arc the angle swept from its start [rad] (a point just before the start is negative; a full
    circle when its end is its start)."""
    start, end, centre, ccw = el
    if centre is None:
        d = end - start
        n = float(np.hypot(*d))
        return float((q - start) @ d) / n, n

    def angle(v: np.ndarray) -> float:
        a = math.atan2(v[1], v[0]) - math.atan2(start[1] - centre[1], start[0] - centre[0])
        return (a if ccw else -a) % (2 * math.pi)

    sweep = angle(end - centre) or 2 * math.pi
    a = angle(q - centre)
    return (a - 2 * math.pi if a > (sweep + 2 * math.pi) / 2 else a), sweep


def _on_element(el: tuple, q: np.ndarray, tol: float = 1e-7) -> bool:
    """q (a point of the element's line or circle) lies between the element's ends."""
    u, n = _along(el, q)
    return -tol <= u <= n + tol


def _tool_path_corner(t: _Tnc, start: np.ndarray, end: np.ndarray, centre, kind: str | None) -> None:
    """Refuse an RL/RR contour the tool cannot follow (iTNC 530 user's manual 60642x-04, "Radius compensation:
    Machining corners": "The TNC calculates the intersection of the tool center paths at inside corners under
    radius compensation. From this point it then starts the next contour element. [...] The permissible tool
    radius, therefore, is limited by the geometry of the programmed contour."). At an inside corner the tool centre
    runs the first element's offset up to the offsets' intersection nearest the corner and the next element's from
    there: an element whose offset the intersections consume (the point lies behind where the tool's path on it
    began, or beyond its end), offsets that do not meet, or an arc curving toward the tool with a radius no larger
    than the tool's leave the tool no path that does not cut into the contour. Outside corners are run round on
    a transition arc: the next element's path starts at its start. A move along the tool axis alone keeps the run;
    the block entering RL/RR (L or APPR: it ends on the first element's offset) is none of it."""
    if centre is None and not np.hypot(*(end - start)[:2]) > 0:
        return
    if centre is not None and kind not in ("arc_ccw", "arc_cw"):  # DEP CT: the tool's arc, not the contour's
        t.run = None
        return
    el = (start[:2].copy(), end[:2].copy(), None if centre is None else np.asarray(centre, float)[:2].copy(),
          kind == "arc_ccw")
    side = t.side * (-1.0 if t.turns_over() else 1.0)  # the tool's side in machine axes (a mirror swaps RL/RR)
    b = _tangent(el, at_end=False)
    ob = _offset_curve(el[0], b, el[2], side, t.radius)
    if ob[0] == "circle" and ob[2] <= 1e-9:
        raise ReferenceError("an arc curving toward the tool with a radius no larger than the tool's")
    prev, t.run = t.run, (None if t.entry else (el, 0.0))
    if prev is None or t.entry:  # the block entering RL/RR (L or APPR) ends on the next element's offset
        return
    (pel, begun) = prev
    a = _tangent(pel, at_end=True)
    p = el[0]
    turn = float(a[0] * b[1] - a[1] * b[0])
    if turn * side <= 1e-9:  # an outside corner, or the elements meet tangentially
        return
    meets = _meet(_offset_curve(p, a, pel[2], side, t.radius), ob)
    if not meets:
        raise ReferenceError("radius compensation: the tool centre paths of an inside corner do not meet")
    x = min(meets, key=lambda q: float(np.hypot(*(q - p))))
    if _along(pel, x)[0] < begun - 1e-7:
        raise ReferenceError("radius compensation: an element shorter than the inside corners at its ends take")
    u, n = _along(el, x)
    if u > n + 1e-7:
        raise ReferenceError("radius compensation: the next element is shorter than the inside corner takes")
    t.run = (el, u)


def _tangent(el: tuple, *, at_end: bool) -> np.ndarray:
    """The unit direction of travel of the element (start, end, centre, ccw) at its start or end."""
    start, end, centre, ccw = el
    if centre is None:
        d = end - start
        return d / np.hypot(*d)
    v = (end if at_end else start) - centre
    d = np.array([-v[1], v[0]]) if ccw else np.array([v[1], -v[0]])
    return d / np.hypot(*d)


def _polar_point(t: _Tnc, p: np.ndarray, r: float, a: float, w: dict) -> np.ndarray:
    """The programmed point at radius ``r`` and angle ``a`` [deg] about the pole from ``p``, in the pole's
    plane; a word of the plane's normal axis (absolute or incremental) moves it along that axis."""
    i, j = t.pole_axes
    n = 3 - i - j
    end_p = p.copy()
    end_p[i] = t.pole[i] + r * math.cos(math.radians(a))
    end_p[j] = t.pole[j] + r * math.sin(math.radians(a))
    axis = "XYZ"[n]
    if axis in w:
        end_p[n] = w[axis] * t.scale
    if "I" + axis in w:
        end_p[n] += w["I" + axis] * t.scale
    return end_p


def _polar_line(t: _Tnc, line: int, w: dict) -> None:
    """``LP``: a line to the point PR from the pole at the angle PA from the reference axis of the pole's
    plane (IPR / IPA: added to the current radius / angle about the pole); a word of the plane's normal
    axis moves it too (under RL/RR: the contour's point). Without transformations only."""
    _comp_words(t, w)
    t.emit(line, "rapid" if "FMAX" in w else "feed", _polar_end(t, w, line=True))


def _polar_end(t: _Tnc, w: dict, *, line: bool = False) -> np.ndarray:
    """The machine end point of ``LP`` / ``CTP`` words: PR (IPR: added to the current radius) from the pole at
    PA (IPA: added to the current angle) from the reference axis of the pole's plane. Without transformations,
    except for a line (``line``): its end point is the program point mapped as any other (the TNC 640 manual's
    example "Sphere" moves so about ``CC X+0 Y+0`` and ``CC Z+0 X+Q108`` under cycle 10)."""
    if not line and (t.turns_over() or t.rot or t.scl != 1 or (t.factors != 1).any()):
        raise ReferenceError("LP/CTP under a transformation")
    p = t.prog()
    i, j = t.pole_axes
    r = math.hypot(p[i] - t.pole[i], p[j] - t.pole[j])
    a = math.degrees(math.atan2(p[j] - t.pole[j], p[i] - t.pole[i]))
    r = w["PR"] * t.scale if "PR" in w else r + w.get("IPR", 0.0) * t.scale
    a = w["PA"] if "PA" in w else a + w.get("IPA", 0.0)
    return t.machine(_polar_point(t, p, r, a, w))


def _approach(t: _Tnc, line: int, w: dict, form: str) -> None:
    """``APPR LT|LN|CT``: the last of its moves (a line; CT: an arc) ends at the contour's first point P_A."""
    _comp_words(t, w)
    t.emit(line, "feed" if form in ("LT", "LN") else None, t.target(w), rows="last")


def _keeps_comp(w: dict) -> bool:
    """A DEP block ends RL/RR unless it writes RL or RR again (TNC 410 user's manual, "Contour approach and
    departure": "The TNC automatically cancels the radius compensation in a DEP block")."""
    return "RL" in w or "RR" in w


def _depart(t: _Tnc, line: int, w: dict, form: str = "LT") -> None:
    """``DEP LT LEN``: straight on along the last element's direction by LEN; ``DEP LN LEN``: LEN to the
    tool's side (RL: left), square to it; ``DEP CT CCA R``: the tool centre leaves on a circle of radius R
    tangent to the last element, turning counter-clockwise for RL with R > 0 or RR with R < 0, through
    CCA (R is the radius of the tool's path: iTNC 530 manual, APPR LCT, "the radius then suffices to
    completely define the tool path")."""
    if t.last_dir is None or t.factors[0] != t.factors[1]:
        raise ReferenceError("DEP without a preceding line (or under an unequal scaling of the plane)")
    k = t.scale * t.scl * float(t.factors[0])  # LEN and R scale with the contour (cycles 11/26); the tool does not
    side = t.side * (-1.0 if t.turns_over() else 1.0)  # the tool's side in machine axes
    left = np.array([-t.last_dir[1], t.last_dir[0], 0.0])
    comp = t.comp and t.radius > 0
    if form == "LT":
        end = t.pos + t.last_dir * w["LEN"] * k
    elif form == "LN":  # PN is LEN plus the tool radius off the last contour point
        end = t.pos + side * left * (w["LEN"] * k + (t.radius if t.comp else 0.0))
    else:  # the circle of the tool centre, from the tool beside the last contour point
        turn = 1.0 if (side > 0) == (w["R"] > 0) else -1.0
        tool = t.pos + (side * t.radius * left if comp else 0.0)
        centre = tool + turn * abs(w["R"]) * k * left
        a = math.radians(turn * w["CCA"])
        v = tool - centre
        tool_end = centre + np.array([v[0] * math.cos(a) - v[1] * math.sin(a), v[0] * math.sin(a) + v[1] * math.cos(a),
                                      0])
        # the contour point whose offset is the tool's end: the tool inside the arc when it turns to its side
        out = 1.0 if (side > 0) == (turn > 0) else -1.0
        end = centre + (tool_end - centre) * (1.0 + out * t.radius / (abs(w["R"]) * k)) if comp else tool_end
    if not _keeps_comp(w) and form != "CT":
        t.comp = False
    if form != "CT":
        t.emit(line, "feed", end, rows="last")
    else:  # the tool runs the arc compensated: its centre path is the circle about the arc's centre
        t.emit(line, None, end, rows="last", centre=centre)
    if form == "CT" and comp:
        t.pos = tool_end
    if not _keeps_comp(w):
        t.comp = False


#: The English item names of the old cycles' dialog (TNC 355 / 426 user's manuals), blanks removed: none has a dot
#: of its own, so a dot right after one is the number's ('DWELL.5': 0.5 s, 'SET UP.5': 0.5 mm; our reading).
_ENGLISH_ITEM = re.compile(r"(SETUP|DIST|DEPTH|PECKG|PLNGNG|DWELL|TIME|PITCH|RADIUS)(?=[-+]?\.\d)", re.I)


def _last_number(text: str, q: dict) -> float:
    # a dot right after a letter is the name's (V.ZEIT, the Czech BEZP.VZD.), not a number's, except after an
    # English name (_ENGLISH_ITEM)
    text = _ENGLISH_ITEM.sub(r"\1 ", text.replace("SET UP", "SETUP"))
    m = re.findall(r"[-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|(?<![A-Za-z])\.\d+)", text)
    if not m:
        raise ReferenceError(f"no value in {text!r}")
    return _val(m[-1].replace(" ", ""), q)


def _cycle_def(t: _Tnc, line: int, text: str) -> None:
    """``CYCL DEF n.k ...`` (and the SolidWorks spelling ``CYCLE DEF``)."""
    m = re.match(r"CYCLE? DEF\s*(\d+)(?:\.(\d+))?\s*(.*)$", text)
    number, sub, rest = int(m.group(1)), int(m.group(2) or 0), m.group(3)
    if number == 7 and sub > 0 and rest.strip().startswith("#"):  # a row of the datum table: its X, Y, Z [mm]
        t.shifted = t.tilt is not None
        row = rest.strip()[1:].strip()
        t.shift[:] = t.datum_rows[int(_val(row, t.q))]
    elif number == 7 and sub > 0:
        w = _words(rest, t.q)
        t.shifted = t.tilt is not None
        for i, a in enumerate("XYZ"):
            if a in w:
                t.shift[i] = w[a] * t.scale
            if "I" + a in w:
                t.shift[i] += w["I" + a] * t.scale
    elif number == 9 and sub == 1:
        t.out.append(Expected(line=line, kind="dwell", end=t.pos.copy()))
    elif number in (13, 32) or (number in (7, 8, 9, 10, 11, 26) and sub == 0):  # 13 ORIENTATION: no motion
        pass
    elif number in (8, 10, 11, 26) and sub == 1:
        _transform(t, number, rest)
    elif number == 247:
        n = int(_val(re.search(r"Q339\s*=\s*([-+]?\s*[\w.]+)", rest).group(1).replace(" ", ""), t.q))
        presets = ("G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3")
        t.preset = presets[max(n - 1, 0)] if n <= len(presets) else None  # beyond the table: zero offset
        t.shift, t.mirror, t.rot, t.scl, t.factors = np.zeros(3), np.ones(3), 0.0, 1.0, np.ones(3)  # all reset
    elif number == 12 and sub == 1:  # PGM CALL: the program is the cycle
        if t.resolve is None:
            raise ReferenceError("cycle 12 without a resolver")
        t.cycle = ("12", rest.split(None, 1)[1].strip().strip('"'))
    elif number == 12:
        pass
    elif number == 14:
        if sub == 1:
            t.contours = tuple(re.findall(r"\d+", rest))
            t.contour, t.islands = t.contours[0], set()
    elif number in (20, 21, 22, 23, 24, 25):
        params = {k: math.inf if v.upper() in ("MAX", "FMAX") else _val(v.replace(" ", ""), t.q)
                  for k, v in re.findall(r"(Q\d+)\s*=\s*([-+]?\s*[\w.]+)", rest)}
        t.q.update(params)
        if number == 20:
            t.data = params
        else:
            t.cycle = (str(number), params if number == 25 else {**t.data, **params})
    elif number == 392:  # ATC, DMG MORI's dynamics tuning of its TNC 640 machines: no motion, its Q set
        t.q.update({k: _val(v.replace(" ", ""), t.q) for k, v in re.findall(r"(Q\d\d\d)\s*=\s*([-+]?\s*[\w.]+)", rest)})
    elif number == 19:  # a tilted working plane (spatial angles; the program positions the rotary axes,
        # unless 19.1 has F: then the control does, as PLANE MOVE with ABST as DIST)
        words = {k.upper(): _val(v, t.q)
                 for k, v in re.findall(r"(?<![A-Z])(ABST|[ABCF])\s*([-+]?\s*[\d.]+|[-+]?Q[LR]?\d+)", rest.upper())}
        auto = dict(positioning="MOVE", feed="feed", dist=words.get("ABST", 0.0)) if "F" in words else {}
        angles = {k: v for k, v in words.items() if k in "ABC"}
        if any(v != 0 for v in angles.values()):
            _tilt_plane(t, line, _spatial(angles.get("A", 0.0), angles.get("B", 0.0), angles.get("C", 0.0)),
                        **(auto or dict(positioning="STAY")))
        elif t.ctx.kinematics is not None and sub == 1:
            _tilt_plane(t, line, None, **(auto or dict(positioning="STAY")))
    elif number in (4, 5):  # POCKET MILLING 4.1 SET UP, 4.2 DEPTH, 4.3 PECKG .. F, 4.4 X, 4.5 Y, 4.6 F DR RADIUS;
        # CIRCULAR POCKET 5.1 SET UP, 5.2 DEPTH, 5.3 PECKG .. F, 5.4 RADIUS, 5.5 F .. DR+/-
        if sub == 0:
            t.cycle = (str(number), {})
            return
        r = rest.upper().replace(" ", "")
        # F the feed, not the end of an item's name (the Italian 4.2 PROF: depth)
        f, dr = re.search(r"(?<![A-Z])F([-+]?(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", r), re.search(r"DR([-+])", r)
        if f is not None:
            t.cycle[1][f"F{sub}"] = _val(f.group(1), t.q)
        if dr is not None:
            t.cycle[1]["DR"] = 1.0 if dr.group(1) == "+" else -1.0
        rad = re.search(r"RADIUS([-+]?(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", r)
        if number == 4 and sub == 6:  # the radius's name in the control's language (PROMIEN: Polish)
            tail = r[dr.end():] if dr is not None else ""
            t.cycle[1][6] = abs(_val(rad.group(1), t.q)) if rad else (
                abs(_last_number(tail, t.q)) if re.search(r"\d|Q", tail) else 0.0)
        elif sub != 5 or number == 4:
            t.cycle[1][sub] = _last_number(r[:f.start()] if f is not None else r, t.q)
    elif number in (1, 2, 17):
        if sub == 0:
            t.cycle = (str(number), {})
        elif sub in (1, 2, 3, 4, 5):
            t.cycle[1][sub] = _last_number(rest, t.q)
    elif number in (200, 201, 202, 203, 204, 205, 206, 207, 208, 209, 210, 211, 212, 213, 214, 215, 220, 221, 230,
                    231, 232, 233, 240, 241, 251, 252, 253, 254, 256, 257, 262, 263, 264, 265, 267) \
            and sub == 0:
        params = {k: math.inf if v.upper() in ("MAX", "FMAX") else _auto(t) if v.upper() in ("AUTO", "FAUTO")
                  else _val(v.replace(" ", ""), t.q) for k, v in re.findall(r"(Q\d\d\d)\s*=\s*([-+]?\s*[\w.]+)", rest)}
        for k, v in params.items():
            t.q[k] = v
        if number in (220, 221):
            _pattern(t, line, number, params)
        else:
            t.cycle = (str(number), params)
    else:
        raise ReferenceError(f"CYCL DEF {number}")


def _touch_probe(t: _Tnc, line: int, up: str) -> None:
    """``TCH PROBE 400/408-413/417/419-424/427/431`` in the XY plane, probe axis Z, the touch probe table of
    ``context.touch_probe`` (SET_UP, F, FMAX, DIST), the tip radius that row's or else the tool radius. Every move
    is a feed move (FMAX column or F): where below the clearance height Q260 the probe rises to it first, then XY,
    then Z. The side touch points: 410/411 left, bottom, right, top; 408/409 the minus side first (the reader's
    reading). The measuring cycles 421-424 probe as 412/413/410/411 (centre Q273/Q274, sides Q282/Q283)."""
    m = re.match(r"TCH\s*PROBE\s*(\d+)", up)
    number = int(m.group(1))
    if number not in (400, 408, 409, 410, 411, 412, 413, 417, 419, 420, 421, 422, 423, 424, 426, 427, 431):
        raise ReferenceError(f"TCH PROBE {number}")
    p = {"Q301": 1.0, "Q305": 0.0, "Q331": 0.0, "Q332": 0.0, "Q333": 0.0, "Q381": 0.0, "Q423": 4.0, "Q365": 1.0,
         "Q303": 1.0, "Q405": 0.0}
    for qm in re.finditer(r"(Q\d+)\s*=\s*([-+]?\s*[\w.]+)", up[m.end():]):
        p[qm.group(1)] = _val(qm.group(2).replace(" ", ""), t.q)
        t.q[qm.group(1)] = p[qm.group(1)]
    tp = t.ctx.touch_probe
    tip = t.radius if tp.tip_radius is None else tp.tip_radius
    gap = p["Q320"] * t.scale + tp.set_up
    high = p["Q260"] * t.scale

    def go(prog_xyz, circle=None) -> None:
        end = t.machine(np.array(prog_xyz, float))
        if circle is None:
            if np.any(np.abs(end - t.pos) > 1e-12):
                t.emit(line, "feed", end)
        else:
            t.emit(line, "arc_ccw" if circle[1] > 0 else "arc_cw", end, centre=t.machine(np.array(circle[0], float)))

    def approach(x: float, y: float, z: float) -> None:
        here = t.prog()
        if here[2] < high:
            go((here[0], here[1], high))
        go((x, y, t.prog()[2]))
        go((x, y, z))

    def probe_down(x: float, y: float, z: float) -> None:
        approach(x, y, z + gap)
        go((x, y, z))
        go((x, y, z + gap))

    move = np.full(3, np.nan)
    if number in (421, 422, 423, 424):  # as the datum cycles, on their own parameter numbers
        for mine, theirs in (("Q321", "Q273"), ("Q322", "Q274"), ("Q323", "Q282"), ("Q324", "Q283")):
            p[mine] = p.get(theirs, 0.0)
        number = {421: 412, 422: 413, 423: 410, 424: 411}[number]
        p["Q381"] = 0.0
        t.q.update({"Q161": 0.0, "Q162": 0.0, "Q163": 0.0, "Q164": 0.0, "Q165": 0.0, "Q180": 1.0, "Q181": 0.0,
                    "Q182": 0.0})
        measuring = True
    else:
        measuring = False
    if number == 417:
        probe_down(p["Q263"] * t.scale, p["Q264"] * t.scale, p["Q294"] * t.scale)
        move[2] = (p["Q294"] - p["Q333"]) * t.scale
        t.q["Q160"] = p["Q294"]
    elif number == 431:
        for k in ((263, 264, 294), (265, 266, 295), (296, 297, 298)):
            probe_down(*(p[f"Q{n}"] * t.scale for n in k))
        t.q.update({"Q173": p["Q294"], "Q174": p["Q295"], "Q175": p["Q298"]})
    elif number in (400, 419, 420, 426, 427):
        _axis_points(t, p, number, tip, gap, go, approach, move)
    else:
        _side_touches(t, p, number, tip, gap, go, approach)
        if number in (408, 409):
            axis = int(p["Q272"]) - 1
            move[axis] = (p[f"Q{321 + axis}"] - p["Q405"]) * t.scale
            t.q.update({"Q166": p["Q311"], "Q157": p[f"Q{321 + axis}"]})
        else:
            move[:2] = (p["Q321"] - p["Q331"]) * t.scale, (p["Q322"] - p["Q332"]) * t.scale
            t.q.update({"Q151": p["Q321"], "Q152": p["Q322"]})
            t.q.update({"Q153": p["Q262"]} if number in (412, 413) else {"Q154": p["Q323"], "Q155": p["Q324"]})
        if p["Q381"] == 1:
            probe_down(p["Q382"] * t.scale, p["Q383"] * t.scale, p["Q384"] * t.scale)
            move[2] = (p["Q384"] - p["Q333"]) * t.scale
    go((*t.prog()[:2], high))
    if measuring or np.all(np.isnan(move)):
        return
    move = np.nan_to_num(move)
    presets = ("G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3")
    row = int(p["Q305"])
    if t.tilt is not None and row != 0 and p["Q303"] != 0:
        raise ReferenceError("a probed datum written to a preset table row in a tilted plane")
    if row == 0:  # in a tilted plane: the move in the plane's axes, the preset in the part's (untilted) ones
        t.overrides[t.preset] = t.preset_point() + (move if t.tilt is None else t.tilt @ move)
    elif p["Q303"] == 1 and row <= len(presets):
        t.overrides[presets[row - 1]] = t.preset_point() + t.shift + move
    elif p["Q303"] == 0:  # row of the datum table: the shift from the zero that puts the probed point there (in a
        # tilted plane a shift in its axes, as cycle 7's there: "the active workpiece coordinate system", Q303)
        t.datum_rows[row] = t.shift + move


def _axis_points(t: _Tnc, p: dict, number: int, tip: float, gap: float, go, approach, move: np.ndarray) -> None:
    """400/420/426 (two points Q263/Q264, Q265/Q266), 419/427 (one, Q263/Q264): probed along the axis Q272 (3: Z,
    touching at Q261) in the direction Q267 (426: -, then +) at the height Q261; between the two up to Q260 when
    Q301=1 (426: always)."""
    pts = [(p["Q263"], p["Q264"])] + ([(p["Q265"], p["Q266"])] if number in (400, 420, 426) else [])
    axis = int(p["Q272"]) - 1
    for k, (x, y) in enumerate(pts):
        d = (-1.0, 1.0)[k] if number == 426 else p["Q267"]
        touch = np.array([x, y, p["Q261"]]) * t.scale
        if axis < 2:
            touch[axis] -= d * tip
        start = touch.copy()
        start[axis] -= d * gap
        if k == 0:
            approach(*start)
        elif p["Q301"] == 1 or number == 426:
            go((*t.prog()[:2], p["Q260"] * t.scale))
            go((start[0], start[1], p["Q260"] * t.scale))
            go(start)
        else:
            go(start)
        go(touch)
        go(start)
    value = (pts[-1][0], pts[-1][1], p["Q261"])[axis]
    if number == 419:
        move[axis] = (value - p["Q333"]) * t.scale
    elif number == 427:
        t.q.update({"Q160": value, "Q180": 1.0, "Q181": 0.0, "Q182": 0.0})
    elif number == 420:
        (x1, y1), (x2, y2) = pts
        t.q["Q150"] = 0.0 if axis == 2 else math.degrees(math.atan2(y2 - y1, x2 - x1))
    elif number == 426:
        a, b = pts[0][axis], pts[1][axis]
        t.q.update({"Q156": a - b, "Q157": (a + b) / 2, "Q166": a - b - p["Q311"], "Q180": 1.0, "Q181": 0.0,
                    "Q182": 0.0})


def _side_touches(t: _Tnc, p: dict, number: int, tip: float, gap: float, go, approach) -> None:
    """The touches in the plane of 408-413 at the measuring height: (direction, wall distance) per point from
    the centre; the tip's centre stops a tip radius short of the wall, starts ``gap`` before that (inside: at the
    centre when that is past it, and then every point from there with no moves between)."""
    cx, cy, zm = (p[k] * t.scale for k in ("Q321", "Q322", "Q261"))
    inside = number in (408, 410, 412)
    if number in (412, 413):
        r = p["Q262"] * t.scale / 2
        rays = [(_unit(p["Q325"] + k * p["Q247"]), r) for k in range(int(p["Q423"]))]
    elif number in (410, 411):
        a, b = p["Q323"] * t.scale / 2, p["Q324"] * t.scale / 2
        rays = [(np.array([-1.0, 0.0]), a), (np.array([0.0, -1.0]), b), (np.array([1.0, 0.0]), a),
                (np.array([0.0, 1.0]), b)]
    else:
        u = np.array([1.0, 0.0]) if p["Q272"] == 1 else np.array([0.0, 1.0])
        rays = [(-u, p["Q311"] * t.scale / 2), (u, p["Q311"] * t.scale / 2)]
    reach = [w - tip if inside else w + tip for _, w in rays]
    starts = [x - gap if inside else x + gap for x in reach]
    small = inside and min(starts) <= 0
    if small:
        starts = [0.0] * len(starts)
    lvl = t.scale * p["Q260"] if (p["Q301"] == 1 or number == 409) and not small else zm
    c = np.array([cx, cy])
    for k, ((u, _), x, s) in enumerate(zip(rays, reach, starts)):
        sx, sy = c + s * u
        if k == 0:
            approach(sx, sy, zm)
        elif not small:
            go((*t.prog()[:2], lvl))
            circle = None
            if number in (412, 413) and p["Q365"] != 0:  # Line=0/arc=1, as cycle 220's
                circle = ((cx, cy, lvl), p["Q247"])
            elif number in (410, 411) and lvl == zm:  # paraxial at the measuring height: round the corner
                px, py = t.prog()[:2]
                go((sx if u[0] else px, sy if u[1] else py, lvl))
            go((sx, sy, lvl), circle)
            go((sx, sy, zm))
        go((*(c + x * u), zm))
        go((sx, sy, zm))


def _unit(angle: float) -> np.ndarray:
    """The unit vector at ``angle`` [deg] in the XY plane."""
    return np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])


def _auto(t: _Tnc) -> float:
    """A cycle feed written AUTO: the F of the last TOOL CALL."""
    if t.auto is None:
        raise ReferenceError("a cycle feed AUTO without a TOOL CALL F")
    return t.auto


def _transform(t: _Tnc, number: int, rest: str) -> None:
    """Item 1 of cycle 8 (mirrored axes, none: off), 10 (ROT/IROT [deg]), 11 (SCL), 26 (factors, CC centre)."""
    text = re.sub(r"\s+", "", rest)
    if number == 8:
        t.mirror = np.array([-1.0 if a in text else 1.0 for a in "XYZ"])
    elif number == 10:
        # iTNC 530 / TNC 640 cycle programming manuals, ROTATION (cycle 10): "An active radius compensation is
        # canceled by defining Cycle 10 and must therefore be reprogrammed": the next RL/RR enters anew; the tool
        # stays beside the last point (a tool radius off it, as after an SL cycle, until X and Y are both written)
        if t.comp and t.rounding is not None:
            raise ReferenceError("cycle 10 with an RND/CHF waiting under RL/RR")
        if t.comp:
            t.loose = max(t.loose, t.radius)
        t.comp = False
        m = re.fullmatch(r"(I?)ROT(.+)", text)
        t.rot = (t.rot if m.group(1) else 0.0) + _val(m.group(2), t.q)
    elif number == 11:
        t.scl = _val(re.fullmatch(r"SCL(.+)", text).group(1), t.q)
    else:
        for cc, axis, v in re.findall(r"(CC)?([XYZ])([-+]?(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", text):
            i = "XYZ".index(axis)
            if cc:
                t.centre[i] = _val(v, t.q) * t.scale
            else:
                t.factors[i] = _val(v, t.q)


def _trans(t: _Tnc, up: str) -> None:
    """TRANS DATUM AXIS (as cycle 7) / RESET, TRANS MIRROR AXIS, TRANS ROTATION, TRANS SCALE (as 8, 10, 11) / RESET."""
    m = re.match(r"TRANS\s+(DATUM|MIRROR|ROTATION|SCALE)\s*(AXIS|RESET)?\s*(.*)$", up)
    kind, sub, rest = m.groups()
    if sub == "RESET":
        if kind == "DATUM":
            t.shift = np.zeros(3)
        elif kind == "MIRROR":
            t.mirror = np.ones(3)
        elif kind == "ROTATION":
            t.rot = 0.0
        else:
            t.scl = 1.0
    elif kind == "DATUM" and rest.startswith("TABLE"):  # TRANS DATUM TABLE TABLINE n: row n of the datum table
        _cycle_def(t, 0, "CYCL DEF 7.1 #" + rest.split("TABLINE")[1].strip())
    elif kind == "DATUM":
        _cycle_def(t, 0, "CYCL DEF 7.1 " + rest)
    else:
        _transform(t, {"MIRROR": 8, "ROTATION": 10, "SCALE": 11}[kind], rest)


def _move_z(t: _Tnc, line: int, kind: str, z: float, *, optional: bool = False) -> None:
    """A tool-axis move to program height ``z``."""
    end = t.pos.copy()
    end[2] = t.machine(np.array([0.0, 0.0, z * t.scale]))[2]
    rows = "optional" if optional and abs(end[2] - t.pos[2]) <= _EPS * max(1.0, abs(end[2])) else "one"
    t.emit(line, kind, end, rows=rows)


def _function_dwell(t: _Tnc, line: int, up: str) -> None:
    """``FUNCTION DWELL TIME t`` / ``REV r`` (TNC 640 user's manual, "Defining a dwell time: FUNCTION DWELL"): a
    dwell where the tool is, t seconds or r spindle revolutions."""
    m = re.match(r"FUNCTION DWELL\s+(TIME|REV)\s*(\S+)\s*$", up)
    if m is None:
        raise ReferenceError(up)
    _dwell(t, line, _val(m.group(2), t.q))


def _dwell(t: _Tnc, line: int, seconds: float) -> None:
    t.out.append(Expected(line=line, kind="dwell", end=t.pos.copy(), rows="one" if seconds > 0 else "optional"))


def _single_lip_entry(t: _Tnc, line: int, p: dict, surface: float, sgn: float) -> None:
    """Cycle 241 before its last plunge: at Q253 (MAX: rapid) to Q200 above the deepened starting point Q379
    (when one is given); at Q206 to the dwell depth Q435 and a dwell Q211 there."""
    start, setup = abs(p.get("Q379", 0.0)), abs(p["Q200"])
    if start:
        _move_z(t, line, "rapid" if math.isinf(p["Q253"]) else "feed", surface + sgn * (start - setup))
    if p.get("Q435", 0.0):
        _move_z(t, line, "feed", surface + sgn * abs(p["Q435"]))
        _dwell(t, line, p.get("Q211", 0.0))


def _old_cycle(t: _Tnc, line: int, kind: str, p: dict, start: float) -> None:
    """The old cycles 1 PECKING, 2 and 17 TAPPING, 4 POCKET MILLING and 5 CIRCULAR POCKET from ``start``."""
    if kind == "1":
        setup, depth, plunge, dwell = abs(p[1]), p[2], abs(p[3]), p[4]
        sgn = -1.0 if depth < 0 else 1.0
        surface = start + sgn * setup
        bottom = surface + depth
        # the advanced stop distance is the control's own clearance in mm of the machine, not a programmed
        # dimension: cycle 11/26 scaling leaves it (and the 30 mm rule's depth is the scaled one), our reading
        k = t.scale * t.scl * float(t.factors[2])
        advance = 0.6 if abs(depth) * k <= 30 else min(abs(depth) * k / 50, 7.0)
        advance /= k
        levels = _levels(surface, bottom, sgn, plunge)
        for k, z in enumerate(levels):
            if k:
                _move_z(t, line, "rapid", start)
                _move_z(t, line, "rapid", levels[k - 1] - sgn * advance)
            _move_z(t, line, "feed", z)
        _dwell(t, line, dwell)
        _move_z(t, line, "rapid", start)
        return
    if kind == "5":  # TNC 426 manual: from the starting position, the set-up clearance above the surface, plunge
        # and mill out at each plunging depth, then back to the starting position: 252's roughing (Q370 = 1)
        sgn = -1.0 if p[2] < 0 else 1.0
        _circular_pocket(t, line, {"Q215": 0.0, "Q203": start + sgn * abs(p[1]), "Q200": abs(p[1]), "Q201": p[2],
                                   "Q202": abs(p[3]), "Q223": 2 * abs(p[4]), "Q370": 1.0, "Q351": p.get("DR", 1.0),
                                   "Q204": 0.0})
        return
    if kind == "4":  # TNC 426 manual: first along the longer side (+Y when square): 251's roughing, turned 90 deg
        sgn = -1.0 if p[2] < 0 else 1.0  # when the second side is the longer
        a, b = abs(p[4]), abs(p[5])
        _circular_pocket(t, line, {"Q215": 0.0, "Q203": start + sgn * abs(p[1]), "Q200": abs(p[1]), "Q201": p[2],
                                   "Q202": abs(p[3]), "Q218": max(a, b), "Q219": min(a, b), "Q220": p.get(6, 0.0),
                                   "Q224": 90.0 if b >= a else 0.0, "Q370": 1.0, "Q351": p.get("DR", 1.0),
                                   "Q204": 0.0})
        return
    if kind in ("2", "17"):  # old tapping: in to the depth below start + set-up clearance, (2: dwell), back out
        sgn = -1.0 if p[2] < 0 else 1.0
        _move_z(t, line, "feed", start + sgn * abs(p[1]) + p[2])
        if kind == "2":
            _dwell(t, line, p.get(3, 0.0))
        _move_z(t, line, "feed", start)


def _called(t: _Tnc) -> None:
    """A 200-series machining cycle (not the surface cycles 230-233) with its Q parameters' current values: a
    cycle reads them when it is called (our reading of the TNC 640 ISO manual 34059x-01, 8.1, Q200-Q1199
    "primarily used for cycles; globally effective", and of cycle 220, whose Q200/Q203/Q204 are effective for
    the cycle it calls); a MAX feed stays."""
    if t.cycle is not None and t.cycle[0].isdigit() and int(t.cycle[0]) >= 200 \
            and t.cycle[0] not in ("230", "231", "232", "233"):
        t.cycle = (t.cycle[0], {k: v if math.isinf(v) else t.q.get(k, v) for k, v in t.cycle[1].items()})


def _run_cycle(t: _Tnc, line: int, *, fresh: bool = True) -> None:
    """The defined machining cycle at the current position (``fresh``: with its Q parameters as they are now;
    a pattern passes its own)."""
    if t.cycle is None:
        raise ReferenceError("cycle call without a machining cycle")
    if fresh:
        _called(t)
    kind, p = t.cycle
    if kind == "12":
        _execute(t, t.resolve(p), t.resolve, called=True)
        return
    start = t.prog()[2] / t.scale
    if kind in ("1", "2", "4", "5", "17"):
        _old_cycle(t, line, kind, p, start)
        return
    if kind in ("200", "203", "205", "240"):
        p = _point_depth(t, kind, p)
    # the cycles one function runs: of (t, line, p), or of (t, line, kind, p)
    runs = {"208": _bore_milling, "230": _face_milling, "232": _face_milling, "231": _ruled_surface,
            "233": _face_milling_233, "25": _contour_train, "262": _thread_milling, "251": _circular_pocket,
            "252": _circular_pocket, "256": _stud, "204": _back_boring}
    kind_runs = {"212": _finishing, "213": _finishing, "214": _finishing, "215": _finishing, "210": _old_slot,
                 "211": _old_slot, "263": _thread_family, "264": _thread_family, "265": _thread_family,
                 "267": _thread_family, "203": _universal_drilling, "205": _universal_drilling}
    if kind in ("251", "253", "256") and p.get("Q367", 0.0):
        _to_shape_centre(t, line, kind, p)
    if kind in runs:
        runs[kind](t, line, p)
        return
    if kind in kind_runs:
        kind_runs[kind](t, line, kind, p)
        return
    if kind in ("22", "23") and len(t.contours) == 1 and not p.get("Q18", 0) and t.loose:
        raise ReferenceError("one pocket's 22/23 after an SL cycle that left the tool's plane position unknown")
    if kind == "23" and len(t.contours) == 1:  # FLOOR FINISHING of one pocket: 22 in one infeed to Q1
        _rough_out(t, line, {**p, "Q4": 0.0, "Q10": abs(p["Q1"])})
        return
    if kind in ("21", "23", "24") or kind == "22" and (len(t.contours) > 1 or p.get("Q18", 0)):
        _sl_region_cycle(t, line, p)
        return
    if kind == "22":
        _rough_out(t, line, p)
        return
    if kind == "253":  # SLOT MILLING: 251's pocket Q218 x Q219 with half circles at the ends, turned by Q374
        _circular_pocket(t, line, {"Q215": 0.0, **p, "Q220": p["Q219"] / 2, "Q224": p.get("Q374", 0.0)})
        return
    if kind == "254":  # CIRCULAR SLOT: Q377 slots Q378 apart, each as a pocket of width Q219 along the arc
        if p.get("Q367", 0.0) or t.turns_over() or t.rot or t.scl != 1 or (t.factors != 1).any():
            raise ReferenceError("254 placed from the tool or under a transformation")
        for k in range(max(1, int(p.get("Q377", 1)))):
            _circular_pocket(t, line, {"Q215": 0.0, **p, "Q223": p["Q219"],
                                       "Q376": p["Q376"] + k * p.get("Q378", 0.0)})
        return
    if kind == "257":  # CIRCULAR STUD: 256's stud Q223 x Q223 rounded by Q223/2 (a circle) from the blank Q222
        d, blank = p["Q223"], p["Q222"]
        if p.get("Q376", -1.0) not in (-1.0, 0.0):
            raise ReferenceError("257 with a starting angle")
        _stud(t, line, {**p, "Q218": d, "Q219": d, "Q220": d / 2, "Q424": blank, "Q425": blank})
        return
    if kind != "200":
        _one_pass_cycle(t, line, kind, p)
        return
    surface, setup, depth = p["Q203"], p["Q200"], p["Q201"]
    plunge, second = p["Q202"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    clear = surface - sgn * setup
    _move_z(t, line, "rapid", clear, optional=True)
    levels = _levels(surface, surface + depth, sgn, plunge)
    for k, z in enumerate(levels):
        if k:
            _move_z(t, line, "rapid", clear)
            _dwell(t, line, p.get("Q210", 0.0))
            _move_z(t, line, "rapid", levels[k - 1] - sgn * setup)
        _move_z(t, line, "feed", z)
    _dwell(t, line, p.get("Q211", 0.0))
    _move_z(t, line, "rapid", clear)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _contour_elements(t: _Tnc) -> tuple[list[tuple], float]:
    """The programmed contour of cycle 14's label, as (line, kind, start, end, centre) [mm, machine], and its
    side (+1 RL, -1 RR, 0 R0): its blocks run on a copy of the machine without a tool radius."""
    blocks, labels = t.program
    s = copy.copy(t)
    s.out, s.pole, s.extra, s.q, s.comp, s.radius = [], t.pole.copy(), t.extra.copy(), dict(t.q), False, 0.0
    for line, b in blocks[labels[t.contour.upper()] + 1:]:
        up = b.upper()
        if re.match(r"LBL\s*0\b", up):
            break
        if _motion(s, line, up) is None:
            raise ReferenceError(f"contour block {b!r}")
    ends = [(e.line, e.kind, e.end, e.centre) for e in s.out]
    return [(ln, k, ends[i][2], end, c) for i, (ln, k, end, c) in enumerate(ends[1:])], s.side if s.comp else 0.0


def _offset_end(el: tuple, at_end: bool, side: float, radius: float) -> np.ndarray:
    """A contour element's end (or start) moved ``radius`` to the tool's side, square to the element."""
    _, kind, a, b, c = el
    x = b if at_end else a
    if kind in ("arc_ccw", "arc_cw"):
        r = (x - c)[:2] / np.linalg.norm((x - c)[:2])
        tan = np.array([-r[1], r[0]]) if kind == "arc_ccw" else np.array([r[1], -r[0]])
    else:
        tan = (b - a)[:2] / np.linalg.norm((b - a)[:2])
    out = x.copy()
    out[:2] += side * radius * np.array([-tan[1], tan[0]])
    return out


def _sl_region_cycle(t: _Tnc, line: int, p: dict) -> None:
    """21 PILOT DRILLING, 22 ROUGH-OUT of several contours (pockets and islands), 23 FLOOR FINISHING, 24 SIDE
    FINISHING: their paths (offset rings of the region) would repeat the reader's algorithm, so only their frame
    is checked: the rise to the clearance height Q7 first (FMAX), and the last row at Q7 within the pockets'
    bounding box (the end is checked to within the box's half diagonal); the tool's plane position after it is
    known only so far (the next moves that keep X or Y are checked within it)."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.mirror.prod() < 0 or t.rot:
        raise ReferenceError("SL cycle under a transformation")
    first, pts = t.contour, []
    for label in t.contours:
        if label in t.islands:  # CONTOUR DEF's islands lie within the pockets
            continue
        t.contour = label
        elements, _ = _contour_elements(t)
        for _, kind, a, b, c in elements:
            pts += [a[:2], b[:2]]
            if kind in ("arc_ccw", "arc_cw"):
                r = float(np.hypot(*(a - c)[:2]))
                pts += [c[:2] + [r, r], c[:2] - [r, r]]
    t.contour = first
    lo, hi = np.min(pts, axis=0), np.max(pts, axis=0)
    _move_z(t, line, "rapid", p["Q7"], optional=True)
    end = t.pos.copy()
    end[:2] = (lo + hi) / 2
    half = float(np.hypot(*(hi - lo))) / 2
    t.out.append(Expected(line=line, kind=None, end=end.copy(), tolerance=half, rows="last"))
    t.pos, t.loose = end, half


def _contour_train(t: _Tnc, line: int, p: dict) -> None:
    """25 CONTOUR TRAIN: per infeed (Q10 from the surface Q5 to the depth Q1): FMAX to the clearance height
    Q7, in the plane to the contour's first point moved R + Q3 square to its first element to the side of
    its RL/RR, Q11 down, the contour (each element's end R + Q3 from it), FMAX up to Q7. Q15 = +1 runs the
    contour with the tool left of it (an RR contour backwards), -1 with the tool right, 0 alternately from
    where the last pass ended (no retraction)."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.mirror.prod() < 0 or t.rot:
        raise ReferenceError("25 under a transformation")
    elements, side = _contour_elements(t)
    radius = (t.radius + p["Q3"] * t.scale) if side else 0.0
    start, end = _offset_end(elements[0], False, side, radius), _offset_end(elements[-1], True, side, radius)
    surface, depth, step = p["Q5"], p["Q1"], abs(p["Q10"])
    sgn = -1.0 if depth < 0 else 1.0
    levels = [surface + sgn * min(step * (k + 1), abs(depth)) for k in range(max(1, math.ceil(abs(depth) / step
                                                                                              - 1e-9)))]
    z0 = t.origin()[2]
    for k, level in enumerate(levels):
        back = k % 2 == 1 if p["Q15"] == 0 else side != 0 and (p["Q15"] > 0) != (side > 0)
        first = end if back else start
        if k == 0 or p["Q15"] != 0:
            _move_z(t, line, "rapid", p["Q7"], optional=True)
            t.emit(line, "rapid", np.array([first[0], first[1], t.pos[2]]), rows="optional" if np.allclose(
                first[:2], t.pos[:2]) else "one")
        _move_z(t, line, "feed", level)
        zm = z0 + level * t.scale
        run = [(ln, {"arc_ccw": "arc_cw", "arc_cw": "arc_ccw"}.get(kind, kind), b, a, c)
               for ln, kind, a, b, c in reversed(elements)] if back else elements
        for ln, kind, a, b, c in run:
            a, b = np.array([a[0], a[1], zm]), np.array([b[0], b[1], zm])
            c = None if c is None else np.array([c[0], c[1], zm])
            if not side:
                t.emit(ln, kind, b, centre=c)
                continue
            element = ("line", a, b) if c is None else ("arc", c, float(np.linalg.norm((b - c)[:2])), (0, 1), a, 0.0)
            t.out.append(Expected(line=ln, kind=None, end=b, tolerance=radius, rows="last", element=element))
        last = start if back else end
        t.pos = np.array([last[0], last[1], zm])
    _move_z(t, line, "rapid", p["Q7"])


def _ring(corners: list[np.ndarray], r: float, wall: float | None = None) -> tuple[np.ndarray, list[np.ndarray]] | None:
    """The ring ``r`` [mm] inside the counter-clockwise polygon ``corners`` (2-D), from the middle of its
    first edge: that start and, per edge (the first edge's second half first, its first half last, back at
    the start), where its offset ends (a convex corner: where the two offsets meet; a reflex corner: the
    offset's end, the arc about the corner belonging to the next edge). None when a point of it lies
    outside the polygon or nearer than r to an edge (edges and arcs sampled), or a point of the legs from and
    back to the start nearer than ``wall`` (default r): on the innermost ring of a pocket narrowing to a corner
    the middle of the first edge lies beyond the ring's own first edge, the legs run out to it along that
    edge's offset, still clear of the walls (seed 1102049: a triangle of inradius 12.3 mm, rings 2 mm apart, the
    ring at 12 clears its middle)."""
    n = len(corners)
    units = [(corners[(i + 1) % n] - corners[i]) / np.linalg.norm(corners[(i + 1) % n] - corners[i])
             for i in range(n)]
    left = [np.array([-u[1], u[0]]) for u in units]
    start = (corners[0] + corners[1 % n]) / 2 + r * left[0]
    ends, dense, here = [], [start[None]], start
    for i in range(n):
        j = (i + 1) % n
        corner = corners[j]
        if units[i][0] * units[j][1] - units[i][1] * units[j][0] > 1e-12:  # convex: the offsets meet
            a, b = corner + r * left[i], corner + r * left[j]
            end = a + units[i] * np.linalg.solve(np.array([units[i], -units[j]]).T, b - a)[0]
            arc = np.empty((0, 2))
        else:
            end = corner + r * left[i]
            a0, a1 = (math.atan2(v[1], v[0]) for v in (left[i], left[j]))
            sweep = (a1 - a0) % (2 * math.pi) - 2 * math.pi  # clockwise about a reflex corner
            angles = a0 + sweep * np.linspace(0, 1, 40)
            arc = corner + r * np.stack([np.cos(angles), np.sin(angles)], axis=1)
        dense += [np.linspace(here, end, 40), arc]
        ends.append(end)
        here = arc[-1] if len(arc) else end
    legs = np.concatenate([dense[1], np.linspace(here, start, 40)])  # out from and back to the start
    dense = dense[2:]
    ends.append(start)
    return (start, ends) if _far_inside(np.concatenate(dense), corners, r) and _far_inside(
        legs, corners, r if wall is None else wall) else None


def _rounded(start: np.ndarray, ends: list[np.ndarray], r: float) -> list[np.ndarray]:
    """Cycle 20's Q8 on a counter-clockwise ring of straight edges (all its corners convex): each corner's end
    moved along the next edge to where the rounding arc of ``r`` [mm] ends, ``r tan(turn / 2)`` from the corner
    (the arc belongs to the edge before). A reflex corner, or a rounding longer than its edges, is refused."""
    pts = [start, *ends]
    trims = []
    for k in range(len(ends) - 1):
        u, v = (b - a for a, b in ((pts[k], pts[k + 1]), (pts[k + 1], pts[k + 2])))
        u, v = u / np.linalg.norm(u), v / np.linalg.norm(v)
        if u[0] * v[1] - u[1] * v[0] <= 1e-9:
            raise ReferenceError("Q8 on a ring with a reflex or straight corner")
        trims.append(r * math.tan(math.acos(float(np.clip(u @ v, -1.0, 1.0))) / 2))
    lengths = [float(np.linalg.norm(b - a)) for a, b in zip(pts, pts[1:])]
    if any(d > lengths[k + 1] - (trims[k + 1] if k + 1 < len(trims) else 0.0) + 1e-9 or d > lengths[k] - (
            trims[k - 1] if k else 0.0) + 1e-9 for k, d in enumerate(trims)):
        raise ReferenceError("Q8 longer than the ring's edges")
    out = list(ends)
    for k, d in enumerate(trims):
        v = pts[k + 2] - pts[k + 1]
        out[k] = pts[k + 1] + v / np.linalg.norm(v) * d
    return out


def _far_inside(pts: np.ndarray, corners: list[np.ndarray], r: float) -> bool:
    """All ``pts`` (n, 2) inside the polygon and at least ``r`` [mm] (less 1 um) from its edges."""
    poly = np.array(corners)
    inside = np.zeros(len(pts), bool)
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0)):
        crosses = (y0 > pts[:, 1]) != (y1 > pts[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            inside ^= crosses & (pts[:, 0] < x0 + (pts[:, 1] - y0) * (x1 - x0) / (y1 - y0))
    a, u = poly, np.roll(poly, -1, axis=0) - poly
    tt = np.clip(np.einsum("nkd,kd->nk", pts[:, None, :] - a[None], u) / np.einsum("kd,kd->k", u, u), 0, 1)
    dist = np.min(np.linalg.norm(pts[:, None, :] - (a[None] + tt[..., None] * u[None]), axis=2), axis=1)
    return bool(np.all(inside) and dist.min() >= r - 1e-6)


def _pocket_rings(corners: list[np.ndarray], r0: float, step: float) -> list[tuple]:
    """The rings of :func:`_ring` from ``r0`` in steps of ``step`` [mm] while one fits and the straight step
    from its start out to the previous ring's start keeps the previous ring's distance."""
    rings: list[tuple] = []
    while len(rings) < 10_000 and (ring := _ring(corners, r0 + len(rings) * step, r0)) is not None:
        if rings and not _far_inside(np.linspace(ring[0], rings[-1][0], 40), corners, r0 + (len(rings) - 1) * step):
            break
        rings.append(ring)
    return rings


def _rough_out(t: _Tnc, line: int, p: dict) -> None:
    """22 ROUGH-OUT, one pocket of straight edges: rings R + Q3 + k Q2 R inside it while one fits
    (:func:`_pocket_rings`), run from the innermost out in the sense Q9 (+1 counter-clockwise), each from
    the middle of the first edge; per depth (Q10 down to Q1 less Q4): FMAX to Q7 (the first), over the
    innermost start, to Q6 above Q5, Q11 down, the rings (each edge's end exact), up to Q6 above Q5 (at Q208 when
    written, not MAX); Q7."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.mirror.prod() < 0 or t.rot:
        raise ReferenceError("22 under a transformation")
    elements, _ = _contour_elements(t)
    if any(k not in ("feed", "rapid") for _, k, _, _, _ in elements):
        raise ReferenceError("22 with arcs")
    if elements and not np.allclose(elements[-1][3][:2], elements[0][2][:2]):  # SL contours close (b6dce84)
        end = elements[-1][3].copy()
        end[:2] = elements[0][2][:2]
        elements.append((elements[-1][0], "feed", elements[-1][3], end, None))
    corners, lines = [a[:2] for _, _, a, _, _ in elements], [ln for ln, _, _, _, _ in elements]
    area = sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(corners, corners[1:] + corners[:1]))
    ccw = p["Q9"] >= 0
    if (area > 0) != ccw:  # the other way round: the edges from their ends
        corners, lines = [b[:2] for _, _, _, b, _ in reversed(elements)], lines[::-1]
    flip = np.array([1.0, 1.0 if ccw else -1.0])  # a clockwise run: the rings of the mirrored pocket
    rings = _pocket_rings([c * flip for c in corners], t.radius + p["Q3"] * t.scale, p["Q2"] * t.radius)
    if p.get("Q8", 0.0):
        rings = [(start, _rounded(start, ends, abs(p["Q8"]) * t.scale)) for start, ends in rings]
    sgn = -1.0 if p["Q1"] < 0 else 1.0
    levels = _levels(p["Q5"], p["Q5"] + sgn * (abs(p["Q1"]) - abs(p["Q4"])), sgn, abs(p["Q10"]))
    above = p["Q5"] - sgn * abs(p["Q6"])
    _move_z(t, line, "rapid", p["Q7"], optional=True)
    for level in levels:
        zm = t.origin()[2] + level * t.scale
        first = rings[-1][0] * flip
        t.emit(line, "rapid", np.array([*first, t.pos[2]]), rows="optional" if np.allclose(first, t.pos[:2])
               else "one")
        _move_z(t, line, "rapid", above, optional=True)
        _move_z(t, line, "feed", level)
        for start, ends in rings[::-1]:
            t.emit(line, "feed", np.array([*(start * flip), zm]), rows="optional" if np.allclose(
                start * flip, t.pos[:2]) else "one")
            for k, end in enumerate(ends):
                if k + 1 < len(ends) and lines[(k + 1) % len(lines)] == lines[k % len(lines)]:
                    continue  # the closing line is its last block's: one row "last" covers both edges
                t.out.append(Expected(line=lines[k % len(lines)], kind=None, end=np.array([*(end * flip), zm]),
                                      rows="last"))
            t.pos = np.array([*(start * flip), zm])
        # up at the iTNC 530's retraction feed Q208 (0: Q12's; MAX or none written: FMAX) (tncwild39)
        _move_z(t, line, "rapid" if math.isinf(p.get("Q208", math.inf)) else "feed", above)
    _move_z(t, line, "rapid", p["Q7"])


def _bore_milling(t: _Tnc, line: int, p: dict) -> None:
    """208: to the set-up clearance, along the reference axis to the helix radius Q335/2 - R, the helix
    (Q334 per turn, Q351 >= 0 counter-clockwise) down to the depth, one more turn, back to the centre,
    rapid out (set-up clearance, then Q204)."""
    if t.scl != 1 or not np.all(t.factors == 1):
        raise ReferenceError("208 under scaling")
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    clear = surface - sgn * setup
    _move_z(t, line, "rapid", clear, optional=True)
    centre = t.prog()
    r = p["Q335"] * t.scale / 2 - t.radius
    bottom = (surface + depth) * t.scale
    if r > 1e-9:
        t.emit(line, "feed", t.machine(centre + np.array([r, 0.0, 0.0])))
        angle = math.radians(360.0 * abs(depth + sgn * setup) / p["Q334"]) * (1 if p.get("Q351", 1) >= 0 else -1)
        end = centre + np.array([r * math.cos(angle), r * math.sin(angle), 0.0])
        end[2] = bottom
        ccw = (angle > 0) != t.turns_over()
        for _ in range(2):
            t.emit(line, "arc_ccw" if ccw else "arc_cw", t.machine(end),
                   centre=t.machine(np.array([centre[0], centre[1], bottom])))
        centre[2] = bottom
        t.emit(line, "feed", t.machine(centre))
    else:
        _move_z(t, line, "feed", surface + depth)
    _move_z(t, line, "rapid", clear)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _point_depth(t: _Tnc, kind: str, p: dict) -> dict:
    """The parameters with Q201 the tip's depth: 200/203/205 with Q395 = 1 measure Q201 to the drill's full
    diameter, the tip lies R / tan(T-ANGLE / 2) deeper; 240 with Q343 = 1 centres to the diameter Q344 (its sign
    the direction), to the depth |Q344| / 2 / tan(T-ANGLE / 2). T-ANGLE from the context's tool table."""
    if not (p.get("Q343", 0.0) if kind == "240" else p.get("Q395", 0.0)):
        return p
    tool = t.ctx.tool(t.tool)
    if tool is None or not tool.point_angle:
        raise ReferenceError("a depth from the point angle of a tool without one")
    tan = math.tan(math.radians(tool.point_angle) / 2)
    if kind == "240":
        return {**p, "Q201": math.copysign(abs(p["Q344"]) / 2 / tan, p["Q344"])}
    return {**p, "Q201": math.copysign(abs(p["Q201"]) + t.radius / t.scale / tan, p["Q201"])}


def _peck_depths(total: float, peck: float, decrement: float, smallest: float) -> list[float]:
    """The depths [mm, from the surface] reached by the pecks of 203/205."""
    out, z = [], 0.0
    while total - z > _EPS:
        z = min(z + peck, total)
        out.append(z)
        if decrement:
            peck = max(peck - decrement, smallest, 1e-3)
    return out


def _universal_drilling(t: _Tnc, line: int, kind: str, p: dict) -> None:
    """203/205: pecks of Q202 shrinking by Q212 to at least Q205; between pecks out to the set-up clearance
    (203: at Q208, 0: Q206; 205: rapid), dwell Q210, rapid back to the set-up clearance (205: Q258) above
    the last depth; 203: Q213 chip breaks (back Q256) before each full retraction; 205: a chip break (back
    Q256 at rapid) after every Q257 within a peck; dwell Q211 at the bottom, out, then to Q204. 205 with a deepened
    starting point Q379: at Q253 (MAX: rapid) to Q200 above it, the pecks from there on."""
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    clear, bottom = surface - sgn * setup, surface + depth
    back = "feed" if kind == "203" and not math.isinf(p.get("Q208", 0.0)) else "rapid"  # Q208=MAX: rapid
    advance = setup if kind == "203" else abs(p.get("Q258", 0.2))
    chip, every = abs(p.get("Q256", 0.2)), abs(p.get("Q257", 0.0)) if kind == "205" else 0.0
    breaks = int(p.get("Q213", 0)) if kind == "203" else 0
    _move_z(t, line, "rapid", clear, optional=True)
    start = abs(p.get("Q379", 0.0)) if kind == "205" else 0.0
    if start:
        _move_z(t, line, "rapid" if math.isinf(p["Q253"]) else "feed", surface + sgn * (start - setup))
    peck, z, n = abs(p["Q202"]) or abs(depth), surface + sgn * start, 0
    depths = _peck_depths(abs(depth) - start, peck, abs(p.get("Q212", 0.0)), abs(p.get("Q205", 0.0)))
    last = abs(p["Q259"]) if kind == "205" and "Q259" in p else advance
    entry = 0
    while (bottom - z) * sgn > _EPS:
        if n == 0 and z != surface + sgn * start:
            _dwell(t, line, p.get("Q210", 0.0))
            # 205: Q258 at the first re-entry to Q259 at the last, in equal steps
            step = advance + (last - advance) * entry / (len(depths) - 2) if len(depths) > 2 else advance
            entry += 1
            if (z - sgn * step - clear) * sgn > 0:
                _move_z(t, line, "rapid", z - sgn * step)
        target = bottom if (bottom - z - sgn * peck) * sgn <= _EPS else z + sgn * peck
        mark = z + sgn * every
        while every > 0 and (target - mark) * sgn > _EPS:
            _move_z(t, line, "feed", mark)
            _move_z(t, line, "rapid", mark - sgn * chip)
            mark += sgn * every
        _move_z(t, line, "feed", target)
        z = target
        if p.get("Q212", 0.0):
            peck = max(peck - abs(p["Q212"]), abs(p.get("Q205", 0.0)), 1e-3)
        if (bottom - z) * sgn <= _EPS:
            break
        if n < breaks:
            n += 1
            _move_z(t, line, back, z - sgn * chip)
            continue
        n = 0
        _move_z(t, line, back, clear)
    _dwell(t, line, p.get("Q211", 0.0))
    _move_z(t, line, back, clear)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _to_shape_centre(t: _Tnc, line: int, kind: str, p: dict) -> None:
    """Q367 = 1..4 of 251 / 256 (the tool at the lower left, lower right, upper right, upper left corner) and 253
    (the tool at the slot's left end, its left circle's centre, its right circle's centre, its right end), the
    shape turned by Q224 / Q374 about the tool: up to the set-up clearance if below it, then at FMAX over the
    centre, as the reader reads the TNC 640 cycle manual's Q367."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.turns_over() or t.rot:
        raise ReferenceError(f"{kind} with Q367 under a transformation")
    n = int(p["Q367"])
    if kind == "253":
        tool = {1: -p["Q218"] / 2, 2: p["Q219"] / 2 - p["Q218"] / 2, 3: p["Q218"] / 2 - p["Q219"] / 2,
                4: p["Q218"] / 2}[n] + 0j
        turn = p.get("Q374", 0.0)
    else:
        tool = complex(p["Q218"] * (1 if n in (2, 3) else -1), p["Q219"] * (1 if n in (3, 4) else -1)) / 2
        turn = p.get("Q224", 0.0)
    here = t.prog()
    centre = complex(*here[:2]) - tool * t.scale * cmath.exp(1j * math.radians(turn))
    clear = p["Q203"] - (-1.0 if p["Q201"] < 0 else 1.0) * p["Q200"]
    if (here[2] / t.scale - clear) * (1.0 if p["Q201"] < 0 else -1.0) < 0:
        _move_z(t, line, "rapid", clear)
    t.emit(line, "rapid", t.machine(np.array([centre.real, centre.imag, t.prog()[2]])))


def _circular_pocket(t: _Tnc, line: int, p: dict) -> None:
    """252 (Q366 = 0): at each depth of Q202 (to the depth less Q369) from the centre out along +X in steps of
    Q370 x R to circles up to Q223/2 - Q368 - R, then up by Q200 and back over the centre; finishing the wall
    (Q215 = 2, or 0 with Q368 > 0) at each depth of Q338: half circle out to Q223/2 - R, full circle, half
    circle back; the floor (Q215 = 2, or 0 with Q369 > 0) with the circles out to Q223/2 - R at the depth."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.turns_over() or t.rot:
        raise ReferenceError("252 under a transformation")
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    op, side, floor = int(p["Q215"]), p.get("Q368", 0.0), p.get("Q369", 0.0)
    kind = "arc_ccw" if p.get("Q351", 1) >= 0 else "arc_cw"
    wall = (p["Q223"] if "Q218" not in p else min(p["Q218"], p["Q219"])) * t.scale / 2 - t.radius
    step = p.get("Q370", 1.0) * t.radius or wall
    clear = surface - sgn * setup
    slot = "Q375" in p  # 254: over the slot's first end
    if slot:
        pc, rp = np.array([p["Q216"], p["Q217"]]) * t.scale, p["Q375"] * t.scale / 2
        t.emit(line, "rapid", t.machine(np.array([*(pc + rp * _unit(p["Q376"])), t.prog()[2]])), rows="optional")
    _move_z(t, line, "rapid", clear, optional=True)
    centre = t.prog()

    def depths(bottom: float, each: float) -> list[float]:
        return _levels(surface, bottom, sgn, each)

    def rings(radius: float) -> None:
        if "Q218" in p:
            return _rectangles(t, line, p, centre, kind, radius, step)
        if slot:
            h = 0.0
            while h < radius - 1e-9:
                h = min(h + step, radius)
                _slot_ring(t, line, p, kind, h)
            return
        r = 0.0
        while r < radius - 1e-9:
            r = min(r + step, radius)
            at = np.array([centre[0] + r, centre[1], t.prog()[2]])
            t.emit(line, "feed", t.machine(at))
            t.emit(line, kind, t.machine(at), centre=t.machine(np.array([centre[0], centre[1], at[2]])))

    def back(z: float) -> None:
        _move_z(t, line, "rapid", z + -sgn * setup)
        here = t.prog()
        t.emit(line, "rapid", t.machine(np.array([centre[0], centre[1], here[2]])), rows="optional")

    if op in (0, 1):
        for z in depths(surface + depth - sgn * floor, p["Q202"] or abs(depth)):
            _plunge(t, line, p, centre, z, wall - side * t.scale, kind)
            rings(wall - side * t.scale)
            back(z)
    if op == 2 or (op == 0 and (side > 0 or p.get("wall only"))):
        for z in depths(surface + depth, p.get("Q338", 0.0) or abs(depth)):
            _move_z(t, line, "feed", z, optional=True)  # none when the roughing left the tool there (Q338 = Q200)
            mid = t.prog()
            if slot:
                _slot_ring(t, line, p, kind, wall)
                t.emit(line, "feed", t.machine(mid))
                continue
            if "Q218" in p:
                half = (p["Q218"] * t.scale / 2 - t.radius, p["Q219"] * t.scale / 2 - t.radius)
                _rectangle(t, line, p, mid, kind, half, max(p.get("Q220", 0.0) * t.scale - t.radius, 0.0))
                t.emit(line, "feed", t.machine(mid))
                continue
            out = mid + np.array([wall, 0.0, 0.0])
            for end, pole in ((out, mid + np.array([wall / 2, 0.0, 0.0])), (out, mid),
                              (mid, mid + np.array([wall / 2, 0.0, 0.0]))):
                t.emit(line, kind, t.machine(end), centre=t.machine(pole))
    if (op == 2 and not p.get("wall only")) or (op == 0 and floor > 0):
        _move_z(t, line, "feed", surface + depth, optional=True)
        rings(wall)
        back(surface + depth)
    _move_z(t, line, "rapid", clear)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _over_centre(t: _Tnc, line: int, p: dict) -> None:
    """212-215, 210: at FMAX along Z to Q203 + max(Q200, Q204), then over the centre Q216, Q217."""
    sgn = -1.0 if p["Q201"] < 0 else 1.0
    _move_z(t, line, "rapid", p["Q203"] - sgn * max(p["Q200"], p["Q204"]), optional=True)
    t.emit(line, "rapid", t.machine(np.array([p["Q216"] * t.scale, p["Q217"] * t.scale, t.prog()[2]])),
           rows="optional")


def _old_slot(t: _Tnc, line: int, kind: str, p: dict) -> None:
    """The old slots (TNC 426/430 manual, cycles 210, 211) as read for vcnc: 210 as 253 over the centre Q216/Q217
    with the reciprocating plunge (Q366 = 2), 211 as 254 on the pitch circle Q244; climbing, the wall finished
    without a floor pass, Q207 also the plunging feed."""
    base = {**p, "Q206": p["Q207"], "Q351": 1.0, "Q368": 0.0, "Q369": 0.0, "Q370": 1.0, "wall only": True}
    if kind == "210":
        _over_centre(t, line, p)
        _circular_pocket(t, line, {**base, "Q220": p["Q219"] / 2, "Q366": 2.0})
    else:
        _circular_pocket(t, line, {**base, "Q375": p["Q244"], "Q376": p["Q245"], "Q223": p["Q219"]})


def _finishing(t: _Tnc, line: int, kind: str, p: dict) -> None:
    """The old finishing cycles (TNC 426/430 manual, cycles 212-215; TNC 370 manual p. 8-20): over the centre
    (:func:`_over_centre`); 212/214: 251's/252's wall finishing (no floor) at each plunging depth Q202, climbing;
    213/215: 256's/257's one revolution at the finished size at each Q202, the start Q221 (213) or (Q222 - Q223)
    / 2 (215) beyond the stud plus R, and at the end back over the centre."""
    _over_centre(t, line, p)
    base = {**p, "Q338": p["Q202"], "Q351": 1.0, "Q368": 0.0, "Q369": 0.0, "Q370": 1.0}
    if kind in ("212", "214"):
        _circular_pocket(t, line, {**base, "Q215": 2, "wall only": True})
        return
    if kind == "213":
        _stud(t, line, {**base, "Q215": 1, "Q424": p["Q218"], "Q425": p["Q219"], "lead": p.get("Q221", 0.0)})
    else:
        d = p["Q223"]
        _stud(t, line, {**base, "Q215": 1, "Q218": d, "Q219": d, "Q220": d / 2, "Q424": d, "Q425": d,
                        "lead": (p["Q222"] - d) / 2})
    _over_centre(t, line, p)


def _plunge(t: _Tnc, line: int, p: dict, centre: np.ndarray, z: float, room: float, kind: str) -> None:
    """Q366 of 251-254: 0 vertical; 1 one helix turn on R (at most ``room``) about the centre, out and back
    along +X; 2 (251/253) along the turned reference axis: out to the room, to the other side halfway down,
    back, then to the centre."""
    mode, here = int(p.get("Q366", 0)), t.prog()
    side = p.get("Q368", 0.0) * t.scale
    reach = min(t.radius or room, room) if mode == 1 else p.get("Q218", 0.0) * t.scale / 2 - side - t.radius
    if mode == 0 or reach <= 1e-9:
        _move_z(t, line, "feed", z)
        return
    a = math.radians(p.get("Q224", 0.0)) if mode == 2 else 0.0

    def pt(u: float, zz: float) -> np.ndarray:
        return t.machine(np.array([centre[0] + u * math.cos(a), centre[1] + u * math.sin(a), zz]))

    t.emit(line, "feed", pt(reach, here[2]))
    if mode == 1:
        t.emit(line, kind, pt(reach, z * t.scale), centre=pt(0.0, z * t.scale))
    else:
        t.emit(line, "feed", pt(-reach, (here[2] + z * t.scale) / 2))
        t.emit(line, "feed", pt(reach, z * t.scale))
    t.emit(line, "feed", pt(0.0, z * t.scale))


def _slot_ring(t: _Tnc, line: int, p: dict, kind: str, h: float) -> None:
    """254: round the slot at ``h`` from its centre line: out along the radius at the first end, then (ccw) the
    outer arc, the far end's half circle, the inner arc back, the first end's half circle; cw reversed."""
    pc, rp = np.array([p["Q216"], p["Q217"]]) * t.scale, p["Q375"] * t.scale / 2
    a0, sweep, z = p["Q376"], p["Q248"], t.prog()[2]

    def at(r: float, a: float) -> np.ndarray:
        return t.machine(np.array([*(pc + r * _unit(a)), z]))

    t.emit(line, "feed", at(rp + h, a0))
    e0, e1, mid = at(rp, a0), at(rp, a0 + sweep), t.machine(np.array([*pc, z]))
    legs = [(at(rp + h, a0 + sweep), mid, "arc_ccw"), (at(rp - h, a0 + sweep), e1, "arc_ccw"),
            (at(rp - h, a0), mid, "arc_cw"), (at(rp + h, a0), e0, "arc_ccw")]
    if kind == "arc_cw":
        legs = [(at(rp - h, a0), e0, "arc_cw"), (at(rp - h, a0 + sweep), mid, "arc_ccw"),
                (at(rp + h, a0 + sweep), e1, "arc_cw"), (at(rp + h, a0), mid, "arc_cw")]
    for end, pole, turn in legs:
        t.emit(line, turn, end, centre=pole)


def _stud(t: _Tnc, line: int, p: dict) -> None:
    """256: rapid to 2 mm + R right of the blank Q424/2, FMAX to Q200, at each depth of Q202 (to the depth
    less Q369): a half circle (counter-clockwise for climb) onto the first revolution, revolutions from the
    blank (Q424 x Q425 + 2R) to the stud grown by Q368 + R in equal steps of at most Q370 x R, clockwise
    for climb, a half circle back to the start (not for Q215 = 2, finishing only); finishing (Q215 = 2, or 0
    with Q368 > 0): the same with one
    revolution round the stud grown by R at each depth of Q338; FMAX out (set-up clearance, Q204)."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.turns_over() or t.rot or p.get("Q224", 0.0):
        raise ReferenceError("256 under a transformation or turned")
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    op, side = int(p.get("Q215", 0)), p.get("Q368", 0.0) * t.scale
    R = t.radius
    kind = "arc_cw" if p.get("Q351", 1) >= 0 else "arc_ccw"
    back = "arc_ccw" if kind == "arc_cw" else "arc_cw"
    a0, b0 = p["Q218"] * t.scale / 2 + side + R, p["Q219"] * t.scale / 2 + side + R
    span = max(p["Q424"] * t.scale / 2 + R - a0, p["Q425"] * t.scale / 2 + R - b0, 0.0)
    n = max(1, math.ceil(span / (p.get("Q370", 1.0) * R or span or 1.0) - 1e-9))
    centre = t.prog()
    lead = p["lead"] * t.scale if "lead" in p else 2.0  # 256: 2 mm beyond the blank
    start = centre + np.array([p["Q424"] * t.scale / 2 + lead + R, 0.0, 0.0])
    t.emit(line, "rapid", t.machine(start), rows="optional")
    _move_z(t, line, "rapid", surface - sgn * setup, optional=True)
    jobs = [(z, [j * span / n for j in range(n - 1, -1, -1)])
            for z in _levels(surface, surface + depth - sgn * p.get("Q369", 0.0), sgn, p["Q202"] or abs(depth))
            if op != 2]  # Q215 = 2: finishing only
    if op == 2 or (op == 0 and side > 0):
        jobs += [(z, [-side]) for z in _levels(surface, surface + depth, sgn, p.get("Q338", 0.0) or abs(depth))]
    for z, offs in jobs:
        _move_z(t, line, "feed", z, optional=True)
        here = t.prog()
        for i, off in enumerate(offs):
            a = a0 + off
            on = np.array([centre[0] + a, centre[1], here[2]])
            if i == 0 and np.hypot(*(on - here)[:2]) > 1e-9:  # no lead (213 Q221 = 0): no half circle
                t.emit(line, back, t.machine(on), centre=t.machine((on + here) / 2))
            _rectangle(t, line, {"Q224": 0.0}, np.array([centre[0], centre[1], here[2]]),
                       "arc_ccw" if kind == "arc_ccw" else "arc_cw", (a, b0 + off),
                       max(p.get("Q220", 0.0) * t.scale + side + R + off, 0.0))
        end = np.array([start[0], start[1], here[2]])
        if np.hypot(*(end - t.prog())[:2]) > 1e-9:
            t.emit(line, back, t.machine(end), centre=t.machine((end + t.prog()) / 2))
    _move_z(t, line, "rapid", surface - sgn * setup)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _rectangles(t: _Tnc, line: int, p: dict, centre: np.ndarray, kind: str, wall: float, step: float) -> None:
    """251's rings: ``wall`` is the 252-style radius (min side / 2 - allowance - R); the outer rectangle is
    the pocket less the same allowance and R, the inner ones offset inward by min half side / n each, n the
    rings needed at ``step`` apart."""
    allowance = min(p["Q218"], p["Q219"]) * t.scale / 2 - t.radius - wall
    a, b = (p["Q218"] * t.scale / 2 - allowance - t.radius, p["Q219"] * t.scale / 2 - allowance - t.radius)
    n = max(1, math.ceil(min(a, b) / step - 1e-9))
    corner = max(p.get("Q220", 0.0) * t.scale - allowance - t.radius, 0.0)
    here = t.prog()
    for j in range(n - 1, -1, -1):
        off = j * min(a, b) / n
        _rectangle(t, line, p, np.array([centre[0], centre[1], here[2]]), kind, (a - off, b - off),
                   max(corner - off, 0.0))


def _rectangle(t: _Tnc, line: int, p: dict, centre: np.ndarray, kind: str, half: tuple, corner: float) -> None:
    """A line to (a, 0), then once round the rectangle (corners rounded by ``corner``) back to (a, 0); local
    axes turned by Q224, v mirrored for clockwise milling."""
    a, b = half
    r = min(corner, a, b)
    s = 1.0 if kind == "arc_ccw" else -1.0
    ang = math.radians(p.get("Q224", 0.0))

    def pt(u: float, v: float) -> np.ndarray:
        v *= s
        return t.machine(centre + np.array([u * math.cos(ang) - v * math.sin(ang),
                                            u * math.sin(ang) + v * math.cos(ang), 0.0]))

    def go(u: float, v: float) -> None:
        if np.linalg.norm(pt(u, v) - t.pos) > 1e-12:
            t.emit(line, "feed", pt(u, v))

    go(a, 0.0)
    for (u0, v0), (cu, cv), (u1, v1) in (((a, b - r), (a - r, b - r), (a - r, b)),
                                         ((-a + r, b), (-a + r, b - r), (-a, b - r)),
                                         ((-a, -b + r), (-a + r, -b + r), (-a + r, -b)),
                                         ((a - r, -b), (a - r, -b + r), (a, -b + r))):
        go(u0, v0)
        if r > 1e-12:
            t.emit(line, kind, pt(u1, v1), centre=pt(cu, cv))
    go(a, 0.0)


def _thread_milling(t: _Tnc, line: int, p: dict) -> None:
    """262: to the set-up clearance, Q253 to the starting plane, a half circle out to the radius Q335/2 - R
    on the +X side, the helix (Q351 >= 0 counter-clockwise; upward for a right-hand thread climb-milled or
    a left-hand one up-cut; Q355 = 0 one pitch at the depth, 1 between the depth and the surface), a half
    circle back to the centre, rapid out (set-up clearance, then Q204)."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.turns_over() or t.rot:
        raise ReferenceError("262 under a transformation")
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    pitch, ccw = abs(p["Q239"]), p["Q351"] >= 0
    sgn = -1.0 if depth < 0 else 1.0
    clear = surface - sgn * setup
    _move_z(t, line, "rapid", clear, optional=True)
    kind = "arc_ccw" if ccw else "arc_cw"
    r = p["Q335"] * t.scale / 2 - t.radius
    for z0, z1 in _thread_turns(surface, depth, pitch, p["Q355"], (p["Q239"] > 0) == ccw):
        _move_z(t, line, "feed", z0)
        centre = t.prog()  # [mm], at the starting plane
        angle = math.radians(360.0 * abs(z1 - z0) / pitch) * (1 if ccw else -1)
        axis_end = np.array([centre[0], centre[1], z1 * t.scale])
        helix_end = axis_end + np.array([r * math.cos(angle), r * math.sin(angle), 0.0])
        for end, pole in ((centre + np.array([r, 0.0, 0.0]), centre + np.array([r / 2, 0.0, 0.0])),
                          (helix_end, axis_end), (axis_end, (helix_end + axis_end) / 2)):
            t.emit(line, kind, t.machine(end), centre=t.machine(pole))
    _move_z(t, line, "rapid", clear)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _thread_turns(surface: float, depth: float, pitch: float, steps: float, up: bool) -> list[tuple[float, float]]:
    """The (from, to) levels of the helices of 262/267: Q355 = 1 one between the depth and the surface; else one
    pitch at the depth, and with Q355 = n > 1 one more every n pitches above it while its deep end is below the
    surface (TNC 426/430 manual p. 251: "several helical paths ... offsets the tool by Q355, multiplied by the
    pitch"); ``up``: each from its deep end, the deepest first; else each down to it, the highest first."""
    sgn = -1.0 if depth < 0 else 1.0
    if steps == 1:
        return [(surface + depth, surface)] if up else [(surface, surface + depth)]
    deep = [abs(depth) - k * steps * pitch for k in range(int(abs(depth) // (steps * pitch)) + 2)] if steps > 1 \
        else [abs(depth)]
    turns = [(surface + sgn * u, surface + sgn * (u - pitch)) for u in deep if u > 1e-9]
    return turns if up else [(b, a) for a, b in reversed(turns)]


def _thread_family(t: _Tnc, line: int, kind: str, p: dict) -> None:
    """263/264/265/267, in the manuals' order: to the set-up clearance; 264: the hole drilled as cycle 205 to
    Q356; 263 with Q356: at Q253 to Q356 less Q200 (with Q357: to Q356), at Q254 to Q356, then a half
    circle out to the thread's radius, a full circle and a half circle back; with Q358: at Q253 (265 before
    the thread: Q254) to Q358 and the same circles on the radius Q359 (265 with Q360 = 1: after the thread);
    the thread as 262 (263, 264 one pitch; 265 from the surface down to the depth, clockwise for a
    right-hand thread; 267 about a stud on Q335/2 + R, clockwise for climb, from a point one pitch outside,
    the half circles against the helix, the departure out along the end radius); rapid out."""
    if t.scl != 1 or not np.all(t.factors == 1) or t.turns_over() or t.rot:
        raise ReferenceError(f"{kind} under a transformation")
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    clear, pitch = surface - sgn * setup, abs(p["Q239"])
    outside, right = kind == "267", p["Q239"] > 0
    climb = (p.get("Q351", 1.0) >= 0) if kind != "265" else not right
    ccw = climb != outside
    spin = "arc_ccw" if ccw else "arc_cw"
    r = p["Q335"] * t.scale / 2 + (t.radius if outside else -t.radius)
    _move_z(t, line, "rapid", clear, optional=True)
    centre = t.prog()

    def circle(radius: float) -> None:
        if radius <= 1e-12:
            return
        c = np.array([centre[0], centre[1], t.prog()[2]])
        on = c + np.array([radius, 0.0, 0.0])
        for end, pole in ((on, c + np.array([radius / 2, 0.0, 0.0])), (on, c), (c, c + np.array([radius / 2, 0, 0]))):
            t.emit(line, spin, t.machine(end), centre=t.machine(pole))

    if kind == "264":
        _universal_drilling(t, line, "205", {"Q203": surface, "Q200": setup, "Q201": sgn * abs(p["Q356"]),
                                             "Q202": p.get("Q202", 0.0), "Q258": p.get("Q258", 0.0),
                                             "Q257": p.get("Q257", 0.0), "Q256": p.get("Q256", 0.0)})
    if kind == "263" and p.get("Q356", 0.0):
        sink = surface + sgn * abs(p["Q356"])
        if not p.get("Q357", 0.0):
            _move_z(t, line, "feed", sink - sgn * setup)
        _move_z(t, line, "feed", sink)
        circle(r)
    front, after = sgn * abs(p.get("Q358", 0.0)), kind == "265" and p.get("Q360", 0.0) == 1
    if front and not after:
        _move_z(t, line, "feed", surface + front)
        circle(abs(p.get("Q359", 0.0)) * t.scale)
    steps = 1.0 if kind == "265" else p.get("Q355", 0.0) if kind == "267" else 0.0
    half = spin if not outside else ("arc_cw" if ccw else "arc_ccw")
    out = r + pitch * t.scale if outside else 0.0
    if outside:
        t.emit(line, "rapid", t.machine(centre + np.array([out, 0.0, 0.0])))
    for z0, z1 in _thread_turns(surface, depth, pitch, steps, (right == climb) != outside):
        angle = math.radians(360.0 * abs(z1 - z0) / pitch) * (1 if ccw else -1)
        _move_z(t, line, "feed", z0)
        here = t.prog()
        axis_end = np.array([centre[0], centre[1], z1 * t.scale])
        on = np.array([centre[0] + r, centre[1], z0 * t.scale])
        helix_end = axis_end + np.array([r * math.cos(angle), r * math.sin(angle), 0.0])
        back = axis_end + (helix_end - axis_end) * (out / r) if outside else axis_end
        t.emit(line, half, t.machine(on), centre=t.machine((here + on) / 2))
        t.emit(line, spin, t.machine(helix_end), centre=t.machine(axis_end))
        t.emit(line, half, t.machine(back), centre=t.machine((helix_end + back) / 2))
    if front and after:
        _move_z(t, line, "feed", surface + front)
        circle(abs(p.get("Q359", 0.0)) * t.scale)
    _move_z(t, line, "rapid", clear)
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _back_boring(t: _Tnc, line: int, p: dict) -> None:
    """204: rapid to Q203 + Q200, Q251 off centre in the Q214 direction, in (Q253: MAX rapid) until
    the tooth, Q252 above the tip, is Q200 below the underside Q203 - Q250; over the centre; up
    until the tooth is Q249 above the underside; dwell Q255; back down to the level below, off
    centre, up to Q203 + Q200, over the centre, up to Q203 + Q204."""
    surface, setup, second = p["Q203"], p["Q200"], p.get("Q204", 0.0)
    underside = surface - p["Q250"]
    low, cut = underside - setup - p["Q252"], underside + p["Q249"] - p["Q252"]
    how = "rapid" if math.isinf(p["Q253"]) else "feed"
    side = {1: (-1, 0), 2: (0, -1), 3: (1, 0), 4: (0, 1)}.get(int(p["Q214"]), (0, 0))
    _move_z(t, line, "rapid", surface + setup, optional=True)
    centre = t.prog()

    def sideways(off: float) -> None:
        if side != (0, 0):
            here = centre + np.array([side[0], side[1], 0.0]) * off * t.scale
            here[2] = t.prog()[2]
            t.emit(line, "rapid", t.machine(here))

    sideways(p["Q251"])
    _move_z(t, line, how, low)
    sideways(0.0)
    _move_z(t, line, "feed", cut)
    _dwell(t, line, p.get("Q255", 0.0))
    _move_z(t, line, how, low)
    sideways(p["Q251"])
    _move_z(t, line, how, surface + setup)
    sideways(0.0)
    _move_z(t, line, "rapid", surface + max(second, setup), optional=True)


def _one_pass_cycle(t: _Tnc, line: int, kind: str, p: dict) -> None:
    """201 reaming, 202 boring, 206/207 tapping, 209 tapping with chip breaking, 240 centering, 241
    single-lip deep-hole drilling (as 201 after :func:`_single_lip_entry`): in to
    the depth (209: in steps of Q257, backing off Q256 pitches after each, 0: out to the set-up
    clearance), dwell Q211 (not 207/209), 202: 0.2 mm off the wall in the Q214 direction; out (240:
    rapid, the others at a feed) to the set-up clearance, 202: back over the centre; up to Q204."""
    surface, setup, depth, second = p["Q203"], p["Q200"], p["Q201"], p.get("Q204", 0.0)
    sgn = -1.0 if depth < 0 else 1.0
    clear = surface - sgn * setup
    bottom = surface + depth
    _move_z(t, line, "rapid", clear, optional=True)
    if kind == "241":
        if 0 < abs(p.get("Q202", 0.0)) < abs(depth):  # the newer 241's infeeds Q202/Q212/Q205 (tncwild39)
            raise ReferenceError("cycle 241 with infeeds Q202 shorter than the depth (pecking not modelled)")
        _single_lip_entry(t, line, p, surface, sgn)
    if kind == "209":
        back = abs(p.get("Q256", 0.0) * p["Q239"])
        levels = _levels(surface, bottom, sgn, abs(p["Q257"]) or abs(depth))
        for z in levels[:-1]:
            _move_z(t, line, "feed", z)
            _move_z(t, line, "feed", z - sgn * back if back else clear)
    _move_z(t, line, "feed", bottom)
    if kind not in ("207", "209"):
        _dwell(t, line, p.get("Q211", 0.0))
    centre = t.prog()
    side = {1: (-1, 0), 2: (0, -1), 3: (1, 0), 4: (0, 1)}.get(int(p.get("Q214", 0))) if kind == "202" else None
    if side:
        t.emit(line, "rapid", t.machine(centre + np.array([side[0], side[1], 0.0]) * 0.2))
    _move_z(t, line, "rapid" if kind == "240" or math.isinf(p.get("Q208", 0.0)) else "feed", clear)
    if side:
        centre[2] = t.prog()[2]
        t.emit(line, "rapid", t.machine(centre))
    _move_z(t, line, "rapid", surface - sgn * max(second, setup), optional=True)


def _contour_def(t: _Tnc, up: str) -> None:
    """CONTOUR DEF (the simple contour formula): Pn = LBL m a pocket, In = LBL m an island, ordered by n; a depth
    DPn / DIn of 0 is cycle 20's Q1 (another depth is not modelled)."""
    item = r"(?<![A-Z])([PI])(\d+)\s*=\s*LBL\s*(\"[^\"]+\"|\w+)"
    depth_item = r"D([PI]\d+)\s*=\s*([-+]?\s*(?:Q\d+|[\d.]+))"
    subs = sorted((int(n), role, label.strip('"').upper()) for role, n, label in re.findall(item, up))
    for _, depth in re.findall(depth_item, up):
        if _val(depth.replace(" ", ""), t.q) != 0:
            raise ReferenceError("CONTOUR DEF with a depth of its own")
    rest = re.sub(depth_item, "", re.sub(item, "", up)).replace("CONTOUR DEF", "").replace("~", "")
    if rest.strip():  # a word this reading does not know (a depth written 'DP-5'): not skipped (tncwild39)
        raise ReferenceError(f"CONTOUR DEF word {rest.strip()!r}")
    t.contours = tuple(label for _, _, label in subs)
    t.contour = t.contours[0]
    t.islands = {label for _, role, label in subs if role == "I"}


def _pattern_def(up: str, q: dict) -> list[dict]:
    """PATTERN DEF's positions in the order written: POSn (X Y Z as words), and the generated forms ROWn (X Y
    start, D apart NUM times along the angle ROT), CIRCn (NUM points on the circle X Y D from START, a full turn
    shared out) and PITCHCIRCn (the same, STEP apart, or from START to END) as the reader reads them (TNC 640
    cycle programming manual, "PATTERN DEF", its dialog); PATn a grid NUMX x NUMY (DX, DY apart; ROTX turns its
    row direction, ROTY its column direction, ROT all, about X/Y) and FRAMEn its outline, row by row in meander
    (the order of cycle 221 CARTESIAN PATTERN)."""
    out: list[dict] = []
    for kind, inner in re.findall(r"(POS|ROW|PITCHCIRC|CIRC|PAT|FRAME)\d+\s*\(([^)]*)\)", up):
        if kind == "POS":
            out.append(_words(inner, q))
            continue
        if kind in ("PAT", "FRAME"):
            out += _grid(kind, inner, q)
            continue
        v = {k: _val(x, q) for k, x in re.findall(r"(NUM|START|STEP|END|ROT|D|X|Y|Z)\s*([-+]?\s*(?:Q\d+|[\d.]+))",
                                                   inner)}
        n, z = int(v["NUM"]), v.get("Z", 0.0)
        if kind == "ROW":
            w = cmath.rect(v["D"], math.radians(v.get("ROT", 0.0)))
            pts = [complex(v["X"], v["Y"]) + k * w for k in range(n)]
        else:
            first = v.get("START", 0.0)
            step = 360.0 / n if kind == "CIRC" else v["STEP"] if "STEP" in v else (v["END"] - first) / max(n - 1, 1)
            pts = [complex(v["X"], v["Y"]) + cmath.rect(v["D"] / 2, math.radians(first + k * step))
                   for k in range(n)]
        out += [{"X": c.real, "Y": c.imag, "Z": z} for c in pts]
    return out


def _grid(kind: str, inner: str, q: dict) -> list[dict]:
    """PATTERN DEF PATn / FRAMEn: the grid's points (FRAME: those on its outline), rows in meander."""
    v = {k: _val(x, q) for k, x in re.findall(r"(NUMX|NUMY|ROTX|ROTY|ROT|DX|DY|X|Y|Z)\s*([-+]?\s*(?:Q\d+|[\d.]+))",
                                               inner)}
    nx, ny = int(v["NUMX"]), int(v["NUMY"])
    turn = cmath.exp(1j * math.radians(v.get("ROT", 0.0)))
    along = v["DX"] * cmath.exp(1j * math.radians(v.get("ROTX", 0.0)))
    across = v["DY"] * 1j * cmath.exp(1j * math.radians(v.get("ROTY", 0.0)))
    out = []
    for row in range(ny):
        cols = list(range(nx))
        if row % 2:
            cols.reverse()
        edge_row = row in (0, ny - 1)
        for col in cols:
            if kind == "FRAME" and not edge_row and 0 < col < nx - 1:
                continue
            c = complex(v["X"], v["Y"]) + turn * (col * along + row * across)
            out.append({"X": c.real, "Y": c.imag, "Z": v.get("Z", 0.0)})
    return out


def _pattern_def_call(t: _Tnc, line: int, between: str = "rapid") -> None:
    """CYCL CALL PAT: at each PATTERN DEF position (IX/IY from the last one; Z shifts the surface Q203),
    up to the clearance max(Q200, Q204) above that surface if below it, over the point at rapid, the cycle."""
    _called(t)
    kind, cyc = t.cycle
    sgn = -1.0 if cyc.get("Q201", -1.0) < 0 else 1.0
    for w in t.pattern:
        p = {**cyc, "Q203": cyc["Q203"] + w.get("Z", 0.0)}
        clear = p["Q203"] - sgn * max(p["Q200"], p.get("Q204", 0.0))
        if sgn * (t.prog()[2] / t.scale - clear) > _EPS:
            _move_z(t, line, between, clear)
        here = t.prog()
        for i, a in enumerate("XY"):
            here[i] = w[a] * t.scale if a in w else here[i] + w.get("I" + a, 0.0) * t.scale
        if not np.allclose(t.machine(here), t.pos, rtol=0, atol=1e-12):
            t.emit(line, between, t.machine(here))
        t.cycle = (kind, p)
        _run_cycle(t, line, fresh=False)
    t.cycle = (kind, cyc)


def _position_call(t: _Tnc, line: int, w: dict) -> None:
    """CYCL CALL POS X Y Z [F|FMAX]: (TNC 640 cycle programming manual, "Calling a cycle with CYCL CALL POS") to the
    point, then the cycle there; Z is the starting position and an additional shift of the surface Q203. Above the
    surface: the plane first, then Z; else first up to the clearance max(Q200, Q204) above it."""
    _called(t)
    kind, cyc = t.cycle
    if not all(a in w for a in "XYZ") or "Q203" not in cyc or "MB" in w:
        raise ReferenceError("CYCL CALL POS without X, Y and Z, with incremental words, of a cycle without Q203")
    move = "rapid" if w.get("F") == "MAX" or "FMAX" in w else "feed"
    sgn = -1.0 if cyc.get("Q201", -1.0) < 0 else 1.0
    p = {**cyc, "Q203": cyc["Q203"] + w["Z"]}
    if sgn * (t.prog()[2] / t.scale - p["Q203"]) > -_EPS:  # at or below the surface: up first
        _move_z(t, line, move, p["Q203"] - sgn * max(p["Q200"], p.get("Q204", 0.0)))
    here = t.prog()
    here[:2] = [w["X"] * t.scale, w["Y"] * t.scale]
    if not np.allclose(t.machine(here), t.pos, rtol=0, atol=1e-12):
        t.emit(line, move, t.machine(here))
    _move_z(t, line, move, w["Z"], optional=True)
    t.cycle = (kind, p)
    _run_cycle(t, line, fresh=False)
    t.cycle = (kind, cyc)


def _pattern(t: _Tnc, line: int, number: int, p: dict) -> None:
    """Cycle 220 (positions on a pitch circle) or 221 (a grid, meandering, turned by Q224 about its
    start): at each, the last machining cycle with the pattern's Q200/Q203/Q204, first reached over
    the 2nd set-up clearance, the next ones at the set-up clearance (Q301 = 1: the 2nd); 220 with Q365 = 1 from
    one position to the next on the pitch circle (TNC 640 cycle manual 34059x-01, cycle 220 "Cycle run")."""
    arc = number == 220 and p.get("Q365", 0.0) != 0.0
    if (t.factors[0] != t.factors[1]) and arc:
        raise ReferenceError("cycle 220 Q365=1 under axis-specific scaling")
    if number == 220:
        n = int(p["Q241"])
        span = p["Q246"] - p["Q245"]
        step = p["Q247"] if p["Q247"] else (span / n if abs(span) == 360 else span / max(n - 1, 1))
        r = p["Q244"] / 2
        points = [(p["Q216"] + r * math.cos(math.radians(p["Q245"] + k * step)),
                   p["Q217"] + r * math.sin(math.radians(p["Q245"] + k * step))) for k in range(n)]
    else:
        rot = math.radians(p.get("Q224", 0.0))
        grid = [(i if j % 2 == 0 else int(p["Q242"]) - 1 - i, j) for j in range(int(p["Q243"]))
                for i in range(int(p["Q242"]))]
        points = [(p["Q225"] + i * p["Q237"] * math.cos(rot) - j * p["Q238"] * math.sin(rot),
                   p["Q226"] + i * p["Q237"] * math.sin(rot) + j * p["Q238"] * math.cos(rot)) for i, j in grid]
    old = t.cycle is not None and t.cycle[0] in ("1", "2", "17")
    if t.cycle is None or not old and (not t.cycle[0].isdigit() or int(t.cycle[0]) < 200
                                       or t.cycle[0] in ("230", "231", "232", "233")):
        raise ReferenceError(f"cycle {number} with cycle {t.cycle[0] if t.cycle else None}: a pattern runs "
                             "the 200-series machining cycles and the old cycles 1, 2, 17 here")
    if old and abs(abs(t.cycle[1][1]) - abs(p["Q200"])) > 1e-9:
        # an old cycle starts where the tool stands, its surface its own set-up clearance below: the pattern
        # places it at Q203 + Q200, the same surface only when Q200 is the cycle's set-up clearance
        raise ReferenceError(f"cycle {number} with cycle {t.cycle[0]}: Q200 differs from the cycle's set-up "
                             "clearance")
    _called(t)
    kind, cyc = t.cycle
    sgn = -1.0 if (cyc[2] if old else cyc.get("Q201", -1.0)) < 0 else 1.0
    _move_z(t, line, "rapid", p["Q203"] - sgn * max(p["Q204"], p["Q200"]), optional=True)
    for k, (x, y) in enumerate(points):
        here = t.prog()
        here[0], here[1] = x * t.scale, y * t.scale
        if k and arc and not np.allclose(t.machine(here), t.pos):
            centre = t.prog()
            centre[0], centre[1] = p["Q216"] * t.scale, p["Q217"] * t.scale
            ccw = (step > 0) != t.turns_over()
            t.emit(line, "arc_ccw" if ccw else "arc_cw", t.machine(here), centre=t.machine(centre))
        else:
            t.emit(line, "rapid", t.machine(here), rows="optional" if np.allclose(t.machine(here), t.pos) else "one")
        last = k == len(points) - 1
        second = p["Q204"] if last or p.get("Q301", 0) else 0.0
        if old:  # down to the set-up clearance, the old cycle from there, back up to the 2nd one (our reading)
            _move_z(t, line, "rapid", p["Q203"] - sgn * p["Q200"], optional=True)
            _run_cycle(t, line, fresh=False)
            if second:
                _move_z(t, line, "rapid", p["Q203"] - sgn * max(p["Q204"], p["Q200"]), optional=True)
            continue
        t.cycle = (kind, {**cyc, "Q200": p["Q200"], "Q203": p["Q203"], "Q204": second})
        _run_cycle(t, line, fresh=False)
    t.cycle = (kind, cyc)


def _face_milling(t: _Tnc, line: int, p: dict) -> None:
    """Cycles 232 FACE MILLING and 230 MULTIPASS MILLING (TNC 640 cycle manual 34059x-01 p. 235-236, TNC 320
    manual 340 551-02 p. 298; TNC 426/430 manual, cycle 230), all in program coordinates: the starting point off
    the near edge by R + Q357 (230: R), lines along X in Q218's direction at Q226 .. Q226 + Q219 (equal steps,
    at most Q370 x R; 230: Q240 lines); 0: meander out to R + Q357 beyond the far edge, stepover at Q253; 1:
    meander from R inside the near edge to R inside the far edge, stepover at Q207; 2: every line from the near
    side, up Q200 above the level at FMAX, back at Q253, down at Q253. Levels: equal infeeds <= Q202 to Q386 +
    Q369, then Q386 at Q385; each level's lines in the reverse order of the last (0, 1); 2nd set-up clearance
    Q204 above Q227 at the end (230: Q200), and first when the tool is below it (232). Where the moves end only:
    the feeds are the tests' own."""
    k, r = t.scale, t.radius / t.scale  # the tool radius in program units
    x0, y0, top, length, width = p["Q225"], p["Q226"], p["Q227"], p["Q218"], p["Q219"]
    sx = math.copysign(1.0, length)
    if "Q240" in p:  # 230
        strategy, side, clear, n = 0, 0.0, top + p["Q200"], int(p["Q240"]) - 1
        levels = [top]
    else:
        strategy, side, clear = int(p["Q389"]), p.get("Q357", p["Q200"]), top + p["Q204"]
        n = math.ceil(abs(width) / (p.get("Q370", 1.0) * r) - 1e-9)
        rough = top - p["Q386"] - p.get("Q369", 0.0)
        m = math.ceil(rough / p["Q202"] - 1e-9) if rough > 0 else 0
        levels = [top - rough * (i + 1) / m for i in range(m)] + ([p["Q386"]] if p.get("Q369", 0.0) else [])
    rows = [y0 + width * j / n for j in range(n + 1)] if n > 0 else [y0]
    start = x0 - sx * (r + side)
    ends = (x0 + sx * r, x0 + length - sx * r) if strategy == 1 else (start, x0 + length + sx * (r + side))

    def go(kind: str, x=None, y=None, z=None) -> None:
        here = t.prog() / k
        pt = np.array([here[0] if x is None else x, here[1] if y is None else y, here[2] if z is None else z])
        end = t.machine(pt * k)
        if np.linalg.norm(end - t.pos) > 1e-9:
            t.emit(line, kind, end)

    if "Q240" not in p and t.prog()[2] / k <= clear:
        go("rapid", z=clear)
    go("rapid", start, rows[0])
    go("rapid", z=top + p["Q200"])
    order = rows
    pre = "rapid" if math.isinf(p.get("Q253", 0.0)) else "feed"  # Q253=MAX
    for i, z in enumerate(levels):
        go(pre, z=z)
        for j, y in enumerate(order):
            if strategy == 2:
                if j:
                    go("rapid", z=z + p["Q200"])
                    go(pre, start, y)
                    go(pre, z=z)
                go("feed", ends[1], y)
                continue
            go(pre if strategy == 0 else "feed", y=y)
            x = t.prog()[0] / k
            go("feed", ends[1] if abs(x - ends[1]) > 1e-9 else ends[0])
        if strategy == 2 and i < len(levels) - 1:
            go("rapid", z=z + p["Q200"])
            go(pre, start, rows[0])
        elif strategy != 2:
            order = order[::-1]
    go("rapid", z=clear)


def _face_milling_233(t: _Tnc, line: int, p: dict) -> None:
    """233 FACE MILLING (TNC7 basic manual 81762x-19, "Cycle 233 FACE MILLING"), without limits, in program
    coordinates: the surface's corner where the tool stands; Q350 = 1 the lines along X (Q218 long, Q219 across),
    2 along Y (Q219 long, Q218 across), across in equal steps of at most Q370 x R from the corner's line to the
    far side. Start R + Q357 before the corner; a line's far end R + Q357 (Q389 0, 2) or Q357 (1, 3) beyond the
    far edge, the meander's (0, 1) way back as far before the near edge; 2, 3: each line from the start, up Q200
    above the level at FMAX, FMAX over, down to the level. Levels: equal infeeds <= Q202 to Q386 + Q369 (Q215 0,
    1), then Q386 (Q215 0 with Q369 > 0, or 2 alone); down to a level at the milling feed. FMAX to Q227 + Q204
    first when below it, and at the end. Where the moves end only."""
    k, r = t.scale, t.radius / t.scale
    corner = t.prog() / k
    along_axis = 0 if p["Q350"] == 1 else 1
    across_axis = 1 - along_axis
    length = p["Q218"] if along_axis == 0 else p["Q219"]
    width = p["Q219"] if along_axis == 0 else p["Q218"]
    top, bottom, allowance = p["Q227"], p["Q386"], p.get("Q369", 0.0)
    strategy, side, setup = int(p["Q389"]), p.get("Q357", 0.0), p["Q200"]
    sa, sw = math.copysign(1.0, length), math.copysign(1.0, width)
    start = corner[along_axis] - sa * (r + side)
    over = r + side if strategy in (0, 2) else side
    far, back = corner[along_axis] + length + sa * over, corner[along_axis] - sa * over
    steps = math.ceil(abs(width) / (p.get("Q370", 1.0) * r) - 1e-9)
    across = [corner[across_axis] + sw * abs(width) * j / steps for j in range(steps + 1)] if steps else \
        [corner[across_axis]]
    op = int(p.get("Q215", 0))
    rough = top - bottom - allowance
    count = math.ceil(rough / p["Q202"] - 1e-9) if rough > 0 else 0
    levels = [] if op == 2 else [top - rough * (i + 1) / count for i in range(count)]
    if op == 2 or (op == 0 and allowance > 0):
        levels.append(bottom)

    def go(kind: str, a=None, b=None, z=None) -> None:
        here = t.prog() / k
        pt = here.copy()
        if a is not None:
            pt[along_axis] = a
        if b is not None:
            pt[across_axis] = b
        if z is not None:
            pt[2] = z
        end = t.machine(pt * k)
        if np.linalg.norm(end - t.pos) > 1e-9:
            t.emit(line, kind, end)

    clear = top + p["Q204"]
    if corner[2] <= clear:
        go("rapid", z=clear)
    go("rapid", start, across[0])
    go("rapid", z=top + setup)
    order = list(across)
    for z in levels:
        go("feed", z=z)
        for j, b in enumerate(order):
            if strategy >= 2:
                if j:
                    go("rapid", z=z + setup)
                    go("rapid", start, b)
                    go("feed", z=z)
                go("feed", far, b)
            else:
                go("feed", b=b)
                here = t.prog()[along_axis] / k
                go("feed", back if abs(here - far) < 1e-9 else far)
        if strategy >= 2:
            if z != levels[-1]:
                go("rapid", z=z + setup)
                go("rapid", start, across[0])
        else:
            order.reverse()
    go("rapid", z=clear)


def _ruled_surface(t: _Tnc, line: int, p: dict) -> None:
    """231 RULED SURFACE (TNC 410 ISO manual p. 292 for the parameters; the cycle run as read for vcnc): FMAX to
    point 1; Q240 lines from the edge 1-4 to the edge 2-3 in equal steps; after each but the last FMAX up by the
    tool diameter, over the line's start, down to it, then fed to the next line's start; at the end FMAX to the
    tool diameter above the highest point. Where the moves end only."""
    pts = [np.array([p[f"Q{k}"], p[f"Q{k + 1}"], p[f"Q{k + 2}"]]) * t.scale for k in (225, 228, 231, 234)]
    n, lift = int(p["Q240"]) - 1, 2 * t.radius
    t.emit(line, "rapid", t.machine(pts[0]))
    for j in range(n + 1):
        f = j / n if n else 0.0
        a, b = pts[0] + (pts[3] - pts[0]) * f, pts[1] + (pts[2] - pts[1]) * f
        for q in ([a] if j else []) + [b]:  # a line of no length (points 3 and 4 the same) may have no row
            t.emit(line, "feed", t.machine(q), rows="optional" if np.allclose(t.machine(q), t.pos) else "one")
        if j < n:
            for q in (b + [0, 0, lift], np.array([a[0], a[1], b[2] + lift]), a):
                t.emit(line, "rapid", t.machine(q), rows="optional" if np.allclose(t.machine(q), t.pos) else "one")
    top = max(pt[2] for pt in pts) + lift
    end = t.prog()
    t.emit(line, "rapid", t.machine(np.array([end[0], end[1], top])), rows="optional")


def _levels(surface: float, bottom: float, sgn: float, plunge: float) -> list[float]:
    """The plunging depths from the surface to the bottom (the last one the bottom)."""
    levels, k = [], 1
    while plunge > 0 and (surface + sgn * k * plunge - bottom) * sgn < -_EPS:
        levels.append(surface + sgn * k * plunge)
        k += 1
    return [*levels, bottom]


def _tool(t: _Tnc, text: str) -> None:
    """``TOOL DEF n L.. R..`` (the program's table) and ``TOOL CALL n Z S.. DL.. DR..``; ``TOOL CALL "NAME"``
    (the table's tool of that NAME, the lowest number of several; none: length and radius are the DL, DR
    deltas) and
    ``TOOL CALL Z S..`` (no tool: the active one stays, only the axis, speed and feed)."""
    # TOOL CALL Q11: the number in a Q; TOOL DEF1 (no space, a hand-written program's) as TOOL DEF 1
    m = re.match(r"TOOL (DEF|CALL)\s*(\d+|Q[LR]?\d+|\"[^\"]*\")?\s*(.*)$", text)
    if m is None or (m.group(2) is None and m.group(1) == "DEF"):
        raise ReferenceError(f"tool block {text!r}")
    rest = m.group(3).upper()
    s = re.search(r"\bS\s*([-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", rest) if m.group(1) == "CALL" else None
    if s:
        t.speed = _val(s.group(1).replace(" ", ""), t.q)
    if m.group(2) is None:  # TOOL CALL Z S..: the tool axis (only Z here), speed and feed
        if re.match(r"\s*[XY]\b", rest):
            raise ReferenceError(f"tool axis in {text!r}")
        f = re.search(r"\bF\s*([-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", rest)
        if f:
            t.auto = _val(f.group(1).replace(" ", ""), t.q)
        return
    if m.group(2).startswith('"'):
        numbers = sorted(n for n, tool in t.ctx.tools.items() if tool.name == m.group(2).strip('"').strip())
        number = numbers[0] if numbers else 0
    else:
        number = int(_val(m.group(2), t.q))

    def word(name: str) -> float:
        w = re.search(rf"\b{name}\s*([-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))", rest)
        return _val(w.group(1).replace(" ", ""), t.q) if w else 0.0

    if m.group(1) == "DEF":  # in the program's unit (an INCH program's TOOL DEF in inches)
        if re.search(r"\b[LR]\s*[-+]?\s*[\dQ.]", rest):  # TOOL DEF n alone pre-selects the next tool (TNC 640
            t.tool_defs[number] = (word("L") * t.scale, word("R") * t.scale)  # manual): the table's L and R stay
        elif not m.group(2).startswith('"'):
            t.prepared = number
        return
    axis = re.match(r"\s*([XYZ])\b", rest)
    if axis and axis.group(1) != "Z":
        raise ReferenceError(f"tool axis {axis.group(1)}")
    if m.group(2).startswith('"') and number == 0:
        length = radius = 0.0
    elif number in t.tool_defs:
        length, radius = t.tool_defs[number]
    else:
        tool = t.ctx.tool(number)
        length, radius = (tool.length, tool.radius) if tool is not None else (0.0, 0.0)
    t.tool = number
    t.length = length + word("DL") * t.scale
    t.radius = radius + word("DR") * t.scale
    t.delta = word("DR") * t.scale  # LN displaces the end point along the surface normal by the delta values
    if re.search(r"\bF\s*[-+]?\s*[\dQ.]", rest):
        t.auto = word("F")
    # the preassigned parameters of the tool (TNC 640 manual): Q108 radius, Q109 tool axis, Q113 unit, Q114 length
    t.q.update(Q108=t.radius / t.scale, Q109=2.0, Q113=float(t.scale != 1.0), Q114=t.length / t.scale)


_FN_CMP = {"EQU": lambda a, b: a == b, "NE": lambda a, b: a != b, "GT": lambda a, b: a > b,
           "LT": lambda a, b: a < b}


def _fn(t: _Tnc, text: str) -> str | None:
    """``FN n: ...``; returns the label of a jump taken, else None."""
    m = re.match(r"FN\s*(\d+)\s*:?\s*(.*)$", text)
    n, rest = int(m.group(1)), m.group(2)
    if n in (0, 1, 2, 3, 4, 5, 6, 7, 8, 13):
        q, expr = rest.split("=", 1)
        if n in (5, 6, 7):  # SQRT, SIN, COS of one value (TNC 426/430 manual, "Trigonometric functions")
            v = _val(re.sub(r"^\s*(SQRT|SIN|COS)", "", expr.upper()).replace(" ", ""), t.q)
            value = {5: math.sqrt(v), 6: math.sin(math.radians(v)), 7: math.cos(math.radians(v))}[n]
        elif n:
            a, b = re.match(r"\s*([-+]?\s*[\w.]+)\s*(?:[-+*/]|DIV|LEN|ANG)\s*([-+]?\s*[\w.]+)\s*$",
                            expr.upper()).groups()
            va, vb = _val(a.replace(" ", ""), t.q), _val(b.replace(" ", ""), t.q)
            # FN 8 LEN: root sum of squares; FN 13 ANG: the angle of (a, b) from the arc tangent, in degrees (each
            # worked out only for its own n: FN 1 with a second value 0 is no division)
            value = {1: lambda: va + vb, 2: lambda: va - vb, 3: lambda: va * vb, 4: lambda: va / vb,
                     8: lambda: math.sqrt(va * va + vb * vb),
                     13: lambda: math.degrees(math.atan2(vb, va)) % 360.0}[n]()  # TNC 370 manual: 0 < angle < 360
        else:
            value = _Formula(expr, t.q).value()
        t.q[q.strip().upper()] = value
    elif n in (9, 10, 11, 12):
        m2 = re.match(r"IF\s*([-+]?\s*[\w.]+)\s*(EQU|NE|GT|LT)\s*([-+]?\s*[\w.]+)\s*GOTO\s*LBL\s*(\S+)", rest)
        a, op, b, label = m2.groups()
        if _FN_CMP[op](_val(a.replace(" ", ""), t.q), _val(b.replace(" ", ""), t.q)):
            return label.strip('"')
    elif n in (15, 16) or (n == 20 and rest.strip().upper().startswith("WAIT FOR")):  # prints; a PLC wait: no motion
        pass
    elif n == 17:  # SYSWRITE (TNC 426/430 technical manual 7.3.3): ID50 NR1 / NR2 IDXt the length / radius of tool t
        ident, nr, idx, expr = re.match(r"SYSWRITE\s*ID\s*(\d+)\s*NR\s*(\d+)\s*(?:IDX\s*(\d+|Q[LR]?\d+))?\s*=\s*(.*)$",
                                        rest).groups()
        if ident == "50" and nr in ("1", "2"):
            k = int(_val(idx, t.q))
            tool = t.ctx.tool(k)
            data = list(t.tool_defs.get(k, (tool.length, tool.radius) if tool is not None else (0.0, 0.0)))
            data[int(nr) - 1] = _Formula(expr, t.q).value() * t.scale
            t.tool_defs[k] = (data[0], data[1])
        elif (ident, nr) == ("20", "1") or (ident == "50" and nr in ("4", "5") and _Formula(expr, t.q).value()):
            raise ReferenceError(f"FN 17 ID{ident} NR{nr}")  # the active tool, DL / DR: data vcnc reads back
    elif n == 18:
        m2 = re.match(r"SYSREAD\s*(Q[LR]?\d+)\s*=\s*ID\s*(\d+)\s*NR\s*(\d+)\s*(?:IDX\s*(\d+|Q[LR]?\d+))?", rest)
        q, ident, nr, idx = m2.groups()
        if ident == "20" and nr == "1":  # the active tool's number
            t.q[q] = float(t.tool)
        elif (ident, nr) in (("20", "2"), ("20", "3"), ("20", "4"), ("10", "1")):
            # iTNC 530 technical manual 07/2013, 9.5.4 (FN18: SYSREAD): ID20 NR2 the prepared tool, NR3 the tool
            # axis (0 = X, 1 = Y, 2 = Z: only Z here), NR4 the programmed spindle speed; ID10 NR1 inch = 1
            t.q[q] = {"2": float(t.prepared), "3": 2.0, "4": t.speed}[nr] if ident == "20" else float(t.scale != 1.0)
        elif ident == "50" and nr in ("1", "2"):  # L / R of tool IDX: the program's TOOL DEF, else the table
            n = int(_val(idx, t.q))
            tool = t.ctx.tool(n)
            data = t.tool_defs.get(n, (tool.length, tool.radius) if tool is not None else (0.0, 0.0))
            t.q[q] = data[int(nr) - 1] / t.scale  # a tool not in the table: 0, 0 (as TOOL CALL takes it)
        elif ident == "50" and nr in ("3", "4", "5"):  # R2, DL, DR: no such columns in the context's table
            t.q[q] = 0.0
        elif nr != "1" or ident not in ("240", "270"):
            raise ReferenceError(f"FN 18 ID{ident} NR{nr}")
        else:
            pos = t.pos if ident == "240" else t.prog()
            t.q[q] = float(pos[int(idx) - 1]) / t.scale
    else:
        raise ReferenceError(f"FN {n}")
    return None


def _label_of(text: str) -> str:
    return re.match(r"LBL\s*(\S+)", text).group(1).strip('"')


# --- tilted working plane (PLANE SPATIAL / RESET, cycle 19) on a tilting table ---------------------------
# Written from the iTNC 530 user's manual ("The PLANE function", PLANE SPATIAL: rotations about the
# fixed machine axes, first A, then B, then C; "Specifying the positioning behavior": MOVE keeps the tool
# tip on the part, TURN turns the rotary axes only, STAY moves nothing and the program positions them with
# the values of Q120 A, Q121 B, Q122 C; SEQ+/- the sign of the master (tilting) axis, else the solution
# nearest the current position) and ISO 841 (a rotary angle turns the tool relative to the part
# right-handedly; a table turns the part the other way). Own geometry: explicit rotation matrices,
# homogeneous 4x4 transforms of the table and the closed-form angles of a table whose inner axis is C.


def _turn(axis: str, deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return {"X": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]), "Y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "Z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]


def _homogeneous(rot: np.ndarray, pivot) -> np.ndarray:
    """4x4 of a rotation about the point ``pivot``."""
    h = np.eye(4)
    h[:3, :3] = rot
    h[:3, 3] = np.asarray(pivot, float) - rot @ np.asarray(pivot, float)
    return h


def _carry(t: _Tnc, point: np.ndarray, angles: dict[str, float], *, back: bool = False) -> np.ndarray:
    """Where the table at ``angles`` carries the part point that is at ``point`` with the rotary axes at 0
    (``back``: the reverse)."""
    h = np.eye(4)
    for ax in t.ctx.kinematics.axes:  # outer first: H = H_outer @ H_inner
        sign = -1.0 if ax.direction.startswith("-") else 1.0
        h = h @ _homogeneous(_turn(ax.direction[-1], -sign * angles[ax.name]), ax.pivot)
    if back:
        h = np.linalg.inv(h)
    return (h @ np.append(np.asarray(point, float), 1.0))[:3]


def _spatial(a: float, b: float, c: float) -> np.ndarray:
    return _turn("Z", c) @ _turn("Y", b) @ _turn("X", a)


def _in_limits(ax, deg: float, near: float | None = None) -> float | None:
    """``deg`` or a turn of 360 from it within the axis' limits: the one in (-180, 180] first, or nearest ``near``."""
    d = (deg + 180.0) % 360.0 - 180.0
    d = 180.0 if abs(d + 180.0) < 1e-9 else d
    turns = (d, d + 360.0, d - 360.0) if near is None else sorted(turns_within(ax.limits, d),
                                                                     key=lambda v: abs(v - near))
    for v in turns:
        if ax.limits[0] - 1e-6 <= v <= ax.limits[1] + 1e-6:
            return v
    return None


def _solve(t: _Tnc, plane: np.ndarray, seq: int, *, nearest: bool = False, table_rot: bool = False,
           turn: Callable[[str, float], float] | None = None) -> dict[str, float]:
    """The rotary positions for ``plane`` of an A/C or B/C table (closed form): the tool's direction in the
    part, Rz(C) Rx(A) e_z = (sin C sin A, -cos C sin A, cos A) or Rz(C) Ry(B) e_z = (cos C sin B, sin C sin B,
    cos B), equal to the plane's Z. ``nearest``: each axis at the turn of 360 nearest its position (a tool
    direction under M128), else in (-180, 180] first. When the plane's Z is the C axis' own, C stays (COORD ROT)
    or, with ``table_rot``, turns the plane's X onto the machine's X (:func:`_table_rot`). Of two solutions the one
    with the shorter path (TNC7 user's manual 81762x-17, "Tilting solution"), a tie (within 1e-6 deg) to the positive
    master angle.
    A wrapping axis (``ctx.wrapped_axes``) is judged by the turn it really makes: under ``nearest`` the shorter
    way from its unwrapped position, ending there; else at the angle it shows in [0, 360), ``turn(name, angle)``
    long (the caller's rule); SEQ takes its angle in (-180, 180]."""
    n = plane[:, 2]
    if len(t.ctx.kinematics.axes) == 1:  # one axis: Rx(A) e_z = (0, -sin A, cos A), Ry(B) e_z = (sin B, 0, cos B)
        ax = t.ctx.kinematics.axes[0]
        if ax.direction not in ("X", "Y") or abs(n["XY".index(ax.direction)]) > 1e-9:
            raise ReferenceError("a plane one axis does not reach")
        deg = math.degrees(math.atan2(-n[1], n[2]) if ax.direction == "X" else math.atan2(n[0], n[2]))
        v = _pick(t, ax, deg, nearest, turn)
        if v is None:
            raise ReferenceError("no rotary position within the limits")
        return {ax.name: v[0]}
    outer, inner = t.ctx.kinematics.axes
    if (outer.direction, inner.direction) not in (("X", "Z"), ("Y", "Z")) or t.ctx.kinematics.kind != "table":
        raise ReferenceError("kinematics other than an A/C or B/C table")
    now = (t.extra["ABC".index(outer.name.upper())], t.extra["ABC".index(inner.name.upper())])
    found = []
    b = math.degrees(math.atan2(math.hypot(n[0], n[1]), n[2]))  # (acos(n_z) keeps 3 digits of a tilt of 1e-6 rad)
    for tilt in {b, -b}:
        st = math.sin(math.radians(tilt))
        if abs(st) < 1e-9:
            rot = _table_rot(t, plane, tilt) if table_rot else now[1]
        elif outer.direction == "X":
            rot = math.degrees(math.atan2(n[0] / st, -n[1] / st))
        else:
            rot = math.degrees(math.atan2(n[1] / st, n[0] / st))
        o, i = _pick(t, outer, tilt, nearest, turn), _pick(t, inner, rot, nearest, turn)
        if o is None or i is None:
            continue
        master = (tilt + 180.0) % 360.0 - 180.0 if outer.name in t.ctx.wrapped_axes else o[0]
        if seq == 0 or master * seq >= -1e-9:
            found.append((o[1] + i[1], -master, o[0], i[0]))
    if not found:
        raise ReferenceError("no rotary positions within the limits")
    least = min(f[0] for f in found)  # paths equal within 1e-6 deg tie (99.99999999999999 against 100)
    _, o, i = min(f[1:] for f in found if f[0] <= least + 1e-6)
    return {outer.name: o, inner.name: i}


def _pick(t: _Tnc, ax, deg: float, nearest: bool, turn: Callable[[str, float], float] | None) -> tuple | None:
    """(the angle ``ax`` takes for the solution's ``deg``, its travel), or None outside the limits (of a wrapping
    axis: no turn of 360 of ``deg`` within them)."""
    now = t.extra["ABC".index(ax.name.upper())]
    if ax.name in t.ctx.wrapped_axes and (nearest or turn is not None):
        if _in_limits(ax, deg) is None:
            return None
        if nearest:  # the shorter way (Fanuc's shortcut control under TCP, read for M128 too)
            end = wrapped_end("shortest", deg, now, 0.0)
            return end, abs(end - now)
        shown = math.fmod(deg, 360.0) + (360.0 if deg < 0.0 else 0.0)
        shown = 0.0 if shown > 360.0 - 1e-9 else shown
        return shown, turn(ax.name, shown)
    v = _in_limits(ax, deg, now if nearest else None)
    return None if v is None else (v, abs(v - now))


def _table_rot(t: _Tnc, plane: np.ndarray, tilt: float) -> float:
    """TABLE ROT (iTNC 530 user's manual, "Selecting the type of transformation": TABLE ROT positions the rotary
    table to the tilting angle, COORD ROT only turns the coordinate system): the C position, with the tilting axis
    at ``tilt`` [deg], at which the table carries the plane's X onto the machine's +X. Tried from the angle of X in
    the part's XY plane and that angle plus 180 (a tilt of 180 deg about Y reverses X)."""
    outer, inner = t.ctx.kinematics.axes
    base = math.degrees(math.atan2(plane[1, 0], plane[0, 0])) * (-1.0 if inner.direction.startswith("-") else 1.0)
    for c in (base, base + 180.0):
        ang = {outer.name: tilt, inner.name: c}
        x = _carry(t, plane[:, 0], ang) - _carry(t, np.zeros(3), ang)
        if x[0] > 1.0 - 1e-9:
            return (c + 180.0) % 360.0 - 180.0
    raise ReferenceError("TABLE ROT: no C position turns the plane's X onto X")


def _projected(propr: float, promin: float, rot: float) -> np.ndarray:
    """``PLANE PROJECTED PROPR PROMIN ROT`` (iTNC 530 user's manual 340 49x, 12.3, "Defining the working plane
    with projection angles"): PROPR is the angle of the tilted plane's trace in the ZX plane from X, PROMIN that
    of its trace in the YZ plane from Y (each within +-89.9999 deg), ROT then turns the tilted axes about the tilted
    tool axis as cycle 10 does. The traces run along (1, 0, -tan PROPR) and (0, 1, tan PROMIN) (our reading of the
    figure's positive directions: PROPR alone is SPB, PROMIN alone is SPA); the tilted X along the first, the tool
    axis square to both."""
    if max(abs(propr), abs(promin)) >= 90.0:
        raise ReferenceError("a projection angle of 90 deg or more")
    x = np.array([1.0, 0.0, -math.tan(math.radians(propr))])
    trace_y = np.array([0.0, 1.0, math.tan(math.radians(promin))])
    z = np.cross(x, trace_y)
    x, z = x / np.linalg.norm(x), z / np.linalg.norm(z)
    return np.column_stack([x, np.cross(z, x), z]) @ _turn("Z", rot)


def _three_points(p1: np.ndarray, p2: np.ndarray, p3: np.ndarray) -> np.ndarray:
    """``PLANE POINTS`` (TNC 640 user's manual 34059x-05, "Defining the working plane via three points"): "thumb (X
    axis) points from Point 1 to Point 2, index finger (Y axis) points parallel to the tilted Y axis in the direction
    of Point 3. Then the middle finger points in the direction of the tilted tool axis": Gram-Schmidt from P1."""
    x = p2 - p1
    if np.linalg.norm(x) < 1e-12:
        raise ReferenceError("PLANE POINTS with P1 = P2")
    x = x / np.linalg.norm(x)
    y = (p3 - p1) - ((p3 - p1) @ x) * x
    if np.linalg.norm(y) < 1e-9 * max(1.0, float(np.linalg.norm(p3 - p1))):
        raise ReferenceError("PLANE POINTS on one line")
    y = y / np.linalg.norm(y)
    return np.column_stack([x, y, np.cross(x, y)])


def _shown(t: _Tnc) -> np.ndarray:
    """The positions of A, B, C (and U, V, W) with a wrapping rotary axis at the angle it shows, in [0, 360)."""
    out = t.extra.copy()
    for a in t.ctx.wrapped_axes:
        i = "abc".index(a)
        v = math.fmod(t.extra[i] - t.shown[i], 360.0)
        v = v + 360.0 if v < 0.0 else v
        out[i] = 0.0 if v > 360.0 - 1e-9 else v
    return out


def _axial(t: _Tnc, w: dict) -> tuple[np.ndarray, dict[str, float]]:
    """``PLANE AXIAL A.. B.. C..`` (TNC7 basic user's manual 81762x-19, "PLANE AXIAL": "Axis angles define both the
    orientation of the working plane as well as the nominal coordinates of the rotary axes", "absolute or incremental
    axis angles"; an axis angle for an axis the machine lacks is an error): the axes go to the angles written (``IB``:
    that much from where the axis is; an axis not written keeps its position, our reading); the plane is the part's
    frame the table at those angles turns onto the machine's axes (its columns: the part directions carried onto
    machine X, Y, Z)."""
    names = [ax.name for ax in t.ctx.kinematics.axes]
    if any(k[-1].lower() not in names for k in w) or not w or any(k in w and "I" + k in w for k in "ABC"):
        raise ReferenceError(f"PLANE AXIAL {sorted(w)} on axes {names}")
    shown = _shown(t)
    now = {a: shown["ABC".index(a.upper())] for a in names}
    angles = {a: w[a.upper()] if a.upper() in w else now[a] + w.get("I" + a.upper(), 0.0) for a in names}
    for ax in t.ctx.kinematics.axes:
        if not ax.limits[0] - 1e-6 <= angles[ax.name] <= ax.limits[1] + 1e-6:
            raise ReferenceError(f"PLANE AXIAL {ax.name.upper()} outside the limits")
    cols = [_carry(t, e, angles, back=True) - _carry(t, np.zeros(3), angles, back=True) for e in np.eye(3)]
    return np.column_stack(cols), angles


def _tilt_plane(t: _Tnc, line: int, plane: np.ndarray | None, *, positioning: str, seq: int = 0,
                feed: str = "rapid", dist: float = 0.0, table_rot: bool = False,
                angles: dict[str, float] | None = None) -> None:
    """Activate ``plane`` (None: cancel it), then position the rotary axes as ``positioning`` says (at ``angles``
    when the block gave them, PLANE AXIAL, else at the solution for the plane)."""
    if t.ctx.kinematics is None:
        raise ReferenceError("a tilt without kinematics")
    names = [ax.name for ax in t.ctx.kinematics.axes]
    old = {a: t.extra["ABC".index(a.upper())] for a in names}
    if plane is None:
        if t.tilt is not None and not t.shifted:
            t.shift = t.base.copy()
        t.tilt, new = None, dict.fromkeys(names, 0.0)
    else:
        machine, t.extra = t.extra, _shown(t)  # solved from the angles a wrapping axis shows

        def turn(name: str, angle: float) -> float:  # how far a wrapping axis turns to the angle it shows
            i = "abc".index(name)
            return abs(wrapped_end(_rule(t), angle, machine[i], t.shown[i]) - machine[i])
        try:
            new = dict(angles) if angles is not None else _solve(t, plane, seq, table_rot=table_rot, turn=turn)
        finally:
            t.extra = machine
        if t.tilt is None:
            t.base = t.shift.copy()
        t.tilt, t.tilt_angles, t.shift, t.shifted = plane, new, np.zeros(3), False
        for a in names:
            t.q[f"Q{120 + 'abc'.index(a)}"] = new[a]
    if positioning in ("MOVE", "TURN"):
        end = t.pos.copy()
        if positioning == "MOVE":  # the point DIST above the tip keeps its place on the part
            up = np.array([0.0, 0.0, dist * t.scale])
            tip = t.pos - np.array([0.0, 0.0, t.length]) + up
            end = _carry(t, _carry(t, tip, old, back=True), new) - up + np.array([0.0, 0.0, t.length])
        ends = {}
        for a in names:  # a wrapping axis reaches its nominal angle by the machine's rule, as an absolute word
            i = "ABC".index(a.upper())
            ends[a] = wrapped_end(_rule(t), new[a], t.extra[i], t.shown[i]) if a in t.ctx.wrapped_axes else new[a]
        still = all(abs(t.extra["ABC".index(a.upper())] - ends[a]) < 1e-12 for a in names)
        for a in names:
            t.extra["ABC".index(a.upper())] = ends[a]
        t.emit(line, feed, end, extra=t.extra.copy(), rows="optional" if still else "one")


def _rule(t: _Tnc) -> str:
    """The way an absolute word turns a wrapping axis: shorter under M126, else the machine's, else the
    difference to the angle shown (TNC 640 user's manual, M126)."""
    return "shortest" if t.m126 else t.ctx.wrap_direction or "difference"


def _plane(t: _Tnc, line: int, up: str) -> None:
    """``PLANE SPATIAL SPA SPB SPC MOVE|TURN|STAY [DIST] [F|FMAX] [SEQ]``, ``PLANE EULER EULPR EULNU EULROT``
    (Z, then the turned X, then the new Z), ``PLANE VECTOR BX .. NZ`` (Z along N, X along B square to it),
    ``PLANE RELATIV SPA|SPB|SPC`` (the active plane turned about its own axis), ``PLANE RESET ..``."""
    w = {k: _val(v, t.q) for k, v in re.findall(
        r"(SP[ABC]|EUL(?:PR|NU|ROT)|PRO(?:PR|MIN)|ROT|P[123][XYZ]|[BN][XYZ]|DIST|F|(?<![A-Z])I?[ABC])"
        r"\s*([-+]?\s*(?:[\d.]+|Q[LR]?\d+))", up)}
    pos = re.search(r"\b(MOVE|TURN|STAY)\b", up)
    seq = re.search(r"\b(?:SEQ|SYM)\s*([+-])", up)
    kind = "rapid" if "MAX" in up.split("SEQ")[0].replace("MB MAX", "") or "F" not in w else "feed"
    plane = None if up.startswith("PLANE RESET") else _spatial(w.get("SPA", 0.0), w.get("SPB", 0.0),
                                                                  w.get("SPC", 0.0))
    if up.startswith("PLANE EULER"):
        plane = _turn("Z", w.get("EULPR", 0.0)) @ _turn("X", w.get("EULNU", 0.0)) @ _turn("Z", w.get("EULROT", 0.0))
    elif up.startswith("PLANE VECTOR"):
        n = np.array([w.get("NX", 0.0), w.get("NY", 0.0), w.get("NZ", 0.0)])
        n = n / np.linalg.norm(n)
        b = np.array([w.get("BX", 0.0), w.get("BY", 0.0), w.get("BZ", 0.0)])
        x = (b - (b @ n) * n) / np.linalg.norm(b - (b @ n) * n)
        plane = np.column_stack([x, np.cross(n, x), n])
    elif up.startswith("PLANE RELATIV"):  # one incremental angle about the active plane's own axis (iTNC 530
        # user's manual, "Incremental tilting: PLANE RELATIVE": it "acts in relation to the active input coordinate
        # system")
        turns = [k for k in ("SPA", "SPB", "SPC") if k in w]
        if len(turns) != 1:
            raise ReferenceError(up)
        plane = (np.eye(3) if t.tilt is None else t.tilt) @ _turn("XYZ"["ABC".index(turns[0][-1])], w[turns[0]])
    elif up.startswith("PLANE PROJECTED"):
        plane = _projected(w.get("PROPR", 0.0), w.get("PROMIN", 0.0), w.get("ROT", 0.0))
    elif up.startswith("PLANE POINTS"):
        plane = _three_points(*(np.array([w.get(f"P{i}{a}", 0.0) for a in "XYZ"]) for i in "123"))
    angles = None
    if up.startswith("PLANE AXIAL"):
        plane, angles = _axial(t, {k: v for k, v in w.items() if k.lstrip("I") in ("A", "B", "C")})
    if not up.startswith(("PLANE RESET", "PLANE SPATIAL", "PLANE EULER", "PLANE VECTOR", "PLANE RELATIV",
                          "PLANE PROJECTED", "PLANE POINTS", "PLANE AXIAL")):
        raise ReferenceError(up)
    mb = re.search(r"\bMB\s*(MAX|\+?\d+\.?\d*)", up)
    up_to = None if not mb else max(t.ctx.home[2], t.pos[2]) if mb.group(1) == "MAX" else \
        t.pos[2] + float(mb.group(1)) * t.scale
    if up_to is not None and up_to > t.pos[2] + _EPS and pos and pos.group(1) in ("MOVE", "TURN"):
        _retract(t, line, mb.group(1), "MAX")  # MB: up the tool axis (machine Z on a table) before the turn
    _tilt_plane(t, line, plane, positioning=pos.group(1) if pos else "STAY",
                seq=0 if seq is None else (1 if seq.group(1) == "+" else -1), feed=kind, dist=w.get("DIST", 0.0),
                table_rot=bool(re.search(r"\bTABLE\s+ROT\b", up)), angles=angles)


def heidenhain_reference(text: str, context, *, resolve=None) -> list[Expected]:
    """The expected ``--blocks`` rows of a Heidenhain conversational program run against ``context``.

    Parameters
    ----------
    text : str
        The program.
    context : interpolators.context.MachineContext
        The tables the reader is given (preset ``G54``, tools, home).
    resolve : callable, optional
        ``resolve(name) -> text`` of the program a ``CALL PGM name`` runs (the called program
        shares the Q parameters and transformations, has its own unit and labels, and returns at
        its ``END PGM``); without it a CALL PGM is not modelled.

    Returns
    -------
    list of Expected
        One entry per motion or dwell, in order.

    Raises
    ------
    ReferenceError
        The program uses a function this reference does not model.
    """
    t = _Tnc(context)
    t.resolve = resolve
    _execute(t, text, resolve, called=False)
    if t.fk.waiting is not None:
        raise ReferenceError("an FK element left open or without FSELECT at the end")
    return t.out


def _execute(t: _Tnc, text: str, resolve, *, called: bool) -> None:
    """Run one program's blocks on the machine state ``t`` (a called one: to its END PGM)."""
    blocks = _blocks(text)
    # label names compared without case (the blocks are read upper-cased)
    labels = {_label_of(b).upper(): i for i, (_, b) in enumerate(blocks) if re.match(r"LBL\s*\S", b.upper())}
    scale = t.scale
    # QL parameters are the program's own (TNC 640 user's manual 34059x-02, 9.1): a called one starts without
    # the caller's, which are back after it
    local = {k: t.q.pop(k) for k in [k for k in t.q if k.startswith("QL")]} if called else {}
    outer, t.program = t.program, (blocks, labels)
    outer_raw, t.raw = t.raw, text.lstrip("\ufeff").split("\n")
    counters: dict[int, int] = {}
    stack: list[tuple[int, int, int]] = []  # (return to, label, runs left)
    pc, steps = 0, 0
    while pc < len(blocks):
        steps += 1
        if steps > 2_000_000:
            raise ReferenceError("more than 2e6 blocks executed")
        line, b = blocks[pc]
        up = b.upper()
        nxt = pc + 1
        if up.startswith("END PGM"):
            break
        _track_feed(t, up)
        if up.startswith("BEGIN PGM"):
            t.scale = 25.4 if up.split()[-1] == "INCH" else 1.0
        elif up.startswith("CALL PGM"):
            if resolve is None:
                raise ReferenceError("CALL PGM without a resolver")
            name = re.match(r"CALL\s+PGM\s*(.+)$", b, re.I).group(1)  # CALL PGM100 as CALL PGM 100
            _execute(t, resolve(name.strip().strip('"')), resolve, called=True)
        elif up.startswith(("CALL LBL", "LBL")):
            nxt = _label_block(t, up, pc, labels, counters, stack)
        elif up.startswith("FN"):
            label = _fn(t, b)
            if label is not None:
                nxt = labels[label.upper()] + 1
        elif re.match(r"Q[LR]?\d+\s*=", up):
            q, expr = up.split("=", 1)
            t.q[q.strip()] = _Formula(expr, t.q).value()
        elif re.match(r"(DECLARE STRING\s+)?QS\d+\s*=", up):
            _string_formula(t, b)
        elif up.startswith("TOOL"):  # TOOL CALL QSn: the name the string parameter holds
            _tool(t, re.sub(r"^(TOOL CALL\s+)QS(\d+)", lambda qm: f'{qm.group(1)}"{t.strings[int(qm.group(2))]}"', up))
        elif up.startswith("TRANS"):
            _trans(t, up)
        elif up.startswith("PLANE") and t.ctx.kinematics is not None:
            _plane(t, line, up)
        elif up.startswith("FUNCTION FEED DWELL"):
            _feed_dwell_def(t, up)
        elif up.startswith("FUNCTION TCPM") or up.startswith("FUNCTION RESET TCPM"):
            _function_tcpm(t, up)
        elif up.startswith("FUNCTION DWELL"):
            _function_dwell(t, line, up)
        elif up.startswith(("PLANE", "FUNCTION")):
            _without_motion(t, up)
        elif re.match(r"CYCLE? DEF", up):
            _cycle_def(t, line, up)
        elif re.match(r"TCH\s*PROBE", up):
            _touch_probe(t, line, up)
        elif up.startswith("PATTERN DEF"):
            t.pattern = _pattern_def(up, t.q)
        elif up.startswith("CONTOUR DEF"):
            _contour_def(t, up)
        elif up.startswith("CYCL CALL PAT"):
            t.modal = False  # F..: the feed between the points (F MAX, none: rapid)
            _pattern_def_call(t, line, "feed" if re.search(r"\bF\s*[\d.Q]", up) else "rapid")
        elif up.startswith("CYCL CALL POS"):
            t.modal = False
            _position_call(t, line, _words(up[len("CYCL CALL POS"):], t.q))
        elif up.startswith("CYCL CALL"):
            _cycl_call(t, line, up)
        elif re.fullmatch(r"(M\d+\s*)+(MB\s*(MAX|\d+\.?\d*)\s*(F\s*(MAX|\d+\.?\d*)\s*)?)?(M\d+\s*)*",
                          _m_words(up, t.q)[0]):
            _reduce_display(t, _m_words(up, t.q)[1])
            ms = [int(v) for v in re.findall(r"M(\d+)", _m_words(up, t.q)[0])]
            _tcpm_switch(t, ms)
            if t.ctx.wrapped_axes and {126, 127} & set(ms):  # M126 / M127 in a block of their own (TNC 640 manual)
                t.m126 = 126 in ms
            t.modal = (t.modal or 89 in ms) and 99 not in ms
            if 99 in ms:
                _run_cycle(t, line)
            mb = re.search(r"MB\s*(MAX|\d+\.?\d*)\s*(?:F\s*(MAX|\d+\.?\d*))?", up)
            if 140 in ms and mb:  # M140 MB alone: the retract of a line's M140, at the block's end
                _retract(t, line, mb.group(1), "MAX" if mb.group(2) is None else mb.group(2))
        elif _motion(t, line, up) is None and not re.match(r"(BLK FORM|STOP|M\d)", up):
            raise ReferenceError(f"block {b!r}")
        if re.search(r"\bM0*(2|30)\b", up) and not up.startswith(("FN", "Q")):
            if called:
                raise ReferenceError("M2/M30 in a called program")
            break
        pc = nxt
    t.scale = scale
    t.program = outer
    t.raw = outer_raw
    if called:
        for k in [k for k in t.q if k.startswith("QL")]:
            del t.q[k]
        t.q.update(local)


def _without_motion(t: _Tnc, up: str) -> None:
    """A PLANE or FUNCTION block the reference knows to move nothing (PLANE RESET, a plane of no rotation on a
    machine without kinematics, FUNCTION MODE MILL, the file functions FILECOPY / FILEMOVE / FILEDELETE of the TNC
    640 user's manual, FUNCTION PARAXCOMP DISPLAY / OFF and PARAXMODE OFF: the display of the parallel axes, their
    resets, TNC7 basic user's manual 81762x-19); any other is not modelled."""
    if not (up.startswith(("PLANE RESET", "FUNCTION MODE MILL", "FUNCTION FILECOPY", "FUNCTION FILEMOVE",
                           "FUNCTION FILEDELETE", "FUNCTION PARAXCOMP OFF", "FUNCTION PARAXMODE OFF",
                           "FUNCTION PARAXCOMP DISPLAY"))
            or re.match(r"PLANE (SPATIAL|PROJECTED|EULER|RELATIVE?|AXIAL)\b", up)
            and all(_val(v, t.q) == 0 for v in re.findall(
                r"(?:SP[ABC]|PRO(?:PR|MIN)|(?<!EUL)ROT|EUL(?:PR|NU|ROT)|(?<![A-Z])[ABC])\s*([-+]?\s*(?:[\d.]+|Q[LR]?\d+))",
                up))):
        raise ReferenceError(up)


def _cycl_call(t: _Tnc, line: int, up: str) -> None:
    """``CYCL CALL`` (with M words): the cycle defined last where the tool is, an ``M140 MB`` after it."""
    if up.strip() != "CYCL CALL" and not re.match(r"CYCL CALL\s+M", up):
        raise ReferenceError(up)
    t.modal = False
    _run_cycle(t, line)
    mb = re.search(r"M140\s+MB\s*(MAX|\d+\.?\d*)\s*(?:F\s*(MAX|\d+\.?\d*))?", up)
    if mb:  # M140 at the block's end, after the cycle
        _retract(t, line, mb.group(1), "MAX" if mb.group(2) is None else mb.group(2))


def _label_block(t: _Tnc, up: str, pc: int, labels: dict[str, int], counters: dict[int, int],
                 stack: list[tuple[int, int, int]]) -> int:
    """The block after ``CALL LBL`` / ``LBL`` at ``pc``: a subprogram call, a section repeat, or the return from
    ``LBL 0``; ``counters`` the repeats left per call block, ``stack`` the (return to, label, runs left) calls."""
    if up.startswith("CALL LBL"):
        m = re.match(r"CALL LBL\s*(\S+)\s*(?:REP\s*(Q[LR]?\d+|\d+))?", up)  # REPQ13: the count in a Q parameter
        target = labels[m.group(1).strip('"')]
        if m.group(2) is not None and _val(m.group(2), t.q) != int(_val(m.group(2), t.q)):
            raise ReferenceError(f"{up}: a fractional repeat count (no manual text says how the TNC rounds it)")
        if m.group(2) is None or target > pc:  # a subprogram; REP k of one after the call: k + 1 runs
            stack.append((pc + 1, target, 1 + (int(_val(m.group(2), t.q)) if m.group(2) else 0)))
            return target + 1
        left = counters.get(pc, int(_val(m.group(2), t.q)))
        if left > 0:
            counters[pc] = left - 1
            return target + 1
        counters.pop(pc, None)
    elif _label_of(up) == "0" and stack:
        back, target, runs = stack.pop()
        if runs > 1:
            stack.append((back, target, runs - 1))
            return target + 1
        return back
    return pc + 1


def _track_feed(t: _Tnc, up: str) -> None:
    """The modal feed F of path blocks, and M103 (for FUNCTION FEED DWELL); F AUTO, FU, FZ under it: unmodelled."""
    if not re.match(r"(L|LP|C|CP|CR|CT|APPR|DEP|RND|CHF|F[LCP]|M\d)\b", up):
        return
    rest, margs = _m_words(up, t.q)
    if 103 in margs:
        t.plunging = bool(margs[103])
    f = re.search(r"\bF\s*([-+]?\s*(?:Q[LR]?\d+|\d+\.?\d*|\.\d+))(?![\w.])", rest)
    if f:
        t.feed = _val(f.group(1).replace(" ", ""), t.q)
    elif t.feed_dwell is not None and re.search(r"\bF\s*(AUTO|[UZ])", rest):
        raise ReferenceError("FUNCTION FEED DWELL with F AUTO, FU or FZ")


def _motion(t: _Tnc, line: int, up: str) -> bool | None:
    """A path block; None when ``up`` is none."""
    polar = re.match(r"(APPR|DEP) P(LT|LN|CT|LCT)\b", up)
    if polar:  # the first / last point by PR, PA about the pole CC (TNC 426/430 manual, APPR PLT .. DEP PLCT)
        w = _words(up[polar.end():], t.q)
        _comp_words(t, w)
        if polar.group(1) == "DEP" and not _keeps_comp(w):
            t.comp = False
        end = t.machine(_polar_point(t, t.prog(), w["PR"] * t.scale, w["PA"], w))
        t.emit(line, "feed" if polar.group(2) in ("LT", "LN") or polar.group(1) == "DEP" else None, end,
               rows="last")
        return True
    for key in ("APPR LCT", "APPR LT", "APPR LN", "APPR CT"):
        if up.startswith(key):
            _approach(t, line, _words(up[len(key):], t.q), key.split()[1])
            return True
    if up.startswith("DEP LCT"):  # the arc leaving the contour, then the line to the programmed PN
        w = _words(up[7:], t.q)
        t.comp = t.comp and _keeps_comp(w)
        t.emit(line, "feed", t.target(w), rows="last")
        return True
    for form in ("LT", "LN", "CT"):
        if up.startswith("DEP " + form):
            _depart(t, line, _words(up[6:], t.q), form)
            return True
    head, _, rest = up.partition(" ")
    if head in ("FPOL", "FL", "FLT", "FC", "FCT", "FSELECT"):
        _free_contour(t, line, head, rest)
        return True
    if t.fk.waiting is not None and head in ("L", "LN", "CC", "C", "CP", "LP", "CR", "CT", "CTP", "RND", "CHF"):
        raise ReferenceError("a block after an FK element left open or without FSELECT")
    if head == "SPL":
        _spline(t, line, rest)
    elif head == "L":
        _line_block(t, line, _words(rest, t.q))
    elif head == "LN" and t.tcpm:
        _tool_vector_line(t, line, _words(rest, t.q))
    elif head == "LN":  # iTNC 530 manual: the end point displaced along N by the delta values; T ignored
        w = _words(rest, t.q)
        n = _surface_normal(w)
        if t.comp or t.turns_over() or t.rot or t.scl != 1 or (t.factors != 1).any():
            raise ReferenceError("LN under RL/RR or a transformation")
        t.emit(line, "rapid" if "FMAX" in w else "feed", t.target(w) + t.delta * n)
    elif head == "CC":
        _pole(t, _words(rest, t.q))
    elif head in ("C", "CP"):
        _arc(t, line, _words(rest, t.q), polar=head == "CP")
    elif head == "LP":
        _polar_line(t, line, _words(rest, t.q))
    elif head == "CR":
        _radius_arc(t, line, _words(rest, t.q))
    elif head in ("CT", "CTP"):
        _tangent_arc(t, line, _words(rest, t.q), polar=head == "CTP")
    elif head in ("RND", "CHF"):
        _start_corner(t, line, head, _words(rest if head == "RND" else "LEN" + rest.strip(), t.q))
    elif head in ("APPR", "DEP"):
        raise ReferenceError(f"{head} block")
    else:
        return None
    return True


def checked_program(text: str, context, *, check: bool = True, exact: bool = True):
    """The Heidenhain reader's program of ``text``, its blocks checked against this reference: every row of
    ``--blocks`` (the rotary and secondary axes' columns too: :func:`reader_rows`) agrees exactly (``exact=False``:
    radius-compensated rows within the tool radius, as :func:`match_blocks` allows). ``check=False``: the reader's
    program alone (one the reference does not model, or one the reader must refuse)."""
    from interpolators.heidenhain import parse_heidenhain
    from vcnc.commands.interpolate import blocks_table

    prog = parse_heidenhain(text, source="t.h", context=context)
    if not check:
        return prog
    match = match_blocks(heidenhain_reference(text, context), reader_rows(*blocks_table(prog)))
    assert match.mismatch is None, match.mismatch
    assert match.exact == len(prog.blocks) if exact else match.exact + match.within == len(prog.blocks)
    return prog


def _free_contour(t: _Tnc, line: int, head: str, rest: str) -> None:
    """FK blocks (:mod:`reference_heidenhain_fk`), in the XY plane: lines, and arcs about their centre (which
    becomes the pole, as the reader takes it); the tangent of a preceding non-FK element from its direction."""
    fk, p = t.fk, t.prog()
    if head == "FSELECT":
        done = fk.select(int(_val(rest.strip(), t.q)))
    else:
        words, refs = fk.parse(head, rest, t.q, t.scale, _val)
        if head == "FPOL":
            fk.pole = np.array([words.get("X", p[0]), words.get("Y", p[1])], float)
            return
        tangent = None
        if t.fk_end == len(t.out) and fk.last_direction is not None:
            tangent = fk.last_direction
        elif t.last_dir is not None:
            a, _ = t.affine()
            d = np.linalg.solve(a, t.last_dir)[:2]
            tangent = d / np.linalg.norm(d)
        number = re.match(r"\s*/?\s*(\d+)?", t.raw[line - 1]).group(1)
        done = fk.element(head, words, refs, line, int(number) if number else None, p[:2], tangent, 1e-6)
    for el, (_, end, centre, ccw) in done:
        _comp_words(t, el.v)
        q = p.copy()
        q[:2] = end
        if centre is None:
            t.emit(el.line, "feed", t.machine(q))
        else:
            t.pole = p.copy()
            t.pole[:2] = centre
            t.pole_axes = (0, 1)
            t.emit(el.line, "arc_ccw" if ccw != t.turns_over() else "arc_cw", t.machine(q), centre=t.machine(t.pole))
            # the arc's direction at its end, for a DEP after it (the TNC 640 manual's FK examples end so)
            _arc_tangent(t, t.machine(q), t.machine(t.pole), ccw != t.turns_over(), (0, 1))
        t.fk_end = len(t.out)
