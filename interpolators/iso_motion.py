"""The ISO reader's motion blocks (:mod:`interpolators.iso`): a block's end point (X Y Z, LinuxCNC's polar
``@ ^``, Fanuc G16), G0/G1/G2/G3 with their feed (G93/G94/G95, the dialect's initial feed, LinuxCNC's zero-feed
refusal), the A-W words that move with them, a Fanuc/Haas ,R/,C corner's start, G33/G33.1, G5/G5.1 splines, the
G5.2/G5.3 NURBS block, rapids of the reader's own moves and the G4 dwell. LinuxCNC G-code reference (G0-G5.3, G33,
G4, G93-G95), Fanuc 0i-MF operator's manual where the dialects differ (each function says its source)."""

from __future__ import annotations

import dataclasses
import math
import re
from typing import TYPE_CHECKING, NoReturn

import numpy as np

from interpolators._words import Where
from interpolators.iso_arc3d import ARC3D_CODES, arc3d_block
from interpolators.iso_arcs import arc_turns, off_plane, read_arc, rotated_arc_chords, rotation_plane_alarm
from interpolators.iso_axes import EXTRA_LETTERS, extra_target, wrapped_target
from interpolators.iso_codes import G_CODES, PLANE_CODES
from interpolators.iso_corners import finish_corner, start_corner
from interpolators.iso_decimal import decimal_literal
from interpolators.iso_dwo import refuse_rotary_under_dwo
from interpolators.iso_nurbs import chord_blocks, nurbs_chords
from interpolators.iso_polar import POLAR_LETTERS, polar_xy
from interpolators.iso_splines import bezier_chords
from interpolators.iso_words import Word, firmware_dwell_hint
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Arc, Line

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["block_target", "fanuc_polar", "check_polar", "motion_block", "move_feed", "initial_feed", "per_rev_missing",
           "per_rev_spindle",
           "nurbs_block", "rapid_move", "dwell_block", "long_dwell_note", "LONG_DWELL_P", "dwell_p_point_note",
           "dwell_p_seconds", "linuxcnc_modal_axis_words"]

#: an M98 subprogram call in a line (a word M98, not M980)
_M98 = re.compile(r"(?<![A-Z])M0*98(?![0-9.])", re.IGNORECASE)


def block_target(seen, axis_words, st: State, *, machine: bool) -> np.ndarray:
    """End point [mm, machine] of the block's X Y Z words (``machine``: G53, absolute machine)
    or its polar words ``@ ^`` with Z."""
    if (st.rotation or st.frame is not None) and not machine:  # G10 R, G68: the rotated system's coordinates
        # a tool length change not yet travelled (Fanuc TOS = 0) is a machine Z distance the tool has not moved:
        # the axes no word names keep their program values under the offset travelled (a "G43 H2 X5." under G18 G68
        # keeps the rotated Z of the tool, not of a tool 20 mm higher), and the change travels along the machine Z
        # as length_travel takes it up (an absolute Z word holds the new offset already)
        pending = np.array([0.0, 0.0, st.length_pending])
        prog = st.to_program(st.pos + pending)
        for letter in axis_words:
            if letter in POLAR_LETTERS:
                continue
            i = "XYZ".index(letter)
            prog[i] = prog[i] + seen[letter].value * st.scale if st.incremental else seen[letter].value * st.scale
        if "@" in seen or "^" in seen:  # LinuxCNC find_ends: polar in the (rotated) program coordinates
            prog[0], prog[1] = polar_xy(prog[0], prog[1], incremental=st.incremental,
                                        distance=seen["@"].value * st.scale if "@" in seen else None,
                                        angle_deg=seen["^"].value if "^" in seen else None)
        target = st.pos.copy()  # axes that no word moves stay exactly where they are
        full = st.to_machine(prog) - (0.0 if "Z" in axis_words and not st.incremental else pending)
        for i in _rotated_axes(st, {"XYZ".index(a) for a in axis_words if a not in POLAR_LETTERS}
                               | ({0, 1} if "@" in seen or "^" in seen else set())):
            target[i] = full[i]
        return target
    target = st.pos.copy()
    off = st.offset()
    for letter in axis_words:
        if letter in POLAR_LETTERS:
            continue
        i = "XYZ".index(letter)
        v = seen[letter].value * st.scale
        if machine:
            target[i] = v
        elif st.incremental:
            target[i] = st.pos[i] + v
        else:
            target[i] = v + off[i]
    if "@" in seen or "^" in seen:
        x, y = polar_xy(st.pos[0] - off[0], st.pos[1] - off[1], incremental=st.incremental,
                        distance=seen["@"].value * st.scale if "@" in seen else None,
                        angle_deg=seen["^"].value if "^" in seen else None)
        target[0], target[1] = x + off[0], y + off[1]
    return target


def _rotated_axes(st: State, named: set[int]) -> list[int]:
    """The machine axes a block's words ``named`` (axis indices) move in a rotated system: each named one, and the
    other axis of a plane of rotation one of them lies in (LinuxCNC G10 R turns X Y about Z; G68 turns the two axes
    of its plane, Z X under G18, Y Z under G19: a "G91 X2." there moves Z too)."""
    planes = [{0, 1}] if st.rotation else []
    if st.frame is not None and st.frame.rotation is not None:
        planes.append(set(PLANE_AXES[st.frame.rotation.plane]))
    moved = set(named)
    for plane in planes * 2:  # twice: G10 R and a G68 in G18/G19 chain X to Y and Z
        if moved & plane:
            moved |= plane
    return sorted(moved)


def fanuc_polar(seen: dict, gcodes, st: State, where: Where, notes: Notes) -> dict:
    """Fanuc G16 / G15 (``fanuc`` dialect): under G16 the X and Y words of a motion block are the radius
    and the angle [deg, counter-clockwise from +X] about the work (or G52 local) zero, read as
    LinuxCNC's ``@ ^`` under G90 (Fanuc Series 16/18-MC operator's manual, 9.2 "Polar coordinate
    command (G15, G16)": "G90 specifies the zero point of the work coordinate system as the origin of
    the polar coordinate system"; a radius left out is the current distance, an angle left out the
    current angle). G91 ("the current position as the origin") and the G18/G19 planes are refused,
    naming them; G10, G52, G92, G53, G68 and G51 blocks take X Y as coordinates."""
    code = gcodes.get("polar", (None,))[0]
    if code is not None:
        st.fanuc_polar = code == 160
        if st.fanuc_polar:
            notes.add("G16 polar coordinates (X radius, Y angle)")
    if not st.fanuc_polar or not ("X" in seen or "Y" in seen):
        return seen
    if any(g in gcodes for g in ("nonmodal", "rotation", "scaling", "mirror")):
        return seen
    w = seen["X"] if "X" in seen else seen["Y"]
    if st.plane != 2:
        where.fail("G16 polar coordinates outside the XY plane (G18/G19): not supported", column=w.column,
                   text=w.text, expected="G17 with G16")
    if st.incremental:
        where.fail("G16 polar coordinates under G91 (the current position as the pole): not supported",
                   column=w.column, text=w.text, expected="G90 with G16")
    renamed = {"X": "@", "Y": "^"}
    return {renamed.get(k, k): dataclasses.replace(v, letter=renamed[k]) if k in renamed else v
            for k, v in seen.items()}


def check_polar(seen, gcodes, st: State, where: Where, w: Word) -> None:
    """Polar words only on motion in the XY plane, without X or Y (LinuxCNC interp_internal.cc)."""
    if "nonmodal" in gcodes:
        where.fail("polar coordinates @ ^ can only be used for motion", column=w.column, text=w.text,
                   expected="@ and ^ on G0, G1, G2, G3 or a canned cycle")
    if st.plane != 2:
        where.fail("polar coordinates @ ^ are only in the XY plane (G17)", column=w.column, text=w.text,
                   expected="G17 before polar words")
    for letter in ("X", "Y"):
        if letter in seen:
            where.fail(f"polar coordinates @ ^ and {letter} in one block", column=seen[letter].column,
                       text=seen[letter].text, expected="either X/Y or @/^")


def motion_block(seen, gcodes, axis_words, arc_words, target, st: State, blocks, used, where: Where, number, *,
            machine: bool = False) -> None:
    motion = st.motion
    mw = gcodes["motion"][1] if "motion" in gcodes else seen[axis_words[0]] if axis_words else None
    mcol, mtok = (mw.column, mw.text) if mw is not None else (1, where.text)
    code = f"G{motion // 10:02d}"
    if motion in (330, 331):
        _synchronised(seen, target, st, blocks, used, where, number, mcol, mtok)
        return
    rot = _extra_words(seen, motion, st, where, used, machine=machine)
    if motion == 10 and "R" in seen and not arc_words and st.context.dialect.name in ("fanuc", "haas"):
        w = seen["R"]  # Fanuc T series "Chamfering and corner R" (lathe): G01 X.. R..; a mill writes ",R"
        where.fail("word R on G01: the lathe form of corner rounding ('G01 X.. R..'); a mill takes ',R'",
                   column=w.column, text=w.text, expected=f",{w.text.strip()} (Fanuc/Haas corner rounding)")
    if motion in (0, 10) and (arc_words or "R" in seen):
        # LinuxCNC interp_check.cc: "I word with no G2, G3, ... to use it"; grbl error 36 "unused value words";
        # the Haas mill manual lists X Y Z A B C for G00 and X Y Z A B C F ,R ,C for G01 (no I J K), and no
        # Fanuc manual found says a control ignores them: refused on every dialect (a typo for G02/G03?)
        # I, J and K together on a move: the tool-axis vector a 5-axis post writes with each point (Siemens
        # ORIVECT "A3= B3= C3=", Heidenhain "LN ... TX TY TZ"), which no ISO mill's G00/G01 reads
        w = seen[(arc_words or ["R"])[0]]
        guess = ("a 5-axis post's tool-axis vector I J K?" if {"I", "J", "K"} <= set(seen) and "R" not in seen
                 else "a G02/G03 meant?")
        if _M98.search(where.text):  # Fanuc/Haas: M98 P L calls without arguments; G65 P passes A-Z as #1-#26
            guess = "M98 passes no arguments to its subprogram: a call with arguments is G65 P<program> (macro B)"
        where.fail(f"word {w.letter} is only allowed on arcs (G02/G03), not on {code} (LinuxCNC and grbl refuse it; "
                   f"the Haas manual lists no I J K R for it; {guess})",
                   column=w.column, text=w.text, expected="X, Y, Z and F on G00/G01")
    if motion != 0 and st.inverse_time and st.block_f is None:
        where.fail(f"{code} in inverse time (G93) without an F word on the block", column=mcol, text=mtok,
                   expected="F<1/minutes> on every G1/G2/G3 block under G93")
    if motion != 0 and not st.inverse_time and st.feed is None and not initial_feed(st, where):
        _no_feed(st, where, code, mcol, mtok)
    if motion != 0 and st.per_rev:
        per_rev_spindle(st, where, code, mcol, mtok)
    for letter in axis_words:
        used.update((0, 1) if letter in POLAR_LETTERS else ("XYZ".index(letter),))
    common = dict(line=where.line, number=number, text=where.text, start=st.pos.copy(), target=target,
                  exact_stop=st.exact_stop, tolerance=st.tolerance)
    if rot is not None:
        common.update(extra_start=st.extra.copy(), extra_target=rot)
    if motion in (50, 51):
        used.update((0, 1))
        _spline(seen, target, st, blocks, where, common, mcol, mtok)
        return
    st.spline_pq = None
    if motion in ARC3D_CODES:
        used.update((0, 1, 2))
        arc3d_block(seen, axis_words, target, st, blocks, where, common, mcol, mtok, move_feed)
        return
    turn = np.zeros(6) if rot is None else rot - st.extra
    if motion in (0, 10):
        seg = Line(st.pos, target)
        blk = Block(kind="rapid" if motion == 0 else "line", feed=np.inf if motion == 0 else move_feed(st, seg, turn),
                    segment=seg, **common)
    else:
        if st.rotation and st.plane != 2 or off_plane(st):
            # a G18/G19 arc of a system rotated about Z lies in no axis plane (Fanuc: alarm 144)
            rotation_plane_alarm(st, where, mcol, mtok, f"{code} arc")
            if rot is not None:
                w = seen[next(k for k in EXTRA_LETTERS if k in seen)]
                where.fail(f"{code} arc with axis word {w.letter} in a rotated coordinate system (G10 L2 R): "
                           "not supported", column=w.column, text=w.text, expected="no A, B, C, U, V, W on this arc")
            used.update((0, 1, 2))
            rotated_arc_chords(seen, arc_words, target, st, blocks, where, common, code, mcol, mtok, move_feed)
            return
        seg = read_arc(seen, arc_words, target, st, where, code, mcol, mtok)
        if "P" in seen:
            seg = arc_turns(seg, seen["P"], st, where, code)
        if st.comp_start is not None and st.arc_center is not None:
            st.comp_centers[len(blocks)] = st.arc_center
        p, q = PLANE_AXES[st.plane]
        used.update((p, q))
        target = np.array(seg.end)
        common["target"] = target
        blk = Block(kind="arc", feed=move_feed(st, seg, turn), segment=seg, **common)
    blk = _corner(st, blocks, blk, motion, where)
    blocks.append(blk)
    st.pos = target
    if rot is not None:
        st.extra = rot


def _corner(st: State, blocks: list[Block], blk: Block, motion: int, where: Where) -> Block:
    """Fanuc/Haas ``,R`` / ``,C`` (:mod:`interpolators.iso_corners`): the corner a previous block asked
    for goes in before ``blk`` (trimmed and returned); a word on this block waits for the next move."""
    if st.corner is not None:
        n = len(blocks)
        blk = finish_corner(st.corner, blocks, blk, dialect=st.context.dialect.name, plane=st.plane, where=where)
        if n in st.comp_centers:  # the programmed centre of this arc: it now comes after the corner block
            st.comp_centers[n + 1] = st.comp_centers.pop(n)
        st.corner = None
    if st.corner_word is not None:
        w, st.corner_word = st.corner_word, None
        factor = st.frame.length_factor(st.plane) if st.frame is not None and not off_plane(st) else 1.0
        if factor is None:
            where.fail(f"{w.text!r} under G51 scaling with different factors in the plane: not supported",
                       column=w.column, text=w.text, expected="equal scaling factors in the plane")
        st.corner = start_corner(w, blk, index=len(blocks), dialect=st.context.dialect.name, motion=motion,
                                 plane=st.plane, size=w.value * st.scale * factor, inverse_time=st.inverse_time,
                                 where=where)
        st.corner_fresh = True
    return blk


def _synchronised(seen, target, st: State, blocks, used, where: Where, number, mcol: int, mtok: str) -> None:
    """G33 spindle-synchronised motion and G33.1 rigid tapping as feed moves.

    LinuxCNC g-code.adoc "G33 Spindle Synchronized Motion" and "G33.1 Rigid Tapping",
    interp_convert.cc ``convert_straight`` and interp_check.cc ``check_other_codes``: the axes move
    K [mm/rev, in/rev under G20] along the drive line per spindle revolution, so the path feed is
    K x S [rev/min] / 60 [mm/s]; G33.1 then goes back to its start, its spindle (and so its feed)
    sped up by I (I < 1 counts as 1), and ends where it began. Errors as LinuxCNC's: no K word, an F
    word, the spindle not turning (M3/M4); also S0 (no speed to follow). The overrun while the spindle
    reverses at the bottom is not modelled: the moves end at the programmed point and the start.
    """
    name = G_CODES[st.motion][1]
    if "K" not in seen:
        where.fail(f"{name} without a K word", column=mcol, text=mtok,
                   expected="K<distance per spindle revolution> > 0 [mm/rev]")
    k = seen["K"]
    if not k.value > 0:
        where.fail(f"{name}: K must be > 0", column=k.column, text=k.text, expected="K > 0 [mm/rev]")
    bad = [w for w in ("F", "J", "R", *EXTRA_LETTERS, *(("I",) if st.motion == 330 else ())) if w in seen]
    if bad:
        w = seen[bad[0]]
        why = " (the feed follows from K and the spindle speed)" if w.letter == "F" else ""
        where.fail(f"{name} with word {w.letter}{why}: not allowed", column=w.column, text=w.text,
                   expected="X, Y, Z, K" + (" and I" if st.motion == 331 else ""))
    if not st.spindle_turning:
        where.fail(f"{name} with the spindle not turning", column=mcol, text=mtok, expected="M3 or M4 before it")
    if not st.spindle_speed > 0:
        where.fail(f"{name} with spindle speed S0", column=mcol, text=mtok, expected="S > 0 [rev/min] before it")
    if st.comp_side is not None:
        where.fail(f"{name} under cutter compensation ({st.comp_code}): not supported", column=mcol, text=mtok,
                   expected="G40 before it")
    feed = k.value * st.scale * st.spindle_speed / 60.0
    start = st.pos.copy()
    used.update(i for i in range(3) if target[i] != start[i])
    common = dict(line=where.line, number=number, text=where.text, tolerance=st.tolerance)
    tap = st.motion == 331
    blocks.append(Block(kind="line", feed=feed, segment=Line(start, target), start=start, target=target.copy(),
                        exact_stop=st.exact_stop or tap, **common))
    if tap:
        back = feed * max(seen["I"].value, 1.0) if "I" in seen else feed
        blocks.append(Block(kind="line", feed=back, segment=Line(target, start), start=target.copy(),
                            target=start, exact_stop=True, **common))
    else:
        st.pos = target.copy()


def _extra_words(seen, motion: int, st: State, where: Where, used: set[int], *, machine: bool) -> np.ndarray | None:
    """End positions of the block's A B C U V W words [deg, mm] (:mod:`interpolators.iso_axes`), or
    None without such words; splines and cutter compensation do not take them."""
    letters = [w for w in EXTRA_LETTERS if w in seen]
    if not letters:
        return None
    w = seen[letters[0]]
    if motion in (50, 51):
        where.fail(f"G5 spline with axis word {w.letter}: not supported", column=w.column, text=w.text,
                   expected="X and Y on a spline")
    if st.comp_side is not None:
        where.fail(f"axis word {w.letter} under cutter compensation ({st.comp_code}): not supported",
                   column=w.column, text=w.text, expected="G40 before A, B, C, U, V, W motion")
    if st.dwo is not None:
        refuse_rotary_under_dwo(st, letters, seen, where)
    st.extra_used = True
    used.update(3 + EXTRA_LETTERS.index(letter) for letter in letters)
    target = extra_target({k: seen[k].value for k in letters}, st.extra, st.extra_offset(),
                          incremental=st.incremental, scale=st.scale, machine=machine)
    return wrapped_target(target, {k: seen[k] for k in letters}, st, where, machine=machine)


def initial_feed(st: State, where: Where) -> bool:
    """Take the machine's initial feed (:attr:`interpolators.context.Dialect.initial_feed`, Fanuc parameter
    No. 1411) for a feed move before any F word, and say whether there was one to take: not after an F0, under
    G95 feed per revolution, or after a G94 that ended G93 (each needs its own F, whatever the setting)."""
    initial = st.context.dialect.initial_feed
    if initial is None or st.feed_zero or st.per_rev or st.feed_reset or st.inverse_time:
        return False
    st.feed = st.feed_rotary = initial / 60.0
    if st.initial_feed_line is None:
        st.initial_feed_line = where.line
    return True


#: How each control refuses a feed move at F0 (the messages of :func:`_no_feed`'s sources).
_ZERO_FEED = {"linuxcnc": "LinuxCNC: cannot do G1 with zero feed rate",
              "grbl": "grbl error 22: feed rate has not yet been set or is undefined",
              "fanuc": "Fanuc alarm PS0011: feed zero"}


#: The same for a dialect without a documented message of its own (Haas, Fadal).
_ZERO_FEED_ANY = "refused by LinuxCNC, grbl (error 22) and Fanuc (alarm PS0011) alike"


def _no_feed(st: State, where: Where, code: str, mcol: int, mtok: str) -> None:
    """A feed move before any F: an error on every control (LinuxCNC "Cannot do G1 with zero feed
    rate"; grbl error 22 "Feed rate has not yet been set or is undefined"; Fanuc alarm PS0011 "feed
    zero"). A file that ends with M99 is a subprogram: the program that calls it sets the feed."""
    why = "no F word before it"
    if st.feed_zero:
        why = f"F0, a zero feed rate ({_ZERO_FEED.get(st.context.dialect.name, _ZERO_FEED_ANY)})"
    elif st.per_rev:
        per_rev_missing(st, where, code, mcol, mtok)
    elif st.uncalled_feed:
        why += f" ({st.uncalled_feed} is not executed: LinuxCNC runs an M98 block as a call only)"
    elif st.subprogram:
        why += " (this file ends with M99: a subprogram, whose feed comes from the program that calls it)"
    elif st.feed_reset:
        why = ("a G94/G95 word cleared the feed (G94 after G93 resets the feed on every control; on LinuxCNC each "
               "G94/G95 word does, interp_convert.cc convert_feed_mode); no F word since")
    vacant = re.search(r"F\s*#\s*(\d+)", re.sub(r"\([^)]*\)", "", where.text or ""), re.I)
    if vacant and not st.feed_zero:  # "F#650" with #650 unset: a vacant variable leaves its word out (iso_params)
        why = f"F#{vacant.group(1)} is vacant (never set), which leaves the F word out; no F word before it"
    where.fail(f"{code} feed move without a feed: {why}", column=mcol, text=mtok,
               expected="F > 0 [mm/min] (or a machine's initial feed: --initial-feed F, [program] initial_feed)")


def per_rev_missing(st: State, where: Where, code: str, mcol: int, mtok: str) -> NoReturn:
    """The error of a feed move (``code``: the move or cycle, for the message) under G95 without a feed: F (per
    revolution) x S (the spindle speed), saying which of the two is missing. LinuxCNC refuses S0 ("Cannot feed with
    zero spindle speed in feed per rev mode", rs274); elsewhere F x S0 is no feed at all."""
    unit = "in/rev" if st.scale != 1.0 else "mm/rev"
    if st.feed_per_rev is None:
        where.fail(f"{code} under G95 feed per revolution: no F word since G95", column=mcol, text=mtok,
                   expected=f"F<feed per revolution> > 0 [{unit}] after G95")
    dialect = st.context.dialect.name
    said = ('rs274: "Cannot feed with zero spindle speed in feed per rev mode"' if dialect == "linuxcnc" else
            f"F{st.feed_per_rev_word:g} per revolution x S0 is no feed")
    cleared = ", or the S of a rigid tap (M29), cleared at its end" if dialect == "fanuc" else ""
    where.fail(f"{code} under G95 feed per revolution without a spindle speed: S0 (no S word > 0 before it{cleared}; "
               f"{said})", column=mcol, text=mtok,
               expected="S<spindle speed> > 0 [rev/min] (and M3/M4) before a feed move under G95")


def per_rev_spindle(st: State, where: Where, code: str, mcol: int, mtok: str) -> None:
    """A feed move under G95 with the spindle stopped: it would wait for revolutions that never come
    (LinuxCNC synchronises it to the spindle's speed feedback), so it is refused."""
    if not st.spindle_turning:
        where.fail(f"{code} under G95 feed per revolution with the spindle stopped", column=mcol, text=mtok,
                   expected="M3 or M4 (and S > 0) before a feed move under G95")


def _spline(seen, target, st: State, blocks, where: Where, common: dict, mcol: int, mtok: str) -> None:
    """G5 / G5.1 (LinuxCNC G-code reference): a Bezier curve in XY as chord blocks
    (:mod:`interpolators.iso_splines`). I J (and G5's P Q) are always incremental, turned with the
    coordinate system under G10 R."""
    code = "G5" if st.motion == 50 else "G5.1"
    if st.plane != 2:
        where.fail(f"{code} spline: only in the XY plane (G17)", column=mcol, text=mtok, expected="G17")
    if "Z" in seen:
        w = seen["Z"]
        where.fail(f"{code} spline: only X and Y move", column=w.column, text=w.text, expected="X and Y words")
    s = st.scale
    p0 = st.pos.copy()
    if st.motion == 51:
        ij = np.array([seen["I"].value if "I" in seen else 0.0, seen["J"].value if "J" in seen else 0.0, 0.0])
        if not ij.any():
            where.fail("G5.1 spline: I and J both unspecified or zero", column=mcol, text=mtok,
                       expected="I and/or J: the control point's offset from the start")
        control = [p0, p0 + st.turned(ij * s), target]
    else:
        if "P" not in seen or "Q" not in seen:
            where.fail("G5 spline: P and Q must both be given", column=mcol, text=mtok,
                       expected="P and Q: the second control point's offset from the end point")
        if ("I" in seen) != ("J" in seen):
            where.fail("G5 spline: I and J must be given together", column=mcol, text=mtok, expected="I and J")
        if "I" in seen:
            ij = st.turned(np.array([seen["I"].value, seen["J"].value, 0.0]) * s)
        elif st.spline_pq is not None:
            ij = -st.spline_pq  # the tangent of the previous G5 continues
        else:
            where.fail("G5 spline: I and J are needed on the first G5 of a series", column=mcol, text=mtok,
                       expected="I and J")
        pq = st.turned(np.array([seen["P"].value, seen["Q"].value, 0.0]) * s)
        control = [p0, p0 + ij, target + pq, target]
        st.spline_pq = pq
    if st.motion == 51:
        st.spline_pq = None
    points = [p0, *bezier_chords(control)]
    segs = [Line(a, b) for a, b in zip(points[:-1], points[1:])]
    # under G93 the whole spline takes the block's 1/F minutes: one speed along all its chords
    speed = sum(g.length for g in segs) * st.block_f / 60.0 if st.inverse_time else None
    for seg in segs:
        blocks.append(Block(kind="line", feed=move_feed(st, seg) if speed is None else speed, segment=seg,
                            **{**common, "start": np.array(seg.start), "target": np.array(seg.end)}))
    st.pos = np.array(target, dtype=float)


def nurbs_block(seen, gcodes, st: State, blocks, used, where: Where, number, notes: Notes) -> None:
    """LinuxCNC G5.2 / G5.3 (:mod:`interpolators.iso_nurbs`; interp_convert.cc convert_nurbs, its errors): a G5.2
    block starts the control points at the current position (weight P when the block has no axis words, else 1),
    each block with the plane's two axis words adds one, weight P (> 0; the G5.2 block's own point without P: 1,
    g-code.adoc's default), L above 3 the order; G5.3 runs the curve to the last point, chords at the modal feed,
    on its line. The current position stays until G5.3 (incremental words count from it, as LinuxCNC's
    find_ends); after it no motion mode is set."""
    w = gcodes["motion"][1] if "motion" in gcodes else None
    mcol, mtok = (w.column, w.text) if w is not None else (1, where.text)
    p, q = PLANE_AXES[st.plane]
    letters = ["XYZ"[p], "XYZ"[q]]
    stray = next((a for a in (*EXTRA_LETTERS, *POLAR_LETTERS, "XYZ"[st.plane], *"IJKQR") if a in seen), None)
    why = (f"with word {stray}: not supported (control points take the {PLANE_CODES[st.plane]} plane's "
           f"{letters[0]} {letters[1]}, P and L)" if stray is not None else
           f"with cutter compensation on ({st.comp_code}): not supported" if st.comp_side is not None else
           "under G93 inverse time: not supported" if st.inverse_time else
           "cannot use G5.3 without G5.2 first" if st.motion == 53 and st.nurbs is None else
           f"you must specify both {letters[0]} and {letters[1]} coordinates for control points"
           if (letters[0] in seen) != (letters[1] in seen) else None)
    if why is not None:
        bad = seen.get(stray, w) if stray is not None else w
        where.fail(f"{'G5.3' if st.motion == 53 else 'G5.2'} NURBS {why}", column=bad.column if bad else mcol,
                   text=bad.text if bad else mtok, expected="G5.2 <P> <L>, lines X- Y- P-, then G5.3 (LinuxCNC)")
    if st.motion == 53:
        _nurbs_curve(st, blocks, used, where, number, mcol, mtok)
        notes.add("G5.2/G5.3 NURBS run as chords within 1 um of the curve")
        return
    moves = letters[0] in seen
    weight = seen["P"].value if "P" in seen else None
    if st.feed is None and not st.inverse_time and not initial_feed(st, where):
        _no_feed(st, where, "G5.2 NURBS", mcol, mtok)  # LinuxCNC: "Cannot make a NURBS with 0 feedrate"
    if st.nurbs is None:
        st.nurbs, st.nurbs_order = [(st.pos.copy(), weight if weight and weight > 0 and not moves else 1.0)], 3
        weight = 1.0 if weight is None and moves else weight
    elif not moves and weight is not None:
        where.fail(f"G5.2 NURBS: can specify P without {letters[0]} and {letters[1]} only for the first control "
                   "point", column=seen["P"].column, text=seen["P"].text, expected=f"{letters[0]}- {letters[1]}- P-")
    if moves and (weight is None or weight <= 0):
        bad = seen.get("P", seen[letters[0]])
        where.fail("G5.2 NURBS: must specify positive weight P for every control point", column=bad.column,
                   text=bad.text, expected=f"{letters[0]}- {letters[1]}- P<weight > 0>")
    if "L" in seen and seen["L"].value > 3:
        st.nurbs_order = int(seen["L"].value)
    if moves:
        st.nurbs.append((block_target(seen, letters, st, machine=False), float(weight)))


def _nurbs_curve(st: State, blocks, used, where: Where, number, mcol: int, mtok: str) -> None:
    """G5.3: the NURBS of the G5.2 control points, as feed chords on this line."""
    points, weights = np.array([c for c, _ in st.nurbs]), np.array([c for _, c in st.nurbs])
    if len(points) < st.nurbs_order:
        where.fail(f"G5.3 NURBS: you must specify a number of control points at least equal to the order "
                   f"L = {st.nurbs_order} (got {len(points)}, the start point included)", column=mcol, text=mtok,
                   expected=f"at least {st.nurbs_order} control points")
    used.update(PLANE_AXES[st.plane])
    chord_blocks(nurbs_chords(points, weights, st.nurbs_order), st, blocks, where, number, move_feed)
    st.nurbs, st.motion = None, None


def move_feed(st: State, seg: Line | Arc, turn: np.ndarray | None = None) -> float:
    """Path feed [mm/s] of a feed move: the modal feed, or under G93 the block's length over its
    time 1/F minutes (LinuxCNC G-code reference, G93; Haas mill manual, G93: "60 (seconds) divided by the F
    value"). Under ``fanuc`` a G93 arc's F is its feed over its radius (FANUC Series 16/18-MC operator's manual
    B-62764EN, "Inverse time feed (G93)": "FRN = feedrate / arc radius", "the feedrate is calculated not from the
    actual amount of movement in the block but from the arc radius"): the arc takes ``|sweep| / F`` minutes, its
    tangential feed in the plane R x F. A move with X, Y, Z still (``seg`` of length
    0, ``turn`` the motion of a, b, c, u, v, w [deg, mm]) runs along its U V W distance at the feed
    [mm/s], or with U, V, W still too along its rotary distance in deg/s (RS274/NGC 3,
    Sec. 2.1.2.5; :attr:`interpolators.program.Block.extra_length`). No floor: LinuxCNC 2.9.0 and later take
    ``rate = length * F`` however short the move (rs274ngc interp_inverse.cc, commit b244b375dd for issue #2410), where
    earlier versions, the Debian 12 rs274 among them, raised it to 0.1 units/min.

    Under G93 it keeps that rate in ``st.inverse_rate`` [program units/min, deg/min for a rotary move]: LinuxCNC's
    interpreter stores ``length * F`` as its feed rate (interp_inverse.cc ``inverse_time_rate_straight`` and
    ``_arc``: ``settings->feed_rate = rate``), the value ``#<_feed>`` reads (interp_namedparams.cc)."""
    if seg.length == 0 and turn is not None and np.any(turn != 0):
        linear = bool(np.any(turn[3:] != 0))
        length = float(np.linalg.norm(turn[3:] if linear else turn[:3]))
        if st.inverse_time:
            st.inverse_rate = (length / st.scale if linear else length) * st.block_f
            return length * st.block_f / 60.0
        return st.feed if linear else st.feed_rotary
    if not st.inverse_time:
        return st.feed * fanuc_feed_share(seg, turn, st.scale) if st.context.dialect.fanuc_feed else st.feed
    st.inverse_rate = seg.length / st.scale * st.block_f
    if type(seg) is Arc and st.context.dialect.name == "fanuc":
        return seg.length * st.block_f / (60.0 * abs(seg.sweep))
    return seg.length * st.block_f / 60.0  # 0 on a zero-length block (no motion)


def fanuc_feed_share(seg: Line | Arc, turn: np.ndarray | None, scale: float) -> float:
    """The speed along ``seg``'s X Y Z path per unit of F on a Fanuc (:attr:`interpolators.context.Dialect.fanuc_feed`):
    a helix's length over its arc's in the plane (F is the feed along that arc, parameter HTG = 0); a line's length
    over the length of its move in every axis, ``turn`` the motion of a, b, c [deg], u, v, w [mm], the degrees
    counted as lengths in the program's unit (``scale`` mm per unit); 1 otherwise."""
    if type(seg) is Arc:
        planar = seg.radius * abs(seg.sweep)
        return seg.length / planar if seg.helix != 0 and planar > 0 else 1.0
    if turn is None or seg.length == 0 or not np.any(turn != 0):
        return 1.0
    path = seg.length / scale
    others = np.concatenate([turn[:3], turn[3:] / scale])
    return path / math.sqrt(path * path + float(others @ others))


#: A whole-number G04 P of this many seconds or more, under a dialect that reads P in seconds, gets a note [s]:
#: such dwells are rare in LinuxCNC and grbl programs and common as milliseconds in Fanuc and Haas posts.
LONG_DWELL_P = 60.0


def long_dwell_note(seconds: float, st: State, notes: Notes | None) -> None:
    """Note a dwell P of :data:`LONG_DWELL_P` whole seconds or more read in seconds (G04 P, a cycle's P): a Fanuc/Haas
    post's ``G04 P500`` (500 ms: Fanuc 0i / Haas mill manuals, P in ms without a decimal point) dwells 500 s where P
    is seconds (LinuxCNC g-code.adoc G4, grbl), and the note shows where such a cycle time comes from."""
    if notes is not None and st.context.dialect.dwell_p_unit == "s" and seconds >= LONG_DWELL_P \
            and float(seconds).is_integer():
        notes.add(f"dwell P of {LONG_DWELL_P:g} or more read as seconds, as {st.context.dialect.name} does (a "
                  "Fanuc/Haas post's P is milliseconds: --dialect fanuc or haas)")


def dwell_p_seconds(word: Word, st: State) -> bool:
    """True when a dwell P (G04's, a canned cycle's) is read in seconds: under a dialect whose P is seconds, and
    under Haas a P written with a decimal point (Haas mill operator's manual, G04 Dwell: "G04 P10. is a dwell of
    10 seconds", "G04 P10 is a dwell of 10 milliseconds"; our reading: a cycle's P as G04's, the manual's cycle
    examples write it in seconds with a decimal point)."""
    dialect = st.context.dialect
    return dialect.dwell_p_unit == "s" or (dialect.name == "haas" and decimal_literal(word))


def dwell_p_point_note(word: Word, st: State, notes: Notes | None) -> None:
    """Note a dwell P written with a decimal point (``G04 P2.0``) read in milliseconds: the Fanuc 0i manual writes
    P in ms without a decimal point (``G04 P500``, see :func:`long_dwell_note`), and the decimal point is the mark
    of a post written for a control whose P is seconds (LinuxCNC g-code.adoc G4 "G4 P0.5"; grbl; Haas, see
    :func:`dwell_p_seconds`; our reading of the Centroid CNC12 posts of the wild set 17, ``G4 P3.00 ; pause for
    dwell``), where the dwell is a thousand times longer. The reading stays the dialect's; the note shows where a
    short cycle time may come from."""
    if notes is not None and not dwell_p_seconds(word, st) and decimal_literal(word) and word.value > 0:
        notes.add(f"dwell P with a decimal point read in milliseconds, as {st.context.dialect.name} reads P "
                  "(where P is seconds, as on LinuxCNC and grbl: --dialect linuxcnc, it dwells 1000 times longer)")


def linuxcnc_modal_axis_words(seen, st: State) -> bool:
    """True when the block's axis words move by the modal motion although a group 0 code is in it: under
    ``linuxcnc``, whose group 0 codes other than G10, G28, G30, G52 and G92 do not use axis words (rs274ngc
    interp_check.cc ``enhance_block``: ``mode_zero_covets_axes``; "if there is an axis value in the block and no
    g-code to use it ... set motion_to_be to be the last motion saved"). So ``G28.1 Z3`` (SheetCAM's Mach3
    floating-head posts) stores the position, then moves to Z3 by G0/G1, as do G30.1, G92.1-G92.3 and a dwell
    ``G4 P..`` (LinuxCNC order of execution: the dwell and the group 0 code before the motion). grbl does the same
    (gnea/grbl ``gcode.c``: only G10, G28, G30 and G92 set ``AXIS_COMMAND_NON_MODAL``; for G28.1, G30.1 and G92.1
    "If axis words are passed here, they are interpreted as an implicit motion mode")."""
    return st.context.dialect.name in ("linuxcnc", "grbl") and any(a in seen for a in ("X", "Y", "Z", *EXTRA_LETTERS))


def dwell_block(gcodes, seen, st: State, blocks, where: Where, number, notes: Notes) -> bool:
    key, gw = gcodes["dwell"]
    if "motion" in gcodes and "P" not in seen:
        w = gcodes["motion"][1]
        where.fail("G04 with a motion code needs its time as P", column=w.column, text=w.text,
                   expected="G04 P<time> G01 X..")
    moves = "motion" in gcodes or ("P" in seen and linuxcnc_modal_axis_words(seen, st))
    axis = ("Y", "Z", *EXTRA_LETTERS) if moves else ()
    bad = [w for w in ("Y", "Z", "I", "J", "K", "R", *EXTRA_LETTERS) if w in seen and w not in axis]
    if "motion" in gcodes:
        bad = []
    if bad:
        w = seen[bad[0]]
        where.fail(f"word {bad[0]} not allowed in a dwell block", column=w.column, text=w.text,
                   expected="G04 P<time> or G04 X<s>")
    unit = st.context.dialect.dwell_p_unit
    if moves:  # X belongs to the motion; the dwell time is P
        seen = {k: v for k, v in seen.items() if k != "X"}
    if ("P" in seen) == ("X" in seen):
        where.fail(f"G04 needs exactly one of P or X{firmware_dwell_hint(seen)}", column=gw.column, text=gw.text,
                   expected=f"G04 P<{unit}> or G04 X<s>")
    w = seen["P"] if "P" in seen else seen["X"]
    seconds = w.value / 1000.0 if ("P" in seen and not dwell_p_seconds(w, st)) else w.value
    if "X" in seen and st.context.dialect.name == "linuxcnc":  # g-code.adoc "G4 Dwell": "G4 P-"; rs274 refuses X
        notes.add("G04 X<s> dwell read as Fanuc does (LinuxCNC refuses it: \"Dwell time missing with g4\")")
    if seconds < 0:
        where.fail("dwell time must be >= 0", column=w.column, text=w.text, expected="a dwell time >= 0")
    if "P" in seen:
        long_dwell_note(seconds, st, notes)
        dwell_p_point_note(w, st, notes)
    blocks.append(Block(line=where.line, number=number, text=where.text, kind="dwell", start=st.pos.copy(),
                        target=st.pos.copy(), feed=0.0, dwell=seconds, exact_stop=True, tolerance=st.tolerance))
    return False


def rapid_move(target, st: State, blocks, used, where: Where, number, axis_words, *, rot=None) -> None:
    """A rapid to ``target`` [mm, machine] and, when ``rot`` is given, the extra axes to ``rot`` [deg, mm]."""
    for a in axis_words:
        used.add("XYZ".index(a))
    extra = {} if rot is None else {"extra_start": st.extra.copy(), "extra_target": np.array(rot, dtype=float)}
    blocks.append(Block(line=where.line, number=number, text=where.text, kind="rapid", start=st.pos.copy(),
                        target=target.copy(), feed=np.inf, segment=Line(st.pos, target), exact_stop=st.exact_stop,
                        tolerance=st.tolerance, **extra))
    st.pos = target.copy()
    if rot is not None:
        st.extra = np.array(rot, dtype=float)
