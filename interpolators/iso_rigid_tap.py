"""Fanuc ``M29 S..`` rigid tapping: what arms it, what the tap needs, what ends it (``--dialect fanuc``).

Fanuc 0i-B connection manual (function) B-63833EN-1/02, 9 "Spindle speed function", "Rigid tapping" (stored at
cncmanuals.com, page 540 of the manual): "M29 S1000 ; G84 Z-100. R-20. F1. ; ... G80 ;" under G99 (feed per
revolution) or G98 (per minute, F/S the lead), with no M03: the control drives the spindle in step with the tapping
axis for the G84 (G74: left-handed) that follows. What vcnc reads of it:

- ``M29`` arms the rigid mode; the S in force is the tap's speed (``M29 S..`` sets it in the same block). A tapping
  cycle that runs armed with no spindle speed (S0, or no S word since the start or since the last rigid tap ended)
  is refused: the Fanuc alarm lists name it PS0200 "ILLEGAL S CODE COMMAND" (in the rigid tap, an S value is out of
  the range or is not specified).
- An axis movement after the M29 block and before its G84/G74 is refused: the alarm lists' PS0204 "ILLEGAL AXIS
  OPERATION" (an axis movement between the rigid M code (M29) block and the G84 (G74) block). A movement in the
  M29 block itself is taken (``G00 Z15. M29 S500``).
- An S word in a block after the M29 block and before its G84/G74 (``M29 S500 ; S600 ; G84 ..``), and an M29 in a
  block that names no motion code while a tapping cycle is in force (``G84 .. ; M29 S500 ; X5.``: the M29 after
  its tapping command), are refused: the alarm lists' 0203 "PROGRAM MISS AT RIGID TAPPING" ("In the rigid tap,
  position for a rigid M code (M29) or an S command is incorrect"; the FANUC Series 0i alarm list as copied in
  public alarm tables). Which positions the control calls incorrect is our reading: an S in the tapping block
  itself (``M29 ; G84 .. S500``) and an M29 in a block that specifies the tapping cycle (``G84 .. M29 S500``) are
  taken. G74 is armed as G84 is (left-handed); under G95 the tap's F is the lead, the feed F x S.
- Not modelled: Fanuc's rigid tapping by G84 alone (parameter G84, No. 5200#0 = 1), which makes a G84 without M29
  rigid: vcnc runs that G84 on the same path (in to Z, out to R at the feed), the only difference being that a
  floating tap under G95 needs the spindle turned on (M03), which vcnc then asks for. The Series 15 format
  ``G84.2``/``G84.3`` is refused by name (:mod:`interpolators.iso_codes`).
- The rigid mode ends with the tapping cycle: at G80, at a group 01 code (G00-G03; B-64304EN "Canned cycle for
  drilling": a cycle is canceled by G80 or a group 01 G code), at a canned cycle other than G84/G74 (``M29 S.. ;
  G84 .. ; G81 .. ; G84 ..``: the second G84 is a floating-holder tap again) and at the program end (a reset);
  with it the S of the rigid tap is cleared, as if S0 were specified (the operator's manuals' "Rigid tapping"
  limitations, "S command": "specify an S command again after cancellation of rigid tapping"); an S word given
  since the tap, or in the block that ends it (``G80 S1000 M03``), is the next operation's and kept.

- A Q in force in an armed G84/G74 (the block's, or the series' sticky Q: Fanuc keeps Q as modal cycle data) is
  Fanuc's peck rigid tapping (16i-TA/TB A-78549E 3.4 and the 0i-F / 16i mill operator's manuals, "Peck rigid
  tapping cycle (G84 or G74)": "Q_ : Depth of cut for each cutting feed"): with parameter PCP (No. 5200#5) = 0 the
  high-speed peck (each cut of q, then back by d, parameter No. 5213, the spindle reversed, then on by d + q), with
  PCP = 1 the peck back to point R each time (d then the cutting start distance above the last depth). The machine
  states both in its file (``[program] peck_tapping``, ``peck_tapping_d``:
  :attr:`interpolators.context.Dialect.peck_tapping`), and the cycle pecks so (:func:`rigid_tap_peck`, the moves
  :func:`interpolators.iso_cycles.cycle_moves`); every move in the hole is at the tapping feed (our reading: the
  retraction override, parameter No. 5211, is not modelled). A machine that states neither is refused by name,
  the manuals giving no default for PCP or d, rather than tapped in one stroke with the Q dropped; so is a peck
  rigid tap under G51 scaling (our reading: Q and d stay unscaled there, as the 0i's "Scaling" says of G73/G83's
  Q and d). A Q in a G84/G74 without M29 (a floating-holder tap; Fanuc's format has no Q there) is noted as not
  used, since a machine with parameter G84 (No. 5200#0) = 1 taps G84 rigidly and would peck.

The alarm texts and the S and cancel rules are taken from the Fanuc 0i/16i operator's manuals' "Rigid tapping"
section and alarm lists as we know them; none of those pages is in the texts searchable here (the connection
manual page above is): our reading where they are not quoted.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from interpolators._words import Where

if TYPE_CHECKING:
    from interpolators.iso import Notes, State
    from interpolators.iso_words import Word

__all__ = ["RIGID_TAP_NOTE", "arm_rigid_tap", "end_rigid_tap", "m29_in_tapping_cycle", "rigid_tap_moved",
           "rigid_tap_peck", "rigid_tap_speed"]

#: The note of a program that arms Fanuc's rigid tapping.
RIGID_TAP_NOTE = "M29 S.. rigid tapping (Fanuc): the G84/G74 that follows turns the spindle itself"

#: round(10 x G) of the tapping cycles M29 arms.
_TAPPING = (740, 840)


def arm_rigid_tap(st: State, where: Where, notes: Notes) -> None:
    """``M29`` (``st.context.dialect`` fanuc): the next G84/G74 is a rigid tap; ``where`` is the M29 block."""
    st.rigid_tap = True
    st.rigid_tap_at = where
    notes.add(RIGID_TAP_NOTE)


def m29_in_tapping_cycle(st: State, m29: Word, has_motion_code: bool, where: Where) -> None:
    """Before a block with M29 (``m29``): a tapping cycle in force (``st.motion``, the block naming no motion code) is
    refused, the M29 coming after its tapping command (alarm 0203, the module text)."""
    if st.motion in _TAPPING and not has_motion_code:
        where.fail(f"M29 while the {'G74' if st.motion == 740 else 'G84'} tapping cycle is in force: Fanuc refuses it "
                   "(alarm 0203 program miss at rigid tapping: the position of M29 is incorrect)", column=m29.column,
                   text=m29.text, expected="G80, then M29 S.. before the G84/G74 block (or in it)")


def rigid_tap_moved(st: State, moved: bool, where: Where, words: tuple[Word, ...] | list[Word] = ()) -> None:
    """After each block while an M29 waits for its tap: a tapping cycle in force takes it; an axis movement
    (``moved``: the block made motion) in any later block before it is refused (PS0204, the module text), also when
    the block's own code ended the rigid mode (``M29 S.. ; G00 X..``); so is an S word among the block's ``words``
    while the rigid mode waits on (alarm 0203, the module text)."""
    armed = st.rigid_tap_at
    later = (armed.file, armed.line) != (where.file, where.line)
    s_word = next((w for w in words if w.letter == "S"), None)
    if st.rigid_tap and st.motion in _TAPPING:
        st.rigid_tap_at = None
        st.rigid_tap_s = st.spindle_speed
    elif moved and later:
        where.fail(f"axis movement after M29 (line {armed.line}) before its G84/G74: Fanuc refuses it (alarm PS0204 "
                   "illegal axis operation)", column=1, text=where.text,
                   expected="M29 S.. right before the G84/G74 block, or in it; position the tool before the M29")
    elif st.rigid_tap and later and s_word is not None:
        where.fail(f"S word after M29 (line {armed.line}) before its G84/G74: Fanuc refuses it (alarm 0203 program "
                   "miss at rigid tapping: the position of the S command is incorrect)", column=s_word.column,
                   text=s_word.text, expected="the tap's speed in the M29 block (M29 S..) or in the G84/G74 block")
    elif not st.rigid_tap:
        st.rigid_tap_at = None


def rigid_tap_speed(st: State, name: str, where: Where, column: int, text: str) -> None:
    """A tapping cycle (``name``) armed by M29 needs a spindle speed (PS0200, the module text)."""
    if st.rigid_tap and st.motion in _TAPPING and not st.spindle_speed > 0:
        where.fail(f"{name} after M29 rigid tapping without a spindle speed (S0): Fanuc refuses it (alarm PS0200 "
                   "illegal S code command)", column=column, text=text,
                   expected="M29 S<spindle speed> > 0 [rev/min] before the G84/G74 (the S of an earlier rigid tap "
                            "is cleared when it ends)")


def rigid_tap_peck(st: State, q: Word | None, name: str, where: Where,
                   notes: Notes | None) -> tuple[str, float] | None:
    """A tapping cycle block (``st.context.dialect`` fanuc; ``q`` its Q word): after M29 with a Q in force (the
    block's or the series'), the machine's peck rigid tapping, ``(kind, d [mm])`` of
    :attr:`interpolators.context.Dialect.peck_tapping`; refused where the machine file does not state it or under
    G51 scaling; None otherwise. A Q without M29 is noted as not used (the module text)."""
    if st.motion not in _TAPPING:
        return None
    code = "G74" if st.motion == 740 else "G84"
    if st.rigid_tap and (q is not None or st.cycle.q is not None):
        dialect = st.context.dialect
        column, text = (q.column, q.text) if q is not None else (1, where.text)
        if dialect.peck_tapping is None:
            where.fail(f"{name} with Q after M29: Fanuc's peck rigid tapping (Q the depth of each cut; parameter PCP "
                       "No. 5200#5 chooses the high-speed peck, back by d = parameter No. 5213, or the peck back to "
                       "R): the machine file states neither PCP nor d, and the manuals give no default",
                       column=column, text=text,
                       expected=f"[program] peck_tapping = \"high-speed\" | \"standard\" and peck_tapping_d = <d "
                                f"mm> in the machine file, or {code} without Q (G80 clears a Q of the series)")
        if st.frame is not None and st.frame.scaled:
            where.fail(f"{name} with Q after M29 (peck rigid tapping) under G51 scaling: not supported (Q and d "
                       "stay unscaled, our reading of Fanuc's scaling of G73/G83)", column=column, text=text,
                       expected="G50 before the peck rigid tap")
        return dialect.peck_tapping, dialect.peck_tapping_d
    if q is not None and notes is not None:
        notes.add(f"{code} Q without M29 (Fanuc): the Q is not used, the tap runs in one stroke to Z (Fanuc's "
                  "floating-holder tap has no Q; a machine tapping G84 rigidly, parameter No. 5200#0, would peck)")
    return None


def end_rigid_tap(st: State, words: tuple[Word, ...] | list[Word] = ()) -> None:
    """The tapping cycle M29 armed ends (G80, a group 01 code, another canned cycle, the program end; ``words``: the
    block's): the rigid mode ends, and the S of a rigid tap that ran is cleared (the module text), but for an S word
    in the block or since the tap (``G80 S1000 M03``, ``S1000 M03`` then ``G81``: given for what follows). An M29
    still waiting for its tap is judged after the block (:func:`rigid_tap_moved`)."""
    if st.rigid_tap and st.rigid_tap_at is None and st.spindle_speed == st.rigid_tap_s and not any(
            w.letter == "S" for w in words):
        st.spindle_speed = 0.0
        if st.per_rev:  # F x S: no feed until an S again
            st.feed = st.feed_rotary = None
    st.rigid_tap = False
