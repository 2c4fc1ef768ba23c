"""The ISO reader's shortcut for plain moves: the bulk of a CAM program, run without the general machinery.

Most lines of a CAM program are ``[N..] [G0|G1|G2|G3] [G93|G94] X.. Y.. Z.. [A.. B.. C.. U.. V.. W..] [I.. J.. K..|R..]
[F..]``: a move in the modal state a post processor leaves alone for thousands of lines. :class:`PlainMoves` runs such a
block itself and appends the same :class:`interpolators.program.Block` the general executor
(:mod:`interpolators.iso`, ``_execute``) makes of it -- the same kind, end points, centre, feed, line, number and
text, the extra axes' start and end positions, bit for bit, and the same modal state after it -- and declines
everything else, which then goes the general way.

The words of the axes beyond X Y Z the machine has (``MachineContext.extra_axes``) are taken as
:mod:`interpolators.iso_axes` reads them (LinuxCNC G-code overview, "Feed Rate"; RS274/NGC 3, Sec. 2.1.2.5): A B C
in degrees whatever G20/G21, U V W in program units; absolute to the work plus G92 offset of the axis under G90,
increments under G91; on G0/G1 with or without X Y Z, and on an arc that has an X Y Z word (the axes then move in
proportion). A move of the extra axes alone runs at the F along their own distance, in deg/min along A B C or
along U V W (:func:`interpolators.iso_motion.move_feed`, the general path's rule).

Under G93 inverse time (LinuxCNC G-code reference, "G93, G94, G95: Feed Rate Mode": "the move should be completed in
[one divided by the F number] minutes"; rs274ngc interp_inverse.cc sets the rate to the block's length times F) a feed
move takes its time from the F word of its own block, through the same :func:`interpolators.iso_motion.move_feed`; the
F does not become the modal feed, and a G0 ignores it. A G93 or G94 word on the move's line is taken as the general
path's ``_modes`` takes it (LinuxCNC interp_convert.cc ``convert_feed_mode``): G94 after G93 clears the modal feed,
and on LinuxCNC every G94 does (:attr:`interpolators.context.Dialect.feed_mode_clears_feed`), so the next feed move
needs an F. A feed move without an F under G93 (rs274ngc: "F word missing with inverse time
g1 move" / "arc move"; Haas: "each non-rapid motion block must have its own feedrate"), F0 and two feed-mode words
go the general way, which words the error.

An arc by its radius R (LinuxCNC G-code reference, "Radius Format Arc": R > 0 at most a half circle, R < 0 more; the
Fanuc and Haas manuals alike) is made by the general path's :func:`interpolators.arcs.arc_from_radius` with its
dialect's tolerance (:func:`interpolators.arcs.radius_arc_tolerance`), R scaled by G20, and keeps no programmed
centre; R beside I J K, on a G0/G1, a full circle by R, an R shorter than half the chord, and under Fanuc an R
without a decimal point go the general way.

It declines (returns False, having changed nothing) a block with any other word (M, S, T, P, R, H, D, E, a word of an
axis the machine lacks -- the general path's note for ``A0``, its error otherwise --, of an axis that wraps at
360 deg (``MachineContext.wrapped_axes``, :func:`interpolators.iso_axes.wrapped_target`), a Fanuc ``,R``/``,C`` ...), a
repeated letter, a G code other than G0-G3, G93 and G94 (by its exact value), a centre word on a G0/G1 or on the plane
normal of an arc, an arc without an X Y Z word, an F <= 0, no axis word, a feed move without a feed, an arc whose
centre is not on the circle (the general path then words the error), under grbl an arc without an end-point word in its
plane, and under Fanuc an axis or centre word written without a decimal point (:mod:`interpolators.iso_decimal`); and
every block in a modal state it does not model: no motion mode, a motion other than G0-G3 (a canned cycle, G5, G33),
axis words after G80 with no motion code (a note), G95 feed per revolution, Fanuc G16 polar coordinates, a rotated
system (G10 L2 R, G68), a tilted working plane (G68.2), G51 scaling and G51.1 mirroring, tool centre point control
(G43.4, G43.5, Haas G234: the rotary words then move the tool tip on the part, :mod:`interpolators.iso_tcp`), cutter
compensation (on, or its exit move pending), a Fanuc ``,R``/``,C`` corner pending, a Fanuc/Haas/Fadal tool length
change not yet travelled (:func:`interpolators.iso_offsets.length_travel`). Units (G20/G21), G90/G91,
G90.1/G91.1, the plane, the work and G92 offsets (of the extra axes too), the tool length, the G61/G64 path mode and
G93/G94 are modelled as the general path has set them.

The state is looked at once after each block the general path ran, and after each write of a work offset or
tool entry by a Fanuc/Haas system variable (``#5221 = ..``, which may share its line with a move)
(:meth:`PlainMoves.reset`): plain moves change none of what the checks read, nor the offsets, which are
cached until then.
"""

from __future__ import annotations

import math

import numpy as np

from interpolators._words import INCH
from interpolators.arcs import (
    ArcWordError,
    arc_from_center,
    arc_from_radius,
    center_arc_tolerance,
    radius_arc_tolerance,
)
from interpolators.iso_axes import EXTRA_LETTERS
from interpolators.iso_grbl import MAX_LINE_NUMBER
from interpolators.iso_motion import move_feed
from interpolators.program import Block
from toolpaths.geometry import PLANE_AXES, Line

__all__ = ["PlainMoves"]

#: G value -> round(10 * G) of the motion codes run here (exact values only: G1.0000001 goes the general way).
_MOTION = {0.0: 0, 1.0: 10, 2.0: 20, 3.0: 30}
#: G93 inverse time -> True, G94 units per minute -> False (exact values; G95 goes the general way).
_FEED_MODE = {93.0: True, 94.0: False}
_AXIS = {"X": 0, "Y": 1, "Z": 2}
_CENTRE = {"I": 0, "J": 1, "K": 2}
_INF = math.inf


class PlainMoves:
    """Runs plain G0-G3 moves on the reader's modal state ``st`` (the general executor's), appending to
    ``blocks`` and marking the axes moved in ``used``.

    Parameters
    ----------
    st
        The ISO reader's modal state.
    blocks : list of Block
        The program's blocks so far.
    used : set of int
        Indices of the axes the program uses.
    """

    def __init__(self, st, blocks: list[Block], used: set[int]) -> None:
        self.st = st
        self.blocks = blocks
        self.used = used
        self.ready: bool | None = None  # None: to be judged at the next block
        self.offset: list[float] = []
        self.extra_offset: list[float] = []
        # the words of the axes beyond X Y Z the machine has -> their column in State.extra; a word of another
        # (an error, or with value 0 a note) or of an axis that wraps at 360 deg (iso_axes.wrapped_target) goes the
        # general way
        extra_columns = {letter: i for i, letter in enumerate(EXTRA_LETTERS)
                         if letter.lower() in st.context.extra_axes and letter.lower() not in st.context.wrapped_axes}
        # a coordinate word -> (which of the block's axes, centre, extra words, its column): one rule for all three
        self.slots = {**{a: (0, i) for a, i in _AXIS.items()}, **{c: (1, i) for c, i in _CENTRE.items()},
                      **{e: (2, i) for e, i in extra_columns.items()}}
        self.fanuc = st.context.dialect.name == "fanuc"
        self.grbl = st.context.dialect.arc_rule == "grbl"
        self.g94_clears = st.context.dialect.feed_mode_clears_feed
        self.fanuc_feed = st.context.dialect.fanuc_feed  # F along a helix's arc, over every axis of a line

    def reset(self) -> None:
        """The general path ran a block: judge the state again before the next plain move."""
        self.ready = None

    def _judge(self) -> bool:
        st = self.st
        self.ready = (not st.per_rev and not st.fanuc_polar and st.frame is None
                      and not st.rotation and st.comp_side is None and st.comp_start is None
                      and st.comp_close_at is None and st.corner is None and st.corner_word is None and not st.tcp
                      and st.dwo is None and not st.length_pending)
        if self.ready:
            self.offset = st.offset().tolist()
            self.extra_offset = st.extra_offset().tolist()
        return self.ready

    def move(self, words: list, line: int, text: str) -> bool:
        """Run the block of ``words`` (line ``line``, source ``text``) if it is a plain move; False (nothing
        changed) if it is not."""
        if not (self.ready or self.ready is None and self._judge()):
            return False
        read = self._read(words)
        if read is None:
            return False
        motion, number, feed, axes, centre, extra, mode, radius = read
        st = self.st
        if not axes and (not extra or centre or radius is not None):
            return False
        if st.motion not in (None, 0, 10, 20, 30):
            return False
        if motion is None:
            if st.after_g80 or st.motion is None:
                return False
            motion = st.motion
        # the feed mode after the block's G93/G94 (LinuxCNC convert_feed_mode; iso._modes): G94 after G93 clears the
        # modal feed, G93 keeps it; under G93 a feed move takes its time from its own F
        inverse = st.inverse_time if mode is None else mode
        # LinuxCNC clears it on every G94 (Dialect.feed_mode_clears_feed), G94 already active or not
        cleared = mode is False and (st.inverse_time or self.g94_clears and st.feed is not None)
        scale = INCH if st.inch else 1.0
        pos = st.pos
        target = pos.copy()
        if st.incremental:
            for i, v in axes.items():
                target[i] = pos[i] + v * scale
        else:
            off = self.offset
            for i, v in axes.items():
                target[i] = v * scale + off[i]
        new_feed = None if feed is None else feed * scale / 60.0
        path_feed = (None if cleared else st.feed) if feed is None else new_feed
        if motion == 0:
            if centre or radius is not None:
                return False
            path_feed = _INF
        elif inverse:
            if feed is None:  # the general path words the error (an F on every G1/G2/G3 block under G93)
                return False
        elif path_feed is None:
            return False
        elif motion == 10 and (centre or radius is not None):
            return False
        if motion <= 10:
            target.setflags(write=False)
            seg = Line.from_points(pos, target)
        else:
            seg = self._arc(motion, axes, centre, target, scale) if radius is None else \
                self._radius_arc(motion, axes, centre, target, radius * scale)
            if seg is None:
                return False
            target = seg.end
        # committed: the modal state as the general path leaves it
        if mode is not None:
            if cleared:
                st.feed = st.feed_rotary = st.feed_per_rev = st.feed_per_rev_word = None
                st.feed_reset = True
            st.inverse_time = mode
            if not mode:
                st.inverse_rate = None
        if feed is not None:
            st.feed_zero = False
            if not inverse:
                st.feed, st.feed_rotary = new_feed, feed / 60.0
        st.block_f = feed
        if extra:
            extra_start, extra_target = self._extra(extra, scale)
        else:
            extra_start = extra_target = None
        if motion != 0 and (inverse or extra and seg.length == 0 or self.fanuc_feed and (extra or motion >= 20)):
            # G93: the block's length over its 1/F minutes; the extra axes alone: the F along their own distance;
            # Fanuc: F along a helix's arc in the plane, over every axis of a line (iso_motion.fanuc_feed_share)
            path_feed = move_feed(st, seg, None if extra_start is None else extra_target - extra_start)
        st.motion = motion
        st.after_g80 = False
        st.spline_pq = None
        self.used.update(axes)
        if motion >= 20:
            st.arc_center = self.centre
            self.used.update(PLANE_AXES[st.plane])
        if number is not None:
            number = int(number.value) if number.value == int(number.value) else None
        self.blocks.append(Block.plain(line=line, number=number, text=text, kind=_KIND[motion], start=seg.start,
                                       target=target, feed=path_feed, segment=seg, exact_stop=st.exact_stop,
                                       tolerance=st.tolerance, extra_start=extra_start, extra_target=extra_target))
        st.pos = target  # read-only: the next block's start, shared (interpolators.program.Block)
        if extra:
            st.extra = extra_target
        st.stopped = False  # a move since a program stop: positions read are the program's again
        return True

    def _read(self, words: list) -> tuple | None:  # noqa: C901 - one pass over the words
        """``(motion, N word, F, axes, centre, extra, feed mode, R)`` of a block's words (axis, centre and
        extra-axis column -> value; the feed mode True for a G93 word, False for G94, None without), or None for a
        word or repeat the shortcut does not take."""
        motion = number = feed = mode = radius = None
        axes: dict[int, float] = {}
        centre: dict[int, float] = {}
        extra: dict[int, float] = {}
        found = (axes, centre, extra)
        slots = self.slots
        fanuc = self.fanuc
        for w in words:
            letter = w.letter
            slot = slots.get(letter)
            if slot is not None:  # X Y Z, I J K, or an extra axis the machine has: once, Fanuc's with its point
                coordinates, i = found[slot[0]], slot[1]
                if i in coordinates or fanuc and "." not in w.text:
                    return None
                coordinates[i] = w.value
            elif letter == "G":
                if w.value in _MOTION and motion is None:
                    motion = _MOTION[w.value]
                elif w.value in _FEED_MODE and mode is None:
                    mode = _FEED_MODE[w.value]
                else:
                    return None
            elif letter == "N":
                if number is not None or not 0 <= w.value <= MAX_LINE_NUMBER:  # iso refuses N < 0, grbl more
                    return None
                number = w
            elif letter == "F":
                if feed is not None or not w.value > 0:
                    return None
                feed = w.value
            elif letter == "R":
                if radius is not None or fanuc and "." not in w.text:
                    return None
                radius = w.value
            else:
                return None
        return motion, number, feed, axes, centre, extra, mode, radius

    def _extra(self, words: dict[int, float], scale: float) -> tuple[np.ndarray, np.ndarray]:
        """The start and end positions ``(a, b, c, u, v, w)`` [deg, mm] of a move with the extra axis words
        ``words`` (column -> value), read-only, as :func:`interpolators.iso_axes.extra_target` makes them: A B C in
        degrees whatever G20/G21, U V W times ``scale``; added to the position under G91, to the work plus G92
        offset under G90. Marks the axes used."""
        st = self.st
        start = st.extra
        if start.flags.writeable:  # the previous block's end is read-only already; another is copied
            start = start.copy()
            start.setflags(write=False)
        end = start.copy()
        off = self.extra_offset
        for i, v in words.items():
            if i >= 3:  # U V W [program units]
                v = v * scale
            end[i] = end[i] + v if st.incremental else v + off[i]
        end.setflags(write=False)
        st.extra_used = True
        self.used.update(3 + i for i in words)
        return start, end

    def _arc(self, motion: int, axes: dict[int, float], centre: dict[int, float], target: np.ndarray,
             scale: float):
        """The arc as the general path makes it, or None where that path would note or refuse something."""
        st = self.st
        p, q = PLANE_AXES[st.plane]
        if st.plane in centre or not centre or self.grbl and p not in axes and q not in axes:
            return None
        pos = st.pos
        center = pos.copy()
        base = pos if st.arc_incremental else self.offset
        for i, v in centre.items():
            center[i] = base[i] + v * scale
        try:
            arc = arc_from_center(pos, target, center, ccw=motion == 30, plane=st.plane,
                                  tolerance=center_arc_tolerance(pos, target, center, plane=st.plane, inch=st.inch,
                                                                 rule=st.context.dialect.arc_rule))
        except ArcWordError:
            return None
        self.centre = center
        return arc

    def _radius_arc(self, motion: int, axes: dict[int, float], centre: dict[int, float], target: np.ndarray,
                    radius: float):
        """The arc of radius ``radius`` [mm] (negative: more than a half circle) as the general path makes it
        (:func:`interpolators.iso_arcs.read_arc`), or None where that path would refuse it (I/J/K beside R, a full
        circle, R too short for the chord, grbl's arc without an end-point word in its plane)."""
        st = self.st
        p, q = PLANE_AXES[st.plane]
        if centre or self.grbl and p not in axes and q not in axes:
            return None
        try:
            arc = arc_from_radius(st.pos, target, radius, ccw=motion == 30, plane=st.plane,
                                  tolerance=radius_arc_tolerance(st.context.dialect.arc_rule))
        except ArcWordError:
            return None
        self.centre = None  # the general path keeps no programmed centre of an R arc
        return arc


_KIND = {0: "rapid", 10: "line", 20: "arc", 30: "arc"}
