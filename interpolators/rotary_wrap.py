"""Rotary axes that wrap at 360 deg (modulo, roll-over axes): the end and direction of an absolute move.

A machine file marks a rotary axis as wrapping with ``[axes.a] wrap = true``
(:attr:`interpolators.context.MachineContext.wrapped_axes`); its positions are then equal modulo 360 deg, and the
control decides which way an absolute word turns the axis. Every rule here leaves an incremental word (G91, the
TNC's ``IC+..``) as it is: the axis turns by the word. The positions the readers keep, and the blocks carry, stay
unwrapped (the angle the motor has turned, continuous from block to block: 350 deg then ``A10`` the short way ends at
370 deg), so that the simulated motion, its time and its contour error follow the axis; a control shows the angle
reduced below 360 deg (LinuxCNC's interpreter keeps it unwrapped too, and only its DRO and the stored ``#5161``..
parameters reduce it). The rule of a machine is :attr:`~interpolators.context.MachineContext.wrap_direction`, one of
:data:`WRAP_DIRECTIONS`, or unset: the control's own (:func:`default_direction`).

``"sign"``
    LinuxCNC ``[AXIS_A] WRAPPED_ROTARY = 1`` (LinuxCNC INI configuration docs, "[AXIS_<letter>] Section": "the axis
    will move 0-359.999 degrees. Positive Numbers will move the axis in a positive direction and negative numbers
    will move the axis in the negative direction"; ``rs274ngc/interp_find.cc`` ``unwrap_rotary``): the word's
    magnitude is the end position modulo 360 (program coordinates), its sign the direction (``A-0`` turns
    negative), the axis turning less than a revolution (none when it is there). A word of magnitude 360 or more is an
    error ("Invalid absolute position .. for wrapped rotary axis A"). Fanuc's rotary axis control (parameter No. 1008
    #1 RABx = 1; Fanuc Series 0i/0i Mate-MC B-63534EN/02, 20.2.2 "Rotary axis control": "the sign of the value
    specified in the command is interpreted as the direction of rotation, and the absolute value of the specified
    value is interpreted as the coordinates of the target end position") is read the same way.
``"shortest"``
    Fanuc rotary axis roll-over (No. 1008 #0 ROAx = 1, #1 RABx = 0, No. 1260 = 360 deg per rotation; B-63534EN/02,
    20.2.1 "Rotary axis roll-over": for an absolute command "the tool moves in the direction in which the final
    coordinates are closest"; A0, then ``G90 A-150.`` -150, ``A540.`` -30, ``A-620.`` -80; Series 15i B-63783EN-1,
    1.6.3: "If the difference is 180 degrees, the movement is made in the normal direction", positive); the TNC's
    ``M126`` ("Shorter-path traverse of rotary axes", TNC 640 / TNC 620 user's manuals: actual 350, nominal 10:
    +20 deg) and its machine parameter ``shortestDistance`` (No. 300401) = always.
``"difference"``
    The TNC without ``M126`` (and after ``M127``) on an axis whose display is reduced below 360 deg (the same
    manuals: "the difference between nominal and actual position", actual 350, nominal 10: -340 deg; 10 to 340:
    +330 deg): from the shown angle (the unwrapped one minus its offset, reduced to [0, 360)) by the word minus it.

Fanuc's RRLx (relative coordinates rounded) changes a display only; Haas documents no rule for an absolute move on a
wrapping 4th axis in a text found here, so the Haas, Fadal and grbl dialects take Fanuc's default (RAB = 0).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Protocol

import numpy as np

__all__ = ["WRAP_DIRECTIONS", "ROTARY_AXES", "default_direction", "within_turn", "wrapped_end", "wrap_words",
           "wrap_reference", "linuxcnc_machine_word"]

#: The rules of an absolute move on a wrapping rotary axis (see the module text).
WRAP_DIRECTIONS: tuple[str, ...] = ("shortest", "sign", "difference")

#: The axes that may wrap (rotary a, b, c).
ROTARY_AXES: tuple[str, ...] = ("a", "b", "c")

#: Angles closer than this are one position of a wrapping axis [deg] (rounding, not a turn).
_SAME = 1e-9

#: The column of each rotary letter in ``Block.extra_target`` (``interpolators.iso_axes.EXTRA_LETTERS`` order).
_COLUMN = {"A": 0, "B": 1, "C": 2}


class _Word(Protocol):
    value: float
    column: int | None
    text: str


class _Where(Protocol):
    def fail(self, message: str, *, column: int | None = None, text: str | None = None,
             expected: str | None = None): ...


def default_direction(dialect: str) -> str:
    """The rule of the control ``dialect`` (a :data:`interpolators.context.DIALECTS` name) when the machine sets
    none: ``"sign"`` for LinuxCNC, ``"difference"`` for the TNC (``M126`` makes it ``"shortest"``), ``"shortest"``
    (Fanuc RAB = 0, Fanuc's default) for the others."""
    return {"linuxcnc": "sign", "heidenhain": "difference"}.get(dialect, "shortest")


def within_turn(angle: float) -> float:
    """``angle`` [deg] reduced to [0, 360), as a control shows a wrapping axis; a rounding residue below a whole
    turn (``0.3 - 3 * 0.1`` = -2.8e-17) reads 0, not 360 minus it (a shown 359.99.. would turn the next absolute
    word a whole revolution under ``"difference"``)."""
    r = angle % 360.0
    return 0.0 if r > 360.0 - _SAME else r


def wrapped_end(value: float, current: float, offset: float, direction: str) -> float:
    """The end [deg, machine, unwrapped] of an absolute word ``value`` [deg, program] on a wrapping axis now at
    ``current`` [deg, machine, unwrapped], whose program position is the machine's minus ``offset`` [deg]: by the
    rule ``direction`` of :data:`WRAP_DIRECTIONS`. ``"sign"`` expects ``|value| < 360`` (the caller checks it)."""
    here = current - offset  # the program position, unwrapped
    if direction == "sign":  # rs274ngc unwrap_rotary, its arithmetic, in program coordinates; an end within
        # _SAME of the axis is where it is (a shown angle reduced from it, 249.68099999999998 for -110.319, is no
        # whole turn: G53.1 keeping C where it is turned it +360 deg)
        end = abs(value) + math.floor(here / 360.0) * 360.0
        if math.copysign(1.0, value) > 0.0:
            end = end + 360.0 if end < here - _SAME else end
        else:
            end = end - 360.0 if end > here + _SAME else end
        return end + offset
    if direction == "shortest":
        turn = (value - here) % 360.0
        return current + (turn - 360.0 if turn > 180.0 else turn)
    if direction == "difference":
        return current + (value - within_turn(here))
    raise ValueError(f"wrap direction must be one of {', '.join(WRAP_DIRECTIONS)}, got {direction!r}")


def wrap_words(target: np.ndarray, words: Mapping[str, _Word], current: np.ndarray, offset: np.ndarray, *,
               wrapped: tuple[str, ...], direction: str, where: _Where,
               linuxcnc_offset: np.ndarray | None = None) -> np.ndarray:
    """``target`` (the ends ``(a, b, c, u, v, w)`` of a block's absolute words read as on a linear axis) with the
    words of the ``wrapped`` axes (``"a"``..) among ``words`` (letter -> word) ended by :func:`wrapped_end`.

    Parameters
    ----------
    target : ndarray, shape (6,)
        The block's end positions [deg, mm; machine]; returned as it is when no word is of a wrapped axis.
    words : mapping of str to word
        The block's absolute words of the axes beyond X, Y, Z (``"A"`` ... ``"W"``), with ``value``, ``column``
        and ``text``.
    current, offset : ndarray, shape (6,)
        Positions before the block [deg, mm; machine, unwrapped] and machine minus program position of each
        axis [deg, mm] (zero for machine-coordinate words, G53 / M91).
    wrapped : tuple of str
        The wrapping axes (:attr:`interpolators.context.MachineContext.wrapped_axes`).
    direction : str
        One of :data:`WRAP_DIRECTIONS`.
    where
        Names the block in the error of a ``"sign"`` word of magnitude 360 deg or more.
    linuxcnc_offset : ndarray, shape (6,), optional
        For machine-coordinate words (``offset`` zero) under LinuxCNC: the program offset [deg] its interpreter
        subtracts first (:func:`linuxcnc_machine_word`).
    """
    letters = [k for k in words if k in _COLUMN and k.lower() in wrapped]
    if not letters:
        return target
    out = np.array(target, dtype=float)
    for k in letters:
        w = words[k]
        if direction == "sign" and not abs(w.value) < 360.0:
            where.fail(f"invalid absolute position {w.value:g} for wrapped rotary axis {k}", column=w.column,
                       text=w.text, expected=f"-360 < {k} < 360 (the sign turns the axis that way, LinuxCNC "
                                             "WRAPPED_ROTARY / Fanuc RAB = 1), or G91")
        i = _COLUMN[k]
        out[i] = _word_end(w.value, i, current, offset, direction, linuxcnc_offset)
    return out


def _word_end(value: float, i: int, current: np.ndarray, offset: np.ndarray | None, direction: str,
              linuxcnc_offset: np.ndarray | None) -> float:
    """:func:`wrapped_end` of the word ``value`` of column ``i``: its offset ``offset[i]`` (None: a machine word,
    offset 0), or for a machine word under LinuxCNC the program offset ``linuxcnc_offset[i]`` its interpreter
    subtracts first (:func:`linuxcnc_machine_word`)."""
    if linuxcnc_offset is None:
        return wrapped_end(value, float(current[i]), 0.0 if offset is None else float(offset[i]), direction)
    off = float(linuxcnc_offset[i])
    return wrapped_end(linuxcnc_machine_word(value, off), float(current[i]), off, direction)


def linuxcnc_machine_word(value: float, offset: float) -> float:
    """The program word LinuxCNC's interpreter unwraps for the machine position ``value`` [deg] (a G53 word, or the
    G28/G30 stored position) on a wrapped axis whose program position is the machine's minus ``offset`` [deg]:
    ``|value - offset|`` with the sign of ``value`` (``interp_find.cc``: ``find_ends``'s G53 branch and
    ``find_relative`` call ``unwrap_rotary(.., block->a_number, block->a_number - AA_origin_offset - AA_axis_offset
    ..)``, which takes the magnitude of the second and the sign of the first). With a zero offset it is the machine
    angle; with another it is not (rs274 2.9.0~pre1, a 30 deg A offset, ``G53 G0 A5``: machine 55 deg; G28 to a
    stored 0: machine 60 deg), and vcnc follows rs274 there."""
    return math.copysign(abs(value - offset), value)


def wrap_reference(target: np.ndarray, current: np.ndarray, *, wrapped: tuple[str, ...], direction: str,
                   moving: tuple[str, ...] = ROTARY_AXES, linuxcnc_offset: np.ndarray | None = None) -> np.ndarray:
    """``target`` (the reference positions G28/G30 send the ``moving`` rotary axes to [deg, machine]) with each
    wrapping one ended by :func:`wrapped_end` as a machine word of that value (a Fanuc roll-over axis returns less
    than a revolution). Under ``"sign"`` the position is first reduced to [0, 360) and reached turning positive, as
    LinuxCNC's ``G28.1``/``G30.1`` store it reduced (``interp_convert.cc``, ``fmod(a, 360.0)``) and its
    ``find_relative`` unwraps it by its sign (``interp_find.cc``; ``linuxcnc_offset``: the program offset it
    subtracts first, :func:`linuxcnc_machine_word`)."""
    axes = [a for a in moving if a in wrapped]
    if not axes:
        return target
    out = np.array(target, dtype=float)
    for a in axes:
        i = _COLUMN[a.upper()]
        value = float(target[i])
        if direction == "sign":
            value = value % 360.0
        out[i] = _word_end(value, i, current, None, direction, linuxcnc_offset)
    return out
