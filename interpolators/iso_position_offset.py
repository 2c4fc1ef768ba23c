"""Fanuc tool position offset ``G45``-``G48``: a block's travel lengthened or shortened by a tool offset.

Sources: Fanuc Series 0i-MD operator's manual (B-64304EN) II-14.2 "Tool position offset (G45 to G48)";
Mitsubishi M700V programming manual (a Fanuc-compatible control) 12.6 "Tool Position Offset; G45 to G48",
which tabulates the cases (https://manualshive.com/en/manual/mitsubishi-electric/m700v-series/238523?page=242).

* One-shot codes (group 00): ``G45`` increases the travel of each axis word of the block by the offset value
  ``l``, ``G46`` decreases it, ``G47`` increases it by ``2 l``, ``G48`` decreases it by ``2 l``: an axis
  travelling ``x`` (its end point minus its start point) travels ``x + k l sign(x)`` with ``k`` = 1, -1, 2, -2.
  A negative ``l`` reverses the effect ("G45 X1000 D.. with l = -10: X990"); the move may even turn round
  ("the tool will proceed to move in the opposite direction").
* A zero travel written incrementally (G91) travels ``k l`` in the direction of the zero's sign: ``G45 X0``
  moves ``+l``, ``G45 X-0`` ``-l``, ``G46 X0`` ``-l``. A zero travel under G90 does not move ("the tool does
  not move for the compensation amount").
* ``l`` is the value of the offset number the block's ``D`` (or ``H``) word names: vcnc's tool table keeps a
  radius for ``D`` and a length for ``H`` (Fanuc's "tool compensation memory C", Mitsubishi's type II); an
  offset number missing from the table is 0, as the table's other entries.

Refused (an error naming the case): an arc (Fanuc runs only quarter and three-quarter circles with I J), a block
without D or H, cutter compensation on (G41/G42: Fanuc's manual says not to combine them), a canned cycle
(Mitsubishi ignores the codes there), a rotated, scaled or mirrored system (G68, G51, G51.1, G10 R: the offset is
along the machine's axes) and an axis word other than X Y Z.
"""

from __future__ import annotations

import numpy as np

__all__ = ["POSITION_OFFSET_CODES", "offset_travel"]

#: The codes (round(10 * G)), their names, and the multiple ``k`` of the offset each adds to the travel.
POSITION_OFFSET_CODES: dict[int, tuple[str, int]] = {
    450: ("G45 tool position offset increase", 1), 460: ("G46 tool position offset decrease", -1),
    470: ("G47 tool position offset double increase", 2), 480: ("G48 tool position offset double decrease", -2),
}


def offset_travel(key: int, start: np.ndarray, target: np.ndarray, axes: dict[int, bool], offset: float, *,
                  incremental: bool) -> np.ndarray:
    """The end point [mm] of a ``G45``-``G48`` block.

    Parameters
    ----------
    key : int
        round(10 * G) of the code (450, 460, 470, 480).
    start, target : ndarray (3,)
        Start and programmed end point [mm, machine].
    axes : dict of int to bool
        The block's axis words (0, 1, 2 for X, Y, Z), each with whether its value was written negative (the
        direction of an incremental zero: ``X-0``).
    offset : float
        The offset value ``l`` [mm].
    incremental : bool
        G91: a zero travel moves ``k l``; under G90 it does not move.
    """
    k = POSITION_OFFSET_CODES[key][1]
    end = np.array(target, dtype=float)
    for axis, negative in axes.items():
        travel = end[axis] - start[axis]
        if travel != 0.0:
            end[axis] += k * offset * np.sign(travel)
        elif incremental:
            end[axis] += -k * offset if negative else k * offset
    return end
