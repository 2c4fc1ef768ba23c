"""FK free contour programming of Heidenhain conversational programs: ``FPOL``, ``FL``, ``FLT``, ``FC``,
``FCT``, ``FSELECT``, resolved into ordinary lines and arcs.

Followed: iTNC 530 user's manual (conversational, 340 49x-03 / 60642x-03), section 6.6 "Path
Contours - FK Free Contour Programming" (pp. 255-272 of 340 49x-03: "Free programming of straight
lines", "Free programming of circular arcs", "Input possibilities": end point coordinates, direction
and length of contour elements, circle centre CC / radius / direction of rotation in the FC/FCT block,
closed contours, "Auxiliary points" on and near a contour (p. 248 of the easymanua.ls copy: ``13 FC DR-
R10 P1X+42.929 P1Y+60.071`` / ``14 FLT AN-70 PDX+50 PDY+53 D10``), relative data); TNC 425/415 B/407
user's manual section 5.6, "FK functions" table (p. 5-44: "Cartesian coordinates of an auxiliary point at
distance D from a contour element"); TNC 370 user's manual section 5.6 (pp. 5-39 .. 5-49: the dialogs "DIST
AUXIL POINT PD X-COORDINATE ?" and "DISTANCE FROM AUXILIARY POINT ?", p. 5-42, and the complete "Example 1",
"Example 2" and "Example 3 for exercise in FK free contour programming", pp. 5-48 .. 5-50: the FK stretches of 1
and 2 in tests/interpolators/test_heidenhain_fk.py, the forms of 1 and 3 that needed more in
tests/interpolators/test_heidenhain_manual_examples.py; Example 1 and 3 run as printed, Example 2 with this
module's FSELECT numbers, see below). The example blocks of these sections (``FPOL X+20 Y+30``, ``FL
IX+10 Y+20 RR F100``, ``FCT PR+15 IPA+30 DR+ R15``, ``FC CCX+20 CCY+15 DR+ R15``, ``FC DR+ R15 CCPR+35
CCPA+40``, ``FC DR- R15 CLSD+ CCX+20 CCY+35``, ``FCT IX+20 DR- R20 CCA+90 RX 13``, ``FL IPR+35 PA+0 RPR 13``,
``FL LEN 12.5 PAR 17 DP 12.5`` / ``FSELECT 2``, ``FL IAN+220 RAN 18``, ``FL AN+60 PDX+30 PDY+30 D+10`` /
``FSELECT 3``) show how they are written. The iTNC 530 manual's own "FK programming 3" example (a chain of
tangential arcs) was not found in the stored pages; its form (arcs ``FCT DR.. R..`` open until an arc of known
centre fixes the chain, FSELECT after it) is tested with a hand-made chain.

Data of an element (program coordinates of the working plane, the program's unit). The manuals allow FK
"only in the working plane"; the words name its axes: X and Y with tool axis Z, and, our reading (no manual
page writes FK in another plane), Z and X (ZX, ``TOOL CALL .. Y``) or Y and Z (YZ, ``TOOL CALL .. X``), the
plane's first axis taking the place of X (``FL Z+20 X+0``, ``CCZ``, ``P1Z``, ``RZ 12``; angles from the first
axis toward the second, DR+ turning that way, as for ``CC``/``C`` in that plane); a word naming the tool axis
is an error. Below, X and Y stand for the plane's first and second axis:

* end point: ``X``/``Y`` (``IX``/``IY`` from the element's start), polar ``PR``/``PA`` about the FK
  pole ``FPOL`` (``IPR``/``IPA`` from the start's polar radius / angle);
* straight line: ``LEN`` its length, ``AN`` its direction angle, ``IAN`` the angle to the preceding
  element's direction; ``FLT``: tangent to the preceding element; ``PAR n``: parallel to the line of
  block n (either way; ``DP``, the distance between them); ``P1X P1Y`` (``P2X P2Y``): points on the line or
  its extension; ``PDX PDY D``: an auxiliary point at the distance D from the line's extension (either side);
* arc: ``DR+``/``DR-`` (counter-clockwise / clockwise), ``R`` radius, centre ``CCX``/``CCY`` (``ICCX``/
  ``ICCY`` from the start) or ``CCPR``/``CCPA`` (``ICCPR``/``ICCPA``) about FPOL, ``CCA`` its centre angle,
  ``LEN`` its chord, ``AN`` the direction of its entry tangent (at the start); ``FCT``: tangent to the
  preceding element; ``P1X P1Y`` .. ``P3X P3Y``: points on the circle; ``PDX PDY D``: an auxiliary point at
  the distance D from the circle (inside or outside);
* relative data: ``RX n``, ``RY n``, ``RPR n``, ``RPA n`` (the ``I`` value from the end point of block n
  instead of this element's start), ``RAN n`` (``IAN`` from the direction of block n), ``RCCX n``,
  ``RCCY n``, ``RCCPR n``, ``RCCPA n`` (the centre's ``I`` values from block n's end point); block n is an
  FK element run before or one of the open stretch;
* ``CLSD+`` marks the start of a closed contour, ``CLSD-`` its end (the end point is the start of the
  ``CLSD+`` element; a bare ``CLSD`` is the one of the two not yet given).

An element whose own data, its start and the preceding element's direction fix it is resolved in closed form (lines
and circles intersected). An element they leave open (the TNC's "not yet resolved" element: a line of known
direction without length, ``FL AN+45``; an arc without its end, ``FCT DR- R15``; ``FL X+10``; ...) opens a stretch,
and each FK element after it joins the stretch until the data fix its leading elements: as the manuals' FK graphics
draw an element once the data entered determine it and show its solutions when there are several (iTNC 530 manual,
section 6.6, on the FK graphics; the stored pages hold that section's example blocks, not its text on the graphics:
our reading). In the stretch each element is written by its start direction, its size (a line's length, an arc's
signed radius) and an arc's sweep, walked from the stretch's start; data naming one of these set it (FLT/FCT: the
preceding end direction; AN, IAN, LEN, R with DR, CCA), every other datum is a residual of the walked geometry. The
unknowns the data fix are those no direction of the null space of the residuals' Jacobian (at a generic point)
moves; the leading elements whose unknowns are all fixed are solved by Newton's method (to 1e-9 program units) from
starts spread over those unknowns and emitted, the rest waits. So an open line is ended by the next line of known
direction and end point, a rounding FCT of radius and sense only with the FLT after it, two circles joined by a
bare FLT, a chain of tangential arcs by the arc of known centre at its end, an arc by the next line's auxiliary
point at a distance. Where the data allow several solutions the TNC shows them and the programmer picks one, saved
as ``FSELECT n`` after the block that made them determined: here the solutions (of the one element, or of the
stretch's elements resolved together) are numbered by the lengths of their elements in turn, shortest first, equal
lengths (to 1e-6 program units) by the direction they leave their start in, counter- clockwise from +X (the manuals
show the choice in the graphic but define no order: our reading; the TNC 370 manual's Example 2 picks FSELECT 3, 2,
3, 2 of 4, 2, 3, 2 solutions found here, where this numbering needs 1, 1, 2, 1 for the lever its dimensions
describe, so the TNC numbers them otherwise), and ``FSELECT n`` picks the n-th. The TNC also counts an arc back to
its own start (sweep 0) where the data allow it: Example 3 writes ``FSELECT 2`` after ``13 FLT PAR9``, which leaves
the arc before it one end and that one; here ``FSELECT 1`` or ``2`` after such a block keeps the one end, with a
note (:func:`_back_to_start`). An arc of a stretch is no full circle unless its data name its end. A stretch still
open at a block that is not FK (or at the program's end) is an error naming its first element, what of it is open
and the data that would fix it; data that fix a stretch but fit no contour are an error naming the block that
brought them and where the stretch began.

The resolved element is a line ``L`` or an arc ``CC`` + ``C`` to the reader (the FK centre is then the
pole: the manuals say a CC programmed before is no longer valid after an FK contour), so radius
compensation ``RL``/``RR``, feeds, ``M`` functions, RND/CHF, APPR/DEP and the coordinate
transformations act on it as on those blocks.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import re

import numpy as np

from interpolators._words import Where, token_at
from interpolators.heidenhain_params import QParameters
from interpolators.heidenhain_words import Word, read_value

__all__ = ["FK_KEYWORDS", "FkElement", "FkWords", "FreeContour", "read_fk_words"]

#: The FK blocks, by their first word (FCT and FLT before FC and FL for a regular expression).
FK_KEYWORDS = ("FPOL", "FSELECT", "FCT", "FLT", "FC", "FL")

_FK_WORD_RE = re.compile(
    r"(?P<clsd>CLSD\s*[+-]?)(?![\d.A-Z])|(?P<dr>DR\s*[+-])(?![\d.Q(])|(?P<rcomp>R[LR0])(?![\d.A-Z])"
    r"|(?P<ref>R(?:CC)?(?:[XYZ]|PR|PA)|RAN|PAR)(?=\s*\d)|(?P<m>M)(?=\s*\d)"
    r"|(?P<value>I?CC(?:[XYZ]|PR|PA)|CCA|P[123][XYZ]|PD[XYZ]|LEN|DP|D|I?AN|I?P[RA]|I?[XYZ]|R|F)(?=\s*[+-]?\s*[\d.Q(])",
    re.I,
)
_FK_EXPECTED = ("FK data: X/Y (IX/IY), PR/PA (IPR/IPA), LEN, AN/IAN, DR+/DR-, R, CCX/CCY, CCPR/CCPA, CCA, "
                "PAR/DP, P1X..P3Y, RX/RY/RPR/RPA/RAN/RCCX/RCCY n, CLSD+/-, RL/RR/R0, F, M")
#: The words an FK line / arc allows.
_LINE_KEYS = frozenset({"X", "Y", "IX", "IY", "PR", "PA", "IPR", "IPA", "LEN", "AN", "IAN", "PAR", "DP", "P1X",
                        "P1Y", "P2X", "P2Y", "PDX", "PDY", "D", "RX", "RY", "RPR", "RPA", "RAN", "CLSD", "RCOMP",
                        "F", "M"})
_ARC_KEYS = frozenset({"X", "Y", "IX", "IY", "PR", "PA", "IPR", "IPA", "LEN", "AN", "DR", "R", "CCX", "CCY", "ICCX",
                       "ICCY", "CCPR", "CCPA", "ICCPR", "ICCPA", "CCA", "P1X", "P1Y", "P2X", "P2Y", "P3X", "P3Y",
                       "PDX", "PDY", "D", "RX", "RY", "RPR", "RPA", "RCCX", "RCCY", "RCCPR", "RCCPA", "CLSD",
                       "RCOMP", "F", "M"})
_UNDETERMINED_LINE = "X/Y, LEN, PR/PA with a direction (AN, IAN, FLT, PAR), or both coordinates of the end point"
_UNDETERMINED_ARC = ("the circle (two of: CCX/CCY, CCPR/CCPA, R, FCT or AN tangency, the end point) and its end "
                     "(X/Y, PR/PA, LEN, CCA)")


@dataclasses.dataclass(frozen=True)
class FkWords:
    """The words of an FK block: ``values`` [program unit, deg] and block numbers ``refs`` by key, ``words``
    the source words (for columns and for the L/C block the element becomes: RL/RR/R0, F, M, DR)."""

    values: dict[str, float]
    refs: dict[str, int]
    words: dict[str, Word]
    ms: tuple[Word, ...]
    clsd: str | None  # "+", "-", "" (bare CLSD) or None


def read_fk_words(code: str, pos: int, where: Where, params: QParameters, *, column0: int,
                  axes: str = "XY") -> FkWords:
    """The words of an FK block from ``pos`` on; each at most once. ``axes``: the letters of the working plane's
    first and second axis (XY, ZX, YZ); the words naming them (X, IX, CCX, P1X, PDX, RX, ...) are kept under X
    for the first and Y for the second, a word naming the tool axis is an error."""
    values: dict[str, float] = {}
    refs: dict[str, int] = {}
    words: dict[str, Word] = {}
    ms: list[Word] = []
    clsd = None
    n = len(code)
    while pos < n:
        if code[pos] in " \t":
            pos += 1
            continue
        col = column0 + pos
        m = _FK_WORD_RE.match(code, pos)
        if m is None:
            tok = token_at(code, pos)
            where.fail(f"unknown word {tok!r} in an FK block", column=col, text=tok, expected=_FK_EXPECTED)
        kind, tok, end = m.lastgroup, m.group(0), m.end()
        key = name = tok.upper().replace(" ", "")
        if kind in ("ref", "value") and key[-1] in "XYZ":
            if key[-1] not in axes:
                where.fail(f"word {token_at(code, pos)!r} names the tool axis, not an axis of the working plane",
                           column=col, text=token_at(code, pos),
                           expected=f"FK data in the working plane {axes} of the TOOL CALL axis")
            key = key[:-1] + "XY"[axes.index(key[-1])]
        if kind == "clsd":
            key, clsd = "CLSD", key[4:]
            word = Word("CLSD", clsd, col, tok)
        elif kind == "dr":
            word, key = Word("DR", key[-1], col, tok), "DR"
        elif kind == "rcomp":
            word, key = Word(key, None, col, tok), "RCOMP"
        elif kind == "m":
            mm = re.compile(r"M\s*(\d+)", re.I).match(code, pos)
            end = mm.end()
            ms.append(Word("M", int(mm.group(1)[:9]), col, mm.group(0)))
            key, word = "", None
        else:
            value, end = read_value(code, end, where, params, what=name, column0=column0)
            word = Word(key, value, col, code[pos:end].strip())
            if kind == "ref":
                if not (value >= 1 and value == int(value)):
                    where.fail(f"{key} {value:g}: not a block number", column=col, text=word.text,
                               expected=f"{key} n, n the number of an FK block before this one")
                refs[key] = int(value)
            else:
                values[key] = value
        if end < n and code[end] not in " \t":
            tok = token_at(code, pos)
            where.fail(f"unknown word {tok!r} in an FK block", column=col, text=tok, expected=_FK_EXPECTED)
        if key:
            if key in words:
                where.fail(f"word {tok!r} repeats a word of this block", column=col, text=tok,
                           expected="each word at most once per block")
            words[key] = word
        pos = end
    return FkWords(values, refs, words, tuple(ms), clsd)


@dataclasses.dataclass(frozen=True)
class FkElement:
    """A resolved FK element in the working plane (program coordinates [program unit]): a line, or an arc
    about ``centre`` (``ccw``: DR+; ``end`` equal to ``start``: a full circle)."""

    start: np.ndarray
    end: np.ndarray
    centre: np.ndarray | None = None
    ccw: bool = True

    @property
    def length(self) -> float:
        if self.centre is None:
            return float(np.hypot(*(self.end - self.start)))
        return float(np.hypot(*(self.start - self.centre))) * self.sweep

    @property
    def sweep(self) -> float:
        """The arc's centre angle [rad], in (0, 2 pi]."""
        a0 = math.atan2(*(self.start - self.centre)[::-1])
        a1 = math.atan2(*(self.end - self.centre)[::-1])
        s = ((a1 - a0) if self.ccw else (a0 - a1)) % (2 * math.pi)
        return s if s > 1e-12 else 2 * math.pi

    def direction(self, *, at_end: bool = True) -> np.ndarray:
        """Unit tangent at the end (or the start) in the direction of travel."""
        if self.centre is None:
            d = self.end - self.start
            return d / np.hypot(*d)
        r = (self.end if at_end else self.start) - self.centre
        t = np.array([-r[1], r[0]]) if self.ccw else np.array([r[1], -r[0]])
        return t / np.hypot(*t)


# --- geometry: curves a point lies on, and their intersections ---------------------------------------------

@dataclasses.dataclass(frozen=True)
class _Curve:
    """A straight line through ``p`` along the unit vector ``u`` (``ray``: only ahead of p, beyond ``p``
    itself when ``strict``), or a circle about ``p`` of radius ``r``."""

    p: np.ndarray
    u: np.ndarray | None = None
    r: float = 0.0
    ray: bool = False
    strict: bool = False

    def holds(self, x: np.ndarray, tol: float) -> bool:
        d = x - self.p
        if self.u is None:
            return abs(float(np.hypot(*d)) - self.r) <= tol
        along = float(d @ self.u)
        if self.ray and along < (tol if self.strict else -tol):
            return False
        return abs(float(d[0] * self.u[1] - d[1] * self.u[0])) <= tol


def _unit(angle_deg: float) -> np.ndarray:
    a = math.radians(angle_deg)
    return np.array([math.cos(a), math.sin(a)])


def _line_circle(line: _Curve, circle: _Curve) -> list[np.ndarray]:
    d = line.p - circle.p
    b = float(d @ line.u)
    disc = b * b - (float(d @ d) - circle.r ** 2)
    if disc < -1e-12 * max(1.0, circle.r ** 2):
        return []
    root = math.sqrt(max(disc, 0.0))
    return [line.p + t * line.u for t in ((-b - root, -b + root) if root > 0 else (-b,))]


def _circle_circle(a: _Curve, b: _Curve) -> list[np.ndarray]:
    d = b.p - a.p
    dist = float(np.hypot(*d))
    if dist <= 1e-12:
        return []
    x = (dist ** 2 + a.r ** 2 - b.r ** 2) / (2 * dist)
    h2 = a.r ** 2 - x * x
    if h2 < -1e-12 * max(1.0, a.r ** 2):
        return []
    h = math.sqrt(max(h2, 0.0))
    e = d / dist
    n = np.array([-e[1], e[0]])
    base = a.p + x * e
    return [base - h * n, base + h * n] if h > 0 else [base]


def _intersect(a: _Curve, b: _Curve, tol: float) -> list[np.ndarray]:
    """The points on both curves (rays: ahead of their start), without repeats."""
    if a.u is not None and b.u is not None:
        det = a.u[0] * (-b.u[1]) - a.u[1] * (-b.u[0])
        if abs(det) <= 1e-12:
            return []
        d = b.p - a.p
        s = (d[0] * (-b.u[1]) - d[1] * (-b.u[0])) / det
        pts = [a.p + s * a.u]
    elif a.u is not None:
        pts = _line_circle(a, b)
    elif b.u is not None:
        pts = _line_circle(b, a)
    else:
        pts = _circle_circle(a, b)
    out: list[np.ndarray] = []
    for x in pts:
        if a.holds(x, tol) and b.holds(x, tol) and not any(np.hypot(*(x - y)) <= tol for y in out):
            out.append(x)
    return out


def _solve(curves: list[_Curve], tol: float) -> list[np.ndarray]:
    """The points on every curve of ``curves`` (at least two): the first two intersected, the others checked."""
    return [x for x in _intersect(curves[0], curves[1], tol) if all(c.holds(x, tol) for c in curves[2:])]


def _perp(u: np.ndarray) -> np.ndarray:
    return np.array([-u[1], u[0]])


# --- the run's FK state ----------------------------------------------------------------------------------

@dataclasses.dataclass
class _Waiting:
    """An FK block not emitted yet: its keyword, data and source line."""

    kw: str
    data: FkWords
    where: Where
    number: int | None
    closing: bool = False  # CLSD- (or the second bare CLSD): the element ends where the closed contour began


#: What the reader hands back: elements to run as L / CC + C blocks, with the block they come from.
Emitted = tuple[FkElement, FkWords, Where, int | None]


class FreeContour:
    """The FK state of a program run: the pole ``FPOL``, the elements resolved so far (by block number, for
    relative data), the start of a closed contour, the open stretch (elements their data leave open, from
    ``start`` in the direction ``tangent``), and resolved elements with several solutions waiting for FSELECT."""

    def __init__(self) -> None:
        self.pole: np.ndarray | None = None
        self.history: dict[int, FkElement] = {}
        self.closed_start: np.ndarray | None = None
        self.stretch: list[_Waiting] = []
        self.start: np.ndarray | None = None
        self.tangent: np.ndarray | None = None
        # elements resolved with several solutions, and the block whose data resolved them (FSELECT follows it)
        self.choices: tuple[list[_Waiting], list[list[FkElement]], _Waiting] | None = None
        self.tol = 1e-6  # [program unit] the run's arc end tolerance, for the closed-form solutions
        # the solver also met an arc back to its own start (sweep 0 or a full circle the data do not name)
        self.degenerate = False
        # the block whose data left one element and such an arc: an FSELECT right after it keeps the one
        self.lone: _Waiting | None = None
        self.notes: list[str] = []  # leniencies for the program's notes

    @property
    def waiting(self) -> bool:
        """An element is open or waits for FSELECT."""
        return bool(self.stretch) or self.choices is not None or self.lone is not None

    # --- blocks ---------------------------------------------------------------------------------------
    def set_pole(self, data: FkWords, start: np.ndarray, where: Where) -> None:
        """``FPOL X.. Y..`` (IX/IY: from the current position): the pole of FK polar coordinates."""
        pole = start.copy()
        for key, word in data.words.items():
            if key not in ("X", "Y", "IX", "IY"):
                where.fail(f"word {word.text!r} not allowed in FPOL", column=word.column, text=word.text,
                           expected="FPOL X.. Y.. (Cartesian coordinates of the FK pole)")
            i = "XY".index(key[-1])
            pole[i] = word.value if key in ("X", "Y") else start[i] + word.value
        self.pole = pole

    def select(self, choice: float, where: Where, column: int, text: str) -> list[Emitted]:
        """``FSELECT n``: the n-th solution of the elements resolved before it; then what the open rest's data
        resolve from its end."""
        lone, self.lone = self.lone, None
        if self.choices is None and lone is not None and choice in (1, 2):
            self.notes.append(f"FSELECT {choice:g} after line {lone.where.line}: its data leave one element and an "
                              "arc back to its own start, which the TNC counts as a solution: the one element kept")
            return []
        if self.choices is None:
            where.fail("FSELECT without an FK element of several solutions before it", column=column, text=text,
                       expected="FSELECT n right after the FK element whose solutions it picks from")
        elements, solutions, _ = self.choices
        if not (choice == int(choice) and 1 <= choice <= len(solutions)):
            where.fail(f"FSELECT {choice:g}: {_which(elements)} {len(solutions)} solutions", column=column, text=text,
                       expected=f"FSELECT 1 .. {len(solutions)}")
        self.choices = None
        chain = solutions[int(choice) - 1]
        out = [self._done(w, e) for w, e in zip(elements, chain)]
        if self.stretch:
            self.start, self.tangent = chain[-1].end, chain[-1].direction()
            out += self._advance()
        return out

    def element(self, kw: str, data: FkWords, start: np.ndarray, tangent: np.ndarray | None, where: Where,
                number: int | None, tol: float) -> list[Emitted]:
        """An FL, FLT, FC or FCT block starting at ``start`` (the preceding element's end, ``tangent`` its unit
        direction there, None when there is none), or after the open stretch: the elements it resolves, in order."""
        self.lone = None
        if self.choices is not None:
            self.unresolved()
        allowed = _LINE_KEYS if kw in ("FL", "FLT") else _ARC_KEYS
        for key, word in data.words.items():
            if key not in allowed:
                where.fail(f"word {word.text!r} not allowed in {kw}", column=word.column, text=word.text,
                           expected=f"{kw} with " + ", ".join(sorted(k for k in allowed if k != "RCOMP")))
        if kw in ("FLT", "FCT") and tangent is None and not self.stretch:
            where.fail(f"{kw} without a preceding contour element", column=1, text=where.text,
                       expected=f"a line or arc before {kw} (its tangent)")
        if kw == "FC" and "DR" not in data.words and "AN" not in data.values:
            where.fail(f"{kw} without a direction of rotation", column=1, text=where.text, expected="DR+ or DR-")
        distance = {"PDX", "PDY", "D"} & set(data.values)
        if distance and len(distance) < 3:
            word = data.words[sorted(distance)[0]]
            where.fail(f"{word.text}: an auxiliary point at a distance needs PDX, PDY and D", column=word.column,
                       text=word.text, expected="PDX.. PDY.. D.. (the point and its distance from the element)")
        opened = self.closed_start is not None or any(w.data.clsd is not None and not w.closing for w in self.stretch)
        new = _Waiting(kw, data, where, number, closing=data.clsd == "-" or (data.clsd == "" and opened))
        if new.closing and not opened:
            where.fail("CLSD- without a CLSD+ before it", column=data.words["CLSD"].column,
                       text=data.words["CLSD"].text, expected="CLSD+ on the first element of the closed contour")
        self.tol = tol
        if not self.stretch:
            self.start, self.tangent = start, tangent
            if _closed_form(new) and _fixed_prefix(self, [new]) == 1:
                return self._alternatives([new], _single(new, start, tangent, self, tol), new)
        self.stretch.append(new)
        return self._advance()

    def unresolved(self) -> None:
        """A block other than the next FK element (or the program's end) while one waits: an error naming it."""
        self.lone = None
        if self.choices is not None:
            elements, solutions, newest = self.choices
            w = elements[-1]
            by = f" (fixed by the {newest.kw} of line {newest.where.line})" if newest is not w else ""
            w.where.fail(f"{w.kw}: {_which(elements)} {len(solutions)} solutions{by} and no FSELECT picks one",
                         column=1, text=w.where.text,
                         expected=f"FSELECT 1 .. {len(solutions)} after the {newest.kw} of line {newest.where.line}")
        if self.stretch:
            w, rest = self.stretch[0], self.stretch[1:]
            after = f", not even with the FK blocks of lines {rest[0].where.line}-{rest[-1].where.line} after it" \
                if rest else ""
            what, data = _open_what(w)
            w.where.fail(f"{w.kw}: {what} is not determined{after} (the TNC's 'not yet resolved' element)",
                         column=1, text=w.where.text, expected=f"{data}, or a next FK element whose data fix it")

    # --- resolution -----------------------------------------------------------------------------------
    def _advance(self) -> list[Emitted]:
        """Resolve the leading elements of the open stretch as long as the data so far fix them."""
        out: list[Emitted] = []
        while self.stretch:
            count = _fixed_prefix(self, self.stretch)
            if count == 0:
                return out
            elements, solutions, newest = self.stretch[:count], _solve_stretch(self, count), self.stretch[-1]
            self.stretch = self.stretch[count:]
            out += self._alternatives(elements, solutions, newest)
            if self.choices is not None:
                return out
            self.start, self.tangent = solutions[0][-1].end, solutions[0][-1].direction()
        return out

    def _alternatives(self, elements: list[_Waiting], solutions: list[list[FkElement]],
                      newest: _Waiting) -> list[Emitted]:
        """The solutions of ``elements`` (resolved when ``newest`` came): one is emitted, several wait for FSELECT,
        none is an error."""
        if not solutions:
            what = "its data" if elements == [newest] else f"the data of the open FK elements from line " \
                                                           f"{elements[0].where.line} on"
            newest.where.fail(f"{newest.kw}: no element fits {what} (they contradict each other or the contour so "
                              "far)", column=1, text=newest.where.text, expected="FK data describing one element")
        lone, self.degenerate = self.degenerate, False
        if len(solutions) > 1:
            self.choices = (elements, solutions, newest)
            return []
        if lone:
            self.lone = newest
        return [self._done(w, e) for w, e in zip(elements, solutions[0])]

    def _done(self, w: _Waiting, element: FkElement) -> Emitted:
        if w.number is not None:
            self.history[w.number] = element
        if w.closing:
            self.closed_start = None
        elif w.data.clsd is not None:
            self.closed_start = element.start.copy()
        return element, w.data, w.where, w.number

    def reference(self, w: _Waiting, key: str, walked: dict[int, FkElement] | None = None) -> FkElement:
        """The element of the block ``w.data.refs[key]`` names (relative data): resolved before, or one of the
        open stretch as ``walked`` has it."""
        n = w.data.refs[key]
        if walked is not None and n in walked:
            return walked[n]
        if n not in self.history:
            word = w.data.words[key]
            w.where.fail(f"{word.text}: block {n} is not an FK element run before", column=word.column, text=word.text,
                         expected="relative data referring to an FK block (FL, FLT, FC, FCT) before this one")
        return self.history[n]

    def polar(self, w: _Waiting, key: str) -> np.ndarray:
        """The FK pole, for the polar word ``key``; an error without FPOL."""
        if self.pole is None:
            word = w.data.words[key]
            w.where.fail(f"{word.text} without an FK pole", column=word.column, text=word.text,
                         expected="an FPOL block before FK polar coordinates (a CC is not the FK pole)")
        return self.pole


def _end_curves(w: _Waiting, start: np.ndarray, fk: FreeContour, *, chord: bool) -> list[_Curve]:
    """The curves the end point lies on by the element's own data (``chord``: LEN is an arc's chord)."""
    v, out = w.data.values, []
    for i, axis in enumerate("XY"):
        if axis in v or "I" + axis in v:
            base = fk.reference(w, "R" + axis).end if "R" + axis in w.data.refs else start
            at = v[axis] if axis in v else base[i] + v["I" + axis]
            out.append(_Curve(np.array([at, 0.0]) if i == 0 else np.array([0.0, at]),
                              np.array([0.0, 1.0]) if i == 0 else np.array([1.0, 0.0])))
    if any(k in v for k in ("PR", "IPR", "PA", "IPA")):
        key = next(k for k in ("PR", "IPR", "PA", "IPA") if k in v)
        pole = fk.polar(w, key)
        ref = fk.reference(w, "RPR").end if "RPR" in w.data.refs else start
        if "PR" in v or "IPR" in v:
            out.append(_Curve(pole, r=v["PR"] if "PR" in v else float(np.hypot(*(ref - pole))) + v["IPR"]))
        ref = fk.reference(w, "RPA").end if "RPA" in w.data.refs else start
        if "PA" in v or "IPA" in v:
            a = v["PA"] if "PA" in v else math.degrees(math.atan2(*(ref - pole)[::-1])) + v["IPA"]
            out.append(_Curve(pole, _unit(a), ray=True))
    if "LEN" in v and chord:
        out.append(_Curve(start, r=abs(v["LEN"])))
    if w.closing:
        out += _point(fk.closed_start)
    return out


def _point(p: np.ndarray) -> list[_Curve]:
    return [_Curve(p.copy(), np.array([0.0, 1.0])), _Curve(p.copy(), np.array([1.0, 0.0]))]


def _line_directions(w: _Waiting, start: np.ndarray, tangent: np.ndarray | None, fk: FreeContour,
                     tol: float) -> list[np.ndarray] | None:
    """The directions the line's own data allow (None: no direction data)."""
    v, sets = w.data.values, []
    if w.kw == "FLT":
        sets.append([tangent])
    if "AN" in v:
        sets.append([_unit(v["AN"])])
    if "IAN" in v:
        base = fk.reference(w, "RAN").direction() if "RAN" in w.data.refs else tangent
        if base is None:
            w.where.fail("IAN without a preceding element", column=w.data.words["IAN"].column,
                         text=w.data.words["IAN"].text, expected="AN, or IAN after a contour element")
        sets.append([_unit(math.degrees(math.atan2(base[1], base[0])) + v["IAN"])])
    if "PAR" in w.data.refs:
        ref = fk.reference(w, "PAR")
        if ref.centre is not None:
            word = w.data.words["PAR"]
            w.where.fail(f"{word.text}: block {w.data.refs['PAR']} is an arc", column=word.column, text=word.text,
                         expected="PAR n with n a straight FK line")
        d = ref.direction()
        if "DP" in v and abs(abs(float((start - ref.start) @ _perp(d))) - abs(v["DP"])) > tol:
            word = w.data.words["DP"]
            w.where.fail(f"{word.text}: the line's start is not at this distance from block {w.data.refs['PAR']}",
                         column=word.column, text=word.text, expected="DP, the distance between the parallel lines")
        sets.append([d, -d])
    for key in ("P1", "P2"):
        if key + "X" in v and key + "Y" in v:
            d = np.array([v[key + "X"], v[key + "Y"]]) - start
            if np.hypot(*d) > tol:
                d = d / np.hypot(*d)
                sets.append([d, -d])
    if not sets:
        return None
    return [d for d in sets[0] if all(any(np.hypot(*(d - e)) <= 1e-6 for e in s) for s in sets[1:])]


def _line_solutions(w: _Waiting, start: np.ndarray, tangent: np.ndarray | None, fk: FreeContour,
                    tol: float) -> list[FkElement]:
    """The lines the data allow (the data fix the line: :func:`_fixed_prefix`)."""
    ends = _end_curves(w, start, fk, chord=False)
    if "LEN" in w.data.values:
        ends.append(_Curve(start, r=abs(w.data.values["LEN"])))
    dirs = _line_directions(w, start, tangent, fk, tol)
    out: list[FkElement] = []
    for d in (dirs if dirs is not None else [None]):
        curves = ends + ([_Curve(start, d, ray=True, strict=True)] if d is not None else [])
        if len(curves) < 2:
            w.where.fail(f"{w.kw}: the end point is not determined", column=1, text=w.where.text,
                         expected=_UNDETERMINED_LINE)
        out += [FkElement(start, e) for e in _solve(curves, tol) if np.hypot(*(e - start)) > tol]
    return out


def _given_centre(w: _Waiting, start: np.ndarray, fk: FreeContour) -> list[_Curve]:
    """The curves the centre lies on by its coordinates CCX/CCY, CCPR/CCPA (I, R forms)."""
    v, out = w.data.values, []
    for i, axis in enumerate("XY"):
        key = "CC" + axis
        if key in v or "I" + key in v:
            base = fk.reference(w, "R" + key).end if "R" + key in w.data.refs else start
            at = v[key] if key in v else base[i] + v["I" + key]
            out.append(_Curve(np.array([at, 0.0]) if i == 0 else np.array([0.0, at]),
                              np.array([0.0, 1.0]) if i == 0 else np.array([1.0, 0.0])))
    for key in ("CCPR", "ICCPR", "CCPA", "ICCPA"):
        if key in v:
            pole = fk.polar(w, key)
            ref = fk.reference(w, "R" + key.lstrip("I")).end if "R" + key.lstrip("I") in w.data.refs else start
            if key.endswith("PR"):
                out.append(_Curve(pole, r=v[key] if key == "CCPR" else float(np.hypot(*(ref - pole))) + v[key]))
            else:
                a = v[key] if key == "CCPA" else math.degrees(math.atan2(*(ref - pole)[::-1])) + v[key]
                out.append(_Curve(pole, _unit(a), ray=True))
    return out


def _centre_curves(w: _Waiting, start: np.ndarray, tangent: np.ndarray | None, ccw: bool | None,
                   fk: FreeContour) -> list[_Curve]:
    """The curves the centre lies on by the arc's own data (before the end point's)."""
    v, out = w.data.values, _given_centre(w, start, fk)
    if "R" in v:
        out.append(_Curve(start, r=abs(v["R"])))
    entry = tangent if w.kw == "FCT" else None
    if "AN" in v:
        entry = _unit(v["AN"])
    if entry is not None:
        n = _perp(entry)
        out.append(_Curve(start, n if ccw is not False else -n, ray=ccw is not None, strict=True))
    for key in ("P1", "P2", "P3"):
        if key + "X" in v and key + "Y" in v:
            p = np.array([v[key + "X"], v[key + "Y"]])
            out.append(_Curve((start + p) / 2, _perp((p - start) / np.hypot(*(p - start)))))
    return out


def _arc_solutions(w: _Waiting, start: np.ndarray, tangent: np.ndarray | None, fk: FreeContour,
                   tol: float) -> list[FkElement]:
    """The arcs the data allow (the data fix the arc: :func:`_fixed_prefix`)."""
    dr = w.data.words.get("DR")
    ccw = None if dr is None else dr.value == "+"
    ends = _end_curves(w, start, fk, chord=True)
    centres = _centre_curves(w, start, tangent if w.kw == "FCT" else None, ccw, fk)
    end_points = _solve(ends, tol) if len(ends) >= 2 else [None]
    out: list[FkElement] = []
    for e in end_points:
        cc = centres + ([] if e is None or np.hypot(*(e - start)) <= tol else
                        [_Curve((start + e) / 2, _perp((e - start) / np.hypot(*(e - start))))])
        if len(cc) < 2:
            w.where.fail(f"{w.kw}: the circle is not determined", column=1, text=w.where.text,
                         expected=_UNDETERMINED_ARC)
        for c in _solve(cc, tol):
            r = float(np.hypot(*(start - c)))
            if r <= tol:
                continue
            sense = ccw
            if sense is None:
                entry = tangent if w.kw == "FCT" else _unit(w.data.values["AN"]) if "AN" in w.data.values else None
                if entry is None:
                    w.where.fail(f"{w.kw} without a direction of rotation", column=1, text=w.where.text,
                                 expected="DR+ or DR-")
                sense = float(entry[0] * (c - start)[1] - entry[1] * (c - start)[0]) > 0
            if e is not None:
                if abs(float(np.hypot(*(e - c))) - r) <= tol:
                    out.append(FkElement(start, e, c, sense))
                continue
            found = _arc_ends(w, start, c, r, sense, ends, tol)
            if found is None:
                w.where.fail(f"{w.kw}: where it ends on its circle is not determined", column=1, text=w.where.text,
                             expected=_UNDETERMINED_ARC)
            out += found
    return out


def _arc_ends(w: _Waiting, start: np.ndarray, c: np.ndarray, r: float, ccw: bool, ends: list[_Curve],
              tol: float) -> list[FkElement] | None:
    """The arc's end points on its circle by CCA or one end curve; None when its data give none."""
    v = w.data.values
    if "CCA" in v:
        a = math.radians(abs(v["CCA"])) * (1 if ccw else -1)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        e = c + rot @ (start - c)
        return [FkElement(start, e, c, ccw)] if all(k.holds(e, tol) for k in ends) else []
    if not ends:
        return None
    return [FkElement(start, e, c, ccw) for e in _solve([_Curve(c, r=r)] + ends, tol)]



# --- open stretches: elements their own data leave open, solved with the data of the ones after them ---------
#
# Each element of a stretch is written by its start direction theta, its size (a line's length, an arc's signed
# radius: > 0 counter-clockwise) and an arc's sweep, walked from the stretch's start: a line ends at S + len u(theta),
# an arc turns about C = S + rho n(theta) (n the left normal) through k sweep (k the sign of rho). Data that name one
# of these (FLT/FCT: theta the preceding end direction; AN, IAN; LEN of a line; R with DR; CCA) set it; the
# unknowns left are solved by Newton's method from the data that remain, each an equation (a residual) of the
# walked geometry. A leading run of elements is resolved once no direction of the null space of the residuals'
# Jacobian (at a generic point) moves its unknowns: then Newton's method from starts spread over the fixed
# unknowns finds its solutions.

_TWO_PI = 2 * math.pi
#: The data naming an arc's end point or sweep (without them a stretch's arc is no full circle).
_END_KEYS = frozenset({"X", "Y", "IX", "IY", "PR", "PA", "IPR", "IPA", "CCA"})
#: Starts converging to solutions found before after which no other is looked for.
_ENOUGH = 32


@dataclasses.dataclass(frozen=True)
class _Walked:
    """An element of a stretch as walked from given unknowns: its geometry and the values it was walked with."""

    element: FkElement
    theta: float  # start direction [rad]
    end_theta: float
    size: float  # length, or signed radius
    sweep: float  # [rad], 0 for a line


def _theta_source(w: _Waiting) -> str | None:
    """Which datum sets the element's start direction (None: an unknown)."""
    if w.kw in ("FLT", "FCT"):
        return "tangent"
    if "AN" in w.data.values:
        return "AN"
    if "IAN" in w.data.values and w.kw in ("FL", "FLT"):
        return "IAN"
    return None


def _layout(w: _Waiting) -> tuple[bool, bool, bool]:
    """Which of (theta, size, sweep) are unknowns of the element."""
    v, arc = w.data.values, w.kw in ("FC", "FCT")
    size_known = ("LEN" in v) if not arc else ("R" in v and "DR" in w.data.words)
    return _theta_source(w) is None, not size_known, arc and "CCA" not in v


def _walk(fk: FreeContour, stretch: list[_Waiting], z: np.ndarray) -> tuple[list[_Walked], np.ndarray]:
    """The stretch walked with the unknowns ``z`` from fk.start, and the residuals of all its data."""
    s, t = fk.start, fk.tangent
    tau = None if t is None else math.atan2(t[1], t[0])
    walked: dict[int, FkElement] = {}
    closed = fk.closed_start
    out, res, k = [], [], 0
    for w in stretch:
        v, arc = w.data.values, w.kw in ("FC", "FCT")
        free = _layout(w)
        vals = []
        for unknown in free:
            vals.append(z[k] if unknown else None)
            k += unknown
        src = _theta_source(w)
        if src == "tangent":
            theta = tau
        elif src == "AN":
            theta = math.radians(v["AN"])
        elif src == "IAN":
            theta = _base_direction(fk, w, tau, walked) + math.radians(v["IAN"])
        else:
            theta = vals[0]
        if arc:
            size = vals[1] if free[1] else abs(v["R"]) * (1 if w.data.words["DR"].value == "+" else -1)
            sweep = vals[2] if free[2] else math.radians(abs(v["CCA"]))
            n = np.array([-math.sin(theta), math.cos(theta)])
            c = s + size * n
            turn = sweep if size > 0 else -sweep
            rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
            element = FkElement(s, c + rot @ (s - c), c, size > 0)
            end_theta = theta + turn
        else:
            size = vals[1] if free[1] else abs(v["LEN"])
            sweep = 0.0
            element = FkElement(s, s + size * np.array([math.cos(theta), math.sin(theta)]))
            end_theta = theta
        if w.data.clsd is not None and not w.closing:
            closed = s
        res += _equations(fk, w, element, theta, tau, walked, closed)
        out.append(_Walked(element, theta, end_theta, size, sweep))
        if w.number is not None:
            walked[w.number] = element
        s, tau = element.end, end_theta
    return out, np.array(res, float)


def _base_direction(fk: FreeContour, w: _Waiting, tau: float | None, walked: dict[int, FkElement]) -> float:
    """The direction IAN turns from [rad]: block RAN n's end direction, or the preceding element's."""
    if "RAN" in w.data.refs:
        d = fk.reference(w, "RAN", walked).direction()
        return math.atan2(d[1], d[0])
    if tau is None:
        word = w.data.words["IAN"]
        w.where.fail("IAN without a preceding element", column=word.column, text=word.text,
                     expected="AN, or IAN after a contour element")
    return tau


def _point_rows(fk: FreeContour, w: _Waiting, point: np.ndarray, start: np.ndarray, walked: dict[int, FkElement],
                prefix: str) -> list[float]:
    """Residuals of the data placing one point of the element (``prefix`` "": its end; "CC": its centre)."""
    v, rows = w.data.values, []
    for i, axis in enumerate("XY"):
        key = prefix + axis
        if key in v:
            rows.append(point[i] - v[key])
        if "I" + key in v:
            base = fk.reference(w, "R" + key, walked).end if "R" + key in w.data.refs else start
            rows.append(point[i] - base[i] - v["I" + key])
    pr, pa = prefix + "PR", prefix + "PA"
    if pr in v or "I" + pr in v or pa in v or "I" + pa in v:
        pole = fk.polar(w, next(k for k in (pr, "I" + pr, pa, "I" + pa) if k in v))
        if pr in v or "I" + pr in v:
            base = fk.reference(w, "R" + pr, walked).end if "R" + pr in w.data.refs else start
            radius = v[pr] if pr in v else float(np.hypot(*(base - pole))) + v["I" + pr]
            rows.append(float(np.hypot(*(point - pole))) - radius)
        if pa in v or "I" + pa in v:
            base = fk.reference(w, "R" + pa, walked).end if "R" + pa in w.data.refs else start
            a = math.radians(v[pa]) if pa in v else math.atan2(*(base - pole)[::-1]) + math.radians(v["I" + pa])
            d = point - pole
            rows.append(math.cos(a) * d[1] - math.sin(a) * d[0])
    return rows


def _equations(fk: FreeContour, w: _Waiting, e: FkElement, theta: float, tau: float | None,
               walked: dict[int, FkElement], closed: np.ndarray | None) -> list[float]:
    """The residuals of the element's data its parametrisation does not set."""
    v, s, src = w.data.values, e.start, _theta_source(w)
    rows = _point_rows(fk, w, e.end, s, walked, "")
    if w.closing:
        rows += list(e.end - closed)
    if "AN" in v and src != "AN":
        rows.append(math.sin(theta - math.radians(v["AN"])))
    if "IAN" in v and src != "IAN" and w.kw in ("FL", "FLT"):
        rows.append(math.sin(theta - _base_direction(fk, w, tau, walked) - math.radians(v["IAN"])))
    u = np.array([math.cos(theta), math.sin(theta)])
    if e.centre is None:
        if "PAR" in w.data.refs:
            ref = fk.reference(w, "PAR", walked)
            d = ref.direction()
            rows.append(float(u[0] * d[1] - u[1] * d[0]))
            if "DP" in v:
                rows.append(abs(float((s - ref.start) @ _perp(d))) - abs(v["DP"]))
        for key in ("P1", "P2"):
            if key + "X" in v and key + "Y" in v:
                q = np.array([v[key + "X"], v[key + "Y"]]) - s
                rows.append(float(u[0] * q[1] - u[1] * q[0]))
        if "D" in v:
            q = np.array([v.get("PDX", 0.0), v.get("PDY", 0.0)]) - s
            rows.append(float(u[0] * q[1] - u[1] * q[0]) ** 2 - v["D"] ** 2)
        return rows
    r = float(np.hypot(*(s - e.centre)))
    if "R" in v and "DR" not in w.data.words:
        rows.append(r - abs(v["R"]))
    rows += _point_rows(fk, w, e.centre, s, walked, "CC")
    if "LEN" in v:
        rows.append(float(np.hypot(*(e.end - s))) - abs(v["LEN"]))
    for key in ("P1", "P2", "P3"):
        if key + "X" in v and key + "Y" in v:
            rows.append(float(np.hypot(*(np.array([v[key + "X"], v[key + "Y"]]) - e.centre))) - r)
    if "D" in v:
        q = np.array([v.get("PDX", 0.0), v.get("PDY", 0.0)])
        rows.append((float(np.hypot(*(q - e.centre))) - r) ** 2 - v["D"] ** 2)
    return rows


def _admissible(fk: FreeContour, w: _Waiting, walked: _Walked, tol: float) -> bool:
    """The inequalities the equations leave: a line ahead of its start along AN/IAN, an arc of the DR sense
    with a sweep, rays PA/CCPA from FPOL."""
    v, e = w.data.values, walked.element
    if abs(walked.size) <= tol or (e.centre is None and walked.size < 0):
        return False
    if e.centre is not None and "DR" in w.data.words and (walked.size > 0) != (w.data.words["DR"].value == "+"):
        return False
    if "AN" in v and math.cos(walked.theta - math.radians(v["AN"])) <= 0:
        return False
    for key, point in (("PA", e.end), ("CCPA", e.centre)):
        if key in v and float((point - fk.pole) @ _unit(v[key])) < -tol:
            return False
    if e.centre is not None and walked.sweep > _TWO_PI - 1e-9 and not (_END_KEYS & set(v) or w.closing):
        return False  # a full circle only where the data name its end (its start), as the closed form reads it
    return e.centre is None or walked.sweep > 1e-9


def _unknown_columns(stretch: list[_Waiting]) -> list[tuple[int, int]]:
    """For each element, the range of its unknowns in the stretch's vector."""
    out, k = [], 0
    for w in stretch:
        n = sum(_layout(w))
        out.append((k, k + n))
        k += n
    return out


def _scale(fk: FreeContour, stretch: list[_Waiting]) -> float:
    """A length of the size of the stretch's data [program unit], for starting points and generic points."""
    sizes = [abs(x) for w in stretch for key, x in w.data.values.items() if key not in ("AN", "IAN", "PA", "IPA",
                                                                                       "CCPA", "ICCPA", "CCA", "F")]
    return 1.0 + max(sizes + [float(np.max(np.abs(fk.start)))])


def _generic(stretch: list[_Waiting], scale: float, rng: np.random.Generator) -> np.ndarray:
    """A point of no special position in the stretch's unknowns (a line's length positive, a radius of the DR
    sign)."""
    out = []
    for w in stretch:
        theta, size, sweep = _layout(w)
        if theta:
            out.append(rng.uniform(0, _TWO_PI))
        if size:
            sign = 1.0 if w.kw in ("FL", "FLT") or "DR" not in w.data.words else \
                (1.0 if w.data.words["DR"].value == "+" else -1.0)
            out.append(sign * rng.uniform(0.3, 1.0) * scale)
        if sweep:
            out.append(rng.uniform(0.5, 5.5))
    return np.array(out, float)


def _jacobian(f, z: np.ndarray) -> np.ndarray:
    """Central differences of the residuals ``f`` at ``z`` (rows: residuals, columns: unknowns)."""
    cols = []
    for i in range(len(z)):
        h = 1e-7 * (1.0 + abs(z[i]))
        dz = np.zeros(len(z))
        dz[i] = h
        cols.append((f(z + dz) - f(z - dz)) / (2 * h))
    return np.array(cols).T if cols else np.zeros((len(f(z)), 0))


def _determined(fk: FreeContour, stretch: list[_Waiting]) -> np.ndarray:
    """Which unknowns of ``stretch`` its data fix: those no direction of the null space of the residuals' Jacobian
    (at a generic point) moves."""
    z = _generic(stretch, _scale(fk, stretch), np.random.default_rng(11))
    jac = _jacobian(lambda x: _walk(fk, stretch, x)[1], z)
    if not len(z):
        return np.zeros(0, bool)
    if not jac.size or not np.all(np.isfinite(jac)):
        return np.zeros(len(z), bool)
    _, sv, vt = np.linalg.svd(jac)
    rank = int(np.sum(sv > 1e-7 * max(1.0, float(sv.max(initial=0.0)))))
    return np.all(np.abs(vt[rank:]) < 1e-6, axis=0)


def _fixed_prefix(fk: FreeContour, stretch: list[_Waiting]) -> int:
    """How many leading elements of ``stretch`` its data fix (0: none yet)."""
    fixed = _determined(fk, stretch)
    count = 0
    for start, end in _unknown_columns(stretch):
        if not fixed[start:end].all():
            break
        count += 1
    return count


def _starts(stretch: list[_Waiting], fixed: np.ndarray, base: np.ndarray, scale: float) -> list[np.ndarray]:
    """Starting points for Newton's method: each fixed angle around the circle, each fixed size small and large
    (either sign where DR is not given), each fixed sweep around the circle, the unknowns the data leave free at
    ``base``; at most 256 of their combinations, in a seeded shuffled order."""
    axes: list[list[float]] = []
    for w in stretch:
        theta, size, sweep = _layout(w)
        if theta:
            axes.append([math.pi / 8 + i * math.pi / 4 for i in range(8)])
        if size:
            signs = [1.0] if w.kw in ("FL", "FLT") else [1.0 if w.data.words["DR"].value == "+" else -1.0] \
                if "DR" in w.data.words else [1.0, -1.0]
            axes.append([s * f * scale for s in signs for f in (0.4, 1.5)])
        if sweep:
            axes.append([0.7, 2.0, 3.3, 4.6, 5.9])
    axes = [values if fixed[i] else [base[i]] for i, values in enumerate(axes)]
    grid = [np.array(p, float) for p in itertools.product(*axes)]
    order = np.random.default_rng(5).permutation(len(grid))[:256]
    return [grid[i] for i in order]


def _newton(f, z: np.ndarray, scale: float) -> np.ndarray | None:
    """A root of the residuals ``f`` (as many or more than unknowns) near ``z``: Gauss-Newton steps, halved while
    they do not reduce the residuals; None when it does not converge to 1e-9 program units."""
    r = f(z)
    for _ in range(60):
        if not np.all(np.isfinite(r)):
            return None
        norm = float(np.linalg.norm(r))
        if norm <= 1e-13 * scale:
            break
        step = np.linalg.lstsq(_jacobian(f, z), -r, rcond=None)[0]
        for _ in range(12):
            trial = f(z + step)
            if np.all(np.isfinite(trial)) and np.linalg.norm(trial) < norm:
                break
            step = step / 2
        else:
            break
        z, r = z + step, trial
    return z if np.all(np.isfinite(r)) and float(np.abs(r).max(initial=0.0)) <= 1e-9 * scale else None


def _solve_stretch(fk: FreeContour, count: int) -> list[list[FkElement]]:
    """The solutions of the first ``count`` elements of the open stretch, which its data fix: Newton's method on
    all its residuals and unknowns from starts spread over the fixed ones (a solution moves the free ones only as
    far as the residuals need), until :data:`_ENOUGH` converged starts in a row find no new one; ordered for
    FSELECT."""
    stretch, scale = fk.stretch, _scale(fk, fk.stretch)
    base = _generic(stretch, scale, np.random.default_rng(11))
    found: list[list[FkElement]] = []
    fk.degenerate = False
    since = 0  # converged starts since the last new solution
    for start in _starts(stretch, _determined(fk, stretch), base, scale):
        if found and since >= _ENOUGH:
            break
        z = _newton(lambda x: _walk(fk, stretch, x)[1], start, scale)
        if z is None:
            continue
        since += 1
        walked = _walk(fk, stretch, _normalised(stretch, z))[0][:count]
        admissible = [_admissible(fk, w, c, fk.tol) for w, c in zip(stretch, walked)]
        if not all(admissible):
            fk.degenerate |= all(ok or _back_to_start(c) for ok, c in zip(admissible, walked))
            continue
        chain = [c.element for c in walked]
        if not any(_same_chain(chain, other, fk.tol) for other in found):
            found.append(chain)
            since = 0
    return _ordered(found)


def _back_to_start(walked: _Walked) -> bool:
    """An arc that ends where it starts: sweep 0, or a full circle where the data do not name its end. The TNC
    370 user's manual's "Example 3 for exercise in FK free contour programming" (section 5.6, p. 5-50) writes
    ``FSELECT 2`` after ``13 FLT PAR9``, which leaves its arc of known circle one end here (the tangent at the
    other point of the circle parallel to line 9 is the arc's start): our reading, the TNC counts the arc back to
    its start as the other solution."""
    return walked.element.centre is not None and (walked.sweep <= 1e-9 or walked.sweep > _TWO_PI - 1e-9)


def _normalised(stretch: list[_Waiting], x: np.ndarray) -> np.ndarray:
    """The unknowns in their ranges: a line's length positive (its direction turned over when that is an unknown),
    an arc's sweep in (0, 2 pi]."""
    x, k = x.copy(), 0
    for w in stretch:
        theta, size, sweep = _layout(w)
        if w.kw in ("FL", "FLT") and theta and size and x[k + 1] < 0:
            x[k], x[k + 1] = x[k] + math.pi, -x[k + 1]
        if sweep:
            at = k + theta + size
            x[at] = x[at] % _TWO_PI or _TWO_PI
        k += theta + size + sweep
    return x


def _same_chain(a: list[FkElement], b: list[FkElement], tol: float) -> bool:
    """Two chains of solutions are one when their ends and centres agree within the run's arc end tolerance
    ``tol`` (at least 1e-6). Where an FK line touches the circle of an arc (``FCT DR+ R10`` then ``FL X+0 Y+0
    AN-90`` along a tangent of that circle) the end is a double root: Newton's method meets it only to the square
    root of its residual, about 1e-5 mm, from every start a little apart, and these are the one solution the
    geometry has (our reading: the TNC offers a point of contact once; the iTNC 530 user's manual, 6.6, counts
    solutions by the geometry)."""
    same = max(tol, 1e-6)
    return all(np.hypot(*(x.end - y.end)) <= same and (x.centre is None or np.hypot(*(x.centre - y.centre)) <= same)
               for x, y in zip(a, b))


def _ordered(solutions: list[list[FkElement]]) -> list[list[FkElement]]:
    """FSELECT's numbering: by the lengths of the elements in turn, shortest first; equal lengths (to 1e-6) by the
    direction they leave their start in, counter-clockwise from +X (our reading)."""
    return sorted(solutions, key=lambda chain: [(round(e.length, 6), math.atan2(*e.direction(at_end=False)[::-1])
                                                 % _TWO_PI) for e in chain])


def _closed_form(w: _Waiting) -> bool:
    """The element's data are of the kinds the closed-form solution of one element reads (not PDX/PDY/D)."""
    return not {"PDX", "PDY", "D"} & set(w.data.values)


def _single(w: _Waiting, start: np.ndarray, tangent: np.ndarray | None, fk: FreeContour,
            tol: float) -> list[list[FkElement]]:
    """The solutions of one element its own data fix, in closed form, ordered for FSELECT."""
    found = (_line_solutions if w.kw in ("FL", "FLT") else _arc_solutions)(w, start, tangent, fk, tol)
    return _ordered([[e] for e in found])


def _which(elements: list[_Waiting]) -> str:
    """The elements resolved together, for a message: '... has' / '... have'."""
    if len(elements) == 1:
        return f"the FK element of line {elements[0].where.line} has"
    return f"the FK elements of lines {elements[0].where.line}-{elements[-1].where.line} (resolved together) have"


def _open_what(w: _Waiting) -> tuple[str, str]:
    """What of the element its data leave open, and the data that would fix it."""
    theta, size, sweep = _layout(w)
    if w.kw in ("FL", "FLT"):
        if not theta:
            return "its length", "LEN, or a coordinate of its end point (X, Y, PR, PA)"
        if not size:
            return "its direction", "AN, IAN, PAR, P1X/P1Y, or a coordinate of its end point (X, Y, PR, PA)"
        return "its end point", _UNDETERMINED_LINE
    if not theta and not size:
        return "where it ends on its circle", "CCA, LEN, or a coordinate of its end point (X, Y, PR, PA)"
    return "its circle or its end", _UNDETERMINED_ARC
