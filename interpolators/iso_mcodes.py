"""The ISO reader's M codes (:mod:`interpolators.iso`): notes of the spindle, coolant, stop and tool codes, the
program end M2/M30, LinuxCNC's M70-M73 modal state (:mod:`interpolators.iso_modal_state`) and M48-M53 overrides,
user M codes M100-M199 (LinuxCNC M-code reference, 'M100 to M199'), the words the I/O codes read (M62-M68, Haas
M59/M69, Haas M96/M46 refused), and the R of LinuxCNC 2.10's ``G64 P.. R..`` planner selection. LinuxCNC M-code
reference and the Haas mill operator's manual (each function says its source)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING

from interpolators._words import Where
from interpolators.iso_codes import LINUXCNC_M
from interpolators.iso_rigid_tap import arm_rigid_tap, end_rigid_tap
from interpolators.iso_words import Word, foreign_hint

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["user_m_file", "m_codes", "planner_word", "io_words", "spindle_select", "smartcool_hint",
           "OVERRIDES_AT_START"]


_M_NOTES = {
    0: "M0/M1 program stop", 1: "M0/M1 program stop", 60: "M60 pallet change stop",
    3: "S/M3-M5 spindle", 4: "S/M3-M5 spindle", 5: "S/M3-M5 spindle", 19: "M19 spindle orient",
    6: "T/M6 tool change", 7: "M7-M9 coolant", 8: "M7-M9 coolant", 9: "M7-M9 coolant",
    48: "M48-M53 overrides", 49: "M48-M53 overrides", 50: "M48-M53 overrides", 51: "M48-M53 overrides",
    52: "M48-M53 overrides", 53: "M48-M53 overrides", 61: "M61 set tool number",
    70: "M70-M73 modal state", 71: "M70-M73 modal state", 72: "M70-M73 modal state", 73: "M70-M73 modal state",
    **{m: "M62-M68 digital/analog I/O" for m in range(62, 69)},
}


#: LinuxCNC's override switches at power-on and what sets them (interp_convert.cc convert_m: M48/M49 both overrides,
#: M50 the feed override, M51 the spindle speed override, M52 adaptive feed, M53 the feed stop; P0 off, another P or
#: none on), read as ``#<_feed_override>`` ``#<_speed_override>`` ``#<_adaptive_feed>`` ``#<_feed_hold>``; rs274
#: 2.9.0~pre1 prints 1, 1, 0, 1 at the start. The program end (M2/M30) enables both overrides again.
OVERRIDES_AT_START = {"feed_override": True, "speed_override": True, "adaptive_feed": False, "feed_hold": True}
_OVERRIDE_M = {48: ("feed_override", "speed_override"), 49: ("feed_override", "speed_override"),
               50: ("feed_override",), 51: ("speed_override",), 52: ("adaptive_feed",), 53: ("feed_hold",)}


#: Haas's own M codes above M99 that move nothing (Haas mill operator's manual, NGC, "M-codes": "M130 Display
#: Media / M131 Cancel Display Media" (``M130 (file.png)`` shows a picture or a video on the pendant, as Fusion's
#: Haas Next Generation post writes for each tool), "M138 / M139 Spindle Speed Variation On / Off"): noted, where
#: other codes M100-M199 are the machine tool builder's (:func:`user_m_file`).
HAAS_OWN_M = {130: "M130/M131 display media (Haas)", 131: "M130/M131 display media (Haas)",
              138: "M138/M139 spindle speed variation (Haas)", 139: "M138/M139 spindle speed variation (Haas)"}


#: Haas M codes with a P word (Haas mill operator's manual, M codes "M59 Set Output Relay", "M69 Clear Output
#: Relay": P the relay number, e.g. M59 P1103): no motion, noted (as other M codes).
_HAAS_P_M = {59: "M59 set output relay", 69: "M69 clear output relay"}


#: M codes below M100 that grbl 1.1 (gcode.c, the ``'M'`` switch: M0-M2, M30, M3-M5, M7-M9, M56) or grblHAL's
#: core (gcode.c: also M6, M48-M51, M53, M60, M61, M62-M68, M70-M73, M98, M99; the OpenPNP plugin's M42, gcode.h
#: ``user_mcode_t`` "OpenPNP_SetPinState = 42") accepts; any other, "default: .. RETURN(
#: Status_GcodeUnsupportedCommand); // [Unsupported M command]" (error 20), is noted as one grbl refuses (Marlin's
#: M82/M83/M84 in CNC programs written for a Marlin router).
_GRBL_KNOWN_M = frozenset((0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 30, 42, 48, 49, 50, 51, 53, 56, 60, 61, 62, 63, 64, 65, 66,
                           67, 68, 70, 71, 72, 73, 98, 99))


#: Haas M codes above M99 that wait for the operator (Haas mill operator's manual, "M109 Interactive User Input":
#: the program shows its prompt, waits for one key and stores it in the macro variable P, 500-549): what follows
#: depends on the key, an error naming it (as :data:`_HAAS_JUMP_M`).
_HAAS_INPUT_M = {109: "M109 interactive user input (Haas: the program waits for the operator's key, stored in the "
                      "macro variable P)"}


#: Haas M codes that branch on a machine input (Haas mill operator's manual "M96 Jump If No Input", "M46 Jump If
#: Pallet Loaded"): which way the program goes is the machine's, errors naming them.
_HAAS_JUMP_M = {96: "M96 jump if no input (Haas)", 46: "M46 jump if pallet loaded (Haas)"}


#: Words the I/O M codes read (LinuxCNC M-code reference: M62-M65 P<output>; M66 P|E<input>
#: L<wait mode> Q<timeout>; M67/M68 E<analog output> Q<value>): theirs, not the motion's.
_IO_WORDS = ("P", "E", "L", "Q")


#: Codes of 3D printer firmware, by Marlin's G-code reference titles (marlinfw.org/docs/gcode: M104 "Set Hotend
#: Temperature", M106 "Set Fan Speed", M400 "Finish Moves", M280 "Servo Position", M300 "Play Tone", ...); a
#: laser on such firmware is often driven as its fan, a pen plotter's pen by its servo, and CNC posts for Marlin
#: routers (Fusion's Snapmaker post, MPCNC posts) write M400 before the spindle stops.
_PRINTER_M = {104: "M104 set hotend temperature", 105: "M105 report temperatures", 106: "M106 set fan speed",
              107: "M107 fan off", 109: "M109 wait for hotend temperature", 114: "M114 get current position",
              117: "M117 set LCD message", 140: "M140 set bed temperature", 190: "M190 wait for bed temperature",
              220: "M220 set feedrate percentage", 221: "M221 set flow percentage", 280: "M280 servo position",
              300: "M300 play tone", 400: "M400 finish moves"}


def printer_hint(m: int) -> str:
    """What an M code above M199 is on 3D printer firmware (Marlin, :data:`_PRINTER_M`); '' if it is none."""
    printer = _PRINTER_M.get(m)
    return f" (Marlin's {printer}: a 3D printer firmware's code, which no dialect of vcnc reads)" if printer else ""


#: M100-M199 codes of LinuxCNC's QtPlasmaC configurations, written with a P word (qtplasmac.adoc, "Automatic
#: Material Handling": "M190 Pn - Changes the currently displayed material to material number n").
_PLASMAC_M = {190: "QtPlasmaC's M190 Pn material change (LinuxCNC plasma: a user M file of its configuration, "
                   "paired with M66 P3 L3 Q1 and F#<_hal[plasmac.cut-feed-rate]>)"}


def user_m_file(w: Word, m: int, st: State, where: Where, *, with_p: bool = False) -> None:
    """M100-M199: LinuxCNC runs the executable file ``M1nn`` (no extension, a capital M) with the block's P and
    Q as its two arguments, and "Execution of the G-code file pauses until the external program exits"
    (m-code.adoc "M100 to M199"; the file is looked for in [DISPLAY] PROGRAM_PREFIX and [RS274NGC]
    USER_M_PATH, and a missing one is an error). The program runs outside the interpreter: nothing of the
    path moves. Its file is looked for in the dialect's ``user_m_path`` and, under ``linuxcnc``, in the folder
    of the file that holds the code (a program read from a file), as vcnc takes the program's folder for
    PROGRAM_PREFIX ("The default location for g-code files and the location for user-defined M-codes. This
    location is searched for the file name before the subroutine path and user M path", INI configuration,
    [DISPLAY]; vcnc looks for o<name> subroutine files there too). An error names the code if none holds it,
    as its control knows it: on Fanuc and Haas controls M100-M199 are the machine tool builder's functions
    (our reading: their manuals define M codes below 100 and leave the others to the machine), grbl 1.1
    refuses them (gnea/grbl ``gcode.c``, the ``'M'`` switch: M0-M5, M7-M9, M30, M56, else error 20). ``with_p``:
    the block has a P word (``M190 P1`` is QtPlasmaC's material change under ``linuxcnc``, :data:`_PLASMAC_M`).
    Under ``haas``, M109 (:data:`_HAAS_INPUT_M`, a Haas code that waits for the operator) is refused naming it."""
    name = f"M{m}"
    if st.context.dialect.name == "haas" and m in _HAAS_INPUT_M:
        where.fail(f"{_HAAS_INPUT_M[m]}: not supported (what follows depends on the operator's input)",
                   column=w.column, text=w.text, expected="a program without interactive input")
    base = Path(where.file).parent if where.file else Path.cwd()
    own = st.context.dialect.name == "linuxcnc" and where.file is not None
    folders = ((".",) if own else ()) + tuple(st.context.dialect.user_m_path)
    if any((base / folder / name).is_file() for folder in folders):
        return
    looked = ", ".join(("its own folder",) * own + tuple(st.context.dialect.user_m_path)) or "none given"
    dialect = st.context.dialect.name
    what = (f"user M code {w.text!r} (M100-M199 runs the executable file {name} of the user M path, LinuxCNC "
            "USER_M_PATH)" if dialect == "linuxcnc" else
            f"M code {w.text!r} unknown to grbl (gcode.c: M0-M5, M7-M9, M30, M56 only; error 20)"
            if dialect == "grbl" else
            f"machine-specific M code {w.text!r} (M100-M199 on a {dialect.capitalize()} control: a function of the "
            "machine tool builder, no motion known here)")
    plasmac = _PLASMAC_M.get(m) if with_p and dialect == "linuxcnc" else None
    printer = _PRINTER_M.get(m)
    if plasmac:
        what += f" ({plasmac})"
    elif printer:
        what += f" (Marlin's {printer}: a 3D printer's code, which laser conversions use for the laser)"
    where.fail(f"{what}: {name} not found (folders: {looked})", column=w.column, text=w.text,
               expected=f"M codes below 100, or the file {name} in a folder of the machine's [program] user_m_path "
                        "or of --user-m-path (the code then runs as a function that moves nothing)")


def m_codes(mcodes, seen, st: State, where: Where, notes: Notes) -> bool:
    """M codes: tool change, LinuxCNC's M70-M73 and notes; True at program end (M2/M30)."""
    ended = False
    for m, _ in mcodes:
        if m == 66 and st.context.dialect.name == "linuxcnc":
            _wait_on_input(seen, st, where, notes)
        if m in (3, 4, 5, 19):  # M19 orients: the spindle stops turning (LinuxCNC m-code.adoc "M19")
            st.spindle_turning = m in (3, 4)
            st.spindle_ccw = m == 4
        _switch_state(m, seen, st)
        if m in (2, 30):
            ended = True
            st.spindle_turning = False
            end_rigid_tap(st)
        elif m == 6:
            st.tool_current = st.tool_selected
            if st.context.dialect.name == "linuxcnc" and not any(k in (3, 4) for k, _ in mcodes):
                # convert_tool_change stops the spindle ([EMCIO] TOOL_CHANGE_WITH_SPINDLE_ON unset); an M3/M4 of the
                # block runs after it (LinuxCNC's order of execution)
                st.spindle_turning = False
            notes.add("T/M6 tool change")
        elif m == 29 and st.context.dialect.name == "fanuc":  # Fanuc rigid tapping (parameter No. 5210: M29)
            arm_rigid_tap(st, where, notes)
        elif m == 61:
            if "Q" in seen:
                st.tool_current = int(seen["Q"].value)
            notes.add(_M_NOTES[m])
        elif 70 <= m <= 73 and st.context.dialect.name == "linuxcnc":
            _modal_state(m, st, where, notes)
        elif m in _M_NOTES:
            notes.add(_M_NOTES[m])
        elif m in HAAS_OWN_M and st.context.dialect.name == "haas":
            notes.add(HAAS_OWN_M[m])
        elif 100 <= m <= 199:
            notes.add(f"user M code M{m} (an external program of the user M path: no motion)")
        elif st.context.dialect.name == "linuxcnc" and m not in LINUXCNC_M:
            notes.add(f"M{m} (no motion; LinuxCNC refuses it: \"Unknown m code used\")")
        elif st.context.dialect.name == "grbl" and m not in _GRBL_KNOWN_M:
            notes.add(f"M{m} (no motion; grbl refuses it: error 20, '[Unsupported M command]', as grblHAL does "
                      "without a plugin that claims it)")
        else:
            notes.add(f"M{m} (no motion)")
    return ended


def _switch_state(m: int, seen, st: State) -> None:
    """The coolant and override switches LinuxCNC's predefined parameters read (``#<_mist>``, ``#<_flood>``,
    ``#<_feed_override>`` ...: :func:`interpolators.iso_system.named_state_parameter`): M7 mist, M8 flood, M9 both
    off; M48-M53 (:data:`OVERRIDES_AT_START`); the program end turns the coolant off and enables the overrides
    (interp_convert.cc convert_stop, M2/M30 steps 5, 7 and 9). No motion."""
    if m in (7, 8, 9):
        st.mist = m == 7 or (st.mist and m == 8)
        st.flood = m == 8 or (st.flood and m == 7)
    elif m in _OVERRIDE_M:
        on = m != 49 and (m == 48 or "P" not in seen or seen["P"].value != 0)
        for name in _OVERRIDE_M[m]:
            st.overrides[name] = on
    elif m in (2, 30):
        st.mist = st.flood = False
        st.overrides.update(feed_override=True, speed_override=True)


def _modal_state(m: int, st: State, where: Where, notes: Notes) -> None:
    """LinuxCNC M70 save, M71 invalidate, M72 restore, M73 save and restore at the return
    (:mod:`interpolators.iso_modal_state`)."""
    states = st.modal_states
    if m in (70, 73):
        states.save(st, autorestore=m == 73)
    elif m == 71:
        states.invalidate()
    else:
        try:
            restored = states.restore(st)
        except ValueError as exc:
            where.fail(f"{exc}: not supported", expected="the same cutter compensation at M70 and M72")
        if not restored:
            notes.add("M72 with no modal state saved at its level (LinuxCNC refuses it: \"missing M70/M73?\"); "
                      "nothing restored")
            return
    notes.add({70: "M70 modal state saved", 71: "M71 saved modal state invalidated", 72: "M72 modal state restored",
               73: "M73 modal state saved, restored at the subroutine's return"}[m])


#: M66 wait modes (LinuxCNC m-code.adoc "M66 Wait on Input": L0 IMMEDIATE, L1 RISE, L2 FALL, L3 HIGH, L4 LOW) and
#: the level the input has when the wait ends: the one waited for (vcnc's machine has no inputs, so the event comes at
#: once); L0 reads an input nothing drives, as LinuxCNC reads a motion.digital-in pin no HAL net connects: 0.
_WAIT_LEVEL = {0: 0.0, 1: 1.0, 2: 0.0, 3: 1.0, 4: 0.0}


def _wait_on_input(seen, st: State, where: Where, notes: Notes) -> None:
    """LinuxCNC ``M66 P- | E- <L-> <Q->`` (m-code.adoc "M66 Wait on Input"): wait for digital input P or read
    analog input E; the input's value goes to ``#5399``, -1 when the Q timeout [s] passes first. The checks and
    messages are rs274's (``interp_check.cc``/``interp_convert.cc``, run on such lines): "Need to have either a valid
    P or a valid E word with M66", "Invalid to select both a digital and an analog input with M66", "Negative l
    word used", "Can't select analog input with wait type != immediate return" ("Mode 0 is the only one permitted
    for an analog input") and "Zero timeout with wait type != immediate return" ("A Q value of zero is an error if
    the L-word is non-zero"; a missing Q is 0). The wait takes no time here and ends with the event it waits for
    (:data:`_WAIT_LEVEL`; our reading for a machine without inputs: the program runs the path it is written for,
    as when its sensor answers, not the timeout's branch), so ``#5399`` is 1 after L1/L3, 0 after L2/L4 and 0 after
    L0; a mode beyond 4, which the manual does not define, leaves ``#5399`` unknown (reading it is an error). rs274
    alone (saicanon.cc) returns 0 for every mode."""
    p, e, lw, q = (seen.get(k) for k in "PELQ")
    m66 = f"M66 {' '.join(w.text for w in (p, e, lw, q) if w is not None)}".strip()
    if p is not None and e is not None:
        where.fail(f"{m66}: both a digital (P) and an analog (E) input (LinuxCNC: \"Invalid to select both a digital "
                   "and an analog input with M66\")", column=e.column, text=e.text,
                   expected="M66 P<digital> or E<analog>")
    given = p if p is not None else e
    if given is None or given.value < 0:
        where.fail(f"{m66}: no input to wait on (LinuxCNC: \"Need to have either a valid P or a valid E word with "
                   "M66\")", column=getattr(given, "column", 1), text=getattr(given, "text", "M66"),
                   expected="M66 P<digital input> or E<analog input>, a number >= 0")
    mode = 0.0 if lw is None else lw.value
    if lw is not None and (mode < 0 or mode != int(mode)):
        where.fail(f"{m66}: wait mode L must be a whole number >= 0 (LinuxCNC: \"Negative l word used\", \"Non "
                   "integer value for integer\")", column=lw.column, text=lw.text, expected="L0 .. L4")
    if mode and e is not None:
        where.fail(f"{m66}: an analog input is read at once (LinuxCNC: \"Can't select analog input with wait type != "
                   "immediate return\")", column=lw.column, text=lw.text, expected="M66 E<input> L0")
    if mode and (q is None or q.value == 0):
        where.fail(f"{m66}: a wait (L{int(mode)}) needs a timeout Q > 0 [s] (LinuxCNC: \"Zero timeout with wait type "
                   "!= immediate return\")", column=lw.column, text=lw.text,
                   expected=f"M66 {given.text} L{int(mode)} Q<s>")
    st.input_result = _WAIT_LEVEL.get(int(mode))
    st.input_unknown = "" if st.input_result is not None else (
        f"the result of {m66} at line {where.line}, whose wait mode L{int(mode)} is none of LinuxCNC's L0-L4")
    notes.add("M66 wait on input: the input taken as answering at once (#5399: 1 after L1/L3, 0 after L2/L4; L0 reads "
              "an input nothing drives, 0)")


#: What reads a ``$`` word (rs274: "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G76, G95, G96
#: or G97 to use it"; rs274 2.9 runs it beside an S word or M3, M4, M5, M19, and refuses "G95 $0", "G97 $0").
_SPINDLE_M = (3, 4, 5, 19)
_SPINDLE_MOTION = (330, 331, 760)


def spindle_select(seen, gcodes, mcodes, st: State, where: Where, notes: Notes) -> None:
    """LinuxCNC's ``$`` word, the spindle an S, M3-M5 or M19 acts on (M-code reference, "M3, M4, M5 Spindle
    Control": "M3 $0 S1000"; "$-1" all spindles, LinuxCNC commit 3139328 "Without a $ M3, M4 & M5 now act on
    spindle zero. To act on all spindles use $-1"), as QtPlasmaC posts write the torch, ``M3 $0 S1``.

    vcnc's machine has one spindle, as rs274's standalone one: ``$0`` and ``$-1`` select it (the value cut toward
    zero as rs274 does: ``$0.9`` is 0), other numbers are refused as rs274 refuses them. The other dialects read
    no ``$`` word."""
    w = seen.get("$")
    if w is None:
        return
    if st.context.dialect.name != "linuxcnc":
        where.fail(f"unknown word {w.text!r}{foreign_hint(w.text, first=False)}; on LinuxCNC '$' selects the "
                   "spindle (M3 $0 S1000): --dialect linuxcnc", column=w.column, text=w.text,
                   expected="a word of the letters A-Z")
    if not ("S" in seen or any(m in _SPINDLE_M for m, _ in mcodes)
            or gcodes.get("motion", (None,))[0] in _SPINDLE_MOTION):
        where.fail("$ (spindle selection) word with no S, M3, M4, M5, M19, G33, G33.1 or G76 to use it (LinuxCNC)",
                   column=w.column, text=w.text, expected="M3 $0 S.., M5 $-1, or the block without $")
    if int(w.value) not in (-1, 0):
        where.fail(f"spindle ${int(w.value)}: vcnc's machine has one spindle, $0 ($-1: all spindles); a LinuxCNC "
                   "machine with [TRAJ] SPINDLES > 1 runs it (rs274: \"Invalid spindle ($) number\")",
                   column=w.column, text=w.text, expected="$0 or $-1")
    notes.add("$ spindle selection (one spindle: $0)")


def planner_word(seen, gcodes, mcodes, where: Where, notes: Notes) -> dict:
    """``seen`` without the R of ``G64 P.. R..``: LinuxCNC 2.10's trajectory planner selection.

    LinuxCNC g-code.adoc "G64 R: planner selection": R0 (or negative) selects the trapezoidal
    planner, R0.1..R1 (clamped) the jerk-limited one and its cornering aggressiveness; it changes
    neither the path nor the end points, so it is accepted with a note (vcnc's look-ahead is its own).
    An R on a line with M19 as well is an error (ambiguous, as LinuxCNC says); an R on G61 is left to
    the other words' checks (an R without a code to use it).
    """
    if "R" not in seen or gcodes.get("path", (0,))[0] != 640:
        return seen
    w = seen["R"]
    if any(m == 19 for m, _ in mcodes):
        where.fail("word R on a line with both G64 and M19 is ambiguous (G64 planner or M19 angle)",
                   column=w.column, text=w.text, expected="G64 R and M19 R on separate lines")
    notes.add("G64 R planner selection (the path is unchanged)")
    return {k: v for k, v in seen.items() if k != "R"}


def smartcool_hint(mcodes) -> str:
    """The hint of an E or P word no code reads in a block with M7/M8: Tormach PathPilot's SmartCool nozzle, as
    Fusion's tormach.cps writes it with "SmartCool equipped" set ("M8 E<top of part>" for drilling, "M8 P0
    [R<sweep length>]" for milling); '' without M7/M8."""
    if not any(m in (7, 8) for m, _ in mcodes):
        return ""
    return (" (Tormach PathPilot's SmartCool nozzle, M7/M8 E<height> or P<mode> R<sweep>, as Fusion's tormach.cps "
            "writes it: a PathPilot extension vcnc does not read)")


def extruder_hint(seen) -> str:
    """The hint of an E word in a block that moves X, Y or Z: the extruder axis of 3D printer G-code (Marlin's
    G-code reference, "G0-G1 Linear Move": "E<pos> An absolute or relative coordinate on the E (extruder) axis";
    RepRapFirmware likewise), which a slicer (Cura, PrusaSlicer, with or without arc fitting) writes on its
    moves; '' without an X, Y or Z word."""
    if not any(letter in seen for letter in "XYZ"):
        return ""
    return (" (E on a move: the extruder axis of 3D printer G-code, as a slicer such as Cura or PrusaSlicer "
            "writes it; a milling control has no E axis: a slicer's output is no milling program)")


def io_words(mcodes, seen, st: State, where: Where) -> dict:
    """``seen`` without the words its M code reads (M61 Q, M62-M68 P E L Q, M19 R Q P, LinuxCNC M50-M53 P); E
    elsewhere is an error."""
    if st.context.dialect.name == "haas" and any(m in _HAAS_P_M or m in _HAAS_JUMP_M for m, _ in mcodes):
        m, w = next((m, w) for m, w in mcodes if m in _HAAS_P_M or m in _HAAS_JUMP_M)
        if m in _HAAS_JUMP_M:
            where.fail(f"{_HAAS_JUMP_M[m]}: not supported (the jump depends on a machine input)", column=w.column,
                       text=w.text, expected="a program without input-dependent jumps")
        seen = {k: v for k, v in seen.items() if k != "P"}
    if st.context.dialect.name == "linuxcnc" and any(48 <= m <= 53 for m, _ in mcodes):
        _override_m_codes(mcodes, st, where)
        if any(50 <= m <= 53 for m, _ in mcodes):
            seen = {k: v for k, v in seen.items() if k != "P"}
        elif "P" in seen:  # interp_check.cc check_other_codes: "P word with no G2 .. M50 M51 M52 M53 .. to use it"
            m, w = next((m, w) for m, w in mcodes if 48 <= m <= 53)
            where.fail(f"M{m} P: M48 and M49 take no P (LinuxCNC; M50 P.. and M51 P.. switch the feed and the "
                       "spindle speed override one by one)", column=seen["P"].column, text=seen["P"].text,
                       expected=f"M{m} alone, or M50 P0/P1 and M51 P0/P1")
    if any(62 <= m <= 68 for m, _ in mcodes):
        return {k: v for k, v in seen.items() if k not in _IO_WORDS}
    if any(m == 19 for m, _ in mcodes):  # LinuxCNC M19 R<angle> Q<timeout> P<direction>: spindle orientation
        seen = {k: v for k, v in seen.items() if k not in "RQP"}
    if any(m == 61 for m, _ in mcodes):  # M61 Q<tool>: the Q is the tool number, read by m_codes
        seen = {k: v for k, v in seen.items() if k != "Q"}
    if any(100 <= m <= 199 for m, _ in mcodes):  # user M codes: P and Q are the external program's arguments
        seen = {k: v for k, v in seen.items() if k not in "PQ"}
    if "E" in seen:
        w = seen["E"]
        lead = re.search(r"[-+]?[\d.]+$", where.text[:w.column - 1])
        if lead and ("." in lead.group(0) or re.fullmatch(r"[eE][-+]\d+", w.text)):
            # "J -8.775e-05", printed by a script: G-code numbers have no exponent (overview.adoc "Numbers")
            number = lead.group(0) + w.text
            where.fail(f"number {number!r} in exponent notation: G-code numbers are plain decimals",
                       column=w.column, text=w.text, expected="a plain decimal number such as -0.0000878")
        # Fadal User Manual (April 2003) section 1, NC word summary: "E Fixture offset" (E1-E48, E0 none)
        fadal = " (E1-E48 select a Fadal fixture offset: use --dialect fadal)" if 0 <= w.value <= 48 and \
            w.value == int(w.value) else ""
        hint = smartcool_hint(mcodes) or fadal + extruder_hint(seen)
        where.fail(f"word {w.text!r} outside M66-M68 (digital/analog I/O){hint}",
                   column=w.column, text=w.text,
                   expected="E only with M66, M67 or M68")
    return seen


def _override_m_codes(mcodes, st: State, where: Where) -> None:
    """LinuxCNC M48-M53 (m-code.adoc "M48, M49 Speed and Feed Override Control", "M50 Feed Override Control",
    "M51 Spindle Speed Override Control", "M52 Adaptive Feed Control", "M53 Feed Stop Control"): ``M50 P1``
    (or no P) enables, ``P0`` disables (interp_convert.cc convert_m: ``block->p_number != 0`` enables); no
    motion, the path is unchanged (noted by :func:`m_codes`). Refused with cutter compensation on, as
    convert_m does ("Cannot enable overrides with cutter radius compensation on", "Cannot disable ..")."""
    if st.comp_side is None:
        return
    m, w = next((m, w) for m, w in mcodes if 48 <= m <= 53)
    where.fail(f"M{m}: cannot enable or disable overrides with cutter radius compensation on (LinuxCNC)",
               column=w.column, text=w.text, expected=f"G40 before M{m}")
