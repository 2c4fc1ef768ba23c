"""Fanuc/Haas custom macro B arguments: the words of a macro call that become the called macro's locals.

Fanuc Series 16i/18i operator's manual B-63684EN, 16 "Custom macro", "Simple call (G65)", "Argument
specification"; Fanuc 0i-MD B-64304EN the same; Haas mill operator's manual, "G65 Macro Subroutine Call" and
"Local Variables". A call ``G65 P9001 L2 A1. C2.5`` (and the modal calls ``G66``/``G66.1``,
:mod:`interpolators.iso_modal_call`) sets a new set of locals ``#1``-``#33``, vacant but for the arguments:

* argument specification I: A B C -> #1 #2 #3, I J K -> #4 #5 #6, D E F -> #7 #8 #9, H -> #11, M -> #13,
  Q R S T U V W X Y Z -> #17 .. #26;
* argument specification II: the n-th I J K -> #(3n+1) #(3n+2) #(3n+3), up to ten sets; where both set a
  variable, the later word wins ("the type of argument specification specified later takes precedence");
* G, L, N, O, P are no arguments ("The addresses G, L, N, O, P cannot be used in arguments"): P names the
  program, L the repeat count (a whole number >= 0; 1 when omitted), N is the block's sequence number.

An argument written as a number without a decimal point: "The units used for argument data passed without a
decimal point correspond to the least input increment of each address. The value of an argument passed without
a decimal point may vary according to the system configuration of the machine" (B-63684EN, "Position of the
decimal point"): :func:`macro_arguments`.
"""

from __future__ import annotations

from collections.abc import Callable

from interpolators._words import Where
from interpolators.iso_decimal import DECIMAL_LETTERS, integer_literal
from interpolators.iso_words import Word

__all__ = ["ARGUMENT_VARIABLES", "macro_arguments"]

#: Argument letters (argument specification I) -> local variable number.
ARGUMENT_VARIABLES = {"A": 1, "B": 2, "C": 3, "I": 4, "J": 5, "K": 6, "D": 7, "E": 8, "F": 9, "H": 11, "M": 13,
                      **{c: 17 + i for i, c in enumerate("QRSTUVWXYZ")}}


def _plain_argument(w: Word, where: Where, what: str, decimal_point_input: str | None,
                    on_note: Callable[[str], None] | None) -> None:
    """An argument written without a decimal point. The configuration is Fanuc's DPI (No. 3401#0, "when a decimal
    point is omitted in an address that can include a decimal point", :mod:`interpolators.iso_decimal`): under
    DPI = 1 (calculator) the value is read as written, noted; under DPI = 0 (increment) F, D, H, M, S and T, which
    count in their own unit either way, are read as written, and a distance, angle or other address is an error
    (its increment is not modelled for macro arguments). Other dialects: an error (our reading: the Haas manual
    says nothing of it)."""
    calculator = decimal_point_input == "calculator"
    if calculator or (decimal_point_input == "increment" and w.letter not in DECIMAL_LETTERS and w.letter != "E"):
        if calculator and on_note is not None:
            on_note(f"{what} argument {w.text} without a decimal point read as {w.value:g} (calculator-type input, "
                    "Fanuc DPI=1)")
        return
    where.fail(f"{what} macro call: argument {w.text!r} without a decimal point (the control scales it by its "
               "least input increment, which depends on the machine)", column=w.column, text=w.text,
               expected=f"{w.letter}{w.text[1:].strip()}. (with a decimal point)")


def macro_arguments(words: list[Word], where: Where, what: str, *, skip: tuple[Word, ...] = (),
                    decimal_point_input: str | None = None, on_note: Callable[[str], None] | None = None,
                    call_block: bool = True) -> tuple[dict[int, float], int]:
    """The locals a macro call's ``words`` set and its repeat count L.

    ``what`` names the call in messages ("G65", "G66"); the words in ``skip`` (the call's own G word) and the
    N word are not arguments, nor are P (the program) and L (the repeat count) of a ``call_block``; not a
    ``call_block`` (a block read as the arguments of a ``G66.1`` call): P and L are errors as G and O are.
    ``decimal_point_input``: Fanuc's DPI setting (``"calculator"``, ``"increment"``) for the arguments written
    without a decimal point; None: they are errors.
    """
    locals_: dict[int, float] = {}
    seen_ijk = {"I": 0, "J": 0, "K": 0}
    count = 1
    for w in words:
        if any(w is s for s in skip) or w.letter == "N" or w.letter == "P" and call_block:
            continue
        if w.letter == "L" and call_block:
            if w.value != int(w.value) or w.value < 0:
                where.fail(f"{what} macro call: the repeat count L must be a whole number >= 0", column=w.column,
                           text=w.text, expected="L1, L2, ...")
            count = int(w.value)
            continue
        if w.letter not in ARGUMENT_VARIABLES:
            where.fail(f"{what} macro call: {w.letter} is not an argument address", column=w.column, text=w.text,
                       expected="arguments A-F, H, I-K, M, Q-Z (not G, L, N, O, P)")
        if integer_literal(w):
            _plain_argument(w, where, what, decimal_point_input, on_note)
        if w.letter in seen_ijk:  # argument specification II: the n-th I J K set #(3n+1) .. #(3n+3)
            n = seen_ijk[w.letter]
            seen_ijk[w.letter] += 1
            number = 4 + 3 * n + "IJK".index(w.letter)
            if number > 33:
                where.fail(f"{what} macro call: more than ten I J K argument sets", column=w.column, text=w.text,
                           expected="at most ten I, J and K words each")
        else:
            number = ARGUMENT_VARIABLES[w.letter]
        locals_[number] = w.value
    return locals_, count
