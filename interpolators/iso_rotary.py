"""Rotary axis words A, B, C of the ISO reader: end positions, feed, and the blocks' rotary positions.

Semantics follow LinuxCNC (G-code overview, "Feed Rate", https://linuxcnc.org/docs/html/gcode/
overview.html#sub:feed-rate) and RS274/NGC 3 (Kramer, Proctor, Messina, NISTIR 6556, 2000,
Sec. 2.1.2.5 "Feed Rate"):

* A, B, C are angles [deg] (never scaled by G20), absolute under G90 and incremental under G91;
  G53 takes them as machine angles. The rotary work offsets are 0 (the tables hold X, Y, Z).
* With X, Y or Z moving (with or without rotary motion), F applies to the XYZ path "as if the
  rotational axes were not moving"; the rotary axes move in proportion (coordinated).
* With only rotary axes moving, F is in deg/min along ``D = sqrt(dA^2 + dB^2 + dC^2)``.
* Under G93 (inverse time) the block takes ``1/F`` minutes either way.

LinuxCNC's canon does the same (``src/emc/task/emccanon.cc``: ``SET_FEED_RATE`` keeps a linear
feed converted from program units and an angular feed in deg/min; ``getStraightVelocity`` calls a
move with X/Y/Z (or U/V/W) "cartesian" and measures it along XYZ, a move of A/B/C alone
"angular", measured along ``sqrt(da^2 + db^2 + dc^2)``, citing NIST IR 6556 Sec. 2.1.2.5).

A machine (:class:`interpolators.context.MachineContext`) names the rotary axes it has; a word of
another axis is an error naming it (a word ``A0`` on a machine without A is accepted with a note,
as CAM posts write it on 3-axis work).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from interpolators.program import Block

__all__ = ["ROTARY_LETTERS", "rotary_target", "fill_rotary"]

#: Rotary axis words, in the column order of ``Block.rotary_start`` / ``rotary_target``.
ROTARY_LETTERS: str = "ABC"


def rotary_target(values: dict[str, float], current: np.ndarray, *, incremental: bool,
                  machine: bool = False) -> np.ndarray:
    """End angles ``(a, b, c)`` [deg] of a block with the rotary words ``values`` (letter -> value).

    Parameters
    ----------
    values : dict of str to float
        The block's rotary words (``"A"``, ``"B"``, ``"C"``) [deg].
    current : ndarray, shape (3,)
        Rotary positions before the block [deg].
    incremental : bool
        G91: the words are added to ``current``.
    machine : bool
        G53: the words are machine angles (absolute, whatever the distance mode).
    """
    target = np.array(current, dtype=float)
    for letter, v in values.items():
        i = ROTARY_LETTERS.index(letter)
        target[i] = current[i] + v if incremental and not machine else v
    return target


def fill_rotary(blocks: list[Block]) -> list[Block]:
    """Blocks with the rotary positions of every block set: a block the reader left without them
    (no rotary word: a dwell, a cycle move, a compensation corner) holds the rotary axes where the
    previous block left them (0 at program start)."""
    out: list[Block] = []
    current = np.zeros(3)
    for b in blocks:
        if b.rotary_target is None:
            out.append(_with_rotary(b, current))
        else:
            out.append(b)
            current = np.array(b.rotary_target, dtype=float)
    return out


def _with_rotary(b: Block, at: np.ndarray) -> Block:
    return dataclasses.replace(b, rotary_start=at.copy(), rotary_target=at.copy())
