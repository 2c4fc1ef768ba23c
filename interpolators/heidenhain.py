"""Reader of Heidenhain conversational (Klartext) programs, as TNC programs are really written.

The reader runs the program as a TNC does (Q parameters, jumps, subprograms, repeats and cycles
are executed, not merely parsed) and records the motion as :class:`~interpolators.program.Block`
s in machine coordinates. One module per concern:

* :mod:`interpolators.heidenhain_words`: blocks, comments, ``~`` continuations, words and values;
* :mod:`interpolators.heidenhain_params`: Q parameters, formulas, ``FN 0`` .. ``FN 13``, ``FN 18``;
* :mod:`interpolators.heidenhain_formulas`: formulas compiled once into closures (loops run them again);
* :mod:`interpolators.heidenhain_labels`: ``LBL``, ``CALL LBL [REP]``, ``FN 9`` .. ``FN 12`` jumps;
* :mod:`interpolators.heidenhain_paths`: polar ``LP``/``CP`` (helix ``CP IPA``), ``CT``, ``RND``, ``CHF``;
* :mod:`interpolators.heidenhain_cycles`: ``CYCL DEF`` 1, 2, 4, 5, 7, 9, 12, 17, 32, 200-209, 240, 241, 251-253,
  254, 256, 257, 262-265, 267 and the pattern cycles 220, 221;
* :mod:`interpolators.heidenhain_transforms`: cycles 8, 10, 11, 26, ``TRANS``, and the ``PLANE`` blocks
  (with :mod:`interpolators.tilted`: the tilted working plane on a tilting table; ``FUNCTION TCPM``: an error);
* :mod:`interpolators.heidenhain_tcpm`: ``M128`` on positioned rotary axes of a tilting table (3+2);
* :mod:`interpolators.heidenhain_programs`: ``CALL PGM``, ``SEL PGM``, ``CALL SELECTED PGM``;
* :mod:`interpolators.heidenhain_probing`: touch probe cycles ``TCH PROBE 400, 408-413, 417, 419-424, 427, 431`` on
  the nominal workpiece;
* :mod:`interpolators.heidenhain_fk`: FK free contour programming, resolved into ``L`` / ``CC`` + ``C`` blocks.

Blocks read here (HEIDENHAIN TNC 640 / iTNC 530 conversational user's manuals)::

    0 BEGIN PGM NAME MM             name and unit (MM or INCH); END PGM ends the run
    L X+50,022                      a decimal comma (programs saved by TNCs set to it) is a point
    * - Drill1                      structure block (skipped); ;comment anywhere
    BLK FORM 0.1 Z X.. Y.. Z..      workpiece blank (skipped)
    TOOL DEF 5 L+10 R+3             tool data in the program (replace the tool table's entry)
    TOOL CALL 5 Z S3000 DL+0.1 DR-0.2  (TOOL CALL Q11 Z: the tool number Q11 holds)
                                    tool axis (plane), tool length along it (table or TOOL DEF,
                                    plus DL) and radius for RL/RR (plus DR), from the next move on
    L X+10 IY-5 R0 F200 M3          line; I = incremental; F MAX / FMAX: rapid (this block only);
                                    F [mm/min] (INCH: [0.1 in/min]) modal; FQ5 feed from Q5;
                                    F AUTO: the F of the last TOOL CALL
    5 /L X+10, /5 L X+10            skippable block: runs (block skip off), noted
    L +0.009                        a number without axis letter repeats the single axis of the
                                    previous L block (the thesis' Tables 4.3/4.4 are written so)
    CC X+25 Y+25                    circle centre / pole (IX/IY: from the current position); CC X.. Z..
                                    (the tool axis and another): C and CP about it run in that plane
    LN X.. Y.. Z.. NX.. NY.. NZ..   a line with 3-D compensation: the point moved along N by DR
    L A+90 C+45 FMAX                rotary / secondary axes of the machine (context.extra_axes)
    C X+45 Y+25 DR+                 arc about CC (end = start: full circle; tool-axis coordinate: helix)
    CR X+5 Y+5 R+20 DR-             arc by radius (R- for more than 180 degrees)
    CT X+10 Y+0, CTP PR+30 PA+30    arc tangent to the preceding element (CTP: end point polar about CC)
    LP PR+20 PA+45, CP IPA+720 IZ-5 DR+
                                    polar line / arc about CC (helix with a tool-axis word); about a
                                    CC naming the tool axis (CC Z.. X..) in that plane
    RND R5, CHF 2                   rounding / chamfer of the corner between two lines
    FPOL X+20 Y+30, FL IX+10 Y+20 RR F100, FLT AN+45, FCT DR- R15 CCA+90 RX 13, FC CCX+20 CCY+15 DR+
    R15, FSELECT 2                  FK free contour programming in the working plane (heidenhain_fk):
                                    each element resolved from its data, its start and tangent, or
                                    the data of the FK elements after it; several solutions need FSELECT
    APPR LT X.. Y.. LEN10 RR F300, DEP LT LEN10 R0
                                    straight approach / departure tangential to the contour; LN
                                    perpendicular, CT on an arc (CCA, R), LCT line and arc (R);
                                    APPR PLT/PLN/PCT/PLCT, DEP PLCT: PA / PN by PR, PA
    STOP, M0, M1                    program stop: no motion (noted)
    L X.. M136 F0.05, M137          M136: F in mm per spindle revolution (x TOOL CALL S) until M137
    L C+180 FMAX M94, M94 C         M94: the rotary display reduced below 360 deg first (_path_m)
    M112 T0.01 A10 .. M113          contour tolerance as cycle 32 T (TNC 426/430); M118 X.. Y.., M124 T..:
                                    noted; M120 LA3: look-ahead of RL/RR (the path as without it)
    SPL X.. Y.. Z.. K3X.. K2X.. K1X.. ..
                                    spline: the cubic of each axis, t from 1 to 0 (heidenhain_splines)
    DECLARE STRING QS1 = "A", QS2 = QS1 || TOCHAR(DAT+Q1 DECIMALS2), TOOL CALL QS2, CALL PGM QS3
                                    string parameters (heidenhain_strings)
    FUNCTION FEED DWELL D-TIME0.5 F-TIME5 .. RESET
                                    a dwell after every F-TIME of feed motion (heidenhain_feed_dwell)
    FN 20: WAIT FOR ..              PLC synchronisation: met at once, noted; FN 19/29 PLC, FN 37 EXPORT,
                                    FN 38 SEND, FUNCTION LIFTOFF/S-PULSE/COUNT: no motion, noted
    L Z-5 F500 M103 F20             M103: the feed down the tool axis at most F percent (until M103 alone)
    CYCL CALL PAT F500 / F MAX      the moves between the pattern's points at F (F MAX: rapid)
    L Z-10 FMAX M91                 M91: coordinates of this block are machine coordinates
    L X+0 M92                       M92: relative to the machine-defined position context.home
    L M140 MB MAX                   retract along the tool axis to context.home's coordinate
                                    (the machine's limit stands in for the software limit switch)
    L M128 ... M129                 TCPM on rotary axes positioned before it (3+2, tilting table):
                                    lines of the tool tip on the turned part (heidenhain_tcpm); the F
                                    right after M128 is its compensation feed (noted)
    M2, M30                         end of the main program (subprograms follow)
    FN 0: Q1 = +5, Q2 = SQRT(Q1)    Q parameters (FN 0-8, 13, formulas)
    FN 9: IF +Q1 EQU +0 GOTO LBL 2  conditional jumps (FN 9-12)
    FN 15/16 PRINT, FN 18 SYSREAD ID240/ID270 NR1 IDXn, ID20 NR1, ID50 NR1..NR5 IDXt
                                    prints are noted; SYSREAD of the nominal position (ID240:
                                    machine coordinates; ID270: active coordinates) reads the
                                    simulated position (after a STOP, M0 or M1 with no move
                                    since: where the program stopped, noted; an operator's jog
                                    is not modelled); ID20 NR1: the active tool's number; ID50
                                    NR1/NR2 IDXt: L / R of tool t (TOOL DEF, else the tool table);
                                    NR3..NR5 (R2, DL, DR): 0, noted
    LBL 1 ... CALL LBL 1 REP 3      labels, subprograms, section repeats (REPQ5: the count in Q5)
    CYCL DEF 7/9/32/1/2/4/5/17/12/200-209/240/241/251-254/256/257/262-265/267/392
                                    cycles; machining cycles run by M99, CYCL CALL, CYCL CALL PAT or
                                    CYCL CALL POS
    CYCL DEF 220/221                polar / Cartesian pattern: the last machining cycle at each position
    PATTERN DEF POS1 (X.. Y.. Z..)  the positions of CYCL CALL PAT
    CYCL DEF 8/10/11/26, TRANS ..   mirror image, rotation, scaling about the datum (arcs and RL/RR
                                    follow a mirror); CYCL DEF 19 / PLANE with angles 0, PLANE RESET:
                                    no motion (without context.kinematics)
    PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN FMAX SEQ+, PLANE .. MOVE DIST50 F1000, PLANE .. STAY
                                    tilted working plane on a tilting table (context.kinematics): the
                                    rotary axes turn (TURN), with the linear axes keeping the tool tip on
                                    the part (MOVE), or not (STAY: the program positions them, L A+Q120
                                    C+Q122 FMAX); also PROJECTED, EULER, VECTOR, POINTS, RELATIV, AXIAL,
                                    RESET, and CYCL DEF 19.1 A.. B.. C.. (as STAY)
    TCH PROBE 417 DATUM IN TS AXIS Q263=.. (400, 408-413, 419-424, 427, 431)
                                    touch probe cycles run on the nominal workpiece (the touch points where
                                    the data put the surface): the probe's moves at the touch probe table's
                                    FMAX / F (context.touch_probe), the results Q150-Q175 (deviations 0,
                                    Q180 status), the datum they set
    CALL PGM name, SEL PGM name, CALL SELECTED PGM
                                    another program file (from the caller's directory), run on the
                                    same machine state in its own unit

Path mode: blocks end at rest (``Block.exact_stop``), as the thesis' identification programs
(Tables 4.3 and 4.4) are run, until ``CYCL DEF 32.1 T..`` sets a path tolerance; from then on
the path is continuous with that tolerance (``32.1`` without T: ``context.dialect.tolerance``).

Unit conversion: positions mm, feeds mm/s. Machine coordinates = the program coordinates
mirrored, rotated and scaled (cycles 8, 10, 11, 26) (in a tilted plane: turned by its ``Transform.tilt``
about the tool axis, from its zero on the tilted table) + the preset (``context.offset("G54")``; cycle 247
selects another work offset of the context) + the
datum shift of cycle 7 + the tool length along the tool axis. ``RL``/``RR`` offset the contour by
the tool radius (table or TOOL DEF, plus DR) from the RL/RR block (the entry move, ending
perpendicular to the first contour element as on the TNC) to the R0 block (the exit move), by
:func:`interpolators.compensation.compensate`. The arc of ``DEP CT .. R0`` is the run's last contour
element: the manuals give only the contour arc (TNC 640 user's manual, "Approaching and departing a
contour"), so the tool centre runs it as any compensated arc, about the same centre with the radius
grown or shrunk by the tool radius, and stops beside PN, offset square to the arc (our reading; the
next R0 block leaves from there). Anything not listed (other pattern forms, tilted planes without
kinematics, other cycles and FN functions) is an error naming the function, line and column. ``CYCLE DEF``, which the
SolidWorks TNC post writes for ``CYCL DEF``, is read as such.
"""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import numpy as np

from interpolators._words import INCH, Where, program_text
from interpolators.arcs import ArcWordError, arc_from_center, arc_from_radius
from interpolators.context import DEFAULT_CONTEXT, WORK_OFFSETS, MachineContext
from interpolators.heidenhain_compensation import finish_compensation, set_compensation
from interpolators.heidenhain_contours import (
    CONTOUR_CYCLES,
    ROUGHING_CYCLES,
    ContourTrain,
    RoughOut,
    contour_data,
    contour_labels,
    contour_train_cycle,
    floor_finishing_cycle,
    pilot_drilling_cycle,
    rough_out_cycle,
    side_finishing_cycle,
)
from interpolators.heidenhain_cycle_calls import cycle_call, pattern_call, position_call, positioning_feed
from interpolators.heidenhain_cycle_moves import pattern_cycle_run
from interpolators.heidenhain_cycles import (
    CYCLE_RE,
    LEGACY_CYCLES,
    MACHINING_CYCLES,
    PATTERN_CYCLES,
    REFUSED_CYCLES,
    DrillCycle,
    drill_cycle,
    legacy_value,
    old_pocket,
    pattern_cycle,
    pattern_positions,
    pecking_cycle,
    pocket_item,
    q_assignments,
    tapping_cycle,
)
from interpolators.heidenhain_fast import PlainBlocks
from interpolators.heidenhain_feed_dwell import FeedDwell, split_at_times
from interpolators.heidenhain_fk import FK_KEYWORDS, FreeContour, read_fk_words
from interpolators.heidenhain_labels import CALL_RE, LABEL_RE, MAX_EXECUTED, MAX_NESTING, Frame, LabelTable, label_key
from interpolators.heidenhain_params import Q_NAME_RE, QParameters, run_function
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
from interpolators.heidenhain_probing import PROBE_CYCLES, PROBE_RE, probe_run, refuse_probe
from interpolators.heidenhain_programs import CALL_PGM_RE, SEL_PGM_RE, find_program
from interpolators.heidenhain_splines import SPLINE_START_TOLERANCE, read_spline, spline_points
from interpolators.heidenhain_strings import QS_NAME_RE, StringParameters
from interpolators.heidenhain_surfaces import SURFACE_CYCLES, surface_cycle
from interpolators.heidenhain_targets import plane_coords, program_target
from interpolators.heidenhain_tcpm import TCPM_EXPECTED, check_tcpm_on, machine_point, part_point
from interpolators.heidenhain_transforms import (
    KINEMATICS_HINT,
    TRANSFORM_CYCLES,
    PlaneBlock,
    TiltedPlane,
    Transform,
    TransformError,
    plane_rotation,
    read_plane,
    tilt_block,
    trans_block,
    transform_item,
)
from interpolators.heidenhain_words import EMPTY_FIELD_NOTE, SourceBlock, Word, read_value, read_words, source_blocks
from interpolators.iso_axes import EXTRA_LETTERS, ROTARY_LETTERS, fill_extra
from interpolators.iso_splines import SPLINE_TOLERANCE
from interpolators.program import Block, Program, end_at_rest
from interpolators.tilted import Solution, TiltError, spatial, tilted_frame
from toolpaths.geometry import PLANE_AXES, Arc, Line
from vcnc.core.axes import AXIS_NAMES
from vcnc.core.text import BinaryDataError

__all__ = ["parse_heidenhain", "looks_like_heidenhain", "Machine"]

#: A block's keyword; "FN 0:Q2=5" and "Q1=Q2" (hyperMILL's TNC post) may go on without a blank.
_KEYWORD_RE = re.compile(
    r"(BEGIN\s+PGM|END\s+PGM|BLK\s+FORM|TOOL\s+CALL|TOOL\s+DEF|CYCLE?\s+DEF|CYCL\s+CALL|CALL\s+LBL|CALL\s+PGM"
    r"|CALL\s+SELECTED\s+PGM|SEL\s+PGM|TCH\s*PROBE|PLANE|FUNCTION|TRANS|SPL|DECLARE\s+STRING|QS\d+\s*="
    r"|LBL|FPOL|FSELECT|FCT|FLT|FC|FL|FN\s*\d+\s*:|Q[LR]?\d+\s*=|STOP|APPR|DEP|PATTERN\s+DEF|RND|CHF|CC|CR|CTP|CT|CP|C|LP|LN|L|M)(?:(?<=[:=])|(?![A-Z]))",
    re.I,
)
_BLANKS_RE = re.compile(r"\s+")
_PLANE_OF_TOOL_AXIS = {"Z": 2, "Y": 1, "X": 0}
#: M functions with a meaning here; any other M (spindle, coolant, clamping, ...) is noted and ignored.
_M_END = (2, 30)
_M_STOP = (0, 1)
_DETECT_RE = re.compile(
    r"\d+\s*(L|LP|CC|CR|CT|CP|C|TOOL\s+CALL|TOOL\s+DEF|BLK\s+FORM|END\s+PGM|CYCL\s+DEF|LBL|FN\s*\d+\s*:)(?:(?<=:)|(?![A-Z]))",
    re.I,
)
#: A conversational first block without a block number: a multi-word keyword, or a path keyword
#: followed by a blank and a conversational word (an axis with its sign or ``I``, ``PA``/``PR``,
#: ``R0/RL/RR``, ``DR``, ``F``/``FMAX``, ``M``) - never a valid ISO line.
_BARE_DETECT_RE = re.compile(
    r"(TOOL\s+CALL|TOOL\s+DEF|BLK\s+FORM|END\s+PGM|CYCL\s+DEF|CYCL\s+CALL|CALL\s+LBL|LBL\s*\d|FN\s*\d+\s*:"
    r"|(?:L|LP|CC|CR|CT|CP|C)\s+(?:I?[XYZ]\s*[+-]?\s*[\d.Q]|I?P[AR]|R[0LR]\b|DR\s*[+-]|F\s*MAX|FMAX|M\d))",
    re.I,
)


def looks_like_heidenhain(text: str) -> bool:
    """True if the text reads as Heidenhain conversational rather than ISO G-code.

    A ``BEGIN PGM`` line anywhere, or a first meaningful line made of a block number followed by
    a conversational keyword (``L``, ``C``, ``CC``, ``CR``, ``TOOL CALL``, ``CYCL DEF``, ...), or
    of such a keyword without a block number where no ISO block can read it (:data:`_BARE_DETECT_RE`:
    ``L X1.376 Y1.202 FMAX`` or ``CC X2.5 Y1.75``, as an engraving generator writes TNC text without
    header and numbers; in ISO ``L``, ``C`` take a number, and ``CC``, ``TOOL CALL`` are no words).
    """
    if re.search(r"^\s*\d*\s*BEGIN\s+PGM\b", text, re.I | re.M):
        return True
    for raw in text.split("\n"):
        s = raw.split(";", 1)[0].strip()
        if not s or s.startswith(("(", "%", "*")):
            continue
        return _DETECT_RE.match(s) is not None or _BARE_DETECT_RE.match(s) is not None
    return False


class Machine:
    """Run-time state of the control while the program runs."""

    def __init__(self, context: MachineContext, source: str | None) -> None:
        self.context = context
        self.source = source
        self.pos = np.array(context.home, dtype=float)  # machine coordinates [mm]
        self.plane = 2
        self.inch = False
        self.feed: float | None = None
        self.pole: np.ndarray | None = None
        self.pole_plane: int | None = None  # the plane of a CC naming the tool axis (None: the working plane)
        self.last_axes: list[int] = []
        self.tool_defs: dict[int, tuple[float, float]] = {}
        self.tool_length = 0.0
        self.tool_radius = 0.0
        self.tool_number = 0  # the active tool (FN 18 SYSREAD ID20 NR1); 0: none, or one called by name
        self.tool_delta = 0.0  # DR of the last TOOL CALL [mm]: LN's 3-D compensation
        self.shift = np.zeros(3)
        # the work offset of the context that is the active preset (cycle 247); None: a preset beyond them (zero)
        self.preset: str | None = "G54"
        # preset table rows a touch probe cycle wrote (interpolators.heidenhain_probing): work offset -> value [mm]
        self.presets: dict[str | None, np.ndarray] = {}
        self.transform = Transform()
        self.comp = "R0"
        self.comp_start: int | None = None  # index of the entry block of the running RL/RR run
        self.comp_side = "RL"
        self.comp_radius = 0.0
        self.ccw: bool | None = None
        self.exact_stop = True
        self.tolerance: float | None = None
        self.cycle: DrillCycle | ContourTrain | RoughOut | None = None
        self.contour: tuple[str, ...] = ()  # cycle 14: the labels of the contour
        self.contour_data: dict[int, float] | None = None  # cycle 20: its Q1 .. Q9
        self.cycle_items: dict[int, float | dict[str, float]] = {}
        self.pattern: list[dict[str, float]] | None = None
        self.params = QParameters()
        self.strings = StringParameters()  # QS (interpolators.heidenhain_strings)
        self.blocks: list[Block] = []
        self.used: set[int] = set()
        self.notes: dict[str, int] = {}
        self.pending: tuple[str, float, float | None, Where] | None = None  # RND/CHF waiting for its next line
        self.approach: dict | None = None  # APPR LT waiting for the first contour element
        self.last_rapid = False
        self.selected: tuple[str, int] | None = None  # SEL PGM: the name and its column
        self.spindle: float | None = None  # spindle speed of the last TOOL CALL S [rpm]
        self.auto_feed: float | None = None  # feed of the last TOOL CALL F [program units/min]: F AUTO
        self.modal_call = False  # M89: every positioning block calls the cycle
        self.cycle_program: tuple[str, int] | None = None  # cycle 12 PGM CALL: the program and its column
        self.runner = None  # the running program flow (a _Run), which runs cycle 12's program
        self.extra = np.zeros(len(EXTRA_LETTERS))  # rotary A B C [deg], secondary U V W [mm] (machine)
        self.extra_used = False  # a block moved (or set) one of them: every block carries their positions
        # the line of a program stop (STOP, M0, M1) with no move since: the operator may have jogged the
        # machine there; FN 18 SYSREAD of the position notes it (None: no such stop)
        self.stopped_at: int | None = None
        self.stop_in_block = False  # the running block stops the program (STOP, M0, M1)
        # the running block halts the axes (STOP, M0, a tool change; not M1: the optional stop switch is off)
        self.at_rest = False
        self.tilt: TiltedPlane | None = None  # the tilted working plane (PLANE, cycle 19) on a tilting table
        self.tcpm = False  # M128 on (interpolators.heidenhain_tcpm): lines are the tool tip on the turned part
        self.tcpm_move = False  # the block being emitted is one M128 reads (a line, an M140 retract)
        self.fk = FreeContour()  # FK free contour programming (interpolators.heidenhain_fk)
        self.plain: PlainBlocks | None = None  # the shortcut for plain L/CC/C/CR blocks (heidenhain_fast)
        self.per_revolution = False  # M136: F in mm per spindle revolution (until M137)
        self.plunge: float | None = None  # M103 F: the plunging feed as a fraction of F (None: off)
        self.feed_dwell: FeedDwell | None = None  # FUNCTION FEED DWELL (interpolators.heidenhain_feed_dwell)
        self.m112: tuple[bool, float | None] | None = None  # M112: the path mode before it (M113 restores it)
        self.look_ahead = False  # M120 LA>0 in a radius-compensated run
        # M94: machine angle minus shown angle of A B C [deg]; absolute angles are shown ones
        self.rotary_shift = np.zeros(len(EXTRA_LETTERS))

    # --- coordinates -------------------------------------------------------------------------
    @property
    def scale(self) -> float:
        return INCH if self.inch else 1.0

    @property
    def feed_scale(self) -> float:
        return (INCH / 10.0 if self.inch else 1.0) / 60.0

    def origin(self) -> np.ndarray:
        """Program zero in machine coordinates [mm]; in a tilted plane its zero on the tilted table plus
        cycle 7's shift in the plane."""
        if self.tilt is not None:
            o = self.tilt.datum + self.transform.turn(self.shift, self.plane)
        else:
            o = np.add(self.preset_value(), self.shift, dtype=float)  # a new array
        o[self.plane] += self.tool_length
        return o

    def preset_value(self) -> np.ndarray:
        """The active preset [mm, machine]: as a touch probe cycle set it, else the context's work offset."""
        if self.preset in self.presets:
            return self.presets[self.preset]
        return self.context.offset(self.preset) if self.preset is not None else np.zeros(3)

    def to_machine(self, point: np.ndarray) -> np.ndarray:
        """Machine coordinates [mm] of the program point ``point`` [mm] (cycles 8, 10, 11, 26 applied)."""
        return self.origin() + self.transform.apply(point, self.plane)

    def to_program(self, position: np.ndarray) -> np.ndarray:
        """Program coordinates [mm] of the machine position ``position`` [mm]."""
        return self.transform.invert(np.asarray(position, dtype=float) - self.origin(), self.plane)

    def axis_level(self, value: float) -> float:
        """Machine tool-axis coordinate [mm] of the program tool-axis coordinate ``value`` [mm]."""
        if self.transform.identity:
            return self.origin()[self.plane] + value
        point = np.zeros(3)
        point[self.plane] = value
        return float(self.to_machine(point)[self.plane])

    def lengths(self, where: Where) -> float:
        """Factor of lengths in the working plane (1 without transformation) [-]; an error at
        ``where`` when cycle 26 scales the plane's axes differently."""
        if self.transform.identity:
            return 1.0
        try:
            return self.transform.length(self.plane)
        except TransformError as exc:
            where.fail(exc.message, column=1, text=where.text, expected=exc.expected)

    def active_origin(self) -> np.ndarray:
        """The machine position minus its program coordinates (the program zero without rotation,
        mirror or scaling) [mm]: what ``FN 18 SYSREAD ID270`` subtracts."""
        if self.transform.identity:
            return self.origin()
        return self.pos - self.to_program(self.pos)

    def tool_data(self, number: int) -> tuple[float, float] | None:
        """Length and radius [mm] of tool ``number`` as ``TOOL CALL`` takes them (the program's ``TOOL DEF``,
        else the machine context's tool table); None when neither has the tool (TOOL CALL then takes 0, 0)."""
        if number in self.tool_defs:
            return self.tool_defs[number]
        tool = self.context.tool(number)
        return None if tool is None else (tool.length, tool.radius)

    def write_tool(self, number: int, column: int, value: float) -> None:
        """``FN 17 SYSWRITE ID50``: tool ``number``'s length (``column`` 1) or radius (2) [mm] is ``value`` from
        now on, kept as the program's ``TOOL DEF`` is (the other of the two as it was, 0 for a tool unknown)."""
        length, radius = self.tool_data(number) or (0.0, 0.0)
        self.tool_defs[number] = (value, radius) if column == 1 else (length, value)

    def check_tilt(self, target: np.ndarray, extra: np.ndarray, where: Where) -> None:
        """A block ending at ``target`` [mm] with the rotary axes at ``extra`` [deg]: an error when it moves
        the linear axes while the tilted plane does not hold (its rotary axes elsewhere, as after PLANE ..
        STAY before the program positions them)."""
        if self.tilt.holds(extra) or not np.any(np.abs(np.asarray(target, dtype=float) - self.pos) > 1e-9):
            return
        at = " ".join(f"{EXTRA_LETTERS[i]}{a:+.4f}" for i, a in self.tilt.angles.items())
        words = " ".join(f"{EXTRA_LETTERS[i]}+Q{120 + 'ABC'.index(EXTRA_LETTERS[i])}" for i in self.tilt.angles)
        where.fail(f"a move in the tilted plane of {self.tilt.what} while the rotary axes are not at its positions "
                   f"{at}", column=1, text=where.text,
                   expected=f"the rotary axes positioned first (STAY, cycle 19: L {words} R0 FMAX), or PLANE .. "
                            "TURN / MOVE")

    def note(self, text: str) -> None:
        """Record what the run ignored or read in a particular way (``Program.notes``, counted)."""
        self.notes[text] = self.notes.get(text, 0) + 1

    def emit(self, kind: str, target: np.ndarray, segment, feed: float, where: Where, number, *, dwell=0.0,
             extra: np.ndarray | None = None) -> None:
        """Append a block from the current position to ``target`` [mm] (``extra``: the end positions of
        the axes beyond X, Y, Z [deg, mm], moved in proportion)."""
        ends = {} if extra is None else {"extra_start": self.extra.copy(), "extra_target": np.array(extra, dtype=float)}
        if self.tcpm and not self.tcpm_move:
            where.fail("a move under M128 other than a straight line L (an arc, a cycle, an approach) is not "
                       "supported", column=1, text=where.text, expected=TCPM_EXPECTED)
        if self.tilt is not None:
            self.check_tilt(target, self.extra if extra is None else extra, where)
        if self.plunge is not None and kind in ("line", "arc") and segment is not None and segment.length > 0:
            down = float(self.pos[self.plane] - np.asarray(target, dtype=float)[self.plane])  # toward the part: -
            if down > 0:  # M103: the tool-axis speed at most plunge x F
                feed = min(feed, self.plunge * feed * segment.length / down)
        if (self.feed_dwell is not None and kind in ("line", "arc") and extra is None and segment is not None
                and math.isfinite(feed) and feed > 0 and segment.length > 0):
            self.emit_with_dwells(kind, segment, feed, where, number)
            return
        self.blocks.append(Block(kind=kind, target=np.array(target, dtype=float), feed=feed, segment=segment,
                                 line=where.line, number=number, text=where.text, start=self.pos.copy(),
                                 exact_stop=self.exact_stop, tolerance=self.tolerance, dwell=dwell, **ends))
        self.pos = np.array(target, dtype=float)
        if extra is not None:
            self.extra = np.array(extra, dtype=float)
        self.last_rapid = kind == "rapid"


    def emit_with_dwells(self, kind: str, segment, feed: float, where: Where, number) -> None:
        """A feed move under ``FUNCTION FEED DWELL`` (:mod:`interpolators.heidenhain_feed_dwell`): its pieces, a
        dwell where the cutting time reaches F-TIME."""
        active, self.feed_dwell = self.feed_dwell, None
        try:
            for piece, dwell in split_at_times(segment, feed, active):
                self.emit(kind, np.array(piece.end, dtype=float), piece, feed, where, number)
                if dwell:
                    self.emit("dwell", self.pos, None, 0.0, where, number, dwell=active.dwell)
        finally:
            self.feed_dwell = active


def parse_heidenhain(text: str, *, source: str | None = None, context: MachineContext = DEFAULT_CONTEXT,
                     max_executed: int = MAX_EXECUTED, shortcuts: bool = True) -> Program:
    """Run a Heidenhain conversational program and return its motion as a :class:`Program`.

    Parameters
    ----------
    text : str
        Program text.
    source : str, optional
        File name used in error messages and recorded in ``Program.source``.
    context : MachineContext
        Tool table, preset (the ``G54`` work offset), home position and path tolerance of the
        machine; the default changes nothing.
    max_executed : int
        Most blocks the run may execute (jumps and repeats count every pass) before the program
        is judged endless and rejected.
    shortcuts : bool
        Plain ``L``/``CC``/``C``/``CR`` blocks in a plain modal state run by :mod:`interpolators.heidenhain_fast`,
        which makes the general path's blocks; False: every block the general way
        (``tests/interpolators/test_heidenhain_fast.py``).

    Raises
    ------
    vcnc.GCodeError
        With file, line, column, the offending text and what was expected.
    """
    m = Machine(context, source)
    m.plain = PlainBlocks(m) if shortcuts else None
    name = _Run(m, source_blocks(text), source, max_executed).run()
    _check_contour_closed(m)
    if m.extra_used:
        m.blocks = fill_extra(m.blocks)
    notes = tuple(text if n == 1 else f"{text} x{n}" for text, n in m.notes.items())
    axes = tuple(a for i, a in enumerate(AXIS_NAMES) if i in m.used)  # x y z, then a b c u v w (3 + i)
    return Program(blocks=tuple(m.blocks), source=source, dialect="heidenhain", axes=axes, name=name, notes=notes)


def _check_contour_closed(m: Machine) -> None:
    """Nothing left waiting at the end: an FK element, RND/CHF, APPR LT, a radius-compensated run."""
    m.fk.unresolved()
    if m.pending is not None:
        kind, _, _, pw = m.pending
        pw.fail(f"{kind} at the end of the contour", column=1, text=pw.text, expected=f"a line after {kind}")
    if m.approach is not None:
        pw = m.approach["where"]
        form = m.approach["form"]
        pw.fail(f"APPR {form} without a following contour element", column=1, text=pw.text,
                expected=f"an L or arc block after APPR {form}")
    if m.comp != "R0":
        finish_compensation(m)


class _Run:
    """The program flow: block by block, with label jumps, section repeats and subprogram calls
    (:mod:`interpolators.heidenhain_labels`); each block's meaning is a function of this module."""

    def __init__(self, m: Machine, blocks: list[SourceBlock], source: str | None, max_executed: int, *,
                 callers: tuple[str, ...] = ()) -> None:
        self.m, self.blocks, self.source, self.max_executed = m, blocks, source, max_executed
        self.callers = callers  # files of the programs that called this one (CALL PGM), outermost first
        self.labels = LabelTable(blocks, source)
        self.stack: list[Frame] = []
        self.repeats: dict[int, int] = {}
        self.pc = 0
        self.executed = 0
        self.name: str | None = None
        self.keywords: dict[int, tuple[re.Match, str]] = {}  # block index -> its keyword, read once (loops)

    def run(self) -> str | None:
        """Run to END PGM, M2/M30 or the last block; returns the program name of BEGIN PGM."""
        caller, self.m.runner = self.m.runner, self  # cycle 12 runs programs through the running program
        try:
            self.steps()
        finally:
            self.m.runner = caller
        return self.name

    def fork(self) -> _Run:
        """A flow of its own over this program's blocks, allowed the blocks this one has left to run (the
        contour subprogram of an SL cycle, :mod:`interpolators.heidenhain_sl`)."""
        return _Run(self.m, self.blocks, self.source, self.max_executed - self.executed, callers=self.callers)

    def steps(self) -> None:
        """The blocks of this program, in the order the flow takes them."""
        while self.pc < len(self.blocks):
            blk = self.blocks[self.pc]
            self.executed += 1
            if self.executed > self.max_executed:
                blk.where(self.source).fail(f"the program does not end: more than {self.max_executed} blocks run "
                                            "(endless jump or repeat?)", column=blk.column, text=blk.code,
                                            expected="a program that reaches M30 or END PGM")
            self.pc += 1
            if blk.skip:
                self.m.note("/ skippable blocks run (block skip switched off)")
            if self.m.plain is not None and self.m.plain.run(blk):  # interpolators.heidenhain_fast
                continue
            where = blk.where(self.source)
            known = self.keywords.get(self.pc - 1)
            if known is None:
                k = _KEYWORD_RE.match(blk.code)
                if k is None:
                    _unknown_block(blk, where)
                known = self.keywords[self.pc - 1] = (k, _BLANKS_RE.sub(" ", k.group(1).upper()))
            k, kw = known
            count, self.m.stop_in_block, self.m.at_rest = len(self.m.blocks), False, False
            ended = self.block(kw, k, blk, where)
            if self.m.plain is not None:
                self.m.plain.reset()  # the state plain blocks read may have changed (a called program's too)
            if self.m.at_rest:
                end_at_rest(self.m.blocks)
            if self.m.stop_in_block:
                self.m.stopped_at = blk.line
            elif len(self.m.blocks) > count:
                self.m.stopped_at = None
            if ended:
                if self.callers and kw != "END PGM":
                    where.fail("M2/M30 in a called program", column=blk.column, text=blk.code,
                               expected="END PGM (TNC manual: the called program must not contain M2 or M30)")
                break

    def block(self, kw: str, k: re.Match, blk: SourceBlock, where: Where) -> bool:
        """Carry out one block; True when the program ends here."""
        m, col0 = self.m, blk.column
        if m.fk.waiting and kw not in FK_KEYWORDS and not (kw.startswith("FN") or kw.endswith("=")):
            m.fk.unresolved()  # an FK element waiting for FSELECT or the next FK element
        if kw == "BEGIN PGM":
            self.name = _begin_pgm(blk, k, m, where)
            return False
        if kw == "END PGM":
            return True
        if kw in ("LBL", "CALL LBL") or kw.startswith("FN"):
            self.flow(kw, blk, where)
            return False
        if kw.startswith(("QS", "DECLARE")):
            m.strings.assign(blk.code, m.params, where, column=col0)
            return False
        if kw.endswith("="):
            qn = Q_NAME_RE.match(blk.code).group(0)
            m.params.set(qn, m.params.evaluate(blk.code[k.end():], where, column=col0 + k.end()), where, column=col0)
            return False
        handler = _HANDLERS.get(kw)
        if handler is not None:
            return bool(handler(kw, blk, k.end(), m, where))
        if kw in ("CALL PGM", "CALL SELECTED PGM", "SEL PGM"):
            self.program_call(kw, blk, where)
            return False
        words = _read_words(blk.code, k.end(), where, m, column0=col0)
        return _motion(kw, words, m, where, blk)

    def flow(self, kw: str, blk: SourceBlock, where: Where) -> None:
        """LBL (the end of a called subprogram at LBL 0), CALL LBL, FN (jumps)."""
        m, col0 = self.m, blk.column
        if kw.startswith("FN"):
            jump = run_function(blk.code, m.params, where, column=col0, position=m.pos, origin=m.active_origin(),
                                scale=m.scale, note=m.note, tool=(m.tool_number, m.tool_data), stopped_at=m.stopped_at,
                                tool_write=m.write_tool)
            if jump is not None:
                self.pc = self.labels.find(jump, where, column=col0, text=blk.code) + 1
        elif kw == "LBL":
            lm = LABEL_RE.match(blk.code)
            if lm is None:
                where.fail("malformed label", column=col0, text=blk.code, expected="LBL n or LBL \"NAME\"")
            if label_key(lm) == "0" and self.stack:
                frame = self.stack[-1]
                frame.runs_left -= 1
                if frame.runs_left > 0:
                    self.pc = self.labels.where_of[frame.label] + 1
                else:
                    self.stack.pop()
                    self.pc = frame.return_to
        else:
            self.call_label(blk, where)

    def program_call(self, kw: str, blk: SourceBlock, where: Where) -> None:
        """``SEL PGM``, ``CALL PGM``, ``CALL SELECTED PGM`` (:mod:`interpolators.heidenhain_programs`):
        the called program runs on the same machine state (Q and QR parameters, tool, transformations,
        position; QL parameters of its own) in its own unit; its blocks report its own file and lines."""
        m, col0 = self.m, blk.column
        rx = SEL_PGM_RE if kw == "SEL PGM" else CALL_PGM_RE
        cm = rx.match(blk.code)
        if cm is None:
            where.fail(f"malformed {kw}", column=col0, text=blk.code, expected=f"{kw} name")
        given = cm.group(1)
        if given is not None and QS_NAME_RE.fullmatch(given):  # the program name a string parameter holds
            given = m.strings.get(given, where, column=col0 + cm.start(1))
        if kw == "SEL PGM":
            m.selected = (given, col0 + cm.start(1))
            return
        name, col = (given, col0 + cm.start(1)) if kw == "CALL PGM" else (m.selected or (None, col0))
        if name is None:
            where.fail("CALL SELECTED PGM without SEL PGM", column=col0, text=blk.code,
                       expected="SEL PGM name before CALL SELECTED PGM")
        self.run_program(name, col, where)

    def run_program(self, name: str, col: int, where: Where) -> None:
        """Run the program file ``name`` (written at column ``col`` of the calling block)."""
        m = self.m
        path, on_drive = find_program(name, self.source, where, column=col)
        if on_drive:
            m.note(f"CALL PGM {name}: the control drive path was looked up in the calling program's directory")
        here = str(path.resolve())
        if here in self.callers or (self.source is not None and here == str(Path(self.source).resolve())):
            where.fail(f"CALL PGM {name} calls a program that is running (an endless loop)", column=col,
                       text=name, expected="a called program that does not call its caller")
        if len(self.callers) >= MAX_NESTING:
            where.fail(f"program calls nested deeper than {MAX_NESTING} levels", column=col, text=name,
                       expected=f"at most {MAX_NESTING} nested CALL PGM")
        try:
            text = program_text(str(path))
        except (OSError, BinaryDataError) as exc:
            why = getattr(exc, "strerror", None) or exc
            where.fail(f"CALL PGM {name}: cannot read {str(path)!r}: {why}", column=col, text=name,
                       expected="a readable program file")
        callers = (*self.callers, str(Path(self.source).resolve()))
        inch, source = m.inch, m.source
        m.source = str(path)
        sub = _Run(m, source_blocks(text), str(path), self.max_executed - self.executed, callers=callers)
        local = m.params.enter_program()
        sub.run()
        m.params.leave_program(local)
        self.executed += sub.executed
        m.inch, m.source = inch, source

    def call_label(self, blk: SourceBlock, where: Where) -> None:
        """``CALL LBL n [REP k]``: a program-section repeat (backwards, with REP) or a subprogram call."""
        col0 = blk.column
        cm = CALL_RE.match(blk.code)
        if cm is None:
            where.fail("malformed label call", column=col0, text=blk.code,
                       expected="CALL LBL n [REP k] (k a number or Qn; the count display '/k' only after a number)")
        key = label_key(cm)
        target = self.labels.find(key, where, column=col0, text=blk.code)
        if cm.group(5) is not None and cm.group(6) is None:
            self.m.note(EMPTY_REP_NOTE)
        rep = _repeat_count(cm.group(6), self.m, where, col0 + cm.start(6)) if cm.group(6) else 0
        index = self.pc - 1
        if cm.group(6) is not None and target < index:  # program-section repeat
            left = self.repeats.get(index, rep)
            if left > 0:
                self.repeats[index] = left - 1
                self.pc = target + 1
            else:
                self.repeats.pop(index, None)
            return
        if len(self.stack) >= MAX_NESTING:
            where.fail(f"subprogram calls nested deeper than {MAX_NESTING} levels", column=col0,
                       text=blk.code, expected=f"at most {MAX_NESTING} nested CALL LBL")
        self.stack.append(Frame(return_to=self.pc, label=key, runs_left=rep + 1))
        self.pc = target + 1


#: ``CALL LBL 1 REP`` with the count left empty (a program of an older TNC, drunsinn/language-klartext's
#: 700.klartext, mirrors the section between LBL 1 and LBL 0 and calls it so): a field left empty
#: programs nothing (:data:`interpolators.heidenhain_words.EMPTY_FIELD_NOTE`), so the block is a
#: plain ``CALL LBL 1`` (a subprogram call, the section once more).
EMPTY_REP_NOTE = "CALL LBL n REP without a count read as CALL LBL n (the REP field left empty)"


def _repeat_count(text: str, m: Machine, where: Where, column: int) -> int:
    """The count of ``REP k``: a number, or a Q parameter holding a whole number >= 0 (``REPQ13``)."""
    if text[0].isdigit():
        return int(text[:6])
    return min(_whole_number(text, m, where, column, what="REP"), 999_999)


def _whole_number(name: str, m: Machine, where: Where, column: int, *, what: str) -> int:
    """The value of the Q parameter ``name`` as a whole number >= 0 (a count, a tool number); an error
    naming ``what`` otherwise (how the TNC rounds a fraction there the manuals do not say)."""
    value = m.params.get(name)
    if not (value >= 0 and abs(value - round(value)) < 1e-9):
        where.fail(f"{what} {name.upper()} = {value:g} is not a whole number >= 0", column=column, text=name,
                   expected=f"a whole number >= 0 for the {what}")
    return int(round(min(value, 1e9)))


def _unknown_block(blk: SourceBlock, where: Where) -> None:
    tok = blk.code.split()[0]
    for pattern, what, expected in _FOREIGN_LINES:
        if pattern.match(blk.code):
            where.fail(f"{what.format(tok=repr(tok))}: not a TNC block", column=blk.column, text=tok,
                       expected=expected)
    if _ERROR_BLOCK.match(blk.code):
        where.fail("a block the control marked 'ERROR =' when it read the program in (it could not read the "
                   "block); the control does not run a program holding one", column=blk.column, text=tok,
                   expected="the block written out again in TNC syntax")
    head = re.match(r"[A-Z]*", tok.upper()).group(0)  # QS1 = ...: QS
    known = _KNOWN_UNSUPPORTED.get(head)
    if known is not None:
        where.fail(f"{known} is not supported", column=blk.column, text=tok,
                   expected="3-axis contours of L, C, CR, CT, CP, LP, RND, CHF and the supported cycles")
    where.fail(f"unknown or unsupported block {tok!r}", column=blk.column, text=tok,
               expected="L, LP, C, CC, CR, CT, CP, RND, CHF, TOOL CALL, CYCL DEF, LBL, CALL LBL, CALL PGM, FN, "
                        "Qn =, TRANS, M")


#: Lines of other languages found in files that otherwise hold a TNC program, named for what they are (a
#: TNC refuses them: its blocks are a block number and a conversational keyword, its comments start
#: with ``;``, TNC 640 user's manual, "Programming fundamentals: NC blocks", "Inserting comments"):
#: ``($Message("..."))``, the message command of the CNC Simulator program that its "Heidenhain" examples
#: start with; a parenthesised ISO comment (the setup-sheet header ``( Einrichtblatt`` of a DNC export);
#: an ISO block number ``N10`` before the block.
_FOREIGN_LINES = (
    (re.compile(r"\(\s*\$MESSAGE\b", re.I), "'($Message(...))' is a command of the CNC Simulator program",
     "TNC conversational blocks (a message: FN 16 F-PRINT or a ';' comment)"),
    (re.compile(r"\("), "a '(...)' comment is ISO (DIN 66025) syntax", "a comment after ';'"),
    (re.compile(r"N\d+\s", re.I), "the block number {tok} is ISO (DIN 66025) syntax",
     "a TNC block number without N ('12 L X+10')"),
)

#: ``ERROR = L XQ102 + Q9``: the TNC keeps a block it cannot read when a program is read in (a file
#: written elsewhere, transferred or converted), marked ``ERROR =`` before its text, and refuses to run
#: the program until the block is corrected (our reading: the TNC user's manuals we searched do not
#: describe the marking; found in a shop's keyway macro among the wild TNC programs).
_ERROR_BLOCK = re.compile(r"ERROR\s*=", re.I)

#: Blocks of the TNC's language that vcnc does not run, by their first word (TNC 640 user's manual).
_KNOWN_UNSUPPORTED = {
    "SEL": "SEL TABLE / SEL CONTOUR (tables and contour programs)",
    "SQL": "SQL (table access)",
    "PRESET": "PRESET (the preset table's functions; CYCL DEF 247 selects a preset)",
}


def _begin_pgm(blk: SourceBlock, k: re.Match, m: Machine, where: Where) -> str | None:
    """``BEGIN PGM name MM|INCH``: the program's unit, the last word; returns its name, the words
    before it (a file name with blanks, ``BEGIN PGM CHANFRO EXT RETO MM``, as a shop's iTNC 530 saved
    it)."""
    parts = blk.code[k.end():].split()
    unit = parts[-1].upper() if len(parts) > 1 else "MM"
    if unit not in ("MM", "INCH"):
        col = blk.code.upper().rfind(parts[-1].upper()) + blk.column
        where.fail(f"unknown program unit {parts[-1]!r}", column=col, text=parts[-1], expected="MM or INCH")
    m.inch = unit == "INCH"
    return " ".join(parts[:-1] if len(parts) > 1 else parts) or None


def _cycle_def_block(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    if kw == "CYCLE DEF":
        m.note("'CYCLE DEF' read as CYCL DEF (the spelling of the SolidWorks post)")
    _cycle_def(blk, m, where)


def _pattern_def(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    m.pattern = pattern_positions(blk.code[pos:], where, m.params, column0=blk.column + pos)


def _cycle_call_block(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``CYCL CALL``, ``CYCL CALL PAT``, ``CYCL CALL POS``, with M functions; True at M2/M30."""
    pat = re.match(r"\s*(PAT|POS)(?![A-Z])", blk.code[pos:], re.I)
    kind = pat.group(1).upper() if pat else ""
    words = _read_words(blk.code, pos + (pat.end() if pat else 0), where, m, column0=blk.column)
    if not kind and any(w.key in ("F", "FMAX") for w in words):
        m.note("CYCL CALL F: no positioning in the block (the cycle runs where the tool is)")
    moves = ("F", "FMAX", "X", "Y", "Z", "IX", "IY", "IZ")
    ended = _m_functions([w for w in words if w.key not in moves], m, where, blk, motion=False)
    m.modal_call = False  # a CYCL CALL ends M89
    if kind == "POS":
        position_call([w for w in words if w.key in moves], m, where, blk)
    elif kind == "PAT":
        pattern_call(m, where, blk, positioning_feed(words, m, where))
    else:
        cycle_call(m, where, blk)
    return ended


def _stop_or_m(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``STOP`` (noted, no motion) or a block of M functions; True at M2/M30."""
    if kw == "STOP":
        m.note("STOP: program stop (no motion)")
        m.stop_in_block = m.at_rest = True
    words = _read_words(blk.code, pos if kw == "STOP" else 0, where, m, column0=blk.column)
    return _m_functions(words, m, where, blk, motion=False)


def _ignore(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """BLK FORM: the workpiece blank for the control's graphics, no motion."""


# --- tools -----------------------------------------------------------------------------------

def _tool_def(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``TOOL DEF n L.. R..``: the tool's data in the program; ``TOOL DEF n`` (or a quoted name)
    alone pre-selects the next tool for the tool changer (TNC 640 user's manual, "Tool
    pre-selection with TOOL DEF"): no data, no motion."""
    code = blk.code
    tm = re.match(r"\s*(\d+|\"[^\"]*\"|'[^']*')", code[pos:])
    if tm is None:
        where.fail("TOOL DEF without a tool number", column=blk.column + pos, text=code, expected="TOOL DEF n L.. R..")
    if not code[pos + tm.end():].strip() or not tm.group(1)[0].isdigit():
        if code[pos + tm.end():].strip():
            tok = code[pos + tm.end():].split()[0]
            where.fail(f"unknown word {tok!r} after a tool name in TOOL DEF", column=blk.column + pos + tm.end(),
                       text=tok, expected="TOOL DEF \"name\" (a pre-selection)")
        m.note("TOOL DEF pre-selection: no motion")
        return
    length = radius = 0.0
    j = pos + tm.end()
    while j < len(code):
        wm = re.compile(r"\s*([LR])(?=\s*[+-]?\s*[\d.Q(])", re.I).match(code, j)
        if wm is None:
            if code[j:].strip():
                tok = code[j:].split()[0]
                where.fail(f"unknown word {tok!r} in TOOL DEF", column=blk.column + j, text=tok,
                           expected="L (length) and R (radius)")
            break
        v, j = read_value(code, wm.end(), where, m.params, what=wm.group(1), column0=blk.column)
        if wm.group(1).upper() == "L":
            length = v
        else:
            radius = v
    m.tool_defs[int(tm.group(1)[:9])] = (length * m.scale, radius * m.scale)


def _read_words(code: str, pos: int, where: Where, m: Machine, *, column0: int) -> list[Word]:
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


def _tool_call(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``TOOL CALL n|"name" [X|Y|Z] [S..] [F..] [DL..] [DR..]``: the tool (length and radius), the
    working plane, the spindle speed and the feed. ``F`` is the feed of the following moves until a
    block programs another (iTNC 530 / TNC 640 user's manuals, "Calling tool data": "Feed rate F ...
    is effective until you program a new feed rate in a positioning block or in a TOOL CALL block";
    shop programs write ``TOOL CALL 22 Z S6000 F2000`` and then ``L Z+Q22`` without F), and what
    ``F AUTO`` reads."""
    code = blk.code
    rest = code[pos:]
    # 12.1: tool 12, index 1; "NAME", QS5: a name; Q11: a number in a Q parameter
    nm = re.match(r"\s*(\d+(?:\.\d)?|\"[^\"]*\"|'[^']*'|QS\d+(?![\d.])|Q[LR]?\d+(?![\d.]))?", rest)
    number = int(nm.group(1).split(".")[0][:9]) if nm.group(1) and nm.group(1)[0].isdigit() else None
    name = nm.group(1)[1:-1] if nm.group(1) and nm.group(1)[0] in "\"'" else None
    if nm.group(1) and QS_NAME_RE.fullmatch(nm.group(1)):  # TOOL CALL QS5: the name the string parameter holds
        name = m.strings.get(nm.group(1), where, column=blk.column + pos + nm.start(1))
    elif nm.group(1) and nm.group(1)[0] in "qQ":  # TOOL CALL Q11 Z ..: the tool number in a Q parameter
        number = _whole_number(nm.group(1), m, where, blk.column + pos + nm.start(1), what="tool number")
    if number is not None and "." in nm.group(1):
        m.note(f"indexed tool {nm.group(1)}: length and radius of tool {number} (vcnc's tool table has no indices)")
    named = name is not None  # a tool called by name: the table's NAME column
    if named:
        by_name = m.context.tool_named(name)
        if by_name is not None:
            number, named = by_name.number, False
        else:
            m.note(f"tool \"{name}\" called by name is not in the tool table: length and radius 0")
    j = pos + nm.end()
    dl = dr = 0.0
    while j < len(code):
        wm = re.compile(r"\s*(?:(DL|DR2|DR|S|F)(?=\s*[+-]?\s*[\d.Q(])|([XYZ])(?![\w+-.]))", re.I).match(code, j)
        if wm is None:
            if code[j:].strip():
                tok = code[j:].split()[0]
                where.fail(f"unknown word {tok!r} in TOOL CALL", column=blk.column + j, text=tok,
                           expected="TOOL CALL n [X|Y|Z] [S..] [F..] [DL..] [DR..]")
            break
        if wm.group(2):
            m.plane = _PLANE_OF_TOOL_AXIS[wm.group(2).upper()]
            j = wm.end()
            continue
        v, j = read_value(code, wm.end(), where, m.params, what=wm.group(1), column0=blk.column)
        word = wm.group(1).upper()
        if word == "DL":
            dl = v * m.scale
        elif word == "DR":
            dr = v * m.scale
        elif word == "S":
            m.spindle = v
        elif word == "F" and v > 0:
            m.auto_feed = v
            m.feed = v * m.feed_scale
    if number is not None:
        if number in m.tool_defs:
            length, radius = m.tool_defs[number]
        else:
            tool = m.context.tool(number)
            if tool is None:
                if number != 0:
                    m.note(f"tool {number} is not in the tool table: length and radius 0")
                length = radius = 0.0
            else:
                length, radius = tool.length, tool.radius
        m.tool_length = length + dl
        m.tool_radius = radius + dr
        m.tool_delta = dr
        m.at_rest = m.at_rest or number != m.tool_number
        m.tool_number = number
    elif named:
        m.tool_length, m.tool_radius, m.tool_delta = dl, dr, dr
        m.tool_number = 0
        m.at_rest = True  # a tool called by name that the table does not hold: a change all the same
    _tool_parameters(m, where)


def _tool_parameters(m: Machine, where: Where) -> None:
    """The preassigned Q parameters of the called tool (TNC 640 user's manual, "Preassigned Q
    parameters"): Q108 the active tool radius (table or TOOL DEF, plus DR), Q109 the tool axis
    (0 X, 1 Y, 2 Z), Q113 the unit of the program (0 mm, 1 inch), Q114 the active tool length, in
    the program's unit. Programs read them to size their own paths (a shop face-milling program:
    ``Q1963 = Q1812 * Q108 * 2``, the stepover from the tool diameter)."""
    m.params.set("Q108", m.tool_radius / m.scale, where)
    m.params.set("Q109", float(m.plane), where)
    m.params.set("Q113", 1.0 if m.inch else 0.0, where)
    m.params.set("Q114", m.tool_length / m.scale, where)


# --- cycles ----------------------------------------------------------------------------------

def _cycle_def(blk: SourceBlock, m: Machine, where: Where) -> None:
    cm = CYCLE_RE.match(blk.code)
    if cm is None:
        where.fail("malformed cycle definition", column=blk.column, text=blk.code, expected="CYCL DEF n[.m] ...")
    number = int(cm.group(1)[:6])
    sub = int(cm.group(2)) if cm.group(2) is not None else None
    rest = cm.group(3)
    col = blk.column + cm.start(3)
    if number == 247:
        _preset_cycle(rest, m, where, col)
        return
    if number in CONTOUR_CYCLES or number in ROUGHING_CYCLES:
        _sl_cycle_def(number, sub, rest, m, where, col)
        return
    if number in _SETTING_CYCLES:
        q_assignments(rest, where, m.params, column0=col)
        m.note(f"CYCL DEF {number}: {_SETTING_CYCLES[number]}; no motion")
        return
    if number in SURFACE_CYCLES:
        q = q_assignments(rest, where, m.params, column0=col, auto_feed=m.auto_feed)
        m.cycle, m.cycle_program = surface_cycle(number, q, feed_scale=m.feed_scale, scale=m.scale, where=where,
                                                 column=blk.column), None
        return
    if number not in (7, 9, 12, 13, 19, 32, *TRANSFORM_CYCLES, *MACHINING_CYCLES, *PATTERN_CYCLES):
        why = f" {REFUSED_CYCLES[number]}" if number in REFUSED_CYCLES else ""
        where.fail(f"cycle {number}{why} is not supported", column=blk.column, text=blk.code.strip(),
                   expected="CYCL DEF 1, 2, 4, 5, 7-14, 17, 19 (reset), 20-26, 32, 200-215, 220, 221, "
                            "230-233, 240, 241, 247, 251, 252, 253, 254, 256, 257, 262-265, 267, 392")
    if number in MACHINING_CYCLES and (number not in LEGACY_CYCLES or sub in (None, 0)):
        m.cycle_program = None
    if number == 12 and sub == 1:
        pm = re.match(r"\s*PGM\s+(\"[^\"]+\"|'[^']+'|\S+)\s*$", rest, re.I)
        if pm is None:
            where.fail("malformed cycle 12 PGM CALL", column=col, text=rest.strip(),
                       expected="CYCL DEF 12.1 PGM name")
        m.cycle_program = (pm.group(1), col + pm.start(1))
        return
    if number >= 200:
        q = q_assignments(rest, where, m.params, column0=col, auto_feed=m.auto_feed)
        if number in PATTERN_CYCLES:
            if q.get(365, 0.0):
                m.note("cycle 220 Q365=1: moves between positions straight, not along the pitch circle")
            pattern_cycle_run(pattern_cycle(number, q, scale=m.scale, where=where, column=blk.column), m, where,
                               blk)
            return
        m.cycle = drill_cycle(number, q, feed_scale=m.feed_scale, scale=m.scale, where=where, column=blk.column,
                              spindle=m.spindle)
        return
    if sub in (None, 0):
        if number in LEGACY_CYCLES:
            m.cycle_items = {}
        return
    if number in TRANSFORM_CYCLES:
        if sub == 1:
            _transform_cycle(number, rest, m, where, col)
        return
    if number == 19:
        _tilt_cycle(rest, m, where, col)
        return
    if number == 7:
        if rest.strip().startswith("#"):  # TNC 640 manual, cycle 7: "#5" selects a row of the datum table
            where.fail("cycle 7 with a datum table row (#n) is not supported (no datum table in the machine context)",
                       column=col, text=rest.strip(), expected="CYCL DEF 7.1 X.. / 7.2 Y.. / 7.3 Z..")
        words = _read_words(rest, 0, where, m, column0=col)
        for w in words:
            if w.key not in ("X", "Y", "Z", "IX", "IY", "IZ"):
                where.fail(f"word {w.text!r} in a datum shift", column=w.column, text=w.text,
                           expected="X, Y or Z (IX.. incremental)")
        _datum_shift({w.key: w.value for w in words}, m)
        return
    if number == 32 and sub >= 2:  # 32.2 HSC-MODE / TA: the control's smoothing filter, not modelled
        m.note(f"CYCL DEF 32.{sub} {rest.strip()} ignored")
        return
    last = LEGACY_CYCLES.get(number, 1)  # the lines a value cycle has: 9.1, 12.1, 32.1; 1.1-1.5, 2.1-2.4, 17.1-17.3
    if number == 12 or sub > last:
        where.fail(f"cycle {number}.{sub}: cycle {number} has no line {sub}", column=blk.column,
                   text=blk.code.strip(), expected=f"CYCL DEF {number}.0 .. {number}.{last}")
    if number in (4, 5):  # POCKET MILLING, CIRCULAR POCKET: lines with a feed and a direction besides the value
        m.cycle_items[sub] = pocket_item(number, sub, rest, where, m.params, column0=col)
        if sub == last:
            m.cycle = old_pocket(number, m.cycle_items, feed_scale=m.feed_scale, scale=m.scale, where=where,
                                 column=blk.column)
        return
    _value_line(number, sub, rest, m, where, blk, col)


def _value_line(number: int, sub: int, rest: str, m: Machine, where: Where, blk: SourceBlock, col: int) -> None:
    """Line ``number.sub`` of an old cycle whose lines each hold one value: 9.1 dwell (runs at once), 13.1
    orientation angle, 32.1 tolerance, and the items of 1 PECKING, 2 TAPPING, 17 RIGID TAPPING (the cycle is
    defined by its last line)."""
    value = legacy_value(rest, where, m.params, column0=col, what=f"cycle {number}.{sub}")
    if number == 9:
        if value is None or value < 0:
            where.fail("dwell time must be >= 0 [s]", column=col, text=rest.strip(), expected="CYCL DEF 9.1 DWELL t")
        m.emit("dwell", m.pos, None, 0.0, where, blk.number, dwell=value)
    elif number == 13:  # 13.1 ANGLE a: TNC 426/430 manual, "ORIENTATION (Cycle 13)": the spindle stops at a
        # (M19 or M20 when called); no motion
        m.note("CYCL DEF 13 ORIENTATION: an oriented spindle stop; no motion")
    elif number == 32:
        if sub == 1:
            if value is not None and not value > 0:
                where.fail("tolerance T must be > 0 [mm]", column=col, text=rest.strip(), expected="T > 0 [mm]")
            m.exact_stop = False
            m.tolerance = value * m.scale if value is not None else m.context.dialect.tolerance
    else:  # cycles 1 PECKING (1.1 .. 1.5), 2 TAPPING (2.1 .. 2.4), 17 RIGID TAPPING (17.1 .. 17.3)
        if value is None:
            where.fail(f"cycle {number}.{sub} without a value", column=col, text=blk.code, expected="a number")
        m.cycle_items[sub] = value
        if sub == LEGACY_CYCLES[number] and number == 1:
            m.cycle = pecking_cycle(m.cycle_items, feed_scale=m.feed_scale, scale=m.scale, where=where,
                                    column=blk.column)
        elif sub == LEGACY_CYCLES[number]:
            m.cycle = tapping_cycle(number, m.cycle_items, feed_scale=m.feed_scale, scale=m.scale, where=where,
                                    column=blk.column, spindle=m.spindle)


def _sl_cycle_def(number: int, sub: int | None, rest: str, m: Machine, where: Where, col: int) -> None:
    """The SL cycles (:mod:`interpolators.heidenhain_contours`): 14 CONTOUR GEOMETRY and 20 CONTOUR DATA
    are DEF-active, 21-24 (pilot drilling, rough-out, floor and side finishing) and 25 CONTOUR TRAIN called."""
    if number == 14:
        if sub == 1:
            m.contour = contour_labels(rest, where, col)
        return
    q = q_assignments(rest, where, m.params, column0=col, auto_feed=m.auto_feed)
    if number == 20:
        m.contour_data = contour_data(q, where, col)
        return
    m.cycle_program = None
    if number in ROUGHING_CYCLES:
        make = {21: pilot_drilling_cycle, 22: rough_out_cycle, 23: floor_finishing_cycle,
                24: side_finishing_cycle}[number]
        m.cycle = make(q, m.contour_data, feed_scale=m.feed_scale, scale=m.scale, where=where, column=col)
        return
    m.cycle = contour_train_cycle(q, feed_scale=m.feed_scale, scale=m.scale, where=where, column=col)


#: Cycles that set the machine up and move nothing: their Q parameters are assigned, the cycle noted.
_SETTING_CYCLES = {
    # DMG MORI's ATC (Application Tuning Cycle), a machine maker's cycle of its TNC 640 machines: Q240
    # TUNING MODE / Q241 WEIGHT MODE select the feed-axis dynamics (hyperMILL's DMU posts write it first)
    392: "ATC (the machine maker's dynamics tuning: vcnc's drive model is the machine's own)",
}


def _preset_cycle(rest: str, m: Machine, where: Where, col: int) -> None:
    """``CYCL DEF 247 DATUM SETTING Q339=n`` activates row n of the preset table (TNC 640 cycle
    manual, "DATUM SETTING (Cycle 247)"). The machine context's work offsets stand in for that
    table in the order of :data:`interpolators.context.WORK_OFFSETS`, as the CAM posts number them
    (G54 = preset 1, G55 = 2, ... G59.3 = 9); row 0, the preset set by hand, is G54, the context's
    preset at the program start. A row beyond them (``Q339=+15``, a shop's fixture program) is a zero
    offset with a note, as the ISO reader takes a work offset the context's table has no entry for
    (:meth:`interpolators.context.MachineContext.offset`: zero). "When activating a preset from the
    preset table, the control resets the datum shift, mirroring, rotation, scaling factor and
    axis-specific scaling factor" (TNC 640 cycle manual, cycle 247, notes)."""
    q = q_assignments(rest, where, m.params, column0=col)
    if 339 not in q:
        where.fail("cycle 247 lacks Q339", column=col, text=rest.strip(), expected="Q339 = the preset number")
    n = int(q[339])
    if n != q[339] or n < 0:
        where.fail(f"cycle 247: preset {q[339]:g} is not a row of the preset table", column=col,
                   text=rest.strip(), expected="Q339 = a whole number >= 0 (1 .. 9: G54 .. G59.3)")
    if m.comp != "R0":
        where.fail(f"cycle 247 while radius compensation {m.comp} is active", column=col, text=rest.strip(),
                   expected="R0 before a new preset")
    if m.tilt is not None:
        where.fail(f"cycle 247 in the tilted working plane of {m.tilt.what}", column=col, text=rest.strip(),
                   expected="PLANE RESET (or CYCL DEF 19.1 without angles) before a new preset")
    m.preset = _preset_row(max(n, 1))
    m.shift = np.zeros(3)
    m.transform = Transform()
    if m.preset is None:
        m.note(f"CYCL DEF 247 Q339={n}: preset {n} is beyond the context's work offsets (G54 .. G59.3): "
               "zero offset, as a work offset without a table entry")
    else:
        m.note(f"CYCL DEF 247 Q339={n}: preset {n} is the work offset {m.preset}")


def _touch_probe(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``TCH PROBE 4xx .. Qnnn=..``: run on the nominal workpiece (:mod:`interpolators.heidenhain_probing`): the
    probe's moves, the result parameters, the datum the cycle sets."""
    pm = PROBE_RE.match(blk.code)
    if pm is None:
        where.fail("malformed touch probe cycle", column=blk.column, text=blk.code, expected="TCH PROBE n ...")
    number = int(pm.group(1))
    if number not in PROBE_CYCLES:
        refuse_probe(number, where, blk.column)
    col = blk.column + pm.start(3)
    if not dataclasses.replace(m.transform, tilt=0.0).identity or m.comp != "R0":
        where.fail(f"TCH PROBE {number} under a mirror, rotation, scaling or radius compensation is not modelled",
                   column=blk.column, text=blk.code, expected="R0, no cycle 8/10/11/26 before the touch probe cycle")
    q = q_assignments(pm.group(3), where, m.params, column0=col)
    tip = m.context.touch_probe.tip_radius
    run = probe_run(number, q, here=m.to_program(m.pos), plane=m.plane,
                    tip_radius=m.tool_radius if tip is None else tip, scale=m.scale,
                    probe=m.context.touch_probe, where=where, column=col)
    sets_datum = not np.all(np.isnan(run.datum_from))  # a datum cycle (the measuring cycles set none)
    if sets_datum and m.tilt is not None and run.q305 != 0:
        where.fail(f"TCH PROBE {number} in the tilted plane of {m.tilt.what} writing row {run.q305} of a table is "
                   "not modelled", column=blk.column, text=blk.code,
                   expected="Q305=0 (the active datum) in a tilted plane, or PLANE RESET before the cycle")
    for move in run.moves:
        target = m.to_machine(move.target)
        if move.centre is None:
            m.emit("line", target, Line(m.pos, target), move.feed / 60.0, where, blk.number)
        else:
            seg = helical_arc(m.pos, m.to_machine(move.centre), move.sweep, plane=m.plane, axis_end=target[m.plane])
            m.emit("arc", target, seg, move.feed / 60.0, where, blk.number)
    for n, value in run.results.items():
        m.params.set(f"Q{n}", value, where, column=col)
    if sets_datum:
        _probed_datum(run.datum_from, run.datum_to, run.q305, run.q303, m, number)
    m.note(f"touch probe cycle {number}: run on the nominal workpiece (touch points where the data put the surface)")
    for note in run.notes:
        m.note(note)


def _probed_datum(origin_from: np.ndarray, origin_to: np.ndarray, row: int, table: int, m: Machine,
                  number: int) -> None:
    """The datum a probe cycle sets: the program point ``origin_from`` [mm] gets the coordinates ``origin_to``
    (NaN: an axis not set). Q305=0: the active preset moves so (the display shows the new datum, iTNC 530 cycle
    manual 15.6, Q305); in a tilted plane the program point is one of the tilted plane, and the preset, which
    stays one of the untilted coordinates, moves by the plane's rotation of it, so that the tilted plane's
    zero moves by it and PLANE RESET finds the part where the probe put it (our reading: the manual's page on
    probing in a tilted plane was not found); Q305=n, Q303=1: row n of the preset table (the work offsets, as
    cycle 247 numbers them)
    holds the datum, active once cycle 247 selects it; Q303=0 (or -1): row n of the datum table, which vcnc
    does not model (noted)."""
    delta = np.where(np.isnan(origin_from), 0.0, origin_from - np.nan_to_num(origin_to))
    if row == 0 and m.tilt is not None:  # the datum set in the tilted plane, the preset kept untilted
        machine = m.to_machine(delta) - m.to_machine(np.zeros(3))
        m.presets[m.preset] = m.preset_value() + m.tilt.rotation @ delta
        m.tilt = dataclasses.replace(m.tilt, datum=m.tilt.datum + machine)
        return
    if row == 0:
        m.presets[m.preset] = m.preset_value() + delta
        return
    if table != 1 or _preset_row(row) is None:
        m.note(f"TCH PROBE {number}: the datum written to row {row} of the "
               f"{'preset' if table == 1 else 'datum'} table is not modelled (no effect on the following blocks)")
        return
    m.presets[_preset_row(row)] = m.preset_value() + m.shift + delta


def _preset_row(n: int) -> str | None:
    """The work offset that stands in for row ``n`` >= 1 of the preset table (:func:`_preset_cycle`: G54 = 1 ..
    G59.3 = 9); None beyond them."""
    return WORK_OFFSETS[n - 1] if n <= len(WORK_OFFSETS) else None


def _datum_shift(values: dict[str, float], m: Machine) -> None:
    """Cycle 7 / TRANS DATUM: ``X`` shifts from the preset, ``IX`` from the last shift [program units]."""
    if m.tilt is not None:  # a shift in the tilted plane: the one in force after PLANE RESET (:func:`_untilt`)
        m.tilt = dataclasses.replace(m.tilt, shifted=True)
    for key, value in values.items():
        i = "XYZ".index(key[-1])
        m.shift[i] = (m.shift[i] if key.startswith("I") else 0.0) + value * m.scale


def _tilt(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``PLANE``: the tilted working plane on a machine with kinematics (:func:`_plane`), else no motion
    when nothing tilts and an error naming the function otherwise; ``FUNCTION``: ``FUNCTION DWELL TIME t``
    / ``REV r`` is a dwell of t [s] or of r spindle revolutions (TNC 640 user's manual, "Defining a
    dwell time: FUNCTION DWELL"), ``FUNCTION TCPM`` an error."""
    if kw == "FUNCTION" and re.match(r"\s*FEED\s+DWELL\b", blk.code[pos:], re.I):
        _feed_dwell(blk, pos, m, where)
        return
    dm = re.match(r"\s*DWELL\s+(TIME|REV)\s*", blk.code[pos:], re.I) if kw == "FUNCTION" else None
    if dm is None:
        if kw == "PLANE" and m.context.kinematics is not None:
            _plane(blk.code[pos:], m, where, blk, blk.column + pos)
            return
        m.note(tilt_block(kw, blk.code[pos:], where, m.params, column0=blk.column + pos))
        return
    col = blk.column + pos
    value, end = read_value(blk.code[pos:], dm.end(), where, m.params, what=dm.group(1).upper(), column0=col)
    if value < 0 or blk.code[pos + end:].strip():
        where.fail("malformed FUNCTION DWELL", column=col, text=blk.code, expected="FUNCTION DWELL TIME t [s] or REV r")
    if dm.group(1).upper() == "REV":
        if not m.spindle:
            where.fail("FUNCTION DWELL REV without a spindle speed", column=col, text=blk.code,
                       expected="TOOL CALL .. S<rpm> before it")
        value = value * 60.0 / m.spindle
    m.emit("dwell", m.pos, None, 0.0, where, blk.number, dwell=value)


_FEED_DWELL_RE = re.compile(r"\s*FEED\s+DWELL\s+(?:(RESET)|D-TIME\s*(\S+)\s+F-TIME\s*(\S+))\s*$", re.I)


def _feed_dwell(blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``FUNCTION FEED DWELL D-TIME d F-TIME f`` / ``FUNCTION FEED DWELL RESET`` (TNC 640 user's manual, "Cyclic
    dwell time"; :mod:`interpolators.heidenhain_feed_dwell`)."""
    fm = _FEED_DWELL_RE.match(blk.code, pos)
    if fm is None:
        where.fail("malformed FUNCTION FEED DWELL", column=blk.column + pos, text=blk.code[pos:].strip(),
                   expected="FUNCTION FEED DWELL D-TIME<s> F-TIME<s>, or FUNCTION FEED DWELL RESET")
    if fm.group(1):
        m.feed_dwell = None
        return
    col = blk.column + pos
    d_time = m.params.evaluate(fm.group(2), where, column=col + fm.start(2))
    f_time = m.params.evaluate(fm.group(3), where, column=col + fm.start(3))
    if not (d_time >= 0 and f_time > 0):
        where.fail("FUNCTION FEED DWELL needs D-TIME >= 0 and F-TIME > 0", column=col, text=blk.code[pos:].strip(),
                   expected="dwell and cutting times in seconds")
    m.feed_dwell = FeedDwell(dwell=d_time, cutting=f_time) if d_time > 0 else None
    m.note("FUNCTION FEED DWELL: a dwell after every F-TIME of feed motion (the cutting time at the programmed feed)")


def _rotary_now(m: Machine) -> Solution:
    """Positions of the kinematics' rotary axes (outer, inner; inner 0 without one) [deg]."""
    return m.context.kinematics.solution_at(m.extra)


def _plane(text: str, m: Machine, where: Where, blk: SourceBlock, col: int) -> None:
    """``PLANE <form> .. MOVE|TURN|STAY``, ``PLANE RESET``: tilt the working plane on the machine's tilting
    table (:mod:`interpolators.tilted`, :func:`interpolators.heidenhain_transforms.read_plane`).

    TNC 640 / iTNC 530 user's manuals, "The PLANE function: Tilting the working plane", "Specifying the
    positioning behavior of the PLANE function": the control computes the rotary axes' positions (and
    stores them in Q120 A, Q121 B, Q122 C: iTNC 530 DIN/ISO manual, "Preassigned Q parameters", "Tilting
    the working plane with mathematical angles: rotary axis coordinates calculated by the TNC"); MOVE
    turns them and moves the linear axes so that the tool tip (the point DIST above it) keeps its place
    on the part, TURN turns them alone, STAY moves nothing (the program positions them, e.g. ``L
    A+Q120 C+Q122 R0 FMAX``; the plane holds once they are there: a move in it before is an error here);
    MB retracts along the tool axis first (MB MAX to ``context.home``'s level, as M140). ``PLANE RESET``
    cancels the tilt; its MOVE/TURN turn the axes back to 0.
    """
    kin = m.context.kinematics
    pb = read_plane(text, where, m.params, column0=col)
    what = f"PLANE {pb.form} (line {where.line})"
    if pb.positioning is None:
        m.note(f"PLANE {pb.form} without MOVE/TURN/STAY: STAY (the rotary axes are not positioned)")
    try:
        kin.require_table()
        current = _rotary_now(m)
        active = m.tilt.rotation if m.tilt is not None else np.eye(3)
        rotation = plane_rotation(pb, active=active, kinematics=kin, current=current)
        angles = None if rotation is None else kin.choose(rotation, current, sequence=pb.sequence,
                                                          table_rot=pb.table_rot)
    except TiltError as exc:
        where.fail(f"PLANE {pb.form}: {exc.message}", column=col, text=text.strip(), expected=exc.expected)
    _retract(pb, m, where, blk)
    if rotation is None:
        _untilt(m)
        angles = Solution(0.0, 0.0)
    else:
        _tilt_to(rotation, angles, what, m, where, col)
    if pb.positioning in ("MOVE", "TURN"):
        _position_rotary(pb, current, angles, m, where, blk)


def _retract(pb: PlaneBlock, m: Machine, where: Where, blk: SourceBlock) -> None:
    """PLANE .. MB: the retraction along the tool axis before the rotary axes turn (TNC 640 user's manual,
    PLANE positioning behaviour "MB": MB MAX to the machine's limit, here ``context.home``'s level)."""
    if pb.retract is None or pb.positioning not in ("MOVE", "TURN"):
        return
    target = m.pos.copy()
    if math.isinf(pb.retract):
        target[m.plane] = max(m.context.home[m.plane], m.pos[m.plane])
    else:
        target[m.plane] += pb.retract * m.scale
    if target[m.plane] != m.pos[m.plane]:
        m.used.add(m.plane)
        m.emit("rapid", target, Line(m.pos, target), math.inf, where, blk.number)


def _untilt(m: Machine) -> None:
    """Cancel the tilted plane. The datum shift of before it is back (TNC cycle manual, cycle 19: reset the
    tilt, then the datum shift, the reverse of activating them), unless one was programmed in the plane: the
    TNC keeps one datum shift, and CAM posts (hyperMILL, PowerMILL) reset it with ``CYCL DEF 7.1 X0 ..`` just
    before ``PLANE RESET``; its last values then stand, in the untilted coordinates (our reading)."""
    if m.tilt is not None and not m.tilt.shifted:
        m.shift = m.tilt.base_shift.copy()
    m.tilt = None
    m.transform = dataclasses.replace(m.transform, tilt=0.0)


def _tilt_to(rotation: np.ndarray, angles: Solution, what: str, m: Machine, where: Where, col: int) -> None:
    """Make the plane ``rotation`` at the rotary positions ``angles`` [deg] the active one. The datum
    shift active before the first tilt moves the plane's zero (in the untilted coordinates); cycle 7 in
    the tilted plane shifts in it, from its zero (TNC cycle manual, cycle 19 WORKING PLANE, "Combining
    coordinate transformation cycles": datum shift before the tilt, other transformations after it)."""
    kin = m.context.kinematics
    if m.plane != 2:
        where.fail(f"{what}: a tilted working plane with tool axis {'XYZ'[m.plane]}", column=col, text=where.text,
                   expected="TOOL CALL .. Z (the tilting table brings the plane under a Z spindle)")
    if m.comp != "R0":
        where.fail(f"{what} while radius compensation {m.comp} is active", column=col, text=where.text,
                   expected="R0 before tilting the working plane")
    base_shift = m.tilt.base_shift if m.tilt is not None else m.shift.copy()
    try:  # the active preset, also one a touch probe cycle set (it was the context's work offset alone)
        theta, datum = tilted_frame(kin, rotation, angles, np.add(m.preset_value(), base_shift))
    except TiltError as exc:
        where.fail(exc.message, column=col, text=where.text, expected=exc.expected)
    positions = kin.positions(angles)
    m.tilt = TiltedPlane(rotation=rotation, angles={EXTRA_LETTERS.index(a.upper()): v for a, v in positions.items()},
                         datum=datum, base_shift=base_shift, what=what)
    m.shift = np.zeros(3)
    m.transform = dataclasses.replace(m.transform, tilt=theta)
    for name, value in positions.items():
        m.params.set(f"Q{120 + 'abc'.index(name)}", value, where)


def _position_rotary(pb: PlaneBlock, old: Solution, new: Solution, m: Machine, where: Where,
                     blk: SourceBlock) -> None:
    """PLANE .. TURN: the rotary axes to ``new`` [deg], the linear axes stay; MOVE: with the linear axes,
    so that the point ``DIST`` above the tool tip keeps its place on the part (one block here)."""
    kin = m.context.kinematics
    extra = m.extra.copy()
    for name, value in kin.positions(new).items():
        extra[EXTRA_LETTERS.index(name.upper())] = value
        m.used.add(3 + EXTRA_LETTERS.index(name.upper()))
    m.extra_used = True
    target = m.pos.copy()
    if pb.positioning == "MOVE":
        lift = np.zeros(3)
        lift[m.plane] = pb.dist * m.scale - m.tool_length  # from the spindle's point to the centre of rotation
        target = kin.place(kin.unplace(m.pos + lift, old), new) - lift
    if np.array_equal(extra, m.extra) and np.allclose(target, m.pos, rtol=0.0, atol=1e-12):
        return  # already there: nothing moves
    if pb.feed is None:
        m.note(f"PLANE {pb.form} {pb.positioning} without F: at FMAX")
    feed = math.inf if pb.feed is None or math.isinf(pb.feed) else pb.feed * m.feed_scale
    m.emit("rapid" if math.isinf(feed) else "line", target, Line(m.pos, target), feed, where, blk.number,
           extra=extra)


def _trans(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``TRANS DATUM|MIRROR|ROTATION|SCALE``: the transformations of cycles 7, 8, 10, 11."""
    col = blk.column + pos
    t, shift = trans_block(blk.code[pos:], m.transform, where, m.params, column0=col, scale=m.scale)
    if shift is not None:
        if not shift:
            m.shift = np.zeros(3)
        _datum_shift(shift, m)
    elif t != m.transform:
        _set_transform(t, "TRANS", m, where, col, blk.code[pos:])


def _transform_cycle(number: int, rest: str, m: Machine, where: Where, col: int) -> None:
    """Item ``.1`` of cycles 8, 10, 11, 26 (:mod:`interpolators.heidenhain_transforms`)."""
    t = transform_item(number, rest, m.transform, where, m.params, column0=col, scale=m.scale)
    _set_transform(t, f"cycle {number}", m, where, col, rest)


def _set_transform(t: Transform, what: str, m: Machine, where: Where, col: int, text: str) -> None:
    if t.mirror[m.plane]:
        where.fail(f"MIRROR IMAGE of the tool axis {'XYZ'[m.plane]}", column=col, text=text.strip(),
                   expected="mirrored axes of the working plane (the TNC cannot mirror the tool axis)")
    if m.comp != "R0" and t != m.transform:
        where.fail(f"{what} while radius compensation {m.comp} is active", column=col, text=text.strip(),
                   expected="R0 before a coordinate transformation (the TNC cancels RL/RR there)")
    m.transform = t


def _tilt_cycle(rest: str, m: Machine, where: Where, col: int) -> None:
    """``CYCL DEF 19.1 A.. B.. C.. [F..] [DIST..]``: cycle 19 WORKING PLANE (TNC 640 cycle programming
    manual, "WORKING PLANE (Cycle 19, software option)"). Without angles, or with all 0, it cancels the
    tilt (no motion). Other angles need the machine's kinematics; they are spatial angles (as PLANE
    SPATIAL: "the function corresponds to Cycle 19, if the entries in Cycle 19 are set to space angles",
    iTNC 530 user's manual, PLANE SPATIAL), and the program positions the rotary axes itself (the manual's
    "manual positioning": ``L B+Q121 C+Q122 R0 F..`` before or after the cycle): as PLANE .. STAY."""
    angles: dict[str, float] = {}
    for am in re.finditer(r"(?<![A-Z])([ABC])(?=\s*[+-]?\s*[\d.Q(])", rest, re.I):
        angles[am.group(1).upper()] = read_value(rest, am.end(), where, m.params, what=am.group(1), column0=col)[0]
    tilted = any(v != 0.0 for v in angles.values())
    kin = m.context.kinematics
    if kin is None:
        if tilted:
            where.fail("cycle 19 WORKING PLANE (a tilted working plane) is not supported without the machine's "
                       "kinematics", column=col, text=rest.strip(), expected=KINEMATICS_HINT)
        m.note("CYCL DEF 19 with angles 0: no tilted working plane (no motion)")
        return
    if not tilted:
        _untilt(m)
        m.note("CYCL DEF 19 without angles: the tilted working plane is cancelled (no motion)")
        return
    try:
        kin.require_table()
        rotation = spatial(angles.get("A", 0.0), angles.get("B", 0.0), angles.get("C", 0.0))
        solution = kin.choose(rotation, _rotary_now(m))
    except TiltError as exc:
        where.fail(f"cycle 19: {exc.message}", column=col, text=rest.strip(), expected=exc.expected)
    _tilt_to(rotation, solution, f"CYCL DEF 19 (line {where.line})", m, where, col)


# --- splines ---------------------------------------------------------------------------------

def _spline_block(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``SPL X.. Y.. Z.. K3X.. K2X.. K1X.. .. [F..] [M..]`` (:mod:`interpolators.heidenhain_splines`): the curve as
    chords joined without stops, the last one ending as the path mode says; True at M2/M30."""
    spl = read_spline(blk.code, pos, where, m.params, column0=blk.column)
    words = _read_words(spl.rest, pos, where, m, column0=blk.column)
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

def _without_m128_feed(words: list[Word], m: Machine) -> list[Word]:
    """``words`` without the F word right after M128, which is not the path feed but "another feed rate, at which
    the TNC will carry out the compensation movements in the linear axes" (TNC 620 user's manual for DIN/ISO
    programming 34056x-04, M128; the iTNC 530 manual's example ``L X+0 Y+38.5 IB-15 RL F125 M128 F1000``). vcnc's
    M128 moves no rotary axis (they are positioned before it): noted, no effect."""
    out: list[Word] = []
    for w in words:
        if w.key == "F" and out and out[-1].key == "M" and out[-1].value == 128:
            m.note(f"M128 {w.text}: the feed of compensation movements (no rotary axis moves under M128 here)")
            continue
        out.append(w)
    return out


def _m_functions(words: list[Word], m: Machine, where: Where, blk: SourceBlock, *, motion: bool) -> bool:
    """Check the M words of a block without motion words; True when the program ends here."""
    words = _without_m128_feed(words, m)
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
                    continue
                else:
                    m.note(f"M{w.value} in a block without coordinates has no effect")
        elif w.key == "MBMAX" or w.key == "MB":
            continue
        elif not motion:
            where.fail(f"word {w.text!r} in a block without motion", column=w.column, text=w.text,
                       expected="M functions")
    return ended


def _one_m(w: Word, m: Machine, where: Where) -> bool:
    if w.value in _M_PATH:
        _path_m(w, m, where)
        return False
    if w.value == 128:  # TNC 640 manual, "Retaining the position of the tool tip when positioning tilting axes"
        check_tcpm_on(m.context.kinematics, tool_axis=m.plane, tilted=m.tilt is not None, where=where,
                      column=w.column, text=w.text)
        m.tcpm = True
        m.note("M128: TCPM on positioned rotary axes (lines of the tool tip on the turned part)")
        return False
    if w.value == 129:
        m.tcpm = False
    if w.value in _M_END:
        return True
    if w.value in _M_STOP:
        m.note(f"M{w.value}: program stop (no motion)")
        m.stop_in_block = True
        m.at_rest = m.at_rest or w.value == 0
    elif w.value not in (3, 4, 5, 8, 9, 89, 91, 92, 99, 140):
        m.note(f"M{w.value} ignored (no motion)")
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
      M136"): F in mm per revolution from the start of the block (:func:`_read_words`).
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

def _corner_def(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    code = blk.code
    rm = re.compile(r"\s*R(?=\s*[+-]?\s*[\d.Q(])", re.I).match(code, pos) if kw == "RND" else None
    j = rm.end() if rm else pos
    value, j = read_value(code, j, where, m.params, what=kw, column0=blk.column)
    words = _read_words(code, j, where, m, column0=blk.column)
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
    r0, a0 = polar_angle(m.pos, m.pole, plane=plane)
    k, t = m.scale * m.lengths(where), m.transform
    pr = seen["PR"].value * k if "PR" in seen else r0 + (seen["IPR"].value * k if "IPR" in seen else 0.0)
    pa = (t.angle(seen["PA"].value, plane) if "PA" in seen
          else a0 + (t.sweep(seen["IPA"].value, plane) if "IPA" in seen else 0.0))
    m.used.update(PLANE_AXES[plane])
    return polar_point(m.pole, pr, pa, plane=plane, base=target)


def _motion(kw: str, words: list[Word], m: Machine, where: Where, blk: SourceBlock) -> bool:
    """Run a motion block (L, LP, C, CR, CT, CTP, CP, CC); True when it ends the program."""
    seen, ms = _motion_words(kw, words, m, where)
    mvals = [w.value for w in ms]
    m9x = 91 if 91 in mvals else 92 if 92 in mvals else None
    ended = any(_one_m(w, m, where) for w in ms)
    if kw == "CC":
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
    if normal:
        target = target + _normal_offset(seen, m, where, blk)
    m.used.update(written)
    feed = math.inf if rapid else m.feed
    extra = _extra_axes(seen, m, where) if kw == "L" else None
    if m.tcpm and m9x is None and (written or kw != "L" or extra is not None):
        target = _tcpm_target(kw, seen, extra, normal or m.pending is not None or m.approach is not None
                              or m.comp != "R0", m, where)
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
    return ended


def _retract_and_call(seen: dict[str, Word], mvals: list[float], m: Machine, where: Where, blk: SourceBlock, *,
                      positioned: bool) -> None:
    """After the motion: ``M140 MB`` retracts along the tool axis, ``M99`` calls the cycle, and so
    does every positioning block (an L or LP with coordinates) from ``M89`` on, until ``M99`` or
    ``CYCL CALL`` (TNC 406/306 technical manual, "M-function M89": "for every following
    positioning block there will be a call of the last-programmed machining cycle. M89 is canceled
    by M99 or a CYCL CALL block"; the M89 block itself calls at its end)."""
    if 140 in mvals:
        if "MBMAX" in seen:
            retract = m.pos.copy()
            retract[m.plane] = max(m.context.home[m.plane], m.pos[m.plane])
        elif "MB" in seen:
            retract = m.pos.copy()
            retract[m.plane] += abs(seen["MB"].value) * m.scale
        else:
            retract = None
            m.note("M140 without MB: no retraction")
        if retract is not None and retract[m.plane] != m.pos[m.plane]:
            m.used.add(m.plane)
            m.tcpm_move = True  # along the spindle, also under M128 (the tool axis of a table machine)
            m.emit("rapid", retract, Line(m.pos, retract), math.inf, where, blk.number)
            m.tcpm_move = False
    if 89 in mvals:
        m.modal_call = True
    if 99 in mvals:
        m.modal_call = False
        cycle_call(m, where, blk)
    elif m.modal_call and positioned:
        cycle_call(m, where, blk)


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
    words = _without_m128_feed(words, m)
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
    values: the sum is the DR of the last TOOL CALL. Returns that displacement [mm, machine]."""
    missing = [k for k in ("NX", "NY", "NZ") if k not in seen]
    normal = np.array([seen[k].value for k in ("NX", "NY", "NZ") if k in seen], dtype=float)
    if missing or not np.linalg.norm(normal) > 0:
        where.fail("LN without a surface-normal vector", column=blk.column, text=where.text,
                   expected="LN X.. Y.. Z.. NX.. NY.. NZ.. (a vector of non-zero length)")
    if not m.transform.identity:
        where.fail("LN under a coordinate transformation (cycles 8, 10, 11, 26) is not supported", column=blk.column,
                   text=where.text, expected="LN without mirror, rotation or scaling")
    if "TX" in seen or "TY" in seen or "TZ" in seen:
        m.note("LN TX/TY/TZ: the tool orientation is ignored without M128 (no tilting axes move)")
    return m.tool_delta * normal / np.linalg.norm(normal)


def _extra_axes(seen: dict[str, Word], m: Machine, where: Where) -> np.ndarray | None:
    """End positions ``(a, b, c, u, v, w)`` [deg, mm] of an L block's words of the axes beyond X, Y, Z,
    or None when it has none. ``A+90`` is the position, ``IA+90`` an increment (TNC 640 user's manual,
    "Straight line L": the block may contain "up to 5 axes" including rotary axes); A, B, C in degrees,
    U, V, W in the program's unit; the preset of these axes is the machine's zero (the context's
    work offsets hold X, Y, Z only), so an absolute word is the machine position, as with M91/M92. A
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
    return target


def _tcpm_target(kw: str, seen: dict[str, Word], extra: np.ndarray | None, other: bool, m: Machine,
                 where: Where) -> np.ndarray:
    """The machine end point [mm] of a line under M128 (:mod:`interpolators.heidenhain_tcpm`): the program
    point on the part with every rotary axis at 0, carried where the table holds it. ``other``: the block is
    an LN, or a corner, approach or radius compensation waits for it (errors)."""
    if kw != "L" or other:
        where.fail(f"{'LN, RND/CHF, APPR/DEP or RL/RR' if kw == 'L' else kw} under M128 is not supported",
                   column=1, text=where.text, expected=TCPM_EXPECTED)
    if extra is not None and np.any(np.abs(extra[:3] - m.extra[:3]) > 1e-9):
        where.fail("a rotary axis moving under M128 (simultaneous 5-axis: the tool tip's path) is not supported",
                   column=1, text=where.text, expected=TCPM_EXPECTED)
    kin = m.context.kinematics
    values = {k: seen[k].value * m.scale for k in ("X", "Y", "Z", "IX", "IY", "IZ") if k in seen}
    part, _ = program_target(m, values, part_point(kin, m.extra, m.pos, m.tool_length))
    return machine_point(kin, m.extra, part, m.tool_length)


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
    for run it. Radius compensation and the coordinate transformations act in the working plane only,
    so such an arc under RL/RR or a transformation is an error."""
    target, written = plane_coords(seen, m, where, m9x=m9x)
    p, q = PLANE_AXES[m.plane]
    plane = m.plane
    off = [i for i in written if i not in (p, q)]
    if off:
        w = seen.get("XYZ"[off[0]]) or seen["I" + "XYZ"[off[0]]]
        if len(written) != 2 or m.comp != "R0" or not m.transform.identity:
            where.fail(f"CC coordinate {w.text!r} is not in the working plane", column=w.column, text=w.text,
                       expected=f"CC {'XYZ'[p]} {'XYZ'[q]}, or CC with the tool axis and one other axis (a circle in "
                                "that plane, without RL/RR and coordinate transformations)")
        plane = 3 - sum(written)  # the axis CC does not name is the circle's normal
    m.pole = target
    m.pole_plane = plane if off else None
    m.used.update(written)


def _polar_plane(kw: str, m: Machine, where: Where, blk: SourceBlock) -> int:
    """The plane of an ``LP`` (or ``CTP``) block: the plane of the pole (:func:`_pole`). After ``CC Z.. X..`` (tool
    axis Z) the polar line runs in ZX with the angle from +Z, as the arcs about that pole do: HEIDENHAIN's
    demonstration program 7025 writes ``CC Z+Q4 X+Q7`` / ``LP PR+Q6 PA-90 R0`` / ``CP IPA+Q12 DR+`` (TNC 426
    manual, "Polar coordinates": the pole CC may lie in any of the three main planes, the angle PA
    counted from the plane's reference axis). As for those arcs, R0 and no coordinate transformation."""
    plane = m.pole_plane if m.pole_plane is not None else m.plane
    if plane != m.plane and (m.comp != "R0" or not m.transform.identity):
        what = "a coordinate transformation" if m.comp == "R0" else m.comp
        where.fail(f"{kw} about a CC outside the working plane under {what}",
                   column=blk.column, text=where.text,
                   expected=f"R0 and no cycle 8/10/11/26 for {kw} in another plane")
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
    plane = m.pole_plane if kw in ("C", "CP") and m.pole_plane is not None else m.plane
    if plane != m.plane and (m.comp != "R0" or not m.transform.identity):
        where.fail(f"{kw} about a CC outside the working plane under {m.comp} or a coordinate transformation",
                   column=blk.column, text=where.text,
                   expected="R0 and no cycle 8/10/11/26 for a circle in another plane")
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
            else:
                where.fail("CP without an angle", column=blk.column, text=where.text, expected="PA or IPA")
            return helical_arc(m.pos, m.pole, sweep, plane=plane, axis_end=target[plane])
        if ccw is None:
            where.fail(f"{kw} arc without direction", column=blk.column, text=where.text, expected="DR+ or DR-")
        m.ccw = ccw
        if kw == "C":
            if m.pole is None:
                where.fail("C arc without a circle centre", column=blk.column, text=where.text,
                           expected="a CC block before C")
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

def _free_contour(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
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
            ended = _motion("L", words, m, ew, source) or ended
            continue
        _pole({a: Word("CC" + a, float(v), 1, "CC" + a) for a, v in zip(axes, element.centre)}, m, ew, None)
        words.append(Word("DR", "+" if element.ccw else "-", 1, "DR"))
        ended = _motion("C", words, m, ew, source) or ended
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

def _approach_depart(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
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
    words = _read_words(code, fm.end(), where, m, column0=blk.column)
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


#: What each keyword block does (the flow keywords and motions are handled by :class:`_Run`);
#: a handler returns True when the program ends at the block (M2/M30).
_HANDLERS = {
    "BLK FORM": _ignore,
    "TOOL DEF": _tool_def,
    "TOOL CALL": _tool_call,
    "CYCL DEF": _cycle_def_block,
    "CYCLE DEF": _cycle_def_block,
    "PATTERN DEF": _pattern_def,
    "CYCL CALL": _cycle_call_block,
    "APPR": _approach_depart,
    "DEP": _approach_depart,
    "STOP": _stop_or_m,
    "M": _stop_or_m,
    "RND": _corner_def,
    "CHF": _corner_def,
    "PLANE": _tilt,
    "FUNCTION": _tilt,
    "TRANS": _trans,
    "TCH PROBE": _touch_probe,
    "SPL": _spline_block,
    **{kw: _free_contour for kw in FK_KEYWORDS},
}
