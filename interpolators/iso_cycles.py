"""Drilling canned cycles of ISO G-code (G73, G81-G86, G89) as ordinary rapid, feed and dwell moves.

Semantics of LinuxCNC's G-code reference ("Canned Cycles",
https://linuxcnc.org/docs/html/gcode/g-code.html#gcode:g81 and interp_cycles.cc), written for the
XY plane (G17) and run in G18 / G19 on the axes permuted (:data:`CYCLE_AXES`: drilling along Y / X):

* **Preliminary motion**: if the initial level (the Z at the start of the series) is below the R
  plane, rapid up to R; then for the first hole of the block, if the tool is above R, rapid in X Y
  at its height and down to R, else rapid to the hole at the clear level and down to R.
* **Levels**: under G90 the Z word is the bottom and R the retract plane (program coordinates);
  under G91 R is an increment from the initial level of the series and Z an increment from R, and X Y
  step incrementally for each of the L (LinuxCNC) or K (Fanuc) repeats. Under G90, L repeats drill
  the same hole.
* **Return**: G99 to the R plane; G98 to the higher of R and the Z at the start of the series of
  contiguous cycles (the "initial level").
* **Holes**: G81 feed to Z, rapid out; G82 also dwells P; G83 pecks Q, rapid to R after each
  peck and back down to 0.010 in (0.254 mm) above the last depth; G73 pecks Q with a chip-break
  retract of 0.010 in; G85 feeds in and out to R, then rapids to the clear level; G89 dwells, then
  feeds out; G86 dwells and rapids out (spindle stopped); G84 (tapping) feeds in, dwells P, and feeds
  out. G84's and G89's feed out goes to the clear level in LinuxCNC (interp_cycles.cc
  ``convert_cycle_g74_g84``, ``convert_cycle_g89``; g-code.adoc G89: "Retract the Z-axis at the current
  feed rate to clear Z"), to R and then rapid to the clear level in Fanuc and Haas (Haas "G84 Tapping
  Canned Cycle": feed to the R plane, rapid to the starting plane), as the dialect says
  (:attr:`interpolators.context.Dialect.tap_out_to_r`). Under ``fanuc`` a G84/G74 with P dwells P again at R,
  where the spindle turns forward again (``tap_dwell_at_r``; Fanuc "Dwell time at the bottom of the hole and at
  point R when a return is made"); a peck rigid tap's returns to R between its cuts do not (our reading).

The words R, Z, Q and P are sticky within the series of cycles, as in LinuxCNC.

LinuxCNC taps only with the spindle turning the tap's way (interp_cycles.cc ``check_g74_g84_spindle``:
"Spindle not turning in G84", "Spindle turning counterclockwise in G84", and for the left-hand G74
"Spindle turning clockwise in G74"): :func:`tap_spindle_error` says which, for the ``linuxcnc``
dialect (Fanuc and Haas reverse the spindle themselves and do not check it).

Cycles of Fanuc and Haas mills (the ``fanuc`` and ``haas`` dialects; in LinuxCNC these codes are
other things or errors):

* **G74 counter tapping**: G84's motion with the spindle reversed (Fanuc 0i-MF operator's manual,
  "Left-handed tapping cycle (G74)"; Haas "G74 Reverse Tap Canned Cycle"): feed to Z, dwell P,
  feed out to R, rapid to the clear level.
* **G76 fine boring** (Fanuc "Fine boring cycle (G76)"; Haas "G76 Fine Boring Canned Cycle"):
  feed to Z, dwell P, oriented spindle stop, a rapid shift away from the wall, the rapid retract,
  the shift back. The shift is Q along +X (sign ignored: Fanuc "specify a positive value for Q ...
  set the shift direction, +X, -X, +Y or -Y, in parameter No. 6240", Haas Setting 27; both
  default to +X), or I J (Fanuc with parameter SIJ, Haas: "I/J shift ... if Q is not specified").
* **G87 back boring** (Fanuc "Back boring cycle (G87)"; Haas mill "G77 Back Bore Canned Cycle"):
  at the hole, oriented stop and shift, rapid down to the R level (the bottom of the bore), shift
  back, feed up to Z (above R), dwell P, shift, rapid up to the initial level, shift back. G99
  cannot be used (the tool returns to the initial level).
* **Haas G73 / G83 with I J K** (Haas mill operator's manual, "G83 Normal Peck Drilling": "I size of
  first peck depth, J amount to reduce each peck, K minimum peck depth"): the pecks are I, I - J,
  I - 2 J, ... but never less than K (used instead of Q when I is given); under the ``haas`` dialect
  K is never a repeat count (Haas repeats with L), as it is on Fanuc.
* **Haas G73 with K and Q** (Haas mill operator's manual 96-8000, June 1999, "G73 High-Speed Peck Drilling
  Canned Cycle": "If K and Q are both specified, a different operating mode is selected for this canned cycle.
  In this mode, the tool is returned to the R plane after a number of passes totals up to the K amount"; Fusion's
  haas.cps writes ``G73 .. Q<peck> K<accumulated depth>`` for chip breaking with a full retract): pecks of Q
  with the chip-break retract, and a rapid to R and back (to the clearance above the last depth, as G83 comes
  back) after the peck at which the depth drilled since the last return to R reaches K (our reading of
  "totals up to"). Setting 52 (a clear move above R) is taken as 0, its default.
* **No R in the first block of a series** (``fanuc_rules``, the ``fanuc`` and ``haas`` dialects): the R
  plane is the initial level. Haas Mill Operator's Manual (NGC, 2017), "G81 Drill Canned Cycle (Group
  09)" (and G73, G74, G84 ...): "*R - Position of the R plane", "* indicates optional"; Fanuc Series
  0i/16i operator's manuals, "Canned cycle cancel (G80)": "point R and point Z are cleared. This means
  that R = 0 and Z = 0 in incremental command", the cleared R being no distance from the initial level.
  Neither manual states the absolute case in words: taking the initial level there too is our reading.
  LinuxCNC refuses the block ("R clearance plane unspecified in cycle").
* **Zero repeats** (``L0``; Fanuc ``K0``): Fanuc and Haas store the cycle data and drill no hole at the block
  (Fanuc 0i "Canned cycle for drilling", repetition K: with K0 the data is stored, no hole drilled, our
  paraphrase; Haas NGC mill manual, bolt-circle example: "L0 on the G81 line will not drill a hole");
  LinuxCNC refuses it (interp_cycles.cc convert_cycle, rs274: "Cannot do zero repeats of cycle").
* **Fadal** (the ``fadal`` dialect, read with the ``fanuc`` rules, :mod:`interpolators.iso_fadal`): a cycle
  started below R positions X Y at the current height, then rapids up to R, as Fanuc's. No Fadal manual text on
  that case is searchable here; the dialect takes Fanuc's rules where Fadal's own words do not differ.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from interpolators.iso_polar import PolarError, polar_xy
from interpolators.iso_words import WordError

__all__ = ["CycleWords", "HoleMove", "CycleError", "cycle_moves", "CYCLE_AXES", "RAPID_DELTA_INCH", "MAX_CYCLE_MOVES",
           "tap_spindle_error", "UNSCALED_Q_CYCLES"]

#: Cycles whose Q (peck depth: G73, G83; shift: G76, G87, Haas G77) and retract d a G51 scaling leaves
#: unscaled while it scales the hole and its levels (Haas "G51 Scaling": "all X, Y, Z, I, J, K, or R
#: values addressing machine motion are multiplied"; Fanuc 0i "Scaling": the cut-in Q and retraction d of
#: G73/G83 and the G76/G87 shift are not scaled): the reader runs the other cycles under scaling through
#: the transformation and refuses these.
UNSCALED_Q_CYCLES = frozenset({73, 83, 76, 87, 77})

#: Clearance of the re-entry (G83) and chip-break retract (G73) [inch] (LinuxCNC G83_RAPID_DELTA).
RAPID_DELTA_INCH = 0.010

#: Most moves one cycle block may make (holes x pecks): a guard against a peck depth Q or a repeat count L
#: that would make millions of moves (a mistyped ``Q0.0000001``, ``L99999999``).
MAX_CYCLE_MOVES = 1_000_000


class CycleError(WordError):
    """Cycle words that describe no cycle; ``letter`` names the word at fault."""


def tap_spindle_error(code: int, turning: bool, ccw: bool) -> tuple[str, str] | None:
    """Why LinuxCNC refuses tapping cycle G``code`` (84 right-hand, 74 left-hand) with the spindle as it
    is (``turning`` M3/M4, ``ccw`` M4), and what it expects; None when it taps (interp_cycles.cc
    ``check_g74_g84_spindle``). Other codes: None."""
    if code not in (74, 84):
        return None
    want = "M3 (clockwise) before G84" if code == 84 else "M4 (counter-clockwise) before G74"
    if not turning:
        return "with the spindle not turning", want
    if ccw == (code == 84):
        return "with the spindle turning " + ("counter-clockwise (M4)" if ccw else "clockwise (M3)"), want
    return None

@dataclasses.dataclass
class CycleWords:
    """Sticky state of a series of canned cycles (program values as written, before scaling)."""

    initial: float | None = None  # Z at the start of the series [mm, machine]
    motion_before: int | None = None  # modal motion before the series (restored by G80, as Fanuc does)
    r: float | None = None
    z: float | None = None
    q: float | None = None
    p: float | None = None
    i: float | None = None  # G76/G87 shift words (Haas; Fanuc with parameter SIJ)
    j: float | None = None
    k: float | None = None  # Haas G73/G83 minimum peck
    shift_by_q: bool | None = None  # the last G76/G87 block that wrote a shift wrote Q (True) or I J (False)
    factors: tuple[float, float, float] = (1.0, 1.0, 1.0)  # the G51 scaling the series began under
    fagor: bool = False  # a Fagor G81 Z I series: Z is the reference plane, I the depth (interpolators.iso)
    # machine minus program coordinate [mm] along the drilling axis at the series' last block: work, G92 and tool
    # offsets (iso_offsets.length_in_cycle)
    zero: float | None = None


@dataclasses.dataclass(frozen=True)
class HoleMove:
    """One move of a cycle: ``kind`` "rapid" | "line" | "dwell", ``target`` [mm, machine],
    ``feed`` [mm/s] (inf for rapids, 0 for dwells), ``dwell`` [s]."""

    kind: str
    target: np.ndarray
    feed: float = math.inf
    dwell: float = 0.0


#: Axes of a cycle per plane (0 = G19 YZ, 1 = G18 ZX, 2 = G17 XY): the two hole-position axes, then the drilling
#: axis (LinuxCNC interp_cycles.cc convert_cycle_xy / _zx: aa = Z, bb = X, cc = Y / _yz: aa = Y, bb = Z, cc = X).
CYCLE_AXES = {2: (0, 1, 2), 1: (2, 0, 1), 0: (1, 2, 0)}


def cycle_moves(g: int, words: dict[str, float], *, cycle: CycleWords, pos: np.ndarray, offset: np.ndarray,
                scale: float, incremental: bool, retract_r: bool, feed: float, dwell_p_ms: bool,
                tap_out_to_r: bool = False, plane: int = 2, haas: bool = False,
                fanuc_rules: bool = False, peck_tap: tuple[str, float] | None = None,
                tap_dwell_at_r: bool = False) -> list[HoleMove]:
    """The moves of one canned-cycle block, in any plane: in G18 (ZX) the holes are drilled along Y
    (Z X position them, Y is the bottom, R a Y level), in G19 (YZ) along X (LinuxCNC "Canned Cycles":
    "the cycle is performed in the plane selected"). The cycle runs on the axes permuted to X Y Z.

    Parameters
    ----------
    g : int
        Cycle code (73, 74, 81, 82, 83, 84, 85, 86, 89; the Fanuc/Haas mill cycles 76, 87).
    words : dict
        The block's words as written (``X Y Z R Q P L K``), not yet scaled.
    cycle : CycleWords
        Sticky state of the series, updated in place (R, Z, Q, P).
    pos : ndarray (3,)
        Current position [mm, machine].
    offset : ndarray (3,)
        Machine minus program coordinates [mm] (work, G92 and tool length offsets).
    scale : float
        mm per program unit (25.4 under G20).
    incremental : bool
        G91.
    retract_r : bool
        G99 (return to R) instead of G98.
    feed : float
        Feed [mm/s].
    dwell_p_ms : bool
        ``P`` in milliseconds (Fanuc/Haas) rather than seconds (LinuxCNC).
    tap_out_to_r : bool
        G84 feeds out to the R plane and rapids on to the clear level (Fanuc, Haas), rather than
        feeding out to the clear level (LinuxCNC).
    plane : int
        2 (G17, drilling along Z), 1 (G18, along Y) or 0 (G19, along X).
    haas : bool
        Haas words: G73/G83 pecks from I J K, and K is not a repeat count.
    fanuc_rules : bool
        Fanuc/Haas rather than LinuxCNC: a series whose first block has no R drills from the initial level,
        and zero repeats (L0, K0) drill no hole, where LinuxCNC refuses both.
    peck_tap : (str, float) or None
        A G84/G74 with a Q in force runs Fanuc's peck rigid tapping (:func:`_tap_pecks`): the kind
        (``"high-speed"`` or ``"standard"``, :attr:`interpolators.context.Dialect.peck_tapping`) and d [mm];
        None: the tap runs in one stroke, a Q unused.
    tap_dwell_at_r : bool
        G84/G74 dwell P also at the R plane on the way out, where the spindle turns forward again (Fanuc: 0i-MD
        B-64304EN and 16i-TA/TB A-78549E, rigid tapping, "P_: Dwell time at the bottom of the hole and at point R when
        a return is made"; the tapping cycles' figures show "P" at both reversals); else at the bottom only.

    Raises
    ------
    CycleError
        Missing R or Z, Q <= 0 for pecking cycles, R below the bottom, bad repeat count.
    """
    axes = CYCLE_AXES[plane]
    if axes == (0, 1, 2):
        return _xy_cycle(g, words, cycle=cycle, pos=pos, offset=offset, scale=scale, incremental=incremental,
                         retract_r=retract_r, feed=feed, dwell_p_ms=dwell_p_ms, tap_out_to_r=tap_out_to_r,
                         haas=haas, fanuc_rules=fanuc_rules, peck_tap=peck_tap, tap_dwell_at_r=tap_dwell_at_r)
    if "@" in words or "^" in words:
        raise CycleError("polar coordinates @ ^ are only in the XY plane (G17)",
                         letter="@" if "@" in words else "^", expected="G17 for polar words")
    letters = {"XYZ"[j]: "XYZ"[a] for j, a in enumerate(axes)}  # permuted letter -> the word's letter
    permuted = {k: v for k, v in words.items() if k not in "XYZ"}
    permuted.update({j: words[a] for j, a in letters.items() if a in words})
    try:
        moves = _xy_cycle(g, permuted, cycle=cycle, pos=pos[list(axes)], offset=offset[list(axes)], scale=scale,
                          incremental=incremental, retract_r=retract_r, feed=feed, dwell_p_ms=dwell_p_ms,
                          tap_out_to_r=tap_out_to_r, haas=haas, fanuc_rules=fanuc_rules, peck_tap=peck_tap,
                          tap_dwell_at_r=tap_dwell_at_r)
    except CycleError as exc:
        exc.letter = letters.get(exc.letter, exc.letter)
        raise
    back = np.argsort(axes)
    return [dataclasses.replace(m, target=m.target[back]) for m in moves]


def _unit(scale: float) -> str:
    """The program's length unit for a message: levels are reported as the program writes them (G20: inch)."""
    return "mm" if scale == 1.0 else "in"


def _xy_cycle(g: int, words: dict[str, float], *, cycle: CycleWords, pos: np.ndarray, offset: np.ndarray,
              scale: float, incremental: bool, retract_r: bool, feed: float, dwell_p_ms: bool,
              tap_out_to_r: bool, haas: bool, fanuc_rules: bool,
              peck_tap: tuple[str, float] | None = None, tap_dwell_at_r: bool = False) -> list[HoleMove]:
    """:func:`cycle_moves` in the XY plane (drilling along Z)."""
    if cycle.initial is None:
        cycle.initial = float(pos[2])
    if cycle.r is None and "R" not in words and fanuc_rules:  # R = the initial level (module docstring)
        cycle.r = 0.0 if incremental else (cycle.initial - offset[2]) / scale
    repeats, dwell = _sticky_words(g, words, cycle, dwell_p_ms=dwell_p_ms, haas=haas)
    if repeats == 0 and not fanuc_rules:
        rl = "L" if "L" in words else "K"
        raise CycleError("zero repeats: LinuxCNC cannot do zero repeats of a cycle (Fanuc and Haas store the "
                         "cycle and drill no hole there)", letter=rl, expected=f"{rl}1 or more")
    if incremental:  # LinuxCNC convert_cycle_xy: r = R + the initial level (cycle_il), not the current Z
        r = cycle.initial + cycle.r * scale
        bottom = r + cycle.z * scale
    else:
        r = cycle.r * scale + offset[2]
        bottom = cycle.z * scale + offset[2]
    if g == 87:
        return _back_bore(words, cycle=cycle, pos=pos, r=r, top=bottom, offset=offset, scale=scale,
                          incremental=incremental, retract_r=retract_r, feed=feed, dwell=dwell)
    if bottom > r:
        unit = _unit(scale)
        raise CycleError(f"hole bottom Z {(bottom - offset[2]) / scale:g} {unit} lies above the R plane "
                         f"{(r - offset[2]) / scale:g} {unit}", letter="Z" if "Z" in words else "R",
                         expected="Z below R")
    # LinuxCNC's loop runs in program units: a Q that divides R - Z makes the pecks its rounding makes
    r_p = (cycle.initial - offset[2]) / scale + cycle.r if incremental else cycle.r
    bottom_p = r_p + cycle.z if incremental else cycle.z
    tap_pecks = peck_tap is not None and g in (74, 84) and cycle.q is not None
    if tap_pecks and not cycle.q > 0:
        raise CycleError("peck depth Q of the peck rigid tap must be > 0", letter="Q" if "Q" in words else None,
                         expected="Q > 0 (the depth of each cut)")
    levels = _peck_depths(cycle, r_p, bottom_p, haas=haas, decimal=fanuc_rules) if g in (73, 83) or tap_pecks else []
    depths = [d * scale + offset[2] for d in levels]
    pecks = len(depths) + 1
    if repeats * (pecks + 3) > MAX_CYCLE_MOVES:  # L99999999 or Q0.0000001 would run for hours, filling the memory
        raise CycleError(f"{repeats} holes of {pecks} pecks each exceed {MAX_CYCLE_MOVES} cycle moves",
                         letter="Q" if pecks > 1 and "Q" in words else next((c for c in "LK" if c in words), None),
                         expected="a larger peck depth Q or fewer repeats L")
    delta = RAPID_DELTA_INCH * 25.4
    # Haas G73 with K and Q (and no I): back to R each time the pecks since the last return total K
    clear_every = cycle.k * scale if haas and g == 73 and not cycle.i and cycle.k and cycle.k > 0 else 0.0
    out: list[HoleMove] = []
    cur = pos.astype(float).copy()

    def go(kind: str, x: float, y: float, z: float, f: float = math.inf) -> None:
        nonlocal cur
        target = np.array([x, y, z])
        if np.array_equal(target, cur):
            return
        out.append(HoleMove(kind, target, f))
        cur = target

    # levels and approach as LinuxCNC's convert_cycle_xy and CYCLE_MACRO (interp_internal.hh)
    old = cycle.initial
    if old < r:  # the initial level is below R: straight up to R first (LinuxCNC; Fanuc, Haas: see below)
        if not fanuc_rules:
            go("rapid", cur[0], cur[1], r)
        old = r
    clear = r if retract_r else old
    for k in range(repeats):
        x, y = _hole(words, cur, offset=offset, scale=scale, incremental=incremental)
        # over at the current height, then down to R; Fanuc and Haas also from below R (0i-MF "Canned cycle for
        # drilling": "Operation 1 Positioning of axes X and Y", "Operation 2 Rapid traverse up to point R level"),
        # as when a G98 block follows G99 holes under a higher R
        if k == 0 and (cur[2] > r or fanuc_rules):
            go("rapid", x, y, cur[2])
        else:  # the tool is at the clear level (or below it): over at the clear level
            go("rapid", x, y, clear)
        go("rapid", x, y, r)
        cleared = r  # the depth of the last return to R (Haas G73 with K and Q)
        for z in _tap_pecks(depths, r, peck_tap) if tap_pecks else ():
            go("line", x, y, z, feed)
        for depth in depths if not tap_pecks else ():
            go("line", x, y, depth, feed)
            full = g == 83 or clear_every > 0 and cleared - depth >= clear_every - 1e-9 * max(1.0, abs(depth))
            go("rapid", x, y, r if full else depth + delta)
            if full:
                cleared = depth
                go("rapid", x, y, depth + delta)
        go("line", x, y, bottom, feed)
        if dwell > 0:
            out.append(HoleMove("dwell", cur.copy(), 0.0, dwell))
        if g == 76:  # oriented stop, shift off the wall, rapid out, shift back
            dx, dy = _shift(cycle, scale)
            go("rapid", x + dx, y + dy, bottom)
            go("rapid", x + dx, y + dy, clear)
            go("rapid", x, y, clear)
            continue
        if g in (74, 84, 89) and not tap_out_to_r:  # LinuxCNC convert_cycle_g74_g84, _g89: feed out to clear
            go("line", x, y, clear, feed)
        elif g in (74, 84, 85, 89):
            go("line", x, y, r, feed)
            if g in (74, 84) and tap_dwell_at_r and dwell > 0:  # the spindle turns forward again at R (Fanuc)
                out.append(HoleMove("dwell", cur.copy(), 0.0, dwell))
        go("rapid", x, y, clear)
    return out


def _tap_pecks(depths: list[float], r: float, peck_tap: tuple[str, float]) -> list[float]:
    """The levels [mm, machine] a peck rigid tap (G84/G74, Fanuc) feeds to before its last cut to the bottom, each
    move at the tapping feed: after each cut to a ``depths`` level, back by d (``"high-speed"``, PCP = 0) or back to
    ``r`` and in again to d above the level cut (``"standard"``, PCP = 1: d the cutting start distance); never above
    R (our reading where d exceeds a cut). :attr:`interpolators.context.Dialect.peck_tapping` cites the manual."""
    kind, d = peck_tap
    out: list[float] = []
    for depth in depths:
        out.append(depth)
        if kind == "standard":
            out.append(r)
        out.append(min(depth + d, r))
    return out


def _peck_depths(cycle: CycleWords, r: float, bottom: float, *, haas: bool, decimal: bool = False) -> list[float]:
    """The depths of the pecks above the bottom, in program units and coordinates as ``r`` and
    ``bottom``: every Q from R (LinuxCNC's loop, interp_cycles.cc convert_cycle_g83, run in program
    units so that a Q that divides R - Z makes the pecks its rounding makes), or under Haas with I the
    pecks I, I - J, ... not below K; at most :data:`MAX_CYCLE_MOVES` + 1 of them. ``decimal`` (Fanuc, Haas):
    a peck within binary rounding of the bottom is the bottom, as in the controls' decimal arithmetic (R0.15
    Z-0.45 Q0.1 is six pecks, the last at Z-0.45; our reading: LinuxCNC's doubles add a seventh)."""
    variable = haas and bool(cycle.i)
    step = cycle.i if variable else cycle.q
    out: list[float] = []
    depth = r - step
    slack = 1e-9 * max(1.0, abs(bottom)) if decimal else 0.0
    while depth > bottom + slack and len(out) <= MAX_CYCLE_MOVES:
        out.append(depth)
        if variable:
            step = max(step - (cycle.j or 0.0), cycle.k or 0.0)
            if step <= 0:
                raise CycleError("peck depths I - n J reach 0 without a minimum K > 0", letter=None,
                                 expected="K > 0 (the minimum peck)")
        depth -= step
    return out


def _sticky_words(g: int, words: dict[str, float], cycle: CycleWords, *, dwell_p_ms: bool,
                  haas: bool = False) -> tuple[int, float]:
    """Update the series' sticky R Z Q P from the block; returns the repeat count and the dwell [s]."""
    shift = ("I", "J") if g in (76, 87) else ("I", "J", "K") if haas and g in (73, 83) else ()
    for letter in ("R", "Z", "Q", "P", *shift):
        if letter in words:
            setattr(cycle, letter.lower(), words[letter])
    if g in (76, 87) and ("Q" in words or "I" in words or "J" in words):
        # Haas (G76, G77: "I/J ... if Q is not specified") takes a written Q over I J; our Fanuc reading takes
        # I J when written (parameter SIJ), Q otherwise
        cycle.shift_by_q = "Q" in words and (haas or not ("I" in words or "J" in words))
    if cycle.r is None:
        # LinuxCNC interp_cycles.cc convert_cycle: NCE_R_CLEARANCE_PLANE_UNSPECIFIED_IN_CYCLE when the
        # first block after another motion mode has no R; the R level has no default
        raise CycleError("no R (retract plane) word in the first block of the series (R has no default; "
                         "LinuxCNC: 'R clearance plane unspecified in cycle')", letter=None,
                         expected="R<retract level> (the fanuc and haas dialects drill from the initial level)")
    if cycle.z is None:
        raise CycleError("no Z (hole bottom) word", letter=None, expected="Z<bottom>")
    repeats = words.get("L", 1.0 if haas else words.get("K", 1.0))
    if repeats != int(repeats) or repeats < 0:
        rl = "L" if "L" in words else "K"
        raise CycleError("repeat count must be a whole number >= 0", letter=rl, expected=f"{rl}1, {rl}2, ...")
    if g in (73, 83) and not (cycle.q is not None and cycle.q > 0) and not (haas and cycle.i and cycle.i > 0):
        # Haas mill manual (NGC 2017) "G73": "three methods to program a G73: using the I, J, K addresses, using
        # the K and Q addresses, and using only a Q address"; Fanuc reads Q (0i "High-speed peck drilling
        # cycle (G73)"): neither documents a peck drilling block without them
        raise CycleError("peck depth Q must be > 0", letter="Q" if "Q" in words else None,
                         expected="Q > 0 (Haas: or I J K)" if haas else "Q > 0")
    dwell = 0.0
    if g in (76, 87) and not cycle.q and not (cycle.i or cycle.j):
        raise CycleError("no shift: Q (along +X) or I J", letter=None, expected="Q<shift> or I.. J..")
    if g in (74, 82, 84, 76, 86, 87, 89) and cycle.p is not None:
        dwell = cycle.p / 1000.0 if dwell_p_ms else cycle.p
        if dwell < 0:
            raise CycleError("dwell P must be >= 0", letter="P", expected="P >= 0")
    return int(repeats), dwell


def _shift(cycle: CycleWords, scale: float) -> tuple[float, float]:
    """The G76/G87 shift [mm] in the positioning plane: what the series' last G76/G87 block with a shift wrote
    (|Q| along +X, or I J); without one (the series' values come from G73/G83 blocks) I J if given, else Q."""
    if cycle.shift_by_q is None and (cycle.i or cycle.j) or cycle.shift_by_q is False:
        return (cycle.i or 0.0) * scale, (cycle.j or 0.0) * scale
    return abs(cycle.q) * scale, 0.0


def _back_bore(words: dict[str, float], *, cycle: CycleWords, pos: np.ndarray, r: float, top: float,
               offset: np.ndarray, scale: float, incremental: bool, retract_r: bool, feed: float,
               dwell: float) -> list[HoleMove]:
    """G87 (Fanuc) / G77 (Haas) back boring: the holes from below, R the bottom and Z the top of the
    bore [mm, machine] (see the module docstring)."""
    if retract_r:
        raise CycleError("G99 cannot be used: back boring returns to the initial level", letter=None,
                         expected="G98")
    initial = cycle.initial
    if not r < top < initial:
        raise CycleError(f"back boring needs R {(r - offset[2]) / scale:g} below Z {(top - offset[2]) / scale:g} "
                         f"below the initial level {(initial - offset[2]) / scale:g} {_unit(scale)}",
                         letter="R" if "R" in words else "Z",
                         expected="R (bore bottom) < Z (top of the cut) < the initial level")
    repeats = int(words.get("L", words.get("K", 1.0)))
    dx, dy = _shift(cycle, scale)
    out: list[HoleMove] = []
    cur = pos.astype(float).copy()
    for _ in range(repeats):
        x, y = _hole(words, cur, offset=offset, scale=scale, incremental=incremental)
        steps = [("rapid", x, y, initial), ("rapid", x + dx, y + dy, initial), ("rapid", x + dx, y + dy, r),
                 ("rapid", x, y, r), ("line", x, y, top), ("dwell", x, y, top), ("rapid", x + dx, y + dy, top),
                 ("rapid", x + dx, y + dy, initial), ("rapid", x, y, initial)]
        for kind, px, py, pz in steps:
            target = np.array([px, py, pz])
            if kind == "dwell":
                if dwell > 0:
                    out.append(HoleMove("dwell", target, 0.0, dwell))
            elif not np.array_equal(target, cur):
                out.append(HoleMove(kind, target, feed if kind == "line" else math.inf))
                cur = target
    return out


def _hole(words: dict[str, float], cur: np.ndarray, *, offset: np.ndarray, scale: float,
          incremental: bool) -> tuple[float, float]:
    """X, Y [mm, machine] of the next hole: X/Y words, or LinuxCNC polar words ``@ ^``
    (``CYCLE_MACRO`` in interp_internal.hh: under G91 each repeat adds X/Y, then @ to the
    distance and ^ to the angle about the program origin)."""
    x, y = float(cur[0]), float(cur[1])
    if incremental:
        x += words.get("X", 0.0) * scale
        y += words.get("Y", 0.0) * scale
    else:
        x = words["X"] * scale + offset[0] if "X" in words else x
        y = words["Y"] * scale + offset[1] if "Y" in words else y
    if "@" in words or "^" in words:
        try:
            px, py = polar_xy(x - offset[0], y - offset[1], incremental=incremental,
                              distance=words["@"] * scale if "@" in words else None, angle_deg=words.get("^"))
        except PolarError as exc:
            raise CycleError(str(exc), letter="@" if "@" in words else "^",
                             expected="a start point away from X0 Y0") from None
        x, y = px + offset[0], py + offset[1]
    return x, y
