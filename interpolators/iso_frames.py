"""The ISO reader's frame blocks (:mod:`interpolators.iso`), Fanuc/Haas only: G68 coordinate rotation, G51 scaling
and G51.1/G50.1 (Haas G101/G100) mirror image, whose frames :mod:`interpolators.iso_transforms` computes, G68.2 and
G53.1 (the tilted working plane, :mod:`interpolators.iso_tilt`), the moves a rotated system supports and a canned
cycle's initial level under a frame."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.iso_arcs import rotation_plane_alarm
from interpolators.iso_axes import EXTRA_LETTERS, reference_turns, wrapped_reference
from interpolators.iso_codes import DIALECT_G, G_CODES, MILL_G
from interpolators.iso_cycles import CYCLE_AXES, UNSCALED_Q_CYCLES
from interpolators.iso_tilt import PLANE_WORDS, TiltedRotation, TiltError, g68_2_rotation
from interpolators.iso_transforms import Frame, g68_rotation, mirror, scaling
from interpolators.iso_words import Word, WordError, fail_words
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Line

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["check_rotated", "g68", "g68_2_g53_1", "set_frame", "scaling_mirror", "framed_initial"]


def check_rotated(st: State, polar: list[str], where: Where, words: list[Word]) -> None:
    """Moves a rotated coordinate system (G10 R, G68) supports: G0-G3 (arcs out of the plane of rotation
    as chords); canned cycles (run in program coordinates, :func:`framed_initial`), under G51 scaling those
    without a peck or shift Q (iso_cycles.UNSCALED_Q_CYCLES: Q is not scaled); under G10 R alone the G5 /
    G5.1 splines (LinuxCNC builds them in program coordinates and turns the arcs it makes of them, emccanon.cc
    ``NURBS_FEED``) and G33 / G33.1, straight moves to a rotated point (emccanon.cc ``STRAIGHT_FEED``,
    ``RIGID_TAP``: ``rotate_and_offset_pos``) and polar ``@ ^`` (interp_find.cc ``find_ends``: in program
    coordinates)."""
    cycle_ok = st.motion is not None and st.motion >= 730 and (st.frame is None or not (
        st.frame.scaled and st.motion // 10 in UNSCALED_Q_CYCLES
        or any(st.frame.mirror) and st.motion in (760, 870, 770))) or (
        st.frame is None and st.motion in (50, 51, 330, 331))
    polar_ok = st.frame is None and st.motion in (0, 10, 20, 30)
    _drilling_axis_mirrored(st, where, words)
    if st.comp_start is not None:
        rotation_plane_alarm(st, where, words[0].column, words[0].text, "cutter compensation (G41/G42)")
    what = ("polar coordinates @ ^" if polar and not polar_ok else G_CODES[st.motion][1] if st.motion is not None
            and st.motion >= 50 and st.motion not in (800,) and not cycle_ok else None)
    if what is not None:
        w = words[0]
        how = f"G10 R {st.rotation:g}" if st.rotation else "G51 scaling" if st.frame.scaled else \
            "G51.1 mirror image" if st.frame.rotation is None else f"G68 R {st.frame.rotation.angle:g}"
        where.fail(f"{what} in a rotated coordinate system ({how}): not supported",
                   column=w.column, text=w.text, expected="G0-G3, or G10 L2 R0 / G69")


def _drilling_axis_mirrored(st: State, where: Where, words: list[Word]) -> None:
    """A canned cycle whose drilling axis a frame turns over (``G51.1 Z0`` in G17, a negative G51 K, or P, factor, a
    G101 Z) is refused: its R and bottom would be mirrored, the hole drilled from R away from the part. Our reading:
    the Fanuc 0i / 16i manuals' "Programmable mirror image" and "Scaling" name no such case (their canned-cycle notes
    are on Q, d and the G76/G87 shift), and Haas's G101 names none; LinuxCNC has no mirror."""
    if st.frame is None or st.motion is None or st.motion < 730 or st.motion == 800:
        return
    axis = CYCLE_AXES[st.plane][2]
    if st.frame.mirror[axis] == (st.frame.factors[axis] < 0):
        return
    letter = "XYZ"[axis]
    w = next((g for g in words if g.letter == "G" and round(g.value * 10) == st.motion), words[0])
    where.fail(f"{G_CODES[st.motion][1]} with its drilling axis {letter} mirrored (G51.1 {letter} or a negative G51 "
               "scale on it): not supported (the hole would be drilled from R away from the part)", column=w.column,
               text=w.text, expected=f"the mirror or scaling on the plane's axes only, or G50.1 {letter}0 / G50 before "
                                     "the cycle")


def g68(seen, st: State, where: Where, w: Word, notes: Notes) -> None:
    """G68: rotate the following blocks' coordinates (:mod:`interpolators.iso_transforms`); the block's
    own words are the centre and the angle, nothing moves."""
    other = [k for k in seen if k not in ("X", "Y", "Z", "R", "N", "F", "S", "T", "H", "D")]
    if other or st.comp_side is not None:
        bad = seen[other[0]] if other else w
        where.fail("G68 coordinate rotation: only the centre (axis words of the plane) and R, without cutter "
                   "compensation", column=bad.column, text=bad.text, expected="G68 X.. Y.. R<angle> with G40")
    axes = [a for a in ("X", "Y", "Z") if a in seen and "XYZ".index(a) not in PLANE_AXES[st.plane]]
    if axes:
        bad = seen[axes[0]]
        where.fail(f"G68 coordinate rotation: {bad.letter} is not an axis of the plane of rotation",
                   column=bad.column, text=bad.text, expected="the centre's two axes of the active plane and R")
    base = st.frame or Frame()
    st.frame = dataclasses.replace(base, rotation=None)
    rotation = g68_rotation({k: v.value for k, v in seen.items()}, plane=st.plane, current=st.to_program(st.pos),
                            scale=st.scale)
    set_frame(st, dataclasses.replace(base, rotation=rotation))
    notes.add("G68 coordinate rotation")


def g68_2_g53_1(gcodes, seen, st: State, blocks: list[Block], used: set[int], where: Where, number,
                 notes: Notes) -> None:
    """G68.2 [P0] X Y Z I J K (Euler angles) or G68.2 P1 Q X Y Z I J K (roll, pitch, yaw): the tilted working
    plane on the machine's tilting table; G53.1: the rotary axes turned to it at rapid, the linear axes staying
    (:mod:`interpolators.iso_tilt`)."""
    if "tilted plane" in gcodes:
        w = gcodes["tilted plane"][1]
        taken = PLANE_WORDS.get(seen["P"].value if "P" in seen else 0)  # None: a P form refused by name below
        other = [k for k in seen if k not in taken + "N"] if taken else []
        if other or st.comp_side is not None or st.frame is not None or st.rotation:
            bad = seen[other[0]] if other else w
            where.fail("G68.2 tilted working plane: only X Y Z (its zero), I J K (its angles), P and with P1 Q, "
                       "without cutter compensation, G68/G51/G51.1 or a G10 R rotation", column=bad.column,
                       text=bad.text, expected="G68.2 X.. Y.. Z.. I.. J.. K.. with G40 and G69")
        zero = st.offset() - np.array([st.tool_xy[0], st.tool_xy[1], st.tool_length])
        try:
            kin = st.context.kinematics
            rot = g68_2_rotation({k: v.value for k, v in seen.items()}, context=st.context, work_zero=zero,
                                 extra=st.extra, scale=st.scale, turns=reference_turns(st, kin.names if kin else ()))
        except TiltError as exc:
            bad = seen.get(exc.letter, w)
            where.fail(exc.message, column=bad.column, text=bad.text, expected=exc.expected)
        set_frame(st, Frame(rotation=rot))
        notes.add("G68.2 tilted working plane")
    if "tool axis" in gcodes:
        w = gcodes["tool axis"][1]
        rot = st.frame.rotation if st.frame is not None else None
        if not isinstance(rot, TiltedRotation):
            where.fail("G53.1 without a G68.2 tilted working plane", column=w.column, text=w.text,
                       expected="G68.2 X.. Y.. Z.. I.. J.. K.. (or P1 Q..) before G53.1")
        _g53_1_side(seen, rot, where, notes)
        turned = st.extra.copy()
        for name, angle in rot.positions.items():
            turned[EXTRA_LETTERS.index(name.upper())] = angle
            used.add(3 + EXTRA_LETTERS.index(name.upper()))
        # an axis that wraps at 360 deg reaches the angle as a machine word, by the machine's rule (a roll-over C at
        # 370 turned to 90: +80 deg, not -280)
        turned = wrapped_reference(turned, st, tuple(rot.positions))
        blocks.append(Block(kind="rapid", feed=np.inf, segment=Line(st.pos, st.pos), line=where.line, number=number,
                            text=where.text, start=st.pos.copy(), target=st.pos.copy(), exact_stop=st.exact_stop,
                            tolerance=st.tolerance, extra_start=st.extra.copy(), extra_target=turned))
        st.extra, st.extra_used = turned, True


def _g53_1_side(seen, rot: TiltedRotation, where: Where, notes: Notes) -> None:
    """``G53.1 P1`` / ``P2``: the solution with a positive / negative first (tilting) rotary axis, as Fusion's
    mazak.cps (Autodesk, 2023; OpenPostProject/mazak) writes them after ``G68.2`` for a Mazak ("P1" when the first
    rotary axis' angle is positive, "P2" when negative, no P at 0: our reading of the post, no Mazak manual at hand).
    vcnc chooses the solution at G68.2 by FANUC's rule (:func:`interpolators.iso_tilt.g68_2_rotation`): a P that
    agrees is noted, one that asks for the other solution is refused, not read silently as the other."""
    if "P" not in seen:
        return
    p = seen["P"]
    sign = {1.0: 1, 2.0: -1}.get(p.value)
    if sign is None:
        where.fail(f"G53.1 {p.text}: P1 or P2 (the side of the first rotary axis, as Mazak's G53.1 takes it)",
                   column=p.column, text=p.text, expected="G53.1, G53.1 P1 or G53.1 P2")
    name, angle = next(iter(rot.positions.items()))
    side = "positive" if sign > 0 else "negative"
    if angle * sign < -1e-6:
        taken = " ".join(f"{n.upper()}{a:+g}" for n, a in rot.positions.items())
        where.fail(f"G53.1 {p.text}: the solution with a {side} {name.upper()} (Mazak's choice, as Fusion's "
                   f"mazak.cps writes it); vcnc took {taken} at the G68.2 (FANUC's rule of the rotary solution): "
                   "not supported", column=p.column, text=p.text,
                   expected=f"G53.1 without P, or a G68.2 plane whose FANUC solution has a {side} {name.upper()}")
    notes.add(f"G53.1 {p.text}: the solution with a {side} {name.upper()} (Mazak), as FANUC's rule took it")


def set_frame(st: State, frame: Frame) -> None:
    st.frame = None if frame.identity else frame


def scaling_mirror(gcodes, seen, st: State, where: Where, notes: Notes) -> None:
    """G51 scaling, G51.1 / G50.1 mirror image (:mod:`interpolators.iso_transforms`): the block's axis
    words are the centre / mirror lines, nothing moves."""
    key, w = gcodes["mirror"] if "mirror" in gcodes else gcodes["scaling"]
    name = MILL_G[key][1] if key in MILL_G else DIALECT_G["haas"][key][1]
    other = [k for k in seen if k not in ("X", "Y", "Z", "N", *(("P", "I", "J", "K") if key == 510 else ()))]
    if other or st.comp_side is not None:
        bad = seen[other[0]] if other else w
        where.fail(f"{name}: only axis words{' and P or I J K' if key == 510 else ''}, without cutter "
                   "compensation", column=bad.column, text=bad.text, expected=f"{w.text.upper()} X.. Y.. with G40")
    values = {k: v.value for k, v in seen.items()}
    if key in (1000, 1010):  # Haas: "mirror image will reflect programmed motion around your work coordinate
        values = {k: 0.0 for k in values}  # zero point"; the axis words only name the axes
    base = st.frame or Frame()
    try:
        if key == 510:
            here = (dataclasses.replace(st, frame=dataclasses.replace(base, factors=(1.0, 1.0, 1.0)))
                    .to_program(st.pos))
            frame = scaling(base, values, {k: v.text for k, v in seen.items()}, current=here, scale=st.scale,
                            thousandths=st.context.dialect.name == "fanuc")
        else:
            frame = mirror(base, values, on=key in (511, 1010), scale=st.scale)
    except WordError as exc:
        fail_words(where, name, exc, seen, w)
    set_frame(st, frame)
    notes.add(name)


def framed_initial(st: State, *, to_program: bool) -> None:
    """Under G68/G51/G51.1 the cycle runs in program coordinates: its initial level (a machine position
    between blocks, so that it stays where the tool was when the series began while the transformation
    changes between holes: Fanuc's initial level is a tool position) goes to the program's drilling axis
    and back. Under G10 R alone it stays in program coordinates, as LinuxCNC keeps it (interp_cycles.cc
    ``cycle_il``, a program coordinate; on a G18/G19 drilling axis X or Y a machine level would mix both)."""
    if st.frame is None or st.cycle.initial is None:
        return
    axis = CYCLE_AXES[st.plane][2]
    if to_program:
        point = st.pos.copy()
        point[axis] = st.cycle.initial
        st.cycle.initial = float(st.to_program(point)[axis])
    else:
        point = st.to_program(st.pos)
        point[axis] = st.cycle.initial
        st.cycle.initial = float(st.to_machine(point)[axis])
