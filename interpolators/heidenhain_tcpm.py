"""``M128`` and ``FUNCTION TCPM`` (TCPM, tool centre point management) of Heidenhain conversational programs on a
tilting table; the geometry is :mod:`interpolators.tcp`'s.

HEIDENHAIN TNC7 user's manual (German, 81762x-17, content.heidenhain.de/doku/tnc_guide/pdf_files/TNC7/81762x-17),
M128: "Wenn sich im NC-Programm die Position einer gesteuerten Drehachse ändert, kompensiert die Steuerung mit
M128 während des Schwenkvorgangs automatisch die Werkzeuganstellung mithilfe einer Ausgleichsbewegung der
Linearachsen. Somit bleibt die Position der Werkzeugspitze gegenüber dem Werkstück unverändert (TCPM)." (the
TNC 640 manual's "Retaining the position of the tool tip when positioning tilting axes (TCPM): M128"); the
programmed X, Y, Z are the tool tip on the workpiece; M129 cancels it. On a machine whose rotary axes turn
the part (a trunnion table, :class:`interpolators.tilted.Kinematics` ``kind = "table"``) the spindle stays
along Z, so the tip of a workpiece point ``p`` (where it is with every rotary axis at 0, tool length included
along Z) is where the table carries it: ``machine = place(p - L, angles) + L``
(:func:`interpolators.tcp.machine_point`).

What vcnc reads: straight lines ``L`` (and ``M140`` retracts along the spindle) whose rotary words A, B, C may
change. With the rotary axes still (the "3+2" use NX posts write: ``L B76.323 C-150.677 FMAX``, ``L M128
F3000.``, then lines) a line maps to a straight machine line; with them moving (simultaneous 5-axis, the
Fusion 360 and NX TNC posts' ``L X.. Y.. Z.. B.. C.. F..``) the tip runs on the straight line to its programmed
end while the rotary axes move in proportion, emitted as chords within the path tolerance (cycle 32 T, else
the default), the feed F that of the tip relative to the part (:func:`interpolators.tcp.tcp_chords`). That is
M128's feed (iTNC 530 user's manual 340 49x-04, M128: "M128 executes compensation movements that must not
change the feed rate of the tool relative to the workpiece"; the F after M128, the feed of those compensation
movements, is noted and ignored) and ``FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS`` (:func:`function_tcpm`).
``LN X Y Z NX NY NZ TX TY TZ`` under it is the tool-vector form (:func:`tool_vector`): the rotary axes turn to
make T the spindle's axis, moving linearly to it, the part point displaced along N by the delta values. An arc,
a polar, approach or compensated block, a cycle, a head-tilting machine or a tool axis other than Z are errors
naming them.

In a tilted working plane that turns the workpiece coordinates (:func:`tilt_turns`; the CAM posts' "3+2" with TCPM
on: hyperMILL's and NX's TNC 640 posts write ``PLANE SPATIAL .. TURN`` then ``FUNCTION TCPM F TCP AXIS POS
PATHCTRL AXIS`` or ``M128``) a line whose rotary axes stay is the plane's line: the programmed X, Y, Z are the tool
tip in the tilted coordinates with or without TCPM, which only acts when a rotary axis moves (TNC 640 user's
manual, "Inclined-tool machining in a tilted plane"; M128: "the position of the tool tip relative to the workpiece
... when positioning tilting axes"). A rotary axis moving there, or another block than such a line, is an error
naming it (:func:`still_in_tilted_plane`; our reading, not modelled).
"""

from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.iso_axes import EXTRA_LETTERS
from interpolators.tcp import ChordsError, block_time, part_point, tcp_chords, tool_vector_extra
from interpolators.tilted import Kinematics, TiltError, spatial
from toolpaths.geometry import Line

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine
    from interpolators.heidenhain_transforms import TiltedPlane

__all__ = ["TCPM_EXPECTED", "check_tcpm_on", "function_tcpm", "spatial_axes", "still_in_tilted_plane", "tcpm_line",
           "tilt_turns", "tool_vector"]

#: What M128 / FUNCTION TCPM need here.
TCPM_EXPECTED = ("M128 or FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS on a machine whose rotary axes turn the part "
                 "([program.kinematics] kind = \"table\"), tool axis Z, straight lines L until M129 / FUNCTION "
                 "RESET TCPM (in a tilted plane that turns the workpiece coordinates: lines with the rotary axes "
                 "still)")

#: The words of FUNCTION TCPM and what vcnc reads of each (None: read as M128 does; AXIS SPAT: :func:`spatial_axes`).
_TCPM_WORDS = {
    "F TCP": None, "AXIS POS": None, "PATHCTRL AXIS": None, "REFPNT TIP-TIP": None, "AXIS SPAT": None,
    "F CONT": "F CONT (the feed as the contouring feed of the programmed axes) is not modelled",
    "PATHCTRL VECTOR": "PATHCTRL VECTOR (the tool vector interpolated in a plane) is not modelled",
    "REFPNT TIP-CENTER": "REFPNT TIP-CENTER (the tool's centre as the point of rotation) is not modelled",
    "REFPNT CENTER-CENTER": "REFPNT CENTER-CENTER (the tool's centre as the programmed point) is not modelled",
}
_TCPM_WORD_RE = re.compile(r"\s*(F\s+(?:TCP|CONT)|AXIS\s+(?:POS|SPAT)|PATHCTRL\s+(?:AXIS|VECTOR)|"
                           r"REFPNT\s+(?:TIP-TIP|TIP-CENTER|CENTER-CENTER))\b", re.I)


def tilt_turns(tilt: TiltedPlane | None) -> bool:
    """True when the tilted working plane ``tilt`` turns the workpiece coordinates: a rotation other than the
    identity, or rotary positions other than 0 (a whole turn apart is 0).

    Our reading: a PLANE whose working plane is the untilted one at rotary positions 0 (``PLANE VECTOR BX1 BY0
    BZ0 NX0 NY0 NZ1 STAY .. TABLE ROT``, which a CAM post of wild set 5x writes before every operation, then
    ``L Z40 R0 F30000 M128``) leaves the tilted coordinates those of the workpiece, so M128 reads its lines as
    with no plane; a plane that turns them (TNC 640 user's manual, "Inclined-tool machining in a tilted plane":
    M128 in a tilted plane) is not modelled."""
    if tilt is None:
        return False
    return (not np.allclose(tilt.rotation, np.eye(3), atol=1e-12)
            or any(abs(math.remainder(a, 360.0)) > 1e-9 for a in tilt.angles.values()))


def check_tcpm_on(kinematics: Kinematics | None, *, tool_axis: int, where: Where, column: int, text: str) -> None:
    """An error at ``where`` unless M128 can be read on this machine in this state (see the module text)."""
    if kinematics is None:
        where.fail(f"{text.upper()} (TCPM, tool centre point management) needs the machine's kinematics",
                   column=column, text=text, expected=TCPM_EXPECTED)
    if kinematics.kind != "table":
        where.fail(f"{text.upper()} (TCPM) on a head-tilting machine is not supported", column=column, text=text,
                   expected=TCPM_EXPECTED)
    if tool_axis != 2:
        where.fail(f"{text.upper()} (TCPM) with a tool axis other than Z is not supported",
                   column=column, text=text, expected=TCPM_EXPECTED)


def still_in_tilted_plane(kw: str, extra: np.ndarray | None, m: Machine, where: Where) -> None:
    """A block under M128 / FUNCTION TCPM in a tilted plane that turns the workpiece coordinates: nothing when it is
    a line ``L`` whose rotary axes stay (the caller runs it as the plane's line), else an error naming what it is
    (a rotary axis moving, an arc, a compensated or approach block: see the module text)."""
    if extra is not None and np.any(np.abs(extra[:3] - m.extra[:3]) > 1e-9):
        where.fail("a rotary axis moving under M128 / FUNCTION TCPM in a tilted working plane is not supported",
                   column=1, text=where.text, expected=TCPM_EXPECTED)
    waiting = ("RND/CHF" if m.pending is not None else "APPR/DEP" if m.approach is not None else "RL/RR"
               if m.comp != "R0" else None)
    if kw != "L" or waiting is not None:
        where.fail(f"{waiting or kw} under M128 in a tilted working plane is not supported", column=1,
                   text=where.text, expected=TCPM_EXPECTED)


def function_tcpm(rest: str, m: Machine, where: Where, *, column: int) -> None:
    """``FUNCTION TCPM F TCP|F CONT AXIS POS|AXIS SPAT PATHCTRL AXIS|PATHCTRL VECTOR [REFPNT ..]``, ``FUNCTION
    RESET TCPM`` (``rest``: the text after FUNCTION).

    iTNC 530 user's manual 60642x-04, 12.4 "TCPM FUNCTION"; TNC 620 user's manual 10/2017, "FUNCTION TCPM":
    F TCP "the programmed feed rate is interpreted as the actual relative velocity between the tool point
    (tool center point) and the workpiece", AXIS POS "the programmed coordinates of rotary axes as the nominal
    position of the respective axis", PATHCTRL AXIS "the tool tip moves on a straight line between the starting
    and end position of the respective NC block"; REFPNT TIP-TIP (TNC 640) the tool tip as the programmed point
    and the point of rotation. That is what vcnc reads (as M128); AXIS SPAT, the rotary words as spatial angles,
    is :func:`spatial_axes`; F CONT, PATHCTRL VECTOR and the other REFPNT are errors naming them. A word left out
    is read as M128 acts (our reading: the manuals show the three groups always given)."""
    if re.match(r"\s*RESET\s+TCPM\s*$", rest, re.I):
        m.tcpm = False
        m.tcpm_spatial = None
        return
    tm = re.match(r"\s*TCPM\b", rest, re.I)
    if tm is None:
        where.fail("malformed FUNCTION RESET TCPM", column=column, text=rest.strip(), expected="FUNCTION RESET TCPM")
    pos = tm.end()
    spat = False
    while rest[pos:].strip():
        wm = _TCPM_WORD_RE.match(rest, pos)
        if wm is None:
            tok = rest[pos:].split()[0]
            where.fail(f"unexpected {tok!r} in FUNCTION TCPM", column=column + pos, text=tok, expected=TCPM_EXPECTED)
        word = re.sub(r"\s+", " ", wm.group(1).upper())
        if _TCPM_WORDS[word] is not None:
            where.fail(f"FUNCTION TCPM {word}: {_TCPM_WORDS[word]}", column=column + wm.start(1), text=wm.group(1),
                       expected=TCPM_EXPECTED)
        spat = spat or word == "AXIS SPAT"
        pos = wm.end()
    check_tcpm_on(m.context.kinematics, tool_axis=m.plane, where=where, column=column, text="FUNCTION TCPM")
    m.tcpm = True
    m.tcpm_spatial = np.zeros(3) if spat else None
    m.note("FUNCTION TCPM: lines of the tool tip on the turned part (as M128)"
           + (", A B C spatial angles (AXIS SPAT)" if spat else ""))


def tool_vector(seen: dict, m: Machine, where: Where) -> np.ndarray | None:
    """``LN .. TX TY TZ`` under M128 / FUNCTION TCPM: the rotary positions [deg] (``m.extra`` changed) that turn the
    tool orientation T onto the spindle, None without T (the axes stay).

    iTNC 530 user's manual 60642x-04, 12.7 "Three-dimensional tool compensation", "Face milling: 3-D compensation
    with and without tool orientation": with M128 "the TNC positions the rotary axes so that the tool reaches
    the defined tool orientation" given by TX, TY, TZ; without M128 it ignores them. Our reading: T points from
    the tip to the spindle, in the workpiece coordinates; the solution nearest the present positions within the
    limits is taken (as PLANE without SEQ), the axes moving linearly to it (PATHCTRL AXIS)."""
    keys = [k for k in ("TX", "TY", "TZ") if k in seen]
    if not keys:
        return None
    if len(keys) < 3:
        w = seen[keys[0]]
        where.fail("LN with only part of the tool orientation TX TY TZ", column=w.column, text=w.text,
                   expected="LN .. TX.. TY.. TZ.. (all three components)")
    return _turn_tool_to([seen[k].value for k in ("TX", "TY", "TZ")], m, where, seen["TX"],
                         what="LN tool orientation TX TY TZ under M128")


def spatial_axes(seen: dict, m: Machine, where: Where) -> np.ndarray | None:
    """``L X.. Y.. Z.. A.. B.. C..`` under ``FUNCTION TCPM .. AXIS SPAT``: the rotary positions [deg] (``m.extra``
    changed) that give the tool the orientation of the spatial angles A, B, C, None without them (the axes stay).

    TNC7 basic user's manual 81762x-19, "Difference between spatial angles and axis angles": with spatial angles
    "you can define the angle of the tool relative to the workpiece ... The control takes care of calculating the
    required axis positions", in "FUNCTION TCPM with AXIS SPAT selected" as in the PLANE functions; PLANE SPATIAL's
    rotations about the machine-fixed axes, first A, then B, then C (iTNC 530 user's manual 340 422, 9.2), turn
    the tool axis +Z (:func:`interpolators.tilted.spatial`). Our reading: the tool's direction is what they give
    (the tip on the part is X, Y, Z whatever the turn about it), the axes' solution nearest where they are (as
    ``LN .. TX TY TZ``); an angle not written keeps its last value under this FUNCTION TCPM, 0 at first; an
    incremental IA/IB/IC or a U, V, W word is an error."""
    words = [k for k in seen if len(k) <= 2 and k[-1] in EXTRA_LETTERS and k[:-1] in ("", "I")]
    if not words:
        return None
    angles = m.tcpm_spatial.copy()
    for key in words:
        w = seen[key]
        if key[0] == "I" or key[-1] not in "ABC":
            where.fail(f"{w.text!r} under FUNCTION TCPM AXIS SPAT (A, B, C spatial angles) is not modelled",
                       column=w.column, text=w.text, expected="A, B, C absolute spatial angles [deg]")
        angles["ABC".index(key[-1])] = w.value
    m.tcpm_spatial = angles
    return _turn_tool_to(spatial(*angles)[:, 2], m, where, seen[words[0]],
                         what="FUNCTION TCPM AXIS SPAT spatial angles")


def _turn_tool_to(direction, m: Machine, where: Where, w, *, what: str) -> np.ndarray:
    """The rotary positions [deg] that turn the tool direction ``direction`` (workpiece coordinates) onto the
    spindle (:func:`interpolators.tcp.tool_vector_extra`), the axes marked used; an error at the word ``w``."""
    kin = m.context.kinematics
    try:
        extra = tool_vector_extra(kin, direction, m.extra, wrapped=m.context.wrapped_axes)
    except TiltError as exc:
        where.fail(f"{what}: {exc.message}", column=w.column, text=w.text, expected=exc.expected)
    m.extra_used = True
    m.used.update(3 + "abc".index(name) for name in kin.names)
    return extra


def tcpm_line(m: Machine, part: np.ndarray, extra: np.ndarray, *, rapid: bool, where: Where, number) -> None:
    """A line ``L`` under TCPM to the part point ``part`` [mm] whose rotary axes move to ``extra`` [deg]: its chords
    (:func:`interpolators.tcp.tcp_chords`), joined without stops, the last ending as the path mode says."""
    kin = m.context.kinematics
    start = part_point(kin, m.extra, m.pos, m.tool_length)
    tolerance = m.tolerance if m.tolerance is not None else m.context.dialect.tolerance
    duration = None if rapid else block_time(start, part, extra - m.extra, feed=m.feed, rotary_feed=m.rotary_feed)
    try:
        chords = tcp_chords(kin, start=start, end=part, start_extra=m.extra, end_extra=extra, length=m.tool_length,
                            tolerance=tolerance, duration=duration, position=m.pos, feed=m.feed)
    except ChordsError as exc:
        where.fail(f"L under M128 (TCPM): {exc}", column=1, text=where.text,
                   expected="a smaller rotary move per block, or a larger tolerance (cycle 32 T)")
    exact_stop = m.exact_stop
    last = len(chords.feeds) - 1
    m.tcpm_move = True
    for k, (target, ends, feed) in enumerate(zip(chords.targets, chords.extras, chords.feeds, strict=True)):
        m.exact_stop = exact_stop if k == last else False
        m.emit("rapid" if rapid else "line", target, Line(m.pos, target), float(feed), where, number, extra=ends)
    m.tcpm_move = False
    m.exact_stop = exact_stop
