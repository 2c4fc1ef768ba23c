"""grbl's system commands and real-time characters in a program file (``grbl`` dialect only).

Files written for grbl often carry lines a grbl sender streams to the controller along with the
G-code: ``$`` system commands (``$$`` settings report, ``$G`` parser state, ``$I`` build info,
``$100=100.5`` a setting) and the ``?`` status query. grbl 1.1 reads them so (gnea/grbl
``grbl/protocol.c`` ``protocol_main_loop``, ``grbl/system.c`` ``system_execute_line``,
``grbl/serial.c`` ``ISR(SERIAL_RX)``):

* The serial receive interrupt picks the real-time characters ``?`` (status report), ``~`` (cycle
  start), ``!`` (feed hold) and Ctrl-X (soft reset) out of the stream wherever they are: they never
  reach a line. A ``?`` is dropped here (a report does not move the tool), and so is ``~``
  (``doc/markdown/commands.md``: "Resumes a feed hold, ... and the M0 program pause states. Command
  is otherwise ignored."; the program runs on anyway here); ``!`` and Ctrl-X stop the machine as the
  operator would, and are errors naming them.
* A line whose first character (after grbl strips spaces and comments) is ``$`` is a system command,
  run instead of the G-code parser. Reports (``$``, ``$$``, ``$#``, ``$G``, ``$I``, ``$N``), the
  alarm unlock ``$X``, stored build info ``$I=..`` and startup lines ``$Nx=..`` (run at the next reset,
  not now) and settings ``$x=value`` (steps, rates, accelerations of the machine, which vcnc takes
  from its own limits) do not move the tool: they become blank lines, with a note. Jogging ``$J=``,
  check mode ``$C`` (the G-code after it is checked, not run), ``$RST=`` (restores settings and work
  offsets) and sleep ``$SLP`` change what the program does and are errors naming the command.
* ``$H`` runs the homing cycle (``doc/markdown/commands.md``: "the only way to perform the homing
  cycle in Grbl"; ``grbl/limits.c`` ``limits_go_home``): with the default ``config.h`` the cycles are
  ``HOMING_CYCLE_0`` = Z ("First move Z to clear workspace") then ``HOMING_CYCLE_1`` = X and Y
  together. The machine ends at its home, the work offsets and G92 kept. :func:`system_lines` blanks
  the line and lists it in :attr:`GrblLines.homing`; the reader runs it as a rapid of Z to the home
  position of the machine context, then of X and Y (the homing switches' seek and locate feeds are
  not modelled).
* A ``(`` comment that does not close runs to the end of the line (``protocol.c``: "Enable comments
  flag and ignore all characters until ')' or EOL"); LinuxCNC and Fanuc refuse it.
* A line that begins with ``%`` and goes on (``%wait``, ``%x0=posx``) is a macro line of the CNCjs
  sender, which evaluates it and never streams it to grbl (CNCjs User Guide, "Macro": "Lines
  beginning with % are used to create variables for later use",
  https://github.com/cncjs/cncjs/wiki/User-Guide; v1.9.4 release notes: "%wait ; Wait for the
  planner queue to empty"). Such lines move nothing: they become blank lines, with a note (a line
  CNCjs cannot evaluate, such as a ``% vfd enable`` remark, is logged by it and skipped alike). A
  ``%`` alone stays the tape marker it is.

:func:`unsupported_codes` holds a block to grbl 1.1's G-code set (gnea/grbl ``grbl/gcode.c``
``gc_execute_line``, the ``'G'`` switch: G0-G3, G4, G10, G17-G19, G20/G21, G28, G30, G38.x, G40, G43.1,
G49, G53, G54-G59, G61, G80, G90/G91, G91.1, G92, G93/G94; "default: FAIL(STATUS_GCODE_UNSUPPORTED_COMMAND)",
error 20) where vcnc's reader, which reads grbl programs as LinuxCNC does otherwise, would run more:

* G41/G42 are errors naming them: grbl has no cutter radius compensation (``case 40``: "Not required since
  cutter radius compensation is always disabled. Only here to support G40 commands that often appear in
  g-code program headers"), so the path a compensated run would give is no path the machine makes.
* G73 and G81-G89 canned cycles, G43 tool length offsets from the tool table, G95 feed per revolution, G5
  cubic splines, G64 path blending, G98/G99, G59.1-G59.3, G92.2/G92.3 and the M codes M6, M48-M51, M62-M66
  run as grblHAL (grbl's successor for 32-bit boards) runs them, with a note that grbl 1.1 refuses them
  (:data:`_GRBLHAL_ONLY`, :data:`_GRBLHAL_ONLY_M` give grblHAL's code for each): grblHAL ``gcode.h`` has
  ``MotionMode_DrillChipBreak = 73``, ``MotionMode_CannedCycle81`` ... ``89``, ``MotionMode_CubicSpline = 5``,
  ``ToolLengthOffset_Enable`` (G43), ``FeedMode_UnitsPerRev`` (G95), and starts in G98 ("CCRetractMode_Previous
  = 0, // G98 (Default: Must be zero)"), as the reader's grbl dialect does.
* G90.1 (arc centres I J K as absolute coordinates) is an error naming it: "if ((mantissa != 10) || (int_value ==
  90)) { FAIL(STATUS_GCODE_UNSUPPORTED_COMMAND); } // [G90.1 not supported]" ... "Otherwise, arc IJK incremental
  mode is default. G91.1 does nothing." (grblHAL's ``gcode.c`` alike), so grbl reads I J K as offsets from the
  arc's start whatever the program meant.
* G61.1 (exact stop mode) is an error naming it (``case 61``: "[G61.1 not supported]").
* Word values (:func:`value_limits`): a line number above 10,000,000 is an error (error 27), ``G10 L2 .. R`` too
  (error 20, grblHAL alike); a tool number above 255 (error 38), ``G10 L2``/``L20`` P7-P9 (error 29) and ``G10
  L1``/``L10``/``L11`` (error 20) run as grblHAL runs them, noted. The axis words of G28.1, G30.1, G92.1 and G4 move
  by the modal motion, as LinuxCNC's (:func:`interpolators.iso_motion.linuxcnc_modal_axis_words`).
* A G4 dwell takes its time from P alone: "if (bit_isfalse(value_words,bit(WORD_P))) {
  FAIL(STATUS_GCODE_VALUE_WORD_MISSING); } // [P word missing]" (error 28; an X in the block is an axis word
  of the non-modal command, not a time), so ``G4 X2`` is an error, where the other dialects read X seconds.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from typing import NamedTuple

from interpolators._words import Where, lines_of
from interpolators.iso_flow import refuse_heidenhain_iso
from interpolators.iso_words import Word, comment_spans, firmware_dwell_hint

__all__ = ["GrblLines", "MAX_LINE_NUMBER", "MAX_TOOL_NUMBER", "N_COORDINATE_SYSTEM", "system_lines",
           "unsupported_codes", "value_limits"]

#: ``$`` commands that neither move the tool nor change the program's geometry (grbl ``system.c``).
_PASSIVE = re.compile(r"\$(?:|\$|#|G|I(?:=.*)?|N(?:\d+=.*)?|X|\d+=[-+]?[\d.]+)")
#: ``$`` commands that do, by their name in grbl's documentation.
_ACTIVE = {"J": "$J= jog", "C": "$C check g-code mode", "R": "$RST= restore",
           "S": "$SLP sleep"}


#: Cutter radius compensation codes (round(10 * G)), which grbl 1.1 refuses (error 20) and vcnc would run.
_NO_COMPENSATION = {410: "G41", 420: "G42", 411: "G41.1", 421: "G42.1"}
#: G90.1, absolute arc centres (round(10 * G)), which grbl 1.1 and grblHAL refuse (error 20) and vcnc would run.
_ABSOLUTE_CENTRES = 901
#: G61.1, exact stop mode: grbl 1.1 ``case 61``: "if (mantissa != 0) { FAIL(STATUS_GCODE_UNSUPPORTED_COMMAND); } //
#: [G61.1 not supported]"; grblHAL the same without path blending (and its path-blending build's test, "mantissa != 0
#: || mantissa != 10", refuses every G61).
_EXACT_STOP_MODE = 611
#: G44, the tool length offset subtracted: grbl 1.1's ``case 43: case 49:`` takes G43.1 and G49 only (G43 "[Unsupported
#: G43.x command]", G44 the switch's "default:", error 20 both), and grblHAL's ``tool_offset_mode_t`` has G49, G43,
#: G43.1 and G43.2, no G44: neither runs it.
_SUBTRACTED_LENGTH = 440
#: Codes (round(10 * G)) grbl 1.1 refuses (error 20) and grblHAL runs (grblHAL ``gcode.h``: ``MotionMode_CubicSpline
#: = 5``, ``MotionMode_DrillChipBreak = 73``, ``MotionMode_CannedCycle81`` ... ``89``, ``ToolLengthOffset_Enable``
#: G43, ``FeedMode_UnitsPerRev = 2 // G95``; grblHAL ``gcode.c`` ``gc_execute_block``, the ``'G'`` switch: ``case 64``
#: path blending when built with ENABLE_PATH_BLENDING, ``case 98: case 99`` the canned cycles' retract mode,
#: ``case 59`` with ``mantissa`` 10-30 when it has 9 work coordinate systems, ``case 92`` with ``mantissa`` 20 or 30).
_GRBLHAL_ONLY = {50: "G5 cubic spline", 730: "G73 canned cycle", **{k: f"G{k // 10} canned cycle" for k in
                                                                     range(810, 900, 10)},
                 430: "G43 tool length offset", 950: "G95 feed per revolution", 640: "G64 path blending",
                 980: "G98 canned cycle retract to the initial level", 990: "G99 canned cycle retract to R",
                 **{k: f"G59.{k % 10} work offset" for k in (591, 592, 593)},
                 922: "G92.2 G92 offset suspended", 923: "G92.3 G92 offset restored"}
#: grbl 1.1's error for those of :data:`_GRBLHAL_ONLY` it does not refuse with error 20: G59.1-G59.3 pass its
#: ``case 59`` ("NOTE: G59.x are not supported.") and fail on the fraction left, "if (mantissa > 0) {
#: FAIL(STATUS_GCODE_COMMAND_VALUE_NOT_INTEGER); }" (error 23).
_GRBL_ERROR = {591: 23, 592: 23, 593: 23}
#: M codes grbl 1.1 refuses (its ``'M'`` switch: M0-M5, M7-M9, M30, M56, "default:
#: FAIL(STATUS_GCODE_UNSUPPORTED_COMMAND); // [Unsupported M command]", error 20) and grblHAL runs (its ``'M'``
#: switch: ``case 6`` a tool change, taken when a tool change mode or an ATC is set and otherwise accepted and
#: ignored; ``case 48: case 49: case 50: case 51`` override control; ``case 62`` ... ``case 65`` digital outputs and
#: ``case 66`` wait on input, on a board with such ports).
_GRBLHAL_ONLY_M = {6: "M6 tool change", 48: "M48 overrides enabled", 49: "M49 overrides disabled",
                   50: "M50 feed override control", 51: "M51 spindle override control",
                   **{m: f"M{m} digital output" for m in (62, 63, 64, 65)}, 66: "M66 wait on input"}


#: grbl 1.1 ``gcode.h``: "#define MAX_LINE_NUMBER 10000000" (grblHAL ``gcode.c`` the same) and "#define
#: MAX_TOOL_NUMBER 255 // Limited by max unsigned 8-bit value" (grblHAL ``config.h``: 2147483647).
MAX_LINE_NUMBER = 10_000_000
MAX_TOOL_NUMBER = 255


#: grbl 1.1 ``settings.h``: "#define N_COORDINATE_SYSTEM 6 // Number of supported work coordinate systems".
N_COORDINATE_SYSTEM = 6


def value_limits(gcodes: Mapping[str, tuple[int, Word]], seen: Mapping[str, Word], where: Where) -> list[str]:
    """Notes for the word values of one block that grbl 1.1 refuses and grblHAL runs: a tool number above
    :data:`MAX_TOOL_NUMBER` (``gcode.c``: "if (value > MAX_TOOL_NUMBER) { FAIL(STATUS_GCODE_MAX_VALUE_EXCEEDED); }",
    error 38; grblHAL takes tool numbers to 2147483647 when it has no tool table), ``G10 L2``/``L20`` with P above
    :data:`N_COORDINATE_SYSTEM` (G59.1-G59.3: "[Greater than N sys]", error 29; grblHAL has nine) and the tool table
    entries ``G10 L1``/``L10``/``L11`` ("[Unsupported L]", error 20; grblHAL ``gcode.c`` "[G10 L1, L10, L11 Errors]").
    ``gcodes`` maps the block's G-code groups to their code (round(10 * G)) and word.

    Raises
    ------
    vcnc.GCodeError
        A line number N above :data:`MAX_LINE_NUMBER` (``gcode.c``: "if (gc_block.values.n > MAX_LINE_NUMBER) {
        FAIL(STATUS_GCODE_INVALID_LINE_NUMBER); } // [Exceeds max line number]", error 27; grblHAL's the same), and
        ``G10 L2 .. R`` (a rotation: "[G10 L2 R not supported]", error 20, in grbl and grblHAL).
    """
    n = seen.get("N")
    if n is not None and n.value > MAX_LINE_NUMBER:
        where.fail(f"line number {n.text.strip()} above grbl's {MAX_LINE_NUMBER:,} (gcode.c MAX_LINE_NUMBER: "
                   "'[Exceeds max line number]', error 27)", column=n.column, text=n.text,
                   expected=f"N0 .. N{MAX_LINE_NUMBER} (or no N word)")
    notes = []
    t = seen.get("T")
    if t is not None and t.value > MAX_TOOL_NUMBER:
        notes.append(f"T{t.value:g} run as grblHAL runs it (grbl 1.1 refuses a tool number above {MAX_TOOL_NUMBER}: "
                     "MAX_TOOL_NUMBER, error 38)")
    if any(key == 100 for key, _ in gcodes.values()) and "L" in seen:
        level, p = seen["L"].value, seen["P"].value if "P" in seen else 0.0
        if level == 2 and "R" in seen:
            r = seen["R"]
            where.fail("G10 L2 R (a rotation of the coordinate system): grbl has none (gcode.c: '[G10 L2 R not "
                       "supported]', error 20; grblHAL the same)", column=r.column, text=r.text,
                       expected="G10 L2 P.. X.. Y.. Z.. without R under grbl")
        if level in (1, 10, 11):
            notes.append(f"G10 L{level:g} tool table entry run as grblHAL runs it (grbl 1.1 refuses it: "
                         "'[Unsupported L]', error 20)")
        elif level in (2, 20) and p > N_COORDINATE_SYSTEM:
            notes.append(f"G10 L{level:g} P{p:g} run as grblHAL runs it (grbl 1.1 has {N_COORDINATE_SYSTEM} work "
                         "coordinate systems: '[Greater than N sys]', error 29)")
    return notes


def unsupported_codes(gcodes: dict[str, tuple[int, Word]], letters: Iterable[str], where: Where,
                      mcodes: Iterable[tuple[int, Word]] = ()) -> list[str]:
    """Notes for the codes of one block that grbl 1.1 lacks and vcnc runs as grblHAL does (:data:`_GRBLHAL_ONLY`,
    :data:`_GRBLHAL_ONLY_M`).

    ``gcodes`` maps each G-code group of the block to its code (round(10 * G)) and word, ``letters`` are the
    block's other word letters, ``mcodes`` its M codes and their words.

    Raises
    ------
    vcnc.GCodeError
        G41/G42 cutter radius compensation (grbl has none), G90.1 absolute arc centres, G61.1 exact stop mode and
        G44 (neither has them), or a G4 dwell without P (grbl error 28).
    """
    notes = []
    for key, w in gcodes.values():
        if key in _NO_COMPENSATION:
            where.fail(f"{_NO_COMPENSATION[key]} cutter radius compensation: grbl has none (gcode.c supports G40 "
                       "only; error 20 unsupported command)", column=w.column, text=w.text,
                       expected="a path already offset by the CAM post (G40 or no compensation code) under grbl")
        if key == _ABSOLUTE_CENTRES:
            where.fail("G90.1 absolute arc centres: grbl has none (gcode.c: '[G90.1 not supported]', error 20 "
                       "unsupported command; its I J K are always offsets from the arc's start)", column=w.column,
                       text=w.text, expected="I J K as offsets from the arc's start (G91.1 or no arc-centre code) "
                                             "under grbl")
        if key == _SUBTRACTED_LENGTH:
            where.fail("G44 tool length offset subtracted: grbl has none (gcode.c takes G43.1 and G49, grblHAL G43, "
                       "G43.1, G43.2 and G49; error 20 unsupported command)", column=w.column, text=w.text,
                       expected="G43.1 Z<offset> (grbl) or G43 H<n> (grblHAL) with the offset's sign, or G49")
        if key == _EXACT_STOP_MODE:
            where.fail("G61.1 exact stop mode: grbl has none (gcode.c: '[G61.1 not supported]', error 20 unsupported "
                       "command; G61 is its only path mode)", column=w.column, text=w.text,
                       expected="G61 or no path-mode code under grbl")
        if key == 40 and "P" not in letters:
            where.fail("G4 dwell without P: grbl takes the dwell time from P only (gcode.c: '[P word missing]', "
                       f"error 28){firmware_dwell_hint(letters)}", column=w.column, text=w.text,
                       expected="G4 P<seconds>")
        if key in _GRBLHAL_ONLY:
            notes.append(f"{_GRBLHAL_ONLY[key]} run as grblHAL runs it (grbl 1.1 refuses it: error "
                         f"{_GRBL_ERROR.get(key, 20)})")
    notes += [f"{_GRBLHAL_ONLY_M[m]} run as grblHAL runs it (grbl 1.1 refuses it: error 20)"
              for m, _ in mcodes if m in _GRBLHAL_ONLY_M]
    return notes


class GrblLines(NamedTuple):
    """A grbl file read for its system commands: ``text`` with the system-command lines blanked, ``?``
    dropped and unclosed ``(`` comments closed at the end of their line (line numbers kept);
    ``blanked`` the number of report and setting lines blanked, ``homing`` the (1-based) lines of
    ``$H`` homing cycles, also blanked, ``closed`` the number of comments closed, ``resumes`` the
    number of ``~`` cycle starts dropped and ``sender`` the number of CNCjs ``%`` macro lines blanked."""

    text: str
    blanked: int
    homing: tuple[int, ...]
    closed: int
    resumes: int
    sender: int


def system_lines(text: str, source: str | None) -> GrblLines:
    """The program text with grbl's system-command lines and the sender's ``%`` macro lines blanked,
    ``?`` dropped and unclosed comments closed, as :class:`GrblLines`.

    Raises
    ------
    vcnc.GCodeError
        A ``$`` command that changes the program's run (``$J=``, ``$C``, ``$RST=``, ``$SLP``), or one
        grbl does not know; a Heidenhain DIN/ISO program's ``%NAME G71 *`` first block.
    """
    out = []
    blanked = closed = resumes = sender = 0
    homing: list[int] = []
    for number, raw in enumerate(lines_of(text), start=1):
        where = Where(source, number, raw)
        spans, semicolon = comment_spans(raw, where, unclosed_to_end=True)
        if spans and spans[-1][1] == len(raw) and not raw.endswith(")"):
            raw += ")"
            closed += 1
        code = list(raw[:semicolon])
        for start, end in spans:
            code[start:end] = " " * (end - start)
        command = "".join(code).replace(" ", "").replace("\t", "").upper()
        if command.startswith("$"):
            column = raw.index("$") + 1
            if _PASSIVE.fullmatch(command.replace("?", "")):
                out.append("")
                blanked += 1
                continue
            if command.replace("?", "") == "$H":
                out.append("")
                homing.append(number)
                continue
            name = _ACTIVE.get(command[1:2])
            if name is not None:
                where.fail(f"grbl {name}: not supported (it changes how the program runs)",
                           column=column, text=command,
                           expected="G-code, $H homing, or grbl reports and settings ($$, $G, $I, $#, $N, $X, "
                                    "$x=value)")
            where.fail("unknown grbl system command", column=column, text=command,
                       expected="$H, $$, $#, $G, $I, $N, $X, $x=value (homing, reports and settings), or G-code")
        if command.startswith("%") and command != "%":
            refuse_heidenhain_iso(raw.strip(), where)  # '%NAME G71 *': a TNC program, no sender macro
            out.append("")
            sender += 1
            continue
        line, dropped = _without_realtime(raw, spans, semicolon, where)
        out.append(line)
        resumes += dropped
    return GrblLines("\n".join(out), blanked, tuple(homing), closed, resumes, sender)


#: Real-time characters that stop the machine, by their name in grbl's documentation.
_HALTS = {"!": "! feed hold", "\x18": "Ctrl-X soft reset"}


def _without_realtime(raw: str, spans: list[tuple[int, int]], semicolon: int, where: Where) -> tuple[str, int]:
    """``raw`` with each ``?`` and ``~`` outside its comments replaced by a space (grbl's receive
    interrupt takes them out of the stream: status query, cycle start), and the number of ``~``.

    Raises
    ------
    vcnc.GCodeError
        A ``!`` feed hold or Ctrl-X soft reset.
    """
    if not any(c in raw for c in "?~!\x18"):
        return raw, 0
    chars = list(raw)
    resumes = 0
    for i in range(semicolon):
        if chars[i] in "?~!\x18" and not any(a <= i < b for a, b in spans):
            if chars[i] in _HALTS:
                where.fail(f"grbl {_HALTS[chars[i]]}: not supported (it stops the machine until the operator acts)",
                           column=i + 1, text=chars[i], expected="G-code, '?' or '~'")
            resumes += chars[i] == "~"
            chars[i] = " "
    return "".join(chars), resumes
