"""Seeded random Fanuc / Haas mill programs, for checking the ISO reader's ``fanuc`` and ``haas`` dialects.

Test code only. :func:`generate` writes a valid program as shops and CAM posts write them: ``%``, an ``O`` number
and comment, ``G20``/``G21``, a safe-start line, ``T.. M06`` after ``G91 G28 Z0.``, ``G43 H..`` / ``G49``, work
offsets ``G54``-``G59``, ``G54.1 P..`` (Fanuc) or ``G154 P..`` / ``G110``-``G129`` (Haas), ``G52``, ``G92``,
``G10 L2``/``L20 P..``, ``G53``, ``G28`` through an intermediate point, ``G0``/``G1`` in ``G90`` and ``G91``,
``G2``/``G3`` in ``G17``-``G19`` by ``I J K`` and ``R`` (negative over 180 degrees), full circles and helices,
``G41``/``G42 D..`` contours with lines and arcs (inside and outside corners) entered and left by straight
moves, drilling cycles ``G73 G81 G82 G83 G84 G85 G86 G89`` with ``R``, ``Q``, ``P``, repeats (Fanuc ``K``, Haas
``L``) and ``G98``/``G99`` in ``G90`` and ``G91``, ``G04``, ``M98``/``M99`` subprograms after ``M30``, Macro B
(``#`` variables, ``IF [..] GOTO``, ``WHILE [..] DO``), ``G65`` macro calls, ``G68`` rotation (also inside a
``G52`` local system), ``G51`` scaling and mirror (Fanuc ``G51.1``, Haas ``G101``), a drilling series whose hole
positions are in a subprogram, ``G10 L2 P0`` (the external offset, also of the rotary B), a tool length offset
changed under ``G91`` and travelled by the next incremental Z, ``G28``/``G30`` or ``G53``, ``G84`` fed per revolution
(Fanuc after ``M29 S..``), Haas ``G73 .. Q K`` and Haas ``M99 P<n>`` inside an ``M98``/``M97`` subprogram.

Sources for what each dialect defines: Haas mill operator's manual, G-code chapter ("G02/G03", "G10", "G12",
"G28", "G41/G42", "G52", "G54.1/G154/G110-G129", "G65", "G68", "G73"-"G89", "G98/G99", "G101"), M-code chapter
("M98 Subprogram Call": ``P`` the program, ``L`` the count); FANUC Series 0i-MF operator's manual B-64604EN
("Circular interpolation", "Cutter compensation C", "Canned cycle for drilling": ``K`` the repeat count,
"Subprogram": ``M98 P<count 4 digits><program 4 digits>``, "Custom macro", "Coordinate system rotation",
"Scaling", "Programmable mirror image", "Local coordinate system").

Every section starts from an absolute ``G90 G0`` move, so the generator knows the program position after it;
arc ends sit exactly on their circle (whole Pythagorean vectors), compensated elements are much longer than the
tool radius, a cycle's R plane is above its bottom and below the initial level, scaling is uniform.
"""

from __future__ import annotations

import dataclasses
import math
import random

from interpolators.context import DIALECTS, Dialect, MachineContext, Tool
from interpolators.tilted import Kinematics, RotaryAxis

__all__ = ["generate", "context", "FEATURES"]

#: Whole vectors of length 5, 10, 25 (arc ends exactly on their circle).
_VECTORS = sorted({(sx * u * k, sy * v * k) for u, v in ((0, 5), (3, 4), (4, 3), (5, 0)) for k in (1, 2, 5)
                   for sx in (-1, 1) for sy in (-1, 1)})

#: The sections a program is made of, by name (the report counts programs per feature).
FEATURES = ("lines", "arcs", "helix", "planes", "comp", "cycles", "cycles_g91", "subprogram", "macro", "g65",
            "rotation", "scaling", "mirror", "g52", "g92", "g10", "extended_offset", "g28_g53", "dwell",
            "tool_change", "g91_arcs", "comp_rotated", "cycles_rotated", "boring", "corner_words", "nested_sub",
            "tool_length", "haas_pattern", "haas_pocket", "haas_peck", "m97", "polar", "comp_arcs", "macro_system",
            "cycle_modal", "g28_shifted", "depth_passes", "scaling_ijk", "block_delete", "corner_arc", "g10_tools",
            "cycle_sub", "g52_rotated", "external", "tcp", "length_motion", "rigid_tap", "haas_g73k", "m99_branch",
            "length_block", "length_reference", "length_cycle", "rigid_tap_end", "arc3d", "offset_vars",
            "haas_then", "peck_tap", "g66", "inverse_time", "frames", "modal_info")


def context(seed: int, dialect: str) -> MachineContext:
    """The machine the generated program of ``seed`` runs on: offsets for G54-G59 and the first extended ones,
    tools 1-6 (length 10n mm, radius 0.5 + 0.25n mm), a rotary table B; or for a quarter of the seeds
    (:func:`five_axis`) the A/C tilting table :data:`_AC_TABLE` instead."""
    offsets = {f"G5{k}": (-300.0 + 10 * k, -200.0 + 5 * k, -400.0 + k) for k in range(4, 10)}
    offsets.update({f"G54.1 P{k}": (-250.0 + k, -150.0 - k, -350.0) for k in range(1, 21)})
    tools = {n: Tool(number=n, length=10.0 * n, radius=0.5 + 0.25 * n) for n in range(1, 7)}
    five = five_axis(seed, dialect)
    return MachineContext(work_offsets=offsets, tools=tools, home=(0.0, 0.0, 0.0), dialect=_dialect(seed, dialect),
                          extra_axes=("a", "c") if five else ("b",), kinematics=_AC_TABLE if five else None,
                          decimal_point_input="increment" if _increments(seed, dialect) else "calculator")


#: The tilting table of the five-axis seeds: A about X round (0, 0, -80), C about Z through (5, 0, 0).
_AC_TABLE = Kinematics(axes=(RotaryAxis(name="a", pivot=(0.0, 0.0, -80.0), limits=(-120.0, 120.0)),
                             RotaryAxis(name="c", pivot=(5.0, 0.0, 0.0))))


def _dialect(seed: int, dialect: str) -> Dialect:
    """The dialect, and for a Fanuc program with a ``peck_tap`` section the machine's peck rigid tapping (PCP, No.
    5200#5: high-speed or standard; d, No. 5213 [mm]; Fanuc 16i-TA/TB A-78549E 3.4)."""
    if dialect != "fanuc" or "peck_tap" not in features(seed, dialect):
        return DIALECTS[dialect]
    r = random.Random(f"{seed}:peck_tapping")
    return dataclasses.replace(DIALECTS[dialect], peck_tapping=r.choice(("high-speed", "standard")),
                               peck_tapping_d=r.choice((0.5, 1.0, 2.0)))


def five_axis(seed: int, dialect: str) -> bool:
    """The program of ``seed`` runs on the A/C tilting table (about a quarter of the seeds) and may use tool
    centre point control (Fanuc ``G43.4``, Haas ``G234``)."""
    return random.Random(f"{seed}:{dialect}:five").random() < 0.25


def _increments(seed: int, dialect: str) -> bool:
    """A Fanuc with DPI = 0 (parameter No. 3401#0; :mod:`interpolators.iso_decimal`) for about a third of the
    seeds: its programs write some distances as integers of least input increments (``X12500`` for 12.5 mm)."""
    return dialect == "fanuc" and random.Random(f"{seed}:dpi").random() < 0.3


def _num(v: float) -> str:
    """A number as CAM posts write it: always a decimal point (``10.``, ``-2.5``, ``0.``), at most 4 decimals."""
    s = f"{v:.4f}".rstrip("0")
    return "0." if s in ("0.", "-0.") else s


@dataclasses.dataclass
class _Gen:
    r: random.Random
    dialect: str
    unit: float  # one grid step in program units (mm: 1, inch: 0.05)
    lines: list[str] = dataclasses.field(default_factory=list)
    subs: list[list[str]] = dataclasses.field(default_factory=list)
    used: set = dataclasses.field(default_factory=set)
    n: int = 0
    pos: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.0, 0.0])  # grid units
    tool: int = 0
    label: int = 9000
    dpi0: bool = False
    five: bool = False  # the A/C tilting table (:func:`five_axis`)

    @property
    def fanuc(self) -> bool:
        return self.dialect == "fanuc"

    def emit(self, text: str, *, number: int | None = None, skip_after_number: bool = False) -> None:
        """Append a block, numbered with ``number`` or half of the time with the next N; a block delete slash
        stands at the head of the block, or with ``skip_after_number`` after its N (``N45 /G1``)."""
        self.n += 5
        if number is None and (skip_after_number or self.r.random() < 0.5):
            number = self.n
        skip = "/" if text.startswith("/") else ""
        text = text.removeprefix("/")
        if number is None:
            self.lines.append(skip + text)
        else:
            self.lines.append(f"N{number} {skip}{text}" if skip_after_number else f"{skip}N{number} {text}")

    def v(self, grid: float, *, plain: bool = True) -> str:
        """A distance of ``grid`` steps; under DPI = 0 sometimes as an integer of least input increments."""
        if plain and self.dpi0 and self.r.random() < 0.5:
            count = grid * self.unit * (1000 if self.unit == 1.0 else 10000)
            if abs(count - round(count)) < 1e-9:
                return str(round(count))
        return _num(grid * self.unit)

    def xyz(self, x=None, y=None, z=None, *, inc: bool = False) -> str:
        out = []
        for letter, val, k in (("X", x, 0), ("Y", y, 1), ("Z", z, 2)):
            if val is not None:
                out.append(letter + self.v(val - self.pos[k] if inc else val))
                self.pos[k] = val
        return " ".join(out)

    def feed(self) -> str:
        return f"F{self.r.choice((100, 250, 500, 1200)) * (0.04 if self.unit < 1 else 1):g}"

    def start(self, z: float = 10.0) -> None:
        """Every section begins known: an absolute rapid over a grid point, then down to ``z``."""
        x, y = self.r.randint(-8, 8) * 5, self.r.randint(-8, 8) * 5
        self.emit(f"G90 G0 {self.xyz(x, y)}")
        self.emit(f"G0 {self.xyz(z=z)}")

    # -- sections ------------------------------------------------------------------------------------
    def lines_section(self) -> None:
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        for _ in range(self.r.randint(2, 5)):
            x, y = self.pos[0] + self.r.randint(-6, 6) * 2.5, self.pos[1] + self.r.randint(-6, 6) * 2.5
            if self.r.random() < 0.4:
                self.emit(f"G91 G1 {self.xyz(x, y, inc=True)}")
                self.emit("G90")
            else:
                self.emit(f"{self.r.choice(('G1 ', ''))}{self.xyz(x, y)}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def arc(self, code: str, *, plane=(0, 1), helix: float | None = None, full: bool = False) -> str:
        """One arc from the current point: ``I J`` (or ``I K``, ``J K``) or ``R`` words."""
        i, j = plane
        letters = "IJK"
        c = self.r.choice(_VECTORS)
        centre = (self.pos[i] + c[0], self.pos[j] + c[1])
        if full:
            end = (self.pos[i], self.pos[j])
        else:
            while True:
                e = self.r.choice(_VECTORS)
                if (e[0] ** 2 + e[1] ** 2) == c[0] ** 2 + c[1] ** 2 and e != (-c[0], -c[1]) and e != c:
                    break
            end = (centre[0] + e[0], centre[1] + e[1])
        words = {i: end[0], j: end[1]}
        if helix is not None:
            words[3 - i - j] = helix
        target = [words.get(k) for k in range(3)]
        radius = (c[0] ** 2 + c[1] ** 2) ** 0.5
        use_r = not full and self.r.random() < 0.4
        if use_r:
            s = (self.pos[i] - centre[0], self.pos[j] - centre[1])
            e = (end[0] - centre[0], end[1] - centre[1])
            cross = s[0] * e[1] - s[1] * e[0]
            ccw = code == "G3"
            large = (cross < 0) if ccw else (cross > 0)
            centre_words = "R" + self.v(-radius if large else radius)
        else:
            centre_words = f"{letters[i]}{self.v(c[0])} {letters[j]}{self.v(c[1])}"
        return f"{code} {self.xyz(*target)} {centre_words}"

    def arcs_section(self) -> None:
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        for _ in range(self.r.randint(1, 4)):
            self.emit(self.arc(self.r.choice(("G2", "G3")), full=self.r.random() < 0.2))
        self.emit(f"G0 {self.xyz(z=10)}")

    def helix_section(self) -> None:
        self.start(2)
        self.emit(f"G1 {self.xyz(z=0)} {self.feed()}")
        for k in range(self.r.randint(1, 3)):
            self.emit(self.arc(self.r.choice(("G2", "G3")), helix=-(k + 1) * 0.5, full=self.r.random() < 0.5))
        self.emit(f"G0 {self.xyz(z=10)}")

    def planes_section(self) -> None:
        self.start(20)
        code, plane = self.r.choice((("G18", (2, 0)), ("G19", (1, 2))))
        self.emit(code)
        self.emit(f"G1 {self.xyz(z=15)} {self.feed()}")
        for _ in range(self.r.randint(1, 3)):
            self.emit(self.arc(self.r.choice(("G2", "G3")), plane=plane, full=self.r.random() < 0.2))
        self.emit("G17")
        self.emit(f"G0 {self.xyz(z=40)}")

    def comp_section(self, d: int | None = None) -> None:
        """A rectangle (sharp or rounded corners) climb- or conventional-cut inside or outside, with offset ``D<d>``
        (else a random one); rounded corners are sometimes helical, each 0.5 lower (Fanuc 0i-MF "Helical
        interpolation": "Cutter compensation is applied only for a circular arc"; fuzz40)."""
        if not self.tool:
            self.tool_change()
        x0, y0 = self.r.randint(-4, 4) * 5, self.r.randint(-4, 4) * 5
        w, h = self.r.choice((20, 30, 40)), self.r.choice((20, 30))
        rc = self.r.choice((0, 0, 5))
        helical = self.r.random() < 0.3
        ccw = self.r.random() < 0.5
        side = self.r.choice(("G41", "G42"))
        d = self.r.randint(1, 6) if d is None else d
        self.emit(f"G90 G0 {self.xyz(x0 + w / 2, y0 - 15)}")
        self.emit(f"G0 {self.xyz(z=5)}")
        self.emit(f"G1 {self.xyz(z=-2)} {self.feed()}")
        self.emit(f"{side} D{d} G1 {self.xyz(y=y0)}")
        pts = [(x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h), (x0, y0), (x0 + w / 2, y0)]
        if not ccw:
            pts = [(x0, y0), (x0, y0 + h), (x0 + w, y0 + h), (x0 + w, y0), (x0 + w / 2, y0)]
        for k, (px, py) in enumerate(pts[:-1]):
            if rc:
                nx, ny = pts[k + 1] if k + 1 < 4 else pts[0]
                # stop rc before the corner, then round it with an arc of radius rc
                dx, dy = (px - self.pos[0], py - self.pos[1])
                ln = max(abs(dx), abs(dy))
                bx, by = px - dx / ln * rc, py - dy / ln * rc
                self.emit(f"G1 {self.xyz(bx, by)}")
                ex, ey = (nx - px), (ny - py)
                el = max(abs(ex), abs(ey))
                ax, ay = px + ex / el * rc, py + ey / el * rc
                code = "G3" if ccw else "G2"
                z = self.pos[2] - 0.5 if helical else None
                if self.r.random() < 0.5:
                    self.emit(f"{code} {self.xyz(ax, ay, z)} R{self.v(rc)}")
                else:
                    ci, cj = bx + ex / el * rc - self.pos[0], by + ey / el * rc - self.pos[1]
                    self.emit(f"{code} {self.xyz(ax, ay, z)} I{self.v(ci)} J{self.v(cj)}")
            else:
                self.emit(f"G1 {self.xyz(px, py)}")
        self.emit(f"G1 {self.xyz(*pts[-1])}")
        self.emit(f"G40 G1 {self.xyz(y=y0 - 15)}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def cycles_section(self, incremental: bool = False) -> None:
        code = self.r.choice(("G73", "G81", "G82", "G83", "G84", "G85", "G86", "G89"))
        ret = self.r.choice(("G98", "G99"))
        self.start(self.r.choice((10, 20)))
        initial = self.pos[2]
        rplane, bottom = self.r.choice((2, 5)), -self.r.choice((5, 8, 12))
        words = ""
        if code in ("G73", "G83"):
            words += f" Q{self.v(self.r.choice((1.5, 2, 3)))}"
        if code in ("G82", "G89", "G86") and self.r.random() < 0.7 or code == "G84" and self.r.random() < 0.3:
            words += f" P{self.r.choice((200, 500, 1000))}"
        feed = "F50." if code == "G84" else self.feed()
        x, y = self.pos[0] + self.r.randint(-3, 3) * 5, self.pos[1] + self.r.randint(-3, 3) * 5
        rep = self.r.random() < 0.3
        if incremental:
            dx, dy = self.r.choice(((5, 0), (0, 5), (-5, 5), (10, -5)))
            count = self.r.randint(1, 4) if rep else 1
            kw = (f" K{count}" if self.fanuc else f" L{count}") if rep else ""
            self.emit(f"G91 {ret} {code} X{self.v(dx)} Y{self.v(dy)} Z{self.v(bottom - rplane)} "
                      f"R{self.v(rplane - initial)}{words}{kw} {feed}")
            self.pos[0] += dx * count
            self.pos[1] += dy * count
            for _ in range(self.r.randint(0, 2)):
                self.emit(f"X{self.v(dx)} Y{self.v(dy)}")
                self.pos[0] += dx
                self.pos[1] += dy
            self.emit("G80 G90")
        else:
            self.emit(f"G90 {ret} {code} {self.xyz(x, y)} Z{self.v(bottom)} R{self.v(rplane)}{words} {feed}")
            for _ in range(self.r.randint(0, 3)):
                self.emit(self.xyz(self.pos[0] + self.r.randint(-3, 3) * 5, self.pos[1] + 5))
            self.emit("G80")
        self.pos[2] = initial if ret == "G98" else rplane
        self.emit(f"G0 {self.xyz(z=20)}")

    def subprogram_section(self) -> None:
        prog = 1000 + len(self.subs) * 10
        count = self.r.randint(1, 3)
        body = [f"O{prog} (SUB)", f"G91 G1 X{self.v(5)} {self.feed()}", f"Y{self.v(5)}", "G90", "M99"]
        if self.r.random() < 0.5:
            body[1:4] = [f"G91 G0 X{self.v(10)}", f"G1 Z{self.v(-3)} {self.feed()}", f"G0 Z{self.v(3)}", "G90"]
        self.subs.append(body)
        self.start()
        if self.fanuc and self.r.random() < 0.6:
            self.emit(f"M98 P{count:04d}{prog:04d}" if count > 1 else f"M98 P{prog}")
        else:
            self.emit(f"M98 P{prog}" + (f" L{count}" if count > 1 else ""))

    def macro_section(self) -> None:
        self.start()
        self.label += 10
        a, b = self.r.randint(2, 4), self.r.choice((2.5, 5))
        self.emit(f"#101={a}")
        self.emit(f"#102={_num(b * self.unit)}")
        self.emit(f"#103={self.v(self.pos[0], plain=False)}")
        self.emit(f"G1 Z{self.v(-1)} {self.feed()}")
        if self.r.random() < 0.5:
            self.emit("WHILE [#101 GT 0] DO1")
            self.emit("#103=#103+#102")
            self.emit("G1 X#103")
            self.emit("#101=#101-1")
            self.emit("END1")
        else:
            lab = self.label
            self.emit("#103=#103+#102", number=lab)
            self.emit("G1 X#103 Y[#103*0.5]")
            self.emit("#101=#101-1")
            self.emit(f"IF [#101 GT 0] GOTO{lab}")
        if self.r.random() < 0.5:
            self.emit(f"IF [#102 LT 0] THEN #104={self.v(3, plain=False)}")
        self.emit(f"G0 Z{self.v(10)}")

    def g65_section(self) -> None:
        prog = 9010 + len(self.subs)
        self.subs.append([f"O{prog} (BOLT CIRCLE)", "#10=0", "WHILE [#10 LT #11] DO1",
                          "#12=#24+#18*COS[#1+#10*360/#11]", "#13=#25+#18*SIN[#1+#10*360/#11]",
                          "G90 G0 X#12 Y#13", "G1 Z#26 F#9", "G0 Z#17", "#10=#10+1", "END1", "M99"])
        self.start()
        self.emit(f"G65 P{prog} X{self.v(self.pos[0], plain=False)} Y{self.v(self.pos[1], plain=False)} "
                  f"R{self.v(10, plain=False)} A{self.r.choice((0, 15, 30))}. H{self.r.randint(2, 5)}. "
                  f"Z{self.v(-2, plain=False)} Q{self.v(5, plain=False)} "
                  f"F{_num(100 * (0.04 if self.unit < 1 else 1))}")
        self.emit(f"G90 G0 {self.xyz(z=10)}")

    def transform_section(self, kind: str) -> None:
        self.start()
        cx, cy = self.pos[0], self.pos[1]
        if kind == "rotation":
            self.emit(f"G68 X{self.v(cx)} Y{self.v(cy)} R{self.r.choice((15, 30, 45, 90, -30))}.")
        elif kind == "scaling":
            s = self.r.choice((0.5, 2.0, 1.5))
            centre = f"X{self.v(cx)} Y{self.v(cy)}"
            self.emit(f"G51 {centre} P{s * 1000:.0f}" if self.fanuc and self.r.random() < 0.5
                      else f"G51 {centre} P{_num(s)}")
        elif self.fanuc:
            self.emit(f"G51.1 X{self.v(cx)}")
        else:
            self.emit("G101 X0.")
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        self.emit(f"G1 {self.xyz(self.pos[0] + 10, self.pos[1] + 5)}")
        self.emit(self.arc(self.r.choice(("G2", "G3"))))
        self.emit(f"G0 {self.xyz(z=10)}")
        self.emit({"rotation": "G69", "scaling": "G50"}.get(kind, "G50.1 X0." if self.fanuc else "G100 X0."))

    def g52_section(self) -> None:
        self.emit(f"G52 X{self.v(self.r.randint(-4, 4) * 5)} Y{self.v(self.r.randint(-4, 4) * 5)}")
        self.lines_section()
        self.emit("G52 X0. Y0.")

    def g92_section(self) -> None:
        self.start()
        px, py = self.pos[0], self.pos[1]
        self.emit("G92 X0. Y0.")
        self.pos[0] = self.pos[1] = 0.0
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        self.emit(f"G1 {self.xyz(10, 5)}")
        self.emit(f"G0 {self.xyz(z=10)}")
        self.emit(f"G92 X{self.v(self.pos[0] + px)} Y{self.v(self.pos[1] + py)}")

    def g10_section(self) -> None:
        p = self.r.randint(1, 6)
        vals = " ".join(f"{a}{_num(self.r.randint(-40, 40) * 5.0 * self.unit)}" for a in "XYZ")
        mode = self.r.choice(("G90", "G90", "G91"))  # G91: added to the offset (Fanuc 0i-MF "G10 L2", fuzz40)
        if self.r.random() < 0.5:
            self.emit(f"{mode} G10 L2 P{p} {vals}")
        else:
            self.emit(f"{mode} G10 L20 P{p} {vals}")
            p = 0
        self.emit(f"G90 G{53 + p}" if p else "G90 " + self.extended_code(1))
        self.lines_section()

    def external_section(self) -> None:
        """``G10 L2 P0``: the external workpiece zero offset, which shifts every workpiece system, for X Y Z and
        the rotary B (Fanuc 0i-MD B-64304EN "Changing workpiece coordinate system": ``G10 L2 Pp IP_``, p=0 the
        external workpiece zero point offset; Haas "G10": P0 the G52 entry, the common shift), absolute or added
        under G91, moves in the shifted system, then the offset cleared."""
        vals = " ".join(f"{a}{_num(self.r.randint(-8, 8) * 2.5 * self.unit)}" for a in "XYZ")
        rot = "C" if self.five else "B"
        b = f" {rot}{self.r.choice((15, -30, 90))}." if self.r.random() < 0.5 else ""
        self.emit(f"{self.r.choice(('G90', 'G91'))} G10 L2 P0 {vals}{b}")
        self.emit("G90")
        self.lines_section()
        if self.r.random() < 0.5:
            self.emit(f"G0 {rot}{self.r.choice((0, 45, -60))}.")
        self.emit("G90 G10 L2 P0 X0. Y0. Z0." + (f" {rot}0." if b else ""))

    def tcp_section(self) -> None:
        """On the five-axis seeds, tool centre point control on the A/C table: Fanuc ``G43.4 H..`` (FANUC 30i
        "Tool center point control for 5-axis machining" A-79348E 1.1: X Y Z the tool tip in the workpiece
        system, which the table carries), Haas ``G234 H..`` ("G234 Tool Center Point Control (TCPC)"), G0/G1
        moves with A and C, ended by ``G49`` and the table turned back; then ``G43 H`` again. Elsewhere plain
        lines."""
        if not self.five:
            self.lines_section()
            return
        self.start(30)
        turned = f"G0 A{self.r.choice((-15, 20))}. C{self.r.randint(0, 8) * 45}."
        self.emit("G0 A0. C0." if self.r.random() < 0.6 else turned)
        self.emit(f"{'G43.4' if self.fanuc else 'G234'} H{self.tool or 1} {self.xyz(z=20)}")
        for _ in range(self.r.randint(1, 4)):
            x, y = self.pos[0] + self.r.randint(-4, 4) * 2.5, self.pos[1] + self.r.randint(-4, 4) * 2.5
            rapid = self.r.random() < 0.3
            feed = "" if rapid else " " + self.feed()
            self.emit(f"G{0 if rapid else 1} {self.xyz(x, y, self.r.choice((5, 10, 20)))} "
                      f"A{self.r.randint(-6, 6) * 5}. C{self.r.randint(-8, 8) * 15}.{feed}")
        self.emit("G49")
        self.emit("G0 A0. C0.")
        self.emit(f"G43 H{self.tool or 1} {self.xyz(z=50)}")

    def extended_code(self, k: int) -> str:
        if self.fanuc:
            return f"G54.1 P{k}"
        return self.r.choice((f"G154 P{k}", f"G{109 + k}"))

    def extended_section(self) -> None:
        self.emit(self.extended_code(self.r.randint(1, 20)))
        self.lines_section()
        self.emit(f"G5{self.r.randint(4, 9)}")

    def g28_g53_section(self) -> None:
        self.start()
        if self.r.random() < 0.5:
            self.emit(f"G28 {self.xyz(z=self.pos[2] + 5)}")
        else:
            self.emit("G91 G28 Z0.")
            self.emit("G90")
        if self.r.random() < 0.5:
            self.emit("G91 G28 X0. Y0.")
            self.emit("G90")
        self.emit(f"G53 G0 Z{_num(-self.r.choice((0, 10, 50)) * 1.0 * self.unit)}")
        if self.r.random() < 0.3:  # G53 under G91: a move by its words (Mitsubishi M700V 14.4, vcnc's reading)
            self.emit(f"G91 G53 G0 Z{_num(-self.r.choice((5, 10)) * self.unit)}")
            self.emit("G90")

    def dwell_section(self) -> None:
        self.start()
        if self.fanuc:
            self.emit(self.r.choice(("G04 X1.5", "G04 P1500", "G4 X0.5")))
        else:
            self.emit(self.r.choice(("G04 P1.5", "G04 P500", "G4 P0.5")))

    def g91_arcs_section(self) -> None:
        """Arcs with incremental end points (G91): in G17, sometimes helical, or in G18/G19 (fuzz40: the plane's
        axes other than X Y, and a helix's third axis, as increments)."""
        plane_code, plane = self.r.choice((("G17", (0, 1)), ("G17", (0, 1)), ("G18", (2, 0)), ("G19", (1, 2))))
        self.start(20 if plane_code != "G17" else 10)
        self.emit(f"{plane_code} G1 {self.xyz(z=15 if plane_code != 'G17' else -1)} {self.feed()}")
        self.emit("G91")
        for _ in range(self.r.randint(1, 3)):
            before, dpi0 = list(self.pos), self.dpi0
            self.dpi0 = False  # the absolute words are read back below
            helix = self.pos[2] - self.r.choice((1, 2)) if plane_code == "G17" and self.r.random() < 0.3 else None
            text = self.arc(self.r.choice(("G2", "G3")), plane=plane, helix=helix, full=self.r.random() < 0.2)
            self.dpi0 = dpi0
            code, rest = text.split(" ", 1)
            words = []
            for w in rest.split():
                k = "XYZ".find(w[0])
                if k >= 0:
                    w = w[0] + self.v(float(w[1:]) / self.unit - before[k])
                words.append(w)
            self.emit(f"{code} {' '.join(words)}")
        self.emit("G90 G17")
        self.emit(f"G0 {self.xyz(z=40 if plane_code != 'G17' else 10)}")

    def comp_rotated_section(self) -> None:
        kind = self.r.choice(("G68", "mirror", "G52", "G51"))
        cx, cy = self.r.randint(-4, 4) * 5, self.r.randint(-4, 4) * 5
        if kind == "G68":
            self.emit(f"G68 X{self.v(cx)} Y{self.v(cy)} R{self.r.choice((30, 45, 90, -60))}.")
        elif kind == "G51":  # the contour scaled, the tool radius not (0i-MF "Scaling": not to offsets)
            self.emit(f"G51 X{self.v(cx)} Y{self.v(cy)} P{self.r.choice(('2.', '1.5', '0.8'))}")
        elif kind == "G52":
            self.emit(f"G52 X{self.v(cx)} Y{self.v(cy)}")
        else:
            self.emit(f"G51.1 X{self.v(cx)}" if self.fanuc else "G101 X0.")
        self.comp_section()
        self.emit({"G68": "G69", "G52": "G52 X0. Y0.", "G51": "G50"}.get(kind, "G50.1 X0." if self.fanuc else
                                                                           "G100 X0."))

    def cycles_rotated_section(self) -> None:
        self.start(20)
        mirror = self.r.random() < 0.4
        if mirror:
            self.emit(f"G51.1 X{self.v(self.pos[0] + 5)}" if self.fanuc else "G101 X0. Y0.")
        else:
            self.emit(f"G68 X{self.v(self.pos[0])} Y{self.v(self.pos[1])} R{self.r.choice((30, 45, 90))}.")
        self.cycles_section(self.r.random() < 0.5)
        self.emit(("G50.1 X0." if self.fanuc else "G100 X0. Y0.") if mirror else "G69")

    def boring_section(self) -> None:
        """G76 fine boring (shift Q, Haas also I J) and G87 back boring (Haas G77): Fanuc 0i-MF "Fine boring
        cycle", "Back boring cycle"; Haas "G76", "G77"."""
        self.start(20)
        shift = f"Q{self.v(0.5)}" if self.fanuc or self.r.random() < 0.5 else f"I{self.v(0.5)} J0."
        if self.r.random() < 0.5:
            self.emit(f"G90 {self.r.choice(('G98', 'G99'))} G76 {self.xyz(self.pos[0] + 5, self.pos[1])} "
                      f"Z{self.v(-10)} R{self.v(2)} {shift} P500 {self.feed()}")
        else:
            self.emit(f"G90 G98 {'G87' if self.fanuc else 'G77'} {self.xyz(self.pos[0] + 5, self.pos[1])} "
                      f"Z{self.v(-2)} R{self.v(-12)} {shift} {self.feed()}")
        self.emit(f"{self.xyz(self.pos[0] + 10, self.pos[1])}")
        self.emit("G80")
        self.pos[2] = 20
        self.emit(f"G0 {self.xyz(z=25)}")

    def corner_words_section(self) -> None:
        """``,R`` / ``,C`` between G01 moves (Fanuc 0i-MF "Optional chamfering and corner R"; Haas "G01 Corner
        Rounding and Chamfering")."""
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        x, y = self.pos[0], self.pos[1]
        pts = [(x + 20, y), (x + 20, y + 20), (x, y + 20), (x, y)]
        for k, (px, py) in enumerate(pts):
            size = self.v(self.r.choice((1, 2, 3)))  # DPI = 0: ,R2000 is 2 mm (vcnc's reading, iso_decimal)
            word = "" if k == len(pts) - 1 else f" ,{self.r.choice('RC')}{size}"
            self.emit(f"G1 {self.xyz(px, py)}{word}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def nested_sub_section(self) -> None:
        inner = 2000 + len(self.subs) * 10
        outer = inner + 5
        self.subs.append([f"O{inner} (INNER)", f"G91 G1 Y{self.v(2)} {self.feed()}", "G90", "M99"])
        self.subs.append([f"O{outer} (OUTER)", f"G91 G1 X{self.v(3)} {self.feed()}", "G90", f"M98 P{inner}",
                          "M99"])
        self.start()
        self.emit(f"M98 P{outer}" + (f" L{self.r.randint(2, 3)}" if self.r.random() < 0.5 else ""))

    def tool_length_section(self) -> None:
        """A second G43 H without G49 (Fanuc: the new offset replaces the old), H of another tool."""
        self.start(30)
        self.emit(f"G43 H{self.r.randint(1, 6)} {self.xyz(z=25)}")
        self.emit(f"G1 {self.xyz(self.pos[0] + 5, self.pos[1])} {self.feed()}")
        self.emit(f"G43 H{self.tool or 1} {self.xyz(z=30)}")

    def haas_pattern_section(self) -> None:
        """Haas G70 bolt hole circle, G71 bolt hole arc, G72 holes along an angle, with G81 active."""
        if self.fanuc:
            return self.cycles_section()
        self.start(20)
        self.emit(f"G90 G99 G81 Z{self.v(-5)} R{self.v(2)} L0 {self.feed()}")
        code = self.r.choice(("G70", "G71", "G72"))
        n = self.r.randint(2, 6)
        words = f"I{self.v(10)} J{self.r.choice((0, 15, 30))}. L{n}"
        if code == "G71":
            words += f" K{self.r.choice((20, 30))}."
        self.emit(f"{code} {words} X{self.v(self.pos[0])} Y{self.v(self.pos[1])}")
        self.emit("G80")
        self.pos[2] = 2
        self.emit(f"G0 {self.xyz(z=20)}")

    def haas_pocket_section(self) -> None:
        """Haas G12 / G13 circular pocket milling (Haas mill operator's manual "G12/G13")."""
        if self.fanuc:
            return self.arcs_section()
        if not self.tool:
            self.tool_change()
        self.start(2)
        extra = f" Q{self.v(3)} K{self.v(15)}" if self.r.random() < 0.5 else ""
        self.emit(f"{self.r.choice(('G12', 'G13'))} I{self.v(6)}{extra} D{self.tool} Z{self.v(-2)} {self.feed()}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def haas_peck_section(self) -> None:
        """Haas G83 with I (first peck) J (less each time) K (at least): Haas "G83 Normal Peck Drilling"; Fadal
        the same (Fusion's fadal.cps)."""
        if self.fanuc:
            return self.cycles_section()
        self.start(20)
        self.emit(f"G90 G98 G83 {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-12)} R{self.v(2)} "
                  f"I{self.v(4)} J{self.v(1)} K{self.v(1.5)} {self.feed()}")
        self.emit("G80")
        self.pos[2] = 20
        self.emit(f"G0 {self.xyz(z=25)}")

    def m97_section(self) -> None:
        """Haas M97 P<n> L<k>: the blocks from N<n> of this program to M99."""
        if self.fanuc:
            return self.subprogram_section()
        n = 8000 + len(self.subs) * 10
        self.subs.insert(0, [f"N{n} G91 G1 X{self.v(4)} {self.feed()}", "G90", "M99"])
        self.start()
        self.emit(f"M97 P{n}" + (f" L{self.r.randint(2, 3)}" if self.r.random() < 0.5 else ""))

    def polar_section(self) -> None:
        """Fanuc G16 polar coordinates (X the radius, Y the angle about the work zero); G15 cancels."""
        if not self.fanuc:
            return self.lines_section()
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        self.emit("G16")
        for _ in range(self.r.randint(1, 3)):
            self.emit(f"G1 X{self.v(self.r.choice((10, 20, 25)))} Y{self.r.choice((0, 30, 45, 120, -60))}.")
        self.emit("G15")
        self.emit(f"G90 G0 {self.xyz(z=10)}")

    def comp_arcs_section(self) -> None:
        """A G41/G42 slot: two lines joined by half circles (outside or inside by the side), or a line, a quarter
        arc and a line meeting at a tangent or a corner."""
        if not self.tool:
            self.tool_change()
        x0, y0 = self.r.randint(-4, 4) * 5, self.r.randint(-4, 4) * 5
        side = self.r.choice(("G41", "G42"))
        self.emit(f"G90 G0 {self.xyz(x0 - 15, y0)}")
        self.emit(f"G0 {self.xyz(z=5)}")
        self.emit(f"G1 {self.xyz(z=-2)} {self.feed()}")
        self.emit(f"{side} D{self.r.randint(1, 6)} G1 {self.xyz(x0)}")
        if self.r.random() < 0.5:  # a slot of width 20: half circles of radius 10 at both ends
            self.emit(f"G1 {self.xyz(x0 + 30)}")
            self.emit(f"G3 {self.xyz(y=y0 + 20)} " + (f"R{self.v(10)}" if self.r.random() < 0.5 else
                                                      f"I0. J{self.v(10)}"))
            self.emit(f"G1 {self.xyz(x0)}")
            self.emit(f"G3 {self.xyz(y=y0)} " + (f"R{self.v(10)}" if self.r.random() < 0.5 else f"J{self.v(-10)}"))
            self.emit(f"G1 {self.xyz(x0 + 10)}")
        else:  # a line, a quarter arc (tangent or turned), a line
            code = self.r.choice(("G2", "G3"))
            sy = 1 if code == "G3" else -1
            self.emit(f"G1 {self.xyz(x0 + 20)}")
            if self.r.random() < 0.5:
                self.emit(f"{code} {self.xyz(x0 + 30, y0 + 10 * sy)} J{self.v(10 * sy)}")
            else:  # the arc leaves the line at a corner: centre straight ahead
                self.emit(f"{code} {self.xyz(x0 + 40, y0)} I{self.v(10)} J0.")
            self.emit(f"G1 {self.xyz(y=self.pos[1] + 20 * sy)}")
        self.emit(f"G40 G1 {self.xyz(self.pos[0] + 15)}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def macro_system_section(self) -> None:
        """Macro B functions and loops (Fanuc 0i-MF "Custom macro": ROUND, FIX, FUP, ABS, SQRT, ATAN, nested
        WHILE, AND in IF)."""
        self.start()
        self.emit(f"#110={self.v(self.pos[0], plain=False)}+{self.v(5, plain=False)}")
        self.emit(f"#111={self.v(self.pos[1], plain=False)}")
        self.emit(f"G1 Z{self.v(-1)} {self.feed()}")
        self.emit("#120=1")
        self.emit("WHILE [#120 LE 2] DO1")
        self.emit("#121=1")
        self.emit("WHILE [#121 LE 2] DO2")
        self.emit(f"G1 X[#110+#121*{self.v(2, plain=False)}] Y[#111+#120*{self.v(3, plain=False)}]")
        self.emit("#121=#121+1")
        self.emit("END2")
        self.emit("#120=#120+1")
        self.emit("END1")
        self.emit(f"IF [[#121 EQ 3] AND [#120 GT 2]] THEN #122=ROUND[{self.v(7.6, plain=False)}]")
        self.emit(f"#123=FIX[{self.v(2.7, plain=False)}]+FUP[{self.v(1.2, plain=False)}]+ABS[-1]+SQRT[16]")
        self.emit("#124=ATAN[1]/[1]")
        self.emit("G1 X[#110+#122] Y[#111+#123+#124/45]")
        x, y = self.pos[0], self.pos[1]
        self.emit(f"G0 Z{self.v(10)}")
        self.emit(f"G90 G0 {self.xyz(x, y)}")

    def cycle_modal_section(self) -> None:
        """A drilling series whose later blocks change Z and R, and G99 to G98 under a higher R (a work offset
        switched within the series is left out: where the initial level then lies no manual says)."""
        code = self.r.choice(("G81", "G82", "G83", "G73"))
        self.start(20)
        q = f" Q{self.v(2)}" if code in ("G73", "G83") else ""
        p = " P300" if code == "G82" else ""
        self.emit(f"G90 G99 {code} {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-6)} R{self.v(3)}{q}{p} "
                  f"{self.feed()}")
        self.emit(f"{self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-9)}")
        self.emit(f"G98 {self.xyz(self.pos[0], self.pos[1] + 5)} R{self.v(5)}")
        self.emit("G80")
        self.pos[2] = 20
        self.emit(f"G0 {self.xyz(z=25)}")

    def cycle_sub_section(self) -> None:
        """A drilling series whose hole positions are in a subprogram: the cycle stays modal through M98 and
        drills at each position block of the subprogram (Haas mill operator's manual, "Subprograms": "G81 G99
        Z-0.26 R0.1 F7." then "M98 P1000" with the positions "X.. Y.." in O01000; Fanuc 0i-MF "Canned cycle
        for drilling": the cycle is modal until G80). Absolute positions, called once."""
        code = self.r.choice(("G81", "G82", "G83", "G73", "G85"))
        ret = self.r.choice(("G98", "G99"))
        self.start(20)
        q = f" Q{self.v(2)}" if code in ("G73", "G83") else ""
        p = " P300" if code == "G82" else ""
        self.emit(f"G90 {ret} {code} {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-6)} R{self.v(3)}{q}{p} "
                  f"{self.feed()}")
        prog = 3000 + len(self.subs) * 10
        body = [f"O{prog} (HOLES)"]
        for _ in range(self.r.randint(1, 4)):
            x, y = self.pos[0] + self.r.randint(-2, 2) * 5, self.pos[1] + self.r.randint(1, 2) * 5
            body.append(self.xyz(x, y))
        body.append("M99")
        self.subs.append(body)
        self.emit(f"M98 P{prog}")
        self.emit("G80")
        self.pos[2] = 20 if ret == "G98" else 3
        self.emit(f"G0 {self.xyz(z=25)}")

    def g52_rotated_section(self) -> None:
        """G68 inside a G52 local system: the centre of rotation and the moves in local coordinates (Fanuc 0i-MF
        "Local coordinate system": commands after G52 are in the local system; "Coordinate system rotation":
        the centre is given in the current workpiece system; Haas "G52", "G68"), then G69 and G52 X0 Y0."""
        self.emit(f"G52 X{self.v(self.r.randint(-4, 4) * 5)} Y{self.v(self.r.randint(-4, 4) * 5)}")
        self.start()
        self.rotated_cut(self.v(self.pos[0] + self.r.randint(-2, 2) * 5), self.v(self.pos[1]))
        self.emit("G52 X0. Y0.")

    def rotated_cut(self, cx: str, cy: str) -> None:
        """G68 about (cx, cy) (as written) by a drawn angle, a line down, a line, an arc and the way up under it, then
        G69."""
        self.emit(f"G68 X{cx} Y{cy} R{self.r.choice((15, 30, 45, 90, -30))}.")
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        self.emit(f"G1 {self.xyz(self.pos[0] + 10, self.pos[1] + 5)}")
        self.emit(self.arc(self.r.choice(("G2", "G3"))))
        self.emit(f"G0 {self.xyz(z=10)}")
        self.emit("G69")

    def frames_section(self) -> None:
        """A G92 shift with a mirror and a rotation inside it (Fanuc 0i-MF "Programmable mirror image", "Coordinate
        system rotation": mirror, then rotation, nested, the centres in the G92 system; Haas "G92", "G101", "G68"):
        lines and an arc, the frames cancelled in reverse order, then the G92 shift taken back."""
        self.start()
        px, py = self.pos[0], self.pos[1]
        self.emit("G92 X0. Y0.")
        self.pos[0] = self.pos[1] = 0.0
        self.emit(f"G51.1 X{self.v(self.r.randint(-2, 2) * 5)}" if self.fanuc else "G101 X0.")
        self.rotated_cut(self.v(self.r.randint(-2, 2) * 5), self.v(self.r.randint(-2, 2) * 5))
        self.emit("G50.1 X0." if self.fanuc else "G100 X0.")
        self.emit(f"G92 X{self.v(self.pos[0] + px)} Y{self.v(self.pos[1] + py)}")

    def modal_info_section(self) -> None:
        """The modal information read into coordinates (Fanuc 0i-MD B-64304EN "System variables", "Modal
        information": ``#4001`` G00-G03, ``#4002`` the plane, ``#4003`` 90/91, ``#4006`` 20/21, ``#4014`` the work
        system, Fanuc only here; Haas "Macros", "#4001-#4021 last block group codes"): in G17 G90 after a G01."""
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        for k, code in enumerate(("4001", "4003", "4006", "4002")):
            self.emit(f"#{131 + k}=#{code}")
        x, y = self.pos[0], self.pos[1]
        inch = self.unit != 1.0
        self.emit(f"G1 X[{self.v(x, plain=False)}+#131*{self.v(5, plain=False)}] Y[{self.v(y, plain=False)}+[#132-90]*"
                  f"{self.v(3, plain=False)}+[#134-17]*{self.v(3, plain=False)}+[21-#133]*{self.v(2, plain=False)}]")
        self.pos[0], self.pos[1] = x + 5, y + (2 if inch else 0)
        if self.fanuc:
            self.emit("#135=#4014")
            self.emit("#136=0")
            self.emit("IF [#135 GE 54] THEN #136=1")
            self.emit(f"G1 X[{self.v(self.pos[0], plain=False)}+#136*{self.v(2, plain=False)}]")
            self.pos[0] += 2
        self.emit(f"G0 {self.xyz(z=10)}")

    def g28_shifted_section(self) -> None:
        """G28 through a point written in the local system (G52) in G90, and G30 in G91 (0i-MF "Reference
        position return": the intermediate point in the workpiece system)."""
        self.emit(f"G52 X{self.v(10)} Y{self.v(-5)}")
        self.start(20)
        self.emit(f"G28 {self.xyz(self.pos[0] + 5, self.pos[1], 30)}")
        self.emit("G52 X0. Y0.")
        if self.r.random() < 0.5:
            self.emit(f"G91 G30 Z{self.v(5)}")
            self.emit("G90")

    def depth_passes_section(self) -> None:
        """A contour subprogram stepping down in G91 and repeated (M98 P L / Fanuc P<count><program>)."""
        prog = 3000 + len(self.subs) * 10
        self.subs.append([f"O{prog} (PASS)", f"G91 G1 Z{self.v(-1)} {self.feed()}", f"X{self.v(10)}",
                          f"Y{self.v(10)}", f"X{self.v(-10)}", f"Y{self.v(-10)}", "G90", "M99"])
        self.start(1)
        n = self.r.randint(2, 4)
        self.emit(f"M98 P{n}{prog:04d}" if self.fanuc and self.r.random() < 0.5 else f"M98 P{prog} L{n}")
        self.emit(f"G90 G0 {self.xyz(z=10)}")

    def scaling_ijk_section(self) -> None:
        """Fanuc G51 I J K per-axis factors (0i-MF "Scaling": "I_J_K_ scaling magnification for X, Y, Z"), on
        straight moves only (an arc under unequal factors is not a circle); Haas scales all axes alike."""
        if not self.fanuc:
            return self.transform_section("scaling")
        self.start()
        i, j = self.r.choice((("1.5", "0.5"), ("2.", "-1."), ("-1.", "1.")))
        self.emit(f"G51 X{self.v(self.pos[0])} Y{self.v(self.pos[1])} I{i} J{j} K1.")
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        for _ in range(2):
            self.emit(f"G1 {self.xyz(self.pos[0] + self.r.randint(-3, 3) * 5, self.pos[1] + 5)}")
        self.emit(f"G0 {self.xyz(z=10)}")
        self.emit("G50")

    def block_delete_section(self) -> None:
        """``/`` block delete (off: the blocks run), also after the sequence number (``N45 /G1``: vcnc's reading,
        iso_flow), comments with odd characters, blocks with only N."""
        self.start()
        self.emit(f"/G1 {self.xyz(self.pos[0] + 5, self.pos[1])} {self.feed()} (SKIP; IF ON)",
                  skip_after_number=self.r.random() < 0.5)
        self.emit("(OP 2 - FACE / 5.0MM, \"FINISH\")")
        self.emit(f"G1 {self.xyz(self.pos[0], self.pos[1] + 5)} {self.feed()}")

    def corner_arc_section(self) -> None:
        """Fanuc ``,R`` between a line and an arc (0i-MF "Optional chamfering and corner R": also between a
        line and an arc)."""
        if not self.fanuc:
            return self.corner_words_section()
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        self.emit(f"G1 {self.xyz(self.pos[0] + 20, self.pos[1])} ,R{self.v(2)}")
        self.emit(f"G3 {self.xyz(self.pos[0] + 10, self.pos[1] - 10)} I{self.v(10)} J0.")  # turning 90 deg
        self.emit(f"G0 {self.xyz(z=10)}")

    def g10_tools_section(self) -> None:
        """Offsets set by the program, then used: ``G10 L10 P R`` tool length, ``L12`` radius (Haas: diameter),
        ``L11``/``L13`` their wear (Fanuc 0i-MF "Changing of tool offset value (programmable data input)",
        memory C; Haas "G10 Set Offsets": L10 length, L1/L11 length wear, L12 diameter, L13 diameter wear)."""
        t = self.r.randint(1, 6)
        self.emit(f"G90 G10 L10 P{t} R{self.v(self.r.choice((40, 55.5, 80)), plain=False)}")
        radius = self.r.choice((1.5, 2, 3))
        self.emit(f"G10 L12 P{t} R{self.v(radius if self.fanuc else 2 * radius, plain=False)}")
        if self.r.random() < 0.5:
            self.emit(f"G10 L{self.r.choice((11, 13))} P{t} R{self.v(-0.1, plain=False)}")
        self.tool = t
        self.emit(f"T{t} M06")
        self.emit(f"G90 G0 {self.xyz(0, 0)}")
        self.emit(f"G43 H{t} {self.xyz(z=50)}")
        self.comp_section(t)

    def length_motion_section(self) -> None:
        """A tool length offset changed under G91 as posts write it, the change travelled by the next incremental
        Z, ``G28`` or ``G53`` (FANUC B-63943EN-1/02 12.5.2, TOS = 0: compensation by an axis movement; Haas, as
        Fanuc): FreeCAD's ``G91 G0 G43 Z-.. H..``, ``G49`` then ``G91 G28 Z0.`` (Fusion's fanuc.cps tool end),
        ``G49`` then ``G53 G0 Z0.``, a ``G91 G43 H..`` block without Z before an X move and a Z one, ``G91 G49 Z0.``;
        the tool's offset set again by an absolute ``G43 H.. Z..`` after."""
        self.start(30)
        t = self.r.randint(1, 6)
        kind = self.r.choice(("freecad", "g49_g28", "g49_g53", "h_alone", "g49_z0"))
        if kind == "freecad":
            self.emit(f"G91 G0 G43 {self.xyz(z=self.pos[2] - self.r.choice((5, 10, 20)), inc=True)} H{t}")
            self.emit("G90")
            self.tool = t
            self.emit(f"G0 {self.xyz(z=40)}")
            return
        if kind == "h_alone":
            self.emit(f"G91 G43 H{t}")
            self.emit(f"G0 {self.xyz(self.pos[0] + self.r.randint(-4, 4) * 2.5, inc=True)}")
            self.emit(f"G0 {self.xyz(z=self.pos[2] - self.r.choice((5, 10)), inc=True)}")
            self.emit("G90")
            self.tool = t
            self.emit(f"G0 {self.xyz(z=40)}")
            return
        if kind == "g49_g28":
            self.emit("G49")
            up = self.r.choice((0, 0, 5))  # an intermediate point above: it travels the change too
            self.emit(f"G91 {self.r.choice(('G28', 'G28', 'G30'))} Z{self.v(up)}")
        elif kind == "g49_g53":
            self.emit("G49")
            self.emit(f"G53 G0 Z{_num(-self.r.choice((0, 10)) * self.unit)}")
        else:
            self.emit("G91 G49 Z0.")
        self.emit("G90")
        self.tool = self.tool or t
        self.emit(f"G43 H{self.tool} {self.xyz(z=50)}")

    def rigid_tap_section(self, *, peck: bool = False) -> None:
        """Tapping fed per revolution, the feed the thread's pitch: Fanuc ``M29 S..`` then ``G84 .. F<pitch>``
        under G95 (0i-B connection manual B-63833EN "Rigid tapping": "G99 ; M29 S1000 ; G84 Z-100. R-20. F1. ;",
        as Fusion's fanuc.cps writes it, ``P0``), Haas ``G84`` under G95 (haas.cps); ``G80``, ``G94`` after.
        With ``peck`` (Fanuc) a ``Q`` each cut: peck rigid tapping (16i-TA/TB A-78549E 3.4 "Peck rigid tapping
        cycle": "G84 X_ Y_ Z_ R_ P_ Q_ F_ K_"), on the machine :func:`_dialect` sets up for it."""
        self.start(20)
        q = f" Q{self.v(self.r.choice((2, 3, 4)))}" if peck else ""
        pitch = self.r.choice((0.8, 1.0, 1.25, 1.5)) * (0.04 if self.unit < 1 else 1)
        self.emit("G95")
        if self.fanuc:
            self.emit(f"M29 S{self.r.choice((300, 500, 800))}")
        ret = self.r.choice(("G98", "G99"))
        dwell = " P0" if self.fanuc and self.r.random() < 0.5 else ""
        if self.r.random() < 0.3:  # a row of holes in G91, repeated (Fanuc K, Haas L)
            count = self.r.randint(2, 3)
            self.emit(f"G91 {ret} G84 X{self.v(5)} Y0. Z{self.v(-13)} R{self.v(-17)}{dwell}{q} "
                      f"{'K' if self.fanuc else 'L'}{count} F{_num(pitch)}")
            self.emit("G90")
            self.pos[0] += 5 * count
        else:
            self.emit(f"{ret} G84 {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-10)} R{self.v(3)}{dwell}{q} "
                      f"F{_num(pitch)}")
            for _ in range(self.r.randint(0, 2)):
                self.emit(self.xyz(self.pos[0] + self.r.randint(-2, 2) * 5, self.pos[1] + 5))
        self.emit("G80")
        self.emit("G94")
        self.pos[2] = 20 if ret == "G98" else 3
        self.emit(f"G0 {self.xyz(z=25)} {self.feed()}")

    def haas_g73k_section(self) -> None:
        """Haas ``G73`` with ``Q`` (each peck) and ``K`` (back to R when the pecks since the last return total K),
        as haas.cps writes chip breaking with an accumulated depth (Haas mill operator's manual 96-8000 "G73");
        on Fanuc the plain cycles."""
        if self.fanuc:
            return self.cycles_section()
        self.start(20)
        q = self.r.choice((1.5, 2, 3))
        k = q * self.r.choice((2, 3)) + self.r.choice((0, 0.5))
        ret = self.r.choice(("G98", "G99"))
        if self.r.random() < 0.3:  # in G91 from the initial level, repeated by L
            count = self.r.randint(1, 3)
            self.emit(f"G91 {ret} G73 X{self.v(5)} Y{self.v(5)} Z{self.v(-self.r.choice((10, 14)))} R{self.v(-18)} "
                      f"Q{self.v(q)} K{self.v(k)}" + (f" L{count}" if count > 1 else "") + f" {self.feed()}")
            self.emit("G80 G90")
            self.pos[0] += 5 * count
            self.pos[1] += 5 * count
        else:
            self.emit(f"G90 {ret} G73 {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-self.r.choice((8, 12, 15)))} "
                      f"R{self.v(2)} Q{self.v(q)} K{self.v(k)} {self.feed()}")
            if self.r.random() < 0.5:
                self.emit(self.xyz(self.pos[0] + 5, self.pos[1]))
            self.emit("G80")
        self.pos[2] = 20 if ret == "G98" else 2
        self.emit(f"G0 {self.xyz(z=25)}")

    def m99_branch_section(self) -> None:
        """Haas ``M99 P<n>`` inside a subprogram branches to its block ``N<n>`` (Haas mill operator's manual
        96-8000, "Macros", "Conditional Expressions": "M99 ... branch unconditionally to any line in the current
        subroutine ... It does not return"): a forward branch past a block, then the subprogram's own ``M99``.
        Fanuc's ``M99 P`` returns to the caller's ``N<n>`` instead: there the plain subprogram."""
        if self.fanuc:
            return self.subprogram_section()
        prog = 3500 + len(self.subs) * 10
        label = 7000 + len(self.subs) * 10
        body = [f"G91 G1 X{self.v(5)} {self.feed()}", f"M99 P{label}", f"G1 Y{self.v(40)}",
                f"N{label} G1 Y{self.v(5)}", "G90", "M99"]
        self.start()
        count = self.r.randint(1, 2)
        repeat = f" L{count}" if count > 1 else ""
        if self.r.random() < 0.5:  # haas.cps's local subprogram after M30, called by M97
            self.subs.insert(0, [f"N{prog + 5000} (BRANCH)", *body])
            self.emit(f"M97 P{prog + 5000}{repeat}")
        else:
            self.subs.append([f"O{prog} (BRANCH)", *body])
            self.emit(f"M98 P{prog}{repeat}")

    def length_block_section(self) -> None:
        """A tool length change in a G00/G01 block without a Z word, which moves Z by the change in that block under
        TOS = 0 (FANUC B-63943EN-1/02 12.5.2: under TOS = 1 "if no move command is specified together with the
        G43, G44, or G49 command, the tool will not move along the axis"; the Allen-Bradley 8520 mill manual's
        "N2 G43 H01;" as a linear block): ``G0 G43 H.. X.. Y..`` after a tool change, ``G43 H..`` alone under the
        modal G00 or G01, ``G49 G0 X.. Y..``; then an absolute Z, and the spindle tool's offset again."""
        self.start(self.r.choice((30, 40)))
        t = self.r.randint(1, 6)
        kind = self.r.choice(("xy", "xy", "alone", "feed", "g49"))
        x, y = self.pos[0] + self.r.randint(-4, 4) * 5, self.pos[1] + self.r.randint(-4, 4) * 5
        if kind == "xy":
            self.emit(f"G0 G43 H{t} {self.xyz(x, y)}")
        elif kind == "alone":
            self.emit(f"G43 H{t}")
        elif kind == "feed":
            self.emit(f"G1 {self.xyz(x, y)} {self.feed()}")
            self.emit(f"G43 H{t}")
        else:
            self.emit(f"G49 G0 {self.xyz(x, y)}")
        self.emit(f"G0 {self.xyz(z=self.pos[2] + 5)}")
        self.emit(f"G43 H{self.tool or 1} {self.xyz(z=50)}")

    def length_reference_section(self) -> None:
        """Z at its reference (G28/G30, in G91 or through an intermediate point) or at a G53 machine coordinate
        cancels the length vector, G43 staying, and the next Z move restores it (0i-MB B-63844EN/02 14.1.2): a
        reference return between operations, then an incremental Z (which travels the vector back) or an
        absolute one; or the Fusion post's tool end ``G28 G91 Z0.`` / ``G90`` / ``G49``, which moves nothing."""
        self.start(20)
        to_z = self.r.choice(("G91 G28 Z0.", "G91 G28 Z0.", "G91 G30 Z0.", "g28_point", "G53"))
        if to_z == "g28_point":
            self.emit(f"G90 G28 {self.xyz(z=self.pos[2] + 5)}")
        elif to_z == "G53":
            self.emit(f"G90 G53 G0 Z{_num(-self.r.choice((0, 10)) * self.unit)}")
        else:
            self.emit(to_z)
        after = self.r.choice(("inc", "inc", "abs", "g49"))
        if after == "inc":
            self.emit(f"G91 G0 Z{self.v(-self.r.choice((5, 10, 20)))}")
            self.emit("G90")
        elif after == "g49":
            self.emit("G90")
            self.emit("G49")
            self.emit(f"G0 {self.xyz(self.pos[0] + 5, self.pos[1])}")
            self.emit(f"G43 H{self.tool or 1} {self.xyz(z=50)}")
        self.emit(f"G90 G0 {self.xyz(z=40)}")

    def length_cycle_section(self) -> None:
        """A tool length change within a canned cycle series, taken up at the next hole's positioning to R
        (FANUC 15i-MA B-63784EN, canned cycles: "When a tool length offset (G43, G44, or G49) is specified in the
        canned cycle, the offset is applied at the time of positioning to point R"): ``G43 H.. X..`` in a
        position block, in G90 or G91 (where R, measured from the initial level, moves by the change), G98 or
        G99; after ``G80`` an incremental Z, then the spindle tool's offset again."""
        code = self.r.choice(("G81", "G82", "G83", "G73", "G85"))
        ret = self.r.choice(("G98", "G99"))
        self.start(20)
        t = self.r.randint(1, 6)
        q = f" Q{self.v(2)}" if code in ("G73", "G83") else ""
        p = " P300" if code == "G82" else ""
        if self.r.random() < 0.4:
            self.emit(f"G91 {ret} {code} X{self.v(5)} Y0. Z{self.v(-5)} R{self.v(-3)}{q}{p} {self.feed()}")
            self.emit(f"G43 H{t} X{self.v(5)}")
            self.emit("G80")
        else:
            self.emit(f"G90 {ret} {code} {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-6)} R{self.v(3)}{q}{p} "
                      f"{self.feed()}")
            self.emit(f"G43 H{t} {self.xyz(self.pos[0] + 5, self.pos[1] + self.r.choice((0, 5)))}")
            if self.r.random() < 0.5:
                self.emit(self.xyz(self.pos[0], self.pos[1] + 5))
            self.emit("G80")
        if self.r.random() < 0.5:
            self.emit(f"G91 G0 Z{self.v(-1)}")
        self.emit(f"G90 G0 Z{self.v(25)}")
        self.emit(f"G43 H{self.tool or 1} {self.xyz(z=50)}")

    def rigid_tap_end_section(self) -> None:
        """Fanuc M29 rigid tapping and where it ends (0i-B connection manual B-63833EN "Rigid tapping": "M29 S1000 ;
        G84 Z-100. R-20. F1. ; ... G80 ;"; the S of the tap is cleared with it): ``M29 S..`` in a block of its own or
        with a rapid of Z, a dwell between it and the G84, two taps each with its own ``M29 S..``, or a drilling
        cycle after ``S.. M03`` ending the rigid mode without G80 (Haas and Fadal: plain tapping)."""
        if not self.fanuc:
            return self.rigid_tap_section()
        self.start(20)
        self.emit("G95")
        for k in range(self.r.randint(1, 2)):
            s, pitch = self.r.choice((300, 500, 800)), self.r.choice((0.8, 1.0, 1.25)) * (0.04 if self.unit < 1 else 1)
            how = self.r.choice(("alone", "alone", "rapid", "dwell"))
            if how == "rapid":
                self.emit(f"G0 {self.xyz(z=self.pos[2] - 5)} M29 S{s}")
            else:
                self.emit(f"M29 S{s}")
                if how == "dwell":
                    self.emit("G04 X0.5")
            self.emit(f"G98 G84 {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-10)} R{self.v(3)} F{_num(pitch)}")
            if self.r.random() < 0.4 and k == 0:  # a drill after the tap: another cycle ends the rigid mode
                self.emit(f"S{self.r.choice((1200, 3000))} M03")
                self.emit("G94")
                self.emit(f"G81 {self.xyz(self.pos[0] + 5, self.pos[1])} Z{self.v(-6)} R{self.v(3)} {self.feed()}")
                self.emit("G80")
                self.emit("M05")
                self.emit("G95")
            else:
                self.emit("G80")
        self.emit("G94")
        self.emit(f"S{self.r.choice((1200, 3000))} M03")
        self.emit(f"G90 G0 {self.xyz(z=25)} {self.feed()}")

    def arc3d_section(self) -> None:
        """Fanuc G02.4 / G03.4 three-dimensional arcs, as Fusion's fanuc.cps writes them with "Allow 3D arcs"
        (``G02.4 X Y Z`` the arc's middle, then ``X Y Z`` its end; Mitsubishi M700V programming manual 6.14, which
        describes the same command): one to three arcs on circles in tilted planes, in G90 or G91 (the
        intermediate point from the start, the end from the intermediate point). Haas and Fadal: plain arcs."""
        if not self.fanuc:
            return self.arcs_section()
        self.start(10)
        self.emit(f"G1 {self.xyz(z=0)} {self.feed()}")
        inc = self.r.random() < 0.3
        if inc:
            self.emit("G91")
        for _ in range(self.r.randint(1, 3)):
            radius = self.r.choice((5, 10, 15))
            tilt, turn = math.radians(self.r.choice((15, 30, 45, 60, 90))), math.radians(self.r.randint(0, 11) * 30)
            u = (math.cos(turn), math.sin(turn), 0.0)
            v = (-math.sin(turn) * math.cos(tilt), math.cos(turn) * math.cos(tilt), math.sin(tilt))
            centre = [self.pos[k] - radius * u[k] for k in range(3)]
            sweep = math.radians(self.r.choice((60, 90, 135, 180, 270)))
            points = []
            for a in (sweep / 2, sweep):
                points.append([round(centre[k] + radius * (u[k] * math.cos(a) + v[k] * math.sin(a)), 3)
                               for k in range(3)])
            code = self.r.choice(("G02.4", "G03.4"))
            self.emit(f"{code} {self.xyz(*points[0], inc=inc)}")
            self.emit(self.xyz(*points[1], inc=inc))
        if inc:
            self.emit("G90")
        self.emit(f"G0 {self.xyz(z=self.pos[2] + 20)}")
        self.emit(f"G0 {self.xyz(z=40)}")

    def offset_vars_section(self) -> None:
        """Work offsets written through the system variables (Fanuc 0i-MD B-64304EN "System variables": ``#5221``-
        ``#5223`` G54 X Y Z, 20 apart up to G59, ``#7001``.. G54.1 P1, 20 apart, ``#5201``.. the external offset,
        "read/write"; Haas "Macros": ``#5221``.. G54-G59, ``#7001``.. G110 = G154 P1, ``#5201``.. G52), a value
        read back, the system selected (or written while in force), moves in it; the external offset back to 0.
        Metric programs only: the variables hold the machine's unit (mm here), which G20 does not change."""
        if self.unit != 1.0:
            self.lines_section()
            return
        extended = self.r.random() < 0.3
        k = self.r.randint(1, 20 if extended else 6)
        base = 7001 + 20 * (k - 1) if extended else 5221 + 20 * (k - 1)
        code = self.extended_code(k) if extended else f"G5{3 + k}"
        before = self.r.random() < 0.7
        if not before:
            self.emit(code)
        self.emit(f"#{base}={_num(-300.0 + 5 * self.r.randint(-10, 10))}")
        self.emit(f"#{base + 1}=#{base}+{_num(5.0 * self.r.randint(0, 20))}")
        self.emit(f"#{base + 2}={_num(-400.0 + 5 * self.r.randint(-4, 4))}")
        external = self.r.random() < 0.3
        if external:
            for i in range(3):
                self.emit(f"#{5201 + i}={_num(2.5 * self.r.randint(-4, 4))}")
        if before:
            self.emit(code)
        self.lines_section()
        if external:
            self.emit("#5201=0.")
            self.emit("#5202=0.")
            self.emit("#5203=0.")

    def haas_then_section(self) -> None:
        """Haas ``IF [..] THEN <NC words>`` (Haas mill operator's manual, "Macros", "Conditional Execution (IF
        THEN)": "IF [#1 NE #0] THEN G1 X#24 Y#26 F#9"): two such moves of which the condition lets one run; Fanuc
        and Fadal (THEN only before an assignment) plain lines."""
        if self.dialect != "haas":
            self.lines_section()
            return
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        which = self.r.randint(1, 2)
        self.emit(f"#106={which}")
        for k in (1, 2):
            x, y = self.pos[0] + self.r.randint(-3, 3) * 5, self.pos[1] + self.r.randint(1, 3) * 5
            if k == which:
                words = self.xyz(x, y)
            else:
                words = f"X{self.v(x)} Y{self.v(y)}"
            op = self.r.choice(("EQ", "NE"))
            cond = f"#106 EQ {k}" if op == "EQ" else f"#106 NE {3 - k}"
            self.emit(f"IF [{cond}] THEN G1 {words}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def g66_section(self) -> None:
        """Fanuc ``G66 P<program> Z F [L]`` (0i-MD B-64304EN "Modal call: call after the move command (G66)"):
        after each positioning the macro drills by its arguments, incrementally (``G91 G1 Z-#26 F#9``, back
        ``G0 Z#26``), until ``G67``; Haas and Fadal (no G66) plain lines."""
        if not self.fanuc:
            self.lines_section()
            return
        prog = 9500 + len(self.subs)
        self.subs.append([f"O{prog} (MODAL DRILL)", "G91 G1 Z-#26 F#9", "G0 Z#26", "G90", "M99"])
        self.start()
        count = f" L{self.r.randint(2, 3)}" if self.r.random() < 0.3 else ""
        self.emit(f"G66 P{prog} Z{self.v(self.r.randint(4, 12), plain=False)} "
                  f"F{_num(100 * (0.04 if self.unit < 1 else 1))}{count}")
        for _ in range(self.r.randint(1, 4)):
            x, y = self.pos[0] + self.r.randint(-3, 3) * 5, self.pos[1] + self.r.randint(1, 3) * 5
            self.emit(f"G0 {self.xyz(x, y)}" if self.r.random() < 0.7 else self.xyz(x, y))
        self.emit("G67")
        self.emit(f"G0 {self.xyz(z=15)}")

    def inverse_time_section(self) -> None:
        """``G93`` inverse time feed (Fanuc 0i-MF "Inverse time feed (G93)": F the reciprocal of the block's time
        [1/min], on every G01/G02/G03 block; Haas "G93 Inverse Time Feed Mode") on lines and arcs, ``G94`` and a
        feed back."""
        self.start()
        self.emit(f"G1 {self.xyz(z=-1)} {self.feed()}")
        self.emit("G93")
        for _ in range(self.r.randint(1, 4)):
            if self.r.random() < 0.5:
                text = self.arc(self.r.choice(("G2", "G3")))
            else:
                text = f"G1 {self.xyz(self.pos[0] + self.r.randint(-3, 3) * 5, self.pos[1] + 5)}"
            self.emit(f"{text} F{self.r.randint(1, 60)}.")
        self.emit(f"G94 G1 {self.xyz(self.pos[0] + 5, self.pos[1])} {self.feed()}")
        self.emit(f"G0 {self.xyz(z=10)}")

    def tool_change(self) -> None:
        self.tool = self.r.randint(1, 6)
        self.emit("G91 G28 Z0.")
        self.emit("G90 G49")
        self.emit(f"T{self.tool} M06")
        x, y = self.r.randint(-8, 8) * 5, self.r.randint(-8, 8) * 5
        self.emit(f"G0 G90 G5{self.r.randint(4, 9)} {self.xyz(x, y)} S{self.r.choice((1200, 3000, 8000))} M03")
        self.emit(f"G43 H{self.tool} {self.xyz(z=50)} M08")


def generate(seed: int, dialect: str = "fanuc") -> str:
    """A valid ``fanuc``, ``haas`` or ``fadal`` (:data:`FADAL_FEATURES`) mill program, the same for the same
    seed."""
    r = random.Random(f"{dialect}:{seed}")
    inch = r.random() < 0.25
    chosen = features(seed, dialect)
    g = _Gen(r, dialect, 0.05 if inch else 1.0, dpi0=_increments(seed, dialect), five=five_axis(seed, dialect))
    g.lines.append("%")
    # the main program O4000-O8999, apart from the subprograms (O1000-O3999, O9010-): a call finds its own
    g.lines.append(f"O{4000 + seed % 5000:04d} (FUZZ {seed})")
    g.emit(f"{'G20' if inch else 'G21'} G17 G40 G49 G80 G90")
    g.tool_change()
    table = {"lines": g.lines_section, "arcs": g.arcs_section, "helix": g.helix_section,
             "planes": g.planes_section, "comp": g.comp_section, "cycles": g.cycles_section,
             "cycles_g91": lambda: g.cycles_section(True), "subprogram": g.subprogram_section,
             "macro": g.macro_section, "g65": g.g65_section, "rotation": lambda: g.transform_section("rotation"),
             "scaling": lambda: g.transform_section("scaling"), "mirror": lambda: g.transform_section("mirror"),
             "g52": g.g52_section, "g92": g.g92_section, "g10": g.g10_section,
             "extended_offset": g.extended_section, "g28_g53": g.g28_g53_section, "dwell": g.dwell_section,
             "tool_change": g.tool_change, "g91_arcs": g.g91_arcs_section, "comp_rotated": g.comp_rotated_section,
             "cycles_rotated": g.cycles_rotated_section, "boring": g.boring_section,
             "corner_words": g.corner_words_section, "nested_sub": g.nested_sub_section,
             "tool_length": g.tool_length_section, "haas_pattern": g.haas_pattern_section,
             "haas_pocket": g.haas_pocket_section, "haas_peck": g.haas_peck_section, "m97": g.m97_section,
             "polar": g.polar_section, "comp_arcs": g.comp_arcs_section, "macro_system": g.macro_system_section,
             "cycle_modal": g.cycle_modal_section, "g28_shifted": g.g28_shifted_section,
             "depth_passes": g.depth_passes_section, "scaling_ijk": g.scaling_ijk_section,
             "block_delete": g.block_delete_section, "corner_arc": g.corner_arc_section,
             "g10_tools": g.g10_tools_section, "cycle_sub": g.cycle_sub_section,
             "g52_rotated": g.g52_rotated_section, "external": g.external_section, "tcp": g.tcp_section,
             "length_motion": g.length_motion_section, "rigid_tap": g.rigid_tap_section,
             "haas_g73k": g.haas_g73k_section, "m99_branch": g.m99_branch_section,
             "length_block": g.length_block_section, "length_reference": g.length_reference_section,
             "length_cycle": g.length_cycle_section, "rigid_tap_end": g.rigid_tap_end_section,
             "arc3d": g.arc3d_section, "offset_vars": g.offset_vars_section, "haas_then": g.haas_then_section,
             "peck_tap": lambda: g.rigid_tap_section(peck=g.fanuc), "g66": g.g66_section,
             "inverse_time": g.inverse_time_section, "frames": g.frames_section,
             "modal_info": g.modal_info_section}
    for name in chosen:
        table[name]()
    g.emit("G91 G28 Z0.")
    g.emit("G90 G49 M05")
    g.emit("M30")
    for body in g.subs:
        g.lines.extend(body)
    g.lines.append("%")
    return "\n".join(g.lines) + "\n"


#: The sections of a ``fadal`` program: Fadal reads Haas's cycle words (Fusion's fadal.cps writes ``G83 .. I J K``
#: and ``G73 .. Q K`` as its Haas post), not Haas's extended offsets, patterns, pockets, macros or M97.
#: ``length_cycle`` (a change to a longer tool within a G99 series: the next hole starts below its R) is read by
#: Fanuc's rule in reader and reference (over at the current height, then up to R; cycles38).
FADAL_FEATURES = ("lines", "arcs", "helix", "planes", "comp", "cycles", "cycles_g91", "subprogram", "rotation",
                  "g52", "g92", "g28_g53", "dwell", "g91_arcs", "tool_length", "haas_peck", "haas_g73k",
                  "length_motion", "depth_passes", "length_block", "length_reference", "length_cycle")


def features(seed: int, dialect: str = "fanuc") -> list[str]:
    """The sections :func:`generate` chose for ``seed`` (for counting programs per feature)."""
    r = random.Random(f"{dialect}:{seed}:features")
    return [r.choice(FADAL_FEATURES if dialect == "fadal" else FEATURES) for _ in range(r.randint(3, 7))]
