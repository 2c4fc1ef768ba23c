"""Random, valid LinuxCNC programs for the differential test against ``rs274`` (``benchmarks/linuxcnc_diff.py
--generate N --seed S``).

Real programs exercise the common paths only; these mix the features the way real programs do, in an order and
with values no CAM post writes. A program is a sequence of *chunks*, one per feature group drawn from
:data:`FEATURES`, each starting from a known point: a ``G90`` rapid to a point of the current work frame (so that
the chunk knows where it is whatever the chunks before left: units, G91, offsets, the tool), then its moves in
the distance mode it draws. Chunks leave their modal state (units, offsets, tool, distance mode, feed mode) for
the next one, which is where readers go wrong; they cancel what would make the next chunk invalid (cutter
compensation, a canned cycle, inverse-time feed).

Each generated value is chosen to make a program LinuxCNC runs (g-code.adoc, m-code.adoc, o-code.adoc of
LinuxCNC 2.9): arc end points on the circle, R at least half the chord, canned-cycle R above Z, cutter
compensation entries longer than the tool radius, subroutines defined before their calls. A program rs274 still
refuses is reported by the differential test as such ("both refuse" or "vcnc only"), not hidden.

The programs keep clear of what LinuxCNC's standalone ``rs274`` does otherwise than LinuxCNC (the differential
test's docstring names them): a G49 before a change of units while a tool length offset is in force, no G43
without H and no G41/G42 without D after M61, no move without a Z word after M6 (each chunk starts with a rapid in
X Y Z). Where LinuxCNC's interpreter does otherwise than its documentation and vcnc follows the documentation
with a note (G84 in G18/G19, a do loop after a break out of a while loop, a G5 without I J after G5.1), the
programs avoid it too.

The same seed gives the same program (``random.Random(seed)``); ``features`` restricts the chunks to some groups.
"""

from __future__ import annotations

import math
import random

INCH = 25.4  # [mm/inch]


class _Writer:
    """A program being written: its lines, the units in force and the position in the work frame [mm]."""

    def __init__(self, rng: random.Random):
        self.rng = rng
        self.lines: list[str] = []
        self.inch = False
        self.incremental = False
        self.pos = [0.0, 0.0, 0.0]
        self.inverse_time = False
        self.tool_offset = False
        self.m61 = False
        self.labels = 100

    def num(self, mm: float) -> str:
        """A length [mm] as a word value in the units in force (4 decimals in inch, 3 in mm)."""
        v = mm / INCH if self.inch else mm
        s = f"{v:.4f}" if self.inch else f"{v:.3f}"
        s = s.rstrip("0").rstrip(".") if "." in s else s
        return "0" if s in ("-0", "") else s

    def emit(self, text: str) -> None:
        self.lines.append(text)

    def units(self) -> None:
        """Sometimes switch units (G20/G21) at a chunk's start; with a tool length offset in force, G49 first.

        LinuxCNC reads the offset back in the new units after G20 / G21 (interp_convert.cc
        ``convert_length_units``: ``GET_EXTERNAL_TOOL_LENGTH_ZOFFSET``; emccanon.cc ``TO_PROG_LEN``), rs274's
        standalone canon returns the number as it was set (saicanon.cc), so that rs274 takes a length set in mm
        as inch (or back) at the next G43.2, G53 or change of the offset in G91."""
        if self.rng.random() < 0.35:
            if self.tool_offset:
                self.emit("G49")
                self.tool_offset = False
            self.inch = not self.inch
            self.emit("G20" if self.inch else "G21")

    def start(self, x: float, y: float, z: float, *, distance: str | None = None, units: bool = True) -> None:
        """A G90 rapid to (x, y, z) of the work frame [mm], then the chunk's distance mode; before it, with
        ``units``, maybe a change of units."""
        if units:
            self.units()
        self.emit(f"G90 G0 X{self.num(x)} Y{self.num(y)} Z{self.num(z)}")
        self.pos = [x, y, z]
        self.incremental = (distance or self.rng.choice(["G90", "G91"])) == "G91"
        self.emit("G91" if self.incremental else "G90")

    def axes(self, target: list[float], names: str = "XYZ") -> str:
        """Axis words to ``target`` [mm] (absolute or incremental as the chunk runs); unchanged axes left out
        unless all are."""
        words = []
        for k, name in enumerate("XYZ"):
            if name not in names:
                continue
            value = target[k] - self.pos[k] if self.incremental else target[k]
            if abs(target[k] - self.pos[k]) > 1e-9 or self.rng.random() < 0.2:
                words.append(f"{name}{self.num(value)}")
        self.pos = list(target)
        return " ".join(words)

    def feed(self) -> str:
        return f"F{self.num(self.rng.choice([100.0, 250.0, 600.0, 1200.0]))}"

    def coord(self, lo: float = -40.0, hi: float = 40.0) -> float:
        """A coordinate [mm] on the grid the units in force print exactly."""
        v = self.rng.uniform(lo, hi)
        return round(v / INCH, 4) * INCH if self.inch else round(v, 3)


def _arc(w: _Writer, plane: int, *, allow_r: bool = True, helix: bool = True) -> None:
    """One arc in plane G17 (2), G18 (1) or G19 (0) from the current point: by I J K (incremental or, under G90.1,
    absolute centre) or by R (negative for more than half a circle), sometimes a full circle, P turns, a helix."""
    rng = w.rng
    p, q = {2: (0, 1), 1: (2, 0), 0: (1, 2)}[plane]
    start = list(w.pos)
    radius = rng.uniform(2.0, 15.0)
    a0, sweep = rng.uniform(0, 2 * math.pi), rng.uniform(0.2, 2 * math.pi - 0.2)
    full = rng.random() < 0.15
    centre = [start[p] - radius * math.cos(a0), start[q] - radius * math.sin(a0)]
    centre = [w.coord(c, c) for c in centre]
    radius = math.hypot(start[p] - centre[0], start[q] - centre[1])
    a0 = math.atan2(start[q] - centre[1], start[p] - centre[0])
    ccw = rng.random() < 0.5
    a1 = a0 + (sweep if ccw else -sweep)
    end = list(start)
    if not full:
        end[p], end[q] = (w.coord(centre[0] + radius * math.cos(a1), centre[0] + radius * math.cos(a1)),
                          w.coord(centre[1] + radius * math.sin(a1), centre[1] + radius * math.sin(a1)))
    if helix and rng.random() < 0.3:
        end[plane] = start[plane] + w.coord(-5.0, 5.0)
    code = "G3" if ccw else "G2"
    by_r = allow_r and not full and rng.random() < 0.4
    words = w.axes(end)
    if by_r:
        digit = 0.0001 * INCH if w.inch else 0.001  # R rounded up: at least half the chord as printed
        r = (radius + digit) * (1 if sweep <= math.pi else -1)
        w.emit(f"{code} {words} R{w.num(r)}{' ' + w.feed() if w.inverse_time else ''}")
        return
    absolute = rng.random() < 0.3
    letters = {0: "I", 1: "J", 2: "K"}
    offs = []
    for axis, c in ((p, centre[0]), (q, centre[1])):
        v = c if absolute else c - start[axis]
        offs.append(f"{letters[axis]}{w.num(v)}")
    turns = f" P{rng.randint(2, 3)}" if rng.random() < 0.15 else ""
    if absolute:
        w.emit("G90.1")
    w.emit(f"{code} {words} {' '.join(offs)}{turns}{' ' + w.feed() if w.inverse_time else ''}")
    if absolute:
        w.emit("G91.1")


def chunk_arcs(w: _Writer) -> None:
    """Arcs in the three planes by I J K and by R, full circles, P turns, helices, between straight feeds."""
    w.start(w.coord(), w.coord(), w.coord(0, 20))
    w.emit(f"G1 {w.feed()}")
    for _ in range(w.rng.randint(2, 6)):
        plane = w.rng.choice([2, 2, 2, 1, 0])
        w.emit({2: "G17", 1: "G18", 0: "G19"}[plane])
        _arc(w, plane)
        if w.rng.random() < 0.5:
            target = [w.pos[0] + w.coord(-10, 10), w.pos[1] + w.coord(-10, 10), w.pos[2]]
            w.emit(f"G1 {w.axes(target) or 'X' + w.num(target[0] - (w.pos[0] if w.incremental else 0))}")
    w.emit("G17 G90")


def _rotary_words(rng: random.Random) -> str:
    """For about a third of the offsets, A B C words [deg] (one to three of them) after the linear ones, with a
    leading space; else nothing. g-code.adoc "G10 L2", "G10 L20", "G52", "G92": the axis words are any of
    X Y Z A B C U V W, rotary axes in degrees in either length unit."""
    if rng.random() >= 0.35:
        return ""
    return "".join(f" {a}{rng.randint(-90, 90)}" for a in sorted(rng.sample("ABC", rng.randint(1, 3))))


def chunk_offsets(w: _Writer) -> None:
    """Work offsets and their changes: G10 L2 (with R rotation) / L20, G54-G59.3, G52, G92 and its cancels, some
    with A B C words (:func:`_rotary_words`), then moves with and without the rotary axes; a G92.1-G92.3 with X Y
    words after a feed move (the cancel, then the modal motion to them: rs274 and vcnc since session 37)."""
    rng = w.rng
    w.units()
    systems = ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"]
    for _ in range(rng.randint(1, 3)):
        kind = rng.choice(["L2", "L20", "G5x", "G52", "G92", "G92x"])
        if kind == "L2":
            rot = f" R{rng.choice([0, 15, 30, 90, -45, 12.5])}" if rng.random() < 0.4 else ""
            w.emit(f"G10 L2 P{rng.randint(0, 9)} X{w.num(w.coord())} Y{w.num(w.coord())} Z{w.num(w.coord(-10, 10))}"
                   f"{_rotary_words(rng)}{rot}")
        elif kind == "L20":
            w.emit(f"G10 L20 P{rng.randint(0, 9)} X{w.num(w.coord())} Y{w.num(w.coord())}{_rotary_words(rng)}")
        elif kind == "G5x":
            w.emit(rng.choice(systems))
        elif kind == "G52":
            w.emit(f"G52 X{w.num(w.coord(-10, 10))} Y{w.num(w.coord(-10, 10))}{_rotary_words(rng)}"
                   if rng.random() < 0.7 else "G52 X0 Y0 Z0")
        elif kind == "G92":
            w.emit(f"G92 X{w.num(w.coord())} Y{w.num(w.coord())}{_rotary_words(rng)}")
        else:
            w.emit(rng.choice(["G92.1", "G92.2", "G92.3"]))
        w.start(w.coord(), w.coord(), w.coord(0, 20))
        w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.pos[2]])} {w.feed()}")
        if rng.random() < 0.2:  # a G92 cancel with axis words: the modal G1 moves to them in the new frame, in
            w.incremental = False  # G90 (the current point's coordinates change with the frame)
            w.emit(f"G90 {rng.choice(['G92.1', 'G92.2', 'G92.3'])} {w.axes([w.coord(), w.coord(), w.pos[2]], 'XY')}")
        if rng.random() < 0.3:
            words = " ".join(f"{a}{rng.randint(-120, 120)}" for a in rng.sample("ABC", rng.randint(1, 3)))
            w.emit(f"G{rng.choice([0, 1])} {words} {w.feed()}")
        if rng.random() < 0.4:
            w.emit("G17")
            _arc(w, 2)
    w.emit("G90")


def chunk_tools(w: _Writer) -> None:
    """Tool changes (T M6, M61) and tool length offsets (G43 H, G43 alone, G43.1, G43.2 H, G49).

    No G43 without H after M61: LinuxCNC's task copies the new tool into the spindle's entry of the tool table
    (task/taskclass.cc ``emcToolSetNumber``: ``load_tool``), which G43 without H reads (interp_convert.cc
    ``convert_tool_length_offset``: index 0), but rs274's standalone canon does not (saicanon.cc
    ``CHANGE_TOOL_NUMBER`` sets the slot only), so rs274 applies the tool before M61; vcnc does as LinuxCNC.
    The same holds for G41/G42 without D (the tool's own diameter), :func:`chunk_compensation`."""
    rng = w.rng
    w.units()
    tool = rng.randint(1, 30)
    w.m61 = rng.random() < 0.4
    w.emit(f"M61 Q{tool}" if w.m61 else f"T{tool} M6")
    w.start(w.coord(), w.coord(), w.coord(5, 30), units=False)
    w.tool_offset = True
    for _ in range(rng.randint(1, 3)):
        offset = rng.choice([f"G43 H{rng.randint(1, 30)}", f"G43.1 Z{w.num(w.coord(-5, 5))}", "G49",
                             f"G43.2 H{rng.randint(1, 30)}", *([] if w.m61 else ["G43"])])
        target = [w.coord(), w.coord(), w.coord(0, 30)]
        # G43.2 H takes no axis words, G43.1's Z is the offset: a move only with G43 H, G43, G49
        with_move = rng.random() < 0.5 and not offset.startswith(("G43.1", "G43.2"))
        w.emit(f"{offset} G0 {w.axes(target)}" if with_move else offset)
        if not with_move and rng.random() < 0.7:
            w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.coord(0, 30)])} {w.feed()}")
    w.emit("G90")


def chunk_home(w: _Writer) -> None:
    """G28 / G30 with and without axis words (absolute and incremental), G28.1 / G30.1 (also with axis words, which
    the modal motion moves to after the position is stored: rs274ngc interp_check.cc ``enhance_block`` lets only
    G10, G28, G30, G52 and G92 of the group 0 codes use axis words), G53 moves."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 20))
    for _ in range(rng.randint(1, 3)):
        kind = rng.choice(["G28", "G30", "G28.1", "G30.1", "G53"])
        if kind in ("G28.1", "G30.1"):
            w.emit(f"G0 G90 X{w.num(w.coord())} Y{w.num(w.coord())} Z{w.num(w.coord(0, 20))}")
            w.incremental = False
            if rng.random() < 0.4:  # SheetCAM's Mach3 plasma posts: "G28.1 Z3.00", the axis words the G0's
                w.emit(f"{kind} {w.axes([w.pos[0], w.pos[1], w.coord(0, 20)], rng.choice(['Z', 'Z', 'XY']))}")
            else:
                w.emit(kind)
            continue
        if kind == "G53":
            w.emit(f"G90 G53 G{rng.choice([0, 1])} X{w.num(w.coord())} Z{w.num(w.coord(-10, 30))}"
                   f"{' ' + w.feed() if not w.inverse_time else ''}")
            w.incremental = False
            continue
        words = rng.choice(["", "Z", "XY", "XYZ"])
        if words:
            mode = rng.choice(["G90", "G91"])
            vals = " ".join(f"{a}{w.num(w.coord(-5, 5) if mode == 'G91' else w.coord())}" for a in words)
            w.emit(f"{mode} {kind} {vals}")
        else:
            w.emit(kind)
    w.emit("G90")


def _contour(w: _Writer) -> list[tuple[str, list[float], float]]:
    """A closed contour of straight lines and arcs (``("line", end, 0)`` or ``("G2"/"G3", end, R)``) around a
    box, with convex and concave corners; arcs by R larger than any tool radius of the generated table."""
    rng = w.rng
    x0, y0 = w.coord(-30, 0), w.coord(-30, 0)
    wd, ht = rng.uniform(15, 40), rng.uniform(15, 40)
    pts = [[x0, y0], [x0 + wd, y0], [x0 + wd, y0 + ht], [x0, y0 + ht]]
    pts = [[w.coord(p[0], p[0]), w.coord(p[1], p[1])] for p in pts]
    out = []
    for k in range(1, 5):
        a, b = pts[k - 1], pts[k % 4]
        chord = math.hypot(b[0] - a[0], b[1] - a[1])
        if rng.random() < 0.35:
            r = chord * rng.uniform(0.55, 2.0)
            out.append((rng.choice(["G2", "G3"]), [b[0], b[1], w.pos[2]], r))
        else:
            if rng.random() < 0.3:  # a notch: a concave corner on the way
                mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
                nx, ny = (b[1] - a[1]) / chord, -(b[0] - a[0]) / chord
                depth = rng.uniform(-4, 4)
                out.append(("line", [w.coord(mid[0] + depth * nx, mid[0] + depth * nx),
                                     w.coord(mid[1] + depth * ny, mid[1] + depth * ny), w.pos[2]], 0.0))
            out.append(("line", [b[0], b[1], w.pos[2]], 0.0))
    return [("start", [pts[0][0], pts[0][1], w.pos[2]], 0.0), *out]


def chunk_compensation(w: _Writer) -> None:
    """Cutter radius compensation: G41/G42 with D or the tool's own, G41.1/G42.1 D (L), an entry move, a closed
    contour of lines and arcs (some of them helical), G40 and an exit move."""
    rng = w.rng
    w.units()
    if rng.random() < 0.5:
        w.emit(f"T{rng.randint(1, 40)} M6")
        w.m61 = False
    w.emit("G17 G90 G40")
    w.incremental = False
    w.pos = [w.coord(-80, -60), w.coord(-80, -60), w.coord(0, 5)]
    w.emit(f"G0 X{w.num(w.pos[0])} Y{w.num(w.pos[1])} Z{w.num(w.pos[2])}")
    w.emit(f"G1 {w.feed()}")
    side = rng.choice(["G41", "G42"])
    how = rng.choice([*([] if w.m61 else [""]), f" D{rng.randint(1, 40)}", f".1 D{w.num(rng.uniform(0.5, 4.0))}"])
    w.emit(f"{side}{how}")
    contour = _contour(w)
    for kind, end, r in contour:
        end = [end[0], end[1], w.pos[2]]  # at the Z the helices before left
        if kind in ("start", "line"):
            w.emit(f"G1 {w.axes(end, 'XY')}")
        elif rng.random() < 0.3:  # a helix: the compensation offsets its XY projection (g-code.adoc "G41, G42")
            z = w.pos[2] - rng.choice([0.5, 1.0, 2.0])
            z = w.coord(z, z)  # on the grid of the units in force
            w.emit(f"{kind} {w.axes([end[0], end[1], z], 'XY')} Z{w.num(z)} R{w.num(r)}")
        else:
            w.emit(f"{kind} {w.axes(end, 'XY')} R{w.num(r)}")
    w.emit("G40")
    w.emit(f"G0 {w.axes([w.coord(-80, -60), w.coord(-80, -60), w.pos[2]], 'XY')}")


def chunk_cycles(w: _Writer) -> None:
    """Canned cycles G73, G81-G86, G89 in G17, G18 or G19 (drilling along Z, Y or X) with G98/G99, R above and
    below the start, L repeats in G91, then G80.

    Not G87 / G88: LinuxCNC's G-code reference lists them as "not yet implemented" (g-code.adoc, table of G
    codes), though rs274 runs them; vcnc refuses them. G84 in G17 only: LinuxCNC feeds a G18/G19 G84 to the
    hole's coordinates in another order (interp_cycles.cc ``convert_cycle_g74_g84``), vcnc taps as documented
    and notes it."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(5, 20), distance="G90")
    plane = rng.choice(["G17", "G17", "G18", "G19"])
    first, second, drill = {"G17": "XYZ", "G18": "ZXY", "G19": "YZX"}[plane]
    w.emit(f"{plane} M3 S1000")
    code = rng.choice(["G73", "G81", "G82", "G83", "G85", "G86", "G89", *(["G84"] if plane == "G17" else [])])
    retract = rng.choice(["G98", "G99"])
    incremental = rng.random() < 0.4
    z0 = w.pos["XYZ".index(drill)]
    r_level = z0 + rng.uniform(-4, 4)
    depth = rng.uniform(2, 10)
    extra = ""
    if code in ("G73", "G83"):
        extra += f" Q{w.num(rng.uniform(0.5, 3))}"
    if code in ("G82", "G89", "G86"):  # LinuxCNC needs P on the first block of these (interp_cycles.cc)
        extra += f" P{rng.choice([0.1, 0.5, 1])}"
    feed = w.feed()
    if incremental:
        w.emit("G91")
        repeats = f" L{rng.randint(2, 4)}" if rng.random() < 0.6 else ""
        w.emit(f"{retract} {code} {first}{w.num(w.coord(-8, 8))} {second}{w.num(w.coord(-8, 8))} "
               f"R{w.num(r_level - z0)} {drill}{w.num(-depth)}{extra}{repeats} {feed}")
    else:
        w.emit(f"{retract} {code} {first}{w.num(w.coord())} {second}{w.num(w.coord())} R{w.num(r_level)} "
               f"{drill}{w.num(r_level - depth)}{extra} {feed}")
    for _ in range(rng.randint(0, 3)):
        words = f"{first}{w.num(w.coord(-8, 8) if incremental else w.coord())}"
        if rng.random() < 0.4:
            words += f" {second}{w.num(w.coord(-8, 8) if incremental else w.coord())}"
        w.emit(words)
    w.emit("G80 G90 G17")


def chunk_tapping(w: _Writer) -> None:
    """G33.1 rigid tapping at the current point or a new X Y."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(2, 10), distance="G90")
    w.emit(f"M3 S{rng.choice([300, 500, 800])}")
    xy = f"X{w.num(w.pos[0])} Y{w.num(w.pos[1])} " if rng.random() < 0.5 else ""
    w.emit(f"G33.1 {xy}Z{w.num(w.pos[2] - rng.uniform(3, 10))} K{w.num(rng.choice([0.5, 1.0, 1.25]))}")


def chunk_splines(w: _Writer) -> None:
    """G5 cubic and G5.1 quadratic splines in G17; G5 without I J only right after a G5 (g-code.adoc G5: "For the
    first G5 command in a series of G5 commands, I and J must both be specified", which vcnc enforces and rs274
    does not: it takes the last G5's -P -Q, interp_convert.cc ``convert_spline``)."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10))
    w.emit(f"G17 G1 {w.feed()}")
    after_g5 = False
    for _ in range(rng.randint(1, 3)):
        end = [w.pos[0] + w.coord(-15, 15), w.pos[1] + w.coord(-15, 15), w.pos[2]]
        if rng.random() < 0.5:
            ij = f"I{w.num(w.coord(-5, 5))} J{w.num(w.coord(-5, 5))} " if not after_g5 or rng.random() < 0.5 else ""
            after_g5 = True
            w.emit(f"G5 {ij}P{w.num(w.coord(-5, 5))} Q{w.num(w.coord(-5, 5))} {w.axes(end, 'XY')}")
        else:
            w.emit(f"G5.1 I{w.num(w.coord(-5, 5))} J{w.num(w.coord(-5, 5))} {w.axes(end, 'XY')}")
            after_g5 = False
    w.emit("G1 G90")


def chunk_blending(w: _Writer) -> None:
    """Path control modes (G61, G61.1, G64 with P and Q) over short straight feeds."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10))
    mode = rng.choice(["G61", "G61.1", "G64", "G64 P0.01", "G64 P0.05 Q0.02"])
    w.emit(mode)
    w.emit(f"G1 {w.feed()}")
    for _ in range(rng.randint(2, 6)):
        w.emit(f"G1 {w.axes([w.pos[0] + w.coord(-8, 8), w.pos[1] + w.coord(-8, 8), w.pos[2]], 'XY')}")
    w.emit("G64 G90")


def chunk_inverse_time(w: _Writer) -> None:
    """G93 inverse-time feed (F on every feed move, arcs too), then back to G94."""
    w.start(w.coord(), w.coord(), w.coord(0, 10))
    w.emit("G93")
    w.inverse_time = True
    for _ in range(w.rng.randint(1, 4)):
        if w.rng.random() < 0.4:
            w.emit("G17")
            _arc(w, 2)
        else:
            w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.pos[2]]) or 'X' + w.num(w.pos[0])} F{w.rng.randint(1, 60)}")
    w.inverse_time = False
    w.emit(f"G94 {w.feed()} G90")
    w.incremental = False  # the G90 above
    if w.rng.random() < 0.3:
        # G94 again while G94 is on: LinuxCNC clears the feed all the same (interp_convert.cc convert_feed_mode),
        # so the next feed move carries its F. Always: without it rs274 and vcnc both refuse the program ("Cannot
        # do g1 with zero feed rate"), which tests nothing after it; test_reader_fast_g93's "G94 again without
        # F" keeps that refusal
        w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.pos[2]]) or 'X' + w.num(w.pos[0])}")
        again = w.rng.choice(["G94", "G94 G1", "G94 G0"])
        feed = " " + w.feed()
        if again == "G94":
            w.emit(again)
        else:
            w.emit(f"{again} {w.axes([w.coord(), w.coord(), w.pos[2]]) or 'X' + w.num(w.pos[0])}"
                   f"{feed if again == 'G94 G1' else ''}")
        w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.pos[2]]) or 'X' + w.num(w.pos[0])}"
               f"{'' if again == 'G94 G1' else feed}")


def chunk_parameters(w: _Writer) -> None:
    """Numbered, local named and global named parameters, expressions with functions, as axis words."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10), distance="G90")
    a, b = rng.uniform(1, 20), rng.uniform(1, 20)
    w.emit(f"#{rng.randint(1, 30)} = {w.num(a)}")
    w.emit(f"#<len> = {w.num(b)}")
    w.emit(f"#<_glob> = [{w.num(a)} + #<len>]")
    w.emit(f"#<ang> = {rng.randint(0, 359)}")
    x = "[#<_glob> * COS[#<ang>]]"
    y = "[#<len> * SIN[#<ang>] - ABS[-1.5]]"
    w.emit(f"G1 X{x} Y{y} F[{w.num(200)} * 2]")
    w.emit("G1 X[ROUND[#<len>] MOD 7] Y[SQRT[#<len> ** 2] / 2] Z[FIX[2.7] + FUP[0.2]]")
    w.emit("G0 X[ATAN[1]/[1] / 10] Y[EXP[1] + LN[2]] Z[#<len> GT 5]")
    # the current position (#5420-#5422: in the work frame, units in force) and the G92 offset read back
    w.emit(f"G1 X[#5420 + {w.num(2)}] Y[#5421 - {w.num(1)}] Z[#5422 + #5213 * 0]")
    w.emit("G1 X[#<_x> + 1] Y[#<_y>]")


def chunk_owords(w: _Writer, subs: list[str]) -> None:
    """O-word flow: calls of the program's subroutines (defined at its top), if/elseif/else, while with break
    and continue, do-while, repeat."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10), distance="G90")
    w.labels += 10
    label = w.labels  # labels label .. label + 9, new in each chunk (LinuxCNC: one O-word label per block)
    kind = rng.choice(["call", "if", "while", "do", "repeat"])
    if kind == "call" and subs:
        name = rng.choice(subs)
        w.emit(f"o<{name}> call [{w.num(w.coord(-20, 20))}] [{w.num(w.coord(-20, 20))}] [{rng.randint(1, 4)}]")
    elif kind == "if":
        w.emit(f"#<k> = {rng.randint(0, 3)}")
        w.emit(f"o{label} if [#<k> EQ 0]")
        w.emit(f"G1 X{w.num(w.coord())} {w.feed()}")
        w.emit(f"o{label} elseif [#<k> LT 2]")
        w.emit(f"G1 Y{w.num(w.coord())} {w.feed()}")
        w.emit(f"o{label} else")
        w.emit(f"G0 X{w.num(w.coord())} Y{w.num(w.coord())}")
        w.emit(f"o{label} endif")
    elif kind in ("while", "call"):
        w.emit("#<i> = 0")
        w.emit(f"o{label} while [#<i> LT {rng.randint(1, 5)}]")
        w.emit("#<i> = [#<i> + 1]")
        w.emit(f"o{label + 1} if [#<i> EQ 2]")
        w.emit(f"G0 Z[{w.num(5)} + #<i>]")
        w.emit(f"o{label} continue")
        w.emit(f"o{label + 1} endif")
        w.emit(f"o{label + 2} if [#<i> GT 3]")
        w.emit(f"o{label} break")
        w.emit(f"o{label + 2} endif")
        w.emit(f"G1 X[#<i> * {w.num(3)}] Y[#<i> * {w.num(-2)}] {w.feed()}")
        w.emit(f"o{label} endwhile")
        w.emit(f"o{label + 3} do")  # clears LinuxCNC's break flag, which would end the next do loop after one pass
        w.emit(f"o{label + 3} while [0]")
    elif kind == "do":
        w.emit("#<i> = 0")
        w.emit(f"o{label} do")
        w.emit(f"G91 G1 X{w.num(2)} {w.feed()}")
        w.emit("#<i> = [#<i> + 1]")
        w.emit(f"o{label} while [#<i> LT {rng.randint(1, 4)}]")
        w.emit("G90")
    else:
        w.emit(f"o{label} repeat [{rng.randint(1, 4)}]")
        w.emit(f"G91 G1 X{w.num(1.5)} Y{w.num(-1)} {w.feed()}")
        w.emit(f"o{label} endrepeat")
        w.emit("G90")


def subroutines() -> tuple[list[str], list[str]]:
    """Subroutine definitions for the program's top and their names: a square by its arguments (#1 X, #2 Y, #3
    count) in G91, and one that returns early."""
    lines = ["o<sq> sub", "#<n> = 0", "o101 while [#<n> LT #3]", "G90 G0 X#1 Y#2", "G91 G1 X2 F300", "G1 Y2",
             "G1 X-2", "G1 Y-2", "G90", "#<n> = [#<n> + 1]", "o101 endwhile", "o<sq> endsub",
             "o<early> sub", "G90 G1 X#1 Y#2 F200", "o102 if [#3 GT 2]", "o<early> return", "o102 endif",
             "G1 X[#1 + #3] Y[#2 - #3]", "o<early> endsub"]
    return lines, ["sq", "early"]


def chunk_mcodes(w: _Writer) -> None:
    """M codes and G codes that do not move (spindle, also with the ``$`` spindle word, m-code.adoc "M3, M4, M5":
    ``$0`` the first spindle, ``$-1`` all; coolant, overrides, digital outputs, dwell, path mode) between straight
    moves, a dwell also with an X word (LinuxCNC: the dwell, then the modal G1 to it); sometimes the modal state
    saved by M70, units and distance mode changed, and restored by M72 (m-code.adoc
    "M70 Save Modal State", "M72 Restore Modal State")."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10))
    codes = ["M3 S1200", "M4 S800", "M5", "M7", "M8", "M9", "M48", "M49", "M50 P1", "M51 P0", "M52 P1", "M53 P0",
             "M62 P1", "M63 P1", "M64 P2", "M65 P2", "G4 P0.2", "M1", "G40", "G61", "G64", "G17", "distance",
             "M3 $0 S1500", "M4 $-1 S600", "M5 $-1", "M5 $0",
             *([] if w.tool_offset else ["units"])]
    saved = (w.inch, w.incremental) if rng.random() < 0.5 else None
    if saved:
        w.emit(f"{w.feed()} M70")
    for _ in range(rng.randint(2, 5)):
        code = rng.choice(codes)
        if code == "units":
            w.inch = not w.inch
            code = "G20" if w.inch else "G21"
        elif code == "distance":
            w.incremental = not w.incremental
            code = "G91" if w.incremental else "G90"
        elif code == "G4 P0.2" and rng.random() < 0.3:  # the dwell, then the modal G1 to the axis words
            code += f" {w.axes([w.pos[0] + w.coord(-8, 8), w.pos[1], w.pos[2]], 'X')}"
        w.emit(code)
        w.emit(f"G1 {w.axes([w.pos[0] + w.coord(-8, 8), w.pos[1] + w.coord(-8, 8), w.pos[2]], 'XY')} {w.feed()}")
    if saved:
        w.emit("M72")
        w.inch, w.incremental = saved
        w.emit(f"G1 {w.axes([w.pos[0] + w.coord(-8, 8), w.pos[1] + w.coord(-8, 8), w.pos[2]], 'XY')}")
    w.emit("G90")
    w.incremental = False


def chunk_polar(w: _Writer) -> None:
    """Polar coordinates (g-code.adoc "Polar Coordinates": ``@`` distance and ``^`` angle in G17, from the
    origin under G90, from the current point under G91) for straight moves."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10))
    w.emit(f"G17 G1 {w.feed()}")
    for _ in range(rng.randint(1, 4)):
        w.emit(f"G{rng.choice([0, 1])} @{w.num(rng.uniform(1, 30))} ^{rng.randint(-180, 360)}")
    w.emit("G90")
    w.incremental = False


def chunk_rotary(w: _Writer) -> None:
    """Rotary axes A B C in rapids and feeds, alone and with X Y Z, absolute and incremental."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10))
    for _ in range(rng.randint(1, 4)):
        words = " ".join(f"{a}{rng.randint(-360, 360)}" for a in rng.sample("ABC", rng.randint(1, 3)))
        xyz = w.axes([w.coord(), w.coord(), w.pos[2]]) if rng.random() < 0.5 else ""
        w.emit(f"G{rng.choice([0, 1])} {xyz} {words} {w.feed()}".replace("  ", " "))
    w.emit("G90")


def chunk_tool_table(w: _Writer) -> None:
    """The tool table set by the program (g-code.adoc "G10 L1 Set Tool Table"), then the tool loaded and its
    length and radius used (G43, G41)."""
    rng = w.rng
    w.units()
    tool = rng.randint(40, 60)
    w.emit(f"G10 L1 P{tool} Z{w.num(rng.uniform(-5, 30))} R{w.num(rng.uniform(0.2, 3))}")
    w.emit(f"T{tool} M6")
    w.m61 = False
    w.start(w.coord(), w.coord(), w.coord(5, 30), units=False)
    w.emit(f"G43 G0 {w.axes([w.coord(), w.coord(), w.coord(0, 30)])}")
    w.tool_offset = True
    w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.coord(0, 30)])} {w.feed()}")
    w.emit("G90")


#: Predefined named parameters that read the modal state (overview.adoc "Predefined Named Parameters"), each
#: with a factor that keeps its part of a coordinate small [program units per unit of the parameter].
STATE_PARAMETERS = {"_motion_mode": 0.01, "_plane": 0.001, "_ccomp": 0.001, "_metric": 1.0, "_imperial": 1.0,
                    "_absolute": 1.0, "_incremental": 1.0, "_inverse_time": 1.0, "_units_per_minute": 1.0,
                    "_units_per_rev": 1.0, "_coord_system": 0.001, "_tool_offset": 1.0, "_retract_r_plane": 1.0,
                    "_retract_old_z": 1.0, "_feed": 0.001, "_rpm": 0.0001, "_spindle_on": 1.0, "_spindle_cw": 1.0,
                    "_mist": 1.0, "_flood": 1.0, "_current_tool": 0.1, "_selected_tool": 0.1, "_x": 0.1, "_y": 0.1,
                    "_z": 0.1, "_a": 0.001, "_abs_x": 0.01, "_abs_y": 0.01, "_abs_z": 0.01, "_ijk_absolute_mode": 1.0,
                    "_spindle_rpm_mode": 1.0}


def chunk_state(w: _Writer) -> None:
    """The modal state read through the predefined named parameters (:data:`STATE_PARAMETERS`) into the coordinates
    of feed moves, and work offsets written through their numbered parameters (overview.adoc "Numbered
    Parameters": "5221-5230 Coordinate System 1, G54 (X Y Z A B C U V W R)", 20 apart up to G59.3), then a system
    selected (LinuxCNC takes the written values at the selection, interp_convert.cc ``convert_coordinate_system``)
    and moves in it."""
    rng = w.rng
    w.start(w.coord(), w.coord(), w.coord(0, 10), distance="G90")
    w.emit(rng.choice(["G17", "G18", "G19", "G98", "G99", "M8", "M7", "M9", "S1000 M3", "S500 M4", "M5"]))
    # not #<_current_tool> after M61: rs274's standalone canon leaves it 0 ("M61 Q5" then "(debug,
    # #<_current_tool>)" prints 0; saicanon.cc CHANGE_TOOL_NUMBER, as chunk_tools says), LinuxCNC's task and vcnc 5
    known = sorted(n for n in STATE_PARAMETERS if not (w.m61 and n == "_current_tool"))
    for _ in range(rng.randint(1, 3)):
        names = rng.sample(known, 2)
        parts = [f"#<{n}> * {STATE_PARAMETERS[n]:g}" for n in names]
        w.emit(f"G1 X[{w.num(w.coord())} + {parts[0]}] Y[{w.num(w.coord())} + {parts[1]}] {w.feed()}")
    if rng.random() < 0.6:
        k = rng.randint(0, 8)
        base = 5221 + 20 * k
        for j in rng.sample(range(3), rng.randint(1, 3)):
            w.emit(f"#{base + j} = [#{base + j} + {rng.randint(-20, 20)}]" if rng.random() < 0.5
                   else f"#{base + j} = {rng.randint(-50, 50)}")
        w.emit(["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"][k])
    w.emit("G17")
    w.start(w.coord(), w.coord(), w.coord(0, 20), distance="G90", units=False)
    w.emit(f"G1 {w.axes([w.coord(), w.coord(), w.pos[2]])} {w.feed()}")


#: Feature groups and the chunk that writes one.
FEATURES = {"arcs": chunk_arcs, "offsets": chunk_offsets, "tools": chunk_tools, "home": chunk_home,
            "compensation": chunk_compensation, "cycles": chunk_cycles, "tapping": chunk_tapping,
            "splines": chunk_splines, "blending": chunk_blending, "inverse_time": chunk_inverse_time,
            "parameters": chunk_parameters, "owords": chunk_owords, "mcodes": chunk_mcodes, "polar": chunk_polar,
            "rotary": chunk_rotary, "tool_table": chunk_tool_table, "state": chunk_state}


def generate(seed: int, *, features: tuple[str, ...] = tuple(FEATURES), chunks: tuple[int, int] = (3, 8)
             ) -> tuple[str, list[str]]:
    """A random LinuxCNC program and the feature groups of its chunks, in order.

    Parameters
    ----------
    seed : int
        Seed of ``random.Random``: the same seed and features give the same program.
    features : tuple of str
        Names of :data:`FEATURES` to draw the chunks from.
    chunks : (int, int)
        Least and most chunks.
    """
    unknown = sorted(set(features) - set(FEATURES))
    if unknown:
        raise ValueError(f"unknown feature groups {unknown}; known: {sorted(FEATURES)}")
    rng = random.Random(seed)
    w = _Writer(rng)
    w.emit(f"(linuxcnc_fuzz seed {seed})")
    subs, names = subroutines() if "owords" in features else ([], [])
    w.lines += subs
    w.emit(rng.choice(["G21", "G20", "G21 G17 G40 G49 G80 G90 G94"]))
    w.inch = w.lines[-1].startswith("G20")
    w.emit(f"G0 Z{w.num(25.0)}")
    used = []
    for _ in range(rng.randint(*chunks)):
        name = rng.choice(features)
        used.append(name)
        if name == "owords":
            chunk_owords(w, names)
        else:
            FEATURES[name](w)
    w.emit("M2")
    return "\n".join(w.lines) + "\n", used
