"""Haas mill bolt-hole patterns: G70 bolt hole circle, G71 bolt hole arc, G72 bolt holes along an angle.

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
"""

from __future__ import annotations

import math

__all__ = ["PATTERN_CODES", "PatternError", "bolt_holes"]

#: The pattern codes, round(10 * G) -> name.
PATTERN_CODES: dict[int, str] = {700: "G70 bolt hole circle", 710: "G71 bolt hole arc",
                                 720: "G72 bolt holes along an angle"}


class PatternError(ValueError):
    """Pattern words that describe no pattern; ``letter`` names the word at fault."""

    def __init__(self, message: str, *, letter: str | None, expected: str) -> None:
        super().__init__(message)
        self.letter = letter
        self.expected = expected


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
    PatternError
        A missing I or L, L not a whole number >= 1, a zero spacing.
    """
    needs = ("I", "J", "K", "L") if key == 710 else ("I", "L")
    for letter in needs:
        if letter not in words:
            raise PatternError(f"no {letter} word", letter=None, expected=" ".join(f"{k}.." for k in needs))
    count = words["L"]
    if count != int(count) or count < 1:
        raise PatternError("the number of holes L must be a whole number >= 1", letter="L", expected="L1, L2, ...")
    radius = words["I"] * scale
    if radius == 0:
        raise PatternError("I (radius / spacing) must not be 0", letter="I", expected="I != 0")
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
