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
from the datum outwards: shift (cycle 7, :class:`interpolators.heidenhain.Machine` keeps it),
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
from interpolators.tilted import (
    ANGLE_TOLERANCE,
    Kinematics,
    Solution,
    TiltError,
    euler,
    points,
    projected,
    relative,
    spatial,
    vector,
)
from toolpaths.geometry import PLANE_AXES

__all__ = ["Transform", "TransformError", "TRANSFORM_CYCLES", "transform_item", "tilt_block", "trans_block",
           "PlaneBlock", "PLANE_FORMS", "read_plane", "axial_angles", "KINEMATICS_HINT", "plane_rotation",
           "TiltedPlane"]


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
    tilt : float
        Turn of the tilted working plane's X about the machine's tool axis [deg] (``theta`` of
        :func:`interpolators.tilted.tilted_frame`), applied last: the tilted plane of a tilting table
        runs in the machine's plane, turned by it. 0 without a tilted plane.
    """

    mirror: tuple[bool, bool, bool] = (False, False, False)
    rotation: float = 0.0
    scale: float = 1.0
    axis_scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tilt: float = 0.0

    @property
    def identity(self) -> bool:
        """True when no transformation is active."""
        return (not any(self.mirror) and self.rotation == 0.0 and self.scale == 1.0
                and self.axis_scale == (1.0, 1.0, 1.0) and self.tilt == 0.0)

    def turn(self, offset: np.ndarray, plane: int, *, inverse: bool = False) -> np.ndarray:
        """``offset`` [mm] turned by :attr:`tilt` in the working plane (back with ``inverse``)."""
        v = np.array(offset, dtype=float)
        if self.tilt == 0.0:
            return v
        p, q = PLANE_AXES[plane]
        a = math.radians(-self.tilt if inverse else self.tilt)
        cos, sin = math.cos(a), math.sin(a)
        v[p], v[q] = cos * v[p] - sin * v[q], sin * v[p] + cos * v[q]
        return v

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
        return self.turn(np.where(self.mirror, -v, v), plane)

    def invert(self, offset: np.ndarray, plane: int) -> np.ndarray:
        """The program point [mm, from the datum] at the machine-axis offset ``offset`` [mm]."""
        offset = self.turn(offset, plane, inverse=True)
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
        return a + self.tilt

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

#: How to give vcnc a machine whose table tilts (the error of a tilt without kinematics says it).
KINEMATICS_HINT = ("a machine with [program.kinematics] (vcnc machines --show: the rotary axes that tilt the "
                   "part), or 3-axis machining: PLANE RESET, PLANE .. with all angles 0")


def tilt_block(kw: str, rest: str, where: Where, params: QParameters, *, column0: int) -> str:
    """``PLANE ...``, ``FUNCTION ...`` on a machine without kinematics: the note of a block that tilts
    nothing, else an error naming it.

    TNC 640 user's manual, "Tilting the working plane (software option 1)": ``PLANE RESET`` cancels
    a tilt; ``PLANE SPATIAL/PROJECTED/EULER/RELATIVE/AXIAL`` with all angles 0 keeps the tool axis
    (no tilt; vcnc moves no rotary axis for it); any other angle and ``PLANE VECTOR``/``POINTS`` need
    the machine's kinematics (``MachineContext.kinematics``: :func:`read_plane` then reads them);
    ``FUNCTION TCPM`` (tool centre point management, as ``M128``) is not supported. ``FUNCTION
    RESET TCPM`` and ``FUNCTION MODE MILL`` change nothing on a milling machine.
    """
    words = rest.split()
    form = words[0].upper() if words else ""
    what = f"{kw} {form}".strip()
    if kw == "FUNCTION":
        second = words[1].upper() if len(words) > 1 else ""
        if (form, second) in (("RESET", "TCPM"), ("MODE", "MILL")):
            return f"{kw} {form} {second}: no motion"
        if form in _NO_MOTION_FUNCTIONS:
            return f"{kw} {form}: {_NO_MOTION_FUNCTIONS[form]} (no motion)"
        if form in ("PARAXCOMP", "PARAXMODE"):
            return _parallel_axes(form, second, where, column0=column0)
        where.fail(f"{what} is not supported", column=column0, text=what,
                   expected="a FUNCTION vcnc runs: TCPM, RESET TCPM, DWELL, FEED DWELL, MODE MILL, "
                            + ", ".join(_NO_MOTION_FUNCTIONS))
    if form == "RESET":
        return "PLANE RESET: no tilted working plane (no motion)"
    if form in ("SPATIAL", "PROJECTED", "EULER", "RELATIVE", "RELATIV", "AXIAL"):
        nonzero = [am.group(1).upper() for am in _TILT_ANGLE_RE.finditer(rest)
                   if read_value(rest, am.end(), where, params, what=am.group(1), column0=column0)[0] != 0.0]
        if not nonzero:
            return f"{what} with angles 0: no tilt (no motion)"
    where.fail(f"{what} (a tilted working plane) is not supported without the machine's kinematics", column=column0,
               text=what, expected=KINEMATICS_HINT)
    raise AssertionError("unreachable")  # pragma: no cover


def _parallel_axes(form: str, second: str, where: Where, *, column0: int) -> str:
    """``FUNCTION PARAXCOMP DISPLAY|MOVE|OFF``, ``FUNCTION PARAXMODE ..|OFF``: the note of a block that moves
    nothing, else an error naming it.

    TNC7 basic user's manual 81762x-19, "Defining behavior when positioning parallel axes with FUNCTION
    PARAXCOMP": DISPLAY "includes movements of the parallel axis in the position display of the associated main
    axis" (the display only), MOVE "compensate[s] for movements of a parallel axis by performing compensation
    movements in the associated main axis", OFF switches both off; FUNCTION PARAXMODE selects the parallel axis
    that machines in place of a main axis, PARAXMODE OFF ends it. CAM posts write the OFF forms as resets in a
    program's header. What moves the main axes otherwise (MOVE, a PARAXMODE with axes) is not modelled: an error."""
    what = f"FUNCTION {form} {second}".strip()
    if second == "OFF":
        return f"{what}: parallel axes as programmed (no motion)"
    if form == "PARAXCOMP" and second == "DISPLAY":
        return f"{what}: the parallel axis summed into the main axis' display only (no motion)"
    why = ("the main axis moving against the parallel axis" if form == "PARAXCOMP" and second == "MOVE"
           else "a parallel axis machining in place of a main axis" if form == "PARAXMODE"
           else "expected DISPLAY, MOVE or OFF")
    where.fail(f"{what} ({why}) is not supported", column=column0, text=what,
               expected="FUNCTION PARAXCOMP DISPLAY / OFF, FUNCTION PARAXMODE OFF (no motion)")
    raise AssertionError("unreachable")  # pragma: no cover


#: FUNCTION blocks that do not move the tool in a program run (TNC 640 user's manual): what they do.
_NO_MOTION_FUNCTIONS = {
    "LIFTOFF": "the lift-off of the tool at an NC stop",  # "Lifting off the tool at an NC stop: FUNCTION LIFTOFF"
    "S-PULSE": "a pulsing spindle speed",  # "Pulsing spindle speed FUNCTION S-PULSE"
    "COUNT": "the machining counter",  # "Defining a counter: FUNCTION COUNT"
    # "File functions": copy, move or delete a file from the NC program (TNC 640 / TNC 620 user's manuals,
    # special functions; Autodesk Fusion's heidenhain.cps copies a probing cycle's TCHPRnnn.TXT log this way)
    "FILECOPY": "a file copied",
    "FILEMOVE": "a file moved",
    "FILEDELETE": "a file deleted",
}


#: The value words of each PLANE form (TNC 640 / iTNC 530 user's manuals, "The PLANE function").
PLANE_FORMS: dict[str, tuple[str, ...]] = {
    "SPATIAL": ("SPA", "SPB", "SPC"),
    "PROJECTED": ("PROPR", "PROMIN", "ROT"),
    "EULER": ("EULPR", "EULNU", "EULROT"),
    "VECTOR": ("BX", "BY", "BZ", "NX", "NY", "NZ"),
    "POINTS": tuple(f"P{i}{a}" for i in "123" for a in "XYZ"),
    "RELATIVE": ("SPA", "SPB", "SPC"),
    "AXIAL": ("A", "B", "C", "IA", "IB", "IC"),
    "RESET": (),
}
_PLANE_FORM_RE = re.compile(r"\s*(SPATIAL|PROJECTED|EULER|VECTOR|POINTS|RELATIVE?|AXIAL|RESET)\b", re.I)
_PLANE_WORD_RE = re.compile(
    r"\s*(MOVE|TURN|STAY|COORD\s+ROT|TABLE\s+ROT|MB\s*MAX|F\s*MAX|FMAX|F\s*AUTO|SEQ\s*[+-]|SYM\s*[+-]"
    r"|DIST|ABST|MB|F|SPA|SPB|SPC|PROPR|PROMIN|EULPR|EULNU|EULROT|ROT|BX|BY|BZ|NX|NY|NZ|P[123][XYZ]|I?[ABC])"
    r"(?![A-Z])", re.I)


@dataclasses.dataclass(frozen=True, kw_only=True)
class PlaneBlock:
    """A ``PLANE`` block as written.

    Attributes
    ----------
    form : str
        ``SPATIAL``, ``PROJECTED``, ``EULER``, ``VECTOR``, ``POINTS``, ``RELATIVE``, ``AXIAL`` or ``RESET``.
    values : dict of str to float
        The form's values (``SPA`` .. [deg], ``P1X`` .. [program units], vector components [-]).
    positioning : str or None
        ``MOVE``, ``TURN``, ``STAY``, or None when the block has none.
    dist : float
        ``DIST``: distance of the centre of rotation from the tool tip for MOVE [program units].
    feed : float or None
        ``F`` [program units/min], ``inf`` for ``FMAX``, None when not written.
    retract : float or None
        ``MB``: retraction along the tool axis before positioning [program units], ``inf`` for ``MB MAX``.
    sequence : int
        ``SEQ+``/``SYM+``: +1, ``SEQ-``/``SYM-``: -1, else 0.
    table_rot : bool
        ``TABLE ROT`` (the rotary table turns for a turn about the tool axis) rather than ``COORD ROT``.
    """

    form: str
    values: dict[str, float]
    positioning: str | None = None
    dist: float = 0.0
    feed: float | None = None
    retract: float | None = None
    sequence: int = 0
    table_rot: bool = False


def read_plane(rest: str, where: Where, params: QParameters, *, column0: int) -> PlaneBlock:
    """Read ``PLANE <form> <values> [MOVE|TURN|STAY] [DIST..] [MB..] [F..|FMAX] [SEQ±|SYM±] [COORD|TABLE ROT]``.

    TNC 640 / iTNC 530 user's manuals, "The PLANE function: Tilting the working plane": the forms and
    their values (:data:`PLANE_FORMS`), then the positioning behaviour ("Specifying the positioning
    behavior of the PLANE function"), the choice of solution (SEQ; TNC 640: SYM) and the type of
    transformation (COORD ROT, TABLE ROT). A word of another form, or an unknown word, is an error.
    """
    fm = _PLANE_FORM_RE.match(rest)
    if fm is None:
        tok = (rest.split() or ["PLANE"])[0]
        where.fail(f"PLANE {tok} is not a PLANE function", column=column0, text=tok,
                   expected="PLANE SPATIAL, PROJECTED, EULER, VECTOR, POINTS, RELATIV, AXIAL or RESET")
    form = fm.group(1).upper()
    form = "RELATIVE" if form.startswith("RELATIV") else form
    out: dict = {"form": form, "values": {}}
    pos = fm.end()
    while rest[pos:].strip():
        wm = _PLANE_WORD_RE.match(rest, pos)
        if wm is None:
            tok = rest[pos:].split()[0]
            where.fail(f"unexpected {tok!r} in PLANE {form}", column=column0 + pos, text=tok,
                       expected=f"PLANE {form} {' '.join(PLANE_FORMS[form])} MOVE|TURN|STAY [DIST] [MB] [F|FMAX] "
                                "[SEQ+|SEQ-] [COORD ROT|TABLE ROT]")
        word = re.sub(r"\s+", "", wm.group(1).upper())
        pos = wm.end()
        if word in ("MOVE", "TURN", "STAY"):
            out["positioning"] = word
        elif word in ("COORDROT", "TABLEROT"):
            out["table_rot"] = word == "TABLEROT"
        elif word in ("MBMAX", "FMAX"):
            out["retract" if word == "MBMAX" else "feed"] = math.inf
        elif word == "FAUTO":
            where.fail("F AUTO in a PLANE block is not supported", column=column0 + wm.start(1), text=word,
                       expected="F<feed> or FMAX")
        elif word[:3] in ("SEQ", "SYM"):
            out["sequence"] = 1 if word[3] == "+" else -1
        else:
            value, pos = read_value(rest, pos, where, params, what=word, column0=column0)
            key = {"ABST": "dist", "DIST": "dist", "MB": "retract", "F": "feed"}.get(word)
            if key == "feed" and not value > 0:
                where.fail(f"feed F of PLANE {form} must be > 0", column=column0 + wm.start(1),
                           text=rest[wm.start(1):pos].strip(), expected="F > 0 [mm/min] or FMAX")
            if key is not None:
                out[key] = abs(value) if key == "retract" else value
            elif word in PLANE_FORMS[form]:
                out["values"][word] = value
            else:
                where.fail(f"{word} is not a value of PLANE {form}", column=column0 + wm.start(1), text=word,
                           expected=f"PLANE {form} {' '.join(PLANE_FORMS[form])}")
    return PlaneBlock(**out)


@dataclasses.dataclass(frozen=True, kw_only=True)
class TiltedPlane:
    """The active tilted working plane of a tilting table (:mod:`interpolators.tilted`).

    Attributes
    ----------
    rotation : ndarray (3, 3)
        Working-plane rotation (columns: tilted X, Y, Z in the untilted workpiece coordinates).
    angles : dict of int to float
        The rotary axes' positions the plane needs, by column of ``Block.extra_target`` [deg].
    datum : ndarray (3,)
        Machine position of the tilted plane's zero at those positions, without tool length [mm].
    base_shift : ndarray (3,)
        The datum shift (cycle 7) active when the plane was tilted, in the untilted coordinates [mm]:
        back in force at ``PLANE RESET`` unless a datum shift was programmed in the tilted plane.
    what : str
        The block that tilted it (``PLANE SPATIAL``, ``CYCL DEF 19``) and its line, for messages.
    shifted : bool
        A datum shift (cycle 7, ``TRANS DATUM``) was programmed in the tilted plane.
    """

    rotation: np.ndarray
    angles: dict[int, float]
    datum: np.ndarray
    base_shift: np.ndarray
    what: str
    shifted: bool = False

    def holds(self, extra: np.ndarray) -> bool:
        """True when the rotary axes at ``extra`` [deg, by column] are at the plane's positions (a whole turn
        apart is the same position of the table: C+270 holds for C-90)."""
        return all(abs(math.remainder(float(extra[i]) - a, 360.0)) <= 1e-6 for i, a in self.angles.items())


def plane_rotation(block: PlaneBlock, *, active: np.ndarray, kinematics: Kinematics,
                   current: Solution) -> np.ndarray | None:
    """The working-plane rotation (columns: tilted X, Y, Z in the untilted workpiece coordinates) of a
    ``PLANE`` block, None for ``PLANE RESET``; ``active``: the rotation of the active tilt (identity
    without one), which ``PLANE RELATIV`` turns further; ``current``: the rotary axes' positions [deg],
    which ``PLANE AXIAL`` keeps for an axis it does not name (:mod:`interpolators.tilted`)."""
    v = block.values
    if block.form == "RESET":
        return None
    if block.form == "SPATIAL":
        return spatial(v.get("SPA", 0.0), v.get("SPB", 0.0), v.get("SPC", 0.0))
    if block.form == "PROJECTED":
        for key in ("PROPR", "PROMIN"):  # iTNC 530 user's manual, PLANE PROJECTED: "Input range: -89.9999 to
            if abs(v.get(key, 0.0)) >= 90.0:  # +89.9999" (a trace at 90 deg is the tool axis itself)
                raise TiltError(f"PLANE PROJECTED {key}{v[key]:+g}: a projection angle of 90 deg or more",
                                f"{key} within -89.9999..+89.9999 deg")
        return projected(v.get("PROPR", 0.0), v.get("PROMIN", 0.0), v.get("ROT", 0.0))
    if block.form == "EULER":
        return euler(v.get("EULPR", 0.0), v.get("EULNU", 0.0), v.get("EULROT", 0.0))
    if block.form == "VECTOR":
        return vector([v.get(k, 0.0) for k in ("BX", "BY", "BZ")], [v.get(k, 0.0) for k in ("NX", "NY", "NZ")])
    if block.form == "POINTS":
        return points(*([v.get(f"P{i}{a}", 0.0) for a in "XYZ"] for i in "123"))
    if block.form == "RELATIVE":
        if len(v) != 1:
            raise TiltError(f"PLANE RELATIV with {len(v)} angles", "one incremental angle: SPA, SPB or SPC")
        (key, angle), = v.items()
        return relative(active, "XYZ"["ABC".index(key[-1])], angle)
    return kinematics.axial(axial_angles(block, kinematics=kinematics, current=current))


def axial_angles(block: PlaneBlock, *, kinematics: Kinematics, current: Solution) -> Solution:
    """The rotary positions of ``PLANE AXIAL A.. B.. C..`` [deg]: the angles written, an axis not written where it is
    (``current``), an incremental one (``IB+10``) from where it is. TNC7 basic user's manual 81762x-19, "PLANE AXIAL":
    the function defines "the working plane with anywhere from one to three absolute or incremental axis angles";
    "Axis angles define both the orientation of the working plane as well as the nominal coordinates of the rotary
    axes", and an angle of an axis the machine does not have is an error. The control takes them as they are, not the
    other solution of the same tool axis (SEQ and the nearest solution choose among the solutions of the other PLANE
    forms), and not a turn of 360 deg to within the limits: an angle outside them is an error.

    Raises
    ------
    TiltError
        No angle, an axis the kinematics lacks, or an angle outside its axis' limits.
    """
    names, v = kinematics.names, block.values
    if not v:
        raise TiltError("PLANE AXIAL without an axis angle (it defines the plane by one to three of them)",
                        "PLANE AXIAL " + " ".join(f"{n.upper()}.." for n in names))
    for key in v:
        if key[-1].lower() not in names:
            raise TiltError(f"PLANE AXIAL {key}: no rotary axis {key[-1]} in the machine's kinematics",
                            "PLANE AXIAL " + " ".join(f"{n.upper()}.." for n in names), letter=key)
        if key[-1] in v and "I" + key[-1] in v:
            raise TiltError(f"PLANE AXIAL with both {key[-1]} and I{key[-1]}", f"{key[-1]} or I{key[-1]}, once",
                            letter=key)
    now = (current.outer, current.inner)
    at = [v.get(n.upper(), now[i] + v.get("I" + n.upper(), 0.0)) for i, n in enumerate(names)]
    for axis, angle in zip(kinematics.axes, at, strict=True):
        lo, hi = axis.limits
        if not lo - ANGLE_TOLERANCE <= angle <= hi + ANGLE_TOLERANCE:
            raise TiltError(f"PLANE AXIAL {axis.name.upper()}{angle:+g} is outside the axis' limits {lo:g}..{hi:g} deg",
                            f"an angle of {axis.name.upper()} within {lo:g}..{hi:g} deg", letter=axis.name.upper())
    return Solution(outer=at[0], inner=at[-1] if len(at) == 2 else 0.0)


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
