"""Fanuc custom macro B modal calls: ``G66`` (call after each move), ``G66.1`` (call for each block), ``G67``.

Sources: Fanuc Series 0i-MD operator's manual B-64304EN and Series 16i/18i B-63684EN, "Custom macro",
"Modal call: call after the move command (G66)" and "Modal call: each block call (G66.1)"; the local-variable
levels and call nesting of B-63684EN 16 "Custom macro", "Call nesting", "Local variable levels"
(http://www.cncmanuals.com/fanuc/477/series-16i-18i-160i-180i-pb-operators-manual/page/304: "Each time a macro is
called (with G65 or G66), the local variable level is incremented by one"); for nested modal calls, which those
manuals give in one sentence ("Modal calls can be nested by specifying another G66 code during a modal call"),
the Mitsubishi M700V programming manual, 13.5 "User macro specifications", Note 2 ("when the G66 command has been
duplicated, the next user macro subprogram is called every time an axis is moved even with movement commands in
the macro. User macro subprograms are called in sequence from the subprogram commanded last") and the NCT 99M/2000M
manual, 20 "Custom macro" (G67 cancels the modal call specified last; nested G66.1 calls "first the last specified
macro ... then the previously specified macro ..., entering the blocks of that macro and treating them as
arguments").

* ``G66 P<program> L<repeats> <arguments>``: from the next block on, after every block that commands a move
  (:func:`moves`), the program ``O<P>`` runs L times (1 when omitted), its locals ``#1``-``#33`` set from the
  G66 block's arguments as for ``G65`` (:mod:`interpolators.iso_macro_args`). "In a G66 block, no macros can be
  called"; "No macros can be called in a block which contains a code such as a miscellaneous function that does
  not involve movement along an axis"; "Local variables (arguments) can only be set in G66 blocks" -- and "local
  variables are not set each time a modal call is performed": our reading is that the blocks of moves pass no
  arguments, and each call starts a new local level (its locals the G66 block's arguments afresh; what a call
  leaves in them is gone at its M99, as at a G65's).
* ``G66.1 P<program> L<repeats> <arguments>``: from the next block on, every NC block (not a macro statement
  ``#i = ..``, ``IF``, ``GOTO``, ``WHILE``) is not executed but calls the program, its words the arguments
  (over those of the G66.1 block). Our reading, from Mitsubishi's wording ("called unconditionally for every
  command block which is assigned between G66.1 and G67"): the G66.1 block itself calls nothing; a word that is no
  argument address (G, L, O, P) in such a block is an error, as the manuals at hand do not say what it does; a
  block of a sequence number alone calls nothing.
* ``G67`` cancels the modal call specified last (G66 or G66.1; a second G67 the one before it); without one it
  does nothing (G67 is the power-on state of its group). The rest of its block runs, and calls nothing. A G67 in
  a modal call's macro cancels the modal call specified last as anywhere else (our reading: the group's modal
  state is one for all levels): with one G66, the macro's own, which makes no call after the macro returns.
* Nesting: modal calls stack. A move (G66) or block (G66.1) of the main program, or of an M98 subprogram or G65
  macro it calls, calls the modal call specified last; a move or block of the macro that modal call runs calls
  the one specified before it, and so on: the oldest modal call's macro calls none (so one G66's macro does not
  call itself). A ``G66`` or ``G66.1`` in the macro of a modal call (nesting from inside a modal call's macro) is
  an error: how it would stack with the calls under way is not modelled. That the moves of an M98 subprogram or
  a G65 macro called in G66 mode call the modal macro is our reading (M98 keeps the local level; the manuals do
  not say it for G65).
* A block that calls or returns (M98, M97, M99, G65) calls no modal macro (our reading).

LinuxCNC and grbl have no G66; the Haas mill G-code list (Haas mill operator's manual 96-8000, "G-codes") has
G65 but no G66/G67: those dialects refuse it, naming it.
"""

from __future__ import annotations

import dataclasses

from interpolators.iso_words import Word

__all__ = ["MODAL_CALL_CODES", "ModalCall", "ModalCalls", "moves"]

#: The G codes of modal macro calls (group 12 of the Fanuc G-code list): G66, G66.1, G67.
MODAL_CALL_CODES = (66.0, 66.1, 67.0)

#: Axis addresses: a block with one of them commands a move, unless one of :data:`_NOT_MOVES` gives it
#: another meaning.
_AXES = frozenset("XYZABCUVW")
#: G codes ×10 whose axis words are no move: dwell (G04 X), data setting (G10, G11), stored stroke check (G22),
#: local and workpiece coordinate systems (G52, G92, G92.1), rotation and tilted-plane centres (G68, G68.2),
#: scaling and mirror image (G51, G51.1, G50.1) and the macro calls (G65, G66, G66.1, G67).
_NOT_MOVES = frozenset({40, 100, 110, 220, 501, 510, 511, 520, 650, 660, 661, 670, 680, 682, 920, 921})


def moves(words: list[Word]) -> bool:
    """Whether a block commands a move along an axis: it has an axis word (X Y Z A B C U V W) that no G code of
    :data:`_NOT_MOVES` reads otherwise (our reading of "a block specifying movement along an axis"; a canned
    cycle's hole position is one)."""
    if not any(w.letter in _AXES for w in words):
        return False
    return not any(w.letter == "G" and round(w.value * 10) in _NOT_MOVES for w in words)


@dataclasses.dataclass(frozen=True)
class ModalCall:
    """One modal call: ``each_block`` (G66.1; else G66), the called ``program`` number and the index ``start`` of
    its first line, the ``arguments`` (locals) of its G66/G66.1 block and the ``repeats`` L of each call."""

    each_block: bool
    program: int
    start: int
    arguments: dict[int, float]
    repeats: int

    @property
    def code(self) -> str:
        return "G66.1" if self.each_block else "G66"


class ModalCalls:
    """The modal calls in force, the one specified last on top."""

    def __init__(self) -> None:
        self.calls: list[ModalCall] = []

    @property
    def group_code(self) -> float:
        """The G code of group 12 in force (system variable ``#4012``): 66, 66.1 or 67."""
        return 67.0 if not self.calls else 66.1 if self.calls[-1].each_block else 66.0

    def specify(self, call: ModalCall) -> None:
        """A G66 / G66.1 block."""
        self.calls.append(call)

    def cancel(self) -> None:
        """A G67 block: the modal call specified last ends (none: nothing happens)."""
        if self.calls:
            self.calls.pop()

    def due(self, words: list[Word], limit: int | None) -> int | None:
        """The index of the modal call a block of ``words`` makes, if any. ``limit``: the index of the modal call
        whose macro the block belongs to (only the calls specified before it can be made), None for the main
        program's blocks (any)."""
        below = len(self.calls) if limit is None else min(limit, len(self.calls))
        if below == 0:
            return None
        call = self.calls[below - 1]
        if call.each_block:
            return below - 1 if any(w.letter != "N" for w in words) else None
        return below - 1 if moves(words) else None
