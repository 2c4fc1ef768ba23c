"""The ISO reader's returns to the machine's reference positions (:mod:`interpolators.iso`): G28/G30 through the
programmed intermediate point (LinuxCNC G-code reference, G28/G30: only the axes named move, none named: all), the
Fanuc/Haas G27, G29 and G60 as rapids of the named axes, and grbl's ``$H`` homing cycle run as a rapid home."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.iso_axes import EXTRA_LETTERS, extra_target, wrapped_reference, wrapped_target
from interpolators.iso_motion import block_target, rapid_move
from interpolators.iso_offsets import length_cancelled, length_travel
from interpolators.iso_polar import POLAR_LETTERS
from interpolators.iso_reference import FANUC_CODES, MILL_CODES, off_reference, stored_intermediate

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["reference_return", "mill_positioning", "grbl_homing"]


def reference_return(key: int, seen, axis_words, st: State, blocks, used, where: Where, number) -> None:
    """G28/G30: through the programmed intermediate point to the reference, only the axes named
    (A-W words too); without axis words every axis, A-W to their reference positions. A tool length change not yet
    travelled (Fanuc, Haas, Fadal: :func:`interpolators.iso_offsets.length_travel`) is taken up by the intermediate
    point's incremental Z; at its reference the offset vector is cancelled, to be restored by the next Z move
    (:func:`interpolators.iso_offsets.length_cancelled`)."""
    ref = st.home if key == 280 else st.reference2
    ref_rot = st.home_extra if key == 280 else st.reference2_extra
    rot_words = [a for a in EXTRA_LETTERS if a in seen]
    if axis_words or rot_words:
        mid = length_travel(block_target(seen, axis_words, st, machine=False), axis_words, st)
        mid_rot = None
        if rot_words:
            st.extra_used = True
            used.update(3 + EXTRA_LETTERS.index(a) for a in rot_words)
            mid_rot = extra_target({a: seen[a].value for a in rot_words}, st.extra, st.extra_offset(),
                                   incremental=st.incremental, scale=st.scale)
            mid_rot = wrapped_target(mid_rot, {a: seen[a] for a in rot_words}, st, where)
        rapid_move(mid, st, blocks, used, where, number, axis_words, rot=mid_rot)
        for a in axis_words:  # Fanuc/Haas G29 returns through it (program coordinates)
            st.intermediate["XYZ".index(a)] = st.to_program(mid)["XYZ".index(a)]
        end = st.pos.copy()
        for a in axis_words:
            end["XYZ".index(a)] = ref["XYZ".index(a)]
        end_rot = None
        if rot_words:
            end_rot = st.extra.copy()
            for a in rot_words:
                end_rot[EXTRA_LETTERS.index(a)] = ref_rot[EXTRA_LETTERS.index(a)]
            end_rot = wrapped_reference(end_rot, st, tuple(a.lower() for a in rot_words))
        rapid_move(end, st, blocks, used, where, number, axis_words, rot=end_rot)
        if "Z" in axis_words:
            length_cancelled(st)
    else:
        length_cancelled(st)  # Z goes to its reference
        st.intermediate = st.to_program(st.pos)
        ref_rot = wrapped_reference(ref_rot.copy(), st)
        back = st.extra_used and bool(np.any(st.extra != ref_rot))
        rapid_move(ref.copy(), st, blocks, used, where, number, ["X", "Y", "Z"], rot=ref_rot.copy() if back else None)


def mill_positioning(key: int, seen, axis_words, st: State, blocks, used, where: Where, number,
                      notes: Notes) -> None:
    """Fanuc/Haas G27, G29 and G60 (:mod:`interpolators.iso_reference`): rapids of the named axes; an incremental Z
    travels a tool length change not yet travelled (:func:`interpolators.iso_offsets.length_travel`)."""
    name = {**MILL_CODES, **FANUC_CODES}[key][1]
    code = name.split()[0]
    bad = next((a for a in (*EXTRA_LETTERS, *POLAR_LETTERS, "I", "J", "K", "R") if a in seen), None)
    if not axis_words or bad is not None or st.comp_side is not None:
        why = (f"with word {bad}: not supported" if bad is not None else
               f"with cutter compensation on ({st.comp_code}): not supported" if st.comp_side is not None else
               "needs axis words (the axes it moves)")
        word = seen[bad] if bad is not None else None
        where.fail(f"{name} {why}", column=word.column if word else 1, text=word.text if word else where.text,
                   expected=f"{code} X.. Y.. Z.. (G40 before it)")
    if key == 290:
        try:
            mid = stored_intermediate(st.intermediate, st.to_program(st.pos), axis_words)
        except KeyError as exc:
            word = seen[exc.args[0]]
            where.fail(f"{name}: no G28/G30 intermediate point for axis {word.letter} (no G28/G30 named it before)",
                       column=word.column, text=word.text, expected=f"G28 {word.letter}.. before {code}")
        rapid_move(st.to_machine(mid), st, blocks, used, where, number, axis_words)
        if "Z" in axis_words:  # a program point: the length vector a G28 Z cancelled is back in it (length_cancelled)
            st.length_pending = 0.0
    target = length_travel(block_target(seen, axis_words, st, machine=False), axis_words, st)
    rapid_move(target, st, blocks, used, where, number, axis_words)
    if key == 270:
        missed = off_reference(st.pos, st.home, axis_words)
        notes.add(f"{name}" + (f": {', '.join(missed)} not at the reference position (the control alarms: PS0092)"
                               if missed else ""))
    elif key == 600:
        notes.add(f"{name} run as a rapid to the end point (the overrun, a machine parameter, is not modelled)")
    else:
        notes.add(name)


def grbl_homing(st: State, blocks, used, where: Where, notes: Notes) -> None:
    """grbl ``$H`` (:mod:`interpolators.iso_grbl`): Z to the machine's home, then X and Y, as rapids
    [mm, machine]; offsets and modes stay."""
    home = np.array(st.context.home, dtype=float)
    up = st.pos.copy()
    up[2] = home[2]
    rapid_move(up, st, blocks, used, where, None, ["Z"])
    rapid_move(home, st, blocks, used, where, None, ["X", "Y"])
    st.stopped = False
    notes.add("grbl $H homing run as rapids to home (Z, then X Y)")
