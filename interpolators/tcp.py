"""Tool centre point control (TCP) on a tilting table: the geometry both readers share.

Under TCP a program's X, Y, Z are the tool tip on the workpiece, in the workpiece coordinate system that the
table carries (with every rotary axis at 0 it is the one the work offset or preset gives); the control moves
the linear axes so that the tip stays where the program puts it while the rotary axes turn the part. The
controls that define it, and what vcnc reads of each:

* HEIDENHAIN ``M128`` (iTNC 530 user's manual 340 49x-04, "Maintaining the position of the tool tip when
  positioning with tilted axes (TCPM): M128": "M128 executes compensation movements that must not change the
  feed rate of the tool relative to the workpiece") and ``FUNCTION TCPM`` (iTNC 530 user's manual 60642x-04 /
  TNC 620 user's manual 10/2017, "FUNCTION TCPM": ``F TCP`` "the programmed feed rate is interpreted as the
  actual relative velocity between the tool point (tool center point) and the workpiece"; ``PATHCTRL AXIS``
  "the tool tip moves on a straight line between the starting and end position of the respective NC block";
  ``AXIS POS`` the rotary words are the axes' positions): :mod:`interpolators.heidenhain_tcpm`.
* Fanuc ``G43.4`` (type 1) and Haas ``G234`` (FANUC Series 30i-MODEL A, "Tool center point control for
  5-axis machining", A-79348E, 1.1: "If linear interpolation is specified in this function mode, speed control
  is exerted in such a way that the tool center point moves at a specified speed with respect to the
  workpiece"; with parameter WKP (No. 19696#5) = 0 "the workpiece coordinate system that is fixed on the table
  ... becomes the programming coordinate system. Thereafter, the programming coordinate system rotates as the
  table turns"; Haas mill operator's manual, "G234 Tool Center Point Control (TCPC)": "TCPC makes sure that
  this coordinate system remains fixed relative to the table; when the rotary axes rotate, the linear
  coordinate system rotates with them"): :mod:`interpolators.iso_tcp`; Fanuc's type 2, ``G43.5``, and
  HEIDENHAIN's ``LN .. TX TY TZ`` give the tool direction instead of the rotary positions
  (:func:`tool_vector_extra`).

The map. On a table machine the spindle stays along Z; the part point ``p`` (where the tool reference would be,
tool length ``L`` along Z included, with the tip on that part point and every rotary axis at 0) is at the
machine position ``place(p - L, angles) + L`` (:func:`machine_point`, :meth:`interpolators.tilted.Kinematics.place`)
and back (:func:`part_point`). Fanuc's manual says that the table's angle when G43.4 is given is the "initial
state" of the programming coordinate system and draws it against the "C-axis reference position" (the axis at
its scale's 0); our reading is that the table-fixed system is the workpiece system at the rotary axes' 0, turned
by their angles, which is what Haas and HEIDENHAIN say and what CAM posts write (the tip in the setup's
coordinates, the rotary axes positioned before G43.4 / M128).

LinuxCNC does the same with a kinematics module rather than a G code (LinuxCNC/linuxcnc
``docs/src/motion/5-axis-kinematics.adoc``, "Table Rotary/Tilting 5-Axis Configurations": the world coordinates
of its xyzac-trt / xyzbc-trt kinematics are "the cutter tip position ... relative to the workpiece coordinate
system", the joints those of the pivot); its planner moves the world coordinates X Y Z A C linearly together,
with the feed along X Y Z, else along the rotary axes (RS274/NGC 3, Sec. 2.1.2.5): the model here.

A block under TCP whose rotary axes move: the tip runs on the straight line from its start to its programmed
end on the part while the rotary axes move in proportion (linearly with the tip's travel: Fanuc type 1,
HEIDENHAIN PATHCTRL AXIS); in machine coordinates that is a curve. :func:`tcp_chords` cuts it into chords,
straight machine blocks with the rotary axes' values at their ends, equally spaced in the tip's travel and as
many as it takes for the tip to stay within the path tolerance of the programmed line (at most
:data:`MAX_CHORDS`). Each chord gets the feed that makes its time its share of the block's: the tip length over
F (F TCP), so the tip moves at F relative to the part; a block whose tip stays (a turn about the tip) takes the
rotary distance over F read as deg/min, as a rotary move without TCP (RS274/NGC 3, Sec. 2.1.2.5; Fanuc's manual
only says such a block "must be executed in G00 or G01 mode": our reading); under inverse time (G93) 1/F
minutes. A rapid's chords are rapids. The last chord ends exactly at the programmed tip's machine position.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence

import numpy as np

from interpolators.lookahead import DEFAULT_TOLERANCE
from interpolators.rotary_wrap import wrapped_end
from interpolators.tilted import Kinematics, vector

__all__ = ["MAX_CHORDS", "ChordsError", "TcpChords", "part_point", "machine_point", "tcp_chords", "block_time",
           "tool_vector_extra"]

#: The most chords one block under TCP is cut into; a block that needs more is an error (:class:`ChordsError`).
MAX_CHORDS = 5000
#: A chord whose machine X, Y, Z move less than this is a rotary move with X, Y, Z still [mm].
_STILL = 1e-9
#: Where in each chord the tip's distance from the programmed line is measured [-].
_PROBES = np.array([0.25, 0.5, 0.75])


class ChordsError(ValueError):
    """A block under TCP needs more than :data:`MAX_CHORDS` chords; the reader adds the file and line."""


def _tool(length: float) -> np.ndarray:
    return np.array([0.0, 0.0, length])


def part_point(kinematics: Kinematics, extra: Sequence[float], position: Sequence[float], length: float) -> np.ndarray:
    """Where the tool tip at machine ``position`` [mm] is on the part with every rotary axis at 0 [mm, machine,
    tool length ``length`` along Z included], the rotary axes at ``extra`` (a, b, c first) [deg]."""
    angles = kinematics.solution_at(extra)
    return kinematics.unplace(np.asarray(position, dtype=float) - _tool(length), angles) + _tool(length)


def machine_point(kinematics: Kinematics, extra: Sequence[float], point: Sequence[float], length: float) -> np.ndarray:
    """The inverse of :func:`part_point`: the machine position [mm] of the part point ``point``."""
    angles = kinematics.solution_at(extra)
    return kinematics.place(np.asarray(point, dtype=float) - _tool(length), angles) + _tool(length)


def tool_vector_extra(kinematics: Kinematics, direction: Sequence[float], extra: np.ndarray, *,
                      wrapped: tuple[str, ...] = ()) -> np.ndarray:
    """The positions of a, b, c, u, v, w [deg, mm] that turn the tool direction ``direction`` (a vector in the
    workpiece coordinates, from the tip towards the spindle) onto the spindle axis: ``extra`` with the kinematics'
    axes at the solution nearest their present positions within their limits, each axis at the turn of 360 deg
    nearest its position (:meth:`interpolators.tilted.Kinematics.choose` with ``nearest``; FANUC Series
    15i/150i-MODEL A connection manual B-63323EN-1/03, 10.4.10, type 2, note 4: "Movement of the rotation axes
    is controlled by a shortcut control so that the amount of movement does not exceed 180°"; our reading for
    HEIDENHAIN's ``LN .. TX TY TZ`` too). An axis among ``wrapped`` (it wraps at 360 deg) turns by at most half a
    turn whatever its unwrapped position (C at 370 to 90: +80 to 450; the limits, which hold a wrapping axis'
    angle modulo 360 deg, no longer keep it near 0: :func:`interpolators.rotary_wrap.wrapped_end` ``"shortest"``).

    Raises
    ------
    interpolators.tilted.TiltError
        No solution within the limits, or a zero vector.
    """
    d = np.asarray(direction, dtype=float)
    base = np.eye(3)[int(np.argmin(np.abs(d)))]  # any direction not along d: only the tool axis matters here
    turns = {name: _shortest_from(float(extra["abc".index(name)])) for name in kinematics.names if name in wrapped}
    angles = kinematics.choose(vector(base, d), kinematics.solution_at(extra), nearest=True, turns=turns)
    out = np.array(extra, dtype=float)
    for name, value in kinematics.positions(angles).items():
        i = "abc".index(name)
        out[i] = out[i] + turns[name](value) if name in turns else value  # a wrapping axis: where its turn ends
    return out


def _shortest_from(now: float) -> Callable[[float], float]:
    """The turn [deg] of a wrapping axis at ``now`` [deg, unwrapped] to an angle, the shorter way."""
    return lambda angle: wrapped_end(angle, now, 0.0, "shortest") - now


def block_time(start: Sequence[float], end: Sequence[float], turn: Sequence[float], *, feed: float,
               rotary_feed: float) -> float:
    """The time [s] of a feed block under TCP: the tip's length from part point ``start`` to ``end`` [mm] at
    ``feed`` [mm/s]; with the tip still, the rotary distance ``|turn[:3]|`` [deg] at ``rotary_feed`` [deg/s]
    (the module's notes)."""
    tip = float(np.linalg.norm(np.subtract(end, start, dtype=float)))
    if tip > _STILL:
        return tip / feed
    return float(np.linalg.norm(np.asarray(turn, dtype=float)[:3])) / rotary_feed


@dataclasses.dataclass(frozen=True)
class TcpChords:
    """The chords of one block under TCP.

    Attributes
    ----------
    targets : ndarray, shape (n, 3)
        Machine end point of each chord [mm]; the last is the block's end.
    extras : ndarray, shape (n, 6)
        Positions of a, b, c [deg], u, v, w [mm] at each chord's end.
    feeds : ndarray, shape (n,)
        Path feed of each chord [mm/s along its X Y Z; deg/s along its rotary distance when X, Y, Z stay];
        ``inf`` for a rapid.
    error : float
        The largest distance of the tip from the programmed line found between the chords' ends [mm].
    """

    targets: np.ndarray
    extras: np.ndarray
    feeds: np.ndarray
    error: float


def tcp_chords(kinematics: Kinematics, *, start: np.ndarray, end: np.ndarray, start_extra: np.ndarray,
               end_extra: np.ndarray, length: float, tolerance: float | None, duration: float | None,
               position: np.ndarray, feed: float = math.inf) -> TcpChords:
    """The chords of a block under TCP from part point ``start`` to ``end`` [mm] (:func:`part_point`) while the
    axes beyond X, Y, Z go from ``start_extra`` to ``end_extra`` [deg, mm].

    Parameters
    ----------
    kinematics : Kinematics
        The tilting table.
    length : float
        Tool length along Z [mm].
    tolerance : float or None
        Largest distance of the tip from the programmed line [mm] (G64 P, cycle 32 T; None:
        :data:`interpolators.lookahead.DEFAULT_TOLERANCE`).
    duration : float or None
        The block's time [s] (:func:`block_time`, or 1/F min under G93); None for a rapid.
    position : ndarray (3,)
        The machine position where the block starts [mm] (the first chord's start).
    feed : float
        The feed of a block in which nothing moves (its time 0) [mm/s]: the programmed one.

    Raises
    ------
    ChordsError
        More than :data:`MAX_CHORDS` chords would be needed.
    """
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    e0, e1 = np.asarray(start_extra, dtype=float), np.asarray(end_extra, dtype=float)
    tolerance = DEFAULT_TOLERANCE if tolerance is None else tolerance
    n = 1
    while True:
        u = np.linspace(0.0, 1.0, n + 1)
        extras = e0 + u[:, None] * (e1 - e0)
        ends = np.array([machine_point(kinematics, extras[k], start + u[k] * (end - start), length)
                         for k in range(1, n + 1)])
        ends[-1] = machine_point(kinematics, e1, end, length)
        points = np.vstack([np.asarray(position, dtype=float), ends])
        error = _largest_error(kinematics, points, extras, start, end, length)
        if error <= tolerance or n >= MAX_CHORDS:
            break
        n = min(MAX_CHORDS, max(n + 1, math.ceil(1.05 * n * math.sqrt(error / tolerance))))
    if error > tolerance:
        raise ChordsError(f"the tool tip would need more than {MAX_CHORDS} chords to stay within {tolerance:g} mm of "
                          f"its line ({error:.3g} mm with {MAX_CHORDS})")
    steps = np.diff(points, axis=0)
    still = np.linalg.norm(steps, axis=1) < _STILL
    for k in np.flatnonzero(still):
        points[k + 1] = points[k]  # X, Y, Z still: a rotary move whose path is the rotary distance
    if duration is None or not duration > 0:
        feeds = np.full(n, math.inf if duration is None else feed)
    else:
        turns = np.diff(extras, axis=0)
        paths = np.where(still, _extra_lengths(turns), np.linalg.norm(np.diff(points, axis=0), axis=1))
        feeds = paths / (duration / n)
    return TcpChords(targets=points[1:], extras=extras[1:], feeds=feeds, error=error)


def _extra_lengths(turns: np.ndarray) -> np.ndarray:
    """The path of a move with X, Y, Z still (:attr:`interpolators.program.Block.extra_length`): the U V W
    distance when U, V or W move, else the rotary distance [mm or deg]."""
    secondary = np.linalg.norm(turns[:, 3:], axis=1)
    return np.where(secondary > 0, secondary, np.linalg.norm(turns[:, :3], axis=1))


def _largest_error(kinematics: Kinematics, points: np.ndarray, extras: np.ndarray, start: np.ndarray,
                   end: np.ndarray, length: float) -> float:
    """The largest distance [mm] of the tip from the segment ``start``-``end`` (part points) at the probes of
    each chord, the machine axes and the extra axes moving in proportion along it."""
    d = end - start
    dd = float(d @ d)
    worst = 0.0
    for k in range(len(points) - 1):
        for s in _PROBES:
            m = points[k] + s * (points[k + 1] - points[k])
            e = extras[k] + s * (extras[k + 1] - extras[k])
            tip = part_point(kinematics, e, m, length)
            t = 0.0 if dd == 0.0 else min(1.0, max(0.0, float((tip - start) @ d) / dd))
            worst = max(worst, float(np.linalg.norm(tip - (start + t * d))))
    return worst
