"""What the compact blocks rely on (:class:`interpolators.program.Block`): slots, no ``__dict__``, frozen fields,
read-only arrays, and the readers' plain moves sharing one array between a block's target, its segment's end and
the next line's start (values equal to the positions written)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from interpolators import parse_program
from interpolators.program import Block
from toolpaths.geometry import Line

ISO = "G21 G90 G64 P0.01\nG0 X0 Y0 Z5\nG1 Z-1 F600\nX10 Y0\nX10 Y5 Z-1.5\nG2 X20 Y5 I5 J0\nG1 X20 Y0\nG0 Z5\nM30\n"

TNC = ("0 BEGIN PGM P MM\n1 TOOL CALL 1 Z S1000\n2 L X+0 Y+0 Z+5 R0 FMAX\n3 L Z-1 F600\n4 L X+10\n"
       "5 L Y+5 Z-1.5\n6 CC X+15 Y+5\n7 C X+20 Y+5 DR-\n8 L X+20 Y+0\n9 END PGM P MM\n")


def test_block_has_slots_and_stays_frozen():
    blk = Block(line=3, kind="line", start=np.zeros(3), target=np.array([1.0, 2.0, 3.0]), feed=10.0,
                segment=Line([0, 0, 0], [1, 2, 3]))
    assert not hasattr(blk, "__dict__")
    with pytest.raises(dataclasses.FrozenInstanceError):
        blk.feed = 20.0
    moved = dataclasses.replace(blk, target=np.array([4.0, 5.0, 6.0]))
    assert moved.target.tolist() == [4.0, 5.0, 6.0] and moved.start is blk.start and moved.feed == 10.0


def test_block_arrays_are_read_only():
    start, target = np.zeros(3), np.array([1.0, 2.0, 3.0])
    extra = np.zeros(6)
    blk = Block(line=1, kind="line", start=start, target=target, feed=10.0, segment=Line(start, target),
                extra_start=extra, extra_target=np.ones(6))
    for arr in (blk.start, blk.target, blk.extra_start, blk.extra_target):
        assert not arr.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            arr[0] = 7.0
    assert blk.start is start and blk.target.tolist() == [1.0, 2.0, 3.0]


def test_plain_is_the_block_init_makes():
    start, target = np.zeros(3), np.array([1.0, 0.0, 0.0])
    start.setflags(write=False)
    target.setflags(write=False)
    seg = Line.from_points(start, target)
    fields = dict(line=4, number=40, text="N40 X1", kind="line", start=start, target=target, feed=5.0, segment=seg,
                  exact_stop=False, tolerance=0.01)
    plain, init = Block.plain(**fields), Block(**fields)
    for f in dataclasses.fields(Block):
        assert getattr(plain, f.name) is getattr(init, f.name), f.name
    assert plain.dwell == 0.0 and plain.extra_start is None and plain.length == 1.0


def test_line_from_points_shares_read_only_points_and_copies_writeable_ones():
    a, b = np.zeros(3), np.array([3.0, 4.0, 0.0])
    copied = Line.from_points(a, b)
    assert copied.start is not a and copied.end is not b and copied.length == 5.0
    assert not copied.start.flags.writeable and a.flags.writeable
    a.setflags(write=False)
    b.setflags(write=False)
    shared = Line.from_points(a, b)
    assert shared.start is a and shared.end is b and shared.direction.tolist() == [0.6, 0.8, 0.0]


@pytest.mark.parametrize("text", [ISO, TNC], ids=["iso", "heidenhain"])
def test_plain_moves_share_the_position_arrays(text):
    blocks = parse_program(text).blocks
    assert [b.kind for b in blocks] == ["rapid", "line", "line", "line", "arc", "line", *(["rapid"] if text == ISO
                                                                                           else [])]
    assert blocks[3].target.tolist() == [10.0, 5.0, -1.5] and blocks[4].target.tolist() == [20.0, 5.0, -1.5]
    for prev, blk in zip(blocks, blocks[1:]):  # an arc keeps its own copy of its start point
        assert blk.start is prev.target if blk.kind != "arc" else np.array_equal(blk.start, prev.target)
    for blk in blocks:
        assert blk.segment.start is blk.start and blk.segment.end is blk.target
        assert not blk.start.flags.writeable and not blk.target.flags.writeable
