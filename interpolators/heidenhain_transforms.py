"""Coordinate transformation cycles of Heidenhain conversational programs: mirror image, rotation, scaling.

Sources: HEIDENHAIN TNC 320 / TNC 620 / TNC 640 user's manuals for cycle programming, chapter
"Cycles: Coordinate Transformations" (TNC 620 340 56x-02, p. 245-258; TNC 640 conversational
manual 10/2017, p. 153: "Transformations in the working plane coordinate system: Cycle 7 DATUM
SHIFT, Cycle 8 MIRROR IMAGE, Cycle 10 ROTATION, Cycle 11 SCALING, Cycle 26 AXIS-SPECIFIC
SCALING"):

* ``CYCL DEF 8.0 MIRROR IMAGE`` / ``8.1 X Y``: the listed axes are mirrored about the active datum
  (``8.1`` without axes cancels it); "the machining direction is reversed" when one axis of the
  working plane is mirrored (arcs turn the other way, RL becomes RR); the tool axis cannot be
  mirrored.
* ``CYCL DEF 10.0 ROTATION`` / ``10.1 ROT+35`` (``IROT``: added to the active angle): the
  coordinate system turns about the active datum in the working plane, the angle measured from the
  reference axis (X in the XY plane); ``ROT+0`` cancels it.
* ``CYCL DEF 11.0 SCALING`` / ``11.1 SCL 0.75``: coordinates are scaled about the active datum, on
  the three principal axes (the default of the machine parameter, iTNC 530 MP7410 = 0), as are the
  lengths of cycles; ``SCL 1`` cancels it.
* ``CYCL DEF 26.0 AXIS-SPECIFIC SCALING`` / ``26.1 X1.4 Y0.6 CCX+15 CCY+20``: a factor per axis about
  the centre CC (TNC 620 manual p. 256: "Coordinate axes sharing coordinates for arcs must be
  enlarged or reduced by the same factor"); a factor 1 cancels it for its axis.

The TNC keeps each transformation apart and applies them in the order of their cycle numbers,
from the datum outwards: shift (cycle 7, :class:`interpolators.heidenhain._Machine` keeps it),
mirror, rotation, scaling. A program point ``p`` [mm, relative to the datum] lies at
``mirror(rotate(scale(p)))`` from the datum in machine axes, so that a mirrored program is the
exact mirror image of the unmirrored one, rotations included (our reading of that order).
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from interpolators._words import Where
from interpolators.heidenhain_params import QParameters
from interpolators.heidenhain_words import read_value
from toolpaths.geometry import PLANE_AXES

__all__ = ["Transform", "TransformError", "TRANSFORM_CYCLES", "transform_item", "tilt_block", "trans_block"]


class TransformError(ValueError):
    """A transformation that cannot map what the program asks; the reader adds the location."""

    def __init__(self, message: str, expected: str) -> None:
        super().__init__(message)
        self.message = message
        self.expected = expected


@dataclasses.dataclass(frozen=True, kw_only=True)
class Transform:
    """The active coordinate transformations of cycles 8, 10, 11 and 26.

    Attributes
    ----------
    mirror : tuple of bool
        Mirrored axes (x, y, z) (cycle 8).
    rotation : float
        Rotation angle in the working plane [deg], counter-clockwise from the reference axis (cycle 10).
    scale : float
        Scaling factor of cycle 11 [-] (> 0), about the datum.
    axis_scale : tuple of float
        Factors of cycle 26 per axis (x, y, z) [-] (> 0), about ``centre``.
    centre : tuple of float
        Centre of the cycle 26 scaling [mm, program coordinates].
    """

    mirror: tuple[bool, bool, bool] = (False, False, False)
    rotation: float = 0.0
    scale: float = 1.0
    axis_scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def identity(self) -> bool:
        """True when no transformation is active."""
        return (not any(self.mirror) and self.rotation == 0.0 and self.scale == 1.0
                and self.axis_scale == (1.0, 1.0, 1.0))

    def _factors(self) -> np.ndarray:
        return self.scale * np.asarray(self.axis_scale, dtype=float)

    def apply(self, point: np.ndarray, plane: int) -> np.ndarray:
        """Machine-axis offset from the datum [mm] of a program point ``point`` [mm, from the datum]."""
        c = np.asarray(self.centre, dtype=float)
        v = self.scale * (c + np.asarray(self.axis_scale, dtype=float) * (np.asarray(point, dtype=float) - c))
        p, q = PLANE_AXES[plane]
        a = math.radians(self.rotation)
        cos, sin = math.cos(a), math.sin(a)
        v[p], v[q] = cos * v[p] - sin * v[q], sin * v[p] + cos * v[q]
        return np.where(self.mirror, -v, v)

    def invert(self, offset: np.ndarray, plane: int) -> np.ndarray:
        """The program point [mm, from the datum] at the machine-axis offset ``offset`` [mm]."""
        v = np.where(self.mirror, -np.asarray(offset, dtype=float), np.asarray(offset, dtype=float))
        p, q = PLANE_AXES[plane]
        a = math.radians(self.rotation)
        cos, sin = math.cos(a), math.sin(a)
        v[p], v[q] = cos * v[p] + sin * v[q], -sin * v[p] + cos * v[q]
        c = np.asarray(self.centre, dtype=float)
        return c + (v / self.scale - c) / np.asarray(self.axis_scale, dtype=float)

    def flips(self, plane: int) -> bool:
        """True when the transformation reverses the sense of rotation in the working plane (one
        of its axes mirrored): arcs turn the other way and RL/RR swap sides."""
        p, q = PLANE_AXES[plane]
        return self.mirror[p] != self.mirror[q]

    def angle(self, angle_deg: float, plane: int) -> float:
        """Machine polar angle [deg] of the program polar angle ``angle_deg`` (about a mapped pole)."""
        a = angle_deg + self.rotation
        p, q = PLANE_AXES[plane]
        if self.mirror[p]:
            a = 180.0 - a
        if self.mirror[q]:
            a = -a
        return a

    def sweep(self, sweep_deg: float, plane: int) -> float:
        """Machine sweep [deg] of a program sweep (sign reversed when :meth:`flips`)."""
        return -sweep_deg if self.flips(plane) else sweep_deg

    def length(self, plane: int) -> float:
        """Factor of lengths in the working plane (arc and rounding radii, LEN) [-].

        Raises
        ------
        TransformError
            When the two axes of the plane are scaled by different factors (an arc would become
            an ellipse).
        """
        f = self._factors()
        p, q = PLANE_AXES[plane]
        if f[p] != f[q]:
            raise TransformError(f"axis-specific scaling {f[p]:g} and {f[q]:g} in the working plane distorts arcs",
                                 "the same factor for both axes of the working plane (cycle 26)")
        return float(f[p])

    def axis_factor(self, axis: int) -> float:
        """Factor of lengths along ``axis`` (the tool axis: cycle depths and clearances) [-]."""
        return float(self._factors()[axis])


#: Cycles that define a coordinate transformation here (cycle 7, the datum shift, is the reader's).
TRANSFORM_CYCLES: tuple[int, ...] = (8, 10, 11, 26)

_AXIS_RE = re.compile(r"\s*(I?)([XYZ])(?![A-Z])", re.I)
_FACTOR_RE = re.compile(r"\s*(CC)?([XYZ])(?=\s*[+-]?\s*[\d.Q(])", re.I)


def transform_item(number: int, rest: str, transform: Transform, where: Where, params: QParameters, *,
                   column0: int, scale: float) -> Transform:
    """The transformation after the item ``CYCL DEF n.1 <rest>`` of cycle 8, 10, 11 or 26.

    ``scale`` [mm per program unit] converts the centre of cycle 26; ``column0`` is the 1-based
    column of ``rest``. Malformed items are errors naming the cycle.
    """
    text = rest.strip()
    if number == 8:
        mirror = [False, False, False]
        pos = 0
        while rest[pos:].strip():
            am = _AXIS_RE.match(rest, pos)
            if am is None or am.group(1):
                tok = rest[pos:].split()[0]
                where.fail(f"cycle 8 MIRROR IMAGE: {tok!r} is not a linear axis", column=column0 + pos, text=tok,
                           expected="CYCL DEF 8.1 followed by the mirrored axes (X, Y), none to cancel")
            mirror["XYZ".index(am.group(2).upper())] = True
            pos = am.end()
        return dataclasses.replace(transform, mirror=tuple(mirror))
    if number == 10:
        m = re.match(r"\s*(I?)ROT\s*", rest, re.I)
        if m is None:
            where.fail("cycle 10 ROTATION without ROT", column=column0, text=text or "10.1",
                       expected="CYCL DEF 10.1 ROT+angle [deg] (IROT: incremental)")
        angle, end = read_value(rest, m.end(), where, params, what="ROT", column0=column0)
        _rest_empty(rest, end, where, column0)
        return dataclasses.replace(transform, rotation=(transform.rotation if m.group(1) else 0.0) + angle)
    if number == 11:
        m = re.match(r"\s*SCL\s*", rest, re.I)
        if m is None:
            where.fail("cycle 11 SCALING without SCL", column=column0, text=text or "11.1",
                       expected="CYCL DEF 11.1 SCL factor")
        factor, end = read_value(rest, m.end(), where, params, what="SCL", column0=column0)
        _rest_empty(rest, end, where, column0)
        _positive(factor, "cycle 11 SCALING: SCL", where, column0, text)
        return dataclasses.replace(transform, scale=factor)
    factors, centre = list(transform.axis_scale), list(transform.centre)
    pos = 0
    while rest[pos:].strip():
        fm = _FACTOR_RE.match(rest, pos)
        if fm is None:
            tok = rest[pos:].split()[0]
            where.fail(f"unexpected {tok!r} in cycle 26 AXIS-SPECIFIC SCALING", column=column0 + pos, text=tok,
                       expected="CYCL DEF 26.1 X<factor> Y<factor> CCX<centre> CCY<centre>")
        value, pos = read_value(rest, fm.end(), where, params, what=fm.group(0).strip(), column0=column0)
        i = "XYZ".index(fm.group(2).upper())
        if fm.group(1):
            centre[i] = value * scale
        else:
            _positive(value, f"cycle 26: factor of {fm.group(2).upper()}", where, column0, text)
            factors[i] = value
    return dataclasses.replace(transform, axis_scale=tuple(factors), centre=tuple(centre))


def _rest_empty(rest: str, end: int, where: Where, column0: int) -> None:
    if rest[end:].strip():
        tok = rest[end:].split()[0]
        where.fail(f"unexpected {tok!r} after the value", column=column0 + end, text=tok, expected="one value")


def _positive(value: float, what: str, where: Where, column0: int, text: str) -> None:
    if not value > 0:
        where.fail(f"{what} must be > 0", column=column0, text=text, expected="a factor > 0")


_TILT_ANGLE_RE = re.compile(r"(SP[ABC]|PROPR|PROMIN|EULPR|EULNU|EULROT|ROT|[ABC])(?=\s*[+-]?\s*[\d.Q(])", re.I)


def tilt_block(kw: str, rest: str, where: Where, params: QParameters, *, column0: int) -> str:
    """``PLANE ...``, ``FUNCTION ...``: the note of a block that tilts nothing, else an error naming it.

    TNC 640 user's manual, "Tilting the working plane (software option 1)": ``PLANE RESET`` cancels
    a tilt; ``PLANE SPATIAL/PROJECTED/EULER/RELATIVE/AXIAL`` with all angles 0 keeps the tool axis
    (no tilt; vcnc moves no rotary axis for it); any other angle, ``PLANE VECTOR``/``POINTS``, and
    ``FUNCTION TCPM`` (tool centre point management, as ``M128``) need the machine's kinematics,
    which vcnc does not model: an error naming the function. ``FUNCTION RESET TCPM`` and
    ``FUNCTION MODE MILL`` change nothing on a milling machine.
    """
    words = rest.split()
    form = words[0].upper() if words else ""
    what = f"{kw} {form}".strip()
    if kw == "FUNCTION":
        second = words[1].upper() if len(words) > 1 else ""
        if (form, second) in (("RESET", "TCPM"), ("MODE", "MILL")):
            return f"{kw} {form} {second}: no motion"
        where.fail(f"{what} is not supported", column=column0, text=what,
                   expected="3-axis machining (FUNCTION TCPM needs the machine's kinematics)")
    if form == "RESET":
        return "PLANE RESET: no tilted working plane (no motion)"
    if form in ("SPATIAL", "PROJECTED", "EULER", "RELATIVE", "AXIAL"):
        nonzero = [am.group(1).upper() for am in _TILT_ANGLE_RE.finditer(rest)
                   if read_value(rest, am.end(), where, params, what=am.group(1), column0=column0)[0] != 0.0]
        if not nonzero:
            return f"{what} with angles 0: no tilt (no motion)"
    where.fail(f"{what} (a tilted working plane) is not supported", column=column0, text=what,
               expected="3-axis machining: PLANE RESET, or PLANE .. with all angles 0")
    raise AssertionError("unreachable")  # pragma: no cover


def trans_block(rest: str, transform: Transform, where: Where, params: QParameters, *, column0: int,
                scale: float) -> tuple[Transform, dict[str, float] | None]:
    """``TRANS MIRROR|ROTATION|SCALE ...`` (the transformation after it) and ``TRANS DATUM ...``
    (the shift words ``{"X": .., "IX": ..}`` in program units, ``{}`` for RESET), TNC 640 user's
    manual, "Coordinate transformations: TRANS DATUM", and the TNC7 manual's TRANS MIRROR, TRANS
    ROTATION, TRANS SCALE: the same transformations as cycles 7, 8, 10, 11; ``RESET`` cancels one."""
    m = re.match(r"\s*(DATUM|MIRROR|ROTATION|SCALE)\s*(AXIS|RESET)?\s*", rest, re.I)
    if m is None:
        tok = (rest.split() or ["TRANS"])[0]
        where.fail(f"TRANS {tok} is not supported", column=column0, text=tok,
                   expected="TRANS DATUM, MIRROR, ROTATION or SCALE")
    kind, sub, body = m.group(1).upper(), (m.group(2) or "").upper(), rest[m.end():]
    col = column0 + m.end()
    if kind == "DATUM":
        if sub == "RESET":
            return transform, {}
        shift: dict[str, float] = {}
        for am in re.finditer(r"\s*(I?[XYZ])(?=\s*[+-]?\s*[\d.Q(])", body, re.I):
            shift[am.group(1).upper()] = read_value(body, am.end(), where, params, what=am.group(1),
                                                    column0=col)[0]
        if not shift:
            where.fail("TRANS DATUM without an axis value", column=col, text=body.strip() or "TRANS DATUM",
                       expected="TRANS DATUM AXIS X.. Y.. Z.. or TRANS DATUM RESET (a datum TABLE is not supported)")
        return transform, shift
    default = Transform()
    if sub == "RESET":
        field = {"MIRROR": "mirror", "ROTATION": "rotation", "SCALE": "scale"}[kind]
        return dataclasses.replace(transform, **{field: getattr(default, field)}), None
    number = {"MIRROR": 8, "ROTATION": 10, "SCALE": 11}[kind]
    return transform_item(number, body, transform, where, params, column0=col, scale=scale), None
