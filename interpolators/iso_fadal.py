"""Programs written for Fadal VMCs (``--dialect fadal``): Fadal's own words, read before Fanuc's rules.

vcnc's built-in machines are modelled on Fadal VMCs, whose control (CNC 88HS) reads two program formats:
Format 1, Fadal's older one (cycle parameters as ``R0+2.``, ``R1``.. registers, ``H`` for the tool length
and the diameter), and Format 2, "Fanuc style" (the Fusion Fadal post's ``format`` property: "Enter 1 for
FADAL style formatting, 2 for Fanuc style"). Both keep Fadal's own words: ``E`` fixture offsets, ``L``
subroutines, ``H`` without G43. The shop programs this dialect was built for write Format 2 cycles (``R2.``
as the R plane, ``Q`` pecks, ``G98``) with those Fadal words, so the ``fadal`` dialect reads Format 2: every
word Fadal gives no meaning of its own is read as under ``--dialect fanuc``
(:mod:`interpolators.iso`); Format 1's numbered ``R1``-``R9`` words are refused, its ``R0+2.`` cycle plane
is read.

Sources: Fadal User Manual (April 2003), section 1 NC word summary ("E Fixture offset", "L Subroutine
definition or call", as :mod:`interpolators.iso`'s refusals under the other dialects quote it) and section
6 "Fixed Subroutines" (L9101 probe, L9201 engraving .. L9901: "called by the use of an L word (L9101 -
L9901)",
https://www.scribd.com/document/627180324/Sect-6-Fixed-Subroutines); helmancnc.com "Fadal G Codes M Codes
Fixed Subroutines" (G4 "P= Time in Milliseconds", G8 "Accelerate (No Feed Ramps)", G9 "Decelerate (Feed
Ramps) Also: In Position Check", G10 "L02= Fixture .. P= 0, 1-48", G15 "YZ Circular Interpolation with the
A Axis", G17.1/G17.2 "A/B Word Swap", G45-G48 "Tool Length Offset Single/Double Expansion/Reduction", G50
"Ramp Slope Control Cancel", G51 "Ramp Slope Control R0= Ramp Speed", G51.2 "Tool Load Compensation");
Autodesk's Fusion "Fadal" post processor (fadal.cps, revision 42984), which shows how Fadal programs are
written: Format 1 positions Z as ``G0 H<n> Z..`` (Format 2: ``G43 Z.. H<n>``) and opens with ``H0 E0``;
fixture offset n is ``E<n>`` or, for n <= 6 in Format 2, ``G<53+n>``; the R plane of a cycle is
``R0+<value>``; rigid tapping is ``G84.2``/``G74.2`` on its own block, then the cycle ``G84.1``/``G74.1``.
The full manual's sections on subroutines, fixture offsets and cycles were not in our search index: what
follows from them is marked "our reading".

What the dialect reads:

* ``E1``-``E48`` select fixture offset n, ``E0`` none (machine coordinates), from the block they are on:
  the work-offset table's ``G54``-``G59`` for E1-E6, its ``E7``-``E48`` beyond
  (:func:`interpolators.context.work_offset_code`).
* ``H<n>`` without G43/G44/G49 applies tool length n, as ``G43 H<n>`` (Format 1's ``G0 H1 Z..``); ``H0``
  cancels it, as ``G49``. On a block with G41/G42 and no D, ``H`` names the diameter offset (Format 1's
  ``G41 H..``), as ``D``.
* Subroutines (our reading of the NC word summary and of the shop programs): ``L<nn>00`` (nn 01-99) opens
  subroutine nn, ``M17`` closes it; the definitions stand first in the file, an ``M30`` ends them and the
  main program follows it. ``L<nn><rr>`` calls subroutine nn rr times (``L0101``, ``L101``); a subroutine may
  call others, up to :data:`interpolators.iso_flow.MAX_CALL_LEVELS` deep (no limit found in the manual).
  The blocks of a subroutine keep their own lines (``--blocks``). ``L9101``-``L9901`` (fixed subroutines:
  probing, engraving, ...) are refused naming them.
* ``L`` on a block of a canned cycle (``G81 .. L0``) is the cycle's repeat count, read as Fanuc's (L0: the
  cycle is stored, no hole drilled there); on an arc block (``G3 I-2. Z-0.2 L19``) the arc runs L times
  (our reading: L times in all, each from where the last ended; under G91 a helix goes down L steps).
* ``G8``/``G9`` (feed ramps off/on), ``G50``/``G51`` (ramp slope control), ``G51.2`` (tool load
  compensation), ``G84.2``/``G74.2`` (rigid tapping set-up) change no path: noted and skipped.
  ``G84.1``/``G74.1`` (rigid tapping cycles) run as G84/G74. G45-G48 run as Fanuc's tool position offsets,
  which their Fadal names describe (expansion = increase, reduction = decrease of the travel by the offset
  the block's H names). ``G4 P`` is in milliseconds.
* ``G10 L02 P1``-``P6`` (fixtures E1-E6) and ``L10 P R0`` (tool length) as Fanuc's; ``L12 P R0`` sets a
  diameter (halved: the tool table keeps radii).
* Arc centres ``I J K`` are the centre minus the start, as Fanuc's (Format 2) and as Autodesk's Fusion Fadal post
  writes them in both formats (fadal.cps ``onCircular``: ``iOutput.format(cx - start.x, 0)``, no branch on the
  ``format`` property). Siemens NX's Post Builder template for Fadal (``pblib/controller/mill/fadal.def``, 1998-2001,
  ``circular_move_1``) writes the start minus the centre; the Fadal manual's text on it was not found, so this is our
  reading, and no setting reverses it. Such a program's arcs mostly end off their circle and are refused, with a
  hint that the reversed centre would fit (:func:`interpolators.iso_arcs.read_arc`); a full circle (end = start)
  would run mirrored about its start without error.
* Refused naming them: ``G15`` (YZ circular interpolation with the A axis), ``G17.1``/``G17.2`` (A/B word
  swap), Format 1's ``R1``-``R9`` words, ``G10 L02 P7``-``P48`` and G10's read functions (L13-L15, L100-L109).
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable, Iterator
from typing import Any

from interpolators._words import Where
from interpolators.context import FADAL_FIXTURES, MachineContext, work_offset_code
from interpolators.iso_flow import MAX_CALL_LEVELS, FlowLine
from interpolators.iso_words import Word
from vcnc.core.errors import GCodeError

__all__ = ["FIXED_SUBROUTINES", "fadal_text", "core_context", "fadal_lines"]

#: Fadal's fixed subroutines (User Manual section 6): number nn of ``L<nn>01`` -> name.
FIXED_SUBROUTINES: dict[int, str] = {91: "L9101 probing", 92: "L9201 engraving", 93: "L9301", 94: "L9401",
                                     95: "L9501", 96: "L9601", 97: "L9701", 98: "L9801", 99: "L9901"}

#: Codes (round(10 * G)) that change no path here, and the note each gives.
_NOTED = {80: "G8 feed ramps off (Fadal): path unchanged", 90: "G9 feed ramps on, in-position check (Fadal): "
          "path unchanged", 500: "G50 ramp slope control cancel (Fadal): path unchanged",
          510: "G51 ramp slope control (Fadal): feed ramps not modelled, path unchanged",
          512: "G51.2 tool load compensation (Fadal): feed not adapted",
          842: "G84.2 rigid tapping set-up (Fadal)", 742: "G74.2 rigid tapping set-up (Fadal)"}
#: Codes refused, with their Fadal meaning.
_REFUSED = {150: "G15 YZ circular interpolation with the A axis (Fadal)", 171: "G17.1 A/B word swap (Fadal)",
            172: "G17.2 A/B word swap off (Fadal)"}
#: Rigid tapping cycles -> the G code they run as.
_RIGID = {841: 84.0, 741: 74.0}
_CYCLES = frozenset({730, 740, 760, 770, 841, 741, *range(810, 900, 10)})
_ARCS = frozenset({20, 30})
#: Format 1's numbered R word with its signed value (``R0+2.``, ``R1-.5``), outside comments.
_R_REGISTER = re.compile(r"([Rr])[ \t]*([0-9])(?=[ \t]*[-+])")


def fadal_text(text: str, source: str | None) -> str:
    """``text`` with Format 1's cycle plane ``R0+2.`` written ``R +2.`` (same columns), line by line.

    Raises
    ------
    vcnc.GCodeError
        A numbered ``R1``-``R9`` word with a signed value (a Format 1 / G51.2 / fixed subroutine parameter).
    """
    if "R" not in text and "r" not in text:
        return text
    lines = text.split("\n")
    for i, line in enumerate(lines):
        parts = re.split(r"(\([^)]*\)?)", line)  # comments stay as they are
        for k in range(0, len(parts), 2):
            m = next((m for m in _R_REGISTER.finditer(parts[k]) if m.group(2) != "0"), None)
            if m is not None:
                column = len("".join(parts[:k])) + m.start() + 1
                Where(source, i + 1, line).fail(
                    f"Fadal R{m.group(2)} word (a Format 1, G51.2 or fixed subroutine parameter): not supported",
                    column=column, text=m.group(0), expected="Format 2 words (R<value> as a cycle's R plane)")
            parts[k] = _R_REGISTER.sub(lambda m: m.group(1) + " ", parts[k])
        lines[i] = "".join(parts)
    return "\n".join(lines)


def core_context(context: MachineContext) -> MachineContext:
    """The context the Fanuc rules read a Fadal program's other words with (the dialect named ``fanuc``)."""
    return dataclasses.replace(context, dialect=dataclasses.replace(context.dialect, name="fanuc"))


@dataclasses.dataclass
class _Reader:
    st: Any  # the ISO executor's state (interpolators.iso): wcs set, motion read here
    note: Callable[[str], None]
    invalidate: Callable[[], None]  # the state's offsets changed: plain moves judge them again
    subs: dict[int, list[FlowLine]] = dataclasses.field(default_factory=dict)


def fadal_lines(lines: Iterator[FlowLine], st, note: Callable[[str], None],
                invalidate: Callable[[], None]) -> Iterator[FlowLine]:
    """The executed lines of a Fadal program (:func:`interpolators.iso_flow.run`'s ``lines``) as the Fanuc
    rules read them: subroutine definitions kept aside and run where called, arcs repeated, E, H and
    Fadal's G codes applied to ``st`` (the executor's state, before the line is yielded) or translated.
    ``invalidate`` is called when a fixture offset changes the state's offset."""
    reader = _Reader(st, note, invalidate)
    note("read as Fadal Format 2 (Fanuc rules for the words Fadal gives no meaning of its own)")
    lines = iter(lines)
    for fl in lines:
        if _definition(fl) is not None:
            _definitions(reader, fl, lines)
            continue
        yield from _run_line(reader, fl, 0)


def _where(fl: FlowLine) -> Where:
    return Where(fl.file, fl.line, fl.raw)


def _definition(fl: FlowLine) -> int | None:
    """The subroutine number nn of a line ``L<nn>00`` (with at most an N word), else None."""
    ls = [w for w in fl.words if w.letter == "L"]
    if len(ls) != 1 or any(w.letter not in "LN" for w in fl.words):
        return None
    v = ls[0].value
    return int(v) // 100 if v == int(v) and v >= 100 and int(v) % 100 == 0 else None


def _definitions(reader: _Reader, first: FlowLine, lines: Iterator[FlowLine]) -> None:
    """Read the subroutine definitions from ``first`` (an ``L<nn>00`` line) to the M30 that ends them."""
    current: int | None = None
    fl = first
    while True:
        nn = _definition(fl)
        ms = [w for w in fl.words if w.letter == "M"]
        if nn is not None:
            if current is not None:
                _where(fl).fail(f"L{nn}00 opens subroutine {nn} inside subroutine {current} (no M17 before it)",
                                expected=f"M17 closing subroutine {current} first")
            if nn in reader.subs:
                _where(fl).fail(f"subroutine {nn} defined twice", expected="one L<nn>00 .. M17 per number")
            current, reader.subs[nn] = nn, []
        elif any(w.value == 17 for w in ms):
            if current is None:
                _where(fl).fail("M17 outside a subroutine definition", expected="L<nn>00 .. M17")
            rest = [w for w in fl.words if not (w.letter == "M" and w.value == 17)]
            if any(w.letter != "N" for w in rest):
                reader.subs[current].append(dataclasses.replace(fl, words=rest))
            current = None
        elif any(w.value == 30 for w in ms):
            if current is not None:  # iso_flow.run reads an M99 outside an M98 call as the program's end (M30)
                m99 = any(re.fullmatch(r"M\s*0*99", w.text, re.I) for w in ms)
                _where(fl).fail(f"{'M99' if m99 else 'M30'} inside subroutine {current} (no M17 closes it"
                                f"{'; M99 returns from an M98 subprogram' if m99 else ''})",
                                expected=f"M17 closing subroutine {current} before the M30")
            reader.note("Fadal subroutines defined before the M30; the main program runs after it")
            return
        elif current is not None:
            reader.subs[current].append(fl)
        elif any(w.letter != "N" for w in fl.words):
            _where(fl).fail("a block between Fadal subroutine definitions (outside L<nn>00 .. M17)",
                            expected="L<nn>00 .. M17 definitions, then M30 and the main program")
        fl = next(lines, None)
        if fl is None:
            where = _where(first)
            raise GCodeError(f"subroutine definitions from L{_definition(first)}00 not ended by an M30"
                             + (f" (subroutine {current} has no M17)" if current is not None else ""),
                             file=where.file, line=where.line, text=first.raw,
                             expected="L<nn>00 .. M17 definitions, then M30 and the main program")


def _run_line(reader: _Reader, fl: FlowLine, depth: int) -> Iterator[FlowLine]:
    """Yield line ``fl`` as the Fanuc rules read it, or the lines of the subroutine it calls."""
    words, call, repeats = _translate(reader, fl)
    if call is None:
        for _ in range(repeats):
            yield dataclasses.replace(fl, words=words)
        return
    nn, rr, w = call
    if any(x.letter != "N" for x in words):
        yield dataclasses.replace(fl, words=words)
    if nn not in reader.subs:
        what = (f"Fadal fixed subroutine {FIXED_SUBROUTINES[nn]} (Fadal User Manual section 6): not supported"
                if nn in FIXED_SUBROUTINES else f"L{w.value:g} calls subroutine {nn}, which is not defined")
        _where(fl).fail(what, column=w.column, text=w.text,
                        expected="L<nn><rr> calling a subroutine L<nn>00 .. M17 defined before the M30")
    if depth >= MAX_CALL_LEVELS:
        _where(fl).fail(f"subroutine calls nested more than {MAX_CALL_LEVELS} deep", column=w.column, text=w.text,
                        expected="subroutines that do not call themselves without end")
    reader.note("Fadal L subroutine call")
    for _ in range(rr):
        for line in reader.subs[nn]:
            yield from _run_line(reader, line, depth + 1)


def _translate(reader: _Reader, fl: FlowLine) -> tuple[list[Word], tuple[int, int, Word] | None, int]:
    """The words of ``fl`` for the Fanuc rules, the subroutine call ``(nn, rr, L word)`` it makes (else
    None) and how many times the line runs (an arc's L)."""
    where = _where(fl)
    keys = {round(w.value * 10): w for w in fl.words if w.letter == "G"}
    words = []
    for w in fl.words:
        key = round(w.value * 10) if w.letter == "G" else None
        if key in _REFUSED:
            where.fail(f"{_REFUSED[key]}: not supported", column=w.column, text=w.text,
                       expected="the G codes Fadal shares with Fanuc")
        if key in _NOTED:
            reader.note(_NOTED[key])
            continue
        if key in _RIGID:
            reader.note(f"{w.text.upper()} rigid tapping (Fadal) run as G{_RIGID[key]:g}")
            w = Word("G", _RIGID[key], w.column, w.text)
        elif key is not None and any(x.letter == "G" and x.value == w.value for x in words):
            reader.note(f"{w.text.upper()} written twice in one block: read once (Fadal)")
            continue
        elif w.letter == "M" and w.value == 17:
            where.fail("M17 outside a subroutine definition", column=w.column, text=w.text,
                       expected="M17 closing a subroutine L<nn>00 before the M30")
        words.append(w)
    if 510 in keys:  # G51's R0 is the ramp speed
        words = [w for w in words if w.letter != "R"]
    if 100 in keys:
        words = _g10(reader, words, where)
    words = _fixture(reader, words, where)
    words = _length(reader, words, keys)
    words = _centreless_arc(reader, words, keys)
    return _l_word(reader, words, keys, where)


def _centreless_arc(reader: _Reader, words: list[Word], keys: dict[int, Word]) -> list[Word]:
    """A block of axis words in the modal G2/G3 without I, J, K or R: a straight feed move (G1), as shop
    programs rely on after ``G3 I-2. L2`` (``G91 X-2.`` back to the start). Our reading: the manual at hand
    does not say; Fanuc refuses such a block."""
    if keys.keys() & {0, 10, 20, 30} or reader.st.motion not in _ARCS:
        return words
    if any(w.letter in "IJKR" for w in words) or not any(w.letter in "XYZ" for w in words):
        return words
    first = next(w for w in words if w.letter in "XYZ")
    reader.note("X/Y/Z in the modal G2/G3 without I, J, K or R: a G1 move (Fadal, our reading)")
    return [Word("G", 1.0, first.column, first.text), *words]


def _g10(reader: _Reader, words: list[Word], where: Where) -> list[Word]:
    """Fadal ``G10`` (helmancnc.com's list): ``L02 P1-6`` (fixtures E1-E6) and ``L10 P R0`` (tool length) as
    Fanuc's; ``L12 P R0`` is a diameter (Fanuc's L12 a radius: halved); the fixtures E7-E48 and the read
    functions L13-L15, L100-L109 are refused naming them."""
    level = next((w for w in words if w.letter == "L"), None)
    p = next((w for w in words if w.letter == "P"), None)
    if level is None or level.value in (10.0,) or level.value == 2 and p is not None and p.value <= 6:
        return words
    if level.value == 12:
        reader.note("G10 L12 R: a diameter (Fadal), half of it the radius")
        return [Word("R", w.value / 2.0, w.column, w.text) if w.letter == "R" else w for w in words]
    what = ("G10 L02 P7-P48: setting Fadal fixture offsets E7-E48" if level.value == 2 else
            f"G10 L{level.value:g} (Fadal: reading offsets into R registers, or setting R values)")
    where.fail(f"{what}: not supported", column=level.column, text=level.text,
               expected="G10 L02 P1-P6, L10 or L12 (fixtures E1-E6, tool length, diameter)")


def _fixture(reader: _Reader, words: list[Word], where: Where) -> list[Word]:
    """Apply the block's E word (fixture offset) to the state; the words without it."""
    e = next((w for w in words if w.letter == "E"), None)
    if e is None:
        return words
    n = e.value
    if n != int(n) or not 0 <= n <= FADAL_FIXTURES:
        where.fail(f"E{n:g} is not a Fadal fixture offset", column=e.column, text=e.text,
                   expected=f"E0 (none) or E1 .. E{FADAL_FIXTURES}")
    reader.st.wcs = "E0" if n == 0 else work_offset_code(f"E{int(n)}")
    reader.invalidate()
    reader.note("E fixture offset (Fadal)" if n else "E0: no fixture offset (Fadal)")
    return [w for w in words if w is not e]


def _length(reader: _Reader, words: list[Word], keys: dict[int, Word]) -> list[Word]:
    """An H word without G43/G44/G49: the tool length (G43 H), H0 its cancel (G49); with G41/G42 and no D, the
    diameter offset (D)."""
    h = next((w for w in words if w.letter == "H"), None)
    if h is None or keys.keys() & {430, 440, 490, 450, 460, 470, 480}:
        return words
    if keys.keys() & {410, 420}:
        if any(w.letter == "D" for w in words):
            return words
        reader.note("H on a G41/G42 block: the diameter offset (Fadal Format 1), read as D")
        return [Word("D", h.value, h.column, h.text) if w is h else w for w in words]
    reader.note("H without G43: the tool length applied (Fadal)" if h.value else "H0: tool length cancelled (Fadal)")
    if h.value == 0:
        return [w for w in words if w is not h] + [Word("G", 49.0, h.column, h.text)]
    return words + [Word("G", 43.0, h.column, h.text)]


def _l_word(reader: _Reader, words: list[Word], keys: dict[int, Word],
            where: Where) -> tuple[list[Word], tuple[int, int, Word] | None, int]:
    """What the block's L word is: a cycle's repeat count or G10's level (left to the Fanuc rules), an arc's
    repeat count, or a subroutine call."""
    ls = [w for w in words if w.letter == "L"]
    if not ls or keys.keys() & (_CYCLES | {100, 650}):
        return words, None, 1
    w = ls[0]
    motion = next((k for k in keys if k in (0, 10, 20, 30)), None)
    st_motion = reader.st.motion
    arc = motion in _ARCS or motion is None and st_motion in _ARCS and any(x.letter in "IJKR" for x in words)
    rest = [x for x in words if x is not w]
    if arc:
        if w.value != int(w.value) or w.value < 1:
            where.fail(f"L{w.value:g} on an arc: not a repeat count", column=w.column, text=w.text,
                       expected="L1 .. L99: the arc runs L times")
        reader.note("L on an arc: the arc runs L times (Fadal)")
        return rest, None, int(w.value)
    axes = any(x.letter in "XYZ" for x in words)
    if st_motion is not None and st_motion >= 730 and axes:
        return words, None, 1  # a hole of the active cycle, its repeats
    v = w.value
    if v != int(v) or v < 100 or int(v) % 100 == 0:
        what = ("opens a subroutine: definitions stand before the M30 that ends them, the main program after it"
                if v == int(v) and v >= 100 else "is no subroutine call (L<nn><rr>: subroutine nn, rr times)")
        where.fail(f"L{v:g} {what}", column=w.column, text=w.text, expected="L<nn><rr> with nn 01-99, rr 01-99")
    return rest, (int(v) // 100, int(v) % 100, w), 1
