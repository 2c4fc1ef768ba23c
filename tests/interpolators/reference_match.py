"""Align a reference's expected blocks with a reader's ``--blocks`` rows and compare the end points.

The rows are ``vcnc.commands.interpolate.blocks_table`` rows: ``block, line, kind, x, y, z, cx, cy,
cz, feed`` (end points in machine coordinates [mm]), optionally followed by the six positions
``a, b, c, u, v, w`` [deg, mm], which are then compared with an expected block's ``extra``. The
expected blocks are :class:`Expected`-like objects (``line``, ``kind``, ``end``, ``tolerance``,
``rows``) from ``reference_iso`` or ``reference_heidenhain``. The comparison stops at the first
disagreement (after it, the alignment means nothing) and says which rows were checked, and how.
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["Match", "match_blocks", "END_TOLERANCE", "COMP_TOLERANCE"]

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


#: Allowance on a compensated end's distance from its programmed element [mm].
COMP_TOLERANCE = 1e-6


def _element_distance(point: np.ndarray, element: tuple) -> float:
    """Distance of a point from a programmed line segment, or from an arc's circle in its plane
    (with the out-of-plane offset from the nearer end's height ignored)."""
    if element[0] == "line":
        a, b = element[1], element[2]
        d = b - a
        t = 0.0 if not d.any() else float(np.clip(np.dot(point - a, d) / np.dot(d, d), 0.0, 1.0))
        return float(np.linalg.norm(point - (a + t * d)))
    _, centre, radius, (i, j), _, _ = element
    return abs(float(np.hypot(point[i] - centre[i], point[j] - centre[j])) - radius)


def _comp_ok(got: np.ndarray, e) -> bool:
    if getattr(e, "corner", None) is not None:  # a Fanuc outside corner (reference_iso.fanuc_corner)
        return _close(got, e.corner, e.corner_tolerance)
    if e.element[0] == "arc":
        normal = 3 - sum(e.element[3])
        rise = abs(e.end[normal] - e.element[4][normal])
        if abs(got[normal] - e.end[normal]) > 0.5 * rise + COMP_TOLERANCE:
            return False
    d = _element_distance(got, e.element)
    allowance = COMP_TOLERANCE + (e.element[5] if e.element[0] == "arc" else 0.0)
    if e.entry:
        return d <= e.tolerance + allowance
    return abs(d - e.tolerance) <= allowance


def _extra_ok(row: list, e) -> bool:
    """The a, b, c, u, v, w ends (row columns 10-15), when both the row and the block have them."""
    want = getattr(e, "extra", None)
    if want is None or len(row) < 16:
        return True
    return _close(np.array(row[10:16], float), want, 0.0)


def _centre_ok(row: list, e) -> bool:
    if e.centre is None:
        return True
    got = np.array(row[6:9], float)
    return all(abs(got[k] - e.centre[k]) <= e.centre_tolerance for k in e.plane)


def _failure(why: str, rows: list[list], i: int, e, j: int, exact: int, within: int) -> Match:
    got = rows[i][:6] + rows[i][10:] if i < len(rows) else "no row"
    return Match(rows=len(rows), exact=exact, within=within,
                 mismatch=f"{why}: expected #{j} line {e.line} {e.kind} {np.round(e.end, 6).tolist()}"
                          f"{'' if getattr(e, 'extra', None) is None else ' ' + str(np.round(e.extra, 6).tolist())}"
                          f" (tol {e.tolerance:g}{_corner_note(e)}), reader row {got}")


def _corner_note(e) -> str:
    corner = getattr(e, "corner", None)
    return "" if corner is None else f"; Fanuc corner {np.round(corner, 6).tolist()}"


def _last_row(expected: list, j: int, rows: list[list], i: int) -> int:
    """Index of the last row of the block ``expected[j]`` that starts at row ``i`` (same line)."""
    e, k = expected[j], i
    while k + 1 < len(rows) and rows[k + 1][1] == e.line and rows[k][1] == e.line \
            and not _next_is(expected, j, rows[k + 1]):
        k += 1
    return k


def reader_rows(header: list[str], rows: list[list]) -> list[list]:
    """The ``--blocks`` rows of :func:`vcnc.commands.interpolate.blocks_table` in the layout :func:`match_blocks`
    compares: the a, b, c, u, v, w columns of the axes the program uses moved behind the feed as all six (the
    others at 0), where the reference keeps its ``extra`` ends."""
    extra = header[6:len(header) - 4]
    at = ["abcuvw".index(a) for a in extra]
    out = []
    for r in rows:
        six = [0.0] * 6
        for k, i in enumerate(at):
            six[i] = r[6 + k]
        out.append(r[:6] + r[6 + len(extra):] + six)
    return out


def match_blocks(expected: list, rows: list[list]) -> Match:
    """Compare expected blocks with the reader's rows, in order."""
    i = exact = within = 0
    for j, e in enumerate(expected):
        if i >= len(rows):
            if e.rows == "optional":
                continue
            return _failure("reader has fewer rows", rows, i, e, j, exact, within)
        row = rows[i]
        got = np.array(row[3:6], float)
        ok_kind = e.kind is None or row[2] == e.kind
        if e.rows == "optional":
            if row[1] == e.line and ok_kind and _close(got, e.end, 0.0) and _extra_ok(row, e):
                i, exact = i + 1, exact + 1
            continue
        if e.rows == "last":
            k = _last_row(expected, j, rows, i)
            row, got = rows[k], np.array(rows[k][3:6], float)
            ok = (_comp_ok(got, e) if e.element is not None else _close(got, e.end, e.tolerance)) and _extra_ok(row, e)
            if row[1] != e.line or not ok:
                return _failure("end point differs" if row[1] == e.line else "line differs", rows, k, e, j, exact,
                                within)
            within += k - i + (1 if e.tolerance > 0 else 0)
            exact += 0 if e.tolerance > 0 else 1
            i = k + 1
            continue
        why = ("line differs" if row[1] != e.line else "kind differs" if not ok_kind
               else "end point differs" if not _close(got, e.end, e.tolerance)
               else "end of the axes a, b, c, u, v, w differs" if not _extra_ok(row, e)
               else f"arc centre differs (reader {row[6:9]}, expected {np.round(e.centre, 6).tolist()})"
               if not _centre_ok(row, e) else None)
        if why:
            return _failure(why, rows, i, e, j, exact, within)
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
    got = np.array(row[3:6], float)
    if n.element is not None:
        return n.line == row[1] and _comp_ok(got, n)
    return n.line == row[1] and n.rows != "last" and _close(got, n.end, n.tolerance)
