"""Differential test of vcnc's ISO reader (``--dialect linuxcnc``) against LinuxCNC's own interpreter, ``rs274``.

Each program runs through both: LinuxCNC's standalone interpreter (``rs274 -g``, the canonical calls it prints;
a G-code error, printed on stderr with a non-zero exit, is its refusal; a time limit per program) and vcnc's
``load_program`` with the context of rs274's standalone machine (``linuxcnc`` dialect, an inch machine: its tool
table and stored offsets are in inch, programs without G20/G21 in mm; axes X Y Z A B C, as rs274 without an INI
[TRAJ] refuses U V W). Both get the same tool table (``--tool-table``, default: a generated table of tools 1 to
999 with lengths and diameters that differ per tool) and the same subroutine folders (the program's own, then
``--subroutine-path``). For programs both accept it compares the motion: the end points of STRAIGHT_TRAVERSE,
STRAIGHT_FEED, ARC_FEED (and RIGID_TAP: there and back) mapped to machine coordinates as LinuxCNC's canon does
(``emccanon.cc`` ``rotate_and_offset_pos``: X Y plus the G92 offset rotated by the G10 R rotation, plus the work
offset and the tool length offset, each converted to mm with the length units in force when it was set), the
arc centres in the arc's plane, direction and turns, and the A B C positions, with vcnc's blocks; zero-length
moves are dropped on both sides (vcnc emits none). Two points are the same within rs274's printed digits (4
decimals in the units of the call).

Prints one row per program (``--list``: all, else the differing ones) and a table of counts:
both accept and match / both accept and differ (the first differing move) / rs274 accepts and vcnc refuses
(vcnc's message) / vcnc accepts and rs274 refuses, with a note of vcnc that says so (``NOTED``: a documented
leniency) or without (rs274's message; the motion before rs274's error is compared too) / both refuse.

Known differences that are rs274's, not LinuxCNC's: after a tool change (M6) the interpreter takes its position
from the canon (interp_execute.cc, ``toolchange_flag``), and the standalone canon returns the last programmed point
without the offsets (saicanon.cc ``GET_EXTERNAL_POSITION_Z``: ``_program_position_z``) where the machine's removes
them (emccanon.cc ``GET_EXTERNAL_POSITION``: ``unoffset_and_unrotate_pos``); so rs274 moves Z by a tool length
offset taken with or after the M6 on the next move without a Z word ("T1 M6 G43 H1" then "G0 X1 Y1"), where
LinuxCNC and vcnc keep the tool still. Also: user M codes (M100-M199) beside a program are not run by rs274, whose
standalone canon knows none; vcnc's ``linuxcnc`` dialect looks for them in the program's folder. M61 does not put
the tool into the spindle's entry of rs274's tool table (saicanon.cc ``CHANGE_TOOL_NUMBER`` sets the slot only, where
LinuxCNC's task loads it, task/taskclass.cc ``emcToolSetNumber``), so G43 without H and G41/G42 without D after M61
take the tool before it in rs274. A tool length offset in force at G20/G21 is read back unconverted
(saicanon.cc ``GET_EXTERNAL_TOOL_LENGTH_ZOFFSET``; emccanon.cc converts it, ``TO_PROG_LEN``), so rs274 takes a length
set in mm as inch (or back) at the next G43.2, G53 or change of offset under G91. The generated programs
(``--generate``) avoid these three. After an M66 wait (L1-L4) rs274 reads ``#5399`` as 0 (saicanon.cc: no inputs),
where vcnc takes the awaited level (1 after L1/L3): a program that moves by ``#5399`` differs there.
One difference is the interpreter's own, so LinuxCNC's too: a G20 or G21 inside a canned-cycle series leaves the
initial level (OLD_Z) a number in the old units (interp_cycles.cc keeps ``cycle_il`` in program units, which
interp_convert.cc ``convert_length_units`` does not scale as it scales the current point and the offsets), so
``G21 G0 Z10`` / ``G98 G81 X1 Z-5 R2`` / ``G20 X0.1`` retracts to 10 inch (254 mm); vcnc keeps the level where the
series began, the "original Z position" of g-code.adoc 'Retract Mode' (10 mm, under R2 in inch: R, 50.8 mm).

Usage: ``python benchmarks/linuxcnc_diff.py [--list] [--files-from LIST] [PROGRAM|DIRECTORY ...]``
(a directory: its ``.ngc .nc .gcode .tap`` files, recursively), or with generated programs instead
(``benchmarks/linuxcnc_fuzz.py``): ``--generate N --seed S [--features arcs,cycles,...] [--out DIR]``, programs of
seeds S to S+N-1, each program that does not match written to DIR as ``fuzz-<seed>.ngc`` to inspect, and a table of
outcomes per feature group (a program counts in each group it draws). Runs only when ``rs274`` is on PATH (LinuxCNC's
``linuxcnc-uspace`` package); otherwise it says so and exits 0. rs274 runs with its own ``HOME`` in a temporary
folder, so it leaves no tool table file (``.tool.mmap``) in the user's home.
"""

from __future__ import annotations

import argparse
import collections
import dataclasses
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.linuxcnc_fuzz import FEATURES, generate  # noqa: E402
from interpolators import load_program  # noqa: E402
from interpolators.context import DIALECTS, MachineContext, read_tool_table  # noqa: E402
from vcnc.errors import GCodeError  # noqa: E402

INCH = 25.4  # [mm/inch]
#: File name endings of programs looked for in a directory.
PROGRAM_SUFFIXES = (".ngc", ".nc", ".gcode", ".tap")
#: One canonical call of rs274's output: ``   12 N..... NAME(args)``; a block number of six digits or more runs
#: into the name (``N002922SET_SPINDLE_MODE(0 0.0000)``: rs274 prints it in a five-character field).
CANONICAL = re.compile(r"^\s*(?:\d+\s+)?N[.\d]+\s*([A-Z_][A-Z0-9_]*)\((.*)\)\s*$")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
#: rs274's error at a file without ``%`` or ``M2``/``M30`` at its end (vcnc reads such a file to its end).
#: rs274's refusals vcnc runs with a note, and a part of that note's text (``Program.notes``).
NOTED = {"File ended with no percent sign": "no M2/M30", "K word given for arc": "K0 on", "I word given for arc":
         "I0 on", "J word given for arc": "J0 on", "Cannot use axis values without a g code": "after G80",
         "Nested comment found": "nested", "Bad character '%'": "'%' lines", "Unknown m code": "Unknown m code",
         "Unknown g code": "Unknown g code", "Cannot use two g codes that both use axis values": "in one block",
         "Cannot do g1 with zero feed rate": "G1 alone", "Bad character '\\357'": "byte-order mark",
         "Bad character '+' used": "outside [ ]", "Bad character '-' used": "outside [ ]",
         "Bad character '*' used": "outside [ ]", "Bad character '/' used": "outside [ ]",
         "Dwell time missing with g4": "G04 X", "Command too long": "Command too long",
         "Unknown word starting with f": "macro B", "Bad character 'w' used": "macro B",
         "Unknown word where unary operation could be": "macro B",
         "Cannot restore context from invalid stack frame": "M72 with no modal state saved",
         "no matching while/do label": "in a repeat loop", "H word with no G43": "H word without G43",
         "D word with no G41": "D word without G41"}
#: rs274's refusal of a reused O-word label, which vcnc notes (its message begins with the line number).
DUPLICATE_LABEL = re.compile(r"\d+: duplicate O-word label")
#: The line number before rs274's O-word messages ("4: no matching while/do label").
LINE_PREFIX = re.compile(r"^\d+: ")
#: A G5/G5.1 spline block or a G5.2 .. G5.3 NURBS (vcnc reads them as chords; a NURBS's chords are the G5.3
#: block's) and a block that names another motion mode.
SPLINE = re.compile(r"G0*5(?:\.[123])?(?![\d.])", re.I)
MOTION = re.compile(r"G0*[0-3](?![\d.])|G0*80|G0*8[1-9]|G0*7[36]|G0*33", re.I)
ARC = re.compile(r"G0*[23](?![\d.])", re.I)
#: How far vcnc's arc centre may be from rs274's: vcnc moves the centre so that both ends are on the circle,
#: within the arc end-point tolerance it accepts (LinuxCNC's programs are checked to 0.0005 inch or 0.1 %) [mm].
CENTRE_TOLERANCE = 0.015
NO_END = "File ended with no percent sign or program end"
G64 = re.compile(r"G0*64(?![\d.])", re.I)


@dataclasses.dataclass(frozen=True, kw_only=True)
class Move:
    """One motion end point in machine coordinates.

    Attributes
    ----------
    kind : str
        ``"rapid"``, ``"line"`` or ``"arc"``.
    xyz : ndarray, shape (3,)
        End point [mm].
    abc : ndarray, shape (3,)
        Rotary axes at the end [deg].
    center : ndarray, shape (3,), or None
        Arc centre [mm] (its component along the plane normal is not compared).
    normal : int
        Axis index of the arc plane's normal (2 for G17, 0 for G19, 1 for G18).
    rotation : int
        LinuxCNC's ARC_FEED rotation: the number of turns started, positive counter-clockwise (0 for lines).
    line : int
        Program line (vcnc's moves; 0 for rs274's).
    unit : float
        Length of one printed unit [mm] (rs274's moves: 1 or 25.4; vcnc's: 1).
    slack : float
        How far the printed (rounded to 4 decimals) offsets in force may be from the interpreter's [mm]: half a
        printed digit of each, in the units in force when it was printed (a G52 set in mm and printed again in
        inch after G20 is rounded to 0.00005 inch).
    """

    kind: str
    xyz: np.ndarray
    abc: np.ndarray
    center: np.ndarray | None = None
    normal: int = 2
    rotation: int = 0
    line: int = 0
    unit: float = 1.0
    slack: float = 0.0


@dataclasses.dataclass(frozen=True, kw_only=True)
class Rs274Result:
    """What rs274 made of a program: its moves and, if it refused it, its message (else "")."""

    moves: list[Move]
    error: str


def _canon_state_update(name: str, args: str, nums: list[float], state: dict) -> None:
    """Follow the canonical calls that set units, offsets, rotation, tool length and plane (``emccanon.cc``:
    each offset is converted from program units when it is set)."""
    if name == "USE_LENGTH_UNITS":
        state["unit"] = INCH if "INCHES" in args else 10.0 if "_CM" in args else 1.0
    elif name == "SET_G5X_OFFSET":
        state["g5x"] = np.array(nums[1:4]) * state["unit"]
        state["g5x_slack"] = 0.5e-4 * state["unit"]
        state["g5x_abc"] = np.array(nums[4:7])
    elif name == "SET_G92_OFFSET":
        state["g92"] = np.array(nums[:3]) * state["unit"]
        state["g92_slack"] = 0.5e-4 * state["unit"]
        state["g92_abc"] = np.array(nums[3:6])
    elif name == "SET_XY_ROTATION":
        state["rotation"] = math.radians(nums[0])
    elif name == "USE_TOOL_LENGTH_OFFSET":
        state["tool"] = np.array(nums[:3]) * state["unit"]
        state["tool_slack"] = 0.5e-4 * state["unit"]
        state["tool_abc"] = np.array(nums[3:6])
    elif name == "SELECT_PLANE":
        state["plane"] = args.rsplit("_", 1)[-1].strip()


def _to_machine(p: np.ndarray, state: dict) -> np.ndarray:
    """A point of a canonical call (program units, offsets removed) in machine coordinates [mm]."""
    p = p * state["unit"] + state["g92"]
    c, s = math.cos(state["rotation"]), math.sin(state["rotation"])
    return np.array([c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]) + state["g5x"] + state["tool"]


def _turned_rounding(state: dict) -> float:
    """What a G10 L2 R rotation adds to the rounding of a printed point [mm]: rs274 prints the point before the
    canon turns it (with the G92 offset), each coordinate within half its last digit; turned by the angle, a
    machine coordinate is within that times |cos| + |sin| (up to sqrt 2 at 45 degrees; fuzz seed 306464: a G41
    arc end under R-45 in inch, 1.8 um off)."""
    turn = abs(math.cos(state["rotation"])) + abs(math.sin(state["rotation"])) - 1.0
    return turn * (0.5e-4 * state["unit"] + (state["g92_slack"] if np.any(state["g92"]) else 0.0))


def canonical_moves(output: str) -> list[Move]:
    """The moves of rs274's printed canonical calls, in machine coordinates.

    ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end, a, b, c) names the end and the
    centre in the plane's axes: XY (x, y; z), YZ (y, z; x), XZ (z, x; y) (``saicanon.cc``).
    """
    state = {"unit": 1.0, "g5x": np.zeros(3), "g92": np.zeros(3), "tool": np.zeros(3), "rotation": 0.0,
             "plane": "XY", "g5x_abc": np.zeros(3), "g92_abc": np.zeros(3), "tool_abc": np.zeros(3), "g5x_slack": 0.0,
             "g92_slack": 0.0, "tool_slack": 0.0}
    order = {"XY": (0, 1, 2), "YZ": (1, 2, 0), "XZ": (2, 0, 1)}  # plane axes -> (first, second, normal)
    moves: list[Move] = []
    for line in output.splitlines():
        m = CANONICAL.match(line)
        if m is None:
            continue
        name, args = m.groups()
        nums = [float(v) for v in NUMBER.findall(args)]
        _canon_state_update(name, args, nums, state)
        if name == "NURBS_FEED":  # G5/G5.1/G5.2: rs274 prints no end point ("NURBS_FEED(3, ...)")
            if not (moves and moves[-1].kind == "spline"):
                moves.append(Move(kind="spline", xyz=np.full(3, np.nan), abc=np.zeros(3), unit=state["unit"]))
            continue
        if name not in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "RIGID_TAP"):
            continue
        abc_offset = state["g5x_abc"] + state["g92_abc"] + state["tool_abc"]
        center, normal, rotation = None, 2, 0
        if name == "ARC_FEED":
            first, second, normal = order[state["plane"]]
            end, cen = np.zeros(3), np.zeros(3)
            end[[first, second, normal]] = nums[0], nums[1], nums[5]
            cen[[first, second, normal]] = nums[2], nums[3], nums[5]
            rotation, abc = int(nums[4]), np.array(nums[6:9])
            center = _to_machine(cen, state)
        else:
            end, abc = np.array(nums[:3]), np.array(nums[3:6])
        kind = {"STRAIGHT_TRAVERSE": "rapid", "ARC_FEED": "arc"}.get(name, "line")
        start = moves[-1] if moves else None
        if name == "RIGID_TAP":  # prints no A B C: they stay where they are
            abc = (start.abc if start else np.zeros(3)) - abc_offset
        slack = sum(state[f"{k}_slack"] for k in ("g5x", "g92", "tool") if np.any(state[k])) + _turned_rounding(state)
        moves.append(Move(kind=kind, xyz=_to_machine(end, state), abc=abc + abc_offset, center=center,
                          normal=normal, rotation=rotation, unit=state["unit"], slack=slack))
        if name == "RIGID_TAP":  # taps to x, y, z and returns to its start (emccanon.cc)
            moves.append(dataclasses.replace(start, kind="line") if start else Move(
                kind="line", xyz=np.zeros(3), abc=np.zeros(3)))
    return moves


def run_rs274(program: Path, *, tool_table: Path, subroutine_path: tuple[str, ...], workdir: Path,
              timeout: float) -> Rs274Result:
    """Run ``rs274 -g`` on a program in ``workdir`` (its HOME too), with the tool table and an INI that names
    the subroutine folders (the program's own first)."""
    ini = workdir / "rs274.ini"
    folders = ":".join((str(program.resolve().parent), *subroutine_path))
    ini.write_text(f"[RS274NGC]\nSUBROUTINE_PATH = {folders}\n")
    env = dict(os.environ, HOME=str(workdir))
    try:
        run = subprocess.run(["rs274", "-g", "-t", str(tool_table), "-i", str(ini), str(program.resolve())],
                             cwd=workdir, env=env, capture_output=True, stdin=subprocess.DEVNULL, timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        out = exc.stdout.decode("latin-1") if exc.stdout else ""
        return Rs274Result(moves=canonical_moves(out), error=f"no end within {timeout:g} s")
    out, err = run.stdout.decode("latin-1"), run.stderr.decode("latin-1")
    message = " | ".join(s for s in err.splitlines() if s.strip() and s.strip() != "executing")
    if run.returncode != 0 and not message:
        message = f"exit status {run.returncode}"
    return Rs274Result(moves=canonical_moves(out), error=message if run.returncode != 0 else "")


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def vcnc_moves(program: Path, context: MachineContext, timeout: int) -> tuple[list[Move], str, tuple[str, ...]]:
    """vcnc's moves of a program in machine coordinates, its error message ("" if it accepts) and its notes."""
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(timeout)
    try:
        prog = load_program(program, context=context)
    except GCodeError as exc:
        return [], str(exc).replace("\n", " "), ()
    except _Timeout:
        return [], f"no end within {timeout} s", ()
    finally:
        signal.alarm(0)
    moves: list[Move] = []
    for b in prog.blocks:
        if b.kind == "dwell":
            continue
        if SPLINE.search(b.text) or (moves and moves[-1].kind == "spline" and not MOTION.search(b.text)):
            if moves and moves[-1].kind == "spline":  # one spline run, as rs274's NURBS_FEED calls
                moves.pop()
            moves.append(Move(kind="spline", xyz=np.asarray(b.target, dtype=float), abc=np.zeros(3), line=b.line))
            continue
        abc = np.zeros(3) if b.extra_target is None else np.asarray(b.extra_target[:3], dtype=float)
        if b.kind == "line" and ARC.search(b.text) and moves and moves[-1].line == b.line and moves[-1].kind == "arc" \
                and moves[-1].center is None:  # an arc vcnc reads as chords (a G18/G19 arc under a G10 R rotation)
            moves[-1] = dataclasses.replace(moves[-1], xyz=np.asarray(b.target, dtype=float), abc=abc)
            continue
        if b.kind == "line" and ARC.search(b.text):
            moves.append(Move(kind="arc", xyz=np.asarray(b.target, dtype=float), abc=abc, line=b.line))
            continue
        center, normal, rotation = None, 2, 0
        if b.kind.startswith("arc") and moves and moves[-1].line == b.line and moves[-1].kind == "arc" \
                and moves[-1].center is None:  # a straight bridge before the arc (cutter compensation: the
            moves.pop()  # tool's offset point to the arc's, which LinuxCNC joins by a spiral arc)
        if b.kind.startswith("arc"):
            seg = b.segment
            center, normal = np.asarray(seg.center, dtype=float), seg.plane
            rotation = math.ceil(abs(seg.sweep) / (2 * math.pi) - 1e-9) * (1 if seg.ccw else -1)
        moves.append(Move(kind="arc" if b.kind.startswith("arc") else b.kind, xyz=np.asarray(b.target, dtype=float),
                          abc=abc, center=center, normal=normal, rotation=rotation, line=b.line))
    return moves, "", prog.notes


def without_repeats(moves: list[Move], *, printed: bool = True) -> list[Move]:
    """The moves without straight ones that end where the one before ended, or at the start (home, the origin),
    up to the printed digits (``printed``: rs274's moves) or exactly (vcnc's)."""
    out: list[Move] = []
    last = Move(kind="rapid", xyz=np.zeros(3), abc=np.zeros(3))
    for m in moves:
        tol = 6e-5 * m.unit + 1e-6 + m.slack + last.slack if printed else 1e-9
        same = np.allclose(last.xyz, m.xyz, atol=tol, rtol=0.0) and np.allclose(last.abc, m.abc, atol=1e-3, rtol=0.0)
        if m.kind in ("rapid", "line") and same:
            continue
        out.append(m)
        last = m if m.kind != "spline" else dataclasses.replace(m, xyz=np.full(3, np.nan))
    return out


def _arc_middle(start: np.ndarray, m: Move) -> np.ndarray:
    """The point halfway along an arc's first turn, in its plane (axes in the order that makes counter-clockwise
    positive: XY, YZ, ZX), at the mean of its start and end radii [mm]."""
    p, q = {2: (0, 1), 0: (1, 2), 1: (2, 0)}[m.normal]
    c = m.center
    a0 = math.atan2(start[q] - c[q], start[p] - c[p])
    a1 = math.atan2(m.xyz[q] - c[q], m.xyz[p] - c[p])
    sweep = (a1 - a0) % (2 * math.pi) if m.rotation > 0 else -((a0 - a1) % (2 * math.pi))
    sweep = sweep or math.copysign(2 * math.pi, m.rotation)
    r = 0.5 * (math.hypot(start[p] - c[p], start[q] - c[q]) + math.hypot(m.xyz[p] - c[p], m.xyz[q] - c[q]))
    a = a0 + 0.5 * sweep
    return np.array([c[p] + r * math.cos(a), c[q] + r * math.sin(a)])


def _same_centre(w: Move, g: Move, before: Move | None) -> bool:
    """Whether vcnc's arc is rs274's: the centres within :data:`CENTRE_TOLERANCE` in the plane, or the points
    halfway along the arcs within it plus the difference of rs274's start and end radii. rs274 prints the
    programmed centre, which LinuxCNC accepts off the two ends' bisector within its tolerance (and runs a spiral);
    vcnc moves the centre onto the bisector, far on a short arc, with hardly a change of the path."""
    plane = [k for k in range(3) if k != w.normal]
    if np.linalg.norm((g.center - w.center)[plane]) <= CENTRE_TOLERANCE:
        return True
    start = before.xyz if before is not None and before.kind != "spline" else np.zeros(3)
    rs, re_ = (float(np.linalg.norm((p - w.center)[plane])) for p in (start, w.xyz))
    gap = np.linalg.norm(_arc_middle(start, w) - _arc_middle(start, g))
    return bool(gap <= CENTRE_TOLERANCE + abs(rs - re_))


def _move_difference(w: Move, g: Move, before: Move | None) -> str:
    """How vcnc's move ``g`` differs from rs274's ``w`` ("" if it does not)."""
    tol = (0.5e-4 + 1e-5) * w.unit + w.slack  # 4 printed decimals: 0.5e-4 for the end point, the offsets' slack
    if w.kind != g.kind:
        return f"kind {g.kind}, rs274 {w.kind} at {np.round(w.xyz, 4).tolist()}"
    if w.kind == "spline":  # rs274 prints no end point: the moves after it tell
        return ""
    if not np.allclose(w.xyz, g.xyz, atol=tol, rtol=0.0):
        return f"end {np.round(g.xyz, 4).tolist()} mm, rs274 {np.round(w.xyz, 4).tolist()} mm"
    if not np.allclose(w.abc, g.abc, atol=3e-4, rtol=0.0):
        return f"ABC {np.round(g.abc, 4).tolist()}, rs274 {np.round(w.abc, 4).tolist()}"
    if w.kind == "arc" and g.center is not None:
        if w.normal != g.normal or w.rotation != g.rotation or not _same_centre(w, g, before):
            return (f"arc centre {np.round(g.center, 4).tolist()} rotation {g.rotation}, rs274 "
                    f"{np.round(w.center, 4).tolist()} rotation {w.rotation}")
    return ""


def _tiny(moves: list[Move], k: int, unit: float) -> bool:
    """Whether move ``k`` is a straight move shorter than rs274 prints (its end rounds to the one before)."""
    return k > 0 and moves[k].kind in ("rapid", "line") and moves[k - 1].kind != "spline" and bool(np.allclose(
        moves[k].xyz, moves[k - 1].xyz, atol=1.5e-4 * unit, rtol=0.0))


def naive_cam_tolerance(text: str) -> float:
    """The largest tolerance of LinuxCNC's "Naive CAM Detector" the program's G64 blocks set [mm], 0 without: rs274
    joins straight feed moves at the same feed that are less than it away from collinear into one (g-code.adoc
    G64: "If you set Q to a non-zero value it turns on the 'Naive CAM Detector' [...] If Q is not specified then it
    will have the same behavior as before and use the value of P-"), where vcnc keeps each programmed point. In
    inch after a G20 before the G64 line (our reading of a program's units; no program seen switches back)."""
    tol, inch = 0.0, False
    for line in text.splitlines():
        code = re.sub(r"\([^)]*\)|;.*", "", line)
        inch = inch or bool(re.search(r"G0*20(?![\d.])", code, re.I))
        if not G64.search(code):
            continue
        words = {m.group(1).upper(): float(m.group(2)) for m in re.finditer(r"([PQ])\s*([-+]?(?:\d+\.?\d*|\.\d+))",
                                                                          code, re.I)}
        tol = max(tol, words.get("Q", words.get("P", 0.0)) * (INCH if inch else 1.0))
    return tol


def _merged(want: list[Move], i: int, g: Move, tolerance: float) -> bool:
    """Whether vcnc's straight feed ``g`` ends within ``tolerance`` of rs274's straight feed ``want[i]``, which
    rs274's naive CAM detector made of it and the moves around it (:func:`naive_cam_tolerance`)."""
    if not tolerance or i == 0 or g.kind != "line" or want[i].kind != "line" or want[i - 1].kind == "spline":
        return False
    a, b = want[i - 1].xyz, want[i].xyz
    d = b - a
    t = float(np.clip(np.dot(g.xyz - a, d) / max(float(np.dot(d, d)), 1e-30), 0.0, 1.0))
    return bool(np.linalg.norm(a + t * d - g.xyz) <= tolerance + 1e-4 * want[i].unit)


def _at_spline_end(want: list[Move], i: int, got: list[Move], k: int) -> bool:
    """Whether rs274's straight move ``want[i]`` right after a spline run ends where vcnc's spline run before
    ``got[k]`` ends: a zero-length move (``G1`` without axis words prints STRAIGHT_FEED to the current point) that
    :func:`without_repeats` cannot drop, rs274 printing no spline end."""
    return (i > 0 and k > 0 and want[i - 1].kind == "spline" and got[k - 1].kind == "spline"
            and want[i].kind in ("rapid", "line") and bool(np.allclose(want[i].xyz, got[k - 1].xyz,
                                                                       atol=1.5e-4 * want[i].unit + want[i].slack,
                                                                       rtol=0.0)))


def first_difference(want: list[Move], got: list[Move], *, prefix: bool = False, merge: float = 0.0) -> str:
    """"" if vcnc's moves (``got``) are rs274's (``want``), else the first that differs and how. A straight move
    shorter than a printed digit on one side only is passed over (rs274 rounds it to a zero-length call, dropped).
    With ``prefix``, vcnc may have more moves (rs274 stopped at an error). ``merge``: the naive CAM tolerance
    [mm]; vcnc's straight feeds that end on rs274's joined one within it are passed over (:func:`_merged`)."""
    i = k = 0
    while i < len(want) and k < len(got):
        diff = _move_difference(want[i], got[k], want[i - 1] if i else None)
        skip_got, skip_want = _tiny(got, k, want[i].unit), _tiny(want, i, want[i].unit)
        if not diff:
            i, k = i + 1, k + 1
        elif skip_got and skip_want:  # both: the one after which the next moves agree
            nxt = k + 1 < len(got) and not _move_difference(want[i], got[k + 1], want[i - 1] if i else None)
            i, k = (i, k + 1) if nxt else (i + 1, k)
        elif skip_got:
            k += 1
        elif skip_want:
            i += 1
        elif _merged(want, i, got[k], merge):
            k += 1
        elif _at_spline_end(want, i, got, k):
            i += 1
        else:
            return f"move {i + 1} (vcnc line {got[k].line}): {diff}"
    while i < len(want) and _at_spline_end(want, i, got, k):
        i += 1
    if (i < len(want) or k < len(got)) and not (prefix and i == len(want)):
        return f"{len(got)} moves, rs274 {len(want)}"
    return ""


def default_tool_table(path: Path) -> Path:
    """Write a LinuxCNC tool table (inch) of tools 1 to 999 (pockets as many, below emctool.h CANON_POCKETS_MAX
    1001; CAM posts number tools 212 and up): length 0.1 + 0.01 T, diameter 0.01 + 0.0001 T."""
    path.write_text("".join(f"T{t} P{t} D{0.01 + 0.0001 * t:.4f} Z+{0.1 + 0.01 * t:.4f}\n" for t in range(1, 1000)))
    return path


def compare(program: Path, *, context: MachineContext, tool_table: Path, subroutine_path: tuple[str, ...],
            workdir: Path, timeout: float) -> dict:
    """One program through both: its outcome (``match``, ``differ``, ``rs274 only``, ``vcnc noted``, ``vcnc only``,
    ``both refuse``) and the detail (the first difference or the refusing side's message)."""
    ctx = dataclasses.replace(context, dialect=dataclasses.replace(context.dialect, subroutine_path=subroutine_path))
    rs = run_rs274(program, tool_table=tool_table, subroutine_path=subroutine_path, workdir=workdir,
                   timeout=timeout)
    got, verror, notes = vcnc_moves(program, ctx, int(timeout) + 1)
    want, got = without_repeats(rs.moves), without_repeats(got, printed=False)
    if rs.error and verror:
        return {"outcome": "both refuse", "detail": f"rs274: {rs.error} || vcnc: {verror}"}
    if verror:
        return {"outcome": "rs274 only", "detail": verror}
    diff = first_difference(want, got, prefix=bool(rs.error),
                            merge=naive_cam_tolerance(program.read_text(encoding="latin-1")))
    if rs.error:
        before = f"; before it: {diff}" if diff else "; the moves before it match"
        key = "O-word label" if DUPLICATE_LABEL.match(rs.error) else \
            next((v for k, v in NOTED.items() if LINE_PREFIX.sub("", rs.error).startswith(k)), None)
        noted = [n for n in notes if "LinuxCNC refuses" in n and key is not None and key in n]
        if noted:
            return {"outcome": "vcnc noted", "detail": f"{rs.error}{before}; vcnc notes: {' | '.join(noted)}"}
        return {"outcome": "vcnc only", "detail": f"{rs.error}{before}"}
    return {"outcome": "differ" if diff else "match", "detail": diff or f"{len(want)} moves"}


def program_paths(args: list[str], files_from: str | None) -> list[Path]:
    """Programs named on the command line (files, or directories searched for programs) and in ``files_from``
    (one path per line)."""
    names = list(args)
    if files_from:
        names += [s for s in Path(files_from).read_text().splitlines() if s.strip()]
    out: list[Path] = []
    for n in names:
        p = Path(n)
        if p.is_dir():
            out += sorted(f for f in p.rglob("*") if f.is_file() and f.suffix.lower() in PROGRAM_SUFFIXES)
        else:
            out.append(p)
    return out


OUTCOMES = ("match", "differ", "rs274 only", "vcnc noted", "vcnc only", "both refuse")


def run_generated(args: argparse.Namespace, compare_one) -> int:
    """``--generate``: programs of seeds ``args.seed`` on, compared one by one (``compare_one(path)``); those that
    do not match are kept in ``args.out``; prints the outcomes per feature group."""
    features = tuple(s for s in args.features.split(",") if s) if args.features else tuple(FEATURES)
    out = Path(args.out) if args.out else None
    if out:
        out.mkdir(parents=True, exist_ok=True)
    counts: collections.Counter[str] = collections.Counter()
    per_group: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    with tempfile.TemporaryDirectory(prefix="linuxcnc_fuzz-") as tmp:
        for seed in range(args.seed, args.seed + args.generate):
            text, used = generate(seed, features=features)
            path = Path(tmp) / f"fuzz-{seed}.ngc"
            path.write_text(text)
            res = compare_one(path)
            counts[res["outcome"]] += 1
            for group in set(used):
                per_group[group][res["outcome"]] += 1
            if args.list or res["outcome"] != "match":
                print(f"{res['outcome']}\t{seed}\t{res['detail']}", flush=True)
                if out:
                    (out / path.name).write_text(text)
    print(f"\n{args.generate} programs, seeds {args.seed}..{args.seed + args.generate - 1}")
    print(f"{'group':14s}" + "".join(f"{o:>12s}" for o in OUTCOMES))
    for group in sorted(per_group):
        print(f"{group:14s}" + "".join(f"{per_group[group][o]:12d}" for o in OUTCOMES))
    print(f"{'all':14s}" + "".join(f"{counts[o]:12d}" for o in OUTCOMES))
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("programs", nargs="*", help="program files or directories")
    ap.add_argument("--files-from", help="a file naming one program per line")
    ap.add_argument("--tool-table", help="LinuxCNC tool table in inch (default: tools 1-999, generated)")
    ap.add_argument("--subroutine-path", default="", help="folders searched for o<name> files, ':'-separated")
    ap.add_argument("--timeout", type=float, default=30.0, help="time limit per program and side [s]")
    ap.add_argument("--list", action="store_true", help="print every program, not only the differing ones")
    ap.add_argument("--generate", type=int, default=0, help="compare N generated programs instead")
    ap.add_argument("--seed", type=int, default=0, help="first seed of the generated programs")
    ap.add_argument("--features", default="", help=f"feature groups to draw from, ','-separated: {','.join(FEATURES)}")
    ap.add_argument("--out", help="folder for the generated programs that do not match")
    args = ap.parse_args()
    if shutil.which("rs274") is None:
        print("rs274 (LinuxCNC's standalone interpreter, package linuxcnc-uspace) is not on PATH: nothing to run")
        return 0
    programs = program_paths(args.programs, args.files_from)
    if not programs and not args.generate:
        print("no programs given")
        return 0
    sub_path = tuple(s for s in args.subroutine_path.split(":") if s)
    counts: collections.Counter[str] = collections.Counter()
    with tempfile.TemporaryDirectory(prefix="linuxcnc_diff-") as tmp:
        workdir = Path(tmp)
        table = Path(args.tool_table) if args.tool_table else default_tool_table(workdir / "tools.tbl")
        context = MachineContext(tools=read_tool_table(str(table), units="inch"), extra_axes=("a", "b", "c"),
                                 dialect=DIALECTS["linuxcnc"], linear_units="inch")
        if args.generate:
            return run_generated(args, lambda p: compare(p, context=context, tool_table=table, subroutine_path=sub_path,
                                                         workdir=workdir, timeout=args.timeout))
        for p in programs:
            res = compare(p, context=context, tool_table=table, subroutine_path=sub_path, workdir=workdir,
                          timeout=args.timeout)
            counts[res["outcome"]] += 1
            if args.list or res["outcome"] != "match":
                print(f"{res['outcome']}\t{p}\t{res['detail']}", flush=True)
    print(f"\n{len(programs)} programs")
    for outcome in OUTCOMES:
        print(f"{outcome:12s} {counts[outcome]:5d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
