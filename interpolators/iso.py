"""Reader of ISO 6983 / Fanuc-style G-code.

Accepted words (case-insensitive; spaces between the address letter and its number allowed,
as in ``N0010 G01 X 0.258`` of the thesis' Table 3.2):

========= ==============================================================================
``N``      block number (ignored)              ``O``  program number (the program name)
``G00``    rapid: a straight line at the machine's rapid rate (not a dog-leg)
``G01``    linear feed move                    ``G02``/``G03`` clockwise / counter-clockwise arc
``G04``    dwell, ``P`` [ms] or ``X`` [s]      ``G17/G18/G19`` arc plane XY / ZX / YZ
``G20/21`` inch / mm input                     ``G90/G91`` absolute / incremental X Y Z
``G61``    exact stop (default): every block starts and ends at rest
``G64``    continuous path; optional ``P`` path tolerance [mm, inch under G20]
``G94``    feed per minute (the only feed mode; accepted)
``G40/G49/G80`` cancel cutter / length compensation, canned cycle (the only states; accepted)
``X Y Z``  end point [mm or inch]              ``I J K`` arc centre, incremental from the start
``R``      arc radius (negative: sweep over 180 degrees; full circles need I/J/K)
``F``      feed [mm/min, in/min under G20]     ``S``  spindle speed (ignored)
``M02/M30`` program end (later lines are not read); ``M03/M04/M05/M08/M09`` ignored
========= ==============================================================================

Comments ``( ... )`` and ``; ...``, and ``%`` tape marks are skipped. Any other word is an error.
The program starts at the origin, in G00-less state: axis words before any motion code are an
error, as is an explicit motion code without axis words (except a full circle given by I/J/K).
"""

from __future__ import annotations

import numpy as np

from interpolators._words import INCH, Where, lines_of, read_number, token_at
from interpolators.arcs import ArcWordError, arc_from_center, arc_from_radius
from interpolators.program import Block, Program
from toolpaths.geometry import AXIS_LETTERS, PLANE_AXES, Line

__all__ = ["parse_iso"]

_LETTERS = set("NOGMFXYZIJKRPS")
_G_GROUP = {
    0: "motion", 1: "motion", 2: "motion", 3: "motion", 4: "dwell",
    17: "plane", 18: "plane", 19: "plane", 20: "units", 21: "units",
    90: "distance", 91: "distance", 61: "path", 64: "path", 94: "feed mode",
    40: "cutter compensation", 49: "length compensation", 80: "canned cycle",
}
_M_OK = {2, 3, 4, 5, 8, 9, 30}
_PLANE_OF_G = {17: 2, 18: 1, 19: 0}


def _strip_comments(raw: str, where: Where) -> str:
    """Blank out comments, keeping columns."""
    out = list(raw)
    i = 0
    n = len(raw)
    while i < n:
        ch = raw[i]
        if ch == ";":
            for k in range(i, n):
                out[k] = " "
            break
        if ch == "(":
            j = raw.find(")", i + 1)
            if j < 0:
                where.fail("unclosed comment", column=i + 1, text=raw[i:], expected="')' closing the comment")
            for k in range(i, j + 1):
                out[k] = " "
            i = j + 1
            continue
        if ch == ")":
            where.fail("')' without '('", column=i + 1, text=")", expected="a word")
        i += 1
    return "".join(out)


def _words(code: str, where: Where) -> list[tuple[str, float, int, str]]:
    """(letter, value, 1-based column, text) for each word of a comment-free line."""
    words = []
    i, n = 0, len(code)
    while i < n:
        ch = code[i]
        if ch in " \t\r\f\v":
            i += 1
            continue
        up = ch.upper()
        if up in "ABCUVW" and up.isalpha():
            where.fail(f"axis word {up!r} is not supported (vcnc interpolates the linear axes X, Y, Z)",
                       column=i + 1, text=token_at(code, i), expected="X, Y or Z")
        if up not in _LETTERS:
            tok = token_at(code, i)
            where.fail(
                f"unknown word {tok!r}",
                column=i + 1,
                text=tok,
                expected="one of the words N O G M F X Y Z I J K R P S",
            )
        value, end = read_number(code, i + 1, where, what=f"word {up}", word_start=i)
        words.append((up, value, i + 1, code[i:end].strip()))
        i = end
    return words


class _State:
    __slots__ = ("pos", "motion", "plane", "inch", "incremental", "exact_stop", "tolerance", "feed")

    def __init__(self) -> None:
        self.pos = np.zeros(3)
        self.motion: int | None = None
        self.plane = 2
        self.inch = False
        self.incremental = False
        self.exact_stop = True
        self.tolerance: float | None = None
        self.feed: float | None = None  # mm/s


def parse_iso(text: str, *, source: str | None = None) -> Program:
    """Parse ISO / Fanuc G-code text into a :class:`Program`.

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
    name: str | None = None
    for lineno, raw in enumerate(lines_of(text), start=1):
        where = Where(source, lineno, raw.strip())
        code = _strip_comments(raw, where)
        stripped = code.strip()
        if not stripped:
            continue
        if stripped.startswith("%"):
            if stripped != "%":
                where.fail("'%' must stand alone on its line", column=code.index("%") + 1, text=stripped,
                           expected="'%' alone")
            continue
        words = _words(code, where)
        if name is None:
            for letter, value, _, _ in words:
                if letter == "O":
                    name = f"O{value:g}"
        ended = _execute(words, st, blocks, used, where)
        if ended:
            break
    axes = tuple(a for i, a in enumerate(AXIS_LETTERS) if i in used)
    return Program(blocks=tuple(blocks), source=source, dialect="iso", axes=axes, name=name)


def _execute(words, st: _State, blocks: list[Block], used: set[int], where: Where) -> bool:  # noqa: C901
    """Apply one block's words to the state; append its executable block. True at program end."""
    seen: dict[str, tuple[float, int, str]] = {}
    gcodes: dict[str, tuple[int, int, str]] = {}
    mcodes: list[tuple[int, int]] = []
    number = None
    for letter, value, col, tok in words:
        if letter == "G":
            g = int(round(value))
            if g != value or g not in _G_GROUP:
                where.fail(f"unknown G code {tok!r}", column=col, text=tok,
                           expected="G00-G04, G17-G21, G40, G49, G61, G64, G80, G90, G91 or G94")
            grp = _G_GROUP[g]
            if grp in gcodes:
                where.fail(f"two G codes of the {grp} group in one block ({gcodes[grp][2]} and {tok})",
                           column=col, text=tok, expected=f"one {grp} code per block")
            gcodes[grp] = (g, col, tok)
        elif letter == "M":
            m = int(round(value))
            if m != value or m not in _M_OK:
                where.fail(f"unknown M code {tok!r}", column=col, text=tok,
                           expected="M02 or M30 (end), M03, M04, M05, M08 or M09 (ignored)")
            mcodes.append((m, col))
        else:
            if letter in seen:
                where.fail(f"word {letter} appears twice in one block", column=col, text=tok,
                           expected=f"at most one {letter} word")
            seen[letter] = (value, col, tok)
            if letter == "N":
                number = int(value) if value == int(value) else None
    # modal settings first: they apply to this block's own words
    if "units" in gcodes:
        st.inch = gcodes["units"][0] == 20
    if "plane" in gcodes:
        st.plane = _PLANE_OF_G[gcodes["plane"][0]]
    if "distance" in gcodes:
        st.incremental = gcodes["distance"][0] == 91
    scale = INCH if st.inch else 1.0
    dwell_g = "dwell" in gcodes
    if "P" in seen and not dwell_g and "path" not in gcodes:
        _, col, tok = seen["P"]
        where.fail("word P needs G04 (dwell [ms]) or G64 (path tolerance)", column=col, text=tok,
                   expected="G04 P<ms> or G64 P<tolerance>")
    if "path" in gcodes:
        g, gcol, gtok = gcodes["path"]
        st.exact_stop = g == 61
        if g == 64 and "P" in seen and not dwell_g:
            tol, col, tok = seen["P"]
            if not tol > 0:
                where.fail("G64 path tolerance P must be > 0", column=col, text=tok, expected="P > 0 [mm]")
            st.tolerance = tol * scale
        elif g == 64:
            st.tolerance = None
    if "F" in seen:
        f, col, tok = seen["F"]
        if not f > 0:
            where.fail("feed F must be > 0", column=col, text=tok,
                       expected="F > 0 [in/min]" if st.inch else "F > 0 [mm/min]")
        st.feed = f * scale / 60.0
    if "S" in seen and seen["S"][0] < 0:
        _, col, tok = seen["S"]
        where.fail("spindle speed S must be >= 0", column=col, text=tok, expected="S >= 0 [rev/min]")
    ended = any(m in (2, 30) for m, _ in mcodes)

    if dwell_g:
        g, gcol, gtok = gcodes["dwell"]
        if "motion" in gcodes:
            where.fail("G04 cannot share a block with a motion code", column=gcodes["motion"][1],
                       text=gcodes["motion"][2], expected="G04 in a block of its own")
        bad = [w for w in ("Y", "Z", "I", "J", "K", "R") if w in seen]
        if bad:
            _, col, tok = seen[bad[0]]
            where.fail(f"word {bad[0]} not allowed in a dwell block", column=col, text=tok,
                       expected="G04 P<ms> or G04 X<s>")
        if ("P" in seen) == ("X" in seen):
            where.fail("G04 needs exactly one of P (milliseconds) or X (seconds)", column=gcol, text=gtok,
                       expected="G04 P<ms> or G04 X<s>")
        val, col, tok = seen["P"] if "P" in seen else seen["X"]
        seconds = val / 1000.0 if "P" in seen else val
        if seconds < 0:
            where.fail("dwell time must be >= 0", column=col, text=tok, expected="a dwell time >= 0")
        blocks.append(Block(line=where.line, number=number, text=where.text, kind="dwell", start=st.pos.copy(),
                            target=st.pos.copy(), feed=0.0, dwell=seconds, exact_stop=True,
                            tolerance=st.tolerance))
        return ended

    if "motion" in gcodes:
        st.motion = gcodes["motion"][0]
    axis_words = [w for w in ("X", "Y", "Z") if w in seen]
    arc_words = [w for w in ("I", "J", "K") if w in seen]
    has_r = "R" in seen
    if not axis_words and "motion" not in gcodes:
        if arc_words or has_r:
            w = (arc_words or ["R"])[0]
            _, col, tok = seen[w]
            where.fail(f"word {w} without an arc motion", column=col, text=tok, expected="G02 or G03 with X/Y/Z")
        return ended
    if st.motion is None:
        _, col, tok = seen[axis_words[0]]
        where.fail("axis words before any motion code", column=col, text=tok,
                   expected="G00, G01, G02 or G03 before the first axis word")
    motion = st.motion
    mcol, mtok = (gcodes["motion"][1], gcodes["motion"][2]) if "motion" in gcodes else (
        seen[axis_words[0]][1], seen[axis_words[0]][2])
    if motion in (0, 1) and (arc_words or has_r):
        w = (arc_words or ["R"])[0]
        _, col, tok = seen[w]
        where.fail(f"word {w} is only allowed on arcs (G02/G03)", column=col, text=tok,
                   expected="X, Y, Z and F on G00/G01")
    if not axis_words and not (motion in (2, 3) and arc_words):
        where.fail(f"G{motion:02d} without axis words", column=mcol, text=mtok,
                   expected="at least one of X, Y, Z")
    target = st.pos.copy()
    for w in axis_words:
        i = "XYZ".index(w)
        v = seen[w][0] * scale
        target[i] = st.pos[i] + v if st.incremental else v
        used.add(i)
    if motion != 0 and st.feed is None:
        where.fail(f"G{motion:02d} feed move without a feed", column=mcol, text=mtok, expected="F > 0 [mm/min]")
    common = dict(line=where.line, number=number, text=where.text, start=st.pos.copy(), target=target,
                  exact_stop=st.exact_stop, tolerance=st.tolerance)
    if motion in (0, 1):
        seg = Line(st.pos, target)
        blk = Block(kind="rapid" if motion == 0 else "line", feed=np.inf if motion == 0 else st.feed,
                    segment=seg, **common)
    else:
        p, q = PLANE_AXES[st.plane]
        used.update((p, q))
        ccw = motion == 3
        if arc_words and has_r:
            _, col, tok = seen["R"]
            where.fail("arc with both I/J/K and R", column=col, text=tok, expected="either I/J/K or R")
        try:
            if has_r:
                seg = arc_from_radius(st.pos, target, seen["R"][0] * scale, ccw=ccw, plane=st.plane)
            elif arc_words:
                allowed = {"XYZ"[p], "XYZ"[q]}
                offs = np.zeros(3)
                for w in arc_words:
                    i = "IJK".index(w)
                    if "XYZ"[i] not in allowed:
                        _, col, tok = seen[w]
                        plane_g = {2: "G17", 1: "G18", 0: "G19"}[st.plane]
                        where.fail(f"word {w} is outside the arc plane ({plane_g})", column=col, text=tok,
                                   expected=f"centre words {'IJK'[p]} and {'IJK'[q]} in {plane_g}")
                    offs[i] = seen[w][0] * scale
                seg = arc_from_center(st.pos, target, st.pos + offs, ccw=ccw, plane=st.plane)
            else:
                where.fail(f"G{motion:02d} arc needs a centre (I/J/K) or a radius (R)", column=mcol, text=mtok,
                           expected="I/J/K or R")
        except ArcWordError as exc:
            w = "R" if has_r else (arc_words[0] if arc_words else None)
            col, tok = (seen[w][1], seen[w][2]) if w else (mcol, mtok)
            where.fail(exc.message, column=col, text=tok, expected=exc.expected)
        target = np.array(seg.end)
        common["target"] = target
        blk = Block(kind="arc", feed=st.feed, segment=seg, **common)
    blocks.append(blk)
    st.pos = target
    return ended
