"""Fanuc ``G02.4`` / ``G03.4`` three-dimensional circular interpolation (``--dialect fanuc``).

An arc through three points in space: the start (the current position), an intermediate point (the block
with G02.4 or G03.4) and the end point (the next block). Sources: FANUC Series 30i/31i-MODEL B operator's
manual (B-64484EN), "Three-dimensional circular interpolation (G02.4, G03.4)" (an option), whose text was
not in our search index; Mitsubishi M700V series programming manual, 6.14 "3-dimensional Circular
Interpolation; G02.4, G03.4", which describes the same command: "an arc shape determined by the three points
(start point, intermediate point, end point) designated on the 3-dimensional space"; "G02.4(G03.4) Xx1 Yy1
Zz1 ; Intermediate point designation (1st block) / Xx2 Yy2 Zz2 ; End point designation (2nd block)"; "The
G02.4 and G03.4 operations are the same. (The rotation direction cannot be designated.)"; "The intermediate
point coordinates omitted in the 1st block become the start point coordinates, and the end point coordinates
omitted in the 2nd block become the intermediate point coordinates"; under incremental command the
intermediate point is relative to the start and the end point to the intermediate point; "When the start
point, intermediate point, and end point are on the same line" or two of them coincide, "liner interpolation
is applied", in the order start, intermediate, end; "a modal command belonging to 01 group ... When the
3-dimensional circular interpolation command is carried out continuously, the end point of present command is
the start point of next command"; "The speed command ... is the tangential speed on arc". Autodesk's Fusion
Fanuc post writes it for arcs outside the G17/G18/G19 planes with its "Allow 3D arcs" property
(elcf-robot/autodesk-fanuc ``fanuc.cps`` ``onCircular``: ``G02.4 X Y Z`` of the arc's middle, then
``X Y Z`` of its end).

vcnc runs the arc as chords within :data:`interpolators.iso_splines.SPLINE_TOLERANCE` of the circle, at the
block's feed (under G93 the pair of blocks takes the end block's 1/F minutes, our reading); the blocks carry the
end point block's line. Refused, each an error naming it: under a G68 rotation, G51 scaling, mirror image or
G10 R rotation, cutter compensation or tool centre point control, with A-W axis words (the manual's
"arbitrary axis"), an intermediate point whose end block never comes (another motion code or the program's
end), and any other block between the two (``G02.4 X Y Z`` / ``G04 X1.`` / ``X Y Z``, or an M code alone): the
manual's format is the two blocks in a row, "Intermediate point designation (1st block)", "End point designation
(2nd block)" (our reading: a block between them is neither; the Fanuc text was not found). A macro statement
between them (``#100 = 1``) is no NC block and is taken.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.iso_splines import SPLINE_TOLERANCE
from interpolators.program import Block
from toolpaths.geometry import Line

if TYPE_CHECKING:
    from interpolators.iso import State

__all__ = ["ARC3D_CODES", "arc3d_block", "arc3d_interrupted", "circle_chords", "unfinished_arc3d"]

#: round(10 x G) of the three-dimensional arc codes, with their names.
ARC3D_CODES = {24: "G02.4 three-dimensional circular interpolation",
               34: "G03.4 three-dimensional circular interpolation"}


def circle_chords(start: np.ndarray, mid: np.ndarray, end: np.ndarray, tolerance: float) -> list[np.ndarray]:
    """The points after ``start`` of chords within ``tolerance`` [mm] of the circle from ``start`` through
    ``mid`` to ``end`` [mm], ``end`` last; ``[mid, end]`` when the three lie on one line or two coincide."""
    a, b = mid - start, end - start
    normal = np.cross(a, b)
    area = float(np.linalg.norm(normal))
    if area <= 1e-9 * max(1.0, float(np.linalg.norm(a)) * float(np.linalg.norm(b))):
        return [mid, end]
    normal /= area
    # centre of the circumscribed circle: start + (|a|^2 (b x n) - |b|^2 (a x n)) / (2 |a x b|) in the plane
    centre = start + (np.dot(a, a) * np.cross(b, normal) - np.dot(b, b) * np.cross(a, normal)) / (2.0 * area)
    radius = float(np.linalg.norm(start - centre))
    u = (start - centre) / radius
    v = np.cross(normal, u)
    sweep = math.atan2(float(np.dot(end - centre, v)), float(np.dot(end - centre, u))) % (2.0 * math.pi)
    if sweep == 0.0:
        sweep = 2.0 * math.pi
    step = 2.0 * math.acos(max(-1.0, 1.0 - tolerance / radius)) if tolerance < radius else math.pi / 2
    n = max(2, math.ceil(sweep / step))
    points = [centre + radius * (math.cos(t) * u + math.sin(t) * v) for t in np.linspace(0.0, sweep, n + 1)[1:-1]]
    return [*points, np.array(end, dtype=float)]


def arc3d_block(seen, axis_words: list[str], target: np.ndarray, st: State, blocks: list[Block], where: Where,
                common: dict, mcol: int, mtok: str, feed_of) -> None:
    """One block under G02.4/G03.4 (``target`` its end as an ordinary move reads it): the intermediate point, kept
    in ``st.arc3d_mid``, or the end point, which runs the arc (``feed_of(st, segment)``: the chords' feed)."""
    code = "G02.4" if st.motion == 24 else "G03.4"
    if st.frame is not None or st.rotation or st.comp_side is not None or st.tcp:
        what = ("cutter compensation" if st.comp_side is not None else "tool centre point control" if st.tcp
                else "a G68 rotation, G51 scaling, mirror image or G10 R rotation")
        where.fail(f"{code} three-dimensional arc under {what}: not supported", column=mcol, text=mtok,
                   expected=f"G40, G49, G69, G50 and G50.1 before {code}")
    extra = next((seen[k] for k in "ABCUVW" if k in seen), None)
    if extra is not None:
        where.fail(f"{code} three-dimensional arc with axis word {extra.letter}: not supported", column=extra.column,
                   text=extra.text, expected="X, Y and Z only on a three-dimensional arc")
    if st.arc3d_mid is None:
        st.arc3d_mid = np.array(target, dtype=float)
        st.arc3d_line = where.line
        return
    mid, st.arc3d_mid = st.arc3d_mid, None
    end = np.array(target, dtype=float)
    if st.incremental:  # relative to the intermediate point
        end = end + (mid - st.pos)
    else:  # an axis the end block leaves out keeps the intermediate point's coordinate
        for i, letter in enumerate("XYZ"):
            if letter not in axis_words:
                end[i] = mid[i]
    points = circle_chords(st.pos, mid, end, SPLINE_TOLERANCE)
    starts = [st.pos.copy(), *points[:-1]]
    segs = [Line(a, b) for a, b in zip(starts, points)]
    # under G93 the arc takes the block's 1/F minutes: one speed along all its chords
    speed = sum(g.length for g in segs) * st.block_f / 60.0 if st.inverse_time else None
    for seg in segs:
        blocks.append(Block(kind="line", feed=feed_of(st, seg) if speed is None else speed, segment=seg,
                            **{**common, "start": np.array(seg.start), "target": np.array(seg.end)}))
    st.pos = end


def unfinished_arc3d(st: State, where: Where) -> None:
    """Fail where a G02.4/G03.4 intermediate point has no end point block: another motion code came, or the
    program ended (``where``: that place)."""
    if st.arc3d_mid is not None:
        where.fail(f"three-dimensional arc: the intermediate point of line {st.arc3d_line} has no end point block",
                   column=1, text=where.text or "", expected="the end point block X.. Y.. Z.. right after the "
                   "G02.4/G03.4 block of the intermediate point")


def arc3d_interrupted(st: State, where: Where) -> None:
    """Fail where a block (``where``) that is not the end point came after a G02.4/G03.4 intermediate point: the
    two blocks must follow each other (the module text)."""
    where.fail(f"three-dimensional arc: a block between the intermediate point (line {st.arc3d_line}) and its end "
               "point block", column=1, text=where.text or "",
               expected="the end point block X.. Y.. Z.. right after the G02.4/G03.4 block (a dwell, M code or "
                        "other block before it or after the arc)")
