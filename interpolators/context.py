"""Machine context of a part program: what a control knows besides the program text.

A real control runs a program against its own tables: work offsets (G54-G59, G92), the tool
table (length and radius per tool), its home and second reference positions (G28/G30), and the
dialect of the language it speaks (unit of ``G04 P``, default units, default path mode). The
readers of both dialects take one :class:`MachineContext`; the machine TOML fills it
(``[program]`` tables, see ``vcnc machines --show``), and the defaults change nothing: zero
offsets, an empty tool table (tool length and radius 0), home at the origin.

Positions are machine coordinates [mm]; the program's coordinates are machine coordinates minus
the active work offset and tool length offset, as in LinuxCNC
(https://linuxcnc.org/docs/html/gcode/coordinates.html) and Fanuc.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping
from types import MappingProxyType
from typing import ClassVar

import numpy as np

from interpolators.arcs import ARC_RULES
from interpolators.rotary_wrap import ROTARY_AXES, WRAP_DIRECTIONS
from interpolators.tilted import Kinematics
from vcnc.core.axes import EXTRA_NAMES
from vcnc.core.errors import InputError

__all__ = ["Tool", "TouchProbe", "Dialect", "MachineContext", "DIALECTS", "WORK_OFFSETS", "DEFAULT_CONTEXT",
           "INTERPOLATION_CONTEXT",
           "read_tool_table", "read_tnc_tool_table", "read_datum_table", "tnc_table_rows", "EXTENDED_OFFSETS",
           "extended_offset", "work_offset_code",
           "FADAL_FIXTURES", "TOOL_OFFSET_MEMORIES", "PECK_TAPPING"]

#: Fanuc peck rigid tapping cycles (:attr:`Dialect.peck_tapping`; parameter PCP, No. 5200#5 = 0 / 1).
PECK_TAPPING: tuple[str, ...] = ("high-speed", "standard")

#: Fanuc tool compensation memory types (:attr:`MachineContext.tool_offset_memory`).
TOOL_OFFSET_MEMORIES: tuple[str, ...] = ("A", "B", "C")

#: Work-offset codes in the order of LinuxCNC's coordinate systems 1-9 (P1-P9 of G10 L2).
WORK_OFFSETS: tuple[str, ...] = ("G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3")

#: Number of additional work offsets a table may hold: Fanuc ``G54.1 P1``-``P300`` (P1-P48 as standard, up to
#: P300 with the 300-set option: Fanuc 0i-MD B-64304EN "Adding workpiece coordinate systems"); Haas ``G154
#: P1``-``P99`` (Haas mill operator's manual "G154 Select Work Coordinates P1-P99") are the same table.
EXTENDED_OFFSETS = 300

_EXTENDED = re.compile(r"G0*54\.1\s*P0*(\d+)|G0*154\s*P0*(\d+)|G0*1([12]\d)")

#: Fadal fixture offsets ``E1``-``E48`` (Fadal User Manual, section 1 NC word summary: "E Fixture offset"; G10
#: L02 P1-48 writes them, helmancnc.com "Fadal G Codes M Codes Fixed Subroutines"): one numbered table, whose
#: first six entries a Format 2 program may also select as G54-G59 (the Fusion Fadal post writes offset n as
#: ``E<n>`` or, n <= 6, ``G<53+n>``), so E1-E6 are the keys G54-G59 and E7-E48 are keys of their own.
FADAL_FIXTURES = 48
_FADAL = re.compile(r"E0*(\d+)")


def extended_offset(n: int) -> str:
    """Code of additional work offset ``n`` (1 .. :data:`EXTENDED_OFFSETS`): ``"G54.1 P<n>"``."""
    if not 1 <= n <= EXTENDED_OFFSETS:
        raise InputError(f"additional work offset P{n}: expected P1 .. P{EXTENDED_OFFSETS}")
    return f"G54.1 P{n}"


def work_offset_code(code: str) -> str:
    """The table key of a work-offset code: one of :data:`WORK_OFFSETS`, or ``"G54.1 P<n>"`` for an
    additional offset written ``G54.1 P<n>`` (Fanuc, n <= 300), ``G154 P<n>`` (Haas, n <= 99) or
    ``G110``-``G129`` (Haas: G154 P1-P20; Haas "G154 Select Work Coordinates P1-P99"), or a Fadal fixture
    offset ``E1``-``E48`` (``"G54"``-``"G59"`` for E1-E6, ``"E7"``-``"E48"`` beyond: :data:`FADAL_FIXTURES`).

    Raises
    ------
    InputError
        Not a work-offset code.
    """
    text = str(code).strip().upper()
    if text in WORK_OFFSETS:
        return text
    m = _FADAL.fullmatch(text)
    if m is not None and 1 <= int(m.group(1)) <= FADAL_FIXTURES:
        n = int(m.group(1))
        return WORK_OFFSETS[n - 1] if n <= 6 else f"E{n}"
    m = _EXTENDED.fullmatch(text)
    if m is not None:
        if m.group(1) is not None:
            n = int(m.group(1))
        elif m.group(2) is not None:
            n = int(m.group(2)) if 1 <= int(m.group(2)) <= 99 else 0
        else:
            n = int(m.group(3)) - 9 if 10 <= int(m.group(3)) <= 29 else 0
        if 1 <= n <= EXTENDED_OFFSETS:
            return extended_offset(n)
    raise InputError(f"unknown work offset {code!r}: expected one of {', '.join(WORK_OFFSETS)}, "
                     f"G54.1 P1 .. G54.1 P{EXTENDED_OFFSETS} (Fanuc), G154 P1 .. G154 P99 or G110 .. G129 (Haas), "
                     f"E1 .. E{FADAL_FIXTURES} (Fadal fixture offsets; E1-E6 are G54-G59)")


def _xyz(value, name: str) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise InputError(f"{name} must be three finite numbers (x, y, z) [mm], got {value!r}")
    arr = arr.copy()
    arr.setflags(write=False)
    return arr


@dataclasses.dataclass(frozen=True, kw_only=True)
class Tool:
    """One entry of the tool table.

    Attributes
    ----------
    number : int
        Tool number (``T`` word, Heidenhain ``TOOL CALL n``), >= 0.
    length : float
        Tool length offset [mm] (G43 H / ``TOOL CALL``: added along the tool axis).
    radius : float
        Tool radius [mm] (G41/G42 D, Heidenhain RL/RR). A negative radius (a tool table holding the
        difference between the actual and a nominal diameter) makes G41 offset as G42 by its
        magnitude and G42 as G41 (LinuxCNC ``interp_convert.cc`` convert_cutter_compensation_on).
    comment : str
        Free text (LinuxCNC tool tables carry one; a Heidenhain TOOL.T its DOC column).
    name : str
        The tool's name (a Heidenhain tool table's NAME column, ``TOOL CALL "NAME"``); empty if none.
    offset_x, offset_y : float
        Tool offsets along X and Y [mm] (LinuxCNC tool-table columns X and Y, ``G10 L1 X.. Y..``;
        lathe tools, or a milling head with an offset spindle): G43 applies them with the length, the
        program's X and Y point then lies this far from the machine's (LinuxCNC g-code.adoc "G43":
        "all the tool's offsets are applied").
    length_wear, radius_wear : float
        The wear part of ``length`` and ``radius`` [mm] (Fanuc/Haas offset tables keep geometry and wear
        apart and apply their sum: ``G10 L11``/``L13`` set the wear, ``L10``/``L12`` the geometry =
        ``length - length_wear``, ``radius - radius_wear``); 0 for a LinuxCNC tool table.
    point_angle : float
        The point angle of a drill or countersink [deg], in (0, 180]; 0: none; 180: a flat end (a tool table may
        hold it for any tool: our reading, the end reaches the full diameter at the tip). A Heidenhain tool table's
        T-ANGLE column ("Point angle for DRILL and CSINK T-ANGLE", iTNC 530 technical manual 07/2013, 9.5.4,
        FN 18 ID50 NR32): cycles 200/203/205 with Q395 = 1 and 240 with Q343 = 1 take their depth from it.
    """

    number: int
    length: float = 0.0
    radius: float = 0.0
    comment: str = ""
    offset_x: float = 0.0
    offset_y: float = 0.0
    length_wear: float = 0.0
    radius_wear: float = 0.0
    name: str = ""
    point_angle: float = 0.0

    def __post_init__(self) -> None:
        if int(self.number) != self.number or self.number < 0:
            raise InputError(f"tool number must be an integer >= 0, got {self.number!r}")
        if not 0.0 <= self.point_angle <= 180.0:
            raise InputError(f"tool {self.number}: point angle must lie in [0, 180] [deg] (0: none), got "
                             f"{self.point_angle!r}")
        if not math.isfinite(self.length):
            raise InputError(f"tool {self.number}: length must be finite [mm], got {self.length!r}")
        if not math.isfinite(self.radius):
            raise InputError(f"tool {self.number}: radius must be finite [mm], got {self.radius!r}")
        if not (math.isfinite(self.length_wear) and math.isfinite(self.radius_wear)):
            raise InputError(f"tool {self.number}: wear must be finite [mm], got {self.length_wear!r}, "
                             f"{self.radius_wear!r}")
        if not (math.isfinite(self.offset_x) and math.isfinite(self.offset_y)):
            raise InputError(f"tool {self.number}: X/Y offsets must be finite [mm], got "
                             f"{self.offset_x!r}, {self.offset_y!r}")


@dataclasses.dataclass(frozen=True, kw_only=True)
class TouchProbe:
    """The workpiece touch probe's row of a Heidenhain touch probe table (TCHPROBE.TP), which the touch probe
    cycles ``TCH PROBE 4xx`` read (TNC 320 cycle programming manual 340 55x-04, "Executing touch probe
    cycles" and the touch probe table's columns; :mod:`interpolators.heidenhain_probing`). The defaults are
    our reading (typical values of a probe row, not found in the manuals of our search index): a machine's
    table holds its own.

    Attributes
    ----------
    set_up : float
        Column SET_UP: the safety clearance [mm] the cycles add to their set-up clearance Q320.
    feed : float
        Column F: the probing feed [mm/min].
    fmax : float
        Column FMAX: the rapid traverse of the cycles' pre-positioning and moves between touch points [mm/min].
    dist : float
        Column DIST: the longest probing path [mm]; a touch point farther than it is never reached (an error).
    tip_radius : float or None
        Radius of the stylus tip [mm]; None (the default): the active tool's radius (``TOOL CALL`` of the
        probe, its R in ``TOOL DEF`` or the tool table), as the TNC takes the probe's data from its tool row.
    """

    #: The units of the fields (the machine file's ``[program.touch_probe]`` names them in its errors).
    UNITS: ClassVar[dict[str, str]] = {"set_up": "mm", "feed": "mm/min", "fmax": "mm/min", "dist": "mm",
                                       "tip_radius": "mm"}
    TABLE: ClassVar[str] = "the touch probe table row"

    set_up: float = 2.0
    feed: float = 100.0
    fmax: float = 2000.0
    dist: float = 20.0
    tip_radius: float | None = None

    def __post_init__(self) -> None:
        for name in ("set_up", "feed", "fmax", "dist"):
            value = getattr(self, name)
            if not (math.isfinite(value) and (value > 0 or (name == "set_up" and value == 0))):
                raise InputError(f"touch probe: {name} must be {'>= 0' if name == 'set_up' else '> 0'}, got {value!r}")
        if self.tip_radius is not None and not (math.isfinite(self.tip_radius) and self.tip_radius >= 0):
            raise InputError(f"touch probe: tip_radius must be >= 0 [mm], got {self.tip_radius!r}")


@dataclasses.dataclass(frozen=True, kw_only=True)
class Dialect:
    """What differs between controls that read the same words.

    Attributes
    ----------
    name : str
        ``"linuxcnc"``, ``"fanuc"``, ``"haas"``, ``"grbl"``, ``"fadal"`` or ``"heidenhain"``.
    dwell_p_unit : {"s", "ms"}
        Unit of ``G04 P``: seconds in LinuxCNC and grbl, milliseconds (integer P) in Fanuc, Haas and
        Fadal ("G4 Dwell P= Time in Milliseconds", helmancnc.com's Fadal list).
    default_units : {"mm", "inch"}
        Units of a program that states neither G20 nor G21 (a warning note is given).
    continuous_path : bool
        Path mode of a program that states neither G61 nor G64: True (continuous path, G64) on
        every control listed here.
    tolerance : float or None
        Path tolerance of the default continuous-path mode [mm]; ``None`` selects
        :data:`interpolators.DEFAULT_TOLERANCE`.
    arc_rule : {"linuxcnc", "grbl"}
        Whose check of an arc's end point applies (:func:`interpolators.arcs.center_arc_tolerance`):
        LinuxCNC's absolute and relative tolerances, or grbl's (0.005 mm, 0.1 % of the radius, at
        most 0.5 mm; no excess of an R arc's chord over the diameter). Fanuc and Haas check against
        a machine parameter (Fanuc No. 3410) and use LinuxCNC's rule here.
    tap_out_to_r : bool
        G84 tapping and G89 boring feed out to the R plane and rapid on to the clear level (Fanuc, Haas:
        True); LinuxCNC feeds out to the clear level (False).
    subroutine_path : tuple of str
        Folders searched for ``<name>.ngc`` of an ``o<name> call`` after the program's own folder
        (LinuxCNC INI ``[RS274NGC] SUBROUTINE_PATH``); a relative folder starts at the program's.
    user_m_path : tuple of str
        Folders searched for the executable file ``M100`` ... ``M199`` of a user M code (LinuxCNC INI
        ``[RS274NGC] USER_M_PATH`` and ``[DISPLAY] PROGRAM_PREFIX``): a code whose file is there runs as
        an external program the control waits for, moving nothing of the path (noted); without it the
        code is an error. A relative folder starts at the program's.
    initial_feed : float or None
        Feed [mm/min] of a feed move (G01, G02, G03, a drilling cycle) that comes before any F word: the
        control's power-on feed, a machine setting (FANUC parameter No. 1411, "cutting feedrate" at power-on
        and reset, which "eliminates the need for specifying a cutting feedrate (F code) in the NC program":
        FANUC 0i-D/0i-F parameter manuals B-64310EN/B-64610EN as issue #18 quotes them, the text itself not
        found in our search index; Beckhoff TwinCAT CNC channel parameter P-CHAN-00099
        ``prog_start.feedrate``, "when a feed block (G01/G02/G03) is programmed, the velocity should be 1000
        mm/min if the F word is missing",
        https://infosys.beckhoff.com/content/1033/tf5200_channel_parameter/149303051.html; Smoothieware's
        ``default_feed_rate``, "default rate (mm/minute) for G1/G2/G3 moves"; Marlin's
        ``DEFAULT_FEEDRATE_MM_M``). None (the default): such a move is an error, as on LinuxCNC ("Cannot do
        G1 with zero feed rate") and grbl (error 22). When set, it applies under every dialect (a note says
        so, and that LinuxCNC and grbl refuse the move); it never replaces an F0, a G95 feed per revolution
        or the F a G94 after G93 needs.
    rapid_feed_stop : bool
        Whether the control stops where a rapid (G00, FMAX) meets a feed move (G01, G02, G03), either way,
        whatever the path mode: True on LinuxCNC, Fanuc, Haas and Fadal, False on grbl and the TNC, whose
        look-ahead passes that junction at speed as any other (:func:`interpolators.interpolate.interpolate`).
        Sources: LinuxCNC ``src/emc/tp/tp.c`` ``handleModeChange`` (older ``tpCheckCanonType``): where one of two
        consecutive moves is a traverse and the other not, "Blending disabled: can't blend between rapid and feed
        motions", the first ends in ``TC_TERM_COND_STOP``. FANUC Series 30i/31i/32i-MA user's manual B-63944EN/02,
        4.1 "Positioning (G00)": "In the positioning mode actuated by G00, the tool is accelerated to a
        predetermined speed at the start of a block and is decelerated at the end of a block. Execution proceeds to
        the next block after confirming the in-position"
        (http://www.cncmanuals.com/fanuc/773/30i-300i-300is-ma-31i-310i-310is-ma-a5-32i-320i-320is-ma-common-to-lathe-machining-center-users-manual/page/82;
        a stop after the rapid; our reading of "accelerated ... at the start of a block": the rapid starts from rest
        after a feed move too, the cutting mode G64 passing only the end of a cutting block at speed, 0i-PC
        B-64154EN/01 Table 5.4). Haas mill operator's manual, G00: "The machine waits until all motions are complete
        before starting the next command", Setting 57 changing "how closely the machine waits for a precise stop
        before and after a rapid move" (https://scribd.com/document/534599821/G00). Fadal reads Fanuc's Format 2
        (our reading: its rapids stop as Fanuc's). grbl ``grbl/planner.c`` ``plan_buffer_line``: every block's entry
        speed is bounded by the junction deviation alone (only a system motion, homing or parking, starts at rest),
        the rapid flag setting only its nominal speed (``plan_compute_profile_nominal_speed``). HEIDENHAIN: no TNC
        manual we found names a stop at an FMAX block's end; an ``L ... FMAX`` block is a straight line at the rapid
        rate within the look-ahead and cycle 32's tolerance as any other (the TNC 425/415 B/407 user's manual rounds
        an FMAX block's corner with M112: "L X+123.723 Y+25.491 R0 FMAX M124 T0.01",
        https://azmanual.top/manuals/797829/heidenhain-tnc-407-280-580-user-manual.html?page=167); our reading: it
        is blended.
    feed_mode_clears_feed : bool
        Whether every G94 or G95 word sets the feed rate to 0, even when that feed mode is already active (True:
        LinuxCNC, ``src/emc/rs274ngc/interp_convert.cc`` ``convert_feed_mode``: ``settings->feed_rate = 0.0`` on
        each G_94 and G_95, so ``F100 / G1 X1 / G94 / G1 X2`` is "Cannot do g1 with zero feed rate" in rs274; the
        block's own F applies after it, ``G94 G1 X2 F50`` runs). False: only a change of feed mode clears it (G94
        after G93, G95 on or off; grbl ``gcode.c``: "feed rate is undefined" after G93 -> G94). LinuxCNC's G-code
        reference ("G93, G94, G95"; Tormach's PathPilot copy, https://tormach.com/feed-rate-mode-g93-g94-and-g95)
        words it "A new feed rate is not specified after switching to G94 or G95" as an error. Fanuc and Haas: their
        manuals give G94 as the feed-per-minute mode and G93's cancel ("G93, Inverse Time Mode OFF and G94, Feed
        Per Minute ON", http://diy.haascnc.com/reference-docs/inverse-time-and-feed-minute-modes), naming no reset
        of a modal F (our reading: the F stays).
    length_offset_motion : bool
        Whether a change of the tool length offset (G43/G44 H.., a new H under G43, G49; Fadal's H word) is an axis
        movement of the control (True: Fanuc, Haas, Fadal) or a shift of the program's coordinates (False: LinuxCNC,
        grbl). Fanuc performs tool length compensation "by an axis movement" unless parameter TOS (No. 5006#6) is
        1, which shifts the coordinate system instead (FANUC Series 30i/31i/32i-MODEL A connection manual
        (function) B-63943EN-1/02, 12.5.2 "Tool Length Compensation Shift Types", which under TOS = 1 says "If no
        move command is specified together with the G43, G44, or G49 command, the tool will not move along the
        axis", http://cncmanuals.com/fanuc/529/30i-300i-300is-model-a-31i-310i-310is-model-a-and-a5-32i-320i-320is-model-a-connection-manual-function/page/1682):
        the change of the offset vector is added to the programmed travel, so a ``G91 Z-50.`` in the block that
        applies a 50 mm tool length (FreeCAD's Fanuc post: ``G91 G0 G43 G54 Z-[#[2000+#4120]] H#4120``) leaves
        the machine where it was, where LinuxCNC moves it 50 mm down (g-code.adoc "G43": "The next time a
        compensated axis is moved, that axis's endpoint is the compensated location"). Under G90 both end at the
        programmed Z plus the new offset. vcnc adds the change not yet travelled to the next incremental Z word of a
        G00-G03 block (:func:`interpolators.iso_offsets.length_travel`); an absolute Z word takes it up; a G43, G44
        or G49 block of G00 or G01 without a Z word (``G43 H1`` alone, ``G49 X0 Y0``) moves Z by the change in that
        block, at its rapid or feed (:func:`interpolators.iso_offsets.length_moves_now`: what 12.5.2 says TOS = 1
        does not do), under G90 and G91 alike; an arc or a canned cycle leaves it to the next Z word. Z at its
        reference (G28, G30) or at a machine coordinate (G53) cancels the offset vector, G43 staying, and the next Z
        move restores it (Fanuc 0i-MB B-63844EN/02 14.1.2; :func:`interpolators.iso_offsets.length_cancelled`): a
        ``G49`` after ``G91 G28 Z0`` moves nothing. Haas (its G43
        "Tool Length Compensation + (Add)" takes the Fanuc words) and Fadal (its Format 2 is Fanuc's) follow
        Fanuc's default here: no Haas or Fadal text we found says otherwise. A machine file's ``[program]
        length_offset_motion`` sets it for its machine (false: Fanuc TOS = 1).
    fanuc_feed : bool
        Whether F is measured as a Fanuc measures it (True: ``fanuc``) or along the X Y Z path (False: RS274/NGC 3,
        Sec. 2.1.2.5, LinuxCNC, grbl's three axes; Haas and Fadal: no text we found says otherwise). A Fanuc takes
        a helix's F along its arc in the plane, the third axis following (FANUC Series 15i/150i-MODEL B connection
        manual (function) B-63783EN-1/01, 6.7 "Helical interpolation B": "If HTG is set to 0, a feedrate along an
        arc is specified by an F command. Therefore, the feedrate on a linear axis is F x length of linear axis /
        length of circular arc"; HTG, parameter No. 1401#2, 0 by default; 16/18 B-63002EN "Helical interpolation":
        "The feedrate along the circumference of two circular interpolated axes is the specified feedrate"), and a
        line's F along every axis it moves, a rotary axis' degrees counted as lengths in the input unit (FANUC Power
        Mate i-D/H operator's manual B-63174EN/03, 4.2 "Linear interpolation (G01)": "When the straight line axis
        alpha (such as X, Y, or Z) and the rotating axis beta (such as A, B, or C) are linearly interpolated, the
        feed rate is that in which the tangential feed rate in the alpha and beta cartesian coordinate system is
        commanded by F"; "G91 G01 X20.0 C40.0 F300.0 ; This changes the unit of the C axis from 40.0 deg to 40mm
        with metric input", so the block takes sqrt(20^2 + 40^2) / 300 = 0.14907 min).
    peck_tapping : {"high-speed", "standard"} or None
        Fanuc's peck rigid tapping cycle, which an ``M29 S.. / G84 (G74) .. Q..`` block runs (Q the depth of each
        cut): the machine's parameter PCP (No. 5200#5). ``"high-speed"`` (PCP = 0, the high-speed peck tapping
        cycle): each cut of Q, then back by :attr:`peck_tapping_d` (the spindle reversed), then on by d + Q;
        ``"standard"`` (PCP = 1, the peck tapping cycle): each cut of Q, then back to point R, then in to d above
        the depth cut (d the "cutting start distance") and on by Q, every move at the tapping feed (the spindle
        synchronised with the axis). FANUC Series 16i/18i/21i-TA/TB additional manual A-78549E, 3.4 "Peck rigid
        tapping cycle" (http://www.cncmanuals.com/fanuc/700/fanuc-series-16i-18i-21i-additional-manual/page/11):
        "Q_ : Depth of cut for each cutting feed", PCP (No. 5200#5), "d = Cutting start distance", the figure of
        the operations; the 0i-F / 30i mill operator's manuals' "Peck rigid tapping cycle (G84 or G74)" name the
        same parameters (their pages are not in our search index). None (the default): the machine does not say,
        and such a block is refused by name (:func:`interpolators.iso_rigid_tap.rigid_tap_peck`), the manuals
        giving no default for PCP or d. Only the ``fanuc`` dialect reads it.
    peck_tapping_d : float or None
        d [mm] of the peck rigid tapping cycle, parameter No. 5213 (the retraction of the high-speed peck, the
        clearance above the depth cut of the standard one): >= 0, set with :attr:`peck_tapping`.
    """

    name: str = "linuxcnc"
    dwell_p_unit: str = "s"
    default_units: str = "mm"
    continuous_path: bool = True
    tolerance: float | None = None
    arc_rule: str = "linuxcnc"
    tap_out_to_r: bool = False
    subroutine_path: tuple[str, ...] = ()
    user_m_path: tuple[str, ...] = ()
    initial_feed: float | None = None
    rapid_feed_stop: bool = True
    feed_mode_clears_feed: bool = True
    length_offset_motion: bool = False
    fanuc_feed: bool = False
    peck_tapping: str | None = None
    peck_tapping_d: float | None = None

    def __post_init__(self) -> None:
        if self.peck_tapping is not None and self.peck_tapping not in PECK_TAPPING:
            raise InputError(f"dialect {self.name}: peck_tapping must be one of {', '.join(PECK_TAPPING)}, "
                             f"got {self.peck_tapping!r}")
        if (self.peck_tapping is None) != (self.peck_tapping_d is None):
            raise InputError(f"dialect {self.name}: peck_tapping (Fanuc PCP, No. 5200#5) and peck_tapping_d (d, "
                             "No. 5213) are set together")
        if self.peck_tapping_d is not None and not (math.isfinite(self.peck_tapping_d) and self.peck_tapping_d >= 0):
            raise InputError(f"dialect {self.name}: peck_tapping_d must be >= 0 [mm], got {self.peck_tapping_d!r}")
        if self.initial_feed is not None and not (math.isfinite(self.initial_feed) and self.initial_feed > 0):
            raise InputError(f"dialect {self.name}: initial_feed must be > 0 [mm/min], got {self.initial_feed!r}")
        if self.arc_rule not in ARC_RULES:
            raise InputError(f"dialect {self.name}: arc_rule must be one of {', '.join(ARC_RULES)}, "
                             f"got {self.arc_rule!r}")
        if self.dwell_p_unit not in ("s", "ms"):
            raise InputError(f"dialect {self.name}: dwell_p_unit must be 's' or 'ms', got {self.dwell_p_unit!r}")
        if self.default_units not in ("mm", "inch"):
            raise InputError(f"dialect {self.name}: default_units must be 'mm' or 'inch', "
                             f"got {self.default_units!r}")
        if self.tolerance is not None and not (math.isfinite(self.tolerance) and self.tolerance > 0):
            raise InputError(f"dialect {self.name}: tolerance must be > 0 [mm], got {self.tolerance!r}")


#: Built-in dialects (``--dialect NAME``). Sources: LinuxCNC G-code reference (G4 P in seconds,
#: http://linuxcnc.org/docs/html/gcode/g-code.html#gcode:g4); Fanuc 0i / Haas mill manuals (G04 P
#: in milliseconds without a decimal point); grbl wiki (G4 P in seconds).
DIALECTS: Mapping[str, Dialect] = MappingProxyType({
    "linuxcnc": Dialect(name="linuxcnc", dwell_p_unit="s"),
    "fanuc": Dialect(name="fanuc", dwell_p_unit="ms", tap_out_to_r=True, feed_mode_clears_feed=False,
                     length_offset_motion=True, fanuc_feed=True),
    "haas": Dialect(name="haas", dwell_p_unit="ms", tap_out_to_r=True, feed_mode_clears_feed=False,
                    length_offset_motion=True),
    "grbl": Dialect(name="grbl", dwell_p_unit="s", arc_rule="grbl", rapid_feed_stop=False,
                    feed_mode_clears_feed=False),
    # Fadal VMC (interpolators.iso_fadal): Format 2 (Fanuc-like) with Fadal's own words; units and path mode
    # are machine settings there (G20/G21 only check them), vcnc's defaults (mm, continuous path) apply
    "fadal": Dialect(name="fadal", dwell_p_unit="ms", tap_out_to_r=True, feed_mode_clears_feed=False,
                     length_offset_motion=True),
    "heidenhain": Dialect(name="heidenhain", dwell_p_unit="s", rapid_feed_stop=False, feed_mode_clears_feed=False),
})


@dataclasses.dataclass(frozen=True, kw_only=True)
class MachineContext:
    """Tables and settings a control applies to a program.

    Attributes
    ----------
    work_offsets : mapping of str to ndarray (3,)
        Work-offset table, keyed by code (``"G54"`` ... ``"G59.3"``, see :data:`WORK_OFFSETS`, and the
        additional offsets ``"G54.1 P1"`` ... ``"G54.1 P300"``; ``"G154 P<n>"`` and ``"G110"``-``"G129"``
        name the same entries, see :func:`work_offset_code`) [mm, machine coordinates]. Missing codes
        are zero. G54 is active at program start. Fadal fixture offsets ``"E7"`` ... ``"E48"`` are keys of their
        own (E1-E6 are G54-G59; ``"E0"``, no fixture offset, is always zero and cannot be set).
    tools : mapping of int to Tool
        Tool table by tool number. A tool missing from it has length and radius 0 (with a note).
    home : ndarray (3,)
        Home position, where every program starts, and G28's reference point [mm, machine].
    reference2 : ndarray (3,)
        Second reference position, G30's [mm, machine].
    dialect : Dialect
        Dialect of the ISO reader (the Heidenhain reader ignores it but for ``tolerance``).
    extra_axes : tuple of str
        The axes beyond X, Y, Z the machine has, among ``vcnc.core.axes.EXTRA_NAMES``: rotary
        ``"a"``, ``"b"``, ``"c"`` [deg] and secondary linear ``"u"``, ``"v"``, ``"w"`` [mm],
        parallel to X, Y, Z; words of others are errors naming the axis (``A0``, ``U0`` are
        accepted with a note). A machine file sets them from its ``[axes.a]`` ... tables;
        :data:`INTERPOLATION_CONTEXT` has all six.
    linear_units : {"mm", "inch"}
        Length unit of the control's own configuration (LinuxCNC INI ``[TRAJ] LINEAR_UNITS``). Tables
        and positions here are mm whatever it is; it only says in which unit a program reads the stored
        offsets through system parameters (``#5161``.. G28/G30 positions, ``#5211``.. G92, ``#5221``..
        work offsets, ``#5401``.. tool offsets: :mod:`interpolators.iso_system`), as LinuxCNC keeps them
        in its INI units whatever G20/G21 says (tests/interp/unit-conversion). rs274's standalone
        interpreter, which LinuxCNC's own tests run, is an inch machine.
    decimal_point_input : {"calculator", "increment"}
        How a Fanuc control reads a distance, angle or time written without a decimal point (parameter
        DPI, No. 3401#0; :mod:`interpolators.iso_decimal`): ``"calculator"`` (DPI = 1, the default here:
        ``X10`` is 10 mm, as Haas, LinuxCNC and grbl read it; a Fanuc program with such words gets a
        note) or ``"increment"`` (DPI = 0, Fanuc's own default: in least input increments of IS-B,
        ``X10`` is 0.010 mm or 0.0010 in). Only the ``fanuc`` dialect reads it.
    tool_offset_memory : {"A", "B", "C"}
        A Fanuc control's tool compensation memory (Fanuc 0i-MD B-64304EN "Tool compensation values"; Series
        0i-MODEL B connection manual B-63833EN-1 "Tool compensation memory"): what ``G10 L10``-``L13`` and the
        tool offset variables ``#2001``.., ``#10001``.. set and read (:mod:`interpolators.iso_offsets`). ``"C"``
        (the default here): geometry and wear apart, and apart for H (length) and D (radius), as vcnc's tool
        table keeps them; ``"B"``: one geometry and one wear per offset number, which H and D share; ``"A"``:
        one value per offset number. Only the ``fanuc`` dialect reads it (Haas has its own variables).
    kinematics : Kinematics or None
        The rotary axes that tilt the part for a tilted working plane (Heidenhain ``PLANE``, cycle 19;
        :mod:`interpolators.tilted`); None (the default): a tilt is an error naming the function.
    touch_probe : TouchProbe
        The workpiece touch probe's table row (Heidenhain ``TCH PROBE`` cycles).
    wrapped_axes : tuple of str
        The rotary axes (``"a"``, ``"b"``, ``"c"``, among ``extra_axes``) that wrap at 360 deg (modulo, roll-over
        axes: LinuxCNC ``WRAPPED_ROTARY``, Fanuc ROA, a TNC axis shown below 360 deg; machine file ``[axes.a] wrap =
        true``): an absolute word of one turns it by :attr:`wrap_direction` (:mod:`interpolators.rotary_wrap`).
        Empty (the default): every rotary axis is read as a linear one (350 deg, then ``A10``: -340 deg).
    wrap_direction : str or None
        The rule of an absolute move on those axes, one of :data:`interpolators.rotary_wrap.WRAP_DIRECTIONS`
        (``"sign"``: LinuxCNC, Fanuc RAB = 1; ``"shortest"``: Fanuc RAB = 0, TNC M126; ``"difference"``: the TNC
        without M126), or None (the default): the reader's control's own
        (:func:`interpolators.rotary_wrap.default_direction`).
    datum_table : mapping of int to ndarray (3,)
        The Heidenhain datum table (a ``.D`` file, :func:`read_datum_table`): row ``D`` to its X, Y, Z
        columns [mm], the shift ``CYCL DEF 7.1 #D`` selects (from the preset, in the workpiece coordinates:
        TNC7 user's manual 81762x-17, "Datum table *.d"). Empty (the default): the context has no datum
        table, and selecting a row is an error naming it.
    """

    work_offsets: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)
    tools: Mapping[int, Tool] = dataclasses.field(default_factory=dict)
    home: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))
    reference2: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(3))
    dialect: Dialect = dataclasses.field(default_factory=Dialect)
    extra_axes: tuple[str, ...] = ()
    linear_units: str = "mm"
    decimal_point_input: str = "calculator"
    tool_offset_memory: str = "C"
    kinematics: Kinematics | None = None
    touch_probe: TouchProbe = dataclasses.field(default_factory=TouchProbe)
    datum_table: Mapping[int, np.ndarray] = dataclasses.field(default_factory=dict)
    wrapped_axes: tuple[str, ...] = ()
    wrap_direction: str | None = None

    def __post_init__(self) -> None:
        if self.linear_units not in ("mm", "inch"):
            raise InputError(f"linear_units must be 'mm' or 'inch', got {self.linear_units!r}")
        if self.decimal_point_input not in ("calculator", "increment"):
            raise InputError(f"decimal_point_input must be 'calculator' or 'increment' (Fanuc DPI = 1 or 0), got "
                             f"{self.decimal_point_input!r}")
        if self.tool_offset_memory not in TOOL_OFFSET_MEMORIES:
            raise InputError(f"tool_offset_memory must be one of {', '.join(TOOL_OFFSET_MEMORIES)} (Fanuc tool "
                             f"compensation memory A, B, C), got {self.tool_offset_memory!r}")
        offsets = {}
        for code, value in dict(self.work_offsets).items():
            key = work_offset_code(code)
            if key in offsets:
                raise InputError(f"work offset {code!r} given twice (it is {key!r})")
            offsets[key] = _xyz(value, f"work offset {code}")
        object.__setattr__(self, "work_offsets", MappingProxyType(offsets))
        tools = {}
        for number, tool in dict(self.tools).items():
            if not isinstance(tool, Tool) or tool.number != number:
                raise InputError(f"tool table entry {number!r} must be a Tool with number {number!r}")
            tools[int(number)] = tool
        object.__setattr__(self, "tools", MappingProxyType(tools))
        rows = {}
        for row, value in dict(self.datum_table).items():
            if not isinstance(row, int) or row < 0:
                raise InputError(f"datum table row {row!r} must be a whole number >= 0")
            rows[row] = _xyz(value, f"datum table row {row}")
        object.__setattr__(self, "datum_table", MappingProxyType(rows))
        object.__setattr__(self, "home", _xyz(self.home, "home"))
        object.__setattr__(self, "reference2", _xyz(self.reference2, "reference2"))
        bad = [a for a in self.extra_axes if a not in EXTRA_NAMES]
        if bad:
            raise InputError(f"extra_axes must be among {', '.join(map(repr, EXTRA_NAMES))}, got {bad!r}")
        bad = [a for a in self.wrapped_axes if a not in ROTARY_AXES]
        if bad:
            raise InputError(f"wrapped_axes must be among {', '.join(map(repr, ROTARY_AXES))} (rotary axes), "
                             f"got {bad!r}")
        if self.wrap_direction is not None and self.wrap_direction not in WRAP_DIRECTIONS:
            raise InputError(f"wrap_direction must be one of {', '.join(WRAP_DIRECTIONS)} (or None: the control's "
                             f"own), got {self.wrap_direction!r}")
        if self.kinematics is not None and not isinstance(self.kinematics, Kinematics):
            raise InputError(f"kinematics must be an interpolators.tilted.Kinematics, got {self.kinematics!r}")

    def offset(self, code: str) -> np.ndarray:
        """Work offset of ``code`` (``"G54"`` ..., ``"G54.1 P7"``, ``"E7"``, see :func:`work_offset_code`) [mm];
        zero when the table has none, and for Fadal's ``"E0"`` (no fixture offset)."""
        value = self.work_offsets.get(code)
        if value is None and code == "E0":  # Fadal E0: no fixture offset
            return np.zeros(3)
        return value if value is not None else self.work_offsets.get(work_offset_code(code), np.zeros(3))

    def tool(self, number: int) -> Tool | None:
        """The tool table's entry for ``number``, or None when the table has none."""
        return self.tools.get(int(number))

    def tool_named(self, name: str) -> Tool | None:
        """The tool table's entry named ``name`` (Heidenhain ``TOOL CALL "NAME"``), the lowest number first
        when several share it, or None."""
        hits = [t for t in self.tools.values() if t.name and t.name == name.strip()]
        return min(hits, key=lambda t: t.number) if hits else None

    def with_dialect(self, name: str) -> MachineContext:
        """This context read as the control ``name`` of :data:`DIALECTS` reads (``--dialect``): that dialect's
        rules, keeping this context's own settings (default units, path mode and tolerance, subroutine and
        user M paths, initial feed, the peck rigid tapping settings: a machine file's ``[program]``; the tool
        length rule ``length_offset_motion`` where it differs from its dialect's default, as a machine file sets
        it)."""
        if name not in DIALECTS:
            raise InputError(f"unknown dialect {name!r}: expected one of {', '.join(DIALECTS)}")
        old = self.dialect
        motion = DIALECTS[name].length_offset_motion
        if old.name in DIALECTS and old.length_offset_motion != DIALECTS[old.name].length_offset_motion:
            motion = old.length_offset_motion
        return dataclasses.replace(self, dialect=dataclasses.replace(
            DIALECTS[name], default_units=old.default_units, continuous_path=old.continuous_path,
            tolerance=old.tolerance, subroutine_path=old.subroutine_path, user_m_path=old.user_m_path,
            initial_feed=old.initial_feed, length_offset_motion=motion, peck_tapping=old.peck_tapping,
            peck_tapping_d=old.peck_tapping_d))


#: The context of a machine that states none: it changes nothing (a three-axis machine: X, Y, Z).
DEFAULT_CONTEXT = MachineContext()

#: The context of interpolation without a machine (``vcnc interpolate`` without ``--machine``, the
#: corpus benchmark): the default tables, and every axis beyond X, Y, Z (rotary a, b, c; secondary
#: linear u, v, w), so that 4- and 5-axis and XYUV programs read; ``vcnc simulate`` and
#: ``--machine`` use the machine's own axes instead.
INTERPOLATION_CONTEXT = MachineContext(extra_axes=EXTRA_NAMES)


def read_tool_table(path: str, *, units: str = "mm") -> dict[int, Tool]:
    """Read a LinuxCNC tool table (``T1 P1 D6.0 Z+12.5 ;comment`` per line), or a Heidenhain TOOL.T
    (a first line ``BEGIN TOOL .T MM|INCH``: :func:`read_tnc_tool_table`).

    Following LinuxCNC's tool-table format (https://linuxcnc.org/docs/html/config/tool-table.html):
    ``T`` tool number, ``P`` pocket (ignored), ``D`` diameter, ``Z`` tool length offset and ``X``
    ``Y`` tool offsets in the machine's units (``units``: ``"mm"``, or ``"inch"`` for a table of an
    inch machine, converted to mm); other offsets (``A B C U V W I J Q``) are read and ignored.
    Lines that are empty or only a comment are skipped.

    Raises
    ------
    InputError
        Unreadable file, or a line without ``T`` or with a malformed word (file and line named).
    """
    if units not in ("mm", "inch"):
        raise InputError(f"tool table units must be 'mm' or 'inch', got {units!r}")
    scale = 25.4 if units == "inch" else 1.0
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            lines = fh.read().splitlines()
    except OSError as exc:
        raise InputError(f"{path}: cannot read tool table: {exc.strerror or exc}") from None
    if lines and _TNC_TABLE_BEGIN.match(lines[0]):
        return read_tnc_tool_table(path, lines)
    tools: dict[int, Tool] = {}
    word = re.compile(r"([A-Za-z])\s*([+-]?(?:\d+\.?\d*|\.\d+))")
    for lineno, raw in enumerate(lines, start=1):
        code, _, comment = raw.partition(";")
        if not code.strip():
            continue
        words: dict[str, float] = {}
        pos = 0
        for m in word.finditer(code):
            if code[pos:m.start()].strip():
                break
            words[m.group(1).upper()] = float(m.group(2))
            pos = m.end()
        if code[pos:].strip():
            raise InputError(f"{path}:{lineno}: malformed tool-table word {code[pos:].split()[0]!r}; "
                             "expected words such as T1 P1 D6.0 Z+12.5")
        if "T" not in words:
            raise InputError(f"{path}:{lineno}: tool-table line without a T word; expected T<number> ...")
        number = int(words["T"])
        tools[number] = Tool(number=number, length=words.get("Z", 0.0) * scale,
                             radius=words.get("D", 0.0) * scale / 2.0, comment=comment.strip(),
                             offset_x=words.get("X", 0.0) * scale, offset_y=words.get("Y", 0.0) * scale)
    return tools


_TNC_TABLE_BEGIN = re.compile(r"\s*BEGIN\s+\S*\s*\.T\s+(MM|INCH)\b", re.I)
_TNC_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)$")


def tnc_table_rows(lines: list[str]) -> list[tuple[int, dict[str, str]]]:
    """The rows of a Heidenhain table file (TOOL.T, a datum table .D): text with fixed column widths, a
    ``BEGIN`` line, a header line whose column names start where their columns start, one line per row, and
    ``[END]``. Each row as its 1-based line number and its fields by column name (stripped text)."""
    header = lines[1].rstrip()
    starts = [m.start() for m in re.finditer(r"\S+", header)]
    names = header.split()
    rows = []
    for lineno, raw in enumerate(lines[2:], start=3):
        if not raw.strip() or raw.strip().upper() == "[END]":
            continue
        rows.append((lineno, {name: raw[a:b].strip() for name, a, b in zip(names, starts, starts[1:] + [len(raw)])}))
    return rows


def read_tnc_tool_table(path: str, lines: list[str]) -> dict[int, Tool]:
    """Read a Heidenhain tool table TOOL.T (iTNC 530, TNC 320/620/640, TNC7).

    The file is text with fixed column widths: ``BEGIN TOOL .T MM`` (or ``INCH``), a header line whose
    column names start where their columns start (``T NAME L R R2 DL DR ... DOC``), one line per tool,
    and ``[END]``. Following the TNC7 user's manual "Tool table tool.t" (HEIDENHAIN 81762x-17): ``T`` the
    tool number (an index after the period: ``5.1`` is index 1 of tool 5), ``NAME`` the tool name (up
    to 32 characters, may hold spaces), ``L`` the length and ``R`` the radius, ``DL`` and ``DR`` their
    oversizes ("is added to the parameter L"), ``DOC`` a comment, ``T-ANGLE`` the point angle of a drill
    (:attr:`Tool.point_angle`). The other columns (R2, tool life,
    kinematics, ...) are read past. Indexed rows are left out: vcnc's tool table has no indices, and
    ``TOOL CALL 5.1`` takes tool 5's data with a note.

    Raises
    ------
    InputError
        No header line with T, L and R columns, or a malformed number (file and line named).
    """
    scale = 25.4 if _TNC_TABLE_BEGIN.match(lines[0]).group(1).upper() == "INCH" else 1.0
    if len(lines) < 2 or not re.match(r"\s*T\s", lines[1]):
        raise InputError(f"{path}:2: Heidenhain tool table without its header line; expected the column names "
                         "T NAME L R ... after the BEGIN line")
    names = lines[1].split()
    missing = [c for c in ("T", "L", "R") if c not in names]
    if missing:
        raise InputError(f"{path}:2: Heidenhain tool table header without column {missing[0]}; expected "
                         "T NAME L R ... (the TNC's TOOL.T)")
    tools: dict[int, Tool] = {}
    for lineno, fields in tnc_table_rows(lines):
        def number(col: str, *, lineno: int = lineno, fields: dict = fields) -> float:
            text = fields.get(col, "")
            if not text:
                return 0.0
            if not _TNC_NUMBER.match(text):
                raise InputError(f"{path}:{lineno}: column {col} holds {text!r}, not a number; expected the "
                                 "TOOL.T columns under the header's names (fixed widths)")
            return float(text)

        t = fields["T"]
        if not re.fullmatch(r"\d+(\.\d+)?", t):
            raise InputError(f"{path}:{lineno}: tool number {t!r} is not a number; expected T as 0..32767[.index]")
        if "." in t and int(t.split(".")[1]) != 0:
            continue
        n = int(t.split(".")[0])
        try:
            tools[n] = Tool(number=n, name=fields.get("NAME", ""), comment=fields.get("DOC", ""),
                            length=(number("L") + number("DL")) * scale, radius=(number("R") + number("DR")) * scale,
                            point_angle=number("T-ANGLE"))
        except InputError as exc:  # a T-ANGLE outside [0, 180]: named where it is
            raise InputError(f"{path}:{lineno}: {exc.message}; expected the TOOL.T columns under the header's "
                             "names") from None
    return tools


_TNC_DATUM_BEGIN = re.compile(r"\s*BEGIN\s+\S*\.D\s+(MM|INCH)\b", re.I)


def read_datum_table(path: str) -> dict[int, np.ndarray]:
    """Read a Heidenhain datum table (a ``.D`` file: ``BEGIN ZEROSHIFT.D MM``, a header ``D X Y Z ...``, one
    line per row, ``[END]``; the fixed widths of :func:`tnc_table_rows`) into :attr:`MachineContext.datum_table`.

    Following the TNC7 user's manual "Datum table *.d" (HEIDENHAIN 81762x-17): ``D`` the row number, ``X``, ``Y``,
    ``Z`` the datum, "a shift in the workpiece coordinate system W-CS" [mm, or inch in an INCH table, converted
    to mm]; an empty field is 0. The columns A, B, C, U, V, W (offsets of those axes in the machine coordinates)
    and DOC are read past.

    Raises
    ------
    InputError
        Unreadable file, no BEGIN ... .D line or no header with D, or a malformed number (file and line named).
    """
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            lines = fh.read().splitlines()
    except OSError as exc:
        raise InputError(f"{path}: cannot read datum table: {exc.strerror or exc}") from None
    begin = _TNC_DATUM_BEGIN.match(lines[0]) if lines else None
    if begin is None:
        raise InputError(f"{path}:1: not a Heidenhain datum table; expected a first line BEGIN <name>.D MM (or INCH)")
    if len(lines) < 2 or "D" not in lines[1].split():
        raise InputError(f"{path}:2: Heidenhain datum table without its header line; expected the column names "
                         "D X Y Z ... after the BEGIN line")
    scale = 25.4 if begin.group(1).upper() == "INCH" else 1.0
    rows: dict[int, np.ndarray] = {}
    for lineno, fields in tnc_table_rows(lines):
        if not re.fullmatch(r"\d+", fields["D"]):
            raise InputError(f"{path}:{lineno}: row number {fields['D']!r} is not a whole number; "
                             "expected D as 0, 1, 2 ...")
        bad = [c for c in "XYZ" if fields.get(c) and not _TNC_NUMBER.match(fields[c])]
        if bad:
            raise InputError(f"{path}:{lineno}: column {bad[0]} holds {fields[bad[0]]!r}, not a number; expected "
                             "the columns under the header's names (fixed widths)")
        rows[int(fields["D"])] = np.array([float(fields.get(c) or 0.0) * scale for c in "XYZ"])
    return rows
