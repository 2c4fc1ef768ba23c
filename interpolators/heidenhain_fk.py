"""FK free contour programming of Heidenhain conversational programs: ``FPOL``, ``FL``, ``FLT``, ``FC``,
``FCT``, ``FSELECT``, resolved into ordinary lines and arcs.

Followed: iTNC 530 user's manual (conversational, 340 49x-03 / 60642x-03), section 6.6 "Path
Contours - FK Free Contour Programming" (pp. 255-272 of 340 49x-03: "Free programming of straight
lines", "Free programming of circular arcs", "Input possibilities": end point coordinates, direction
and length of contour elements, circle centre CC / radius / direction of rotation in the FC/FCT block,
closed contours, auxiliary points, relative data); TNC 425/415 B/407 user's manual section 5.6,
"FK functions" table (p. 5-44); TNC 370 user's manual section 5.6 (pp. 5-39 .. 5-47). The example
blocks of these sections (``FPOL X+20 Y+30``, ``FL IX+10 Y+20 RR F100``, ``FCT PR+15 IPA+30 DR+ R15``,
``FC CCX+20 CCY+15 DR+ R15``, ``FC DR+ R15 CCPR+35 CCPA+40``, ``FC DR- R15 CLSD+ CCX+20 CCY+35``,
``FCT IX+20 DR- R20 CCA+90 RX 13``, ``FL IPR+35 PA+0 RPR 13``, ``FL LEN 12.5 PAR 17 DP 12.5`` /
``FSELECT 2``, ``FL IAN+220 RAN 18``, ``FC DR- R10 P1X+42.929 P1Y+60.071``) show how they are written.

Data of an element (all in the working plane XY, program coordinates, the program's unit):

* end point: ``X``/``Y`` (``IX``/``IY`` from the element's start), polar ``PR``/``PA`` about the FK
  pole ``FPOL`` (``IPR``/``IPA`` from the start's polar radius / angle);
* straight line: ``LEN`` its length, ``AN`` its direction angle, ``IAN`` the angle to the preceding
  element's direction; ``FLT``: tangent to the preceding element; ``PAR n``: parallel to the line of
  block n (either way; ``DP``, the distance between them, is checked); ``P1X P1Y`` (``P2X P2Y``): points
  on the line or its extension;
* arc: ``DR+``/``DR-`` (counter-clockwise / clockwise), ``R`` radius, centre ``CCX``/``CCY`` (``ICCX``/
  ``ICCY`` from the start) or ``CCPR``/``CCPA`` (``ICCPR``/``ICCPA``) about FPOL, ``CCA`` its centre angle,
  ``LEN`` its chord, ``AN`` the direction of its entry tangent (at the start); ``FCT``: tangent to the
  preceding element; ``P1X P1Y`` .. ``P3X P3Y``: points on the circle;
* relative data: ``RX n``, ``RY n``, ``RPR n``, ``RPA n`` (the ``I`` value from the end point of block n
  instead of this element's start), ``RAN n`` (``IAN`` from the direction of block n), ``RCCX n``,
  ``RCCY n``, ``RCCPR n``, ``RCCPA n`` (the centre's ``I`` values from block n's end point); block n is an
  FK element run before;
* ``CLSD+`` marks the start of a closed contour, ``CLSD-`` its end (the end point is the start of the
  ``CLSD+`` element; a bare ``CLSD`` is the one of the two not yet given).

Each element is resolved from its own data, the end point and direction of the preceding element
(its start, and for FLT/FCT its tangent) and, when its end point is left open (a line of known
direction without length, as ``FL AN+45`` or ``FLT``; an arc of known circle without end, as ``FCT DR-
R15``), from the next FK element: a line ending where the next line of known direction and end
point, or the next tangent arc of known radius (``FCT .. R.. DR..``, with its end point or ``CCA`` and
one coordinate), meets it; an arc ending where the next ``FLT`` to a known end point, or the next ``FLT``
of known direction tangent to it, leaves it; an open line, an ``FCT`` of radius and sense only and an
``FLT`` of known end point and direction together (the FK form of a rounded corner); an open arc, an
``FLT`` without data and an ``FCT`` of known centre, radius and sense together (the tangent between two
circles, as the manuals' FK programming examples run their contours). Where the data
allow several solutions the TNC shows them and the programmer picks one, saved as ``FSELECT n`` after
the element: here the solutions are numbered from the shortest element on, of equal lengths (to 1e-6
program units) by the direction they leave the start in, counter-clockwise from +X (the manuals show
the choice in the graphic but define no order: our reading), and ``FSELECT n`` picks the n-th.
Anything else that leaves the element open (the TNC's "not yet resolved" elements waiting for more
data further on, auxiliary points at a distance ``PDX PDY D``) is an error naming the element and the
data that would determine it.

The resolved element is a line ``L`` or an arc ``CC`` + ``C`` to the reader (the FK centre is then the
pole: the manuals say a CC programmed before is no longer valid after an FK contour), so radius
compensation ``RL``/``RR``, feeds, ``M`` functions, RND/CHF, APPR/DEP and the coordinate
transformations act on it as on those blocks.
"""

from __future__ import annotations

import dataclasses
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
    r"|(?P<ref>R(?:CC)?(?:X|Y|PR|PA)|RAN|PAR)(?=\s*\d)|(?P<m>M)(?=\s*\d)"
    r"|(?P<value>I?CC(?:X|Y|PR|PA)|CCA|P[123][XY]|PD[XY]|LEN|DP|D|I?AN|I?P[RA]|I?[XY]|R|F)(?=\s*[+-]?\s*[\d.Q(])",
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
#: The start of the element after an open one, for its data: unknown, so data relative to it (IX, IY, IPR, IPA,
#: ICCX, ...) give no curve (NaN fits nothing) and the join fails naming the data that would fix it.
_UNKNOWN = np.full(2, np.nan)


@dataclasses.dataclass(frozen=True)
class FkWords:
    """The words of an FK block: ``values`` [program unit, deg] and block numbers ``refs`` by key, ``words``
    the source words (for columns and for the L/C block the element becomes: RL/RR/R0, F, M, DR)."""

    values: dict[str, float]
    refs: dict[str, int]
    words: dict[str, Word]
    ms: tuple[Word, ...]
    clsd: str | None  # "+", "-", "" (bare CLSD) or None


def read_fk_words(code: str, pos: int, where: Where, params: QParameters, *, column0: int) -> FkWords:
    """The words of an FK block from ``pos`` on; each at most once."""
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
        key = tok.upper().replace(" ", "")
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
            value, end = read_value(code, end, where, params, what=key, column0=column0)
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
    """An FK element that is not emitted yet: several ``solutions`` (waiting for FSELECT), or an open end
    (``open``: a line of known direction, an arc of known circle) waiting for the next element."""

    kw: str
    data: FkWords
    where: Where
    number: int | None
    solutions: list[FkElement]
    open: FkElement | None = None
    closing: bool = False  # CLSD- (or the second bare CLSD): the element ends where the closed contour began


#: What the reader hands back: elements to run as L / CC + C blocks, with the block they come from.
Emitted = tuple[FkElement, FkWords, Where, int | None]


class FreeContour:
    """The FK state of a program run: the pole ``FPOL``, the elements resolved so far (by block number, for
    relative data), the start of a closed contour, and an element waiting for ``FSELECT`` or for the next."""

    def __init__(self) -> None:
        self.pole: np.ndarray | None = None
        self.history: dict[int, FkElement] = {}
        self.closed_start: np.ndarray | None = None
        self.waiting: _Waiting | None = None
        # the element between an open one and the one that fixes both: an FCT of radius and sense only after an
        # open line (a rounding), an FLT without data after an open arc (a tangent to the next circle)
        self.middle: _Waiting | None = None

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
        """``FSELECT n``: the n-th solution of the element before it."""
        w = self.waiting
        if w is None or w.open is not None or len(w.solutions) < 2:
            where.fail("FSELECT without an FK element of several solutions before it", column=column, text=text,
                       expected="FSELECT n right after the FK element whose solutions it picks from")
        if not (choice == int(choice) and 1 <= choice <= len(w.solutions)):
            where.fail(f"FSELECT {choice:g}: the FK element of line {w.where.line} has {len(w.solutions)} solutions",
                       column=column, text=text, expected=f"FSELECT 1 .. {len(w.solutions)}")
        self.waiting = None
        return [self._done(w, w.solutions[int(choice) - 1])]

    def element(self, kw: str, data: FkWords, start: np.ndarray, tangent: np.ndarray | None, where: Where,
                number: int | None, tol: float) -> list[Emitted]:
        """An FL, FLT, FC or FCT block starting at ``start`` (the preceding element's end, ``tangent`` its unit
        direction there, None when there is none): the elements it and a waiting one resolve to, in order."""
        w = self.waiting
        if w is not None and w.open is None:
            self.unresolved()
        allowed = _LINE_KEYS if kw in ("FL", "FLT") else _ARC_KEYS
        for key, word in data.words.items():
            if key not in allowed:
                where.fail(f"word {word.text!r} not allowed in {kw}", column=word.column, text=word.text,
                           expected=f"{kw} with " + ", ".join(sorted(k for k in allowed if k != "RCOMP")))
        if kw in ("FLT", "FCT") and tangent is None and w is None:
            where.fail(f"{kw} without a preceding contour element", column=1, text=where.text,
                       expected=f"a line or arc before {kw} (its tangent)")
        new = _Waiting(kw, data, where, number, [], closing=data.clsd == "-" or (data.clsd == "" and
                                                                              self.closed_start is not None))
        if new.closing and self.closed_start is None:
            where.fail("CLSD- without a CLSD+ before it", column=data.words["CLSD"].column,
                       text=data.words["CLSD"].text, expected="CLSD+ on the first element of the closed contour")
        if w is not None and self.middle is not None:
            return self._round_corner(new, tol) if w.open.centre is None else self._bridge(new, tol)
        if w is not None and (_rounding(new) if w.open.centre is None else _bare_tangent(new)):
            self.middle = new
            return []
        if w is not None:
            self.waiting = None
            first, second = _join(w, new, self, tol)
            out = [self._done(w, first)]
            start, tangent = first.end, first.direction()
            if second is not None:
                return out + [self._done(new, second)]
            return out + self._resolve(new, start, tangent, tol)
        return self._resolve(new, start, tangent, tol)

    def unresolved(self) -> None:
        """A block other than the next FK element (or the program's end) while one waits: an error naming it."""
        w = self.waiting
        if w is None:
            return
        if self.middle is not None:
            c = self.middle
            if w.open.centre is None:
                c.where.fail(f"{w.kw} of line {w.where.line} (its length open) and this {c.kw} of radius and sense "
                             "only: where they end is not determined", column=1, text=c.where.text,
                             expected="a next FLT with its end point and AN (the direction after the arc)")
            c.where.fail(f"{w.kw} of line {w.where.line} (its end open) and this {c.kw} without data: where they end "
                         "is not determined", column=1, text=c.where.text,
                         expected="a next FCT with its centre CCX/CCY (or CCPR/CCPA), R and DR (the circle the line "
                                  "is tangent to)")
        if w.open is None:
            w.where.fail(f"{w.kw} has {len(w.solutions)} solutions and no FSELECT picks one", column=1,
                         text=w.where.text, expected=f"FSELECT 1 .. {len(w.solutions)} after the {w.kw} block")
        what = "its length" if w.open.centre is None else "where it ends on its circle"
        w.where.fail(f"{w.kw}: {what} is not determined (the TNC's 'not yet resolved' element)", column=1,
                     text=w.where.text, expected=(_UNDETERMINED_LINE if w.open.centre is None else
                                                  "X/Y, PR/PA, LEN or CCA, or a next FLT to a known end point or "
                                                  "of known direction") + ", or a next FK element that fixes it")

    # --- resolution -----------------------------------------------------------------------------------
    def _bridge(self, new: _Waiting, tol: float) -> list[Emitted]:
        """An open arc (circle c1, r1, its sense), an FLT without data, and ``new``, an FCT of known circle (centre
        CCX/CCY or CCPR/CCPA, R) and sense DR: the line is the tangent leaving the first circle and reaching the
        second in their senses. With n the unit normal from a circle's centre to the point where its tangent
        runs along u (n = -perp(u), times -1 for a clockwise circle: k = -1), T = c + k r n on each circle, and
        T2 - T1 along u: (c2 - c1) . n = k1 r1 - k2 r2, two normals of which one has T2 ahead of T1."""
        w, bare = self.waiting, self.middle
        self.waiting = self.middle = None
        c1, ccw1 = w.open.centre, w.open.ccw
        r1 = float(np.hypot(*(w.open.start - c1)))
        v = new.data.values
        curves = _given_centre(new, _UNKNOWN, self)
        if new.kw == "FCT" and "R" in v and "DR" in new.data.words and len(curves) >= 2:
            k1, k2 = (1.0 if ccw1 else -1.0), (1.0 if new.data.words["DR"].value == "+" else -1.0)
            r2 = abs(v["R"])
            for c2 in _solve(curves, tol):
                d = c2 - c1
                dist = float(np.hypot(*d))
                q = k1 * r1 - k2 * r2
                if dist <= tol or abs(q) > dist:
                    continue
                base, spread = math.atan2(d[1], d[0]), math.acos(q / dist)
                for phi in (base - spread, base + spread):
                    n = np.array([math.cos(phi), math.sin(phi)])
                    u = _perp(n)
                    t1, t2 = c1 + k1 * r1 * n, c2 + k2 * r2 * n
                    if float((t2 - t1) @ u) > tol:
                        arc = FkElement(w.open.start, t1, c1, ccw1)
                        line = FkElement(t1, t2)
                        return [self._done(w, arc), self._done(bare, line)] + self._resolve(new, t2, u, tol)
        new.where.fail(f"{w.kw} of line {w.where.line} (its end open), the {bare.kw} of line {bare.where.line} (no "
                       "data) and this block: the tangent between them is not determined", column=1,
                       text=new.where.text, expected="FCT with its centre CCX/CCY (or CCPR/CCPA), R and DR, a circle "
                                                     "apart from the first")

    def _round_corner(self, new: _Waiting, tol: float) -> list[Emitted]:
        """An open line, an FCT of radius R and sense DR only, and ``new``, an FLT of known end point E and
        direction AN (tangent to the arc: without it the arc's sweep stays open): the arc turns the line's
        direction d1 into d3 = AN, so its shape is fixed and only where the first line ends (t along d1) is
        open; the third line through E along d3 fixes t (linear)."""
        w, corner = self.waiting, self.middle
        self.waiting = self.middle = None
        s, d1 = w.open.start, w.open.direction()
        ccw = corner.data.words["DR"].value == "+"
        r = abs(corner.data.values["R"])
        sign = 1.0 if ccw else -1.0
        if "AN" in new.data.values and new.kw == "FLT":
            d3 = _unit(new.data.values["AN"])
            n1, n3 = _perp(d1) * sign, -_perp(d3) * sign  # from the line to the centre, from the centre to the end
            den = float(d1[0] * d3[1] - d1[1] * d3[0])
            ends = _end_curves(new, _UNKNOWN, self, chord=False)
            for e in (_solve(ends, tol) if len(ends) >= 2 and abs(den) > 1e-12 else []):
                q = e - s - r * (n1 + n3)
                t = float(q[0] * d3[1] - q[1] * d3[0]) / den
                centre = s + t * d1 + r * n1
                if t > tol and float((e - (centre + r * n3)) @ d3) > tol:
                    line = FkElement(s, s + t * d1)
                    arc = FkElement(line.end, centre + r * n3, centre, ccw)
                    return [self._done(w, line), self._done(corner, arc)] + self._resolve(new, arc.end, d3, tol)
        new.where.fail(f"{w.kw} of line {w.where.line} (its length open), the {corner.kw} of line {corner.where.line} "
                       "(radius and sense only) and this block: where they meet is not determined", column=1,
                       text=new.where.text, expected="FLT with AN and its end point (X/Y or PR/PA) after them")

    def _resolve(self, new: _Waiting, start: np.ndarray, tangent: np.ndarray | None, tol: float) -> list[Emitted]:
        if new.kw in ("FL", "FLT"):
            solutions, opened = _line_solutions(new, start, tangent, self, tol)
        else:
            solutions, opened = _arc_solutions(new, start, tangent, self, tol)
        if opened is not None:
            new.open = opened
            self.waiting = new
            return []
        if not solutions:
            new.where.fail(f"{new.kw}: no element fits its data (they contradict each other or the contour so far)",
                           column=1, text=new.where.text, expected="FK data describing one element")
        solutions.sort(key=lambda e: (round(e.length, 6), math.atan2(*e.direction(at_end=False)[::-1]) % (2 * math.pi)))
        if len(solutions) > 1:
            new.solutions = solutions
            self.waiting = new
            return []
        return [self._done(new, solutions[0])]

    def _done(self, w: _Waiting, element: FkElement) -> Emitted:
        if w.number is not None:
            self.history[w.number] = element
        if w.closing:
            self.closed_start = None
        elif w.data.clsd is not None:
            self.closed_start = element.start.copy()
        return element, w.data, w.where, w.number

    def reference(self, w: _Waiting, key: str) -> FkElement:
        """The element of the block ``w.data.refs[key]`` names (relative data)."""
        n = w.data.refs[key]
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


def _bare_tangent(w: _Waiting) -> bool:
    """An FLT with no data of its own (after an open arc: the tangent to the next element's circle)."""
    return w.kw == "FLT" and not w.closing and not (set(w.data.values) | set(w.data.refs)) - {"F"}


def _rounding(w: _Waiting) -> bool:
    """An FCT with radius and sense and nothing else of its circle or end (after an open line: a rounding)."""
    keys = set(w.data.values) | set(w.data.refs)
    return w.kw == "FCT" and "DR" in w.data.words and "R" in keys and not w.closing and \
        not keys - {"R", "F"}


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
                    tol: float) -> tuple[list[FkElement], FkElement | None]:
    """The lines the data allow, or (no solutions, an open line of known direction)."""
    if "PDX" in w.data.values or "PDY" in w.data.values or "D" in w.data.values:
        _refuse_distance_point(w)
    ends = _end_curves(w, start, fk, chord=False)
    if "LEN" in w.data.values:
        ends.append(_Curve(start, r=abs(w.data.values["LEN"])))
    dirs = _line_directions(w, start, tangent, fk, tol)
    out: list[FkElement] = []
    for d in (dirs if dirs is not None else [None]):
        curves = ends + ([_Curve(start, d, ray=True, strict=True)] if d is not None else [])
        if len(curves) < 2:
            if d is not None and len(dirs) == 1:
                return [], FkElement(start, start + d)
            w.where.fail(f"{w.kw}: the end point is not determined", column=1, text=w.where.text,
                         expected=_UNDETERMINED_LINE)
        out += [FkElement(start, e) for e in _solve(curves, tol) if np.hypot(*(e - start)) > tol]
    return out, None


def _refuse_distance_point(w: _Waiting) -> None:
    key = next(k for k in ("PDX", "PDY", "D") if k in w.data.words)
    word = w.data.words[key]
    w.where.fail(f"{w.kw}: an auxiliary point at a distance (PDX/PDY/D) is not supported", column=word.column,
                 text=word.text, expected="the element's end point, direction, or points P1X/P1Y on it")


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
                   tol: float) -> tuple[list[FkElement], FkElement | None]:
    """The arcs the data allow, or (no solutions, an open arc of known circle)."""
    if "PDX" in w.data.values or "PDY" in w.data.values or "D" in w.data.values:
        _refuse_distance_point(w)
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
                return [], FkElement(start, start, c, sense)
            out += found
    return out, None


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


# --- an open element and the next one ---------------------------------------------------------------------


def _join(w: _Waiting, new: _Waiting, fk: FreeContour, tol: float) -> tuple[FkElement, FkElement | None]:
    """The open element ``w`` resolved by the next one ``new``: (w's element, new's element or None when new
    is to be resolved from w's end on)."""
    if w.open.centre is None:
        return _join_line(w, new, fk, tol)
    return _join_arc(w, new, fk, tol), None


def _join_line(w: _Waiting, new: _Waiting, fk: FreeContour, tol: float) -> tuple[FkElement, FkElement | None]:
    """A line of known direction whose end the next element fixes: the next line's end point and direction
    known (their intersection), or the next FCT's radius and sense known (its centre on the parallel at
    that distance; the end point, CCA and one end coordinate, or a centre coordinate fix it)."""
    s, d = w.open.start, w.open.direction()
    v = new.data.values
    if new.kw in ("FL", "FLT"):
        ends = _end_curves(new, _UNKNOWN, fk, chord=False)
        dirs = _line_directions(new, _UNKNOWN, d, fk, tol) if new.kw != "FLT" else None
        if len(ends) >= 2 and dirs is not None and len(dirs) == 1:
            for e in _solve(ends, tol):
                for p in _intersect(_Curve(s, d, ray=True, strict=True), _Curve(e, dirs[0]), tol):
                    return FkElement(s, p), FkElement(p, e)
    elif new.kw == "FCT" and "R" in v and "DR" in new.data.words:
        ccw = new.data.words["DR"].value == "+"
        r = abs(v["R"])
        side = _perp(d) * (1 if ccw else -1)
        rail = _Curve(s + r * side, d, ray=True, strict=True)
        conditions = _given_centre(new, _UNKNOWN, fk)
        ends = _end_curves(new, _UNKNOWN, fk, chord=False)
        if len(ends) >= 2:
            conditions += [_Curve(e, r=r) for e in _solve(ends, tol)][:1]
        elif ends and "CCA" in v:
            a = math.radians(abs(v["CCA"])) * (1 if ccw else -1)
            rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
            offset = rot @ (-r * side)  # from the centre to the end
            conditions += [dataclasses.replace(ends[0], p=ends[0].p - offset)]
        for c in (_solve([rail, conditions[0]], tol) if conditions else []):
            p = c - r * side
            return FkElement(s, p), None
    new.where.fail(f"{w.kw} of line {w.where.line} (its length open) and this {new.kw}: the corner between them is "
                   "not determined", column=1, text=new.where.text,
                   expected=f"{_UNDETERMINED_LINE} in line {w.where.line}, or here an FL/FLT with its end point and "
                            "direction, or an FCT with R, DR and its end point (or CCA and one coordinate)")


def _join_arc(w: _Waiting, new: _Waiting, fk: FreeContour, tol: float) -> FkElement:
    """An arc of known circle whose end the next element fixes: the next FLT to a known end point (the tangent
    from it that continues the arc's sense), or an FLT with AN (where the arc runs that way)."""
    s, c, ccw = w.open.start, w.open.centre, w.open.ccw
    r = float(np.hypot(*(s - c)))
    out: list[np.ndarray] = []
    if new.kw == "FLT":
        ends = _end_curves(new, _UNKNOWN, fk, chord=False)
        v = new.data.values
        if len(ends) >= 2:
            for e in _solve(ends, tol):
                dist = float(np.hypot(*(e - c)))
                if dist > r:
                    for t in _circle_circle(_Curve(c, r=r), _Curve((c + e) / 2, r=dist / 2)):
                        tangent = FkElement(s, t, c, ccw).direction()
                        if float((e - t) @ tangent) > 0:
                            out.append(t)
        elif "AN" in v:
            n = -_perp(_unit(v["AN"])) * (1 if ccw else -1)  # from the centre to the point of that tangent
            out.append(c + r * n)
    if not out:
        new.where.fail(f"{w.kw} of line {w.where.line} (its end open) and this {new.kw}: where the arc ends is not "
                       "determined", column=1, text=new.where.text,
                       expected=f"the arc's end (X/Y, PR/PA, LEN, CCA) in line {w.where.line}, or here an FLT to a "
                                "known end point or with AN")
    return FkElement(s, out[0], c, ccw)

