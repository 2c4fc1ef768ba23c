"""A parsed part program: the executable blocks, dialect independent."""

from __future__ import annotations

import dataclasses

import numpy as np

from toolpaths.geometry import AXIS_LETTERS, Arc, Line, Path

__all__ = ["Block", "Program", "BLOCK_KINDS"]

#: Kinds of executable blocks.
BLOCK_KINDS: tuple[str, ...] = ("rapid", "line", "arc", "dwell")


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
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
        Position before and after the block, ``(x, y, z)`` [mm].
    feed : float
        Programmed path feed [mm/s]; ``inf`` for rapids (the machine's rapid rate applies) and
        ``0`` for dwells. On a pure rotary move (X, Y, Z still, see :attr:`rotary_length`) it is
        the angular feed [deg/s] along the rotary distance.
    segment : Line or Arc or None
        Exact geometry of the motion (``None`` for a dwell).
    dwell : float
        Dwell time [s] (0 for motions).
    exact_stop : bool
        True if the block ends at rest (G61, the default); False for continuous path (G64),
        where the look-ahead may pass the block end at speed.
    tolerance : float or None
        Path tolerance of G64 ``P`` [mm]; ``None`` selects ``interpolators.DEFAULT_TOLERANCE``.
    rotary_start, rotary_target : ndarray, shape (3,), or None
        Rotary axis positions ``(a, b, c)`` [deg] before and after the block; ``None`` in a
        program that moves no rotary axis. The rotary axes move in proportion to the path
        (RS274/NGC 3, Sec. 2.1.2.5: with X, Y or Z moving, the feed applies to the XYZ path).
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
    rotary_start: np.ndarray | None = None
    rotary_target: np.ndarray | None = None

    @property
    def length(self) -> float:
        """Path length of the block [mm] (0 for a dwell)."""
        return 0.0 if self.segment is None else self.segment.length

    @property
    def rotary_delta(self) -> np.ndarray:
        """Rotary motion ``(da, db, dc)`` of the block [deg] (zeros without rotary axes)."""
        if self.rotary_start is None or self.rotary_target is None:
            return np.zeros(3)
        return np.asarray(self.rotary_target, dtype=float) - np.asarray(self.rotary_start, dtype=float)

    @property
    def rotary_length(self) -> float:
        """Rotary distance ``sqrt(da^2 + db^2 + dc^2)`` [deg]: the path of a pure rotary move, whose
        feed is in deg/min (RS274/NGC 3, Sec. 2.1.2.5, case C)."""
        return float(np.linalg.norm(self.rotary_delta))


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
        (``vcnc.core.axes.AXIS_NAMES``: x, y, z, then the rotary axes a, b, c).
    name : str or None
        Program name (Heidenhain ``BEGIN PGM`` name or ISO ``O`` number), if given.
    notes : tuple of str
        What the reader accepted without motion or assumed, one line per kind with its count
        (``"T/M6 tool change x3"``, ``"no G20/G21: mm assumed (linuxcnc default)"``).
    """

    blocks: tuple[Block, ...]
    source: str | None = None
    dialect: str = "iso"
    axes: tuple[str, ...] = ()
    name: str | None = None
    notes: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.blocks)

    @property
    def end_position(self) -> np.ndarray:
        """Position after the last block [mm] (the origin for an empty program)."""
        return self.blocks[-1].target.copy() if self.blocks else np.zeros(3)

    def path(self) -> Path:
        """The programmed geometry: one segment per motion block of non-zero length (the linear
        axes x, y, z; rotary positions are in the blocks)."""
        segs, idx = [], []
        for i, b in enumerate(self.blocks):
            if b.segment is not None and b.segment.length > 0:
                segs.append(b.segment)
                idx.append(i)
        linear = tuple(a for a in self.axes if a in AXIS_LETTERS)
        return Path(segments=tuple(segs), blocks=tuple(idx), axes=linear or AXIS_LETTERS)
