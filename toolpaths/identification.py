"""Identification test programs: random moves (thesis Table 3.2) and the slow/fast pair (Tables
4.3 and 4.4)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from toolpaths.writer import ProgramWriter
from vcnc.core.errors import InputError

__all__ = ["random_moves", "heidenhain_identification", "IDENTIFICATION_KINDS"]

#: Kinds of identification programs (``vcnc toolpath identification --kind``).
IDENTIFICATION_KINDS: tuple[str, ...] = ("random", "slow", "fast")


def _axes(axes: Sequence[str]) -> list[str]:
    ax = [str(a).lower() for a in axes]
    if not ax or any(a not in ("x", "y", "z") for a in ax) or len(set(ax)) != len(ax):
        raise InputError(f"axes must be distinct names among x, y, z, got {axes!r}")
    return ax


def _check(n: int, span: float, feed: float) -> None:
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise InputError(f"n (number of moves) must be an integer >= 1, got {n!r}")
    for name, v, unit in (("span", span, "mm"), ("feed", feed, "mm/min")):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InputError(f"{name} must be a finite value > 0 {unit}, got {v!r}")


def random_moves(
    n: int = 200,
    span: float = 10.0,
    feed: float = 12000.0,
    *,
    seed: int = 0,
    axes: Sequence[str] = ("x",),
    dialect: str = "iso",
) -> str:
    """Random linear moves within +/-``span``, in the style of the thesis' Table 3.2.

    ISO output reproduces the table's layout: ``N0000 G00 X0.000 F12000`` then
    ``N0010 G01 X 0.258`` (a space stands for the plus sign, three decimals, N step 10), and a
    final ``M30``. A first line ``G21 G61`` states mm and exact stop, which the table leaves to the
    control: every move starts and ends at rest, whatever the control's default path mode.

    Parameters
    ----------
    n : int
        Number of random moves (200 in Table 3.2).
    span : float
        Targets are uniform in ``[-span, +span]`` [mm] (10 mm in Table 3.2).
    feed : float
        [mm/min] (12000 = 200 mm/s in Table 3.2).
    seed : int
        Seed of ``numpy.random.default_rng``; the same arguments give the same text.
    axes : sequence of str
        Axes moved; each block moves all of them to independent random targets.
    dialect : {"iso", "heidenhain"}
    """
    _check(n, span, feed)
    ax = _axes(axes)
    rng = np.random.default_rng(seed)
    targets = np.round(rng.uniform(-span, span, size=(n, len(ax))), 3)
    f = f"{feed:.3f}".rstrip("0").rstrip(".")
    if dialect != "iso":
        w = ProgramWriter(dialect, name="RANDOM", comment=f"{n} random moves within +/-{span:g} mm", decimals=3)
        w.rapid({a: 0.0 for a in ax})
        for row in targets:
            w.line(dict(zip(ax, row.tolist())), feed=float(feed))
        return w.end()
    width = max(4, len(str(10 * (n + 1))))
    lines = ["G21 G61", f"N{0:0{width}d} G00 " + " ".join(f"{a.upper()}0.000" for a in ax) + f" F{f}"]
    for i, row in enumerate(targets, start=1):
        words = " ".join(f"{a.upper()}{' ' if v >= 0 else '-'}{abs(v):.3f}" for a, v in zip(ax, row))
        lines.append(f"N{10 * i:0{width}d} G01 {words}")
    lines.append(f"N{10 * (n + 1):0{width}d} M30")
    return "\n".join(lines) + "\n"


def heidenhain_identification(
    kind: str = "slow",
    *,
    n: int | None = None,
    span: float | None = None,
    feed: float = 15000.0,
    seed: int = 0,
    axis: str = "x",
) -> str:
    """The slow or fast identification program of the thesis' Tables 4.3 / 4.4 (Heidenhain).

    Both start like the tables (``BEGIN PGM RAPIDIDENT MM``, the comment, ``BLK FORM``,
    ``TOOL CALL 0 Z``, ``L Z+200.000 F MAX``, ``L X+0.000 Y+0.000 R0 F MAX M3``), then move one
    axis to random positions at ``F 15000.000`` and return to zero.

    Parameters
    ----------
    kind : {"slow", "fast"}
        ``"slow"``: moves up to 30 um (Table 4.3: ``L X-0.000``, ``L X+0.000``, then targets in
        +/-0.030 mm); ``"fast"``: moves up to 10 mm (Table 4.4: ``L Z+0.000 F MAX``, then
        ``L X-<span>``, ``L X+<span>`` and targets in +/-``span``).
    n : int, optional
        Number of random targets (default 197 slow, 97 fast: the tables' lengths).
    span : float, optional
        Largest |target| [mm] (default 0.030 slow, 9.375 fast as in Table 4.4).
    feed : float
        [mm/min] (15000 in the tables).
    seed : int
        Seed of ``numpy.random.default_rng``.
    axis : str
        Axis moved (the tables show x; the y test is identical).
    """
    if kind not in ("slow", "fast"):
        raise InputError(f"unknown identification kind {kind!r}", expected="slow or fast")
    n = (197 if kind == "slow" else 97) if n is None else n
    span = (0.030 if kind == "slow" else 9.375) if span is None else span
    _check(n, span, feed)
    a = _axes([axis])[0].upper()
    rng = np.random.default_rng(seed)
    targets = np.round(rng.uniform(-span, span, size=n), 3)
    lines = [
        "0 BEGIN PGM RAPIDIDENT MM",
        ";Rapid Identification on TNC 430 5 axis machine",
        "1 BLK FORM 0.1 Z X-50.000 Y-50.000 Z-50.000",
        "2 BLK FORM 0.2 X+50.000 Y+50.000 Z+50.000",
        "3 TOOL CALL 0 Z",
        "4 L Z+200.000 F MAX",
        "5 L X+0.000 Y+0.000 R0 F MAX M3",
    ]
    f = f"{feed:.3f}"
    if kind == "slow":
        lines += [f"7 L {a}-0.000 F {f}", f"8 L {a}+0.000"]
    else:
        lines += ["6 L Z+0.000 F MAX", f"7 L {a}-{span:.3f} F {f}", f"8 L {a}+{span:.3f}"]
    k = 9
    for v in targets:
        lines.append(f"{k} L {a}{v:+.3f}")
        k += 1
    lines += [f"{k} L {a}+0.000", f"{k + 1} M30", f"{k + 2} END PGM RAPIDIDENT MM"]
    return "\n".join(lines) + "\n"
