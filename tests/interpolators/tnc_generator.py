"""Seeded random HEIDENHAIN TNC conversational programs, for checking the reader against the reference.

Test code only. :func:`generate` writes a valid program of what real TNC programs mix: ``BEGIN PGM .. MM|INCH``,
``BLK FORM``, ``TOOL DEF``/``TOOL CALL`` (DL/DR, S, F), ``L`` with absolute and incremental words, RL/RR
compensated contours entered and left by ``L`` or ``APPR``/``DEP``, ``F``/``FMAX``/``F AUTO``, ``CC`` (absolute,
incremental), ``C``, ``CR``, ``CT``, ``CP`` (IPA, IZ helix), ``LP`` (PR/PA, IPR/IPA), ``RND``/``CHF``, Q parameters
(``FN 0``-``FN 4``, formulas) in coordinates and feeds, ``LBL``/``CALL LBL REP`` (nested, and a subprogram after
``M30``), cycles 7 (absolute and incremental), 9, 32, drilling 1/200/203/205 called by ``CYCL CALL``, ``M99``,
``CYCL CALL POS`` and ``CYCL CALL PAT`` (``PATTERN DEF`` items continued by ``~`` or on lines of their own),
pockets 251/252 (:meth:`_Gen.pocket`), ``M91``/``M92`` and ``M140 MB``; on a B/C table (:func:`context`, a quarter
of the seeds) ``PLANE SPATIAL`` (also with ``TABLE ROT``/``COORD ROT``), ``PROJECTED``, ``EULER``, ``VECTOR``,
``POINTS`` and ``AXIAL`` (:meth:`_Gen.plane_definition`; ``TURN`` or ``MOVE``; also followed by ``PLANE RELATIV``)/
``PLANE RESET`` and ``M128`` with B C or ``FUNCTION TCPM`` with ``LN X Y Z TX TY TZ`` (:meth:`_Gen.tilted`); from a
stream of their own (:class:`_Extras`, session 40) the milling cycles 208/240/253/256/257/262-265/267, the SL cycles
(14 or ``CONTOUR DEF``, 20, 22/23/24, 25) with a tool of their own, the old cycles 1/2/17 on patterns 220/221,
``FN 9``, ``FN 18 SYSREAD ID270`` and ``QS`` strings.

The generator keeps the geometry the TNC accepts (TNC 640 conversational user's manual, "Path contours -
Cartesian coordinates" and "Polar coordinates"): a ``C`` end on the circle about ``CC`` (exactly, or at any angle
rounded to 4 places, within the TNC's input tolerance), a ``CR`` chord shorter than the diameter, corners of 25-155
degrees for ``RND``/``CHF`` and of 0.2-3 degrees between elements (the transition arc or the intersection of the
compensated paths), elements of at least 8 units beside a tool radius of at most 3, ``IPA``/``IPR`` only after a
polar block about the same pole. A pole is kept across cycles 7, 8, 10, 11 and TOOL CALL (its program coordinates,
:attr:`interpolators.heidenhain.Machine.pole`), and ``CC`` without coordinates sets it at the last programmed point.
"""

from __future__ import annotations

import math
import random
import re

from interpolators.context import MachineContext
from interpolators.tilted import Kinematics, RotaryAxis

__all__ = ["generate", "context", "five_axis"]

#: The tilting table of the five-axis seeds: B about Y round (0, 0, -50), C about Z through the machine zero.
BC_TABLE = Kinematics(axes=(RotaryAxis(name="b", pivot=(0.0, 0.0, -50.0), limits=(-120.0, 120.0)),
                            RotaryAxis(name="c")))


def five_axis(seed: int) -> bool:
    """The program of ``seed`` runs on :data:`BC_TABLE` (about a quarter of the seeds)."""
    return random.Random(f"{seed}:five").random() < 0.25


def context(seed: int) -> MachineContext:
    """The machine the program of ``seed`` runs on: the machine-defined position (M92, MB MAX) at Z 300, and on
    the five-axis seeds the B/C table."""
    if five_axis(seed):
        return MachineContext(home=(0.0, 0.0, 300.0), extra_axes=("b", "c"), kinematics=BC_TABLE)
    return MachineContext(home=(0.0, 0.0, 300.0))


#: Whole vectors of length 25 in all directions (C arc ends exactly on their circle).
_RADII = sorted({(sx * u, sy * v) for u, v in ((0, 25), (7, 24), (15, 20), (20, 15), (24, 7), (25, 0))
                 for sx in (-1, 1) for sy in (-1, 1)})


def _n(v: float) -> str:
    """A signed TNC number with at most 4 decimals."""
    s = f"{v:+.4f}".rstrip("0").rstrip(".")
    return "+0" if s in ("+", "-", "-0", "+0") else s


class _Gen:
    def __init__(self, seed: int):
        self.r = random.Random(seed)
        self.five = five_axis(seed)
        self.blocks: list[list[str]] = []
        self.pos = [0.0, 0.0, 50.0]  # program coordinates, known after the first absolute XYZ move
        self.known = False
        self.exact = True  # the current point is a 4-decimal one the program states
        self.q: dict[int, float] = {}
        self.words = 0  # coordinates written through a Q parameter
        self.cc: tuple[float, float] | None = None
        self.polar_ok = False  # the last block was a polar move about the current pole
        self.heading: float | None = None  # direction [deg] of the last contour element's end tangent
        self.lbl = 1
        self.subs: list[list[list[str]]] = []
        self.feed_set = False
        self.tool_feed = False
        self.appr = False
        self.comp = "R0"
        self.rounding = False  # a RND/CHF waits for the next element
        self.pole_kept = False  # the pole was set before a transformation or TOOL CALL and not used since
        self.unit = "MM"
        self.last_tool_call = ""  # the TOOL CALL block in force (a section with a tool of its own calls it again)

    # -- output --------------------------------------------------------------------------------
    def emit(self, *lines: str) -> None:
        self.blocks.append(list(lines))

    def coord(self, axis: str, value: float, *, incremental: bool = False, q_ok: bool = True) -> str:
        """``X+12.5`` or ``IX-3``, sometimes through a Q parameter set just before."""
        pre = ("I" if incremental else "") + axis
        if q_ok and self.r.random() < 0.15:
            self.words += 1
            k = 30 + self.words % 20  # a fresh number for each word of a block
            self.emit(f"FN 0: Q{k} = {_n(round(value, 4))}")
            self.q[k] = round(value, 4)
            return f"{pre}+Q{k}"
        return f"{pre}{_n(value)}"

    def feed(self) -> str:
        x = self.r.random()
        if x < 0.5 and self.feed_set:
            return ""
        self.feed_set = True
        if x < 0.6 and self.tool_feed:
            return " F AUTO"
        if x < 0.7 and self.q:
            k = self.r.choice(sorted(self.q))
            if self.q[k] > 1:
                return f" FQ{k}"
        return f" F{self.r.choice([100, 250, 500, 800, 1200])}"

    # -- blocks --------------------------------------------------------------------------------
    def header(self, unit: str) -> None:
        self.unit = unit
        radii = [0, 0.04, 0.1] if unit == "INCH" else [0, 1, 2.5, 3]
        self.emit("BLK FORM 0.1 Z X+0 Y+0 Z-20")
        self.emit("BLK FORM 0.2 X+100 Y+100 Z+0")
        for t in (1, 2):
            if self.r.random() < 0.7:
                self.emit(f"TOOL DEF {t} L{_n(self.r.choice([0, 10, 35.5]))} R{_n(self.r.choice(radii))}")
        self.tool_call()

    def tool_call(self) -> None:
        t = self.r.choice([1, 2])
        words = f"TOOL CALL {t} Z S{self.r.choice([1000, 2500, 8000])}"
        if self.r.random() < 0.4:
            words += f" DL{_n(self.r.choice([-0.5, 0.2, 1]))}"
        if self.r.random() < 0.3:
            words += f" DR{_n(self.r.choice([0.01, 0.05]))}"
        self.tool_feed = self.r.random() < 0.5
        if self.tool_feed:
            words += f" F{self.r.choice([300, 600])}"
        self.emit(words)
        self.last_tool_call = words
        self.feed_set = self.tool_feed
        self.known = False
        self.pole_kept = self.cc is not None

    def q_params(self) -> None:
        for _ in range(self.r.randint(1, 3)):
            k = self.r.randint(1, 20)
            kind = self.r.random()
            a, b = self.r.choice([2, 5, 7.5, 10]), self.r.choice([1, 3, 4, 8])
            if kind < 0.2:
                self.emit(f"FN 0: Q{k} = {_n(a)}")
                v = a
            elif kind < 0.35:
                self.emit(f"FN 1: Q{k} = {_n(a)} + {_n(b)}")
                v = a + b
            elif kind < 0.5:
                self.emit(f"FN 2: Q{k} = {_n(a)} - {_n(b)}")
                v = a - b
            elif kind < 0.65:
                self.emit(f"FN 3: Q{k} = {_n(a)} * {_n(b)}")
                v = a * b
            elif kind < 0.8:
                self.emit(f"FN 4: Q{k} = {_n(a)} DIV {_n(b)}")
                v = a / b
            elif kind < 0.9 or not self.q:
                self.emit(f"Q{k} = ({_n(a)} + {_n(b)}) * 2 - SQRT 16")
                v = (a + b) * 2 - 4
            else:  # from another parameter
                j = self.r.choice(sorted(self.q))
                if self.r.random() < 0.5:
                    self.emit(f"FN 1: Q{k} = +Q{j} + {_n(b)}")
                    v = self.q[j] + b
                else:
                    self.emit(f"Q{k} = ABS (Q{j} * 2) + {_n(b)} / 4")
                    v = abs(self.q[j] * 2) + b / 4
            self.q[k] = v

    def move(self, *, rapid: bool | None = None) -> None:
        """A plain R0 positioning or feed move, absolute or incremental, sometimes with Z."""
        r = self.r
        x, y = round(r.uniform(-40, 140), 4), round(r.uniform(-40, 140), 4)
        z = r.choice([2, 5, 10, 50]) if (r.random() < 0.4 or not self.known) else self.pos[2]
        words = []
        for axis, v, i in (("X", x, 0), ("Y", y, 1), ("Z", z, 2)):
            if not self.known or r.random() < 0.8:
                inc = self.known and self.exact and r.random() < 0.3
                words.append(self.coord(axis, v - self.pos[i] if inc else v, incremental=inc))
        if not words:
            words.append(self.coord("X", x))
            y, z = self.pos[1], self.pos[2]
        fast = r.random() < 0.5 if rapid is None else rapid
        self.emit("L " + " ".join(words) + " R0" + (" FMAX" if fast else self.feed()))
        self.pos = [x if any(w.lstrip("I").startswith("X") for w in words) else self.pos[0],
                    y if any(w.lstrip("I").startswith("Y") for w in words) else self.pos[1],
                    z if any(w.lstrip("I").startswith("Z") for w in words) else self.pos[2]]
        self.known = True
        self.exact = self.exact or len(words) == 3
        self.heading = None

    def machine_move(self) -> None:
        m = self.r.choice(["M91", "M92", "M140"])
        if m == "M140":
            self.emit(self.r.choice(["L M140 MB MAX", "L Z+5 R0 FMAX M140 MB 50", "L M140 MB+20 F500"]))
        else:
            self.emit(f"L Z{_n(self.r.choice([-5, 0, 20]))} R0 FMAX {m}")
        if self.r.random() < 0.5:  # on from where it left the tool: incremental
            self.emit(f"L IX{_n(self.r.choice([5, -8]))} IY+2 R0 FMAX")
        self.known = False

    def datum(self) -> None:
        inc = self.r.random() < 0.4
        dx, dy = self.r.choice([5, 10, -7.5, 20]), self.r.choice([0, 3, -12])
        p = "I" if inc else ""
        self.emit("CYCL DEF 7.0 DATUM SHIFT")
        self.emit(f"CYCL DEF 7.1 {p}X{_n(dx)}")
        self.emit(f"CYCL DEF 7.2 {p}Y{_n(dy)}")
        if self.r.random() < 0.3:
            self.emit(f"CYCL DEF 7.3 {p}Z{_n(self.r.choice([-2, 5]))}")
        self.known = False  # the shift's absolute total is the reader's and the reference's to work out
        # a pole set before the shift stays, in program coordinates: its numbers from the new datum
        # (interpolators.heidenhain.Machine.pole); the current point is another program point now
        self.polar_ok, self.pole_kept = False, self.cc is not None

    def other_cycle(self) -> None:
        if self.r.random() < 0.5:
            self.emit("CYCL DEF 9.0 DWELL TIME")
            self.emit(f"CYCL DEF 9.1 DWELL {self.r.choice(['0.5', '1', '2'])}")
        else:
            self.emit("CYCL DEF 32.0 TOLERANCE")
            self.emit(f"CYCL DEF 32.1 T{self.r.choice(['0.01', '0.05'])}")

    # -- drilling ------------------------------------------------------------------------------
    def drilling(self) -> None:
        r = self.r
        self.emit(f"L X{_n(r.uniform(0, 100))} Y{_n(r.uniform(0, 100))} Z+20 R0 FMAX")
        kind = r.choice([1, 200, 203, 205])
        depth = -r.choice([3, 6, 10, 14])
        if kind == 1:
            self.emit("CYCL DEF 1.0 PECKING")
            self.emit("CYCL DEF 1.1 SET UP 2")
            self.emit(f"CYCL DEF 1.2 DEPTH {_n(depth)}")
            self.emit(f"CYCL DEF 1.3 PECKG {r.choice([2, 4, 20])}")
            self.emit(f"CYCL DEF 1.4 DWELL {r.choice([0, 0.5])}")
            self.emit(f"CYCL DEF 1.5 F{r.choice([100, 300])}")
            self.emit("L Z+2 R0 FMAX")
            self.emit(r.choice(["CYCL CALL", "L Z+2 R0 FMAX M99", "CYCL CALL M3"]))
            self.known = False
            return
        q = {200: "DRILLING", 203: "UNIVERSAL DRILLING", 205: "UNIVERSAL PECKING"}[kind]
        lines = [f"CYCL DEF {kind} {q} ~", "  Q200=+2 ;SET-UP CLEARANCE ~", f"  Q201={_n(depth)} ;DEPTH ~",
                 f"  Q206=+{r.choice([100, 150])} ;FEED RATE FOR PLNGNG ~",
                 f"  Q202=+{r.choice([2, 3, 5, 20])} ;PLUNGING DEPTH ~"]
        if kind in (200, 203):
            lines.append(f"  Q210=+{r.choice([0, 0.5])} ;DWELL TIME AT TOP ~")
        lines += [f"  Q203={_n(r.choice([0, -1, 2]))} ;SURFACE COORDINATE ~",
                  f"  Q204=+{r.choice([10, 50])} ;2ND SET-UP CLEARANCE ~"]
        if kind in (203, 205):
            lines += [f"  Q212=+{r.choice([0, 0.5])} ;DECREMENT ~", "  Q205=+1 ;MIN. PLUNGING DEPTH ~"]
        if kind == 203:
            lines += [f"  Q213=+{r.choice([0, 2])} ;BREAKS ~", "  Q208=+500 ;RETRACTION FEED RATE ~"]
        if kind == 205:
            lines += ["  Q258=+0.2 ;UPPER ADV STOP DIST ~", "  Q259=+0.2 ;LOWER ADV STOP DIST ~",
                      f"  Q257=+{r.choice([0, 2])} ;DEPTH FOR CHIP BRKNG ~", "  Q256=+0.2 ;DIST FOR CHIP BRKNG ~"]
        lines.append(f"  Q211=+{r.choice([0, 0.2])} ;DWELL TIME AT DEPTH")
        self.emit(*lines)
        if r.random() < 0.3:
            self.pattern_cycle()
            return
        for _ in range(r.randint(1, 3)):
            call = r.random()
            x, y = _n(r.uniform(0, 100)), _n(r.uniform(0, 100))
            if call < 0.3:
                self.emit(f"L X{x} Y{y} R0 FMAX M99")
            elif call < 0.5:
                self.emit(f"L X{x} Y{y} R0 FMAX")
                self.emit("CYCL CALL")
            elif call < 0.75:
                self.emit(f"CYCL CALL POS X{x} Y{y} Z{_n(r.choice([0, 2]))} FMAX")
            else:
                self.emit(*self.pattern_def(x, y))
                self.emit("CYCL CALL PAT FMAX")
        self.known = False

    def pattern_def(self, x: str, y: str) -> list[str]:
        """``PATTERN DEF`` and its items: two POSn points, or a ROW1 / CIRC1 / PITCHCIRC1 / PAT1 / FRAME1 form (TNC
        640 cycle programming manual, "PATTERN DEF"), continued by ``~`` or, as older TNCs save them, the items on
        lines of their own without it."""
        r = self.r
        items = [f"POS1 (X{x} Y{y} Z+0)", f"POS2 (IX+{r.choice([5, 12])} Y{y} Z+0)"]
        form = r.choice(["POS", "POS", "ROW", "CIRC", "PITCHCIRC", "PAT", "FRAME"])
        if form == "ROW":
            items = [f"ROW1 (X{x} Y{y} D+{r.choice([5, 8])} NUM{r.randint(2, 4)} ROT{_n(r.choice([0, 30, -90]))} Z+0)"]
        elif form in ("CIRC", "PITCHCIRC"):
            step = f" STEP+{r.choice([30, 45])}" if form == "PITCHCIRC" else ""
            items = [f"{form}1 (X{x} Y{y} D{r.choice([20, 40])} START{_n(r.choice([0, 45, -30]))}{step} "
                     f"NUM{r.randint(2, 5)} Z+0)"]
        elif form in ("PAT", "FRAME"):
            items = [f"{form}1 (X{x} Y{y} DX+{r.choice([5, 8])} DY+{r.choice([4, 10])} NUMX{r.randint(2, 3)} "
                     f"NUMY{r.randint(1, 3)} ROT{_n(r.choice([0, 15]))} ROTX+0 ROTY+0 Z+0)"]
        if r.random() < 0.5:
            return ["PATTERN DEF", *items]
        return ["PATTERN DEF ~", *[item + " ~" for item in items[:-1]], items[-1]]

    def pattern_cycle(self) -> None:
        """Cycle 220 (a pitch circle, Q365 = 0 straight or 1 on the circle, full or partial, either sense,
        Q247 = 0 or a given step) or 221 (a grid turned by Q224), calling the machining cycle just defined."""
        r = self.r
        common = ["  Q200=+2 ;SET-UP CLEARANCE ~", f"  Q203={_n(r.choice([0, -1, 2]))} ;SURFACE COORDINATE ~",
                  f"  Q204=+{r.choice([10, 50])} ;2ND SET-UP CLEARANCE ~",
                  f"  Q301=+{r.choice([0, 1])} ;MOVE TO CLEARANCE"]
        if r.random() < 0.7:
            start = r.choice([0, 30, -45, 90, 200])
            stop = start + r.choice([360, -360, 180, -90, 270, 45])
            step = r.choice([0, 0, (stop - start) / 4])
            lines = ["CYCL DEF 220 POLAR PATTERN ~", f"  Q216={_n(r.uniform(20, 80))} ;CENTER IN 1ST AXIS ~",
                     f"  Q217={_n(r.uniform(20, 80))} ;CENTER IN 2ND AXIS ~",
                     f"  Q244=+{r.choice([10, 40, 75.5])} ;PITCH CIRCLE DIAMETR ~",
                     f"  Q245={_n(start)} ;STARTING ANGLE ~", f"  Q246={_n(stop)} ;STOPPING ANGLE ~",
                     f"  Q247={_n(step)} ;STEPPING ANGLE ~", f"  Q241=+{r.choice([1, 2, 3, 5])} ;NR OF REPETITIONS ~"]
            common[-1] += " ~"
            common.append(f"  Q365=+{r.choice([0, 1])} ;TYPE OF TRAVERSE")
        else:
            lines = ["CYCL DEF 221 CARTESIAN PATTERN ~", f"  Q225={_n(r.uniform(0, 50))} ;STARTNG PNT 1ST AXIS ~",
                     f"  Q226={_n(r.uniform(0, 50))} ;STARTNG PNT 2ND AXIS ~",
                     f"  Q237=+{r.choice([5, 12.5])} ;SPACING IN 1ST AXIS ~",
                     f"  Q238=+{r.choice([4, 10])} ;SPACING IN 2ND AXIS ~",
                     f"  Q242=+{r.choice([1, 2, 3])} ;NUMBER OF COLUMNS ~",
                     f"  Q243=+{r.choice([1, 2, 3])} ;NUMBER OF LINES ~",
                     f"  Q224={_n(r.choice([0, 30, -15]))} ;ANGLE OF ROTATION ~"]
        self.emit(*lines, *common)
        self.known = False

    def reset_transforms(self) -> None:
        """Cycles 10 ROTATION, 8 MIRROR IMAGE and 11 SCALING reset, each its own block."""
        for block in ("CYCL DEF 10.0 ROTATION", "CYCL DEF 10.1 ROT+0", "CYCL DEF 8.0 MIRROR IMAGE", "CYCL DEF 8.1",
                      "CYCL DEF 11.0 SCALING", "CYCL DEF 11.1 SCL1"):
            self.emit(block)

    def tilted(self) -> None:
        """On the five-axis seeds (:func:`five_axis`), the B/C table :data:`BC_TABLE`: a tilted working plane
        (iTNC 530 user's manual, "The PLANE function": ``PLANE SPATIAL SPA SPB SPC TURN MB MAX FMAX``, lines in the
        tilted plane, ``PLANE RESET TURN MB MAX FMAX``) or tool centre point control (TNC 640 user's manual, M128
        "Retaining the position of the tool tip when positioning tilting axes": lines with B and C under
        ``M128``, ``M129`` after), after the transformations 8/10/11 are reset. Elsewhere a plain move."""
        r = self.r
        if not self.five:
            self.move()
            return
        self.reset_transforms()
        self.emit("L Z+100 R0 FMAX")
        if r.random() < 0.5:
            self.emit(self.plane_definition())
            if r.random() < 0.4:  # NX TNC posts chain an incremental turn about the active plane's own axis
                axis, angle = r.choice([("SPB", r.choice([-20, 10, 15])), ("SPC", r.choice([-45, 30, 90])),
                                        ("SPA", 10)])
                self.emit(f"PLANE RELATIV {axis}{_n(angle)} TURN MB MAX FMAX")
            self.emit(f"L X{_n(r.uniform(0, 60))} Y{_n(r.uniform(0, 60))} Z+20 R0 FMAX")
            for _ in range(r.randint(1, 3)):
                self.emit(f"L X{_n(r.uniform(0, 60))} Y{_n(r.uniform(0, 60))} Z{_n(r.choice([0, 5]))}{self.feed()}")
            self.emit("L Z+50 R0 FMAX")
            self.emit("PLANE RESET TURN MB MAX FMAX")
        else:
            self.emit(f"L X{_n(r.uniform(0, 60))} Y{_n(r.uniform(0, 60))} Z+50 B+0 C+0 R0 FMAX")
            tcpm = r.random() < 0.4  # FUNCTION TCPM and LN X Y Z TX TY TZ, as Fusion's heidenhain.cps writes them
            self.emit("FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS" if tcpm else "L Z+20 R0 FMAX M128")
            for _ in range(r.randint(1, 4)):
                xyz = f"X{_n(r.uniform(0, 60))} Y{_n(r.uniform(0, 60))} Z{_n(r.choice([0, 5, 20]))}"
                if tcpm:
                    b, c = math.radians(r.choice([0, 15, 30, 45])), math.radians(r.choice([0, 45, -90, 180]))
                    t = (math.sin(b) * math.cos(c), math.sin(b) * math.sin(c), math.cos(b))
                    self.emit(f"LN {xyz} TX{_n(round(t[0], 7))} TY{_n(round(t[1], 7))} TZ{_n(round(t[2], 7))} R0"
                              f"{self.feed() or ' F' + str(r.choice([300, 1000]))}")
                else:
                    self.emit(f"L {xyz} B{_n(r.choice([-30, 0, 20, 45]))} C{_n(r.choice([0, 45, -90, 180]))}"
                              f"{self.feed()}")
            self.emit("L Z+50 R0 FMAX" if tcpm else "L Z+50 R0 FMAX M129")
            if tcpm:
                self.emit("FUNCTION RESET TCPM")
            self.emit("L B+0 C+0 R0 FMAX")
        self.known = False
        self.polar_ok = False
        self.pole_kept = self.cc is not None

    def plane_definition(self) -> str:
        """A ``PLANE`` block tilting the working plane on the B/C table, in the forms posts and shops write (TNC 640
        user's manual, "Tilting the working plane", PLANE SPATIAL, PROJECTED, EULER, VECTOR, POINTS, AXIAL; the
        positioning ``TURN MB MAX FMAX`` or ``MOVE DIST.. F..``; ``TABLE ROT``/``COORD ROT`` on a plane turned about
        C alone): half of the time SPATIAL as before, the rest the other forms (tool axes B within -90..90)."""
        r = self.r
        move = "TURN MB MAX FMAX" if r.random() < 0.8 else f"MOVE DIST+{r.choice([20, 50])} F{r.choice([2000, 5000])}"
        form = r.choice(["spatial"] * 5 + ["table", "projected", "euler", "vector", "points", "axial"])
        if form == "spatial":
            return (f"PLANE SPATIAL SPA+0 SPB{_n(r.choice([-30, 15, 45, 90]))} SPC{_n(r.choice([0, 30, -90]))} "
                    f"{move}")
        if form == "table":
            rot = r.choice(["TABLE", "COORD"])
            return f"PLANE SPATIAL SPA+0 SPB+0 SPC{_n(r.choice([30, -45, 90]))} {move} {rot} ROT"
        if form == "projected":
            return (f"PLANE PROJECTED PROPR{_n(r.choice([-45, -20, 0, 30]))} PROMIN{_n(r.choice([0, 15, 35, -40]))} "
                    f"ROT{_n(r.choice([0, 15, -90]))} {move}")
        if form == "euler":
            return (f"PLANE EULER EULPR{_n(r.choice([0, 30, -60, 90]))} EULNU{_n(r.choice([15, 30, 45, 60]))} "
                    f"EULROT{_n(r.choice([0, -30, 90]))} {move}")
        if form == "axial":
            b = r.choice([-40, 20, 45])
            if r.random() < 0.3:
                return f"PLANE AXIAL B{_n(b)} {move}"
            return f"PLANE AXIAL B{_n(b)} C{_n(r.choice([0, 90, 170, -30]))} {move}"
        b, c = math.radians(r.choice([20, 30, 45, -35])), math.radians(r.choice([0, 45, -90, 120]))
        x = (math.cos(b) * math.cos(c), math.cos(b) * math.sin(c), -math.sin(b))  # the tilted X, square to N
        y = (-math.sin(c), math.cos(c), 0.0)
        if form == "vector":
            n = (math.sin(b) * math.cos(c), math.sin(b) * math.sin(c), math.cos(b))
            return (f"PLANE VECTOR BX{_n(round(x[0], 4))} BY{_n(round(x[1], 4))} BZ{_n(round(x[2], 4))} "
                    f"NX{_n(round(n[0], 4))} NY{_n(round(n[1], 4))} NZ{_n(round(n[2], 4))} {move}")
        p1 = [r.choice([0, 10, -5]), r.choice([0, 20]), r.choice([0, -3])]
        p2 = [p1[k] + 20 * x[k] for k in range(3)]
        p3 = [p1[k] + 15 * y[k] + r.choice([0, 5]) * x[k] for k in range(3)]
        return "PLANE POINTS " + " ".join(f"P{i + 1}{a}{_n(round(p[k], 4))}" for i, p in enumerate((p1, p2, p3))
                                          for k, a in enumerate("XYZ")) + f" {move}"

    def pocket(self) -> None:
        """Cycle 251 RECTANGULAR POCKET or 252 CIRCULAR POCKET (TNC 640 cycle programming manual, "POCKET MILLING
        (Cycle 251)", "CIRCULAR POCKET (Cycle 252)": the pocket centred on the tool position, Q367 = 0), roughing
        and finishing (Q215 = 0), plunging vertically (Q366 = 0), after the transformations 8/10/11 are reset (the
        reference models the pockets without them), called by ``CYCL CALL``, ``M99`` or ``CYCL CALL POS``."""
        r = self.r
        self.reset_transforms()
        self.emit(f"L X{_n(r.uniform(20, 80))} Y{_n(r.uniform(20, 80))} Z+20 R0 FMAX")
        kind = r.choice([251, 252])
        if kind == 251:
            lines = ["CYCL DEF 251 RECTANGULAR POCKET ~", "  Q215=+0 ;MACHINING OPERATION ~",
                     f"  Q218=+{r.choice([30, 40, 55])} ;FIRST SIDE LENGTH ~",
                     f"  Q219=+{r.choice([20, 25, 30])} ;2ND SIDE LENGTH ~",
                     f"  Q220=+{r.choice([4, 6])} ;CORNER RADIUS ~",
                     f"  Q368=+{r.choice([0, 0.2])} ;ALLOWANCE FOR SIDE ~",
                     f"  Q224=+{r.choice([0, 30, 90])} ;ANGLE OF ROTATION ~", "  Q367=+0 ;POCKET POSITION ~"]
        else:
            lines = ["CYCL DEF 252 CIRCULAR POCKET ~", "  Q215=+0 ;MACHINING OPERATION ~",
                     f"  Q223=+{r.choice([20, 32, 50])} ;CIRCLE DIAMETER ~",
                     f"  Q368=+{r.choice([0, 0.2])} ;ALLOWANCE FOR SIDE ~"]
        lines += [f"  Q207=+{r.choice([300, 500])} ;FEED RATE FOR MILLING ~",
                  f"  Q351={r.choice(['+1', '-1'])} ;CLIMB OR UP-CUT ~", f"  Q201=-{r.choice([4, 6, 10])} ;DEPTH ~",
                  f"  Q202=+{r.choice([2, 3, 5])} ;PLUNGING DEPTH ~",
                  f"  Q369=+{r.choice([0, 0.1])} ;ALLOWANCE FOR FLOOR ~", "  Q206=+150 ;FEED RATE FOR PLNGNG ~",
                  f"  Q338=+{r.choice([0, 2])} ;INFEED FOR FINISHING ~", "  Q200=+2 ;SET-UP CLEARANCE ~",
                  f"  Q203=+{r.choice([0, 1])} ;SURFACE COORDINATE ~", "  Q204=+50 ;2ND SET-UP CLEARANCE ~",
                  f"  Q370=+{r.choice([1, 0.8])} ;TOOL PATH OVERLAP ~", "  Q366=+0 ;PLUNGE ~",
                  "  Q385=+500 ;FINISHING FEED RATE"]
        self.emit(*lines)
        x, y = _n(r.uniform(20, 80)), _n(r.uniform(20, 80))
        self.emit(r.choice(["CYCL CALL", f"L X{x} Y{y} R0 FMAX M99", f"CYCL CALL POS X{x} Y{y} Z+0 FMAX"]))
        self.known = False
        self.polar_ok = False
        self.pole_kept = self.cc is not None

    # -- contours ------------------------------------------------------------------------------
    def step(self, length: float, turn: float) -> tuple[float, float]:
        """The point ``length`` away along the heading turned by ``turn`` degrees."""
        h = (self.heading if self.heading is not None else self.r.uniform(0, 360)) + turn
        return (self.pos[0] + length * math.cos(math.radians(h)), self.pos[1] + length * math.sin(math.radians(h)))

    def turn(self) -> float:
        return self.r.choice([-1, 1]) * self.r.uniform(25, 155)

    def line(self, end: tuple[float, float]) -> None:
        inc = self.r.random() < 0.4
        w = [self.coord(a, end[i] - self.pos[i] if inc else end[i], incremental=inc) for i, a in ((0, "X"), (1, "Y"))]
        self.emit("L " + " ".join(w) + self.feed())
        end = self.typed(end, inc)
        self.heading = math.degrees(math.atan2(end[1] - self.pos[1], end[0] - self.pos[0]))
        self.pos[:2] = end
        self.polar_ok = False

    def typed(self, end: tuple[float, float], inc: bool) -> tuple[float, float]:
        """The end the program states: its 4 decimals, absolute or from the current point (and whether the
        current point is then known exactly: after LP/CP it is a computed point)."""
        if inc:
            return tuple(self.pos[i] + round(end[i] - self.pos[i], 4) for i in (0, 1))
        self.exact = True
        return round(end[0], 4), round(end[1], 4)

    def set_pole(self, centre: tuple[float, float]) -> None:
        inc = self.r.random() < 0.5 or not self.exact
        if inc:
            self.emit(f"CC IX{_n(centre[0] - self.pos[0])} IY{_n(centre[1] - self.pos[1])}")
        else:
            self.emit(f"CC X{_n(centre[0])} Y{_n(centre[1])}")
        self.pole_kept = False
        self.cc = tuple(self.pos[i] + round(centre[i] - self.pos[i], 4) for i in (0, 1)) if inc else \
            (round(centre[0], 4), round(centre[1], 4))
        self.polar_ok = False

    def arc_c(self, *, helix: bool = True) -> None:
        """A pole, then ``C`` to a point on its circle (or ``CP IPA``, a helix with ``IZ``). The pole and the end
        are the start plus vectors of length 25 x k with whole components (7, 24), (15, 20), ..., so that the
        written end lies exactly on the circle."""
        r = self.r
        k = r.choice([0.4, 0.8, 1.2])
        ccw = r.random() < 0.5
        v1 = r.choice([v for v in _RADII if self.smooth(-v[1], v[0]) if ccw] or
                      [v for v in _RADII if self.smooth(v[1], -v[0])])
        v2 = r.choice([v for v in _RADII if abs(v[0] * v1[0] + v[1] * v1[1]) < 480])  # 40 to 140 degrees apart
        self.set_pole((self.pos[0] - k * v1[0], self.pos[1] - k * v1[1]))
        cc = self.cc
        a0, a1 = math.atan2(v1[1], v1[0]), math.atan2(v2[1], v2[0])
        sweep = math.degrees(a1 - a0) % 360.0
        sweep = sweep if ccw else sweep - 360.0
        dr = "DR+" if ccw else "DR-"
        if r.random() < 0.4:
            sweep = round(sweep, 4)
            iz = f" IZ{_n(r.choice([-1, -2]))}" if helix and r.random() < 0.3 else ""
            if r.random() < 0.3 and not iz:  # the end angle absolute: PA (the arc runs to it in the sense DR)
                pa = round(math.degrees(a0) + sweep, 4)
                self.emit(f"CP PA{_n(pa)} {dr}{self.feed()}")
                sweep = pa - math.degrees(a0)
            else:
                self.emit(f"CP IPA{_n(sweep)}{iz} {dr}{self.feed()}")
            if iz:
                self.pos[2] += float(iz.strip()[2:])
            rad = 25 * k
            end = (cc[0] + rad * math.cos(a0 + math.radians(sweep)), cc[1] + rad * math.sin(a0 + math.radians(sweep)))
            self.polar_ok, self.exact = True, False
        else:
            end = (cc[0] + k * v2[0], cc[1] + k * v2[1])
            if r.random() < 0.3:  # an end at any angle, rounded to 4 places: off the circle by up to 0.00007
                a1 += r.uniform(-0.2, 0.2)
                end = (cc[0] + 25 * k * math.cos(a1), cc[1] + 25 * k * math.sin(a1))
            inc = r.random() < 0.3 or not self.exact
            w = " ".join(self.coord(a, end[i] - self.pos[i] if inc else end[i], incremental=inc, q_ok=False)
                         for i, a in ((0, "X"), (1, "Y")))
            end = self.typed(end, inc)
            self.emit(f"C {w} {dr}{self.feed()}")
            self.polar_ok = False
        ea = math.atan2(end[1] - cc[1], end[0] - cc[0])
        self.heading = math.degrees(ea) + (90 if ccw else -90)
        self.pos[:2] = end

    def smooth(self, dx: float, dy: float) -> bool:
        """Whether the next element may leave in the direction (dx, dy): a corner of at most 110 degrees (a
        sharper one makes the compensated tool gouge, which the reader rightly refuses); a small one too, which
        the TNC rounds by its transition arc or cuts at the offsets' intersection as any other."""
        if self.heading is None:
            return True
        h = math.radians(self.heading)
        c = (dx * math.cos(h) + dy * math.sin(h)) / math.hypot(dx, dy)
        # a RND/CHF waiting for this element needs a corner to round (25 degrees: the radius fits)
        return math.cos(math.radians(110)) < c < (math.cos(math.radians(25)) if self.rounding else 2.0)

    def arc_cr(self) -> None:
        r = self.r
        for _ in range(30):
            end = self.step(r.uniform(8, 30), self.turn())
            ex, ey = round(end[0], 4), round(end[1], 4)
            half = math.hypot(ex - self.pos[0], ey - self.pos[1]) / 2
            rr = round(half * r.uniform(1.05, 3), 4)
            big, ccw = r.random() < 0.3, r.random() < 0.5
            # the centre: on the chord's bisector, left of start->end for a small counter-clockwise arc
            mx, my = (self.pos[0] + ex) / 2, (self.pos[1] + ey) / 2
            d = math.sqrt(max(rr * rr - half * half, 0.0))
            ux, uy = (ex - self.pos[0]) / (2 * half), (ey - self.pos[1]) / (2 * half)
            s = 1 if ccw != big else -1
            cx, cy = mx - s * uy * d, my + s * ux * d
            vx, vy = self.pos[0] - cx, self.pos[1] - cy
            if self.smooth(-vy, vx) if ccw else self.smooth(vy, -vx):
                break
        self.emit(f"CR X{_n(ex)} Y{_n(ey)} R{'-' if big else '+'}{_n(rr)[1:]} {'DR+' if ccw else 'DR-'}" + self.feed())
        ea = math.atan2(ey - cy, ex - cx)
        self.heading = math.degrees(ea) + (90 if ccw else -90)
        self.pos[:2] = (ex, ey)
        self.polar_ok, self.exact = False, True

    def arc_ct(self) -> None:
        end = self.step(self.r.uniform(10, 30), self.r.choice([-1, 1]) * self.r.uniform(20, 70))
        end = (round(end[0], 4), round(end[1], 4))
        self.emit(f"CT X{_n(end[0])} Y{_n(end[1])}" + self.feed())
        # tangent arc: the end tangent is the start tangent mirrored about the chord
        chord = math.degrees(math.atan2(end[1] - self.pos[1], end[0] - self.pos[0]))
        self.heading = 2 * chord - self.heading
        self.pos[:2] = end
        self.polar_ok, self.exact = False, True

    def polar_line(self) -> None:
        r = self.r
        if r.random() < 0.15:  # a CC without coordinates: the pole at the last programmed position
            self.emit("CC")
            self.cc, self.polar_ok = (self.pos[0], self.pos[1]), False
        cc = self.cc
        pr = math.hypot(self.pos[0] - cc[0], self.pos[1] - cc[1])
        pa = math.degrees(math.atan2(self.pos[1] - cc[1], self.pos[0] - cc[0]))
        for _ in range(30):
            npr, npa = max(pr + r.uniform(-5, 10), 8.0), pa + r.choice([-1, 1]) * r.uniform(25, 120)
            if self.smooth(cc[0] + npr * math.cos(math.radians(npa)) - self.pos[0],
                           cc[1] + npr * math.sin(math.radians(npa)) - self.pos[1]):
                break
        if self.polar_ok and r.random() < 0.5:
            text = f"LP IPR{_n(round(npr - pr, 4))} IPA{_n(round(npa - pa, 4))}"
            npr, npa = pr + round(npr - pr, 4), pa + round(npa - pa, 4)
        else:
            npr, npa = round(npr, 4), round(npa, 4)
            text = f"LP PR{_n(npr)} PA{_n(npa)}"
        end = (cc[0] + npr * math.cos(math.radians(npa)), cc[1] + npr * math.sin(math.radians(npa)))
        self.emit(text + self.feed())
        self.pole_kept = False
        self.heading = math.degrees(math.atan2(end[1] - self.pos[1], end[0] - self.pos[0]))
        self.pos[:2] = end
        self.polar_ok, self.exact = True, False

    def contour(self, depth: float | None) -> None:
        """An RL/RR (or R0) contour: entered by L or APPR (LT, LN, CT, LCT), elements, left by L R0 or DEP (LT,
        LN, CT, LCT). ``depth`` None: the contour of a repeated section (``LBL``: ``L IZ`` down each time, then
        back to its first point, repeated by ``CALL LBL n REP``)."""
        r = self.r
        comp = r.choice(["RL", "RR", "R0"])
        start = (round(r.uniform(10, 90), 4), round(r.uniform(10, 90), 4))
        pre = (round(start[0] - 15, 4), round(start[1] - 15, 4))
        self.emit(f"L X{_n(pre[0])} Y{_n(pre[1])} R0 FMAX")
        if depth is None:
            self.emit(f"L Z+{r.choice([1, 2])} R0 FMAX")
            n = self.lbl
            self.lbl += 1
            self.emit(f"LBL {n}")
            self.emit(f"L IZ-{r.choice([1, 1.5])} R0{self.feed()}")
            self.cc, self.pole_kept = None, False  # a pole set in the section is another at its next run's start
        else:
            self.emit(f"L Z{_n(depth)} R0{self.feed()}")
        self.pos, self.known, self.heading = [pre[0], pre[1], depth or 0.0], True, None
        self.exact = True
        self.comp = comp
        self.enter(comp, start)
        self.elements()
        self.leave(comp)
        if depth is None:
            self.emit(f"L X{_n(pre[0])} Y{_n(pre[1])} R0 FMAX")
            self.emit(f"CALL LBL {n} REP{r.choice([1, 2, 3])}")
            self.known = False
        self.emit("L Z+20 R0 FMAX")
        self.pos[2] = 20.0
        self.heading = None

    def enter(self, comp: str, start: tuple[float, float]) -> None:
        r = self.r
        self.appr = comp != "R0" and r.random() < 0.4
        xy = f"X{_n(start[0])} Y{_n(start[1])}"
        if self.appr:
            form = r.choice(["LT", "LN", "CT", "LCT"])
            extra = {"LT": f" LEN{r.choice([5, 8])}", "LN": f" LEN{r.choice([5, 8])}",
                     "CT": f" CCA{r.choice([45, 90, 180])} R{r.choice(['+', '-'])}{r.choice([5, 8])}",
                     "LCT": f" R{r.choice([3, 5])}"}[form]
            self.emit(f"APPR {form} {xy}{extra} {comp}{self.feed()}")
            self.heading = None
        else:
            self.emit(f"L {xy} {comp}{self.feed()}")
            self.heading = 45.0
        self.pos[:2] = list(start)

    def elements(self) -> None:
        r = self.r
        corner = None
        for n in range(r.randint(2, 7)):
            k = r.random()
            if n == 0 and self.appr:
                self.line(self.step(r.uniform(10, 30), r.uniform(0, 360)))
            elif self.pole_kept and corner != "CHF" and k < 0.7:  # LP about a pole set before a transformation
                self.polar_line()
            elif corner == "CHF" or k < 0.35:  # a chamfer joins two straight lines (TNC 640 manual, "Chamfer CHF")
                self.line(self.step(r.uniform(8, 30), self.turn()))
            elif k < 0.55:
                # RND between elements in the working plane; a helix under RL/RR cut short by an inside corner
                # leaves the rest of its depth to the next element, which the reference does not follow
                self.arc_c(helix=corner is None and self.comp == "R0")
            elif k < 0.7:
                self.arc_cr()
            elif k < 0.8 and self.heading is not None and corner is None:
                self.arc_ct()
            elif self.cc is not None and k < 0.9:
                self.polar_line()
            elif k < 0.95 and self.heading is not None and corner is None:  # a corner of 0.2 to 3 degrees
                self.line(self.step(r.uniform(8, 30), r.choice([-1, 1]) * r.uniform(0.2, 3.0)))
            else:
                self.line(self.step(r.uniform(8, 30), self.turn()))
            corner, self.rounding = None, False
            if r.random() < 0.25 and " IZ" not in self.blocks[-1][0]:  # RND in the working plane only
                corner = "CHF" if self.blocks[-1][0].startswith("L ") and r.random() < 0.4 else "RND"
                self.rounding = True
                self.emit(f"{'CHF ' if corner == 'CHF' else 'RND R'}{r.choice([1, 2, 3])}")
        if corner is not None:
            self.line(self.step(r.uniform(8, 30), self.turn()))
            self.rounding = False

    def leave(self, comp: str) -> None:
        r = self.r
        if comp != "R0" and (self.appr or r.random() < 0.3):
            form = r.choice(["LT", "LN", "CT", "LCT"])
            if form == "LCT":
                end = self.step(30, r.choice([-60, 60]))
                extra = f" X{_n(end[0])} Y{_n(end[1])} R{r.choice([3, 5])}"
            else:
                extra = {"LT": f" LEN{r.choice([5, 10])}", "LN": f" LEN{r.choice([5, 10])}",
                         "CT": f" CCA{r.choice([45, 90, 180])} R{r.choice(['+', '-'])}{r.choice([5, 8])}"}[form]
            self.emit(f"DEP {form}{extra} R0 F{r.choice([500, 1000])}")
            self.known = False

    def transform(self) -> None:
        """Cycles 10 ROTATION, 8 MIRROR IMAGE, 11 SCALING set, or all reset."""
        r = self.r
        k = r.random()
        if k < 0.35:
            self.emit("CYCL DEF 10.0 ROTATION")
            self.emit(f"CYCL DEF 10.1 ROT{_n(r.choice([0, 30, -45, 90, 12.5]))}")
        elif k < 0.6:
            self.emit("CYCL DEF 8.0 MIRROR IMAGE")
            self.emit(f"CYCL DEF 8.1 {r.choice(['X', 'Y', 'X Y', ''])}".rstrip())
        elif k < 0.8:
            self.emit("CYCL DEF 11.0 SCALING")
            self.emit(f"CYCL DEF 11.1 SCL{r.choice(['0.5', '1', '2'])}")
        else:
            self.emit("CYCL DEF 10.0 ROTATION")
            self.emit("CYCL DEF 10.1 ROT+0")
            self.emit("CYCL DEF 8.0 MIRROR IMAGE")
            self.emit("CYCL DEF 8.1")
            self.emit("CYCL DEF 11.0 SCALING")
            self.emit("CYCL DEF 11.1 SCL1")
        self.known = False
        self.polar_ok = False  # the pole keeps its program coordinates under the new transformation
        self.pole_kept = self.cc is not None

    # -- labels --------------------------------------------------------------------------------
    def repeated(self) -> None:
        """``LBL n`` .. ``CALL LBL n REP k`` of incremental moves, sometimes a nested repeat."""
        r = self.r
        n = self.lbl
        self.lbl += 1
        self.emit(f"LBL {n}")
        self.emit(f"L IX{_n(r.choice([2, 5, -3]))} IY{_n(r.choice([0, 4]))} R0{self.feed()}")
        if r.random() < 0.4:
            m = self.lbl
            self.lbl += 1
            self.emit(f"LBL {m}")
            self.emit(f"L IZ{_n(r.choice([-1, 1]))} R0 FMAX")
            self.emit(f"CALL LBL {m} REP{r.choice([1, 2])}")
        if r.random() < 0.5 and self.q:
            k = r.choice(sorted(self.q))
            self.emit(f"L IX+Q{k} R0{self.feed()}" if abs(self.q[k]) < 50 else "L IY+1 R0")
        self.emit(f"CALL LBL {n} REP{r.choice([1, 2, 3])}")
        self.known = False

    def counted_loop(self) -> None:
        """A loop by a counter and a conditional jump (``FN 12: IF +Q60 LT +3 GOTO LBL n``, or FN 9/11)."""
        r = self.r
        n, k, times = self.lbl, r.choice([60, 61]), r.choice([2, 3])
        self.lbl += 1
        self.emit(f"FN 0: Q{k} = +0")
        self.emit(f"LBL {n}")
        self.emit(f"L IX{_n(r.choice([2, -3]))} IY{_n(r.choice([0, 1.5]))} R0{self.feed()}")
        self.emit(f"FN 1: Q{k} = +Q{k} + +1")
        jump = r.choice([f"FN 12: IF +Q{k} LT +{times} GOTO LBL {n}", f"FN 11: IF +{times} GT +Q{k} GOTO LBL {n}",
                         f"FN 10: IF +Q{k} NE +{times} GOTO LBL {n}"])
        self.emit(jump)
        self.known = False

    def subprogram_call(self) -> None:
        n = 90 + len(self.subs)
        self.subs.append([[f"LBL {n}"], [f"L IX{_n(self.r.choice([3, -4]))} R0 F300"],
                          [f"L IY{_n(self.r.choice([2, 6]))} R0"], ["LBL 0"]])
        self.emit(f"CALL LBL {n}")
        self.known = False


class _Extras:
    """The functions session 40 added (tncgen40), drawn from a stream of their own (``f"{seed}:gen40"``) between
    the sections of :class:`_Gen`, which resumes as it was (its state saved and the tool put back where it stood),
    so that the programs of the seeds before keep their sections: the milling cycles 208, 240, 253, 256, 257 and
    262-265/267, the SL cycles (14 or ``CONTOUR DEF``, 20, 22 / 23 / 24 / 25 on a contour subprogram), the old
    cycles 1/2/17 on the patterns 220/221, ``FN 9`` jumps, ``FN 18 SYSREAD`` and ``QS`` string parameters."""

    def __init__(self, g: _Gen, seed: int):
        self.g = g
        self.r = random.Random(f"{seed}:gen40")

    def section(self) -> None:
        g, r = self.g, self.r
        saved = (list(g.pos), g.known, g.exact, g.heading, g.polar_ok, g.pole_kept, g.feed_set)
        k = r.random()
        if k < 0.55:  # a milling tool of radius 2 mm (0.08 in) of its own, then the program's again
            g.emit(f"TOOL DEF 9 L+0 R+{'0.08' if g.unit == 'INCH' else '2'}")
            g.emit(f"TOOL CALL 9 Z S{r.choice([3000, 6000])} F{r.choice([400, 800])}")
            if k < 0.3:
                self.milling()
            else:
                self.sl_cycles()
                self.sl_parameters()
            g.emit("L Z+50 R0 FMAX")
            g.emit(g.last_tool_call)
        elif k < 0.7:
            self.old_pattern()
        elif k < 0.8:
            self.jump()
        elif k < 0.9:
            self.sysread()
        else:
            self.strings()
        g.pos, g.known, g.exact, g.heading, g.polar_ok, g.pole_kept, g.feed_set = saved
        if g.known:  # back where the main sections left the tool, in the coordinates they wrote
            g.emit("L Z+50 R0 FMAX")
            g.emit(f"L X{_n(g.pos[0])} Y{_n(g.pos[1])} R0 FMAX")
            g.emit(f"L Z{_n(g.pos[2])} R0 FMAX")

    def call(self) -> str:
        x, y = _n(self.r.uniform(20, 80)), _n(self.r.uniform(20, 80))
        return self.r.choice(["CYCL CALL", f"L X{x} Y{y} R0 FMAX M99", f"CYCL CALL POS X{x} Y{y} Z+0 FMAX"])

    def milling(self) -> None:
        """A milling cycle at the tool's position (TNC 640 cycle programming manual, "SLOT MILLING (Cycle 253)",
        "RECTANGULAR STUD (Cycle 256)", "CIRCULAR STUD (Cycle 257)", "BORE MILLING (Cycle 208)", "CENTERING (Cycle
        240)", "THREAD MILLING (Cycle 262)" .. "OUTSIDE THREAD MILLING (Cycle 267)"), sizes well above the tool's
        diameter (at most 6 units), after the transformations are reset, as :meth:`_Gen.pocket`."""
        g, r = self.g, self.r
        g.reset_transforms()
        g.emit(f"L X{_n(r.uniform(20, 80))} Y{_n(r.uniform(20, 80))} Z+20 R0 FMAX")
        kind = r.choice([253, 256, 257, 208, 240, 262, 263, 264, 265, 267])
        depth, top = f"Q201=-{r.choice([3, 5, 8])}", f"Q200=+2 Q203=+{r.choice([0, 1])} Q204=+{r.choice([20, 50])}"
        mill = f"Q207=+{r.choice([300, 500])} Q351={r.choice(['+1', '-1'])}"
        if kind == 253:
            q = (f"CYCL DEF 253 SLOT MILLING Q215=+{r.choice([0, 1, 2])} Q218=+{r.choice([30, 40])} "
                 f"Q219=+{r.choice([12, 16])} Q368=+{r.choice([0, 0.3])} Q374=+{r.choice([0, 30, 90])} Q367=+0 "
                 f"{mill} {depth} Q202=+{r.choice([2, 5])} Q369=+0 Q206=+150 Q338=+0 {top} Q366=+{r.choice([0, 1])} "
                 "Q385=+400")
        elif kind == 256:
            q = (f"CYCL DEF 256 RECTANGULAR STUD Q218=+20 Q424=+{r.choice([26, 30])} Q219=+{r.choice([10, 16])} "
                 f"Q425=+{r.choice([16, 22])} Q220=+{r.choice([0, 2])} Q368=+0 Q224=+0 Q367=+0 "
                 f"{mill} {depth} Q202=+{r.choice([2, 5])} Q206=+150 {top} Q370=+1 Q215=+0 Q369=+0 Q338=+0 Q385=+400")
        elif kind == 257:
            q = (f"CYCL DEF 257 CIRCULAR STUD Q223=+{r.choice([20, 24])} Q222=+{r.choice([30, 36])} "
                 f"Q368=+0 Q215=+{r.choice([0, 1])} {mill} {depth} Q202=+{r.choice([2, 5])} Q206=+150 {top} Q370=+1")
        elif kind == 208:
            q = (f"CYCL DEF 208 BORE MILLING {top} {depth} Q206=+150 Q334=+{r.choice([0.5, 2])} "
                 f"Q335=+{r.choice([16, 20])} Q342=+0 Q351={r.choice(['+1', '-1'])}")
        elif kind == 240:
            q = f"CYCL DEF 240 CENTERING {top} Q343=+0 Q201=-{r.choice([1, 2])} Q206=+100 Q211=+{r.choice([0, 0.2])}"
        else:
            thread = f"Q335=+{r.choice([16, 20])} Q239={r.choice(['+1.5', '-1.5', '+2'])} {depth} Q253=+750"
            q = {262: f"CYCL DEF 262 THREAD MILLING {thread} Q355=+{r.choice([0, 1])} {mill} {top}",
                 263: f"CYCL DEF 263 THREAD MLLNG/CNTSNKG {thread} Q356=-2 {mill} Q357=+0 Q358=+0 Q359=+0 {top} "
                      "Q254=+200",
                 264: f"CYCL DEF 264 BORE/THREAD MLLNG {thread} Q356=-{r.choice([8, 10])} {mill} Q202=+5 Q258=+0.5 "
                      "Q257=+0 Q256=+0 Q358=+0 Q359=+0 Q206=+100 " + top,
                 265: f"CYCL DEF 265 HEL. BORE/THRD MLLNG {thread} Q358=+0 Q359=+0 Q360=+{r.choice([0, 1])} {top} "
                      "Q254=+150 Q207=+300",
                 267: f"CYCL DEF 267 OUTSIDE THREAD MLLNG {thread} Q355=+0 {mill} Q358=+0 Q359=+0 {top} Q254=+0"
                 }[kind]
        g.emit(q)
        g.emit(self.call())
        g.known = False

    def sl_cycles(self) -> None:
        """An SL pocket (TNC 640 cycle programming manual, "SL cycles"): ``CYCL DEF 14.0 CONTOUR`` / ``14.1 CONTOUR
        LABEL n`` or ``CONTOUR DEF P1 = LBL n``, ``CYCL DEF 20 CONTOUR DATA``, then 22 ROUGH-OUT (also followed by 23
        FLOOR FINISHING or 24 SIDE FINISHING) or 25 CONTOUR TRAIN, each called by ``CYCL CALL``; the contour a
        subprogram after ``M30``: a rectangle entered with RL or RR (the pocket; no triangle: the reader leaves its
        innermost ring out when the ring is shorter than its start leg, seed 1102224, left to the lead)."""
        g, r = self.g, self.r
        g.reset_transforms()
        n = g.lbl
        g.lbl += 1
        x0, y0 = r.uniform(0, 40), r.uniform(0, 40)
        # half sides off the rings' grid (R + Q3 + k Q2 R): a ring at exactly half the width is a line of no area,
        # which the reader runs or not by the rounding of its offsets (seeds 1102037, 1102216: left to the lead)
        w, h = r.choice([25, 30, 40]) + 0.7, r.choice([20, 30, 35]) + 0.7
        corners = [(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)]
        if r.random() < 0.5:
            corners.reverse()
        comp = r.choice(["RL", "RR"])
        sub = [[f"LBL {n}"], [f"L X{_n(corners[0][0])} Y{_n(corners[0][1])} {comp}"]]
        sub += [[f"L X{_n(x)} Y{_n(y)}"] for x, y in corners[1:]]
        sub += [[f"L X{_n(corners[0][0])} Y{_n(corners[0][1])}"], ["LBL 0"]]
        g.subs.append(sub)
        g.emit("L Z+50 R0 FMAX")
        if r.random() < 0.5:
            g.emit("CYCL DEF 14.0 CONTOUR")
            g.emit(f"CYCL DEF 14.1 CONTOUR LABEL {n}")
        else:
            g.emit(f"CONTOUR DEF P1 = LBL {n}")
        depth, surface = -r.choice([4, 5, 8]), r.choice([0, 1])
        if r.random() < 0.3:
            g.emit("CYCL DEF 25 CONTOUR TRAIN ~", f"  Q1={_n(depth)} ;MILLING DEPTH ~",
                   f"  Q3=+{r.choice([0, 0.5])} ;ALLOWANCE FOR SIDE ~", f"  Q5=+{surface} ;SURFACE COORDINATE ~",
                   "  Q7=+50 ;CLEARANCE HEIGHT ~", f"  Q10=+{r.choice([2, 5])} ;PLUNGING DEPTH ~",
                   "  Q11=+100 ;FEED RATE FOR PLUNGING ~", "  Q12=+350 ;FEED RATE FOR MILLING ~",
                   f"  Q15={r.choice(['+1', '-1'])} ;CLIMB OR UP-CUT")
            g.emit(f"L X{_n(x0 - 10)} Y{_n(y0 - 10)} R0 FMAX")
            g.emit("CYCL CALL")
            g.known = False
            return
        g.emit("CYCL DEF 20 CONTOUR DATA ~", f"  Q1={_n(depth)} ;MILLING DEPTH ~", "  Q2=+1 ;TOOL PATH OVERLAP ~",
               f"  Q3=+{r.choice([0, 0.5])} ;ALLOWANCE FOR SIDE ~",
               f"  Q4=+{r.choice([0, 0.5])} ;ALLOWANCE FOR FLOOR ~", f"  Q5=+{surface} ;SURFACE COORDINATE ~",
               "  Q6=+2 ;SET-UP CLEARANCE ~", "  Q7=+50 ;CLEARANCE HEIGHT ~",
               "  Q8=+0 ;ROUNDING RADIUS ~",
               f"  Q9={r.choice(['+1', '-1'])} ;ROTATIONAL DIRECTION")
        g.emit("CYCL DEF 22 ROUGH-OUT ~", f"  Q10=+{r.choice([2, 5])} ;PLUNGING DEPTH ~",
               "  Q11=+100 ;FEED RATE FOR PLNGNG ~", "  Q12=+350 ;FEED RATE F. ROUGHNG ~",
               "  Q18=+0 ;COARSE ROUGHING TOOL ~", "  Q19=+0 ;FEED RATE FOR RECIP.")
        g.emit("CYCL CALL")
        finish = r.random()
        if finish < 0.25:
            g.emit("CYCL DEF 23 FLOOR FINISHING ~", "  Q11=+100 ;FEED RATE FOR PLNGNG ~",
                   "  Q12=+350 ;FEED RATE F. ROUGHNG")
            g.emit("CYCL CALL")
        elif finish < 0.5:
            g.emit("CYCL DEF 24 SIDE FINISHING ~", "  Q9=+1 ;ROTATIONAL DIRECTION ~", "  Q10=+5 ;PLUNGING DEPTH ~",
                   "  Q11=+100 ;FEED RATE FOR PLNGNG ~", "  Q12=+350 ;FEED RATE F. ROUGHNG ~",
                   "  Q14=+0 ;ALLOWANCE FOR SIDE")
            g.emit("CYCL CALL")
        g.known = False

    def sl_parameters(self) -> None:
        """The SL cycles' data are the parameters Q1-Q19 (TNC 426/430 user's manual, "SL cycles": "the
        parameters of cycle 20 are global"): the main sections' ``FQn`` and ``+Qn`` words read their values."""
        for block in self.g.blocks[-12:]:
            for line in block:
                for k, v in re.findall(r"\bQ(\d+)=([-+][\d.]+)", line):
                    if int(k) < 20:
                        self.g.q[int(k)] = float(v)

    def old_pattern(self) -> None:
        """An old cycle, 1 PECKING, 2 TAPPING or 17 RIGID TAPPING (TNC 426/430 user's manual), its set-up clearance the
        pattern's Q200, run at the positions of cycle 220 or 221 (:meth:`_Gen.pattern_cycle`)."""
        g, r = self.g, self.r
        g.emit(f"L X{_n(r.uniform(0, 100))} Y{_n(r.uniform(0, 100))} Z+20 R0 FMAX")
        kind = r.choice([1, 2, 17])
        depth = _n(-r.choice([5, 10]))
        if kind == 1:
            lines = ["CYCL DEF 1.0 PECKING", "CYCL DEF 1.1 SET UP 2", f"CYCL DEF 1.2 DEPTH {depth}",
                     f"CYCL DEF 1.3 PECKG {r.choice([3, 20])}", "CYCL DEF 1.4 DWELL 0", "CYCL DEF 1.5 F150"]
        elif kind == 2:
            lines = ["CYCL DEF 2.0 TAPPING", "CYCL DEF 2.1 SET UP 2", f"CYCL DEF 2.2 DEPTH {depth}",
                     f"CYCL DEF 2.3 DWELL {r.choice([0, 0.5])}", "CYCL DEF 2.4 F100"]
        else:
            lines = ["CYCL DEF 17.0 RIGID TAPPING GS", "CYCL DEF 17.1 SET UP 2", f"CYCL DEF 17.2 DEPTH {depth}",
                     f"CYCL DEF 17.3 PITCH {r.choice(['+1', '+1.5'])}"]
        for block in lines:  # each line a block of its own
            g.emit(block)
        stream, g.r = g.r, r  # the pattern's numbers from this stream too
        g.pattern_cycle()
        g.r = stream
        g.known = False

    def jump(self) -> None:
        """``FN 9: IF +Qn EQU +1 GOTO LBL m`` (iTNC 530 user's manual, "If-then decisions with Q parameters"): the
        counted section runs twice, the jump taken when the counter is 1."""
        g, r = self.g, self.r
        n, k = g.lbl, r.choice([62, 63])
        g.lbl += 1
        g.emit(f"FN 0: Q{k} = +0")
        g.emit(f"LBL {n}")
        g.emit(f"L IX{_n(r.choice([2, -3]))} IY{_n(r.choice([0, 1.5]))} R0 F{r.choice([300, 800])}")
        g.emit(f"FN 1: Q{k} = +Q{k} + +1")
        g.emit(f"FN 9: IF +Q{k} EQU +1 GOTO LBL {n}")
        g.known = False

    def sysread(self) -> None:
        """``FN 18: SYSREAD Qn = ID270 NR1 IDXi`` (the position in the active system, iTNC 530 user's manual,
        "FN 18: SYSREAD"), then a move by it: 5 units on from where the tool stands in X or Y."""
        g, r = self.g, self.r
        i = r.choice([1, 2])
        g.emit(f"L X{_n(r.uniform(0, 100))} Y{_n(r.uniform(0, 100))} Z+20 R0 FMAX")
        g.emit(f"FN 18: SYSREAD Q71 = ID270 NR1 IDX{i}")
        g.emit("Q72 = Q71 + 5")
        g.emit(f"L {'XY'[i - 1]}+Q72 R0 F{r.choice([300, 800])}")
        g.known = False

    def strings(self) -> None:
        """``QS`` string parameters (TNC 640 user's manual, "String parameters"): ``DECLARE STRING`` and a
        concatenation ``||``, no motion of their own, between two moves."""
        g, r = self.g, self.r
        g.emit(f'DECLARE STRING QS{r.choice([1, 2])} = "PART"')
        g.emit(f'QS3 = "OP" || "{r.choice(["10", "20"])}"')
        g.emit(f"L X{_n(r.uniform(0, 100))} Y{_n(r.uniform(0, 100))} Z+20 R0 FMAX")
        g.known = False


def generate(seed: int) -> str:
    """A random valid TNC conversational program (text with block numbers) for ``seed``."""
    g = _Gen(seed)
    unit = "INCH" if g.r.random() < 0.15 else "MM"
    g.header(unit)
    g.q_params()
    g.move(rapid=True)
    extras = _Extras(g, seed)
    for _ in range(g.r.randint(3, 9)):
        if extras.r.random() < 0.25:
            extras.section()
        k = g.r.random()
        if not g.known:
            g.move(rapid=True)
        if k < 0.3:
            g.contour(g.r.choice([-2, -5, 0, None]))
        elif k < 0.42:
            g.drilling()
        elif k < 0.52:
            g.repeated()
        elif k < 0.55:
            g.subprogram_call()
        elif k < 0.58:
            g.counted_loop()
        elif k < 0.66:
            g.datum()
        elif k < 0.72:
            g.machine_move()
        elif k < 0.75:
            g.other_cycle()
        elif k < 0.78:
            g.transform()
        elif k < 0.84:
            g.q_params()
        elif k < 0.9:
            g.emit("L Z+50 R0 FMAX")
            g.tool_call()
        elif k < 0.94:
            g.pocket()
        elif k < 0.97:
            g.tilted()
        else:
            g.move()
    g.emit("L Z+50 R0 FMAX M30" if not g.subs else "L Z+50 R0 FMAX")
    if g.subs:
        g.emit("M30")
    for sub in g.subs:
        g.blocks.extend(sub)
    out = [f"0 BEGIN PGM FUZZ{seed} {unit}"]
    for block in g.blocks:
        if not block or not block[0]:
            continue
        out.append(f"{len(out)} {block[0]}")
        out.extend(block[1:])
    out.append(f"{len(out)} END PGM FUZZ{seed} {unit}")
    return "\n".join(out) + "\n"
