"""Fanuc ``G43.4`` and Haas ``G234`` tool centre point control on a tilting table; the geometry is
:mod:`interpolators.tcp`'s.

FANUC Series 30i-MODEL A, "Tool center point control for 5-axis machining" (A-79348E), 1.1: ``G43.4 H..``
(type 1) or ``G43.5 H..`` (type 2: the tool direction I J K instead of the rotary words) starts it, G49 (any
other code of group 08) ends it; X, Y, Z are the tool tip in the programming
coordinate system, "fixed on the table" (parameter WKP, No. 19696#5, = 0), which "rotates as the table turns";
"If linear interpolation is specified in this function mode, speed control is exerted in such a way that the
tool center point moves at a specified speed with respect to the workpiece"; "Any command that does not move
the tool center point with respect to the workpiece (one that moves the rotary axes only) must be executed in
G00 or G01 mode". Haas mill operator's manual, "G234 Tool Center Point Control (TCPC) (Group 08)": the same on
a UMC ("TCPC makes sure that this coordinate system remains fixed relative to the table; when the rotary axes
rotate, the linear coordinate system rotates with them"); Fusion 360's Haas UMC post writes ``G234 H..``, its
Fanuc 5-axis posts ``G43.4 H..``, then ``G1 X.. Y.. Z.. A.. C.. F..``.

What vcnc reads: G43.4 and G43.5 under ``--dialect fanuc``, G234 under ``--dialect haas``, on a machine with
``[program.kinematics]`` of a tilting table (:class:`interpolators.tilted.Kinematics` ``kind = "table"``); the H
word takes the tool length as G43 does. G00 and G01 blocks, their rotary words moving or not, under G90 or G91,
G94 or G93 (inverse time: the block takes 1/F minutes): each a straight line of the tip on the part, emitted as
chords (:func:`interpolators.tcp.tcp_chords`; G64 P / the dialect's tolerance, else the default). Not read,
each an error naming it: G43.4 without kinematics, on a head-tilting machine, with a tilted plane (G68.2),
rotation, scaling or mirror image, or cutter compensation (G41/G42); arcs, canned cycles, polar coordinates,
G95 and the corner words ,R ,C under it; I J K under type 1, rotary words under type 2. G43.5's I J K (one left
out is 0) turn the rotary axes to the solution nearest their positions
(:func:`interpolators.tcp.tool_vector_extra`), moving linearly to it (our reading: the manual does not say how
type 2 interpolates the direction).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.iso_axes import EXTRA_LETTERS, extra_target, wrapped_target
from interpolators.iso_motion import block_target, initial_feed
from interpolators.program import Block
from interpolators.tcp import ChordsError, block_time, machine_point, part_point, tcp_chords, tool_vector_extra
from interpolators.tilted import TiltError
from toolpaths.geometry import Line

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["TCP_CODES", "tcp_switch", "tcp_block", "tip_point"]

#: round(10 x G) of the codes that start tool centre point control, with their names.
TCP_CODES = {434: "G43.4 tool centre point control", 435: "G43.5 tool centre point control type 2",
             2340: "G234 tool centre point control"}

_EXPECTED = ("G43.4 H.. (--dialect fanuc) or G234 H.. (--dialect haas) on a machine whose rotary axes turn the part "
             "([program.kinematics] kind = \"table\"), then G00/G01 X Y Z A B C, G49 to end it")


def tip_point(st: State) -> np.ndarray:
    """Where the program's current point is, in machine coordinates at rotary 0 (tool length along Z included):
    under TCP the tool tip on the part (:func:`interpolators.tcp.part_point`), else the machine position. What
    the program's X Y Z are measured from: a block's start, G92's current position. A tool length change not yet
    travelled (``st.length_pending``: ``G43.4 H2`` after ``G43 H1 Z5.``, or a new H in G43.4 mode, under Fanuc's
    TOS = 0) leaves the programmed point where it was: the tip is found with the length the axes carry, the point
    counted with the new one, and the next TCP block travels the change (:func:`tcp_block`; our reading, as a G43's
    change travels at the next move, :func:`interpolators.iso_offsets.length_travel`)."""
    if not st.tcp:
        return st.pos
    travelled = part_point(st.context.kinematics, st.extra, st.pos, st.tool_length - st.length_pending)
    return travelled + np.array([0.0, 0.0, st.length_pending])


def tcp_switch(entry: tuple[int, object], st: State, where: Where, notes: Notes) -> None:
    """A group 08 code (``entry``: its key and word): G43.4 / G234 start TCP (an error where the machine or the
    state cannot take it, see the module text), any other code ends it."""
    key, w = entry
    st.tcp = key if key in TCP_CODES else 0
    if not st.tcp:
        return
    name = TCP_CODES[key]
    kin = st.context.kinematics
    if kin is None:
        where.fail(f"{name} needs the machine's kinematics", column=w.column, text=w.text,
                   expected="a machine with [program.kinematics] (vcnc machines --show: the rotary axes that turn the "
                            "part)")
    if kin.kind != "table":
        where.fail(f"{name} on a head-tilting machine: not supported", column=w.column, text=w.text,
                   expected=_EXPECTED)
    if st.frame is not None or st.rotation:
        where.fail(f"{name} with a tilted plane (G68.2), rotation, scaling or mirror image: not supported",
                   column=w.column, text=w.text, expected="G69, G50, G50.1 before it")
    if st.comp_side is not None:
        where.fail(f"{name} under cutter compensation ({st.comp_code}): not supported", column=w.column,
                   text=w.text, expected="G40 before it")
    notes.add(f"{name}: lines of the tool tip on the turned part")


def _refuse(seen, gcodes, axis_words: list[str], st: State, where: Where) -> None:
    """An error for what TCP does not read here (the module text)."""
    mw = gcodes["motion"][1] if "motion" in gcodes else seen[axis_words[0]] if axis_words else None
    col, tok = (mw.column, mw.text) if mw is not None else (1, where.text)
    why = ("motion other than G00/G01 (arcs, cycles)" if st.motion not in (0, 10) else
           "cutter compensation (G41/G42)" if st.comp_side is not None or st.comp_start is not None
           or st.comp_close_at is not None else
           "rotation, scaling, mirror image or a tilted plane" if st.frame is not None or st.rotation else
           "polar coordinates" if st.fanuc_polar or "@" in seen or "^" in seen else
           "feed per revolution (G95)" if st.per_rev else
           "the corner words ,R ,C" if st.corner_word is not None or st.corner is not None else
           "a tool position offset (G45-G48)" if "position offset" in gcodes else None)
    if why is not None:
        where.fail(f"{why} under tool centre point control (G43.4 / G234): not supported", column=col, text=tok,
                   expected=_EXPECTED)
    vector = [k for k in ("I", "J", "K") if k in seen]
    rotary = [k for k in EXTRA_LETTERS if k in seen]
    bad = (rotary if st.tcp == 435 else vector) + (["R"] if "R" in seen else [])
    if bad:
        w = seen[bad[0]]
        where.fail(f"word {w.letter} under {TCP_CODES[st.tcp].split()[0]}: not allowed", column=w.column, text=w.text,
                   expected="G43.4 / G234 (type 1): X Y Z and the rotary words; G43.5 (type 2): X Y Z and the tool "
                            "direction I J K")
    if st.motion == 10 and st.inverse_time and not (st.block_f or 0.0) > 0:
        where.fail("G01 under tool centre point control in inverse time (G93) without an F > 0 on the block",
                   column=col, text=tok, expected="F<1/minutes> > 0 on every G01 block under G93")
    if st.motion == 10 and not st.inverse_time and st.feed is None and not initial_feed(st, where):
        where.fail("G01 under tool centre point control without a feed", column=col, text=tok,
                   expected="F<feed of the tool tip on the part>")


def _tool_direction(seen, st: State, where: Where) -> np.ndarray:
    """G43.5's I J K: the rotary positions that make the tool direction (from the tip towards the spindle, in the
    table-fixed programming coordinates) the spindle's axis, the solution nearest the present one within the
    limits (FANUC 30i A-79348E 1.1, type 2: "the tool direction seen from the coordinate system that is fixed on
    the table is specified by I, J, K"; Mazak's G43.5 I J K: "direction of tool axis (position vector from tip
    point to center of rotation of the tool)"). A component left out is 0 (FANUC Series 15i/150i-MODEL A
    connection manual B-63323EN-1/03, 10.4.10, type 2 format, note 3: "When any of I, J, and K is omitted, the
    omitted I, J, or K is assumed to be 0"). Our reading: the axes move linearly to it, as under type 1."""
    kin = st.context.kinematics
    try:
        rot = tool_vector_extra(kin, [seen[k].value if k in seen else 0.0 for k in ("I", "J", "K")], st.extra,
                                wrapped=st.context.wrapped_axes)
    except TiltError as exc:
        w = next(seen[k] for k in ("I", "J", "K") if k in seen)
        where.fail(f"G43.5 tool direction I J K: {exc.message}", column=w.column, text=w.text, expected=exc.expected)
    st.extra_used = True
    return rot


def tcp_block(seen, gcodes, axis_words: list[str], other_words: list[str], st: State, blocks: list[Block],
              used: set[int], where: Where, number: int | None) -> bool:
    """A block under TCP with axis words ``axis_words`` (X Y Z, polar) or ``other_words`` (A-W, I J K): the tip's
    straight line on the part to the programmed X Y Z, the rotary axes to their words or G43.5's tool direction,
    as chords (:func:`interpolators.tcp.tcp_chords`); True when it ran the block, False for a block without
    them (the reader's general path takes it: a motion code alone, a word without motion)."""
    if not axis_words and not [k for k in other_words if k not in "IJK" or st.tcp == 435]:
        return False
    _refuse(seen, gcodes, axis_words, st, where)
    kin = st.context.kinematics
    start = tip_point(st)
    # a length change not yet travelled travels in the block's first chord: the chords are found from the start with
    # the new length, the first leaving the axes where they are
    begin = machine_point(kin, st.extra, start, st.tool_length) if st.length_pending else st.pos
    st.length_pending = 0.0
    here, st.pos = st.pos, start  # the program's X Y Z are the tip's on the part: the end from its start there
    try:
        end = block_target(seen, axis_words, st, machine=False)
    finally:
        st.pos = here
    letters = [k for k in EXTRA_LETTERS if k in seen]
    rot = None
    if any(k in seen for k in ("I", "J", "K")):
        rot = _tool_direction(seen, st, where)
    if letters:
        rot = extra_target({k: seen[k].value for k in letters}, st.extra, st.extra_offset(),
                           incremental=st.incremental, scale=st.scale)
        rot = wrapped_target(rot, {k: seen[k] for k in letters}, st, where)
        st.extra_used = True
    if rot is not None:
        used.update(3 + i for i in range(6) if rot[i] != st.extra[i] or EXTRA_LETTERS[i] in letters)
    used.update("XYZ".index(a) for a in axis_words)
    turn = np.zeros(6) if rot is None else rot - st.extra
    rapid = st.motion == 0
    duration = (None if rapid else 60.0 / st.block_f if st.inverse_time else
                block_time(start, end, turn, feed=st.feed, rotary_feed=st.feed_rotary))
    try:
        chords = tcp_chords(kin, start=start, end=end, start_extra=st.extra, end_extra=st.extra + turn,
                            length=st.tool_length, tolerance=st.tolerance, duration=duration, position=begin,
                            feed=np.inf if rapid else 0.0 if st.inverse_time else st.feed)
    except ChordsError as exc:
        where.fail(f"G0{1 - rapid} under tool centre point control: {exc}", column=1, text=where.text,
                   expected="a smaller rotary move per block, or a larger tolerance (G64 P)")
    last = len(chords.feeds) - 1
    for k, (target, ends, feed) in enumerate(zip(chords.targets, chords.extras, chords.feeds, strict=True)):
        extra = {} if rot is None else {"extra_start": st.extra.copy(), "extra_target": ends.copy()}
        used.update(i for i in range(3) if target[i] != st.pos[i])
        blocks.append(Block(line=where.line, number=number, text=where.text, kind="rapid" if rapid else "line",
                            start=st.pos.copy(), target=target.copy(), feed=float(feed), segment=Line(st.pos, target),
                            exact_stop=st.exact_stop if k == last else False, tolerance=st.tolerance,
                            tcp=bool(np.any(ends != st.extra)), **extra))
        st.pos = target.copy()
        st.extra = ends.copy()
    return True
