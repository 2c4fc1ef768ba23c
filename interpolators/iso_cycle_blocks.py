"""The ISO reader's canned-cycle blocks (:mod:`interpolators.iso`): a block in a cycle's modal state run as the
holes' rapid, feed and dwell blocks that :func:`interpolators.iso_cycles.cycle_moves` computes (the feed, tapping
spindle and G68/G51 frame checks before it; LinuxCNC G-code reference 'G80-G89', Fanuc 0i-MF for the mill
dialects), Fagor's G81 Z I drilling form under ``--dialect fanuc``, a G5.2 NURBS point in that modal group, and the
Haas G70-G72 bolt-hole patterns and G12/G13 circular pocket (:mod:`interpolators.iso_haas`)."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.arcs import arc_from_center
from interpolators.iso_arcs import off_plane
from interpolators.iso_codes import DIALECT_G, G_CODES, G_UNSUPPORTED, PLANE_CODES
from interpolators.iso_cycles import cycle_moves, tap_spindle_error
from interpolators.iso_frames import framed_initial
from interpolators.iso_haas import PATTERN_CODES, bolt_holes, circular_pocket
from interpolators.iso_motion import (
    dwell_p_point_note,
    dwell_p_seconds,
    initial_feed,
    long_dwell_note,
    nurbs_block,
    per_rev_missing,
    per_rev_spindle,
    rapid_move,
)
from interpolators.iso_offsets import length_in_cycle
from interpolators.iso_rigid_tap import rigid_tap_peck, rigid_tap_speed
from interpolators.iso_words import Word, WordError, fail_words
from interpolators.program import Block
from toolpaths.geometry import Line

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["cycle_block", "pattern_or_pocket"]


def _cycle_plane_refused(st: State, name: str, where: Where, mw: Word) -> None:
    """A canned cycle in a plane other than the G68 rotation's, under ``fanuc``: refused. Fanuc says the plane is not
    to change under a rotation (Series 15i/150i-MA operator's manual B-63324EN/03 and 16i-LA B-63194EN/02,
    "Coordinate system rotation": "The G code for selecting a plane (G17, G18, or G19) can be specified before the
    block containing the G code for coordinate system rotation (G68). G17, G18 or G19 must not be designated in the
    mode of coordinate system rotation"), so what a hole drilled along an axis the rotation turns would do is not
    given (the arcs and cutter compensation of another plane are its alarm 144, :func:`rotation_plane_alarm`). The
    plane code itself is taken, as for the arcs; Haas (no Haas text found) and LinuxCNC's G10 R drill along the turned
    axis."""
    planes = {2: "G17", 1: "G18", 0: "G19"}
    where.fail(f"{name} in {planes[st.plane]} while G68 rotates the {planes[st.frame.rotation.plane]} plane: Fanuc "
               "does not define it (FANUC 15i-MA B-63324EN/03 'Coordinate system rotation': G17, G18 or G19 must not "
               "be designated in the mode of coordinate system rotation)", column=mw.column, text=mw.text,
               expected=f"{planes[st.frame.rotation.plane]} for canned cycles under this G68, or G69 first")


def cycle_block(seen, gcodes, st: State, blocks, used, where: Where, number, notes: Notes, moves: bool,
                 rot_words: list[str]) -> None:
    """A block in a canned cycle's modal state: a hole where it has X/Y/Z (or polar) words; rotary words refused.
    Under G5.2/G5.3 a NURBS control point or the curve."""
    if st.motion in (52, 53):
        nurbs_block(seen, gcodes, st, blocks, used, where, number, notes)
        return
    if rot_words:
        w = seen[rot_words[0]]
        where.fail(f"{G_CODES[st.motion][1]} with axis word {w.letter}: not supported", column=w.column,
                   text=w.text, expected="X, Y, Z, R, Q, P, L words on a canned cycle")
    if "K" in seen and st.context.dialect.name == "linuxcnc" and st.motion not in (760, 870):
        # interp_check.cc check_other_codes: "K word with no G2, G3, G33, G33.1, G76, or G87 to use it"; the
        # repeat count is L (g-code.adoc "G80-G89"), K Fanuc's
        w = seen["K"]
        where.fail(f"word K on the {G_CODES[st.motion][1]}: LinuxCNC repeats a cycle with L and reads no K (K is "
                   "Fanuc's repeat count)", column=w.column, text=w.text, expected="L<repeats>")
    if moves:
        _canned_cycle(seen, gcodes, st, blocks, used, where, number, notes)


def pattern_or_pocket(gcodes, seen, st: State, blocks: list[Block], used: set[int], where: Where,
                       number: int | None, notes: Notes) -> None:
    """A block of the Haas bolt-hole patterns (G70-G72) or the G12/G13 circular pocket: its moves, noted."""
    if "pattern" in gcodes:
        _bolt_holes(gcodes["pattern"], seen, st, blocks, used, where, number)
        notes.add(PATTERN_CODES[gcodes["pattern"][0]])
    else:
        _pocket(gcodes["pocket"], seen, st, blocks, used, where, number)
        notes.add("G12/G13 circular pocket milling")


def _bolt_holes(entry, seen, st: State, blocks, used, where: Where, number) -> None:
    """Haas G70/G71/G72 (:mod:`interpolators.iso_haas`): the active canned cycle at every hole."""
    key, w = entry
    name = PATTERN_CODES[key]
    lathe = [k for k in ("P", "Q", "U", "W", "D", "R") if k in seen]
    if lathe:  # "G70 P10 Q20": a Haas lathe program's finishing cycle, not the mill's bolt-hole pattern
        where.fail(f"{G_UNSUPPORTED[key]}: not supported (word {lathe[0]}: the lathe form; the mill's {name} "
                   "takes I J K L)", column=w.column, text=w.text, expected="milling G codes (see vcnc's ISO reader)")
    if st.motion is None or st.motion < 730 or st.rotation:
        where.fail(f"{name} without an active canned cycle" if not st.rotation else
                   f"{name} in a coordinate system rotated by G10 R: not supported", column=w.column, text=w.text,
                   expected="a drilling cycle (e.g. G81 ... L0) before it")
    here = st.to_program(st.pos)
    for i, a in enumerate("XY"):
        if a in seen:
            here[i] = here[i] + seen[a].value * st.scale if st.incremental else seen[a].value * st.scale
    try:
        holes = bolt_holes(key, {k: v.value for k, v in seen.items()}, centre=(here[0], here[1]), scale=st.scale)
    except WordError as exc:
        fail_words(where, name, exc, seen, w)
    for x, y in holes:
        cur = st.to_program(st.pos)
        xy = (x - cur[0], y - cur[1]) if st.incremental else (x, y)
        words = {a: Word(letter=a, value=v / st.scale, column=w.column, text=w.text) for a, v in zip("XY", xy)}
        _canned_cycle(words, {}, st, blocks, used, where, number)


def _pocket(entry, seen, st: State, blocks, used, where: Where, number) -> None:
    """Haas G12/G13 (:mod:`interpolators.iso_haas`): the pocket's feed moves from its centre."""
    key, w = entry
    name = DIALECT_G["haas"][key][1]
    no_feed = st.feed is None and not initial_feed(st, where)
    bad = ("no feed rate" if no_feed else "in inverse time (G93)" if st.inverse_time else
           "with cutter compensation on (it implies its own)" if st.comp_side is not None else
           "only in the XY plane (G17)" if st.plane != 2 else
           "under scaling with different X and Y factors" if st.frame is not None
           and st.frame.length_factor(2) is None else None)
    if bad is not None:
        where.fail(f"{name}: {bad}", column=w.column, text=w.text, expected="G17 G94 G40 and an F word")
    tool = st.tool(int(seen["D"].value)) if "D" in seen else None
    here = st.to_program(st.pos)
    xy = [a for a in ("X", "Y") if a in seen]
    if xy:  # to the centre first
        for a in xy:
            i = "XY".index(a)
            here[i] = here[i] + seen[a].value * st.scale if st.incremental else seen[a].value * st.scale
        rapid_move(st.to_machine(here), st, blocks, used, where, number, xy)
    try:
        moves = circular_pocket(key == 130, {k: v.value for k, v in seen.items()}, centre=tuple(here),
                                scale=st.scale, incremental=st.incremental,
                                tool_radius=0.0 if tool is None else tool.radius)
    except WordError as exc:
        fail_words(where, name, exc, seen, w)
    flip = st.frame is not None and st.frame.flips(2)
    used.update((0, 1, 2))
    for mv in moves:
        target = st.to_machine(np.array(mv.end))
        common = dict(line=where.line, number=number, text=where.text, start=st.pos.copy(), target=target,
                      exact_stop=st.exact_stop, tolerance=st.tolerance, feed=st.feed)
        if mv.centre is None:
            blocks.append(Block(kind="line", segment=Line(st.pos, target), **common))
        else:
            centre = st.to_machine(np.array([*mv.centre, mv.end[2]]))
            arc = arc_from_center(st.pos, target, centre, ccw=mv.ccw != flip, plane=2)
            blocks.append(Block(kind="arc", segment=arc, **common))
        st.pos = target


def _fagor_drilling(seen, st: State, where: Where, notes: Notes) -> dict:
    """A G81 series whose first block has I and no R under ``--dialect fanuc``: the Fagor 8055 form
    (programming manual 9.7 "G81. Drilling canned cycle": "G81 G98/G99 X Y Z I K" -- "Z Reference plane ...
    I Drilling depth ... K Dwell, in hundredths of a second"), which Fanuc's G81 (R plane, Z bottom, K
    repeats) cannot mean (no I). Each block of the series is read as Fanuc's ``R<Z> Z<I>``: both keep their
    absolute and incremental references (Fagor: Z "referred to the initial plane", I "referred to the
    reference plane"; Fanuc G91: R from the initial level, Z from R); a later block's Z alone is a new
    reference plane, drilled to the same depth."""
    st.cycle.fagor = True
    w = seen.get("I") or seen.get("Z") or next(iter(seen.values()))
    if st.plane != 2 or seen.get("K") is not None and seen["K"].value != 0:
        what = "a dwell K" if st.plane == 2 else "a plane other than G17"
        where.fail(f"G81 Z I (Fagor drilling form) with {what}: not supported", column=w.column, text=w.text,
                   expected="G17 and G81 Z<reference plane> I<depth> without K")
    notes.add("G81 Z I read as Fagor's drilling cycle (Z the reference plane, I the depth)")
    out = {k: v for k, v in seen.items() if k not in "ZIK"}
    if "Z" in seen:
        out["R"] = Word("R", seen["Z"].value, seen["Z"].column, seen["Z"].text)
    if "I" in seen:
        out["Z"] = Word("Z", seen["I"].value, seen["I"].column, seen["I"].text)
    return out


def cycle_turns_spindle(st: State) -> bool:
    """Whether the tapping cycle in force turns the spindle itself, so that it feeds per revolution (G95) with
    no M3/M4 before it: Haas's G84/G74 always (Haas mill operator's manual, "G84 Tapping Canned Cycle": "It is
    not necessary to start the spindle CW before this canned cycle. The control does this automatically"; our
    reading is the same for G74's CCW), Fanuc's after M29 S.. (rigid tapping,
    :mod:`interpolators.iso_rigid_tap`). Other cycles under G95 need the spindle turning,
    :func:`interpolators.iso_motion.per_rev_spindle`."""
    if st.motion not in (740, 840):
        return False
    dialect = st.context.dialect.name
    return dialect == "haas" or dialect == "fanuc" and st.rigid_tap


def _canned_cycle(seen, gcodes, st: State, blocks, used, where: Where, number, notes: Notes | None = None) -> None:
    """One canned-cycle block: its holes as ordinary rapid, feed and dwell blocks."""
    if st.motion == 810 and st.context.dialect.name == "fanuc" and notes is not None and (
            st.cycle.fagor or st.cycle.r is None and "I" in seen and "R" not in seen):
        seen = _fagor_drilling(seen, st, where, notes)
    name = G_CODES[st.motion][1]
    if notes is not None and st.cycle.r is None and "R" not in seen and st.context.dialect.name in ("fanuc", "haas"):
        notes.add(f"{name} without R in the first block of the series: the R plane is the initial level "
                  "(Fanuc/Haas reading; LinuxCNC refuses it)")
    if notes is not None and st.motion in (740, 840) and st.plane != 2 and st.context.dialect.name == "linuxcnc":
        # interp_cycles.cc convert_cycle_g74_g84 passes the plane's coordinates to cycle_feed in another order
        # for YZ and XZ than every other cycle (LinuxCNC 2.9 and master)
        notes.add(f"{name} in {PLANE_CODES[st.plane]}: tapped along the plane's drilling axis at the hole, as "
                  "g-code.adoc describes (LinuxCNC's interpreter feeds to the hole's coordinates in another order)")
    mw = gcodes["motion"][1] if "motion" in gcodes else next(iter(seen.values()))
    if st.inverse_time:
        where.fail(f"{name} in inverse time (G93): not supported", column=mw.column, text=mw.text,
                   expected="G94 before a canned cycle")
    if st.context.dialect.name == "fanuc" and off_plane(st):
        _cycle_plane_refused(st, name, where, mw)
    peck_tap = None
    if st.context.dialect.name == "fanuc":
        rigid_tap_speed(st, name, where, mw.column, mw.text)
        peck_tap = rigid_tap_peck(st, seen.get("Q"), name, where, notes)
    elif st.context.dialect.name == "haas" and st.motion in (740, 840) and "Q" in seen and notes is not None:
        notes.add(f"{name} with Q under haas: the Q is not used, the tap runs in one stroke to Z (no Haas text on a "
                  "peck tap was found; under fanuc a Q after M29 is the machine's peck rigid tapping)")
    if st.feed is None and st.motion != 0 and st.per_rev:
        per_rev_missing(st, where, name, mw.column, mw.text)
    if st.feed is None and st.motion != 0 and not initial_feed(st, where):
        where.fail(f"{name}: no feed rate", column=mw.column, text=mw.text, expected="F > 0 [mm/min]")
    if st.per_rev and st.motion != 0 and not cycle_turns_spindle(st):
        per_rev_spindle(st, where, name, mw.column, mw.text)
    tap = tap_spindle_error(st.motion // 10, st.spindle_turning, st.spindle_ccw)
    if tap is not None and st.context.dialect.name == "linuxcnc":  # LinuxCNC check_g74_g84_spindle
        where.fail(f"{name} {tap[0]}", column=mw.column, text=mw.text, expected=tap[1])
    # under G68 or G10 R the cycle runs in the rotated program coordinates, its moves mapped to the machine's
    # (LinuxCNC: interp_cycles.cc works in program coordinates, emccanon.cc rotate_and_offset_pos turns each move)
    turned = st.frame is not None or bool(st.rotation)
    pos, off = (st.to_program(st.pos), np.zeros(3)) if turned else (st.pos, st.offset())
    factors = (1.0, 1.0, 1.0) if st.frame is None else st.frame.factors
    if st.cycle.initial is not None and st.cycle.factors != factors:  # where is the initial level now?
        where.fail(f"{name}: the G51 scaling changed within the series of cycles (the initial level of a "
                   "series is then undefined)", column=mw.column, text=mw.text, expected="G80 before G51 / G50")
    st.cycle.factors = factors
    length_in_cycle(st)
    framed_initial(st, to_program=True)
    try:
        code = 87 if st.motion == 770 else st.motion // 10  # Haas G77 is Fanuc's G87
        values = {k: v.value for k, v in seen.items()}
        if "P" in seen and st.context.dialect.dwell_p_unit == "ms" and dwell_p_seconds(seen["P"], st):
            values["P"] *= 1000.0  # Haas's P0.5 is seconds: kept as the series' P in the dialect's milliseconds
        moves = cycle_moves(code, values, cycle=st.cycle, pos=pos,
                            offset=off, scale=st.scale, incremental=st.incremental, retract_r=st.retract_r,
                            feed=st.feed, dwell_p_ms=st.context.dialect.dwell_p_unit == "ms",
                            tap_out_to_r=st.context.dialect.tap_out_to_r, plane=st.plane,
                            haas=st.context.dialect.name == "haas" or st.fadal and code in (73, 83),
                            fanuc_rules=st.context.dialect.name in ("fanuc", "haas"), peck_tap=peck_tap,
                            tap_dwell_at_r=st.context.dialect.name == "fanuc")
    except WordError as exc:
        fail_words(where, name, exc, seen, mw)
    framed_initial(st, to_program=False)
    if turned:
        moves = [dataclasses.replace(mv, target=st.to_machine(mv.target)) for mv in moves]
    for mv in moves:
        used.update(i for i in range(3) if mv.target[i] != st.pos[i])
        common = dict(line=where.line, number=number, text=where.text, start=st.pos.copy(),
                      target=mv.target.copy(), exact_stop=True, tolerance=st.tolerance)
        if mv.kind == "dwell":
            long_dwell_note(mv.dwell, st, notes)
            if "P" in seen:
                dwell_p_point_note(seen["P"], st, notes)
            blocks.append(Block(kind="dwell", feed=0.0, dwell=mv.dwell, **common))
        else:
            blocks.append(Block(kind=mv.kind, feed=mv.feed, segment=Line(st.pos, mv.target), **common))
            st.pos = mv.target.copy()
