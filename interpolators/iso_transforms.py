"""Programmable coordinate transformations of Fanuc and Haas mills: G68 / G69 rotation, G51 / G50
scaling, G51.1 / G50.1 programmable mirror image.

Haas mill operator's manual, "G68 Rotation (Group 16)": ``G17 G68 X.. Y.. R..`` rotates all the
X, Y, Z, I, J and K values of the following blocks about the centre X Y (the two axes of the
selected plane: X Z under G18, Y Z under G19; an axis not given: the current position) by R
degrees, counter-clockwise positive; the values of the G68 block itself are not rotated. R omitted:
the default angle (Haas Setting 72, Fanuc parameter No. 5410), 0 here. Under G91, R is added to the
active angle only with Haas Setting 73 / Fanuc parameter RIN (No. 5400#0) on; both are off by
default, so R is absolute (Fanuc 0i-MF operator's manual, "Coordinate system rotation (G68, G69)").
G69 cancels it. Arcs rotate with their centre; the G68 centre is in the program coordinates of the
active work offset, never incremental.

Scaling (Fanuc 0i-MF operator's manual, "Scaling (G50, G51)"; Haas "G51 Scaling"): ``G51 X Y Z P``
scales about the centre X Y Z (an axis not given: the current position) by P, ``G51 X Y Z I J K``
by a factor per axis (Fanuc); a negative factor mirrors the axis. The Fanuc P, I, J, K written
without a decimal point are in units of 0.001 (parameter SCR No. 5400#7 = 0, the default); Haas P
is the factor itself (omitted: Setting 71, 1 here). An arc under different factors on its two axes
would be an ellipse: an error. G50 cancels.

Programmable mirror image (Fanuc "Programmable mirror image (G50.1, G51.1)"): ``G51.1 X..`` mirrors
the X axis about the line X = the value (likewise Y, Z); ``G50.1 X..`` cancels it for the axes
named. Haas G101 / G100 (Haas mill operator's manual, "G101 Enable Mirror Image": "mirror image
will reflect programmed motion around your work coordinate zero point") mirror / restore the axes
named about 0, the words' values unused. With one axis of the plane mirrored "the direction of
circular interpolation is reversed" (G02 runs as G03) and "the offset direction of cutter
compensation is reversed" (G41 as G42).

In programmable mirror image mode Fanuc refuses the commands that change the coordinate system or return
to a reference position (Fanuc 0i "Programmable mirror image", Limitations: "G codes related to reference
position return (G27, G28, G29, G30, etc.) and those for changing the coordinate system (G52 to G59, G92,
etc.) must not be specified"; the Fanuc-compatible ISO dialect of Sinumerik states the same):
:func:`mirror_forbids` names them, for the ``fanuc`` dialect (a G92 under a mirror would otherwise have
no documented meaning).

When they are combined, Fanuc applies the mirror first, then the scaling, then the rotation: a
program point ``p`` lies at ``rotate(scale(mirror(p)))`` in the untransformed program coordinates;
the reader adds its offsets after that (:meth:`interpolators.iso.State.to_machine`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from interpolators.iso_words import WordError
from toolpaths.geometry import PLANE_AXES

__all__ = ["Frame", "Rotation", "g68_rotation", "scaling", "mirror", "mirror_forbids"]

#: round(10 * G) of the non-modal codes Fanuc refuses under G51.1: G52, G53, G92, G28, G30 (the
#: coordinate-system selections G54-G59, G54.1 are refused as a group).
_MIRROR_FORBIDDEN = frozenset({520, 530, 920, 280, 300})


@dataclasses.dataclass(frozen=True, kw_only=True)
class Rotation:
    """An active G68 rotation.

    Attributes
    ----------
    plane : int
        Plane of rotation: 2 (G17, XY), 1 (G18, ZX) or 0 (G19, YZ).
    centre : tuple of float
        Centre of rotation (x, y, z) [mm, program coordinates]; only the plane's two axes matter.
    angle : float
        Angle [deg], counter-clockwise positive seen from the plane's normal.
    """

    plane: int
    centre: tuple[float, float, float]
    angle: float

    def _turn(self, point: np.ndarray, angle: float) -> np.ndarray:
        out = np.array(point, dtype=float)
        p, q = PLANE_AXES[self.plane]
        c = np.asarray(self.centre, dtype=float)
        a = math.radians(angle)
        cos, sin = math.cos(a), math.sin(a)
        dp, dq = out[p] - c[p], out[q] - c[q]
        out[p], out[q] = c[p] + cos * dp - sin * dq, c[q] + sin * dp + cos * dq
        return out

    def forward(self, point: np.ndarray) -> np.ndarray:
        """Unrotated program coordinates [mm] of a point of the rotated system."""
        return self._turn(point, self.angle)

    def inverse(self, point: np.ndarray) -> np.ndarray:
        """Rotated-system coordinates [mm] of a point in unrotated program coordinates."""
        return self._turn(point, -self.angle)


def g68_rotation(words: dict[str, float], *, plane: int, current: np.ndarray, scale: float) -> Rotation:
    """The rotation a ``G68`` block sets.

    Parameters
    ----------
    words : dict
        The block's words as written (the plane's two axis letters for the centre, ``R`` the angle).
    plane : int
        Active plane (2 G17, 1 G18, 0 G19), after the block's own plane code.
    current : ndarray (3,)
        Current position [mm, unrotated program coordinates]: the centre's default.
    scale : float
        mm per program unit.
    """
    centre = np.array(current, dtype=float)
    for i in PLANE_AXES[plane]:
        letter = "XYZ"[i]
        if letter in words:
            centre[i] = words[letter] * scale
    return Rotation(plane=plane, centre=tuple(float(v) for v in centre), angle=float(words.get("R", 0.0)))


@dataclasses.dataclass(frozen=True, kw_only=True)
class Frame:
    """The active transformations of the program coordinates (all [mm, program coordinates]).

    Attributes
    ----------
    mirror : tuple of bool
        Axes (x, y, z) mirrored by G51.1.
    mirror_at : tuple of float
        Positions of the mirror lines [mm].
    factors : tuple of float
        Scaling factors per axis [-] (G51; 1: none).
    scale_centre : tuple of float
        Centre of the scaling [mm].
    rotation : Rotation or None
        The G68 rotation.
    """

    mirror: tuple[bool, bool, bool] = (False, False, False)
    mirror_at: tuple[float, float, float] = (0.0, 0.0, 0.0)
    factors: tuple[float, float, float] = (1.0, 1.0, 1.0)
    scale_centre: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: Rotation | None = None

    @property
    def identity(self) -> bool:
        """True when nothing is transformed."""
        return not any(self.mirror) and self.factors == (1.0, 1.0, 1.0) and self.rotation is None

    @property
    def scaled(self) -> bool:
        """True when a scaling is active."""
        return self.factors != (1.0, 1.0, 1.0)

    def forward(self, point: np.ndarray) -> np.ndarray:
        """Untransformed program coordinates [mm] of a programmed point."""
        p = np.where(self.mirror, 2.0 * np.asarray(self.mirror_at) - point, np.asarray(point, dtype=float))
        c = np.asarray(self.scale_centre)
        p = c + np.asarray(self.factors) * (p - c)
        return p if self.rotation is None else self.rotation.forward(p)

    def inverse(self, point: np.ndarray) -> np.ndarray:
        """The programmed point [mm] at untransformed program coordinates ``point``."""
        p = np.asarray(point, dtype=float) if self.rotation is None else self.rotation.inverse(point)
        c = np.asarray(self.scale_centre)
        p = c + (p - c) / np.asarray(self.factors)
        return np.where(self.mirror, 2.0 * np.asarray(self.mirror_at) - p, p)

    def flips(self, plane: int) -> bool:
        """True when arcs in ``plane`` turn the other way (an odd number of its axes mirrored)."""
        p, q = PLANE_AXES[plane]
        sign = [(-1.0 if m else 1.0) * f for m, f in zip(self.mirror, self.factors)]
        return (sign[p] < 0) != (sign[q] < 0)

    def length_factor(self, plane: int) -> float | None:
        """Factor of lengths in ``plane`` (an arc's R) [-], or None when its two axes scale differently."""
        p, q = PLANE_AXES[plane]
        a, b = abs(self.factors[p]), abs(self.factors[q])
        return a if a == b else None


def _factor(words: dict[str, float], texts: dict[str, str], letter: str, *, thousandths: bool) -> float:
    value = words[letter]
    if thousandths and "." not in texts[letter]:
        value /= 1000.0
    if value == 0:
        raise WordError(f"scaling factor {letter} must not be 0", letter=letter, expected=f"{letter} != 0")
    return value


def scaling(frame: Frame, words: dict[str, float], texts: dict[str, str], *, current: np.ndarray, scale: float,
            thousandths: bool) -> Frame:
    """The frame after a ``G51`` block.

    Parameters
    ----------
    frame : Frame
        The active frame.
    words, texts : dict
        The block's words as written: values and texts (``P1500`` and ``P1.5`` differ on a Fanuc).
    current : ndarray (3,)
        Current position [mm, program coordinates]: the centre's default.
    scale : float
        mm per program unit.
    thousandths : bool
        P I J K without a decimal point count 0.001 (Fanuc), rather than 1 (Haas).
    """
    centre = np.array(current, dtype=float)
    for i, letter in enumerate("XYZ"):
        if letter in words:
            centre[i] = words[letter] * scale
    if "P" in words and any(k in words for k in "IJK"):
        raise WordError("G51 with both P and I J K", letter="P", expected="P (all axes) or I J K (per axis)")
    if "P" in words:
        f = _factor(words, texts, "P", thousandths=thousandths)
        factors = (f, f, f)
    elif any(k in words for k in "IJK"):
        factors = tuple(_factor(words, texts, k, thousandths=thousandths) if k in words else 1.0 for k in "IJK")
    else:
        factors = (1.0, 1.0, 1.0)
    return dataclasses.replace(frame, factors=factors, scale_centre=tuple(float(v) for v in centre))


def mirror(frame: Frame, words: dict[str, float], *, on: bool, scale: float) -> Frame:
    """The frame after ``G51.1`` (``on``) or ``G50.1``: the axes named are mirrored about their value,
    or no longer mirrored."""
    named = [i for i, letter in enumerate("XYZ") if letter in words]
    if not named:
        raise WordError("no axis word", letter=None, expected="X.., Y.. or Z.. (the mirror line)")
    flags, at = list(frame.mirror), list(frame.mirror_at)
    for i in named:
        flags[i] = on
        at[i] = words["XYZ"[i]] * scale if on else 0.0
    return dataclasses.replace(frame, mirror=tuple(flags), mirror_at=tuple(at))


def mirror_forbids(frame: Frame | None, groups: dict[str, int]) -> str | None:
    """The modal group of a block's code Fanuc refuses in programmable mirror image mode (G51.1 on an axis
    of ``frame``), or None. ``groups`` maps a block's modal groups to round(10 * G) of their code."""
    if frame is None or not any(frame.mirror):
        return None
    if "coordinate system" in groups:
        return "coordinate system"
    return "nonmodal" if groups.get("nonmodal") in _MIRROR_FORBIDDEN else None
