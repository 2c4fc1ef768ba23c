"""The ISO reader's cutter radius compensation (:mod:`interpolators.iso`): G40/G41/G42 and G41.1/G42.1 with their
D word (LinuxCNC G-code reference, G41/G42 and G41.1/G42.1), Fanuc/Haas G39 corner arcs (Fanuc Series 16/18-MC
operator's manual, 'Corner offset circular interpolation (G39)'), a run's end compensated by
:func:`interpolators.compensation.compensate` (LinuxCNC's or Fanuc's corners by the dialect), the position a
compensated run makes the reader re-read, and LinuxCNC's refusal of M6 under compensation."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.compensation import CompensationError, compensate
from interpolators.iso_words import Word
from interpolators.program import Block

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["cutter_compensation", "rereads_position", "g39", "finish_compensation", "tool_change_under_compensation"]


def tool_change_under_compensation(mcodes, st: State, where: Where) -> None:
    """LinuxCNC refuses a tool change (M6) while G41/G42 is on (interp_convert.cc ``convert_tool_change``:
    "Cannot change tools with cutter radius compensation on")."""
    if st.comp_side is None or st.context.dialect.name != "linuxcnc":
        return
    for m, w in mcodes:
        if m == 6:
            where.fail(f"M6 tool change with cutter radius compensation on ({st.comp_code}): LinuxCNC refuses it "
                       "('Cannot change tools with cutter radius compensation on')", column=w.column, text=w.text,
                       expected="G40 before the tool change")


def cutter_compensation(entry, seen, st: State, blocks: list[Block], where: Where, notes: Notes) -> None:
    """G40/G41/G42 (LinuxCNC "G41, G42 Cutter Compensation"): the run of blocks from the entry move to
    the exit move after G40 is offset by :func:`interpolators.compensation.compensate`."""
    key, w = entry
    if key == 400:
        if st.comp_start is not None:
            st.comp_close_at = len(blocks)
        st.comp_side = None
        return
    if st.comp_start is not None:
        where.fail(f"{w.text.upper()}: cutter radius compensation is already on", column=w.column, text=w.text,
                   expected="G40 before switching compensation")
    dynamic = key in (411, 421)
    if "D" in seen and not dynamic:
        _whole_offset_number(w.text.upper(), seen["D"], where)
        st.comp_number = int(seen["D"].value)
    if "D" in seen and dynamic:
        radius = seen["D"].value * st.scale / 2.0
    else:
        tool = st.tool(int(seen["D"].value)) if "D" in seen else (
            st.tool(st.tool_offsets.get(st.tool_current, st.tool_current)) if st.tool_current is not None else None)
        radius = 0.0 if tool is None else tool.radius
    st.comp_side = "left" if key in (410, 411) else "right"
    if radius < 0.0:  # LinuxCNC convert_cutter_compensation_on: a negative radius switches the side
        radius = -radius
        st.comp_side = "right" if st.comp_side == "left" else "left"
    if st.frame is not None and st.frame.flips(st.plane):  # Fanuc: under a mirror image G41 offsets as G42
        st.comp_side = "right" if st.comp_side == "left" else "left"
    st.comp_code = w.text.upper()
    if radius == 0.0:
        notes.add("G41/G42 with tool radius 0 (path unchanged)")
        return
    st.comp_radius = radius
    st.comp_run_side, st.comp_plane = st.comp_side, st.plane
    st.comp_start = len(blocks)
    notes.add("G41/G42 cutter radius compensation")


def _whole_offset_number(code: str, d: Word, where: Where) -> None:
    """G41/G42 D names a tool (LinuxCNC) or an offset register (Fanuc, Haas): a whole number. LinuxCNC's
    ``convert_cutter_compensation_on`` (interp_convert.cc) refuses another ("G41 requires D word to be a whole
    number"); Fanuc refuses a decimal point after D (alarm PS0007 "illegal use of decimal point"); Haas, our
    reading, takes D as the register number only. A post that writes the cutter's radius there (Newfangled
    Solutions' Mach3 wizards: "M6 T7 (TOOL DIA. 3)" then "G41 D1.5") named no register. A negative D is refused
    alike (rs274: "G41 D-1" gets the same message)."""
    if d.value != int(d.value) or d.value < 0:
        where.fail(f"{code} D{d.value:g}: the offset number D must be a whole number >= 0 (LinuxCNC: \"G41 requires D "
                   "word to be a whole number\"; Fanuc: decimal point not allowed after D)", column=d.column,
                   text=d.text, expected=f"{code} D<n>, n a tool or offset number (the tool table gives the radius)")


def rereads_position(words: list[Word], st: State) -> bool:
    """Whether LinuxCNC takes the current position from the motion queue after this block: M6 and M61 set
    ``toolchange_flag`` (interp_convert.cc ``convert_tool_change``, ``convert_m``), and the next read
    (rs274ngc_pre.cc ``read_inputs``) calls ``refresh_actual_position``. After a G40 with no exit move yet,
    the queue ends at the last compensated point (``convert_cutter_compensation_off`` only flushes it), so
    that point becomes the current position and the compensated run ends there (rs274 2.9.0~pre1: a
    Z-only move after ``G40`` and ``T2 M6`` stays at the compensated X Y)."""
    return st.context.dialect.name == "linuxcnc" and any(w.letter == "M" and w.value in (6.0, 61.0) for w in words)


def g39(w: Word, seen, st: State, count: int, where: Where, notes: Notes) -> None:
    """Fanuc/Haas G39 corner circular interpolation (Fanuc Series 16/18-MC operator's manual, "Corner offset
    circular interpolation (G39)"; Fanuc 0i-MF, cutter compensation C): in offset mode, an arc of the tool
    radius about the corner from the vector perpendicular to the block before to the new vector, which
    without I J K (or X Y) is perpendicular to the next block at its start: LinuxCNC's corner arc at that
    one corner (:func:`interpolators.compensation.compensate`, ``rounded``); the arc carries the next block's
    line, as every corner arc does (our reading: the G39 block has no motion of its own to carry). A new
    vector given by X Y or I J K is not read."""
    if st.comp_side is None or st.comp_start is None or count == st.comp_start:
        where.fail("G39 corner circular interpolation outside offset mode", column=w.column, text=w.text,
                   expected="G39 under G41/G42 after the start-up move")
    for letter in ("X", "Y", "Z", "I", "J", "K", "R"):
        if letter in seen:
            v = seen[letter]
            where.fail(f"word {letter} on G39: a corner vector given by X Y or I J K is not supported",
                       column=v.column, text=v.text,
                       expected="G39 alone (the arc ends perpendicular to the next block)")
    st.comp_rounded.add(count)
    notes.add("G39 corner circular interpolation")


def finish_compensation(st: State, blocks: list[Block], source: str | None) -> None:
    """Replace the finished compensated run by the tool-centre path. Under ``--dialect fanuc`` and ``haas`` the
    start-up is Fanuc's type A (the default, parameter 5003#0 SUP = 0; Fanuc 0i-MF operator's manual, cutter
    compensation C, "Tool movement in start-up"): the start-up block ends at the offset vector perpendicular
    to the next block at its start point, whatever its length; Haas's Setting 43 "Cutter Comp Type" offers
    the same A (our reading: A, its default, as Fanuc's). LinuxCNC's entry ends perpendicular to the entry
    move itself and must be longer than the radius, which CAM programs for wear-only offsets (a start-up of
    0.005 mm and a D of a few hundredths) never are. Their outside corners are Fanuc's too (intersections, at
    an acute corner two vectors: :mod:`interpolators.compensation`), not LinuxCNC's arcs."""
    closed = st.comp_close_at is not None and len(blocks) > st.comp_close_at  # a motion came after G40
    start, st.comp_start, st.comp_close_at = st.comp_start, None, None
    centers, st.comp_centers = {i - start: c for i, c in st.comp_centers.items()}, {}
    rounded, st.comp_rounded = {i - start for i in st.comp_rounded}, set()
    run = blocks[start:]
    if not run:
        return
    fanuc = st.context.dialect.name in ("fanuc", "haas")
    try:
        new = compensate(run, side=st.comp_run_side, radius=st.comp_radius, plane=st.comp_plane, closed=closed,
                         centers=centers, inch=st.inch, open_end=not closed,
                         entry="perpendicular" if fanuc else "linuxcnc", corner="fanuc" if fanuc else "linuxcnc",
                         rounded=rounded)
    except CompensationError as exc:
        b = run[min(exc.index, len(run) - 1)]
        Where(source, b.line, b.text).fail(
            f"{st.comp_code} cutter radius compensation: {exc.message}", column=1, text=b.text,
            expected=f"a contour a tool of radius {st.comp_radius:g} mm can follow")
    blocks[start:] = new
    st.pos = np.array(new[-1].target, dtype=float)
