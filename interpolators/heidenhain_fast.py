"""The Heidenhain reader's shortcut for plain path blocks: the bulk of a CAM program, run without the general machinery.

Most blocks of a TNC program written by a CAM post are ``L X+1.5 Y-2 Z+0.1 [R0] [F200|FMAX] [M..]``, ``CC X.. Y..``,
``C X.. Y.. DR+`` and ``CR X.. Y.. R+5 DR-``: plain numbers in the modal state a post leaves alone for thousands of
blocks. :class:`PlainBlocks` runs such a block itself and makes what the general reader
(:mod:`interpolators.heidenhain_motion`, ``motion_block``) makes of it -- the same
:class:`interpolators.program.Block` (kind,
end point, segment, feed, line, number and text, bit for bit), the same notes in the same order, and the same
machine state after it (position, feed, pole, arc sense, the axes used, the axes of the last ``L`` for a number
without an axis letter) -- and declines everything else, which then goes the general way.

It declines (returns False, having changed nothing) a block that is not one keyword ``L``, ``CC``, ``C`` or ``CR``
(upper case) followed by words of this form, each after a blank and written without blanks inside: ``X+1.5``, ``IY-2``
(an axis X Y Z, ``I`` for incremental, a plain decimal number), ``R0``, ``R+5`` (a radius), ``DR+``, ``DR-``,
``F200``, ``FMAX``, ``M3`` -- so every Q parameter, formula, ``RL``/``RR``, ``LN``, ``LP``/``CP``/``CT``,
``RND``/``CHF``, FK, ``APPR``/``DEP``, rotary and secondary axes, ``F AUTO``/``FU``/``FZ``, ``MB``, a word left empty,
a number without an axis letter, a blank inside a word, lower-case text; a word its block does not allow (``DR`` or
``R`` on a line, ``F``/``FMAX`` on ``CC``, ``FMAX`` on an arc), a word twice, ``F`` <= 0, a block without an axis
word, a move without a feed, an arc without a sense or without its ``CC``, an arc the general path would refuse (its
error is worded there), a non-finite end point; the M functions with a meaning (M0, M1, M2, M30: stop and end; M89,
M99: cycle calls; M91, M92: machine coordinates; M128, M129: TCPM; M94, M103, M112, M113, M118, M120, M124, M136,
M137, M138: the path and feed functions; M140: retract); under M128 (TCPM) an arc. And it declines every block in a
modal state it does not model: a coordinate transformation (cycles 8, 10, 11, 26), a tilted working plane (PLANE,
cycle 19), radius compensation RL/RR, an RND/CHF or an APPR waiting for the next element, an FK element waiting, M89's
modal cycle call, M136's feed per revolution, FUNCTION FEED DWELL, M103's plunging feed. Units (MM/INCH), the preset
and datum shift (cycles 7, 247), the tool axis and tool length, a pole in another plane (``CC`` with the tool axis),
the path mode (cycle 32) and M128 on positioned rotary axes (lines of the tool tip on the turned part,
:mod:`interpolators.heidenhain_tcpm`) are modelled as the general path has set them.

The state is judged once after each block the general path ran (:meth:`PlainBlocks.reset`): plain blocks change
none of what the judgement reads, nor the program zero, which is kept until then. The word forms follow the
general reader's (:mod:`interpolators.heidenhain_words`, which cites the TNC 640 / iTNC 530 user's manuals); the
M functions theirs (heidenhain_motion's ``_one_m``, ``_retract_and_call``).
"""

from __future__ import annotations

import math
import re
from typing import NamedTuple

import numpy as np

from interpolators.arcs import arc_from_center, arc_from_radius
from interpolators.heidenhain_paths import arc_end_tolerance
from interpolators.heidenhain_words import SourceBlock, ignored_m_note
from interpolators.iso_words import PLAIN_NUMBER
from interpolators.program import Block
from interpolators.tcp import machine_point, part_point
from toolpaths.geometry import PLANE_AXES, Line

__all__ = ["PlainBlocks", "PlainWords", "plain_words"]

#: A plain block: its keyword, then words each after blanks (the general reader's word forms, the numbers as
#: :data:`interpolators._words.NUMBER_RE` reads them with their sign, in the linear-time form of PLAIN_NUMBER).
_PLAIN_BLOCK = re.compile(r"(L|CC|CR|C)((?:[ \t]+(?:I?[XYZ]" + PLAIN_NUMBER + r"|R0|R" + PLAIN_NUMBER
                          + r"|DR[+-]|F" + PLAIN_NUMBER + r"|FMAX|M\d+))+)")
_AXIS = {"X": 0, "Y": 1, "Z": 2}
#: M functions the general path does more with than note them (see the module text).
_ACTIVE_M = frozenset({0, 1, 2, 30, 89, 91, 92, 94, 99, 103, 112, 113, 118, 120, 124, 128, 129, 136, 137, 138, 140})
#: M126 / M127, with a meaning on a machine whose rotary axes wrap at 360 deg (declined there, noted elsewhere).
_WRAP_M = frozenset({126, 127})
#: M functions the general path accepts without a note (spindle, coolant).
_QUIET_M = frozenset({3, 4, 5, 8, 9})


class PlainWords(NamedTuple):
    """The words of a plain block (:func:`plain_words`)."""

    keyword: str  #: "L", "CC", "C" or "CR"
    axes: dict[int, tuple[bool, float]]  #: axis index -> (incremental, value [program unit])
    m: tuple[int, ...]  #: the M functions, in their order
    feed: float | None  #: F [program unit/min], or None
    rapid: bool  #: FMAX
    radius: float | None  #: R of CR [program unit]
    ccw: bool | None  #: DR+ (True), DR- (False), or None


def plain_words(code: str) -> PlainWords | None:  # noqa: C901 - one pass over the words
    """The words of the block ``code`` (:attr:`interpolators.heidenhain_words.SourceBlock.code`) when it is a
    plain block whose words the general path would accept in any state (see the module text); None when not."""
    match = _PLAIN_BLOCK.fullmatch(code)
    if match is None:
        return None
    kw = match.group(1)
    axes: dict[int, tuple[bool, float]] = {}
    ms: list[int] = []
    feed = radius = sense = None
    rapid = r0 = False
    for w in match.group(2).split():
        c = w[0]
        if c in _AXIS or c == "I":
            i, v = (_AXIS[w[1]], (True, float(w[2:]))) if c == "I" else (_AXIS[c], (False, float(w[1:])))
            if i in axes:
                return None
            axes[i] = v
        elif c == "M":
            ms.append(int(w[1:10]))
        elif w == "FMAX" or c == "F":
            if rapid or feed is not None:
                return None
            if w == "FMAX":
                rapid = True
            else:
                feed = float(w[1:])
        elif w == "R0":
            if r0:
                return None
            r0 = True
        elif c == "R":
            if radius is not None:
                return None
            radius = float(w[1:])
        else:  # DR+ / DR-
            if sense is not None:
                return None
            sense = w[2] == "+"
    if (not axes or (feed is not None and not feed > 0) or not _ACTIVE_M.isdisjoint(ms)
            or (radius is not None) != (kw == "CR") or (sense is not None and kw in ("L", "CC"))
            or (rapid and kw != "L") or (kw == "CC" and (feed is not None or r0))):
        return None
    return PlainWords(kw, axes, tuple(ms), feed, rapid, radius, sense)


class PlainBlocks:
    """Runs plain ``L``/``CC``/``C``/``CR`` blocks on the Heidenhain reader's machine state ``m``.

    Parameters
    ----------
    m
        The reader's run-time state (``interpolators.heidenhain.Machine``): its blocks, notes and modal state.
    """

    def __init__(self, m) -> None:
        self.m = m
        self.ready: bool | None = None  # None: to be judged at the next plain block
        self.origin: list[float] = []

    def reset(self) -> None:
        """The general path ran a block: judge the state again before the next plain block."""
        self.ready = None

    def _judge(self) -> bool:
        m = self.m
        self.ready = (m.transform.identity and m.tilt is None and m.comp == "R0" and m.pending is None
                      and m.approach is None and not m.fk.waiting and not m.modal_call and not m.per_revolution
                      and m.feed_dwell is None and m.plunge is None)
        if self.ready:
            self.origin = m.origin().tolist()
        return self.ready

    def run(self, blk: SourceBlock) -> bool:
        """Run ``blk`` if it is a plain block; False (nothing changed) if it is not."""
        words = plain_words(blk.code)
        if words is None or not (self.ready or self.ready is None and self._judge()):
            return False
        if self.m.context.wrapped_axes and not _WRAP_M.isdisjoint(words.m):
            return False  # M126 / M127: the shorter-path switch of the machine's wrapping rotary axes
        if words.keyword == "CC":
            return self._pole(words)
        return self._move(words, blk)

    def _target(self, axes: dict[int, tuple[bool, float]], base: list[float]) -> list[float] | None:
        """The end point [mm] of the axis words from ``base`` (program zero: the judged origin), as the general
        path's ``program_target`` (heidenhain_targets); None when not finite."""
        scale = self.m.scale
        origin = self.origin
        target = list(base)
        for i, (incremental, v) in axes.items():
            v = v * scale
            target[i] = base[i] + v if incremental else origin[i] + v
        return target if all(map(math.isfinite, target)) else None

    def _pole(self, words: PlainWords) -> bool:
        """``CC``: the pole, in the working plane or (with the tool axis and one other) in the plane of its axes."""
        m = self.m
        axes = words.axes
        target = self._target(axes, m.pos.tolist())
        p, q = PLANE_AXES[m.plane]
        off = [i for i in axes if i not in (p, q)]
        if target is None or off and len(axes) != 2:
            return False
        self._notes(words.m)
        m.pole = np.array(target)
        m.pole_plane = 3 - sum(axes) if off else None
        m.used.update(axes)
        return True

    def _move(self, words: PlainWords, blk: SourceBlock) -> bool:  # noqa: C901
        """``L``, ``C``, ``CR``: the block the general path's ``motion_block`` makes, or False where it would do
        more."""
        m = self.m
        kw, axes, feed, rapid = words.keyword, words.axes, words.feed, words.rapid
        pos = m.pos
        tcpm = m.tcpm
        if tcpm and (kw != "L" or m.plane != 2):  # under M128 a line in tool axis Z only (motion's _tcpm_target)
            return False
        kin = m.context.kinematics
        base = part_point(kin, m.extra, pos, m.tool_length).tolist() if tcpm else pos.tolist()
        target = self._target(axes, base)
        if target is None:
            return False
        end = np.array(target)
        if tcpm:
            end = machine_point(kin, m.extra, end, m.tool_length)
            if not all(map(math.isfinite, end.tolist())):
                return False
        new_feed = None if feed is None else feed * m.feed_scale
        path_feed = m.feed if feed is None else new_feed
        if kw == "L":
            if rapid:
                path_feed = math.inf
            elif path_feed is None:
                return False
            end.setflags(write=False)
            kind, seg = "rapid" if rapid else "line", Line.from_points(pos, end)
        else:
            ccw = m.ccw if words.ccw is None else words.ccw
            if path_feed is None or ccw is None:
                return False
            seg = self._arc(kw, end, words.radius, ccw)
            if seg is None:
                return False
            kind, end = "arc", seg.end
        # committed: the state as the general path leaves it
        self._notes(words.m)
        if feed is not None:
            m.feed = new_feed
        m.used.update(axes)
        if kw == "L":
            m.last_axes = sorted(axes)
        else:
            m.ccw = ccw
            m.used.update(PLANE_AXES[seg.plane])
        m.blocks.append(Block.plain(line=blk.line, number=blk.number, text=blk.text, kind=kind, start=seg.start,
                                    target=end, feed=path_feed, segment=seg, exact_stop=m.exact_stop,
                                    tolerance=m.tolerance))
        m.pos = end  # read-only: the next block's start, shared (interpolators.program.Block)
        m.last_rapid = rapid
        m.stopped_at = None  # a move since a program stop
        return True

    def _arc(self, kw: str, end: np.ndarray, radius: float | None, ccw: bool):
        """The arc of a ``C`` (about the pole, in its plane) or ``CR`` block as the general path's ``_arc`` makes
        it, or None where that path would refuse it."""
        m = self.m
        try:
            if kw == "C":
                if m.pole is None:
                    return None
                plane = m.plane if m.pole_plane is None else m.pole_plane
                return arc_from_center(m.pos, end, m.pole, ccw=ccw, plane=plane, tolerance=arc_end_tolerance(m.inch))
            return arc_from_radius(m.pos, end, radius * m.scale, ccw=ccw, plane=m.plane)
        except Exception:  # noqa: BLE001 - the general path words the error
            return None

    def _notes(self, ms: tuple[int, ...]) -> None:
        """The notes of the block's M functions (none with a meaning here: spindle, coolant, and others ignored)."""
        for v in ms:
            if v not in _QUIET_M:
                self.m.note(ignored_m_note(v))
