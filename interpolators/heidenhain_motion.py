"""Motion blocks of Heidenhain conversational programs: ``L``, ``LN``, ``C``, ``CR``, ``CT``, ``CTP``, ``LP``,
``CP`` (about the pole ``CC``), ``RND`` / ``CHF``, ``SPL``, the FK blocks' glue to :mod:`interpolators.heidenhain_fk`,
``APPR`` / ``DEP``, the M functions of a block (``M91``/``M92``, ``M94``, ``M103``, ``M112``/``M113``, ``M120``,
``M128``/``M129``, ``M136``/``M137``, ``M140``, ``M89``/``M99`` cycle calls) and the words of a block (``F AUTO``,
``FU``), on the machine state :class:`interpolators.heidenhain.Machine`. The manual sections are in each
function's docstring; the blocks are listed in :mod:`interpolators.heidenhain`'s docstring.
"""
from __future__ import annotations

import dataclasses
import math
import re
from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.arcs import ArcWordError, arc_from_center, arc_from_radius
from interpolators.heidenhain_compensation import finish_compensation, set_compensation
from interpolators.heidenhain_cycle_calls import cycle_call
from interpolators.heidenhain_fk import read_fk_words
from interpolators.heidenhain_paths import (
    PathGeometryError,
    approach_lct,
    approach_start,
    arc_end_tolerance,
    chamfer_corner,
    contour_arc_radius,
    departure_element,
    departure_lct,
    end_tangent,
    helical_arc,
    polar_angle,
    polar_point,
    round_elements,
    tangential_arc,
)
from interpolators.heidenhain_splines import SPLINE_START_TOLERANCE, read_spline, spline_points
from interpolators.heidenhain_targets import plane_coords, program_target
from interpolators.heidenhain_tcpm import (
    TCPM_EXPECTED,
    check_tcpm_on,
    spatial_axes,
    still_in_tilted_plane,
    tcpm_line,
    tilt_turns,
    tool_vector,
)
from interpolators.heidenhain_words import EMPTY_FIELD_NOTE, SourceBlock, Word, ignored_m_note, read_value, read_words
from interpolators.iso_axes import EXTRA_LETTERS, ROTARY_LETTERS
from interpolators.iso_splines import SPLINE_TOLERANCE
from interpolators.rotary_wrap import wrap_words
from interpolators.tcp import machine_point, part_point
from toolpaths.geometry import PLANE_AXES, Arc, Line

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine

__all__ = ["block_words", "spline_block", "m_functions", "corner_def", "motion_block", "free_contour",
           "approach_depart", "is_retract_feed", "block_end_retract"]


#: M functions with a meaning here; any other M (spindle, coolant, clamping, ...) is noted and ignored.
_M_END = (2, 30)
_M_STOP = (0, 1)


def block_words(code: str, pos: int, where: Where, m: Machine, *, column0: int) -> list[Word]:
    """The words of a block, ``F AUTO`` read as the feed of the last ``TOOL CALL .. F`` (TNC 640
    user's manual, "Feed rate F": "F AUTO: the feed rate defined in the TOOL CALL block") and ``FU``
    (feed per spindle revolution [mm/rev]) as ``F`` = FU x the TOOL CALL's S [mm/min]; ``FZ`` (per
    tooth) needs the tool's number of teeth, which vcnc's tool table does not hold: an error."""
    words = read_words(code, pos, where, m.params, column0=column0)
    for w in words:
        if w.key == "M" and w.value in (136, 137):  # effective at the start of the block
            m.per_revolution = w.value == 136
    if m.per_revolution:
        words = [Word("FU", w.value, w.column, w.text) if w.key == "F" else w for w in words]
    if any(w.key == "EMPTY" for w in words):
        m.note(EMPTY_FIELD_NOTE)
        words = [w for w in words if w.key != "EMPTY"]
    for i, w in enumerate(words):
        if w.key == "FZ":
            where.fail("FZ (feed per tooth) needs the tool's number of teeth", column=w.column, text=w.text,
                       expected="F <mm/min> or FU <mm/rev>")
        if w.key == "FU":
            if not m.spindle:
                where.fail(f"{w.text}: feed per revolution (FU, M136) without a spindle speed", column=w.column,
                           text=w.text, expected="TOOL CALL .. S<rpm> before FU or M136")
            words[i] = Word("F", w.value * m.spindle, w.column, w.text)
        if w.key == "FAUTO":
            if m.auto_feed is None:
                where.fail("F AUTO without a feed in the TOOL CALL", column=w.column, text=w.text,
                           expected="TOOL CALL n Z S.. F<mm/min> before F AUTO, or F <mm/min>")
            words[i] = Word("F", m.auto_feed, w.column, w.text)
    return words


# --- splines ---------------------------------------------------------------------------------

def spline_block(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``SPL X.. Y.. Z.. K3X.. K2X.. K1X.. .. [F..] [M..]`` (:mod:`interpolators.heidenhain_splines`): the curve as
    chords joined without stops, the last one ending as the path mode says; True at M2/M30."""
    spl = read_spline(blk.code, pos, where, m.params, column0=blk.column)
    words = block_words(spl.rest, pos, where, m, column0=blk.column)
    seen, ms = _motion_words("SPL", words, m, where)
    ended = any(_one_m(w, m, where) for w in ms)
    if "F" in seen:
        w = seen["F"]
        if not w.value > 0:
            where.fail("feed F must be > 0", column=w.column, text=w.text, expected="F > 0 [mm/min]")
        m.feed = w.value * m.feed_scale
    if m.feed is None:
        where.fail("SPL feed move without a feed", column=blk.column, text=where.text, expected="F > 0 [mm/min]")
    if m.comp != "R0" or m.pending is not None or m.approach is not None or m.tcpm:
        where.fail("SPL under RL/RR, after RND/CHF/APPR or under M128 is not supported", column=blk.column,
                   text=where.text, expected="SPL blocks with R0 (the CAM system's tool-centre path)")
    first, points = spline_points(m.to_program(m.pos), spl, m.scale)
    gap = float(np.max(np.abs(m.to_machine(first) - m.pos)))  # per axis: the manual's own example is 1.2 um apart
    if gap > SPLINE_START_TOLERANCE * (1.0 + 1e-6):
        where.fail(f"SPL starts {gap:.4f} mm (in one axis) from the end of the previous element", column=blk.column,
                   text=where.text, expected=f"a spline start (t = 1) within {SPLINE_START_TOLERANCE * 1000:g} um of "
                                             "the previous end point (iTNC 530 user's manual, spline interpolation)")
    exact_stop, tolerance = m.exact_stop, m.tolerance
    m.exact_stop, m.tolerance = False, tolerance if tolerance is not None else SPLINE_TOLERANCE
    for i, point in enumerate(points):
        if i == len(points) - 1:
            m.exact_stop, m.tolerance = exact_stop, tolerance
        target = m.to_machine(point)
        m.emit("line", target, Line(m.pos, target), m.feed, where, blk.number)
    m.used.update(spl.end)
    m.last_axes = []
    return ended


# --- M functions -----------------------------------------------------------------------------

def _without_m_feeds(words: list[Word], m: Machine, where: Where) -> list[Word]:
    """``words`` without the feeds of M functions. The F word right after M128 is not the path feed but "another
    feed rate, at which the TNC will carry out the compensation movements in the linear axes" (TNC 620 user's
    manual for DIN/ISO programming 34056x-04, M128; the iTNC 530 manual's example ``L X+0 Y+38.5 IB-15 RL F125
    M128 F1000``). vcnc's M128 moves no rotary axis (they are positioned before it): noted, no effect. An F (or
    FMAX) after ``M140 MB ..`` is the feed of the retraction (TNC 640 user's manual, "Retraction in the tool
    axis: M140": after the path "you can also enter a feed rate", else it is at rapid traverse; its example
    ``L X+0 Y+38.5 F125 M140 MB 50 F750``): kept in ``m.retract_feed`` [mm/s, inf for FMAX], not the path's."""
    out: list[Word] = []
    m.retract_feed = math.inf
    for i, w in enumerate(words):
        if w.key == "F" and out and out[-1].key == "M" and out[-1].value == 128:
            m.note(f"M128 {w.text}: the feed of compensation movements (no rotary axis moves under M128 here)")
            continue
        if is_retract_feed(words, i):
            if w.key == "F" and not w.value > 0:
                where.fail("feed F of M140 must be > 0", column=w.column, text=w.text, expected="F > 0 [mm/min]")
            m.retract_feed = math.inf if w.key == "FMAX" else w.value * m.feed_scale
            continue
        out.append(w)
    return out


def is_retract_feed(words: list[Word], i: int) -> bool:
    """True when ``words[i]`` is the feed of M140's retraction, an F or FMAX right after ``MB ..`` (TNC 640 user's
    manual, "Retraction in the tool axis: M140"), not the block's path or positioning feed."""
    return words[i].key in ("F", "FMAX") and i > 0 and words[i - 1].key in ("MB", "MBMAX")


def m_functions(words: list[Word], m: Machine, where: Where, blk: SourceBlock, *, motion: bool,
                retract: bool = True) -> bool:
    """Check the M words of a block without motion words; True when the program ends here. ``retract=False``
    leaves an ``M140 MB`` to :func:`block_end_retract`, for a block whose own action (a ``CYCL CALL``'s cycle)
    comes first."""
    words = _without_m_feeds(words, m, where)
    ended = False
    for w in words:
        if w.key == "M":
            ended = _one_m(w, m, where) or ended
            if w.value in (89, 91, 92, 99, 140) and not motion:
                if w.value == 99:
                    m.modal_call = False
                    cycle_call(m, where, blk)
                elif w.value == 89:
                    m.modal_call = True
                elif w.value == 140:
                    continue  # retracts at the block's end, below
                else:
                    m.note(f"M{w.value} in a block without coordinates has no effect")
        elif w.key == "MBMAX" or w.key == "MB":
            if not any(v.key == "M" and v.value == 140 for v in words):  # as in a motion block (motion_block)
                where.fail("MB without M140", column=w.column, text=w.text, expected="M140 MB MAX")
        elif not motion:
            where.fail(f"word {w.text!r} in a block without motion", column=w.column, text=w.text,
                       expected="M functions")
    if not motion and retract:
        # M140 MB in a block of M functions ("7475 M140 MB MAX", a CAM post's retract): as in a line, at its end
        block_end_retract(words, m, where, blk)
    if any(w.key == "M" and w.value == 129 for w in words):  # at the end of the block, after an M128 in it too
        m.tcpm = False
    return ended


def block_end_retract(words: list[Word], m: Machine, where: Where, blk: SourceBlock) -> None:
    """The ``M140 MB ..`` of a block without motion words, at the block's end (TNC 640 user's manual, "Retraction
    in the tool axis: M140": effective at the end of its block; in a ``CYCL CALL`` block after the cycle, and
    at the F after MB that :func:`m_functions` read into ``m.retract_feed``)."""
    if any(w.key == "M" and w.value == 140 for w in words):
        _retract({w.key: w for w in words if w.key in ("MB", "MBMAX")}, m, where, blk)


def _one_m(w: Word, m: Machine, where: Where) -> bool:
    if w.value in _M_PATH:
        _path_m(w, m, where)
        return False
    if w.value == 128:  # TNC 640 manual, "Retaining the position of the tool tip when positioning tilting axes"
        check_tcpm_on(m.context.kinematics, tool_axis=m.plane, where=where, column=w.column, text=w.text)
        m.tcpm, m.tcpm_spatial = True, None  # M128's rotary words are axis positions
        m.note("M128: TCPM (lines of the tool tip on the turned part)")
        return False
    if w.value == 129:
        m.tcpm = False
    if w.value in (126, 127) and m.context.wrapped_axes:  # "Shorter-path traverse of rotary axes: M126"
        m.shortest_path = w.value == 126  # from the start of its block until M127 (_extra_axes)
        return False
    if w.value == 114:  # iTNC 530 user's manual, "Automatic compensation of machine geometry when working with
        # tilted axes: M114": the programmed X, Y, Z become the tool's after a 3-D length compensation at each block's
        # end, by the machine's geometry; ignored, every later point would be silently off by that compensation
        where.fail("M114 (automatic compensation of the machine geometry when working with tilted axes) is not "
                   "modelled", column=w.column, text=w.text,
                   expected="M128 or FUNCTION TCPM (lines of the tool tip on the turned part), or no M114")
    if w.value in _M_END:
        return True
    if w.value in _M_STOP:
        m.note(f"M{w.value}: program stop (no motion)")
        m.stop_in_block = True
        m.at_rest = m.at_rest or w.value == 0
    elif w.value == 130:  # TNC 640 manual, M130: the untilted coordinates in a tilted plane (_untilted_block)
        m.note("M130: the block's coordinates untilted" if m.tilt is not None else ignored_m_note(130))
    elif w.value not in (3, 4, 5, 8, 9, 89, 91, 92, 99, 140):
        m.note(ignored_m_note(w.value))
    return False


#: M functions of the path and the feed with a meaning here (:func:`_path_m`).
_M_PATH = (94, 103, 112, 113, 118, 120, 124, 136, 137, 138)


def _path_m(w: Word, m: Machine, where: Where) -> None:
    """M functions with parameters (:data:`interpolators.heidenhain_words.M_ARGUMENTS`) and the feed per
    revolution.

    * ``M94 [A|B|C]`` (TNC 426 B/430 user's manual, "Reducing display of a rotary axis to a value less
      than 360 deg: M94"; TNC 640 the same): at the start of the block the current angle of the axis (of
      every rotary axis without a letter) is reduced below 360 deg, then the block moves to its programmed
      value (538 deg, then ``C+180``: a traverse of +2 deg). The axis does not move: vcnc keeps the
      machine angle and counts later absolute angles from the reduced value (:attr:`Machine.rotary_shift`).
    * ``M112 T.. A..`` / ``M113`` (TNC 410/426/430 user's manual, "Insert rounding arc between straight
      lines: M112": "for reasons of compatibility ... HEIDENHAIN recommends the use of the TOLERANCE
      cycle"; TNC 407: ``E``, ``H``): the contour transitions within the tolerance T, read as cycle 32
      ``T`` (without T: the context's path tolerance) until ``M113``; the limit angle A is noted.
    * ``M124 T..`` (TNC 407 user's manual, "Ignore points for calculating the rounding arc with M112"):
      points closer than T are left out of M112's rounding arc, not out of the path: noted.
    * ``M118 X.. Y..`` (TNC 640 user's manual, "Superimposing handwheel positioning during program run:
      M118"): limits of an operator's handwheel; no motion, noted.
    * ``M120 LA..`` (TNC 640 user's manual, "Calculating the radius-compensated path in advance (LOOK
      AHEAD): M120"): the TNC leaves out contour undercuts of a radius-compensated run; until R0, ``LA0``,
      M120 without LA or a ``CALL PGM``. vcnc compensates as without it (the same path where the tool
      fits); where it would leave out an undercut, the compensation error names M120.
    * ``M136`` / ``M137`` (TNC 640 user's manual, "Feed rate in millimeters per spindle revolution:
      M136"): F in mm per revolution from the start of the block (:func:`block_words`).
    * ``M103 F..`` (TNC 640 / TNC 410 user's manuals, "Feed rate for plunging: M103"): a move down the tool
      axis runs at most F percent of the feed along it (the manual's table: F500 M103 F20, ``Y+5 Z-5`` at 141
      mm/min, ``Z-2.5`` at 100); ``M103`` without F ends it.
    * ``M138 B C`` (TNC 640 user's manual, "Selecting tilting axes: M138"): noted."""
    args = dict(w.args)
    if w.value == 94:
        letters = [a for a in args if a.lower() in m.context.extra_axes] if args else \
            [a for a in ROTARY_LETTERS if a.lower() in m.context.extra_axes]
        for letter in letters:
            i = EXTRA_LETTERS.index(letter)
            shown = m.extra[i] - m.rotary_shift[i]
            m.rotary_shift[i] = m.extra[i] - shown % 360.0
        m.note("M94: the rotary axis display reduced below 360 deg (no motion; later absolute angles from there)")
    elif w.value == 112:
        if m.m112 is None:
            m.m112 = (m.exact_stop, m.tolerance)
        tolerance = args.get("T", args.get("E"))
        m.exact_stop = False
        m.tolerance = abs(tolerance) * m.scale if tolerance else m.context.dialect.tolerance
        m.note("M112: contour transitions within the tolerance T, read as cycle 32 TOLERANCE (limit angle A not "
               "modelled)")
    elif w.value == 113 and m.m112 is not None:
        m.exact_stop, m.tolerance = m.m112
        m.m112 = None
    elif w.value == 124:
        m.note("M124 T: M112's point filter (the path is not changed)")
    elif w.value == 118:
        m.note("M118: handwheel superimposition limits (no motion; an operator's handwheel is not modelled)")
    elif w.value == 120:
        m.look_ahead = bool(args.get("LA"))
        m.note("M120 LA: look-ahead of the radius-compensated path (the same path where the tool fits)")
    elif w.value == 103:
        m.plunge = args["F"] / 100.0 if args.get("F") else None
    elif w.value == 138:
        m.note("M138: the rotary axes M128 takes (vcnc's M128 takes the kinematics' axes)")
    elif w.value == 136 and m.inch:
        where.fail("M136 in an inch program (the unit of F per revolution there is not documented)",
                   column=w.column, text=w.text, expected="M136 in a program in MM, or FU")


# --- contour ---------------------------------------------------------------------------------

def corner_def(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    code = blk.code
    rm = re.compile(r"\s*R(?=\s*[+-]?\s*[\d.Q(])", re.I).match(code, pos) if kw == "RND" else None
    j = rm.end() if rm else pos
    value, j = read_value(code, j, where, m.params, what=kw, column0=blk.column)
    words = block_words(code, j, where, m, column0=blk.column)
    feed = None
    for w in words:
        if w.key == "F":
            if not w.value > 0:
                where.fail("feed F must be > 0", column=w.column, text=w.text, expected="F > 0 [mm/min]")
            feed = w.value * m.feed_scale
        elif w.key != "M":
            where.fail(f"word {w.text!r} not allowed in {kw}", column=w.column, text=w.text, expected="F or M")
    last = m.blocks[-1] if m.blocks else None
    # TNC 620 manual: CHF joins two straight lines; RND any two contour elements
    kinds = ("line",) if kw == "CHF" else ("line", "arc")
    if last is None or last.kind not in kinds or m.pending is not None:
        what = "a straight line L" if kw == "CHF" else "a line or an arc"
        where.fail(f"{kw} must follow {what}", column=blk.column, text=code.split()[0],
                   expected=f"L ... then {kw} then L ..." if kw == "CHF" else "L/C/CR/CT/CP, then RND, then L/C/...")
    m.pending = (kw, value * m.scale * m.lengths(where), feed, where)


def _polar_target(kw: str, seen: dict[str, Word], target: np.ndarray, m: Machine, where: Where,
                  blk: SourceBlock) -> np.ndarray:
    """The machine end point of an ``LP`` or ``CTP`` block: ``PR``/``IPR`` and ``PA``/``IPA`` about the pole in
    its plane (:func:`_polar_plane`; a word not written keeps the current radius or angle), the tool axis of
    ``target``. CTP, "circle tangential polar", is the arc CT with its end point in polar coordinates (TNC7 basic
    user's manual 81762x-19, "Overview of path functions with polar coordinates": "Circular path with tangential
    connection to the preceding contour element"; TNC 426/430 user's manual 6.5 writes ``CTP PR+30 PA+30``)."""
    if m.pole is None:
        where.fail(f"{kw} without a pole", column=blk.column, text=where.text, expected=f"a CC block before {kw}")
    if kw == "CTP":  # the arc is in the working plane, as CT's
        _pole_in_working_plane(m, where, kw)
    plane = _polar_plane(kw, m, where, blk)
    if plane != m.plane and not m.transform.identity:  # LP about a pole outside the working plane, transformed
        return _transformed_polar(seen, target, plane, m, where)
    r0, a0 = polar_angle(m.pos, m.pole, plane=plane)
    k, t = m.scale * m.lengths(where), m.transform
    pr = seen["PR"].value * k if "PR" in seen else r0 + (seen["IPR"].value * k if "IPR" in seen else 0.0)
    pa = (t.angle(seen["PA"].value, plane) if "PA" in seen
          else a0 + (t.sweep(seen["IPA"].value, plane) if "IPA" in seen else 0.0))
    m.used.update(PLANE_AXES[plane])
    return polar_point(m.pole, pr, pa, plane=plane, base=target)


def _transformed_polar(seen: dict[str, Word], target: np.ndarray, plane: int, m: Machine, where: Where) -> np.ndarray:
    """The end point of an ``LP`` about a pole outside the working plane under a coordinate transformation: the
    polar point about the pole in program coordinates (PR, PA and the current radius and angle there), then
    transformed as any program point; a line's end point is all it needs (our reading of the TNC 640 manual's
    example "Sphere", whose LP blocks about ``CC Z+0 X+Q108`` run under cycle 10 ROTATION)."""
    pole, here = m.to_program(m.pole), m.to_program(m.pos)
    r0, a0 = polar_angle(here, pole, plane=plane)
    k = m.scale
    pr = seen["PR"].value * k if "PR" in seen else r0 + (seen["IPR"].value * k if "IPR" in seen else 0.0)
    pa = seen["PA"].value if "PA" in seen else a0 + (seen["IPA"].value if "IPA" in seen else 0.0)
    m.used.update(PLANE_AXES[plane])
    return m.to_machine(polar_point(pole, pr, pa, plane=plane, base=m.to_program(target)))


def motion_block(kw: str, words: list[Word], m: Machine, where: Where, blk: SourceBlock) -> bool:
    """Run a motion block (L, LP, C, CR, CT, CTP, CP, CC); True when it ends the program."""
    seen, ms = _motion_words(kw, words, m, where)
    mvals = [w.value for w in ms]
    m9x = 91 if 91 in mvals else 92 if 92 in mvals else None
    if m9x is None and 130 in mvals and m.tilt is not None:  # M130: this block in the untilted coordinates
        m9x = _untilted_block(kw, seen, m, where)
    # M129 ends M128 at the end of its block (TNC 426/430 ISO manual, M128: "M128 becomes effective at the start
    # of block, M129 at the end of block"): a line with M129 is still one of the tip on the turned part
    ended = any(_one_m(w, m, where) for w in ms if w.value != 129)
    if kw == "CC":
        m.tcpm = m.tcpm and 129 not in mvals
        _pole(seen, m, where, m9x)
        return ended
    normal, kw = kw == "LN", "L" if kw == "LN" else kw  # LN: a line to a point displaced along the normal
    exit_run = "RCOMP" in seen and set_compensation(seen["RCOMP"], m, where)
    rapid = "FMAX" in seen
    if "F" in seen:
        w = seen["F"]
        if not w.value > 0:
            where.fail("feed F must be > 0", column=w.column, text=w.text, expected="F > 0 [mm/min]")
        m.feed = w.value * m.feed_scale
    if rapid and kw not in ("L", "LP"):
        w = seen["FMAX"]
        where.fail("F MAX is not allowed on arcs", column=w.column, text=w.text, expected="a feed F [mm/min]")
    if "MBMAX" in seen or "MB" in seen:
        if 140 not in mvals:
            w = seen.get("MBMAX") or seen["MB"]
            where.fail("MB without M140", column=w.column, text=w.text, expected="M140 MB MAX")
    target, written = plane_coords(seen, m, where, m9x=m9x)
    shift = _normal_offset(seen, m, where, blk) if normal else None
    if shift is not None:
        target = target + shift
    m.used.update(written)
    feed = math.inf if rapid else m.feed
    spatial = m.tcpm and m.tcpm_spatial is not None and m9x is None  # FUNCTION TCPM .. AXIS SPAT
    extra = (spatial_axes(seen, m, where) if spatial else _extra_axes(seen, m, where)) if kw == "L" else None
    turning = False  # under M128 a rotary axis moves: the line's chords (heidenhain_tcpm.tcpm_line)
    if m.tcpm and m9x is None and tilt_turns(m.tilt) and (written or kw != "L" or extra is not None):
        still_in_tilted_plane("LN" if normal else kw, extra, m, where)  # the plane's line, or an error
    elif m.tcpm and m9x is None and (written or kw != "L" or extra is not None):
        waiting = ("RND/CHF" if m.pending is not None else "APPR/DEP" if m.approach is not None else "RL/RR"
                   if m.comp != "R0" else None)
        target = _tcpm_target(kw, seen, waiting, m, where)
        if normal:  # LN: N displaces the part point, T turns the rotary axes (heidenhain_tcpm.tool_vector)
            target, extra = target + shift, tool_vector(seen, m, where)
        turning = extra is not None and bool(np.any(np.abs(extra[:3] - m.extra[:3]) > 1e-9))
        if not turning:
            target = machine_point(m.context.kinematics, m.extra, target, m.tool_length)
    if kw in ("L", "LP") and (written or kw == "LP" or extra is not None):
        if kw == "LP":
            target = _polar_target(kw, seen, target, m, where, blk)
        m.last_axes = sorted(written) if kw == "L" else []
        if not rapid and m.feed is None:
            where.fail(f"{kw} feed move without a feed", column=blk.column, text=where.text,
                       expected="F > 0 [mm/min] or F MAX")
        if m.pending is not None:
            _resolve_corner(m, Line(m.pos, target), where)
        if m.approach is not None:
            p, q = PLANE_AXES[m.plane]
            _resolve_approach(m, np.array([target[p] - m.pos[p], target[q] - m.pos[q]]), where)
        if turning:
            tcpm_line(m, target, extra, rapid=rapid, where=where, number=blk.number)
        else:
            if (extra is not None and not rapid and not np.any(target != m.pos) and not np.any(extra[3:] != m.extra[3:])
                    and np.any(extra[:3] != m.extra[:3])):
                feed = m.rotary_feed  # a rotary axis alone: F in degrees/min, also in an INCH program
            m.tcpm_move = True
            m.emit("rapid" if rapid else "line", target, Line(m.pos, target), feed, where, blk.number, extra=extra)
            m.tcpm_move = False
    elif kw in ("C", "CR", "CT", "CP", "CTP"):
        if kw == "CTP":
            target = _polar_target(kw, seen, target, m, where, blk)
        if m.feed is None:
            where.fail(f"{kw} feed move without a feed", column=blk.column, text=where.text,
                       expected="F > 0 [mm/min]")
        if m.pending is not None and m.pending[0] == "CHF":
            pw = m.pending[3]
            pw.fail("CHF before an arc: a chamfer joins two straight lines", column=1, text=pw.text,
                    expected="a line after CHF (RND rounds a corner with an arc)")
        seg = _arc(kw, seen, target, m, where, blk)
        if m.pending is not None:
            seg = _resolve_corner(m, seg, where)
        m.used.update(PLANE_AXES[seg.plane])
        if m.approach is not None:
            p, q = PLANE_AXES[m.plane]
            t = np.asarray(seg.tangent_at(0.0), dtype=float).reshape(3)
            _resolve_approach(m, np.array([t[p], t[q]]), where)
        m.emit("arc", np.array(seg.end), seg, m.feed, where, blk.number)
    if exit_run:  # the R0 block ends the run at its programmed point, also with only the tool axis in it
        finish_compensation(m, closed=True)
    _retract_and_call(seen, mvals, m, where, blk, positioned=kw in ("L", "LP") and bool(written))
    m.tcpm = m.tcpm and 129 not in mvals
    return ended


def _retract_and_call(seen: dict[str, Word], mvals: list[float], m: Machine, where: Where, blk: SourceBlock, *,
                      positioned: bool) -> None:
    """After the motion: ``M99`` calls the cycle, and so does every positioning block (an L or LP with
    coordinates) from ``M89`` on, until ``M99`` or ``CYCL CALL`` (TNC 406/306 technical manual, "M-function
    M89": "for every following positioning block there will be a call of the last-programmed machining
    cycle. M89 is canceled by M99 or a CYCL CALL block"; the M89 block itself calls at its end); then
    ``M140 MB`` retracts along the tool axis (effective at the end of its block: after the block's cycle too,
    our reading where the manual orders no two functions of a block's end)."""
    if 89 in mvals:
        m.modal_call = True
    if 99 in mvals:
        m.modal_call = False
        cycle_call(m, where, blk)
    elif m.modal_call and positioned:
        cycle_call(m, where, blk)
    if 140 in mvals:
        _retract(seen, m, where, blk)


def _retract(seen: dict[str, Word], m: Machine, where: Where, blk: SourceBlock) -> None:
    """``M140 MB MAX`` / ``MB n``: a rapid (or a line at the F after MB) along the tool axis, up to the limit
    (home stands in for it) or by n (TNC 640 user's manual, "Retraction in the tool axis: M140": effective at
    the end of its block); ``M140`` without MB retracts nothing (noted)."""
    if "MBMAX" in seen:
        retract = m.pos.copy()
        retract[m.plane] = max(m.context.home[m.plane], m.pos[m.plane])
    elif "MB" in seen:
        retract = m.pos.copy()
        retract[m.plane] += abs(seen["MB"].value) * m.scale
    else:
        m.note("M140 without MB: no retraction")
        return
    if retract[m.plane] != m.pos[m.plane]:
        m.used.add(m.plane)
        m.tcpm_move = True  # along the spindle, also under M128 (the tool axis of a table machine)
        feed = m.retract_feed
        m.emit("rapid" if math.isinf(feed) else "line", retract, Line(m.pos, retract), feed, where, blk.number)
        m.tcpm_move = False


#: A word's key -> the axis or setting it gives (one per block): IX and X both give X, RL and R0 the compensation.
_BASE_KEY = {"IX": "X", "IY": "Y", "IZ": "Z", "IA": "A", "IB": "B", "IC": "C", "IU": "U", "IV": "V", "IW": "W",
             "IPA": "PA", "IPR": "PR", "FMAX": "F", "R0": "RCOMP", "RL": "RCOMP",
             "RR": "RCOMP", "MBMAX": "MB", "BARE": "X"}


#: The words each motion block allows (by key; RCOMP stands for R0/RL/RR).
_ALLOWED_WORDS = {
    "L": frozenset({"X", "Y", "Z", "IX", "IY", "IZ", "F", "FMAX", "RCOMP", "R0", "RL", "RR", "MB", "MBMAX",
                    *EXTRA_LETTERS, *("I" + a for a in EXTRA_LETTERS)}),
    "LN": frozenset({"X", "Y", "Z", "NX", "NY", "NZ", "TX", "TY", "TZ", "F", "FMAX", "RCOMP", "R0"}),
    "LP": frozenset({"PR", "PA", "IPR", "IPA", "Z", "IZ", "X", "Y", "IX", "IY", "F", "FMAX", "RCOMP", "R0", "RL",
                     "RR"}),
    "C": frozenset({"X", "Y", "Z", "IX", "IY", "IZ", "DR", "F", "RCOMP", "R0", "RL", "RR"}),
    "CR": frozenset({"X", "Y", "Z", "IX", "IY", "IZ", "DR", "R", "F", "RCOMP", "R0", "RL", "RR"}),
    "CT": frozenset({"X", "Y", "Z", "IX", "IY", "IZ", "F", "RCOMP", "R0", "RL", "RR"}),
    "CP": frozenset({"PA", "IPA", "X", "Y", "Z", "IX", "IY", "IZ", "DR", "F", "RCOMP", "R0", "RL", "RR"}),
    "CTP": frozenset({"PR", "PA", "IPR", "IPA", "Z", "IZ", "F", "RCOMP", "R0", "RL", "RR"}),
    "CC": frozenset({"X", "Y", "Z", "IX", "IY", "IZ"}),
    "SPL": frozenset({"F"}),
}


def _motion_words(kw: str, words: list[Word], m: Machine, where: Where) -> tuple[dict[str, Word], list[Word]]:
    """The words of a motion block by key (each axis or setting once, allowed in ``kw``), and its M words."""
    words = _without_m_feeds(words, m, where)
    seen: dict[str, Word] = {}
    ms: list[Word] = []
    bases: set[str] = set()
    for w in words:
        if w.key == "M":
            ms.append(w)
            continue
        base = _BASE_KEY.get(w.key, w.key)
        if base in bases or (w.key == "BARE" and bases & {"X", "Y", "Z"}) or (base in "XYZ" and "BARE" in seen):
            where.fail(f"word {w.text!r} repeats an axis or setting of this block", column=w.column, text=w.text,
                       expected="each word at most once per block")
        bases.add(base)
        seen[w.key] = w
        if base == "RCOMP":
            seen["RCOMP"] = w
    if "BARE" in seen:
        w = seen.pop("BARE")
        if kw != "L" or len(m.last_axes) != 1:
            where.fail("coordinate without an axis letter", column=w.column, text=w.text,
                       expected="an axis letter (X, Y or Z) before the number")
        seen["XYZ"[m.last_axes[0]]] = w
    allowed = _ALLOWED_WORDS[kw]
    for key, w in seen.items():
        if key not in allowed:
            where.fail(f"word {w.text!r} not allowed in {kw}", column=w.column, text=w.text,
                       expected=f"{kw} with " + ", ".join(sorted(k for k in allowed if k != 'RCOMP')))
    return seen, ms


def _normal_offset(seen: dict[str, Word], m: Machine, where: Where, blk: SourceBlock) -> np.ndarray:
    """``LN X.. Y.. Z.. NX.. NY.. NZ.. [TX.. TY.. TZ..]``, a straight line with 3-D tool compensation: X, Y,
    Z are the end point the CAM system computed for the tool as defined, and "the TNC displaces the tool in
    the direction of the surface-normal vectors by the sum of the delta values (tool table and TOOL CALL)";
    without M128 / FUNCTION TCPM "the TNC ignores the direction vector T" (iTNC 530 user's manual
    60642x-03 p. 519, "3-D compensation without tool orientation"). vcnc's tool table holds no delta
    values: the sum is the DR of the last TOOL CALL. Returns that displacement [mm, machine].

    ``LN X.. Y.. Z.. TX.. TY.. TZ..`` without N (Autodesk Fusion's ``heidenhain.cps`` writes it for 5-axis
    work) is the "block format with tool orientation" of peripheral milling (TNC 620 user's manual 81760x-02,
    12.6 "Three-dimensional tool compensation", "Peripheral milling: 3-D radius compensation with TCPM"):
    the TNC displaces the tool square to the motion and to the tool only with RL/RR, by DR; under R0 the
    point is not displaced. Its 3-D radius compensation under RL/RR is not modelled: an error."""
    missing = [k for k in ("NX", "NY", "NZ") if k not in seen]
    if len(missing) == 3 and all(k in seen for k in ("TX", "TY", "TZ")):
        if m.comp != "R0":
            where.fail("LN with the tool orientation TX TY TZ under RL/RR (3-D radius compensation, peripheral "
                       "milling) is not supported", column=blk.column, text=where.text,
                       expected="LN .. TX.. TY.. TZ.. R0, or LN .. NX.. NY.. NZ.. (face milling)")
        return np.zeros(3)
    normal = np.array([seen[k].value for k in ("NX", "NY", "NZ") if k in seen], dtype=float)
    if missing or not np.linalg.norm(normal) > 0:
        where.fail("LN without a surface-normal vector", column=blk.column, text=where.text,
                   expected="LN X.. Y.. Z.. NX.. NY.. NZ.. (a vector of non-zero length), or TX.. TY.. TZ.. alone")
    if not m.transform.identity:
        where.fail("LN under a coordinate transformation (cycles 8, 10, 11, 26) is not supported", column=blk.column,
                   text=where.text, expected="LN without mirror, rotation or scaling")
    if ("TX" in seen or "TY" in seen or "TZ" in seen) and not m.tcpm:
        m.note("LN TX/TY/TZ: the tool orientation is ignored without M128 (no tilting axes move)")
    return m.tool_delta * normal / np.linalg.norm(normal)


def _extra_axes(seen: dict[str, Word], m: Machine, where: Where) -> np.ndarray | None:
    """End positions ``(a, b, c, u, v, w)`` [deg, mm] of an L block's words of the axes beyond X, Y, Z,
    or None when it has none. ``A+90`` is the position, ``IA+90`` an increment (TNC 640 user's manual,
    "Straight line L": the block may contain "up to 5 axes" including rotary axes); A, B, C in degrees,
    U, V, W in the program's unit; the preset of these axes is the machine's zero (the context's
    work offsets hold X, Y, Z only), so an absolute word is the machine position, as with M91/M92. An absolute
    word of an axis the machine wraps at 360 deg (``MachineContext.wrapped_axes``) turns it the shorter way under
    ``M126`` (TNC 640 user's manual, "Shorter-path traverse of rotary axes: M126"; ``M127`` ends it), otherwise
    by the shown angle's difference to the word, or the machine's ``wrap_direction``
    (:mod:`interpolators.rotary_wrap`); an incremental one as it is ("M126 is not in effect with incremental
    traverse movements", TNC7 user's manual). A
    machine (``MachineContext.extra_axes``) without the axis: an error naming it, but for a word of
    value 0 (posts write ``L A0 C0 R0 FMAX`` on 3-axis work), which is noted and ignored."""
    letters = [k for k in seen if len(k) <= 2 and k[-1] in EXTRA_LETTERS and k[:-1] in ("", "I")]
    if not letters:
        return None
    target = m.extra.copy()
    moved = False
    for key in letters:
        w = seen[key]
        axis = key[-1]
        if axis.lower() not in m.context.extra_axes:
            if w.value != 0.0:
                where.fail(f"axis {axis!r} is not an axis of this machine", column=w.column, text=w.text,
                           expected="X, Y, Z" + "".join(f", {a.upper()}" for a in m.context.extra_axes))
            m.note(f"{w.text}: no {axis} axis on this machine (ignored)")
            continue
        value = w.value if axis in ROTARY_LETTERS else w.value * m.scale
        i = EXTRA_LETTERS.index(axis)
        target[i] = target[i] + value if key[0] == "I" else value + m.rotary_shift[i]  # M94's reduced display
        m.used.add(3 + i)
        moved = True
    if not moved:
        return None
    m.extra_used = True
    if m.context.wrapped_axes:
        target = wrap_words(target, {k: seen[k] for k in letters if k in ROTARY_LETTERS}, m.extra, m.rotary_shift,
                            wrapped=m.context.wrapped_axes, direction=m.wrap_rule, where=where)
    return target


def _untilted_block(kw: str, seen: dict[str, Word], m: Machine, where: Where) -> int:
    """``M130`` in a tilted working plane: 130, the block's coordinates then being those of the untilted
    workpiece coordinate system (:func:`interpolators.heidenhain_targets.plane_coords`), or an error.

    TNC 640 user's manual, "Moving to positions in a non-tilted coordinate system with a tilted working plane:
    M130": with M130 the control places the coordinates of straight-line blocks in the untilted coordinate system
    and positions the tilted tool to them; M130 acts in its block, in straight lines without radius
    compensation; the blocks after it run in the tilted plane again. Our reading on a tilting table: the untilted
    system is the one of the program without the plane, the preset plus the datum shift of before the tilt
    (``TiltedPlane.base_shift``) and the tool length along Z, not carried by the table (as M91 is not); an arc,
    RL/RR, M128 or a cycle 8/10/11/26 with it is an error naming M130 (not modelled)."""
    t = m.transform
    why = ("an arc or a polar block" if kw not in ("L", "LN") else "radius compensation RL/RR"
           if m.comp != "R0" or "RCOMP" in seen and seen["RCOMP"].text.upper() != "R0" else "M128 / FUNCTION TCPM"
           if m.tcpm else "a cycle 8, 10, 11 or 26" if dataclasses.replace(t, tilt=0.0) != type(t)() else None)
    if why is not None:
        where.fail(f"M130 (a block in the untilted coordinates of a tilted plane) with {why} is not supported",
                   column=1, text=where.text, expected="M130 in a straight line L under R0 (TNC 640 manual, M130)")
    return 130


def _tcpm_target(kw: str, seen: dict[str, Word], waiting: str | None, m: Machine, where: Where) -> np.ndarray:
    """The end point of a line under M128 (:mod:`interpolators.heidenhain_tcpm`) on the part with every rotary
    axis at 0 [mm, machine, tool length included]. ``waiting``: what the block is or what waits for it (an LN, a
    corner, an approach, radius compensation: errors)."""
    if kw != "L" or waiting is not None:
        where.fail(f"{waiting or kw} under M128 is not supported", column=1, text=where.text,
                   expected=TCPM_EXPECTED)
    if m.plane != 2:  # a TOOL CALL .. X / Y after M128 (M128 itself checks the tool axis: check_tcpm_on)
        where.fail(f"a line under M128 with tool axis {'XYZ'[m.plane]} is not supported", column=1, text=where.text,
                   expected=TCPM_EXPECTED)
    values = {k: seen[k].value * m.scale for k in ("X", "Y", "Z", "IX", "IY", "IZ") if k in seen}
    part, _ = program_target(m, values, part_point(m.context.kinematics, m.extra, m.pos, m.tool_length))
    return part


def _pole(seen: dict[str, Word], m: Machine, where: Where, m9x: int | None) -> None:
    """``CC``: the circle centre and pole. Its plane is the working plane, or, when CC names the
    tool axis and one axis of the working plane (``CC X+37.6 Z+3.3`` with tool axis Z), the plane
    of those two axes (ZX, YZ, XY with the reference axes Z, Y, X and DR+ turning from the first to
    the second: TNC 426 manual, "Circle Center and Pole: CC", table of the reference axes): the arcs
    ``C`` and ``CP`` about it then run in that plane. This is our reading: the TNC 426/407 manuals
    assign a circle to the main plane of the TOOL CALL and name no other plane; Fusion 360's TNC post
    writes its vertical lead-in and lead-out arcs as ``CC Y-31.628 Z-1.6`` / ``CP IPA+90 DR+`` /
    ``L Y-31.48 Z-3`` (the third coordinate of CC is the current one), and only the arc in the plane
    of CC's axes ends where the next line starts, tangentially, so that is how the controls it posts
    for run it. Radius compensation acts in the working plane only, so such a pole under RL/RR is an
    error; under a coordinate transformation the pole is set (the TNC 640 manual's Q parameter example
    "Sphere" sets ``CC Z+0 X+Q108`` under cycle 10 ROTATION and moves about it with LP only, see
    :func:`_polar_plane`), an arc about it stays an error (:func:`_arc`)."""
    target, written = plane_coords(seen, m, where, m9x=m9x)
    p, q = PLANE_AXES[m.plane]
    plane = m.plane
    off = [i for i in written if i not in (p, q)]
    if off:
        w = seen.get("XYZ"[off[0]]) or seen["I" + "XYZ"[off[0]]]
        if len(written) != 2 or m.comp != "R0":
            where.fail(f"CC coordinate {w.text!r} is not in the working plane", column=w.column, text=w.text,
                       expected=f"CC {'XYZ'[p]} {'XYZ'[q]}, or CC with the tool axis and one other axis (a circle in "
                                "that plane, without RL/RR)")
        plane = 3 - sum(written)  # the axis CC does not name is the circle's normal
    m.pole = target
    m.pole_plane = plane if off else None
    m.used.update(written)


def _polar_plane(kw: str, m: Machine, where: Where, blk: SourceBlock) -> int:
    """The plane of an ``LP`` (or ``CTP``) block: the plane of the pole (:func:`_pole`). After ``CC Z.. X..`` (tool
    axis Z) the polar line runs in ZX with the angle from +Z, as the arcs about that pole do: HEIDENHAIN's
    demonstration program 7025 writes ``CC Z+Q4 X+Q7`` / ``LP PR+Q6 PA-90 R0`` / ``CP IPA+Q12 DR+`` (TNC 426
    manual, "Polar coordinates": the pole CC may lie in any of the three main planes, the angle PA
    counted from the plane's reference axis). As for those arcs, R0; an LP line may run under a coordinate
    transformation (its end point worked out in program coordinates and transformed, :func:`_polar_target`), as the
    TNC 640 manual's Q parameter example "Sphere" moves about ``CC Z+0 X+Q108`` under cycle 10 ROTATION; CTP is an
    arc and stays an error there, as are C and CP (:func:`_arc`). The error names what is in force: RL/RR, or (under
    R0) the transformation."""
    plane = m.pole_plane if m.pole_plane is not None else m.plane
    if plane != m.plane and (m.comp != "R0" or (kw != "LP" and not m.transform.identity)):
        what = "a coordinate transformation" if m.comp == "R0" else m.comp
        where.fail(f"{kw} about a CC outside the working plane under {what}",
                   column=blk.column, text=where.text,
                   expected="R0 for LP in another plane" if kw == "LP" else
                   f"R0 and no cycle 8/10/11/26 for {kw} in another plane")
    return plane


def _pole_in_working_plane(m: Machine, where: Where, what: str) -> None:
    """Polar coordinates (LP, APPR P..) are in the working plane: an error after a CC in another plane."""
    if m.pole_plane is not None and m.pole_plane != m.plane:
        where.fail(f"{what} about a pole outside the working plane", column=1, text=where.text,
                   expected="a CC in the working plane before polar coordinates")


def _arc(kw: str, seen: dict[str, Word], target: np.ndarray, m: Machine, where: Where, blk: SourceBlock) -> Arc:
    """The arc of a C, CR, CT or CP block in machine coordinates. ``DR`` and ``IPA`` are senses of
    the program; with one axis of the plane mirrored (cycle 8) the arc turns the other way. C and
    CP run in the plane of the pole (:func:`_pole`)."""
    plane = _polar_plane(kw, m, where, blk) if kw in ("C", "CP") else m.plane
    dr = seen.get("DR")
    ccw = (dr.value == "+") if dr is not None else m.ccw
    k = m.lengths(where)
    flips = m.transform.flips(plane)
    try:
        if kw in ("CT", "CTP"):
            if not m.blocks or m.blocks[-1].segment is None:
                where.fail(f"{kw} without a preceding contour element", column=blk.column, text=where.text,
                           expected=f"an L, C, CR, CT or CP block before {kw}")
            return tangential_arc(m.pos, end_tangent(m.blocks[-1].segment, plane), target, plane=plane)
        if kw == "CP":
            if m.pole is None:
                where.fail("CP without a pole", column=blk.column, text=where.text, expected="a CC block before CP")
            _, a0 = polar_angle(m.pos, m.pole, plane=plane)
            if "IPA" in seen:
                sweep = seen["IPA"].value
                if dr is not None and (sweep > 0) != ccw:
                    w = seen["IPA"]
                    where.fail("IPA and DR have different signs", column=w.column, text=w.text,
                               expected="the same sign for IPA and DR (manual: 'enter the same sign')")
                m.ccw = sweep > 0
                sweep = m.transform.sweep(sweep, plane)
            elif "PA" in seen:
                if ccw is None:
                    where.fail("CP arc without direction", column=blk.column, text=where.text, expected="DR+ or DR-")
                # [0, 360): the counter-clockwise angle to the end
                delta = (m.transform.angle(seen["PA"].value, plane) - a0) % 360.0
                if delta <= 1e-9 or delta >= 360.0 - 1e-9:
                    delta = 0.0  # the end is the start: a full circle
                m.ccw = ccw
                sweep = (delta or 360.0) if ccw != flips else -((360.0 - delta) if delta else 360.0)
            else:  # no PA: the angle stays the current one, the end is the start, a full circle
                if ccw is None:
                    where.fail("CP arc without direction", column=blk.column, text=where.text, expected="DR+ or DR-")
                m.ccw = ccw
                sweep = 360.0 if ccw != flips else -360.0
            return helical_arc(m.pos, m.pole, sweep, plane=plane, axis_end=target[plane])
        if ccw is None:
            where.fail(f"{kw} arc without direction", column=blk.column, text=where.text, expected="DR+ or DR-")
        m.ccw = ccw
        if kw == "C":
            if m.pole is None:
                where.fail("C arc without a circle centre", column=blk.column, text=where.text,
                           expected="a CC block before C")
            p, q = PLANE_AXES[plane]
            if math.hypot(m.pos[p] - m.pole[p], m.pos[q] - m.pole[q]) <= 1e-9:
                # TNC 640 user's manual, "Circular path C around circle center CC": the arc runs about CC from
                # the tool's position, so a start on CC has radius 0 (the control stops with an error there)
                where.fail("C arc of radius zero: the tool stands on the circle centre CC", column=blk.column,
                           text=where.text, expected="a CC away from the start point (the centre of the arc)")
            return arc_from_center(m.pos, target, m.pole, ccw=ccw != flips, plane=plane,
                                   tolerance=arc_end_tolerance(m.inch))
        if "R" not in seen:
            where.fail("CR arc without radius", column=blk.column, text=where.text, expected="R+ or R- [mm]")
        return arc_from_radius(m.pos, target, seen["R"].value * m.scale * k, ccw=ccw != flips, plane=plane)
    except (ArcWordError, PathGeometryError) as exc:
        w = seen.get("R") or seen.get("IPA") or seen.get("PA")
        col, tok = (w.column, w.text) if w is not None else (blk.column, where.text)
        where.fail(exc.message, column=col, text=tok, expected=exc.expected)


def _resolve_corner(m: Machine, second: Line | Arc, where: Where) -> Line | Arc:
    """Trim the previous element and insert the RND arc / CHF line before ``second`` (the next
    element, starting at the corner); returns ``second`` trimmed to start where the corner ends."""
    kind, value, feed, pw = m.pending
    m.pending = None
    prev = m.blocks.pop()
    try:
        if kind == "RND":
            first, corner_seg, trimmed = round_elements(prev.segment, second, value, plane=m.plane)
            if _inside_rounding(m, corner_seg):
                m.blocks.append(prev)
                m.note(f"RND R{value / m.scale:g} on an inside corner under {m.comp_side} with a tool of radius "
                       f"{m.comp_radius / m.scale:g}: the corner is cut where the tool centre paths meet (the "
                       "tool's own radius rounds it)")
                return second
            second = trimmed
        else:
            t1, t2 = chamfer_corner(prev.start, prev.target, second.end, value, plane=m.plane)
            first, corner_seg, second = Line(prev.start, t1), Line(t1, t2), Line(t2, second.end)
    except PathGeometryError as exc:
        pw.fail(exc.message, column=1, text=pw.text, expected=exc.expected)
    m.pos = np.array(prev.start, dtype=float)
    m.blocks.append(dataclasses.replace(prev, target=np.array(first.end), segment=first))
    m.pos = np.array(first.end)
    m.emit("arc" if kind == "RND" else "line", np.array(corner_seg.end), corner_seg,
           feed if feed is not None else prev.feed, pw, None)
    return second


def _inside_rounding(m: Machine, corner: Arc) -> bool:
    """An RND arc under RL/RR that turns toward the tool's side (an inside corner) with a radius not above the tool
    radius: the tool centre's arc would have no radius left. The TNC cuts inside corners where the tool centre
    paths meet (iTNC 530 user's manual, 5.3 "Radius compensation: Machining corners", "Inside corners"), so the
    corner is left to compensation, rounded by the tool itself. The manuals' own programs write such roundings:
    the TNC 370 user's manual's "Example 1/2 for exercise in FK free contour programming" (section 5.6, pp. 5-48,
    5-49) round the corner at the contour's start with RND R1 (tool R2) and RND R5 (tool R5) right after the
    block that switches RL/RR on. Our reading: the iTNC 530 manual asks that "the rounding arc must be machinable
    with the called tool" and names no error for these."""
    if m.comp_start is None or m.comp_radius <= 0:  # no compensated run (its R0 exit block is still one)
        return False
    toward_tool = corner.ccw == (m.comp_side == "RL")
    return toward_tool and corner.radius <= m.comp_radius + 1e-9


# --- FK free contour programming ------------------------------------------------------------------

def free_contour(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``FPOL``, ``FL``, ``FLT``, ``FC``, ``FCT``, ``FSELECT`` (:mod:`interpolators.heidenhain_fk`): the
    elements resolved run as ``L`` and ``CC`` + ``C`` blocks in program coordinates of the working plane."""
    axes = "".join("XYZ"[i] for i in PLANE_AXES[m.plane])  # the working plane's first and second axis
    start = m.to_program(m.pos)[list(PLANE_AXES[m.plane])] / m.scale
    if kw == "FSELECT":
        value, _ = read_value(blk.code, pos, where, m.params, what=kw, column0=blk.column)
        done = m.fk.select(value, where, blk.column, blk.code)
        for text in m.fk.notes:
            m.note(text)
        m.fk.notes.clear()
    else:
        data = read_fk_words(blk.code, pos, where, m.params, column0=blk.column, axes=axes)
        if kw == "FPOL":
            m.fk.set_pole(data, start, where)
            return False
        if m.feed is None and "F" not in data.words:
            where.fail(f"{kw} feed move without a feed", column=blk.column, text=where.text,
                       expected="F > 0 [mm/min] in this or an earlier block")
        done = m.fk.element(kw, data, start, _fk_tangent(m), where, blk.number,
                            arc_end_tolerance(m.inch) / m.scale)
    ended = False
    for element, data, ew, number in done:
        words = [Word(a, float(v), 1, a) for a, v in zip(axes, element.end)]
        words += [data.words[k] for k in ("RCOMP", "F") if k in data.words] + list(data.ms)
        source = SourceBlock(line=ew.line, number=number, code=ew.text, column=1, text=ew.text)
        if element.centre is None:
            ended = motion_block("L", words, m, ew, source) or ended
            continue
        _pole({a: Word("CC" + a, float(v), 1, "CC" + a) for a, v in zip(axes, element.centre)}, m, ew, None)
        words.append(Word("DR", "+" if element.ccw else "-", 1, "DR"))
        ended = motion_block("C", words, m, ew, source) or ended
    return ended


def _fk_tangent(m: Machine) -> np.ndarray | None:
    """Unit direction [program XY] at the end of the preceding element (FLT, FCT, IAN); None without one."""
    if not m.blocks or m.blocks[-1].segment is None:
        return None
    try:
        t = end_tangent(m.blocks[-1].segment, m.plane)
    except PathGeometryError:
        return None
    step = np.zeros(3)
    step[list(PLANE_AXES[m.plane])] = t
    d = (m.to_program(m.pos + step) - m.to_program(m.pos))[list(PLANE_AXES[m.plane])]
    return d / np.hypot(*d)


# --- approach and departure ----------------------------------------------------------------------

def approach_depart(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``APPR LT|LN|CT`` / ``DEP LT|LN|CT`` (TNC 640 user's manual 1/2015, "Approaching and departing
    a contour", p. 213; TNC7 manual "APPR LT", "APPR LN", "APPR CT"): the approach through the
    auxiliary point PH (LT: ``LEN`` before the first contour point PA along the first element; LN:
    ``LEN`` off it, perpendicular, on the tool's side; CT: the start of the arc of radius ``R``
    through the centre angle ``CCA`` that ends tangentially at PA) and the departure from the last
    contour point (LT: ``LEN`` on along the last element; LN: ``LEN`` off it, perpendicular; CT: the
    arc leaving it tangentially). PS to PH runs at the last programmed feed (rapid if the last move
    was rapid); a tool-axis coordinate is reached after PH (APPR) or after PN (DEP). LN, CT and LCT
    need RL or RR (the tool's side; R's sign and the side give the arc's sense); the R of a CT/LCT arc
    is the radius of the tool's path (:func:`interpolators.heidenhain_paths.contour_arc_radius`). A DEP
    without R0/RL/RR cancels the compensation (TNC 410 user's manual: "The TNC automatically cancels
    the radius compensation in a DEP block"). The polar forms APPR PLT/PLN/PCT/PLCT and DEP PLCT take
    PA from PR and PA about the pole CC."""
    code = blk.code
    fm = re.compile(r"\s*(P?L?[A-Z]{1,3})(?![A-Z])", re.I).match(code, pos)
    form = fm.group(1).upper() if fm else ""
    what = f"{kw} {form}"
    polar = form in ("PLT", "PLN", "PCT", "PLCT") and (kw == "APPR" or form == "PLCT")  # PR, PA about CC
    form = form[1:] if polar else form
    if form not in ("LT", "LN", "CT", "LCT"):
        where.fail(f"{what} is not supported", column=blk.column, text=what,
                   expected=f"{kw} LT, LN, CT or LCT (polar: APPR PLT, PLN, PCT, PLCT, DEP PLCT)")
    words = block_words(code, fm.end(), where, m, column0=blk.column)
    keys = {"CT": ("CCA", "R"), "LCT": ("R",)}.get(form, ("LEN",))
    axes = ("PR", "PA", "Z", "IZ") if polar else ("X", "Y", "Z", "IX", "IY", "IZ")
    seen = {}
    for w in words:
        if w.key not in (*axes, "R0", "RL", "RR", "F", "FMAX", "M", *keys):
            where.fail(f"word {w.text!r} not allowed in {what}", column=w.column, text=w.text,
                       expected=f"{', '.join(axes)}, {', '.join(keys)}, R0/RL/RR, F, M")
        if w.key != "M":
            seen[w.key] = w
    if polar and (m.pole is None or "PR" not in seen or "PA" not in seen):
        where.fail(f"{what} needs a pole CC, PR and PA", column=blk.column, text=code,
                   expected=f"CC X.. Y.. before {what} PR.. PA..")
    if polar:
        _pole_in_working_plane(m, where, what)
    ended = any(_one_m(w, m, where) for w in words if w.key == "M")
    for key in keys:
        w = seen.get(key)
        if w is None or (key == "LEN" and not w.value > 0):
            where.fail(f"{what} needs {key}" + (" > 0" if key == "LEN" else ""), column=w.column if w else blk.column,
                       text=w.text if w else code, expected=f"{key} [mm]" if key != "CCA" else "CCA [deg]")
    k = m.scale * m.lengths(where)
    sizes = {"length": seen["LEN"].value * k if "LEN" in seen else 0.0,
             "radius": seen["R"].value * k if "R" in seen else 0.0,
             "angle": seen["CCA"].value if "CCA" in seen else 0.0}
    was = m.comp
    exit_run = False
    for comp in ("R0", "RL", "RR"):
        if comp in seen:
            exit_run = set_compensation(seen[comp], m, where)
    if kw == "DEP" and was != "R0" and not any(c in seen for c in ("R0", "RL", "RR")):
        # TNC 410 user's manual, "Contour approach and departure": "The TNC automatically cancels the
        # radius compensation in a DEP block" (RL/RR written again keep it)
        m.comp, exit_run = "R0", True
    active = m.comp if kw == "APPR" else was
    if form != "LT" and active == "R0":
        where.fail(f"{what} without radius compensation", column=blk.column, text=code,
                   expected=f"{what} with RL or RR (the tool's side)")
    sizes["side"] = 1.0 if m.comp_side == "RL" else -1.0
    prev_feed = m.feed
    if "F" in seen:
        if not seen["F"].value > 0:
            where.fail("feed F must be > 0", column=seen["F"].column, text=seen["F"].text, expected="F > 0 [mm/min]")
        m.feed = seen["F"].value * m.feed_scale
    if m.feed is None:
        where.fail(f"{what} without a feed", column=blk.column, text=code, expected="F > 0 [mm/min]")
    target, written = plane_coords(seen, m, where, m9x=None)
    if polar:
        target = polar_point(m.pole, seen["PR"].value * k, m.transform.angle(seen["PA"].value, m.plane),
                             plane=m.plane, base=target)
        written |= set(PLANE_AXES[m.plane])
    m.used.update(written)
    if kw == "APPR":
        m.approach = {"ps": m.pos.copy(), "form": form, **sizes, "rapid": m.last_rapid,
                      "feed": prev_feed or m.feed, "where": where, "number": blk.number}
        m.pos = target  # the first contour point PA: where the next element starts
        return ended
    if form == "LN":  # TNC 640 manual: "PN is separated from PE by the distance LEN plus the tool radius"
        sizes["length"] += m.comp_radius
    _depart(form, sizes, target, m, where, blk)
    if exit_run:  # DEP CT under RL/RR: the arc is a compensated element, the run has no exit line
        finish_compensation(m, open_end=form == "CT")
    if target[m.plane] != m.pos[m.plane]:
        up = m.pos.copy()
        up[m.plane] = target[m.plane]
        m.emit("line", up, Line(m.pos, up), m.feed, where, blk.number)
    return ended


def _depart(form: str, sizes: dict[str, float], target: np.ndarray, m: Machine, where: Where,
            blk: SourceBlock) -> None:
    """The departure move of DEP LT/LN/CT from the end of the last contour element."""
    if not m.blocks or m.blocks[-1].segment is None:
        where.fail(f"DEP {form} without a preceding contour element", column=blk.column, text=blk.code,
                   expected=f"a contour element before DEP {form}")
    try:
        t = end_tangent(m.blocks[-1].segment, m.plane)
        if form in ("CT", "LCT"):  # R is the tool path's radius: the contour arc's is R +- the tool radius
            sizes = {**sizes, "radius": contour_arc_radius(f"DEP {form}", sizes["radius"], m.comp_radius)}
        if form == "LCT":
            segs = departure_lct(m.pos, target, t, radius=sizes["radius"], side=sizes["side"], plane=m.plane,
                                 tool_radius=m.comp_radius)
        else:
            segs = (departure_element(form, m.pos, t, plane=m.plane, **sizes),)
    except PathGeometryError as exc:
        where.fail(exc.message, column=blk.column, text=blk.code, expected=exc.expected)
    for seg in segs:
        m.emit("line" if isinstance(seg, Line) else "arc", np.array(seg.end), seg, m.feed, where, blk.number)


def _resolve_approach(m: Machine, direction: np.ndarray, where: Where) -> None:
    """Emit PS -> PH -> (depth) -> PA of a pending APPR, PH from the first element's ``direction`` at PA."""
    a = m.approach
    m.approach = None
    n = float(np.hypot(*direction))
    pw = a["where"]
    if n <= 1e-12:
        pw.fail(f"the first contour element after APPR {a['form']} has no direction in the working plane", column=1,
                text=pw.text, expected="a first contour element in the working plane")
    pa = m.pos.copy()
    p, q = PLANE_AXES[m.plane]
    arc = None
    if a["form"] == "LT":
        ph = np.array(a["ps"], dtype=float)
        ph[p] = pa[p] - a["length"] * direction[0] / n
        ph[q] = pa[q] - a["length"] * direction[1] / n
    else:
        if a["form"] == "LN":  # "PH is separated from PA by the distance LEN plus the tool radius"
            a["length"] += m.comp_radius
        try:
            if a["form"] in ("CT", "LCT"):  # R is the tool path's radius (heidenhain_paths.contour_arc_radius)
                a["radius"] = contour_arc_radius(f"APPR {a['form']}", a["radius"], m.comp_radius)
            if a["form"] == "LCT":
                ph, arc = approach_lct(a["ps"], pa, direction / n, radius=a["radius"], side=a["side"], plane=m.plane,
                                       tool_radius=m.comp_radius)
            else:
                ph, arc = approach_start(a["form"], pa, direction / n, length=a["length"], radius=a["radius"],
                                         angle=a["angle"], side=a["side"], plane=m.plane)
        except PathGeometryError as exc:
            pw.fail(exc.message, column=1, text=pw.text, expected=exc.expected)
        ph[m.plane] = a["ps"][m.plane]
    m.pos = np.array(a["ps"], dtype=float)
    m.emit("rapid" if a["rapid"] else "line", ph, Line(m.pos, ph), math.inf if a["rapid"] else a["feed"], pw,
           a["number"])
    if ph[m.plane] != pa[m.plane]:
        down = ph.copy()
        down[m.plane] = pa[m.plane]
        m.emit("line", down, Line(m.pos, down), m.feed, pw, a["number"])
    if arc is None:
        if a["form"] == "LN" and m.comp_start is not None:
            m.comp_start = len(m.blocks)  # PH -> PA is the entry move: it ends at PA, off by the radius
        m.emit("line", pa, Line(m.pos, pa), m.feed, pw, a["number"])
    else:
        m.emit("arc", pa, Arc(m.pos, pa, arc.center, ccw=arc.ccw, plane=m.plane), m.feed, pw, a["number"])
