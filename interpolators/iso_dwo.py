"""Haas ``G254`` dynamic work offset (DWO) and ``G255``, its cancel, on a tilting table.

Haas mill operator's manual (NGC), "G254 Dynamic Work Offset (DWO) (Group 23)": "G254 Dynamic Work Offset (DWO)
is similar to TCPC, except that it is designed for use with 3+1 or 3+2 positioning, not for simultaneous 4- or
5-axis machining ... DWO uses the current rotary positions and the machine rotary zero point (MRZP) to compute
where the work offset has gone"; "G255 cancels DWO". Fusion's Haas posts (OpenPostProject/haas ``haas.cps``
``setWorkPlane``) write ``G00 A.. C..`` (the indexing), then ``G254``, then the operation with X Y Z already
turned by the post into the machine's axes (``setRotation`` of the remaining orientation), and ``G255`` before
the next indexing.

What vcnc reads (``--dialect haas``, a machine with ``[program.kinematics]`` of a tilting table): at G254 the work
zero (work offset plus G92 offset, machine coordinates with the rotary axes at 0) is carried by the table to its
place at the present rotary positions (:meth:`interpolators.tilted.Kinematics.place`, about the axes' pivots, which
stand for the MRZP; a work offset selected under G254 is carried the same way), and every following move is shifted
by that translation, its X Y Z axes those of the machine (our reading of "work offset": a translation, as the post's
own rotation of the coordinates shows); arcs, cycles and compensation run as without it. G255 drops the shift.
Refused, each an error naming it: G254 without kinematics, on a head-tilting machine, under TCPC (G234) or a G68/G51
frame; a rotary axis word while G254 is in force (the posts cancel DWO with G255 before indexing: our reading, a
move whose offset would change along it).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["DWO_CODES", "carry_work_zero", "dwo_switch", "refuse_rotary_under_dwo"]

#: round(10 x G) of Haas's DWO codes, with their names.
DWO_CODES = {2540: "G254 dynamic work offset", 2550: "G255 dynamic work offset cancel"}

_EXPECTED = ("G254 after the rotary axes are positioned, on a machine whose rotary axes turn the part "
             "([program.kinematics] kind = \"table\"), G255 before they turn again")


def dwo_switch(entry: tuple[int, object], st: State, where: Where, notes: Notes) -> None:
    """G254 (``entry``: its key and word) starts the shift of the work zero to where the table has carried it,
    G255 ends it (the module text)."""
    key, w = entry
    if key == 2550:
        st.dwo = None
        notes.add("G254/G255 dynamic work offset")
        return
    kin = st.context.kinematics
    if kin is None:
        where.fail("G254 dynamic work offset needs the machine's kinematics", column=w.column, text=w.text,
                   expected="a machine with [program.kinematics] (the rotary axes that turn the part)")
    if kin.kind != "table":
        where.fail("G254 dynamic work offset on a head-tilting machine: not supported", column=w.column, text=w.text,
                   expected=_EXPECTED)
    if st.tcp or st.frame is not None or st.rotation:
        what = "tool centre point control (G234)" if st.tcp else "a G68 rotation, G51 scaling or G10 R rotation"
        where.fail(f"G254 dynamic work offset under {what}: not supported", column=w.column, text=w.text,
                   expected=_EXPECTED)
    carry_work_zero(st)
    notes.add("G254/G255 dynamic work offset")


def carry_work_zero(st: State) -> None:
    """``st.dwo``: the shift of the work zero in force (work offset plus G92 offset, machine coordinates with the
    rotary axes at 0) to where the table at its present rotary positions has carried it; at G254 and at each
    change of work offset (G54-G59, G54.1 P..) under it, the control's "active work offset" (the module text)."""
    kin = st.context.kinematics
    st.dwo = None
    zero = st.offset() - np.array([st.tool_xy[0], st.tool_xy[1], st.tool_length])
    st.dwo = kin.place(zero, kin.solution_at(st.extra)) - zero


def refuse_rotary_under_dwo(st: State, letters: list[str], seen, where: Where) -> None:
    """A rotary axis word (``letters``: the block's A-W words, ``seen`` its words) while G254 is in force."""
    rotary = [a for a in letters if a in "ABC" and a.lower() in st.context.kinematics.names]
    if st.dwo is not None and rotary:
        w = seen[rotary[0]]
        where.fail(f"axis word {w.letter} under G254 dynamic work offset: not supported", column=w.column,
                   text=w.text, expected="G255 before the rotary axes turn, G254 again after")
