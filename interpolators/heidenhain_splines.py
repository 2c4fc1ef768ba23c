"""``SPL`` spline blocks of Heidenhain conversational programs, as chains of chords.

iTNC 530 user's manual (60642x-04, section 12.7 "Contour movements - Spline interpolation (software
option 2)", pp. 539-541; TNC 426/430 user's manual 280 476, section 6.7 the same): a CAM system writes
a spline as blocks ::

    7 L X+28.338 Y+19.385 Z-0.5 FMAX              the spline's starting point
    8 SPL X24.875 Y15.924 Z-0.5 K3X-4.688E-002 K2X2.459E-002 K1X3.486E+000
      K3Y-4.563E-002 K2Y2.155E-002 K1Y3.486E+000 K3Z0.000E+000 K2Z0.000E+000 K1Z0.000E+000 F10000

and the TNC runs each block along the third-degree polynomials ``X(t) = K3X t^3 + K2X t^2 + K1X t + X``
(the same for every axis of the block) "whereby the variable t runs from 1 to 0": at ``t = 0`` the
block's end point, at ``t = 1`` its start, which "can deviate from the end point of the previous
contour by no more than 1 um. Larger deviations will provoke an error message". For every end-point
coordinate the block holds K3, K2, K1 of its axis, in that order; a K may carry an exponent
(``K3X+1.2750 E2``, ``K3X-4.688E-002``); F and M may follow. The end point and the coefficients are in
the program's coordinates and unit.

vcnc runs the curve as chords within :data:`interpolators.iso_splines.SPLINE_TOLERANCE` of it
(:func:`interpolators.iso_splines.bezier_chords`, which ISO's G5 splines use: the polynomial is
a Bezier curve), joined without stops (the manual asks for tangential transitions); X, Y and Z only
(the manual's A, B, C, U, V, W splines are refused).
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np

from interpolators._words import Where, token_at
from interpolators.heidenhain_params import QParameters
from interpolators.heidenhain_words import read_value
from interpolators.iso_splines import bezier_chords

__all__ = ["SPLINE_START_TOLERANCE", "SplineBlock", "read_spline", "spline_points"]

#: The most the start of an SPL block (``t = 1``) may lie from the end of the previous element [mm] (iTNC 530
#: user's manual: "no more than 1 um").
SPLINE_START_TOLERANCE: float = 0.001  # in each axis

_K_RE = re.compile(r"K([123])([XYZABCUVW])\s*([+-]?\s*(?:\d+\.?\d*|\.\d+))(?:\s*E\s*([+-]?\d+))?(?![\w.])", re.I)
_END_RE = re.compile(r"([XYZABCUVW])(?=\s*[+-]?\s*[\d.Q(])", re.I)


@dataclasses.dataclass(frozen=True)
class SplineBlock:
    """The data of one ``SPL`` block.

    Attributes
    ----------
    end : dict
        Axis index (0, 1, 2) -> end-point coordinate [program unit].
    coefficients : dict
        Axis index -> (K3, K2, K1) [program unit].
    rest : str
        The block with end point and coefficients blanked out (its F and M words, columns kept).
    """

    end: dict[int, float]
    coefficients: dict[int, tuple[float, float, float]]
    rest: str


def read_spline(code: str, pos: int, where: Where, params: QParameters, *, column0: int) -> SplineBlock:
    """The end point and coefficients of the ``SPL`` block ``code`` (its words from ``pos`` on; ``column0``:
    the 1-based column of ``code[0]``); an error for a K without its end-point coordinate, an end-point
    coordinate without K3, K2, K1, or a rotary or secondary axis."""
    chars = list(code)
    ks: dict[int, dict[int, float]] = {}
    end: dict[int, float] = {}
    for km in _K_RE.finditer(code, pos):
        axis = _axis(km.group(2), where, column0 + km.start(), km.group(0))
        value = float(km.group(3).replace(" ", "")) * 10.0 ** int(km.group(4) or 0)
        ks.setdefault(axis, {})[int(km.group(1))] = value
        chars[km.start():km.end()] = " " * (km.end() - km.start())
    blanked = "".join(chars)
    j = pos
    while (em := _END_RE.search(blanked, j)) is not None:
        if em.start() > 0 and not blanked[em.start() - 1].isspace():
            j = em.end()
            continue
        axis = _axis(em.group(1), where, column0 + em.start(), token_at(blanked, em.start()))
        value, stop = read_value(blanked, em.end(), where, params, what=f"SPL {em.group(1).upper()}", column0=column0)
        end[axis] = value
        chars[em.start():stop] = " " * (stop - em.start())
        blanked = "".join(chars)
        j = stop
    for axis in set(ks) | set(end):
        letter = "XYZ"[axis]
        if axis not in end or sorted(ks.get(axis, {})) != [1, 2, 3]:
            where.fail(f"SPL: axis {letter} without its end point and K3{letter}, K2{letter}, K1{letter}",
                       column=column0 + pos, text=code[pos:].strip(),
                       expected="for every end-point coordinate the spline parameters K3, K2, K1 of its axis")
    if not end:
        where.fail("SPL without an end point", column=column0, text=code.strip(),
                   expected="SPL X.. Y.. Z.. K3X.. K2X.. K1X.. ...")
    coefficients = {a: (k[3], k[2], k[1]) for a, k in ks.items()}
    return SplineBlock(end=end, coefficients=coefficients, rest=blanked)


def _axis(letter: str, where: Where, column: int, text: str) -> int:
    axis = "XYZ".find(letter.upper())
    if axis < 0:
        where.fail(f"SPL with the axis {letter.upper()} is not supported", column=column, text=text,
                   expected="splines in X, Y and Z")
    return axis


def spline_points(start: np.ndarray, block: SplineBlock, scale: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """The curve's start (``t = 1``) and the end points of its chords (the last the programmed end point) in
    program coordinates [mm]; ``start`` [mm] gives the axes the block does not name (they stay), ``scale``
    mm per program unit."""
    d = np.array(start, dtype=float)
    k3, k2, k1 = np.zeros(3), np.zeros(3), np.zeros(3)
    for axis, value in block.end.items():
        d[axis] = value * scale
        k3[axis], k2[axis], k1[axis] = (c * scale for c in block.coefficients[axis])
    # the polynomial in t from 0 (the end) to 1 (the start) is the Bezier curve of these control points
    control = [d + k1 + k2 + k3, d + 2.0 * k1 / 3.0 + k2 / 3.0, d + k1 / 3.0, d]
    return control[0], bezier_chords(control)
