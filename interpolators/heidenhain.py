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
  (with :mod:`interpolators.tilted`: the tilted working plane on a tilting table);
* :mod:`interpolators.heidenhain_tcpm`: ``M128`` / ``FUNCTION TCPM`` on a tilting table (:mod:`interpolators.tcp`);
* :mod:`interpolators.heidenhain_programs`: ``CALL PGM``, ``SEL PGM``, ``CALL SELECTED PGM``;
* :mod:`interpolators.heidenhain_probing`: touch probe cycles ``TCH PROBE 400, 408-413, 417, 419-424, 427, 431`` on
  the nominal workpiece;
* :mod:`interpolators.heidenhain_fk`: FK free contour programming, resolved into ``L`` / ``CC`` + ``C`` blocks;
* :mod:`interpolators.heidenhain_motion`: the motion blocks (``L`` .. ``CP``, ``SPL``, FK, ``APPR`` / ``DEP``), the
  words of a block and its M functions, on :mod:`interpolators.heidenhain_targets` (program words to machine points)
  and :mod:`interpolators.heidenhain_compensation` (``RL`` / ``RR`` runs);
* :mod:`interpolators.heidenhain_cycle_calls`: ``M99``, ``CYCL CALL``, ``CYCL CALL PAT``, ``CYCL CALL POS``; the
  moves of the cycles they run: :mod:`interpolators.heidenhain_cycle_moves` (drilling .. studs, slots, the
  surfaces 230-233, the patterns 220/221) and :mod:`interpolators.heidenhain_sl` (the SL cycles 21-25, their
  contours by cycle 14 or by ``CONTOUR DEF``, :mod:`interpolators.heidenhain_contour_def`).

This module keeps the machine state (:class:`Machine`), the program flow and the blocks' dispatch, tools,
``CYCL DEF``, presets, touch probe blocks and the tilted plane.

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
                                    polar line / arc about CC (helix with a tool-axis word; CP DR+
                                    without PA: a full circle); about a CC naming the tool axis
                                    (CC Z.. X..) in that plane (LP there also under cycles 7-11/26)
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
    L C+180 FMAX M94, M94 C         M94: the rotary display reduced below 360 deg first (heidenhain_motion)
    L C+10 FMAX M126, M127          on an axis that wraps ([axes.c] wrap = true): M126 the shorter way, M127 (and
                                    before M126) the shown angle's difference (interpolators.rotary_wrap)
    M112 T0.01 A10 .. M113          contour tolerance as cycle 32 T (TNC 426/430); M118 X.. Y.., M124 T..:
                                    noted; M120 LA3: look-ahead of RL/RR (the path as without it)
    SPL X.. Y.. Z.. K3X.. K2X.. K1X.. ..
                                    spline: the cubic of each axis, t from 1 to 0 (heidenhain_splines)
    DECLARE STRING QS1 = "A", QS2 = QS1 || TOCHAR(DAT+Q1 DECIMALS2), TOOL CALL QS2, CALL PGM QS3
                                    string parameters (heidenhain_strings)
    FUNCTION FEED DWELL D-TIME0.5 F-TIME5 .. RESET
                                    a dwell after every F-TIME of feed motion (heidenhain_feed_dwell)
    FN 20: WAIT FOR ..              PLC synchronisation: met at once, noted; FN 19/29 PLC, FN 37 EXPORT,
                                    FN 38 SEND, FUNCTION LIFTOFF/S-PULSE/COUNT, FUNCTION PARAXCOMP
                                    DISPLAY/OFF, PARAXMODE OFF: no motion, noted (PARAXCOMP MOVE an error)
    Q12 = 400 % 360, Q7 = SGN Q6    % the division remainder (40); SGN 0 is +1 (heidenhain_formulas)
    L X+20 Z+50 R0 FMAX M130        in a tilted plane: this line in the untilted coordinates (heidenhain_motion)
    L Z-5 F500 M103 F20             M103: the feed down the tool axis at most F percent (until M103 alone)
    CYCL CALL PAT F500 / F MAX      the moves between the pattern's points at F (F MAX: rapid)
    L Z-10 FMAX M91                 M91: coordinates of this block are machine coordinates
    L X+0 M92                       M92: relative to the machine-defined position context.home
    L M140 MB MAX                   retract along the tool axis to context.home's coordinate
                                    (the machine's limit stands in for the software limit switch)
    L M128 ... M129                 TCPM on a tilting table: lines of the tool tip on the turned part,
    FUNCTION TCPM F TCP AXIS POS    their rotary words moving too (chords within the tolerance, F the
      PATHCTRL AXIS .. RESET TCPM   tip's feed on the part: heidenhain_tcpm, tcp); the F right after
                                    M128 is its compensation feed (noted); AXIS SPAT: A B C are
                                    spatial angles, the tool's direction (heidenhain_tcpm.spatial_axes);
                                    in a tilted plane that turns: still lines as the plane's (tncposts38)
    LN X.. Y.. Z.. TX.. TY.. TZ..   the tool orientation alone (peripheral milling): no displacement
                                    under R0; FUNCTION FILECOPY/FILEMOVE/FILEDELETE: no motion, noted
    M2, M30                         end of the main program (subprograms follow)
    FN 0: Q1 = +5, Q2 = SQRT(Q1)    Q parameters (FN 0-8, 13, formulas)
    FN 9: IF +Q1 EQU +0 GOTO LBL 2  conditional jumps (FN 9-12)
    FN 15/16 PRINT, FN 18 SYSREAD ID240/ID270 NR1 IDXn, ID20 NR1, ID50 NR1..NR5 IDXt
                                    prints are noted; SYSREAD of the nominal position (ID240:
                                    machine coordinates; ID270: active coordinates) reads the
                                    simulated position (after a STOP, M0 or M1 with no move
                                    since: where the program stopped, noted; an operator's jog
                                    is not modelled); ID20 NR1: the active tool's number,
                                    NR2 .. NR4 the prepared tool, tool axis, spindle speed;
                                    ID10 NR1 inch = 1; ID50
                                    NR1/NR2 IDXt: L / R of tool t (TOOL DEF, else the tool table);
                                    NR3..NR5 (R2, DL, DR): 0, noted
    LBL 1 ... CALL LBL 1 REP 3      labels, subprograms, section repeats (REPQ5: the count in Q5)
    CYCL DEF 7/9/32/1/2/4/5/17/12/200-209/240/241/251-254/256/257/262-265/267/392
                                    cycles; machining cycles run by M99, CYCL CALL, CYCL CALL PAT or
                                    CYCL CALL POS
    CYCL DEF 7.1 #5, TRANS DATUM TABLE TABLINE 5
                                    datum shift to row 5 of the datum table (context.datum_table)
    CYCL DEF 220/221                polar / Cartesian pattern: the last machining cycle at each position
    PATTERN DEF POS1 (X.. Y.. Z..)  the positions of CYCL CALL PAT; also ROW1, CIRC1, PITCHCIRC1 and the
                                    grids PAT1 / FRAME1 (NUMX x NUMY points, row by row in meander)
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
from collections.abc import Callable
from pathlib import Path

import numpy as np

from interpolators._words import INCH, Where, program_text
from interpolators.context import DEFAULT_CONTEXT, DIALECTS, WORK_OFFSETS, MachineContext
from interpolators.heidenhain_compensation import finish_compensation
from interpolators.heidenhain_contour_def import contour_def
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
    takes_point_angle,
    tapping_cycle,
)
from interpolators.heidenhain_fast import PlainBlocks
from interpolators.heidenhain_feed_dwell import FeedDwell, split_at_times
from interpolators.heidenhain_fk import FK_KEYWORDS, FreeContour
from interpolators.heidenhain_labels import CALL_RE, LABEL_RE, MAX_EXECUTED, MAX_NESTING, Frame, LabelTable, label_key
from interpolators.heidenhain_motion import (
    approach_depart,
    block_end_retract,
    block_words,
    corner_def,
    free_contour,
    is_retract_feed,
    m_functions,
    motion_block,
    spline_block,
)
from interpolators.heidenhain_params import Q_NAME_RE, QParameters, run_function
from interpolators.heidenhain_paths import helical_arc
from interpolators.heidenhain_probing import PROBE_CYCLES, PROBE_RE, probe_run, refuse_probe
from interpolators.heidenhain_programs import CALL_PGM_RE, SEL_PGM_RE, find_program
from interpolators.heidenhain_strings import QS_NAME_RE, StringParameters
from interpolators.heidenhain_surfaces import SURFACE_CYCLES, surface_cycle
from interpolators.heidenhain_tcpm import TCPM_EXPECTED, function_tcpm, tilt_turns
from interpolators.heidenhain_transforms import (
    KINEMATICS_HINT,
    TRANSFORM_CYCLES,
    PlaneBlock,
    TiltedPlane,
    Transform,
    TransformError,
    axial_angles,
    plane_rotation,
    read_plane,
    tilt_block,
    trans_block,
    transform_item,
)
from interpolators.heidenhain_words import SourceBlock, read_value, source_blocks
from interpolators.iso_axes import EXTRA_LETTERS, fill_extra
from interpolators.program import Block, Program, end_at_rest, program_axes
from interpolators.rotary_wrap import default_direction, within_turn, wrapped_end
from interpolators.tcp import part_point
from interpolators.tilted import Solution, TiltError, spatial, tilted_frame
from toolpaths.geometry import Line
from vcnc.core.text import BinaryDataError

__all__ = ["parse_heidenhain", "looks_like_heidenhain", "Machine"]

#: A block's keyword; "FN 0:Q2=5" and "Q1=Q2" (hyperMILL's TNC post) may go on without a blank.
_KEYWORD_RE = re.compile(
    r"(BEGIN\s+PGM|END\s+PGM|BLK\s+FORM|TOOL\s+CALL|TOOL\s+DEF|CYCLE?\s+DEF|CYCL\s+CALL|CALL\s+LBL|CALL\s+PGM"
    r"|CALL\s+SELECTED\s+PGM|SEL\s+PGM|TCH\s*PROBE|PLANE|FUNCTION|TRANS|SPL|DECLARE\s+STRING|QS\d+\s*="
    r"|LBL|FPOL|FSELECT|FCT|FLT|FC|FL|FN\s*\d+\s*:|Q[LR]?\d+\s*=|STOP|APPR|DEP|PATTERN\s+DEF|CONTOUR\s+DEF|RND|CHF|CC|CR|CTP|CT|CP|C|LP|LN|L|M)(?:(?<=[:=])|(?![A-Z]))",
    re.I,
)
_BLANKS_RE = re.compile(r"\s+")
_PLANE_OF_TOOL_AXIS = {"Z": 2, "Y": 1, "X": 0}
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
        # the pole CC [mm]: its machine point, its program coordinates and the frame (frame_key) they were taken in
        self.pole_record: tuple[np.ndarray, np.ndarray, tuple] | None = None
        self.pole_plane: int | None = None  # the plane of a CC naming the tool axis (None: the working plane)
        self.last_axes: list[int] = []
        self.tool_defs: dict[int, tuple[float, float]] = {}
        self.tool_length = 0.0
        self.tool_radius = 0.0
        self.tool_number = 0  # the active tool (FN 18 SYSREAD ID20 NR1); 0: none, or one called by name
        self.tool_called: str | None = None  # the active tool as its TOOL CALL names it (None: no TOOL CALL yet)
        self.prepared_tool = 0  # the tool a TOOL DEF n pre-selected (FN 18 SYSREAD ID20 NR2); 0: none
        self.tool_delta = 0.0  # DR of the last TOOL CALL [mm]: LN's 3-D compensation
        self.point_angle = 0.0  # the called tool's T-ANGLE [deg] (context Tool.point_angle); 0: none
        self.shift = np.zeros(3)
        # the work offset of the context that is the active preset (cycle 247); None: a preset beyond them (zero)
        self.preset: str | None = "G54"
        # preset table rows a touch probe cycle wrote (interpolators.heidenhain_probing): work offset -> value [mm]
        self.presets: dict[str | None, np.ndarray] = {}
        # the datum table (context.datum_table) with the rows a touch probe cycle wrote (Q303=0): row -> X, Y, Z [mm]
        self.datum_rows: dict[int, np.ndarray] = dict(context.datum_table)
        self.transform = Transform()
        self.comp = "R0"
        self.comp_start: int | None = None  # index of the entry block of the running RL/RR run
        self.comp_side = "RL"
        self.comp_radius = 0.0
        self.ccw: bool | None = None
        self.exact_stop = True
        self.tolerance: float | None = None
        self.cycle: DrillCycle | ContourTrain | RoughOut | None = None
        # the 200-series definition the cycle was built from: its number, Q parameters, the cycle built and the
        # tool's radius and point angle then (refresh_cycle rebuilds it when a call finds one of them changed)
        self.cycle_source: tuple[int, dict[int, float], DrillCycle, tuple[float, float]] | None = None
        self.contour: tuple[str, ...] = ()  # cycle 14 or CONTOUR DEF: the labels of the contour
        self.contour_roles: tuple[str, ...] = ()  # CONTOUR DEF: "P" / "I" of each label; cycle 14: () (by RL/RR)
        self.contour_data: dict[int, float] | None = None  # cycle 20: its Q1 .. Q9
        self.cycle_items: dict[int, float | dict[str, float]] = {}
        self.incomplete_cycle: int | None = None  # an old cycle whose CYCL DEF n.0 came, its last line not yet
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
        # FUNCTION TCPM .. AXIS SPAT: the spatial angles A, B, C [deg] last written; None: rotary words are positions
        self.tcpm_spatial: np.ndarray | None = None
        self.retract_feed = math.inf  # the feed of the block's M140 retraction (the F after MB) [mm/s]
        self.fk = FreeContour()  # FK free contour programming (interpolators.heidenhain_fk)
        self.plain: PlainBlocks | None = None  # the shortcut for plain L/CC/C/CR blocks (heidenhain_fast)
        self.per_revolution = False  # M136: F in mm per spindle revolution (until M137)
        self.plunge: float | None = None  # M103 F: the plunging feed as a fraction of F (None: off)
        self.feed_dwell: FeedDwell | None = None  # FUNCTION FEED DWELL (interpolators.heidenhain_feed_dwell)
        self.m112: tuple[bool, float | None] | None = None  # M112: the path mode before it (M113 restores it)
        self.look_ahead = False  # M120 LA>0 in a radius-compensated run
        # M94: machine angle minus shown angle of A B C [deg]; absolute angles are shown ones
        self.rotary_shift = np.zeros(len(EXTRA_LETTERS))
        self.shortest_path = False  # M126 (until M127) on a machine whose rotary axes wrap (interpolators.rotary_wrap)

    @property
    def wrap_rule(self) -> str:
        """The direction of an absolute move of the machine's wrapping rotary axes (:mod:`interpolators.rotary_wrap`):
        the shorter way under ``M126``, else the machine's ``wrap_direction``, else the TNC's own."""
        return "shortest" if self.shortest_path else self.context.wrap_direction or default_direction("heidenhain")

    # --- coordinates -------------------------------------------------------------------------
    @property
    def scale(self) -> float:
        return INCH if self.inch else 1.0

    @property
    def feed_scale(self) -> float:
        return (INCH / 10.0 if self.inch else 1.0) / 60.0

    @property
    def rotary_feed(self) -> float | None:
        """The feed of rotary axes moving with X, Y, Z still [deg/s]: F in degrees/min in mm and inch programs
        alike (iTNC 530 user's manual 60642x-03, 12.5 "Miscellaneous functions for rotary axes", M116, "Standard
        behavior": "The TNC interprets the programmed feed rate of a rotary axis in degrees/min (in mm programs and
        also in inch programs)"), where :attr:`feed` holds F read in the program's unit (1/10 inch/min in INCH)."""
        return None if self.feed is None else self.feed / (self.feed_scale * 60.0)

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

    def frame_key(self) -> tuple:
        """What maps program to machine coordinates now (the transformations, the working plane, program zero):
        equal keys, equal maps."""
        return self.transform, self.plane, tuple(self.origin().tolist())

    @property
    def pole(self) -> np.ndarray | None:
        """The pole ``CC`` in machine coordinates [mm], or None before any. CC sets a point of the part in program
        coordinates: "An absolutely defined circle center or pole is always measured from the workpiece datum" (TNC
        426 / TNC 310 pilot, "Circle Center and Pole: CC"), the datum cycle 7 moves; a pole set before a
        transformation (cycles 7, 8, 10, 11, 26, a PLANE, a preset) or a TOOL CALL (the tool length) keeps its
        program coordinates and is mapped as the next block's points are. Our reading: no manual page found shows
        a CC set before a transformation and used after it; taken as a program point the pole keeps a subprogram
        relocatable, as the manuals' "Coordinate transformation" examples run one contour at several datums, and a
        pole in ZX stays on the part's Z across a tool of another length."""
        if self.pole_record is None:
            return None
        machine, program, frame = self.pole_record
        return machine if frame == self.frame_key() else self.to_machine(program)

    @pole.setter
    def pole(self, machine: np.ndarray) -> None:
        machine = np.array(machine, dtype=float)
        self.pole_record = (machine, self.to_program(machine), self.frame_key())

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

    def lengths(self, where: Where, blk: SourceBlock | None = None, *, what: str = "") -> float:
        """Factor of lengths in the working plane (1 without transformation) [-]; an error at
        ``where`` (at ``blk``'s code when given; naming ``what`` needs the factor: "``what`` under ...")
        when cycle 26 scales the plane's axes differently."""
        if self.transform.identity:
            return 1.0
        try:
            return self.transform.length(self.plane)
        except TransformError as exc:
            message = f"{what} under {exc.message}" if what else exc.message
            column, text = (1, where.text) if blk is None else (blk.column, blk.code)
            where.fail(message, column=column, text=text, expected=exc.expected)

    def active_position(self) -> np.ndarray:
        """The position in the active coordinate system [mm] that ``FN 18 SYSREAD ID270`` reads: the program
        coordinates of the machine position, under M128 / FUNCTION TCPM those of the tool tip on the turned part
        (:func:`interpolators.tcp.part_point`). Our reading: under TCPM the program's X Y Z are the tip's, so a
        position read back and programmed again (``L X+Q1``) stays where it is, as G92 under G43.4 takes the tip."""
        tip = self.tcpm and not tilt_turns(self.tilt)  # in a plane that turns: the plane's point, TCPM or not
        point = part_point(self.context.kinematics, self.extra, self.pos, self.tool_length) if tip else self.pos
        return self.to_program(point)

    def no_radius(self) -> str:
        """For a message on a cycle that needs a tool radius: ``tool 20 has none``, ``tool "MILL_D10" (called by
        name, not in the tool table) has none`` or, before any TOOL CALL, ``no tool was called before it``."""
        return f"{self.tool_called} has none" if self.tool_called else "no tool was called before it"

    def tool_data(self, number: int) -> tuple[float, float] | None:
        """Length and radius [mm] of tool ``number`` as ``TOOL CALL`` takes them (the program's ``TOOL DEF``,
        else the machine context's tool table); None when neither has the tool (TOOL CALL then takes 0, 0)."""
        if number in self.tool_defs:
            return self.tool_defs[number]
        tool = self.context.tool(number)
        return None if tool is None else (tool.length, tool.radius)

    def system_datum(self, ident: int, nr: int) -> float:
        """The machine status ``FN 18 SYSREAD IDi NRj`` reads (iTNC 530 technical manual 07/2013, 9.5.4 "Data
        transfer NC > NC program (FN18: SYSREAD)", and the TNC 426/430 technical manual 12/2001, 7.3.4): ID10
        NR1 mm = 0, inch = 1; ID20 NR2 the prepared tool number (of the last ``TOOL DEF n``: 0 before one, our
        reading), NR3 the active tool axis 0 = X, 1 = Y, 2 = Z, NR4 the programmed spindle speed [rpm] (0 before
        a ``TOOL CALL .. S``, our reading)."""
        return {(10, 1): float(self.inch), (20, 2): float(self.prepared_tool), (20, 3): float(self.plane),
                (20, 4): self.spindle or 0.0}[ident, nr]

    def refresh_cycle(self, where: Where, column: int) -> None:
        """The machining cycle of a 200-series definition with the values its Q parameters hold now.

        The cycle parameters are Q parameters (TNC 640 ISO programming manual 34059x-01, 8.1: "Q200 to
        Q1199: parameters that are primarily used for cycles; they are globally effective"); a definition
        assigns them, and the pattern cycles 220/221 assign their Q200, Q203, Q204, which then "are
        effective" for the machining cycle they call (TNC 320 cycle manual, cycle 220). Our reading: a cycle
        reads its Q parameters when it is called, so an assignment between the definition and a call
        (``Q201=-18`` before the next ``CYCL CALL``, as an iTNC 530 training program in wild set 9 deepens
        its holes for a second drill) is the call's. A feed given as MAX keeps its value (the parameter
        store holds finite values only). The called tool's radius and point angle are the call's too (a
        depth to the drill's full diameter, Q395=1, takes them: :func:`drill_cycle`)."""
        if self.cycle_source is None or self.cycle is not self.cycle_source[2]:
            return
        number, q, _, tool = self.cycle_source
        now = {k: v if math.isinf(v) else self.params.get(f"Q{k}") for k, v in q.items()}
        called = self.drill_tool()
        if now == q and (tool == called or not takes_point_angle(number, q)):
            return
        self.cycle = drill_cycle(number, now, feed_scale=self.feed_scale, scale=self.scale, where=where,
                                 column=column, spindle=self.spindle, tool=called)
        self.cycle_source = (number, now, self.cycle, called)

    def define_drill_cycle(self, number: int, q: dict[int, float], where: Where, column: int) -> None:
        """``CYCL DEF`` of a 200-series machining cycle (:func:`drill_cycle`). A machining cycle is call-active: one
        whose depth takes the tool's point angle (Q395=1, Q343=1) takes the tool called at its call, which may come
        after the definition (``CYCL DEF 200 .. Q395=1`` / ``TOOL CALL 2`` / ``M99``), so it is built with a stand-in
        tool here, its parameters checked, and rebuilt with the called tool at its first call (:meth:`refresh_cycle`).
        Our reading of the TNC 640 cycle manual, "Calling cycles": the cycle is defined, and a CYCL CALL or M99
        runs it."""
        pending = takes_point_angle(number, q)
        tool = (1.0, 90.0) if pending else self.drill_tool()
        self.cycle = drill_cycle(number, q, feed_scale=self.feed_scale, scale=self.scale, where=where, column=column,
                                 spindle=self.spindle, tool=tool)
        self.cycle_source = (number, q, self.cycle, (math.nan, math.nan) if pending else tool)

    def drill_tool(self) -> tuple[float, float]:
        """The called tool's radius [mm] and point angle [deg] (0: none), as :func:`drill_cycle` takes them."""
        return self.tool_radius, self.point_angle

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
        if self.tilt is not None and not (self.tcpm and not tilt_turns(self.tilt)):
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
                                 exact_stop=self.exact_stop, tolerance=self.tolerance, dwell=dwell,
                                 tcp=bool(self.tcpm and self.tcpm_move and extra is not None
                                          and np.any(np.asarray(extra, dtype=float) != self.extra)), **ends))
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
    axes = program_axes(m.used, m.blocks)
    return Program(blocks=tuple(m.blocks), source=source, dialect="heidenhain", axes=axes, name=name, notes=notes,
                   rapid_feed_stop=DIALECTS["heidenhain"].rapid_feed_stop)


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
        self.read_keywords()
        caller, self.m.runner = self.m.runner, self  # cycle 12 runs programs through the running program
        try:
            self.steps()
        finally:
            self.m.runner = caller
        return self.name

    def read_keywords(self) -> None:
        """Every block's keyword, before the first block runs: a block of no TNC language is an error even
        where the flow never takes it (a simulator's tool-change macro jumps over its '##LANGUAGE AC' lines).
        Our reading of the ``ERROR =`` marking: a TNC checks every block when it reads a program in and does
        not run a program holding one it could not read. The program ends at its ``END PGM`` ("The last block
        of a program is identified by END PGM", TNC 640 user's manual, "Program structure"): what a file holds
        after it (a DOS transfer's Ctrl-Z, a '%') is not read, as the run does not read it."""
        for i, blk in enumerate(self.blocks):
            if i not in self.keywords:
                k = _KEYWORD_RE.match(blk.code)
                if k is None:
                    _unknown_block(blk, blk.where(self.source))
                self.keywords[i] = (k, _BLANKS_RE.sub(" ", k.group(1).upper()))
            if self.keywords[i][1] == "END PGM":
                break

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
        words = block_words(blk.code, k.end(), where, m, column0=col0)
        return motion_block(kw, words, m, where, blk)

    def flow(self, kw: str, blk: SourceBlock, where: Where) -> None:
        """LBL (the end of a called subprogram at LBL 0), CALL LBL, FN (jumps)."""
        m, col0 = self.m, blk.column
        if kw.startswith("FN"):
            jump = run_function(blk.code, m.params, where, column=col0, position=m.pos, active=m.active_position(),
                                scale=m.scale, note=m.note, tool=(m.tool_number, m.tool_data), stopped_at=m.stopped_at,
                                tool_write=m.write_tool, system=m.system_datum)
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
#: an ISO block number ``N10`` before the block; an ISO G function (``G1 X10 Y26``: a training program's contour
#: between APPR and DEP written in ISO, which a TNC runs only as a separate DIN/ISO program).
_FOREIGN_LINES = (
    (re.compile(r"\(\s*\$MESSAGE\b", re.I), "'($Message(...))' is a command of the CNC Simulator program",
     "TNC conversational blocks (a message: FN 16 F-PRINT or a ';' comment)"),
    (re.compile(r"\("), "a '(...)' comment is ISO (DIN 66025) syntax", "a comment after ';'"),
    (re.compile(r"N\d+\s", re.I), "the block number {tok} is ISO (DIN 66025) syntax",
     "a TNC block number without N ('12 L X+10')"),
    (re.compile(r"G\d+(?:\.\d+)?(?![\w.])", re.I), "the G function {tok} is ISO (DIN 66025) syntax",
     "a conversational block (L for G0/G1, C or CR for G2/G3)"),
)

#: ``ERROR = L XQ102 + Q9``: the TNC keeps a block it cannot read when a program is read in (a file
#: written elsewhere, transferred or converted), marked ``ERROR =`` before its text, and refuses to run
#: the program until the block is corrected (our reading: the TNC user's manuals we searched do not
#: describe the marking; found in a shop's keyway macro among the wild TNC programs).
_ERROR_BLOCK = re.compile(r"ERROR\s*=", re.I)

#: Blocks of the TNC's language that vcnc does not run, by their first word (TNC 640 user's manual).
_KNOWN_UNSUPPORTED = {
    "SEL": "SEL TABLE / SEL CONTOUR (tables, and the contour formula file with DECLARE CONTOUR and QC1 = ..; "
           "CONTOUR DEF P1 = LBL 1 I2 = LBL 2 .. names contours vcnc runs)",
    "SQL": "SQL (table access)",
    "PRESET": "PRESET (the preset table's functions; CYCL DEF 247 selects a preset)",
    "CONTOUR": "this CONTOUR block (CONTOUR DEF P1 = LBL 1 I2 = LBL 2 .. and CYCL DEF 14 CONTOUR GEOMETRY name "
               "contours vcnc runs)",
    "DECLARE": "this DECLARE block (DECLARE CONTOUR of the contour formula file of SEL CONTOUR; DECLARE STRING and "
               "CONTOUR DEF P1 = LBL 1 I2 = LBL 2 .. are run)",
    "QC": "a contour formula QCn = .. (of the contour formula file of SEL CONTOUR; CONTOUR DEF P1 = LBL 1 "
          "I2 = LBL 2 .. names contours vcnc runs)",
}


def _begin_pgm(blk: SourceBlock, k: re.Match, m: Machine, where: Where) -> str | None:
    """``BEGIN PGM name MM|INCH``: the program's unit, the last word; returns its name, the words
    before it (a file name with blanks, ``BEGIN PGM CHANFRO EXT RETO MM``, as a shop's iTNC 530 saved
    it). A lone ``MM`` or ``INCH`` is the unit of a program without a name (FreeCAD's heidenhain post writes
    ``BEGIN PGM MM``, or ``BEGIN PGM INCH`` with its UNITS INCH: our reading, the unit being the last word)."""
    parts = blk.code[k.end():].split()
    if len(parts) == 1 and parts[0].upper() in ("MM", "INCH"):
        m.note(f"BEGIN PGM {parts[0]} without a program name: {parts[0].upper()} read as the unit")
        m.inch = parts[0].upper() == "INCH"
        return None
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


def _contour_def(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``CONTOUR DEF P1 = LBL 1 I2 = LBL 2 ..`` (:mod:`interpolators.heidenhain_contour_def`): the SL cycles'
    contour, as cycle 14 gives it, with each label's role written."""
    d = contour_def(blk.code[pos:], where, m.params, column0=blk.column + pos)
    m.contour, m.contour_roles = d.labels, d.roles


def _cycle_call_block(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``CYCL CALL``, ``CYCL CALL PAT``, ``CYCL CALL POS``, with M functions; True at M2/M30. An ``M140 MB`` in
    the block retracts after the cycle (M140 is effective at the end of its block, TNC 640 user's manual,
    "Retraction in the tool axis: M140")."""
    pat = re.match(r"\s*(PAT|POS)(?![A-Z])", blk.code[pos:], re.I)
    kind = pat.group(1).upper() if pat else ""
    words = block_words(blk.code, pos + (pat.end() if pat else 0), where, m, column0=blk.column)
    # the positioning words; an F after M140 MB is the retraction's feed, left with the M functions
    positioning = [w.key in ("F", "FMAX", "X", "Y", "Z", "IX", "IY", "IZ") and not is_retract_feed(words, i)
                   for i, w in enumerate(words)]
    moving = [w for w, p in zip(words, positioning) if p]
    if not kind and any(w.key in ("F", "FMAX") for w in moving):
        m.note("CYCL CALL F: no positioning in the block (the cycle runs where the tool is)")
    m_words = [w for w, p in zip(words, positioning) if not p]
    ended = m_functions(m_words, m, where, blk, motion=False, retract=False)
    m.modal_call = False  # a CYCL CALL ends M89
    if kind == "POS":
        position_call(moving, m, where, blk)
    elif kind == "PAT":
        pattern_call(m, where, blk, positioning_feed(moving, m, where))
    else:
        cycle_call(m, where, blk)
    block_end_retract(m_words, m, where, blk)  # M140 at the block's end, after the cycle
    return ended


def _stop_or_m(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> bool:
    """``STOP`` (noted, no motion) or a block of M functions; True at M2/M30."""
    if kw == "STOP":
        m.note("STOP: program stop (no motion)")
        m.stop_in_block = m.at_rest = True
    words = block_words(blk.code, pos if kw == "STOP" else 0, where, m, column0=blk.column)
    return m_functions(words, m, where, blk, motion=False)


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
        if tm.group(1)[0].isdigit():
            m.prepared_tool = int(tm.group(1)[:9])
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
        table = m.context.tool(number)
        if number in m.tool_defs:
            length, radius = m.tool_defs[number]
        elif table is None:
            if number != 0:
                m.note(f"tool {number} is not in the tool table: length and radius 0")
            length = radius = 0.0
        else:
            length, radius = table.length, table.radius
        m.point_angle = table.point_angle if table is not None else 0.0  # the table's: TOOL DEF sets L and R only
        m.tool_length = length + dl
        m.tool_radius = radius + dr
        m.tool_delta = dr
        m.at_rest = m.at_rest or number != m.tool_number
        m.tool_number, m.tool_called = number, f"tool {number}"
    elif named:
        m.tool_length, m.tool_radius, m.tool_delta = dl, dr, dr
        m.tool_number, m.point_angle = 0, 0.0
        m.tool_called = f'tool "{name}" (called by name, not in the tool table)'
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
            m.refresh_cycle(where, blk.column)
            pattern_cycle_run(pattern_cycle(number, q, scale=m.scale, where=where, column=blk.column), m, where,
                               blk)
            return
        m.define_drill_cycle(number, q, where, blk.column)
        return
    if sub in (None, 0):
        if number in LEGACY_CYCLES:
            # a new machining cycle replaces the last from its first line; it is defined by its last line, so
            # until then a call has none (not the one before, our reading: the TNC's editor writes every line)
            m.cycle_items, m.cycle, m.cycle_source, m.cycle_program = {}, None, None, None
            m.incomplete_cycle = number
        return
    if number in TRANSFORM_CYCLES:
        if sub == 1:
            _transform_cycle(number, rest, m, where, col)
        return
    if number == 19:
        _tilt_cycle(rest, m, where, col, blk)
        return
    if number == 7:
        if rest.strip().startswith("#"):
            found = re.fullmatch(r"\s*#\s*(\d+|Q[LR]?\d+)\s*", rest, re.I)
            if found is None:
                where.fail(f"cycle 7: malformed datum table row {rest.strip()!r}", column=col, text=rest.strip(),
                           expected="#n or #Qn, the row of the datum table")
            _datum_table_shift(found.group(1), m, where, col, "cycle 7", rest.strip())
            return
        words = block_words(rest, 0, where, m, column0=col)
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
            m.incomplete_cycle = None
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
        if sub == LEGACY_CYCLES[number]:
            m.incomplete_cycle = None
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
            m.contour, m.contour_roles = contour_labels(rest, where, col), ()
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
    if sets_datum and m.tilt is not None and run.q305 != 0 and run.q303 == 1:
        where.fail(f"TCH PROBE {number} in the tilted plane of {m.tilt.what} writing row {run.q305} of the preset "
                   "table (Q303=1) is not modelled", column=blk.column, text=blk.code,
                   expected="Q305=0 (the active datum) or Q303=0 (the datum table) in a tilted plane, or PLANE RESET "
                            "before the cycle")
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
    holds the datum, active once cycle 247 selects it; Q303=0: row n of the datum table ("Write determined datum
    in the active datum table. The reference system is the active workpiece coordinate system", iTNC 530 cycle
    manual 15.6, Q303), the shift from the preset that puts the probed point at ``origin_to``, active once
    ``CYCL DEF 7.1 #n`` selects it; in a tilted plane, the active workpiece coordinate system of that page, the
    shift is one in the plane's axes from its zero, as cycle 7 shifts there (:func:`_tilt_to`), so that the row
    selected in the same plane puts the probed point at ``origin_to``; Q303=-1 (entered by the TNC in old
    programs, "do not use"): noted."""
    delta = np.where(np.isnan(origin_from), 0.0, origin_from - np.nan_to_num(origin_to))
    if row == 0 and m.tilt is not None:  # the datum set in the tilted plane, the preset kept untilted
        machine = m.to_machine(delta) - m.to_machine(np.zeros(3))
        m.presets[m.preset] = m.preset_value() + m.tilt.rotation @ delta
        m.tilt = dataclasses.replace(m.tilt, datum=m.tilt.datum + machine)
        return
    if row == 0:
        m.presets[m.preset] = m.preset_value() + delta
        return
    if table == 0:
        m.datum_rows[row] = m.shift + delta
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


def _datum_table_shift(name: str, m: Machine, where: Where, column: int, what: str, text: str) -> None:
    """The datum shift to the row ``name`` (a number or a Q parameter) of the datum table, its X, Y and Z
    (:attr:`MachineContext.datum_table`, in mm whatever the program's unit): ``CYCL DEF 7.1 #5`` (TNC 640 cycle
    programming manual, cycle 7 DATUM SHIFT: with datum tables the cycle takes the number of a datum from the
    table) and ``TRANS DATUM TABLE TABLINE 5`` (TNC 640 user's manual, "TRANS DATUM"). TNC7 user's manual
    81762x-17, "Datum table *.d": its X, Y, Z "have the effect of a shift in the workpiece coordinate system
    W-CS", and a datum table must be active to use it, so a row the context's table lacks, or a context without a
    table, is an error naming the row (a TNC without the row stops there too)."""
    row = int(name) if name[0].isdigit() else _whole_number(name, m, where, column, what="datum table row")
    value = m.datum_rows.get(row)
    if value is None:
        held = (f"the datum table has rows {', '.join(map(str, sorted(m.datum_rows)))}"
                if m.datum_rows else "the machine context has no datum table")
        where.fail(f"{what}: row {row} of the datum table is not known ({held})", column=column, text=text,
                   expected="a datum table with that row (vcnc interpolate --datum-table FILE.D, or the machine "
                            "file's [program] datum_table)")
    _datum_shift({axis: value[i] / m.scale for i, axis in enumerate("XYZ")}, m)


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
    dwell time: FUNCTION DWELL"), ``FUNCTION TCPM`` / ``FUNCTION RESET TCPM`` TCPM on and off
    (:func:`interpolators.heidenhain_tcpm.function_tcpm`)."""
    if kw == "FUNCTION" and re.match(r"\s*FEED\s+DWELL\b", blk.code[pos:], re.I):
        _feed_dwell(blk, pos, m, where)
        return
    if kw == "FUNCTION" and re.match(r"\s*(RESET\s+)?TCPM\b", blk.code[pos:], re.I):
        function_tcpm(blk.code[pos:], m, where, column=blk.column + pos)
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
    """Positions of the kinematics' rotary axes (outer, inner; inner 0 without one) [deg]; of an axis the machine
    wraps at 360 deg the one it shows, in [0, 360) (:mod:`interpolators.rotary_wrap`): PLANE's angles are nominal
    positions from there, which :func:`_position_rotary` reaches by the machine's rule."""
    shown = m.extra.copy()
    for a in m.context.wrapped_axes:
        i = EXTRA_LETTERS.index(a.upper())
        shown[i] = within_turn(shown[i] - m.rotary_shift[i])
    return m.context.kinematics.solution_at(shown)


def _wrap_turns(m: Machine) -> dict[str, Callable[[float], float]]:
    """For each kinematics axis the machine wraps at 360 deg, the turn [deg] it makes to an angle it shows, reached
    as :func:`_position_rotary` reaches it (an absolute word by the machine's rule): what
    :meth:`interpolators.tilted.Kinematics.choose` weighs the solutions by (TNC7 user's manual 81762x-17, "Tilting
    solution": "Based on the current position of the rotary axes, choose the possible solution with the shortest
    path"; C shown at 280 and B+30 C+90 or B-30 C-90: C270, 10 deg away under the TNC's own rule, not C90, -190)."""
    def turn(i: int) -> Callable[[float], float]:
        now, shift = float(m.extra[i]), float(m.rotary_shift[i])
        return lambda angle: wrapped_end(angle, now, shift, m.wrap_rule) - now

    return {a: turn(EXTRA_LETTERS.index(a.upper())) for a in m.context.kinematics.names
            if a in m.context.wrapped_axes}


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
        if pb.form == "AXIAL":  # the axes' angles as written, not a solution for the plane
            angles = axial_angles(pb, kinematics=kin, current=current)
        else:
            angles = None if rotation is None else kin.choose(rotation, current, sequence=pb.sequence,
                                                              table_rot=pb.table_rot, turns=_wrap_turns(m))
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
        i = EXTRA_LETTERS.index(name.upper())
        # an axis that wraps at 360 deg reaches the angle as an absolute word of it (C shown at 10, PLANE needs
        # C+90: +80 deg; our reading: the manuals name no other rule for PLANE's positioning)
        wraps = name in m.context.wrapped_axes
        extra[i] = wrapped_end(value, float(m.extra[i]), float(m.rotary_shift[i]), m.wrap_rule) if wraps else value
        m.used.add(3 + i)
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


#: ``TRANS DATUM TABLE TABLINE 5`` (``TABLINE Q5``), optionally with the table's file ``TABLE "TNC:\\ZS.D"``.
_TRANS_TABLE_RE = re.compile(r'\s*DATUM\s+TABLE\s+(?:TABLE\s*("[^"]*")\s*)?TABLINE\s*(\d+|Q[LR]?\d+)\s*$', re.I)


def _trans(kw: str, blk: SourceBlock, pos: int, m: Machine, where: Where) -> None:
    """``TRANS DATUM|MIRROR|ROTATION|SCALE``: the transformations of cycles 7, 8, 10, 11."""
    col = blk.column + pos
    table = _TRANS_TABLE_RE.match(blk.code, pos)
    if table is not None:
        if table.group(1) is not None:
            where.fail(f"TRANS DATUM TABLE with its own table {table.group(1)!r}", column=col,
                       text=blk.code[pos:].strip(),
                       expected="TRANS DATUM TABLE TABLINE n of the machine context's datum table (vcnc interpolate "
                                "--datum-table FILE.D, or the machine file's [program] datum_table)")
        _datum_table_shift(table.group(2), m, where, col, "TRANS DATUM TABLE", blk.code[pos:].strip())
        return
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
        if what != "cycle 10" or m.pending is not None or m.approach is not None:
            where.fail(f"{what} while radius compensation {m.comp} is active", column=col, text=text.strip(),
                       expected="R0 before a coordinate transformation (only cycle 10 cancels RL/RR on its own)")
        # iTNC 530 / TNC 640 cycle programming manuals, ROTATION (cycle 10): "An active radius compensation is
        # canceled by defining Cycle 10 and must therefore be reprogrammed, if necessary": the run ends where its
        # last element's tool centre ends (a proton-therapy workshop's TNC program writer turns its wings so)
        m.note(f"cycle 10 cancels radius compensation {m.comp} (line {where.line}); the next RL/RR starts anew")
        finish_compensation(m, open_end=True)
    m.transform = t


#: A word of ``CYCL DEF 19.1``: an angle, the feed or the set-up clearance, each followed by its value.
_TILT_WORD = re.compile(r"\s*(ABST|[ABCF])(?=\s*[+-]?\s*[\d.Q(])", re.I)


def _tilt_cycle(rest: str, m: Machine, where: Where, col: int, blk: SourceBlock) -> None:
    """``CYCL DEF 19.1 A.. B.. C.. [F..] [ABST..]``: cycle 19 WORKING PLANE (TNC 640 cycle programming
    manual, "WORKING PLANE (Cycle 19, software option)"). Without angles, or with all 0, it cancels the
    tilt (no motion). Other angles need the machine's kinematics; they are spatial angles (as PLANE
    SPATIAL: "the function corresponds to Cycle 19, if the entries in Cycle 19 are set to space angles",
    iTNC 530 user's manual, PLANE SPATIAL). Without F the program positions the rotary axes itself (the
    manual's "manual positioning": ``L B+Q121 C+Q122 R0 F..`` before or after the cycle): as PLANE .. STAY.
    With F the control positions them (the cycle's "Feed rate? F=" and "Set-up clearance?" ABST, asked on
    machines that position the rotary axes automatically): as PLANE .. MOVE DIST<ABST> F<F>, the point ABST
    ahead of the tool tip keeping its place on the part (our reading of the cycle's set-up clearance)."""
    angles: dict[str, float] = {}
    auto: dict[str, float] = {}
    pos = 0
    while rest[pos:].strip():
        wm = _TILT_WORD.match(rest, pos)
        if wm is None:  # a word the cycle has not (F MAX, MB): named here, not as the next move's error
            at = len(rest) - len(rest[pos:].lstrip())
            where.fail(f"{rest[at:].split()[0]!r} is no word of CYCL DEF 19.1", column=col + at,
                       text=rest[at:].split()[0], expected="CYCL DEF 19.1 A.. B.. C.. [F<feed>] [ABST<clearance>]")
        word = wm.group(1).upper()
        value, pos = read_value(rest, wm.end(), where, m.params, what=word, column0=col)
        (angles if word in "ABC" else auto)[word] = value
        if word == "F" and not value > 0:
            where.fail("cycle 19: the feed F of the rotary axes must be > 0", column=col + wm.start(1),
                       text=rest[wm.start(1):pos].strip(), expected="F > 0 [mm/min] (the cycle's 'Feed rate? F=')")
    tilted = any(v != 0.0 for v in angles.values())
    kin = m.context.kinematics
    if kin is None:
        if tilted:
            where.fail("cycle 19 WORKING PLANE (a tilted working plane) is not supported without the machine's "
                       "kinematics", column=col, text=rest.strip(), expected=KINEMATICS_HINT)
        m.note("CYCL DEF 19 with angles 0: no tilted working plane (no motion)")
        return
    current = _rotary_now(m)
    rotation, solution = None, Solution(0.0, 0.0)
    if tilted or "F" in auto:
        try:
            kin.require_table()
            if tilted:
                rotation = spatial(angles.get("A", 0.0), angles.get("B", 0.0), angles.get("C", 0.0))
                solution = kin.choose(rotation, current, turns=_wrap_turns(m))
        except TiltError as exc:
            where.fail(f"cycle 19: {exc.message}", column=col, text=rest.strip(), expected=exc.expected)
    if tilted:
        _tilt_to(rotation, solution, f"CYCL DEF 19 (line {where.line})", m, where, col)
    else:
        _untilt(m)
        m.note("CYCL DEF 19 without angles: the tilted working plane is cancelled"
               + (" (the rotary axes turn to 0 at its F)" if "F" in auto else " (no motion)"))
    if "F" in auto:
        pb = PlaneBlock(form="SPATIAL", values={}, positioning="MOVE", dist=auto.get("ABST", 0.0), feed=auto["F"])
        _position_rotary(pb, current, solution, m, where, blk)


#: What each keyword block does (the flow keywords and motions are handled by :class:`_Run`);
#: a handler returns True when the program ends at the block (M2/M30).
_HANDLERS = {
    "BLK FORM": _ignore,
    "TOOL DEF": _tool_def,
    "TOOL CALL": _tool_call,
    "CYCL DEF": _cycle_def_block,
    "CYCLE DEF": _cycle_def_block,
    "PATTERN DEF": _pattern_def,
    "CONTOUR DEF": _contour_def,
    "CYCL CALL": _cycle_call_block,
    "APPR": approach_depart,
    "DEP": approach_depart,
    "STOP": _stop_or_m,
    "M": _stop_or_m,
    "RND": corner_def,
    "CHF": corner_def,
    "PLANE": _tilt,
    "FUNCTION": _tilt,
    "TRANS": _trans,
    "TCH PROBE": _touch_probe,
    "SPL": spline_block,
    **{kw: free_contour for kw in FK_KEYWORDS},
}
