"""Compiled ``%.<P>g`` / ``%d`` text of float64 tables, byte for byte what Python's ``%`` writes.

:func:`vcnc.core.io.write_rows` formats millions of numbers per capture; Python's ``%`` costs about a
microsecond per number. This module writes the same text from compiled code.

How a number is rounded
-----------------------
C's ``%.<P>g`` (which Python's ``%`` follows: ISO C 7.21.6.1, "g, G conversion") rounds the exact binary
value to ``P`` significant decimal digits, a tie to even. Here ``x * 10**k`` (``k`` = ``P - 1`` minus the
decimal exponent of ``x``) is formed in double-double arithmetic (Dekker's exact product; ``10**k`` held as
the sum of two doubles, tabled from exact integers), with an error below 1e-20 of a unit of the last digit.
Where the part after the last digit lies within :data:`HARD_MARGIN` of one half, and ``10**k`` is a double
(``0 <= k <= 22``: numbers from 1e-11 to 1e12 at ``P`` = 12), the product is exact and so is the side of the
tie; exact ties are common (a DAC's control signal, k / 2**n volt, has 13 digits ending in 5). Elsewhere
within that margin, for NaN, inf, the largest and smallest magnitudes and ``%d`` beyond 2**62, the number is
formatted by Python's ``%``: the text is always Python's.

Then the C rules for ``%g`` without ``#``: with ``X`` the decimal exponent after rounding, ``%f`` style
with ``P - 1 - X`` decimals when ``-4 <= X < P``, else ``%e`` style with a sign and at least two exponent
digits; trailing zeros of the fraction and a bare decimal point are removed.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterator, Sequence
from fractions import Fraction

import numba
import numpy as np

__all__ = ["format_chunks", "column_codes", "HARD_MARGIN"]

#: Distance from a rounding tie (in units of the last digit kept) below which Python formats the number.
HARD_MARGIN = 1e-7

#: Largest precision of ``%.<P>g`` done here: ``10**P`` must stay below 2**53 (integers exact in a double).
MAX_PRECISION = 15

#: Magnitudes formatted here (outside: Python's ``%``), so that every ``10**k`` needed and its Dekker split
#: stay normal doubles.
_MIN_ABS, _MAX_ABS = 1e-280, 1e280

#: The ``%d`` column code (a precision code is 1 .. MAX_PRECISION).
INT_CODE = 0

_K_MIN, _K_MAX = -290, 300

#: Largest k with 10**k a double (exactly).
_EXACT_POW = 22


def _power_table() -> tuple[np.ndarray, np.ndarray]:
    """10**k for k in [_K_MIN, _K_MAX] as hi + lo doubles (hi the nearest double, lo the nearest to the rest)."""
    hi = np.empty(_K_MAX - _K_MIN + 1)
    lo = np.empty_like(hi)
    for i, k in enumerate(range(_K_MIN, _K_MAX + 1)):
        exact = Fraction(10) ** k
        hi[i] = float(exact)
        lo[i] = float(exact - Fraction(hi[i]))
    return hi, lo


_POW_HI, _POW_LO = _power_table()
_SPLIT = 134217729.0  # 2**27 + 1, Dekker's splitter
_TEN = np.uint64(10)
_LOG10_2 = math.log10(2.0)


def column_codes(fmt: Sequence[str]) -> np.ndarray | None:
    """One code per column (its precision for ``%.<P>g``, :data:`INT_CODE` for ``%d``), or None when a
    format is neither (then the caller formats with Python)."""
    codes = []
    for f in fmt:
        m = re.fullmatch(r"%\.(\d+)g", f)
        if f == "%d":
            codes.append(INT_CODE)
        elif m and 1 <= int(m.group(1)) <= MAX_PRECISION:
            codes.append(int(m.group(1)))
        else:
            return None
    return np.asarray(codes, dtype=np.int64)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _two_prod(a, b):  # pragma: no cover - compiled
    """(p, e) with p = fl(a * b) and a * b = p + e exactly (Dekker)."""
    p = a * b
    c = _SPLIT * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLIT * b
    bh = c - (c - b)
    bl = b - bh
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, e


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _digits(a, prec):  # pragma: no cover - compiled
    """(m, X, ok): ``a`` > 0 rounded to ``prec`` digits m in [10**(prec-1), 10**prec) times 10**(X-prec+1);
    ok False when the rounding is too close to a tie to decide here."""
    top = _POW_HI[prec - _K_MIN]
    X = int(math.floor((math.frexp(a)[1] - 1) * _LOG10_2))  # the decimal exponent, or one less
    if a >= _POW_HI[X + 1 - _K_MIN]:
        X += 1
    for _ in range(4):
        k = prec - 1 - X
        hi = _POW_HI[k - _K_MIN]
        p, e = _two_prod(a, hi)
        t = e + a * _POW_LO[k - _K_MIN]
        n = np.floor(p)
        r = (p - n) + t
        while r < 0.0:
            n -= 1.0
            r += 1.0
        while r >= 1.0:
            n += 1.0
            r -= 1.0
        if n >= top:
            X += 1
            continue
        if n < _POW_HI[prec - 1 - _K_MIN]:
            X -= 1
            continue
        if abs(r - 0.5) < HARD_MARGIN:
            if not 0 <= k <= _EXACT_POW:
                return np.uint64(0), 0, False
            # 10**k is a double and a * 10**k = p + e exactly: the side of the tie n + 1/2 is exact too
            # (p - (n + 1/2) is exact by Sterbenz' lemma, and a rounded sum keeps the sign of the exact one)
            side = (p - (n + 0.5)) + e
            if side > 0.0 or (side == 0.0 and n - 2.0 * np.floor(0.5 * n) == 1.0):  # a tie goes to the even digit
                n += 1.0
        elif r > 0.5:
            n += 1.0
        if n >= top:
            n = _POW_HI[prec - 1 - _K_MIN]
            X += 1
        return np.uint64(n), X, True
    return np.uint64(0), 0, False


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _layout_g(x, prec):  # pragma: no cover - compiled
    """``'%.<prec>g' % x`` as (style, negative, digits m without trailing zeros, their count, exponent X);
    style 0: zero, 1: ``%f``, 2: ``%e``, -1: left to Python."""
    neg = math.copysign(1.0, x) < 0.0
    a = abs(x)
    if math.isnan(x) or math.isinf(x) or (a != 0.0 and (a < _MIN_ABS or a > _MAX_ABS)):
        return -1, neg, np.uint64(0), 0, 0
    if a == 0.0:
        return 0, neg, np.uint64(0), 1, 0
    m, X, ok = _digits(a, prec)
    if not ok:
        return -1, neg, m, 0, 0
    nd = prec
    while m % _TEN == 0 and nd > 1:  # trailing zeros go
        m //= _TEN
        nd -= 1
    return (1 if -4 <= X < prec else 2), neg, m, nd, X


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _layout_d(x):  # pragma: no cover - compiled
    """``'%d' % x`` (x truncated toward zero) in the terms of :func:`_layout_g`; left to Python beyond 2**62
    and for NaN."""
    if not (abs(x) < 4.611686018427388e18):
        return -1, False, np.uint64(0), 0, 0
    v = int(x)
    if v == 0:
        return 0, False, np.uint64(0), 1, 0
    m = np.uint64(abs(v))
    nd = 1
    w = m
    while w >= _TEN:
        w //= _TEN
        nd += 1
    return 1, v < 0, m, nd, nd - 1


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _format(data, codes, delim, buf, hard):  # pragma: no cover - compiled
    """Rows of ``data`` into ``buf``; returns (bytes written, count of numbers left to Python), whose
    positions in ``buf`` and flat indices in ``data`` are ``hard[:count, 0]``, ``hard[:count, 1]``.

    (The writing is all here: array arguments of helper calls cost reference counting per number.)"""
    n_rows, n_cols = data.shape
    pos = 0
    n_hard = 0
    for i in range(n_rows):
        for j in range(n_cols):
            if j:
                buf[pos] = delim
                pos += 1
            if codes[j] == INT_CODE:
                style, neg, m, nd, X = _layout_d(data[i, j])
            else:
                style, neg, m, nd, X = _layout_g(data[i, j], codes[j])
            if style < 0:
                hard[n_hard, 0] = pos
                hard[n_hard, 1] = i * n_cols + j
                n_hard += 1
                continue
            if neg:
                buf[pos] = 45  # '-'
                pos += 1
            if style == 0:
                buf[pos] = 48
                pos += 1
                continue
            dot = 0  # the decimal point follows digit ``dot`` (when digits follow it)
            if style == 1 and X < 0:  # 0.000ddd
                buf[pos] = 48
                buf[pos + 1] = 46
                pos += 2
                for _ in range(-X - 1):
                    buf[pos] = 48
                    pos += 1
                dot = nd
            elif style == 1:
                dot = X
            point = 1 if dot < nd - 1 else 0
            for k in range(nd - 1, -1, -1):  # unsigned: the divisions become multiplications
                q = m // _TEN
                buf[pos + k + (point if k > dot else 0)] = np.uint8(48 + (m - q * _TEN))
                m = q
            if point:
                buf[pos + dot + 1] = 46
            pos += nd + point
            if style == 1:
                for _ in range(X + 1 - nd):  # integral digits beyond the significant ones
                    buf[pos] = 48
                    pos += 1
                continue
            buf[pos] = 101  # 'e'
            buf[pos + 1] = 45 if X < 0 else 43
            pos += 2
            ax = abs(X)
            if ax >= 100:
                buf[pos] = 48 + ax // 100
                pos += 1
            buf[pos] = 48 + (ax // 10) % 10
            buf[pos + 1] = 48 + ax % 10
            pos += 2
        buf[pos] = 10
        pos += 1
    return pos, n_hard


#: Bytes reserved per number: sign, up to MAX_PRECISION digits, '0.000' before them or 'e-308' after, a
#: delimiter.
_WIDTH = 1 + MAX_PRECISION + 5 + 5 + 1


def format_chunks(table: Callable[[int, int], np.ndarray], n_rows: int, codes: np.ndarray, fmt: Sequence[str],
                  delimiter: str, rows: int) -> Iterator[str]:
    """The text of the ``n_rows`` rows of a table, ``rows`` at a time (``table(start, stop)``: those rows,
    2-D), one line per row, columns formatted by ``codes`` (:func:`column_codes` of ``fmt``) and joined by
    the one-character ``delimiter``.

    One buffer serves every chunk (fresh memory costs a page fault per 4 kB, as much as the formatting)."""
    n_cols = len(fmt)
    n = min(n_rows, rows) * n_cols
    buf = np.empty(max(n * _WIDTH, 1), dtype=np.uint8)
    hard = np.empty((n, 2), dtype=np.int64)
    for start in range(0, n_rows, rows):
        chunk = np.ascontiguousarray(table(start, min(start + rows, n_rows)), dtype=np.float64)
        end, n_hard = _format(chunk, codes, ord(delimiter), buf, hard)
        if not n_hard:
            yield buf[:end].tobytes().decode("ascii")
            continue
        parts, last = [], 0
        flat = chunk.ravel()
        for pos, idx in hard[:n_hard]:
            parts += [buf[last:pos].tobytes().decode("ascii"), fmt[idx % n_cols] % float(flat[idx])]
            last = pos
        parts.append(buf[last:end].tobytes().decode("ascii"))
        yield "".join(parts)
