"""An independent reference for where the blocks of an ISO (RS274/NGC) program end.

Test code only: it imports nothing of the readers (``interpolators.iso*``), only the machine
context's tables (:class:`interpolators.context.MachineContext`, the same offsets, tools, home and
reference positions the reader is given). It is written from the LinuxCNC G-code documentation
(LinuxCNC/linuxcnc ``docs/src/gcode/g-code.adoc``, ``overview.adoc``, ``coordinates.adoc``,
``o-code.adoc``; https://linuxcnc.org/docs/html/gcode/g-code.html) and, for ``M98``/``M99``, the
Fanuc/Haas subprogram rules (Haas mill operator's manual, "M98 Subprogram Call"):

- Lines: ``( )`` and ``;`` comments, ``/`` block delete (off: the block runs), ``N`` numbers,
  ``%`` marks, spaces ignored, case ignored (overview.adoc "Format of a line").
- Order of execution on a line (overview.adoc "G-code order of execution"): parameter settings
  (read before any is set), dwell, plane, units, cutter compensation, tool length, coordinate
  system, distance mode, retract mode, G28/G30/G10/G92, motion (as modified by G53), stops.
- Machine position = rotation(G10 R) of (program + G92 offset) + work offset + tool offsets (length
  along Z, the table's X Y offsets: g-code.adoc "G43") (``coordinates.adoc``; LinuxCNC applies the
  XY rotation of ``G10 L2 R`` about the coordinate system origin). G44 subtracts what G43 adds (Fanuc
  B-63943EN-1/02 12.5.2 "Offset direction"). Where the context's dialect moves the axis by a length change
  (``Dialect.length_offset_motion``, Fanuc parameter TOS = 0, its default; the machine file's
  ``length_offset_motion``) the change is added to the next incremental Z, and a G43/G44/G49 block of G00/G01 without
  a Z word moves Z by it at once (12.5.2 says of TOS = 1 that such a block does not move the tool). A canned cycle
  in G17 that drills a hole takes the change up at its R positioning (Fanuc 15i-MA B-63784EN, "Tool length
  compensation" in a canned cycle: "the offset is applied at the time of positioning to point R"): under G90 its
  levels hold the new offset, and the series' initial level (a program level here) is where the tool stood under the
  offset it had travelled, so a G91 R is measured from it and a G98 returns to it.
- Fanuc G43.4 / G43.5 / Haas G234 (``--dialect fanuc`` / ``haas``) on the context's tilting table: the tool
  length as G43, X Y Z the tool tip in the work system the table carries (G43.5: I J K the tool direction
  there) (FANUC 30i "Tool center point control for 5-axis machining" A-79348E 1.1; Haas "G234 TCPC"): a G0/G1
  ends where the table at the block's rotary positions carries the programmed tip (its own map: elementary
  rotations about each axis' pivot).
- G28/G30: with axis words a rapid to that point (program coordinates, with offsets), then a rapid
  of the named axes to the home / second reference position; without axis words, every axis to it
  (g-code.adoc "G28, G28.1"); G28.1 / G30.1 make the current position that reference. G53: the named
  axes go to machine coordinates.
- Canned cycles G73, G81-G89 (g-code.adoc "G80-G89 Canned Cycles", "G73", "G83", "G98, G99"):
  preliminary rapid to R when below it (once; Fanuc/Haas: X Y first, 0i-MF "Canned cycle for drilling"), per
  repeat a rapid in XY, a rapid to R, the feed to the bottom (pecks of Q for G73/G83 with the 0.254 mm /
  0.010 in clearance, G83 back to R between pecks), dwell for G82/G89, the feed out for G85/G89 (under
  fanuc/haas to R, then the rapid to clear Z: FANUC 30i operator's manual B-63944EN-2 5.1.9), and the retract
  to clear Z
  (G98: the Z before the series if above R, else R; G99: R). In G91, X/Y/R are increments from
  the current position and Z from R; polar ``@ ^`` repeats add to the polar position.
- Parameters ``#n``, ``#<local>``, ``#<_global>``, expressions in ``[ ]`` with the documented
  precedence (``**``; ``* / MOD``; ``+ -``; comparisons; ``AND OR XOR``) and functions
  (overview.adoc "Expressions", "Unary Operation Value"); O-words sub/endsub/call/return,
  if/elseif/else/endif, while/endwhile, do/while, repeat/endrepeat, break/continue
  (o-code.adoc), call arguments in ``#1..#30``, return value in ``#<_value>``.
- Polar ``@ ^`` (overview.adoc "Polar Coordinates"): from the XY zero of the current system,
  cumulative in G91.
- G33 (g-code.adoc "G33 Spindle Synchronized Motion"): a feed move to the end point; G33.1 ("G33.1
  Rigid Tapping"): a feed move to the end point and one back to where it started.
- G5 / G5.1 splines: the end point only (the reader writes chords; their last one must end there).
- G41/G42: the compensated end points are not the programmed ones; see :class:`Expected`. Under
  ``fanuc``/``haas`` an outside corner's end point is Fanuc's (:func:`fanuc_corner`: the offsets'
  intersection, at an acute corner the vectors lengthened by the radius; under a mirror of one plane axis the
  side is the other one in the machine, Fanuc 0i-MF "Programmable mirror image"); after ``G39`` the corner
  is an arc about it, checked one radius off. After G40 with
  no exit move, LinuxCNC's M6/M61 makes the last offset point the current one (``read_inputs``:
  ``refresh_actual_position``): the next move is checked within the radius.
- The axes beyond X, Y, Z (g-code.adoc "G0", overview.adoc "Feed Rate", coordinates.adoc): A, B, C
  [deg] and U, V, W [mm, inches under G20] go to their word's value plus the work and G92 offsets
  of that axis (G91: plus the word; G53: the word), others stay. G92, G10 L2/L20 set those
  offsets as for X, Y, Z (LinuxCNC ``interp_convert.cc`` ``convert_setup``: L20 makes the current
  position, G92 included, the given value); the tool length and the G10 R rotation leave them
  alone. G28/G30 take the named axes through the intermediate point to the reference (0 for
  these axes), without words all of them.
- Fanuc / Haas mills (``fanuc``, ``haas`` dialects; Haas mill operator's manual "G68 Rotation", "G187
  Smoothness Control", "G103"; Fanuc 0i-MF operator's manual "Coordinate system rotation", "AI
  contour control"): G187, G103, G05.1, G08 and G05 P10000 move nothing (their words are theirs);
  ``G68 X Y R`` (the plane's two axes, default the current position; R absolute [deg],
  counter-clockwise) rotates the program coordinates of the following blocks about that centre
  before any offset, G69 cancels. Their mill cycles (Fanuc 0i-MF "Left-handed tapping cycle",
  "Fine boring cycle", "Back boring cycle"; Haas "G74", "G76", "G77 Back Bore"): G74 as a tap (feed
  in, dwell, feed out to R, rapid to clear); G76 feed in, dwell, rapid shift (I J, else Q along +X),
  rapid to clear, rapid shift back; G87 (Haas G77) from the initial level: shift, rapid down to R,
  shift back, feed up to Z, dwell, shift, rapid to the initial level, shift back. Haas G70 (L holes
  on a circle of radius I about X Y or the current point, from J degrees), G71 (K degrees apart), G72
  (along a line at J degrees, I apart, the first I from the start): the active cycle at each hole.
  ``G51.1 X..`` mirrors X about that line (G50.1 cancels; Haas G101 / G100 about 0), ``G51 X Y Z P``
  / ``I J K`` scales about the centre (Fanuc: P I J K without a decimal point in 0.001), G50 cancels;
  a program point goes through mirror, scaling, then rotation; an arc in a plane with one axis
  mirrored turns the other way.
  Haas G12 / G13 circular pocket (the radii I, I + Q, ... up to K less the D tool's radius): per
  pass (Z, under G91 L times deeper; no Z: at the current Z) a feed down at the centre, for each radius a
  half circle from the previous one's +X point (the centre first) and the full circle, a feed back to the
  centre.
  Additional work offsets (Fanuc 0i-MD "Adding workpiece coordinate systems"; Haas "G154"): Fanuc
  ``G54.1 P1``-``P300``, Haas ``G154 P1``-``P99`` and ``G110``-``G129`` (= P1-P20), P omitted = P1,
  select the context's ``"G54.1 P<n>"`` entry; ``G10 L2 P1``-``P6`` (G54-G59) and ``G10 L20 P<n>`` set
  the offset to the value under G90 and add it under G91; ``G10 L2 P0`` the external offset, added to
  every system. G52 is the local system on top of the G92
  shift (Fanuc "Local coordinate system": G52 X0 cancels it; G92 cancels it on the axes it names).
  Fanuc/Haas ``G10 L10 P R`` sets tool length geometry, ``L11``/``L1`` its wear, ``L12`` radius geometry
  (Haas: a diameter), ``L13`` its wear (G91: added); G43 H / G41 D use geometry + wear. LinuxCNC
  ``G10 L1 P<tool> Z R`` sets the tool table's length and radius (X/Y tool offsets are not modelled).
  The external output commands ``POPEN``, ``DPRNT[..]``, ``BPRNT[..]``, ``PCLOS`` move nothing.
  Fanuc ``G16`` (Series 16/18-MC operator's manual 9.2 "Polar coordinate command"): under G90 and
  G17 the X and Y of a motion block are the radius and angle about the work zero, as ``@ ^``; G15
  cancels.
  Fadal VMCs (``fadal`` dialect; Fadal User Manual section 1 NC words and section 6 fixed subroutines,
  helmancnc.com's Fadal G/M code list, the Fusion "Fadal" post processor): read as Fanuc after a pass over
  the lines in the order they run: ``L<nn>00`` .. ``M17`` subroutines stand before the ``M30`` that ends
  them, the main program after it, ``L<nn><rr>`` runs subroutine nn rr times where it stands; ``L<k>`` on a
  ``G2``/``G3`` block runs the arc k times, on a cycle block it is the cycle's count; ``E<n>`` selects
  fixture offset n (E1-E6: G54-G59, E0: none); ``H<n>`` without G43/G44/G49 is ``G43 H<n>`` (``H0``:
  ``G49``); ``G10 L12 R0`` is a diameter; ``G8``/``G9``/``G50``/``G51 R..``/``G51.2``/``G84.2``/``G74.2``
  move nothing, ``G84.1``/``G74.1`` are G84/G74; ``R0+v`` is ``R v``; X/Y/Z without a centre in the modal
  G2/G3 is a G1 move.
  Fanuc ``M98 P<count><program>`` (0i-MC B-64124EN 12.3 "Subprogram": ``M98 P51002`` calls O1002 five times)
  when there is no L and no program O<P>. Fanuc DPI = 0 (``MachineContext.decimal_point_input`` "increment"):
  distances without a decimal point in least input increments (:func:`_least_increments`).
  Haas ``M97 P<n> L<k>`` ("M97 Local Sub-Program Call") runs the blocks from ``N<n>`` of the same
  program to its ``M99`` k times; ``M98 P<p> Q<n>`` (Mitsubishi, Mach4) runs ``O<p>`` from its
  ``N<n>``; ``M98 Q<n>`` without P (Mitsubishi: P "own program if omitted") runs this program's ``N<n>``
  to its M99, as M97 does. Under LinuxCNC an M98 block runs the call alone ("analogous to the traditional
  o100 call", o-code.adoc "Fanuc-Style Numbered Programs"): its other words do not run; Fanuc and Haas run
  them before the call. ``M99 P<n>`` returns to the block ``N<n>`` of the calling program (Haas "M99 Subprogram
  Return or Loop"), found as a GOTO finds it from the call.
  Fanuc ``G66 P<program> L<count> <arguments>`` (0i-MD B-64304EN "Modal call (G66)"): after each later block with
  axis words the program runs L times with the G66 block's arguments as a G65's, until ``G67``; the called
  program's own moves call nothing; nested G66, moves of an M98/G65 call under G66 and a G28/G92/G10 block under
  it are not modelled (ReferenceError). Fanuc/Haas work offset variables written by the program (0i-MD "System
  variables"; Haas "Macros"): ``#5201``-``#5203`` the external offset (as G10 L2 P0), ``#5221``.. G54-G59 and
  ``#7001``.. G54.1 P<n> / G154 P<n> (20 apart), X Y Z, in the machine's length unit, at once (fuzz40).
- Fanuc/Haas ``,R r`` / ``,C c`` at the end of a G01 block (Fanuc 0i-MF operator's manual "Optional
  chamfering and corner R"; Haas mill operator's manual "G01 Corner Rounding and Chamfering"), here
  between two straight feed moves only: a rounding arc tangent to both, touching each ``r tan(t/2)``
  from the corner (``t`` the turn angle), its centre ``r / cos(t/2)`` from the corner on the bisector;
  a chamfer from ``c`` before the corner to ``c`` after it; a row of the first block's line between
  the two moves, which end / start there. Next to an arc (Fanuc) the rounding's centre is searched
  among the points ``r`` from both elements, and a chamfer's ends are at the chord ``c`` from the corner.
- grbl (gnea/grbl ``doc/markdown/commands.md``, ``grbl/config.h``): ``$`` lines are system commands
  and move nothing, but ``$H``, the homing cycle: Z to the home position, then X and Y
  (``HOMING_CYCLE_0``, ``HOMING_CYCLE_1``), as rapids; a ``(`` without ``)`` comments out the rest
  of the line (``protocol.c``).

What the reference predicts for each motion block is an :class:`Expected`; the test aligns them
with the reader's ``--blocks`` rows.
"""

from __future__ import annotations

import copy
import dataclasses
import itertools
import math
import re

import numpy as np

__all__ = ["Expected", "ReferenceError", "iso_reference"]

#: G73/G83 peck clearance of LinuxCNC's defaults (g-code.adoc "G73", "G83") [program units: in].
PECK_CLEARANCE_IN = 0.010


#: Relative rounding allowance when comparing two program positions (is Z below R?) [mm/mm].
_EPS = 1e-9


class ReferenceError(Exception):
    """The program uses something this reference does not model (the test reports it)."""


def wrapped_end(rule: str, word: float, now: float, offset: float) -> float:
    """The end [deg, machine] of the absolute word ``word`` on a rotary axis that wraps at 360 deg, now at ``now``,
    machine = program + ``offset``: among the positions that show the word's angle, the one the rule picks
    (searched over the turns around ``now``, not computed as the reader does). ``"sign"`` (LinuxCNC INI docs,
    WRAPPED_ROTARY; Fanuc RAB = 1): ``|word|`` is the angle, its sign the way; ``"shortest"`` (Fanuc RAB = 0, TNC
    M126): at most half a turn, exactly half the positive way (Fanuc 15i B-63783EN-1, 1.6.3); ``"difference"`` (TNC
    without M126): from the angle shown in [0, 360) by the word minus it."""
    shown = abs(word) if rule == "sign" else word
    if rule == "sign" and abs(word) >= 360.0:
        raise ReferenceError(f"wrapped word {word} (an error)")
    k0 = int(math.floor((now - shown - offset) / 360.0))
    ends = [shown + offset + 360.0 * k for k in range(k0 - 2, k0 + 4)]
    if rule == "sign":
        if math.copysign(1.0, word) > 0:
            return min(e for e in ends if e >= now - 1e-9)
        return max(e for e in ends if e <= now + 1e-9)
    if rule == "shortest":
        return min(ends, key=lambda e: (abs(e - now) > 180.0 + 1e-9, abs(e - now), e < now))
    shown_now = now - offset
    while shown_now >= 360.0:
        shown_now -= 360.0
    while shown_now < 0.0:
        shown_now += 360.0
    if shown_now > 360.0 - 1e-9:  # a residue below a whole turn (-2.8e-17 + 360 = 360.0) shows 0
        shown_now = 0.0
    return now + word - shown_now


@dataclasses.dataclass(frozen=True, kw_only=True)
class Expected:
    """What one programmed motion produces in the ``--blocks`` table.

    Attributes
    ----------
    line : int
        1-based source line of the block.
    kind : str
        ``rapid``, ``feed``, ``arc_cw``, ``arc_ccw`` or ``dwell``; ``None`` when any kind is right
        (a compensated block may become a line and a corner arc).
    end : ndarray (3,)
        End point in machine coordinates [mm] (for a dwell: where the tool stands).
    tolerance : float
        How far the reader's end may be from ``end`` [mm]: 0 (exact, up to rounding) except for
        blocks under G41/G42, where it is the tool radius (the compensated end is one radius
        from the programmed point, and a corner arc inserted at an outside corner ends there too).
    rows : str
        ``"one"``: exactly one row; ``"last"``: one or more rows with this line whose last ends at
        ``end`` (spline chords, compensated blocks with inserted corner arcs); ``"optional"``: one
        row or none (a zero-length move LinuxCNC may leave out, e.g. a cycle's rapid to R when
        already at R).
    centre : ndarray (3,) or None
        Arc centre [mm, machine]; its two in-plane coordinates are checked.
    centre_tolerance : float
        How far the reader's centre may be from ``centre`` [mm]: 1 um, plus, when the programmed
        centre is not equidistant from the start and the end (CAM output rounded to 3-4
        decimals: radii ``rs`` and ``re`` differ), ``2 |rs - re| max(rs, re) / chord``: LinuxCNC
        then keeps the centre and makes a spiral, a reader may fit an arc through both ends with
        its centre on their bisector, which lies ``|rs^2 - re^2| / (2 chord)`` from the centre.
    plane : tuple of int
        Indices of the arc plane's axes (G17: x, y; G18: z, x; G19: y, z).
    element : tuple or None
        Under G41/G42: the programmed element, ``("line", start, end)`` or ``("arc", centre, radius,
        plane, start, slack)`` [mm, machine]. The compensated end must lie one tool radius from it (within
        1 um, and for an arc ``slack`` more when its programmed centre is not equidistant from its
        ends; the offset path runs at the radius from its element, at an inside corner the
        intersection of two offsets and at an outside corner the offset of the end; for an arc in
        its plane); for the entry move (``entry``) at most one radius from it. A compensated arc's
        end keeps its programmed height along the plane normal, within half the block's travel
        along it (a helix trimmed at an inside corner ends a little short of its height).
    entry : bool
        The first move under G41/G42 (LinuxCNC's entry move, from the uncompensated point).
    extra : ndarray (6,) or None
        End of the axes a, b, c [deg], u, v, w [mm] in machine positions; checked exactly.
    side, ccw : str or None, bool
        Under G41/G42: the tool's side (``"left"``, ``"right"``) and, for an arc, its direction.
    corner : ndarray (3,) or None
        Under G41/G42 with ``--dialect fanuc``/``haas``: where the block ends at an outside corner by Fanuc's
        cutter compensation C (:func:`fanuc_corner`), checked within ``corner_tolerance`` [mm] instead of
        one radius from ``element``.
    """

    line: int
    kind: str | None
    end: np.ndarray
    tolerance: float = 0.0
    rows: str = "one"
    centre: np.ndarray | None = None
    centre_tolerance: float = 0.0
    plane: tuple[int, int] = (0, 1)
    element: tuple | None = None
    entry: bool = False
    extra: np.ndarray | None = None
    side: str | None = None
    ccw: bool = False
    corner: np.ndarray | None = None
    corner_tolerance: float = 0.0


# ----------------------------------------------------------------------------------------------
# Lines and expressions

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)")
_FUNCS = ("abs", "acos", "asin", "atan", "cos", "exp", "fix", "fup", "round", "ln", "sin", "sqrt", "tan",
          "exists")
_BINOPS = [("**", 4), ("*", 3), ("/", 3), ("mod", 3), ("+", 2), ("-", 2), ("eq", 1), ("ne", 1), ("gt", 1),
           ("ge", 1), ("lt", 1), ("le", 1), ("and", 0), ("or", 0), ("xor", 0)]


def clean_line(raw: str) -> str:
    """The line without comments and spaces, lower case (overview.adoc: spaces and case ignored)."""
    out, depth = [], 0
    for ch in raw:
        if depth == 0 and ch == ";":
            break
        if ch == "(":
            depth += 1
        elif ch == ")" and depth:
            depth -= 1
        elif depth == 0 and not ch.isspace():
            out.append(ch)
    return "".join(out).lower()


class _Eval:
    """Recursive-descent reader of real values on one cleaned line, against the parameters."""

    def __init__(self, text: str, params: _Params):
        self.s = text
        self.i = 0
        self.p = params
        # macro B: the least input increment of the address being read, which its ROUND rounds to (Fanuc 30i
        # "ROUND function" in NC statement addresses; Haas 96-8000 "Round": three places in mm and deg, four in inch)
        self.step: float | None = None

    def peek(self, n: int = 1) -> str:
        return self.s[self.i:self.i + n]

    def expect(self, tok: str) -> None:
        if not self.s.startswith(tok, self.i):
            raise ReferenceError(f"expected {tok!r} at {self.s[self.i:self.i + 20]!r}")
        self.i += len(tok)

    def param_ref(self) -> str | int:
        """After ``#``: the parameter's key (int or name)."""
        self.expect("#")
        if self.peek() == "<":
            j = self.s.index(">", self.i)
            name = self.s[self.i + 1:j]
            self.i = j + 1
            return name
        step, self.step = self.step, None  # the number of a variable is no address value
        key = int(round(_number(self.real())))
        self.step = step
        return key

    def real(self) -> float:
        c = self.peek()
        if c == "[":
            return self.expr()
        if c == "#":
            return self.p.get(self.param_ref())
        if c in "+-":
            self.i += 1
            v = self.real()
            return -v if c == "-" else v
        for f in _FUNCS:
            if self.s.startswith(f, self.i) and self.s[self.i + len(f):self.i + len(f) + 1] == "[":
                self.i += len(f)
                return self.func(f)
        m = _NUMBER.match(self.s, self.i)
        if not m:
            raise ReferenceError(f"no value at {self.s[self.i:self.i + 20]!r}")
        self.i = m.end()
        return float(m.group())

    def func(self, f: str) -> float:
        if f == "exists":
            self.expect("[")
            key = self.param_ref()
            self.expect("]")
            return 1.0 if self.p.exists(key) else 0.0
        a = _number(self.expr())
        if f == "round" and self.step is not None:
            return math.copysign(math.floor(abs(a) / self.step + 0.5), a) * self.step
        if f == "atan":
            self.expect("/")
            b = _number(self.expr())
            return math.degrees(math.atan2(a, b))
        table = {"abs": abs, "acos": lambda v: math.degrees(math.acos(v)),
                 "asin": lambda v: math.degrees(math.asin(v)), "cos": lambda v: math.cos(math.radians(v)),
                 "exp": math.exp, "fix": math.floor, "fup": math.ceil, "round": lambda v: float(math.floor(v + 0.5)),
                 "ln": math.log, "sin": lambda v: math.sin(math.radians(v)), "sqrt": math.sqrt,
                 "tan": lambda v: math.tan(math.radians(v))}
        return float(table[f](a))

    def expr(self) -> float:
        """``[ value op value ... ]`` with LinuxCNC's precedence, left to right within a level."""
        self.expect("[")
        value = self.chain(closed=True)
        self.i += 1
        return value

    def chain(self, *, closed: bool) -> float:
        """``value op value ...`` up to ``]`` (closed) or to the first thing that is no operator
        (a Fanuc macro B assignment ``#1=#2+1``, a condition ``[a]and[b]``)."""
        vals, ops = [self.real()], []
        while self.i < len(self.s) and not (closed and self.peek() == "]"):
            tok, prec = next(((t, p) for t, p in _BINOPS if self.s.startswith(t, self.i)), (None, None))
            if tok is None:
                if not closed:
                    break
                raise ReferenceError(f"bad operator at {self.s[self.i:self.i + 20]!r}")
            self.i += len(tok)
            while ops and ops[-1][1] >= prec:
                _reduce(vals, ops)
            ops.append((tok, prec))
            vals.append(self.real())
        if closed and self.peek() != "]":
            raise ReferenceError("unclosed [")
        while ops:
            _reduce(vals, ops)
        return vals[0]


def _number(v: float) -> float:
    """Fanuc: a vacant value (NaN here) counts 0 in arithmetic and functions."""
    return 0.0 if math.isnan(v) else v


def _reduce(vals: list[float], ops: list) -> None:
    b, a = vals.pop(), vals.pop()
    op = ops.pop()[0]
    if op in ("eq", "ne") and (math.isnan(a) or math.isnan(b)):  # Fanuc: vacant differs from 0 for EQ/NE only
        vals.append(float((math.isnan(a) and math.isnan(b)) == (op == "eq")))
        return
    a, b = _number(a), _number(b)
    res = {"**": lambda: a ** b, "*": lambda: a * b, "/": lambda: a / b, "mod": lambda: math.fmod(a, b) % abs(b)
           if b else math.nan, "+": lambda: a + b, "-": lambda: a - b, "eq": lambda: float(a == b),
           "ne": lambda: float(a != b), "gt": lambda: float(a > b), "ge": lambda: float(a >= b),
           "lt": lambda: float(a < b), "le": lambda: float(a <= b), "and": lambda: float(bool(a) and bool(b)),
           "or": lambda: float(bool(a) or bool(b)), "xor": lambda: float(bool(a) != bool(b))}[op]()
    vals.append(res)


#: Fanuc's clocks #3001/#3002, date #3011 and time #3012, Haas's timers #3020-#3025 (macro B).
_CLOCKS = frozenset((3001, 3002, 3011, 3012, *range(3020, 3026)))


class _Params:
    """Numbered parameters (global), named ``#<_global>`` and ``#<local>`` (per call level)."""

    def __init__(self, *, vacant: bool = False):
        self.numbered: dict[int, float] = {}
        self.globals: dict[str, float] = {}
        self.frames: list[dict] = [{}]
        # Fanuc/Haas macro B: a variable never set is vacant ("null"), as #0; LinuxCNC reads it as 0
        self.unset = math.nan if vacant else 0.0
        # macro B: common variables (#100 up) that hold a clock's reading (Fanuc #3001/#3002, the date and time
        # #3011/#3012, Haas #3020-#3025), which no reading of the text fixes: it may be stored (a cycle-time log) but
        # not used; ``holding`` is set while an assignment's value is read (False: no clock read yet, True: one was)
        self.held: set[int] = set()
        self.holding: bool | None = None
        self.system = None  # Fanuc/Haas: the modal information #4001.. the machine gives (_modal_information)

    def get(self, key: str | int) -> float:
        if key == 0:
            return math.nan  # Fanuc's #0: always vacant
        if self.system is not None and isinstance(key, int) and 4001 <= key <= 4022:
            value = self.system(key)
            if value is not None:
                return value
        if isinstance(key, int) and key not in self.numbered and math.isnan(self.unset) and 5000 <= key < 5400:
            raise ReferenceError(f"system variable #{key} (position, offsets: the machine's state)")
        if isinstance(key, int) and math.isnan(self.unset) and (key in _CLOCKS or key in self.held):
            if self.holding is None:
                raise ReferenceError(f"#{key}: a clock's reading used")
            self.holding = True
            return 0.0
        if isinstance(key, int) and key not in self.numbered and math.isnan(self.unset) and 1000 <= key < 5000:
            raise ReferenceError(f"system variable #{key} (signals, modal information: the control's state)")
        if isinstance(key, int):
            return self.numbered.get(key, self.unset)
        if key.startswith("_"):
            if key not in self.globals:
                raise ReferenceError(f"global #<{key}> read before it is set")
            return self.globals[key]
        if key not in self.frames[-1]:
            raise ReferenceError(f"#<{key}> read before it is set")
        return self.frames[-1][key]

    def exists(self, key: str | int) -> bool:
        if isinstance(key, int):
            return True
        return key in (self.globals if key.startswith("_") else self.frames[-1])

    def set(self, key: str | int, value: float) -> None:
        if key == 0:
            raise ReferenceError("#0 set")
        if isinstance(key, int) and math.isnan(value):
            self.numbered.pop(key, None)  # #1 = #0: vacant again (reads 0 under LinuxCNC's rules)
        elif isinstance(key, int):
            self.numbered[key] = value
        elif key.startswith("_"):
            self.globals[key] = value
        else:
            self.frames[-1][key] = value


@dataclasses.dataclass
class _Line:
    """One cleaned line: O-word statement or words and parameter settings (still unevaluated text)."""

    number: int
    text: str
    oname: str | None = None
    okey: str | None = None
    orest: str = ""
    seq: int | None = None  # N number (a macro B GOTO target)
    macro: tuple[str, str] | None = None  # Fanuc macro B statement: (if|goto|while|do|end, rest)


_FADAL_GONE = re.compile(r"g0*(?:8|9|50|51\.2|84\.2|74\.2)(?![\d.])")
_FADAL_CYCLE = re.compile(r"g0*(?:73|74|76|8[1-9])(?:\.1)?(?![\d])")
_FADAL_MOTION = re.compile(r"g0*([0-3]|7[346]|8\d)(?![\d.])")


def _fadal_text(text: str) -> str:
    """A Fadal line's words as Fanuc reads them (see the module docstring): codes that move nothing gone,
    rigid tapping as G84/G74, ``R0+v`` as ``R+v``, H without G43 as G43 / G49."""
    text = re.sub(r"r0(?=[-+])", "r", text)
    if re.search(r"g0*51(?![\d.])", text):
        text = re.sub(r"r[-+]?[\d.]+", "", re.sub(r"g0*51(?![\d.])", "", text))
    text = _FADAL_GONE.sub("", text)
    if re.search(r"g0*10(?![\d.])", text) and re.search(r"l0*12(?![\d.])", text):  # L12 R0: a diameter
        text = re.sub(r"r([-+]?[\d.]+)", lambda m: f"r{float(m.group(1)) / 2:.6f}", text)
    text = re.sub(r"(g0*[78]4)\.1", r"\1", text)
    h = re.search(r"h([\d.]+)", text)
    if h and not re.search(r"g0*4[1-9](?![\d.])", text):
        text += "g49" if float(h.group(1)) == 0 else "g43"
    elif h and re.search(r"g0*4[12](?![\d.])", text) and "d" not in text:
        text = text.replace("h", "d", 1)
    return text


def _fadal_lines(lines: list[_Line]) -> list[_Line]:
    """The lines of a Fadal program in the order they run: subroutines (``L<nn>00`` .. ``M17`` before the
    ``M30``) taken out and run where ``L<nn><rr>`` calls them, arcs with ``L`` repeated."""
    subs: dict[int, list[_Line]] = {}
    out: list[_Line] = []
    i, current = 0, None
    first = next((k for k, ln in enumerate(lines) if re.fullmatch(r"l\d+", ln.text) and int(ln.text[1:]) % 100 == 0),
                 None)
    if first is not None:
        out, i = lines[:first], first
        while i < len(lines) and not (current is None and re.search(r"m0*30(?!\d)", lines[i].text)):
            ln = lines[i]
            if re.fullmatch(r"l\d+", ln.text) and int(ln.text[1:]) % 100 == 0:
                current = int(ln.text[1:]) // 100
                subs[current] = []
            elif current is not None:
                text = re.sub(r"m0*17(?!\d)", "", ln.text)
                if text:
                    subs[current].append(dataclasses.replace(ln, text=text))
                if text != ln.text:
                    current = None
            i += 1
        i += 1
    state = {"motion": 0}
    for ln in out + lines[i:] if first is not None else lines:
        _fadal_run(ln, subs, state, 0)
    return state.get("out", [])


def _fadal_run(ln: _Line, subs: dict, state: dict, depth: int) -> None:
    """Append line ``ln`` (or the subroutine it calls) to ``state["out"]`` as it runs."""
    if depth > 10:
        raise ReferenceError("Fadal subroutines nested too deep")
    out = state.setdefault("out", [])
    text = ln.text
    call = re.fullmatch(r"l(\d+)", text)
    if call and int(call.group(1)) % 100:
        v = int(call.group(1))
        for _ in range(v % 100):
            for sub in subs[v // 100]:
                _fadal_run(sub, subs, state, depth + 1)
        return
    text = _fadal_text(text)
    codes = [int(c) for c in _FADAL_MOTION.findall(text)]
    motion = codes[-1] if codes else state["motion"]
    if not codes and motion in (2, 3) and re.search(r"[xyz]", text) and not re.search(r"[ijkr]", text):
        text, motion = "g1" + text, 1
    state["motion"] = 80 if re.search(r"g0*80(?!\d)", text) else motion
    count = 1
    lw = re.search(r"l([\d.]+)", text)
    if lw and not _FADAL_CYCLE.search(text) and not re.search(r"g0*(?:10|65)(?![\d.])|m0*9[78](?!\d)", text):
        if motion not in (2, 3):
            raise ReferenceError(f"Fadal L word outside a call, an arc or a cycle: {ln.text}")
        count, text = int(float(lw.group(1))), text[:lw.start()] + text[lw.end():]
    out.extend([dataclasses.replace(ln, text=text)] * count)


_OWORD = re.compile(r"o(<[^>]*>|\d+)(sub|endsub|call|return|if|elseif|else|endif|while|endwhile|do|repeat|"
                    r"endrepeat|break|continue)?(.*)$")


def _split(text: str) -> list[str]:
    """The lines as an editor numbers them: CR LF and LF end a line; a bare CR does so only in a text
    without LF (in a LF text a stray CR stays inside its line)."""
    if "\n" not in text:
        return text.split("\r")
    return [ln[:-1] if ln.endswith("\r") else ln for ln in text.split("\n")]


#: Fanuc's abbreviated function names (custom macro, "Abbreviations of macro statements": a word's first two
#: characters stand for it, "ROUND -> RO, FIX -> FI").
_SHORT_FUNCTIONS = {"ab": "abs", "ac": "acos", "as": "asin", "at": "atan", "bc": "bcd", "bi": "bin", "co": "cos",
                    "fi": "fix", "fu": "fup", "ro": "round", "si": "sin", "sq": "sqrt", "ta": "tan"}


def _unabbreviated(s: str) -> str:
    """A cleaned Fanuc line with its abbreviated macro words written out: WH[..]DO, EN m, GO n (a target alone
    after it), IF[..]GO / TH, and the functions."""
    s = re.sub(r"^wh(?=\[)", "while", s)
    s = re.sub(r"^en(?=\d$)", "end", s)
    s = re.sub(r"^go(?=(?:\d+|#\d+|\[.*\])$)", "goto", s)
    s = re.sub(r"^(if\[.*\])(go(?!to)|th(?!en))", lambda m: m.group(1) + ("goto" if m.group(2) == "go" else "then"), s)
    return re.sub(r"(?<![a-z])(" + "|".join(_SHORT_FUNCTIONS) + r")(?=\[)", lambda m: _SHORT_FUNCTIONS[m.group(1)], s)


def _unskipped(s: str, *, fanuc: bool) -> str:
    """A cleaned line without its leading '/': block delete, switch off; Fanuc's optional block skip levels
    '/1'-'/9' (the additional optional block skip option) alike, '/1' the same as '/'."""
    if not s.startswith("/"):
        return s
    return s[2:] if fanuc and re.match(r"/[1-9]", s) else s[1:]


def _lines(text: str, *, grbl: bool = False, fanuc: bool = False, linuxcnc: bool = False) -> list[_Line]:
    out = []
    for no, raw in enumerate(_split(text), start=1):
        s = clean_line(raw)
        if grbl:  # grbl: '$' lines are system commands (system.c), '?' '~' real-time status query and cycle
            # start (serial.c);
            # '$H' the homing cycle (commands.md), run below
            s = s if s == "$h" else "" if s.startswith("$") else s.replace("?", "").replace("~", "")
            # '%' lines: the sender's (CNCjs macro lines such as %wait, and tape markers, which end nothing: grbl
            # reads no '%' and the sender streams the whole file)
            s = "" if s.startswith("%") else s
        elif re.match(r"\$[a-z]{4}|#(end)?region", s):
            # CNCSimulator Pro's simulation commands ($AddRegPart, $Inches, ...) and #region marks (its user
            # guide, 6.3 "$-commands and regions"): no G-code of any control; the simulator alone reads them
            s = ""
        s = _unskipped(s, fanuc=fanuc)
        n = re.match(r"^n(\d+)(\.\d*)?", s)
        s = s[n.end():] if n else s
        if n:  # a '/' after the sequence number: as at the line's start (Fanuc/Haas/grbl; LinuxCNC refuses it)
            s = _unskipped(s, fanuc=fanuc)
        s = _unabbreviated(s) if fanuc else s
        seq = int(n.group(1)) if n else None
        if linuxcnc and s.startswith(":"):  # rs274ngc reads no ':' (rs274: "Bad character ':' used")
            raise ReferenceError(f"line {no}: ':' refused under LinuxCNC")
        if re.match(r":\d", s):  # ISO code's program-number address ':' (O of EIA code): ":0097" is O0097
            s = "o" + s[1:]
        m = _OWORD.match(s)
        mac = _MACRO.match(s)
        if m is None and re.fullmatch(r"o[a-z]\w*", s):
            out.append(_Line(no, "", seq=seq))  # "OWASHER", "OPIS": a program's name, not a block
        elif m:
            out.append(_Line(no, s, m.group(1).strip("<>"), m.group(2), m.group(3), seq=seq))
        elif mac:
            kind = next(k for k in ("if", "goto", "while", "do", "end", "dprnt", "bprnt", "popen", "pclos")
                        if s.startswith(k))
            out.append(_Line(no, s, seq=seq, macro=(kind, s[len(kind):])))
        else:
            out.append(_Line(no, s, seq=seq))
    return out


#: Fanuc custom macro B statements (Fanuc 0i-MD B-64304EN "Branch and repetition"), on a cleaned line.
#: Also the external output commands, which send text and move nothing (B-64304EN "External output
#: commands"; Haas "Formatted Output": DPRNT must be the only command in the block).
_MACRO = re.compile(r"^(if\[|goto|while\[.*\]do\d$|do\d$|end\d$|[db]prnt\[.*\]$|popen$|pclos$)")


#: Macro B least input increments of the addresses (IS-B), for ROUND in an address: distances [mm, in], angles [deg].
_LENGTH_ADDRESSES, _ANGLE_ADDRESSES = "xyzuvwijkqr", "abc"


def _words(line: str, params: _Params, *, inch: bool = False) -> tuple[dict[str, list[float]], list[tuple]]:
    """Words (letter -> values in order) and parameter settings of a line, values evaluated (``inch``: G20 in force,
    the increment a macro B ROUND in a length address rounds to)."""
    ev = _Eval(line, params)
    macro_b = math.isnan(params.unset)
    computed: list[tuple[str, int, float]] = []  # computed address values to round: letter, index, increment
    words: dict[str, list[float]] = {}
    sets = []
    while ev.i < len(ev.s):
        c = ev.peek()
        if c == "#":
            key = ev.param_ref()
            ev.expect("=")
            common = isinstance(key, int) and key >= 100 and math.isnan(params.unset)
            params.holding = False if common else None
            sets.append((key, ev.chain(closed=False)))
            if common:
                (params.held.add if params.holding else params.held.discard)(key)
            params.holding = None
        elif c in "@^$" or c.isalpha():
            ev.i += 1
            if macro_b and c in _LENGTH_ADDRESSES + _ANGLE_ADDRESSES:
                ev.step = 0.001 if c in _ANGLE_ADDRESSES or not inch else 0.0001
            start = ev.i
            value = ev.real()
            if macro_b and not math.isnan(value) and not _NUMBER.fullmatch(ev.s[start:ev.i]):
                # Fanuc/Haas round a variable or expression in an address to the address's least significant digit
                # (haascnc.com "Address substitution": "#1=.123456, then G01 X#1 would move ... to .1235"; Haas
                # 96-8000 "Round": "D[1.67] (Diameter 2 is made current)"); kept for the blocks named below
                step = 1.0 if c in "dhmt" else ev.step
                if step is not None:
                    computed.append((c, len(words.get(c, [])), step))
            ev.step = None
            if not math.isnan(value):  # Fanuc: a word whose value is vacant is left out
                words.setdefault(c, []).append(value)
        elif c == "%":
            ev.i += 1
        elif c == "," and ev.peek(2)[1:] in ("r", "c"):  # Fanuc/Haas corner words: see _corner
            ev.i += 2
            words.setdefault("," + ev.s[ev.i - 1], []).append(ev.real())
        else:
            raise ReferenceError(f"unexpected {ev.s[ev.i:ev.i + 20]!r}")
    codes = {round(v * 10) for v in words.get("g", [])}
    if not codes & {510, 50, 51, 80, 434, 435, 62, 650, 660, 661}:  # scaling factors, vectors, knots, calls keep theirs
        for c, i, step in computed:
            if c in _ANGLE_ADDRESSES or c == "r" and 680 in codes:  # G68's R is an angle too [deg]
                step = 0.001
            elif step == 0.0001 and 210 in codes:  # G21 in the block: the mm increment
                step = 0.001
            elif step == 0.001 and 200 in codes:
                step = 0.0001
            v = words[c][i]
            words[c][i] = math.copysign(math.floor(abs(v) / step + 0.5), v) * step
    return words, sets


# ----------------------------------------------------------------------------------------------
# O-word structure

def _structure(lines: list[_Line]) -> dict:
    """Matching ends of the O-word blocks: sub, if/elseif/else, while, do/while, repeat."""
    subs, ends, branches, owner, fanuc = {}, {}, {}, {}, {}
    stack: list[tuple[str, str, int]] = []
    loops_open: list[int] = []
    program_of: dict[int, int] = {}
    program_start = 0
    for i, ln in enumerate(lines):
        k, name = ln.okey, ln.oname
        if ln.macro is not None and ln.macro[0] in ("while", "do", "end"):
            if ln.macro[0] == "end":
                j = loops_open.pop()  # END m closes the innermost DO
                ends[j], ends[i] = i, j
            else:
                loops_open.append(i)
        if name is not None and k is None:
            program_start = i  # an O number starts a program: GOTO searches within it
        program_of[i] = program_start
        if name is None:
            continue
        if k is None:  # O01000 is program 1000 (Fanuc program numbers: M98 P1000 calls it)
            fanuc[str(int(name)) if name.isdigit() else name] = i
        elif k in ("sub", "if", "repeat") or (k == "while" and not (stack and stack[-1][:2] == (name, "do"))) \
                or k == "do":
            stack.append((name, k, i))
            if k == "if":
                branches[i] = []
        elif k == "while":  # closes a do
            _, _, j = stack.pop()
            ends[j] = i
        elif k in ("endsub", "endif", "endwhile", "endrepeat"):
            while stack and stack[-1][0] != name:
                stack.pop()
            if not stack:  # its block was closed already ("endsub" inside an "if" ends the sub there)
                continue
            _, opener, j = stack.pop()
            ends[j] = i
            if opener == "sub":
                subs[name] = j
            if opener == "if":
                for b in branches[j]:
                    ends[b] = i
        elif k in ("elseif", "else"):
            j = next(s[2] for s in reversed(stack) if s[0] == name and s[1] == "if")
            branches[j].append(i)
        elif k in ("break", "continue"):
            owner[i] = next(s[2] for s in reversed(stack) if s[0] == name and s[1] in ("while", "do", "repeat"))
    return {"subs": subs, "ends": ends, "branches": branches, "owner": owner, "fanuc": fanuc, "lines": lines,
            "program_of": program_of}


# ----------------------------------------------------------------------------------------------
# The machine

# G74 / G84 / G86 (g-code.adoc "G74 Left-hand Tapping Cycle with Dwell", "G84 Right-hand Tapping Cycle,
# Dwell", "G86 Boring Cycle, Spindle Stop, Rapid Move Out"; Fanuc 0i-MF and Haas "G84 Tapping Canned
# Cycle": out at feed to R, then rapid to the clear level)
_CYCLES = (73, 74, 81, 82, 83, 84, 85, 86, 89)
_MILL_CYCLES = (76, 87)
#: The axes beyond X, Y, Z, in the order of :attr:`Expected.extra`; U, V, W scale with G20.
_EXTRA = "abcuvw"

_WCS = {540: "G54", 550: "G55", 560: "G56", 570: "G57", 580: "G58", 590: "G59", 591: "G59.1", 592: "G59.2",
        593: "G59.3"}


class _Machine:
    """Modal state of the control; positions in machine coordinates [mm]."""

    def __init__(self, context):
        self.ctx = context
        self.pos = np.array(context.home, float)
        self.scale = 25.4 if context.dialect.default_units == "inch" else 1.0
        self.incremental = False
        # G00 at power-on under grbl (gc_init zeroes the parser state: MOTION_MODE_SEEK), Fanuc (parameter
        # 3402#0 = 0) and Haas (group 01 default); LinuxCNC starts in G80: axis words alone are an error
        self.motion: int | None = 0 if context.dialect.name in ("grbl", "fanuc", "haas") else None
        self.linear: int | None = self.motion
        self.plane = 17
        self.wcs = "G54"
        self.fadal = False  # read E words as Fadal fixture offsets
        self.offsets = {code: np.array(context.offset(code), float) for code in _WCS.values()}
        self.rotation = dict.fromkeys(_WCS.values(), 0.0)
        self.g92 = np.zeros(3)
        # G28 / G30 reference positions [machine mm]; G28.1 / G30.1 store the current position (g-code.adoc
        # "G28, G28.1": "G28.1 - stores the current absolute position into parameters 5161-5166")
        self.home = {280: np.array(context.home, float), 300: np.array(context.reference2, float)}
        self.saved_states: dict[int, tuple[dict, bool]] = {}  # LinuxCNC M70/M73 per call level: state, autorestore
        self.level = 0  # the O-word call level (0: the main program)
        self.parameter_input = False  # Fanuc G10 L50 .. G11
        self.nurbs_end: np.ndarray | None = None  # LinuxCNC G5.2: the last control point [machine mm]
        self.intermediate = np.full(3, np.nan)  # the last G28/G30 intermediate point [program mm]: Fanuc G29's
        self.extra = np.zeros(6)  # a, b, c [deg], u, v, w [mm], machine positions
        self.extra_offsets = {code: np.zeros(6) for code in _WCS.values()}
        self.g92_extra = np.zeros(6)
        self.local = np.zeros(3)  # Fanuc/Haas G52 (a part of g92)
        self.external = np.zeros(3)  # Fanuc/Haas G10 L2 P0 (a part of g92)
        self.external_extra = np.zeros(6)  # its A-W part (a part of g92_extra)
        self.tool_lengths: dict[int, tuple[float, float]] = {}  # Fanuc/Haas G10 L10/L11: (geometry, wear) [mm]
        self.tool_radii: dict[int, tuple[float, float]] = {}  # G10 L12/L13
        self.tool_length = 0.0
        # Fanuc (parameter TOS = 0), Haas, Fadal: the change of the length offset is an axis movement, added to
        # the next incremental Z travel (B-63943EN-1/02 12.5.2 "Tool Length Compensation Shift Types" tells the
        # other way, TOS = 1: "If no move command is specified together with the G43, G44, or G49 command, the
        # tool will not move along the axis"); LinuxCNC and grbl shift the coordinates (g-code.adoc "G43")
        self.length_moves = self.ctx.dialect.length_offset_motion  # a machine setting (TOS), default per dialect
        self.length_change = 0.0  # [mm] not yet travelled
        self.length_mode = 490  # the group 08 code in force (x10)
        self.tool_xy = np.zeros(2)  # the tool's X Y offsets (LinuxCNC tool table X Y; G43 applies them)
        self.tcp = False  # Fanuc G43.4 / Haas G234 tool centre point control on the machine's tilting table
        self.tcp_vector = False  # Fanuc G43.5: the tool direction I J K instead of rotary words
        self.tilted: np.ndarray | None = None  # Fanuc G68.2's plane (columns: its X, Y, Z in the work system)
        self.selected = self.loaded = 0
        self.offsets_of: dict[int, int] = {}  # Fagor T<tool>.<offset>
        self.spindle = 0.0  # S [rev/min] (Fanuc rigid tapping: _rigid_tap)
        self.rigid = False  # Fanuc M29 until its tapping cycle ends
        self.rigid_at: int | None = None  # the line of that M29 until a G84/G74 runs
        self.rigid_s = 0.0  # the S of the rigid tap that ran
        self.dwo_on = False  # Haas G254 dynamic work offset (_dwo)
        self.arc3d: tuple[np.ndarray, int] | None = None  # Fanuc G02.4's intermediate point [mm] and line (_arc3d)
        self.dwo = np.zeros(3)  # its shift of the work zero [mm]
        self.comp_radius: float | None = None
        self.comp_entry = False
        self.comp_side = "left"
        self.g39 = False  # Fanuc/Haas G39 came: the next corner is an arc about it (no corner point)
        self.comp_closed = 0.0  # the radius of a run G40 closed, until the next move (its exit move)
        self.reread = 0.0  # LinuxCNC M6/M61 after such a G40: the next move starts at the offset point
        self.arc_absolute = False
        self.retract = 99 if context.dialect.name == "linuxcnc" else 98  # LinuxCNC interp_setup.cc: R_PLANE
        self.cycle_clear: float | None = None
        self.sticky: dict[str, float] = {}
        self.g68: tuple[tuple[int, int], np.ndarray, float] | None = None  # plane axes, centre, angle [deg]
        self.mirror, self.mirror_at = np.zeros(3, bool), np.zeros(3)  # G51.1
        self.factors, self.scale_centre = np.ones(3), np.zeros(3)  # G51
        self.polar16 = False  # Fanuc G16 polar coordinate command
        self.corner: tuple[str, float, np.ndarray] | None = None  # a ,R / ,C: word, size [mm], its block's start
        self.modal_call: dict | None = None  # Fanuc G66: the program and its arguments (_g66_call)
        self.block_moves = self.block_nonmodal = False  # the last block's axis words: a move / a G28, G92 .. block
        self.out: list[Expected] = []

    def tool(self, number: int):
        """The context's tool ``number``, with the lengths and radii Fanuc/Haas G10 L10-L13 set (geometry +
        wear); none for number 0, whose offset is always 0 (Fanuc: "the offset amount corresponding to H00
        always means 0"; LinuxCNC G43: "It is OK for the H number to be zero; an offset value of zero will
        be used")."""
        if number == 0:
            return None
        tool = self.ctx.tool(number)
        if number not in self.tool_lengths and number not in self.tool_radii:
            return tool
        tool = tool or _Tool()
        length = sum(self.tool_lengths.get(number, (tool.length, 0.0)))
        radius = sum(self.tool_radii.get(number, (tool.radius, 0.0)))
        return dataclasses.replace(tool, length=length, radius=radius)

    def _g68_turn(self, v: np.ndarray, sign: float) -> np.ndarray:
        if self.g68 is None:
            return v
        (a, b), c, angle = self.g68
        t = math.radians(sign * angle)
        out = v.copy()
        out[a] = c[a] + math.cos(t) * (v[a] - c[a]) - math.sin(t) * (v[b] - c[b])
        out[b] = c[b] + math.sin(t) * (v[a] - c[a]) + math.cos(t) * (v[b] - c[b])
        return out

    # coordinates ------------------------------------------------------------------------------
    def _rot(self, v: np.ndarray, sign: float) -> np.ndarray:
        a = math.radians(sign * self.rotation[self.wcs])
        c, s = math.cos(a), math.sin(a)
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])

    def to_machine(self, prog: np.ndarray) -> np.ndarray:
        """Machine position of a program point: rotation(program + G92) + work offset (+ Haas G254's shift of it,
        :func:`_dwo`) + tool length."""
        p = np.where(self.mirror, 2 * self.mirror_at - prog, np.asarray(prog, float))
        p = self.scale_centre + self.factors * (p - self.scale_centre)
        m = self._rot(self._g68_turn(p, 1.0) + self.g92, 1.0) + self.offsets[self.wcs] + self.dwo
        m[2] += self.tool_length
        m[:2] += self.tool_xy
        return m

    def to_program(self, machine: np.ndarray) -> np.ndarray:
        v = machine - self.offsets[self.wcs] - self.dwo
        v[2] -= self.tool_length
        v[:2] -= self.tool_xy
        p = self._g68_turn(self._rot(v, -1.0) - self.g92, -1.0)
        p = self.scale_centre + (p - self.scale_centre) / self.factors
        return np.where(self.mirror, 2 * self.mirror_at - p, p)

    def target(self, words: dict, *, incremental: bool | None = None, untravelled: float = 0.0) -> np.ndarray:
        """Program coordinates of the block's end from X/Y/Z (and polar) words; ``untravelled``: a tool length change
        [mm] the tool has not moved along the machine Z, the unnamed words read under the offset it travelled."""
        inc = self.incremental if incremental is None else incremental
        cur = self.to_program(self.pos + np.array([0.0, 0.0, untravelled]))
        t = cur.copy()
        for i, a in enumerate("xyz"):
            if a in words:
                v = words[a][-1] * self.scale
                t[i] = cur[i] + v if inc else v
        if "@" in words or "^" in words:
            r, ang = math.hypot(cur[0], cur[1]), math.degrees(math.atan2(cur[1], cur[0]))
            if inc:
                r += words.get("@", [0.0])[-1] * self.scale
                ang += words.get("^", [0.0])[-1]
            else:
                r = words["@"][-1] * self.scale if "@" in words else r
                ang = words["^"][-1] if "^" in words else ang
            t[0], t[1] = r * math.cos(math.radians(ang)), r * math.sin(math.radians(ang))
        return t

    def extra_words(self, words: dict) -> dict[int, float]:
        """The A-W words of a block by axis index [deg, mm]."""
        return {i: words[a][-1] * (1.0 if a in "abc" else self.scale) for i, a in enumerate(_EXTRA) if a in words}

    def extra_end(self, words: dict, *, machine: bool = False) -> np.ndarray:
        """Machine positions of a, b, c, u, v, w after a block with these words."""
        end = self.extra.copy()
        for i, v in self.extra_words(words).items():
            if machine:
                end[i] = v
            elif self.incremental:
                end[i] += v
            else:
                end[i] = v + self.extra_offsets[self.wcs][i] + self.g92_extra[i]
            if i < 3 and "abc"[i] in self.ctx.wrapped_axes and (machine or not self.incremental):
                end[i] = self.wrapped(v, self.extra[i], end[i] - v)
        return end

    def wrap_rule(self) -> str:
        """The direction rule of the machine's wrapping rotary axes: its ``wrap_direction``, else the control's
        (LinuxCNC INI docs, WRAPPED_ROTARY: the sign; Fanuc B-63534EN/02 20.2.1, RAB = 0 by default: the shorter)."""
        return self.ctx.wrap_direction or ("sign" if self.ctx.dialect.name == "linuxcnc" else "shortest")

    def wrapped(self, word: float, now: float, offset: float) -> float:
        """:func:`wrapped_end` by this machine's rule."""
        return wrapped_end(self.wrap_rule(), word, now, offset)

    def emit(self, line: int, kind: str | None, end: np.ndarray, *, rows: str = "one",
             centre: np.ndarray | None = None, centre_tolerance: float = 0.0) -> None:
        plane = {17: (0, 1), 18: (2, 0), 19: (1, 2)}[self.plane]
        if self.comp_radius and kind != "dwell":
            if centre is None:
                element = ("line", self.pos.copy(), end.copy())
            else:
                # an arc whose programmed centre is not equidistant from its ends (rounded CAM output): a
                # reader may offset the arc about its own centre on the ends' bisector, which lies up to
                # the centre's allowance away, and the radii differ by |rs - re|
                rs = float(np.hypot(*(self.pos - centre)[list(plane)]))
                re_ = float(np.hypot(*(end - centre)[list(plane)]))
                slack = max(centre_tolerance - 1e-6, 0.0) + abs(rs - re_)
                element = ("arc", centre, re_, plane, self.pos.copy(), slack)
            # one plane axis mirrored (Fanuc 0i-MF "Programmable mirror image": "the offset direction is reversed";
            # Haas "G101"): the tool keeps its side of the programmed contour, the other side of the machine's
            signs = np.where(self.mirror, -1.0, 1.0) * self.factors
            side = self.comp_side if signs[plane[0]] * signs[plane[1]] > 0 else \
                {"left": "right", "right": "left"}[self.comp_side]
            self.out.append(Expected(line=line, kind=None, end=end.copy(), tolerance=self.comp_radius, rows="last",
                                     element=element, entry=self.comp_entry, extra=self.extra.copy(),
                                     side=side, ccw=kind == "arc_ccw"))
            self.comp_entry = False
            if self.ctx.dialect.name in ("fanuc", "haas") and not self.g39:
                fanuc_corner(self.out, self.comp_radius)
            if np.any((end - self.pos)[list(plane)]) or centre is not None:
                self.g39 = False  # G39's arc is LinuxCNC's corner arc: the block before ends one radius off
        else:
            # after G40 and an M6/M61 (LinuxCNC), a move that names no X Y stays at the run's last offset
            # point, one radius from the programmed one (rs274ngc_pre.cc read_inputs: refresh_actual_position)
            self.out.append(Expected(line=line, kind=kind, end=end.copy(), rows=rows, centre=centre, plane=plane,
                                     centre_tolerance=centre_tolerance, extra=self.extra.copy(),
                                     tolerance=self.reread))
        self.pos = end.copy()
        self.comp_closed = self.reread = 0.0

    def move(self, line: int, kind: str, prog: np.ndarray, *, optional: bool = False, extra=None) -> None:
        """A move to the program point ``prog`` (and the extra axes to ``extra``, machine positions)."""
        end = self.to_machine(prog)
        still = extra is None or np.allclose(extra, self.extra, atol=1e-12)
        rows = "optional" if optional and still and np.allclose(end, self.pos, atol=1e-12) else "one"
        if extra is not None:
            self.extra = np.array(extra, float)
        self.emit(line, kind, end, rows=rows)


def _table(m: _Machine, point: np.ndarray, extra: np.ndarray, *, back: bool = False) -> np.ndarray:
    """Where the machine's tilting table at the rotary positions ``extra`` carries the part point that is at
    ``point`` with every rotary axis at 0 (``back``: the reverse). Each axis turns the part by minus its angle
    about its direction (ISO 841: a table axis turns the other way) round its pivot; the outer axis carries the
    inner one, so the inner turn comes first."""
    axes = list(m.ctx.kinematics.axes)
    steps = []
    for ax in reversed(axes):  # inner first
        angle = -math.radians(extra["abc".index(ax.name)]) * (-1.0 if ax.direction.startswith("-") else 1.0)
        c, s = math.cos(angle), math.sin(angle)
        k = "XYZ".index(ax.direction[-1])
        i, j = (k + 1) % 3, (k + 2) % 3
        rot = np.eye(3)
        rot[i, i], rot[i, j], rot[j, i], rot[j, j] = c, -s, s, c
        steps.append((rot, np.asarray(ax.pivot, float)))
    q = np.asarray(point, float)
    for rot, pivot in (reversed(steps) if back else steps):
        q = pivot + (rot.T if back else rot) @ (q - pivot)
    return q


def _angle_pairs(m: _Machine, tool: np.ndarray) -> list[tuple[float, float]]:
    """The (outer, inner) angles [deg] of an A/C or B/C table (or one A or B axis, inner 0) that make ``tool`` (part
    coordinates) the spindle's axis; the tool's direction in the part at angles (o, i): Rz(C) Rx(A) e_z = (sin C sin A,
    -cos C sin A, cos A), Rz(C) Ry(B) e_z = (cos C sin B, sin C sin B, cos B); one axis: (0, -sin A, cos A),
    (sin B, 0, cos B). A tool along C leaves C where it is."""
    axes = m.ctx.kinematics.axes
    n = tool / np.linalg.norm(tool)
    if any(ax.direction not in ("X", "Y", "Z") for ax in axes) or axes[0].direction == "Z" or (
            len(axes) == 2 and axes[1].direction != "Z"):
        raise ReferenceError("kinematics other than an A/C or B/C table")
    x = axes[0].direction == "X"
    if len(axes) == 1:
        return [(math.degrees(math.atan2(-n[1], n[2]) if x else math.atan2(n[0], n[2])), 0.0)]
    tilt = math.degrees(math.atan2(math.hypot(n[0], n[1]), n[2]))  # (acos(n_z) loses a tilt of 1e-6 rad)
    pairs = []
    for o in (tilt, -tilt):
        so = math.sin(math.radians(o))
        i = m.extra["abc".index(axes[1].name)] if abs(so) < 1e-9 else math.degrees(
            math.atan2(n[0] / so, -n[1] / so) if x else math.atan2(n[1] / so, n[0] / so))
        pairs.append((o, i))
    return pairs


def _tool_angles(m: _Machine, tool: np.ndarray) -> np.ndarray:
    """The rotary positions of an A/C or B/C table (or one A or B axis) that make ``tool`` (part coordinates) the
    spindle's axis, nearest the present ones within the limits (:func:`_angle_pairs`)."""
    axes = m.ctx.kinematics.axes
    pairs = _angle_pairs(m, tool)
    now = [m.extra["abc".index(ax.name)] for ax in axes]
    found = []
    for pair in pairs:
        fit = []
        for ax, v in zip(axes, pair, strict=False):
            now_ax = m.extra["abc".index(ax.name)]  # the turn of 360 deg nearest the axis' position (Fanuc 15i)
            inside = sorted(turns_within(ax.limits, v), key=lambda c: abs(c - now_ax))
            if ax.name in m.ctx.wrapped_axes and inside:  # a wrapping axis: the shorter way from wherever it is
                inside = [wrapped_end("shortest", v, now_ax, 0.0)]  # (its limits hold modulo 360 deg)
            fit.append(inside[0] if inside else None)
        if None not in fit:
            found.append((sum(abs(f - c) for f, c in zip(fit, now, strict=True)), -fit[0], fit))
    if not found:
        raise ReferenceError("a tool direction the rotary axes do not reach")
    least = min(f[0] for f in found)  # travels equal within 1e-6 deg tie: the positive master angle
    best = min((f for f in found if f[0] <= least + 1e-6), key=lambda f: f[1])
    out = m.extra.copy()
    for ax, v in zip(axes, best[2], strict=True):
        out["abc".index(ax.name)] = v
    return out


def turns_within(limits: tuple[float, float], angle: float) -> list[float]:
    """Every turn of 360 deg of ``angle`` [deg] within ``limits`` (within 1e-6 deg), counted from the lowest."""
    k = math.ceil((limits[0] - 1e-6 - angle) / 360.0)
    out = []
    while angle + 360.0 * k <= limits[1] + 1e-6:
        out.append(angle + 360.0 * k)
        k += 1
    return out


def _tilted_plane(m: _Machine, line: int, g: list[int], words: dict) -> None:
    """Fanuc G68.2 (P0: the Euler angles I, J, K about Z, the turned X, the new Z) and G53.1 (30i B-63942EN/02 5.44
    "Tilted working plane command"): G53.1 turns the rotary axes at rapid to the output angles of FANUC's tool axis
    direction control (16i/18i-MB operator's manual, "Angle of rotation axis"): of the computed angles (every turn
    of 360 deg of both solutions, within the limits) the pair whose master (outer) axis moves least, then the
    slave, then the master angle nearest a multiple of 360 deg, then the slave's; a wrapping axis at the angle it
    shows, reached as a machine word by the machine's rule (its move what it turns). Motion in the tilted plane is
    not modelled (ReferenceError); G69 ends it."""
    if 690 in g:
        m.tilted = None
    if 682 in g:
        if set(words) - set("xyzijkng") or m.ctx.kinematics is None:
            raise ReferenceError("G68.2 other than X Y Z I J K (P0) or without kinematics")
        i, j, k = (words.pop(a, [0.0])[-1] for a in "ijk")
        for a in "xyz":
            words.pop(a, None)
        m.tilted = _euler(i, j, k)
        g.remove(682)
    if 531 in g and m.tilted is not None:
        m.extra = _output_angles(m, _angle_pairs(m, m.tilted[:, 2]))
        m.emit(line, "rapid", m.pos.copy(), rows="optional")
        g.remove(531)
    if m.tilted is not None and any(a in words for a in "xyz"):
        raise ReferenceError("motion in a G68.2 tilted plane")


def _euler(i: float, j: float, k: float) -> np.ndarray:
    """The plane of G68.2's Euler angles [deg]: turned about Z by I, then about the turned X by J, then about the new
    Z by K (columns: the plane's X, Y, Z in the work system)."""
    def rz(a: float) -> np.ndarray:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    c, s = math.cos(math.radians(j)), math.sin(math.radians(j))
    return rz(i) @ np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]) @ rz(k)


def _output_angles(m: _Machine, pairs: list[tuple[float, float]]) -> np.ndarray:
    """The rotary positions G53.1 turns the axes to (:func:`_tilted_plane`)."""
    axes = m.ctx.kinematics.axes
    ranked = []
    for pair in pairs:
        options = []
        for ax, v in zip(axes, pair, strict=False):
            now = m.extra["abc".index(ax.name)]
            inside = turns_within(ax.limits, v)
            if ax.name in m.ctx.wrapped_axes:
                shown = v % 360.0 if abs(math.remainder(v, 360.0)) > 1e-9 else 0.0
                options.append([(m.wrapped(shown, now, 0.0), shown)] if inside else [])
            else:
                options.append([(c, c) for c in inside])
        for combo in itertools.product(*options):
            moves = [round(abs(end - m.extra["abc".index(ax.name)]) * 1e6) for ax, (end, _) in zip(axes, combo)]
            zero = [round(abs(math.remainder(c, 360.0)) * 1e6) for _, c in combo]
            master = pair[0] if axes[0].name in m.ctx.wrapped_axes else combo[0][1]
            ranked.append(((*moves, *zero, -master), [end for end, _ in combo]))
    if not ranked:
        raise ReferenceError("a tilted plane the rotary axes do not reach")
    out = m.extra.copy()
    for ax, end in zip(axes, min(ranked)[1], strict=False):
        out["abc".index(ax.name)] = end
    return out


def _tcp_move(m: _Machine, line: int, words: dict) -> None:
    """G0 / G1 under G43.4 / G234 (Fanuc 30i "Tool center point control for 5-axis machining" A-79348E 1.1: X Y Z
    the tool tip in the workpiece system fixed on the table; Haas "G234 TCPC"): the programmed point where the
    table at the block's rotary positions carries it; a block whose rotary axes turn is the reader's chords,
    the last one's end checked. A length change the axes have not travelled (Fanuc TOS = 0: ``G43.4 H2`` after ``G43
    H1 Z5.``, a new H in G43.4 mode) leaves the programmed tip where it was, the block travelling it (our reading)."""
    length = np.array([0.0, 0.0, m.tool_length])
    carried = length - np.array([0.0, 0.0, m.length_change])  # the length the axes hold now
    here = m.pos
    m.pos = _table(m, here - carried, m.extra, back=True) + length  # where the tip is on the part
    m.length_change = 0.0
    prog = m.target(words)
    m.pos = here
    extra = m.extra_end(words)
    if m.tcp_vector and any(k in words for k in "ijk"):  # a component left out is 0 (Fanuc 15i B-63323EN-1/03)
        extra = _tool_angles(m, np.array([words[k][-1] if k in words else 0.0 for k in "ijk"], float))
    end = _table(m, m.to_machine(prog) - length, extra) + length
    turning = not np.allclose(extra[:3], m.extra[:3], rtol=0.0, atol=1e-12)
    m.extra = extra
    m.emit(line, "rapid" if m.motion == 0 else "feed", end, rows="last" if turning else "one")


def _codes(words: dict, letter: str) -> list[int]:
    """G or M codes of a line as integers x10 (``G59.1`` -> 591, ``G1`` -> 10)."""
    return [int(round(v * 10)) for v in words.get(letter, [])]


def _modes(m: _Machine, g: list[int], words: dict, text: str = "") -> None:
    """Steps 12-19 of the order of execution: plane, units, compensation, tool length, system, modes."""
    if m.ctx.dialect.name in ("fanuc", "haas"):
        _mill_codes(m, g, words)
        _mirror_scaling(m, g, words, text)
    for code in g:
        if code in (170, 180, 190):
            m.plane = code // 10
        elif code in (200, 210):
            m.scale = 25.4 if code == 200 else 1.0
        elif code in (700, 710) and m.ctx.dialect.name == "fanuc":  # Siemens/Fagor units in a mill post
            m.scale = 25.4 if code == 700 else 1.0
    for code in g:
        if code == 400:
            m.comp_closed, m.comp_radius = m.comp_radius or 0.0, None
        elif code in (410, 420):
            number = int(words["d"][-1]) if "d" in words else m.offsets_of.get(m.loaded, m.loaded)
            tool = m.tool(number)
            m.comp_radius = tool.radius if tool is not None and tool.radius > 0 else None
            m.comp_entry, m.comp_side = True, "left" if code == 410 else "right"
        elif code in (411, 421):
            raise ReferenceError("G41.1/G42.1 dynamic compensation")
    before = m.tool_length
    if m.ctx.dialect.name in ("fanuc", "haas") and "h" in words and (m.length_mode in (430, 440) or m.tcp) and not \
            any(c in (430, 431, 432, 434, 435, 440, 490, 2340, *_POSITION_OFFSET) for c in g):
        # an H word alone in G43/G44 mode changes the offset to H's, the direction staying (SZGH-CNC1000MDb "G43,
        # G44": "the offset value changes to the new tool length offset value"; Milltronics PL-551: "The new H offset
        # will automatically take effect in either the G43 or G44 mode"): as G43 H / G44 H; in G43.4 / G43.5 / G234
        # mode as that code's H (our reading)
        tcp_code = (2340 if m.ctx.dialect.name == "haas" else 435 if m.tcp_vector else 434) if m.tcp else None
        g.append(tcp_code or m.length_mode)
    for code in g:
        if code in (430, 431, 432, 440, 490):
            m.tcp = False
            m.length_mode = code
        if (code, m.ctx.dialect.name) in ((434, "fanuc"), (435, "fanuc"), (2340, "haas")):
            m.tcp, m.tcp_vector = True, code == 435  # the tool length as G43, X Y Z the tip on the part (_tcp_move)
            code = 430
        if code in (430, 440) or code == 431 and m.ctx.dialect.name == "fanuc":  # Fanuc G43.1: along the tool axis
            number = int(words["h"][-1]) if "h" in words else m.offsets_of.get(m.loaded, m.loaded)
            if number == 0 and m.ctx.dialect.name == "linuxcnc":  # LinuxCNC find_tool_index: H0 is the spindle's
                number = m.loaded
            tool = m.tool(number)
            # G44 subtracts the offset, G43 adds it (Fanuc B-63943EN-1/02 12.5.2 "Offset direction": "if G44, to
            # the - side"); the tool's X Y offsets with it (our reading)
            sign = -1.0 if code == 440 else 1.0
            m.tool_length = sign * tool.length if tool is not None else 0.0
            m.tool_xy = sign * np.array([tool.offset_x, tool.offset_y]) if tool is not None else np.zeros(2)
        elif code == 490:
            m.tool_length = 0.0
            m.tool_xy = np.zeros(2)
        elif code == 431 and "z" in words and not any(a in words for a in "xyabcuvw"):
            # g-code.adoc "G43.1": dynamic tool length offset, the Z word is the offset (no motion)
            m.tool_length = words.pop("z")[-1] * m.scale
        elif code == 432 and m.ctx.dialect.name == "linuxcnc":
            # g-code.adoc "G43.2": H<n> adds tool n's offsets (H0 the spindle's tool's, find_tool_index), axis words
            # add themselves (no motion)
            number = int(words.pop("h")[-1]) if "h" in words else None
            tool = m.tool(m.loaded if number == 0 else number) if number is not None else None
            add = [tool.offset_x, tool.offset_y, tool.length] if tool is not None else [0.0, 0.0, 0.0]
            for i, a in enumerate("xyz"):
                if a in words:
                    add[i] = words.pop(a)[-1] * m.scale
            m.tool_xy = m.tool_xy + np.array(add[:2])
            m.tool_length += add[2]
        elif code in (431, 432):
            raise ReferenceError(f"G{code / 10:g} tool length mode")
    if m.length_moves:
        m.length_change += m.tool_length - before
    if m.fadal and "e" in words:  # Fadal fixture offset E<n>: E1-E6 are G54-G59, E0 none
        n = int(words.pop("e")[-1])
        m.wcs = "E0" if n == 0 else _WCS[530 + 10 * n] if n <= 6 else f"E{n}"
        _use_system(m, m.wcs)
    for code in g:
        if _extended(m, code, g, words):
            pass
        elif code in _WCS:
            m.wcs = _WCS[code]
        elif code in (900, 910):
            m.incremental = code == 910
        elif code in (901, 911):
            m.arc_absolute = code == 901
        elif code in (980, 990):
            m.retract = code // 10
    if m.ctx.dialect.name == "haas":
        _dwo(m, g, words)


def _dwo(m: _Machine, g: list[int], words: dict) -> None:
    """Haas G254 dynamic work offset (Haas mill operator's manual (NGC) "G254 Dynamic Work Offset (DWO)": for 3+1 /
    3+2 positioning "DWO uses the current rotary positions and the machine rotary zero point (MRZP) to compute where
    the work offset has gone"; "G255 cancels DWO"), on the context's tilting table: the work zero in force (work
    offset and G92 shift, machine coordinates with the rotary axes at 0) carried by the table to the rotary
    positions (:func:`_table`, the pivots standing for the MRZP) shifts every position, incremental moves included
    (an offset, which a G91 move does not see: it goes from where the tool is). A rotary word under it, a G68 frame
    or TCPC are not modelled (ReferenceError)."""
    if 2550 in g:
        m.dwo_on, m.dwo = False, np.zeros(3)
    if 2540 in g:
        kin = m.ctx.kinematics
        if kin is None or kin.kind != "table" or m.g68 is not None or m.tcp:
            raise ReferenceError("G254 without a tilting table, or under G68 / G234")
        m.dwo_on = True
    if m.dwo_on:
        if any(a in words for a in "abc"):
            raise ReferenceError("a rotary axis word under G254")
        zero = m.offsets[m.wcs] + m._rot(m.g92, 1.0)
        m.dwo = _table(m, zero, m.extra) - zero


def _use_system(m: _Machine, code: str) -> None:
    """Make work offset ``code`` known to the machine (from the context's table) and active."""
    if code not in m.offsets:
        m.offsets[code] = np.array(m.ctx.offset(code), float)
        m.rotation[code] = 0.0
        m.extra_offsets[code] = np.zeros(6)


def _extended(m: _Machine, code: int, g: list[int], words: dict) -> bool:
    """Fanuc G54.1 P (or G54 P when no G04, G10, G64 or cycle reads the P) / Haas G154 P, G110-G129: select
    an additional work offset (its P word taken off)."""
    dialect = m.ctx.dialect.name
    cycle = any(c // 10 in (*_CYCLES, *_MILL_CYCLES, 84, 86) for c in g) or (m.motion or 0) // 10 in (
        *_CYCLES, *_MILL_CYCLES, 84, 86)
    g54p = code == 540 and "p" in words and not cycle and not any(c in g for c in (40, 640, 100))
    if dialect == "fanuc" and (code == 541 or g54p) or dialect == "haas" and code == 1540:
        n = int(words.pop("p", [1])[-1])
    elif dialect == "haas" and 1100 <= code <= 1290 and code % 10 == 0:
        n = code // 10 - 109
    else:
        return False
    m.wcs = f"G54.1 P{n}"
    _use_system(m, m.wcs)
    return True


def _mill_codes(m: _Machine, g: list[int], words: dict) -> None:
    """Fanuc/Haas look-ahead codes (their words taken off, the codes too), Fanuc G40.1-G42.1 and G68/G69."""
    if m.ctx.dialect.name == "haas" and 770 in g:  # Haas G77 is Fanuc's G87
        g[g.index(770)] = 870
    for code in (401, 411, 421):  # Fanuc normal direction control (B-63844EN II-14.9): turns a C axis only
        if code in g and m.ctx.dialect.name == "fanuc":
            if code != 401 and "c" in m.ctx.extra_axes:
                raise ReferenceError("G41.1/G42.1 normal direction control with a C axis")
            g.remove(code)
    if 90 in g:  # G09 exact stop: the block ends at rest, at the same point
        g.remove(90)
    if 390 in g:  # G39 corner circular interpolation (Fanuc 16/18-MC "Corner offset circular interpolation")
        if m.comp_radius is None or set(words) & set("xyzijkr"):
            raise ReferenceError("G39 outside compensation or with a vector")
        g.remove(390)
        m.g39 = True
    if m.ctx.dialect.name == "fanuc" and (220 in g or 230 in g):  # G22 X Y Z I J K: the stroke check's area
        g[:] = [c for c in g if c not in (220, 230)]
        for k in "xyzijk":
            words.pop(k, None)
    for code, letters in ((1870, "pe"), (1030, "p"), (51, "qrxyz"), (80, "p"), (50, "p")):
        if code in g:
            g.remove(code)
            for k in letters:
                words.pop(k, None)
    for code in g:
        if code in (170, 180, 190):
            m.plane = code // 10
    if 690 in g:
        m.g68 = None
    if 680 in g:
        axes = {17: (0, 1), 18: (2, 0), 19: (1, 2)}[m.plane]
        m.g68 = None
        centre = m.to_program(m.pos)
        for i in axes:
            if "xyz"[i] in words:
                centre[i] = words.pop("xyz"[i])[-1] * m.scale
        m.g68 = (axes, centre, words.pop("r", [0.0])[-1])


def _mirror_scaling(m: _Machine, g: list[int], words: dict, text: str) -> None:
    """G51.1 / G50.1 mirror and G51 / G50 scaling (their axis words taken off)."""
    if 500 in g:
        m.factors = np.ones(3)
    haas = m.ctx.dialect.name == "haas" and (1010 in g or 1000 in g)  # G101 / G100: about the work zero
    if 511 in g or 501 in g or haas:
        for i, a in enumerate("xyz"):
            if a in words:
                value = words.pop(a)[-1] * m.scale
                m.mirror[i] = 511 in g or 1010 in g
                m.mirror_at[i] = value if 511 in g else 0.0
    if 510 in g:
        m.factors = np.ones(3)
        m.scale_centre = m.to_program(m.pos)
        for i, a in enumerate("xyz"):
            if a in words:
                m.scale_centre[i] = words.pop(a)[-1] * m.scale

        def factor(k: str) -> float:
            value = words.pop(k)[-1]
            plain = re.search(rf"{k}\s*[-+]?\d+(?![\d.])", text) is not None
            return value / 1000.0 if m.ctx.dialect.name == "fanuc" and plain else value

        if "p" in words:
            m.factors = np.full(3, factor("p"))
        else:
            m.factors = np.array([factor(k) if k in words else 1.0 for k in "ijk"])


def _non_modal(m: _Machine, line: int, g: list[int], words: dict) -> bool:
    """Step 20: G28/G30, G10, G92 family. True when the axis words were used here."""
    for code in g:
        if code in (700, 710, 720) and m.ctx.dialect.name == "haas":
            _pattern(m, line, code, words)
            return True
        if code in (120, 130) and m.ctx.dialect.name == "haas":
            _pocket(m, line, code, words)
            return True
        if code in (280, 300):
            home = m.home[code]
            axes = [i for i, a in enumerate("xyz") if a in words]
            extra = m.extra_words(words)
            mid = m.target(words)
            if "z" in words:  # Fanuc: an incremental Z travels the tool length change too
                mid[2] += m.length_change if m.incremental else 0.0
            if "z" in words or not axes and not extra:
                # Fanuc 0i-MB B-63844EN/02 14.1.2: the length vector is cancelled at the reference, G43 staying;
                # the next Z move restores it
                m.length_change = m.tool_length if m.length_moves else 0.0
            m.intermediate[axes] = mid[axes]  # Fanuc/Haas G29 returns through it
            if not axes and not extra:
                m.intermediate = m.to_program(m.pos)
            if axes or extra:
                m.move(line, "rapid", mid, optional=True, extra=m.extra_end(words))
            end = m.pos.copy()
            for i in axes if axes or extra else range(3):
                end[i] = home[i]
            for i in extra if axes or extra else range(6):
                # the reference position of a, b, c, u, v, w: 0; a wrapping rotary axis turns there by its rule,
                # less than a turn (LinuxCNC: reached the positive way, as G28.1 stores it reduced below 360)
                wraps = i < 3 and "abc"[i] in m.ctx.wrapped_axes
                m.extra[i] = m.wrapped(0.0, m.extra[i], 0.0) if wraps else 0.0
            m.emit(line, "rapid", end)
            return True
        if code in (270, 290, 600) and m.ctx.dialect.name in ("fanuc", "haas"):
            _from_reference(m, line, code, words)
            return True
        if code in (281, 301):  # LinuxCNC, grbl: the block's axis words move by the modal motion (enhance_block)
            m.home[code - 1] = m.pos.copy()
            return m.ctx.dialect.name not in ("linuxcnc", "grbl")
        if code == 531:
            raise ReferenceError(f"G{code / 10:g}")
        if code == 100:
            _g10(m, words)
            return True
        if code == 520:  # g-code.adoc "G52 Local Coordinate System Offset": the offset is the value
            fanuc = m.ctx.dialect.name in ("fanuc", "haas")  # Fanuc: the local system, on top of the G92 shift
            for i, a in enumerate("xyz"):
                if a in words:
                    v = words[a][-1] * m.scale
                    m.g92[i] = m.g92[i] - m.local[i] + v if fanuc else v
                    m.local[i] = v if fanuc else 0.0
            return True
        if code == 920:  # under G43.4 / G234 the current point is the tip on the part (as _tcp_move reads it)
            length = np.array([0.0, 0.0, m.tool_length])
            here = _table(m, m.pos - length, m.extra, back=True) + length if m.tcp else m.pos
            prog_no_g92 = m.to_program(here) + m.g92
            for i, a in enumerate("xyz"):
                if a in words:
                    m.g92[i] = prog_no_g92[i] - words[a][-1] * m.scale
                    m.local[i] = 0.0
            for i, v in m.extra_words(words).items():
                m.g92_extra[i] = m.extra[i] - m.extra_offsets[m.wcs][i] - v
            return True
        if code == 921 and m.ctx.dialect.name not in ("linuxcnc", "grbl") and set(words) & set("xyzabcuvw"):
            # Fanuc's workpiece coordinate system preset "G92.1 IP 0": the axes named only, no motion
            for i, a in enumerate("xyz"):
                if a in words:
                    m.g92[i] = m.local[i] = 0.0
            for i in m.extra_words(words):
                m.g92_extra[i] = 0.0
            return True
        if code in (921, 922):
            m.g92 = np.zeros(3)
            m.g92_extra = np.zeros(6)
        elif code == 923:
            raise ReferenceError("G92.3")
    return False


def _from_reference(m: _Machine, line: int, code: int, words: dict) -> None:
    """Fanuc G27 and G60 (Haas G60): a rapid to the point (G60's overrun not modelled: the same end); Fanuc/Haas
    G29 (Haas "G29 Return From Reference Point": "the axes selected in this block are moved to the G29 reference
    point saved in G28, and then moved to the location specified"): the named axes to the last G28/G30
    intermediate point, then to the point (under G91 an increment from the intermediate point)."""
    if code == 290:
        mid = m.to_program(m.pos)
        for i, a in enumerate("xyz"):
            if a in words:
                mid[i] = m.intermediate[i]
        m.move(line, "rapid", mid, optional=True)
        if "z" in words:  # a program point: the length vector a G28 Z cancelled is back in it
            m.length_change = 0.0
    end = m.target(words)
    if "z" in words:  # an incremental Z travels a tool length change not yet travelled
        end[2] += m.length_change if m.incremental else 0.0
        m.length_change = 0.0
    m.move(line, "rapid", end, optional=True)


def _pocket(m: _Machine, line: int, code: int, words: dict) -> None:
    """Haas G12 / G13 circular pocket milling in G17."""
    s = m.scale
    centre = m.target({k: v for k, v in words.items() if k in "xy"})
    if "x" in words or "y" in words:
        m.move(line, "rapid", centre)
    tool = m.tool(int(words["d"][-1])) if "d" in words else None
    radius = tool.radius if tool is not None else 0.0
    radii = [words["i"][-1] * s]
    while "k" in words and radii[-1] < words["k"][-1] * s - 1e-9:
        radii.append(min(radii[-1] + words["q"][-1] * s, words["k"][-1] * s))
    signs = np.where(m.mirror, -1.0, 1.0) * m.factors
    cw = (code == 120) != ((signs[0] < 0) != (signs[1] < 0))
    z = centre[2]
    for _ in range(int(words["l"][-1]) if "l" in words else 1):
        if "z" in words:  # no Z: the circles at the current Z (the tool already at depth)
            z = z + words["z"][-1] * s if m.incremental else words["z"][-1] * s
        m.move(line, "feed", np.array([centre[0], centre[1], z]), optional=True)
        previous = 0.0
        for r in (r - radius for r in radii):
            end = m.to_machine(np.array([centre[0] + r, centre[1], z]))
            for c in (centre[0] + (previous + r) / 2, centre[0]):
                m.emit(line, "arc_cw" if cw else "arc_ccw", end, centre=m.to_machine(np.array([c, centre[1], z])),
                       centre_tolerance=1e-6)
            previous = r
        m.move(line, "feed", np.array([centre[0], centre[1], z]))


def _pattern(m: _Machine, line: int, code: int, words: dict) -> None:
    """Haas G70 / G71 / G72: the active canned cycle at each hole, given as absolute X Y."""
    centre = m.target({k: v for k, v in words.items() if k in "xy"})[:2]
    n, size = int(words["l"][-1]), words["i"][-1] * m.scale
    j = words.get("j", [0.0])[-1]
    if code == 720:
        points = [centre + size * (k + 1) * np.array([math.cos(math.radians(j)), math.sin(math.radians(j))])
                  for k in range(n)]
    else:
        step = 360.0 / n if code == 700 else words["k"][-1]
        points = [centre + size * np.array([math.cos(math.radians(j + k * step)), math.sin(math.radians(j + k * step))])
                  for k in range(n)]
    for p in points:
        if m.incremental:  # an increment from the previous hole, as the cycle reads X Y under G91
            here = m.to_program(m.pos)[:2]
            _cycle(m, line, {"x": [(p[0] - here[0]) / m.scale], "y": [(p[1] - here[1]) / m.scale]})
        else:
            _cycle(m, line, {"x": [p[0] / m.scale], "y": [p[1] / m.scale]})


def _g10(m: _Machine, words: dict) -> None:
    """G10 L2 / L20 P: set a coordinate system (g-code.adoc "G10 L2", "G10 L20"); R rotates it."""
    kind = int(words["l"][-1])
    p = int(words["p"][-1]) if "p" in words else 0
    if kind == 50 and m.ctx.dialect.name == "fanuc":  # Fanuc programmable parameter input: data lines to G11
        m.parameter_input = True
        return
    if kind in (1, 10, 11, 12, 13) and m.ctx.dialect.name in ("fanuc", "haas"):
        _g10_tool(m, kind, p, words)
        return
    if kind == 1 and not ("x" in words or "y" in words):  # LinuxCNC G10 L1: the tool table's Z and R
        _g10_l1(m, p, words)
        return
    if kind not in (2, 20):
        raise ReferenceError(f"G10 L{kind}")
    if m.ctx.dialect.name in ("fanuc", "haas") and kind == 2 and p == 0:  # the external offset: every system
        for i, a in enumerate("xyz"):
            if a in words:
                v = (m.external[i] if m.incremental else 0.0) + words[a][-1] * m.scale
                m.g92[i] += v - m.external[i]
                m.external[i] = v
        for i, v in m.extra_words(words).items():  # A-W: their external offsets alike (B-64304EN "G10 L2")
            value = (m.external_extra[i] if m.incremental else 0.0) + v
            m.g92_extra[i] += value - m.external_extra[i]
            m.external_extra[i] = value
        return
    if m.ctx.dialect.name in ("fanuc", "haas"):  # Fanuc "G10 L2 / L20": the value (G90) or an increment (G91)
        code = list(_WCS.values())[p - 1] if kind == 2 else f"G54.1 P{p}"
        _use_system(m, code)
        for i, a in enumerate("xyz"):
            if a in words:
                m.offsets[code][i] = (m.offsets[code][i] if m.incremental else 0.0) + words[a][-1] * m.scale
        for i, v in m.extra_words(words).items():
            m.extra_offsets[code][i] = (m.extra_offsets[code][i] if m.incremental else 0.0) + v
        return
    code = m.wcs if p == 0 else list(_WCS.values())[p - 1]
    # the current position in the active system, G92 included: L20 makes it the given value (LinuxCNC
    # interp_convert.cc convert_setup with interp_find.cc find_current_in_system, which takes the G92
    # offset off when it is on)
    here = m.to_program(m.pos)
    base = m.offsets[m.wcs].copy() if kind == 20 else None
    for i, a in enumerate("xyz"):
        if a in words:
            v = words[a][-1] * m.scale
            if kind == 2:
                m.offsets[code][i] = v
            else:
                m.offsets[code][i] = base[i] + here[i] - v
    if kind == 20 and m.rotation[code] and ("x" in words or "y" in words):
        # under a G10 R rotation the current and the wanted X Y are in the rotated system: both turn into the
        # unrotated one before the offset is their difference (interp_convert.cc convert_setup, "old position in
        # rotated system"; tests/interp/g10/g10-l20-while-active)
        want = np.array([words[a][-1] * m.scale if a in words else here[i] for i, a in enumerate("xy")])
        t = math.radians(m.rotation[code])
        turn = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
        m.offsets[code][:2] = base[:2] + turn @ (here[:2] - want)
    for i, v in m.extra_words(words).items():
        m.extra_offsets[code][i] = v if kind == 2 else m.extra[i] - m.g92_extra[i] - v
    if "r" in words:
        m.rotation[code] = words["r"][-1]


@dataclasses.dataclass(frozen=True)
class _Tool:
    """A tool the context's table lacks, as G10 L10-L13 create it."""

    length: float = 0.0
    radius: float = 0.0
    offset_x: float = 0.0
    offset_y: float = 0.0


def _g10_tool(m: _Machine, kind: int, p: int, words: dict) -> None:
    """Fanuc/Haas G10 L10 (L11, L1: wear) length and L12 (L13: wear) radius of offset P to R, or by R under
    G91 (Haas: L12/L13 are diameters)."""
    v = words["r"][-1] * m.scale / (2.0 if kind in (12, 13) and m.ctx.dialect.name == "haas" else 1.0)
    table = m.tool_radii if kind in (12, 13) else m.tool_lengths
    base = m.ctx.tool(p)
    geometry, wear = table.get(p, ((base.radius if kind in (12, 13) else base.length) if base else 0.0, 0.0))
    if kind in (10, 12):
        geometry = (geometry if m.incremental else 0.0) + v
    else:
        wear = (wear if m.incremental else 0.0) + v
    table[p] = (geometry, wear)


def _g10_l1(m: _Machine, p: int, words: dict) -> None:
    """LinuxCNC ``G10 L1 P<tool> Z.. R..`` (g-code.adoc "G10 L1 Set Tool Table": "P - tool number", "R - radius
    of tool", the axis words the tool's offsets): the table's length and radius of tool P become the values, in
    the current units; a G43 or G41 after it reads them (tool() looks the table up there)."""
    if "z" in words:
        m.tool_lengths[p] = (words["z"][-1] * m.scale, 0.0)
    if "r" in words:
        m.tool_radii[p] = (words["r"][-1] * m.scale, 0.0)


def _motion(m: _Machine, line: int, g: list[int], words: dict, axes: bool) -> None:
    """Step 21: the motion of the active mode (as modified by G53)."""
    cycles = _CYCLES + (_MILL_CYCLES if m.ctx.dialect.name in ("fanuc", "haas") else ())
    unmodelled = [c for c in g if c % 10 == 0 and 73 <= c // 10 <= 89 and c // 10 not in (*cycles, 80)]
    if unmodelled:  # G88 boring with manual retract, G76/G87 outside Fanuc/Haas: not modelled here
        raise ReferenceError(f"G{unmodelled[0] // 10} cycle")
    nurbs = (52, 53) if m.ctx.dialect.name == "linuxcnc" else ()
    if 52 in nurbs and 52 in g and m.motion != 52:  # a new G5.2 block: the current position is its first point
        m.nurbs_end = m.pos.copy()
    arcs3d = (24, 34) if m.ctx.dialect.name == "fanuc" else ()
    explicit = [c for c in g if c in (0, 10, 20, 30, 50, 51, 330, 331, 800, *nurbs, *arcs3d) or c // 10 in cycles]
    for code in explicit:
        m.motion = code
        if code // 10 not in cycles:
            m.cycle_clear = None
        if code == 800:  # Fanuc: the cycles are group 09, G80 gives back the G0-G3 mode before them
            m.motion = m.linear
        elif code // 10 not in cycles:
            m.linear = code
    if m.motion in (52, 53):
        _nurbs(m, line, words, axes)
        return
    # TOS = 0 (B-63943EN-1/02 12.5.2): a G43/G44/G49 block (Fadal: its H) of G00/G01 without Z moves Z by the change
    length_code = any(c in (430, 431, 440, 490) for c in g)
    now = bool(m.length_change) and m.motion in (0, 10) and not m.tcp and "z" not in words and length_code \
        and 530 not in g
    if 530 in g and length_code and not axes:  # "G53 G49 M05": the vector cancelled, no move (0i-MB 14.1.2)
        m.length_change = m.tool_length if m.length_moves else 0.0
    if 530 in g and axes:
        if m.motion not in (0, 10):
            raise ReferenceError("G53 without G0/G1 motion")
        # under G91 Fanuc/Haas move by the words (Mitsubishi M700V 14.4 (4)); grbl keeps them machine positions
        steps = m.incremental and m.ctx.dialect.name in ("fanuc", "haas")
        end = m.pos.copy()
        for i, a in enumerate("xyz"):
            if a in words:
                end[i] = end[i] * steps + words[a][-1] * m.scale
        if "z" in words or length_code:  # 14.1.2: a G53 Z or G49 G53 cancels the length vector, no Z travel; the
            # next Z move restores it (G43 staying)
            m.length_change = m.tool_length if m.length_moves else 0.0
        m.extra = m.extra_end(words, machine=not steps)
        m.emit(line, "rapid" if m.motion == 0 else "feed", end)
        return
    arc_alone = m.motion in (20, 30) and any(c in (20, 30) for c in g) and any(k in words for k in "ijkr")
    # Fanuc 0i "Circular interpolation": X, Y, Z all omitted with I J K -> a 360 deg circle, in the modal
    # G02/G03 too (a block of I J alone); LinuxCNC too (rs274ngc enhance_block: a block of "i1" in arc mode)
    arc_alone = arc_alone or (m.ctx.dialect.name in ("fanuc", "linuxcnc") and m.motion in (20, 30) and "r" not in words
                              and any(k in words for k in "ijk"))
    if not (axes or arc_alone or now) or m.motion is None:
        return
    rotated = m.g68 is not None and m.g68[0] != {17: (0, 1), 18: (2, 0), 19: (1, 2)}[m.plane]
    if m.motion // 10 in cycles:
        if m.ctx.dialect.name == "fanuc" and rotated:  # 15i-MA B-63324EN/03: "G17, G18 or G19 must not be
            raise ReferenceError(f"line {line}: a canned cycle outside the G68 plane")  # designated" under G68
        _cycle(m, line, words)
        return
    if m.tcp and m.motion in (0, 10):
        _tcp_move(m, line, words)
        return
    if m.ctx.dialect.name == "fanuc" and rotated and (m.motion in (20, 30) or m.comp_radius is not None):
        # Fanuc 0i-A B-63503EN-1/01 alarm 144: "The coordinate rotation plane and arc or cutter compensation C plane
        # must be the same"
        raise ReferenceError(f"line {line}: an arc or G41/G42 outside the G68 plane (Fanuc alarm 144)")
    # the unnamed axes under the offset travelled: they differ under a rotation that turns Z into X or Y (G18/G19 G68)
    end = m.to_machine(m.target(words, untravelled=m.length_change))
    end[2] -= 0.0 if "z" in words and not m.incremental else m.length_change
    if ("z" in words or now) and m.length_change:  # Fanuc: an incremental Z travels the offset's change too
        end[2] += m.length_change if m.incremental or now else 0.0
        m.length_change = 0.0
    shift = [c for c in g if c in _POSITION_OFFSET]
    if shift and m.ctx.dialect.name == "fanuc":
        end = _position_offset(m, shift[0], words, end)
    m.extra = m.extra_end(words)
    if m.motion in (24, 34):
        _arc3d(m, line, words, end)
    elif m.motion in (0, 10, 330):
        m.emit(line, "rapid" if m.motion == 0 else "feed", end)
    elif m.motion == 331:  # g-code.adoc "G33.1 Rigid Tapping": to the end point and back to the start
        start = m.pos.copy()
        m.emit(line, "feed", end)
        m.emit(line, "feed", start)
    elif m.motion in (20, 30) and m.rotation[m.wcs] and m.plane != 17:
        # an XZ/YZ arc of a system rotated about Z lies in no axis plane: the reader runs it as
        # chords (as LinuxCNC's canon does for such arcs); the end of the last one is checked
        m.emit(line, "feed", end, rows="last")
    elif m.motion in (20, 30):
        centre = _centre(m, words, end)
        a, b = {17: (0, 1), 18: (2, 0), 19: (1, 2)}[m.plane]
        rs, re_ = (math.hypot(p[a] - centre[a], p[b] - centre[b]) for p in (m.pos, end))
        chord = math.hypot(end[a] - m.pos[a], end[b] - m.pos[b])
        slack = 2 * abs(rs - re_) * max(rs, re_) / chord if chord > 0 else 0.0
        signs = np.where(m.mirror, -1.0, 1.0) * m.factors
        if abs(m.factors[a]) != abs(m.factors[b]):
            raise ReferenceError("an arc under unequal scaling")
        flip = (signs[a] < 0) != (signs[b] < 0)  # one axis of the plane mirrored: G02 runs as G03
        m.emit(line, "arc_cw" if (m.motion == 20) != flip else "arc_ccw", end, centre=centre,
               centre_tolerance=1e-6 + slack)
    else:  # G5 / G5.1: the reader's chords, the last at the end of the spline
        m.emit(line, "feed", end, rows="last")


def _arc3d(m: _Machine, line: int, words: dict, end: np.ndarray) -> None:
    """Fanuc G02.4 / G03.4 (Mitsubishi M700V programming manual 6.14, which describes the same command: "G02.4
    Xx1 Yy1 Zz1 ; Intermediate point designation (1st block) / Xx2 Yy2 Zz2 ; End point designation (2nd block)"):
    the first block's point is kept, the second runs the arc (the reader's chords, the last checked at its end);
    an end coordinate the second block omits is the intermediate point's, under G91 it counts from there."""
    if m.arc3d is None:
        m.arc3d = (end, line)
        return
    mid, m.arc3d = m.arc3d[0], None
    if m.incremental:
        end = end + (mid - m.pos)
    else:
        end = np.array([end[i] if a in words else mid[i] for i, a in enumerate("xyz")])
    m.emit(line, "feed", end, rows="last")


def _nurbs(m: _Machine, line: int, words: dict, axes: bool) -> None:
    """LinuxCNC G5.2 / G5.3 (g-code.adoc "G5.2 G5.3 NURBS Block"): the control points' blocks move nothing (the
    position, from which G91 words count, stays); at G5.3 the curve runs to the last control point (the reader's
    chords on the G5.3 line: the last row checked)."""
    if m.motion == 53:
        m.emit(line, "feed", m.nurbs_end, rows="last")
        m.motion = None
    elif axes:
        m.nurbs_end = m.to_machine(m.target(words))


#: Fanuc G45-G48 tool position offset: the multiple of the offset each adds to an axis' travel.
_POSITION_OFFSET = {450: 1, 460: -1, 470: 2, 480: -2}


def _position_offset(m: _Machine, code: int, words: dict, end: np.ndarray) -> np.ndarray:
    """Fanuc G45-G48 (Fanuc 0i-MD B-64304EN II-14.2; the Mitsubishi M700V programming manual 12.6 tabulates
    the cases): each axis word's travel x becomes x + k l sign(x), l the offset of D (a radius) or H (a
    length); an incremental zero travels k l towards its own sign (X-0: minus); an absolute zero stays."""
    if m.motion not in (0, 10):
        raise ReferenceError("G45-G48 off a G00/G01 move")
    letter = "d" if "d" in words else "h"
    tool = m.tool(int(words[letter][-1]))
    offset = 0.0 if tool is None else tool.radius if letter == "d" else tool.length
    k = _POSITION_OFFSET[code]
    end = end.copy()
    for i, a in enumerate("xyz"):
        if a not in words:
            continue
        travel = end[i] - m.pos[i]
        if travel:
            end[i] += k * offset * math.copysign(1.0, travel)
        elif m.incremental:
            end[i] += k * offset * math.copysign(1.0, words[a][-1])
    return end


def _centre(m: _Machine, words: dict, end: np.ndarray) -> np.ndarray:
    """Arc centre [mm, machine] (g-code.adoc "G2, G3 Arcs"): I J K offsets from the start (G91.1,
    the default) or positions (G90.1); or R, the centre on the right of the chord for G2 with
    R > 0, on the left for G3, the other side for R < 0 (the longer arc)."""
    a, b = {17: (0, 1), 18: (2, 0), 19: (1, 2)}[m.plane]
    start_p, end_p = m.to_program(m.pos), m.to_program(end)
    centre = start_p.copy()
    if "r" in words:
        radius = words["r"][-1] * m.scale
        chord = np.array([end_p[a] - start_p[a], end_p[b] - start_p[b]])
        half = np.linalg.norm(chord) / 2
        h = math.sqrt(max(radius * radius - half * half, 0.0))
        unit = chord / (2 * half)
        left = np.array([-unit[1], unit[0]])
        side = (1.0 if m.motion == 30 else -1.0) * (1.0 if radius > 0 else -1.0)
        mid = np.array([start_p[a], start_p[b]]) + chord / 2
        centre[a], centre[b] = mid + side * h * left
    else:
        for i, k in enumerate("ijk"):
            if i in (a, b):
                v = words.get(k, [0.0])[-1] * m.scale
                centre[i] = v if m.arc_absolute else start_p[i] + v
    return m.to_machine(centre)


def _cycle(m: _Machine, line: int, words: dict) -> None:
    """One canned-cycle block (g-code.adoc "G80-G89 Canned Cycles"): in G17 the holes are drilled along
    Z, in G18 along Y (Z X place them), in G19 along X (Y Z place them): "the cycle is performed in the
    plane selected"."""
    axes = {17: (0, 1, 2), 18: (2, 0, 1), 19: (1, 2, 0)}[m.plane]
    first, second, depth = ("xyz"[a] for a in axes)

    def prog(v) -> np.ndarray:  # plane coordinates (first, second, depth) -> program X Y Z
        out = np.empty(3)
        out[list(axes)] = v
        return out

    code = m.motion // 10
    turned = np.where(m.mirror, -1.0, 1.0) * m.factors
    if turned[axes[2]] < 0:  # our reading: a drilling axis turned over would drill from R away from the part
        raise ReferenceError(f"line {line}: canned cycle with its drilling axis mirrored")
    if m.cycle_clear is None and m.ctx.dialect.name != "linuxcnc":
        m.sticky = {}  # Fanuc/Haas: G80 clears the hole data; LinuxCNC keeps its cycle_p, cycle_q, cycle_cc
    if code == 81 and m.ctx.dialect.name == "fanuc" and (m.sticky.get("fagor") or m.cycle_clear is None
                                                         and "i" in words and "r" not in words):
        # Fagor 8055 programming manual 9.7: "G81 G98/G99 X Y Z I K", Z the reference plane, I the depth, in
        # every block of the series
        if m.plane != 17 or words.get("k", [0.0])[-1] != 0:
            raise ReferenceError("Fagor G81 with a dwell K or outside G17")
        m.sticky["fagor"] = True
        if "z" in words:
            words["r"] = words.pop("z")
        if "i" in words:
            words["z"] = words.pop("i")
        words.pop("k", None)
    for k in "rqpijk":
        if k in words:
            m.sticky[k] = words[k][-1]
    written = {k for k in "qij" if k in words}
    if code in (76, 87) and written:  # Haas "G77": "If Q is not specified, the optional I and J values are used"
        haas = m.ctx.dialect.name == "haas"
        m.sticky["shift"] = "q" if "q" in written and (haas or written == {"q"}) else "ij"
    if depth in words:
        m.sticky["z"] = words[depth][-1]
    cur = m.to_program(m.pos)[list(axes)]
    if m.cycle_clear is None:
        # the tool's level under the offset it travelled, as the new offset counts it: the change is a machine Z
        # distance, taken before the program's scaling or mirror counts it
        here = m.pos + np.array([0.0, 0.0, m.length_change if m.plane == 17 else 0.0])
        m.cycle_clear = m.to_program(here)[list(axes)][2]
    s = m.scale
    if "r" not in m.sticky and m.ctx.dialect.name in ("fanuc", "haas"):
        # no R in the first block: the R plane is the initial level (Haas NGC mill manual 2017, G81: "*R ...
        # * indicates optional"; Fanuc "Canned cycle cancel (G80)": "R = 0 ... in incremental command")
        m.sticky["r"] = 0.0 if m.incremental else m.cycle_clear / s
    # G91: R from the series' initial level, which LinuxCNC keeps from the series' first block
    # (interp_cycles.cc convert_cycle_xy: r = r_number + cycle_il)
    r = (m.cycle_clear + m.sticky["r"] * s) if m.incremental else m.sticky["r"] * s
    bottom = r + m.sticky["z"] * s if m.incremental else m.sticky["z"] * s
    clear = max(m.cycle_clear, r) if m.retract == 98 else r
    # Fanuc repeats a cycle K times (0i-MF "Canned cycle": "K: number of repeats"); LinuxCNC and Haas with L
    # (Fadal's G73/G83 read K as Haas's minimum peck: Fusion's fadal.cps writes "G83 .. I.. J.. K..")
    fanuc_k = m.ctx.dialect.name == "fanuc" and "k" in words and "l" not in words and not (m.fadal and code in (73, 83))
    repeats = int(words["k"][-1]) if fanuc_k else int(words["l"][-1]) if "l" in words else 1
    if m.plane == 17:  # the R positioning travels a pending tool length change (TOS = 0), K0 stores it
        m.length_change = 0.0
    if code == 87:
        _back_bore(m, line, words, cur, r, bottom, prog)
        return
    if cur[2] < r - _EPS * max(1.0, abs(r)) and m.ctx.dialect.name not in ("fanuc", "haas"):
        # LinuxCNC: below R, straight up to R first; Fanuc/Haas position X Y where the tool is, then rapid to R
        # (0i-MF "Canned cycle for drilling", operations 1 and 2); Fadal as Fanuc (no Fadal text on a cycle
        # started below R is searchable here: the Fadal dialect reads Fanuc's rules where its manual says nothing)
        cur[2] = r
        m.move(line, "rapid", prog(cur))
    xy = cur[:2].copy()
    polar = "@" in words or "^" in words
    if polar and m.plane != 17:
        raise ReferenceError("polar words outside G17")
    for _ in range(repeats):
        if polar:
            xy = m.target(words)[:2]
        elif m.incremental:
            xy = xy + np.array([words.get(a, [0.0])[-1] * s for a in (first, second)])
        else:
            xy = np.array([words[a][-1] * s if a in words else xy[i] for i, a in enumerate((first, second))])
        z_now = m.to_program(m.pos)[axes[2]]
        m.move(line, "rapid", prog([*xy, z_now]), optional=True)
        m.move(line, "rapid", prog([*xy, r]), optional=True)
        _hole(m, line, code, xy, r, bottom, clear, prog)


def _hole(m: _Machine, line: int, code: int, xy: np.ndarray, r: float, bottom: float, clear: float, prog) -> None:
    """The moves of one hole, from the R plane (``prog`` maps plane coordinates to program X Y Z)."""
    def at(z: float) -> np.ndarray:
        return prog([*xy, z])

    dwell = m.sticky.get("p", 0.0)
    if code in (73, 83):
        # Haas "G83": I the first peck, each next J less, never below K (instead of Q)
        haas = (m.ctx.dialect.name == "haas" or m.fadal) and bool(m.sticky.get("i"))  # fadal.cps writes them too
        if not haas and "q" not in m.sticky:  # every control refuses a peck cycle without its peck depth
            raise ReferenceError(f"G{code} without Q")
        delta = (m.sticky["i"] if haas else m.sticky["q"]) * m.scale
        if delta <= 0:  # rs274: "Negative or zero q value used" (the reader refuses it under every dialect)
            raise ReferenceError(f"G{code} with a peck depth <= 0")
        step = PECK_CLEARANCE_IN * 25.4
        depth = r - delta
        # LinuxCNC's loop in doubles: a last peck within rounding of the bottom may be left out. Fanuc and Haas
        # count in decimal: Q dividing R - Z exactly makes no peck at the bottom (our reading, the reader's too;
        # in mm the pecks of an inch program can land within rounding above it, fanuc_generator seed 501518)
        slack = _EPS * max(1.0, abs(bottom))
        # Haas "G73": with K and Q (no I) the tool returns to R once the passes since the last return total K
        every = m.sticky.get("k", 0.0) * m.scale if code == 73 and (m.ctx.dialect.name == "haas" or m.fadal) \
            and not haas else 0.0
        since = 0.0
        while depth > bottom + (slack if m.ctx.dialect.name in ("fanuc", "haas") else 0.0):
            rows = "optional" if depth - bottom <= slack else "one"
            since += delta
            full = code == 83 or every > 0 and since >= every - slack
            since = 0.0 if full else since
            for kind, z in [("feed", depth), *([("rapid", r)] if full else []), ("rapid", depth + step)]:
                m.out.append(Expected(line=line, kind=kind, end=m.to_machine(at(z)), rows=rows))
                m.pos = m.out[-1].end.copy()
            if haas:  # the next peck is J shorter
                delta = max(delta - m.sticky.get("j", 0.0) * m.scale, m.sticky.get("k", 0.0) * m.scale)
                if delta <= 0:  # J shortens the pecks to nothing and no K keeps a least one: no end to the cycle
                    raise ReferenceError(f"G{code}: pecks shortened to zero (J without K)")
            depth -= delta
    if code in (74, 84) and m.rigid and "q" in m.sticky and m.ctx.dialect.peck_tapping is not None:
        _peck_tap(m, line, r, bottom, at)
    m.move(line, "feed", at(bottom))
    if code in (74, 76, 82, 84, 86, 89):
        m.out.append(Expected(line=line, kind="dwell", end=m.pos.copy(), rows="one" if dwell > 0 else "optional"))
    if code == 76:
        shift = _shift(m)
        for z in (bottom, clear):
            m.move(line, "rapid", prog([*(xy + shift), z]))
        m.move(line, "rapid", at(clear))
    elif code in (74, 84) and m.ctx.dialect.tap_out_to_r:
        m.move(line, "feed", at(r))
        if m.ctx.dialect.name == "fanuc":  # Fanuc: P is the dwell "at the bottom of the hole and at point R when a
            # return is made" (0i-MD B-64304EN, 16i-TA/TB A-78549E, tapping): the spindle reverses at both
            m.out.append(Expected(line=line, kind="dwell", end=m.pos.copy(), rows="one" if dwell > 0 else "optional"))
        m.move(line, "rapid", at(clear), optional=True)
    elif code in (74, 84):  # LinuxCNC: "Move the Z-axis at the current feed rate to clear Z"
        m.move(line, "feed", at(clear))
    elif code == 85 or code == 89 and m.ctx.dialect.name in ("fanuc", "haas"):
        # Fanuc G85/G89 (30i operator's manual B-63944EN-2 5.1.9, 0i-MF "Boring cycle"; Haas "G89"): a feed
        # back to R, under G98 a rapid on to the initial level
        m.move(line, "feed", at(r))
        m.move(line, "rapid", at(clear), optional=True)
    elif code == 89:
        m.move(line, "feed", at(clear))
    else:
        m.move(line, "rapid", at(clear))


def _peck_tap(m: _Machine, line: int, r: float, bottom: float, at) -> None:
    """Fanuc peck rigid tapping (16i-TA/TB A-78549E 3.4 "Peck rigid tapping cycle": Q each cut, PCP No. 5200#5, d
    No. 5213 "cutting start distance"), every move synchronised, so at the tapping feed: PCP = 0 ("high-speed") cuts
    Q, backs off d, cuts d + Q; PCP = 1 ("standard") cuts Q, goes back to R, comes in to d short of the depth already
    tapped. The cut that reaches the bottom is the caller's; a retract never rises above R."""
    q = m.sticky["q"] * m.scale
    if not q > 0:
        raise ReferenceError(f"line {line}: peck rigid tap with Q <= 0")
    d = m.ctx.dialect.peck_tapping_d
    tapped = r
    while tapped - q > bottom + _EPS * max(1.0, abs(bottom)):  # Fanuc's decimal pecks: none at the bottom itself
        tapped -= q
        m.move(line, "feed", at(tapped))
        if m.ctx.dialect.peck_tapping == "standard":
            m.move(line, "feed", at(r))
        m.move(line, "feed", at(min(r, tapped + d)), optional=True)


def _shift(m: _Machine) -> np.ndarray:
    """The G76/G87 shift in the hole plane [mm]: the last shift a G76/G87 block of the series wrote (|Q| along the
    first axis, or I J), else I J when given, else Q."""
    by = m.sticky.get("shift", "ij" if m.sticky.get("i") or m.sticky.get("j") else "q")
    if by == "ij":
        return np.array([m.sticky.get("i", 0.0), m.sticky.get("j", 0.0)]) * m.scale
    return np.array([abs(m.sticky["q"]) * m.scale, 0.0])


def _back_bore(m: _Machine, line: int, words: dict, cur: np.ndarray, r: float, top: float, prog) -> None:
    """G87 back boring, each repeat from the initial level ``m.cycle_clear``."""
    initial, shift = m.cycle_clear, _shift(m)
    xy = cur[:2].copy()
    for _ in range(int(words["l"][-1]) if "l" in words else 1):
        if m.incremental:
            xy = xy + np.array([words.get(a, [0.0])[-1] * m.scale for a in "xy"])
        else:
            xy = np.array([words[a][-1] * m.scale if a in words else xy[i] for i, a in enumerate("xy")])
        m.move(line, "rapid", prog([*xy, initial]), optional=True)
        for kind, at, z in (("rapid", xy + shift, initial), ("rapid", xy + shift, r), ("rapid", xy, r),
                            ("feed", xy, top)):
            m.move(line, kind, prog([*at, z]))
        dwell = m.sticky.get("p", 0.0)
        m.out.append(Expected(line=line, kind="dwell", end=m.pos.copy(), rows="one" if dwell > 0 else "optional"))
        for at, z in ((xy + shift, top), (xy + shift, initial), (xy, initial)):
            m.move(line, "rapid", prog([*at, z]))


def _block(m: _Machine, params: _Params, ln: _Line) -> str | None:
    """Run one ordinary line; returns ``"end"`` (M2/M30), ``"m97"``/``"m98"``/``"m99"``, ``"g65"`` or None."""
    words, sets = _words(ln.text, params, inch=m.scale != 1.0)
    if m.parameter_input:  # Fanuc G10 L50: N<parameter> R<value> lines up to G11
        m.parameter_input = 110 not in _codes(words, "g")
        return None
    for key, value in sets:
        params.set(key, value)
        if m.ctx.dialect.name in ("fanuc", "haas"):
            _offset_variable(m, key, value)
    g, mc = _codes(words, "g"), _codes(words, "m")
    m.block_moves = m.block_nonmodal = False
    if 660 in g and m.ctx.dialect.name == "fanuc":  # Fanuc G66 modal macro call: its words are the arguments
        if m.ctx.decimal_point_input == "increment":
            _least_increments(m, g, words, ln.text)
        return "g66"
    if 670 in g and m.ctx.dialect.name == "fanuc":
        m.modal_call = None
    for value in words.pop("$", []):  # LinuxCNC's spindle of S/M3-M5/M19/G33 (m-code.adoc "M3, M4, M5": "M3 $0
        # S1000", $-1 all of them); one spindle here, $0 or $-1 (rs274 takes the integer part: "M3 $0.9" runs)
        if m.ctx.dialect.name != "linuxcnc" or int(value) not in (0, -1):
            raise ReferenceError(f"line {ln.number}: spindle word ${value:g}")
    if 980 in mc and m.ctx.dialect.name == "linuxcnc":  # an M98 block is the call alone: its F, S, X.. do not run
        return "m98"
    if 650 in g:  # Fanuc/Haas G65 macro call: run by iso_reference (the called program, its arguments as locals)
        return "g65"
    if "t" in words:
        m.selected = int(words["t"][-1])
        dotted = re.search(r"T\s*(\d+)\.(\d+)", ln.text, re.I) if m.ctx.dialect.name == "fanuc" else None
        if dotted:  # Fagor T<tool>.<offset> (the 8055's T D): G43 / G41 without H / D take that offset
            m.offsets_of[int(dotted.group(1))] = int(dotted.group(2))
    if m.ctx.dialect.name == "linuxcnc":
        for code in mc:
            if code in (700, 710, 720, 730):
                _modal_state(m, code // 10)
    if 60 in mc:
        m.loaded = m.selected
    if (60 in mc or 610 in mc) and m.ctx.dialect.name == "linuxcnc":
        m.reread = m.comp_closed
    if 62 in g:  # Fanuc G06.2 NURBS: its curve is not modelled here
        raise ReferenceError("G06.2 NURBS")
    if 40 in g:
        m.out.append(Expected(line=ln.number, kind="dwell", end=m.pos.copy()))
        # G04 X<s> alone: X is the dwell time (Fanuc, Haas); with a motion code ("G4 P.001 G0 X1") X is that
        # motion's, and under LinuxCNC and grbl with P also without one ("G4 P0.5 X3": the modal motion,
        # enhance_block; grbl's implicit motion mode)
        if not any(c in (0, 10, 20, 30) for c in g) and not ("p" in words and m.ctx.dialect.name in ("linuxcnc",
                                                                                                      "grbl")):
            words.pop("x", None)
    if m.ctx.dialect.name == "fanuc" and m.ctx.decimal_point_input == "increment":
        _least_increments(m, g, words, ln.text)
    _modes(m, g, words, ln.text)
    if m.ctx.dialect.name in ("fanuc", "haas") and (682 in g or 531 in g or m.tilted is not None):
        _tilted_plane(m, ln.number, g, words)
    if m.ctx.dialect.name == "fanuc" and (150 in g or 160 in g or m.polar16):
        _fanuc_polar(m, g, words)
    axes = any(a in words for a in "xyz@^abcuvw")  # a block with only A-W words moves (X Y Z stay)
    if m.ctx.dialect.name == "fanuc":
        _rigid_tap(m, ln.number, g, mc, words)
    used = _non_modal(m, ln.number, g, words)
    count, start = len(m.out), m.pos.copy()
    m.block_moves, m.block_nonmodal = axes and not used, axes and used
    if not used:
        _motion(m, ln.number, g, words, axes)
    if m.rigid_at is not None:
        _rigid_tap_after(m, ln.number, any(e.kind != "dwell" for e in m.out[count:]))
    if m.arc3d is not None and m.arc3d[1] != ln.number and words:  # a block between G02.4's two (not a macro line)
        raise ReferenceError(f"line {ln.number}: a block between a G02.4/G03.4 intermediate point and its end point")
    if m.corner is not None and len(m.out) > count:
        _corner(m, count)
    for key in (",r", ",c"):
        if key in words:
            m.corner = (key, words[key][-1] * m.scale * float(np.mean(np.abs(m.factors))), start)
    if any(c in (20, 300) for c in mc):
        return "end"
    if 980 in mc:
        return "m98"
    if 970 in mc:
        return "m97"
    if 990 in mc:
        return "m99"
    return None


def _rigid_tap(m: _Machine, line: int, g: list[int], mc: list[int], words: dict) -> None:
    """Fanuc M29 rigid tapping (0i-B connection manual B-63833EN "Rigid tapping": "M29 S1000 ; G84 Z-100. R-20. F1.
    ; ... G80 ;"; the operator's manuals' limitations and alarm list as we read them): G80, a group 01 code or
    another canned cycle ends the rigid mode and clears the S of a tap that ran (an S word since, or in the block, is
    kept);
    M29 arms it for the next G84/G74, which needs S > 0 (alarm PS0200); the program end ends it."""
    tapping = (740, 840)
    motion_code = any(c in (0, 10, 20, 30, 800) or c // 10 in _CYCLES + _MILL_CYCLES for c in g)
    if 290 in mc and m.motion in tapping and not motion_code:  # alarm 0203: M29 after its tapping command
        raise ReferenceError(f"line {line}: M29 while a tapping cycle is in force (Fanuc alarm 0203)")
    ends = [c for c in g if c in (0, 10, 20, 30, 800) or c // 10 in _CYCLES + _MILL_CYCLES and c not in tapping]
    block_cycle = next((c for c in reversed(g) if c == 800 or c // 10 in _CYCLES + _MILL_CYCLES), m.motion)
    if "s" in words and m.rigid and m.rigid_at not in (None, line) and 290 not in mc and block_cycle not in tapping \
            and not ends and 20 not in mc and 300 not in mc:  # alarm 0203: an S between M29 and its tap
        raise ReferenceError(f"line {line}: S word between M29 and G84/G74 (Fanuc alarm 0203)")
    if m.rigid and (ends or 20 in mc or 300 in mc) and 290 not in mc:
        if m.rigid_at is None and m.spindle == m.rigid_s:  # no S word since the tap
            m.spindle = 0.0
        m.rigid = False
    if "s" in words:
        m.spindle = words["s"][-1]
    if 290 in mc:
        m.rigid, m.rigid_at = True, line
    cycle = next((c for c in reversed(g) if c == 800 or c // 10 in _CYCLES + _MILL_CYCLES), m.motion)
    if m.rigid and cycle in tapping and not m.spindle > 0:
        raise ReferenceError(f"line {line}: G84/G74 after M29 with S0 (Fanuc alarm PS0200)")
    series_q = m.cycle_clear is not None and "q" in m.sticky  # Q is modal hole data until G80
    if m.rigid and cycle in tapping and ("q" in words or series_q) and m.ctx.dialect.peck_tapping is None:
        # 0i-F "Peck rigid tapping cycle": PCP (No. 5200#5) and d (No. 5213) are the machine's, not stated
        raise ReferenceError(f"line {line}: G84/G74 Q after M29 (Fanuc peck rigid tapping, PCP and d not stated)")


def _rigid_tap_after(m: _Machine, line: int, moved: bool) -> None:
    """After a block while an M29 waits for its G84/G74: the tap takes it; an axis movement in a later block is
    Fanuc's alarm PS0204 (:func:`_rigid_tap`)."""
    if m.rigid and m.motion in (740, 840):
        m.rigid_at, m.rigid_s = None, m.spindle
    elif moved and line != m.rigid_at:
        raise ReferenceError(f"line {line}: axis movement between M29 and G84/G74 (Fanuc alarm PS0204)")
    elif not m.rigid:
        m.rigid_at = None


def _least_increments(m: _Machine, g: list[int], words: dict, text: str) -> None:
    """Fanuc DPI = 0 (0i-MF operator's manual B-64604EN "Decimal point programming", parameter No. 3401#0): a
    distance or angle written without a decimal point counts least input increments of IS-B, 0.001 mm / deg or
    0.0001 in (X Y Z U V W A B C I J K Q R and the corner words ,R ,C; ``G04 X`` 0.001 s; K of a cycle block is
    its repeat count); in a G51 block its centre X Y Z (its factors: :func:`_mirror_scaling`). G65 and G66
    arguments without a decimal point are not modelled (ReferenceError)."""
    # G51: the centre, its factors have their own rule; ",r" ",c": corner lengths, as r (our reading)
    letters = set("xyz") if 510 in g else {*"xyzuvwabcijkqr", ",r", ",c"}
    if 650 in g or 660 in g:
        if re.search(r"(?<![a-z#])[xyzuvwabcijkqr][+-]?\d+(?![\d.])", text):
            raise ReferenceError("G65/G66 arguments without a decimal point under DPI = 0")
        return
    inch = 200 in g or 210 not in g and m.scale != 1.0
    cycle = any(c is not None and c % 10 == 0 and c // 10 in _CYCLES + _MILL_CYCLES for c in [m.motion, *g])
    seen: dict[str, int] = {}
    depth = 0
    for k, ch in enumerate(text):
        depth += (ch == "[") - (ch == "]")
        if not ch.isalpha() or depth:
            continue
        letter = "," + ch if k and text[k - 1] == "," else ch
        index = seen.get(letter, 0)
        seen[letter] = index + 1
        literal = re.match(r"[+-]?\d+(?![\d.#\[])", text[k + 1:])
        if letter not in letters or literal is None or (k and text[k - 1].isalpha()) or letter == "k" and cycle \
                or letter not in words or index >= len(words[letter]):
            continue
        unit = 0.001 if letter in "abc" or not inch or (40 in g and letter == "x") else 0.0001
        words[letter][index] *= unit


#: What LinuxCNC's M70 saves (m-code.adoc "M70 Saved state") of what this reference models.
_SAVED = ("scale", "plane", "incremental", "arc_absolute", "wcs", "tool_length", "tool_xy", "retract", "comp_radius")


def _modal_state(m: _Machine, code: int) -> None:
    """LinuxCNC M70 / M73 save the modal state at the call level, M71 forgets it, M72 restores it (m-code.adoc
    "M70" - "M73"; M72 with nothing saved: LinuxCNC refuses it, the reader runs on: nothing restored here)."""
    if code in (70, 73):
        m.saved_states[m.level] = ({k: copy.copy(getattr(m, k)) for k in _SAVED}, code == 73)
    elif code == 71:
        m.saved_states.pop(m.level, None)
    elif m.level in m.saved_states:
        _restore(m, m.saved_states[m.level][0])


def _restore(m: _Machine, state: dict) -> None:
    if state["comp_radius"] != m.comp_radius:
        raise ReferenceError("M72/M73 restoring cutter compensation")
    for k, v in state.items():
        setattr(m, k, copy.copy(v))


def _call_level(m: _Machine, level: int) -> None:
    """After an O-word line: a subroutine returned from restores the state its M73 saved (m-code.adoc "M73")."""
    while m.level > level:
        state = m.saved_states.pop(m.level, None)
        if state is not None and state[1]:
            _restore(m, state[0])
        m.level -= 1
    m.level = level


def _corner(m: _Machine, n: int) -> None:
    """Fanuc/Haas ``,R r`` / ``,C c`` (Fanuc 0i-MF operator's manual "Optional chamfering and corner R";
    Haas mill operator's manual "G01 Corner Rounding and Chamfering") between two straight feed moves
    in the plane (next to an arc: :func:`_arc_corner`), the rows ``n - 1`` (the block with the word, from
    its start ``a`` to the corner) and ``n``: the first ends where the corner begins, and a row of the
    first's line is put in between.
    With the turn angle ``t`` between the unit directions ``u1``, ``u2``: a rounding touches each line
    ``r tan(t/2)`` from the corner and its centre lies ``r / cos(t/2)`` from the corner along the
    bisector ``u2 - u1``; a chamfer runs from ``c`` before the corner to ``c`` after it."""
    (key, size, a), m.corner = m.corner, None
    first, second = m.out[n - 1], m.out[n]
    if {"arc_cw", "arc_ccw"} & {first.kind, second.kind} and first.element is None and second.element is None:
        _arc_corner(m, n, key, size, a)
        return
    for row in (first, second):
        if (row.kind if row.element is None else row.element[0]) not in ("feed", "line"):
            raise ReferenceError("a ,R / ,C next to a rapid, or next to an arc under G41/G42")
    corner, b = first.end, second.end  # the programmed points (under G41/G42 too)
    i, j = first.plane
    u1 = np.array([corner[i] - a[i], corner[j] - a[j]])
    u2 = np.array([b[i] - corner[i], b[j] - corner[j]])
    u1, u2 = u1 / np.linalg.norm(u1), u2 / np.linalg.norm(u2)
    turn = math.acos(max(-1.0, min(1.0, float(u1 @ u2))))
    along = size * math.tan(turn / 2) if key == ",r" else size
    t1, t2 = corner.copy(), corner.copy()
    t1[[i, j]] = corner[[i, j]] - along * u1
    t2[[i, j]] = corner[[i, j]] + along * u2
    if key == ",r":
        bisector = (u2 - u1) / np.linalg.norm(u2 - u1)
        centre = corner.copy()
        centre[[i, j]] = corner[[i, j]] + size / math.cos(turn / 2) * bisector
        kind = "arc_ccw" if u1[0] * u2[1] - u1[1] * u2[0] > 0 else "arc_cw"
    else:
        centre, kind = None, "feed"
    inserted = dataclasses.replace(first, kind=kind if first.element is None else None, end=t2, centre=centre,
                                   centre_tolerance=1e-6 if centre is not None else 0.0, entry=False)
    first = dataclasses.replace(first, end=t1)
    if first.element is not None:  # G41/G42: the rows' ends lie one radius from the programmed elements
        first = dataclasses.replace(first, element=("line", first.element[1], t1))
        inserted = dataclasses.replace(inserted, element=("arc", centre, size, first.plane, t1, 0.0)
                                       if centre is not None else ("line", t1, t2))
        m.out[n] = dataclasses.replace(second, element=("line", t2, second.element[2]))
    m.out[n - 1] = first
    m.out.insert(n, inserted)


def _arc_corner(m: _Machine, n: int, key: str, size: float, a: np.ndarray) -> None:
    """``,R`` / ``,C`` next to an arc (Fanuc): found by search, not construction. The rounding's centre is
    any point ``size`` from both elements (on a line's two parallels, on an arc's circles of radius
    ``R + size`` and ``R - size``) whose feet lie on the elements, where the rounding runs on in both
    elements' directions; of those the nearest the corner. A chamfer's ends are the points of the
    elements at the chord ``size`` from the corner (NCT 2000M manual 16.1: on an arc ",C is the length
    of the chord drawn from intersection")."""
    first, second = m.out[n - 1], m.out[n]
    if "rapid" in (first.kind, second.kind):
        raise ReferenceError("a ,R / ,C next to a rapid")
    i, j = first.plane
    corner = first.end[[i, j]]
    els = [_element(first, a[[i, j]], corner, (i, j)), _element(second, corner, second.end[[i, j]], (i, j))]
    if key == ",c":
        ends = [_chord_point(el, corner, size) for el in els]
        inserted = dataclasses.replace(first, kind="feed", end=_lift(first.end, ends[1], (i, j)), centre=None,
                                       centre_tolerance=0.0)
        m.out[n - 1] = dataclasses.replace(first, end=_lift(first.end, ends[0], (i, j)))
        m.out.insert(n, inserted)
        return
    best = None
    for c in _offset_meets(els[0], els[1], size):
        feet = [_foot(el, c) for el in els]
        if not all(_on(el, f) for el, f in zip(els, feet)):
            continue
        d1, d2 = _heading(els[0], feet[0]), _heading(els[1], feet[1])
        ccw = d1[0] * d2[1] - d1[1] * d2[0] > 0
        runs = [np.array([-(f - c)[1], (f - c)[0]]) / size * (1 if ccw else -1) for f in feet]
        if runs[0] @ d1 > 1 - 1e-9 and runs[1] @ d2 > 1 - 1e-9 and (
                best is None or np.linalg.norm(c - corner) < np.linalg.norm(best[0] - corner)):
            best = (c, feet, ccw)
    if best is None:
        raise ReferenceError("no rounding of that radius fits")
    c, feet, ccw = best
    inserted = dataclasses.replace(first, kind="arc_ccw" if ccw else "arc_cw", end=_lift(first.end, feet[1], (i, j)),
                                   centre=_lift(first.end, c, (i, j)), centre_tolerance=1e-6)
    m.out[n - 1] = dataclasses.replace(first, end=_lift(first.end, feet[0], (i, j)))
    m.out.insert(n, inserted)


def _lift(like: np.ndarray, p: np.ndarray, plane: tuple[int, int]) -> np.ndarray:
    out = like.copy()
    out[list(plane)] = p
    return out


def _element(row: Expected, start: np.ndarray, end: np.ndarray, plane: tuple[int, int]) -> tuple:
    """A row in the plane: ``("line", start, end)`` or ``("arc", centre, radius, ccw, start, end)``."""
    if row.kind == "feed":
        return ("line", start, end)
    o = row.centre[list(plane)]
    return ("arc", o, float(np.linalg.norm(start - o)), row.kind == "arc_ccw", start, end)


def _heading(el: tuple, p: np.ndarray) -> np.ndarray:
    if el[0] == "line":
        return (el[2] - el[1]) / np.linalg.norm(el[2] - el[1])
    r = p - el[1]
    return np.array([-r[1], r[0]]) / np.linalg.norm(r) * (1 if el[3] else -1)


def _angle_along(el: tuple, p: np.ndarray) -> float:
    """Angle [rad] from an arc's start to ``p`` in its direction of travel, in [0, 2 pi)."""
    v0, v = el[4] - el[1], p - el[1]
    ang = math.atan2(v0[0] * v[1] - v0[1] * v[0], v0 @ v) * (1 if el[3] else -1)
    return ang % (2 * math.pi)


def _on(el: tuple, p: np.ndarray) -> bool:
    if el[0] == "line":
        t = (p - el[1]) @ (el[2] - el[1]) / ((el[2] - el[1]) @ (el[2] - el[1]))
        return -1e-9 <= t <= 1 + 1e-9
    sweep = _angle_along(el, el[5]) or 2 * math.pi
    return _angle_along(el, p) <= sweep + 1e-9 or _angle_along(el, p) > 2 * math.pi - 1e-9


def _foot(el: tuple, c: np.ndarray) -> np.ndarray:
    if el[0] == "line":
        u = (el[2] - el[1]) / np.linalg.norm(el[2] - el[1])
        return el[1] + u * ((c - el[1]) @ u)
    return el[1] + (c - el[1]) * el[2] / np.linalg.norm(c - el[1])


def _offset_meets(e1: tuple, e2: tuple, r: float) -> list[np.ndarray]:
    """Points at distance ``r`` from both elements (their offsets on either side, intersected)."""
    def offsets(el):
        if el[0] == "line":
            u = (el[2] - el[1]) / np.linalg.norm(el[2] - el[1])
            nrm = np.array([-u[1], u[0]])
            return [("l", el[1] + s * r * nrm, u) for s in (1, -1)]
        return [("c", el[1], el[2] + s * r) for s in (1, -1) if el[2] + s * r > 0]
    out = []
    for o1 in offsets(e1):
        for o2 in offsets(e2):
            out += _meet(o1, o2)
    return out


def _meet(o1: tuple, o2: tuple) -> list[np.ndarray]:
    if o1[0] == "c" and o2[0] == "l":
        o1, o2 = o2, o1
    if o1[0] == "l" and o2[0] == "l":
        (p, u), (q, v) = o1[1:], o2[1:]
        den = u[0] * v[1] - u[1] * v[0]
        if abs(den) < 1e-12:
            return []
        t = ((q - p)[0] * v[1] - (q - p)[1] * v[0]) / den
        return [p + t * u]
    if o1[0] == "l":
        (p, u), (o, rad) = o1[1:], o2[1:]
        w = p - o
        b, cc = w @ u, w @ w - rad * rad
        disc = b * b - cc
        return [] if disc < 0 else [p + (-b + s * math.sqrt(disc)) * u for s in (1, -1)]
    (o, r1), (q, r2) = o1[1:], o2[1:]
    d = float(np.linalg.norm(q - o))
    if d < 1e-12 or d > r1 + r2 or d < abs(r1 - r2):
        return []
    x = (d * d + r1 * r1 - r2 * r2) / (2 * d)
    h = math.sqrt(max(r1 * r1 - x * x, 0.0))
    e = (q - o) / d
    return [o + x * e + s * h * np.array([-e[1], e[0]]) for s in (1, -1)]


def _chord_point(el: tuple, corner: np.ndarray, c: float) -> np.ndarray:
    """The point of the element ``c`` (a chord) from the corner, on the element."""
    if el[0] == "line":
        u = (el[2] - el[1]) / np.linalg.norm(el[2] - el[1])
        return corner - c * u if np.allclose(el[2], corner) else corner + c * u
    for p in _meet(("c", corner, c), ("c", el[1], el[2])):
        if _on(el, p):
            return p
    raise ReferenceError("no chamfer of that length fits")


#: A Fanuc outside corner of at most this turn [rad] whose offsets do not meet (a tangent arc off by rounding) keeps
#: the one-radius check: vcnc leaves it to LinuxCNC's rule (our reading; Fanuc's own small-vector limits are
#: parameters of the machine).
_TANGENT_TURN = 0.05


def fanuc_corner(out: list[Expected], r: float) -> None:
    """Fanuc's cutter compensation C ("Tool movement in offset mode", Fanuc 0i-MF/0i-MD operator's manual) at
    the corner the last compensated block of ``out`` makes with the one before it (rows along the plane's
    normal only in between stand where that one ends). With ``t1``, ``t2`` the tangents at the corner ``P``
    and ``n1``, ``n2`` the vectors of length ``r`` to the tool side perpendicular to them: an inside corner
    keeps the one-radius check; an outside corner turned by at most 90 degrees (``alpha >= 90``) ends where
    the two offset paths (lines through ``P + n``, circles about the arc centres) cross, the crossing nearest
    ``P``; a sharper one (``alpha < 90``) ends a line at ``P + n1 + r t1`` (an arc at ``P + n1``, checked by
    the radius), as do obtuse ones whose offsets do not cross. A reversal next to an arc (within
    :data:`_TANGENT_TURN` of 180 degrees) is inside or outside by the arc's curvature, not the tangents: it
    keeps the one-radius check."""
    b, k = out[-1], len(out) - 2
    i, j = b.plane

    def flat(e: Expected) -> bool:
        return e.element[0] == "line" and not np.any(e.element[2][[i, j]] - e.element[1][[i, j]])

    if flat(b):
        return
    between = []
    while k >= 0 and out[k].element is not None and flat(out[k]) and not out[k].entry:
        between.append(k)
        k -= 1
    if k < 0 or out[k].element is None or out[k].entry or out[k].side != b.side or out[k].plane != b.plane:
        return
    a, p = out[k], out[k].end[[i, j]]
    t1, t2 = _comp_tangent(a, p), _comp_tangent(b, p)
    sgn = 1.0 if a.side == "left" else -1.0
    cross, dot = float(t1[0] * t2[1] - t1[1] * t2[0]), float(t1 @ t2)
    if not (sgn * cross < -1e-12 or abs(cross) <= 1e-12 and dot < 0):
        return  # an inside corner or no turn
    if dot < 0 and abs(cross) < math.sin(_TANGENT_TURN) and "arc" in (a.element[0], b.element[0]):
        return  # a reversal next to an arc: inside or outside by the curvature ("h", "m" shapes): one radius
    q1 = p + r * sgn * np.array([-t1[1], t1[0]])
    q2 = p + r * sgn * np.array([-t2[1], t2[0]])
    slack = sum(e.element[5] for e in (a, b) if e.element[0] == "arc")
    x, tol = None, 1e-6 + 2.0 * slack / max(abs(cross), 0.05)
    if dot >= 0:
        offsets = [("l", q, t) if e.element[0] == "line" else ("c", e.element[1][[i, j]],
                                                               float(np.linalg.norm(q - e.element[1][[i, j]])))
                   for e, q, t in ((a, q1, t1), (b, q2, t2))]
        meets = _meet(*offsets)
        if meets:
            x = min(meets, key=lambda c: float(np.linalg.norm(c - p)))
        elif math.acos(min(dot, 1.0)) <= _TANGENT_TURN:
            return
    if x is None:
        if a.element[0] == "arc":
            return
        x = q1 + r * t1
    for m in (k, *between):
        out[m] = dataclasses.replace(out[m], corner=_lift(out[m].end, x, (i, j)), corner_tolerance=tol)


def _comp_tangent(e: Expected, p: np.ndarray) -> np.ndarray:
    """Unit tangent of a compensated block's programmed element at its point ``p`` (in its plane)."""
    i, j = e.plane
    if e.element[0] == "line":
        d = (e.element[2] - e.element[1])[[i, j]]
        return d / np.linalg.norm(d)
    v = p - e.element[1][[i, j]]
    t = np.array([-v[1], v[0]]) if e.ccw else np.array([v[1], -v[0]])
    return t / np.linalg.norm(t)


def _fanuc_polar(m: _Machine, g: list[int], words: dict) -> None:
    """Fanuc G16 (Series 16/18-MC operator's manual 9.2): X Y of a motion block are the radius and the
    angle about the work zero, as ``@ ^`` under G90; G15 cancels."""
    if 150 in g or 160 in g:
        m.polar16 = 160 in g
    if not m.polar16 or any(c in g for c in (100, 280, 300, 520, 530, 920, 680, 510)):
        return
    if m.plane != 17 or m.incremental:
        raise ReferenceError("G16 outside G17 / under G91")
    for a, b in (("x", "@"), ("y", "^")):
        if a in words:
            words[b] = words.pop(a)


def iso_reference(text: str, context, *, resolve=None) -> list[Expected]:
    """The expected ``--blocks`` rows of an ISO program run against ``context``.

    Parameters
    ----------
    text : str
        The program.
    context : interpolators.context.MachineContext
        The tables the reader is given (work offsets, tools, home, second reference, dialect).
    resolve : callable, optional
        ``resolve("1002")`` gives the text of a numbered subprogram ``O1002`` that ``M98 P1002``
        calls and the file does not hold (a Fanuc control has it in its memory), or None.

    Returns
    -------
    list of Expected
        One entry per motion or dwell, in order.

    Raises
    ------
    ReferenceError
        The program uses a feature this reference does not model.
    """
    fadal = context.dialect.name == "fadal"
    if fadal:  # Fadal's own words in a pass over the lines (_fadal_lines), Fanuc's rules for the rest
        context = dataclasses.replace(context, dialect=dataclasses.replace(context.dialect, name="fanuc"))
    fanuc = context.dialect.name == "fanuc"
    lines = _lines(text.lstrip("\ufeff"), grbl=context.dialect.name == "grbl", fanuc=fanuc,
                   linuxcnc=context.dialect.name == "linuxcnc")
    if fadal:
        lines = _fadal_lines(lines)
    own = {str(int(ln.oname)) if ln.oname.isdigit() else ln.oname for ln in lines
           if ln.oname is not None and ln.okey is None}
    for target in sorted({str(int(float(v))) for ln in lines for v in re.findall(r"(?:m0*98|g0*65)p(\d+)", ln.text)}
                         - own):
        other = resolve(target) if resolve is not None else None
        if other is not None:  # a numbered subprogram from its own file (Fanuc: in the control's memory)
            lines += _lines(other.lstrip("\ufeff"), fanuc=fanuc)
    st = _structure(lines)
    m, params = _Machine(context), _Params(vacant=context.dialect.name in ("fanuc", "haas"))
    m.fadal = fadal
    if context.dialect.name in ("fanuc", "haas"):
        params.system = lambda key: _modal_information(m, key)
    frames: list[dict] = []
    counters: dict[int, int] = {}
    percent = 0
    pc, steps = 0, 0
    while pc < len(lines):
        steps += 1
        if steps > 5_000_000:
            raise ReferenceError("more than 5e6 lines executed")
        ln = lines[pc]
        if ln.text.startswith("%"):
            percent += 1
            if percent == 2:
                break
            pc += 1
            continue
        if ln.oname is not None:
            pc = _oword(ln, pc, st, params, frames, counters)
            if context.dialect.name == "linuxcnc":
                _call_level(m, len(params.frames) - 1)
            if pc < 0:
                break
            continue
        if ln.macro is not None:
            pc, ln = _macro(ln, pc, st, params, haas=context.dialect.name == "haas")  # ln: a Haas THEN block
            if ln is None:
                continue
        if not ln.text:
            pc += 1
            continue
        if ln.text == "$h":  # grbl limits.c limits_go_home, config.h HOMING_CYCLE_0 (Z) then _1 (X Y)
            for axes in ((2,), (0, 1)):
                end = m.pos.copy()
                end[list(axes)] = np.asarray(context.home, float)[list(axes)]
                m.emit(ln.number, "rapid", end, rows="optional" if np.allclose(end, m.pos) else "one")
            pc += 1
            continue
        res = _block(m, params, ln)
        if res == "end":
            break
        called = _call(res, m, ln, pc, st, params, frames, fanuc=fanuc)
        if called is not None:
            pc = called
            continue
        if res == "m99":
            if not frames or frames[-1]["kind"] not in ("m98", "g65", "g66"):
                break
            pc = _m99_return(ln, pc, frames, st, params, haas=context.dialect.name == "haas")
            continue
        pc += 1
    return m.out


def _call(res, m: _Machine, ln, pc: int, st, params, frames: list[dict], *, fanuc: bool) -> int | None:  # noqa: ANN001
    """The line to run next after a block that calls: M98/M97, G65, G66 (the modal call set) and a move under G66
    (the call made); None for a block that calls nothing."""
    if res in ("m98", "m97"):
        frame = _subprogram_call(res, ln, pc, st, params, fanuc=fanuc)
        if frame["left"] < 0:  # L0: no call (LinuxCNC tests/interp/m98m99/05-M98-loops, "Test with 0 loops")
            return pc + 1
        frames.append(frame)
        return frame["start"]
    if res == "g65":
        frames.append(_g65_call(ln, pc, st, params))
        return frames[-1]["start"]
    if res == "g66":
        if m.modal_call is not None or frames:
            raise ReferenceError(f"line {ln.number}: G66 nested or within a call (not modelled here)")
        m.modal_call = _g66_words(ln, params)
        return pc + 1
    if res is None and m.modal_call is not None and (m.block_moves or m.block_nonmodal) \
            and not any(f["kind"] == "g66" for f in frames):  # the called program's moves call nothing
        if m.block_nonmodal or frames:
            raise ReferenceError(f"line {ln.number}: a G28/G92/G10 block, or a move in a call, under G66")
        frames.append(_g66_call(m.modal_call, pc, st, params))
        return frames[-1]["start"]
    return None


def _m99_return(ln, pc: int, frames: list[dict], st, params, *, haas: bool = False) -> int:  # noqa: ANN001
    """The line an M99 (line ``pc``) goes on at in an M98 or G65 frame: the called program again while repeats are
    left, else the caller's next line (or its block N<n> for an M99 P<n>, Fanuc B-64304EN "Subprogram"); a G65's
    locals #1-#33 as they were. Haas's M99 P<n> branches to N<n> of the subprogram it stands in, the call still
    open (Haas mill operator's manual 96-8000 "Conditional Expressions": "M99 in the HAAS control has the ability to
    branch unconditionally to any line in the current subroutine ... It does not return control to the calling
    subroutine")."""
    f = frames[-1]
    if f["kind"] == "g66" and f["left"] > 0:  # L repeats: the program again, its locals the arguments afresh
        f["left"] -= 1
        params.numbered = {k: v for k, v in params.numbered.items() if not 1 <= k <= 33} | f["args"]
        return f["start"]
    if f["kind"] in ("g65", "g66"):
        frames.pop()
        params.numbered = {k: v for k, v in params.numbered.items() if not 1 <= k <= 33} | f["saved"]
        return f["ret"]
    words, _ = _words(ln.text, params)
    if haas and "p" in words:
        return _goto(words["p"][-1], pc, st)
    if f["left"] > 0:
        f["left"] -= 1
        return f["start"]
    frames.pop()
    return _goto(words["p"][-1], f["ret"] - 1, st) if "p" in words else f["ret"]


def _subprogram_call(res: str, ln, pc: int, st, params, *, fanuc: bool = False) -> dict:  # noqa: ANN001
    """The frame of an M98 (``P`` a program, or ``Q`` a block of this one) or a Haas M97 ("M97 Local Sub-Program
    Call": N<P> of this program) call, run L times to its M99. Fanuc ``M98 P51002`` without L and without an
    ``O51002`` calls ``O1002`` five times (0i-MC operator's manual B-64124EN 12.3 "Subprogram")."""
    words, _ = _words(ln.text, params)
    count = int(words["l"][-1]) if "l" in words else 1
    p = int(words["p"][-1]) if res == "m98" and "p" in words else 0
    if fanuc and p >= 10000 and not {"l", "q"} & set(words) and str(p) not in st["fanuc"] \
            and str(p % 10000) in st["fanuc"]:
        count, words["p"] = p // 10000, [float(p % 10000)]
    if res == "m97":
        start = _goto(words["p"][-1], pc, st)
    else:
        start = _m98_start(words, st) if "p" in words else _goto(words["q"][-1], pc, st)
    return {"kind": "m98", "ret": pc + 1, "start": start, "left": count - 1}


#: G65 argument addresses and the locals they set (Fanuc "Argument specification I"; Haas "Local Variables").
_G65_LOCALS = {"a": 1, "b": 2, "c": 3, "i": 4, "j": 5, "k": 6, "d": 7, "e": 8, "f": 9, "h": 11, "m": 13,
               **{c: 17 + i for i, c in enumerate("qrstuvwxyz")}}


def _g65_call(ln: _Line, pc: int, st: dict, params: _Params) -> dict:
    """``G65 P<program> <arguments>`` (Fanuc 0i-MD B-64304EN "Simple call (G65)"): the program's frame, the
    caller's locals #1-#33 kept aside, the arguments set as the called program's (the others vacant)."""
    words, _ = _words(ln.text, params)
    if "l" in words or any(len(words[a]) > 1 for a in "ijk" if a in words):
        raise ReferenceError("G65 with L repeats or several I J K sets")
    start = _m98_start({"p": words["p"]}, st)
    saved = {k: v for k, v in params.numbered.items() if 1 <= k <= 33}
    params.numbered = {k: v for k, v in params.numbered.items() if not 1 <= k <= 33}
    for letter, number in _G65_LOCALS.items():
        if letter in words:
            params.numbered[number] = words[letter][-1]
    return {"kind": "g65", "ret": pc + 1, "start": start, "saved": saved}


def _modal_information(m: _Machine, key: int) -> float | None:
    """Fanuc/Haas modal information of the blocks run so far (Fanuc 0i-MD B-64304EN "System variables", "Modal
    information": ``#4001`` group 01 G00-G03, ``#4002`` 17/18/19, ``#4003`` 90/91, ``#4006`` 20/21, ``#4014`` the
    work system 54-59 (Fanuc 54.1 for G54.1 P); Haas "Macros", "#4001-#4021 last block group codes"); None for the
    others (not modelled here)."""
    if key == 4001 and m.linear in (0, 10, 20, 30):
        return m.linear / 10.0
    if key == 4002:
        return float(m.plane)
    if key == 4003:
        return 91.0 if m.incremental else 90.0
    if key == 4006:
        return 20.0 if m.scale != 1.0 else 21.0
    if key == 4014 and m.wcs in list(_WCS.values())[:6]:
        return float(m.wcs[1:])
    if key == 4014 and m.wcs.startswith("G54.1") and m.ctx.dialect.name == "fanuc":
        return 54.1
    return None


def _g66_words(ln: _Line, params: _Params) -> dict:
    """``G66 P<program> L<repeats> <arguments>`` (Fanuc 0i-MD B-64304EN "Modal call: call after the move command
    (G66)": "Once G66 is issued to specify a modal call a macro is called after a block specifying movement along
    axes is executed. This continues until G67 is issued to cancel a modal call"; "Local variables (arguments) can
    only be set in G66 blocks"; the addresses of "Argument specification I", as G65): what each call runs."""
    words, _ = _words(ln.text, params)
    if any(len(words[a]) > 1 for a in "ijk" if a in words):
        raise ReferenceError("G66 with several I J K sets")
    args = {number: words[letter][-1] for letter, number in _G65_LOCALS.items() if letter in words}
    return {"p": words["p"], "count": int(words["l"][-1]) if "l" in words else 1, "args": args}


def _g66_call(call: dict, pc: int, st: dict, params: _Params) -> dict:
    """The frame of one G66 modal call after the move of line ``pc``: as a G65 call (the caller's locals kept
    aside, the G66 block's arguments the called program's), run L times."""
    saved = {k: v for k, v in params.numbered.items() if 1 <= k <= 33}
    params.numbered = {k: v for k, v in params.numbered.items() if not 1 <= k <= 33} | call["args"]
    return {"kind": "g66", "ret": pc + 1, "start": _m98_start({"p": call["p"]}, st), "saved": saved,
            "left": call["count"] - 1, "args": call["args"]}


def _offset_variable(m: _Machine, key: str | int, value: float) -> None:
    """A Fanuc/Haas work offset system variable written by the program: the offset changes at once, as a ``G10
    L2`` under G90 would, in the machine's length unit (Fanuc 0i-MD B-64304EN "System variables": ``#5201``-
    ``#5206`` the external workpiece zero point offset, ``#5221``-``#5226`` G54 up to ``#5321``-``#5326`` G59,
    ``#7001``-``#7006`` G54.1 P1, 20 apart, "read/write"; Haas mill operator's manual "Macros": ``#5201``.. G52,
    ``#5221``.. G54-G59, ``#7001``-``#7006`` G110 (G154 P1), 20 apart). X Y Z only here."""
    if not isinstance(key, int) or math.isnan(value):
        return
    unit = 25.4 if m.ctx.linear_units == "inch" else 1.0
    if 5201 <= key <= 5203:
        i = key - 5201
        m.g92[i] += value * unit - m.external[i]
        m.external[i] = value * unit
        return
    if 5221 <= key < 5341:
        code, axis = list(_WCS.values())[(key - 5221) // 20], (key - 5221) % 20
    elif 7001 <= key < 7401:
        code, axis = f"G54.1 P{(key - 7001) // 20 + 1}", (key - 7001) % 20
        if code not in m.offsets:
            m.offsets[code] = np.array(m.ctx.offset(code), float)
            m.rotation[code] = 0.0
            m.extra_offsets[code] = np.zeros(6)
    else:
        return
    if axis >= 3:
        raise ReferenceError(f"#{key}: a work offset beyond X Y Z")
    m.offsets[code][axis] = value * unit


def _m98_start(words: dict, st: dict) -> int:
    """The line index an ``M98 P<program> [Q<n>]`` call starts at: the block after ``O<program>``, or with Q
    (Mitsubishi, Mach4) that program's block N<n>."""
    target = str(int(words["p"][-1]))
    if target not in st["fanuc"]:
        raise ReferenceError(f"M98 P{target}: no O{target} in the file")
    start = st["fanuc"][target] + 1
    if "q" in words:
        start = next(i for i in range(start, len(st["lines"])) if st["lines"][i].seq == int(words["q"][-1])
                     and st["program_of"].get(i) == st["program_of"].get(start))
    return start


def _macro(ln: _Line, pc: int, st: dict, params: _Params, *, haas: bool = False) -> tuple[int, _Line | None]:
    """Run a macro B statement; returns the next line index and None. GOTO n: the first line numbered Nn
    after this one in the same program, else the first from the program's start; IF [c] GOTO n /
    THEN #i=e; WHILE [c] DO m ... END m (the condition is tested at WHILE). Under ``haas`` an IF whose condition
    holds gives its own index and the line after THEN, to run as a block (Haas mill operator's manual, "Macros",
    "Conditional Execution (IF THEN)": "IF [#1 NE #0] THEN G1 X#24 Y#26 F#9")."""
    nxt = _macro_step(ln, pc, st, params, haas=haas)
    return (pc, nxt) if isinstance(nxt, _Line) else (nxt, None)


def _macro_step(ln: _Line, pc: int, st: dict, params: _Params, *, haas: bool) -> int | _Line:
    """:func:`_macro`: the next line index, or (Haas) the THEN block to run."""
    kind, rest = ln.macro
    if kind in ("do", "dprnt", "bprnt", "popen", "pclos"):
        return pc + 1
    if kind == "end":
        return st["ends"][pc]
    ev = _Eval(rest, params)
    if kind == "goto":
        return _goto(ev.chain(closed=False), pc, st)
    holds = ev.chain(closed=False)
    holds = not math.isnan(holds) and holds != 0
    if kind == "while":
        return pc + 1 if holds else st["ends"][pc] + 1
    rest = ev.s[ev.i:]
    if rest in ("then", "th"):
        raise ReferenceError("IF [..] THEN alone: a multi-line IF .. ENDIF block")
    if not holds:
        return pc + 1
    if rest.startswith("goto"):
        return _goto(_Eval(rest[4:], params).chain(closed=False), pc, st)
    if not rest.startswith("then"):
        raise ReferenceError(f"IF without GOTO/THEN: {rest[:20]!r}")
    if haas:
        return dataclasses.replace(ln, text=rest[4:], macro=None)
    words, sets = _words(rest[4:], params)
    if words:
        raise ReferenceError("NC words after THEN")
    for key, value in sets:
        params.set(key, value)
    return pc + 1


def _goto(value: float, pc: int, st: dict) -> int:
    n = math.floor(_number(value) + 0.5)
    start = st["program_of"][pc]
    same = [i for i, ln in enumerate(st["lines"]) if ln.seq == n and st["program_of"].get(i) == start]
    after = [i for i in same if i > pc]
    if not (after or same):
        raise ReferenceError(f"GOTO {n}: no N{n}")
    return (after or same)[0]


def _cond(ln: _Line, params: _Params) -> float:
    return _Eval(ln.orest, params).expr()


def _oword(ln: _Line, pc: int, st: dict, params: _Params, frames: list, counters: dict) -> int:
    """Run an O-word line; returns the next line index (-1: program end)."""
    k, ends = ln.okey, st["ends"]
    if k is None:  # a Fanuc program number: O1001 opens the main program or a numbered subprogram
        return pc + 1
    if k == "sub":
        return ends[pc] + 1
    if k == "call":
        if ln.oname not in st["subs"]:
            raise ReferenceError(f"o<{ln.oname}> call of a subroutine outside the file")
        ev, args = _Eval(ln.orest, params), []
        while ev.i < len(ev.s):
            args.append(ev.expr())
        saved = {i: params.numbered.get(i, 0.0) for i in range(1, 31)}
        for i in range(1, 31):
            params.numbered[i] = args[i - 1] if i <= len(args) else 0.0
        params.frames.append({})
        frames.append({"kind": "sub", "ret": pc + 1, "saved": saved})
        return st["subs"][ln.oname] + 1
    if k in ("endsub", "return"):
        if ln.orest:
            params.globals["_value"] = _Eval(ln.orest, params).expr()
        if not frames or frames[-1]["kind"] != "sub":
            return -1
        f = frames.pop()
        params.frames.pop()
        params.numbered.update(f["saved"])
        return f["ret"]
    if k == "if":
        if _cond(ln, params):
            return pc + 1
        for b in st["branches"][pc]:
            bl = st["lines"][b]
            if bl.okey == "else" or _cond(bl, params):
                return b + 1
        return ends[pc] + 1
    if k in ("elseif", "else"):
        return ends[pc] + 1
    if k == "endif":
        return pc + 1
    if k == "while" and pc in ends:  # while [...] ... endwhile
        return pc + 1 if _cond(ln, params) else ends[pc] + 1
    if k == "while":  # the end of a do ... while
        opener = next(j for j, e in ends.items() if e == pc)
        return opener + 1 if _cond(ln, params) else pc + 1
    if k == "endwhile":
        return next(j for j, e in ends.items() if e == pc)
    if k == "do":
        return pc + 1
    if k == "repeat":
        left = counters.get(pc)
        if left is None:
            left = int(round(_cond(ln, params)))
        if left <= 0:
            counters.pop(pc, None)
            return ends[pc] + 1
        counters[pc] = left - 1
        return pc + 1
    if k == "endrepeat":
        return next(j for j, e in ends.items() if e == pc)
    if k in ("break", "continue"):
        opener = st["owner"][pc]
        if k == "break":
            counters.pop(opener, None)
            return ends[opener] + 1
        return ends[opener] if st["lines"][opener].okey == "do" else opener
    raise ReferenceError(f"O-word {k}")
