"""Cycles of Heidenhain conversational programs: ``CYCL DEF`` blocks and their parameters.

Sources: HEIDENHAIN TNC 426/430 user's manual ("Cycles for drilling", cycle 1 PECKING; cycles
200 DRILLING, 203 UNIVERSAL DRILLING, 205 UNIVERSAL PECKING; "Coordinate transformation
cycles", 7 DATUM SHIFT; "Special cycles", 9 DWELL TIME and 32 TOLERANCE), TNC 320 user's
manual 340 55x-03 p. 238 (the Q parameters: Q200 set-up clearance, incremental from the
surface; Q201 depth, incremental from the surface, its sign the working direction; Q203
surface coordinate, absolute; Q204 2nd set-up clearance, incremental from the surface).

Supported definitions (one ``CYCL DEF n.m`` line per item for the old cycles; the 200 series
as one block of ``Qnnn=value`` assignments, possibly continued over lines with ``~``):

========================= ==================================================================
``CYCL DEF 1.0 PECKING``  1.1 SET UP (or DIST) clearance, 1.2 DEPTH, 1.3 PECKG (or PLNGNG)
                          plunge depth, 1.4 DWELL [s], 1.5 F [mm/min]; drills from the
                          current position (set-up clearance above the surface)
``CYCL DEF 4.0 POCKET ..`` 4.1 SET UP, 4.2 DEPTH, 4.3 PECKG .. F, 4.4 X side, 4.5 Y side, 4.6 F DR+/- RADIUS
                          (:func:`old_rectangular_pocket`); ``CYCL DEF 5.0 CIRCULAR POCKET`` 5.1 SET UP,
                          5.2 DEPTH, 5.3 PECKG .. F, 5.4 RADIUS, 5.5 F DR+/- (:func:`old_circular_pocket`)
``CYCL DEF 7.0 DATUM ..`` 7.1 X, 7.2 Y, 7.3 Z: datum shift (``IX``: added to the last shift)
``CYCL DEF 9.0 DWELL ..`` 9.1 DWELL (or TIME) t [s]: a dwell right away
``CYCL DEF 32.0 TOL..``   32.1 T [mm] (empty: the machine's default); 32.2 ignored
``CYCL DEF 200``          Q200 Q201 Q206 Q202 Q210 Q203 Q204 Q211, Q395 = 1 the depth to the full diameter
                          (the tool's point angle T-ANGLE, :func:`point_depth`; also 203, 205)
``CYCL DEF 203``          as 200, plus Q212 decrement, Q213 breaks, Q205 minimum plunge, Q208
                          retraction feed, Q256 chip-break retraction
``CYCL DEF 205``          as 203 (Q212, Q205, Q256, Q257 chip breaking within an infeed), Q258/Q259
                          advanced stop distances, Q379 deepened starting point at Q253
``CYCL DEF 204``          back boring: Q249 Q250 Q251 Q252 Q253 Q254 Q255 Q214 (:func:`back_boring_cycle`)
``CYCL DEF 2 / 17``       old tapping, item by item (:func:`tapping_cycle`)
``CYCL DEF 201 .. 209``   reaming, boring, tapping, bore milling, centering 240 (Q343 = 1: to the diameter Q344)
                          (:func:`drill_cycle`, TNC 320 cycle programming manual 9/2016)
``CYCL DEF 241``          single-lip deep-hole drilling in one infeed, Q379 deepened starting point at
                          Q253, Q435 dwell depth, Q401 feed factor (:func:`single_lip_cycle`)
``CYCL DEF 251``          rectangular pocket, as 252 with rounded rectangles (Q218, Q219, Q220, Q224)
``CYCL DEF 256``          rectangular stud, revolutions from the blank Q424 x Q425 in
                          (:func:`circular_pocket_cycle`); 257 circular stud, as 256 with a circle
``CYCL DEF 253``          slot milling, as 251 with the slot's obround (:func:`circular_pocket_cycle`);
                          254 circular slot, rings round the slot along its arc
``CYCL DEF 252``          circular pocket, vertical plunge, rings and finishing (:func:`circular_pocket_cycle`)
``CYCL DEF 212 .. 215``   pocket, stud, circular pocket, circular stud finishing about Q216, Q217, as 251, 256,
                          252, 257 finish (:func:`finishing_cycle`)
``CYCL DEF 210 / 211``    slot and circular slot with reciprocating plunge, as 253 / 254 (:func:`old_slot_cycle`)
``CYCL DEF 262``          thread milling, one helix or a continuous one (:func:`thread_milling_cycle`);
                          263 with countersinking, 264 drilling first, 265 helical, 267 outside
``CYCL DEF 220 / 221``    polar / Cartesian pattern, DEF-active (:func:`pattern_cycle`)
========================= ==================================================================

The Q parameters of a definition are also assigned in the program's parameter store, as the
TNC does. Machining cycles run where they are called (``M99``, ``CYCL CALL``).
"""

from __future__ import annotations

import dataclasses
import math
import re

from interpolators._words import Where
from interpolators.heidenhain_params import QParameters
from interpolators.heidenhain_words import read_value, read_words

__all__ = ["CYCLE_RE", "DrillCycle", "AxisMove", "MACHINING_CYCLES", "PATTERN_CYCLES", "THREAD_CYCLES",
           "BORING_DISENGAGE",
           "LEGACY_CYCLES", "tapping_cycle",
           "pocket_item", "old_pocket", "q_assignments", "legacy_value", "required_q", "PatternCycle",
           "pattern_cycle", "MAX_PATTERN_POSITIONS",
           "pecking_cycle", "drill_cycle", "thread_milling_cycle", "back_boring_cycle", "back_boring_moves",
           "circular_pocket_cycle", "single_lip_cycle", "single_lip_moves", "scaled_cycle", "pattern_positions",
           "hole_moves", "SAME_MOVES", "finishing_cycle", "old_slot_cycle", "REFUSED_CYCLES", "takes_point_angle",
           "point_depth", "to_second_clearance", "grid_order"]

#: ``CYCL DEF 7.1 X+0`` (also the ``CYCLE DEF`` some posts write): number, sub-number, rest.
CYCLE_RE = re.compile(r"CYCLE?\s+DEF\s*(\d+)(?:\.(\d+))?(?![\d.])\s*(.*)$", re.I)

#: Cycles run by M99 / CYCL CALL.
MACHINING_CYCLES: tuple[int, ...] = (1, 2, 4, 5, 17, 200, 201, 202, 203, 204, 205, 206, 207, 208, 209, 210, 211,
                                      212, 213, 214, 215, 230, 231, 232, 240, 241,
                                      251, 252, 253, 254, 256, 257, 262, 263, 264, 265, 267)
#: The thread-milling cycles (:func:`thread_milling_cycle`).
THREAD_CYCLES: tuple[int, ...] = (262, 263, 264, 265, 267)
#: Pattern cycles: DEF-active, they run the last machining cycle at each position.
PATTERN_CYCLES: tuple[int, ...] = (220, 221)
#: Cycles that run the moves of a newer one: 4 POCKET MILLING and 5 CIRCULAR POCKET as 251's / 252's roughing,
#: 212 POCKET FINISHING and 214 CIRCULAR POCKET FINISHING as 251's / 252's wall finishing, 213 STUD FINISHING
#: and 215 CIRCULAR STUD FINISHING as 256's / 257's revolutions (:func:`finishing_cycle`), 210 SLOT RECIP. PLNG
#: and 211 CIRCULAR SLOT as 253's and 254's slots (:func:`old_slot_cycle`).
SAME_MOVES: dict[int, int] = {4: 251, 5: 252, 212: 251, 214: 252, 213: 256, 215: 257, 210: 253, 211: 254}
#: Milling cycles of the TNC 640 / TNC 620 / iTNC 530 cycle manuals (and the old TNC 355/426 ones) vcnc refuses, with
#: why: the manuals found in the corpora give no cycle run for them, or their motion needs what vcnc does not model.
REFUSED_CYCLES: dict[int, str] = {
    3: "SLOT MILLING (the old cycle: no manual page of its run was found; CYCL DEF 253 SLOT MILLING runs)",
    6: "ROUGH-OUT (the old SL I cycle: no manual page found; the SL II cycles 20-24 run)",
    15: "PILOT DRILLING (the old SL I cycle: no manual page found; cycle 21 runs)",
    16: "CONTOUR MILLING (the old SL I cycle: no manual page found; cycles 24, 25 run)",
    18: "THREAD CUTTING (spindle-synchronised single-point threading: no manual page of its run was found)",
    27: "CYLINDER SURFACE (a contour unrolled onto a rotary axis)",
    28: "CYLINDER SURFACE SLOT (a contour unrolled onto a rotary axis)",
    29: "CYLINDER SURFACE RIDGE (a contour unrolled onto a rotary axis)",
    39: "CYLINDER SURFACE CONTOUR (a contour unrolled onto a rotary axis)",
    224: "DATAMATRIX CODE PATTERN (the code's dot pattern is not modelled)",
    225: "ENGRAVING (the control's font is not modelled)",
    258: "POLYGON STUD (the manual found, TNC7 basic 81762x-19, gives its sequence but neither the spiral path nor "
         "the parameter list)",
    270: "CONTOUR TRAIN DATA (cycle 25's approach and departure by it are not modelled)",
    271: "OCM CONTOUR DATA (optimized contour milling: trochoidal paths not modelled)",
    272: "OCM ROUGHING (optimized contour milling: trochoidal paths not modelled)",
    273: "OCM FINISHING FLOOR (optimized contour milling is not modelled)",
    274: "OCM FINISHING SIDE (optimized contour milling is not modelled)",
    275: "TROCHOIDAL SLOT (trochoidal paths are not modelled)",
    276: "THREE-D CONTOUR TRAIN (3-D contour trains are not modelled)",
    277: "OCM CHAMFERING (optimized contour milling is not modelled)",
}
#: Most infeeds of one hole (a guard against a mistyped plunging depth such as ``Q202=0.0000001``).
MAX_INFEEDS: int = 100_000
#: Most machining positions of one pattern: cycle 220's Q241 "Number of repetitions ... Input range 1 to 99999"
#: (TNC 320 user's manual for cycle programming 9/2016, "POLAR PATTERN (Cycle 220)", p. 178; TNC 640 34059x-01
#: p. 162); our reading applies the same bound to cycle 221's Q242 x Q243 and to a PATTERN DEF's NUM and its
#: whole list (the PATTERN DEF dialog's input ranges are on pages not in the search index): a mistyped
#: ``NUM100000000`` is an error, not hours of moves filling the memory.
MAX_PATTERN_POSITIONS: int = 99_999
#: Retraction of cycle 202 from the wall at the bottom, in the direction Q214 [mm] (a fixed value).
BORING_DISENGAGE = 0.2

#: The Q parameters a cycle definition must give (TNC 320 cycle programming manual, the cycles' parameter
#: lists; the others have the defaults of the TNC's cycle dialog).
_REQUIRED = {
    200: (200, 201, 206, 203, 204), 201: (200, 201, 206, 203, 204), 202: (200, 201, 206, 203, 204),
    203: (200, 201, 206, 203, 204), 204: (200, 249, 250, 251, 252, 253, 254, 203, 204, 214),
    205: (200, 201, 206, 203, 204), 206: (200, 201, 206, 203, 204),
    207: (200, 201, 239, 203, 204), 208: (200, 201, 206, 334, 203, 204, 335),
    209: (200, 201, 239, 203, 204, 257), 240: (200, 201, 206, 203, 204), 241: (200, 201, 206, 203, 204),
    262: (335, 239, 201, 355, 253, 351, 200, 203, 204, 207),
    263: (335, 239, 201, 356, 253, 351, 200, 203, 204, 207),
    264: (335, 239, 201, 356, 253, 351, 200, 203, 204, 206, 207),
    265: (335, 239, 201, 253, 200, 203, 204, 207), 267: (335, 239, 201, 253, 351, 200, 203, 204, 207),
    252: (215, 223, 201, 202, 206, 207, 200, 203, 204), 251: (215, 218, 219, 201, 202, 206, 207, 200, 203, 204),
    256: (218, 424, 219, 425, 201, 202, 206, 207, 200, 203, 204),
    253: (218, 219, 201, 202, 206, 207, 200, 203, 204), 257: (223, 222, 201, 202, 206, 207, 200, 203, 204),
    254: (219, 375, 216, 217, 376, 248, 201, 202, 206, 207, 200, 203, 204),
    210: (200, 201, 207, 202, 215, 203, 204, 216, 217, 218, 219, 224),
    211: (200, 201, 207, 202, 215, 203, 204, 216, 217, 244, 219, 245, 248),
    212: (200, 201, 206, 202, 207, 203, 204, 216, 217, 218, 219),
    213: (200, 201, 206, 202, 207, 203, 204, 216, 217, 218, 219),
    214: (200, 201, 206, 202, 207, 203, 204, 216, 217, 222, 223),
    215: (200, 201, 206, 202, 207, 203, 204, 216, 217, 222, 223),
    220: (216, 217, 244, 245, 246, 247, 241, 200, 203, 204), 221: (225, 226, 237, 238, 242, 243, 200, 203, 204),
}

#: (cycle, Q) whose value may be ``MAX`` (rapid): 204's pre-positioning feed, the retraction feed of
#: 201/202/203 (the Fusion 360 TNC post writes ``Q208=MAX`` in cycle 203), 241's and 205's feed to the deepened
#: starting point (TNC 640 cycle manual, cycle 205: Q253 "alternatively FMAX").
_MAX_ALLOWED = frozenset({(204, 253), (201, 208), (202, 208), (203, 208), (241, 208), (241, 253), (205, 253)})
_Q_RE = re.compile(r"\s*Q(\d+)\s*=\s*", re.I)

#: The cycle's name after its number, as the TNC saves it in the language of its dialogs: ``DRILLING``,
#: ``BOHREN``, ``TAPPING W/ CHIP BRKG``, ``SINGLE-LIP D.H.DRLNG``, ``VRTÁNÍ`` (TNC 640 cycle programming
#: manual, examples "11 CYCL DEF 200 DRILLING"; the German manual "CYCL DEF 200 BOHREN"): any text up to
#: the first ``Qnnn=`` that is not itself an assignment (no ``=``). The name has no meaning for the run.
_CYCLE_NAME_RE = re.compile(r"\s*(?!Q\d)[^\s=][^=]*?(?=\s+Q\d+\s*=|\s*$)", re.I)
_FMAX_RE = re.compile(r"F?MAX(?![A-Z0-9])", re.I)
_AUTO_RE = re.compile(r"F?AUTO(?![A-Z0-9])", re.I)


@dataclasses.dataclass(frozen=True, kw_only=True)
class DrillCycle:
    """A drilling cycle as defined, in program units converted to mm, mm/s and s.

    Attributes
    ----------
    number : int
        Cycle number (1, 200, 203 or 205).
    setup : float
        Set-up clearance above the surface [mm] (>= 0).
    depth : float
        Hole depth from the surface [mm]; its sign is the working direction along the tool axis.
    plunge : float
        Plunging depth per infeed [mm] (> 0; a depth at least the hole's drills in one pass).
    feed : float
        Drilling feed [mm/s].
    dwell_top, dwell_bottom : float
        Dwell at the set-up clearance between infeeds / at the hole bottom [s].
    surface : float or None
        Surface coordinate in the tool axis [mm, program]; ``None`` for cycle 1 (the surface is
        the set-up clearance below the starting point).
    second_setup : float
        2nd set-up clearance from the surface [mm]: the end height of a 200-series cycle.
    decrement : float
        Q212: each infeed is smaller by this [mm] (203/205), down to ``min_plunge``.
    min_plunge : float
        Q205: smallest infeed [mm].
    chip_breaks : int
        Q213 (203): chip breaks before a full retraction; 0 retracts every infeed.
    chip_break : float
        Q256: retraction of a chip break [mm].
    chip_depth : float
        Q257 (205): within each infeed the tool breaks the chip (retracting ``chip_break`` at rapid) after
        every ``chip_depth`` [mm]; 0: no chip breaking.
    retract_feed : float or None
        Q208 (203): retraction feed [mm/s]; ``None`` retracts at rapid.
    advance : float or None
        Advanced stop distance [mm]: how far above the last depth a re-entry at rapid stops
        (205: Q258); ``None``: the cycle's own rule (1: 0.6 mm, or depth/50 up to 7 mm, for holes
        deeper than 30 mm; 200/203: the set-up clearance).
    advance_last : float or None
        205: Q259, the advanced stop distance of the last re-entry [mm]; the re-entries between the
        first (Q258) and the last change it at the same rate (``None``: all Q258).
    disengage : tuple of float
        Cycle 202: the move off the wall at the bottom, in the working plane's (reference, minor)
        axes [mm, program directions] (Q214; (0, 0): none).
    bore_diameter : float
        Cycle 208: the nominal diameter Q335 [mm] (0 for the other cycles).
    helix_pitch : float
        Cycle 208: the infeed per helix turn Q334 [mm].
    climb : bool
        Cycles 208, 262: climb milling with M3 (Q351 = +1: counter-clockwise), else up-cut (clockwise).
    right_hand : bool
        Cycle 262: a right-hand thread (Q239 > 0); with ``climb`` it gives the milling direction.
    continuous : bool
        Cycle 262: Q355 = 1, one helix over the whole thread depth (else Q355 = 0: one 360 degree turn).
    threads_per_step : int
        Cycles 262, 267: Q355 > 1, several 360 degree helices offset by Q355 pitches (0: one).
    approach_feed : float
        Cycle 262: Q253, the feed in and out along the tool axis [mm/s]; 252: Q206, the plunging feed; 241 and
        205: Q253, the feed down to the deepened starting point.
    side_allowance, floor_allowance : float
        Cycle 252: Q368, Q369, the finishing allowances on the wall and the floor [mm].
    stepover : float
        Cycle 252: Q370, the path overlap factor: the rings are Q370 x the tool radius apart [-].
    operation : int
        Cycle 252: Q215, 0 roughing and finishing, 1 roughing only, 2 finishing only.
    finish_infeed : float
        Cycle 252: Q338, the infeed of the wall finishing [mm]; 0: one pass at the full depth.
    finish_feed : float
        Cycle 252: Q385, the finishing feed [mm/s].
    sides : tuple of float
        Cycle 251: Q218, Q219, the pocket's side lengths along its reference and minor axes [mm].
    corner : float
        Cycle 251: Q220, the pocket's corner radius [mm].
    angle : float
        Cycle 251: Q224, the pocket's rotation about its centre [deg].
    blank : tuple of float
        Cycle 256: Q424, Q425, the workpiece blank's side lengths [mm].
    counterbore : float
        Cycle 204: Q249, the depth of the counterbore from the workpiece's underside, its sign the
        direction along the tool axis (+: towards the spindle) [mm].
    edge_height : float
        Cycle 204: Q252, the distance from the underside of the boring bar (the tool tip) up to its
        main cutting tooth [mm].
    sink_depth : float
        Cycle 263: Q356, the countersinking depth from the surface, signed as the depth (0: none) [mm];
        cycle 264: Q356, the total hole depth drilled before the thread [mm].
    sink_side : bool
        Cycle 263: Q357 != 0, a set-up clearance to the side: the tool goes to the countersinking
        depth at Q253 in one move (else at Q253 to the set-up clearance above it, then at Q254).
    front_depth, front_offset : float
        Cycles 263, 264, 265: Q358, the depth of the countersinking at the front (0: none), signed as
        the depth, and Q359, the offset of the tool centre from the hole centre for it [mm].
    front_after : bool
        Cycle 265: Q360 = 1, the countersinking at the front after the thread (0: before).
    sink_feed : float
        Cycles 263-265: Q254, the countersinking feed [mm/s].
    drill_feed : float
        Cycle 264: Q206, the drilling feed [mm/s].
    outside : bool
        Cycle 267: an outside thread (the helix on Q335 / 2 plus the tool radius, from outside).
    plunge_type : int
        Cycles 251-254: Q366, 0 vertical plunging, 1 helical, 2 reciprocating (251, 253).
    slot : tuple of float
        Cycle 254: the pitch circle's centre Q216, Q217 [mm, program], its radius Q375 / 2 [mm], the slot's
        angular length Q248 and the stepping angle Q378 between repetitions [deg] (the starting angle
        Q376 is ``angle``, the width Q219 ``bore_diameter``).
    repeats : int
        Cycle 254: Q377, the number of slots on the pitch circle.
    start_depth : float
        Cycles 241, 205: Q379, the deepened starting point below the surface [mm] (0: none).
    dwell_depth : float
        Cycle 241: Q435, the depth below the surface where the tool dwells Q211 on its way down [mm] (0: none).
    reduced_feed : float or None
        Cycle 241: the feed below the dwell depth, Q206 x Q401 / 100 [mm/s] (``None``: Q206).
    place : tuple of float or None
        Cycles 210, 212-215: the centre Q216, Q217 [mm, program] the tool goes to at the clearance height first
        (``None``: the cycle runs where the tool is).
    centre_offset : tuple of float
        Cycles 251, 253, 256 with Q367 = 1..4: the pocket's, slot's or stud's centre from the tool's position at
        the call [mm, program directions, turned by Q224 / Q374] (see :func:`beside_tool_offset`).
    wall_only : bool
        Cycles 210, 211, 212, 214: the finishing runs round the wall only (no floor finishing, as 251/252's Q215 = 2
        has), with Q215 = 0 also without a side allowance.
    lead : float
        Cycles 256, 257: how far beyond the blank the starting position lies [mm] (2 mm, the manual's); 213: Q221;
        215: from the finished diameter out to the blank's Q222.
    """

    number: int
    setup: float
    depth: float
    plunge: float
    feed: float
    dwell_top: float = 0.0
    dwell_bottom: float = 0.0
    surface: float | None = None
    second_setup: float = 0.0
    decrement: float = 0.0
    min_plunge: float = 0.0
    chip_breaks: int = 0
    chip_break: float = 0.0
    chip_depth: float = 0.0
    retract_feed: float | None = None
    advance: float | None = None
    disengage: tuple[float, float] = (0.0, 0.0)
    bore_diameter: float = 0.0
    helix_pitch: float = 0.0
    climb: bool = True
    right_hand: bool = True
    continuous: bool = False
    threads_per_step: int = 0
    approach_feed: float = 0.0
    side_allowance: float = 0.0
    floor_allowance: float = 0.0
    stepover: float = 1.0
    operation: int = 0
    finish_infeed: float = 0.0
    finish_feed: float = 0.0
    sides: tuple[float, float] = (0.0, 0.0)
    corner: float = 0.0
    angle: float = 0.0
    blank: tuple[float, float] = (0.0, 0.0)
    counterbore: float = 0.0
    edge_height: float = 0.0
    advance_last: float | None = None
    sink_depth: float = 0.0
    sink_side: bool = False
    front_depth: float = 0.0
    front_offset: float = 0.0
    front_after: bool = False
    sink_feed: float = 0.0
    drill_feed: float = 0.0
    outside: bool = False
    plunge_type: int = 0
    slot: tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)
    repeats: int = 1
    start_depth: float = 0.0
    dwell_depth: float = 0.0
    reduced_feed: float | None = None
    place: tuple[float, float] | None = None
    wall_only: bool = False
    lead: float = 2.0
    centre_offset: tuple[float, float] = (0.0, 0.0)

    @property
    def shape(self) -> int:
        """The newer cycle whose moves this one runs (:data:`SAME_MOVES`; itself for the others)."""
        return SAME_MOVES.get(self.number, self.number)


def q_assignments(rest: str, where: Where, params: QParameters, *, column0: int,
                  auto_feed: float | None = None) -> dict[int, float]:
    """The ``Qnnn=value`` assignments of a 200-series definition (values may be Q parameters). A feed
    written ``AUTO`` (``Q207= AUTO``, as the iTNC 530 saves the soft key FAUTO: TNC 640 cycle manual, the
    feed parameters "alternatively FAUTO, FU, FZ") is ``auto_feed``, the F of the last ``TOOL CALL``
    [program units/min]; without one, an error."""
    out: dict[int, float] = {}
    pos = 0
    m = _CYCLE_NAME_RE.match(rest, pos)
    if m:
        pos = m.end()
    while pos < len(rest) and rest[pos:].strip():
        m = _Q_RE.match(rest, pos)
        if m is None:
            tok = rest[pos:].split()[0]
            if re.fullmatch(r"Q\d+", tok, re.I):  # 'Q206 FAUTO': a TNC simulator's test program wrote it so
                where.fail(f"cycle parameter {tok} without '='", column=column0 + pos,
                           text=" ".join(rest[pos:].split()[:2]),
                           expected=f"{tok}=value (a number, a Q parameter, or for a feed FAUTO / FMAX)")
            where.fail(f"unexpected {tok!r} in a cycle definition", column=column0 + pos, text=tok,
                       expected="Qnnn=value assignments")
        fmax = _FMAX_RE.match(rest, m.end())
        auto = _AUTO_RE.match(rest, m.end())
        if fmax:  # a feed given as MAX (rapid), as the Fusion 360 TNC post writes Q253 of cycle 204
            value, pos = math.inf, fmax.end()
        elif auto:
            if auto_feed is None:
                where.fail(f"Q{m.group(1)}=AUTO without a feed in the TOOL CALL", column=column0 + m.start(),
                           text=rest[m.start():auto.end()].strip(), expected="TOOL CALL n Z S.. F.. before the cycle")
            value, pos = auto_feed, auto.end()
        else:
            value, pos = read_value(rest, m.end(), where, params, what=f"Q{m.group(1)}", column0=column0)
        out[int(m.group(1))] = value
        if not fmax:  # the parameter store holds finite values only
            params.set(f"Q{m.group(1)}", value, where, column=column0 + m.start())
    return out


def legacy_value(rest: str, where: Where, params: QParameters, *, column0: int, what: str) -> float | None:
    """The value of an old-style cycle line (``DIST27.5``, ``SET UP 2``, ``F 500``, ``T0.05``,
    ``DWELL 1.5``, ``5``): the number (or Q parameter) after the item's name; None when empty. A dot right
    after a letter ends the name (``V.ZEIT``, the Polish ``CZAS ZWL.0.5``: dwell 0.5 s), as the TNC writes
    a number with its leading digit (``T0.05``; our reading of the saved dialog texts). The English names
    of the TNC's own dialog (``DWELL``, ``SET UP``, ``DEPTH`` .., :data:`_ENGLISH_ITEMS`) have no dot of
    their own: after one of them a dot is the number's decimal point, ``DWELL.5`` 0.5 s (our reading; a
    post writing the number without its leading zero and blank; the TNC 355 post of Fusion writes
    ``DWELL 0.5``)."""
    m = _ENGLISH_ITEM_RE.match(rest) or \
        re.match(r"\s*([A-Z][A-Z\-. ]*?)?\s*(?=[+-]?\s*(?:\d|(?<![A-Z])\.\d|Q))", rest, re.I)
    if m is None:
        if rest.strip() == "":
            return None
        where.fail(f"no value for {what} in {rest.strip()!r}", column=column0, text=rest.strip(),
                   expected=f"{what} followed by a number")
    value, end = read_value(rest, m.end(), where, params, what=what, column0=column0)
    if rest[end:].strip():
        tok = rest[end:].strip()
        where.fail(f"unexpected {tok!r} after {what}", column=column0 + end, text=tok, expected="one value")
    return value


#: The English item names of the old cycles' dialog (TNC 355 / 426 user's manuals: 1 PECKING, 2 TAPPING, 4 / 5
#: POCKET, 9 DWELL TIME, 17 RIGID TAPPING, 32 TOLERANCE), none with a dot of its own.
_ENGLISH_ITEMS = ("SET UP", "SETUP", "DIST", "DEPTH", "PECKG", "PLNGNG", "DWELL", "TIME", "PITCH", "RADIUS")
_ENGLISH_ITEM_RE = re.compile(r"\s*(" + "|".join(_ENGLISH_ITEMS) + r")\s*(?=[+-]?\s*\.\d)", re.I)


#: The old cycles defined item by item (``CYCL DEF n.1`` ...): number -> the item that completes the definition.
LEGACY_CYCLES: dict[int, int] = {1: 5, 2: 4, 4: 6, 5: 5, 17: 3}


def tapping_cycle(number: int, items: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                  column: int, spindle: float | None) -> DrillCycle:
    """The old tapping cycles from the starting point, the set-up clearance ahead of the surface (TNC
    426/430 user's manual, "Cycles for drilling"): 2 TAPPING (2.1 set-up clearance, 2.2 depth, 2.3
    dwell [s], 2.4 feed F: in at F, dwell, reversed out at F to the starting point) and 17 RIGID
    TAPPING (17.1 set-up clearance, 17.2 depth, 17.3 pitch: in and out at S x pitch)."""
    need = (1, 2, 4) if number == 2 else (1, 2, 3)
    missing = [f"{number}.{k}" for k in need if k not in items]
    if missing:
        where.fail(f"cycle {number} TAPPING lacks {', '.join(missing)}", column=column, text=where.text,
                   expected=f"{number}.1 set-up clearance, {number}.2 depth, "
                            + ("2.3 dwell, 2.4 feed" if number == 2 else "17.3 pitch"))
    if number == 2:
        feed = items[4] * feed_scale
    else:
        if not spindle:
            where.fail("cycle 17: the feed is the spindle speed times the pitch, and no speed is known",
                       column=column, text=where.text, expected="TOOL CALL .. S<rpm> before the cycle")
        feed = spindle * abs(items[3]) * scale / 60.0
    depth = items[2] * scale
    return _checked(DrillCycle(number=number, setup=abs(items[1]) * scale, depth=depth, plunge=abs(depth), feed=feed,
                               dwell_bottom=items.get(3, 0.0) if number == 2 else 0.0, retract_feed=feed),
                    where, column)


#: A word of a pocket line: F, DR+/-, or an item's name; as in :func:`legacy_value` a dot right after a letter is the
#: name's, not the number's (the Czech 'BEZP.VZD. 2': set-up clearance 2; it read '.VZD.' as the number), except
#: after an English name of the TNC's dialog (:data:`_ENGLISH_ITEMS`): 'SET UP.5' is 0.5, as 'DWELL.5' is.
_POCKET_ITEM_RE = re.compile(r"\s*(?:(F)\s*(?=[+-]?\s*[\d.Q(])|(DR)\s*([+-])(?![\d.Q(])"
                             r"|(?:" + "|".join(_ENGLISH_ITEMS) + r")\s*(?=[+-]?\s*\.\d)"  # 'SET UP.5': 0.5
                             r"|([A-Z][A-Z\-. ]*?)\s*(?=[+-]?\s*(?:\d|(?<![A-Z])\.\d|Q|\()))", re.I)


_POCKET_LINES = {4: "4.1 SET UP d, 4.2 DEPTH d, 4.3 PECKG d F f, 4.4 X l1, 4.5 Y l2, 4.6 F f DR+|DR- RADIUS r",
                 5: "5.1 SET UP d, 5.2 DEPTH d, 5.3 PECKG d F f, 5.4 RADIUS r, 5.5 F f DR+|DR-"}


def pocket_item(number: int, sub: int, rest: str, where: Where, params: QParameters, *,
                column0: int) -> dict[str, float]:
    """The words of line ``number.sub`` of the old cycles 4 POCKET MILLING and 5 CIRCULAR POCKET: a named value
    (``SET UP-2``, ``TIEFE-5,9``, ``X+60``, ``RADIUS10``: key ``"value"``), ``F`` a feed (``PECKG -1.5 F50``,
    ``F450``) and ``DR+``/``DR-`` (key ``"DR"`` = +1 / -1)."""
    out: dict[str, float] = {}
    pos = 0
    while rest[pos:].strip():
        m = _POCKET_ITEM_RE.match(rest, pos)
        if m is None:
            tok = rest[pos:].split()[0]
            where.fail(f"unexpected {tok!r} in cycle {number}.{sub}", column=column0 + pos, text=tok,
                       expected=_POCKET_LINES[number])
        if m.group(2):
            out["DR"], pos = (1.0 if m.group(3) == "+" else -1.0), m.end()
            continue
        key = "F" if m.group(1) else "value"
        if key in out:
            tok = rest[m.start():].split()[0]
            where.fail(f"a second value {tok!r} in cycle {number}.{sub}", column=column0 + m.start(), text=tok,
                       expected="one value per item")
        out[key], pos = read_value(rest, m.end(), where, params, what=f"cycle {number}.{sub}", column0=column0)
    return out


def old_pocket(number: int, items: dict[int, dict[str, float]], *, feed_scale: float, scale: float,
               where: Where, column: int) -> DrillCycle:
    """Cycle 4 POCKET MILLING or 5 CIRCULAR POCKET from its lines (:func:`old_circular_pocket`,
    :func:`old_rectangular_pocket`)."""
    last = 6 if number == 4 else 5
    values = (1, 2, 3, 4, 5) if number == 4 else (1, 2, 3, 4)
    missing = [f"{number}.{k}" for k in values if "value" not in items.get(k, {})]
    if missing or "F" not in items.get(3, {}) or "F" not in items.get(last, {}):
        where.fail(f"cycle {number} {'POCKET MILLING' if number == 4 else 'CIRCULAR POCKET'} lacks "
                   + (", ".join(missing) or f"a feed F in {number}.3 / {number}.{last}"),
                   column=column, text=where.text, expected=_POCKET_LINES[number])
    if not items[3]["F"] > 0:
        where.fail(f"cycle {number}: the plunging feed must be > 0", column=column, text=where.text,
                   expected=f"{number}.3 PECKG d F f with f > 0 [mm/min]")
    common = dict(setup=abs(items[1]["value"]) * scale, depth=items[2]["value"] * scale,
                  plunge=abs(items[3]["value"]) * scale, feed=items[last]["F"] * feed_scale,
                  approach_feed=items[3]["F"] * feed_scale, climb=items[last].get("DR", 1.0) > 0, stepover=1.0,
                  operation=0)
    if number == 5:
        return old_circular_pocket(items, common, scale=scale, where=where, column=column)
    return old_rectangular_pocket(items, common, scale=scale, where=where, column=column)


def old_circular_pocket(items: dict[int, dict[str, float]], common: dict, *, scale: float, where: Where,
                        column: int) -> DrillCycle:
    """Cycle 5 CIRCULAR POCKET from its lines 5.1 .. 5.5 (TNC 426/430 user's manual, "Cycles for milling
    pockets, studs and slots", CIRCULAR POCKET (Cycle 5)): 5.1 set-up clearance (tool tip at the starting
    position to the surface), 5.2 depth, 5.3 plunging depth and its feed F, 5.4 radius, 5.5 the milling feed F
    and DR+ (climb milling with M3: counter-clockwise) / DR- (up-cut: clockwise). Cycle run: from the
    starting position over the pocket centre the tool plunges to each plunging depth, then "follows a spiral
    path at the feed rate F" out to the pocket wall, the paths the stepover factor k = K x R apart (K: the
    machine parameter MP7430), until the depth is reached; finally it returns to the starting position.

    It runs as cycle 252's roughing (Q215 = 0 without allowances, so no finishing pass): the spiral becomes
    full circles about the centre, reached by straight steps outward (our reading of the "spiral", kept inside
    the pocket), K = 1 (MP7430 is the machine tool builder's; 1 is our choice); the surface is the set-up
    clearance beyond the starting point, as in cycle 1, and the tool ends back at the starting position."""
    radius = abs(items[4]["value"]) * scale
    if not radius > 0:
        where.fail("cycle 5: radius 0", column=column, text=where.text, expected="5.4 RADIUS r > 0 [mm]")
    return _checked(DrillCycle(number=5, bore_diameter=2.0 * radius, **common), where, column)


def old_rectangular_pocket(items: dict[int, dict[str, float]], common: dict, *, scale: float, where: Where,
                           column: int) -> DrillCycle:
    """Cycle 4 POCKET MILLING from its lines 4.1 .. 4.6 (TNC 426/430 user's manual, "POCKET MILLING (Cycle
    4)"): 4.1 set-up clearance, 4.2 depth, 4.3 plunging depth and its feed F, 4.4 the first side length (along
    the reference axis), 4.5 the second side length, 4.6 the milling feed F, DR+ (climb milling with M3) /
    DR- and the corner radius RADIUS. Cycle run: from the starting position over the pocket centre the tool
    plunges to each plunging depth, "then moves first in the positive direction of the longer side (in square
    pockets, in the positive Y direction) and then roughs out the pocket from the inside out", paths K x R apart
    (MP7430), until the depth is reached; at the end it returns to the starting position.

    It runs as cycle 251's roughing (Q215 = 0 without allowances): rounded rectangles about the centre from the
    inside out, each entered from the centre along the pocket's first axis, which is the longer side (turned by
    90 degrees, i.e. +Y, when the second side is the longer or the pocket square); K = 1 and the surface as for
    cycle 5 (:func:`old_circular_pocket`)."""
    first, second = abs(items[4]["value"]) * scale, abs(items[5]["value"]) * scale
    if not (first > 0 and second > 0):
        where.fail("cycle 4: a side length 0", column=column, text=where.text, expected="4.4 X l1 > 0, 4.5 Y l2 > 0")
    turned = second >= first
    sides = (second, first) if turned else (first, second)
    return _checked(DrillCycle(number=4, bore_diameter=min(sides), sides=sides, angle=90.0 if turned else 0.0,
                               corner=abs(items[6].get("value", 0.0)) * scale, **common), where, column)


def pecking_cycle(items: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                  column: int) -> DrillCycle:
    """Cycle 1 PECKING from its items 1.1 .. 1.5 (program units; ``scale`` [mm per unit],
    ``feed_scale`` [mm/s per program feed unit])."""
    missing = [f"1.{k}" for k in (1, 2, 3, 5) if k not in items]
    if missing:
        where.fail(f"cycle 1 PECKING lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="1.1 set-up clearance, 1.2 depth, 1.3 plunging depth, 1.4 dwell, 1.5 feed")
    return _checked(DrillCycle(number=1, setup=abs(items[1]) * scale, depth=items[2] * scale,
                               plunge=abs(items[3]) * scale, feed=items[5] * feed_scale,
                               dwell_top=0.0, dwell_bottom=items.get(4, 0.0)), where, column)


def required_q(number: int, q: dict[int, float], where: Where, column: int) -> None:
    """An error naming the Q parameters that cycle ``number``'s definition lacks."""
    missing = [f"Q{k}" for k in _REQUIRED[number] if k not in q]
    if missing:
        where.fail(f"cycle {number} lacks {', '.join(missing)}", column=column, text=where.text,
                   expected="the cycle's Q parameters: " + " ".join(f"Q{k}" for k in _REQUIRED[number]))


def takes_point_angle(number: int, q: dict[int, float]) -> bool:
    """True when cycle ``number`` with the parameters ``q`` takes its depth from the tool's point angle: 200, 203,
    205 with Q395 = 1, 240 with Q343 = 1 (:func:`point_depth`)."""
    return bool(number in (200, 203, 205) and q.get(395, 0.0) or number == 240 and q.get(343, 0.0))


def point_depth(number: int, q: dict[int, float], *, scale: float, tool: tuple[float, float], where: Where,
                column: int) -> float:
    """The depth of the tool tip below the surface [mm, signed as Q201] of cycle ``number``; ``tool`` is the called
    tool's radius [mm] and point angle [deg] (0: none).

    The TNC 640 user's manual for cycle programming names the point angle in the tool table's T-ANGLE column
    for two parameters: cycles 200, 203, 205 "Q395 Depth reference": 0 the depth Q201 to the tool tip, 1 to the
    cylindrical part of the tool; cycle 240 "Q343 Select diameter/depth (1/0)": 1 centering to the diameter
    Q344 (its sign the working direction) instead of the depth Q201 (iTNC 530 technical manual 07/2013, 9.5.4,
    ID50 NR32 "Point angle for DRILL and CSINK T-ANGLE"). Our reading of the geometry: a cone of that point angle
    ends r / tan(angle / 2) below where it reaches the radius r, so Q395 = 1 drills the tip that much deeper
    (r the tool radius) and Q343 = 1 centres to the depth that gives the diameter Q344 (r = |Q344| / 2). Without
    a point angle in the tool table the TNC cannot work either out: an error naming the column. A point angle of
    180 deg is a flat end (:attr:`interpolators.context.Tool.point_angle`): Q395 = 1 drills to Q201 as 0 does, and
    Q343 = 1 has no depth that gives a diameter (an error)."""
    if not takes_point_angle(number, q):
        return q[201] * scale
    radius, angle = tool
    what = "Q343=1 (centering to the diameter Q344)" if number == 240 else "Q395=1 (depth to the full diameter)"
    if not 0.0 < angle <= 180.0:
        where.fail(f"cycle {number}: {what} needs the tool's point angle, and the called tool has none",
                   column=column, text=where.text,
                   expected="a point angle in the tool table (T-ANGLE, [program.tools.n] point_angle) or "
                            + ("Q343=0 (depth Q201)" if number == 240 else "Q395=0 (depth to the tool tip)"))
    slope = math.tan(math.radians(angle) / 2.0)
    if number == 240:
        if angle == 180.0:
            where.fail(f"cycle 240: {what} needs a pointed tool, and the called tool's point angle is 180 deg (a flat "
                       "end, no depth gives a diameter)", column=column, text=where.text,
                       expected="a centering tool with a point angle below 180 deg (T-ANGLE), or Q343=0 (depth Q201)")
        if q.get(344, 0.0) == 0.0:
            where.fail("cycle 240: Q343=1 centres to the diameter Q344, which is 0", column=column, text=where.text,
                       expected="Q344 < 0 [mm] (the diameter, its sign the working direction)")
        return math.copysign(abs(q[344]) * scale / 2.0 / slope, q[344])
    if radius <= 0.0:
        where.fail(f"cycle {number}: {what} needs the tool radius, and the called tool has none", column=column,
                   text=where.text, expected="a tool with a radius > 0, or Q395=0 (depth to the tool tip)")
    depth = q[201] * scale
    if angle == 180.0 or not depth:  # a flat end is at its full diameter at the tip
        return depth
    return math.copysign(abs(depth) + radius / slope, depth)


def drill_cycle(number: int, q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                column: int, spindle: float | None = None, tool: tuple[float, float] = (0.0, 0.0)) -> DrillCycle:
    """A 200-series machining cycle from its Q parameters (TNC 320 cycle programming manual 9/2016,
    "Fixed cycles: drilling" and "tapping"; ``spindle`` [rpm] is the speed of the last TOOL CALL,
    whose product with the pitch Q239 is the feed of 207 and 209):

    * 200 DRILLING, 203 UNIVERSAL DRILLING, 205 UNIVERSAL PECKING: pecks (see :func:`hole_moves`);
    * 201 REAMING: feed to depth, dwell Q211, retract at Q208 (0: at Q206) to the set-up clearance;
    * 202 BORING: as 201, then at the bottom the spindle is oriented and the tool moved off the
      wall by 0.2 mm (a fixed value) in the direction Q214 (1/3: minus/plus the reference axis,
      2/4: minus/plus the minor axis, 0: none) before the retraction at Q208 (0: Q206); back over
      the centre of the hole at the set-up clearance (our reading), then to the 2nd set-up clearance;
    * 206 TAPPING: feed to depth, dwell Q211, retract at the feed Q206;
    * 207 RIGID TAPPING: feed = S x pitch Q239 to depth and back to the set-up clearance;
    * 209 TAPPING WITH CHIP BREAKING: infeeds Q257, after each the tool backs off by Q256 x pitch
      (Q256 = 0: out to the set-up clearance) at the feed times Q403 (default 1), as it retracts at
      the bottom;
    * 240 CENTERING: feed to the depth Q201 (Q343 = 0), dwell Q211, rapid back;
    * 241 SINGLE-LIP DEEP-HOLE DRILLING: :func:`single_lip_cycle`;
    * 208 BORE MILLING: a helix of Q334 per turn on the diameter Q335 (heidenhain_cycle_moves'
      ``_bore_milling``), Q351 = +1 climb (with M3: counter-clockwise), -1 up-cut.
    """
    required_q(number, q, where, column)
    for k, v in q.items():
        if math.isinf(v) and (number, k) not in _MAX_ALLOWED:
            where.fail(f"cycle {number}: Q{k}=MAX is not a value here", column=column, text=where.text,
                       expected=f"Q{k}=<number>")
    if number == 204:
        return back_boring_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if number in THREAD_CYCLES:
        return thread_milling_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column, number=number)
    if number in (210, 211):
        return old_slot_cycle(number, q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if number in (212, 213, 214, 215):
        return finishing_cycle(number, q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if number in (251, 252, 253, 254, 256, 257):
        return circular_pocket_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column,
                                     number=number)
    if number == 241:
        return single_lip_cycle(q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if q.get(379, 0.0) != 0.0 and number != 205:
        where.fail(f"cycle {number}: a deepened starting point Q379 is not supported", column=column,
                   text=where.text, expected="Q379=0 (drilling from the set-up clearance above the surface)")
    if q.get(395, 0.0) != 0.0 and number not in (200, 203, 205):
        where.fail(f"cycle {number}: Q395=1 (depth to the full diameter) is not supported here", column=column,
                   text=where.text, expected="Q395=0 (depth to the tool tip)")
    depth = point_depth(number, q, scale=scale, tool=tool, where=where, column=column)
    base = dict(number=number, setup=abs(q[200]) * scale, depth=depth, surface=q[203] * scale,
                second_setup=q[204] * scale, dwell_bottom=q.get(211, 0.0))
    if number in (207, 209):
        if not spindle:
            where.fail(f"cycle {number}: the feed is the spindle speed times the pitch, and no speed is known",
                       column=column, text=where.text, expected="TOOL CALL .. S<rpm> before the cycle")
        feed = spindle * abs(q[239]) * scale / 60.0
        pitch = abs(q[239]) * scale
        back = feed * (q.get(403, 0.0) or 1.0)
        if number == 207:
            return _checked(DrillCycle(plunge=abs(depth), feed=feed, retract_feed=feed, **base), where, column)
        plunge = abs(q[257]) * scale or abs(depth)
        chip = abs(q.get(256, 0.0)) * pitch
        return _checked(DrillCycle(plunge=plunge, feed=feed, retract_feed=back, chip_breaks=10 ** 9 if chip else 0,
                                   chip_break=chip, **base), where, column)
    feed = q[206] * feed_scale
    if number in (201, 202, 206):
        back = (q.get(208, 0.0) or q[206]) * feed_scale if number != 206 else feed
        back = None if math.isinf(back) else back  # Q208=MAX: out at rapid
        side = {1: (-1.0, 0.0), 2: (0.0, -1.0), 3: (1.0, 0.0), 4: (0.0, 1.0)}.get(int(q.get(214, 0.0)), (0.0, 0.0))
        off = tuple(BORING_DISENGAGE * v for v in side) if number == 202 else (0.0, 0.0)
        return _checked(DrillCycle(plunge=abs(depth), feed=feed, retract_feed=back, disengage=off, **base),
                        where, column)
    if number == 240:
        return _checked(DrillCycle(plunge=abs(depth), feed=feed, **base), where, column)
    if number == 208:
        if q[334] == 0 and q[335] > 0:
            # the TNC 640 cycle manual gives Q334 the input range 0 .. 99999.9999 but no run without an infeed
            # per helix (a TNC simulator's demo program chamfers with Q334=0 and a 1 mm depth)
            where.fail("cycle 208 with Q334=0 (no infeed per helix) is not modelled: no manual page found says how "
                       "the control reaches the depth then", column=column, text=where.text,
                       expected="Q334 > 0 [mm] (the depth per helix turn)")
        if not q[334] > 0 or not q[335] > 0:
            where.fail("cycle 208: Q334 (infeed per helix) and Q335 (diameter) must be > 0", column=column,
                       text=where.text, expected="Q334 > 0 and Q335 > 0 [mm]")
        return _checked(DrillCycle(plunge=abs(depth), feed=feed, bore_diameter=q[335] * scale,
                                   helix_pitch=q[334] * scale, climb=q.get(351, 1.0) >= 0, **base), where, column)
    plunge = abs(q.get(202, 0.0)) * scale or abs(depth)
    start = _deepened_start(205, q, feed_scale=feed_scale, scale=scale, where=where, column=column) \
        if number == 205 else {}
    # 203: Q208 = 0 retracts at the drilling feed Q206 (TNC 426/430 manual, cycle 203)
    retract = (q.get(208, 0.0) or q[206]) if number == 203 else 0.0
    return _checked(DrillCycle(
        plunge=plunge, feed=feed, dwell_top=q.get(210, 0.0), decrement=abs(q.get(212, 0.0)) * scale,
        min_plunge=abs(q.get(205, 0.0)) * scale, chip_breaks=int(q.get(213, 0.0)) if number == 203 else 0,
        chip_break=abs(q.get(256, 0.2)) * scale if number in (203, 205) else 0.0,
        retract_feed=retract * feed_scale if 0 < retract < math.inf else None,  # Q208=MAX: rapid
        advance=abs(q.get(258, 0.2)) * scale if number == 205 else None,
        advance_last=abs(q[259]) * scale if number == 205 and 259 in q else None,
        chip_depth=abs(q.get(257, 0.0)) * scale if number == 205 else 0.0, **start, **base), where, column)


def _deepened_start(number: int, q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                    column: int) -> dict[str, float]:
    """The deepened starting point Q379 of cycle 205 or 241 (:func:`single_lip_cycle`) as :class:`DrillCycle`
    fields, checked. Cycle 205 (TNC 640 user's manual for cycle programming, "UNIVERSAL PECKING (Cycle 205)", cycle
    run: "If you enter a deepened starting point, the TNC moves at the defined positioning feed rate to the set-up
    clearance above the deepened starting point"; Q379 incremental from the surface, Q253 the feed for
    pre-positioning, MAX rapid). The infeeds then count
    from the deepened starting point (our reading: the manual's "first plunging depth" follows that move);
    between infeeds the tool retracts to the set-up clearance above the surface as without Q379."""
    start = abs(q.get(379, 0.0)) * scale
    if not start:
        return {}
    if start >= abs(q[201]) * scale:
        where.fail(f"cycle {number}: the deepened starting point Q379 must lie within the depth Q201", column=column,
                   text=where.text, expected="|Q379| < |Q201|")
    if not q.get(253, 0.0) > 0:
        where.fail(f"cycle {number}: a deepened starting point Q379 needs the pre-positioning feed Q253 > 0",
                   column=column, text=where.text, expected="Q253 > 0 [mm/min] or MAX")
    return {"start_depth": start, "approach_feed": q[253] * feed_scale}


def finishing_cycle(number: int, q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                    column: int) -> DrillCycle:
    """The old finishing cycles from their Q parameters (TNC 426/430 user's manual, "Cycles for milling pockets,
    studs and slots": POCKET FINISHING (Cycle 212), STUD FINISHING (Cycle 213), CIRCULAR POCKET FINISHING (Cycle
    214), CIRCULAR STUD FINISHING (Cycle 215); TNC 370 user's manual p. 8-20, cycle 213's process,
    https://www.easymanua.ls/heidenhain/tnc-370/manual?p=209): Q200 set-up clearance, Q201 depth, Q206 feed for
    plunging, Q202 plunging depth, Q207 milling feed, Q203 surface, Q204 2nd set-up clearance, Q216/Q217 the
    centre; 212/213: Q218, Q219 side lengths, Q220 corner radius, Q221 allowance for pre-positioning; 214/215:
    Q222 blank diameter, Q223 finished diameter.

    Cycle run: at the set-up clearance (or the 2nd one when higher) over the centre, from there in the plane to
    the starting point, at Q206 to each plunging depth, "tangentially to the contour of the finished part and,
    using climb milling, machines one revolution", tangentially off back to the starting point, until the depth;
    at FMAX to the clearance and over the centre. They run the moves of the newer cycles (:data:`SAME_MOVES`):
    212 and 214 as 251's and 252's wall finishing at each plunging depth from the centre (our reading: the
    manual's starting point "for which the TNC takes the allowance and the tool radius into account" is reached
    from the centre as those cycles reach their wall, which leaves Q221 and Q222 without motion), 213 and 215 as
    256's and 257's one revolution at the finished size at each depth, the starting point Q221 (213) or the blank
    Q222 (215) outside the stud (plus the tool radius; our reading of "takes into account the finishing allowance
    and the tool radius")."""
    required_q(number, q, where, column)
    depth = q[201] * scale
    if number in (212, 213):
        sides = (abs(q[218]) * scale, abs(q[219]) * scale)
        shape = dict(sides=sides, corner=abs(q.get(220, 0.0)) * scale, bore_diameter=min(sides))
        if number == 213:
            shape |= dict(blank=sides, lead=abs(q.get(221, 0.0)) * scale)
    else:
        d = abs(q[223]) * scale
        shape = dict(sides=(d, d), corner=d / 2.0, bore_diameter=d)
        if number == 215:
            if abs(q[222]) < abs(q[223]):
                where.fail("cycle 215: the blank Q222 must be at least the finished diameter Q223", column=column,
                           text=where.text, expected="Q222 >= Q223 [mm]")
            shape |= dict(blank=(d, d), lead=(abs(q[222]) - abs(q[223])) / 2.0 * scale)
    if not min(shape["sides"]) > 0 or not q[206] > 0:
        where.fail(f"cycle {number}: the pocket's or stud's size and the plunging feed Q206 must be > 0", column=column,
                   text=where.text, expected="Q218, Q219 (Q223) > 0, Q206 > 0")
    plunge = abs(q[202]) * scale or abs(depth)
    return _checked(DrillCycle(
        number=number, setup=abs(q[200]) * scale, depth=depth, plunge=plunge, feed=q[207] * feed_scale,
        surface=q[203] * scale, second_setup=q[204] * scale, approach_feed=q[206] * feed_scale,
        operation=1 if number in (213, 215) else 2, finish_infeed=plunge, finish_feed=q[207] * feed_scale,
        wall_only=number in (212, 214), place=(q[216] * scale, q[217] * scale), **shape), where, column)


def old_slot_cycle(number: int, q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                   column: int) -> DrillCycle:
    """210 SLOT RECIP. PLNG and 211 CIRCULAR SLOT from their Q parameters (TNC 426/430 user's manual, "Cycles for
    milling pockets, studs and slots", SLOT (oblong hole) with reciprocating plunge-cut (Cycle 210), CIRCULAR SLOT
    (oblong hole) with reciprocating plunge-cut (Cycle 211)): Q200, Q201, Q207 milling feed (also the plunging
    one), Q202 plunging depth (the infeed of one reciprocation), Q215 0 roughing and finishing, 1 roughing, 2
    finishing, Q203, Q204, Q338 infeed for finishing (0: one); 210: Q216/Q217 the slot's centre, Q218 its length,
    Q219 its width, Q224 its rotation; 211: Q216/Q217 the pitch circle's centre, Q244 its diameter, Q219 the width,
    Q245 the starting angle, Q248 the angular length.

    Cycle run: over the slot's first end circle at the 2nd set-up clearance, down to the set-up clearance; roughing
    reciprocates, plunging obliquely from one end to the other by Q202 per stroke, to the depth; finishing from the
    slot's centre tangentially onto its contour, climb milling round it, tangentially back. They run the moves of
    253 and 254 (:data:`SAME_MOVES`), our reading: 210 as 253 over the centre Q216/Q217 with Q366 = 2 (253's
    reciprocating plunge along the slot to each infeed) and 253's rings out to the wall (the manual's roughing
    stays on the centre line, leaving the wall to the finishing pass), 211 as 254 plunging vertically at the slot's
    first end (254 does not reciprocate along its arc) and its rings; the wall finished as 253's / 254's, climbing,
    no floor pass."""
    required_q(number, q, where, column)
    operation = int(q[215])
    if operation not in (0, 1, 2) or not q[207] > 0 or not q[219] > 0:
        where.fail(f"cycle {number}: Q215 must be 0, 1 or 2, the feed Q207 and the width Q219 > 0", column=column,
                   text=where.text, expected="Q215 in 0..2, Q207 > 0, Q219 > 0")
    depth, feed = q[201] * scale, q[207] * feed_scale
    width = q[219] * scale
    if number == 210:
        if not abs(q[218]) > abs(q[219]):
            where.fail("cycle 210: the slot length Q218 must exceed its width Q219", column=column, text=where.text,
                       expected="|Q218| > Q219 [mm]")
        shape = dict(sides=(abs(q[218]) * scale, width), corner=width / 2.0, angle=q[224], plunge_type=2,
                     place=(q[216] * scale, q[217] * scale))
    else:
        if not q[248] > 0 or not q[244] > q[219]:
            where.fail("cycle 211: the angular length Q248 must be > 0, the pitch circle Q244 wider than the slot "
                       "width Q219", column=column, text=where.text, expected="Q248 > 0, Q244 > Q219 > 0")
        shape = dict(slot=(q[216] * scale, q[217] * scale, q[244] / 2.0 * scale, q[248], 0.0), angle=q[245])
    return _checked(DrillCycle(
        number=number, setup=abs(q[200]) * scale, depth=depth, plunge=abs(q[202]) * scale or abs(depth), feed=feed,
        surface=q[203] * scale, second_setup=q[204] * scale, bore_diameter=width, approach_feed=feed,
        operation=operation, finish_infeed=abs(q.get(338, 0.0)) * scale, finish_feed=feed, wall_only=True,
        **shape), where, column)


def back_boring_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                      column: int) -> DrillCycle:
    """Cycle 204 BACK BORING from its Q parameters (TNC 320 / iTNC 530 user's manual for cycle
    programming, "BACK BORING (Cycle 204)"): Q200 set-up clearance, Q249 depth of the counterbore
    from the workpiece's underside (+: bored towards the spindle), Q250 material thickness, Q251
    off-centre distance of the boring bar, Q252 tool edge height (underside of the bar to the main
    cutting tooth), Q253 pre-positioning feed (``MAX``: rapid), Q254 counterboring feed, Q255 dwell
    at the top of the counterbore, Q203, Q204, Q214 disengaging direction (1/3: minus/plus the
    reference axis, 2/4: minus/plus the minor axis, 0: the bar is not moved off centre). Q336
    (spindle orientation) gives no motion. The moves are :func:`hole_moves`'.
    """
    if not q[250] > 0 or q[251] < 0 or q[252] < 0 or q[249] == 0:
        where.fail("cycle 204: the material thickness Q250 must be > 0, Q251 and Q252 >= 0, Q249 != 0",
                   column=column, text=where.text, expected="Q250 > 0, Q251 >= 0, Q252 >= 0, Q249 != 0 [mm]")
    if not q[253] > 0:
        where.fail("cycle 204: the pre-positioning feed Q253 must be > 0", column=column, text=where.text,
                   expected="Q253 > 0 [mm/min] or MAX")
    side = {1: (-1.0, 0.0), 2: (0.0, -1.0), 3: (1.0, 0.0), 4: (0.0, 1.0)}.get(int(q[214]), (0.0, 0.0))
    off = abs(q[251]) * scale
    return _checked(DrillCycle(
        number=204, setup=abs(q[200]) * scale, depth=-q[250] * scale, plunge=q[250] * scale,
        feed=q[254] * feed_scale, dwell_bottom=q.get(255, 0.0), surface=q[203] * scale,
        second_setup=q[204] * scale, disengage=(off * side[0], off * side[1]),
        approach_feed=q[253] * feed_scale, counterbore=q[249] * scale, edge_height=q[252] * scale), where, column)


def back_boring_moves(cycle: DrillCycle, *, surface: float) -> list[AxisMove]:
    """The moves of cycle 204 BACK BORING at one hole (TNC 320 / iTNC 530 user's manual for cycle
    programming, "BACK BORING (Cycle 204)", cycle run): FMAX to the set-up clearance above the
    surface; after the oriented spindle stop the bar moves the off-centre distance Q251 in the
    direction Q214; in at the pre-positioning feed Q253 until the tooth is the set-up clearance
    below the workpiece's underside (the tip a further Q252 lower); back over the centre; at the
    counterboring feed Q254 until the tooth is Q249 above the underside; dwell Q255; out of the
    cut at Q253 to the level below the underside (our reading of "retracted from the hole"), off
    centre again, at Q253 to the set-up clearance, back over the centre (our reading, as cycle 202),
    FMAX to the 2nd set-up clearance. ``surface`` [mm, machine] in the tool axis, which points
    away from the workpiece.
    """
    top = surface + cycle.setup
    underside = surface + cycle.depth  # depth = -Q250
    below = underside - cycle.setup - cycle.edge_height
    cut = underside + cycle.counterbore - cycle.edge_height
    kind, feed = ("rapid", math.inf) if math.isinf(cycle.approach_feed) else ("line", cycle.approach_feed)
    moved = cycle.disengage != (0.0, 0.0)
    out = [AxisMove("rapid", top)]
    out += [AxisMove("plane", top, offset=cycle.disengage)] if moved else []
    out.append(AxisMove(kind, below, feed))
    out += [AxisMove("plane", below)] if moved else []
    out.append(AxisMove("line", cut, cycle.feed))
    if cycle.dwell_bottom > 0:
        out.append(AxisMove("dwell", cut, 0.0, cycle.dwell_bottom))
    out.append(AxisMove(kind, below, feed))
    out += [AxisMove("plane", below, offset=cycle.disengage)] if moved else []
    out.append(AxisMove(kind, top, feed))
    out += [AxisMove("plane", top)] if moved else []
    return out + to_second_clearance(cycle, surface=surface)  # depth = -Q250 < 0: up is +


def single_lip_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                     column: int) -> DrillCycle:
    """Cycle 241 SINGLE-LIP DEEP-HOLE DRILLING from its Q parameters (iTNC 530 / TNC 640 user's manual for
    cycle programming, "SINGLE-LIP DEEP-HOLE DRILLING (Cycle 241)"; the moves are :func:`single_lip_moves`):
    Q200 set-up clearance, Q201 depth, Q206 plunging feed, Q211 dwell at the bottom, Q203 surface, Q204 2nd
    set-up clearance, Q379 deepened starting point (incremental from the surface; 0: none), Q253 feed for
    pre-positioning (``MAX``: rapid), Q208 retraction feed (0: Q206, ``MAX``: rapid), Q435 dwell depth
    (incremental from the surface, 0: none; the tool dwells Q211 there), Q401 feed factor below the dwell
    depth [%] (default 100). The spindle and coolant words Q426-Q430 move nothing. Infeeds Q202 shorter
    than the depth (the newer versions' pecking with Q212/Q205) are an error, as a Q379 deeper than the
    hole or a Q435 outside it."""
    depth = q[201] * scale
    dwell_at = abs(q.get(435, 0.0)) * scale
    if 0.0 < abs(q.get(202, 0.0)) < abs(q[201]):
        where.fail("cycle 241: infeeds Q202 shorter than the depth are not supported", column=column,
                   text=where.text, expected="Q202=0 or at least the depth Q201")
    start = _deepened_start(241, q, feed_scale=feed_scale, scale=scale, where=where, column=column)
    if dwell_at >= abs(depth):
        where.fail("cycle 241: the dwell depth Q435 must lie within the depth Q201", column=column, text=where.text,
                   expected="|Q435| < |Q201|")
    factor = q.get(401, 100.0)
    if not 0 < factor <= 100:
        where.fail("cycle 241: the feed factor Q401 must lie in (0, 100] %", column=column, text=where.text,
                   expected="0 < Q401 <= 100")
    back = (q.get(208, 0.0) or q[206]) * feed_scale
    return _checked(DrillCycle(
        number=241, setup=abs(q[200]) * scale, depth=depth, plunge=abs(depth), feed=q[206] * feed_scale,
        surface=q[203] * scale, second_setup=q[204] * scale, dwell_bottom=q.get(211, 0.0),
        retract_feed=None if math.isinf(back) else back, **start, dwell_depth=dwell_at,
        reduced_feed=q[206] * feed_scale * factor / 100.0 if dwell_at and factor != 100 else None), where, column)


def single_lip_moves(cycle: DrillCycle, *, surface: float) -> list[AxisMove]:
    """The tool-axis moves of cycle 241 (iTNC 530 / TNC 640 user's manual for cycle programming, "SINGLE-LIP
    DEEP-HOLE DRILLING (Cycle 241)", cycle run): FMAX to the set-up clearance above the surface; with a
    deepened starting point Q379, at the pre-positioning feed Q253 to the set-up clearance above the
    deepened starting point; at Q206 to the dwell depth Q435 and dwell Q211 there (when entered), on to the
    depth (below the dwell depth at Q206 x Q401 %); dwell Q211; out at the retraction feed Q208 to the set-up
    clearance above the surface, then FMAX to the 2nd set-up clearance when it is higher. ``surface`` is
    the tool-axis coordinate of the surface [mm, machine]."""
    d = -1.0 if cycle.depth < 0 else 1.0
    top = surface - d * cycle.setup
    out = [AxisMove("rapid", top)]
    entry = surface + d * (cycle.start_depth - cycle.setup)
    if cycle.start_depth:
        out.append(AxisMove("line", entry, cycle.approach_feed) if math.isfinite(cycle.approach_feed)
                   else AxisMove("rapid", entry))
    bottom = surface + cycle.depth
    feed = cycle.feed
    if cycle.dwell_depth:
        out.append(AxisMove("line", surface + d * cycle.dwell_depth, cycle.feed))
        if cycle.dwell_bottom > 0:
            out.append(AxisMove("dwell", surface + d * cycle.dwell_depth, 0.0, cycle.dwell_bottom))
        feed = cycle.reduced_feed or cycle.feed
    out.append(AxisMove("line", bottom, feed))
    if cycle.dwell_bottom > 0:
        out.append(AxisMove("dwell", bottom, 0.0, cycle.dwell_bottom))
    out.append(AxisMove("line", top, cycle.retract_feed) if cycle.retract_feed else AxisMove("rapid", top))
    return out + to_second_clearance(cycle, surface=surface)


def thread_milling_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                         column: int, number: int = 262) -> DrillCycle:
    """The thread-milling cycles from their Q parameters (TNC 426/430 user's manual, "Cycles for
    drilling, tapping and thread milling": 262's parameters p. 251, https://www.easymanua.ls/heidenhain/
    tnc-430/manual?p=277; 264's p. 244, ?p=270; 265's p. 247, ?p=273; TNC 320 user's manual 340 55x-03 p. 246,
    https://azmanual.top/manuals/798411/heidenhain-tnc-320-340-55x-03.html?page=246: 263's). The moves are
    heidenhain_cycle_moves' ``_thread_milling``.

    * 262 THREAD MILLING: Q335 nominal diameter, Q239 pitch (its sign: right-hand +, left-hand -), Q201
      thread depth, Q355 threads per step (0: one 360 degree helix, 1: one continuous helix over the
      thread depth; more: "several helical paths with approach and departure; between them, the TNC offsets
      the tool by Q355, multiplied by the pitch", p. 251), Q253 feed in and out of the hole, Q351
      climb (+1) or up-cut (-1) with M3, Q200, Q203, Q204, Q207 milling feed;
    * 263 THREAD MILLING/COUNTERSINKING: as 262 with one 360 degree helix, plus Q356 countersinking depth
      ("distance between tool point and the top surface of the workpiece"), Q357 set-up clearance to the
      side, Q358 depth and Q359 offset of the countersinking at the front, Q254 countersinking feed;
    * 264 BORE/THREAD MILLING: drills first, Q356 total hole depth in infeeds of Q202 at Q206, with Q258
      upper advanced stop distance, Q257 infeed for chip breaking, Q256 retraction for chip breaking (as
      cycle 205), then Q358/Q359 at the front and the thread as 263 (Q254 absent: Q206);
    * 265 HELICAL BORE/THREAD MILLING: Q335, Q239, Q201, Q253, Q358, Q359, Q360 countersinking at the front
      before (0) or after (1) the thread, Q200, Q203, Q204, Q254, Q207: one continuous helix from the
      surface down to the thread depth, turning with the thread (no Q351);
    * 267 OUTSIDE THREAD MILLING: as 262 about a stud; the countersinking at the front (Q358 != 0) is not
      supported.
    """
    q = {355: 0.0, 351: 1.0, 356: 0.0, 357: 0.0, 358: 0.0, 359: 0.0, 360: 0.0, **q}
    steps = int(q[355])
    if steps < 0 or q[355] != steps:
        where.fail(f"cycle {number}: Q355={q[355]:g} is not a number of threads", column=column, text=where.text,
                   expected="Q355=0 (one helix), 1 (continuous) or a whole number of threads per step")
    if q[239] == 0 or not q[335] > 0 or not q[253] > 0:
        where.fail(f"cycle {number}: the pitch Q239 must be != 0, the diameter Q335 and the feed Q253 > 0",
                   column=column, text=where.text, expected="Q239 != 0, Q335 > 0, Q253 > 0")
    if number == 267 and q[358] != 0.0:
        where.fail("cycle 267: the countersinking at the front (Q358 != 0) of an outside thread is not supported",
                   column=column, text=where.text, expected="Q358=0")
    depth = q[201] * scale
    sign = -1.0 if depth < 0 else 1.0
    sink_feed = (q.get(254, 0.0) or (q[206] if number == 264 else 0.0)) * feed_scale
    if number in (263, 264, 265) and (q[356] or q[358]) and not sink_feed > 0:
        where.fail(f"cycle {number}: the countersinking feed Q254 must be > 0", column=column, text=where.text,
                   expected="Q254 > 0 [mm/min]")
    extra = {}
    if number == 264:
        if abs(q[356]) < abs(q[201]) or not q[206] > 0:
            where.fail("cycle 264: the total hole depth Q356 must reach the thread depth Q201, the feed Q206 > 0",
                       column=column, text=where.text, expected="|Q356| >= |Q201|, Q206 > 0")
        extra = dict(plunge=abs(q.get(202, 0.0)) * scale or abs(q[356]) * scale, drill_feed=q[206] * feed_scale,
                     advance=abs(q.get(258, 0.0)) * scale, chip_depth=abs(q.get(257, 0.0)) * scale,
                     chip_break=abs(q.get(256, 0.0)) * scale)
    return _checked(DrillCycle(
        number=number, setup=abs(q[200]) * scale, depth=depth, **({"plunge": abs(depth)} | extra),
        feed=q[207] * feed_scale, surface=q[203] * scale, second_setup=q[204] * scale,
        bore_diameter=q[335] * scale, helix_pitch=abs(q[239]) * scale,
        climb=(q[351] >= 0) if number != 265 else q[239] < 0, right_hand=q[239] > 0,
        continuous=steps == 1 or number == 265, threads_per_step=steps if steps > 1 and number in (262, 267) else 0,
        approach_feed=q[253] * feed_scale,
        sink_depth=sign * abs(q[356]) * scale if number in (263, 264) else 0.0, sink_side=q[357] != 0.0,
        front_depth=sign * abs(q[358]) * scale, front_offset=abs(q[359]) * scale, front_after=q[360] == 1.0,
        sink_feed=sink_feed, outside=number == 267), where, column)


def circular_pocket_cycle(q: dict[int, float], *, feed_scale: float, scale: float, where: Where,
                          column: int, number: int = 252) -> DrillCycle:
    """Cycle 252 CIRCULAR POCKET from its Q parameters (TNC 640 user's manual for cycle programming,
    "CIRCULAR POCKET (Cycle 252)"): Q215 machining operation, Q223 diameter, Q368 side and Q369 floor
    finishing allowances, Q207 milling feed, Q351 climb (+1) / up-cut (-1), Q201 depth, Q202 plunging
    depth, Q206 plunging feed, Q338 finishing infeed, Q200, Q203, Q204, Q370 path overlap (default 1),
    Q366 plunging (0 or absent vertical, 1 helical; 251 and 253 also 2 reciprocating:
    heidenhain_cycle_moves' ``_plunge``), Q385 finishing feed (default Q207). The moves are
    heidenhain_cycle_moves' ``_circular_pocket``.

    ``number`` = 251: RECTANGULAR POCKET (TNC 640 manual, "RECTANGULAR POCKET (Cycle 251)") with Q218, Q219
    side lengths, Q220 corner radius, Q224 rotation instead of Q223; its position Q367 places the pocket
    beside the tool (:func:`beside_tool_offset`). The moves are heidenhain_cycle_moves' ``_circular_pocket``.

    ``number`` = 256: RECTANGULAR STUD (TNC 640 manual, "RECTANGULAR STUD (Cycle 256)"): Q218, Q219, Q220,
    Q224 as 251, Q424, Q425 the blank's sides (at least the stud's), Q215 absent: 0. The moves are
    heidenhain_cycle_moves' ``_rectangular_stud``.

    ``number`` = 253: SLOT MILLING (TNC 640 manual, "SLOT MILLING (Cycle 253)"): Q218 slot length, Q219 slot
    width, Q374 angle of rotation, Q367 slot position (:func:`beside_tool_offset`), the rest as 251. The slot is
    the rectangle Q218 x Q219 with the corner radius Q219 / 2 (two
    half circles joined by straight sides), and is milled as cycle 251 mills its pocket: the manual
    leaves the roughing path to the control, and 251's rings (each an obround here) stay inside the slot.

    ``number`` = 254: CIRCULAR SLOT (TNC 640 manual, "CIRCULAR SLOT (Cycle 254)"): Q219 slot width, Q375 pitch
    circle diameter, Q216/Q217 its centre, Q376 starting angle, Q248 angular length, Q378 stepping angle and Q377
    number of slots, Q367 reference (0: the slot from Q216/Q217; the others, from the tool position, an
    error), Q366 0 or 1, the rest as 252. Our reading where the manual leaves the path to the control, kept
    inside the slot: the tool goes at FMAX over the slot's first end (the pitch circle at Q376) at its height,
    down to the set-up clearance, and plunges there; the rings are the slot's outline at growing distances
    from its centre line (Q370 x R apart, up to the width / 2 less Q368 and R), each entered along the radius
    at the first end: the outer arc, a half
    circle round the far end, the inner arc back, a half circle round the first end (reversed for up-cut);
    the wall is finished the same way at the width / 2 less R; the slots one after the other.

    ``number`` = 257: CIRCULAR STUD (TNC 640 manual, "CIRCULAR STUD (Cycle 257)"): Q223 finished-part
    diameter, Q222 workpiece blank diameter, Q376 starting angle (absent or -1: 0), the rest as 256. The
    stud is 256's rounded rectangle Q223 x Q223 with the corner radius Q223 / 2, i.e. a circle, from the
    blank Q222 (the cycle run is 256's: from the starting position 2 mm outside the blank, half circles on
    and off, revolutions stepping in to the finished diameter)."""
    offset = beside_tool_offset(number, q, where, column)
    if number == 253:
        q = {**q, 220: q[219] / 2.0, 224: q.get(374, 0.0)}
    slot = (0.0, 0.0, 0.0, 0.0, 0.0)
    if number == 254:
        if not q[248] > 0 or not q[375] > q[219] > 0:
            where.fail("cycle 254: the angular length Q248 must be > 0, the pitch circle Q375 wider than the slot "
                       "width Q219 > 0", column=column, text=where.text, expected="Q248 > 0, Q375 > Q219 > 0")
        slot = (q[216] * scale, q[217] * scale, q[375] / 2.0 * scale, q[248], q.get(378, 0.0))
        q = {215: 0.0, **q, 223: q[219], 224: q[376]}
    if number == 257:
        start = q.get(376, -1.0)
        q = {**q, 218: q[223], 219: q[223], 220: q[223] / 2.0, 424: q[222], 425: q[222],
             224: 0.0 if start == -1.0 else start}
    if number in (251, 253, 256, 257):
        if not q[218] > 0 or not q[219] > 0 or (number in (256, 257) and (q[424] < q[218] or q[425] < q[219])):
            where.fail(f"cycle {number}: the side lengths Q218 and Q219 must be > 0 (256: the blank's Q424, Q425 at "
                       "least as long)", column=column, text=where.text, expected="Q218 > 0, Q219 > 0, Q424 >= Q218, "
                       "Q425 >= Q219 [mm]")
        q = {215: 0.0, **q, 223: min(q[218], q[219])}
    plunge_types = (0.0, 1.0, 2.0) if number in (251, 253) else (0.0, 1.0) if number in (252, 254) else (0.0,)
    if q.get(366, 0.0) not in plunge_types:
        where.fail(f"cycle {number}: Q366={q[366]:g} is not a plunging strategy of this cycle", column=column,
                   text=where.text, expected="Q366=" + ", ".join(f"{v:g}" for v in plunge_types))
    operation = int(q[215])
    if operation not in (0, 1, 2) or not q[223] > 0 or not q.get(370, 1.0) > 0 or not q[206] > 0:
        where.fail(f"cycle {number}: Q215 must be 0, 1 or 2, the diameter Q223, the overlap Q370 and the plunging feed "
                   "Q206 > 0", column=column, text=where.text, expected="Q215 in 0..2, Q223 > 0, Q370 > 0, Q206 > 0")
    depth = q[201] * scale
    return _checked(DrillCycle(
        number=number, setup=abs(q[200]) * scale, depth=depth, plunge=abs(q[202]) * scale or abs(depth),
        feed=q[207] * feed_scale, surface=q[203] * scale, second_setup=q[204] * scale, bore_diameter=q[223] * scale,
        climb=q.get(351, 1.0) >= 0, approach_feed=q[206] * feed_scale, side_allowance=abs(q.get(368, 0.0)) * scale,
        floor_allowance=abs(q.get(369, 0.0)) * scale, stepover=q.get(370, 1.0), operation=operation,
        finish_infeed=abs(q.get(338, 0.0)) * scale, finish_feed=(q.get(385, 0.0) or q[207]) * feed_scale,
        sides=(q.get(218, 0.0) * scale, q.get(219, 0.0) * scale), corner=abs(q.get(220, 0.0)) * scale,
        angle=q.get(224, 0.0), blank=(q.get(424, 0.0) * scale, q.get(425, 0.0) * scale),
        plunge_type=int(q.get(366, 0.0)) if number in (251, 252, 253, 254) else 0, slot=slot,
        repeats=max(1, int(q.get(377, 1.0))), centre_offset=(offset[0] * scale, offset[1] * scale)), where, column)


#: Q367 of cycles 251 and 256: the corner of the pocket or stud where the tool stands, in half side lengths.
_CORNERS = {1: (1.0, 1.0), 2: (-1.0, 1.0), 3: (-1.0, -1.0), 4: (1.0, -1.0)}


def beside_tool_offset(number: int, q: dict[int, float], where: Where, column: int) -> tuple[float, float]:
    """The centre of a pocket, slot or stud from the tool's position at the call, by its position Q367 [program
    units] (TNC 640 cycle programming manual, cycles 251 "Q367 Position of pocket" and 256 "Q367 Position of
    stud": 0 the tool over the centre, 1 at the lower left corner, 2 the lower right, 3 the upper right, 4 the
    upper left; cycle 253 "Q367 Position of slot": 0 the centre, 1 the slot's left end, 2 the centre of its left
    circle, 3 the centre of its right circle, 4 its right end). The offset turns with the angle of rotation Q224
    (253: Q374), whose centre the manual puts at the tool's position. No copy of those pages is in the search
    index: our reading of their parameter texts. Cycle 257 has no position; 254's Q367 (a reference point for
    the pitch circle) stays an error."""
    where_q = q.get(367, 0.0)
    if number == 254 and where_q != 0.0:
        where.fail(f"cycle 254: Q367={where_q:g} (the slot placed from the tool position) is not supported",
                   column=column, text=where.text, expected="Q367=0 (the slot from the centre Q216, Q217)")
    if number not in (251, 253, 256) or where_q == 0.0:
        return (0.0, 0.0)
    if where_q not in (1.0, 2.0, 3.0, 4.0):
        where.fail(f"cycle {number}: Q367={where_q:g} is not a position", column=column, text=where.text,
                   expected="Q367=0 (centre), 1, 2, 3 or 4")
    if number == 253:
        half, radius = q[218] / 2.0, q[219] / 2.0
        u, v = {1.0: (half, 0.0), 2.0: (half - radius, 0.0), 3.0: (radius - half, 0.0), 4.0: (-half, 0.0)}[where_q]
        angle = q.get(374, 0.0)
    else:
        su, sv = _CORNERS[int(where_q)]
        u, v, angle = su * q[218] / 2.0, sv * q[219] / 2.0, q.get(224, 0.0)
    a = math.radians(angle)
    return (u * math.cos(a) - v * math.sin(a), u * math.sin(a) + v * math.cos(a))


def _checked(cycle: DrillCycle, where: Where, column: int) -> DrillCycle:
    if not cycle.feed > 0:
        where.fail(f"cycle {cycle.number}: the drilling feed must be > 0", column=column, text=where.text,
                   expected="a feed > 0 [mm/min]")
    if cycle.depth == 0:
        where.fail(f"cycle {cycle.number}: depth 0 (the TNC does not run the cycle)", column=column, text=where.text,
                   expected="a depth != 0 [mm]")
    if cycle.plunge <= 0:
        where.fail(f"cycle {cycle.number}: plunging depth must be > 0", column=column, text=where.text,
                   expected="a plunging depth > 0 [mm]")
    if cycle.dwell_top < 0 or cycle.dwell_bottom < 0:
        where.fail(f"cycle {cycle.number}: negative dwell", column=column, text=where.text, expected="dwell >= 0 [s]")
    smallest = min(cycle.plunge, max(cycle.min_plunge, 1e-3)) if cycle.decrement else cycle.plunge
    if abs(cycle.depth) / smallest > MAX_INFEEDS:  # Q202=0.0000001 would make moves for hours, filling the memory
        where.fail(f"cycle {cycle.number}: {abs(cycle.depth):g} mm in infeeds of {smallest:g} mm are more than "
                   f"{MAX_INFEEDS} infeeds", column=column, text=where.text,
                   expected="a larger plunging depth (Q202, Q205) or a smaller depth")
    return cycle



def scaled_cycle(cycle: DrillCycle, factor: float) -> DrillCycle:
    """The cycle with its tool-axis lengths (not the surface coordinate) multiplied by ``factor`` [-]."""
    def f(v: float | None) -> float | None:
        return None if v is None else v * factor

    return dataclasses.replace(cycle, setup=cycle.setup * factor, depth=cycle.depth * factor,
                               plunge=cycle.plunge * factor, second_setup=cycle.second_setup * factor,
                               decrement=cycle.decrement * factor, min_plunge=cycle.min_plunge * factor,
                               chip_break=cycle.chip_break * factor, chip_depth=cycle.chip_depth * factor,
                               advance=f(cycle.advance), advance_last=f(cycle.advance_last),
                               disengage=(cycle.disengage[0] * factor, cycle.disengage[1] * factor),
                               bore_diameter=cycle.bore_diameter * factor, helix_pitch=cycle.helix_pitch * factor,
                               side_allowance=cycle.side_allowance * factor,
                               floor_allowance=cycle.floor_allowance * factor,
                               finish_infeed=cycle.finish_infeed * factor, corner=cycle.corner * factor,
                               sides=(cycle.sides[0] * factor, cycle.sides[1] * factor),
                               blank=(cycle.blank[0] * factor, cycle.blank[1] * factor),
                               counterbore=cycle.counterbore * factor, edge_height=cycle.edge_height * factor,
                               sink_depth=cycle.sink_depth * factor, front_depth=cycle.front_depth * factor,
                               front_offset=cycle.front_offset * factor, start_depth=cycle.start_depth * factor,
                               dwell_depth=cycle.dwell_depth * factor, lead=cycle.lead * factor)


@dataclasses.dataclass(frozen=True, kw_only=True)
class PatternCycle:
    """Cycle 220 POLAR PATTERN or 221 CARTESIAN PATTERN, in mm.

    Attributes
    ----------
    number : int
        220 or 221.
    points : tuple of (float, float)
        The machining positions in the working plane's (reference, minor) axes [mm, program], in
        the order the TNC machines them.
    setup, surface, second_setup : float
        Q200, Q203, Q204 [mm]: they replace the machining cycle's own.
    high : bool
        Q301 = 1: between the positions the tool moves at the 2nd set-up clearance (0: at the set-up
        clearance).
    centre : tuple of (float, float) or None
        Cycle 220 with Q365 = 1: the pitch circle's centre (Q216, Q217) [mm, program], about which the tool
        moves from one position to the next; None: straight moves (Q365 = 0, cycle 221).
    step : float
        The signed angle from one position to the next about ``centre`` [deg] (0 without one).
    """

    number: int
    points: tuple[tuple[float, float], ...]
    setup: float
    surface: float
    second_setup: float
    high: bool
    centre: tuple[float, float] | None = None
    step: float = 0.0


def pattern_cycle(number: int, q: dict[int, float], *, scale: float, where: Where, column: int) -> PatternCycle:
    """Cycle 220 or 221 from its Q parameters (TNC 320 user's manual for cycle programming 9/2016,
    "Fixed cycles: pattern definitions", p. 176-181):

    * 220: Q241 positions on the circle of diameter Q244 about (Q216, Q217), from the starting angle
      Q245 in steps of Q247; Q247 = 0: the step is (Q246 - Q245) / (Q241 - 1), on a full circle
      (Q246 - Q245 = +-360) (Q246 - Q245) / Q241;
    * 221: Q242 columns spaced Q237 along the reference axis and Q243 lines spaced Q238 from the
      starting point (Q225, Q226), turned by Q224 about it; the TNC machines the first line in
      the positive direction of the reference axis, the next one back (meander).

    ``Q365`` of cycle 220 is the "Type of traverse? Line=0/arc=1" between the positions: 0 a straight
    line, 1 an arc on the pitch circle (TNC 640 user's manual for cycle programming 34059x-01, cycle 220
    "Cycle run" 3: "moves the tool on a straight line or circular arc to the starting point of the next
    machining operation"); :attr:`PatternCycle.centre` and ``step`` carry the arc. More positions than
    :data:`MAX_PATTERN_POSITIONS` (Q241, or Q242 x Q243) are an error, as is a definition lacking a
    parameter.
    """
    required_q(number, q, where, column)
    if number == 220:
        n = int(q[241])
        if not 1 <= n <= MAX_PATTERN_POSITIONS:
            where.fail(f"cycle 220: Q241={q[241]:g} positions", column=column, text=where.text,
                       expected=f"Q241 from 1 to {MAX_PATTERN_POSITIONS} (the manual's input range)")
        span = q[246] - q[245]
        step = q[247] or (span / n if abs(abs(span) - 360.0) <= 1e-9 else (span / (n - 1) if n > 1 else 0.0))
        r = q[244] / 2.0
        pts = [(q[216] + r * math.cos(math.radians(q[245] + k * step)),
                q[217] + r * math.sin(math.radians(q[245] + k * step))) for k in range(n)]
    else:
        cols, rows = int(q[242]), int(q[243])
        if cols < 1 or rows < 1:
            where.fail("cycle 221: Q242 and Q243 must be >= 1", column=column, text=where.text,
                       expected="Q242 >= 1 and Q243 >= 1")
        if cols * rows > MAX_PATTERN_POSITIONS:
            where.fail(f"cycle 221: Q242 x Q243 = {cols} x {rows} positions", column=column, text=where.text,
                       expected=f"at most {MAX_PATTERN_POSITIONS} positions (cycle 220's Q241 input range)")
        a = math.radians(q.get(224, 0.0))
        pts = []
        for i, j in grid_order(cols, rows):
            u, v = i * q[237], j * q[238]
            pts.append((q[225] + u * math.cos(a) - v * math.sin(a), q[226] + u * math.sin(a) + v * math.cos(a)))
    arc = number == 220 and q.get(365, 0.0) != 0.0 and n > 1
    return PatternCycle(number=number, points=tuple((x * scale, y * scale) for x, y in pts), setup=abs(q[200]) * scale,
                        surface=q[203] * scale, second_setup=q[204] * scale, high=q.get(301, 0.0) != 0.0,
                        centre=(q[216] * scale, q[217] * scale) if arc else None, step=step if arc else 0.0)


_POS_RE = re.compile(r"\s*POS(\d+)\s*\(([^)]*)\)", re.I)
_FORM_RE = re.compile(r"\s*(ROW|CIRC|PITCHCIRC|PAT|FRAME)(\d+)\s*\(([^)]*)\)", re.I)
#: A form the reader reads whose parenthesis is left open (``ROW1 (X+0 Y+0 D+10 NUM2``).
_OPEN_FORM_RE = re.compile(r"\s*(POS|ROW|CIRC|PITCHCIRC|PAT|FRAME)(\d+)\s*\([^)]*$", re.I)
_FORM_KEY_RE = re.compile(r"\s*(NUMX|NUMY|NUM|START|STEP|END|ROTX|ROTY|ROT|DX|DY|D|X|Y|Z)(?![A-Z])", re.I)
#: The words of each generated pattern form, and those it must have.
_FORM_WORDS = {"ROW": ({"X", "Y", "D", "NUM", "ROT", "Z"}, {"X", "Y", "D", "NUM"}),
               "CIRC": ({"X", "Y", "D", "START", "NUM", "Z"}, {"X", "Y", "D", "NUM"}),
               "PITCHCIRC": ({"X", "Y", "D", "START", "STEP", "END", "NUM", "Z"}, {"X", "Y", "D", "NUM"}),
               "PAT": ({"X", "Y", "DX", "DY", "NUMX", "NUMY", "ROT", "ROTX", "ROTY", "Z"},
                       {"X", "Y", "DX", "DY", "NUMX", "NUMY"})}
_FORM_WORDS["FRAME"] = _FORM_WORDS["PAT"]


def _form_words(kind: str, text: str, start: int, where: Where, params: QParameters,
                column0: int) -> dict[str, float]:
    """The words of one ROW / CIRC / PITCHCIRC / PAT / FRAME form, ``text[start:]`` its inside, values evaluated."""
    allowed, needed = _FORM_WORDS[kind]
    words: dict[str, float] = {}
    pos = start
    while text[pos:].strip():
        m = _FORM_KEY_RE.match(text, pos)
        key = m.group(1).upper() if m else ""
        if m is None or key not in allowed or key in words:
            tok = text[pos:].split()[0]
            where.fail(f"word {tok!r} in PATTERN DEF {kind}", column=column0 + pos, text=tok,
                       expected=", ".join(sorted(allowed)) + " (each once)")
        words[key], pos = read_value(text, m.end(), where, params, what=key, column0=column0)
    missing = sorted(needed - words.keys()) + (["STEP or END"] if kind == "PITCHCIRC" and
                                                not {"STEP", "END"} & words.keys() else [])
    inside = text[start:].strip()
    if missing:
        where.fail(f"PATTERN DEF {kind} without {', '.join(missing)}", column=column0 + start, text=inside,
                   expected=f"{kind}n ({' '.join(sorted(needed))} ...)")
    for key in sorted({"NUM", "NUMX", "NUMY"} & words.keys()):
        if not 1 <= words[key] <= MAX_PATTERN_POSITIONS or words[key] != int(words[key]):
            where.fail(f"PATTERN DEF {kind} with {key}{words[key]:g}", column=column0 + start, text=inside,
                       expected=f"{key} a whole number from 1 to {MAX_PATTERN_POSITIONS}")
    if {"NUMX", "NUMY"} <= words.keys() and words["NUMX"] * words["NUMY"] > MAX_PATTERN_POSITIONS:
        where.fail(f"PATTERN DEF {kind} with NUMX{words['NUMX']:g} x NUMY{words['NUMY']:g} points",
                   column=column0 + start, text=inside, expected=f"at most {MAX_PATTERN_POSITIONS} points")
    if {"STEP", "END"} <= words.keys():
        where.fail("PATTERN DEF PITCHCIRC with both STEP and END", column=column0 + start, text=inside,
                   expected="STEP (the stepping angle) or END (the end angle)")
    return words


def grid_order(columns: int, rows: int, *, frame: bool = False) -> list[tuple[int, int]]:
    """The (column, row) indices of a ``columns`` x ``rows`` grid in the order a TNC machines them: row by row
    in meander, the first row in the positive direction of the reference axis, the next back, and so on, as
    the TNC 320 user's manual for cycle programming describes cycle 221 CARTESIAN PATTERN ("CARTESIAN PATTERN
    (Cycle 221)", p. 180-181: to the last point of the first line, then to the last point of the second line,
    then back along it in the negative reference-axis direction). ``frame``: only the points on the grid's
    outline (the first and last row and column), in the same order."""
    out = []
    for j in range(rows):
        for i in (range(columns) if j % 2 == 0 else reversed(range(columns))):
            if not frame or i in (0, columns - 1) or j in (0, rows - 1):
                out.append((i, j))
    return out


def _grid_points(kind: str, w: dict[str, float]) -> list[dict[str, float]]:
    """The positions of ``PAT`` (a grid) or ``FRAME`` (its outline) in program units (see
    :func:`pattern_positions`)."""
    cols, rows, z = int(w["NUMX"]), int(w["NUMY"]), w.get("Z", 0.0)
    rot, rx, ry = (math.radians(w.get(k, 0.0)) for k in ("ROT", "ROTX", "ROTY"))
    out = []
    for i, j in grid_order(cols, rows, frame=kind == "FRAME"):
        u = i * w["DX"] * math.cos(rx) - j * w["DY"] * math.sin(ry)
        v = i * w["DX"] * math.sin(rx) + j * w["DY"] * math.cos(ry)
        out.append({"X": w["X"] + u * math.cos(rot) - v * math.sin(rot),
                    "Y": w["Y"] + u * math.sin(rot) + v * math.cos(rot), "Z": z})
    return out


def _form_points(kind: str, w: dict[str, float]) -> list[dict[str, float]]:
    """The positions of a generated pattern form, in program units (see :func:`pattern_positions`)."""
    if kind in ("PAT", "FRAME"):
        return _grid_points(kind, w)
    count, z = int(w["NUM"]), w.get("Z", 0.0)
    if kind == "ROW":
        a = math.radians(w.get("ROT", 0.0))
        return [{"X": w["X"] + k * w["D"] * math.cos(a), "Y": w["Y"] + k * w["D"] * math.sin(a), "Z": z}
                for k in range(count)]
    first = w.get("START", 0.0)
    if kind == "CIRC":
        step = 360.0 / count
    elif "STEP" in w:
        step = w["STEP"]
    else:
        step = (w["END"] - first) / (count - 1) if count > 1 else 0.0
    r = w["D"] / 2.0
    return [{"X": w["X"] + r * math.cos(math.radians(first + k * step)),
             "Y": w["Y"] + r * math.sin(math.radians(first + k * step)), "Z": z} for k in range(count)]


def pattern_positions(rest: str, where: Where, params: QParameters, *, column0: int) -> list[dict[str, float]]:
    """The machining positions of ``PATTERN DEF POS1 (X+25 Y+33.5 Z+0) POS2 (...)`` (TNC 640
    user's manual, "Pattern definition PATTERN DEF": up to 9 positions; ``Z`` is the workpiece
    surface there, added to the cycle's Q203; ``IX``/``IY`` are from the previous position), and of the
    generated forms of the same page, as the control's dialog names their data (TNC 640 cycle programming
    manual, "PATTERN DEF": "Defining a single row", "Defining a full circle", "Defining a pitch circle"; no copy
    of those pages is in the search index, so the rules below are our reading of their dialog):
    ``ROW1 (X+25 Y+33.5 D+8 NUM5 ROT+0 Z+0)`` NUM positions from the starting point X/Y, D apart along the
    direction ROT (degrees from the working plane's reference axis, about the starting point);
    ``CIRC1 (X+25 Y+33 D80 START+45 NUM8 Z+0)`` NUM positions on the circle of diameter D about X/Y, the first at
    the polar angle START, then 360/NUM apart counter-clockwise; ``PITCHCIRC1 (X+25 Y+33 D80 START+45 STEP+30
    NUM8 Z+0)`` the same with the stepping angle STEP (its sign the direction), or with the end angle ``END``
    instead (the steps (END - START) / (NUM - 1)). ``Z`` is the surface there, as in POS.
    ``PAT1 (X+25 Y+33.5 DX+8 DY+10 NUMX5 NUMY4 ROT+0 ROTX+0 ROTY+0 Z+0)`` ("Defining a point pattern") a grid of
    NUMX points DX apart along the reference axis times NUMY rows DY apart along the minor axis from the starting
    point X/Y; ``FRAME1 (...)`` with the same words ("Defining a frame") the points of that grid on its outline
    only. ROTX turns the reference axis of the grid and ROTY its minor axis, each alone (the dialog's "rotational
    position of the reference / minor axis", which the manual says distorts the pattern), ROT the whole pattern,
    all about the starting point [degrees]. The order of a grid's points is not stated on the pages we could
    read: our reading takes the meander of cycle 221 CARTESIAN PATTERN, the same grid as a cycle
    (:func:`grid_order`). The positions are machined in the order the forms are written, each from its first
    position on.

    Returns one dict per position with the words as written (``"X"``, ``"IY"``, ``"Z"`` ...) in
    program units. A NUM (NUMX, NUMY) or a list of more than :data:`MAX_PATTERN_POSITIONS` positions is an error.
    """
    out: list[dict[str, float]] = []
    pos, listed = 0, 0
    while rest[pos:].strip():
        m = _POS_RE.match(rest, pos)
        if m is None:
            f = _FORM_RE.match(rest, pos)
            if f is None:
                tok = rest[pos:].split()[0]
                open_form = _OPEN_FORM_RE.match(rest, pos)
                what = (f"PATTERN DEF {open_form.group(1).upper()}{open_form.group(2)} without its closing ')'"
                        if open_form else f"pattern {tok!r} is not supported")
                where.fail(what, column=column0 + pos + len(rest[pos:]) - len(rest[pos:].lstrip()), text=tok,
                           expected="PATTERN DEF POS1 (X.. Y.. Z..) POS2 (...), ROW1 (...), CIRC1 (...), "
                                    "PITCHCIRC1 (...), PAT1 (...) or FRAME1 (...)")
            kind = f.group(1).upper()
            out += _form_points(kind, _form_words(kind, rest[: f.end(3)], f.start(3), where, params, column0))
            if len(out) > MAX_PATTERN_POSITIONS:
                where.fail(f"PATTERN DEF with {len(out)} positions", column=column0 + f.start(),
                           text=f.group(0).strip(), expected=f"at most {MAX_PATTERN_POSITIONS} positions in all")
            pos = f.end()
            continue
        words = read_words(rest[: m.end(2)], m.start(2), where, params, column0=column0)
        point: dict[str, float] = {}
        for w in words:
            if w.key not in ("X", "Y", "Z", "IX", "IY", "IZ") or w.key[-1] in {k[-1] for k in point}:
                where.fail(f"word {w.text!r} in a pattern position", column=w.column, text=w.text,
                           expected="X, Y, Z (each once; IX, IY incremental)")
            point[w.key] = float(w.value)
        out.append(point)
        listed += 1
        pos = m.end()
    if not out or listed > 9:
        where.fail(f"PATTERN DEF with {listed} positions", column=column0, text=rest.strip(),
                   expected="1 to 9 positions POS1 .. POS9")
    return out


@dataclasses.dataclass(frozen=True)
class AxisMove:
    """One move of a drilling cycle along the tool axis (the hole's in-plane position is fixed).

    Attributes
    ----------
    kind : {"rapid", "line", "dwell", "plane"}
        ``"plane"``: a rapid in the working plane to ``offset`` from the hole's centre.
    level : float
        Tool-axis coordinate at the end of the move [mm, machine].
    feed : float
        [mm/s]; ``inf`` for rapids, 0 for dwells.
    dwell : float
        [s] for a dwell.
    offset : tuple of float
        For ``"plane"``: where the tool goes, from the hole's centre in the working plane's
        (reference, minor) axes [mm, program directions].
    """

    kind: str
    level: float
    feed: float = math.inf
    dwell: float = 0.0
    offset: tuple[float, float] = (0.0, 0.0)


def to_second_clearance(cycle: DrillCycle, *, surface: float) -> list[AxisMove]:
    """The last move of a cycle at a hole, from the set-up clearance Q200 above ``surface`` [mm, machine]: at FMAX
    to the 2nd set-up clearance Q204 when it is higher, else none (the cycle runs of the TNC 320 user's manual
    for cycle programming end so, e.g. "BORE MILLING (Cycle 208)", "CIRCULAR POCKET (Cycle 252)": out at FMAX
    to the set-up clearance and the 2nd one). The sign of the depth is the working direction."""
    if not cycle.second_setup > cycle.setup:
        return []
    d = -1.0 if cycle.depth < 0 else 1.0
    return [AxisMove("rapid", surface - d * cycle.second_setup)]


def _infeeds(cycle: DrillCycle) -> int:
    """How many infeeds drill ``cycle``'s hole (plunges shrinking by the decrement)."""
    done, plunge, n = cycle.start_depth, cycle.plunge, 0
    while done < abs(cycle.depth) - 1e-12:
        done += min(plunge, abs(cycle.depth) - done)
        n += 1
        if cycle.decrement:
            plunge = max(plunge - cycle.decrement, cycle.min_plunge, 1e-3)
    return n


def _reentry_advance(cycle: DrillCycle, first: float, k: int) -> float:
    """The advanced stop distance of the ``k``-th re-entry [mm]: 205 goes from Q258 at the first to Q259
    at the last at the same rate per re-entry (TNC 426/430 user's manual, "UNIVERSAL PECKING (Cycle
    205)": "If you enter Q258 not equal to Q259, the TNC will change the advance stop distances
    between the first and last plunging depths at the same rate"; per re-entry: our reading)."""
    n = _infeeds(cycle) - 1  # re-entries
    if cycle.advance_last is None or n <= 1:
        return first
    return first + (cycle.advance_last - first) * (k - 1) / (n - 1)


def hole_moves(cycle: DrillCycle, *, start: float, surface: float) -> list[AxisMove]:
    """The tool-axis moves of one hole, the TNC way (TNC 426/430 user's manual, "Cycles for
    drilling"; values from the cycle's definition):

    * cycle 1: drill at F from the starting point ``start`` to the first plunging depth (below
      the surface, which lies the set-up clearance ahead); retract at FMAX to the starting point,
      advance at FMAX to the advanced stop distance t above the last depth (t = 0.6 mm for a
      total depth up to 30 mm, else depth/50, at most 7 mm), drill the next infeed; at the bottom
      dwell, then FMAX back to the starting point;
    * cycles 200/203/205: FMAX to the set-up clearance above the surface, drill to the plunging
      depth, FMAX back to the set-up clearance, dwell Q210 there, FMAX to the set-up clearance
      (205: Q258 at the first re-entry, Q259 at the last, :func:`_reentry_advance`) above the last
      depth, drill on; infeeds shrink by Q212 down to Q205 (203/205);
      205 breaks the chip within an infeed after every Q257, retracting Q256 at FMAX (TNC 426/430
      user's manual, "UNIVERSAL PECKING (Cycle 205)": "Infeed depth for chip breaking Q257",
      "Retraction rate for chip breaking Q256");
      203 breaks the chip Q213 times by retracting Q256 before a full retraction; at the bottom
      dwell Q211, retract (203: at Q208) to the set-up clearance and, when it is higher, to the
      2nd set-up clearance;
    * the other 200-series cycles (:func:`drill_cycle`): the same moves with one infeed (209: Q257
      infeeds, each followed by a back-off), a tap re-entering at its feed, cycle 202's moves off
      the wall and back as ``"plane"`` moves.

    ``start`` and ``surface`` are tool-axis coordinates [mm, machine]; the sign of the depth is the
    working direction.
    """
    if cycle.number == 241:
        return single_lip_moves(cycle, surface=surface)
    d = -1.0 if cycle.depth < 0 else 1.0
    total = abs(cycle.depth)
    out: list[AxisMove] = []
    if cycle.number == 1:
        top = start
        advance = 0.6 if total <= 30.0 else min(total / 50.0, 7.0)
    else:
        top = surface - d * cycle.setup
        advance = cycle.setup if cycle.advance is None else cycle.advance
        out.append(AxisMove("rapid", top))
    retract_kind, retract_feed = ("line", cycle.retract_feed) if cycle.retract_feed else ("rapid", math.inf)
    done = cycle.start_depth  # 205 Q379: from the set-up clearance above the deepened starting point
    if done:
        entry = surface + d * (done - cycle.setup)
        out.append(AxisMove("line", entry, cycle.approach_feed) if math.isfinite(cycle.approach_feed)
                   else AxisMove("rapid", entry))
    plunge = cycle.plunge
    breaks = 0
    at_top = True
    reentries = 0
    while done < total - 1e-12:
        if done > cycle.start_depth and at_top:
            if cycle.dwell_top > 0:
                out.append(AxisMove("dwell", top, 0.0, cycle.dwell_top))
            reentries += 1
            reentry = surface + d * (done - _reentry_advance(cycle, advance, reentries))
            if d * (reentry - top) > 0 and cycle.number not in (2, 17, 206, 207, 209):  # a tap follows its thread
                out.append(AxisMove("rapid", reentry))
        step = min(plunge, total - done)
        cut = cycle.chip_depth
        while 0.0 < cut < step - 1e-12:  # 205 Q257: chip breaks within the infeed, Q256 back at rapid
            out.append(AxisMove("line", surface + d * (done + cut), cycle.feed))
            out.append(AxisMove("rapid", surface + d * (done + cut - cycle.chip_break)))
            cut += cycle.chip_depth
        done += step
        out.append(AxisMove("line", surface + d * done, cycle.feed))
        if cycle.decrement:
            plunge = max(plunge - cycle.decrement, cycle.min_plunge, 1e-3)
        if done >= total - 1e-12:
            break
        if breaks < cycle.chip_breaks:
            breaks += 1
            out.append(AxisMove(retract_kind, surface + d * (done - cycle.chip_break), retract_feed))
            at_top = False
            continue
        breaks = 0
        out.append(AxisMove(retract_kind, top, retract_feed))
        at_top = True
    if cycle.dwell_bottom > 0:
        out.append(AxisMove("dwell", surface + d * total, 0.0, cycle.dwell_bottom))
    if cycle.disengage != (0.0, 0.0):
        out.append(AxisMove("plane", surface + d * total, offset=cycle.disengage))
    out.append(AxisMove(retract_kind, top, retract_feed))
    if cycle.disengage != (0.0, 0.0):
        out.append(AxisMove("plane", top))
    return out + (to_second_clearance(cycle, surface=surface) if cycle.number != 1 else [])
