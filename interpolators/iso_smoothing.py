"""Look-ahead and smoothing codes of Fanuc and Haas mills: words that set how the control blends the
path, never where it goes.

Accepted under the ``fanuc`` and ``haas`` dialects (:class:`interpolators.context.Dialect`); each
is a note, and Haas G187 E also sets the path tolerance as ``G64 P`` does:

=================== ===============================================================================
``G187 P1-P3 E..``  Haas "G187 Smoothness Control" (Haas mill operator's manual, G-codes): P1 rough,
                    P2 medium, P3 finish; E "sets the max corner rounding value" [in / mm]: here
                    the path tolerance of continuous-path mode. ``G187`` without P and E returns to
                    the machine's default (Setting 191): the dialect's tolerance.
``G103 P0-P15``     Haas "G103 Limit Block Lookahead": how many blocks the control reads ahead.
``G05.1 Q1 / Q0``   Fanuc AI contour control on / off (R1-R10 the level); ``Q2`` nano smoothing,
                    whose axis words name the axes (no motion) (Fanuc 0i-MF operator's manual,
                    "AI contour control", "Nano smoothing"); ``Q3`` the 30i's smooth tolerance+
                    control, written as Fusion's fanuc.cps writes it: ``G05.1 Q3 X0 Y0 Z0 [A0 B0 C0]
                    R<level>``, the axis words again naming the axes (our reading of the post; the
                    30i-B manual's section was not in our index).
``G08 P1 / P0``     Fanuc AI advanced preview control (look-ahead feed-forward) on / off.
``G05 P10000 / P0`` Fanuc high-precision contour control (HPCC) on / off.
``G61.1 [P..]``     Mazak geometry compensation (Mazak VORTEX i-series manual, 5 Supplement, "G-code
                    (Group13)", "A. Geometry compensation": pre-interpolation acceleration/deceleration,
                    feedforward, precise vector compensation, optimum corner deceleration), in the
                    group of G61-G64: a continuous-path mode, read as G64 without tolerance, the P
                    (the level Keycult's Mazak HCN post writes, P0-P3) noted. Fanuc and Haas define no
                    G61.1; LinuxCNC's (exact stop mode) stays under ``linuxcnc``.
=================== ===============================================================================

``G05 P2`` is refused by name: Mazak's high-speed machining mode (Keycult's Mazak HCN post, a fork of
Fusion's mazak.cps: "Enables G5 P2 for this operation"; its README: "high speed smoothing, high speed machining"),
a smoothing mode whose path vcnc does not model; :data:`G05_OTHERS` says so. Session 39 looked for Mazak's own
text (the docs, pages and code corpora: the Mazatrol/EIA programming manuals) to accept it as G05 P10000 is
accepted, with a note, and found none; only posts and third-party tables name it, so it stays refused.

In the ``linuxcnc`` dialect G5 and G5.1 are splines and G8 is lathe radius mode: these keys are
only read this way in the Fanuc and Haas dialects.
"""

from __future__ import annotations

import dataclasses

from interpolators.iso_words import WordError

__all__ = ["G05_OTHERS", "SMOOTHING_CODES", "Smoothing", "smoothing"]

#: Look-ahead codes (round(10 * G) -> name) of the Fanuc and Haas dialects.
SMOOTHING_CODES: dict[int, str] = {
    1870: "G187 smoothness control", 1030: "G103 block look-ahead limit", 51: "G05.1 AI contour control",
    80: "G08 AI advanced preview control", 50: "G05 high-precision contour control",
    611: "G61.1 geometry compensation (Mazak): continuous path, as G64",
}


@dataclasses.dataclass(frozen=True, kw_only=True)
class Smoothing:
    """What one look-ahead block does.

    Attributes
    ----------
    note : str
        The note for ``Program.notes``.
    consumed : tuple of str
        The block's words the code reads (they are not motion words).
    tolerance : float or None
        New path tolerance [program units] (G187 E), or None to leave it.
    reset : bool
        True when the tolerance returns to the dialect's default (G187 alone).
    continuous : bool
        True when the code selects a continuous-path mode without tolerance, as G64 does (Mazak G61.1).
    """

    note: str
    consumed: tuple[str, ...]
    tolerance: float | None = None
    reset: bool = False
    continuous: bool = False


#: The hint of a G05 other than Fanuc's HPCC P10000 / P0 (the module text).
G05_OTHERS = (" (Fanuc's high-precision contour control: P10000 on, P0 off; G05 P2 is Mazak's high-speed machining "
              "mode, G05 P0 its cancel: a smoothing mode vcnc does not model; the controls' other G05 functions are "
              "not supported either)")


def _choice(words: dict[str, float], letter: str, allowed: tuple[float, ...], code: str, hint: str = "") -> float:
    if letter not in words or words[letter] not in allowed:
        shown = " or ".join(f"{letter}{v:g}" for v in allowed)
        raise WordError(f"{code} needs {shown}{hint}", letter=letter if letter in words else None, expected=shown)
    return words[letter]


def smoothing(key: int, words: dict[str, float]) -> Smoothing:
    """Read one look-ahead code (a key of :data:`SMOOTHING_CODES`) with the block's words as written.

    Raises
    ------
    WordError
        A P, Q or E value the control does not define.
    """
    name = SMOOTHING_CODES[key]
    if key == 1870:
        if "P" in words:
            _choice(words, "P", (1.0, 2.0, 3.0), "G187")
        if "E" in words and not words["E"] > 0:
            raise WordError("G187 E (corner rounding) must be > 0", letter="E", expected="E > 0")
        return Smoothing(note=f"{name} (path tolerance from E)" if "E" in words else name,
                         consumed=("P", "E"), tolerance=words.get("E"), reset="P" not in words and "E" not in words)
    if key == 1030:
        p = words.get("P", 0.0)
        if p != int(p) or not 0 <= p <= 15:
            raise WordError("G103 P (blocks of look-ahead) must be 0-15", letter="P", expected="P0 .. P15")
        return Smoothing(note=name, consumed=("P",))
    if key == 51:
        q = _choice(words, "Q", (0.0, 1.0, 2.0, 3.0), "G05.1")
        consumed = ("Q", "R", "X", "Y", "Z", "A", "B", "C") if q >= 2.0 else ("Q", "R")
        note = {2.0: "G05.1 Q2 nano smoothing", 3.0: "G05.1 Q3 smooth tolerance+ control"}.get(q, name)
        return Smoothing(note=note, consumed=consumed)
    if key == 611:
        level = f" (P{words['P']:g}: its level, not modelled)" if "P" in words else ""
        return Smoothing(note=name + level, consumed=("P",), continuous=True)
    if key == 80:
        _choice(words, "P", (0.0, 1.0), "G08")
        return Smoothing(note=name, consumed=("P",))
    _choice(words, "P", (0.0, 10000.0), "G05", G05_OTHERS)
    return Smoothing(note=name, consumed=("P",))
