"""Haas mill patterns and pocket: G70 bolt hole circle, G71 bolt hole arc, G72 bolt holes along an
angle; G12 / G13 circular pocket milling.

Haas mill operator's manual, G-codes chapter ("G70 Bolt Hole Circle", "G71 Bolt Hole Arc", "G72
Bolt Holes Along an Angle", group 00, non-modal): each must come with an active canned cycle
(G73, G74, G76, G77, G81-G89), which runs at every hole of the pattern; the cycle block itself is
usually written with ``L0`` so that it does not drill the pattern's centre.

* ``G70 I.. J.. L..``: L holes evenly spaced on a circle of radius I about the current X Y, the
  first at J degrees (counter-clockwise from the +X "3 o'clock" direction).
* ``G71 I.. J.. K.. L..``: L holes on that circle from J, K degrees apart (K < 0: clockwise).
* ``G72 I.. J.. L..``: L holes I apart along a line at J degrees from the current X Y, the first one
  I from it (the start point is the cycle block's own hole).

An ``X Y`` on the pattern's block moves the centre (start) there first, as the canned cycle's own
X Y would. In the ``fanuc`` dialect G70-G72 are lathe cycles (not supported).

G12 (clockwise) / G13 (counter-clockwise) circular pocket milling (Haas mill operator's manual
"G12 Circular Pocket Milling CW / G13 Circular Pocket Milling CCW", group 00; a Yasnac-style cycle):
the tool starts at the centre (X Y on the block move it there first, at rapid); ``Z`` is the depth
(G91: an increment, repeated ``L`` times for deeper cuts); ``I`` the radius of the first circle (the
finished one without K), ``K`` the finished radius, ``Q`` the step from one circle to the next (with
K); ``D`` the tool whose radius the circles are offset by (cutter compensation is implied: G42 for
G12, G41 for G13; D0 or none: the tool centre follows the programmed radii). Our reading of the
manual's figure for each depth: feed down to Z at the centre, a half circle out to the first circle
on its +X side, the full circle, for each further radius a half circle out to it and the full circle,
then a feed straight back to the centre. Without Z the circles run at the current Z (the tool already at depth;
under G91 an increment of 0): our reading, the manual listing "Z Depth of cut or increment" with the optional K,
Q and L and no text requiring it, and the Haas workbook (96-8000, June 1999, "Circular pocket milling") naming the
single pass "Using I only". The half circles turn the same way as the circles, so that
the tool comes onto each circle along its tangent. In the ``fanuc`` dialect G12/G13 are not supported.
"""

from __future__ import annotations

import dataclasses
import math

from interpolators.iso_cycles import MAX_CYCLE_MOVES
from interpolators.iso_words import WordError

__all__ = ["PATTERN_CODES", "PocketMove", "bolt_holes", "circular_pocket"]

#: The pattern codes, round(10 * G) -> name.
PATTERN_CODES: dict[int, str] = {700: "G70 bolt hole circle", 710: "G71 bolt hole arc",
                                 720: "G72 bolt holes along an angle"}


def bolt_holes(key: int, words: dict[str, float], *, centre: tuple[float, float],
               scale: float) -> list[tuple[float, float]]:
    """The X Y [mm, program coordinates] of the holes of one pattern block, in the order drilled.

    Parameters
    ----------
    key : int
        700 (G70), 710 (G71) or 720 (G72).
    words : dict
        The block's words as written (I, J, K, L; program units and degrees).
    centre : tuple of float
        Centre of the circle / start of the line [mm, program coordinates].
    scale : float
        mm per program unit.

    Raises
    ------
    WordError
        A missing I or L, L not a whole number >= 1, a zero spacing.
    """
    needs = ("I", "J", "K", "L") if key == 710 else ("I", "L")
    for letter in needs:
        if letter not in words:
            raise WordError(f"no {letter} word", letter=None, expected=" ".join(f"{k}.." for k in needs))
    count = words["L"]
    if count != int(count) or count < 1:
        raise WordError("the number of holes L must be a whole number >= 1", letter="L", expected="L1, L2, ...")
    if count > MAX_CYCLE_MOVES:
        raise WordError(f"{count:g} holes exceed {MAX_CYCLE_MOVES} cycle moves", letter="L",
                           expected="fewer holes L")
    radius = words["I"] * scale
    if radius == 0:
        raise WordError("I (radius / spacing) must not be 0", letter="I", expected="I != 0")
    start = words.get("J", 0.0)
    x0, y0 = centre
    out = []
    for k in range(int(count)):
        if key == 720:
            a = math.radians(start)
            d = radius * (k + 1)
            out.append((x0 + d * math.cos(a), y0 + d * math.sin(a)))
            continue
        step = 360.0 / count if key == 700 else words["K"]
        a = math.radians(start + k * step)
        out.append((x0 + radius * math.cos(a), y0 + radius * math.sin(a)))
    return out


@dataclasses.dataclass(frozen=True, kw_only=True)
class PocketMove:
    """One feed move of a circular pocket, in program coordinates [mm].

    Attributes
    ----------
    end : tuple of float
        End point (x, y, z).
    centre : tuple of float or None
        Arc centre (x, y) for an arc, None for a line.
    ccw : bool
        Counter-clockwise arc (G13).
    """

    end: tuple[float, float, float]
    centre: tuple[float, float] | None = None
    ccw: bool = False


def circular_pocket(ccw: bool, words: dict[str, float], *, centre: tuple[float, float, float], scale: float,
                    incremental: bool, tool_radius: float) -> list[PocketMove]:
    """The feed moves of a G12 (``ccw`` False) / G13 block from the centre (see the module docstring).

    Parameters
    ----------
    ccw : bool
        G13.
    words : dict
        The block's words as written (I, K, Q, L, Z).
    centre : tuple of float
        The centre and the current Z [mm, program coordinates].
    scale : float
        mm per program unit.
    incremental : bool
        G91: Z is an increment per pass.
    tool_radius : float
        Radius of the D tool [mm], 0 for the tool centre.

    Raises
    ------
    WordError
        No I, K without Q (or Q <= 0), I not between the tool radius and K, a bad L.
    """
    if "I" not in words:
        raise WordError("no I word", letter=None, expected="I<radius> (Z, K, Q, L, D)")
    first = words["I"] * scale
    last = words["K"] * scale if "K" in words else first
    if "K" in words and not words.get("Q", 0.0) > 0:
        raise WordError("K (finished radius) needs a step Q > 0", letter="Q" if "Q" in words else "K",
                           expected="I<first radius> K<finished radius> Q<step>")
    if not tool_radius < first <= last:
        raise WordError(f"radii must satisfy tool radius {tool_radius:g} < I {first:g} <= K {last:g} mm",
                           letter="I", expected="I greater than the tool radius, K not below I")
    count = math.ceil((last - first) / (words["Q"] * scale) - 1e-9) if last > first else 0
    loops = words.get("L", 1.0)
    if loops != int(loops) or loops < 1:
        raise WordError("L (passes) must be a whole number >= 1", letter="L", expected="L1, L2, ...")
    if loops * (count + 1) > MAX_CYCLE_MOVES:
        raise WordError(f"{loops:g} passes of {count + 1} circles exceed {MAX_CYCLE_MOVES} moves",
                           letter="L" if loops > 1 else "Q", expected="fewer passes L or a larger step Q")
    radii = [min(first + k * words["Q"] * scale, last) for k in range(count + 1)] if count else [first]
    cx, cy, z = centre
    out: list[PocketMove] = []
    for _ in range(int(loops)):
        z = z + words.get("Z", 0.0) * scale if incremental else words["Z"] * scale if "Z" in words else z
        out.append(PocketMove(end=(cx, cy, z)))
        inner = 0.0
        for r in (radius - tool_radius for radius in radii):
            # a half circle from the last circle's +X point (the centre at first) out to this one's
            out.append(PocketMove(end=(cx + r, cy, z), centre=(cx + (inner + r) / 2.0, cy), ccw=ccw))
            out.append(PocketMove(end=(cx + r, cy, z), centre=(cx, cy), ccw=ccw))
            inner = r
        out.append(PocketMove(end=(cx, cy, z)))
    return out
