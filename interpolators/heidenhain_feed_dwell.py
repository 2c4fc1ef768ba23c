"""``FUNCTION FEED DWELL``: a dwell repeated during the feed moves, for chip breaking.

TNC 640 user's manual (conversational programming, "Cyclic dwell time: FUNCTION FEED DWELL"): ::

    FUNCTION FEED DWELL D-TIME0.5 F-TIME5      after every 5 s of feed motion the feed stops for 0.5 s
    FUNCTION FEED DWELL RESET                  no more dwells

The dwells interrupt feed moves only, not rapid traverse. The manual page was not in the corpus we could
search; what it says beyond the two times (whether the count of cutting time runs on across blocks, and
across the moves of cycles) is our reading: the cutting time counts the programmed feed moves of the
path, lines and arcs alike (at their programmed feed, the time the path takes without acceleration),
across blocks, from the FUNCTION FEED DWELL block on; a move is split where the count reaches F-TIME and
the dwell runs there.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from toolpaths.geometry import Arc, Line, piece_of

__all__ = ["FeedDwell", "split_at_times"]


@dataclasses.dataclass
class FeedDwell:
    """The active cyclic dwell: ``dwell`` [s] after every ``cutting`` [s] of feed motion; ``elapsed`` [s] the
    cutting time since the last dwell."""

    dwell: float
    cutting: float
    elapsed: float = 0.0


def split_at_times(segment: Line | Arc, feed: float, state: FeedDwell) -> list[tuple[Line | Arc, bool]]:
    """The pieces of the feed move ``segment`` at ``feed`` [mm/s], each with True where a dwell follows it;
    ``state.elapsed`` is carried on. An arc of more than one turn is not split: a dwell due in it runs at
    its end."""
    out: list[tuple[Line | Arc, bool]] = []
    length = segment.length
    done = 0.0  # [mm] of the segment behind
    while True:
        due = (state.cutting - state.elapsed) * feed  # [mm] to the next dwell
        if done + due >= length - 1e-9:
            state.elapsed += (length - done) / feed
            out.append((_piece(segment, done, length), False))
            return out
        if isinstance(segment, Arc) and abs(segment.sweep) > 2.0 * math.pi + 1e-12:
            state.elapsed = 0.0
            out.append((segment, True))
            return out
        cut = done + due
        out.append((_piece(segment, done, cut), True))
        state.elapsed = 0.0
        done = cut


def _piece(segment: Line | Arc, s0: float, s1: float) -> Line | Arc:
    """The part of ``segment`` between the arc lengths ``s0`` and ``s1`` [mm]."""
    if s0 == 0.0 and s1 >= segment.length - 1e-9:
        return segment
    a = np.asarray(segment.point_at(s0), dtype=float).reshape(3) if s0 > 0 else np.array(segment.start)
    b = np.asarray(segment.point_at(s1), dtype=float).reshape(3) if s1 < segment.length - 1e-9 \
        else np.array(segment.end)
    return piece_of(segment, a, b)
