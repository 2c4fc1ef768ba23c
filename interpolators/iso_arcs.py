"""The ISO reader's arcs (:mod:`interpolators.iso`): G2/G3 from I J K or R (LinuxCNC G-code reference, G2/G3;
LinuxCNC's and the dialects' end point tolerances in :mod:`interpolators.arcs`), full turns by P, grbl's arc end
check, the hint when I J K read in the other arc-centre mode would fit, and an arc in a plane a Fanuc/Haas G68 turned
out of the axis planes, run as chords."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.arcs import (
    ArcWordError,
    arc_from_center,
    arc_from_radius,
    center_arc_tolerance,
    radius_arc_tolerance,
)
from interpolators.iso_splines import SPLINE_TOLERANCE
from interpolators.iso_words import Word
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Arc, Line

if TYPE_CHECKING:
    from collections.abc import Callable

    from interpolators.iso import State

__all__ = ["off_plane", "arc_turns", "read_arc", "rotated_arc_chords", "rotation_plane_alarm"]


def off_plane(st: State) -> bool:
    """True when a G68 rotation turns the arc plane out of the axis planes (a rotation in another plane)."""
    return st.frame is not None and st.frame.rotation is not None and st.frame.rotation.plane != st.plane


def rotation_plane_alarm(st: State, where: Where, column: int, text: str, what: str) -> None:
    """``what`` (an arc, cutter compensation) in a plane other than the G68 rotation's (:func:`off_plane`) is Fanuc's
    alarm 144 "ILLEGAL PLANE SELECTED: The coordinate rotation plane and arc or cutter compensation C plane must be
    the same" (FANUC Series 0i-MODEL A connection manual (function) B-63503EN-1/01, 11 "Coordinate system rotation",
    http://cncmanuals.com/fanuc/49/series-0i-model-a-connection-manual-function/page/618): refused under ``fanuc``.
    A plane code in G68 mode is taken, only the arc or compensation in the other plane is refused; Haas (no Haas text
    found) and LinuxCNC's G10 R run such an arc as chords (:func:`rotated_arc_chords`)."""
    if st.context.dialect.name != "fanuc" or not off_plane(st):
        return
    planes = {2: "G17", 1: "G18", 0: "G19"}
    where.fail(f"{what} in {planes[st.plane]} while G68 rotates the {planes[st.frame.rotation.plane]} plane: Fanuc "
               "refuses it (alarm 144 illegal plane selected: the coordinate rotation plane and arc or cutter "
               "compensation C plane must be the same)", column=column, text=text,
               expected=f"{planes[st.frame.rotation.plane]} for arcs and G41/G42 under this G68, or G69 first")


def rotated_arc_chords(seen, arc_words, target, st: State, blocks, where: Where, common: dict, code: str,
                        mcol: int, mtok: str, feed_of: Callable[[State, Arc], float]) -> None:
    """A G18/G19 arc in a coordinate system rotated about Z (G10 R): built in program coordinates,
    where it is an ordinary arc, and run as chords within :data:`SPLINE_TOLERANCE` of it, mapped to
    machine coordinates (LinuxCNC rotates the arc's points the same way, emccanon.cc); LinuxCNC's P turns
    (:func:`arc_turns`) too. Each chord runs at the arc's feed ``feed_of(st, arc)``
    (:func:`interpolators.iso_motion.move_feed`, whose G93 rules, Fanuc's by the arc's radius among them, hold
    for the arc whatever frame it lies in)."""
    start_p, end_p = st.to_program(st.pos), st.to_program(target)
    shadow = dataclasses.replace(st, pos=start_p, rotations={}, frame=None, offsets={st.wcs: np.zeros(3)},
                                 g92=np.zeros(3), tool_length=0.0, tool_xy=np.zeros(2))
    arc = read_arc(seen, arc_words, end_p, shadow, where, code, mcol, mtok)
    if "P" in seen and st.context.dialect.name == "linuxcnc":
        arc = arc_turns(arc, seen["P"], st, where, code)
    step = 2.0 * math.acos(max(-1.0, 1.0 - SPLINE_TOLERANCE / arc.radius))
    n = max(1, math.ceil(abs(arc.sweep) / step))
    speed = feed_of(st, arc)  # the arc's feed on each chord
    start = st.pos.copy()
    for k in range(1, n + 1):
        point = target.copy() if k == n else st.to_machine(arc.point_at(arc.length * k / n))
        blocks.append(Block(kind="line", feed=speed, segment=Line(start, point),
                            **{**common, "start": start.copy(), "target": point.copy()}))
        start = point
    st.pos = np.array(target, dtype=float)


def arc_turns(arc: Arc, p: Word, st: State, where: Where, code: str) -> Arc:
    """LinuxCNC ``G2``/``G3`` ``P``: the number of turns (g-code.adoc "G2, G3 Arc Move": "For each P
    increment above 1 an extra full circle is added to the programmed arc"; interp_check.cc: "P value
    not an integer with M19 G2 or G3", "P value should be 1 or greater with G2 or G3"). Refused under
    cutter compensation, whose offset paths are built for one turn."""
    turns = round(p.value)
    if abs(turns - p.value) > 0.001 or turns < 1:
        where.fail(f"{code} P (number of turns) must be a whole number >= 1", column=p.column, text=p.text,
                   expected=f"{code} ... P1, P2, ...")
    if turns == 1:
        return arc
    if st.comp_start is not None:
        where.fail(f"{code} P{turns} (several turns) under cutter compensation: not supported", column=p.column,
                   text=p.text, expected="G40 before a multi-turn arc")
    return Arc(arc.start, arc.end, arc.center, ccw=arc.ccw, plane=arc.plane, turns=turns - 1)


def _grbl_arc_end(seen, st: State, where: Where, code: str, mcol: int, mtok: str) -> None:
    """grbl refuses an arc without an end-point word in its plane, the full circle of ``G2 I5`` that LinuxCNC
    and Fanuc run (gnea/grbl ``grbl/gcode.c``, the arc checks: "[No axis words]" STATUS_GCODE_NO_AXIS_WORDS,
    error 26; "[No axis words in plane]" STATUS_GCODE_NO_AXIS_WORDS_IN_PLANE, error 32)."""
    axes = ["XYZ"[i] for i in PLANE_AXES[st.plane]]
    if not any(a in seen for a in axes):
        plane_g = {2: "G17", 1: "G18", 0: "G19"}[st.plane]
        where.fail(f"{code} arc without an end point in its plane: grbl refuses it (error 26/32, no axis words "
                   "in plane; a full circle needs its end point written)", column=mcol, text=mtok,
                   expected=f"{axes[0]} and/or {axes[1]} with {code} in {plane_g}")


def _lathe_hint(st: State, seen, arc_words) -> str:
    """Why an arc has K in G17: I and K without J or Y, a ZX arc as a lathe program writes it without a plane
    word, a lathe working in G18 from the start (LinuxCNC "Lathe User Information", default plane: "A normal
    lathe only uses the XZ plane (G18)", set by RS274NGC_STARTUP_CODE = G18); "" otherwise."""
    if st.plane == 2 and "K" in arc_words and "J" not in arc_words and "Y" not in seen:
        return (" (I and K without J: a ZX arc as a lathe program writes it, a lathe starting in G18; a mill "
                "program selects G18 before it)")
    return ""


def read_arc(seen, arc_words, target, st: State, where: Where, code: str, mcol: int, mtok: str):
    if st.context.dialect.arc_rule == "grbl":
        _grbl_arc_end(seen, st, where, code, mcol, mtok)
    p, q = PLANE_AXES[st.plane]
    ccw = st.motion == 30
    has_r = "R" in seen
    factor = 1.0
    if st.frame is not None and not off_plane(st):  # G51.1 / G51 (Fanuc: mirror reverses G02 and G03)
        ccw = ccw != st.frame.flips(st.plane)
        factor = st.frame.length_factor(st.plane)
        if factor is None:
            where.fail(f"{code} arc under G51 scaling with different factors on its two axes (an ellipse): "
                       "not supported", column=mcol, text=mtok, expected="equal scaling factors in the arc's plane")
    allowed = {"IJK"[p], "IJK"[q]}
    plane_g = {2: "G17", 1: "G18", 0: "G19"}[st.plane]
    for letter in arc_words:
        w = seen[letter]
        if letter not in allowed and w.value != 0.0:
            where.fail(f"word {letter} is outside the arc plane ({plane_g}){_lathe_hint(st, seen, arc_words)}",
                       column=w.column, text=w.text,
                       expected=f"centre words {'IJK'[p]} and {'IJK'[q]} in {plane_g} (others only as 0)")
    in_plane = [w for w in arc_words if w in allowed]
    rule = st.context.dialect.arc_rule
    if in_plane and has_r:
        w = seen["R"]
        where.fail("arc with both I/J/K and R", column=w.column, text=w.text, expected="either I/J/K or R")
    st.arc_center = None
    try:
        if has_r:
            return arc_from_radius(st.pos, target, seen["R"].value * st.scale * factor, ccw=ccw, plane=st.plane,
                                   tolerance=radius_arc_tolerance(rule))
        if in_plane and (st.rotation or st.frame is not None):  # the centre words are in the rotated system
            prog = st.to_program(st.pos)
            for letter in in_plane:
                i = "IJK".index(letter)
                prog[i] = prog[i] + seen[letter].value * st.scale if st.arc_incremental else \
                    seen[letter].value * st.scale
            center = st.to_machine(prog)
            st.arc_center = center
            return arc_from_center(st.pos, target, center, ccw=ccw, plane=st.plane,
                                   tolerance=center_arc_tolerance(st.pos, target, center, plane=st.plane,
                                                                  inch=st.inch, rule=rule))
        if in_plane:
            center = _centre(st, seen, in_plane, incremental=st.arc_incremental)
            st.arc_center = center
            try:
                return arc_from_center(st.pos, target, center, ccw=ccw, plane=st.plane,
                                       tolerance=center_arc_tolerance(st.pos, target, center, plane=st.plane,
                                                                      inch=st.inch, rule=rule))
            except ArcWordError as exc:
                hint = _other_centre_mode(st, seen, in_plane, target) or _fadal_reversed_centre(st, seen, in_plane,
                                                                                                target)
                raise ArcWordError(exc.message + hint, exc.expected) from None
        where.fail(f"{code} arc needs a centre (I/J/K) or a radius (R)", column=mcol, text=mtok, expected="I/J/K or R")
    except ArcWordError as exc:
        w = seen["R"] if has_r else (seen[in_plane[0]] if in_plane else None)
        col, tok = (w.column, w.text) if w is not None else (mcol, mtok)
        where.fail(exc.message, column=col, text=tok, expected=exc.expected)
    raise AssertionError("unreachable")


def _centre(st: State, seen, in_plane: list[str], *, incremental: bool) -> np.ndarray:
    """An arc's centre [mm, machine] from its I/J/K: offsets from the start (G91.1) or program coordinates
    (G90.1)."""
    center = st.pos.copy()
    off = st.offset()
    for letter in in_plane:
        i = "IJK".index(letter)
        center[i] = (st.pos[i] if incremental else off[i]) + seen[letter].value * st.scale
    return center


def _fadal_reversed_centre(st: State, seen, in_plane: list[str], target: np.ndarray) -> str:
    """A hint for a Fadal arc whose end is off its circle: whether I/J/K read as the start minus the centre put both
    ends on one circle. Siemens NX's Post Builder template for Fadal (``pblib/controller/mill/fadal.def``,
    ``circular_move_1``: ``I[$mom_prev_pos(0) - $mom_pos_arc_center(0)]``) writes them so; Autodesk's Fusion Fadal
    post (fadal.cps ``onCircular``: ``iOutput.format(cx - start.x)``, Format 1 and Format 2 alike) and Fanuc write
    the centre minus the start, which vcnc reads (:mod:`interpolators.iso_fadal`: no Fadal manual text on it was
    found). "" when the reversed centre does not fit either, or off Fadal."""
    if not st.fadal or not st.arc_incremental:
        return ""
    center = st.pos.copy()
    for letter in in_plane:
        i = "IJK".index(letter)
        center[i] = st.pos[i] - seen[letter].value * st.scale
    if not _centre_fits(st, target, center):
        return ""
    return ("; I/J/K as the start minus the centre would fit (NX Post Builder's fadal.def writes them so): vcnc reads "
            "Fadal's I/J/K as the centre minus the start, as Fanuc's and Fusion's fadal.cps")


def _centre_fits(st: State, target: np.ndarray, center: np.ndarray) -> bool:
    """Whether an arc from the current point to ``target`` about ``center`` has both ends on one circle within the
    dialect's arc tolerance (for the hints of an arc refused as written)."""
    try:
        arc_from_center(st.pos, target, center, ccw=True, plane=st.plane,
                        tolerance=center_arc_tolerance(st.pos, target, center, plane=st.plane, inch=st.inch,
                                                       rule=st.context.dialect.arc_rule))
    except ArcWordError:
        return False
    return True


def _other_centre_mode(st: State, seen, in_plane: list[str], target: np.ndarray) -> str:
    """A hint for an arc whose end is off its circle: whether its I/J/K read in the other arc-centre mode put
    both ends on one circle, as in programs for a control that reads arc centres as absolute coordinates
    (LinuxCNC g-code.adoc "G90.1, G91.1": "G90.1 - absolute distance mode for I, J & K offsets"; G91.1, the
    power-on mode, incremental; Fanuc reads I J K incremental always; grbl has no G90.1), or the other way round.
    "" if not, for a centre on the start (no circle to be off) and for absolute centres missing a plane word
    (G90.1 needs both: "I and J both must be specified")."""
    plane = list(PLANE_AXES[st.plane])
    here = _centre(st, seen, in_plane, incremental=st.arc_incremental)
    if np.allclose(here[plane], st.pos[plane]) or (st.arc_incremental and len(in_plane) < 2):
        return ""
    center = _centre(st, seen, in_plane, incremental=not st.arc_incremental)
    if not _centre_fits(st, target, center):
        return ""
    if st.arc_incremental and st.context.dialect.name == "grbl":  # interpolators.iso_grbl: no G90.1 there
        return "; I/J/K as absolute centre coordinates would fit: a program for a control with LinuxCNC's G90.1, " \
               "which grbl lacks"
    if st.arc_incremental:
        return "; I/J/K as absolute centre coordinates (LinuxCNC G90.1) would fit"
    return "; I/J/K as offsets from the start (G91.1) would fit"
