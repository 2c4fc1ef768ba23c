"""Seeded setpoint fuzzer: random programs interpolated under both profiles, their setpoints checked for invariants.

The readers' fuzzers (``benchmarks/linuxcnc_fuzz.py``, ``tests/interpolators/fanuc_generator.py``,
``tests/interpolators/tnc_generator.py``) compare block end points with references; this one checks the *setpoints*
of random programs: those three generators' programs and CAM-like dense code written here (:func:`cam_program`:
chords of random curves 1 um - 2 mm long, tangent arc chains, tiny arcs, zig-zags, helices, near-reversals, very
short segments, feed changes, dwells, G61 / G64 / G64 P; :func:`tnc_cam_program`: the same in TNC conversational
with cycle 32 tolerances; :func:`rotary_cam_program`: coarse chords with A-C swinging and cornering under G94 and
G93, tangent arc chains of alternating sense, an axis of A-C/U-W written on some blocks only along lines and arcs,
long lines and small tangent arcs of either sense with one or two of A-C/U-W moving on every block,
a third in G20; :func:`fanuc_cam_program`: Fanuc 30i code with G06.2 NURBS and G02.4 three-dimensional arcs among
such chords, under ``--dialect fanuc``), each run under the trapezoid and the S-curve with random but sane limits
per axis (:func:`random_limits`: velocity, acceleration and jerk differing up to 40x between axes, 400x for
rotary_cam, rapid rates) and a sample time of 0.25 - 4 ms. :func:`check_setpoints` names what is wrong:

* ``nonfinite``: a NaN or infinity in a column;
* ``limits``: an axis beyond its velocity, acceleration (or, S-curve, jerk) limit by finite differences or in the
  analytic columns, or the X/Y/Z path speed above the programmed feed (``setpoint_checks.check_limits``);
* ``jump``: a position step that the analytic velocity and acceleration columns do not explain;
* ``block_order``: ``Setpoints.block`` decreasing;
* ``start`` / ``end``: the first sample not at the program's start, the last not exactly at its end;
* ``deviation``: a sample farther from the programmed path than the tolerance of the junctions at its block's two
  ends (:func:`junction_tolerances`: the smaller of the two blocks' G64 P, 0.01 mm without P,
  ``interpolators.DEFAULT_TOLERANCE``, the TNC cycle 32 T or the dialect's tolerance, ``Block.tolerance``, as
  LinuxCNC's ``tcFindBlendTolerance``; 0 where a block ends at rest, G61, a dwell);
* ``corner``: a programmed block end not passed within its junction's tolerance (not on a sample within 1 nm where
  the block ends at rest);
* ``dwell``: a dwell not held at rest for its time rounded up to whole samples;
* ``axis``: an axis beyond X/Y/Z outside its programmed values over the sample's block and two blocks either side,
  widened by their largest tolerance (deg on A-C);
* ``axis_path``: such an axis farther from its value programmed at the nearest point of the path than the sample's
  tolerance (deg on A-C), beyond the axis' rate times the sample's distance from the path (:func:`_axis_path_failures`).

* ``wrap``: with ``--wrap RULE`` or ``--machine FILE`` (rotary axes that wrap at 360 deg), a line with an absolute
  word of a wrapping axis that ends elsewhere than the word's angle modulo 360 deg, or turns the axis otherwise than
  the rule says (:func:`wrap_failures`; checked on ISO programs without G91, G53, G28/G30, offsets or parameters).

``python -m benchmarks.setpoint_fuzz --count 200 --seed 0`` prints a table of outcomes per source; ``--list``
names every failing case (source, seed, profile, sample time, kind and detail). ``--wrap sign|shortest|difference``
runs every source with its rotary axes A, B, C wrapping at 360 deg under that rule (``[axes.a] wrap = true``,
``[program] wrap_direction``, :mod:`interpolators.rotary_wrap`); ``--machine FILE`` takes the wrapping axes and the
rule from a machine file (unset: each source's control's own), the rest of each source's context kept. The limits
and every check are then judged on the motion the axes really make (the blocks carry the unwrapped angle).
"""

from __future__ import annotations

import argparse
import collections
import dataclasses
import math
import random
import re
import sys
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks import linuxcnc_fuzz  # noqa: E402
from interpolators import DEFAULT_TOLERANCE, AxisLimits, interpolate, parse_program  # noqa: E402
from interpolators.context import DEFAULT_CONTEXT, DIALECTS, INTERPOLATION_CONTEXT, MachineContext  # noqa: E402
from interpolators.rotary_wrap import ROTARY_AXES, WRAP_DIRECTIONS, default_direction  # noqa: E402
from tests.interpolators import fanuc_generator, tnc_generator  # noqa: E402
from tests.interpolators.setpoint_checks import check_limits, path_distances, xyz  # noqa: E402
from vcnc.core.axes import EXTRA_NAMES  # noqa: E402
from vcnc.errors import GCodeError, ProgramTooLongError  # noqa: E402

#: Sources of programs: name -> (program text, machine context) of a seed.
SOURCES = ("cam", "tnc_cam", "rotary_cam", "linuxcnc", "fanuc", "haas", "tnc", "fanuc_cam")
#: Largest number of samples a case may take (a longer one is skipped as ``too_long``).
MAX_SAMPLES = 3_000_000
#: rotary_cam seeds from this one run a quarter each at 0.25 ms and 4 ms (seeds below keep their sample times).
ROTARY_EDGE_TS_SEED = 43000
#: A point "on" a sample [mm] (exact stops, program start and end).
EXACT = 1e-6
#: Allowance beyond a tolerance [mm] for the rounding of the measurement.
ALLOWANCE = 1e-6


def _num(rng: random.Random, v: float) -> str:
    """A coordinate as CAM posts write it: mostly 4 decimals, sometimes 3 or 6."""
    return f"{v:.{rng.choice((4, 4, 4, 3, 6))}f}"


class _Cam:
    """A CAM-like ISO program being written: its lines and the current point [mm]."""

    def __init__(self, rng: random.Random, *, tnc: bool = False, unit: float = 1.0):
        self.r = rng
        self.tnc = tnc
        self.unit = unit  # mm per program unit: 25.4 under G20 (coordinates, feeds and P written in inches)
        self.lines: list[str] = []
        self.pos = np.array([0.0, 0.0, 5.0])
        self.extra = False

    def move(self, p, *, rapid: bool = False, feed: float | None = None, extra: str = "") -> None:
        """A straight move to ``p`` (written with the program's rounding; the current point follows it)."""
        words = [self._coord(a, v / self.unit) for a, v in zip("XYZ", p)]
        self.pos = np.array([float(w[1:]) * self.unit for w in words])
        if self.tnc:
            f = " FMAX" if rapid else (f" F{feed:.0f}" if feed else "")
            self.lines.append(f"L {' '.join(words)} R0{f}")
        else:
            f = f" F{feed / self.unit:.{0 if self.unit == 1.0 else 2}f}" if feed else ""
            self.lines.append(f"{'G0' if rapid else 'G1'} {' '.join(words)}{extra}{f}")

    def _coord(self, axis: str, v: float) -> str:
        s = _num(self.r, v)
        return f"{axis}{'+' if self.tnc and not s.startswith('-') else ''}{s}"

    def arc(self, centre, end, ccw: bool, *, z: float | None = None, extra: str = "") -> None:
        """An arc about ``centre`` (X Y) to ``end`` (X Y), helical to ``z``, with ``extra`` words (ISO: axes beyond
        X/Y/Z moving along it); the end put on the circle."""
        c = np.array([float(_num(self.r, centre[0])), float(_num(self.r, centre[1]))])
        r0 = float(np.hypot(*(self.pos[:2] - c)))
        ang = math.atan2(end[1] - c[1], end[0] - c[0])
        end = c + r0 * np.array([math.cos(ang), math.sin(ang)])
        zz = self.pos[2] if z is None else z
        ex, ey, ez = (f"{v / self.unit:.6f}" for v in (end[0], end[1], zz))
        if self.tnc:
            self.lines.append(f"CC X{c[0]:+.6f} Y{c[1]:+.6f}")
            zw = f" Z{float(ez):+.6f}" if z is not None else ""
            self.lines.append(f"C X{float(ex):+.6f} Y{float(ey):+.6f}{zw} DR{'+' if ccw else '-'}")
        else:
            i, j = (c - self.pos[:2]) / self.unit
            zw = f" Z{ez}" if z is not None else ""
            self.lines.append(f"{'G3' if ccw else 'G2'} X{ex} Y{ey}{zw}{extra} I{i:.6f} J{j:.6f}")
        self.pos = np.array([float(ex), float(ey), float(ez)]) * self.unit

    def tangent_arc(self, heading: float, rad: float, sweep: float, ccw: bool, *, extra: str = "") -> float:
        """An arc of radius ``rad`` leaving the current point along ``heading`` [rad], to the left (``ccw``) or the
        right, turning by ``sweep`` [rad, signed: > 0 to the left], with ``extra`` words (:meth:`arc`); returns the
        heading at its end."""
        c = self.pos[:2] + rad * np.array([-math.sin(heading), math.cos(heading)]) * (1 if ccw else -1)
        a0 = math.atan2(self.pos[1] - c[1], self.pos[0] - c[0])
        self.arc(c, c + rad * np.array([math.cos(a0 + sweep), math.sin(a0 + sweep)]), ccw, extra=extra)
        return heading + sweep

    def mode(self) -> None:
        """A path mode: G61, G64, G64 P (TNC: cycle 32 with or without T, or none)."""
        tol = self.r.choice((0.001, 0.005, 0.01, 0.02, 0.05, 0.1))
        k = self.r.random()
        if self.tnc:
            if k < 0.6:
                self.lines += ["CYCL DEF 32.0 TOLERANCE", f"CYCL DEF 32.1 T{tol}" if k < 0.45 else "CYCL DEF 32.1"]
            return
        p = tol if self.unit == 1.0 else f"{tol / self.unit:.6f}"
        self.lines.append("G61" if k < 0.2 else "G64" if k < 0.4 else f"G64 P{p}")

    def feed(self) -> float:
        return self.r.choice((100.0, 500.0, 1500.0, 3000.0, 6000.0, 12000.0, 30000.0))

    def dwell(self) -> None:
        t = self.r.choice((0.001, 0.0123, 0.1, 0.25))
        self.lines += (["CYCL DEF 9.0 DWELL TIME", f"CYCL DEF 9.1 DWELL {t}"] if self.tnc else [f"G4 P{t}"])


def _chords(g: _Cam) -> None:
    """Chords of a random smooth curve (a wavy circle or a sine wave, in 2D or 3D), each 1 um - 2 mm long."""
    r = g.r
    step = 10 ** r.uniform(-3, math.log10(2.0))
    n = r.randint(8, min(400, max(9, int(60 / step))))
    amp, freq, phase = r.uniform(0, 0.3), r.randint(1, 7), r.uniform(0, 6.3)
    radius = r.uniform(0.2, 30.0)
    dz = r.choice((0.0, 0.0, r.uniform(-2, 2)))
    start = g.pos.copy()
    kind = r.random()
    feed = g.feed()
    for k in range(1, n + 1):
        s = k * step
        if kind < 0.5:
            th = s / radius
            rr = radius * (1 + amp * math.sin(freq * th + phase))
            p = start + [rr * math.cos(th) - radius, rr * math.sin(th), dz * k / n]
        else:
            p = start + [s, radius * 0.1 * math.sin(s * freq / max(radius, 1) + phase), dz * k / n]
        g.move(p, feed=feed if k == 1 else None)
        if r.random() < 0.02:
            feed = g.feed()
            g.move(g.pos + [step, 0, 0], feed=feed)


def _arc_chain(g: _Cam, *, tiny: bool = False) -> None:
    """Tangent arcs (and lines) turning either way; radii 1 um - 0.05 mm when ``tiny``."""
    r = g.r
    heading = r.uniform(0, 2 * math.pi)
    g.move(g.pos + [math.cos(heading), math.sin(heading), 0], feed=g.feed())
    for _ in range(r.randint(2, 12)):
        rad = 10 ** r.uniform(-3, math.log10(0.05)) if tiny else 10 ** r.uniform(-1.3, 1.3)
        ccw = r.random() < 0.5
        heading = g.tangent_arc(heading, rad, r.uniform(0.05, 3.0) * (1 if ccw else -1), ccw)
        if r.random() < 0.3:
            length = 10 ** r.uniform(-2, 0.7)
            g.move(g.pos + [length * math.cos(heading), length * math.sin(heading), 0])


def _zigzag(g: _Cam) -> None:
    """A raster: passes 0.5 - 20 mm long, 0.01 - 1 mm apart, or a saw tooth of small amplitude."""
    r = g.r
    length, over = r.uniform(0.5, 20), 10 ** r.uniform(-2, 0)
    g.move(g.pos, feed=g.feed())
    for k in range(r.randint(3, 20)):
        g.move(g.pos + [length * (1 if k % 2 == 0 else -1), 0, 0])
        g.move(g.pos + [0, over, 0])


def _helix(g: _Cam) -> None:
    """Helical arcs descending about a centre, a quarter to a whole turn each."""
    r = g.r
    rad = r.uniform(0.2, 10)
    c = g.pos[:2] + [rad, 0]
    ccw = r.random() < 0.5
    g.move(g.pos, feed=g.feed())
    for _ in range(r.randint(1, 5)):
        a0 = math.atan2(g.pos[1] - c[1], g.pos[0] - c[0])
        sweep = r.choice((0.5, 1.0, 1.5, 3.0)) * (1 if ccw else -1)
        end = c + rad * np.array([math.cos(a0 + sweep), math.sin(a0 + sweep)])
        g.arc(c, end, ccw, z=g.pos[2] - r.uniform(0.01, 2))


def _reversals(g: _Cam) -> None:
    """Lines that turn back by nearly 180 degrees, and very short segments (0.1 - 10 um)."""
    r = g.r
    heading = r.uniform(0, 2 * math.pi)
    g.move(g.pos, feed=g.feed())
    for _ in range(r.randint(2, 10)):
        if r.random() < 0.5:
            length = 10 ** r.uniform(-4, -2)
        else:
            length = r.uniform(0.05, 5)
            heading += math.pi - 10 ** r.uniform(-4, -0.5) * r.choice((1, -1))
        g.move(g.pos + [length * math.cos(heading), length * math.sin(heading), r.choice((0, 0, 0, 1e-3))])


def _extra_axes(g: _Cam) -> None:
    """Feed moves with a rotary or secondary axis moving beside X/Y (ISO only)."""
    r = g.r
    axis = r.choice("ABCUVW")
    value = 0.0
    g.extra = True
    g.move(g.pos, feed=g.feed())
    for _ in range(r.randint(2, 10)):
        value += r.uniform(-20, 20)
        g.move(g.pos + [r.uniform(-3, 3), r.uniform(-3, 3), 0], extra=f" {axis}{value:.4f}")


def _rotary_words(values: dict[str, float]) -> str:
    return "".join(f" {a}{v:.4f}" for a, v in values.items())


def _rotary_chords(g: _Cam, *, inverse_time: bool = False) -> None:
    """Coarse chords (0.3 - 5 mm) of a gentle curve with one to three of A, B, C swinging beside X/Y/Z, a corner
    (a turn of 10 - 120 degrees, or a rotary axis reversing) every few chords; with ``inverse_time`` under G93
    with an F on every block, the chords' speeds differing up to 5x from one block to the next, G94 after."""
    r = g.r
    axes = r.sample("ABC", r.randint(1, 3))
    values = {a: r.uniform(-30, 30) for a in axes}
    amp = {a: r.uniform(1, 40) for a in axes}
    step = 10 ** r.uniform(math.log10(0.3), math.log10(5))
    heading, bend = r.uniform(0, 2 * math.pi), r.uniform(-0.3, 0.3)
    g.extra = True
    feed = g.feed()
    g.move(g.pos, feed=feed, extra=_rotary_words(values))
    if inverse_time:
        g.lines.append("G93")
    for k in range(r.randint(4, 30)):
        heading += bend if r.random() < 0.8 else math.radians(r.uniform(10, 120)) * r.choice((1, -1))
        for a in axes:
            values[a] += amp[a] * step / 10 * (1 if (k // r.randint(1, 4)) % 2 == 0 else -1)
        p = g.pos + [step * math.cos(heading), step * math.sin(heading), r.choice((0.0, 0.0, r.uniform(-0.3, 0.3)))]
        if inverse_time:
            g.move(p, extra=_rotary_words(values))
            g.lines[-1] += f" F{feed * r.uniform(0.2, 5) / step:.3f}"
        else:
            g.move(p, feed=feed if r.random() < 0.1 else None, extra=_rotary_words(values))
    if inverse_time:
        g.lines.append("G94")
        g.move(g.pos + [step, 0, 0], feed=g.feed())


def _alternating_arcs(g: _Cam) -> None:
    """Tangent chains of arcs turning alternately left and right (radii 0.005 - 2 mm), some joined by short
    tangent lines: line/arc and arc/arc junctions whose curvature changes sign."""
    r = g.r
    heading = r.uniform(0, 2 * math.pi)
    g.move(g.pos + [math.cos(heading), math.sin(heading), 0], feed=g.feed())
    ccw = r.random() < 0.5
    for _ in range(r.randint(3, 16)):
        rad = 10 ** r.uniform(math.log10(0.005), math.log10(2.0))
        heading = g.tangent_arc(heading, rad, r.uniform(0.1, 2.5) * (1 if ccw else -1), ccw)
        if r.random() < 0.3:
            length = 10 ** r.uniform(-2.5, 0)
            g.move(g.pos + [length * math.cos(heading), length * math.sin(heading), 0])
        ccw = not ccw if r.random() < 0.85 else ccw


def _staircase(g: _Cam) -> None:
    """Lines and tangent arcs (radii 0.05 - 10 mm) under one feed with an axis of A-C or U-W written on some blocks
    only: indexing (a move of that axis alone every few blocks, still between), a staircase (a step on every k-th
    block), or moving on every block at a rate per mm that changes from block to block, on lines and on arcs alike:
    junctions where that axis starts, stops or steps its rate, line/line, line/arc and arc/arc."""
    r = g.r
    axis = r.choice("AAABCUVW")
    value = r.uniform(-30, 30) if axis in "ABC" else r.uniform(-5, 5)
    rate = 10 ** r.uniform(-1.5, 1.5) * (1 if axis in "ABC" else 0.1)  # per mm of path
    every, style = r.randint(2, 6), r.choice(("index", "stair", "rates"))
    heading = r.uniform(0, 2 * math.pi)
    g.extra = True
    g.move(g.pos, feed=g.feed(), extra=f" {axis}{value:.4f}")
    for k in range(r.randint(4, 30)):
        length = 10 ** r.uniform(-1, 1)
        word = ""
        if style == "index" and k % every == 0:
            value += r.uniform(-90, 90) if axis in "ABC" else r.uniform(-5, 5)
            g.lines.append(f"G1 {axis}{value:.4f}")
        elif style == "rates" or (style == "stair" and k % every == 0):
            value += rate * length * r.choice((1, 1, -1, 0.2, 3)) * (1 if style == "rates" else r.uniform(0.5, 2))
            word = f" {axis}{value:.4f}"
        if r.random() < 0.4:
            rad = 10 ** r.uniform(math.log10(0.05), 1)
            ccw = r.random() < 0.5
            heading = g.tangent_arc(heading, rad, min(length / rad, 2.5) * (1 if ccw else -1), ccw, extra=word)
        else:
            if r.random() < 0.3:
                heading += math.radians(r.uniform(1, 90)) * r.choice((1, -1))
            g.move(g.pos + [length * math.cos(heading), length * math.sin(heading), 0], extra=word)


def _rotary_tangent_chain(g: _Cam) -> None:
    """Chains of long lines (2 - 30 mm) and small arcs (radii 0.02 - 0.5 mm, some 2 - 10 mm; some full circles) of
    either sense, mostly tangent (a kink of 1 - 60 degrees before a fifth of them), arc/arc pairs often of opposite
    sense, with one or two of A-C/U-W moving on every block at a rate per
    mm that steps from block to block: line/arc and arc/arc junctions tangent in X/Y with the axes moving on both
    sides, curvature steps beside them (the chains ``blend_corners`` and the one-sample junction rule handle)."""
    r = g.r
    axes = r.sample("ABCUVW", r.choice((1, 1, 2)))
    values = {a: r.uniform(-30, 30) if a in "ABC" else r.uniform(-5, 5) for a in axes}
    heading = r.uniform(0, 2 * math.pi)
    g.extra = True
    g.move(g.pos, feed=g.feed(), extra=_rotary_words(values))
    ccw = r.random() < 0.5
    for _ in range(r.randint(3, 14)):
        arc = r.random() < 0.55
        length = 10 ** r.uniform(math.log10(2), math.log10(30)) if not arc else 0.0
        rad = 10 ** r.uniform(math.log10(0.02), math.log10(0.5)) if r.random() < 0.8 else r.uniform(2, 10)
        sweep = (2 * math.pi if r.random() < 0.1 else r.uniform(0.1, 2.5)) if arc else 0.0
        if r.random() < 0.2:
            heading += math.radians(r.uniform(1, 60)) * r.choice((1, -1))  # a kink beside the arcs
        travel = length or rad * sweep
        for a in axes:
            values[a] += travel * 10 ** r.uniform(-1.5, 1) * (1 if a in "ABC" else 0.1) * r.choice((1, 1, -1))
        if arc:
            heading = g.tangent_arc(heading, rad, sweep * (1 if ccw else -1), ccw, extra=_rotary_words(values))
            ccw = not ccw if r.random() < 0.6 else ccw
        else:
            g.move(g.pos + [length * math.cos(heading), length * math.sin(heading), 0], extra=_rotary_words(values))


_ROTARY_SECTIONS = (_rotary_chords, _rotary_chords, lambda g: _rotary_chords(g, inverse_time=True),
                    _alternating_arcs, _extra_axes, _chords, _arc_chain)


def rotary_cam_program(seed: int) -> str:
    """A CAM-like ISO program of ``seed`` for the rotary-axis blends and S-curve tangent junctions: coarse chords
    with A/B/C swinging and cornering (under G94 or G93 with F changing every block), tangent line/arc and arc/arc
    chains of alternating sense with small radii, staircases of one axis beyond X/Y/Z (:func:`_staircase`), in
    random path modes, a third of the programs in G20 (inches:
    coordinates, feeds and P; A-C stay in degrees)."""
    r = random.Random(f"rotary_cam:{seed}")
    g = _Cam(r, unit=25.4 if r.random() < 1 / 3 else 1.0)
    g.lines.append(f"{'G20' if g.unit != 1.0 else 'G21'} G17 G90 G40 G94")
    g.move([0, 0, 5], rapid=True)
    stairs = random.Random(f"rotary_cam:stairs:{seed}")
    chains = random.Random(f"rotary_cam:chains:{seed}")
    for _ in range(r.randint(2, 5)):
        g.mode()
        r.choice(_ROTARY_SECTIONS)(g)
        for extra_rng, section in ((stairs, _staircase), (chains, _rotary_tangent_chain)):
            if extra_rng.random() < 0.5:  # drawn apart: the other sections of a seed stay as they were before
                g.r, main = extra_rng, g.r
                section(g)
                g.r = main
        if r.random() < 0.2:
            g.move(g.pos + [0, 0, r.uniform(0.5, 5)], rapid=True)
    return "\n".join([*g.lines, "M2"]) + "\n"


_SECTIONS = (_chords, _chords, _chords, _arc_chain, lambda g: _arc_chain(g, tiny=True), _zigzag, _helix,
             _reversals)


def cam_program(seed: int, *, tnc: bool = False) -> str:
    """A CAM-like program of ``seed``: sections of dense chords, arc chains, zig-zags, helices, near-reversals
    and short segments in random path modes, with feed changes and dwells; ISO (LinuxCNC) or, with ``tnc``, TNC
    conversational with cycle 32."""
    r = random.Random(f"cam:{tnc}:{seed}")
    g = _Cam(r, tnc=tnc)
    if not tnc:
        g.lines.append("G21 G17 G90 G40")
    g.move([0, 0, 5], rapid=True)
    for _ in range(r.randint(2, 6)):
        g.mode()
        section = r.choice(_SECTIONS + (() if tnc else (_extra_axes,)))
        section(g)
        if r.random() < 0.25:
            g.dwell()
        if r.random() < 0.2:
            g.move(g.pos + [0, 0, r.uniform(0.5, 5)], rapid=True)
    if tnc:
        body = ["BEGIN PGM CAM MM", *g.lines, "END PGM CAM MM"]
        return "\n".join(f"{k} {line}" for k, line in enumerate(body)) + "\n"
    return "\n".join([*g.lines, "M2"]) + "\n"


def _fanuc_nurbs(g: _Cam) -> None:
    """A Fanuc ``G06.2`` NURBS as Siemens NX Post Builder's Fanuc 30i post writes it (``G06.2 X Y Z K F P<rank>``, a
    block ``X Y Z K [R]`` per control point, then ``K`` alone rank times; FANUC 15i-MA operator's manual "NURBS
    interpolation (G06.2)"): rank 2-4, 3-10 control points 0.05-20 mm apart turning up to 70 degrees at each,
    weights 0.3-3 or none, knots clamped and uniform or random inside; the first control point the current one."""
    r = g.r
    rank = r.choice((2, 3, 4, 4))
    n = r.randint(max(rank, 3), rank + 6)
    step, heading = 10 ** r.uniform(math.log10(0.05), math.log10(20)), r.uniform(0, 2 * math.pi)
    points = [g.pos.copy()]
    for _ in range(n - 1):
        heading += math.radians(r.uniform(-70, 70))
        points.append(points[-1] + step * np.array([math.cos(heading), math.sin(heading), r.choice((0, 0, 0.2))]))
    inner = (sorted(r.uniform(0.0, 1.0) for _ in range(n - rank)) if r.random() < 0.5
             else [(k + 1) / (n - rank + 1) for k in range(n - rank)])
    knots = [0.0] * rank + inner + [1.0] * rank
    weighted = r.random() < 0.5
    for k, p in enumerate(points):
        words = " ".join(f"{a}{_num(r, v)}" for a, v in zip("XYZ", p)) if k else "X{:.6f} Y{:.6f} Z{:.6f}".format(*p)
        weight = f" R{r.uniform(0.3, 3):.4f}" if weighted and 0 < k < n - 1 else ""
        head = f"G06.2 P{rank} " if k == 0 else ""
        feed = f" F{g.feed():.0f}" if k == 0 else ""
        g.lines.append(f"{head}{words} K{knots[k]:.6f}{weight}{feed}")
        if k:
            g.pos = np.array([float(w[1:]) for w in words.split()])
    g.lines += [f"K{v:.6f}" for v in knots[n:]]


def _fanuc_arc3d(g: _Cam) -> None:
    """Fanuc ``G02.4`` three-dimensional arcs as Fusion's fanuc.cps writes them with "Allow 3D arcs" (the arc's
    middle, then its end; :mod:`interpolators.iso_arc3d`): a chain of arcs 0.05-20 mm in radius on circles tilted
    5-90 degrees, each leaving where the last ended."""
    r = g.r
    g.move(g.pos, feed=g.feed())
    for _ in range(r.randint(1, 6)):
        radius = 10 ** r.uniform(math.log10(0.05), math.log10(20))
        tilt, turn = math.radians(r.uniform(5, 90)), r.uniform(0, 2 * math.pi)
        u = np.array([math.cos(turn), math.sin(turn), 0.0])
        v = np.array([-math.sin(turn) * math.cos(tilt), math.cos(turn) * math.cos(tilt), math.sin(tilt)])
        centre = g.pos - radius * u
        sweep = r.uniform(0.3, 1.9 * math.pi)
        for a in (sweep / 2, sweep):
            p = centre + radius * (u * math.cos(a) + v * math.sin(a))
            words = " ".join(f"{x}{_num(r, c)}" for x, c in zip("XYZ", p))
            g.lines.append(f"G02.4 {words}" if a < sweep else words)
            g.pos = np.array([float(w[1:]) for w in words.split()])


_FANUC_SECTIONS = (_chords, _arc_chain, _zigzag, _helix, _reversals, _fanuc_nurbs, _fanuc_nurbs, _fanuc_arc3d,
                   _fanuc_arc3d)


def fanuc_cam_program(seed: int) -> str:
    """A CAM-like Fanuc 30i program of ``seed`` (``--dialect fanuc``): ``G05.1 Q1`` AI contour control, dense chords,
    arc chains, helices and reversals as :func:`cam_program`'s, ``G06.2`` NURBS (:func:`_fanuc_nurbs`) and
    ``G02.4`` three-dimensional arcs (:func:`_fanuc_arc3d`), in G61 / G64 / G64 P."""
    r = random.Random(f"fanuc_cam:{seed}")
    g = _Cam(r)
    g.lines.append("G21 G17 G90 G40 G94")
    g.lines.append("G05.1 Q1")
    g.move([0, 0, 5], rapid=True)
    for _ in range(r.randint(2, 6)):
        g.mode()
        r.choice(_FANUC_SECTIONS)(g)
        if r.random() < 0.2:
            g.move(g.pos + [0, 0, r.uniform(0.5, 5)], rapid=True)
    return "\n".join([*g.lines, "G05.1 Q0", "M30"]) + "\n"


def program_of(source: str, seed: int) -> tuple[str, MachineContext]:
    """The program text of ``source`` and ``seed`` and the machine context it runs on."""
    if source == "cam":
        return cam_program(seed), INTERPOLATION_CONTEXT
    if source == "tnc_cam":
        return cam_program(seed, tnc=True), DEFAULT_CONTEXT
    if source == "rotary_cam":
        return rotary_cam_program(seed), INTERPOLATION_CONTEXT
    if source == "fanuc_cam":
        return fanuc_cam_program(seed), MachineContext(dialect=DIALECTS["fanuc"])
    if source == "linuxcnc":
        return linuxcnc_fuzz.generate(seed)[0], INTERPOLATION_CONTEXT
    if source in ("fanuc", "haas"):
        return fanuc_generator.generate(seed, source), fanuc_generator.context(seed, source)
    if source == "tnc":
        return tnc_generator.generate(seed), tnc_generator.context(seed)
    raise ValueError(f"unknown source {source!r}; known: {', '.join(SOURCES)}")


def random_limits(rng: random.Random, axes, spread: float = 40.0) -> dict[str, AxisLimits]:
    """Limits per axis (mm or deg): velocity from 10, acceleration from 100, jerk from 1000, each axis' value a
    random 1 - ``spread`` times a base drawn per program (so up to ``spread`` x apart between axes); rapid 1 - 3 x
    the velocity."""
    base = [10 ** rng.uniform(1, 1.5), 10 ** rng.uniform(2, 3), 10 ** rng.uniform(3, 5)]
    out = {}
    for axis in axes:
        v, a, j = (b * spread ** rng.random() for b in base)
        out[axis] = AxisLimits(velocity=v, acceleration=a, jerk=j, rapid=v * rng.uniform(1, 3))
    return out


def block_tolerances(program) -> np.ndarray:
    """The path tolerance of each block [mm]: 0 where it ends at rest (G61, dwells), else its G64 P or cycle 32 T
    (``Block.tolerance``), :data:`interpolators.DEFAULT_TOLERANCE` without (rapids too: G0 corners are blended
    under G64 as LinuxCNC's planner blends them)."""
    return np.array([0.0 if b.exact_stop or b.kind == "dwell" else
                     DEFAULT_TOLERANCE if b.tolerance is None else b.tolerance for b in program.blocks])


def junction_tolerances(program) -> np.ndarray:
    """The path tolerance of the junction at each block's end [mm]: the smaller of its own and the next moving
    block's (``Block.tolerance``, :data:`interpolators.DEFAULT_TOLERANCE` without), as LinuxCNC's
    ``tcFindBlendTolerance`` (src/emc/tp/tc.c) blends within ``fmin(T1, T2)``; 0 where it ends at rest (G61, a
    dwell before the next move, the program's end). A block's samples lie within the larger of the junctions at
    its two ends (a blend's first half carries the incoming block, its second half the outgoing one)."""
    blocks = program.blocks
    own = np.array([DEFAULT_TOLERANCE if b.tolerance is None else b.tolerance for b in blocks])
    out = np.zeros(len(blocks))
    nxt, stop = len(blocks), True
    for i in range(len(blocks) - 1, -1, -1):
        b = blocks[i]
        if b.kind == "dwell":
            stop = True
            continue
        if b.segment is None or b.length == 0:
            continue
        out[i] = 0.0 if stop or b.exact_stop else min(own[i], own[nxt])
        nxt, stop = i, False
    return out


def _full(program, sp, pos: np.ndarray, extra: np.ndarray | None) -> np.ndarray:
    """A position of the program (X Y Z and the blocks' extra axes) in the column order of ``sp``."""
    return np.array([pos["xyz".index(a)] if a in "xyz" else (0.0 if extra is None else extra[EXTRA_NAMES.index(a)])
                     for a in sp.axes])


def _polyline_distance(points: np.ndarray, q: np.ndarray) -> float:
    """Distance [mm] of ``q`` from the polyline through ``points`` (n, 3)."""
    if len(points) == 1:
        return float(np.linalg.norm(points[0] - q))
    a, d = points[:-1], np.diff(points, axis=0)
    dd = np.einsum("ij,ij->i", d, d)
    u = np.clip(np.einsum("ij,ij->i", q - a, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    return float(np.linalg.norm(a + u[:, None] * d - q, axis=1).min())


def _corner_failures(program, sp, pts: np.ndarray, tol: np.ndarray, sagitta: float) -> list[str]:
    """Each motion block's end passed within its tolerance by the samples' polyline (its chords, up to ``sagitta``
    [mm] inside the curve the samples are on, allowed beside it), and on the block's last sample where the setpoints
    stop there."""
    blocks = program.blocks
    first = np.searchsorted(sp.block, np.arange(len(blocks)), side="left")
    last = np.searchsorted(sp.block, np.arange(len(blocks)), side="right")
    for i, b in enumerate(blocks):
        if b.segment is None or b.length == 0 or first[i] == last[i]:
            continue
        hi = int(np.searchsorted(sp.block, i + 1, side="right")) + 1
        lo = max(first[i] - 1, 0)
        d = _polyline_distance(pts[lo:hi], b.target)
        k = last[i] - 1
        # a block shorter than a sample may carry only the stop at its start
        at_rest = not sp.velocity[k].any() and np.linalg.norm(pts[k] - b.start) > EXACT
        if at_rest:
            d = float(np.linalg.norm(pts[k] - b.target))
        if d > (EXACT if at_rest else tol[i] + sagitta + ALLOWANCE):
            return [f"corner: block {i} (line {b.line}) end missed by {d:.3g} mm, tolerance {tol[i]:g}"
                    f"{' (at rest)' if at_rest else ''}"]
    return []


def _dwell_failures(program, sp) -> list[str]:
    out = []
    Ts = sp.sample_time
    for i, b in enumerate(program.blocks):
        if b.kind != "dwell":
            continue
        on = sp.block == i
        n = int(on.sum())
        want = math.ceil(b.dwell / Ts - 1e-9)
        if not (want <= n <= want + 1) or np.abs(sp.velocity[on]).max(initial=0.0) > 0:
            out.append(f"dwell: block {i} (line {b.line}) {b.dwell:g} s held {n} samples of {Ts:g} s")
            break
    return out


def _jump_failures(sp, limits) -> list[str]:
    """Position steps the analytic velocity explains: the trapezoid rule within an acceleration step."""
    Ts = sp.sample_time
    step = np.diff(sp.position, axis=0)
    rule = Ts * (sp.velocity[:-1] + sp.velocity[1:]) / 2
    bound = np.array([limits[a].acceleration for a in sp.axes]) * Ts**2 + 1e-9
    bad = np.abs(step - rule) > bound
    if bad.any():
        k, j = np.argwhere(bad)[0]
        return [f"jump: axis {sp.axes[j]} at sample {k}: step {step[k, j]:.4g}, velocity says {rule[k, j]:.4g}"]
    return []


def _axis_failures(program, sp, tol: np.ndarray) -> list[str]:
    """Each axis beyond X/Y/Z within its programmed values over the sample's block and the two blocks either side,
    widened by the largest tolerance among them (read as deg on A-C): a blend or a merged run follows the
    polyline of those values within 0.9 of it (``axis_blends.excess``, ``dense.fit_axes``), so a sample outside
    overshot or took another value (a unit, a G93 feed, a blend's end)."""
    cols = [(k, EXTRA_NAMES.index(a)) for k, a in enumerate(sp.axes) if a not in "xyz"]
    if not cols:
        return []
    zero = np.zeros(len(EXTRA_NAMES))
    ends = np.array([[zero if b.extra_start is None else b.extra_start, zero if b.extra_target is None
                      else b.extra_target] for b in program.blocks])
    lo, hi, wide = ends.min(axis=1), ends.max(axis=1), tol.copy()
    n = len(program.blocks)
    for shift in (1, 2):
        for src in (np.minimum(np.arange(n) + shift, n - 1), np.maximum(np.arange(n) - shift, 0)):
            lo, hi = np.minimum(lo, ends.min(axis=1)[src]), np.maximum(hi, ends.max(axis=1)[src])
            wide = np.maximum(wide, tol[src])
    blk = np.clip(sp.block, 0, None)
    for k, j in cols:
        v = sp.position[:, k]
        out = np.maximum(lo[blk, j] - v, v - hi[blk, j]) - wide[blk] - ALLOWANCE
        if np.any(out > 0):
            i = int(np.argmax(out))
            return [f"axis: {sp.axes[k]} at sample {i} (block {blk[i]}, line {program.blocks[blk[i]].line}) "
                    f"{v[i]:.6g}, {out[i] + wide[blk[i]] + ALLOWANCE:.3g} beyond its programmed values "
                    f"{lo[blk[i], j]:.6g} .. {hi[blk[i], j]:.6g}, tolerance {wide[blk[i]]:g}"]
    return []


def _programmed_axes(block) -> tuple[list[tuple[cKDTree, np.ndarray]], np.ndarray, np.ndarray]:
    """Points of a feed move's X/Y/Z path at most 0.5 um apart (2,000 at most) in two halves, each half's tree
    and the indices of its points (a full circle passes its start point again at its end, with other values of
    the axes: each half finds its own nearest point), the axes beyond X/Y/Z programmed at the points (in
    proportion to the path, RS274/NGC 3 Sec. 2.1.2.5) and each axis' rate per mm."""
    n = int(min(2000, max(50, block.length / 5e-4)))
    s = np.linspace(0.0, block.length, n)
    rate = (block.extra_target - block.extra_start) / block.length
    points = np.atleast_2d(block.segment.point_at(s))
    halves = [np.arange(0, n // 2 + 1), np.arange(n // 2, n)]
    return [(cKDTree(points[h]), h) for h in halves], block.extra_start + np.outer(s, rate), rate


def _axis_path_failures(program, sp, allowed: np.ndarray) -> list[str]:
    """Each axis beyond X/Y/Z within ``allowed`` (the sample's path tolerance, read as deg on A-C) of its value
    programmed at the point of the path nearest the sample (on the sample's move or the move either side), widened
    by the axis' rate per mm times the sample's distance from that point and the points' spacing: blends keep their
    axes within 0.9 P of that measure (``axis_blends.excess``), ramps and merged runs follow the programmed motion
    within 0.9 P along the path (``axis_blends.ramp_half_length``, ``dense.fit_axes``). Samples on moves with X/Y/Z
    still or under tool centre point control are left out."""
    cols = [(k, EXTRA_NAMES.index(a)) for k, a in enumerate(sp.axes) if a not in "xyz"]
    if not cols:
        return []
    blocks = program.blocks
    feed = [b.segment is not None and b.length > 0 and b.extra_start is not None and not b.tcp for b in blocks]
    pts, blk = xyz(sp), np.clip(sp.block, 0, None)
    lo = np.searchsorted(blk, np.arange(len(blocks)), side="left")
    hi = np.searchsorted(blk, np.arange(len(blocks)), side="right")
    best = np.full((len(sp), len(cols)), -np.inf)  # samples left out stay below any tolerance
    cache: dict[int, tuple] = {}
    moving = [i for i, b in enumerate(blocks) if b.segment is not None and b.length > 0]
    for n, i in enumerate(moving):
        if not feed[i] or hi[i] == lo[i]:
            continue
        rows = slice(lo[i], hi[i])
        best[rows] = np.inf
        for j in moving[max(n - 1, 0):n + 2]:  # the moves either side (a zero-length block between has no samples)
            if not feed[j]:
                continue
            if j not in cache:  # each move's trees once (setdefault would build them for every use)
                cache[j] = _programmed_axes(blocks[j])
            trees, values, rate = cache[j]
            spacing = blocks[j].length / (len(values) - 1)
            for tree, half in trees:
                dist, idx = tree.query(pts[rows])
                for c, (k, e) in enumerate(cols):
                    off = np.abs(sp.position[rows, k] - values[half[idx], e]) - abs(rate[e]) * (dist + spacing)
                    best[rows, c] = np.minimum(best[rows, c], off)
    out = best - allowed[:, None]
    if np.any(out > 0):
        r, c = np.unravel_index(int(np.argmax(out)), out.shape)
        return [f"axis_path: {sp.axes[cols[c][0]]} at sample {r} (block {blk[r]}, line {blocks[blk[r]].line}) "
                f"{best[r, c]:.3g} beyond its value at the nearest point of the path and the slack of its rate, "
                f"tolerance {allowed[r] - ALLOWANCE:g}"]
    return []


def check_setpoints(program, sp, limits: dict[str, AxisLimits], profile: str) -> list[str]:
    """The failures of ``sp`` (setpoints of ``program`` under ``limits`` and ``profile``), one line per kind
    (see the module docstring); empty when every invariant holds."""
    cols = (sp.position, sp.velocity, sp.acceleration)
    if not all(np.isfinite(c).all() for c in cols):
        return ["nonfinite: a NaN or infinity in the setpoints"]
    out = []
    try:
        check_limits(sp, program, limits, jerk=profile == "scurve", feed=True)
    except AssertionError as e:
        out.append(f"limits: {e}")
    out += _jump_failures(sp, limits)
    if np.any(np.diff(sp.block) < 0):
        out.append(f"block_order: block decreases at sample {int(np.argmax(np.diff(sp.block) < 0))}")
    b0, b1 = program.blocks[0], program.blocks[-1]
    if np.abs(sp.position[0] - _full(program, sp, b0.start, b0.extra_start)).max() > EXACT:
        out.append("start: first sample not at the program start")
    end = _full(program, sp, b1.target, b1.extra_target)
    if np.abs(sp.position[-1] - end).max() > EXACT:
        out.append(f"end: last sample {np.abs(sp.position[-1] - end).max():.3g} mm from the program end")
    tol = block_tolerances(program)
    joint = junction_tolerances(program)
    blk = np.clip(sp.block, 0, None)
    # a blend joins a block to the moving block before it (a zero-length block between them has no samples)
    moving = np.array([b.segment is not None and b.length > 0 for b in program.blocks])
    before = np.maximum.accumulate(np.where(moving, np.arange(len(moving)), 0))
    before = np.concatenate([[0], before[:-1]])
    allowed = np.maximum(joint[blk], np.where(blk > 0, joint[before[blk]], 0.0)) + ALLOWANCE
    path = program.path()
    if path.segments:
        d = path_distances(path, xyz(sp))
        if np.any(d > allowed):
            k = int(np.argmax(d - allowed))
            out.append(f"deviation: sample {k} (block {sp.block[k]}, line {program.blocks[blk[k]].line}) "
                       f"{d[k]:.3g} mm off the path, tolerance {allowed[k] - ALLOWANCE:g}")
    # a chord between samples v Ts apart on a curve of radius v^2 / a lies a Ts^2 / 8 inside it
    a_xyz = np.linalg.norm([limits[a].acceleration for a in sp.axes if a in "xyz"])
    out += _corner_failures(program, sp, xyz(sp), joint, a_xyz * sp.sample_time**2 / 8)
    out += _dwell_failures(program, sp)
    out += _axis_failures(program, sp, tol)
    out += _axis_path_failures(program, sp, allowed)
    return out


#: Words after which a line's absolute rotary word is not simply the angle it ends at (:func:`wrap_failures`).
_WRAP_UNCHECKED = re.compile(r"G9[12]|G5[23]|G28|G30|G10|G68|G43\.[45]|G234|#|\[|(?<![A-Z])O\d|M98|M99")
_ROTARY_WORD = re.compile(r"(?<![A-Z])([ABC])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


def wrap_failures(program, text: str, context: MachineContext) -> list[str]:
    """``wrap``: each line of ``text`` with an absolute word of an axis ``context`` wraps at 360 deg must end that
    axis at the word's angle modulo 360 deg (``sign``: its magnitude's), the turn from the line's first block's start
    to its last block's end being the rule's (:mod:`interpolators.rotary_wrap`): ``shortest`` at most half a turn
    (exactly half the positive way), ``sign`` in the word's sign's direction (less than a turn), ``difference`` the
    word minus the angle shown in [0, 360). Only for ISO programs with neither G91 nor G53, G28/G30, G92/G52/G10,
    G68, TCP, parameters or subprograms (a word there is not simply the angle it ends at), with no work offsets on
    the rotary axes."""
    if not context.wrapped_axes or "BEGIN PGM" in text.upper() or _WRAP_UNCHECKED.search(text.upper()):
        return []
    rule = context.wrap_direction or default_direction(context.dialect.name)
    lines: dict[int, list] = {}
    for b in program.blocks:
        if b.extra_start is not None and b.extra_target is not None:
            lines.setdefault(b.line, []).append(b)
    for line, blocks in lines.items():
        code = re.sub(r"\(.*?\)|;.*", "", blocks[-1].text.upper())
        for letter, word in _ROTARY_WORD.findall(code):
            if letter.lower() not in context.wrapped_axes:
                continue
            i, w = "ABC".index(letter), float(word)
            start, end = float(blocks[0].extra_start[i]), float(blocks[-1].extra_target[i])
            turn, angle = end - start, abs(w) if rule == "sign" else w
            shown = start % 360.0 if abs(math.remainder(start, 360.0)) > 1e-9 else 0.0
            off = abs(math.remainder(end - angle, 360.0)) > 1e-6
            wrong = {"shortest": not -180.0 - 1e-6 < turn <= 180.0 + 1e-6,
                     "sign": not -1e-6 <= turn * math.copysign(1.0, w) < 360.0 + 1e-6,
                     "difference": abs(turn - (w - shown)) > 1e-6}[rule]
            if off or wrong:
                return [f"wrap: line {line} {letter}{word} ({rule}) from {start:.6g} ends at {end:.6g} (turn "
                        f"{turn:.6g})"]
    return []


def on_machine(context: MachineContext, machine: MachineContext) -> MachineContext:
    """``context`` (a source's) with ``machine``'s rotary axes that wrap at 360 deg (those ``context`` has) and its
    rule of an absolute move on them."""
    wrapped = tuple(a for a in machine.wrapped_axes if a in context.extra_axes)
    return dataclasses.replace(context, wrapped_axes=wrapped, wrap_direction=machine.wrap_direction if wrapped
                               else None)


def wrapping(rule: str) -> MachineContext:
    """A machine context whose rotary axes A, B, C wrap at 360 deg under ``rule`` (for :func:`on_machine`)."""
    return MachineContext(extra_axes=ROTARY_AXES, wrapped_axes=ROTARY_AXES, wrap_direction=rule)


def run_case(source: str, seed: int, sample_time: float | None = None, *,
             machine: MachineContext | None = None) -> list[tuple[str, str, float, list[str]]]:
    """Both profiles of the program of ``source`` and ``seed``: (outcome, profile, sample time, failures) each;
    outcome ``ok``, ``fail``, ``refused`` (the reader's GCodeError), ``too_long`` or ``crash``. ``sample_time``
    [s]: instead of the seed's own (the program and the limits stay the seed's); ``machine``: its wrapping rotary
    axes and their rule on the source's context (:func:`on_machine`), the ``wrap`` check added."""
    text, context = program_of(source, seed)
    if machine is not None:
        context = on_machine(context, machine)
    rng = random.Random(f"limits:{source}:{seed}")
    Ts = 10 ** rng.uniform(math.log10(2.5e-4), math.log10(4e-3))
    if source == "rotary_cam" and seed >= ROTARY_EDGE_TS_SEED:
        Ts = random.Random(f"ts:{seed}").choice((Ts, Ts, 2.5e-4, 4e-3))  # the range's ends, as often as the rest
    if sample_time is not None:
        Ts = sample_time
    try:
        program = parse_program(text, source=f"{source}-{seed}", context=context)
    except GCodeError as e:
        return [("refused", "-", Ts, [str(e).splitlines()[0]])]
    if not any(b.segment is not None for b in program.blocks):
        return [("refused", "-", Ts, ["no motion"])]
    limits = random_limits(rng, program.axes, spread=400.0 if source == "rotary_cam" else 40.0)
    out = []
    for profile in ("trapezoid", "scurve"):
        try:
            sp = interpolate(program, limits=limits, sample_time=Ts, profile=profile, max_samples=MAX_SAMPLES)
        except ProgramTooLongError:
            out.append(("too_long", profile, Ts, []))
            continue
        except Exception as e:  # noqa: BLE001 - a fuzzer reports every failure
            out.append(("crash", profile, Ts, [f"crash: {type(e).__name__}: {e}"]))
            continue
        fails = check_setpoints(program, sp, limits, profile) + wrap_failures(program, text, context)
        out.append(("fail" if fails else "ok", profile, Ts, fails))
    return out


def _machine_context(path: Path) -> MachineContext:
    """The program context of the machine file ``path``; exit status 2 naming the file when it is none."""
    from vcnc.engine.machine import load_machine
    from vcnc.errors import VcncError
    try:
        return load_machine(path).context
    except (OSError, VcncError) as e:
        print(f"error: {path}: {e}", file=sys.stderr)
        raise SystemExit(2) from e


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=100, help="programs per source")
    ap.add_argument("--seed", type=int, default=0, help="first seed")
    ap.add_argument("--sources", default=",".join(SOURCES), help="comma-separated: " + ", ".join(SOURCES))
    ap.add_argument("--list", action="store_true", help="name every failing case")
    ap.add_argument("--sample-time", type=float, help="sample time [s] of every case (default: each seed's own)")
    wrap = ap.add_mutually_exclusive_group()
    wrap.add_argument("--wrap", choices=WRAP_DIRECTIONS,
                      help="rotary axes A, B, C wrap at 360 deg, an absolute move turning them by this rule")
    wrap.add_argument("--machine", type=Path, metavar="FILE",
                      help="a machine TOML whose [axes.a] wrap = true axes and [program] wrap_direction apply")
    args = ap.parse_args(argv)
    machine = wrapping(args.wrap) if args.wrap else _machine_context(args.machine) if args.machine else None
    table: dict[str, collections.Counter] = {}
    for source in args.sources.split(","):
        counts = table.setdefault(source, collections.Counter())
        for seed in range(args.seed, args.seed + args.count):
            for outcome, profile, Ts, fails in run_case(source, seed, args.sample_time, machine=machine):
                counts[outcome] += 1
                for f in fails if outcome in ("fail", "crash") else ():
                    counts[f.split(":")[0]] += 1
                    if args.list:
                        print(f"{source} {seed} {profile} Ts={Ts:.3g}: {f}", flush=True)
    kinds = sorted({k for c in table.values() for k in c})
    print("source     " + " ".join(f"{k:>11}" for k in kinds))
    for source, c in table.items():
        print(f"{source:<10} " + " ".join(f"{c[k]:>11}" for k in kinds))
    return 0


if __name__ == "__main__":
    sys.exit(main())
