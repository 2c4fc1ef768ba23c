"""System parameters of ISO G-code: the machine state a program reads through ``#5000`` and above.

LinuxCNC "Numbered Parameters" (https://linuxcnc.org/docs/html/gcode/overview.html#sub:numbered-parameters;
``interp_convert.cc`` ``get_abs_position``, ``rs274ngc_pre.cc``), all read-only here:

========================= ==========================================================================
``#5021``-``#5029``       current machine position (G53: no work, G92 or tool length offset) X Y Z A B C
                          U V W, in program units (mm or inch; rotary axes deg)
``#5061``-``#5070``       probe result: an error (G38 probing is not supported)
``#5081``-``#5089``       tool length offset in effect (G43/G43.1; Z only, 0 under G49), program units
``#5161``-``#5169``       G28 reference position, ``#5181``-``#5189`` G30's [machine units, deg]
``#5210``                 1 while a G92/G52 offset is applied; ``#5211``-``#5219`` that offset, kept
                          while G92.2 suspends it [machine units]
``#5220``                 coordinate system number 1-9 (G54 .. G59.3)
``#5221``-``#5230``       G54 offset X Y Z A B C U V W and rotation R [machine units, deg], ``#5241``.. G55, every 20
                          up to ``#5381``-``#5390`` G59.3
``#5399``                 the result of the last M66 wait on input, 0 before one (:mod:`interpolators.iso_mcodes`)
``#5400``                 tool in the spindle (0 when none); ``#5401``-``#5409`` its stored offsets (Z:
                          length), ``#5410`` its diameter [machine units]
``#5420``-``#5428``       current position in the active coordinate system with all offsets, program
                          units (an error under cutter compensation, as LinuxCNC)
========================= ==========================================================================

The stored tables (offsets, references, tools) read in the machine's configured length unit
(:attr:`interpolators.context.MachineContext.linear_units`, mm unless set), whatever G20/G21 says, as
LinuxCNC keeps them in its INI units (tests/interp/unit-conversion: "the numbered parameters that back
the work and axis offsets stay constant because they are stored in user INI units"); positions follow
G20/G21 (X Y Z U V W); rotary axes (deg) are never scaled.

Fanuc and Haas (custom macro B system variables, Fanuc 0i-MD B-64304EN "System variables"; Haas
mill operator's manual "Macros", "#5001-#5006 block end position", "#5021-#5026 present machine
coordinate position", "#5041-#5046 present work coordinate position"): under those dialects
``#5001``-``#5008`` is the end point of the last block and ``#5041``-``#5048`` the current position,
both in work coordinates, as ``#5420``.. (the two are the same in a reader that moves block by block), but for
the tool offsets: ``#5001``.. is the programmed end point, ``#5041``.. the position of the tool with its length
offset "included" (Fanuc's position-information table: block end point "Not included", current position in the
workpiece coordinate system "Included", as the Fanuc-compatible YASNAC LX3 manual's table gives it, ABSIO / ABSOT;
shop macros read the current work Z as ``#735 = #5043 - #[2000 + #4111]``, "current work Z: start point Z", and
Renishaw's O9816 as ``#27 = #5043 - #116``): after ``G43 H1 Z10.`` with a 20 mm tool ``#5003`` reads 10 and
``#5043`` 30. Under Haas the same (our reading: Haas's table numbers them as Fanuc's and says nothing of the offsets);
under tool centre point control both read the tip's position (below).

Under those dialects the modal information reads too (Fanuc 0i-MD "System variables", "Modal
information"; Haas "#4001-#4021 last block group codes"): ``#4001`` motion G0-G3 (in a canned cycle, group 09,
the group 01 code the cycle left in force), ``#4002`` plane
17/18/19, ``#4003`` 90/91, ``#4005`` 94/93/95, ``#4006`` 20/21, ``#4007`` 40/41/42, ``#4008``
43/43.1/44/49, ``#4009`` 80 or the cycle, ``#4010`` 98/99, ``#4011`` 50/51 (scaling), ``#4012`` 66/66.1/67
(:mod:`interpolators.iso_modal_call`, ``fanuc`` only: 67 under ``haas``), ``#4013`` 97 (no G96 on a mill),
``#4014`` 54-59, ``#4015`` 61/64,
``#4016`` 68/69, ``#4022`` 50.1/51.1 (mirror); ``#4107`` the D number of the compensation in effect,
``#4109`` F [program units/min], ``#4111`` the H number of the length offset, ``#4119`` S [rev/min],
``#4120`` T (the tool in the spindle). The others (``#4004``, ``#4017``.., ``#4102``.., ``#4113``..)
are not modelled: reading one is an error naming it.

Under those dialects a program may also write the work offsets (Fanuc 0i-MD "System variables":
"workpiece zero point offset value ... read/write"; Haas "Macros", "Offsets": "all tool work offsets
can be read and set within a macro expression"): ``#5221``-``#5326`` (G54-G59: X Y Z A B C, 20 per
system), the additional ones below, and the external offset ``#5201``-``#5206`` (as ``G10 L2 P0``; Haas: its G52
entry; fuzz40); the offset changes at once, as ``G10 L2`` would
(:func:`set_system_parameter`). LinuxCNC's stay read-only here (its #5221.. back the offsets and change
with G10, not the other way round).

The tool offset variables read and write the tool table (:class:`interpolators.context.Tool`: length = geometry
+ wear), in the machine's length unit: Haas's ``#2001``-``#2800`` (Haas macro variables, "Tool Offsets": length
geometry, length wear, diameter geometry, diameter wear of tools 1-200), and Fanuc's by its tool compensation
memory (:attr:`interpolators.context.MachineContext.tool_offset_memory`; memory C: ``#11001``.. / ``#2201``.. H
geometry, ``#10001``.. / ``#2001``.. H wear, ``#13001``.. D geometry, ``#12001``.. D wear), the registers
:func:`interpolators.iso_offsets.tool_offset_variable` names and ``G10 L10``-``L13`` sets. Under memory A and B
one offset number serves H and D: writing it sets the tool's length and radius; reading it gives their common
value, or the one that is not 0, and is an error naming both when the machine's table holds two different
ones. A Fanuc variable the memory does not have (``#13001`` under memory B) is an error naming the memory.
Haas ``#3026`` ("Tool in spindle", read only) is the tool in the spindle, as ``#4120``.

The parts counters ``#3901`` (number of machined parts) and ``#3902`` (number of required parts) read and write
under those dialects (Fanuc 0i-MD B-64304EN "System variables": "#3901 Number of machined parts, #3902 Number of
required parts, read/write"; Haas "Macros": "#3901 M30 count 1, #3902 M30 count 2"). They count finished parts
and move nothing; the virtual machine's counters are 0 when the program starts (our reading: a machine the
program is the first to run on), and a program that reads them is noted (:attr:`ReaderState.parts_read`).

The clocks are not read (Fanuc 0i-MD B-64304EN "System variables"; Haas "Macros" #3001 millisecond
timer, #3002 hour timer, and Haas's own timers #3020-#3025, power-on, cycle start, feed and part timers, all but the
power-on timer #3020 ("read only") reset as #3001 is;
Mike Lynch, "Converting Time and Date to a More Useful Format", Modern Machine Shop 2019:
``#3001`` the milliseconds clock "always runs, can be reset using #3001=0", ``#3002`` the hours clock likewise,
``#3011`` the date yyyymmdd and ``#3012`` the time hhmmss, which "cannot be reset"). A program writes ``#3001 = 0``
or ``#3002 = 0`` to start timing: accepted, without effect. Reading one is an error naming it (where the
value is only stored in a common variable, the variable holds it: :mod:`interpolators.iso_params`): the clocks count the
time the machine has run, which depends on the feeds, accelerations and servo lags the interpolation and
simulation work out after the program is read, and on how long the control takes per macro statement, which no
manual gives; the value may steer the program (a wait ``WHILE [#3001 LT 2000]``, a tool-life count), so no
reading of the text alone fixes it. The date and time are those of a run, which a program file does not fix.

The additional work offsets of Fanuc (``G54.1 P``: ``#7001``.., ``#14001``..) and Haas (``G154 P``,
``G110``-``G129``) read under those dialects (:mod:`interpolators.iso_offsets`), with ``#4014`` = 54.1
(Haas 154) and ``#4130`` = the P number while one is selected; ``#5201``-``#5203`` the external offset
(Fanuc; Haas: its G52 entry) G10 L2 P0 sets (``#5204``-``#5206`` 0); ``#5220`` (LinuxCNC's system number 1-9)
is then not modelled.

A position read after a program stop (``M0``, ``M1``, ``M60``) before the next move is where the
operator may have jogged the machine, which a program file does not say: it reads the position where
the program stopped (the operator pressing start without a jog, as on a dry run) and the reader notes
the stop's line (``stops_read``), as the Heidenhain reader does for ``FN 18 SYSREAD`` after STOP.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

import numpy as np

from interpolators.context import WORK_OFFSETS, MachineContext, Tool
from interpolators.iso_offsets import (
    ToolRegister,
    extended_number,
    fanuc_tool_variable,
    offset_parameter,
    set_external_axis,
    tool_offset,
    tool_offset_variable,
    with_tool_offset,
)
from interpolators.rotary_wrap import within_turn
from interpolators.tcp import part_point

if TYPE_CHECKING:
    from interpolators.iso_cycles import CycleWords
    from interpolators.iso_modal_call import ModalCalls
    from interpolators.iso_transforms import Frame

__all__ = ["ReaderState", "system_parameter", "set_system_parameter", "named_state_parameter",
           "set_reference_parameter", "set_work_offset_parameter", "take_written_offsets", "POSITION_PARAMETERS"]

#: Fanuc/Haas parts counters: machined parts, required parts.
PARTS_COUNTERS = (3901, 3902)
#: Fanuc/Haas clocks (module docstring): the milliseconds and hours clocks a program may reset, the date and time.
_CLOCKS = {3001: "the milliseconds clock", 3002: "the hours clock", 3011: "the date", 3012: "the time of day"}
_RESETTABLE_CLOCKS = (3001, 3002)
#: Haas's timers (zappettiniconsulting.com/wiki/haas-system-variables, from the Haas mill operator's manual "Macros",
#: "System variables": #3020 power on timer (read only), #3021 cycle start timer, #3022 feed timer, #3023 present part
#: timer, #3024 last complete part timer, #3025 previous part timer): like the clocks, the time the machine has run.
_HAAS_TIMERS = {3020: "Haas's power-on timer", 3021: "Haas's cycle start timer", 3022: "Haas's feed timer",
                3023: "Haas's present part timer", 3024: "Haas's last complete part timer",
                3025: "Haas's previous part timer"}
#: The Haas timers a program may reset (the same table: all but #3020, "read only"), as it may the clocks #3001/#3002.
_HAAS_RESETTABLE_TIMERS = (3021, 3022, 3023, 3024, 3025)
#: Parameters that report the current position (machine, program, Fanuc block end / work position).
POSITION_PARAMETERS = frozenset([*range(5021, 5030), *range(5420, 5429), *range(5001, 5009), *range(5041, 5049)])


class ReaderState(Protocol):
    """What :func:`system_parameter` reads of the ISO executor's modal state."""

    context: MachineContext
    tools: dict[int, Tool]  # tool table entries the program wrote
    external: np.ndarray  # Fanuc/Haas G10 L2 P0 offset [mm]
    external_extra: np.ndarray  # its a, b, c [deg], u, v, w [mm]
    pos: np.ndarray  # machine coordinates [mm]
    extra: np.ndarray  # a, b, c [deg], u, v, w [mm], machine positions
    wcs: str
    g92: np.ndarray
    g92_extra: np.ndarray
    g92_saved: np.ndarray
    g92_applied: bool
    tool_length: float
    tool_current: int | None
    home: np.ndarray | None
    reference2: np.ndarray | None
    home_extra: np.ndarray
    reference2_extra: np.ndarray
    g92_extra_saved: np.ndarray
    extra_offsets: dict[str, np.ndarray]
    offsets: dict[str, np.ndarray]
    rotations: dict[str, float]
    comp_side: str | None
    stop_line: int  # the line of the last program stop
    stops_read: set[int]  # the stops a position was read after
    comp_code: str
    stopped: bool
    motion: int | None
    plane: int
    incremental: bool
    inverse_time: bool
    inverse_rate: float | None  # the rate of the last G93 move [units/min] (iso_motion.move_feed)
    inch: bool
    retract_r: bool
    exact_stop: bool
    feed: float | None
    feed_rotary: float | None  # the F word as written / 60
    feed_per_rev_word: float | None  # the F word as written under G95
    per_rev: bool
    frame: Frame | None
    length_code: float
    length_number: int
    comp_number: int
    spindle_speed: float
    modal_calls: ModalCalls | None  # Fanuc G66/G66.1 in force
    cycle: CycleWords  # the canned-cycle series (its motion_before: the group 01 code it left)
    parts_counters: dict[int, float]  # Fanuc/Haas #3901, #3902 as the program set them
    parts_read: bool  # the program read a parts counter
    input_result: float | None  # LinuxCNC #5399 (iso_mcodes, M66)
    input_unknown: str
    tcp: int  # tool centre point control in force (iso_tcp), 0 off
    after_g80: bool
    arc_incremental: bool
    tool_selected: int | None
    tool_xy: np.ndarray
    spindle_turning: bool
    spindle_ccw: bool
    mist: bool
    flood: bool
    overrides: dict[str, bool]  # LinuxCNC M48-M53 (iso_mcodes.OVERRIDES_AT_START)
    written_offsets: dict[str, dict[int, float]]  # LinuxCNC #5221.. of the system in force, not yet taken
    rotations: dict[str, float]

    @property
    def scale(self) -> float: ...

    def to_program(self, machine: np.ndarray) -> np.ndarray: ...

    def extra_offset(self) -> np.ndarray: ...

    def tool(self, number: int) -> Tool | None: ...


def _nine(linear: np.ndarray, extra: np.ndarray, scale: float) -> list[float]:
    """X Y Z and U V W (divided by ``scale``), A B C (deg) from ``linear`` (x, y, z) and ``extra``
    (a, b, c, u, v, w)."""
    return [*(float(v) / scale for v in linear), *(float(v) for v in extra[:3]), *(float(v) / scale for v in extra[3:])]


def _stored(st: ReaderState) -> float:
    """mm per unit of the stored tables' parameters (the machine's configured length unit)."""
    return 25.4 if st.context.linear_units == "inch" else 1.0


def _position(n: int, st: ReaderState, fanuc: bool) -> tuple[float | None, str]:
    base = 5021 if n < 5030 and n >= 5021 else 5420 if n >= 5420 else (5001 if n < 5009 else 5041)
    if base in (5001, 5041) and not fanuc:
        return None, ""  # LinuxCNC: user parameters
    if st.stopped:
        st.stops_read.add(st.stop_line)  # noted by the reader: a jog at the stop is not modelled
    if base == 5021:
        return _rolled(_nine(st.pos, st.extra, st.scale), st, fanuc)[n - 5021], ""
    if st.comp_side is not None:
        return None, "the current position cannot be read with cutter radius compensation on (LinuxCNC)"
    # under tool centre point control the program's X Y Z are the tip's on the part (iso_tcp.tip_point), so the
    # end point and the current position in work coordinates are the tip's: a position read back and programmed
    # again does not move (our reading; FANUC 30i A-79348E 1.1: in G43.4 "the tool center point ... is
    # specified" by the program)
    point = part_point(st.context.kinematics, st.extra, st.pos, st.tool_length) if st.tcp else st.pos
    program = st.to_program(point)
    if base == 5041 and not st.tcp:  # Fanuc's current position: the tool offsets included (docstring)
        program = program + np.array([st.tool_xy[0], st.tool_xy[1], st.tool_length])
    values = _nine(program, st.extra - st.extra_offset(), st.scale)
    return _rolled(values, st, fanuc)[n - base], ""


def _rolled(values: list[float], st: ReaderState, fanuc: bool) -> list[float]:
    """``values`` (X Y Z A B C U V W) with the angles of the axes the machine wraps at 360 deg reduced to [0, 360)
    under Fanuc and Haas, whose roll-over axis shows its coordinates within one rotation (Fanuc Series 0i-MC
    B-63534EN/02, 20.2.1 "Rotary axis roll-over": A0, then ``G90 A-150.``: "absolute coordinate value after
    movement end" 210; Power Mate i B-63172EN/01, 7.5: "The rotation axis roll-over function rounds the absolute
    coordinate value and relative coordinate value ... within one rotation", 7.4: "The machine coordinate system is
    always normalized to the range from 0deg to 360deg"). LinuxCNC's interpreter reads them unwrapped (rs274
    2.9.0~pre1 with ``WRAPPED_ROTARY``: 350 deg then ``A10``, ``#5423`` = 370), as the blocks carry them."""
    wrapped = st.context.wrapped_axes
    if not fanuc or not wrapped:
        return values
    return [within_turn(v) if 3 <= i < 6 and "abc"[i - 3] in wrapped else v for i, v in enumerate(values)]


def _work_offset(n: int, st: ReaderState) -> float | None:
    k, j = divmod(n - 5221, 20)
    if k >= len(WORK_OFFSETS) or j > 9:
        return None
    code = WORK_OFFSETS[k]
    if j in st.written_offsets.get(code, {}):
        return st.written_offsets[code][j]
    if j == 9:
        return float(st.rotations.get(code, 0.0))
    return _offset_axis(code, j, st)


def _offset_axis(code: str, j: int, st: ReaderState) -> float:
    """Axis ``j`` (X Y Z A B C U V W; 0 beyond) of work offset ``code`` as the program sees it [mm, deg]."""
    off = st.offsets.get(code)
    xyz = st.context.offset(code) if off is None else off
    if j >= 9:
        return 0.0
    return _nine(xyz, st.extra_offsets.get(code, np.zeros(6)), _stored(st))[j]


def _tool(n: int, st: ReaderState) -> float | None:
    number = st.tool_current or 0
    if n == 5400:
        return float(number)
    tool = st.tool(number) if number else None
    if n in range(5401, 5410):
        if tool is None or n not in (5401, 5402, 5403):
            return 0.0
        return float({5401: tool.offset_x, 5402: tool.offset_y, 5403: tool.length}[n]) / _stored(st)
    if n == 5410:
        return 0.0 if tool is None else 2.0 * float(tool.radius) / _stored(st)
    return None


def _tool_register(n: int, st: ReaderState) -> tuple[ToolRegister | None, str]:
    """The tool offset register Fanuc/Haas variable ``#n`` names, or None with why (empty: ``#n`` is none)."""
    dialect, memory = st.context.dialect.name, st.context.tool_offset_memory
    register = tool_offset_variable(n, dialect, memory)
    if register is None and dialect == "fanuc" and fanuc_tool_variable(n):
        return None, (f"a tool offset variable that tool compensation memory {memory} does not have (the machine's "
                      "[program] tool_offset_memory: A, B or C)")
    return register, ""


def _tool_offset(register: ToolRegister, st: ReaderState) -> tuple[float | None, str]:
    """The value of a tool offset register in the machine's unit, or None with why."""
    tool = st.tool(register.number)
    value = tool_offset(tool, register)
    if value is None:
        return None, (f"offset {register.number} is one register for H and D under tool compensation memory "
                      f"{st.context.tool_offset_memory}, but the tool table holds length {tool.length:g} and radius "
                      f"{tool.radius:g} mm for it")
    return value / _stored(st), ""


def _fanuc_modal(n: int, st: ReaderState) -> float | None:
    """Fanuc/Haas modal information #4001.. (the G code of each group in effect, F and T)."""
    if n == 4001:  # group 01; a canned cycle (group 09) leaves it as it was (G80 or a group 01 code ends the cycle)
        motion = st.cycle.motion_before if st.motion is not None and st.motion >= 730 else st.motion
        return motion / 10 if motion in (0, 10, 20, 30) else None
    if n == 4009:
        return st.motion / 10 if st.motion is not None and st.motion >= 730 else 80.0
    extended = extended_number(st.wcs)
    if extended:
        wcs = "154" if st.context.dialect.name == "haas" else "54.1"
    else:
        wcs = st.wcs[1:]
    table = {4130: float(extended), 4002: {2: 17.0, 1: 18.0, 0: 19.0}[st.plane],
             4003: 91.0 if st.incremental else 90.0,
             4005: 95.0 if st.per_rev else 93.0 if st.inverse_time else 94.0, 4006: 20.0 if st.inch else 21.0,
             4007: 40.0 if st.comp_side is None else float(st.comp_code[1:3]), 4008: st.length_code,
             4010: 99.0 if st.retract_r else 98.0,
             4011: 51.0 if st.frame is not None and st.frame.factors != (1.0, 1.0, 1.0) else 50.0,
             4012: 67.0 if st.modal_calls is None else st.modal_calls.group_code,
             4013: 97.0, 4014: float(wcs), 4015: 61.0 if st.exact_stop else 64.0,
             4016: 68.0 if st.frame is not None and st.frame.rotation is not None else 69.0,
             4022: 51.1 if st.frame is not None and any(st.frame.mirror) else 50.1,
             4107: float(st.comp_number), 4109: 0.0 if st.feed is None else st.feed * 60.0 / st.scale,
             4111: float(st.length_number), 4119: st.spindle_speed, 4120: float(st.tool_current or 0)}
    return table.get(n)


def system_parameter(n: int, st: ReaderState, *, fanuc: bool = False) -> tuple[float | None, str]:
    """The value of system parameter ``#n`` from the reader's state, or ``(None, why)``.

    ``why`` is empty when vcnc does not model ``#n`` (the caller then reads the program's own
    parameter or reports it), else the reason it cannot be known (a jogged or probed position).
    """
    if n in POSITION_PARAMETERS:
        return _position(n, st, fanuc)
    if 4001 <= n <= 4130:
        return (_fanuc_modal(n, st) if fanuc else None), ""
    register, why = _tool_register(n, st) if fanuc else (None, "")
    if register is not None or why:
        return _tool_offset(register, st) if register is not None else (None, why)
    if fanuc and st.context.dialect.name == "haas" and n == 3026:  # Haas "Macros": #3026 tool in spindle
        return float(st.tool_current or 0), ""
    timer = _HAAS_TIMERS.get(n) if fanuc and st.context.dialect.name == "haas" else None
    if fanuc and (n in _CLOCKS or timer):
        if n in _RESETTABLE_CLOCKS or timer:
            return None, (f"{_CLOCKS.get(n, timer)}, which counts the time the machine has run: that time comes from "
                          "interpolating the program after it is read, so a program steered by it (a wait "
                          "WHILE [#3001 LT ..]) cannot be read; G04 waits a given time")
        return None, f"{_CLOCKS[n]} of a run, which a program file does not fix"
    if fanuc and n in PARTS_COUNTERS:
        st.parts_read = True
        return st.parts_counters.get(n, 0.0), ""
    if fanuc and 5201 <= n <= 5206:  # Fanuc external workpiece zero offset, Haas G52 (G10 L2 P0): X Y Z A B C
        return _nine(st.external, st.external_extra, _stored(st))[n - 5201], ""
    extended = offset_parameter(n, st.context.dialect.name) if fanuc else None
    if extended is not None:
        return _offset_axis(extended[0], extended[1], st), ""
    if 5061 <= n <= 5070:
        return None, "the probe result (G38 probing is not supported)"
    if 5081 <= n <= 5089:
        return (st.tool_length / st.scale if n == 5083 else 0.0), ""
    if 5161 <= n <= 5169 or 5181 <= n <= 5189:
        home = st.home if n < 5180 else st.reference2
        rot = (st.home_extra if n < 5180 else st.reference2_extra).copy()
        for a in st.context.wrapped_axes:  # G28.1/G30.1 store a wrapped axis' angle reduced to [0, 360) (LinuxCNC
            rot["abc".index(a)] = within_turn(rot["abc".index(a)])  # rs274 2.9.0~pre1: A370 reads 10, A-370 350)
        linear = np.zeros(3) if home is None else home
        return _nine(linear, rot, _stored(st))[n - (5161 if n < 5180 else 5181)], ""
    if n == 5210:
        return (1.0 if st.g92_applied else 0.0), ""
    if 5211 <= n <= 5219:  # the stored offset, kept while G92.2 suspends it (tests/interp/g52-g92-interaction)
        return _nine(st.g92_saved, st.g92_extra_saved, _stored(st))[n - 5211], ""
    if n == 5220:
        return (float(WORK_OFFSETS.index(st.wcs) + 1) if st.wcs in WORK_OFFSETS else None), ""
    if 5221 <= n <= 5390:
        return _work_offset(n, st), ""
    if 5400 <= n <= 5410:
        return _tool(n, st), ""
    if n == 5399 and not fanuc:
        return st.input_result, st.input_unknown
    return None, ""


#: LinuxCNC's version as its interpreter gives it (interp_namedparams.cc ``init_named_parameters``: ``sscanf`` of
#: PACKAGE_VERSION "2.9.0~pre1" into ``%lf%lf``, 2.9 and 0.0; "M.N.m" gives M.N and 0.m): vcnc reads LinuxCNC 2.9's
#: G-code and is checked against rs274 2.9.0~pre1 (benchmarks/linuxcnc_diff.py), whose values these are.
LINUXCNC_VERSION = {"_vmajor": 2.9, "_vminor": 0.0}
#: Predefined parameters whose value is the machine's and not the program's: errors naming why.
_UNKNOWN_NAMED = {
    "_current_pocket": "the tool changer's pocket of the tool in the spindle (LinuxCNC reads it from the tool table's "
                       "P column and [EMCIO] RANDOM_TOOLCHANGER; vcnc models no pockets)",
    "_selected_pocket": "the tool changer's pocket of the selected tool (LinuxCNC reads it from the tool table's P "
                        "column and [EMCIO] RANDOM_TOOLCHANGER; vcnc models no pockets)",
}


def _feed_word(st: ReaderState) -> float:
    """LinuxCNC ``#<_feed>``: the F number as last written (interp's ``feed_rate``), 0 before one and after the
    G94/G95 that clears it: a change of units since does not convert it (rs274 2.9.0~pre1: ``F600`` then ``G20``
    reads 600, the canon having taken 600 mm/min when F was set), under G95 the feed per revolution (``F0.01``
    reads 0.01). Under G93 it is the rate worked out for the last inverse-time move, its length x F in program units
    (interp_inverse.cc ``inverse_time_rate_straight``/``_arc``: ``settings->feed_rate = rate``; rs274 2.9.0~pre1;
    ``iso_motion.move_feed`` keeps it in ``inverse_rate``), the G94 F before the first
    (fuzz40, shopngc40)."""
    if st.per_rev:
        return 0.0 if st.feed_per_rev_word is None else float(st.feed_per_rev_word)
    if st.inverse_time and st.inverse_rate is not None:
        return st.inverse_rate
    return 0.0 if st.feed_rotary is None else st.feed_rotary * 60.0


def named_state_parameter(key: str, st: ReaderState) -> tuple[float | None, str]:
    """LinuxCNC's predefined named parameter ``#<key>`` (lower case) of the modal state: ``(value, "")``, ``(None,
    why)`` for one whose value is the machine's (the pockets: an error naming why), ``(None, "")`` for another name.

    overview.adoc "Predefined Named Parameters" and interp_namedparams.cc ``lookup_named_param``: the motion mode
    and plane as G code x 10 (``_motion_mode`` 10 in G1, 800 with none and after G80; ``_plane`` 170), ``_ccomp``
    400/410/420, 1 or 0 for ``_metric`` ``_imperial`` ``_absolute`` ``_incremental`` ``_inverse_time``
    ``_units_per_minute`` ``_units_per_rev`` ``_ijk_absolute_mode`` ``_tool_offset`` (an offset in force),
    ``_retract_r_plane`` (G99) and ``_retract_old_z`` (G98), ``_coord_system`` 540 .. 590, 591 .. 593 for G59.1 ..
    G59.3, ``_feed`` (:func:`_feed_word`) and ``_rpm`` (S), ``_selected_tool`` (the last T, 0 before any),
    ``_spindle_rpm_mode`` 1 (G97: vcnc has no G96), ``_lathe_radius_mode`` 1 (G8), ``_lathe_diameter_mode`` 0 and
    ``_remap_level`` 0 (no remaps); rs274 2.9.0~pre1 prints these for "G21 G0 X0" / "(DEBUG, #<_plane> ...)".

    The switches (active_m_codes): ``_spindle_on`` (M3/M4; M5, M19, M6 and the program end stop it), ``_spindle_cw``
    (M3 turning), ``_mist`` (M7) and ``_flood`` (M8) until M9, ``_feed_override`` ``_speed_override`` ``_adaptive_feed``
    ``_feed_hold`` as M48-M53 set them (1 1 0 1 at the start: :data:`interpolators.iso_mcodes.OVERRIDES_AT_START`);
    ``_metric_machine`` 1 on a machine in mm, 0 in inch (LinuxCNC's [TRAJ] LINEAR_UNITS, the machine's
    ``linear_units``; rs274 without that INI entry reads -1); ``_vmajor`` 2.9 and ``_vminor`` 0
    (:data:`LINUXCNC_VERSION`). ``_line`` and ``_task`` are :class:`interpolators.iso_params.Parameters`'."""
    if key in _UNKNOWN_NAMED:
        return None, _UNKNOWN_NAMED[key]
    if key[1:] in st.overrides:
        return float(st.overrides[key[1:]]), ""
    if key in LINUXCNC_VERSION:
        return LINUXCNC_VERSION[key], ""
    wcs = WORK_OFFSETS.index(st.wcs) + 1 if st.wcs in WORK_OFFSETS else 0
    values = {
        "_motion_mode": 800.0 if st.motion is None or st.after_g80 else float(st.motion),
        "_plane": {2: 170.0, 1: 180.0, 0: 190.0}[st.plane],
        "_ccomp": 400.0 if st.comp_side is None else float(st.comp_code[1:3]) * 10.0,
        "_metric": float(not st.inch), "_imperial": float(st.inch),
        "_absolute": float(not st.incremental), "_incremental": float(st.incremental),
        "_inverse_time": float(st.inverse_time), "_units_per_rev": float(st.per_rev),
        "_units_per_minute": float(not st.inverse_time and not st.per_rev),
        "_ijk_absolute_mode": float(not st.arc_incremental),
        "_tool_offset": float(bool(st.tool_length) or bool(np.any(st.tool_xy))),
        "_retract_r_plane": float(st.retract_r), "_retract_old_z": float(not st.retract_r),
        "_coord_system": float(530 + 10 * wcs if wcs < 7 else 584 + wcs) if wcs else None,
        "_feed": _feed_word(st), "_rpm": abs(st.spindle_speed),
        "_selected_tool": float(st.tool_selected or 0), "_spindle_rpm_mode": 1.0, "_spindle_css_mode": 0.0,
        "_lathe_radius_mode": 1.0, "_lathe_diameter_mode": 0.0, "_remap_level": 0.0,
        "_spindle_on": float(st.spindle_turning), "_spindle_cw": float(st.spindle_turning and not st.spindle_ccw),
        "_mist": float(st.mist), "_flood": float(st.flood),
        "_metric_machine": float(st.context.linear_units == "mm"),
    }
    return values.get(key), ""


def _offset_variable(n: int, st: ReaderState) -> tuple[str, int] | None:
    """The work offset and axis index (0-5: X Y Z A B C) a Fanuc/Haas offset variable ``#n`` names."""
    k, j = divmod(n - 5221, 20)
    if 0 <= k < 6 and n >= 5221:
        found: tuple[str, int] | None = (WORK_OFFSETS[k], j)
    else:
        found = offset_parameter(n, st.context.dialect.name)
    return found if found is not None and found[1] < 6 else None


def set_work_offset_parameter(n: int, value: float | None, st: ReaderState) -> bool:
    """LinuxCNC ``#n = value`` on a work offset, ``#5221``-``#5230`` (G54 X Y Z A B C U V W and the G10 R rotation)
    .. ``#5381``-``#5390`` (G59.3): True when ``#n`` is one. LinuxCNC keeps them as numbered parameters below #5400,
    which a program may write (overview.adoc "Numbered Parameters": "5221-5230 Coordinate System 1, G54 (X Y Z A B
    C U V W R)"), and takes the table into the offset in force when G54-G59.3 selects another system
    (interp_convert.cc ``convert_coordinate_system``, which does nothing for the system already in force): a write
    to another system's values is taken at its selection, one to the system in force waits in
    ``st.written_offsets`` for :func:`take_written_offsets` and reads back at once. rs274 2.9.0~pre1: ``#5241 = 10``
    then ``G55 G0 X0`` goes to X 10 (machine units); ``#5221 = 10`` under G54, then ``G0 X0``, stays at 0. In the
    machine's unit (:attr:`interpolators.context.MachineContext.linear_units`), A B C and R in deg."""
    k, j = divmod(n - 5221, 20)
    if not (0 <= k < len(WORK_OFFSETS) and n >= 5221 and j <= 9):
        return False
    code = WORK_OFFSETS[k]
    v = 0.0 if value is None else float(value)
    if code == st.wcs:
        st.written_offsets.setdefault(code, {})[j] = v
    else:
        _write_offset(code, j, v, st)
    return True


def take_written_offsets(st: ReaderState) -> None:
    """Take the values a LinuxCNC program wrote to the work offset in force (:func:`set_work_offset_parameter`) into
    its table: at the selection of another system, or a G10 L2/L20 that sets the table (convert_setup reads the
    parameters for the axes it is not given)."""
    for code, values in st.written_offsets.items():
        for j, v in values.items():
            _write_offset(code, j, v, st)
    st.written_offsets.clear()


def _write_offset(code: str, j: int, v: float, st: ReaderState) -> None:
    """Axis ``j`` (X Y Z A B C U V W R) of work offset ``code`` becomes ``v`` (the machine's unit; deg)."""
    if j == 9:
        st.rotations[code] = v
    elif j < 3:
        current = st.offsets.get(code)
        linear = (st.context.offset(code) if current is None else current).copy()
        linear[j] = v * _stored(st)
        st.offsets[code] = linear
    else:
        extra = st.extra_offsets.get(code, np.zeros(6)).copy()
        extra[j - 3] = v if j < 6 else v * _stored(st)
        st.extra_offsets[code] = extra


def set_reference_parameter(n: int, value: float | None, st: ReaderState) -> bool:
    """LinuxCNC ``#n = value`` on the G28 (``#5161``-``#5169``) or G30 (``#5181``-``#5189``) position, X Y Z A B C U V W
    in machine coordinates: the next G28 / G30 goes there (numbered parameters below #5400 are the program's to
    write; interp_convert.cc ``convert_home`` reads them, ``USER_TO_PROGRAM_LEN``: in the machine's unit; a
    tool-change subroutine saves and restores the G30 position so: ``#5181 = #<_G30_oldX>``). True when ``#n`` is
    one of them."""
    if not (5161 <= n <= 5169 or 5181 <= n <= 5189):
        return False
    j = n - (5161 if n < 5180 else 5181)
    v = 0.0 if value is None else float(value)
    if j < 3:
        point = st.home if n < 5180 else st.reference2
        point = np.zeros(3) if point is None else point.copy()
        point[j] = v * _stored(st)
        if n < 5180:
            st.home = point
        else:
            st.reference2 = point
    else:
        extra = (st.home_extra if n < 5180 else st.reference2_extra).copy()
        extra[j - 3] = v if j < 6 else v * _stored(st)
        if n < 5180:
            st.home_extra = extra
        else:
            st.reference2_extra = extra
    return True


def set_system_parameter(n: int, value: float | None, st: ReaderState) -> bool:
    """Fanuc/Haas ``#n = value`` on a work-offset variable: that offset's axis becomes ``value`` (in the
    machine's unit, :attr:`interpolators.context.MachineContext.linear_units`; A B C in deg; a vacant
    value is 0); the tool offset variables set a tool's length / radius geometry or wear, and a write to the clocks
    ``#3001``/``#3002`` (and under ``haas`` its timers ``#3021``-``#3025``) is taken without effect (module
    docstring). True when ``#n`` is such a variable (the caller reports the others). The parts counters
    ``#3901``/``#3902`` take the value (vacant: 0)."""
    if n in PARTS_COUNTERS:
        st.parts_counters[n] = 0.0 if value is None else float(value)
        return True
    if n in _RESETTABLE_CLOCKS or n in _HAAS_RESETTABLE_TIMERS and st.context.dialect.name == "haas":
        return True  # a reset that starts a timing: the clock is not read (module docstring)
    register, _ = _tool_register(n, st)
    if register is not None:
        tool = st.tool(register.number) or Tool(number=register.number)
        amount = 0.0 if value is None else float(value) * _stored(st)
        st.tools[register.number] = with_tool_offset(tool, register, amount)
        return True
    if 5201 <= n <= 5206:  # the external workpiece zero offset (Fanuc 0i-MD "System variables": read/write; Haas: G52)
        v = 0.0 if value is None else float(value)
        set_external_axis(st, n - 5201, v * _stored(st) if n <= 5203 else v)
        return True
    target = _offset_variable(n, st)
    if target is None:
        return False
    code, j = target  # j < 6: X Y Z and the three rotary axes
    _write_offset(code, j, 0.0 if value is None else float(value), st)
    return True
