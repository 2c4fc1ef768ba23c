"""Axis words beyond X, Y, Z of the ISO reader: rotary A, B, C and secondary linear U, V, W.

Semantics follow LinuxCNC (G-code overview, "Feed Rate", https://linuxcnc.org/docs/html/gcode/
overview.html#sub:feed-rate, and "Coordinate Systems", https://linuxcnc.org/docs/html/gcode/
coordinates.html) and RS274/NGC 3 (Kramer, Proctor, Messina, NISTIR 6556, 2000, Sec. 2.1.2.5
"Feed Rate"):

* A, B, C are angles [deg] (never scaled by G20); U, V, W are linear axes parallel to X, Y, Z
  [mm, or inches under G20]. All are absolute under G90 and incremental under G91; G53 takes
  them as machine positions.
* Offsets: like X, Y, Z, each has a work offset (0 in the machine's table, which holds X, Y, Z;
  ``G10 L2``/``L20`` set it) and a G92 offset, added to the programmed value (LinuxCNC
  ``emccanon.cc`` ``rotate_and_offset_pos``: ``g92Offset`` and ``g5xOffset`` of all nine axes;
  the G10 R rotation turns X and Y only). The tool length applies to Z only.
* With X, Y or Z moving, F applies to the XYZ path "as if the rotational axes were not moving";
  the other axes move in proportion (coordinated). With X, Y, Z still and U, V or W moving, F
  (mm/min) applies along ``sqrt(dU^2 + dV^2 + dW^2)``, the rotary axes in proportion. With only
  rotary axes moving, F is in deg/min along ``sqrt(dA^2 + dB^2 + dC^2)``. Under G93 (inverse
  time) the block takes ``1/F`` minutes either way.

LinuxCNC's canon does the same (``src/emc/task/emccanon.cc``: ``SET_FEED_RATE`` keeps a linear
feed converted from program units and an angular feed in deg/min; ``getStraightVelocity`` calls a
move with X/Y/Z or U/V/W "cartesian" and measures it along XYZ if they move, else along UVW, a
move of A/B/C alone "angular", measured along ``sqrt(da^2 + db^2 + dc^2)``, citing NIST IR 6556
Sec. 2.1.2.5).

A rotary axis the machine wraps at 360 deg (``MachineContext.wrapped_axes``) ends an absolute or G53 word by the
machine's rule (:func:`wrapped_target`, :mod:`interpolators.rotary_wrap`); G91 turns it by the word.

A machine (:class:`interpolators.context.MachineContext`) names the extra axes it has; a word of
another axis is an error naming it (a word ``A0`` or ``U0`` on a machine without the axis is
accepted with a note, as CAM posts write it on 3-axis work).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from interpolators.program import Block
from interpolators.rotary_wrap import ROTARY_AXES, default_direction, wrap_reference, wrap_words
from vcnc.core.axes import EXTRA_NAMES

__all__ = ["EXTRA_LETTERS", "ROTARY_LETTERS", "word_values", "extra_target", "wrapped_target", "wrapped_reference",
           "reference_turns", "refuse_wrapped_offset", "fill_extra"]

#: Axis words beyond X, Y, Z, in the column order of ``Block.extra_start`` / ``extra_target``.
EXTRA_LETTERS: str = "".join(EXTRA_NAMES).upper()

#: The rotary axis words (angles [deg], never scaled by G20).
ROTARY_LETTERS: str = "ABC"


def word_values(values: dict[str, float], *, scale: float) -> np.ndarray:
    """The words ``values`` (letter -> value) as positions ``(a, b, c, u, v, w)`` [deg, mm]: U, V, W
    times ``scale`` (millimetres per program unit, 25.4 under G20), A, B, C as they are; NaN for an
    axis without a word."""
    out = np.full(len(EXTRA_LETTERS), np.nan)
    for letter, v in values.items():
        out[EXTRA_LETTERS.index(letter)] = v if letter in ROTARY_LETTERS else v * scale
    return out


def extra_target(values: dict[str, float], current: np.ndarray, offset: np.ndarray, *, incremental: bool,
                 scale: float, machine: bool = False) -> np.ndarray:
    """End positions ``(a, b, c, u, v, w)`` [deg, mm] of a block with the axis words ``values``.

    Parameters
    ----------
    values : dict of str to float
        The block's words of the extra axes (``"A"`` ... ``"W"``) [deg; program units for U V W].
    current : ndarray, shape (6,)
        Positions before the block [deg, mm; machine].
    offset : ndarray, shape (6,)
        Machine minus program position of each axis (work offset plus G92 offset) [deg, mm].
    incremental : bool
        G91: the words are added to ``current``.
    scale : float
        Millimetres per program unit (25.4 under G20); applies to U, V, W only.
    machine : bool
        G53: the words are machine positions (absolute, whatever the distance mode).
    """
    v = word_values(values, scale=scale)
    given = ~np.isnan(v)
    target = np.array(current, dtype=float)
    if machine:
        target[given] = v[given]
    elif incremental:
        target[given] = target[given] + v[given]
    else:
        target[given] = v[given] + np.asarray(offset, dtype=float)[given]
    return target


def wrapped_target(target: np.ndarray, words: dict, st, where, *, machine: bool = False) -> np.ndarray:
    """``target`` (:func:`extra_target`'s ends of the block's words ``words``, letter -> word) with the absolute
    (G90 or G53: ``machine``) words of the axes the machine wraps at 360 deg ended by its rule
    (:func:`interpolators.rotary_wrap.wrap_words`; ``st``: the reader's state, before the block)."""
    ctx = st.context
    if not ctx.wrapped_axes or (st.incremental and not machine):
        return target
    offset = np.zeros(len(EXTRA_LETTERS)) if machine else st.extra_offset()
    direction = _direction(ctx)
    return wrap_words(target, words, st.extra, offset, wrapped=ctx.wrapped_axes, direction=direction, where=where,
                      linuxcnc_offset=_linuxcnc_offset(st, direction) if machine else None)


def _direction(ctx) -> str:
    """The machine's rule for its wrapping axes: its ``wrap_direction``, else its control's own
    (:func:`interpolators.rotary_wrap.default_direction`)."""
    return ctx.wrap_direction or default_direction(ctx.dialect.name)


def _linuxcnc_offset(st, direction: str) -> np.ndarray | None:
    """The program offset LinuxCNC subtracts from a machine-coordinate word of a wrapped axis
    (:func:`interpolators.rotary_wrap.linuxcnc_machine_word`), under its own rule only."""
    return st.extra_offset() if st.context.dialect.name == "linuxcnc" and direction == "sign" else None


def wrapped_reference(target: np.ndarray, st, moving: tuple[str, ...] = ROTARY_AXES) -> np.ndarray:
    """``target`` (the reference positions of G28/G30 [deg, mm; machine]) with the ``moving`` axes the machine
    wraps ended by its rule (:func:`interpolators.rotary_wrap.wrap_reference`)."""
    ctx = st.context
    if not ctx.wrapped_axes:
        return target
    direction = _direction(ctx)
    return wrap_reference(target, st.extra, wrapped=ctx.wrapped_axes, moving=moving, direction=direction,
                          linuxcnc_offset=_linuxcnc_offset(st, direction))


def reference_turns(st, names: tuple[str, ...]) -> dict[str, Callable[[float], float]]:
    """For each of the rotary axes ``names`` the machine wraps at 360 deg, the turn [deg] it makes to a machine angle
    reached as :func:`wrapped_reference` reaches it (G53.1 turning the axes to a tilted plane): what
    :meth:`interpolators.tilted.Kinematics.choose` weighs the solutions by."""
    def turn(name: str) -> Callable[[float], float]:
        i = EXTRA_LETTERS.index(name.upper())

        def to(angle: float) -> float:
            target = st.extra.copy()
            target[i] = angle
            return float(wrapped_reference(target, st, (name,))[i] - st.extra[i])
        return to

    return {a: turn(a) for a in names if a in st.context.wrapped_axes}


def refuse_wrapped_offset(seen: dict, st, where, code: str) -> None:
    """LinuxCNC refuses a ``code`` (G92, G52, G10 L20) word of magnitude 360 deg or more on a wrapped axis
    (``interp_convert.cc`` ``convert_axis_offsets`` and ``convert_setup``: "Invalid absolute position .. for wrapped
    rotary axis A"); the other controls are not known to."""
    ctx = st.context
    if ctx.dialect.name != "linuxcnc" or not ctx.wrapped_axes:
        return
    for k in ROTARY_LETTERS:
        w = seen.get(k)
        if w is not None and k.lower() in ctx.wrapped_axes and not abs(w.value) < 360.0:
            where.fail(f"{code}: invalid absolute position {w.value:g} for wrapped rotary axis {k}", column=w.column,
                       text=w.text, expected=f"-360 < {k} < 360 on an axis that wraps at 360 deg")


def fill_extra(blocks: list[Block]) -> list[Block]:
    """Blocks with the extra axes' positions of every block set: a block the reader left without
    them (no extra axis word: a dwell, a cycle move, a compensation corner) holds the axes where
    the previous block left them (0 at program start)."""
    out: list[Block] = []
    current = np.zeros(len(EXTRA_LETTERS))
    for b in blocks:
        if b.extra_target is None:
            out.append(dataclasses.replace(b, extra_start=current.copy(), extra_target=current.copy()))
        else:
            out.append(b)
            current = np.array(b.extra_target, dtype=float)
    return out
