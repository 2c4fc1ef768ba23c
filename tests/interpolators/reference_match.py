"""Align a reference's expected blocks with a reader's ``--blocks`` rows and compare the end points.

The rows are ``vcnc.commands.interpolate.blocks_table`` rows: ``block, line, kind, x, y, z, ...``
(end points in machine coordinates [mm]). The expected blocks are :class:`Expected`-like objects
(``line``, ``kind``, ``end``, ``tolerance``, ``rows``) from ``reference_iso`` or
``reference_heidenhain``. The comparison stops at the first disagreement (after it, the alignment
means nothing) and says which rows were checked, and how.
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["Match", "match_blocks", "END_TOLERANCE"]

#: Rounding allowance on an exact end point: relative to the coordinates' size [mm/mm].
END_TOLERANCE = 1e-9


@dataclasses.dataclass(frozen=True, kw_only=True)
class Match:
    """Outcome of one program's comparison.

    Attributes
    ----------
    rows : int
        Rows in the reader's table.
    exact : int
        Rows whose line, kind and end point agreed with an exact prediction.
    within : int
        Rows checked within a tolerance (G41/G42 blocks: the tool radius) or as intermediate rows of
        a block whose last row was checked (spline chords, compensation corner arcs).
    mismatch : str or None
        The first disagreement: reader row, expected block, both end points; None if none.
    """

    rows: int
    exact: int
    within: int
    mismatch: str | None = None


def _close(got: np.ndarray, want: np.ndarray, tolerance: float) -> bool:
    scale = max(1.0, float(np.abs(want).max()))
    return float(np.linalg.norm(got - want)) <= tolerance + END_TOLERANCE * scale * 10


def match_blocks(expected: list, rows: list[list]) -> Match:
    """Compare expected blocks with the reader's rows, in order."""
    i = exact = within = 0
    for j, e in enumerate(expected):
        def bad(why: str, _i=i, _e=e, _j=j) -> Match:
            got = rows[_i][:6] if _i < len(rows) else "no row"
            return Match(rows=len(rows), exact=exact, within=within,
                         mismatch=f"{why}: expected #{_j} line {_e.line} {_e.kind} {np.round(_e.end, 6).tolist()}"
                                  f" (tol {_e.tolerance:g}), reader row {got}")

        if i >= len(rows):
            if e.rows == "optional":
                continue
            return bad("reader has fewer rows")
        row = rows[i]
        got = np.array(row[3:6], float)
        ok_kind = e.kind is None or row[2] == e.kind
        if e.rows == "optional":
            if row[1] == e.line and ok_kind and _close(got, e.end, 0.0):
                i, exact = i + 1, exact + 1
            continue
        if e.rows == "last":
            k = i
            while k + 1 < len(rows) and rows[k + 1][1] == e.line and rows[k][1] == e.line \
                    and not _next_is(expected, j, rows[k + 1]):
                k += 1
            row, got = rows[k], np.array(rows[k][3:6], float)
            if row[1] != e.line or not _close(got, e.end, e.tolerance):
                i = k
                return bad("end point differs" if row[1] == e.line else "line differs")
            within += k - i + (1 if e.tolerance > 0 else 0)
            exact += 0 if e.tolerance > 0 else 1
            i = k + 1
            continue
        if row[1] != e.line:
            return bad("line differs")
        if not ok_kind:
            return bad("kind differs")
        if not _close(got, e.end, e.tolerance):
            return bad("end point differs")
        if e.tolerance > 0:
            within += 1
        else:
            exact += 1
        i += 1
    if i < len(rows):
        return Match(rows=len(rows), exact=exact, within=within,
                     mismatch=f"reader has {len(rows) - i} more rows, first {rows[i][:6]}")
    return Match(rows=len(rows), exact=exact, within=within)


def _next_is(expected: list, j: int, row: list) -> bool:
    """Whether ``row`` already is the next expected block (same line: a loop or another block)."""
    if j + 1 >= len(expected):
        return False
    n = expected[j + 1]
    return n.line == row[1] and n.rows != "last" and _close(np.array(row[3:6], float), n.end, n.tolerance)
