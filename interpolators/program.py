"""A parsed part program: the executable blocks, dialect independent."""

from __future__ import annotations

import dataclasses

import numpy as np

from toolpaths.geometry import AXIS_LETTERS, Arc, Line, Path
from vcnc.core.axes import AXIS_NAMES, EXTRA_NAMES
from vcnc.core.errors import InputError

__all__ = ["Block", "Message", "Program", "BLOCK_KINDS", "MESSAGE_KINDS", "end_at_rest", "program_axes"]

#: Kinds of executable blocks.
BLOCK_KINDS: tuple[str, ...] = ("rapid", "line", "arc", "dwell")
#: Kinds of messages a program gives as it runs (LinuxCNC active comments, :mod:`interpolators.iso_messages`).
MESSAGE_KINDS: tuple[str, ...] = ("msg", "debug", "print", "log")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Message:
    """A message the program gives where the run reaches it: a LinuxCNC ``(MSG, text)`` operator
    message, a ``(DEBUG, text)`` (shown to the operator as MSG is), a ``(PRINT, text)`` (written to the
    console) or a ``(LOG, text)`` (a line of the log file ``(LOGOPEN, file)`` names; vcnc writes no file).

    Attributes
    ----------
    line : int
        1-based line of the comment in its file.
    kind : str
        One of :data:`MESSAGE_KINDS`.
    text : str
        The text as the control shows it: after the comma, as written for MSG; for DEBUG, PRINT and
        LOG with its parameters replaced by their values at that point of the run.
    file : str or None
        The file of the line (a subroutine file may differ from ``Program.source``).
    """

    line: int
    kind: str
    text: str
    file: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in MESSAGE_KINDS:
            raise InputError(f"message kind must be one of {', '.join(MESSAGE_KINDS)}, got {self.kind!r}")


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False, slots=True)
class Block:
    """One executable block (a motion or a dwell).

    Attributes
    ----------
    line : int
        1-based line of the block in the source text.
    number : int or None
        Block number as written (``N`` word or Heidenhain block number), if any.
    text : str
        The source line (stripped).
    kind : str
        ``"rapid"`` (G00 / FMAX: a straight line at the machine's rapid rate), ``"line"`` (G01 / L),
        ``"arc"`` (G02 / G03 / C / CR, possibly helical) or ``"dwell"`` (G04).
    start, target : ndarray, shape (3,)
        Position before and after the block, ``(x, y, z)`` [mm]. Read-only: a block's ``start`` may be the
        very array of the previous block's ``target`` and of its segment's end points (see :meth:`plain`).
    feed : float
        Programmed path feed [mm/s]; ``inf`` for rapids (the machine's rapid rate applies) and
        ``0`` for dwells. On a move with X, Y, Z still (see :attr:`extra_length`) it is the feed
        along the U V W distance [mm/s], or with U, V, W still too the angular feed [deg/s] along
        the rotary distance.
    segment : Line or Arc or None
        Exact geometry of the motion (``None`` for a dwell).
    dwell : float
        Dwell time [s] (0 for motions).
    exact_stop : bool
        True if the block ends at rest (G61, the default); False for continuous path (G64),
        where the look-ahead may pass the block end at speed.
    tolerance : float or None
        Path tolerance of G64 ``P`` [mm]; ``None`` selects ``interpolators.DEFAULT_TOLERANCE``.
    extra_start, extra_target : ndarray, shape (6,), or None
        Positions of the axes beyond X, Y, Z (``vcnc.core.axes.EXTRA_NAMES``: the rotary axes
        ``a, b, c`` [deg], then the secondary linear axes ``u, v, w`` [mm]) before and after the
        block; ``None`` in a program that moves none of them. They move in proportion to the path
        (RS274/NGC 3, Sec. 2.1.2.5: with X, Y or Z moving, the feed applies to the XYZ path). Read-only.
    tcp : bool
        A chord of a move under tool centre point control (G43.4/G43.5/G234, M128 / FUNCTION TCPM) that turns a
        rotary axis: its X, Y, Z follow the tool tip through the rotary axes, within the path tolerance already, so
        the look-ahead never merges such chords (a fit of the rotary axes apart from X, Y, Z would move the tip by
        the pivot distance times the angle's error).

    Notes
    -----
    A block holds its fields in slots, not in a ``__dict__`` (a CAM program has millions of blocks); the arrays
    given are made read-only in place, not copied, so that blocks, their segments and the readers' positions may
    share them.
    """

    line: int
    number: int | None = None
    text: str = ""
    kind: str
    start: np.ndarray
    target: np.ndarray
    feed: float
    segment: Line | Arc | None = None
    dwell: float = 0.0
    exact_stop: bool = True
    tolerance: float | None = None
    extra_start: np.ndarray | None = None
    extra_target: np.ndarray | None = None
    tcp: bool = False

    def __post_init__(self) -> None:
        for arr in (self.start, self.target, self.extra_start, self.extra_target):
            if isinstance(arr, np.ndarray):
                arr.setflags(write=False)

    @classmethod
    def plain(cls, *, line: int, number: int | None, text: str, kind: str, start: np.ndarray, target: np.ndarray,
              feed: float, segment: Line | Arc, exact_stop: bool, tolerance: float | None,
              extra_start: np.ndarray | None = None, extra_target: np.ndarray | None = None) -> Block:
        """A motion block: the same as ``Block(...)`` with these fields, made without the frozen dataclass's
        ``__init__`` (the readers make one per line, :mod:`interpolators.iso_fast`,
        :mod:`interpolators.heidenhain_fast`). ``start``, ``target`` and the extra axes' ``extra_start`` and
        ``extra_target`` (None: a block without them) must be read-only already: they are kept as given (a reader
        passes the previous block's target as the start)."""
        blk = object.__new__(cls)
        _set_line(blk, line)
        _set_number(blk, number)
        _set_text(blk, text)
        _set_kind(blk, kind)
        _set_start(blk, start)
        _set_target(blk, target)
        _set_feed(blk, feed)
        _set_segment(blk, segment)
        _set_dwell(blk, 0.0)
        _set_exact_stop(blk, exact_stop)
        _set_tolerance(blk, tolerance)
        _set_extra_start(blk, extra_start)
        _set_extra_target(blk, extra_target)
        _set_tcp(blk, False)
        return blk

    @property
    def length(self) -> float:
        """Path length of the block [mm] (0 for a dwell)."""
        return 0.0 if self.segment is None else self.segment.length

    @property
    def extra_delta(self) -> np.ndarray:
        """Motion ``(da, db, dc, du, dv, dw)`` of the axes beyond X, Y, Z [deg, mm] (zeros without them)."""
        if self.extra_start is None or self.extra_target is None:
            return np.zeros(len(EXTRA_NAMES))
        return np.asarray(self.extra_target, dtype=float) - np.asarray(self.extra_start, dtype=float)

    @property
    def extra_length(self) -> float:
        """The path of a move with X, Y, Z still: the U V W distance ``sqrt(du^2 + dv^2 + dw^2)``
        [mm] when U, V or W moves, else the rotary distance ``sqrt(da^2 + db^2 + dc^2)`` [deg]
        (RS274/NGC 3, Sec. 2.1.2.5; LinuxCNC ``emccanon.cc`` ``getStraightVelocity``: the distance
        of a move is along XYZ if they move, else along UVW, else along ABC)."""
        d = self.extra_delta
        secondary = float(np.linalg.norm(d[3:]))
        return secondary if secondary > 0 else float(np.linalg.norm(d[:3]))


# the slots' own setters: what the frozen dataclass's __init__ does, without its per-field object.__setattr__
(_set_line, _set_number, _set_text, _set_kind, _set_start, _set_target, _set_feed, _set_segment, _set_dwell,
 _set_exact_stop, _set_tolerance, _set_extra_start, _set_extra_target, _set_tcp) = (
    vars(Block)[f.name].__set__ for f in dataclasses.fields(Block))


def end_at_rest(blocks: list[Block]) -> None:
    """The machine comes to rest at the end of the last block so far, whatever the path mode: a program stop
    or a tool change halts the path there, and the look-ahead may not blend through it.

    The program stops: LinuxCNC M-codes "M0, M1 Program Pause" and "M60 Pallet Change Pause" (the program
    pauses; the motion has come to an end), Fanuc 0i-MD B-64304EN "Miscellaneous function": M00 "Program stop:
    automatic operation is stopped after a block containing M00 is executed"; HEIDENHAIN TNC 640 user's manual,
    "STOP": "the program run or programming test is interrupted". A tool change (M6, TOOL CALL n) is made with
    the axes at rest (our reading: the changer takes the tool from a spindle that has stopped moving along the
    path).
    """
    if blocks and not blocks[-1].exact_stop:
        blocks[-1] = dataclasses.replace(blocks[-1], exact_stop=True)


def program_axes(used: set[int], blocks: list[Block]) -> tuple[str, ...]:
    """The axes a program uses, canonical order (``vcnc.core.axes.AXIS_NAMES``): those its words wrote (``used``,
    indices into ``AXIS_NAMES``) and any of X, Y, Z that a block moves all the same. A reader adds an axis where a
    word writes it; a move the reader makes itself (a cycle's pattern points, a probing cycle's approach) could
    leave one out, and a simulation of the program would then drop that axis' motion without a word (a Heidenhain
    CYCL CALL PAT drilled at its X Y points on a Z-only machine). A full circle ends where it starts: its plane's
    axes count by its segment. Only the linear axes not already named are looked for, so a program that names X, Y
    and Z costs nothing."""
    moved = set(used)
    for i in range(3):
        if i not in moved and any(b.target[i] != b.start[i] or isinstance(b.segment, Arc) and i in b.segment.plane_axes
                                  for b in blocks):
            moved.add(i)
    return tuple(a for i, a in enumerate(AXIS_NAMES) if i in moved)


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class Program:
    """A parsed program.

    Attributes
    ----------
    blocks : tuple of Block
        Executable blocks in order (non-motion lines such as comments, ``BLK FORM`` or ``M03``
        do not appear). Sample ``block`` indices of :class:`vcnc.Setpoints` index this tuple.
    source : str or None
        File name (or label) the text came from.
    dialect : str
        ``"iso"`` or ``"heidenhain"``.
    axes : tuple of str
        Axes the program uses (written in an axis word or moved by an arc), canonical order
        (``vcnc.core.axes.AXIS_NAMES``: x, y, z, the rotary axes a, b, c, then u, v, w).
    name : str or None
        Program name (Heidenhain ``BEGIN PGM`` name or ISO ``O`` number), if given.
    notes : tuple of str
        What the reader accepted without motion or assumed, one line per kind with its count
        (``"T/M6 tool change x3"``, ``"no G20/G21: mm assumed (linuxcnc default)"``).
    messages : tuple of Message
        The messages of the run in the order it gives them (a message in a loop once per pass):
        LinuxCNC's active comments under the ``linuxcnc`` dialect; none under the others, where a
        comment is a comment.
    rapid_feed_stop : bool
        Whether the control that reads it stops where a rapid meets a feed move, either way, whatever the path
        mode (:attr:`interpolators.context.Dialect.rapid_feed_stop`, which the readers copy here): True on
        LinuxCNC (the default dialect), Fanuc, Haas and Fadal; False on grbl and the TNC, whose look-ahead
        passes that junction at speed.
    """

    blocks: tuple[Block, ...]
    source: str | None = None
    dialect: str = "iso"
    axes: tuple[str, ...] = ()
    name: str | None = None
    notes: tuple[str, ...] = ()
    messages: tuple[Message, ...] = ()
    rapid_feed_stop: bool = True

    def __len__(self) -> int:
        return len(self.blocks)

    @property
    def end_position(self) -> np.ndarray:
        """Position after the last block [mm] (the origin for an empty program)."""
        return self.blocks[-1].target.copy() if self.blocks else np.zeros(3)

    def path(self) -> Path:
        """The programmed geometry: one segment per motion block of non-zero length (the linear
        axes x, y, z; the other axes' positions are in the blocks)."""
        segs, idx = [], []
        for i, b in enumerate(self.blocks):
            if b.segment is not None and b.segment.length > 0:
                segs.append(b.segment)
                idx.append(i)
        linear = tuple(a for a in self.axes if a in AXIS_LETTERS)
        return Path(segments=tuple(segs), blocks=tuple(idx), axes=linear or AXIS_LETTERS)
