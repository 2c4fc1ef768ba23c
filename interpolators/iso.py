"""Reader of ISO 6983 G-code as LinuxCNC, Fanuc and Haas controls run it.

Semantics follow the LinuxCNC G-code reference (https://linuxcnc.org/docs/html/gcode/g-code.html,
https://linuxcnc.org/docs/html/gcode/m-code.html, and for coordinates
https://linuxcnc.org/docs/html/gcode/coordinates.html); where Fanuc/Haas differ the
:class:`interpolators.context.Dialect` says how (unit of ``G04 P``).

Coordinates. Blocks carry **machine coordinates** [mm]: the programmed value plus the active work
offset (G54-G59.3 from the machine's table), the G92 offset and the tool length offset (G43/G44
with H, along Z). A program starts at the machine's home position. G53 takes the block's axis words
as machine coordinates; G28/G30 go through the programmed intermediate point to the home / second
reference position (only the axes named move; no words: all axes); G28.1/G30.1 store the current
position as the reference; G10 L2/L20 set a work offset.

Accepted words and codes (case-insensitive; spaces inside words allowed):

========================= =======================================================================
``G0 G1 G2 G3``           rapid, feed, clockwise / counter-clockwise arc; alone on a line they set
                          the motion mode only
``G5 G5.1``               cubic / quadratic spline in XY (I J, P Q control offsets), run as chords
                          within 1 um (:mod:`interpolators.iso_splines`)
``G5.2 G5.3``             LinuxCNC NURBS block (control points X Y P, order L), run as chords within 1 um
                          (:mod:`interpolators.iso_nurbs`)
``G33 G33.1``             spindle-synchronised feed (K x S) and rigid tapping (there and back)
``@ ^``                   LinuxCNC polar distance and angle instead of X Y (:mod:`interpolators.iso_polar`)
``G4``                    dwell ``P`` (seconds under LinuxCNC/grbl, milliseconds under Fanuc/Haas)
                          or ``X`` [s]
``G17 G18 G19``           arc plane; ``G20 G21`` inch / mm (a program with neither runs in the
                          dialect's default unit, with a note); ``G90 G91`` absolute / incremental
``G90.1 G91.1``           arc centre I J K absolute / incremental (default)
``G61 G61.1 G64``         exact stop; continuous path with ``P`` tolerance (``Q``, LinuxCNC 2.10's planner
                          selection ``R`` noted). A program
                          with neither runs in the dialect's default (continuous path)
``G73 G81-G86 G89 G80``   drilling cycles with R, Q, P, L/K and G98/G99 (:mod:`interpolators.iso_cycles`);
                          ``G74`` left-hand tapping as G84 (spindle M4)
``G40 G41 G42``           cutter radius compensation (D from the tool table, G41.1/G42.1 D diameter),
                          LinuxCNC's entry/exit and corner rules (:mod:`interpolators.compensation`)
``G43 G43.1 G44 G49``     tool length offset from the tool table (H, default the current tool);
``G43.2``                 LinuxCNC: H or axis words added to the offsets in effect
``G54``-``G59.3``         work offsets; ``G92 G92.1 G92.2 G92.3``, ``G52``; ``G53``; ``G28 G30 G28.1 G30.1``
                          (Fanuc ``G54.1 P``, Haas ``G154 P``/``G110``-``G129``, their ``G10 L20``:
                          :mod:`interpolators.iso_offsets`)
``G93 G94 G95``           inverse time (F: the block takes 1/F minutes; an F on every feed block),
                          feed per minute (which resets the feed: an F must follow) and feed per
                          revolution (F [mm/rev] at the spindle speed S: F x S per minute; switching
                          to or from it resets the feed; a feed move with the spindle stopped or S0
                          is an error)
``T M6``                  tool select / change (no motion; the tool's length applies with G43; the path halts)
``S M3 M4 M5 M7 M8 M9``   spindle and coolant (noted); ``M0 M1 M60`` program stops (noted; M0 and M60
                          halt the path, M1 not: ``_AT_REST``); ``M2 M30`` end (later lines are not
                          read); other M codes below 100 are noted
========================= =======================================================================

Fanuc and Haas mills (``fanuc`` and ``haas`` dialects only; LinuxCNC keeps its meanings and errors):

========================= =======================================================================
``G187 G103 G05.1 G08``   look-ahead and smoothing, noted; ``G187 E`` sets the path tolerance
``G05 P10000``            (:mod:`interpolators.iso_smoothing`)
``G68 G69``               coordinate rotation; ``G51 G50`` scaling; ``G51.1 G50.1`` mirror image,
                          Haas ``G101 G100`` (:mod:`interpolators.iso_transforms`)
``G68.2 G53.1``           tilted working plane X Y Z I J K (Euler, P0; P1 one roll/pitch/yaw angle) and the rotary
                          axes turned to it, on a machine with a tilting table (``MachineContext.kinematics``;
                          :mod:`interpolators.iso_tilt`)
``G43.4 G43.5 G234``      tool centre point control (Fanuc, Haas): X Y Z the tool tip on the part the tilting table
                          carries, rotary words (G43.5: the tool direction I J K) moving with it, G49 ends it
                          (:mod:`interpolators.iso_tcp`, :mod:`interpolators.tcp`)
``G74 G76 G87``           counter tapping, fine boring, back boring (Haas: ``G77``); Haas G73/G83
                          pecks from I J K (:mod:`interpolators.iso_cycles`)
``G70 G71 G72 G12 G13``   Haas only: bolt-hole circle, arc, line with the active cycle; circular
                          pocket milling (:mod:`interpolators.iso_haas`)
``G09 G29 G60``           exact stop for one block; back through the last G28/G30 intermediate point;
                          single direction positioning as a rapid (overrun not modelled, noted)
``G27 G22 G23``           Fanuc only: rapid and reference position check (noted); stroke check
                          (noted) (:mod:`interpolators.iso_reference`)
========================= =======================================================================

grbl (``grbl`` dialect only): ``$`` system-command lines (reports, settings) and the ``?`` status
query a grbl sender streams with the G-code are not run, with a note; ``$H`` homing, ``$J=`` jog,
``$C`` check mode, ``$RST=`` are errors naming them (:mod:`interpolators.iso_grbl`). Under grbl,
Fanuc and Haas the motion mode at power-on is G00: axis words before any motion code are a rapid
(LinuxCNC starts in G80, where they are an error). The directive lines of the CNCSimulator Pro school
simulator (``$AddRegPart ..``, ``$Inches``, ``#region``) are not run, with a note (:mod:`interpolators.iso_simulator`).

Parameters, expressions and O-word control flow: :mod:`interpolators.iso_params` and
:mod:`interpolators.iso_flow` (LinuxCNC semantics; Fanuc ``M98``/``M99`` subprograms in the same
file). Rotary axes A B C [deg] and secondary linear axes U V W [mm] on a machine that has them
(``MachineContext.extra_axes``): G0/G1/G2/G3 (an arc with such a word moves the axis in proportion,
as LinuxCNC does), G90/G91, G53, G28/G30, G92/G10 offsets, G93 (:mod:`interpolators.iso_axes`).
Out of scope, each an error naming the feature: an axis the machine lacks (a word that keeps the
axis at 0, ``A0``, is accepted with a note), A B C U V W words in cycles, splines, dwells and under
cutter compensation,
probing G38.x, threading G76, lathe codes (G7/G8, G70-G72, G75; in the Fanuc/Haas dialects
the mill codes above), NURBS G5.2 (Fanuc, Haas), polar G16 (LinuxCNC, Haas; Fanuc G16 under G90 and G17 runs as
``@ ^``), scaling G51 and rotation G68 (LinuxCNC), manual-retract
boring G88 (and Haas G87), user M codes M100-M199 whose file is not in the dialect's ``user_m_path``.

LinuxCNC's active comments ``(MSG, ..)``, ``(DEBUG, ..)``, ``(PRINT, ..)``, ``(LOG, ..)`` become
``Program.messages`` under the ``linuxcnc`` dialect (:mod:`interpolators.iso_messages`).
Fanuc ``G65`` macro calls: :mod:`interpolators.iso_flow`; Fanuc/Haas macro B ``IF``/``GOTO``/
``WHILE``: :mod:`interpolators.iso_macro`; system parameters (``#5021``.., read from this
reader's state): :mod:`interpolators.iso_system`.

This module keeps the reader's state (:class:`State`), the line loop (:func:`parse_iso`) and the dispatch of a
block's words by modal group; the blocks themselves, by concern: :mod:`interpolators.iso_codes` (the tables of G
and M codes), :mod:`interpolators.iso_text` (the text before the run, the notes around it),
:mod:`interpolators.iso_motion` (end points, G0-G3 and their feeds, G33, G5, G5.2, G4) and
:mod:`interpolators.iso_arcs`, :mod:`interpolators.iso_compensation` (G40-G42, G39),
:mod:`interpolators.iso_offsets` (G10, G52, G43/G44/G49), :mod:`interpolators.iso_home` (G28/G30, G27/G29/G60,
grbl ``$H``), :mod:`interpolators.iso_mcodes` (M codes), :mod:`interpolators.iso_frames` (G68, G51, G51.1,
G68.2/G53.1), :mod:`interpolators.iso_tcp` (G43.4, G43.5, G234) and :mod:`interpolators.iso_cycle_blocks` (canned-cycle
blocks, Haas patterns and pocket).
"""

from __future__ import annotations

import collections
import dataclasses
import functools
import re

import numpy as np

from interpolators._words import INCH, Where, lines_of
from interpolators.context import DEFAULT_CONTEXT, WORK_OFFSETS, MachineContext, Tool
from interpolators.iso_arc3d import ARC3D_CODES, arc3d_interrupted, unfinished_arc3d
from interpolators.iso_arcs import off_plane
from interpolators.iso_axes import EXTRA_LETTERS, ROTARY_LETTERS, fill_extra, refuse_wrapped_offset, word_values
from interpolators.iso_codes import (
    DIALECT_G,
    G_CODES,
    G_UNSUPPORTED,
    HURCO_BNC_HINT,
    LAST_ONE_VALID,
    LINUXCNC_ALLOCATED_G,
    LINUXCNC_G,
    LINUXCNC_UNDEFINED,
    MILL_G,
    NORMAL_DIRECTION,
    PLANE_CODES,
    PLANE_OF,
    UNITS_HINT,
)
from interpolators.iso_compensation import (
    cutter_compensation,
    finish_compensation,
    g39,
    rereads_position,
    tool_change_under_compensation,
)
from interpolators.iso_corners import PendingCorner, corner_after_block, corner_not_followed, corner_word
from interpolators.iso_cycle_blocks import cycle_block, pattern_or_pocket
from interpolators.iso_cycles import CycleWords
from interpolators.iso_decimal import decimal_point_note, decimal_point_words
from interpolators.iso_dwo import carry_work_zero, dwo_switch
from interpolators.iso_fadal import core_context, fadal_lines, fadal_text
from interpolators.iso_fanuc_nurbs import NurbsCurve, g062_block, unfinished_g062
from interpolators.iso_fast import PlainMoves
from interpolators.iso_flow import run
from interpolators.iso_frames import check_rotated, g68, g68_2_g53_1, scaling_mirror, set_frame
from interpolators.iso_grbl import unsupported_codes, value_limits
from interpolators.iso_home import grbl_homing, mill_positioning, reference_return
from interpolators.iso_mcodes import (
    HAAS_OWN_M,
    OVERRIDES_AT_START,
    io_words,
    m_codes,
    planner_word,
    printer_hint,
    smartcool_hint,
    spindle_select,
    user_m_file,
)
from interpolators.iso_modal_call import ModalCalls
from interpolators.iso_modal_state import ModalStates
from interpolators.iso_motion import (
    block_target,
    check_polar,
    dwell_block,
    fanuc_polar,
    linuxcnc_modal_axis_words,
    motion_block,
    move_feed,
)
from interpolators.iso_offsets import (
    P_SELECT_CODES,
    g10,
    g54_takes_p,
    h_alone,
    length_cancelled,
    length_compensation,
    length_moves_now,
    length_travel,
    local_offset,
    reference_p,
    selected_offset,
)
from interpolators.iso_params import Parameters
from interpolators.iso_polar import POLAR_LETTERS, PolarError
from interpolators.iso_position_offset import POSITION_OFFSET_CODES, offset_travel
from interpolators.iso_reference import FANUC_CODES
from interpolators.iso_rigid_tap import end_rigid_tap, m29_in_tapping_cycle, rigid_tap_moved
from interpolators.iso_smoothing import SMOOTHING_CODES, smoothing
from interpolators.iso_system import (
    named_state_parameter,
    set_reference_parameter,
    set_system_parameter,
    set_work_offset_parameter,
    system_parameter,
    take_written_offsets,
)
from interpolators.iso_tcp import tcp_block, tcp_switch, tip_point
from interpolators.iso_text import (
    closing_notes,
    ends_with_m99,
    expression_notes,
    line_notes,
    message_stops,
    note_comment,
    prepared_text,
    program_name,
)
from interpolators.iso_transforms import Frame, mirror_forbids
from interpolators.iso_words import Word, WordError, fail_words, offset_number
from interpolators.program import Block, Message, Program, end_at_rest, program_axes

__all__ = ["parse_iso"]


#: Motion mode (round(10 * G)) at power-on, by dialect: G00 on grbl (gnea/grbl ``gcode.c`` ``gc_init``
#: zeroes the parser state, and ``MOTION_MODE_SEEK`` 0 is G0), on Fanuc mills (parameter 3402#0 G01 = 0,
#: its default: G00 at power-on and reset) and on Haas mills (G00 is group 01's default in the Haas mill
#: operator's manual), so that axis words before any motion code are a rapid. LinuxCNC starts in G80
#: (``rs274ngc_pre.cc`` ``init``: ``motion_mode = G_80``): there they are an error.
_POWER_ON_MOTION = {"grbl": 0, "fanuc": 0, "haas": 0}


#: M codes after which the machine is at rest (:func:`interpolators.program.end_at_rest`): the program stop M0,
#: the pallet change stop M60, the tool change M6. M1 stops only with the control's optional stop switch on, which
#: the virtual machine's is not (LinuxCNC M-codes "M1": "if the optional stop switch is on"; Fanuc M01 likewise).
_AT_REST = (0.0, 60.0, 6.0)


class Notes:
    """What a run ignored or assumed, counted: ``Program.notes`` lines."""

    def __init__(self) -> None:
        self.counts: collections.Counter[str] = collections.Counter()

    def add(self, what: str) -> None:
        self.counts[what] += 1

    def lines(self) -> tuple[str, ...]:
        return tuple(f"{k} x{v}" if v > 1 else k for k, v in self.counts.items())


@dataclasses.dataclass
class State:
    """Modal state of the interpreter (positions are machine coordinates [mm])."""

    context: MachineContext
    pos: np.ndarray
    motion: int | None = None  # round(10 * G) of the modal motion
    after_g80: bool = False  # G80 the last motion code (LinuxCNC has no motion mode then)
    plane: int = 2
    fanuc_polar: bool = False  # Fanuc G16: X Y of motion blocks are radius and angle
    inch: bool = False
    units_stated: bool = False
    incremental: bool = False
    arc_incremental: bool = True
    exact_stop: bool = False
    tolerance: float | None = None
    feed: float | None = None  # mm/s
    feed_rotary: float | None = None  # the same F word as deg/s, for pure rotary moves (never scaled by G20)
    # the axes beyond X Y Z: a, b, c [deg], u, v, w [mm] (machine), their G92 and work offsets
    extra: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(6))
    extra_used: bool = False  # an A-W word moved (or set) an axis: every block carries their positions
    home_extra: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(6))  # G28 reference [deg, mm]
    reference2_extra: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(6))  # G30's
    g92_extra: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(6))
    g92_extra_saved: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(6))
    extra_offsets: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)  # set by G10 (table: 0)
    inverse_time: bool = False  # G93: F is 1/minutes for the block (the block's F, not modal)
    block_f: float | None = None  # the F word of the block being run [1/min under G93]
    inverse_rate: float | None = None  # LinuxCNC's feed rate after a G93 move: its length x F [units/min]
    zero_words_dropped: bool = False  # the block's words of axes the machine lacks, all at 0, were left out
    feed_reset: bool = False  # G94 after G93 cleared the feed (LinuxCNC convert_feed_mode)
    feed_zero: bool = False  # the last F word was F0 (a zero feed rate: no feed move until the next F)
    per_rev: bool = False  # G95: F is per spindle revolution [mm/rev], the feed F x S
    feed_per_rev: float | None = None  # the F word under G95 [mm/rev]
    feed_per_rev_word: float | None = None  # the same F as written [deg/rev for a pure rotary move]
    subprogram: bool = False  # the file's last block has M99 (a subprogram file, run alone)
    uncalled_feed: str | None = None  # an F of an M98 line LinuxCNC does not execute, before any feed
    initial_feed_line: int | None = None  # the line whose feed move took the dialect's initial feed
    spline_pq: np.ndarray | None = None  # P Q offset of the last G5 block [mm], for the next one's tangent
    nurbs: list[tuple[np.ndarray, float]] | None = None  # G5.2 control points [mm, machine] and weights
    nurbs_order: int = 3  # G5.2 L
    wcs: str = "G54"
    g92: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))
    g92_saved: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))
    g92_applied: bool = False  # LinuxCNC #5210: G92/G52/G92.3 set it, G92.1/G92.2 clear it
    local: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))  # Fanuc/Haas G52's part of g92
    external: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))  # Fanuc G10 L2 P0's part of g92
    external_extra: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(6))  # its part of g92_extra
    tool_length: float = 0.0  # along Z [mm]
    length_pending: float = 0.0  # a tool length change not yet travelled along Z [mm] (Dialect.length_offset_motion)
    tool_xy: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(2))  # the tool's X Y offsets [mm]
    tool_selected: int | None = None
    tool_current: int | None = None
    tool_offsets: dict[int, int] = dataclasses.field(default_factory=dict)  # Fagor T<tool>.<offset>: its offset
    length_code: float = 49.0  # the group 8 G code in effect (43, 43.1, 44, 49: Fanuc #4008)
    length_number: int = 0  # the H number of the length offset in effect (Fanuc #4111)
    comp_number: int = 0  # the D number of the cutter compensation in effect (Fanuc #4107)
    home: np.ndarray | None = None
    reference2: np.ndarray | None = None
    # the last G28/G30 intermediate point [mm, program], NaN on an axis none named: Fanuc/Haas G29's
    intermediate: np.ndarray = dataclasses.field(default_factory=lambda: np.full(3, np.nan))
    offsets: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)
    # G99; LinuxCNC starts in G99 (interp_setup.cc: retract_mode(RETRACT_MODE::R_PLANE)), Fanuc/Haas in G98
    retract_r: bool = False
    cycle: CycleWords = dataclasses.field(default_factory=CycleWords)
    comp_side: str | None = None  # "left" (G41) / "right" (G42) while compensation is on
    comp_radius: float = 0.0
    comp_run_side: str = "left"  # side of the run being compensated (kept after G40 clears comp_side)
    comp_plane: int = 2  # plane of that run (kept after G40: the plane may change before the exit move)
    comp_code: str = ""
    comp_start: int | None = None  # index of the run's first block
    comp_close_at: int | None = None  # number of blocks when G40 came: the next motion is the exit
    comp_centers: dict[int, np.ndarray] = dataclasses.field(default_factory=dict)  # programmed arc centres
    comp_rounded: set[int] = dataclasses.field(default_factory=set)  # G39: number of blocks when it came
    arc_center: np.ndarray | None = None  # programmed centre (start + I/J/K) of the last arc read [mm]

    rotations: dict[str, float] = dataclasses.field(default_factory=dict)  # G10 R per work offset [deg]
    frame: Frame | None = None  # Fanuc/Haas G51.1 mirror, G51 scaling, G68 rotation of the program coordinates
    stopped: bool = False  # a program stop (M0/M1/M60) and no move since: the position may have been jogged
    stop_line: int = 0  # the line of that stop
    stops_read: set[int] = dataclasses.field(default_factory=set)  # lines of the stops a position was read after
    tools: dict[int, Tool] = dataclasses.field(default_factory=dict)  # tool table entries G10 L1/L10/L11 wrote
    spindle_speed: float = 0.0  # S [rev/min]
    spindle_turning: bool = False  # M3/M4 on, M5 (and M2/M30, M19) off
    spindle_ccw: bool = False  # the last start was M4
    mist: bool = False  # M7 on, M9 (and M2/M30) off (LinuxCNC #<_mist>)
    flood: bool = False  # M8 on, M9 (and M2/M30) off (LinuxCNC #<_flood>)
    overrides: dict[str, bool] = dataclasses.field(default_factory=lambda: dict(OVERRIDES_AT_START))  # M48-M53
    written_offsets: dict[str, dict[int, float]] = dataclasses.field(default_factory=dict)  # LinuxCNC #5221 .. #5390
    rigid_tap: bool = False  # Fanuc M29 S.. until its tapping cycle ends: the G84/G74 turns it (iso_rigid_tap)
    rigid_tap_at: Where | None = None  # the M29 block while no G84/G74 has come since (iso_rigid_tap)
    rigid_tap_s: float = 0.0  # the S [rev/min] of the rigid tap that ran (iso_rigid_tap)
    corner_word: Word | None = None  # the block's Fanuc/Haas ,R / ,C word, until its move takes it
    corner: PendingCorner | None = None  # a ,R / ,C waiting for the next move (interpolators.iso_corners)
    modal_calls: ModalCalls | None = None  # Fanuc G66/G66.1 in force (interpolators.iso_modal_call), fanuc only
    parts_counters: dict[int, float] = dataclasses.field(default_factory=dict)  # Fanuc/Haas #3901, #3902 as set
    parts_read: bool = False  # the program read #3901/#3902 (a note)
    input_result: float | None = 0.0  # LinuxCNC #5399, the result of the last M66 (0 until one runs)
    input_unknown: str = ""  # why #5399 cannot be known, when input_result is None
    corner_fresh: bool = False  # the corner was set by the block just run
    decimal_noted: bool = False  # the note on a Fanuc number without a decimal point is given
    parameter_input: bool = False  # Fanuc G10 L50 .. G11: the lines are parameter data
    modal_states: ModalStates = dataclasses.field(default_factory=ModalStates)  # LinuxCNC M70-M73
    tcp: int = 0  # round(10 x G) of Fanuc G43.4 / G43.5, Haas G234 tool centre point control, 0 off (iso_tcp)
    dwo: np.ndarray | None = None  # Haas G254: the shift of the work zero the table carried [mm] (iso_dwo)
    # a Fadal program (read under Fanuc's rules): its G73/G83 take Haas's I J K (Autodesk's Fusion Fadal post,
    # fadal.cps "chip-breaking", "deep-drilling", writes the same G83 .. I.. J.. K.. as its Haas post; our
    # reading, the Fadal manual's cycle section was not found), K no repeat count (Fadal repeats with L)
    fadal: bool = False
    arc3d_mid: np.ndarray | None = None  # Fanuc G02.4/G03.4: the intermediate point read [mm] (iso_arc3d)
    g062: NurbsCurve | None = None  # Fanuc G06.2: the NURBS being read (iso_fanuc_nurbs)
    arc3d_line: int = 0  # its line
    lathe_marks: dict[str, tuple[str | None, int]] = dataclasses.field(default_factory=dict)  # Fanuc/Haas lathe
    # codes seen: their file and line

    def tool(self, number: int) -> Tool | None:
        """The tool table's entry for ``number``: as the program wrote it (G10 L1), else the machine's."""
        return self.tools.get(int(number)) or self.context.tool(number)

    @property
    def scale(self) -> float:
        return INCH if self.inch else 1.0

    @property
    def rotation(self) -> float:
        """Rotation of the active coordinate system about Z (G10 L2 R) [deg]."""
        return self.rotations.get(self.wcs, 0.0)

    def _rotated_parts(self) -> tuple[np.ndarray, np.ndarray, float, float]:
        off = self.offset()
        base = off - self.g92 - np.array([0.0, 0.0, self.tool_length])
        a = np.radians(self.rotation)
        return off, base, float(np.cos(a)), float(np.sin(a))

    def turned(self, vector: np.ndarray) -> np.ndarray:
        """A program-coordinate vector [mm] (an offset such as G5's I J) turned about Z by the G10 R rotation into
        the machine's axes, as :meth:`to_machine` turns the points (G68 left out)."""
        _, _, c, s = self._rotated_parts()
        v = np.asarray(vector, dtype=float)
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])

    def to_machine(self, prog: np.ndarray) -> np.ndarray:
        """Machine coordinates [mm] of program coordinates under a rotated coordinate system:
        X Y plus the G92 offset, rotated about the work offset's origin, plus the work offset
        (LinuxCNC emccanon.cc rotate_and_offset_pos); Z plus all offsets."""
        off, base, c, s = self._rotated_parts()
        if self.frame is not None:  # G68 first: it turns the program's own coordinates
            prog = self.frame.forward(prog)
        x, y = prog[0] + self.g92[0], prog[1] + self.g92[1]
        return np.array([c * x - s * y + base[0], s * x + c * y + base[1], prog[2] + off[2]])

    def to_program(self, machine: np.ndarray) -> np.ndarray:
        """Inverse of :meth:`to_machine`."""
        off, base, c, s = self._rotated_parts()
        x, y = machine[0] - base[0], machine[1] - base[1]
        prog = np.array([c * x + s * y - self.g92[0], -s * x + c * y - self.g92[1], machine[2] - off[2]])
        return prog if self.frame is None else self.frame.inverse(prog)

    def extra_offset(self) -> np.ndarray:
        """Machine minus program positions of a, b, c [deg], u, v, w [mm]: work plus G92 offset."""
        return self.extra_offsets.get(self.wcs, np.zeros(6)) + self.g92_extra

    def offset(self) -> np.ndarray:
        """Machine minus program coordinates [mm]."""
        o = self.offsets.get(self.wcs)
        base = self.context.offset(self.wcs) if o is None else o
        shift = base + self.g92 + np.array([self.tool_xy[0], self.tool_xy[1], self.tool_length])
        return shift if self.dwo is None else shift + self.dwo


def parse_iso(text: str, *, source: str | None = None, context: MachineContext = DEFAULT_CONTEXT,
              shortcuts: bool = True) -> Program:
    """Parse ISO / Fanuc / LinuxCNC G-code text into a :class:`Program`.

    Parameters
    ----------
    text : str
        Program text.
    source : str, optional
        File name used in error messages and recorded in ``Program.source``.
    context : MachineContext
        Work offsets, tool table, home and reference positions and the dialect of the machine.
    shortcuts : bool
        Plain G0-G3 moves in a plain modal state run by :mod:`interpolators.iso_fast`, which makes the general
        executor's blocks; False: every block the general way (``tests/interpolators/test_reader_fast.py``).

    Raises
    ------
    vcnc.GCodeError
        With file, line, column, the offending text and what was expected; an unsupported
        feature is named (``G38 probing: ...``).
    """
    fadal = context.dialect.name == "fadal"
    if fadal:  # Fadal's own words first (interpolators.iso_fadal), Fanuc's rules for the rest
        text, context = fadal_text(text, source), core_context(context)
    dialect = context.dialect
    st = State(context=context, pos=np.array(context.home, dtype=float),
                inch=dialect.default_units == "inch", exact_stop=not dialect.continuous_path,
                tolerance=dialect.tolerance, home=np.array(context.home), reference2=np.array(context.reference2),
                motion=_POWER_ON_MOTION.get(dialect.name), retract_r=dialect.name == "linuxcnc",
                modal_calls=ModalCalls() if dialect.name == "fanuc" else None, fadal=fadal)
    notes = Notes()
    raw_lines = lines_of(text)
    text, homing, wrapped = prepared_text(text, source, dialect.name, notes)
    st.subprogram = ends_with_m99(text)
    blocks: list[Block] = []
    used: set[int] = set()
    name = program_name(text)
    external: set[str | None] = set()  # files of subprograms called from this one
    plain = PlainMoves(st, blocks, used)  # a work offset written by "#5221 = .." on its line: judged again
    params = _parameters(st, dialect.name, plain)
    messages: list[Message] = []
    on_comment = functools.partial(note_comment, messages=messages, notes=notes) if dialect.name == "linuxcnc" else None
    lines = run(text, source=source, params=params, subroutine_path=tuple(dialect.subroutine_path),
                tape_leader=dialect.name == "fanuc", on_comment=on_comment, on_note=notes.add,
                decimal_point_input=context.decimal_point_input if dialect.name == "fanuc" else None,
                on_call_words=functools.partial(_m98_words, st=st, notes=notes) if dialect.name == "linuxcnc" else None,
                modal_calls=st.modal_calls, tape_forms=dialect.name != "linuxcnc")
    if fadal:
        lines = fadal_lines(lines, st, notes.add, plain.reset)
    for fl in lines:
        message_stops(params, st, blocks, notes)
        line_notes(fl, source, external, notes)
        if dialect.name == "linuxcnc":  # M73's state comes back when its subroutine returns
            _enter_level(st, len(params.frames), params.lowest_since_last(), plain, Where(fl.file, fl.line, fl.raw),
                         notes)
        while homing and fl.file == source and homing[0] < fl.line:
            grbl_homing(st, blocks, used, Where(source, homing[0], raw_lines[homing.pop(0) - 1]), notes)
        if shortcuts and plain.move(fl.words, fl.line, fl.raw):  # a plain G0-G3 move (interpolators.iso_fast)
            continue
        plain.reset()
        count = len(blocks)
        ended = _execute(fl.words, st, blocks, used, Where(fl.file, fl.line, fl.raw), notes)
        if st.corner is not None or st.corner_word is not None:
            corner_after_block(st, fl.words, count, blocks, Where(fl.file, fl.line, fl.raw))
        if any(w.letter == "M" and w.value in _AT_REST for w in fl.words):
            end_at_rest(blocks)
        if any(w.letter == "M" and w.value in (0.0, 1.0, 60.0) for w in fl.words):
            st.stopped, st.stop_line = True, fl.line  # the operator may jog before the next move
        elif len(blocks) > count:
            st.stopped = False
        if st.comp_close_at is not None and (len(blocks) > st.comp_close_at or ended
                                             or rereads_position(fl.words, st)):
            if st.corner is not None:
                corner_not_followed(st.corner, Where(fl.file, fl.line, fl.raw), "cutter compensation ends (G40)")
            finish_compensation(st, blocks, source)
        if ended:
            break
    else:
        message_stops(params, st, blocks, notes)
        for line in homing:  # $H lines after the last block
            grbl_homing(st, blocks, used, Where(source, line, raw_lines[line - 1]), notes)
        if dialect.name == "linuxcnc" and not wrapped:
            # rs274 refuses it at the end: "File ended with no percent sign or program end" (interp_read.cc)
            notes.add("no M2/M30 (nor % at the start and end): read to the end of the file (LinuxCNC refuses it)")
    if st.corner is not None:
        corner_not_followed(st.corner, None, "the program ends")
    if st.comp_start is not None:
        finish_compensation(st, blocks, source)
    expression_notes(text, params, dialect.name, notes, called=external)
    unfinished_arc3d(st, Where(source, st.arc3d_line, ""))
    unfinished_g062(st, Where(source, st.g062.line if st.g062 is not None else 0, ""))
    closing_notes(st, blocks, dialect, notes, reading="fadal" if fadal else dialect.name)
    axes = program_axes(used, blocks)
    blocks = fill_extra(blocks) if st.extra_used else blocks
    return Program(blocks=tuple(blocks), source=source, dialect="iso", axes=axes, name=name, notes=notes.lines(),
                   messages=tuple(messages), rapid_feed_stop=dialect.rapid_feed_stop)


def _enter_level(st: State, level: int, lowest: int, plain: PlainMoves, where: Where, notes: Notes) -> None:
    """LinuxCNC: the call level of the next line and the lowest since the last line
    (:mod:`interpolators.iso_modal_state`); a subroutine that saved the modal state with M73 gives it back as it
    returns."""
    try:
        restored = st.modal_states.enter(st, level, lowest)
    except ValueError as exc:
        where.fail(f"M73 modal state restored at a subroutine's return: {exc}: not supported", expected="G40 "
                   "before the M73 and before the return, or the same compensation in both")
    if restored:
        plain.reset()
        notes.add("M73 modal state restored at the subroutine's return")


def _gkey(w: Word, where: Where) -> int:
    key = round(w.value * 10)
    if abs(w.value * 10 - key) > 1e-6:
        where.fail(f"unknown G code {w.text!r}", column=w.column, text=w.text, expected="a G code such as G1 or G91.1")
    return key


def _collect(words: list[Word], where: Where, notes: Notes, st: State):
    """Sort a block's words: G codes by group, M codes, the other words by letter."""
    seen: dict[str, Word] = {}
    gcodes: dict[str, tuple[int, Word]] = {}
    mcodes: list[tuple[int, Word]] = []
    st.zero_words_dropped = False
    for w in words:
        if w.letter == "G":
            key = _gkey(w, where)
            dialect = st.context.dialect.name
            mill = (MILL_G.get(key, DIALECT_G[dialect].get(key)) if dialect in DIALECT_G
                    else LINUXCNC_G.get(key) if dialect == "linuxcnc" else None)
            if dialect == "linuxcnc" and key == 80 and _fanuc_g08(w, words, where):
                mill = None  # Fanuc's G08 P1 / P0 (look-ahead), named by _unsupported_g, not LinuxCNC's G8
            if mill is not None and mill[0] == "refused":  # LinuxCNC's code, another meaning in this dialect
                where.fail(f"{mill[1]}: not supported", column=w.column, text=w.text,
                           expected=f"milling G codes of the {dialect} dialect")
            if mill is not None:
                if mill[0] in gcodes:
                    where.fail(f"two G codes of the {mill[0]} group in one block", column=w.column, text=w.text,
                               expected=f"one {mill[0]} code per block")
                gcodes[mill[0]] = (key, w)
                continue
            remap = (f" (not a LinuxCNC code: it runs where a configuration remaps it, REMAP=G{key / 10:g} in its "
                     "INI, which vcnc does not read)") if dialect == "linuxcnc" and key not in LINUXCNC_ALLOCATED_G \
                else ""
            if key in G_UNSUPPORTED:
                where.fail(_unsupported_g(key, words, dialect) + remap, column=w.column, text=w.text,
                           expected="milling G codes (see vcnc's ISO reader)")
            if key not in G_CODES:
                # FreeCAD's Job offers the fixtures G59.4-G59.9 (Path/Main MachineState.WCSLIST) and its posts
                # write them as chosen; LinuxCNC's last is G59.3 (g-code.adoc "G54-G59.3"), Fanuc's extra ones are
                # G54.1 P<n>
                fixture = (" (a fixture FreeCAD's Job offers: LinuxCNC has G54-G59.3, Fanuc G54.1 P1-P300 beyond "
                           "G59)") if 594 <= key <= 599 else ""
                where.fail(f"unknown G code {w.text!r}{fixture}{remap}", column=w.column, text=w.text,
                           expected=f"a G code of the {dialect} milling set vcnc reads")
            grp = G_CODES[key][0]
            if grp == "motion" and key == 800 and "motion" in gcodes or grp == "motion" and gcodes.get(
                    "motion", (0,))[0] == 800:
                # "G80 G00": Fanuc posts cancel the cycle and set the motion in one block
                if key == 800:
                    continue
            elif grp in gcodes and dialect == "fanuc" and grp in LAST_ONE_VALID:
                # Fanuc 0i-MD operator's manual (B-64304EN) II-3 "Preparatory function": "If two or more
                # G codes that belong to the same group are specified, only the last G code specified
                # is valid" ("G91 G28 X0 Y0 Z100. G90" runs the G28 under G90)
                notes.add(f"two G codes of the {grp} group in one block: the last one is valid (Fanuc)")
            elif grp in gcodes:
                where.fail(f"two G codes of the {grp} group in one block ({gcodes[grp][1].text} and {w.text})",
                           column=w.column, text=w.text, expected=f"one {grp} code per block")
            elif dialect == "linuxcnc" and grp in ("dwell", "nonmodal") and ("dwell" if grp == "nonmodal"
                                                                               else "nonmodal") in gcodes \
                    and not {key, gcodes.get("nonmodal", (0,))[0]} & {921, 922, 923}:  # G92.1-.3: its group 16
                # LinuxCNC's modal group 0 holds both (interp_array.cc gees[]: G4 G10 G28 G30 G52 G53 G92..);
                # rs274 refuses "G4 P25 G30" ("Two g codes used from same modal group")
                other = gcodes["dwell" if grp == "nonmodal" else "nonmodal"][1]
                where.fail(f"two G codes of LinuxCNC's non-modal group 0 in one block ({other.text} and {w.text})",
                           column=w.column, text=w.text, expected="one of G4, G10, G28, G30, G52, G53, G92 per block")
            gcodes[grp] = (key, w)
        elif w.letter == "M":
            m = int(round(w.value))
            if m != w.value or m < 0:
                where.fail(f"unknown M code {w.text!r}", column=w.column, text=w.text, expected="M0 .. M99")
            if 100 <= m <= 199 and not (m in HAAS_OWN_M and st.context.dialect.name == "haas"):
                user_m_file(w, m, st, where, with_p=any(v.letter == "P" for v in words))
            if m > 199:  # no standard meaning: a LinuxCNC configuration's remap (REMAP=M428 in its INI), or a
                # code of one machine or firmware (Marlin M300 beep, plotter pen servos) elsewhere
                what = ("remapped or user M code" if st.context.dialect.name == "linuxcnc"
                        else "machine- or firmware-specific M code")
                where.fail(f"{what} {w.text!r} (above M199: defined by a machine configuration){printer_hint(m)}: "
                           "not supported",
                           column=w.column, text=w.text, expected="M codes below 100")
            mcodes.append((m, w))
        else:
            lacks = w.letter in EXTRA_LETTERS and w.letter.lower() not in st.context.extra_axes
            kind = "rotary axis" if w.letter in ROTARY_LETTERS else "secondary linear axis"
            if lacks and w.value == 0.0:
                # a word that keeps the axis where it starts (0): no motion (CAM posts write "A0" on
                # 3-axis work); any other value is refused below
                notes.add(f"{w.letter}0 ({kind} {w.letter} stays at 0)")
                st.zero_words_dropped = True
                continue
            if lacks:
                axes = ", ".join(["X", "Y", "Z", *(a.upper() for a in st.context.extra_axes)])
                where.fail(f"axis word {w.letter!r} is not supported: this machine has no {kind} "
                           f"{w.letter} (axis words it takes: {axes})", column=w.column, text=w.text,
                           expected=f"axis words {axes}")
            if w.letter in seen:
                where.fail(f"word {w.letter} appears twice in one block", column=w.column, text=w.text,
                           expected=f"at most one {w.letter} word")
            seen[w.letter] = w
    return seen, gcodes, mcodes


def _execute(words: list[Word], st: State, blocks: list[Block], used: set[int], where: Where,
             notes: Notes) -> bool:
    """Apply one block's words in LinuxCNC's order of execution; append its motion. True at program end.

    A Fanuc/Haas ``G09`` makes the block's motion end in an exact stop, the modal path mode (G61/G64, which
    the block may set too) unchanged (:mod:`interpolators.iso_reference`)."""
    if st.parameter_input:  # Fanuc "Programmable parameter input (G10 L50)": N<number> [P<axis>] R<value> lines
        st.parameter_input = not any(w.letter == "G" and w.value == 11 for w in words)  # G11 ends them
        return False
    if st.context.dialect.name == "fanuc":
        words = _decimal_point(words, st, notes)
    seen, gcodes, mcodes = _collect(words, where, notes, st)
    spindle_select(seen, gcodes, mcodes, st, where, notes)
    if st.context.dialect.name == "grbl":
        for note in [*unsupported_codes(gcodes, seen, where, mcodes), *value_limits(gcodes, seen, where)]:
            notes.add(note)
    before, arc3d = len(blocks), st.arc3d_mid is not None
    m29 = next((w for m, w in mcodes if m == 29), None) if st.context.dialect.name == "fanuc" else None
    if m29 is not None:  # an M29 after its tapping command (interpolators.iso_rigid_tap)
        m29_in_tapping_cycle(st, m29, "motion" in gcodes, where)
    if "exact stop check" not in gcodes:
        ended = _execute_block(words, seen, gcodes, mcodes, st, blocks, used, where, notes)
    else:
        notes.add("G09 exact stop (one block)")
        modal, st.exact_stop = st.exact_stop, True
        ended = _execute_block(words, seen, gcodes, mcodes, st, blocks, used, where, notes)
        if "path" not in gcodes:
            st.exact_stop = modal
    if arc3d and st.arc3d_mid is not None and not ended and any(w.letter != "N" for w in words):  # G02.4 pair
        arc3d_interrupted(st, where)
    if st.rigid_tap_at is not None:  # Fanuc M29 waiting for its G84/G74 (interpolators.iso_rigid_tap)
        rigid_tap_moved(st, any(b.kind != "dwell" for b in blocks[before:]), where, words)
    return ended


def _sequence_number(seen, where: Where) -> int | None:
    """The block's N number (None without one, or with a fraction); a negative N is refused under every dialect:
    rs274ngc reads N as an unsigned integer (interp_read.cc ``read_n_number``: "Bad format unsigned integer"),
    grbl refuses a negative N ("[Word value cannot be negative]", error 4) and Fanuc numbers blocks 1 to 99999
    (a sign in a sequence number: our reading, an alarm)."""
    n = seen.get("N")
    if n is None:
        return None
    if n.value < 0:
        where.fail(f"negative sequence number {n.text.strip()} (LinuxCNC: \"Bad format unsigned integer\"; grbl: "
                   "error 4, word value cannot be negative)", column=n.column, text=n.text,
                   expected="N followed by a whole number >= 0")
    return int(n.value) if n.value == int(n.value) else None


def _execute_block(words: list[Word], seen, gcodes, mcodes, st: State, blocks: list[Block], used: set[int],
                   where: Where, notes: Notes) -> bool:
    """:func:`_execute` of a block whose words are sorted."""
    seen, st.corner_word = corner_word(seen, st.context.dialect.name, where)
    number = _sequence_number(seen, where)
    # order of execution (LinuxCNC G-code overview, "Order of Execution")
    _modes(seen, gcodes, st, where, notes)
    if "polar" in gcodes or st.fanuc_polar:
        seen = fanuc_polar(seen, gcodes, st, where, notes)
    tool_change_under_compensation(mcodes, st, where)
    ended = m_codes(mcodes, seen, st, where, notes)
    seen = planner_word(seen, gcodes, mcodes, where, notes)
    if "smoothing" in gcodes:
        seen = _smoothing(gcodes["smoothing"], seen, st, where, notes)
    if "normal direction" in gcodes:
        _normal_direction(gcodes["normal direction"], st, where, notes)
    seen = io_words(mcodes, seen, st, where)
    _fanuc_system_codes(gcodes, seen, st, where)
    _modal_settings(seen, gcodes, st, blocks, where, notes)
    if gcodes.get("coordinate system", (0,))[0] in P_SELECT_CODES:  # its P names the offset
        seen = {k: v for k, v in seen.items() if k != "P"}
    if "dwell" in gcodes:  # G4 runs before the block's motion (LinuxCNC order of execution)
        dwell_block(gcodes, seen, st, blocks, where, number, notes)
        if "motion" not in gcodes and not ("P" in seen and linuxcnc_modal_axis_words(seen, st)):
            return ended
        seen = {k: v for k, v in seen.items() if k != "P"}
    polar = [w for w in POLAR_LETTERS if w in seen]
    if polar:
        check_polar(seen, gcodes, st, where, seen[polar[0]])
    if gcodes.get("rotation", (0,))[0] == 680:
        g68(seen, st, where, gcodes["rotation"][1], notes)
        return ended
    if "tilted plane" in gcodes or "tool axis" in gcodes:  # G68.2, G53.1 (interpolators.iso_tilt)
        g68_2_g53_1(gcodes, seen, st, blocks, used, where, number, notes)
        return ended
    if gcodes.get("scaling", (0,))[0] == 510 or "mirror" in gcodes:
        scaling_mirror(gcodes, seen, st, where, notes)
        return ended
    if "pattern" in gcodes or "pocket" in gcodes:
        pattern_or_pocket(gcodes, seen, st, blocks, used, where, number, notes)
        return ended
    if "stroke check" in gcodes:  # Fanuc G22/G23: no motion; G22's X Y Z I J K bound the forbidden area
        notes.add(f"{FANUC_CODES[gcodes['stroke check'][0]][1]} (no motion; the stroke limits are not checked)")
        return ended
    if "corner circular" in gcodes:
        g39(gcodes["corner circular"][1], seen, st, len(blocks), where, notes)
        return ended
    if st.context.dialect.name == "linuxcnc":
        _linuxcnc_leniencies(seen, gcodes, st, bool(polar) or any(w in seen for w in ("X", "Y", "Z", *EXTRA_LETTERS)),
                             notes)
    if "nonmodal" in gcodes:
        handled = _nonmodal(gcodes, seen, st, blocks, used, where, number, notes)
        if handled:
            return ended
    if _g062(seen, gcodes, st):  # Fanuc G06.2 NURBS: its P (rank), K (knots) and R (weights)
        if st.g062 is not None and gcodes.get("motion", (62,))[0] != 62:
            unfinished_g062(st, where)
        _motion_mode(gcodes, words, st)
        target = block_target(seen, [a for a in "XYZ" if a in seen], st, machine=False)
        g062_block(seen, gcodes, target, st, blocks, used, where, number, move_feed, notes)
        return ended
    _check_p_q(seen, gcodes, st, where, mcodes)
    _motion_mode(gcodes, words, st)
    if st.arc3d_mid is not None and st.motion not in ARC3D_CODES:
        unfinished_arc3d(st, where)
    axis_words, arc_words, rot_words = ([w for w in g if w in seen] for g in ("XYZ", "IJK", EXTRA_LETTERS))
    if "position offset" in gcodes:
        _check_position_offset(gcodes["position offset"], seen, st, where, rot_words + polar)
    if (st.rotation or st.frame is not None) and (axis_words or polar):
        check_rotated(st, polar, where, words)
    _unused_words(seen, gcodes, st, notes)
    if st.tcp and tcp_block(seen, gcodes, axis_words + polar, rot_words + arc_words, st, blocks, used, where, number):
        return ended  # G43.4 / G43.5 / G234 (interpolators.iso_tcp)
    if st.motion is not None and (st.motion >= 730 or st.motion in (52, 53)):
        cycle_block(seen, gcodes, st, blocks, used, where, number, notes, bool(axis_words or polar), rot_words)
        return ended
    axis_words += polar  # "@" and "^" move X and Y
    if not axis_words and not rot_words and st.motion in (330, 331) and "motion" in gcodes:
        w = gcodes["motion"][1]
        where.fail(f"{G_CODES[st.motion][1]}: all axis words omitted", column=w.column, text=w.text,
                   expected="at least one of X, Y, Z")
    now = length_moves_now(gcodes, st.motion, st)  # Fanuc TOS = 0: "G43 H1" alone moves Z (iso_offsets)
    if not axis_words and not rot_words and _no_move(seen, gcodes, arc_words, st, where) and not now:
        return ended  # a motion code alone sets the mode (LinuxCNC: "G0 G17 G40 G49 G80 G90")
    if st.motion is None:
        w = seen[(axis_words or rot_words)[0]]
        where.fail("axis words before any motion code", column=w.column, text=w.text,
                   expected="G00, G01, G02 or G03 before the first axis word")
    try:
        target = length_travel(block_target(seen, axis_words, st, machine=False), axis_words, st, now=now)
    except PolarError as exc:
        w = seen["@"] if "@" in seen else seen["^"]
        where.fail(str(exc), column=w.column, text=w.text, expected="a start point away from X0 Y0, or X and Y")
    if "position offset" in gcodes:
        target = _position_offset(gcodes["position offset"][0], seen, axis_words, target, st, where, notes)
    if now:
        used.add(2)
    motion_block(seen, gcodes, axis_words, arc_words, target, st, blocks, used, where, number)
    return ended


def _g062(seen, gcodes, st: State) -> bool:
    """True for a block of a Fanuc G06.2 NURBS (:mod:`interpolators.iso_fanuc_nurbs`): the G06.2 block, a block
    while a curve is being read, or under the modal G06.2 a block with X Y Z or K (which starts another curve)."""
    if st.g062 is not None or gcodes.get("motion", (0,))[0] == 62:
        return True
    return "motion" not in gcodes and st.motion == 62 and any(a in seen for a in "XYZK")


def _no_move(seen, gcodes, arc_words: list[str], st: State, where: Where) -> bool:
    """True if a block without axis words moves nothing (its motion code only sets the mode); an arc's I J K
    or R without an arc that runs them is an error. A full circle from I J K alone is a move."""
    if not arc_words and "R" not in seen:
        _arc_code_alone(gcodes, st, where)
    # Fanuc 0i-MD operator's manual (B-64304EN) II-4.4 "Circular interpolation": "When X_, Y_, and Z_ are
    # all omitted (the end point is the same as the start point) and the center is specified with I_, J_,
    # and K_, a 360 deg arc (circle) is specified" -- also in the modal G02/G03 ("I-15. J0" after a helix); LinuxCNC
    # too (interp_internal.cc enhance_block: "a block like simply "i1" [..] accepted if we're in arc mode")
    modal_circle = st.context.dialect.name in ("fanuc", "linuxcnc") and "R" not in seen
    if st.motion in (20, 30) and arc_words and ("motion" in gcodes or modal_circle):
        return False
    for letter in ("I", "J", "K", "R"):
        if letter in seen:
            w = seen[letter]
            where.fail(f"word {letter} without an arc motion", column=w.column, text=w.text,
                       expected="G02 or G03 with X/Y/Z")
    return True


def _check_position_offset(entry, seen, st: State, where: Where, other_axes: list[str]) -> None:
    """Refuse a G45-G48 block :mod:`interpolators.iso_position_offset` does not run, naming the case."""
    key, w = entry
    name = POSITION_OFFSET_CODES[key][0]
    why = ("without D or H (the offset number)" if "D" not in seen and "H" not in seen else
           "on an arc (Fanuc: quarter and three-quarter circles only): not supported" if st.motion in (20, 30) else
           "in a canned cycle" if st.motion is not None and st.motion >= 730 else
           f"with cutter compensation on ({st.comp_code})" if st.comp_side is not None else
           "in a rotated, scaled or mirrored coordinate system: not supported"
           if st.rotation or st.frame is not None else
           f"with axis word {other_axes[0]}: not supported" if other_axes else None)
    if why is not None:
        where.fail(f"{name} {why}", column=w.column, text=w.text,
                   expected=f"{w.text.strip()} X/Y/Z D<n> (or H<n>) on a G00/G01 move, without G41/G42")


def _position_offset(key: int, seen, axis_words: list[str], target: np.ndarray, st: State, where: Where,
                     notes: Notes) -> np.ndarray:
    """The end point of a G45-G48 block (:mod:`interpolators.iso_position_offset`): the offset of its D word (the
    tool table's radius) or H word (length)."""
    letter = "D" if "D" in seen else "H"
    number = offset_number(seen[letter], where, POSITION_OFFSET_CODES[key][0].split()[0])
    tool = st.tool(number)
    if tool is None:
        notes.add(f"{letter}{number} not in the tool table (offset 0)")
    offset = 0.0 if tool is None else tool.radius if letter == "D" else tool.length
    notes.add(POSITION_OFFSET_CODES[key][0])
    axes = {"XYZ".index(a): "-" in seen[a].text for a in axis_words}
    return offset_travel(key, st.pos, target, axes, offset, incremental=st.incremental)


def _arc_code_alone(gcodes, st: State, where: Where) -> None:
    """A G2/G3 block with no axis, centre or radius word: LinuxCNC refuses it (interp_arc.cc convert_arc: "The
    block has neither an r value nor any i,j,k values: NCE_R_I_J_K_WORDS_ALL_MISSING_FOR_ARC", checked also on a
    block without axis words: rs274 refuses "G3 F360"), and so does grbl (gnea/grbl ``grbl/gcode.c``: a G2/G3
    word makes the block an axis command, ``axis_command = AXIS_COMMAND_MOTION_MODE``, and the arc checks then
    fail "[No axis words]" STATUS_GCODE_NO_AXIS_WORDS, error 26; only G0 and G1 without axis words just set the
    mode); Fanuc, Haas and Fadal take the motion mode from it. An arc with axis words and no centre is refused by
    :func:`interpolators.iso_arcs.read_arc`."""
    dialect = st.context.dialect.name
    if dialect not in ("linuxcnc", "grbl") or gcodes.get("motion", (0,))[0] not in (20, 30):
        return
    w = gcodes["motion"][1]
    code = w.text.upper()
    if dialect == "grbl":
        where.fail(f"{code} arc without axis words: grbl refuses it (error 26, no axis words: unlike G0 and G1, "
                   "an arc code alone does not just set the motion mode)", column=w.column, text=w.text,
                   expected=f"{code} in the block that moves, with its end point and I/J or R")
    where.fail(f"{code} arc without R, I, J or K (LinuxCNC: 'R i j k words all missing for arc', also on a block "
               "without axis words)", column=w.column, text=w.text, expected=f"{code} with I/J/K or R, in the block "
               "that moves")


def _decimal_point(words: list[Word], st: State, notes: Notes) -> list[Word]:
    """Fanuc decimal-point input (:mod:`interpolators.iso_decimal`): under ``increment`` (DPI = 0) the
    distances, angles and times written without a decimal point in least input increments; under
    ``calculator`` (DPI = 1) unchanged, with a note the first time."""
    codes = {round(w.value, 1) for w in words if w.letter == "G"}
    inch = 20 in codes or st.inch and 21 not in codes
    mode = st.context.decimal_point_input
    out, first = decimal_point_words(words, mode=mode, inch=inch, cycle=st.motion is not None and st.motion >= 730)
    if first is not None and mode == "calculator" and not st.decimal_noted:
        st.decimal_noted = True
        notes.add(decimal_point_note(first, inch=inch))
    return out


def _fanuc_system_codes(gcodes, seen, st: State, where: Where) -> None:
    """Fanuc, before the modal settings: the codes a G51.1 mirror forbids are errors
    (:func:`interpolators.iso_transforms.mirror_forbids`), and ``G54 P<n>`` is ``G54.1 P<n>``
    (:func:`interpolators.iso_offsets.g54_takes_p`; ``gcodes`` is changed)."""
    if st.context.dialect.name != "fanuc":
        return
    group = mirror_forbids(st.frame, {k: v[0] for k, v in gcodes.items()})
    if group is not None:
        w = gcodes[group][1]
        where.fail(f"{w.text.upper()} in programmable mirror image mode (G51.1): Fanuc refuses it", column=w.column,
                   text=w.text, expected="G50.1 (mirror image cancel) before it")
    cycle = "motion" in gcodes and gcodes["motion"][0] >= 730 or st.motion is not None and st.motion >= 730
    if g54_takes_p(gcodes, "P" in seen, st.context.dialect.name, cycle):
        gcodes["coordinate system"] = (541, gcodes["coordinate system"][1])


def _modes(seen, gcodes, st: State, where: Where, notes: Notes) -> None:
    """Feed mode, units, plane, distance modes, F, S and T: they apply to this block's own words."""
    if "feed mode" in gcodes:
        # LinuxCNC convert_feed_mode: G93 inverse time; G94 resets the feed rate to 0 (an F must follow)
        key, w = gcodes["feed mode"]
        changed = (key == 940 and st.inverse_time) or (key == 950) != st.per_rev
        # on LinuxCNC every G94/G95 word does, the mode already active or not (Dialect.feed_mode_clears_feed)
        again = (key != 930 and st.context.dialect.feed_mode_clears_feed
                 and (st.feed is not None or st.feed_per_rev is not None))
        if changed or again:
            # G95 (units per revolution) and G94 after it reset the feed as well: an F must follow
            st.feed = st.feed_rotary = st.feed_per_rev = st.feed_per_rev_word = None
            st.feed_reset = True
        st.inverse_time = key == 930
        if not st.inverse_time:
            st.inverse_rate = None
        st.per_rev = key == 950
    st.block_f = seen["F"].value if "F" in seen else None
    if "lathe mode" in gcodes:  # LinuxCNC's G8 (interpolators.iso_codes.LINUXCNC_G)
        notes.add("G8 lathe radius mode (LinuxCNC's default at power up): X is the distance from the centre, "
                  "as it always is here")
    # units, plane and distance modes first: they apply to this block's own words
    if "units" in gcodes:
        key, w = gcodes["units"]
        if key in (700, 710):
            _g70_g71_units(key, w, seen, where, notes)
        st.inch = key in (200, 700)
        st.units_stated = True
    if "plane" in gcodes:
        st.plane = PLANE_OF[G_CODES[gcodes["plane"][0]][1]]
    if "distance" in gcodes:
        st.incremental = gcodes["distance"][0] == 910
    if "arc distance" in gcodes:
        st.arc_incremental = gcodes["arc distance"][0] == 911
    if "F" in seen:
        f = seen["F"]
        scale = st.scale
        if f.value < 0 or (st.inverse_time and f.value == 0):
            where.fail("feed F must be > 0", column=f.column, text=f.text,
                       expected="F > 0 [1/min]" if st.inverse_time else "F > 0 [in/min]" if scale != 1.0 else
                       "F > 0 [mm/min]")
        st.feed_zero = f.value == 0
        if st.feed_zero:
            # LinuxCNC read_f refuses only a negative F; F0 is a zero feed rate, an error at the next feed
            # move ("Cannot do G1 with zero feed rate"), as on grbl (error 22) and Fanuc (PS0011 feed zero)
            st.feed = st.feed_rotary = st.feed_per_rev = st.feed_per_rev_word = None
        elif st.per_rev:
            st.feed_per_rev, st.feed_per_rev_word = f.value * scale, f.value
        elif not st.inverse_time:
            st.feed = f.value * scale / 60.0
            st.feed_rotary = f.value / 60.0
    if "S" in seen:
        if seen["S"].value < 0:
            w = seen["S"]
            where.fail("spindle speed S must be >= 0", column=w.column, text=w.text, expected="S >= 0 [rev/min]")
        st.spindle_speed = seen["S"].value
        notes.add("S/M3-M5 spindle")
    if st.per_rev:
        # LinuxCNC g-code.adoc "G93, G94, G95": the controlled point moves F units per spindle revolution,
        # so at F x S per minute (S: interp_convert.cc refuses "zero spindle speed in feed per rev mode")
        has = st.feed_per_rev is not None and st.spindle_speed > 0
        st.feed = st.feed_per_rev * st.spindle_speed / 60.0 if has else None
        st.feed_rotary = st.feed_per_rev_word * st.spindle_speed / 60.0 if has else None
    if "T" in seen:
        w = seen["T"]
        fagor = re.fullmatch(r"T\s*(\d+)\.(\d+)", w.text, re.I) if st.context.dialect.name == "fanuc" else None
        if fagor is not None:
            w = _fagor_tool(w, fagor, st, notes)
        if w.value != int(w.value) or w.value < 0:
            where.fail("tool number T must be a whole number >= 0", column=w.column, text=w.text,
                       expected="T0, T1, ...")
        st.tool_selected = int(w.value)
        if st.tool(st.tool_selected) is None and st.tool_selected != 0:
            notes.add(f"T{st.tool_selected} not in the tool table (length and radius 0)")


def _parameters(st: State, dialect: str, plain: PlainMoves) -> Parameters:
    """The program's parameters: macro B's system variables under fanuc/haas (a work offset written through them
    judged again by ``plain``); under linuxcnc the writable G28/G30 positions and work offsets and the predefined
    named parameters of the modal state (:mod:`interpolators.iso_system`)."""
    macro_b = dialect in ("fanuc", "haas")
    linuxcnc = dialect == "linuxcnc"

    def set_linuxcnc(n, v):
        return set_reference_parameter(n, v, st) or set_work_offset_parameter(n, v, st)

    return Parameters(macro_b=macro_b, system=lambda n: system_parameter(n, st, fanuc=macro_b),
                      fanuc=dialect == "fanuc", inch=lambda: st.inch,
                      set_system=(lambda n, v: plain.reset() or set_system_parameter(n, v, st)) if macro_b else
                      set_linuxcnc if linuxcnc else None,
                      named_state=(lambda k: named_state_parameter(k, st)) if linuxcnc else None)


def _smoothing(entry, seen, st: State, where: Where, notes: Notes) -> dict:
    """A Fanuc/Haas look-ahead code (:mod:`interpolators.iso_smoothing`): a note, G187 E the path
    tolerance; returns ``seen`` without the words it reads."""
    key, w = entry
    try:
        sm = smoothing(key, {k: v.value for k, v in seen.items()})
    except WordError as exc:
        fail_words(where, SMOOTHING_CODES[key], exc, seen, w)
    if sm.tolerance is not None:
        st.exact_stop, st.tolerance = False, sm.tolerance * st.scale
    elif sm.continuous:
        st.exact_stop, st.tolerance = False, None
    elif sm.reset:
        st.tolerance = st.context.dialect.tolerance
    notes.add(sm.note)
    return {k: v for k, v in seen.items() if k not in sm.consumed}


def _fagor_tool(w: Word, m: re.Match, st: State, notes: Notes) -> Word:
    """``T<tool>.<offset>`` under ``--dialect fanuc``: Fagor's 8025/8030 form of the 8055's ``T<tool> D<offset>``
    (Fagor 8055 programming manual, 5.6 "Tool number (T) and tool offset (D)": "T5 D18 selects tool 5 and
    assumes the dimensions of tool offset 18"; the dotted form is our reading of the older controls' programs,
    no 8025 manual at hand). The offset is the tool-table entry G43 without H and G41/G42 without D take
    while that tool is in the spindle (8055 manual 8.2: G43 "compensates the length in accordance with the
    value of the tool offset selected with code D"). Returns the T word of the tool alone."""
    tool, offset = int(m.group(1)), int(m.group(2))
    st.tool_offsets[tool] = offset
    notes.add("T<tool>.<offset> read as Fagor's tool and offset (T D of the Fagor 8055)")
    return Word("T", float(tool), w.column, w.text)


#: LinuxCNC's drilling cycles that read P (the dwell at the bottom) and Q (the peck): rs274ngc interp_check.cc
#: check_other_codes ("P word with no G2 G3 G4 G10 G64 G5 G5.2 G6, G6.2, G76 G82 G86 G88 G89 ... to use it",
#: which lets G74 and G84 through too; "Q word with no G5, G6, G10, G64, G73, G76, G83, M19, M66, M67, M68 or
#: user M code that uses it"); g-code.adoc: G81 "G81 (X- Y- Z-) R- L-", G83 "G83 (X- Y- Z-) R- L- Q-".
LINUXCNC_CYCLE_WORDS = {"P": (740, 820, 840, 860, 880, 890), "Q": (730, 830)}


#: The G codes (10 x G) and M codes that read a P in rs274ngc (interp_check.cc check_other_codes, above: the
#: drilling cycles of :data:`LINUXCNC_CYCLE_WORDS` and G2 G3 G4 G10 G64 G5 G5.2 G6 G6.2 G76; M62-M66 and M98 read
#: theirs, M100-M199 user M codes P and Q).
_P_READERS_G = frozenset((20, 30, 40, 100, 640, 50, 52, 60, 62, 760, *LINUXCNC_CYCLE_WORDS["P"]))
_P_READERS_M = frozenset((62, 63, 64, 65, 66, 98, *range(100, 200)))


def _fanuc_g08(g8: Word, words: list[Word], where: Where) -> bool:
    """Whether the G8 ``g8`` of a ``linuxcnc`` block is Fanuc's ``G08 P1`` / ``P0`` (AI advanced preview control):
    it has a P and no other code of the block reads one (:data:`_P_READERS_G`, :data:`_P_READERS_M`). LinuxCNC's G8
    (lathe radius mode, modal group 15 of g-code.adoc "Modal Groups") takes no P: ``G8 G64 P0.01`` or ``G8 G4 P1``
    gives the P to G64 or G4, while ``G90 G08 P1`` is Fanuc's."""
    if not any(v.letter == "P" for v in words):
        return False
    for v in words:
        if v is g8 or v.letter not in "GM":
            continue
        if v.letter == "G" and _gkey(v, where) in _P_READERS_G or v.letter == "M" and v.value in _P_READERS_M:
            return False
    return True


def _unsupported_g(key: int, words: list[Word], dialect: str) -> str:
    """The error of a G code of :data:`G_UNSUPPORTED`; a bare G70/G71 (no lathe-cycle or pattern word in its
    block) with :data:`UNITS_HINT`, a bare G75 with :data:`HURCO_BNC_HINT`; a G8 with P named as Fanuc's
    look-ahead (Fanuc 0i-MF "AI advanced preview control", :mod:`interpolators.iso_smoothing`); under
    ``linuxcnc`` G87/G88 with what LinuxCNC's g-code.adoc says of them (:data:`LINUXCNC_UNDEFINED`)."""
    bare = not any(v.letter in "PQUWRIJKL" for v in words)
    hurco = HURCO_BNC_HINT if key == 750 and bare else ""  # a bare G75: Hurco BNC's arc mode
    if dialect == "linuxcnc" and key in LINUXCNC_UNDEFINED:
        return f"{G_UNSUPPORTED[key]}: not supported{LINUXCNC_UNDEFINED[key]}{hurco}"
    if key == 80 and any(v.letter == "P" for v in words):  # LinuxCNC's G8 takes no P; Fanuc's G08 P1 / P0 does
        return (f"{G_UNSUPPORTED[key]}: not supported (G08 P1 / P0 with a P is Fanuc's AI advanced preview "
                "control, a mill's look-ahead: --dialect fanuc)")
    return f"{G_UNSUPPORTED[key]}: not supported{UNITS_HINT.get(key, '') if bare else ''}{hurco}"


def _g70_g71_units(key: int, w: Word, seen, where: Where, notes: Notes) -> None:
    """G70 / G71 in a Fanuc mill program (``--dialect fanuc``; Haas reads bolt-hole patterns): inch / metric
    input, as Siemens (SINUMERIK programming manual, "Inch or metric dimensions: G70/G700, G71/G710"), Fagor
    8055 ("G70/G71 programming units") and Heidenhain ISO (TNC ISO programming manual: "G70 inch, G71 mm")
    mills read them; on Fanuc mills they are no mill code (Fanuc's lathe finishing/roughing cycles, which a
    mill refuses). Our reading: a post written for one of those controls (Chinese shop posts: "G40 G17 G90
    G71"), noted. With a lathe cycle's words (P Q U W R) or a Haas bolt-hole pattern's (I J K L) it is no
    unit: refused."""
    cycle = [c for c in "PQUWRIJKL" if c in seen]
    if cycle:
        name = "G70 lathe finishing cycle" if key == 700 else "G71 lathe roughing cycle"
        where.fail(f"{name}: not supported (its {cycle[0]} word)", column=w.column, text=w.text,
                   expected="milling G codes (see vcnc's ISO reader)")
    notes.add(f"G{key // 10} read as {'inch' if key == 700 else 'metric'} input (Siemens, Fagor, Heidenhain ISO; "
              "not a Fanuc mill code)")


def _normal_direction(entry, st: State, where: Where, notes: Notes) -> None:
    """Fanuc G40.1/G41.1/G42.1 (:data:`NORMAL_DIRECTION`): the control turns the C axis normal to the XY
    path and leaves the path itself as programmed. A machine without a C axis has nothing to turn: the
    codes are a note (CAM safety lines write ``G40.1`` among G40 G49 G80). With a C axis the turning
    would be motion vcnc does not make: refused."""
    key, w = entry
    if key != 401 and "c" in st.context.extra_axes:
        where.fail(f"{NORMAL_DIRECTION[key]} (turning the C axis normal to the path): not supported",
                   column=w.column, text=w.text, expected="G40.1, or C moves programmed in the blocks")
    notes.add(NORMAL_DIRECTION[key] if key == 401 else "G41.1/G42.1 normal direction control: this machine has "
              "no C axis to turn, the path is as programmed")


#: G50 with an S word: on a Fanuc lathe (G code system A) the maximum spindle speed setting ("G50 Coordinate
#: system setting, maximum spindle speed setting", FANUC Series 0i-TF G code list), on a mill the scaling cancel
#: and a spindle speed, as vcnc reads it; noted, the program being a lathe's most likely.
LATHE_G50 = ("G50 S read as the mill's scaling cancel and a spindle speed (on a Fanuc lathe G50 S is the maximum "
             "spindle speed: a lathe program, whose X is a diameter?)")


def _lathe_program(seen, gcodes, st: State, where: Where) -> None:
    """Fanuc and Haas: a program with both G50 S and G96 is a lathe's. FANUC Series 0i-TF G code list (G code
    system A): "G50 Coordinate system setting, maximum spindle speed setting", "G96 Constant surface speed
    control"; Haas lathe operator's manual: "G50 Spindle Speed Limit", "G96 Constant Surface Speed On". On a
    mill G50 is the scaling cancel and G96 an option no milling post writes beside it. A lathe's X is a diameter
    and its U W incremental X Z: read as a mill program each X would end twice as far from the centre. A T word of
    four digits with a leading zero (``T0101``) is the lathe's tool and offset number (Fanuc lathe "T code": the
    first two digits the tool, the last two its offset; Haas lathe manual "Tool Functions": "T0101"), which no mill
    post writes: either code beside it is a lathe's too (newuser34: a lathe program with G96 or G50 S alone was
    read as a mill's, its F0.2 [mm/rev] as 0.2 mm/min, seven hours). Any one of the three alone stays a note
    (:data:`LATHE_G50`, "G96/G97 spindle mode")."""
    if st.context.dialect.name not in ("fanuc", "haas"):
        return
    marks = []
    if gcodes.get("scaling", (0,))[0] == 500 and "S" in seen:
        marks.append(("G50 S (the lathe's maximum spindle speed)", gcodes["scaling"][1]))
    if gcodes.get("spindle mode", (0,))[0] == 960:
        marks.append(("G96 (constant surface speed)", gcodes["spindle mode"][1]))
    if "T" in seen and re.fullmatch(r"T\s*0\d{3}", seen["T"].text.strip(), re.IGNORECASE):
        marks.append(("a T word of four digits (T0101: a lathe's tool and offset number)", seen["T"]))
    for what, w in marks:
        other = next(((k, at) for k, at in st.lathe_marks.items() if k != what), None)
        if other is not None:
            file, line = other[1]
            at = f"line {line}" if file == where.file else f"{file or '<input>'}:{line}"  # a subprogram's file
            where.fail(f"a lathe program: {what} here and {other[0]} at {at} are a Fanuc/Haas lathe's "
                       "codes (its X is a diameter, U and W incremental X and Z): not supported", column=w.column,
                       text=w.text, expected="a milling program (vcnc reads mill programs)")
        st.lathe_marks.setdefault(what, (where.file, where.line))


def _modal_settings(seen, gcodes, st: State, blocks: list[Block], where: Where, notes: Notes) -> None:
    """Compensation, length offsets, work offsets, path mode and return level."""
    _lathe_program(seen, gcodes, st, where)
    if "spindle mode" in gcodes:
        notes.add("G96/G97 spindle mode")
    alone = h_alone(gcodes, seen, st)  # Fanuc/Haas: "H2" alone in G43 mode is G43 H2 (interpolators.iso_offsets)
    if gcodes.get("polar", (0,))[0] == 150 and "H" in seen and "length compensation" not in gcodes \
            and alone is None:  # in G43/G44 mode "G15 H2" is Fanuc's: the H changes the length
        # Okuma OSP (OSP-E100M/P300M programming manuals, G15 "work coordinate system selection", modal; Fusion's
        # okuma.cps writes "G15 H<work offset>" then "G56 Z.. H<n>" for the tool length and "G71 Z.." for the
        # cycles' return level): read as Fanuc's polar cancel, the offsets would be lost without a word
        w = gcodes["polar"][1]
        where.fail(f"G15 {seen['H'].text}: Okuma OSP's work coordinate system selection (then G56 H is its tool "
                   "length offset, G71 Z its cycle return level); vcnc reads no OSP program (Fanuc's G15, polar "
                   "coordinates off, takes no H)", column=w.column, text=w.text,
                   expected="a Fanuc/Haas/LinuxCNC/grbl program: G54-G59 and G43 H in place of G15 H and G56 H")
    for grp in ("rotation", "scaling", "polar"):
        if grp in gcodes and gcodes[grp][0] not in (680, 510, 160):
            # G69, G50, G15 are no LinuxCNC codes (interp_array.cc gees[]: -1)
            refused = "; LinuxCNC refuses it: \"Unknown g code used\"" if st.context.dialect.name == "linuxcnc" else ""
            lathe = grp == "scaling" and gcodes[grp][0] == 500 and "S" in seen  # "N01G50S0600" (a Fanuc 0T program)
            notes.add(f"{LATHE_G50}{refused}" if lathe else f"{gcodes[grp][1].text.upper()} cancel{refused}")
    if gcodes.get("rotation", (0,))[0] == 690 and st.frame is not None:
        set_frame(st, dataclasses.replace(st.frame, rotation=None))
    if gcodes.get("scaling", (0,))[0] == 500 and st.frame is not None:
        set_frame(st, dataclasses.replace(st.frame, factors=(1.0, 1.0, 1.0)))
    scale = st.scale
    if "cutter compensation" in gcodes:
        cutter_compensation(gcodes["cutter compensation"], seen, st, blocks, where, notes)
    if alone is not None:
        gcodes["length compensation"] = alone
    if "length compensation" in gcodes:
        key, w = gcodes["length compensation"]
        tcp_switch((key, w), st, where, notes)  # G43.4 / G43.5 / G234: the length as G43 (interpolators.iso_tcp)
        if st.tcp and st.dwo is not None:
            where.fail("G234 tool centre point control under G254 dynamic work offset: not supported", column=w.column,
                       text=w.text, expected="G255 before G234")
        length_compensation((430, w) if st.tcp else (key, w), seen, st, where, notes)
        st.length_code = key / 10
    if "coordinate system" in gcodes:
        key, w = gcodes["coordinate system"]
        if st.comp_side is not None and st.context.dialect.name == "linuxcnc":  # convert_coordinate_system
            where.fail(f"{w.text.upper()}: cannot change coordinate systems with cutter radius compensation on "
                       "(LinuxCNC)", column=w.column, text=w.text, expected=f"G40 before {w.text.upper()}")
        if key in G_CODES:
            if st.written_offsets and G_CODES[key][1] != st.wcs:
                take_written_offsets(st)
            st.wcs = G_CODES[key][1]
        else:  # Fanuc G54.1 P, Haas G154 P / G110-G129 (interpolators.iso_offsets)
            try:
                p = seen["P"].value if "P" in seen else None
                st.wcs, assumed = selected_offset(key, p, st.context.dialect.name)
            except WordError as exc:
                fail_words(where, f"{w.text.upper()} additional work offset", exc, seen, w)
            if assumed:
                notes.add(f"{w.text.upper()} without P: P1")
        if st.dwo is not None and "dwo" not in gcodes:  # G254 carries the work offset in force
            carry_work_zero(st)
    if "dwo" in gcodes:  # Haas G254 / G255 (interpolators.iso_dwo), after the block's work offset
        dwo_switch(gcodes["dwo"], st, where, notes)
    if "path" in gcodes:
        key, w = gcodes["path"]
        st.exact_stop = key in (610, 611)
        if key in (620, 630):  # Fanuc G62/G63 (interpolators.iso_reference): continuous, as G64
            notes.add(f"{FANUC_CODES[key][1]}: continuous path as G64 (the feed override it changes is not modelled)")
        if key == 640 and "P" in seen and "dwell" not in gcodes and seen["P"].value != 0:
            tol = seen["P"]
            if not tol.value > 0:
                where.fail("G64 path tolerance P must be >= 0", column=tol.column, text=tol.text,
                           expected="P >= 0 [mm] (P0: no tolerance given)")
            st.tolerance = tol.value * scale
        elif key in (620, 630, 640):
            st.tolerance = None
        if key == 640 and "Q" in seen:
            notes.add("G64 Q naive-CAM tolerance (segments are blended, not merged)")
    if "return mode" in gcodes:
        st.retract_r = gcodes["return mode"][0] == 990


def _linuxcnc_leniencies(seen, gcodes, st: State, moves: bool, notes: Notes) -> None:
    """Notes of what the ``linuxcnc`` dialect runs although LinuxCNC refuses it (``moves``: the block has axis
    words)."""
    # G10, G28, G30, G52, G92 and G43.1 use the axis words themselves (interp_internal.cc check_g_codes:
    # mode_zero_covets_axes; convert_tool_length_offset reads G43.1's), so LinuxCNC runs them after G80 ("G80"
    # then "G28 G91 Z0.", as Fusion 360's posts end a drilling operation)
    takes_axes = gcodes.get("nonmodal", (0,))[0] in (100, 280, 300, 520, 920) or \
        gcodes.get("length compensation", (0,))[0] == 431
    if st.after_g80 and "motion" not in gcodes and moves and st.motion is not None and not takes_axes:
        # LinuxCNC refuses them: G80 sets motion_mode = G_80 (interp_convert.cc convert_motion), and axis
        # words without a motion code then fail (interp_internal.cc: "Cannot use axis values without a g code
        # that uses them"); CAM posts write them after G80 (Fusion 360's "G80" then "Z5.533")
        notes.add(f"axis words after G80 run as {G_CODES[st.motion][1]}, the motion before the cycle "
                  "(LinuxCNC refuses them: G80 leaves no motion mode)")
    if "nonmodal" in gcodes and gcodes["nonmodal"][0] in (100, 280, 300, 520, 920) and "motion" in gcodes \
            and gcodes["motion"][0] != 800:  # interp_internal.cc check_g_codes: mode_zero_covets_axes
        notes.add(f"{gcodes['motion'][1].text.upper()} with {gcodes['nonmodal'][1].text.upper()} in one block "
                  "(LinuxCNC refuses them: \"Cannot use two g codes that both use axis values\")")
    if gcodes.get("motion", (0,))[0] == 10 and not moves and "F" not in seen and st.feed is None:
        # interp_convert.cc convert_straight checks the feed before it looks for axis words
        notes.add("G1 alone before any F (LinuxCNC refuses it: \"Cannot do g1 with zero feed rate\")")
    normal = "IJK"[st.plane]  # a centre word along the plane normal: 0 is accepted (FreeCAD writes K0 on G17 arcs)
    if normal in seen and seen[normal].value == 0.0 and (gcodes["motion"][0] if "motion" in gcodes
                                                         else st.motion) in (20, 30):
        # LinuxCNC refuses it (interp_convert.cc convert_arc: "K word given for arc in xy plane", and I, J alike)
        notes.add(f"{normal}0 on {PLANE_CODES[st.plane]} arcs ignored (LinuxCNC refuses a {normal} word there)")


def _motion_mode(gcodes, words: list[Word], st: State) -> None:
    """The modal motion; a drilling cycle remembers the motion before its series (G80 restores it)."""
    if "motion" in gcodes:
        key = gcodes["motion"][0]
        st.after_g80 = key == 800
        if key not in (52, 53):  # LinuxCNC convert_nurbs: another motion mode drops the G5.2 control points
            st.nurbs = None
        in_cycle = st.motion is not None and st.motion >= 730
        if key == 800:
            st.motion = st.cycle.motion_before if in_cycle else st.motion
            end_rigid_tap(st, words)
        else:
            if key >= 730 and not in_cycle:  # a new series of cycles: remember the initial level
                # LinuxCNC keeps the last dwell P across series (settings->cycle_p; interp_cycles.cc
                # convert_cycle_xy: G74/G84 without P take it, rs274 dwells after "G82 .. P1.5 G80 G84 .."); Fanuc
                # clears the hole machining data at G80 (B-64304EN "Canned cycle for drilling")
                carried = st.cycle.p if st.context.dialect.name == "linuxcnc" else None
                st.cycle = CycleWords(motion_before=st.motion, p=carried)
            st.motion = key
            if key not in (740, 840) and not any(w.letter == "M" and w.value == 29 for w in words):
                end_rigid_tap(st, words)  # a group 01 code ends the cycle as G80 does, another cycle the tap
    elif "G80" in (w.text.upper().replace("G080", "G80") for w in words if w.letter == "G"):
        st.motion = st.cycle.motion_before if st.motion is not None and st.motion >= 730 else st.motion
        end_rigid_tap(st, words)


def _check_p_q(seen, gcodes, st: State, where: Where, mcodes: list) -> None:
    """P, Q and L only where a code reads them. ``M3 P100`` is named: the Snapmaker 2.0 firmware (Marlin-based)
    reads P as the spindle power in percent ("M3 [P] | 50 < percentage <= 100", Snapmaker's gcode_reference.md,
    https://github.com/Snapmaker/snapmaker_cnc_post_process), a word none of these dialects has."""
    motion = gcodes["motion"][0] if "motion" in gcodes else st.motion
    if motion in (50, 52):  # G5 P Q, G5.2 P L: theirs
        return
    linuxcnc = st.context.dialect.name == "linuxcnc"
    if linuxcnc:  # rs274: the block's own motion; G80 or G0 after a cycle reads none
        cycle = motion is not None and motion >= 730 and motion != 800
        if cycle:
            _linuxcnc_cycle_p_q(seen, gcodes, motion, where, mcodes)
    else:
        cycle = "motion" in gcodes and gcodes["motion"][0] >= 730 or (st.motion is not None and st.motion >= 730)
    if "P" in seen and motion in (20, 30) and linuxcnc and not off_plane(st):
        return _check_q_l(seen, gcodes, cycle, where)  # G2/G3 P: the number of turns (arc_turns)
    if "P" in seen and "path" not in gcodes and not cycle and "nonmodal" not in gcodes:
        w = seen["P"]
        spindle = next((m for m, _ in mcodes if m in (3, 4)), None)
        if smartcool_hint(mcodes):
            where.fail(f"word P with M7/M8{smartcool_hint(mcodes)}", column=w.column, text=w.text,
                       expected="M7/M8 alone (flood or mist coolant)")
        if spindle is not None:
            where.fail(f"M{spindle} P: spindle power in percent (Snapmaker 2.0 firmware): not a word of the linuxcnc, "
                       "grbl, fanuc or haas dialect", column=w.column, text=w.text, expected=f"M{spindle} S<rpm>")
        where.fail("word P needs G04 (dwell), G64 (path tolerance), G10, a drilling cycle or (linuxcnc) G2/G3",
                   column=w.column, text=w.text, expected="G04 P<time> or G64 P<tolerance>")
    _check_q_l(seen, gcodes, cycle, where)


def _linuxcnc_cycle_p_q(seen, gcodes, code: int | None, where: Where, mcodes: list) -> None:
    """Under ``linuxcnc`` a P or Q in a drilling cycle that does not read it is LinuxCNC's error (a Fanuc or Haas
    post's ``G83 ... P500 Q2``, ``G81 ... Q1``), not a word vcnc drops: see :data:`LINUXCNC_CYCLE_WORDS`; so is a P
    or Q in a block of a modal cycle that names no G code (rs274 2.9.0~pre1 refuses "P2" after "G82 ... P1" and
    "Q0.3" after "G83 ... Q0.5": check_other_codes looks at the block's own G codes)."""
    if code is None or code not in G_CODES or not 730 <= code <= 890 or code == 800 or "nonmodal" in gcodes \
            or "path" in gcodes:
        return
    io = any(m in (50, 51, 52, 53, 62, 63, 64, 65, 66) for m, _ in mcodes)
    if "motion" not in gcodes:  # rs274 check_other_codes reads the block's G codes: a modal cycle's block has none
        for letter in ("P", "Q"):
            if letter in seen and not (letter == "P" and io):
                w = seen[letter]
                where.fail(f"word {letter} in a block of the modal {G_CODES[code][1]} that does not name it: LinuxCNC "
                           f"refuses it ('{letter} word with no G code to use it'; a cycle's {letter} goes in the "
                           "block that names the cycle)", column=w.column, text=w.text,
                           expected=f"{G_CODES[code][1].split()[0]} ... {letter}.. again, or the block without "
                                    f"{letter} (or --dialect fanuc/haas for a post written for them)")
    for letter, readers in LINUXCNC_CYCLE_WORDS.items():
        if letter in seen and code not in readers and not (letter == "P" and io):
            w = seen[letter]
            uses = ("the dwell at the bottom: G82, G86, G88, G89 or the tapping cycles G74/G84" if letter == "P" else
                    "the peck depth: G73 and G83 only")
            where.fail(f"word {letter} in a {G_CODES[code][1]}: LinuxCNC refuses it ('{letter} word with no G code "
                       f"to use it'; {letter} is {uses})", column=w.column, text=w.text,
                       expected=f"the cycle without {letter} (or --dialect fanuc/haas for a post written for them)")


def _check_q_l(seen, gcodes, cycle: bool, where: Where) -> None:
    for letter in ("Q", "L"):
        if letter in seen and not cycle and not ("path" in gcodes and letter == "Q") \
                and not ("nonmodal" in gcodes and letter == "L"):
            w = seen[letter]
            # Fadal User Manual section 1: "L Subroutine definition or call" (L<nn>00 opens subroutine nn,
            # M17 ends it; L<nn><count> calls it)
            fadal = " (a Fadal subroutine definition or call: use --dialect fadal)" if letter == "L" and \
                w.value >= 100 and w.value == int(w.value) else ""
            if letter == "Q" and gcodes.get("motion", (None,))[0] == 51:  # Fanuc 0i-MF "AI contour control"
                fadal = (" (G05.1 Q1 / Q0 is Fanuc's AI contour control, look-ahead on / off: --dialect fanuc; "
                         "LinuxCNC's G5.1 is a quadratic spline through I J)")
            where.fail(f"unknown word {w.text!r} outside a drilling cycle{fadal}", column=w.column, text=w.text,
                       expected=f"{letter} only in drilling cycles (G73, G83)" if letter == "Q" else
                       f"{letter} only in drilling cycles or G10")


def _unused_words(seen, gcodes, st: State, notes: Notes) -> None:
    """H and D words without the compensation that reads them: noted (Fanuc posts write them apart); under the
    ``linuxcnc`` dialect the note says that LinuxCNC refuses them (rs274 2.9: "H word with no G43 or G76 to use it",
    "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it")."""
    if "position offset" in gcodes:  # G45-G48 read them
        return
    refused = "; LinuxCNC refuses it" if st.context.dialect.name == "linuxcnc" else ""
    if "H" in seen and "length compensation" not in gcodes:
        notes.add(f"H word without G43 (ignored{refused})")
    if "D" in seen and "cutter compensation" not in gcodes:
        notes.add(f"D word without G41/G42 (ignored{refused})")


def _m98_words(words: list[Word], where: Where, *, st: State, notes: Notes) -> None:
    """Words of an M98 line LinuxCNC reads and does not execute (:func:`interpolators.iso_flow.run`)."""
    notes.add(f"{' '.join(w.text for w in words)} on an M98 line not executed (LinuxCNC runs an M98 block as a "
              "call only, as o<n> call; Fanuc and Haas would)")
    feed = next((w for w in words if w.letter == "F"), None)
    if feed is not None and st.feed is None:
        st.uncalled_feed = f"{feed.text} of the M98 line {where.line}"


def _incremental_g53(st: State, notes: Notes) -> bool:
    """True when a G53 block's words are increments: G53 under G91 in the Fanuc and Haas dialects (LinuxCNC refuses
    it, grbl's gcode.c takes them as machine positions: "ignore if absolute override is active").

    The Fanuc-style manuals at hand write G53 with absolute words ("(G90) G53 X... Y... Z...", "Absolute dimension
    word", "The G53 command has to be determined by using absolute values": Siemens' 840D ISO-dialect milling
    manual, 3.1.1 "Machine coordinate system (G53)"; no Fanuc manual text on G53 under G91 was found). Our
    reading follows the Fanuc-compatible Mitsubishi M700V
    programming manual, 14.4 "Basic Machine Coordinate System Selection; G53", (4): "In the incremental value
    command mode (G91), the G53 command provides movement with the incremental value": the axes move by the
    words from where they are (as a G91 block without G53 would), noted. Another Fanuc-compatible control reads it
    otherwise: the Allen-Bradley 8520 9/Series manual, 11.1.1, "the control ignores the G53 code and any axis words
    in the G53 block" under G91 (no motion); the note says the block was read as increments, so a user of such a
    control sees where the readings part."""
    if not (st.incremental and st.context.dialect.name in ("fanuc", "haas")):
        return False
    notes.add("G53 under G91: its axis words moved as increments from the current position (Mitsubishi M700V "
              "14.4; Fanuc gives G53 absolute words only)")
    return True


def _nonmodal(gcodes, seen, st: State, blocks, used, where: Where, number, notes: Notes) -> bool:  # noqa: C901
    """G10, G28, G30, G53, G92 family. True when the block is fully handled here."""
    key, w = gcodes["nonmodal"]
    axis_words = [a for a in ("X", "Y", "Z") if a in seen]
    if key == 530:  # G53: this block's motion in machine coordinates
        motion = gcodes["motion"][0] if "motion" in gcodes else st.motion
        if motion not in (0, 10):
            mode = ("no motion mode is set yet" if motion is None
                    else f"the motion mode is {G_CODES.get(motion, (None, f'G{motion / 10:g}'))[1]}")
            where.fail(f"G53 needs G0 or G1 ({mode})", column=w.column, text=w.text,
                       expected="G53 G0/G1 with axis words")
        if st.incremental and st.context.dialect.name == "linuxcnc":  # rs274ngc interp_check.cc check_g_codes
            where.fail("G53 in incremental distance mode (G91): LinuxCNC refuses it (\"Cannot use G53 incremental\")",
                       column=w.column, text=w.text, expected="G90 before G53 (its words are absolute machine "
                       "coordinates), or --dialect fanuc/haas for a post written for them")
        if "motion" in gcodes:
            st.motion = motion
        if not axis_words and not any(a in seen for a in EXTRA_LETTERS):
            if "motion" not in gcodes and st.context.dialect.name == "linuxcnc":
                # rs274 check_g_codes tests the block's motion_to_be, the modal motion only when the block has axis
                # words: a bare "G53" (a FreeCAD Job's fixture G53, its fixture op writing the code alone) is
                # refused, "G53 G0" and "G53 X5" after G0 run
                where.fail("G53 without G0/G1 or axis words in its block: LinuxCNC refuses it (\"Must use G0 or G1 "
                           "with G53\")", column=w.column, text=w.text,
                           expected="G53 G0 X.. (a move in machine coordinates), or --dialect fanuc/grbl, where a "
                                    "bare G53 does nothing")
            if "length compensation" in gcodes:
                length_cancelled(st)
            return True  # no axis word: nothing moves (a Fanuc post's "G53 G49 M05")
        machine = not _incremental_g53(st, notes)
        # a Z in machine coordinates moves by its words alone; it and a G43/G49 of the block cancel the tool length
        # vector without moving Z (Fanuc 0i-MB 14.1.2, "G49 G53": restored by the next Z move, iso_offsets)
        target = block_target(seen, axis_words, st, machine=machine)
        motion_block(seen, gcodes, axis_words, [], target, st, blocks, used, where, number, machine=machine)
        if "Z" in axis_words or "length compensation" in gcodes:
            length_cancelled(st)
        return True
    if "P" in seen and key in (280, 281, 300, 301, 520, 530, 920, 921, 922, 923) and "path" not in gcodes \
            and "motion" not in gcodes:  # not G64's P, nor a cycle's or an arc's
        reference_p(key, seen, st, where, notes)
    if key in (280, 300):
        reference_return(key, seen, axis_words, st, blocks, used, where, number)
        notes.add("G28/G30 reference return")
        return True
    if key in (270, 290, 600):
        mill_positioning(key, seen, axis_words, st, blocks, used, where, number, notes)
        return True
    if key in (281, 301):
        if key == 281:
            st.home, st.home_extra = st.pos.copy(), st.extra.copy()
        else:
            st.reference2, st.reference2_extra = st.pos.copy(), st.extra.copy()
        return not linuxcnc_modal_axis_words(seen, st)
    if key == 520:
        refuse_wrapped_offset(seen, st, where, "G52")
        local_offset(seen, axis_words, st, where, w)
        notes.add("G52 local offset")
        return True
    if key == 920:
        _g92(seen, axis_words, st, where, w)
        notes.add("G92 offset")
        return True
    if key in (921, 922):
        return _g92_reset(key, seen, st, where, w)
    if key == 923:
        st.g92, st.g92_extra = st.g92_saved.copy(), st.g92_extra_saved.copy()
        st.g92_applied = True
        return not linuxcnc_modal_axis_words(seen, st)
    if key == 100:
        if "L" in seen and seen["L"].value == 0:
            # LinuxCNC g-code.adoc "G10 L0 Reload Tool Table Data" (interp_convert.cc convert_modal_0: an
            # error with a tool loaded). vcnc's table is the one given, and the program's G10 L1 entries
            # are written to the table file too, so a reload changes nothing here.
            if st.tool_current:
                where.fail(f"G10 L0 not allowed with loaded tool T{st.tool_current}", column=w.column,
                           text=w.text, expected="M6 T0 (no tool in the spindle) before G10 L0")
            notes.add("G10 L0 tool table reload (table unchanged)")
            return True
        p = int(seen["P"].value) if "P" in seen else -1
        sets_system = "L" in seen and seen["L"].value in (2, 20)  # convert_setup: L1/L10/L11 P is a tool number
        if st.written_offsets and sets_system and (p == 0 or 0 < p <= len(WORK_OFFSETS) and
                                                   WORK_OFFSETS[p - 1] == st.wcs):  # LinuxCNC #5221 .. written
            take_written_offsets(st)
        notes.add(g10(seen, st, where, w))
        return True
    return False


def _g92_reset(key: int, seen, st: State, where: Where, w) -> bool:
    """G92.1 (G92 offset, its saved copy and the local system reset) and G92.2 (the G92 offset suspended); True
    when the block's axis words have no motion left to make.

    LinuxCNC and grbl take no axis words with them: those move by the modal motion (rs274ngc ``enhance_block``;
    grbl ``gcode.c``: "If axis words are passed here, they are interpreted as an implicit motion mode"). Fanuc's
    G92.1 is the workpiece coordinate system preset, ``G92.1 IP 0;``: the axes named are preset, the others keep
    their shift (Fanuc 0i-MD operator's manual B-64304EN, "Workpiece coordinate system preset"; the page was not in
    our search index: our reading of its format, whose axis words are written 0; another value is refused); without
    an axis word, every axis (our reading, as a LinuxCNC post's header ``G92.1`` means it)."""
    named = [i for i, a in enumerate("XYZ") if a in seen]
    extra = [i for i, a in enumerate(EXTRA_LETTERS) if a in seen]
    preset = key == 921 and (named or extra) and st.context.dialect.name not in ("linuxcnc", "grbl")
    if preset:
        nonzero = next((seen[a] for a in ("X", "Y", "Z", *EXTRA_LETTERS) if a in seen and seen[a].value != 0), None)
        if nonzero is not None:
            where.fail(f"G92.1 {nonzero.text.strip()}: the workpiece coordinate system preset names its axes with 0 "
                       "(Fanuc: G92.1 IP 0)", column=nonzero.column, text=nonzero.text,
                       expected=f"G92.1 {nonzero.letter}0 (the axes to preset)")
        for arrays, axes in (((st.g92, st.g92_saved, st.local), named), ((st.g92_extra, st.g92_extra_saved), extra)):
            for a in arrays:
                a[axes] = 0.0
        st.g92_applied = bool(np.any(st.g92) or np.any(st.g92_extra))
        return True
    if key == 921:
        st.g92_saved, st.g92_extra_saved, st.local = np.zeros(3), np.zeros(6), np.zeros(3)
    st.g92, st.g92_extra = np.zeros(3), np.zeros(6)
    st.g92_applied = False
    return not linuxcnc_modal_axis_words(seen, st)


def _g92(seen, axis_words: list[str], st: State, where: Where, w) -> None:
    """G92: the offset that makes the current position the block's axis words (LinuxCNC refuses a word of 360 deg or
    more on a wrapped rotary axis: :func:`interpolators.iso_axes.refuse_wrapped_offset`)."""
    refuse_wrapped_offset(seen, st, where, "G92")
    rot_words = [a for a in EXTRA_LETTERS if a in seen]
    if not axis_words and not rot_words and st.zero_words_dropped:
        return  # "G92 A0" on a machine without A: nothing to offset (noted as A0), as G52 A0 and G10 L2 A0
    if not axis_words and not rot_words:
        lathe = " (G92 S alone is the Fanuc lathe's maximum spindle speed: a lathe program)" if "S" in seen else ""
        where.fail(f"G92 needs at least one axis word{lathe}", column=w.column, text=w.text,
                   expected="G92 X.. Y.. Z..")
    # LinuxCNC convert_axis_offsets: offset = current + offset - value, in the (rotated) program frame; under
    # tool centre point control the current point is the tip on the part (iso_tcp.tip_point), our reading
    current = st.to_program(tip_point(st))
    for a in axis_words:
        i = "XYZ".index(a)
        st.g92[i] = current[i] + st.g92[i] - seen[a].value * st.scale
        st.local[i] = 0.0  # Fanuc: G92 cancels the local system (G52) of the axes it names
    # A-W as X-Z (LinuxCNC emccanon.cc rotate_and_offset_pos adds the G92 offset of all nine axes):
    # the offset that makes the axis' current position the programmed value
    v = word_values({a: seen[a].value for a in rot_words}, scale=st.scale)
    given = ~np.isnan(v)
    work = st.extra_offset() - st.g92_extra
    st.g92_extra[given] = (st.extra - work - v)[given]
    st.g92_saved, st.g92_extra_saved = st.g92.copy(), st.g92_extra.copy()
    st.g92_applied = True
