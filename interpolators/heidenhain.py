"""Reader of Heidenhain conversational (plain-language) programs.

Accepted blocks, each optionally preceded by its block number (as in the thesis' Tables 4.3
and 4.4)::

    0 BEGIN PGM RAPIDIDENT MM         name and unit (MM or INCH)
    ;comment                          also after a block
    1 BLK FORM 0.1 Z X-50 Y-50 Z-50   workpiece blank (accepted, no motion)
    3 TOOL CALL 0 Z                   tool call (no motion); the tool axis selects the plane
    4 L Z+200.000 F MAX               straight line; F MAX / FMAX = rapid, for this block only
    5 L X+0 Y+0 R0 F MAX M3           R0 (no radius compensation) accepted; RL/RR are errors
    7 L X-0.000 F 15000.000           F [mm/min] (in INCH programs [0.1 inch/min]), modal
    9 L IX+0.5                        I prefix: incremental coordinate
    200 L +0.009                      a signed number without axis letter repeats the single
                                      axis of the previous L block (the tables are written so)
    10 CC X+25 Y+25                   circle centre (CC alone: the current position)
    11 C X+45 Y+25 DR+                arc to the end point about CC; DR+ counter-clockwise;
                                      end = start gives a full circle; a tool-axis coordinate
                                      makes a helix
    12 CR X+5 Y+5 R+20 DR-            arc by radius (R- for more than 180 degrees)
    206 M30                           M2/M30 end; M3, M4, M5, M8, M9 ignored
    207 END PGM RAPIDIDENT MM         end (nothing after it is read)

A trailing ``*`` (older TNC block end) is ignored. Anything else (CT, CP, RND, CHF, LBL, CYCL,
FN, Q parameters, rotary axes) is an error naming the line and column.
"""

from __future__ import annotations

import re

import numpy as np

from interpolators._words import INCH, NUMBER_RE, Where, checked_float, lines_of, token_at
from interpolators.arcs import ArcWordError, arc_from_center, arc_from_radius
from interpolators.program import Block, Program
from toolpaths.geometry import AXIS_LETTERS, PLANE_AXES, Line

__all__ = ["parse_heidenhain", "looks_like_heidenhain"]

_HEAD_RE = re.compile(r"\s*(\d+)?\s*")
_KEYWORD_RE = re.compile(r"(BEGIN\s+PGM|END\s+PGM|BLK\s+FORM|TOOL\s+CALL|TOOL\s+DEF|CC|CR|C|L|M)(?![A-Z])", re.I)
_WORD_RE = re.compile(
    r"(?P<fmax>F\s*MAX\b)|(?P<fauto>F\s*AUTO\b)|(?P<feed>F)\s*(?P<fv>[+-]?(?:\d+\.?\d*|\.\d+))"
    r"|(?P<inc>I?)(?P<axis>[XYZ])\s*(?P<av>[+-]?(?:\d+\.?\d*|\.\d+))"
    r"|(?P<bare>[+-](?:\d+\.?\d*|\.\d+))"
    r"|(?P<dr>DR\s*[+-])"
    r"|(?P<rcomp>R[LR0])(?![\d.])"
    r"|(?P<rad>R)\s*(?P<rv>[+-]?(?:\d+\.?\d*|\.\d+))"
    r"|(?P<m>M)\s*(?P<mv>\d+)",
    re.I,
)
_M_OK = {2, 3, 4, 5, 8, 9, 30}
_PLANE_OF_TOOL_AXIS = {"Z": 2, "Y": 1, "X": 0}


def looks_like_heidenhain(text: str) -> bool:
    """True if the text reads as Heidenhain conversational rather than ISO G-code.

    A ``BEGIN PGM`` line anywhere, or a first meaningful line made of a block number followed by
    a conversational keyword (``L``, ``C``, ``CC``, ``CR``, ``TOOL CALL``, ``BLK FORM``, ...).
    """
    if re.search(r"^\s*\d*\s*BEGIN\s+PGM\b", text, re.I | re.M):
        return True
    for raw in lines_of(text):
        s = raw.split(";", 1)[0].strip()
        if not s or s.startswith(("(", "%")):
            continue
        return re.match(r"\d+\s*(L|CC|CR|C|TOOL\s+CALL|BLK\s+FORM|END\s+PGM)(?![A-Z])", s, re.I) is not None
    return False


class _State:
    __slots__ = ("pos", "plane", "inch", "feed", "center", "last_axes")

    def __init__(self) -> None:
        self.pos = np.zeros(3)
        self.plane = 2
        self.inch = False
        self.feed: float | None = None
        self.center: np.ndarray | None = None
        self.last_axes: list[int] = []


def parse_heidenhain(text: str, *, source: str | None = None) -> Program:
    """Parse a Heidenhain conversational program into a :class:`Program`.

    Parameters
    ----------
    text : str
        Program text.
    source : str, optional
        File name used in error messages and recorded in ``Program.source``.

    Raises
    ------
    vcnc.GCodeError
        With file, line, column, the offending text and what was expected.
    """
    st = _State()
    blocks: list[Block] = []
    used: set[int] = set()
    name = None
    for lineno, raw in enumerate(lines_of(text), start=1):
        where = Where(source, lineno, raw.strip())
        code = raw.split(";", 1)[0].rstrip()
        if code.endswith("*"):
            code = code[:-1].rstrip()
        if not code.strip():
            continue
        m = _HEAD_RE.match(code)
        number = int(m.group(1)) if m.group(1) else None
        pos = m.end()
        if pos >= len(code):
            continue  # a bare block number
        k = _KEYWORD_RE.match(code, pos)
        if k is None:
            tok = token_at(code, pos)
            where.fail(f"unknown or unsupported block {tok!r}", column=pos + 1, text=tok,
                       expected="BEGIN PGM, END PGM, BLK FORM, TOOL CALL, L, CC, C, CR or M")
        kw = re.sub(r"\s+", " ", k.group(1).upper())
        rest_at = k.end() if kw != "M" else pos
        if kw == "BEGIN PGM":
            parts = code[rest_at:].split()
            name = parts[0] if parts else None
            unit = parts[1].upper() if len(parts) > 1 else "MM"
            if unit not in ("MM", "INCH"):
                col = code.upper().rfind(parts[1].upper()) + 1
                where.fail(f"unknown program unit {parts[1]!r}", column=col, text=parts[1], expected="MM or INCH")
            st.inch = unit == "INCH"
            continue
        if kw == "END PGM":
            break
        if kw in ("BLK FORM", "TOOL DEF"):
            continue
        if kw == "TOOL CALL":
            for t in re.finditer(r"(?<![A-Z0-9.+-])([XYZ])(?![A-Z0-9.+-])", code[rest_at:], re.I):
                st.plane = _PLANE_OF_TOOL_AXIS[t.group(1).upper()]
                break
            continue
        words = _words(code, rest_at, where)
        ended = _execute(kw, words, st, blocks, used, where, number, pos + 1)
        if ended:
            break
    axes = tuple(a for i, a in enumerate(AXIS_LETTERS) if i in used)
    return Program(blocks=tuple(blocks), source=source, dialect="heidenhain", axes=axes, name=name)


def _words(code: str, pos: int, where: Where) -> list[tuple[str, object, int, str]]:
    out = []
    n = len(code)
    while pos < n:
        if code[pos] in " \t":
            pos += 1
            continue
        m = _WORD_RE.match(code, pos)
        col = pos + 1
        if m is None or (m.end() < n and code[m.end()] not in " \t"):
            tok = token_at(code, pos)
            num = re.sub(r"^I?[XYZF]\s*", "", tok, flags=re.I)
            if re.match(r"I?[XYZF]", tok, re.I) and not NUMBER_RE.fullmatch(num):
                where.fail(f"malformed number in {tok!r}", column=col, text=tok, expected="a signed decimal number")
            if re.match(r"I?[ABCUVW][+-]?[\d.]", tok, re.I):
                where.fail(f"axis {tok[0]!r} is not supported (vcnc interpolates X, Y, Z)", column=col, text=tok,
                           expected="X, Y or Z")
            where.fail(f"unknown word {tok!r}", column=col, text=tok,
                       expected="X/Y/Z (I for incremental), R0, F, F MAX, DR+/DR-, R, or M")
        tok = m.group(0)
        g = m.lastgroup
        if m.group("fmax"):
            out.append(("FMAX", None, col, tok))
        elif m.group("fauto"):
            where.fail("F AUTO is not supported", column=col, text=tok, expected="F <mm/min> or F MAX")
        elif m.group("feed"):
            out.append(("F", checked_float(m.group("fv"), where, column=col, what="F"), col, tok))
        elif m.group("axis"):
            value = checked_float(m.group("av"), where, column=col, what="a coordinate")
            out.append(("I" * bool(m.group("inc")) + m.group("axis").upper(), value, col, tok))
        elif m.group("bare"):
            value = checked_float(m.group("bare"), where, column=col, what="a coordinate")
            out.append(("BARE", value, col, tok))
        elif m.group("dr"):
            out.append(("DR", tok.replace(" ", "")[-1], col, tok))
        elif m.group("rcomp"):
            c = tok.upper()
            if c != "R0":
                where.fail(f"radius compensation {c} is not supported", column=col, text=tok,
                           expected="R0 (programmed contour = tool centre path)")
            out.append(("R0", None, col, tok))
        elif m.group("rad"):
            out.append(("R", checked_float(m.group("rv"), where, column=col, what="R"), col, tok))
        elif m.group("m"):
            out.append(("M", int(m.group("mv")[:9]), col, tok))
        else:  # pragma: no cover - every alternative is handled above
            raise AssertionError(g)
        pos = m.end()
    return out


def _execute(kw, words, st: _State, blocks, used, where: Where, number, kw_col) -> bool:  # noqa: C901
    seen: dict[str, tuple[object, int, str]] = {}
    ended = False
    for key, value, col, tok in words:
        if key == "M":
            if value not in _M_OK:
                where.fail(f"unknown M function {tok!r}", column=col, text=tok,
                           expected="M2 or M30 (end), M3, M4, M5, M8 or M9 (ignored)")
            ended = ended or value in (2, 30)
            continue
        base = key[-1] if key in ("IX", "IY", "IZ") else key
        if base in seen or (key == "BARE" and any(k in seen for k in "XYZ")):
            where.fail(f"word {tok!r} repeats an axis or setting of this block", column=col, text=tok,
                       expected="each word at most once per block")
        if key in ("F", "FMAX") and ("F" in seen or "FMAX" in seen):
            where.fail("two feeds in one block", column=col, text=tok, expected="one F word")
        seen[base if base in "XYZ" else key] = (value if key not in ("IX", "IY", "IZ") else ("I", value), col, tok)
    if kw == "M":
        return ended
    scale = INCH if st.inch else 1.0
    if "F" in seen:
        f, col, tok = seen["F"]
        if not f > 0:
            where.fail("feed F must be > 0", column=col, text=tok, expected="F > 0 [mm/min]")
        st.feed = f * (INCH / 10.0 if st.inch else 1.0) / 60.0

    def coord(axis: str) -> float | None:
        if axis not in seen:
            return None
        v = seen[axis][0]
        i = "XYZ".index(axis)
        if isinstance(v, tuple):
            used.add(i)
            return st.pos[i] + v[1] * scale
        used.add(i)
        return v * scale

    if "BARE" in seen:
        v, col, tok = seen.pop("BARE")
        if kw != "L" or len(st.last_axes) != 1:
            where.fail("coordinate without an axis letter", column=col, text=tok,
                       expected="an axis letter (X, Y or Z) before the number")
        seen["XYZ"[st.last_axes[0]]] = (v, col, tok)

    if kw == "CC":
        bad = [k for k in seen if k not in ("X", "Y", "Z")]
        if bad:
            _, col, tok = seen[bad[0]]
            where.fail(f"word {tok!r} not allowed in CC", column=col, text=tok, expected="CC with plane coordinates")
        c = st.pos.copy()
        p, q = PLANE_AXES[st.plane]
        for a in seen:
            i = "XYZ".index(a)
            if i not in (p, q):
                _, col, tok = seen[a]
                where.fail(f"CC coordinate {tok!r} is not in the working plane", column=col, text=tok,
                           expected=f"CC {'XYZ'[p]} {'XYZ'[q]}")
            c[i] = coord(a)
        st.center = c
        return ended

    axis_keys = [a for a in "XYZ" if a in seen]
    if not axis_keys and kw in ("L", "CR"):
        where.fail(f"{kw} block without coordinates", column=kw_col, text=where.text,
                   expected="at least one of X, Y, Z")
    target = st.pos.copy()
    for a in axis_keys:
        target["XYZ".index(a)] = coord(a)
    rapid = "FMAX" in seen
    if kw != "L" and rapid:
        _, col, tok = seen["FMAX"]
        where.fail("F MAX is not allowed on arcs", column=col, text=tok, expected="a feed F [mm/min]")
    if not rapid and st.feed is None:
        where.fail(f"{kw} feed move without a feed", column=kw_col, text=where.text, expected="F > 0 [mm/min] or F MAX")
    common = dict(line=where.line, number=number, text=where.text, start=st.pos.copy(), exact_stop=True)
    if kw == "L":
        extra = [k for k in seen if k in ("DR", "R")]
        if extra:
            _, col, tok = seen[extra[0]]
            where.fail(f"word {tok!r} not allowed in L", column=col, text=tok, expected="coordinates, R0, F, M")
        st.last_axes = ["XYZ".index(a) for a in axis_keys]
        blk = Block(kind="rapid" if rapid else "line", target=target, feed=np.inf if rapid else st.feed,
                    segment=Line(st.pos, target), **common)
    else:
        p, q = PLANE_AXES[st.plane]
        used.update((p, q))
        if "DR" not in seen:
            where.fail(f"{kw} arc without direction", column=kw_col, text=where.text, expected="DR+ or DR-")
        ccw = seen["DR"][0] == "+"
        try:
            if kw == "C":
                if "R" in seen:
                    _, col, tok = seen["R"]
                    where.fail("radius word in a C block", column=col, text=tok, expected="CR for a radius arc")
                if st.center is None:
                    where.fail("C arc without a circle centre", column=kw_col, text=where.text,
                               expected="a CC block before C")
                seg = arc_from_center(st.pos, target, st.center, ccw=ccw, plane=st.plane)
            else:
                if "R" not in seen:
                    where.fail("CR arc without radius", column=kw_col, text=where.text, expected="R+ or R- [mm]")
                seg = arc_from_radius(st.pos, target, seen["R"][0] * scale, ccw=ccw, plane=st.plane)
        except ArcWordError as exc:
            col, tok = (seen["R"][1], seen["R"][2]) if "R" in seen else (kw_col, where.text)
            where.fail(exc.message, column=col, text=tok, expected=exc.expected)
        target = np.array(seg.end)
        blk = Block(kind="arc", target=target, feed=st.feed, segment=seg, **common)
    blocks.append(blk)
    st.pos = target
    return ended
