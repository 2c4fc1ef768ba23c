"""Fanuc decimal-point input: what a number written without a decimal point means.

On a Fanuc control, parameter DPI (No. 3401#0) decides how an address that takes a decimal point
reads a number written without one (Fanuc Series 0i-MF operator's manual B-64604EN, II-"Decimal
point programming" and parameter manual No. 3401#0 DPI; Series 30i-B the same): DPI = 0, the default,
counts it in least input increments (IS-B: 0.001 mm, 0.0001 in, 0.001 deg, so ``X10`` is 0.010 mm
and ``X10.`` 10 mm); DPI = 1, "calculator-type decimal point input", reads it in whole units
(``X10`` is 10 mm). The addresses this applies to are those of distances, angles and times: X Y Z,
U V W, A B C, I J K, Q and R, and the dwell ``G04 X`` (0.001 s); F is a feed in its own unit
(mm/min, ``F100`` is 100 mm/min either way), and P, L, K as a repeat count, D, H, N, S, T, M are
integers. The corner words ``,R`` and ``,C`` (0i-MF "Optional chamfering and corner R") are lengths as R is: under
DPI = 0 ``,R2`` is 0.002 mm and ``,R2.`` 2 mm (our reading: a corner's radius or chamfer is a distance like the other
distance words, and no manual text at hand gives the comma words a unit or an exception of their own). Numbers that
come from a variable or an expression (``X#1``, ``X[10]``) carry their own decimal point (Mitsubishi M700V
programming manual 5.3 "Decimal Point Input", which describes the same two types: "Command X1 in the 1 um system is
equivalent to command X0.001"; values of variables are read "the same way in either" type).
The scaling factors of ``G51 I J K`` / ``P`` have their own rule
(:func:`interpolators.iso_transforms.scaling`; its centre ``X Y Z`` is a position like any other: 0i-MF
"Scaling", "absolute command for center coordinate value"), and so do the arguments of ``G65``
(:mod:`interpolators.iso_flow`: as written under DPI = 1, noted; under DPI = 0 as written for F D H M S T,
an error for the others, whose increments are not modelled); the switches of ``G05.1 Q1`` and ``G08 P1`` are
no distances.

Haas, LinuxCNC and grbl read whole units: the setting (``MachineContext.decimal_point_input``)
only applies under the ``fanuc`` dialect. The default, ``"calculator"``, changes nothing; under
it a Fanuc program with such words gets a note (a Fanuc with DPI = 0 would run it a thousand
times smaller). IS-C (0.0001 mm) is not modelled.
"""

from __future__ import annotations

import dataclasses
import re

from interpolators.iso_corners import CORNER_LETTERS
from interpolators.iso_words import Word

__all__ = ["DECIMAL_POINT_INPUTS", "DECIMAL_LETTERS", "integer_literal", "decimal_literal", "decimal_point_words",
           "decimal_point_note", "address_increment", "WHOLE_LETTERS"]

#: Values of ``MachineContext.decimal_point_input``: Fanuc DPI = 1 and DPI = 0.
DECIMAL_POINT_INPUTS: tuple[str, ...] = ("calculator", "increment")
#: Addresses whose numbers without a decimal point are counted in least input increments under DPI = 0.
DECIMAL_LETTERS = frozenset("XYZUVWABCIJKQR")

#: Least input increment of IS-B [program unit]: mm, inch, and deg (rotary axes, angles).
_INCREMENT = {"mm": 0.001, "inch": 0.0001, "deg": 0.001}
#: Addresses counted in whole units (codes, numbers and counts, spindle speed): their least input increment is 1.
WHOLE_LETTERS = frozenset("DGHLMNOPST")
_CYCLE_CODES = {73, 74, 76, 77, 81, 82, 83, 84, 85, 86, 87, 88, 89}
#: Blocks whose words are no distances: G65 macro arguments and G51 scaling factors (their own rules),
#: the look-ahead switches G05 P10000, G05.1 Q1, G08 P1 (:mod:`interpolators.iso_smoothing`).
_OWN_RULES = {65, 51, 5, 5.1, 8}


def address_increment(letter: str, *, inch: bool) -> float | None:
    """The least input increment of address ``letter`` (IS-B, as :data:`_INCREMENT`) [program unit]: 0.001 mm,
    0.0001 in or 0.001 deg for the distances and angles (:data:`DECIMAL_LETTERS`, the corner words ``,R`` ``,C``),
    1 for the addresses of :data:`WHOLE_LETTERS`; None for the others (F, E), whose increment is not modelled.
    What Fanuc's and Haas's ``ROUND`` rounds to in an NC address (:mod:`interpolators.iso_params`)."""
    letter = letter.upper()
    if letter in ("A", "B", "C"):
        return _INCREMENT["deg"]
    if letter in DECIMAL_LETTERS or letter in CORNER_LETTERS:
        return _INCREMENT["inch" if inch else "mm"]
    return 1.0 if letter in WHOLE_LETTERS else None


def integer_literal(word: Word) -> bool:
    """True when the word is written as a plain number without a decimal point (``X10``, ``Y-5``, ``,R2``)."""
    return re.fullmatch(r",?\s*[A-Za-z]\s*[+-]?\s*\d+", word.text) is not None


def decimal_literal(word: Word) -> bool:
    """True when the word is written as a plain number with a decimal point (``P2.0``, ``P.5``, ``P3.``)."""
    return re.fullmatch(r"[A-Za-z]\s*[+-]?\s*(\d+\.\d*|\.\d+)", word.text) is not None


def _scaled(words: list[Word], *, cycle: bool) -> list[Word]:
    """The words of a block a least input increment applies to (see the module docstring)."""
    codes = {round(w.value, 1) for w in words if w.letter == "G"}
    if codes & _OWN_RULES - {51}:
        return []
    if 51 in codes:  # G51's centre X Y Z is a position (0i-MF "Scaling": "absolute command for center coordinate")
        return [w for w in words if w.letter in "XYZ" and integer_literal(w)]
    cycle = cycle or bool(codes & _CYCLE_CODES)
    return [w for w in words if (w.letter in DECIMAL_LETTERS or w.letter in CORNER_LETTERS) and integer_literal(w)
            and not (w.letter == "K" and cycle)]


def decimal_point_words(words: list[Word], *, mode: str, inch: bool, cycle: bool) -> tuple[list[Word], Word | None]:
    """The block's words as a Fanuc control with ``mode`` reads them, and the first word without a
    decimal point it reads differently from the other mode (None: none).

    Parameters
    ----------
    words : list of Word
        The block's words.
    mode : {"calculator", "increment"}
        Fanuc DPI = 1 or DPI = 0.
    inch : bool
        G20 in effect for this block (0.0001 in per increment; else 0.001 mm).
    cycle : bool
        A canned cycle is modal (its K is a repeat count).
    """
    scaled = _scaled(words, cycle=cycle)
    differs = next((w for w in scaled if w.value != 0), None)  # X0 is 0 either way
    if not scaled or mode == "calculator":
        return words, differs
    dwell = any(w.letter == "G" and round(w.value, 1) == 4 for w in words)
    out = []
    for w in words:
        if w in scaled:
            unit = "deg" if w.letter in "ABC" else "mm" if not inch or (dwell and w.letter == "X") else "inch"
            w = dataclasses.replace(w, value=w.value * _INCREMENT[unit])
        out.append(w)
    return out, differs


def decimal_point_note(word: Word, *, inch: bool) -> str:
    """The note of a Fanuc program read with calculator-type input that has ``word`` without a decimal point."""
    unit = "deg" if word.letter in "ABC" else "in" if inch else "mm"
    small = word.value * _INCREMENT["deg" if unit == "deg" else "inch" if inch else "mm"]
    digits = 4 if unit == "in" else 3
    return (f"{word.text} without a decimal point read as {word.value:g} {unit} (calculator-type input, Fanuc "
            f"DPI=1); a Fanuc with DPI=0 reads {small:.{digits}f} {unit}")
